/*
 * test_scene.c: SCENE.md's scene as data (src/lab/scene.c): the
 * xorshift32 colours, the tiling of more cubes, the frame of draws and
 * the uniforms at a time t, against values derived from SCENE.md's text.
 */
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "test_support.h"

#include "lab/scene.h"
#include "luz/shade.h"
#include "luz/texture.h"

#define TOLERANCE 1e-6

#define assert_vec3_near(got, expected_x, expected_y, expected_z, tolerance) \
    assert_vec3_near_at((got), (expected_x), (expected_y), (expected_z), (tolerance), #got, \
                        __FILE__, __LINE__)

static void assert_vec3_near_at(luz_vec3 got, double x, double y, double z, double tolerance,
                                const char *expression, const char *file, int line)
{
    assert_near_at(got.x, x, tolerance, expression, file, line);
    assert_near_at(got.y, y, tolerance, expression, file, line);
    assert_near_at(got.z, z, tolerance, expression, file, line);
}

/* SCENE.md's generator, written here from its text: x ^= x << 13;
 * x ^= x >> 17; x ^= x << 5; each float is (x >> 8) / 16777216 after one
 * step; seed 0 means 0x9E3779B9. */
static float next_float(uint32_t *x)
{
    *x ^= *x << 13;
    *x ^= *x >> 17;
    *x ^= *x << 5;
    return (float)(*x >> 8) / 16777216.0f;
}

/* By hand for seed 1: 1 ^ (1 << 13) = 8193; 8193 >> 17 = 0; 8193 ^
 * (8193 << 5) = 0x2001 ^ 0x40020 = 0x42021 = 270369; 270369 >> 8 = 1056:
 * cube 0's red is 1056 / 16777216. The rest follows from the generator
 * above: cube 0 takes r, g, b, then cube 1. Floats of 24 bits are exact,
 * so the comparison is exact. */
static void test_random_colours_follow_xorshift32(void **state)
{
    (void)state;
    const uint32_t seeds[2] = {0, 1};
    for (int s = 0; s < 2; s++) {
        luz_vec3 colours[4];
        luz_scene_random_colours(seeds[s], 4, colours);
        uint32_t x = seeds[s] == 0 ? 0x9E3779B9u : seeds[s];
        for (int i = 0; i < 4; i++) {
            float r = next_float(&x), g = next_float(&x), b = next_float(&x);
            assert_true(colours[i].x == r);
            assert_true(colours[i].y == g);
            assert_true(colours[i].z == b);
            assert_true(r >= 0.0f && r < 1.0f);
        }
    }
    luz_vec3 seed_one[1];
    luz_scene_random_colours(1, 1, seed_one);
    assert_true(seed_one[0].x == 1056.0f / 16777216.0f);
}

/* Seed 0 stands for 0x9E3779B9: both give the same colours. */
static void test_seed_zero_means_golden_ratio_constant(void **state)
{
    (void)state;
    luz_vec3 zero[3], golden[3];
    luz_scene_random_colours(0, 3, zero);
    luz_scene_random_colours(0x9E3779B9u, 3, golden);
    assert_memory_equal(zero, golden, sizeof zero);
}

/* SCENE.md's tiles: tile k = floor(i / 10) at cell (gx, gy), offset
 * (9 gx, 8 gy, -16 r). Ring 1 row by row: tile 1 (-1,-1), 2 (0,-1),
 * 3 (1,-1), 4 (-1,0), 5 (1,0), 6 (-1,1), 7 (0,1), 8 (1,1); ring 2 starts
 * at tile 9 with (-2,-2), then (-1,-2) ... (2,-2) (tile 13), (-2,-1) (14),
 * (2,-1) (15), ..., (2,2) (24); ring 3 starts at tile 25 with (-3,-3). */
