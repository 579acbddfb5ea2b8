/*
 * test_threads.c: the renderer's thread pool (src/renderer/bands.c). Every
 * job index of a batch must run exactly once, on a worker index below the
 * pool's thread count that names its thread (0 the caller's, one index a
 * thread), and the pool must survive batch after batch; each thread
 * starts with its own share of the jobs. Run under ThreadSanitizer, this
 * is also the pool's race test.
 */
#include <errno.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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

/* ---- distinct worker indices ------------------------------------------ */

/* worker_index tells a job which thread runs it: the bands view tints a
 * band by it (view.c), and a job may keep per-thread scratch indexed by
 * it. So it must name the thread: below the thread count, 0 for the
 * calling thread, and one-to-one, two threads never sharing an index and
 * one thread never reporting two. */

#define INDEX_POOL_MAX_THREADS 4
#define INDEX_JOBS_PER_THREAD 3
#define INDEX_BATCHES 3
#define INDEX_MAX_JOBS (INDEX_POOL_MAX_THREADS * INDEX_JOBS_PER_THREAD)
/* How long a job waits for the other threads to arrive: far beyond a
 * wake-up, even under ThreadSanitizer on a loaded machine; only a pool
 * whose threads never come gets there, and the test still ends. */
#define INDEX_WAIT_SECONDS 10

typedef struct index_observation {
    pthread_t thread;
    int worker_index;
} index_observation;

typedef struct index_batch {
    pthread_mutex_t mutex;
    pthread_cond_t arrived;          /* another thread started its first job */
    pthread_t started[INDEX_MAX_JOBS];   /* distinct threads that started jobs */
    int started_count;
    int wanted;                      /* threads to wait for: the pool's count */
    struct timespec deadline;        /* CLOCK_MONOTONIC */
    index_observation seen[INDEX_MAX_JOBS];   /* by job index */
    int first_job[INDEX_POOL_MAX_THREADS];    /* by worker index */
    bool timed_out;                  /* a job stopped waiting at the deadline */
} index_batch;

/* Records who ran the job, then holds its thread until every thread of
 * the pool has started a job (or the deadline passes). A thread holding a
 * job cannot claim another, so the other jobs wait for the other threads:
 * each of them has to take part, and report its index. */
static void observe_worker(void *context, int job_index, int worker_index)
{
    index_batch *batch = context;
    pthread_t self = pthread_self();
    batch->seen[job_index] = (index_observation){self, worker_index};

    pthread_mutex_lock(&batch->mutex);
    bool known = false;
    for (int k = 0; k < batch->started_count; k++)
        if (pthread_equal(batch->started[k], self)) known = true;
    if (!known) {
        if (worker_index >= 0 && worker_index < INDEX_POOL_MAX_THREADS)
            batch->first_job[worker_index] = job_index;
        batch->started[batch->started_count++] = self;
        pthread_cond_broadcast(&batch->arrived);
    }
    while (batch->started_count < batch->wanted)
        if (pthread_cond_timedwait(&batch->arrived, &batch->mutex, &batch->deadline) ==
            ETIMEDOUT) {
            batch->timed_out = true;
            break;
        }
    pthread_mutex_unlock(&batch->mutex);
}

/* Pools of 2, 3 and 4 threads, three batches each of three jobs per
 * thread. Every job's (thread, worker index) is checked against the
 * properties above; the map from thread to index is built over all of a
 * pool's batches, so a thread that changed its index between batches
 * would be caught too. */
