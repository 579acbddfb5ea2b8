/*
 * new_file.c: files that appear complete or not at all (see new_file.h).
 * The PNG writer and the viewer's scene files go through here.
 */
#include "io/new_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int luz_new_file_open(luz_new_file *file, const char *path, luz_error *error)
{
    *file = (luz_new_file){.path = path};
    size_t length = strlen(path);
    file->temporary = malloc(length + sizeof ".tmp-XXXXXX");
    if (file->temporary == NULL)
        return luz_error_set(error, "%s: out of memory", path);
    memcpy(file->temporary, path, length);
    memcpy(file->temporary + length, ".tmp-XXXXXX", sizeof ".tmp-XXXXXX");

    int descriptor = mkstemp(file->temporary);
    if (descriptor < 0) {
        int saved = errno;
        free(file->temporary);
        file->temporary = NULL;
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
    int status = written ? publish(file->temporary, file->path, replace) : -1;
    if (written && status < 0)
        saved = errno;
    if (status != 0)
        unlink(file->temporary);   /* refused or failed: nothing left behind */
    free(file->temporary);
    file->temporary = NULL;
    if (status < 0)
        return luz_error_set(error, "%s: cannot write (%s)", file->path, strerror(saved));
    return status;
}
