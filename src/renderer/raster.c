/*
 * raster.c: rasterisation and the depth test.
 *
 * In:  a set-up luz_triangle and a band of rows of the framebuffer.
 * Out: for every pixel centre inside the triangle whose depth is LESS than
 *      the depth buffer's, the new depth and the triangle's id in the
 *      visibility buffer. No colour yet: fragment.c shades each pixel once,
 *      after every triangle has been tested, so hidden fragments cost only
 *      a depth test (a "visibility buffer", Burns and Hunt 2013).
 *      With four samples a pixel (SCENE.md, "Anti-aliasing"), the same for
 *      each sample point: luz_raster_triangle_samples covers sample k of
 *      every pixel, (x + sx, y + sy), with the depth interpolated there,
 *      into that sample's depth and id beside the pixel's other samples
 *      (luz_sample_buffers). Same arithmetic, another offset.
 *
 * Coverage: pixel (x, y) samples its centre (x + 0.5, y + 0.5), in fixed
 * point X = 256 x + 128. Along a row an edge function is linear in x,
 *      E(x) = e + s x,   s = 256 a,
 * so instead of testing every pixel of the bounding box, each edge gives
 * the range of x where E(x) >= 0 by one exact integer division:
 *      s > 0:  x >= ceil(-e / s)        (the triangle is to the right)
 *      s < 0:  x <= floor(e / -s)       (the triangle is to the left)
 *      s = 0:  every x, or none, by the sign of e.
 * The covered span of the row is the intersection of the three ranges. The
 * arithmetic is the same exact integers as testing each pixel, so the fill
 * rule (folded into the edges by setup.c) holds to the last pixel, and
 * the result does not depend on where a band starts.
 *
 * Small triangles: a 64-bit division costs some 40 cycles, three a row,
 * more than testing a few pixels. When the bounding box is at most
 * LUZ_RASTER_SMALL_SPAN pixels wide, each pixel of the row is tested
 * instead (E >= 0 for the three edges, a multiply-add each); a triangle is
 * convex, so the pixels that pass are one span, the same span the
 * divisions give.
 *
 * Long spans: in luz_raster_triangle_spans, a span of more than LONG_SPAN
 * pixels (a cube's face in the lab) has its depth tests made by the
 * instruction set's luz_centre_span_function (sample_loops.c: 16 at a
 * time with AVX-512, masked stores), each pixel by luz_raster_depth's
 * operations, so the same bits. Shorter ones stay a plain loop, which
 * costs less than the call.
 *
 * The per-pixel arithmetic (a row's span, either way, and the depth at a
 * pixel centre) is in pipeline.h, luz_raster_row_span and
 * luz_raster_depth, shared with the pixel probe (probe.c) so that its
 * account of a pixel's depth tests is this file's arithmetic. Inlined, it
 * compiles to the same loop.
 */
#include <string.h>

#include "renderer/pipeline.h"

/* Spans longer than this go to the table's test (see the top of the file). */
enum { LONG_SPAN = 16 };

/* The rasteriser itself. overdraw, when not NULL, counts the depth tests of
 * every pixel (the overdraw view); test_span, when not NULL, tests the long
 * spans. The three public functions below call it with NULL or a buffer
 * and NULL or the table's test; inlined into each (always_inline, GCC and
 * clang), the plain one is compiled without either at all. */
