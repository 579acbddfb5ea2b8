/*
 * test_panel.c: the viewer's 2D layer (app/panel.h) without a window: the
 * sliders' table, slider edits by key and by mouse, the layout's hit
 * rectangles, the drawing primitives' pixels, and the layer filled in
 * bands of rows as the renderer's threads fill it.
 *
 * Slider numbers follow the panel from top to bottom: ambient r, g, b,
 * strength (0-3), diffuse (4-7), specular (8-11), shininess (12), point
 * (13-16), spot (17-20), inner, outer, reach (21-23), directional (24-27).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/panel.h"

enum {
    AMBIENT_GREEN = 1,
    AMBIENT_STRENGTH = 3,
    DIFFUSE_GREEN = 5,
    SHININESS = 12,
    SPOT_INNER = 21,
    SPOT_OUTER = 22,
    SPOT_REACH = 23,
};

static void assert_near(float actual, float expected, float tolerance)
{
    if (!(fabsf(actual - expected) <= tolerance))
        fail_msg("expected %.7g, got %.7g", (double)expected, (double)actual);
}

static luz_lights default_lights(void)
{
    return luz_scene_defaults().lights;
}

/* ---- the table ------------------------------------------------------------------------ */

static void test_slider_table(void **state)
{
    (void)state;
    int per_term[LUZ_TERM_COUNT] = {0};
    for (int i = 0; i < LUZ_PANEL_SLIDER_COUNT; i++) {
        const luz_slider *slider = &luz_panel_sliders[i];
        per_term[slider->term]++;
        assert_true(slider->min < slider->max);
        assert_true(slider->fine_step > 0.0f && slider->fine_step <= slider->step);
    }
    /* Four each, plus shininess for the specular and three for the spot. */
    int expected[LUZ_TERM_COUNT] = {4, 4, 5, 4, 7, 4};
    assert_memory_equal(per_term, expected, sizeof expected);
    assert_int_equal(luz_panel_sliders[SHININESS].field, LUZ_SLIDER_SHININESS);
    assert_int_equal(luz_panel_sliders[SPOT_INNER].field, LUZ_SLIDER_SPOT_INNER);
    assert_int_equal(luz_panel_sliders[SPOT_OUTER].field, LUZ_SLIDER_SPOT_OUTER);
    assert_int_equal(luz_panel_sliders[SPOT_REACH].field, LUZ_SLIDER_SPOT_REACH);
    /* The spot's reach must stay above 0. */
    assert_true(luz_panel_sliders[SPOT_REACH].min > 0.0f);
}

/* ---- values --------------------------------------------------------------------------------- */

static void test_slider_reads_and_writes_its_field(void **state)
{
    (void)state;
    luz_lights lights = default_lights();
    luz_slider_set(&lights, DIFFUSE_GREEN, 0.25f);
    assert_near(lights.diffuse.colour.y, 0.25f, 0.0f);
    assert_near(luz_slider_value(&lights, DIFFUSE_GREEN), 0.25f, 0.0f);
    /* Nothing else moved. */
    assert_near(lights.diffuse.colour.x, 1.0f, 0.0f);
    assert_near(lights.diffuse.strength, 0.6f, 0.0f);
    assert_near(lights.ambient.colour.y, 1.0f, 0.0f);

    luz_slider_set(&lights, SHININESS, 64.0f);
    assert_near(lights.shininess, 64.0f, 0.0f);
    luz_slider_set(&lights, 27, 0.9f);   /* directional strength */
    assert_near(lights.directional.strength, 0.9f, 0.0f);
}

static void test_slider_values_are_clamped(void **state)
{
    (void)state;
    luz_lights lights = default_lights();
    luz_slider_set(&lights, AMBIENT_GREEN, 2.0f);
    assert_near(lights.ambient.colour.y, 1.0f, 0.0f);
    luz_slider_set(&lights, AMBIENT_GREEN, -1.0f);
    assert_near(lights.ambient.colour.y, 0.0f, 0.0f);
    luz_slider_set(&lights, AMBIENT_GREEN, NAN);
    assert_near(lights.ambient.colour.y, 0.0f, 0.0f);
    luz_slider_set(&lights, SPOT_REACH, 0.0f);
    assert_near(lights.spot_reach, 0.5f, 0.0f);
    luz_slider_set(&lights, SPOT_OUTER, 100.0f);
    assert_near(lights.spot_outer_degrees, 89.0f, 0.0f);
}

static void test_spot_sliders_keep_inner_within_outer(void **state)
{
    (void)state;
    luz_lights lights = default_lights();   /* 12.5, 17.5 */
    luz_slider_set(&lights, SPOT_INNER, 30.0f);
    assert_near(lights.spot_inner_degrees, 30.0f, 0.0f);
    assert_near(lights.spot_outer_degrees, 30.0f, 0.0f);
    luz_slider_set(&lights, SPOT_OUTER, 5.0f);
    assert_near(lights.spot_outer_degrees, 5.0f, 0.0f);
    assert_near(lights.spot_inner_degrees, 5.0f, 0.0f);
}

static void test_arrow_steps(void **state)
{
    (void)state;
    luz_lights lights = default_lights();
    luz_slider_step(&lights, AMBIENT_STRENGTH, +1, false);    /* 0.2 + 0.05 */
    assert_near(lights.ambient.strength, 0.25f, 1e-6f);
    luz_slider_step(&lights, AMBIENT_STRENGTH, -1, true);     /* - 0.01 */
    assert_near(lights.ambient.strength, 0.24f, 1e-6f);
    /* A step lands on a whole number of steps: 0.24 + 0.05 = 0.29 rounds
     * to 6 steps of 0.05, 0.30. */
    luz_slider_step(&lights, AMBIENT_STRENGTH, +1, false);
    assert_near(lights.ambient.strength, 0.30f, 1e-6f);
    /* At the ends, it stays. */
    lights.ambient.strength = 0.0f;
    luz_slider_step(&lights, AMBIENT_STRENGTH, -1, false);
    assert_near(lights.ambient.strength, 0.0f, 0.0f);
    lights.ambient.strength = 1.0f;
    luz_slider_step(&lights, AMBIENT_STRENGTH, +1, false);
    assert_near(lights.ambient.strength, 1.0f, 0.0f);

    luz_slider_step(&lights, SHININESS, +1, false);   /* 32 + 4 */
    assert_near(lights.shininess, 36.0f, 0.0f);
    luz_slider_step(&lights, SHININESS, -1, true);    /* - 1 */
    assert_near(lights.shininess, 35.0f, 0.0f);
    /* 17.5 - 1 = 16.5, a half step, which roundf takes away from 0: 17. */
    luz_slider_step(&lights, SPOT_OUTER, -1, false);
    assert_near(lights.spot_outer_degrees, 17.0f, 0.0f);
}

