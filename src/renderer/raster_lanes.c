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
 *      Or the same for each triangle of a band's list in turn (the list
 *      kernel, luz_raster_list_function), in one call.
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
#define RASTER_LIST luz_raster_list_avx512
#elif defined(LUZ_LANES_AVX2)
#define RASTER_GROUPS luz_raster_groups_avx2
#define RASTER_LIST luz_raster_list_avx2
#elif defined(LUZ_LANES_NEON)
#define RASTER_GROUPS luz_raster_groups_neon
#define RASTER_LIST luz_raster_list_neon
#elif defined(LUZ_LANES_SSE2)
#define RASTER_GROUPS luz_raster_groups_sse2
#define RASTER_LIST luz_raster_list_sse2
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
 * them one by one before the call, 4 ms a frame on the 1M sphere).
 *
 * First a bound that needs no products, which every triangle of a big
 * mesh meets. Edge k from corner (Xi, Yi) has c = -(a Xi + b Yi), less
 * 0 or 1 (setup.c's make_edge), so at any point
 *     |E| <= |a| |X - Xi| + |b| |Y - Yi| + 1.
 * Setup's box is its corners' box (min X .. max X, min Y .. max Y) moved
 * in by the samples' reach, 32 to 224 (256 min_x >= min X - 224, 256 max_x
 * <= max X - 32; clamped to the viewport or narrowed, only smaller), so
 * the points checked below, x from min_x - 3 to max_x + 4 pixels and y
 * from min_y to max_y + 1, have |X - Xi| <= W + 992 and |Y - Yi| <= H +
 * 224, W and H the corners' box in 1/256 pixel. Its width W is the
 * largest |b| of the three edges (the leftmost and rightmost corners
 * share an edge) and H the largest |a|. With every |a|, |b| below 2^14:
 *     |E| <= 2^14 (2^14 + 992) + 2^14 (2^14 + 224) + 1 < 2^29 + 2^25,
 * below 2^30. */
