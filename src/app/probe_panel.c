/*
 * probe_panel.c: the viewer's probe panel (probe_panel.h).
 *
 * The panel is a list of rows worked out once from the probe
 * (panel_rows): plain text, a row of swatches, a light term with its bar,
 * the sum with the six bars end to end. The layout and the drawing both
 * read that list, so what is laid out is what is drawn. Numbers show three
 * decimals (depths five): enough to read; luz-render --probe prints them
 * exactly.
 */
#include "app/probe_panel.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* At text scale 1; everything scales with it (the light panel's sizes). */
enum {
    ROW = 12,          /* a row: 10 pixels of text and a gap */
    PAD = 5,           /* inside the box */
    MARGIN = 6,        /* between the box and the framebuffer's edge */
    GAP = 4,           /* between the parts of a row */
    BAR_WIDTH = 120,   /* a bar's full width */
    SHORT_BAR_WIDTH = 96,  /* ... on the light's page of numbers, whose rows
                              are longer: 640x360 keeps the centre in sight */
    SWATCH = 16,       /* a swatch's width; its height is a row's less 3 */
    LABEL = 78,        /* the width of a term's label column */
    MARKER_REACH = 9,  /* the marker's arms reach 8 pixels, its outline 9 */
};

static const luz_rgba text_colour = {235, 235, 235, 255};
static const luz_rgba dim_colour = {150, 150, 150, 255};
static const luz_rgba accent_colour = {255, 210, 120, 255};
/* Opaque: the numbers are read, and stay still when the scene behind moves. */
static const luz_rgba box_colour = {12, 12, 16, 255};
static const luz_rgba track_colour = {45, 45, 52, 255};

luz_rgba luz_probe_term_colour(luz_term term)
{
    static const luz_rgba colours[LUZ_TERM_COUNT] = {
        {120, 130, 160, 255},   /* ambient: a dim blue-grey */
        {240, 200, 60, 255},    /* diffuse: yellow */
        {250, 250, 250, 255},   /* specular: white */
        {240, 120, 40, 255},    /* point: orange */
        {70, 200, 230, 255},    /* spot: cyan */
        {200, 90, 220, 255},    /* directional: violet */
    };
    return (unsigned)term < LUZ_TERM_COUNT ? colours[term] : text_colour;
}

/* ---- the rows -------------------------------------------------------------------- */

typedef enum row_kind {
    ROW_TEXT,
    ROW_SWATCHES,   /* up to three: label, swatch, values */
    ROW_TERM,       /* label, bar, values */
    ROW_LIGHT,      /* label, the six bars end to end, values */
    ROW_LABELLED,   /* label, values in a column after it */
} row_kind;

typedef struct panel_row {
    row_kind kind;
    luz_rgba colour;          /* of the text */
    char text[160];           /* the line, or a term's label */
    char values[96];          /* a term's values */
    int term;
    int swatch_count;
    char swatch_label[3][48];
    luz_rgba swatch[3];
    char swatch_values[3][96];
    luz_probe_swatch swatch_role[3];
    luz_rect swatch_rect[3];  /* where layout_rows puts them */
} panel_row;

typedef struct panel_rows {
    panel_row rows[LUZ_PROBE_PANEL_MAX_ROWS];
    int count;
    int first_history;        /* the row of the first test listed, or count */
    int history_total;        /* the tests there are to list */
    int bar_width;            /* a bar's full width at scale 1 */
} panel_rows;

static panel_row *add_row(panel_rows *rows, row_kind kind, luz_rgba colour)
{
    if (rows->count == LUZ_PROBE_PANEL_MAX_ROWS) return NULL;
    panel_row *row = &rows->rows[rows->count++];
    memset(row, 0, sizeof *row);
    row->kind = kind;
    row->colour = colour;
    return row;
}

