/*
 * test_math.c: luz/vecmath.h and luz_camera_front against matrices and
 * vectors worked out by hand from their textbook definitions
 * (gluPerspective, gluLookAt, Rodrigues' rotation, gl-matrix's order of
 * composition) and from SCENE.md's camera formula.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_support.h"

#include "lab/scene.h"
#include "luz/vecmath.h"

/* Single-precision results of a handful of operations on values near 1. */
#define TOLERANCE 1e-6

#define assert_vec3_near(got, expected_x, expected_y, expected_z) \
    assert_vec3_near_at((got), (expected_x), (expected_y), (expected_z), #got, __FILE__, \
                        __LINE__)

static void assert_vec3_near_at(luz_vec3 got, double x, double y, double z,
                                const char *expression, const char *file, int line)
{
    assert_near_at(got.x, x, TOLERANCE, expression, file, line);
    assert_near_at(got.y, y, TOLERANCE, expression, file, line);
    assert_near_at(got.z, z, TOLERANCE, expression, file, line);
}

/* Element (row, column) of a column-major matrix. */
static float element(luz_mat4 m, int row, int column)
{
    return m.m[column * 4 + row];
}

static luz_vec3 transform_point(luz_mat4 m, float x, float y, float z)
{
    return luz_mat4_transform_point(m, (luz_vec3){x, y, z});
}

/* gluPerspective with fovy 90, aspect 2, near 1, far 3: f = cot(45) = 1, so
 * the matrix is [f/aspect 0 0 0; 0 f 0 0; 0 0 (far+near)/(near-far)
 * 2 far near/(near-far); 0 0 -1 0] = [0.5 0 0 0; 0 1 0 0; 0 0 -2 -3;
 * 0 0 -1 0]. Every one of the 16 elements is checked. */
static void test_perspective_matches_glu_perspective(void **state)
{
    (void)state;
    luz_mat4 p = luz_mat4_perspective(luz_radians(90.0f), 2.0f, 1.0f, 3.0f);
    const float expected[4][4] = {
        {0.5f, 0.0f, 0.0f, 0.0f},
        {0.0f, 1.0f, 0.0f, 0.0f},
        {0.0f, 0.0f, -2.0f, -3.0f},
        {0.0f, 0.0f, -1.0f, 0.0f},
    };
    for (int row = 0; row < 4; row++)
        for (int column = 0; column < 4; column++)
            assert_near(element(p, row, column), expected[row][column], TOLERANCE);
}

/* The same matrix sends the near plane (z_eye = -1) to z_ndc = -1 and the
 * far plane (z_eye = -3) to +1, with w_clip = -z_eye: clip z at the near
 * plane is -2 * -1 - 3 = -1 with w 1; at the far plane -2 * -3 - 3 = 3 with
 * w 3. A point on the right edge of the near plane (x = aspect * near *
 * tan 45 = 2) lands on x_ndc = 1. */
static void test_perspective_maps_frustum_to_clip_cube(void **state)
{
    (void)state;
    luz_mat4 p = luz_mat4_perspective(luz_radians(90.0f), 2.0f, 1.0f, 3.0f);
    luz_vec4 near_point = luz_mat4_transform(p, (luz_vec4){2.0f, 0.0f, -1.0f, 1.0f});
    assert_near(near_point.x / near_point.w, 1.0, TOLERANCE);
    assert_near(near_point.z / near_point.w, -1.0, TOLERANCE);
    assert_near(near_point.w, 1.0, TOLERANCE);
    luz_vec4 far_point = luz_mat4_transform(p, (luz_vec4){0.0f, 3.0f, -3.0f, 1.0f});
    assert_near(far_point.y / far_point.w, 1.0, TOLERANCE);
    assert_near(far_point.z / far_point.w, 1.0, TOLERANCE);
    assert_near(far_point.w, 3.0, TOLERANCE);
}

/* Looking from (0, 0, 3) at the origin with up +y, the camera's axes are the
 * world's, so the view matrix is a translation by -3 in z: the identity
 * except element (2, 3) = -3. */
static void test_look_at_down_negative_z_is_a_translation(void **state)
{
    (void)state;
    luz_mat4 view = luz_mat4_look_at((luz_vec3){0, 0, 3}, (luz_vec3){0, 0, 0},
                                     (luz_vec3){0, 1, 0});
    for (int row = 0; row < 4; row++) {
        for (int column = 0; column < 4; column++) {
            float expected = row == column ? 1.0f : 0.0f;
            if (row == 2 && column == 3) expected = -3.0f;
            assert_near(element(view, row, column), expected, TOLERANCE);
        }
    }
}

/* From (2, 0, 0) looking at the origin with up +y: back = eye - centre =
 * +x, right = up x back = (0,1,0) x (1,0,0) = (0, 0, -1), up = back x right
 * = (0, 1, 0). So the origin is 2 units ahead (view (0, 0, -2)), world
 * (0, 0, -1) is 1 unit to the right (view (1, 0, -2)), world (0, 1, 0) is
 * 1 unit up (view (0, 1, -2)) and the eye is the view origin. */
