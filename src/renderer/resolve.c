/*
 * resolve.c: four samples a pixel, from the samples' winners to one colour
 * (SCENE.md, "Anti-aliasing: four samples a pixel").
 *
 * In:  for a band of rows, each sample's winner (luz_sample_buffers' side
 *      by side ids, written by raster.c's luz_raster_triangle_samples);
 *      after the fragment stage, the colour of each (pixel, winning
 *      triangle).
 * Out: first (luz_samples_sort_winners), the fragment stage's work: the
 *      buffers' first_winner holds each pixel's first winner, and a
 *      list the mixed pixels (those whose samples differ) with their
 *      other winners, each (pixel, triangle) once; then
 *      (luz_samples_resolve_winners) the framebuffer's colour, each mixed
 *      pixel per channel floor((s0 + s1 + s2 + s3 + 2) / 4) of its
 *      samples' 8-bit colours, the clear colour for a sample no triangle
 *      won.
 *
 * Why so: SCENE.md shades once per pixel for each triangle that wins one
 * of its samples, at the pixel centre, as a GPU's multisampling does (a
 * fragment's inputs are interpolated at the centre unless declared
 * `centroid`). Inside a triangle the four samples agree, and the first
 * winners are the whole one-sample visibility buffer: the fragment stage
 * (the packets, fragment_packet.c) shades it exactly as for one sample,
 * so the inside of a surface keeps its one-sample bytes. Only where an
 * edge crosses a pixel is there more: those few (pixel, triangle) pairs
 * are listed and shaded as a list (16 scattered fragments to a packet),
 * and the resolve mixes those pixels alone. A pixel's colour depends on
 * its own samples alone, so bands and threads change nothing.
 *
 * luz_samples_resolve_planes is the plain form: a colour for every sample
 * (the teaching views shade every plane, four times the work, the same
 * bytes for a colour that depends on the triangle and the pixel centre
 * only), averaged the same way.
 */
#include <stdbool.h>
#include <string.h>

#include "renderer/pipeline.h"

/* A row's mixed pixels are found by mixed_pixels, the instruction set's
 * copy of sample_loops.c's loop (most chunks of a row agree and are passed
 * over at a few instructions each, sixteen ids at a time under AVX-512). */
void luz_samples_sort_winners(luz_sample_buffers *buffers, int first_row, int end_row,
                              luz_sample_band *band, luz_mixed_pixels_function *mixed_pixels)
{
    const int width = buffers->width;
    band->mixed_count = 0;
    band->extra_count = 0;
    for (int y = first_row; y < end_row; y++) {
        const size_t row = (size_t)y * width;
        const uint32_t *ids = buffers->visibility + row * LUZ_MAX_SAMPLES;
        uint32_t *first = buffers->first_winner + row;
        const int mixed = mixed_pixels(ids, width, first, band->row_mixed);
        for (int m = 0; m < mixed; m++) {
            const int x = band->row_mixed[m];
            const uint32_t *id = ids + (size_t)x * LUZ_MAX_SAMPLES;
            /* The first sample a triangle won (0 if none did). */
            const uint32_t winner = id[0] ? id[0] : id[1] ? id[1] : id[2] ? id[2] : id[3];
            luz_mixed_pixel *pixel = &band->mixed[band->mixed_count++];
            pixel->index = (uint32_t)(row + (size_t)x);
            pixel->first_extra = (uint32_t)band->extra_count;
            int others = 0;
            for (int k = 0; k < 4; k++) {
                if (id[k] == 0) {
                    pixel->source[k] = LUZ_SAMPLE_FROM_CLEAR;
                } else if (id[k] == winner) {
                    pixel->source[k] = LUZ_SAMPLE_FROM_FIRST;
                } else {
                    /* A triangle an earlier sample won has its entry. */
                    int j = 0;
                    while (j < k && id[j] != id[k]) j++;
                    if (j < k) {
                        pixel->source[k] = pixel->source[j];
                    } else {
                        pixel->source[k] = (uint8_t)(2 + others++);
                        band->extra[band->extra_count++] =
                            (luz_fragment_ref){id[k], (uint16_t)x, (uint16_t)y};
                    }
                }
            }
            first[x] = winner;
        }
    }
}

void luz_samples_resolve_winners(const luz_sample_band *band, luz_framebuffer *framebuffer,
                                 const uint8_t background[4])
{
    for (size_t m = 0; m < band->mixed_count; m++) {
        const luz_mixed_pixel *pixel = &band->mixed[m];
        uint8_t *out = framebuffer->colour + (size_t)pixel->index * 4;
        const uint8_t *colour[4];
        for (int k = 0; k < 4; k++) {
            const uint8_t source = pixel->source[k];
            colour[k] = source == LUZ_SAMPLE_FROM_CLEAR ? background
                        : source == LUZ_SAMPLE_FROM_FIRST
                            ? out
                            : (const uint8_t *)&band->extra_colour[pixel->first_extra +
                                                                   (uint32_t)(source - 2)];
        }
        uint8_t resolved[4];
        for (int channel = 0; channel < 4; channel++)
            resolved[channel] = luz_samples_resolve_channel(colour[0][channel], colour[1][channel],
                                                            colour[2][channel], colour[3][channel]);
        memcpy(out, resolved, sizeof resolved);
    }
}

void luz_samples_resolve_planes(const luz_sample_buffers *buffers, luz_framebuffer *framebuffer,
                                int first_row, int end_row)
{
    const size_t begin = (size_t)first_row * framebuffer->width * 4;
    const size_t end = (size_t)end_row * framebuffer->width * 4;
    const uint8_t *c0 = buffers->plane[0].colour, *c1 = buffers->plane[1].colour;
    const uint8_t *c2 = buffers->plane[2].colour, *c3 = buffers->plane[3].colour;
    for (size_t i = begin; i < end; i++)
        framebuffer->colour[i] = luz_samples_resolve_channel(c0[i], c1[i], c2[i], c3[i]);
}

void luz_samples_clear_rows(luz_sample_buffers *buffers, int first_row, int end_row)
{
    /* The side-by-side arrays are a framebuffer's depth and visibility
     * LUZ_MAX_SAMPLES times as wide: cleared the same way. */
    luz_framebuffer rows = {.width = buffers->width * LUZ_MAX_SAMPLES,
                            .height = buffers->height,
                            .depth = buffers->depth,
                            .visibility = buffers->visibility};
    luz_framebuffer_clear_rows(&rows, first_row, end_row);
}

void luz_samples_split_rows(luz_sample_buffers *buffers, int first_row, int end_row)
{
    const size_t begin = (size_t)first_row * (size_t)buffers->width;
    const size_t end = (size_t)end_row * (size_t)buffers->width;
    for (int k = 0; k < buffers->samples; k++) {
        luz_framebuffer *plane = &buffers->plane[k];
        for (size_t i = begin; i < end; i++) {
            plane->depth[i] = buffers->depth[i * LUZ_MAX_SAMPLES + (size_t)k];
            plane->visibility[i] = buffers->visibility[i * LUZ_MAX_SAMPLES + (size_t)k];
        }
    }
}