static void test_arrow_keys_choose_and_change(void **state)
{
    (void)state;
    luz_lights lights = default_lights();
    luz_panel panel;
    luz_panel_init(&panel);
    assert_int_equal(panel.focus, 0);
    assert_int_equal(panel.dragging, -1);
    luz_panel_key_press(&panel, &lights, LUZ_PANEL_UP, false);   /* wraps to the last */
    assert_int_equal(panel.focus, LUZ_PANEL_SLIDER_COUNT - 1);
    luz_panel_key_press(&panel, &lights, LUZ_PANEL_DOWN, false);
    assert_int_equal(panel.focus, 0);
    for (int i = 0; i < AMBIENT_STRENGTH; i++)
        luz_panel_key_press(&panel, &lights, LUZ_PANEL_DOWN, false);
    assert_int_equal(panel.focus, AMBIENT_STRENGTH);
    luz_panel_key_press(&panel, &lights, LUZ_PANEL_LEFT, false);
    assert_near(lights.ambient.strength, 0.15f, 1e-6f);
    luz_panel_key_press(&panel, &lights, LUZ_PANEL_RIGHT, true);
    assert_near(lights.ambient.strength, 0.16f, 1e-6f);
}

/* ---- layout and the mouse --------------------------------------------------------------------- */

static bool rects_overlap(luz_rect a, luz_rect b)
{
    return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height &&
           b.y < a.y + a.height;
}

static bool rect_inside(luz_rect inner, luz_rect outer)
{
    return inner.x >= outer.x && inner.y >= outer.y &&
           inner.x + inner.width <= outer.x + outer.width &&
           inner.y + inner.height <= outer.y + outer.height;
}

static void check_layout(int width, int height, int expected_scale)
{
    luz_panel_layout layout = luz_panel_layout_for(width, height);
    assert_int_equal(layout.scale, expected_scale);
    luz_rect screen = {0, 0, width, height};
    assert_true(rect_inside(layout.box, screen));
    for (int i = 0; i < LUZ_PANEL_SLIDER_COUNT; i++) {
        assert_true(rect_inside(layout.row[i], layout.box));
        assert_true(rect_inside(layout.track[i], layout.row[i]));
        assert_true(layout.track[i].width >= 20 * expected_scale);
        for (int j = i + 1; j < LUZ_PANEL_SLIDER_COUNT; j++)
            assert_false(rects_overlap(layout.row[i], layout.row[j]));
        for (int term = 0; term < LUZ_TERM_COUNT; term++)
            assert_false(rects_overlap(layout.row[i], layout.header[term]));
    }
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        assert_true(rect_inside(layout.header[term], layout.box));
    /* Top to bottom in slider order: a later slider is never above. */
    for (int i = 1; i < LUZ_PANEL_SLIDER_COUNT; i++)
        assert_true(layout.row[i].y >= layout.row[i - 1].y);
}

static void test_layout(void **state)
{
    (void)state;
    check_layout(1280, 720, 2);
    check_layout(640, 360, 1);   /* --render-scale 0.5 of the default */
    check_layout(1920, 1080, 2);
    /* Shorter than the panel's 286 pixels at scale 1: shorter rows, and
     * still every slider inside the window (the e2e test's sizes, and
     * 320x240). */
    check_layout(480, 270, 1);
    check_layout(400, 300, 1);
    check_layout(320, 240, 1);
}

static void test_track_value(void **state)
{
    (void)state;
    luz_panel_layout layout = luz_panel_layout_for(1280, 720);
    luz_rect track = layout.track[AMBIENT_STRENGTH];
    assert_near(luz_panel_track_value(&layout, AMBIENT_STRENGTH, track.x), 0.0f, 0.0f);
    assert_near(luz_panel_track_value(&layout, AMBIENT_STRENGTH, track.x + track.width - 1), 1.0f,
                0.0f);
    /* Beyond the ends: the ends. */
    assert_near(luz_panel_track_value(&layout, AMBIENT_STRENGTH, track.x - 50), 0.0f, 0.0f);
    assert_near(luz_panel_track_value(&layout, AMBIENT_STRENGTH, track.x + track.width + 50), 1.0f,
                0.0f);
    /* The middle pixel gives about half, snapped to hundredths. */
    float middle = luz_panel_track_value(&layout, AMBIENT_STRENGTH, track.x + (track.width - 1) / 2);
    assert_near(middle, 0.5f, 0.011f);
    assert_near(middle * 100.0f, roundf(middle * 100.0f), 1e-3f);
    /* The spot's inner angle over [0, 89]: the right end is 89. */
    track = layout.track[SPOT_INNER];
    assert_near(luz_panel_track_value(&layout, SPOT_INNER, track.x + track.width - 1), 89.0f, 1e-4f);
}

static int centre_x(luz_rect rect) { return rect.x + rect.width / 2; }
static int centre_y(luz_rect rect) { return rect.y + rect.height / 2; }

