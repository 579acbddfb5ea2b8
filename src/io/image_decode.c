/*
 * image_decode.c: the pixels of an image file that image_formats.c has
 * checked.
 *
 * In:  the bytes of a PNG, JPEG, BMP or TGA file and what its checks
 *      found (format, width, height).
 * Out: width x height RGBA8 pixels, row 0 on top.
 *
 * PNG goes to libpng (Debian's libpng-dev), which OSS-Fuzz fuzzes
 * continuously: stb_image 2.27's PNG decoder has undefined behaviour on a
 * valid PNG whose first IDAT chunk is empty (it adds 0 to a null
 * pointer). libpng is asked for exactly the pixels stb_image gave, so no
 * image changed (decode_png says how).
 *
 * BMP and TGA go to stb_image (Debian's libstb-dev), built with its PNG,
 * BMP and TGA decoders only (stb_image_only.c): whatever a file's bytes
 * say, stb_image cannot pick its GIF, PSD, HDR, PNM or PIC decoders.
 *
 * JPEG goes to libjpeg-turbo (TurboJPEG API, Debian's libturbojpeg0-dev):
 * stb_image 2.27's JPEG decoder writes past its Huffman tables for a table
 * that declares more than 256 codes, and libjpeg-turbo is fuzzed
 * continuously by OSS-Fuzz. Warnings (a premature end of data, a corrupt
 * segment) stop the decoding: a damaged JPEG is refused rather than shown
 * in part.
 *
 * A PNG's image data is inflated once before libpng sees it, into a
 * buffer of exactly the size IHDR implies (image_formats.c computes it):
 * a stream that inflates to more or less is refused, so the memory a
 * decode takes is known before it starts. For an image with a palette,
 * the inflated rows are also unfiltered and every index checked against
 * the palette's entries (libpng would show the others as black).
 */
#include "io/image_decode.h"

#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>
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

/* ---- PNG: libpng ------------------------------------------------------------------------------ */

/* libpng reports an error by calling this, which must not return: its
 * message is kept and decode_png's setjmp is resumed. Its warnings (an
 * ancillary chunk with a bad CRC, an unknown chunk) say nothing about the
 * pixels and go unprinted: one line per failure is luz's rule. */
typedef struct png_failure {
    jmp_buf resume;
    char message[160];
} png_failure;

static void png_failed(png_structp png, png_const_charp message)
{
    png_failure *failure = png_get_error_ptr(png);
    snprintf(failure->message, sizeof failure->message, "%s", message ? message : "error");
    longjmp(failure->resume, 1);
}

static void png_warned(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message;
}

/* The file's bytes, read by libpng through this. */
typedef struct png_source {
    const unsigned char *bytes;
    size_t size, position;
} png_source;

static void png_read_bytes(png_structp png, png_bytep out, size_t length)
{
    png_source *source = png_get_io_ptr(png);
    if (length > source->size - source->position) png_error(png, "truncated PNG");
    memcpy(out, source->bytes + source->position, length);
    source->position += length;
}

/* Decodes a PNG that image_formats.c and check_png_data have accepted into
 * RGBA8 with libpng, transformed as stb_image transformed it, so that
 * every image stays byte for byte what it was: a palette looked up, its
 * tRNS entries as alpha; grey of 1, 2 or 4 bits scaled to 8 (0x55 for 1
 * of 2 bits); a tRNS colour key compared at the file's depth, then
 * transparent; 16 bits cut to their high byte (png_set_strip_16, as stb's
 * >> 8); grey copied to red, green and blue; alpha 255 where the file has
 * none. No gamma, colour profile or background is applied: stb applied
 * none. */
static int decode_png(const unsigned char *bytes, size_t size, const luz_image_header *header,
                      const char *name, uint8_t **rgba, luz_error *error)
{
    png_failure failure = {.message = ""};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &failure, png_failed,
                                             png_warned);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (info == NULL) {
        png_destroy_read_struct(&png, NULL, NULL);
        luz_error_set(error, "%s: out of memory decoding a %dx%d PNG", name, header->width,
                      header->height);
        return LUZ_MACHINE_FAILED;
    }
    /* Changed after setjmp and read after longjmp: volatile (C11 7.13.2.1). */
    uint8_t *volatile pixels = NULL;
    png_bytep *volatile rows = NULL;
    png_source source = {.bytes = bytes, .size = size};
    if (setjmp(failure.resume) != 0) {
        free(pixels);
        free(rows);
        png_destroy_read_struct(&png, &info, NULL);
        /* libpng's png_malloc: "Out of memory"; every other error is the
         * file's */
        if (strstr(failure.message, "memory") != NULL) {
            luz_error_set(error, "%s: out of memory decoding a %dx%d PNG (%s)", name,
                          header->width, header->height, failure.message);
            return LUZ_MACHINE_FAILED;
        }
        return luz_error_set(error, "%s: corrupt PNG (%s)", name, failure.message);
    }
    png_set_read_fn(png, &source, png_read_bytes);
    /* The limits luz has checked already, told to libpng too: the size,
     * and what one ancillary chunk may take (luz reads none of them). */
    png_set_user_limits(png, LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
    png_set_chunk_cache_max(png, 128);
    png_set_chunk_malloc_max(png, (png_alloc_size_t)1 << 20);
    png_read_info(png, info);
    png_uint_32 width, height;
    int depth, colour_type, interlace;
    png_get_IHDR(png, info, &width, &height, &depth, &colour_type, &interlace, NULL, NULL);
    if (width != (png_uint_32)header->width || height != (png_uint_32)header->height)
        png_error(png, "its IHDR changed between the checks and the decoding");
    if (depth == 16) png_set_strip_16(png);
    if (colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if (colour_type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
    if (colour_type == PNG_COLOR_TYPE_GRAY || colour_type == PNG_COLOR_TYPE_GRAY_ALPHA)
        png_set_gray_to_rgb(png);
    png_set_filler(png, 0xff, PNG_FILLER_AFTER);   /* nothing where there is alpha */
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    const size_t row_bytes = (size_t)width * 4;
    if (png_get_rowbytes(png, info) != row_bytes)
        png_error(png, "its rows do not come out as RGBA8");
    /* width x height x 4 fits in size_t: the budget has allowed it */
    pixels = malloc(row_bytes * height);
    rows = malloc(sizeof *rows * height);
    if (pixels == NULL || rows == NULL) png_error(png, "Out of memory for its pixels");
    for (png_uint_32 y = 0; y < height; y++) rows[y] = pixels + y * row_bytes;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    free(rows);
    *rgba = pixels;
    return 0;
}

/* ---- BMP, TGA: stb_image ------------------------------------------------------------------ */

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
        return decode_png(bytes, size, header, name, rgba, error);
    }
    case LUZ_IMAGE_BMP:
    case LUZ_IMAGE_TGA:
        return decode_with_stb(bytes, size, header, name, rgba, error);
    default:
        return luz_error_set(error, "%s: not an image luz reads", name);
    }
}
