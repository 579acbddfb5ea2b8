/*
 * test_controls.c: the viewer's controls (app/controls.h) without a window.
 *
 * Expected values are worked out by hand from SCENE.md: the camera starts
 * at (0, 0, 3) with yaw -90 and pitch 0, so front = (cos -90, 0, sin -90)
 * = (0, 0, -1) and right = cross(front, up) = (1, 0, 0); speed 2.5 units a
 * second; the mouse turns 0.1 degree a pixel; the cone moves 1 degree a
 * press within [0, 89].
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "app/controls.h"
#include "lab/scene.h"

#define EPSILON 1e-5f

static void assert_near(float actual, float expected, float tolerance)
{
    if (!(fabsf(actual - expected) <= tolerance))
        fail_msg("expected %.7g, got %.7g", (double)expected, (double)actual);
}

static void assert_vec3_near(luz_vec3 actual, float x, float y, float z)
{
    assert_near(actual.x, x, EPSILON);
    assert_near(actual.y, y, EPSILON);
    assert_near(actual.z, z, EPSILON);
}

static luz_camera start_camera(void)
{
    return luz_scene_defaults().camera;
}

/* ---- motion ------------------------------------------------------------------------ */

static void test_forward_is_minus_z_at_the_start(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    luz_camera_move(&camera, (luz_motion){.forward = true}, 1.0f);
    assert_vec3_near(camera.position, 0.0f, 0.0f, 0.5f);   /* 3 - 2.5 */
    luz_camera_move(&camera, (luz_motion){.back = true}, 0.4f);
    assert_vec3_near(camera.position, 0.0f, 0.0f, 1.5f);   /* 0.5 + 1.0 */
}

static void test_strafe_up_and_down(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    luz_camera_move(&camera, (luz_motion){.right = true}, 1.0f);
    assert_vec3_near(camera.position, 2.5f, 0.0f, 3.0f);
    luz_camera_move(&camera, (luz_motion){.left = true}, 2.0f);
    assert_vec3_near(camera.position, -2.5f, 0.0f, 3.0f);
    luz_camera_move(&camera, (luz_motion){.up = true}, 2.0f);
    assert_vec3_near(camera.position, -2.5f, 5.0f, 3.0f);
    luz_camera_move(&camera, (luz_motion){.down = true}, 0.5f);
    assert_vec3_near(camera.position, -2.5f, 3.75f, 3.0f);
}

static void test_opposite_keys_cancel(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    luz_motion all = {true, true, true, true, true, true};
    luz_camera_move(&camera, all, 1.0f);
    assert_vec3_near(camera.position, 0.0f, 0.0f, 3.0f);
}

static void test_keys_add_up(void **state)
{
    (void)state;
    /* As in the report, each held key adds its own full-speed vector. */
    luz_camera camera = start_camera();
    luz_camera_move(&camera, (luz_motion){.forward = true, .right = true}, 1.0f);
    assert_vec3_near(camera.position, 2.5f, 0.0f, 0.5f);
}

static void test_motion_is_per_second(void **state)
{
    (void)state;
    /* Ten frames of 0.1 s go where one frame of 1 s goes. */
    luz_camera many = start_camera(), one = start_camera();
    for (int frame = 0; frame < 10; frame++)
        luz_camera_move(&many, (luz_motion){.forward = true}, 0.1f);
    luz_camera_move(&one, (luz_motion){.forward = true}, 1.0f);
    assert_vec3_near(many.position, one.position.x, one.position.y, one.position.z);
}

/* Flying stops at the options' range, +-10000 on each axis, so that
 * --print-state and F2 never write a camera-pos the reader refuses; the
 * other axes move on as usual. */
