/*
 * transpose8.h: the 8 x 8 transpose of 32-bit elements in AVX registers,
 * one copy for the kernels that read eight records' fields at once and
 * need them as eight vectors of one field each: lanes.h's (AVX2's
 * geometry), lanes_avx512.h's (AVX-512's, two of them for sixteen lanes)
 * and fragment_packet.c's (the packets' planes). Private to the library.
 *
 * Defined only where the file is compiled for AVX (its variant's flags,
 * src/renderer/meson.build).
 */
#ifndef LUZ_TRANSPOSE8_H
#define LUZ_TRANSPOSE8_H

#if defined(__AVX__)
#include <immintrin.h>

/* Afterwards rows[j][i] is what rows[i][j] was. Three rounds: unpack
 * pairs of rows, shuffle pairs of pairs, swap 128-bit halves (24
 * shuffles for 64 elements). */
static inline __attribute__((always_inline)) void luz_transpose8(__m256 rows[8])
{
    const __m256 t0 = _mm256_unpacklo_ps(rows[0], rows[1]);
    const __m256 t1 = _mm256_unpackhi_ps(rows[0], rows[1]);
    const __m256 t2 = _mm256_unpacklo_ps(rows[2], rows[3]);
    const __m256 t3 = _mm256_unpackhi_ps(rows[2], rows[3]);
    const __m256 t4 = _mm256_unpacklo_ps(rows[4], rows[5]);
    const __m256 t5 = _mm256_unpackhi_ps(rows[4], rows[5]);
    const __m256 t6 = _mm256_unpacklo_ps(rows[6], rows[7]);
    const __m256 t7 = _mm256_unpackhi_ps(rows[6], rows[7]);
    const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xee);
    const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xee);
    const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xee);
    const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xee);
    rows[0] = _mm256_permute2f128_ps(u0, u4, 0x20);
    rows[1] = _mm256_permute2f128_ps(u1, u5, 0x20);
    rows[2] = _mm256_permute2f128_ps(u2, u6, 0x20);
    rows[3] = _mm256_permute2f128_ps(u3, u7, 0x20);
    rows[4] = _mm256_permute2f128_ps(u0, u4, 0x31);
    rows[5] = _mm256_permute2f128_ps(u1, u5, 0x31);
    rows[6] = _mm256_permute2f128_ps(u2, u6, 0x31);
    rows[7] = _mm256_permute2f128_ps(u3, u7, 0x31);
}
#endif

#endif
