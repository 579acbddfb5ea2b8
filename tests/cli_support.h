/*
 * cli_support.h: what the tests of luz-render as a user runs it share
 * (test_cli_render, test_cli_refused, test_cli_output, test_cli_sequences)
 * and test_options: a sandbox of fixtures, running a program in it with
 * its output captured, and the checks on what it left. Include after
 * <cmocka.h>.
 *
 *   sandbox_create(&box)       a fresh temporary directory: work/ is where
 *                              the program runs, with tex/ (two small BMPs
 *                              written by hand here), empty/ (no image) and
 *                              corrupt/ (a .png that is not one); the
 *                              captured output lies beside work/, so that
 *                              work/ holds only what the program made
 *   run_in(&box, ARGS(...), textures_env)   luz-render ($LUZ_RENDER) in
 *                              work/: exit status, stdout, stderr
 *   run_program_in(&box, program, ...)      another program the same way
 *   assert_success, assert_png_size, assert_new_files, assert_contains
 *   parse_or_fail, read_scene_from          the option functions, in process
 */
#ifndef LUZ_TEST_CLI_SUPPORT_H
#define LUZ_TEST_CLI_SUPPORT_H

#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "file_support.h"

#include "luz/luz.h"
#include "app/options.h"

static inline void write_file(const char *path, const void *data, size_t length)
{
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(data, 1, length, file), length);
    assert_int_equal(fclose(file), 0);
}

static inline void write_text(const char *directory, const char *name, const char *text)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", directory, name);
    write_file(path, text, strlen(text));
}

/* A 24-bit uncompressed BMP, the simplest image format stb_image reads:
 * a 14-byte file header, a 40-byte info header, then rows bottom-up, each
 * padded to a multiple of 4 bytes. */
static inline void write_bmp(const char *path, int width, int height, uint8_t red,
                             uint8_t green, uint8_t blue)
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
static inline bool has_line(const char *text, const char *line, size_t length)
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
static inline void assert_new_files(const char *before, const char *after,
                                    const char *const *expected)
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

/* A fresh temporary directory: work/ is where luz-render runs, the captured
 * output lies beside it so that work/ holds only what the program made. */
typedef struct sandbox {
    char root[256];
    char work[300];
} sandbox;

static inline void sandbox_create(sandbox *box)
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

static inline void sandbox_destroy(sandbox *box)
{
    remove_tree(box->root);
}

static inline void sandbox_path(const sandbox *box, const char *name, char *out, size_t size)
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

static inline const char *luz_render_path(void)
{
    const char *program = getenv("LUZ_RENDER");
    if (program == NULL)
        fail_msg("LUZ_RENDER is not set (tests/meson.build sets it to luz-render's path)");
    return program;
}

/* argv for execv: the program, then the arguments (at most 62 of them),
 * then NULL. */
static inline void program_argv(const char *program, const char *const *arguments,
                                char *argv[64])
{
    int argc = 0;
    argv[argc++] = (char *)program;
    for (int i = 0; arguments[i] != NULL && argc < 63; i++)
        argv[argc++] = (char *)arguments[i];
    argv[argc] = NULL;
}

/* Starts program with the NULL-terminated arguments in box->work, its
 * stdout on out_path opened with O_WRONLY | out_flags (0644 if it creates
 * it), its stderr on err_path, created or emptied. textures_environment
 * sets $LUZ_TEXTURES; NULL unsets it, so that no test depends on the
 * caller's environment. */
static inline pid_t start_program_in(const sandbox *box, const char *program,
                                     const char *const *arguments, const char *out_path,
                                     int out_flags, const char *err_path,
                                     const char *textures_environment)
{
    char *argv[64];
    program_argv(program, arguments, argv);
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int out = open(out_path, O_WRONLY | out_flags, 0644);
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
    return child;
}

/* Waits for child: its exit status, or 128 + the signal that ended it. */
static inline int wait_status(pid_t child)
{
    int status;
    while (waitpid(child, &status, 0) < 0)
        assert_int_equal(errno, EINTR);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* Runs program as start_program_in does, stdout and stderr captured in
 * files beside box->work. */
static inline run_result run_program_in(const sandbox *box, const char *program,
                                        const char *const *arguments,
                                        const char *textures_environment)
{
    char out_path[400], err_path[400];
    snprintf(out_path, sizeof out_path, "%s/stdout", box->root);
    snprintf(err_path, sizeof err_path, "%s/stderr", box->root);
    double start = now_seconds();
    pid_t child = start_program_in(box, program, arguments, out_path, O_CREAT | O_TRUNC,
                                   err_path, textures_environment);
    run_result result;
    result.status = wait_status(child);
    result.seconds = now_seconds() - start;
    result.out = read_file(out_path, &result.out_length);
    result.err = read_file(err_path, NULL);
    assert_non_null(result.out);
    assert_non_null(result.err);
    return result;
}

/* Runs luz-render, as run_program_in does. */
static inline run_result run_in(const sandbox *box, const char *const *arguments,
                                const char *textures_environment)
{
    return run_program_in(box, luz_render_path(), arguments, textures_environment);
}

static inline void run_result_free(run_result *result)
{
    free(result->out);
    free(result->err);
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

static inline void assert_contains(const char *text, const char *needle)
{
    if (strstr(text, needle) == NULL)
        fail_msg("'%s' lacks '%s'", text, needle);
}

/* Exit status 0 with nothing on stderr; shows stderr if not. */
static inline void assert_success(const run_result *result)
{
    if (result->status != 0 || result->err[0] != '\0')
        fail_msg("luz-render exited %d, stderr: %s", result->status, result->err);
}

/* The PNG signature, then the IHDR chunk (length 13) whose first eight
 * bytes are the width and height, big-endian (PNG specification 11.2.2). */
static inline void assert_png_size(const sandbox *box, const char *name, uint32_t width,
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

/* Reads a scene file into fresh options, as luz-render --scene does. */
static inline void read_scene_from(luz_options *options, const char *path)
{
    luz_error error = {{0}};
    luz_options_init(options);
    if (luz_options_read_scene_file(options, path, &error) != 0 ||
        luz_options_finish(options, &error) != 0)
        fail_msg("reading %s back: %s", path, error.message);
}

/* Parses a command line into fresh options. */
static inline void parse_or_fail(luz_options *options, int argc, char **argv)
{
    luz_error error = {{0}};
    luz_options_init(options);
    if (luz_options_parse(options, argc, argv, &error) != 0)
        fail_msg("%s", error.message);
}

#endif
