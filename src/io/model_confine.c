/*
 * model_confine.c: the confinement of assimp's process (io/model_confine.h).
 *
 * In:  the model's path, the pipe the child writes to, and what the
 *      kernel offers (Landlock's ABI version, seccomp filters).
 * Out: the calling process confined: no new privileges, reads only
 *      beneath the model's folder (Landlock), only the system calls
 *      reading a model needs (seccomp); or one line saying what could not
 *      be set up.
 *
 * The order matters: no new privileges first (both Landlock and an
 * unprivileged seccomp filter require it), Landlock next (its own system
 * calls are not on the seccomp list), the seccomp filter last.
 *
 * The system calls allowed are those the child makes on every file of
 * Debian's assimp-testmodels of at most 2 MiB (400 files, every format),
 * traced with strace (pread64, newfstatat, openat, close, brk, write,
 * getpid, exit_group, mmap, munmap, futex), their close kin (read, lseek,
 * fstat, statx, mremap, madvise, mprotect; clock_gettime and getrandom,
 * which C++ runtimes use; sleeping, which is harmless), and those of a crash or an abort (signal
 * handling, sigaltstack, and tgkill to itself): openat only for reading,
 * mmap and mprotect never executable, write() to the pipe alone. Everything else fails with
 * EPERM, so that a library that tries something harmless (isatty's
 * ioctl) carries on; what only an attack would do kills the process with
 * SIGSYS, which luz reports as a crash.
 *
 * Under AddressSanitizer and ThreadSanitizer the filter is the same: they
 * need nothing more to run a sound import (the corpus passes under both);
 * their reports of an unsound one, which need to write to stderr (here
 * /dev/null) and read /proc/self/maps, fail, and the child then dies with
 * the sanitizer's exit, which luz reports as a failed import.
 */
#define _GNU_SOURCE   /* O_PATH */
#include "io/model_confine.h"

#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <linux/landlock.h>
#if defined(LUZ_HAVE_SECCOMP)
#include <seccomp.h>
#endif

/* ---- Landlock -------------------------------------------------------------------------------- */

/* Debian 12's <linux/landlock.h> knows ABI 1; later ABIs add rights and
 * fields that the kernel may have (it tells its version), defined here as
 * the kernel's uapi header defines them. */
#define FS_REFER (1ULL << 13)       /* ABI 2 */
#define FS_TRUNCATE (1ULL << 14)    /* ABI 3 */
#define FS_IOCTL_DEV (1ULL << 15)   /* ABI 5 */
#define NET_BIND_TCP (1ULL << 0)    /* ABI 4 */
#define NET_CONNECT_TCP (1ULL << 1)
#define SCOPE_ABSTRACT_UNIX_SOCKET (1ULL << 0)   /* ABI 6 */
#define SCOPE_SIGNAL (1ULL << 1)

/* struct landlock_ruleset_attr as of ABI 6; a kernel is given the part its
 * ABI knows. */
typedef struct ruleset_attr {
    uint64_t handled_access_fs;
    uint64_t handled_access_net;
    uint64_t scoped;
} ruleset_attr;

static int landlock_version(void)
{
    long version = syscall(SYS_landlock_create_ruleset, NULL, 0, LANDLOCK_CREATE_RULESET_VERSION);
    return version > 0 ? (int)version : 0;
}

/* A rule: what may be done to path (a folder, and what is beneath it, or
 * a file). A path that is not there needs none (if optional). */
static int allow_path(int ruleset, const char *path, uint64_t access, bool optional,
                      luz_error *error)
{
    int descriptor = open(path, O_PATH | O_CLOEXEC);
    if (descriptor < 0 && optional && errno == ENOENT) return 0;
    if (descriptor < 0)
        return luz_error_set(error, "cannot confine the process reading it to %s (%s)", path,
                             strerror(errno));
    struct landlock_path_beneath_attr rule = {.allowed_access = access, .parent_fd = descriptor};
    long added = syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &rule, 0);
    const int reason = errno;
    close(descriptor);
    if (added != 0)
        return luz_error_set(error, "cannot confine the process reading it to %s (Landlock: %s)",
                             path, strerror(reason));
    return 0;
}

/* Reading beneath the model's folder, and the model file itself (which may
 * be a symbolic link to a file elsewhere); every other file access of the
 * ABI denied, and with ABI 4 TCP, with ABI 6 signals and abstract sockets
 * outside. */
