/*
 * test_samples.c: four samples a pixel (SCENE.md, "Anti-aliasing: four
 * samples a pixel").
 *
 * The frames are built by hand: identity view and projection, so a
 * vertex's position is its clip position with w = 1, and on the W x H =
 * 16 x 16 viewport x_win = (x + 1) * 8, y_win = (1 - y) * 8. Unlit
 * materials write their colour as it is, round(c * 255), so every byte
 * below is worked out by hand from the positions SCENE.md gives:
 *
 *     sample 0 (0.375, 0.125), 1 (0.875, 0.375), 2 (0.125, 0.625),
 *     3 (0.625, 0.875)
 *
 * and the resolve floor((s0 + s1 + s2 + s3 + 2) / 4). Which triangle won
 * each sample is read from the public probe (luz/probe.h), whose sample
 * winners are the raster stage's arithmetic again; the bytes from the
 * image itself.
 */
#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "luz/luz.h"
#include "lab/scene.h"
#include "lab_support.h"

#define SIZE 16

/* x_win -> x_ndc and y_win -> y_ndc on the 16 x 16 viewport. */
static float ndc_x(double x_win) { return (float)(x_win / 8.0 - 1.0); }
static float ndc_y(double y_win) { return (float)(1.0 - y_win / 8.0); }

typedef struct scene {
    luz_mesh *meshes[4];
    int mesh_count;
    luz_frame frame;
} scene;

/* Adds triangle (a, b, c), each (x_win, y_win, z_ndc), counter-clockwise
 * in NDC, drawn unlit in colour. */
static void add_triangle(scene *s, const double a[3], const double b[3], const double c[3],
                         luz_vec3 colour)
{
    const double *corner[3] = {a, b, c};
    luz_vertex vertices[3];
    for (int k = 0; k < 3; k++)
        vertices[k] = (luz_vertex){
            .position = {ndc_x(corner[k][0]), ndc_y(corner[k][1]), (float)corner[k][2]},
            .normal = {0.0f, 0.0f, 1.0f},
        };
    const uint32_t indices[3] = {0, 1, 2};
    luz_error error = {{0}};
    luz_mesh *mesh = luz_mesh_create(
        &(luz_mesh_desc){.vertices = vertices, .vertex_count = 3, .indices = indices,
                         .index_count = 3},
        &error);
    assert_non_null(mesh);
    s->meshes[s->mesh_count++] = mesh;
    luz_draw draw = {.mesh = mesh, .model = luz_mat4_identity(),
                     .material = {.shading = LUZ_SHADING_UNLIT, .colour = colour,
                                  .has_colour = true}};
    assert_int_equal(luz_frame_add_draw(&s->frame, &draw, &error), 0);
}

static void scene_begin(scene *s, int samples)
{
    memset(s, 0, sizeof *s);
    s->frame.view = luz_mat4_identity();
    s->frame.projection = luz_mat4_identity();
    s->frame.clear_colour = (luz_vec3){0.1f, 0.1f, 0.1f};
    s->frame.samples = samples;
}

static void scene_end(scene *s)
{
    luz_frame_free(&s->frame);
    for (int k = 0; k < s->mesh_count; k++) luz_mesh_destroy(s->meshes[k]);
}

/* Draws the frame and probes pixel (x, y); returns the image (caller
 * frees). */
static uint8_t *draw(const scene *s, int threads, int x, int y, luz_pixel_probe *probe)
{
    luz_error error = {{0}};
    luz_renderer *renderer =
        luz_renderer_create(&(luz_renderer_desc){.thread_count = threads}, &error);
    assert_non_null(renderer);
    luz_framebuffer *framebuffer = luz_framebuffer_create(SIZE, SIZE, &error);
    assert_non_null(framebuffer);
    if (probe) {
        probe->x = x;
        probe->y = y;
    }
    assert_int_equal(luz_renderer_draw(renderer, &s->frame, framebuffer,
                                       &(luz_render_options){.probe = probe}, &error),
                     0);
    uint8_t *image = malloc(SIZE * SIZE * 4);
    assert_non_null(image);
    memcpy(image, framebuffer->colour, SIZE * SIZE * 4);
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
    return image;
}

static const uint8_t *pixel(const uint8_t *image, int x, int y)
{
    return image + ((size_t)y * SIZE + (size_t)x) * 4;
}