static void test_motion_stops_at_the_range(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    camera.position = (luz_vec3){9999.0f, 0.0f, -9999.5f};
    /* one second right: +2.5 on x, clamped to 10000; z stays */
    luz_camera_move(&camera, (luz_motion){.right = true}, 1.0f);
    assert_vec3_near(camera.position, 10000.0f, 0.0f, -9999.5f);
    /* one second forward (-z): -9999.5 - 2.5 = -10002, clamped to -10000 */
    luz_camera_move(&camera, (luz_motion){.forward = true}, 1.0f);
    assert_vec3_near(camera.position, 10000.0f, 0.0f, -10000.0f);
    /* 5000 seconds up would be 12500: it ends at the range too */
    luz_camera_move(&camera, (luz_motion){.up = true}, 5000.0f);
    assert_vec3_near(camera.position, 10000.0f, 10000.0f, -10000.0f);
    /* and back, as far as the motion goes: 10000 - 2.5 */
    luz_camera_move(&camera, (luz_motion){.left = true}, 1.0f);
    assert_vec3_near(camera.position, 9997.5f, 10000.0f, -10000.0f);
}

static void test_forward_follows_the_pitch(void **state)
{
    (void)state;
    /* Pitch 30: front = (0, sin 30, -cos 30) = (0, 0.5, -0.8660254); one
     * second forward climbs 1.25 and goes 2.1650635 towards -z. Right stays
     * (1, 0, 0): cross(front, up) = (-front.z, 0, front.x), normalised. */
    luz_camera camera = start_camera();
    camera.pitch_degrees = 30.0f;
    luz_camera_move(&camera, (luz_motion){.forward = true}, 1.0f);
    assert_vec3_near(camera.position, 0.0f, 1.25f, 3.0f - 2.1650635f);
    luz_camera_move(&camera, (luz_motion){.right = true}, 1.0f);
    assert_vec3_near(camera.position, 2.5f, 1.25f, 3.0f - 2.1650635f);
}

static void test_strafe_follows_the_yaw(void **state)
{
    (void)state;
    /* Yaw 0 looks down +x: front (1, 0, 0), right = cross(front, up) =
     * (0, 0, 1). */
    luz_camera camera = start_camera();
    camera.yaw_degrees = 0.0f;
    luz_camera_move(&camera, (luz_motion){.right = true}, 1.0f);
    assert_vec3_near(camera.position, 0.0f, 0.0f, 5.5f);
    luz_camera_move(&camera, (luz_motion){.forward = true}, 1.0f);
    assert_vec3_near(camera.position, 2.5f, 0.0f, 5.5f);
}

/* ---- mouse look ------------------------------------------------------------------------ */

static void test_mouse_turns_a_tenth_of_a_degree_a_pixel(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    luz_camera_turn(&camera, 10.0f, 0.0f);
    assert_near(camera.yaw_degrees, -89.0f, EPSILON);
    assert_near(camera.pitch_degrees, 0.0f, EPSILON);
    /* The mouse moving down (dy > 0) looks down. */
    luz_camera_turn(&camera, 0.0f, 50.0f);
    assert_near(camera.pitch_degrees, -5.0f, EPSILON);
    luz_camera_turn(&camera, -20.0f, -150.0f);
    assert_near(camera.yaw_degrees, -91.0f, EPSILON);
    assert_near(camera.pitch_degrees, 10.0f, EPSILON);
}

static void test_yaw_and_pitch_give_the_front_vector(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    assert_vec3_near(luz_camera_front(&camera), 0.0f, 0.0f, -1.0f);
    /* 900 pixels right: yaw -90 + 90 = 0, looking down +x. */
    luz_camera_turn(&camera, 900.0f, 0.0f);
    assert_vec3_near(luz_camera_front(&camera), 1.0f, 0.0f, 0.0f);
    /* 450 pixels up: pitch 45; front = (cos 45, sin 45, 0). */
    luz_camera_turn(&camera, 0.0f, -450.0f);
    assert_vec3_near(luz_camera_front(&camera), 0.70710678f, 0.70710678f, 0.0f);
}

