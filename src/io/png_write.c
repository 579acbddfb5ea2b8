/*
 * png_write.c: PNG files that are either complete or absent.
 *
 * stb_image_write encodes the image into a temporary file in the target's
 * own directory (new_file.c); only when every byte is written and the file
 * closed is it renamed onto the target. rename() within one file system is
 * atomic, so a reader, or a render that fails or is interrupted half-way,
 * never sees a partial PNG under the requested name. Termination signals
 * wait until the file is complete, so Ctrl-C does not leave the temporary
 * NAME.tmp-XXXXXX behind either (only SIGKILL can).
 *
 * luz_framebuffer_write_new_png never replaces a file: the complete
 * temporary file is hard-linked to the name (link() fails if the name
 * exists, atomically, where a check with access() then a rename would
 * race with another program saving under the same name), and then
 * unlinked. The viewer's numbered screenshots rely on it.
 *
 * A PNG's pixels are RGBA. A framebuffer drawn in BGRA (a window's order,
 * see luz/framebuffer.h) is converted into a temporary copy first, so the
 * framebuffer itself is left as it was, and the file is still either
 * complete or absent.
 */
#include <pthread.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#include <stb_image_write.h>

#include "io/new_file.h"
#include "io/image.h"

static void write_to_file(void *context, void *data, int size)
{
    fwrite(data, 1, (size_t)size, context);   /* a short write sets the stream's error */
}

static int encode(const char *path, int width, int height, const uint8_t *rgba, bool replace,
                  luz_error *error)
{
    luz_new_file file;
    if (luz_new_file_open(&file, path, error) != 0)
        return -1;
    if (!stbi_write_png_to_func(write_to_file, file.stream, width, height, 4, rgba, width * 4)) {
        luz_new_file_abandon(&file);
        return luz_error_set(error, "%s: cannot write (PNG encoding failed)", path);
    }
    return luz_new_file_commit(&file, replace, error);
}

static int write_png(const char *path, int width, int height, const uint8_t *rgba,
                     bool replace, luz_error *error)
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
    int status = encode(path, width, height, rgba, replace, error);
    pthread_sigmask(SIG_SETMASK, &previous, NULL);
    return status;
}

int luz_png_write(const char *path, int width, int height, const uint8_t *rgba,
                  luz_error *error)
{
    return write_png(path, width, height, rgba, true, error);
}

static int write_framebuffer(const luz_framebuffer *framebuffer, const char *path, bool replace,
                             luz_error *error)
{
    const int width = framebuffer->width, height = framebuffer->height;
    if (framebuffer->channel_order == LUZ_CHANNELS_RGBA)
        return write_png(path, width, height, framebuffer->colour, replace, error);

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
    int status = write_png(path, width, height, rgba, replace, error);
    free(rgba);
    return status;
}

int luz_framebuffer_write_png(const luz_framebuffer *framebuffer, const char *path,
                              luz_error *error)
{
    return write_framebuffer(framebuffer, path, true, error);
}

int luz_framebuffer_write_new_png(const luz_framebuffer *framebuffer, const char *path,
                                  luz_error *error)
{
    return write_framebuffer(framebuffer, path, false, error);
}
