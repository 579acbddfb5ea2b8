/*
 * setup_lanes.c: setup in lanes (setup_eight.c's job: the vertex stage of
 * eight triangles' corners, their projection and setup.c's
 * luz_setup_projected, one triangle a lane) written once on lanes.h's
 * portable vectors, for the instruction sets without AVX-512: the eight
 * triangles in one step of 8 float lanes with AVX2, two of 4 with SSE2
 * and NEON.
 *
 * In, out and the arithmetic: setup_eight.c's (see there, and setup.c),
 * operation for operation: the transforms in float, summed left to right;
 * the projection, the determinant, its reciprocal and each plane in
 * double, each rounded to float as a C cast does; the box in 32-bit
 * lanes, the doubled area, the edges' constants and the small boxes'
 * centres in 64-bit lanes, every 32 x 32-bit product exact (the area and
 * the centres in 32-bit lanes where a group's corners are near each
 * other and every value fits: NEAR_EXTENT). No fused
 * multiply-add (-ffp-contract=off). tests/test_setup_eight.c holds every
 * variant's lanes to luz_setup_projected, field by field, bit for bit.
 * The AVX-512 variant stays setup_eight.c's, in intrinsics.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "renderer/pipeline.h"

#if defined(LUZ_LANES_AVX2)
#define LANES 8
#define SETUP_LANES luz_setup_eight_avx2
#define SETUP_LANES_FOUR luz_setup_eight_four_avx2
#elif defined(LUZ_LANES_NEON)
#define LANES 4
#define SETUP_LANES luz_setup_eight_neon
#define SETUP_LANES_FOUR luz_setup_eight_four_neon
#elif defined(LUZ_LANES_SSE2)
#define LANES 4
#define SETUP_LANES luz_setup_eight_sse2
#define SETUP_LANES_FOUR luz_setup_eight_four_sse2
#else
#error "setup_lanes.c is compiled for one instruction set: -DLUZ_LANES_AVX2, ..."
#endif

#include "renderer/lanes.h"

#define STEP 8                  /* triangles a call (luz_setup_eight_function) */
#define GROUPS (STEP / LANES)   /* steps of LANES lanes a call */

_Static_assert(LUZ_VARYING_COUNT == 8 && LUZ_VARYING_POSITION == 0 && LUZ_VARYING_NORMAL == 3 &&
                   LUZ_VARYING_UV == 6,
               "the varyings are world position, normal and uv: eight floats");
_Static_assert(sizeof(luz_vertex) == 8 * sizeof(float) && offsetof(luz_vertex, normal) == 12 &&
                   offsetof(luz_vertex, uv) == 24,
               "a mesh vertex is eight floats: position, normal, uv");
_Static_assert(LUZ_MESH_MAX_VERTICES <= (1u << 30), "vertex indices fit an int32");
_Static_assert(offsetof(luz_triangle, edges) == 16 && sizeof(luz_edge) == 16,
               "the box and the edges are the record's first 64 bytes");
_Static_assert(offsetof(luz_triangle, reference_x) == 64 &&
                   offsetof(luz_triangle, depth) == 72 &&
                   offsetof(luz_triangle, inverse_w) == 84 &&
                   offsetof(luz_triangle, varyings) == 96 &&
                   offsetof(luz_triangle, draw_index) == 192,
               "the reference point and the planes are 32 floats from byte 64");

/* Half h of 32-bit lanes as doubles (exact; from the 32-bit values, which
 * every instruction set converts in lanes). */
LANES_INLINE vf64 double_half(vi32 v, int h)
{
#if LANES == 8 && defined(__AVX2__)
    /* One vcvtdq2pd of the half (lanes.h's widen_half says why). */
    return (vf64)_mm256_cvtepi32_pd(h == 0 ? _mm256_castsi256_si128((__m256i)v)
                                           : _mm256_extracti128_si256((__m256i)v, 1));
#else
    typedef int32_t half_ints __attribute__((vector_size(HALF * sizeof(int32_t))));
    half_ints part;
    memcpy(&part, (const int32_t *)&v + h * HALF, sizeof part);
    return __builtin_convertvector(part, vf64);
#endif
}

/* vertex.c's transform4 with w = 1, row r of a column-major 4 x 4: a[r] x
 * + a[4 + r] y + a[8 + r] z + a[12 + r], summed left to right in float
 * (a[12 + r] * 1.0f is a[12 + r] exactly)... */
