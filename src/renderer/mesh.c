/*
 * mesh.c: the meshes a frame draws, and the frame's list of draws.
 */
#include <limits.h>
#include <stdlib.h>

#include "luz/frame.h"

/* A mesh the pipeline can read: every index names one of its vertices. */
static bool mesh_is_valid(const luz_mesh *mesh)
{
    if (mesh == NULL || mesh->vertices == NULL || mesh->vertex_count < 0 ||
        mesh->index_count < 0 || mesh->index_count % 3 != 0 ||
        (mesh->index_count > 0 && mesh->indices == NULL))
        return false;
    for (int i = 0; i < mesh->index_count; i++)
        if (mesh->indices[i] >= mesh->vertex_count) return false;
    return true;
}

int luz_frame_add_draw(luz_frame *frame, const luz_draw *draw)
{
    if (!mesh_is_valid(draw->mesh)) return -1;
    if (frame->draw_count == frame->draw_capacity) {
        if (frame->draw_capacity > INT_MAX / 2) return -1;
        int capacity = frame->draw_capacity ? frame->draw_capacity * 2 : 16;
        luz_draw *draws = realloc(frame->draws, (size_t)capacity * sizeof *draws);
        if (!draws) return -1;
        frame->draws = draws;
        frame->draw_capacity = capacity;
    }
    frame->draws[frame->draw_count++] = *draw;
    return 0;
}

void luz_frame_free(luz_frame *frame)
{
    free(frame->draws);
    frame->draws = NULL;
    frame->draw_count = frame->draw_capacity = 0;
}
