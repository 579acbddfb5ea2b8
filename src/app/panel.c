/*
 * panel.c: the light panel, the HUD and the help overlay (see app/panel.h).
 *
 * Everything is computed from plain data: the slider table below says
 * which field of luz_lights each slider edits and over what range, the
 * layout is a function of the framebuffer's size, and the mouse and the
 * arrow keys edit luz_lights through luz_slider_set(). Drawing comes last
 * and reads the same layout, so what is hit-tested is what is drawn.
 *
 * A light's block in the panel:
 *
 *     1 ambient                 [swatch]  on     <- click to switch
 *     r [====--] 0.60  g [==] 0.60  b [==] 0.60
 *     strength [=======-----------]      0.20
 *
 * then shininess after the specular light, inner, outer and reach after
 * the spot; last, the output's exposure and tone map.
 */
#include "app/panel.h"
#include "luz/view.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* ---- the sliders ------------------------------------------------------------------ */

#define COLOUR_SLIDERS(term)                                                     \
    {term, LUZ_SLIDER_RED, "r", 0.0f, 1.0f, 0.05f, 0.01f},                       \
    {term, LUZ_SLIDER_GREEN, "g", 0.0f, 1.0f, 0.05f, 0.01f},                     \
    {term, LUZ_SLIDER_BLUE, "b", 0.0f, 1.0f, 0.05f, 0.01f},                      \
    {term, LUZ_SLIDER_STRENGTH, "strength", 0.0f, 1.0f, 0.05f, 0.01f}

const luz_slider luz_panel_sliders[LUZ_PANEL_SLIDER_COUNT] = {
    COLOUR_SLIDERS(LUZ_TERM_AMBIENT),
    COLOUR_SLIDERS(LUZ_TERM_DIFFUSE),
    COLOUR_SLIDERS(LUZ_TERM_SPECULAR),
    {LUZ_TERM_SPECULAR, LUZ_SLIDER_SHININESS, "shininess", 0.0f, 128.0f, 4.0f, 1.0f},
    COLOUR_SLIDERS(LUZ_TERM_POINT),
    COLOUR_SLIDERS(LUZ_TERM_SPOT),
    {LUZ_TERM_SPOT, LUZ_SLIDER_SPOT_INNER, "inner", 0.0f, LUZ_SPOT_ANGLE_MAX, 1.0f, 0.1f},
    {LUZ_TERM_SPOT, LUZ_SLIDER_SPOT_OUTER, "outer", 0.0f, LUZ_SPOT_ANGLE_MAX, 1.0f, 0.1f},
    /* The reach stays within the options' range, 0.1 to 10000 (the spot
     * divides by it). */
    {LUZ_TERM_SPOT, LUZ_SLIDER_SPOT_REACH, "reach", 0.5f, 30.0f, 0.5f, 0.1f},
    COLOUR_SLIDERS(LUZ_TERM_DIRECTIONAL),
};

/* The float a slider edits. */
static float *slider_field(luz_lights *lights, const luz_slider *slider)
{
    luz_light *light = luz_lights_term(lights, slider->term);
    switch (slider->field) {
    case LUZ_SLIDER_RED: return &light->colour.x;
    case LUZ_SLIDER_GREEN: return &light->colour.y;
    case LUZ_SLIDER_BLUE: return &light->colour.z;
    case LUZ_SLIDER_STRENGTH: return &light->strength;
    case LUZ_SLIDER_SHININESS: return &lights->shininess;
    case LUZ_SLIDER_SPOT_INNER: return &lights->spot_inner_degrees;
    case LUZ_SLIDER_SPOT_OUTER: return &lights->spot_outer_degrees;
    case LUZ_SLIDER_SPOT_REACH: return &lights->spot_reach;
    }
    return &light->strength;
}

float luz_slider_value(const luz_lights *lights, int slider)
{
    return *slider_field((luz_lights *)lights, &luz_panel_sliders[slider]);
}

void luz_slider_set(luz_lights *lights, int slider, float value)
{
    const luz_slider *spec = &luz_panel_sliders[slider];
    if (!(value >= spec->min)) value = spec->min;   /* NaN lands on min */
    if (value > spec->max) value = spec->max;
    if (spec->field == LUZ_SLIDER_SPOT_INNER)
        luz_spot_set_inner(lights, value);
    else if (spec->field == LUZ_SLIDER_SPOT_OUTER)
        luz_spot_set_outer(lights, value);
    else
        *slider_field(lights, spec) = value;
}

void luz_slider_step(luz_lights *lights, int slider, int direction, bool fine)
{
    const luz_slider *spec = &luz_panel_sliders[slider];
    float step = fine ? spec->fine_step : spec->step;
    float value = luz_slider_value(lights, slider) + (float)direction * step;
    luz_slider_set(lights, slider, roundf(value / step) * step);
}

