/*
 * test_cpu.c: the choice of instruction set (src/renderer/cpu.c) and
 * LUZ_ISA.
 *
 * The widest set is derived apart from cpu.c's cpuid: from the flags the
 * kernel lists in /proc/cpuinfo (x86-64 Linux; AVX-512 needs F, VL, BW
 * and DQ, AVX2 needs FMA too). Every set this CPU runs is named by the
 * renderer made under its LUZ_ISA and in a frame's statistics; a name no
 * build knows, or a set of another CPU family, is refused by
 * luz_renderer_create and luz_isa_check with the name and the choices,
 * and by luz-render with one line and status 2. Each set's copies of the
 * plain loops (sample_loops.c) do what pipeline.h defines, checked one
 * sample or pixel at a time.
 */
#define _DEFAULT_SOURCE   /* setenv */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "luz/luz.h"
#include "test_support.h"
#include "renderer/cpu.h"

#if defined(__x86_64__) && defined(__linux__)
/* Whether /proc/cpuinfo's first "flags" line lists every one of flags
 * (x86's; aarch64's has "Features", and its widest set is fixed). */
static bool cpuinfo_has(FILE *cpuinfo, const char *const *flags, int count)
{
    rewind(cpuinfo);
    char line[8192];
    while (fgets(line, sizeof line, cpuinfo) != NULL) {
        if (strncmp(line, "flags", 5) != 0) continue;
        for (int i = 0; i < count; i++) {
            char word[40];
            snprintf(word, sizeof word, " %s", flags[i]);
            const char *at = strstr(line, word);
            const size_t length = strlen(word);
            if (at == NULL || (at[length] != ' ' && at[length] != '\n')) return false;
        }
        return true;
    }
    return false;
}
#endif

static void test_widest_is_what_the_cpu_lists(void **state)
{
    (void)state;
#if defined(__x86_64__) && defined(__linux__)
    FILE *cpuinfo = fopen("/proc/cpuinfo", "r");
    if (cpuinfo == NULL) skip();
    static const char *const avx512[] = {"avx512f", "avx512vl", "avx512bw", "avx512dq",
                                         "avx2", "fma"};
    static const char *const avx2[] = {"avx2", "fma"};
    const luz_isa expected = cpuinfo_has(cpuinfo, avx512, 6) ? LUZ_ISA_AVX512
                             : cpuinfo_has(cpuinfo, avx2, 2) ? LUZ_ISA_AVX2
                                                             : LUZ_ISA_BASELINE;
    fclose(cpuinfo);
    print_message("this CPU: %s\n", luz_isa_name(expected));
    assert_int_equal(luz_isa_widest(), expected);
    assert_string_equal(luz_isa_name(LUZ_ISA_BASELINE), "sse2");
#elif defined(__aarch64__)
    /* Advanced SIMD is part of the aarch64 architecture. */
    assert_int_equal(luz_isa_widest(), LUZ_ISA_BASELINE);
    assert_string_equal(luz_isa_name(LUZ_ISA_BASELINE), "neon");
#else
    skip();
#endif
    /* A set no wider than an available one is available. */
    for (int isa = LUZ_ISA_SCALAR; isa <= (int)luz_isa_widest(); isa++)
        assert_true(luz_isa_available((luz_isa)isa));
}

/* The renderer made under LUZ_ISA=name, or NULL with error's reason. */
static luz_renderer *renderer_under(const char *name, luz_error *error)
{
    if (name != NULL) assert_int_equal(setenv("LUZ_ISA", name, 1), 0);
    else assert_int_equal(unsetenv("LUZ_ISA"), 0);
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, error);
    unsetenv("LUZ_ISA");
    return renderer;
}

static void test_each_set_is_named(void **state)
{
    (void)state;
    luz_error error = {{0}};
    luz_framebuffer *framebuffer = luz_framebuffer_create(8, 8, &error);
    assert_non_null(framebuffer);
    const luz_frame frame = {0};   /* nothing to draw: a cleared image */
    int named = 0;
    for (int isa = 0; isa < LUZ_ISA_COUNT; isa++) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        const char *name = luz_isa_name((luz_isa)isa);
        luz_renderer *renderer = renderer_under(name, &error);
        assert_non_null(renderer);
        assert_string_equal(luz_renderer_isa(renderer), name);
        luz_frame_stats stats;
        assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer,
                                           &(luz_render_options){.stats = &stats}, &error),
                         0);
        assert_string_equal(stats.isa, name);
        luz_renderer_destroy(renderer);
        named++;
    }
    assert_true(named >= 2);   /* scalar and the build's target at least */
    /* Unset or empty: the widest. */
    for (int empty = 0; empty < 2; empty++) {
        luz_renderer *renderer = renderer_under(empty ? "" : NULL, &error);
        assert_non_null(renderer);
        assert_string_equal(luz_renderer_isa(renderer), luz_isa_name(luz_isa_widest()));
        luz_renderer_destroy(renderer);
    }
    luz_framebuffer_destroy(framebuffer);
}

