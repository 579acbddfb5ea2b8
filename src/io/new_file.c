/*
 * new_file.c: files that appear complete or not at all (see new_file.h).
 * The PNG writer and the viewer's scene files go through here.
 *
 * In:  a path, then the bytes of the file, written to file.stream.
 * Out: the complete file under path, or nothing at all (no temporary file
 *      either), and one line saying why; whatever was at the path before
 *      is replaced only if it was a regular file.
 */
#include "io/new_file.h"

#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* ---- signals ------------------------------------------------------------------------ */

void luz_hold_write_signals(luz_held_signals *held, bool termination)
{
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGXFSZ);
    if (termination) {
        sigaddset(&signals, SIGINT);
        sigaddset(&signals, SIGTERM);
        sigaddset(&signals, SIGHUP);
        sigaddset(&signals, SIGQUIT);
    }
    pthread_sigmask(SIG_BLOCK, &signals, &held->previous);
}

void luz_release_write_signals(const luz_held_signals *held)
{
    /* A write past the file-size limit raised SIGXFSZ at this thread (the
     * kernel sends it to the writer) and failed with EFBIG, which the
     * caller reports. Delivered now, the signal would kill the program
     * before the report: take it off the pending set first, unless the
     * caller held it already. */
    sigset_t pending;
    if (!sigismember(&held->previous, SIGXFSZ) && sigpending(&pending) == 0 &&
        sigismember(&pending, SIGXFSZ)) {
        sigset_t file_size;
        sigemptyset(&file_size);
        sigaddset(&file_size, SIGXFSZ);
        const struct timespec no_wait = {0, 0};
        while (sigtimedwait(&file_size, NULL, &no_wait) < 0 && errno == EINTR) {}
    }
    pthread_sigmask(SIG_SETMASK, &held->previous, NULL);
}

/* ---- what is at the path ------------------------------------------------------------- */

static const char *kind_of_file(mode_t mode)
{
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISLNK(mode)) return "a symbolic link";
    return "not a regular file";
}

int luz_new_file_check_target(const char *path, luz_error *error)
{
    size_t length = strlen(path);
    struct stat status;
    /* "d/" names a directory whether or not it exists; say so rather than
     * fail on the temporary file "d/.tmp-XXXXXX" or the rename. */
    if (length > 0 && path[length - 1] == '/') {
        bool directory = stat(path, &status) == 0 && S_ISDIR(status.st_mode);
        return luz_error_set(error,
                             "%s: %s; expected a file name (such as %sluz.png)", path,
                             directory ? "is a directory" : "ends in '/', a directory's name",
                             path);
    }
    /* lstat: a symbolic link is replaced itself by the rename, not the file
     * it points to (/dev/stdout is one, to /proc/self/fd/1). */
    if (lstat(path, &status) != 0 || S_ISREG(status.st_mode))
        return 0;
    if (S_ISDIR(status.st_mode))
        return luz_error_set(error,
                             "%s: is a directory; expected a file name (such as %s/luz.png)",
                             path, path);
    return luz_error_set(error,
                         "%s: is %s, not a regular file; expected a new file or a regular "
                         "file to replace",
                         path, kind_of_file(status.st_mode));
}

/* ---- the folders above a path ------------------------------------------------------- */

int luz_new_file_folders(const char *path, bool create, luz_error *error)
{
    size_t length = strlen(path);
    char *folder = malloc(length + 1);
    if (folder == NULL)
        return luz_error_set(error, "%s: out of memory", path);
    /* Each prefix that ends just before a '/' (but the root's "" and the
     * repeats of "a//b") is a folder the file needs, outermost first. */
    int status = 0;
    for (size_t end = 1; end < length && status == 0; end++) {
        if (path[end] != '/' || path[end - 1] == '/')
            continue;
        memcpy(folder, path, end);
        folder[end] = '\0';
        struct stat info;
        if (stat(folder, &info) == 0) {
            if (!S_ISDIR(info.st_mode))
                status = luz_error_set(error, "%s: %s is not a folder (it is %s)", path, folder,
                                       S_ISREG(info.st_mode) ? "a file"
                                                             : kind_of_file(info.st_mode));
            continue;
        }
        if (errno != ENOENT) {
            status = luz_error_set(error, "%s: cannot reach the folder %s (%s)", path, folder,
                                   strerror(errno));
        } else if (create && mkdir(folder, 0777) != 0 &&
                   !(errno == EEXIST && stat(folder, &info) == 0 && S_ISDIR(info.st_mode))) {
            /* EEXIST: another run (a shard) made it meanwhile */
            status = luz_error_set(error, "%s: cannot create the folder %s (%s)", path, folder,
                                   strerror(errno));
        } else if (!create) {
            break;   /* missing: the folders below it are missing too */
        }
    }
    free(folder);
    return status;
}

