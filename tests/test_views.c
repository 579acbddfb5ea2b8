/*
 * test_views.c: the teaching views (--view) and affine interpolation
 * (--interp affine), through luz_renderer_draw.
 *
 * Most checks draw hand-made quads with a camera at the origin looking down
 * -z with a 90-degree field of view on a square image, so that a point at
 * depth d with NDC coordinates (x, y) sits at world (x d, y d, -d): where a
 * quad lands on the screen, and what its uv, normal and depth are at a
 * pixel centre, follow from that by hand. The views' palettes are
 * luz/view.h's; what is tested is that each view puts the right one of
 * them at the right pixel.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "luz/luz.h"
#include "app/bench.h"
#include "app/controls.h"
#include "app/options.h"
#include "app/panel.h"
#include "io/image.h"
#include "io/textures.h"
#include "lab/scene.h"
#include "lab_support.h"

/* ---- rendering ------------------------------------------------------------------ */

static luz_framebuffer *draw_frame(const luz_frame *frame, const luz_render_options *render,
                                   int width, int height, int threads, bool reference)
{
    luz_error error = {{0}};
    luz_renderer *renderer = luz_renderer_create(
        &(luz_renderer_desc){.thread_count = threads, .reference = reference}, &error);
    assert_non_null(renderer);
    luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, &error);
    assert_non_null(framebuffer);
    assert_int_equal(luz_renderer_draw(renderer, frame, framebuffer, render, &error), 0);
    luz_renderer_destroy(renderer);
    return framebuffer;
}

/* SCENE.md's default scene with the repository's textures. */
static luz_framebuffer *draw_scene(const luz_scene *scene, const luz_texture_set *textures,
                                   int width, int height, int threads, bool reference)
{
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), scene, textures ? textures->textures : NULL,
                                           textures ? textures->count : 0,
                                           (float)width / (float)height, &frame, NULL),
                     0);
    const luz_render_options render = luz_scene_render_options(scene);
    luz_framebuffer *framebuffer = draw_frame(&frame, &render, width, height, threads, reference);
    luz_frame_free(&frame);
    return framebuffer;
}

static int load_textures(void **state)
{
    luz_texture_set *textures = calloc(1, sizeof *textures);
    luz_error error = {{0}};
    const char *directory = getenv("LUZ_TEXTURES");
    if (!textures || !directory || luz_texture_set_load(textures, directory, NULL, &error) != 0) {
        free(textures);
        return -1;
    }
    *state = textures;
    return 0;
}

static int free_textures(void **state)
{
    luz_texture_set_free(*state);
    free(*state);
    return 0;
}

static const uint8_t *pixel_of(const luz_framebuffer *framebuffer, int x, int y)
{
    return framebuffer->colour + ((size_t)y * framebuffer->width + x) * 4;
}

#define assert_pixel_near(framebuffer, x, y, expected, tolerance) \
    assert_pixel_near_at((framebuffer), (x), (y), (expected), (tolerance), __FILE__, __LINE__)

/* Each channel within `tolerance` levels of round(expected * 255). */
static void assert_pixel_near_at(const luz_framebuffer *framebuffer, int x, int y,
                                 luz_vec3 expected, int tolerance, const char *file, int line)
{
    const uint8_t *p = pixel_of(framebuffer, x, y);
    const float want[3] = {expected.x, expected.y, expected.z};
    for (int c = 0; c < 3; c++) {
        int byte = luz_colour_to_byte(want[c]);
        if (abs(p[c] - byte) > tolerance) {
            print_error("pixel (%d, %d) is (%d, %d, %d), expected (%d, %d, %d) +- %d\n", x, y,
                        p[0], p[1], p[2], luz_colour_to_byte(want[0]),
                        luz_colour_to_byte(want[1]), luz_colour_to_byte(want[2]), tolerance);
            _fail(file, line);
        }
    }
}

/* ---- hand-made quads ------------------------------------------------------------------ */

/* The camera of every quad test: at the origin, looking down -z, 90
 * degrees, and SCENE.md's lights; returns the options that draw the view
 * with the interpolation. */
