/*
 * luz/framebuffer.h: where the pipeline's output lands.
 *
 * Colour is 8 bits a channel, four bytes a pixel, in RGBA order (as in a
 * PNG file) unless the caller asks for BGRA; row 0 on top, alpha always
 * 255. Every pixel's colour is written by the shading pass, the background
 * included, so colour needs no clearing and may be memory the caller
 * lends (luz_framebuffer_use_colour).
 * Depth is a float per pixel in [0, 1] (24 bits of mantissa, SCENE.md asks
 * for at least 24), cleared to 1.0 and tested with LESS.
 *
 * The visibility buffer holds, per pixel, which triangle is nearest so far
 * (0 for none): the rasteriser writes it, and the shading pass then shades
 * every pixel exactly once, for the triangle that won the depth test.
 *
 * A frame of four samples a pixel (luz_frame.samples) keeps each sample's
 * depth and winner in the renderer's own buffers and writes only colour
 * here, the resolved pixels: depth and visibility are then left as they
 * were. So does a frame drawn with luz_render_options.colour_only, which
 * keeps each band's depth and visibility (at four samples, each
 * sample's) in the renderer's own small buffers (luz-render and the
 * viewer draw so).
 */
#ifndef LUZ_FRAMEBUFFER_H
#define LUZ_FRAMEBUFFER_H

#include <stdint.h>

#include "luz/api.h"
#include "luz/error.h"
#include "luz/vecmath.h"

/* Limits that keep every size the renderer accepts safe: the rasteriser's
 * fixed-point range is proven for sides up to LUZ_MAX_DIMENSION (see
 * src/renderer/setup.c), and LUZ_MAX_PIXELS bounds the memory: 12 bytes a
 * pixel here (colour, depth and visibility, 768 MiB at the limit), and in
 * the renderer 36 more for four samples (each sample's depth and winner,
 * a first winner), 48 more again for a teaching view at four samples (a
 * colour, depth and winner a sample) and 4 a sample for the overdraw
 * view. */
#define LUZ_MAX_DIMENSION 16384
#define LUZ_MAX_PIXELS (64 * 1024 * 1024)

/* The order of a pixel's four bytes in colour. RGBA is a PNG file's. BGRA
 * is how X11 and most window systems store a pixel on a little-endian
 * machine (the 32-bit value 0xAARRGGBB), so a viewer can have luz draw
 * straight into the window's memory instead of converting every frame. */
typedef enum luz_channel_order {
    LUZ_CHANNELS_RGBA = 0,
    LUZ_CHANNELS_BGRA,
} luz_channel_order;

typedef struct luz_framebuffer {
    int width;
    int height;
    luz_channel_order channel_order;   /* of colour */
    uint8_t *colour;        /* width * height * 4 bytes */
    float *depth;           /* width * height */
    uint32_t *visibility;   /* width * height triangle ids, 0 = background */
    uint8_t *own_colour;    /* what the framebuffer allocated; colour points
                               here unless the caller lent memory */
} luz_framebuffer;

/* Returns 0 if width x height is a size the renderer supports, else -1 with
 * a message. */
LUZ_API int luz_framebuffer_check_size(int width, int height, luz_error *error);
LUZ_API luz_framebuffer *luz_framebuffer_create(int width, int height, luz_error *error);
LUZ_API int luz_framebuffer_resize(luz_framebuffer *framebuffer, int width, int height, luz_error *error);
LUZ_API void luz_framebuffer_destroy(luz_framebuffer *framebuffer);

/* Draw the colour into the caller's memory from now on: pixels holds
 * width * height * 4 bytes, rows packed, in the given order. pixels NULL
 * goes back to the framebuffer's own memory, in the given order. The
 * caller keeps the memory alive while it is in use; the framebuffer never
 * frees it. luz_framebuffer_resize goes back to the framebuffer's own
 * memory and keeps the order. */
LUZ_API void luz_framebuffer_use_colour(luz_framebuffer *framebuffer, uint8_t *pixels,
                                        luz_channel_order order);

/* Clears rows [first_row, end_row): depth to 1.0, visibility to 0. Colour
 * is not touched: the shading pass writes the clear colour wherever
 * visibility stays 0. */
LUZ_API void luz_framebuffer_clear_rows(luz_framebuffer *framebuffer, int first_row, int end_row);

/* SCENE.md's colour output: round(clamp(c, 0, 1) * 255). */
static inline uint8_t luz_colour_to_byte(float c)
{
    /* The comparisons are written so that NaN lands on 0. */
    if (!(c > 0.0f)) return 0;
    if (!(c < 1.0f)) return 255;
    return (uint8_t)(c * 255.0f + 0.5f);
}

#endif
