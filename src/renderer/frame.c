/*
 * frame.c: the renderer, and the draw function that reads as the pipeline.
 *
 * luz_renderer_draw() runs the stages in two phases:
 *
 *   0. Uniforms: what every stage reads that is the same for the whole
 *      frame (matrices, the eye, the lights, the spot's cone, the
 *      exposure), once.
 *
 *   1. Geometry (geometry.c), in batches of a few thousand triangles over
 *      all the draws, one job each:
 *        vertex stage    every vertex to clip space, with its varyings
 *        clipping        each triangle against the near, far and guard planes
 *        setup           each clipped triangle to edges and planes; back
 *                        faces culled
 *      Triangles get ids 1, 2, ... in submission order, and each is binned
 *      to the bands of rows its bounding box touches, still in id order.
 *
 *   2. Bands, per band of rows (one job each):
 *        clear           the band's depth and visibility (each sample's,
 *                        with four samples a pixel; with colour_only, in
 *                        the thread's band buffers, which stay in cache)
 *        raster + depth  the band's triangles, in id order, at each pixel
 *                        centre (or at each of the four sample points)
 *        fragment        each visible pixel shaded once (a lit colour
 *                        exposed and tone-mapped), and the
 *                        background given the clear colour (or, for a
 *                        --view other than color, a picture of a stage:
 *                        view.c); with four samples, once per pixel for
 *                        each triangle that won one of its samples
 *        resolve         four samples only: each pixel's samples averaged
 *                        (resolve.c)
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
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "renderer/cpu.h"
#include "renderer/pipeline.h"
#include "luz/renderer.h"

/* Rows per band: small enough to balance two or more threads and keep a
 * band's depth and visibility rows in cache, large enough that a triangle
 * rarely spans many bands. */
#define BAND_HEIGHT 16
_Static_assert((BAND_HEIGHT & (BAND_HEIGHT - 1)) == 0, "luz_geometry_run bins by a shift");

typedef struct band_counters {
    uint64_t fragments_tested;
    uint64_t fragments_shaded;
} band_counters;

struct luz_renderer {
    luz_thread_pool *pool;
    luz_geometry *geometry;         /* phase 1's buffers */
    band_counters *bands;
    int band_capacity;
    bool reference;                 /* fragment.c's shading, not the packets */
    luz_kernels kernels;            /* the stages in lanes, of the instruction
                                       set chosen at creation (cpu.h) */
    uint32_t *overdraw;             /* depth tests per pixel (per sample), for
                                       the overdraw view only; allocated when
                                       first asked */
    size_t overdraw_capacity;
    luz_sample_buffers samples;     /* four samples' depth and winners,
                                       the whole frame's allocated when a
                                       frame first asks for them (not one
                                       drawn in the band buffers) */
    size_t sample_capacity;         /* pixels they hold */
    size_t plane_capacity;          /* pixels the views' planes hold */
    luz_sample_band *sample_bands;  /* one per thread: a band's mixed pixels */
    luz_winner_pattern winner_patterns[LUZ_WINNER_PATTERNS];   /* the sort's,
                                       made once at creation */
    size_t sample_band_capacity;    /* pixels each holds room for */
    int sample_band_count;          /* the threads' */
    float *band_depth;              /* one band of depth and visibility per
                                       thread (luz_render_options.colour_only),
                                       each sample's with four samples */
    uint32_t *band_visibility;
    size_t band_scratch_slots;      /* samples each thread's band holds */
    uint32_t *band_first_winner;    /* four samples: one band of first
                                       winners per thread */
    size_t band_first_pixels;       /* pixels each thread's holds */
};

/* What the jobs of one frame share; read-only for the jobs except their
 * own band slot. */
typedef struct frame_job {
    luz_renderer *renderer;
    const luz_frame *frame;
    luz_framebuffer *framebuffer;
    luz_uniforms uniforms;
    luz_geometry_result geometry;   /* phase 1's triangles, binned */
    uint32_t *overdraw;             /* NULL unless the overdraw view (with
                                       four samples, one plane per sample) */
    luz_sample_buffers *samples;    /* NULL for one sample a pixel */
    const luz_band_hook *hook;      /* NULL, or called after each band */
    luz_pixel_probe *probe;         /* NULL, or the pixel to explain */
    bool band_scratch;              /* depth and visibility in the threads'
                                       band buffers, not the framebuffer's */
} frame_job;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

