/*
 * luz-render: the batch renderer. Renders SCENE.md's scene (or a scene
 * file's) into PNG files, or times it.
 *
 *   luz-render --size 640x360 --time 2 -o lab.png
 *   luz-render --frames 60 --fps 30 -o frames/lab_%04d.png
 *   luz-render --frames 240 --shard 3/8 --skip-existing -o frames/lab_%04d.png
 *   luz-render --frames 60 -o - | ffmpeg -f image2pipe -framerate 30 -i - lab.mp4
 *   luz-render --bench 20 --threads 2
 *   luz-render --probe 700,450                  why pixel (700, 450) has its colour
 *   luz-render --diagnose mine.png --time 2     which light term a student's frame gets wrong
 *
 * The program is a thin shell around libluz: luz_options_parse() reads and
 * checks every option (and the scene file) before anything is rendered, so
 * a bad option never leaves a file behind; the frames are drawn by
 * luz_renderer_draw() and written by luz_framebuffer_write_png(), which
 * writes a temporary file and renames it into place. With -o - the PNGs
 * go to standard output instead, one after another, and nothing else does.
 *
 * Exit status: 0 on success; 2 for a usage error (an option, a scene file or
 * a textures directory that is not right), with one line on stderr; 1 when
 * rendering or writing fails for another reason (out of memory, a disk
 * error). --diagnose has its own: 0 when every light term of the frame is
 * right, 1 when one is not (or rendering failed), 2 for a frame that
 * cannot be compared. docs/cli.md is the user's reference.
 */
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "luz/luz.h"
#include "app/bench.h"
#include "app/controls.h"
#include "app/diagnose.h"
#include "app/options.h"
#include "app/quiz.h"
#include "app/panel.h"
#include "app/probe_report.h"
#include "io/image.h"
#include "io/input_file.h"
#include "io/textures.h"
#include "lab/scene.h"

#ifndef LUZ_VERSION
#error "src/meson.build passes LUZ_VERSION"
#endif

enum {
    EXIT_OK = 0,
    EXIT_RUNTIME = 1,   /* rendering or writing failed */
    EXIT_USAGE = 2,     /* the user asked for something we refuse */
};

static void print_usage(FILE *out)
{
    fprintf(out,
            "Usage: luz-render [OPTION]...\n"
            "Render the luz lighting lab (rotating textured cubes lit by six lights, as\n"
            "SCENE.md describes) into a PNG file, a numbered sequence of them, or a\n"
            "benchmark line. Options take `--name value` or `--name=value`.\n"
            "\n");
    luz_options_print_help(out);
    fprintf(out,
            "\n"
            "Without --textures the images come from $LUZ_TEXTURES if it is set, else from\n"
            "the source tree's textures/ for a luz-render run from its build directory,\n"
            "else from the installed textures.\n"
            "\n"
            "A scene file holds `name = value` lines (the long options without their\n"
            "dashes), `#` comments, and `cube = x, y, z [colour r,g,b] [texture NAME]`\n"
            "lines that replace the cube list. The command line overrides the file.\n"
            "\n"
            "Exit status: 0 on success, 2 for a bad option, scene file or textures\n"
            "directory, 1 if rendering or writing failed.\n");
}

/* ---- rendering -------------------------------------------------------------------- */

/* What every frame needs, made once. */
typedef struct render_context {
    const luz_options *options;
    const luz_texture_set *textures;
    const luz_lab *lab;
    luz_framebuffer *framebuffer;
    luz_frame frame;
    luz_layer layer;       /* --legend and --mark, drawn over every frame */
    bool has_layer;
    int thread_count;      /* the renderer's, for the bands view's legend */
} render_context;

/* The renderer's hook: the legend's and the marks' share of a band. */
static void fill_layer_rows(void *layer, luz_framebuffer *framebuffer, int first_row,
                            int end_row)
{
    luz_layer_draw_rows(layer, framebuffer, first_row, end_row);
}

/* Does the legend depend on the frame? The triangles view's shows as
 * many ids as the frame has triangles (up to 3), known once it is drawn. */
