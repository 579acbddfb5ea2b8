/*
 * input_file.c: the one way luz opens a file to read it.
 *
 * In:  a path, the kind of file it should be, the largest it may be.
 * Out: an open descriptor of a regular file of at most that size, or its
 *      bytes; else one line saying what the path is instead.
 *
 * fopen() of a FIFO blocks until a writer comes, and a device such as
 * /dev/zero never ends, so checking the type after opening (as luz once
 * did) is too late. Here the type is checked with stat() before anything
 * is opened, the open itself cannot block (O_NONBLOCK), and the
 * descriptor is checked again with fstat(), so a file swapped for a FIFO
 * in between is caught too. O_NONBLOCK changes nothing for a regular file.
 */
#define _XOPEN_SOURCE 700   /* realpath (POSIX's XSI part, on every system luz builds on) */
#include "io/input_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/platform.h"

const char *luz_input_file_kind(unsigned mode)
{
    if (S_ISREG(mode)) return "a regular file";
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a file";
}

static int check_status(const char *path, const char *what, uint64_t max_bytes,
                        const struct stat *status, luz_error *error)
{
    if (!S_ISREG(status->st_mode)) {
        luz_error_set(error, "%s: not a regular file (%s; expected %s)", path,
                      luz_input_file_kind((unsigned)status->st_mode), what);
        return LUZ_BAD_INPUT;
    }
    if (status->st_size < 0 || (uint64_t)status->st_size > max_bytes) {
        luz_error_set(error, "%s: %lld bytes, expected %s of at most %llu MiB", path,
                      (long long)status->st_size, what,
                      (unsigned long long)(max_bytes >> 20));
        return LUZ_BAD_INPUT;
    }
    return 0;
}

static int open_failed(const char *path, const char *what, int reason, luz_error *error)
{
    /* "cannot open the scene file (No such file or directory)": what
     * without its article */
    const char *kind = strchr(what, ' ') ? strchr(what, ' ') + 1 : what;
    luz_error_set(error, "%s: cannot open the %s (%s)", path, kind, strerror(reason));
    return reason == ENOENT || reason == ENOTDIR ? LUZ_NO_SUCH_FILE : LUZ_BAD_INPUT;
}

int luz_input_open(const char *path, const char *what, uint64_t max_bytes, int *descriptor,
                   uint64_t *size, luz_error *error)
{
    *descriptor = -1;
    *size = 0;
    struct stat status;
    if (stat(path, &status) != 0) return open_failed(path, what, errno, error);
    int code = check_status(path, what, max_bytes, &status, error);
    if (code != 0) return code;

    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) return open_failed(path, what, errno, error);
    if (fstat(fd, &status) != 0) {
        int reason = errno;
        close(fd);
        return open_failed(path, what, reason, error);
    }
    code = check_status(path, what, max_bytes, &status, error);
    if (code != 0) {
        close(fd);
        return code;
    }
    *descriptor = fd;
    *size = (uint64_t)status.st_size;
    return 0;
}

/* ---- a file named inside a directory -------------------------------------------------- */

/* What a path that leaves the directory is told. */
static int outside(const char *path, const char *directory, const char *how, luz_error *error)
{
    luz_error_set(error, "%s: outside %s (%s)", path, directory, how);
    return LUZ_OUTSIDE_DIRECTORY;
}

/* Without openat2 (an older kernel, or a filter that forbids it; or
 * another system: io/platform.h): open the path as it is, then ask the
 * kernel where the descriptor leads (/proc/self/fd, F_GETPATH) and check
 * that it lies in the directory's real path. The check is of the file
 * opened, so a link changed in between changes nothing. Returns a
 * descriptor opened with luz_platform_path_flags, or -1 with the error
 * set. */
static int open_checked_by_proc(const char *directory, const char *path, int *status,
                                luz_error *error)
{
    char real_directory[PATH_MAX], target[PATH_MAX + 1];
    if (realpath(directory, real_directory) == NULL) {
        *status = open_failed(directory, "a directory", errno, error);
        return -1;
    }
    int fd = open(path, luz_platform_path_flags() | O_CLOEXEC);
    if (fd < 0) {
        *status = open_failed(path, "an image file", errno, error);
        return -1;
    }
    if (luz_platform_descriptor_path(fd, target, sizeof target) != 0) {
        const int reason = errno;
        close(fd);
        luz_error_set(error, "%s: cannot tell whether it lies in %s (the system resolves no "
                             "name within a folder, and cannot say where an open file is: %s)",
                      path, directory, strerror(reason));
        *status = LUZ_OUTSIDE_DIRECTORY;
        return -1;
    }
    const size_t prefix = strlen(real_directory);
    const bool root = strcmp(real_directory, "/") == 0;
    if (!root && (strncmp(target, real_directory, prefix) != 0 || target[prefix] != '/')) {
        close(fd);
        *status = outside(path, directory, "it leads to a file elsewhere through '..' or a "
                                           "symbolic link", error);
        return -1;
    }
    return fd;
}

