/*
 * lanes_scalar.c: the scalar set's geometry kernels (cpu.h): setup "in
 * lanes" and the position-only vertex pass, one triangle or vertex at a
 * time, made of the scalar reference's own functions (vertex.c's
 * luz_vertex_stage_one, setup.c's luz_setup_project_vertex and
 * luz_setup_projected).
 *
 * In, out: luz_setup_eight_function's and luz_vertex_project_function's
 * (pipeline.h), with one difference: this setup does not rely on
 * screening (the scalar set screens nothing, luz_screen_every_triangle),
 * so it drops back faces and tests small boxes itself, as setup does.
 *
 * Why: the data flow of the wider sets, position-only shading, is what
 * keeps a big mesh's vertex pass to its snapped positions (8 bytes a
 * vertex where one at a time it keeps a clip and a window vertex, 100):
 * the 1M sphere's renderer holds about 77 bytes a triangle instead of 128
 * under every set. Plain C on any CPU: no vector, no intrinsic.
 */
#include <stdint.h>

#include "renderer/pipeline.h"

luz_setup_eight_function luz_setup_eight_scalar;
luz_vertex_project_function luz_vertex_project_scalar;

/* A vertex the vertex pass marked (outside a clip plane, or not
 * projected): its x is a marker, below every snapped coordinate. */
static bool marked(luz_fixed_vertex vertex)
{
    return vertex.x < -(1 << 24);
}

/* The corners shaded for one call's eight triangles. Neighbours in an
 * index buffer share vertices (two of three, in a strip-ordered mesh), so
 * a vertex shaded for one triangle is kept for the next: each is shaded
 * once a call, not once a triangle. A vertex's shading is a function of
 * its index alone, so taking it from here changes no bit. */
typedef struct corner_cache {
    int count;
    uint32_t index[24];
    luz_clip_vertex clip[24];
    luz_window_vertex window[24];
} corner_cache;

/* Where in cache vertex index is, shaded and projected: no corner of
 * these triangles is marked, so each is inside every clip plane, as the
 * vertex pass found, and projected as the lanes project it; its snapped
 * position is the vertex pass's (the same, from the same vertex). */
static int shade_corner(corner_cache *cache, const luz_draw_transform *transform,
                        uint32_t index, const luz_fixed_vertex *fixed, int width, int height)
{
    for (int at = 0; at < cache->count; at++)
        if (cache->index[at] == index) return at;
    const int at = cache->count++;
    cache->index[at] = index;
    cache->clip[at] = luz_vertex_stage_one(transform, index);
    cache->clip[at].outcode = 0;
    cache->window[at] = luz_setup_project_vertex(&cache->clip[at], width, height);
    cache->window[at].fixed_x = fixed[index].x;
    cache->window[at].fixed_y = fixed[index].y;
    return at;
}

bool luz_setup_eight_scalar(const uint32_t *indices, const uint32_t triangles[8],
                            const luz_draw_transform *transform, const luz_fixed_vertex *fixed,
                            int width, int height, uint32_t draw_index,
                            luz_interpolation interpolation, luz_triangle out[8],
                            luz_setup_result result[8])
{
    /* A marked vertex leaves all eight to the caller, before any record is
     * written (as setup_eight.c). */
    for (int lane = 0; lane < 8; lane++)
        for (int k = 0; k < 3; k++)
            if (marked(fixed[indices[3 * (size_t)triangles[lane] + (size_t)k]])) return true;
    corner_cache cache;
    cache.count = 0;
    for (int lane = 0; lane < 8; lane++) {
        const uint32_t *corner = &indices[3 * (size_t)triangles[lane]];
        /* Setup's verdicts before the planes (a back face; no pixel centre
         * in the box, or none covered in a small box) read the snapped
         * positions alone: taken from them first, before the corners are
         * shaded. Past them, these vertices (no clip vertex, no window
         * position: setup cannot solve their planes) give CULLED, and the
         * triangle is set up from its shaded corners below. */
        static const luz_clip_vertex unshaded = {0};
        luz_window_vertex snapped[3];
        for (int k = 0; k < 3; k++)
            snapped[k] = (luz_window_vertex){.fixed_x = fixed[corner[k]].x,
                                             .fixed_y = fixed[corner[k]].y};
        if (!luz_setup_front_facing(&snapped[0], &snapped[1], &snapped[2])) {
            result[lane] = LUZ_SETUP_CULLED;
            continue;
        }
        luz_triangle scratch;
        if (luz_setup_projected(&unshaded, &unshaded, &unshaded, &snapped[0], &snapped[1],
                                &snapped[2], width, height, draw_index, interpolation, false,
                                &scratch) == LUZ_SETUP_OFFSCREEN) {
            result[lane] = LUZ_SETUP_OFFSCREEN;
            continue;
        }
        luz_clip_vertex shaded[3];
        luz_window_vertex projected[3];
        for (int k = 0; k < 3; k++) {
            const int at = shade_corner(&cache, transform, corner[k], fixed, width, height);
            shaded[k] = cache.clip[at];
            projected[k] = cache.window[at];
        }
        /* small_box_checked: the test above found a centre in its box
         * (any box of up to LUZ_SETUP_SMALL_BOX_PIXELS), so that setup
         * need not look again in a box of 2 x 2. */
        result[lane] = luz_setup_projected(&shaded[0], &shaded[1], &shaded[2], &projected[0],
                                           &projected[1], &projected[2], width, height,
                                           draw_index, interpolation, true, &out[lane]);
    }
    return false;
}

void luz_vertex_project_scalar(const luz_draw *draw, luz_mat4 view_projection, uint32_t first,
                               uint32_t end, int width, int height, luz_clip_vertex *out,
                               luz_window_vertex *window, luz_fixed_vertex *fixed)
{
    if (first >= end) return;
    const luz_draw_transform transform = luz_draw_transform_of(draw, view_projection);
    for (uint32_t i = first; i < end; i++) {
        const luz_clip_vertex vertex = luz_vertex_stage_one(&transform, i);
        const luz_window_vertex projected = luz_setup_project_vertex(&vertex, width, height);
        if (out != NULL) out[i] = vertex;
        if (window != NULL) window[i] = projected;
        if (fixed != NULL) fixed[i] = (luz_fixed_vertex){projected.fixed_x, projected.fixed_y};
    }
}
