/*
 * test_probe_panel.c: the viewer's probe panel (app/probe_panel.h) without
 * a window, drawn into a framebuffer from probes made by hand.
 *
 * The terms of the hand-made probe are chosen so that the bars' lengths
 * are known: their mean channels 0.2, 0.6, 0, 0.3, 0.5 and 0.1 sum to
 * light = 1.7, the bars' scale, so on a bar of 120 pixels they are
 * round(120 x mean / 1.7) = 14, 42, 0, 21, 35 and 7 pixels, and the sum's
 * bar is the six end to end, 119 pixels. Each bar and swatch is then
 * looked for in the pixels: the colours the panel promises where the
 * layout says.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "app/probe_panel.h"
#include "lab/scene.h"

static luz_pixel_probe *hand_made_probe(void)
{
    luz_pixel_probe *probe = calloc(1, sizeof *probe);
    assert_non_null(probe);
    probe->x = 700;
    probe->y = 450;
    probe->filled = true;
    probe->view = LUZ_VIEW_COLOR;
    probe->triangle = 5;
    probe->draw = 1;
    probe->primitive = 2;
    probe->vertices[0] = 4;
    probe->vertices[1] = 5;
    probe->vertices[2] = 6;
    probe->barycentric = (luz_vec3){0.25f, 0.25f, 0.5f};
    probe->w = 2.5f;
    probe->depth = 0.96f;
    probe->normal = (luz_vec3){0, 0, 1};
    probe->shading = LUZ_SHADING_LIT;
    /* means 0.2, 0.6, 0, 0.3, 0.5, 0.1 */
    const luz_vec3 terms[LUZ_TERM_COUNT] = {
        {0.2f, 0.2f, 0.2f}, {0.9f, 0.6f, 0.3f}, {0, 0, 0},
        {0.3f, 0.3f, 0.3f}, {0.5f, 0.5f, 0.5f}, {0.1f, 0.1f, 0.1f},
    };
    memcpy(probe->terms, terms, sizeof terms);
    probe->light = (luz_vec3){2.0f, 1.7f, 1.4f};   /* mean 1.7 */
    probe->texel = (luz_vec3){0.5f, 0.25f, 1.0f};
    probe->object_colour = (luz_vec3){1.0f, 0.5f, 0.2f};
    probe->colour = (luz_vec3){1.0f, 0.2125f, 0.28f};
    /* the output, made up by hand: its swatch is mapped's, not colour's */
    probe->exposure = -1.0f;
    probe->tone_map = LUZ_TONE_MAP_NEUTRAL;
    probe->exposed = (luz_vec3){0.5f, 0.10625f, 0.14f};
    probe->mapped = (luz_vec3){0.5f, 0.25f, 1.0f};
    probe->bytes[0] = 255;
    probe->bytes[1] = 54;
    probe->bytes[2] = 71;
    probe->test_count = probe->tests_kept = 3;
    for (int k = 0; k < 3; k++)
        probe->tests[k] = (luz_probe_test){.triangle = (uint32_t)(3 + k), .draw = k % 2,
                                           .depth = 0.97f - 0.01f * k,
                                           .stored = k ? 0.97f - 0.01f * (k - 1) : 1.0f,
                                           .passed = true};
    return probe;
}

typedef struct picture {
    luz_framebuffer *framebuffer;
    luz_layer layer;
} picture;

static void picture_begin(picture *p, int width, int height)
{
    luz_error error = {{0}};
    p->framebuffer = luz_framebuffer_create(width, height, &error);
    assert_non_null(p->framebuffer);
    memset(p->framebuffer->colour, 0, (size_t)width * height * 4);
    memset(&p->layer, 0, sizeof p->layer);
    luz_layer_begin(&p->layer, width, height);
}

static void picture_fill(picture *p)
{
    assert_int_equal(luz_layer_finish(&p->layer), 0);
    luz_layer_draw(&p->layer, p->framebuffer);
}

static void picture_end(picture *p)
{
    luz_layer_free(&p->layer);
    luz_framebuffer_destroy(p->framebuffer);
}

static const uint8_t *pixel(const picture *p, int x, int y)
{
    return p->framebuffer->colour + ((size_t)y * p->framebuffer->width + x) * 4;
}

