/*
 * bug.c: the names and descriptions of luz/bug.h's classic mistakes.
 *
 * In:  a luz_bug, or a name.
 * Out: its name and one line saying what it changes; or the bug of a name.
 *
 * Where each bug lives: the shading ones in shade_steps.c, the vertex
 * stage's in vertex.c, the fill rule and culling in geometry.c's setup of
 * one triangle, the depth test in raster.c, the interpolation in
 * luz_uniforms_of (frame.c), the level of detail in fragment.c.
 */
#include <string.h>

#include "luz/bug.h"

static const struct {
    const char *name;
    const char *description;
} bugs[LUZ_BUG_COUNT] = {
    [LUZ_BUG_NONE] = {"none", "no mistake: SCENE.md's equations and pipeline"},
    [LUZ_BUG_DIFFUSE_REVERSED] =
        {"diffuse-reversed", "the diffuse light vector points from the headlight to the "
                             "fragment, L = normalize(P - E) (the report's printed code)"},
    [LUZ_BUG_DIRECTIONAL_UNCLAMPED] =
        {"directional-unclamped", "the directional term has no max(..., 0): faces turned "
                                  "away from the sun subtract light (the report's code)"},
    [LUZ_BUG_SPOT_REACH_TWICE] =
        {"spot-reach-twice", "the spot distance is divided by the reach twice: f_win = "
                             "max(1 - (dn / reach)^4, 0)^2 (the report's code)"},
    [LUZ_BUG_NORMAL_NOT_NORMALISED] =
        {"normal-not-normalised", "the interpolated normal is used as it is, not "
                                  "re-normalised per fragment"},
    [LUZ_BUG_NORMAL_MATRIX_IS_MODEL] =
        {"normal-matrix-is-model", "the normal goes through the model matrix as a point "
                                   "does, (M (N, 1)).xyz, translation included"},
    [LUZ_BUG_SPECULAR_HALF_VECTOR] =
        {"specular-half-vector", "the specular term uses dot(N, H), H = normalize(L + V), "
                                 "in place of dot(V, R), with the same exponent"},
    [LUZ_BUG_UV_AFFINE] =
        {"uv-affine", "texture coordinates (and the other varyings) interpolated linearly "
                      "in screen space, not perspective-correct"},
    [LUZ_BUG_LOD_OFF_BY_ONE] =
        {"lod-off-by-one", "the level of detail is log2(rho) + 1: textures read one mip "
                           "level too blurry"},
    [LUZ_BUG_FILL_RULE_BOTTOM_RIGHT] =
        {"fill-rule-bottom-right", "a sample exactly on an edge belongs to the triangle "
                                   "if the edge is a bottom or right edge, not top or left"},
    [LUZ_BUG_NO_DEPTH_TEST] =
        {"no-depth-test", "no depth test: every fragment passes, the last triangle drawn "
                          "over a pixel wins, the depth buffer is not written"},
    [LUZ_BUG_NO_BACKFACE_CULLING] =
        {"no-backface-culling", "back faces are not culled: they are rasterised and "
                                "depth-tested like front faces"},
};

const char *luz_bug_name(luz_bug bug)
{
    return (unsigned)bug < LUZ_BUG_COUNT ? bugs[bug].name : NULL;
}

const char *luz_bug_description(luz_bug bug)
{
    return (unsigned)bug < LUZ_BUG_COUNT ? bugs[bug].description : NULL;
}

bool luz_bug_from_name(const char *name, luz_bug *bug)
{
    for (int i = 0; i < LUZ_BUG_COUNT; i++) {
        if (strcmp(name, bugs[i].name) == 0) {
            *bug = (luz_bug)i;
            return true;
        }
    }
    return false;
}
