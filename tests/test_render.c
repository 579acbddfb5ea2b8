/*
 * test_render.c: the whole pipeline (luz_renderer_draw) on SCENE.md's
 * default scene, checked against properties that follow from SCENE.md
 * without running a renderer: where the camera of SCENE.md projects a
 * point, what colour a pixel lit by known lights must have, that the
 * image does not depend on the number of threads, and that the caller's
 * per-band hook runs once per row, after the row is shaded.
 *
 * Projection by hand: the camera at E looks down -z with a vertical field
 * of view of 45 degrees, so a point at eye-relative (x, y, z), z < 0, has
 *   x_ndc = (x / -z) / (tan 22.5 * W / H),  y_ndc = (y / -z) / tan 22.5,
 * and window coordinates x = (x_ndc + 1) / 2 W, y = (1 - y_ndc) / 2 H.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdatomic.h>
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
#include "app/panel.h"

#define WIDTH 1280
#define HEIGHT 720
#define BACKGROUND 26   /* round(0.1 * 255) = round(25.5) = 26 */

/* The pixel that contains the projection of a world point for a camera at
 * `eye` looking down -z (the start camera of SCENE.md is at (0, 0, 3)). */
static void project(luz_vec3 eye, luz_vec3 point, int *x, int *y)
{
    const double tan_half_fov = tan(22.5 * LUZ_PI / 180.0);
    double depth = eye.z - point.z;
    double x_ndc = (point.x - eye.x) / depth / (tan_half_fov * WIDTH / HEIGHT);
    double y_ndc = (point.y - eye.y) / depth / tan_half_fov;
    *x = (int)floor((x_ndc + 1) / 2 * WIDTH);
    *y = (int)floor((1 - y_ndc) / 2 * HEIGHT);
}

/* True if byte is round(clamp(value, 0, 1) * 255), accepting either
 * neighbour when value * 255 is within 0.001 of a half (where float and
 * double evaluation may round differently). */
static bool byte_is_rounding_of(uint8_t byte, double value)
{
    double scaled = (value < 0 ? 0 : value > 1 ? 1 : value) * 255.0;
    double low = floor(scaled + 0.5 - 1e-3), high = floor(scaled + 0.5 + 1e-3);
    return byte >= low && byte <= high;
}

static const uint8_t *pixel(const luz_framebuffer *framebuffer, int x, int y)
{
    return framebuffer->colour + ((size_t)y * framebuffer->width + x) * 4;
}

static bool pixel_is_rounding_of(const uint8_t *rgba, luz_vec3 colour, double light)
{
    return byte_is_rounding_of(rgba[0], light * colour.x) &&
           byte_is_rounding_of(rgba[1], light * colour.y) &&
           byte_is_rounding_of(rgba[2], light * colour.z) && rgba[3] == 255;
}

#define assert_pixel(framebuffer, pixel_x, pixel_y, colour, light) \
    assert_pixel_at((framebuffer), (pixel_x), (pixel_y), (colour), (light), __FILE__, __LINE__)

static void assert_pixel_at(const luz_framebuffer *framebuffer, int x, int y, luz_vec3 colour,
                            double light, const char *file, int line)
{
    const uint8_t *rgba = pixel(framebuffer, x, y);
    if (pixel_is_rounding_of(rgba, colour, light)) return;
    print_error("pixel (%d, %d) is (%d, %d, %d), expected %g * (%g, %g, %g) * 255\n", x, y,
                rgba[0], rgba[1], rgba[2], light, colour.x, colour.y, colour.z);
    _fail(file, line);
}

/* Draws a scene at WIDTH x HEIGHT with the given number of threads,
 * shading with the SIMD fragment stage (the default) or, for `reference`,
 * the one-pixel-at-a-time one: every expectation below holds for both. */
