/*
 * app/panel.h: the viewer's 2D layer, drawn into luz's own framebuffer.
 *
 * Text (stb_easy_font's segment font, scaled by whole pixels), filled and
 * blended rectangles, and on top of them the three things the viewer shows
 * over the scene: the HUD, the light panel and the help overlay. Nothing
 * here knows about SDL: the light panel is a plain struct, and a mouse
 * press, a drag or an arrow key is a function of (panel, lights, position),
 * so the panel's behaviour is tested without a window.
 *
 * The light panel is the report's six colour pickers, whose alpha set each
 * light's strength: for each light a swatch and sliders for red, green,
 * blue and strength, plus the specular shininess and the spot's angles and
 * reach. A light whose strength is 0 is off. Its last row shows the
 * exposure and the tone map of the output.
 */
#ifndef LUZ_PANEL_H
#define LUZ_PANEL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "app/controls.h"
#include "luz/view.h"
#include "luz/framebuffer.h"
#include "lab/scene.h"

/* ---- drawing --------------------------------------------------------------- */

typedef struct luz_rect {
    int x, y, width, height;
} luz_rect;

typedef struct luz_rgba {
    uint8_t r, g, b;
    uint8_t a;   /* opacity: 255 covers, 0 leaves the pixel as it was */
} luz_rgba;

static inline bool luz_rect_contains(luz_rect rect, int x, int y)
{
    return x >= rect.x && x < rect.x + rect.width && y >= rect.y && y < rect.y + rect.height;
}

/* The 2D layer: what the HUD, the panel and the help draw, kept as a list
 * of filled rectangles in drawing order (text too: stb_easy_font's glyphs
 * are rectangles), and filled into a framebuffer afterwards, all of it at
 * once or a band of rows at a time.
 *
 * Recording first and filling later is what lets the renderer's threads do
 * the filling: the renderer's band hook calls luz_layer_draw_rows for
 * each band of rows right after shading it, on the thread that shaded it,
 * while those rows are still in its cache, instead of one thread blending
 * the HUD's corner after the whole frame, when it has left the cache.
 *
 *   luz_layer_begin(&layer, width, height);     empty, for a framebuffer
 *   luz_hud_draw(&layer, &hud); ...             record
 *   luz_layer_finish(&layer);                   index the rectangles by row
 *   luz_layer_draw(&layer, framebuffer);        fill (or draw_rows, per band)
 *
 * A layer is reused frame after frame; its memory grows to the most
 * rectangles a frame has recorded. Zero-initialise it before its first
 * luz_layer_begin, and free it with luz_layer_free. */
typedef struct luz_layer_rect {
    luz_rect rect;         /* clipped to the layer's size */
    luz_rgba colour;
} luz_layer_rect;

typedef struct luz_layer {
    int width, height;         /* the size of the framebuffer it is for */
    luz_layer_rect *rects;     /* in drawing order */
    size_t rect_count, rect_capacity;
    /* Built by luz_layer_finish: the rectangles that touch rows
     * [k * LUZ_LAYER_BUCKET_ROWS, (k + 1) * LUZ_LAYER_BUCKET_ROWS) are
     * bucket_rects[bucket_start[k] .. bucket_start[k + 1]), in order. */
    size_t *bucket_start;
    uint32_t *bucket_rects;
    size_t bucket_start_capacity, bucket_rects_capacity;
    bool finished;
    bool out_of_memory;        /* a rectangle could not be recorded */
    size_t cut_rects;          /* rectangles recorded that reached past the
                                  layer's edges, cut (or left out): what a
                                  small window would hide */
} luz_layer;

#define LUZ_LAYER_BUCKET_ROWS 16

/* Empties the layer, for a framebuffer of width x height. */
void luz_layer_begin(luz_layer *layer, int width, int height);
/* Indexes the recorded rectangles by row, so that a band of rows visits
 * only its own. Returns 0, or -1 if memory ran out (while recording or
 * now); the layer then draws nothing. */
int luz_layer_finish(luz_layer *layer);
/* Fills the finished layer's rectangles into rows [first_row, end_row) of
 * the framebuffer, in drawing order, each pixel blended once: filling
 * disjoint bands of rows, from any threads at the same time, gives the
 * same bytes as filling all rows at once. */
void luz_layer_draw_rows(const luz_layer *layer, luz_framebuffer *framebuffer, int first_row,
                         int end_row);
void luz_layer_draw(const luz_layer *layer, luz_framebuffer *framebuffer);
void luz_layer_free(luz_layer *layer);

/* Records colour blended over the rectangle (clipped to the layer). */
void luz_overlay_fill(luz_layer *layer, luz_rect rect, luz_rgba colour);

/* One line of text, its top-left corner at (x, y), each font pixel drawn as
 * scale x scale pixels. Characters outside printable ASCII show as '?'.
 * Returns the width drawn, as luz_overlay_text_width does. */
