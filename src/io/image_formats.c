/*
 * image_formats.c: the checks an image file passes before it is decoded.
 *
 * In:  the bytes of an image file and the format its name (or an embedded
 *      texture's hint) says it is.
 * Out: its width and height, once its signature, its header and its
 *      structure are known to be sound; else one line saying what is not.
 *
 * The decoders (stb_image for PNG, BMP and TGA, libjpeg-turbo for JPEG;
 * image_decode.c) are large and were written to be fast, not to distrust
 * their input: stb_image 2.27 reads past the end of a buffer as zeros,
 * fills the pixels a short file lacks with whatever memory held, and
 * believes a header's size. So everything that can be known without
 * decoding a pixel is checked here, in plain code that reads a byte only
 * after checking that it is there:
 *
 *  - PNG (PNG specification, 3rd edition, sections 5 and 11): the
 *    signature, IHDR first with a valid depth and colour type, every
 *    chunk inside the file up to IEND, no critical chunk luz does not
 *    know, and the exact size the image data must inflate to, which the
 *    decoder then holds the zlib stream to (a "zlib bomb" of a few
 *    kilobytes could otherwise inflate to gigabytes).
 *  - JPEG (ITU T.81, annex B): SOI, then every marker segment and every
 *    scan's entropy-coded data inside the file up to EOI, a frame header
 *    (SOF) before the first scan, and at most LUZ_JPEG_MAX_SCANS scans.
 *  - BMP (Microsoft's BITMAPINFOHEADER and its V4, V5 successors): the
 *    variants stb_image decodes (1, 4, 8, 16, 24, 32 bits; no RLE), the
 *    pixel rows inside the file, and for 1, 4 and 8 bits every pixel's
 *    index inside the palette (stb_image would read a stack array past
 *    its entries).
 *  - TGA (Truevision TGA 2.0): no signature, so every header field must
 *    be one stb_image accepts; the pixels inside the file, run-length
 *    packets walked one by one.
 */
#include "io/image_formats.h"

#include <stdbool.h>
#include <string.h>
#include <strings.h>

#include "io/input_file.h"
#include "luz/texture.h"

/* ---- names and signatures ------------------------------------------------------------ */

luz_image_format luz_image_format_of_hint(const char *hint)
{
    static const struct {
        const char *hint;
        luz_image_format format;
    } hints[] = {{"png", LUZ_IMAGE_PNG}, {"jpg", LUZ_IMAGE_JPEG}, {"jpeg", LUZ_IMAGE_JPEG},
                 {"bmp", LUZ_IMAGE_BMP}, {"tga", LUZ_IMAGE_TGA}};
    for (size_t i = 0; i < sizeof hints / sizeof hints[0]; i++)
        if (strcasecmp(hint, hints[i].hint) == 0) return hints[i].format;
    return LUZ_IMAGE_UNKNOWN;
}

luz_image_format luz_image_format_of_name(const char *name)
{
    const char *dot = strrchr(name, '.');
    const char *slash = strrchr(name, '/');
    if (dot == NULL || (slash != NULL && dot < slash)) return LUZ_IMAGE_UNKNOWN;
    return luz_image_format_of_hint(dot + 1);
}

static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

static bool starts_with(const unsigned char *bytes, size_t size, const void *prefix,
                        size_t length)
{
    return size >= length && memcmp(bytes, prefix, length) == 0;
}

luz_image_format luz_image_format_of_signature(const unsigned char *bytes, size_t size)
{
    if (starts_with(bytes, size, png_signature, 8)) return LUZ_IMAGE_PNG;
    if (starts_with(bytes, size, "\xff\xd8\xff", 3)) return LUZ_IMAGE_JPEG;
    if (starts_with(bytes, size, "BM", 2)) return LUZ_IMAGE_BMP;
    return LUZ_IMAGE_UNKNOWN;
}

