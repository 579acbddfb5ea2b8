/*
 * test_cli_sequences.c: sequences of frames (docs/cli.md, docs/sequences):
 * -o patterns and frame times, the progress bar on a terminal, a sequence
 * cut by --frame-range and --shard (and by tools/render-sequence with GNU
 * parallel) giving the one run's bytes, a killed shard resumed with
 * --skip-existing, and -o -: the PNGs on standard output, a reader that
 * quits, a terminal or an input as stdout refused, and ffmpeg making a
 * video of the stream where it is installed.
 *
 * The tests run the real luz-render ($LUZ_RENDER) and tools/render-sequence
 * ($RENDER_SEQUENCE), set by tests/meson.build, in a fresh sandbox
 * (cli_support.h).
 */
/* posix_openpt and friends, for the progress bar's terminal */
#define _XOPEN_SOURCE 700

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "cli_support.h"

#include <signal.h>
#include <time.h>

#include "io/model.h"

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
    char *argv[64];
    program_argv(program, arguments, argv);

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
    assert_contains(text, "1/3 frames, 0:");
    /* the time so far and the time left (issue 31): none left at the end */
    assert_contains(text, "3/3 frames, 0:");
    assert_contains(text, " elapsed, 0:00 left");
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

/* tools/render-sequence --help prints its own help, not luz-render's
 * (issue 31), and renders nothing. */
static void test_render_sequence_help(void **state)
{
    (void)state;
    const char *tool = getenv("RENDER_SEQUENCE");
    if (tool == NULL)
        fail_msg("RENDER_SEQUENCE is not set (tests/meson.build sets it to tools/render-sequence)");
    if (!have_programs("parallel")) {
        print_message("skipped: GNU parallel is not installed\n");
        skip();
    }
    sandbox box;
    sandbox_create(&box);
    run_result result = run_program_in(&box, tool, ARGS("--help"), NULL);
    assert_success(&result);
    assert_contains(result.out, "Usage: tools/render-sequence [--shards M]");
    assert_contains(result.out, "--sshlogin LOGIN");
    assert_null(strstr(result.out, "Usage: luz-render"));
    assert_null(strstr(result.out, "set -eu"));
    run_result_free(&result);
    sandbox_destroy(&box);
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
    return start_program_in(box, luz_render_path(), arguments, "/dev/null", 0, "/dev/null",
                            NULL);
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
    char err_path[400], out_path[600];
    snprintf(err_path, sizeof err_path, "%s/stderr", box->root);
    sandbox_path(box, stdout_name, out_path, sizeof out_path);
    int status = wait_status(start_program_in(box, luz_render_path(), arguments, out_path,
                                              open_flags, err_path, NULL));
    *err = read_file(err_path, NULL);
    assert_non_null(*err);
    return status;
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
    static const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frame_sequence),
        cmocka_unit_test(test_sequence_times),
        cmocka_unit_test(test_progress_bar_on_a_terminal),
        cmocka_unit_test(test_render_sequence_help),
        cmocka_unit_test(test_shards_by_parallel_match_one_run),
        cmocka_unit_test(test_slices_match_one_run),
        cmocka_unit_test(test_killed_shard_resumed),
        cmocka_unit_test(test_stdout_stream_is_the_files),
        cmocka_unit_test(test_stdout_reader_quits),
        cmocka_unit_test(test_stdout_terminal_refused),
        cmocka_unit_test(test_stdout_is_never_an_input),
        cmocka_unit_test(test_stdout_stream_with_progress_bar),
        cmocka_unit_test(test_video_through_ffmpeg),
    };
    return _cmocka_run_group_tests("cli-sequences", tests, sizeof tests / sizeof tests[0], NULL, NULL);
}
