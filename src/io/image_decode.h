/*
 * io/image_decode.h: an image file's pixels, once io/image_formats.h has
 * checked it (image_decode.c).
 */
#ifndef LUZ_IO_IMAGE_DECODE_H
#define LUZ_IO_IMAGE_DECODE_H

#include <stddef.h>
#include <stdint.h>

#include "io/image_formats.h"
#include "luz/error.h"

/* Decodes bytes, which luz_image_check has accepted into *header, into
 * header->width x header->height RGBA8 pixels, row 0 on top (malloc'd:
 * free() them). Returns 0; LUZ_BAD_INPUT for what only decoding finds (a
 * corrupt compressed stream, a colour index outside a PNG's palette, a
 * JPEG variant libjpeg-turbo does not decode), or LUZ_MACHINE_FAILED when
 * memory runs out; with one line starting "NAME: ". */
int luz_image_decode(const unsigned char *bytes, size_t size, const luz_image_header *header,
                     const char *name, uint8_t **rgba, luz_error *error);

#endif
