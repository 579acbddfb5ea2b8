/*
 * setup_eight.c: the vertex stage of a triangle's corners and triangle
 * setup (vertex.c, then setup.c's luz_setup_project_vertex and
 * luz_setup_projected) for eight triangles at once, one per lane of
 * AVX-512 vectors.
 *
 * In:  eight triangles of a draw that screening let through (screen.c: so
 *      each is a front face whose box of up to 2 x 2 pixel centres has one
 *      covered), the draw's mesh and transforms (luz_draw_transform), and
 *      its vertices' snapped positions (with the markers) as
 *      luz_setup_project left them.
 * Out: for each lane, setup's result and, when VISIBLE, its record, the
 *      same bits luz_setup_projected(..., small_box_checked = true, ...)
 *      writes for the corners' clip vertices (luz_vertex_stage_one) and
 *      their projection; or, when one of the eight has a vertex outside a
 *      clip plane or not projected (the clipper's or setup's own
 *      business), all eight left to luz_setup_projected. For four samples
 *      a pixel, luz_setup_eight_four_avx512: the same as
 *      luz_setup_projected_samples(..., small_box_checked = true, 4, ...)
 *      for triangles luz_screen_triangles_four_avx512 let through.
 *
 * Why: on a mesh of a million triangles about a quarter reach setup, and
 * one at a time setup is arithmetic, not memory (set up twice in a row,
 * the second time from the cache, a triangle costs the same): some sixty
 * cycles of integer and double-precision work, which here runs eight
 * triangles to a vector (faster: docs/performance.md, "Measured in the
 * code").
 *
 * Position-only shading: with setup in lanes, a big draw's vertex pass
 * transforms positions alone and keeps only their snapped positions,
 * which screening reads (8 bytes a vertex); each corner that reaches
 * setup goes through the vertex stage and the projection again here,
 * from the mesh (as tile-based GPUs shade positions first and the rest
 * of a vertex only for triangles that survive culling: ARM Mali's
 * IDVS). That shades more corners than the mesh has vertices (the 1M
 * sphere: 750k corners of the 250k triangles that reach setup, against
 * 500k vertices), but the arithmetic is cheap beside the memory it
 * saves: the sphere's vertex pass wrote 60 bytes a vertex (its clip
 * vertex and snapped position; 100 with the window vertex, until setup
 * projected its corners itself) that setup read back scattered, where
 * now it writes 8 (faster: docs/performance.md, "Measured in the
 * code").
 *
 * The arithmetic is vertex.c's and setup.c's, operation for operation
 * (but where NaN normals, uv or matrix entries, which no check keeps
 * out, meet NaNs of another sign, the NaN that comes out may have the
 * other sign, as vertex_sixteen.c says):
 * the transforms in float, summed left to right, the projection in
 * double, the box and the edge functions in the same integers
 * (coordinates below 2^24, so 32 x 32 -> 64-bit products are exact), the
 * determinant, its reciprocal and each
 * plane (make_plane) in double with the same operations in the same order
 * and no fused multiply-add, each rounded to float as a C cast does
 * (round to nearest even). tests/test_setup_eight.c holds every lane to
 * luz_setup_projected, field by field, bit for bit.
 *
 * Instruction sets: src/renderer/meson.build compiles this file with
 * AVX-512 alone; without it the caller sets up one by one (cpu.c's
 * tables).
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

_Static_assert(LUZ_VARYING_COUNT == 8 && LUZ_VARYING_POSITION == 0 && LUZ_VARYING_NORMAL == 3 &&
                   LUZ_VARYING_UV == 6,
               "the varyings are world position, normal and uv: eight floats");
_Static_assert(sizeof(luz_vertex) == 8 * sizeof(float) && offsetof(luz_vertex, normal) == 12 &&
                   offsetof(luz_vertex, uv) == 24,
               "a mesh vertex is eight floats: position, normal, uv");
/* Gathers and the corner arrays take signed 32-bit indices. */
_Static_assert(LUZ_MESH_MAX_VERTICES <= (1u << 30), "vertex indices fit an int32");
_Static_assert(offsetof(luz_triangle, edges) == 16 && sizeof(luz_edge) == 16,
               "the box and the edges are the record's first 64 bytes");
