/*
 * test_cli.c: luz-render as a user runs it, and the scene-file functions.
 *
 * Most tests run the real luz-render binary (its path in $LUZ_RENDER, set
 * by tests/meson.build) in a fresh temporary directory, with stdout and
 * stderr captured in files outside that directory, and then look at what a
 * user would see: the exit status, the one line on stderr, and the files
 * left behind. Every refused input must give exit status 2, exactly one
 * line naming the flag (or FILE:LINE) and what was expected, and no file at
 * all: neither the PNG nor the writer's temporary.
 *
 * The work directory holds the same fixtures for every test: tex/ (two
 * small BMP images written by hand here), empty/ (no image), corrupt/ (a
 * .png that is not one), and, per test, a scene file s.luz.
 *
 * The last tests call the option functions directly (linking libluz): the
 * scene-file round trip, precedence, --only, and the -o pattern.
 */
/* posix_openpt and friends, for the progress bar's terminal */
#define _XOPEN_SOURCE 700

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "file_support.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <stb_image.h>

#include "luz/luz.h"
#include "app/bench.h"
#include "app/controls.h"
#include "app/options.h"
#include "app/orbit.h"
#include "app/panel.h"
#include "io/image.h"
#include "io/new_file.h"
#include "io/textures.h"
#include "lab/scene.h"

/* ---- files and directories ----------------------------------------------------- */

static void write_file(const char *path, const void *data, size_t length)
{
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(data, 1, length, file), length);
    assert_int_equal(fclose(file), 0);
}

static void write_text(const char *directory, const char *name, const char *text)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", directory, name);
    write_file(path, text, strlen(text));
}

/* A 24-bit uncompressed BMP, the simplest image format stb_image reads:
 * a 14-byte file header, a 40-byte info header, then rows bottom-up, each
 * padded to a multiple of 4 bytes. */
static void write_bmp(const char *path, int width, int height, uint8_t red, uint8_t green,
                      uint8_t blue)
{
    int row_size = (width * 3 + 3) & ~3;
    int pixel_bytes = row_size * height;
    size_t size = 54 + (size_t)pixel_bytes;
    uint8_t *data = calloc(1, size);
    assert_non_null(data);
    uint32_t header[] = {(uint32_t)size, 0, 54, 40, (uint32_t)width, (uint32_t)height};
    data[0] = 'B';
    data[1] = 'M';
    for (int i = 0; i < 6; i++)
        for (int b = 0; b < 4; b++)
            data[2 + 4 * i + b] = (uint8_t)(header[i] >> (8 * b));
    data[26] = 1;    /* planes */
    data[28] = 24;   /* bits per pixel; compression (30..33) stays 0 */
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            uint8_t *pixel = data + 54 + y * row_size + x * 3;
            /* A checker so that the image is not flat. */
            bool dark = (x + y) % 2;
            pixel[0] = dark ? blue / 2 : blue;
            pixel[1] = dark ? green / 2 : green;
            pixel[2] = dark ? red / 2 : red;
        }
    }
    write_file(path, data, size);
    free(data);
}

/* Is `line` one of the lines of text? */
static bool has_line(const char *text, const char *line, size_t length)
{
    for (const char *start = text; *start != '\0';) {
        const char *end = strchr(start, '\n');
        size_t size = end ? (size_t)(end - start) : strlen(start);
        if (size == length && memcmp(start, line, length) == 0)
            return true;
        if (end == NULL)
            break;
        start = end + 1;
    }
    return false;
}

/* The paths of `after` that are not in `before` are exactly `expected`, a
 * NULL-terminated list: the files a run made, and no temporary beside them. */
static void assert_new_files(const char *before, const char *after, const char *const *expected)
{
    int expected_count = 0;
    while (expected[expected_count] != NULL)
        expected_count++;
    int new_count = 0;
    for (const char *start = after; *start != '\0';) {
        const char *end = strchr(start, '\n');
        size_t length = end ? (size_t)(end - start) : strlen(start);
        if (!has_line(before, start, length)) {
            bool wanted = false;
            for (int i = 0; i < expected_count; i++)
                wanted = wanted || (strlen(expected[i]) == length &&
                                    memcmp(expected[i], start, length) == 0);
            if (!wanted)
                fail_msg("unexpected new file '%.*s'", (int)length, start);
            new_count++;
        }
        if (end == NULL)
            break;
        start = end + 1;
    }
    assert_int_equal(new_count, expected_count);
}

/* ---- running luz-render ------------------------------------------------------------ */

/* A fresh temporary directory: work/ is where luz-render runs, the captured
 * output lies beside it so that work/ holds only what the program made. */
typedef struct sandbox {
    char root[256];
    char work[300];
} sandbox;

static void sandbox_create(sandbox *box)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(box->root, sizeof box->root, "%s/luz-cli-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    assert_non_null(mkdtemp(box->root));
    snprintf(box->work, sizeof box->work, "%s/work", box->root);
    assert_int_equal(mkdir(box->work, 0755), 0);

    char path[600];
    snprintf(path, sizeof path, "%s/tex", box->work);
    assert_int_equal(mkdir(path, 0755), 0);
    snprintf(path, sizeof path, "%s/tex/a.bmp", box->work);
    write_bmp(path, 4, 4, 255, 128, 0);
    snprintf(path, sizeof path, "%s/tex/b.bmp", box->work);
    write_bmp(path, 8, 2, 0, 100, 255);
    snprintf(path, sizeof path, "%s/empty", box->work);
    assert_int_equal(mkdir(path, 0755), 0);
    write_text(path, "readme.txt", "no images here\n");
    snprintf(path, sizeof path, "%s/corrupt", box->work);
    assert_int_equal(mkdir(path, 0755), 0);
    write_text(path, "bad.png", "this is not a PNG file at all");
}

static void sandbox_destroy(sandbox *box)
{
    remove_tree(box->root);
}

static void sandbox_path(const sandbox *box, const char *name, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", box->work, name);
}

typedef struct run_result {
    int status;       /* the exit status, or 128 + signal */
    char *out;        /* stdout */
    size_t out_length;   /* its bytes (it may hold PNGs, NUL bytes and all) */
    char *err;        /* stderr */
    double seconds;
} run_result;


static const char *luz_render_path(void)
{
    const char *program = getenv("LUZ_RENDER");
    if (program == NULL)
        fail_msg("LUZ_RENDER is not set (tests/meson.build sets it to luz-render's path)");
    return program;
}

/* Runs program with the NULL-terminated arguments in box->work.
 * textures_environment sets $LUZ_TEXTURES; NULL unsets it, so that no test
 * depends on the caller's environment. */
/* argv for execv: the program, then the arguments (at most 62 of them),
 * then NULL. */
static void program_argv(const char *program, const char *const *arguments, char *argv[64])
{
    int argc = 0;
    argv[argc++] = (char *)program;
    for (int i = 0; arguments[i] != NULL && argc < 63; i++)
        argv[argc++] = (char *)arguments[i];
    argv[argc] = NULL;
}

static run_result run_program_in(const sandbox *box, const char *program,
                                 const char *const *arguments, const char *textures_environment)
{
    char out_path[400], err_path[400];
    snprintf(out_path, sizeof out_path, "%s/stdout", box->root);
    snprintf(err_path, sizeof err_path, "%s/stderr", box->root);

    char *argv[64];
    program_argv(program, arguments, argv);

    double start = now_seconds();
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int out = open(out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int err = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || chdir(box->work) != 0 || dup2(out, STDOUT_FILENO) < 0 ||
            dup2(err, STDERR_FILENO) < 0)
            _exit(127);
        if (textures_environment)
            setenv("LUZ_TEXTURES", textures_environment, 1);
        else
            unsetenv("LUZ_TEXTURES");
        execv(program, argv);
        _exit(127);
    }
    int status;
    while (waitpid(child, &status, 0) < 0)
        assert_int_equal(errno, EINTR);
    run_result result;
    result.seconds = now_seconds() - start;
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = read_file(out_path, &result.out_length);
    result.err = read_file(err_path, NULL);
    assert_non_null(result.out);
    assert_non_null(result.err);
    return result;
}

/* Runs luz-render, as run_program_in does. */
static run_result run_in(const sandbox *box, const char *const *arguments,
                         const char *textures_environment)
{
    return run_program_in(box, luz_render_path(), arguments, textures_environment);
}

