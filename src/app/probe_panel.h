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
 * U turns the panel's page (Shift+U back): after the story above come the
 * numbers in between, one page per stage of the tour (docs/pipeline.md),
 * each short enough to keep the panel's text large and the pixel in sight:
 *
 *     vertex (tour step 2): the model, view and projection matrices, row
 *         by row, once per probe, and the winner's corners in clip space;
 *     raster (steps 4 to 7): the corners in the window, the three edge
 *         functions at the pixel centre, top / left and whose the centre
 *         is, barycentric, w, depth, uv and its derivatives, rho, lambda,
 *         the levels and every tap of the filter (level, texel, weight);
 *     light (step 8): |N|, L and N.L, V, R and V.R, Lp and N.Lp, the
 *         spot's c, ci, co, f_dir, dn, f_win and f_dist, the sun and N.sun,
 *         then the six terms with their bars and their sum.
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

/* The panel's pages, in the order U shows them. */
typedef enum luz_probe_page {
    LUZ_PROBE_PAGE_STORY,    /* why the pixel has its colour */
    LUZ_PROBE_PAGE_VERTEX,   /* the numbers in between: the vertex stage */
    LUZ_PROBE_PAGE_RASTER,   /* ... setup, rasterisation, interpolation, texture */
    LUZ_PROBE_PAGE_LIGHT,    /* ... the six light terms */
    LUZ_PROBE_PAGE_COUNT
} luz_probe_page;

/* The page after (or, back, before) page, round the ring. */
luz_probe_page luz_probe_page_next(luz_probe_page page, bool back);

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
                                                  const luz_probe_names *names, bool frozen,
                                                  luz_probe_page page);

/* Records the panel's page for a probe of the viewer's frame: frozen says
 * the animation is paused and the story is the one it had then. */
void luz_probe_panel_draw(luz_layer *layer, const luz_pixel_probe *probe,
                          const luz_probe_names *names, bool frozen, luz_probe_page page);

/* The page's rows as text, as they are drawn before any is cut for room
 * (a term's row: its label, then its values; a row of swatches: each
 * label, then its values), at most max_lines of them into lines; returns
 * how many rows there are. For tests, which read the words. */
#define LUZ_PROBE_PANEL_LINE 200
int luz_probe_panel_text(const luz_pixel_probe *probe, const luz_probe_names *names,
                         bool frozen, luz_probe_page page, char (*lines)[LUZ_PROBE_PANEL_LINE],
                         int max_lines);

/* Records a cross-hair around pixel (x, y), leaving the pixel itself
 * uncovered. */
void luz_probe_marker_draw(luz_layer *layer, int x, int y);

#endif
