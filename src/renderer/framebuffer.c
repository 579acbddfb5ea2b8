/*
 * framebuffer.c: allocation and clearing of the colour, depth and
 * visibility buffers (see luz/framebuffer.h).
 *
 * Sizes are checked before anything is allocated, so a request for
 * 100000 x 100000 pixels fails at once with a message instead of asking
 * the system for 130 GB.
 *
 * colour is normally own_colour, which the framebuffer allocates and frees;
 * luz_framebuffer_use_colour points it at memory the caller lends (a
 * window's pixels, say), which the framebuffer writes but never frees.
 */
#include <stdlib.h>
#include <string.h>

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

/* Frees what the framebuffer allocated; lent colour memory is the
 * caller's and stays. */
static void release_buffers(luz_framebuffer *framebuffer)
{
    free(framebuffer->own_colour);
    free(framebuffer->depth);
    free(framebuffer->visibility);
    framebuffer->own_colour = NULL;
    framebuffer->colour = NULL;
    framebuffer->depth = NULL;
    framebuffer->visibility = NULL;
}

int luz_framebuffer_resize(luz_framebuffer *framebuffer, int width, int height,
                           luz_error *error)
{
    if (luz_framebuffer_check_size(width, height, error) != 0) return -1;
    /* Lent memory has the caller's size, not necessarily the new one, so
     * a resize always goes back to the framebuffer's own. */
    if (framebuffer->own_colour && framebuffer->width == width && framebuffer->height == height) {
        framebuffer->colour = framebuffer->own_colour;
        return 0;
    }
    release_buffers(framebuffer);
    size_t pixels = (size_t)width * (size_t)height;   /* <= LUZ_MAX_PIXELS */
    framebuffer->own_colour = malloc(pixels * 4);
    framebuffer->depth = malloc(pixels * sizeof *framebuffer->depth);
    framebuffer->visibility = malloc(pixels * sizeof *framebuffer->visibility);
    if (!framebuffer->own_colour || !framebuffer->depth || !framebuffer->visibility) {
        release_buffers(framebuffer);
        framebuffer->width = framebuffer->height = 0;
        return luz_error_set(error, "size %dx%d: out of memory", width, height);
    }
    framebuffer->colour = framebuffer->own_colour;
    framebuffer->width = width;
    framebuffer->height = height;
    /* Drawing writes every colour byte, so this is only for a framebuffer
     * read before anything is drawn into it: opaque black (in either
     * order, as black's three channels are equal), never uninitialised
     * memory. */
    const uint8_t black[4] = {0, 0, 0, 255};
    for (size_t i = 0; i < pixels; i++)
        memcpy(framebuffer->own_colour + i * 4, black, sizeof black);
    luz_framebuffer_clear_rows(framebuffer, 0, height);
    return 0;
}

luz_framebuffer *luz_framebuffer_create(int width, int height, luz_error *error)
{
    if (luz_framebuffer_check_size(width, height, error) != 0) return NULL;
    luz_framebuffer *framebuffer = calloc(1, sizeof *framebuffer);
    if (!framebuffer) {
        luz_error_set(error, "out of memory for a %dx%d framebuffer", width, height);
        return NULL;
    }
    framebuffer->channel_order = LUZ_CHANNELS_RGBA;
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

void luz_framebuffer_use_colour(luz_framebuffer *framebuffer, uint8_t *pixels,
                                luz_channel_order order)
{
    framebuffer->colour = pixels ? pixels : framebuffer->own_colour;
    framebuffer->channel_order = order;
}

void luz_framebuffer_clear_rows(luz_framebuffer *framebuffer, int first_row, int end_row)
{
    /* Only depth and visibility: the shading pass writes every colour
     * byte, the background's included (the clear colour where visibility
     * stays 0), so clearing colour too would write each byte twice.
     * Visibility's 0 is all-zero bytes, a memset. Depth's 1.0 is not a
     * repeated byte, so it is copied eight floats at a time, which the
     * compiler turns into wide stores: GCC 12 at -O2 leaves a loop of
     * single floats unvectorised, and that loop took twice the memset's
     * time (perf, on luz-render --bench). */
    static const float far_plane[8] = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f};
    const size_t begin = (size_t)first_row * (size_t)framebuffer->width;
    const size_t end = (size_t)end_row * (size_t)framebuffer->width;
    float *depth = framebuffer->depth;
    size_t i = begin;
    for (; end - i >= 8; i += 8)
        memcpy(depth + i, far_plane, sizeof far_plane);
    for (; i < end; i++)
        depth[i] = 1.0f;
    memset(framebuffer->visibility + begin, 0, (end - begin) * sizeof *framebuffer->visibility);
}