static void assert_rgb(const picture *p, int x, int y, uint8_t r, uint8_t g, uint8_t b)
{
    const uint8_t *got = pixel(p, x, y);
    if (got[0] != r || got[1] != g || got[2] != b)
        fail_msg("pixel (%d, %d) is (%d, %d, %d), expected (%d, %d, %d)", x, y, got[0], got[1],
                 got[2], r, g, b);
}

/* Every pixel of the rectangle has the colour. */
static void assert_filled(const picture *p, luz_rect rect, luz_rgba colour)
{
    assert_true(rect.width > 0 && rect.height > 0);
    for (int y = rect.y; y < rect.y + rect.height; y++)
        for (int x = rect.x; x < rect.x + rect.width; x++)
            assert_rgb(p, x, y, colour.r, colour.g, colour.b);
}

static void test_bars_are_the_terms(void **state)
{
    (void)state;
    luz_pixel_probe *probe = hand_made_probe();
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    const luz_probe_panel_layout layout =
        luz_probe_panel_layout_for(960, 540, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.scale, 1);
    assert_int_equal(layout.bar_width, 120);
    assert_true(layout.bar_scale > 1.6999f && layout.bar_scale < 1.7001f);
    const int expected[LUZ_TERM_COUNT] = {14, 42, 0, 21, 35, 7};
    int pen = layout.light_bar[0].x;
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        assert_int_equal(layout.term_bar[term].width, expected[term]);
        /* the sum: the same lengths, end to end, in luz_term's order */
        assert_int_equal(layout.light_bar[term].width, expected[term]);
        assert_int_equal(layout.light_bar[term].x, pen);
        pen += expected[term];
        /* every term's bar starts where the others do */
        assert_int_equal(layout.term_bar[term].x, layout.light_bar[0].x);
    }
    assert_int_equal(pen - layout.light_bar[0].x, 119);

    picture p;
    picture_begin(&p, 960, 540);
    luz_probe_panel_draw(&p.layer, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    picture_fill(&p);
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        const luz_rgba colour = luz_probe_term_colour((luz_term)term);
        if (expected[term] > 0) {
            assert_filled(&p, layout.term_bar[term], colour);
            assert_filled(&p, layout.light_bar[term], colour);
        }
    }
    /* The swatches: the texel and C as their bytes, the colour clamped,
     * the image's bytes as they are. */
    assert_filled(&p, layout.swatch[LUZ_PROBE_SWATCH_TEXEL], (luz_rgba){128, 64, 255, 255});
    assert_filled(&p, layout.swatch[LUZ_PROBE_SWATCH_OBJECT], (luz_rgba){255, 128, 51, 255});
    assert_filled(&p, layout.swatch[LUZ_PROBE_SWATCH_COLOUR], (luz_rgba){255, 54, 71, 255});
    assert_filled(&p, layout.swatch[LUZ_PROBE_SWATCH_BYTES], (luz_rgba){255, 54, 71, 255});
    assert_filled(&p, layout.swatch[LUZ_PROBE_SWATCH_MAPPED], (luz_rgba){128, 64, 255, 255});
    assert_int_equal(layout.swatch[LUZ_PROBE_SWATCH_SHOWN].width, 0);   /* no view */
    /* The box in the bottom-left corner, inside the frame, the history
     * listed whole. */
    assert_true(layout.box.x >= 0 && layout.box.y >= 0);
    assert_int_equal(layout.box.y + layout.box.height, 540 - 6);
    assert_true(layout.box.x + layout.box.width <= 960 / 2);
    assert_int_equal(layout.history_rows, 3);
    picture_end(&p);
    free(probe);
}