/* ---- layout ---------------------------------------------------------------------------- */

/* Whole rows of the panel at text scale 1; everything scales with it. */
enum {
    ROW = 12,            /* row height: 10 of text and a pixel above and below */
    PAD = 5,             /* inside the panel's box */
    MARGIN = 6,          /* between the box and the framebuffer's edge */
    GAP = 3,             /* between a label, its track and its value */
    INNER_WIDTH = 200,   /* the box's width without its padding */
    ROW_COUNT = 1 + LUZ_TERM_COUNT * 3 + 4 + 1,   /* title, 3 per light, 4 extras,
                                                     the output */
    MIN_ROW = 9,         /* the shortest row, in a short window: the 7-pixel
                            capitals and a gap; descenders touch the next row */
};

/* The panel's box height with rows of `row` pixels at text scale `scale`. */
static int panel_height(int row, int scale)
{
    return ROW_COUNT * row + 2 * PAD * scale;
}

void luz_panel_init(luz_panel *panel)
{
    *panel = (luz_panel){.focus = 0, .dragging = -1};
}

/* A row's label, track and value, left to right, in `area`. */
static void layout_slider(luz_panel_layout *layout, int slider, luz_rect area, int label_width,
                          int value_width)
{
    int gap = GAP * layout->scale;
    int track_height = 6 * layout->scale;
    layout->row[slider] = area;
    layout->track[slider] = (luz_rect){
        area.x + label_width + gap,
        area.y + (area.height - track_height) / 2,
        area.width - label_width - value_width - 2 * gap,
        track_height,
    };
}

luz_panel_layout luz_panel_layout_for(int width, int height)
{
    luz_panel_layout layout;
    memset(&layout, 0, sizeof layout);
    bool room_for_2 = height >= panel_height(ROW * 2, 2) + 2 * MARGIN * 2 &&
                      width >= 3 * INNER_WIDTH * 2;
    int s = room_for_2 ? 2 : 1;
    layout.scale = s;
    int row = ROW * s;
    /* A window too short for the whole panel at scale 1 (below 298
     * pixels, such as 480x270) gets shorter rows, down to MIN_ROW, so
     * that every slider stays on screen. */
    if (s == 1 && height < panel_height(ROW, 1) + 2 * MARGIN) {
        int fits = (height - 2 * MARGIN - 2 * PAD) / ROW_COUNT;
        row = fits < MIN_ROW ? MIN_ROW : fits;
    }
    int inner = INNER_WIDTH * s;
    layout.box = (luz_rect){width - inner - (2 * PAD + MARGIN) * s, MARGIN * s, inner + 2 * PAD * s,
                            panel_height(row, s)};
    int x = layout.box.x + PAD * s;
    int y = layout.box.y + PAD * s;

    layout.title = (luz_rect){x, y, inner, row};
    y += row;

    int value_width = luz_overlay_text_width("0.00", s);
    int wide_label = luz_overlay_text_width("shininess", s);
    int wide_value = luz_overlay_text_width("100.0", s);
    int group_gap = 3 * GAP * s;   /* between the r, g and b groups */
    int third = (inner - 2 * group_gap) / 3;
    for (int slider = 0; slider < LUZ_PANEL_SLIDER_COUNT; slider++) {
        const luz_slider *spec = &luz_panel_sliders[slider];
        if (spec->field == LUZ_SLIDER_RED) {   /* a light's block starts */
            layout.header[spec->term] = (luz_rect){x, y, inner, row};
            y += row;
        }
        switch (spec->field) {
        case LUZ_SLIDER_RED:   /* red, green and blue share a row */
        case LUZ_SLIDER_GREEN:
        case LUZ_SLIDER_BLUE: {
            int column = (int)(spec->field - LUZ_SLIDER_RED);
            int left = x + column * (third + group_gap);
            int right = column == 2 ? x + inner : left + third;
            luz_rect area = {left, y, right - left, row};
            layout_slider(&layout, slider, area, luz_overlay_text_width("g", s), value_width);
            if (spec->field == LUZ_SLIDER_BLUE)
                y += row;
            break;
        }
        default:
            layout_slider(&layout, slider, (luz_rect){x, y, inner, row}, wide_label, wide_value);
            y += row;
            break;
        }
    }
    layout.output = (luz_rect){x, y, inner, row};
    return layout;
}

float luz_panel_track_value(const luz_panel_layout *layout, int slider, int x)
{
    const luz_slider *spec = &luz_panel_sliders[slider];
    luz_rect track = layout->track[slider];
    float fraction = track.width > 1 ? (float)(x - track.x) / (float)(track.width - 1) : 0.0f;
    if (fraction < 0.0f) fraction = 0.0f;
    if (fraction > 1.0f) fraction = 1.0f;
    float value = spec->min + fraction * (spec->max - spec->min);
    return roundf(value / spec->fine_step) * spec->fine_step;
}

