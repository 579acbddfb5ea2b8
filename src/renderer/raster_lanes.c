/*
 * raster_lanes.c: four samples a pixel, the raster's depth tests in lanes
 * (raster.c's luz_raster_triangle_samples, whose comment gives the
 * arithmetic and why it is exact).
 *
 * In:  a set-up luz_triangle, rows [y_begin, y_end) of its box, sample
 *      buffers at least LUZ_RASTER_GROUP_PIXELS pixels wide, and whether
 *      its box is small (luz_raster_is_small).
 * Out: for every sample inside the triangle and nearer than the
 *      buffers' (LESS), its depth and the triangle's id; the tests made.
 *
 * Lanes of one register, the four samples of one, two or four pixels of a
 * row (SSE2 and NEON, AVX2, AVX-512), are written once in GCC / clang
 * vector extensions (`vector_size`) and compiled once per instruction set
 * (src/renderer/meson.build), each lane the scalar
 * arithmetic of raster.c's raster_samples_one_by_one; cpu.c's table picks
 * one. Per-file flags, not LUZ_CLONES: GCC lowers a vector operation for
 * the file's own target before clones are made, and under SSE2 it split
 * the integer comparisons into scalars (the AVX-512 clone then took
 * longer than the loop it replaced).
 */
#include <string.h>

#include "renderer/pipeline.h"

#if defined(LUZ_LANES_AVX512)
#define RASTER_GROUPS luz_raster_groups_avx512
#elif defined(LUZ_LANES_AVX2)
#define RASTER_GROUPS luz_raster_groups_avx2
#elif defined(LUZ_LANES_NEON)
#define RASTER_GROUPS luz_raster_groups_neon
#elif defined(LUZ_LANES_SSE2)
#define RASTER_GROUPS luz_raster_groups_sse2
#else
#error "define LUZ_LANES_AVX512, LUZ_LANES_AVX2, LUZ_LANES_NEON or LUZ_LANES_SSE2"
#endif

/* A step is the pixels whose four samples fill one register of the set
 * (AVX-512 four, AVX2 two, SSE2 and NEON one): a vector wider than the
 * target's registers GCC 12 lowers through the stack, and AVX2's raster
 * then took seven times AVX-512's time (store-forwarding stalls on the
 * halves). The group the buffers are sized for stays
 * LUZ_RASTER_GROUP_PIXELS wide; a step is at most that. */
#if defined(LUZ_LANES_AVX512)
#define GROUP_LANES 16
#elif defined(LUZ_LANES_AVX2)
#define GROUP_LANES 8
#else
#define GROUP_LANES 4
#endif
#define GROUP_PIXELS (GROUP_LANES / LUZ_MAX_SAMPLES)
_Static_assert(GROUP_PIXELS <= LUZ_RASTER_GROUP_PIXELS, "a step fits the buffers' group");

typedef int32_t group_i32 __attribute__((vector_size(GROUP_LANES * sizeof(int32_t))));
typedef float group_f32 __attribute__((vector_size(GROUP_LANES * sizeof(float))));
typedef int64_t corner_i64 __attribute__((vector_size(4 * sizeof(int64_t))));

/* Whether |E| < 2^30 for each edge over the box of sample points that the
 * groups of rows [min_y, max_y] may test (raster.c's comment on four
 * samples: E is linear, so its largest magnitude over the box is at a
 * corner), the four corners of an edge in the lanes of one vector. The
 * check only picks between two exact ways to the same coverage, but it
 * must never say yes wrongly: the corners' E in 64 bits, as setup's
 * (pipeline.h's luz_edge), compared without a branch (raster.c compared
 * them one by one before the call, 4 ms a frame on the 1M sphere). */
