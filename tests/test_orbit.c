/*
 * test_orbit.c: the viewer's orbit camera (app/orbit.h) without a window.
 *
 * Expected values are worked out by hand: front = (cos yaw cos pitch,
 * sin pitch, sin yaw cos pitch) (SCENE.md), so yaw -90 looks down -z and
 * yaw 0 down +x; the eye of an orbit is target - distance * front; a drag
 * turns 0.25 degree a pixel, a wheel notch multiplies the distance by 0.9;
 * sin 22.5 degrees = sqrt(2 - sqrt 2) / 2 = 0.38268343; the unit cube's
 * sphere has radius sqrt(3) / 2 = 0.8660254.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "app/orbit.h"
#include "lab/scene.h"
#include "test_support.h"

static void assert_vec3_near(luz_vec3 actual, double x, double y, double z, double tolerance)
{
    assert_near(actual.x, x, tolerance);
    assert_near(actual.y, y, tolerance);
    assert_near(actual.z, z, tolerance);
}

static void assert_target(const luz_orbit *orbit, double x, double y, double z)
{
    assert_near(orbit->target[0], x, 1e-12);
    assert_near(orbit->target[1], y, 1e-12);
    assert_near(orbit->target[2], z, 1e-12);
}

static luz_camera camera_at(float yaw, float pitch)
{
    luz_camera camera = luz_scene_defaults().camera;
    camera.yaw_degrees = yaw;
    camera.pitch_degrees = pitch;
    return camera;
}

/* ---- turning round the target ------------------------------------------------------ */

static void test_a_drag_of_ninety_degrees_turns_the_eye_round_the_target(void **state)
{
    (void)state;
    luz_orbit orbit = {{1.0, 2.0, 3.0}, 4.0};
    luz_camera camera = camera_at(-90.0f, 0.0f);
    luz_orbit_place(&orbit, &camera);
    assert_vec3_near(camera.position, 1.0, 2.0, 7.0, 1e-6);   /* (1, 2, 3) - 4 (0, 0, -1) */

    /* 360 pixels right: yaw -90 + 90 = 0, front (1, 0, 0), the eye at
     * (1, 2, 3) - 4 (1, 0, 0) = (-3, 2, 3): a quarter turn round the
     * target, which stays in the middle of the view. */
    luz_orbit_turn(&orbit, &camera, 360.0f, 0.0f);
    assert_near(camera.yaw_degrees, 0.0, 0.0);
    assert_near(camera.pitch_degrees, 0.0, 0.0);
    assert_vec3_near(camera.position, -3.0, 2.0, 3.0, 1e-6);
    assert_target(&orbit, 1.0, 2.0, 3.0);
    luz_vec3 to_target = luz_vec3_normalize(
        luz_vec3_sub((luz_vec3){1.0f, 2.0f, 3.0f}, camera.position));
    luz_vec3 front = luz_camera_front(&camera);
    assert_vec3_near(to_target, front.x, front.y, front.z, 1e-6);
    assert_vec3_near(front, 1.0, 0.0, 0.0, 1e-7);

    /* 180 pixels up: pitch +45, front (cos 45, sin 45, 0): the eye below
     * the target, at (1 - 4 cos 45, 2 - 4 sin 45, 3). */
    luz_orbit_turn(&orbit, &camera, 0.0f, -180.0f);
    assert_near(camera.pitch_degrees, 45.0, 0.0);
    assert_vec3_near(camera.position, -1.8284271, -0.8284271, 3.0, 1e-5);

    /* Back down and 720 pixels left: yaw 0 - 180 = -180, front (-1, 0, 0):
     * the eye on the other side, at (5, 2, 3). */
    luz_orbit_turn(&orbit, &camera, -720.0f, 180.0f);
    assert_near(camera.yaw_degrees, -180.0, 0.0);
    assert_vec3_near(camera.position, 5.0, 2.0, 3.0, 1e-5);
    assert_target(&orbit, 1.0, 2.0, 3.0);
    assert_near(orbit.distance, 4.0, 0.0);
}

