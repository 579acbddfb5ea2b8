/*
 * luz/shade.h: the fragment shader, SCENE.md's six light terms.
 *
 * One small pure function per term, each written as its equation reads, so
 * that each can be tested alone against values worked out by hand. All
 * vectors are in world space:
 *
 *   P  the fragment's position        N  its normal (unit length)
 *   E  the eye (camera) position      F  the spot's direction (the lab: the camera front)
 *
 * The functions are static inline, like GLSL's built-ins: the fragment
 * stage (src/renderer/fragment.c) compiles them into its pixel loop, and
 * tests call each term alone.
 *
 * luz_shade_fragment() adds the six terms and multiplies by the object's
 * colour C and the texel T, as the report's GLSL does:
 *
 *   colour = (ambient + diffuse + specular + point + spot + directional) * C * T
 *
 * and luz_shade_output() turns that colour into what is written, with the
 * frame's exposure and tone map (SCENE.md, "Output").
 */
#ifndef LUZ_SHADE_H
#define LUZ_SHADE_H

#include <stdbool.h>

#include "luz/api.h"
#include "luz/bug.h"
#include "luz/frame.h"
#include "luz/vecmath.h"

/* Where the report's printed code differs from its intent, SCENE.md (and so
 * this file) follows the intent: the diffuse light vector points towards
 * the headlight, the directional term is clamped at 0, and the spot
 * distance is divided by its reach once.
 *
 *   ambient     = A.a * A.rgb
 *   diffuse     = max(dot(N, L), 0) * D.rgb * D.a,      L = normalize(E - P)
 *   specular    = S.a * pow(max(dot(V, R), 0), shininess) * S.rgb,
 *                 V = L (the headlight), R = reflect(-L, N)
 *   point       = max(dot(N, normalize(Ppoint - P)), 0) * Pt.rgb * Pt.a
 *   spot        = Sp.rgb * f_dir * f_dist
 *   directional = max(dot(N, normalize(-d)), 0) * Dl.rgb * Dl.a
 */

/* GLSL's max() for the clamps below. fmaxf would do, but it treats NaN
 * specially and compilers turn it into a library call; this is one
 * instruction, and a NaN dot product still gives 0. */
static inline float luz_shade_max(float a, float b)
{
    return a > b ? a : b;
}

/* pow(x, s) with C's meaning (pow(0, 0) = 1). Shininess is nearly always a
 * whole number (32 by default), and then repeated squaring is exact to a
 * few ulps and several times faster than powf: for s = 32, five multiplies. */
static inline bool luz_shade_power_is_whole(float s)
{
    return s >= 0.0f && s <= 1024.0f && s == (float)(int)s;
}

static inline float luz_shade_power(float x, float s)
{
    if (luz_shade_power_is_whole(s)) {
        float result = 1.0f, square = x;
        for (unsigned e = (unsigned)s; e != 0; e >>= 1) {
            if (e & 1u) result *= square;
            square *= square;
        }
        return result;
    }
    return powf(x, s);
}

static inline luz_vec3 luz_shade_ambient(const luz_light *ambient)
{
    return luz_vec3_scale(ambient->colour, ambient->strength);
}

static inline luz_vec3 luz_shade_diffuse(luz_vec3 normal, luz_vec3 position,
                                         luz_vec3 camera_position,
                           const luz_light *diffuse)
{
    luz_vec3 to_light = luz_vec3_normalize(luz_vec3_sub(camera_position, position));
    float lambert = luz_shade_max(luz_vec3_dot(normal, to_light), 0.0f);
    return luz_vec3_scale(diffuse->colour, lambert * diffuse->strength);
}

