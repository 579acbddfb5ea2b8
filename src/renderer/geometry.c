/*
 * geometry.c: phase 1 of a frame, geometry, spread over the threads.
 *
 * In:  the frame's draws (meshes and model matrices), its uniforms, the
 *      framebuffer's size and the height of phase 2's bands.
 * Out: every visible triangle set up (setup.c's luz_triangle), numbered
 *      1, 2, ... in submission order (draw by draw, triangle by triangle,
 *      fan triangle by fan triangle), and binned: for each band of rows,
 *      the ids of the triangles whose bounding box touches it, in id order.
 *
 * The work is cut into batches of about BATCH_TRIANGLES triangles whatever
 * the draws look like, so that one mesh of a million triangles keeps every
 * thread as busy as a hundred thousand cubes do:
 *
 *   cull         (parallel) a draw whose bounding box lies wholly outside
 *                one clip plane is dropped (clipping would reject each of
 *                its triangles)
 *   plan         (one thread) small draws go whole into batches,
 *                several to a batch; a big draw is cut into ranges of
 *                triangles, and its vertices get a place in the frame's
 *                vertex arena
 *   vertex pass  (parallel) the big draws' vertices, in ranges: the vertex
 *                stage, then setup's per-vertex projection, all kept; or,
 *                where setup and this pass both run in lanes (AVX-512),
 *                positions alone, of which only the snapped positions
 *                are kept, for screening: position-only shading, the
 *                corners that reach setup shaded there from the mesh
 *   batches      (parallel) each small draw's vertex stage and projection
 *                (into the thread's scratch), then clipping and setup of the batch's
 *                triangles; the batch counts its triangles per band
 *   number       (one thread) prefix sums: each batch's first id, and
 *                each batch's place in each band's list (a counting sort)
 *   bin          (parallel) each batch writes its ids into the bands' lists
 *
 * The serial steps are O(draws + batches x bands), not O(triangles). Ids,
 * and each band's list, follow the submission order whatever the batches
 * and the threads, so the image does not depend on them (frame.c).
 *
 * The records of a frame with many of them lie in one block, each batch's
 * in a slice the size it needed before, on 2 MB pages where the system
 * has them (place_records): the bands read them scattered, a few tens of
 * megabytes on a big mesh, which on 4 KB pages missed the TLB at nearly
 * every triangle.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "renderer/cpu.h"
#include "renderer/huge_pages.h"
#include "renderer/pipeline.h"

/* Triangles per batch of a big draw: enough work (about 0.2 ms) to be
 * worth a job, few enough that a million triangles make hundreds of
 * batches to balance over the threads. */
#define BATCH_TRIANGLES 2048
/* Small draws join a batch until it holds this many triangles: a batch of
 * about 40 cubes, whose vertex stage runs in the batch too (roughly 2
 * microseconds a cube), so that a hundred cubes still make three jobs. */
#define SMALL_DRAWS_BATCH 512
/* Vertices per job of the vertex pass. */
#define VERTEX_BATCH 8192
/* Records a frame must need (in the slices of the last frame's records,
 * slice_records) to be placed in one block of huge pages: 4 MB of them,
 * two huge pages. */
#define RECORD_BLOCK_MIN (((size_t)4 << 20) / sizeof(luz_triangle))

typedef struct geometry_batch {
    /* What the batch covers: whole draws [draw_first, draw_end), or
     * triangles [triangle_first, triangle_end) of the big draw draw_first,
     * whose snapped positions the vertex pass leaves at fixed (and,
     * unless it shades positions alone, its clip-space vertices at
     * vertices and their projection at window). */
    uint32_t draw_first, draw_end;
    uint32_t triangle_first, triangle_end;
    bool whole_draws;
    const luz_clip_vertex *vertices;   /* NULL with position-only shading:
                                          setup shades its corners itself */
    const luz_window_vertex *window;   /* the same vertices, projected (or
                                          NULL likewise) */
    const luz_fixed_vertex *fixed;     /* and their snapped positions alone */
    /* What it made, reused from frame to frame: its own array, or its
     * slice of the frame's block of records (in_block, place_records). */
    luz_triangle *triangles;
    size_t count, capacity;
    bool in_block;
    /* Per triangle, the bands its box touches, first | last << 16: what
     * binning reads, 4 bytes a triangle instead of the whole record. */
    uint32_t *band_ranges;
    size_t band_range_capacity;
    size_t first_id;
    uint64_t submitted, clipped, culled;
    bool out_of_memory;
} geometry_batch;

typedef struct vertex_range {
    uint32_t draw, first, end;
    luz_clip_vertex *out;          /* the draw's vertex 0 in the arena (or
                                      NULL: positions alone) */
    luz_window_vertex *window;     /* the same, projected (or NULL) */
    luz_fixed_vertex *fixed;       /* and snapped */
} vertex_range;

typedef struct vertex_scratch {
    luz_clip_vertex *vertices;
    luz_window_vertex *window;
    luz_fixed_vertex *fixed;
    uint32_t capacity;
} vertex_scratch;

struct luz_geometry {
    int thread_count;
    geometry_batch *batches;
    int batch_count, batch_capacity;
    vertex_range *vertex_ranges;
    size_t vertex_range_count, vertex_range_capacity;
    luz_clip_vertex *arena;        /* the big draws' vertices (not with
                                      position-only shading) */
    size_t arena_capacity;
    luz_window_vertex *window_arena;   /* the same, projected (likewise) */
    size_t window_arena_capacity;
    luz_fixed_vertex *fixed_arena;     /* and their snapped positions */
    size_t fixed_arena_capacity;
    vertex_scratch *scratch;       /* one per thread, for small draws */
    bool *draw_outside;            /* per draw: wholly outside the clip volume */
    size_t draw_outside_capacity;
    uint64_t outside_draw_triangles, outside_draws;
    size_t *band_slots;            /* batch x band: counts, then offsets */
    size_t band_slot_capacity;
    luz_triangle *record_block;    /* the batches' slices, huge pages
                                      (place_records), or NULL */
    size_t record_block_capacity;
    const luz_triangle **by_id;
    size_t by_id_capacity;
    size_t *band_start;
    int band_capacity;
    uint32_t *band_ids;
    size_t band_id_capacity;
    luz_screen_function *screen;   /* the renderer's table's (cpu.h) */
    bool screen_checks_small_boxes;
    luz_setup_eight_function *setup_eight;   /* setup_eight.c's, or NULL */
    luz_vertex_project_function *vertex_project;   /* vertex_sixteen.c's, or NULL */
    luz_screen_function *screen_four;        /* the same two for four samples */
    luz_setup_eight_function *setup_eight_four;   /* a pixel (or NULL) */
};

