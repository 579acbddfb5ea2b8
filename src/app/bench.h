/*
 * luz/bench.h: what the --bench lines of luz-render, the viewer and
 * tools/glref are made of.
 *
 * They quote medians, not means: the machines are shared, and a busy
 * neighbour makes a few frames slow but never a few frames fast, so a
 * mean follows the neighbour and a median follows the renderer.
 */
#ifndef LUZ_BENCH_H
#define LUZ_BENCH_H

#include <stdio.h>

#include "app/options.h"

/* Clocks in milliseconds from an arbitrary start: the wall clock
 * (monotonic, never stepped), and the CPU time of the whole process, all
 * its threads. Their differences time a frame. */
double luz_wall_ms(void);
double luz_cpu_ms(void);

/* The median of count values (count > 0); sorts them, so values[0] is then
 * the minimum. */
double luz_median(double *values, int count);

/* The start of a --bench line, what was measured: "frames=N size=WxH
 * threads=T cubes=C filter=F fragment=packet|reference", then view= and
 * interp= when they are not the defaults, and a trailing blank. The
 * figures follow it. */
void luz_bench_print_case(FILE *out, const luz_options *options, int frames, int width,
                          int height, int threads);

#endif