LANES_INLINE vf32 transform_row(const float *a, int r, vf32 x, vf32 y, vf32 z)
{
    return ((a[r] * x + a[4 + r] * y) + a[8 + r] * z) + a[12 + r];
}

/* ... and its transform3, row r of a column-major 3 x 3. */
LANES_INLINE vf32 transform_row3(const float *a, int r, vf32 x, vf32 y, vf32 z)
{
    return (a[r] * x + a[3 + r] * y) + a[6 + r] * z;
}

/* make_plane for half a step: the plane through (x_k, y_k, value_k), its
 * value at (rx, ry) and its gradient (before rounding to float). */
LANES_INLINE void make_plane_half(vf64 x10, vf64 x20, vf64 y10, vf64 y20,
                                  vf64 inverse_determinant, vf64 rx0, vf64 ry0, vf64 value0,
                                  vf64 value1, vf64 value2, vf64 out[3])
{
    const vf64 d1 = value1 - value0, d2 = value2 - value0;
    const vf64 dx = (d1 * y20 - d2 * y10) * inverse_determinant;
    const vf64 dy = (d2 * x10 - d1 * x20) * inverse_determinant;
    out[0] = (value0 + dx * rx0) + dy * ry0;
    out[1] = dx;
    out[2] = dy;
}

/* setup.c's covers_a_centre (covers_a_sample for `samples` samples a
 * pixel, luz_sample_offset_of) for the lanes of half h in testing: those
 * whose box, (min_x, min_y) and box_width x box_height pixels, has a
 * sample where the three edges' E = a X + b Y + c >= 0. E at each sample
 * of the box's first pixel is worked out once (|a|, |b| < 2^26, samples
 * below 2^23: each product exact in 64 bits); a pixel's is that plus
 * 256 a its column and 256 b its row, which the edge's two terms keep,
 * the same for every sample (exact: each |E| below 2^52). The three
 * edges' E are or-ed, so one sign a sample says whether all three pass. */
LANES_INLINE unsigned covered_half(unsigned testing, vi64 min_x, vi64 min_y, vi64 box_width,
                                   vi64 box_height, const vi64 a[3], const vi64 b[3],
                                   const vi64 c[3], int samples)
{
    const vi64 centres = multiply_wide(box_width, box_height);   /* at most 16 */
    const vi64 corner_x = min_x << LUZ_SUBPIXEL_BITS, corner_y = min_y << LUZ_SUBPIXEL_BITS;
    vi64 first[LUZ_MAX_SAMPLES][3], step_x[3], step_y[3], column_term[3], row_term[3];
    for (int s = 0; s < samples; s++) {
        const luz_sample_offset offset = luz_sample_offset_of(samples, s);
        const vi64 sample_x = corner_x + offset.x, sample_y = corner_y + offset.y;
        for (int k = 0; k < 3; k++)
            first[s][k] = multiply_wide(a[k], sample_x) + multiply_wide(b[k], sample_y) + c[k];
    }
    for (int k = 0; k < 3; k++) {
        step_x[k] = multiply_wide(a[k], splat64(LUZ_SUBPIXEL_ONE));
        step_y[k] = multiply_wide(b[k], splat64(LUZ_SUBPIXEL_ONE));
        column_term[k] = splat64(0);
        row_term[k] = splat64(0);
    }
    vi64 column = splat64(0), visited = splat64(0);
    unsigned covered = 0, left = testing;
    while (left != 0) {
        vi64 offset[3];
        for (int k = 0; k < 3; k++) offset[k] = column_term[k] + row_term[k];
        unsigned inside_any = 0;
        for (int s = 0; s < samples; s++)
            inside_any |= ~negative_bits64((first[s][0] + offset[0]) | (first[s][1] + offset[1]) |
                                           (first[s][2] + offset[2]));
        const unsigned inside = inside_any & left;
        covered |= inside;
        visited += 1;
        left &= ~inside & negative_bits64(visited - centres);
        column += 1;
        /* column == box_width, where column runs from 0 up to it (in the
         * lanes tested; the others' are never read). */
        const vi64 wrap = ~negative_mask64(column - box_width);
        column = select64(wrap, splat64(0), column);
        for (int k = 0; k < 3; k++) {
            column_term[k] = select64(wrap, splat64(0), column_term[k] + step_x[k]);
            row_term[k] += wrap & step_y[k];   /* wrap is -1 where a row ends */
        }
    }
    return covered;
}