/* What the jobs of one frame's geometry share. */
typedef struct geometry_job {
    luz_geometry *geometry;
    const luz_frame *frame;
    const luz_uniforms *uniforms;
    int width, height;
    int band_shift, band_count;   /* a band is 2^band_shift rows */
    size_t binned;                 /* ids 1 .. binned go to the bands */
    luz_screen_function *screen;   /* screen.c's variant for this CPU */
    bool screen_checks_small_boxes;
    luz_setup_eight_function *setup_eight;   /* NULL: one triangle at a time */
    luz_vertex_project_function *vertex_project;   /* NULL: one vertex at a time */
} geometry_job;

luz_geometry *luz_geometry_create(int thread_count)
{
    luz_geometry *geometry = calloc(1, sizeof *geometry);
    if (!geometry) return NULL;
    geometry->thread_count = thread_count;
    const luz_kernels widest = luz_kernels_of(luz_isa_widest());
    luz_geometry_set_kernels(geometry, &widest);
    geometry->scratch = calloc((size_t)thread_count, sizeof *geometry->scratch);
    if (!geometry->scratch) {
        free(geometry);
        return NULL;
    }
    return geometry;
}

void luz_geometry_destroy(luz_geometry *geometry)
{
    if (!geometry) return;
    for (int i = 0; i < geometry->batch_capacity; i++) {
        if (!geometry->batches[i].in_block) free(geometry->batches[i].triangles);
        free(geometry->batches[i].band_ranges);
    }
    free(geometry->record_block);
    for (int i = 0; i < geometry->thread_count; i++) {
        free(geometry->scratch[i].vertices);
        free(geometry->scratch[i].window);
        free(geometry->scratch[i].fixed);
    }
    free(geometry->batches);
    free(geometry->vertex_ranges);
    free(geometry->arena);
    free(geometry->window_arena);
    free(geometry->fixed_arena);
    free(geometry->scratch);
    free(geometry->draw_outside);
    free(geometry->band_slots);
    free(geometry->by_id);
    free(geometry->band_start);
    free(geometry->band_ids);
    free(geometry);
}

void luz_geometry_set_kernels(luz_geometry *geometry, const luz_kernels *kernels)
{
    geometry->screen = kernels->screen;
    geometry->screen_checks_small_boxes = kernels->screen_checks_small_boxes;
    /* Setup in lanes trusts screening's check of the small boxes, unless
     * it makes it itself. */
    geometry->setup_eight = kernels->screen_checks_small_boxes || kernels->setup_eight_screens
                                ? kernels->setup_eight
                                : NULL;
    geometry->vertex_project = kernels->vertex_project;
    geometry->screen_four = kernels->screen_four;
    geometry->setup_eight_four = kernels->screen_four != NULL ? kernels->setup_eight_four : NULL;
}

size_t luz_geometry_memory(const luz_geometry *geometry)
{
    size_t bytes = sizeof *geometry;
    bytes += (size_t)geometry->batch_capacity * sizeof *geometry->batches;
    for (int i = 0; i < geometry->batch_capacity; i++)
        bytes += (geometry->batches[i].in_block ? 0 : geometry->batches[i].capacity) *
                     sizeof(luz_triangle) +
                 geometry->batches[i].band_range_capacity * sizeof(uint32_t);
    bytes += geometry->record_block_capacity * sizeof(luz_triangle);
    for (int i = 0; i < geometry->thread_count; i++)
        bytes += geometry->scratch[i].capacity *
                 (sizeof(luz_clip_vertex) + sizeof(luz_window_vertex) +
                  sizeof(luz_fixed_vertex));
    bytes += (size_t)geometry->thread_count * sizeof *geometry->scratch;
    bytes += geometry->vertex_range_capacity * sizeof *geometry->vertex_ranges;
    bytes += geometry->arena_capacity * sizeof *geometry->arena;
    bytes += geometry->window_arena_capacity * sizeof *geometry->window_arena;
    bytes += geometry->fixed_arena_capacity * sizeof *geometry->fixed_arena;
    bytes += geometry->draw_outside_capacity * sizeof *geometry->draw_outside;
    bytes += geometry->band_slot_capacity * sizeof *geometry->band_slots;
    bytes += geometry->by_id_capacity * sizeof *geometry->by_id;
    bytes += ((size_t)geometry->band_capacity + 1) * sizeof *geometry->band_start;
    bytes += geometry->band_id_capacity * sizeof *geometry->band_ids;
    return bytes;
}

/* Grows *array to hold count elements of size bytes (kept from frame to
 * frame, so after the first frames this does nothing). */
static bool reserve(void **array, size_t *capacity, size_t count, size_t size)
{
    if (count <= *capacity) return true;
    size_t grown = *capacity ? *capacity : 64;
    while (grown < count) grown *= 2;
    if (grown > SIZE_MAX / size) return false;
    void *bigger = realloc(*array, grown * size);
    if (!bigger) return false;
    *array = bigger;
    *capacity = grown;
    return true;
}

/* Room for count records in the batch: its slice of the block, or its own
 * array, which a batch whose slice is too small moves to (place_records
 * then gives it a larger slice in the next frame's block). */
