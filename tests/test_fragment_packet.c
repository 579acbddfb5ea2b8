/*
 * test_fragment_packet.c: the SIMD fragment stage (fragment_packet.c)
 * against the reference (fragment.c).
 *
 * Both shade every visible pixel once from the same visibility buffer, so
 * any difference between their images is a difference in shading. The
 * packets compute the reference's operations in the reference's order, and
 * differ only in the logarithm of the texture's level of detail; the
 * contract checked here is looser than that, the one the fast path
 * promises: every channel within 1 of the reference, and at least 99.9%
 * of the pixels identical. Each case runs every compiled variant the CPU
 * supports (baseline, AVX2, AVX-512) and prints the agreement it measured.
 *
 * Covered: SCENE.md's default scene at t = 0, 3 and 8 with each filter;
 * each light term alone; a camera close enough to a cube that its texture
 * is magnified everywhere; a far camera and many tiny cubes (heavy
 * minification, deep mip levels); lights at the edges of their ranges
 * (a fractional shininess, which takes powf; equal spot cones). Then two
 * exact properties: the fast path's image is the same byte for byte for
 * any thread count, any variant (and a width that is not a whole number
 * of packets), and with no textures and only ambient light both paths
 * give each cube exactly round(0.2 C 255). Last, what both paths promise
 * about the colour buffer itself: every byte is written (colour is never
 * cleared, so what it held before must not show), the background gets the
 * clear colour, and a BGRA framebuffer gets the RGBA image with red and
 * blue swapped. And the output (exposure, tone map): both paths give the
 * same bytes under every setting, and neither touches the point-light
 * marker or the background.
 */
#include <fenv.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
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
#include "renderer/cpu.h"
#include "renderer/pipeline.h"

#define WIDTH 1280          /* the default scene's size */
#define HEIGHT 720
#define HALF_WIDTH 640      /* for the many variations, to keep the suite */
#define HALF_HEIGHT 360     /* quick under the sanitizers */

/* The fast path's compiled variants: one per instruction set (cpu.h). */
static const luz_isa variants[] = {LUZ_ISA_SCALAR, LUZ_ISA_BASELINE, LUZ_ISA_AVX2,
                                   LUZ_ISA_AVX512};
#define VARIANT_COUNT (sizeof variants / sizeof variants[0])

/* The reference, or the fast path in one variant. */
typedef struct stage {
    bool reference;
    luz_isa isa;   /* the fast path's (the reference's geometry: the widest) */
} stage;

static const stage reference_stage = {true, LUZ_ISA_SCALAR};

/* Draws a scene into a new width x height framebuffer. */
static luz_framebuffer *render(const luz_scene *scene, const luz_texture_set *texture_set,
                               int width, int height, int thread_count, stage how)
{
    luz_error error = {{0}};
    luz_renderer_desc desc = {.thread_count = thread_count, .reference = how.reference};
    luz_renderer *renderer = luz_renderer_create(&desc, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, &error);
    luz_frame frame = {0};
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    if (!how.reference) luz_renderer_set_isa(renderer, how.isa);
    assert_int_equal(luz_scene_build_frame(test_lab(), scene,
                                           texture_set ? texture_set->textures : NULL,
                                           texture_set ? texture_set->count : 0,
                                           (float)width / (float)height, &frame, NULL),
                     0);
    const luz_render_options render = luz_scene_render_options(scene);
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &render, &error), 0);
    luz_frame_free(&frame);
    luz_renderer_destroy(renderer);
    return framebuffer;
}

/* How two images of the same size agree, over all their pixels and over
 * the pixels that a triangle covers (the ones the fragment stage shades). */
typedef struct agreement {
    size_t pixels, identical;                 /* identical: all four channels */
    size_t shaded_pixels, shaded_identical;
    int max_difference;                       /* over every channel */
} agreement;

static agreement compare(const luz_framebuffer *a, const luz_framebuffer *b)
{
    agreement result = {.pixels = (size_t)a->width * (size_t)a->height};
    for (size_t p = 0; p < result.pixels; p++) {
        int difference = 0;
        for (int c = 0; c < 4; c++) {
            int d = abs((int)a->colour[p * 4 + c] - (int)b->colour[p * 4 + c]);
            if (d > difference) difference = d;
        }
        const bool shaded = a->visibility[p] != 0;
        result.identical += difference == 0;
        result.shaded_pixels += shaded;
        result.shaded_identical += shaded && difference == 0;
        if (difference > result.max_difference) result.max_difference = difference;
    }
    return result;
}

static double percent(size_t part, size_t whole)
{
    return whole ? 100.0 * (double)part / (double)whole : 100.0;
}

/* Renders the scene with the reference and with every supported variant of
 * the fast path, and asserts the contract: each channel within 1 level,
 * at least 99.9% of the pixels identical, and of the shaded pixels too. */
