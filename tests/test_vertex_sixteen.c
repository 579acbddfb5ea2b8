/*
 * test_vertex_sixteen.c: the vertex stage and projection in lanes, every
 * variant this machine runs (src/renderer/vertex_sixteen.c,
 * vertex_lanes.c), against the same stages one vertex at a time
 * (luz_vertex_stage_range, then luz_setup_project), the functions the
 * other tests derive by hand.
 *
 * Its contract: every byte of every clip vertex the same, every snapped
 * position (fixed) the same, and every window vertex the same but for
 * the fields of a marked vertex other than its marker. Random meshes
 * through random cameras and models: vertices in view, beyond the guard
 * band, behind the camera, at the near plane, far beyond the fixed-point
 * limit, a matrix that leaves w = 0 (not projectable), a model so large
 * that clip coordinates are infinite or NaN; vertices exactly on the
 * clip planes (whole coordinates through identity matrices: x = 4 w is
 * the guard band's edge, z = w the far plane) and at w = -0; ranges that
 * start and end anywhere (tails of 1 to 15 done one at a time), with and
 * without the fixed, window and clip arrays.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "test_support.h"

#include "luz/mesh.h"
#include "luz/vecmath.h"
#include "renderer/cpu.h"
#include "renderer/pipeline.h"

#define VERTEX_COUNT 4099   /* not a multiple of 16 */

/* Compares range [first, end) of the two results (clip_a, window_a and
 * fixed_a: NULL where the lanes were asked for none). */
static int compare(const luz_clip_vertex *clip_a, const luz_window_vertex *window_a,
                   const luz_fixed_vertex *fixed_a, const luz_clip_vertex *clip_b,
                   const luz_window_vertex *window_b, const luz_fixed_vertex *fixed_b,
                   uint32_t first, uint32_t end)
{
    int marked = 0;
    for (uint32_t i = first; i < end; i++) {
        if (clip_a != NULL && memcmp(&clip_a[i], &clip_b[i], sizeof clip_a[i]) != 0)
            fail_msg("vertex %u: clip vertices differ", i);
        if (fixed_a != NULL && memcmp(&fixed_a[i], &fixed_b[i], sizeof fixed_a[i]) != 0)
            fail_msg("vertex %u: fixed (%d, %d), one at a time (%d, %d)", i, fixed_a[i].x,
                     fixed_a[i].y, fixed_b[i].x, fixed_b[i].y);
        const bool is_marked = window_b[i].fixed_x == LUZ_WINDOW_CLIPPED ||
                               window_b[i].fixed_x == LUZ_WINDOW_INVALID;
        if (is_marked) marked++;
        if (window_a == NULL) continue;
        if (is_marked) {
            if (window_a[i].fixed_x != window_b[i].fixed_x ||
                window_a[i].fixed_y != window_b[i].fixed_y)
                fail_msg("vertex %u: marker (%d, %d), one at a time (%d, %d)", i,
                         window_a[i].fixed_x, window_a[i].fixed_y, window_b[i].fixed_x,
                         window_b[i].fixed_y);
        } else if (memcmp(&window_a[i], &window_b[i], sizeof window_a[i]) != 0) {
            fail_msg("vertex %u: window vertices differ (x %.17g / %.17g, fixed %d / %d)", i,
                     window_a[i].x, window_b[i].x, window_a[i].fixed_x, window_b[i].fixed_x);
        }
    }
    return marked;
}

/* One variant's vertex pass against the two functions, on the same
 * vertices, cameras and ranges whatever the variant. */
