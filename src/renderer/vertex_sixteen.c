/*
 * vertex_sixteen.c: the vertex stage and the projection of its vertices
 * (vertex.c's luz_vertex_stage_range, then setup.c's luz_setup_project)
 * for sixteen vertices at once, one per 32-bit lane of AVX-512 vectors.
 *
 * In:  a draw (mesh, model matrix), the frame's projection * view, a range
 *      of the mesh's vertices, the viewport's size.
 * Out: for each vertex, the same bits as the two functions write: its
 *      luz_clip_vertex (clip position, world position and normal, uv,
 *      outcode; unless out is NULL, when only positions are transformed:
 *      position-only shading, for a pass that keeps the snapped positions
 *      alone), and, unless marked, its luz_window_vertex (window x, y,
 *      depth, 1/w in double, snapped position; unless window is NULL)
 *      and luz_fixed_vertex (unless fixed is NULL); but
 *      where two NaNs of different signs meet (NaN normals, uv or matrix
 *      entries, which no check keeps out), the NaN that comes out may have
 *      the other sign (x86 keeps one operand's, and the compiler orders
 *      the operands of each loop its own way). A
 *      marked vertex (outside a clip plane, LUZ_WINDOW_CLIPPED, or not
 *      projectable, LUZ_WINDOW_INVALID) gets its marker; its window
 *      vertex's other fields are left meaning nothing, as setup.c's
 *      leave them.
 *
 * Why: one vertex at a time, the two passes were a large share of a
 * 1M-triangle sphere's geometry (500k vertices): three transforms and a
 * divide a vertex, and 52 bytes of clip vertex written, read back, then
 * 48 bytes of projection written. Here sixteen vertices are read whole
 * and transposed into lanes, transformed and projected in registers, and
 * transposed back out once (faster, though the stores remained, until
 * position-only shading, setup_eight.c, left 8 bytes a vertex to store;
 * docs/performance.md, "Measured in the code").
 *
 * The arithmetic is vertex.c's and setup.c's, operation for operation:
 * each transform a[0] x + a[4] y + a[8] z + a[12] summed left to right
 * in float (a[12] * 1.0f is a[12] exactly), the outcode's six
 * comparisons, the divide, viewport and clamp in double, the snap rounded
 * to nearest even as llrint does; no fused multiply-add.
 * tests/test_vertex_sixteen.c holds every byte to the two functions.
 *
 * Instruction sets: src/renderer/meson.build compiles this file with
 * AVX-512 alone; without it vertices go one at a time (cpu.c's tables).
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "renderer/pipeline.h"

#if !defined(__AVX512F__) || !defined(__AVX512DQ__) || !defined(__AVX512VL__)
#error "the AVX-512 variant is compiled with -mavx512f -mavx512dq -mavx512vl ..."
#endif
#include <immintrin.h>

#include "renderer/lanes_avx512.h"

_Static_assert(sizeof(luz_vertex) == 8 * sizeof(float), "a mesh vertex is eight floats");
_Static_assert(offsetof(luz_vertex, normal) == 12 && offsetof(luz_vertex, uv) == 24,
               "position, normal, uv");
_Static_assert(sizeof(luz_clip_vertex) == 13 * sizeof(float) &&
                   offsetof(luz_clip_vertex, varyings) == 16 &&
                   offsetof(luz_clip_vertex, outcode) == 48,
               "a clip vertex is 13 words: position, varyings, outcode");
_Static_assert(sizeof(luz_window_vertex) == 5 * sizeof(double) &&
                   offsetof(luz_window_vertex, fixed_x) == 32,
               "a window vertex is 5 quadwords: x, y, depth, 1/w, fixed x and y");

/* Lanes 8 h .. 8 h + 7 of a vector (h, 0 or 1, in an immediate each way). */
static inline __attribute__((always_inline)) __m256 half_of(__m512 v, int h)
{
    return h ? _mm512_extractf32x8_ps(v, 1) : _mm512_castps512_ps256(v);
}

