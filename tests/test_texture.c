/*
 * test_texture.c: mip chains, sampling and the level of detail of
 * luz/texture.h on tiny hand-made textures whose every filtered value is
 * worked out by hand from SCENE.md's rules.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "test_support.h"

#include "luz/texture.h"

/* Bilinear weights and 1/255 scaling in single precision. */
#define TOLERANCE 1e-6

/* A sample's red and green channels, given in bytes (0..255). */
#define assert_red_green(got, red, green) \
    assert_red_green_at((got), (red), (green), #got, __FILE__, __LINE__)

static void assert_red_green_at(luz_vec3 got, double red, double green, const char *expression,
                                const char *file, int line)
{
    assert_near_at(got.x, red / 255.0, TOLERANCE, expression, file, line);
    assert_near_at(got.y, green / 255.0, TOLERANCE, expression, file, line);
}

/* The 4x4 test texture. Red, row by row:
 *     10  20   0   1
 *     30  41   1   1
 *    100 100 255 255
 *    101 100 255 254
 * green = 255 - red, blue = 0, alpha = 255. Level 1 (2x2), each texel
 * (a + b + c + d + 2) / 4 in integers:
 *   red   (10+20+30+41+2)/4 = 103/4 = 25     (0+1+1+1+2)/4 = 5/4 = 1
 *         (100+100+101+100+2)/4 = 403/4 = 100 (255+255+255+254+2)/4 = 255
 *   green (245+235+225+214+2)/4 = 921/4 = 230 (255+254+254+254+2)/4 = 254
 *         (155+155+154+155+2)/4 = 621/4 = 155 (0+0+0+1+2)/4 = 0
 * Level 2 (1x1), from level 1: red (25+1+100+255+2)/4 = 383/4 = 95,
 * green (230+254+155+0+2)/4 = 641/4 = 160. The rounding is visible: a
 * truncating average would give red 0 (not 1) at level 1's top right. */
static const uint8_t red_4x4[16] = {
    10, 20, 0, 1, 30, 41, 1, 1, 100, 100, 255, 255, 101, 100, 255, 254,
};

static luz_texture *make_texture(int width, int height, const uint8_t *red)
{
    uint8_t rgba[16 * 4];
    for (int i = 0; i < width * height; i++) {
        rgba[4 * i + 0] = red[i];
        rgba[4 * i + 1] = (uint8_t)(255 - red[i]);
        rgba[4 * i + 2] = 0;
        rgba[4 * i + 3] = 255;
    }
    luz_error error;
    luz_texture *texture = luz_texture_create(width, height, rgba, &error);
    assert_non_null(texture);
    return texture;
}

static int setup_4x4(void **state)
{
    *state = make_texture(4, 4, red_4x4);
    return 0;
}

static int teardown_texture(void **state)
{
    luz_texture_destroy(*state);
    return 0;
}

static const uint8_t *texel(const luz_texture *texture, int level, int x, int y)
{
    const luz_texture_level *l = &texture->levels[level];
    return l->texels + ((size_t)y * l->width + x) * 4;
}

/* The chain of the 4x4: 4x4, 2x2, 1x1, with the texels above. */
static void test_mip_chain_of_4x4(void **state)
{
    const luz_texture *texture = *state;
    assert_int_equal(texture->level_count, 3);
    assert_int_equal(texture->levels[1].width, 2);
    assert_int_equal(texture->levels[1].height, 2);
    assert_int_equal(texture->levels[2].width, 1);
    assert_int_equal(texture->levels[2].height, 1);
    const int red[4] = {25, 1, 100, 255}, green[4] = {230, 254, 155, 0};
    for (int i = 0; i < 4; i++) {
        const uint8_t *t = texel(texture, 1, i % 2, i / 2);
        assert_int_equal(t[0], red[i]);
        assert_int_equal(t[1], green[i]);
        assert_int_equal(t[2], 0);
        assert_int_equal(t[3], 255);
    }
    assert_int_equal(texel(texture, 2, 0, 0)[0], 95);
    assert_int_equal(texel(texture, 2, 0, 0)[1], 160);
}

/* A 3x3: level 1 is max(1, floor(3/2)) = 1 square, the average of the
 * top-left 2x2 only (the odd last row and column are dropped):
 * (4 + 8 + 12 + 16 + 2) / 4 = 42 / 4 = 10. Including the 200s would give
 * far more. */
static void test_mip_chain_of_3x3_drops_odd_row_and_column(void **state)
{
    (void)state;
    const uint8_t red[9] = {4, 8, 200, 12, 16, 200, 200, 200, 200};
    luz_texture *texture = make_texture(3, 3, red);
    assert_int_equal(texture->level_count, 2);
    assert_int_equal(texture->levels[1].width, 1);
    assert_int_equal(texture->levels[1].height, 1);
    assert_int_equal(texel(texture, 1, 0, 0)[0], 10);
    luz_texture_destroy(texture);
}

/* A 4x1: levels 4x1, 2x1, 1x1. A single row pairs with itself, so the
 * 2x2 box is (a + b + a + b + 2) / 4: red 0 10 20 31 gives
 * (0+10+0+10+2)/4 = 5 and (20+31+20+31+2)/4 = 104/4 = 26, then
 * (5+26+5+26+2)/4 = 64/4 = 16. */
static void test_mip_chain_of_4x1(void **state)
{
    (void)state;
    const uint8_t red[4] = {0, 10, 20, 31};
    luz_texture *texture = make_texture(4, 1, red);
    assert_int_equal(texture->level_count, 3);
    assert_int_equal(texture->levels[1].width, 2);
    assert_int_equal(texture->levels[1].height, 1);
    assert_int_equal(texture->levels[2].width, 1);
    assert_int_equal(texture->levels[2].height, 1);
    assert_int_equal(texel(texture, 1, 0, 0)[0], 5);
    assert_int_equal(texel(texture, 1, 1, 0)[0], 26);
    assert_int_equal(texel(texture, 2, 0, 0)[0], 16);
    luz_texture_destroy(texture);
}

/* Sizes outside 1x1 .. 8192x8192 are refused with a message. */
static void test_create_refuses_bad_sizes(void **state)
{
    (void)state;
    const uint8_t rgba[4] = {0};
    luz_error error = {{0}};
    assert_null(luz_texture_create(0, 1, rgba, &error));
    assert_true(error.message[0] != '\0');
    assert_null(luz_texture_create(1, LUZ_TEXTURE_MAX_SIZE + 1, rgba, &error));
}

/* Nearest at each texel centre ((i + 0.5) / 4, (j + 0.5) / 4) returns that
 * texel. */
static void test_nearest_at_texel_centres(void **state)
{
    const luz_texture *texture = *state;
    for (int j = 0; j < 4; j++) {
        for (int i = 0; i < 4; i++) {
            luz_vec2 uv = {(i + 0.5f) / 4, (j + 0.5f) / 4};
            uint8_t red = red_4x4[j * 4 + i];
            assert_red_green(luz_texture_sample_nearest(texture, 0, uv), red, 255 - red);
        }
    }
}

/* Texel 0 covers [0, 0.25), texel 1 [0.25, 0.5): u = 0.2499 is red 10,
 * u = 0.25 and 0.2501 are red 20 (row 0, v = 0.125). Likewise v = 0.2499
 * is row 0, v = 0.2501 row 1 (red 30 in column 0). */
static void test_nearest_near_texel_edges(void **state)
{
    const luz_texture *texture = *state;
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.2499f, 0.125f}), 10, 245);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.25f, 0.125f}), 20, 235);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.2501f, 0.125f}), 20, 235);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.125f, 0.2499f}), 10, 245);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.125f, 0.2501f}), 30, 225);
}

