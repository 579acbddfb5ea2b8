/*
 * overlay.c: rectangles and text drawn into a framebuffer's colour (see
 * app/panel.h), for the viewer's HUD, panel and help.
 *
 * The text comes from stb_easy_font, which turns a string into quads made
 * of whole font pixels (each segment of a glyph is a 1-pixel-wide bar).
 * Every quad is an axis-aligned rectangle with integer corners, so scaling
 * it by a whole number and filling it gives crisp text without any
 * rasterisation beyond a rectangle fill. This is not the pipeline: the
 * overlay writes colour only, over the shaded frame, and never touches
 * depth or visibility.
 *
 * Drawing records rectangles into a luz_layer; luz_layer_finish indexes
 * them by bands of rows (a counting sort, as frame.c bins triangles), and
 * luz_layer_draw_rows fills a band's share of them, which is what the
 * renderer's threads call per band (a luz_band_hook).
 */
#include "app/panel.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* stb_easy_font is a header of static functions, written for brevity: it
 * does not use all of them here, and brace-elides a struct initialiser. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

/* ---- rectangles ---------------------------------------------------------------- */

/* Clips rect to columns [0, width) and rows [first_row, end_row); false if
 * nothing is left. */
static bool clip_rect(luz_rect *rect, int width, int first_row, int end_row)
{
    int x0 = rect->x < 0 ? 0 : rect->x;
    int y0 = rect->y < first_row ? first_row : rect->y;
    long long x1 = (long long)rect->x + rect->width, y1 = (long long)rect->y + rect->height;
    if (x1 > width) x1 = width;
    if (y1 > end_row) y1 = end_row;
    if (x1 <= x0 || y1 <= y0)
        return false;
    *rect = (luz_rect){x0, y0, (int)x1 - x0, (int)y1 - y0};
    return true;
}

/* GCC and clang vector extensions, as in fragment_packet.c: 16 bytes (four
 * pixels) widened to sixteen 16-bit lanes. The compiler maps them onto
 * whatever SIMD the target has, at -O2 too, where it would not vectorise
 * the plain loop by itself. */
typedef uint8_t byte_lanes __attribute__((vector_size(16)));
typedef uint16_t word_lanes __attribute__((vector_size(32)));

/* One channel of the blend below. */
static inline uint8_t blend_channel(uint8_t destination, uint16_t keep, uint16_t add)
{
    uint16_t t = (uint16_t)(destination * keep + add);
    return (uint8_t)((uint16_t)(t + (t >> 8)) >> 8);
}