static void add_text(panel_rows *rows, luz_rgba colour, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static void add_text(panel_rows *rows, luz_rgba colour, const char *format, ...)
{
    panel_row *row = add_row(rows, ROW_TEXT, colour);
    if (row == NULL) return;
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(row->text, sizeof row->text, format, arguments);
    va_end(arguments);
}

static void add_labelled(panel_rows *rows, luz_rgba colour, const char *label,
                         const char *format, ...) __attribute__((format(printf, 4, 5)));

static void add_labelled(panel_rows *rows, luz_rgba colour, const char *label,
                         const char *format, ...)
{
    panel_row *row = add_row(rows, ROW_LABELLED, colour);
    if (row == NULL) return;
    snprintf(row->text, sizeof row->text, "%s", label);
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(row->values, sizeof row->values, format, arguments);
    va_end(arguments);
}

static luz_rgba swatch_of(luz_vec3 colour)
{
    return (luz_rgba){luz_colour_to_byte(colour.x), luz_colour_to_byte(colour.y),
                      luz_colour_to_byte(colour.z), 255};
}

static void add_swatch(panel_row *row, luz_probe_swatch role, const char *label, luz_rgba colour,
                       const char *values)
{
    if (row == NULL || row->swatch_count == 3) return;
    const int k = row->swatch_count++;
    row->swatch_role[k] = role;
    snprintf(row->swatch_label[k], sizeof row->swatch_label[k], "%s", label);
    row->swatch[k] = colour;
    snprintf(row->swatch_values[k], sizeof row->swatch_values[k], "%s", values);
}

static void format_vec3(char *buffer, size_t size, luz_vec3 v)
{
    snprintf(buffer, size, "%.3f %.3f %.3f", (double)v.x, (double)v.y, (double)v.z);
}

/* "cube 3", "spider.obj mesh 2", "the point light's marker". */
static void describe_source(char *buffer, size_t size, const luz_probe_names *names, int draw,
                            bool long_form)
{
    const luz_probe_source source = luz_probe_source_of(names, draw);
    if (source.object == LUZ_DRAW_POINT_LIGHT)
        snprintf(buffer, size, long_form ? "the point light's marker" : "light marker");
    else if (source.object == LUZ_DRAW_NONE)
        snprintf(buffer, size, "draw %d", draw);
    else if (source.model == NULL)
        snprintf(buffer, size, "cube %d", source.object);
    else if (!long_form)
        snprintf(buffer, size, "object %d mesh %d", source.object, source.mesh);
    else
        snprintf(buffer, size, "object %d: %s mesh %d%s%s%s%s%s", source.object, source.model,
                 source.mesh, source.mesh_name ? " " : "", source.mesh_name ? source.mesh_name : "",
                 source.material_name ? " (" : "",
                 source.material_name ? source.material_name : "",
                 source.material_name ? ")" : "");
}

static void add_view_rows(panel_rows *rows, const luz_pixel_probe *probe)
{
    char detail[96] = "";
    switch (probe->view) {
    case LUZ_VIEW_COLOR:
        return;
    case LUZ_VIEW_DEPTH:
        snprintf(detail, sizeof detail, ": depth buffer %.5f", (double)probe->depth_buffer);
        break;
    case LUZ_VIEW_OVERDRAW:
        snprintf(detail, sizeof detail, ": %lu depth tests", (unsigned long)probe->overdraw);
        break;
    case LUZ_VIEW_BANDS:
        snprintf(detail, sizeof detail, ": band %d, drawn by thread %d", probe->band,
                 probe->worker);
        break;
    case LUZ_VIEW_TRIANGLES:
        if (probe->triangle != 0)
            snprintf(detail, sizeof detail, ": %.2f px from an edge%s",
                     (double)probe->edge_distance,
                     probe->on_edge ? ", a neighbour is another's" : "");
        break;
    default:
        break;
    }
    panel_row *row = add_row(rows, ROW_SWATCHES, text_colour);
    if (row == NULL) return;
    char label[48], values[48];
    snprintf(label, sizeof label, "view %s", luz_view_name(probe->view));
    format_vec3(values, sizeof values, probe->shown);
    add_swatch(row, LUZ_PROBE_SWATCH_SHOWN, label, swatch_of(probe->shown), values);
    if (detail[0] != '\0') add_text(rows, dim_colour, "%s%s", luz_view_name(probe->view), detail);
}

/* compact: the six term rows left out (the light row's bar still shows
 * each term, in its colour, end to end). */
static void story_rows(panel_rows *rows, const luz_pixel_probe *probe,
                       const luz_probe_names *names, bool compact)
{
    char a[96], b[96], c[96];
    if (probe->triangle == 0) {
        add_text(rows, text_colour, "background: no triangle won the pixel");
    } else {
        describe_source(a, sizeof a, names, probe->draw, true);
        /* two numbers for one triangle: its id in the frame (the order
         * of drawing, from 1, as the depth tests below and the
         * visibility buffer count) and its index in its own mesh */
        add_text(rows, text_colour, "%s  drawn triangle #%lu of the frame", a,
                 (unsigned long)probe->triangle);
        if (probe->primitive >= 0) {
            if (probe->clipped_pieces > 0)
                add_text(rows, text_colour,
                         "= its mesh's triangle %d (vertices %lu %lu %lu), clipped: "
                         "piece %d of %d",
                         probe->primitive, (unsigned long)probe->vertices[0],
                         (unsigned long)probe->vertices[1], (unsigned long)probe->vertices[2],
                         probe->piece, probe->clipped_pieces);
            else
                add_text(rows, text_colour, "= its mesh's triangle %d (vertices %lu %lu %lu)",
                         probe->primitive, (unsigned long)probe->vertices[0],
                         (unsigned long)probe->vertices[1], (unsigned long)probe->vertices[2]);
            format_vec3(a, sizeof a, probe->barycentric);
            add_text(rows, text_colour, "barycentric %s  w %.3f  depth %.5f", a,
                     (double)probe->w, (double)probe->depth);
        }
        format_vec3(a, sizeof a, probe->position);
        format_vec3(b, sizeof b, probe->normal);
        add_text(rows, text_colour, "P %s   N %s", a, b);
        add_text(rows, text_colour, "uv %.3f %.3f", (double)probe->uv.x, (double)probe->uv.y);

        if (probe->shading == LUZ_SHADING_UNLIT) {
            add_text(rows, dim_colour, "unlit: its colour is C, no light, no texture");
            panel_row *row = add_row(rows, ROW_SWATCHES, text_colour);
            format_vec3(a, sizeof a, probe->object_colour);
            add_swatch(row, LUZ_PROBE_SWATCH_OBJECT, "C", swatch_of(probe->object_colour), a);
        } else {
            const char *texture =
                luz_probe_texture_name(names, probe->draw, probe->texture);
            if (probe->texture == NULL)
                add_text(rows, text_colour, "texture none: T = 1");
            else
                add_text(rows, text_colour,
                         "texture %s  %s  rho %.3f  lod %.3f  levels %d,%d (%.2f)", texture,
                         luz_filter_name(probe->filter), (double)probe->rho,
                         (double)probe->lambda, probe->levels.lower, probe->levels.upper,
                         (double)probe->levels.blend);
            panel_row *row = add_row(rows, ROW_SWATCHES, text_colour);
            format_vec3(a, sizeof a, probe->texel);
            add_swatch(row, LUZ_PROBE_SWATCH_TEXEL, "T", swatch_of(probe->texel), a);

            for (int term = 0; term < LUZ_TERM_COUNT && !compact; term++) {
                row = add_row(rows, ROW_TERM, text_colour);
                if (row == NULL) break;
                row->term = term;
                snprintf(row->text, sizeof row->text, "%s", luz_term_name((luz_term)term));
                format_vec3(row->values, sizeof row->values, probe->terms[term]);
            }
            row = add_row(rows, ROW_LIGHT, accent_colour);
            if (row != NULL) {
                snprintf(row->text, sizeof row->text, "light");
                format_vec3(row->values, sizeof row->values, probe->light);
            }
            row = add_row(rows, ROW_SWATCHES, text_colour);
            format_vec3(a, sizeof a, probe->object_colour);
            add_swatch(row, LUZ_PROBE_SWATCH_OBJECT, "C", swatch_of(probe->object_colour), a);
            format_vec3(b, sizeof b, probe->colour);
            add_swatch(row, LUZ_PROBE_SWATCH_COLOUR, "light x C x T", swatch_of(probe->colour), b);
        }
    }
    add_view_rows(rows, probe);
    panel_row *row = add_row(rows, ROW_SWATCHES, accent_colour);
    if (probe->triangle != 0 && probe->shading == LUZ_SHADING_LIT &&
        probe->view == LUZ_VIEW_COLOR) {
        /* The output (SCENE.md): light x C x T times 2^EV, then the tone
         * map, whose clamp is the bytes. */
        char label[48];
        snprintf(label, sizeof label, "EV %+.1f %s", (double)probe->exposure,
                 luz_tone_map_name(probe->tone_map));
        format_vec3(a, sizeof a, probe->mapped);
        add_swatch(row, LUZ_PROBE_SWATCH_MAPPED, label, swatch_of(probe->mapped), a);
    }
    snprintf(c, sizeof c, "%u %u %u", probe->bytes[0], probe->bytes[1], probe->bytes[2]);
    add_swatch(row, LUZ_PROBE_SWATCH_BYTES, "bytes",
               (luz_rgba){probe->bytes[0], probe->bytes[1], probe->bytes[2], 255}, c);

    add_text(rows, accent_colour, "%d depth test%s, in draw order%s", probe->test_count,
             probe->test_count == 1 ? "" : "s",
             probe->test_count > 1 ? " (the last that passed won)" : "");
    rows->first_history = rows->count;
    rows->history_total = probe->tests_kept;
    for (int k = 0; k < probe->tests_kept && rows->count < LUZ_PROBE_PANEL_MAX_ROWS; k++) {
        const luz_probe_test *test = &probe->tests[k];
        describe_source(a, sizeof a, names, test->draw, false);
        add_text(rows, test->passed ? text_colour : dim_colour,
                 "%2d %s #%lu  %.5f %s %.5f  %s", k + 1, a,
                 (unsigned long)test->triangle, (double)test->depth, test->passed ? "<" : ">=",
                 (double)test->stored, test->passed ? "pass" : "fail");
    }
}

/* ---- the numbers in between: one page per stage ------------------------------------ */

/* Three numbers, as the panel shows them (format_vec3, without a buffer). */
#define VEC3_ARGS(v) (double)(v).x, (double)(v).y, (double)(v).z

/* The vertex stage (tour step 2): clip = projection x view x model x (P, 1)
 * for each corner; the matrices row by row (docs/cli.md's model_row0 ...). */
static void vertex_rows(panel_rows *rows, const luz_pixel_probe *probe)
{
    add_text(rows, dim_colour, "clip = projection x view x model x (P, 1)");
    const struct {
        const char *name;
        const luz_mat4 *matrix;
    } matrices[3] = {{"model", &probe->model_matrix},
                     {"view", &probe->view_matrix},
                     {"projection", &probe->projection_matrix}};
    for (int k = 0; k < 3; k++)
        for (int row = 0; row < 4; row++) {
            /* column-major: element (row, column) is m[column * 4 + row] */
            const float *m = matrices[k].matrix->m;
            add_labelled(rows, text_colour, row == 0 ? matrices[k].name : "",
                         "%7.3f %7.3f %7.3f %7.3f", (double)m[row], (double)m[4 + row],
                         (double)m[8 + row], (double)m[12 + row]);
        }
    if (probe->primitive < 0) return;
    for (int k = 0; k < 3; k++) {
        char label[32];
        snprintf(label, sizeof label, "clip %d", k);
        add_labelled(rows, text_colour, label, "%.3f %.3f %.3f %.3f",
                     (double)probe->corner_clip[k].x, (double)probe->corner_clip[k].y,
                     (double)probe->corner_clip[k].z, (double)probe->corner_clip[k].w);
    }
}

/* Setup, rasterisation, interpolation and the texture (tour steps 4 to 7). */
static void raster_rows(panel_rows *rows, const luz_pixel_probe *probe,
                        const luz_probe_names *names)
{
    char label[32];
    if (probe->primitive >= 0) {
        for (int k = 0; k < 3; k++) {
            snprintf(label, sizeof label, "window %d", k);
            add_labelled(rows, text_colour, label, "%.3f %.3f %.5f",
                         VEC3_ARGS(probe->corner_window[k]));
        }
        /* the edge functions in 1/256 pixel squared units (probe.h), as
         * the rasteriser compares them with 0 */
        for (int k = 0; k < 3; k++) {
            const luz_probe_edge *edge = &probe->edges[k];
            snprintf(label, sizeof label, "edge %d", k);
            add_labelled(rows, text_colour, label, "%lld%s%s  %s", (long long)edge->value,
                         edge->top ? "  top" : "", edge->left ? "  left" : "",
                         edge->value > 0 || (edge->value == 0 && edge->owns_its_samples)
                             ? "inside"
                         : edge->value == 0 ? "on it, not its"
                                            : "outside");
        }
        add_labelled(rows, text_colour, "barycentric", "%.3f %.3f %.3f",
                     VEC3_ARGS(probe->barycentric));
    }
    add_labelled(rows, text_colour, "w, depth", "%.3f  %.5f", (double)probe->w,
                 (double)probe->depth);
    add_labelled(rows, text_colour, "uv", "%.3f %.3f", (double)probe->uv.x, (double)probe->uv.y);
    add_labelled(rows, text_colour, "uv / dx, dy", "%.4f %.4f   %.4f %.4f", (double)probe->du_dx,
                 (double)probe->dv_dx, (double)probe->du_dy, (double)probe->dv_dy);
    if (probe->shading == LUZ_SHADING_UNLIT) {
        add_text(rows, dim_colour, "unlit: no texture");
        return;
    }
    if (probe->texture == NULL) {
        add_text(rows, text_colour, "texture none: T = 1");
        return;
    }
    add_labelled(rows, text_colour, "texture", "%s  %s",
                 luz_probe_texture_name(names, probe->draw, probe->texture),
                 luz_filter_name(probe->filter));
    add_labelled(rows, text_colour, "rho, lod", "%.3f  %.3f  levels %d,%d (%.2f)",
                 (double)probe->rho, (double)probe->lambda, probe->levels.lower,
                 probe->levels.upper, (double)probe->levels.blend);
    /* two taps a row: trilinear's eight in four rows */
    for (int k = 0; k < probe->tap_count; k += 2) {
        char taps[2][64] = {"", ""};
        for (int j = 0; j < 2 && k + j < probe->tap_count; j++) {
            const luz_probe_tap *tap = &probe->taps[k + j];
            snprintf(taps[j], sizeof taps[j], "L%d %d,%d x%.3f", tap->level, tap->x, tap->y,
                     (double)tap->weight);
        }
        snprintf(label, sizeof label, k == 0 ? "taps" : "");
        add_labelled(rows, text_colour, label, "%s  %s", taps[0], taps[1]);
    }
    add_labelled(rows, text_colour, "T", "%.3f %.3f %.3f", VEC3_ARGS(probe->texel));
}

/* The six terms' intermediates (tour step 8, SCENE.md's names; the font
 * has no dot operator: N.L is dot(N, L)), then the terms and their sum. */
static void light_rows(panel_rows *rows, const luz_pixel_probe *probe, bool compact)
{
    if (probe->shading == LUZ_SHADING_UNLIT) {
        add_text(rows, dim_colour, "unlit: its colour is C, no light");
        return;
    }
    const luz_shade_steps *steps = &probe->steps;
    add_labelled(rows, text_colour, "N", "%.3f %.3f %.3f  |N| %.3f", VEC3_ARGS(probe->normal),
                 (double)steps->normal_length);
    add_labelled(rows, text_colour, "L", "%.3f %.3f %.3f  N.L %.3f", VEC3_ARGS(steps->to_light),
                 (double)steps->n_dot_l);
    add_labelled(rows, text_colour, "V", "%.3f %.3f %.3f", VEC3_ARGS(steps->to_viewer));
    add_labelled(rows, text_colour, "R", "%.3f %.3f %.3f  V.R %.3f", VEC3_ARGS(steps->reflected),
                 (double)steps->v_dot_r);
    add_labelled(rows, text_colour, "Lp", "%.3f %.3f %.3f  N.Lp %.3f",
                 VEC3_ARGS(steps->to_point), (double)steps->n_dot_lp);
    add_labelled(rows, text_colour, "spot", "c %.3f  ci %.3f  co %.3f",
                 (double)steps->spot_cos, (double)steps->spot_cos_inner,
                 (double)steps->spot_cos_outer);
    add_labelled(rows, text_colour, "", "f_dir %.3f  dn %.3f", (double)steps->f_dir,
                 (double)steps->dn);
    add_labelled(rows, text_colour, "", "f_win %.3f  f_dist %.3f", (double)steps->f_win,
                 (double)steps->f_dist);
    add_labelled(rows, text_colour, "sun", "%.3f %.3f %.3f  N.sun %.3f",
                 VEC3_ARGS(steps->to_sun), (double)steps->n_dot_sun);
    for (int term = 0; term < LUZ_TERM_COUNT && !compact; term++) {
        panel_row *row = add_row(rows, ROW_TERM, text_colour);
        if (row == NULL) break;
        row->term = term;
        snprintf(row->text, sizeof row->text, "%s", luz_term_name((luz_term)term));
        format_vec3(row->values, sizeof row->values, probe->terms[term]);
    }
    panel_row *row = add_row(rows, ROW_LIGHT, accent_colour);
    if (row != NULL) {
        snprintf(row->text, sizeof row->text, "light");
        format_vec3(row->values, sizeof row->values, probe->light);
    }
}

static const char *const page_titles[LUZ_PROBE_PAGE_COUNT] = {
    "",
    "  vertex (tour 2)",
    "  raster (tour 4-7)",
    "  light (tour 8)",
};

luz_probe_page luz_probe_page_next(luz_probe_page page, bool back)
{
    const int count = LUZ_PROBE_PAGE_COUNT;
    return (luz_probe_page)((((int)page + (back ? -1 : 1)) % count + count) % count);
}

/* compact: the six term rows left out (the light row's bar still shows
 * each term, in its colour, end to end). */
static void panel_rows_of(panel_rows *rows, const luz_pixel_probe *probe,
                          const luz_probe_names *names, bool frozen, bool compact,
                          luz_probe_page page)
{
    rows->count = 0;
    if ((unsigned)page >= LUZ_PROBE_PAGE_COUNT) page = LUZ_PROBE_PAGE_STORY;
    rows->bar_width = page == LUZ_PROBE_PAGE_STORY ? BAR_WIDTH : SHORT_BAR_WIDTH;
    /* (the pages of numbers are narrower than the story: a short note) */
    add_text(rows, accent_colour, "PROBE %d,%d%s%s", probe->x, probe->y, page_titles[page],
             !frozen                         ? ""
             : page == LUZ_PROBE_PAGE_STORY ? "  (paused: T follows again)"
                                            : "  (paused)");
    /* The bug, as luz-render --probe says it: a quiz's is not told. */
    if (names != NULL && names->scene != NULL && names->scene->bug_hidden)
        add_text(rows, accent_colour, "bug: hidden (quiz)");
    else if (probe->bug != LUZ_BUG_NONE)
        add_text(rows, accent_colour, "bug: %s", luz_bug_name(probe->bug));
    rows->history_total = 0;
    if (!probe->filled) {
        add_text(rows, dim_colour, "outside the image");
    } else if (page == LUZ_PROBE_PAGE_STORY) {
        story_rows(rows, probe, names, compact);
        return;
    } else if (probe->triangle == 0) {
        add_text(rows, text_colour, "background: no triangle won the pixel");
    } else if (page == LUZ_PROBE_PAGE_VERTEX) {
        vertex_rows(rows, probe);
    } else if (page == LUZ_PROBE_PAGE_RASTER) {
        raster_rows(rows, probe, names);
    } else {
        light_rows(rows, probe, compact);
    }
    rows->first_history = rows->count;
}

/* ---- layout ----------------------------------------------------------------------- */

static int swatch_row_width(const panel_row *row, int s)
{
    int width = 0;
    for (int k = 0; k < row->swatch_count; k++)
        width += luz_overlay_text_width(row->swatch_label[k], s) + (2 * GAP + SWATCH) * s +
                 luz_overlay_text_width(row->swatch_values[k], s) + 3 * GAP * s;
    return width;
}

static int row_width(const panel_row *row, int bar_width, int s)
{
    switch (row->kind) {
    case ROW_TEXT:
        return luz_overlay_text_width(row->text, s);
    case ROW_SWATCHES:
        return swatch_row_width(row, s);
    case ROW_TERM:
    case ROW_LIGHT:
        return (LABEL + bar_width + GAP) * s + luz_overlay_text_width(row->values, s);
    case ROW_LABELLED:
        return LABEL * s + luz_overlay_text_width(row->values, s);
    }
    return 0;
}

static float mean(luz_vec3 v)
{
    return (v.x + v.y + v.z) / 3.0f;
}

static int bar_length(float value, float scale, int width)
{
    float fraction = value / scale;
    if (!(fraction > 0.0f)) return 0;
    if (fraction > 1.0f) fraction = 1.0f;
    return (int)lroundf(fraction * (float)width);
}

static bool rects_overlap(luz_rect a, luz_rect b)
{
    return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height &&
           b.y < a.y + a.height;
}

static int widest_row(const panel_rows *rows, int s)
{
    int inner = 0;
    for (int i = 0; i < rows->count; i++) {
        int w = row_width(&rows->rows[i], rows->bar_width, s);
        if (w > inner) inner = w;
    }
    return inner;
}

/* compact: panel_rows_of's, and the history cut to keep the box within
 * half the frame's area. */
static luz_probe_panel_layout layout_rows(int width, int height, const luz_pixel_probe *probe,
                                          panel_rows *rows, bool compact, int s)
{
    luz_probe_panel_layout layout;
    memset(&layout, 0, sizeof layout);
    layout.scale = s;
    layout.row_height = ROW * s;
    layout.compact = compact;

    /* History rows that do not fit under the rest are left out (and
     * counted in a last row); compact, also those that would take the box
     * past half the frame's area, and all of them if not one fits. */
    int room = (height - 2 * MARGIN * s - 2 * PAD * s) / layout.row_height;
    if (compact) {
        const int box_width = widest_row(rows, s) + 2 * PAD * s;
        const int half = (int)((long long)width * height / 2 / box_width);
        const int rows_in_half = (half - 2 * PAD * s) / layout.row_height;
        if (rows_in_half < room) room = rows_in_half;
        if (room <= rows->first_history && rows->count > rows->first_history &&
            rows->first_history > 0) {
            rows->count = rows->first_history;
            panel_row *header = &rows->rows[rows->first_history - 1];
            snprintf(header->text, sizeof header->text, "%d depth test%s (listed in a larger window)",
                     probe->test_count, probe->test_count == 1 ? "" : "s");
        }
    }
    layout.history_rows = rows->count - rows->first_history;
    if (rows->count > room && room > rows->first_history) {
        rows->count = room - 1;
        layout.history_rows = rows->count - rows->first_history;
        panel_row *more = add_row(rows, ROW_TEXT, dim_colour);
        if (more)
            snprintf(more->text, sizeof more->text, "... and %d more",
                     rows->history_total - layout.history_rows);
    }
    layout.row_count = rows->count;

    const int inner = widest_row(rows, s);
    const int box_height = rows->count * layout.row_height + 2 * PAD * s;
    layout.box = (luz_rect){MARGIN * s, height - MARGIN * s - box_height, inner + 2 * PAD * s,
                            box_height};
    /* The panel must not hide the pixel it explains, nor its marker: if the
     * bottom-left corner would, the bottom-right one, if that does not,
     * else the top-right one (away from the HUD). A pixel that both bottom
     * corners hide lies in both boxes' columns, so the two top corners
     * hide it alike. */
    const luz_rect around = {probe->x - MARKER_REACH, probe->y - MARKER_REACH,
                             2 * MARKER_REACH + 1, 2 * MARKER_REACH + 1};
    if (rects_overlap(layout.box, around)) {
        const int right = width - MARGIN * s - layout.box.width, top = MARGIN * s;
        const int corners[2][2] = {{right, layout.box.y}, {right, top}};
        for (int k = 0; k < 2; k++) {
            luz_rect moved = layout.box;
            moved.x = corners[k][0];
            moved.y = corners[k][1];
            if (!rects_overlap(moved, around)) {
                layout.box = moved;
                break;
            }
        }
    }

    /* The swatches, after their labels. */
    for (int i = 0; i < rows->count; i++) {
        panel_row *row = &rows->rows[i];
        const int y = layout.box.y + PAD * s + i * layout.row_height + s;
        int pen = layout.box.x + PAD * s;
        for (int k = 0; k < row->swatch_count; k++) {
            pen += luz_overlay_text_width(row->swatch_label[k], s) + GAP * s;
            row->swatch_rect[k] = (luz_rect){pen, y - s, SWATCH * s, (ROW - 3) * s};
            layout.swatch[row->swatch_role[k]] = row->swatch_rect[k];
            pen += (SWATCH + GAP) * s + luz_overlay_text_width(row->swatch_values[k], s) +
                   3 * GAP * s;
        }
    }

    /* The bars: a term's mean channel, on a scale of at least 1, so that
     * the sum of a bright pixel still fits. */
    layout.bar_width = rows->bar_width * s;
    layout.bar_scale = mean(probe->light) > 1.0f ? mean(probe->light) : 1.0f;
    const int bar_height = (ROW - 4) * s;
    for (int i = 0; i < rows->count; i++) {
        const panel_row *row = &rows->rows[i];
        if (row->kind != ROW_TERM && row->kind != ROW_LIGHT) continue;
        const int top = layout.box.y + PAD * s + i * layout.row_height + s;
        const int left = layout.box.x + (PAD + LABEL) * s;
        if (row->kind == ROW_TERM) {
            layout.term_bar[row->term] =
                (luz_rect){left, top,
                           bar_length(mean(probe->terms[row->term]), layout.bar_scale,
                                      layout.bar_width),
                           bar_height};
            continue;
        }
        int pen = left;
        for (int term = 0; term < LUZ_TERM_COUNT; term++) {
            int length = bar_length(mean(probe->terms[term]), layout.bar_scale, layout.bar_width);
            if (pen + length > left + layout.bar_width) length = left + layout.bar_width - pen;
            layout.light_bar[term] = (luz_rect){pen, top, length, bar_height};
            pen += length;
        }
    }
    return layout;
}

/* The whole story, or, where its box would cover more than half the
 * frame's area, the compact one. */
static luz_probe_panel_layout rows_and_layout(panel_rows *rows, int width, int height,
                                              const luz_pixel_probe *probe,
                                              const luz_probe_names *names, bool frozen,
                                              luz_probe_page page)
{
    /* The text at twice the size where the whole story fits so (issue 31:
     * at 1280x720 the pixel font's 6 pixels were hard to read): every row
     * listed, the box within the frame and within half its area, and in
     * a corner that leaves the pixel and its marker in sight. */
    const long long half = (long long)width * height / 2;
    panel_rows_of(rows, probe, names, frozen, false, page);
    const int all_rows = rows->count;
    luz_probe_panel_layout layout = layout_rows(width, height, probe, rows, false, 2);
    const luz_rect around = {probe->x - MARKER_REACH, probe->y - MARKER_REACH,
                             2 * MARKER_REACH + 1, 2 * MARKER_REACH + 1};
    if (rows->count == all_rows && (long long)layout.box.width * layout.box.height <= half &&
        layout.box.x >= 0 && layout.box.y >= 0 && layout.box.x + layout.box.width <= width &&
        !rects_overlap(layout.box, around))
        return layout;
    panel_rows_of(rows, probe, names, frozen, false, page);
    layout = layout_rows(width, height, probe, rows, false, 1);
    if ((long long)layout.box.width * layout.box.height <= half)
        return layout;
    panel_rows_of(rows, probe, names, frozen, true, page);
    return layout_rows(width, height, probe, rows, true, 1);
}

luz_probe_panel_layout luz_probe_panel_layout_for(int width, int height,
                                                  const luz_pixel_probe *probe,
                                                  const luz_probe_names *names, bool frozen,
                                              luz_probe_page page)
{
    luz_probe_panel_layout layout;
    memset(&layout, 0, sizeof layout);
    panel_rows *rows = malloc(sizeof *rows);
    if (rows == NULL) return layout;
    layout = rows_and_layout(rows, width, height, probe, names, frozen, page);
    free(rows);
    return layout;
}

/* ---- drawing ----------------------------------------------------------------------- */

static void draw_swatch(luz_layer *layer, luz_rect swatch, int s, luz_rgba colour)
{
    luz_overlay_fill(layer, (luz_rect){swatch.x - s, swatch.y - s, swatch.width + 2 * s,
                                       swatch.height + 2 * s},
                     (luz_rgba){150, 150, 150, 255});
    luz_overlay_fill(layer, swatch, colour);
}

void luz_probe_panel_draw(luz_layer *layer, const luz_pixel_probe *probe,
                          const luz_probe_names *names, bool frozen, luz_probe_page page)
{
    panel_rows *rows = malloc(sizeof *rows);
    if (rows == NULL) return;
    const luz_probe_panel_layout layout =
        rows_and_layout(rows, layer->width, layer->height, probe, names, frozen, page);
    const int s = layout.scale;
    luz_overlay_fill(layer, layout.box, box_colour);
    const char *hint = "E: mode  U: more  Shift+E: close";
    const int hint_width = luz_overlay_text_width(hint, s);

    const int x = layout.box.x + PAD * s;
    for (int i = 0; i < rows->count; i++) {
        const panel_row *row = &rows->rows[i];
        const int y = layout.box.y + PAD * s + i * layout.row_height + s;
        switch (row->kind) {
        case ROW_TEXT:
            luz_overlay_text(layer, x, y, s, row->text, row->colour);
            break;
        case ROW_LABELLED:
            luz_overlay_text(layer, x, y, s, row->text, dim_colour);
            luz_overlay_text(layer, x + LABEL * s, y, s, row->values, row->colour);
            break;
        case ROW_SWATCHES:
            for (int k = 0; k < row->swatch_count; k++) {
                const luz_rect swatch = row->swatch_rect[k];
                luz_overlay_text(layer, swatch.x - GAP * s -
                                            luz_overlay_text_width(row->swatch_label[k], s),
                                 y, s, row->swatch_label[k], row->colour);
                draw_swatch(layer, swatch, s, row->swatch[k]);
                luz_overlay_text(layer, swatch.x + swatch.width + GAP * s, y, s,
                                 row->swatch_values[k], row->colour);
            }
            break;
        case ROW_TERM:
        case ROW_LIGHT: {
            luz_overlay_text(layer, x, y, s, row->text, row->colour);
            const int left = x + LABEL * s;
            luz_overlay_fill(layer,
                             (luz_rect){left, y, layout.bar_width, (ROW - 4) * s}, track_colour);
            if (row->kind == ROW_TERM)
                luz_overlay_fill(layer, layout.term_bar[row->term],
                                 luz_probe_term_colour((luz_term)row->term));
            else
                for (int term = 0; term < LUZ_TERM_COUNT; term++)
                    luz_overlay_fill(layer, layout.light_bar[term],
                                     luz_probe_term_colour((luz_term)term));
            luz_overlay_text(layer, left + layout.bar_width + GAP * s, y, s, row->values,
                             row->colour);
            break;
        }
        }
        /* the hint at the right of the title */
        if (i == 0 && layout.box.width - 2 * PAD * s >=
                          luz_overlay_text_width(row->text, s) + hint_width + 2 * GAP * s)
            luz_overlay_text(layer, layout.box.x + layout.box.width - PAD * s - hint_width, y, s,
                             hint, dim_colour);
    }
    free(rows);
}

void luz_probe_marker_draw(luz_layer *layer, int x, int y)
{
    /* Four arms, from 3 to 8 pixels off the pixel, yellow on black
     * (MARKER_REACH). */
    const luz_rgba outline = {0, 0, 0, 255}, core = {255, 230, 40, 255};
    const luz_rect arms[4] = {
        {x - 8, y, 6, 1}, {x + 3, y, 6, 1}, {x, y - 8, 1, 6}, {x, y + 3, 1, 6},
    };
    for (int i = 0; i < 4; i++)
        luz_overlay_fill(layer, (luz_rect){arms[i].x - 1, arms[i].y - 1, arms[i].width + 2,
                                           arms[i].height + 2},
                         outline);
    for (int i = 0; i < 4; i++) luz_overlay_fill(layer, arms[i], core);
}

int luz_probe_panel_text(const luz_pixel_probe *probe, const luz_probe_names *names,
                         bool frozen, luz_probe_page page, char (*lines)[LUZ_PROBE_PANEL_LINE],
                         int max_lines)
{
    panel_rows *rows = malloc(sizeof *rows);
    if (rows == NULL) return 0;
    panel_rows_of(rows, probe, names, frozen, false, page);
    for (int i = 0; i < rows->count && i < max_lines; i++) {
        const panel_row *row = &rows->rows[i];
        switch (row->kind) {
        case ROW_TEXT:
            snprintf(lines[i], LUZ_PROBE_PANEL_LINE, "%s", row->text);
            break;
        case ROW_SWATCHES: {
            int used = 0;
            lines[i][0] = '\0';
            for (int k = 0; k < row->swatch_count && used < LUZ_PROBE_PANEL_LINE; k++)
                used += snprintf(lines[i] + used, (size_t)(LUZ_PROBE_PANEL_LINE - used),
                                 "%s%s %s", k ? "  " : "", row->swatch_label[k],
                                 row->swatch_values[k]);
            break;
        }
        default:
            snprintf(lines[i], LUZ_PROBE_PANEL_LINE, "%s %s", row->text, row->values);
            break;
        }
    }
    const int count = rows->count;
    free(rows);
    return count;
}