static bool edges_fit_32_bits(const luz_triangle *triangle)
{
    const int64_t left = ((int64_t)triangle->min_x - (LUZ_RASTER_GROUP_PIXELS - 1)) *
                         LUZ_SUBPIXEL_ONE;
    const int64_t right = ((int64_t)triangle->max_x + LUZ_RASTER_GROUP_PIXELS) * LUZ_SUBPIXEL_ONE;
    const int64_t top = (int64_t)triangle->min_y * LUZ_SUBPIXEL_ONE;
    const int64_t bottom = ((int64_t)triangle->max_y + 1) * LUZ_SUBPIXEL_ONE;
    const corner_i64 corner_x = {left, right, left, right};
    const corner_i64 corner_y = {top, top, bottom, bottom};
    const int64_t limit = (int64_t)1 << 30;
    corner_i64 outside = {0};
    for (int k = 0; k < 3; k++) {
        const luz_edge *edge = &triangle->edges[k];
        const corner_i64 e = (int64_t)edge->a * corner_x + (int64_t)edge->b * corner_y + edge->c;
        outside |= (e >= limit) | (e <= -limit);
    }
    return (outside[0] | outside[1] | outside[2] | outside[3]) == 0;
}

luz_raster_groups_function RASTER_GROUPS;

uint64_t RASTER_GROUPS(const luz_triangle *triangle, uint32_t triangle_id,
                      luz_sample_buffers *buffers, int y_begin, int y_end, bool small)
{
    /* Coverage from the edge functions in 32-bit lanes, or from each
     * sample's span (raster.c). */
    const bool small_edges = small && edges_fit_32_bits(triangle);
    const int width = buffers->width;
    const luz_plane depth = triangle->depth;
    /* Lane l: sample l % 4 of pixel l / 4 of the group, at lane_dx,
     * lane_dy from the group's first pixel's corner in 1/256 pixel (the
     * offsets of luz_sample_offset_of, checked by test_samples), and its
     * sample's offsets in pixels (k / 256: exact in a float). */
#define GROUP_OFFSETS(pixel) \
    96 + 256 * (pixel), 224 + 256 * (pixel), 32 + 256 * (pixel), 160 + 256 * (pixel)
    static const int32_t all_dx[16] = {GROUP_OFFSETS(0), GROUP_OFFSETS(1), GROUP_OFFSETS(2),
                                       GROUP_OFFSETS(3)};
#undef GROUP_OFFSETS
#define GROUP_OFFSETS 32, 96, 160, 224
    static const int32_t all_dy[16] = {GROUP_OFFSETS, GROUP_OFFSETS, GROUP_OFFSETS, GROUP_OFFSETS};
#undef GROUP_OFFSETS
    static const int32_t all_pixel[16] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};
    /* The step's lanes are the first GROUP_LANES of the four pixels'. */
    group_i32 lane_dx, lane_dy, lane_pixel;
    memcpy(&lane_dx, all_dx, sizeof lane_dx);
    memcpy(&lane_dy, all_dy, sizeof lane_dy);
    memcpy(&lane_pixel, all_pixel, sizeof lane_pixel);
    const group_f32 lane_offset_x =
        __builtin_convertvector(lane_dx - lane_pixel * LUZ_SUBPIXEL_ONE, group_f32) /
        (float)LUZ_SUBPIXEL_ONE;
    const group_f32 lane_offset_y =
        __builtin_convertvector(lane_dy, group_f32) / (float)LUZ_SUBPIXEL_ONE;
    /* a (256 (l / 4) + sx) + b sy of each edge (exact: small_edges). */
    group_i32 edge_at_lane[3];
    for (int k = 0; k < 3; k++)
        edge_at_lane[k] = triangle->edges[k].a * lane_dx + triangle->edges[k].b * lane_dy;
    const group_f32 reference_x = (group_f32){0} + triangle->reference_x;
    const group_f32 reference_y = (group_f32){0} + triangle->reference_y;
    const group_f32 depth_dx = (group_f32){0} + depth.dx;
    const group_f32 depth_dy = (group_f32){0} + depth.dy;
    const group_f32 depth_value = (group_f32){0} + depth.value;
    const group_i32 id = (group_i32){0} + (int32_t)triangle_id;
    group_i32 counted = {0};   /* minus the tests made, per lane */

    for (int y = y_begin; y < y_end; y++) {
        /* The row's pixels to visit, and each lane's sample's span. */
        int first_x = triangle->min_x, last_x = triangle->max_x;
        group_i32 span_first = {0}, span_last = {0};
        if (!small_edges) {
            int32_t first[LUZ_MAX_SAMPLES], last[LUZ_MAX_SAMPLES];
            first_x = triangle->max_x + 1;
            last_x = triangle->min_x - 1;
            for (int s = 0; s < LUZ_MAX_SAMPLES; s++) {
                int64_t span_begin, span_end;
                luz_raster_row_span_at(triangle, y, luz_raster_is_small(triangle),
                                       luz_sample_offset_of(LUZ_MAX_SAMPLES, s), &span_begin,
                                       &span_end);
                /* Within the box (luz_raster_row_span_at narrows it), or
                 * empty: each fits an int. */
                if (span_begin > span_end) {
                    first[s] = triangle->max_x + 1;
                    last[s] = triangle->max_x;
                    continue;
                }
                first[s] = (int32_t)span_begin;
                last[s] = (int32_t)span_end;
                if (first[s] < first_x) first_x = first[s];
                if (last[s] > last_x) last_x = last[s];
            }
            for (int l = 0; l < GROUP_LANES; l++) {
                span_first[l] = first[l % LUZ_MAX_SAMPLES];
                span_last[l] = last[l % LUZ_MAX_SAMPLES];
            }
            if (first_x > last_x) continue;
        }
        /* luz_raster_sample_row_depth, lane by lane. */
        const group_f32 row_depth =
            depth_value + depth_dy * (((group_f32){0} + (float)y + lane_offset_y) - reference_y);
        float *depth_row = buffers->depth + (size_t)y * (size_t)width * LUZ_MAX_SAMPLES;
        uint32_t *visibility_row = buffers->visibility + (size_t)y * (size_t)width * LUZ_MAX_SAMPLES;
        for (int x0 = first_x; x0 <= last_x; x0 += GROUP_PIXELS) {
            /* The group's first pixel, moved left at the row's end. */
            const int at = x0 + GROUP_PIXELS <= width ? x0 : width - GROUP_PIXELS;
            const group_i32 x = (group_i32){0} + at + lane_pixel;
            group_i32 covered = (x >= (group_i32){0} + x0) & (x <= (group_i32){0} + last_x);
            if (small_edges) {
                group_i32 any_outside = {0};
                for (int k = 0; k < 3; k++) {
                    const luz_edge *edge = &triangle->edges[k];
                    const int32_t base = (int32_t)(
                        (int64_t)edge->a * ((int64_t)at * LUZ_SUBPIXEL_ONE) +
                        (int64_t)edge->b * ((int64_t)y * LUZ_SUBPIXEL_ONE) + edge->c);
                    any_outside |= base + edge_at_lane[k];
                }
                covered &= any_outside >= (group_i32){0};    /* E >= 0 for all three */
            } else {
                covered &= (x >= span_first) & (x <= span_last);
            }
            /* luz_raster_sample_depth, lane by lane. */
            group_f32 x_float = __builtin_convertvector(x, group_f32);
            const group_f32 z = row_depth + depth_dx * ((x_float + lane_offset_x) - reference_x);
            group_f32 old_depth;
            group_i32 old_id;
            memcpy(&old_depth, depth_row + (size_t)at * LUZ_MAX_SAMPLES, sizeof old_depth);
            memcpy(&old_id, visibility_row + (size_t)at * LUZ_MAX_SAMPLES, sizeof old_id);
            const group_i32 pass = covered & (z < old_depth);    /* GL_LESS, per sample */
            group_i32 z_bits, old_bits;
            memcpy(&z_bits, &z, sizeof z_bits);
            memcpy(&old_bits, &old_depth, sizeof old_bits);
            const group_i32 new_bits = (pass & z_bits) | (~pass & old_bits);
            const group_i32 new_id = (pass & id) | (~pass & old_id);
            memcpy(depth_row + (size_t)at * LUZ_MAX_SAMPLES, &new_bits, sizeof new_bits);
            memcpy(visibility_row + (size_t)at * LUZ_MAX_SAMPLES, &new_id, sizeof new_id);
            counted += covered;
        }
    }
    /* The lanes' counts added. */
    int64_t tests = 0;
    for (int l = 0; l < GROUP_LANES; l++) tests -= counted[l];
    return (uint64_t)tests;
}
