/*
 * raster.c: rasterisation and the depth test.
 *
 * In:  a set-up luz_triangle and a band of rows of the framebuffer.
 * Out: for every pixel centre inside the triangle whose depth is LESS than
 *      the depth buffer's, the new depth and the triangle's id in the
 *      visibility buffer. No colour yet: fragment.c shades each pixel once,
 *      after every triangle has been tested, so hidden fragments cost only
 *      a depth test (a "visibility buffer", Burns and Hunt 2013).
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
 * SMALL_SPAN pixels wide, each pixel of the row is tested instead (E >= 0
 * for the three edges, a multiply-add each); a triangle is convex, so the
 * pixels that pass are one span, the same span the divisions give.
 */
#include "renderer/pipeline.h"

/* Bounding boxes at most this wide test pixels rather than divide. */
#define SMALL_SPAN 8

/* Narrows [*first, *last] to the x where edge E(x) = e + s x >= 0. */
static void clip_span_to_edge(int64_t e, int64_t s, int64_t *first, int64_t *last)
{
    if (s > 0) {
        int64_t bound = luz_ceil_divide(-e, s);
        if (bound > *first) *first = bound;
    } else if (s < 0) {
        int64_t bound = luz_floor_divide(e, -s);
        if (bound < *last) *last = bound;
    } else if (e < 0) {
        *last = *first - 1;                        /* empty */
    }
}

/* The rasteriser itself. overdraw, when not NULL, counts the depth tests of
 * every pixel (the overdraw view). The two public functions below call it
 * with NULL or a buffer; inlined into each (always_inline, GCC and clang),
 * the plain one is compiled without the counting at all. */
static inline __attribute__((always_inline)) uint64_t raster_triangle(const luz_triangle *triangle, uint32_t triangle_id,
                                       luz_framebuffer *framebuffer, int first_row,
                                       int end_row, uint32_t *overdraw)
{
    int y_begin = triangle->min_y > first_row ? triangle->min_y : first_row;
    int y_end = triangle->max_y + 1 < end_row ? triangle->max_y + 1 : end_row;
    const luz_plane depth = triangle->depth;
    const int width = framebuffer->width;
    const bool small = triangle->max_x - triangle->min_x < SMALL_SPAN;
    uint64_t tests = 0;

    for (int y = y_begin; y < y_end; y++) {
        const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + LUZ_SUBPIXEL_ONE / 2;
        int64_t first = triangle->min_x, last = triangle->max_x;
        int64_t e[3], step[3];
        for (int k = 0; k < 3; k++) {
            const luz_edge *edge = &triangle->edges[k];
            /* E at the centre of pixel 0 of this row, and its step per pixel. */
            e[k] = edge->a * (LUZ_SUBPIXEL_ONE / 2) + edge->b * sample_y + edge->c;
            step[k] = edge->a * LUZ_SUBPIXEL_ONE;
        }
        if (small) {
            int64_t covered_first = last + 1, covered_last = first - 1;
            for (int64_t x = first; x <= last; x++) {
                if (e[0] + step[0] * x >= 0 && e[1] + step[1] * x >= 0 &&
                    e[2] + step[2] * x >= 0) {
                    if (covered_first > x) covered_first = x;
                    covered_last = x;
                }
            }
            first = covered_first;
            last = covered_last;
        } else {
            for (int k = 0; k < 3; k++) clip_span_to_edge(e[k], step[k], &first, &last);
        }
        if (first > last) continue;

        /* Depth is affine in window coordinates: one multiply-add a pixel
         * from the row's value, each pixel computed directly so that its
         * value never depends on where the span began. */
        const float row_depth =
            depth.value + depth.dy * ((float)y + 0.5f - triangle->reference_y);
        float *depth_row = framebuffer->depth + (size_t)y * width;
        uint32_t *visibility_row = framebuffer->visibility + (size_t)y * width;
        for (int x = (int)first; x <= (int)last; x++) {
            float z = row_depth + depth.dx * ((float)x + 0.5f - triangle->reference_x);
            if (z < depth_row[x]) {    /* GL_LESS */
                depth_row[x] = z;
                visibility_row[x] = triangle_id;
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
    return raster_triangle(triangle, triangle_id, framebuffer, first_row, end_row, NULL);
}

uint64_t luz_raster_triangle_counting(const luz_triangle *triangle, uint32_t triangle_id,
                                      luz_framebuffer *framebuffer, int first_row,
                                      int end_row, uint32_t *overdraw)
{
    return raster_triangle(triangle, triangle_id, framebuffer, first_row, end_row, overdraw);
}
