/*
 * luz/image.h: writing the framebuffer to a PNG file.
 *
 * The file is written to a temporary name beside the target and renamed
 * into place only once complete, so a failed or interrupted render never
 * leaves a partial PNG under the requested name.
 */
#ifndef LUZ_IMAGE_H
#define LUZ_IMAGE_H

#include <stdint.h>

#include "luz/error.h"
#include "luz/framebuffer.h"

/* Writes width x height RGBA8 pixels (row 0 on top) as an RGBA PNG. */
int luz_png_write(const char *path, int width, int height, const uint8_t *rgba,
                  luz_error *error);
int luz_framebuffer_write_png(const luz_framebuffer *framebuffer, const char *path,
                              luz_error *error);

#endif
