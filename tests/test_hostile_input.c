/*
 * test_hostile_input.c: the files luz reads, as an attacker would write
 * them (issue 13: decoding and opening inputs).
 *
 * Every file is made here, byte by byte, from the formats' specifications
 * (PNG chunks with their CRC-32, zlib streams of stored or fixed-Huffman
 * blocks with their Adler-32, BMP and TGA headers, JPEG marker segments),
 * or with stb_image_write, an encoder independent of the decoders luz
 * uses. The pixels a sound file must decode to are the ones written into
 * it; the refusals are the malformed files the issue found (a 16-bit PGM
 * named x.png, a truncated RLE HDR named x.png, a TGA header claiming
 * 8000 x 8000, a JPEG Huffman table of more than 256 codes, PNG sizes far
 * over the limit) and one of each check the loader makes.
 *
 * Three groups:
 *  - io directly: images decode to their pixels, every malformed one is
 *    refused with LUZ_BAD_INPUT and a message naming it, the texture
 *    budget adds up, luz_input_read refuses what is not a regular file;
 *  - the real luz-render ($LUZ_RENDER), in a fresh directory: a FIFO as
 *    the scene file, a texture, a model, a model's .mtl and a model's
 *    texture; crafted textures; textures over the budget: each exits with
 *    status 2 within seconds, with one line naming the file, and leaves no
 *    file behind;
 *  - out of memory while decoding (a limit on the address space): exit
 *    status 1, "out of memory", not "corrupt".
 */
#define _XOPEN_SOURCE 700

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include "file_support.h"

/* AddressSanitizer and ThreadSanitizer reserve terabytes of address space:
 * no limit on it can be set under them, and their reports end a
 * process. */
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define LUZ_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define LUZ_TEST_SANITIZED 1
#endif
#endif
#ifndef LUZ_TEST_SANITIZED
#define LUZ_TEST_SANITIZED 0
#endif

#include "app/options.h"
#include "io/input_file.h"
#include "io/model.h"
#include "io/model_confine.h"
#include "io/model_description.h"
#include "io/model_sandbox.h"
#include "io/textures.h"

/* ---- bytes ------------------------------------------------------------------------------- */

typedef struct buffer {
    unsigned char *data;
    size_t length, capacity;
} buffer;

static void put(buffer *b, const void *bytes, size_t count)
{
    if (b->length + count > b->capacity) {
        size_t capacity = b->capacity ? b->capacity : 256;
        while (capacity < b->length + count) capacity *= 2;
        b->data = realloc(b->data, capacity);
        assert_non_null(b->data);
        b->capacity = capacity;
    }
    if (count > 0) memcpy(b->data + b->length, bytes, count);
    b->length += count;
}

static void put_byte(buffer *b, unsigned value)
{
    unsigned char byte = (unsigned char)value;
    put(b, &byte, 1);
}

static void put_be32(buffer *b, uint32_t value)
{
    for (int shift = 24; shift >= 0; shift -= 8) put_byte(b, value >> shift);
}

static void put_le16(buffer *b, unsigned value)
{
    put_byte(b, value);
    put_byte(b, value >> 8);
}

static void put_le32(buffer *b, uint32_t value)
{
    for (int shift = 0; shift < 32; shift += 8) put_byte(b, value >> shift);
}

static void put_text(buffer *b, const char *text)
{
    put(b, text, strlen(text));
}

static void buffer_free(buffer *b)
{
    free(b->data);
    memset(b, 0, sizeof *b);
}

/* CRC-32 of the PNG specification (annex D), bit by bit. */
static uint32_t crc32_of(const unsigned char *bytes, size_t length)
{
    uint32_t crc = 0xffffffffu;
    for (size_t i = 0; i < length; i++) {
        crc ^= bytes[i];
        for (int k = 0; k < 8; k++) crc = crc & 1 ? 0xedb88320u ^ (crc >> 1) : crc >> 1;
    }
    return crc ^ 0xffffffffu;
}

/* Adler-32 of RFC 1950, section 8. */
static uint32_t adler32_of(const unsigned char *bytes, size_t length)
{
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < length; i++) {
        a = (a + bytes[i]) % 65521;
        b = (b + a) % 65521;
    }
    return b << 16 | a;
}

/* A zlib stream (RFC 1950) of stored deflate blocks (RFC 1951, 3.2.4):
 * the bytes as they are, at most 65535 a block. */
static buffer zlib_stored(const unsigned char *raw, size_t length)
{
    buffer z = {0};
    put_byte(&z, 0x78);   /* CM 8, CINFO 7 */
    put_byte(&z, 0x01);   /* FCHECK: 0x7801 is a multiple of 31 */
    size_t done = 0;
    do {
        size_t block = length - done > 65535 ? 65535 : length - done;
        put_byte(&z, done + block == length);   /* BFINAL, BTYPE 00 */
        put_le16(&z, (unsigned)block);
        put_le16(&z, (unsigned)~block & 0xffff);
        put(&z, raw + done, block);
        done += block;
    } while (done < length);
    put_be32(&z, adler32_of(raw, length));
    return z;
}

/* Deflate's bits, least significant first; a Huffman code goes most
 * significant bit first (RFC 1951, 3.1.1). */
typedef struct bit_writer {
    buffer *out;
    uint32_t pending;
    int count;
} bit_writer;

static void put_bits(bit_writer *w, uint32_t value, int count)
{
    for (int i = 0; i < count; i++) {
        w->pending |= ((value >> i) & 1u) << w->count;
        if (++w->count == 8) {
            put_byte(w->out, w->pending);
            w->pending = 0;
            w->count = 0;
        }
    }
}

static void put_code(bit_writer *w, uint32_t code, int length)
{
    for (int i = length - 1; i >= 0; i--) put_bits(w, (code >> i) & 1u, 1);
}

/* A zlib stream of `count` zero bytes in one block of RFC 1951's fixed
 * Huffman codes (3.2.6): a literal 0 (code 0x30, 8 bits), then copies of
 * 258 bytes at distance 1 (length symbol 285: code 0xC5, 8 bits, no extra
 * bits; distance code 0: 5 bits), the rest as literals, then end of block
 * (symbol 256: 7 zero bits). 13 bits for 258 bytes: 268 MB in 1.7 MB. */
static buffer zlib_zeros(uint64_t count)
{
    buffer z = {0};
    put_byte(&z, 0x78);
    put_byte(&z, 0x01);
    bit_writer w = {.out = &z};
    put_bits(&w, 1, 1);   /* BFINAL */
    put_bits(&w, 1, 2);   /* BTYPE 01: fixed codes */
    uint64_t left = count;
    if (left > 0) {
        put_code(&w, 0x30, 8);
        left--;
    }
    for (; left >= 258; left -= 258) {
        put_code(&w, 0xc5, 8);
        put_code(&w, 0, 5);
    }
    for (; left > 0; left--) put_code(&w, 0x30, 8);
    put_code(&w, 0, 7);
    if (w.count > 0) put_bits(&w, 0, 8 - w.count);
    /* Adler-32 of zeros: a stays 1 and b grows by 1 a byte */
    put_be32(&z, (uint32_t)(count % 65521) << 16 | 1u);
    return z;
}

static void png_chunk(buffer *png, const char *type, const void *data, size_t length)
{
    put_be32(png, (uint32_t)length);
    buffer typed = {0};
    put(&typed, type, 4);
    put(&typed, data, length);
    put(png, typed.data, typed.length);
    put_be32(png, crc32_of(typed.data, typed.length));
    buffer_free(&typed);
}

static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

/* A PNG's start: the signature, IHDR with these fields, PLTE if
 * palette_entries > 0; the caller adds what follows. */
static buffer png_start(uint32_t width, uint32_t height, unsigned depth, unsigned colour,
                        unsigned interlace, const unsigned char *palette, size_t palette_entries)
{
    buffer png = {0};
    put(&png, png_signature, 8);
    buffer header = {0};
    put_be32(&header, width);
    put_be32(&header, height);
    put_byte(&header, depth);
    put_byte(&header, colour);
    put_byte(&header, 0);
    put_byte(&header, 0);
    put_byte(&header, interlace);
    png_chunk(&png, "IHDR", header.data, header.length);
    buffer_free(&header);
    if (palette_entries > 0) png_chunk(&png, "PLTE", palette, palette_entries * 3);
    return png;
}

/* A PNG: png_start, then one IDAT holding zlib (a whole zlib stream), IEND. */
static buffer make_png(uint32_t width, uint32_t height, unsigned depth, unsigned colour,
                       unsigned interlace, const unsigned char *palette, size_t palette_entries,
                       const buffer *zlib)
{
    buffer png = png_start(width, height, depth, colour, interlace, palette, palette_entries);
    png_chunk(&png, "IDAT", zlib->data, zlib->length);
    png_chunk(&png, "IEND", NULL, 0);
    return png;
}

/* make_png with the raw (filtered) image data stored uncompressed. */
static buffer make_png_raw(uint32_t width, uint32_t height, unsigned depth, unsigned colour,
                           unsigned interlace, const unsigned char *palette,
                           size_t palette_entries, const unsigned char *raw, size_t raw_length)
{
    buffer zlib = zlib_stored(raw, raw_length);
    buffer png = make_png(width, height, depth, colour, interlace, palette, palette_entries, &zlib);
    buffer_free(&zlib);
    return png;
}

/* A BMP of 14 + 40 bytes of headers (BITMAPINFOHEADER), the palette
 * (BGRX entries), then `rows` (bottom-up, each padded to 4 bytes). */
static buffer make_bmp(int32_t width, int32_t height, unsigned bits, uint32_t compression,
                       const unsigned char *palette, size_t palette_entries,
                       const unsigned char *rows, size_t rows_length)
{
    buffer bmp = {0};
    const uint32_t offset = 14 + 40 + (uint32_t)palette_entries * 4;
    put_text(&bmp, "BM");
    put_le32(&bmp, offset + (uint32_t)rows_length);
    put_le32(&bmp, 0);
    put_le32(&bmp, offset);
    put_le32(&bmp, 40);
    put_le32(&bmp, (uint32_t)width);
    put_le32(&bmp, (uint32_t)height);
    put_le16(&bmp, 1);
    put_le16(&bmp, bits);
    put_le32(&bmp, compression);
    put_le32(&bmp, (uint32_t)rows_length);
    put_le32(&bmp, 2835);
    put_le32(&bmp, 2835);
    put_le32(&bmp, (uint32_t)palette_entries);
    put_le32(&bmp, 0);
    put(&bmp, palette, palette_entries * 4);
    put(&bmp, rows, rows_length);
    return bmp;
}