static int restrict_files(const char *model_path, int abi, luz_error *error)
{
    ruleset_attr attributes = {
        .handled_access_fs = LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_WRITE_FILE |
                             LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_READ_DIR |
                             LANDLOCK_ACCESS_FS_REMOVE_DIR | LANDLOCK_ACCESS_FS_REMOVE_FILE |
                             LANDLOCK_ACCESS_FS_MAKE_CHAR | LANDLOCK_ACCESS_FS_MAKE_DIR |
                             LANDLOCK_ACCESS_FS_MAKE_REG | LANDLOCK_ACCESS_FS_MAKE_SOCK |
                             LANDLOCK_ACCESS_FS_MAKE_FIFO | LANDLOCK_ACCESS_FS_MAKE_BLOCK |
                             LANDLOCK_ACCESS_FS_MAKE_SYM};
    size_t size = sizeof attributes.handled_access_fs;
    if (abi >= 2) attributes.handled_access_fs |= FS_REFER;
    if (abi >= 3) attributes.handled_access_fs |= FS_TRUNCATE;
    if (abi >= 5) attributes.handled_access_fs |= FS_IOCTL_DEV;
    if (abi >= 4) {
        attributes.handled_access_net = NET_BIND_TCP | NET_CONNECT_TCP;
        size = offsetof(ruleset_attr, scoped);
    }
    if (abi >= 6) {
        attributes.scoped = SCOPE_ABSTRACT_UNIX_SOCKET | SCOPE_SIGNAL;
        size = sizeof attributes;
    }
    long ruleset = syscall(SYS_landlock_create_ruleset, &attributes, size, 0);
    if (ruleset < 0)
        return luz_error_set(error, "cannot confine the process reading it (Landlock: %s)",
                             strerror(errno));
    char folder[4096];
    const char *slash = strrchr(model_path, '/');
    if (slash == NULL) snprintf(folder, sizeof folder, ".");
    else if (slash == model_path) snprintf(folder, sizeof folder, "/");
    else snprintf(folder, sizeof folder, "%.*s", (int)(slash - model_path), model_path);
    const uint64_t read = LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_READ_DIR;
    int status = allow_path((int)ruleset, folder, read, false, error);
    if (status == 0)
        status = allow_path((int)ruleset, model_path, LANDLOCK_ACCESS_FS_READ_FILE, true, error);
    if (status == 0 && syscall(SYS_landlock_restrict_self, ruleset, 0) != 0)
        status = luz_error_set(error, "cannot confine the process reading it (Landlock: %s)",
                               strerror(errno));
    close((int)ruleset);
    return status;
}

/* ---- seccomp --------------------------------------------------------------------------------- */

#if defined(LUZ_HAVE_SECCOMP)

static int seccomp_failed(scmp_filter_ctx filter, int result, luz_error *error)
{
    seccomp_release(filter);
    return luz_error_set(error, "cannot confine the process reading it (seccomp: %s)",
                         strerror(-result));
}