/* ---- phase 2: bands ---------------------------------------------------- */

/* Raster and depth test, the band's triangles in submission order, at
 * each pixel centre, or with four samples at each sample point into its
 * plane. Each triangle's record is asked for ahead
 * (luz_prefetch_triangle_ahead). At four samples the set's list kernel
 * takes the whole list in one call. */
static uint64_t raster_band(const frame_job *job, luz_framebuffer *framebuffer,
                            luz_sample_buffers *samples, int band_index, int first_row,
                            int end_row)
{
    const luz_triangle *const *by_id = job->geometry.by_id;
    uint32_t *overdraw = job->overdraw;
    const size_t pixels = (size_t)framebuffer->width * (size_t)framebuffer->height;
    uint64_t tested = 0;
    const size_t *band_start = job->geometry.band_start;
    const uint32_t *ids = job->geometry.band_ids;
    const size_t list_end = band_start[band_index + 1];
    luz_raster_list_function *raster_list = job->renderer->kernels.raster_list;
    if (samples && raster_list && job->uniforms.bug != LUZ_BUG_NO_DEPTH_TEST &&
        luz_raster_in_lanes(samples, overdraw))
        return raster_list(by_id, ids, band_start[band_index], list_end, samples, first_row,
                           end_row);
    for (size_t k = band_start[band_index]; k < list_end; k++) {
        luz_prefetch_triangle_ahead(by_id, ids, k, list_end);
        const uint32_t id = ids[k];
        const luz_triangle *triangle = by_id[id];
        if (job->uniforms.bug == LUZ_BUG_NO_DEPTH_TEST) {   /* luz/bug.h */
            for (int s = 0; s < (samples ? samples->samples : 1); s++)
                tested += luz_raster_triangle_always(
                    triangle, id, samples ? samples->visibility + s : framebuffer->visibility,
                    framebuffer->width, samples ? LUZ_MAX_SAMPLES : 1,
                    luz_sample_offset_of(samples ? samples->samples : 1, s), first_row, end_row,
                    overdraw ? overdraw + (size_t)s * pixels : NULL);
        } else if (samples) {
            tested += luz_raster_triangle_samples(triangle, id, samples, first_row, end_row,
                                                  overdraw, job->renderer->kernels.raster_groups);
        } else if (overdraw) {
            tested += luz_raster_triangle_counting(triangle, id, framebuffer, first_row,
                                                   end_row, overdraw);
        } else {
            tested += luz_raster_triangle_spans(triangle, id, framebuffer, first_row, end_row,
                                                job->renderer->kernels.centre_span_test);
        }
    }
    return tested;
}

/* Fragment stage: shade each visible pixel once, one pixel at a time (the
 * reference, fragment.c) or a packet of them at a time (the same
 * equations as SIMD vectors, fragment_packet.c). The teaching views draw
 * a picture of a stage instead, with the reference (view.c). */
static uint64_t shade_band(const frame_job *job, luz_framebuffer *target, int first_row,
                           int end_row, const uint32_t *overdraw, int worker_index)
{
    const luz_renderer *renderer = job->renderer;
    const luz_uniforms *uniforms = &job->uniforms;
    const luz_draw *draws = job->frame->draws;
    const luz_triangle *const *by_id = job->geometry.by_id;
    if (uniforms->show != LUZ_VIEW_COLOR && uniforms->show != LUZ_VIEW_BANDS)
        return luz_view_shade_rows(uniforms, draws, by_id, target, first_row, end_row,
                                   overdraw, worker_index);
    /* A frame with a bug (luz/bug.h) is shaded by the reference: the
     * packets know nothing of bugs. */
    if (renderer->reference || uniforms->show == LUZ_VIEW_BANDS || uniforms->bug != LUZ_BUG_NONE)
        return luz_fragment_shade_rows(uniforms, draws, by_id, target, first_row, end_row);
    return renderer->kernels.packet_rows(uniforms, draws, by_id, target, first_row, end_row);
}

/* The fragment stage and the resolve of a band of four samples a pixel.
 * Each pixel's first winner is shaded as one sample would be, every pixel
 * of the band (the packets, or the reference); then the other winners of
 * the pixels an edge crosses, as a list; then those pixels are resolved
 * (resolve.c). The views shade every sample's plane and resolve every
 * pixel, the plain way. */