/* For setup.c's narrow_to_one_centre, half h's lanes' four centres of a
 * box of up to 2 x 2 pixels from (min_x, min_y): bits where the three
 * edges pass at the first centre, the one to its right, the one below,
 * and the one below and right (inside[0..3]). E at the first centre,
 * then 256 a and 256 b on (exact: each |E| below 2^52, setup.c). */
LANES_INLINE void centres_inside_half(vi64 min_x, vi64 min_y, const vi64 a[3], const vi64 b[3],
                                      const vi64 c[3], unsigned inside[4])
{
    const vi64 centre_x = (min_x << LUZ_SUBPIXEL_BITS) + LUZ_SUBPIXEL_ONE / 2;
    const vi64 centre_y = (min_y << LUZ_SUBPIXEL_BITS) + LUZ_SUBPIXEL_ONE / 2;
    /* The three edges' E or-ed: negative where one of them is. */
    vi64 any[4] = {splat64(0), splat64(0), splat64(0), splat64(0)};
    for (int k = 0; k < 3; k++) {
        const vi64 e00 = multiply_wide(a[k], centre_x) + multiply_wide(b[k], centre_y) + c[k];
        const vi64 step_x = a[k] << LUZ_SUBPIXEL_BITS, step_y = b[k] << LUZ_SUBPIXEL_BITS;
        any[0] |= e00;
        any[1] |= e00 + step_x;
        any[2] |= e00 + step_y;
        any[3] |= e00 + step_x + step_y;
    }
    for (int i = 0; i < 4; i++) inside[i] = ~negative_bits64(any[i]) & ((1u << HALF) - 1);
}

/* Where every lane's corners lie within NEAR_EXTENT subpixels (16
 * pixels) of each other in x and in y, the edge functions at the
 * centres of a box that is not empty fit 32 bits, taken from an edge's
 * first vertex: E = a X + b Y + c = a (X - xi) + b (Y - yi) - bias
 * (c = -(a xi + b yi) - bias, step 4). |a|, |b| < 2^12, and the box's
 * centres lie between the corners' least and greatest X (and Y): it is
 * the box of the pixels whose centre may be inside. So |X - xi| and
 * |Y - yi| < 2^12 + 2^8 even at the centre one pixel on, each product is
 * below 2^25 and E below 2^26; the doubled area's products are below
 * 2^24. In such groups (every group of the 1M sphere but a few) the
 * centres' tests take all LANES lanes in one step of 32-bit lanes
 * instead of two halves of 64-bit ones. Lanes whose box is empty can
 * hold anything: their values wrap (unsigned) and are never read. */
#define NEAR_EXTENT (1 << 12)

/* E of edge k at (x, y), 32-bit (see NEAR_EXTENT): not_top_left is -1
 * where the edge is neither top nor left (bias 1), 0 where it is. */
LANES_INLINE vi32 edge_near(vi32 a, vi32 b, vi32 not_top_left, vi32 from_x, vi32 from_y, vi32 x,
                            vi32 y)
{
    return (vi32)((vu32)a * (vu32)(x - from_x) + (vu32)b * (vu32)(y - from_y) +
                  (vu32)not_top_left);
}

/* covered_half's test in one step of 32-bit lanes, one sample a pixel
 * (its centre), for the lanes of testing. */
LANES_INLINE unsigned covered_near(unsigned testing, vi32 min_x, vi32 min_y, vi32 box_width,
                                   vi32 box_pixels, const vi32 a[3], const vi32 b[3],
                                   const vi32 not_top_left[3], const vi32 from_x[3],
                                   const vi32 from_y[3])
{
    vi32 column = splat32(0), row = splat32(0), visited = splat32(0);
    unsigned covered = 0, left = testing;
    while (left != 0) {
        const vi32 centre_x = ((min_x + column) << LUZ_SUBPIXEL_BITS) + LUZ_SUBPIXEL_ONE / 2;
        const vi32 centre_y = ((min_y + row) << LUZ_SUBPIXEL_BITS) + LUZ_SUBPIXEL_ONE / 2;
        vi32 any = splat32(0);
        for (int k = 0; k < 3; k++)
            any |= edge_near(a[k], b[k], not_top_left[k], from_x[k], from_y[k], centre_x,
                             centre_y);
        const unsigned inside = left & ~lane_bits(any < 0);
        covered |= inside;
        visited += 1;
        left &= ~inside & lane_bits(visited < box_pixels);   /* at most 16 where tested */
        column += 1;
        const vi32 wrap = column == box_width;
        column = select32(wrap, splat32(0), column);
        row -= wrap;   /* wrap is -1 where a row ends */
    }
    return covered;
}