static void test_pitch_limits_keep_the_up_vector_defined(void **state)
{
    (void)state;
    const int signs[2] = {1, -1};
    for (int s = 0; s < 2; s++) {
        luz_orbit orbit = {{0.0, 0.0, 0.0}, 4.0};
        luz_camera camera = camera_at(-90.0f, 0.0f);
        /* A drag far past the pole stops at 89 degrees, as flying does. */
        luz_orbit_turn(&orbit, &camera, 0.0f, -1e5f * (float)signs[s]);
        assert_near(camera.pitch_degrees, 89.0 * signs[s], 0.0);
        /* front . up = sin 89 = 0.99984770, so front x up keeps a length
         * of cos 89 = 0.01745241: lookAt's right vector is defined. */
        luz_vec3 front = luz_camera_front(&camera);
        assert_near(front.y, 0.9998477 * signs[s], 1e-6);
        luz_vec3 right = luz_vec3_cross(front, (luz_vec3){0.0f, 1.0f, 0.0f});
        assert_near(sqrt(luz_vec3_dot(right, right)), 0.0174524, 1e-6);
        /* The eye is still 4 from the target, above (or below) it. */
        assert_near(sqrt(luz_vec3_dot(camera.position, camera.position)), 4.0, 1e-5);
        assert_near(camera.position.y, -4.0 * 0.9998477 * signs[s], 1e-5);
        /* and the view matrix the lab builds from it is finite */
        luz_scene scene = luz_scene_defaults();
        scene.camera = camera;
        luz_frame frame = {0};
        luz_scene_set_camera_and_lights(&scene, 16.0f / 9.0f, &frame);
        for (int i = 0; i < 16; i++)
            assert_true(isfinite(frame.view.m[i]));
        /* its first row, the camera's right, is a unit vector */
        const float *m = frame.view.m;
        assert_near(m[0] * m[0] + m[4] * m[4] + m[8] * m[8], 1.0, 1e-5);
    }
}

/* ---- the wheel ------------------------------------------------------------------ */

static void test_dolly_keeps_the_target_and_never_passes_it(void **state)
{
    (void)state;
    luz_orbit orbit = {{0.0, 0.0, 0.0}, 5.0};
    luz_camera camera = camera_at(-90.0f, 0.0f);
    luz_orbit_place(&orbit, &camera);
    assert_vec3_near(camera.position, 0.0, 0.0, 5.0, 1e-6);

    luz_orbit_dolly(&orbit, &camera, 1.0f);   /* one notch closer: 5 x 0.9 */
    assert_near(orbit.distance, 4.5, 1e-12);
    assert_vec3_near(camera.position, 0.0, 0.0, 4.5, 1e-6);
    luz_orbit_dolly(&orbit, &camera, -2.0f);  /* two away: 4.5 / 0.81 */
    assert_near(orbit.distance, 5.5555556, 1e-6);
    assert_vec3_near(camera.position, 0.0, 0.0, 5.5555556, 1e-6);
    assert_target(&orbit, 0.0, 0.0, 0.0);

    /* However far the wheel turns, the eye stops 0.2 short of the target,
     * on the same side, and 50 from it the other way. */
    luz_orbit_dolly(&orbit, &camera, 1000.0f);
    assert_near(orbit.distance, 0.2, 1e-12);
    assert_vec3_near(camera.position, 0.0, 0.0, 0.2, 1e-7);
    luz_orbit_dolly(&orbit, &camera, 1e30f);
    assert_near(orbit.distance, 0.2, 1e-12);
    assert_true(camera.position.z > 0.0f);
    luz_orbit_dolly(&orbit, &camera, -1000.0f);
    assert_near(orbit.distance, 50.0, 1e-12);
    assert_vec3_near(camera.position, 0.0, 0.0, 50.0, 1e-5);
    assert_target(&orbit, 0.0, 0.0, 0.0);
}

/* ---- framing ----------------------------------------------------------------------- */