static void test_tiled_positions(void **state)
{
    (void)state;
    assert_vec3_near(luz_scene_tiled_position(0), 0, 0, 0, 0);
    assert_vec3_near(luz_scene_tiled_position(3), -3.8, -2.0, -12.3, TOLERANCE);
    assert_vec3_near(luz_scene_tiled_position(10), -9, -8, -16, 0);
    assert_vec3_near(luz_scene_tiled_position(11), 2 - 9, 5 - 8, -15 - 16, 0);
    assert_vec3_near(luz_scene_tiled_position(20), 0, -8, -16, 0);
    assert_vec3_near(luz_scene_tiled_position(40), -9, 0, -16, 0);
    assert_vec3_near(luz_scene_tiled_position(50), 9, 0, -16, 0);
    assert_vec3_near(luz_scene_tiled_position(80), 9, 8, -16, 0);
    assert_vec3_near(luz_scene_tiled_position(90), -18, -16, -32, 0);
    assert_vec3_near(luz_scene_tiled_position(130), 18, -16, -32, 0);
    assert_vec3_near(luz_scene_tiled_position(140), -18, -8, -32, 0);
    assert_vec3_near(luz_scene_tiled_position(150), 18, -8, -32, 0);
    assert_vec3_near(luz_scene_tiled_position(240), 18, 16, -32, 0);
    assert_vec3_near(luz_scene_tiled_position(250), -27, -24, -48, 0);
    assert_vec3_near(luz_scene_tiled_position(257), 1.5 - 27, 2 - 24, -2.5 - 48, TOLERANCE);
}

/* SCENE.md's ten positions, typed again from its text. */
static const float scene_md_positions[10][3] = {
    { 0.0f,  0.0f,   0.0f}, { 2.0f,  5.0f, -15.0f}, {-1.5f, -2.2f,  -2.5f},
    {-3.8f, -2.0f, -12.3f}, { 2.4f, -0.4f,  -3.5f}, {-1.7f,  3.0f,  -7.5f},
    { 1.3f, -2.0f,  -2.5f}, { 1.5f,  2.0f,  -2.5f}, { 1.5f,  0.2f,  -1.5f},
    {-1.3f,  1.0f,  -1.5f},
};

typedef struct tile_cell {
    int gx, gy, ring;
} tile_cell;

#define TILE_COUNT ((LUZ_MAX_CUBES + 9) / 10)

/* Fails unless got holds exactly the bits of expected: position p[i mod
 * 10] plus the offset (9 gx, 8 gy, -16 r), each a float sum of the
 * table's float and the offset's (exact: small whole numbers). */
static void assert_tiled_position_bits(int cube_index, tile_cell cell)
{
    const float *p = scene_md_positions[cube_index % 10];
    const float expected[3] = {p[0] + 9.0f * cell.gx, p[1] + 8.0f * cell.gy,
                               p[2] + -16.0f * cell.ring};
    luz_vec3 position = luz_scene_tiled_position(cube_index);
    const float got[3] = {position.x, position.y, position.z};
    if (memcmp(got, expected, sizeof got) != 0)
        fail_msg("cube %d (cell %d, %d in ring %d): (%.9g, %.9g, %.9g), expected (%.9g, %.9g, "
                 "%.9g)",
                 cube_index, cell.gx, cell.gy, cell.ring, got[0], got[1], got[2], expected[0],
                 expected[1], expected[2]);
}

/* Every cube up to LUZ_MAX_CUBES against SCENE.md's tiling enumerated
 * literally: ring 0 is the single cell (0, 0); then for r = 1, 2, ...,
 * gy from -r to r and, for each gy, gx from -r to r, keeping the cells
 * with max(|gx|, |gy|) = r, numbering the tiles as they come. Bit for
 * bit: the tiling may be computed any way, but not rounded differently. */
static void test_tiling_matches_scene_md_enumeration(void **state)
{
    (void)state;
    static tile_cell cells[TILE_COUNT];
    int tiles = 0;
    cells[tiles++] = (tile_cell){0, 0, 0};
    for (int r = 1; tiles < TILE_COUNT; r++) {
        int in_ring = 0;
        for (int gy = -r; gy <= r; gy++) {
            for (int gx = -r; gx <= r; gx++) {
                int ring = abs(gx) > abs(gy) ? abs(gx) : abs(gy);
                if (ring != r) continue;
                in_ring++;
                if (tiles < TILE_COUNT) cells[tiles++] = (tile_cell){gx, gy, r};
            }
        }
        assert_int_equal(in_ring, 8 * r);   /* the square's border */
    }
    /* The enumeration is SCENE.md's: tiles 1-8 start (-1,-1), (0,-1),
     * (1,-1), (-1,0), (1,0), (-1,1), ... */
    assert_true(cells[1].gx == -1 && cells[1].gy == -1 && cells[2].gx == 0 &&
                cells[2].gy == -1 && cells[4].gx == -1 && cells[4].gy == 0 &&
                cells[5].gx == 1 && cells[5].gy == 0 && cells[6].gx == -1 && cells[6].gy == 1);

    for (int i = 0; i < LUZ_MAX_CUBES; i++) assert_tiled_position_bits(i, cells[i / 10]);
}

