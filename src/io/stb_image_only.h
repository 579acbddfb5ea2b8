/*
 * io/stb_image_only.h: the stb_image luz decodes with (stb_image_only.c),
 * built with its PNG, BMP and TGA decoders and nothing else.
 */
#ifndef LUZ_IO_STB_IMAGE_ONLY_H
#define LUZ_IO_STB_IMAGE_ONLY_H

/* stbi_load_from_memory(bytes, size, width, height, NULL, 4): RGBA8
 * pixels (malloc'd; free() them), or NULL. */
unsigned char *luz_stb_load_rgba(const unsigned char *bytes, int size, int *width, int *height);

/* stbi_zlib_decode_buffer: inflates a zlib stream into a buffer of fixed
 * size; the bytes written, or -1 (the buffer full is a failure too). */
int luz_stb_inflate(unsigned char *out, int out_size, const unsigned char *in, int in_size);

/* stbi_failure_reason: why the last call on this thread failed ("outofmem"
 * when memory ran out). */
const char *luz_stb_failure_reason(void);

#endif
