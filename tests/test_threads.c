/*
 * test_threads.c: the renderer's thread pool (src/pipeline/bands.c). Every
 * job index of a batch must run exactly once, on a worker index below the
 * pool's thread count, and the pool must survive batch after batch. Run
 * under ThreadSanitizer, this is also the pool's race test.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdlib.h>

#include <cmocka.h>

#include "renderer/pipeline.h"

#define MAX_JOBS 1000

typedef struct job_record {
    atomic_int runs[MAX_JOBS];      /* how many times each job index ran */
    atomic_int bad_workers;         /* jobs that saw an out-of-range worker */
    int thread_count;
} job_record;

static void record_job(void *context, int job_index, int worker_index)
{
    job_record *record = context;
    atomic_fetch_add(&record->runs[job_index], 1);
    if (worker_index < 0 || worker_index >= record->thread_count)
        atomic_fetch_add(&record->bad_workers, 1);
}

static void reset(job_record *record, int thread_count)
{
    for (int i = 0; i < MAX_JOBS; i++) atomic_store(&record->runs[i], 0);
    atomic_store(&record->bad_workers, 0);
    record->thread_count = thread_count;
}

/* Job counts 0, 1, 7 and 1000 with 1, 2 and 5 threads: each index in
 * [0, job_count) runs once, none beyond it runs, and every worker index
 * is in [0, thread_count). */
static void test_every_job_runs_exactly_once(void **state)
{
    (void)state;
    const int thread_counts[3] = {1, 2, 5};
    const int job_counts[4] = {0, 1, 7, MAX_JOBS};
    job_record *record = malloc(sizeof *record);
    assert_non_null(record);
    for (int t = 0; t < 3; t++) {
        luz_thread_pool *pool = luz_thread_pool_create(thread_counts[t]);
        assert_non_null(pool);
        assert_int_equal(luz_thread_pool_thread_count(pool), thread_counts[t]);
        for (int j = 0; j < 4; j++) {
            reset(record, thread_counts[t]);
            luz_thread_pool_run(pool, job_counts[j], record_job, record);
            for (int i = 0; i < MAX_JOBS; i++) {
                int expected = i < job_counts[j] ? 1 : 0;
                if (atomic_load(&record->runs[i]) != expected)
                    fail_msg("%d threads, %d jobs: job %d ran %d times", thread_counts[t],
                             job_counts[j], i, atomic_load(&record->runs[i]));
            }
            assert_int_equal(atomic_load(&record->bad_workers), 0);
        }
        luz_thread_pool_destroy(pool);
    }
    free(record);
}

/* One pool, 1000 batches of varying size (1 to 64 jobs) in a row, as the
 * renderer runs two batches per frame: all of each batch is done when
 * luz_thread_pool_run returns, before the next one starts. */
static void test_many_batches_in_a_row(void **state)
{
    (void)state;
    job_record *record = malloc(sizeof *record);
    assert_non_null(record);
    luz_thread_pool *pool = luz_thread_pool_create(5);
    assert_non_null(pool);
    for (int batch = 0; batch < 1000; batch++) {
        int job_count = 1 + batch % 64;
        reset(record, 5);
        luz_thread_pool_run(pool, job_count, record_job, record);
        for (int i = 0; i < MAX_JOBS; i++) {
            int expected = i < job_count ? 1 : 0;
            if (atomic_load(&record->runs[i]) != expected)
                fail_msg("batch %d: job %d ran %d times", batch, i,
                         atomic_load(&record->runs[i]));
        }
        assert_int_equal(atomic_load(&record->bad_workers), 0);
    }
    luz_thread_pool_destroy(pool);
    free(record);
}

/* A pool created and destroyed without ever running a batch shuts its
 * workers down cleanly (the leak checker and ThreadSanitizer watch). */
static void test_idle_pool_shuts_down(void **state)
{
    (void)state;
    for (int round = 0; round < 20; round++) {
        luz_thread_pool *pool = luz_thread_pool_create(4);
        assert_non_null(pool);
        luz_thread_pool_destroy(pool);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_job_runs_exactly_once),
        cmocka_unit_test(test_many_batches_in_a_row),
        cmocka_unit_test(test_idle_pool_shuts_down),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
