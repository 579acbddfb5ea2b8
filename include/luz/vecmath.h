/*
 * luz/vecmath.h: the small linear algebra the pipeline needs.
 *
 * Vectors of 3 and 4 floats and 4x4 matrices, with the conventions of
 * OpenGL and of the gl-matrix library the original WebGL practical used:
 *
 *   - matrices are column-major, m[column * 4 + row], and act on column
 *     vectors: clip = projection * view * model * position;
 *   - luz_mat4_translate(M, t) and luz_mat4_rotate(M, angle, axis) return
 *     M * T and M * R, as gl-matrix's mat4.translate and mat4.rotate do, so
 *     "translate then rotate" reads in the same order as the report's code;
 *   - luz_mat4_look_at and luz_mat4_perspective build gluLookAt's and
 *     gluPerspective's matrices (camera looking down -Z, clip z in [-w, w]).
 *
 * Everything is a pure function on values: no allocation, no state.
 */
#ifndef LUZ_VECMATH_H
#define LUZ_VECMATH_H

#include <math.h>

#include "luz/api.h"

typedef struct luz_vec2 { float x, y; } luz_vec2;
typedef struct luz_vec3 { float x, y, z; } luz_vec3;
typedef struct luz_vec4 { float x, y, z, w; } luz_vec4;

/* Column-major: element (row r, column c) is m[c * 4 + r]. */
typedef struct luz_mat4 { float m[16]; } luz_mat4;

/* A 3x3 matrix, column-major, used for transforming normals. */
typedef struct luz_mat3 { float m[9]; } luz_mat3;

#define LUZ_PI 3.14159265358979323846

static inline float luz_radians(float degrees) { return degrees * (float)(LUZ_PI / 180.0); }

static inline luz_vec3 luz_vec3_make(float x, float y, float z) { return (luz_vec3){x, y, z}; }
static inline luz_vec3 luz_vec3_add(luz_vec3 a, luz_vec3 b) { return (luz_vec3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline luz_vec3 luz_vec3_sub(luz_vec3 a, luz_vec3 b) { return (luz_vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline luz_vec3 luz_vec3_scale(luz_vec3 a, float s) { return (luz_vec3){a.x * s, a.y * s, a.z * s}; }
static inline luz_vec3 luz_vec3_mul(luz_vec3 a, luz_vec3 b) { return (luz_vec3){a.x * b.x, a.y * b.y, a.z * b.z}; }
static inline float luz_vec3_dot(luz_vec3 a, luz_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline luz_vec3 luz_vec3_cross(luz_vec3 a, luz_vec3 b)
{
    return (luz_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static inline float luz_vec3_length(luz_vec3 a) { return sqrtf(luz_vec3_dot(a, a)); }

/* GLSL's normalize(); the zero vector stays zero instead of becoming NaN. */
static inline luz_vec3 luz_vec3_normalize(luz_vec3 a)
{
    float length = luz_vec3_length(a);
    return length > 0.0f ? luz_vec3_scale(a, 1.0f / length) : a;
}

LUZ_API luz_mat4 luz_mat4_identity(void);
LUZ_API luz_mat4 luz_mat4_multiply(luz_mat4 a, luz_mat4 b);           /* a * b */
LUZ_API luz_mat4 luz_mat4_translate(luz_mat4 m, luz_vec3 offset);     /* m * T(offset) */
LUZ_API luz_mat4 luz_mat4_scale(luz_mat4 m, luz_vec3 factors);        /* m * S(factors) */
/* m * R, R the right-handed rotation by angle_radians about axis (any
         * non-zero length; normalised here as gl-matrix does). */
LUZ_API luz_mat4 luz_mat4_rotate(luz_mat4 m, float angle_radians, luz_vec3 axis);
LUZ_API luz_mat4 luz_mat4_look_at(luz_vec3 eye, luz_vec3 centre, luz_vec3 up);
LUZ_API luz_mat4 luz_mat4_perspective(float fovy_radians, float aspect, float near, float far);
LUZ_API luz_vec4 luz_mat4_transform(luz_mat4 m, luz_vec4 v);
LUZ_API luz_vec3 luz_mat4_transform_point(luz_mat4 m, luz_vec3 p);    /* w = 1, no divide */

/* The normal matrix: the inverse transpose of m's upper-left 3x3. Returns
         * the 3x3 itself if it is singular (nothing sensible can be done). */
LUZ_API luz_mat3 luz_mat3_normal_matrix(luz_mat4 m);
LUZ_API luz_vec3 luz_mat3_transform(luz_mat3 m, luz_vec3 v);

#endif
