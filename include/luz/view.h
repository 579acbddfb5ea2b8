/*
 * luz/view.h: the colours of the teaching views, and a legend for each.
 *
 * luz_render_options.view (the programs' `--view NAME`) makes the pipeline
 * write a picture of one of its stages into the colour buffer
 * instead of the shaded image: the same triangles, rasterised by the same
 * code, only the last step (what colour a pixel gets) differs. The
 * pictures are drawn by src/renderer/view.c; this header gives their
 * palettes, so that a legend, a test or a caption can say what each colour
 * means.
 *
 *   color      the shaded image
 *   depth      the z-buffer: window depth turned back into eye distance and
 *              shown on a log scale, white at the near plane, black at the
 *              far one (luz_view_depth_brightness)
 *   normals    the re-normalised world normal N as (N + 1) / 2
 *   uv         (fract(u), fract(v), 0): red grows along u, green along v
 *   mip        the mip level the trilinear sampler read, one colour per
 *              level, blended by fract(lambda) between the two it mixes
 *   overdraw   how many fragments were depth-tested at each pixel
 *   bands      each band of rows tinted by the thread that drew it, over
 *              the dimmed image
 *   triangles  each triangle in its own flat colour, darker where a
 *              neighbouring pixel lies outside it (its edges), so that
 *              every pixel, edges too, shows which triangle owns it
 */
#ifndef LUZ_VIEW_H
#define LUZ_VIEW_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/api.h"
#include "luz/vecmath.h"

/* What the pipeline writes into the colour buffer: the shaded image, or a
 * picture of one of its stages (src/renderer/view.c draws them). Every view
 * is drawn by the same pipeline, from the same triangles. */
typedef enum luz_view {
    LUZ_VIEW_COLOR,       /* the shaded image (the default) */
    LUZ_VIEW_DEPTH,       /* the z-buffer, as eye distance on a log scale */
    LUZ_VIEW_NORMALS,     /* world normal * 0.5 + 0.5 */
    LUZ_VIEW_UV,          /* (fract(u), fract(v), 0) */
    LUZ_VIEW_MIP,         /* the mip level the sampler read, one colour each */
    LUZ_VIEW_OVERDRAW,    /* depth tests per pixel, as a heat map */
    LUZ_VIEW_BANDS,       /* each band tinted by the thread that drew it */
    LUZ_VIEW_TRIANGLES,   /* each triangle in its own colour, its edges darker */
    LUZ_VIEW_COUNT
} luz_view;

LUZ_API const char *luz_view_name(luz_view view);          /* "color", "depth", ... */

/* The view called name ("depth", ...); false if there is none. */
LUZ_API bool luz_view_from_name(const char *name, luz_view *view);

/* One line that says how to read the view's colours, every colour named. */
LUZ_API const char *luz_view_legend(luz_view view);

/* Overdraw: the colour of a pixel that had `count` depth tests; 0 black,
 * then dark blue, blue, cyan, green, yellow, orange, red, and white for 8
 * or more. */
LUZ_API luz_vec3 luz_view_overdraw_colour(uint32_t count);

/* Mip: the colour of level `level` (0 red, 1 orange, 2 yellow, 3 green,
 * 4 cyan, 5 blue, 6 violet, 7 magenta, 8 white, grey beyond); an
 * untextured surface is LUZ_VIEW_MIP_UNTEXTURED. */
LUZ_API luz_vec3 luz_view_mip_colour(int level);
#define LUZ_VIEW_MIP_UNTEXTURED ((luz_vec3){0.35f, 0.35f, 0.35f})

/* Bands: the tint of worker thread `worker` (0 is the calling thread). A
 * pixel of the bands view is (1 - LUZ_VIEW_BANDS_TINT) * its colour-view
 * value + LUZ_VIEW_BANDS_TINT * the tint of its band's thread. */
LUZ_API luz_vec3 luz_view_thread_colour(int worker);
#define LUZ_VIEW_BANDS_TINT 0.55f

/* Triangles: the flat colour of triangle `id` (ids count from 1 in
 * submission order); consecutive ids get hues far apart. A pixel of the
 * triangle one of whose four neighbours in the image lies outside it (by
 * the rasteriser's coverage test) is drawn in that colour times
 * LUZ_VIEW_TRIANGLE_EDGE_SHADE: its edges, in its own hue. */
LUZ_API luz_vec3 luz_view_triangle_colour(uint32_t id);
#define LUZ_VIEW_TRIANGLE_EDGE_SHADE 0.55f

/* Depth: the brightness in [0, 1] shown for window depth `depth` under
 * `projection` (a perspective matrix, as luz_mat4_perspective builds):
 * the eye distance d = B / (z_ndc + A), z_ndc = 2 depth - 1, A and B the
 * matrix's z row, then 1 - log(d / near) / log(far / near). */
LUZ_API float luz_view_depth_brightness(float depth, const luz_mat4 *projection);

#endif
