/*
 * test_framebuffer.c: the framebuffer's memory (luz/framebuffer.h) and its
 * PNG output.
 *
 * Colour is the framebuffer's own memory unless the caller lends some
 * (luz_framebuffer_use_colour, as a viewer lends a window's pixels): a
 * drawing must land in the lent memory and leave the own memory alone,
 * NULL and a resize must go back to the own memory, and the framebuffer
 * must never free what was lent. Clearing touches depth and visibility
 * only, since the shading pass writes every colour byte. A PNG is always
 * RGBA, so a BGRA framebuffer must come back from the file, read by
 * stb_image, as the RGBA image. luz_framebuffer_write_new_png must never
 * replace a file that exists.
 */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <stb_image.h>

#include "luz/luz.h"
#include "app/bench.h"
#include "app/controls.h"
#include "app/options.h"
#include "app/panel.h"
#include "io/image.h"
#include "io/textures.h"
#include "lab/scene.h"
#include "lab_support.h"

/* ---- clearing and allocation --------------------------------------------------- */

/* A new framebuffer draws into its own memory, in RGBA, cleared: depth at
 * the far plane, no triangle anywhere, and colour opaque black rather than
 * whatever malloc returned. */
static void test_create_gives_own_cleared_memory(void **state)
{
    (void)state;
    enum { WIDTH = 13, HEIGHT = 5 };
    luz_error error = {{0}};
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(framebuffer);
    assert_int_equal(framebuffer->channel_order, LUZ_CHANNELS_RGBA);
    assert_non_null(framebuffer->own_colour);
    assert_ptr_equal(framebuffer->colour, framebuffer->own_colour);
    for (size_t p = 0; p < (size_t)WIDTH * HEIGHT; p++) {
        assert_true(framebuffer->depth[p] == 1.0f);
        assert_int_equal(framebuffer->visibility[p], 0);
        const uint8_t *pixel = framebuffer->colour + p * 4;
        assert_int_equal(pixel[0], 0);
        assert_int_equal(pixel[1], 0);
        assert_int_equal(pixel[2], 0);
        assert_int_equal(pixel[3], 255);
    }
    luz_framebuffer_destroy(framebuffer);
}

/* Rows [2, 5) of a 13-pixel-wide buffer: 39 depths, not a whole number of
 * the eight-float stores clear_rows makes, so its last few go one by one.
 * Exactly those rows get depth 1 and visibility 0; every other row, and
 * all of colour, keep what they held. */
static void test_clear_rows_clears_depth_and_visibility_only(void **state)
{
    (void)state;
    enum { WIDTH = 13, HEIGHT = 7, FIRST = 2, END = 5 };
    luz_error error = {{0}};
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(framebuffer);
    const size_t pixels = (size_t)WIDTH * HEIGHT;
    for (size_t p = 0; p < pixels; p++) {
        framebuffer->depth[p] = 0.25f;
        framebuffer->visibility[p] = 7;
    }
    memset(framebuffer->colour, 0xA5, pixels * 4);

    luz_framebuffer_clear_rows(framebuffer, FIRST, END);
    for (int y = 0; y < HEIGHT; y++) {
        const bool cleared = y >= FIRST && y < END;
        for (int x = 0; x < WIDTH; x++) {
            const size_t p = (size_t)y * WIDTH + x;
            assert_true(framebuffer->depth[p] == (cleared ? 1.0f : 0.25f));
            assert_int_equal(framebuffer->visibility[p], cleared ? 0 : 7);
        }
    }
    for (size_t i = 0; i < pixels * 4; i++) assert_int_equal(framebuffer->colour[i], 0xA5);
    luz_framebuffer_destroy(framebuffer);
}

/* ---- lent colour memory --------------------------------------------------------- */

enum { SCENE_WIDTH = 160, SCENE_HEIGHT = 90 };

/* The default scene at t = 2.5 (no textures) drawn by renderer into
 * framebuffer with the options given. */
static void draw_samples_with(luz_renderer *renderer, luz_framebuffer *framebuffer,
                              const luz_render_options *options, int samples)
{
    luz_error error = {{0}};
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 2.5;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, NULL, 0,
                                           (float)framebuffer->width / (float)framebuffer->height,
                                           &frame, NULL),
                     0);
    frame.samples = samples;
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, options, &error), 0);
    luz_frame_free(&frame);
}

static void draw_with(luz_renderer *renderer, luz_framebuffer *framebuffer,
                      const luz_render_options *options)
{
    draw_samples_with(renderer, framebuffer, options, 1);
}

