/*
 * screen_lanes.c: screening (screen.c's job: the cheap decisions of
 * triangle setup, many triangles at once) written once on lanes.h's
 * portable vectors, for every instruction set with lanes: 16 triangles a
 * step with AVX-512, 8 with AVX2, 4 with SSE2 and NEON.
 *
 * In, out and the arithmetic: screen.c's, decision for decision (the
 * doubled area and the edge functions at the box's centres in 64-bit
 * lanes, each 32 x 32-bit product exact; the box in 32-bit lanes, where
 * every coordinate fits), so tests/test_screen.c holds every variant to
 * luz_setup_projected alike.
 *
 * AVX-512 once had a kernel of its own in intrinsics (screen.c), in 64-bit
 * lanes throughout: this kernel then took 6% more CPU time on the 1M
 * sphere (32.4 against 30.4 ms a frame); since it takes a step's edge
 * functions in 32-bit lanes where every product fits (small_near_box) it
 * takes less (28.26 against 28.77, docs/performance.md, "The 1M sphere
 * and its setup"), and the intrinsics went.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "renderer/pipeline.h"

/* Vertex indices are below 2^28: they fit a signed 32-bit lane. */
_Static_assert(LUZ_MESH_MAX_VERTICES <= (1u << 30), "vertex indices fit an int32 lane");

#if defined(LUZ_LANES_AVX512)
#define LANES 16
#define SCREEN_LANES luz_screen_triangles_avx512
#define SCREEN_LANES_FOUR luz_screen_triangles_four_avx512
#elif defined(LUZ_LANES_AVX2)
#define LANES 8
#define SCREEN_LANES luz_screen_triangles_avx2
#define SCREEN_LANES_FOUR luz_screen_triangles_four_avx2
#elif defined(LUZ_LANES_NEON)
#define LANES 4
#define SCREEN_LANES luz_screen_triangles_neon
#define SCREEN_LANES_FOUR luz_screen_triangles_four_neon
#elif defined(LUZ_LANES_SSE2)
#define LANES 4
#define SCREEN_LANES luz_screen_triangles_sse2
#define SCREEN_LANES_FOUR luz_screen_triangles_four_sse2
#else
#error "screen_lanes.c is compiled for one instruction set: -DLUZ_LANES_AVX2, ..."
#endif

#include "renderer/lanes.h"

/* Lane j of *a, *b, *c: indices 3 j, 3 j + 1, 3 j + 2 of the step's 3
 * LANES indices, loaded as three vectors (first, second, third). Each
 * takes what lies in the first two, then the rest from the third. */
LANES_INLINE void corner_indices(vi32 first, vi32 second, vi32 third, vi32 *a, vi32 *b, vi32 *c)
{
#if LANES == 16
    *a = __builtin_shufflevector(
        __builtin_shufflevector(first, second, 0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0,
                                0, 0),
        third, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29);
    *b = __builtin_shufflevector(
        __builtin_shufflevector(first, second, 1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0,
                                0, 0),
        third, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30);
    *c = __builtin_shufflevector(
        __builtin_shufflevector(first, second, 2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0,
                                0, 0),
        third, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31);
#elif LANES == 8
    *a = __builtin_shufflevector(__builtin_shufflevector(first, second, 0, 3, 6, 9, 12, 15, 0, 0),
                                 third, 0, 1, 2, 3, 4, 5, 10, 13);
    *b = __builtin_shufflevector(__builtin_shufflevector(first, second, 1, 4, 7, 10, 13, 0, 0, 0),
                                 third, 0, 1, 2, 3, 4, 8, 11, 14);
    *c = __builtin_shufflevector(__builtin_shufflevector(first, second, 2, 5, 8, 11, 14, 0, 0, 0),
                                 third, 0, 1, 2, 3, 4, 9, 12, 15);
#elif LANES == 4
    *a = __builtin_shufflevector(__builtin_shufflevector(first, second, 0, 3, 6, 0), third, 0, 1,
                                 2, 5);
    *b = __builtin_shufflevector(__builtin_shufflevector(first, second, 1, 4, 7, 0), third, 0, 1,
                                 2, 6);
    *c = __builtin_shufflevector(__builtin_shufflevector(first, second, 2, 5, 0, 0), third, 0, 1,
                                 4, 7);
#else
#error "corner_indices: 4, 8 or 16 lanes"
#endif
}