/* Beyond LUZ_MAX_CUBES, where an integer square root taken through
 * floating point could land on the wrong side of a perfect square: for
 * every ring r whose tiles have cube indices within int, the first tile
 * of the ring, (2r - 1)^2, is cell (-r, -r), and its last,
 * (2r + 1)^2 - 1, is (r, r) (rings before r fill the (2r - 1)^2 square;
 * the order ends on the bottom row's last cell). */
static void test_tiling_ring_boundaries_up_to_int_max(void **state)
{
    (void)state;
    int rings = 0;
    for (int r = 1;; r++) {
        int64_t first = (int64_t)(2 * r - 1) * (2 * r - 1);
        int64_t last = (int64_t)(2 * r + 1) * (2 * r + 1) - 1;
        if (10 * last + 9 > INT_MAX) break;
        for (int k = 0; k < 10; k++) {
            assert_tiled_position_bits((int)(10 * first) + k, (tile_cell){-r, -r, r});
            assert_tiled_position_bits((int)(10 * last) + k, (tile_cell){r, r, r});
        }
        rings++;
    }
    assert_true(rings > 7000);   /* sqrt(INT_MAX / 10) / 2 = 7327 */
}

/* The default frame: ten cubes in index order, then the point-light
 * marker, unlit, in Pt.rgb (not scaled by the strength), a 0.2 cube at the
 * light's position, at t = 0 (3, 0.5, 0): its corner (0.5, 0.5, 0.5) lands
 * on (3.1, 0.6, 0.1). With the point strength at 0 there is no marker. */
static void test_frame_has_ten_cubes_and_a_marker(void **state)
{
    (void)state;
    luz_lab *lab = luz_lab_create(NULL);
    assert_non_null(lab);
    luz_scene scene = luz_scene_defaults();
    scene.lights.point.colour = (luz_vec3){0.5f, 0.25f, 1.0f};
    scene.lights.point.strength = 0.3f;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(lab, &scene, NULL, 0, 16.0f / 9.0f, &frame, NULL), 0);
    assert_int_equal(frame.draw_count, 11);
    for (int i = 0; i < 10; i++) {
        assert_false(frame.draws[i].material.shading == LUZ_SHADING_UNLIT);
        assert_ptr_equal(frame.draws[i].mesh, luz_lab_cube_mesh(lab));
        assert_null(frame.draws[i].material.texture);
    }
    const luz_draw *marker = &frame.draws[10];
    assert_true(marker->material.shading == LUZ_SHADING_UNLIT);
    assert_ptr_equal(marker->mesh, luz_lab_cube_mesh(lab));
    assert_vec3_near(marker->material.colour, 0.5, 0.25, 1.0, 0);
    assert_vec3_near(luz_mat4_transform_point(marker->model, (luz_vec3){0.5f, 0.5f, 0.5f}), 3.1,
                     0.6, 0.1, TOLERANCE);
    assert_vec3_near(luz_mat4_transform_point(marker->model, (luz_vec3){-0.5f, -0.5f, -0.5f}),
                     2.9, 0.4, -0.1, TOLERANCE);

    scene.lights.point.strength = 0.0f;
    assert_int_equal(luz_scene_build_frame(lab, &scene, NULL, 0, 16.0f / 9.0f, &frame, NULL), 0);
    assert_int_equal(frame.draw_count, 10);
    luz_lab_destroy(lab);
    luz_frame_free(&frame);
}

/* Each cube's objectColor is the generator's, in index order, and cube i
 * uses texture i mod N: with three textures, cubes 0..9 use 0 1 2 0 1 2
 * 0 1 2 0. */
static void test_frame_colours_and_textures(void **state)
{
    (void)state;
    luz_lab *lab = luz_lab_create(NULL);
    assert_non_null(lab);
    const uint8_t texel[4] = {1, 2, 3, 255};
    luz_error error;
    luz_texture *textures[3];
    for (int k = 0; k < 3; k++) {
        textures[k] = luz_texture_create(1, 1, texel, &error);
        assert_non_null(textures[k]);
    }
    luz_scene scene = luz_scene_defaults();
    scene.seed = 7;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(lab, &scene, textures, 3, 1.0f, &frame, NULL), 0);
    uint32_t x = 7;
    for (int i = 0; i < 10; i++) {
        float r = next_float(&x), g = next_float(&x), b = next_float(&x);
        assert_true(frame.draws[i].material.colour.x == r && frame.draws[i].material.colour.y == g &&
                    frame.draws[i].material.colour.z == b);
        assert_ptr_equal(frame.draws[i].material.texture, textures[i % 3]);
    }
    luz_lab_destroy(lab);
    luz_frame_free(&frame);
    for (int k = 0; k < 3; k++) luz_texture_destroy(textures[k]);
}

