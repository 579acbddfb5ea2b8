/*
 * frame.c: the renderer, and the draw function that reads as the pipeline.
 *
 * luz_renderer_draw() runs the stages in two phases:
 *
 *   0. Uniforms: what every stage reads that is the same for the whole
 *      frame (matrices, the eye, the lights, the spot's cone), once.
 *
 *   1. Geometry, per draw (draws are split into chunks, one job each):
 *        vertex stage    every vertex to clip space, with its varyings
 *        clipping        each triangle against the near, far and guard planes
 *        setup           each clipped triangle to edges and planes; back
 *                        faces culled
 *      Chunks keep the submission order, and triangles get ids 1, 2, ... in
 *      that order. Each triangle is then binned to the bands of rows its
 *      bounding box touches, still in id order.
 *
 *   2. Bands, per band of rows (one job each):
 *        clear           the band's depth and visibility
 *        raster + depth  the band's triangles, in id order
 *        fragment        each visible pixel shaded once, and the
 *                        background given the clear colour (or, for a
 *                        --view other than color, a picture of a stage:
 *                        view.c)
 *        probe           if a pixel is probed and lies in the band, the
 *                        bytes it got (luz/probe.h)
 *        hook            the caller's work on top of the band, if any
 *                        (the viewer's 2D layer: luz_band_hook)
 *
 *   3. The probe, if one was asked for: the pixel's story, from what the
 *      bands left (probe.c).
 *
 * A band touches only its own rows and draws triangles in submission order,
 * so the image is the same byte for byte whichever thread draws which band
 * and however many threads there are.
 */
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "renderer/pipeline.h"
#include "luz/renderer.h"

/* Rows per band: small enough to balance two or more threads and keep a
 * band's depth and visibility rows in cache, large enough that a triangle
 * rarely spans many bands. */
#define BAND_HEIGHT 16
#define CHUNKS_PER_THREAD 4
/* A cube's geometry takes about 2 microseconds, less than waking a thread:
 * chunks of fewer draws than this would cost more than they save, so the
 * default scene's 11 draws run as one chunk on the caller's thread. */
#define MIN_DRAWS_PER_CHUNK 16

/* The set-up triangles of one chunk of draws. */
typedef struct triangle_list {
    luz_triangle *triangles;
    size_t count;
    size_t capacity;
    luz_clip_vertex *vertices;      /* vertex-stage output, reused per draw */
    uint32_t vertex_capacity;
    bool out_of_memory;
    luz_interpolation interpolation;   /* the frame's, for setup */
    uint64_t submitted, clipped, culled;
} triangle_list;

typedef struct band_counters {
    uint64_t fragments_tested;
    uint64_t fragments_shaded;
} band_counters;

struct luz_renderer {
    luz_thread_pool *pool;
    triangle_list *chunks;
    int chunk_capacity;
    const luz_triangle **by_id;     /* by_id[id] for id = 1 .. triangle_count */
    size_t by_id_capacity;
    band_counters *bands;
    int band_capacity;
    size_t *band_start;             /* band b's ids: band_ids[band_start[b] ..
                                       band_start[b + 1]) */
    uint32_t *band_ids;
    size_t band_ids_capacity;
    bool reference;                 /* fragment.c's shading, not the packets */
    luz_packet_rows_function *packet_rows;   /* the SIMD variant this CPU
                                                runs, chosen at creation */
    uint32_t *overdraw;             /* depth tests per pixel, for the overdraw
                                       view only; allocated when first asked */
    size_t overdraw_capacity;
};

/* What the jobs of one frame share; read-only for the jobs except their
 * own chunk or band slot. */
typedef struct frame_job {
    luz_renderer *renderer;
    const luz_frame *frame;
    luz_framebuffer *framebuffer;
    luz_uniforms uniforms;
    int chunk_count;
    int draws_per_chunk;
    size_t triangle_count;
    int band_count;
    uint32_t triangle_limit;        /* 0, or rasterise only the first N */
    uint32_t *overdraw;             /* NULL unless the overdraw view */
    const luz_band_hook *hook;      /* NULL, or called after each band */
    luz_pixel_probe *probe;         /* NULL, or the pixel to explain */
} frame_job;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