static uint64_t shade_and_resolve_samples(const frame_job *job, luz_sample_buffers *samples,
                                          int first_row, int end_row, int worker_index)
{
    luz_framebuffer *framebuffer = job->framebuffer;
    const luz_uniforms *uniforms = &job->uniforms;
    uint64_t shaded = 0;
    if (uniforms->show == LUZ_VIEW_COLOR || uniforms->show == LUZ_VIEW_BANDS) {
        luz_sample_band *band = &job->renderer->sample_bands[worker_index];
        luz_samples_sort_winners(samples, first_row, end_row, band,
                                 job->renderer->kernels.mixed_pixels);
        /* The first winners into the image. */
        luz_framebuffer first_winners = *framebuffer;
        first_winners.visibility = samples->first_winner;
        shaded += shade_band(job, &first_winners, first_row, end_row, NULL, worker_index);
        const bool reference = job->renderer->reference || uniforms->show == LUZ_VIEW_BANDS ||
                               uniforms->bug != LUZ_BUG_NONE;
        shaded += (reference ? luz_fragment_shade_list : job->renderer->kernels.packet_list)(
            uniforms, job->frame->draws, job->geometry.by_id, framebuffer->channel_order,
            band->extra, band->extra_count, band->extra_colour);
        uint8_t background[4];
        luz_pixel_write(background, luz_pixel_layout_of(framebuffer->channel_order),
                        uniforms->clear_colour);
        luz_samples_resolve_winners(band, framebuffer, background);
        return shaded;
    }
    const size_t pixels = (size_t)framebuffer->width * (size_t)framebuffer->height;
    luz_samples_split_rows(samples, first_row, end_row);
    for (int k = 0; k < samples->samples; k++)
        shaded += shade_band(job, &samples->plane[k], first_row, end_row,
                             job->overdraw ? job->overdraw + (size_t)k * pixels : NULL,
                             worker_index);
    luz_samples_resolve_planes(samples, framebuffer, first_row, end_row);
    return shaded;
}

/* A pointer to the thread's band buffer `own`, set back by `before`
 * elements, so that the stages index it as a whole frame's array (at
 * y * width for row y) although it holds the band's rows alone. Through
 * uintptr_t: it points before the buffer, and only rows of the band are
 * ever read or written through it. */
static void *set_back(void *own, size_t before, size_t element_size)
{
    return (void *)((uintptr_t)own - before * element_size);
}

/* The framebuffer with depth and visibility moved to the thread's band
 * buffers, which hold rows [first_row, first_row + BAND_HEIGHT). At
 * 1920x1080 a band's 245 KB stay in L2, where the framebuffer's 16 MB went
 * to memory and back every frame. */
static luz_framebuffer band_buffers(const frame_job *job, int first_row, int worker_index)
{
    luz_framebuffer band = *job->framebuffer;
    const luz_renderer *renderer = job->renderer;
    const size_t own = (size_t)worker_index * renderer->band_scratch_slots;
    const size_t before = (size_t)first_row * (size_t)band.width;
    band.depth = set_back(renderer->band_depth + own, before, sizeof(float));
    band.visibility = set_back(renderer->band_visibility + own, before, sizeof(uint32_t));
    return band;
}

/* The same for four samples: the sample buffers' depth, winners and
 * first winners of the band's rows in the thread's band buffers (36
 * bytes a pixel: 1.1 MB a band at 1920x1080, in L2 and L3, where the
 * whole frame's 75 MB went to memory and back). */
static void band_sample_buffers(const frame_job *job, int first_row, int worker_index,
                                luz_sample_buffers *band)
{
    const luz_renderer *renderer = job->renderer;
    *band = *job->samples;
    const size_t own = (size_t)worker_index * renderer->band_scratch_slots;
    const size_t before = (size_t)first_row * (size_t)band->width;
    band->depth = set_back(renderer->band_depth + own, before * LUZ_MAX_SAMPLES, sizeof(float));
    band->visibility =
        set_back(renderer->band_visibility + own, before * LUZ_MAX_SAMPLES, sizeof(uint32_t));
    band->first_winner =
        set_back(renderer->band_first_winner + (size_t)worker_index * renderer->band_first_pixels,
                 before, sizeof(uint32_t));
}