static void test_fit_distance_is_radius_over_the_sine_of_the_half_angle(void **state)
{
    (void)state;
    /* A wide view: the vertical half-angle 22.5 is the smaller one,
     * 2 / sin 22.5 = 2 / 0.38268343 = 5.2262519. */
    assert_near(luz_orbit_fit_distance(2.0f, 45.0f, 16.0f / 9.0f), 5.2262519, 1e-6);
    /* A tall one (aspect 0.5): the horizontal half-angle a, tan a =
     * 0.5 tan 22.5 = 0.5 (sqrt 2 - 1) = 0.20710678, sin a = 0.20710678 /
     * sqrt(1 + 0.20710678^2) = 0.20280312, 2 / that = 9.8617866. */
    assert_near(luz_orbit_fit_distance(2.0f, 45.0f, 0.5f), 9.8617866, 1e-5);
    /* A square view of 90 degrees: 1 / sin 45 = sqrt 2. */
    assert_near(luz_orbit_fit_distance(1.0f, 90.0f, 1.0f), 1.4142136, 1e-6);
}

/* The signed distance of point p from each side of the view's frustum, its
 * planes read off the rows of projection x view (Gribb and Hartmann):
 * row 4 + row 1 (left), row 4 - row 1 (right), and the same with row 2. */
static void frustum_distances(const luz_frame *frame, luz_vec3 p, double distances[4])
{
    const luz_mat4 m = luz_mat4_multiply(frame->projection, frame->view);
    for (int plane = 0; plane < 4; plane++) {
        const int row = plane / 2;
        const double sign = plane % 2 == 0 ? 1.0 : -1.0;
        double coefficient[4];
        for (int column = 0; column < 4; column++)
            coefficient[column] = (double)m.m[column * 4 + 3] + sign * m.m[column * 4 + row];
        const double length = sqrt(coefficient[0] * coefficient[0] +
                                   coefficient[1] * coefficient[1] +
                                   coefficient[2] * coefficient[2]);
        distances[plane] = (coefficient[0] * p.x + coefficient[1] * p.y +
                            coefficient[2] * p.z + coefficient[3]) / length;
    }
}

static void test_framing_fits_the_sphere_in_the_view(void **state)
{
    (void)state;
    const float aspects[3] = {2.0f, 1.0f, 0.5f};
    const float yaws[3] = {-90.0f, 30.0f, 150.0f};
    const float pitches[3] = {0.0f, -40.0f, 60.0f};
    const luz_sphere sphere = {{1.0f, -2.0f, 3.0f}, 1.5f};
    for (int a = 0; a < 3; a++) {
        for (int k = 0; k < 3; k++) {
            luz_orbit orbit = {{0.0, 0.0, 0.0}, 3.0};
            luz_camera camera = camera_at(yaws[k], pitches[k]);
            luz_orbit_frame(&orbit, &camera, sphere, aspects[a]);
            assert_target(&orbit, 1.0, -2.0, 3.0);
            /* The direction is kept, the target is in the middle. */
            assert_near(camera.yaw_degrees, yaws[k], 0.0);
            assert_near(camera.pitch_degrees, pitches[k], 0.0);
            luz_scene scene = luz_scene_defaults();
            scene.camera = camera;
            luz_frame frame = {0};
            luz_scene_set_camera_and_lights(&scene, aspects[a], &frame);
            /* Every side of the view is at least the radius from the
             * centre (the sphere is inside), and the nearest exactly it
             * (the sphere touches: no closer camera would fit it). */
            double distances[4];
            frustum_distances(&frame, sphere.centre, distances);
            double nearest = INFINITY;
            for (int plane = 0; plane < 4; plane++) {
                assert_true(distances[plane] >= 1.5 - 1e-4);
                nearest = fmin(nearest, distances[plane]);
            }
            assert_near(nearest, 1.5, 1e-4);
            /* Tall views touch the left and right sides, wide ones the
             * top and bottom, the square one all four. */
            const int touching = aspects[a] < 1.0f ? 0 : 2;
            assert_near(distances[touching], 1.5, 1e-4);
            assert_near(distances[touching + 1], 1.5, 1e-4);
        }
    }
}