static inline luz_vec3 luz_shade_specular(luz_vec3 normal, luz_vec3 position,
                                          luz_vec3 camera_position,
                            const luz_light *specular, float shininess)
{
    /* The light is the headlight, so the light and view vectors coincide. */
    luz_vec3 to_light = luz_vec3_normalize(luz_vec3_sub(camera_position, position));
    luz_vec3 to_viewer = to_light;
    /* reflect(-L, N) = -L + 2 dot(N, L) N */
    luz_vec3 reflected = luz_vec3_sub(
        luz_vec3_scale(normal, 2.0f * luz_vec3_dot(normal, to_light)), to_light);
    float highlight = luz_shade_power(luz_shade_max(luz_vec3_dot(to_viewer, reflected), 0.0f), shininess);
    return luz_vec3_scale(specular->colour, specular->strength * highlight);
}

static inline luz_vec3 luz_shade_point(luz_vec3 normal, luz_vec3 position, luz_vec3 light_position,
                         const luz_light *point)
{
    luz_vec3 to_light = luz_vec3_normalize(luz_vec3_sub(light_position, position));
    float lambert = luz_shade_max(luz_vec3_dot(normal, to_light), 0.0f);
    return luz_vec3_scale(point->colour, lambert * point->strength);
}

static inline luz_vec3 luz_shade_spot(luz_vec3 position, luz_vec3 camera_position, luz_vec3 camera_front,
                        const luz_light *spot, float cos_inner, float cos_outer, float reach)
{
    /* Direction: the cosine of the angle between the spot's axis and the
     * ray to the fragment, smoothed between the outer and inner cones. */
    luz_vec3 ray = luz_vec3_normalize(luz_vec3_sub(position, camera_position));
    float c = luz_vec3_dot(ray, luz_vec3_normalize(camera_front));
    float f_direction;
    if (c > cos_inner) {
        f_direction = 1.0f;
    } else if (c > cos_outer) {
        float s = sqrtf((c - cos_outer) / (cos_inner - cos_outer));
        f_direction = s * s * (3.0f - 2.0f * s);
    } else {
        f_direction = 0.0f;
    }

    /* Distance: a window that reaches 0 at `reach`, times an inverse-square
     * style fall-off; the strength enters squared, as in the report. */
    float distance = luz_vec3_length(luz_vec3_sub(camera_position, position)) / reach;
    float distance2 = distance * distance;
    float window = luz_shade_max(1.0f - distance2 * distance2, 0.0f);
    float f_distance = window * window * (spot->strength * spot->strength) / (distance2 + 1.0f);

    return luz_vec3_scale(spot->colour, f_direction * f_distance);
}

static inline luz_vec3 luz_shade_directional(luz_vec3 normal, luz_vec3 direction,
                               const luz_light *directional)
{
    luz_vec3 to_sun = luz_vec3_normalize(luz_vec3_scale(direction, -1.0f));
    float lambert = luz_shade_max(luz_vec3_dot(normal, to_sun), 0.0f);
    return luz_vec3_scale(directional->colour, lambert * directional->strength);
}

/* What the six terms read that is the same for every fragment of a frame:
 * the eye, the lights, and the spot's cone as cosines, worked out once. */
typedef struct luz_shade_uniforms {
    luz_vec3 eye;          /* E */
    luz_lights lights;
    float spot_cos_inner;  /* cos(lights.spot_inner_degrees) */
    float spot_cos_outer;
} luz_shade_uniforms;

LUZ_API luz_shade_uniforms luz_shade_uniforms_of(luz_vec3 eye, const luz_lights *lights);

/* The six terms at world position P with normal N (normalised here, as
 * SCENE.md asks after interpolation), each into terms[] as its function
 * above returns it, in luz_term's order; returns their sum, added in that
 * order. The fragment stage calls it through luz_shade_lighting; the pixel
 * probe (luz/probe.h) keeps the terms. */