/* SCENE.md's default scene at t = 2.5 (no textures) into framebuffer. */
static void draw_into(luz_framebuffer *framebuffer)
{
    luz_error error = {{0}};
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 2}, &error);
    assert_non_null(renderer);
    draw_with(renderer, framebuffer, NULL);
    luz_renderer_destroy(renderer);
}

static bool all_bytes_are(const uint8_t *bytes, size_t count, uint8_t value)
{
    for (size_t i = 0; i < count; i++)
        if (bytes[i] != value) return false;
    return true;
}

/* The image drawn into lent memory (filled with 0xA5 first) is the image
 * drawn into a framebuffer's own memory, and the own memory (filled with
 * 0x5A) is not touched; after NULL the drawing lands in the own memory
 * again. Resizing, to the same size or another, goes back to the own
 * memory and keeps the channel order. The framebuffer never frees the lent
 * memory: it still holds what it held after luz_framebuffer_destroy, and
 * the test's own free() would be caught as a double free (by glibc, or by
 * AddressSanitizer in a sanitizer build) if the framebuffer had freed it. */
static void test_lent_colour_memory(void **state)
{
    (void)state;
    const size_t bytes = (size_t)SCENE_WIDTH * SCENE_HEIGHT * 4;
    luz_error error = {{0}};
    luz_framebuffer *expected = luz_framebuffer_create(SCENE_WIDTH, SCENE_HEIGHT, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(SCENE_WIDTH, SCENE_HEIGHT, &error);
    uint8_t *lent = malloc(bytes);
    assert_non_null(expected);
    assert_non_null(framebuffer);
    assert_non_null(lent);
    draw_into(expected);

    memset(lent, 0xA5, bytes);
    memset(framebuffer->own_colour, 0x5A, bytes);
    luz_framebuffer_use_colour(framebuffer, lent, LUZ_CHANNELS_RGBA);
    assert_ptr_equal(framebuffer->colour, lent);
    draw_into(framebuffer);
    assert_memory_equal(lent, expected->colour, bytes);
    assert_true(all_bytes_are(framebuffer->own_colour, bytes, 0x5A));

    luz_framebuffer_use_colour(framebuffer, NULL, LUZ_CHANNELS_RGBA);
    assert_ptr_equal(framebuffer->colour, framebuffer->own_colour);
    memset(lent, 0xA5, bytes);
    draw_into(framebuffer);
    assert_memory_equal(framebuffer->own_colour, expected->colour, bytes);
    assert_true(all_bytes_are(lent, bytes, 0xA5));

    /* A resize to the same size, then to another, each after lending
     * memory in BGRA. */
    luz_framebuffer_use_colour(framebuffer, lent, LUZ_CHANNELS_BGRA);
    assert_int_equal(luz_framebuffer_resize(framebuffer, SCENE_WIDTH, SCENE_HEIGHT, &error), 0);
    assert_ptr_equal(framebuffer->colour, framebuffer->own_colour);
    assert_int_equal(framebuffer->channel_order, LUZ_CHANNELS_BGRA);
    luz_framebuffer_use_colour(framebuffer, lent, LUZ_CHANNELS_BGRA);
    assert_int_equal(luz_framebuffer_resize(framebuffer, SCENE_WIDTH + 3, SCENE_HEIGHT, &error),
                     0);
    assert_ptr_equal(framebuffer->colour, framebuffer->own_colour);
    assert_ptr_not_equal(framebuffer->colour, lent);
    assert_int_equal(framebuffer->channel_order, LUZ_CHANNELS_BGRA);
    assert_int_equal(framebuffer->width, SCENE_WIDTH + 3);
    draw_into(framebuffer);
    assert_true(all_bytes_are(lent, bytes, 0xA5));

    luz_framebuffer_use_colour(framebuffer, lent, LUZ_CHANNELS_RGBA);
    luz_framebuffer_destroy(framebuffer);
    assert_true(all_bytes_are(lent, bytes, 0xA5));
    free(lent);
    luz_framebuffer_destroy(expected);
}

/* ---- PNG output ------------------------------------------------------------------ */

/* Pixel p of the test pattern, as RGBA: every channel different, alpha
 * included, so that a byte in the wrong place shows. */
static void pattern_pixel(size_t p, uint8_t rgba[4])
{
    rgba[0] = (uint8_t)(p * 7 + 1);
    rgba[1] = (uint8_t)(p * 13 + 2);
    rgba[2] = (uint8_t)(p * 29 + 3);
    rgba[3] = (uint8_t)(255 - p);
}

/* Writes framebuffer to directory/name and reads it back with stb_image as
 * four channels; asserts the pattern came back. */
static void assert_png_is_pattern(const luz_framebuffer *framebuffer, const char *directory,
                                  const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", directory, name);
    luz_error error = {{0}};
    if (luz_framebuffer_write_png(framebuffer, path, &error) != 0) fail_msg("%s", error.message);
    int width = 0, height = 0, channels = 0;
    uint8_t *read = stbi_load(path, &width, &height, &channels, 4);
    assert_non_null(read);
    assert_int_equal(width, framebuffer->width);
    assert_int_equal(height, framebuffer->height);
    for (size_t p = 0; p < (size_t)width * height; p++) {
        uint8_t expected[4];
        pattern_pixel(p, expected);
        if (memcmp(read + p * 4, expected, 4) != 0)
            fail_msg("%s: pixel %zu is (%d, %d, %d, %d), expected (%d, %d, %d, %d)", name, p,
                     read[p * 4], read[p * 4 + 1], read[p * 4 + 2], read[p * 4 + 3],
                     expected[0], expected[1], expected[2], expected[3]);
    }
    stbi_image_free(read);
    assert_int_equal(unlink(path), 0);
}


/* ---- colour only ---------------------------------------------------------------- */

/* luz_render_options.colour_only: the colour is the image a plain draw
 * gives, byte for byte, and the framebuffer's depth and visibility keep
 * what they held (0.25 and 7 here; a plain draw puts the cubes' ids and
 * depths there, which the first loop checks, so the test sees a
 * difference). Twice with one renderer of two threads: first at 160x90,
 * then at 333x75 (a wider band, so its band buffers grow, and a last
 * band of 11 rows), where a band buffer too small or a band written into
 * another's rows would show in the image (or to AddressSanitizer). A
 * probe reads depth and visibility after the frame, so with one the
 * option is ignored and they hold the frame's. Then at four samples a
 * pixel, whose bands keep every sample's depth and winner and the first
 * winners in band buffers four times as large (so they grow again at
 * each size): the colour is a plain four-sample draw's (the whole
 * frame's sample buffers), which is not the one-sample image, and depth
 * and visibility still hold 0.25 and 7. */
static void test_colour_only_leaves_depth_and_visibility(void **state)
{
    (void)state;
    static const int sizes[2][2] = {{SCENE_WIDTH, SCENE_HEIGHT}, {333, 75}};
    luz_error error = {{0}};
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 2}, &error);
    assert_non_null(renderer);
    for (int s = 0; s < 2; s++) {
        const int width = sizes[s][0], height = sizes[s][1];
        const size_t pixels = (size_t)width * height;
        luz_framebuffer *expected = luz_framebuffer_create(width, height, &error);
        luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, &error);
        assert_non_null(expected);
        assert_non_null(framebuffer);
        draw_with(renderer, expected, NULL);
        size_t covered = 0;
        for (size_t p = 0; p < pixels; p++)
            if (expected->visibility[p] != 0 && expected->depth[p] < 1.0f) covered++;
        assert_true(covered > pixels / 20);

        for (size_t p = 0; p < pixels; p++) {
            framebuffer->depth[p] = 0.25f;
            framebuffer->visibility[p] = 7;
        }
        draw_with(renderer, framebuffer, &(luz_render_options){.colour_only = true});
        assert_memory_equal(framebuffer->colour, expected->colour, pixels * 4);
        for (size_t p = 0; p < pixels; p++) {
            assert_true(framebuffer->depth[p] == 0.25f);
            assert_int_equal(framebuffer->visibility[p], 7);
        }

        luz_pixel_probe probe = {.x = width / 2, .y = height / 2};
        draw_with(renderer, framebuffer,
                  &(luz_render_options){.colour_only = true, .probe = &probe});
        assert_memory_equal(framebuffer->colour, expected->colour, pixels * 4);
        assert_memory_equal(framebuffer->visibility, expected->visibility,
                            pixels * sizeof *expected->visibility);
        assert_memory_equal(framebuffer->depth, expected->depth, pixels * sizeof *expected->depth);

        luz_framebuffer *four = luz_framebuffer_create(width, height, &error);
        assert_non_null(four);
        draw_samples_with(renderer, four, NULL, 4);
        assert_memory_not_equal(four->colour, expected->colour, pixels * 4);
        for (size_t p = 0; p < pixels; p++) {
            framebuffer->depth[p] = 0.25f;
            framebuffer->visibility[p] = 7;
        }
        draw_samples_with(renderer, framebuffer, &(luz_render_options){.colour_only = true}, 4);
        assert_memory_equal(framebuffer->colour, four->colour, pixels * 4);
        for (size_t p = 0; p < pixels; p++) {
            assert_true(framebuffer->depth[p] == 0.25f);
            assert_int_equal(framebuffer->visibility[p], 7);
        }
        luz_framebuffer_destroy(four);
        luz_framebuffer_destroy(framebuffer);
        luz_framebuffer_destroy(expected);
    }
    luz_renderer_destroy(renderer);
}