/* A TGA's 18-byte header (Truevision TGA 2.0): no image ID, no colour map. */
static buffer tga_header(unsigned image_type, unsigned width, unsigned height, unsigned bits,
                         unsigned descriptor)
{
    buffer tga = {0};
    put_byte(&tga, 0);
    put_byte(&tga, 0);
    put_byte(&tga, image_type);
    for (int i = 0; i < 5 + 4; i++) put_byte(&tga, 0);   /* colour map spec, origin */
    put_le16(&tga, width);
    put_le16(&tga, height);
    put_byte(&tga, bits);
    put_byte(&tga, descriptor);
    return tga;
}

static void write_to_buffer(void *context, void *data, int size)
{
    put(context, data, (size_t)size);
}

/* ---- JPEG marker segments (ITU T.81, annex B) ----------------------------------------------- */

static void jpeg_segment(buffer *jpeg, unsigned marker, const buffer *payload)
{
    put_byte(jpeg, 0xff);
    put_byte(jpeg, marker);
    put_byte(jpeg, (payload->length + 2) >> 8);
    put_byte(jpeg, payload->length + 2);
    put(jpeg, payload->data, payload->length);
}

/* SOI, a quantisation table, the frame header of a baseline 8x8 grey
 * image, `huffman` as a DHT segment, then `scans` scans of one byte of
 * data, then EOI. */
static buffer make_jpeg(const buffer *huffman, int scans)
{
    buffer jpeg = {0}, payload = {0};
    put_byte(&jpeg, 0xff);
    put_byte(&jpeg, 0xd8);
    put_byte(&payload, 0x00);   /* 8-bit table 0 */
    for (int i = 0; i < 64; i++) put_byte(&payload, 1);
    jpeg_segment(&jpeg, 0xdb, &payload);
    payload.length = 0;
    put_byte(&payload, 8);              /* precision */
    put_byte(&payload, 0);              /* height 8 */
    put_byte(&payload, 8);
    put_byte(&payload, 0);              /* width 8 */
    put_byte(&payload, 8);
    put_byte(&payload, 1);              /* one component: */
    put_byte(&payload, 1);              /*   id 1 */
    put_byte(&payload, 0x11);           /*   1x1 sampling */
    put_byte(&payload, 0);              /*   table 0 */
    jpeg_segment(&jpeg, 0xc0, &payload);
    if (huffman != NULL) jpeg_segment(&jpeg, 0xc4, huffman);
    for (int s = 0; s < scans; s++) {
        payload.length = 0;
        put_byte(&payload, 1);          /* one component */
        put_byte(&payload, 1);
        put_byte(&payload, 0x00);       /* DC and AC tables 0 */
        put_byte(&payload, 0);          /* Ss, Se, Ah/Al */
        put_byte(&payload, 63);
        put_byte(&payload, 0);
        jpeg_segment(&jpeg, 0xda, &payload);
        put_byte(&jpeg, 0x00);          /* entropy-coded data */
    }
    put_byte(&jpeg, 0xff);
    put_byte(&jpeg, 0xd9);
    buffer_free(&payload);
    return jpeg;
}

/* A DHT segment's payload (B.2.4.2) declaring 300 codes, more than the
 * 256 a table can hold: stb_image 2.27 wrote past its tables for it. */
static buffer huffman_table_of_300_codes(void)
{
    buffer table = {0};
    put_byte(&table, 0x00);   /* DC table 0 */
    static const unsigned counts[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 45, 255};
    for (int i = 0; i < 16; i++) put_byte(&table, counts[i]);
    for (int i = 0; i < 300; i++) put_byte(&table, 0);
    return table;
}

/* ---- loading from memory ------------------------------------------------------------------- */

/* Loads bytes as `name` and checks every texel of level 0 against rgba
 * (width x height, row 0 on top), within tolerance levels. */
static void assert_decodes_to(const buffer *file, const char *name, int width, int height,
                              const unsigned char *rgba, int tolerance)
{
    luz_texture *texture = NULL;
    luz_error error = {{0}};
    int status = luz_texture_load_memory(file->data, file->length, name, NULL, NULL, &texture,
                                         &error);
    if (status != 0) fail_msg("%s: %s", name, error.message);
    assert_int_equal(texture->levels[0].width, width);
    assert_int_equal(texture->levels[0].height, height);
    for (int i = 0; i < width * height * 4; i++) {
        int got = texture->levels[0].texels[i], expected = rgba[i];
        if (abs(got - expected) > tolerance)
            fail_msg("%s: texel %d channel %d is %d, expected %d", name, i / 4, i % 4, got,
                     expected);
    }
    luz_texture_destroy(texture);
}

/* Refused with LUZ_BAD_INPUT, one line holding the name and each needle. */
static void assert_refused_as(const buffer *file, const char *name, const char *hint,
                              const char *needle, const char *other)
{
    luz_texture *texture = NULL;
    luz_error error = {{0}};
    int status =
        luz_texture_load_memory(file->data, file->length, name, hint, NULL, &texture, &error);
    if (status != LUZ_BAD_INPUT)
        fail_msg("%s: status %d, expected LUZ_BAD_INPUT (%s)", name, status, error.message);
    assert_null(texture);
    if (strstr(error.message, name) == NULL || strstr(error.message, needle) == NULL ||
        (other != NULL && strstr(error.message, other) == NULL))
        fail_msg("%s: '%s' lacks '%s' or '%s'", name, error.message, needle, other ? other : "");
    assert_null(strchr(error.message, '\n'));
}

/* ---- images that decode -------------------------------------------------------------------- */

static void test_png_from_another_encoder(void **state)
{
    (void)state;
    /* 3x2 RGBA, every channel different */
    const unsigned char rgba[3 * 2 * 4] = {255, 0, 0, 255,    0, 255, 0, 128,   0, 0, 255, 0,
                                           10, 20, 30, 40,    50, 60, 70, 80,   90, 100, 110, 120};
    buffer png = {0};
    assert_true(stbi_write_png_to_func(write_to_buffer, &png, 3, 2, 4, rgba, 3 * 4));
    assert_decodes_to(&png, "a.png", 3, 2, rgba, 0);
    buffer_free(&png);
}

/* A colour-mapped PNG of 2x2 pixels and two palette entries, written by
 * hand, its rows filtered (PNG specification 9.2): row 0 with Sub (each
 * byte is the index minus the one before), row 1 with Up (minus the index
 * above). Indices 0 1 / 1 0: raw rows [1: 0 1] and [2: 1 255]. */
static void test_png_with_a_palette(void **state)
{
    (void)state;
    const unsigned char palette[2 * 3] = {200, 10, 20, 30, 40, 250};
    const unsigned char raw[] = {1, 0, 1, 2, 1, 255};
    buffer png = make_png_raw(2, 2, 8, 3, 0, palette, 2, raw, sizeof raw);
    const unsigned char rgba[] = {200, 10, 20, 255,   30, 40, 250, 255,
                                  30, 40, 250, 255,   200, 10, 20, 255};
    assert_decodes_to(&png, "palette.png", 2, 2, rgba, 0);
    buffer_free(&png);

    /* Interlaced (Adam7, 8.2): 2x2 pixels are pass 1's (0,0), pass 6's
     * (1,0) and pass 7's row (0,1) (1,1); the other passes are empty and
     * have no bytes. Indices 1 0 / 0 1. */
    const unsigned char interlaced[] = {0, 1, 0, 0, 0, 0, 1};
    png = make_png_raw(2, 2, 8, 3, 1, palette, 2, interlaced, sizeof interlaced);
    const unsigned char rgba_interlaced[] = {30, 40, 250, 255,   200, 10, 20, 255,
                                             200, 10, 20, 255,   30, 40, 250, 255};
    assert_decodes_to(&png, "interlaced.png", 2, 2, rgba_interlaced, 0);
    buffer_free(&png);
}

/* A valid PNG whose first IDAT chunk is empty (the PNG specification
 * lets the zlib stream be split anywhere among the IDATs, 0 bytes
 * included): stb_image 2.27 added 0 to a null pointer on it (undefined
 * behaviour, which UBSan reports); libpng decodes it. 2x1 RGB, filter 0:
 * raw row [0: 10 20 30  200 100 0]. The same file, with a first byte 0
 * (x.png) in front, is in the texture fuzzer's corpus. */
static buffer png_with_empty_first_idat(void)
{
    const unsigned char raw[] = {0, 10, 20, 30, 200, 100, 0};
    buffer zlib = zlib_stored(raw, sizeof raw);
    buffer png = {0};
    put(&png, png_signature, 8);
    const unsigned char header[13] = {0, 0, 0, 2, 0, 0, 0, 1, 8, 2, 0, 0, 0};
    png_chunk(&png, "IHDR", header, sizeof header);
    png_chunk(&png, "IDAT", NULL, 0);
    png_chunk(&png, "IDAT", zlib.data, zlib.length);
    png_chunk(&png, "IEND", NULL, 0);
    buffer_free(&zlib);
    return png;
}

static void test_png_with_empty_first_idat(void **state)
{
    (void)state;
    buffer png = png_with_empty_first_idat();
    const unsigned char rgba[] = {10, 20, 30, 255, 200, 100, 0, 255};
    assert_decodes_to(&png, "empty-idat.png", 2, 1, rgba, 0);
    /* and it is the corpus file, byte for byte */
    const char *corpus = getenv("TEXTURE_CORPUS_EMPTY_IDAT");
    if (corpus != NULL) {
        size_t length;
        char *bytes = read_file(corpus, &length);
        assert_non_null(bytes);
        assert_int_equal(length, png.length + 1);
        assert_int_equal(bytes[0], 0);
        assert_memory_equal(bytes + 1, png.data, png.length);
        free(bytes);
    }
    buffer_free(&png);
}

/* libpng gives the pixels stb_image gave (luz decoded PNG with it before),
 * for every colour type and bit depth PNG has, interlaced or not, with and
 * without a tRNS chunk, from rows of random bytes under random filters: so
 * no texture changes. stb_image (the tests' own libstb) is the reference. */