static luz_framebuffer *render_with_stats(const luz_scene *scene,
                                          const luz_texture_set *textures, int thread_count,
                                          bool reference, luz_frame_stats *stats)
{
    luz_error error;
    luz_renderer_desc desc = {.thread_count = thread_count, .reference = reference};
    luz_renderer *renderer = luz_renderer_create(&desc, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    luz_frame frame = {0};
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    assert_int_equal(luz_scene_build_frame(test_lab(), scene,
                                           textures ? textures->textures : NULL,
                                           textures ? textures->count : 0, (float)WIDTH / HEIGHT,
                                           &frame, NULL),
                     0);
    luz_render_options render = luz_scene_render_options(scene);
    render.stats = stats;
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &render, &error), 0);
    luz_frame_free(&frame);
    luz_renderer_destroy(renderer);
    return framebuffer;
}

static luz_framebuffer *render(const luz_scene *scene, const luz_texture_set *textures,
                               int thread_count, bool reference)
{
    return render_with_stats(scene, textures, thread_count, reference, NULL);
}

/* Each test runs twice, once per fragment stage; its state says which. */
static const bool simd_stage = false, reference_stage = true;

static int use_simd_stage(void **state)
{
    *state = (void *)&simd_stage;
    return 0;
}

static int use_reference_stage(void **state)
{
    *state = (void *)&reference_stage;
    return 0;
}

static bool uses_reference_stage(void **state)
{
    return *(const bool *)*state;
}