static void test_worker_indices_are_distinct(void **state)
{
    (void)state;
    const pthread_t caller = pthread_self();
    for (int thread_count = 2; thread_count <= INDEX_POOL_MAX_THREADS; thread_count++) {
        luz_thread_pool *pool = luz_thread_pool_create(thread_count);
        assert_non_null(pool);
        const int job_count = thread_count * INDEX_JOBS_PER_THREAD;
        /* Each distinct thread of the pool with the index it reported. */
        index_observation threads[INDEX_MAX_JOBS];
        int thread_total = 0;

        for (int round = 0; round < INDEX_BATCHES; round++) {
            index_batch batch;
            memset(&batch, 0, sizeof batch);
            pthread_condattr_t attributes;
            assert_int_equal(pthread_condattr_init(&attributes), 0);
            assert_int_equal(pthread_condattr_setclock(&attributes, CLOCK_MONOTONIC), 0);
            assert_int_equal(pthread_cond_init(&batch.arrived, &attributes), 0);
            pthread_condattr_destroy(&attributes);
            assert_int_equal(pthread_mutex_init(&batch.mutex, NULL), 0);
            batch.wanted = thread_count;
            clock_gettime(CLOCK_MONOTONIC, &batch.deadline);
            batch.deadline.tv_sec += INDEX_WAIT_SECONDS;

            luz_thread_pool_run(pool, job_count, observe_worker, &batch);

            pthread_cond_destroy(&batch.arrived);
            pthread_mutex_destroy(&batch.mutex);
            /* Several threads took part, or one-to-one would prove nothing.
             * (With the wait above, every thread of the pool normally does;
             * that is checked over all batches below.) */
            if (batch.started_count < 2)
                fail_msg("%d threads, batch %d: only %d thread ran jobs", thread_count, round,
                         batch.started_count);
            for (int job = 0; job < job_count; job++) {
                const index_observation seen = batch.seen[job];
                if (seen.worker_index < 0 || seen.worker_index >= thread_count)
                    fail_msg("%d threads: job %d ran on worker index %d", thread_count, job,
                             seen.worker_index);
                if (pthread_equal(seen.thread, caller) && seen.worker_index != 0)
                    fail_msg("%d threads: the calling thread reported worker index %d",
                             thread_count, seen.worker_index);
                int known = -1;
                for (int k = 0; k < thread_total; k++)
                    if (pthread_equal(threads[k].thread, seen.thread)) known = k;
                if (known >= 0) {
                    if (threads[known].worker_index != seen.worker_index)
                        fail_msg("%d threads: one thread reported worker indices %d and %d",
                                 thread_count, threads[known].worker_index, seen.worker_index);
                    continue;
                }
                for (int k = 0; k < thread_total; k++)
                    if (threads[k].worker_index == seen.worker_index)
                        fail_msg("%d threads: two threads both reported worker index %d",
                                 thread_count, seen.worker_index);
                assert_true(thread_total < INDEX_MAX_JOBS);
                threads[thread_total++] = seen;
            }
            /* Shares (bands.c): thread k of n claims from the k-th n-th of
             * the jobs first, so that consecutive passes over the same
             * data give a thread the same part of it. Its first job is the
             * first of its share, floor(k * jobs / n): no thread can take
             * another's before it has finished its own, and each is held
             * in its first job until all have started one (unless a
             * wait timed out, which frees the thread early). */
            if (batch.started_count == thread_count && !batch.timed_out)
                for (int k = 0; k < thread_count; k++)
                    if (batch.first_job[k] != k * job_count / thread_count)
                        fail_msg("%d threads, batch %d: worker %d began with job %d, not the "
                                 "first of its share, %d", thread_count, round, k,
                                 batch.first_job[k], k * job_count / thread_count);
        }
        /* The calling thread works too (bands.c), as worker 0. */
        bool caller_took_part = false;
        for (int k = 0; k < thread_total; k++)
            if (pthread_equal(threads[k].thread, caller)) caller_took_part = true;
        assert_true(caller_took_part);
        /* Every thread of the pool reported its index in some batch, so
         * each index was checked: the pool has thread_count threads and
         * the wait holds each one's job until the others start theirs. */
        assert_int_equal(thread_total, thread_count);
        luz_thread_pool_destroy(pool);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_job_runs_exactly_once),
        cmocka_unit_test(test_many_batches_in_a_row),
        cmocka_unit_test(test_idle_pool_shuts_down),
        cmocka_unit_test(test_worker_indices_are_distinct),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
