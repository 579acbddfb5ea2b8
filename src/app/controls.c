/*
 * controls.c: the viewer's controls as pure functions on scene data (see
 * app/controls.h). No SDL here: the viewer maps keys to these calls, and
 * tests/test_controls.c checks each against values worked out by hand.
 */
#include "app/controls.h"

#include <math.h>

static float clamp_float(float value, float low, float high)
{
    return value < low ? low : value > high ? high : value;
}

/* ---- the camera ----------------------------------------------------------------- */

void luz_camera_move(luz_camera *camera, luz_motion motion, float seconds)
{
    const luz_vec3 world_up = {0.0f, 1.0f, 0.0f};
    luz_vec3 front = luz_camera_front(camera);
    /* The pitch stays within [-89, 89], so front is never parallel to the
     * world's up and the cross product never vanishes. */
    luz_vec3 right = luz_vec3_normalize(luz_vec3_cross(front, world_up));
    float step = LUZ_CAMERA_SPEED * seconds;

    luz_vec3 offset = {0.0f, 0.0f, 0.0f};
    if (motion.forward) offset = luz_vec3_add(offset, front);
    if (motion.back) offset = luz_vec3_sub(offset, front);
    if (motion.right) offset = luz_vec3_add(offset, right);
    if (motion.left) offset = luz_vec3_sub(offset, right);
    if (motion.up) offset = luz_vec3_add(offset, world_up);
    if (motion.down) offset = luz_vec3_sub(offset, world_up);
    luz_vec3 position = luz_vec3_add(camera->position, luz_vec3_scale(offset, step));
    /* The options take no camera beyond LUZ_SCENE_MAX_COORDINATE; flying
     * stops there too, so that a saved view always reads back. */
    const float limit = LUZ_SCENE_MAX_COORDINATE;
    camera->position = (luz_vec3){clamp_float(position.x, -limit, limit),
                                  clamp_float(position.y, -limit, limit),
                                  clamp_float(position.z, -limit, limit)};
}

void luz_camera_turn_degrees(luz_camera *camera, float yaw_degrees, float pitch_degrees)
{
    float yaw = camera->yaw_degrees + yaw_degrees;
    if (yaw < -180.0f || yaw >= 180.0f)
        yaw -= 360.0f * floorf((yaw + 180.0f) / 360.0f);
    camera->yaw_degrees = yaw;
    camera->pitch_degrees = clamp_float(camera->pitch_degrees + pitch_degrees,
                                        -LUZ_PITCH_LIMIT, LUZ_PITCH_LIMIT);
}

void luz_camera_turn(luz_camera *camera, float dx, float dy)
{
    /* -(dy * k) is exact: the same pitch as pitch - dy * k */
    luz_camera_turn_degrees(camera, dx * LUZ_MOUSE_DEGREES_PER_PIXEL,
                            -(dy * LUZ_MOUSE_DEGREES_PER_PIXEL));
}

void luz_camera_reset(luz_camera *camera, const luz_camera *start)
{
    camera->position = start->position;
    camera->yaw_degrees = start->yaw_degrees;
    camera->pitch_degrees = start->pitch_degrees;
}

/* ---- the spot's cone ---------------------------------------------------------------- */

void luz_spot_set_outer(luz_lights *lights, float degrees)
{
    lights->spot_outer_degrees = clamp_float(degrees, 0.0f, LUZ_SPOT_ANGLE_MAX);
    if (lights->spot_inner_degrees > lights->spot_outer_degrees)
        lights->spot_inner_degrees = lights->spot_outer_degrees;
}

void luz_spot_set_inner(luz_lights *lights, float degrees)
{
    lights->spot_inner_degrees = clamp_float(degrees, 0.0f, LUZ_SPOT_ANGLE_MAX);
    if (lights->spot_outer_degrees < lights->spot_inner_degrees)
        lights->spot_outer_degrees = lights->spot_inner_degrees;
}

void luz_spot_press(luz_lights *lights, luz_cone_key key)
{
    switch (key) {
    case LUZ_CONE_WIDEN_OUTER:
        luz_spot_set_outer(lights, lights->spot_outer_degrees + LUZ_SPOT_ANGLE_STEP);
        break;
    case LUZ_CONE_NARROW_OUTER:
        luz_spot_set_outer(lights, lights->spot_outer_degrees - LUZ_SPOT_ANGLE_STEP);
        break;
    case LUZ_CONE_WIDEN_INNER:
        luz_spot_set_inner(lights, lights->spot_inner_degrees + LUZ_SPOT_ANGLE_STEP);
        break;
    case LUZ_CONE_NARROW_INNER:
        luz_spot_set_inner(lights, lights->spot_inner_degrees - LUZ_SPOT_ANGLE_STEP);
        break;
    }
}

/* ---- light switches -------------------------------------------------------------------- */

bool luz_light_is_on(const luz_lights *lights, luz_term term)
{
    return luz_lights_term((luz_lights *)lights, term)->strength > 0.0f;
}

void luz_light_toggle(luz_lights *lights, luz_light_switches *switches, luz_term term)
{
    luz_light *light = luz_lights_term(lights, term);
    if (light->strength > 0.0f) {
        switches->restore[term] = light->strength;
        light->strength = 0.0f;
    } else if (switches->restore[term] > 0.0f) {
        light->strength = switches->restore[term];
    } else {
        luz_scene defaults = luz_scene_defaults();
        light->strength = luz_lights_term(&defaults.lights, term)->strength;
    }
}