static void assert_agreement(const char *name, const luz_scene *scene,
                             const luz_texture_set *texture_set, int width, int height)
{
    luz_framebuffer *expected = render(scene, texture_set, width, height, 1, reference_stage);
    for (size_t v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) {
            print_message("%-26s %-8s not supported by this CPU\n", name, luz_isa_name(variants[v]));
            continue;
        }
        luz_framebuffer *got = render(scene, texture_set, width, height, 1,
                                      (stage){false, variants[v]});
        agreement a = compare(expected, got);
        print_message("%-26s %-8s identical: %zu/%zu pixels (%.4f%%), %zu/%zu shaded "
                      "(%.4f%%); max difference %d\n",
                      name, luz_isa_name(variants[v]), a.identical, a.pixels,
                      percent(a.identical, a.pixels), a.shaded_identical, a.shaded_pixels,
                      percent(a.shaded_identical, a.shaded_pixels), a.max_difference);
        luz_framebuffer_destroy(got);
        assert_true(a.max_difference <= 1);
        assert_true(a.identical * 1000 >= a.pixels * 999);
        assert_true(a.shaded_identical * 1000 >= a.shaded_pixels * 999);
    }
    luz_framebuffer_destroy(expected);
}

/* Renders the scene at half the test size with every supported variant of
 * the fast path, and asserts that each gives `expected`'s bytes. */
static void assert_every_variant_same_bytes(const luz_scene *scene,
                                            const luz_texture_set *texture_set,
                                            const luz_framebuffer *expected)
{
    for (size_t v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) continue;
        luz_framebuffer *got = render(scene, texture_set, HALF_WIDTH, HALF_HEIGHT, 1,
                                      (stage){false, variants[v]});
        assert_memory_equal(got->colour, expected->colour, (size_t)HALF_WIDTH * HALF_HEIGHT * 4);
        luz_framebuffer_destroy(got);
    }
}

/* The number of shaded pixels whose colour differs between the reference
 * images of the scene with bilinear and with trilinear filtering: 0 when
 * every pixel is magnified (trilinear then samples level 0 alone). */
static size_t minified_pixels(const luz_scene *scene, size_t *shaded)
{
    luz_scene bilinear = *scene, trilinear = *scene;
    bilinear.filter = LUZ_FILTER_BILINEAR;
    trilinear.filter = LUZ_FILTER_TRILINEAR;
    luz_framebuffer *a = render(&bilinear, lab_textures(), WIDTH, HEIGHT, 1, reference_stage);
    luz_framebuffer *b = render(&trilinear, lab_textures(), WIDTH, HEIGHT, 1, reference_stage);
    agreement same = compare(a, b);
    luz_framebuffer_destroy(a);
    luz_framebuffer_destroy(b);
    *shaded = same.shaded_pixels;
    return same.shaded_pixels - same.shaded_identical;
}

/* ---- the default scene -------------------------------------------------- */

static const luz_filter filters[] = {LUZ_FILTER_NEAREST, LUZ_FILTER_BILINEAR,
                                     LUZ_FILTER_TRILINEAR};
#define FILTER_COUNT (sizeof filters / sizeof filters[0])

/* assert_agreement for the scene with each filter, the case named
 * "<prefix> <filter>", at the full test size. */
static void assert_agreement_each_filter(const char *prefix, luz_scene scene)
{
    for (size_t f = 0; f < FILTER_COUNT; f++) {
        scene.filter = filters[f];
        char name[64];
        snprintf(name, sizeof name, "%s %s", prefix, luz_filter_name(filters[f]));
        assert_agreement(name, &scene, lab_textures(), WIDTH, HEIGHT);
    }
}


static void default_scene_with_each_filter(void **state)
{
    (void)state;
    const double times[] = {0.0, 3.0, 8.0};
    for (size_t t = 0; t < sizeof times / sizeof times[0]; t++) {
        luz_scene scene = luz_scene_defaults();
        scene.time_seconds = times[t];
        char prefix[32];
        snprintf(prefix, sizeof prefix, "default t=%g", times[t]);
        assert_agreement_each_filter(prefix, scene);
    }
}

/* Each of the six terms alone: the others' strengths 0 (SCENE.md: a term
 * at strength 0 is exactly 0). At t = 3 the point light and the sun have
 * moved off their start positions. */
static void each_term_alone(void **state)
{
    (void)state;
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        luz_scene scene = luz_scene_defaults();
        scene.time_seconds = 3.0;
        for (int other = 0; other < LUZ_TERM_COUNT; other++)
            if (other != term) luz_lights_term(&scene.lights, (luz_term)other)->strength = 0.0f;
        char name[64];
        snprintf(name, sizeof name, "only %s", luz_term_name((luz_term)term));
        assert_agreement(name, &scene, lab_textures(), HALF_WIDTH, HALF_HEIGHT);
    }
}

/* ---- levels of detail -------------------------------------------------- */

/* A quarter of a unit in front of cube 0's front face (z = 0.5): the face
 * fills the screen, 256 texels over 720 rows and more, so every pixel is
 * magnified (lambda <= 0, level 0 alone), as the first check confirms. */
