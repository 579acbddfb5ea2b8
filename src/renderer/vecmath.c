/*
 * vecmath.c: 4x4 matrices with OpenGL's conventions (see luz/vecmath.h).
 *
 * The formulas are those of the OpenGL reference pages for gluLookAt and
 * gluPerspective, and of gl-matrix's mat4.rotate (Rodrigues' rotation
 * formula); the matrices are column-major, element (row r, column c) at
 * m[c * 4 + r].
 */
#include "luz/vecmath.h"

#define AT(matrix, row, column) ((matrix).m[(column) * 4 + (row)])

luz_mat4 luz_mat4_identity(void)
{
    luz_mat4 result = {{0}};
    AT(result, 0, 0) = AT(result, 1, 1) = AT(result, 2, 2) = AT(result, 3, 3) = 1.0f;
    return result;
}

luz_mat4 luz_mat4_multiply(luz_mat4 a, luz_mat4 b)
{
    luz_mat4 result;
    for (int column = 0; column < 4; column++) {
        for (int row = 0; row < 4; row++) {
            float sum = 0.0f;
            for (int k = 0; k < 4; k++) sum += AT(a, row, k) * AT(b, k, column);
            AT(result, row, column) = sum;
        }
    }
    return result;
}

luz_mat4 luz_mat4_translate(luz_mat4 m, luz_vec3 offset)
{
    luz_mat4 translation = luz_mat4_identity();
    AT(translation, 0, 3) = offset.x;
    AT(translation, 1, 3) = offset.y;
    AT(translation, 2, 3) = offset.z;
    return luz_mat4_multiply(m, translation);
}

luz_mat4 luz_mat4_scale(luz_mat4 m, luz_vec3 factors)
{
    luz_mat4 scaling = luz_mat4_identity();
    AT(scaling, 0, 0) = factors.x;
    AT(scaling, 1, 1) = factors.y;
    AT(scaling, 2, 2) = factors.z;
    return luz_mat4_multiply(m, scaling);
}

/* Rodrigues: R = c I + (1 - c) a a^T + s [a]x, for the unit axis a. */
luz_mat4 luz_mat4_rotate(luz_mat4 m, float angle_radians, luz_vec3 axis)
{
    luz_vec3 a = luz_vec3_normalize(axis);
    float s = sinf(angle_radians), c = cosf(angle_radians), t = 1.0f - c;
    luz_mat4 rotation = luz_mat4_identity();
    AT(rotation, 0, 0) = a.x * a.x * t + c;
    AT(rotation, 1, 0) = a.y * a.x * t + a.z * s;
    AT(rotation, 2, 0) = a.z * a.x * t - a.y * s;
    AT(rotation, 0, 1) = a.x * a.y * t - a.z * s;
    AT(rotation, 1, 1) = a.y * a.y * t + c;
    AT(rotation, 2, 1) = a.z * a.y * t + a.x * s;
    AT(rotation, 0, 2) = a.x * a.z * t + a.y * s;
    AT(rotation, 1, 2) = a.y * a.z * t - a.x * s;
    AT(rotation, 2, 2) = a.z * a.z * t + c;
    return luz_mat4_multiply(m, rotation);
}

/* gluLookAt: the rows of the rotation are the camera's right, up and back
 * axes; the translation moves the eye to the origin. */
luz_mat4 luz_mat4_look_at(luz_vec3 eye, luz_vec3 centre, luz_vec3 up)
{
    luz_vec3 back = luz_vec3_normalize(luz_vec3_sub(eye, centre));
    luz_vec3 right = luz_vec3_normalize(luz_vec3_cross(up, back));
    luz_vec3 true_up = luz_vec3_cross(back, right);
    luz_mat4 result = luz_mat4_identity();
    AT(result, 0, 0) = right.x;   AT(result, 0, 1) = right.y;   AT(result, 0, 2) = right.z;
    AT(result, 1, 0) = true_up.x; AT(result, 1, 1) = true_up.y; AT(result, 1, 2) = true_up.z;
    AT(result, 2, 0) = back.x;    AT(result, 2, 1) = back.y;    AT(result, 2, 2) = back.z;
    AT(result, 0, 3) = -luz_vec3_dot(right, eye);
    AT(result, 1, 3) = -luz_vec3_dot(true_up, eye);
    AT(result, 2, 3) = -luz_vec3_dot(back, eye);
    return result;
}

