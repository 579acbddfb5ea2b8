/*
 * lanes.h: the vectors the geometry kernels in lanes are written with
 * (screen_lanes.c, setup_lanes.c, vertex_lanes.c), once for every width.
 *
 * A kernel is plain C on GCC / clang vector extensions (`vector_size`, as
 * fragment_packet.c): `a + b` on two vi64 adds LANES pairs of int64, a
 * comparison gives all ones or all zeros per lane, and the compiler turns
 * each operation into the instructions of the file's instruction set,
 * splitting a vector wider than a register into several. src/renderer/
 * meson.build compiles each kernel once per set, with one of
 *
 *   LUZ_LANES_AVX2     x86-64 AVX2 and FMA (FMA unused: -ffp-contract=off)
 *   LUZ_LANES_NEON     aarch64 Advanced SIMD (the build's target)
 *   LUZ_LANES_SSE2     x86-64's baseline, SSE2 (the build's target)
 *   LUZ_LANES_AVX512   x86-64 AVX-512 F, VL, BW, DQ: screen_lanes.c (the
 *                      other kernels keep AVX-512 intrinsics of their
 *                      own, faster: setup_eight.c, vertex_sixteen.c)
 *
 * and the file picks its LANES for each (the triangles or vertices of a
 * step). A handful of operations that the extensions cannot say, or say
 * slowly, are the functions below, with an instruction-set form where
 * one exists and a portable loop otherwise: the signed 32 x 32 -> 64-bit
 * product, a lane mask as bits, the gather of snapped positions, the
 * transposes between a structure per lane and a vector per field, and
 * appending the kept lanes to a list. Every one of them computes exactly
 * what its loop says; the kernels' arithmetic is the scalar reference's,
 * operation for operation (see each kernel), so every width gives the
 * same bits.
 */
#ifndef LUZ_LANES_H
#define LUZ_LANES_H

#include <stdint.h>
#include <string.h>

#include "renderer/pipeline.h"
#include "renderer/transpose8.h"

#if !defined(LANES)
#error "define LANES (the lanes of a step) before including lanes.h"
#endif
#if defined(__AVX2__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__ARM_NEON) && defined(__aarch64__)
#include <arm_neon.h>
#endif

#define LANES_INLINE static inline __attribute__((always_inline))

/* A vector wider than the registers (int64 lanes with AVX2) is passed in
 * memory between functions, which GCC warns has changed; these functions
 * are always inlined, so no vector crosses a call. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

typedef float vf32 __attribute__((vector_size(LANES * sizeof(float))));
typedef int32_t vi32 __attribute__((vector_size(LANES * sizeof(int32_t))));
typedef uint32_t vu32 __attribute__((vector_size(LANES * sizeof(uint32_t))));
/* 64-bit lanes: half as many, so that every vector is one register (a
 * vector wider than the registers is split by the compiler, but its
 * comparisons are done one element at a time). A step's 64-bit work is
 * done in two halves, lanes 0 .. HALF - 1 and HALF .. LANES - 1. */
#define HALF (LANES / 2)
typedef double vf64 __attribute__((vector_size(HALF * sizeof(double))));
typedef int64_t vi64 __attribute__((vector_size(HALF * sizeof(int64_t))));

/* ---- lanes of masks and values ------------------------------------------ */

LANES_INLINE vi32 splat32(int32_t value)
{
    return (vi32){0} + value;
}

LANES_INLINE vi64 splat64(int64_t value)
{
    return (vi64){0} + value;
}

LANES_INLINE vf32 splatf(float value)
{
    return value - (vf32){0};   /* x - 0 is x, even for x = -0 */
}

LANES_INLINE vf64 splatd(double value)
{
    return value - (vf64){0};
}

/* mask ? a : b, lane by lane (a mask lane is all ones or all zeros). */
LANES_INLINE vi32 select32(vi32 mask, vi32 a, vi32 b)
{
    return (a & mask) | (b & ~mask);
}

LANES_INLINE vi64 select64(vi64 mask, vi64 a, vi64 b)
{
    return (a & mask) | (b & ~mask);
}