/* ---- phase 1: geometry ------------------------------------------------- */

static bool reserve_triangles(triangle_list *list, size_t extra)
{
    if (list->count + extra <= list->capacity) return true;
    size_t capacity = list->capacity ? list->capacity : 256;
    while (capacity < list->count + extra) capacity *= 2;
    luz_triangle *triangles = realloc(list->triangles, capacity * sizeof *triangles);
    if (!triangles) return false;
    list->triangles = triangles;
    list->capacity = capacity;
    return true;
}

static void set_up(triangle_list *list, const luz_clip_vertex *a, const luz_clip_vertex *b,
                   const luz_clip_vertex *c, const luz_framebuffer *framebuffer,
                   uint32_t draw_index)
{
    luz_triangle *out = &list->triangles[list->count];
    luz_setup_result result = luz_setup_triangle(a, b, c, framebuffer->width,
                                                 framebuffer->height, draw_index,
                                                 list->interpolation, out);
    if (result == LUZ_SETUP_VISIBLE) list->count++;
    else if (result == LUZ_SETUP_CULLED) list->culled++;
}

static void geometry_of_draw(triangle_list *list, const luz_draw *draw, uint32_t draw_index,
                             const luz_mat4 view_projection, const luz_framebuffer *framebuffer)
{
    const luz_mesh *mesh = draw->mesh;
    if (mesh->vertex_count > list->vertex_capacity) {
        luz_clip_vertex *vertices =
            realloc(list->vertices, (size_t)mesh->vertex_count * sizeof *vertices);
        if (!vertices) {
            list->out_of_memory = true;
            return;
        }
        list->vertices = vertices;
        list->vertex_capacity = mesh->vertex_count;
    }

    /* Vertex stage. */
    luz_vertex_stage(draw, view_projection, list->vertices);

    for (uint32_t i = 0; i + 2 < mesh->index_count; i += 3) {
        const luz_clip_vertex *a = &list->vertices[mesh->indices[i]];
        const luz_clip_vertex *b = &list->vertices[mesh->indices[i + 1]];
        const luz_clip_vertex *c = &list->vertices[mesh->indices[i + 2]];
        list->submitted++;
        /* A fan of a clipped triangle has at most this many triangles. */
        if (!reserve_triangles(list, LUZ_CLIP_MAX_VERTICES - 2)) {
            list->out_of_memory = true;
            return;
        }

        /* Clipping: trivially accept, trivially reject, or cut. */
        unsigned code_a = luz_clip_outcode(a->position);
        unsigned code_b = luz_clip_outcode(b->position);
        unsigned code_c = luz_clip_outcode(c->position);
        if ((code_a | code_b | code_c) == 0) {
            set_up(list, a, b, c, framebuffer, draw_index);
            continue;
        }
        if (code_a & code_b & code_c) continue;   /* all outside one plane */
        list->clipped++;
        luz_clip_polygon polygon;
        int count = luz_clip_triangle(a, b, c, &polygon);
        /* Setup, for each triangle of the polygon's fan. */
        for (int k = 1; k + 1 < count; k++)
            set_up(list, &polygon.vertices[0], &polygon.vertices[k], &polygon.vertices[k + 1],
                   framebuffer, draw_index);
    }
}

static void geometry_job(void *context, int chunk_index, int worker_index)
{
    (void)worker_index;
    frame_job *job = context;
    triangle_list *list = &job->renderer->chunks[chunk_index];
    int first = chunk_index * job->draws_per_chunk;
    int end = first + job->draws_per_chunk;
    if (end > job->frame->draw_count) end = job->frame->draw_count;
    for (int d = first; d < end && !list->out_of_memory; d++)
        geometry_of_draw(list, &job->frame->draws[d], (uint32_t)d,
                         job->uniforms.view_projection, job->framebuffer);
}