static inline __attribute__((always_inline)) __m256i half_of_int(__m512i v, int h)
{
    return h ? _mm512_extracti32x8_epi32(v, 1) : _mm512_castsi512_si256(v);
}

/* a[0] x + a[4] y + a[8] z + a[12] w with w = 1 (vertex.c's transform4,
 * row r of a column-major 4 x 4), summed left to right. */
static inline __attribute__((always_inline)) __m512
transform_row(const float *a, int r, __m512 x, __m512 y, __m512 z)
{
    return _mm512_add_ps(
        _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(a[r]), x),
                                    _mm512_mul_ps(_mm512_set1_ps(a[4 + r]), y)),
                      _mm512_mul_ps(_mm512_set1_ps(a[8 + r]), z)),
        _mm512_set1_ps(a[12 + r]));
}

/* a[0] x + a[3] y + a[6] z (transform3, row r of a column-major 3 x 3). */
static inline __attribute__((always_inline)) __m512
transform_row3(const float *a, int r, __m512 x, __m512 y, __m512 z)
{
    return _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(a[r]), x),
                                       _mm512_mul_ps(_mm512_set1_ps(a[3 + r]), y)),
                         _mm512_mul_ps(_mm512_set1_ps(a[6 + r]), z));
}

/* One bit of the outcode: set where !(value >= 0) (NaN included). */
static inline __attribute__((always_inline)) __m512i
outcode_bit(__m512i code, __m512 value, unsigned bit)
{
    const __mmask16 inside = _mm512_cmp_ps_mask(value, _mm512_setzero_ps(), _CMP_GE_OQ);
    return _mm512_mask_or_epi32(code, (__mmask16)~inside, code, _mm512_set1_epi32((int)bit));
}

/* Half h (vertices 8 h .. 8 h + 7) of sixteen: their projection, setup.c's
 * luz_setup_project. */
static inline __attribute__((always_inline)) void
project_eight(__m256 x, __m256 y, __m256 z, __m256 w, __m256i outcode, double width,
              double height, luz_window_vertex *window, luz_fixed_vertex *fixed)
{
    const __m512d xd = _mm512_cvtps_pd(x), yd = _mm512_cvtps_pd(y);
    const __m512d zd = _mm512_cvtps_pd(z), wd = _mm512_cvtps_pd(w);
    const __m512d infinity = _mm512_set1_pd(INFINITY);
    /* 1. Divide and viewport, then the clamp to +-2^24 sub-pixel units. */
    const luz_window_lanes projected = luz_project_lanes(xd, yd, zd, wd, width, height);
    const __m512d window_x = projected.x, window_y = projected.y;
    const __m512d depth = projected.depth, inverse_w = projected.inverse_w;
    /* 2. Snap: rounded to nearest even (the MXCSR's mode, llrint's). */
    const __m512d subpixel = _mm512_set1_pd(LUZ_SUBPIXEL_ONE);
    __m256i fixed_x = _mm512_cvtpd_epi32(_mm512_mul_pd(window_x, subpixel));
    __m256i fixed_y = _mm512_cvtpd_epi32(_mm512_mul_pd(window_y, subpixel));
    /* The markers: outside a clip plane, else not projectable (w not
     * above 0, or x, y or z not finite). */
    const __mmask8 clipped = _mm256_cmpneq_epi32_mask(outcode, _mm256_setzero_si256());
    const __mmask8 projectable =
        _mm512_cmp_pd_mask(wd, _mm512_setzero_pd(), _CMP_GT_OQ) &
        _mm512_cmp_pd_mask(_mm512_abs_pd(xd), infinity, _CMP_LT_OQ) &
        _mm512_cmp_pd_mask(_mm512_abs_pd(yd), infinity, _CMP_LT_OQ) &
        _mm512_cmp_pd_mask(_mm512_abs_pd(zd), infinity, _CMP_LT_OQ);
    const __mmask8 invalid = (__mmask8)(~clipped & ~projectable);
    fixed_x = _mm256_mask_blend_epi32(clipped, fixed_x, _mm256_set1_epi32(LUZ_WINDOW_CLIPPED));
    fixed_x = _mm256_mask_blend_epi32(invalid, fixed_x, _mm256_set1_epi32(LUZ_WINDOW_INVALID));
    fixed_y = _mm256_maskz_mov_epi32((__mmask8)~(clipped | invalid), fixed_y);
    const __m512i packed = _mm512_or_si512(
        _mm512_cvtepu32_epi64(fixed_x), _mm512_slli_epi64(_mm512_cvtepu32_epi64(fixed_y), 32));
    if (fixed != NULL) _mm512_storeu_si512((void *)fixed, packed);
    if (window == NULL) return;
    __m512i rows[8] = {_mm512_castpd_si512(window_x),  _mm512_castpd_si512(window_y),
                       _mm512_castpd_si512(depth),     _mm512_castpd_si512(inverse_w),
                       packed,                         _mm512_setzero_si512(),
                       _mm512_setzero_si512(),         _mm512_setzero_si512()};
    luz_transpose8_quads(rows);
    /* Each row is five quadwords of eight: stored whole, its last three
     * land on the next vertex's first three, which that vertex's own
     * store then overwrites; only the eighth is masked, the next vertex
     * not being ours (AMD's Zen runs a masked store slower than a plain
     * one). */
    for (int lane = 0; lane < 7; lane++) _mm512_storeu_si512((void *)&window[lane], rows[lane]);
    _mm512_mask_storeu_epi64((void *)&window[7], 0x1f, rows[7]);
}