static void check_variant(luz_vertex_project_function *vertex_project)
{
    luz_vertex *vertices = calloc(VERTEX_COUNT, sizeof *vertices);
    uint32_t *indices = calloc(3, sizeof *indices);
    luz_clip_vertex *clip_a = calloc(VERTEX_COUNT, sizeof *clip_a);
    luz_clip_vertex *clip_b = calloc(VERTEX_COUNT, sizeof *clip_b);
    luz_window_vertex *window_a = calloc(VERTEX_COUNT, sizeof *window_a);
    luz_window_vertex *window_b = calloc(VERTEX_COUNT, sizeof *window_b);
    luz_fixed_vertex *fixed_a = calloc(VERTEX_COUNT, sizeof *fixed_a);
    luz_fixed_vertex *fixed_b = calloc(VERTEX_COUNT, sizeof *fixed_b);
    assert_true(vertices && indices && clip_a && clip_b && window_a && window_b && fixed_a &&
                fixed_b);
    uint32_t random = 99;
    for (uint32_t i = 0; i < VERTEX_COUNT; i++) {
        const uint32_t kind = test_random(&random) % 100;
        const float reach = kind < 70 ? 2.0f : kind < 90 ? 30.0f : 3e6f;
        vertices[i] = (luz_vertex){
            {test_uniform(&random, -reach, reach), test_uniform(&random, -reach, reach),
             test_uniform(&random, -reach, reach)},
            {test_uniform(&random, -1, 1), test_uniform(&random, -1, 1),
             test_uniform(&random, -1, 1)},
            {test_uniform(&random, -2, 3), test_uniform(&random, -2, 3)}};
        if (kind >= 85)   /* whole coordinates from -5 to 5: on planes, below */
            for (int k = 0; k < 3; k++)
                (&vertices[i].position.x)[k] = (float)((int)(test_random(&random) % 11) - 5);
    }
    luz_error error = {{0}};
    luz_mesh *mesh = luz_mesh_create(
        &(luz_mesh_desc){.vertices = vertices, .vertex_count = VERTEX_COUNT,
                         .indices = indices, .index_count = 3},
        &error);
    assert_non_null(mesh);

    enum { CAMERA, ZERO, IDENTITY, NEGATIVE_ZERO_W };
    const struct {
        int width, height;
        int projection;   /* CAMERA: a random camera's; ZERO: w = 0 for every
                             vertex, none projectable; IDENTITY: clip = (x, y,
                             z, 1) under the identity model, so whole
                             coordinates lie on the clip planes;
                             NEGATIVE_ZERO_W: the same with w's row -0, so
                             that w = -0 where x, y and z are not negative */
    } cases[] = {{1280, 720, CAMERA},   {321, 181, CAMERA}, {1, 1, CAMERA},
                 {16384, 9000, CAMERA}, {640, 360, ZERO},   {640, 360, IDENTITY},
                 {640, 360, NEGATIVE_ZERO_W}};
    int on_plane = 0, negative_zero_w = 0;
    int marked = 0, projected = 0, non_finite = 0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
        for (int camera = 0; camera < 4; camera++) {
            const luz_vec3 eye = {test_uniform(&random, -5, 5), test_uniform(&random, -5, 5),
                                  test_uniform(&random, -5, 5)};
            luz_mat4 view_projection = luz_mat4_multiply(
                luz_mat4_perspective(luz_radians(test_uniform(&random, 20, 100)),
                                     (float)cases[c].width / (float)cases[c].height, 0.1f,
                                     test_uniform(&random, 5, 500)),
                luz_mat4_look_at(eye, (luz_vec3){0, 0, 0}, (luz_vec3){0, 1, 0}));
            if (cases[c].projection == ZERO) memset(&view_projection, 0, sizeof view_projection);
            if (cases[c].projection >= IDENTITY) view_projection = luz_mat4_identity();
            if (cases[c].projection == NEGATIVE_ZERO_W)
                for (int k = 3; k < 16; k += 4) view_projection.m[k] = -0.0f;
            int infinite = 0, nan = 0;
            luz_draw draw = {.mesh = mesh,
                             .model = luz_mat4_rotate(
                                 luz_mat4_translate(luz_mat4_identity(),
                                                    (luz_vec3){test_uniform(&random, -1, 1), 0, 0}),
                                 test_uniform(&random, 0, 6.28f), (luz_vec3){0.6f, 0.8f, 0})};
            if (cases[c].projection >= IDENTITY) draw.model = luz_mat4_identity();
            else if (camera == 3)   /* far beyond float's range: infinite and NaN coordinates */
                for (int k = 0; k < 12; k++) draw.model.m[k] *= k % 2 ? 1e38f : -1e38f;
            for (uint32_t first = 0; first < VERTEX_COUNT;) {
                const uint32_t length = 1 + test_random(&random) % 300;
                const uint32_t end = first + length < VERTEX_COUNT ? first + length : VERTEX_COUNT;
                const bool with_fixed = test_random(&random) % 4 != 0;
                /* Setup in lanes projects corners itself: the vertex
                 * pass then keeps no window vertices. */
                const bool with_window = test_random(&random) % 4 != 0;
                /* Position-only shading (setup in lanes shades corners
                 * itself): no clip vertices either. */
                const bool with_clip = with_window || test_random(&random) % 2 != 0;
                memset(window_a, 0x5A, VERTEX_COUNT * sizeof *window_a);
                memset(clip_a, 0x5A, VERTEX_COUNT * sizeof *clip_a);
                memset(fixed_a, 0x5A, VERTEX_COUNT * sizeof *fixed_a);
                vertex_project(&draw, view_projection, first, end, cases[c].width,
                               cases[c].height, with_clip ? clip_a : NULL,
                               with_window ? window_a : NULL, with_fixed ? fixed_a : NULL);
                /* Nothing written outside the range (the stores of whole
                 * rows that overlap the next vertex stay within it). */
                for (size_t byte = 0; byte < VERTEX_COUNT * sizeof *clip_a; byte++) {
                    const size_t vertex = byte / sizeof *clip_a;
                    const bool outside = vertex < first || vertex >= end;
                    if ((outside || !with_clip) && ((unsigned char *)clip_a)[byte] != 0x5A)
                        fail_msg("clip vertex %zu written (range [%u, %u)%s)", vertex, first, end,
                                 with_clip ? "" : ", none asked for");
                }
                for (size_t byte = 0; byte < VERTEX_COUNT * sizeof *window_a; byte++) {
                    const size_t vertex = byte / sizeof *window_a;
                    const bool outside = vertex < first || vertex >= end;
                    if ((outside || !with_window) && ((unsigned char *)window_a)[byte] != 0x5A)
                        fail_msg("window vertex %zu written (range [%u, %u)%s)", vertex, first,
                                 end, with_window ? "" : ", none asked for");
                }
                for (size_t byte = 0; byte < VERTEX_COUNT * sizeof *fixed_a; byte++) {
                    const size_t vertex = byte / sizeof *fixed_a;
                    if ((vertex < first || vertex >= end || !with_fixed) &&
                        ((unsigned char *)fixed_a)[byte] != 0x5A)
                        fail_msg("fixed vertex %zu written (range [%u, %u))", vertex, first, end);
                }
                luz_vertex_stage_range(&draw, view_projection, first, end, clip_b);
                luz_setup_project(clip_b, first, end, cases[c].width, cases[c].height, window_b,
                                  fixed_b);
                const int m = compare(with_clip ? clip_a : NULL, with_window ? window_a : NULL,
                                      with_fixed ? fixed_a : NULL, clip_b, window_b, fixed_b,
                                      first, end);
                for (uint32_t i = first; i < end; i++) {
                    const luz_vec4 p = clip_b[i].position;
                    infinite += !isfinite(p.x) || !isfinite(p.w);
                    nan += isnan(p.x) || isnan(p.w);
                    on_plane += p.w == 1.0f && (fabsf(p.x) == 4.0f || fabsf(p.z) == 1.0f);
                    negative_zero_w += p.w == 0.0f && signbit(p.w);
                }
                marked += m;
                projected += (int)(end - first) - m;
                first = end;
            }
            if (camera == 3 && cases[c].projection == CAMERA)
                assert_true(infinite > 100 && nan > 100);
            non_finite += infinite;
        }
    print_message("%d vertices projected, %d marked (%d with clip coordinates not finite)\n",
                  projected, marked, non_finite);
    print_message("%d vertices on a clip plane, %d at w = -0\n", on_plane, negative_zero_w);
    assert_true(on_plane > 500 && negative_zero_w > 500);
    assert_true(projected > 20000);
    assert_true(marked > 20000);
    luz_mesh_destroy(mesh);
    free(vertices);
    free(indices);
    free(clip_a);
    free(clip_b);
    free(window_a);
    free(window_b);
    free(fixed_a);
    free(fixed_b);
}

/* Every instruction set's vertex pass in lanes that this build and CPU
 * have (AVX-512's vertex_sixteen.c, AVX2's and NEON's vertex_lanes.c). */
static void test_lanes_agree_with_one_at_a_time(void **state)
{
    (void)state;
    int tested = 0;
    for (int isa = 0; isa < LUZ_ISA_COUNT; isa++) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        luz_vertex_project_function *vertex_project = luz_kernels_of((luz_isa)isa).vertex_project;
        if (vertex_project == NULL) continue;
        print_message("%s:\n", luz_isa_name((luz_isa)isa));
        check_variant(vertex_project);
        tested++;
    }
    if (tested == 0) {
        print_message("skipped: this build or CPU has no vertex pass in lanes\n");
        skip();
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lanes_agree_with_one_at_a_time),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