/* ---- phase 2: bands ---------------------------------------------------- */

static void band_job(void *context, int band_index, int worker_index)
{
    frame_job *job = context;
    luz_framebuffer *framebuffer = job->framebuffer;
    const luz_renderer *renderer = job->renderer;
    const luz_triangle **by_id = renderer->by_id;
    int first_row = band_index * BAND_HEIGHT;
    int end_row = first_row + BAND_HEIGHT;
    if (end_row > framebuffer->height) end_row = framebuffer->height;
    band_counters *counters = &job->renderer->bands[band_index];

    /* Clear depth and visibility. Not colour: the fragment stage (or the
     * view) writes every pixel of the band, the clear colour where no
     * triangle wins, so each colour byte is written once. */
    luz_framebuffer_clear_rows(framebuffer, first_row, end_row);

    /* The overdraw view counts every depth test of the band's pixels. */
    uint32_t *overdraw = job->overdraw;
    if (overdraw)
        memset(overdraw + (size_t)first_row * framebuffer->width, 0,
               (size_t)(end_row - first_row) * framebuffer->width * sizeof *overdraw);

    /* Raster and depth test, the band's triangles in submission order. */
    uint64_t tested = 0;
    for (size_t k = renderer->band_start[band_index]; k < renderer->band_start[band_index + 1];
         k++) {
        const uint32_t id = renderer->band_ids[k];
        const luz_triangle *triangle = by_id[id];
        if (overdraw)
            tested += luz_raster_triangle_counting(triangle, id, framebuffer, first_row,
                                                   end_row, overdraw);
        else
            tested += luz_raster_triangle(triangle, id, framebuffer, first_row, end_row);
    }

    /* Fragment stage: shade each visible pixel once, one pixel at a time
     * (the reference, fragment.c) or a packet of them at a time (the same
     * equations as SIMD vectors, fragment_packet.c). The teaching views
     * draw a picture of a stage instead, with the reference (view.c). */
    const luz_uniforms *uniforms = &job->uniforms;
    const luz_draw *draws = job->frame->draws;
    if (uniforms->show != LUZ_VIEW_COLOR)
        counters->fragments_shaded = luz_view_shade_rows(uniforms, draws, by_id, framebuffer,
                                                         first_row, end_row, overdraw,
                                                         worker_index);
    else if (renderer->reference)
        counters->fragments_shaded = luz_fragment_shade_rows(uniforms, draws, by_id,
                                                             framebuffer, first_row, end_row);
    else
        counters->fragments_shaded = renderer->packet_rows(uniforms, draws, by_id, framebuffer,
                                                           first_row, end_row);
    counters->fragments_tested = tested;

    /* The probed pixel's bytes, before the hook can draw over them. */
    if (job->probe)
        luz_probe_capture(job->probe, framebuffer, first_row, end_row, band_index,
                          worker_index);

    /* The caller's work on top, while the band's rows are in this core's
     * cache. */
    if (job->hook && job->hook->after_band)
        job->hook->after_band(job->hook->context, framebuffer, first_row, end_row);
}

/* ---- the renderer ------------------------------------------------------ */

static int online_cpus(void)
{
    long count = sysconf(_SC_NPROCESSORS_ONLN);
    if (count < 1) return 1;
    return count > LUZ_MAX_THREADS ? LUZ_MAX_THREADS : (int)count;
}