const char *luz_image_format_name(luz_image_format format)
{
    switch (format) {
    case LUZ_IMAGE_PNG: return "PNG";
    case LUZ_IMAGE_JPEG: return "JPEG";
    case LUZ_IMAGE_BMP: return "BMP";
    case LUZ_IMAGE_TGA: return "TGA";
    default: return "unknown";
    }
}

/* What the bytes are when they are not what the name says: the four
 * formats, and the others a misnamed file most often is, so that the
 * message can say "a GIF image" rather than only "not a PNG file". */
static const char *what_bytes_are(const unsigned char *bytes, size_t size)
{
    switch (luz_image_format_of_signature(bytes, size)) {
    case LUZ_IMAGE_PNG: return "a PNG image";
    case LUZ_IMAGE_JPEG: return "a JPEG image";
    case LUZ_IMAGE_BMP: return "a BMP image";
    default: break;
    }
    if (starts_with(bytes, size, "GIF8", 4)) return "a GIF image";
    if (starts_with(bytes, size, "8BPS", 4)) return "a Photoshop image";
    if (starts_with(bytes, size, "#?RADIANCE", 10) || starts_with(bytes, size, "#?RGBE", 6))
        return "a Radiance HDR image";
    if (starts_with(bytes, size, "DDS ", 4)) return "a DDS texture";
    if (starts_with(bytes, size, "II*\0", 4) || starts_with(bytes, size, "MM\0*", 4))
        return "a TIFF image";
    if (size >= 12 && memcmp(bytes, "RIFF", 4) == 0 && memcmp(bytes + 8, "WEBP", 4) == 0)
        return "a WebP image";
    if (size >= 3 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '7' &&
        (bytes[2] == ' ' || bytes[2] == '\t' || bytes[2] == '\n' || bytes[2] == '\r'))
        return "a PNM image (PBM, PGM, PPM or PAM)";
    return NULL;
}

static int not_this_format(const unsigned char *bytes, size_t size, luz_image_format format,
                           const char *name, luz_error *error)
{
    const char *what = what_bytes_are(bytes, size);
    if (what != NULL)
        luz_error_set(error, "%s: not a %s file but, by its first bytes, %s (luz reads PNG, "
                             "JPEG, BMP and TGA files named for their format)",
                      name, luz_image_format_name(format), what);
    else
        luz_error_set(error, "%s: not a %s file (its first bytes are not the %s signature)",
                      name, luz_image_format_name(format), luz_image_format_name(format));
    return LUZ_BAD_INPUT;
}

