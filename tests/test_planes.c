/*
 * test_planes.c: the shading planes (src/renderer/planes.c) solved from
 * (draw, primitive) alone, against the records setup writes: setup one
 * triangle at a time (luz_setup_projected, luz_setup_projected_bug) and
 * setup in lanes, every variant this machine runs (setup_eight.c,
 * setup_lanes.c, whose planes are their own code, not planes.c's). The
 * promise a slim raster record rests on: the 1/w and varying planes
 * solved again at shading time are the record's, bit for bit, for every
 * triangle setup keeps that no clip plane cut; one that was cut is named
 * (LUZ_PLANES_CLIPPED), one setup drops before its planes too
 * (LUZ_PLANES_NONE). And, by hand, planes whose values and gradients are
 * known exactly.
 *
 * Random triangles (as test_setup_eight.c's): most a pixel or two across,
 * some large, some off the viewport, some back faces, 1/w from 0.05 to
 * 10, random normals and uv; both interpolations; the identity model and
 * a projection of ones and zeros, then a turned model and camera; and
 * luz/bug.h's two bugs that change what setup is given (no-backface-
 * culling trades a back face's corners, normal-matrix-is-model changes the
 * normals).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "test_support.h"
#include "geometry_support.h"

#include "renderer/cpu.h"
#include "renderer/pipeline.h"

#define WIDTH 40
#define HEIGHT 24

/* A draw's mesh, one triangle per three vertices, and its transforms. */
typedef struct mesh {
    uint32_t triangle_count;
    luz_vertex *vertices;
    uint32_t *indices;
    luz_draw_transform transform;
} mesh;

/* triangle_count random triangles: 60% about a pixel, 30% a few, 8%
 * dozens of pixels, 2% with a corner behind the eye or far outside the
 * guard band (the clipper's). */
static mesh random_mesh(uint32_t triangle_count, uint32_t seed)
{
    mesh m = {triangle_count, calloc(3 * (size_t)triangle_count, sizeof(luz_vertex)),
              calloc(3 * (size_t)triangle_count, sizeof(uint32_t)), {0}};
    assert_true(m.vertices && m.indices);
    m.transform = (luz_draw_transform){m.vertices, luz_mat4_identity(),
                                       luz_mat3_normal_matrix(luz_mat4_identity()),
                                       test_w_from_z()};
    uint32_t random = seed;
    for (uint32_t t = 0; t < triangle_count; t++) {
        const uint32_t kind = test_random(&random) % 100;
        const int32_t base_x = (int32_t)(test_random(&random) % (256 * (WIDTH + 8))) - 256 * 4;
        const int32_t base_y = (int32_t)(test_random(&random) % (256 * (HEIGHT + 8))) - 256 * 4;
        const int32_t reach = kind < 60 ? 256 : kind < 90 ? 640 : 256 * 12;
        for (int k = 0; k < 3; k++) {
            const uint32_t i = 3 * t + (uint32_t)k;
            m.indices[i] = i;
            const uint32_t span = (uint32_t)(2 * reach + 1);
            /* (Each argument its own statement: their order is the
             * generator's.) */
            const int32_t x = base_x + (int32_t)(test_random(&random) % span) - reach;
            const int32_t y = base_y + (int32_t)(test_random(&random) % span) - reach;
            const float w = 1.0f / test_uniform(&random, 0.05f, 10.0f);
            m.vertices[i] = test_vertex_at(x, y, w, WIDTH, HEIGHT, &random);
        }
        if (kind == 98) m.vertices[3 * t + 1].position.z = -0.5f;            /* behind */
        if (kind == 99) m.vertices[3 * t + 2].position.x = 100.0f * m.vertices[3 * t].position.z;
    }
    return m;
}

static void mesh_destroy(mesh *m)
{
    free(m->vertices);
    free(m->indices);
}

/* Whether the record's 1/w and varying planes are planes' bytes. */
static bool same_planes(const luz_triangle *record, const luz_shading_planes *planes)
{
    return memcmp(&record->inverse_w, &planes->inverse_w, sizeof planes->inverse_w) == 0 &&
           memcmp(record->varyings, planes->varyings, sizeof planes->varyings) == 0;
}

