/*
 * png_write.c: PNG files that are either complete or absent.
 *
 * stb_image_write encodes the image into a temporary file in the target's
 * own directory (new_file.c); only when every byte is written and the file
 * closed is it renamed onto the target. rename() within one file system is
 * atomic, so a reader, or a render that fails or is interrupted half-way,
 * never sees a partial PNG under the requested name. Termination signals
 * wait until the file is complete, so Ctrl-C does not leave the temporary
 * NAME.tmp-XXXXXX behind either (only SIGKILL can), and a file-size limit
 * makes the write fail with EFBIG rather than kill the program with
 * SIGXFSZ (new_file.c holds both). Only a regular file is replaced.
 *
 * luz_framebuffer_write_new_png never replaces a file: the complete
 * temporary file is hard-linked to the name (link() fails if the name
 * exists, atomically, where a check with access() then a rename would
 * race with another program saving under the same name), and then
 * unlinked. The viewer's numbered screenshots rely on it.
 *
 * luz_framebuffer_write_png_stream writes to a stream that is already open
 * (standard output, for a video encoder): no temporary file is possible
 * there, so a failed write is reported and the reader sees a PNG cut
 * short. SIGXFSZ is held there too (standard output redirected to a file
 * under ulimit -f).
 *
 * A PNG's pixels are RGBA. A framebuffer drawn in BGRA (a window's order,
 * see luz/framebuffer.h) is converted into a temporary copy first, so the
 * framebuffer itself is left as it was, and the file is still either
 * complete or absent.
 */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "io/new_file.h"
#include "io/image.h"

/* stb_image_write's output, and the first write's failure: its errno,
 * kept before anything else can change errno. */
typedef struct stream_writer {
    FILE *stream;
    int error;   /* errno of the first failed write, 0 while all went well */
} stream_writer;

static void write_to_stream(void *context, void *data, int size)
{
    stream_writer *writer = context;
    if (writer->error == 0 && fwrite(data, 1, (size_t)size, writer->stream) != (size_t)size)
        writer->error = errno ? errno : EIO;
}

/* Ctrl-C or a kill arriving mid-write would leave the temporary file
 * behind: luz_new_file holds such signals while the file is written and
 * renamed (or removed), and delivers them as soon as it is done; only
 * SIGKILL can still cut a write short. */
static int write_png(const char *path, int width, int height, const uint8_t *rgba,
                     bool replace, luz_error *error)
{
    luz_new_file file;
    if (luz_new_file_open(&file, path, error) != 0)
        return -1;
    stream_writer writer = {.stream = file.stream};
    errno = 0;
    if (!stbi_write_png_to_func(write_to_stream, &writer, width, height, 4, rgba, width * 4)) {
        luz_new_file_abandon(&file);
        return luz_error_set(error, "%s: cannot write (PNG encoding failed)", path);
    }
    if (writer.error != 0) {   /* EFBIG past ulimit -f, ENOSPC, ... */
        luz_new_file_abandon(&file);
        return luz_error_set(error, "%s: cannot write (%s)", path, strerror(writer.error));
    }
    return luz_new_file_commit(&file, replace, error);
}

int luz_png_write(const char *path, int width, int height, const uint8_t *rgba,
                  luz_error *error)
{
    return write_png(path, width, height, rgba, true, error);
}

/* Where a PNG goes: a new file at path, or an open stream (then path only
 * names it in messages). */
typedef struct png_target {
    const char *path;
    bool replace;
    FILE *stream;   /* NULL: a new file */
} png_target;

static int write_png_to_stream(FILE *stream, const char *name, int width, int height,
                               const uint8_t *rgba, luz_error *error)
{
    stream_writer writer = {.stream = stream};
    luz_held_signals held;
    luz_hold_write_signals(&held, false);
    errno = 0;
    const bool encoded =
        stbi_write_png_to_func(write_to_stream, &writer, width, height, 4, rgba, width * 4);
    /* flushed, so that the reader has each image whole as soon as it is
     * written, and a failure is seen at this image */
    if (encoded && writer.error == 0 && fflush(stream) != 0)
        writer.error = errno ? errno : EIO;
    luz_release_write_signals(&held);
    if (!encoded)
        return luz_error_set(error, "%s: cannot write (PNG encoding failed)", name);
    if (writer.error != 0)
        return luz_error_set(error, "%s: cannot write (%s)", name, strerror(writer.error));
    return 0;
}

static int write_target(const png_target *target, int width, int height, const uint8_t *rgba,
                        luz_error *error)
{
    if (target->stream != NULL)
        return write_png_to_stream(target->stream, target->path, width, height, rgba, error);
    return write_png(target->path, width, height, rgba, target->replace, error);
}

static int write_framebuffer(const luz_framebuffer *framebuffer, const png_target *target,
                             luz_error *error)
{
    const char *path = target->path;
    const int width = framebuffer->width, height = framebuffer->height;
    if (framebuffer->channel_order == LUZ_CHANNELS_RGBA)
        return write_target(target, width, height, framebuffer->colour, error);

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
    int status = write_target(target, width, height, rgba, error);
    free(rgba);
    return status;
}

int luz_framebuffer_write_png(const luz_framebuffer *framebuffer, const char *path,
                              luz_error *error)
{
    return write_framebuffer(framebuffer, &(png_target){.path = path, .replace = true}, error);
}

int luz_framebuffer_write_new_png(const luz_framebuffer *framebuffer, const char *path,
                                  luz_error *error)
{
    return write_framebuffer(framebuffer, &(png_target){.path = path, .replace = false}, error);
}

int luz_framebuffer_write_png_stream(const luz_framebuffer *framebuffer, FILE *stream,
                                     const char *name, luz_error *error)
{
    return write_framebuffer(framebuffer, &(png_target){.path = name, .stream = stream},
                             error);
}