static bool legend_of_the_frame(const luz_options *options)
{
    return options->legend && options->scene.view == LUZ_VIEW_TRIANGLES;
}

/* Records what --legend and --mark draw over the image; they are the same
 * for every frame, but for the legend of a frame of triangle_count
 * triangles (legend_of_the_frame). */
static int record_layer(render_context *context, uint64_t triangle_count, luz_error *error)
{
    const luz_options *options = context->options;
    const bool legend = options->legend && options->scene.view != LUZ_VIEW_COLOR;
    context->has_layer = legend || options->mark_count > 0;
    if (!context->has_layer)
        return 0;
    luz_layer *layer = &context->layer;
    luz_layer_begin(layer, options->width, options->height);
    if (legend) {
        const luz_legend key =
            luz_legend_of(options->scene.view, context->thread_count, triangle_count);
        luz_legend_draw_in_corner(layer, &key);
    }
    /* Rings twice the size in a large image, where a picture is shown
     * scaled down. */
    const int scale = options->width >= 1000 ? 2 : 1;
    for (int i = 0; i < options->mark_count; i++)
        luz_overlay_mark(layer, options->marks[i][0], options->marks[i][1], scale);
    if (luz_layer_finish(layer) != 0)
        return luz_error_set(error, "out of memory for the legend and marks");
    return 0;
}

/* Draws the scene at the given time into the context's framebuffer, and
 * explains the probe's pixel if probe is not NULL. */
static int render_at(render_context *context, luz_renderer *renderer, double time_seconds,
                     luz_frame_stats *stats, luz_pixel_probe *probe, luz_error *error)
{
    luz_scene scene = context->options->scene;
    scene.time_seconds = time_seconds;
    float aspect = (float)context->options->width / (float)context->options->height;
    if (luz_scene_build_frame(context->lab, &scene, context->textures->textures,
                              context->textures->count, aspect, &context->frame, error) != 0)
        return -1;
    luz_render_options render = luz_scene_render_options(&scene);
    /* The legend and marks, filled band by band over the finished rows;
     * a legend of the frame's own is recorded once the frame is drawn,
     * and drawn over the whole image then. */
    const bool after = context->has_layer && legend_of_the_frame(context->options);
    luz_frame_stats own_stats;
    if (after && stats == NULL)
        stats = &own_stats;
    render.stats = stats;
    const luz_band_hook fill_layer = {fill_layer_rows, &context->layer};
    if (context->has_layer && !after)
        render.hook = &fill_layer;
    render.probe = probe;
    /* Only colour is written out: depth and visibility stay in the
     * threads' band buffers. */
    render.colour_only = true;
    if (luz_renderer_draw(renderer, &context->frame, context->framebuffer, &render, error) != 0)
        return -1;
    if (after) {
        if (record_layer(context, stats->triangles_rasterised, error) != 0)
            return -1;
        luz_layer_draw(&context->layer, context->framebuffer);
    }
    return 0;
}

/* --probe X,Y: the frame at --time, drawn once, the pixel's story on
 * standard output, and the PNG only if -o names one: the very image whose
 * pixel the probe read. */
static int render_probe(render_context *context, luz_renderer *renderer, luz_error *error)
{
    const luz_options *options = context->options;
    luz_pixel_probe probe = {.x = options->probe_x, .y = options->probe_y};
    if (render_at(context, renderer, options->scene.time_seconds, NULL, &probe, error) != 0)
        return -1;
    if (options->output_path != NULL &&
        luz_framebuffer_write_png(context->framebuffer, options->output_path, error) != 0)
        return -1;
    const luz_probe_names names = {.scene = &options->scene, .textures = context->textures};
    luz_probe_write(stdout, &probe, &names, options->width, options->height,
                    options->scene.time_seconds);
    return 0;
}

/* seconds as m:ss, or h:mm:ss from an hour */
static void format_duration(char *text, size_t size, double seconds)
{
    long whole = seconds > 0.0 ? (long)(seconds + 0.5) : 0;
    if (whole >= 3600)
        snprintf(text, size, "%ld:%02ld:%02ld", whole / 3600, whole / 60 % 60, whole % 60);
    else
        snprintf(text, size, "%ld:%02ld", whole / 60, whole % 60);
}