/* make_edge's fill rule for the edge from (xi, yi) to (xj, yj), in 32-bit
 * lanes (differences below 2^25): a top edge (dy = 0, dx < 0) or a left
 * edge (dy > 0) keeps E = 0, the others need E >= 1; the bias, 0 or 1. */
LANES_INLINE vi32 fill_bias(vi32 xi, vi32 yi, vi32 xj, vi32 yj)
{
    const vi32 dx = xj - xi, dy = yj - yi;
    return ~(((dy == 0) & (dx < 0)) | (dy > 0)) & 1;
}

/* E >= 0 at the centres (X, Y), (X + 256, Y), (X, Y + 256), (X + 256,
 * Y + 256) for the edge from (xi, yi) to (xj, yj), in 64-bit lanes (half
 * a step); four lane bits. dy (X - Xi) >= dx (Y - Yi) + bias is taken as
 * the sign of the difference (each side below 2^51, so it cannot
 * overflow): a sign bit is read without a 64-bit comparison, which SSE2
 * lacks. */
LANES_INLINE void edge_at_centres(vi64 xi, vi64 yi, vi64 xj, vi64 yj, vi64 bias, vi64 sample_x,
                                  vi64 sample_y, unsigned inside[4])
{
    const vi64 dx = xj - xi, dy = yj - yi;
    const vi64 column0 = multiply_wide(dy, sample_x - xi);
    const vi64 column1 = column0 + (dy << LUZ_SUBPIXEL_BITS);
    const vi64 row0 = multiply_wide(dx, sample_y - yi) + bias;
    const vi64 row1 = row0 + (dx << LUZ_SUBPIXEL_BITS);
    inside[0] &= ~negative_bits64(column0 - row0);
    inside[1] &= ~negative_bits64(column1 - row0);
    inside[2] &= ~negative_bits64(column0 - row1);
    inside[3] &= ~negative_bits64(column1 - row1);
}

/* Whether every lane's triangle is small and near its box's corner
 * (corner_x, corner_y): its corners' extent on either axis, highest -
 * lowest, and the corner's distances to the least and the greatest of
 * them, below 2^14 sub-pixel units (64 pixels; nearly every triangle of
 * a big mesh). Then each edge's dx and dy and each vertex's distance to
 * the corner are below 2^14 (x - corner lies between lowest - corner and
 * highest - corner), and the doubled area and the edge functions at the
 * box's four pixels' samples (each less than 512 units from the corner)
 * fit 32-bit lanes: each product below 2^14 (2^14 + 512) < 2^29, each
 * side of a comparison below 2^29 + 2^23 + 1. (Six differences and
 * comparisons, where the twelve differences from the vertices, made
 * magnitudes and or-ed, took 47 instructions a step.) */
LANES_INLINE bool small_near_box(vi32 lowest_x, vi32 lowest_y, vi32 highest_x, vi32 highest_y,
                                 vi32 corner_x, vi32 corner_y)
{
    const vi32 limit = splat32(1 << 14);
    return lane_bits((highest_x - lowest_x < limit) & (highest_x - corner_x < limit) &
                     (corner_x - lowest_x < limit) & (highest_y - lowest_y < limit) &
                     (highest_y - corner_y < limit) & (corner_y - lowest_y < limit)) ==
           (1u << LANES) - 1;
}

/* edge_at_centres in 32-bit lanes, for a step that small_near_box allows:
 * four masks. */
