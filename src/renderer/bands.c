/*
 * bands.c: the renderer's persistent worker threads.
 *
 * A pool of thread_count - 1 workers, started once and reused for every
 * frame; the calling thread works too, so thread_count threads share each
 * batch of jobs. Each thread has a share of the jobs, a run of consecutive
 * indices (thread k of n, counting from 0: [k N / n, (k + 1) N / n) of N),
 * and claims them one at a time from its share's atomic counter; a thread
 * whose share is done takes jobs from the others' shares, so that all
 * finish together. The shares are for the caches: the passes of a frame
 * cut the same data the same way (the geometry's vertex ranges, then its
 * batches of triangles, then their bins, in mesh order), so that a thread
 * mostly reads what it wrote itself, from its own cache, rather than lines
 * another core holds (taking jobs from one counter, two threads' jobs
 * interleave, and on the 1M-triangle sphere the triangle pass spent about
 * 60% longer reading its vertices with two threads than with one). Which
 * thread runs which job still varies from run to run; the callers
 * (frame.c) make sure the result never depends on it: a job writes only
 * its own rows or its own output list.
 *
 * Between batches the workers sleep on a condition variable: no spinning,
 * so an idle viewer or a single-threaded test costs no CPU.
 */
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>

#include "renderer/pipeline.h"

typedef struct worker {
    luz_thread_pool *pool;
    int index;
    pthread_t thread;
} worker;

/* Jobs [next, end) of a thread's share are not claimed yet. A cache line
 * each, so that claiming from one share does not slow the other threads'
 * claims. */
typedef struct job_share {
    _Alignas(64) atomic_int next;
    int end;
} job_share;

struct luz_thread_pool {
    int thread_count;
    worker *workers;            /* thread_count - 1 of them */
    int started_workers;

    pthread_mutex_t mutex;
    pthread_cond_t start;       /* a batch is ready, or stop */
    pthread_cond_t finished;    /* the last worker left the batch */
    unsigned long generation;   /* batches handed out so far */
    int busy_workers;
    bool stopping;

    /* The current batch: written under the mutex before the generation
     * changes, read by the workers after they see the change. */
    luz_job_function *job;
    void *context;
    job_share *shares;          /* thread_count of them */
};

/* Runs the jobs of the thread's own share, then helps with the others'. */
static void run_jobs(luz_thread_pool *pool, luz_job_function *job, void *context,
                     int worker_index)
{
    for (int k = 0; k < pool->thread_count; k++) {
        job_share *share = &pool->shares[(worker_index + k) % pool->thread_count];
        /* A share already done costs a read, not a contended add. */
        if (atomic_load_explicit(&share->next, memory_order_relaxed) >= share->end) continue;
        for (;;) {
            int index = atomic_fetch_add_explicit(&share->next, 1, memory_order_relaxed);
            if (index >= share->end) break;
            job(context, index, worker_index);
        }
    }
}

static void *worker_main(void *argument)
{
    worker *self = argument;
    luz_thread_pool *pool = self->pool;
    unsigned long seen = 0;

    pthread_mutex_lock(&pool->mutex);
    for (;;) {
        while (!pool->stopping && pool->generation == seen)
            pthread_cond_wait(&pool->start, &pool->mutex);
        if (pool->stopping) break;
        seen = pool->generation;
        luz_job_function *job = pool->job;
        void *context = pool->context;
        pthread_mutex_unlock(&pool->mutex);

        run_jobs(pool, job, context, self->index);

        pthread_mutex_lock(&pool->mutex);
        if (--pool->busy_workers == 0) pthread_cond_signal(&pool->finished);
    }
    pthread_mutex_unlock(&pool->mutex);
    return NULL;
}

