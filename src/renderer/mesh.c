/*
 * mesh.c: meshes, made and checked once; and the frame's list of draws.
 *
 * In:  the caller's vertex and index arrays (luz_mesh_desc).
 * Out: a luz_mesh that owns copies of them, with 32-bit indices and its
 *      bounds, which the pipeline then reads without checking anything:
 *      every index names a vertex, every position is finite.
 *
 * The checks live here, not in luz_frame_add_draw, so that a mesh drawn in
 * a thousand frames is checked once (a million-triangle mesh takes about a
 * millisecond to check).
 */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "renderer/pipeline.h"

static bool is_finite_vec3(luz_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

luz_mesh *luz_mesh_create(const luz_mesh_desc *desc, luz_error *error)
{
    const luz_mesh_desc empty = {0};
    if (desc == NULL) desc = &empty;
    const bool indexed = desc->indices != NULL || desc->indices16 != NULL;
    const uint32_t vertex_count = desc->vertex_count;
    const uint32_t index_count = indexed ? desc->index_count : vertex_count;

    /* The shape of the arrays. */
    if (desc->indices != NULL && desc->indices16 != NULL) {
        luz_error_set(error, "mesh: both indices and indices16 given; expected one of them");
        return NULL;
    }
    if (vertex_count > 0 && desc->vertices == NULL) {
        luz_error_set(error, "mesh: %u vertices but no vertex array", (unsigned)vertex_count);
        return NULL;
    }
    if (!indexed && desc->index_count != 0) {
        luz_error_set(error, "mesh: index_count %u but no index array",
                      (unsigned)desc->index_count);
        return NULL;
    }
    if (index_count % 3 != 0) {
        luz_error_set(error, "mesh: %u %s, expected a multiple of 3 (three a triangle)",
                      (unsigned)index_count, indexed ? "indices" : "vertices and no indices");
        return NULL;
    }
    if (vertex_count > LUZ_MESH_MAX_VERTICES || index_count / 3 > LUZ_MESH_MAX_TRIANGLES) {
        luz_error_set(error, "mesh: %u vertices and %u triangles, expected at most %u of each",
                      (unsigned)vertex_count, (unsigned)(index_count / 3),
                      (unsigned)LUZ_MESH_MAX_VERTICES);
        return NULL;
    }

    /* Positions: finite, or clipping and setup would read NaN. */
    luz_bounds bounds = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    for (uint32_t i = 0; i < vertex_count; i++) {
        const luz_vec3 p = desc->vertices[i].position;
        if (!is_finite_vec3(p)) {
            luz_error_set(error, "mesh: vertex %u has a position that is not finite",
                          (unsigned)i);
            return NULL;
        }
        if (i == 0) bounds.min = bounds.max = p;
        bounds.min = (luz_vec3){fminf(bounds.min.x, p.x), fminf(bounds.min.y, p.y),
                                fminf(bounds.min.z, p.z)};
        bounds.max = (luz_vec3){fmaxf(bounds.max.x, p.x), fmaxf(bounds.max.y, p.y),
                                fmaxf(bounds.max.z, p.z)};
    }

    luz_mesh *mesh = calloc(1, sizeof *mesh);
    if (mesh != NULL) {
        mesh->vertices = malloc((size_t)vertex_count * sizeof *mesh->vertices + 1);
        mesh->indices = malloc((size_t)index_count * sizeof *mesh->indices + 1);
    }
    if (mesh == NULL || mesh->vertices == NULL || mesh->indices == NULL) {
        luz_mesh_destroy(mesh);
        luz_error_set(error, "mesh: out of memory for %u vertices and %u indices",
                      (unsigned)vertex_count, (unsigned)index_count);
        return NULL;
    }
    if (vertex_count > 0)
        memcpy(mesh->vertices, desc->vertices, (size_t)vertex_count * sizeof *mesh->vertices);
    mesh->vertex_count = vertex_count;
    mesh->index_count = index_count;
    mesh->bounds = bounds;

    /* Indices: every one names a vertex. */
    for (uint32_t i = 0; i < index_count; i++) {
        const uint32_t index = desc->indices     ? desc->indices[i]
                               : desc->indices16 ? desc->indices16[i]
                                                 : i;
        if (index >= vertex_count) {
            luz_error_set(error, "mesh: index %u is %u, past the last of %u vertices",
                          (unsigned)i, (unsigned)index, (unsigned)vertex_count);
            luz_mesh_destroy(mesh);
            return NULL;
        }
        mesh->indices[i] = index;
    }
    return mesh;
}

void luz_mesh_destroy(luz_mesh *mesh)
{
    if (mesh == NULL) return;
    free(mesh->vertices);
    free(mesh->indices);
    free(mesh);
}

uint32_t luz_mesh_vertex_count(const luz_mesh *mesh)
{
    return mesh->vertex_count;
}

uint32_t luz_mesh_triangle_count(const luz_mesh *mesh)
{
    return mesh->index_count / 3;
}

luz_bounds luz_mesh_bounds(const luz_mesh *mesh)
{
    return mesh->bounds;
}

/* ---- the frame's draws ---------------------------------------------------- */

int luz_frame_add_draw(luz_frame *frame, const luz_draw *draw, luz_error *error)
{
    if (draw->mesh == NULL)
        return luz_error_set(error, "draw %d: no mesh", frame->draw_count);
    if (frame->draw_count < 0 || (frame->draw_count > 0 && frame->draws == NULL))
        return luz_error_set(error, "frame: %d draws but no draw array", frame->draw_count);
    if (frame->draw_count >= frame->draw_capacity) {
        if (frame->draw_count > INT_MAX / 2)
            return luz_error_set(error, "draw %d: more draws than a frame holds",
                                 frame->draw_count);
        int capacity = frame->draw_count ? frame->draw_count * 2 : 16;
        /* An array of the caller's (draw_capacity 0) is copied, never
         * realloc'ed or freed: luz/frame.h's rule of who owns what. */
        const bool own = frame->draw_capacity > 0;
        luz_draw *draws = realloc(own ? frame->draws : NULL, (size_t)capacity * sizeof *draws);
        if (!draws)
            return luz_error_set(error, "draw %d: out of memory for the frame's draws",
                                 frame->draw_count);
        if (!own && frame->draw_count > 0)
            memcpy(draws, frame->draws, (size_t)frame->draw_count * sizeof *draws);
        frame->draws = draws;
        frame->draw_capacity = capacity;
    }
    frame->draws[frame->draw_count++] = *draw;
    return 0;
}

void luz_frame_free(luz_frame *frame)
{
    if (frame->draw_capacity > 0) free(frame->draws);   /* else the caller's */
    frame->draws = NULL;
    frame->draw_count = frame->draw_capacity = 0;
}