static void camera_close_to_a_cube(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    scene.camera.position = (luz_vec3){0.1f, -0.05f, 0.75f};
    size_t shaded;
    assert_int_equal(minified_pixels(&scene, &shaded), 0);
    assert_int_equal(shaded, (size_t)WIDTH * HEIGHT);

    assert_agreement_each_filter("close", scene);
}

/* 1000 cubes (SCENE.md's tiles) seen from 50 units away; those within the
 * far plane (100) lie 50 to 100 units off, where a cube spans 9 to 17
 * pixels: its 256 texels are minified 15 to 30 times (lambda about 4 to 5,
 * deep in the mip chain; nearly every shaded pixel changes between
 * bilinear and trilinear), and many packets straddle several cubes. */
static void camera_far_from_tiny_cubes(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    scene.cube_count = 1000;
    scene.camera.position = (luz_vec3){0.0f, 0.0f, 50.0f};
    scene.time_seconds = 5.0;
    size_t shaded;
    const size_t minified = minified_pixels(&scene, &shaded);
    assert_true(shaded > 40000);
    assert_true(minified * 10 > shaded * 9);

    assert_agreement_each_filter("far", scene);
}

/* ---- lights at the edges of their ranges ------------------------------- */

static void lights_at_their_limits(void **state)
{
    (void)state;
    /* A fractional exponent: luz_shade_power falls back to powf. */
    luz_scene scene = luz_scene_defaults();
    scene.lights.shininess = 7.5f;
    assert_agreement("shininess 7.5", &scene, lab_textures(), HALF_WIDTH, HALF_HEIGHT);

    /* pow(x, 0) = 1: the highlight covers every lit pixel. */
    scene = luz_scene_defaults();
    scene.lights.shininess = 0.0f;
    assert_agreement("shininess 0", &scene, lab_textures(), HALF_WIDTH, HALF_HEIGHT);

    /* Equal cones: the smooth band between them is empty (and nothing
     * divides by cos(inner) - cos(outer) = 0: equal_cones_divide_by_nothing). */
    scene = luz_scene_defaults();
    scene.lights.spot_inner_degrees = 10.0f;
    scene.lights.spot_outer_degrees = 10.0f;
    assert_agreement("spot cones equal", &scene, lab_textures(), HALF_WIDTH, HALF_HEIGHT);

    /* The widest cones, coloured lights. */
    scene = luz_scene_defaults();
    scene.lights.spot_inner_degrees = 0.0f;
    scene.lights.spot_outer_degrees = 89.0f;
    scene.lights.diffuse.colour = (luz_vec3){1.0f, 0.5f, 0.25f};
    scene.lights.point.colour = (luz_vec3){0.2f, 1.0f, 0.6f};
    assert_agreement("spot cones 0-89, colours", &scene, lab_textures(), HALF_WIDTH, HALF_HEIGHT);
}

/* Equal cones with every variant, the frame drawn on this thread: the
 * floating-point status flags say whether anything divided by zero. The
 * scalar stage divides only strictly between the cones; the packets
 * compute the smooth step in every lane and keep it only there, so their
 * divisor must not be 0 either (UndefinedBehaviorSanitizer's
 * float-divide-by-zero does not see vector divisions: the flag does). */
static void equal_cones_divide_by_nothing(void **state)
{
    (void)state;
    luz_scene scene = luz_scene_defaults();
    scene.lights.spot_inner_degrees = 10.0f;
    scene.lights.spot_outer_degrees = 10.0f;
    for (size_t v = 0; v < sizeof variants / sizeof variants[0]; v++) {
        if (!luz_isa_available(variants[v])) continue;
        feclearexcept(FE_DIVBYZERO);
        luz_framebuffer *image =
            render(&scene, lab_textures(), HALF_WIDTH, HALF_HEIGHT, 1, (stage){false, variants[v]});
        const bool divided_by_zero = fetestexcept(FE_DIVBYZERO) != 0;
        luz_framebuffer_destroy(image);
        if (divided_by_zero) fail_msg("%s: a division by zero", luz_isa_name(variants[v]));
    }
}

/* The spot alone, no textures (so nothing but the spot's own arithmetic
 * can differ), with its edges through the cubes: a narrow cone (inner 3,
 * outer 9 degrees) and a reach of 3.5 from the start position (0, 0, 3),
 * so the cone's rim and the fade-out at the reach both cross packets
 * (cube 0's front face is 2.5 away, the cubes at z = -1.5 about 4.5).
 * The packets leave the term out of a pass whose pixels are all outside
 * the cone or beyond the reach, where it is exactly +0; the reference
 * computes it everywhere. Both must give the same bytes, at one sample and
 * at four (the list of edge fragments). The frame must show both sides:
 * pixels the spot lights and shaded pixels it leaves black. */
