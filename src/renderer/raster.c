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

/* The samples of a pixel are independent (each its own plane, its own
 * depth test), so the order in which a triangle's are visited changes no
 * bit. A small triangle (a box at most LUZ_RASTER_SMALL_SPAN pixels wide:
 * a million-triangle mesh's, where nearly every pixel is an edge pixel)
 * is walked pixel by pixel, each pixel's samples tested together: E at
 * sample s of pixel (x, y) is a (256 x + sx) + b (256 y + sy) + c =
 * (a sx + b sy + c) + 256 (a x + b y), the first term worked out once per
 * triangle and the second stepped by 256 a a pixel, the same exact
 * integers as the span's (luz_raster_row_span_at), so the same samples
 * are covered. A larger triangle goes row by row, and in each row sample
 * by sample, each span found as for one sample and tested by test_span
 * (the instruction set's copy of sample_loops.c's: with four samples a
 * pixel the spans are four times the pixels, and each test is independent
 * of its neighbours, so AVX-512 does sixteen with masked stores). */
uint64_t luz_raster_triangle_samples(const luz_triangle *triangle, uint32_t triangle_id,
                                     luz_sample_buffers *buffers, int first_row, int end_row,
                                     uint32_t *overdraw, luz_span_test_function *test_span)
{
    int y_begin = triangle->min_y > first_row ? triangle->min_y : first_row;
    int y_end = triangle->max_y + 1 < end_row ? triangle->max_y + 1 : end_row;
    const luz_plane depth = triangle->depth;
    const int samples = buffers->samples;
    const int width = buffers->width;
    const size_t pixels = (size_t)width * (size_t)buffers->height;
    uint64_t tests = 0;

    /* Each sample's offset in pixels, exact in a float (k / 256). */
    float offset_x[LUZ_MAX_SAMPLES], offset_y[LUZ_MAX_SAMPLES];
    for (int s = 0; s < samples; s++) {
        const luz_sample_offset sample = luz_sample_offset_of(samples, s);
        offset_x[s] = (float)sample.x / LUZ_SUBPIXEL_ONE;
        offset_y[s] = (float)sample.y / LUZ_SUBPIXEL_ONE;
    }

    if (!luz_raster_is_small(triangle)) {
        for (int y = y_begin; y < y_end; y++) {
            for (int s = 0; s < samples; s++) {
                int64_t first, last;
                luz_raster_row_span_at(triangle, y, false, luz_sample_offset_of(samples, s),
                                       &first, &last);
                if (first > last) continue;
                const float row_depth =
                    luz_raster_sample_row_depth(depth, triangle->reference_y, y, offset_y[s]);
                const size_t row = (size_t)y * width * LUZ_MAX_SAMPLES + (size_t)s;
                test_span(depth, triangle->reference_x, row_depth, offset_x[s], (int)first,
                          (int)last, buffers->depth + row, buffers->visibility + row,
                          triangle_id);
                tests += (uint64_t)(last - first + 1);
                if (overdraw != NULL) {
                    uint32_t *count_row = overdraw + (size_t)s * pixels + (size_t)y * width;
                    for (int64_t x = first; x <= last; x++) count_row[x]++;
                }
            }
        }
        return tests;
    }

    /* a sx + b sy + c of each sample and edge, and 256 a, 256 b. */
    int64_t at_sample[LUZ_MAX_SAMPLES][3], step_x[3], step_y[3];
    for (int k = 0; k < 3; k++) {
        const luz_edge *edge = &triangle->edges[k];
        step_x[k] = (int64_t)edge->a * LUZ_SUBPIXEL_ONE;
        step_y[k] = (int64_t)edge->b * LUZ_SUBPIXEL_ONE;
        for (int s = 0; s < samples; s++) {
            const luz_sample_offset sample = luz_sample_offset_of(samples, s);
            at_sample[s][k] = (int64_t)edge->a * sample.x + (int64_t)edge->b * sample.y + edge->c;
        }
    }
    const int min_x = triangle->min_x, max_x = triangle->max_x;
    for (int y = y_begin; y < y_end; y++) {
        float row_depth[LUZ_MAX_SAMPLES];
        for (int s = 0; s < samples; s++)
            row_depth[s] = luz_raster_sample_row_depth(depth, triangle->reference_y, y,
                                                       offset_y[s]);
        /* 256 (a x + b y) at the box's first pixel of the row. */
        int64_t e[3];
        for (int k = 0; k < 3; k++) e[k] = step_x[k] * min_x + step_y[k] * y;
        const size_t row = (size_t)y * width;
        for (int x = min_x; x <= max_x; x++) {
            for (int s = 0; s < samples; s++) {
                if (e[0] + at_sample[s][0] < 0 || e[1] + at_sample[s][1] < 0 ||
                    e[2] + at_sample[s][2] < 0)
                    continue;
                const size_t at = (row + (size_t)x) * LUZ_MAX_SAMPLES + (size_t)s;
                const float z = luz_raster_sample_depth(depth, triangle->reference_x,
                                                        row_depth[s], x, offset_x[s]);
                if (z < buffers->depth[at]) {    /* GL_LESS, per sample */
                    buffers->depth[at] = z;
                    buffers->visibility[at] = triangle_id;
                }
                tests++;
                if (overdraw != NULL) overdraw[(size_t)s * pixels + row + (size_t)x]++;
            }
            for (int k = 0; k < 3; k++) e[k] += step_x[k];
        }
    }
    return tests;
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
