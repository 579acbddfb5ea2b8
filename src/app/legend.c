/*
 * legend.c: the key to a view's colours, as swatches with their meaning
 * (see app/panel.h), for the viewer's HUD and for luz-render --legend.
 *
 * Every swatch is a colour of luz/view.h's palettes, the very functions
 * view.c colours pixels with, so the key cannot drift from the picture.
 * The entries are all of them (every mip level the sampler can name,
 * every overdraw count up to 8+, every thread of the renderer), laid out
 * in as many rows as the width allows.
 */
#include "app/panel.h"
#include "luz/view.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void add(luz_legend *legend, luz_vec3 colour, const char *label)
{
    if (legend->entry_count >= LUZ_LEGEND_MAX_ENTRIES)
        return;
    luz_legend_entry *entry = &legend->entries[legend->entry_count++];
    entry->colour = colour;
    snprintf(entry->label, sizeof entry->label, "%s", label);
}

static luz_vec3 grey(float value)
{
    return (luz_vec3){value, value, value};
}

luz_legend luz_legend_of(luz_view view, int thread_count, uint64_t triangle_count)
{
    luz_legend legend;
    memset(&legend, 0, sizeof legend);
    char label[LUZ_LEGEND_LABEL_SIZE];
    switch (view) {
    case LUZ_VIEW_COLOR:
        legend.title = "color: the shaded image";
        break;
    case LUZ_VIEW_DEPTH: {
        /* Distances on the log scale between the near plane (0.1) and the
         * far one (100): 1 - log(d / 0.1) / log(1000), SCENE.md's planes. */
        legend.title = "depth: eye distance, log scale";
        static const float distances[] = {0.1f, 1.0f, 10.0f, 100.0f};
        static const char *const names[] = {"0.1 near", "1", "10", "100 far"};
        for (int i = 0; i < 4; i++)
            add(&legend, grey(1.0f - log10f(distances[i] / 0.1f) / 3.0f), names[i]);
        break;
    }
    case LUZ_VIEW_NORMALS:
        legend.title = "normals: world N as (N + 1) / 2";
        add(&legend, (luz_vec3){1.0f, 0.5f, 0.5f}, "+x");
        add(&legend, (luz_vec3){0.0f, 0.5f, 0.5f}, "-x");
        add(&legend, (luz_vec3){0.5f, 1.0f, 0.5f}, "+y");
        add(&legend, (luz_vec3){0.5f, 0.0f, 0.5f}, "-y");
        add(&legend, (luz_vec3){0.5f, 0.5f, 1.0f}, "+z");
        add(&legend, (luz_vec3){0.5f, 0.5f, 0.0f}, "-z");
        break;
    case LUZ_VIEW_UV:
        legend.title = "uv: red fract(u), green fract(v)";
        add(&legend, (luz_vec3){0.0f, 0.0f, 0.0f}, "u 0, v 0");
        add(&legend, (luz_vec3){1.0f, 0.0f, 0.0f}, "u 1");
        add(&legend, (luz_vec3){0.0f, 1.0f, 0.0f}, "v 1");
        add(&legend, (luz_vec3){1.0f, 1.0f, 0.0f}, "u 1, v 1");
        break;
    case LUZ_VIEW_MIP:
        legend.title = "mip: the level read, blends by fract(lambda)";
        for (int level = 0; level <= 8; level++) {
            snprintf(label, sizeof label, "%d", level);
            add(&legend, luz_view_mip_colour(level), label);
        }
        add(&legend, luz_view_mip_colour(9), "9+");
        add(&legend, LUZ_VIEW_MIP_UNTEXTURED, "no texture");
        break;
    case LUZ_VIEW_OVERDRAW:
        legend.title = "overdraw: depth tests per pixel";
        for (uint32_t count = 0; count <= 8; count++) {
            snprintf(label, sizeof label, count == 8 ? "%u+" : "%u", (unsigned)count);
            add(&legend, luz_view_overdraw_colour(count), label);
        }
        break;
    case LUZ_VIEW_BANDS:
        legend.title = "bands: tint of the thread (0, 1, ...) that drew the band";
        for (int worker = 0; worker < thread_count && worker < LUZ_LEGEND_MAX_ENTRIES;
             worker++) {
            snprintf(label, sizeof label, "%d", worker);
            add(&legend, luz_view_thread_colour(worker), label);
        }
        break;
    case LUZ_VIEW_TRIANGLES: {
        legend.title = "triangles: a colour each; darker where a neighbour is another's";
        /* Examples, the first three ids, of those the frame has. */
        const uint32_t shown = triangle_count < 3 ? (uint32_t)triangle_count : 3;
        for (uint32_t id = 1; id <= shown; id++) {
            snprintf(label, sizeof label, "id %u", (unsigned)id);
            add(&legend, luz_view_triangle_colour(id), label);
        }
        for (uint32_t id = 1; id <= shown; id++) {
            snprintf(label, sizeof label, "%u at an edge", (unsigned)id);
            add(&legend, luz_vec3_scale(luz_view_triangle_colour(id),
                                        LUZ_VIEW_TRIANGLE_EDGE_SHADE),
                label);
        }
        break;
    }
    case LUZ_VIEW_COUNT:
        break;
    }
    return legend;
}