/* REPEAT: only the fractional part counts. u = 1.25 is u = 0.25 (red 20),
 * u = -0.25 is u = 0.75 (red 1, texel 3 of row 0), v = -0.875 is v = 0.125
 * (row 0), and v = 2.625 is v = 0.625 (row 2: red 100 in column 0). */
static void test_nearest_repeats(void **state)
{
    const luz_texture *texture = *state;
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){1.25f, 0.125f}), 20, 235);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){-0.25f, 0.125f}), 1, 254);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.75f, 0.125f}), 1, 254);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.125f, -0.875f}), 10, 245);
    assert_red_green(luz_texture_sample_nearest(texture, 0, (luz_vec2){0.125f, 2.625f}), 100, 155);
}

/* Bilinear at a texel centre is that texel; halfway between the centres
 * of texels 0 and 1 of row 0 (u = 0.25, v = 0.125) it is their average,
 * red (10 + 20) / 2 = 15; a quarter of the way (u = 0.1875) it is
 * 0.75 * 10 + 0.25 * 20 = 12.5; halfway down (u = 0.125, v = 0.25),
 * (10 + 30) / 2 = 20; at the corner of four centres (0.25, 0.25),
 * (10 + 20 + 30 + 41) / 4 = 25.25 (green 229.75). */
