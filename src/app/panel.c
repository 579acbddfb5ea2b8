/*
 * panel.c: the light panel, the HUD and the help overlay (see luz/panel.h).
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
 * the spot.
 */
#include "app/panel.h"
#include "luz/view.h"

#include <math.h>
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
    ROW_COUNT = 1 + LUZ_TERM_COUNT * 3 + 4,   /* title, 3 per light, 4 extras */
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

/* Text centred vertically in a row. */
static void row_text(luz_layer *layer, int x, luz_rect row, int scale, const char *text,
                     luz_rgba colour)
{
    int top = row.y + (row.height - luz_overlay_text_height(scale)) / 2 + scale;
    luz_overlay_text(layer, x, top, scale, text, colour);
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
                    const luz_panel *panel, const luz_lights *lights)
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

void luz_hud_draw(luz_layer *layer, const luz_hud *hud)
{
    enum { MAX_LINES = 12 };
    const luz_scene *scene = hud->scene;
    const luz_camera *camera = &scene->camera;
    char lines[MAX_LINES][160];
    snprintf(lines[0], sizeof lines[0], "%.1f fps  %.1f ms/frame", hud->frames_per_second,
             hud->frame_ms);
    snprintf(lines[1], sizeof lines[1], "geometry %.1f ms  raster+shade %.1f ms",
             hud->geometry_ms, hud->raster_ms);
    if (hud->render_scale != 1.0f)
        snprintf(lines[2], sizeof lines[2], "%dx%d (window %dx%d at scale %g)  %d threads",
                 layer->width, layer->height, hud->window_width, hud->window_height,
                 (double)hud->render_scale, hud->threads);
    else
        snprintf(lines[2], sizeof lines[2], "%dx%d  %d threads", layer->width,
                 layer->height, hud->threads);
    snprintf(lines[3], sizeof lines[3], "camera %.2f, %.2f, %.2f  yaw %.1f  pitch %.1f",
             (double)camera->position.x, (double)camera->position.y, (double)camera->position.z,
             (double)camera->yaw_degrees, (double)camera->pitch_degrees);
    snprintf(lines[4], sizeof lines[4], "time %.2f s%s  filter %s  seed %lu", scene->time_seconds,
             hud->paused ? " (paused)" : "", luz_filter_name(scene->filter),
             (unsigned long)scene->seed);
    /* What is drawn: the model's name (the first model's, with how many
     * more there are), or the cubes, and the triangles. */
    const luz_lab_model *model = NULL;
    const int objects = scene->objects ? scene->object_count : scene->cube_count;
    for (int i = 0; scene->objects && i < scene->object_count && model == NULL; i++)
        model = scene->objects[i].model;
    if (model != NULL && objects > 1)
        snprintf(lines[5], sizeof lines[5], "%s and %d more objects  %llu triangles",
                 model->name, objects - 1, (unsigned long long)hud->triangles);
    else if (model != NULL)
        snprintf(lines[5], sizeof lines[5], "%s  %llu triangles", model->name,
                 (unsigned long long)hud->triangles);
    else
        snprintf(lines[5], sizeof lines[5], "%d cubes  %llu triangles", objects,
                 (unsigned long long)hud->triangles);
    /* The teaching controls: the view (V) with its legend, the
     * interpolation (X) and the step mode (G). */
    int count = 6;
    snprintf(lines[count++], sizeof lines[0], "view %s (V)  interp %s (X)",
             luz_view_name(scene->view), luz_interpolation_name(scene->interpolation));
    if (scene->view != LUZ_VIEW_COLOR)
        snprintf(lines[count++], sizeof lines[0], "%s", luz_view_legend(scene->view));
    if (hud->step_shown > 0)
        snprintf(lines[count++], sizeof lines[0], "step (G): %lu of %llu triangles",
                 (unsigned long)hud->step_shown, (unsigned long long)hud->step_total);
    const int lights_line = count;
    snprintf(lines[count++], sizeof lines[0], "lights");
    snprintf(lines[count++], sizeof lines[0], "H help  I HUD  Tab %s",
             hud->panel_open ? "fly" : "panel");
    const int line_count = count;

    /* The lights line is drawn word by word: the names of the lights that
     * are on in full colour, the others dimmed. */
    char light_names[LUZ_TERM_COUNT][24];
    int s = hud_scale(layer);
    int width = luz_overlay_text_width(lines[lights_line], s);
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        snprintf(light_names[term], sizeof light_names[term], "  %d %s", term + 1,
                 luz_term_name((luz_term)term));
        width += luz_overlay_text_width(light_names[term], s);
    }
    for (int i = 0; i < line_count; i++) {
        int line_width = luz_overlay_text_width(lines[i], s);
        if (line_width > width)
            width = line_width;
    }

    int line = ROW * s;
    luz_rect box = {MARGIN * s, MARGIN * s, width + 2 * PAD * s,
                    line_count * line + 2 * PAD * s};
    luz_overlay_fill(layer, box, box_colour);
    int x = box.x + PAD * s, y = box.y + PAD * s + s;
    for (int i = 0; i < line_count; i++, y += line) {
        luz_rgba colour = i == 0                ? accent_colour
                          : i == line_count - 1 ? dim_text_colour
                                                : text_colour;
        int pen = x + luz_overlay_text(layer, x, y, s, lines[i], colour);
        if (i != lights_line)
            continue;
        for (int term = 0; term < LUZ_TERM_COUNT; term++)
            pen += luz_overlay_text(layer, pen, y, s, light_names[term],
                                    luz_light_is_on(&scene->lights, (luz_term)term)
                                        ? accent_colour : dim_text_colour);
    }
}

/* ---- help ---------------------------------------------------------------------------------------- */

void luz_help_draw(luz_layer *layer)
{
    const char *title = "luz controls";
    const char *footer = "H closes this help";
    int keys_width = 0, actions_width = 0;
    for (int i = 0; i < luz_controls_help_count; i++) {
        int k = luz_overlay_text_width(luz_controls_help[i].keys, 1);
        int a = luz_overlay_text_width(luz_controls_help[i].action, 1);
        keys_width = k > keys_width ? k : keys_width;
        actions_width = a > actions_width ? a : actions_width;
    }
    int column_gap = 16;
    int rows = luz_controls_help_count + 3;   /* title, a blank row, the list, the footer */
    int s = 1;
    for (int candidate = 3; candidate > 1; candidate--) {
        if ((keys_width + column_gap + actions_width + 2 * PAD) * candidate <= layer->width &&
            (rows * ROW + 2 * PAD) * candidate <= layer->height) {
            s = candidate;
            break;
        }
    }

    int width = (keys_width + column_gap + actions_width + 2 * PAD) * s;
    int height = (rows * ROW + 2 * PAD) * s;
    luz_rect box = {(layer->width - width) / 2, (layer->height - height) / 2, width,
                    height};
    luz_overlay_fill(layer, box, (luz_rgba){12, 12, 16, 240});
    int x = box.x + PAD * s, y = box.y + PAD * s + s, line = ROW * s;
    luz_overlay_text(layer, x, y, s, title, accent_colour);
    y += 2 * line;
    for (int i = 0; i < luz_controls_help_count; i++, y += line) {
        luz_overlay_text(layer, x, y, s, luz_controls_help[i].keys, accent_colour);
        luz_overlay_text(layer, x + (keys_width + column_gap) * s, y, s,
                         luz_controls_help[i].action, text_colour);
    }
    luz_overlay_text(layer, x, y, s, footer, dim_text_colour);
}