static void test_pitch_is_clamped(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    luz_camera_turn(&camera, 0.0f, -2000.0f);   /* 200 degrees up */
    assert_near(camera.pitch_degrees, 89.0f, 0.0f);
    luz_camera_turn(&camera, 0.0f, 5000.0f);    /* 500 degrees down */
    assert_near(camera.pitch_degrees, -89.0f, 0.0f);
    /* Clamped, not wound up: 10 degrees back up is -79. */
    luz_camera_turn(&camera, 0.0f, -100.0f);
    assert_near(camera.pitch_degrees, -79.0f, EPSILON);
    /* At the clamp the camera still moves sideways: right never vanishes. */
    camera.pitch_degrees = 89.0f;
    luz_vec3 before = camera.position;
    luz_camera_move(&camera, (luz_motion){.right = true}, 1.0f);
    assert_near(luz_vec3_length(luz_vec3_sub(camera.position, before)), 2.5f, EPSILON);
}

static void test_yaw_wraps(void **state)
{
    (void)state;
    luz_camera camera = start_camera();
    camera.yaw_degrees = 170.0f;
    luz_camera_turn(&camera, 200.0f, 0.0f);     /* 190 is -170 */
    assert_near(camera.yaw_degrees, -170.0f, EPSILON);
    luz_camera_turn(&camera, -200.0f, 0.0f);    /* -190 is 170 */
    assert_near(camera.yaw_degrees, 170.0f, EPSILON);
}

static void test_reset(void **state)
{
    (void)state;
    luz_camera start = start_camera();
    luz_camera camera = start;
    luz_camera_move(&camera, (luz_motion){.forward = true, .up = true}, 3.0f);
    luz_camera_turn(&camera, 123.0f, -456.0f);
    luz_camera_reset(&camera, &start);
    assert_vec3_near(camera.position, 0.0f, 0.0f, 3.0f);
    assert_near(camera.yaw_degrees, -90.0f, 0.0f);
    assert_near(camera.pitch_degrees, 0.0f, 0.0f);
    assert_vec3_near(luz_camera_front(&camera), 0.0f, 0.0f, -1.0f);

    /* A start of the user's own, and the field of view is left alone. */
    luz_camera own = {{1.0f, 2.0f, 3.0f}, 10.0f, -20.0f, 45.0f};
    camera.fov_degrees = 60.0f;
    luz_camera_reset(&camera, &own);
    assert_vec3_near(camera.position, 1.0f, 2.0f, 3.0f);
    assert_near(camera.yaw_degrees, 10.0f, 0.0f);
    assert_near(camera.pitch_degrees, -20.0f, 0.0f);
    assert_near(camera.fov_degrees, 60.0f, 0.0f);
}

/* ---- the cone keys ---------------------------------------------------------------------------- */

static void test_cone_keys_move_one_degree(void **state)
{
    (void)state;
    luz_lights lights = luz_scene_defaults().lights;   /* inner 12.5, outer 17.5 */
    luz_spot_press(&lights, LUZ_CONE_WIDEN_OUTER);
    assert_near(lights.spot_outer_degrees, 18.5f, 0.0f);
    luz_spot_press(&lights, LUZ_CONE_NARROW_OUTER);
    luz_spot_press(&lights, LUZ_CONE_NARROW_OUTER);
    assert_near(lights.spot_outer_degrees, 16.5f, 0.0f);
    luz_spot_press(&lights, LUZ_CONE_WIDEN_INNER);
    assert_near(lights.spot_inner_degrees, 13.5f, 0.0f);
    luz_spot_press(&lights, LUZ_CONE_NARROW_INNER);
    luz_spot_press(&lights, LUZ_CONE_NARROW_INNER);
    assert_near(lights.spot_inner_degrees, 11.5f, 0.0f);
    assert_near(lights.spot_outer_degrees, 16.5f, 0.0f);
}

static void test_narrowing_the_outer_cone_takes_the_inner_along(void **state)
{
    (void)state;
    luz_lights lights = luz_scene_defaults().lights;
    for (int press = 0; press < 5; press++)
        luz_spot_press(&lights, LUZ_CONE_NARROW_OUTER);
    assert_near(lights.spot_outer_degrees, 12.5f, 0.0f);   /* meets the inner */
    assert_near(lights.spot_inner_degrees, 12.5f, 0.0f);
    luz_spot_press(&lights, LUZ_CONE_NARROW_OUTER);
    assert_near(lights.spot_outer_degrees, 11.5f, 0.0f);
    assert_near(lights.spot_inner_degrees, 11.5f, 0.0f);
}