static luz_render_options quad_frame(luz_frame *frame, luz_view view,
                                     luz_interpolation interpolation)
{
    luz_scene scene = luz_scene_defaults();
    scene.camera.position = (luz_vec3){0.0f, 0.0f, 0.0f};
    scene.camera.yaw_degrees = -90.0f;
    scene.camera.fov_degrees = 90.0f;
    luz_scene_set_camera_and_lights(&scene, 1.0f, frame);
    return (luz_render_options){.view = view, .interpolation = interpolation};
}

typedef struct quad {
    luz_mesh *mesh;
} quad;

/* A quad through four world points, counter-clockwise seen by the camera
 * (bottom left, bottom right, top right, top left on the screen), with
 * texture coordinates running over [0, u_range] x [0, v_range], v = 0 on
 * top. */
static void make_quad(quad *q, const luz_vec3 corner[4], float u_range, float v_range)
{
    const luz_vec2 uv[4] = {{0.0f, v_range}, {u_range, v_range}, {u_range, 0.0f}, {0.0f, 0.0f}};
    luz_vec3 normal = luz_vec3_normalize(luz_vec3_cross(luz_vec3_sub(corner[1], corner[0]),
                                                        luz_vec3_sub(corner[3], corner[0])));
    luz_vertex vertices[4];
    for (int i = 0; i < 4; i++) vertices[i] = (luz_vertex){corner[i], normal, uv[i]};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    luz_error error = {{0}};
    q->mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices, .vertex_count = 4,
                                               .indices16 = indices, .index_count = 6},
                              &error);
    assert_non_null(q->mesh);
}

/* A face-on quad covering NDC [x0, x1] x [y0, y1] at depth d. */
static void make_screen_quad(quad *q, float x0, float x1, float y0, float y1, float depth,
                             float u_range, float v_range)
{
    const luz_vec3 corner[4] = {
        {x0 * depth, y0 * depth, -depth}, {x1 * depth, y0 * depth, -depth},
        {x1 * depth, y1 * depth, -depth}, {x0 * depth, y1 * depth, -depth},
    };
    make_quad(q, corner, u_range, v_range);
}

/* A white quad, its texture sampled trilinearly (a zero material's filter). */
static void add_quad(luz_frame *frame, const quad *q, const luz_texture *texture)
{
    luz_draw draw = {0};
    draw.mesh = q->mesh;
    draw.model = luz_mat4_identity();
    draw.material.colour = (luz_vec3){1.0f, 1.0f, 1.0f};
    draw.material.texture = texture;
    assert_int_equal(luz_frame_add_draw(frame, &draw, NULL), 0);
}

/* ---- every view, any size, any thread count --------------------------------------------- */

static void test_views_do_not_depend_on_the_thread_count(void **state)
{
    const luz_texture_set *textures = *state;
    const int sizes[][2] = {{17, 9}, {97, 61}, {1, 1}};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        const int width = sizes[s][0], height = sizes[s][1];
        luz_scene scene = luz_scene_defaults();
        scene.time_seconds = 2.5;
        luz_framebuffer *colour = draw_scene(&scene, textures, width, height, 1, false);
        for (int v = 0; v < LUZ_VIEW_COUNT; v++) {
            if (v == LUZ_VIEW_BANDS) continue;   /* depends on the threads: below */
            scene.view = (luz_view)v;
            luz_framebuffer *one = draw_scene(&scene, textures, width, height, 1, false);
            luz_framebuffer *three = draw_scene(&scene, textures, width, height, 3, false);
            size_t bytes = (size_t)width * height * 4;
            if (memcmp(one->colour, three->colour, bytes) != 0)
                fail_msg("view %s at %dx%d differs between 1 and 3 threads",
                         luz_view_name((luz_view)v), width, height);
            /* Each view draws something of its own, except at 1x1 where
             * the pixel may be background. */
            if (v != LUZ_VIEW_COLOR && width > 1 && memcmp(one->colour, colour->colour, bytes) == 0)
                fail_msg("view %s at %dx%d is the colour image", luz_view_name((luz_view)v),
                         width, height);
            luz_framebuffer_destroy(one);
            luz_framebuffer_destroy(three);
        }
        luz_framebuffer_destroy(colour);
    }
}

/* In the bands view every band of 16 rows must be the colour image (drawn
 * by the reference fragment stage, which the views use) under a single
 * thread's tint: with one thread, thread 0's everywhere. */
