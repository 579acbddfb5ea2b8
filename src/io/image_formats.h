/*
 * io/image_formats.h: which image format a file is, and whether it is
 * whole and small enough to decode (image_formats.c); the decoding itself
 * is io/image_decode.h's.
 *
 * luz reads four formats: PNG, JPEG, BMP and TGA. A file's name says which
 * one it must be (.png, .jpg or .jpeg, .bmp, .tga) and its first bytes
 * must agree, so that no file reaches a decoder its name did not choose.
 */
#ifndef LUZ_IO_IMAGE_FORMATS_H
#define LUZ_IO_IMAGE_FORMATS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "luz/error.h"

typedef enum luz_image_format {
    LUZ_IMAGE_UNKNOWN = 0,
    LUZ_IMAGE_PNG,
    LUZ_IMAGE_JPEG,
    LUZ_IMAGE_BMP,
    LUZ_IMAGE_TGA,
} luz_image_format;

/* The most scans a JPEG may have. A progressive JPEG is decoded scan by
 * scan over the whole image, so its cost grows with their number;
 * encoders write about 10 (libjpeg's progressive script, mozjpeg), and a
 * small file of thousands would take minutes. */
#define LUZ_JPEG_MAX_SCANS 100

/* The format a file name's extension names (case-insensitive), or
 * LUZ_IMAGE_UNKNOWN. */
luz_image_format luz_image_format_of_name(const char *name);
/* The same for a format hint such as assimp's embedded textures carry
 * ("png", "jpg", "jpeg", "bmp", "tga"). */
luz_image_format luz_image_format_of_hint(const char *hint);
/* The format the first bytes are the signature of: PNG, JPEG or BMP (TGA
 * has none), else LUZ_IMAGE_UNKNOWN. */
luz_image_format luz_image_format_of_signature(const unsigned char *bytes, size_t size);
/* "PNG", "JPEG", "BMP", "TGA". */
const char *luz_image_format_name(luz_image_format format);

/* What the checks found, for the decoder. */
typedef struct luz_image_header {
    luz_image_format format;
    int width, height;                /* 1 to LUZ_TEXTURE_MAX_SIZE each */
    /* PNG only: IHDR's fields, PLTE's entries, and the exact size of the
     * image data once inflated (filter bytes included, interlacing
     * counted) */
    unsigned png_colour_type, png_depth, png_palette_entries;
    bool png_interlaced;
    uint64_t png_inflated_bytes;
} luz_image_header;

/* Checks that bytes are an image of `format` that the decoder can read
 * whole, reading headers and structure only (no pixel is decoded, nothing
 * is allocated):
 *  - the signature (TGA, which has none: its header's fields);
 *  - the width and height, from 1 to LUZ_TEXTURE_MAX_SIZE;
 *  - every byte the decoder will read is in the file (a truncated file is
 *    refused): PNG's chunks up to IEND, JPEG's segments and scans up to
 *    EOI (at most LUZ_JPEG_MAX_SCANS scans), BMP's and TGA's pixels
 *    (TGA's run-length packets are walked);
 *  - the variants the decoder supports, and for a BMP with a palette,
 *    every pixel's index in it.
 * Returns 0 with *header filled, or LUZ_BAD_INPUT with one line starting
 * "NAME: ". */
int luz_image_check(const unsigned char *bytes, size_t size, luz_image_format format,
                    const char *name, luz_image_header *header, luz_error *error);

#endif