static void test_unknown_names_are_refused(void **state)
{
    (void)state;
#if defined(__aarch64__)
    static const char *const foreign = "avx2";
#else
    static const char *const foreign = "neon";
#endif
    const char *const refused[] = {"avx9", "AVX2", "scalar ", "", foreign};
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        if (refused[k][0] == '\0') continue;   /* empty is unset */
        luz_error error = {{0}};
        assert_null(renderer_under(refused[k], &error));
        print_message("%s\n", error.message);
        char expected[64];
        snprintf(expected, sizeof expected, "LUZ_ISA=%s:", refused[k]);
        assert_non_null(strstr(error.message, expected));
        assert_non_null(strstr(error.message, "expected"));
        assert_non_null(strstr(error.message, "scalar"));
        assert_int_equal(setenv("LUZ_ISA", refused[k], 1), 0);
        luz_error check = {{0}};
        assert_int_equal(luz_isa_check(&check), -1);
        assert_string_equal(check.message, error.message);
        unsetenv("LUZ_ISA");
    }
}

/* luz-render under LUZ_ISA=avx9: one line on stderr naming it, status 2,
 * nothing on stdout. LUZ_EXE_WRAPPER, if set, is the program that runs
 * luz-render (a cross build's emulator). */
static void test_luz_render_refuses_an_unknown_set(void **state)
{
    (void)state;
    const char *program = getenv("LUZ_RENDER");
    if (program == NULL) fail_msg("LUZ_RENDER is not set (tests/meson.build sets it)");
    int err[2], out[2];
    assert_int_equal(pipe(err), 0);
    assert_int_equal(pipe(out), 0);
    fflush(NULL);
    const pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        if (dup2(err[1], STDERR_FILENO) < 0 || dup2(out[1], STDOUT_FILENO) < 0) _exit(127);
        close(err[0]);
        close(out[0]);
        setenv("LUZ_ISA", "avx9", 1);
        /* A cross build's luz-render runs through the emulator that runs
         * this test (tools/aarch64-check: qemu-aarch64; no binfmt_misc
         * needed). */
        const char *wrapper = getenv("LUZ_EXE_WRAPPER");
        if (wrapper != NULL && wrapper[0] != '\0')
            execlp(wrapper, wrapper, program, "--bench", "1", "--size", "8x8", (char *)NULL);
        else
            execl(program, program, "--bench", "1", "--size", "8x8", (char *)NULL);
        _exit(127);
    }
    close(err[1]);
    close(out[1]);
    char text[1024] = "", printed[16];
    size_t length = 0;
    ssize_t got;
    while ((got = read(err[0], text + length, sizeof text - 1 - length)) > 0)
        length += (size_t)got;
    text[length] = '\0';
    const ssize_t on_stdout = read(out[0], printed, sizeof printed);
    close(err[0]);
    close(out[0]);
    int status;
    while (waitpid(child, &status, 0) < 0) assert_int_equal(errno, EINTR);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 2);
    assert_int_equal(on_stdout, 0);
    assert_non_null(strstr(text, "luz-render: LUZ_ISA=avx9: expected"));
    assert_non_null(strchr(text, '\n'));
    assert_int_equal(strchr(text, '\n') - text, (ptrdiff_t)length - 1);   /* one line */
}

/* Every set's depth tests of a span of pixel centres (sample_loops.c,
 * through the table): where luz_raster_depth at x is LESS than the row's,
 * both rows take it; elsewhere, equal depths included, and outside
 * [first, last], nothing changes. Spans of 0 to 70 pixels at every start,
 * so that every copy's vector remainders run. */
