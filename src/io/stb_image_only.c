/*
 * stb_image_only.c: Debian's stb_image 2.27, compiled with the three
 * decoders luz uses (PNG, BMP, TGA) and no others.
 *
 * In:  encoded bytes that image_formats.c has checked.
 * Out: what stb_image makes of them.
 *
 * The full build (libstb) picks a decoder from a file's contents, not its
 * name, so any .png could reach its GIF, PSD, HDR, PNM and PIC decoders;
 * a 19-byte PGM named x.png crashed luz-render through the PNM one. Here
 * they are not compiled at all (STBI_ONLY_*), and neither is reading from
 * files (luz reads files itself, io/input_file.h). STB_IMAGE_STATIC keeps
 * every stb symbol inside this file, apart from libstb's own copy that
 * the tests link; STBI_MAX_DIMENSIONS is luz's texture limit. This file
 * is stb's and three wrappers, so stb's unused functions may stay unused.
 */
#include "io/stb_image_only.h"

#include "luz/texture.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STBI_ONLY_TGA
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_NO_HDR
#define STBI_MAX_DIMENSIONS LUZ_TEXTURE_MAX_SIZE
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb_image.h>

unsigned char *luz_stb_load_rgba(const unsigned char *bytes, int size, int *width, int *height)
{
    int channels;
    return stbi_load_from_memory(bytes, size, width, height, &channels, 4);
}

int luz_stb_inflate(unsigned char *out, int out_size, const unsigned char *in, int in_size)
{
    return stbi_zlib_decode_buffer((char *)out, out_size, (const char *)in, in_size);
}

const char *luz_stb_failure_reason(void)
{
    const char *reason = stbi_failure_reason();
    return reason ? reason : "no reason given";
}