static void spot_edges_same_bytes_in_both_paths(void **state)
{
    (void)state;
    const luz_texture_set none = {0};
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 2.0;
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        if (term != LUZ_TERM_SPOT) luz_lights_term(&scene.lights, (luz_term)term)->strength = 0.0f;
    scene.lights.spot_inner_degrees = 3.0f;
    scene.lights.spot_outer_degrees = 9.0f;
    scene.lights.spot_reach = 3.5f;
    for (int samples = 1; samples <= 4; samples += 3) {
        scene.samples = samples;
        luz_framebuffer *expected =
            render(&scene, &none, HALF_WIDTH, HALF_HEIGHT, 1, reference_stage);
        size_t lit = 0, dark = 0;
        /* Shaded pixels are those not of the clear colour (0.1: bytes
         * 26); the spot alone leaves the unlit ones black. */
        for (size_t p = 0; p < (size_t)HALF_WIDTH * HALF_HEIGHT; p++) {
            const uint8_t *rgb = expected->colour + p * 4;
            if (rgb[0] == 26 && rgb[1] == 26 && rgb[2] == 26) continue;
            if (rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0) dark++;
            else lit++;
        }
        print_message("spot edges, %d sample(s): %zu pixels lit, %zu shaded and dark\n",
                      samples, lit, dark);
        assert_true(lit > 1000 && dark > 1000);
        assert_every_variant_same_bytes(&scene, &none, expected);
        luz_framebuffer_destroy(expected);
    }
}

/* ---- exact properties ----------------------------------------------------- */

/* Each pixel is shaded from its own position alone, so neither the bands
 * (one per thread or not) nor where a row's last, short packet ends change
 * a byte (1283 = 80 packets of 16 + 3 pixels; 719 rows end in a short
 * band). And every variant performs the same operations lane by lane, so
 * the image does not depend on the CPU either. */
static void same_bytes_for_any_thread_count_and_variant(void **state)
{
    (void)state;
    enum { ODD_WIDTH = 1283, ODD_HEIGHT = 719 };
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 8.0;
    scene.cube_count = 40;
    luz_framebuffer *first = NULL;
    for (size_t v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) continue;
        const stage fast = {false, variants[v]};
        luz_framebuffer *one = render(&scene, lab_textures(), ODD_WIDTH, ODD_HEIGHT, 1, fast);
        const int thread_counts[] = {2, 3, 7};
        for (size_t k = 0; k < sizeof thread_counts / sizeof thread_counts[0]; k++) {
            luz_framebuffer *many =
                render(&scene, lab_textures(), ODD_WIDTH, ODD_HEIGHT, thread_counts[k], fast);
            assert_memory_equal(one->colour, many->colour, (size_t)ODD_WIDTH * ODD_HEIGHT * 4);
            luz_framebuffer_destroy(many);
        }
        if (first == NULL) {
            first = one;
        } else {
            assert_memory_equal(first->colour, one->colour, (size_t)ODD_WIDTH * ODD_HEIGHT * 4);
            luz_framebuffer_destroy(one);
        }
    }
    luz_framebuffer_destroy(first);
}

/* round(c * 255) in double precision, and whether c * 255 is so close to a
 * half that float and double evaluation could round it differently. */
static int rounded(double c)
{
    return (int)floor(c * 255.0 + 0.5);
}

static bool near_a_half(double c)
{
    double scaled = c * 255.0;
    return fabs(scaled - floor(scaled) - 0.5) < 1e-4;
}

/* With no textures (T = 1) and only the ambient light, a cube's colour is
 * 0.2 C: every pixel of cube i must be exactly round(0.2 C_i 255) on both
 * paths, and the background the clear colour round(0.1 255) = 26. Each
 * cube is drawn alone (a custom cube list of one) so that every covered
 * pixel is known to be its. */
static void ambient_only_is_exact(void **state)
{
    (void)state;
    enum { SMALL_WIDTH = 321, SMALL_HEIGHT = 181 };
    luz_vec3 colours[10];
    luz_scene_random_colours(0, 10, colours);
    const luz_texture_set none = {0};

    for (int i = 0; i < 10; i++) {
        const luz_object cube = {
            .position = luz_scene_tiled_position(i),
            .has_colour = true,
            .colour = colours[i],
            .texture = LUZ_TEXTURE_BY_INDEX,
        };
        luz_scene scene = luz_scene_defaults();
        scene.time_seconds = 2.0;
        scene.objects = &cube;
        scene.object_count = 1;
        for (int term = 0; term < LUZ_TERM_COUNT; term++)
            if (term != LUZ_TERM_AMBIENT)
                luz_lights_term(&scene.lights, (luz_term)term)->strength = 0.0f;

        const double ambient = 0.2;
        int expected[3];
        for (int c = 0; c < 3; c++) {
            const double channel = c == 0 ? colours[i].x : c == 1 ? colours[i].y : colours[i].z;
            assert_false(near_a_half(ambient * channel));
            expected[c] = rounded(ambient * channel);
        }

        for (size_t v = 0; v <= VARIANT_COUNT; v++) {
            const bool reference = v == VARIANT_COUNT;
            if (!reference && !luz_isa_available(variants[v])) continue;
            const stage how = reference ? reference_stage : (stage){false, variants[v]};
            luz_framebuffer *image = render(&scene, &none, SMALL_WIDTH, SMALL_HEIGHT, 1, how);
            size_t covered = 0;
            for (size_t p = 0; p < (size_t)SMALL_WIDTH * SMALL_HEIGHT; p++) {
                const uint8_t *rgba = image->colour + p * 4;
                assert_int_equal(rgba[3], 255);
                if (image->visibility[p] == 0) {
                    assert_int_equal(rgba[0], 26);
                    assert_int_equal(rgba[1], 26);
                    assert_int_equal(rgba[2], 26);
                    continue;
                }
                covered++;
                assert_int_equal(rgba[0], expected[0]);
                assert_int_equal(rgba[1], expected[1]);
                assert_int_equal(rgba[2], expected[2]);
            }
            /* Cubes 0-9 are all in view of the start camera. */
            assert_true(covered > 0);
            luz_framebuffer_destroy(image);
        }
    }
}

