/*
 * model_sandbox.c: a model's import in a child process, within limits
 * (io/model_sandbox.h).
 *
 * In:  a model file's path and size, and the work the child does (assimp's
 *      import, writing the model's description down a pipe).
 * Out: the bytes the child sent, once it has exited normally; else one
 *      line naming the file: crashed, over the time or memory limit, or
 *      failed.
 *
 * The child is made with fork() and ends with _exit(): it runs no atexit
 * handler and flushes none of the parent's stdio buffers (luz-render may
 * hold half a PNG for standard output). It dies with its parent
 * (PR_SET_PDEATHSIG on Linux: io/platform.h), limits itself (RLIMIT_CPU, RLIMIT_AS, no core
 * files), writes to the pipe and exits. The parent
 * reads with poll() against a wall-clock deadline (a child that blocks or
 * sleeps uses no CPU time), kills the child when it passes, always reaps
 * it (no zombies) and closes both ends of the pipe on every path. The
 * pipe is made O_CLOEXEC; the child ignores SIGPIPE, so a parent that
 * stopped reading makes its write fail (EPIPE) and it exits.
 */
/* sigaltstack and SA_ONSTACK (POSIX's XSI part), and wait4 (4.3BSD's,
 * which POSIX does not name but Linux, macOS and the BSDs have): glibc
 * declares them with _DEFAULT_SOURCE, the others by default. */
#define _DEFAULT_SOURCE
#include "io/model_sandbox.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "io/input_file.h"
#include "io/model_confine.h"
#include "io/platform.h"

/* AddressSanitizer and ThreadSanitizer reserve terabytes of address space
 * for their shadow memory: under them, RLIMIT_AS would stop everything. */
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define LUZ_ADDRESS_SPACE_RESERVED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define LUZ_ADDRESS_SPACE_RESERVED 1
#endif
#endif
#ifndef LUZ_ADDRESS_SPACE_RESERVED
#define LUZ_ADDRESS_SPACE_RESERVED 0
#endif

int luz_model_memory_refusal(const char *path, uint64_t memory_bytes, luz_error *error)
{
    return luz_error_set(error, "%s: assimp needs more than %llu MiB to read it (its memory "
                                "limit; --model-memory MiB raises it)", path,
                         (unsigned long long)(memory_bytes >> 20));
}

luz_model_limits luz_model_limits_for(uint64_t file_size)
{
    const double mib = (double)file_size / (1024.0 * 1024.0);
    const double cpu = LUZ_MODEL_SECONDS + LUZ_MODEL_SECONDS_PER_MIB * mib;
    const uint64_t memory = LUZ_MODEL_MEMORY_BYTES + LUZ_MODEL_MEMORY_PER_BYTE * file_size;
    return (luz_model_limits){.cpu_seconds = cpu,
                              .wall_seconds = 2.0 * cpu + 10.0,
                              .memory_bytes = LUZ_ADDRESS_SPACE_RESERVED ? 0 : memory,
                              .description_bytes = memory};
}

void luz_model_limits_set_memory(luz_model_limits *limits, uint64_t memory_mib)
{
    const uint64_t memory = memory_mib << 20;
    limits->memory_bytes = LUZ_ADDRESS_SPACE_RESERVED ? 0 : memory;
    limits->description_bytes = memory;
}

static double now_seconds(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + (double)now.tv_nsec / 1e9;
}

/* Lowers a limit of the process to at most `value` (never raises one
 * that is lower already, which setrlimit could not do anyway). */
static void lower_limit(int resource, rlim_t soft, rlim_t hard)
{
    struct rlimit now;
    if (getrlimit(resource, &now) != 0) return;
    if (now.rlim_max != RLIM_INFINITY && now.rlim_max < hard) hard = now.rlim_max;
    if (soft > hard) soft = hard;
    if (now.rlim_cur != RLIM_INFINITY && now.rlim_cur < soft) soft = now.rlim_cur;
    setrlimit(resource, &(struct rlimit){soft, hard});
}

/* ---- a crash at the memory limit -------------------------------------------------------------- */

/* assimp does not check every allocation: at the address-space limit it
 * may use the null pointer a failed allocation gave, or a stack that
 * could not grow, and die by SIGSEGV, as a bug would. (A 24 MB OBJ of 3
 * million faces asks for 2.4 GB in one piece, mmap fails with ENOMEM,
 * and it crashes at once.) The child tells the two apart itself when it
 * crashes: if the last system call that failed ran out of memory (errno
 * is ENOMEM: glibc's malloc leaves it so), or its peak address space
 * (VmPeak, from /proc/self/status, opened before it is confined) is
 * within an eighth of the limit, it was the limit, and it exits with
 * CHILD_EXIT_MEMORY; any other crash goes on as a crash.
 *
 * A signal handler reaches only what is global: this is set once, in the
 * child, before the handler is installed, and never in luz's process. */