/* Blends colour over rect, which lies inside the framebuffer. */
static void fill_rect(luz_framebuffer *framebuffer, luz_rect rect, luz_rgba colour)
{
    /* The colour's bytes in the framebuffer's order. */
    const bool bgra = framebuffer->channel_order == LUZ_CHANNELS_BGRA;
    const uint8_t source[4] = {bgra ? colour.b : colour.r, colour.g, bgra ? colour.r : colour.b,
                               255};
    const size_t stride = (size_t)framebuffer->width * 4;
    uint8_t *first_row = framebuffer->colour + (size_t)rect.y * stride + (size_t)rect.x * 4;

    if (colour.a == 255) {   /* opaque: text, sliders; a plain store */
        for (int y = 0; y < rect.height; y++)
            for (int x = 0; x < rect.width; x++)
                memcpy(first_row + (size_t)y * stride + (size_t)x * 4, source, 4);
        return;
    }

    /* Each channel becomes round((src * a + dst * (255 - a)) / 255). With
     * x that sum and t = x + 128, (t + (t >> 8)) >> 8 is exactly
     * round(x / 255) for every x in [0, 255 * 255] (Jim Blinn, "Three
     * Wrongs Make a Right", 1995): no division and no branch, so four
     * pixels go through at once (the HUD's box: docs/performance.md,
     * "Measured in the code"). t + (t >> 8) is at most 255 * 255 + 128 +
     * 254 = 65407, so 16-bit lanes hold it. The alpha channel's source is
     * 255, which keeps it at 255. */
    const uint16_t keep = (uint16_t)(255u - colour.a);
    uint16_t add[4];
    for (int c = 0; c < 4; c++)
        add[c] = (uint16_t)(source[c] * colour.a + 128u);
    word_lanes keep_lanes, add_lanes;
    for (int i = 0; i < 16; i++) {
        keep_lanes[i] = keep;
        add_lanes[i] = add[i % 4];
    }
    const int row_bytes = rect.width * 4;
    for (int y = 0; y < rect.height; y++) {
        uint8_t *row = first_row + (size_t)y * stride;
        int x = 0;
        for (; x + 16 <= row_bytes; x += 16) {
            /* When the layer is filled after the whole frame, the HUD's
             * corner has left the caches: asking for the rows four ahead,
             * a cache line at a time, hides most of the wait
             * (docs/performance.md, "Measured in the code"). Filled band
             * by band (a luz_band_hook) the rows are still cached and the
             * prefetch costs next to nothing. */
            if ((x & 63) == 0 && y + 4 < rect.height)
                __builtin_prefetch(row + 4 * stride + x, 1);
            byte_lanes bytes;
            memcpy(&bytes, row + x, sizeof bytes);
            word_lanes t = __builtin_convertvector(bytes, word_lanes) * keep_lanes + add_lanes;
            bytes = __builtin_convertvector((t + (t >> 8)) >> 8, byte_lanes);
            memcpy(row + x, &bytes, sizeof bytes);
        }
        for (; x < row_bytes; x++)   /* the row's last pixels, fewer than four */
            row[x] = blend_channel(row[x], keep, add[x % 4]);
    }
}

/* ---- the layer: record, index by rows, fill ---------------------------------------- */

/* More rectangles than any HUD, panel and help together (a few thousand):
 * a bound on the memory a runaway caller can make the layer take. */
#define MAX_LAYER_RECTS (1u << 22)

void luz_layer_begin(luz_layer *layer, int width, int height)
{
    layer->width = width > 0 ? width : 0;
    layer->height = height > 0 ? height : 0;
    layer->rect_count = 0;
    layer->finished = false;
    layer->out_of_memory = false;
    layer->cut_rects = 0;
}

void luz_overlay_fill(luz_layer *layer, luz_rect rect, luz_rgba colour)
{
    if (colour.a == 0 || rect.width <= 0 || rect.height <= 0)
        return;
    const luz_rect asked = rect;
    const bool inside = clip_rect(&rect, layer->width, 0, layer->height);
    if (!inside || rect.width != asked.width || rect.height != asked.height)
        layer->cut_rects++;
    if (!inside)
        return;
    if (layer->rect_count == layer->rect_capacity) {
        size_t capacity = layer->rect_capacity ? 2 * layer->rect_capacity : 1024;
        luz_layer_rect *rects = capacity <= MAX_LAYER_RECTS
                                    ? realloc(layer->rects, capacity * sizeof *rects)
                                    : NULL;
        if (rects == NULL) {
            layer->out_of_memory = true;
            return;
        }
        layer->rects = rects;
        layer->rect_capacity = capacity;
    }
    layer->rects[layer->rect_count++] = (luz_layer_rect){rect, colour};
}

