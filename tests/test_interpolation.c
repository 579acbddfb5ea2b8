/*
 * test_interpolation.c: perspective-correct interpolation of varyings
 * (src/renderer/fragment.c, luz_fragment_interpolate) against a ray-plane
 * intersection worked out by hand.
 *
 * The scene: a camera at the origin looking down -z with a 90 degree
 * vertical field of view, aspect 1, near 0.1, far 100, on a 64x64 image.
 * A floor quad at y = -1 from x = -1 to 1 and z = -1 to -4, with
 *   u = (x + 1) / 2,  v = (-z - 1) / 3,
 * seen at a steep angle, so its depth changes a lot across the screen.
 * With f = cot 45 = 1, x_ndc = x / -z and y_ndc = y / -z; the corners land
 * on window coordinates (0, 64), (64, 64), (40, 40) and (24, 40): exact
 * on the sub-pixel grid, so snapping changes nothing.
 *
 * Pixel (40, 44) has its centre at (40.5, 44.5): x_ndc = 81/64 - 1 =
 * 17/64, y_ndc = 1 - 89/64 = -25/64. The ray t (x_ndc, y_ndc, -1) meets
 * y = -1 at t = 64/25 = 2.56: the point (0.68, -1, -2.56), so u = 0.84 and
 * v = 1.56 / 3 = 0.52.
 *
 * Last, a triangle whose vertices lie between the 1/256-pixel grid points
 * against barycentric interpolation from its exact positions: the planes
 * must not be solved from the snapped ones.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "test_support.h"

#include "renderer/pipeline.h"

#define SIZE 64
#define PIXEL_X 40
#define PIXEL_Y 44

typedef struct floor_fixture {
    luz_triangle triangles[2];
    luz_framebuffer *framebuffer;
    luz_fragment fragment;   /* at (PIXEL_X, PIXEL_Y) */
} floor_fixture;

/* The vertex stage's output for a floor corner: clip position from the
 * real projection, world position, normal +y and the uv above. */
static luz_clip_vertex floor_vertex(luz_mat4 view_projection, float x, float z)
{
    luz_clip_vertex vertex;
    vertex.position = luz_mat4_transform(view_projection, (luz_vec4){x, -1.0f, z, 1.0f});
    vertex.outcode = luz_clip_outcode(vertex.position);
    const float varyings[LUZ_VARYING_COUNT] = {x, -1.0f, z, 0, 1, 0, (x + 1) / 2, (-z - 1) / 3};
    memcpy(vertex.varyings, varyings, sizeof varyings);
    return vertex;
}

/* The floor's corners through the camera at the origin looking down -z
 * (90 degree field of view): near left, near right, far right, far left,
 * counter-clockwise seen from above, a front face for the camera above. */
static void floor_corners(luz_clip_vertex *a, luz_clip_vertex *b, luz_clip_vertex *c,
                          luz_clip_vertex *d)
{
    luz_mat4 view = luz_mat4_look_at((luz_vec3){0, 0, 0}, (luz_vec3){0, 0, -1},
                                     (luz_vec3){0, 1, 0});
    luz_mat4 projection = luz_mat4_perspective(luz_radians(90.0f), 1.0f, 0.1f, 100.0f);
    luz_mat4 view_projection = luz_mat4_multiply(projection, view);
    *a = floor_vertex(view_projection, -1, -1);
    *b = floor_vertex(view_projection, 1, -1);
    *c = floor_vertex(view_projection, 1, -4);
    *d = floor_vertex(view_projection, -1, -4);
}

/* Sets up the two triangles of the floor, rasterises them (ids 1 and 2)
 * and interpolates the fragment at the test pixel from the triangle that
 * covers it. */