int luz_overlay_text(luz_layer *layer, int x, int y, int scale, const char *text,
                     luz_rgba colour);
int luz_overlay_text_width(const char *text, int scale);
/* The height of a line of text, descenders included. */
int luz_overlay_text_height(int scale);

/* ---- the light panel's sliders ---------------------------------------------- */

typedef enum luz_slider_field {
    LUZ_SLIDER_RED,
    LUZ_SLIDER_GREEN,
    LUZ_SLIDER_BLUE,
    LUZ_SLIDER_STRENGTH,
    LUZ_SLIDER_SHININESS,
    LUZ_SLIDER_SPOT_INNER,
    LUZ_SLIDER_SPOT_OUTER,
    LUZ_SLIDER_SPOT_REACH,
} luz_slider_field;

typedef struct luz_slider {
    luz_term term;            /* the light it belongs to */
    luz_slider_field field;
    const char *label;
    float min, max;
    float step;               /* one arrow key press */
    float fine_step;          /* one press with Shift; the mouse snaps to it */
} luz_slider;

/* Per light red, green, blue, strength; shininess after the specular light,
 * inner, outer and reach after the spot: 6 * 4 + 1 + 3. The sliders are
 * numbered in the order the panel shows them, top to bottom. */
#define LUZ_PANEL_SLIDER_COUNT 28
extern const luz_slider luz_panel_sliders[LUZ_PANEL_SLIDER_COUNT];

float luz_slider_value(const luz_lights *lights, int slider);
/* Sets a slider's value, clamped to its range; the spot's angles keep
 * inner <= outer as the cone keys do (luz_spot_set_inner/outer). */
void luz_slider_set(luz_lights *lights, int slider, float value);
/* One arrow key press: direction +1 or -1, by step (fine: fine_step), the
 * result rounded to a whole number of steps. */
void luz_slider_step(luz_lights *lights, int slider, int direction, bool fine);

/* ---- the light panel -------------------------------------------------------- */

typedef struct luz_panel {
    int focus;      /* the slider the arrow keys change */
    int dragging;   /* the slider the mouse holds, or -1 */
} luz_panel;

/* Where everything of the panel is, for a framebuffer of a given size: on
 * the right, text at scale 2 where the window is tall enough, else 1. */
typedef struct luz_panel_layout {
    int scale;
    luz_rect box;
    luz_rect title;
    luz_rect header[LUZ_TERM_COUNT];   /* a light's name and swatch: click to switch */
    luz_rect row[LUZ_PANEL_SLIDER_COUNT];
    luz_rect track[LUZ_PANEL_SLIDER_COUNT];
    luz_rect output;   /* the last row: the exposure and the tone map */
} luz_panel_layout;

void luz_panel_init(luz_panel *panel);
luz_panel_layout luz_panel_layout_for(int width, int height);

typedef enum luz_panel_key {
    LUZ_PANEL_UP,      /* previous slider */
    LUZ_PANEL_DOWN,    /* next slider */
    LUZ_PANEL_LEFT,    /* decrease */
    LUZ_PANEL_RIGHT,   /* increase */
} luz_panel_key;

void luz_panel_key_press(luz_panel *panel, luz_lights *lights, luz_panel_key key, bool fine);

/* A mouse press at (x, y) in framebuffer pixels. On a light's header it
 * switches the light; on a slider's row it focuses the slider, and on its
 * track it also sets the value under the cursor and holds the slider for
 * dragging. Returns true if the press landed on the panel. */
bool luz_panel_mouse_press(luz_panel *panel, const luz_panel_layout *layout, luz_lights *lights,
                           luz_light_switches *switches, int x, int y);
/* The mouse moved to x while a slider is held: it follows the cursor. */
void luz_panel_mouse_drag(luz_panel *panel, const luz_panel_layout *layout, luz_lights *lights,
                          int x);
void luz_panel_mouse_release(luz_panel *panel);

/* The value of a track at x: its range spread over the track's pixels,
 * snapped to the slider's fine step. */
float luz_panel_track_value(const luz_panel_layout *layout, int slider, int x);

/* The panel: the lights' blocks, and under them the output in force
 * (SCENE.md, "Output"), which the keys [ ] and N change. */
void luz_panel_draw(luz_layer *layer, const luz_panel_layout *layout,
                    const luz_panel *panel, const luz_lights *lights, luz_output output);

/* ---- view legends (legend.c) ---------------------------------------------------- */

/* The key to a view's colours: a title and swatches, each a colour of
 * luz/view.h's palettes with what it means. The viewer's HUD shows it
 * under its text; luz-render --legend draws it into the PNG. */
#define LUZ_LEGEND_MAX_ENTRIES 16
#define LUZ_LEGEND_LABEL_SIZE 24

typedef struct luz_legend_entry {
    luz_vec3 colour;
    char label[LUZ_LEGEND_LABEL_SIZE];
} luz_legend_entry;

typedef struct luz_legend {
    const char *title;
    int entry_count;
    luz_legend_entry entries[LUZ_LEGEND_MAX_ENTRIES];
} luz_legend;