#define ON_BOTH_STAGES(function) \
    {#function " (SIMD)", function, use_simd_stage, NULL, NULL}, \
    {#function " (reference)", function, use_reference_stage, NULL, NULL}

/* A scene with only ambient light (and the spot at `spot`), no marker. */
static luz_scene ambient_scene(float spot)
{
    luz_scene scene = luz_scene_defaults();
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        if (term != LUZ_TERM_AMBIENT)
            luz_lights_term(&scene.lights, (luz_term)term)->strength = 0.0f;
    scene.lights.spot.strength = spot;
    return scene;
}

/* At t = 0 the cubes are unrotated. The image corners see only the
 * background: e.g. the ray through the centre of pixel (0, 0) has
 * direction (-0.7358, 0.4136, -1), and where it passes the depths of the
 * cubes near that corner (cube 9 at z = -1.5: (-3.31, 1.86), cube 7:
 * (-4.05, 2.28), cube 5: (-7.72, 4.34)) it is more than 2 units from them
 * (a cube reaches at most sqrt(3)/2 from its centre); the other three
 * corners likewise (checked with a ray / box test). The marker at
 * (3, 0.5, 0) projects off screen (x_ndc = (3/3) / 0.7364 > 1). So the
 * corners hold the clear colour 0.1, byte 26, and no triangle id. The
 * origin projects to (640, 360), the middle of cube 0's front face
 * (which spans 0.5 / 2.5 / tan 22.5 * 360 = 174 pixels either way). */
static void test_background_and_cube_zero(void **state)
{
    luz_scene scene = luz_scene_defaults();
    luz_framebuffer *framebuffer = render(&scene, NULL, 1, uses_reference_stage(state));
    const int corners[4][2] = {{0, 0}, {WIDTH - 1, 0}, {0, HEIGHT - 1}, {WIDTH - 1, HEIGHT - 1}};
    for (int k = 0; k < 4; k++) {
        const uint8_t *rgba = pixel(framebuffer, corners[k][0], corners[k][1]);
        assert_int_equal(rgba[0], BACKGROUND);
        assert_int_equal(rgba[1], BACKGROUND);
        assert_int_equal(rgba[2], BACKGROUND);
        assert_int_equal(rgba[3], 255);
        assert_int_equal(framebuffer->visibility[corners[k][1] * WIDTH + corners[k][0]], 0);
    }
    int x, y;
    project(scene.camera.position, (luz_vec3){0, 0, 0}, &x, &y);
    assert_int_equal(x, 640);
    assert_int_equal(y, 360);
    assert_int_not_equal(framebuffer->visibility[y * WIDTH + x], 0);
    const uint8_t *centre = pixel(framebuffer, x, y);
    assert_false(centre[0] == BACKGROUND && centre[1] == BACKGROUND && centre[2] == BACKGROUND);
    luz_framebuffer_destroy(framebuffer);
}

/* Ambient light alone, no textures (T = 1): every pixel of cube i is
 * round(0.2 * C_i * 255), C_i from the seed's colours, and every other
 * pixel is the background. At the projections of the centres of cubes
 * 0, 1, 2, 6, 7, 8 and 9 (t = 0, camera at (0, 0, 3)) that cube is in
 * front: the ray through the centre pixel meets no other cube, even one
 * grown by a fifth (checked by a ray / box test for the unrotated
 * cubes); cubes 3, 4 and 5 are partly behind others and not checked
 * there. */
static void test_ambient_only_gives_a_fifth_of_each_colour(void **state)
{
    luz_scene scene = ambient_scene(0.0f);
    luz_vec3 colours[10];
    luz_scene_random_colours(scene.seed, 10, colours);
    luz_framebuffer *framebuffer = render(&scene, NULL, 2, uses_reference_stage(state));

    for (int y = 0; y < HEIGHT; y++) {
        for (int x = 0; x < WIDTH; x++) {
            const uint8_t *rgba = pixel(framebuffer, x, y);
            if (framebuffer->visibility[y * WIDTH + x] == 0) {
                if (rgba[0] != BACKGROUND || rgba[1] != BACKGROUND || rgba[2] != BACKGROUND)
                    fail_msg("background pixel (%d, %d) is (%d, %d, %d)", x, y, rgba[0],
                             rgba[1], rgba[2]);
                continue;
            }
            bool matches = false;
            for (int i = 0; i < 10 && !matches; i++)
                matches = pixel_is_rounding_of(rgba, colours[i], 0.2);
            if (!matches)
                fail_msg("pixel (%d, %d) is (%d, %d, %d), no cube's 0.2 * C", x, y, rgba[0],
                         rgba[1], rgba[2]);
        }
    }
    const int unoccluded[7] = {0, 1, 2, 6, 7, 8, 9};
    for (int k = 0; k < 7; k++) {
        int i = unoccluded[k], x, y;
        project(scene.camera.position, luz_scene_tiled_position(i), &x, &y);
        assert_pixel(framebuffer, x, y, colours[i], 0.2);
    }
    luz_framebuffer_destroy(framebuffer);
}

/* The spot, ambient and nothing else, no textures; the camera moved back
 * to (0, 0, 5.5), so cube 0's front face (z = 0.5) is 5 units ahead, and
 * the spot narrowed to an inner cone of 2 and an outer cone of 4 degrees,
 * at strength 0.8.
 *   At the face's centre, pixel (640, 360), the fragment is on the spot's
 *   axis (0.03 degrees off it: f_dir = 1) at distance 5: dn = 0.5,
 *   f_win = (1 - 0.0625)^2 = 0.87890625, f_dist = 0.87890625 * 0.8^2 /
 *   1.25 = 0.45. Colour (0.2 + 0.45) C = 0.65 C.
 *   Pixel (718, 360) has x_ndc = 2 * 718.5 / 1280 - 1 = 0.12265625, so its
 *   ray meets the face at x = 0.12265625 * tan 22.5 * 16/9 * 5 = 0.4516
 *   (inside the face, half-side 0.5), atan(0.4516 / 5) = 5.2 degrees off
 *   the axis: beyond the outer cone, the spot adds exactly 0 and the
 *   colour is 0.2 C.
 * So the lit centre is brighter, by exactly the spot's share. */
static void test_spot_lights_the_centre_not_the_edge(void **state)
{
    luz_scene scene = ambient_scene(0.8f);
    scene.camera.position = (luz_vec3){0, 0, 5.5f};
    scene.lights.spot_inner_degrees = 2.0f;
    scene.lights.spot_outer_degrees = 4.0f;
    luz_vec3 colours[1];
    luz_scene_random_colours(scene.seed, 1, colours);
    luz_framebuffer *framebuffer = render(&scene, NULL, 1, uses_reference_stage(state));
    assert_pixel(framebuffer, 640, 360, colours[0], 0.65);
    assert_pixel(framebuffer, 718, 360, colours[0], 0.2);
    const uint8_t *centre = pixel(framebuffer, 640, 360), *edge = pixel(framebuffer, 718, 360);
    assert_true(centre[0] + centre[1] + centre[2] > edge[0] + edge[1] + edge[2]);
    luz_framebuffer_destroy(framebuffer);
}

/* Clipping, end to end: ambient light only, no textures, the camera at
 * (0.8, 0, 0.55) looking down -z, just outside cube 0's +X face (x = 0.5)
 * and only 0.05 in front of the plane of its +Z face, which the near plane
 * (0.1) therefore cuts away whole. The +X face crosses the near plane
 * (its points with z > 0.45 are nearer than 0.1) and, where it comes
 * close, leaves the guard band: its point (0.5, 0, 0.44) is eye-relative
 * (-0.3, 0, -0.11), x_ndc = (0.3 / 0.11) / 0.7364 = -3.7, and nearer
 * points beyond -4. So both of its triangles are clipped. On screen the
 * face covers everything left of its far edge z = -0.5, eye-relative
 * (-0.3, 0, -1.05): x_ndc = -(0.3 / 1.05) / 0.7364 = -0.388, window x =
 * 391.7; and every row, since at depth 1.05 the face's half-height 0.5
 * is at y_ndc = (0.5 / 1.05) / 0.4142 = 1.15 > 1. Nothing is nearer. So
 * every pixel with x <= 390 is 0.2 C_0: no holes along the clipped edges
 * or the diagonal shared by the two clipped triangles. */
static void test_clipped_face_covers_its_region(void **state)
{
    luz_scene scene = ambient_scene(0.0f);
    scene.camera.position = (luz_vec3){0.8f, 0, 0.55f};
    luz_vec3 colours[1];
    luz_scene_random_colours(scene.seed, 1, colours);
    luz_frame_stats stats;
    luz_framebuffer *framebuffer = render_with_stats(&scene, NULL, 2, uses_reference_stage(state),
                                                     &stats);
    assert_true(stats.triangles_clipped >= 2);
    for (int y = 0; y < HEIGHT; y++)
        for (int x = 0; x <= 390; x++) assert_pixel(framebuffer, x, y, colours[0], 0.2);
    luz_framebuffer_destroy(framebuffer);
}

/* The point-light marker at t = 8: (3 cos 4, 0.5, 3 sin 4) =
 * (-1.96093, 0.5, -2.27041), eye-relative (-1.96093, 0.5, -5.27041):
 * x_ndc = 0.37207 / 0.73640 = -0.50525, y_ndc = 0.09487 / 0.41421 =
 * 0.22904, window (316.6, 277.5): pixel (316, 277). Nothing hides it: the
 * nearest cube to that ray, cube 9 (rotated by 10/3 * 8 * 50 = 1333.3
 * degrees), misses it (a ray / oriented-box test shows it would take a
 * cube 10 % larger to reach the ray), and the marker's face there is 0.1
 * from its centre, 16 pixels wide. The marker is unlit in the point
 * light's colour, not scaled by its strength: white gives (255, 255,
 * 255); colour (1, 0.25, 0) at strength 0.3 gives (255, 64, 0)
 * (0.25 * 255 = 63.75). */
static void test_point_light_marker(void **state)
{
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 8.0;
    int x, y;
    project(scene.camera.position, (luz_vec3){(float)(3 * cos(4.0)), 0.5f, (float)(3 * sin(4.0))},
            &x, &y);
    assert_int_equal(x, 316);
    assert_int_equal(y, 277);
    luz_framebuffer *framebuffer = render(&scene, NULL, 2, uses_reference_stage(state));
    const uint8_t *rgba = pixel(framebuffer, x, y);
    assert_int_equal(rgba[0], 255);
    assert_int_equal(rgba[1], 255);
    assert_int_equal(rgba[2], 255);
    luz_framebuffer_destroy(framebuffer);

    scene.lights.point.colour = (luz_vec3){1.0f, 0.25f, 0.0f};
    scene.lights.point.strength = 0.3f;
    framebuffer = render(&scene, NULL, 2, uses_reference_stage(state));
    rgba = pixel(framebuffer, x, y);
    assert_int_equal(rgba[0], 255);
    assert_int_equal(rgba[1], 64);
    assert_int_equal(rgba[2], 0);
    luz_framebuffer_destroy(framebuffer);
}

/* Renders scene with 1, 2, 3 and 7 threads and asserts identical colour,
 * depth and visibility buffers. */
static void assert_same_for_any_thread_count(const luz_scene *scene,
                                             const luz_texture_set *textures, bool reference)
{
    luz_framebuffer *one_thread = render(scene, textures, 1, reference);
    const int thread_counts[3] = {2, 3, 7};
    for (int k = 0; k < 3; k++) {
        luz_framebuffer *framebuffer = render(scene, textures, thread_counts[k], reference);
        assert_memory_equal(one_thread->colour, framebuffer->colour, (size_t)WIDTH * HEIGHT * 4);
        assert_memory_equal(one_thread->depth, framebuffer->depth,
                            (size_t)WIDTH * HEIGHT * sizeof *framebuffer->depth);
        assert_memory_equal(one_thread->visibility, framebuffer->visibility,
                            (size_t)WIDTH * HEIGHT * sizeof *framebuffer->visibility);
        luz_framebuffer_destroy(framebuffer);
    }
    luz_framebuffer_destroy(one_thread);
}

/* Bands own disjoint rows and draw triangles in submission order, so the
 * default scene (with the textures of $LUZ_TEXTURES, if any, and all six
 * lights; at t = 2.5, so the cubes are turned and trilinear filtering
 * blends levels) at 1280x720 is identical byte for byte with 1, 2, 3 and
 * 7 threads: colour, depth and visibility. The 100-cube scene too: its 101
 * draws are split into 4 geometry chunks on one thread and 7 on more, so
 * the triangle numbering across chunks is checked as well. */
static void test_image_is_identical_for_any_thread_count(void **state)
{
    luz_texture_set textures = {0};
    const char *directory = getenv("LUZ_TEXTURES");
    bool have_textures = directory && *directory;
    if (have_textures) {
        luz_error error;
        if (luz_texture_set_load(&textures, directory, NULL, &error) != 0)
            fail_msg("%s", error.message);
    }
    const luz_texture_set *set = have_textures ? &textures : NULL;
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 2.5;
    assert_same_for_any_thread_count(&scene, set, uses_reference_stage(state));
    scene.cube_count = 100;
    assert_same_for_any_thread_count(&scene, set, uses_reference_stage(state));
    if (have_textures) luz_texture_set_free(&textures);
}

/* What a band hook saw, row by row; calls for different bands run on
 * different threads at once. */
typedef struct hook_record {
    const luz_framebuffer *shaded;   /* the same frame drawn without a hook */
    const luz_layer *layer;
    atomic_int calls[HEIGHT];        /* hook calls that covered each row */
    atomic_int rows_not_shaded;      /* rows that differed from `shaded` */
    atomic_int bad_bands;            /* empty or outside the framebuffer */
} hook_record;

static void record_band(void *context, luz_framebuffer *framebuffer, int first_row, int end_row)
{
    hook_record *record = context;
    if (first_row < 0 || end_row > HEIGHT || first_row >= end_row) {
        atomic_fetch_add(&record->bad_bands, 1);
        return;
    }
    const size_t row_bytes = (size_t)WIDTH * 4;
    for (int y = first_row; y < end_row; y++) {
        atomic_fetch_add(&record->calls[y], 1);
        if (memcmp(framebuffer->colour + y * row_bytes, record->shaded->colour + y * row_bytes,
                   row_bytes) != 0)
            atomic_fetch_add(&record->rows_not_shaded, 1);
    }
    luz_layer_draw_rows(record->layer, framebuffer, first_row, end_row);
}

/* luz_renderer_draw with a band hook, with 1, 2 and 3 threads: the hook covers
 * every row exactly once, sees each of its rows already shaded (the same
 * bytes as the frame drawn without a hook), and a 2D layer filled from it
 * band by band gives the frame drawn first and the layer filled after. */
static void test_band_hook_runs_once_per_row_after_shading(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 1.0;
    luz_layer layer = {0};
    luz_layer_begin(&layer, WIDTH, HEIGHT);
    luz_overlay_fill(&layer, (luz_rect){10, 10, 400, 300}, (luz_rgba){12, 12, 16, 190});
    luz_overlay_text(&layer, 20, 20, 2, "60.0 fps", (luz_rgba){255, 210, 120, 255});
    luz_overlay_fill(&layer, (luz_rect){900, 5, 380, 715}, (luz_rgba){0, 80, 0, 128});
    assert_int_equal(luz_layer_finish(&layer), 0);

    hook_record *record = calloc(1, sizeof *record);
    assert_non_null(record);
    record->layer = &layer;
    luz_frame frame = {0};
    assert_int_equal(
        luz_scene_build_frame(test_lab(), &scene, NULL, 0, (float)WIDTH / HEIGHT, &frame, NULL), 0);
    const int thread_counts[3] = {1, 2, 3};
    for (int t = 0; t < 3; t++) {
        luz_framebuffer *expected = render(&scene, NULL, thread_counts[t], false);
        record->shaded = expected;
        for (int y = 0; y < HEIGHT; y++) atomic_store(&record->calls[y], 0);
        atomic_store(&record->rows_not_shaded, 0);
        atomic_store(&record->bad_bands, 0);

        luz_error error;
        luz_renderer *renderer =
            luz_renderer_create(&(luz_renderer_desc){.thread_count = thread_counts[t]}, &error);
        luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
        assert_non_null(renderer);
        assert_non_null(framebuffer);
        const luz_band_hook hook = {record_band, record};
        const luz_render_options render = {.hook = &hook};
        assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &render, &error), 0);

        for (int y = 0; y < HEIGHT; y++)
            if (atomic_load(&record->calls[y]) != 1)
                fail_msg("%d threads: row %d covered by %d hook calls", thread_counts[t], y,
                         atomic_load(&record->calls[y]));
        assert_int_equal(atomic_load(&record->bad_bands), 0);
        assert_int_equal(atomic_load(&record->rows_not_shaded), 0);
        uint8_t unlayered[4];
        memcpy(unlayered, pixel(expected, 1000, 400), 4);
        luz_layer_draw(&layer, expected);
        assert_memory_equal(framebuffer->colour, expected->colour, (size_t)WIDTH * HEIGHT * 4);
        /* And the layer did change the frame. */
        assert_memory_not_equal(pixel(framebuffer, 1000, 400), unlayered, 4);

        luz_framebuffer_destroy(framebuffer);
        luz_renderer_destroy(renderer);
        luz_framebuffer_destroy(expected);
    }
    luz_frame_free(&frame);
    luz_layer_free(&layer);
    free(record);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        ON_BOTH_STAGES(test_background_and_cube_zero),
        ON_BOTH_STAGES(test_ambient_only_gives_a_fifth_of_each_colour),
        ON_BOTH_STAGES(test_spot_lights_the_centre_not_the_edge),
        ON_BOTH_STAGES(test_clipped_face_covers_its_region),
        ON_BOTH_STAGES(test_point_light_marker),
        ON_BOTH_STAGES(test_image_is_identical_for_any_thread_count),
        cmocka_unit_test(test_band_hook_runs_once_per_row_after_shading),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