static void test_a_long_history_fits_a_small_window(void **state)
{
    (void)state;
    luz_pixel_probe *probe = hand_made_probe();
    probe->test_count = probe->tests_kept = 40;
    for (int k = 0; k < 40; k++)
        probe->tests[k] = (luz_probe_test){.triangle = (uint32_t)(k + 1), .depth = 0.5f,
                                           .stored = 1.0f, .passed = k == 0};
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    const int sizes[3][2] = {{1280, 720}, {640, 360}, {480, 400}};
    for (int i = 0; i < 3; i++) {
        const luz_probe_panel_layout layout =
            luz_probe_panel_layout_for(sizes[i][0], sizes[i][1], probe, &names, true, LUZ_PROBE_PAGE_STORY);
        assert_true(layout.box.y >= 0);
        assert_true(layout.box.y + layout.box.height <= sizes[i][1]);
        /* 18 rows above the history and 40 tests fit in 720 rows of
         * 12 pixels, not in 360 or 400: those list fewer, and say so */
        if (sizes[i][1] == 720)
            assert_int_equal(layout.history_rows, 40);
        else
            assert_true(layout.history_rows < 40);
        assert_true(layout.history_rows > 0);
    }
    free(probe);
}

/* The panel moves to the bottom-right corner rather than hide the pixel
 * it explains (and its marker); where both corners would, it stays. */