/* centres_inside_half's four centres in one step of 32-bit lanes. */
LANES_INLINE void centres_inside_near(vi32 min_x, vi32 min_y, const vi32 a[3], const vi32 b[3],
                                      const vi32 not_top_left[3], const vi32 from_x[3],
                                      const vi32 from_y[3], unsigned inside[4])
{
    const vi32 centre_x = (min_x << LUZ_SUBPIXEL_BITS) + LUZ_SUBPIXEL_ONE / 2;
    const vi32 centre_y = (min_y << LUZ_SUBPIXEL_BITS) + LUZ_SUBPIXEL_ONE / 2;
    vi32 any[4] = {splat32(0), splat32(0), splat32(0), splat32(0)};
    for (int k = 0; k < 3; k++) {
        const vi32 e00 =
            edge_near(a[k], b[k], not_top_left[k], from_x[k], from_y[k], centre_x, centre_y);
        const vi32 step_x = (vi32)((vu32)a[k] << LUZ_SUBPIXEL_BITS);
        const vi32 step_y = (vi32)((vu32)b[k] << LUZ_SUBPIXEL_BITS);
        const vi32 e10 = (vi32)((vu32)e00 + (vu32)step_x);
        any[0] |= e00;
        any[1] |= e10;
        any[2] |= (vi32)((vu32)e00 + (vu32)step_y);
        any[3] |= (vi32)((vu32)e10 + (vu32)step_y);
    }
    for (int i = 0; i < 4; i++) inside[i] = ~lane_bits(any[i] < 0) & ((1u << LANES) - 1);
}

/* The corners' vertex indices (corner[k]) and snapped positions of a
 * group of LANES triangles. */
typedef struct group_corners {
    vi32 vertex[3];
    vi32 x[3], y[3];
} group_corners;

/* Sets up the group of LANES triangles (corners as gathered), into out
 * and result. */