/* ---- the output: exposure and tone map ------------------------------------ */

static const luz_output outputs[] = {
    {.exposure = -1.0f, .tone_map = LUZ_TONE_MAP_CLAMP},
    {.exposure = 1.5f, .tone_map = LUZ_TONE_MAP_CLAMP},
    {.exposure = 0.0f, .tone_map = LUZ_TONE_MAP_NEUTRAL},
    {.exposure = -1.0f, .tone_map = LUZ_TONE_MAP_NEUTRAL},
    {.exposure = 2.5f, .tone_map = LUZ_TONE_MAP_NEUTRAL},
    {.exposure = -0.3f, .tone_map = LUZ_TONE_MAP_NEUTRAL},
};
#define OUTPUT_COUNT (sizeof outputs / sizeof outputs[0])

static luz_scene scene_with_output(luz_output output)
{
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 3.0;
    scene.has_exposure = scene.has_tone_map = true;
    scene.exposure = output.exposure;
    scene.tone_map = output.tone_map;
    return scene;
}

/* Untextured (T = 1, so the level of detail's logarithm, the one
 * operation the paths compute differently, is never taken), the SIMD
 * variants give the reference's bytes exactly under every output, with one
 * sample a pixel and with four; and each output changes more than a third
 * of the plain image's pixels (the cubes cover 38% of it). With the textures the usual contract
 * holds. */
static void output_same_bytes_in_both_paths(void **state)
{
    (void)state;
    const luz_texture_set none = {0};
    for (int samples = 1; samples <= 4; samples += 3) {
    luz_scene plain_at_3 = luz_scene_defaults();
    plain_at_3.time_seconds = 3.0;
    plain_at_3.samples = samples;
    luz_framebuffer *unchanged =
        render(&plain_at_3, &none, HALF_WIDTH, HALF_HEIGHT, 1, reference_stage);
    for (size_t o = 0; o < OUTPUT_COUNT; o++) {
        luz_scene scene = scene_with_output(outputs[o]);
        scene.samples = samples;
        luz_framebuffer *expected =
            render(&scene, &none, HALF_WIDTH, HALF_HEIGHT, 1, reference_stage);
        const agreement moved = compare(unchanged, expected);
        /* The cubes cover 38% of the image (87421 of 230400 pixels at
         * one sample); all but a few of theirs change. */
        print_message("output %s EV %g, %d sample(s): %zu of %zu pixels changed\n",
                      luz_tone_map_name(outputs[o].tone_map), (double)outputs[o].exposure,
                      samples, moved.pixels - moved.identical, moved.pixels);
        assert_true((moved.pixels - moved.identical) * 3 > moved.pixels);
        assert_every_variant_same_bytes(&scene, &none, expected);
        luz_framebuffer_destroy(expected);

        char name[64];
        snprintf(name, sizeof name, "output %s EV %g, %d", luz_tone_map_name(outputs[o].tone_map),
                 (double)outputs[o].exposure, samples);
        assert_agreement(name, &scene, lab_textures(), HALF_WIDTH, HALF_HEIGHT);
    }
    luz_framebuffer_destroy(unchanged);
    }
}

/* SCENE.md: the point-light marker and the clear colour are written as
 * they are. A marker coloured (0.2, 0.6, 1) is bytes (51, 153, 255) at
 * every output, and the background 26 (test_shade and the test above
 * show the lit pixels change). One cube far behind, at t = 7.85 (the light's orbit at 5/4 pi, in view). */