static struct {
    int status_descriptor;   /* luz_platform_peak_address_space's */
    uint64_t limit_bytes;    /* RLIMIT_AS */
} crash_watch = {-1, 0};

#define CHILD_EXIT_MEMORY 86

static void on_crash(int number)
{
    /* the interrupted code's errno: a handler runs in its thread */
    const bool out_of_memory = errno == ENOMEM;
    const uint64_t peak = luz_platform_peak_address_space(crash_watch.status_descriptor);
    if (out_of_memory ||
        (peak > 0 && peak >= crash_watch.limit_bytes - crash_watch.limit_bytes / 8))
        _exit(CHILD_EXIT_MEMORY);
    /* A crash: the handler is reset (SA_RESETHAND) and the signal blocked
     * until it returns; raised again, it ends the child as it would have. */
    raise(number);
}

static void watch_crashes(uint64_t limit_bytes)
{
    static unsigned char stack[64 << 10];   /* the stack may be what ran out */
    /* where the peak cannot be read (-1), errno alone tells */
    crash_watch.status_descriptor = luz_platform_peak_address_space_open();
    crash_watch.limit_bytes = limit_bytes;
    if (sigaltstack(&(stack_t){.ss_sp = stack, .ss_size = sizeof stack}, NULL) != 0) return;
    struct sigaction action = {.sa_handler = on_crash, .sa_flags = SA_ONSTACK | SA_RESETHAND};
    sigemptyset(&action.sa_mask);
    static const int crashes[] = {SIGSEGV, SIGBUS, SIGABRT};
    for (size_t i = 0; i < sizeof crashes / sizeof crashes[0]; i++)
        sigaction(crashes[i], &action, NULL);
}

/* The child: its limits, its work, what it found down the pipe, _exit. */
static _Noreturn void run_child(const char *path, int pipe_end, pid_t parent,
                                const luz_model_limits *limits,
                                const luz_confinement *confinement, luz_model_child_work work,
                                const void *context)
{
    /* It dies with luz: whatever ends luz's process (SIGKILL, or SIGTERM
     * and SIGINT, which end luz-render and the viewer as their default
     * action does), the kernel then sends the child SIGKILL, rather than
     * leave assimp running under PID 1 until its CPU limit. (Strictly, the
     * kernel sends it when the thread that forked ends: luz forks from its
     * main thread.) A parent that ended before the prctl took effect is
     * seen in getppid(): the child is then someone else's, and leaves. */
    if ((luz_platform_die_with_parent() != 0 && errno != ENOSYS) || getppid() != parent)
        _exit(1);
    signal(SIGPIPE, SIG_IGN);
    /* A crash ends the child with its signal, which the parent reports,
     * whatever handlers the parent had (a test framework's, a sanitizer's,
     * whose report would go to /dev/null); ^C ends it with the parent. */
    static const int ending[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGXCPU,
                                 SIGINT, SIGTERM, SIGHUP};
    for (size_t i = 0; i < sizeof ending / sizeof ending[0]; i++) signal(ending[i], SIG_DFL);
    int nothing = open("/dev/null", O_RDWR | O_CLOEXEC);
    if (nothing >= 0) {
        dup2(nothing, STDIN_FILENO);
        dup2(nothing, STDOUT_FILENO);
        dup2(nothing, STDERR_FILENO);
        if (nothing > STDERR_FILENO) close(nothing);
    }
    lower_limit(RLIMIT_CORE, 0, 0);
    /* at the soft limit SIGXCPU, a second later SIGKILL: whole seconds,
     * rounded up past cpu_seconds (the kernel counts in whole seconds), so
     * a child is stopped within two seconds after the stated limit */
    const rlim_t cpu = (rlim_t)limits->cpu_seconds + 1;
    lower_limit(RLIMIT_CPU, cpu, cpu + 1);
    if (limits->memory_bytes > 0) {
        /* on top of what the child shares with luz's process (the cube
         * textures, models read before): the limit is assimp's alone */
        const rlim_t memory = (rlim_t)(luz_platform_address_space() + limits->memory_bytes);
        lower_limit(RLIMIT_AS, memory, memory);
        struct rlimit set;
        if (getrlimit(RLIMIT_AS, &set) == 0 && set.rlim_cur != RLIM_INFINITY)
            watch_crashes((uint64_t)set.rlim_cur);
    }
    /* the writer's buffer, which needs no memory that may have run out */
    unsigned char buffer[64 << 10];
    luz_model_writer writer = {.descriptor = pipe_end, .bytes = buffer,
                               .capacity = sizeof buffer};
    luz_error error = {{0}};
    /* Confined before it reads a byte of the model (io/model_confine.h). */
    int status = 0;
    luz_error confine_error;
    if (luz_confine_model_reader(path, pipe_end, confinement, &confine_error) != 0) {
        luz_error_set(&error, "%s: %s", path, confine_error.message);
        status = LUZ_MACHINE_FAILED;
    }
    if (status == 0) {
        status = work(context, limits->memory_bytes, &writer, &error);
        if (status == LUZ_MACHINE_FAILED && limits->memory_bytes > 0) {
            /* out of memory within the limit: the file asked for too much */
            status = LUZ_BAD_INPUT;
            luz_model_memory_refusal(path, limits->memory_bytes, &error);
        }
    }
    if (status != 0) {
        /* after what was written of the description: the reader stops at
         * the refusal. (A writer whose pipe broke has no reader.) */
        writer.status = 0;
        luz_model_write_refusal(&writer, status, error.message);
    }
    _exit(luz_model_writer_flush(&writer) == 0 ? 0 : 1);
}