static void band_job(void *context, int band_index, int worker_index)
{
    frame_job *job = context;
    luz_sample_buffers *samples = job->samples;
    int first_row = band_index * BAND_HEIGHT;
    int end_row = first_row + BAND_HEIGHT;
    if (end_row > job->framebuffer->height) end_row = job->framebuffer->height;
    /* Where this band's depth and visibility go (each sample's, with four
     * samples): the framebuffer's (the sample buffers'), or the thread's
     * band buffers (colour is the framebuffer's either way). */
    luz_framebuffer scratch;
    luz_sample_buffers band_samples;
    luz_framebuffer *framebuffer = job->framebuffer;
    if (job->band_scratch && samples) {
        band_sample_buffers(job, first_row, worker_index, &band_samples);
        samples = &band_samples;
    } else if (job->band_scratch) {
        scratch = band_buffers(job, first_row, worker_index);
        framebuffer = &scratch;
    }
    band_counters *counters = &job->renderer->bands[band_index];
    const int sample_count = samples ? samples->samples : 1;

    /* Clear depth and visibility (each sample's). Not colour: the
     * fragment stage (or the view, or the resolve) writes every pixel of
     * the band, the clear colour where no triangle wins, so each colour
     * byte is written once. */
    if (samples)
        luz_samples_clear_rows(samples, first_row, end_row);
    else
        luz_framebuffer_clear_rows(framebuffer, first_row, end_row);

    /* The overdraw view counts every depth test of the band's pixels (of
     * each sample). */
    if (job->overdraw) {
        const size_t pixels = (size_t)framebuffer->width * (size_t)framebuffer->height;
        for (int k = 0; k < sample_count; k++)
            memset(job->overdraw + (size_t)k * pixels + (size_t)first_row * framebuffer->width,
                   0, (size_t)(end_row - first_row) * framebuffer->width * sizeof *job->overdraw);
    }

    /* Raster and depth test. */
    const uint64_t tested = raster_band(job, framebuffer, samples, band_index, first_row, end_row);

    /* Fragment stage (and, with four samples, the resolve). */
    if (samples)
        counters->fragments_shaded =
            shade_and_resolve_samples(job, samples, first_row, end_row, worker_index);
    else
        counters->fragments_shaded =
            shade_band(job, framebuffer, first_row, end_row, job->overdraw, worker_index);
    counters->fragments_tested = tested;

    /* The bands view tints what the colour view drew by the thread. */
    if (job->uniforms.show == LUZ_VIEW_BANDS)
        luz_view_tint_rows(framebuffer, first_row, end_row, worker_index);

    /* The probed pixel's bytes, before the hook can draw over them. */
    if (job->probe)
        luz_probe_capture(job->probe, framebuffer, first_row, end_row, band_index,
                          worker_index);

    /* The caller's work on top, while the band's rows are in this core's
     * cache. */
    if (job->hook && job->hook->after_band)
        job->hook->after_band(job->hook->context, job->framebuffer, first_row, end_row);
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
    luz_isa isa;
    if (luz_isa_chosen(&isa, error) != 0) return NULL;

    luz_renderer *renderer = calloc(1, sizeof *renderer);
    if (!renderer) {
        luz_error_set(error, "out of memory for the renderer");
        return NULL;
    }
    renderer->reference = desc->reference;
    luz_samples_winner_patterns(renderer->winner_patterns);
    renderer->geometry = luz_geometry_create(threads);
    renderer->pool = luz_thread_pool_create(threads);
    if (!renderer->geometry || !renderer->pool) {
        luz_error_set(error, "cannot start %d rendering threads", threads);
        luz_renderer_destroy(renderer);
        return NULL;
    }
    luz_renderer_set_isa(renderer, isa);
    return renderer;
}

static void free_sample_bands(luz_renderer *renderer)
{
    if (renderer->sample_bands) {
        for (int t = 0; t < renderer->sample_band_count; t++) {
            free(renderer->sample_bands[t].mixed);
            free(renderer->sample_bands[t].extra);
            free(renderer->sample_bands[t].extra_colour);
            free(renderer->sample_bands[t].row_mixed);
        }
    }
    free(renderer->sample_bands);
    renderer->sample_bands = NULL;
    renderer->sample_band_capacity = 0;
    renderer->sample_band_count = 0;
}