static void test_png_pixels_as_stb_gave_them(void **state)
{
    (void)state;
    static const struct {
        unsigned colour, channels;
        unsigned depths[5];
    } types[] = {{0, 1, {1, 2, 4, 8, 16}}, {2, 3, {8, 16}}, {3, 1, {1, 2, 4, 8}},
                 {4, 2, {8, 16}}, {6, 4, {8, 16}}};
    uint32_t random = 2463534242u;
    int checked = 0;
    for (size_t t = 0; t < sizeof types / sizeof types[0]; t++) {
        for (int d = 0; d < 5 && types[t].depths[d] != 0; d++) {
            const unsigned depth = types[t].depths[d], colour = types[t].colour;
            for (unsigned interlace = 0; interlace <= 1; interlace++) {
                for (int with_trns = 0; with_trns <= (colour == 4 || colour == 6 ? 0 : 1);
                     with_trns++) {
                    const uint32_t width = 13, height = 7;
                    /* the filtered rows: each pass's rows (Adam7) or the
                     * image's, a filter byte then random bytes */
                    buffer raw = {0};
                    static const unsigned x0[7] = {0, 4, 0, 2, 0, 1, 0}, y0[7] = {0, 0, 4, 0, 2, 0, 1};
                    static const unsigned dx[7] = {8, 8, 4, 4, 2, 2, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
                    for (int pass = 0; pass < (interlace ? 7 : 1); pass++) {
                        const uint32_t w = interlace ? (width > x0[pass] ? (width - x0[pass] + dx[pass] - 1) / dx[pass] : 0) : width;
                        const uint32_t h = interlace ? (height > y0[pass] ? (height - y0[pass] + dy[pass] - 1) / dy[pass] : 0) : height;
                        if (w == 0 || h == 0) continue;
                        const size_t row_bytes = ((size_t)w * types[t].channels * depth + 7) / 8;
                        for (uint32_t y = 0; y < h; y++) {
                            random ^= random << 13, random ^= random >> 17, random ^= random << 5;
                            put_byte(&raw, random % 5);
                            for (size_t i = 0; i < row_bytes; i++) {
                                random ^= random << 13, random ^= random >> 17, random ^= random << 5;
                                unsigned char byte = (unsigned char)(random >> 24);
                                put_byte(&raw, byte);
                            }
                        }
                    }
                    /* a palette with every index a depth allows: no index
                     * can fall outside it whatever the filters make */
                    unsigned char palette[256 * 3];
                    for (int i = 0; i < 256 * 3; i++) palette[i] = (unsigned char)(i * 7 + 3);
                    const size_t entries = colour == 3 ? (size_t)1 << depth : 0;
                    buffer zlib = zlib_stored(raw.data, raw.length);
                    buffer png = png_start(width, height, depth, colour, interlace, palette,
                                           entries);
                    if (with_trns) {
                        /* a palette's first entries' alphas (at most as
                         * many as it has); a grey key of 1, which half
                         * the pixels of 1 bit meet; an RGB key of 1, 1, 1 */
                        unsigned char trns[6] = {0, 1, 0, 1, 0, 1};
                        size_t trns_length = colour == 3 ? (entries < 5 ? entries : 5)
                                             : colour == 0 ? 2 : 6;
                        if (colour == 3)
                            for (int i = 0; i < 5; i++) trns[i] = (unsigned char)(i * 60);
                        png_chunk(&png, "tRNS", trns, trns_length);
                    }
                    png_chunk(&png, "IDAT", zlib.data, zlib.length);
                    png_chunk(&png, "IEND", NULL, 0);
                    buffer_free(&zlib);
                    buffer_free(&raw);

                    int stb_width, stb_height, stb_channels;
                    unsigned char *expected = stbi_load_from_memory(
                        png.data, (int)png.length, &stb_width, &stb_height, &stb_channels, 4);
                    if (expected == NULL)
                        fail_msg("colour %u depth %u: stb_image refused it: %s", colour, depth,
                                 stbi_failure_reason());
                    char name[64];
                    snprintf(name, sizeof name, "c%u-d%u-i%u-t%d.png", colour, depth, interlace,
                             with_trns);
                    assert_decodes_to(&png, name, (int)width, (int)height, expected, 0);
                    stbi_image_free(expected);
                    buffer_free(&png);
                    checked++;
                }
            }
        }
    }
    assert_int_equal(checked, 2 * (5 * 2 + 2 * 2 + 4 * 2) + 2 * (2 + 2));
}

/* 24-bit BMP, 3x2, bottom-up rows of 9 bytes padded to 12 (BGR). */
static void test_bmp(void **state)
{
    (void)state;
    const unsigned char rows[2 * 12] = {
        /* bottom row: (0,1) (1,1) (2,1) */
        1, 2, 3,   4, 5, 6,   7, 8, 9,   0, 0, 0,
        /* top row */
        30, 20, 10,   60, 50, 40,   90, 80, 70,   0, 0, 0};
    buffer bmp = make_bmp(3, 2, 24, 0, NULL, 0, rows, sizeof rows);
    const unsigned char rgba[] = {10, 20, 30, 255,   40, 50, 60, 255,   70, 80, 90, 255,
                                  3, 2, 1, 255,      6, 5, 4, 255,      9, 8, 7, 255};
    assert_decodes_to(&bmp, "rgb.bmp", 3, 2, rgba, 0);
    buffer_free(&bmp);

    /* 8 bits, a palette of two: indices 1 0 (bottom) and 0 1 (top) */
    const unsigned char palette[2 * 4] = {10, 20, 30, 0, 40, 50, 60, 0};
    const unsigned char indices[2 * 4] = {1, 0, 0, 0, 0, 1, 0, 0};
    bmp = make_bmp(2, 2, 8, 0, palette, 2, indices, sizeof indices);
    const unsigned char rgba_mapped[] = {30, 20, 10, 255,   60, 50, 40, 255,
                                         60, 50, 40, 255,   30, 20, 10, 255};
    assert_decodes_to(&bmp, "mapped.bmp", 2, 2, rgba_mapped, 0);
    buffer_free(&bmp);
}

/* TGA: 24-bit true colour, rows bottom-up (descriptor 0), stored and
 * run-length encoded (a packet of 0x81 repeats its one pixel twice, one of
 * 0x01 holds two pixels as they are). */
static void test_tga(void **state)
{
    (void)state;
    const unsigned char rgba[] = {1, 2, 3, 255,   4, 5, 6, 255,   7, 8, 9, 255,   7, 8, 9, 255};
    buffer tga = tga_header(2, 2, 2, 24, 0);
    const unsigned char bgr[] = {9, 8, 7, 9, 8, 7, /* bottom */ 3, 2, 1, 6, 5, 4};
    put(&tga, bgr, sizeof bgr);
    assert_decodes_to(&tga, "stored.tga", 2, 2, rgba, 0);
    buffer_free(&tga);

    tga = tga_header(10, 2, 2, 24, 0);
    const unsigned char packets[] = {0x81, 9, 8, 7, 0x01, 3, 2, 1, 6, 5, 4};
    put(&tga, packets, sizeof packets);
    assert_decodes_to(&tga, "rle.tga", 2, 2, rgba, 0);
    buffer_free(&tga);
}

/* JPEG through stb_image_write's encoder (quality 100, no subsampling),
 * two flat 8x8 blocks: lossy, but a flat block's DC is all there is. */
static void test_jpeg(void **state)
{
    (void)state;
    unsigned char rgb[16 * 8 * 3], rgba[16 * 8 * 4];
    for (int y = 0; y < 8; y++) {
        for (int x = 0; x < 16; x++) {
            const unsigned char colour[3] = {x < 8 ? 200 : 20, x < 8 ? 100 : 180, x < 8 ? 50 : 90};
            memcpy(rgb + (y * 16 + x) * 3, colour, 3);
            memcpy(rgba + (y * 16 + x) * 4, colour, 3);
            rgba[(y * 16 + x) * 4 + 3] = 255;
        }
    }
    buffer jpeg = {0};
    assert_true(stbi_write_jpg_to_func(write_to_buffer, &jpeg, 16, 8, 3, rgb, 100));
    assert_decodes_to(&jpeg, "blocks.jpg", 16, 8, rgba, 3);
    assert_decodes_to(&jpeg, "BLOCKS.JPEG", 16, 8, rgba, 3);

    /* cut at two thirds: truncated, not shown in part */
    buffer cut = {0};
    put(&cut, jpeg.data, jpeg.length * 2 / 3);
    assert_refused_as(&cut, "cut.jpg", NULL, "truncated JPEG", NULL);
    buffer_free(&cut);
    buffer_free(&jpeg);
}

/* ---- refusals --------------------------------------------------------------------------------- */

/* The crafted files of the issue, and the other formats a .png can hide. */
static void test_misnamed_files_refused(void **state)
{
    (void)state;
    buffer file = {0};
    /* a 16-bit PGM of 1x1 (Netpbm: P5, width, height, maxval 65535, then
     * two bytes): stb_image's PNM decoder crashed on it */
    put_text(&file, "P5\n1 1\n65535\n\xff\xff");
    assert_refused_as(&file, "x.png", NULL, "not a PNG file", "PNM");
    buffer_free(&file);

    /* a truncated run-length HDR: stb_image's HDR decoder looped forever */
    put_text(&file, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 8\n\x02\x02\x00\x08\x88");
    assert_refused_as(&file, "x.png", NULL, "not a PNG file", "Radiance HDR");
    buffer_free(&file);

    put_text(&file, "8BPS\x00\x01\x00\x00\x00\x00\x00\x00\x00\x03");
    assert_refused_as(&file, "layers.png", NULL, "not a PNG file", "Photoshop");
    buffer_free(&file);

    put_text(&file, "GIF89a\x01\x00\x01\x00\x00\x00\x00;");
    assert_refused_as(&file, "anim.jpg", NULL, "not a JPEG file", "GIF");
    buffer_free(&file);

    /* a sound JPEG named .png: the name and the bytes must agree */
    file = make_jpeg(NULL, 1);
    assert_refused_as(&file, "photo.png", NULL, "not a PNG file", "a JPEG image");
    assert_refused_as(&file, "photo.bmp", NULL, "not a BMP file", "a JPEG image");
    assert_refused_as(&file, "photo.tga", NULL, "not a TGA file", "a JPEG image");
    buffer_free(&file);

    put_text(&file, "just some text");
    assert_refused_as(&file, "notes.png", NULL, "not a PNG file", "signature");
    assert_refused_as(&file, "notes.jpg", NULL, "not a JPEG file", "signature");
    assert_refused_as(&file, "notes.bmp", NULL, "not a BMP file", "signature");
    /* embedded, with no name nor hint to tell: only the signatures can */
    assert_refused_as(&file, "*0", NULL, "no PNG, JPEG or BMP signature", NULL);
    assert_refused_as(&file, "*0", "dds", "format 'dds'", NULL);
    assert_refused_as(&file, "texture.gif", NULL, "signature", NULL);
    buffer_free(&file);

    put_byte(&file, 0);
    file.length = 0;
    assert_refused_as(&file, "empty.png", NULL, "empty", NULL);
    buffer_free(&file);
}

static void test_png_refusals(void **state)
{
    (void)state;
    const unsigned char one_grey_pixel[] = {0, 128};
    buffer png = make_png_raw(100000, 100000, 8, 6, 0, NULL, 0, one_grey_pixel, 2);
    assert_refused_as(&png, "huge.png", NULL, "image is 100000x100000",
                      "expected 1x1 to 8192x8192");
    buffer_free(&png);
    png = make_png_raw(8193, 1, 8, 0, 0, NULL, 0, one_grey_pixel, 2);
    assert_refused_as(&png, "wide.png", NULL, "image is 8193x1", NULL);
    buffer_free(&png);

    /* the signature and IHDR, and nothing more (33 bytes) */
    png = make_png_raw(1, 1, 8, 0, 0, NULL, 0, one_grey_pixel, 2);
    buffer cut = {0};
    put(&cut, png.data, 33);
    assert_refused_as(&cut, "cut.png", NULL, "truncated PNG", NULL);
    /* everything but the last byte of IEND's CRC */
    cut.length = 0;
    put(&cut, png.data, png.length - 1);
    assert_refused_as(&cut, "cut.png", NULL, "truncated PNG", NULL);
    buffer_free(&cut);
    buffer_free(&png);

    /* a 1x1 grey image's data is 2 bytes (a filter byte and the pixel):
     * a stream of 100000 must not be inflated past them, one of 1 is short */
    unsigned char *zeros = calloc(100000, 1);
    assert_non_null(zeros);
    png = make_png_raw(1, 1, 8, 0, 0, NULL, 0, zeros, 100000);
    assert_refused_as(&png, "bomb.png", NULL, "inflates to more than the 2 bytes", NULL);
    buffer_free(&png);
    buffer zlib = zlib_zeros(100000000);   /* 100 MB in 630 KB */
    png = make_png(1, 1, 8, 0, 0, NULL, 0, &zlib);
    assert_refused_as(&png, "bomb.png", NULL, "inflates to more than the 2 bytes", NULL);
    buffer_free(&png);
    buffer_free(&zlib);
    png = make_png_raw(1, 1, 8, 0, 0, NULL, 0, zeros, 1);
    assert_refused_as(&png, "short.png", NULL, "inflates to fewer", NULL);
    buffer_free(&png);
    free(zeros);

    /* an index past the palette's two entries, once Sub is undone: raw
     * [1: 1 1] is indices 1 and 2 (stb_image would read a stack array
     * it never filled) */
    const unsigned char palette[2 * 3] = {1, 2, 3, 4, 5, 6};
    const unsigned char past[] = {1, 1, 1};
    png = make_png_raw(2, 1, 8, 3, 0, palette, 2, past, sizeof past);
    assert_refused_as(&png, "index.png", NULL, "a pixel of colour 2", "palette has 2");
    buffer_free(&png);
    /* the same in pass 7 of an interlaced image (passes 1 and 6 are one
     * pixel each, their rows [0: 1] and [0: 0]) */
    const unsigned char past_interlaced[] = {0, 1, 0, 0, 1, 1, 1};
    png = make_png_raw(2, 2, 8, 3, 1, palette, 2, past_interlaced, sizeof past_interlaced);
    assert_refused_as(&png, "index.png", NULL, "a pixel of colour 2", NULL);
    buffer_free(&png);
    /* no palette at all */
    png = make_png_raw(2, 1, 8, 3, 0, NULL, 0, past, sizeof past);
    assert_refused_as(&png, "noplte.png", NULL, "no PLTE", NULL);
    buffer_free(&png);
    /* colour type 2 (RGB) cannot have 4 bits */
    png = make_png_raw(1, 1, 4, 2, 0, NULL, 0, one_grey_pixel, 2);
    assert_refused_as(&png, "depth.png", NULL, "colour type 2 with bit depth 4", NULL);
    buffer_free(&png);

    /* a critical chunk luz does not know, after IHDR */
    png.length = 0;
    put(&png, png_signature, 8);
    buffer tail = make_png_raw(1, 1, 8, 0, 0, NULL, 0, one_grey_pixel, 2);
    put(&png, tail.data + 8, 25);   /* IHDR */
    png_chunk(&png, "ABCD", "x", 1);
    put(&png, tail.data + 33, tail.length - 33);
    assert_refused_as(&png, "chunk.png", NULL, "critical chunk ABCD", NULL);
    buffer_free(&png);
    /* Apple's CgBI before IHDR */
    put(&png, png_signature, 8);
    png_chunk(&png, "CgBI", "\x50\x00\x20\x06", 4);
    put(&png, tail.data + 8, tail.length - 8);
    assert_refused_as(&png, "apple.png", NULL, "expected IHDR first", NULL);
    buffer_free(&png);
    buffer_free(&tail);
}

static void test_bmp_refusals(void **state)
{
    (void)state;
    const unsigned char row[4] = {1, 2, 3, 0};
    buffer bmp = make_bmp(1, 1, 24, 0, NULL, 0, row, 4);
    buffer cut = {0};
    put(&cut, bmp.data, bmp.length - 1);
    assert_refused_as(&cut, "cut.bmp", NULL, "truncated BMP", NULL);
    buffer_free(&cut);
    buffer_free(&bmp);

    bmp = make_bmp(1, 1, 8, 1, (const unsigned char *)"\0\0\0\0", 1, row, 4);
    assert_refused_as(&bmp, "rle.bmp", NULL, "unsupported BMP", "compression 1");
    buffer_free(&bmp);
    bmp = make_bmp(1, -9000, 24, 0, NULL, 0, row, 4);
    assert_refused_as(&bmp, "tall.bmp", NULL, "image is 1x9000", NULL);
    buffer_free(&bmp);
    bmp = make_bmp(100000, 1, 24, 0, NULL, 0, row, 4);
    assert_refused_as(&bmp, "wide.bmp", NULL, "image is 100000x1", NULL);
    buffer_free(&bmp);

    /* 8 bits, a palette of two, a pixel of colour 5 */
    const unsigned char palette[2 * 4] = {0};
    const unsigned char indices[4] = {5, 0, 0, 0};
    bmp = make_bmp(1, 1, 8, 0, palette, 2, indices, 4);
    assert_refused_as(&bmp, "index.bmp", NULL, "a pixel of colour 5", "palette has 2");
    buffer_free(&bmp);
    /* 4 bits: the second pixel is the low nibble, colour 3 */
    const unsigned char nibbles[4] = {0x13, 0, 0, 0};
    bmp = make_bmp(2, 1, 4, 0, palette, 2, nibbles, 4);
    assert_refused_as(&bmp, "nibble.bmp", NULL, "a pixel of colour 3", NULL);
    buffer_free(&bmp);

    /* an OS/2 bitmap: its 12-byte header */
    put_text(&bmp, "BM");
    put_le32(&bmp, 30);
    put_le32(&bmp, 0);
    put_le32(&bmp, 26);
    put_le32(&bmp, 12);
    put_le16(&bmp, 1);
    put_le16(&bmp, 1);
    put_le16(&bmp, 1);
    put_le16(&bmp, 24);
    put(&bmp, row, 4);
    assert_refused_as(&bmp, "os2.bmp", NULL, "OS/2", NULL);
    buffer_free(&bmp);
}

static void test_tga_refusals(void **state)
{
    (void)state;
    /* 18 bytes that claim 8000 x 8000 pixels of 32 bits: once a black
     * texture of 586 MB, now a file 256 MB too short */
    buffer tga = tga_header(2, 8000, 8000, 32, 0);
    assert_refused_as(&tga, "x.tga", NULL, "truncated TGA", "8000x8000");
    buffer_free(&tga);
    tga = tga_header(2, 9000, 10, 32, 0);
    assert_refused_as(&tga, "wide.tga", NULL, "image is 9000x10", NULL);
    buffer_free(&tga);
    /* image type 5 does not exist; 12 bits a pixel neither */
    tga = tga_header(5, 1, 1, 24, 0);
    put_text(&tga, "abc");
    assert_refused_as(&tga, "type.tga", NULL, "not a TGA file luz reads", "image type 5");
    buffer_free(&tga);
    tga = tga_header(2, 1, 1, 12, 0);
    put_text(&tga, "abc");
    assert_refused_as(&tga, "bits.tga", NULL, "not a TGA file luz reads", "12 bits");
    buffer_free(&tga);
    /* run-length data ending after 2 of 4 pixels */
    tga = tga_header(10, 2, 2, 24, 0);
    const unsigned char packets[] = {0x81, 9, 8, 7};
    put(&tga, packets, sizeof packets);
    assert_refused_as(&tga, "rle.tga", NULL, "truncated TGA", "after 2 of 4 pixels");
    /* a raw packet whose pixels run past the end */
    put_byte(&tga, 0x01);
    put_byte(&tga, 1);
    assert_refused_as(&tga, "rle.tga", NULL, "truncated TGA", "after 2 of 4 pixels");
    buffer_free(&tga);
    /* an embedded TGA needs its hint; with it, it is read */
    tga = tga_header(2, 1, 1, 24, 0);
    put_text(&tga, "abc");
    assert_refused_as(&tga, "*1", NULL, "no PNG, JPEG or BMP signature", NULL);
    luz_texture *texture = NULL;
    luz_error error;
    assert_int_equal(luz_texture_load_memory(tga.data, tga.length, "*1", "tga", NULL, &texture,
                                             &error), 0);
    assert_int_equal(texture->levels[0].texels[0], 'c');   /* BGR: c, b, a */
    luz_texture_destroy(texture);
    buffer_free(&tga);
}

static void test_jpeg_refusals(void **state)
{
    (void)state;
    buffer huffman = huffman_table_of_300_codes();
    buffer jpeg = make_jpeg(&huffman, 1);
    assert_refused_as(&jpeg, "huffman.jpg", NULL, "corrupt or unsupported JPEG", NULL);
    buffer_free(&jpeg);
    buffer_free(&huffman);

    /* 101 scans: each would be a pass over the whole image */
    jpeg = make_jpeg(NULL, 101);
    assert_refused_as(&jpeg, "scans.jpg", NULL, "more than 100 scans", NULL);
    buffer_free(&jpeg);

    /* no EOI: the last scan's data runs to the end */
    jpeg = make_jpeg(NULL, 1);
    jpeg.length -= 2;
    assert_refused_as(&jpeg, "noeoi.jpg", NULL, "truncated JPEG", NULL);
    buffer_free(&jpeg);

    /* a scan before any frame header */
    put_byte(&jpeg, 0xff);
    put_byte(&jpeg, 0xd8);
    buffer sos = {0};
    const unsigned char scan[] = {1, 1, 0, 0, 63, 0};
    put(&sos, scan, sizeof scan);
    jpeg_segment(&jpeg, 0xda, &sos);
    put_byte(&jpeg, 0xff);
    put_byte(&jpeg, 0xd9);
    assert_refused_as(&jpeg, "noframe.jpg", NULL, "a scan before the frame header", NULL);
    buffer_free(&jpeg);
    buffer_free(&sos);
}

/* ---- the budget ----------------------------------------------------------------------------- */

static void write_buffer(const char *path, const buffer *b)
{
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(b->data, 1, b->length, file), b->length);
    assert_int_equal(fclose(file), 0);
}

static void write_text_file(const char *path, const char *text)
{
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_int_equal(fputs(text, file) >= 0, 1);
    assert_int_equal(fclose(file), 0);
}

static void make_temporary_directory(char *path, size_t size)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(path, size, "%s/luz-hostile-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    assert_non_null(mkdtemp(path));
}

/* A 4x4 texture's chain is 4x4, 2x2 and 1x1 texels of 4 bytes: 84 bytes,
 * and the luz_texture itself. A budget of two such textures takes a.bmp
 * and b.bmp and refuses c.bmp, naming it. */
static void test_budget(void **state)
{
    (void)state;
    const uint64_t one = sizeof(luz_texture) + 4 * (16 + 4 + 1);
    assert_int_equal(luz_texture_bytes(4, 4), one);
    /* 8192 x 8192: 4 (4^14 - 1) / 3 bytes of texels, 341.3 MiB */
    assert_int_equal(luz_texture_bytes(8192, 8192), sizeof(luz_texture) + 357913940u);

    char directory[256], path[512];
    make_temporary_directory(directory, sizeof directory);
    unsigned char rows[4 * 12] = {0};
    buffer bmp = make_bmp(4, 4, 24, 0, NULL, 0, rows, sizeof rows);
    for (const char *name = "abc"; *name != '\0'; name++) {
        snprintf(path, sizeof path, "%s/%c.bmp", directory, *name);
        write_buffer(path, &bmp);
    }
    buffer_free(&bmp);

    luz_texture_budget budget = {.limit = 2 * one};
    luz_texture_set set;
    luz_error error = {{0}};
    assert_int_equal(luz_texture_set_load(&set, directory, &budget, &error), LUZ_BAD_INPUT);
    if (strstr(error.message, "/c.bmp: a 4x4 texture") == NULL ||
        strstr(error.message, "over luz's budget") == NULL)
        fail_msg("%s", error.message);
    assert_int_equal(set.count, 0);

    /* with room for three, all three, and the budget says what they take */
    budget = (luz_texture_budget){.limit = 3 * one};
    assert_int_equal(luz_texture_set_load(&set, directory, &budget, &error), 0);
    assert_int_equal(set.count, 3);
    assert_int_equal(budget.used, 3 * one);
    luz_texture_set_free(&set);
    /* the budget is checked from the header, before decoding: a 64x64
     * PNG of no pixels at all is refused for its size */
    budget = (luz_texture_budget){.limit = one};
    const unsigned char nothing[1] = {0};
    buffer png = make_png_raw(64, 64, 8, 6, 0, NULL, 0, nothing, 1);
    luz_texture *texture = NULL;
    assert_int_equal(luz_texture_load_memory(png.data, png.length, "empty.png", NULL, &budget,
                                             &texture, &error), LUZ_BAD_INPUT);
    if (strstr(error.message, "empty.png: a 64x64 texture") == NULL) fail_msg("%s", error.message);
    assert_int_equal(budget.used, 0);
    buffer_free(&png);
    /* the default, 1 GiB, when the limit is 0 */
    budget = (luz_texture_budget){.used = LUZ_TEXTURE_BUDGET_BYTES - one + 1};
    assert_int_equal(luz_texture_budget_check(&budget, 4, 4, "x", &error), LUZ_BAD_INPUT);
    budget.used--;
    assert_int_equal(luz_texture_budget_check(&budget, 4, 4, "x", &error), 0);
    remove_tree(directory);
}

/* ---- opening inputs ---------------------------------------------------------------------------- */

/* luz_input_read refuses path with status, one line holding the needle,
 * at once (a blocking open would never return: SIGALRM ends the test). */
static void assert_input_refused(const char *path, uint64_t limit, int status, const char *needle)
{
    unsigned char *bytes = (unsigned char *)"untouched";
    size_t size = 7;
    luz_error error = {{0}};
    alarm(10);
    int got = luz_input_read(path, "a test file", limit, &bytes, &size, &error);
    alarm(0);
    if (got != status) fail_msg("%s: status %d, expected %d (%s)", path, got, status, error.message);
    assert_null(bytes);
    assert_int_equal(size, 0);
    if (strstr(error.message, path) == NULL || strstr(error.message, needle) == NULL)
        fail_msg("%s: '%s' lacks '%s'", path, error.message, needle);
}

static void test_input_files(void **state)
{
    (void)state;
    char directory[256], path[512];
    make_temporary_directory(directory, sizeof directory);

    snprintf(path, sizeof path, "%s/fifo", directory);
    assert_int_equal(mkfifo(path, 0600), 0);
    assert_input_refused(path, 1000, LUZ_BAD_INPUT, "not a regular file (a FIFO; expected a test file)");
    assert_input_refused(directory, 1000, LUZ_BAD_INPUT, "not a regular file (a directory");
    assert_input_refused("/dev/null", 1000, LUZ_BAD_INPUT, "(a character device");
    snprintf(path, sizeof path, "%s/missing", directory);
    assert_input_refused(path, 1000, LUZ_NO_SUCH_FILE, "No such file");
    snprintf(path, sizeof path, "%s/missing/below", directory);
    assert_input_refused(path, 1000, LUZ_NO_SUCH_FILE, "No such file");

    /* 11 bytes against a limit of 10, then 11 */
    buffer text = {0};
    put_text(&text, "eleven byte");
    snprintf(path, sizeof path, "%s/eleven", directory);
    write_buffer(path, &text);
    assert_input_refused(path, 10, LUZ_BAD_INPUT, "11 bytes");
    unsigned char *bytes;
    size_t size;
    luz_error error;
    assert_int_equal(luz_input_read(path, "a test file", 11, &bytes, &size, &error), 0);
    assert_int_equal(size, 11);
    assert_memory_equal(bytes, "eleven byte", 12);   /* and a NUL after */
    free(bytes);
    buffer_free(&text);

    /* a /proc file says it has 0 bytes and has more: read to its end,
     * never past the limit */
    assert_int_equal(luz_input_read("/proc/self/status", "a test file", 1 << 20, &bytes, &size,
                                    &error), 0);
    assert_true(size > 0);
    assert_non_null(strstr((char *)bytes, "Name:"));
    free(bytes);
    assert_input_refused("/proc/self/status", 5, LUZ_BAD_INPUT, "more than");
    remove_tree(directory);
}

/* The scene fuzzer's entry: text in memory, read as a file named so. */
static void test_scene_text(void **state)
{
    (void)state;
    luz_options options;
    luz_options_init(&options);
    luz_error error = {{0}};
    const char text[] = "time = 2.5\nmodel = m.obj at 1, 2, 3\n";
    assert_int_equal(luz_options_read_scene_text(&options, text, sizeof text - 1,
                                                 "/scenes/a.luz", &error), 0);
    assert_true(options.scene.time_seconds == 2.5);
    assert_int_equal(options.scene.object_count, 1);
    assert_string_equal(options.object_sources[0].model_path, "/scenes/m.obj");
    luz_options_free(&options);

    luz_options_init(&options);
    assert_int_equal(luz_options_read_scene_text(&options, "", 0, "/e.luz", &error), 0);
    const char bad[] = "time = 1\nfov = 400\n";
    assert_int_equal(luz_options_read_scene_text(&options, bad, sizeof bad - 1, "/b.luz",
                                                 &error), -1);
    if (strstr(error.message, "/b.luz:2: fov") == NULL) fail_msg("%s", error.message);
    luz_options_free(&options);
}

/* ---- luz-render ----------------------------------------------------------------------------- */

static const char *luz_render_path(void)
{
    const char *program = getenv("LUZ_RENDER");
    if (program == NULL) fail_msg("LUZ_RENDER is not set (tests/meson.build sets it)");
    return program;
}

typedef struct run_result {
    int status;        /* exit status, 128 + signal, or -1 for killed at the deadline */
    char *err;
    double seconds;
} run_result;


/* Runs luz-render with arguments (NULL-terminated) in work, stderr into
 * work/../stderr, no LUZ_TEXTURES; killed if it runs past `deadline`
 * seconds (a blocked open). address_space: RLIMIT_AS in bytes, 0 for
 * none. */
static run_result run_render(const char *root, const char *work, const char *const *arguments,
                             double deadline, rlim_t address_space)
{
    char err_path[512];
    snprintf(err_path, sizeof err_path, "%s/stderr", root);
    char *argv[32];
    int argc = 0;
    argv[argc++] = (char *)luz_render_path();
    for (int i = 0; arguments[i] != NULL && argc < 31; i++) argv[argc++] = (char *)arguments[i];
    argv[argc] = NULL;
    const double start = now_seconds();
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int err = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int out = open("/dev/null", O_WRONLY);
        if (err < 0 || out < 0 || chdir(work) != 0 || dup2(err, STDERR_FILENO) < 0 ||
            dup2(out, STDOUT_FILENO) < 0)
            _exit(127);
        unsetenv("LUZ_TEXTURES");
        if (address_space != 0) {
            struct rlimit limit = {address_space, address_space};
            if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(127);
        }
        execv(argv[0], argv);
        _exit(127);
    }
    run_result result = {.status = -1};
    for (;;) {
        int status;
        pid_t done = waitpid(child, &status, WNOHANG);
        assert_true(done >= 0 || errno == EINTR);
        if (done == child) {
            result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            break;
        }
        if (now_seconds() - start > deadline) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
            break;
        }
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    }
    result.seconds = now_seconds() - start;
    result.err = read_file(err_path, NULL);
    assert_non_null(result.err);
    return result;
}