/* The teaching views at four samples with colour_only: each band splits
 * its samples into the views' planes from the thread's band buffers, and
 * the image is, byte for byte, the one a plain draw makes from the whole
 * frame's sample buffers, for every view, at 333x75 (a last band of 11
 * rows) on two threads; it is not the one-sample view (so four samples
 * were drawn). Each path has a renderer of its own, and the colour_only
 * one never holds the whole frame's depth, winners and first winners (36
 * bytes a pixel), only a band's 16 rows of them for each of its two
 * threads: its memory is at least 75 - 32 rows' worth below the plain
 * one's (both hold the views' planes; it was above when the views kept
 * the whole frame's buffers). */
static void test_colour_only_four_sample_views(void **state)
{
    (void)state;
    enum { WIDTH = 333, HEIGHT = 75 };
    static const luz_view views[] = {LUZ_VIEW_DEPTH, LUZ_VIEW_NORMALS, LUZ_VIEW_UV,
                                     LUZ_VIEW_MIP, LUZ_VIEW_OVERDRAW, LUZ_VIEW_TRIANGLES};
    const size_t pixels = (size_t)WIDTH * HEIGHT;
    luz_error error = {{0}};
    luz_renderer *plain = luz_renderer_create(&(luz_renderer_desc){.thread_count = 2}, &error);
    luz_renderer *banded = luz_renderer_create(&(luz_renderer_desc){.thread_count = 2}, &error);
    luz_framebuffer *one = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    luz_framebuffer *expected = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(plain);
    assert_non_null(banded);
    assert_non_null(one);
    assert_non_null(expected);
    assert_non_null(framebuffer);
    for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
        luz_frame_stats plain_stats = {0}, banded_stats = {0};
        draw_samples_with(plain, one, &(luz_render_options){.view = views[v]}, 1);
        draw_samples_with(plain, expected,
                          &(luz_render_options){.view = views[v], .stats = &plain_stats}, 4);
        draw_samples_with(banded, framebuffer,
                          &(luz_render_options){.view = views[v], .colour_only = true,
                                                .stats = &banded_stats},
                          4);
        assert_memory_not_equal(expected->colour, one->colour, pixels * 4);
        assert_memory_equal(framebuffer->colour, expected->colour, pixels * 4);
        assert_true(banded_stats.memory_bytes + (size_t)(HEIGHT - 2 * 16) * WIDTH * (4 * 8 + 4) <=
                    plain_stats.memory_bytes);
    }
    luz_framebuffer_destroy(framebuffer);
    luz_framebuffer_destroy(expected);
    luz_framebuffer_destroy(one);
    luz_renderer_destroy(banded);
    luz_renderer_destroy(plain);
}