static const luz_vec3 red = {1.0f, 0.0f, 0.0f};
static const luz_vec3 blue = {0.0f, 0.0f, 1.0f};

/* The clear colour 0.1: round(25.5) = 26 (0.1f * 255 is a hair above). */
#define CLEAR_BYTE 26

/* Which of pixel (x, y)'s four samples the probe finds won by triangle
 * id, as bits. */
static unsigned samples_won(const luz_pixel_probe *probe, uint32_t id)
{
    unsigned bits = 0;
    for (int k = 0; k < 4; k++)
        if (probe->sample[k].triangle == id) bits |= 1u << k;
    return bits;
}

/* A half-plane through pixel (10, 5): a triangle whose left edge is the
 * vertical line x = 10.5 covers samples 1 (x 10.875) and 3 (10.625), not
 * 0 (10.375) or 2 (10.125). One whose top edge is y = 5.5 covers 2
 * (y 5.625) and 3 (5.875). One whose edge is the diagonal x + y = 16
 * through the pixel, the triangle below-right of it, covers the samples
 * with sx + sy > 1: 1 (1.25) and 3 (1.5), not 0 (0.5) or 2 (0.75). */
static void test_half_plane_covers_the_samples_the_positions_say(void **state)
{
    (void)state;
    struct {
        double a[3], b[3], c[3];
        unsigned expected;
    } cases[] = {
        /* right of x = 10.5: (10.5, 38) -> (38, 38) -> (10.5, -20), CCW in NDC */
        {{10.5, 38, 0}, {38, 38, 0}, {10.5, -20, 0}, 1u << 1 | 1u << 3},
        /* below y = 5.5 */
        {{-20, 5.5, 0}, {-20, 38, 0}, {38, 5.5, 0}, 1u << 2 | 1u << 3},
        /* x + y >= 16: (16, 0), (-10, 26), (38, 26) */
        {{16, 0, 0}, {-10, 26, 0}, {38, 26, 0}, 1u << 1 | 1u << 3},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scene s;
        scene_begin(&s, 4);
        add_triangle(&s, cases[i].a, cases[i].b, cases[i].c, red);
        luz_pixel_probe probe;
        uint8_t *image = draw(&s, 1, 10, 5, &probe);
        assert_int_equal(probe.samples, 4);
        assert_int_equal(samples_won(&probe, 1), cases[i].expected);
        /* Two samples red (255, 0, 0), two the clear colour (26 each):
         * red floor((255 + 255 + 26 + 26 + 2) / 4) = 141, green and blue
         * floor((26 + 26 + 2) / 4) = 13. */
        const uint8_t *p = pixel(image, 10, 5);
        assert_int_equal(p[0], 141);
        assert_int_equal(p[1], 13);
        assert_int_equal(p[2], 13);
        assert_int_equal(p[3], 255);
        assert_int_equal(probe.bytes[0], 141);
        free(image);
        scene_end(&s);
    }
}

/* Pixel (10, 5) split at x = 10.5 between a blue triangle on the left
 * (samples 0 and 2) and a red one on the right (1 and 3): red
 * floor((0 + 255 + 0 + 255 + 2) / 4) = 128, blue the same, green 0. At
 * one sample the centre, x = 10.5, lies on the shared edge, which is the
 * red triangle's left edge: the pixel is red. */
static void test_pixel_split_between_two_triangles(void **state)
{
    (void)state;
    for (int samples = 1; samples <= 4; samples += 3) {
        scene s;
        scene_begin(&s, samples);
        add_triangle(&s, (double[]){-20, 38, 0}, (double[]){10.5, 38, 0},
                     (double[]){10.5, -20, 0}, blue);
        add_triangle(&s, (double[]){10.5, 38, 0}, (double[]){38, 38, 0},
                     (double[]){10.5, -20, 0}, red);
        luz_pixel_probe probe;
        uint8_t *image = draw(&s, 1, 10, 5, &probe);
        const uint8_t *p = pixel(image, 10, 5);
        if (samples == 4) {
            assert_int_equal(samples_won(&probe, 1), 1u << 0 | 1u << 2);
            assert_int_equal(samples_won(&probe, 2), 1u << 1 | 1u << 3);
            assert_int_equal(p[0], 128);
            assert_int_equal(p[1], 0);
            assert_int_equal(p[2], 128);
        } else {
            assert_int_equal(p[0], 255);
            assert_int_equal(p[1], 0);
            assert_int_equal(p[2], 0);
        }
        /* Pixels wholly inside either triangle keep its colour. */
        assert_int_equal(pixel(image, 3, 5)[2], 255);
        assert_int_equal(pixel(image, 3, 5)[0], 0);
        assert_int_equal(pixel(image, 13, 5)[0], 255);
        assert_int_equal(pixel(image, 13, 5)[2], 0);
        free(image);
        scene_end(&s);
    }
}