/* A bar that redraws itself on one line, with the time so far and the
 * time left at the mean pace of the frames done; only on a terminal,
 * where it helps a person, and never in a log, where it would be noise. */
static void show_progress(int done, int total, double elapsed_seconds)
{
    enum { BAR_WIDTH = 40 };
    int filled = (int)((long long)done * BAR_WIDTH / total);
    fputs("\rluz-render: [", stderr);
    for (int i = 0; i < BAR_WIDTH; i++)
        fputc(i < filled ? '#' : ' ', stderr);
    char elapsed[32], left[32];
    format_duration(elapsed, sizeof elapsed, elapsed_seconds);
    format_duration(left, sizeof left, elapsed_seconds / done * (total - done));
    /* blanks after: a shorter line than the last leaves none of it */
    fprintf(stderr, "] %d/%d frames, %s elapsed, %s left  ", done, total, elapsed, left);
    if (done == total)
        fputc('\n', stderr);
    fflush(stderr);
}

/* Is there a file under path already? Only a regular file counts: luz's
 * own are complete or absent, so one that is there is finished. */
static bool frame_exists(const char *path)
{
    struct stat info;
    return stat(path, &info) == 0 && S_ISREG(info.st_mode);
}

/* Renders frame k of the sequence (frame 0 of a single image) to its file,
 * or to standard output for -o -. With --skip-existing, a frame whose file
 * exists is left as it is. */
static int render_frame(render_context *context, luz_renderer *renderer, int k,
                        luz_error *error)
{
    const luz_options *options = context->options;
    /* the same arithmetic for every run, so that any slice of the sequence
     * gets the whole run's bytes */
    double time_seconds = options->scene.time_seconds + k / options->frames_per_second;
    if (luz_options_output_is_stdout(options)) {
        if (render_at(context, renderer, time_seconds, NULL, NULL, error) != 0)
            return -1;
        return luz_framebuffer_write_png_stream(context->framebuffer, stdout, "standard output",
                                                error);
    }
    char path[4096];
    if (luz_options_output_path(options, k, path, sizeof path, error) != 0)
        return -1;
    if (options->skip_existing && frame_exists(path))
        return 0;
    if (render_at(context, renderer, time_seconds, NULL, NULL, error) != 0 ||
        luz_framebuffer_write_png(context->framebuffer, path, error) != 0)
        return -1;
    return 0;
}

/* Renders the frames of this run: one, a --frames sequence, or the part of
 * it that --frame-range and --shard select (none, for an empty shard). */
static int render_files(render_context *context, luz_renderer *renderer, luz_error *error)
{
    int first, count;
    luz_options_frames_to_render(context->options, &first, &count);
    bool progress = count > 1 && isatty(STDERR_FILENO);
    const double start_ms = luz_wall_ms();
    for (int i = 0; i < count; i++) {
        if (render_frame(context, renderer, first + i, error) != 0) {
            if (progress)
                fputc('\n', stderr);   /* the error goes on its own line */
            return -1;
        }
        if (progress)
            show_progress(i + 1, count, (luz_wall_ms() - start_ms) / 1000.0);
    }
    return 0;
}

/* A frame of the benchmark: the scene at time_seconds, drawn by the
 * renderer the context holds for it. */
typedef struct bench_context {
    render_context *render;
    luz_renderer *renderer;
} bench_context;

static int bench_frame(void *context, double time_seconds, double parts[LUZ_BENCH_MAX_PARTS],
                       luz_error *error)
{
    bench_context *bench = context;
    luz_frame_stats stats;
    if (render_at(bench->render, bench->renderer, time_seconds, &stats, NULL, error) != 0)
        return -1;
    parts[0] = stats.geometry_ms;
    parts[1] = stats.raster_ms;
    parts[2] = (double)stats.memory_bytes / 1048576.0;
    return 0;
}