_Static_assert(offsetof(luz_triangle, reference_x) == 64 &&
                   offsetof(luz_triangle, depth) == 72 &&
                   offsetof(luz_triangle, inverse_w) == 84 &&
                   offsetof(luz_triangle, varyings) == 96 &&
                   offsetof(luz_triangle, draw_index) == 192,
               "the reference point and the planes are 32 floats from byte 64");

/* The coefficients of the edge from (xi, yi) to (xj, yj), as make_edge:
 * a = dy, b = -dx, c = -(dy xi - dx yi), less 1 unless it is a top edge
 * (dy = 0, dx < 0) or a left edge (dy > 0). */
static inline __attribute__((always_inline)) void
make_edge_lanes(__m512i xi, __m512i yi, __m512i xj, __m512i yj, __m512i *a, __m512i *b, __m512i *c)
{
    const __m512i zero = _mm512_setzero_si512();
    const __m512i dx = _mm512_sub_epi64(xj, xi), dy = _mm512_sub_epi64(yj, yi);
    const __mmask8 top_or_left =
        (_mm512_cmpeq_epi64_mask(dy, zero) & _mm512_cmplt_epi64_mask(dx, zero)) |
        _mm512_cmpgt_epi64_mask(dy, zero);
    *a = dy;
    *b = _mm512_sub_epi64(zero, dx);
    const __m512i c0 = _mm512_sub_epi64(zero, _mm512_sub_epi64(_mm512_mul_epi32(dy, xi),
                                                               _mm512_mul_epi32(dx, yi)));
    *c = _mm512_mask_sub_epi64(c0, (__mmask8)~top_or_left, c0, _mm512_set1_epi64(1));
}

/* vertex.c's transform4 with w = 1, row r of a column-major 4 x 4: a[r]
 * x + a[4 + r] y + a[8 + r] z + a[12 + r], summed left to right in float
 * (a[12 + r] * 1.0f is a[12 + r] exactly)... */
static inline __attribute__((always_inline)) __m256
transform_row(const float *a, int r, __m256 x, __m256 y, __m256 z)
{
    return _mm256_add_ps(
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(a[r]), x),
                                    _mm256_mul_ps(_mm256_set1_ps(a[4 + r]), y)),
                      _mm256_mul_ps(_mm256_set1_ps(a[8 + r]), z)),
        _mm256_set1_ps(a[12 + r]));
}

/* ... and its transform3, row r of a column-major 3 x 3. */
static inline __attribute__((always_inline)) __m256
transform_row3(const float *a, int r, __m256 x, __m256 y, __m256 z)
{
    return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_set1_ps(a[r]), x),
                                       _mm256_mul_ps(_mm256_set1_ps(a[3 + r]), y)),
                         _mm256_mul_ps(_mm256_set1_ps(a[6 + r]), z));
}

/* make_plane for eight triangles: the plane through (x_k, y_k, value_k),
 * its value at (rx, ry) and its gradient, each rounded to float. The
 * edge vectors (x1 - x0, ...) are passed in, computed once as setup.c's
 * compiler does; the products are the same. */
typedef struct plane_eight {
    __m256 value, dx, dy;
} plane_eight;

static inline __attribute__((always_inline)) plane_eight
make_plane_eight(__m512d x10, __m512d x20, __m512d y10, __m512d y20, __m512d inverse_determinant,
                 __m512d rx0, __m512d ry0, __m512d value0, __m512d value1, __m512d value2)
{
    const __m512d d1 = _mm512_sub_pd(value1, value0), d2 = _mm512_sub_pd(value2, value0);
    const __m512d dx = _mm512_mul_pd(_mm512_sub_pd(_mm512_mul_pd(d1, y20), _mm512_mul_pd(d2, y10)),
                                     inverse_determinant);
    const __m512d dy = _mm512_mul_pd(_mm512_sub_pd(_mm512_mul_pd(d2, x10), _mm512_mul_pd(d1, x20)),
                                     inverse_determinant);
    const __m512d value = _mm512_add_pd(_mm512_add_pd(value0, _mm512_mul_pd(dx, rx0)),
                                        _mm512_mul_pd(dy, ry0));
    return (plane_eight){_mm512_cvtpd_ps(value), _mm512_cvtpd_ps(dx), _mm512_cvtpd_ps(dy)};
}