static int band_worker(const luz_framebuffer *bands, const luz_framebuffer *colour,
                       int first_row, int end_row, int threads)
{
    for (int worker = 0; worker < threads; worker++) {
        luz_vec3 tint = luz_view_thread_colour(worker);
        const float shown[3] = {tint.x, tint.y, tint.z};
        bool all = true;
        for (int y = first_row; y < end_row && all; y++) {
            for (int x = 0; x < bands->width && all; x++) {
                const uint8_t *b = pixel_of(bands, x, y), *c = pixel_of(colour, x, y);
                for (int k = 0; k < 3; k++) {
                    float want = (1.0f - LUZ_VIEW_BANDS_TINT) * (c[k] / 255.0f) +
                                 LUZ_VIEW_BANDS_TINT * shown[k];
                    if (abs(b[k] - luz_colour_to_byte(want)) > 1) all = false;
                }
            }
        }
        if (all) return worker;
    }
    return -1;
}

static void test_bands_view_tints_each_band_by_one_thread(void **state)
{
    const luz_texture_set *textures = *state;
    const int width = 64, height = 70;   /* five bands, the last one short */
    luz_scene scene = luz_scene_defaults();
    luz_framebuffer *colour = draw_scene(&scene, textures, width, height, 1, true);
    scene.view = LUZ_VIEW_BANDS;
    const int thread_counts[] = {1, 3};
    for (int t = 0; t < 2; t++) {
        const int threads = thread_counts[t];
        luz_framebuffer *bands = draw_scene(&scene, textures, width, height, threads, false);
        for (int first = 0; first < height; first += 16) {
            int end = first + 16 < height ? first + 16 : height;
            int worker = band_worker(bands, colour, first, end, threads);
            if (worker < 0)
                fail_msg("%d threads: rows %d to %d are not the image under one thread's tint",
                         threads, first, end - 1);
            if (threads == 1) assert_int_equal(worker, 0);
        }
        luz_framebuffer_destroy(bands);
    }
    luz_framebuffer_destroy(colour);
}

/* ---- every byte of colour, in either channel order ---------------------------------------- */

/* Draws the scene into a new width x height framebuffer in the given
 * channel order, whose colour held `fill` in every byte beforehand; with
 * one thread, so that the bands view is the same every time. */
static luz_framebuffer *draw_scene_over(const luz_scene *scene, const luz_texture_set *textures,
                                        luz_vec3 clear_colour, int width, int height,
                                        uint8_t fill, luz_channel_order order)
{
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), scene, textures ? textures->textures : NULL,
                                           textures ? textures->count : 0,
                                           (float)width / (float)height, &frame, NULL),
                     0);
    frame.clear_colour = clear_colour;
    luz_error error = {{0}};
    luz_renderer *renderer =
        luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, &error);
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    memset(framebuffer->colour, fill, (size_t)width * height * 4);
    luz_framebuffer_use_colour(framebuffer, NULL, order);
    const luz_render_options render = luz_scene_render_options(scene);
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &render, &error), 0);
    luz_renderer_destroy(renderer);
    luz_frame_free(&frame);
    return framebuffer;
}

/* Nothing clears colour before a view draws, so every view must write every
 * byte: drawn over 0xA5 bytes it is the image drawn over zeros. In BGRA it
 * is the RGBA image with bytes 0 and 2 of each pixel swapped (the bands
 * view reads colour back to tint it, so it must read red and blue from
 * where the order put them). The views that do not colour the background
 * by a palette (all but depth and overdraw) give it the clear colour,
 * here (0.25, 0.6, 0.85): round(63.75, 153.0, 216.75) = (64, 153, 217). */
