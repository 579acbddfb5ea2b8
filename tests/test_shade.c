/*
 * test_shade.c: the six light terms of luz/shade.h, one geometry at a time,
 * against SCENE.md's fragment equations evaluated by hand.
 *
 * Every light is coloured (0.2, 0.5, 1.0) with strength 0.8 unless a test
 * says otherwise, so a term that mixes up channels, forgets the strength or
 * applies it twice cannot pass.
 *
 * Then the output (SCENE.md, "Output: exposure and tone map"): the
 * exposure's factor 2^EV, and the Khronos PBR Neutral tone map on colours
 * worked through its formula by hand (each branch: a minimum below 0.08,
 * a peak below 0.76, the compression and the mix towards grey), and on
 * many colours against the formula evaluated again here in double.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "test_support.h"

#include "lab/scene.h"
#include "luz/shade.h"

/* The terms are a few single-precision operations on values near 1. */
#define TOLERANCE 2e-6

/* got == factor * (0.2, 0.5, 1.0) within tolerance, channel by channel. */
#define assert_light(got, factor, tolerance) \
    assert_light_at((got), (factor), (tolerance), #got, __FILE__, __LINE__)

static void assert_light_at(luz_vec3 got, double factor, double tolerance,
                            const char *expression, const char *file, int line)
{
    assert_near_at(got.x, factor * 0.2, tolerance, expression, file, line);
    assert_near_at(got.y, factor * 0.5, tolerance, expression, file, line);
    assert_near_at(got.z, factor * 1.0, tolerance, expression, file, line);
}

/* Exactly zero in all three channels: SCENE.md says so for a light that is
 * off, and max(..., 0) makes it so for a surface turned away. */
#define assert_exactly_zero(got) \
    do { \
        luz_vec3 zero_ = (got); \
        assert_true(zero_.x == 0.0f && zero_.y == 0.0f && zero_.z == 0.0f); \
    } while (0)

static const luz_light coloured_light = {{0.2f, 0.5f, 1.0f}, 0.8f};
static const luz_light dark_light = {{0.2f, 0.5f, 1.0f}, 0.0f};

static const luz_vec3 origin = {0, 0, 0};
static const luz_vec3 up_z = {0, 0, 1};

/* ambient = A.a * A.rgb = 0.8 (0.2, 0.5, 1). */
static void test_ambient(void **state)
{
    (void)state;
    assert_light(luz_shade_ambient(&coloured_light), 0.8, TOLERANCE);
    assert_exactly_zero(luz_shade_ambient(&dark_light));
}

/* Normal +z at the origin, headlight at (sqrt 3, 0, 1): L makes 60 degrees
 * with N, so max(dot(N, L), 0) = cos 60 = 0.5 and diffuse = 0.5 * 0.8 *
 * rgb. Straight above (0, 0, 5): 1 * 0.8. Below the surface (0, 0, -5):
 * dot = -1, clamped to 0. */
static void test_diffuse(void **state)
{
    (void)state;
    const luz_vec3 at_60_degrees = {sqrtf(3.0f), 0, 1};
    assert_light(luz_shade_diffuse(up_z, origin, at_60_degrees, &coloured_light), 0.4,
                 TOLERANCE);
    assert_light(luz_shade_diffuse(up_z, origin, (luz_vec3){0, 0, 5}, &coloured_light), 0.8,
                 TOLERANCE);
    assert_exactly_zero(luz_shade_diffuse(up_z, origin, (luz_vec3){0, 0, -5}, &coloured_light));
    assert_exactly_zero(luz_shade_diffuse(up_z, origin, at_60_degrees, &dark_light));
}

/* The specular light is the headlight, so V = L and R = reflect(-L, N) =
 * -L + 2 (N.L) N, which gives dot(V, R) = 2 (N.L)^2 - 1.
 *   Eye on the normal: N.L = 1, dot(V, R) = 1, specular = 0.8 rgb for any
 *   shininess.
 *   Eye at 30 degrees, (1, 0, sqrt 3): N.L = cos 30, (N.L)^2 = 3/4, so
 *   dot(V, R) = 1/2: shininess 2 gives 1/4 * 0.8, shininess 3 gives
 *   1/8 * 0.8, shininess 1.5 gives 0.5^1.5 = 0.35355339 times 0.8.
 *   Eye at 60 degrees: (N.L)^2 = 1/4, dot(V, R) = -1/2, clamped to 0:
 *   0^32 = 0 exactly.
 *   Eye at 120 degrees (behind the surface, N.L = -1/2): dot(V, R) = -1/2,
 *   0 as well. */
static void test_specular(void **state)
{
    (void)state;
    const luz_vec3 on_normal = {0, 0, 4};
    const luz_vec3 at_30_degrees = {1, 0, sqrtf(3.0f)};
    const luz_vec3 at_60_degrees = {sqrtf(3.0f), 0, 1};
    const luz_vec3 at_120_degrees = {sqrtf(3.0f), 0, -1};
    assert_light(luz_shade_specular(up_z, origin, on_normal, &coloured_light, 32.0f), 0.8,
                 TOLERANCE);
    assert_light(luz_shade_specular(up_z, origin, at_30_degrees, &coloured_light, 2.0f),
                 0.25 * 0.8, TOLERANCE);
    assert_light(luz_shade_specular(up_z, origin, at_30_degrees, &coloured_light, 3.0f),
                 0.125 * 0.8, TOLERANCE);
    assert_light(luz_shade_specular(up_z, origin, at_30_degrees, &coloured_light, 1.5f),
                 0.35355339 * 0.8, TOLERANCE);
    assert_exactly_zero(luz_shade_specular(up_z, origin, at_60_degrees, &coloured_light, 32.0f));
    assert_exactly_zero(
        luz_shade_specular(up_z, origin, at_120_degrees, &coloured_light, 32.0f));
    assert_exactly_zero(luz_shade_specular(up_z, origin, on_normal, &dark_light, 32.0f));
}

/* Shininess 0: SCENE.md's pow follows C, pow(0, 0) = 1. At 60 degrees
 * dot(V, R) = -1/2, max(-1/2, 0) = 0 and 0^0 = 1, so specular is the full
 * 0.8 rgb even though the highlight points away; at 30 degrees 0.5^0 = 1
 * too. */
static void test_specular_shininess_zero_follows_c_pow(void **state)
{
    (void)state;
    const luz_vec3 at_60_degrees = {sqrtf(3.0f), 0, 1};
    const luz_vec3 at_30_degrees = {1, 0, sqrtf(3.0f)};
    assert_light(luz_shade_specular(up_z, origin, at_60_degrees, &coloured_light, 0.0f), 0.8,
                 TOLERANCE);
    assert_light(luz_shade_specular(up_z, origin, at_30_degrees, &coloured_light, 0.0f), 0.8,
                 TOLERANCE);
}

/* Point light at P + (3, 0, 4): Lp = (0.6, 0, 0.8), dot(N, Lp) = 0.8, so
 * point = 0.8 * 0.8 rgb. The fragment is not at the origin, so a term
 * that forgot to subtract P would see (4, 2, 4) instead. At P + (0, 0, -2),
 * behind the surface: 0. */
static void test_point(void **state)
{
    (void)state;
    const luz_vec3 position = {1, 2, 0};
    assert_light(luz_shade_point(up_z, position, (luz_vec3){4, 2, 4}, &coloured_light),
                 0.8 * 0.8, TOLERANCE);
    assert_exactly_zero(luz_shade_point(up_z, position, (luz_vec3){1, 2, -2}, &coloured_light));
    assert_exactly_zero(luz_shade_point(up_z, position, (luz_vec3){4, 2, 4}, &dark_light));
}

/* The spot rides on a camera at E = (1, 1, 1) looking down -z; the
 * fragment is at E + d (sin a, 0, -cos a), a degrees off the axis. The
 * scene's cones: ci = cos 12.5 = 0.97629601, co = cos 17.5 = 0.95371695;
 * reach 10. */
static const luz_vec3 spot_eye = {1, 1, 1};
static const luz_vec3 spot_front = {0, 0, -1};
static const float scene_cos_inner = 0.97629601f;
static const float scene_cos_outer = 0.95371695f;

static luz_vec3 spot_fragment(double degrees_off_axis, double distance)
{
    double a = degrees_off_axis * LUZ_PI / 180.0;
    return (luz_vec3){(float)(spot_eye.x + distance * sin(a)), spot_eye.y,
                      (float)(spot_eye.z - distance * cos(a))};
}

static luz_vec3 scene_spot(luz_vec3 position, const luz_light *spot)
{
    return luz_shade_spot(position, spot_eye, spot_front, spot, scene_cos_inner,
                          scene_cos_outer, 10.0f);
}

/* On the axis, f_dir = 1. At distance 5 = reach / 2: dn = 0.5, dn^4 =
 * 0.0625, f_win = 0.9375^2 = 0.87890625, f_dist = 0.87890625 * a^2 / 1.25 =
 * 0.703125 a^2. Strength 0.8 enters squared: 0.703125 * 0.64 = 0.45. At
 * distance 4 with strength 1: f_win = (1 - 0.0256)^2 = 0.94945536,
 * f_dist = 0.94945536 / 1.16 = 0.818496. An unnormalised front (0, 0, -3)
 * must give the same, as SCENE.md normalises F. */
static void test_spot_on_axis(void **state)
{
    (void)state;
    assert_light(scene_spot(spot_fragment(0, 5), &coloured_light), 0.703125 * 0.64, TOLERANCE);
    const luz_light full = {{0.2f, 0.5f, 1.0f}, 1.0f};
    assert_light(scene_spot(spot_fragment(0, 4), &full), 0.818496, TOLERANCE);
    assert_light(luz_shade_spot(spot_fragment(0, 4), spot_eye, (luz_vec3){0, 0, -3}, &full,
                                scene_cos_inner, scene_cos_outer, 10.0f),
                 0.818496, TOLERANCE);
}

/* The strength enters squared: halving it quarters the spot. */
static void test_spot_strength_enters_squared(void **state)
{
    (void)state;
    const luz_light full = {{0.2f, 0.5f, 1.0f}, 1.0f};
    const luz_light half = {{0.2f, 0.5f, 1.0f}, 0.5f};
    luz_vec3 position = spot_fragment(0, 5);
    assert_light(scene_spot(position, &full), 0.703125, TOLERANCE);
    assert_light(scene_spot(position, &half), 0.703125 / 4, TOLERANCE);
}

/* Between the cones, with the scene's angles, 15 degrees off the axis at
 * distance 3, strength 1:
 *   c = cos 15 = 0.96592583, (c - co) / (ci - co) = 0.01220888 / 0.02257906
 *   = 0.54071682, s = sqrt of that = 0.73533449,
 *   f_dir = s^2 (3 - 2 s) = 0.54071682 * 1.52933101 = 0.82693500;
 *   dn = 0.3: f_win = (1 - 0.0081)^2 = 0.98386561, f_dist = 0.98386561 /
 *   1.09 = 0.902629; spot = 0.82693500 * 0.902629 = 0.74641551.
 * The subtraction c - co loses digits in single precision, hence the wider
 * tolerance. */
static void test_spot_between_the_cones(void **state)
{
    (void)state;
    const luz_light full = {{0.2f, 0.5f, 1.0f}, 1.0f};
    assert_light(scene_spot(spot_fragment(15, 3), &full), 0.74641551, 2e-5);
}

/* With cones of my own, ci = 0.9 and co = 0.8, a fragment whose c = 0.825
 * has (c - co) / (ci - co) = 1/4, s = 1/2 and f_dir = 1/4 (3 - 1) = 1/2.
 * At distance 5 (f_dist = 0.703125 with strength 1) the spot is 0.3515625.
 * sin a = sqrt(1 - 0.825^2) = sqrt(0.319375). */
static void test_spot_smoothstep_midpoint(void **state)
{
    (void)state;
    const luz_light full = {{0.2f, 0.5f, 1.0f}, 1.0f};
    const double distance = 5.0, sin_a = sqrt(0.319375), cos_a = 0.825;
    luz_vec3 position = {(float)(spot_eye.x + distance * sin_a), spot_eye.y,
                         (float)(spot_eye.z - distance * cos_a)};
    assert_light(luz_shade_spot(position, spot_eye, spot_front, &full, 0.9f, 0.8f, 10.0f),
                 0.3515625, 2e-5);
}

/* Outside the outer cone (20 degrees > 17.5), behind the camera, at the
 * reach (dn = 1, f_win = 0) and beyond it (dn = 1.2: 1 - 2.0736 < 0,
 * clamped): all exactly 0. With strength 0, on the axis: exactly 0. */
static void test_spot_outside_is_zero(void **state)
{
    (void)state;
    assert_exactly_zero(scene_spot(spot_fragment(20, 3), &coloured_light));
    assert_exactly_zero(scene_spot(spot_fragment(180, 3), &coloured_light));
    assert_exactly_zero(scene_spot(spot_fragment(0, 10), &coloured_light));
    assert_exactly_zero(scene_spot(spot_fragment(0, 12), &coloured_light));
    assert_exactly_zero(scene_spot(spot_fragment(0, 3), &dark_light));
}

/* directional = max(dot(N, normalize(-d)), 0) Dl.rgb Dl.a with N = +y:
 *   d = (0, -3, 0), straight down (not unit): dot = 1, 0.8 rgb;
 *   d = -(sin 60, cos 60, 0): normalize(-d) is 60 degrees from N, 0.5 * 0.8;
 *   d = (0, 1, 0), from below: dot = -1, clamped to 0 (the report's code
 *   would subtract light here; SCENE.md clamps). */
static void test_directional(void **state)
{
    (void)state;
    const luz_vec3 up_y = {0, 1, 0};
    assert_light(luz_shade_directional(up_y, (luz_vec3){0, -3, 0}, &coloured_light), 0.8,
                 TOLERANCE);
    const luz_vec3 at_60_degrees = {-sqrtf(3.0f) / 2, -0.5f, 0};
    assert_light(luz_shade_directional(up_y, at_60_degrees, &coloured_light), 0.4, TOLERANCE);
    assert_exactly_zero(luz_shade_directional(up_y, (luz_vec3){0, 1, 0}, &coloured_light));
    assert_exactly_zero(luz_shade_directional(up_y, (luz_vec3){0, -1, 0}, &dark_light));
}

/* Uniforms where every term has a simple value at the origin, normal +z,
 * all lights white:
 *   ambient 0.2                                      0.2
 *   diffuse 0.6, eye (0, 0, 4) on the normal         0.6
 *   specular 0.5, mirror direction, shininess 32     0.5
 *   point 0.7 at (3, 0, 4): dot = 0.8                0.56
 *   spot 1.0, front (0, 0, -1), on axis at 4         0.818496
 *   directional 0.4, d = (0, 0, -1)                  0.4
 * sum 3.078496. */
static luz_shade_uniforms simple_uniforms(void)
{
    luz_lights lights = luz_scene_defaults().lights;
    lights.spot_direction = (luz_vec3){0, 0, -1};
    lights.point_position = (luz_vec3){3, 0, 4};
    lights.directional_direction = (luz_vec3){0, 0, -1};
    return luz_shade_uniforms_of((luz_vec3){0, 0, 4}, &lights);
}

#define SIMPLE_LIGHT_SUM 3.078496

/* The defaults of SCENE.md's light table feed simple_uniforms()'s sum; the
 * scene's spot cones put (0, 0, 0) on the axis, well inside them. A normal
 * of length 3 must be re-normalised first: without it diffuse alone would
 * be 1.8 and the point term 1.68. */
static void test_lighting_sums_the_terms_and_normalises_the_normal(void **state)
{
    (void)state;
    luz_shade_uniforms uniforms = simple_uniforms();
    luz_vec3 unit = luz_shade_lighting(&uniforms, origin, up_z);
    luz_vec3 long_normal = luz_shade_lighting(&uniforms, origin, (luz_vec3){0, 0, 3});
    assert_near(unit.x, SIMPLE_LIGHT_SUM, 1e-5);
    assert_near(unit.y, SIMPLE_LIGHT_SUM, 1e-5);
    assert_near(unit.z, SIMPLE_LIGHT_SUM, 1e-5);
    assert_near(long_normal.x, SIMPLE_LIGHT_SUM, 1e-5);
    assert_near(long_normal.y, SIMPLE_LIGHT_SUM, 1e-5);
    assert_near(long_normal.z, SIMPLE_LIGHT_SUM, 1e-5);
}

/* colour = (sum of terms) * C * T channel by channel: with C = (0.5, 0.25,
 * 0.1) and T = (1, 0.5, 0.2), 3.078496 * (0.5, 0.125, 0.02) =
 * (1.539248, 0.384812, 0.06156992). Not clamped here: clamping is the
 * colour output's job. */
static void test_fragment_multiplies_by_colour_and_texel(void **state)
{
    (void)state;
    luz_shade_uniforms uniforms = simple_uniforms();
    luz_vec3 colour = luz_shade_fragment(&uniforms, origin, up_z, (luz_vec3){0.5f, 0.25f, 0.1f},
                                         (luz_vec3){1.0f, 0.5f, 0.2f});
    assert_near(colour.x, 1.539248, 1e-5);
    assert_near(colour.y, 0.384812, 1e-5);
    assert_near(colour.z, 0.06156992, 1e-5);
}

/* With every strength at 0 the sum is exactly 0 even where every term
 * would be lit: any term can be studied alone by zeroing the others. */
static void test_all_strengths_zero_give_exact_black(void **state)
{
    (void)state;
    luz_shade_uniforms uniforms = simple_uniforms();
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        luz_lights_term(&uniforms.lights, (luz_term)term)->strength = 0.0f;
    assert_exactly_zero(luz_shade_lighting(&uniforms, origin, up_z));
}

/* ---- output: exposure and tone map ------------------------------------ */

#define assert_rgb(got, r, g, b, tolerance)                \
    do {                                                   \
        const luz_vec3 got_ = (got);                       \
        assert_near(got_.x, (r), (tolerance));             \
        assert_near(got_.y, (g), (tolerance));             \
        assert_near(got_.z, (b), (tolerance));             \
    } while (0)

/* Below 0.08 the minimum sets the offset, x - 6.25 x^2: for x = 0.05,
 * 0.05 - 6.25 * 0.0025 = 0.034375, taken off every channel; the peak,
 * 0.465625, is below 0.76, so that is all. */
static void test_neutral_small_minimum_offsets_only(void **state)
{
    (void)state;
    assert_rgb(luz_tone_map_neutral((luz_vec3){0.05f, 0.3f, 0.5f}), 0.015625, 0.265625,
               0.465625, 1e-7);
    /* A zero minimum: offset 0 - 0 = 0, the colour unchanged. */
    assert_rgb(luz_tone_map_neutral((luz_vec3){0.0f, 0.25f, 0.5f}), 0.0, 0.25, 0.5, 0.0);
}

/* A minimum of 0.08 or more: the offset is 0.04. (0.2, 0.4, 0.6) ->
 * (0.16, 0.36, 0.56), the peak below 0.76. */
static void test_neutral_offset_of_four_hundredths(void **state)
{
    (void)state;
    assert_rgb(luz_tone_map_neutral((luz_vec3){0.2f, 0.4f, 0.6f}), 0.16, 0.36, 0.56, 1e-7);
    /* Just under the start of compression, after the offset: 0.8 - 0.04
     * = 0.76 is at it, 0.79 - 0.04 = 0.75 below. */
    assert_rgb(luz_tone_map_neutral((luz_vec3){0.79f, 0.5f, 0.3f}), 0.75, 0.46, 0.26, 1e-7);
}

/* White above the peak: 1 - 0.04 = 0.96 per channel; new_peak = 1 -
 * 0.24^2 / (0.96 + 0.24 - 0.76) = 1 - 0.0576 / 0.44 = 0.8690909; the three
 * channels equal, the mix leaves them so. White becomes byte 222
 * (0.8690909 * 255 = 221.62), not 255: a white model keeps its shading. */
static void test_neutral_compresses_white(void **state)
{
    (void)state;
    const luz_vec3 white = luz_tone_map_neutral((luz_vec3){1.0f, 1.0f, 1.0f});
    assert_rgb(white, 0.8690909, 0.8690909, 0.8690909, 1e-6);
    assert_int_equal(luz_colour_to_byte(white.x), 222);
}

/* The mix: (2, 1, 0.5) - 0.04 = (1.96, 0.96, 0.46), peak 1.96; new_peak =
 * 1 - 0.0576 / 1.44 = 0.96; scaled by 0.96 / 1.96: (0.96, 0.4702041,
 * 0.2253061); g = 1 - 1 / (0.15 * (1.96 - 0.96) + 1) = 3/23; mixed
 * towards 0.96 by 3/23: (0.96, (0.4702041 * 20 + 0.96 * 3) / 23,
 * (0.2253061 * 20 + 0.96 * 3) / 23) = (0.96, 0.5340905, 0.3211358). */
static void test_neutral_mixes_towards_grey(void **state)
{
    (void)state;
    assert_rgb(luz_tone_map_neutral((luz_vec3){2.0f, 1.0f, 0.5f}), 0.96, 0.5340905, 0.3211358,
               1e-6);
}

/* SCENE.md's formula again, in double, written from the text (not from
 * shade.h's code). */
static void neutral_in_double(const double in[3], double out[3])
{
    double c[3] = {in[0], in[1], in[2]};
    const double x = fmin(c[0], fmin(c[1], c[2]));
    const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    for (int i = 0; i < 3; i++) c[i] -= offset;
    const double peak = fmax(c[0], fmax(c[1], c[2]));
    if (peak >= 0.76) {
        const double d = 0.24;
        const double new_peak = 1.0 - d * d / (peak + d - 0.76);
        const double g = 1.0 - 1.0 / (0.15 * (peak - new_peak) + 1.0);
        for (int i = 0; i < 3; i++) {
            const double scaled = c[i] * new_peak / peak;
            c[i] = scaled + (new_peak - scaled) * g;
        }
    }
    for (int i = 0; i < 3; i++) out[i] = c[i];
}

/* Many colours from black to 16 (EV +4 on a bright spot), each channel
 * against the double evaluation: a few float roundings apart. Every
 * output stays below 1 and, for inputs of at least 0.08, above 0. */
static void test_neutral_against_double(void **state)
{
    (void)state;
    uint32_t seed = 27;
    int compressed = 0, offset_by_minimum = 0;
    for (int i = 0; i < 20000; i++) {
        const float high = (i & 1) ? 1.0f : 16.0f;
        const luz_vec3 in = {test_uniform(&seed, 0.0f, high), test_uniform(&seed, 0.0f, high),
                             test_uniform(&seed, 0.0f, high)};
        const double in_double[3] = {in.x, in.y, in.z};
        double expected[3];
        neutral_in_double(in_double, expected);
        const luz_vec3 got = luz_tone_map_neutral(in);
        const float channels[3] = {got.x, got.y, got.z};
        for (int c = 0; c < 3; c++) {
            assert_near(channels[c], expected[c], 4e-6);
            assert_true(channels[c] < 1.0f);
        }
        compressed += fmax(in.x, fmax(in.y, in.z)) >= 0.8;
        offset_by_minimum += fmin(in.x, fmin(in.y, in.z)) < 0.08;
    }
    /* Both branches were taken, many times. */
    assert_true(compressed > 5000);
    assert_true(offset_by_minimum > 1000);
}

/* The exposure multiplies by 2^EV before the tone map; clamp leaves the
 * rest to luz_colour_to_byte. EV -1 halves exactly; EV +1 then neutral on
 * (1, 0.5, 0.25) is the mix above on (2, 1, 0.5). */
static void test_output_exposes_then_maps(void **state)
{
    (void)state;
    assert_rgb(luz_shade_output((luz_vec3){0.5f, 0.25f, 3.0f}, exp2f(-1.0f), LUZ_TONE_MAP_CLAMP),
               0.25, 0.125, 1.5, 0.0);
    assert_rgb(luz_shade_output((luz_vec3){1.0f, 0.5f, 0.25f}, exp2f(1.0f), LUZ_TONE_MAP_NEUTRAL),
               0.96, 0.5340905, 0.3211358, 1e-6);
    /* A fractional EV: 2^0.5. */
    assert_rgb(luz_shade_output((luz_vec3){1.0f, 0.5f, 0.25f}, exp2f(0.5f), LUZ_TONE_MAP_CLAMP),
               sqrt(2.0), sqrt(2.0) / 2, sqrt(2.0) / 4, 1e-6);
    assert_string_equal(luz_tone_map_name(LUZ_TONE_MAP_CLAMP), "clamp");
    assert_string_equal(luz_tone_map_name(LUZ_TONE_MAP_NEUTRAL), "neutral");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ambient),
        cmocka_unit_test(test_diffuse),
        cmocka_unit_test(test_specular),
        cmocka_unit_test(test_specular_shininess_zero_follows_c_pow),
        cmocka_unit_test(test_point),
        cmocka_unit_test(test_spot_on_axis),
        cmocka_unit_test(test_spot_strength_enters_squared),
        cmocka_unit_test(test_spot_between_the_cones),
        cmocka_unit_test(test_spot_smoothstep_midpoint),
        cmocka_unit_test(test_spot_outside_is_zero),
        cmocka_unit_test(test_directional),
        cmocka_unit_test(test_lighting_sums_the_terms_and_normalises_the_normal),
        cmocka_unit_test(test_fragment_multiplies_by_colour_and_texel),
        cmocka_unit_test(test_all_strengths_zero_give_exact_black),
        cmocka_unit_test(test_neutral_small_minimum_offsets_only),
        cmocka_unit_test(test_neutral_offset_of_four_hundredths),
        cmocka_unit_test(test_neutral_compresses_white),
        cmocka_unit_test(test_neutral_mixes_towards_grey),
        cmocka_unit_test(test_neutral_against_double),
        cmocka_unit_test(test_output_exposes_then_maps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