/* setup.c's covers_a_centre (covers_a_sample for `samples` samples a
 * pixel, luz_sample_offset_of) for the lanes of testing: the mask of
 * those whose box, (min_x, min_y) and box_width x box_height pixels, has a
 * sample where the three edges' E = a X + b Y + c >= 0. The pixels are
 * visited in every lane at once, column by column and row by row from
 * each box's corner, until each lane tested has found one or run out.
 * E at each sample of the box's first pixel is worked out once (|a|, |b| <
 * 2^26 and samples below 2^23: each product fits 32 x 32 -> 64 bits, as
 * setup.c's proof has it); a pixel's is that plus 256 a its column and
 * 256 b its row, which the edge's two terms keep, the same for every
 * sample (exact: each |E| below 2^52). The three edges' E are or-ed, so
 * one sign test a sample says whether all three pass. */
static inline __attribute__((always_inline)) __mmask8
covered_lanes(__mmask8 testing, __m512i min_x, __m512i min_y, __m512i box_width,
              __m512i box_height, const __m512i a[3], const __m512i b[3], const __m512i c[3],
              int samples)
{
    const __m512i one = _mm512_set1_epi64(1), zero = _mm512_setzero_si512();
    const __m512i centres = _mm512_mullo_epi64(box_width, box_height);
    const __m512i corner_x = _mm512_slli_epi64(min_x, LUZ_SUBPIXEL_BITS);
    const __m512i corner_y = _mm512_slli_epi64(min_y, LUZ_SUBPIXEL_BITS);
    __m512i first[LUZ_MAX_SAMPLES][3], step_x[3], step_y[3], column_term[3], row_term[3];
    for (int s = 0; s < samples; s++) {
        const luz_sample_offset offset = luz_sample_offset_of(samples, s);
        const __m512i sample_x = _mm512_add_epi64(corner_x, _mm512_set1_epi64(offset.x));
        const __m512i sample_y = _mm512_add_epi64(corner_y, _mm512_set1_epi64(offset.y));
        for (int k = 0; k < 3; k++)
            first[s][k] = _mm512_add_epi64(_mm512_add_epi64(_mm512_mul_epi32(a[k], sample_x),
                                                            _mm512_mul_epi32(b[k], sample_y)),
                                           c[k]);
    }
    for (int k = 0; k < 3; k++) {
        step_x[k] = _mm512_slli_epi64(a[k], LUZ_SUBPIXEL_BITS);
        step_y[k] = _mm512_slli_epi64(b[k], LUZ_SUBPIXEL_BITS);
        column_term[k] = zero;
        row_term[k] = zero;
    }
    __m512i column = zero, visited = zero;
    __mmask8 covered = 0, left = testing;
    while (left != 0) {
        __m512i offset[3];
        for (int k = 0; k < 3; k++) offset[k] = _mm512_add_epi64(column_term[k], row_term[k]);
        __mmask8 inside_any = 0;
        for (int s = 0; s < samples; s++) {
            const __m512i any = _mm512_or_si512(
                _mm512_or_si512(_mm512_add_epi64(first[s][0], offset[0]),
                                _mm512_add_epi64(first[s][1], offset[1])),
                _mm512_add_epi64(first[s][2], offset[2]));
            inside_any |= _mm512_cmpge_epi64_mask(any, zero);
        }
        inside_any &= left;
        covered |= inside_any;
        visited = _mm512_add_epi64(visited, one);
        left &= (__mmask8)~inside_any & _mm512_cmplt_epi64_mask(visited, centres);
        column = _mm512_add_epi64(column, one);
        const __mmask8 wrap = _mm512_cmpeq_epi64_mask(column, box_width);
        column = _mm512_mask_mov_epi64(column, wrap, zero);
        for (int k = 0; k < 3; k++) {
            column_term[k] = _mm512_mask_mov_epi64(_mm512_add_epi64(column_term[k], step_x[k]),
                                                   wrap, zero);
            row_term[k] = _mm512_mask_add_epi64(row_term[k], wrap, row_term[k], step_y[k]);
        }
    }
    return covered;
}

