/*
 * cpu.h: the instruction set the renderer's kernels use, and the table of
 * kernels chosen for it together, once, when a renderer is made. Private
 * to the library (and its tests).
 *
 * The kernels are the stages written in lanes: the fragment packets
 * (fragment_packet.c), screening, setup in lanes and the vertex pass in
 * lanes (screen_lanes.c for every set with lanes; AVX-512's setup_eight.c
 * and vertex_sixteen.c; AVX2's, SSE2's and NEON's setup_lanes.c and
 * vertex_lanes.c, one source on lanes.h for all three; the scalar set's lanes_scalar.c, the
 * reference's functions one at a time), and four samples' two plain
 * loops that the compiler vectorises (sample_loops.c: the scalar set
 * shares the build's target's copy). Each is compiled once per
 * instruction set (src/renderer/meson.build); cpu.c
 * asks the CPU once which it runs, and luz_kernels_of hands out one
 * table, so that no stage asks again and no two stages can disagree.
 * LUZ_ISA names a narrower set than the widest (luz_isa_check), so that
 * every path can be tested on the one machine.
 *
 * Every table gives the same image, byte for byte: each lane performs the
 * scalar reference's IEEE operations in the same order (no fused
 * multiply-add: -ffp-contract=off), so the width changes only the time.
 */
#ifndef LUZ_CPU_H
#define LUZ_CPU_H

#include <stdbool.h>

#include "luz/error.h"
#include "renderer/pipeline.h"

/* From narrowest to widest: a table never uses a wider set than its own. */
typedef enum luz_isa {
    LUZ_ISA_SCALAR,     /* one lane: plain C, any CPU */
    LUZ_ISA_BASELINE,   /* the build's target, four lanes: SSE2 on x86-64
                           ("sse2"), Advanced SIMD on aarch64 ("neon") */
    LUZ_ISA_AVX2,       /* x86-64 AVX2 and FMA, 8 lanes */
    LUZ_ISA_AVX512,     /* x86-64 AVX-512 F, VL, BW and DQ, 16 lanes */
} luz_isa;

#define LUZ_ISA_COUNT 4

/* "scalar", "sse2" (or "neon", or "vector" on other CPUs), "avx2",
 * "avx512". */
const char *luz_isa_name(luz_isa isa);

/* Whether this build has the set's kernels and this CPU runs them. */
bool luz_isa_available(luz_isa isa);

/* The widest set available. */
luz_isa luz_isa_widest(void);

/* The set the renderer uses: LUZ_ISA's if the environment names one, else
 * the widest. Returns 0, or -1 with the reason (LUZ_ISA names no set this
 * build knows, or one this CPU lacks). */
int luz_isa_chosen(luz_isa *out, luz_error *error);

/* The table of kernels of one set. */
typedef struct luz_kernels {
    luz_isa isa;
    luz_packet_rows_function *packet_rows;   /* the fragment packets' rows */
    luz_packet_list_function *packet_list;   /* and their list (four samples) */
    luz_screen_function *screen;             /* screening (every triangle
                                                through where the set has
                                                none) */
    bool screen_checks_small_boxes;          /* luz_screen_function's promise */
    luz_setup_eight_function *setup_eight;   /* NULL: one triangle at a time */
    bool setup_eight_screens;                /* setup_eight drops what screening
                                                would, itself (the scalar set's):
                                                it runs without screening */
    luz_vertex_project_function *vertex_project;   /* NULL: one vertex at a time */
    /* The same two for four samples a pixel (SCENE.md, "Anti-aliasing"):
     * the box and the small boxes' test are the samples'. NULL: every
     * triangle through, and one at a time (luz_setup_projected_samples). */
    luz_screen_function *screen_four;        /* checks the small boxes */
    luz_setup_eight_function *setup_eight_four;
    /* Four samples' plain loop (sample_loops.c), compiled per set. */
    luz_mixed_pixels_function *mixed_pixels; /* the resolve's mixed pixels */
    /* One sample's long spans (sample_loops.c too). */
    luz_centre_span_function *centre_span_test;
    /* The raster's depth tests at four samples in lanes (raster_lanes.c).
     * NULL: one sample at a time. */
    luz_raster_groups_function *raster_groups;
    luz_raster_list_function *raster_list;   /* the same, a band's list a call */
} luz_kernels;

/* The table of isa, which must be available. */
luz_kernels luz_kernels_of(luz_isa isa);

/* Which kernels phase 1 runs (geometry.c); the widest set's when it is
 * made. */
void luz_geometry_set_kernels(luz_geometry *geometry, const luz_kernels *kernels);

/* For tests: the renderer's table, as if it had been made with isa. */
void luz_renderer_set_isa(struct luz_renderer *renderer, luz_isa isa);

#endif
