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

/* The definition of the sort of one pixel's winners: sample k's source
 * is the clear colour (no triangle won it), the pixel's first winner
 * (that of its first sample a triangle won), or, for any other triangle,
 * the entry of the first sample it won, a new one numbered in sample
 * order. */
static void sort_pixel(const uint32_t id[LUZ_MAX_SAMPLES], luz_winner_pattern *pattern)
{
    memset(pattern, 0, sizeof *pattern);
    while (pattern->first < 3 && id[pattern->first] == 0) pattern->first++;
    const uint32_t winner = id[pattern->first];
    for (int k = 0; k < 4; k++) {
        if (id[k] == 0) {
            pattern->source[k] = LUZ_SAMPLE_FROM_CLEAR;
        } else if (id[k] == winner) {
            pattern->source[k] = LUZ_SAMPLE_FROM_FIRST;
        } else {
            /* A triangle an earlier sample won has its entry. */
            int j = 0;
            while (j < k && id[j] != id[k]) j++;
            if (j < k) {
                pattern->source[k] = pattern->source[j];
            } else {
                pattern->source[k] = (uint8_t)(2 + pattern->extra_count);
                pattern->extra_sample[pattern->extra_count++] = (uint8_t)k;
            }
        }
    }
}

/* For each key, winners that have it: sample k's is 0 if the key says
 * so, else that of the first earlier sample the key pairs it with, else
 * a new id. (A key no four winners have, such as 0 = 1 and 1 = 2 but
 * 0 != 2, gets some pattern; the sort never looks it up.) */
void luz_samples_winner_patterns(luz_winner_pattern patterns[LUZ_WINNER_PATTERNS])
{
    static const int pair_bit[4][4] = {
        {-1, 4, 5, 6}, {4, -1, 7, 8}, {5, 7, -1, 9}, {6, 8, 9, -1}};
    for (unsigned key = 0; key < LUZ_WINNER_PATTERNS; key++) {
        uint32_t id[LUZ_MAX_SAMPLES];
        for (int k = 0; k < 4; k++) {
            id[k] = (uint32_t)(k + 1);
            if (key >> k & 1) {
                id[k] = 0;
                continue;
            }
            for (int j = 0; j < k; j++)
                if (key >> pair_bit[j][k] & 1) {
                    id[k] = id[j];
                    break;
                }
        }
        sort_pixel(id, &patterns[key]);
    }
}

/* A row's mixed pixels are found by mixed_pixels, the instruction set's
 * copy of sample_loops.c's loop (most chunks of a row agree and are passed
 * over at a few instructions each, sixteen ids at a time under AVX-512).
 * Each mixed pixel is then sorted by its key's pattern, without a branch:
 * sort_pixel's branches follow the pattern of each pixel, and on the 1M
 * sphere (nearly every covered pixel mixed) most of them were
 * mispredicted. A pattern's three other winners are written whether it
 * has them or not (room: a pixel's entries start below three times the
 * pixels before it), and the count moves by those it has. */
void luz_samples_sort_winners(luz_sample_buffers *buffers, int first_row, int end_row,
                              luz_sample_band *band, luz_mixed_pixels_function *mixed_pixels)
{
    const int width = buffers->width;
    const luz_winner_pattern *patterns = band->patterns;
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
            const luz_winner_pattern *pattern = &patterns[luz_samples_winner_key(id)];
            luz_mixed_pixel *pixel = &band->mixed[band->mixed_count++];
            pixel->index = (uint32_t)(row + (size_t)x);
            pixel->first_extra = (uint32_t)band->extra_count;
            memcpy(pixel->source, pattern->source, sizeof pixel->source);
            luz_fragment_ref *extra = band->extra + band->extra_count;
            for (int j = 0; j < 3; j++)
                extra[j] = (luz_fragment_ref){id[pattern->extra_sample[j]], (uint16_t)x,
                                              (uint16_t)y};
            band->extra_count += pattern->extra_count;
            first[x] = id[pattern->first];
        }
    }
}

/* Each mixed pixel's four colours picked from its five candidates (the
 * clear colour, the first winner's, three others') by the sources, and
 * averaged per byte in two 32-bit words (bytes 0 and 2, then 1 and 3, in
 * 16-bit halves: four bytes and the 2 sum to at most 1022), which is
 * luz_samples_resolve_channel's floor((s0 + s1 + s2 + s3 + 2) / 4) for
 * each channel, whatever the byte order. */
void luz_samples_resolve_winners(const luz_sample_band *band, luz_framebuffer *framebuffer,
                                 const uint8_t background[4])
{
    uint32_t candidate[5];
    memcpy(&candidate[LUZ_SAMPLE_FROM_CLEAR], background, 4);
    for (size_t m = 0; m < band->mixed_count; m++) {
        const luz_mixed_pixel *pixel = &band->mixed[m];
        uint8_t *out = framebuffer->colour + (size_t)pixel->index * 4;
        memcpy(&candidate[LUZ_SAMPLE_FROM_FIRST], out, 4);
        memcpy(&candidate[2], &band->extra_colour[pixel->first_extra], 3 * sizeof(uint32_t));
        uint32_t even = 0x00020002u, odd = 0x00020002u;
        for (int k = 0; k < 4; k++) {
            const uint32_t colour = candidate[pixel->source[k]];
            even += colour & 0x00ff00ffu;
            odd += colour >> 8 & 0x00ff00ffu;
        }
        const uint32_t resolved = (even >> 2 & 0x00ff00ffu) | (odd >> 2 & 0x00ff00ffu) << 8;
        memcpy(out, &resolved, sizeof resolved);
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
