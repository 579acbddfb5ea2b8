/*
 * screen.c: screening, the cheap decisions of triangle setup taken for
 * sixteen triangles at once, before any triangle is set up alone.
 *
 * In:  a draw's index buffer, a range of its triangles, and its vertices
 *      as luz_setup_project left them (luz_window_vertex: the snapped
 *      position, or a marker for a vertex outside a clip plane or one that
 *      could not be projected).
 * Out: the triangles of the range that still need luz_setup_projected
 *      (or the clipper), in order, and the number of back faces dropped.
 *      The others are exactly those setup would drop without a record:
 *      back faces and zero areas (CULLED), and front faces whose box holds
 *      no pixel centre of the viewport or, for a box of up to 2 x 2
 *      pixels, whose box's centres all fall outside the edges (OFFSCREEN).
 *      For four samples a pixel (luz_screen_triangles_four_avx512) the
 *      same with the samples of SCENE.md's pattern for the centres: the
 *      box of luz_setup_projected_samples, and its 2 x 2 pixels' sixteen
 *      samples tested.
 *
 * Why: on a mesh of a million triangles nearly every triangle is one of
 * those (the 1M sphere: 569k back faces and 191k front faces between
 * centres, 238k left), and one at a time each decision is a branch the CPU
 * cannot predict and a call. Here each decision is a lane of a mask: no
 * branch per triangle, and the triangles that remain are listed with one
 * compress, so the loop that sets them up runs only over those.
 *
 * The arithmetic is setup.c's, in the same integers: the doubled area of
 * luz_setup_front_facing, the box of pixel centres of
 * luz_setup_projected, and make_edge's edge functions with the fill rule,
 * E = dy (X - Xi) - dx (Y - Yi) - bias, at the box's centres. setup.c's
 * proof bounds every coordinate by 2^24, so differences fit 32 bits and
 * each product, taken in 64 (a signed 32 x 32 -> 64 multiply), is exact.
 * tests/test_screen.c holds each decision to luz_setup_projected's on
 * random and hand-made triangles.
 *
 * Instruction sets: src/renderer/meson.build compiles this file once for
 * the build's target (which screens nothing: every triangle is left to
 * setup, the loop luz had before) and once with AVX-512, whose masks,
 * compress and 64-bit lanes the kernel is written for; cpu.c puts one in
 * the renderer's table of kernels.
 * AVX2, SSE2 and NEON screen with screen_lanes.c, the same decisions on
 * lanes.h's portable vectors (an earlier AVX2 variant with 32-bit gathers
 * was slower than the one-by-one loop: docs/performance.md, "Measured in
 * the code"; screen_lanes.c loads each vertex whole instead).
 */
#include <stddef.h>
#include <stdint.h>

#include "renderer/pipeline.h"

/* Gathers take signed 32-bit indices: a mesh's are below 2^28. */
_Static_assert(LUZ_MESH_MAX_VERTICES <= (1u << 30), "vertex indices fit a gather's int32");

#if defined(LUZ_SCREEN_AVX512)
#if !defined(__AVX512F__) || !defined(__AVX512DQ__)
#error "the AVX-512 variant is compiled with -mavx512f -mavx512dq ..."
#endif
#include <immintrin.h>

#include "renderer/lanes_avx512.h"

/* Lanes 0..15: element j of the result is indices[3 j + corner] of the
 * sixteen triangles' 48 indices, loaded as three vectors of 16. The first
 * permute takes what lies in the first 32 (from_two[j] = 3 j + corner),
 * the second keeps those (j) and takes the rest from the third vector
 * (16 + 3 j + corner - 32 picks its element 3 j + corner - 32). */
static const int32_t from_two[3][16] = {
    {0, 3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 0, 0, 0, 0, 0},
    {1, 4, 7, 10, 13, 16, 19, 22, 25, 28, 31, 0, 0, 0, 0, 0},
    {2, 5, 8, 11, 14, 17, 20, 23, 26, 29, 0, 0, 0, 0, 0, 0},
};
static const int32_t from_third[3][16] = {
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 17, 20, 23, 26, 29},
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 18, 21, 24, 27, 30},
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 16, 19, 22, 25, 28, 31},
};

static __m512i corner_indices(__m512i first, __m512i second, __m512i third, int corner)
{
    const __m512i two = _mm512_permutex2var_epi32(first, _mm512_loadu_si512(from_two[corner]),
                                                  second);
    return _mm512_permutex2var_epi32(two, _mm512_loadu_si512(from_third[corner]), third);
}