static bool reserve_records(geometry_batch *batch, size_t count)
{
    if (count <= batch->capacity) return true;
    if (!batch->in_block)
        return reserve((void **)&batch->triangles, &batch->capacity, count,
                       sizeof *batch->triangles);
    /* Twice the slice, not reserve's next power of two from 64, which
     * could hold four times the records the batch made before. */
    const size_t capacity = count > 2 * batch->capacity ? count : 2 * batch->capacity;
    if (capacity > SIZE_MAX / sizeof(luz_triangle)) return false;
    luz_triangle *own = malloc(capacity * sizeof *own);
    if (!own) return false;
    memcpy(own, batch->triangles, batch->count * sizeof *own);
    batch->triangles = own;
    batch->capacity = capacity;
    batch->in_block = false;
    return true;
}

/* Every batch's slice given up, and the block freed: each batch makes an
 * array of its own as it needs one (the records are made anew each
 * frame: nothing to copy). */
static void release_record_block(luz_geometry *geometry)
{
    for (int k = 0; k < geometry->batch_capacity; k++) {
        geometry_batch *batch = &geometry->batches[k];
        if (!batch->in_block) continue;
        batch->triangles = NULL;
        batch->capacity = 0;
        batch->in_block = false;
    }
    free(geometry->record_block);
    geometry->record_block = NULL;
    geometry->record_block_capacity = 0;
}

/* A batch's slice: the records it made in the last frame, an eighth more
 * for a mesh that turns (more of a batch's triangles face the view from
 * frame to frame), and room for one group of setup's eight, which
 * reserve_records asks for before it sets the group up (or for a clipped
 * triangle's fan): a batch that makes as many records as before stays in
 * its slice. */
#define SLICE_SPARE 16
_Static_assert(SLICE_SPARE >= 8 && SLICE_SPARE >= LUZ_CLIP_MAX_VERTICES - 2,
               "a slice holds the records made before and one reserve_records more");
static size_t slice_records(size_t records_before)
{
    return records_before + records_before / 8 + SLICE_SPARE;
}

/* Before the batches run: the frame's records in one block, on huge
 * pages (renderer/huge_pages.h, where the system has them: Linux's
 * transparent huge pages), each batch a slice in batch order, so that
 * each thread's share of the batches writes one stretch of it. The bands
 * read the records through by_id in band order, scattered over tens of
 * megabytes on a big mesh (the 1M sphere: 48 MB, twelve thousand 4 KB
 * pages, more than the TLB holds, so nearly every record cost a page
 * walk; docs/performance.md, "The 1M sphere, 2026-11-28"). The slices are
 * sized from what each batch made in the last frame (slice_records; a
 * batch the last frame did not run has made nothing), not from the
 * capacities the batches reached, which double and never shrink: the
 * memory follows the records the frames make, not the biggest frames
 * drawn before. A batch keeps its slice from frame to frame; one that
 * needs more (a mesh turning puts more of a batch's triangles in view)
 * moves to an array of its own (reserve_records), and once an eighth of
 * the last frame's records were made outside the block, every batch gets
 * a slice again. The records are made anew each frame, so nothing is
 * copied. Few records (below RECORD_BLOCK_MIN), or no memory for a block:
 * each batch keeps its own array, and a block left from bigger frames (a
 * 1M-triangle model, then the lab's cubes) is freed. A block more than
 * twice the slices the frame needs and a huge page (a smaller model
 * after a big one) is laid out again at the frame's size. */
static void place_records(luz_geometry *geometry)
{
    /* Batches past this frame's: what they made is no guide to the
     * frames that run them again (a batch is whatever the plan makes it). */
    for (int k = geometry->batch_count; k < geometry->batch_capacity; k++)
        geometry->batches[k].count = 0;
    size_t total = 0, outside = 0;
    for (int k = 0; k < geometry->batch_count; k++) {
        const geometry_batch *batch = &geometry->batches[k];
        total += slice_records(batch->count);
        if (!batch->in_block) outside += batch->count;
    }
    if (total < RECORD_BLOCK_MIN) {
        if (geometry->record_block) release_record_block(geometry);
        return;
    }
    const size_t page_records = LUZ_HUGE_PAGE_BYTES / sizeof(luz_triangle);
    const bool oversized = geometry->record_block_capacity > 2 * total + page_records;
    if (outside <= total / 8 && !oversized) return;
    luz_triangle *block = geometry->record_block;
    size_t block_capacity = geometry->record_block_capacity;
    if (total > block_capacity || oversized) {
        /* Whole huge pages: the rounding is the only room to spare, so a
         * turning mesh whose batches outgrow it lays out a new block. */
        const size_t bytes = (total * sizeof(luz_triangle) + LUZ_HUGE_PAGE_BYTES - 1) /
                             LUZ_HUGE_PAGE_BYTES * LUZ_HUGE_PAGE_BYTES;
        block = luz_huge_pages_alloc(bytes);
        if (!block) return;
        block_capacity = bytes / sizeof(luz_triangle);
    }
    size_t at = 0;
    for (int k = 0; k < geometry->batch_capacity; k++) {
        geometry_batch *batch = &geometry->batches[k];
        if (k < geometry->batch_count) {
            if (!batch->in_block) free(batch->triangles);
            batch->triangles = block + at;
            batch->capacity = slice_records(batch->count);
            batch->in_block = true;
            at += batch->capacity;
        } else if (batch->in_block) {   /* not in this frame: it starts again with none */
            batch->triangles = NULL;
            batch->capacity = 0;
            batch->in_block = false;
        }
    }
    if (block != geometry->record_block) free(geometry->record_block);
    geometry->record_block = block;
    geometry->record_block_capacity = block_capacity;
}

size_t luz_geometry_record_block(const luz_geometry *geometry, size_t *records_in_block)
{
    size_t records = 0;
    for (int k = 0; k < geometry->batch_count; k++)
        if (geometry->batches[k].in_block) records += geometry->batches[k].count;
    *records_in_block = records;
    return geometry->record_block_capacity;
}

/* ---- plan ------------------------------------------------------------- */

/* Element (row, column) of a column-major luz_mat4, in double. */
static double element(const luz_mat4 *m, int row, int column)
{
    return (double)m->m[column * 4 + row];
}