/* ---- input ------------------------------------------------------------------------------ */

void luz_panel_key_press(luz_panel *panel, luz_lights *lights, luz_panel_key key, bool fine)
{
    switch (key) {
    case LUZ_PANEL_UP:
        panel->focus = (panel->focus + LUZ_PANEL_SLIDER_COUNT - 1) % LUZ_PANEL_SLIDER_COUNT;
        break;
    case LUZ_PANEL_DOWN:
        panel->focus = (panel->focus + 1) % LUZ_PANEL_SLIDER_COUNT;
        break;
    case LUZ_PANEL_LEFT:
        luz_slider_step(lights, panel->focus, -1, fine);
        break;
    case LUZ_PANEL_RIGHT:
        luz_slider_step(lights, panel->focus, +1, fine);
        break;
    }
}

bool luz_panel_mouse_press(luz_panel *panel, const luz_panel_layout *layout, luz_lights *lights,
                           luz_light_switches *switches, int x, int y)
{
    if (!luz_rect_contains(layout->box, x, y))
        return false;
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        if (luz_rect_contains(layout->header[term], x, y)) {
            luz_light_toggle(lights, switches, (luz_term)term);
            return true;
        }
    }
    for (int slider = 0; slider < LUZ_PANEL_SLIDER_COUNT; slider++) {
        if (!luz_rect_contains(layout->row[slider], x, y))
            continue;
        panel->focus = slider;
        /* The track is thin: a press anywhere in its column of the row
         * (not on the label or the value) takes it. */
        luz_rect track = layout->track[slider];
        if (x >= track.x && x < track.x + track.width) {
            panel->dragging = slider;
            luz_slider_set(lights, slider, luz_panel_track_value(layout, slider, x));
        }
        return true;
    }
    return true;
}

void luz_panel_mouse_drag(luz_panel *panel, const luz_panel_layout *layout, luz_lights *lights,
                          int x)
{
    if (panel->dragging >= 0)
        luz_slider_set(lights, panel->dragging, luz_panel_track_value(layout, panel->dragging, x));
}

void luz_panel_mouse_release(luz_panel *panel)
{
    panel->dragging = -1;
}

/* ---- drawing ----------------------------------------------------------------------------- */

static const luz_rgba text_colour = {235, 235, 235, 255};
static const luz_rgba dim_text_colour = {130, 130, 130, 255};
static const luz_rgba accent_colour = {255, 210, 120, 255};
static const luz_rgba box_colour = {12, 12, 16, 190};

static uint8_t to_byte(float value)
{
    return luz_colour_to_byte(value);
}

/* Text centred vertically in a row; returns its width. */
static int row_text(luz_layer *layer, int x, luz_rect row, int scale, const char *text,
                    luz_rgba colour)
{
    int top = row.y + (row.height - luz_overlay_text_height(scale)) / 2 + scale;
    return luz_overlay_text(layer, x, top, scale, text, colour);
}

static luz_rgba fill_colour(const luz_slider *spec, const luz_light *light)
{
    switch (spec->field) {
    case LUZ_SLIDER_RED: return (luz_rgba){220, 60, 60, 255};
    case LUZ_SLIDER_GREEN: return (luz_rgba){60, 190, 70, 255};
    case LUZ_SLIDER_BLUE: return (luz_rgba){70, 110, 235, 255};
    case LUZ_SLIDER_STRENGTH: {
        /* The light's own colour, lifted a little so that a dark light's
         * bar still shows against the track. */
        luz_rgba colour = {to_byte(light->colour.x), to_byte(light->colour.y),
                           to_byte(light->colour.z), 255};
        if (colour.r < 60 && colour.g < 60 && colour.b < 60)
            colour = (luz_rgba){90, 90, 90, 255};
        return colour;
    }
    default:
        return (luz_rgba){200, 200, 200, 255};
    }
}