static void run_result_free(run_result *result)
{
    free(result->out);
    free(result->err);
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

static void assert_contains(const char *text, const char *needle)
{
    if (strstr(text, needle) == NULL)
        fail_msg("'%s' lacks '%s'", text, needle);
}

/* Exit status 0 with nothing on stderr; shows stderr if not. */
static void assert_success(const run_result *result)
{
    if (result->status != 0 || result->err[0] != '\0')
        fail_msg("luz-render exited %d, stderr: %s", result->status, result->err);
}

/* The PNG signature, then the IHDR chunk (length 13) whose first eight
 * bytes are the width and height, big-endian (PNG specification 11.2.2). */
static void assert_png_size(const sandbox *box, const char *name, uint32_t width,
                            uint32_t height)
{
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char ihdr[8] = {0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    char path[600];
    size_t length = 0;
    sandbox_path(box, name, path, sizeof path);
    unsigned char *data = (unsigned char *)read_file(path, &length);
    if (data == NULL)
        fail_msg("%s was not written", name);
    assert_true(length >= 33);
    assert_memory_equal(data, signature, 8);
    assert_memory_equal(data + 8, ihdr, 8);
    uint32_t file_width = (uint32_t)data[16] << 24 | (uint32_t)data[17] << 16 |
                          (uint32_t)data[18] << 8 | data[19];
    uint32_t file_height = (uint32_t)data[20] << 24 | (uint32_t)data[21] << 16 |
                           (uint32_t)data[22] << 8 | data[23];
    assert_int_equal(file_width, width);
    assert_int_equal(file_height, height);
    free(data);
}

/* ---- every refused input -------------------------------------------------------------- */

typedef struct error_case {
    const char *name;
    const char *arguments[16];       /* NULL-terminated */
    const char *scene;               /* the text of s.luz, or NULL */
    const char *textures_environment;
    const char *needles[4];          /* each must appear in the one line */
} error_case;

/* Ten copies of a string literal: for a scene line longer than the reader
 * accepts. */
#define TEN(text) text text text text text text text text text text

static const error_case error_cases[] = {
    /* the shape of the command line */
    {"unknown-option", {"--bogus"}, NULL, NULL, {"--bogus", "unknown"}},
    {"unknown-option-with-value", {"--colour=red"}, NULL, NULL, {"--colour", "unknown"}},
    {"unknown-short-option", {"-x"}, NULL, NULL, {"-x", "unknown"}},
    {"stray-argument", {"picture.png"}, NULL, NULL, {"picture.png", "unexpected"}},
    {"missing-value-at-end", {"--size", "16x9", "--time"}, NULL, NULL, {"--time", "missing"}},
    {"missing-value-after-equals", {"--time="}, NULL, NULL, {"--time", "missing"}},
    {"missing-value-empty", {"--textures", ""}, NULL, NULL, {"--textures", "missing"}},
    {"missing-output", {"-o"}, NULL, NULL, {"-o", "missing"}},
    {"flag-with-value", {"--help=yes"}, NULL, NULL, {"--help", "no value"}},
    /* numbers */
    {"time-malformed", {"--time", "abc"}, NULL, NULL, {"--time", "number"}},
    {"time-trailing-junk", {"--time", "1.5s"}, NULL, NULL, {"--time", "number"}},
    {"time-nan", {"--time", "nan"}, NULL, NULL, {"--time", "finite"}},
    {"time-inf", {"--time=-inf"}, NULL, NULL, {"--time", "finite"}},
    {"time-overflow", {"--time", "1e400"}, NULL, NULL, {"--time", "finite"}},
    /* finite, but cube i's angle (i + 1) / 3 * 50 t overflows at 1e302 */
    {"time-beyond-range", {"--time", "1.7e308"}, NULL, NULL,
     {"--time", "[-1000000000, 1000000000]"}},
    {"time-just-beyond-range", {"--time=-1000000000.5"}, NULL, NULL,
     {"--time", "[-1000000000, 1000000000]", "'-1000000000.5'"}},
    {"seed-trailing-junk", {"--seed", "12abc"}, NULL, NULL, {"--seed", "integer"}},
    {"seed-negative", {"--seed", "-1"}, NULL, NULL, {"--seed", "0 to 4294967295"}},
    {"seed-too-large", {"--seed", "4294967296"}, NULL, NULL, {"--seed", "0 to 4294967295"}},
    {"seed-fraction", {"--seed", "1.5"}, NULL, NULL, {"--seed", "integer"}},
    {"camera-pos-two", {"--camera-pos", "1,2"}, NULL, NULL, {"--camera-pos", "x,y,z"}},
    {"camera-pos-four", {"--camera-pos", "1,2,3,4"}, NULL, NULL, {"--camera-pos", "x,y,z"}},
    {"camera-pos-empty-field", {"--camera-pos", "1,,3"}, NULL, NULL, {"--camera-pos", "x,y,z"}},
    {"camera-pos-inf", {"--camera-pos", "0,0,-inf"}, NULL, NULL, {"--camera-pos", "finite"}},
    {"camera-pos-beyond-range", {"--camera-pos", "0,3e38,0"}, NULL, NULL,
     {"--camera-pos", "each in [-10000, 10000]"}},
    {"camera-pos-just-beyond-range", {"--camera-pos", "-10000.01,0,0"}, NULL, NULL,
     {"--camera-pos", "each in [-10000, 10000]"}},
    {"camera-yaw-beyond-float", {"--camera-yaw", "1e39"}, NULL, NULL,
     {"--camera-yaw", "finite"}},
    {"camera-yaw-nan", {"--camera-yaw", "NaN"}, NULL, NULL, {"--camera-yaw", "finite"}},
    /* just past FLT_MAX's rounding range (FLT_MAX's own 3.4028235e38 reads) */
    {"camera-yaw-rounds-to-infinity", {"--camera-yaw", "3.40282357e38"}, NULL, NULL,
     {"--camera-yaw", "finite"}},
    {"paused-not-yes-no", {"--paused", "true"}, NULL, NULL, {"--paused", "yes or no"}},
    {"mark-odd", {"--mark", "10,20,30"}, NULL, NULL, {"--mark", "X,Y"}},
    {"mark-negative", {"--mark", "-1,5"}, NULL, NULL, {"--mark", "X,Y"}},
    {"mark-junk", {"--mark", "10;20"}, NULL, NULL, {"--mark", "X,Y"}},
    {"mark-outside", {"--size", "64x36", "--mark", "10,36"}, NULL, NULL,
     {"--mark", "inside the 64x36 image"}},
    {"mark-too-many", {"--mark", "1,1,2,2,3,3,4,4,5,5,6,6,7,7,8,8,9,9"}, NULL, NULL,
     {"--mark", "at most 8"}},
    {"legend-with-value", {"--legend=yes"}, NULL, NULL, {"--legend", "no value"}},
    {"scene-mark", {"--scene", "s.luz"}, "mark = 1,1\n", NULL, {"s.luz:1", "mark"}},
    {"scene-paused-not-yes-no", {"--scene", "s.luz"}, "paused = 1\n", NULL,
     {"s.luz:1: paused", "yes or no"}},
    {"camera-pitch-above", {"--camera-pitch", "90"}, NULL, NULL,
     {"--camera-pitch", "[-89, 89]"}},
    {"camera-pitch-below", {"--camera-pitch=-89.5"}, NULL, NULL,
     {"--camera-pitch", "[-89, 89]"}},
    {"fov-zero", {"--fov", "0"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-180", {"--fov", "180"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-negative", {"--fov", "-5"}, NULL, NULL, {"--fov", "[1, 179]"}},
    /* the issue's case: a blank image after dividing by tan(fov / 2) = 0 */
    {"fov-denormal", {"--fov", "1e-45"}, NULL, NULL, {"--fov", "[1, 179]", "'1e-45'"}},
    {"fov-below-one", {"--fov", "0.999"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-above-179", {"--fov", "179.001"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-inf", {"--fov=inf"}, NULL, NULL, {"--fov", "finite"}},
    {"shininess-negative", {"--shininess", "-1"}, NULL, NULL, {"--shininess", "[0, 100000]"}},
    {"shininess-beyond-range", {"--shininess", "3e38"}, NULL, NULL,
     {"--shininess", "[0, 100000]"}},
    {"spot-reach-zero", {"--spot-reach", "0"}, NULL, NULL, {"--spot-reach", "[0.1, 10000]"}},
    {"spot-reach-negative", {"--spot-reach", "-2"}, NULL, NULL,
     {"--spot-reach", "[0.1, 10000]"}},
    {"spot-reach-denormal", {"--spot-reach", "1e-45"}, NULL, NULL,
     {"--spot-reach", "[0.1, 10000]"}},
    {"spot-reach-beyond-range", {"--spot-reach", "10001"}, NULL, NULL,
     {"--spot-reach", "[0.1, 10000]"}},
    {"spot-inner-negative", {"--spot-inner", "-1"}, NULL, NULL, {"--spot-inner", "[0, 89]"}},
    {"spot-outer-above", {"--spot-outer", "90"}, NULL, NULL, {"--spot-outer", "[0, 89]"}},
    {"spot-inner-wider-than-default-outer", {"--spot-inner", "20"}, NULL, NULL,
     {"--spot-inner", "--spot-outer"}},
    {"spot-inner-wider-than-outer", {"--spot-inner", "10", "--spot-outer", "5"}, NULL, NULL,
     {"--spot-inner", "--spot-outer"}},
    /* colours and strengths */
    {"ambient-strength-above-one", {"--ambient", "1,1,1,1.5"}, NULL, NULL,
     {"--ambient", "[0, 1]"}},
    {"diffuse-negative", {"--diffuse", "-0.1,1,1,1"}, NULL, NULL, {"--diffuse", "[0, 1]"}},
    {"specular-colour-above-one", {"--specular=2,0,0,1"}, NULL, NULL,
     {"--specular", "[0, 1]"}},
    {"point-three-values", {"--point", "1,1,1"}, NULL, NULL, {"--point", "r,g,b,a"}},
    {"spot-nan", {"--spot", "1,nan,1,1"}, NULL, NULL, {"--spot", "finite"}},
    {"directional-trailing-junk", {"--directional", "1,1,1,1x"}, NULL, NULL,
     {"--directional", "r,g,b,a"}},
    /* sizes */
    {"size-zero", {"--size", "0x5"}, NULL, NULL, {"--size", "at least 1"}},
    {"size-negative", {"--size", "-16x9"}, NULL, NULL, {"--size", "at least 1"}},
    {"size-no-height", {"--size", "1280"}, NULL, NULL, {"--size", "WIDTHxHEIGHT"}},
    {"size-trailing-junk", {"--size", "16x9px"}, NULL, NULL, {"--size", "WIDTHxHEIGHT"}},
    {"size-fraction", {"--size", "16.5x9"}, NULL, NULL, {"--size", "WIDTHxHEIGHT"}},
    {"size-too-wide", {"--size", "16385x1"}, NULL, NULL, {"--size", "16384"}},
    {"size-too-many-pixels", {"--size", "10000x10000"}, NULL, NULL, {"--size", "67108864"}},
    {"size-huge", {"--size", "100000x100000"}, NULL, NULL, {"--size", "supports"}},
    {"size-beyond-int", {"--size", "99999999999999999999x9"}, NULL, NULL,
     {"--size", "supports"}},
    /* counts */
    {"cubes-zero", {"--cubes", "0"}, NULL, NULL, {"--cubes", "from 1 to 100000"}},
    {"cubes-above", {"--cubes", "100001"}, NULL, NULL, {"--cubes", "from 1 to 100000"}},
    {"cubes-fraction", {"--cubes", "2.5"}, NULL, NULL, {"--cubes", "integer"}},
    {"threads-negative", {"--threads", "-1"}, NULL, NULL, {"--threads", "from 0 to 256"}},
    {"threads-above", {"--threads", "257"}, NULL, NULL, {"--threads", "from 0 to 256"}},
    {"fps-zero", {"--fps", "0"}, NULL, NULL, {"--fps", "[0.001, 1000000]"}},
    {"fps-negative", {"--fps", "-30"}, NULL, NULL, {"--fps", "[0.001, 1000000]"}},
    /* frame 1's time would be 1e300 seconds on */
    {"fps-tiny", {"--frames", "2", "--fps", "1e-300", "-o", "f%d.png"}, NULL, NULL,
     {"--fps", "[0.001, 1000000]"}},
    {"fps-beyond-range", {"--fps", "1e7"}, NULL, NULL, {"--fps", "[0.001, 1000000]"}},
    {"frames-zero", {"--frames", "0"}, NULL, NULL, {"--frames", "from 1"}},
    {"frames-negative", {"--frames", "-2"}, NULL, NULL, {"--frames", "from 1"}},
    {"bench-zero", {"--bench", "0"}, NULL, NULL, {"--bench", "from 1"}},
    {"bench-junk", {"--bench", "two"}, NULL, NULL, {"--bench", "integer"}},
    /* names */
    {"filter-unknown", {"--filter", "cubic"}, NULL, NULL, {"--filter", "trilinear"}},
    /* samples a pixel: 1 or 4, nothing else */
    {"samples-zero", {"--samples", "0"}, NULL, NULL, {"--samples", "expected 1 or 4", "'0'"}},
    {"samples-two", {"--samples", "2"}, NULL, NULL, {"--samples", "expected 1 or 4", "'2'"}},
    {"samples-eight", {"--samples", "8"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-negative", {"--samples", "-4"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-trailing-junk", {"--samples", "4x"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-leading-zero", {"--samples", "04"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-empty", {"--samples="}, NULL, NULL, {"--samples", "missing"}},
    {"only-unknown-term", {"--only", "spot,moon"}, NULL, NULL, {"--only", "directional"}},
    {"only-trailing-comma", {"--only", "spot,"}, NULL, NULL, {"--only", "ambient"}},
    /* the -o pattern */
    {"output-frames-without-conversion", {"--frames", "3", "-o", "out.png"}, NULL, NULL,
     {"-o", "%d"}},
    {"output-two-conversions", {"--frames", "2", "-o", "a%d_%d.png"}, NULL, NULL, {"-o", "%d"}},
    {"output-string-conversion", {"-o", "out_%s.png"}, NULL, NULL, {"-o", "%d"}},
    {"output-minus-flag", {"--frames", "2", "-o", "out_%-4d.png"}, NULL, NULL, {"-o", "%d"}},
    {"output-trailing-percent", {"-o", "out%"}, NULL, NULL, {"-o", "%d"}},
    {"output-default-pattern-long-option", {"--frames", "2", "--output", "x%5x.png"}, NULL, NULL,
     {"-o", "%d"}},
    /* what -o may replace: a regular file that is none of the run's inputs */
    {"output-is-a-texture", {"--size", "8x8", "--textures", "tex", "-o", "tex/a.bmp"}, NULL,
     NULL, {"-o: tex/a.bmp: is a texture this run reads", "expected an output file"}},
    {"output-is-a-texture-by-another-name",
     {"--size", "8x8", "--textures", "tex", "-o", "./tex/../tex/b.bmp"}, NULL, NULL,
     {"-o: ./tex/../tex/b.bmp: is a texture this run reads (tex/b.bmp)"}},
    {"output-is-the-scene-file", {"--scene", "s.luz", "-o", "s.luz"},
     "size = 8x8\ntextures = none\n", NULL, {"-o: s.luz: is the scene file this run reads"}},
    {"output-key-is-the-scene-file", {"--scene", "s.luz"},
     "size = 8x8\ntextures = none\noutput = s.luz\n", NULL,
     {"-o: s.luz: is the scene file this run reads"}},
    {"output-is-a-directory", {"--size", "8x8", "--textures", "none", "-o", "tex"}, NULL, NULL,
     {"-o: tex: is a directory", "expected a file name (such as tex/luz.png)"}},
    {"output-is-a-directory-with-slash", {"--size", "8x8", "--textures", "none", "-o", "tex/"},
     NULL, NULL, {"-o: tex/: is a directory", "(such as tex/luz.png)"}},
    {"output-ends-in-slash", {"--size", "8x8", "--textures", "none", "-o", "nowhere/"}, NULL,
     NULL, {"-o: nowhere/: ends in '/'", "(such as nowhere/luz.png)"}},
    /* what the name says: PNG (issue 31) */
    {"output-jpg", {"--size", "8x8", "--textures", "none", "-o", "out.jpg"}, NULL, NULL,
     {"-o: out.jpg: expected a name ending in .png"}},
    {"output-pattern-without-extension", {"--frames", "2", "-o", "f_%04d"}, NULL, NULL,
     {"-o: f_%04d: expected a name ending in .png"}},
    {"output-key-jpeg", {"--scene", "s.luz"}, "size = 8x8\ntextures = none\noutput = a.jpeg\n",
     NULL, {"-o: a.jpeg: expected a name ending in .png"}},
    /* a folder of the path that is a file: refused before any frame */
    {"output-folder-is-a-file", {"--frames", "2", "-o", "corrupt/bad.png/f_%d.png"}, NULL, NULL,
     {"-o: corrupt/bad.png/f_0.png: corrupt/bad.png is not a folder (it is a file)",
      "expected folders that exist or can be made"}},
    /* a slice of a sequence (--frame-range, --shard) and its files */
    {"frame-range-reversed", {"--frames", "24", "--frame-range", "7:3"}, NULL, NULL,
     {"--frame-range", "0 <= A <= B <= 23", "'7:3'"}},
    {"frame-range-past-the-end", {"--frame-range", "0:24", "--frames", "24"}, NULL, NULL,
     {"--frame-range", "0 <= A <= B <= 23", "'0:24'"}},
    {"frame-range-open-start-past-the-end", {"--frames", "24", "--frame-range", "24:"}, NULL,
     NULL, {"--frame-range", "<= 23", "'24:'"}},
    {"frame-range-without-frames", {"--frame-range", "1:1"}, NULL, NULL,
     {"--frame-range", "<= 0", "--frames 1"}},
    {"frame-range-one-number", {"--frames", "24", "--frame-range", "3"}, NULL, NULL,
     {"--frame-range", "A:B", "'3'"}},
    {"frame-range-negative", {"--frames", "24", "--frame-range", "-1:2"}, NULL, NULL,
     {"--frame-range", "A:B"}},
    {"frame-range-three-numbers", {"--frames", "24", "--frame-range", "1:2:3"}, NULL, NULL,
     {"--frame-range", "A:B"}},
    {"frame-range-words", {"--frames", "24", "--frame-range=a:b"}, NULL, NULL,
     {"--frame-range", "A:B"}},
    {"frame-range-missing-value", {"--frames", "24", "--frame-range"}, NULL, NULL,
     {"--frame-range", "missing", "A:B"}},
    {"shard-index-equals-count", {"--frames", "24", "--shard", "4/4"}, NULL, NULL,
     {"--shard", "0 <= K < M", "'4/4'"}},
    {"shard-no-shards", {"--frames", "24", "--shard", "0/0"}, NULL, NULL,
     {"--shard", "0 <= K < M"}},
    {"shard-negative", {"--frames", "24", "--shard", "-1/4"}, NULL, NULL,
     {"--shard", "K/M"}},
    {"shard-no-slash", {"--frames", "24", "--shard", "2"}, NULL, NULL, {"--shard", "K/M"}},
    {"shard-fraction", {"--frames", "24", "--shard", "1.5/4"}, NULL, NULL, {"--shard", "K/M"}},
    {"shard-too-many", {"--frames", "24", "--shard", "0/1000001"}, NULL, NULL,
     {"--shard", "1000000"}},
    {"skip-existing-with-stdout", {"--frames", "2", "-o", "-", "--skip-existing"}, NULL, NULL,
     {"--skip-existing", "-o -", "standard output"}},
    {"skip-existing-with-value", {"--skip-existing=yes"}, NULL, NULL,
     {"--skip-existing", "no value"}},
    {"scene-frame-range-key", {"--scene", "s.luz"}, "frames = 24\nframe-range = 1:2\n", NULL,
     {"s.luz:2", "frame-range", "not allowed"}},
    {"scene-shard-key", {"--scene", "s.luz"}, "shard = 1/4\n", NULL,
     {"s.luz:1", "shard", "not allowed"}},
    {"scene-skip-existing-key", {"--scene", "s.luz"}, "skip-existing = 1\n", NULL,
     {"s.luz:1", "skip-existing", "not allowed"}},
    {"scene-reference-key", {"--scene", "s.luz"}, "reference = 1\n", NULL,
     {"s.luz:1", "reference", "not allowed"}},
    /* --exposure EV and --tonemap clamp|neutral (SCENE.md, "Output") */
    {"exposure-nan", {"--exposure", "nan"}, NULL, NULL, {"--exposure", "finite", "'nan'"}},
    {"exposure-infinite", {"--exposure", "-inf"}, NULL, NULL, {"--exposure", "finite"}},
    {"exposure-above-ten", {"--exposure", "10.5"}, NULL, NULL,
     {"--exposure", "[-10, 10]", "'10.5'"}},
    {"exposure-below-minus-ten", {"--exposure", "-11"}, NULL, NULL, {"--exposure", "[-10, 10]"}},
    {"exposure-word", {"--exposure", "bright"}, NULL, NULL, {"--exposure", "a number"}},
    {"exposure-missing-value", {"--exposure"}, NULL, NULL, {"--exposure", "missing", "EV"}},
    {"tonemap-unknown", {"--tonemap", "aces"}, NULL, NULL,
     {"--tonemap", "clamp or neutral", "'aces'"}},
    {"tonemap-case", {"--tonemap", "Neutral"}, NULL, NULL, {"--tonemap", "clamp or neutral"}},
    {"scene-exposure", {"--scene", "s.luz"}, "\nexposure = 1e3\n", NULL,
     {"s.luz:2", "exposure", "[-10, 10]"}},
    {"scene-tonemap", {"--scene", "s.luz"}, "tonemap = reinhard\n", NULL,
     {"s.luz:1", "tonemap", "clamp or neutral"}},
    /* --up AXIS, with --model only (SCENE.md, "Up axis") */
    {"up-without-model", {"--up", "z"}, NULL, NULL, {"--up", "--model FILE"}},
    {"up-with-cube-lines", {"--scene", "s.luz", "--up", "x"}, "cube = 0, 0, 0\n", NULL,
     {"--up", "--model FILE"}},
    {"up-unknown", {"--up", "+z", "--model", "m.obj"}, NULL, NULL,
     {"--up", "y, z, x, -y, -z or -x", "'+z'"}},
    {"up-missing-value", {"--up"}, NULL, NULL, {"--up", "missing"}},
    {"scene-up-key", {"--scene", "s.luz"}, "up = z\n", NULL, {"s.luz:1", "up", "not allowed"}},
    {"scene-model-up-unknown", {"--scene", "s.luz"}, "\nmodel = m.obj up w\n", NULL,
     {"s.luz:2", "up AXIS", "y, z, x, -y, -z, -x"}},
    {"scene-model-up-twice", {"--scene", "s.luz"}, "model = m.obj up z up x\n", NULL,
     {"s.luz:1", "up AXIS", "once"}},
    /* --probe X,Y */
    {"probe-malformed", {"--probe", "abc"}, NULL, NULL, {"--probe", "X,Y", "'abc'"}},
    {"probe-one-number", {"--probe", "5"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-three-numbers", {"--probe", "1,2,3"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-negative", {"--probe", "-1,5"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-fraction", {"--probe", "1.5,2"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-missing-value", {"--probe"}, NULL, NULL, {"--probe", "missing"}},
    {"probe-right-of-the-image", {"--size", "16x9", "--probe", "16,0"}, NULL, NULL,
     {"--probe", "16x9", "X from 0 to 15", "'16,0'"}},
    {"probe-below-the-image", {"--probe", "0,9", "--size", "16x9"}, NULL, NULL,
     {"--probe", "Y from 0 to 8", "'0,9'"}},
    {"probe-with-bench", {"--probe", "1,1", "--bench", "3"}, NULL, NULL,
     {"--probe", "one frame", "--bench"}},
    {"probe-with-frames", {"--probe", "1,1", "--frames", "2", "-o", "f_%d.png"}, NULL, NULL,
     {"--probe", "one frame", "--frames 2"}},
    {"probe-with-shard", {"--probe", "1,1", "--shard", "0/2"}, NULL, NULL,
     {"--probe", "--shard"}},
    {"probe-with-stdout", {"--probe", "1,1", "-o", "-"}, NULL, NULL, {"--probe", "-o -"}},
    {"scene-probe-key", {"--scene", "s.luz"}, "probe = 1,1\n", NULL,
     {"s.luz:1", "probe", "not allowed"}},
    /* textures */
    {"textures-missing-directory", {"--size", "8x8", "--textures", "nowhere"}, NULL, NULL,
     {"--textures", "nowhere"}},
    {"textures-no-images", {"--size", "8x8", "--textures", "empty"}, NULL, NULL,
     {"--textures", "empty", "image"}},
    {"textures-corrupt-image", {"--size", "8x8", "--textures=corrupt"}, NULL, NULL,
     {"--textures", "bad.png"}},
    {"textures-environment-no-images", {"--size", "8x8"}, NULL, "empty",
     {"LUZ_TEXTURES", "empty"}},
    {"texture-name-unknown", {"--size", "8x8", "--textures", "tex", "--scene", "s.luz"},
     "cube = 0, 0, 0 texture nope.png\n", NULL, {"s.luz:1", "nope.png", "a.bmp"}},
    {"texture-name-with-textures-off", {"--textures", "none", "--scene", "s.luz"},
     "# one cube\ncube = 0, 0, 0 texture a.bmp\n", NULL, {"s.luz:2", "a.bmp"}},
    /* scene files */
    {"scene-missing", {"--scene", "nope.luz"}, NULL, NULL, {"nope.luz", "cannot open"}},
    {"scene-is-a-directory", {"--scene", "tex"}, NULL, NULL, {"tex", "not a regular file"}},
    /* a device would feed the reader forever; a huge line must not grow it */
    {"scene-is-a-device", {"--scene", "/dev/zero"}, NULL, NULL,
     {"/dev/zero", "not a regular file"}},
    /* 16384 characters, and 20000 */
    {"scene-line-too-long", {"--scene", "s.luz"}, "time = 1\n" TEN(TEN(TEN("####################"))),
     NULL, {"s.luz:2", "longer than 16384"}},
    {"scene-texture-name-too-long", {"--scene", "s.luz"},
     "cube = 0, 0, 0 texture " TEN(TEN("abc")) TEN("abcdefgh") "aaaaaa.png\n", NULL,
     {"s.luz:1", "at most 255 bytes"}},
    {"scene-syntax", {"--scene", "s.luz"}, "size = 16x9\nthis is not an option\n", NULL,
     {"s.luz:2", "name = value"}},
    {"scene-empty-name", {"--scene", "s.luz"}, "= 5\n", NULL, {"s.luz:1", "name = value"}},
    {"scene-unknown-key", {"--scene", "s.luz"}, "colour = 1, 0, 0\n", NULL,
     {"s.luz:1", "unknown key", "colour"}},
    {"scene-short-output-key", {"--scene", "s.luz"}, "o = x.png\n", NULL,
     {"s.luz:1", "unknown key"}},
    {"scene-help-key", {"--scene", "s.luz"}, "\n\nhelp = 1\n", NULL, {"s.luz:3", "not allowed"}},
    {"scene-version-key", {"--scene", "s.luz"}, "version = 1\n", NULL,
     {"s.luz:1", "not allowed"}},
    {"scene-scene-key", {"--scene", "s.luz"}, "scene = other.luz\n", NULL,
     {"s.luz:1", "not allowed"}},
    {"scene-bad-value", {"--scene", "s.luz"}, "# a comment\nfov = 200  # too wide\n", NULL,
     {"s.luz:2", "fov", "[1, 179]"}},
    {"scene-malformed-number", {"--scene", "s.luz"}, "seed = 12abc\n", NULL,
     {"s.luz:1", "seed", "integer"}},
    {"scene-missing-value", {"--scene", "s.luz"}, "fov =\n", NULL, {"s.luz:1", "missing"}},
    {"scene-bad-samples", {"--scene", "s.luz"}, "\nsamples = 16\n", NULL,
     {"s.luz:2", "samples", "expected 1 or 4"}},
    {"scene-duplicate-key", {"--scene", "s.luz"}, "seed = 1\nseed = 2\n", NULL,
     {"s.luz:2", "duplicate", "line 1"}},
    {"scene-spot-cone", {"--scene", "s.luz"}, "spot-inner = 30\n", NULL,
     {"--spot-inner", "--spot-outer"}},
    {"scene-cube-duplicate-colour", {"--scene", "s.luz"},
     "cube = 0, 0, 0 colour 1, 0, 0 colour 0, 1, 0\n", NULL, {"s.luz:1", "duplicate colour"}},
    {"scene-cube-duplicate-texture", {"--textures", "tex", "--scene", "s.luz"},
     "cube = 0,0,0 texture a.bmp texture b.bmp\n", NULL, {"s.luz:1", "duplicate texture"}},
    {"scene-cube-unknown-field", {"--scene", "s.luz"}, "cube = 0, 0, 0 shiny\n", NULL,
     {"s.luz:1", "shiny", "colour"}},
    {"scene-cube-two-numbers", {"--scene", "s.luz"}, "\ncube = 0, 0\n", NULL,
     {"s.luz:2", "x,y,z"}},
    {"scene-cube-colour-range", {"--scene", "s.luz"}, "cube = 0,0,0 colour 2, 0, 0\n", NULL,
     {"s.luz:1", "[0, 1]"}},
    {"scene-cube-infinite", {"--scene", "s.luz"}, "cube = inf, 0, 0\n", NULL,
     {"s.luz:1", "finite"}},
    {"scene-cube-beyond-range", {"--scene", "s.luz"}, "\ncube = 0, 0, -3e38\n", NULL,
     {"s.luz:2", "cube", "each in [-10000, 10000]"}},
    {"scene-cube-just-beyond-range", {"--scene", "s.luz"}, "cube = 10000.001, 0, 0\n", NULL,
     {"s.luz:1", "cube", "each in [-10000, 10000]"}},
    {"scene-cube-texture-without-name", {"--scene", "s.luz"}, "cube = 0,0,0 texture\n", NULL,
     {"s.luz:1", "texture NAME"}},
    {"scene-cubes-and-cube-lines", {"--scene", "s.luz"}, "cubes = 20\ncube = 0, 0, 0\n", NULL,
     {"s.luz:2", "cubes"}},
    {"scene-cube-lines-then-cubes", {"--scene", "s.luz"}, "cube = 0, 0, 0\ncubes = 20\n", NULL,
     {"s.luz:2", "cubes"}},
    {"scene-quote-unterminated", {"--scene", "s.luz"}, "seed = 1\ntextures = \"tex # x\n",
     NULL, {"s.luz:2", "textures", "closing \""}},
    {"scene-quote-ends-in-backslash", {"--scene", "s.luz"}, "textures = \"tex\\\n", NULL,
     {"s.luz:1", "textures", "closing \""}},
    {"scene-quote-unknown-escape", {"--scene", "s.luz"}, "textures = \"a\\qb\"\n", NULL,
     {"s.luz:1", "textures", "escape '\\q'", "\\\""}},
    {"scene-quote-junk-after", {"--scene", "s.luz"}, "textures = \"a\" b\n", NULL,
     {"s.luz:1", "textures", "after the closing quote", "'b'"}},
    {"scene-cube-quote-unterminated", {"--scene", "s.luz"},
     "\ncube = 0, 0, 0 texture \"old wood.png colour 1, 0, 0\n", NULL,
     {"s.luz:2", "texture", "closing \""}},
    {"scene-cube-quote-junk-after", {"--scene", "s.luz"},
     "cube = 0, 0, 0 texture \"a\"colour 1, 0, 0\n", NULL,
     {"s.luz:1", "texture", "after the closing quote", "colour"}},
    {"scene-error-before-command-line", {"--size", "8x8", "--scene", "s.luz"}, "time = soon\n",
     NULL, {"s.luz:1", "time", "number"}},
};

#define ERROR_CASE_COUNT (sizeof error_cases / sizeof error_cases[0])

static void test_refused(void **state)
{
    const error_case *test = *state;
    sandbox box;
    sandbox_create(&box);
    if (test->scene != NULL)
        write_text(box.work, "s.luz", test->scene);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);

    run_result result = run_in(&box, test->arguments, test->textures_environment);

    if (result.status != 2)
        fail_msg("exit status %d, expected 2; stderr: %s", result.status, result.err);
    /* exactly one line, with the program's name in front */
    size_t length = strlen(result.err);
    if (length < 2 || result.err[length - 1] != '\n' ||
        strchr(result.err, '\n') != result.err + length - 1)
        fail_msg("stderr is not exactly one line: '%s'", result.err);
    if (strncmp(result.err, "luz-render: ", 12) != 0)
        fail_msg("stderr does not start with 'luz-render: ': %s", result.err);
    for (int i = 0; i < 4 && test->needles[i] != NULL; i++) {
        if (strstr(result.err, test->needles[i]) == NULL)
            fail_msg("stderr lacks '%s': %s", test->needles[i], result.err);
    }
    assert_string_equal(result.out, "");
    /* no PNG, no temporary file, nothing */
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);

    run_result_free(&result);
    sandbox_destroy(&box);
}

/* A NUL byte anywhere in a scene file is refused at its line. fgets took
 * a NUL for the end of its string, so a NUL in a last line without a
 * newline, or a file of one NUL byte, passed unseen. */
static void test_scene_nul_bytes(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        size_t length;
        const char *where;
    } cases[] = {
        {"seed = 1\nfov = 4\0", 17, "s.luz:2: "},            /* the last line, no newline */
        {"\0", 1, "s.luz:1: "},                               /* one NUL byte */
        {"seed = 1\0 2\nfov = 30\n", 21, "s.luz:1: "},       /* within a line */
        {"\ntextures = \"a\0b\"\n", 18, "s.luz:2: "},       /* within quotes */
        {"# c\n\n# x\0", 9, "s.luz:3: "},                    /* after a comment */
        {"seed = 1\n\0\n", 11, "s.luz:2: "},                 /* a line of one NUL */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        sandbox box;
        sandbox_create(&box);
        char path[600], expected[100];
        sandbox_path(&box, "s.luz", path, sizeof path);
        write_file(path, cases[c].text, cases[c].length);
        run_result result = run_in(&box, ARGS("--scene", "s.luz", "--textures", "none"), NULL);
        snprintf(expected, sizeof expected, "luz-render: %sexpected text, found a NUL byte\n",
                 cases[c].where);
        if (result.status != 2 || strcmp(result.err, expected) != 0)
            fail_msg("case %zu: exit %d, stderr '%s'; expected 2 and '%s'", c, result.status,
                     result.err, expected);
        run_result_free(&result);
        sandbox_destroy(&box);
    }
}

/* 100000x100000 would be 130 GB: the refusal must come from the check, at
 * once, not from an allocation that fails (or, worse, succeeds). */
static void test_huge_size_refused_at_once(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "100000x100000", "--textures", "none"), NULL);
    assert_int_equal(result.status, 2);
    if (result.seconds > 2.0)
        fail_msg("took %.2f s to refuse the size", result.seconds);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* ---- long paths come through whole ------------------------------------------------------ */

/* Makes `levels` nested directories under box->work, each named by 250
 * copies of `letter`, and writes their relative path into out. */
static void make_deep_directory(const sandbox *box, char letter, int levels, char *out,
                                size_t size)
{
    char name[251];
    memset(name, letter, 250);
    name[250] = '\0';
    out[0] = '\0';
    for (int level = 0; level < levels; level++) {
        size_t used = strlen(out);
        snprintf(out + used, size - used, "%s%s", level ? "/" : "", name);
        char absolute[4096];
        snprintf(absolute, sizeof absolute, "%s/%s", box->work, out);
        assert_int_equal(mkdir(absolute, 0755), 0);
    }
}

/* Exit status 2 and one line on stderr that holds every needle whole. */
static void assert_refused_naming(const run_result *result, const char *const *needles)
{
    if (result->status != 2)
        fail_msg("exit status %d, expected 2; stderr: %.300s", result->status, result->err);
    size_t length = strlen(result->err);
    assert_true(length > 0 && result->err[length - 1] == '\n');
    assert_ptr_equal(strchr(result->err, '\n'), result->err + length - 1);
    for (int i = 0; needles[i] != NULL; i++) {
        if (strstr(result->err, needles[i]) == NULL)
            fail_msg("stderr (%zu bytes) lacks the whole of the %zu-byte '%.60s...'", length,
                     strlen(needles[i]), needles[i]);
    }
}

/* An error message names its paths whole, however long: a 1506-byte
 * scene path, a 3000-byte model path beside it, a 1506-byte output
 * directory. (luz_error once held 512 bytes and cut them off.) */
static void test_long_paths_come_through_whole(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char scene_directory[2048], model_directory[2048], scene[2100], model_line[2100];
    char model[4096], output[2100];
    make_deep_directory(&box, 's', 6, scene_directory, sizeof scene_directory);
    assert_true(strlen(scene_directory) > 1500);

    /* a bad value in a scene file deep down: FILE:LINE with the whole FILE */
    snprintf(scene, sizeof scene, "%s/s.luz", scene_directory);
    char scene_absolute[4096];
    snprintf(scene_absolute, sizeof scene_absolute, "%s/%s", box.work, scene);
    write_file(scene_absolute, "seed = 1\nfov = 0\n", 17);
    char where[2200];
    snprintf(where, sizeof where, "%s:2: fov", scene);
    run_result result = run_in(&box, ARGS("--scene", scene, "--textures", "none"), NULL);
    assert_refused_naming(&result, ARGS(where, "[1, 179]"));
    run_result_free(&result);

    /* a model that is not there, 1500 more bytes below the scene file's
     * directory: the scene file and the model's absolute path, both whole */
    make_deep_directory(&box, 'm', 6, model_directory, sizeof model_directory);
    snprintf(model_line, sizeof model_line, "model = %s/nothere.obj\n", model_directory);
    write_file(scene_absolute, model_line, strlen(model_line));
    snprintf(where, sizeof where, "%s:1: model", scene);
    snprintf(model, sizeof model, "%s/%s/%s/nothere.obj", box.work, scene_directory,
             model_directory);
    assert_true(strlen(model) > 3000);
    result = run_in(&box, ARGS("--scene", scene, "--textures", "none"), NULL);
    assert_refused_naming(&result, ARGS(where, model));
    run_result_free(&result);

    /* an output folder that is a file (the scene file): exit 2, the path
     * whole */
    snprintf(output, sizeof output, "%s/s.luz/out.png", scene_directory);
    result = run_in(&box, ARGS("--size", "8x8", "--textures", "none", "-o", output), NULL);
    assert_int_equal(result.status, 2);
    if (strstr(result.err, output) == NULL)
        fail_msg("stderr lacks the whole output path: %.300s", result.err);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* luz_error holds three PATH_MAX paths and some words whole; what does not
 * fit ends in "...", so a cut is never silent. */
static void test_error_message_room(void **state)
{
    (void)state;
    char *path = malloc(4096);
    assert_non_null(path);
    memset(path, 'p', 4095);
    path[4095] = '\0';
    luz_error error;
    assert_int_equal(luz_error_set(&error, "%s:12: model: %s: texture '%s': cannot open it",
                                   path, path, path), -1);
    /* 3 x 4095 + the words between, counted by hand: ":12: model: " is 12,
     * ": texture '" 11, "': cannot open it" 17 */
    assert_int_equal(strlen(error.message), 3 * 4095 + 12 + 11 + 17);
    assert_string_equal(error.message + strlen(error.message) - 17, "': cannot open it");

    luz_error_set(&error, "%s%s%s%s%s", path, path, path, path, path);
    assert_int_equal(strlen(error.message), LUZ_ERROR_MESSAGE_SIZE - 1);
    assert_string_equal(error.message + LUZ_ERROR_MESSAGE_SIZE - 4, "...");
    free(path);
}

/* ---- what works ---------------------------------------------------------------------------- */

static void test_help(void **state)
{
    (void)state;
    static const char *const options[] = {
        "--size",         "--time",       "--seed",        "--camera-pos", "--camera-yaw",
        "--camera-pitch", "--fov",        "--ambient",     "--diffuse",    "--specular",
        "--shininess",    "--point",      "--spot",        "--spot-inner", "--spot-outer",
        "--spot-reach",   "--directional", "--filter",     "--textures",   "--cubes",
        "--threads",      "--only",       "-o",            "--frames",     "--fps",
        "--bench",        "--scene",      "--help",        "--version",    "--reference",
        "--view",         "--interp",     "--frame-range", "--shard",     "--skip-existing",
        "--probe",
    };
    /* defaults that SCENE.md and the issue fix */
    static const char *const defaults[] = {
        "1280x720", "default: 0, 0, 3", "default: -90", "default: 45", "default: 1, 1, 1, 0.2",
        "default: 32", "default: 12.5", "default: 17.5", "default: 10", "default: trilinear",
        "default: luz.png", "default: 30", "default: 1, 1, 1, 0.4", "default: color",
        "default: perspective",
    };
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--help"), NULL);
    assert_success(&result);
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++) {
        if (strstr(result.out, options[i]) == NULL)
            fail_msg("--help does not mention %s", options[i]);
    }
    for (size_t i = 0; i < sizeof defaults / sizeof defaults[0]; i++) {
        if (strstr(result.out, defaults[i]) == NULL)
            fail_msg("--help does not show '%s'", defaults[i]);
    }
    run_result_free(&result);
    sandbox_destroy(&box);
}

static void test_version(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--version"), NULL);
    assert_success(&result);
    assert_string_equal(result.out, "luz-render 0.1.0\n");
    run_result_free(&result);
    sandbox_destroy(&box);
}

static void test_tiny_render(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    run_result result = run_in(&box, ARGS("--size", "16x9", "--textures", "none", "-o", "tiny.png"),
                               NULL);
    assert_success(&result);
    assert_string_equal(result.out, "");
    assert_png_size(&box, "tiny.png", 16, 9);
    /* exactly one new file: no temporary left behind */
    list_tree(box.work, "", after, sizeof after);
    assert_new_files(before, after, ARGS("tiny.png"));
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* --name=value works as --name value does, and the default output is luz.png. */
static void test_equals_form_and_default_output(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size=16x9", "--textures=none", "--time=2"), NULL);
    assert_success(&result);
    assert_png_size(&box, "luz.png", 16, 9);
    run_result_free(&result);
    sandbox_destroy(&box);
}

static void test_textures_directory(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "12x10", "--textures", "tex", "-o", "t.png"),
                               NULL);
    assert_success(&result);
    assert_png_size(&box, "t.png", 12, 10);
    run_result_free(&result);

    /* $LUZ_TEXTURES is used without --textures, and --textures beats it */
    result = run_in(&box, ARGS("--size", "10x10", "-o", "env.png"), "tex");
    assert_success(&result);
    assert_png_size(&box, "env.png", 10, 10);
    run_result_free(&result);
    result = run_in(&box, ARGS("--size", "10x10", "--textures", "tex", "-o", "beats.png"), "empty");
    assert_success(&result);
    assert_png_size(&box, "beats.png", 10, 10);
    run_result_free(&result);
    sandbox_destroy(&box);
}


/* --probe X,Y prints the pixel's story and writes no PNG; with -o it
 * writes the image, and bytes= is that image's pixel. The background
 * says object=none and then only bytes=. */
static void test_probe(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    /* the middle of 32x18 is cube 0's front face at t = 0 */
    run_result result = run_in(&box, ARGS("--size", "32x18", "--textures", "tex", "--probe",
                                          "16,9"), NULL);
    assert_success(&result);
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);   /* no file without -o */
    char value[256];
    assert_string_equal(key_value(result.out, "pixel", value, sizeof value), "16,9");
    assert_string_equal(key_value(result.out, "size", value, sizeof value), "32,18");
    assert_string_equal(key_value(result.out, "time", value, sizeof value), "0");
    assert_string_equal(key_value(result.out, "object", value, sizeof value), "0");
    assert_string_equal(key_value(result.out, "mesh", value, sizeof value), "0");
    assert_string_equal(key_value(result.out, "texture", value, sizeof value), "a.bmp");
    assert_string_equal(key_value(result.out, "N", value, sizeof value), "0,0,1");
    assert_contains(result.out, "\ntest=1 object=0 mesh=0 triangle=");
    assert_contains(result.out, " result=pass\n");
    static const char *const keys[] = {"triangle", "barycentric", "w", "P", "uv", "rho",
                                       "lod", "levels", "weight", "texel", "ambient",
                                       "diffuse", "specular", "point", "spot", "directional",
                                       "light", "C", "colour", "exposure", "tonemap",
                                       "exposed", "mapped", "bytes"};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (key_value(result.out, keys[i], value, sizeof value) == NULL)
            fail_msg("no %s= in:\n%s", keys[i], result.out);
    char bytes_without_png[64];
    key_value(result.out, "bytes", bytes_without_png, sizeof bytes_without_png);
    run_result_free(&result);

    /* With -o: the image, and the pixel the probe read is in it. */
    const int probed[2][2] = {{16, 9}, {0, 0}};
    for (int i = 0; i < 2; i++) {
        char pixel[32];
        snprintf(pixel, sizeof pixel, "%d,%d", probed[i][0], probed[i][1]);
        result = run_in(&box, ARGS("--size", "32x18", "--textures", "tex", "--probe", pixel, "-o",
                                   "p.png"), NULL);
        assert_success(&result);
        char path[600];
        sandbox_path(&box, "p.png", path, sizeof path);
        int width, height, channels;
        unsigned char *image = stbi_load(path, &width, &height, &channels, 3);
        assert_non_null(image);
        assert_int_equal(width, 32);
        const unsigned char *p = image + ((size_t)probed[i][1] * width + probed[i][0]) * 3;
        char expected[64];
        snprintf(expected, sizeof expected, "%u,%u,%u", p[0], p[1], p[2]);
        assert_string_equal(key_value(result.out, "bytes", value, sizeof value), expected);
        if (i == 0) {
            assert_string_equal(expected, bytes_without_png);
        } else {
            /* the clear colour, round(0.1 x 255) */
            assert_string_equal(expected, "26,26,26");
            assert_non_null(strstr(result.out, "\nobject=none\nbytes=26,26,26\n"));
            const char *none = strstr(result.out, "object=none");
            assert_string_equal(none, "object=none\nbytes=26,26,26\n");
        }
        stbi_image_free(image);
        run_result_free(&result);
    }

    /* A view: what it shows, and the overdraw it counts is the history's. */
    result = run_in(&box, ARGS("--size", "32x18", "--textures", "none", "--probe", "16,9",
                               "--view", "overdraw"), NULL);
    assert_success(&result);
    assert_string_equal(key_value(result.out, "view", value, sizeof value), "overdraw");
    char tests[32];
    assert_non_null(key_value(result.out, "tests", tests, sizeof tests));
    assert_string_equal(key_value(result.out, "overdraw", value, sizeof value), tests);
    assert_non_null(key_value(result.out, "shown", value, sizeof value));
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* docs/cli.md shows what `luz-render --probe 700,450` prints: it must be
 * what it prints (the default scene, the source tree's textures, which a
 * luz-render of the build tree reads). */
static void test_probe_example_in_the_docs(void **state)
{
    (void)state;
    const char *doc_path = getenv("LUZ_CLI_DOC");
    if (doc_path == NULL) fail_msg("LUZ_CLI_DOC is not set (tests/meson.build sets it)");
    char *doc = read_file(doc_path, NULL);
    assert_non_null(doc);
    const char *command = "$ luz-render --probe 700,450\n";
    const char *start = strstr(doc, command);
    if (start == NULL) fail_msg("%s has no '%s'", doc_path, command);
    start += strlen(command);
    const char *end = strstr(start, "```");
    assert_non_null(end);
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--probe", "700,450"), NULL);
    assert_success(&result);
    if (strlen(result.out) != (size_t)(end - start) ||
        memcmp(result.out, start, (size_t)(end - start)) != 0)
        fail_msg("docs/cli.md's example differs from the output:\n%s", result.out);
    run_result_free(&result);
    sandbox_destroy(&box);
    free(doc);
}

static bool file_exists(const sandbox *box, const char *name)
{
    char path[600];
    struct stat info;
    sandbox_path(box, name, path, sizeof path);
    return stat(path, &info) == 0;
}

static void test_frame_sequence(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    run_result result = run_in(&box,
                               ARGS("--frames", "3", "--fps", "10", "--size", "8x6", "--textures",
                                    "none", "-o", "out_%04d.png"),
                               NULL);
    assert_success(&result);
    assert_string_equal(result.out, "");
    assert_png_size(&box, "out_0000.png", 8, 6);
    assert_png_size(&box, "out_0001.png", 8, 6);
    assert_png_size(&box, "out_0002.png", 8, 6);
    list_tree(box.work, "", after, sizeof after);
    assert_new_files(before, after, ARGS("out_0000.png", "out_0001.png", "out_0002.png"));
    assert_false(file_exists(&box, "out_0003.png"));
    run_result_free(&result);

    /* %% is a percent sign; no -o with --frames gives luz_%04d.png */
    result = run_in(&box, ARGS("--frames", "2", "--size", "8x6", "--textures", "none", "-o",
                               "p%%_%2d.png"),
                    NULL);
    assert_success(&result);
    assert_png_size(&box, "p%_ 0.png", 8, 6);
    assert_png_size(&box, "p%_ 1.png", 8, 6);
    run_result_free(&result);
    result = run_in(&box, ARGS("--frames", "2", "--size", "8x6", "--textures", "none"), NULL);
    assert_success(&result);
    assert_png_size(&box, "luz_0000.png", 8, 6);
    assert_png_size(&box, "luz_0001.png", 8, 6);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* Runs luz-render in box's work directory with arguments (NULL-ended,
 * the program's name left out), with a pseudo-terminal as the descriptor
 * on_terminal (STDOUT_FILENO or STDERR_FILENO) and the other one written to
 * other_path. Reads what the terminal shows until it hangs up (EIO once
 * the child has exited) into text (NUL-ended; *length bytes) and returns
 * the exit status. */
static int run_on_terminal(const sandbox *box, const char *const *arguments, int on_terminal,
                           const char *other_path, char *text, size_t size, size_t *length)
{
    const char *program = getenv("LUZ_RENDER");
    assert_non_null(program);
    int master = posix_openpt(O_RDWR | O_NOCTTY);
    assert_true(master >= 0);
    assert_int_equal(grantpt(master), 0);
    assert_int_equal(unlockpt(master), 0);
    const char *name = ptsname(master);
    assert_non_null(name);
    char terminal[256];
    snprintf(terminal, sizeof terminal, "%s", name);
    char *argv[64] = {(char *)program};
    for (int i = 0; arguments[i] != NULL && i < 62; i++) argv[i + 1] = (char *)arguments[i];

    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int shown = open(terminal, O_RDWR | O_NOCTTY);
        int other = open(other_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int other_fd = on_terminal == STDOUT_FILENO ? STDERR_FILENO : STDOUT_FILENO;
        if (shown < 0 || other < 0 || chdir(box->work) != 0 || dup2(shown, on_terminal) < 0 ||
            dup2(other, other_fd) < 0)
            _exit(127);
        close(master);
        execv(program, argv);
        _exit(127);
    }
    *length = 0;
    for (;;) {
        ssize_t got = read(master, text + *length, size - 1 - *length);
        if (got > 0)
            *length += (size_t)got;
        else if (!(got < 0 && errno == EINTR))
            break;
        if (*length == size - 1)
            break;
    }
    text[*length] = '\0';
    close(master);
    int status;
    assert_int_equal(waitpid(child, &status, 0), child);
    assert_true(WIFEXITED(status));
    return WEXITSTATUS(status);
}

/* On a terminal a sequence draws a progress bar on stderr, redrawn in
 * place with \r; the test gives luz-render a pseudo-terminal as stderr. */
static void test_progress_bar_on_a_terminal(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    const char *arguments[] = {"--frames", "3", "--size", "8x6", "--textures", "none", "-o",
                               "bar_%d.png", NULL};
    char text[4096];
    size_t length;
    assert_int_equal(
        run_on_terminal(&box, arguments, STDERR_FILENO, "/dev/null", text, sizeof text, &length),
        0);
    assert_contains(text, "\rluz-render: [");
    assert_contains(text, "1/3 frames");
    assert_contains(text, "3/3 frames");
    assert_png_size(&box, "bar_2.png", 8, 6);
    sandbox_destroy(&box);
}

static bool files_equal(const sandbox *box, const char *a, const char *b)
{
    char path_a[600], path_b[600];
    size_t length_a = 0, length_b = 0;
    sandbox_path(box, a, path_a, sizeof path_a);
    sandbox_path(box, b, path_b, sizeof path_b);
    char *data_a = read_file(path_a, &length_a), *data_b = read_file(path_b, &length_b);
    assert_non_null(data_a);
    assert_non_null(data_b);
    bool equal = length_a == length_b && memcmp(data_a, data_b, length_a) == 0;
    free(data_a);
    free(data_b);
    return equal;
}

/* Frame k of a sequence is the scene at time + k / fps: the second frame
 * of a sequence from t = 1 at 2 fps is the single frame at t = 1.5. */
static void test_sequence_times(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--frames", "2", "--fps", "2", "--time", "1", "--size",
                                           "48x32", "--textures", "tex", "-o", "seq_%d.png"),
                               NULL);
    assert_success(&result);
    run_result_free(&result);
    result = run_in(&box, ARGS("--time", "1.5", "--size", "48x32", "--textures", "tex", "-o",
                               "single.png"),
                    NULL);
    assert_success(&result);
    run_result_free(&result);
    assert_true(files_equal(&box, "seq_1.png", "single.png"));
    assert_false(files_equal(&box, "seq_0.png", "seq_1.png"));
    sandbox_destroy(&box);
}

static void test_bench(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    run_result result = run_in(&box, ARGS("--bench", "2", "--size", "16x9", "--textures", "none",
                                          "--threads", "1", "--cubes", "20"),
                               NULL);
    assert_success(&result);
    /* one line */
    assert_non_null(strchr(result.out, '\n'));
    assert_string_equal(strchr(result.out, '\n'), "\n");
    static const char *const fields[] = {"frames=2 ", "size=16x9 ", "threads=1 ", "cubes=20 ",
                                         "filter=trilinear ", "median_ms=", "min_ms=", "fps=",
                                         "cpu_ms=", "geometry_ms=", "raster_ms="};
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
        assert_contains(result.out, fields[i]);
    assert_null(strstr(result.out, "speedup="));
    double median_ms = atof(strstr(result.out, "median_ms=") + 10);
    double min_ms = atof(strstr(result.out, "min_ms=") + 7);
    assert_true(median_ms > 0.0);
    assert_true(min_ms > 0.0 && min_ms <= median_ms);
    run_result_free(&result);

    /* with threads, the single-thread comparison */
    result = run_in(&box, ARGS("--bench=2", "--size", "16x9", "--textures", "none", "--threads",
                               "2", "--filter", "nearest"),
                    NULL);
    assert_success(&result);
    assert_contains(result.out, "threads=2 ");
    assert_contains(result.out, "filter=nearest ");
    assert_contains(result.out, "single_thread_median_ms=");
    assert_contains(result.out, "speedup=");
    run_result_free(&result);

    /* no file written */
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

/* The command line overrides the scene file whatever the order. */
static void test_scene_file_and_precedence(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    write_text(box.work, "s.luz",
               "# a small scene\n"
               "size = 20x10\n"
               "textures = none   # all white\n"
               "\n"
               "camera-pos = 0, 0, 4\n");
    run_result result = run_in(&box, ARGS("--scene", "s.luz", "-o", "file.png"), NULL);
    assert_success(&result);
    assert_png_size(&box, "file.png", 20, 10);
    run_result_free(&result);

    result = run_in(&box, ARGS("--size", "16x9", "--scene", "s.luz", "-o", "before.png"), NULL);
    assert_success(&result);
    assert_png_size(&box, "before.png", 16, 9);
    run_result_free(&result);
    result = run_in(&box, ARGS("--scene", "s.luz", "--size=16x9", "-o", "after.png"), NULL);
    assert_success(&result);
    assert_png_size(&box, "after.png", 16, 9);
    run_result_free(&result);

    /* --textures on the command line beats the file's `none` */
    write_text(box.work, "cubes.luz",
               "size = 24x16\n"
               "textures = none\n"
               "cube = 0, 0, 0 colour 1, 0, 0 texture b.bmp\n"
               "cube = 1.5, 0.5, -1   texture a.bmp colour 0, 1, 0.5\n"
               "cube = -1.5, -0.5, -1\n");
    result = run_in(&box, ARGS("--scene", "cubes.luz", "--textures", "tex", "-o", "cubes.png"),
                    NULL);
    assert_success(&result);
    assert_png_size(&box, "cubes.png", 24, 16);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* The options reach the picture: with --only ambient and a black ambient
 * light, every cube is black and the background keeps SCENE.md's clear
 * colour 0.1 (26 of 255); the point light's marker is not drawn since its
 * strength is 0. With the default lights some pixel is something else. */
static void test_options_reach_the_image(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "64x36", "--textures", "none", "--only",
                                          "ambient", "--ambient", "0,0,0,1", "-o", "dark.png"),
                               NULL);
    assert_success(&result);
    run_result_free(&result);
    result = run_in(&box, ARGS("--size", "64x36", "--textures", "none", "-o", "lit.png"), NULL);
    assert_success(&result);
    run_result_free(&result);

    char path[600];
    int width, height, channels;
    sandbox_path(&box, "dark.png", path, sizeof path);
    unsigned char *dark = stbi_load(path, &width, &height, &channels, 3);
    assert_non_null(dark);
    assert_int_equal(width, 64);
    assert_int_equal(height, 36);
    int black = 0, background = 0;
    for (int i = 0; i < width * height; i++) {
        const unsigned char *p = dark + 3 * i;
        if (p[0] == 0 && p[1] == 0 && p[2] == 0)
            black++;
        else if (p[0] == 26 && p[1] == 26 && p[2] == 26)
            background++;
        else
            fail_msg("pixel %d is %d,%d,%d: neither black cube nor background", i, p[0], p[1],
                     p[2]);
    }
    assert_true(black > 0);
    assert_true(background > 0);
    stbi_image_free(dark);

    sandbox_path(&box, "lit.png", path, sizeof path);
    unsigned char *lit = stbi_load(path, &width, &height, &channels, 3);
    assert_non_null(lit);
    int other = 0;
    for (int i = 0; i < width * height * 3; i++)
        other += lit[i] != 0 && lit[i] != 26;
    assert_true(other > 0);
    stbi_image_free(lit);
    sandbox_destroy(&box);
}

/* Renders args into NAME.png in the box and loads it as RGB. */
static unsigned char *render_and_load(const sandbox *box, const char *const *arguments,
                                      const char *name, int width, int height)
{
    run_result result = run_in(box, arguments, NULL);
    assert_success(&result);
    run_result_free(&result);
    char path[600];
    int w, h, channels;
    sandbox_path(box, name, path, sizeof path);
    unsigned char *image = stbi_load(path, &w, &h, &channels, 3);
    assert_non_null(image);
    assert_int_equal(w, width);
    assert_int_equal(h, height);
    return image;
}

static bool same_pixel(const unsigned char *a, const unsigned char *b, int width, int x, int y)
{
    return memcmp(a + 3 * ((size_t)y * width + x), b + 3 * ((size_t)y * width + x), 3) == 0;
}

static void assert_rgb(const unsigned char *image, int width, int x, int y, int r, int g, int b)
{
    const unsigned char *p = image + 3 * ((size_t)y * width + x);
    if (p[0] != r || p[1] != g || p[2] != b)
        fail_msg("pixel (%d, %d) is (%d, %d, %d), expected (%d, %d, %d)", x, y, p[0], p[1],
                 p[2], r, g, b);
}

/* --exposure and --tonemap reach the image, worked by hand: a white cube
 * lit by the ambient light alone at strength 0.5 is 0.5 everywhere, byte
 * round(127.5) = 128. EV 1 doubles it to 1 (255), EV -1 halves it to 0.25
 * (63.75: 64). Neutral at EV 0 takes off 0.04 (0.46: 117.3, 117); at
 * EV 1, white: 1 - 0.04 = 0.96, compressed to 1 - 0.0576 / 0.44 =
 * 0.8690909 (221.6: 222). The background stays 26 whatever the output.
 * The same keys in a scene file give the same image. */
static void test_exposure_and_tone_map_reach_the_image(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    write_text(box.work, "white.luz",
               "size = 32x18\ntextures = none\nonly = ambient\nambient = 1, 1, 1, 0.5\n"
               "cube = 0, 0, 0 colour 1, 1, 1\n");
    static const struct {
        const char *exposure, *tone_map;
        int byte;
    } cases[] = {
        {"0", "clamp", 128},   {"1", "clamp", 255},    {"-1", "clamp", 64},
        {"0", "neutral", 117}, {"1", "neutral", 222},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        unsigned char *image = render_and_load(
            &box,
            ARGS("--scene", "white.luz", "--exposure", cases[i].exposure, "--tonemap",
                 cases[i].tone_map, "-o", "out.png"),
            "out.png", 32, 18);
        assert_rgb(image, 32, 16, 9, cases[i].byte, cases[i].byte, cases[i].byte);
        assert_rgb(image, 32, 0, 0, 26, 26, 26);
        stbi_image_free(image);
    }
    /* The probe at the cube's centre pixel, worked by hand: colour 0.5
     * (ambient 0.5 x C 1 x T 1), exposure 1, tonemap neutral, exposed
     * 0.5 x 2 = 1, mapped 1 - 0.0576 / 0.44 = 0.8690909 after the offset
     * 0.04, bytes 222. */
    run_result probed = run_in(&box,
                               ARGS("--scene", "white.luz", "--exposure", "1", "--tonemap",
                                    "neutral", "--probe", "16,9"),
                               NULL);
    assert_success(&probed);
    char value[256];
    assert_string_equal(key_value(probed.out, "colour", value, sizeof value), "0.5,0.5,0.5");
    assert_string_equal(key_value(probed.out, "exposure", value, sizeof value), "1");
    assert_string_equal(key_value(probed.out, "tonemap", value, sizeof value), "neutral");
    assert_string_equal(key_value(probed.out, "exposed", value, sizeof value), "1,1,1");
    key_value(probed.out, "mapped", value, sizeof value);
    float mapped[3];
    assert_int_equal(sscanf(value, "%f,%f,%f", &mapped[0], &mapped[1], &mapped[2]), 3);
    for (int c = 0; c < 3; c++) assert_true(fabsf(mapped[c] - 0.8690909f) < 1e-6f);
    assert_string_equal(key_value(probed.out, "bytes", value, sizeof value), "222,222,222");
    /* the lines in this order, after colour */
    assert_non_null(strstr(probed.out, "\ncolour=0.5,0.5,0.5\nexposure=1\ntonemap=neutral\n"
                                       "exposed=1,1,1\nmapped="));
    run_result_free(&probed);
    /* and clamp at EV -1: exposed = mapped = 0.25, bytes 64 */
    probed = run_in(&box, ARGS("--scene", "white.luz", "--exposure", "-1", "--probe", "16,9"),
                    NULL);
    assert_success(&probed);
    assert_string_equal(key_value(probed.out, "tonemap", value, sizeof value), "clamp");
    assert_string_equal(key_value(probed.out, "exposed", value, sizeof value), "0.25,0.25,0.25");
    assert_string_equal(key_value(probed.out, "mapped", value, sizeof value), "0.25,0.25,0.25");
    assert_string_equal(key_value(probed.out, "bytes", value, sizeof value), "64,64,64");
    run_result_free(&probed);

    write_text(box.work, "neutral.luz",
               "size = 32x18\ntextures = none\nonly = ambient\nambient = 1, 1, 1, 0.5\n"
               "cube = 0, 0, 0 colour 1, 1, 1\nexposure = 1\ntonemap = neutral\n");
    unsigned char *image = render_and_load(&box, ARGS("--scene", "neutral.luz", "-o", "out.png"),
                                           "out.png", 32, 18);
    assert_rgb(image, 32, 16, 9, 222, 222, 222);
    stbi_image_free(image);
    sandbox_destroy(&box);
}

/* --mark rings a pixel and leaves it and the pixels around it as rendered:
 * along the marked row, the ring is black 8 pixels out, white 7 and 6, and
 * black 5 (at an image under 1000 wide); 4 pixels out and nearer nothing
 * changes. --legend draws the view's key bottom left and nothing else;
 * with the colour view it draws nothing at all. */
static void test_mark_and_legend(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    enum { W = 160, H = 90, X = 80, Y = 50 };
    unsigned char *plain = render_and_load(
        &box, ARGS("--size", "160x90", "--textures", "none", "-o", "plain.png"), "plain.png", W, H);
    unsigned char *marked = render_and_load(
        &box, ARGS("--size", "160x90", "--textures", "none", "--mark", "80,50", "-o", "marked.png"),
        "marked.png", W, H);
    for (int dy = -4; dy <= 4; dy++)
        for (int dx = -4; dx <= 4; dx++)
            if (!same_pixel(plain, marked, W, X + dx, Y + dy))
                fail_msg("--mark changed pixel (%d, %d), inside its ring", X + dx, Y + dy);
    for (int side = -1; side <= 1; side += 2) {
        assert_rgb(marked, W, X + side * 8, Y, 0, 0, 0);
        assert_rgb(marked, W, X + side * 7, Y, 255, 255, 255);
        assert_rgb(marked, W, X + side * 6, Y, 255, 255, 255);
        assert_rgb(marked, W, X + side * 5, Y, 0, 0, 0);
        assert_rgb(marked, W, X, Y + side * 8, 0, 0, 0);
    }
    /* far from the ring and its ticks: untouched */
    assert_true(same_pixel(plain, marked, W, 10, 10));
    assert_true(same_pixel(plain, marked, W, 150, 80));

    /* The legend: only in the bottom-left corner, only for a view. */
    enum { LW = 320, LH = 180 };
    unsigned char *mip = render_and_load(
        &box, ARGS("--size", "320x180", "--textures", "none", "--view", "mip", "-o", "mip.png"),
        "mip.png", LW, LH);
    unsigned char *keyed = render_and_load(
        &box,
        ARGS("--size", "320x180", "--textures", "none", "--view", "mip", "--legend", "-o",
             "keyed.png"),
        "keyed.png", LW, LH);
    int changed_bottom = 0;
    for (int y = 0; y < LH; y++) {
        for (int x = 0; x < LW; x++) {
            bool same = same_pixel(mip, keyed, LW, x, y);
            if ((y < LH / 2 || x > LW - 6) && !same)
                fail_msg("--legend changed pixel (%d, %d), outside the bottom left", x, y);
            changed_bottom += !same;
        }
    }
    assert_true(changed_bottom > 2000);
    unsigned char *colour_keyed = render_and_load(
        &box, ARGS("--size", "160x90", "--textures", "none", "--legend", "-o", "colour.png"),
        "colour.png", W, H);
    assert_memory_equal(colour_keyed, plain, (size_t)W * H * 3);

    stbi_image_free(plain);
    stbi_image_free(marked);
    stbi_image_free(mip);
    stbi_image_free(keyed);
    stbi_image_free(colour_keyed);
    sandbox_destroy(&box);
}

/* ---- the option functions, in process ------------------------------------------------------- */

static void assert_float_same(float a, float b)
{
    if (memcmp(&a, &b, sizeof a) != 0)
        fail_msg("%.9g != %.9g", (double)a, (double)b);
}

static void assert_light_same(const luz_light *a, const luz_light *b)
{
    assert_float_same(a->colour.x, b->colour.x);
    assert_float_same(a->colour.y, b->colour.y);
    assert_float_same(a->colour.z, b->colour.z);
    assert_float_same(a->strength, b->strength);
}

/* Everything luz_options_write_scene promises to keep. */
static void assert_scene_options_equal(const luz_options *a, const luz_options *b)
{
    assert_int_equal(a->width, b->width);
    assert_int_equal(a->height, b->height);
    assert_memory_equal(&a->scene.time_seconds, &b->scene.time_seconds, sizeof(double));
    assert_int_equal(a->scene.seed, b->scene.seed);
    assert_float_same(a->scene.camera.position.x, b->scene.camera.position.x);
    assert_float_same(a->scene.camera.position.y, b->scene.camera.position.y);
    assert_float_same(a->scene.camera.position.z, b->scene.camera.position.z);
    assert_float_same(a->scene.camera.yaw_degrees, b->scene.camera.yaw_degrees);
    assert_float_same(a->scene.camera.pitch_degrees, b->scene.camera.pitch_degrees);
    assert_float_same(a->scene.camera.fov_degrees, b->scene.camera.fov_degrees);
    const luz_lights *la = &a->scene.lights, *lb = &b->scene.lights;
    assert_light_same(&la->ambient, &lb->ambient);
    assert_light_same(&la->diffuse, &lb->diffuse);
    assert_light_same(&la->specular, &lb->specular);
    assert_light_same(&la->point, &lb->point);
    assert_light_same(&la->spot, &lb->spot);
    assert_light_same(&la->directional, &lb->directional);
    assert_float_same(la->shininess, lb->shininess);
    assert_float_same(la->spot_inner_degrees, lb->spot_inner_degrees);
    assert_float_same(la->spot_outer_degrees, lb->spot_outer_degrees);
    assert_float_same(la->spot_reach, lb->spot_reach);
    assert_int_equal(a->scene.filter, b->scene.filter);
    assert_int_equal(a->scene.view, b->scene.view);
    assert_int_equal(a->scene.interpolation, b->scene.interpolation);
    assert_float_same(luz_options_output(a).exposure, luz_options_output(b).exposure);
    assert_int_equal(luz_options_output(a).tone_map, luz_options_output(b).tone_map);
    if (a->textures_directory == NULL || b->textures_directory == NULL)
        assert_ptr_equal(a->textures_directory, b->textures_directory);
    else
        assert_string_equal(a->textures_directory, b->textures_directory);
    assert_int_equal(a->scene.object_count, b->scene.object_count);
    if (a->scene.object_count == 0)
        assert_int_equal(a->scene.cube_count, b->scene.cube_count);
    for (int i = 0; i < a->scene.object_count; i++) {
        const luz_object *ca = &a->scene.objects[i], *cb = &b->scene.objects[i];
        assert_float_same(ca->position.x, cb->position.x);
        assert_float_same(ca->position.y, cb->position.y);
        assert_float_same(ca->position.z, cb->position.z);
        assert_int_equal(ca->has_colour, cb->has_colour);
        if (ca->has_colour) {
            assert_float_same(ca->colour.x, cb->colour.x);
            assert_float_same(ca->colour.y, cb->colour.y);
            assert_float_same(ca->colour.z, cb->colour.z);
        }
        const char *na = a->object_sources[i].texture_name, *nb = b->object_sources[i].texture_name;
        if (na == NULL || nb == NULL)
            assert_ptr_equal(na, nb);
        else
            assert_string_equal(na, nb);
    }
}

static void write_scene_to(const luz_options *options, const char *path)
{
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    luz_options_write_scene(options, file);
    assert_int_equal(fclose(file), 0);
}

static void read_scene_from(luz_options *options, const char *path)
{
    luz_error error = {{0}};
    luz_options_init(options);
    if (luz_options_read_scene_file(options, path, &error) != 0 ||
        luz_options_finish(options, &error) != 0)
        fail_msg("reading %s back: %s", path, error.message);
}

static void parse_or_fail(luz_options *options, int argc, char **argv)
{
    luz_error error = {{0}};
    luz_options_init(options);
    if (luz_options_parse(options, argc, argv, &error) != 0)
        fail_msg("%s", error.message);
}

/* The viewer's orbit camera end to end: a view set through the controls
 * (the scene framed, turned round its target, dollied), saved as F2 saves
 * it, is rendered by luz-render to the very bytes of the viewer's frame
 * (the scene drawn in this process as luz_viewer.c's draw_frame draws it,
 * without its HUD). The orbit's view is not the default one, so the check
 * would catch a camera saved from the wrong place. */
static void test_orbit_view_renders_the_same_in_luz_render(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char textures_path[600], scene_path[600];
    sandbox_path(&box, "tex", textures_path, sizeof textures_path);
    sandbox_path(&box, "orbit.luz", scene_path, sizeof scene_path);
    enum { WIDTH = 96, HEIGHT = 54 };
    const float aspect = (float)WIDTH / (float)HEIGHT;

    luz_options options;
    char *argv[] = {"luz", "--size", "96x54", "--textures", textures_path, "--time", "1.25",
                    NULL};
    parse_or_fail(&options, 7, argv);
    luz_error error = {{0}};
    luz_texture_set textures = {0};
    assert_int_equal(luz_options_load_textures(&options, &textures, NULL, &error), 0);

    luz_scene *scene = &options.scene;
    luz_orbit orbit = luz_orbit_from_camera(&scene->camera, (luz_vec3){0.0f, 0.0f, 0.0f});
    luz_orbit_frame(&orbit, &scene->camera, luz_scene_bounding_sphere(scene), aspect);
    luz_orbit_turn(&orbit, &scene->camera, 157.0f, -63.0f);
    luz_orbit_dolly(&orbit, &scene->camera, 3.0f);
    assert_true(scene->camera.yaw_degrees != -90.0f && scene->camera.pitch_degrees != 0.0f);

    /* The viewer's frame. */
    const luz_renderer_desc desc = luz_options_renderer_desc(&options);
    luz_renderer *renderer = luz_renderer_create(&desc, &error);
    luz_lab *lab = luz_lab_create(&error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(renderer);
    assert_non_null(lab);
    assert_non_null(framebuffer);
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(lab, scene, textures.textures, textures.count, aspect,
                                           &frame, &error),
                     0);
    const luz_render_options render = luz_scene_render_options(scene);
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &render, &error), 0);

    /* F2's file, rendered by luz-render. */
    assert_int_equal(luz_options_save_scene(&options, scene_path, false, &error), 0);
    unsigned char *saved = render_and_load(&box, ARGS("--scene", "orbit.luz", "-o", "orbit.png"),
                                           "orbit.png", WIDTH, HEIGHT);
    int differing = 0;
    for (int i = 0; i < WIDTH * HEIGHT; i++)
        differing += memcmp(saved + 3 * i, framebuffer->colour + 4 * i, 3) != 0;
    assert_int_equal(differing, 0);

    /* and the default camera's picture is another one */
    unsigned char *start = render_and_load(
        &box, ARGS("--size", "96x54", "--textures", "tex", "--time", "1.25", "-o", "start.png"),
        "start.png", WIDTH, HEIGHT);
    differing = 0;
    for (int i = 0; i < WIDTH * HEIGHT; i++)
        differing += memcmp(start + 3 * i, saved + 3 * i, 3) != 0;
    assert_true(differing > WIDTH * HEIGHT / 4);

    stbi_image_free(start);
    stbi_image_free(saved);
    luz_frame_free(&frame);
    luz_framebuffer_destroy(framebuffer);
    luz_lab_destroy(lab);
    luz_renderer_destroy(renderer);
    luz_texture_set_free(&textures);
    luz_options_free(&options);
    sandbox_destroy(&box);
}

