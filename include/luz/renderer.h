/*
 * luz/renderer.h: the object that draws a frame.
 *
 * A renderer owns its worker threads (created once, reused every frame) and
 * its scratch memory; the caller owns the renderer. Drawing a frame runs the
 * pipeline of src/pipeline/frame.c:
 *
 *   geometry  vertex stage -> clipping -> triangle setup   (per object)
 *   bands     raster + depth test -> shading -> colour     (per band of rows)
 *
 * Bands are disjoint sets of rows, and every band draws the triangles in
 * submission order, so the image is byte-identical for any thread count.
 */
#ifndef LUZ_RENDERER_H
#define LUZ_RENDERER_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/error.h"
#include "luz/framebuffer.h"
#include "luz/frame.h"

#define LUZ_THREADS_AUTO (-1)   /* one thread per online CPU */
#define LUZ_MAX_THREADS 256

typedef struct luz_renderer_desc {
    int thread_count;   /* LUZ_THREADS_AUTO, or 0 / 1 for the caller's
                           thread only, or up to LUZ_MAX_THREADS */
    bool reference;     /* true: shade one pixel at a time with the plain
                           reference fragment stage; false (the default):
                           with the SIMD one. They agree to within rounding
                           (every channel within 1, nearly every pixel
                           identical) */
} luz_renderer_desc;

typedef struct luz_frame_stats {
    double geometry_ms;        /* vertex, clip, setup (wall clock) */
    double raster_ms;          /* raster, depth, shade, colour (wall clock) */
    double total_ms;
    uint64_t triangles_submitted;
    uint64_t triangles_clipped;   /* triangles that crossed a clip plane */
    uint64_t triangles_culled;    /* back faces and zero-area triangles */
    uint64_t triangles_rasterised;
    uint64_t fragments_tested;    /* depth tests, over all bands */
    uint64_t fragments_shaded;    /* pixels shaded (once each) */
} luz_frame_stats;

typedef struct luz_renderer luz_renderer;

luz_renderer *luz_renderer_create(const luz_renderer_desc *desc, luz_error *error);
void luz_renderer_destroy(luz_renderer *renderer);
/* The number of threads that work on a frame, the caller's included. */
int luz_renderer_thread_count(const luz_renderer *renderer);

/* Draws the frame into the framebuffer (cleared first). stats may be NULL.
 * Returns 0, or -1 if memory ran out. */
int luz_renderer_draw(luz_renderer *renderer, const luz_frame *frame,
                      luz_framebuffer *framebuffer, luz_frame_stats *stats,
                      luz_error *error);

/* Work the caller puts on top of each band of the frame: the renderer
 * calls after_band(context, framebuffer, first_row, end_row) for every
 * band of rows right after its fragment stage, on the thread that drew
 * the band, while those rows are still in its cache. The viewer fills its
 * 2D layer this way (luz_layer_draw_rows). Calls for different bands run
 * at the same time, in any order, so after_band must touch nothing but
 * colour rows [first_row, end_row); together the calls cover every row
 * once. Their time counts in raster_ms. */
typedef struct luz_band_hook {
    void (*after_band)(void *context, luz_framebuffer *framebuffer, int first_row,
                       int end_row);
    void *context;
} luz_band_hook;

/* luz_renderer_draw, with hook (which may be NULL) called per band. */
int luz_renderer_draw_with_hook(luz_renderer *renderer, const luz_frame *frame,
                                luz_framebuffer *framebuffer, const luz_band_hook *hook,
                                luz_frame_stats *stats, luz_error *error);

#endif