static int bench(render_context *context, luz_renderer *renderer, luz_error *error)
{
    const luz_options *options = context->options;
    const double start = options->scene.time_seconds;
    const int threads = luz_renderer_thread_count(renderer);
    luz_bench measured = {.part_names = {"geometry_ms", "raster_ms", "renderer_mb"}};

    /* With threads, the same frames on the caller's thread alone first, so
     * that the line says what the threads bought. */
    double single_thread_median = 0.0;
    if (threads > 1) {
        luz_renderer *single = luz_renderer_create(
            &(luz_renderer_desc){.thread_count = 1, .reference = options->reference}, error);
        if (single == NULL)
            return -1;
        int status = luz_bench_run(&measured, options->bench_frames, start,
                                   options->frames_per_second, bench_frame,
                                   &(bench_context){context, single}, error);
        luz_renderer_destroy(single);
        if (status != 0) {
            luz_bench_free(&measured);
            return -1;
        }
        single_thread_median = luz_median(measured.wall_ms, measured.frames);
    }
    if (luz_bench_run(&measured, options->bench_frames, start, options->frames_per_second,
                      bench_frame, &(bench_context){context, renderer}, error) != 0) {
        luz_bench_free(&measured);
        return -1;
    }
    const uint64_t triangles = luz_bench_triangles(&context->frame);
    luz_bench_print_case(stdout, options, measured.frames, options->width, options->height,
                         threads, triangles, luz_renderer_isa(renderer));
    luz_bench_print_figures(stdout, &measured);
    if (triangles > 0)
        printf(" renderer_bytes_per_triangle=%.1f",
               luz_median(measured.parts[2], measured.frames) * 1048576.0 / (double)triangles);
    if (threads > 1) {
        const double median_ms = luz_median(measured.wall_ms, measured.frames);
        printf(" single_thread_median_ms=%.3f speedup=%.2f", single_thread_median,
               median_ms > 0.0 ? single_thread_median / median_ms : 0.0);
    }
    printf("\n");
    luz_bench_free(&measured);
    return 0;
}

