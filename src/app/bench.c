/*
 * bench.c: the --bench loop, its medians and its line (see app/bench.h).
 */
#include <stdbool.h>
#include <stdint.h>
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

uint64_t luz_bench_triangles(const luz_frame *frame)
{
    uint64_t triangles = 0;
    for (int d = 0; d < frame->draw_count; d++)
        triangles += luz_mesh_triangle_count(frame->draws[d].mesh);
    return triangles;
}

void luz_bench_print_case(FILE *out, const luz_options *options, int frames, int width,
                          int height, int threads, uint64_t triangles, const char *isa)
{
    const luz_scene *scene = &options->scene;
    int cubes = scene->cube_count;
    if (scene->objects) {
        cubes = 0;
        for (int i = 0; i < scene->object_count; i++) cubes += scene->objects[i].model == NULL;
    }
    /* The teaching views are drawn by view.c, which is scalar code. */
    bool reference = options->reference || scene->view != LUZ_VIEW_COLOR;
    fprintf(out,
            "frames=%d size=%dx%d threads=%d cubes=%d triangles=%llu filter=%s fragment=%s "
            "isa=%s ",
            frames, width, height, threads, cubes, (unsigned long long)triangles,
            luz_filter_name(scene->filter), reference ? "reference" : "packet", isa);
    if (scene->view != LUZ_VIEW_COLOR)
        fprintf(out, "view=%s ", luz_view_name(scene->view));
    if (scene->interpolation != LUZ_INTERPOLATION_PERSPECTIVE)
        fprintf(out, "interp=%s ", luz_interpolation_name(scene->interpolation));
    if (scene->samples > 1) fprintf(out, "samples=%d ", scene->samples);
}

int luz_bench_run(luz_bench *bench, int frame_count, double start_seconds,
                  double frames_per_second, luz_bench_frame_function *frame, void *context,
                  luz_error *error)
{
    luz_bench_free(bench);
    const size_t count = frame_count > 0 ? (size_t)frame_count : 0;
    const size_t series = 2 + LUZ_BENCH_MAX_PARTS;
    double *storage = calloc(count * series + 1, sizeof *storage);
    if (storage == NULL)
        return luz_error_set(error, "--bench: out of memory for %d frames", frame_count);
    bench->wall_ms = storage;
    bench->cpu_ms = storage + count;
    for (int p = 0; p < LUZ_BENCH_MAX_PARTS; p++) bench->parts[p] = storage + (2 + p) * count;

    double parts[LUZ_BENCH_MAX_PARTS];
    int status = frame(context, start_seconds, parts, error);   /* the warm-up */
    for (int k = 0; k < frame_count && status == 0; k++) {
        const double wall = luz_wall_ms(), cpu = luz_cpu_ms();
        status = frame(context, start_seconds + k / frames_per_second, parts, error);
        if (status != 0) break;
        bench->cpu_ms[k] = luz_cpu_ms() - cpu;
        bench->wall_ms[k] = luz_wall_ms() - wall;
        for (int p = 0; p < LUZ_BENCH_MAX_PARTS; p++) bench->parts[p][k] = parts[p];
        bench->frames = k + 1;
    }
    return status < 0 ? -1 : 0;
}

void luz_bench_print_figures(FILE *out, luz_bench *bench)
{
    const int n = bench->frames;
    if (n == 0) return;
    const double median_ms = luz_median(bench->wall_ms, n);
    const double min_ms = bench->wall_ms[0];   /* sorted by luz_median */
    fprintf(out, "median_ms=%.3f min_ms=%.3f fps=%.2f cpu_ms=%.3f", median_ms, min_ms,
            median_ms > 0.0 ? 1000.0 / median_ms : 0.0, luz_median(bench->cpu_ms, n));
    for (int p = 0; p < LUZ_BENCH_MAX_PARTS && bench->part_names[p] != NULL; p++)
        fprintf(out, " %s=%.3f", bench->part_names[p], luz_median(bench->parts[p], n));
}

void luz_bench_free(luz_bench *bench)
{
    free(bench->wall_ms);
    bench->wall_ms = bench->cpu_ms = NULL;
    for (int p = 0; p < LUZ_BENCH_MAX_PARTS; p++) bench->parts[p] = NULL;
    bench->frames = 0;
}
