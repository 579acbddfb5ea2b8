/*
 * platform_linux.c: io/platform.h on Linux.
 *
 * In:  luz's questions to the operating system beyond POSIX.
 * Out: Linux's answers: pipe2, prctl(PR_SET_PDEATHSIG), openat2 with
 *      RESOLVE_BENEATH, O_PATH, and /proc/self (statm, status, fd/,
 *      exe). The only file of libluz and luz-render, with model_confine.c
 *      (Landlock, seccomp), that includes a Linux header or names /proc.
 */
#define _GNU_SOURCE   /* pipe2, O_PATH, syscall */
#include "io/platform.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <linux/openat2.h>

int luz_platform_pipe(int ends[2])
{
    return pipe2(ends, O_CLOEXEC);
}

/* PR_SET_PDEATHSIG: strictly, the kernel sends the signal when the thread
 * that forked ends (luz forks from its main thread). */
int luz_platform_die_with_parent(void)
{
    return prctl(PR_SET_PDEATHSIG, SIGKILL);
}

/* The first field of /proc/self/statm, in pages. */
uint64_t luz_platform_address_space(void)
{
    int descriptor = open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
    if (descriptor < 0) return 0;
    char text[128];
    ssize_t length = read(descriptor, text, sizeof text - 1);
    close(descriptor);
    if (length <= 0) return 0;
    text[length] = '\0';
    unsigned long long pages = strtoull(text, NULL, 10);
    long page_size = sysconf(_SC_PAGESIZE);
    return page_size > 0 ? pages * (uint64_t)page_size : 0;
}

int luz_platform_peak_address_space_open(void)
{
    return open("/proc/self/status", O_RDONLY | O_CLOEXEC);
}

/* VmPeak of /proc/self/status, in kiB there. */
uint64_t luz_platform_peak_address_space(int descriptor)
{
    if (descriptor < 0) return 0;
    char text[4096];
    ssize_t length = pread(descriptor, text, sizeof text - 1, 0);
    if (length <= 0) return 0;
    text[length] = '\0';
    for (const char *line = text; line != NULL && *line != '\0';) {
        if (strncmp(line, "VmPeak:", 7) == 0) {
            uint64_t kib = 0;
            for (const char *c = line + 7; *c == ' ' || *c == '\t' || (*c >= '0' && *c <= '9');
                 c++)
                if (*c >= '0' && *c <= '9') kib = kib * 10 + (uint64_t)(*c - '0');
            return kib * 1024;
        }
        line = strchr(line, '\n');
        if (line != NULL) line++;
    }
    return 0;
}

int luz_platform_path_flags(void)
{
    return O_PATH;
}

/* openat2(2) with RESOLVE_BENEATH (Linux 5.6): the kernel resolves name
 * within directory_fd, refusing (EXDEV) an absolute name, a `..` above
 * directory_fd and a symbolic link that leads out (or to an absolute
 * path), and with RESOLVE_NO_MAGICLINKS /proc's links. glibc 2.36 has no
 * wrapper. */
int luz_platform_open_beneath(int directory_fd, const char *name, int flags)
{
#ifdef SYS_openat2
    struct open_how how = {.flags = (uint64_t)flags,
                           .resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS};
    return (int)syscall(SYS_openat2, directory_fd, name, &how, sizeof how);
#else
    (void)directory_fd;
    (void)name;
    (void)flags;
    errno = ENOSYS;
    return -1;
#endif
}

/* The kernel's own answer: the link /proc/self/fd/N. */
int luz_platform_descriptor_path(int fd, char *path, size_t size)
{
    char link[64];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t length = readlink(link, path, size > 0 ? size - 1 : 0);
    if (length < 0) return -1;
    if ((size_t)length >= size - 1) {
        errno = ENAMETOOLONG;
        return -1;
    }
    path[length] = '\0';
    return 0;
}

/* An O_PATH descriptor is opened for reading through its /proc link,
 * which leads to the very file it names. */
int luz_platform_reopen(int fd, int flags)
{
    char link[64];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    return open(link, flags);
}

int luz_platform_executable_path(char *path, size_t size)
{
    if (size == 0) return -1;
    const ssize_t length = readlink("/proc/self/exe", path, size - 1);
    if (length <= 0) return -1;
    path[length] = '\0';
    return 0;
}