LANES_INLINE vf32 selectf(vi32 mask, vf32 a, vf32 b)
{
    return (vf32)select32(mask, (vi32)a, (vi32)b);
}

LANES_INLINE vf64 selectd(vi64 mask, vf64 a, vf64 b)
{
    return (vf64)select64(mask, (vi64)a, (vi64)b);
}

LANES_INLINE vi32 min32(vi32 a, vi32 b)
{
    return select32(a < b, a, b);
}

LANES_INLINE vi32 max32(vi32 a, vi32 b)
{
    return select32(a > b, a, b);
}

/* Half h (0: lanes 0 .. HALF - 1, 1: the rest) of 32-bit lanes,
 * sign-extended to 64 bits (a mask stays a mask). With AVX2 and AVX-512
 * one vpmovsxdq of the half: GCC 12 made __builtin_convertvector's
 * widening two conversions of a quarter each and an insert. */
LANES_INLINE vi64 widen_half(vi32 v, int h)
{
#if LANES == 16 && defined(__AVX512F__)
    return (vi64)_mm512_cvtepi32_epi64(h == 0 ? _mm512_castsi512_si256((__m512i)v)
                                              : _mm512_extracti64x4_epi64((__m512i)v, 1));
#elif LANES == 8 && defined(__AVX2__)
    return (vi64)_mm256_cvtepi32_epi64(h == 0 ? _mm256_castsi256_si128((__m256i)v)
                                              : _mm256_extracti128_si256((__m256i)v, 1));
#else
#if LANES == 16
    typedef int32_t half_vector __attribute__((vector_size(8 * sizeof(int32_t))));
    const half_vector part = h == 0 ? __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7)
                                    : __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15);
#elif LANES == 8
    typedef int32_t half_vector __attribute__((vector_size(4 * sizeof(int32_t))));
    const half_vector part = h == 0 ? __builtin_shufflevector(v, v, 0, 1, 2, 3)
                                    : __builtin_shufflevector(v, v, 4, 5, 6, 7);
#elif LANES == 4
    typedef int32_t half_vector __attribute__((vector_size(2 * sizeof(int32_t))));
    const half_vector part = h == 0 ? __builtin_shufflevector(v, v, 0, 1)
                                    : __builtin_shufflevector(v, v, 2, 3);
#else
#error "lanes.h: 4, 8 or 16 lanes"
#endif
    return __builtin_convertvector(part, vi64);
#endif
}

/* Bit i set where lane i of the mask is. */
LANES_INLINE unsigned lane_bits(vi32 mask)
{
#if LANES == 16 && defined(__AVX512DQ__)
    return (unsigned)_mm512_movepi32_mask((__m512i)mask);
#elif LANES == 8 && defined(__AVX2__)
    return (unsigned)_mm256_movemask_ps((__m256)mask);
#elif LANES == 4 && defined(__SSE2__)
    return (unsigned)_mm_movemask_ps((__m128)mask);
#else
    unsigned bits = 0;
    for (int i = 0; i < LANES; i++) bits |= (unsigned)(mask[i] != 0) << i;
    return bits;
#endif
}

/* The lanes whose bits are set, as a mask. */
LANES_INLINE vi32 lanes_of_bits(unsigned bits)
{
    vi32 bit;
    for (int i = 0; i < LANES; i++) bit[i] = (int32_t)(1u << i);
    return (splat32((int32_t)bits) & bit) != 0;
}

/* Half h of float lanes, widened to double (exact); one vcvtps2pd of the
 * half with AVX2 and AVX-512, as widen_half. */
LANES_INLINE vf64 widen_half_float(vf32 v, int h)
{
#if LANES == 16 && defined(__AVX512F__)
    return (vf64)_mm512_cvtps_pd(
        h == 0 ? _mm512_castps512_ps256((__m512)v)
               : _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd((__m512)v), 1)));
#elif LANES == 8 && defined(__AVX2__)
    return (vf64)_mm256_cvtps_pd(h == 0 ? _mm256_castps256_ps128((__m256)v)
                                        : _mm256_extractf128_ps((__m256)v, 1));
#else
#if LANES == 16
    typedef float half_vector __attribute__((vector_size(8 * sizeof(float))));
    const half_vector part = h == 0 ? __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7)
                                    : __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15);