void luz_renderer_destroy(luz_renderer *renderer)
{
    if (!renderer) return;
    luz_thread_pool_destroy(renderer->pool);
    luz_geometry_destroy(renderer->geometry);
    free(renderer->bands);
    free(renderer->overdraw);
    free(renderer->samples.depth);
    free(renderer->samples.visibility);
    free(renderer->samples.first_winner);
    for (int k = 0; k < LUZ_MAX_SAMPLES; k++) {
        free(renderer->samples.plane[k].colour);
        free(renderer->samples.plane[k].depth);
        free(renderer->samples.plane[k].visibility);
    }
    free_sample_bands(renderer);
    free(renderer->band_depth);
    free(renderer->band_visibility);
    free(renderer->band_first_winner);
    free(renderer);
}

void luz_renderer_set_isa(luz_renderer *renderer, luz_isa isa)
{
    renderer->kernels = luz_kernels_of(isa);
    luz_geometry_set_kernels(renderer->geometry, &renderer->kernels);
}

const char *luz_renderer_isa(const luz_renderer *renderer)
{
    return luz_isa_name(renderer->kernels.isa);
}

int luz_isa_check(luz_error *error)
{
    luz_isa isa;
    return luz_isa_chosen(&isa, error);
}

int luz_renderer_thread_count(const luz_renderer *renderer)
{
    return luz_thread_pool_thread_count(renderer->pool);
}

/* One counter pair per band. */
static int prepare_bands(luz_renderer *renderer, int band_count, luz_error *error)
{
    if (band_count <= renderer->band_capacity) return 0;
    band_counters *bands = realloc(renderer->bands, (size_t)band_count * sizeof *bands);
    if (!bands) return luz_error_set(error, "out of memory for the frame's bands");
    renderer->bands = bands;
    renderer->band_capacity = band_count;
    return 0;
}

/* Whether the frame's bands keep depth and visibility (each sample's) in
 * the threads' band buffers: asked for by luz_render_options.colour_only,
 * and possible when nothing reads them after the bands, which a probe
 * does. A teaching view at four samples splits each sample's plane from
 * the band's rows alone (luz_samples_split_rows), and a view reads no
 * other row of its plane (view.c), so it draws from the band buffers
 * too: only its planes are the whole frame's. */
static bool draws_in_band_buffers(const frame_job *job, const luz_render_options *options)
{
    return options->colour_only && !job->probe;
}

/* The buffers of a frame of more than one sample a pixel
 * (luz_sample_buffers), allocated when a frame first asks for them and
 * kept (grown as needed); the whole frame's depth and winners only when
 * the bands do not keep them in their own buffers, the views' planes
 * only when a view asks. */