/* A custom cube with a colour of its own keeps it; one without gets the
 * generator's colour for its index (cube 1: the 4th to 6th floats). */
static void test_custom_cubes_keep_their_colour(void **state)
{
    (void)state;
    luz_lab *lab = luz_lab_create(NULL);
    assert_non_null(lab);
    const luz_object cubes[2] = {
        {.position = {1, 2, 3}, .has_colour = true, .colour = {0.25f, 0.5f, 0.75f},
         .texture = LUZ_TEXTURE_BY_INDEX},
        {.position = {-1, 0, 0}, .texture = LUZ_TEXTURE_BY_INDEX},
    };
    luz_scene scene = luz_scene_defaults();
    scene.objects = cubes;
    scene.object_count = 2;
    scene.lights.point.strength = 0.0f;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(lab, &scene, NULL, 0, 1.0f, &frame, NULL), 0);
    assert_int_equal(frame.draw_count, 2);
    assert_vec3_near(frame.draws[0].material.colour, 0.25, 0.5, 0.75, 0);
    assert_vec3_near(luz_mat4_transform_point(frame.draws[0].model, (luz_vec3){0, 0, 0}), 1, 2,
                     3, 0);
    uint32_t x = 0x9E3779B9u;
    for (int k = 0; k < 3; k++) next_float(&x);
    float r = next_float(&x), g = next_float(&x), b = next_float(&x);
    assert_true(frame.draws[1].material.colour.x == r && frame.draws[1].material.colour.y == g &&
                frame.draws[1].material.colour.z == b);
    luz_lab_destroy(lab);
    luz_frame_free(&frame);
}

/* The rotation part of cube i's model at time t, checked through the
 * scene's axis a = normalize(1, 0.5, 1) = (2/3, 1/3, 2/3): the model takes
 * the origin to p_i, fixes the axis direction, and turns v = (1, 0, -1)
 * (perpendicular to it, |v|^2 = 2) by the angle: dot(v, R v) = 2 cos angle,
 * v x R v = 2 sin angle a. */
static void assert_cube_model(const luz_draw *draw, luz_vec3 position, double cos_angle,
                              double sin_angle, double tolerance)
{
    luz_mat4 model = draw->model;
    luz_vec3 origin = luz_mat4_transform_point(model, (luz_vec3){0, 0, 0});
    assert_vec3_near(origin, position.x, position.y, position.z, tolerance);
    luz_vec3 axis = luz_vec3_sub(luz_mat4_transform_point(model, (luz_vec3){1, 0.5f, 1}), origin);
    assert_vec3_near(axis, 1, 0.5, 1, tolerance);
    const luz_vec3 v = {1, 0, -1};
    luz_vec3 turned = luz_vec3_sub(luz_mat4_transform_point(model, v), origin);
    assert_near(luz_vec3_dot(v, turned), 2 * cos_angle, tolerance);
    assert_vec3_near(luz_vec3_cross(v, turned), 2 * sin_angle * 2 / 3, 2 * sin_angle / 3,
                     2 * sin_angle * 2 / 3, tolerance);
}

/* angle_i = (i + 1) / 3 * t * 50 degrees:
 *   t = 0: every cube unrotated; cube 0's model is the identity;
 *   cube 2 at t = 1.2: 3/3 * 1.2 * 50 = 60 degrees;
 *   cube 4 at t = 0.9: 5/3 * 0.9 * 50 = 75 degrees
 *     (2 cos 75 = 0.51763809, 2 sin 75 = 1.93185165);
 *   cube 9 at t = 10000 (a viewer left running for three hours):
 *     10/3 * 10000 * 50 = 1666666.667 degrees, which is 226.667 after 4629
 *     turns (cos = -0.68624164, sin = -0.72737364); an angle turned into
 *     radians in single precision before reducing it to one turn would be
 *     off by 0.03 degrees, 4e-4 in these numbers. */
