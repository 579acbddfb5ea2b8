/*
 * luz/renderer.h: the object that draws a frame.
 *
 * A renderer owns its worker threads (created once, reused every frame) and
 * its scratch memory; the caller owns the renderer. Drawing a frame runs the
 * pipeline of src/renderer/frame.c:
 *
 *   geometry  vertex stage -> clipping -> triangle setup   (per draw)
 *   bands     raster + depth test -> shading -> colour     (per band of rows)
 *
 * Bands are disjoint sets of rows, and every band draws the triangles in
 * submission order, so the image is byte-identical for any thread count.
 *
 * Threads: one luz_renderer_draw at a time per renderer (it is not to be
 * called from two threads at once on the same renderer); any number of
 * renderers may draw at once, from any threads, and may share meshes and
 * textures, which drawing only reads.
 */
#ifndef LUZ_RENDERER_H
#define LUZ_RENDERER_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/api.h"
#include "luz/bug.h"
#include "luz/error.h"
#include "luz/frame.h"
#include "luz/framebuffer.h"
#include "luz/view.h"

#define LUZ_THREADS_AUTO (-1)   /* one thread per online CPU, as 0 is */
#define LUZ_MAX_THREADS 256

/* A zero desc (or NULL) is the default renderer: one thread per online CPU,
 * the SIMD fragment stage. */
typedef struct luz_renderer_desc {
    int thread_count;   /* 0 or LUZ_THREADS_AUTO: one per online CPU; 1:
                           the caller's thread only; up to LUZ_MAX_THREADS */
    bool reference;     /* true: shade one pixel at a time with the plain
                           reference fragment stage; false (the default):
                           with the SIMD one, whose widest variant the CPU
                           runs is chosen once, here. They agree to within
                           rounding (every channel within 1, nearly every
                           pixel identical) */
} luz_renderer_desc;

typedef struct luz_renderer luz_renderer;

/* Returns the renderer, or NULL with the reason in error (an unknown or
 * unavailable LUZ_ISA among them: luz_renderer_isa). */
LUZ_API luz_renderer *luz_renderer_create(const luz_renderer_desc *desc, luz_error *error);
LUZ_API void luz_renderer_destroy(luz_renderer *renderer);
/* The number of threads that work on a frame, the caller's included. */
LUZ_API int luz_renderer_thread_count(const luz_renderer *renderer);
/* The instruction set the renderer's stages run in lanes: "avx512",
 * "avx2", "sse2" (x86-64), "neon" (aarch64) or "scalar" (one lane). The
 * widest this CPU runs, unless the environment variable LUZ_ISA names a
 * narrower one when the renderer is made; every set draws the same image,
 * byte for byte, only the time differs. */
LUZ_API const char *luz_renderer_isa(const luz_renderer *renderer);
/* LUZ_ISA as luz_renderer_create reads it: 0 if it is unset, empty or
 * names a set this CPU runs; else -1 with the reason (a program can
 * refuse it with its other usage errors). */
LUZ_API int luz_isa_check(luz_error *error);

/* How varyings are interpolated across a triangle on the screen. */
typedef enum luz_interpolation {
    LUZ_INTERPOLATION_PERSPECTIVE,   /* perspective-correct (the default) */
    LUZ_INTERPOLATION_AFFINE,        /* linear in screen space: textures swim */
} luz_interpolation;

LUZ_API const char *luz_interpolation_name(luz_interpolation interpolation);  /* "perspective", ... */

typedef struct luz_frame_stats {
            double geometry_ms;        /* vertex, clip, setup (wall clock) */
            double raster_ms;          /* raster, depth, shade, colour (wall clock) */
            double total_ms;
    uint64_t triangles_submitted;
    uint64_t draws_culled;        /* draws whose bounding box lay wholly outside
                                     the clip volume: their triangles (counted
                                     as submitted) were never looked at */
    uint64_t triangles_clipped;   /* triangles that crossed a clip plane */
    uint64_t triangles_culled;    /* back faces and zero-area triangles */
    uint64_t triangles_rasterised;  /* front faces that cover a pixel centre of
                                       the viewport (a small one that falls
                                       between centres is dropped at setup) */
    uint64_t fragments_tested;    /* depth tests, over all bands */
    uint64_t fragments_shaded;    /* pixels shaded (once each) */
    uint64_t memory_bytes;        /* what the renderer holds for its frames'
                                     work (triangles, vertices, bins), kept
                                     from frame to frame; not the framebuffer */
    const char *isa;              /* luz_renderer_isa: the instruction set */
} luz_frame_stats;

/* Work the caller puts on top of each band of the frame: the renderer
 * calls after_band(context, framebuffer, first_row, end_row) for every
 * band of rows right after its fragment stage, on the thread that drew
 * the band, while those rows are still in its cache. The viewer fills its
 * 2D layer this way. Calls for different bands run at the same time, in
 * any order, so after_band must touch nothing but colour rows
 * [first_row, end_row); together the calls cover every row once. Their
 * time counts in raster_ms. */
typedef struct luz_band_hook {
    void (*after_band)(void *context, luz_framebuffer *framebuffer, int first_row,
                       int end_row);
    void *context;
} luz_band_hook;

/* A pixel to explain (luz/probe.h). */
typedef struct luz_pixel_probe luz_pixel_probe;

/* How to draw a frame: the teaching switches, and what to report. A zero
 * struct (or NULL) draws the shaded image, perspective-correct, every
 * triangle, with no hook, no statistics and no probe. */
typedef struct luz_render_options {
    luz_view view;                     /* what the colour buffer shows
                                          (luz/view.h): LUZ_VIEW_COLOR, the
                                          image, or a stage of the pipeline */
    luz_interpolation interpolation;
    uint32_t triangle_limit;           /* 0: every triangle; N: only the first
                                          N that survive clipping and culling
                                          and cover a pixel centre (a small
                                          triangle that falls between centres
                                          is dropped at setup), in submission
                                          order (the viewer's step mode) */
    const luz_band_hook *hook;         /* NULL, or called after each band */
    luz_frame_stats *stats;            /* NULL, or filled in */
    luz_pixel_probe *probe;            /* NULL, or the pixel at probe->x,
                                          probe->y explained (luz/probe.h) */
    luz_bug bug;                       /* LUZ_BUG_NONE, or one classic mistake
                                          put in (luz/bug.h); the probe's
                                          numbers follow it */
    bool colour_only;                  /* true: only the framebuffer's colour
                                          is written; each band's depth and
                                          visibility are kept in a small
                                          buffer of the drawing thread's,
                                          which stays in its cache, and the
                                          framebuffer's are left as they were
                                          (the same image, faster). Ignored
                                          with a probe, which reads them
                                          after the frame */
} luz_render_options;

/* Draws the frame into the framebuffer (cleared first: every pixel is
 * written). Returns 0, or -1 with the reason in error (memory ran out, or
 * a draw the frame should not hold). */
LUZ_API int luz_renderer_draw(luz_renderer *renderer, const luz_frame *frame,
                              luz_framebuffer *framebuffer, const luz_render_options *options,
                              luz_error *error);

#endif