static int prepare_samples(luz_renderer *renderer, frame_job *job,
                           const luz_render_options *options, luz_error *error)
{
    if (job->uniforms.samples <= 1) return 0;
    const luz_framebuffer *framebuffer = job->framebuffer;
    const size_t pixels = (size_t)framebuffer->width * (size_t)framebuffer->height;
    luz_sample_buffers *samples = &renderer->samples;
    if (!draws_in_band_buffers(job, options) && pixels > renderer->sample_capacity) {
        renderer->sample_capacity = 0;
        free(samples->depth);
        free(samples->visibility);
        free(samples->first_winner);
        samples->depth = malloc(pixels * LUZ_MAX_SAMPLES * sizeof *samples->depth);
        samples->visibility = malloc(pixels * LUZ_MAX_SAMPLES * sizeof *samples->visibility);
        samples->first_winner = malloc(pixels * sizeof *samples->first_winner);
        if (!samples->depth || !samples->visibility || !samples->first_winner)
            return luz_error_set(error, "out of memory for %d samples a pixel at %dx%d",
                                 job->uniforms.samples, framebuffer->width, framebuffer->height);
        renderer->sample_capacity = pixels;
    }
    const bool view = job->uniforms.show != LUZ_VIEW_COLOR && job->uniforms.show != LUZ_VIEW_BANDS;
    if (view && pixels > renderer->plane_capacity) {
        renderer->plane_capacity = 0;
        for (int k = 0; k < LUZ_MAX_SAMPLES; k++) {
            luz_framebuffer *plane = &samples->plane[k];
            free(plane->colour);
            free(plane->depth);
            free(plane->visibility);
            plane->colour = malloc(pixels * 4);
            plane->depth = malloc(pixels * sizeof *plane->depth);
            plane->visibility = malloc(pixels * sizeof *plane->visibility);
            if (!plane->colour || !plane->depth || !plane->visibility)
                return luz_error_set(error, "out of memory for %d samples a pixel at %dx%d",
                                     job->uniforms.samples, framebuffer->width,
                                     framebuffer->height);
        }
        renderer->plane_capacity = pixels;
    }
    /* A band's mixed pixels: at most each of its pixels, with at most
     * three other winners each. */
    const size_t band_pixels = (size_t)BAND_HEIGHT * (size_t)framebuffer->width;
    if (band_pixels > renderer->sample_band_capacity) {
        free_sample_bands(renderer);
        const int threads = luz_thread_pool_thread_count(renderer->pool);
        renderer->sample_bands = calloc((size_t)threads, sizeof *renderer->sample_bands);
        if (!renderer->sample_bands)
            return luz_error_set(error, "out of memory for %d samples a pixel",
                                 job->uniforms.samples);
        renderer->sample_band_count = threads;
        for (int t = 0; t < threads; t++) {
            luz_sample_band *band = &renderer->sample_bands[t];
            band->mixed = malloc(band_pixels * sizeof *band->mixed);
            band->extra = malloc(3 * band_pixels * sizeof *band->extra);
            band->extra_colour = calloc(3 * band_pixels, sizeof *band->extra_colour);
            band->patterns = renderer->winner_patterns;
            band->row_mixed = malloc((size_t)framebuffer->width * sizeof *band->row_mixed);
            if (!band->mixed || !band->extra || !band->extra_colour || !band->row_mixed) {
                free_sample_bands(renderer);
                return luz_error_set(error, "out of memory for %d samples a pixel",
                                     job->uniforms.samples);
            }
        }
        renderer->sample_band_capacity = band_pixels;
    }
    samples->samples = job->uniforms.samples;
    samples->width = framebuffer->width;
    samples->height = framebuffer->height;
    for (int k = 0; k < LUZ_MAX_SAMPLES; k++) {
        luz_framebuffer *plane = &samples->plane[k];
        plane->width = framebuffer->width;
        plane->height = framebuffer->height;
        plane->channel_order = framebuffer->channel_order;
        plane->own_colour = NULL;
    }
    job->samples = samples;
    return 0;
}

/* Each thread's band of depth and visibility (each sample's, and with
 * four samples the first winners), for a frame drawn with
 * luz_render_options.colour_only (draws_in_band_buffers), allocated when
 * first asked and kept (grown as needed). Each thread's share starts on a
 * cache line of its own: BAND_HEIGHT * width * 4 bytes is a multiple of
 * 64. */
static int prepare_band_scratch(luz_renderer *renderer, frame_job *job,
                                const luz_render_options *options, luz_error *error)
{
    if (!draws_in_band_buffers(job, options)) return 0;
    const size_t band_pixels = (size_t)BAND_HEIGHT * (size_t)job->framebuffer->width;
    const size_t band_slots = band_pixels * (size_t)job->uniforms.samples;
    const size_t threads = (size_t)luz_thread_pool_thread_count(renderer->pool);
    if (band_slots > renderer->band_scratch_slots) {
        free(renderer->band_depth);
        free(renderer->band_visibility);
        renderer->band_depth = aligned_alloc(64, band_slots * threads * sizeof(float));
        renderer->band_visibility = aligned_alloc(64, band_slots * threads * sizeof(uint32_t));
        renderer->band_scratch_slots = band_slots;
        if (!renderer->band_depth || !renderer->band_visibility) {
            free(renderer->band_depth);
            free(renderer->band_visibility);
            renderer->band_depth = NULL;
            renderer->band_visibility = NULL;
            renderer->band_scratch_slots = 0;
            return luz_error_set(error, "out of memory for the bands' depth at %dx%d",
                                 job->framebuffer->width, job->framebuffer->height);
        }
    }
    if (job->samples && band_pixels > renderer->band_first_pixels) {
        free(renderer->band_first_winner);
        renderer->band_first_winner = aligned_alloc(64, band_pixels * threads * sizeof(uint32_t));
        renderer->band_first_pixels = band_pixels;
        if (!renderer->band_first_winner) {
            renderer->band_first_pixels = 0;
            return luz_error_set(error, "out of memory for the bands' samples at %dx%d",
                                 job->framebuffer->width, job->framebuffer->height);
        }
    }
    job->band_scratch = true;
    return 0;
}