/* Every entry of the view's key; the bands view has one per thread of
 * thread_count (at most LUZ_LEGEND_MAX_ENTRIES), the triangles view a
 * flat and an edge swatch for each of the frame's first triangles, ids 1
 * to min(3, triangle_count), so that it names none the picture lacks. The
 * colour view has a title and no entries. */
luz_legend luz_legend_of(luz_view view, int thread_count, uint64_t triangle_count);

/* Draws the legend with its top-left corner at (x, y), the title on the
 * first line and the swatches in as many rows as max_width needs, at text
 * scale `scale`, and returns the rectangle it covers. A NULL layer only
 * measures. */
luz_rect luz_legend_draw(luz_layer *layer, const luz_legend *legend, int x, int y,
                         int max_width, int scale);
/* The legend in a box in the layer's bottom-left corner, as wide as the
 * layer allows (luz-render --legend). */
void luz_legend_draw_in_corner(luz_layer *layer, const luz_legend *legend);

/* ---- HUD and help ------------------------------------------------------------ */

/* The HUD's timings. Frames are counted into a window until it spans
 * LUZ_HUD_AVERAGE_SECONDS; then the window's averages are what the HUD
 * shows until the next window closes. The frame time and the renderer's
 * share of it are averaged over the same frames, so that they compare. */
#define LUZ_HUD_AVERAGE_SECONDS 0.5

typedef struct luz_hud_timing {
    /* the window being counted */
    int window_frames;
    double window_seconds, window_geometry_ms, window_raster_ms;
    /* the last closed window's averages; zero before the first closes */
    double frames_per_second;
    double frame_ms;        /* wall time from one frame's start to the next's */
    double geometry_ms;     /* luz_frame_stats: vertex, clipping, setup */
    double raster_ms;       /* raster, depth, shading, the 2D layer */
} luz_hud_timing;

/* One more frame: `seconds` from the start of the frame before it to its
 * own, of which the renderer spent geometry_ms and raster_ms. A frame of
 * no time (the first) is not counted. Returns true when a window closed
 * and the averages changed. */
bool luz_hud_timing_add(luz_hud_timing *timing, double seconds, double geometry_ms,
                        double raster_ms);

typedef struct luz_hud {
    double frames_per_second;  /* a luz_hud_timing's averages, all four */
    double frame_ms;
    double geometry_ms;
    double raster_ms;
    int window_width, window_height;
    float render_scale;
    int threads;
    bool paused;
    bool panel_open;
    bool orbiting;            /* the orbit camera (O), else the fly camera */
    double orbit_distance;    /* the orbit's distance to its target */
    uint32_t step_shown;      /* the step mode's triangles drawn, 0 when off */
    uint64_t step_total;      /* and the frame's triangles (rasterised), also
                                 when it is off: the triangles view's legend
                                 shows no more ids than the frame has */
    uint64_t triangles;       /* the last frame's, submitted */
    const luz_scene *scene;   /* its view and interpolation are shown too, with
                                 the view's legend (luz_legend_of) */
    int max_width;            /* the HUD stays within [0, max_width) (the
                                 viewer keeps it left of the open panel);
                                 0: the layer's width */
} luz_hud;

/* The HUD in the top-left corner: its lines broken between their parts
 * where the width asks for it, and the view's legend under them. */
void luz_hud_draw(luz_layer *layer, const luz_hud *hud);
/* A one-line message at the bottom left ("wrote luz-shot-0001.png"). */
void luz_hud_draw_message(luz_layer *layer, const char *message);

/* The help: every control (luz_controls_help) in a box in the middle of a
 * width x height framebuffer. The largest text that fits, in one column
 * or two, long actions wrapped; where even the smallest does not fit (a
 * framebuffer under about 480x330), one column that scrolls: rows_shown
 * rows at a time, from a first row between 0 and first_max. */
typedef struct luz_help_layout {
    int scale;          /* text scale */
    int row;            /* row height in pixels */
    int columns;        /* 1 or 2 */
    int action_width;   /* the actions' column, at scale 1: they wrap to it */
    int rows;           /* rows of controls in all, wrapped lines included */
    int rows_shown;     /* rows in the tallest column, or shown at once */
    int first_max;      /* 0 when everything is shown */
    luz_rect box;
} luz_help_layout;

luz_help_layout luz_help_layout_for(int width, int height);
/* The first row shown after scrolling by `rows` (negative: up), clamped. */
int luz_help_scroll(const luz_help_layout *layout, int first, int rows);
void luz_help_draw(luz_layer *layer, const luz_help_layout *layout, int first);

/* A ring around pixel (x, y) that leaves the pixel and its neighbours
 * uncovered: white with a black rim, seen on any colour. scale 1 or more
 * makes it bigger, for large images. (overlay.c) */
void luz_overlay_mark(luz_layer *layer, int x, int y, int scale);

#endif