/* Every value that is not the shortest decimal of its float (0.1, 1/3,
 * 12345.678) must come back with the same bits. */
static void test_scene_round_trip(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char *argv[] = {
        "luz-render",     "--size",        "33x17",      "--time",
        "1.2345678901234567", "--seed",    "4294967295", "--camera-pos",
        "0.1,-2.5e-3,3.3333333", "--camera-yaw", "-100.7", "--camera-pitch",
        "-88.9",          "--fov",         "33.333333",  "--ambient",
        "0.1,0.2,0.3,0.4", "--diffuse",    "0.7,0.11,0.13,0.6", "--specular",
        "1,0.5,0.25,0.125", "--shininess", "12345.678",  "--point",
        "0.3,0.3,0.9,0.7", "--spot",       "1,1,0.9,1",  "--spot-inner",
        "5.5",            "--spot-outer",  "20.25",      "--spot-reach",
        "7.7",            "--directional", "0.9,0.8,0.7,0.33333334", "--filter",
        "nearest",        "--textures",    "some/dir",   "--cubes",
        "25",             "--only",        "ambient,spot,point,directional,diffuse",
    };
    luz_options original, copy, again;
    parse_or_fail(&original, (int)(sizeof argv / sizeof argv[0]), argv);
    assert_float_same(original.scene.lights.specular.strength, 0.0f);   /* --only */

    char first[600], second[600];
    snprintf(first, sizeof first, "%s/first.luz", box.root);
    snprintf(second, sizeof second, "%s/second.luz", box.root);
    write_scene_to(&original, first);
    read_scene_from(&copy, first);
    assert_scene_options_equal(&original, &copy);
    /* and writing the copy gives the same text */
    write_scene_to(&copy, second);
    char *text_first = read_file(first, NULL), *text_second = read_file(second, NULL);
    assert_string_equal(text_first, text_second);
    free(text_first);
    free(text_second);
    luz_options_free(&copy);
    luz_options_free(&original);

    /* custom cubes: colours and texture names survive */
    char scene[600];
    snprintf(scene, sizeof scene, "%s/cubes.luz", box.root);
    write_text(box.root, "cubes.luz",
               "cube = 0.1, 0.2, 0.3 colour 0.1, 0.7, 1 texture wood.png\n"
               "cube = -1, 2, -3.75 texture stone.png\n"
               "cube = 5, 5, 5 colour 0, 0, 0.333\n"
               "cube = 1e-3, 0, 0\n"
               "seed = 7\n");
    read_scene_from(&original, scene);
    assert_int_equal(original.scene.object_count, 4);
    assert_ptr_equal(original.scene.objects, original.objects);
    write_scene_to(&original, first);
    read_scene_from(&again, first);
    assert_scene_options_equal(&original, &again);
    assert_string_equal(again.object_sources[0].texture_name, "wood.png");
    assert_null(again.object_sources[2].texture_name);
    luz_options_free(&again);
    luz_options_free(&original);
    sandbox_destroy(&box);
}