static int check_size(int width, int height, const char *name, luz_error *error)
{
    if (width < 1 || height < 1 || width > LUZ_TEXTURE_MAX_SIZE || height > LUZ_TEXTURE_MAX_SIZE) {
        luz_error_set(error, "%s: image is %dx%d, expected 1x1 to %dx%d", name, width, height,
                      LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
        return LUZ_BAD_INPUT;
    }
    return 0;
}

static uint32_t big_endian_32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static unsigned big_endian_16(const unsigned char *p)
{
    return (unsigned)p[0] << 8 | p[1];
}

static uint32_t little_endian_32(const unsigned char *p)
{
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

static unsigned little_endian_16(const unsigned char *p)
{
    return (unsigned)p[1] << 8 | p[0];
}

/* ---- PNG ----------------------------------------------------------------------------- */

/* Bytes of one row of `width` pixels of `bits` bits, with its filter byte. */
static uint64_t png_row_bytes(uint64_t width, unsigned bits)
{
    return 1 + (width * bits + 7) / 8;
}

/* The image data's size once inflated: every row with its filter byte; an
 * interlaced image (Adam7) is seven reduced images, each with its own rows,
 * and a pass with no pixel has no rows at all (PNG specification 8.2). */
static uint64_t png_inflated_size(uint32_t width, uint32_t height, unsigned bits, bool interlaced)
{
    if (!interlaced) return (uint64_t)height * png_row_bytes(width, bits);
    static const unsigned x0[7] = {0, 4, 0, 2, 0, 1, 0}, y0[7] = {0, 0, 4, 0, 2, 0, 1};
    static const unsigned dx[7] = {8, 8, 4, 4, 2, 2, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
    uint64_t total = 0;
    for (int pass = 0; pass < 7; pass++) {
        uint64_t w = width > x0[pass] ? (width - x0[pass] + dx[pass] - 1) / dx[pass] : 0;
        uint64_t h = height > y0[pass] ? (height - y0[pass] + dy[pass] - 1) / dy[pass] : 0;
        if (w > 0 && h > 0) total += h * png_row_bytes(w, bits);
    }
    return total;
}

static bool png_depth_valid(unsigned colour, unsigned depth)
{
    switch (colour) {
    case 0: return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3: return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2: case 4: case 6: return depth == 8 || depth == 16;
    default: return false;
    }
}

static int check_png(const unsigned char *bytes, size_t size, const char *name,
                     luz_image_header *header, luz_error *error)
{
    size_t position = 8;
    bool seen_header = false, seen_palette = false, seen_data = false, data_ended = false;
    unsigned colour = 0;
    for (;;) {
        if (size - position < 12)
            return luz_error_set(error, "%s: truncated PNG (it ends at byte %zu, inside a chunk "
                                        "or before IEND)", name, size);
        const uint32_t length = big_endian_32(bytes + position);
        const unsigned char *type = bytes + position + 4;
        char type_text[5] = {0};
        for (int k = 0; k < 4; k++) {
            const unsigned char c = type[k];
            if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z')))
                return luz_error_set(error, "%s: corrupt PNG (a chunk at byte %zu has a type "
                                            "that is not four letters)", name, position);
            type_text[k] = (char)c;
        }
        if (length > 0x7fffffffu || length > size - position - 12)
            return luz_error_set(error, "%s: truncated PNG (chunk %s at byte %zu claims %u "
                                        "bytes, the file has %zu after it)",
                                 name, type_text, position, (unsigned)length,
                                 size - position - 12);
        const unsigned char *data = bytes + position + 8;
        const bool is_header = memcmp(type, "IHDR", 4) == 0;
        if (seen_header == is_header)
            return luz_error_set(error, "%s: corrupt PNG (expected IHDR first and only once, "
                                        "got chunk %s at byte %zu)", name, type_text, position);
        if (is_header) {
            seen_header = true;
            if (length != 13)
                return luz_error_set(error, "%s: corrupt PNG (IHDR of %u bytes, expected 13)",
                                     name, (unsigned)length);
            const uint32_t width = big_endian_32(data), height = big_endian_32(data + 4);
            if (width > (uint32_t)LUZ_TEXTURE_MAX_SIZE || height > (uint32_t)LUZ_TEXTURE_MAX_SIZE ||
                width == 0 || height == 0)
                return luz_error_set(error, "%s: image is %ux%u, expected 1x1 to %dx%d", name,
                                     (unsigned)width, (unsigned)height, LUZ_TEXTURE_MAX_SIZE,
                                     LUZ_TEXTURE_MAX_SIZE);
            const unsigned depth = data[8];
            colour = data[9];
            if (!png_depth_valid(colour, depth))
                return luz_error_set(error, "%s: corrupt PNG (colour type %u with bit depth %u)",
                                     name, colour, depth);
            if (data[10] != 0 || data[11] != 0 || data[12] > 1)
                return luz_error_set(error, "%s: corrupt PNG (compression %u, filter %u, "
                                            "interlace %u; expected 0, 0, 0 or 1)",
                                     name, data[10], data[11], data[12]);
            static const unsigned channels[7] = {1, 0, 3, 1, 2, 0, 4};
            header->width = (int)width;
            header->height = (int)height;
            header->png_colour_type = colour;
            header->png_depth = depth;
            header->png_interlaced = data[12] == 1;
            header->png_inflated_bytes =
                png_inflated_size(width, height, depth * channels[colour], data[12] == 1);
        } else if (memcmp(type, "IDAT", 4) == 0) {
            /* the image data is one stream cut into consecutive chunks */
            if (data_ended)
                return luz_error_set(error, "%s: corrupt PNG (IDAT chunks not consecutive)",
                                     name);
            if (colour == 3 && !seen_palette)
                return luz_error_set(error, "%s: corrupt PNG (an image with a palette, and no "
                                            "PLTE before its IDAT)", name);
            seen_data = true;
        } else if (memcmp(type, "PLTE", 4) == 0) {
            if (seen_data || length == 0 || length % 3 != 0 || length > 256 * 3)
                return luz_error_set(error, "%s: corrupt PNG (a PLTE chunk of %u bytes%s)",
                                     name, (unsigned)length, seen_data ? " after IDAT" : "");
            seen_palette = true;
            header->png_palette_entries = length / 3;
        } else if (memcmp(type, "IEND", 4) == 0) {
            if (!seen_data)
                return luz_error_set(error, "%s: corrupt PNG (no IDAT chunk)", name);
            break;
        } else if (type[0] >= 'A' && type[0] <= 'Z') {
            /* critical (bit 5 of the first byte clear): a decoder must
             * understand it, and luz's does not */
            return luz_error_set(error, "%s: unsupported PNG (critical chunk %s)", name,
                                 type_text);
        }
        if (seen_data && memcmp(type, "IDAT", 4) != 0) data_ended = true;
        position += 12 + (size_t)length;
    }
    return 0;
}

/* ---- JPEG ---------------------------------------------------------------------------- */

static int check_jpeg(const unsigned char *bytes, size_t size, const char *name,
                      luz_image_header *header, luz_error *error)
{
    size_t position = 2;   /* after SOI */
    bool seen_frame = false;
    int scans = 0;
    for (;;) {
        if (position >= size)
            return luz_error_set(error, "%s: truncated JPEG (it ends at byte %zu, before its "
                                        "EOI marker)", name, size);
        if (bytes[position] != 0xff)
            return luz_error_set(error, "%s: corrupt JPEG (expected a marker at byte %zu)", name,
                                 position);
        while (position < size && bytes[position] == 0xff) position++;   /* fill bytes */
        if (position >= size) continue;
        const unsigned marker = bytes[position++];
        if (marker == 0xd9) break;                                      /* EOI */
        if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd7)) continue;   /* no length */
        if (marker == 0x00 || marker == 0xd8)
            return luz_error_set(error, "%s: corrupt JPEG (marker %02X at byte %zu)", name,
                                 marker, position - 1);
        if (size - position < 2 || big_endian_16(bytes + position) < 2 ||
            big_endian_16(bytes + position) > size - position)
            return luz_error_set(error, "%s: truncated JPEG (the segment of marker %02X at byte "
                                        "%zu runs past the end)", name, marker, position - 1);
        const size_t length = big_endian_16(bytes + position);
        /* SOF0 to SOF15 but DHT (C4), JPG (C8) and DAC (CC): the frame,
         * whose header gives the size (T.81, B.2.2) */
        if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 &&
            marker != 0xcc && !seen_frame) {
            if (length < 8)
                return luz_error_set(error, "%s: corrupt JPEG (a frame header of %zu bytes)",
                                     name, length);
            seen_frame = true;
            header->height = (int)big_endian_16(bytes + position + 3);
            header->width = (int)big_endian_16(bytes + position + 5);
            if (header->height == 0)
                return luz_error_set(error, "%s: unsupported JPEG (its height comes after the "
                                            "first scan, in a DNL marker)", name);
            if (check_size(header->width, header->height, name, error) != 0)
                return LUZ_BAD_INPUT;
        }
        position += length;
        if (marker != 0xda) continue;

        /* SOS: a scan, then its entropy-coded data up to the next marker
         * that is neither a stuffed 0xFF (FF 00) nor a restart (FF D0 to
         * FF D7) (T.81, B.1.1.5). */
        if (!seen_frame)
            return luz_error_set(error, "%s: corrupt JPEG (a scan before the frame header)",
                                 name);
        if (++scans > LUZ_JPEG_MAX_SCANS)
            return luz_error_set(error, "%s: JPEG with more than %d scans, expected at most "
                                        "that (each costs a pass over the whole image)",
                                 name, LUZ_JPEG_MAX_SCANS);
        while (position < size) {
            if (bytes[position] != 0xff) {
                position++;
                continue;
            }
            if (position + 1 >= size) {
                position = size;
                break;
            }
            const unsigned next = bytes[position + 1];
            if (next == 0x00 || (next >= 0xd0 && next <= 0xd7)) {
                position += 2;
                continue;
            }
            break;
        }
    }
    if (!seen_frame || scans == 0)
        return luz_error_set(error, "%s: corrupt JPEG (no %s before EOI)", name,
                             seen_frame ? "scan" : "frame header");
    return 0;
}