static void test_widening_the_inner_cone_takes_the_outer_along(void **state)
{
    (void)state;
    luz_lights lights = luz_scene_defaults().lights;
    for (int press = 0; press < 6; press++)
        luz_spot_press(&lights, LUZ_CONE_WIDEN_INNER);
    assert_near(lights.spot_inner_degrees, 18.5f, 0.0f);
    assert_near(lights.spot_outer_degrees, 18.5f, 0.0f);
}

static void test_cone_limits(void **state)
{
    (void)state;
    luz_lights lights = luz_scene_defaults().lights;
    lights.spot_outer_degrees = 88.5f;
    luz_spot_press(&lights, LUZ_CONE_WIDEN_OUTER);
    assert_near(lights.spot_outer_degrees, 89.0f, 0.0f);
    luz_spot_press(&lights, LUZ_CONE_WIDEN_OUTER);
    assert_near(lights.spot_outer_degrees, 89.0f, 0.0f);

    lights.spot_inner_degrees = 0.5f;
    luz_spot_press(&lights, LUZ_CONE_NARROW_INNER);
    assert_near(lights.spot_inner_degrees, 0.0f, 0.0f);
    luz_spot_press(&lights, LUZ_CONE_NARROW_INNER);
    assert_near(lights.spot_inner_degrees, 0.0f, 0.0f);

    for (int press = 0; press < 200; press++)
        luz_spot_press(&lights, LUZ_CONE_WIDEN_INNER);
    assert_near(lights.spot_inner_degrees, 89.0f, 0.0f);
    assert_near(lights.spot_outer_degrees, 89.0f, 0.0f);
    for (int press = 0; press < 200; press++)
        luz_spot_press(&lights, LUZ_CONE_NARROW_OUTER);
    assert_near(lights.spot_inner_degrees, 0.0f, 0.0f);
    assert_near(lights.spot_outer_degrees, 0.0f, 0.0f);
}

static void test_cone_invariant_under_any_presses(void **state)
{
    (void)state;
    luz_lights lights = luz_scene_defaults().lights;
    uint32_t x = 12345;
    for (int press = 0; press < 20000; press++) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        luz_spot_press(&lights, (luz_cone_key)(x % 4));
        assert_true(lights.spot_inner_degrees >= 0.0f);
        assert_true(lights.spot_inner_degrees <= lights.spot_outer_degrees);
        assert_true(lights.spot_outer_degrees <= 89.0f);
    }
}

static void test_cone_setters_clamp(void **state)
{
    (void)state;
    luz_lights lights = luz_scene_defaults().lights;
    luz_spot_set_outer(&lights, 120.0f);
    assert_near(lights.spot_outer_degrees, 89.0f, 0.0f);
    luz_spot_set_inner(&lights, -5.0f);
    assert_near(lights.spot_inner_degrees, 0.0f, 0.0f);
    luz_spot_set_inner(&lights, 30.0f);
    assert_near(lights.spot_inner_degrees, 30.0f, 0.0f);
    assert_near(lights.spot_outer_degrees, 89.0f, 0.0f);   /* already wider */
    luz_spot_set_outer(&lights, 20.0f);
    assert_near(lights.spot_outer_degrees, 20.0f, 0.0f);
    assert_near(lights.spot_inner_degrees, 20.0f, 0.0f);
}

/* ---- light switches ----------------------------------------------------------------------------- */