int luz_layer_finish(luz_layer *layer)
{
    layer->finished = false;
    if (layer->out_of_memory)
        return -1;
    const size_t bucket_count =
        ((size_t)layer->height + LUZ_LAYER_BUCKET_ROWS - 1) / LUZ_LAYER_BUCKET_ROWS;
    if (bucket_count + 1 > layer->bucket_start_capacity) {
        size_t *grown = realloc(layer->bucket_start, (bucket_count + 1) * sizeof *grown);
        if (grown == NULL)
            goto out_of_memory;
        layer->bucket_start = grown;
        layer->bucket_start_capacity = bucket_count + 1;
    }

    /* Count each bucket's rectangles, turn the counts into starts, then
     * place the rectangles in drawing order, as frame.c bins triangles. */
    size_t *start = layer->bucket_start;
    memset(start, 0, (bucket_count + 1) * sizeof *start);
    for (size_t i = 0; i < layer->rect_count; i++) {
        const luz_rect *rect = &layer->rects[i].rect;
        for (int k = rect->y / LUZ_LAYER_BUCKET_ROWS;
             k <= (rect->y + rect->height - 1) / LUZ_LAYER_BUCKET_ROWS; k++)
            start[k + 1]++;
    }
    for (size_t k = 0; k < bucket_count; k++)
        start[k + 1] += start[k];
    if (start[bucket_count] > layer->bucket_rects_capacity) {
        uint32_t *grown = realloc(layer->bucket_rects, start[bucket_count] * sizeof *grown);
        if (grown == NULL)
            goto out_of_memory;
        layer->bucket_rects = grown;
        layer->bucket_rects_capacity = start[bucket_count];
    }
    for (size_t i = 0; i < layer->rect_count; i++) {
        const luz_rect *rect = &layer->rects[i].rect;
        for (int k = rect->y / LUZ_LAYER_BUCKET_ROWS;
             k <= (rect->y + rect->height - 1) / LUZ_LAYER_BUCKET_ROWS; k++)
            layer->bucket_rects[start[k]++] = (uint32_t)i;
    }
    for (size_t k = bucket_count; k > 0; k--)
        start[k] = start[k - 1];
    start[0] = 0;
    layer->finished = true;
    return 0;

out_of_memory:
    layer->out_of_memory = true;
    return -1;
}

void luz_layer_draw_rows(const luz_layer *layer, luz_framebuffer *framebuffer, int first_row,
                         int end_row)
{
    if (!layer->finished)
        return;
    if (first_row < 0) first_row = 0;
    if (end_row > layer->height) end_row = layer->height;
    if (end_row > framebuffer->height) end_row = framebuffer->height;
    const int width = layer->width < framebuffer->width ? layer->width : framebuffer->width;
    /* Bucket by bucket, each rectangle cut to the rows the bucket and the
     * band share: a rectangle that spans buckets is filled in disjoint
     * pieces, so every pixel is blended once whatever the band's rows. */
    for (int k = first_row / LUZ_LAYER_BUCKET_ROWS; k * LUZ_LAYER_BUCKET_ROWS < end_row; k++) {
        int bucket_first = k * LUZ_LAYER_BUCKET_ROWS;
        int bucket_end = bucket_first + LUZ_LAYER_BUCKET_ROWS;
        if (bucket_first < first_row) bucket_first = first_row;
        if (bucket_end > end_row) bucket_end = end_row;
        for (size_t j = layer->bucket_start[k]; j < layer->bucket_start[k + 1]; j++) {
            const luz_layer_rect *entry = &layer->rects[layer->bucket_rects[j]];
            luz_rect rect = entry->rect;
            if (clip_rect(&rect, width, bucket_first, bucket_end))
                fill_rect(framebuffer, rect, entry->colour);
        }
    }
}

void luz_layer_draw(const luz_layer *layer, luz_framebuffer *framebuffer)
{
    luz_layer_draw_rows(layer, framebuffer, 0, framebuffer->height);
}

void luz_layer_free(luz_layer *layer)
{
    free(layer->rects);
    free(layer->bucket_start);
    free(layer->bucket_rects);
    *layer = (luz_layer){0};
}

/* ---- text --------------------------------------------------------------------------- */

/* stb_easy_font indexes its tables with (c - 32): anything but printable
 * ASCII would read outside them. */
static char printable(char c)
{
    return (c >= 32 && c < 127) ? c : '?';
}

int luz_overlay_text_width(const char *text, int scale)
{
    int width = 0;
    for (const char *c = text; *c != '\0'; c++)
        width += (stb_easy_font_charinfo[printable(*c) - 32].advance & 15) * scale;
    return width;
}