/* Vertices i .. i + 15 of the draw's mesh; with out NULL (a constant
 * where this is inlined), their positions alone: no normal, no clip
 * vertex. */
static inline __attribute__((always_inline)) void
sixteen(const luz_vertex *vertices, const float *model, const float *normal_matrix,
        const float *view_projection, uint32_t i, double width, double height,
        luz_clip_vertex *out, luz_window_vertex *window, luz_fixed_vertex *fixed)
{
    /* In: each vertex's eight floats, transposed into lanes. */
    __m256 low[8], high[8];
    for (int k = 0; k < 8; k++) {
        low[k] = _mm256_loadu_ps(&vertices[i + (uint32_t)k].position.x);
        high[k] = _mm256_loadu_ps(&vertices[i + 8 + (uint32_t)k].position.x);
    }
    luz_transpose8(low);
    luz_transpose8(high);
    __m512 in[8];
    for (int k = 0; k < 8; k++)
        in[k] = _mm512_insertf32x8(_mm512_castps256_ps512(low[k]), high[k], 1);

    /* vertex.c: world = model p, normal = N n, clip = VP world. */
    const __m512 world_x = transform_row(model, 0, in[0], in[1], in[2]);
    const __m512 world_y = transform_row(model, 1, in[0], in[1], in[2]);
    const __m512 world_z = transform_row(model, 2, in[0], in[1], in[2]);
    const __m512 normal_x = transform_row3(normal_matrix, 0, in[3], in[4], in[5]);
    const __m512 normal_y = transform_row3(normal_matrix, 1, in[3], in[4], in[5]);
    const __m512 normal_z = transform_row3(normal_matrix, 2, in[3], in[4], in[5]);
    const __m512 clip_x = transform_row(view_projection, 0, world_x, world_y, world_z);
    const __m512 clip_y = transform_row(view_projection, 1, world_x, world_y, world_z);
    const __m512 clip_z = transform_row(view_projection, 2, world_x, world_y, world_z);
    const __m512 clip_w = transform_row(view_projection, 3, world_x, world_y, world_z);
    /* luz_clip_outcode: near, far, left, right, bottom, top. */
    const __m512 guard_w = _mm512_mul_ps(_mm512_set1_ps(LUZ_CLIP_GUARD_BAND), clip_w);
    __m512i outcode = _mm512_setzero_si512();
    outcode = outcode_bit(outcode, _mm512_add_ps(clip_w, clip_z), 1u << 0);
    outcode = outcode_bit(outcode, _mm512_sub_ps(clip_w, clip_z), 1u << 1);
    outcode = outcode_bit(outcode, _mm512_add_ps(guard_w, clip_x), 1u << 2);
    outcode = outcode_bit(outcode, _mm512_sub_ps(guard_w, clip_x), 1u << 3);
    outcode = outcode_bit(outcode, _mm512_add_ps(guard_w, clip_y), 1u << 4);
    outcode = outcode_bit(outcode, _mm512_sub_ps(guard_w, clip_y), 1u << 5);

    /* Out: the clip vertices, words 0-7 and 8-12 of each, transposed back
     * a half (eight vertices) at a time. */
    const __m512 words[13] = {clip_x,   clip_y,   clip_z,   clip_w, world_x,
                              world_y,  world_z,  normal_x, normal_y, normal_z,
                              in[6],    in[7],    _mm512_castsi512_ps(outcode)};
    for (int h = 0; h < 2; h++) {
        const uint32_t base = i + 8 * (uint32_t)h;
        /* setup.c: the projection of these eight, from the lanes. */
        project_eight(half_of(clip_x, h), half_of(clip_y, h), half_of(clip_z, h),
                      half_of(clip_w, h), half_of_int(outcode, h), width, height,
                      window != NULL ? &window[base] : NULL,
                      fixed != NULL ? &fixed[base] : NULL);
        __m256 first[8], second[8];
        for (int k = 0; k < 8; k++) {
            first[k] = half_of(words[k], h);
            second[k] = k < 5 ? half_of(words[8 + k], h) : _mm256_setzero_ps();
        }
        if (out == NULL) continue;
        luz_transpose8(first);
        luz_transpose8(second);
        /* Words 8-12 stored whole as well, over the next vertex's first
         * three, which its own first store overwrites (as in
         * project_eight); the last vertex's masked. */
        for (int lane = 0; lane < 8; lane++) {
            float *record = (float *)(void *)&out[base + (uint32_t)lane];
            _mm256_storeu_ps(record, first[lane]);
            if (lane < 7 || h == 0) _mm256_storeu_ps(record + 8, second[lane]);
            else _mm256_mask_storeu_ps(record + 8, 0x1f, second[lane]);
        }
    }
}