/* Whether every point of the mesh's bounding box, through the model and
 * view_projection matrices, is outside one of clip.c's six planes, by a
 * margin: then so is every vertex, and clipping would reject each of the
 * draw's triangles (all three outcodes share that plane's bit).
 *
 * The clip coordinates are affine in the object position, so over the box
 * (centre c, half extents h along the object axes) a plane's distance
 * d = k . clip, a fixed combination k of (x, y, z, w), is largest at one
 * corner: max d = k . M c + sum over axes a of |k . M_a| h_a, where M_a is
 * M's column a (the "positive vertex" of Greene's box-frustum test). The
 * draw goes when that maximum is below minus a margin of 1e-4 of the
 * coordinates' size over the box, far beyond the float rounding of the
 * vertex stage, so a draw is dropped only where the renderer would have
 * drawn nothing of it. In double: one 4x4 product, then six planes of a
 * few multiplies each. */
static bool outside_the_clip_volume(const luz_draw *draw, const luz_mat4 *view_projection)
{
    /* M = view_projection * model. */
    double m[4][4];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            m[r][c] = 0.0;
            for (int k = 0; k < 4; k++)
                m[r][c] += element(view_projection, r, k) * element(&draw->model, k, c);
        }
    const luz_bounds bounds = draw->mesh->bounds;
    const double centre[3] = {0.5 * ((double)bounds.min.x + bounds.max.x),
                              0.5 * ((double)bounds.min.y + bounds.max.y),
                              0.5 * ((double)bounds.min.z + bounds.max.z)};
    const double half[3] = {0.5 * ((double)bounds.max.x - bounds.min.x),
                            0.5 * ((double)bounds.max.y - bounds.min.y),
                            0.5 * ((double)bounds.max.z - bounds.min.z)};
    /* The box in clip space: its centre and its three half axes. */
    double clip_centre[4], axis[3][4];
    for (int r = 0; r < 4; r++) {
        clip_centre[r] = m[r][0] * centre[0] + m[r][1] * centre[1] + m[r][2] * centre[2] + m[r][3];
        for (int a = 0; a < 3; a++) axis[a][r] = m[r][a] * half[a];
    }
    const double g = LUZ_CLIP_GUARD_BAND;
    /* The margin, at least the largest of 1e-4 (|x| + |y| + |z| + g |w|)
     * over the box. */
    double size = 0.0;
    for (int r = 0; r < 4; r++) {
        double extent = fabs(clip_centre[r]);
        for (int a = 0; a < 3; a++) extent += fabs(axis[a][r]);
        size += r == 3 ? g * extent : extent;
    }
    const double margin = 1e-4 * size;
    /* clip.c's planes as combinations of (x, y, z, w): near w + z, far
     * w - z, left g w + x, right g w - x, bottom g w + y, top g w - y. */
    static const double planes[LUZ_CLIP_PLANE_COUNT][4] = {
        {0, 0, 1, 1}, {0, 0, -1, 1}, {1, 0, 0, LUZ_CLIP_GUARD_BAND},
        {-1, 0, 0, LUZ_CLIP_GUARD_BAND}, {0, 1, 0, LUZ_CLIP_GUARD_BAND},
        {0, -1, 0, LUZ_CLIP_GUARD_BAND},
    };
    for (int plane = 0; plane < LUZ_CLIP_PLANE_COUNT; plane++) {
        const double *k = planes[plane];
        double largest = k[0] * clip_centre[0] + k[1] * clip_centre[1] + k[2] * clip_centre[2] +
                         k[3] * clip_centre[3];
        for (int a = 0; a < 3; a++)
            largest += fabs(k[0] * axis[a][0] + k[1] * axis[a][1] + k[2] * axis[a][2] +
                            k[3] * axis[a][3]);
        if (largest < -margin) return true;
    }
    return false;
}

/* Draws per job of the culling pass. */
#define CULL_BATCH 4096

static void cull_job(void *context, int job_index, int worker_index);

static uint32_t triangles_of(const luz_draw *draw)
{
    return draw->mesh->index_count / 3;
}

static bool is_big(const luz_draw *draw)
{
    return triangles_of(draw) > BATCH_TRIANGLES;
}

static geometry_batch *add_batch(luz_geometry *geometry)
{
    if (geometry->batch_count == geometry->batch_capacity) {
        int capacity = geometry->batch_capacity ? geometry->batch_capacity * 2 : 16;
        geometry_batch *batches = realloc(geometry->batches, (size_t)capacity * sizeof *batches);
        if (!batches) return NULL;
        memset(batches + geometry->batch_capacity, 0,
               (size_t)(capacity - geometry->batch_capacity) * sizeof *batches);
        geometry->batches = batches;
        geometry->batch_capacity = capacity;
    }
    return &geometry->batches[geometry->batch_count++];
}

static vertex_range *add_vertex_range(luz_geometry *geometry)
{
    if (!reserve((void **)&geometry->vertex_ranges, &geometry->vertex_range_capacity,
                 geometry->vertex_range_count + 1, sizeof *geometry->vertex_ranges))
        return NULL;
    return &geometry->vertex_ranges[geometry->vertex_range_count++];
}

