/*
 * lanes_avx512.h: what the AVX-512 variants in intrinsics (setup_eight.c,
 * vertex_sixteen.c) share to turn arrays of structures, one vertex or
 * triangle each, into vectors of one field each (lanes), and back: the
 * gather of snapped positions and the 8 x 8 transposes; and what they
 * compute in lanes: a triangle's doubled area and box of pixel centres,
 * the projection of a vertex. Included only
 * where the file is compiled with -mavx512f and the rest.
 */
#ifndef LUZ_LANES_AVX512_H
#define LUZ_LANES_AVX512_H

#include <immintrin.h>

#include "renderer/pipeline.h"
#include "renderer/transpose8.h"

/* The snapped (X, Y) of eight vertices, one 64-bit load each (a gather),
 * sign-extended to 64-bit lanes. */
static inline __attribute__((always_inline)) void
luz_gather_fixed(__m256i vertex_index, const luz_fixed_vertex *fixed, __m512i *x, __m512i *y)
{
    _Static_assert(sizeof(luz_fixed_vertex) == 8, "a vertex's x and y are one 64-bit load");
    const __m512i both = _mm512_i32gather_epi64(vertex_index, (const void *)fixed, 8);
    *x = _mm512_srai_epi64(_mm512_slli_epi64(both, 32), 32);
    *y = _mm512_srai_epi64(both, 32);
}

/* luz_setup_front_facing's doubled area of eight triangles of snapped
 * corners (x0, y0), (x1, y1), (x2, y2), one per 64-bit lane: differences
 * below 2^25, so each 32 x 32 -> 64-bit product is exact. A front face's
 * is above 0. */
static inline __attribute__((always_inline)) __m512i
luz_doubled_area_lanes(__m512i x0, __m512i y0, __m512i x1, __m512i y1, __m512i x2, __m512i y2)
{
    return _mm512_sub_epi64(
        _mm512_mul_epi32(_mm512_sub_epi64(y1, y0), _mm512_sub_epi64(x2, x0)),
        _mm512_mul_epi32(_mm512_sub_epi64(x1, x0), _mm512_sub_epi64(y2, y0)));
}

/* luz_setup_projected_samples's box of the same eight triangles for
 * pixels of `samples` samples (1 or 4; a constant where it is inlined):
 * the x one of whose samples may lie within [min X, max X], from
 * ceil((min X - high) / 256) = -((high - min X) >> 8) to floor((max X -
 * low) / 256) = (max X - low) >> 8 (arithmetic shifts: floors), low and
 * high the nearest and farthest a sample lies from the pixel's corner
 * (luz_sample_reach_low, _high: 32 and 224 for four samples; 128 and
 * 128, the centre, for one), clamped to the viewport; likewise y. Empty
 * where min > max. */
static inline __attribute__((always_inline)) void
luz_sample_box_lanes(__m512i x0, __m512i y0, __m512i x1, __m512i y1, __m512i x2, __m512i y2,
                     int width, int height, int samples, __m512i *min_x, __m512i *min_y,
                     __m512i *max_x, __m512i *max_y)
{
    const __m512i low = _mm512_set1_epi64(luz_sample_reach_low(samples));
    const __m512i high = _mm512_set1_epi64(luz_sample_reach_high(samples));
    const __m512i zero = _mm512_setzero_si512();
    const __m512i min_fx = _mm512_min_epi64(x0, _mm512_min_epi64(x1, x2));
    const __m512i max_fx = _mm512_max_epi64(x0, _mm512_max_epi64(x1, x2));
    const __m512i min_fy = _mm512_min_epi64(y0, _mm512_min_epi64(y1, y2));
    const __m512i max_fy = _mm512_max_epi64(y0, _mm512_max_epi64(y1, y2));
    *min_x = _mm512_max_epi64(
        _mm512_sub_epi64(zero, _mm512_srai_epi64(_mm512_sub_epi64(high, min_fx),
                                                 LUZ_SUBPIXEL_BITS)),
        zero);
    *min_y = _mm512_max_epi64(
        _mm512_sub_epi64(zero, _mm512_srai_epi64(_mm512_sub_epi64(high, min_fy),
                                                 LUZ_SUBPIXEL_BITS)),
        zero);
    *max_x = _mm512_min_epi64(_mm512_srai_epi64(_mm512_sub_epi64(max_fx, low), LUZ_SUBPIXEL_BITS),
                              _mm512_set1_epi64(width - 1));
    *max_y = _mm512_min_epi64(_mm512_srai_epi64(_mm512_sub_epi64(max_fy, low), LUZ_SUBPIXEL_BITS),
                              _mm512_set1_epi64(height - 1));
}

/* luz_setup_projected's box of pixel centres: the x whose centre 256 x +
 * 128 lies within [min X, max X], from ceil((min X - 128) / 256) =
 * -((128 - min X) >> 8) to floor((max X - 128) / 256) = (max X - 128) >>
 * 8 (arithmetic shifts: floors), clamped to the viewport; likewise y. */