static void test_look_at_from_positive_x(void **state)
{
    (void)state;
    luz_mat4 view = luz_mat4_look_at((luz_vec3){2, 0, 0}, (luz_vec3){0, 0, 0},
                                     (luz_vec3){0, 1, 0});
    assert_vec3_near(transform_point(view, 0, 0, 0), 0, 0, -2);
    assert_vec3_near(transform_point(view, 0, 0, -1), 1, 0, -2);
    assert_vec3_near(transform_point(view, 0, 1, 0), 0, 1, -2);
    assert_vec3_near(transform_point(view, 2, 0, 0), 0, 0, 0);
}

/* A right-handed quarter turn about +z takes x to y and y to -x; z stays.
 * An axis of any length is normalised first, so (0, 0, 5) does the same. */
static void test_rotate_quarter_turn_about_z(void **state)
{
    (void)state;
    luz_mat4 r = luz_mat4_rotate(luz_mat4_identity(), luz_radians(90.0f), (luz_vec3){0, 0, 5});
    assert_vec3_near(transform_point(r, 1, 0, 0), 0, 1, 0);
    assert_vec3_near(transform_point(r, 0, 1, 0), -1, 0, 0);
    assert_vec3_near(transform_point(r, 0, 0, 1), 0, 0, 1);
}

/* 120 degrees about (1, 1, 1) permutes the axes x -> y -> z -> x.
 * Rodrigues with a = (1,1,1)/sqrt 3, c = -1/2, s = sqrt(3)/2:
 * R x = c x + (1 - c)(a.x) a + s (a cross x)
 *     = (-1/2, 0, 0) + (1/2, 1/2, 1/2) + (0, 1/2, -1/2) = (0, 1, 0). */
static void test_rotate_120_degrees_about_diagonal_permutes_axes(void **state)
{
    (void)state;
    luz_mat4 r = luz_mat4_rotate(luz_mat4_identity(), luz_radians(120.0f), (luz_vec3){1, 1, 1});
    assert_vec3_near(transform_point(r, 1, 0, 0), 0, 1, 0);
    assert_vec3_near(transform_point(r, 0, 1, 0), 0, 0, 1);
    assert_vec3_near(transform_point(r, 0, 0, 1), 1, 0, 0);
}

/* About the scene's axis (1, 0.5, 1) (length 1.5, unit a = (2/3, 1/3, 2/3)):
 * the axis itself is fixed, and v = (1, 0, -1), perpendicular to it, turns
 * by the angle in the right-handed sense: for 60 degrees,
 * dot(v, R v) = |v|^2 cos 60 = 1 and v x R v = |v|^2 sin 60 a
 * = sqrt(3) (2/3, 1/3, 2/3). */
static void test_rotate_about_scene_axis(void **state)
{
    (void)state;
    luz_mat4 r = luz_mat4_rotate(luz_mat4_identity(), luz_radians(60.0f),
                                 (luz_vec3){1.0f, 0.5f, 1.0f});
    assert_vec3_near(transform_point(r, 1.0f, 0.5f, 1.0f), 1.0, 0.5, 1.0);
    luz_vec3 v = {1, 0, -1};
    luz_vec3 turned = luz_mat4_transform_point(r, v);
    assert_near(luz_vec3_dot(v, turned), 1.0, TOLERANCE);
    const double root3 = sqrt(3.0);
    assert_vec3_near(luz_vec3_cross(v, turned), root3 * 2 / 3, root3 / 3, root3 * 2 / 3);
}

/* translate(M, t) is M * T and rotate(M, ...) is M * R, as in gl-matrix:
 * the last call acts on the point first. With R a quarter turn about z and
 * t = (1, 0, 0):
 *   R * T takes the origin to R (1, 0, 0) = (0, 1, 0), and (1, 0, 0) to
 *         R (2, 0, 0) = (0, 2, 0);
 *   T * R takes the origin to (1, 0, 0), and (1, 0, 0) to (0, 1, 0) + t
 *         = (1, 1, 0).
 * luz_mat4_multiply(T, R) must equal the second, T * R. */
static void test_translate_and_rotate_compose_like_gl_matrix(void **state)
{
    (void)state;
    const luz_vec3 z_axis = {0, 0, 1}, offset = {1, 0, 0};
    const float quarter = luz_radians(90.0f);
    luz_mat4 rotate_then_translate =
        luz_mat4_translate(luz_mat4_rotate(luz_mat4_identity(), quarter, z_axis), offset);
    assert_vec3_near(transform_point(rotate_then_translate, 0, 0, 0), 0, 1, 0);
    assert_vec3_near(transform_point(rotate_then_translate, 1, 0, 0), 0, 2, 0);

    luz_mat4 translate_then_rotate =
        luz_mat4_rotate(luz_mat4_translate(luz_mat4_identity(), offset), quarter, z_axis);
    assert_vec3_near(transform_point(translate_then_rotate, 0, 0, 0), 1, 0, 0);
    assert_vec3_near(transform_point(translate_then_rotate, 1, 0, 0), 1, 1, 0);

    luz_mat4 product = luz_mat4_multiply(luz_mat4_translate(luz_mat4_identity(), offset),
                                         luz_mat4_rotate(luz_mat4_identity(), quarter, z_axis));
    assert_vec3_near(transform_point(product, 1, 0, 0), 1, 1, 0);
}