static int plan(luz_geometry *geometry, luz_thread_pool *pool, geometry_job *job,
                luz_error *error)
{
    const luz_frame *frame = job->frame;
    geometry->batch_count = 0;
    geometry->vertex_range_count = 0;

    /* Draws out of sight first, so that the arena holds only the rest. */
    size_t arena_vertices = 0;
    geometry->outside_draw_triangles = geometry->outside_draws = 0;
    if (!reserve((void **)&geometry->draw_outside, &geometry->draw_outside_capacity,
                 (size_t)frame->draw_count, sizeof *geometry->draw_outside))
        goto out_of_memory;
    luz_thread_pool_run(pool, (frame->draw_count + CULL_BATCH - 1) / CULL_BATCH, cull_job, job);
    for (int d = 0; d < frame->draw_count; d++) {
        const luz_draw *draw = &frame->draws[d];
        if (geometry->draw_outside[d]) {
            geometry->outside_draw_triangles += triangles_of(draw);
            geometry->outside_draws++;
        }
        else if (is_big(draw))
            arena_vertices += draw->mesh->vertex_count;
    }
    /* Setup in lanes shades and projects each corner again from the
     * mesh (position-only shading, setup_eight.c): then the big draws'
     * vertex pass, in lanes too, shades positions alone and keeps their
     * snapped positions, 8 bytes a vertex, not 100. */
    const bool keep_vertices = job->setup_eight == NULL || job->vertex_project == NULL;
    if ((keep_vertices &&
         (!reserve((void **)&geometry->arena, &geometry->arena_capacity, arena_vertices,
                   sizeof *geometry->arena) ||
          !reserve((void **)&geometry->window_arena, &geometry->window_arena_capacity,
                   arena_vertices, sizeof *geometry->window_arena))) ||
        !reserve((void **)&geometry->fixed_arena, &geometry->fixed_arena_capacity,
                 arena_vertices, sizeof *geometry->fixed_arena))
        return luz_error_set(error, "out of memory for the frame's %zu vertices",
                             arena_vertices);

    size_t arena_used = 0;
    geometry_batch *open = NULL;   /* the batch small draws are joining */
    size_t open_cost = 0;
    for (int d = 0; d < frame->draw_count; d++) {
        const luz_draw *draw = &frame->draws[d];
        if (geometry->draw_outside[d]) continue;
        if (!is_big(draw)) {
            if (!open) {
                open = add_batch(geometry);
                if (!open) goto out_of_memory;
                open->whole_draws = true;
                open->draw_first = (uint32_t)d;
                open_cost = 0;
            }
            open->draw_end = (uint32_t)d + 1;   /* draws out of sight in it are skipped */
            /* A draw costs its triangles, and a little even with none. */
            open_cost += triangles_of(draw) + 1;
            if (open_cost >= SMALL_DRAWS_BATCH) open = NULL;
            continue;
        }
        open = NULL;
        luz_clip_vertex *vertices = keep_vertices ? geometry->arena + arena_used : NULL;
        luz_window_vertex *window = keep_vertices ? geometry->window_arena + arena_used : NULL;
        luz_fixed_vertex *fixed = geometry->fixed_arena + arena_used;
        const uint32_t vertex_count = draw->mesh->vertex_count;
        arena_used += vertex_count;
        for (uint32_t first = 0; first < vertex_count; first += VERTEX_BATCH) {
            vertex_range *range = add_vertex_range(geometry);
            if (!range) goto out_of_memory;
            range->draw = (uint32_t)d;
            range->first = first;
            range->end = vertex_count - first > VERTEX_BATCH ? first + VERTEX_BATCH
                                                             : vertex_count;
            range->out = vertices;
            range->window = window;
            range->fixed = fixed;
        }
        const uint32_t triangle_count = triangles_of(draw);
        for (uint32_t first = 0; first < triangle_count; first += BATCH_TRIANGLES) {
            geometry_batch *batch = add_batch(geometry);
            if (!batch) goto out_of_memory;
            batch->whole_draws = false;
            batch->draw_first = (uint32_t)d;
            batch->draw_end = (uint32_t)d + 1;
            batch->triangle_first = first;
            batch->triangle_end = triangle_count - first > BATCH_TRIANGLES
                                      ? first + BATCH_TRIANGLES : triangle_count;
            batch->vertices = vertices;
            batch->window = window;
            batch->fixed = fixed;
        }
    }
    return 0;

out_of_memory:
    return luz_error_set(error, "out of memory for the frame's geometry batches");
}

/* ---- culling pass and vertex pass --------------------------------------- */

static void cull_job(void *context, int job_index, int worker_index)
{
    (void)worker_index;
    const geometry_job *job = context;
    const int first = job_index * CULL_BATCH;
    const int end = job->frame->draw_count - first > CULL_BATCH ? first + CULL_BATCH
                                                                 : job->frame->draw_count;
    for (int d = first; d < end; d++)
        job->geometry->draw_outside[d] =
            outside_the_clip_volume(&job->frame->draws[d], &job->uniforms->view_projection);
}

static void vertex_job(void *context, int range_index, int worker_index)
{
    (void)worker_index;
    const geometry_job *job = context;
    const vertex_range *range = &job->geometry->vertex_ranges[range_index];
    const luz_draw *draw = &job->frame->draws[range->draw];
    if (job->vertex_project != NULL) {   /* the same, sixteen vertices at a time */
        job->vertex_project(draw, job->uniforms->view_projection, range->first, range->end,
                            job->width, job->height, range->out, range->window, range->fixed);
    } else {   /* (then plan kept the arena whole: keep_vertices) */
        luz_vertex_stage_bug(draw, job->uniforms->view_projection, job->uniforms->bug,
                             range->first, range->end, range->out);
        luz_setup_project(range->out, range->first, range->end, job->width, job->height,
                          range->window, range->fixed);
    }
}

/* ---- batches: clipping and setup --------------------------------------- */

static void set_up(geometry_batch *batch, const geometry_job *job, const luz_clip_vertex *a,
                   const luz_clip_vertex *b, const luz_clip_vertex *c,
                   const luz_window_vertex *window_a, const luz_window_vertex *window_b,
                   const luz_window_vertex *window_c, uint32_t draw_index, uint32_t primitive,
                   bool small_box_checked)
{
    luz_triangle *out = &batch->triangles[batch->count];
    const int samples = job->uniforms->samples;
    luz_setup_result result =
        job->uniforms->bug != LUZ_BUG_NONE   /* luz/bug.h */
            ? luz_setup_projected_bug(a, b, c, window_a, window_b, window_c, job->width,
                                      job->height, draw_index, job->uniforms->interpolation,
                                      samples, job->uniforms->bug, out)
        : samples > 1
            ? luz_setup_projected_samples(a, b, c, window_a, window_b, window_c, job->width,
                                          job->height, draw_index, job->uniforms->interpolation,
                                          small_box_checked, samples, out)
            : luz_setup_projected(a, b, c, window_a, window_b, window_c, job->width,
                                  job->height, draw_index, job->uniforms->interpolation,
                                  small_box_checked, out);
    out->primitive = primitive;
    if (result == LUZ_SETUP_VISIBLE) batch->count++;
    else if (result == LUZ_SETUP_CULLED) batch->culled++;
}

