/*
 * resolve.c: four samples a pixel, from the samples' winners to one colour
 * (SCENE.md, "Anti-aliasing: four samples a pixel").
 *
 * In:  for a band of rows, each sample's winner and depth (the planes of
 *      luz_sample_buffers, written by raster.c's luz_raster_triangle_sample);
 *      after the fragment stage, the colour of each (pixel, winning
 *      triangle).
 * Out: first (luz_samples_sort_winners), the fragment stage's work: the
 *      framebuffer's visibility holds each pixel's first winner and the
 *      winner lists 1 .. 3 the others, each (pixel, triangle) once; then
 *      (luz_samples_resolve_winners) the framebuffer's colour, each pixel
 *      per channel floor((s0 + s1 + s2 + s3 + 2) / 4) of its samples'
 *      8-bit colours, the clear colour for a sample no triangle won.
 *
 * Why lists: SCENE.md shades once per pixel for each triangle that wins
 * one of its samples, at the pixel centre, as a GPU's multisampling does
 * (a fragment's inputs are interpolated at the centre unless declared
 * `centroid`). Inside a triangle the four samples agree, and the first
 * list is the whole one-sample visibility buffer: the fragment stage
 * (the packets, fragment_packet.c) shades it exactly as for one sample, so
 * the inside of a surface keeps its one-sample bytes. Only where an edge
 * crosses the pixel do lists 1 .. 3 hold anything: the same fragment
 * stage shades those rows again, list by list, into the colour planes,
 * and the resolve mixes the pixels whose samples differ. A pixel's colour
 * depends on its own samples alone, so bands and threads change nothing.
 *
 * luz_samples_resolve_planes is the plain form: a colour for every sample
 * (the teaching views and the reference fragment stage shade every plane,
 * four times the work, the same bytes), averaged the same way.
 */
#include <stdbool.h>
#include <string.h>

#include "renderer/pipeline.h"

/* Pixels looked at together for "do all four samples agree?": one AVX-512
 * vector of ids, or two AVX2 ones; the compiler vectorises the test. */
#define CHUNK 16

/* Whether pixels [0, count) of the four sample rows agree. */
static inline bool chunk_agrees(const uint32_t *s0, const uint32_t *s1, const uint32_t *s2,
                                const uint32_t *s3, int count)
{
    unsigned differ = 0;
    for (int i = 0; i < count; i++)
        differ |= (s0[i] ^ s1[i]) | (s0[i] ^ s2[i]) | (s0[i] ^ s3[i]);
    return differ == 0;
}

void luz_samples_sort_winners(luz_sample_buffers *buffers, luz_framebuffer *framebuffer,
                              int first_row, int end_row, uint8_t *row_summary)
{
    const int width = framebuffer->width;
    for (int y = first_row; y < end_row; y++) {
        const size_t row = (size_t)y * width;
        const uint32_t *s0 = buffers->plane[0].visibility + row;
        const uint32_t *s1 = buffers->plane[1].visibility + row;
        const uint32_t *s2 = buffers->plane[2].visibility + row;
        const uint32_t *s3 = buffers->plane[3].visibility + row;
        uint32_t *first = framebuffer->visibility + row;
        uint32_t *list1 = buffers->winners[1] + row;
        uint32_t *list2 = buffers->winners[2] + row;
        uint32_t *list3 = buffers->winners[3] + row;
        uint8_t summary = 0;
        for (int x0 = 0; x0 < width; x0 += CHUNK) {
            const int count = width - x0 < CHUNK ? width - x0 : CHUNK;
            const size_t bytes = (size_t)count * sizeof *first;
            /* Inside a surface (or the background) the four samples agree
             * on whole chunks: the first list is sample 0's winners, the
             * others empty. */
            if (chunk_agrees(s0 + x0, s1 + x0, s2 + x0, s3 + x0, count)) {
                memcpy(first + x0, s0 + x0, bytes);
                memset(list1 + x0, 0, bytes);
                memset(list2 + x0, 0, bytes);
                memset(list3 + x0, 0, bytes);
                continue;
            }
            for (int x = x0; x < x0 + count; x++) {
                const uint32_t a = s0[x], b = s1[x], c = s2[x], d = s3[x];
                /* The first sample a triangle won (0 if none did). */
                const uint32_t winner = a ? a : b ? b : c ? c : d;
                first[x] = winner;
                /* Sample k's triangle goes to list k if neither the first
                 * winner nor an earlier sample has it. */
                list1[x] = (b != 0 && b != winner && b != a) ? b : 0;
                list2[x] = (c != 0 && c != winner && c != a && c != b) ? c : 0;
                list3[x] = (d != 0 && d != winner && d != a && d != b && d != c) ? d : 0;
                summary |= (uint8_t)((a != b || a != c || a != d) | (list1[x] != 0) << 1 |
                                     (list2[x] != 0) << 2 | (list3[x] != 0) << 3);
            }
        }
        row_summary[y - first_row] = summary;
    }
}

luz_framebuffer luz_samples_winner_target(const luz_sample_buffers *buffers, int k)
{
    luz_framebuffer target = buffers->plane[k];
    target.visibility = buffers->winners[k];
    return target;
}

/* The four bytes of sample k's colour at pixel index i. */
static const uint8_t *sample_colour(const luz_sample_buffers *buffers,
                                    const luz_framebuffer *framebuffer, size_t i, int k,
                                    const uint8_t background[4])
{
    const uint32_t id = buffers->plane[k].visibility[i];
    if (id == 0) return background;
    if (id == framebuffer->visibility[i]) return framebuffer->colour + i * 4;
    /* The first sample that this triangle won: its list holds it. */
    for (int j = 1; j < k; j++)
        if (buffers->plane[j].visibility[i] == id) return buffers->plane[j].colour + i * 4;
    return buffers->plane[k].colour + i * 4;
}

void luz_samples_resolve_winners(const luz_sample_buffers *buffers, luz_framebuffer *framebuffer,
                                 int first_row, int end_row, const uint8_t *row_summary,
                                 const uint8_t background[4])
{
    const int width = framebuffer->width;
    for (int y = first_row; y < end_row; y++) {
        if (!(row_summary[y - first_row] & LUZ_ROW_MIXED)) continue;
        const size_t row = (size_t)y * width;
        const uint32_t *s0 = buffers->plane[0].visibility + row;
        const uint32_t *s1 = buffers->plane[1].visibility + row;
        const uint32_t *s2 = buffers->plane[2].visibility + row;
        const uint32_t *s3 = buffers->plane[3].visibility + row;
        for (int x = 0; x < width; x++) {
            if (x % CHUNK == 0 && width - x >= CHUNK &&
                chunk_agrees(s0 + x, s1 + x, s2 + x, s3 + x, CHUNK)) {
                x += CHUNK - 1;
                continue;   /* the first list's colours, as shaded */
            }
            const size_t i = row + (size_t)x;
            const uint32_t a = s0[x];
            if (a == s1[x] && a == s2[x] && a == s3[x])
                continue;   /* the first list's colour, as shaded */
            const uint8_t *c[4];
            for (int k = 0; k < 4; k++) c[k] = sample_colour(buffers, framebuffer, i, k, background);
            uint8_t resolved[4];
            for (int channel = 0; channel < 4; channel++)
                resolved[channel] = luz_samples_resolve_channel(c[0][channel], c[1][channel],
                                                                c[2][channel], c[3][channel]);
            memcpy(framebuffer->colour + i * 4, resolved, sizeof resolved);
        }
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