static void draw_slider(luz_layer *layer, const luz_panel_layout *layout,
                        const luz_panel *panel, const luz_lights *lights, int slider)
{
    const luz_slider *spec = &luz_panel_sliders[slider];
    const luz_light *light = luz_lights_term((luz_lights *)lights, spec->term);
    int s = layout->scale;
    luz_rect row = layout->row[slider], track = layout->track[slider];
    bool focused = panel->focus == slider;
    if (focused)
        luz_overlay_fill(layer, (luz_rect){row.x - s, row.y, row.width + 2 * s, row.height},
                         (luz_rgba){70, 90, 150, 200});

    row_text(layer, row.x, row, s, spec->label, focused ? accent_colour : text_colour);

    float value = luz_slider_value(lights, slider);
    float fraction = (value - spec->min) / (spec->max - spec->min);
    if (!(fraction > 0.0f)) fraction = 0.0f;
    if (fraction > 1.0f) fraction = 1.0f;
    int filled = (int)lroundf(fraction * (float)track.width);
    luz_overlay_fill(layer, track, (luz_rgba){55, 55, 60, 255});
    luz_overlay_fill(layer, (luz_rect){track.x, track.y, filled, track.height},
                     fill_colour(spec, light));

    char text[32];
    if (spec->field == LUZ_SLIDER_SHININESS)
        snprintf(text, sizeof text, "%.0f", (double)value);
    else if (spec->field >= LUZ_SLIDER_SPOT_INNER)
        snprintf(text, sizeof text, "%.1f", (double)value);
    else
        snprintf(text, sizeof text, "%.2f", (double)value);
    int width = luz_overlay_text_width(text, s);
    row_text(layer, row.x + row.width - width, row, s, text, text_colour);
}

static void draw_header(luz_layer *layer, const luz_panel_layout *layout,
                        const luz_lights *lights, luz_term term)
{
    int s = layout->scale;
    luz_rect header = layout->header[term];
    const luz_light *light = luz_lights_term((luz_lights *)lights, term);
    bool on = luz_light_is_on(lights, term);

    char name[32];
    snprintf(name, sizeof name, "%d %s", (int)term + 1, luz_term_name(term));
    row_text(layer, header.x, header, s, name, on ? text_colour : dim_text_colour);

    /* The swatch: the light's colour, and beside it that colour at its
     * strength, which is what reaches the cubes. */
    const char *state = on ? "on" : "off";
    int state_width = luz_overlay_text_width("off", s);
    int swatch_width = 24 * s, swatch_height = 8 * s;
    luz_rect swatch = {header.x + header.width - state_width - GAP * s - swatch_width,
                       header.y + (header.height - swatch_height) / 2, swatch_width, swatch_height};
    luz_overlay_fill(layer, (luz_rect){swatch.x - s, swatch.y - s, swatch.width + 2 * s,
                                             swatch.height + 2 * s},
                     (luz_rgba){150, 150, 150, 255});
    luz_vec3 colour = light->colour;
    luz_overlay_fill(layer, (luz_rect){swatch.x, swatch.y, swatch.width / 2, swatch.height},
                     (luz_rgba){to_byte(colour.x), to_byte(colour.y), to_byte(colour.z), 255});
    luz_vec3 lit = luz_vec3_scale(colour, light->strength);
    luz_overlay_fill(layer,
                     (luz_rect){swatch.x + swatch.width / 2, swatch.y,
                                swatch.width - swatch.width / 2, swatch.height},
                     (luz_rgba){to_byte(lit.x), to_byte(lit.y), to_byte(lit.z), 255});
    row_text(layer, header.x + header.width - state_width, header, s, state,
             on ? accent_colour : dim_text_colour);
}

void luz_panel_draw(luz_layer *layer, const luz_panel_layout *layout,
                    const luz_panel *panel, const luz_lights *lights, luz_output output)
{
    int s = layout->scale;
    luz_overlay_fill(layer, layout->box, box_colour);
    row_text(layer, layout->title.x, layout->title, s, "LIGHTS", accent_colour);
    const char *hint = "Tab: fly  H: help";
    row_text(layer, layout->title.x + layout->title.width - luz_overlay_text_width(hint, s),
             layout->title, s, hint, dim_text_colour);
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        draw_header(layer, layout, lights, (luz_term)term);
    for (int slider = 0; slider < LUZ_PANEL_SLIDER_COUNT; slider++)
        draw_slider(layer, layout, panel, lights, slider);

    /* The output: "EV -1.0  neutral", the keys on the right. */
    char text[48];
    snprintf(text, sizeof text, "EV %+.1f  %s", (double)output.exposure,
             luz_tone_map_name(output.tone_map));
    const luz_rect row = layout->output;
    const int label_width = row_text(layer, row.x, row, s, "output", text_colour);
    row_text(layer, row.x + label_width + 2 * GAP * s, row, s, text, accent_colour);
    const char *keys = "[ ] N";
    row_text(layer, row.x + row.width - luz_overlay_text_width(keys, s), row, s, keys,
             dim_text_colour);
}

/* ---- HUD timings ------------------------------------------------------------------------------- */