luz_renderer *luz_renderer_create(const luz_renderer_desc *desc, luz_error *error)
{
    const luz_renderer_desc defaults = {0};
    if (desc == NULL) desc = &defaults;
    int threads = desc->thread_count;
    if (threads < LUZ_THREADS_AUTO || threads > LUZ_MAX_THREADS) {
        luz_error_set(error, "thread count %d: expected 0 (one per CPU) to %d", threads,
                      LUZ_MAX_THREADS);
        return NULL;
    }
    if (threads == 0 || threads == LUZ_THREADS_AUTO) threads = online_cpus();

    luz_renderer *renderer = calloc(1, sizeof *renderer);
    if (!renderer) {
        luz_error_set(error, "out of memory for the renderer");
        return NULL;
    }
    renderer->reference = desc->reference;
    renderer->packet_rows = luz_packet_rows_for(LUZ_PACKET_ISA_BEST);
    renderer->chunk_capacity = threads * CHUNKS_PER_THREAD;
    renderer->chunks = calloc((size_t)renderer->chunk_capacity, sizeof *renderer->chunks);
    renderer->pool = luz_thread_pool_create(threads);
    if (!renderer->chunks || !renderer->pool) {
        luz_error_set(error, "cannot start %d rendering threads", threads);
        luz_renderer_destroy(renderer);
        return NULL;
    }
    return renderer;
}

void luz_renderer_destroy(luz_renderer *renderer)
{
    if (!renderer) return;
    luz_thread_pool_destroy(renderer->pool);
    for (int i = 0; renderer->chunks && i < renderer->chunk_capacity; i++) {
        free(renderer->chunks[i].triangles);
        free(renderer->chunks[i].vertices);
    }
    free(renderer->chunks);
    free(renderer->by_id);
    free(renderer->bands);
    free(renderer->band_start);
    free(renderer->band_ids);
    free(renderer->overdraw);
    free(renderer);
}

void luz_renderer_set_packet_isa(luz_renderer *renderer, luz_packet_isa isa)
{
    renderer->packet_rows = luz_packet_rows_for(isa);
}

int luz_renderer_thread_count(const luz_renderer *renderer)
{
    return luz_thread_pool_thread_count(renderer->pool);
}

/* Splits the frame's draws into chunks of consecutive draws, one
 * geometry job each, and empties the chunks' triangle lists. */
static void split_into_chunks(luz_renderer *renderer, frame_job *job)
{
    const luz_frame *frame = job->frame;
    job->chunk_count = (frame->draw_count + MIN_DRAWS_PER_CHUNK - 1) / MIN_DRAWS_PER_CHUNK;
    if (job->chunk_count > renderer->chunk_capacity) job->chunk_count = renderer->chunk_capacity;
    if (job->chunk_count < 1) job->chunk_count = 1;
    job->draws_per_chunk = (frame->draw_count + job->chunk_count - 1) / job->chunk_count;
    if (job->draws_per_chunk < 1) job->draws_per_chunk = 1;
    for (int c = 0; c < job->chunk_count; c++) {
        triangle_list *list = &renderer->chunks[c];
        list->count = 0;
        list->out_of_memory = false;
        list->submitted = list->clipped = list->culled = 0;
        list->interpolation = job->uniforms.interpolation;
    }
}

/* Gives the set-up triangles ids 1, 2, ... in submission order (chunk by
 * chunk), through renderer->by_id. */
static int number_triangles(luz_renderer *renderer, frame_job *job, size_t *total,
                            luz_error *error)
{
    *total = 0;
    for (int c = 0; c < job->chunk_count; c++) {
        if (renderer->chunks[c].out_of_memory)
            return luz_error_set(error, "out of memory for the frame's triangles");
        *total += renderer->chunks[c].count;
    }
    if (*total >= UINT32_MAX)
        return luz_error_set(error, "%zu triangles: more than a frame supports", *total);
    if (*total + 1 > renderer->by_id_capacity) {
        const luz_triangle **by_id = realloc(renderer->by_id, (*total + 1) * sizeof *by_id);
        if (!by_id) return luz_error_set(error, "out of memory for the frame's triangles");
        renderer->by_id = by_id;
        renderer->by_id_capacity = *total + 1;
    }
    size_t id = 1;
    for (int c = 0; c < job->chunk_count; c++)
        for (size_t k = 0; k < renderer->chunks[c].count; k++)
            renderer->by_id[id++] = &renderer->chunks[c].triangles[k];

    job->triangle_count = *total;
    /* The viewer's step mode rasterises only the first triangles. */
    const uint32_t limit = job->triangle_limit;
    if (limit != 0 && limit < *total) job->triangle_count = limit;
    return 0;
}