/* ---- BMP ----------------------------------------------------------------------------- */

/* The largest palette index of 1-, 4- or 8-bit rows: every pixel read as
 * stb_image reads it (rows padded to 4 bytes, the high bits first). */
static unsigned bmp_largest_index(const unsigned char *pixels, int width, int rows, int bits,
                                  size_t stride)
{
    unsigned largest = 0;
    const unsigned mask = (1u << bits) - 1;
    for (int y = 0; y < rows; y++) {
        const unsigned char *row = pixels + (size_t)y * stride;
        for (int x = 0; x < width; x++) {
            const size_t bit = (size_t)x * (size_t)bits;
            const unsigned index = (row[bit / 8] >> (8 - bits - bit % 8)) & mask;
            if (index > largest) largest = index;
        }
    }
    return largest;
}

static int check_bmp(const unsigned char *bytes, size_t size, const char *name,
                     luz_image_header *header, luz_error *error)
{
    if (size < 18)
        return luz_error_set(error, "%s: truncated BMP (%zu bytes, shorter than its header)",
                             name, size);
    const uint32_t offset = little_endian_32(bytes + 10);
    const uint32_t header_size = little_endian_32(bytes + 14);
    if (header_size == 12)
        return luz_error_set(error, "%s: unsupported BMP (an OS/2 1.x bitmap; expected a "
                                    "Windows BMP, BITMAPINFOHEADER or later)", name);
    if (header_size != 40 && header_size != 56 && header_size != 108 && header_size != 124)
        return luz_error_set(error, "%s: corrupt or unsupported BMP (an info header of %u "
                                    "bytes; expected 40, 56, 108 or 124)",
                             name, (unsigned)header_size);
    if (size < 14 + (size_t)header_size)
        return luz_error_set(error, "%s: truncated BMP (%zu bytes, shorter than its header)",
                             name, size);
    const int32_t width = (int32_t)little_endian_32(bytes + 18);
    const int32_t signed_height = (int32_t)little_endian_32(bytes + 22);
    /* a negative height: rows top-down */
    const int64_t height = signed_height < 0 ? -(int64_t)signed_height : signed_height;
    if (width < 1 || height < 1 || width > LUZ_TEXTURE_MAX_SIZE || height > LUZ_TEXTURE_MAX_SIZE)
        return luz_error_set(error, "%s: image is %dx%lld, expected 1x1 to %dx%d", name,
                             (int)width, (long long)height, LUZ_TEXTURE_MAX_SIZE,
                             LUZ_TEXTURE_MAX_SIZE);
    const unsigned planes = little_endian_16(bytes + 26), bits = little_endian_16(bytes + 28);
    const uint32_t compression = little_endian_32(bytes + 30);
    if (planes != 1 || (bits != 1 && bits != 4 && bits != 8 && bits != 16 && bits != 24 &&
                        bits != 32))
        return luz_error_set(error, "%s: corrupt BMP (%u planes of %u bits; expected 1 plane of "
                                    "1, 4, 8, 16, 24 or 32)", name, planes, bits);
    /* 0 is BI_RGB; 3 is BI_BITFIELDS, masks for 16 or 32 bits. stb_image
     * decodes no other: RLE (1, 2), JPEG or PNG inside (4, 5). */
    if (compression != 0 && !(compression == 3 && (bits == 16 || bits == 32)))
        return luz_error_set(error, "%s: unsupported BMP (compression %u with %u bits; luz "
                                    "reads uncompressed BMPs)", name, (unsigned)compression,
                             bits);
    /* what stb_image reads before the pixels: the 14-byte file header, the
     * info header, the three masks after a 40- or 56-byte header with
     * BI_BITFIELDS, the palette (of 4-byte entries) for 8 bits or fewer */
    const size_t masks = (header_size == 40 || header_size == 56) && compression == 3 ? 12 : 0;
    const size_t before_pixels = 14 + (size_t)header_size + masks;
    size_t palette_entries = 0;
    if (bits <= 8) {
        if (offset < before_pixels + 4 || (offset - before_pixels) / 4 > 256)
            return luz_error_set(error, "%s: corrupt BMP (its pixels at byte %u leave room for "
                                        "%lld palette entries, expected 1 to 256)",
                                 name, (unsigned)offset,
                                 ((long long)offset - (long long)before_pixels) / 4);
        palette_entries = (offset - before_pixels) / 4;
    } else if (offset < before_pixels) {
        return luz_error_set(error, "%s: corrupt BMP (its pixels at byte %u, inside its headers)",
                             name, (unsigned)offset);
    }
    const size_t stride = (((size_t)width * bits + 31) / 32) * 4;
    if (offset > size || (size - offset) / stride < (size_t)height)
        return luz_error_set(error, "%s: truncated BMP (%lld rows of %zu bytes from byte %u, "
                                    "the file has %zu bytes)",
                             name, (long long)height, stride, (unsigned)offset, size);
    if (bits <= 8) {
        const unsigned largest =
            bmp_largest_index(bytes + offset, (int)width, (int)height, (int)bits, stride);
        if (largest >= palette_entries)
            return luz_error_set(error, "%s: corrupt BMP (a pixel of colour %u, the palette has "
                                        "%zu)", name, largest, palette_entries);
    }
    header->width = (int)width;
    header->height = (int)height;
    return 0;
}