int luz_input_open_beneath(const char *directory, const char *name, const char *what,
                           uint64_t max_bytes, int *descriptor, uint64_t *size,
                           luz_error *error)
{
    *descriptor = -1;
    *size = 0;
    char path[2 * PATH_MAX];
    const int written = snprintf(path, sizeof path, "%s/%s", directory, name);
    if (written < 0 || (size_t)written >= sizeof path)
        return luz_error_set(error, "%s/%s: path too long", directory, name);
    if (name[0] == '/')
        return outside(name, directory, "named by an absolute path", error);

    /* The file without opening it for reading (O_PATH: a device or a FIFO
     * is not opened; io/platform.h), resolved within the directory. */
    int status = 0;
    const int path_flags = luz_platform_path_flags() | O_CLOEXEC;
    int path_fd = -1, directory_fd = open(directory, path_flags | O_DIRECTORY);
    if (directory_fd < 0)
        return open_failed(directory, "a directory", errno, error);
    path_fd = luz_platform_open_beneath(directory_fd, name, path_flags);
    const bool kernel_checks = path_fd >= 0 || (errno != ENOSYS && errno != EPERM);
    if (path_fd < 0 && errno == EXDEV) {
        close(directory_fd);
        return outside(path, directory, "it leads out through '..' or a symbolic link", error);
    }
    if (path_fd < 0 && kernel_checks) {
        status = open_failed(path, what, errno, error);
        close(directory_fd);
        return status;
    }
    if (!kernel_checks) {
        path_fd = open_checked_by_proc(directory, path, &status, error);
        if (path_fd < 0) {
            close(directory_fd);
            return status;
        }
    }
    struct stat found;
    if (fstat(path_fd, &found) != 0) {
        status = open_failed(path, what, errno, error);
    } else {
        status = check_status(path, what, max_bytes, &found, error);
    }
    /* Then the same file for reading: through the kernel's check again, or
     * through the descriptor found, and it must be the file found. */
    int fd = -1;
    if (status == 0) {
        const int flags = O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY;
        if (kernel_checks)
            fd = luz_platform_open_beneath(directory_fd, name, flags);
        else
            fd = luz_platform_reopen(path_fd, flags);
        struct stat opened;
        if (fd < 0)
            status = open_failed(path, what, errno, error);
        else if (fstat(fd, &opened) != 0)
            status = open_failed(path, what, errno, error);
        else if (opened.st_dev != found.st_dev || opened.st_ino != found.st_ino)
            status = luz_error_set(error, "%s: changed while it was opened", path);
        else
            status = check_status(path, what, max_bytes, &opened, error);
        if (status == 0) *size = (uint64_t)opened.st_size;
    }
    close(path_fd);
    close(directory_fd);
    if (status != 0) {
        if (fd >= 0) close(fd);
        *size = 0;
        return status;
    }
    *descriptor = fd;
    return 0;
}

/* ---- the whole file ---------------------------------------------------------------------- */

int luz_input_read(const char *path, const char *what, uint64_t max_bytes,
                   unsigned char **bytes, size_t *size, luz_error *error)
{
    *bytes = NULL;
    *size = 0;
    int fd;
    uint64_t expected;
    int code = luz_input_open(path, what, max_bytes, &fd, &expected, error);
    if (code != 0) return code;
    return luz_input_read_descriptor(fd, expected, path, what, max_bytes, bytes, size, error);
}

int luz_input_read_descriptor(int fd, uint64_t expected, const char *path, const char *what,
                              uint64_t max_bytes, unsigned char **bytes, size_t *size,
                              luz_error *error)
{
    *bytes = NULL;
    *size = 0;

    /* The size stat() gave, and more only if the file has more (it grew,
     * or it is a /proc file that says 0): never more than max_bytes + 1,
     * which is enough to tell that it is too large. */
    size_t capacity = (size_t)expected + 1, length = 0;
    unsigned char *data = malloc(capacity);
    if (data == NULL) {
        close(fd);
        luz_error_set(error, "%s: out of memory for its %zu bytes", path, capacity - 1);
        return LUZ_MACHINE_FAILED;
    }
    for (;;) {
        if (length == capacity) {
            if ((uint64_t)capacity > max_bytes) {
                free(data);
                close(fd);
                luz_error_set(error, "%s: more than %llu MiB, expected %s of at most that",
                              path, (unsigned long long)(max_bytes >> 20), what);
                return LUZ_BAD_INPUT;
            }
            size_t grown = capacity * 2 > max_bytes + 1 ? (size_t)max_bytes + 1 : capacity * 2;
            unsigned char *larger = realloc(data, grown);
            if (larger == NULL) {
                free(data);
                close(fd);
                luz_error_set(error, "%s: out of memory for its %zu bytes", path, grown);
                return LUZ_MACHINE_FAILED;
            }
            data = larger;
            capacity = grown;
        }
        ssize_t got = read(fd, data + length, capacity - length);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            int reason = errno;
            free(data);
            close(fd);
            const char *kind = strchr(what, ' ') ? strchr(what, ' ') + 1 : what;
            luz_error_set(error, "%s: cannot read the %s (%s)", path, kind, strerror(reason));
            /* A disk's read error (EIO) or the kernel's lack of memory is
             * the machine's failure; any other refusal to read is the
             * file's: /proc/self/pagemap, which a symbolic link can pass
             * off as an image, is a regular file that reads EINVAL. */
            return reason == EIO || reason == ENOMEM || reason == ENOBUFS ? LUZ_MACHINE_FAILED
                                                                          : LUZ_BAD_INPUT;
        }
        if (got == 0) break;
        length += (size_t)got;
    }
    close(fd);
    /* The loop stops only with room left after the last byte: for the NUL. */
    data[length] = '\0';
    *bytes = data;
    *size = length;
    return 0;
}
