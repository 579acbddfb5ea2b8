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
 *
 * A PNG's pixels are RGBA. A framebuffer drawn in BGRA (a window's order,
 * see luz/framebuffer.h) is converted into a temporary copy first, so the
 * framebuffer itself is left as it was, and the file is still either
 * complete or absent.
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
    const int width = framebuffer->width, height = framebuffer->height;
    if (framebuffer->channel_order == LUZ_CHANNELS_RGBA)
        return luz_png_write(path, width, height, framebuffer->colour, error);

    /* BGRA: red and blue, bytes 0 and 2, trade places; green and alpha
     * stay. The copy is made before any file exists, so running out of
     * memory leaves nothing behind. */
    const size_t bytes = (size_t)width * (size_t)height * 4;
    uint8_t *rgba = malloc(bytes);
    if (!rgba)
        return luz_error_set(error, "%s: out of memory converting the %dx%d image to RGBA",
                             path, width, height);
    const uint8_t *bgra = framebuffer->colour;
    for (size_t i = 0; i < bytes; i += 4) {
        rgba[i + 0] = bgra[i + 2];
        rgba[i + 1] = bgra[i + 1];
        rgba[i + 2] = bgra[i + 0];
        rgba[i + 3] = bgra[i + 3];
    }
    int status = luz_png_write(path, width, height, rgba, error);
    free(rgba);
    return status;
}
