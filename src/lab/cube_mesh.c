/*
 * cube_mesh.c: the unit cube of SCENE.md, as its table gives it.
 *
 * 24 vertices, 4 per face, so that each face has its own normal and its own
 * texture coordinates. v = 0 is the top row of the image file, so the
 * texture stands upright on the four side faces seen from outside. Face k
 * has the counter-clockwise triangles (4k, 4k+1, 4k+2) and (4k, 4k+2, 4k+3).
 */
#include "lab/scene.h"

#define FACE(nx, ny, nz, ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz)            \
    {{ax, ay, az}, {nx, ny, nz}, {0, 1}}, {{bx, by, bz}, {nx, ny, nz}, {1, 1}},      \
    {{cx, cy, cz}, {nx, ny, nz}, {1, 0}}, {{dx, dy, dz}, {nx, ny, nz}, {0, 0}}

static const luz_vertex cube_vertices[24] = {
    /*      normal     v0 (uv 0,1)      v1 (uv 1,1)      v2 (uv 1,0)      v3 (uv 0,0) */
    FACE( 0, 0, 1,  -.5f,-.5f, .5f,   .5f,-.5f, .5f,   .5f, .5f, .5f,  -.5f, .5f, .5f), /* +Z */
    FACE( 0, 0,-1,   .5f,-.5f,-.5f,  -.5f,-.5f,-.5f,  -.5f, .5f,-.5f,   .5f, .5f,-.5f), /* -Z */
    FACE( 1, 0, 0,   .5f,-.5f, .5f,   .5f,-.5f,-.5f,   .5f, .5f,-.5f,   .5f, .5f, .5f), /* +X */
    FACE(-1, 0, 0,  -.5f,-.5f,-.5f,  -.5f,-.5f, .5f,  -.5f, .5f, .5f,  -.5f, .5f,-.5f), /* -X */
    FACE( 0, 1, 0,  -.5f, .5f, .5f,   .5f, .5f, .5f,   .5f, .5f,-.5f,  -.5f, .5f,-.5f), /* +Y */
    FACE( 0,-1, 0,  -.5f,-.5f,-.5f,   .5f,-.5f,-.5f,   .5f,-.5f, .5f,  -.5f,-.5f, .5f), /* -Y */
};

#define FACE_TRIANGLES(k) 4 * k, 4 * k + 1, 4 * k + 2, 4 * k, 4 * k + 2, 4 * k + 3

static const uint16_t cube_indices[36] = {
    FACE_TRIANGLES(0), FACE_TRIANGLES(1), FACE_TRIANGLES(2),
    FACE_TRIANGLES(3), FACE_TRIANGLES(4), FACE_TRIANGLES(5),
};

luz_mesh *luz_cube_mesh_create(luz_error *error)
{
    return luz_mesh_create(&(luz_mesh_desc){.vertices = cube_vertices,
                                            .vertex_count = 24,
                                            .indices16 = cube_indices,
                                            .index_count = 36},
                           error);
}