typedef struct tally {
    int solved, clipped, none;
} tally;

/* Every triangle of m set up one at a time, as geometry.c does with bug
 * in (the vertex stage, luz_setup_project_vertex, then
 * luz_setup_projected_bug or, without a bug, luz_setup_projected), and
 * solved by luz_planes_of_primitive: a record's planes are the solved
 * ones, a triangle with a corner outside a clip plane is CLIPPED, and one
 * setup drops at its determinant is NONE. */
static tally check_one_at_a_time(const mesh *m, luz_interpolation interpolation, luz_bug bug)
{
    tally count = {0, 0, 0};
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        luz_clip_vertex clip[3];
        luz_window_vertex window[3];
        unsigned outcodes = 0;
        for (int k = 0; k < 3; k++) {
            clip[k] = luz_vertex_stage_one_bug(&m->transform, bug, m->indices[3 * t + k]);
            outcodes |= clip[k].outcode;
            window[k] = luz_setup_project_vertex(&clip[k], WIDTH, HEIGHT);
        }
        luz_shading_planes planes;
        memset(&planes, 0xA5, sizeof planes);
        const luz_planes_result solved = luz_planes_of_primitive(
            &m->transform, m->indices, t, WIDTH, HEIGHT, interpolation, bug, &planes);
        if (outcodes != 0) {
            if (solved != LUZ_PLANES_CLIPPED)
                fail_msg("triangle %u crosses a clip plane, planes.c says %d", t, (int)solved);
            count.clipped++;
            continue;
        }
        luz_triangle record;
        memset(&record, 0x5A, sizeof record);
        const luz_setup_result result =
            bug == LUZ_BUG_NONE
                ? luz_setup_projected(&clip[0], &clip[1], &clip[2], &window[0], &window[1],
                                      &window[2], WIDTH, HEIGHT, 3, interpolation, false,
                                      &record)
                : luz_setup_projected_bug(&clip[0], &clip[1], &clip[2], &window[0], &window[1],
                                          &window[2], WIDTH, HEIGHT, 3, interpolation, 1, bug,
                                          &record);
        if (result == LUZ_SETUP_VISIBLE) {
            if (solved != LUZ_PLANES_SOLVED)
                fail_msg("triangle %u: a record, but planes.c says %d", t, (int)solved);
            if (!same_planes(&record, &planes))
                fail_msg("triangle %u: its planes differ from its record's", t);
            count.solved++;
        } else if (solved == LUZ_PLANES_NONE) {
            count.none++;
        }
    }
    return count;
}

/* The same against setup in lanes of every variant this build and CPU
 * have, for one sample a pixel and for four (whose boxes and kept
 * triangles differ, not their planes): eight triangles at a time whose corners are all inside the clip
 * volume and projected (as screening lets them through), each record a
 * variant writes VISIBLE has the planes planes.c solves. Returns the
 * records compared. */