static inline luz_vec3 luz_shade_terms(const luz_shade_uniforms *uniforms, luz_vec3 position,
                                       luz_vec3 normal, luz_vec3 terms[LUZ_TERM_COUNT])
{
    const luz_lights *lights = &uniforms->lights;
    const luz_vec3 n = luz_vec3_normalize(normal);
    const luz_vec3 eye = uniforms->eye;

    terms[LUZ_TERM_AMBIENT] = luz_shade_ambient(&lights->ambient);
    terms[LUZ_TERM_DIFFUSE] = luz_shade_diffuse(n, position, eye, &lights->diffuse);
    terms[LUZ_TERM_SPECULAR] = luz_shade_specular(n, position, eye, &lights->specular,
                                                  lights->shininess);
    terms[LUZ_TERM_POINT] = luz_shade_point(n, position, lights->point_position, &lights->point);
    terms[LUZ_TERM_SPOT] = luz_shade_spot(position, eye, lights->spot_direction, &lights->spot,
                                          uniforms->spot_cos_inner, uniforms->spot_cos_outer,
                                          lights->spot_reach);
    terms[LUZ_TERM_DIRECTIONAL] = luz_shade_directional(n, lights->directional_direction,
                                                        &lights->directional);
    luz_vec3 light = terms[LUZ_TERM_AMBIENT];
    for (int term = LUZ_TERM_DIFFUSE; term < LUZ_TERM_COUNT; term++)
        light = luz_vec3_add(light, terms[term]);
    return light;
}

/* ---- the numbers in between (the pixel probe, and luz/bug.h) ------------ */

/* What the six terms compute on the way, in SCENE.md's names: the pixel
 * probe's intermediates. Every dot product is the one the term takes
 * before its max(..., 0). */
typedef struct luz_shade_steps {
    luz_vec3 normal;        /* N as the terms read it: re-normalised (as
                               interpolated with normal-not-normalised) */
    float normal_length;    /* |N| */
    luz_vec3 to_light;      /* L, the diffuse term's light vector */
    float n_dot_l;          /* dot(N, L) */
    luz_vec3 to_viewer;     /* V = normalize(E - P) */
    luz_vec3 reflected;     /* R = reflect(-L, N) = -L + 2 dot(N, L) N, with
                               L towards the headlight */
    float v_dot_r;          /* dot(V, R); dot(N, H) with specular-half-vector */
    luz_vec3 to_point;      /* Lp = normalize(Ppoint - P) */
    float n_dot_lp;         /* dot(N, Lp) */
    float spot_cos;         /* c = dot(normalize(P - E), normalize(F)) */
    float spot_cos_inner, spot_cos_outer;   /* ci, co */
    float f_dir;            /* the spot's cone factor */
    float dn;               /* length(E - P) / reach */
    float f_win;            /* max(1 - dn^4, 0)^2 */
    float f_dist;           /* f_win * Sp.a^2 / (dn^2 + 1) */
    luz_vec3 to_sun;        /* normalize(-d) */
    float n_dot_sun;        /* dot(N, normalize(-d)) */
} luz_shade_steps;

/* The six terms as luz_shade_terms gives them (bit for bit with
 * LUZ_BUG_NONE: the same operations in the same order), with the numbers
 * in between kept in *steps (which may be NULL), and with a shading bug
 * of luz/bug.h put in (diffuse-reversed, directional-unclamped,
 * spot-reach-twice, normal-not-normalised, specular-half-vector; the
 * others are not the shader's and change nothing here). Returns their
 * sum, added in luz_term's order. src/renderer/shade_steps.c. */
LUZ_API luz_vec3 luz_shade_terms_explained(const luz_shade_uniforms *uniforms, luz_bug bug,
                                           luz_vec3 position, luz_vec3 normal,
                                           luz_vec3 terms[LUZ_TERM_COUNT],
                                           luz_shade_steps *steps);

/* The sum of the six terms at world position P with normal N. */
static inline luz_vec3 luz_shade_lighting(const luz_shade_uniforms *uniforms, luz_vec3 position,
                                          luz_vec3 normal)
{
    luz_vec3 terms[LUZ_TERM_COUNT];
    return luz_shade_terms(uniforms, position, normal, terms);
}

