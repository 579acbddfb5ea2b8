/*
 * vertex_lanes.c: the vertex pass in lanes (vertex_sixteen.c's job: the
 * vertex stage and the projection of a big mesh's vertices, many at a
 * time) written once on lanes.h's portable vectors, for the instruction
 * sets without AVX-512: 8 vertices a step with AVX2, 4 with SSE2 and NEON.
 *
 * In, out: vertex_sixteen.c's (luz_vertex_project_function). Position-only
 * shading, the pass that setup in lanes (setup_lanes.c) makes possible,
 * runs in lanes: positions alone, transformed and projected, and their
 * snapped positions stored, 8 bytes a vertex. A pass that keeps clip or
 * window vertices (four samples a pixel, where setup in lanes is off)
 * goes one vertex at a time here.
 *
 * The arithmetic is vertex.c's and setup.c's, operation for operation:
 * each transform a[0] x + a[4] y + a[8] z + a[12] summed left to right in
 * float, the outcode's six comparisons, the divide, viewport and clamp in
 * double, the snap rounded to nearest even as llrint does (lanes.h's
 * round_to_even); no fused multiply-add. tests/test_vertex_sixteen.c
 * holds every variant's bytes to the two functions. The AVX-512 variant
 * stays vertex_sixteen.c's, in intrinsics.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "renderer/pipeline.h"

#if defined(LUZ_LANES_AVX2)
#define LANES 8
#define VERTEX_LANES luz_vertex_project_avx2
#elif defined(LUZ_LANES_NEON)
#define LANES 4
#define VERTEX_LANES luz_vertex_project_neon
#elif defined(LUZ_LANES_SSE2)
#define LANES 4
#define VERTEX_LANES luz_vertex_project_sse2
#else
#error "vertex_lanes.c is compiled for one instruction set: -DLUZ_LANES_AVX2, ..."
#endif

#include "renderer/lanes.h"

_Static_assert(sizeof(luz_vertex) == 8 * sizeof(float), "a mesh vertex is eight floats");
_Static_assert(sizeof(luz_fixed_vertex) == 2 * sizeof(int32_t), "a snapped vertex is x, y");

/* a[0] x + a[4] y + a[8] z + a[12] w with w = 1 (vertex.c's transform4,
 * row r of a column-major 4 x 4), summed left to right. */
LANES_INLINE vf32 transform_row(const float *a, int r, vf32 x, vf32 y, vf32 z)
{
    return ((a[r] * x + a[4 + r] * y) + a[8 + r] * z) + a[12 + r];
}

/* Half a step's snapped x and y, interleaved as luz_fixed_vertex: HALF
 * vertices. */
LANES_INLINE vi32 interleave_half(vi32 x, vi32 y, int h)
{
#if LANES == 8
    return h == 0 ? __builtin_shufflevector(x, y, 0, 8, 1, 9, 2, 10, 3, 11)
                  : __builtin_shufflevector(x, y, 4, 12, 5, 13, 6, 14, 7, 15);
#else
    return h == 0 ? __builtin_shufflevector(x, y, 0, 4, 1, 5)
                  : __builtin_shufflevector(x, y, 2, 6, 3, 7);
#endif
}

/* Vertices i .. i + LANES - 1 of the mesh: their positions alone, through
 * the vertex stage and luz_setup_project_vertex, snapped into fixed (or
 * marked). */