static void output_leaves_marker_and_background(void **state)
{
    (void)state;
    enum { SMALL_WIDTH = 321, SMALL_HEIGHT = 181 };
    const luz_texture_set none = {0};
    const luz_object cube = {.position = {0.0f, 0.0f, -6.0f},
                             .has_colour = true,
                             .colour = {1.0f, 1.0f, 1.0f},
                             .texture = LUZ_TEXTURE_BY_INDEX};
    for (size_t o = 0; o < OUTPUT_COUNT; o++) {
        luz_scene scene = scene_with_output(outputs[o]);
        scene.time_seconds = 7.85;
        scene.objects = &cube;
        scene.object_count = 1;
        scene.lights.point.colour = (luz_vec3){0.2f, 0.6f, 1.0f};
        /* Triangle ids count those that survive culling, in draw order:
         * the cube's are those of the image without the marker (a point
         * light at strength 0 is not drawn), the marker's come after. */
        luz_scene unmarked = scene;
        unmarked.lights.point.strength = 0.0f;
        luz_framebuffer *cube_only =
            render(&unmarked, &none, SMALL_WIDTH, SMALL_HEIGHT, 1, reference_stage);
        uint32_t cube_ids = 0;
        for (size_t p = 0; p < (size_t)SMALL_WIDTH * SMALL_HEIGHT; p++)
            if (cube_only->visibility[p] > cube_ids) cube_ids = cube_only->visibility[p];
        luz_framebuffer_destroy(cube_only);
        assert_true(cube_ids > 0);
        for (size_t v = 0; v <= VARIANT_COUNT; v++) {
            const bool reference = v == VARIANT_COUNT;
            if (!reference && !luz_isa_available(variants[v])) continue;
            const stage how = reference ? reference_stage : (stage){false, variants[v]};
            luz_framebuffer *image = render(&scene, &none, SMALL_WIDTH, SMALL_HEIGHT, 1, how);
            size_t marker = 0, background = 0, cube_pixels = 0;
            for (size_t p = 0; p < (size_t)SMALL_WIDTH * SMALL_HEIGHT; p++) {
                const uint8_t *rgba = image->colour + p * 4;
                const uint32_t id = image->visibility[p];
                if (id == 0) {
                    background++;
                    assert_int_equal(rgba[0], 26);
                    assert_int_equal(rgba[1], 26);
                    assert_int_equal(rgba[2], 26);
                } else if (id <= cube_ids) {
                    cube_pixels++;
                } else {
                    marker++;
                    assert_int_equal(rgba[0], 51);
                    assert_int_equal(rgba[1], 153);
                    assert_int_equal(rgba[2], 255);
                }
            }
            assert_true(cube_pixels > 0);
            assert_true(marker > 0);
            assert_true(background > 0);
            luz_framebuffer_destroy(image);
        }
    }
}

/* ---- every byte of colour, in either channel order ----------------------- */

/* A clear colour whose channels all differ, each far from a rounding tie:
 * 0.25 * 255 = 63.75, 0.6 * 255 = 153.0, 0.85 * 255 = 216.75. */
static const luz_vec3 tinted_clear = {0.25f, 0.6f, 0.85f};
static const uint8_t tinted_clear_bytes[3] = {64, 153, 217};

/* Draws frame into a new width x height framebuffer in the given channel
 * order, whose colour held `fill` in every byte beforehand. */
