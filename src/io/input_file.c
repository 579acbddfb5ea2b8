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
#include "io/input_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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

int luz_input_read(const char *path, const char *what, uint64_t max_bytes,
                   unsigned char **bytes, size_t *size, luz_error *error)
{
    *bytes = NULL;
    *size = 0;
    int fd;
    uint64_t expected;
    int code = luz_input_open(path, what, max_bytes, &fd, &expected, error);
    if (code != 0) return code;

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