static bool edges_fit_32_bits(const luz_triangle *triangle)
{
    uint32_t widest = 0;
    for (int k = 0; k < 3; k++) {
        const int32_t a = triangle->edges[k].a, b = triangle->edges[k].b;
        widest |= (uint32_t)(a < 0 ? -(int64_t)a : a) | (uint32_t)(b < 0 ? -(int64_t)b : b);
    }
    if (widest < (1u << 14)) return true;
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

/* The lanes' constants, the same for every triangle. Lane l: sample l % 4
 * of pixel l / 4 of the group, at dx, dy from the group's first pixel's
 * corner in 1/256 pixel (the offsets of luz_sample_offset_of, checked by
 * test_samples), and its sample's offsets in pixels (k / 256: exact in a
 * float). */
typedef struct lane_constants {
    group_i32 dx, dy, pixel;
    group_f32 offset_x, offset_y;
} lane_constants;

static inline __attribute__((always_inline)) lane_constants make_lane_constants(void)
{
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
    lane_constants lanes;
    memcpy(&lanes.dx, all_dx, sizeof lanes.dx);
    memcpy(&lanes.dy, all_dy, sizeof lanes.dy);
    memcpy(&lanes.pixel, all_pixel, sizeof lanes.pixel);
    lanes.offset_x =
        __builtin_convertvector(lanes.dx - lanes.pixel * LUZ_SUBPIXEL_ONE, group_f32) /
        (float)LUZ_SUBPIXEL_ONE;
    lanes.offset_y = __builtin_convertvector(lanes.dy, group_f32) / (float)LUZ_SUBPIXEL_ONE;
    return lanes;
}

typedef uint32_t group_u32 __attribute__((vector_size(GROUP_LANES * sizeof(uint32_t))));

/* One group's depth tests: the covered lanes whose z is LESS than the
 * buffers' take z and the id, the others keep theirs. */
static inline __attribute__((always_inline)) void
test_group(float *depth_at, uint32_t *visibility_at, group_i32 covered, group_f32 z, group_i32 id)
{
    group_f32 old_depth;
    group_i32 old_id;
    memcpy(&old_depth, depth_at, sizeof old_depth);
    memcpy(&old_id, visibility_at, sizeof old_id);
    const group_i32 pass = covered & (z < old_depth);    /* GL_LESS, per sample */
    group_i32 z_bits, old_bits;
    memcpy(&z_bits, &z, sizeof z_bits);
    memcpy(&old_bits, &old_depth, sizeof old_bits);
    const group_i32 new_bits = (pass & z_bits) | (~pass & old_bits);
    const group_i32 new_id = (pass & id) | (~pass & old_id);
    memcpy(depth_at, &new_bits, sizeof new_bits);
    memcpy(visibility_at, &new_id, sizeof new_id);
}

/* A triangle's rows [y_begin, y_end): its samples' depth tests, each
 * lane's count of them taken from `counted` (minus one a test), which is
 * returned. */
static inline __attribute__((always_inline)) group_i32
raster_groups_of(const lane_constants *lanes, const luz_triangle *triangle, uint32_t triangle_id,
                 luz_sample_buffers *buffers, int y_begin, int y_end, bool small,
                 group_i32 counted)
{
    /* Coverage from the edge functions in 32-bit lanes, or from each
     * sample's span (raster.c). */
    const bool small_edges = small && edges_fit_32_bits(triangle);
    const int width = buffers->width;
    const luz_plane depth = triangle->depth;
    const group_i32 lane_pixel = lanes->pixel;
    const group_f32 lane_offset_x = lanes->offset_x, lane_offset_y = lanes->offset_y;
    /* a (256 (l / 4) + sx) + b sy of each edge (exact: small_edges). */
    group_i32 edge_at_lane[3];
    for (int k = 0; k < 3; k++)
        edge_at_lane[k] = triangle->edges[k].a * lanes->dx + triangle->edges[k].b * lanes->dy;
    const group_f32 reference_x = (group_f32){0} + triangle->reference_x;
    const group_f32 reference_y = (group_f32){0} + triangle->reference_y;
    const group_f32 depth_dx = (group_f32){0} + depth.dx;
    const group_f32 depth_dy = (group_f32){0} + depth.dy;
    const group_f32 depth_value = (group_f32){0} + depth.value;
    const group_i32 id = (group_i32){0} + (int32_t)triangle_id;
    const size_t row_stride = (size_t)width * LUZ_MAX_SAMPLES;
    if (small_edges) {
        /* The box's groups column by column, each down its rows: what a
         * column keeps (its lanes' x, the box's lanes, the depth's x term,
         * luz_raster_sample_depth's depth_dx (x + sx - reference_x)) is
         * worked out once, and each edge's E moves by 256 b a row. That is
         * exact: every E the lanes take fits 32 bits (small_edges), so the
         * difference of two does too, and the steps are made in unsigned
         * lanes, modulo 2^32, which give each row's E itself. The samples
         * are independent, so the order changes no bit. */
        for (int x0 = triangle->min_x; x0 <= triangle->max_x; x0 += GROUP_PIXELS) {
            /* The group's first pixel, moved left at the row's end. */
            const int at = x0 + GROUP_PIXELS <= width ? x0 : width - GROUP_PIXELS;
            const group_i32 x = (group_i32){0} + at + lane_pixel;
            const group_i32 in_box =
                (x >= (group_i32){0} + x0) & (x <= (group_i32){0} + triangle->max_x);
            const group_f32 x_float = __builtin_convertvector(x, group_f32);
            const group_f32 depth_x = depth_dx * ((x_float + lane_offset_x) - reference_x);
            group_u32 e[3];
            uint32_t step[3];
            for (int k = 0; k < 3; k++) {
                const luz_edge *edge = &triangle->edges[k];
                const int32_t base = (int32_t)((int64_t)edge->a * ((int64_t)at * LUZ_SUBPIXEL_ONE) +
                                               (int64_t)edge->b * ((int64_t)y_begin * LUZ_SUBPIXEL_ONE) +
                                               edge->c);
                e[k] = (group_u32)(base + edge_at_lane[k]);
                step[k] = (uint32_t)((int64_t)edge->b * LUZ_SUBPIXEL_ONE);
            }
            float *depth_at = buffers->depth + (size_t)y_begin * row_stride + (size_t)at * LUZ_MAX_SAMPLES;
            uint32_t *visibility_at =
                buffers->visibility + (size_t)y_begin * row_stride + (size_t)at * LUZ_MAX_SAMPLES;
            for (int y = y_begin; y < y_end; y++) {
                /* E >= 0 for all three. */
                const group_i32 covered = in_box & ((group_i32)(e[0] | e[1] | e[2]) >= (group_i32){0});
                /* luz_raster_sample_row_depth and luz_raster_sample_depth,
                 * lane by lane. */
                const group_f32 row_depth =
                    depth_value + depth_dy * (((group_f32){0} + (float)y + lane_offset_y) - reference_y);
                test_group(depth_at, visibility_at, covered, row_depth + depth_x, id);
                counted += covered;
                for (int k = 0; k < 3; k++) e[k] += step[k];
                depth_at += row_stride;
                visibility_at += row_stride;
            }
        }
        return counted;
    }
    for (int y = y_begin; y < y_end; y++) {
        /* The row's pixels to visit, and each lane's sample's span. */
        int32_t first[LUZ_MAX_SAMPLES], last[LUZ_MAX_SAMPLES];
        int first_x = triangle->max_x + 1, last_x = triangle->min_x - 1;
        for (int s = 0; s < LUZ_MAX_SAMPLES; s++) {
            int64_t span_begin, span_end;
            luz_raster_row_span_at(triangle, y, small, luz_sample_offset_of(LUZ_MAX_SAMPLES, s),
                                   &span_begin, &span_end);
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
        if (first_x > last_x) continue;
        group_i32 span_first, span_last;
        for (int l = 0; l < GROUP_LANES; l++) {
            span_first[l] = first[l % LUZ_MAX_SAMPLES];
            span_last[l] = last[l % LUZ_MAX_SAMPLES];
        }
        /* luz_raster_sample_row_depth, lane by lane. */
        const group_f32 row_depth =
            depth_value + depth_dy * (((group_f32){0} + (float)y + lane_offset_y) - reference_y);
        float *depth_row = buffers->depth + (size_t)y * row_stride;
        uint32_t *visibility_row = buffers->visibility + (size_t)y * row_stride;
        for (int x0 = first_x; x0 <= last_x; x0 += GROUP_PIXELS) {
            /* The group's first pixel, moved left at the row's end. */
            const int at = x0 + GROUP_PIXELS <= width ? x0 : width - GROUP_PIXELS;
            const group_i32 x = (group_i32){0} + at + lane_pixel;
            const group_i32 covered = (x >= (group_i32){0} + x0) & (x <= (group_i32){0} + last_x) &
                                      (x >= span_first) & (x <= span_last);
            /* luz_raster_sample_depth, lane by lane. */
            const group_f32 x_float = __builtin_convertvector(x, group_f32);
            const group_f32 z = row_depth + depth_dx * ((x_float + lane_offset_x) - reference_x);
            test_group(depth_row + (size_t)at * LUZ_MAX_SAMPLES,
                       visibility_row + (size_t)at * LUZ_MAX_SAMPLES, covered, z, id);
            counted += covered;
        }
    }
    return counted;
}

/* The lanes' counts, negated and added. */
static inline __attribute__((always_inline)) uint64_t lanes_total(group_i32 counted)
{
    int64_t tests = 0;
    for (int l = 0; l < GROUP_LANES; l++) tests -= counted[l];
    return (uint64_t)tests;
}

luz_raster_groups_function RASTER_GROUPS;
luz_raster_list_function RASTER_LIST;

uint64_t RASTER_GROUPS(const luz_triangle *triangle, uint32_t triangle_id,
                      luz_sample_buffers *buffers, int y_begin, int y_end, bool small)
{
    const lane_constants lanes = make_lane_constants();
    return lanes_total(raster_groups_of(&lanes, triangle, triangle_id, buffers, y_begin, y_end,
                                        small, (group_i32){0}));
}

/* The list: the lanes' constants once, and their counts added across the
 * lanes every SUM_EVERY small triangles and after a large one. A lane
 * counts at most one test a group, a small box (luz_raster_is_small) at
 * most 8 groups a row and 2^14 rows (LUZ_MAX_DIMENSION): 2^12 of them stay
 * below 2^29 in an int32 lane. */
enum { SUM_EVERY = 1 << 12 };
_Static_assert(LUZ_RASTER_SMALL_SPAN <= 8 && LUZ_MAX_DIMENSION <= (1 << 14),
               "a lane's count of SUM_EVERY small triangles fits an int32");

uint64_t RASTER_LIST(const luz_triangle *const *by_id, const uint32_t *ids, size_t begin,
                     size_t end, luz_sample_buffers *buffers, int first_row, int end_row)
{
    const lane_constants lanes = make_lane_constants();
    uint64_t tests = 0;
    group_i32 counted = {0};
    unsigned small_since_sum = 0;
    for (size_t k = begin; k < end; k++) {
        luz_prefetch_triangle_ahead(by_id, ids, k, end);
        const uint32_t id = ids[k];
        const luz_triangle *triangle = by_id[id];
        /* raster.c's luz_raster_triangle_samples: the band's rows of the box. */
        const int y_begin = triangle->min_y > first_row ? triangle->min_y : first_row;
        const int y_end = triangle->max_y + 1 < end_row ? triangle->max_y + 1 : end_row;
        if (y_begin >= y_end) continue;
        const bool small = luz_raster_is_small(triangle);
        counted = raster_groups_of(&lanes, triangle, id, buffers, y_begin, y_end, small, counted);
        if (!small || ++small_since_sum == SUM_EVERY) {
            tests += lanes_total(counted);
            counted = (group_i32){0};
            small_since_sum = 0;
        }
    }
    return tests + lanes_total(counted);
}