/* ---- TGA ----------------------------------------------------------------------------- */

static int check_tga(const unsigned char *bytes, size_t size, const char *name,
                     luz_image_header *header, luz_error *error)
{
    /* Truevision TGA 2.0, the 18-byte header */
    if (size < 18)
        return luz_error_set(error, "%s: not a TGA file (%zu bytes, shorter than its header)",
                             name, size);
    const unsigned id_length = bytes[0], colour_map_type = bytes[1], image_type = bytes[2];
    const unsigned map_first = little_endian_16(bytes + 3), map_length = little_endian_16(bytes + 5);
    const unsigned map_bits = bytes[7];
    const int width = (int)little_endian_16(bytes + 12), height = (int)little_endian_16(bytes + 14);
    const unsigned bits = bytes[16], descriptor = bytes[17];
    const bool indexed = colour_map_type == 1;
    const unsigned type = image_type & 7;
    const bool run_length = image_type >= 8;
    /* the kinds stb_image decodes: colour-mapped (1, and 9 run-length)
     * with 8- or 16-bit indices into 15-, 16-, 24- or 32-bit entries (or
     * 8-bit grey); true colour (2, 10) and grey (3, 11) of 8, 15, 16, 24
     * or 32 bits */
    bool valid = colour_map_type <= 1 && (image_type == type || image_type == type + 8) &&
                 (indexed ? type == 1 : type == 2 || type == 3) && (descriptor & 0xc0) == 0;
    if (valid && indexed)
        valid = (bits == 8 || bits == 16) && map_length > 0 &&
                (map_bits == 8 || map_bits == 15 || map_bits == 16 || map_bits == 24 ||
                 map_bits == 32);
    else if (valid)
        valid = bits == 8 || bits == 15 || bits == 16 || bits == 24 || bits == 32;
    if (!valid)
        return luz_error_set(error, "%s: not a TGA file luz reads (colour map %u, image type "
                                    "%u, %u bits a pixel, descriptor %02X: expected an "
                                    "uncompressed or run-length true-colour, grey or "
                                    "colour-mapped image)",
                             name, colour_map_type, image_type, bits, descriptor);
    if (check_size(width, height, name, error) != 0) return LUZ_BAD_INPUT;

    /* where stb_image reads the pixels: after the header, the image ID,
     * and for a colour-mapped image map_first bytes (stb_image's reading
     * of the field) and the map */
    const size_t pixel_bytes = (bits + 7) / 8;
    size_t position = 18 + (size_t)id_length;
    if (indexed) position += map_first + (size_t)map_length * ((map_bits + 7) / 8);
    const uint64_t pixels = (uint64_t)width * (uint64_t)height;
    if (!run_length) {
        if (position > size || (size - position) / pixel_bytes < pixels)
            return luz_error_set(error, "%s: truncated TGA (%dx%d pixels of %zu bytes from byte "
                                        "%zu, the file has %zu bytes)",
                                 name, width, height, pixel_bytes, position, size);
    } else {
        /* packets of a header byte and then one pixel repeated (the high
         * bit set) or up to 128 pixels as they are; the last one may
         * reach past the image, and only what the image needs is read */
        uint64_t done = 0;
        while (done < pixels) {
            if (position >= size)
                return luz_error_set(error, "%s: truncated TGA (its run-length data ends after "
                                            "%llu of %llu pixels)",
                                     name, (unsigned long long)done,
                                     (unsigned long long)pixels);
            const unsigned packet = bytes[position++];
            uint64_t count = (packet & 0x7f) + 1;
            if (count > pixels - done) count = pixels - done;
            const uint64_t needed = (packet & 0x80 ? 1 : count) * pixel_bytes;
            if (needed > size - position)
                return luz_error_set(error, "%s: truncated TGA (its run-length data ends after "
                                            "%llu of %llu pixels)",
                                     name, (unsigned long long)done,
                                     (unsigned long long)pixels);
            position += (size_t)needed;
            done += count;
        }
    }
    header->width = width;
    header->height = height;
    return 0;
}

