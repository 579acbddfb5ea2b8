/*
 * app/orbit.h: the viewer's orbit camera, as pure functions on scene data.
 *
 * The fly camera (controls.h) is a position and a direction. The orbit
 * camera turns round a target instead: a drag turns it round the target,
 * the wheel dollies it towards or away from the target, and a key frames
 * the whole scene's bounding sphere. It is not a second camera: its yaw and
 * pitch are the scene camera's own, and only the target and the distance
 * are kept here; every change writes the camera's position as
 *
 *     position = target - distance * front(yaw, pitch)
 *
 * so the camera (luz_camera, SCENE.md's position, yaw and pitch) is always
 * what is drawn, and F2 and --print-state save the orbit's view as the
 * usual camera keys (camera-pos, camera-yaw, camera-pitch) that luz-render
 * reproduces exactly.
 *
 * tests/test_orbit.c checks every function against values worked out by
 * hand, without a window.
 */
#ifndef LUZ_APP_ORBIT_H
#define LUZ_APP_ORBIT_H

#include "app/controls.h"
#include "lab/scene.h"

#define LUZ_ORBIT_DEGREES_PER_PIXEL 0.25f   /* a drag across 360 pixels: 90 degrees */
#define LUZ_ORBIT_DOLLY_STEP 0.9            /* a wheel notch away from you: distance x 0.9 */
/* The distance stays within [0.2, 50]: twice the near plane's 0.1, so the
 * target itself is never clipped and the eye never reaches or passes it,
 * and half the far plane's 100, so the target stays well in sight. */
#define LUZ_ORBIT_MIN_DISTANCE 0.2
#define LUZ_ORBIT_MAX_DISTANCE 50.0

/* The target, in double precision: the camera's float position is worked
 * out from it and back (luz_orbit_from_camera, luz_orbit_place) to the
 * bit, so switching to the orbit camera moves nothing. */
typedef struct luz_orbit {
    double target[3];
    double distance;   /* within [LUZ_ORBIT_MIN_DISTANCE, LUZ_ORBIT_MAX_DISTANCE] */
} luz_orbit;

typedef struct luz_sphere {
    luz_vec3 centre;
    float radius;
} luz_sphere;

/* The sphere round everything the scene draws of its own: every cube
 * (radius sqrt(3)/2 round its position: the unit cube turns about its
 * centre) and every model (radius k |h|, h the half-sides of its
 * normalised box, which is centred on the object's position and turns
 * about it). Its centre is the centre of the box round those objects'
 * spheres, its radius the largest distance from there to an object's
 * centre plus that object's radius: not the smallest sphere, but one that
 * holds them all whatever the time. The point light's marker, which
 * circles the origin at radius 3, is a light, not part of the scene, and
 * is left out. A scene of no objects gives the unit sphere at the origin. */
luz_sphere luz_scene_bounding_sphere(const luz_scene *scene);

/* The orbit round the point on the camera's line of sight nearest to
 * `centre` (the scene's centre), at least LUZ_ORBIT_MIN_DISTANCE and at
 * most LUZ_ORBIT_MAX_DISTANCE ahead: the view does not change, and the
 * drag then turns round what is in front of the camera. */
luz_orbit luz_orbit_from_camera(const luz_camera *camera, luz_vec3 centre);

/* Writes camera->position = target - distance * front for the camera's
 * own yaw and pitch, keeping each coordinate within
 * +-LUZ_SCENE_MAX_COORDINATE (the options' range, so that a saved view
 * reads back) by shortening the distance if it must. */
void luz_orbit_place(luz_orbit *orbit, luz_camera *camera);

/* A drag of dx, dy pixels (y down): yaw += dx * 0.25, pitch -= dy * 0.25,
 * the pitch within [-89, 89] as the fly camera's (so front is never
 * parallel to the world's up and the view stays defined), then placed:
 * the eye turns round the target, which stays in the middle of the view.
 * Dragging right moves the eye left round the target, so the scene turns
 * with the mouse. */
void luz_orbit_turn(luz_orbit *orbit, luz_camera *camera, float dx, float dy);

/* The wheel: `notches` towards the target (SDL's wheel y: positive away
 * from the user) multiply the distance by 0.9 each, within
 * [LUZ_ORBIT_MIN_DISTANCE, LUZ_ORBIT_MAX_DISTANCE]; the target stays. */
void luz_orbit_dolly(luz_orbit *orbit, luz_camera *camera, float notches);

/* The motion keys while orbiting: the camera moves as it flies
 * (luz_camera_move) and carries the target along. */
void luz_orbit_move(luz_orbit *orbit, luz_camera *camera, luz_motion motion, float seconds);

/* The distance at which a sphere of `radius` just fits a view of vertical
 * field of view fov_degrees and aspect width / height:
 * radius / sin(a), a the smaller of the vertical half-angle fov / 2 and the
 * horizontal one atan(aspect tan(fov / 2)). At that distance the sphere
 * touches the view's two nearer sides and lies inside the other two. */
double luz_orbit_fit_distance(float radius, float fov_degrees, float aspect);

/* The frame key: the target at the sphere's centre, at the distance that
 * fits it (within the distance's range), the direction kept. */
void luz_orbit_frame(luz_orbit *orbit, luz_camera *camera, luz_sphere sphere, float aspect);

#endif