static void test_views_write_every_byte_in_either_order(void **state)
{
    const luz_texture_set *textures = *state;
    enum { WIDTH = 97, HEIGHT = 61 };
    const size_t pixels = (size_t)WIDTH * HEIGHT;
    const luz_vec3 clear_colour = {0.25f, 0.6f, 0.85f};
    const uint8_t clear_bytes[3] = {64, 153, 217};
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 2.5;
    for (int v = 0; v < LUZ_VIEW_COUNT; v++) {
        const char *name = luz_view_name((luz_view)v);
        scene.view = (luz_view)v;
        luz_framebuffer *zeros = draw_scene_over(&scene, textures, clear_colour, WIDTH, HEIGHT,
                                                 0x00, LUZ_CHANNELS_RGBA);
        luz_framebuffer *garbage = draw_scene_over(&scene, textures, clear_colour, WIDTH,
                                                   HEIGHT, 0xA5, LUZ_CHANNELS_RGBA);
        luz_framebuffer *bgra = draw_scene_over(&scene, textures, clear_colour, WIDTH, HEIGHT,
                                                0xA5, LUZ_CHANNELS_BGRA);
        if (memcmp(zeros->colour, garbage->colour, pixels * 4) != 0)
            fail_msg("view %s: the image drawn over 0xA5 bytes differs", name);
        const bool palette_background = v == LUZ_VIEW_DEPTH || v == LUZ_VIEW_OVERDRAW;
        size_t background = 0, red_not_blue = 0;
        for (size_t p = 0; p < pixels; p++) {
            const uint8_t *rgba = zeros->colour + p * 4, *swapped = bgra->colour + p * 4;
            if (swapped[0] != rgba[2] || swapped[1] != rgba[1] || swapped[2] != rgba[0] ||
                swapped[3] != rgba[3])
                fail_msg("view %s: pixel %zu is (%d, %d, %d, %d) in BGRA, (%d, %d, %d, %d) in "
                         "RGBA", name, p, swapped[0], swapped[1], swapped[2], swapped[3],
                         rgba[0], rgba[1], rgba[2], rgba[3]);
            red_not_blue += rgba[0] != rgba[2];
            if (zeros->visibility[p] != 0) continue;
            background++;
            if (palette_background || v == LUZ_VIEW_BANDS) continue;
            if (rgba[0] != clear_bytes[0] || rgba[1] != clear_bytes[1] ||
                rgba[2] != clear_bytes[2] || rgba[3] != 255)
                fail_msg("view %s: background pixel %zu is (%d, %d, %d, %d)", name, p, rgba[0],
                         rgba[1], rgba[2], rgba[3]);
        }
        if (background == 0 || background == pixels)
            fail_msg("view %s: %zu of %zu pixels are background", name, background, pixels);
        /* Otherwise the swap would go unseen; the depth view is grey. */
        if (v != LUZ_VIEW_DEPTH && red_not_blue == 0)
            fail_msg("view %s: no pixel has red != blue", name);
        luz_framebuffer_destroy(zeros);
        luz_framebuffer_destroy(garbage);
        luz_framebuffer_destroy(bgra);
    }
}

/* ---- what each view shows ---------------------------------------------------------------- */

static void test_normals_view_of_a_face_on_face(void **state)
{
    const luz_texture_set *textures = *state;
    /* At t = 0 cube 0 is unrotated at the origin and its +z face looks
     * straight at the camera at (0, 0, 3): N = (0, 0, 1), shown as
     * (0.5, 0.5, 1.0) * 255 rounded, (128, 128, 255). */
    luz_scene scene = luz_scene_defaults();
    scene.view = LUZ_VIEW_NORMALS;
    luz_framebuffer *framebuffer = draw_scene(&scene, textures, 128, 72, 2, false);
    for (int y = 30; y < 42; y++) {
        for (int x = 58; x < 70; x++) {
            const uint8_t *p = pixel_of(framebuffer, x, y);
            if (p[0] != 128 || p[1] != 128 || p[2] != 255)
                fail_msg("normals view at (%d, %d) is (%d, %d, %d), expected (128, 128, 255)",
                         x, y, p[0], p[1], p[2]);
        }
    }
    luz_framebuffer_destroy(framebuffer);
}

static void test_uv_view_at_texel_centres(void **state)
{
    (void)state;
    /* A quad filling a 16 x 16 image with uv over [0, 1]: pixel (x, y)
     * samples u = (x + 0.5) / 16 and v = (y + 0.5) / 16, the centres of
     * the texels of a 16 x 16 texture. */
    enum { SIZE = 16 };
    quad q;
    make_screen_quad(&q, -1.0f, 1.0f, -1.0f, 1.0f, 2.0f, 1.0f, 1.0f);
    luz_frame frame = {0};
    luz_render_options render = quad_frame(&frame, LUZ_VIEW_UV, LUZ_INTERPOLATION_PERSPECTIVE);
    add_quad(&frame, &q, NULL);
    luz_framebuffer *framebuffer = draw_frame(&frame, &render, SIZE, SIZE, 1, false);
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++)
            assert_pixel_near(framebuffer, x, y,
                              ((luz_vec3){(x + 0.5f) / SIZE, (y + 0.5f) / SIZE, 0.0f}), 1);
    luz_framebuffer_destroy(framebuffer);
    luz_frame_free(&frame);
    luz_mesh_destroy(q.mesh);
}