bool luz_hud_timing_add(luz_hud_timing *timing, double seconds, double geometry_ms,
                        double raster_ms)
{
    if (!(seconds > 0.0))   /* the first frame, or one after a pause in time */
        return false;
    timing->window_frames++;
    timing->window_seconds += seconds;
    timing->window_geometry_ms += geometry_ms;
    timing->window_raster_ms += raster_ms;
    if (timing->window_seconds < LUZ_HUD_AVERAGE_SECONDS)
        return false;
    const double frames = (double)timing->window_frames;
    timing->frames_per_second = frames / timing->window_seconds;
    timing->frame_ms = 1000.0 * timing->window_seconds / frames;
    timing->geometry_ms = timing->window_geometry_ms / frames;
    timing->raster_ms = timing->window_raster_ms / frames;
    timing->window_frames = 0;
    timing->window_seconds = timing->window_geometry_ms = timing->window_raster_ms = 0.0;
    return true;
}

/* ---- HUD -------------------------------------------------------------------------------------- */

/* Scale 2 where the layer is big enough for it to stay a corner. */
static int hud_scale(const luz_layer *layer)
{
    return (layer->width >= 1000 && layer->height >= 560) ? 2 : 1;
}

void luz_hud_draw_message(luz_layer *layer, const char *message)
{
    int s = hud_scale(layer);
    int line = ROW * s;
    luz_rect box = {MARGIN * s, layer->height - MARGIN * s - line - 2 * PAD * s,
                    luz_overlay_text_width(message, s) + 2 * PAD * s, line + 2 * PAD * s};
    luz_overlay_fill(layer, box, box_colour);
    luz_overlay_text(layer, box.x + PAD * s, box.y + PAD * s + s, s, message, accent_colour);
}

/* The HUD's text as pieces that stay whole: a line of the HUD is broken
 * between pieces, never inside one, when the HUD's box is too narrow for
 * it (a small window, or the panel open beside it). */
enum { HUD_MAX_PIECES = 40, HUD_PIECE_SIZE = 96 };

typedef struct hud_piece {
    char text[HUD_PIECE_SIZE];
    luz_rgba colour;
    bool starts_line;   /* the first piece of one of the HUD's lines */
    int x, y;           /* where it is drawn, relative to the text's corner */
} hud_piece;

typedef struct hud_text {
    hud_piece pieces[HUD_MAX_PIECES];
    int count;
} hud_text;