/* E >= 0 for the edge from (xi, yi) to (xj, yj) at each sample of the
 * pixels (x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1), whose corner
 * (x, y) is (corner_x, corner_y) = (256 x, 256 y): inside[pixel][sample]
 * for `samples` samples a pixel (luz_sample_offset_of: one, the centre,
 * or SCENE.md's four), a mask each. */
static inline __attribute__((always_inline)) void
edge_at_samples(__m512i xi, __m512i yi, __m512i xj, __m512i yj, __m512i corner_x,
                __m512i corner_y, int samples, __mmask8 inside[4][LUZ_MAX_SAMPLES])
{
    const __m512i dx = _mm512_sub_epi64(xj, xi), dy = _mm512_sub_epi64(yj, yi);
    const __m512i zero = _mm512_setzero_si512();
    /* make_edge's fill rule: a top edge (dy = 0, dx < 0) or a left edge
     * (dy > 0) keeps E = 0, the others need E >= 1. */
    const __mmask8 top_or_left = (_mm512_cmpeq_epi64_mask(dy, zero) &
                                  _mm512_cmplt_epi64_mask(dx, zero)) |
                                 _mm512_cmpgt_epi64_mask(dy, zero);
    const __m512i bias = _mm512_mask_blend_epi64(top_or_left, _mm512_set1_epi64(1), zero);
    for (int s = 0; s < samples; s++) {
        const luz_sample_offset offset = luz_sample_offset_of(samples, s);
        const __m512i sample_x = _mm512_add_epi64(corner_x, _mm512_set1_epi64(offset.x));
        const __m512i sample_y = _mm512_add_epi64(corner_y, _mm512_set1_epi64(offset.y));
        const __m512i column0 = _mm512_mul_epi32(dy, _mm512_sub_epi64(sample_x, xi));
        const __m512i column1 =
            _mm512_add_epi64(column0, _mm512_slli_epi64(dy, LUZ_SUBPIXEL_BITS));
        const __m512i row0 =
            _mm512_add_epi64(_mm512_mul_epi32(dx, _mm512_sub_epi64(sample_y, yi)), bias);
        const __m512i row1 = _mm512_add_epi64(row0, _mm512_slli_epi64(dx, LUZ_SUBPIXEL_BITS));
        inside[0][s] &= _mm512_cmpge_epi64_mask(column0, row0);
        inside[1][s] &= _mm512_cmpge_epi64_mask(column1, row0);
        inside[2][s] &= _mm512_cmpge_epi64_mask(column0, row1);
        inside[3][s] &= _mm512_cmpge_epi64_mask(column1, row1);
    }
}

/* Eight triangles, (a, b, c) vertex indices: which setup would cull, and
 * which it would find offscreen, for pixels of `samples` samples (the
 * box and the covered test are the samples': luz_setup_projected_samples). */
static inline __attribute__((always_inline)) void
screen_eight(__m256i a, __m256i b, __m256i c, const luz_fixed_vertex *fixed, int width,
             int height, int samples, __mmask8 *culled, __mmask8 *offscreen)
{
    __m512i x0, y0, x1, y1, x2, y2;
    luz_gather_fixed(a, fixed, &x0, &y0);
    luz_gather_fixed(b, fixed, &x1, &y1);
    luz_gather_fixed(c, fixed, &x2, &y2);

    /* A marker (LUZ_WINDOW_INVALID, LUZ_WINDOW_CLIPPED) is below every
     * snapped coordinate, -2^24: such a triangle is left to setup. */
    const __m512i lowest = _mm512_set1_epi64(-((int64_t)1 << 24));
    const __mmask8 eligible = _mm512_cmpge_epi64_mask(x0, lowest) &
                              _mm512_cmpge_epi64_mask(x1, lowest) &
                              _mm512_cmpge_epi64_mask(x2, lowest);

    /* Step 3: the doubled area, as luz_setup_front_facing. */
    const __mmask8 front = _mm512_cmpgt_epi64_mask(luz_doubled_area_lanes(x0, y0, x1, y1, x2, y2),
                                                   _mm512_setzero_si512());

    /* The box of the pixels whose samples (one: the centre) may be
     * inside, as setup's. */
    __m512i min_x, min_y, max_x, max_y;
    luz_sample_box_lanes(x0, y0, x1, y1, x2, y2, width, height, samples, &min_x, &min_y, &max_x,
                         &max_y);
    const __mmask8 empty = _mm512_cmpgt_epi64_mask(min_x, max_x) |
                           _mm512_cmpgt_epi64_mask(min_y, max_y);
    const __m512i one = _mm512_set1_epi64(1);
    const __mmask8 second_column = _mm512_cmpgt_epi64_mask(max_x, min_x);
    const __mmask8 second_row = _mm512_cmpgt_epi64_mask(max_y, min_y);
    const __mmask8 small =
        _mm512_cmple_epi64_mask(_mm512_sub_epi64(max_x, min_x), one) &
        _mm512_cmple_epi64_mask(_mm512_sub_epi64(max_y, min_y), one);

    /* The samples of the box's first pixel and its (up to) three
     * neighbours; a sample counts where its pixel lies in the box. */
    const __m512i corner_x = _mm512_slli_epi64(min_x, LUZ_SUBPIXEL_BITS);
    const __m512i corner_y = _mm512_slli_epi64(min_y, LUZ_SUBPIXEL_BITS);
    __mmask8 inside[4][LUZ_MAX_SAMPLES];
    for (int s = 0; s < samples; s++) {
        inside[0][s] = 0xff;
        inside[1][s] = second_column;
        inside[2][s] = second_row;
        inside[3][s] = second_column & second_row;
    }
    edge_at_samples(x1, y1, x2, y2, corner_x, corner_y, samples, inside);   /* edge 0: 1 -> 2 */
    edge_at_samples(x2, y2, x0, y0, corner_x, corner_y, samples, inside);   /* edge 1: 2 -> 0 */
    edge_at_samples(x0, y0, x1, y1, corner_x, corner_y, samples, inside);   /* edge 2: 0 -> 1 */
    __mmask8 covers = 0;
    for (int s = 0; s < samples; s++)
        covers |= inside[0][s] | inside[1][s] | inside[2][s] | inside[3][s];

    *culled = eligible & ~front;
    *offscreen = eligible & front & (empty | (small & ~covers));
}

