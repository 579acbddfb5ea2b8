/*
 * test_bench.c: the --bench loop every program shares (app/bench.h): its
 * schedule of scene times, its early stop, its errors, and the medians it
 * prints, against values worked out by hand.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "app/bench.h"

typedef struct recorder {
    double times[16];
    int calls;
    int stop_at;      /* return 1 on this call (0: never) */
    int fail_at;      /* return -1 on this call (0: never) */
} recorder;

/* Reports parts that follow the call number, so their medians are known:
 * call c (1 is the warm-up) reports c and 10 c. */
static int record_frame(void *context, double time_seconds, double parts[LUZ_BENCH_MAX_PARTS],
                        luz_error *error)
{
    recorder *r = context;
    r->times[r->calls++] = time_seconds;
    if (r->calls == r->stop_at) return 1;
    if (r->calls == r->fail_at) return luz_error_set(error, "frame %d failed", r->calls);
    parts[0] = r->calls;
    parts[1] = 10.0 * r->calls;
    return 0;
}

/* One warm-up at the start time, then frame k at start + k / fps. */
static void test_schedule_is_warm_up_then_k_over_fps(void **state)
{
    (void)state;
    recorder r = {0};
    luz_bench bench = {.part_names = {"a_ms", "b_ms"}};
    assert_int_equal(luz_bench_run(&bench, 4, 2.0, 8.0, record_frame, &r, NULL), 0);
    assert_int_equal(bench.frames, 4);
    assert_int_equal(r.calls, 5);
    const double expected[5] = {2.0, 2.0, 2.125, 2.25, 2.375};
    for (int k = 0; k < 5; k++) assert_true(r.times[k] == expected[k]);
    /* The measured frames are calls 2 to 5: parts 2, 3, 4, 5 (median 3.5)
     * and 20 ... 50 (median 35); the warm-up's 1 and 10 are not counted. */
    char line[512] = {0};
    FILE *out = fmemopen(line, sizeof line - 1, "w");
    assert_non_null(out);
    luz_bench_print_figures(out, &bench);
    fclose(out);
    assert_non_null(strstr(line, " a_ms=3.500 b_ms=35.000"));
    assert_true(strncmp(line, "median_ms=", 10) == 0);
    assert_null(strchr(line, '\n'));
    luz_bench_free(&bench);
}

/* A frame that asks to stop ends the run with the frames so far; one that
 * fails ends it with -1 and its reason. */
static void test_early_stop_and_failure(void **state)
{
    (void)state;
    recorder stop = {.stop_at = 4};
    luz_bench bench = {.part_names = {"a_ms"}};
    assert_int_equal(luz_bench_run(&bench, 10, 0.0, 30.0, record_frame, &stop, NULL), 0);
    assert_int_equal(bench.frames, 2);   /* the warm-up, 2 frames, then the stop */
    luz_bench_free(&bench);

    recorder fail = {.fail_at = 3};
    luz_error error = {{0}};
    assert_int_equal(luz_bench_run(&bench, 10, 0.0, 30.0, record_frame, &fail, &error), -1);
    assert_string_equal(error.message, "frame 3 failed");
    luz_bench_free(&bench);
}

/* The median of an even count is the mean of the middle two; the values
 * come back sorted, the minimum first. */
static void test_median(void **state)
{
    (void)state;
    double odd[5] = {5, 1, 4, 2, 3};
    assert_true(luz_median(odd, 5) == 3.0);
    assert_true(odd[0] == 1.0);
    double even[4] = {8, 2, 6, 4};
    assert_true(luz_median(even, 4) == 5.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_schedule_is_warm_up_then_k_over_fps),
        cmocka_unit_test(test_early_stop_and_failure),
        cmocka_unit_test(test_median),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
