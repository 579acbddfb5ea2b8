/*
 * luz/bug.h: classic mistakes, injected on purpose, one at a time.
 *
 * A student of the lighting practical learns as much from a wrong image as
 * from a right one. luz_render_options.bug (the programs' `--bug NAME`)
 * draws the frame with one classic error put back into the shading or the
 * pipeline, so that its effect can be seen in the image, in the teaching
 * views and in the pixel probe, whose numbers follow the bug. Zero,
 * LUZ_BUG_NONE, is SCENE.md's contract: a frame without a bug is drawn by
 * exactly the code it was drawn by before (with a bug on, the renderer
 * takes its plain reference paths, the SIMD ones stay bug-free).
 *
 * The first three are the errata of the report luz comes from (SCENE.md,
 * "The fragment equations", the three places where its printed code
 * differs from its intent). Each bug's description says exactly what it
 * changes, in SCENE.md's names:
 *
 *   diffuse-reversed        L = normalize(P - E) in the diffuse term, the
 *                           report's printed vector: max(dot(N, L), 0)
 *                           becomes max(-dot(N, L_right), 0)
 *   directional-unclamped   directional = dot(N, normalize(-d)) Dl.rgb Dl.a,
 *                           no max(..., 0): faces away from the sun subtract
 *   spot-reach-twice        f_win = max(1 - (dn / reach)^4, 0)^2, with
 *                           dn = length(E - P) / reach already
 *   normal-not-normalised   N is used as interpolated, not re-normalised
 *   normal-matrix-is-model  the normal goes through the model matrix as a
 *                           point does, (M (N, 1)).xyz: the translation is
 *                           added to it
 *   specular-half-vector    specular = S.a pow(max(dot(N, H), 0), s) S.rgb,
 *                           H = normalize(L + V) (Blinn's vector in Phong's
 *                           formula, same exponent)
 *   uv-affine               the varyings (uv among them) interpolated
 *                           linearly in screen space, not divided by w
 *   lod-off-by-one          lambda = log2(rho) + 1: the texture read one
 *                           mip level too blurry
 *   fill-rule-bottom-right  a sample on an edge belongs to the triangle if
 *                           the edge is a bottom or a right edge (not top
 *                           or left)
 *   no-depth-test           every fragment passes (GL_DEPTH_TEST off): the
 *                           last triangle drawn over a pixel wins, and the
 *                           depth buffer is not written
 *   no-backface-culling     back faces are rasterised too
 */
#ifndef LUZ_BUG_H
#define LUZ_BUG_H

#include <stdbool.h>

#include "luz/api.h"

typedef enum luz_bug {
    LUZ_BUG_NONE,                     /* SCENE.md: no mistake */
    LUZ_BUG_DIFFUSE_REVERSED,
    LUZ_BUG_DIRECTIONAL_UNCLAMPED,
    LUZ_BUG_SPOT_REACH_TWICE,
    LUZ_BUG_NORMAL_NOT_NORMALISED,
    LUZ_BUG_NORMAL_MATRIX_IS_MODEL,
    LUZ_BUG_SPECULAR_HALF_VECTOR,
    LUZ_BUG_UV_AFFINE,
    LUZ_BUG_LOD_OFF_BY_ONE,
    LUZ_BUG_FILL_RULE_BOTTOM_RIGHT,
    LUZ_BUG_NO_DEPTH_TEST,
    LUZ_BUG_NO_BACKFACE_CULLING,
    LUZ_BUG_COUNT
} luz_bug;

/* "none", "diffuse-reversed", ...; NULL for a value that is not a bug. */
LUZ_API const char *luz_bug_name(luz_bug bug);
/* One line: what the mistake is, in SCENE.md's names (the table above). */
LUZ_API const char *luz_bug_description(luz_bug bug);
/* The bug called name ("none" included); false if there is none. */
LUZ_API bool luz_bug_from_name(const char *name, luz_bug *bug);

#endif