static void test_depth_view(void **state)
{
    (void)state;
    /* A face-on quad at eye distance 2 over the left half; the right half
     * is background, the far plane. Distance 2 on the log scale from 0.1
     * to 100: 1 - log(2 / 0.1) / log(1000) = 0.5663. */
    enum { SIZE = 16 };
    quad q;
    make_screen_quad(&q, -1.0f, 0.0f, -1.0f, 1.0f, 2.0f, 1.0f, 1.0f);
    luz_frame frame = {0};
    luz_render_options render = quad_frame(&frame, LUZ_VIEW_DEPTH, LUZ_INTERPOLATION_PERSPECTIVE);
    add_quad(&frame, &q, NULL);
    luz_framebuffer *framebuffer = draw_frame(&frame, &render, SIZE, SIZE, 1, false);
    const float grey = (float)(1.0 - log(2.0 / 0.1) / log(1000.0));
    for (int y = 0; y < SIZE; y++) {
        for (int x = 0; x < SIZE; x++) {
            float expected = x < SIZE / 2 ? grey : 0.0f;
            assert_pixel_near(framebuffer, x, y, ((luz_vec3){expected, expected, expected}), 1);
        }
    }
    luz_framebuffer_destroy(framebuffer);
    luz_frame_free(&frame);
    luz_mesh_destroy(q.mesh);
}

static void test_overdraw_counts_depth_tests(void **state)
{
    (void)state;
    /* Three face-on quads on a 32 x 32 image, drawn far to near: A over
     * NDC x in [-1, 0.5] at depth 4, B over [-0.5, 1] at depth 3, and C
     * over [-0.25, 0.25] x [-0.25, 0.25] at depth 2. Every covered pixel
     * is one depth test per quad over it, whether the test passes or not. */
    enum { SIZE = 32 };
    quad a, b, c;
    make_screen_quad(&a, -1.0f, 0.5f, -1.0f, 1.0f, 4.0f, 1.0f, 1.0f);
    make_screen_quad(&b, -0.5f, 1.0f, -1.0f, 1.0f, 3.0f, 1.0f, 1.0f);
    make_screen_quad(&c, -0.25f, 0.25f, -0.25f, 0.25f, 2.0f, 1.0f, 1.0f);
    for (int order = 0; order < 2; order++) {
        luz_frame frame = {0};
        luz_render_options render = quad_frame(&frame, LUZ_VIEW_OVERDRAW, LUZ_INTERPOLATION_PERSPECTIVE);
        /* Far to near, then near to far: the counts are the same. */
        const quad *quads[3] = {&a, &b, &c};
        for (int i = 0; i < 3; i++) add_quad(&frame, quads[order ? 2 - i : i], NULL);
        luz_framebuffer *framebuffer = draw_frame(&frame, &render, SIZE, SIZE, 3, false);
        for (int y = 0; y < SIZE; y++) {
            for (int x = 0; x < SIZE; x++) {
                /* Pixel centre in NDC. */
                float nx = (x + 0.5f) / SIZE * 2.0f - 1.0f, ny = 1.0f - (y + 0.5f) / SIZE * 2.0f;
                uint32_t count = (nx < 0.5f) + (nx > -0.5f) +
                                 (fabsf(nx) < 0.25f && fabsf(ny) < 0.25f);
                assert_pixel_near(framebuffer, x, y, luz_view_overdraw_colour(count), 0);
            }
        }
        luz_framebuffer_destroy(framebuffer);
        luz_frame_free(&frame);
    }
    /* The colour view of the same quads is not a heat map. */
    assert_true(luz_view_overdraw_colour(2).z != luz_view_overdraw_colour(3).z);
    luz_mesh_destroy(a.mesh);
    luz_mesh_destroy(b.mesh);
    luz_mesh_destroy(c.mesh);
}

static luz_vec3 edge_shade(uint32_t id)
{
    return luz_vec3_scale(luz_view_triangle_colour(id), LUZ_VIEW_TRIANGLE_EDGE_SHADE);
}