static void test_click_and_drag(void **state)
{
    (void)state;
    luz_lights lights = default_lights();
    luz_light_switches switches = {{0}};
    luz_panel panel;
    luz_panel_init(&panel);
    luz_panel_layout layout = luz_panel_layout_for(1280, 720);

    /* A press at the left end of ambient green's track sets 0 and holds
     * the slider. */
    luz_rect track = layout.track[AMBIENT_GREEN];
    assert_true(luz_panel_mouse_press(&panel, &layout, &lights, &switches, track.x,
                                      centre_y(track)));
    assert_int_equal(panel.focus, AMBIENT_GREEN);
    assert_int_equal(panel.dragging, AMBIENT_GREEN);
    assert_near(lights.ambient.colour.y, 0.0f, 0.0f);
    /* Dragging follows x only, wherever y is. */
    luz_panel_mouse_drag(&panel, &layout, &lights, track.x + track.width + 100);
    assert_near(lights.ambient.colour.y, 1.0f, 0.0f);
    luz_panel_mouse_release(&panel);
    assert_int_equal(panel.dragging, -1);
    luz_panel_mouse_drag(&panel, &layout, &lights, track.x);   /* released: no effect */
    assert_near(lights.ambient.colour.y, 1.0f, 0.0f);

    /* A press on a row's label focuses without changing the value. */
    luz_rect row = layout.row[SHININESS];
    assert_true(luz_panel_mouse_press(&panel, &layout, &lights, &switches, row.x + 1,
                                      centre_y(row)));
    assert_int_equal(panel.focus, SHININESS);
    assert_int_equal(panel.dragging, -1);
    assert_near(lights.shininess, 32.0f, 0.0f);

    /* Outside the panel: not taken, nothing changes. */
    luz_lights before = lights;
    assert_false(luz_panel_mouse_press(&panel, &layout, &lights, &switches, 5, 5));
    assert_memory_equal(&before, &lights, sizeof lights);
}

static void test_click_a_header_switches_the_light(void **state)
{
    (void)state;
    luz_lights lights = default_lights();
    luz_light_switches switches = {{0}};
    luz_panel panel;
    luz_panel_init(&panel);
    luz_panel_layout layout = luz_panel_layout_for(1280, 720);
    luz_rect header = layout.header[LUZ_TERM_POINT];
    assert_true(luz_panel_mouse_press(&panel, &layout, &lights, &switches, centre_x(header),
                                      centre_y(header)));
    assert_near(lights.point.strength, 0.0f, 0.0f);
    assert_true(luz_panel_mouse_press(&panel, &layout, &lights, &switches, centre_x(header),
                                      centre_y(header)));
    assert_near(lights.point.strength, 0.7f, 0.0f);
    assert_near(lights.spot.strength, 1.0f, 0.0f);
}

/* ---- drawing ---------------------------------------------------------------------------------- */

/* A framebuffer of one grey, alpha 255 as luz's always is. */
static luz_framebuffer *grey_framebuffer(int width, int height, uint8_t grey)
{
    luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, NULL);
    assert_non_null(framebuffer);
    size_t bytes = (size_t)width * (size_t)height * 4;
    for (size_t i = 0; i < bytes; i++)
        framebuffer->colour[i] = (i % 4 == 3) ? 255 : grey;
    return framebuffer;
}

static const uint8_t *pixel(const luz_framebuffer *framebuffer, int x, int y)
{
    return framebuffer->colour + ((size_t)y * (size_t)framebuffer->width + (size_t)x) * 4;
}

/* The viewer records its 2D layer, then fills it. These run one recording
 * and fill it all at once, for the tests of what the pixels become. */
static luz_layer begin(const luz_framebuffer *framebuffer)
{
    luz_layer layer = {0};
    luz_layer_begin(&layer, framebuffer->width, framebuffer->height);
    return layer;
}

static void fill_into(luz_framebuffer *framebuffer, luz_layer *layer)
{
    assert_int_equal(luz_layer_finish(layer), 0);
    luz_layer_draw(layer, framebuffer);
    luz_layer_free(layer);
}

static void fill(luz_framebuffer *framebuffer, luz_rect rect, luz_rgba colour)
{
    luz_layer layer = begin(framebuffer);
    luz_overlay_fill(&layer, rect, colour);
    fill_into(framebuffer, &layer);
}

static int text(luz_framebuffer *framebuffer, int x, int y, int scale, const char *string,
                luz_rgba colour)
{
    luz_layer layer = begin(framebuffer);
    int width = luz_overlay_text(&layer, x, y, scale, string, colour);
    fill_into(framebuffer, &layer);
    return width;
}

static void test_fill_blends_and_clips(void **state)
{
    (void)state;
    luz_framebuffer *framebuffer = grey_framebuffer(8, 8, 100);
    /* round((200 * 128 + 100 * 127) / 255) = round(150.2) = 150 */
    fill(framebuffer, (luz_rect){-4, -4, 6, 6}, (luz_rgba){200, 0, 255, 128});
    assert_int_equal(pixel(framebuffer, 0, 0)[0], 150);
    /* round((0 * 128 + 100 * 127) / 255) = round(49.8) = 50;
     * round((255 * 128 + 100 * 127) / 255) = round(177.8) = 178 */
    assert_int_equal(pixel(framebuffer, 1, 1)[1], 50);
    assert_int_equal(pixel(framebuffer, 1, 1)[2], 178);
    assert_int_equal(pixel(framebuffer, 1, 1)[3], 255);
    /* The clipped rectangle ends at (2, 2). */
    assert_int_equal(pixel(framebuffer, 2, 1)[0], 100);
    assert_int_equal(pixel(framebuffer, 1, 2)[0], 100);

    fill(framebuffer, (luz_rect){6, 6, 100, 100}, (luz_rgba){7, 8, 9, 255});
    assert_memory_equal(pixel(framebuffer, 7, 7), ((uint8_t[]){7, 8, 9, 255}), 4);
    assert_int_equal(pixel(framebuffer, 5, 7)[0], 100);
    fill(framebuffer, (luz_rect){0, 0, 8, 8}, (luz_rgba){7, 8, 9, 0});
    assert_int_equal(pixel(framebuffer, 3, 3)[0], 100);
    /* Entirely outside, or empty: nothing, and no crash. */
    fill(framebuffer, (luz_rect){100, 100, 5, 5}, (luz_rgba){0, 0, 0, 255});
    fill(framebuffer, (luz_rect){2, 2, 0, -3}, (luz_rgba){0, 0, 0, 255});
    assert_int_equal(pixel(framebuffer, 3, 3)[0], 100);
    luz_framebuffer_destroy(framebuffer);
}

/* A translucent fill over a row of varied pixels, 13 wide so that the
 * blend runs both four pixels at a time and one at a time, in both
 * channel orders. Each byte is checked against round((src * a + dst *
 * (255 - a)) / 255), computed here with a division: x / 255 is never
 * exactly halfway between integers (255 is odd), so the rounding is
 * floor((2x + 255) / 510). */