/* Depth per sample: a blue triangle at z = 0 over the whole viewport,
 * then a red one whose depth rises to the right, z = 0.2 (x_ndc - x0),
 * crossing the blue one at x_win = 8.44: nearer (LESS) left of it. Pixel
 * (8, 8)'s centre, 8.5, is right of the crossing: one sample gives blue.
 * With four, samples 0 (8.375) and 2 (8.125) are left of it and go to
 * red, 1 and 3 stay blue: red and blue floor((255 + 255 + 2) / 4) = 128,
 * a colour the centre alone cannot give. */
static void test_depth_per_sample_decides_the_winner(void **state)
{
    (void)state;
    const double crossing = 8.44;
    const double x0 = crossing / 8.0 - 1.0;
    /* z at x_win: 0.2 (x_win / 8 - 1 - x0) */
    const double left = -20, right = 38;
    const double z_left = 0.2 * (left / 8.0 - 1.0 - x0), z_right = 0.2 * (right / 8.0 - 1.0 - x0);
    for (int samples = 1; samples <= 4; samples += 3) {
        scene s;
        scene_begin(&s, samples);
        add_triangle(&s, (double[]){left, 38, 0}, (double[]){right, 38, 0},
                     (double[]){left, -20, 0}, blue);
        add_triangle(&s, (double[]){right, 38, 0}, (double[]){right, -20, 0},
                     (double[]){left, -20, 0}, blue);
        add_triangle(&s, (double[]){left, 38, z_left}, (double[]){right, 38, z_right},
                     (double[]){left, -20, z_left}, red);
        add_triangle(&s, (double[]){right, 38, z_right}, (double[]){right, -20, z_right},
                     (double[]){left, -20, z_left}, red);
        luz_pixel_probe probe;
        uint8_t *image = draw(&s, 1, 8, 8, &probe);
        const uint8_t *p = pixel(image, 8, 8);
        if (samples == 1) {
            assert_int_equal(p[0], 0);
            assert_int_equal(p[2], 255);
        } else {
            /* Samples 0 and 2 went to a red triangle (id 3 or 4). */
            for (int k = 0; k < 4; k++) {
                const bool red_won = probe.sample[k].triangle >= 3;
                assert_int_equal(red_won, k == 0 || k == 2);
            }
            assert_int_equal(p[0], 128);
            assert_int_equal(p[1], 0);
            assert_int_equal(p[2], 128);
        }
        free(image);
        scene_end(&s);
    }
}

/* The top-left rule on a sample exactly on a shared edge: two triangles
 * share the vertical edge x = 10.375, on which sample 0 of every pixel of
 * column 10 lies (10.375 = 2656 / 256, exact). It is the right
 * triangle's left edge, so the sample is the right one's, and exactly
 * one triangle tests it: no gap, no double hit. */
static void test_top_left_rule_on_a_sample(void **state)
{
    (void)state;
    const double edge = 10.375;
    scene s;
    scene_begin(&s, 4);
    add_triangle(&s, (double[]){-20, 38, 0}, (double[]){edge, 38, 0}, (double[]){edge, -20, 0},
                 blue);
    add_triangle(&s, (double[]){edge, 38, 0}, (double[]){38, 38, 0}, (double[]){edge, -20, 0},
                 red);
    for (int y = 0; y < SIZE; y++) {
        luz_pixel_probe probe;
        uint8_t *image = draw(&s, 1, 10, y, &probe);
        assert_int_equal(probe.sample[0].test_count, 1);
        assert_int_equal(probe.sample[0].triangle, 2);   /* the right one */
        assert_int_equal(probe.sample[2].triangle, 1);   /* x 10.125: left */
        /* samples 0, 1, 3 red, 2 blue: red floor((3 * 255 + 2) / 4) =
         * 191, blue floor((255 + 2) / 4) = 64 */
        assert_int_equal(pixel(image, 10, y)[0], 191);
        assert_int_equal(pixel(image, 10, y)[2], 64);
        free(image);
    }
    scene_end(&s);
}