static void test_triangles_view_colours_and_edges(void **state)
{
    (void)state;
    /* A screen-filling quad: triangle 1 is (bottom left, bottom right, top
     * right), the lower right half, triangle 2 the upper left. Their shared
     * edge runs from the bottom left corner to the top right one, through
     * the centres of the pixels with x + y = SIZE - 1. By the top-left
     * rule those go to triangle 1, for which the shared edge is a left
     * edge (it is triangle 2's right edge). */
    enum { SIZE = 24 };
    quad q;
    make_screen_quad(&q, -1.0f, 1.0f, -1.0f, 1.0f, 2.0f, 1.0f, 1.0f);
    luz_frame frame = {0};
    luz_render_options render = quad_frame(&frame, LUZ_VIEW_TRIANGLES, LUZ_INTERPOLATION_PERSPECTIVE);
    add_quad(&frame, &q, NULL);
    luz_framebuffer *framebuffer = draw_frame(&frame, &render, SIZE, SIZE, 2, false);
    /* Every pixel shows its owner: triangle 1 on and below the diagonal,
     * 2 above it; darker on either side of the shared edge (each pixel
     * whose neighbour across it is the other triangle's), flat elsewhere,
     * the image's border included (no neighbour there). So the edge is
     * two pixels wide, one of each triangle, and no pixel is in both. */
    for (int y = 0; y < SIZE; y++) {
        for (int x = 0; x < SIZE; x++) {
            const int sum = x + y;
            luz_vec3 expected = sum == SIZE - 1   ? edge_shade(1)
                                : sum == SIZE - 2 ? edge_shade(2)
                                : sum >= SIZE - 1 ? luz_view_triangle_colour(1)
                                                  : luz_view_triangle_colour(2);
            assert_pixel_near(framebuffer, x, y, expected, 0);
        }
    }
    luz_vec3 one = luz_view_triangle_colour(1), two = luz_view_triangle_colour(2);
    assert_true(fabsf(one.x - two.x) + fabsf(one.y - two.y) + fabsf(one.z - two.z) > 0.3f);
    /* and the darker shades of the two are apart as well */
    luz_vec3 dark_one = edge_shade(1), dark_two = edge_shade(2);
    assert_true(fabsf(dark_one.x - dark_two.x) + fabsf(dark_one.y - dark_two.y) +
                    fabsf(dark_one.z - dark_two.z) > 0.12f);
    luz_framebuffer_destroy(framebuffer);

    /* The step mode's limit: only triangle 1 is drawn, the upper left half
     * stays background, and triangle 1's diagonal is now an edge against
     * the background. */
    render.triangle_limit = 1;
    framebuffer = draw_frame(&frame, &render, SIZE, SIZE, 2, false);
    assert_pixel_near(framebuffer, SIZE - 4, SIZE - 4, luz_view_triangle_colour(1), 0);
    assert_pixel_near(framebuffer, 5, SIZE - 6, edge_shade(1), 0);
    assert_pixel_near(framebuffer, 3, 3, frame.clear_colour, 0);
    luz_framebuffer_destroy(framebuffer);
    luz_frame_free(&frame);

    /* A quad in front of another: the front one, NDC [-0.5, 0.5] at depth
     * 1 (pixels 6 to 17 of 24), drawn second (triangles 3 and 4). Its
     * outline is on its own side; the pixel just outside it belongs to the
     * back quad, which covers it, and stays flat. */
    quad front;
    make_screen_quad(&front, -0.5f, 0.5f, -0.5f, 0.5f, 1.0f, 1.0f, 1.0f);
    render = quad_frame(&frame, LUZ_VIEW_TRIANGLES, LUZ_INTERPOLATION_PERSPECTIVE);
    add_quad(&frame, &q, NULL);
    add_quad(&frame, &front, NULL);
    framebuffer = draw_frame(&frame, &render, SIZE, SIZE, 1, false);
    /* Its diagonal runs through the centres with x + y = 23 (from window
     * (6, 18) to (18, 6)): triangle 3 on and below it, 4 above, as for the
     * back quad. Pixel (6, 12) is in its left column (x + y = 18): an edge
     * pixel of 4; (17, 12), in the right column, one of 3. */
    assert_pixel_near(framebuffer, 6, 12, edge_shade(4), 0);
    assert_pixel_near(framebuffer, 17, 12, edge_shade(3), 0);   /* right column: 3 */
    assert_pixel_near(framebuffer, 9, 9, luz_view_triangle_colour(4), 0);
    assert_pixel_near(framebuffer, 14, 14, luz_view_triangle_colour(3), 0);
    /* Left of it, the back quad's triangle 2 (x + y = 17, far from its
     * own diagonal), flat: its neighbour (6, 12) is inside triangle 2
     * too, though the front quad won it. */
    assert_pixel_near(framebuffer, 5, 12, luz_view_triangle_colour(2), 0);
    luz_framebuffer_destroy(framebuffer);
    luz_frame_free(&frame);
    luz_mesh_destroy(front.mesh);
    luz_mesh_destroy(q.mesh);
}