LANES_INLINE void edge_at_centres32(vi32 xi, vi32 yi, vi32 xj, vi32 yj, vi32 bias, vi32 sample_x,
                                    vi32 sample_y, vi32 inside[4])
{
    const vi32 dx = xj - xi, dy = yj - yi;
    const vi32 column0 = dy * (sample_x - xi);
    const vi32 column1 = column0 + (dy << LUZ_SUBPIXEL_BITS);
    const vi32 row0 = dx * (sample_y - yi) + bias;
    const vi32 row1 = row0 + (dx << LUZ_SUBPIXEL_BITS);
    inside[0] &= column0 >= row0;
    inside[1] &= column1 >= row0;
    inside[2] &= column0 >= row1;
    inside[3] &= column1 >= row1;
}

/* How many triangles ahead the loop asks for the vertices it will gather.
 * A mesh's triangles in file order walk its vertices mostly forward, so
 * the corners of the first and last triangles of a step four AVX-512
 * steps on are near the vertices that step will gather; a gather does not
 * start loading until it is the oldest miss, a prefetch does (the 1M
 * sphere's geometry phase: 3-4% faster with it). */
#define SCREEN_AHEAD 64

/* How many triangles ahead the loop asks for the index buffer itself,
 * read in order, 12 bytes a triangle: the hardware's prefetcher alone
 * left the loop waiting on those loads (their line the hottest of its
 * profile); 3 KB ahead, the sphere's geometry 10.8 -> 10.4 ms a frame
 * (6 KB did no better). */
#define INDEX_AHEAD 256

/* LANES triangles from triangle_indices, of which the first `valid` are
 * real (the others read vertex 0, which a draw with triangles has): which
 * setup would cull, and which it would find offscreen. Their survivors
 * are appended at survivors + *count, the back faces counted. */