static int setup_floor(void **state)
{
    floor_fixture *fixture = calloc(1, sizeof *fixture);
    luz_error error;
    fixture->framebuffer = luz_framebuffer_create(SIZE, SIZE, &error);
    if (!fixture->framebuffer) return -1;

    luz_clip_vertex a, b, c, d;
    floor_corners(&a, &b, &c, &d);
    const luz_interpolation perspective = LUZ_INTERPOLATION_PERSPECTIVE;
    if (luz_setup_triangle(&a, &b, &c, SIZE, SIZE, 0, perspective, &fixture->triangles[0]) !=
            LUZ_SETUP_VISIBLE ||
        luz_setup_triangle(&a, &c, &d, SIZE, SIZE, 0, perspective, &fixture->triangles[1]) !=
            LUZ_SETUP_VISIBLE)
        return -1;
    for (int k = 0; k < 2; k++)
        luz_raster_triangle(&fixture->triangles[k], (uint32_t)k + 1, fixture->framebuffer, 0,
                            SIZE);
    *state = fixture;
    return 0;
}

static int teardown_floor(void **state)
{
    floor_fixture *fixture = *state;
    luz_framebuffer_destroy(fixture->framebuffer);
    free(fixture);
    return 0;
}

static const luz_fragment *fragment_at(floor_fixture *fixture, int x, int y)
{
    uint32_t id = fixture->framebuffer->visibility[y * SIZE + x];
    assert_true(id == 1 || id == 2);
    luz_fragment_interpolate(&fixture->triangles[id - 1], x, y, &fixture->fragment);
    return &fixture->fragment;
}

/* The hand-computed u and v of the floor at the centre of pixel (x, y),
 * from the ray-plane intersection above. */
static double floor_u(int x, int y)
{
    double x_ndc = 2.0 * (x + 0.5) / SIZE - 1.0, y_ndc = 1.0 - 2.0 * (y + 0.5) / SIZE;
    return (-x_ndc / y_ndc + 1.0) / 2.0;
}

static double floor_v(int y)
{
    double y_ndc = 1.0 - 2.0 * (y + 0.5) / SIZE;
    return (-1.0 / y_ndc - 1.0) / 3.0;
}

/* u = 0.84, v = 0.52, world position (0.68, -1, -2.56), normal +y: the
 * perspective-correct values. The centre of (40, 44) lies in the triangle
 * (near left, near right, far right), id 1 (see the intro). */
static void test_perspective_correct_varyings(void **state)
{
    floor_fixture *fixture = *state;
    assert_int_equal(fixture->framebuffer->visibility[PIXEL_Y * SIZE + PIXEL_X], 1);
    const luz_fragment *fragment = fragment_at(fixture, PIXEL_X, PIXEL_Y);
    assert_near(fragment->uv.x, 0.84, 1e-5);
    assert_near(fragment->uv.y, 0.52, 1e-5);
    assert_near(fragment->position.x, 0.68, 1e-5);
    assert_near(fragment->position.y, -1.0, 1e-5);
    assert_near(fragment->position.z, -2.56, 1e-5);
    assert_near(fragment->normal.x, 0.0, 1e-6);
    assert_near(fragment->normal.y, 1.0, 1e-6);
    assert_near(fragment->normal.z, 0.0, 1e-6);
}

/* Screen-linear (affine) interpolation gives other values here, so the
 * test above tells the two apart. In window coordinates the triangle is
 * A (0, 64), B (64, 64), C (40, 40), area 768; the pixel centre P (40.5,
 * 44.5) has barycentric weights area(PBC) / 768 = 48/768 = 0.0625 for A,
 * area(APC) / 768 = 96/768 = 0.125 for B and area(ABP) / 768 = 624/768 =
 * 0.8125 for C. With u = 0, 1, 1 and v = 0, 0, 1 at A, B, C, affine
 * interpolation gives u = 0.125 + 0.8125 = 0.9375 and v = 0.8125, against
 * the perspective-correct 0.84 and 0.52. Setting the triangle up with
 * LUZ_INTERPOLATION_AFFINE must give exactly those. */