static void test_cube_model_matrices(void **state)
{
    (void)state;
    luz_lab *lab = luz_lab_create(NULL);
    assert_non_null(lab);
    luz_scene scene = luz_scene_defaults();
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(lab, &scene, NULL, 0, 1.0f, &frame, NULL), 0);
    luz_mat4 identity = luz_mat4_identity();
    assert_memory_equal(frame.draws[0].model.m, identity.m, sizeof identity.m);
    assert_cube_model(&frame.draws[5], (luz_vec3){-1.7f, 3.0f, -7.5f}, 1, 0, TOLERANCE);

    scene.time_seconds = 1.2;
    assert_int_equal(luz_scene_build_frame(lab, &scene, NULL, 0, 1.0f, &frame, NULL), 0);
    assert_cube_model(&frame.draws[2], (luz_vec3){-1.5f, -2.2f, -2.5f}, 0.5, sqrt(3.0) / 2,
                      1e-5);

    scene.time_seconds = 0.9;
    assert_int_equal(luz_scene_build_frame(lab, &scene, NULL, 0, 1.0f, &frame, NULL), 0);
    assert_cube_model(&frame.draws[4], (luz_vec3){2.4f, -0.4f, -3.5f}, 0.51763809 / 2,
                      1.93185165 / 2, 1e-5);

    scene.time_seconds = 10000.0;
    assert_int_equal(luz_scene_build_frame(lab, &scene, NULL, 0, 1.0f, &frame, NULL), 0);
    assert_cube_model(&frame.draws[9], (luz_vec3){-1.3f, 1.0f, -1.5f}, -0.68624164, -0.72737364,
                      1e-5);
    luz_lab_destroy(lab);
    luz_frame_free(&frame);
}

/* The camera and lights at t = pi: the point light at (3 cos(pi/2), 0.5,
 * 3 sin(pi/2)) = (0, 0.5, 3); the sun's direction (cos 0.1 pi,
 * sin 0.1 pi, 0) = (0.95105652, 0.30901699, 0). The camera of SCENE.md:
 * E = (0, 0, 3), F = (0, 0, -1) (the spot's direction), a view that
 * translates by -3 in z, projection with f = cot 22.5 = 2.41421356 over
 * aspect 16/9 = 1.35799513; the spot cones cos 12.5 = 0.97629601 and
 * cos 17.5 = 0.95371695; the clear colour 0.1. */
static void test_camera_and_lights_at_pi(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = LUZ_PI;
    luz_frame frame = {0};
    luz_scene_set_camera_and_lights(&scene, 16.0f / 9.0f, &frame);
    assert_vec3_near(frame.lights.point_position, 0, 0.5, 3, TOLERANCE);
    assert_vec3_near(frame.lights.directional_direction, 0.95105652, 0.30901699, 0, TOLERANCE);
    assert_vec3_near(frame.eye, 0, 0, 3, 0);
    assert_vec3_near(frame.lights.spot_direction, 0, 0, -1, TOLERANCE);
    assert_vec3_near(luz_mat4_transform_point(frame.view, (luz_vec3){1, 2, 3}), 1, 2, 0,
                     TOLERANCE);
    assert_near(frame.projection.m[0], 1.35799513, 1e-6);
    assert_near(frame.projection.m[5], 2.41421356, 1e-6);
    luz_shade_uniforms shade = luz_shade_uniforms_of(frame.eye, &frame.lights);
    assert_near(shade.spot_cos_inner, 0.97629601, TOLERANCE);
    assert_near(shade.spot_cos_outer, 0.95371695, TOLERANCE);
    assert_vec3_near(frame.clear_colour, 0.1, 0.1, 0.1, TOLERANCE);
    /* The lights' colours and strengths are the scene's. */
    assert_vec3_near(frame.lights.spot.colour, 1, 1, 1, 0);
    assert_near(frame.lights.directional.strength, 0.4, 1e-7);

    /* The teaching settings become render options. */
    scene.view = LUZ_VIEW_NORMALS;
    scene.interpolation = LUZ_INTERPOLATION_AFFINE;
    luz_render_options options = luz_scene_render_options(&scene);
    assert_int_equal(options.view, LUZ_VIEW_NORMALS);
    assert_int_equal(options.interpolation, LUZ_INTERPOLATION_AFFINE);
    assert_int_equal(options.triangle_limit, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_colours_follow_xorshift32),
        cmocka_unit_test(test_seed_zero_means_golden_ratio_constant),
        cmocka_unit_test(test_tiled_positions),
        cmocka_unit_test(test_tiling_matches_scene_md_enumeration),
        cmocka_unit_test(test_tiling_ring_boundaries_up_to_int_max),
        cmocka_unit_test(test_frame_has_ten_cubes_and_a_marker),
        cmocka_unit_test(test_frame_colours_and_textures),
        cmocka_unit_test(test_custom_cubes_keep_their_colour),
        cmocka_unit_test(test_cube_model_matrices),
        cmocka_unit_test(test_camera_and_lights_at_pi),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
