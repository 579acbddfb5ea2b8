/*
 * overlay.c: rectangles and text drawn into a framebuffer's colour (see
 * luz/panel.h), for the viewer's HUD, panel and help.
 *
 * The text comes from stb_easy_font, which turns a string into quads made
 * of whole font pixels (each segment of a glyph is a 1-pixel-wide bar).
 * Every quad is an axis-aligned rectangle with integer corners, so scaling
 * it by a whole number and filling it gives crisp text without any
 * rasterisation beyond a rectangle fill. This is not the pipeline: the
 * overlay writes colour only, after the frame is drawn, and never touches
 * depth or visibility.
 */
#include "luz/panel.h"

#include <stdbool.h>
#include <string.h>

/* stb_easy_font is a header of static functions, written for brevity: it
 * does not use all of them here, and brace-elides a struct initialiser. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

/* ---- rectangles ---------------------------------------------------------------- */

/* Clips rect to the framebuffer; false if nothing is left. */
static bool clip_rect(const luz_framebuffer *framebuffer, luz_rect *rect)
{
    int x0 = rect->x < 0 ? 0 : rect->x;
    int y0 = rect->y < 0 ? 0 : rect->y;
    long long x1 = (long long)rect->x + rect->width, y1 = (long long)rect->y + rect->height;
    if (x1 > framebuffer->width) x1 = framebuffer->width;
    if (y1 > framebuffer->height) y1 = framebuffer->height;
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

void luz_overlay_fill(luz_framebuffer *framebuffer, luz_rect rect, luz_rgba colour)
{
    if (colour.a == 0 || !clip_rect(framebuffer, &rect))
        return;
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
     * pixels go through at once; the HUD's box then costs about 0.05 ms
     * instead of 0.2. t + (t >> 8) is at most 255 * 255 + 128 + 254 =
     * 65407, so 16-bit lanes hold it. The alpha channel's source is 255,
     * which keeps it at 255. */
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
            /* The HUD's corner of the frame was drawn first and has left
             * the caches by the time the 2D layer is drawn: asking for the
             * rows four ahead, a cache line at a time, hides most of the
             * wait (0.2 ms down to 0.13 ms for the HUD at 1280x720). */
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

int luz_overlay_text(luz_framebuffer *framebuffer, int x, int y, int scale, const char *text,
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
            luz_overlay_fill(framebuffer,
                             (luz_rect){pen + x0 * scale, y + y0 * scale, (x1 - x0) * scale,
                                        (y1 - y0) * scale},
                             colour);
        }
        pen += (stb_easy_font_charinfo[glyph[0] - 32].advance & 15) * scale;
    }
    return pen - x;
}