/* Sizes at text scale 1; everything scales with it. */
enum {
    ROW = 12,          /* a line: 10 of text and a pixel above and below */
    SWATCH = 9,        /* a swatch's side, its 1-pixel frame included */
    SWATCH_GAP = 3,    /* between a swatch and its label */
    ENTRY_GAP = 9,     /* between one entry's label and the next swatch */
};

static const luz_rgba title_colour = {235, 235, 235, 255};
static const luz_rgba label_colour = {200, 200, 200, 255};
static const luz_rgba frame_colour = {150, 150, 150, 255};

static int entry_width(const luz_legend_entry *entry, int scale)
{
    return (SWATCH + SWATCH_GAP) * scale + luz_overlay_text_width(entry->label, scale);
}

luz_rect luz_legend_draw(luz_layer *layer, const luz_legend *legend, int x, int y,
                         int max_width, int scale)
{
    const int line = ROW * scale;
    /* The title, broken at blanks into lines of at most max_width. */
    int width = 0, pen_y = y;
    const char *start = legend->title;
    while (*start != '\0') {
        char piece[128];
        int length = 0, fits = 0;
        for (;;) {
            int end = length;
            while (start[end] == ' ')
                end++;
            while (start[end] != '\0' && start[end] != ' ')
                end++;
            if (end >= (int)sizeof piece)
                break;
            memcpy(piece, start, (size_t)end);
            piece[end] = '\0';
            if (fits > 0 && luz_overlay_text_width(piece, scale) > max_width)
                break;
            fits = end;
            length = end;
            if (start[end] == '\0')
                break;
        }
        if (fits == 0)
            fits = (int)strlen(start) < (int)sizeof piece ? (int)strlen(start)
                                                          : (int)sizeof piece - 1;
        memcpy(piece, start, (size_t)fits);
        piece[fits] = '\0';
        int w = luz_overlay_text_width(piece, scale);
        width = w > width ? w : width;
        if (layer != NULL)
            luz_overlay_text(layer, x, pen_y + scale, scale, piece, title_colour);
        pen_y += line;
        start += fits;
        while (*start == ' ')
            start++;
    }
    int pen_x = x;
    for (int i = 0; i < legend->entry_count; i++) {
        const luz_legend_entry *entry = &legend->entries[i];
        const int w = entry_width(entry, scale);
        /* A new row when this entry would pass the width (never for the
         * first of a row, which is drawn whatever its width). */
        if (pen_x > x && pen_x - x + w > max_width) {
            pen_x = x;
            pen_y += line;
        }
        if (layer != NULL) {
            const int side = SWATCH * scale;
            const int top = pen_y + (line - side) / 2;
            luz_overlay_fill(layer, (luz_rect){pen_x, top, side, side}, frame_colour);
            luz_overlay_fill(layer, (luz_rect){pen_x + scale, top + scale, side - 2 * scale,
                                               side - 2 * scale},
                             (luz_rgba){luz_colour_to_byte(entry->colour.x),
                                        luz_colour_to_byte(entry->colour.y),
                                        luz_colour_to_byte(entry->colour.z), 255});
            luz_overlay_text(layer, pen_x + (SWATCH + SWATCH_GAP) * scale, pen_y + scale, scale,
                             entry->label, label_colour);
        }
        if (pen_x - x + w > width)
            width = pen_x - x + w;
        pen_x += w + ENTRY_GAP * scale;
    }
    const int rows_bottom = legend->entry_count > 0 ? pen_y + line : pen_y;
    return (luz_rect){x, y, width, rows_bottom - y};
}

void luz_legend_draw_in_corner(luz_layer *layer, const luz_legend *legend)
{
    /* Text at twice the size in a large image, as the viewer's HUD. */
    const int scale = (layer->width >= 1000 && layer->height >= 560) ? 2 : 1;
    const int margin = 6 * scale, pad = 5 * scale;
    const int room = layer->width - 2 * margin - 2 * pad;
    const luz_rect size = luz_legend_draw(NULL, legend, 0, 0, room, scale);
    const luz_rect box = {margin, layer->height - margin - size.height - 2 * pad,
                          size.width + 2 * pad, size.height + 2 * pad};
    luz_overlay_fill(layer, box, (luz_rgba){12, 12, 16, 200});
    luz_legend_draw(layer, legend, box.x + pad, box.y + pad, room, scale);
}