/* The same rule with small triangles, at most 8 pixels wide, which the
 * raster walks pixel by pixel, each pixel's four samples together
 * (raster.c), instead of finding each sample's span of a row: a blue one
 * from x = 7 and a red one to x = 13.5 share the edge x = 10.375, with
 * the red one's corners listed in each of their three rotations (so that
 * the shared edge is each of its edges 0, 1 and 2 in turn). Column 10:
 * sample 0 on the edge (red's left edge: red's), 2 at 10.125 blue's, 1
 * and 3 red's at every row. */
static void test_top_left_rule_on_a_sample_of_a_small_triangle(void **state)
{
    (void)state;
    const double edge = 10.375;
    const double red_corners[3][3] = {{edge, 38, 0}, {13.5, 38, 0}, {edge, -20, 0}};
    for (int rotation = 0; rotation < 3; rotation++) {
        scene s;
        scene_begin(&s, 4);
        add_triangle(&s, (double[]){7, 38, 0}, (double[]){edge, 38, 0},
                     (double[]){edge, -20, 0}, blue);
        add_triangle(&s, red_corners[rotation], red_corners[(rotation + 1) % 3],
                     red_corners[(rotation + 2) % 3], red);
        uint8_t *image = draw(&s, 1, 0, 0, NULL);
        for (int y = 0; y < SIZE; y++) {
            assert_int_equal(pixel(image, 10, y)[0], 191);
            assert_int_equal(pixel(image, 10, y)[2], 64);
        }
        free(image);
        scene_end(&s);
    }
}

/* The lab's default scene, small: every pixel whose four samples one
 * triangle won has exactly the one-sample image's bytes (shading is once
 * per pixel at its centre, as with one sample), and the probe's resolve
 * of its four sample colours is the image's byte at every pixel. */
static void test_covered_pixels_keep_their_one_sample_colour(void **state)
{
    (void)state;
    const int width = 96, height = 54;
    luz_scene lab_scene = luz_scene_defaults();
    luz_error error = {{0}};
    luz_frame frame = {0};
    const luz_texture_set *textures = lab_textures();
    assert_int_equal(luz_scene_build_frame(test_lab(), &lab_scene, textures->textures,
                                           textures->count, (float)width / (float)height, &frame,
                                           &error),
                     0);
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    luz_framebuffer *one = luz_framebuffer_create(width, height, &error);
    luz_framebuffer *four = luz_framebuffer_create(width, height, &error);
    assert_non_null(renderer);
    assert_non_null(one);
    assert_non_null(four);
    frame.samples = 1;
    assert_int_equal(luz_renderer_draw(renderer, &frame, one, NULL, &error), 0);
    frame.samples = 4;
    assert_int_equal(luz_renderer_draw(renderer, &frame, four, NULL, &error), 0);
    int covered = 0, mixed = 0;
    luz_framebuffer *scratch = luz_framebuffer_create(width, height, &error);
    assert_non_null(scratch);
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            luz_pixel_probe probe = {.x = x, .y = y};
            assert_int_equal(luz_renderer_draw(renderer, &frame, scratch,
                                               &(luz_render_options){.probe = &probe}, &error),
                             0);
            const uint8_t *p4 = four->colour + ((size_t)y * width + x) * 4;
            const uint8_t *p1 = one->colour + ((size_t)y * width + x) * 4;
            for (int c = 0; c < 3; c++) {
                const unsigned sum = probe.sample[0].bytes[c] + probe.sample[1].bytes[c] +
                                     probe.sample[2].bytes[c] + probe.sample[3].bytes[c];
                assert_int_equal(p4[c], (sum + 2) / 4);
            }
            const uint32_t id = probe.sample[0].triangle;
            if (id != 0 && probe.sample[1].triangle == id && probe.sample[2].triangle == id &&
                probe.sample[3].triangle == id) {
                covered++;
                assert_memory_equal(p4, p1, 4);
            } else if (probe.sample[0].triangle != probe.sample[1].triangle ||
                       probe.sample[0].triangle != probe.sample[2].triangle ||
                       probe.sample[0].triangle != probe.sample[3].triangle) {
                mixed++;
            }
        }
    }
    /* The scene has both kinds in plenty. */
    printf("covered pixels %d, mixed %d\n", covered, mixed);
    assert_true(covered > 1000);
    assert_true(mixed > 100);
    luz_framebuffer_destroy(scratch);
    luz_framebuffer_destroy(one);
    luz_framebuffer_destroy(four);
    luz_renderer_destroy(renderer);
    luz_frame_free(&frame);
}