luz_vertex_project_function luz_vertex_project_avx512;

void luz_vertex_project_avx512(const luz_draw *draw, luz_mat4 view_projection, uint32_t first,
                               uint32_t end, int width, int height, luz_clip_vertex *out,
                               luz_window_vertex *window, luz_fixed_vertex *fixed)
{
    if (first >= end) return;   /* as the two functions: nothing to do */
    const luz_draw_transform transform = luz_draw_transform_of(draw, view_projection);
    const float *model = transform.model.m, *normal_matrix = transform.normal_matrix.m;
    uint32_t i = first;
    /* Two loops, so that each inlined sixteen knows whether out is NULL. */
    if (out != NULL)
        for (; end - i >= 16; i += 16)
            sixteen(transform.vertices, model, normal_matrix, view_projection.m, i, width,
                    height, out, window, fixed);
    else
        for (; end - i >= 16; i += 16)
            sixteen(transform.vertices, model, normal_matrix, view_projection.m, i, width,
                    height, NULL, window, fixed);
    for (; i < end; i++) {   /* the last few, one at a time */
        const luz_clip_vertex vertex = luz_vertex_stage_one(&transform, i);
        const luz_window_vertex projected = luz_setup_project_vertex(&vertex, width, height);
        if (out != NULL) out[i] = vertex;
        if (window != NULL) window[i] = projected;
        if (fixed != NULL) fixed[i] = (luz_fixed_vertex){projected.fixed_x, projected.fixed_y};
    }
}