/* ---- writing ------------------------------------------------------------------------ */

int luz_new_file_open(luz_new_file *file, const char *path, luz_error *error)
{
    *file = (luz_new_file){.path = path};
    size_t length = strlen(path);
    file->temporary = malloc(length + sizeof ".tmp-XXXXXX");
    if (file->temporary == NULL)
        return luz_error_set(error, "%s: out of memory", path);
    memcpy(file->temporary, path, length);
    memcpy(file->temporary + length, ".tmp-XXXXXX", sizeof ".tmp-XXXXXX");

    /* Held from before the temporary file exists until it is gone or has
     * its name, so that no signal can leave it behind. */
    luz_hold_write_signals(&file->signals, true);
    int descriptor = mkstemp(file->temporary);
    if (descriptor < 0) {
        int saved = errno;
        free(file->temporary);
        file->temporary = NULL;
        luz_release_write_signals(&file->signals);
        return luz_error_set(error, "%s: cannot write (%s)", path, strerror(saved));
    }
    /* mkstemp makes the file 0600; give it the mode a plain fopen would,
     * 0666 less the umask (read back by setting it and restoring it). */
    mode_t mask = umask(0);
    umask(mask);
    fchmod(descriptor, 0666 & ~mask);
    file->stream = fdopen(descriptor, "wb");
    if (file->stream == NULL) {
        int saved = errno;
        close(descriptor);
        luz_new_file_abandon(file);
        return luz_error_set(error, "%s: cannot write (%s)", path, strerror(saved));
    }
    return 0;
}

void luz_new_file_abandon(luz_new_file *file)
{
    if (file->stream != NULL)
        fclose(file->stream);
    if (file->temporary != NULL) {
        unlink(file->temporary);
        free(file->temporary);
        luz_release_write_signals(&file->signals);
    }
    file->stream = NULL;
    file->temporary = NULL;
}

/* Puts the complete temporary file under path. On a file system without
 * hard links (link fails with EPERM or ENOTSUP, as FAT does) a check for
 * the name and then a rename are the best left, and not atomic. */
static int publish(const char *temporary, const char *path, bool replace)
{
    if (replace)
        return rename(temporary, path) == 0 ? 0 : -1;
    if (link(temporary, path) == 0) {
        unlink(temporary);
        return 0;
    }
    if (errno == EEXIST)
        return LUZ_FILE_EXISTS;
    if (errno != EPERM && errno != ENOTSUP && errno != EOPNOTSUPP)
        return -1;
    if (access(path, F_OK) == 0)
        return LUZ_FILE_EXISTS;
    return rename(temporary, path) == 0 ? 0 : -1;
}

int luz_new_file_commit(luz_new_file *file, bool replace, luz_error *error)
{
    bool written = !ferror(file->stream);
    int saved = written ? 0 : (errno ? errno : EIO);
    if (fclose(file->stream) != 0 && written) {
        written = false;
        saved = errno;
    }
    file->stream = NULL;
    /* Checked again at the last moment: something may have appeared at
     * the path since the caller's own check. (What appears between this
     * check and the rename still loses to it; no system call replaces
     * "only a regular file".) */
    luz_error refused;
    const bool allowed = !replace || luz_new_file_check_target(file->path, &refused) == 0;
    int status = written && allowed ? publish(file->temporary, file->path, replace) : -1;
    if (written && allowed && status < 0)
        saved = errno;
    if (status != 0)
        unlink(file->temporary);   /* refused or failed: nothing left behind */
    free(file->temporary);
    file->temporary = NULL;
    luz_release_write_signals(&file->signals);
    if (written && !allowed)
        return luz_error_set(error, "%s", refused.message);
    if (status < 0)
        return luz_error_set(error, "%s: cannot write (%s)", file->path, strerror(saved));
    return status;
}