static void test_affine_interpolation_is_screen_linear(void **state)
{
    floor_fixture *fixture = *state;
    luz_clip_vertex a, b, c, d;
    floor_corners(&a, &b, &c, &d);
    luz_triangle affine;
    assert_int_equal(luz_setup_triangle(&a, &b, &c, SIZE, SIZE, 0, LUZ_INTERPOLATION_AFFINE,
                                        &affine),
                     LUZ_SETUP_VISIBLE);
    luz_fragment_interpolate(&affine, PIXEL_X, PIXEL_Y, &fixture->fragment);
    assert_near(fixture->fragment.uv.x, 0.9375, 1e-5);
    assert_near(fixture->fragment.uv.y, 0.8125, 1e-5);
}

/* Every pixel of a row and a column through the test pixel matches the
 * ray-plane intersection, in both triangles. Row 44 of the floor runs from
 * the left side, x = 64 - 44.5 = 19.5, to the right side, x = 44.5 (the
 * diagonal between the triangles crosses it at 32.5); column 40 from the
 * right side, y = 40.5, to the bottom of the image. */
static void test_varyings_along_a_row_and_a_column(void **state)
{
    floor_fixture *fixture = *state;
    for (int x = 20; x <= 43; x++) {
        const luz_fragment *fragment = fragment_at(fixture, x, PIXEL_Y);
        assert_near(fragment->uv.x, floor_u(x, PIXEL_Y), 1e-5);
        assert_near(fragment->uv.y, floor_v(PIXEL_Y), 1e-5);
    }
    for (int y = 42; y <= 60; y++) {
        const luz_fragment *fragment = fragment_at(fixture, PIXEL_X, y);
        assert_near(fragment->uv.x, floor_u(PIXEL_X, y), 1e-5);
        assert_near(fragment->uv.y, floor_v(y), 1e-5);
    }
}

/* The analytic derivatives at the test pixel, by hand: with
 * X = -x_ndc / y_ndc, dx_ndc/dx = 2/64 and dy_ndc/dy = -2/64,
 *   du/dx = (1/2)(-1 / y_ndc)(1/32) = (64/25) / 64 = 0.04 (u is linear
 *           along a row of the floor: constant depth),
 *   dv/dx = 0,
 *   du/dy = (1/2)(x_ndc / y_ndc^2)(-1/32) = -(17 * 64 / 625) / 64 = -0.0272,
 *   dv/dy = (1/3)(1 / y_ndc^2)(-1/32) = -(4096 / 625) / 96 = -0.068266667.
 * Finite differences of the hand-computed u and v between neighbouring
 * pixels agree: (u(41) - u(39)) / 2 = (0.88 - 0.80) / 2 = 0.04 exactly, and
 * (v(45) - v(43)) / 2 = (37/81 - 41/69) / 2 = -0.068706, within 1 % of the
 * derivative (v is not linear down a column). */
static void test_texture_coordinate_derivatives(void **state)
{
    floor_fixture *fixture = *state;
    const luz_fragment *fragment = fragment_at(fixture, PIXEL_X, PIXEL_Y);
    assert_near(fragment->du_dx, 0.04, 1e-5);
    assert_near(fragment->dv_dx, 0.0, 1e-5);
    assert_near(fragment->du_dy, -0.0272, 1e-5);
    assert_near(fragment->dv_dy, -0.068266667, 1e-5);

    double du_dx = (floor_u(PIXEL_X + 1, PIXEL_Y) - floor_u(PIXEL_X - 1, PIXEL_Y)) / 2;
    double dv_dy = (floor_v(PIXEL_Y + 1) - floor_v(PIXEL_Y - 1)) / 2;
    assert_near(fragment->du_dx, du_dx, 1e-5);
    assert_near(fragment->dv_dy, dv_dy, 0.01 * fabs(dv_dy));
}