LANES_INLINE void setup_group(const group_corners *corners, const luz_draw_transform *transform,
                              int width, int height, uint32_t draw_index,
                              luz_interpolation interpolation, int samples,
                              luz_triangle out[LANES], luz_setup_result result[LANES])
{
    const vi32 *fx = corners->x, *fy = corners->y;

    /* The box of the pixels whose samples (one: the centre) may be
     * inside, as setup's (screen_lanes.c). */
    const vi32 low = splat32(luz_sample_reach_low(samples));
    const vi32 high = splat32(luz_sample_reach_high(samples)), zero = splat32(0);
    const vi32 lowest_x = min32(fx[0], min32(fx[1], fx[2]));
    const vi32 lowest_y = min32(fy[0], min32(fy[1], fy[2]));
    const vi32 highest_x = max32(fx[0], max32(fx[1], fx[2]));
    const vi32 highest_y = max32(fy[0], max32(fy[1], fy[2]));
    const vi32 min_x = max32(-((high - lowest_x) >> LUZ_SUBPIXEL_BITS), zero);
    const vi32 min_y = max32(-((high - lowest_y) >> LUZ_SUBPIXEL_BITS), zero);
    const vi32 max_x = min32((highest_x - low) >> LUZ_SUBPIXEL_BITS, splat32(width - 1));
    const vi32 max_y = min32((highest_y - low) >> LUZ_SUBPIXEL_BITS, splat32(height - 1));
    const unsigned empty = lane_bits((min_x > max_x) | (min_y > max_y));
    /* A box of up to LUZ_SETUP_SMALL_BOX_PIXELS but more than 2 x 2: its
     * centres are tested (covered_half). (An empty box's sizes may be 0
     * or negative; it is OFFSCREEN whatever they are.) */
    const vi32 box_width = max_x - min_x + 1, box_height = max_y - min_y + 1;
    /* (Multiplied as unsigned: an empty box's sizes may be anything, and
     * its product wrap; a box that is not empty has at most 2^28 pixels.) */
    const vi32 box_pixels = (vi32)((vu32)box_width * (vu32)box_height);
    const unsigned small = lane_bits(box_pixels <= LUZ_SETUP_SMALL_BOX_PIXELS);
    const unsigned up_to_2x2 = lane_bits((box_width <= 2) & (box_height <= 2));

    /* 4. Edge k is opposite vertex k, from (x[i], y[i]) to (x[j], y[j]):
     * a = dy, b = -dx, c = -(dy xi - dx yi), less 1 unless it is a top edge
     * (dy = 0, dx < 0) or a left edge (dy > 0). */
    static const int from[3] = {1, 2, 0}, to[3] = {2, 0, 1};
    vi32 edge_a[3], edge_b[3], top_or_left[3];
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
        const vi32 dx = fx[to[k]] - fx[from[k]], dy = fy[to[k]] - fy[from[k]];
        edge_a[k] = dy;
        edge_b[k] = -dx;
        top_or_left[k] = ((dy == 0) & (dx < 0)) | (dy > 0);
    }
    /* One sample a pixel, every lane's corners near each other: the
     * area and the centres' tests in 32-bit lanes (NEAR_EXTENT). (Four
     * samples keep the 64-bit tests.) */
    const bool near = samples == 1 &&
                      lane_bits((highest_x - lowest_x < NEAR_EXTENT) &
                                (highest_y - lowest_y < NEAR_EXTENT)) == (1u << LANES) - 1;

    /* The vertex stage and steps 1-2 again, per corner, from the mesh. */
    vf32 varying[3][8];
    vf64 x[3][2], y[3][2], depth[3][2], weight[3][2];
    const float *model = transform->model.m, *normal_matrix = transform->normal_matrix.m;
    const float *view_projection = transform->view_projection.m;
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++) {
        const float *from_vertex[LANES];
        for (int lane = 0; lane < LANES; lane++)
            from_vertex[lane] = &transform->vertices[corners->vertex[k][lane]].position.x;
        vf32 in[8];
        load_columns8(from_vertex, in);
        /* vertex.c: world = model p, normal = N n, clip = VP world. */
        const vf32 world_x = transform_row(model, 0, in[0], in[1], in[2]);
        const vf32 world_y = transform_row(model, 1, in[0], in[1], in[2]);
        const vf32 world_z = transform_row(model, 2, in[0], in[1], in[2]);
        varying[k][LUZ_VARYING_POSITION + 0] = world_x;
        varying[k][LUZ_VARYING_POSITION + 1] = world_y;
        varying[k][LUZ_VARYING_POSITION + 2] = world_z;
        for (int r = 0; r < 3; r++)
            varying[k][LUZ_VARYING_NORMAL + r] =
                transform_row3(normal_matrix, r, in[3], in[4], in[5]);
        varying[k][LUZ_VARYING_UV + 0] = in[6];
        varying[k][LUZ_VARYING_UV + 1] = in[7];
        const vf32 clip[4] = {transform_row(view_projection, 0, world_x, world_y, world_z),
                              transform_row(view_projection, 1, world_x, world_y, world_z),
                              transform_row(view_projection, 2, world_x, world_y, world_z),
                              transform_row(view_projection, 3, world_x, world_y, world_z)};
        /* setup.c: divide, viewport (the snap is fixed's, gathered). */
#pragma GCC unroll 2
        for (int h = 0; h < 2; h++) {
            const vf64 one = splatd(1.0);
            const vf64 inverse_w = one / widen_half_float(clip[3], h);
            const vf64 x_ndc = widen_half_float(clip[0], h) * inverse_w;
            const vf64 y_ndc = widen_half_float(clip[1], h) * inverse_w;
            vf64 window_x = (x_ndc + 1.0) * 0.5 * (double)width;
            vf64 window_y = (1.0 - y_ndc) * 0.5 * (double)height;
            const double limit = LUZ_COORDINATE_LIMIT / LUZ_SUBPIXEL_ONE;
            window_x = clamp_to_limit(window_x, limit);
            window_y = clamp_to_limit(window_y, limit);
            x[k][h] = window_x;
            y[k][h] = window_y;
            depth[k][h] = (widen_half_float(clip[2], h) * inverse_w + 1.0) * 0.5;
            weight[k][h] = interpolation == LUZ_INTERPOLATION_AFFINE ? one : inverse_w;
        }
    }

    /* 3 and 5, half a step at a time: the doubled area, the edges'
     * constants, the planes from the exact window positions relative to
     * the snapped vertex 0. */
    unsigned back = 0, solvable = 0, covered = 0;
    unsigned centre_inside[4] = {0, 0, 0, 0};   /* narrow_to_one_centre's */
    if (near) {
        /* area <= 0 where -area is not negative (as below) */
        back = lane_bits((fx[1] - fx[0]) * (fy[2] - fy[0]) - (fy[1] - fy[0]) * (fx[2] - fx[0]) >=
                         0);
        const vi32 from_x[3] = {fx[1], fx[2], fx[0]}, from_y[3] = {fy[1], fy[2], fy[0]};
        const vi32 not_top_left[3] = {~top_or_left[0], ~top_or_left[1], ~top_or_left[2]};
        covered = covered_near(~back & ~empty & small & ~up_to_2x2 & ((1u << LANES) - 1), min_x,
                               min_y, box_width, box_pixels, edge_a, edge_b, not_top_left,
                               from_x, from_y);
        centres_inside_near(min_x, min_y, edge_a, edge_b, not_top_left, from_x, from_y,
                            centre_inside);
    }
    vi64 c[3][2];
    vf64 x10[2], x20[2], y10[2], y20[2], inverse_determinant[2], rx[2], ry[2], rx0[2], ry0[2];
