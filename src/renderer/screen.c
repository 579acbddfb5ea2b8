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
 * The kernels are screen_lanes.c's, written once on lanes.h's portable
 * vectors and compiled for each instruction set: 16 triangles a step
 * with AVX-512, 8 with AVX2, 4 with SSE2 and NEON; cpu.c puts one in the
 * renderer's table of kernels. This file keeps the contract above and
 * the loop of a set without one (the scalar set), which screens nothing.
 * (AVX-512 had a kernel of its own here, in intrinsics, in 64-bit lanes
 * throughout; screen_lanes.c, which takes a step's edge functions in
 * 32-bit lanes where every product fits, took 0.5 ms less of the 1M
 * sphere's frame: docs/performance.md, "The 1M sphere and its setup".)
 */
#include <stddef.h>
#include <stdint.h>

#include "renderer/pipeline.h"

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