/* A work directory (root/work) with what the cases share: tex/ with one
 * sound BMP, a model with its .mtl naming a texture. */
typedef struct sandbox {
    char root[256], work[300];
} sandbox;

static void sandbox_path(const sandbox *box, const char *name, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", box->work, name);
}

static void sandbox_write(const sandbox *box, const char *name, const void *data, size_t length)
{
    char path[600];
    sandbox_path(box, name, path, sizeof path);
    buffer b = {.data = (unsigned char *)data, .length = length};
    write_buffer(path, &b);
}

static void sandbox_text(const sandbox *box, const char *name, const char *text)
{
    sandbox_write(box, name, text, strlen(text));
}

static void sandbox_directory(const sandbox *box, const char *name)
{
    char path[600];
    sandbox_path(box, name, path, sizeof path);
    assert_int_equal(mkdir(path, 0755), 0);
}

static void sandbox_fifo(const sandbox *box, const char *name)
{
    char path[600];
    sandbox_path(box, name, path, sizeof path);
    assert_int_equal(mkfifo(path, 0600), 0);
}

/* an OBJ triangle with texture coordinates, its material from mtl */
static void sandbox_model(const sandbox *box, const char *name, const char *mtl)
{
    char text[512];
    snprintf(text, sizeof text,
             "mtllib %s\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\n"
             "f 1/1 2/2 3/3\n", mtl);
    sandbox_text(box, name, text);
}