/* Bins triangles 1 .. job->triangle_count to the bands their bounding
 * boxes touch, so that a band visits only its own triangles. Counting
 * first, then filling in id order, keeps each band's list in submission
 * order. */
static int bin_triangles(luz_renderer *renderer, frame_job *job, luz_error *error)
{
    const int band_count = job->band_count;
    if (band_count > renderer->band_capacity) {
        band_counters *bands = realloc(renderer->bands, (size_t)band_count * sizeof *bands);
        size_t *band_start = realloc(renderer->band_start,
                                     ((size_t)band_count + 1) * sizeof *band_start);
        if (bands) renderer->bands = bands;
        if (band_start) renderer->band_start = band_start;
        if (!bands || !band_start)
            return luz_error_set(error, "out of memory for the frame's bands");
        renderer->band_capacity = band_count;
    }

    size_t *start = renderer->band_start;
    memset(start, 0, ((size_t)band_count + 1) * sizeof *start);
    for (size_t id = 1; id <= job->triangle_count; id++) {
        const luz_triangle *triangle = renderer->by_id[id];
        for (int b = triangle->min_y / BAND_HEIGHT; b <= triangle->max_y / BAND_HEIGHT; b++)
            start[b + 1]++;
    }
    for (int b = 0; b < band_count; b++) start[b + 1] += start[b];

    if (start[band_count] > renderer->band_ids_capacity) {
        uint32_t *ids = realloc(renderer->band_ids, start[band_count] * sizeof *ids);
        if (!ids) return luz_error_set(error, "out of memory for the frame's bands");
        renderer->band_ids = ids;
        renderer->band_ids_capacity = start[band_count];
    }
    /* Fill, moving each band's start forward, then move the starts back. */
    for (size_t id = 1; id <= job->triangle_count; id++) {
        const luz_triangle *triangle = renderer->by_id[id];
        for (int b = triangle->min_y / BAND_HEIGHT; b <= triangle->max_y / BAND_HEIGHT; b++)
            renderer->band_ids[start[b]++] = (uint32_t)id;
    }
    for (int b = band_count; b > 0; b--) start[b] = start[b - 1];
    start[0] = 0;
    return 0;
}

/* The overdraw view's counters, one per pixel, allocated when first asked. */
static int prepare_overdraw(luz_renderer *renderer, frame_job *job, luz_error *error)
{
    if (job->uniforms.show != LUZ_VIEW_OVERDRAW) return 0;
    size_t pixels = (size_t)job->framebuffer->width * (size_t)job->framebuffer->height;
    if (pixels > renderer->overdraw_capacity) {
        uint32_t *overdraw = realloc(renderer->overdraw, pixels * sizeof *overdraw);
        if (!overdraw) return luz_error_set(error, "out of memory for the overdraw view");
        renderer->overdraw = overdraw;
        renderer->overdraw_capacity = pixels;
    }
    job->overdraw = renderer->overdraw;
    return 0;
}

static void collect_stats(const luz_renderer *renderer, const frame_job *job,
                          size_t triangle_total, luz_frame_stats *stats)
{
    for (int c = 0; c < job->chunk_count; c++) {
        stats->triangles_submitted += renderer->chunks[c].submitted;
        stats->triangles_clipped += renderer->chunks[c].clipped;
        stats->triangles_culled += renderer->chunks[c].culled;
    }
    stats->triangles_rasterised = triangle_total;
    for (int b = 0; b < job->band_count; b++) {
        stats->fragments_tested += renderer->bands[b].fragments_tested;
        stats->fragments_shaded += renderer->bands[b].fragments_shaded;
    }
}