static inline __attribute__((always_inline)) void
luz_centre_box_lanes(__m512i x0, __m512i y0, __m512i x1, __m512i y1, __m512i x2, __m512i y2,
                     int width, int height, __m512i *min_x, __m512i *min_y, __m512i *max_x,
                     __m512i *max_y)
{
    luz_sample_box_lanes(x0, y0, x1, y1, x2, y2, width, height, 1, min_x, min_y, max_x, max_y);
}

/* setup.c's luz_setup_project_vertex for eight vertices of clip position (x, y,
 * z, w), one per lane, in the same double operations: 1/w, the window
 * position clamped to +-2^24 sub-pixel units, the depth. The markers (a
 * vertex outside a clip plane, or w not above 0) are the caller's. */
typedef struct luz_window_lanes {
    __m512d x, y, depth, inverse_w;
} luz_window_lanes;

static inline __attribute__((always_inline)) luz_window_lanes
luz_project_lanes(__m512d x, __m512d y, __m512d z, __m512d w, double width, double height)
{
    const __m512d one = _mm512_set1_pd(1.0), half = _mm512_set1_pd(0.5);
    luz_window_lanes window;
    window.inverse_w = _mm512_div_pd(one, w);
    const __m512d x_ndc = _mm512_mul_pd(x, window.inverse_w);
    const __m512d y_ndc = _mm512_mul_pd(y, window.inverse_w);
    window.x = _mm512_mul_pd(_mm512_mul_pd(_mm512_add_pd(x_ndc, one), half),
                             _mm512_set1_pd(width));
    window.y = _mm512_mul_pd(_mm512_mul_pd(_mm512_sub_pd(one, y_ndc), half),
                             _mm512_set1_pd(height));
    const __m512d limit = _mm512_set1_pd(LUZ_COORDINATE_LIMIT / LUZ_SUBPIXEL_ONE);
    const __m512d lowest = _mm512_set1_pd(-LUZ_COORDINATE_LIMIT / LUZ_SUBPIXEL_ONE);
    /* (Unreachable for a vertex inside the guard band, as in setup.c:
     * a bound that holds whatever the input.) */
    window.x = _mm512_mask_mov_pd(window.x, _mm512_cmp_pd_mask(window.x, limit, _CMP_GT_OQ),
                                  limit);
    window.x = _mm512_mask_mov_pd(window.x, _mm512_cmp_pd_mask(window.x, lowest, _CMP_LT_OQ),
                                  lowest);
    window.y = _mm512_mask_mov_pd(window.y, _mm512_cmp_pd_mask(window.y, limit, _CMP_GT_OQ),
                                  limit);
    window.y = _mm512_mask_mov_pd(window.y, _mm512_cmp_pd_mask(window.y, lowest, _CMP_LT_OQ),
                                  lowest);
    window.depth = _mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(z, window.inverse_w), one), half);
    return window;
}

/* luz_transpose8 (transpose8.h) for 64-bit elements: rows[0..7] of eight
 * quadwords each; rows[k][r] becomes rows[r][k]. */
static inline __attribute__((always_inline)) void luz_transpose8_quads(__m512i rows[8])
{
    __m512i t[8], u[8];
    /* t[2j] holds, per 128-bit block b, (r2j[2b], r2j+1[2b]); t[2j + 1]
     * the same of the odd columns. */
    for (int k = 0; k < 8; k += 2) {
        t[k] = _mm512_unpacklo_epi64(rows[k], rows[k + 1]);
        t[k + 1] = _mm512_unpackhi_epi64(rows[k], rows[k + 1]);
    }
    /* u[c] (c < 4) holds columns c and c + 4 of rows 0-3, u[4 + c] of
     * rows 4-7: (r0[c], r1[c]), (r0[c+4], r1[c+4]), (r2[c], r3[c]),
     * (r2[c+4], r3[c+4]). */
    for (int k = 0; k < 8; k += 4) {
        u[k] = _mm512_shuffle_i64x2(t[k], t[k + 2], 0x88);
        u[k + 1] = _mm512_shuffle_i64x2(t[k + 1], t[k + 3], 0x88);
        u[k + 2] = _mm512_shuffle_i64x2(t[k], t[k + 2], 0xdd);
        u[k + 3] = _mm512_shuffle_i64x2(t[k + 1], t[k + 3], 0xdd);
    }
    const __m512i low = _mm512_set_epi64(13, 12, 9, 8, 5, 4, 1, 0);
    const __m512i high = _mm512_set_epi64(15, 14, 11, 10, 7, 6, 3, 2);
    for (int c = 0; c < 4; c++) {
        rows[c] = _mm512_permutex2var_epi64(u[c], low, u[4 + c]);
        rows[c + 4] = _mm512_permutex2var_epi64(u[c], high, u[4 + c]);
    }
}

#endif