#pragma GCC unroll 2
    for (int h = 0; h < 2; h++) {
        vi64 wx[3], wy[3];
        for (int k = 0; k < 3; k++) wx[k] = widen_half(fx[k], h), wy[k] = widen_half(fy[k], h);
        /* area <= 0 where -area is not negative */
        if (!near)
            back |= (~negative_bits64(multiply_wide(wx[1] - wx[0], wy[2] - wy[0]) -
                                      multiply_wide(wy[1] - wy[0], wx[2] - wx[0])) &
                     ((1u << HALF) - 1))
                    << (h * HALF);
        vi64 a[3], b[3], c_half[3];
        for (int k = 0; k < 3; k++) {
            const vi64 dx = wx[to[k]] - wx[from[k]], dy = wy[to[k]] - wy[from[k]];
            a[k] = widen_half(edge_a[k], h);
            b[k] = widen_half(edge_b[k], h);
            c_half[k] = -(multiply_wide(dy, wx[from[k]]) - multiply_wide(dx, wy[from[k]])) -
                        (~widen_half(top_or_left[k], h) & 1);
            c[k][h] = c_half[k];
        }
        if (!near) {
            const unsigned to_test = (~back & ~empty & small & ~up_to_2x2) >> (h * HALF) &
                                     ((1u << HALF) - 1);
            covered |= covered_half(to_test, widen_half(min_x, h), widen_half(min_y, h),
                                    widen_half(box_width, h), widen_half(box_height, h), a, b,
                                    c_half, samples)
                       << (h * HALF);
            if (samples == 1) {
                unsigned inside[4];
                centres_inside_half(widen_half(min_x, h), widen_half(min_y, h), a, b, c_half,
                                    inside);
                for (int i = 0; i < 4; i++) centre_inside[i] |= inside[i] << (h * HALF);
            }
        }

        x10[h] = x[1][h] - x[0][h], x20[h] = x[2][h] - x[0][h];
        y10[h] = y[1][h] - y[0][h], y20[h] = y[2][h] - y[0][h];
        const vf64 determinant = x10[h] * y20[h] - x20[h] * y10[h];
        /* setup.c: !(determinant != 0.0) || !isfinite(determinant) culls. */
        const vf64 magnitude = (vf64)((vi64)determinant & 0x7fffffffffffffff);
        solvable |= lane_bits64((determinant != 0.0) & (magnitude < (double)INFINITY))
                    << (h * HALF);
        /* (A lane that cannot be solved divides 1 by 1 instead: it is
         * culled whatever its planes, and -fsanitize=float-divide-by-zero
         * traps a division by 0.) */
        inverse_determinant[h] = 1.0 / selectd(determinant != 0.0, determinant, splatd(1.0));
        /* fixed / 256: exact, a power of two. */
        rx[h] = double_half(fx[0], h) / (double)LUZ_SUBPIXEL_ONE;
        ry[h] = double_half(fy[0], h) / (double)LUZ_SUBPIXEL_ONE;
        rx0[h] = rx[h] - x[0][h], ry0[h] = ry[h] - y[0][h];
    }

    /* The record's floats from byte 64, each a vector of LANES made in
     * registers from its two halves: the reference point, then depth, 1/w
     * and each varying/w as (value, dx, dy); column j holds float j of
     * every lane. */
    vf32 column[32];
    column[0] = narrow_join(rx[0], rx[1]);
    column[1] = narrow_join(ry[0], ry[1]);
    vf64 plane[2][3];
    for (int h = 0; h < 2; h++)
        make_plane_half(x10[h], x20[h], y10[h], y20[h], inverse_determinant[h], rx0[h], ry0[h],
                        depth[0][h], depth[1][h], depth[2][h], plane[h]);
    for (int j = 0; j < 3; j++) column[2 + j] = narrow_join(plane[0][j], plane[1][j]);
    for (int h = 0; h < 2; h++)
        make_plane_half(x10[h], x20[h], y10[h], y20[h], inverse_determinant[h], rx0[h], ry0[h],
                        weight[0][h], weight[1][h], weight[2][h], plane[h]);
    for (int j = 0; j < 3; j++) column[5 + j] = narrow_join(plane[0][j], plane[1][j]);
    for (int i = 0; i < LUZ_VARYING_COUNT; i++) {
        for (int h = 0; h < 2; h++) {
            vf64 value[3];
            for (int k = 0; k < 3; k++)
                value[k] = widen_half_float(varying[k][i], h) * weight[k][h];
            make_plane_half(x10[h], x20[h], y10[h], y20[h], inverse_determinant[h], rx0[h],
                            ry0[h], value[0], value[1], value[2], plane[h]);
        }
        for (int j = 0; j < 3; j++)
            column[8 + 3 * i + j] = narrow_join(plane[0][j], plane[1][j]);
    }

    /* A box of up to 2 x 2 pixels with one centre covered becomes that
     * pixel (setup.c's narrow_to_one_centre); the verdicts below read
     * the sizes of the box before. */
    vi32 box[4] = {min_x, min_y, max_x, max_y};
    if (samples == 1) {
        const unsigned wide = lane_bits(box_width == 2), tall = lane_bits(box_height == 2);
        const unsigned lanes = ~back & ~empty & up_to_2x2;
        const unsigned at00 = lanes & centre_inside[0], at10 = lanes & wide & centre_inside[1];
        const unsigned at01 = lanes & tall & centre_inside[2];
        const unsigned at11 = lanes & wide & tall & centre_inside[3];
        const unsigned two_or_more =
            (at00 & (at10 | at01 | at11)) | (at10 & (at01 | at11)) | (at01 & at11);
        const unsigned only = (at00 | at10 | at01 | at11) & ~two_or_more;
        /* A mask's lanes are -1: subtracting one adds 1 there. */
        box[0] -= lanes_of_bits(only & (at10 | at11));
        box[1] -= lanes_of_bits(only & (at01 | at11));
        box[2] = select32(lanes_of_bits(only), box[0], box[2]);
        box[3] = select32(lanes_of_bits(only), box[1], box[3]);
    }

    /* The box and edges as sixteen 32-bit words a lane: min x, min y,
     * max x, max y, then a, b and c (low word, high word) of each edge. */
    vi32 word[16] = {box[0], box[1], box[2], box[3]};
    for (int k = 0; k < 3; k++) {
        word[4 + 4 * k] = edge_a[k];
        word[5 + 4 * k] = edge_b[k];
        word[6 + 4 * k] = low_words(c[k][0], c[k][1]);
        word[7 + 4 * k] = high_words(c[k][0], c[k][1]);
    }
    /* Each lane's record: words 0-15, then the 32 floats. */
    vf32 record[48];
    for (int j = 0; j < 16; j++) record[j] = (vf32)word[j];
    for (int j = 0; j < 32; j++) record[16 + j] = column[j];
    float *to_record[LANES];
    for (int lane = 0; lane < LANES; lane++) to_record[lane] = (float *)(void *)&out[lane];
    store_columns(to_record, record, 48);
    for (int lane = 0; lane < LANES; lane++) out[lane].draw_index = draw_index;

    /* Each lane's verdict in setup's order: culled (a back face), off
     * screen (no centre in the box, or in a box of 3 to 16 centres none
     * covered), then culled again (no plane can be solved). */
    const unsigned offscreen = empty | (~back & ~empty & small & ~up_to_2x2 & ~covered);
    for (int lane = 0; lane < LANES; lane++) {
        const unsigned bit = 1u << lane;
        result[lane] = (back & bit)        ? LUZ_SETUP_CULLED
                       : (offscreen & bit) ? LUZ_SETUP_OFFSCREEN
                       : (solvable & bit)  ? LUZ_SETUP_VISIBLE
                                           : LUZ_SETUP_CULLED;
    }
}