/* Depth, unlike the varyings, is affine on the screen and equals
 * (z_ndc + 1) / 2 with z_ndc = (f + n)/(f - n) + 2 f n / ((f - n) z_eye):
 * at z_eye = -2.56, 100.1/99.9 - 20/(99.9 * 2.56) = 0.92379880, depth
 * 0.96189940. The depth buffer holds the same value. */
static void test_depth_at_the_pixel(void **state)
{
    floor_fixture *fixture = *state;
    const luz_fragment *fragment = fragment_at(fixture, PIXEL_X, PIXEL_Y);
    assert_near(fragment->depth, 0.96189940, 1e-5);
    assert_near(fixture->framebuffer->depth[PIXEL_Y * SIZE + PIXEL_X], 0.96189940, 1e-5);
}

/* THE PLANES COME FROM THE EXACT POSITIONS. Setup snaps window positions
 * to 1/256 pixel for coverage only (setup.c, step 5); the planes are
 * solved from the unsnapped positions, as OpenGL's interpolation formula
 * (OpenGL 4.6, equations 14.9 and 14.10) takes them. A triangle whose
 * vertices sit between grid points, 0.3 to 0.4 of a step off each, tells
 * the two apart: solved from the snapped positions, every varying would
 * be read as if the vertices had moved by up to 1/640 pixel.
 *
 * Window positions (x, y) and w at the three vertices; clip x = x_ndc w
 * with x_ndc = 2 x / 64 - 1, y_ndc = 1 - 2 y / 64 (SCENE.md's viewport
 * read backwards). It is a front face: (15)(16) - (3)(3) > 0, the doubled
 * area setup culls on. */
#define STEP (1.0 / 256.0)
static const double off_grid_window[3][2] = {
    {10.0 + 0.4 * STEP, 12.0 + 0.3 * STEP},
    {13.0 - 0.3 * STEP, 27.0 + 0.4 * STEP},
    {26.0 + 0.4 * STEP, 15.0 - 0.4 * STEP},
};
static const float off_grid_w[3] = {1.0f, 2.0f, 0.5f};
static const float off_grid_z_ndc[3] = {0.1f, 0.5f, -0.3f};
static const float off_grid_u[3] = {0.0f, 3.0f, 1.0f};
static const float off_grid_v[3] = {2.0f, 0.0f, 4.0f};

/* Doubled signed area of (a, b, c) in window coordinates. */
static double doubled_area(const double a[2], const double b[2], const double c[2])
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
}

typedef struct interpolated {
    double u, v, depth;
    bool inside;
} interpolated;

/* The values at window point p of the triangle with window positions
 * window[k], in double: barycentric weights from areas, u and v
 * perspective-correct (the weights over w, renormalised: equation 14.9),
 * depth affine on the screen (equation 14.10). */
static interpolated interpolate_by_hand(const double window[3][2], const double w[3],
                                        const double depth[3], double px, double py)
{
    const double p[2] = {px, py};
    const double area = doubled_area(window[0], window[1], window[2]);
    const double weight[3] = {doubled_area(p, window[1], window[2]) / area,
                              doubled_area(window[0], p, window[2]) / area,
                              doubled_area(window[0], window[1], p) / area};
    double over_w = 0, u = 0, v = 0;
    interpolated result = {0, 0, 0, true};
    for (int k = 0; k < 3; k++) {
        over_w += weight[k] / w[k];
        u += weight[k] * off_grid_u[k] / w[k];
        v += weight[k] * off_grid_v[k] / w[k];
        result.depth += weight[k] * depth[k];
        if (weight[k] <= 0) result.inside = false;
    }
    result.u = u / over_w;
    result.v = v / over_w;
    return result;
}

/* Float planes and a float division are good to about 1e-6 here (the
 * values are below 4); snapped planes would be off by up to about 1e-3
 * (u and v change by up to 0.75 a pixel, times 1/640 pixel), so the
 * tolerance sits between the two, and the test checks that the second is
 * really there for this triangle. */
