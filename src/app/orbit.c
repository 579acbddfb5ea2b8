/*
 * orbit.c: the viewer's orbit camera (see app/orbit.h).
 *
 * In:  the scene camera (position, yaw, pitch, field of view), a target and
 *      a distance, and the user's drag, wheel and keys; the scene's objects
 *      for the frame key.
 * Out: the scene camera's position, yaw and pitch, which is all that is
 *      drawn and saved: the orbit is a way of moving the fly camera, not a
 *      camera of its own.
 *
 * The eye sits at target - distance * front, so the target is on the line
 * of sight at the given distance. The target and the distance are kept in
 * double precision: the float position computed from them, and the target
 * computed back from a float position, agree to the bit (a float's 24 bits
 * survive the round trip through 53), so switching from flying to the
 * orbit camera leaves the picture exactly as it was.
 */
#include "app/orbit.h"

#include <math.h>
#include <stddef.h>

static double clamp_double(double value, double low, double high)
{
    return value < low ? low : value > high ? high : value;
}

/* ---- the scene's bounding sphere ------------------------------------------------ */

/* The radius round an object's position that holds it at any angle. */
static double object_radius(const luz_object *object)
{
    if (object == NULL || object->model == NULL)
        return 0.5 * sqrt(3.0);   /* the unit cube's half-diagonal */
    /* Norm (SCENE.md, "Models") centres the box and divides by its largest
     * side s, so its half-sides become (max - min) / s; Scale(k) follows. */
    const luz_bounds b = object->model->bounds;
    const double sides[3] = {(double)b.max.x - b.min.x, (double)b.max.y - b.min.y,
                             (double)b.max.z - b.min.z};
    double s = fmax(sides[0], fmax(sides[1], sides[2]));
    if (!(s > 0.0))
        return 0.0;
    const double k = object->scale > 0.0f ? object->scale : 1.0;
    const double hx = sides[0] / s, hy = sides[1] / s, hz = sides[2] / s;
    return k * sqrt(hx * hx + hy * hy + hz * hz);
}

static luz_vec3 object_position(const luz_scene *scene, int i)
{
    return scene->objects ? scene->objects[i].position : luz_scene_tiled_position(i);
}

luz_sphere luz_scene_bounding_sphere(const luz_scene *scene)
{
    const int count = scene->objects ? scene->object_count : scene->cube_count;
    if (count <= 0)
        return (luz_sphere){{0.0f, 0.0f, 0.0f}, 1.0f};
    /* First the box round every object's sphere, then its centre. */
    double low[3] = {INFINITY, INFINITY, INFINITY};
    double high[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < count; i++) {
        const luz_vec3 p = object_position(scene, i);
        const double r = object_radius(scene->objects ? &scene->objects[i] : NULL);
        const double c[3] = {p.x, p.y, p.z};
        for (int axis = 0; axis < 3; axis++) {
            low[axis] = fmin(low[axis], c[axis] - r);
            high[axis] = fmax(high[axis], c[axis] + r);
        }
    }
    const double centre[3] = {0.5 * (low[0] + high[0]), 0.5 * (low[1] + high[1]),
                              0.5 * (low[2] + high[2])};
    /* Then the farthest object from that centre, its own radius added. */
    double radius = 0.0;
    for (int i = 0; i < count; i++) {
        const luz_vec3 p = object_position(scene, i);
        const double d[3] = {p.x - centre[0], p.y - centre[1], p.z - centre[2]};
        const double reach = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) +
                             object_radius(scene->objects ? &scene->objects[i] : NULL);
        radius = fmax(radius, reach);
    }
    /* Rounded up to a float, so the sphere still holds everything. */
    float r = (float)radius;
    if ((double)r < radius)
        r = nextafterf(r, INFINITY);
    return (luz_sphere){{(float)centre[0], (float)centre[1], (float)centre[2]}, r};
}

/* ---- the orbit -------------------------------------------------------------------------- */

luz_orbit luz_orbit_from_camera(const luz_camera *camera, luz_vec3 centre)
{
    const luz_vec3 front = luz_camera_front(camera);
    const luz_vec3 p = camera->position;
    /* The nearest point of the line of sight to the centre is
     * t = (centre - p) . front ahead (front is a unit vector). */
    double t = ((double)centre.x - p.x) * front.x + ((double)centre.y - p.y) * front.y +
               ((double)centre.z - p.z) * front.z;
    const double distance = clamp_double(t, LUZ_ORBIT_MIN_DISTANCE, LUZ_ORBIT_MAX_DISTANCE);
    return (luz_orbit){{p.x + distance * front.x, p.y + distance * front.y,
                        p.z + distance * front.z},
                       distance};
}