static luz_framebuffer *render_over(const luz_frame *frame, int width, int height, stage how,
                                    uint8_t fill, luz_channel_order order)
{
    luz_error error = {{0}};
    luz_renderer_desc desc = {.thread_count = 1, .reference = how.reference};
    luz_renderer *renderer = luz_renderer_create(&desc, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(width, height, &error);
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    if (!how.reference) luz_renderer_set_isa(renderer, how.isa);
    memset(framebuffer->colour, fill, (size_t)width * (size_t)height * 4);
    luz_framebuffer_use_colour(framebuffer, NULL, order);
    assert_int_equal(luz_renderer_draw(renderer, frame, framebuffer, NULL, &error), 0);
    luz_renderer_destroy(renderer);
    return framebuffer;
}

/* For the reference and every variant: the image drawn over colour full
 * of 0xA5 bytes is the image drawn over zeros, byte for byte; each
 * background pixel is (64, 153, 217, 255), round(clear colour * 255); and
 * the BGRA image is the RGBA one with bytes 0 and 2 of every pixel
 * swapped, background and cubes alike. 321 = 20 * 16 + 1 pixels a row, so
 * every variant's last packet of a row is short. */
static void every_byte_written_in_either_order(void **state)
{
    (void)state;
    enum { SMALL_WIDTH = 321, SMALL_HEIGHT = 181 };
    const size_t pixels = (size_t)SMALL_WIDTH * SMALL_HEIGHT;
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 3.0;
    scene.cube_count = 40;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, lab_textures()->textures, lab_textures()->count,
                                           (float)SMALL_WIDTH / (float)SMALL_HEIGHT, &frame, NULL),
                     0);
    frame.clear_colour = tinted_clear;

    for (size_t v = 0; v <= VARIANT_COUNT; v++) {
        const bool reference = v == VARIANT_COUNT;
        if (!reference && !luz_isa_available(variants[v])) continue;
        const stage how = reference ? reference_stage : (stage){false, variants[v]};
        const char *name = reference ? "reference" : luz_isa_name(variants[v]);
        luz_framebuffer *zeros =
            render_over(&frame, SMALL_WIDTH, SMALL_HEIGHT, how, 0x00, LUZ_CHANNELS_RGBA);
        luz_framebuffer *garbage =
            render_over(&frame, SMALL_WIDTH, SMALL_HEIGHT, how, 0xA5, LUZ_CHANNELS_RGBA);
        luz_framebuffer *bgra =
            render_over(&frame, SMALL_WIDTH, SMALL_HEIGHT, how, 0xA5, LUZ_CHANNELS_BGRA);
        assert_int_equal(bgra->channel_order, LUZ_CHANNELS_BGRA);
        assert_memory_equal(zeros->colour, garbage->colour, pixels * 4);

        size_t background = 0, shaded_red_not_blue = 0;
        for (size_t p = 0; p < pixels; p++) {
            const uint8_t *rgba = zeros->colour + p * 4, *swapped = bgra->colour + p * 4;
            if (swapped[0] != rgba[2] || swapped[1] != rgba[1] || swapped[2] != rgba[0] ||
                swapped[3] != rgba[3])
                fail_msg("%s: pixel %zu is (%d, %d, %d, %d) in BGRA, (%d, %d, %d, %d) in RGBA",
                         name, p, swapped[0], swapped[1], swapped[2], swapped[3], rgba[0],
                         rgba[1], rgba[2], rgba[3]);
            if (zeros->visibility[p] != 0) {
                shaded_red_not_blue += rgba[0] != rgba[2];
                continue;
            }
            background++;
            if (rgba[0] != tinted_clear_bytes[0] || rgba[1] != tinted_clear_bytes[1] ||
                rgba[2] != tinted_clear_bytes[2] || rgba[3] != 255)
                fail_msg("%s: background pixel %zu is (%d, %d, %d, %d)", name, p, rgba[0],
                         rgba[1], rgba[2], rgba[3]);
        }
        print_message("%-9s %zu background pixels, %zu shaded with red != blue\n", name,
                      background, shaded_red_not_blue);
        /* The swap is seen on both kinds of pixel. */
        assert_true(background > 0 && background < pixels);
        assert_true(shaded_red_not_blue > 0);
        luz_framebuffer_destroy(zeros);
        luz_framebuffer_destroy(garbage);
        luz_framebuffer_destroy(bgra);
    }
    luz_frame_free(&frame);
}


/* ---- pixel-sized triangles: packets of many triangles ------------------ */

/* A wavy grid of 240 x 135 quads (64,800 triangles) filling a 321 x 181
 * image, one triangle to about a pixel, in two draws (a vertical split, so
 * some packets hold triangles of both), textured with each filter: most
 * packets hold three triangles or more, which the fast path shades in one
 * pass per draw with each lane's own triangle's planes. The contract is
 * the one assert_agreement checks, against the reference, for every
 * variant; and the depth and visibility buffers are the reference's to
 * the bit, with and without screening. */
