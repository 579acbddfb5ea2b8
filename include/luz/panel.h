/*
 * luz/panel.h: the viewer's 2D layer, drawn into luz's own framebuffer.
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
 * reach. A light whose strength is 0 is off.
 */
#ifndef LUZ_PANEL_H
#define LUZ_PANEL_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/controls.h"
#include "luz/framebuffer.h"
#include "luz/scene.h"

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

/* Blends colour over the rectangle (clipped to the framebuffer). */
void luz_overlay_fill(luz_framebuffer *framebuffer, luz_rect rect, luz_rgba colour);

/* One line of text, its top-left corner at (x, y), each font pixel drawn as
 * scale x scale pixels. Characters outside printable ASCII show as '?'.
 * Returns the width drawn, as luz_overlay_text_width does. */
int luz_overlay_text(luz_framebuffer *framebuffer, int x, int y, int scale, const char *text,
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

void luz_panel_draw(luz_framebuffer *framebuffer, const luz_panel_layout *layout,
                    const luz_panel *panel, const luz_lights *lights);

/* ---- HUD and help ------------------------------------------------------------ */

typedef struct luz_hud {
    double frames_per_second;
    double frame_ms;          /* wall time between frames */
    double geometry_ms;       /* luz_frame_stats of the last frame */
    double raster_ms;
    int window_width, window_height;
    float render_scale;
    int threads;
    bool paused;
    bool panel_open;
    uint32_t step_shown;      /* the step mode's triangles drawn, 0 when off */
    uint64_t step_total;      /* and the frame's triangles */
    const luz_scene *scene;   /* its view and interpolation are shown too, with
                                 the view's legend (luz_view_legend) */
} luz_hud;

/* The HUD in the top-left corner. */
void luz_hud_draw(luz_framebuffer *framebuffer, const luz_hud *hud);
/* A one-line message at the bottom left ("wrote luz-shot-0001.png"). */
void luz_hud_draw_message(luz_framebuffer *framebuffer, const char *message);
/* Every control (luz_controls_help), in a box over the scene. */
void luz_help_draw(luz_framebuffer *framebuffer);

#endif