/* Reaps the child, killing it first if it has not exited by the deadline
 * (or at once, if kill_now); *killed says whether it was. Returns 0, or
 * the errno of a wait that failed (then *wait_status means nothing). */
static int reap(pid_t child, double deadline, bool kill_now, int *wait_status,
                struct rusage *usage, bool *killed)
{
    *killed = false;
    for (;;) {
        if (kill_now && !*killed) {
            kill(child, SIGKILL);
            *killed = true;
        }
        pid_t done = wait4(child, wait_status, *killed ? 0 : WNOHANG, usage);
        if (done == child) return 0;
        if (done < 0 && errno != EINTR) {
            /* Not for our own child, unless the program that links luz
             * reaps children itself (SIGCHLD ignored: ECHILD). Its status
             * is then unknown: kill it in case, and say so. */
            const int why = errno;
            kill(child, SIGKILL);
            *killed = true;
            return why;
        }
        if (done == 0) {
            if (now_seconds() >= deadline) kill_now = true;
            else nanosleep(&(struct timespec){0, 5 * 1000 * 1000}, NULL);
        }
    }
}

static const char *signal_name(int number)
{
    switch (number) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGABRT: return "SIGABRT";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGXCPU: return "SIGXCPU";
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGSYS: return "SIGSYS: a system call the confinement forbids";
    default: return "a signal";
    }
}