static void sandbox_create(sandbox *box)
{
    make_temporary_directory(box->root, sizeof box->root);
    snprintf(box->work, sizeof box->work, "%s/work", box->root);
    assert_int_equal(mkdir(box->work, 0755), 0);
    sandbox_directory(box, "tex");
    const unsigned char row[4] = {10, 20, 30, 0};
    buffer bmp = make_bmp(1, 1, 24, 0, NULL, 0, row, 4);
    sandbox_write(box, "tex/a.bmp", bmp.data, bmp.length);
    buffer_free(&bmp);
}

/* Status 2 within the deadline, one line holding needle and other (or,
 * if not NULL, alternative in other's place), nothing on stdout, and no
 * file made in work/. */
static void assert_render_refuses_either(const sandbox *box, const char *const *arguments,
                                         double deadline, const char *needle, const char *other,
                                         const char *alternative)
{
    static char before[16384], after[16384];
    before[0] = after[0] = '\0';
    list_tree(box->work, "", before, sizeof before);
    run_result result = run_render(box->root, box->work, arguments, deadline, 0);
    if (result.status == -1)
        fail_msg("luz-render still running after %.0f s (blocked?): %s", deadline, result.err);
    if (result.status != 2)
        fail_msg("exit status %d, expected 2; stderr: %s", result.status, result.err);
    const char *newline = strchr(result.err, '\n');
    if (newline == NULL || newline[1] != '\0' || strncmp(result.err, "luz-render: ", 12) != 0)
        fail_msg("expected one line 'luz-render: ...', got '%s'", result.err);
    const bool has_other = other == NULL || strstr(result.err, other) != NULL ||
                           (alternative != NULL && strstr(result.err, alternative) != NULL);
    if (strstr(result.err, needle) == NULL || !has_other)
        fail_msg("'%s' lacks '%s' or '%s'%s%s%s", result.err, needle, other ? other : "",
                 alternative ? " (or '" : "", alternative ? alternative : "",
                 alternative ? "')" : "");
    list_tree(box->work, "", after, sizeof after);
    assert_string_equal(before, after);
    free(result.err);
}