/* Gives options the custom cubes i at (i, 0, 0), cube i with texture
 * names[i], built here rather than read from a file, so that the reader
 * under test is not also what set them up. */
static void set_named_cubes(luz_options *options, const char *const *names, int count)
{
    luz_options_clear_objects(options);
    options->objects = calloc((size_t)count, sizeof *options->objects);
    options->object_sources = calloc((size_t)count, sizeof *options->object_sources);
    assert_non_null(options->objects);
    assert_non_null(options->object_sources);
    options->object_capacity = count;
    for (int i = 0; i < count; i++) {
        options->objects[i] = (luz_object){.position = luz_vec3_make((float)i, 0.0f, 0.0f),
                                       .texture = LUZ_TEXTURE_BY_INDEX};
        options->object_sources[i].texture_name = strdup(names[i]);
        assert_non_null(options->object_sources[i].texture_name);
    }
    options->scene.objects = options->objects;
    options->scene.object_count = count;
}

/* What luz_options_write_scene writes for options, as one string. */
static char *scene_text(const luz_options *options)
{
    char *text = NULL;
    size_t length = 0;
    FILE *stream = open_memstream(&text, &length);
    assert_non_null(stream);
    luz_options_write_scene(options, stream);
    assert_int_equal(fclose(stream), 0);
    assert_non_null(text);
    return text;
}