static void hud_add(hud_text *text, bool starts_line, luz_rgba colour, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

static void hud_add(hud_text *text, bool starts_line, luz_rgba colour, const char *format, ...)
{
    if (text->count >= HUD_MAX_PIECES)
        return;
    hud_piece *piece = &text->pieces[text->count++];
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(piece->text, sizeof piece->text, format, arguments);
    va_end(arguments);
    piece->colour = colour;
    piece->starts_line = starts_line;
}

/* Places the pieces in lines at most max_width wide; returns the width
 * used and sets *height. Pieces of a line are two blanks apart; a piece
 * that does not fit starts a line of its own, indented by one blank. */
static int hud_flow(hud_text *text, int scale, int max_width, int *height)
{
    const int line = ROW * scale;
    const int gap = luz_overlay_text_width("  ", scale);
    const int indent = luz_overlay_text_width(" ", scale);
    int x = 0, y = -line, width = 0;
    for (int i = 0; i < text->count; i++) {
        hud_piece *piece = &text->pieces[i];
        int w = luz_overlay_text_width(piece->text, scale);
        if (piece->starts_line) {
            x = 0;
            y += line;
        } else if (x + gap + w > max_width) {
            x = indent;
            y += line;
        } else {
            x += gap;
        }
        piece->x = x;
        piece->y = y;
        x += w;
        if (x > width)
            width = x;
    }
    *height = y + line;
    return width;
}

/* value as printf shows it with `decimals` digits, but a value that
 * rounds to zero is 0: "camera 0.00", never "-0.00" for -0.001. */
static double shown(double value, int decimals)
{
    return fabs(value) < 0.5 * pow(10.0, -decimals) ? 0.0 : value;
}

void luz_hud_draw(luz_layer *layer, const luz_hud *hud)
{
    const luz_scene *scene = hud->scene;
    const luz_camera *camera = &scene->camera;
    hud_text text;
    text.count = 0;

    /* The frame's time and the renderer's share of it, averaged over the
     * same frames (luz_hud_timing), so that the two can be compared. */
    hud_add(&text, true, accent_colour, "%.1f fps", hud->frames_per_second);
    hud_add(&text, false, accent_colour, "%.1f ms/frame", hud->frame_ms);
    hud_add(&text, true, text_colour, "geometry %.2f ms", hud->geometry_ms);
    hud_add(&text, false, text_colour, "raster+shade %.1f ms", hud->raster_ms);
    if (hud->render_scale != 1.0f) {
        hud_add(&text, true, text_colour, "%dx%d", layer->width, layer->height);
        hud_add(&text, false, text_colour, "(window %dx%d at scale %g)", hud->window_width,
                hud->window_height, (double)hud->render_scale);
    } else {
        hud_add(&text, true, text_colour, "%dx%d", layer->width, layer->height);
    }
    hud_add(&text, false, text_colour, "%d threads", hud->threads);
    /* Which camera the keys and the mouse move (O switches), and where it
     * is: the orbit camera's distance to its target too. */
    hud_add(&text, true, accent_colour, "%s (O)", hud->orbiting ? "orbit" : "fly");
    hud_add(&text, false, text_colour, "camera %.2f, %.2f, %.2f",
            shown(camera->position.x, 2), shown(camera->position.y, 2),
            shown(camera->position.z, 2));
    hud_add(&text, false, text_colour, "yaw %.1f", shown(camera->yaw_degrees, 1));
    hud_add(&text, false, text_colour, "pitch %.1f", shown(camera->pitch_degrees, 1));
    if (hud->orbiting)
        hud_add(&text, false, text_colour, "distance %.2f", hud->orbit_distance);
    hud_add(&text, true, text_colour, "time %.2f s%s", shown(scene->time_seconds, 2),
            hud->paused ? " (paused)" : "");
    hud_add(&text, false, text_colour, "filter %s", luz_filter_name(scene->filter));
    hud_add(&text, false, text_colour, "seed %lu", (unsigned long)scene->seed);

    /* What is drawn: the model's name (the first model's, with how many
     * more there are), or the cubes, and the triangles. */
    const luz_lab_model *model = NULL;
    const int objects = scene->objects ? scene->object_count : scene->cube_count;
    for (int i = 0; scene->objects && i < scene->object_count && model == NULL; i++)
        model = scene->objects[i].model;
    if (model != NULL && objects > 1)
        hud_add(&text, true, text_colour, "%.60s and %d more objects", model->name, objects - 1);
    else if (model != NULL)
        hud_add(&text, true, text_colour, "%.60s", model->name);
    else
        hud_add(&text, true, text_colour, "%d cubes", objects);
    hud_add(&text, false, text_colour, "%llu triangles", (unsigned long long)hud->triangles);

    /* The teaching controls: the view (V), the interpolation (X) and the
     * step mode (G); the view's legend goes under the text. */
    hud_add(&text, true, text_colour, "view %s (V)", luz_view_name(scene->view));
    hud_add(&text, false, text_colour, "interp %s (X)",
            luz_interpolation_name(scene->interpolation));
    hud_add(&text, false, text_colour, "%d sample%s (B)", scene->samples,
            scene->samples == 1 ? "" : "s");
    if (hud->step_shown > 0)
        hud_add(&text, true, text_colour, "step (G): %lu of %llu triangles",
                (unsigned long)hud->step_shown, (unsigned long long)hud->step_total);

    /* The lights, word by word: those that are on in full colour, the
     * others dimmed. */
    hud_add(&text, true, text_colour, "lights");
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        hud_add(&text, false,
                luz_light_is_on(&scene->lights, (luz_term)term) ? accent_colour
                                                                : dim_text_colour,
                "%d %s", term + 1, luz_term_name((luz_term)term));
    hud_add(&text, true, dim_text_colour, "H help");
    hud_add(&text, false, dim_text_colour, "I HUD");
    hud_add(&text, false, dim_text_colour, "Tab %s",
            !hud->panel_open ? "panel" : hud->orbiting ? "orbit" : "fly");

    const int s = hud_scale(layer);
    int room = (hud->max_width > 0 && hud->max_width < layer->width) ? hud->max_width
                                                                      : layer->width;
    room -= 2 * MARGIN * s + 2 * PAD * s;   /* the text's width inside the box */
    int text_height;
    int width = hud_flow(&text, s, room, &text_height);
    /* In the step mode the picture holds step_shown of the triangles. */
    const uint64_t drawn = hud->step_shown > 0 && hud->step_shown < hud->step_total
                               ? hud->step_shown
                               : hud->step_total;
    luz_legend legend = luz_legend_of(scene->view, hud->threads, drawn);
    const bool show_legend = scene->view != LUZ_VIEW_COLOR;
    luz_rect legend_rect = {0, 0, 0, 0};
    if (show_legend) {
        legend_rect = luz_legend_draw(NULL, &legend, 0, 0, room, s);
        if (legend_rect.width > width)
            width = legend_rect.width;
    }
    const int gap = show_legend ? PAD * s : 0;
    luz_rect box = {MARGIN * s, MARGIN * s, width + 2 * PAD * s,
                    text_height + gap + legend_rect.height + 2 * PAD * s};
    luz_overlay_fill(layer, box, box_colour);
    const int x = box.x + PAD * s, y = box.y + PAD * s;
    for (int i = 0; i < text.count; i++) {
        const hud_piece *piece = &text.pieces[i];
        luz_overlay_text(layer, x + piece->x, y + piece->y + s, s, piece->text, piece->colour);
    }
    if (show_legend)
        luz_legend_draw(layer, &legend, x, y + text_height + gap, room, s);
}

/* ---- help ---------------------------------------------------------------------------------------- */

enum {
    HELP_COLUMN_GAP = 16,   /* between the keys and the action */
    HELP_COLUMNS_GAP = 24,  /* between two columns of controls */
    HELP_SHORT_ROW = 10,    /* the text's own height: rows touch */
};

/* The width of the keys column at scale 1. */
static int help_keys_width(void)
{
    int width = 0;
    for (int i = 0; i < luz_controls_help_count; i++) {
        int w = luz_overlay_text_width(luz_controls_help[i].keys, 1);
        width = w > width ? w : width;
    }
    return width;
}

/* Breaks an action into lines at most `width` wide (scale 1), at blanks;
 * calls line() for each (if not NULL) and returns how many there are. A
 * word wider than the width gets a line of its own. */
typedef void help_line_function(void *context, const char *text, int length);

static int help_wrap(const char *action, int width, help_line_function *line, void *context)
{
    int lines = 0;
    const char *start = action;
    while (*start != '\0') {
        const char *end = start, *cut = NULL;
        char piece[128];
        for (;;) {
            const char *word_end = end;
            while (*word_end == ' ')
                word_end++;
            while (*word_end != '\0' && *word_end != ' ')
                word_end++;
            int length = (int)(word_end - start);
            if (length >= (int)sizeof piece)
                break;
            memcpy(piece, start, (size_t)length);
            piece[length] = '\0';
            if (cut != NULL && luz_overlay_text_width(piece, 1) > width)
                break;
            cut = word_end;
            end = word_end;
            if (*word_end == '\0')
                break;
        }
        if (cut == NULL)   /* nothing fits: the whole rest */
            cut = start + strlen(start);
        if (line != NULL)
            line(context, start, (int)(cut - start));
        lines++;
        start = cut;
        while (*start == ' ')
            start++;
    }
    return lines > 0 ? lines : 1;
}

/* Rows of controls the help has at an action width, each control on as
 * many rows as its action wraps to. */
static int help_rows(int action_width)
{
    int rows = 0;
    for (int i = 0; i < luz_controls_help_count; i++)
        rows += help_wrap(luz_controls_help[i].action, action_width, NULL, NULL);
    return rows;
}

/* The control that starts column `column` of `columns`, the rows split as
 * evenly as whole controls allow. */
static int help_column_start(int column, int columns, int action_width, int total_rows)
{
    if (column == 0)
        return 0;
    int rows = 0;
    for (int i = 0; i < luz_controls_help_count; i++) {
        if (rows * columns >= total_rows * column)
            return i;
        rows += help_wrap(luz_controls_help[i].action, action_width, NULL, NULL);
    }
    return luz_controls_help_count;
}

static int help_column_rows(int first, int end, int action_width)
{
    int rows = 0;
    for (int i = first; i < end; i++)
        rows += help_wrap(luz_controls_help[i].action, action_width, NULL, NULL);
    return rows;
}

luz_help_layout luz_help_layout_for(int width, int height)
{
    const int keys = help_keys_width();
    int widest_action = 0;
    for (int i = 0; i < luz_controls_help_count; i++) {
        int w = luz_overlay_text_width(luz_controls_help[i].action, 1);
        widest_action = w > widest_action ? w : widest_action;
    }
    /* Largest text first; at a scale, no wrapped action before any
     * wrapped one, then one column before two, then roomy rows before
     * short ones. The action column is no wider than its widest action. */
    for (int scale = 3; scale >= 1; scale--) {
        for (int wrapping = 0; wrapping <= 1; wrapping++) {
            for (int shape = 0; shape < 4; shape++) {
                const int columns = 1 + shape / 2, roomy = shape % 2 == 0;
                const int row = (roomy ? ROW : HELP_SHORT_ROW) * scale;
                int inner = width / scale - 2 * PAD - 2 * MARGIN;
                int column_width = (inner - (columns - 1) * HELP_COLUMNS_GAP) / columns;
                int action_width = column_width - keys - HELP_COLUMN_GAP;
                if (action_width > widest_action)
                    action_width = widest_action;
                if (!wrapping && action_width < widest_action)
                    continue;
                /* Wrapping into a column narrower than a third of the
                 * widest action reads badly: not at this size. */
                if (action_width < widest_action / 3)
                    continue;
                int total = help_rows(action_width);
                int tallest = 0;
                for (int c = 0; c < columns; c++) {
                    int first = help_column_start(c, columns, action_width, total);
                    int end = help_column_start(c + 1, columns, action_width, total);
                    int rows = help_column_rows(first, end, action_width);
                    tallest = rows > tallest ? rows : tallest;
                }
                /* title, a blank row, the controls, the footer */
                int box_height = (3 + tallest) * row + 2 * PAD * scale;
                if (box_height + 2 * MARGIN * scale > height)
                    continue;
                int box_width = (columns * (keys + HELP_COLUMN_GAP + action_width) +
                                 (columns - 1) * HELP_COLUMNS_GAP + 2 * PAD) *
                                scale;
                return (luz_help_layout){
                    .scale = scale, .row = row, .columns = columns,
                    .action_width = action_width, .rows = total, .rows_shown = tallest,
                    .first_max = 0,
                    .box = {(width - box_width) / 2, (height - box_height) / 2, box_width,
                            box_height},
                };
            }
        }
    }
    /* Too small for every control at once: one column at scale 1, short
     * rows, as many as fit, and the rest scrolled to. */
    const int row = HELP_SHORT_ROW;
    int action_width = width - 2 * PAD - 2 * MARGIN - keys - HELP_COLUMN_GAP;
    if (action_width > widest_action)
        action_width = widest_action;
    if (action_width < 1)
        action_width = 1;
    int total = help_rows(action_width);
    int shown = (height - 2 * MARGIN - 2 * PAD) / row - 3;
    if (shown < 1)
        shown = 1;
    if (shown > total)
        shown = total;
    int box_width = keys + HELP_COLUMN_GAP + action_width + 2 * PAD;
    int box_height = (3 + shown) * row + 2 * PAD;
    return (luz_help_layout){
        .scale = 1, .row = row, .columns = 1, .action_width = action_width, .rows = total,
        .rows_shown = shown, .first_max = total - shown,
        .box = {(width - box_width) / 2, (height - box_height) / 2, box_width, box_height},
    };
}

int luz_help_scroll(const luz_help_layout *layout, int first, int rows)
{
    long long next = (long long)first + rows;
    if (next > layout->first_max)
        next = layout->first_max;
    if (next < 0)
        next = 0;
    return (int)next;
}

/* Drawing one control's action lines: where they go. */
typedef struct help_pen {
    luz_layer *layer;
    int x, y, scale, row;
    int row_index;           /* of the whole help's rows, counted from 0 */
    int first, end;          /* the rows shown (scrolled) */
} help_pen;

static void help_draw_line(void *context, const char *text, int length)
{
    help_pen *pen = context;
    if (pen->row_index >= pen->first && pen->row_index < pen->end) {
        char line[128];
        snprintf(line, sizeof line, "%.*s", length, text);
        luz_overlay_text(pen->layer, pen->x, pen->y, pen->scale, line, text_colour);
        pen->y += pen->row;
    }
    pen->row_index++;
}

void luz_help_draw(luz_layer *layer, const luz_help_layout *layout, int first)
{
    const int s = layout->scale, row = layout->row;
    const int keys = help_keys_width();
    first = luz_help_scroll(layout, first, 0);
    const luz_rect box = layout->box;
    luz_overlay_fill(layer, box, (luz_rgba){12, 12, 16, 240});
    const int x = box.x + PAD * s, top = box.y + PAD * s + s;
    luz_overlay_text(layer, x, top, s, "luz controls", accent_colour);

    const int column_step = (keys + HELP_COLUMN_GAP + layout->action_width + HELP_COLUMNS_GAP) * s;
    for (int c = 0; c < layout->columns; c++) {
        int begin = help_column_start(c, layout->columns, layout->action_width, layout->rows);
        int end = help_column_start(c + 1, layout->columns, layout->action_width, layout->rows);
        help_pen pen = {
            .layer = layer, .x = x + c * column_step + (keys + HELP_COLUMN_GAP) * s,
            .y = top + 2 * row, .scale = s, .row = row, .row_index = 0,
            .first = layout->columns == 1 ? first : 0,
            .end = layout->columns == 1 ? first + layout->rows_shown : INT32_MAX,
        };
        for (int i = begin; i < end; i++) {
            if (pen.row_index >= pen.first && pen.row_index < pen.end)
                luz_overlay_text(layer, x + c * column_step, pen.y, s,
                                 luz_controls_help[i].keys, accent_colour);
            help_wrap(luz_controls_help[i].action, layout->action_width, help_draw_line, &pen);
        }
    }

    char footer[96];
    if (layout->first_max > 0)
        snprintf(footer, sizeof footer, "rows %d-%d of %d: Up / Down or the wheel scroll; H closes",
                 first + 1, first + layout->rows_shown, layout->rows);
    else
        snprintf(footer, sizeof footer, "H closes this help");
    luz_overlay_text(layer, x, top + (2 + layout->rows_shown) * row, s, footer, dim_text_colour);
}
