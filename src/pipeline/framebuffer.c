/*
 * framebuffer.c: allocation and clearing of the colour, depth and
 * visibility buffers (see luz/framebuffer.h).
 *
 * Sizes are checked before anything is allocated, so a request for
 * 100000 x 100000 pixels fails at once with a message instead of asking
 * the system for 130 GB.
 */
#include <stdlib.h>

#include "luz/framebuffer.h"

int luz_framebuffer_check_size(int width, int height, luz_error *error)
{
    if (width < 1 || height < 1)
        return luz_error_set(error, "size %dx%d: width and height must be at least 1",
                             width, height);
    if (width > LUZ_MAX_DIMENSION || height > LUZ_MAX_DIMENSION)
        return luz_error_set(error, "size %dx%d: width and height must be at most %d", width,
                             height, LUZ_MAX_DIMENSION);
    if ((long long)width * height > LUZ_MAX_PIXELS)
        return luz_error_set(error, "size %dx%d: at most %d pixels are supported (e.g. 8192x8192)",
                             width, height, LUZ_MAX_PIXELS);
    return 0;
}

static void release_buffers(luz_framebuffer *framebuffer)
{
    free(framebuffer->colour);
    free(framebuffer->depth);
    free(framebuffer->visibility);
    framebuffer->colour = NULL;
    framebuffer->depth = NULL;
    framebuffer->visibility = NULL;
}

int luz_framebuffer_resize(luz_framebuffer *framebuffer, int width, int height,
                           luz_error *error)
{
    if (luz_framebuffer_check_size(width, height, error) != 0) return -1;
    if (framebuffer->colour && framebuffer->width == width && framebuffer->height == height)
        return 0;
    release_buffers(framebuffer);
    size_t pixels = (size_t)width * (size_t)height;   /* <= LUZ_MAX_PIXELS */
    framebuffer->colour = malloc(pixels * 4);
    framebuffer->depth = malloc(pixels * sizeof *framebuffer->depth);
    framebuffer->visibility = malloc(pixels * sizeof *framebuffer->visibility);
    if (!framebuffer->colour || !framebuffer->depth || !framebuffer->visibility) {
        release_buffers(framebuffer);
        framebuffer->width = framebuffer->height = 0;
        return luz_error_set(error, "size %dx%d: out of memory", width, height);
    }
    framebuffer->width = width;
    framebuffer->height = height;
    luz_framebuffer_clear_rows(framebuffer, 0, height, (luz_vec3){0.0f, 0.0f, 0.0f});
    return 0;
}

luz_framebuffer *luz_framebuffer_create(int width, int height, luz_error *error)
{
    if (luz_framebuffer_check_size(width, height, error) != 0) return NULL;
    luz_framebuffer *framebuffer = calloc(1, sizeof *framebuffer);
    if (!framebuffer) {
        luz_error_set(error, "out of memory");
        return NULL;
    }
    if (luz_framebuffer_resize(framebuffer, width, height, error) != 0) {
        free(framebuffer);
        return NULL;
    }
    return framebuffer;
}

void luz_framebuffer_destroy(luz_framebuffer *framebuffer)
{
    if (!framebuffer) return;
    release_buffers(framebuffer);
    free(framebuffer);
}

void luz_framebuffer_clear_rows(luz_framebuffer *framebuffer, int first_row, int end_row,
                                luz_vec3 clear_colour)
{
    const uint8_t r = luz_colour_to_byte(clear_colour.x);
    const uint8_t g = luz_colour_to_byte(clear_colour.y);
    const uint8_t b = luz_colour_to_byte(clear_colour.z);
    size_t begin = (size_t)first_row * framebuffer->width;
    size_t end = (size_t)end_row * framebuffer->width;
    for (size_t i = begin; i < end; i++) {
        uint8_t *pixel = framebuffer->colour + i * 4;
        pixel[0] = r;
        pixel[1] = g;
        pixel[2] = b;
        pixel[3] = 255;
        framebuffer->depth[i] = 1.0f;
        framebuffer->visibility[i] = 0;
    }
}