static int check_lanes(const mesh *m, luz_interpolation interpolation)
{
    luz_fixed_vertex *fixed = calloc(3 * (size_t)m->triangle_count, sizeof *fixed);
    uint32_t *chosen = calloc(m->triangle_count, sizeof *chosen);
    assert_true(fixed && chosen);
    uint32_t chosen_count = 0;
    for (uint32_t t = 0; t < m->triangle_count; t++) {
        bool inside = true;
        for (uint32_t k = 0; k < 3; k++) {
            const luz_clip_vertex clip = luz_vertex_stage_one(&m->transform, 3 * t + k);
            const luz_window_vertex window = luz_setup_project_vertex(&clip, WIDTH, HEIGHT);
            fixed[3 * t + k] = (luz_fixed_vertex){window.fixed_x, window.fixed_y};
            inside = inside && clip.outcode == 0 && window.fixed_x != LUZ_WINDOW_INVALID;
        }
        if (inside) chosen[chosen_count++] = t;
    }
    int compared = 0;
    for (int variant = 0; variant < 2 * LUZ_ISA_COUNT; variant++) {
        const int isa = variant / 2, samples = variant % 2 ? 4 : 1;
        if (!luz_isa_available((luz_isa)isa)) continue;
        const luz_kernels kernels = luz_kernels_of((luz_isa)isa);
        luz_setup_eight_function *setup_eight =
            samples == 4 ? kernels.setup_eight_four : kernels.setup_eight;
        if (setup_eight == NULL) continue;
        int variant_compared = 0;
        for (uint32_t group = 0; group + 8 <= chosen_count; group += 8) {
            luz_triangle out[8];
            luz_setup_result result[8];
            memset(out, 0xA5, sizeof out);
            assert_false(setup_eight(m->indices, &chosen[group], &m->transform, fixed, WIDTH,
                                     HEIGHT, 3, interpolation, out, result));
            for (int lane = 0; lane < 8; lane++) {
                if (result[lane] != LUZ_SETUP_VISIBLE) continue;
                luz_shading_planes planes;
                assert_int_equal(luz_planes_of_primitive(&m->transform, m->indices,
                                                         chosen[group + lane], WIDTH, HEIGHT,
                                                         interpolation, LUZ_BUG_NONE, &planes),
                                 LUZ_PLANES_SOLVED);
                if (!same_planes(&out[lane], &planes))
                    fail_msg("%s, %d samples: triangle %u: its planes differ from its record's",
                             luz_isa_name((luz_isa)isa), samples, chosen[group + lane]);
                variant_compared++;
            }
        }
        print_message("%s, %d samples: %d records of setup in lanes\n",
                      luz_isa_name((luz_isa)isa), samples, variant_compared);
        assert_true(variant_compared > 1000);
        compared += variant_compared;
    }
    free(fixed);
    free(chosen);
    return compared;
}

static void test_planes_of_primitive_are_setups(void **state)
{
    (void)state;
    mesh m = random_mesh(12000, 2929);
    for (int turned = 0; turned < 2; turned++) {
        if (turned) test_turn(&m.transform);
        for (int mode = 0; mode < 2; mode++) {
            const luz_interpolation interpolation =
                mode ? LUZ_INTERPOLATION_AFFINE : LUZ_INTERPOLATION_PERSPECTIVE;
            const luz_bug bugs[3] = {LUZ_BUG_NONE, LUZ_BUG_NO_BACKFACE_CULLING,
                                     LUZ_BUG_NORMAL_MATRIX_IS_MODEL};
            for (int b = 0; b < 3; b++) {
                const tally count = check_one_at_a_time(&m, interpolation, bugs[b]);
                print_message("%s%s, bug %s: %d solved, %d clipped\n", turned ? "turned, " : "",
                              luz_interpolation_name(interpolation), luz_bug_name(bugs[b]),
                              count.solved, count.clipped);
                /* Most are seen: about half the triangles are front faces
                 * that cover a centre (all with no-backface-culling). */
                assert_true(count.solved > 1500);
                assert_true(count.clipped > 100);
            }
            if (!turned) check_lanes(&m, interpolation);
        }
    }
    mesh_destroy(&m);
}

/* CANCELLATION (test_setup_eight.c's): front faces a pixel or two across
 * whose normal and uv are sampled from steep planes f = A (x - rx) + B (y
 * - ry) through the reference point, so that a plane's value there, v0 +
 * dx (rx - x0) + dy (ry - y0), is the rounding left of terms thousands of
 * times larger: summed in another order, or with a fused multiply-add,
 * it comes out different from setup in lanes'. */