/* ---- main ----------------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    luz_options options;
    luz_texture_set textures = {0};
    luz_model_set models = {0};
    luz_renderer *renderer = NULL;
    luz_lab *lab = NULL;
    render_context context = {.options = &options, .textures = &textures};
    luz_error error = {{0}};
    luz_student_frame student = {0};
    bool verdict_given = false;
    int status = EXIT_OK;
    bool answer_wrong = false;

    luz_options_init(&options);
    if (luz_options_parse(&options, argc, argv, &error) != 0) {
        status = EXIT_USAGE;
        goto done;
    }
    if (options.help) {
        print_usage(stdout);
        goto done;
    }
    if (options.version) {
        printf("luz-render %s\n", LUZ_VERSION);
        goto done;
    }
    /* --bug help and --answer NAME --quiz SEED answer without drawing
     * (app/quiz.h); a wrong answer is status 1 with no error line. */
    if (options.bug_help) {
        luz_quiz_print_bugs(stdout);
        goto done;
    }
    if (options.answer_given) {
        answer_wrong = luz_quiz_answer(stdout, options.quiz_seed, options.answer) != 0;
        goto done;
    }
    /* LUZ_ISA names the renderer's instruction set: a bad one is a usage
     * error, refused before any file is read. */
    if (luz_isa_check(&error) != 0) {
        status = EXIT_USAGE;
        goto done;
    }
    if (luz_options_output_is_stdout(&options) && options.bench_frames == 0) {
        /* PNG bytes would garble a terminal; as gzip does, refuse. */
        if (isatty(STDOUT_FILENO)) {
            luz_error_set(&error, "-o -: standard output is a terminal; expected a pipe "
                                  "(| ffmpeg -f image2pipe -i - ...) or a file (> frames.bin)");
            status = EXIT_USAGE;
            goto done;
        }
        /* A reader that quits (ffmpeg, head) makes a write fail with EPIPE:
         * one line and status 1, rather than death by SIGPIPE. */
        signal(SIGPIPE, SIG_IGN);
    }
    /* --diagnose: the student's frame is read first: a file that cannot be
     * compared is the user's error, before anything is rendered; it takes
     * the frame's size unless a size was given, and no output may replace
     * it. */
    if (options.diagnose_path != NULL) {
        int read = luz_student_frame_read(options.diagnose_path, &student, &error);
        if (read == 0 && options.size_given &&
            (student.width != options.width || student.height != options.height))
            read = luz_error_set(&error, "%s: %dx%d pixels; expected the %dx%d of --size (or "
                                         "the scene file's size), the size luz renders",
                                 options.diagnose_path, student.width, student.height,
                                 options.width, options.height);
        if (read == 0)
            read = luz_input_files_add(&options.inputs, options.diagnose_path,
                                       "the frame to diagnose", &error);
        if (read != 0) {
            status = read == LUZ_MACHINE_FAILED ? EXIT_RUNTIME : EXIT_USAGE;
            goto done;
        }
        options.width = student.width;
        options.height = student.height;
    }
    /* The run's texture budget, shared by the cube textures and the
     * models' (io/textures.h). The outputs are checked once every input
     * is known: none may replace a texture, a model or the scene file, nor
     * anything but a regular file; and all before the first frame, so that
     * a refused name leaves no part of a sequence behind. */
    luz_texture_budget budget = {0};
    int loaded = luz_options_load_textures(&options, &textures, &budget, &error);
    if (loaded == 0) loaded = luz_options_load_models(&options, &models, &budget, &error);
    if (loaded == 0 && (luz_options_check_outputs(&options, &error) != 0 ||
                        luz_options_make_output_folders(&options, &error) != 0))
        loaded = -1;
    if (loaded != 0) {
        /* out of memory is the machine's failure, not the input's */
        status = loaded == LUZ_MACHINE_FAILED ? EXIT_RUNTIME : EXIT_USAGE;
        goto done;
    }

    status = EXIT_RUNTIME;
    const luz_renderer_desc desc = luz_options_renderer_desc(&options);
    renderer = luz_renderer_create(&desc, &error);
    if (renderer == NULL)
        goto done;
    lab = luz_lab_create(&error);
    if (lab == NULL)
        goto done;
    context.lab = lab;
    context.framebuffer = luz_framebuffer_create(options.width, options.height, &error);
    if (context.framebuffer == NULL)
        goto done;
    context.thread_count = luz_renderer_thread_count(renderer);
    if (record_layer(&context, 0, &error) != 0)
        goto done;
    if (options.diagnose_path != NULL) {
        const luz_diagnose_setup setup = {.options = &options, .textures = &textures,
                                          .lab = lab, .renderer = renderer,
                                          .frame_name = options.diagnose_path,
                                          .residual_path = options.output_path};
        const int verdict = luz_diagnose(&setup, &student, stdout, &error);
        if (verdict < 0)
            goto done;
        status = verdict;   /* a wrong term is no error message */
        verdict_given = true;
        goto done;
    }
    if ((options.bench_frames > 0 ? bench(&context, renderer, &error)
         : options.probe          ? render_probe(&context, renderer, &error)
                                  : render_files(&context, renderer, &error)) != 0)
        goto done;
    status = EXIT_OK;

done:
    if (status != EXIT_OK && !verdict_given)
        luz_error_print("luz-render", error.message[0] ? error.message : "failed");
    luz_frame_free(&context.frame);
    luz_layer_free(&context.layer);
    if (context.framebuffer != NULL)
        luz_framebuffer_destroy(context.framebuffer);
    if (renderer != NULL)
        luz_renderer_destroy(renderer);
    luz_lab_destroy(lab);
    luz_model_set_free(&models);
    luz_texture_set_free(&textures);
    luz_student_frame_free(&student);
    luz_options_free(&options);
    /* ferror too: a write that failed earlier (--print-state past
     * ulimit -f) leaves nothing for this flush to fail on */
    if ((fflush(stdout) != 0 || ferror(stdout)) && status == EXIT_OK) {
        luz_error_print("luz-render", "cannot write to standard output");
        status = EXIT_RUNTIME;
    }
    return status == EXIT_OK && answer_wrong ? EXIT_RUNTIME : status;
}