static void test_bilinear_between_texel_centres(void **state)
{
    const luz_texture *texture = *state;
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.375f, 0.375f}), 41, 214);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.25f, 0.125f}), 15, 240);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.1875f, 0.125f}), 12.5,
                     242.5);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.125f, 0.25f}), 20, 235);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.25f, 0.25f}), 25.25,
                     229.75);
}

/* REPEAT in bilinear filtering: on a 2x1 texture with red 0 and 200, u = 0
 * lies halfway between the centre of the last texel (u = 0.75, i.e.
 * -0.25) and of the first (0.25): (200 + 0) / 2 = 100; so does u = 1.
 * u = 0.125 is 0.375 past the last centre and 0.125 short of the first:
 * 0.25 * 200 + 0.75 * 0 = 50 (green 0.25 * 55 + 0.75 * 255 = 205). At the
 * centres: 0 and 200. */
static void test_bilinear_wraps_around_the_edge(void **state)
{
    (void)state;
    const uint8_t red[2] = {0, 200};
    luz_texture *texture = make_texture(2, 1, red);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.0f, 0.5f}), 100, 155);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){1.0f, 0.5f}), 100, 155);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.125f, 0.5f}), 50, 205);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.25f, 0.5f}), 0, 255);
    assert_red_green(luz_texture_sample_bilinear(texture, 0, (luz_vec2){0.75f, 0.5f}), 200, 55);
    luz_texture_destroy(texture);
}

/* Trilinear at (0.25, 0.25), the centre of level 1's top-left texel and of
 * level 2's only one:
 *   lambda <= 0: bilinear level 0, red 25.25 (above), green 229.75;
 *   lambda = 0.5: halfway between level 0 (25.25) and level 1 (25):
 *     25.125, green (229.75 + 230) / 2 = 229.875;
 *   lambda = 1: level 1 alone, 25 / 230;
 *   lambda = 1.5: halfway between levels 1 and 2, (25 + 95) / 2 = 60,
 *     green (230 + 160) / 2 = 195;
 *   lambda = 2 and beyond: the last level, 95 / 160. */
static void test_trilinear_blends_levels(void **state)
{
    const luz_texture *texture = *state;
    const luz_vec2 uv = {0.25f, 0.25f};
    assert_red_green(luz_texture_sample_trilinear(texture, uv, -3.0f), 25.25, 229.75);
    assert_red_green(luz_texture_sample_trilinear(texture, uv, 0.0f), 25.25, 229.75);
    assert_red_green(luz_texture_sample_trilinear(texture, uv, 0.5f), 25.125, 229.875);
    assert_red_green(luz_texture_sample_trilinear(texture, uv, 1.0f), 25, 230);
    assert_red_green(luz_texture_sample_trilinear(texture, uv, 1.5f), 60, 195);
    assert_red_green(luz_texture_sample_trilinear(texture, uv, 2.0f), 95, 160);
    assert_red_green(luz_texture_sample_trilinear(texture, uv, 9.0f), 95, 160);
}

/* luz_texture_sample picks the filter: at (0.25, 0.25) with lambda 1.5,
 * nearest is texel (1, 1) (the point is its top-left corner), red 41;
 * bilinear 25.25 and trilinear 60 (above). A NULL texture is white for
 * every filter. */