void luz_lights_reset(luz_lights *lights, luz_light_switches *switches)
{
    luz_lights defaults = luz_scene_defaults().lights;
    defaults.point_position = lights->point_position;
    defaults.spot_direction = lights->spot_direction;
    defaults.directional_direction = lights->directional_direction;
    *lights = defaults;
    *switches = (luz_light_switches){{0}};
}

/* ---- the rest ---------------------------------------------------------------------------- */

luz_filter luz_filter_next(luz_filter filter)
{
    switch (filter) {
    case LUZ_FILTER_NEAREST: return LUZ_FILTER_BILINEAR;
    case LUZ_FILTER_BILINEAR: return LUZ_FILTER_TRILINEAR;
    case LUZ_FILTER_TRILINEAR: break;
    }
    return LUZ_FILTER_NEAREST;
}

luz_view luz_view_next(luz_view view, bool backwards)
{
    int next = (int)view + (backwards ? LUZ_VIEW_COUNT - 1 : 1);
    return (luz_view)(next % LUZ_VIEW_COUNT);
}

int luz_samples_next(int samples)
{
    return samples == 4 ? 1 : 4;
}

luz_interpolation luz_interpolation_next(luz_interpolation interpolation)
{
    return interpolation == LUZ_INTERPOLATION_PERSPECTIVE ? LUZ_INTERPOLATION_AFFINE
                                                          : LUZ_INTERPOLATION_PERSPECTIVE;
}

uint32_t luz_step_advance(luz_step_mode *step, double seconds, uint64_t total)
{
    if (!step->on || total == 0)
        return 0;
    step->elapsed += seconds;
    /* One cycle: the triangles one by one, then the whole frame held. */
    const double building = (double)(total - 1) / LUZ_STEP_TRIANGLES_PER_SECOND;
    if (step->elapsed >= building + LUZ_STEP_HOLD_SECONDS)
        step->elapsed = 0.0;
    double shown = 1.0 + step->elapsed * LUZ_STEP_TRIANGLES_PER_SECOND;
    if (shown >= (double)total || shown >= (double)UINT32_MAX)
        return total < UINT32_MAX ? (uint32_t)total : UINT32_MAX;
    return (uint32_t)shown;
}

void luz_exposure_step(luz_scene *scene, int direction)
{
    float exposure = luz_scene_output(scene).exposure + (float)direction * LUZ_EXPOSURE_STEP;
    exposure = roundf(exposure / LUZ_EXPOSURE_STEP) * LUZ_EXPOSURE_STEP;
    if (exposure < -LUZ_EXPOSURE_LIMIT) exposure = -LUZ_EXPOSURE_LIMIT;
    if (exposure > LUZ_EXPOSURE_LIMIT) exposure = LUZ_EXPOSURE_LIMIT;
    scene->exposure = exposure;
    scene->has_exposure = true;
}

void luz_tone_map_toggle(luz_scene *scene)
{
    scene->tone_map = luz_scene_output(scene).tone_map == LUZ_TONE_MAP_CLAMP
                          ? LUZ_TONE_MAP_NEUTRAL
                          : LUZ_TONE_MAP_CLAMP;
    scene->has_tone_map = true;
}

uint32_t luz_seed_next(uint32_t seed, uint32_t entropy)
{
    uint32_t x = seed ^ entropy;
    if (x == 0)
        x = 0x9E3779B9u;
    return luz_xorshift32(x);
}

/* ---- the list of controls ------------------------------------------------------------------ */

const luz_control_help luz_controls_help[] = {
    {"W / Z / Up", "forward"},
    {"S / Down", "back"},
    {"A / Q / Left", "strafe left"},
    {"D / Right", "strafe right"},
    {"Space", "up"},
    {"Shift+Space", "down"},
    {"Mouse", "turn the camera (while flying)"},
    {"C", "back to the start position and rotation"},
    {"O", "orbit camera on / off (on from the start with a model)"},
    {"Drag (orbit)", "turn round the target"},
    {"Wheel (orbit)", "dolly towards / away from the target"},
    {"Home / Shift+O", "frame the whole scene (the orbit's target at its centre)"},
    {"P / M", "widen / narrow the spot's outer cone"},
    {"Shift+P / Shift+M", "widen / narrow the spot's inner cone"},
    {"F5", "new cube colours"},
    {"1 - 6", "switch ambient, diffuse, specular, point, spot, directional on or off"},
    {"R", "every light back to SCENE.md's defaults"},
    {"Tab", "switch between flying and the light panel (free cursor)"},
    {"Up / Down (panel)", "choose a slider"},
    {"Left / Right (panel)", "change it; with Shift, in fine steps"},
    {"Click, drag (panel)", "set a slider; click a light's name to switch it"},
    {"[ / ], N", "exposure down / up half a stop; tone map clamp / neutral"},
    {"F", "texture filter: nearest, bilinear, trilinear"},
    {"V / Shift+V", "next / previous view of the pipeline (its legend in the HUD)"},
    {"X, B", "interpolation perspective-correct / affine; 1 / 4 samples a pixel"},
    {"G", "step mode: draw the frame triangle by triangle, slowly"},
    {"E", "probe mode: click a pixel to see why it has its colour; T freezes the panel"},
    {"Shift+E / U", "close the probe panel / its next page"},
    {"T", "pause / resume the animation"},
    {"I", "HUD on / off"},
    {"H", "this help on / off"},
    {"F2", "save the view as a scene file (luz-scene-N.luz)"},
    {"F12", "save a screenshot of the scene (luz-shot-N.png)"},
    {"F11", "fullscreen on / off"},
    {"Esc", "quit"},
};

const int luz_controls_help_count = (int)(sizeof luz_controls_help / sizeof luz_controls_help[0]);