int luz_model_run_isolated(const char *path, const luz_model_limits *limits,
                           luz_model_child_work work, const void *context,
                           unsigned char **description, size_t *size, luz_error *error)
{
    *description = NULL;
    *size = 0;
    int ends[2];
    if (luz_platform_pipe(ends) != 0) {
        luz_error_set(error, "%s: cannot make a pipe to read it through (%s)", path,
                      strerror(errno));
        return LUZ_MACHINE_FAILED;
    }
    const luz_confinement confinement = luz_confinement_available();
    const double start = now_seconds(), deadline = start + limits->wall_seconds;
    const pid_t parent = getpid();
    pid_t child = fork();
    if (child < 0) {
        int reason = errno;
        close(ends[0]);
        close(ends[1]);
        luz_error_set(error, "%s: cannot start a process to read it (%s)", path,
                      strerror(reason));
        return LUZ_MACHINE_FAILED;
    }
    if (child == 0) {
        close(ends[0]);
        run_child(path, ends[1], parent, limits, &confinement, work, context);
    }
    close(ends[1]);

    /* What the child sends, until it closes the pipe, the deadline passes
     * or it sends more than it may. */
    unsigned char *bytes = NULL;
    size_t length = 0, capacity = 0;
    enum { READING, ENDED, LATE, TOO_LONG, NO_MEMORY, BROKEN } reading = READING;
    int read_error = 0;
    while (reading == READING) {
        const double left = deadline - now_seconds();
        if (left <= 0.0) {
            reading = LATE;
            break;
        }
        struct pollfd wait = {.fd = ends[0], .events = POLLIN};
        int ready = poll(&wait, 1, left > 60.0 ? 60000 : (int)(left * 1000.0) + 1);
        if (ready < 0 && errno != EINTR) {
            read_error = errno;
            reading = BROKEN;
        }
        if (ready <= 0) continue;
        if (length == capacity) {
            if (capacity > limits->description_bytes) {
                reading = TOO_LONG;
                break;
            }
            size_t grown_capacity = capacity < ((size_t)1 << 20) ? (size_t)1 << 20 : 2 * capacity;
            if (grown_capacity > limits->description_bytes + 1)
                grown_capacity = (size_t)limits->description_bytes + 1;
            unsigned char *grown = grown_capacity > capacity ? realloc(bytes, grown_capacity)
                                                             : NULL;
            if (grown == NULL) {
                reading = grown_capacity > capacity ? NO_MEMORY : TOO_LONG;
                break;
            }
            bytes = grown;
            capacity = grown_capacity;
        }
        ssize_t got = read(ends[0], bytes + length, capacity - length);
        if (got > 0) length += (size_t)got;
        else if (got == 0) reading = ENDED;
        else if (errno != EINTR && errno != EAGAIN) {
            read_error = errno;
            reading = BROKEN;
        }
    }
    close(ends[0]);
    int wait_status = 0;
    struct rusage usage = {0};
    bool killed;
    const int wait_error = reap(child, deadline, reading != ENDED, &wait_status, &usage, &killed);
    const double cpu = (double)usage.ru_utime.tv_sec + (double)usage.ru_stime.tv_sec +
                       ((double)usage.ru_utime.tv_usec + (double)usage.ru_stime.tv_usec) / 1e6;

    int status = LUZ_BAD_INPUT;
    if (wait_error != 0) {
        luz_error_set(error, "%s: cannot learn how the process that reads it ended (%s)", path,
                      strerror(wait_error));
        status = LUZ_MACHINE_FAILED;
    } else if (reading == NO_MEMORY) {
        luz_error_set(error, "%s: out of memory for its description (%zu bytes)", path, length);
        status = LUZ_MACHINE_FAILED;
    } else if (reading == BROKEN) {
        luz_error_set(error, "%s: cannot read from the process that reads it (%s)", path,
                      strerror(read_error));
        status = LUZ_MACHINE_FAILED;
    } else if (reading == TOO_LONG) {
        luz_error_set(error, "%s: assimp's process sent more than %llu MiB (luz's limit for a "
                             "model file of this size)", path,
                      (unsigned long long)(limits->description_bytes >> 20));
    } else if (reading == LATE || (killed && WIFSIGNALED(wait_status)) ||
               (WIFSIGNALED(wait_status) &&
                (WTERMSIG(wait_status) == SIGXCPU ||
                 (WTERMSIG(wait_status) == SIGKILL && cpu >= limits->cpu_seconds)))) {
        luz_error_set(error, "%s: assimp took more than %.0f s to read it (luz's limit for a "
                             "model file of this size)", path,
                      reading == LATE || killed ? limits->wall_seconds : limits->cpu_seconds);
    } else if (WIFSIGNALED(wait_status)) {
        const int number = WTERMSIG(wait_status);
        if (number == SIGKILL || number == SIGINT || number == SIGTERM || number == SIGHUP) {
            /* not luz's doing nor the file's: the system's out-of-memory
             * killer, or a user who stopped it */
            luz_error_set(error, "%s: the process reading it was stopped (%s)", path,
                          signal_name(number));
            status = LUZ_MACHINE_FAILED;
        } else if (number == SIGABRT && limits->memory_bytes > 0) {
            luz_error_set(error, "%s: assimp crashed reading it (SIGABRT: a failed check, or "
                                 "more memory than luz's limit of %llu MiB for a model file "
                                 "of this size)", path,
                          (unsigned long long)(limits->memory_bytes >> 20));
        } else {
            luz_error_set(error, "%s: assimp crashed reading it (%s, signal %d)", path,
                          signal_name(number), number);
        }
    } else if (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == CHILD_EXIT_MEMORY &&
               limits->memory_bytes > 0) {
        /* it crashed at its memory limit (on_crash) */
        luz_model_memory_refusal(path, limits->memory_bytes, error);
    } else if (!WIFEXITED(wait_status) || WEXITSTATUS(wait_status) != 0) {
        luz_error_set(error, "%s: assimp failed reading it (its process exited with status %d)",
                      path, WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1);
    } else {
        status = 0;
    }
    if (status != 0) {
        free(bytes);
        return status;
    }
    *description = bytes;
    *size = length;
    return 0;
}