void luz_orbit_place(luz_orbit *orbit, luz_camera *camera)
{
    const luz_vec3 front = luz_camera_front(camera);
    const double f[3] = {front.x, front.y, front.z};
    const double limit = LUZ_SCENE_MAX_COORDINATE;
    double d = orbit->distance;
    /* Each coordinate target - d f must stay within [-limit, limit]. The
     * target is kept inside that range, so a shorter distance always
     * brings the eye back inside: for f > 0 the coordinate falls with d
     * and d <= (target + limit) / f keeps it above -limit; for f < 0,
     * d <= (limit - target) / -f keeps it below limit. */
    for (int axis = 0; axis < 3; axis++) {
        orbit->target[axis] = clamp_double(orbit->target[axis], -limit, limit);
        const double eye = orbit->target[axis] - d * f[axis];
        if (eye < -limit && f[axis] > 0.0)
            d = (orbit->target[axis] + limit) / f[axis];
        else if (eye > limit && f[axis] < 0.0)
            d = (limit - orbit->target[axis]) / -f[axis];
    }
    /* The eye, rounded to floats; the clamp only catches that rounding. */
    const float x = (float)(orbit->target[0] - d * f[0]);
    const float y = (float)(orbit->target[1] - d * f[1]);
    const float z = (float)(orbit->target[2] - d * f[2]);
    const float flimit = LUZ_SCENE_MAX_COORDINATE;
    camera->position = (luz_vec3){fminf(fmaxf(x, -flimit), flimit),
                                  fminf(fmaxf(y, -flimit), flimit),
                                  fminf(fmaxf(z, -flimit), flimit)};
}

void luz_orbit_turn(luz_orbit *orbit, luz_camera *camera, float dx, float dy)
{
    luz_camera_turn_degrees(camera, dx * LUZ_ORBIT_DEGREES_PER_PIXEL,
                            -dy * LUZ_ORBIT_DEGREES_PER_PIXEL);
    luz_orbit_place(orbit, camera);
}

void luz_orbit_dolly(luz_orbit *orbit, luz_camera *camera, float notches)
{
    const double scaled = orbit->distance * pow(LUZ_ORBIT_DOLLY_STEP, (double)notches);
    /* pow of a huge notch count is 0 or infinity, both clamped */
    orbit->distance = clamp_double(isnan(scaled) ? orbit->distance : scaled,
                                   LUZ_ORBIT_MIN_DISTANCE, LUZ_ORBIT_MAX_DISTANCE);
    luz_orbit_place(orbit, camera);
}

void luz_orbit_move(luz_orbit *orbit, luz_camera *camera, luz_motion motion, float seconds)
{
    const luz_vec3 before = camera->position;
    luz_camera_move(camera, motion, seconds);
    /* What the camera really moved (it stops at the coordinates' range),
     * so that the target stays at the same place relative to the eye. */
    orbit->target[0] += (double)camera->position.x - before.x;
    orbit->target[1] += (double)camera->position.y - before.y;
    orbit->target[2] += (double)camera->position.z - before.z;
}

double luz_orbit_fit_distance(float radius, float fov_degrees, float aspect)
{
    const double half_vertical = 0.5 * (double)fov_degrees * (LUZ_PI / 180.0);
    const double half_horizontal = atan((double)aspect * tan(half_vertical));
    const double half = fmin(half_vertical, half_horizontal);
    /* A sphere of radius r whose centre lies on the view's axis at
     * distance d is seen under the half-angle asin(r / d): it fits when
     * that is at most the view's half-angle, d >= r / sin(half). */
    return (double)radius / sin(half);
}

void luz_orbit_frame(luz_orbit *orbit, luz_camera *camera, luz_sphere sphere, float aspect)
{
    orbit->target[0] = sphere.centre.x;
    orbit->target[1] = sphere.centre.y;
    orbit->target[2] = sphere.centre.z;
    orbit->distance = clamp_double(luz_orbit_fit_distance(sphere.radius, camera->fov_degrees,
                                                          aspect),
                                   LUZ_ORBIT_MIN_DISTANCE, LUZ_ORBIT_MAX_DISTANCE);
    luz_orbit_place(orbit, camera);
}
