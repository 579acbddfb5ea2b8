/*
 * app/bench.h: the --bench loop and line of luz-render, the viewer and
 * tools/glref.
 *
 * They quote medians, not means: the machines are shared, and a busy
 * neighbour makes a few frames slow but never a few frames fast, so a
 * mean follows the neighbour and a median follows the renderer.
 */
#ifndef LUZ_BENCH_H
#define LUZ_BENCH_H

#include <stdint.h>
#include <stdio.h>

#include "app/options.h"
#include "luz/error.h"

/* Clocks in milliseconds from an arbitrary start: the wall clock
 * (monotonic, never stepped), and the CPU time of the whole process, all
 * its threads. Their differences time a frame. */
double luz_wall_ms(void);
double luz_cpu_ms(void);

/* The median of count values (count > 0); sorts them, so values[0] is then
 * the minimum. */
double luz_median(double *values, int count);

/* The start of a --bench line, what was measured: "frames=N size=WxH
 * threads=T cubes=C triangles=N filter=F fragment=packet|reference
 * isa=I" (luz_renderer_isa), then view= and interp= when they are not the
 * defaults, and a trailing blank. The figures follow it. */
void luz_bench_print_case(FILE *out, const luz_options *options, int frames, int width,
                          int height, int threads, uint64_t triangles, const char *isa);

/* The triangles a frame submits: its draws' meshes' counts added up. */
uint64_t luz_bench_triangles(const luz_frame *frame);

/* ---- the loop ------------------------------------------------------------------------ */

#define LUZ_BENCH_MAX_PARTS 4

/* One frame of a benchmark: draw (and show) the scene at time_seconds, and
 * put the time its parts took (in milliseconds) into parts[], in the order
 * of the bench's part_names. Returns 0, 1 to stop early with the frames so
 * far (the viewer's Esc), or -1 with the reason in error. */
typedef int luz_bench_frame_function(void *context, double time_seconds,
                                     double parts[LUZ_BENCH_MAX_PARTS], luz_error *error);

/* A benchmark's frames: set part_names (NULL-terminated if fewer than
 * LUZ_BENCH_MAX_PARTS: "geometry_ms", "raster_ms", ...), run it, print its
 * figures, free it. */
typedef struct luz_bench {
    const char *part_names[LUZ_BENCH_MAX_PARTS];
    int frames;                  /* frames measured */
    double *wall_ms, *cpu_ms;    /* one per frame */
    double *parts[LUZ_BENCH_MAX_PARTS];
} luz_bench;

/* --bench N's schedule, the same in every program: one warm-up frame at
 * start_seconds (caches filled, threads started), then frame k at
 * start_seconds + k / frames_per_second, k < frame_count, each timed by
 * the wall clock and the process's CPU time. Returns 0 (bench->frames may
 * be fewer than frame_count if a frame stopped the run), or -1. */
int luz_bench_run(luz_bench *bench, int frame_count, double start_seconds,
                  double frames_per_second, luz_bench_frame_function *frame, void *context,
                  luz_error *error);

/* The measurements: "median_ms=M min_ms=M fps=F cpu_ms=M", then each
 * part's median as "NAME=M", with a blank before each; no newline. */
void luz_bench_print_figures(FILE *out, luz_bench *bench);

void luz_bench_free(luz_bench *bench);

#endif