static void test_fill_blends_every_pixel_in_either_order(void **state)
{
    (void)state;
    const luz_rgba colour = {200, 31, 97, 170};
    for (int order = 0; order < 2; order++) {
        luz_framebuffer *framebuffer = grey_framebuffer(15, 3, 0);
        luz_framebuffer_use_colour(framebuffer, NULL,
                                   order ? LUZ_CHANNELS_BGRA : LUZ_CHANNELS_RGBA);
        uint8_t before[15 * 3 * 4];
        for (size_t i = 0; i < sizeof before; i++)
            before[i] = framebuffer->colour[i] = (uint8_t)(i % 4 == 3 ? 255 : (i * 37) % 256);
        fill(framebuffer, (luz_rect){1, 1, 13, 1}, colour);
        /* The colour's bytes as they sit in a pixel of this order. */
        const uint8_t source[4] = {order ? colour.b : colour.r, colour.g,
                                   order ? colour.r : colour.b, 255};
        for (int y = 0; y < 3; y++) {
            for (int x = 0; x < 15; x++) {
                bool inside = y == 1 && x >= 1 && x <= 13;
                for (int c = 0; c < 4; c++) {
                    size_t i = ((size_t)y * 15 + (size_t)x) * 4 + (size_t)c;
                    unsigned sum = source[c] * colour.a + before[i] * (255u - colour.a);
                    unsigned expected = inside ? (2 * sum + 255) / 510 : before[i];
                    assert_int_equal(framebuffer->colour[i], expected);
                }
            }
        }
        luz_framebuffer_destroy(framebuffer);
    }
}

/* An opaque fill stores the colour's bytes in the framebuffer's order. */
static void test_opaque_fill_follows_the_channel_order(void **state)
{
    (void)state;
    luz_framebuffer *framebuffer = grey_framebuffer(4, 4, 100);
    luz_framebuffer_use_colour(framebuffer, NULL, LUZ_CHANNELS_BGRA);
    fill(framebuffer, (luz_rect){1, 1, 2, 2}, (luz_rgba){7, 8, 9, 255});
    assert_memory_equal(pixel(framebuffer, 2, 2), ((uint8_t[]){9, 8, 7, 255}), 4);
    assert_memory_equal(pixel(framebuffer, 0, 0), ((uint8_t[]){100, 100, 100, 255}), 4);
    luz_framebuffer_destroy(framebuffer);
}

/* round((src * a + dst * (255 - a)) / 255), with a division, as above. */
static uint8_t blended(uint8_t destination, uint8_t source, uint8_t alpha)
{
    unsigned sum = source * alpha + destination * (255u - alpha);
    return (uint8_t)((2 * sum + 255) / 510);
}

/* A layer of overlapping rectangles, translucent and opaque, that cross
 * the 16-row buckets and the bands below, filled band by band in an odd
 * order, as the renderer's threads fill it. Each pixel must be each
 * rectangle blended once, in drawing order, whatever the bands: computed
 * here pixel by pixel from the rectangles. A rectangle filled twice where
 * two bands or two buckets meet, or filled out of order, shows. */
static void test_layer_filled_by_bands_blends_each_pixel_once(void **state)
{
    (void)state;
    enum { W = 37, H = 70 };
    const struct { luz_rect rect; luz_rgba colour; } drawn[] = {
        {{-3, 5, 30, 50}, {200, 10, 60, 128}},     /* from row 5 to 54 */
        {{10, 14, 20, 40}, {0, 250, 90, 77}},      /* 14 to 53: crosses 16, 32, 48 */
        {{4, 31, 9, 2}, {30, 60, 90, 255}},        /* opaque, rows 31 and 32 */
        {{20, 15, 40, 60}, {255, 255, 255, 200}},  /* clipped right and below */
        {{0, 0, W, H}, {9, 9, 9, 0}},              /* transparent: not recorded */
    };
    const size_t drawn_count = sizeof drawn / sizeof drawn[0];

    uint8_t expected[W * H * 4];
    luz_framebuffer *framebuffer = grey_framebuffer(W, H, 0);
    for (size_t i = 0; i < sizeof expected; i++)
        expected[i] = framebuffer->colour[i] = (uint8_t)(i % 4 == 3 ? 255 : (i * 53) % 256);
    for (size_t d = 0; d < drawn_count; d++) {
        const luz_rgba c = drawn[d].colour;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                if (!luz_rect_contains(drawn[d].rect, x, y) || c.a == 0)
                    continue;
                uint8_t *p = expected + ((size_t)y * W + (size_t)x) * 4;
                p[0] = blended(p[0], c.r, c.a);
                p[1] = blended(p[1], c.g, c.a);
                p[2] = blended(p[2], c.b, c.a);
            }
    }

    luz_layer layer = begin(framebuffer);
    for (size_t d = 0; d < drawn_count; d++)
        luz_overlay_fill(&layer, drawn[d].rect, drawn[d].colour);
    assert_int_equal(layer.rect_count, drawn_count - 1);
    assert_int_equal(luz_layer_finish(&layer), 0);
    /* Bands of 1, 7, 16, 3 and the rest, from the bottom up. */
    const int bounds[] = {0, 1, 8, 24, 27, H};
    for (int b = 4; b >= 0; b--)
        luz_layer_draw_rows(&layer, framebuffer, bounds[b], bounds[b + 1]);
    assert_memory_equal(framebuffer->colour, expected, sizeof expected);

    /* Rows outside the framebuffer, or an empty band, draw nothing. */
    luz_layer_draw_rows(&layer, framebuffer, H, H + 16);
    luz_layer_draw_rows(&layer, framebuffer, 30, 30);
    assert_memory_equal(framebuffer->colour, expected, sizeof expected);

    /* Begun again, the layer is empty: it draws nothing. */
    luz_layer_begin(&layer, W, H);
    assert_int_equal(luz_layer_finish(&layer), 0);
    luz_layer_draw(&layer, framebuffer);
    assert_memory_equal(framebuffer->colour, expected, sizeof expected);

    /* A layer recorded for a bigger framebuffer is clipped to a smaller
     * one (the window shrank between recording and filling). */
    luz_layer_begin(&layer, 200, 200);
    luz_overlay_fill(&layer, (luz_rect){0, 0, 200, 200}, (luz_rgba){1, 2, 3, 255});
    assert_int_equal(luz_layer_finish(&layer), 0);
    luz_layer_draw(&layer, framebuffer);
    assert_memory_equal(pixel(framebuffer, W - 1, H - 1), ((uint8_t[]){1, 2, 3, 255}), 4);
    luz_layer_free(&layer);
    luz_framebuffer_destroy(framebuffer);
}