/* How many triangles ahead the loop asks for the vertices it will gather.
 * A mesh's triangles in file order walk its vertices mostly forward, so
 * the corners of the first and last triangles of a group four groups on
 * are near the vertices that group will gather; a gather does not start
 * loading until it is the oldest miss, a prefetch does (the 1M sphere's
 * geometry phase faster with it: docs/performance.md, "Measured in the
 * code"). */
#define SCREEN_AHEAD 64

/* How many triangles ahead the loop asks for the index buffer itself,
 * read in order, 12 bytes a triangle: the hardware's prefetcher alone
 * left the loop waiting on those loads (their line the hottest of its
 * profile); 3 KB ahead the sphere's geometry was faster, and 6 KB did no
 * better (docs/performance.md, "Measured in the code"). */
#define INDEX_AHEAD 256

/* Sixteen triangles from triangle_indices, of which the lanes of valid are
 * real (masked loads: no index is read past the last triangle; the others
 * gather vertex 0, which a draw with triangles has): their survivors
 * appended at survivors + *count, the back faces counted. */
static inline __attribute__((always_inline)) void
screen_sixteen(const uint32_t *triangle_indices, uint32_t t, __mmask16 valid,
               const luz_fixed_vertex *fixed, int width, int height, int samples,
               uint32_t *survivors, size_t *count, uint32_t *culled_total)
{
    const unsigned index_count = 3u * (unsigned)__builtin_popcount(valid);   /* 0 .. 48 */
    const __mmask16 load0 = (__mmask16)(index_count >= 16 ? 0xffffu : (1u << index_count) - 1);
    const __mmask16 load1 =
        (__mmask16)(index_count >= 32 ? 0xffffu
                                      : index_count > 16 ? (1u << (index_count - 16)) - 1 : 0);
    const __mmask16 load2 =
        (__mmask16)(index_count >= 48 ? 0xffffu
                                      : index_count > 32 ? (1u << (index_count - 32)) - 1 : 0);
    const __m512i first16 = _mm512_maskz_loadu_epi32(load0, triangle_indices);
    const __m512i second16 = _mm512_maskz_loadu_epi32(load1, triangle_indices + 16);
    const __m512i third16 = _mm512_maskz_loadu_epi32(load2, triangle_indices + 32);
    const __m512i a = corner_indices(first16, second16, third16, 0);
    const __m512i b = corner_indices(first16, second16, third16, 1);
    const __m512i c = corner_indices(first16, second16, third16, 2);
    __mmask8 culled_low, offscreen_low, culled_high, offscreen_high;
    screen_eight(_mm512_castsi512_si256(a), _mm512_castsi512_si256(b), _mm512_castsi512_si256(c),
                 fixed, width, height, samples, &culled_low, &offscreen_low);
    screen_eight(_mm512_extracti64x4_epi64(a, 1), _mm512_extracti64x4_epi64(b, 1),
                 _mm512_extracti64x4_epi64(c, 1), fixed, width, height, samples, &culled_high,
                 &offscreen_high);
    const __mmask16 culled = (__mmask16)((culled_low | (unsigned)culled_high << 8) & valid);
    const __mmask16 kept =
        (__mmask16)(valid & ~(culled_low | (unsigned)culled_high << 8 | offscreen_low |
                              (unsigned)offscreen_high << 8));
    const __m512i lane = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
    const __m512i triangle = _mm512_add_epi32(_mm512_set1_epi32((int)t), lane);
    /* The compress in a register, then a plain (masked) store: AMD's Zen 4
     * runs a compress straight to memory as slow microcode. */
    const int kept_count = __builtin_popcount(kept);
    _mm512_mask_storeu_epi32(survivors + *count, (__mmask16)((1u << kept_count) - 1),
                             _mm512_maskz_compress_epi32(kept, triangle));
    *count += (size_t)kept_count;
    *culled_total += (uint32_t)__builtin_popcount(culled);
}

