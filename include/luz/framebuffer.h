/*
 * luz/framebuffer.h: where the pipeline's output lands.
 *
 * Colour is RGBA8, row 0 on top (as in a PNG file), alpha always 255.
 * Depth is a float per pixel in [0, 1] (24 bits of mantissa, SCENE.md asks
 * for at least 24), cleared to 1.0 and tested with LESS.
 *
 * The visibility buffer holds, per pixel, which triangle is nearest so far
 * (0 for none): the rasteriser writes it, and the shading pass then shades
 * every pixel exactly once, for the triangle that won the depth test.
 */
#ifndef LUZ_FRAMEBUFFER_H
#define LUZ_FRAMEBUFFER_H

#include <stdint.h>

#include "luz/error.h"
#include "luz/vecmath.h"

/* Limits that keep every size the renderer accepts safe: the rasteriser's
 * fixed-point range is proven for sides up to LUZ_MAX_DIMENSION (see
 * src/pipeline/setup.c), and LUZ_MAX_PIXELS bounds the memory (13 bytes a
 * pixel: under 900 MiB). */
#define LUZ_MAX_DIMENSION 16384
#define LUZ_MAX_PIXELS (64 * 1024 * 1024)

typedef struct luz_framebuffer {
    int width;
    int height;
    uint8_t *colour;        /* width * height * 4 bytes */
    float *depth;           /* width * height */
    uint32_t *visibility;   /* width * height triangle ids, 0 = background */
} luz_framebuffer;

/* Returns 0 if width x height is a size the renderer supports, else -1 with
 * a message. */
int luz_framebuffer_check_size(int width, int height, luz_error *error);
luz_framebuffer *luz_framebuffer_create(int width, int height, luz_error *error);
int luz_framebuffer_resize(luz_framebuffer *framebuffer, int width, int height, luz_error *error);
void luz_framebuffer_destroy(luz_framebuffer *framebuffer);

/* Clears rows [first_row, end_row): colour to clear_colour, depth to 1.0,
 * visibility to 0. */
void luz_framebuffer_clear_rows(luz_framebuffer *framebuffer, int first_row, int end_row,
                                luz_vec3 clear_colour);

/* SCENE.md's colour output: round(clamp(c, 0, 1) * 255). */
static inline uint8_t luz_colour_to_byte(float c)
{
    /* The comparisons are written so that NaN lands on 0. */
    if (!(c > 0.0f)) return 0;
    if (!(c < 1.0f)) return 255;
    return (uint8_t)(c * 255.0f + 0.5f);
}

#endif
