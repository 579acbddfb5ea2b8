/*
 * luz/mesh.h: meshes, the geometry a draw refers to.
 *
 * A luz_mesh is an indexed triangle list made once from the caller's
 * arrays, which it copies: the caller may free or reuse them as soon as
 * luz_mesh_create returns. It is checked once, there (every index names a
 * vertex, every position is finite, the counts are within the limits
 * below), and its bounds are computed once, so that drawing it, frame
 * after frame, checks nothing. A mesh is read-only after creation: any
 * number of frames, draws and renderers may use it at once.
 *
 *     luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){
 *         .vertices = vertices, .vertex_count = 24,
 *         .indices = indices, .index_count = 36,
 *     }, &error);
 *
 * Counter-clockwise triangles (seen from outside) are front faces; back
 * faces are culled.
 */
#ifndef LUZ_MESH_H
#define LUZ_MESH_H

#include <stdint.h>

#include "luz/api.h"
#include "luz/error.h"
#include "luz/vecmath.h"

/* The largest mesh: 2^28 vertices and 2^28 triangles. The renderer keeps
 * 48 bytes of vertex-stage output per vertex and numbers a frame's
 * triangles with 32-bit ids, so these bound both. */
#define LUZ_MESH_MAX_VERTICES (1u << 28)
#define LUZ_MESH_MAX_TRIANGLES (1u << 28)

typedef struct luz_vertex {
    luz_vec3 position;  /* object space */
    luz_vec3 normal;    /* object space; need not be unit length: the
                           fragment stage normalises after interpolation */
    luz_vec2 uv;        /* texture coordinates; v = 0 is the image's top row */
} luz_vertex;

/* A zero desc is an empty mesh (it draws nothing). */
typedef struct luz_mesh_desc {
    const luz_vertex *vertices;
    uint32_t vertex_count;
    /* Three indices a triangle, as 32-bit or (as glTF allows) 16-bit
     * numbers: give one of the two arrays, or neither, and then the
     * vertices themselves are taken three at a time. */
    const uint32_t *indices;
    const uint16_t *indices16;
    uint32_t index_count;     /* a multiple of 3 */
} luz_mesh_desc;

typedef struct luz_bounds {
    luz_vec3 min, max;        /* both 0 for an empty mesh */
} luz_bounds;

typedef struct luz_mesh luz_mesh;

/* Returns the new mesh, or NULL with the reason in error (NULL desc means
 * the zero desc). */
LUZ_API luz_mesh *luz_mesh_create(const luz_mesh_desc *desc, luz_error *error);
LUZ_API void luz_mesh_destroy(luz_mesh *mesh);

LUZ_API uint32_t luz_mesh_vertex_count(const luz_mesh *mesh);
LUZ_API uint32_t luz_mesh_triangle_count(const luz_mesh *mesh);
/* The box around every vertex position, in object space. */
LUZ_API luz_bounds luz_mesh_bounds(const luz_mesh *mesh);

#endif