/* setup.c's narrow_to_one_centre for the lanes of `lanes` (boxes of up to
 * 2 x 2 pixels, one sample a pixel): where the three edges pass at one of
 * the box's centres alone, the box becomes that pixel. E at the box's
 * first centre, then 256 a and 256 b on (exact: each |E| below 2^52, as
 * setup.c's proof has it). */
static inline __attribute__((always_inline)) void
narrow_lanes(__mmask8 lanes, __m512i box_width, __m512i box_height, const __m512i a[3],
             const __m512i b[3], const __m512i c[3], __m512i *min_x, __m512i *min_y,
             __m512i *max_x, __m512i *max_y)
{
    const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi64(1);
    const __m512i two = _mm512_set1_epi64(2), half = _mm512_set1_epi64(LUZ_SUBPIXEL_ONE / 2);
    const __m512i centre_x = _mm512_add_epi64(_mm512_slli_epi64(*min_x, LUZ_SUBPIXEL_BITS), half);
    const __m512i centre_y = _mm512_add_epi64(_mm512_slli_epi64(*min_y, LUZ_SUBPIXEL_BITS), half);
    const __mmask8 wide = _mm512_cmpeq_epi64_mask(box_width, two);
    const __mmask8 tall = _mm512_cmpeq_epi64_mask(box_height, two);
    /* The three edges' E or-ed at each centre: negative where one is. */
    __m512i any[4] = {zero, zero, zero, zero};
    for (int k = 0; k < 3; k++) {
        const __m512i e00 = _mm512_add_epi64(_mm512_add_epi64(_mm512_mul_epi32(a[k], centre_x),
                                                              _mm512_mul_epi32(b[k], centre_y)),
                                             c[k]);
        const __m512i step_x = _mm512_slli_epi64(a[k], LUZ_SUBPIXEL_BITS);
        const __m512i step_y = _mm512_slli_epi64(b[k], LUZ_SUBPIXEL_BITS);
        const __m512i e10 = _mm512_add_epi64(e00, step_x);
        any[0] = _mm512_or_si512(any[0], e00);
        any[1] = _mm512_or_si512(any[1], e10);
        any[2] = _mm512_or_si512(any[2], _mm512_add_epi64(e00, step_y));
        any[3] = _mm512_or_si512(any[3], _mm512_add_epi64(e10, step_y));
    }
    /* Whether each of the four centres is in the box and inside. */
    const __mmask8 at00 = lanes & _mm512_cmpge_epi64_mask(any[0], zero);
    const __mmask8 at10 = lanes & wide & _mm512_cmpge_epi64_mask(any[1], zero);
    const __mmask8 at01 = lanes & tall & _mm512_cmpge_epi64_mask(any[2], zero);
    const __mmask8 at11 = lanes & wide & tall & _mm512_cmpge_epi64_mask(any[3], zero);
    const __mmask8 two_or_more = (at00 & (at10 | at01 | at11)) | (at10 & (at01 | at11)) |
                                 (at01 & at11);
    const __mmask8 only = (at00 | at10 | at01 | at11) & (__mmask8)~two_or_more;
    *min_x = _mm512_mask_add_epi64(*min_x, only & (at10 | at11), *min_x, one);
    *min_y = _mm512_mask_add_epi64(*min_y, only & (at01 | at11), *min_y, one);
    *max_x = _mm512_mask_mov_epi64(*max_x, only, *min_x);
    *max_y = _mm512_mask_mov_epi64(*max_y, only, *min_y);
}

/* Setup in lanes for pixels of `samples` samples, 1 or 4 (a constant in
 * each of the two functions below): the box and the small boxes' test are
 * the samples' (luz_setup_projected_samples). */