#elif LANES == 8
    typedef float half_vector __attribute__((vector_size(4 * sizeof(float))));
    const half_vector part = h == 0 ? __builtin_shufflevector(v, v, 0, 1, 2, 3)
                                    : __builtin_shufflevector(v, v, 4, 5, 6, 7);
#else
    typedef float half_vector __attribute__((vector_size(2 * sizeof(float))));
    const half_vector part = h == 0 ? __builtin_shufflevector(v, v, 0, 1)
                                    : __builtin_shufflevector(v, v, 2, 3);
#endif
    return __builtin_convertvector(part, vf64);
#endif
}

/* Bit i set where lane i of a 64-bit mask is. */
LANES_INLINE unsigned lane_bits64(vi64 mask)
{
#if HALF == 8 && defined(__AVX512DQ__)
    return (unsigned)_mm512_movepi64_mask((__m512i)mask);
#elif HALF == 4 && defined(__AVX2__)
    return (unsigned)_mm256_movemask_pd((__m256d)mask);
#elif HALF == 2 && defined(__SSE2__)
    return (unsigned)_mm_movemask_pd((__m128d)mask);
#else
    unsigned bits = 0;
    for (int i = 0; i < HALF; i++) bits |= (unsigned)(mask[i] != 0) << i;
    return bits;
#endif
}

/* Bit i set where 64-bit lane i is negative: its sign bit, read as a
 * double's on x86 (movmskpd; SSE2 has no 64-bit comparison, and a
 * comparison emulated there goes one lane at a time). */
LANES_INLINE unsigned negative_bits64(vi64 v)
{
#if HALF == 4 && defined(__AVX2__)
    return (unsigned)_mm256_movemask_pd((__m256d)v);
#elif HALF == 2 && defined(__SSE2__)
    return (unsigned)_mm_movemask_pd((__m128d)v);
#else
    return lane_bits64(v < 0);
#endif
}

/* All ones in the negative 64-bit lanes, zeros in the others: the sign
 * spread over the lane (SSE2: each high word's, shifted across it and
 * copied to the low word). */
LANES_INLINE vi64 negative_mask64(vi64 v)
{
#if HALF == 2 && defined(__SSE2__) && !defined(__SSE4_2__)
    return (vi64)_mm_shuffle_epi32(_mm_srai_epi32((__m128i)v, 31), 0xf5);
#else
    return v < 0;
#endif
}

/* a * b for 64-bit lanes that hold signed 32-bit values, each product
 * exact in 64 bits (vpmuldq; smull). */
LANES_INLINE vi64 multiply_wide(vi64 a, vi64 b)
{
#if HALF == 8 && defined(__AVX512F__)
    return (vi64)_mm512_mul_epi32((__m512i)a, (__m512i)b);
#elif HALF == 4 && defined(__AVX2__)
    return (vi64)_mm256_mul_epi32((__m256i)a, (__m256i)b);
#elif HALF == 2 && defined(__ARM_NEON) && defined(__aarch64__)
    return (vi64)vmull_s32(vmovn_s64((int64x2_t)a), vmovn_s64((int64x2_t)b));
#else
    return a * b;
#endif
}

/* v > limit ? limit : v < -limit ? -limit : v, lane by lane (a NaN stays
 * itself): x86's minpd (a < b ? a : b) and maxpd (a > b ? a : b) with
 * the bound first are those selects, one instruction each, where a
 * select is a comparison and a blend. */
LANES_INLINE vf64 clamp_to_limit(vf64 v, double limit)
{
#if HALF == 4 && defined(__AVX2__)
    return (vf64)_mm256_max_pd(_mm256_set1_pd(-limit),
                               _mm256_min_pd(_mm256_set1_pd(limit), (__m256d)v));
#elif HALF == 2 && defined(__SSE2__)
    return (vf64)_mm_max_pd(_mm_set1_pd(-limit), _mm_min_pd(_mm_set1_pd(limit), (__m128d)v));
#else
    v = selectd(v > limit, splatd(limit), v);
    return selectd(v < -limit, splatd(-limit), v);
#endif
}