static void test_frame_two_cubes(void **state)
{
    (void)state;
    /* Cubes at x = -5 and 5: the sphere round them is centred on the
     * origin with radius 5 + sqrt(3) / 2 = 5.8660254; at 45 degrees in a
     * wide view it fits at 5.8660254 / sin 22.5 = 15.328663. */
    luz_object cubes[2] = {{.position = {-5.0f, 0.0f, 0.0f}, .texture = LUZ_TEXTURE_BY_INDEX},
                           {.position = {5.0f, 0.0f, 0.0f}, .texture = LUZ_TEXTURE_BY_INDEX}};
    luz_scene scene = luz_scene_defaults();
    scene.objects = cubes;
    scene.object_count = 2;
    luz_sphere sphere = luz_scene_bounding_sphere(&scene);
    assert_vec3_near(sphere.centre, 0.0, 0.0, 0.0, 0.0);
    assert_near(sphere.radius, 5.8660254, 1e-6);
    luz_orbit orbit;
    luz_orbit_frame(&orbit, &scene.camera, sphere, 2.0f);
    assert_near(orbit.distance, 15.328663, 1e-5);
    assert_vec3_near(scene.camera.position, 0.0, 0.0, 15.328663, 1e-5);
}

/* ---- the scene's sphere --------------------------------------------------------------- */

static void test_bounding_sphere_of_the_lab(void **state)
{
    (void)state;
    /* SCENE.md's ten cubes: x from -3.8 to 2.4, y from -2.2 to 5, z from
     * -15 to 0, so the box round their spheres is centred on (-0.7, 1.4,
     * -7.5); the farthest cube from there is (2, 5, -15), at
     * sqrt(2.7^2 + 3.6^2 + 7.5^2) = sqrt(76.5) = 8.7464278, plus 0.8660254. */
    luz_scene scene = luz_scene_defaults();
    luz_sphere sphere = luz_scene_bounding_sphere(&scene);
    assert_vec3_near(sphere.centre, -0.7, 1.4, -7.5, 1e-6);
    assert_near(sphere.radius, 9.6124532, 1e-5);
    /* No objects at all: the unit sphere at the origin. */
    luz_object none[1];
    scene.objects = none;
    scene.object_count = 0;
    sphere = luz_scene_bounding_sphere(&scene);
    assert_vec3_near(sphere.centre, 0.0, 0.0, 0.0, 0.0);
    assert_near(sphere.radius, 1.0, 0.0);
}

static void test_bounding_sphere_with_a_model(void **state)
{
    (void)state;
    /* A model of box [0, 4] x [0, 2] x [0, 1]: normalised by its longest
     * side 4, half-sides (1, 0.5, 0.25); at scale 2 its sphere has radius
     * 2 sqrt(1 + 0.25 + 0.0625) = 2.2912878, round (0, 0, 10). With a cube
     * at the origin the box runs along z from -0.8660254 to 12.2912878:
     * centre z = 5.7126312, radius (12.2912878 + 0.8660254) / 2 = 6.5786566. */
    luz_lab_model model = {.name = "box", .bounds = {{0.0f, 0.0f, 0.0f}, {4.0f, 2.0f, 1.0f}}};
    luz_object objects[2] = {
        {.position = {0.0f, 0.0f, 0.0f}, .texture = LUZ_TEXTURE_BY_INDEX},
        {.position = {0.0f, 0.0f, 10.0f}, .texture = LUZ_TEXTURE_BY_INDEX, .model = &model,
         .scale = 2.0f},
    };
    luz_scene scene = luz_scene_defaults();
    scene.objects = objects;
    scene.object_count = 2;
    luz_sphere sphere = luz_scene_bounding_sphere(&scene);
    assert_vec3_near(sphere.centre, 0.0, 0.0, 5.7126312, 1e-5);
    assert_near(sphere.radius, 6.5786566, 1e-5);
    /* The model alone, scale 0 meaning 1: radius 1.1456439 round it. */
    objects[1].scale = 0.0f;
    scene.objects = &objects[1];
    scene.object_count = 1;
    sphere = luz_scene_bounding_sphere(&scene);
    assert_vec3_near(sphere.centre, 0.0, 0.0, 10.0, 1e-6);
    assert_near(sphere.radius, 1.1456439, 1e-6);
}