static void test_toggle_keeps_the_strength(void **state)
{
    (void)state;
    luz_lights lights = luz_scene_defaults().lights;
    luz_light_switches switches = {{0}};
    assert_true(luz_light_is_on(&lights, LUZ_TERM_DIFFUSE));
    luz_light_toggle(&lights, &switches, LUZ_TERM_DIFFUSE);
    assert_false(luz_light_is_on(&lights, LUZ_TERM_DIFFUSE));
    assert_near(lights.diffuse.strength, 0.0f, 0.0f);
    /* The others are untouched. */
    assert_near(lights.ambient.strength, 0.2f, 0.0f);
    assert_near(lights.spot.strength, 1.0f, 0.0f);

    /* An edited strength comes back as edited, not as the default. */
    lights.spot.strength = 0.35f;
    luz_light_toggle(&lights, &switches, LUZ_TERM_SPOT);
    luz_light_toggle(&lights, &switches, LUZ_TERM_DIFFUSE);
    assert_near(lights.diffuse.strength, 0.6f, 0.0f);
    luz_light_toggle(&lights, &switches, LUZ_TERM_SPOT);
    assert_near(lights.spot.strength, 0.35f, 0.0f);
    /* The colour is never touched. */
    assert_near(lights.spot.colour.x, 1.0f, 0.0f);
}

static void test_toggle_a_light_that_started_off(void **state)
{
    (void)state;
    /* --only spot leaves the point light at 0: switching it on gives
     * SCENE.md's 0.7. */
    luz_lights lights = luz_scene_defaults().lights;
    lights.point.strength = 0.0f;
    luz_light_switches switches = {{0}};
    assert_false(luz_light_is_on(&lights, LUZ_TERM_POINT));
    luz_light_toggle(&lights, &switches, LUZ_TERM_POINT);
    assert_near(lights.point.strength, 0.7f, 0.0f);
}

/* R: SCENE.md's lights table, typed in again here (not read from
 * luz_scene_defaults), whatever the lights were; the switches forget. */
static void test_reset_lights_to_scene_defaults(void **state)
{
    (void)state;
    luz_lights lights;
    memset(&lights, 0, sizeof lights);
    lights.ambient = (luz_light){{0.1f, 0.2f, 0.3f}, 0.9f};
    lights.spot = (luz_light){{0.0f, 0.0f, 1.0f}, 0.0f};
    lights.shininess = 3.0f;
    lights.spot_inner_degrees = 40.0f;
    lights.spot_outer_degrees = 41.0f;
    lights.spot_reach = 2.0f;
    lights.point_position = (luz_vec3){3.0f, 0.5f, 0.0f};
    luz_light_switches switches = {{0}};
    switches.restore[LUZ_TERM_SPOT] = 0.25f;   /* switched off at 0.25 */

    luz_lights_reset(&lights, &switches);
    const luz_light *expected[LUZ_TERM_COUNT] = {&lights.ambient, &lights.diffuse,
                                                 &lights.specular, &lights.point,
                                                 &lights.spot, &lights.directional};
    const float strengths[LUZ_TERM_COUNT] = {0.2f, 0.6f, 0.5f, 0.7f, 1.0f, 0.4f};
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        assert_near(expected[term]->colour.x, 1.0f, 0.0f);
        assert_near(expected[term]->colour.y, 1.0f, 0.0f);
        assert_near(expected[term]->colour.z, 1.0f, 0.0f);
        assert_near(expected[term]->strength, strengths[term], 0.0f);
        assert_near(switches.restore[term], 0.0f, 0.0f);
    }
    assert_near(lights.shininess, 32.0f, 0.0f);
    assert_near(lights.spot_inner_degrees, 12.5f, 0.0f);
    assert_near(lights.spot_outer_degrees, 17.5f, 0.0f);
    assert_near(lights.spot_reach, 10.0f, 0.0f);
    /* the orbit's position is the frame's, left as it was */
    assert_near(lights.point_position.x, 3.0f, 0.0f);
    /* Switching the spot off and on now gives SCENE.md's 1, not the 0.25
     * the switch had kept. */
    luz_light_toggle(&lights, &switches, LUZ_TERM_SPOT);
    luz_light_toggle(&lights, &switches, LUZ_TERM_SPOT);
    assert_near(lights.spot.strength, 1.0f, 0.0f);
}

/* ---- the rest -------------------------------------------------------------------------------------- */