luz_uniforms luz_uniforms_of(const luz_frame *frame, const luz_render_options *options)
{
    const luz_render_options defaults = {0};
    if (options == NULL) options = &defaults;
    luz_uniforms uniforms;
    memset(&uniforms, 0, sizeof uniforms);
    uniforms.view_projection = luz_mat4_multiply(frame->projection, frame->view);
    uniforms.projection = frame->projection;
    uniforms.shade = luz_shade_uniforms_of(frame->eye, &frame->lights);
    uniforms.clear_colour = frame->clear_colour;
    uniforms.show = options->view;
    uniforms.interpolation = options->interpolation;
    return uniforms;
}

/* What the pipeline needs of the caller's data that no type can say. */
static int check_frame(const luz_frame *frame, const luz_render_options *options,
                       luz_error *error)
{
    if (frame->draw_count < 0 || (frame->draw_count > 0 && frame->draws == NULL))
        return luz_error_set(error, "frame: %d draws but no draw array", frame->draw_count);
    for (int d = 0; d < frame->draw_count; d++)
        if (frame->draws[d].mesh == NULL) return luz_error_set(error, "draw %d: no mesh", d);
    if ((unsigned)options->view >= LUZ_VIEW_COUNT)
        return luz_error_set(error, "render options: view %d is not a luz_view",
                             (int)options->view);
    if (options->interpolation != LUZ_INTERPOLATION_PERSPECTIVE &&
        options->interpolation != LUZ_INTERPOLATION_AFFINE)
        return luz_error_set(error, "render options: interpolation %d is not a "
                             "luz_interpolation", (int)options->interpolation);
    return 0;
}

int luz_renderer_draw(luz_renderer *renderer, const luz_frame *frame,
                      luz_framebuffer *framebuffer, const luz_render_options *options,
                      luz_error *error)
{
    const double start = now_ms();
    const luz_render_options defaults = {0};
    if (options == NULL) options = &defaults;
    if (check_frame(frame, options, error) != 0) return -1;
    frame_job job = {
        .renderer = renderer,
        .frame = frame,
        .framebuffer = framebuffer,
        .hook = options->hook,
        .probe = options->probe,
        .triangle_limit = options->triangle_limit,
        .band_count = (framebuffer->height + BAND_HEIGHT - 1) / BAND_HEIGHT,
    };

    /* Uniforms, once for the frame. */
    job.uniforms = luz_uniforms_of(frame, options);

    /* Phase 1: geometry (vertex stage, clipping, setup), in chunks of
     * consecutive draws; then number the triangles and bin them to bands. */
    split_into_chunks(renderer, &job);
    luz_thread_pool_run(renderer->pool, job.chunk_count, geometry_job, &job);
    size_t triangle_total;
    if (number_triangles(renderer, &job, &triangle_total, error) != 0) return -1;
    if (bin_triangles(renderer, &job, error) != 0) return -1;
    const double geometry_end = now_ms();

    /* Phase 2: bands of rows (clear, raster and depth test, fragments,
     * the caller's hook). */
    if (prepare_overdraw(renderer, &job, error) != 0) return -1;
    if (job.probe) luz_probe_begin(job.probe, framebuffer, options->view);
    luz_thread_pool_run(renderer->pool, job.band_count, band_job, &job);

    /* The probed pixel's story (luz/probe.h), from what the bands left. */
    if (job.probe)
        luz_probe_explain(job.probe, &job.uniforms, frame->draws, renderer->by_id,
                          job.triangle_count, framebuffer, job.overdraw, !renderer->reference);
    const double end = now_ms();

    luz_frame_stats *stats = options->stats;
    if (stats) {
        memset(stats, 0, sizeof *stats);
        stats->geometry_ms = geometry_end - start;
        stats->raster_ms = end - geometry_end;
        stats->total_ms = end - start;
        collect_stats(renderer, &job, triangle_total, stats);
    }
    return 0;
}