/* ---- flying and orbiting ----------------------------------------------------------------- */

/* The orbit found for a camera puts the eye back where it was, to the
 * bit, so that switching to the orbit camera changes no pixel. */
static void test_from_camera_and_back_is_exact(void **state)
{
    (void)state;
    const luz_camera cameras[] = {
        {{0.0f, 0.0f, 3.0f}, -90.0f, 0.0f, 45.0f},
        {{0.1f, -3.7f, 12.3f}, 33.3f, -71.2f, 45.0f},
        {{9999.0f, -9999.5f, 5000.25f}, 170.0f, 88.9f, 60.0f},
        {{-0.001f, 1e-7f, 2.5f}, -179.9f, 0.3f, 45.0f},
    };
    const luz_vec3 centres[] = {{0.0f, 0.0f, 0.0f}, {-0.7f, 1.4f, -7.5f}, {100.0f, 20.0f, -3.0f},
                                {0.0f, 0.0f, 1e4f}};
    for (size_t c = 0; c < sizeof cameras / sizeof cameras[0]; c++) {
        for (size_t k = 0; k < sizeof centres / sizeof centres[0]; k++) {
            luz_camera camera = cameras[c];
            luz_orbit orbit = luz_orbit_from_camera(&camera, centres[k]);
            assert_true(orbit.distance >= LUZ_ORBIT_MIN_DISTANCE &&
                        orbit.distance <= LUZ_ORBIT_MAX_DISTANCE);
            luz_orbit_place(&orbit, &camera);
            if (memcmp(&camera, &cameras[c], sizeof camera) != 0)
                fail_msg("camera %zu, centre %zu: (%.9g, %.9g, %.9g) came back as (%.9g, %.9g, "
                         "%.9g)",
                         c, k, (double)cameras[c].position.x, (double)cameras[c].position.y,
                         (double)cameras[c].position.z, (double)camera.position.x,
                         (double)camera.position.y, (double)camera.position.z);
        }
    }
    /* and 100000 cameras anywhere in [-100, 100)^3, looking anywhere */
    uint32_t random = 27;
    for (int i = 0; i < 100000; i++) {
        luz_camera start = {{test_uniform(&random, -100.0f, 100.0f),
                             test_uniform(&random, -100.0f, 100.0f),
                             test_uniform(&random, -100.0f, 100.0f)},
                            test_uniform(&random, -180.0f, 180.0f),
                            test_uniform(&random, -89.0f, 89.0f), 45.0f};
        const luz_vec3 centre = {test_uniform(&random, -100.0f, 100.0f),
                                 test_uniform(&random, -100.0f, 100.0f),
                                 test_uniform(&random, -100.0f, 100.0f)};
        luz_camera camera = start;
        luz_orbit orbit = luz_orbit_from_camera(&camera, centre);
        luz_orbit_place(&orbit, &camera);
        if (memcmp(&camera, &start, sizeof camera) != 0)
            fail_msg("camera %d: (%.9g, %.9g, %.9g) came back as (%.9g, %.9g, %.9g)", i,
                     (double)start.position.x, (double)start.position.y,
                     (double)start.position.z, (double)camera.position.x,
                     (double)camera.position.y, (double)camera.position.z);
    }
}