#define EXACT_TOLERANCE 1e-5

static void test_planes_use_unsnapped_positions(void **state)
{
    (void)state;
    luz_clip_vertex vertex[3];
    double window[3][2], snapped[3][2], w[3], depth[3];
    for (int k = 0; k < 3; k++) {
        double x_ndc = 2.0 * off_grid_window[k][0] / SIZE - 1.0;
        double y_ndc = 1.0 - 2.0 * off_grid_window[k][1] / SIZE;
        memset(&vertex[k], 0, sizeof vertex[k]);
        vertex[k].position = (luz_vec4){(float)(x_ndc * off_grid_w[k]),
                                        (float)(y_ndc * off_grid_w[k]),
                                        off_grid_z_ndc[k] * off_grid_w[k], off_grid_w[k]};
        vertex[k].varyings[LUZ_VARYING_NORMAL + 2] = 1.0f;
        vertex[k].varyings[LUZ_VARYING_UV + 0] = off_grid_u[k];
        vertex[k].varyings[LUZ_VARYING_UV + 1] = off_grid_v[k];
        /* What the clip vertex really holds, through the viewport: the
         * float rounding of x_ndc w moves it by under 1e-5 of a step. */
        const luz_vec4 clip = vertex[k].position;
        w[k] = clip.w;
        window[k][0] = ((double)clip.x / clip.w + 1.0) / 2.0 * SIZE;
        window[k][1] = (1.0 - (double)clip.y / clip.w) / 2.0 * SIZE;
        depth[k] = ((double)clip.z / clip.w + 1.0) / 2.0;
        for (int axis = 0; axis < 2; axis++) {
            snapped[k][axis] = nearbyint(window[k][axis] / STEP) * STEP;
            assert_true(fabs(window[k][axis] - snapped[k][axis]) > 0.25 * STEP);
        }
    }
    luz_triangle triangle;
    assert_int_equal(luz_setup_triangle(&vertex[0], &vertex[1], &vertex[2], SIZE, SIZE, 0,
                                        LUZ_INTERPOLATION_PERSPECTIVE, &triangle),
                     LUZ_SETUP_VISIBLE);

    int inside = 0;
    double snapping_effect = 0;
    for (int y = 0; y < SIZE; y++) {
        for (int x = 0; x < SIZE; x++) {
            interpolated exact = interpolate_by_hand(window, w, depth, x + 0.5, y + 0.5);
            if (!exact.inside) continue;
            inside++;
            interpolated moved = interpolate_by_hand(snapped, w, depth, x + 0.5, y + 0.5);
            snapping_effect = fmax(snapping_effect, fabs(moved.u - exact.u));
            snapping_effect = fmax(snapping_effect, fabs(moved.v - exact.v));
            luz_fragment fragment;
            luz_fragment_interpolate(&triangle, x, y, &fragment);
            assert_near(fragment.uv.x, exact.u, EXACT_TOLERANCE);
            assert_near(fragment.uv.y, exact.v, EXACT_TOLERANCE);
            assert_near(fragment.depth, exact.depth, EXACT_TOLERANCE);
        }
    }
    assert_true(inside > 50);
    /* The test can tell: planes through the snapped positions would be off
     * by far more than the tolerance somewhere inside. */
    assert_true(snapping_effect > 20 * EXACT_TOLERANCE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_perspective_correct_varyings),
        cmocka_unit_test(test_affine_interpolation_is_screen_linear),
        cmocka_unit_test(test_varyings_along_a_row_and_a_column),
        cmocka_unit_test(test_texture_coordinate_derivatives),
        cmocka_unit_test(test_depth_at_the_pixel),
        cmocka_unit_test(test_planes_use_unsnapped_positions),
    };
    return cmocka_run_group_tests(tests, setup_floor, teardown_floor);
}