static void assert_render_refuses(const sandbox *box, const char *const *arguments,
                                  double deadline, const char *needle, const char *other)
{
    assert_render_refuses_either(box, arguments, deadline, needle, other, NULL);
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

/* FIFOs where luz reads files: each once blocked luz-render forever. */
static void test_fifos_never_block(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    sandbox_fifo(&box, "scene.luz");
    assert_render_refuses(&box, ARGS("--scene", "scene.luz", "-o", "x.png"), 10,
                          "scene.luz: not a regular file (a FIFO", NULL);

    sandbox_directory(&box, "fifotex");
    sandbox_fifo(&box, "fifotex/x.png");
    assert_render_refuses(&box, ARGS("--textures", "fifotex", "--size", "8x8", "-o", "x.png"), 10,
                          "fifotex/x.png: not a regular file (a FIFO", NULL);

    if (luz_models_supported()) {
        sandbox_fifo(&box, "fifo.obj");
        assert_render_refuses(&box, ARGS("--model", "fifo.obj", "--textures", "none", "-o", "x.png"),
                              10, "fifo.obj: not a regular file (a FIFO", NULL);
        /* the .mtl an OBJ names */
        sandbox_fifo(&box, "fifo.mtl");
        sandbox_model(&box, "mtl.obj", "fifo.mtl");
        assert_render_refuses(&box, ARGS("--model", "mtl.obj", "--textures", "none", "-o", "x.png"),
                              10, "mtl.obj: ", "fifo.mtl: not a regular file (a FIFO");
        /* the texture a material names: not opened, and (SCENE.md,
         * "Models") the model is drawn without it, with one warning */
        sandbox_text(&box, "tex.mtl", "newmtl m\nmap_Kd fifotex/x.png\n");
        sandbox_model(&box, "tex.obj", "tex.mtl");
        run_result result = run_render(box.root, box.work,
                                       ARGS("--model", "tex.obj", "--textures", "none", "--size",
                                            "8x8", "-o", "x.png"), 10, 0);
        if (result.status != 0) fail_msg("exit status %d: %s", result.status, result.err);
        const char *newline = strchr(result.err, '\n');
        assert_true(newline != NULL && newline[1] == '\0');
        assert_non_null(strstr(result.err, "tex.obj: texture 'fifotex/x.png'"));
        assert_non_null(strstr(result.err, "a FIFO"));
        free(result.err);
        char png[600];
        sandbox_path(&box, "x.png", png, sizeof png);
        assert_int_equal(unlink(png), 0);
        /* a model in a scene file */
        sandbox_text(&box, "models.luz", "model = mtl.obj\n");
        assert_render_refuses(&box, ARGS("--scene", "models.luz", "--textures", "none", "-o", "x.png"),
                              10, "models.luz:1: model", "fifo.mtl: not a regular file");
    }
    remove_tree(box.root);
}

/* Textures that cannot be read are the input's fault, exit 2 with one
 * line naming them, not 1 (a failure of the machine): a symbolic link to
 * /proc/self/pagemap (a regular file whose read() says EINVAL), a
 * directory under an image's name, and, when not run as root (whom
 * permissions do not stop), a file without read permission. */
static void test_unreadable_textures(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    sandbox_directory(&box, "p");
    char path[600];
    sandbox_path(&box, "p/x.png", path, sizeof path);
    assert_int_equal(symlink("/proc/self/pagemap", path), 0);
    assert_render_refuses(&box, ARGS("--textures", "p", "--size", "8x8", "-o", "x.png"), 10,
                          "p/x.png: ", "cannot read the image file");
    sandbox_directory(&box, "d");
    sandbox_directory(&box, "d/x.png");
    assert_render_refuses(&box, ARGS("--textures", "d", "--size", "8x8", "-o", "x.png"), 10,
                          "d/x.png: not a regular file (a directory", NULL);
    if (geteuid() != 0) {
        sandbox_directory(&box, "n");
        const unsigned char row[4] = {10, 20, 30, 0};
        buffer bmp = make_bmp(1, 1, 24, 0, NULL, 0, row, 4);
        sandbox_write(&box, "n/x.bmp", bmp.data, bmp.length);
        buffer_free(&bmp);
        sandbox_path(&box, "n/x.bmp", path, sizeof path);
        assert_int_equal(chmod(path, 0), 0);
        assert_render_refuses(&box, ARGS("--textures", "n", "--size", "8x8", "-o", "x.png"), 10,
                              "n/x.bmp: cannot open the image file", "Permission denied");
    } else {
        print_message("not checked as root: a texture without read permission\n");
    }
    remove_tree(box.root);
}

/* Crafted textures through the real program: one line each, exit 2. */
static void test_crafted_textures(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    sandbox_directory(&box, "t");
    sandbox_directory(&box, "t/d.png");
    assert_render_refuses(&box, ARGS("--textures", "t", "--size", "8x8", "-o", "x.png"), 10,
                          "t/d.png: not a regular file (a directory", NULL);
    remove_tree(box.root);

    struct {
        const char *name;
        buffer file;
        const char *needle;
    } cases[4] = {{"x.png", {0}, "not a PNG file but, by its first bytes, a PNM image"},
                  {"x.tga", {0}, "truncated TGA"},
                  {"x.jpg", {0}, "corrupt or unsupported JPEG"},
                  {"y.png", {0}, "image is 100000x100000"}};
    put_text(&cases[0].file, "P5\n1 1\n65535\n\xff\xff");
    cases[1].file = tga_header(2, 8000, 8000, 32, 0);
    buffer huffman = huffman_table_of_300_codes();
    cases[2].file = make_jpeg(&huffman, 1);
    buffer_free(&huffman);
    const unsigned char one_grey_pixel[] = {0, 128};
    cases[3].file = make_png_raw(100000, 100000, 8, 0, 0, NULL, 0, one_grey_pixel, 2);
    for (int i = 0; i < 4; i++) {
        sandbox_create(&box);
        sandbox_directory(&box, "t");
        char name[64];
        snprintf(name, sizeof name, "t/%s", cases[i].name);
        sandbox_write(&box, name, cases[i].file.data, cases[i].file.length);
        assert_render_refuses(&box, ARGS("--textures", "t", "--size", "8x8", "-o", "x.png"), 10,
                              name, cases[i].needle);
        remove_tree(box.root);
        buffer_free(&cases[i].file);
    }
}

/* The models that hung or crashed Debian's assimp 5.2.5 under luz's
 * fuzzer, which luz now refuses before they can (io/model_guards.c and
 * model_import.c's check_imported), or stops within the limits of the
 * process it reads models in (io/model_sandbox.h): exit status 2, one
 * line. Their
 * files are in tests/fuzz/assimp-findings/ ($FUZZ_FINDINGS); its
 * README.md says what each did. */
static void test_assimp_findings_refused(void **state)
{
    (void)state;
    if (!luz_models_supported()) {
        print_message("skipped: this luz was built without model support (-Dmodels)\n");
        skip();
    }
    const char *findings = getenv("FUZZ_FINDINGS");
    if (findings == NULL) fail_msg("FUZZ_FINDINGS is not set (tests/meson.build sets it)");
    static const struct {
        const char *file, *needle, *alternative;
    } cases[] = {
        {"ply-no-end-header.ply", "a PLY header without its end_header line", NULL},
        {"ply-element-count.ply", "PLY header line 3: expected `element NAME COUNT`", NULL},
        {"ply-triangulate-assert.ply", "assimp's importer gave mesh 0 a face with no corners", NULL},
        {"ply-empty-face.ply", "assimp's importer gave mesh 0 a face with no corners", NULL},
        {"glb-length.glb", "a binary glTF whose header claims 1112 bytes, the file has 417", NULL},
        /* the findings no check keeps out, stopped by the limits assimp
         * runs under in its own process (io/model_sandbox.h): */
        /* a parser that reads past its buffer: what lies there decides
         * what follows (the heap's bytes: meson test sets
         * MALLOC_PERTURB_): a loop, stopped after 10 s of CPU time, or a
         * scene that fails assimp's validation, or under AddressSanitizer
         * its report, which ends the process. Each is one line naming the
         * file, status 2, in bounded time. */
        {"opengex-heap-over-read.glb", "", NULL},
        /* 245 million indices: over 1 GiB (under the sanitizers, which
         * cannot limit memory, over 10 s of CPU time on a slow machine;
         * on a fast one assimp reads them in less and its validation
         * refuses the face) */
#if LUZ_TEST_SANITIZED
        {"ply-slow-list-count.ply", "assimp took more than", "has too many faces"},
#else
        {"ply-slow-list-count.ply", "needs more than 1024 MiB to read it (its memory limit", NULL},
#endif
        /* 4.5 s before assimp refuses it: within the limit, or (under the
         * sanitizers, over 10 s) not */
#if LUZ_TEST_SANITIZED
        {"ply-slow-truncated.ply", "", NULL},
#else
        {"ply-slow-truncated.ply", "the model has zero size", NULL},
#endif
    };
    sandbox box;
    sandbox_create(&box);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", findings, cases[i].file);
        /* generous: the limit is 10 s of CPU time, 30 s on the clock */
        assert_render_refuses_either(
            &box, ARGS("--model", path, "--textures", "none", "-o", "x.png"), 120, path,
            cases[i].needle, cases[i].alternative);
    }
    /* the PLY check reads an element count as a number: one more than
     * the file's bytes is refused, and a header that ends is let through */
    const char header[] = "ply\nformat ascii 1.0\nelement vertex 99999\nproperty float x\n"
                          "end_header\n";
    luz_model model;
    luz_error error = {{0}};
    assert_int_equal(luz_model_load_memory(&model, (const unsigned char *)header,
                                           sizeof header - 1, "big.ply", NULL, &error),
                     LUZ_BAD_INPUT);
    if (strstr(error.message, "big.ply: PLY header line 3: 99999 elements in a file of 70 "
                              "bytes") == NULL)
        fail_msg("%s", error.message);
    remove_tree(box.root);
}

