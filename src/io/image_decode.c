/*
 * image_decode.c: the pixels of an image file that image_formats.c has
 * checked.
 *
 * In:  the bytes of a PNG, JPEG, BMP or TGA file and what its checks
 *      found (format, width, height).
 * Out: width x height RGBA8 pixels, row 0 on top.
 *
 * PNG, BMP and TGA go to stb_image (Debian's libstb-dev), built with
 * those three decoders only (stb_image_only.c): whatever a file's bytes
 * say, stb_image cannot pick its GIF, PSD, HDR, PNM or PIC decoders.
 *
 * JPEG goes to libjpeg-turbo (TurboJPEG API, Debian's libturbojpeg0-dev):
 * stb_image 2.27's JPEG decoder writes past its Huffman tables for a table
 * that declares more than 256 codes, and libjpeg-turbo is fuzzed
 * continuously by OSS-Fuzz. Warnings (a premature end of data, a corrupt
 * segment) stop the decoding: a damaged JPEG is refused rather than shown
 * in part.
 *
 * A PNG's image data is inflated once before stb_image sees it, into a
 * buffer of exactly the size IHDR implies (image_formats.c computes it):
 * a stream that inflates to more or less is refused, so a small file
 * cannot make stb_image's growing buffer allocate gigabytes, and stb's
 * habit of reading zeros past the end of its input cannot run on. For an
 * image with a palette, the inflated rows are also unfiltered and every
 * index checked against the palette's entries: stb_image would look the
 * others up in an array it never filled.
 */
#include "io/image_decode.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include <turbojpeg.h>

#include "io/input_file.h"
#include "io/stb_image_only.h"
#include "luz/texture.h"

/* ---- PNG: the image data, inflated and checked ---------------------------------------------- */

static uint32_t read_32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* The Paeth predictor (PNG specification 9.4). */
static unsigned paeth(unsigned a, unsigned b, unsigned c)
{
    const int p = (int)a + (int)b - (int)c;
    const int pa = abs(p - (int)a), pb = abs(p - (int)b), pc = abs(p - (int)c);
    if (pa <= pb && pa <= pc) return a;
    return pb <= pc ? b : c;
}

/* Unfilters, in place, the rows of one (reduced) image of a colour-mapped
 * PNG, whose filter unit is one byte (depths 1 to 8, one channel), and
 * returns the largest index, or -1 for a filter type above 4. *data moves
 * past the rows. */
static int largest_index_of_pass(unsigned char **data, uint32_t width, uint32_t height,
                                 unsigned depth)
{
    if (width == 0 || height == 0) return 0;
    const size_t row_bytes = ((size_t)width * depth + 7) / 8;
    const unsigned mask = (1u << depth) - 1;
    int largest = 0;
    unsigned char *previous = NULL;
    for (uint32_t y = 0; y < height; y++) {
        const unsigned filter = (*data)[0];
        unsigned char *row = *data + 1;
        if (filter > 4) return -1;
        for (size_t i = 0; i < row_bytes; i++) {
            const unsigned a = i > 0 ? row[i - 1] : 0, b = previous ? previous[i] : 0;
            const unsigned c = i > 0 && previous ? previous[i - 1] : 0;
            const unsigned prediction = filter == 1   ? a
                                        : filter == 2 ? b
                                        : filter == 3 ? (a + b) / 2
                                        : filter == 4 ? paeth(a, b, c)
                                                      : 0;
            row[i] = (unsigned char)(row[i] + prediction);
        }
        for (uint32_t x = 0; x < width; x++) {
            const size_t bit = (size_t)x * depth;
            const int index = (row[bit / 8] >> (8 - depth - bit % 8)) & mask;
            if (index > largest) largest = index;
        }
        previous = row;
        *data += 1 + row_bytes;
    }
    return largest;
}

/* The largest palette index of an inflated colour-mapped image, pass by
 * pass for an interlaced one (Adam7, as image_formats.c counts them). */