/* gluPerspective: maps the view frustum to the clip cube, z_ndc = -1 at
 * the near plane and +1 at the far plane, w_clip = -z_eye. */
luz_mat4 luz_mat4_perspective(float fovy_radians, float aspect, float near, float far)
{
    float f = 1.0f / tanf(fovy_radians / 2.0f);
    luz_mat4 result = {{0}};
    AT(result, 0, 0) = f / aspect;
    AT(result, 1, 1) = f;
    AT(result, 2, 2) = (far + near) / (near - far);
    AT(result, 2, 3) = 2.0f * far * near / (near - far);
    AT(result, 3, 2) = -1.0f;
    return result;
}

luz_vec4 luz_mat4_transform(luz_mat4 m, luz_vec4 v)
{
    return (luz_vec4){
        AT(m, 0, 0) * v.x + AT(m, 0, 1) * v.y + AT(m, 0, 2) * v.z + AT(m, 0, 3) * v.w,
        AT(m, 1, 0) * v.x + AT(m, 1, 1) * v.y + AT(m, 1, 2) * v.z + AT(m, 1, 3) * v.w,
        AT(m, 2, 0) * v.x + AT(m, 2, 1) * v.y + AT(m, 2, 2) * v.z + AT(m, 2, 3) * v.w,
        AT(m, 3, 0) * v.x + AT(m, 3, 1) * v.y + AT(m, 3, 2) * v.z + AT(m, 3, 3) * v.w,
    };
}

luz_vec3 luz_mat4_transform_point(luz_mat4 m, luz_vec3 p)
{
    luz_vec4 q = luz_mat4_transform(m, (luz_vec4){p.x, p.y, p.z, 1.0f});
    return (luz_vec3){q.x, q.y, q.z};
}

/* The inverse transpose by cofactors: inverse(A)^T = cofactor(A) / det(A).
 * Normals transform with it so that they stay perpendicular to surfaces
 * under non-uniform scaling; for the rigid motions of the scene it equals
 * the 3x3 itself. */
luz_mat3 luz_mat3_normal_matrix(luz_mat4 m)
{
    float a = AT(m, 0, 0), b = AT(m, 0, 1), c = AT(m, 0, 2);
    float d = AT(m, 1, 0), e = AT(m, 1, 1), f = AT(m, 1, 2);
    float g = AT(m, 2, 0), h = AT(m, 2, 1), i = AT(m, 2, 2);
    float cofactor[3][3] = {
        {e * i - f * h, f * g - d * i, d * h - e * g},
        {c * h - b * i, a * i - c * g, b * g - a * h},
        {b * f - c * e, c * d - a * f, a * e - b * d},
    };
    float determinant = a * cofactor[0][0] + b * cofactor[0][1] + c * cofactor[0][2];
    luz_mat3 result;
    if (determinant == 0.0f || !isfinite(determinant)) {
        for (int column = 0; column < 3; column++)
            for (int row = 0; row < 3; row++) result.m[column * 3 + row] = AT(m, row, column);
        return result;
    }
    /* cofactor[row][column] of A is element (row, column) of inverse(A)^T
     * times det(A). */
    for (int column = 0; column < 3; column++)
        for (int row = 0; row < 3; row++)
            result.m[column * 3 + row] = cofactor[row][column] / determinant;
    return result;
}

luz_vec3 luz_mat3_transform(luz_mat3 m, luz_vec3 v)
{
    return (luz_vec3){
        m.m[0] * v.x + m.m[3] * v.y + m.m[6] * v.z,
        m.m[1] * v.x + m.m[4] * v.y + m.m[7] * v.z,
        m.m[2] * v.x + m.m[5] * v.y + m.m[8] * v.z,
    };
}