static void test_mip_view_shows_the_sampled_levels(void **state)
{
    (void)state;
    /* A 64 x 64 texture over a screen-filling quad on a 32 x 32 image, with
     * uv over [0, 1.5]: one pixel step covers 1.5 * 64 / 32 = 3 texels, so
     * lambda = log2 3 = 1.585, and trilinear filtering mixes levels 1 and 2
     * by 0.585. Bilinear filtering reads level 0 only; a draw without a
     * texture has no level. */
    enum { SIZE = 32, TEXELS = 64 };
    uint8_t *rgba = calloc(TEXELS * TEXELS, 4);
    assert_non_null(rgba);
    luz_error error = {{0}};
    luz_texture *texture = luz_texture_create(TEXELS, TEXELS, rgba, &error);
    assert_non_null(texture);
    quad q;
    make_screen_quad(&q, -1.0f, 1.0f, -1.0f, 1.0f, 2.0f, 1.5f, 1.5f);

    const float blend = (float)(log2(3.0) - 1.0);
    luz_vec3 one = luz_view_mip_colour(1), two = luz_view_mip_colour(2);
    const luz_vec3 expected[3] = {
        luz_vec3_add(luz_vec3_scale(one, 1.0f - blend), luz_vec3_scale(two, blend)),
        luz_view_mip_colour(0),
        LUZ_VIEW_MIP_UNTEXTURED,
    };
    const luz_filter filters[3] = {LUZ_FILTER_TRILINEAR, LUZ_FILTER_BILINEAR,
                                   LUZ_FILTER_TRILINEAR};
    for (int k = 0; k < 3; k++) {
        luz_frame frame = {0};
        luz_render_options render = quad_frame(&frame, LUZ_VIEW_MIP, LUZ_INTERPOLATION_PERSPECTIVE);
        add_quad(&frame, &q, k == 2 ? NULL : texture);
        frame.draws[0].material.filter = filters[k];
        luz_framebuffer *framebuffer = draw_frame(&frame, &render, SIZE, SIZE, 1, false);
        for (int y = 0; y < SIZE; y += 5)
            for (int x = 0; x < SIZE; x += 3) assert_pixel_near(framebuffer, x, y, expected[k], 1);
        luz_framebuffer_destroy(framebuffer);
        luz_frame_free(&frame);
    }
    luz_texture_destroy(texture);
    free(rgba);
    luz_mesh_destroy(q.mesh);
}

/* ---- affine interpolation ------------------------------------------------------------------ */

/* Renders one quad in the uv view with each interpolation; returns how
 * many pixels differ by more than `levels` in any channel. */
static int affine_differences(const quad *q, int levels, int *covered)
{
    enum { SIZE = 48 };
    luz_framebuffer *images[2];
    for (int k = 0; k < 2; k++) {
        luz_frame frame = {0};
        luz_render_options render = quad_frame(&frame, LUZ_VIEW_UV, k ? LUZ_INTERPOLATION_AFFINE : LUZ_INTERPOLATION_PERSPECTIVE);
        add_quad(&frame, q, NULL);
        images[k] = draw_frame(&frame, &render, SIZE, SIZE, 2, false);
        luz_frame_free(&frame);
    }
    int different = 0;
    *covered = 0;
    for (int i = 0; i < SIZE * SIZE; i++) {
        *covered += images[0]->visibility[i] != 0;
        for (int c = 0; c < 3; c++) {
            if (abs(images[0]->colour[i * 4 + c] - images[1]->colour[i * 4 + c]) > levels) {
                different++;
                break;
            }
        }
    }
    luz_framebuffer_destroy(images[0]);
    luz_framebuffer_destroy(images[1]);
    return different;
}