static void test_every_set_tests_centre_spans_as_defined(void **state)
{
    (void)state;
    enum { ROW = 96 };
    uint32_t seed = 29;
    for (int isa = 0; isa < LUZ_ISA_COUNT; isa++) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        const luz_kernels kernels = luz_kernels_of((luz_isa)isa);
        int replaced = 0, kept = 0;
        for (int trial = 0; trial < 400; trial++) {
            const luz_plane depth = {(float)(test_random(&seed) % 1000) / 1000.0f,
                                     ((float)(test_random(&seed) % 200) - 100.0f) / 4096.0f,
                                     ((float)(test_random(&seed) % 200) - 100.0f) / 4096.0f};
            const float reference_x = (float)(test_random(&seed) % 64) + 0.5f;
            const float row_depth = luz_raster_row_depth(depth, 3.5f, 7);
            const int first = (int)(test_random(&seed) % 20);
            const int last = first - 1 + (int)(test_random(&seed) % 71);
            float depth_row[ROW], expected_depth[ROW];
            uint32_t visibility_row[ROW], expected_visibility[ROW];
            for (int x = 0; x < ROW; x++) {
                const float z = luz_raster_depth(depth, reference_x, row_depth, x);
                /* Nearer, farther, or the same depth (kept: LESS). */
                const uint32_t pick = test_random(&seed) % 3;
                depth_row[x] = pick == 0 ? z : pick == 1 ? z + 0.25f : z - 0.25f;
                visibility_row[x] = 1000 + (uint32_t)x;
                const bool inside = x >= first && x <= last;
                const bool wins = inside && pick == 1;
                expected_depth[x] = wins ? z : depth_row[x];
                expected_visibility[x] = wins ? 7 : visibility_row[x];
                replaced += wins;
                kept += inside && !wins;
            }
            kernels.centre_span_test(depth, reference_x, row_depth, first, last, depth_row,
                                     visibility_row, 7);
            assert_memory_equal(depth_row, expected_depth, sizeof depth_row);
            assert_memory_equal(visibility_row, expected_visibility, sizeof visibility_row);
        }
        assert_true(replaced > 1000 && kept > 1000);
    }
}

/* Every set's mixed pixels of a row (sample_loops.c, through the table):
 * each pixel's sample 0 into first, and the x, in order, where the four
 * samples' ids are not all equal, found here one pixel at a time. Rows of
 * 1 to 200 pixels, most pixels agreeing (as inside a surface), a few
 * differing in one sample or more. */
static void test_every_set_finds_mixed_pixels_as_defined(void **state)
{
    (void)state;
    enum { ROW = 200 };
    uint32_t seed = 27;
    for (int isa = 0; isa < LUZ_ISA_COUNT; isa++) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        const luz_kernels kernels = luz_kernels_of((luz_isa)isa);
        int found = 0;
        for (int trial = 0; trial < 300; trial++) {
            const int width = 1 + (int)(test_random(&seed) % ROW);
            uint32_t ids[ROW][LUZ_MAX_SAMPLES], first[ROW], expected_first[ROW];
            uint16_t expected[ROW], mixed[ROW];
            int count = 0;
            for (int x = 0; x < width; x++) {
                const uint32_t id = test_random(&seed) % 4;   /* 0: the background */
                for (int k = 0; k < 4; k++) ids[x][k] = id;
                if (test_random(&seed) % 8 == 0)   /* an edge: one sample or more differs */
                    for (int k = 0; k < 4; k++)
                        if (test_random(&seed) % 2) ids[x][k] = test_random(&seed) % 4;
                if (ids[x][0] != ids[x][1] || ids[x][0] != ids[x][2] || ids[x][0] != ids[x][3])
                    expected[count++] = (uint16_t)x;
                expected_first[x] = ids[x][0];
            }
            assert_int_equal(kernels.mixed_pixels(&ids[0][0], width, first, mixed), count);
            if (count > 0) assert_memory_equal(mixed, expected, (size_t)count * sizeof *mixed);
            assert_memory_equal(first, expected_first, (size_t)width * sizeof *first);
            found += count;
        }
        assert_true(found > 1000);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_widest_is_what_the_cpu_lists),
        cmocka_unit_test(test_each_set_is_named),
        cmocka_unit_test(test_unknown_names_are_refused),
        cmocka_unit_test(test_luz_render_refuses_an_unknown_set),
        cmocka_unit_test(test_every_set_tests_centre_spans_as_defined),
        cmocka_unit_test(test_every_set_finds_mixed_pixels_as_defined),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