/* |a| of float and double lanes: the sign bit cleared. */
LANES_INLINE vf32 absf(vf32 a)
{
    return (vf32)((vi32)a & 0x7fffffff);
}

/* x rounded to the nearest integer, ties to even (llrint in the default
 * rounding mode), for |x| < 2^51: adding 1.5 * 2^52 leaves no bit below
 * the units, and taking it away again is exact. */
LANES_INLINE vf64 round_to_even(vf64 x)
{
    const double magic = 6755399441055744.0;   /* 1.5 * 2^52 */
    return (x + magic) - magic;
}

/* ---- from memory to lanes and back ------------------------------------ */

/* The snapped (X, Y) of the vertices of index (a vertex each lane). */
LANES_INLINE void gather_fixed(vi32 index, const luz_fixed_vertex *fixed, vi32 *x, vi32 *y)
{
    _Static_assert(sizeof(luz_fixed_vertex) == 8, "a vertex's x and y are one 64-bit load");
#if LANES == 16 && defined(__AVX512F__)
    /* A 64-bit gather a vertex, for each half. */
    const __m512i low = _mm512_i32gather_epi64(_mm512_castsi512_si256((__m512i)index),
                                               (const void *)fixed, 8);
    const __m512i high = _mm512_i32gather_epi64(_mm512_extracti64x4_epi64((__m512i)index, 1),
                                                (const void *)fixed, 8);
    *x = (vi32)_mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvtepi64_epi32(low)),
                                  _mm512_cvtepi64_epi32(high), 1);
    *y = (vi32)_mm512_inserti64x4(
        _mm512_castsi256_si512(_mm512_cvtepi64_epi32(_mm512_srli_epi64(low, 32))),
        _mm512_cvtepi64_epi32(_mm512_srli_epi64(high, 32)), 1);
#elif LANES == 8 && defined(__AVX2__)
    /* A 64-bit load a vertex, two to a 128-bit half, then x and y apart
     * (AVX2's vpgatherdq is slower on AMD's Zen 4 than the loop: the 1M
     * sphere's frame 30.7 -> 33.2 CPU ms; the loop, two vpinsrd a
     * vertex, twice the instructions of these loads). */
    __m128i pair[4];
    for (int p = 0; p < 4; p++) {
        const __m128i first = _mm_loadl_epi64((const void *)&fixed[index[2 * p]]);
        pair[p] = _mm_castpd_si128(_mm_loadh_pd(_mm_castsi128_pd(first),
                                                (const void *)&fixed[index[2 * p + 1]]));
    }
    /* (x0 y0 x1 y1 | x4 y4 x5 y5) and (x2 y2 x3 y3 | x6 y6 x7 y7) */
    const __m256 low = _mm256_castsi256_ps(
        _mm256_inserti128_si256(_mm256_castsi128_si256(pair[0]), pair[2], 1));
    const __m256 high = _mm256_castsi256_ps(
        _mm256_inserti128_si256(_mm256_castsi128_si256(pair[1]), pair[3], 1));
    *x = (vi32)_mm256_castps_si256(_mm256_shuffle_ps(low, high, _MM_SHUFFLE(2, 0, 2, 0)));
    *y = (vi32)_mm256_castps_si256(_mm256_shuffle_ps(low, high, _MM_SHUFFLE(3, 1, 3, 1)));
#else
    for (int i = 0; i < LANES; i++) {
        (*x)[i] = fixed[index[i]].x;
        (*y)[i] = fixed[index[i]].y;
    }
#endif
}

#if LANES == 4
/* A 4 x 4 transpose of floats in registers (SSE2's shufps and unpcks,
 * NEON's zips): row[l][k] becomes row[k][l]. */