static int largest_png_index(unsigned char *data, const luz_image_header *header)
{
    static const unsigned x0[7] = {0, 4, 0, 2, 0, 1, 0}, y0[7] = {0, 0, 4, 0, 2, 0, 1};
    static const unsigned dx[7] = {8, 8, 4, 4, 2, 2, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
    const uint32_t width = (uint32_t)header->width, height = (uint32_t)header->height;
    if (!header->png_interlaced) return largest_index_of_pass(&data, width, height, header->png_depth);
    int largest = 0;
    for (int pass = 0; pass < 7; pass++) {
        const uint32_t w = width > x0[pass] ? (width - x0[pass] + dx[pass] - 1) / dx[pass] : 0;
        const uint32_t h = height > y0[pass] ? (height - y0[pass] + dy[pass] - 1) / dy[pass] : 0;
        const int pass_largest = largest_index_of_pass(&data, w, h, header->png_depth);
        if (pass_largest < 0) return -1;
        if (pass_largest > largest) largest = pass_largest;
    }
    return largest;
}

/* Inflates the IDAT chunks (image_formats.c has walked them: each lies
 * inside the file, IEND follows) into a buffer of exactly the size IHDR
 * implies, and checks a palette's indices. */
static int check_png_data(const unsigned char *bytes, size_t size, const luz_image_header *header,
                          const char *name, luz_error *error)
{
    size_t compressed_size = 0;
    for (size_t position = 8; position + 12 <= size;) {
        const uint32_t length = read_32(bytes + position);
        if (memcmp(bytes + position + 4, "IDAT", 4) == 0) compressed_size += length;
        if (memcmp(bytes + position + 4, "IEND", 4) == 0) break;
        position += 12 + (size_t)length;
    }
    const uint64_t expected = header->png_inflated_bytes;
    unsigned char *compressed = malloc(compressed_size + 1);
    /* one byte more than the data needs: stb's inflater fails when its
     * fixed buffer is full, so a stream with more than expected is seen */
    unsigned char *inflated = compressed ? malloc((size_t)expected + 1) : NULL;
    if (inflated == NULL) {
        free(compressed);
        luz_error_set(error, "%s: out of memory inflating a %dx%d PNG", name, header->width,
                      header->height);
        return LUZ_MACHINE_FAILED;
    }
    size_t filled = 0;
    for (size_t position = 8; position + 12 <= size;) {
        const uint32_t length = read_32(bytes + position);
        if (memcmp(bytes + position + 4, "IDAT", 4) == 0) {
            memcpy(compressed + filled, bytes + position + 8, length);
            filled += length;
        }
        if (memcmp(bytes + position + 4, "IEND", 4) == 0) break;
        position += 12 + (size_t)length;
    }
    const int got = luz_stb_inflate(inflated, (int)expected + 1, compressed, (int)compressed_size);
    free(compressed);
    int status = 0;
    if (got < 0 || (uint64_t)got != expected) {
        if (got < 0 && strcmp(luz_stb_failure_reason(), "outofmem") == 0) {
            luz_error_set(error, "%s: out of memory inflating a %dx%d PNG", name, header->width,
                          header->height);
            status = LUZ_MACHINE_FAILED;
        } else if (got < 0 && strcmp(luz_stb_failure_reason(), "output buffer limit") != 0) {
            status = luz_error_set(error, "%s: corrupt PNG (its image data does not inflate: "
                                          "%s)", name, luz_stb_failure_reason());
        } else {
            status = luz_error_set(error, "%s: corrupt PNG (its image data inflates to %s "
                                          "than the %llu bytes a %dx%d image has)",
                                   name, got < 0 ? "more" : "fewer",
                                   (unsigned long long)expected, header->width, header->height);
        }
    } else if (header->png_colour_type == 3 &&
               header->png_palette_entries < (1u << header->png_depth)) {
        const int largest = largest_png_index(inflated, header);
        if (largest < 0)
            status = luz_error_set(error, "%s: corrupt PNG (a row with a filter type above 4)",
                                   name);
        else if ((unsigned)largest >= header->png_palette_entries)
            status = luz_error_set(error, "%s: corrupt PNG (a pixel of colour %d, the palette "
                                          "has %u)", name, largest, header->png_palette_entries);
    }
    free(inflated);
    return status;
}

/* ---- PNG, BMP, TGA: stb_image ------------------------------------------------------------ */

static int decode_with_stb(const unsigned char *bytes, size_t size, const luz_image_header *header,
                           const char *name, uint8_t **rgba, luz_error *error)
{
    int width, height;
    unsigned char *pixels = luz_stb_load_rgba(bytes, (int)size, &width, &height);
    if (pixels == NULL) {
        if (strcmp(luz_stb_failure_reason(), "outofmem") == 0) {
            luz_error_set(error, "%s: out of memory decoding a %dx%d image", name, header->width,
                          header->height);
            return LUZ_MACHINE_FAILED;
        }
        return luz_error_set(error, "%s: corrupt or unsupported %s (%s)", name,
                             luz_image_format_name(header->format), luz_stb_failure_reason());
    }
    if (width != header->width || height != header->height) {
        free(pixels);
        return luz_error_set(error, "%s: corrupt %s (decoded as %dx%d, its header says %dx%d)",
                             name, luz_image_format_name(header->format), width, height,
                             header->width, header->height);
    }
    *rgba = pixels;
    return 0;
}

/* ---- JPEG: libjpeg-turbo -------------------------------------------------------------------- */

/* What a libjpeg-turbo message means: memory ran out (libjpeg's
 * JERR_OUT_OF_MEMORY, "Insufficient memory", or TurboJPEG's own
 * "Memory allocation failure"), or the file is at fault. */
static int jpeg_failure(tjhandle decoder, const char *name, luz_error *error)
{
    const char *reason = decoder ? tjGetErrorStr2(decoder) : tjGetErrorStr2(NULL);
    if (reason == NULL) reason = "unknown error";
    if (strstr(reason, "Insufficient memory") || strstr(reason, "Memory allocation failure")) {
        luz_error_set(error, "%s: out of memory decoding a JPEG (%s)", name, reason);
        return LUZ_MACHINE_FAILED;
    }
    return luz_error_set(error, "%s: corrupt or unsupported JPEG (%s)", name, reason);
}

/* stb_image's 8-bit product x * y / 255, rounded (Jim Blinn's). */
static uint8_t blinn_8x8(unsigned x, unsigned y)
{
    const unsigned t = x * y + 128;
    return (uint8_t)((t + (t >> 8)) >> 8);
}

static int decode_jpeg(const unsigned char *bytes, size_t size, const luz_image_header *header,
                       const char *name, uint8_t **rgba, luz_error *error)
{
    tjhandle decoder = tjInitDecompress();
    if (decoder == NULL) return jpeg_failure(NULL, name, error);
    int width, height, subsampling, colour_space;
    if (tjDecompressHeader3(decoder, bytes, (unsigned long)size, &width, &height, &subsampling,
                            &colour_space) != 0) {
        int status = jpeg_failure(decoder, name, error);
        tjDestroy(decoder);
        return status;
    }
    if (width != header->width || height != header->height) {
        tjDestroy(decoder);
        return luz_error_set(error, "%s: corrupt JPEG (its frame is %dx%d, its first frame "
                                    "header says %dx%d)",
                             name, width, height, header->width, header->height);
    }
    const size_t pixel_count = (size_t)width * (size_t)height;
    uint8_t *pixels = malloc(pixel_count * 4);
    if (pixels == NULL) {
        tjDestroy(decoder);
        luz_error_set(error, "%s: out of memory decoding a %dx%d JPEG", name, width, height);
        return LUZ_MACHINE_FAILED;
    }
    /* libjpeg decodes CMYK (and YCCK, which it turns into CMYK) only into
     * CMYK; Adobe's files store it inverted, so a channel times K is the
     * RGB one, as stb_image computed it. Everything else comes as RGBA. */
    const bool cmyk = colour_space == TJCS_CMYK || colour_space == TJCS_YCCK;
    if (tjDecompress2(decoder, bytes, (unsigned long)size, pixels, width, 0, height,
                      cmyk ? TJPF_CMYK : TJPF_RGBA, TJFLAG_STOPONWARNING) != 0) {
        int status = jpeg_failure(decoder, name, error);
        tjDestroy(decoder);
        free(pixels);
        return status;
    }
    tjDestroy(decoder);
    if (cmyk) {
        for (size_t i = 0; i < pixel_count; i++) {
            uint8_t *p = pixels + 4 * i;
            const unsigned k = p[3];
            p[0] = blinn_8x8(p[0], k);
            p[1] = blinn_8x8(p[1], k);
            p[2] = blinn_8x8(p[2], k);
            p[3] = 255;
        }
    }
    *rgba = pixels;
    return 0;
}

int luz_image_decode(const unsigned char *bytes, size_t size, const luz_image_header *header,
                     const char *name, uint8_t **rgba, luz_error *error)
{
    *rgba = NULL;
    /* image_formats.c refuses files over LUZ_IMAGE_FILE_MAX_BYTES' reach,
     * and the decoders take an int */
    if (size > (size_t)INT32_MAX)
        return luz_error_set(error, "%s: %zu bytes, more than an image decoder takes", name,
                             size);
    switch (header->format) {
    case LUZ_IMAGE_JPEG:
        return decode_jpeg(bytes, size, header, name, rgba, error);
    case LUZ_IMAGE_PNG: {
        int status = check_png_data(bytes, size, header, name, error);
        if (status != 0) return status;
        return decode_with_stb(bytes, size, header, name, rgba, error);
    }
    case LUZ_IMAGE_BMP:
    case LUZ_IMAGE_TGA:
        return decode_with_stb(bytes, size, header, name, rgba, error);
    default:
        return luz_error_set(error, "%s: not an image luz reads", name);
    }
}
