/*
 * png_write.c: PNG files that are either complete or absent.
 *
 * stb_image_write encodes the image into a temporary file created (with
 * mkstemp, so two renders never collide) in the target's own directory;
 * only when every byte is written and the file closed is it renamed onto
 * the target. rename() within one file system is atomic, so a reader, or a
 * render that fails or is interrupted half-way, never sees a partial PNG
 * under the requested name. Termination signals wait until the file is
 * complete, so Ctrl-C does not leave the temporary NAME.tmp-XXXXXX behind
 * either (only SIGKILL can).
 */
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "luz/image.h"

typedef struct png_sink {
    FILE *file;
    bool failed;
} png_sink;

static void write_to_file(void *context, void *data, int size)
{
    png_sink *sink = context;
    if (!sink->failed && fwrite(data, 1, (size_t)size, sink->file) != (size_t)size)
        sink->failed = true;
}

static int write_then_rename(const char *path, int width, int height, const uint8_t *rgba,
                             luz_error *error)
{
    size_t length = strlen(path);
    char *temporary = malloc(length + sizeof ".tmp-XXXXXX");
    if (!temporary) return luz_error_set(error, "%s: out of memory", path);
    memcpy(temporary, path, length);
    memcpy(temporary + length, ".tmp-XXXXXX", sizeof ".tmp-XXXXXX");

    int descriptor = mkstemp(temporary);
    if (descriptor < 0) {
        int saved = errno;
        free(temporary);
        return luz_error_set(error, "%s: cannot write (%s)", path, strerror(saved));
    }
    /* mkstemp makes the file 0600; give it the mode a plain fopen would,
     * 0666 less the umask (read back by setting it and restoring it). */
    mode_t mask = umask(0);
    umask(mask);
    fchmod(descriptor, 0666 & ~mask);
    png_sink sink = {fdopen(descriptor, "wb"), false};
    if (!sink.file) {
        int saved = errno;
        close(descriptor);
        unlink(temporary);
        free(temporary);
        return luz_error_set(error, "%s: cannot write (%s)", path, strerror(saved));
    }

    int encoded = stbi_write_png_to_func(write_to_file, &sink, width, height, 4, rgba,
                                         width * 4);
    int saved = errno;
    bool closed = fclose(sink.file) == 0;
    if (!closed) saved = errno;
    if (!encoded || sink.failed || !closed) {
        unlink(temporary);
        free(temporary);
        return luz_error_set(error, "%s: cannot write (%s)", path,
                             encoded ? strerror(saved) : "PNG encoding failed");
    }
    if (rename(temporary, path) != 0) {
        saved = errno;
        unlink(temporary);
        free(temporary);
        return luz_error_set(error, "%s: cannot write (%s)", path, strerror(saved));
    }
    free(temporary);
    return 0;
}

int luz_png_write(const char *path, int width, int height, const uint8_t *rgba,
                  luz_error *error)
{
    /* Ctrl-C or a kill arriving mid-write would leave the temporary file
     * behind. Such signals are held while the file is written and renamed
     * (or removed), and delivered as soon as it is done; only SIGKILL can
     * still cut a write short. */
    sigset_t termination, previous;
    sigemptyset(&termination);
    sigaddset(&termination, SIGINT);
    sigaddset(&termination, SIGTERM);
    sigaddset(&termination, SIGHUP);
    sigaddset(&termination, SIGQUIT);
    pthread_sigmask(SIG_BLOCK, &termination, &previous);
    int status = write_then_rename(path, width, height, rgba, error);
    pthread_sigmask(SIG_SETMASK, &previous, NULL);
    return status;
}

int luz_framebuffer_write_png(const luz_framebuffer *framebuffer, const char *path,
                              luz_error *error)
{
    return luz_png_write(path, framebuffer->width, framebuffer->height, framebuffer->colour,
                         error);
}