LANES_INLINE void screen_step(const uint32_t *triangle_indices, uint32_t t, int valid,
                              const luz_fixed_vertex *fixed, int width, int height, int samples,
                              uint32_t *survivors, size_t *count, uint32_t *culled_total)
{
    vi32 loaded[3];
    if (valid == LANES) {
        memcpy(loaded, triangle_indices, sizeof loaded);
    } else {   /* the last few: no index is read past the last triangle */
        memset(loaded, 0, sizeof loaded);
        memcpy(loaded, triangle_indices, 3 * (size_t)valid * sizeof *triangle_indices);
    }
    vi32 a, b, c;
    corner_indices(loaded[0], loaded[1], loaded[2], &a, &b, &c);
    vi32 x0, y0, x1, y1, x2, y2;
    gather_fixed(a, fixed, &x0, &y0);
    gather_fixed(b, fixed, &x1, &y1);
    gather_fixed(c, fixed, &x2, &y2);

    /* A marker (LUZ_WINDOW_INVALID, LUZ_WINDOW_CLIPPED) is below every
     * snapped coordinate, -2^24: such a triangle is left to setup. Its
     * lanes compute on 0 instead, so that no difference below overflows. */
    const vi32 lowest = splat32(-(1 << 24));
    const vi32 eligible = (x0 >= lowest) & (x1 >= lowest) & (x2 >= lowest);
    x0 &= eligible, x1 &= eligible, x2 &= eligible;

    /* The box of pixel centres, as setup's: the x whose centre 256 x +
     * 128 lies within [min X, max X], from ceil((min X - 128) / 256) =
     * -((128 - min X) >> 8) to floor((max X - 128) / 256) = (max X - 128)
     * >> 8 (arithmetic shifts: floors), clamped to the viewport; likewise
     * y. Empty where min > max. With four samples a pixel, 128 is the
     * farthest a sample lies from the pixel's corner (224) on the left
     * and the nearest (32) on the right: the box of
     * luz_setup_projected_samples. */
    const vi32 low = splat32(luz_sample_reach_low(samples));
    const vi32 high = splat32(luz_sample_reach_high(samples)), zero = splat32(0);
    const vi32 lowest_x = min32(x0, min32(x1, x2)), lowest_y = min32(y0, min32(y1, y2));
    const vi32 highest_x = max32(x0, max32(x1, x2)), highest_y = max32(y0, max32(y1, y2));
    const vi32 min_x = max32(-((high - lowest_x) >> LUZ_SUBPIXEL_BITS), zero);
    const vi32 min_y = max32(-((high - lowest_y) >> LUZ_SUBPIXEL_BITS), zero);
    const vi32 max_x = min32((highest_x - low) >> LUZ_SUBPIXEL_BITS, splat32(width - 1));
    const vi32 max_y = min32((highest_y - low) >> LUZ_SUBPIXEL_BITS, splat32(height - 1));
    const vi32 empty = (min_x > max_x) | (min_y > max_y);
    const vi32 second_column = max_x > min_x, second_row = max_y > min_y;
    const vi32 small = (max_x - min_x <= 1) & (max_y - min_y <= 1);

    /* The box's first centre, X = 256 x + 128 (or each of its samples),
     * and its (up to) three neighbours'; one counts where its pixel lies
     * in the box. */
    const vi32 corner_x = min_x << LUZ_SUBPIXEL_BITS, corner_y = min_y << LUZ_SUBPIXEL_BITS;

    const vi32 bias[3] = {fill_bias(x1, y1, x2, y2), fill_bias(x2, y2, x0, y0),
                          fill_bias(x0, y0, x1, y1)};
    unsigned front = 0, covers = 0;
    if (small_near_box(lowest_x, lowest_y, highest_x, highest_y, corner_x, corner_y)) {
        /* In 32-bit lanes, the whole step at once: every product below
         * 2^29 (small_near_box), so each is exact and the decisions are
         * those of the 64-bit lanes below. */
        front = lane_bits((y1 - y0) * (x2 - x0) - (x1 - x0) * (y2 - y0) > 0);
        for (int s = 0; s < samples; s++) {
            const luz_sample_offset offset = luz_sample_offset_of(samples, s);
            const vi32 sample_x = corner_x + offset.x, sample_y = corner_y + offset.y;
            vi32 inside[4] = {splat32(-1), second_column, second_row,
                              second_column & second_row};
            edge_at_centres32(x1, y1, x2, y2, bias[0], sample_x, sample_y, inside);   /* edge 0 */
            edge_at_centres32(x2, y2, x0, y0, bias[1], sample_x, sample_y, inside);   /* edge 1 */
            edge_at_centres32(x0, y0, x1, y1, bias[2], sample_x, sample_y, inside);   /* edge 2 */
            covers |= lane_bits(inside[0] | inside[1] | inside[2] | inside[3]);
        }
    } else {
        /* In 64-bit lanes, half a step at a time: step 3, the doubled
         * area, as luz_setup_front_facing (differences below 2^25: each
         * product exact in 64 bits; area > 0 where -area is negative), and
         * the edges at the box's centres. */
        const unsigned second_column_bits = lane_bits(second_column);
        const unsigned second_row_bits = lane_bits(second_row);
        for (int h = 0; h < 2; h++) {
            const vi64 wx0 = widen_half(x0, h), wy0 = widen_half(y0, h);
            const vi64 wx1 = widen_half(x1, h), wy1 = widen_half(y1, h);
            const vi64 wx2 = widen_half(x2, h), wy2 = widen_half(y2, h);
            const vi64 area =
                multiply_wide(wy1 - wy0, wx2 - wx0) - multiply_wide(wx1 - wx0, wy2 - wy0);
            front |= negative_bits64(-area) << (h * HALF);
            const unsigned column_bits = second_column_bits >> (h * HALF);
            const unsigned row_bits = second_row_bits >> (h * HALF);
            for (int s = 0; s < samples; s++) {
                const luz_sample_offset offset = luz_sample_offset_of(samples, s);
                const vi64 wsample_x = widen_half(corner_x + offset.x, h);
                const vi64 wsample_y = widen_half(corner_y + offset.y, h);
                unsigned inside[4] = {~0u, column_bits, row_bits, column_bits & row_bits};
                edge_at_centres(wx1, wy1, wx2, wy2, widen_half(bias[0], h), wsample_x,
                                wsample_y, inside);   /* edge 0: 1 -> 2 */
                edge_at_centres(wx2, wy2, wx0, wy0, widen_half(bias[1], h), wsample_x,
                                wsample_y, inside);   /* edge 1: 2 -> 0 */
                edge_at_centres(wx0, wy0, wx1, wy1, widen_half(bias[2], h), wsample_x,
                                wsample_y, inside);   /* edge 2: 0 -> 1 */
                covers |= ((inside[0] | inside[1] | inside[2] | inside[3]) &
                           ((1u << HALF) - 1))
                          << (h * HALF);
            }
        }
    }

    const unsigned valid_lanes = (unsigned)((1ull << valid) - 1);
    const unsigned eligible_bits = lane_bits(eligible) & valid_lanes;
    const unsigned culled = eligible_bits & ~front;
    const unsigned offscreen =
        eligible_bits & front & (lane_bits(empty) | (lane_bits(small) & ~covers));
    append_lanes(survivors, count, t, valid_lanes & ~culled & ~offscreen, valid);
    *culled_total += (uint32_t)__builtin_popcount(culled);
}