static void test_planes_that_cancel(void **state)
{
    (void)state;
    const uint32_t triangle_count = 4000;
    mesh m = {triangle_count, calloc(3 * (size_t)triangle_count, sizeof(luz_vertex)),
              calloc(3 * (size_t)triangle_count, sizeof(uint32_t)), {0}};
    assert_true(m.vertices && m.indices);
    m.transform = (luz_draw_transform){m.vertices, luz_mat4_identity(),
                                       luz_mat3_normal_matrix(luz_mat4_identity()),
                                       test_w_from_z()};
    uint32_t random = 4242;
    for (uint32_t t = 0; t < triangle_count; t++) {
        const int32_t x0 = 256 * 5 + (int32_t)(test_random(&random) % (256 * 30));
        const int32_t y0 = 256 * 5 + (int32_t)(test_random(&random) % (256 * 14));
        const int32_t long_side = 200 + (int32_t)(test_random(&random) % 300);
        const int32_t short_side = (int32_t)(test_random(&random) % 100);
        const int32_t corner[3][2] = {
            {x0, y0}, {x0 + short_side, y0 + long_side}, {x0 + long_side, y0 + short_side}};
        luz_window_vertex window[3];
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t i = 3 * t + k;
            m.indices[i] = i;
            m.vertices[i] =
                test_vertex_at(corner[k][0], corner[k][1], 1.0f, WIDTH, HEIGHT, &random);
            const luz_clip_vertex clip = luz_vertex_stage_one(&m.transform, i);
            window[k] = luz_setup_project_vertex(&clip, WIDTH, HEIGHT);
        }
        const double rx = window[0].fixed_x / (double)LUZ_SUBPIXEL_ONE;
        const double ry = window[0].fixed_y / (double)LUZ_SUBPIXEL_ONE;
        for (int v = 0; v < 5; v++) {
            const double a = test_uniform(&random, 1000.0f, 30000.0f);
            const double b = test_uniform(&random, -30000.0f, 30000.0f);
            for (uint32_t k = 0; k < 3; k++) {
                luz_vertex *vertex = &m.vertices[3 * t + k];
                float *free_floats[5] = {&vertex->normal.x, &vertex->normal.y, &vertex->normal.z,
                                         &vertex->uv.x, &vertex->uv.y};
                *free_floats[v] = (float)(a * (window[k].x - rx) + b * (window[k].y - ry));
            }
        }
    }
    assert_true(check_lanes(&m, LUZ_INTERPOLATION_PERSPECTIVE) >= 0);
    /* The cancellation happened: values far below their terms. */
    int tiny = 0;
    for (uint32_t t = 0; t < triangle_count; t++) {
        luz_shading_planes planes;
        if (luz_planes_of_primitive(&m.transform, m.indices, t, WIDTH, HEIGHT,
                                    LUZ_INTERPOLATION_PERSPECTIVE, LUZ_BUG_NONE,
                                    &planes) != LUZ_PLANES_SOLVED)
            continue;
        for (int v = LUZ_VARYING_NORMAL; v < LUZ_VARYING_COUNT; v++)
            tiny += fabsf(planes.varyings[v].value) < 1e-3f && fabsf(planes.varyings[v].dx) > 500.0f;
    }
    print_message("%d planes' values cancel to below 1e-3\n", tiny);
    assert_true(tiny > 1000);
    mesh_destroy(&m);
}

/* HAND-MADE: in a 64 x 32 frame (every coordinate below exact in
 * binary, so every comparison is), the triangle with window corners
 * (4, 2), (4, 10), (12, 2) (pixels, y down: a front face), clip w 1, 2
 * and 4, and u = x / 8, v = y / 4 at each corner. Then 1/w is the plane
 * through 1, 1/2, 1/4: its gradient (1/4 - 1) / 8 = -3/32 along x and
 * (1/2 - 1) / 8 = -1/16 along y; u/w goes 0.5, 0.25, 0.375: its gradient
 * (0.375 - 0.5) / 8 along x and (0.25 - 0.5) / 8 along y; the values
 * are those at vertex 0, the reference point (the corners are whole
 * pixels, so snapping leaves them). A normal (0, 0, 1) makes normal z / w
 * the 1/w plane itself. Affine: 1/w is 1 everywhere, u's plane u itself
 * (gradient 1/8 along x), v's v itself (1/4 along y). */