static void test_from_camera_targets_the_point_nearest_the_centre(void **state)
{
    (void)state;
    /* From (0, 0, 3) looking down -z: the origin is 3 ahead. */
    luz_camera camera = camera_at(-90.0f, 0.0f);
    luz_orbit orbit = luz_orbit_from_camera(&camera, (luz_vec3){0.0f, 0.0f, 0.0f});
    assert_target(&orbit, 0.0, 0.0, 0.0);
    assert_near(orbit.distance, 3.0, 1e-7);
    /* (2, 1, -4) is nearest the line of sight at (0, 0, -4), 7 ahead. */
    orbit = luz_orbit_from_camera(&camera, (luz_vec3){2.0f, 1.0f, -4.0f});
    assert_near(orbit.distance, 7.0, 1e-6);
    assert_near(orbit.target[2], -4.0, 1e-6);
    /* A centre behind the camera: the least distance, 0.2 ahead. */
    orbit = luz_orbit_from_camera(&camera, (luz_vec3){0.0f, 0.0f, 10.0f});
    assert_near(orbit.distance, 0.2, 1e-12);
    assert_near(orbit.target[2], 2.8, 1e-7);
    /* One far away: at most 50 ahead. */
    orbit = luz_orbit_from_camera(&camera, (luz_vec3){0.0f, 0.0f, -1000.0f});
    assert_near(orbit.distance, 50.0, 1e-12);
    assert_near(orbit.target[2], -47.0, 1e-6);
}

static void test_motion_keys_carry_the_target(void **state)
{
    (void)state;
    luz_orbit orbit = {{0.0, 0.0, 0.0}, 3.0};
    luz_camera camera = camera_at(-90.0f, 0.0f);
    luz_orbit_place(&orbit, &camera);
    /* W for a second: 2.5 units down -z, the target along. */
    luz_orbit_move(&orbit, &camera, (luz_motion){.forward = true}, 1.0f);
    assert_vec3_near(camera.position, 0.0, 0.0, 0.5, 1e-6);
    assert_target(&orbit, 0.0, 0.0, -2.5);
    /* then a drag turns round the moved target */
    luz_orbit_turn(&orbit, &camera, 360.0f, 0.0f);
    assert_vec3_near(camera.position, -3.0, 0.0, -2.5, 1e-5);
}

static void test_the_eye_stays_within_the_scene_range(void **state)
{
    (void)state;
    /* A target near the edge, the eye 50 beyond it: the distance is
     * shortened so that the eye stops at x = 10000. */
    luz_orbit orbit = {{9999.5, 0.0, 0.0}, 50.0};
    luz_camera camera = camera_at(-180.0f, 0.0f);   /* front (-1, 0, 0) */
    luz_orbit_place(&orbit, &camera);
    assert_true(camera.position.x <= LUZ_SCENE_MAX_COORDINATE);
    assert_near(camera.position.x, 10000.0, 1e-3);
    /* A target outside the range is brought inside too. */
    orbit = (luz_orbit){{0.0, -2e4, 0.0}, 5.0};
    camera = camera_at(-90.0f, 0.0f);
    luz_orbit_place(&orbit, &camera);
    assert_near(orbit.target[1], -LUZ_SCENE_MAX_COORDINATE, 0.0);
    assert_vec3_near(camera.position, 0.0, -1e4, 5.0, 1e-3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_drag_of_ninety_degrees_turns_the_eye_round_the_target),
        cmocka_unit_test(test_pitch_limits_keep_the_up_vector_defined),
        cmocka_unit_test(test_dolly_keeps_the_target_and_never_passes_it),
        cmocka_unit_test(test_fit_distance_is_radius_over_the_sine_of_the_half_angle),
        cmocka_unit_test(test_framing_fits_the_sphere_in_the_view),
        cmocka_unit_test(test_frame_two_cubes),
        cmocka_unit_test(test_bounding_sphere_of_the_lab),
        cmocka_unit_test(test_bounding_sphere_with_a_model),
        cmocka_unit_test(test_from_camera_and_back_is_exact),
        cmocka_unit_test(test_from_camera_targets_the_point_nearest_the_centre),
        cmocka_unit_test(test_motion_keys_carry_the_target),
        cmocka_unit_test(test_the_eye_stays_within_the_scene_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
