/*
 * resolve.c: four samples a pixel, from the samples' winners to one colour
 * (SCENE.md, "Anti-aliasing: four samples a pixel").
 *
 * In:  for a band of rows, each sample's winner and depth (the planes of
 *      luz_sample_buffers, written by raster.c's luz_raster_triangle_samples);
 *      after the fragment stage, the colour of each (pixel, winning
 *      triangle).
 * Out: first (luz_samples_sort_winners), the fragment stage's work: the
 *      framebuffer's visibility holds each pixel's first winner, and a
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

/* Pixels looked at together for "do all four samples agree?": one AVX-512
 * vector of ids, or two AVX2 ones. */
#define CHUNK 16

/* The x of row's pixels whose four samples differ, in order, into mixed_x;
 * returns how many. Most chunks of a row agree (inside a surface, or the
 * background) and are passed over at a few instructions each: compiled
 * for wider vectors too (LUZ_CLONES). */
static LUZ_CLONES int mixed_pixels_of_row(const uint32_t *s0, const uint32_t *s1,
                                          const uint32_t *s2, const uint32_t *s3, int width,
                                          uint16_t *mixed_x)
{
    int count = 0;
    for (int x0 = 0; x0 < width; x0 += CHUNK) {
        const int end = width - x0 < CHUNK ? width : x0 + CHUNK;
        uint32_t differ = 0;
        for (int x = x0; x < end; x++)
            differ |= (s0[x] ^ s1[x]) | (s0[x] ^ s2[x]) | (s0[x] ^ s3[x]);
        if (differ == 0) continue;
        for (int x = x0; x < end; x++)
            if (s0[x] != s1[x] || s0[x] != s2[x] || s0[x] != s3[x]) mixed_x[count++] = (uint16_t)x;
    }
    return count;
}

void luz_samples_sort_winners(luz_sample_buffers *buffers, int first_row, int end_row,
                              luz_sample_band *band)
{
    const int width = buffers->plane[0].width;
    band->mixed_count = 0;
    band->extra_count = 0;
    for (int y = first_row; y < end_row; y++) {
        const size_t row = (size_t)y * width;
        uint32_t *s[4] = {buffers->plane[0].visibility + row, buffers->plane[1].visibility + row,
                          buffers->plane[2].visibility + row, buffers->plane[3].visibility + row};
        const int mixed = mixed_pixels_of_row(s[0], s[1], s[2], s[3], width, band->row_mixed);
        for (int m = 0; m < mixed; m++) {
            const int x = band->row_mixed[m];
            const uint32_t id[4] = {s[0][x], s[1][x], s[2][x], s[3][x]};
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
            /* Sample 0's plane becomes the first winners (the fragment
             * stage reads it as a one-sample visibility buffer). */
            s[0][x] = winner;
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