/* Every option set by hand to a value that is not its default (docs/cli.md's
 * defaults column), the scene's and the run's alike. The struct is filled
 * directly, so that the parser is not also what sets the test up. */
static void set_every_option_by_hand(luz_options *options)
{
    luz_options_init(options);
    options->width = 640;
    options->height = 360;
    options->scene.time_seconds = 2.75;
    options->scene.seed = 12345;
    options->scene.cube_count = 25;
    options->scene.camera.position = luz_vec3_make(0.5f, -1.25f, 4.0f);
    options->scene.camera.yaw_degrees = -100.7f;
    options->scene.camera.pitch_degrees = 12.5f;
    options->scene.camera.fov_degrees = 60.0f;
    luz_lights *lights = &options->scene.lights;
    lights->ambient = (luz_light){.colour = luz_vec3_make(0.1f, 0.2f, 0.3f), .strength = 0.4f};
    lights->diffuse = (luz_light){.colour = luz_vec3_make(0.5f, 0.6f, 0.7f), .strength = 0.25f};
    lights->specular = (luz_light){.colour = luz_vec3_make(1.0f, 0.5f, 0.0f), .strength = 0.75f};
    lights->shininess = 64.0f;
    lights->point = (luz_light){.colour = luz_vec3_make(0.3f, 0.3f, 0.9f), .strength = 0.1f};
    lights->spot = (luz_light){.colour = luz_vec3_make(1.0f, 1.0f, 0.9f), .strength = 0.5f};
    lights->spot_inner_degrees = 5.5f;
    lights->spot_outer_degrees = 20.25f;
    lights->spot_reach = 7.5f;
    lights->directional = (luz_light){.colour = luz_vec3_make(0.9f, 0.8f, 0.7f), .strength = 0.2f};
    options->scene.filter = LUZ_FILTER_NEAREST;
    options->scene.samples = 4;
    options->scene.view = LUZ_VIEW_DEPTH;
    options->scene.interpolation = LUZ_INTERPOLATION_AFFINE;
    options->paused = true;
    options->scene.has_exposure = options->scene.has_tone_map = true;
    options->scene.exposure = -2.5f;
    options->scene.tone_map = LUZ_TONE_MAP_NEUTRAL;
    options->textures_directory = strdup("hand/textures");
    assert_non_null(options->textures_directory);
    /* and what a scene file does not keep (docs/cli.md, Writing scene
     * files): --only (its effect is in the strengths, which are set above
     * and not zeroed, since luz_options_finish is not called) and a run's
     * settings */
    options->only_terms = 1u << LUZ_TERM_SPOT;
    options->thread_count = 3;
    options->output_path = strdup("hand_%02d.png");
    assert_non_null(options->output_path);
    options->frame_count = 4;
    options->frames_per_second = 12.0;
    options->bench_frames = 5;
    options->reference = true;
}

/* The text of set_every_option_by_hand's options, written out by hand from
 * docs/cli.md's format: the keys in the order saved files have always had,
 * view, interp and paused last as the settings written only when changed. */
static const char every_option_text[] =
    "# luz scene: render it with luz-render --scene FILE (see docs/cli.md)\n"
    "size = 640x360\n"
    "time = 2.75\n"
    "seed = 12345\n"
    "cubes = 25\n"
    "camera-pos = 0.5, -1.25, 4\n"
    "camera-yaw = -100.7\n"
    "camera-pitch = 12.5\n"
    "fov = 60\n"
    "ambient = 0.1, 0.2, 0.3, 0.4\n"
    "diffuse = 0.5, 0.6, 0.7, 0.25\n"
    "specular = 1, 0.5, 0, 0.75\n"
    "shininess = 64\n"
    "point = 0.3, 0.3, 0.9, 0.1\n"
    "spot = 1, 1, 0.9, 0.5\n"
    "spot-inner = 5.5\n"
    "spot-outer = 20.25\n"
    "spot-reach = 7.5\n"
    "directional = 0.9, 0.8, 0.7, 0.2\n"
    "filter = nearest\n"
    "samples = 4\n"
    "exposure = -2.5\n"
    "tonemap = neutral\n"
    "textures = hand/textures\n"
    "view = depth\n"
    "interp = affine\n"
    "paused = yes\n";

static void assert_light_is(const luz_light *light, float r, float g, float b, float strength)
{
    assert_float_same(light->colour.x, r);
    assert_float_same(light->colour.y, g);
    assert_float_same(light->colour.z, b);
    assert_float_same(light->strength, strength);
}

/* Every key the writer saves, each at a value that is not its default:
 * written, read back into fresh options, written again. The two texts are
 * the same, and every field read back is the value set by hand (compared
 * with the literals, not with the options that were written). */
static void test_scene_round_trip_every_saved_key(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    luz_options original, copy;
    set_every_option_by_hand(&original);
    char *first = scene_text(&original);
    assert_string_equal(first, every_option_text);

    char path[600];
    snprintf(path, sizeof path, "%s/every.luz", box.root);
    write_text(box.root, "every.luz", first);
    read_scene_from(&copy, path);
    char *second = scene_text(&copy);
    assert_string_equal(first, second);

    assert_int_equal(copy.width, 640);
    assert_int_equal(copy.height, 360);
    assert_true(copy.scene.time_seconds == 2.75);
    assert_int_equal(copy.scene.seed, 12345);
    assert_int_equal(copy.scene.cube_count, 25);
    assert_int_equal(copy.scene.object_count, 0);
    assert_float_same(copy.scene.camera.position.x, 0.5f);
    assert_float_same(copy.scene.camera.position.y, -1.25f);
    assert_float_same(copy.scene.camera.position.z, 4.0f);
    assert_float_same(copy.scene.camera.yaw_degrees, -100.7f);
    assert_float_same(copy.scene.camera.pitch_degrees, 12.5f);
    assert_float_same(copy.scene.camera.fov_degrees, 60.0f);
    const luz_lights *lights = &copy.scene.lights;
    assert_light_is(&lights->ambient, 0.1f, 0.2f, 0.3f, 0.4f);
    assert_light_is(&lights->diffuse, 0.5f, 0.6f, 0.7f, 0.25f);
    assert_light_is(&lights->specular, 1.0f, 0.5f, 0.0f, 0.75f);
    assert_float_same(lights->shininess, 64.0f);
    assert_light_is(&lights->point, 0.3f, 0.3f, 0.9f, 0.1f);
    assert_light_is(&lights->spot, 1.0f, 1.0f, 0.9f, 0.5f);
    assert_float_same(lights->spot_inner_degrees, 5.5f);
    assert_float_same(lights->spot_outer_degrees, 20.25f);
    assert_float_same(lights->spot_reach, 7.5f);
    assert_light_is(&lights->directional, 0.9f, 0.8f, 0.7f, 0.2f);
    assert_int_equal(copy.scene.filter, LUZ_FILTER_NEAREST);
    assert_int_equal(copy.scene.samples, 4);
    assert_int_equal(copy.scene.view, LUZ_VIEW_DEPTH);
    assert_int_equal(copy.scene.interpolation, LUZ_INTERPOLATION_AFFINE);
    assert_true(copy.paused);
    assert_true(copy.scene.has_exposure && copy.scene.has_tone_map);
    assert_float_same(copy.scene.exposure, -2.5f);
    assert_int_equal(copy.scene.tone_map, LUZ_TONE_MAP_NEUTRAL);
    assert_string_equal(copy.textures_directory, "hand/textures");
    /* what is not written comes back as the defaults */
    assert_int_equal(copy.only_terms, 0);
    assert_int_equal(copy.thread_count, LUZ_THREADS_AUTO);
    assert_string_equal(copy.output_path, "luz.png");
    assert_int_equal(copy.frame_count, 1);
    assert_true(copy.frames_per_second == 30.0);
    assert_int_equal(copy.bench_frames, 0);
    assert_false(copy.reference);

    free(first);
    free(second);
    luz_options_free(&copy);
    luz_options_free(&original);
    sandbox_destroy(&box);
}

/* The keys of a scene file's `name = value` lines, in order, into keys
 * (at most capacity); `cube` lines are counted in *cube_lines instead.
 * Returns the number of keys. */
static int scene_keys(const char *text, char keys[][32], int capacity, int *cube_lines)
{
    int count = 0;
    *cube_lines = 0;
    for (const char *line = text; *line != '\0';) {
        const char *end = strchr(line, '\n');
        size_t length = end ? (size_t)(end - line) : strlen(line);
        const char *equals = memchr(line, '=', length);
        if (line[0] != '#' && equals != NULL) {
            size_t key_length = (size_t)(equals - line);
            while (key_length > 0 && line[key_length - 1] == ' ')
                key_length--;
            if (key_length == 4 && memcmp(line, "cube", 4) == 0) {
                (*cube_lines)++;
            } else {
                assert_true(count < capacity && key_length < 32);
                snprintf(keys[count++], 32, "%.*s", (int)key_length, line);
            }
        }
        if (end == NULL)
            break;
        line = end + 1;
    }
    return count;
}

static bool is_one_of(const char *name, const char *const *names, size_t count)
{
    for (size_t i = 0; i < count; i++)
        if (strcmp(name, names[i]) == 0)
            return true;
    return false;
}

/* With every option changed, the writer writes exactly the option table's
 * scene keys less those docs/cli.md says it leaves out (Writing scene
 * files): `only`, and a run's threads, output, frames, fps, bench and
 * model-files and model-memory; each
 * once. With custom cubes, `cubes` goes too and the cube lines stand for
 * it. So a key dropped by the writer, or a key added to the table that the
 * writer does not save nor the docs exclude, fails here. */
static void test_scene_writer_saves_every_scene_key(void **state)
{
    (void)state;
    static const char *const left_out[] = {"only", "threads", "output", "frames", "fps",
                                           "bench", "model-files",
                                           "model-memory"};
    const size_t left_out_count = sizeof left_out / sizeof left_out[0];
    luz_options options;
    set_every_option_by_hand(&options);

    for (int custom = 0; custom <= 1; custom++) {
        if (custom) {
            static const char *const names[] = {"a.bmp", "b.bmp"};
            set_named_cubes(&options, names, 2);
        }
        char *text = scene_text(&options);
        char keys[64][32];
        int cube_lines;
        int key_count = scene_keys(text, keys, 64, &cube_lines);
        assert_int_equal(cube_lines, custom ? 2 : 0);

        /* every expected key is written, once */
        int expected_count = 0;
        bool saw_view = false;
        luz_option_info row;
        for (size_t i = 0; luz_options_row(i, &row); i++) {
            if (!luz_options_is_scene_key(row.name) ||
                is_one_of(row.name, left_out, left_out_count) ||
                (custom && strcmp(row.name, "cubes") == 0))
                continue;
            expected_count++;
            saw_view = saw_view || strcmp(row.name, "view") == 0;
            int times = 0;
            for (int k = 0; k < key_count; k++)
                times += strcmp(keys[k], row.name) == 0;
            if (times != 1)
                fail_msg("scene key '%s' written %d times in:\n%s", row.name, times, text);
        }
        /* and nothing else: every written key is a table row, expected above */
        assert_true(saw_view);
        if (key_count != expected_count)
            fail_msg("%d keys written, %d expected, in:\n%s", key_count, expected_count, text);
        free(text);
    }
    luz_options_free(&options);
}

/* The defaults, written: SCENE.md's scene at 1280x720 (docs/cli.md's
 * defaults column), without view, interp (both at their defaults) or
 * textures (not set). */
static void test_scene_text_of_the_defaults(void **state)
{
    (void)state;
    luz_options options;
    luz_options_init(&options);
    char *text = scene_text(&options);
    assert_string_equal(text,
                        "# luz scene: render it with luz-render --scene FILE (see docs/cli.md)\n"
                        "size = 1280x720\n"
                        "time = 0\n"
                        "seed = 0\n"
                        "cubes = 10\n"
                        "camera-pos = 0, 0, 3\n"
                        "camera-yaw = -90\n"
                        "camera-pitch = 0\n"
                        "fov = 45\n"
                        "ambient = 1, 1, 1, 0.2\n"
                        "diffuse = 1, 1, 1, 0.6\n"
                        "specular = 1, 1, 1, 0.5\n"
                        "shininess = 32\n"
                        "point = 1, 1, 1, 0.7\n"
                        "spot = 1, 1, 1, 1\n"
                        "spot-inner = 12.5\n"
                        "spot-outer = 17.5\n"
                        "spot-reach = 10\n"
                        "directional = 1, 1, 1, 0.4\n"
                        "filter = trilinear\n"
                        "samples = 1\n"
                        "exposure = 0\n"
                        "tonemap = clamp\n");
    free(text);
    /* one of the two changed: only that one is written */
    options.scene.interpolation = LUZ_INTERPOLATION_AFFINE;
    text = scene_text(&options);
    assert_contains(text, "\nfilter = trilinear\nsamples = 1\nexposure = 0\ntonemap = clamp\ninterp = affine\n");
    assert_null(strstr(text, "view ="));
    free(text);
    luz_options_free(&options);
}