static void test_the_panel_leaves_the_pixel_in_sight(void **state)
{
    (void)state;
    luz_pixel_probe *probe = hand_made_probe();
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    probe->x = 900;
    probe->y = 100;
    luz_probe_panel_layout layout = luz_probe_panel_layout_for(960, 540, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.box.x, 6);
    probe->x = 20;
    probe->y = 520;
    layout = luz_probe_panel_layout_for(960, 540, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.box.x + layout.box.width, 960 - 6);
    /* 8 pixels of the marker and its outline: 9 pixels to the box */
    probe->x = 6 + layout.box.width + 9;
    layout = luz_probe_panel_layout_for(960, 540, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.box.x, 6);
    probe->x--;
    layout = luz_probe_panel_layout_for(960, 540, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_true(layout.box.x > 6);
    /* too narrow for either bottom corner to leave it: the top-right one */
    probe->x = 200;
    probe->y = 200;
    layout = luz_probe_panel_layout_for(400, 300, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.box.x + layout.box.width, 400 - 6);
    assert_int_equal(layout.box.y, 6);
    assert_true(layout.box.y + layout.box.height <= 200 - 9);
    /* hidden in every corner: it stays in the bottom-left one */
    probe->x = 200;
    probe->y = 150;
    layout = luz_probe_panel_layout_for(400, 300, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.box.x, 6);
    assert_int_equal(layout.box.y + layout.box.height, 300 - 6);
    free(probe);
}

/* Twice the text size where the whole story fits so (issue 31: the
 * 1280x720 window had the 6-pixel font): at 1280x720 scale 2, every row
 * listed, the box inside the frame and within half its area, margins and
 * bars doubled; at 960x540, where the box would be taller than half the
 * frame, and for a pixel that the big box would hide, scale 1. */
static void test_readable_text_where_it_fits(void **state)
{
    (void)state;
    luz_pixel_probe *probe = hand_made_probe();
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    probe->x = 1200;   /* top right: the big box leaves it in sight */
    probe->y = 100;
    luz_probe_panel_layout layout = luz_probe_panel_layout_for(1280, 720, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.scale, 2);
    assert_int_equal(layout.bar_width, 240);
    assert_int_equal(layout.history_rows, 3);
    assert_int_equal(layout.box.x, 12);
    assert_int_equal(layout.box.y + layout.box.height, 720 - 12);
    assert_true(layout.box.y >= 0 && layout.box.x + layout.box.width <= 1280);
    assert_true((long long)layout.box.width * layout.box.height <= 1280 * 720 / 2);
    layout = luz_probe_panel_layout_for(960, 540, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.scale, 1);
    /* the centre of 1280x720, which the big box hides in every corner:
     * the small text, whose box leaves it in sight */
    probe->x = 640;
    probe->y = 360;
    layout = luz_probe_panel_layout_for(1280, 720, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_int_equal(layout.scale, 1);
    assert_true(layout.box.x + layout.box.width < 640 - 9 || layout.box.x > 640 + 9 ||
                layout.box.y + layout.box.height < 360 - 9 || layout.box.y > 360 + 9);
    free(probe);
}

/* In a small window the whole story would cover most of it: the panel
 * leaves out the six term rows, whose bars the light row's bar still
 * shows end to end, and lists fewer tests, to stay within half the
 * window's area. */
static void test_a_small_window_gets_a_compact_panel(void **state)
{
    (void)state;
    luz_pixel_probe *probe = hand_made_probe();
    probe->x = 20;
    probe->y = 20;
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    luz_probe_panel_layout layout = luz_probe_panel_layout_for(1280, 720, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_false(layout.compact);
    const int whole_rows = layout.row_count;
    assert_false(luz_probe_panel_layout_for(640, 360, probe, &names, false, LUZ_PROBE_PAGE_STORY).compact);

    layout = luz_probe_panel_layout_for(480, 270, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_true(layout.compact);
    assert_true(layout.box.width * layout.box.height <= 480 * 270 / 2);
    assert_true(layout.row_count < whole_rows - LUZ_TERM_COUNT + 1);
    assert_true(layout.box.y >= 0 && layout.box.y + layout.box.height <= 270);
    const int expected[LUZ_TERM_COUNT] = {14, 42, 0, 21, 35, 7};
    picture p;
    picture_begin(&p, 480, 270);
    luz_probe_panel_draw(&p.layer, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    picture_fill(&p);
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        assert_int_equal(layout.term_bar[term].width, 0);
        assert_int_equal(layout.light_bar[term].width, expected[term]);
        if (expected[term] > 0)
            assert_filled(&p, layout.light_bar[term], luz_probe_term_colour((luz_term)term));
    }
    assert_filled(&p, layout.swatch[LUZ_PROBE_SWATCH_BYTES], (luz_rgba){255, 54, 71, 255});
    picture_end(&p);

    /* A long history: cut to the half, and counted. */
    probe->test_count = probe->tests_kept = 40;
    for (int k = 0; k < 40; k++)
        probe->tests[k] = (luz_probe_test){.triangle = (uint32_t)(k + 1), .depth = 0.5f,
                                           .stored = 1.0f, .passed = k == 0};
    layout = luz_probe_panel_layout_for(480, 400, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_true(layout.compact);
    assert_true(layout.box.width * layout.box.height <= 480 * 400 / 2);
    assert_true(layout.history_rows > 0 && layout.history_rows < 40);
    layout = luz_probe_panel_layout_for(480, 270, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    assert_true(layout.box.width * layout.box.height <= 480 * 270 / 2);
    free(probe);
}

static void test_background_and_a_view(void **state)
{
    (void)state;
    luz_pixel_probe *probe = calloc(1, sizeof *probe);
    probe->x = 3;
    probe->y = 4;
    probe->filled = true;
    probe->view = LUZ_VIEW_OVERDRAW;
    probe->overdraw = 0;
    probe->shown = (luz_vec3){0, 0, 0};
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    const luz_probe_panel_layout layout =
        luz_probe_panel_layout_for(640, 360, probe, &names, false, LUZ_PROBE_PAGE_STORY);
    /* no bars, no texel; what the view shows, and the bytes */
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        assert_int_equal(layout.term_bar[term].width, 0);
        assert_int_equal(layout.light_bar[term].width, 0);
    }
    assert_int_equal(layout.swatch[LUZ_PROBE_SWATCH_TEXEL].width, 0);
    assert_true(layout.swatch[LUZ_PROBE_SWATCH_SHOWN].width > 0);
    assert_true(layout.swatch[LUZ_PROBE_SWATCH_BYTES].width > 0);
    free(probe);
}

static void test_marker_leaves_the_pixel(void **state)
{
    (void)state;
    picture p;
    picture_begin(&p, 64, 48);
    luz_probe_marker_draw(&p.layer, 30, 20);
    picture_fill(&p);
    assert_rgb(&p, 30, 20, 0, 0, 0);   /* the pixel itself stays as it was */
    for (int d = 3; d <= 8; d++) {
        assert_rgb(&p, 30 + d, 20, 255, 230, 40);
        assert_rgb(&p, 30 - d, 20, 255, 230, 40);
        assert_rgb(&p, 30, 20 + d, 255, 230, 40);
        assert_rgb(&p, 30, 20 - d, 255, 230, 40);
    }
    for (int d = 0; d <= 2; d++) assert_rgb(&p, 30 + d, 20, 0, 0, 0);
    /* at the edge of the frame, clipped, not a crash */
    luz_layer_begin(&p.layer, 64, 48);
    luz_probe_marker_draw(&p.layer, 0, 47);
    picture_fill(&p);
    assert_rgb(&p, 3, 47, 255, 230, 40);
    picture_end(&p);
}

/* ---- the numbers in between (U) ----------------------------------------------------- */

/* The hand-made probe with its intermediates worked by hand: P at the
 * origin facing +z (N = (0, 0, 1)), the eye and headlight at E = (3, 0, 4),
 * the point light at (0, 3, 4), the spot aimed from E through P, the sun
 * shining down -z. So (SCENE.md, "Lighting"):
 *   L = V = E / |E| = (0.6, 0, 0.8), N.L = 0.8;
 *   R = -L + 2 (N.L) N = (-0.6, 0, 0.8), V.R = -0.36 + 0.64 = 0.28;
 *   Lp = (0, 3, 4) / 5 = (0, 0.6, 0.8), N.Lp = 0.8;
 *   c = 1 (on the spot's axis), ci = cos 12.5 = 0.976, co = cos 17.5 = 0.954,
 *   f_dir = 1; dn = 5 / 20 = 0.25, f_win = (1 - 0.25^4)^2 = 0.992202,
 *   f_dist = f_win / (0.25^2 + 1) = 0.933837 (Sp.a = 1);
 *   sun = (0, 0, 1), N.sun = 1.
 * The model matrix moves by (1, 2, 3); the view is the identity but for
 * z - 3 (an eye at z = 3); the projection is made up, with -1 in row 3. */
static luz_pixel_probe *probe_with_intermediates(void)
{
    luz_pixel_probe *probe = hand_made_probe();
    luz_shade_steps *steps = &probe->steps;
    steps->normal_length = 1.0f;
    steps->to_light = (luz_vec3){0.6f, 0.0f, 0.8f};
    steps->n_dot_l = 0.8f;
    steps->to_viewer = (luz_vec3){0.6f, 0.0f, 0.8f};
    steps->reflected = (luz_vec3){-0.6f, 0.0f, 0.8f};
    steps->v_dot_r = 0.28f;
    steps->to_point = (luz_vec3){0.0f, 0.6f, 0.8f};
    steps->n_dot_lp = 0.8f;
    steps->spot_cos = 1.0f;
    steps->spot_cos_inner = cosf(12.5f * 3.14159265f / 180.0f);
    steps->spot_cos_outer = cosf(17.5f * 3.14159265f / 180.0f);
    steps->f_dir = 1.0f;
    steps->dn = 0.25f;
    steps->f_win = (1.0f - 0.25f * 0.25f * 0.25f * 0.25f) * (1.0f - 0.25f * 0.25f * 0.25f * 0.25f);
    steps->f_dist = steps->f_win / (0.25f * 0.25f + 1.0f);
    steps->to_sun = (luz_vec3){0.0f, 0.0f, 1.0f};
    steps->n_dot_sun = 1.0f;
    /* column-major (luz_mat4): the translation in m[12..14] */
    for (int k = 0; k < 4; k++) {
        probe->model_matrix.m[k * 5] = 1.0f;
        probe->view_matrix.m[k * 5] = 1.0f;
    }
    probe->model_matrix.m[12] = 1.0f;
    probe->model_matrix.m[13] = 2.0f;
    probe->model_matrix.m[14] = 3.0f;
    probe->view_matrix.m[14] = -3.0f;
    probe->projection_matrix.m[0] = 1.358f;
    probe->projection_matrix.m[5] = 2.414f;
    probe->projection_matrix.m[10] = -1.002f;
    probe->projection_matrix.m[11] = -1.0f;
    probe->projection_matrix.m[14] = -0.2f;
    /* a frame's worth of digits: corners, edge values, eight taps */
    for (int k = 0; k < 3; k++) {
        probe->corner_clip[k] = (luz_vec4){-0.679f, -1.207f, 2.305f, 2.5f};
        probe->corner_window[k] = (luz_vec3){813.824f, 533.824f, 0.96096f};
    }
    probe->edges[0] = (luz_probe_edge){.value = 3948930258LL, .top = true};
    probe->edges[1] = (luz_probe_edge){.value = 0, .left = true, .owns_its_samples = true};
    probe->edges[2] = (luz_probe_edge){.value = 0};
    probe->uv = (luz_vec2){0.5f, 0.25f};
    probe->du_dx = 0.0029f;
    probe->dv_dy = -0.0058f;
    probe->texture = (const luz_texture *)probe;   /* any non-NULL: named "unnamed" */
    probe->filter = LUZ_FILTER_TRILINEAR;
    probe->rho = 1.473f;
    probe->lambda = 0.559f;
    probe->levels = (luz_texture_mip_pair){.lower = 0, .upper = 1, .blend = 0.56f};
    probe->tap_count = 8;
    for (int k = 0; k < 8; k++)
        probe->taps[k] = (luz_probe_tap){.level = k / 4, .x = 127 + k % 2, .y = 128 + k / 2 % 2,
                                         .weight = 0.125f};
    return probe;
}

/* Whether line is among the first count of lines. */
static bool has_line(char (*lines)[LUZ_PROBE_PANEL_LINE], int count, const char *line)
{
    for (int i = 0; i < count; i++)
        if (strcmp(lines[i], line) == 0) return true;
    print_message("not found: '%s'\n", line);
    return false;
}

static void test_the_numbers_in_between(void **state)
{
    (void)state;
    luz_pixel_probe *probe = probe_with_intermediates();
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    char (*lines)[LUZ_PROBE_PANEL_LINE] = calloc(LUZ_PROBE_PANEL_MAX_ROWS, sizeof *lines);
    assert_non_null(lines);

    int count = luz_probe_panel_text(probe, &names, false, LUZ_PROBE_PAGE_LIGHT, lines,
                                     LUZ_PROBE_PANEL_MAX_ROWS);
    assert_true(has_line(lines, count, "PROBE 700,450  light (tour 8)"));
    assert_true(has_line(lines, count, "N 0.000 0.000 1.000  |N| 1.000"));
    assert_true(has_line(lines, count, "L 0.600 0.000 0.800  N.L 0.800"));
    assert_true(has_line(lines, count, "V 0.600 0.000 0.800"));
    assert_true(has_line(lines, count, "R -0.600 0.000 0.800  V.R 0.280"));
    assert_true(has_line(lines, count, "Lp 0.000 0.600 0.800  N.Lp 0.800"));
    assert_true(has_line(lines, count, "spot c 1.000  ci 0.976  co 0.954"));
    assert_true(has_line(lines, count, " f_dir 1.000  dn 0.250"));
    assert_true(has_line(lines, count, " f_win 0.992  f_dist 0.934"));
    assert_true(has_line(lines, count, "sun 0.000 0.000 1.000  N.sun 1.000"));
    assert_true(has_line(lines, count, "diffuse 0.900 0.600 0.300"));
    assert_true(has_line(lines, count, "light 2.000 1.700 1.400"));

    /* the matrices row by row, once: rows 0 and 3 of each */
    count = luz_probe_panel_text(probe, &names, true, LUZ_PROBE_PAGE_VERTEX, lines,
                                 LUZ_PROBE_PANEL_MAX_ROWS);
    assert_true(has_line(lines, count, "PROBE 700,450  vertex (tour 2)  (paused)"));
    assert_true(has_line(lines, count, "model   1.000   0.000   0.000   1.000"));
    assert_true(has_line(lines, count, "   0.000   1.000   0.000   2.000"));
    assert_true(has_line(lines, count, "   0.000   0.000   1.000   3.000"));
    assert_true(has_line(lines, count, "view   1.000   0.000   0.000   0.000"));
    assert_true(has_line(lines, count, "   0.000   0.000   1.000  -3.000"));
    assert_true(has_line(lines, count, "projection   1.358   0.000   0.000   0.000"));
    assert_true(has_line(lines, count, "   0.000   0.000  -1.000   0.000"));
    assert_true(has_line(lines, count, "clip 2 -0.679 -1.207 2.305 2.500"));
    int matrix_rows = 0;
    for (int i = 0; i < count; i++) matrix_rows += strchr(lines[i], '.') != NULL && i > 1;
    assert_int_equal(matrix_rows, 12 + 3);   /* the three matrices once, three corners */

    /* the edges: E > 0 inside; E = 0 the triangle's only if it owns its
     * samples (top or left); the eight taps two a row */
    count = luz_probe_panel_text(probe, &names, false, LUZ_PROBE_PAGE_RASTER, lines,
                                 LUZ_PROBE_PANEL_MAX_ROWS);
    assert_true(has_line(lines, count, "edge 0 3948930258  top  inside"));
    assert_true(has_line(lines, count, "edge 1 0  left  inside"));
    assert_true(has_line(lines, count, "edge 2 0  on it, not its"));
    assert_true(has_line(lines, count, "uv / dx, dy 0.0029 0.0000   0.0000 -0.0058"));
    assert_true(has_line(lines, count, "rho, lod 1.473  0.559  levels 0,1 (0.56)"));
    assert_true(has_line(lines, count, "taps L0 127,128 x0.125  L0 128,128 x0.125"));
    assert_true(has_line(lines, count, " L1 127,128 x0.125  L1 128,128 x0.125"));
    assert_true(has_line(lines, count, "T 0.500 0.250 1.000"));
    free(lines);
    free(probe);
}

/* Each page at 1280x720 and 640x360, for the centre pixel and a corner
 * one: every row listed, the box inside the frame and within half of it,
 * and the pixel and its marker left in sight; at 1280x720 the large text
 * for every page of numbers (they are narrower than the story). */
static void test_every_page_fits_and_leaves_the_pixel(void **state)
{
    (void)state;
    luz_pixel_probe *probe = probe_with_intermediates();
    const luz_scene scene = luz_scene_defaults();
    const luz_probe_names names = {.scene = &scene};
    char (*lines)[LUZ_PROBE_PANEL_LINE] = calloc(LUZ_PROBE_PANEL_MAX_ROWS, sizeof *lines);
    assert_non_null(lines);
    const int sizes[2][2] = {{1280, 720}, {640, 360}};
    for (int i = 0; i < 2; i++)
        for (int where = 0; where < 2; where++)
            for (int page = LUZ_PROBE_PAGE_VERTEX; page < LUZ_PROBE_PAGE_COUNT; page++) {
                const int width = sizes[i][0], height = sizes[i][1];
                probe->x = where ? 20 : width / 2;
                probe->y = where ? height - 20 : height / 2;
                const luz_probe_panel_layout layout = luz_probe_panel_layout_for(
                    width, height, probe, &names, false, (luz_probe_page)page);
                const int count = luz_probe_panel_text(probe, &names, false,
                                                       (luz_probe_page)page, lines,
                                                       LUZ_PROBE_PANEL_MAX_ROWS);
                print_message("%dx%d pixel %d,%d page %d: scale %d box %d,%d %dx%d\n", width,
                              height, probe->x, probe->y, page, layout.scale, layout.box.x,
                              layout.box.y, layout.box.width, layout.box.height);
                assert_int_equal(layout.row_count, count);
                assert_false(layout.compact);
                assert_true(layout.box.x >= 0 && layout.box.y >= 0);
                assert_true(layout.box.x + layout.box.width <= width);
                assert_true(layout.box.y + layout.box.height <= height);
                assert_true((long long)layout.box.width * layout.box.height <=
                            (long long)width * height / 2);
                /* the marker reaches 9 pixels round the pixel */
                assert_true(layout.box.x + layout.box.width < probe->x - 9 ||
                            layout.box.x > probe->x + 9 ||
                            layout.box.y + layout.box.height < probe->y - 9 ||
                            layout.box.y > probe->y + 9);
                if (width == 1280) assert_int_equal(layout.scale, 2);
            }
    free(lines);
    free(probe);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bars_are_the_terms),
        cmocka_unit_test(test_a_long_history_fits_a_small_window),
        cmocka_unit_test(test_a_small_window_gets_a_compact_panel),
        cmocka_unit_test(test_the_panel_leaves_the_pixel_in_sight),
        cmocka_unit_test(test_readable_text_where_it_fits),
        cmocka_unit_test(test_background_and_a_view),
        cmocka_unit_test(test_marker_leaves_the_pixel),
        cmocka_unit_test(test_the_numbers_in_between),
        cmocka_unit_test(test_every_page_fits_and_leaves_the_pixel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