/* Clips and sets up triangle t of draw draw_index, whose clip-space
 * vertices are at vertices, and projected at window; both NULL where the
 * vertex pass kept only snapped positions (position-only shading,
 * setup_eight.c): then the three corners go through the vertex stage
 * (transform) and are projected here. */
static void one_triangle(geometry_batch *batch, const geometry_job *job, uint32_t draw_index,
                         const uint32_t *indices, const luz_clip_vertex *vertices,
                         const luz_window_vertex *window, const luz_draw_transform *transform,
                         uint32_t t)
{
    const uint32_t ia = indices[3 * (size_t)t], ib = indices[3 * (size_t)t + 1],
                   ic = indices[3 * (size_t)t + 2];
    luz_clip_vertex shaded[3];
    luz_window_vertex projected[3];
    const luz_clip_vertex *a, *b, *c;
    const luz_window_vertex *window_a, *window_b, *window_c;
    if (vertices != NULL) {
        a = &vertices[ia], b = &vertices[ib], c = &vertices[ic];
        window_a = &window[ia], window_b = &window[ib], window_c = &window[ic];
    } else {
        const uint32_t corner[3] = {ia, ib, ic};
        for (int k = 0; k < 3; k++) {
            shaded[k] = luz_vertex_stage_one(transform, corner[k]);
            projected[k] = luz_setup_project_vertex(&shaded[k], job->width, job->height);
        }
        a = &shaded[0], b = &shaded[1], c = &shaded[2];
        window_a = &projected[0], window_b = &projected[1], window_c = &projected[2];
    }
    /* A fan of a clipped triangle has at most this many triangles. */
    if (!reserve_records(batch, batch->count + LUZ_CLIP_MAX_VERTICES - 2)) {
        batch->out_of_memory = true;
        return;
    }

    /* Clipping: trivially accept, trivially reject, or cut (the vertex
     * stage worked out each vertex's outcode). */
    const unsigned code_a = a->outcode, code_b = b->outcode, code_c = c->outcode;
    if ((code_a | code_b | code_c) == 0) {
        /* Half the triangles of a closed mesh face away: drop them here,
         * as setup would. */
        if (!luz_setup_front_facing(window_a, window_b, window_c) &&
            job->uniforms->bug != LUZ_BUG_NO_BACKFACE_CULLING) {
            batch->culled++;
            return;
        }
        /* Screening saw this triangle as it is (its vertices projected,
         * none marked): what it checked holds. */
        set_up(batch, job, a, b, c, window_a, window_b, window_c, draw_index, t,
               job->screen_checks_small_boxes);
        return;
    }
    if (code_a & code_b & code_c) return;   /* all outside one plane */
    batch->clipped++;
    luz_clip_polygon polygon;
    int count = luz_clip_triangle(a, b, c, &polygon);
    /* The polygon's vertices are inside every plane: project each once
     * (outcode 0 by construction), then set up each triangle of its fan. */
    luz_window_vertex polygon_window[LUZ_CLIP_MAX_VERTICES];
    for (int k = 0; k < count; k++) polygon.vertices[k].outcode = 0;
    luz_setup_project(polygon.vertices, 0, (uint32_t)count, job->width, job->height,
                      polygon_window, NULL);
    for (int k = 1; k + 1 < count; k++)
        set_up(batch, job, &polygon.vertices[0], &polygon.vertices[k], &polygon.vertices[k + 1],
               &polygon_window[0], &polygon_window[k], &polygon_window[k + 1], draw_index, t,
               false);
}

/* Triangles screened at a time: the list of those left fits the stack. */
#define SCREEN_CHUNK 1024

/* Sets up survivors[0..7] of draw draw_index in lanes (setup_eight.c), or,
 * when setup in lanes leaves them (a marked vertex among them), each
 * through one_triangle: the records come out in order, as one triangle at
 * a time would make them. */
static void eight_triangles(geometry_batch *batch, const geometry_job *job, uint32_t draw_index,
                            const uint32_t *indices, const luz_clip_vertex *vertices,
                            const luz_window_vertex *window, const luz_fixed_vertex *fixed,
                            const luz_draw_transform *transform, const uint32_t survivors[8])
{
    if (!reserve_records(batch, batch->count + 8)) {
        batch->out_of_memory = true;
        return;
    }
    luz_triangle *out = &batch->triangles[batch->count];
    luz_setup_result result[8];
    if (job->setup_eight(indices, survivors, transform, fixed, job->width, job->height,
                         draw_index, job->uniforms->interpolation, out, result)) {
        for (int lane = 0; lane < 8 && !batch->out_of_memory; lane++)
            one_triangle(batch, job, draw_index, indices, vertices, window, transform,
                         survivors[lane]);
        return;
    }
    /* Each visible record moved down over those of the lanes before it
     * that are not (a record only ever moves to a lower place, so in
     * order nothing is overwritten before it is read; all eight visible,
     * the usual case, nothing moves). */
    size_t count = batch->count;
    for (int lane = 0; lane < 8; lane++) {
        if (result[lane] == LUZ_SETUP_VISIBLE) {
            if (count != batch->count + (size_t)lane) batch->triangles[count] = out[lane];
            batch->triangles[count++].primitive = survivors[lane];
        } else if (result[lane] == LUZ_SETUP_CULLED) {
            batch->culled++;
        }
    }
    batch->count = count;
}

/* Clips and sets up triangles [first, end) of draw draw_index: screening
 * first drops, many at a time, the back faces and the triangles that
 * cover no pixel centre (screen.c), then those left are set up eight at a
 * time where the CPU can (setup_eight.c), else each alone. vertices and
 * window: the draw's, or NULL (position-only shading: the corners are
 * shaded from the mesh). */