/* The overdraw view's counters, one per pixel (per sample), allocated when
 * first asked. */
static int prepare_overdraw(luz_renderer *renderer, frame_job *job, luz_error *error)
{
    if (job->uniforms.show != LUZ_VIEW_OVERDRAW) return 0;
    size_t pixels = (size_t)job->framebuffer->width * (size_t)job->framebuffer->height *
                    (size_t)(job->uniforms.samples > 1 ? job->uniforms.samples : 1);
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
                          luz_frame_stats *stats)
{
    stats->triangles_submitted = job->geometry.triangles_submitted;
    stats->triangles_clipped = job->geometry.triangles_clipped;
    stats->triangles_culled = job->geometry.triangles_culled;
    stats->draws_culled = job->geometry.draws_culled;
    stats->isa = luz_renderer_isa(renderer);
    stats->memory_bytes = luz_geometry_memory(renderer->geometry) +
                          (size_t)renderer->band_capacity * sizeof *renderer->bands +
                          renderer->overdraw_capacity * sizeof *renderer->overdraw +
                          renderer->sample_capacity *
                              (LUZ_MAX_SAMPLES * (sizeof(float) + sizeof(uint32_t)) +
                               sizeof(uint32_t)) +
                          renderer->plane_capacity * LUZ_MAX_SAMPLES *
                              (4 + sizeof(float) + sizeof(uint32_t)) +
                          renderer->sample_band_capacity *
                              (size_t)renderer->sample_band_count *
                              (sizeof(luz_mixed_pixel) +
                               3 * (sizeof(luz_fragment_ref) + sizeof(uint32_t))) +
                          (renderer->band_scratch_slots * (sizeof(float) + sizeof(uint32_t)) +
                           renderer->band_first_pixels * sizeof(uint32_t)) *
                              (size_t)luz_thread_pool_thread_count(renderer->pool);
    stats->triangles_rasterised = job->geometry.triangle_total;
    for (int b = 0; b < job->geometry.band_count; b++) {
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
    uniforms.view = frame->view;
    uniforms.shade = luz_shade_uniforms_of(frame->eye, &frame->lights);
    uniforms.clear_colour = frame->clear_colour;
    /* 2^EV, exact for a whole EV (exp2f of an integer is a power of two). */
    uniforms.output_exposure = frame->output.exposure;
    uniforms.exposure_scale = exp2f(frame->output.exposure);
    uniforms.tone_map = frame->output.tone_map;
    uniforms.output_is_identity =
        frame->output.tone_map == LUZ_TONE_MAP_CLAMP && frame->output.exposure == 0.0f;
    uniforms.show = options->view;
    uniforms.bug = options->bug;
    /* uv-affine is --interp affine's switch, hidden behind a bug's name. */
    uniforms.interpolation = options->bug == LUZ_BUG_UV_AFFINE ? LUZ_INTERPOLATION_AFFINE
                                                               : options->interpolation;
    uniforms.samples = frame->samples > 1 ? frame->samples : 1;
    return uniforms;
}

/* What the pipeline needs of the caller's data that no type can say. */
/* What luz/frame.h forbids in the lights: a strength outside [0, 1], a
 * negative shininess, a cone outside 0 <= inner <= outer <= 89, a reach
 * below 0 (0 is SCENE.md's 10), or any of them not a finite number. The
 * shading divides by the reach and raises to the shininess, so a value
 * past these would make no picture SCENE.md defines. */
static int check_lights(const luz_lights *lights, luz_error *error)
{
    const luz_light *terms[LUZ_TERM_COUNT] = {&lights->ambient, &lights->diffuse,
                                              &lights->specular, &lights->point,
                                              &lights->spot, &lights->directional};
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        const float strength = terms[term]->strength;
        if (!(strength >= 0.0f && strength <= 1.0f))
            return luz_error_set(error, "frame: the %s light's strength %g: expected a number "
                                 "in [0, 1]", luz_term_name((luz_term)term), (double)strength);
    }
    if (!(lights->shininess >= 0.0f && isfinite(lights->shininess)))
        return luz_error_set(error, "frame: shininess %g: expected a finite number >= 0",
                             (double)lights->shininess);
    const float inner = lights->spot_inner_degrees, outer = lights->spot_outer_degrees;
    if (!(inner >= 0.0f && inner <= outer && outer <= 89.0f))
        return luz_error_set(error, "frame: spot cone %g to %g degrees: expected 0 <= inner <= "
                             "outer <= 89", (double)inner, (double)outer);
    if (!(lights->spot_reach >= 0.0f && isfinite(lights->spot_reach)))
        return luz_error_set(error, "frame: spot_reach %g: expected a finite number above 0 "
                             "(or 0 for SCENE.md's 10)", (double)lights->spot_reach);
    return 0;
}

