/*
 * app/controls.h: what the viewer's keys and mouse do to a scene.
 *
 * The interactive viewer (src/programs/luz_viewer.c) reads SDL events and
 * turns them into calls of these functions; everything they change is plain
 * scene data (luz_camera, luz_lights), so the behaviour of every control is
 * tested without a window. The controls are those of SCENE.md (from the
 * report): motion per second, mouse look with the pitch clamped, the spot's
 * cone keys, plus the viewer's own light switches and filter key, and the
 * teaching controls: the pipeline's views, affine interpolation and the
 * step mode.
 *
 * luz_controls_help lists every control of the viewer, in the order its H
 * overlay, `luz --help` and docs/viewer.md show them.
 */
#ifndef LUZ_CONTROLS_H
#define LUZ_CONTROLS_H

#include <stdbool.h>
#include <stdint.h>

#include "lab/scene.h"

#define LUZ_CAMERA_SPEED 2.5f            /* units per second (SCENE.md) */
#define LUZ_MOUSE_DEGREES_PER_PIXEL 0.1f /* yaw += dx * 0.1, pitch -= dy * 0.1 */
#define LUZ_PITCH_LIMIT 89.0f            /* the pitch stays within [-89, 89] */
#define LUZ_SPOT_ANGLE_MAX 89.0f         /* spot angles within [0, 89] */
#define LUZ_SPOT_ANGLE_STEP 1.0f         /* degrees per press of P / M */

/* ---- the camera ------------------------------------------------------------ */

/* The motion keys held down during a frame. Opposite keys cancel. */
typedef struct luz_motion {
    bool forward, back;   /* W / Z / Up, S / Down */
    bool left, right;     /* A / Q / Left, D / Right */
    bool up, down;        /* Space, Shift+Space */
} luz_motion;

/* Moves the camera for `seconds` of the held keys at LUZ_CAMERA_SPEED, as
 * the report does: forward and back along the front vector (so looking up
 * and pressing W climbs), sideways along normalize(cross(front, world up)),
 * up and down along the world's up (0, 1, 0). Each held key contributes its
 * full speed, so a diagonal is faster than a straight line, as in the
 * report. Each coordinate stays within +-LUZ_SCENE_MAX_COORDINATE, the
 * options' range (lab/scene.h). */
void luz_camera_move(luz_camera *camera, luz_motion motion, float seconds);

/* Mouse look: yaw += dx * 0.1, pitch -= dy * 0.1 (dx, dy in pixels, y
 * pointing down), the pitch clamped to [-89, 89]. The yaw is kept within
 * [-180, 180) so that hours of turning lose no precision. */
void luz_camera_turn(luz_camera *camera, float dx, float dy);

/* Turns by the given degrees: yaw += yaw_degrees, kept within [-180, 180);
 * pitch += pitch_degrees, clamped to [-89, 89]. Mouse look and the orbit
 * camera's drag (app/orbit.h) both turn this way. */
void luz_camera_turn_degrees(luz_camera *camera, float yaw_degrees, float pitch_degrees);

/* C: back to the position and rotation the viewer started with (SCENE.md's
 * start unless options or a scene file chose another). The field of view is
 * not part of a reset. */
void luz_camera_reset(luz_camera *camera, const luz_camera *start);

/* ---- the spot's cone -------------------------------------------------------- */

/* Sets an angle of the cone, clamped to [0, 89]. The other angle follows
 * when needed to keep inner <= outer: narrowing the outer cone below the
 * inner one narrows both, widening the inner cone past the outer one widens
 * both. */
void luz_spot_set_outer(luz_lights *lights, float degrees);
void luz_spot_set_inner(luz_lights *lights, float degrees);

typedef enum luz_cone_key {
    LUZ_CONE_WIDEN_OUTER,    /* P */
    LUZ_CONE_NARROW_OUTER,   /* M */
    LUZ_CONE_WIDEN_INNER,    /* Shift+P */
    LUZ_CONE_NARROW_INNER,   /* Shift+M */
} luz_cone_key;