LANES_INLINE void positions(const luz_vertex *vertices, const float *model,
                            const float *view_projection, uint32_t i, double width,
                            double height, luz_fixed_vertex *fixed)
{
    const float *from[LANES];
    for (int lane = 0; lane < LANES; lane++) from[lane] = &vertices[i + (uint32_t)lane].position.x;
    vf32 in[8];
    load_columns8(from, in);
    /* vertex.c: world = model p, clip = VP world. */
    const vf32 world_x = transform_row(model, 0, in[0], in[1], in[2]);
    const vf32 world_y = transform_row(model, 1, in[0], in[1], in[2]);
    const vf32 world_z = transform_row(model, 2, in[0], in[1], in[2]);
    const vf32 clip_x = transform_row(view_projection, 0, world_x, world_y, world_z);
    const vf32 clip_y = transform_row(view_projection, 1, world_x, world_y, world_z);
    const vf32 clip_z = transform_row(view_projection, 2, world_x, world_y, world_z);
    const vf32 clip_w = transform_row(view_projection, 3, world_x, world_y, world_z);
    /* luz_clip_outcode != 0: outside one of the six planes, !(d >= 0)
     * (a NaN is outside). */
    const vf32 guard_w = LUZ_CLIP_GUARD_BAND * clip_w;
    const vi32 inside = (clip_w + clip_z >= 0.0f) & (clip_w - clip_z >= 0.0f) &
                        (guard_w + clip_x >= 0.0f) & (guard_w - clip_x >= 0.0f) &
                        (guard_w + clip_y >= 0.0f) & (guard_w - clip_y >= 0.0f);
    const vi32 clipped = ~inside;
    /* setup.c: not projectable unless w > 0 and x, y, z finite. */
    const float infinity = INFINITY;
    const vi32 projectable = (clip_w > 0.0f) & (absf(clip_x) < infinity) &
                             (absf(clip_y) < infinity) & (absf(clip_z) < infinity);
    const vi32 invalid = ~clipped & ~projectable;

    typedef int32_t half_ints __attribute__((vector_size(HALF * sizeof(int32_t))));
    half_ints snapped_x_half[2], snapped_y_half[2];
    for (int h = 0; h < 2; h++) {
        /* 1-2. Divide, viewport, the clamp to +-2^24 sub-pixel units, the
         * snap; lanes that are not projected compute on 1 instead (their
         * marker replaces the result), so that no NaN is converted. */
        const vi64 keep = widen_half(projectable, h);
        const vf64 one = splatd(1.0);
        const vf64 inverse_w = one / selectd(keep, widen_half_float(clip_w, h), one);
        const vf64 x_ndc = selectd(keep, widen_half_float(clip_x, h), one) * inverse_w;
        const vf64 y_ndc = selectd(keep, widen_half_float(clip_y, h), one) * inverse_w;
        vf64 window_x = (x_ndc + 1.0) * 0.5 * width;
        vf64 window_y = (1.0 - y_ndc) * 0.5 * height;
        const double limit = LUZ_COORDINATE_LIMIT / LUZ_SUBPIXEL_ONE;
        window_x = clamp_to_limit(window_x, limit);
        window_y = clamp_to_limit(window_y, limit);
        snapped_x_half[h] =
            __builtin_convertvector(round_to_even(window_x * (double)LUZ_SUBPIXEL_ONE), half_ints);
        snapped_y_half[h] =
            __builtin_convertvector(round_to_even(window_y * (double)LUZ_SUBPIXEL_ONE), half_ints);
    }
    /* The halves joined in registers (stored as halves and loaded whole,
     * they would wait for the store buffer). */
    const vi32 snapped_x = LANES_JOIN(snapped_x_half[0], snapped_x_half[1]);
    const vi32 snapped_y = LANES_JOIN(snapped_y_half[0], snapped_y_half[1]);
    /* The markers: outside a clip plane, else not projectable; a marked
     * vertex's y is 0. */
    vi32 fixed_x = select32(clipped, splat32(LUZ_WINDOW_CLIPPED), snapped_x);
    fixed_x = select32(invalid, splat32(LUZ_WINDOW_INVALID), fixed_x);
    const vi32 fixed_y = snapped_y & ~(clipped | invalid);
    for (int h = 0; h < 2; h++) {
        const vi32 pairs = interleave_half(fixed_x, fixed_y, h);
        memcpy(&fixed[i + (uint32_t)(h * HALF)], &pairs, sizeof pairs);
    }
}

luz_vertex_project_function VERTEX_LANES;

void VERTEX_LANES(const luz_draw *draw, luz_mat4 view_projection, uint32_t first, uint32_t end,
                  int width, int height, luz_clip_vertex *out, luz_window_vertex *window,
                  luz_fixed_vertex *fixed)
{
    if (first >= end) return;   /* as the two functions: nothing to do */
    const luz_draw_transform transform = luz_draw_transform_of(draw, view_projection);
    uint32_t i = first;
    if (out == NULL && window == NULL && fixed != NULL)   /* position-only shading */
        for (; end - i >= LANES; i += LANES)
            positions(transform.vertices, transform.model.m, view_projection.m, i, width, height,
                      fixed);
    for (; i < end; i++) {   /* the last few, or every vertex, one at a time */
        const luz_clip_vertex vertex = luz_vertex_stage_one(&transform, i);
        const luz_window_vertex projected = luz_setup_project_vertex(&vertex, width, height);
        if (out != NULL) out[i] = vertex;
        if (window != NULL) window[i] = projected;
        if (fixed != NULL) fixed[i] = (luz_fixed_vertex){projected.fixed_x, projected.fixed_y};
    }
}