/* Four samples, 1, 2 and 3 threads, 100 cubes at an odd size: the same
 * bytes; and the reference fragment stage agrees with the packets. */
static void test_four_samples_same_bytes_for_any_thread_count(void **state)
{
    (void)state;
    const int width = 331, height = 197;
    luz_scene lab_scene = luz_scene_defaults();
    lab_scene.cube_count = 100;
    lab_scene.time_seconds = 1.7;
    luz_error error = {{0}};
    luz_frame frame = {0};
    const luz_texture_set *textures = lab_textures();
    assert_int_equal(luz_scene_build_frame(test_lab(), &lab_scene, textures->textures,
                                           textures->count, (float)width / (float)height, &frame,
                                           &error),
                     0);
    frame.samples = 4;
    uint8_t *first = NULL;
    for (int threads = 1; threads <= 3; threads++) {
        luz_renderer *renderer =
            luz_renderer_create(&(luz_renderer_desc){.thread_count = threads}, &error);
        luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, &error);
        assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, NULL, &error), 0);
        if (first == NULL) {
            first = malloc((size_t)width * height * 4);
            memcpy(first, framebuffer->colour, (size_t)width * height * 4);
        } else {
            assert_memory_equal(first, framebuffer->colour, (size_t)width * height * 4);
        }
        luz_framebuffer_destroy(framebuffer);
        luz_renderer_destroy(renderer);
    }
    luz_renderer *reference = luz_renderer_create(
        &(luz_renderer_desc){.thread_count = 2, .reference = true}, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, &error);
    assert_int_equal(luz_renderer_draw(reference, &frame, framebuffer, NULL, &error), 0);
    int differ = 0;
    for (size_t i = 0; i < (size_t)width * height * 4; i++) {
        const int d = abs((int)first[i] - (int)framebuffer->colour[i]);
        assert_true(d <= 1);
        differ += d != 0;
    }
    assert_true(differ < width * height / 100);
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(reference);
    free(first);
    luz_frame_free(&frame);
}

/* A sample count other than 0, 1 or 4 is an error, named. */
static void test_bad_sample_counts_are_errors(void **state)
{
    (void)state;
    const int bad[] = {-1, 2, 3, 5, 8, 16};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        scene s;
        scene_begin(&s, bad[i]);
        add_triangle(&s, (double[]){0, 16, 0}, (double[]){16, 16, 0}, (double[]){0, 0, 0}, red);
        luz_error error = {{0}};
        luz_renderer *renderer =
            luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
        luz_framebuffer *framebuffer = luz_framebuffer_create(SIZE, SIZE, &error);
        assert_int_equal(luz_renderer_draw(renderer, &s.frame, framebuffer, NULL, &error), -1);
        assert_non_null(strstr(error.message, "samples"));
        luz_framebuffer_destroy(framebuffer);
        luz_renderer_destroy(renderer);
        scene_end(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_half_plane_covers_the_samples_the_positions_say),
        cmocka_unit_test(test_pixel_split_between_two_triangles),
        cmocka_unit_test(test_depth_per_sample_decides_the_winner),
        cmocka_unit_test(test_top_left_rule_on_a_sample),
        cmocka_unit_test(test_top_left_rule_on_a_sample_of_a_small_triangle),
        cmocka_unit_test(test_covered_pixels_keep_their_one_sample_colour),
        cmocka_unit_test(test_four_samples_same_bytes_for_any_thread_count),
        cmocka_unit_test(test_bad_sample_counts_are_errors),
    };
    return cmocka_run_group_tests(tests, lab_textures_load, lab_textures_free);
}