static inline __attribute__((always_inline)) bool
setup_eight(const uint32_t *indices, const uint32_t triangles[8],
            const luz_draw_transform *transform, const luz_fixed_vertex *fixed, int width,
            int height, uint32_t draw_index, luz_interpolation interpolation, int samples,
            luz_triangle out[8], luz_setup_result result[8])
{
    /* The corners' vertex indices, a lane per triangle: gathered
     * (3 t + k < 3 * 2^28 fits an int32), where eight indices stored one
     * by one and loaded as a vector waited for the stores to retire. */
    const __m256i first_index = _mm256_mullo_epi32(
        _mm256_loadu_si256((const void *)triangles), _mm256_set1_epi32(3));
    const __m256i vertex0 = _mm256_i32gather_epi32((const int *)indices, first_index, 4);
    const __m256i vertex1 = _mm256_i32gather_epi32((const int *)indices + 1, first_index, 4);
    const __m256i vertex2 = _mm256_i32gather_epi32((const int *)indices + 2, first_index, 4);
    int32_t corner[3][8];
    _mm256_storeu_si256((void *)corner[0], vertex0);
    _mm256_storeu_si256((void *)corner[1], vertex1);
    _mm256_storeu_si256((void *)corner[2], vertex2);

    /* 3. The doubled area in fixed point, as luz_setup_front_facing; a
     * marked vertex (below -2^24) leaves the eight to the caller. */
    __m512i fx0, fy0, fx1, fy1, fx2, fy2;
    luz_gather_fixed(vertex0, fixed, &fx0, &fy0);
    luz_gather_fixed(vertex1, fixed, &fx1, &fy1);
    luz_gather_fixed(vertex2, fixed, &fx2, &fy2);
    const __m512i lowest = _mm512_set1_epi64(-((int64_t)1 << 24));
    const __mmask8 marked = _mm512_cmplt_epi64_mask(fx0, lowest) |
                            _mm512_cmplt_epi64_mask(fx1, lowest) |
                            _mm512_cmplt_epi64_mask(fx2, lowest);
    /* Marked vertices come in runs (a draw across a clip plane, whose back
     * faces screening cannot judge either): such a group is left whole. */
    if (marked != 0) return true;
    const __mmask8 back = _mm512_cmple_epi64_mask(
        luz_doubled_area_lanes(fx0, fy0, fx1, fy1, fx2, fy2), _mm512_setzero_si512());

    /* The box of the pixels whose samples (one: the centre) may be
     * inside, as setup's. */
    __m512i min_x, min_y, max_x, max_y;
    luz_sample_box_lanes(fx0, fy0, fx1, fy1, fx2, fy2, width, height, samples, &min_x, &min_y,
                         &max_x, &max_y);
    const __mmask8 empty = _mm512_cmpgt_epi64_mask(min_x, max_x) |
                           _mm512_cmpgt_epi64_mask(min_y, max_y);
    /* A box of up to LUZ_SETUP_SMALL_BOX_PIXELS but more than 2 x 2:
     * its centres are tested below (covered_lanes). */
    const __m512i one = _mm512_set1_epi64(1);
    const __m512i box_width = _mm512_add_epi64(_mm512_sub_epi64(max_x, min_x), one);
    const __m512i box_height = _mm512_add_epi64(_mm512_sub_epi64(max_y, min_y), one);
    const __m512i two = _mm512_set1_epi64(2);
    const __mmask8 small = _mm512_cmple_epi64_mask(_mm512_mullo_epi64(box_width, box_height),
                                                   _mm512_set1_epi64(LUZ_SETUP_SMALL_BOX_PIXELS));
    const __mmask8 up_to_2x2 = _mm512_cmple_epi64_mask(box_width, two) &
                               _mm512_cmple_epi64_mask(box_height, two);
    const __mmask8 to_test = (__mmask8)(~back & ~empty & small & ~up_to_2x2);

    /* 4. Edge k is opposite vertex k. */
    __m512i a[3], b[3], c[3];
    make_edge_lanes(fx1, fy1, fx2, fy2, &a[0], &b[0], &c[0]);
    make_edge_lanes(fx2, fy2, fx0, fy0, &a[1], &b[1], &c[1]);
    make_edge_lanes(fx0, fy0, fx1, fy1, &a[2], &b[2], &c[2]);

    /* The vertex stage and steps 1-2 again, then 5. Planes, from the
     * exact window positions, relative to the snapped vertex 0 (setup.c).
     * Each corner's mesh vertex is 32 contiguous bytes: loaded a lane at
     * a time and transposed into vectors (when setup read window and clip
     * vertices, a gather for each field instead made the 1M sphere's
     * geometry slower than one triangle at a time, the loads and
     * transposes faster: docs/performance.md, "Measured in the code"). */
    __m512d x[3], y[3], depth[3], weight[3];
    __m256 varying[3][8];
    const float *model = transform->model.m, *normal_matrix = transform->normal_matrix.m;
    const float *view_projection = transform->view_projection.m;
    for (int k = 0; k < 3; k++) {
        /* Each corner's mesh vertex, eight floats (position, normal, uv),
         * transposed into lanes. */
        __m256 in[8];
        for (int lane = 0; lane < 8; lane++)
            in[lane] = _mm256_loadu_ps(&transform->vertices[corner[k][lane]].position.x);
        luz_transpose8(in);
        /* vertex.c: world = model p, normal = N n, clip = VP world; the
         * varyings are world, normal and uv. */
        const __m256 world_x = transform_row(model, 0, in[0], in[1], in[2]);
        const __m256 world_y = transform_row(model, 1, in[0], in[1], in[2]);
        const __m256 world_z = transform_row(model, 2, in[0], in[1], in[2]);
        varying[k][LUZ_VARYING_POSITION + 0] = world_x;
        varying[k][LUZ_VARYING_POSITION + 1] = world_y;
        varying[k][LUZ_VARYING_POSITION + 2] = world_z;
        for (int r = 0; r < 3; r++)
            varying[k][LUZ_VARYING_NORMAL + r] =
                transform_row3(normal_matrix, r, in[3], in[4], in[5]);
        varying[k][LUZ_VARYING_UV + 0] = in[6];
        varying[k][LUZ_VARYING_UV + 1] = in[7];
        /* setup.c: divide, viewport (the snap is fixed's, read above). */
        const luz_window_lanes projected = luz_project_lanes(
            _mm512_cvtps_pd(transform_row(view_projection, 0, world_x, world_y, world_z)),
            _mm512_cvtps_pd(transform_row(view_projection, 1, world_x, world_y, world_z)),
            _mm512_cvtps_pd(transform_row(view_projection, 2, world_x, world_y, world_z)),
            _mm512_cvtps_pd(transform_row(view_projection, 3, world_x, world_y, world_z)),
            width, height);
        x[k] = projected.x;
        y[k] = projected.y;
        depth[k] = projected.depth;
        weight[k] = interpolation == LUZ_INTERPOLATION_AFFINE ? _mm512_set1_pd(1.0)
                                                               : projected.inverse_w;
    }
    const __m512d x10 = _mm512_sub_pd(x[1], x[0]), x20 = _mm512_sub_pd(x[2], x[0]);
    const __m512d y10 = _mm512_sub_pd(y[1], y[0]), y20 = _mm512_sub_pd(y[2], y[0]);
    const __m512d determinant = _mm512_sub_pd(_mm512_mul_pd(x10, y20), _mm512_mul_pd(x20, y10));
    /* setup.c: !(determinant != 0.0) || !isfinite(determinant) culls. */
    const __mmask8 solvable =
        _mm512_cmp_pd_mask(determinant, _mm512_setzero_pd(), _CMP_NEQ_OQ) &
        _mm512_cmp_pd_mask(_mm512_abs_pd(determinant), _mm512_set1_pd(INFINITY),
                           _CMP_LT_OQ);
    const __m512d inverse_determinant = _mm512_div_pd(_mm512_set1_pd(1.0), determinant);
    /* fixed / 256: exact, a power of two. */
    const __m512d rx = _mm512_div_pd(_mm512_cvtepi64_pd(fx0), _mm512_set1_pd(LUZ_SUBPIXEL_ONE));
    const __m512d ry = _mm512_div_pd(_mm512_cvtepi64_pd(fy0), _mm512_set1_pd(LUZ_SUBPIXEL_ONE));
    const __m512d rx0 = _mm512_sub_pd(rx, x[0]), ry0 = _mm512_sub_pd(ry, y[0]);

    /* The record's floats from byte 64: the reference point, then depth,
     * 1/w and each varying/w as (value, dx, dy); column j holds float j of
     * every lane. */
    __m256 column[32];
    column[0] = _mm512_cvtpd_ps(rx);
    column[1] = _mm512_cvtpd_ps(ry);
    plane_eight plane = make_plane_eight(x10, x20, y10, y20, inverse_determinant, rx0, ry0,
                                         depth[0], depth[1], depth[2]);
    column[2] = plane.value, column[3] = plane.dx, column[4] = plane.dy;
    plane = make_plane_eight(x10, x20, y10, y20, inverse_determinant, rx0, ry0, weight[0],
                             weight[1], weight[2]);
    column[5] = plane.value, column[6] = plane.dx, column[7] = plane.dy;
    for (int i = 0; i < LUZ_VARYING_COUNT; i++) {
        __m512d value[3];
        for (int k = 0; k < 3; k++)
            value[k] = _mm512_mul_pd(_mm512_cvtps_pd(varying[k][i]), weight[k]);
        plane = make_plane_eight(x10, x20, y10, y20, inverse_determinant, rx0, ry0, value[0],
                                 value[1], value[2]);
        column[8 + 3 * i] = plane.value;
        column[9 + 3 * i] = plane.dx;
        column[10 + 3 * i] = plane.dy;
    }

    /* A small box with one centre covered becomes that pixel (setup.c's
     * narrow_to_one_centre); after the verdicts' box sizes, which are
     * the box's before. */
    if (samples == 1)
        narrow_lanes((__mmask8)(~back & ~empty & up_to_2x2), box_width, box_height, a, b, c,
                     &min_x, &min_y, &max_x, &max_y);

    /* The box and edges as sixteen 32-bit words a lane: min x, min y,
     * max x, max y, then a, b and c (low, high) of each edge. */
    __m256 word[16];
    word[0] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(min_x));
    word[1] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(min_y));
    word[2] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(max_x));
    word[3] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(max_y));
    for (int k = 0; k < 3; k++) {
        word[4 + 4 * k] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(a[k]));
        word[5 + 4 * k] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(b[k]));
        word[6 + 4 * k] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(c[k]));
        word[7 + 4 * k] = _mm256_castsi256_ps(_mm512_cvtepi64_epi32(_mm512_srai_epi64(c[k], 32)));
    }
    /* Transposed, a lane's words are its record's bytes 0-63 and 64-191. */
    luz_transpose8(&word[0]);
    luz_transpose8(&word[8]);
    for (int q = 0; q < 4; q++) luz_transpose8(&column[8 * q]);
    for (int lane = 0; lane < 8; lane++) {
        float *record = (float *)(void *)&out[lane];
        _mm256_storeu_ps(record, word[lane]);
        _mm256_storeu_ps(record + 8, word[8 + lane]);
        for (int q = 0; q < 4; q++) _mm256_storeu_ps(record + 16 + 8 * q, column[8 * q + lane]);
        out[lane].draw_index = draw_index;
    }

    /* Each lane's verdict in setup's order: culled (a back face), off
     * screen (no centre in the box, or in a box of 3 to 16 centres none
     * covered), then culled again (no plane can be solved). */
    const unsigned offscreen =
        empty | (to_test &
                 ~covered_lanes(to_test, min_x, min_y, box_width, box_height, a, b, c, samples));
    for (int lane = 0; lane < 8; lane++) {
        const unsigned bit = 1u << lane;
        result[lane] = (back & bit)        ? LUZ_SETUP_CULLED
                       : (offscreen & bit) ? LUZ_SETUP_OFFSCREEN
                       : (solvable & bit)  ? LUZ_SETUP_VISIBLE
                                           : LUZ_SETUP_CULLED;
    }
    return false;
}

luz_setup_eight_function luz_setup_eight_avx512, luz_setup_eight_four_avx512;

bool luz_setup_eight_avx512(const uint32_t *indices, const uint32_t triangles[8],
                            const luz_draw_transform *transform,
                            const luz_fixed_vertex *fixed, int width, int height,
                            uint32_t draw_index, luz_interpolation interpolation,
                            luz_triangle out[8], luz_setup_result result[8])
{
    return setup_eight(indices, triangles, transform, fixed, width, height, draw_index,
                       interpolation, 1, out, result);
}

/* The same for four samples a pixel: luz_setup_projected_samples(..., 4,
 * ...) for triangles luz_screen_triangles_four_avx512 let through. */
bool luz_setup_eight_four_avx512(const uint32_t *indices, const uint32_t triangles[8],
                                 const luz_draw_transform *transform,
                                 const luz_fixed_vertex *fixed, int width, int height,
                                 uint32_t draw_index, luz_interpolation interpolation,
                                 luz_triangle out[8], luz_setup_result result[8])
{
    return setup_eight(indices, triangles, transform, fixed, width, height, draw_index,
                       interpolation, 4, out, result);
}