/* Screening for pixels of `samples` samples, 1 or 4 (a constant in each
 * of the two functions below). */
LANES_INLINE size_t screen_triangles(const uint32_t *indices, uint32_t first, uint32_t end,
                                     const luz_fixed_vertex *fixed, int width, int height,
                                     int samples, uint32_t *survivors, uint32_t *culled_count)
{
    size_t count = 0;
    uint32_t culled_total = 0;
    uint32_t t = first;
    for (; end - t >= LANES; t += LANES) {
        const uint32_t *triangle_indices = indices + 3 * (size_t)t;
        if (end - t >= LANES + SCREEN_AHEAD) {
            const uint32_t *ahead = triangle_indices + 3 * SCREEN_AHEAD;
            __builtin_prefetch(&fixed[ahead[0]]);
            __builtin_prefetch(&fixed[ahead[1]]);
            __builtin_prefetch(&fixed[ahead[2]]);
            __builtin_prefetch(&fixed[ahead[3 * LANES - 3]]);
            __builtin_prefetch(&fixed[ahead[3 * LANES - 2]]);
            __builtin_prefetch(&fixed[ahead[3 * LANES - 1]]);
        }
        if (end - t >= LANES + INDEX_AHEAD)
            for (int line = 0; line < 3 * LANES; line += 16)   /* 64 bytes a line */
                __builtin_prefetch(triangle_indices + 3 * INDEX_AHEAD + line);
        screen_step(triangle_indices, t, LANES, fixed, width, height, samples, survivors,
                    &count, &culled_total);
    }
    if (t < end)   /* the last few */
        screen_step(indices + 3 * (size_t)t, t, (int)(end - t), fixed, width, height, samples,
                    survivors, &count, &culled_total);
    *culled_count = culled_total;
    return count;
}

luz_screen_function SCREEN_LANES, SCREEN_LANES_FOUR;

size_t SCREEN_LANES(const uint32_t *indices, uint32_t first, uint32_t end,
                    const luz_fixed_vertex *fixed, int width, int height, uint32_t *survivors,
                    uint32_t *culled_count)
{
    return screen_triangles(indices, first, end, fixed, width, height, 1, survivors,
                            culled_count);
}

/* The same for four samples a pixel (SCENE.md, "Anti-aliasing"): what
 * luz_setup_projected_samples(..., 4, ...) drops without a record. */
size_t SCREEN_LANES_FOUR(const uint32_t *indices, uint32_t first, uint32_t end,
                         const luz_fixed_vertex *fixed, int width, int height,
                         uint32_t *survivors, uint32_t *culled_count)
{
    return screen_triangles(indices, first, end, fixed, width, height, 4, survivors,
                            culled_count);
}