/* The same pattern, stored RGBA in one framebuffer and BGRA (bytes 0 and 2
 * swapped) in another, gives the same PNG, the pattern in RGBA; writing
 * converts a copy, so the BGRA framebuffer is unchanged afterwards; and
 * the writer leaves nothing else in the directory. */
static void test_png_of_bgra_framebuffer_reads_back_as_rgba(void **state)
{
    (void)state;
    enum { WIDTH = 7, HEIGHT = 5 };
    const size_t pixels = (size_t)WIDTH * HEIGHT;
    luz_error error = {{0}};
    luz_framebuffer *rgba = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    luz_framebuffer *bgra = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(rgba);
    assert_non_null(bgra);
    luz_framebuffer_use_colour(bgra, NULL, LUZ_CHANNELS_BGRA);
    for (size_t p = 0; p < pixels; p++) {
        uint8_t pixel[4];
        pattern_pixel(p, pixel);
        memcpy(rgba->colour + p * 4, pixel, 4);
        const uint8_t swapped[4] = {pixel[2], pixel[1], pixel[0], pixel[3]};
        memcpy(bgra->colour + p * 4, swapped, 4);
    }
    uint8_t before[WIDTH * HEIGHT * 4];
    memcpy(before, bgra->colour, sizeof before);

    const char *tmp = getenv("TMPDIR");
    char directory[256];
    snprintf(directory, sizeof directory, "%s/luz-framebuffer-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    assert_non_null(mkdtemp(directory));
    assert_png_is_pattern(rgba, directory, "rgba.png");
    assert_png_is_pattern(bgra, directory, "bgra.png");
    assert_memory_equal(bgra->colour, before, sizeof before);

    DIR *handle = opendir(directory);
    assert_non_null(handle);
    struct dirent *entry;
    while ((entry = readdir(handle)) != NULL)
        if (strcmp(entry->d_name, ".") != 0 && strcmp(entry->d_name, "..") != 0)
            fail_msg("%s left behind in %s", entry->d_name, directory);
    closedir(handle);
    assert_int_equal(rmdir(directory), 0);
    luz_framebuffer_destroy(rgba);
    luz_framebuffer_destroy(bgra);
}

/* Writing a new PNG: the first write makes the file; a second one under
 * the same name, of a different image, reports LUZ_FILE_EXISTS and leaves
 * the first file byte for byte as it was, with no temporary file behind.
 * A file that is not a PNG at all is kept the same way. */
static void test_new_png_never_replaces_a_file(void **state)
{
    (void)state;
    luz_error error = {{0}};
    luz_framebuffer *first = luz_framebuffer_create(3, 2, &error);
    luz_framebuffer *second = luz_framebuffer_create(3, 2, &error);
    assert_non_null(first);
    assert_non_null(second);
    memset(first->colour, 200, 3 * 2 * 4);
    memset(second->colour, 10, 3 * 2 * 4);

    const char *tmp = getenv("TMPDIR");
    char directory[256], path[512], other[512];
    snprintf(directory, sizeof directory, "%s/luz-new-png-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    assert_non_null(mkdtemp(directory));
    snprintf(path, sizeof path, "%s/shot.png", directory);
    snprintf(other, sizeof other, "%s/notes.txt", directory);

    assert_int_equal(luz_framebuffer_write_new_png(first, path, &error), 0);
    assert_int_equal(luz_framebuffer_write_new_png(second, path, &error), LUZ_FILE_EXISTS);
    int width = 0, height = 0, channels = 0;
    uint8_t *read = stbi_load(path, &width, &height, &channels, 4);
    assert_non_null(read);
    assert_int_equal(width, 3);
    assert_int_equal(height, 2);
    assert_memory_equal(read, first->colour, 3 * 2 * 4);
    stbi_image_free(read);

    FILE *file = fopen(other, "w");
    assert_non_null(file);
    fputs("not a picture\n", file);
    assert_int_equal(fclose(file), 0);
    assert_int_equal(luz_framebuffer_write_new_png(second, other, &error), LUZ_FILE_EXISTS);
    char text[32] = {0};
    file = fopen(other, "r");
    assert_non_null(file);
    assert_non_null(fgets(text, sizeof text, file));
    fclose(file);
    assert_string_equal(text, "not a picture\n");

    /* Only the two files: no temporary left by the refused writes. */
    DIR *handle = opendir(directory);
    assert_non_null(handle);
    int entries = 0;
    struct dirent *entry;
    while ((entry = readdir(handle)) != NULL)
        if (strcmp(entry->d_name, ".") != 0 && strcmp(entry->d_name, "..") != 0) {
            entries++;
            if (strcmp(entry->d_name, "shot.png") != 0 && strcmp(entry->d_name, "notes.txt") != 0)
                fail_msg("%s left behind in %s", entry->d_name, directory);
        }
    closedir(handle);
    assert_int_equal(entries, 2);
    assert_int_equal(unlink(path), 0);
    assert_int_equal(unlink(other), 0);
    assert_int_equal(rmdir(directory), 0);
    luz_framebuffer_destroy(first);
    luz_framebuffer_destroy(second);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_gives_own_cleared_memory),
        cmocka_unit_test(test_clear_rows_clears_depth_and_visibility_only),
        cmocka_unit_test(test_lent_colour_memory),
        cmocka_unit_test(test_colour_only_leaves_depth_and_visibility),
        cmocka_unit_test(test_colour_only_four_sample_views),
        cmocka_unit_test(test_png_of_bgra_framebuffer_reads_back_as_rgba),
        cmocka_unit_test(test_new_png_never_replaces_a_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