static inline __attribute__((always_inline)) uint64_t raster_triangle(const luz_triangle *triangle, uint32_t triangle_id,
                                       luz_framebuffer *framebuffer, int first_row,
                                       int end_row, uint32_t *overdraw,
                                       luz_centre_span_function *test_span)
{
    int y_begin = triangle->min_y > first_row ? triangle->min_y : first_row;
    int y_end = triangle->max_y + 1 < end_row ? triangle->max_y + 1 : end_row;
    const luz_plane depth = triangle->depth;
    const int width = framebuffer->width;
    const bool small = luz_raster_is_small(triangle);
    uint64_t tests = 0;

    for (int y = y_begin; y < y_end; y++) {
        int64_t first, last;
        luz_raster_row_span(triangle, y, small, &first, &last);
        if (first > last) continue;

        /* Depth is affine in window coordinates (luz_raster_depth). */
        const float row_depth = luz_raster_row_depth(depth, triangle->reference_y, y);
        float *depth_row = framebuffer->depth + (size_t)y * width;
        uint32_t *visibility_row = framebuffer->visibility + (size_t)y * width;
        if (test_span != NULL && last - first >= LONG_SPAN) {
            test_span(depth, triangle->reference_x, row_depth, (int)first, (int)last, depth_row,
                      visibility_row, triangle_id);
        } else {
            for (int x = (int)first; x <= (int)last; x++) {
                float z = luz_raster_depth(depth, triangle->reference_x, row_depth, x);
                if (z < depth_row[x]) {    /* GL_LESS */
                    depth_row[x] = z;
                    visibility_row[x] = triangle_id;
                }
            }
        }
        tests += (uint64_t)(last - first + 1);
        if (overdraw != NULL) {
            uint32_t *count_row = overdraw + (size_t)y * width;
            for (int x = (int)first; x <= (int)last; x++) count_row[x]++;
        }
    }
    return tests;
}

uint64_t luz_raster_triangle(const luz_triangle *triangle, uint32_t triangle_id,
                             luz_framebuffer *framebuffer, int first_row, int end_row)
{
    return raster_triangle(triangle, triangle_id, framebuffer, first_row, end_row, NULL, NULL);
}

uint64_t luz_raster_triangle_spans(const luz_triangle *triangle, uint32_t triangle_id,
                                   luz_framebuffer *framebuffer, int first_row, int end_row,
                                   luz_centre_span_function *test_span)
{
    return raster_triangle(triangle, triangle_id, framebuffer, first_row, end_row, NULL,
                           test_span);
}

uint64_t luz_raster_triangle_counting(const luz_triangle *triangle, uint32_t triangle_id,
                                      luz_framebuffer *framebuffer, int first_row,
                                      int end_row, uint32_t *overdraw)
{
    return raster_triangle(triangle, triangle_id, framebuffer, first_row, end_row, overdraw,
                           NULL);
}

/* ---- four samples a pixel ------------------------------------------------
 *
 * A pixel's four samples lie side by side (luz_sample_buffers), so sixteen
 * lanes hold four neighbouring pixels of a row, lane l being sample l % 4
 * of pixel x0 + l / 4: one AVX-512 register of depths (two AVX2, four
 * SSE2 ones), one 64-byte line. Each group of four pixels is tested at
 * once: coverage, the depth at each lane's sample, LESS, and the depths
 * and ids that pass written back with the others unchanged.
 *
 * Coverage, two ways, each the exact integers of the one-sample raster:
 *  - A small triangle (a box at most LUZ_RASTER_SMALL_SPAN pixels wide:
 *    nearly every triangle of a big mesh) whose edge functions stay below
 *    2^30 in magnitude over its box (widened by the three pixels a group
 *    may reach to the left, and the samples' reach): E at lane l is
 *        E(256 x0, 256 y) + a (256 (l / 4) + sx) + b sy,
 *    the first term per group and row, the second a constant vector per
 *    triangle and edge. E is linear, so its largest magnitude over the
 *    box is at a corner: when the corners are below 2^30, every lane's E,
 *    and every difference of two (each product above is one), fits an
 *    int32, and the lanes compute exactly what int64 would.
 *  - Any other triangle: each sample's span of the row by
 *    luz_raster_row_span_at (exact divisions, as for one sample), and a
 *    lane is covered where its pixel lies within its sample's span.
 * The depth at a sample is luz_raster_sample_depth's float operations in
 * the same order (no fused multiply-add: -ffp-contract=off), so every lane
 * gives the scalar bits. The samples are independent (each its own depth
 * test), so the order in which they are visited changes no bit.
 *
 * A group never reaches past its row: near the right edge it is moved
 * left to end at the row's last pixel, and the lanes before the group's
 * first pixel are masked out (they were tested by the group before).
 * The lanes are raster_lanes.c's, compiled once per instruction set
 * (cpu.c's table gives one). With fewer than four pixels a row, with the
 * overdraw view's counts, or without lanes (the scalar set), the samples
 * are tested one at a time instead (raster_samples_one_by_one;
 * luz_raster_in_lanes says which). */

