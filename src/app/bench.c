/*
 * bench.c: the median behind every --bench line (see luz/bench.h).
 */
#include <stdbool.h>
#include <stdlib.h>
#include <time.h>

#include "app/bench.h"

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double luz_median(double *values, int count)
{
    qsort(values, (size_t)count, sizeof *values, compare_doubles);
    return count % 2 ? values[count / 2] : 0.5 * (values[count / 2 - 1] + values[count / 2]);
}

static double milliseconds_of(clockid_t clock)
{
    struct timespec now;
    clock_gettime(clock, &now);
    return (double)now.tv_sec * 1e3 + (double)now.tv_nsec * 1e-6;
}

double luz_wall_ms(void)
{
    return milliseconds_of(CLOCK_MONOTONIC);
}

double luz_cpu_ms(void)
{
    return milliseconds_of(CLOCK_PROCESS_CPUTIME_ID);
}

void luz_bench_print_case(FILE *out, const luz_options *options, int frames, int width,
                          int height, int threads)
{
    const luz_scene *scene = &options->scene;
    int cubes = scene->custom_cubes ? scene->custom_cube_count : scene->cube_count;
    /* The teaching views are drawn by view.c, which is scalar code. */
    bool reference = options->reference || scene->view != LUZ_VIEW_COLOR;
    fprintf(out, "frames=%d size=%dx%d threads=%d cubes=%d filter=%s fragment=%s ", frames, width,
            height, threads, cubes, luz_filter_name(scene->filter),
            reference ? "reference" : "packet");
    if (scene->view != LUZ_VIEW_COLOR)
        fprintf(out, "view=%s ", luz_view_name(scene->view));
    if (scene->interpolation != LUZ_INTERPOLATION_PERSPECTIVE)
        fprintf(out, "interp=%s ", luz_interpolation_name(scene->interpolation));
}