static void test_filter_cycles(void **state)
{
    (void)state;
    assert_int_equal(luz_filter_next(LUZ_FILTER_NEAREST), LUZ_FILTER_BILINEAR);
    assert_int_equal(luz_filter_next(LUZ_FILTER_BILINEAR), LUZ_FILTER_TRILINEAR);
    assert_int_equal(luz_filter_next(LUZ_FILTER_TRILINEAR), LUZ_FILTER_NEAREST);
}

static void test_seed_next(void **state)
{
    (void)state;
    /* 5 ^ 16 = 21 = 0b10101; x ^= x << 13 gives 172053; x ^= x >> 17 gives
     * 172052; x ^= x << 5 gives 0x2A014 ^ 0x540280 = 0x56A294. */
    assert_int_equal(luz_seed_next(5, 16), 5677716u);
    /* A zero state would stay zero, so it starts from the default seed:
     * xorshift32(0x9E3779B9) = 0x510C4619. */
    assert_int_equal(luz_seed_next(7, 7), 0x510C4619u);
    assert_int_equal(luz_seed_next(0, 0), 0x510C4619u);
    uint32_t seed = 0;
    for (int press = 0; press < 1000; press++) {
        uint32_t next = luz_seed_next(seed, (uint32_t)press * 2654435761u);
        assert_true(next != 0);
        assert_true(next != seed);
        seed = next;
    }
}

static void test_view_and_interpolation_keys_cycle(void **state)
{
    (void)state;
    /* V visits every view once and comes back; Shift+V goes the other way. */
    luz_view view = LUZ_VIEW_COLOR;
    bool seen[LUZ_VIEW_COUNT] = {false};
    for (int press = 0; press < LUZ_VIEW_COUNT; press++) {
        assert_false(seen[view]);
        seen[view] = true;
        luz_view next = luz_view_next(view, false);
        assert_int_equal(luz_view_next(next, true), view);
        view = next;
    }
    assert_int_equal(view, LUZ_VIEW_COLOR);
    assert_int_equal(luz_view_next(LUZ_VIEW_COLOR, true), LUZ_VIEW_TRIANGLES);
    assert_int_equal(luz_interpolation_next(LUZ_INTERPOLATION_PERSPECTIVE),
                     LUZ_INTERPOLATION_AFFINE);
    assert_int_equal(luz_interpolation_next(LUZ_INTERPOLATION_AFFINE),
                     LUZ_INTERPOLATION_PERSPECTIVE);
}

static void test_step_mode_adds_triangles_over_time(void **state)
{
    (void)state;
    luz_step_mode step = {0};
    assert_int_equal(luz_step_advance(&step, 0.1, 50), 0);   /* off: draw them all */
    step.on = true;
    assert_int_equal(luz_step_advance(&step, 0.0, 50), 1);   /* the first triangle */
    assert_int_equal(luz_step_advance(&step, 1.0, 50), 1 + (int)LUZ_STEP_TRIANGLES_PER_SECOND);
    /* After (50 - 1) / rate seconds every triangle is drawn, and stays so
     * for the hold time; then it starts again from one. */
    const double building = 49.0 / LUZ_STEP_TRIANGLES_PER_SECOND;
    assert_int_equal(luz_step_advance(&step, building - 1.0 + 0.01, 50), 50);
    assert_int_equal(luz_step_advance(&step, LUZ_STEP_HOLD_SECONDS - 0.02, 50), 50);
    assert_int_equal(luz_step_advance(&step, 0.02, 50), 1);
    assert_int_equal(luz_step_advance(&step, 0.5, 0), 0);     /* an empty frame */
}

/* [ and ] step the exposure in force by half a stop, N switches the tone
 * map in force: from a lab scene's clamp at EV 0, and from a model
 * scene's neutral at EV -1 (SCENE.md's defaults); the exposure stops at
 * -10 and 10 and lands on whole half stops. */