/* Screening for pixels of `samples` samples, 1 or 4 (a constant in each
 * of the two functions below). */
static inline __attribute__((always_inline)) size_t
screen_triangles(const uint32_t *indices, uint32_t first, uint32_t end,
                 const luz_fixed_vertex *fixed, int width, int height, int samples,
                 uint32_t *survivors, uint32_t *culled_count)
{
    size_t count = 0;
    uint32_t culled_total = 0;
    uint32_t t = first;
    for (; end - t >= 16; t += 16) {
        const uint32_t *triangle_indices = indices + 3 * (size_t)t;
        if (end - t >= 16 + SCREEN_AHEAD) {
            const uint32_t *ahead = triangle_indices + 3 * SCREEN_AHEAD;
            _mm_prefetch((const char *)&fixed[ahead[0]], _MM_HINT_T0);
            _mm_prefetch((const char *)&fixed[ahead[1]], _MM_HINT_T0);
            _mm_prefetch((const char *)&fixed[ahead[2]], _MM_HINT_T0);
            _mm_prefetch((const char *)&fixed[ahead[45]], _MM_HINT_T0);
            _mm_prefetch((const char *)&fixed[ahead[46]], _MM_HINT_T0);
            _mm_prefetch((const char *)&fixed[ahead[47]], _MM_HINT_T0);
        }
        if (end - t >= 16 + INDEX_AHEAD)
            for (int line = 0; line < 3; line++)   /* 48 indices: three lines */
                _mm_prefetch((const char *)(triangle_indices + 3 * INDEX_AHEAD + 16 * line),
                             _MM_HINT_T0);
        screen_sixteen(triangle_indices, t, 0xffff, fixed, width, height, samples, survivors,
                       &count, &culled_total);
    }
    if (t < end)   /* the last few, in masked lanes */
        screen_sixteen(indices + 3 * (size_t)t, t, (__mmask16)((1u << (end - t)) - 1), fixed,
                       width, height, samples, survivors, &count, &culled_total);
    *culled_count = culled_total;
    return count;
}

luz_screen_function luz_screen_triangles_avx512, luz_screen_triangles_four_avx512;

size_t luz_screen_triangles_avx512(const uint32_t *indices, uint32_t first, uint32_t end,
                                   const luz_fixed_vertex *fixed, int width, int height,
                                   uint32_t *survivors, uint32_t *culled_count)
{
    return screen_triangles(indices, first, end, fixed, width, height, 1, survivors,
                            culled_count);
}

/* The same for four samples a pixel (SCENE.md, "Anti-aliasing"): what
 * luz_setup_projected_samples(..., 4, ...) drops without a record. */
size_t luz_screen_triangles_four_avx512(const uint32_t *indices, uint32_t first, uint32_t end,
                                        const luz_fixed_vertex *fixed, int width, int height,
                                        uint32_t *survivors, uint32_t *culled_count)
{
    return screen_triangles(indices, first, end, fixed, width, height, 4, survivors,
                            culled_count);
}

#else /* every other build of this file */

/* Screens nothing: every triangle goes to setup, one by one (the table of
 * an instruction set without a screening variant, cpu.c). */
luz_screen_function luz_screen_every_triangle;

size_t luz_screen_every_triangle(const uint32_t *indices, uint32_t first, uint32_t end,
                                 const luz_fixed_vertex *fixed, int width, int height,
                                 uint32_t *survivors, uint32_t *culled_count)
{
    (void)indices, (void)fixed, (void)width, (void)height;
    size_t count = 0;
    for (uint32_t t = first; t < end; t++) survivors[count++] = t;
    *culled_count = 0;
    return count;
}

#endif
