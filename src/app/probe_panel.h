/*
 * app/probe_panel.h: the viewer's probe panel, the pixel probe
 * (luz/probe.h) laid out for reading.
 *
 * In the viewer, E turns the probe mode on: the cursor is free and a click
 * marks a pixel. The marked pixel is probed on every frame, so the panel
 * follows it as the scene moves; while the animation is paused (T) the
 * panel keeps the story it had (a new click still asks again). Shift+E
 * forgets the pixel. luz-render --probe prints the same story as text.
 *
 * The panel, in the bottom-left corner (else the bottom-right or the
 * top-right one, the first that does not hide the pixel it explains).
 * Where it would cover more than half the frame (a small window), it is
 * compact: the six term rows go, and the history lists fewer tests:
 *
 *     PROBE 700,450                        E: mode  Shift+E: close
 *     cube 0  drawn triangle #1 of the frame
 *     = its mesh's triangle 0 (vertices 0 1 2)
 *     barycentric 0.326 0.434 0.240  w 2.500  depth 0.96096
 *     P ...  N ...  uv ...
 *     texture bricks.png  rho 0.736  lod 0.000  levels 0,0 (0.00)
 *     T  [texel swatch]  0.775 0.742 0.674
 *     ambient      [bar]  0.200 0.200 0.200       one bar per term, its
 *     ...                                         length the term's mean
 *     light        [the six bars end to end]      channel, in the term's
 *     C  [swatch] ...   colour [swatch] ...       colour of the key
 *     EV +0.0 clamp [swatch] ...  bytes [swatch] 120 255 159
 *                                                 (the colour exposed and
 *                                                 tone-mapped, its bytes)
 *     2 depth tests, in draw order
 *      1 cube 0 #1  0.96096 < 1.00000  pass
 *      ...
 *
 * Like the light panel (panel.h), it is recorded into the 2D layer and
 * needs no window: what it draws is tested with a framebuffer.
 */
#ifndef LUZ_PROBE_PANEL_H
#define LUZ_PROBE_PANEL_H

#include <stdbool.h>

#include "luz/probe.h"
#include "app/panel.h"
#include "app/probe_report.h"

/* The colour that stands for each term in the panel's bars (not the
 * light's own colour: six white lights would give six white bars). */
luz_rgba luz_probe_term_colour(luz_term term);

/* The swatches of the panel. */
typedef enum luz_probe_swatch {
    LUZ_PROBE_SWATCH_TEXEL,     /* T */
    LUZ_PROBE_SWATCH_OBJECT,    /* C */
    LUZ_PROBE_SWATCH_COLOUR,    /* light x C x T, clamped */
    LUZ_PROBE_SWATCH_MAPPED,    /* that colour exposed and tone-mapped */
    LUZ_PROBE_SWATCH_SHOWN,     /* what a view shows */
    LUZ_PROBE_SWATCH_BYTES,     /* the image's pixel */
    LUZ_PROBE_SWATCH_COUNT
} luz_probe_swatch;

/* Where the panel's parts are, for a framebuffer of width x height and a
 * probe (compact where the whole would cover more than half of it): the box, one row per line, the swatches (zero size when absent),
 * the bars of the six terms and of their sum (whose segments are the six
 * bars, end to end, in order). */
#define LUZ_PROBE_PANEL_MAX_ROWS 64
typedef struct luz_probe_panel_layout {
    int scale;                         /* text scale, 1 or 2 */
    int row_height;
    luz_rect box;
    int row_count;
    luz_rect term_bar[LUZ_TERM_COUNT]; /* zero width for a term that is 0 */
    luz_rect light_bar[LUZ_TERM_COUNT];/* the sum's segments */
    float bar_scale;                   /* the value a bar's full width stands for */
    int bar_width;                     /* that full width in pixels */
    int history_rows;                  /* tests listed (the others counted) */
    bool compact;                      /* the whole story would cover more than
                                          half the frame: no term rows (the
                                          light row's bar still shows each
                                          term), and the history cut to keep
                                          the box within half the frame */
    luz_rect swatch[LUZ_PROBE_SWATCH_COUNT];
} luz_probe_panel_layout;

luz_probe_panel_layout luz_probe_panel_layout_for(int width, int height,
                                                  const luz_pixel_probe *probe,
                                                  const luz_probe_names *names, bool frozen);

/* Records the panel for a probe of the viewer's frame: frozen says the
 * animation is paused and the story is the one it had then. */
void luz_probe_panel_draw(luz_layer *layer, const luz_pixel_probe *probe,
                          const luz_probe_names *names, bool frozen);

/* Records a cross-hair around pixel (x, y), leaving the pixel itself
 * uncovered. */
void luz_probe_marker_draw(luz_layer *layer, int x, int y);

#endif