static void test_exposure_and_tone_map_keys(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    luz_exposure_step(&scene, +1);
    assert_true(scene.has_exposure);
    assert_true(luz_scene_output(&scene).exposure == 0.5f);
    luz_exposure_step(&scene, -1);
    luz_exposure_step(&scene, -1);
    assert_true(luz_scene_output(&scene).exposure == -0.5f);
    luz_tone_map_toggle(&scene);
    assert_int_equal(luz_scene_output(&scene).tone_map, LUZ_TONE_MAP_NEUTRAL);
    luz_tone_map_toggle(&scene);
    assert_int_equal(luz_scene_output(&scene).tone_map, LUZ_TONE_MAP_CLAMP);
    for (int i = 0; i < 30; i++) luz_exposure_step(&scene, +1);
    assert_true(scene.exposure == 10.0f);
    for (int i = 0; i < 50; i++) luz_exposure_step(&scene, -1);
    assert_true(scene.exposure == -10.0f);
    /* a given exposure between steps lands on one */
    scene.exposure = 0.3f;
    luz_exposure_step(&scene, +1);
    assert_true(scene.exposure == 1.0f);

    /* a scene with a model starts from neutral at EV -1 */
    const luz_lab_model model = {.name = "m"};
    const luz_object object = {.model = &model, .texture = LUZ_TEXTURE_BY_INDEX};
    luz_scene with_model = luz_scene_defaults();
    with_model.objects = &object;
    with_model.object_count = 1;
    luz_exposure_step(&with_model, +1);
    assert_true(luz_scene_output(&with_model).exposure == -0.5f);
    assert_int_equal(luz_scene_output(&with_model).tone_map, LUZ_TONE_MAP_NEUTRAL);
    luz_tone_map_toggle(&with_model);
    assert_int_equal(luz_scene_output(&with_model).tone_map, LUZ_TONE_MAP_CLAMP);
}

static void test_help_lists_every_control(void **state)
{
    (void)state;
    assert_true(luz_controls_help_count >= 20);
    for (int i = 0; i < luz_controls_help_count; i++) {
        assert_non_null(luz_controls_help[i].keys);
        assert_non_null(luz_controls_help[i].action);
        assert_true(luz_controls_help[i].keys[0] != '\0');
        assert_true(luz_controls_help[i].action[0] != '\0');
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_forward_is_minus_z_at_the_start),
        cmocka_unit_test(test_strafe_up_and_down),
        cmocka_unit_test(test_opposite_keys_cancel),
        cmocka_unit_test(test_keys_add_up),
        cmocka_unit_test(test_motion_is_per_second),
        cmocka_unit_test(test_motion_stops_at_the_range),
        cmocka_unit_test(test_forward_follows_the_pitch),
        cmocka_unit_test(test_strafe_follows_the_yaw),
        cmocka_unit_test(test_mouse_turns_a_tenth_of_a_degree_a_pixel),
        cmocka_unit_test(test_yaw_and_pitch_give_the_front_vector),
        cmocka_unit_test(test_pitch_is_clamped),
        cmocka_unit_test(test_yaw_wraps),
        cmocka_unit_test(test_reset),
        cmocka_unit_test(test_cone_keys_move_one_degree),
        cmocka_unit_test(test_narrowing_the_outer_cone_takes_the_inner_along),
        cmocka_unit_test(test_widening_the_inner_cone_takes_the_outer_along),
        cmocka_unit_test(test_cone_limits),
        cmocka_unit_test(test_cone_invariant_under_any_presses),
        cmocka_unit_test(test_cone_setters_clamp),
        cmocka_unit_test(test_toggle_keeps_the_strength),
        cmocka_unit_test(test_toggle_a_light_that_started_off),
        cmocka_unit_test(test_reset_lights_to_scene_defaults),
        cmocka_unit_test(test_filter_cycles),
        cmocka_unit_test(test_seed_next),
        cmocka_unit_test(test_view_and_interpolation_keys_cycle),
        cmocka_unit_test(test_step_mode_adds_triangles_over_time),
        cmocka_unit_test(test_exposure_and_tone_map_keys),
        cmocka_unit_test(test_help_lists_every_control),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