/* ---- the process models are read in (io/model_sandbox.h) ---------------------------------- */

/* What a child of luz_model_run_isolated does instead of assimp's import,
 * for each way a child can end. */
enum child_act { CHILD_SEGV, CHILD_ILL, CHILD_SPIN, CHILD_SLEEP, CHILD_ALLOCATE, CHILD_LIE,
                 CHILD_FLOOD, CHILD_REFUSE, CHILD_EXIT };

/* Where CHILD_ALLOCATE keeps its last block. */
char *volatile kept_block;

static int misbehave(const void *context, uint64_t memory_limit, luz_model_writer *writer,
                     luz_error *error)
{
    (void)memory_limit;
    switch (*(const enum child_act *)context) {
    case CHILD_SEGV: raise(SIGSEGV); break;
    case CHILD_ILL: raise(SIGILL); break;
    case CHILD_SPIN:
        for (volatile unsigned long i = 0;; i++) {}
    case CHILD_SLEEP:
        for (;;) pause();
    case CHILD_ALLOCATE:
        /* until malloc fails: touched, so that it is memory, and kept
         * where the compiler must assume it is used (clang removes a
         * malloc whose block nothing reads) */
        for (;;) {
            char *block = malloc((size_t)16 << 20);
            if (block == NULL) {
                luz_error_set(error, "x.obj: out of memory");
                return LUZ_MACHINE_FAILED;
            }
            memset(block, 1, (size_t)16 << 20);
            kept_block = block;
        }
    case CHILD_LIE: {
        /* a part of a million vertices, and not one of them sent */
        const luz_described_part part = {.vertex_count = 1000000, .triangle_count = 1,
                                         .mesh_name = "", .material_name = "",
                                         .texture_name = "", .embedded = -1};
        luz_model_write_part_start(writer, &part);
        luz_model_write_end(writer, 1, 0);
        return 0;
    }
    case CHILD_FLOOD: {
        static unsigned char zeros[1 << 16];
        for (int i = 0; i < 64; i++) luz_model_write_vertices(writer, (const luz_vertex *)zeros,
                                                              sizeof zeros / sizeof(luz_vertex));
        return 0;
    }
    case CHILD_REFUSE:
        return luz_error_set(error, "x.obj: refused\nwith a second line");
    case CHILD_EXIT:
        _exit(3);
    }
    return 0;
}

static int open_descriptors(void)
{
    int count = 0;
    for (int fd = 0; fd < 1024; fd++) count += fcntl(fd, F_GETFD) != -1;
    return count;
}

/* Every way the child can end is one line naming the file: a crash, the
 * time limit (on the CPU and on the clock), the memory limit, a lying or
 * flooding description, a refusal of its own, a failed exit. Nothing is
 * left behind: no child to reap, no descriptor open. */