/* colour = light * C * T, multiplied in that order. */
static inline luz_vec3 luz_shade_colour(luz_vec3 light, luz_vec3 object_colour, luz_vec3 texel)
{
    return luz_vec3_mul(luz_vec3_mul(light, object_colour), texel);
}

static inline luz_vec3 luz_shade_fragment(const luz_shade_uniforms *uniforms, luz_vec3 position,
                                          luz_vec3 normal, luz_vec3 object_colour, luz_vec3 texel)
{
    return luz_shade_colour(luz_shade_lighting(uniforms, position, normal), object_colour,
                            texel);
}

/* ---- output: exposure and tone map (SCENE.md, "Output") ------------------ */

/* GLSL's min() for the tone map, as luz_shade_max: a NaN b gives b. */
static inline float luz_shade_min(float a, float b)
{
    return a < b ? a : b;
}

/* The Khronos PBR Neutral tone mapper, on a linear colour, step by step as
 * SCENE.md (and Khronos's GLSL) write it:
 *
 *   x        = min(r, g, b)
 *   offset   = x < 0.08 ? x - 6.25 x^2 : 0.04
 *   c        = c - offset
 *   peak     = max(r, g, b) of the new c
 *   if peak < 0.76: done
 *   d        = 0.24
 *   new_peak = 1 - d^2 / (peak + d - 0.76)
 *   c        = c * new_peak / peak
 *   g        = 1 - 1 / (0.15 (peak - new_peak) + 1)
 *   c        = mix(c, new_peak (1, 1, 1), g)
 *
 * Below 0.76 the colour is only shifted down by the offset (a little
 * darker, slightly more contrast near black); above, the peak channel is
 * compressed towards 1 (1 - d^2 / (peak - 0.52): 0.76 stays 0.76, no input
 * reaches 1) and the colour is moved towards grey by g, as film does with
 * very bright light. fragment_packet.c computes the same operations in
 * the same order, lane by lane. */
#define LUZ_TONE_MAP_START_COMPRESSION 0.76f
#define LUZ_TONE_MAP_DESATURATION 0.15f

static inline luz_vec3 luz_tone_map_neutral(luz_vec3 c)
{
    const float x = luz_shade_min(c.x, luz_shade_min(c.y, c.z));
    const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    c = (luz_vec3){c.x - offset, c.y - offset, c.z - offset};

    const float peak = luz_shade_max(c.x, luz_shade_max(c.y, c.z));
    if (peak < LUZ_TONE_MAP_START_COMPRESSION) return c;

    const float d = 1.0f - LUZ_TONE_MAP_START_COMPRESSION;
    const float new_peak = 1.0f - d * d / (peak + d - LUZ_TONE_MAP_START_COMPRESSION);
    const float ratio = new_peak / peak;
    c = (luz_vec3){c.x * ratio, c.y * ratio, c.z * ratio};

    const float g = 1.0f - 1.0f / (LUZ_TONE_MAP_DESATURATION * (peak - new_peak) + 1.0f);
    /* mix(a, b, g) = a (1 - g) + b g, as GLSL defines it */
    return (luz_vec3){c.x * (1.0f - g) + new_peak * g, c.y * (1.0f - g) + new_peak * g,
                      c.z * (1.0f - g) + new_peak * g};
}

/* The colour a lit fragment writes, before luz_colour_to_byte: the
 * equations' colour times 2^EV (exposure_scale, worked out once a frame
 * with exp2f), then the tone map. Clamp at EV 0 is the colour itself: the
 * fragment stages skip this call then, so the report's images stay the
 * same to the bit. */
static inline luz_vec3 luz_shade_output(luz_vec3 colour, float exposure_scale,
                                        luz_tone_map tone_map)
{
    colour = (luz_vec3){colour.x * exposure_scale, colour.y * exposure_scale,
                        colour.z * exposure_scale};
    return tone_map == LUZ_TONE_MAP_NEUTRAL ? luz_tone_map_neutral(colour) : colour;
}

#endif