/* Every sample of the box's pixels in rows [y_begin, y_end), one at a
 * time: the definition that the lanes compute, and the overdraw
 * view's counting (overdraw[k * pixels + i] for sample k of pixel i). */
static uint64_t raster_samples_one_by_one(const luz_triangle *triangle, uint32_t triangle_id,
                                          luz_sample_buffers *buffers, int y_begin, int y_end,
                                          uint32_t *overdraw)
{
    const int samples = buffers->samples;
    const size_t pixels = (size_t)buffers->width * (size_t)buffers->height;
    uint64_t tests = 0;
    for (int y = y_begin; y < y_end; y++) {
        for (int x = triangle->min_x; x <= triangle->max_x; x++) {
            const size_t pixel = (size_t)y * (size_t)buffers->width + (size_t)x;
            for (int s = 0; s < samples; s++) {
                const luz_sample_offset sample = luz_sample_offset_of(samples, s);
                const int64_t sample_x = (int64_t)x * LUZ_SUBPIXEL_ONE + sample.x;
                const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + sample.y;
                if (!luz_edges_cover(triangle->edges, sample_x, sample_y)) continue;
                const float z = luz_raster_sample_depth(
                    triangle->depth, triangle->reference_x,
                    luz_raster_sample_row_depth(triangle->depth, triangle->reference_y, y,
                                                (float)sample.y / LUZ_SUBPIXEL_ONE),
                    x, (float)sample.x / LUZ_SUBPIXEL_ONE);
                const size_t at = pixel * LUZ_MAX_SAMPLES + (size_t)s;
                if (z < buffers->depth[at]) {    /* GL_LESS, per sample */
                    buffers->depth[at] = z;
                    buffers->visibility[at] = triangle_id;
                }
                tests++;
                if (overdraw != NULL) overdraw[(size_t)s * pixels + pixel]++;
            }
        }
    }
    return tests;
}

uint64_t luz_raster_triangle_samples(const luz_triangle *triangle, uint32_t triangle_id,
                                     luz_sample_buffers *buffers, int first_row, int end_row,
                                     uint32_t *overdraw, luz_raster_groups_function *groups)
{
    int y_begin = triangle->min_y > first_row ? triangle->min_y : first_row;
    int y_end = triangle->max_y + 1 < end_row ? triangle->max_y + 1 : end_row;
    if (y_begin >= y_end) return 0;
    if (!luz_raster_in_lanes(buffers, overdraw))
        return raster_samples_one_by_one(triangle, triangle_id, buffers, y_begin, y_end,
                                         overdraw);
    if (groups == NULL)
        return raster_samples_one_by_one(triangle, triangle_id, buffers, y_begin, y_end, NULL);
    return groups(triangle, triangle_id, buffers, y_begin, y_end, luz_raster_is_small(triangle));
}

/* luz/bug.h's no-depth-test: the samples at offset `sample` of rows
 * [first_row, end_row) inside the triangle all pass, as with GL_DEPTH_TEST
 * off: the visibility buffer takes the triangle's id and the depth buffer
 * is left as it is (OpenGL writes no depth with the test off). */
uint64_t luz_raster_triangle_always(const luz_triangle *triangle, uint32_t triangle_id,
                                    uint32_t *visibility, int width, int stride,
                                    luz_sample_offset sample, int first_row, int end_row,
                                    uint32_t *overdraw)
{
    int y_begin = triangle->min_y > first_row ? triangle->min_y : first_row;
    int y_end = triangle->max_y + 1 < end_row ? triangle->max_y + 1 : end_row;
    const bool small = luz_raster_is_small(triangle);
    uint64_t tests = 0;
    for (int y = y_begin; y < y_end; y++) {
        int64_t first, last;
        luz_raster_row_span_at(triangle, y, small, sample, &first, &last);
        for (int64_t x = first; x <= last; x++) {
            const size_t pixel = (size_t)y * (size_t)width + (size_t)x;
            visibility[pixel * (size_t)stride] = triangle_id;
            if (overdraw != NULL) overdraw[pixel]++;
        }
        if (first <= last) tests += (uint64_t)(last - first + 1);
    }
    return tests;
}