int luz_overlay_text_height(int scale)
{
    /* Glyphs span rows 0-6, descenders (g, p, q, y) reach row 9. */
    return 10 * scale;
}

int luz_overlay_text(luz_layer *layer, int x, int y, int scale, const char *text,
                     luz_rgba colour)
{
    int pen = x;
    for (const char *c = text; *c != '\0'; c++) {
        char glyph[2] = {printable(*c), '\0'};
        /* One glyph at a time keeps the vertex buffer small and bounded:
         * the largest glyph has fewer than 16 segments of 4 vertices. */
        float vertices[16 * 4 * 4];
        int quads = stb_easy_font_print(0.0f, 0.0f, glyph, NULL, vertices, sizeof vertices);
        for (int q = 0; q < quads; q++) {
            /* A vertex is x, y, z, colour (16 bytes); vertices 0 and 2 are
             * opposite corners. */
            const float *corner0 = &vertices[q * 16];
            const float *corner2 = &vertices[q * 16 + 8];
            int x0 = (int)corner0[0], y0 = (int)corner0[1];
            int x1 = (int)corner2[0], y1 = (int)corner2[1];
            luz_overlay_fill(layer,
                             (luz_rect){pen + x0 * scale, y + y0 * scale, (x1 - x0) * scale,
                                        (y1 - y0) * scale},
                             colour);
        }
        pen += (stb_easy_font_charinfo[glyph[0] - 32].advance & 15) * scale;
    }
    return pen - x;
}

/* ---- marking a pixel ---------------------------------------------------------------- */

/* A square frame `thickness` wide whose outer edge is `half` pixels from
 * pixel (x, y) on every side. */
static void frame_around(luz_layer *layer, int x, int y, int half, int thickness,
                         luz_rgba colour)
{
    const int side = 2 * half + 1;
    luz_overlay_fill(layer, (luz_rect){x - half, y - half, side, thickness}, colour);
    luz_overlay_fill(layer, (luz_rect){x - half, y + half + 1 - thickness, side, thickness},
                     colour);
    luz_overlay_fill(layer, (luz_rect){x - half, y - half, thickness, side}, colour);
    luz_overlay_fill(layer, (luz_rect){x + half + 1 - thickness, y - half, thickness, side},
                     colour);
}

void luz_overlay_mark(luz_layer *layer, int x, int y, int scale)
{
    if (scale < 1)
        scale = 1;
    /* From the outside in: black, white twice as wide, black; inside the
     * ring the pixel and 3 x scale pixels around it are left as drawn. */
    const luz_rgba black = {0, 0, 0, 255}, white = {255, 255, 255, 255};
    frame_around(layer, x, y, 8 * scale, scale, black);
    frame_around(layer, x, y, 7 * scale, 2 * scale, white);
    frame_around(layer, x, y, 5 * scale, scale, black);
    /* Four ticks pointing in from the sides, so that the ring is found in
     * a busy picture shown small: white, edged in black. */
    const int ring = 8 * scale, length = 8 * scale, half = 2 * scale;
    const luz_rect ticks[4] = {
        {x - ring - length, y - half, length, 2 * half + 1},   /* left */
        {x + ring + 1, y - half, length, 2 * half + 1},        /* right */
        {x - half, y - ring - length, 2 * half + 1, length},   /* top */
        {x - half, y + ring + 1, 2 * half + 1, length},        /* bottom */
    };
    for (int i = 0; i < 4; i++) {
        luz_rect t = ticks[i];
        luz_overlay_fill(layer, t, black);
        luz_overlay_fill(layer, (luz_rect){t.x + (t.width > t.height ? 0 : scale),
                                           t.y + (t.width > t.height ? scale : 0),
                                           t.width > t.height ? t.width : t.width - 2 * scale,
                                           t.width > t.height ? t.height - 2 * scale : t.height},
                         white);
    }
}