static void triangles_of_draw(geometry_batch *batch, const geometry_job *job,
                              uint32_t draw_index, const luz_clip_vertex *vertices,
                              const luz_window_vertex *window, const luz_fixed_vertex *fixed,
                              uint32_t first, uint32_t end)
{
    const luz_draw *draw = &job->frame->draws[draw_index];
    const uint32_t *indices = draw->mesh->indices;
    /* The draw's transforms (its normal matrix an inverse), worked out
     * only when a corner is shaded here: by setup in lanes, which reads
     * one kind of vertex, the mesh's, so it shades its corners again even
     * for a small draw whose vertex stage ran whole (one with eight
     * survivors in a chunk: a cube of the lab never has them), or for a
     * big draw shaded position-only. */
    luz_draw_transform transform;
    bool have_transform = false;
    uint32_t survivors[SCREEN_CHUNK];
    for (uint32_t chunk = first; chunk < end && !batch->out_of_memory; chunk += SCREEN_CHUNK) {
        const uint32_t chunk_end = end - chunk > SCREEN_CHUNK ? chunk + SCREEN_CHUNK : end;
        uint32_t culled = 0;
        const size_t count = job->screen(indices, chunk, chunk_end, fixed, job->width,
                                         job->height, survivors, &culled);
        batch->submitted += chunk_end - chunk;
        batch->culled += culled;
        if (!have_transform && (vertices == NULL || (job->setup_eight != NULL && count >= 8))) {
            transform = luz_draw_transform_of(draw, job->uniforms->view_projection);
            have_transform = true;
        }
        const luz_draw_transform *shading = have_transform ? &transform : NULL;
        size_t k = 0;
        if (job->setup_eight != NULL)
            for (; k + 8 <= count && !batch->out_of_memory; k += 8)
                eight_triangles(batch, job, draw_index, indices, vertices, window, fixed,
                                shading, &survivors[k]);
        for (; k < count && !batch->out_of_memory; k++)
            one_triangle(batch, job, draw_index, indices, vertices, window, shading,
                         survivors[k]);
    }
}

/* Each triangle's bands, while its record is still in the cache (a band
 * index fits 16 bits: LUZ_MAX_DIMENSION / band height < 2^16). A band is
 * 2^band_shift rows: a shift, where a division by a variable band height
 * took a measurable share of the 1M sphere's geometry
 * (docs/performance.md, "Measured in the code"). */
static bool find_band_ranges(geometry_batch *batch, int band_shift)
{
    if (!reserve((void **)&batch->band_ranges, &batch->band_range_capacity, batch->count,
                 sizeof *batch->band_ranges))
        return false;
    for (size_t i = 0; i < batch->count; i++) {
        const luz_triangle *triangle = &batch->triangles[i];
        batch->band_ranges[i] = (uint32_t)(triangle->min_y >> band_shift) |
                                (uint32_t)(triangle->max_y >> band_shift) << 16;
    }
    return true;
}

/* Counts the first count triangles of a batch per band, into its row. */
static void count_per_band(const geometry_batch *batch, size_t count, size_t *row,
                           int band_count)
{
    memset(row, 0, (size_t)band_count * sizeof *row);
    for (size_t i = 0; i < count; i++) {
        const uint32_t range = batch->band_ranges[i];
        for (uint32_t b = range & 0xffff; b <= range >> 16; b++) row[b]++;
    }
}

static void batch_job(void *context, int batch_index, int worker_index)
{
    const geometry_job *job = context;
    luz_geometry *geometry = job->geometry;
    geometry_batch *batch = &geometry->batches[batch_index];
    batch->count = 0;
    batch->submitted = batch->clipped = batch->culled = 0;
    batch->out_of_memory = false;

    if (!batch->whole_draws) {
        triangles_of_draw(batch, job, batch->draw_first, batch->vertices, batch->window,
                          batch->fixed, batch->triangle_first, batch->triangle_end);
    } else {
        vertex_scratch *scratch = &geometry->scratch[worker_index];
        for (uint32_t d = batch->draw_first; d < batch->draw_end && !batch->out_of_memory; d++) {
            if (geometry->draw_outside[d]) continue;
            const luz_draw *draw = &job->frame->draws[d];
            const uint32_t vertex_count = draw->mesh->vertex_count;
            if (vertex_count > scratch->capacity) {
                luz_clip_vertex *vertices =
                    realloc(scratch->vertices, (size_t)vertex_count * sizeof *vertices);
                if (vertices) scratch->vertices = vertices;
                luz_window_vertex *window =
                    realloc(scratch->window, (size_t)vertex_count * sizeof *window);
                if (window) scratch->window = window;
                luz_fixed_vertex *fixed =
                    realloc(scratch->fixed, (size_t)vertex_count * sizeof *fixed);
                if (fixed) scratch->fixed = fixed;
                if (!vertices || !window || !fixed) {
                    batch->out_of_memory = true;
                    break;
                }
                scratch->capacity = vertex_count;
            }
            /* Vertex stage, for a draw too small to be worth its own pass. */
            luz_vertex_stage_bug(draw, job->uniforms->view_projection, job->uniforms->bug, 0,
                                 vertex_count, scratch->vertices);
            luz_setup_project(scratch->vertices, 0, vertex_count, job->width, job->height,
                              scratch->window, scratch->fixed);
            triangles_of_draw(batch, job, d, scratch->vertices, scratch->window, scratch->fixed,
                              0, triangles_of(draw));
        }
    }
    if (!batch->out_of_memory && !find_band_ranges(batch, job->band_shift))
        batch->out_of_memory = true;
    if (!batch->out_of_memory)
        count_per_band(batch, batch->count,
                       geometry->band_slots + (size_t)batch_index * job->band_count,
                       job->band_count);
}

/* ---- number ------------------------------------------------------------ */

/* Gives each batch its first id and each (batch, band) its offset in the
 * band's list; sizes by_id and the lists. Only ids 1 .. limit are binned
 * (0: all of them). */