static void test_sample_dispatches_on_filter(void **state)
{
    const luz_texture *texture = *state;
    const luz_vec2 corner = {0.25f, 0.25f};
    assert_red_green(luz_texture_sample(texture, LUZ_FILTER_NEAREST, corner, 1.5f), 41, 214);
    assert_red_green(luz_texture_sample(texture, LUZ_FILTER_BILINEAR, corner, 1.5f), 25.25,
                     229.75);
    assert_red_green(luz_texture_sample(texture, LUZ_FILTER_TRILINEAR, corner, 1.5f), 60, 195);
    const luz_filter filters[3] = {LUZ_FILTER_NEAREST, LUZ_FILTER_BILINEAR, LUZ_FILTER_TRILINEAR};
    for (int i = 0; i < 3; i++) {
        luz_vec3 white = luz_texture_sample(NULL, filters[i], corner, 1.5f);
        assert_true(white.x == 1.0f && white.y == 1.0f && white.z == 1.0f);
    }
}

/* lambda = log2(rho), rho the longer of the two pixel steps in level-0
 * texels (u scaled by the width 4, v by the height 4):
 *   du/dx = 1/4: one texel per pixel, rho = 1, lambda 0;
 *   du/dx = 1/2: two texels, lambda 1;
 *   du/dx = 1/2, dv/dy = 2: 2 texels across, 8 down: the max, lambda 3;
 *   du/dx = 3/4, dv/dx = 1: a step of (3, 4) texels, length 5,
 *   lambda = log2 5 = 2.32192809;
 *   du/dx = 1/8: half a texel, magnified, lambda <= 0. */
static void test_level_of_detail(void **state)
{
    const luz_texture *texture = *state;
    assert_near(luz_texture_level_of_detail(texture, 0.25f, 0, 0, 0.25f), 0.0, TOLERANCE);
    assert_near(luz_texture_level_of_detail(texture, 0.5f, 0, 0, 0), 1.0, TOLERANCE);
    assert_near(luz_texture_level_of_detail(texture, 0.5f, 0, 0, 2.0f), 3.0, TOLERANCE);
    assert_near(luz_texture_level_of_detail(texture, 0.75f, 1.0f, 0, 0), 2.32192809, 1e-5);
    assert_true(luz_texture_level_of_detail(texture, 0.125f, 0, 0, 0.125f) <= 0.0f);
}

/* On an 8x2 texture u and v scale differently: du/dx = 1/8 and dv/dy = 1/2
 * are one texel each (lambda 0); dv/dx = 1 is 2 texels (lambda 1). */
static void test_level_of_detail_of_non_square_texture(void **state)
{
    (void)state;
    uint8_t red[16] = {0};
    luz_texture *texture = make_texture(8, 2, red);
    assert_near(luz_texture_level_of_detail(texture, 0.125f, 0, 0, 0.5f), 0.0, TOLERANCE);
    assert_near(luz_texture_level_of_detail(texture, 0, 1.0f, 0, 0), 1.0, TOLERANCE);
    luz_texture_destroy(texture);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_mip_chain_of_4x4, setup_4x4, teardown_texture),
        cmocka_unit_test(test_mip_chain_of_3x3_drops_odd_row_and_column),
        cmocka_unit_test(test_mip_chain_of_4x1),
        cmocka_unit_test(test_create_refuses_bad_sizes),
        cmocka_unit_test_setup_teardown(test_nearest_at_texel_centres, setup_4x4,
                                        teardown_texture),
        cmocka_unit_test_setup_teardown(test_nearest_near_texel_edges, setup_4x4,
                                        teardown_texture),
        cmocka_unit_test_setup_teardown(test_nearest_repeats, setup_4x4, teardown_texture),
        cmocka_unit_test_setup_teardown(test_bilinear_between_texel_centres, setup_4x4,
                                        teardown_texture),
        cmocka_unit_test(test_bilinear_wraps_around_the_edge),
        cmocka_unit_test_setup_teardown(test_trilinear_blends_levels, setup_4x4,
                                        teardown_texture),
        cmocka_unit_test_setup_teardown(test_sample_dispatches_on_filter, setup_4x4,
                                        teardown_texture),
        cmocka_unit_test_setup_teardown(test_level_of_detail, setup_4x4, teardown_texture),
        cmocka_unit_test(test_level_of_detail_of_non_square_texture),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