static void test_model_child_ends(void **state)
{
    (void)state;
    const int descriptors = open_descriptors();
    static const struct {
        enum child_act act;
        int status;               /* of luz_model_run_isolated, then of reading */
        bool sanitized_too;       /* run under the sanitizers too */
        const char *needle;
    } cases[] = {
        /* the sanitizers catch SIGSEGV and end the process with their report */
        {CHILD_SEGV, LUZ_BAD_INPUT, false, "x.obj: assimp crashed reading it (SIGSEGV, signal 11)"},
        {CHILD_ILL, LUZ_BAD_INPUT, true, "x.obj: assimp crashed reading it (SIGILL, signal 4)"},
        /* 1 s of CPU time, or 3 s on the clock on a busy machine */
        {CHILD_SPIN, LUZ_BAD_INPUT, true, "x.obj: assimp took more than "},
        {CHILD_SLEEP, LUZ_BAD_INPUT, true, "x.obj: assimp took more than 3 s to read it"},
        {CHILD_ALLOCATE, LUZ_BAD_INPUT, false, "x.obj: assimp needs more than 256 MiB to read it"},
        {CHILD_LIE, LUZ_BAD_INPUT, true,
         "x.obj: assimp's process sent a description luz cannot read"},
        {CHILD_FLOOD, LUZ_BAD_INPUT, true, "x.obj: assimp's process sent more than 1 MiB"},
        {CHILD_REFUSE, LUZ_BAD_INPUT, true, "x.obj: refused?with a second line"},
        {CHILD_EXIT, LUZ_BAD_INPUT, true,
         "x.obj: assimp failed reading it (its process exited with status 3)"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (LUZ_TEST_SANITIZED && !cases[i].sanitized_too) continue;
        /* small limits, so that the test is quick */
        const luz_model_limits limits = {.cpu_seconds = 1.0, .wall_seconds = 3.0,
                                         .memory_bytes = LUZ_TEST_SANITIZED ? 0 : (uint64_t)256 << 20,
                                         .description_bytes = (uint64_t)1 << 20};
        unsigned char *bytes = NULL;
        size_t size = 0;
        luz_error error = {{0}};
        int status = luz_model_run_isolated("x.obj", &limits, misbehave, &cases[i].act, &bytes,
                                            &size, &error);
        if (status == 0) {
            luz_model_description description;
            status = luz_model_description_read(bytes, size, "x.obj", &description, &error);
            if (status == 0 && description.refusal != 0) {
                status = description.refusal;
                luz_error_set(&error, "%s", description.refusal_message);
            }
            if (status == 0) luz_model_description_free(&description);
            free(bytes);
        }
        if (status != cases[i].status || strstr(error.message, cases[i].needle) == NULL ||
            strchr(error.message, '\n') != NULL)
            fail_msg("case %zu: status %d, '%s'; expected %d, '%s'", i, status, error.message,
                     cases[i].status, cases[i].needle);
    }
    errno = 0;
    assert_int_equal(waitpid(-1, NULL, WNOHANG), -1);   /* no child left, not even a zombie */
    assert_int_equal(errno, ECHILD);
    assert_int_equal(open_descriptors(), descriptors);
}

/* ---- the confinement of that process (io/model_confine.h) ---------------------------------- */

/* What a child of luz_model_run_isolated tries in place of assimp's
 * import, under the confinement a model at `model` gets; what came of it
 * is sent back as its refusal ("errno N", or the bytes read). */
enum confined_act { READ_BESIDE, READ_OUTSIDE, READ_ROOT_FILE, WRITE_BESIDE, WRITE_OUTSIDE,
                    OPEN_SOCKET, RUN_PROGRAM, FORK };

typedef struct confined_try {
    enum confined_act act;
    const char *path;        /* the file it reads or writes */
} confined_try;

static int try_confined(const void *context, uint64_t memory_limit, luz_model_writer *writer,
                        luz_error *error)
{
    (void)memory_limit;
    (void)writer;
    const confined_try *attempt = context;
    int result = -1;
    switch (attempt->act) {
    case READ_BESIDE:
    case READ_OUTSIDE:
    case READ_ROOT_FILE: {
        int descriptor = open(attempt->path, O_RDONLY | O_CLOEXEC);
        if (descriptor >= 0) {
            char text[64] = "";
            ssize_t got = read(descriptor, text, sizeof text - 1);
            close(descriptor);
            return luz_error_set(error, "read %zd bytes: %s", got, got > 0 ? text : "");
        }
        break;
    }
    case WRITE_BESIDE:
    case WRITE_OUTSIDE:
        result = open(attempt->path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (result >= 0) {
            (void)!write(result, "written", 7);
            close(result);
            return luz_error_set(error, "wrote the file");
        }
        break;
    case OPEN_SOCKET:
        result = socket(AF_INET, SOCK_STREAM, 0);
        if (result >= 0) return luz_error_set(error, "opened a socket");
        break;
    case RUN_PROGRAM: {
        char *const arguments[] = {"/bin/true", NULL};
        execv("/bin/true", arguments);
        break;
    }
    case FORK: {
        pid_t child = fork();
        if (child == 0) _exit(0);
        if (child > 0) {
            waitpid(child, NULL, 0);
            return luz_error_set(error, "forked");
        }
        break;
    }
    }
    return luz_error_set(error, "errno %d", errno);
}

/* The child that reads a model reads files beside it (the folder and
 * below), and nothing else: a file in a folder next to it, or /etc/passwd,
 * cannot be opened (Landlock: EACCES); no file can be written, beside it
 * or elsewhere (seccomp: EPERM, or Landlock: EACCES), and none appears;
 * a socket, a program run or a fork kills it (SIGSYS), which luz reports
 * as one line naming the model. Where the kernel lacks a mechanism, the
 * cases it holds are skipped with a note. */
static void test_model_child_confined(void **state)
{
    (void)state;
    const luz_confinement available = luz_confinement_available();
    char root[1024], model[1200], beside[1200], outside[1200], written[1200],
        written_outside[1200];
    make_temporary_directory(root, sizeof root);
    snprintf(model, sizeof model, "%s/models/m.obj", root);
    snprintf(beside, sizeof beside, "%s/models/sub/beside.txt", root);
    snprintf(outside, sizeof outside, "%s/other/secret.txt", root);
    snprintf(written, sizeof written, "%s/models/new.txt", root);
    snprintf(written_outside, sizeof written_outside, "%s/other/new.txt", root);
    char folder[1200];
    snprintf(folder, sizeof folder, "%s/models", root);
    assert_int_equal(mkdir(folder, 0755), 0);
    snprintf(folder, sizeof folder, "%s/models/sub", root);
    assert_int_equal(mkdir(folder, 0755), 0);
    snprintf(folder, sizeof folder, "%s/other", root);
    assert_int_equal(mkdir(folder, 0755), 0);
    write_text_file(model, "v 0 0 0\n");
    write_text_file(beside, "beside");
    write_text_file(outside, "secret");

    static const char eacces[] = "errno 13", eperm[] = "errno 1";
    const struct {
        enum confined_act act;
        const char *path;
        bool needs_landlock, needs_seccomp;
        const char *expected, *or_expected;   /* the refusal's message, or the crash's */
    } cases[] = {
        {READ_BESIDE, beside, false, false, "read 6 bytes: beside", NULL},
        {READ_OUTSIDE, outside, true, false, eacces, NULL},
        {READ_ROOT_FILE, "/etc/passwd", true, false, eacces, NULL},
        {WRITE_BESIDE, written, false, true, eperm, eacces},
        {WRITE_OUTSIDE, written_outside, false, true, eperm, eacces},
        {OPEN_SOCKET, NULL, false, true, "SIGSYS", NULL},
        {RUN_PROGRAM, NULL, false, true, "SIGSYS", NULL},
        {FORK, NULL, false, true, "SIGSYS", NULL},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if ((cases[i].needs_landlock && available.landlock_abi == 0) ||
            (cases[i].needs_seccomp && !available.seccomp)) {
            print_message("skipped case %zu: this kernel has no %s\n", i,
                          cases[i].needs_landlock ? "Landlock" : "seccomp filter");
            continue;
        }
        const luz_model_limits limits = {.cpu_seconds = 5.0, .wall_seconds = 20.0,
                                         .description_bytes = (uint64_t)1 << 20};
        const confined_try attempt = {.act = cases[i].act, .path = cases[i].path};
        unsigned char *bytes = NULL;
        size_t size = 0;
        luz_error error = {{0}};
        int status = luz_model_run_isolated(model, &limits, try_confined, &attempt, &bytes, &size,
                                            &error);
        if (status == 0) {
            luz_model_description description;
            assert_int_equal(luz_model_description_read(bytes, size, model, &description, &error),
                             0);
            assert_int_not_equal(description.refusal, 0);
            luz_error_set(&error, "%s", description.refusal_message);
            free(bytes);
        }
        const bool as_expected =
            strstr(error.message, cases[i].expected) != NULL ||
            (cases[i].or_expected != NULL && strstr(error.message, cases[i].or_expected) != NULL);
        if (!as_expected || strchr(error.message, '\n') != NULL)
            fail_msg("case %zu: '%s', expected '%s'", i, error.message, cases[i].expected);
        if (strcmp(cases[i].expected, "SIGSYS") == 0) {
            /* a crash of the child, reported naming the model */
            assert_int_equal(status, LUZ_BAD_INPUT);
            assert_true(strncmp(error.message, model, strlen(model)) == 0);
        }
    }
    /* nothing was written, beside the model or elsewhere */
    assert_int_equal(access(written, F_OK), -1);
    assert_int_equal(access(written_outside, F_OK), -1);
    remove_tree(root);
}

/* luz_model_load through its child, a sound model and a refused one:
 * no zombie, no descriptor left open. luz's process holds 4 GiB of
 * address space first (as it may, with a gigabyte of textures and other
 * models): the child's memory limit is on top of that. */
static void test_model_load_leaves_nothing(void **state)
{
    (void)state;
    if (!luz_models_supported()) {
        print_message("skipped: this luz was built without model support (-Dmodels)\n");
        skip();
    }
    sandbox box;
    sandbox_create(&box);
    sandbox_text(&box, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    sandbox_text(&box, "bad.obj", "v 0 0 0\nf 1 2 9\n");
    /* (MAP_ANONYMOUS is not POSIX: /dev/zero, private, is the same) */
    int zero = open("/dev/zero", O_RDONLY | O_CLOEXEC);
    assert_true(zero >= 0);
    void *held = mmap(NULL, (size_t)4 << 30, PROT_NONE, MAP_PRIVATE, zero, 0);
    close(zero);
    assert_true(held != MAP_FAILED);
    const int descriptors = open_descriptors();
    char path[600];
    luz_model model;
    luz_error error = {{0}};
    sandbox_path(&box, "m.obj", path, sizeof path);
    if (luz_model_load(&model, path, NULL, &error) != 0) fail_msg("%s", error.message);
    assert_int_equal(model.part_count, 1);
    assert_int_equal(model.triangle_count, 1);
    luz_model_free(&model);
    sandbox_path(&box, "bad.obj", path, sizeof path);
    assert_int_equal(luz_model_load(&model, path, NULL, &error), LUZ_BAD_INPUT);
    assert_non_null(strstr(error.message, "bad.obj: "));
    errno = 0;
    assert_int_equal(waitpid(-1, NULL, WNOHANG), -1);
    assert_int_equal(errno, ECHILD);
    assert_int_equal(open_descriptors(), descriptors);
    munmap(held, (size_t)4 << 30);
    remove_tree(box.root);
}

/* A black RGBA PNG of width x height: rows of a filter byte 0 and 4 zero
 * bytes a pixel, deflated as zlib_zeros does (1.7 MB for 8192 x 8192). */
static buffer black_png(uint32_t width, uint32_t height)
{
    buffer zlib = zlib_zeros((uint64_t)height * (1 + (uint64_t)width * 4));
    buffer png = make_png(width, height, 8, 6, 0, NULL, 0, &zlib);
    buffer_free(&zlib);
    return png;
}

/* The run's textures share one budget of 1024 MiB. An 8192 x 6144
 * texture's chain is 8192 x 6144 x 4 bytes times (1 - 4^-12) / (3/4) over
 * its first 12 levels, 268435440 bytes, and 8 + 4 for its 2x1 and 1x1
 * levels: 256.0 MiB. Three of them (a, b, c) take 768.0 MiB; d.png, of
 * 8192 x 8192, would take 4 (4^14 - 1) / 3 bytes, 341.3 MiB, more than
 * the 256 MiB left, and is refused before it is decoded. (The six
 * 8192 x 8192 PNGs took 2.4 GB.) */
static void test_budget_through_luz_render(void **state)
{
    (void)state;
    /* Decoding is done on one thread: ThreadSanitizer has nothing to see
     * in it, and makes its 576 MB of pixels take minutes. The plain build
     * and AddressSanitizer's run it. */
#if defined(__SANITIZE_THREAD__)
    print_message("skipped: a ThreadSanitizer build (decoding is single-threaded)\n");
    skip();
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
    print_message("skipped: a ThreadSanitizer build (decoding is single-threaded)\n");
    skip();
#endif
#endif
    assert_int_equal(luz_texture_bytes(8192, 6144), sizeof(luz_texture) + 268435452u);
    sandbox box;
    sandbox_create(&box);
    sandbox_directory(&box, "big");
    buffer png = black_png(8192, 6144);
    sandbox_write(&box, "big/a.png", png.data, png.length);
    sandbox_write(&box, "big/b.png", png.data, png.length);
    sandbox_write(&box, "big/c.png", png.data, png.length);
    buffer_free(&png);
    /* d.png's data is one byte short of a row: had it been decoded, it
     * would be refused as corrupt, not over the budget */
    buffer zlib = zlib_zeros(1);
    png = make_png(8192, 8192, 8, 6, 0, NULL, 0, &zlib);
    buffer_free(&zlib);
    sandbox_write(&box, "big/d.png", png.data, png.length);
    buffer_free(&png);
    assert_render_refuses(&box, ARGS("--textures", "big", "--size", "8x8", "-o", "x.png"), 240,
                          "big/d.png: a 8192x8192 texture takes 341.3 MiB, and the textures "
                          "before it 768.0 MiB: over luz's budget of 1024 MiB", NULL);
    remove_tree(box.root);
}

/* Out of memory while decoding is the machine's failure: status 1 and
 * "out of memory", not a corrupt image. An address space of 200 MB runs
 * luz-render (about 100 MB) but not a 256 MB image. The sanitizers
 * reserve terabytes of address space for their shadow memory, so there the
 * limit cannot be used. */
static void test_out_of_memory_while_decoding(void **state)
{
    (void)state;
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
    print_message("skipped: a sanitizer build cannot run under a limit on the address space\n");
    skip();
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
    print_message("skipped: a sanitizer build cannot run under a limit on the address space\n");
    skip();
#endif
#endif
    sandbox box;
    sandbox_create(&box);
    sandbox_directory(&box, "big");
    buffer png = black_png(8192, 8192);
    sandbox_write(&box, "big/a.png", png.data, png.length);
    buffer_free(&png);
    run_result result = run_render(box.root, box.work,
                                   ARGS("--textures", "big", "--size", "8x8", "--threads", "1",
                                        "-o", "x.png"),
                                   60, (rlim_t)200 << 20);
    if (result.status != 1 || strstr(result.err, "big/a.png: out of memory") == NULL ||
        strchr(result.err, '\n')[1] != '\0')
        fail_msg("exit status %d, expected 1 with one line 'big/a.png: out of memory'; stderr: %s",
                 result.status, result.err);
    char path[600];
    sandbox_path(&box, "x.png", path, sizeof path);
    assert_int_equal(access(path, F_OK), -1);
    free(result.err);
    remove_tree(box.root);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_png_from_another_encoder),
        cmocka_unit_test(test_png_with_a_palette),
        cmocka_unit_test(test_png_with_empty_first_idat),
        cmocka_unit_test(test_png_pixels_as_stb_gave_them),
        cmocka_unit_test(test_bmp),
        cmocka_unit_test(test_tga),
        cmocka_unit_test(test_jpeg),
        cmocka_unit_test(test_misnamed_files_refused),
        cmocka_unit_test(test_png_refusals),
        cmocka_unit_test(test_bmp_refusals),
        cmocka_unit_test(test_tga_refusals),
        cmocka_unit_test(test_jpeg_refusals),
        cmocka_unit_test(test_budget),
        cmocka_unit_test(test_input_files),
        cmocka_unit_test(test_scene_text),
        cmocka_unit_test(test_fifos_never_block),
        cmocka_unit_test(test_crafted_textures),
        cmocka_unit_test(test_unreadable_textures),
        cmocka_unit_test(test_assimp_findings_refused),
        cmocka_unit_test(test_model_child_ends),
        cmocka_unit_test(test_model_child_confined),
        cmocka_unit_test(test_model_load_leaves_nothing),
        cmocka_unit_test(test_budget_through_luz_render),
        cmocka_unit_test(test_out_of_memory_while_decoding),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