static int number(luz_geometry *geometry, geometry_job *job, size_t limit, luz_error *error)
{
    size_t total = 0;
    for (int k = 0; k < geometry->batch_count; k++) {
        geometry_batch *batch = &geometry->batches[k];
        if (batch->out_of_memory)
            return luz_error_set(error, "out of memory for the frame's triangles");
        batch->first_id = total + 1;
        total += batch->count;
    }
    if (total >= UINT32_MAX)
        return luz_error_set(error, "%zu triangles: more than a frame supports", total);
    if (!reserve((void **)&geometry->by_id, &geometry->by_id_capacity, total + 1,
                 sizeof *geometry->by_id))
        return luz_error_set(error, "out of memory for the frame's triangles");

    /* The viewer's step mode rasterises only the first triangles: the
     * batches past the limit are counted again, up to it. */
    job->binned = (limit != 0 && limit < total) ? limit : total;
    const int band_count = job->band_count;
    for (int k = 0; k < geometry->batch_count; k++) {
        const geometry_batch *batch = &geometry->batches[k];
        if (batch->first_id + batch->count - 1 <= job->binned) continue;
        size_t kept = batch->first_id > job->binned ? 0 : job->binned - batch->first_id + 1;
        count_per_band(batch, kept,
                       geometry->band_slots + (size_t)k * band_count, band_count);
    }

    /* Counting sort: band b's list holds batch 0's ids, then batch 1's, ... */
    size_t *start = geometry->band_start;
    size_t offset = 0;
    for (int b = 0; b < band_count; b++) {
        start[b] = offset;
        for (int k = 0; k < geometry->batch_count; k++) {
            size_t *slot = &geometry->band_slots[(size_t)k * band_count + b];
            size_t count = *slot;
            *slot = offset;
            offset += count;
        }
    }
    start[band_count] = offset;
    if (!reserve((void **)&geometry->band_ids, &geometry->band_id_capacity, offset,
                 sizeof *geometry->band_ids))
        return luz_error_set(error, "out of memory for the frame's bands");
    return 0;
}

/* ---- bin --------------------------------------------------------------- */

static void bin_job(void *context, int batch_index, int worker_index)
{
    (void)worker_index;
    const geometry_job *job = context;
    luz_geometry *geometry = job->geometry;
    const geometry_batch *batch = &geometry->batches[batch_index];
    size_t *slot = geometry->band_slots + (size_t)batch_index * job->band_count;
    for (size_t i = 0; i < batch->count; i++) {
        const size_t id = batch->first_id + i;
        geometry->by_id[id] = &batch->triangles[i];
        if (id > job->binned) continue;
        const uint32_t range = batch->band_ranges[i];
        for (uint32_t b = range & 0xffff; b <= range >> 16; b++)
            geometry->band_ids[slot[b]++] = (uint32_t)id;
    }
}

/* ---- phase 1 ----------------------------------------------------------- */

int luz_geometry_run(luz_geometry *geometry, luz_thread_pool *pool, const luz_frame *frame,
                     const luz_uniforms *uniforms, const luz_framebuffer *framebuffer,
                     int band_height, uint32_t triangle_limit, luz_geometry_result *out,
                     luz_error *error)
{
    geometry_job job = {
        .geometry = geometry,
        .frame = frame,
        .uniforms = uniforms,
        .width = framebuffer->width,
        .height = framebuffer->height,
        .band_shift = __builtin_ctz((unsigned)band_height),
        .band_count = (framebuffer->height + band_height - 1) / band_height,
        .screen = geometry->screen,
        .screen_checks_small_boxes = geometry->screen_checks_small_boxes,
        .setup_eight = geometry->setup_eight,
        .vertex_project = geometry->vertex_project,
    };
    memset(out, 0, sizeof *out);
    /* With four samples a pixel, screening and setup in lanes of their
     * own, which test the samples where the others test the centres (or,
     * in a table without them, every triangle through and set up one at
     * a time by luz_setup_projected_samples). */
    if (uniforms->samples > 1) {
        job.screen = geometry->screen_four != NULL ? geometry->screen_four
                                                   : luz_screen_every_triangle;
        job.screen_checks_small_boxes = geometry->screen_four != NULL;
        job.setup_eight = geometry->setup_eight_four;
    }
    /* A frame with a bug (luz/bug.h) takes the plain path: the vertex
     * stage, screening and setup in lanes know nothing of bugs. */
    if (uniforms->bug != LUZ_BUG_NONE) {
        job.screen = luz_screen_every_triangle;
        job.screen_checks_small_boxes = false;
        job.setup_eight = NULL;
        job.vertex_project = NULL;
    }

    if (plan(geometry, pool, &job, error) != 0) return -1;
    place_records(geometry);
    if (job.band_count > geometry->band_capacity) {
        size_t *start = realloc(geometry->band_start,
                                ((size_t)job.band_count + 1) * sizeof *start);
        if (!start) return luz_error_set(error, "out of memory for the frame's bands");
        geometry->band_start = start;
        geometry->band_capacity = job.band_count;
    }
    if (!reserve((void **)&geometry->band_slots, &geometry->band_slot_capacity,
                 (size_t)geometry->batch_count * (size_t)job.band_count,
                 sizeof *geometry->band_slots))
        return luz_error_set(error, "out of memory for the frame's bands");

    luz_thread_pool_run(pool, (int)geometry->vertex_range_count, vertex_job, &job);
    luz_thread_pool_run(pool, geometry->batch_count, batch_job, &job);
    if (number(geometry, &job, triangle_limit, error) != 0) return -1;
    luz_thread_pool_run(pool, geometry->batch_count, bin_job, &job);

    /* A draw out of sight was submitted; its triangles went nowhere, as
     * they would have at the clipper. */
    out->triangles_submitted = geometry->outside_draw_triangles;
    out->draws_culled = geometry->outside_draws;
    for (int k = 0; k < geometry->batch_count; k++) {
        out->triangles_submitted += geometry->batches[k].submitted;
        out->triangles_clipped += geometry->batches[k].clipped;
        out->triangles_culled += geometry->batches[k].culled;
        out->triangle_total += geometry->batches[k].count;
    }
    out->triangle_count = job.binned;
    out->by_id = geometry->by_id;
    out->band_count = job.band_count;
    out->band_start = geometry->band_start;
    out->band_ids = geometry->band_ids;
    return 0;
}