/* A textures directory with `#` and a trailing blank, and texture names
 * with a blank, a `#` and a `"`, come back byte for byte; the writer quotes
 * those and only those. */
static void test_scene_quoted_round_trip(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    static const char *const names[] = {"old wood.png", "a#b.png", "quote\"d.png",
                                        "stone.png"};
    luz_options original, copy;
    luz_options_init(&original);
    luz_error error = {{0}};
    assert_int_equal(luz_options_set(&original, "textures", "dir # with hash ", NULL, &error),
                     0);
    set_named_cubes(&original, names, 4);

    char path[600], saved[600];
    snprintf(path, sizeof path, "%s/quoted.luz", box.root);
    snprintf(saved, sizeof saved, "%s/saved.luz", box.root);
    write_scene_to(&original, path);
    char *text = read_file(path, NULL);
    assert_non_null(text);
    assert_contains(text, "\ntextures = \"dir # with hash \"\n");
    assert_contains(text, " texture \"old wood.png\"\n");
    assert_contains(text, " texture \"a#b.png\"\n");
    assert_contains(text, " texture \"quote\\\"d.png\"\n");
    assert_contains(text, " texture stone.png\n");

    read_scene_from(&copy, path);
    assert_scene_options_equal(&original, &copy);
    assert_string_equal(copy.textures_directory, "dir # with hash ");
    assert_int_equal(copy.scene.object_count, 4);
    assert_string_equal(copy.object_sources[0].texture_name, "old wood.png");
    assert_string_equal(copy.object_sources[1].texture_name, "a#b.png");
    assert_string_equal(copy.object_sources[2].texture_name, "quote\"d.png");
    assert_string_equal(copy.object_sources[3].texture_name, "stone.png");
    luz_options_free(&copy);

    /* the viewer's F2 writes the same text */
    assert_int_equal(luz_options_save_scene(&original, saved, false, &error), 0);
    char *saved_text = read_file(saved, NULL);
    assert_non_null(saved_text);
    assert_string_equal(saved_text, text);
    free(saved_text);
    free(text);

    /* the escapes, a leading blank and an empty name */
    static const char *const odd[] = {"back\\slash", "tab\there", "line\nbreak\r",
                                      " lead", ""};
    free(original.textures_directory);
    original.textures_directory = strdup("\\\\server\\share");
    assert_non_null(original.textures_directory);
    set_named_cubes(&original, odd, 5);
    write_scene_to(&original, path);
    text = read_file(path, NULL);
    assert_non_null(text);
    assert_contains(text, "\ntextures = \"\\\\\\\\server\\\\share\"\n");
    assert_contains(text, " texture \"back\\\\slash\"\n");
    assert_contains(text, " texture \"tab\\there\"\n");
    assert_contains(text, " texture \"line\\nbreak\\r\"\n");
    assert_contains(text, " texture \" lead\"\n");
    assert_contains(text, " texture \"\"\n");
    free(text);
    read_scene_from(&copy, path);
    assert_scene_options_equal(&original, &copy);
    assert_string_equal(copy.textures_directory, "\\\\server\\share");
    assert_string_equal(copy.object_sources[2].texture_name, "line\nbreak\r");
    luz_options_free(&copy);

    /* blanks: at the ends they need quotes, inside a value they do not */
    static const char *const directories[][2] = {
        {" leading", "\ntextures = \" leading\"\n"},
        {"trailing ", "\ntextures = \"trailing \"\n"},
        {"my textures", "\ntextures = my textures\n"},
    };
    for (size_t i = 0; i < sizeof directories / sizeof directories[0]; i++) {
        free(original.textures_directory);
        original.textures_directory = strdup(directories[i][0]);
        assert_non_null(original.textures_directory);
        write_scene_to(&original, path);
        text = read_file(path, NULL);
        assert_non_null(text);
        assert_contains(text, directories[i][1]);
        free(text);
        read_scene_from(&copy, path);
        assert_string_equal(copy.textures_directory, directories[i][0]);
        luz_options_free(&copy);
    }

    luz_options_free(&original);
    sandbox_destroy(&box);
}

/* Quoted values written by hand, with comments after them and the fields
 * of a cube line in either order; a `"` inside an unquoted value is still
 * an ordinary character. */
static void test_scene_quoted_values_read(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600];
    snprintf(path, sizeof path, "%s/hand.luz", box.root);
    write_text(box.root, "hand.luz",
               "textures = \"a # b\"  # comment\n"
               "cube = 0, 0, 0 texture \"x y.png\" colour 1, 0, 0\n"
               "cube = 1, 2, 3 colour 0, 0.5, 1 texture \"c:\\\\t\\\"x\\\"\\t#1\" # why\n"
               "cube = 4, 5, 6 texture\t\"\"\n"
               "cube = 7, 8, 9 texture it\"s.png  # an ordinary quote\n"
               "output = say \"hi\".png # likewise\n");
    luz_options options;
    read_scene_from(&options, path);
    assert_string_equal(options.textures_directory, "a # b");
    assert_int_equal(options.scene.object_count, 4);
    assert_string_equal(options.object_sources[0].texture_name, "x y.png");
    assert_true(options.objects[0].has_colour);
    assert_float_same(options.objects[0].colour.x, 1.0f);
    assert_float_same(options.objects[0].colour.y, 0.0f);
    assert_float_same(options.objects[0].colour.z, 0.0f);
    assert_string_equal(options.object_sources[1].texture_name, "c:\\t\"x\"\t#1");
    assert_true(options.objects[1].has_colour);
    assert_float_same(options.objects[1].colour.y, 0.5f);
    assert_string_equal(options.object_sources[2].texture_name, "");
    assert_float_same(options.objects[2].position.z, 6.0f);
    assert_string_equal(options.object_sources[3].texture_name, "it\"s.png");
    assert_string_equal(options.output_path, "say \"hi\".png");
    luz_options_free(&options);
    sandbox_destroy(&box);
}

/* luz_options_save_scene (the viewer's F2): the file reads back as the
 * options; saved again without replace, under the same name, it is
 * refused with LUZ_FILE_EXISTS and the first file stays as it was, with
 * no temporary file left; with replace it is replaced. A directory that
 * does not exist gives -1 and a message naming the path. */
static void test_save_scene_never_replaces_unless_asked(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600], missing[600];
    sandbox_path(&box, "view.luz", path, sizeof path);
    sandbox_path(&box, "no-such-directory/view.luz", missing, sizeof missing);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);

    luz_options first, second, copy;
    parse_or_fail(&first, 3, (char *[]){"luz", "--seed", "11", NULL});
    parse_or_fail(&second, 3, (char *[]){"luz", "--seed", "22", NULL});
    luz_error error = {{0}};
    assert_int_equal(luz_options_save_scene(&first, path, false, &error), 0);
    char *text = read_file(path, NULL);
    assert_int_equal(luz_options_save_scene(&second, path, false, &error), LUZ_FILE_EXISTS);
    char *unchanged = read_file(path, NULL);
    assert_string_equal(text, unchanged);
    read_scene_from(&copy, path);
    assert_int_equal(copy.scene.seed, 11);
    luz_options_free(&copy);
    list_tree(box.work, "", after, sizeof after);
    assert_new_files(before, after, ARGS("view.luz"));

    assert_int_equal(luz_options_save_scene(&second, path, true, &error), 0);
    read_scene_from(&copy, path);
    assert_int_equal(copy.scene.seed, 22);
    luz_options_free(&copy);

    assert_int_equal(luz_options_save_scene(&first, missing, false, &error), -1);
    assert_non_null(strstr(error.message, missing));

    free(text);
    free(unchanged);
    luz_options_free(&first);
    luz_options_free(&second);
    sandbox_destroy(&box);
}

/* ---- what -o may replace ------------------------------------------------------------- */

/* A thing at a path, as lstat sees it: luz-render must leave it as it was. */
typedef struct file_identity {
    mode_t type;
    dev_t device;
    ino_t inode;
} file_identity;

static file_identity identity_of(const char *path)
{
    struct stat status;
    if (lstat(path, &status) != 0)
        fail_msg("%s: %s", path, strerror(errno));
    return (file_identity){status.st_mode & S_IFMT, status.st_dev, status.st_ino};
}

/* luz-render -o NAME, with NAME something the rename would replace: exit
 * status 2, one line naming NAME and what it is, nothing written, NAME
 * still the same thing. */
static void assert_output_refused(const sandbox *box, const char *name, const char *what)
{
    char path[600], before[8192] = "", after[8192] = "";
    sandbox_path(box, name, path, sizeof path);
    const file_identity was = identity_of(path);
    list_tree(box->work, "", before, sizeof before);
    run_result result = run_in(box, ARGS("--size", "8x8", "--textures", "none", "-o", name), NULL);
    char needle[700];
    snprintf(needle, sizeof needle, "luz-render: -o: %s: is %s, not a regular file", name, what);
    if (result.status != 2 || strncmp(result.err, needle, strlen(needle)) != 0 ||
        strchr(result.err, '\n') != result.err + strlen(result.err) - 1)
        fail_msg("-o %s: exit %d, stderr '%s'; expected 2 and '%s...'", name, result.status,
                 result.err, needle);
    const file_identity is = identity_of(path);
    assert_int_equal(is.type, was.type);
    assert_int_equal(is.inode, was.inode);
    assert_int_equal(is.device, was.device);
    list_tree(box->work, "", after, sizeof after);
    assert_string_equal(before, after);
    run_result_free(&result);
}

/* The issue's case: as root, -o /dev/null replaced the system's /dev/null
 * with a PNG, since a rename replaces whatever has the name. Only a regular
 * file is replaced now; everything else at the path is refused. (The
 * devices are made in the sandbox, never the system's own, so that a
 * regression cannot harm the machine that runs the test.) */
static void test_output_replaces_only_regular_files(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600];

    sandbox_path(&box, "fifo.png", path, sizeof path);
    assert_int_equal(mkfifo(path, 0644), 0);
    assert_output_refused(&box, "fifo.png", "a FIFO");

    sandbox_path(&box, "socket.png", path, sizeof path);
    int listener = socket(AF_UNIX, SOCK_STREAM, 0);
    assert_true(listener >= 0);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (strlen(path) < sizeof address.sun_path) {   /* a socket's path is short */
        memcpy(address.sun_path, path, strlen(path) + 1);
        assert_int_equal(bind(listener, (struct sockaddr *)&address, sizeof address), 0);
        assert_output_refused(&box, "socket.png", "a socket");
    }
    close(listener);

    /* a symbolic link is replaced itself, so it is refused whatever it
     * points to: a device (/dev/stdout is a link), or a file */
    sandbox_path(&box, "null-link.png", path, sizeof path);
    assert_int_equal(symlink("/dev/null", path), 0);
    assert_output_refused(&box, "null-link.png", "a symbolic link");
    sandbox_path(&box, "file-link.png", path, sizeof path);
    assert_int_equal(symlink("tex/a.bmp", path), 0);
    assert_output_refused(&box, "file-link.png", "a symbolic link");

    /* a character device of the sandbox's own (1, 3 is null's number);
     * only root may make one */
    sandbox_path(&box, "device.png", path, sizeof path);
    if (mknod(path, S_IFCHR | 0666, makedev(1, 3)) == 0)
        assert_output_refused(&box, "device.png", "a character device");
    else
        print_message("device case skipped: mknod: %s\n", strerror(errno));

    /* the check itself, on the system's devices: it writes nothing */
    luz_error error;
    assert_int_equal(luz_new_file_check_target("/dev/null", &error), -1);
    assert_string_equal(error.message, "/dev/null: is a character device, not a regular file; "
                                       "expected a new file or a regular file to replace");
    assert_int_equal(luz_new_file_check_target("/dev/stdout", &error), -1);
    assert_non_null(strstr(error.message, "/dev/stdout: is a symbolic link"));
    sandbox_destroy(&box);
}

/* A sequence's every frame is checked before the first is rendered: frame
 * 1 of tex/%d.bmp is tex/1.bmp, a texture, so nothing is written at all
 * (not frame 0 either) and the texture stays as it was. */
static void test_no_frame_replaces_an_input(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char texture[600], frame0[600];
    sandbox_path(&box, "tex/1.bmp", texture, sizeof texture);
    sandbox_path(&box, "tex/0.bmp", frame0, sizeof frame0);
    write_bmp(texture, 2, 2, 10, 20, 30);
    size_t length_before, length_after;
    char *bytes_before = read_file(texture, &length_before);
    run_result result = run_in(&box, ARGS("--size", "8x8", "--textures", "tex", "--frames", "3",
                                          "-o", "tex/%d.bmp"), NULL);
    assert_int_equal(result.status, 2);
    assert_string_equal(result.err, "luz-render: -o: tex/1.bmp: is a texture this run reads; "
                                    "expected an output file that is none of its inputs\n");
    assert_int_equal(access(frame0, F_OK), -1);
    char *bytes_after = read_file(texture, &length_after);
    assert_int_equal(length_after, length_before);
    assert_memory_equal(bytes_after, bytes_before, length_before);
    free(bytes_before);
    free(bytes_after);
    run_result_free(&result);

    /* the same file by a hard link elsewhere: its device and inode */
    char link_path[600];
    sandbox_path(&box, "same.bmp", link_path, sizeof link_path);
    assert_int_equal(link(texture, link_path), 0);
    result = run_in(&box, ARGS("--size", "8x8", "--textures", "tex", "-o", "same.bmp"), NULL);
    assert_int_equal(result.status, 2);
    assert_string_equal(result.err, "luz-render: -o: same.bmp: is a texture this run reads "
                                    "(tex/1.bmp); expected an output file that is none of its "
                                    "inputs\n");
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* Missing folders of -o are made, as mkdir -p makes them (issue 31: the
 * README's -o frames/... failed on a fresh clone after frame 0, exit 1);
 * a pattern whose folder changes with the frame gets each; .PNG is a
 * PNG's name too. */
static void test_output_folders_are_made(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "8x6", "--textures", "none", "--frames", "3",
                                          "-o", "new/deeper/f_%d.png"), NULL);
    assert_int_equal(result.status, 0);
    assert_string_equal(result.err, "");
    run_result_free(&result);
    for (int k = 0; k < 3; k++) {
        char name[64];
        snprintf(name, sizeof name, "new/deeper/f_%d.png", k);
        assert_png_size(&box, name, 8, 6);
    }
    result = run_in(&box, ARGS("--size", "8x6", "--textures", "none", "--frames", "2", "-o",
                               "shot_%d//f.PNG"), NULL);
    assert_int_equal(result.status, 0);
    run_result_free(&result);
    assert_png_size(&box, "shot_0/f.PNG", 8, 6);
    assert_png_size(&box, "shot_1/f.PNG", 8, 6);

    /* a folder that cannot be made, even by root (sysfs refuses mkdir):
     * one line naming it, exit 2, no frame */
    struct stat sys;
    if (stat("/sys/kernel", &sys) == 0 && S_ISDIR(sys.st_mode)) {
        result = run_in(&box, ARGS("--size", "8x6", "--textures", "none", "-o",
                                   "/sys/luz-no-folder/f.png"), NULL);
        assert_int_equal(result.status, 2);
        assert_non_null(strstr(result.err, "luz-render: -o: /sys/luz-no-folder/f.png: cannot "
                                           "create the folder /sys/luz-no-folder ("));
        assert_int_equal(strchr(result.err, '\n') - result.err, strlen(result.err) - 1);
        run_result_free(&result);
    } else {
        print_message("the folder that cannot be made: skipped, no sysfs at /sys\n");
    }
    sandbox_destroy(&box);
}

/* The check is new_file's, right before the rename too: a FIFO that
 * appears while the PNG is written is not replaced, and the temporary
 * file is removed. */
static void test_commit_checks_the_path_again(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600], before[8192] = "", after[8192] = "";
    sandbox_path(&box, "late.png", path, sizeof path);
    list_tree(box.work, "", before, sizeof before);
    luz_new_file file;
    luz_error error;
    assert_int_equal(luz_new_file_open(&file, path, &error), 0);
    fputs("not yet a PNG", file.stream);
    assert_int_equal(mkfifo(path, 0644), 0);
    assert_int_equal(luz_new_file_commit(&file, true, &error), -1);
    assert_non_null(strstr(error.message, "late.png: is a FIFO, not a regular file"));
    assert_int_equal(identity_of(path).type, S_IFIFO);
    list_tree(box.work, "", after, sizeof after);
    assert_new_files(before, after, ARGS("late.png"));   /* the FIFO, and no temporary */
    sandbox_destroy(&box);
}

/* A file-size limit (ulimit -f) made the write die of SIGXFSZ and leave
 * NAME.tmp-XXXXXX behind. Now the write fails with EFBIG: -1, one message,
 * no file, and the signal is not delivered once the mask is restored. In
 * a child, whose limit the test can lower: the defaults' scene text is
 * about 400 bytes, the limit 100. This is the viewer's F2 path. */