/* The bounding box of the pixels that are not grey any more. */
static luz_rect changed_box(const luz_framebuffer *framebuffer, uint8_t grey)
{
    int x0 = framebuffer->width, y0 = framebuffer->height, x1 = -1, y1 = -1;
    for (int y = 0; y < framebuffer->height; y++)
        for (int x = 0; x < framebuffer->width; x++)
            if (pixel(framebuffer, x, y)[0] != grey) {
                x0 = x < x0 ? x : x0;
                y0 = y < y0 ? y : y0;
                x1 = x > x1 ? x : x1;
                y1 = y > y1 ? y : y1;
            }
    return (luz_rect){x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

static void test_text(void **state)
{
    (void)state;
    /* stb_easy_font's "I" is a vertical bar with serifs, within its 7-row
     * cap height and its advance. */
    luz_framebuffer *framebuffer = grey_framebuffer(64, 32, 0);
    int width = text(framebuffer, 10, 5, 1, "I", (luz_rgba){255, 255, 255, 255});
    assert_int_equal(width, luz_overlay_text_width("I", 1));
    luz_rect box = changed_box(framebuffer, 0);
    assert_true(box.x >= 10 && box.x + box.width <= 10 + width);
    assert_true(box.y >= 5 && box.y + box.height <= 5 + luz_overlay_text_height(1));
    assert_true(box.height >= 5);

    /* Scale 2 doubles everything. */
    luz_framebuffer *doubled = grey_framebuffer(64, 32, 0);
    text(doubled, 20, 10, 2, "I", (luz_rgba){255, 255, 255, 255});
    luz_rect box2 = changed_box(doubled, 0);
    assert_int_equal(box2.x, 20 + (box.x - 10) * 2);
    assert_int_equal(box2.y, 10 + (box.y - 5) * 2);
    assert_int_equal(box2.width, box.width * 2);
    assert_int_equal(box2.height, box.height * 2);
    assert_int_equal(luz_overlay_text_width("abc", 2), 2 * luz_overlay_text_width("abc", 1));

    /* Bytes outside printable ASCII draw as '?' (and read no table out of
     * bounds), so a file name can never break the HUD. */
    luz_framebuffer_destroy(framebuffer);
    luz_framebuffer_destroy(doubled);
    framebuffer = grey_framebuffer(64, 32, 0);
    doubled = grey_framebuffer(64, 32, 0);
    text(framebuffer, 0, 0, 1, "\xff\x01\n", (luz_rgba){255, 255, 255, 255});
    text(doubled, 0, 0, 1, "???", (luz_rgba){255, 255, 255, 255});
    assert_memory_equal(framebuffer->colour, doubled->colour, 64 * 32 * 4);
    /* Text running off the framebuffer is clipped. */
    text(framebuffer, 50, 28, 3, "clipped", (luz_rgba){255, 255, 255, 255});

    luz_framebuffer_destroy(framebuffer);
    luz_framebuffer_destroy(doubled);
}

static void test_panel_draws_inside_its_box(void **state)
{
    (void)state;
    luz_framebuffer *framebuffer = grey_framebuffer(640, 360, 77);
    luz_panel_layout layout = luz_panel_layout_for(640, 360);
    luz_panel panel;
    luz_panel_init(&panel);
    luz_lights lights = default_lights();
    luz_layer layer = begin(framebuffer);
    luz_panel_draw(&layer, &layout, &panel, &lights, (luz_output){0});
    fill_into(framebuffer, &layer);
    luz_rect changed = changed_box(framebuffer, 77);
    assert_true(rect_inside(changed, (luz_rect){layout.box.x - layout.scale, layout.box.y,
                                                layout.box.width + 2 * layout.scale,
                                                layout.box.height}));
    /* The ambient strength's bar is filled to 0.2 of its track in the
     * light's colour, white. */
    luz_rect track = layout.track[AMBIENT_STRENGTH];
    int filled = (int)lroundf(0.2f * (float)track.width);
    assert_memory_equal(pixel(framebuffer, track.x, track.y), ((uint8_t[]){255, 255, 255, 255}), 4);
    assert_memory_equal(pixel(framebuffer, track.x + filled - 1, track.y + track.height - 1),
                        ((uint8_t[]){255, 255, 255, 255}), 4);
    assert_true(pixel(framebuffer, track.x + filled, track.y)[0] != 255);
    luz_framebuffer_destroy(framebuffer);
}

/* The panel's last row shows the output: inside the box, under the last
 * slider, and its text changes with the exposure and with the tone map
 * (and nothing else of the panel does). */
static void test_panel_shows_the_output(void **state)
{
    (void)state;
    luz_panel_layout layout = luz_panel_layout_for(1280, 720);
    const luz_rect row = layout.output;
    assert_true(rect_inside(row, layout.box));
    const luz_rect last = layout.row[LUZ_PANEL_SLIDER_COUNT - 1];
    assert_true(row.y >= last.y + last.height);
    luz_panel panel;
    luz_panel_init(&panel);
    luz_lights lights = default_lights();
    const luz_output outputs[3] = {{0.0f, LUZ_TONE_MAP_CLAMP},
                                   {-1.0f, LUZ_TONE_MAP_CLAMP},
                                   {-1.0f, LUZ_TONE_MAP_NEUTRAL}};
    luz_framebuffer *images[3];
    for (int i = 0; i < 3; i++) {
        images[i] = grey_framebuffer(1280, 720, 77);
        luz_layer layer = begin(images[i]);
        luz_panel_draw(&layer, &layout, &panel, &lights, outputs[i]);
        fill_into(images[i], &layer);
    }
    for (int i = 1; i < 3; i++) {
        /* compare the two images row by row: the rows that differ lie in
         * the output's row */
        int differing = 0;
        for (int y = 0; y < 720; y++) {
            const bool differs = memcmp(pixel(images[i - 1], 0, y), pixel(images[i], 0, y),
                                        1280 * 4) != 0;
            if (differs) {
                differing++;
                assert_true(y >= row.y && y < row.y + row.height);
            }
        }
        assert_true(differing > 0);
    }
    for (int i = 0; i < 3; i++) luz_framebuffer_destroy(images[i]);
}

static void test_hud_and_help_draw_within_the_framebuffer(void **state)
{
    (void)state;
    /* Sizes down to a single pixel: nothing may be written outside. */
    int sizes[][2] = {{1280, 720}, {640, 360}, {100, 50}, {1, 1}};
    luz_scene scene = luz_scene_defaults();
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        luz_framebuffer *framebuffer = grey_framebuffer(sizes[i][0], sizes[i][1], 50);
        luz_hud hud = {.frames_per_second = 38.5, .frame_ms = 26.0, .geometry_ms = 0.1,
                       .raster_ms = 25.0, .window_width = sizes[i][0],
                       .window_height = sizes[i][1], .render_scale = 1.0f, .threads = 2,
                       .scene = &scene};
        luz_layer layer = begin(framebuffer);
        luz_hud_draw(&layer, &hud);
        /* With the teaching lines too: a view's legend and the step mode. */
        scene.view = LUZ_VIEW_OVERDRAW;
        hud.step_shown = 12;
        hud.step_total = 66;
        luz_hud_draw(&layer, &hud);
        scene.view = LUZ_VIEW_COLOR;
        luz_hud_draw_message(&layer, "wrote luz-shot-0001.png");
        luz_help_layout help = luz_help_layout_for(sizes[i][0], sizes[i][1]);
        luz_help_draw(&layer, &help, 0);
        luz_panel_layout layout = luz_panel_layout_for(sizes[i][0], sizes[i][1]);
        luz_panel panel;
        luz_panel_init(&panel);
        luz_panel_draw(&layer, &layout, &panel, &scene.lights, luz_scene_output(&scene));
        /* Every rectangle recorded lies inside the framebuffer. */
        for (size_t r = 0; r < layer.rect_count; r++)
            assert_true(rect_inside(layer.rects[r].rect,
                                    (luz_rect){0, 0, sizes[i][0], sizes[i][1]}));
        fill_into(framebuffer, &layer);
        luz_framebuffer_destroy(framebuffer);
    }
}

/* The HUD says which camera the mouse moves: the same scene drawn with the
 * orbit camera on gives another HUD than with the fly camera, and the
 * orbit's distance shows in it. */
static void test_hud_says_which_camera_is_on(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    uint8_t *drawn[3];
    const bool orbiting[3] = {false, true, true};
    const double distances[3] = {3.0, 3.0, 7.5};
    for (int k = 0; k < 3; k++) {
        luz_framebuffer *framebuffer = grey_framebuffer(640, 360, 50);
        luz_hud hud = {.window_width = 640, .window_height = 360, .render_scale = 1.0f,
                       .threads = 2, .scene = &scene, .orbiting = orbiting[k],
                       .orbit_distance = distances[k]};
        luz_layer layer = begin(framebuffer);
        luz_hud_draw(&layer, &hud);
        fill_into(framebuffer, &layer);
        drawn[k] = malloc(640 * 360 * 4);
        assert_non_null(drawn[k]);
        memcpy(drawn[k], framebuffer->colour, 640 * 360 * 4);
        luz_framebuffer_destroy(framebuffer);
    }
    assert_true(memcmp(drawn[0], drawn[1], 640 * 360 * 4) != 0);
    assert_true(memcmp(drawn[1], drawn[2], 640 * 360 * 4) != 0);
    for (int k = 0; k < 3; k++)
        free(drawn[k]);
}

/* A number that rounds to zero shows as 0.00, not -0.00 (issue 31): a
 * camera at x = -0.001, pitch -0.04 and time -0.004 draws the very HUD
 * of one at 0, 0 and 0; one at x = -0.01 another. */
static void test_hud_shows_no_negative_zero(void **state)
{
    (void)state;
    const float x[3] = {0.0f, -0.001f, -0.01f};
    const float pitch[3] = {0.0f, -0.04f, 0.0f};
    const double time[3] = {0.0, -0.004, 0.0};
    uint8_t *drawn[3];
    for (int k = 0; k < 3; k++) {
        luz_scene scene = luz_scene_defaults();
        scene.camera.position.x = x[k];
        scene.camera.pitch_degrees = pitch[k];
        scene.time_seconds = time[k];
        luz_framebuffer *framebuffer = grey_framebuffer(640, 360, 50);
        luz_hud hud = {.window_width = 640, .window_height = 360, .render_scale = 1.0f,
                       .threads = 2, .scene = &scene};
        luz_layer layer = begin(framebuffer);
        luz_hud_draw(&layer, &hud);
        fill_into(framebuffer, &layer);
        drawn[k] = malloc(640 * 360 * 4);
        assert_non_null(drawn[k]);
        memcpy(drawn[k], framebuffer->colour, 640 * 360 * 4);
        luz_framebuffer_destroy(framebuffer);
    }
    assert_memory_equal(drawn[0], drawn[1], 640 * 360 * 4);
    assert_true(memcmp(drawn[0], drawn[2], 640 * 360 * 4) != 0);
    for (int k = 0; k < 3; k++)
        free(drawn[k]);
}

/* ---- the HUD's timings -------------------------------------------------------------------------- */

static void test_hud_timing_averages_the_same_frames(void **state)
{
    (void)state;
    luz_hud_timing timing = {0};
    /* The first frame has no time yet: not counted. */
    assert_false(luz_hud_timing_add(&timing, 0.0, 9.0, 9.0));
    /* Four frames of 0.1, 0.1, 0.1, 0.15 s: the window closes at 0.45?
     * No: at the frame that brings it to 0.5 s or more, the fifth. */
    const double seconds[5] = {0.1, 0.1, 0.1, 0.15, 0.2};
    const double geometry[5] = {0.5, 0.25, 0.25, 0.5, 0.5};
    const double raster[5] = {80.0, 85.0, 90.0, 95.0, 150.0};
    for (int i = 0; i < 4; i++) {
        assert_false(luz_hud_timing_add(&timing, seconds[i], geometry[i], raster[i]));
        assert_true(timing.frame_ms == 0.0);   /* nothing shown before a window closes */
    }
    assert_true(luz_hud_timing_add(&timing, seconds[4], geometry[4], raster[4]));
    /* 5 frames in 0.65 s: 130 ms a frame, 7.69 fps; raster (80 + 85 + 90
     * + 95 + 150) / 5 = 100 ms, geometry 2 / 5 = 0.4 ms. */
    assert_near((float)timing.frame_ms, 130.0f, 1e-4f);
    assert_near((float)timing.frames_per_second, 5.0f / 0.65f, 1e-4f);
    assert_near((float)timing.raster_ms, 100.0f, 1e-4f);
    assert_near((float)timing.geometry_ms, 0.4f, 1e-6f);
    /* The next window starts empty: one frame of 0.6 s closes it alone,
     * and the averages are that frame's. */
    assert_true(luz_hud_timing_add(&timing, 0.6, 1.0, 7.0));
    assert_near((float)timing.frame_ms, 600.0f, 1e-4f);
    assert_near((float)timing.raster_ms, 7.0f, 1e-6f);
    assert_near((float)timing.geometry_ms, 1.0f, 1e-6f);
}

/* ---- the HUD, the legends and the help laid out for the window ---------------------------------- */

/* The sizes a user meets: the default window, half of it (and
 * --render-scale 0.5 of the default), the smallest window the viewer
 * opens, and a large screen. */
static const int layout_sizes[][2] = {{1280, 720}, {640, 360}, {480, 270}, {1920, 1080}};
#define LAYOUT_SIZE_COUNT (sizeof layout_sizes / sizeof layout_sizes[0])

static luz_rect bounds_of(const luz_layer *layer, size_t first)
{
    luz_rect bounds = layer->rects[first].rect;
    for (size_t r = first + 1; r < layer->rect_count; r++) {
        luz_rect rect = layer->rects[r].rect;
        int x1 = bounds.x + bounds.width, y1 = bounds.y + bounds.height;
        if (rect.x < bounds.x) bounds.x = rect.x;
        if (rect.y < bounds.y) bounds.y = rect.y;
        if (rect.x + rect.width > x1) x1 = rect.x + rect.width;
        if (rect.y + rect.height > y1) y1 = rect.y + rect.height;
        bounds.width = x1 - bounds.x;
        bounds.height = y1 - bounds.y;
    }
    return bounds;
}

static void test_hud_fits_the_window_and_stays_left_of_the_panel(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    scene.camera.position = (luz_vec3){-12.345f, 100.25f, -3.5f};
    scene.camera.yaw_degrees = -123.4f;
    scene.camera.pitch_degrees = -45.6f;
    scene.time_seconds = 1234.5;
    scene.seed = 4294967295u;
    for (size_t i = 0; i < LAYOUT_SIZE_COUNT; i++) {
        const int width = layout_sizes[i][0], height = layout_sizes[i][1];
        const luz_panel_layout panel = luz_panel_layout_for(width, height);
        for (int view = 0; view < LUZ_VIEW_COUNT; view++) {
            for (int open = 0; open <= 1; open++) {
                scene.view = (luz_view)view;
                luz_hud hud = {.frames_per_second = 1234.5, .frame_ms = 123.4,
                               .geometry_ms = 12.34, .raster_ms = 123.4,
                               .window_width = width * 2, .window_height = height * 2,
                               .render_scale = 0.5f, .threads = 16, .panel_open = open,
                               .step_shown = 123456, .step_total = 1234567,
                               .triangles = 12345678, .scene = &scene,
                               .max_width = open ? panel.box.x : 0};
                luz_layer layer = {0};
                luz_layer_begin(&layer, width, height);
                luz_hud_draw(&layer, &hud);
                /* Nothing cut off at the window's edges... */
                if (layer.cut_rects != 0)
                    fail_msg("%dx%d, view %s, panel %s: %zu rectangles of the HUD cut off",
                             width, height, luz_view_name((luz_view)view),
                             open ? "open" : "closed", layer.cut_rects);
                /* ...nor under the panel. */
                luz_rect bounds = bounds_of(&layer, 0);
                if (open && bounds.x + bounds.width > panel.box.x)
                    fail_msg("%dx%d, view %s: the HUD reaches x = %d, the panel starts at %d",
                             width, height, luz_view_name((luz_view)view),
                             bounds.x + bounds.width, panel.box.x);
                luz_layer_free(&layer);
            }
        }
    }
}

static void test_legends_have_every_entry(void **state)
{
    (void)state;
    /* mip: levels 0 to 8, 9 and up, and untextured, in the view's colours */
    luz_legend legend = luz_legend_of(LUZ_VIEW_MIP, 2, 100);
    assert_int_equal(legend.entry_count, 11);
    for (int level = 0; level <= 9; level++) {
        luz_vec3 expected = luz_view_mip_colour(level);
        assert_near(legend.entries[level].colour.x, expected.x, 0.0f);
        assert_near(legend.entries[level].colour.y, expected.y, 0.0f);
        assert_near(legend.entries[level].colour.z, expected.z, 0.0f);
    }
    assert_string_equal(legend.entries[6].label, "6");
    assert_string_equal(legend.entries[8].label, "8");
    assert_near(legend.entries[10].colour.x, LUZ_VIEW_MIP_UNTEXTURED.x, 0.0f);
    /* overdraw: 0 to 7, and 8 or more */
    legend = luz_legend_of(LUZ_VIEW_OVERDRAW, 2, 100);
    assert_int_equal(legend.entry_count, 9);
    assert_string_equal(legend.entries[8].label, "8+");
    assert_near(legend.entries[8].colour.x, luz_view_overdraw_colour(100).x, 0.0f);
    /* bands: one per thread */
    assert_int_equal(luz_legend_of(LUZ_VIEW_BANDS, 3, 100).entry_count, 3);
    assert_int_equal(luz_legend_of(LUZ_VIEW_BANDS, 1, 100).entry_count, 1);
    legend = luz_legend_of(LUZ_VIEW_BANDS, 3, 100);
    assert_near(legend.entries[2].colour.y, luz_view_thread_colour(2).y, 0.0f);
    /* depth: the greys the view draws at those distances, for SCENE.md's
     * projection; window depth from the distance by the matrix's z row */
    legend = luz_legend_of(LUZ_VIEW_DEPTH, 2, 100);
    assert_int_equal(legend.entry_count, 4);
    luz_mat4 projection = luz_mat4_perspective(luz_radians(45.0f), 16.0f / 9.0f, 0.1f, 100.0f);
    const double distances[4] = {0.1, 1.0, 10.0, 100.0};
    for (int i = 0; i < 4; i++) {
        double z_ndc = -projection.m[10] + projection.m[14] / distances[i];
        float depth = (float)((z_ndc + 1.0) / 2.0);
        float grey = luz_view_depth_brightness(depth, &projection);
        assert_near(legend.entries[i].colour.x, grey, 2e-3f);
    }
    /* triangles: flat and edge shades */
    legend = luz_legend_of(LUZ_VIEW_TRIANGLES, 2, 100);
    assert_int_equal(legend.entry_count, 6);
    assert_near(legend.entries[0].colour.x, luz_view_triangle_colour(1).x, 0.0f);
    assert_near(legend.entries[3].colour.x,
                luz_view_triangle_colour(1).x * LUZ_VIEW_TRIANGLE_EDGE_SHADE, 1e-6f);
    /* no swatch for a triangle the frame does not have */
    legend = luz_legend_of(LUZ_VIEW_TRIANGLES, 2, 2);
    assert_int_equal(legend.entry_count, 4);
    assert_string_equal(legend.entries[1].label, "id 2");
    assert_near(legend.entries[2].colour.x,
                luz_view_triangle_colour(1).x * LUZ_VIEW_TRIANGLE_EDGE_SHADE, 1e-6f);
    assert_int_equal(luz_legend_of(LUZ_VIEW_TRIANGLES, 2, 0).entry_count, 0);
    /* every view has a title; every entry a label */
    for (int view = 0; view < LUZ_VIEW_COUNT; view++) {
        legend = luz_legend_of((luz_view)view, 4, 100);
        assert_non_null(legend.title);
        for (int e = 0; e < legend.entry_count; e++)
            assert_true(strlen(legend.entries[e].label) > 0);
    }

    /* Drawn, the entries wrap to the width given: nothing past it but the
     * title (which the HUD measures with the rest). */
    legend = luz_legend_of(LUZ_VIEW_MIP, 2, 100);
    luz_layer layer = {0};
    luz_layer_begin(&layer, 1000, 1000);
    luz_rect drawn = luz_legend_draw(&layer, &legend, 10, 20, 150, 1);
    luz_rect measured = luz_legend_draw(NULL, &legend, 10, 20, 150, 1);
    assert_memory_equal(&drawn, &measured, sizeof drawn);
    luz_rect bounds = bounds_of(&layer, 0);
    assert_true(rect_inside(bounds, drawn));
    assert_true(drawn.height > 3 * 12);   /* the title and at least three rows */
    luz_layer_free(&layer);
}

static void test_help_fits_every_window(void **state)
{
    (void)state;
    for (size_t i = 0; i < LAYOUT_SIZE_COUNT + 2; i++) {
        /* and two below the viewer's smallest window, where it scrolls */
        const int width = i < LAYOUT_SIZE_COUNT ? layout_sizes[i][0] : i == LAYOUT_SIZE_COUNT ? 480 : 400;
        const int height = i < LAYOUT_SIZE_COUNT ? layout_sizes[i][1] : i == LAYOUT_SIZE_COUNT ? 200 : 240;
        luz_help_layout help = luz_help_layout_for(width, height);
        /* From 640x360 up, every control at once. */
        if (width >= 640 && height >= 360 && help.first_max != 0)
            fail_msg("%dx%d: the help scrolls", width, height);
        assert_int_equal(help.rows_shown * help.columns >= help.rows - help.first_max, 1);
        assert_true(help.rows_shown >= 1);
        /* Every scroll position draws inside the window and the box. */
        for (int first = 0; first <= help.first_max; first++) {
            luz_layer layer = {0};
            luz_layer_begin(&layer, width, height);
            luz_help_draw(&layer, &help, first);
            if (layer.cut_rects != 0)
                fail_msg("%dx%d, first row %d: %zu rectangles of the help cut off", width,
                         height, first, layer.cut_rects);
            if (!rect_inside(bounds_of(&layer, 0), help.box))
                fail_msg("%dx%d: the help's text leaves its box", width, height);
            luz_layer_free(&layer);
        }
        /* Scrolling is clamped to the rows there are. */
        assert_int_equal(luz_help_scroll(&help, 0, -5), 0);
        assert_int_equal(luz_help_scroll(&help, 0, 1000), help.first_max);
    }
    /* The default window gets text twice the size the smallest gets. */
    assert_int_equal(luz_help_layout_for(1280, 720).scale, 2);
    assert_int_equal(luz_help_layout_for(480, 270).scale, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slider_table),
        cmocka_unit_test(test_slider_reads_and_writes_its_field),
        cmocka_unit_test(test_slider_values_are_clamped),
        cmocka_unit_test(test_spot_sliders_keep_inner_within_outer),
        cmocka_unit_test(test_arrow_steps),
        cmocka_unit_test(test_arrow_keys_choose_and_change),
        cmocka_unit_test(test_layout),
        cmocka_unit_test(test_track_value),
        cmocka_unit_test(test_click_and_drag),
        cmocka_unit_test(test_click_a_header_switches_the_light),
        cmocka_unit_test(test_fill_blends_and_clips),
        cmocka_unit_test(test_fill_blends_every_pixel_in_either_order),
        cmocka_unit_test(test_opaque_fill_follows_the_channel_order),
        cmocka_unit_test(test_layer_filled_by_bands_blends_each_pixel_once),
        cmocka_unit_test(test_text),
        cmocka_unit_test(test_panel_draws_inside_its_box),
        cmocka_unit_test(test_panel_shows_the_output),
        cmocka_unit_test(test_hud_and_help_draw_within_the_framebuffer),
        cmocka_unit_test(test_hud_says_which_camera_is_on),
        cmocka_unit_test(test_hud_shows_no_negative_zero),
        cmocka_unit_test(test_hud_timing_averages_the_same_frames),
        cmocka_unit_test(test_hud_fits_the_window_and_stays_left_of_the_panel),
        cmocka_unit_test(test_legends_have_every_entry),
        cmocka_unit_test(test_help_fits_every_window),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
