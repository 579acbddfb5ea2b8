/*
 * geometry_support.h: what the tests of setup in lanes and of the planes
 * (test_setup_eight.c, test_planes.c) share to make their random
 * triangles. Include after <cmocka.h> and test_support.h.
 *
 * test_w_from_z: a projection * view under which a vertex's world z is
 * its clip w. test_vertex_at: an object-space vertex that lands about
 * where a test wants it in fixed point. test_turn: the turned model and
 * camera under which a term summed in another order, or taken from the
 * wrong row, shows.
 */
#ifndef LUZ_GEOMETRY_SUPPORT_H
#define LUZ_GEOMETRY_SUPPORT_H

#include <stdint.h>

#include "renderer/pipeline.h"

/* A projection * view that takes world (x, y, z) to clip (x, y, z - 0.1,
 * z) exactly (ones and zeros: each sum is x, y or z): a vertex's world z
 * is its clip w, so a test places it on the screen, and its depth (1 -
 * 0.1 / w + 1) / 2 varies with w. */
static inline luz_mat4 test_w_from_z(void)
{
    luz_mat4 m = {{0}};
    m.m[0] = 1.0f;            /* column 0: x -> clip x */
    m.m[5] = 1.0f;            /* column 1: y -> clip y */
    m.m[10] = 1.0f;           /* column 2: z -> clip z and clip w */
    m.m[11] = 1.0f;
    m.m[14] = -0.1f;          /* column 3: the translation of clip z */
    return m;
}

/* A vertex at clip w (the window position divides by it), placed so that,
 * under test_w_from_z and the identity model, it projects to within a
 * sub-pixel unit or so of (fixed_x, fixed_y) in fixed point on a width x
 * height window (float clip coordinates round it), with a random normal
 * and uv. */
static inline luz_vertex test_vertex_at(int32_t fixed_x, int32_t fixed_y, float w, int width,
                                        int height, uint32_t *random)
{
    const double x_ndc = 2.0 * fixed_x / (LUZ_SUBPIXEL_ONE * (double)width) - 1.0;
    const double y_ndc = 1.0 - 2.0 * fixed_y / (LUZ_SUBPIXEL_ONE * (double)height);
    return (luz_vertex){
        {(float)(x_ndc * w), (float)(y_ndc * w), w},
        {test_uniform(random, -1.0f, 1.0f), test_uniform(random, -1.0f, 1.0f),
         test_uniform(random, -1.0f, 1.0f)},
        {test_uniform(random, -4.0f, 4.0f), test_uniform(random, -4.0f, 4.0f)}};
}

/* A model matrix that turns and moves (and a normal matrix that is not
 * the identity) and a camera turned a little (a projection * view with no
 * zero to hide a term). */
static inline void test_turn(luz_draw_transform *transform)
{
    transform->model = luz_mat4_rotate(
        luz_mat4_translate(luz_mat4_identity(), (luz_vec3){0.3f, -0.2f, 0.05f}), 0.3f,
        (luz_vec3){0.1f, 0.2f, 0.97f});
    transform->normal_matrix = luz_mat3_normal_matrix(transform->model);
    transform->view_projection =
        luz_mat4_multiply(test_w_from_z(), luz_mat4_rotate(luz_mat4_identity(), 0.05f,
                                                           (luz_vec3){0.3f, 0.5f, 0.81f}));
}

#endif
