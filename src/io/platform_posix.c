/*
 * platform_posix.c: io/platform.h on systems other than Linux (macOS, the
 * BSDs).
 *
 * In:  luz's questions to the operating system beyond POSIX.
 * Out: POSIX's answers, and a system's own where it has one that luz can
 *      see at compile time: FreeBSD's O_RESOLVE_BENEATH (13.0) for a file
 *      named inside a directory, macOS's F_GETPATH for where a descriptor
 *      leads; else ENOSYS, and the caller does without: a model's child
 *      does not die with luz (its CPU and clock limits still end it), its
 *      memory limit counts from zero rather than from what it shares with
 *      luz, and a texture named by a model is refused when its folder
 *      cannot be checked.
 *
 * Not run on those systems by luz's CI (it has none of them): compiled on
 * Linux with POSIX's headers alone by tests/portable_build.sh.
 */
/* Each system's own names (macOS's F_GETPATH, FreeBSD's
 * O_RESOLVE_BENEATH), which meson.build's -D_POSIX_C_SOURCE would hide:
 * a system's defaults show them (FreeBSD's), _DARWIN_C_SOURCE on macOS;
 * glibc's defaults (POSIX and BSD, not GNU) are _DEFAULT_SOURCE's. */
#undef _POSIX_C_SOURCE
#define _DEFAULT_SOURCE
#define _DARWIN_C_SOURCE
#include "io/platform.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <unistd.h>

int luz_platform_pipe(int ends[2])
{
    if (pipe(ends) != 0) return -1;
    for (int i = 0; i < 2; i++) {
        const int flags = fcntl(ends[i], F_GETFD);
        if (flags < 0 || fcntl(ends[i], F_SETFD, flags | FD_CLOEXEC) != 0) {
            const int reason = errno;
            close(ends[0]);
            close(ends[1]);
            errno = reason;
            return -1;
        }
    }
    return 0;
}

int luz_platform_die_with_parent(void)
{
    errno = ENOSYS;
    return -1;
}

uint64_t luz_platform_address_space(void)
{
    return 0;
}

int luz_platform_peak_address_space_open(void)
{
    return -1;
}

uint64_t luz_platform_peak_address_space(int descriptor)
{
    (void)descriptor;
    return 0;
}

/* A regular file opens at once; O_NONBLOCK keeps a FIFO's open from
 * waiting for a writer. */
int luz_platform_path_flags(void)
{
    return O_RDONLY | O_NONBLOCK;
}

int luz_platform_open_beneath(int directory_fd, const char *name, int flags)
{
#if defined(O_RESOLVE_BENEATH)
    /* FreeBSD: ENOTCAPABLE for a name that leaves the directory */
    const int fd = openat(directory_fd, name, flags | O_RESOLVE_BENEATH);
#if defined(ENOTCAPABLE)
    if (fd < 0 && errno == ENOTCAPABLE) errno = EXDEV;
#endif
    return fd;
#else
    (void)directory_fd;
    (void)name;
    (void)flags;
    errno = ENOSYS;
    return -1;
#endif
}

int luz_platform_descriptor_path(int fd, char *path, size_t size)
{
#if defined(F_GETPATH)
    /* macOS: the path the kernel has for the file, links resolved */
    if (size < PATH_MAX) {
        errno = ENAMETOOLONG;
        return -1;
    }
    return fcntl(fd, F_GETPATH, path) == -1 ? -1 : 0;
#else
    (void)fd;
    (void)path;
    (void)size;
    errno = ENOSYS;
    return -1;
#endif
}

/* luz_platform_path_flags opened the file for reading already: the same
 * open file, on a descriptor of its own. */
int luz_platform_reopen(int fd, int flags)
{
    (void)flags;
    return fcntl(fd, F_DUPFD_CLOEXEC, 0);
}

int luz_platform_executable_path(char *path, size_t size)
{
    (void)path;
    (void)size;
    return -1;
}