static int filter_system_calls(int pipe_end, luz_error *error)
{
    scmp_filter_ctx filter = seccomp_init(SCMP_ACT_ERRNO(EPERM));
    if (filter == NULL)
        return luz_error_set(error, "cannot confine the process reading it (seccomp: out of "
                                    "memory)");
    /* Reading, through descriptors; memory; time; ending. */
    static const int allowed[] = {
        SCMP_SYS(read), SCMP_SYS(pread64), SCMP_SYS(lseek), SCMP_SYS(fstat),
        SCMP_SYS(newfstatat), SCMP_SYS(statx), SCMP_SYS(close), SCMP_SYS(brk), SCMP_SYS(munmap),
        SCMP_SYS(mremap), SCMP_SYS(madvise), SCMP_SYS(futex), SCMP_SYS(clock_gettime),
        SCMP_SYS(getrandom), SCMP_SYS(getpid), SCMP_SYS(gettid), SCMP_SYS(rt_sigaction),
        SCMP_SYS(rt_sigprocmask), SCMP_SYS(rt_sigreturn), SCMP_SYS(sigaltstack),
        SCMP_SYS(pause), SCMP_SYS(nanosleep), SCMP_SYS(clock_nanosleep),
        SCMP_SYS(exit), SCMP_SYS(exit_group),
    };
    int result = 0;
    for (size_t i = 0; i < sizeof allowed / sizeof allowed[0] && result == 0; i++)
        result = seccomp_rule_add(filter, SCMP_ACT_ALLOW, allowed[i], 0);
    /* What only an attack would do: the process is killed (SIGSYS). */
    static const int fatal[] = {
        SCMP_SYS(socket), SCMP_SYS(socketpair), SCMP_SYS(connect), SCMP_SYS(bind),
        SCMP_SYS(listen), SCMP_SYS(accept), SCMP_SYS(accept4), SCMP_SYS(sendto),
        SCMP_SYS(sendmsg), SCMP_SYS(execve), SCMP_SYS(execveat), SCMP_SYS(fork),
        SCMP_SYS(vfork), SCMP_SYS(clone), SCMP_SYS(clone3), SCMP_SYS(ptrace),
        SCMP_SYS(process_vm_writev), SCMP_SYS(process_vm_readv),
    };
    for (size_t i = 0; i < sizeof fatal / sizeof fatal[0] && result == 0; i++)
        result = seccomp_rule_add(filter, SCMP_ACT_KILL_PROCESS, fatal[i], 0);
    /* Files open for reading only: O_WRONLY, O_RDWR, O_CREAT, O_TRUNC,
     * O_APPEND or O_TMPFILE fail. */
    const scmp_datum_t writing = O_WRONLY | O_RDWR | O_CREAT | O_TRUNC | O_APPEND |
                                 (O_TMPFILE & ~O_DIRECTORY);
    if (result == 0)
        result = seccomp_rule_add(filter, SCMP_ACT_ALLOW, SCMP_SYS(openat), 1,
                                  SCMP_A2(SCMP_CMP_MASKED_EQ, writing, 0));
    /* Memory that is never executable. */
    if (result == 0)
        result = seccomp_rule_add(filter, SCMP_ACT_ALLOW, SCMP_SYS(mmap), 1,
                                  SCMP_A2(SCMP_CMP_MASKED_EQ, PROT_EXEC, 0));
    if (result == 0)
        result = seccomp_rule_add(filter, SCMP_ACT_ALLOW, SCMP_SYS(mprotect), 1,
                                  SCMP_A2(SCMP_CMP_MASKED_EQ, PROT_EXEC, 0));
    /* Writes to the pipe alone; signals to itself alone (abort, raise). */
    if (result == 0)
        result = seccomp_rule_add(filter, SCMP_ACT_ALLOW, SCMP_SYS(write), 1,
                                  SCMP_A0(SCMP_CMP_EQ, (scmp_datum_t)pipe_end, 0));
    const scmp_datum_t self = (scmp_datum_t)getpid();
    if (result == 0)
        result = seccomp_rule_add(filter, SCMP_ACT_ALLOW, SCMP_SYS(tgkill), 1,
                                  SCMP_A0(SCMP_CMP_EQ, self, 0));
    if (result == 0) result = seccomp_load(filter);
    if (result != 0) return seccomp_failed(filter, result, error);
    seccomp_release(filter);
    return 0;
}

#else

static int filter_system_calls(int pipe_end, luz_error *error)
{
    (void)pipe_end;
    return luz_error_set(error, "this luz was built without libseccomp");
}

#endif

/* ---- the whole ------------------------------------------------------------------------------- */

luz_confinement luz_confinement_available(void)
{
    /* PR_GET_SECCOMP fails with EINVAL on a kernel without seccomp; a
     * kernel with it but without filters (no CONFIG_SECCOMP_FILTER) is
     * found when the filter fails to load. */
#if defined(LUZ_HAVE_SECCOMP)
    const bool seccomp = prctl(PR_GET_SECCOMP, 0, 0, 0, 0) >= 0;
#else
    const bool seccomp = false;   /* built without libseccomp (and without models) */
#endif
    return (luz_confinement){.landlock_abi = landlock_version(), .seccomp = seccomp};
}

const char *luz_confinement_missing(const luz_confinement *available)
{
    if (available->landlock_abi == 0 && !available->seccomp) return "Landlock and seccomp";
    if (available->landlock_abi == 0) return "Landlock";
    if (!available->seccomp) return "seccomp";
    return "";
}

int luz_confine_model_reader(const char *model_path, int pipe_end,
                             const luz_confinement *available, luz_error *error)
{
    if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0)
        return luz_error_set(error, "cannot confine the process reading it (no new privileges: "
                                    "%s)", strerror(errno));
    if (available->landlock_abi > 0 &&
        restrict_files(model_path, available->landlock_abi, error) != 0)
        return -1;
    if (available->seccomp && filter_system_calls(pipe_end, error) != 0) return -1;
    return 0;
}