/* Setup in lanes for pixels of `samples` samples, 1 or 4 (a constant in
 * each of the two functions below). */
LANES_INLINE bool setup_eight(const uint32_t *indices, const uint32_t triangles[8],
                              const luz_draw_transform *transform,
                              const luz_fixed_vertex *fixed, int width, int height,
                              uint32_t draw_index, luz_interpolation interpolation, int samples,
                              luz_triangle out[8], luz_setup_result result[8])
{
    /* The corners of every group first: a marked vertex (below -2^24)
     * leaves all eight to the caller before any record is written.
     * Marked vertices come in runs (a draw across a clip plane, whose back
     * faces screening cannot judge either): such a call is left whole. */
    group_corners corners[GROUPS];
    unsigned marked = 0;
    for (int g = 0; g < GROUPS; g++) {
#if LANES == 8 && defined(__AVX2__)
        /* Gathered (3 t + k < 3 * 2^28 fits an int32), as setup_eight.c
         * does: eight indices stored one by one and loaded as a vector
         * wait for the stores to retire. */
        const __m256i first_index = _mm256_mullo_epi32(
            _mm256_loadu_si256((const void *)(triangles + g * LANES)),
            _mm256_set1_epi32(3));
        for (int k = 0; k < 3; k++)
            corners[g].vertex[k] =
                (vi32)_mm256_i32gather_epi32((const int *)indices + k, first_index, 4);
#else
        int32_t vertex[3][LANES];
        for (int lane = 0; lane < LANES; lane++)
            for (int k = 0; k < 3; k++)
                vertex[k][lane] =
                    (int32_t)indices[3 * (size_t)triangles[g * LANES + lane] + (size_t)k];
        for (int k = 0; k < 3; k++) memcpy(&corners[g].vertex[k], vertex[k], sizeof vertex[k]);
#endif
        for (int k = 0; k < 3; k++) {
            gather_fixed(corners[g].vertex[k], fixed, &corners[g].x[k], &corners[g].y[k]);
            marked |= lane_bits(corners[g].x[k] < -(1 << 24));
        }
    }
    if (marked != 0) return true;
    for (int g = 0; g < GROUPS; g++)
        setup_group(&corners[g], transform, width, height, draw_index, interpolation, samples,
                    &out[g * LANES], &result[g * LANES]);
    return false;
}

luz_setup_eight_function SETUP_LANES, SETUP_LANES_FOUR;

bool SETUP_LANES(const uint32_t *indices, const uint32_t triangles[8],
                 const luz_draw_transform *transform, const luz_fixed_vertex *fixed, int width,
                 int height, uint32_t draw_index, luz_interpolation interpolation,
                 luz_triangle out[8], luz_setup_result result[8])
{
    return setup_eight(indices, triangles, transform, fixed, width, height, draw_index,
                       interpolation, 1, out, result);
}

/* The same for four samples a pixel (setup_eight.c's
 * luz_setup_eight_four_avx512). */
bool SETUP_LANES_FOUR(const uint32_t *indices, const uint32_t triangles[8],
                      const luz_draw_transform *transform, const luz_fixed_vertex *fixed,
                      int width, int height, uint32_t draw_index,
                      luz_interpolation interpolation, luz_triangle out[8],
                      luz_setup_result result[8])
{
    return setup_eight(indices, triangles, transform, fixed, width, height, draw_index,
                       interpolation, 4, out, result);
}