/* One press of a cone key: LUZ_SPOT_ANGLE_STEP degrees. */
void luz_spot_press(luz_lights *lights, luz_cone_key key);

/* ---- light switches ----------------------------------------------------------- */

/* The number keys 1-6 switch the six terms on and off. A light is on while
 * its strength is above 0; switching it off keeps its strength in `restore`
 * so that switching it on again brings back the same light. A light that was
 * off from the start (strength 0, nothing kept) comes on at SCENE.md's
 * default strength. */
typedef struct luz_light_switches {
    float restore[LUZ_TERM_COUNT];   /* 0: nothing kept */
} luz_light_switches;

bool luz_light_is_on(const luz_lights *lights, luz_term term);
void luz_light_toggle(luz_lights *lights, luz_light_switches *switches, luz_term term);

/* R: every light back to SCENE.md's defaults (colour, strength, the
 * shininess, the spot's cone and reach), whatever options or a scene file
 * started the viewer with, and the switches forget what they kept, so that
 * a number key then switches SCENE.md's light. The lights' positions are
 * the frame's business (their orbits) and are left alone. */
void luz_lights_reset(luz_lights *lights, luz_light_switches *switches);

/* ---- the rest ------------------------------------------------------------------- */

/* nearest -> bilinear -> trilinear -> nearest. */
luz_filter luz_filter_next(luz_filter filter);

/* ---- the output: exposure and tone map (SCENE.md, "Output") -------------------- */

#define LUZ_EXPOSURE_STEP 0.5f    /* EV per press of [ / ] */
#define LUZ_EXPOSURE_LIMIT 10.0f  /* the options' range, [-10, 10] */

/* [ / ]: the exposure in force (luz_scene_output) down / up by
 * LUZ_EXPOSURE_STEP (direction -1 or +1), rounded to a whole number of
 * steps and kept within [-10, 10]; from then on the user's. */
void luz_exposure_step(luz_scene *scene, int direction);
/* N: clamp <-> neutral, from the tone map in force. */
void luz_tone_map_toggle(luz_scene *scene);

/* ---- the teaching controls (docs/pipeline.md, "Guided tour") --------------------- */

/* V / Shift+V: the next / previous --view (color, depth, normals, uv, mip,
 * overdraw, bands, triangles, then color again). */
luz_view luz_view_next(luz_view view, bool backwards);

/* B: 1 <-> 4 samples a pixel. */
int luz_samples_next(int samples);

/* X: perspective-correct <-> affine interpolation. */
luz_interpolation luz_interpolation_next(luz_interpolation interpolation);

/* G: the step mode draws the frame triangle by triangle: it starts with
 * the first triangle and adds LUZ_STEP_TRIANGLES_PER_SECOND, shows the
 * whole frame for LUZ_STEP_HOLD_SECONDS and starts again. The viewer
 * freezes the animation meanwhile, so the triangles keep their order. */
#define LUZ_STEP_TRIANGLES_PER_SECOND 6.0
#define LUZ_STEP_HOLD_SECONDS 2.0

typedef struct luz_step_mode {
    bool on;
    double elapsed;      /* seconds since the first triangle */
} luz_step_mode;

/* Advances the step mode by `seconds` for a frame of `total` triangles
 * (after clipping and culling) and returns how many to draw now, from 1 to
 * total: the renderer's luz_uniforms.triangle_limit. Returns 0 (draw them
 * all) when the mode is off or the frame has none. */
uint32_t luz_step_advance(luz_step_mode *step, double seconds, uint64_t total);

/* F5's new colour seed: the current one stirred with some entropy (the
 * viewer passes the clock) through SCENE.md's xorshift32, so that each press
 * gives new colours and the result is never 0 (which would mean the default
 * seed again). */
uint32_t luz_seed_next(uint32_t seed, uint32_t entropy);

/* ---- the list of controls --------------------------------------------------------- */

typedef struct luz_control_help {
    const char *keys;     /* "W / Z / Up" */
    const char *action;   /* "forward" */
} luz_control_help;

extern const luz_control_help luz_controls_help[];
extern const int luz_controls_help_count;

#endif