int luz_image_check(const unsigned char *bytes, size_t size, luz_image_format format,
                    const char *name, luz_image_header *header, luz_error *error)
{
    memset(header, 0, sizeof *header);
    header->format = format;
    if (format != LUZ_IMAGE_UNKNOWN && size == 0)
        return luz_error_set(error, "%s: an empty file, expected a %s image", name,
                             luz_image_format_name(format));
    switch (format) {
    case LUZ_IMAGE_PNG:
        if (!starts_with(bytes, size, png_signature, 8))
            return not_this_format(bytes, size, format, name, error);
        return check_png(bytes, size, name, header, error) != 0 ? LUZ_BAD_INPUT : 0;
    case LUZ_IMAGE_JPEG:
        if (!starts_with(bytes, size, "\xff\xd8\xff", 3))
            return not_this_format(bytes, size, format, name, error);
        return check_jpeg(bytes, size, name, header, error) != 0 ? LUZ_BAD_INPUT : 0;
    case LUZ_IMAGE_BMP:
        if (!starts_with(bytes, size, "BM", 2))
            return not_this_format(bytes, size, format, name, error);
        return check_bmp(bytes, size, name, header, error) != 0 ? LUZ_BAD_INPUT : 0;
    case LUZ_IMAGE_TGA:
        /* no signature: a file that is one of the others is not a TGA
         * whatever its header happens to say */
        if (luz_image_format_of_signature(bytes, size) != LUZ_IMAGE_UNKNOWN ||
            what_bytes_are(bytes, size) != NULL)
            return not_this_format(bytes, size, format, name, error);
        return check_tga(bytes, size, name, header, error) != 0 ? LUZ_BAD_INPUT : 0;
    default:
        return luz_error_set(error, "%s: not an image luz reads (expected PNG, JPEG, BMP or TGA)",
                             name);
    }
}