luz_thread_pool *luz_thread_pool_create(int thread_count)
{
    if (thread_count < 1) thread_count = 1;
    luz_thread_pool *pool = calloc(1, sizeof *pool);
    if (!pool) return NULL;
    pool->thread_count = thread_count;
    if (thread_count == 1) return pool;

    pool->workers = calloc((size_t)thread_count - 1, sizeof *pool->workers);
    if (!pool->workers) goto fail_workers;
    pool->shares =
        aligned_alloc(_Alignof(job_share), (size_t)thread_count * sizeof *pool->shares);
    if (!pool->shares) goto fail_shares;
    for (int i = 0; i < thread_count; i++) {
        atomic_init(&pool->shares[i].next, 0);
        pool->shares[i].end = 0;
    }
    if (pthread_mutex_init(&pool->mutex, NULL) != 0) goto fail_mutex;
    if (pthread_cond_init(&pool->start, NULL) != 0) goto fail_start;
    if (pthread_cond_init(&pool->finished, NULL) != 0) goto fail_finished;
    /* Workers start with every signal blocked (a new thread inherits its
     * creator's mask), so that signals sent to the process go to the
     * caller's threads, as a program that never made a renderer would see
     * them; luz_png_write relies on this to hold Ctrl-C until a file is
     * complete. */
    sigset_t all_signals, caller_mask;
    sigfillset(&all_signals);
    pthread_sigmask(SIG_SETMASK, &all_signals, &caller_mask);
    for (int i = 0; i < thread_count - 1; i++) {
        pool->workers[i].pool = pool;
        pool->workers[i].index = i + 1;   /* 0 is the calling thread */
        if (pthread_create(&pool->workers[i].thread, NULL, worker_main, &pool->workers[i]) != 0)
            break;
        pool->started_workers++;
    }
    pthread_sigmask(SIG_SETMASK, &caller_mask, NULL);
    if (pool->started_workers == thread_count - 1) return pool;
    luz_thread_pool_destroy(pool);   /* stops the ones that did start */
    return NULL;

fail_finished:
    pthread_cond_destroy(&pool->start);
fail_start:
    pthread_mutex_destroy(&pool->mutex);
fail_mutex:
    free(pool->shares);
fail_shares:
    free(pool->workers);
fail_workers:
    free(pool);
    return NULL;
}

void luz_thread_pool_destroy(luz_thread_pool *pool)
{
    if (!pool) return;
    if (pool->thread_count > 1) {
        pthread_mutex_lock(&pool->mutex);
        pool->stopping = true;
        pthread_cond_broadcast(&pool->start);
        pthread_mutex_unlock(&pool->mutex);
        for (int i = 0; i < pool->started_workers; i++)
            pthread_join(pool->workers[i].thread, NULL);
        pthread_cond_destroy(&pool->finished);
        pthread_cond_destroy(&pool->start);
        pthread_mutex_destroy(&pool->mutex);
        free(pool->shares);
        free(pool->workers);
    }
    free(pool);
}

int luz_thread_pool_thread_count(const luz_thread_pool *pool)
{
    return pool->thread_count;
}

void luz_thread_pool_run(luz_thread_pool *pool, int job_count, luz_job_function *job,
                         void *context)
{
    if (pool->thread_count == 1 || job_count <= 1) {
        for (int i = 0; i < job_count; i++) job(context, i, 0);
        return;
    }
    pthread_mutex_lock(&pool->mutex);
    pool->job = job;
    pool->context = context;
    for (int i = 0; i < pool->thread_count; i++) {
        job_share *share = &pool->shares[i];
        atomic_store_explicit(&share->next,
                              (int)((int64_t)job_count * i / pool->thread_count),
                              memory_order_relaxed);
        share->end = (int)((int64_t)job_count * (i + 1) / pool->thread_count);
    }
    pool->busy_workers = pool->thread_count - 1;
    pool->generation++;
    pthread_cond_broadcast(&pool->start);
    pthread_mutex_unlock(&pool->mutex);

    run_jobs(pool, job, context, 0);

    pthread_mutex_lock(&pool->mutex);
    while (pool->busy_workers > 0) pthread_cond_wait(&pool->finished, &pool->mutex);
    pthread_mutex_unlock(&pool->mutex);
}