/* scale(M, s) is M * S: translate by (1, 2, 3) then scale by 2 takes
 * (1, 1, 1) to 2 (1, 1, 1) + (1, 2, 3) = (3, 4, 5). */
static void test_scale_composes_after_translate(void **state)
{
    (void)state;
    luz_mat4 m = luz_mat4_scale(luz_mat4_translate(luz_mat4_identity(), (luz_vec3){1, 2, 3}),
                                (luz_vec3){2, 2, 2});
    assert_vec3_near(transform_point(m, 1, 1, 1), 3, 4, 5);
}

/* The normal matrix of a scale by (2, 1, 1) is its inverse transpose,
 * diag(1/2, 1, 1). It keeps normals perpendicular: the surface x + y = 0
 * has normal (1, 1, 0) and tangent (1, -1, 0); after the scale the tangent
 * is (2, -1, 0) and the normal (0.5, 1, 0), and 2 * 0.5 - 1 * 1 = 0. (The
 * upper 3x3 itself would give (2, 1, 0), with dot product 3.) */
static void test_normal_matrix_of_non_uniform_scale(void **state)
{
    (void)state;
    luz_mat4 scale = luz_mat4_scale(luz_mat4_identity(), (luz_vec3){2, 1, 1});
    luz_mat3 normal_matrix = luz_mat3_normal_matrix(scale);
    const float expected[9] = {0.5f, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int i = 0; i < 9; i++) assert_near(normal_matrix.m[i], expected[i], TOLERANCE);

    luz_vec3 tangent = luz_mat4_transform_point(scale, (luz_vec3){1, -1, 0});
    luz_vec3 normal = luz_mat3_transform(normal_matrix, (luz_vec3){1, 1, 0});
    assert_vec3_near(normal, 0.5, 1, 0);
    assert_near(luz_vec3_dot(tangent, normal), 0.0, TOLERANCE);
}

/* For a rotation (plus a translation, which the 3x3 ignores) the inverse
 * transpose is the rotation itself: 120 degrees about (1, 1, 1) still takes
 * the normal +x to +y. */
static void test_normal_matrix_of_rigid_motion_is_its_rotation(void **state)
{
    (void)state;
    luz_mat4 m = luz_mat4_rotate(luz_mat4_translate(luz_mat4_identity(), (luz_vec3){4, 5, 6}),
                                 luz_radians(120.0f), (luz_vec3){1, 1, 1});
    luz_mat3 normal_matrix = luz_mat3_normal_matrix(m);
    assert_vec3_near(luz_mat3_transform(normal_matrix, (luz_vec3){1, 0, 0}), 0, 1, 0);
    assert_vec3_near(luz_mat3_transform(normal_matrix, (luz_vec3){0, 1, 0}), 0, 0, 1);
}

/* SCENE.md: front = normalize(cos(yaw) cos(pitch), sin(pitch),
 * sin(yaw) cos(pitch)). yaw -90, pitch 0: (0, 0, -1); yaw 0: (1, 0, 0);
 * yaw -90, pitch 89: (0, sin 89, -cos 89) = (0, 0.99984770, -0.017452406). */
static void test_camera_front(void **state)
{
    (void)state;
    luz_camera camera = {{0, 0, 3}, -90.0f, 0.0f, 45.0f};
    assert_vec3_near(luz_camera_front(&camera), 0, 0, -1);
    camera.yaw_degrees = 0.0f;
    assert_vec3_near(luz_camera_front(&camera), 1, 0, 0);
    camera.yaw_degrees = -90.0f;
    camera.pitch_degrees = 89.0f;
    assert_vec3_near(luz_camera_front(&camera), 0, 0.99984770, -0.017452406);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_perspective_matches_glu_perspective),
        cmocka_unit_test(test_perspective_maps_frustum_to_clip_cube),
        cmocka_unit_test(test_look_at_down_negative_z_is_a_translation),
        cmocka_unit_test(test_look_at_from_positive_x),
        cmocka_unit_test(test_rotate_quarter_turn_about_z),
        cmocka_unit_test(test_rotate_120_degrees_about_diagonal_permutes_axes),
        cmocka_unit_test(test_rotate_about_scene_axis),
        cmocka_unit_test(test_translate_and_rotate_compose_like_gl_matrix),
        cmocka_unit_test(test_scale_composes_after_translate),
        cmocka_unit_test(test_normal_matrix_of_non_uniform_scale),
        cmocka_unit_test(test_normal_matrix_of_rigid_motion_is_its_rotation),
        cmocka_unit_test(test_camera_front),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
