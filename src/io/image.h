/*
 * io/image.h: writing the framebuffer to a PNG file (or to an open
 * stream, luz_framebuffer_write_png_stream).
 *
 * A file is written to a temporary name beside the target and renamed
 * into place only once complete, so a failed or interrupted render never
 * leaves a partial PNG under the requested name. Each function returns 0,
 * or -1 with the reason in error.
 */
#ifndef LUZ_IMAGE_H
#define LUZ_IMAGE_H

#include <stdint.h>
#include <stdio.h>

#include "io/new_file.h"
#include "luz/error.h"
#include "luz/framebuffer.h"

/* Writes width x height RGBA8 pixels (row 0 on top) as an RGBA PNG. */
int luz_png_write(const char *path, int width, int height, const uint8_t *rgba,
                  luz_error *error);
int luz_framebuffer_write_png(const luz_framebuffer *framebuffer, const char *path,
                              luz_error *error);

/* As luz_framebuffer_write_png, but never replaces a file: if path exists
 * (or comes to exist while the PNG is encoded), nothing is left behind and
 * it returns LUZ_FILE_EXISTS (io/new_file.h), so that a caller numbering its
 * files takes the next number. Two programs saving at once never
 * overwrite each other's file. */
int luz_framebuffer_write_new_png(const luz_framebuffer *framebuffer, const char *path,
                                  luz_error *error);

/* Writes the framebuffer as a PNG to an open stream (standard output, for a
 * video encoder reading image after image) and flushes it. A stream cannot
 * be written complete-or-absent: if a write fails (EPIPE when the reader
 * has quit), -1 is returned with "NAME: cannot write (REASON)", name
 * standing for the stream in the message. */
int luz_framebuffer_write_png_stream(const luz_framebuffer *framebuffer, FILE *stream,
                                     const char *name, luz_error *error);

#endif