static void pixel_sized_triangles(void **state)
{
    (void)state;
    enum { SMALL_WIDTH = 321, SMALL_HEIGHT = 181, COLUMNS = 240, ROWS = 135 };
    luz_scene scene = luz_scene_defaults();
    scene.time_seconds = 3.0;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, lab_textures()->textures, lab_textures()->count,
                                           (float)SMALL_WIDTH / (float)SMALL_HEIGHT, &frame, NULL),
                     0);
    frame.draw_count = 0;   /* keep the camera and the lights, draw the grid */

    /* The camera sits at (0, 0, 3) looking down -z with a 45-degree field
     * of view: at z = 0 the image spans 2 tan(22.5 deg) 3 = 2.49 high. */
    const float half_height = 1.25f, half_width = half_height * SMALL_WIDTH / SMALL_HEIGHT;
    luz_vertex *vertices = calloc((size_t)(COLUMNS + 1) * (ROWS + 1), sizeof *vertices);
    uint32_t *indices = calloc((size_t)COLUMNS * ROWS * 6, sizeof *indices);
    assert_non_null(vertices);
    assert_non_null(indices);
    for (int row = 0; row <= ROWS; row++)
        for (int column = 0; column <= COLUMNS; column++) {
            const float u = (float)column / COLUMNS, v = (float)row / ROWS;
            const float wave = 0.3f * sinf(9.0f * u) * cosf(7.0f * v);
            vertices[row * (COLUMNS + 1) + column] = (luz_vertex){
                {(2.0f * u - 1.0f) * half_width, (1.0f - 2.0f * v) * half_height, wave},
                {sinf(9.0f * u), cosf(7.0f * v), 1.0f},
                {4.0f * u, 3.0f * v},
            };
        }
    luz_mesh *halves[2];
    for (int half = 0; half < 2; half++) {
        size_t count = 0;
        for (int row = 0; row < ROWS; row++)
            for (int column = half * COLUMNS / 2; column < (half + 1) * COLUMNS / 2; column++) {
                const uint32_t a = (uint32_t)(row * (COLUMNS + 1) + column), b = a + 1,
                               c = a + COLUMNS + 1, d = c + 1;
                const uint32_t quad[6] = {a, c, d, a, d, b};   /* counter-clockwise */
                memcpy(&indices[count], quad, sizeof quad);
                count += 6;
            }
        luz_error error = {{0}};
        halves[half] = luz_mesh_create(
            &(luz_mesh_desc){.vertices = vertices, .vertex_count = (COLUMNS + 1) * (ROWS + 1),
                             .indices = indices, .index_count = (uint32_t)count},
            &error);
        assert_non_null(halves[half]);
        luz_draw draw = {.mesh = halves[half], .model = luz_mat4_identity()};
        draw.material.colour = half ? (luz_vec3){0.9f, 0.6f, 0.3f} : (luz_vec3){0.4f, 0.8f, 1.0f};
        draw.material.has_colour = true;
        draw.material.texture = lab_textures()->textures[half];
        assert_int_equal(luz_frame_add_draw(&frame, &draw, &error), 0);
    }
    free(vertices);
    free(indices);

    for (size_t f = 0; f < FILTER_COUNT; f++) {
        for (int d = 0; d < frame.draw_count; d++) frame.draws[d].material.filter = filters[f];
        luz_framebuffer *expected =
            render_over(&frame, SMALL_WIDTH, SMALL_HEIGHT, reference_stage, 0, LUZ_CHANNELS_RGBA);
        /* Packets of 4 pixels (the narrowest variant) with three triangles
         * or more: what the per-lane planes are for. */
        size_t packets = 0, mixed = 0;
        for (int y = 0; y < SMALL_HEIGHT; y++)
            for (int x = 0; x + 4 <= SMALL_WIDTH; x += 4) {
                const uint32_t *ids = expected->visibility + (size_t)y * SMALL_WIDTH + x;
                int distinct = 0;
                for (int i = 0; i < 4; i++) {
                    bool seen = false;
                    for (int j = 0; j < i; j++) seen = seen || ids[j] == ids[i];
                    distinct += !seen && ids[i] != 0;
                }
                packets++;
                mixed += distinct >= 3;
            }
        assert_true(mixed * 4 > packets);
        for (size_t v = 0; v < VARIANT_COUNT; v++) {
            if (!luz_isa_available(variants[v])) continue;
            luz_framebuffer *got = render_over(&frame, SMALL_WIDTH, SMALL_HEIGHT,
                                               (stage){false, variants[v]}, 0, LUZ_CHANNELS_RGBA);
            agreement a = compare(expected, got);
            print_message("grid %-9s %-8s identical: %zu/%zu shaded (%.4f%%); max difference "
                          "%d; %zu of %zu 4-pixel packets hold 3+ triangles\n",
                          luz_filter_name(filters[f]), luz_isa_name(variants[v]), a.shaded_identical,
                          a.shaded_pixels, percent(a.shaded_identical, a.shaded_pixels),
                          a.max_difference, mixed, packets);
            assert_true(a.shaded_pixels * 10 > (size_t)SMALL_WIDTH * SMALL_HEIGHT * 9);
            assert_true(a.max_difference <= 1);
            assert_true(a.shaded_identical * 1000 >= a.shaded_pixels * 999);
            /* The raster's output is the same bits whichever variant:
             * the AVX-512 one screens triangles before setup (screen.c;
             * so does the reference, which takes the best), the others
             * leave every triangle to setup, and screening may drop only
             * what setup would. */
            const size_t pixels = (size_t)SMALL_WIDTH * SMALL_HEIGHT;
            assert_memory_equal(got->visibility, expected->visibility,
                                pixels * sizeof *got->visibility);
            assert_memory_equal(got->depth, expected->depth, pixels * sizeof *got->depth);
            luz_framebuffer_destroy(got);
        }
        luz_framebuffer_destroy(expected);
    }
    luz_frame_free(&frame);
    luz_mesh_destroy(halves[0]);
    luz_mesh_destroy(halves[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(default_scene_with_each_filter),
        cmocka_unit_test(each_term_alone),
        cmocka_unit_test(camera_close_to_a_cube),
        cmocka_unit_test(camera_far_from_tiny_cubes),
        cmocka_unit_test(lights_at_their_limits),
        cmocka_unit_test(equal_cones_divide_by_nothing),
        cmocka_unit_test(spot_edges_same_bytes_in_both_paths),
        cmocka_unit_test(same_bytes_for_any_thread_count_and_variant),
        cmocka_unit_test(ambient_only_is_exact),
        cmocka_unit_test(every_byte_written_in_either_order),
        cmocka_unit_test(pixel_sized_triangles),
        cmocka_unit_test(output_same_bytes_in_both_paths),
        cmocka_unit_test(output_leaves_marker_and_background),
    };
    return cmocka_run_group_tests(tests, lab_textures_load, lab_textures_free);
}