static int check_frame(const luz_frame *frame, const luz_render_options *options,
                       luz_error *error)
{
    if (check_lights(&frame->lights, error) != 0) return -1;
    if (frame->draw_count < 0 || (frame->draw_count > 0 && frame->draws == NULL))
        return luz_error_set(error, "frame: %d draws but no draw array", frame->draw_count);
    for (int d = 0; d < frame->draw_count; d++)
        if (frame->draws[d].mesh == NULL) return luz_error_set(error, "draw %d: no mesh", d);
    if (frame->samples != 0 && frame->samples != 1 && frame->samples != 4)
        return luz_error_set(error, "frame: %d samples a pixel: expected 1 or 4 (0 means 1)",
                             frame->samples);
    if ((unsigned)frame->output.tone_map >= LUZ_TONE_MAP_COUNT)
        return luz_error_set(error, "frame: tone map %d is not a luz_tone_map",
                             (int)frame->output.tone_map);
    if (!isfinite(frame->output.exposure))
        return luz_error_set(error, "frame: exposure %g EV is not a finite number",
                             (double)frame->output.exposure);
    if ((unsigned)options->view >= LUZ_VIEW_COUNT)
        return luz_error_set(error, "render options: view %d is not a luz_view",
                             (int)options->view);
    if (options->interpolation != LUZ_INTERPOLATION_PERSPECTIVE &&
        options->interpolation != LUZ_INTERPOLATION_AFFINE)
        return luz_error_set(error, "render options: interpolation %d is not a "
                             "luz_interpolation", (int)options->interpolation);
    if ((unsigned)options->bug >= LUZ_BUG_COUNT)
        return luz_error_set(error, "render options: bug %d is not a luz_bug",
                             (int)options->bug);
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
    };

    /* Uniforms, once for the frame. */
    job.uniforms = luz_uniforms_of(frame, options);

    /* Phase 1: geometry (vertex stage, clipping, setup) in batches over the
     * threads; the triangles numbered and binned to bands. */
    if (luz_geometry_run(renderer->geometry, renderer->pool, frame, &job.uniforms, framebuffer,
                         BAND_HEIGHT, options->triangle_limit, &job.geometry, error) != 0)
        return -1;
    const double geometry_end = now_ms();

    /* Phase 2: bands of rows (clear, raster and depth test, fragments,
     * the caller's hook). */
    if (prepare_bands(renderer, job.geometry.band_count, error) != 0) return -1;
    if (prepare_samples(renderer, &job, options, error) != 0) return -1;
    if (prepare_overdraw(renderer, &job, error) != 0) return -1;
    if (prepare_band_scratch(renderer, &job, options, error) != 0) return -1;
    if (job.probe) luz_probe_begin(job.probe, framebuffer, options->view);
    luz_thread_pool_run(renderer->pool, job.geometry.band_count, band_job, &job);

    /* The probed pixel's story (luz/probe.h), from what the bands left. */
    if (job.probe)
        luz_probe_explain(job.probe, &job.uniforms, frame->draws, job.geometry.by_id,
                          job.geometry.triangle_count, framebuffer, job.samples, job.overdraw,
                          renderer->reference || job.uniforms.bug != LUZ_BUG_NONE
                              ? NULL
                              : renderer->kernels.packet_list);
    const double end = now_ms();

    luz_frame_stats *stats = options->stats;
    if (stats) {
        memset(stats, 0, sizeof *stats);
        stats->geometry_ms = geometry_end - start;
        stats->raster_ms = end - geometry_end;
        stats->total_ms = end - start;
        collect_stats(renderer, &job, stats);
    }
    return 0;
}