static void test_affine_differs_only_on_slanted_faces(void **state)
{
    (void)state;
    int covered;
    /* Face-on, w is the same at every vertex, and u/w over 1/w is u
     * interpolated linearly: the two agree to rounding. */
    quad face_on;
    make_screen_quad(&face_on, -0.8f, 0.7f, -0.6f, 0.9f, 3.0f, 1.0f, 1.0f);
    assert_int_equal(affine_differences(&face_on, 1, &covered), 0);
    assert_true(covered > 400);

    /* Slanted: the left edge at depth 1.5, the right one at depth 6. In
     * perspective the near half of the quad takes most of the screen, so
     * at the screen's middle u is far below the affine 0.5. */
    const luz_vec3 corner[4] = {
        {-1.2f, -1.2f, -1.5f}, {4.8f, -4.8f, -6.0f}, {4.8f, 4.8f, -6.0f}, {-1.2f, 1.2f, -1.5f},
    };
    quad slanted;
    make_quad(&slanted, corner, 1.0f, 1.0f);
    int different = affine_differences(&slanted, 8, &covered);
    print_message("slanted quad: %d of %d pixels differ by more than 8 levels\n", different,
                  covered);
    assert_true(different > covered / 2);
    luz_mesh_destroy(face_on.mesh);
    luz_mesh_destroy(slanted.mesh);
}

static void test_affine_packet_and_reference_agree(void **state)
{
    const luz_texture_set *textures = *state;
    /* The colour view with --interp affine may take the SIMD fragment
     * stage: it reads the affine planes exactly as the reference does. */
    luz_scene scene = luz_scene_defaults();
    scene.interpolation = LUZ_INTERPOLATION_AFFINE;
    scene.time_seconds = 3.0;
    luz_framebuffer *packet = draw_scene(&scene, textures, 160, 90, 1, false);
    luz_framebuffer *reference = draw_scene(&scene, textures, 160, 90, 1, true);
    scene.interpolation = LUZ_INTERPOLATION_PERSPECTIVE;
    luz_framebuffer *perspective = draw_scene(&scene, textures, 160, 90, 1, false);
    int off = 0, changed = 0;
    for (int i = 0; i < 160 * 90 * 4; i++) {
        off += abs(packet->colour[i] - reference->colour[i]) > 1;
        changed += packet->colour[i] != perspective->colour[i];
    }
    assert_int_equal(off, 0);
    assert_true(changed > 100);
    luz_framebuffer_destroy(packet);
    luz_framebuffer_destroy(reference);
    luz_framebuffer_destroy(perspective);
}

static void test_view_names(void **state)
{
    (void)state;
    for (int v = 0; v < LUZ_VIEW_COUNT; v++) {
        luz_view parsed;
        assert_true(luz_view_from_name(luz_view_name((luz_view)v), &parsed));
        assert_int_equal(parsed, v);
        assert_true(strlen(luz_view_legend((luz_view)v)) > 0);
    }
    luz_view parsed;
    assert_false(luz_view_from_name("colour", &parsed));
    assert_string_equal(luz_interpolation_name(LUZ_INTERPOLATION_AFFINE), "affine");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_view_names),
        cmocka_unit_test(test_views_do_not_depend_on_the_thread_count),
        cmocka_unit_test(test_bands_view_tints_each_band_by_one_thread),
        cmocka_unit_test(test_views_write_every_byte_in_either_order),
        cmocka_unit_test(test_normals_view_of_a_face_on_face),
        cmocka_unit_test(test_uv_view_at_texel_centres),
        cmocka_unit_test(test_depth_view),
        cmocka_unit_test(test_overdraw_counts_depth_tests),
        cmocka_unit_test(test_triangles_view_colours_and_edges),
        cmocka_unit_test(test_mip_view_shows_the_sampled_levels),
        cmocka_unit_test(test_affine_differs_only_on_slanted_faces),
        cmocka_unit_test(test_affine_packet_and_reference_agree),
    };
    return cmocka_run_group_tests(tests, load_textures, free_textures);
}