static void test_planes_by_hand(void **state)
{
    (void)state;
    mesh m = {1, calloc(3, sizeof(luz_vertex)), calloc(3, sizeof(uint32_t)), {0}};
    assert_true(m.vertices && m.indices);
    m.transform = (luz_draw_transform){m.vertices, luz_mat4_identity(),
                                       luz_mat3_normal_matrix(luz_mat4_identity()),
                                       test_w_from_z()};
    const float corner[3][3] = {{4, 2, 1}, {4, 10, 2}, {12, 2, 4}};   /* x, y pixels; w */
    for (uint32_t k = 0; k < 3; k++) {
        const float w = corner[k][2];
        const float x_ndc = corner[k][0] / 32.0f - 1.0f;
        const float y_ndc = 1.0f - corner[k][1] / 16.0f;
        m.vertices[k] = (luz_vertex){{x_ndc * w, y_ndc * w, w},
                                     {0.0f, 0.0f, 1.0f},
                                     {corner[k][0] / 8.0f, corner[k][1] / 4.0f}};
        m.indices[k] = k;
    }
    luz_shading_planes planes;
    assert_int_equal(luz_planes_of_primitive(&m.transform, m.indices, 0, 64, 32,
                                             LUZ_INTERPOLATION_PERSPECTIVE, LUZ_BUG_NONE,
                                             &planes),
                     LUZ_PLANES_SOLVED);
    assert_true(planes.inverse_w.value == 1.0f);
    assert_true(planes.inverse_w.dx == -3.0f / 32.0f);   /* (1/4 - 1) / 8 */
    assert_true(planes.inverse_w.dy == -1.0f / 16.0f);   /* (1/2 - 1) / 8 */
    const luz_plane u = planes.varyings[LUZ_VARYING_UV];
    assert_true(u.value == 0.5f);                 /* 4 / 8 at w 1 */
    assert_true(u.dx == (0.375f - 0.5f) / 8.0f);  /* 12 / 8 / 4 */
    assert_true(u.dy == (0.25f - 0.5f) / 8.0f);   /* 4 / 8 / 2 */
    const luz_plane normal_z = planes.varyings[LUZ_VARYING_NORMAL + 2];   /* 1/w itself */
    assert_memory_equal(&normal_z, &planes.inverse_w, sizeof normal_z);

    assert_int_equal(luz_planes_of_primitive(&m.transform, m.indices, 0, 64, 32,
                                             LUZ_INTERPOLATION_AFFINE, LUZ_BUG_NONE, &planes),
                     LUZ_PLANES_SOLVED);
    assert_true(planes.inverse_w.value == 1.0f && planes.inverse_w.dx == 0.0f &&
                planes.inverse_w.dy == 0.0f);
    assert_true(planes.varyings[LUZ_VARYING_UV].value == 0.5f);
    assert_true(planes.varyings[LUZ_VARYING_UV].dx == 1.0f / 8.0f);
    assert_true(planes.varyings[LUZ_VARYING_UV].dy == 0.0f);
    assert_true(planes.varyings[LUZ_VARYING_UV + 1].dx == 0.0f);
    assert_true(planes.varyings[LUZ_VARYING_UV + 1].dy == 1.0f / 4.0f);

    /* Corner 1 behind the eye: the clipper's, not this triangle's. */
    m.vertices[1].position.z = -1.0f;
    assert_int_equal(luz_planes_of_primitive(&m.transform, m.indices, 0, 64, 32,
                                             LUZ_INTERPOLATION_PERSPECTIVE, LUZ_BUG_NONE,
                                             &planes),
                     LUZ_PLANES_CLIPPED);
    /* All three on one point: no plane to solve. */
    m.vertices[1] = m.vertices[2] = m.vertices[0];
    assert_int_equal(luz_planes_of_primitive(&m.transform, m.indices, 0, 64, 32,
                                             LUZ_INTERPOLATION_PERSPECTIVE, LUZ_BUG_NONE,
                                             &planes),
                     LUZ_PLANES_NONE);
    mesh_destroy(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_planes_by_hand),
        cmocka_unit_test(test_planes_of_primitive_are_setups),
        cmocka_unit_test(test_planes_that_cancel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