LANES_INLINE void transpose4(vf32 row[4])
{
    const vf32 t0 = __builtin_shufflevector(row[0], row[1], 0, 4, 1, 5);
    const vf32 t1 = __builtin_shufflevector(row[0], row[1], 2, 6, 3, 7);
    const vf32 t2 = __builtin_shufflevector(row[2], row[3], 0, 4, 1, 5);
    const vf32 t3 = __builtin_shufflevector(row[2], row[3], 2, 6, 3, 7);
    row[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    row[1] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
    row[2] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    row[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}
#endif

/* Lanes l of the 8 floats at from[l] (l < LANES): column[k][l] =
 * from[l][k], a transpose of LANES rows of 8 into 8 vectors. */
LANES_INLINE void load_columns8(const float *const from[LANES], vf32 column[8])
{
#if LANES == 8 && defined(__AVX2__)
    __m256 rows[8];
    for (int l = 0; l < 8; l++) rows[l] = _mm256_loadu_ps(from[l]);
    luz_transpose8(rows);
    for (int k = 0; k < 8; k++) column[k] = (vf32)rows[k];
#elif LANES == 16 && defined(__AVX512F__)
    union { vf32 v; __m256 half[2]; } out[8];
    for (int h = 0; h < 2; h++) {
        __m256 rows[8];
        for (int l = 0; l < 8; l++) rows[l] = _mm256_loadu_ps(from[8 * h + l]);
        luz_transpose8(rows);
        for (int k = 0; k < 8; k++) out[k].half[h] = rows[k];
    }
    for (int k = 0; k < 8; k++) column[k] = out[k].v;
#elif LANES == 4
    for (int q = 0; q < 2; q++) {   /* floats 0-3, then 4-7 */
        vf32 rows[4];
        for (int l = 0; l < 4; l++) memcpy(&rows[l], from[l] + 4 * q, sizeof rows[l]);
        transpose4(rows);
        for (int k = 0; k < 4; k++) column[4 * q + k] = rows[k];
    }
#else
    for (int k = 0; k < 8; k++)
        for (int l = 0; l < LANES; l++) column[k][l] = from[l][k];
#endif
}

/* The other way: to[l][k] = column[k][l] for k < count (a multiple of
 * 8), l < LANES: each lane's count words, stored whole and lane after
 * lane, so that each lane's bytes are written in order (on the 1M sphere
 * writing eight records 32 bytes at a time, the first 32 bytes of each,
 * then the next, made AVX2's setup slower). The transposes stay in
 * registers: through memory, the halves a vector was stored as would be
 * loaded back whole, which the CPU cannot forward from its store buffer. */
LANES_INLINE void store_columns(float *const to[LANES], const vf32 *column, int count)
{
#if LANES == 8 && defined(__AVX2__)
    __m256 rows[count / 8][8];
    for (int q = 0; q < count / 8; q++) {
        for (int k = 0; k < 8; k++) rows[q][k] = (__m256)column[8 * q + k];
        luz_transpose8(rows[q]);   /* a transpose is its own inverse */
    }
    for (int l = 0; l < 8; l++)
        for (int q = 0; q < count / 8; q++) _mm256_storeu_ps(to[l] + 8 * q, rows[q][l]);
#elif LANES == 4
    vf32 rows[count / 4][4];
    for (int q = 0; q < count / 4; q++) {
        for (int k = 0; k < 4; k++) rows[q][k] = column[4 * q + k];
        transpose4(rows[q]);
    }
    for (int l = 0; l < 4; l++)
        for (int q = 0; q < count / 4; q++) memcpy(to[l] + 4 * q, &rows[q][l], sizeof rows[q][l]);
#else
    for (int l = 0; l < LANES; l++)
        for (int k = 0; k < count; k++) to[l][k] = column[k][l];
#endif
}

/* Two halves of 64-bit lanes made one vector of 32-bit lanes, in
 * registers: the doubles rounded to float (as a C cast: to nearest
 * even), or the integers' low or high words (little-endian: a 64-bit
 * lane's low word is its first 32-bit element). */
#if LANES == 16
#define LANES_JOIN(a, b) \
    __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15)
#define LANES_EVEN(a, b) \
    __builtin_shufflevector(a, b, 0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30)
#define LANES_ODD(a, b) \
    __builtin_shufflevector(a, b, 1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31)
#elif LANES == 8
#define LANES_JOIN(a, b) __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7)
#define LANES_EVEN(a, b) __builtin_shufflevector(a, b, 0, 2, 4, 6, 8, 10, 12, 14)
#define LANES_ODD(a, b) __builtin_shufflevector(a, b, 1, 3, 5, 7, 9, 11, 13, 15)
#elif LANES == 4
#define LANES_JOIN(a, b) __builtin_shufflevector(a, b, 0, 1, 2, 3)
#define LANES_EVEN(a, b) __builtin_shufflevector(a, b, 0, 2, 4, 6)
#define LANES_ODD(a, b) __builtin_shufflevector(a, b, 1, 3, 5, 7)
#endif

LANES_INLINE vf32 narrow_join(vf64 low, vf64 high)
{
#if LANES == 8 && defined(__AVX2__)
    /* (GCC 12 put a vmovaps between each vcvtpd2ps and the insert.) */
    return (vf32)_mm256_insertf128_ps(_mm256_castps128_ps256(_mm256_cvtpd_ps((__m256d)low)),
                                      _mm256_cvtpd_ps((__m256d)high), 1);
#endif
    typedef float half_floats __attribute__((vector_size(HALF * sizeof(float))));
    return LANES_JOIN(__builtin_convertvector(low, half_floats),
                      __builtin_convertvector(high, half_floats));
}

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#error "lanes.h: low_words and high_words assume little-endian lanes"
#endif

LANES_INLINE vi32 low_words(vi64 low, vi64 high)
{
    return LANES_EVEN((vi32)low, (vi32)high);
}

LANES_INLINE vi32 high_words(vi64 low, vi64 high)
{
    return LANES_ODD((vi32)low, (vi32)high);
}

/* Appends first + l for each lane l of bits to list, in order, and
 * returns how many; bits has none of lanes valid and above, and list has
 * room for `valid` more past *count. */
LANES_INLINE unsigned append_lanes(uint32_t *list, size_t *count, uint32_t first, unsigned bits,
                                   int valid)
{
#if LANES == 16 && defined(__AVX512F__)
    const __m512i lane = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
    const __m512i value = _mm512_add_epi32(_mm512_set1_epi32((int)first), lane);
    (void)valid;
    const unsigned kept = (unsigned)__builtin_popcount(bits);
    /* The compress in a register, then a plain (masked) store: AMD's Zen 4
     * runs a compress straight to memory as slow microcode. */
    _mm512_mask_storeu_epi32(list + *count, (__mmask16)((1u << kept) - 1),
                             _mm512_maskz_compress_epi32((__mmask16)bits, value));
    *count += kept;
    return kept;
#else
    size_t at = *count;
    if (valid == LANES) {
        /* Four lanes at a time: the kept ones' numbers, first + the lanes
         * in order (a table of the 16 patterns), stored as four words at
         * the end of the list, which moves on past the kept ones (the
         * other words are written over next, or lie in the list's room).
         * Where the loop below takes a store and a chain of adds a lane
         * (AVX2's screening of the 1M sphere 4.75 -> 4.53 ms a frame). */
        typedef uint32_t quarter __attribute__((vector_size(4 * sizeof(uint32_t))));
        static const quarter kept_lanes[16] = {
            {0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0},
            {2, 0, 0, 0}, {0, 2, 0, 0}, {1, 2, 0, 0}, {0, 1, 2, 0},
            {3, 0, 0, 0}, {0, 3, 0, 0}, {1, 3, 0, 0}, {0, 1, 3, 0},
            {2, 3, 0, 0}, {0, 2, 3, 0}, {1, 2, 3, 0}, {0, 1, 2, 3},
        };
        for (int q = 0; q < LANES / 4; q++) {
            const unsigned four = bits >> (4 * q) & 15u;
            const quarter kept = kept_lanes[four] + (first + 4 * (uint32_t)q);
            memcpy(list + at, &kept, sizeof kept);
            at += 0x4332322132212110ull >> (4 * four) & 15u;   /* four's bits set */
        }
        const unsigned kept = (unsigned)(at - *count);
        *count = at;
        return kept;
    }
    /* Each lane written at the end of the list, which moves on only past
     * the kept ones: no branch per lane. */
    for (int l = 0; l < valid; l++) {
        list[at] = first + (uint32_t)l;
        at += bits >> l & 1u;
    }
    const unsigned kept = (unsigned)(at - *count);
    *count = at;
    return kept;
#endif
}

#endif