static void test_save_scene_past_the_file_size_limit(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600], before[8192] = "", after[8192] = "";
    sandbox_path(&box, "view.luz", path, sizeof path);
    list_tree(box.work, "", before, sizeof before);
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        luz_options options;
        luz_options_init(&options);
        struct rlimit limit = {100, 100};
        luz_error error = {{0}};
        int status = setrlimit(RLIMIT_FSIZE, &limit) == 0
                         ? luz_options_save_scene(&options, path, false, &error)
                         : 9;
        /* 0: the expected failure and message; else what went wrong */
        bool expected = status == -1 && strstr(error.message, "view.luz: cannot write (File "
                                                             "too large)") != NULL;
        _exit(expected ? 0 : status == 0 ? 3 : 4);
    }
    int status;
    while (waitpid(child, &status, 0) < 0)
        assert_int_equal(errno, EINTR);
    if (!WIFEXITED(status))
        fail_msg("the child died of signal %d", WTERMSIG(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

static void test_parse_precedence_and_forms(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char scene[600];
    snprintf(scene, sizeof scene, "%s/p.luz", box.root);
    write_text(box.root, "p.luz", "fov = 30\ntime = 5\ncube = 1, 2, 3\n");

    /* --scene read first, the command line applied over it in any order */
    char *argv_a[] = {"luz-render", "--fov", "60", "--scene", scene};
    char *argv_b[] = {"luz-render", "--scene", scene, "--fov=60"};
    luz_options a, b;
    parse_or_fail(&a, 5, argv_a);
    parse_or_fail(&b, 4, argv_b);
    assert_float_same(a.scene.camera.fov_degrees, 60.0f);
    assert_float_same(b.scene.camera.fov_degrees, 60.0f);
    assert_true(a.scene.time_seconds == 5.0);
    assert_scene_options_equal(&a, &b);
    assert_int_equal(a.scene.object_count, 1);
    assert_string_equal(a.scene_path, scene);
    luz_options_free(&b);

    /* --cubes on the command line replaces the file's cube lines */
    char *argv_c[] = {"luz-render", "--cubes", "30", "--scene", scene};
    parse_or_fail(&b, 5, argv_c);
    assert_int_equal(b.scene.object_count, 0);
    assert_null(b.scene.objects);
    assert_int_equal(b.scene.cube_count, 30);
    luz_options_free(&b);
    luz_options_free(&a);

    /* --only zeroes the other terms whatever the order, and keeps a set
     * strength of a kept term */
    char *argv_d[] = {"luz-render", "--spot", "1,0,0,0.5", "--only", "spot, point",
                      "--ambient", "1,1,1,1"};
    parse_or_fail(&a, 7, argv_d);
    assert_float_same(a.scene.lights.ambient.strength, 0.0f);
    assert_float_same(a.scene.lights.diffuse.strength, 0.0f);
    assert_float_same(a.scene.lights.specular.strength, 0.0f);
    assert_float_same(a.scene.lights.directional.strength, 0.0f);
    assert_float_same(a.scene.lights.spot.strength, 0.5f);
    assert_float_same(a.scene.lights.point.strength, luz_scene_defaults().lights.point.strength);
    luz_options_free(&a);

    /* the spot's cone is checked once both angles are known */
    char *argv_e[] = {"luz-render", "--spot-inner", "20", "--spot-outer", "25"};
    parse_or_fail(&a, 5, argv_e);
    assert_float_same(a.scene.lights.spot_inner_degrees, 20.0f);
    luz_options_free(&a);

    /* the defaults: SCENE.md's scene, 1280x720, luz.png, automatic threads */
    char *argv_f[] = {"luz-render"};
    parse_or_fail(&a, 1, argv_f);
    luz_scene defaults = luz_scene_defaults();
    assert_int_equal(a.width, 1280);
    assert_int_equal(a.height, 720);
    assert_string_equal(a.output_path, "luz.png");
    assert_int_equal(a.thread_count, LUZ_THREADS_AUTO);
    assert_null(a.textures_directory);
    assert_int_equal(a.frame_count, 1);
    assert_true(a.frames_per_second == 30.0);
    assert_int_equal(a.scene.cube_count, defaults.cube_count);
    assert_float_same(a.scene.lights.ambient.strength, defaults.lights.ambient.strength);
    luz_options_free(&a);
    sandbox_destroy(&box);
}

static void test_output_pattern(void **state)
{
    (void)state;
    static const struct {
        const char *pattern;
        int frame;
        const char *expected;
    } cases[] = {
        {"out_%04d.png", 7, "out_0007.png"},
        {"out_%04d.png", 12345, "out_12345.png"},
        {"%d.png", 42, "42.png"},
        {"x%%y%3d.png", 5, "x%y  5.png"},
        {"100%%.png", 3, "100%.png"},
        {"plain.png", 9, "plain.png"},
        {"f%0d", 3, "f3"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        luz_options options;
        luz_error error = {{0}};
        char path[64];
        luz_options_init(&options);
        options.output_path = strdup(cases[i].pattern);
        if (luz_options_output_path(&options, cases[i].frame, path, sizeof path, &error) != 0)
            fail_msg("%s: %s", cases[i].pattern, error.message);
        assert_string_equal(path, cases[i].expected);
        luz_options_free(&options);
    }
    /* a name that does not fit is refused, not cut */
    luz_options options;
    luz_error error = {{0}};
    char small[8];
    luz_options_init(&options);
    options.output_path = strdup("longer_than_eight_%d.png");
    assert_int_equal(luz_options_output_path(&options, 1, small, sizeof small, &error), -1);
    luz_options_free(&options);
}

/* Built in the build tree, this test program finds the source textures;
 * $LUZ_TEXTURES beats that. */
static void test_default_textures_directory(void **state)
{
    (void)state;
    char buffer[4096];
    char *saved = getenv("LUZ_TEXTURES") ? strdup(getenv("LUZ_TEXTURES")) : NULL;
    unsetenv("LUZ_TEXTURES");
    assert_string_equal(luz_default_textures_directory(buffer, sizeof buffer),
                        LUZ_SOURCE_TEXTURES);
    setenv("LUZ_TEXTURES", "/some/where", 1);
    assert_string_equal(luz_default_textures_directory(buffer, sizeof buffer), "/some/where");
    setenv("LUZ_TEXTURES", "", 1);   /* empty counts as unset */
    assert_string_equal(luz_default_textures_directory(buffer, sizeof buffer),
                        LUZ_SOURCE_TEXTURES);
    if (saved) {
        setenv("LUZ_TEXTURES", saved, 1);
        free(saved);
    } else {
        unsetenv("LUZ_TEXTURES");
    }
}

/* ---- sequences beyond one run: --frame-range, --shard, --skip-existing, -o - ---------- */

/* luz_shard_frames against shares worked out by hand: with q = N / M and
 * r = N mod M, shares 0 to r - 1 get q + 1 frames, the others q, in
 * order; an empty share starts where the frames ran out. */
static void test_shard_arithmetic(void **state)
{
    (void)state;
    static const struct {
        int first, count, index, shards;
        int expected_first, expected_frames;
    } cases[] = {
        /* 24 frames in 4 shares: 6 each */
        {0, 24, 0, 4, 0, 6}, {0, 24, 1, 4, 6, 6}, {0, 24, 2, 4, 12, 6}, {0, 24, 3, 4, 18, 6},
        /* 10 in 4: q = 2, r = 2: frames 0-2, 3-5, 6-7, 8-9 */
        {0, 10, 0, 4, 0, 3}, {0, 10, 1, 4, 3, 3}, {0, 10, 2, 4, 6, 2}, {0, 10, 3, 4, 8, 2},
        /* 3 in 5: q = 0, r = 3: one frame each for shares 0 to 2, then empty */
        {0, 3, 0, 5, 0, 1}, {0, 3, 1, 5, 1, 1}, {0, 3, 2, 5, 2, 1}, {0, 3, 3, 5, 3, 0},
        {0, 3, 4, 5, 3, 0},
        /* one share: all of them */
        {0, 7, 0, 1, 0, 7},
        /* frames 10 to 19 in 3: q = 3, r = 1: 10-13, 14-16, 17-19 */
        {10, 10, 0, 3, 10, 4}, {10, 10, 1, 3, 14, 3}, {10, 10, 2, 3, 17, 3},
        /* 1000000 frames in 7: q = 142857, r = 1; share 6 starts at
         * 6 * 142857 + 1 = 857143 and ends at 999999 */
        {0, 1000000, 0, 7, 0, 142858}, {0, 1000000, 1, 7, 142858, 142857},
        {0, 1000000, 6, 7, 857143, 142857},
        /* 1000000 shares of 1000000 frames: the last is frame 999999 */
        {0, 1000000, 999999, 1000000, 999999, 1},
        /* ... and of one frame: share 0 has it, the last is empty */
        {0, 1, 0, 1000000, 0, 1}, {0, 1, 999999, 1000000, 1, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int first = -1, frames = -1;
        luz_shard_frames(cases[i].first, cases[i].count, cases[i].index, cases[i].shards, &first,
                         &frames);
        if (first != cases[i].expected_first || frames != cases[i].expected_frames)
            fail_msg("%d frames from %d, share %d/%d: got %d frames from %d, expected %d from "
                     "%d",
                     cases[i].count, cases[i].first, cases[i].index, cases[i].shards, frames,
                     first, cases[i].expected_frames, cases[i].expected_first);
    }

    /* and for every small case: the shares cover the frames once, in
     * order, and differ by at most one frame, the longer ones first */
    for (int count = 0; count <= 30; count++) {
        for (int shards = 1; shards <= 40; shards++) {
            int next = 5, previous_frames = count + 1;
            for (int index = 0; index < shards; index++) {
                int first, frames;
                luz_shard_frames(5, count, index, shards, &first, &frames);
                assert_int_equal(first, next);
                assert_true(frames == count / shards || frames == count / shards + 1);
                assert_true(frames <= previous_frames);
                next = first + frames;
                previous_frames = frames;
            }
            assert_int_equal(next, 5 + count);
        }
    }
}

/* --frame-range and --shard, parsed, and the frames a run then renders,
 * worked out by hand for --frames 24. */
static void test_frame_range_and_shard_parsing(void **state)
{
    (void)state;
    static const struct {
        const char *range, *shard;
        int first, last;             /* range_first, range_last */
        int render_first, render_count;
        const char *formatted;       /* luz_options_format's frame-range */
    } cases[] = {
        {NULL, NULL, 0, LUZ_FRAME_RANGE_OPEN, 0, 24, NULL},
        {"5:9", NULL, 5, 9, 5, 5, "5:9"},
        {"5:", NULL, 5, LUZ_FRAME_RANGE_OPEN, 5, 19, "5:"},
        {":4", NULL, 0, 4, 0, 5, "0:4"},
        {":", NULL, 0, LUZ_FRAME_RANGE_OPEN, 0, 24, NULL},
        {" 2 : 3 ", NULL, 2, 3, 2, 2, "2:3"},
        {"23:23", NULL, 23, 23, 23, 1, "23:23"},
        {"0:23", NULL, 0, 23, 0, 24, "0:23"},
        /* 24 in 4: frames 6-11 */
        {NULL, "1/4", 0, LUZ_FRAME_RANGE_OPEN, 6, 6, NULL},
        /* 24 in 5: q = 4, r = 4: 5, 5, 5, 5, 4 frames */
        {NULL, "3/5", 0, LUZ_FRAME_RANGE_OPEN, 15, 5, NULL},
        {NULL, "4/5", 0, LUZ_FRAME_RANGE_OPEN, 20, 4, NULL},
        /* frames 4-13 (10) in 3: 4-7, 8-10, 11-13 */
        {"4:13", "2/3", 4, 13, 11, 3, "4:13"},
        /* frames 20-23 in 4: one each */
        {"20:", "3/4", 20, LUZ_FRAME_RANGE_OPEN, 23, 1, "20:"},
        /* frames 0-1 in 4: shares 2 and 3 are empty */
        {":1", "3/4", 0, 1, 2, 0, "0:1"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *argv[8] = {"luz-render", "--frames", "24"};
        int argc = 3;
        if (cases[i].range != NULL) {
            argv[argc++] = "--frame-range";
            argv[argc++] = (char *)cases[i].range;
        }
        if (cases[i].shard != NULL) {
            argv[argc++] = "--shard";
            argv[argc++] = (char *)cases[i].shard;
        }
        luz_options options;
        parse_or_fail(&options, argc, argv);
        assert_int_equal(options.range_first, cases[i].first);
        assert_int_equal(options.range_last, cases[i].last);
        int first = -1, count = -1;
        luz_options_frames_to_render(&options, &first, &count);
        if (first != cases[i].render_first || count != cases[i].render_count)
            fail_msg("--frame-range %s --shard %s: %d frames from %d, expected %d from %d",
                     cases[i].range ? cases[i].range : "(none)",
                     cases[i].shard ? cases[i].shard : "(none)", count, first,
                     cases[i].render_count, cases[i].render_first);
        char text[32];
        if (cases[i].formatted == NULL) {
            assert_int_equal(luz_options_format(&options, "frame-range", text, sizeof text), -1);
        } else {
            assert_int_equal(luz_options_format(&options, "frame-range", text, sizeof text), 0);
            assert_string_equal(text, cases[i].formatted);
        }
        if (cases[i].shard != NULL) {
            assert_int_equal(luz_options_format(&options, "shard", text, sizeof text), 0);
            assert_string_equal(text, cases[i].shard);
        } else {
            assert_int_equal(options.shard_count, 0);
        }
        luz_options_free(&options);
    }

    /* the range is checked once --frames is known, whatever the order */
    luz_options options;
    parse_or_fail(&options, 5,
                  (char *[]){"luz-render", "--frame-range", "20:23", "--frames", "24", NULL});
    assert_int_equal(options.range_first, 20);
    luz_options_free(&options);
    /* without --frames a sequence is one frame, frame 0 */
    parse_or_fail(&options, 3, (char *[]){"luz-render", "--frame-range", "0:0", NULL});
    int first, count;
    luz_options_frames_to_render(&options, &first, &count);
    assert_int_equal(first, 0);
    assert_int_equal(count, 1);
    assert_false(options.skip_existing);
    assert_false(luz_options_output_is_stdout(&options));
    luz_options_free(&options);
    parse_or_fail(&options, 4, (char *[]){"luz-render", "--skip-existing", "-o", "x.png", NULL});
    assert_true(options.skip_existing);
    luz_options_free(&options);
    parse_or_fail(&options, 5, (char *[]){"luz-render", "--frames", "3", "-o", "-", NULL});
    assert_true(luz_options_output_is_stdout(&options));
    luz_options_free(&options);
}

/* The test sequence: 24 small frames, with the sandbox's textures. */
#define SEQUENCE "--frames", "24", "--fps", "12", "--size", "160x90", "--textures", "tex"

static void make_directory(const sandbox *box, const char *name)
{
    char path[600];
    sandbox_path(box, name, path, sizeof path);
    assert_int_equal(mkdir(path, 0755), 0);
}

static int count_lines(const char *text)
{
    int lines = 0;
    for (; *text != '\0'; text++)
        lines += *text == '\n';
    return lines;
}

/* Directories a and b (under work/) hold the same file names, `count` of
 * them, with the same bytes. */
static void assert_same_files(const sandbox *box, const char *a, const char *b, int count)
{
    char path_a[600], path_b[600], names_a[8192] = "", names_b[8192] = "";
    sandbox_path(box, a, path_a, sizeof path_a);
    sandbox_path(box, b, path_b, sizeof path_b);
    list_tree(path_a, "", names_a, sizeof names_a);
    list_tree(path_b, "", names_b, sizeof names_b);
    if (strcmp(names_a, names_b) != 0)
        fail_msg("%s/ holds\n%s\nbut %s/ holds\n%s", a, names_a, b, names_b);
    assert_int_equal(count_lines(names_a), count);
    for (const char *name = names_a; *name != '\0';) {
        const char *end = strchr(name, '\n');
        char file_a[128], file_b[128];
        snprintf(file_a, sizeof file_a, "%s/%.*s", a, (int)(end - name), name);
        snprintf(file_b, sizeof file_b, "%s/%.*s", b, (int)(end - name), name);
        if (!files_equal(box, file_a, file_b))
            fail_msg("%s and %s differ", file_a, file_b);
        name = end + 1;
    }
}

/* The PNGs of frames first..last of directory `directory`, named
 * f_%02d.png, are those of one/, and the directory holds nothing else. */
static void assert_frames_of_one_run(const sandbox *box, const char *directory, int first,
                                     int last)
{
    char path[600], names[8192] = "", expected[8192] = "";
    sandbox_path(box, directory, path, sizeof path);
    list_tree(path, "", names, sizeof names);
    for (int k = first; k <= last; k++) {
        size_t used = strlen(expected);
        snprintf(expected + used, sizeof expected - used, "f_%02d.png\n", k);
        char mine[128], theirs[128];
        snprintf(mine, sizeof mine, "%s/f_%02d.png", directory, k);
        snprintf(theirs, sizeof theirs, "one/f_%02d.png", k);
        if (file_exists(box, mine) && !files_equal(box, mine, theirs))
            fail_msg("%s differs from %s", mine, theirs);
    }
    if (strcmp(names, expected) != 0)
        fail_msg("%s/ holds\n%s\nexpected\n%s", directory, names, expected);
}

/* One run of the sequence into one/. */
static void render_one_run(const sandbox *box)
{
    make_directory(box, "one");
    run_result result = run_in(box, ARGS(SEQUENCE, "-o", "one/f_%02d.png"), NULL);
    assert_success(&result);
    assert_string_equal(result.out, "");
    run_result_free(&result);
}

static bool have_programs(const char *names)
{
    char command[256];
    snprintf(command, sizeof command, "for p in %s; do command -v $p; done >/dev/null 2>&1",
             names);
    return system(command) == 0;
}

/* The sequence in one run, and as 4 shards that tools/render-sequence runs
 * with GNU parallel: the same file names, the same bytes. */
static void test_shards_by_parallel_match_one_run(void **state)
{
    (void)state;
    const char *tool = getenv("RENDER_SEQUENCE");
    if (tool == NULL)
        fail_msg("RENDER_SEQUENCE is not set (tests/meson.build sets it to tools/render-sequence)");
    if (!have_programs("parallel")) {
        print_message("skipped: GNU parallel is not installed (tools/install-deps test "
                      "installs it)\n");
        skip();
    }
    sandbox box;
    sandbox_create(&box);
    /* a value with blanks must reach every shard whole */
    make_directory(&box, "one");
    run_result result = run_in(
        &box, ARGS(SEQUENCE, "--camera-pos", "0, 0.2, 3.5", "-o", "one/f_%02d.png"), NULL);
    assert_success(&result);
    run_result_free(&result);
    make_directory(&box, "shards");
    result = run_program_in(&box, tool,
                            ARGS("--shards", "4", "--luz-render", luz_render_path(), "--",
                                 SEQUENCE, "--camera-pos", "0, 0.2, 3.5", "-o",
                                 "shards/f_%02d.png"),
                            NULL);
    assert_success(&result);
    assert_string_equal(result.out, "");
    run_result_free(&result);
    assert_same_files(&box, "one", "shards", 24);
    sandbox_destroy(&box);
}

/* --shard and --frame-range alone write exactly their frames, with the
 * bytes of the whole run; an empty shard writes nothing and succeeds. */
static void test_slices_match_one_run(void **state)
{
    (void)state;
    static const struct {
        const char *option, *value;
        int first, last;   /* by hand, for 24 frames */
    } slices[] = {
        {"--shard", "2/4", 12, 17},      {"--shard", "4/5", 20, 23},
        {"--frame-range", "5:9", 5, 9},  {"--frame-range", "20:", 20, 23},
        {"--frame-range", ":2", 0, 2},   {"--frame-range", "23:23", 23, 23},
    };
    sandbox box;
    sandbox_create(&box);
    render_one_run(&box);
    for (size_t i = 0; i < sizeof slices / sizeof slices[0]; i++) {
        char directory[32], pattern[64];
        snprintf(directory, sizeof directory, "slice%zu", i);
        snprintf(pattern, sizeof pattern, "%s/f_%%02d.png", directory);
        make_directory(&box, directory);
        run_result result =
            run_in(&box, ARGS(SEQUENCE, slices[i].option, slices[i].value, "-o", pattern), NULL);
        assert_success(&result);
        run_result_free(&result);
        assert_frames_of_one_run(&box, directory, slices[i].first, slices[i].last);
    }

    /* both: frames 4 to 13 in 3 shares, 4-7, 8-10, 11-13; the last */
    make_directory(&box, "both");
    run_result result = run_in(
        &box, ARGS(SEQUENCE, "--frame-range", "4:13", "--shard", "2/3", "-o", "both/f_%02d.png"),
        NULL);
    assert_success(&result);
    run_result_free(&result);
    assert_frames_of_one_run(&box, "both", 11, 13);

    /* 3 frames in 5 shares: shard 4 is empty; nothing at all is written */
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    result = run_in(&box, ARGS("--frames", "3", "--size", "16x9", "--textures", "tex", "--shard",
                               "4/5", "-o", "empty_%d.png"),
                    NULL);
    assert_success(&result);
    assert_string_equal(result.out, "");
    run_result_free(&result);
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

static struct stat stat_or_fail(const sandbox *box, const char *name)
{
    char path[600];
    struct stat info;
    sandbox_path(box, name, path, sizeof path);
    if (stat(path, &info) != 0)
        fail_msg("%s: %s", name, strerror(errno));
    return info;
}

static bool same_file_version(const struct stat *a, const struct stat *b)
{
    return a->st_ino == b->st_ino && a->st_mtim.tv_sec == b->st_mtim.tv_sec &&
           a->st_mtim.tv_nsec == b->st_mtim.tv_nsec;
}

/* Starts luz-render in box->work with stdout and stderr thrown away. */
static pid_t start_in(const sandbox *box, const char *const *arguments)
{
    const char *program = luz_render_path();
    char *argv[64];
    program_argv(program, arguments, argv);
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int null = open("/dev/null", O_WRONLY);
        if (null < 0 || chdir(box->work) != 0 || dup2(null, STDOUT_FILENO) < 0 ||
            dup2(null, STDERR_FILENO) < 0)
            _exit(127);
        unsetenv("LUZ_TEXTURES");
        execv(program, argv);
        _exit(127);
    }
    return child;
}

/* A shard killed (SIGKILL: no clean-up at all) after its first frames,
 * then run again with --skip-existing: the frames it had finished keep
 * their inode and modification time (not rendered again), the others are
 * written, and every frame is the one run's. The frames are made slow
 * (20000 cubes on one thread) so that the kill lands inside the shard. */
static void test_killed_shard_resumed(void **state)
{
    (void)state;
#define SLOW_SEQUENCE \
    "--frames", "8", "--fps", "12", "--size", "160x90", "--textures", "tex", "--cubes", \
        "20000", "--threads", "1"
    sandbox box;
    sandbox_create(&box);
    make_directory(&box, "one");
    run_result result = run_in(&box, ARGS(SLOW_SEQUENCE, "-o", "one/f_%02d.png"), NULL);
    assert_success(&result);
    run_result_free(&result);

    /* shard 1 of 2 is frames 4 to 7; kill it once frame 5 is there */
    char directory[32] = "", pattern[64] = "";
    bool caught = false;
    for (int attempt = 0; attempt < 5 && !caught; attempt++) {
        snprintf(directory, sizeof directory, "killed%d", attempt);
        snprintf(pattern, sizeof pattern, "%s/f_%%02d.png", directory);
        make_directory(&box, directory);
        char second[64];
        snprintf(second, sizeof second, "%s/f_05.png", directory);
        pid_t child = start_in(&box, ARGS(SLOW_SEQUENCE, "--shard", "1/2", "-o", pattern));
        for (int polls = 0; polls < 600000 && !file_exists(&box, second); polls++)
            nanosleep(&(struct timespec){.tv_nsec = 100000}, NULL);
        kill(child, SIGKILL);
        int status;
        assert_int_equal(waitpid(child, &status, 0), child);
        char last[64];
        snprintf(last, sizeof last, "%s/f_07.png", directory);
        caught = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL &&
                 file_exists(&box, second) && !file_exists(&box, last);
    }
    if (!caught)
        fail_msg("the shard finished before it could be killed, 5 times");

    struct stat before[8];
    bool existed[8] = {false};
    int finished = 0;
    for (int k = 4; k <= 7; k++) {
        char name[64];
        snprintf(name, sizeof name, "%s/f_%02d.png", directory, k);
        existed[k] = file_exists(&box, name);
        if (existed[k]) {
            before[k] = stat_or_fail(&box, name);
            finished++;
        }
    }
    assert_true(existed[4] && existed[5] && !existed[7]);

    result = run_in(&box, ARGS(SLOW_SEQUENCE, "--shard", "1/2", "--skip-existing", "-o", pattern),
                    NULL);
    assert_success(&result);
    run_result_free(&result);
    for (int k = 4; k <= 7; k++) {
        char name[64], theirs[64];
        snprintf(name, sizeof name, "%s/f_%02d.png", directory, k);
        snprintf(theirs, sizeof theirs, "one/f_%02d.png", k);
        struct stat after = stat_or_fail(&box, name);
        if (existed[k] && !same_file_version(&before[k], &after))
            fail_msg("%s was written again (%d of 4 frames were finished)", name, finished);
        if (!files_equal(&box, name, theirs))
            fail_msg("%s differs from %s", name, theirs);
    }
    /* the directory holds frames 4 to 7, and at most the temporary file a
     * SIGKILL can leave (NAME.tmp-XXXXXX) */
    char path[600], names[8192] = "";
    sandbox_path(&box, directory, path, sizeof path);
    list_tree(path, "", names, sizeof names);
    for (const char *name = names; *name != '\0'; name = strchr(name, '\n') + 1) {
        int k = -1;
        if (sscanf(name, "f_%2d.png\n", &k) == 1 && k >= 4 && k <= 7)
            continue;
        if (strstr(name, ".png.tmp-") != NULL && strchr(name, '\n') - name == 19)
            continue;
        fail_msg("unexpected file in %s/: %s", directory, name);
    }

    /* the control: without --skip-existing the same run writes frame 4
     * again, and the check above sees it */
    result = run_in(&box, ARGS(SLOW_SEQUENCE, "--shard", "1/2", "-o", pattern), NULL);
    assert_success(&result);
    run_result_free(&result);
    char first[64];
    snprintf(first, sizeof first, "%s/f_04.png", directory);
    struct stat rewritten = stat_or_fail(&box, first);
    assert_false(same_file_version(&before[4], &rewritten));
    sandbox_destroy(&box);
#undef SLOW_SEQUENCE
}

/* Splits a stream of PNGs by their structure (PNG specification, 5.2 and
 * 5.3): the 8-byte signature, then chunks, each a 4-byte big-endian data
 * length, a 4-byte type, the data and a 4-byte CRC, up to and including
 * IEND. Fails on anything else. Returns the number of PNGs. */
static size_t split_png_stream(const unsigned char *data, size_t length, size_t *starts,
                               size_t *lengths, size_t capacity)
{
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    size_t count = 0, at = 0;
    while (at < length) {
        if (length - at < 8 || memcmp(data + at, signature, 8) != 0)
            fail_msg("byte %zu of the stream: expected a PNG signature", at);
        size_t start = at;
        at += 8;
        for (;;) {
            if (length - at < 12)
                fail_msg("PNG %zu of the stream is cut short at byte %zu", count, at);
            uint32_t chunk = (uint32_t)data[at] << 24 | (uint32_t)data[at + 1] << 16 |
                             (uint32_t)data[at + 2] << 8 | data[at + 3];
            if (chunk > length - at - 12)
                fail_msg("PNG %zu of the stream: a chunk of %u bytes runs past the end", count,
                         chunk);
            bool end = memcmp(data + at + 4, "IEND", 4) == 0;
            at += 12 + (size_t)chunk;
            if (end)
                break;
        }
        if (count == capacity)
            fail_msg("more than %zu PNGs in the stream", capacity);
        starts[count] = start;
        lengths[count] = at - start;
        count++;
    }
    return count;
}

/* PNG `index` of the stream is file `name` of the sandbox, byte for byte. */
static void assert_stream_png_is(const sandbox *box, const run_result *result,
                                 const size_t *starts, const size_t *lengths, size_t index,
                                 const char *name)
{
    char path[600];
    size_t length = 0;
    sandbox_path(box, name, path, sizeof path);
    char *file = read_file(path, &length);
    assert_non_null(file);
    if (lengths[index] != length || memcmp(result->out + starts[index], file, length) != 0)
        fail_msg("PNG %zu of the stream is not %s", index, name);
    free(file);
}

/* -o -: the PNGs of the sequence on stdout, in order, each the file that
 * one run writes, and nothing else; no file is written. */
static void test_stdout_stream_is_the_files(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    render_one_run(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);

    size_t starts[32], lengths[32];
    run_result result = run_in(&box, ARGS(SEQUENCE, "-o", "-"), NULL);
    assert_success(&result);
    size_t count = split_png_stream((const unsigned char *)result.out, result.out_length,
                                    starts, lengths, 32);
    assert_int_equal(count, 24);
    for (size_t k = 0; k < count; k++) {
        char name[32];
        snprintf(name, sizeof name, "one/f_%02zu.png", k);
        assert_stream_png_is(&box, &result, starts, lengths, k, name);
    }
    run_result_free(&result);

    /* a slice of the sequence streams its own frames */
    result = run_in(&box, ARGS(SEQUENCE, "--frame-range", "5:9", "-o", "-"), NULL);
    assert_success(&result);
    count = split_png_stream((const unsigned char *)result.out, result.out_length, starts,
                             lengths, 32);
    assert_int_equal(count, 5);
    for (size_t i = 0; i < count; i++) {
        char name[32];
        snprintf(name, sizeof name, "one/f_%02zu.png", 5 + i);
        assert_stream_png_is(&box, &result, starts, lengths, i, name);
    }
    run_result_free(&result);

    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

/* The reader of -o - quits after 1000 bytes (as ffmpeg might): luz-render
 * says so in one line and exits with status 1, not killed by SIGPIPE
 * (which the child is given at its default, as a shell would). */
static void test_stdout_reader_quits(void **state)
{
    (void)state;
    const char *program = luz_render_path();
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "", err_path[400];
    list_tree(box.work, "", before, sizeof before);
    snprintf(err_path, sizeof err_path, "%s/stderr", box.root);
    int pipe_ends[2];
    assert_int_equal(pipe(pipe_ends), 0);
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int err = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        signal(SIGPIPE, SIG_DFL);
        if (err < 0 || chdir(box.work) != 0 || dup2(pipe_ends[1], STDOUT_FILENO) < 0 ||
            dup2(err, STDERR_FILENO) < 0)
            _exit(127);
        close(pipe_ends[0]);
        close(pipe_ends[1]);
        unsetenv("LUZ_TEXTURES");
        /* 24 PNGs of some 15 kB: more than a pipe holds, so the writer
         * is still writing when the reader goes */
        execl(program, program, SEQUENCE, "-o", "-", (char *)NULL);
        _exit(127);
    }
    close(pipe_ends[1]);
    unsigned char head[1000];
    size_t got = 0;
    while (got < sizeof head) {
        ssize_t n = read(pipe_ends[0], head + got, sizeof head - got);
        if (n < 0 && errno == EINTR)
            continue;
        assert_true(n > 0);
        got += (size_t)n;
    }
    close(pipe_ends[0]);
    int status;
    assert_int_equal(waitpid(child, &status, 0), child);
    if (!WIFEXITED(status))
        fail_msg("luz-render was killed by signal %d", WTERMSIG(status));
    assert_int_equal(WEXITSTATUS(status), 1);
    assert_memory_equal(head, "\x89PNG\r\n\x1a\n", 8);
    char *err = read_file(err_path, NULL);
    assert_non_null(err);
    assert_int_equal(count_lines(err), 1);
    assert_true(strncmp(err, "luz-render: ", 12) == 0);
    assert_contains(err, "standard output");
    assert_contains(err, "cannot write");
    free(err);
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

/* A terminal as stdout for -o - is refused: status 2, one line, nothing
 * on the terminal, no file. */
static void test_stdout_terminal_refused(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "", err_path[400];
    list_tree(box.work, "", before, sizeof before);
    snprintf(err_path, sizeof err_path, "%s/stderr", box.root);
    const char *arguments[] = {"--frames", "2", "--size", "8x6", "--textures", "none", "-o", "-",
                               NULL};
    char text[4096];
    size_t length;
    assert_int_equal(
        run_on_terminal(&box, arguments, STDOUT_FILENO, err_path, text, sizeof text, &length), 2);
    assert_int_equal(length, 0);
    char *err = read_file(err_path, NULL);
    assert_non_null(err);
    assert_int_equal(count_lines(err), 1);
    assert_contains(err, "luz-render: -o -: ");
    assert_contains(err, "terminal");
    free(err);
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

/* Runs luz-render in box->work with standard output opened on
 * work/stdout_name with open_flags (O_APPEND: `>> name`; neither it nor
 * O_TRUNC: `1<> name`), stderr captured; returns the status and *err. */
static int run_with_stdout_on(const sandbox *box, const char *const *arguments,
                              const char *stdout_name, int open_flags, char **err)
{
    const char *program = luz_render_path();
    char err_path[400], out_path[600];
    snprintf(err_path, sizeof err_path, "%s/stderr", box->root);
    sandbox_path(box, stdout_name, out_path, sizeof out_path);
    char *argv[64];
    program_argv(program, arguments, argv);
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int out = open(out_path, O_WRONLY | open_flags);
        int errfd = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || errfd < 0 || chdir(box->work) != 0 || dup2(out, STDOUT_FILENO) < 0 ||
            dup2(errfd, STDERR_FILENO) < 0)
            _exit(127);
        unsetenv("LUZ_TEXTURES");
        execv(program, argv);
        _exit(127);
    }
    int status;
    while (waitpid(child, &status, 0) < 0)
        assert_int_equal(errno, EINTR);
    *err = read_file(err_path, NULL);
    assert_non_null(*err);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* -o - with standard output redirected onto a file the run reads
 * (appended, or opened without truncating) is refused before anything is
 * written: status 2, one line naming the input, the file unchanged. With
 * a hard link, the same file under another name. A file that is none of
 * the inputs takes the stream as before. */
static void test_stdout_is_never_an_input(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    write_text(box.work, "view.luz", "size = 8x6\ntime = 1\n");
    char tex[600], link_path[600];
    sandbox_path(&box, "tex/a.bmp", tex, sizeof tex);
    sandbox_path(&box, "a-link.bmp", link_path, sizeof link_path);
    assert_int_equal(link(tex, link_path), 0);
    const bool models = luz_models_supported();
    if (models) {
        write_text(box.work, "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                      "vt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n");
        write_text(box.work, "m.mtl", "newmtl m\nKd 1 1 1\nmap_Kd mtex/c.bmp\n");
        make_directory(&box, "mtex");
        char texture[600];
        sandbox_path(&box, "mtex/c.bmp", texture, sizeof texture);
        write_bmp(texture, 2, 2, 10, 20, 30);
    }
    static const struct {
        const char *stdout_name;
        int flags;
        bool model;
        const char *needle;
    } cases[] = {
        {"tex/a.bmp", O_APPEND, false, "is a texture this run reads (tex/a.bmp)"},
        {"tex/b.bmp", 0, false, "is a texture this run reads (tex/b.bmp)"},
        {"a-link.bmp", O_APPEND, false, "is a texture this run reads (tex/a.bmp)"},
        {"view.luz", O_APPEND, false, "is the scene file this run reads"},
        {"m.obj", O_APPEND, true, "is a model this run reads"},
        {"mtex/c.bmp", O_APPEND, true, "is a texture of a model this run reads (/"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        if (cases[c].model && !models)
            continue;
        char path[600];
        sandbox_path(&box, cases[c].stdout_name, path, sizeof path);
        size_t length_before, length_after;
        char *before = read_file(path, &length_before);
        assert_non_null(before);
        char *err;
        const int status =
            cases[c].model
                ? run_with_stdout_on(&box, ARGS("--model", "m.obj", "--textures", "tex",
                                                "--size", "8x6", "-o", "-"),
                                     cases[c].stdout_name, cases[c].flags, &err)
                : run_with_stdout_on(&box, ARGS("--scene", "view.luz", "--textures", "tex",
                                                "--frames", "2", "-o", "-"),
                                     cases[c].stdout_name, cases[c].flags, &err);
        print_message("stdout on %s: %s", cases[c].stdout_name, err);
        assert_int_equal(status, 2);
        assert_int_equal(count_lines(err), 1);
        assert_contains(err, "luz-render: -o -: standard output ");
        assert_contains(err, cases[c].needle);
        char *after = read_file(path, &length_after);
        assert_int_equal(length_after, length_before);
        assert_memory_equal(after, before, length_before);
        free(before);
        free(after);
        free(err);
    }
    /* a file that is no input takes the PNGs */
    write_text(box.work, "frames.bin", "");
    char *err;
    assert_int_equal(run_with_stdout_on(&box, ARGS("--scene", "view.luz", "--textures", "tex",
                                                   "-o", "-"),
                                        "frames.bin", O_APPEND, &err), 0);
    assert_string_equal(err, "");
    free(err);
    char frames[600];
    sandbox_path(&box, "frames.bin", frames, sizeof frames);
    size_t length;
    char *png = read_file(frames, &length);
    assert_true(length > 8 && memcmp(png, "\x89PNG", 4) == 0);
    free(png);
    sandbox_destroy(&box);
}

/* With -o -, the progress bar still goes to stderr when that is a
 * terminal, and stdout holds the PNGs alone. */
static void test_stdout_stream_with_progress_bar(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char out_path[400];
    snprintf(out_path, sizeof out_path, "%s/stdout", box.root);
    const char *arguments[] = {"--frames", "3", "--size", "8x6", "--textures", "none", "-o", "-",
                               NULL};
    char text[4096];
    size_t length;
    assert_int_equal(
        run_on_terminal(&box, arguments, STDERR_FILENO, out_path, text, sizeof text, &length), 0);
    assert_contains(text, "3/3 frames");
    assert_null(memchr(text, 0x89, length));   /* no PNG signature on the terminal */
    size_t out_length = 0, starts[4], lengths[4];
    char *out = read_file(out_path, &out_length);
    assert_non_null(out);
    assert_int_equal(split_png_stream((const unsigned char *)out, out_length, starts, lengths, 4),
                     3);
    free(out);
    sandbox_destroy(&box);
}

/* Where ffmpeg is installed: the -o - stream piped into ffmpeg as the
 * docs/sequences.md shows makes a video of 24 frames, as ffprobe counts them. */
static void test_video_through_ffmpeg(void **state)
{
    (void)state;
    if (!have_programs("ffmpeg ffprobe")) {
        print_message("skipped: ffmpeg is not installed (tools/install-deps test installs it; "
                      "the rest of the sequence tests ran)\n");
        skip();
    }
    sandbox box;
    sandbox_create(&box);
    char command[2048];
    snprintf(command, sizeof command,
             "{ '%s' --frames 24 --fps 12 --size 160x90 --textures tex -o -; "
             "echo $? > luz-status; } | "
             "ffmpeg -loglevel error -f image2pipe -framerate 12 -i - out.mp4 && "
             "ffprobe -v error -count_frames -select_streams v:0 "
             "-show_entries stream=nb_read_frames -of csv=p=0 out.mp4",
             luz_render_path());
    run_result result = run_program_in(&box, "/bin/sh", ARGS("-c", command), NULL);
    if (result.status != 0)
        fail_msg("ffmpeg or ffprobe failed (%d): %s", result.status, result.err);
    char status_path[600];
    sandbox_path(&box, "luz-status", status_path, sizeof status_path);
    char *luz_status = read_file(status_path, NULL);
    assert_non_null(luz_status);
    assert_string_equal(luz_status, "0\n");
    assert_string_equal(result.out, "24\n");
    free(luz_status);
    run_result_free(&result);
    sandbox_destroy(&box);
}

int main(void)
{
    static const struct CMUnitTest fixed_tests[] = {
        cmocka_unit_test(test_help),
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_tiny_render),
        cmocka_unit_test(test_probe),
        cmocka_unit_test(test_probe_example_in_the_docs),
        cmocka_unit_test(test_equals_form_and_default_output),
        cmocka_unit_test(test_textures_directory),
        cmocka_unit_test(test_frame_sequence),
        cmocka_unit_test(test_sequence_times),
        cmocka_unit_test(test_progress_bar_on_a_terminal),
        cmocka_unit_test(test_bench),
        cmocka_unit_test(test_scene_file_and_precedence),
        cmocka_unit_test(test_options_reach_the_image),
        cmocka_unit_test(test_mark_and_legend),
        cmocka_unit_test(test_exposure_and_tone_map_reach_the_image),
        cmocka_unit_test(test_huge_size_refused_at_once),
        cmocka_unit_test(test_scene_nul_bytes),
        cmocka_unit_test(test_long_paths_come_through_whole),
        cmocka_unit_test(test_error_message_room),
        cmocka_unit_test(test_scene_round_trip),
        cmocka_unit_test(test_scene_round_trip_every_saved_key),
        cmocka_unit_test(test_scene_text_of_the_defaults),
        cmocka_unit_test(test_scene_writer_saves_every_scene_key),
        cmocka_unit_test(test_scene_quoted_round_trip),
        cmocka_unit_test(test_scene_quoted_values_read),
        cmocka_unit_test(test_save_scene_never_replaces_unless_asked),
        cmocka_unit_test(test_output_replaces_only_regular_files),
        cmocka_unit_test(test_no_frame_replaces_an_input),
        cmocka_unit_test(test_output_folders_are_made),
        cmocka_unit_test(test_commit_checks_the_path_again),
        cmocka_unit_test(test_save_scene_past_the_file_size_limit),
        cmocka_unit_test(test_parse_precedence_and_forms),
        cmocka_unit_test(test_output_pattern),
        cmocka_unit_test(test_default_textures_directory),
        cmocka_unit_test(test_shard_arithmetic),
        cmocka_unit_test(test_frame_range_and_shard_parsing),
        cmocka_unit_test(test_shards_by_parallel_match_one_run),
        cmocka_unit_test(test_slices_match_one_run),
        cmocka_unit_test(test_killed_shard_resumed),
        cmocka_unit_test(test_orbit_view_renders_the_same_in_luz_render),
        cmocka_unit_test(test_stdout_stream_is_the_files),
        cmocka_unit_test(test_stdout_reader_quits),
        cmocka_unit_test(test_stdout_terminal_refused),
        cmocka_unit_test(test_stdout_is_never_an_input),
        cmocka_unit_test(test_stdout_stream_with_progress_bar),
        cmocka_unit_test(test_video_through_ffmpeg),
    };
    enum { FIXED = sizeof fixed_tests / sizeof fixed_tests[0] };
    /* One named test per refused input, so that a failure says which. */
    static struct CMUnitTest tests[FIXED + ERROR_CASE_COUNT];
    for (size_t i = 0; i < FIXED; i++)
        tests[i] = fixed_tests[i];
    for (size_t i = 0; i < ERROR_CASE_COUNT; i++) {
        tests[FIXED + i] = (struct CMUnitTest){
            .name = error_cases[i].name,
            .test_func = test_refused,
            .initial_state = (void *)&error_cases[i],
        };
    }
    return _cmocka_run_group_tests("cli", tests, FIXED + ERROR_CASE_COUNT, NULL, NULL);
}
