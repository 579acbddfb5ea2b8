/*
 * fragment_packet.c: the fast fragment stage. The same job as fragment.c
 * (shade every visible pixel once, from the visibility buffer), done for
 * packets of consecutive pixels of a row: 4 with SSE2, 8 with AVX2, 16
 * with AVX-512, as many as a register holds floats.
 *
 * In:  the visibility buffer, the set-up triangles, the frame.
 * Out: the colour buffer, as fragment.c writes it: every pixel, the
 *      background's included, in the framebuffer's channel order.
 *
 * fragment.c stays the reference: it reads as the equations do, one pixel
 * at a time. This file computes the same equations, in the same order, on
 * a packet at once:
 *
 *   - Structure of arrays. A packet holds each quantity (u, the position's
 *     x, the normal's z, ...) of its pixels in one vector, a GCC / clang
 *     vector extension (`vector_size`), so each operation below is one
 *     SIMD instruction.
 *   - Triangles. A packet's pixels may belong to different triangles, or to
 *     none (the background). Most packets hold one triangle: shaded in one
 *     pass with its planes, a lane mask keeping its lanes. The pixels of
 *     any other packet go to their draw's queue, shaded a full register
 *     at a time with each lane's own triangle's planes (the band's rows,
 *     below). The packet starts as the clear colour in every lane, so the
 *     lanes no triangle claims are the background, and it is stored whole:
 *     colour is not cleared before this pass, and one store of a full
 *     packet is cheaper than picking out its background lanes.
 *   - Uniforms. What is the same for every pixel (normalize(F),
 *     normalize(-d), which terms are on, where the channel order puts red
 *     and blue, ...) is worked out once per band, by the very operations
 *     shade.h applies per pixel.
 *   - Textures. Texel addresses, bilinear weights and blends are vectors;
 *     the texel fetches are one load per lane (a "gather"; with AVX-512
 *     and AVX2 one 64-bit load per lane for a row's two texels), sent
 *     out for both of trilinear's levels before the lighting, and
 *     filtered after it, so that the texels arrive while the lighting is
 *     computed.
 *   - Instruction sets. src/renderer/meson.build compiles this file once
 *     for the build's target (baseline: SSE2 on x86-64, NEON on aarch64),
 *     once with one lane (the scalar variant), and once each with -mavx2
 *     and -mavx512*; cpu.c picks one for the renderer (the widest the CPU
 *     has, or LUZ_ISA's), so one binary runs everywhere. The variants are
 *     separate compilations, not target attributes on one function,
 *     because a vector must be as wide as the registers: GCC 12 compiles
 *     32-byte vector comparisons for SSE2 one element at a time, which
 *     made an 8-lane baseline no faster than the reference. GCC 12.2
 *     miscompiles the scalar variant's one-lane masks at -O2 (a mask
 *     folded to 0: trilinear's second level lost), so meson.build
 *     compiles it with -fno-tree-vrp (docs/platforms.md, "A GCC bug in
 *     one-lane vectors").
 *
 * Agreement with the reference. Each lane performs the IEEE operations
 * that fragment.c, texture.c and shade.h perform for its pixel, in the same
 * order, and SIMD operations round exactly as scalar ones do; the build
 * passes -ffp-contract=off (meson.build) so that neither path fuses a
 * multiply and an add behind our back. So interpolation, texel addressing,
 * filtering, lighting and the conversion to bytes give the reference's
 * bits. The one exception is the logarithm of the level of detail, a
 * polynomial here (log2_above_one) instead of libm's log2f: the two agree
 * to an ulp or so, and trilinear filtering is continuous in lambda, so the
 * colour moves by about 1e-7. tests/test_fragment_packet.c measures it.
 * A pixel's colour depends on that pixel alone, never on where a packet,
 * a band or a thread's share begins.
 *
 * What this file is not: a second set of equations. A change to the
 * shading goes into shade.h (and fragment.c, texture.c) first, then here,
 * and the test holds the two together.
 */
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "renderer/pipeline.h"
#include "renderer/transpose8.h"
#include "luz/shade.h"
#include "luz/texture.h"

/* The variant this compilation builds (see src/renderer/meson.build), and
 * its lanes: as many floats as a register holds, or one (the scalar
 * variant: the same code, no vector instruction). */
#if defined(LUZ_PACKET_AVX512)
#if !defined(__AVX512F__) || !defined(__AVX512DQ__)
#error "the AVX-512 variant is compiled with -mavx512f -mavx512dq ..."
#endif
#define LANES 16
#define VARIANT_ROWS luz_fragment_packet_rows_avx512
#define VARIANT_LIST luz_fragment_packet_list_avx512
#elif defined(LUZ_PACKET_AVX2)
#if !defined(__AVX2__)
#error "the AVX2 variant is compiled with -mavx2 -mfma"
#endif
#define LANES 8
#define VARIANT_ROWS luz_fragment_packet_rows_avx2
#define VARIANT_LIST luz_fragment_packet_list_avx2
#elif defined(LUZ_PACKET_SCALAR)
#define LANES 1
#define VARIANT_ROWS luz_fragment_packet_rows_scalar
#define VARIANT_LIST luz_fragment_packet_list_scalar
#else
#define LANES 4
#define VARIANT_ROWS luz_fragment_packet_rows_baseline
#define VARIANT_LIST luz_fragment_packet_list_baseline
#define BASELINE_VARIANT 1
#endif

#define ALL_LANES ((1u << LANES) - 1u)

/* The helpers are small and called from the packet loop alone: inlined,
 * their vectors stay in registers. */
#define INLINE static inline __attribute__((always_inline))

typedef float vfloat __attribute__((vector_size(LANES * sizeof(float))));
typedef int32_t vint __attribute__((vector_size(LANES * sizeof(int32_t))));
typedef uint32_t vuint __attribute__((vector_size(LANES * sizeof(uint32_t))));

typedef struct vvec3 {
    vfloat x, y, z;
} vvec3;

/* ---- lane helpers ------------------------------------------------------ */

/* A comparison gives, per lane, all ones (true) or all zeros (false). */
INLINE vfloat select_float(vint mask, vfloat if_true, vfloat if_false)
{
    return (vfloat)(((vint)if_true & mask) | ((vint)if_false & ~mask));
}

INLINE vint select_int(vint mask, vint if_true, vint if_false)
{
    return (if_true & mask) | (if_false & ~mask);
}

/* One bit per lane whose mask is true (movmskps). */
INLINE unsigned lane_bits(vint mask)
{
#if LANES == 16 && defined(__AVX512DQ__)
    return (unsigned)_mm512_movepi32_mask((__m512i)mask);
#elif LANES == 8 && defined(__AVX__)
    return (unsigned)_mm256_movemask_ps((__m256)mask);
#elif LANES == 4 && defined(__SSE2__)
    return (unsigned)_mm_movemask_ps((__m128)mask);
#else
    unsigned bits = 0;
    for (int i = 0; i < LANES; i++)
        bits |= (unsigned)(mask[i] != 0) << i;
    return bits;
#endif
}

INLINE vfloat splat(float value)
{
    return value - (vfloat){0};   /* x - 0 is x, even for x = -0 */
}

INLINE vint splat_int(int32_t value)
{
    return (vint){0} + value;
}

INLINE vfloat to_float(vint value)
{
    return __builtin_convertvector(value, vfloat);
}

/* Truncation towards 0, as a C cast; every caller makes sure each lane is
 * within int range first. */
INLINE vint to_int(vfloat value)
{
    return __builtin_convertvector(value, vint);
}

/* sqrtps: correctly rounded, as sqrtf. */
INLINE vfloat sqrt_lanes(vfloat a)
{
#if LANES == 16 && defined(__AVX512F__)
    return (vfloat)_mm512_sqrt_ps((__m512)a);
#elif LANES == 8 && defined(__AVX__)
    return (vfloat)_mm256_sqrt_ps((__m256)a);
#elif LANES == 4 && defined(__SSE2__)
    return (vfloat)_mm_sqrt_ps((__m128)a);
#else
    vfloat root;
    for (int i = 0; i < LANES; i++)
        root[i] = sqrtf(a[i]);
    return root;
#endif
}

/* shade.h's max_float(a, 0): NaN gives 0. */
INLINE vfloat max_zero(vfloat a)
{
    return select_float(a > 0.0f, a, splat(0.0f));
}

INLINE vfloat dot3(vvec3 a, vvec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

INLINE vfloat dot3_uniform(vvec3 a, luz_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

/* luz_vec3_normalize, which also hands back the length: the zero vector
 * stays zero. */
INLINE vvec3 normalize3(vvec3 a, vfloat *length_out)
{
    vfloat length = sqrt_lanes(dot3(a, a));
    vfloat inverse = 1.0f / length;
    vint positive = length > 0.0f;
    *length_out = length;
    return (vvec3){
        select_float(positive, a.x * inverse, a.x),
        select_float(positive, a.y * inverse, a.y),
        select_float(positive, a.z * inverse, a.z),
    };
}

/* ---- the uniforms of a band ------------------------------------------- */

/* Where byte c of four bytes in memory lands in a uint32_t that reads or
 * writes them at once: an RGBA8 texel's channel c, or byte c of a pixel of
 * the framebuffer. */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define CHANNEL_SHIFT(c) (24 - 8 * (c))
#else
#define CHANNEL_SHIFT(c) (8 * (c))
#endif

/* What every pixel of the band shares, worked out once, each with the
 * operations shade.h applies per pixel, so that the bits are the same. */
typedef struct packet_uniforms {
    luz_vec3 eye;               /* E */
    luz_vec3 point_position;
    luz_vec3 spot_axis;         /* normalize(F) */
    luz_vec3 to_sun;            /* normalize(-d) */
    luz_vec3 ambient;           /* A.a * A.rgb */
    luz_light diffuse, specular, point, spot, directional;
    /* A term whose strength is 0 is exactly 0 (SCENE.md), and adding 0
     * changes no sum: such terms are skipped. */
    bool diffuse_on, specular_on, point_on, spot_on, directional_on;
    bool shininess_whole;       /* luz_shade_power's repeated squaring */
    unsigned shininess_exponent;
    float shininess;
    float spot_strength_squared;
    float cos_inner, cos_outer, reach;
    /* cos_inner - cos_outer, the smooth step's divisor; 1 when the two
     * cones are one (every lane computes the step, and the lanes that
     * would divide by zero are the ones that never use it: luz_shade_spot
     * divides only strictly between the cones). */
    float cone_width;
    /* The framebuffer's channel order, as the shifts that put red and blue
     * into a pixel's uint32_t (CHANNEL_SHIFT), and the clear colour packed
     * in it. */
    unsigned red_shift, blue_shift;
    uint32_t background;
    /* luz_shade_output's settings; skipped when they leave the colour as
     * it is (clamp at EV 0). */
    bool output_is_identity;
    bool tone_map_neutral;
    float exposure_scale;
} packet_uniforms;

static packet_uniforms packet_uniforms_of(const luz_uniforms *uniforms, luz_channel_order order)
{
    const luz_lights *lights = &uniforms->shade.lights;
    packet_uniforms u = {
        .eye = uniforms->shade.eye,
        .point_position = lights->point_position,
        .spot_axis = luz_vec3_normalize(lights->spot_direction),
        .to_sun = luz_vec3_normalize(luz_vec3_scale(lights->directional_direction, -1.0f)),
        .ambient = luz_shade_ambient(&lights->ambient),
        .diffuse = lights->diffuse,
        .specular = lights->specular,
        .point = lights->point,
        .spot = lights->spot,
        .directional = lights->directional,
        .diffuse_on = lights->diffuse.strength != 0.0f,
        .specular_on = lights->specular.strength != 0.0f,
        .point_on = lights->point.strength != 0.0f,
        .spot_on = lights->spot.strength != 0.0f,
        .directional_on = lights->directional.strength != 0.0f,
        .shininess = lights->shininess,
        .spot_strength_squared = lights->spot.strength * lights->spot.strength,
        .cos_inner = uniforms->shade.spot_cos_inner,
        .cos_outer = uniforms->shade.spot_cos_outer,
        .reach = lights->spot_reach,
        .output_is_identity = uniforms->output_is_identity,
        .tone_map_neutral = uniforms->tone_map == LUZ_TONE_MAP_NEUTRAL,
        .exposure_scale = uniforms->exposure_scale,
    };
    u.cone_width = u.cos_inner - u.cos_outer != 0.0f ? u.cos_inner - u.cos_outer : 1.0f;
    const float s = lights->shininess;
    u.shininess_whole = luz_shade_power_is_whole(s);
    u.shininess_exponent = u.shininess_whole ? (unsigned)s : 0;
    const luz_pixel_layout layout = luz_pixel_layout_of(order);
    u.red_shift = CHANNEL_SHIFT(layout.red);
    u.blue_shift = CHANNEL_SHIFT(layout.blue);
    uint8_t background[4];
    luz_pixel_write(background, layout, uniforms->clear_colour);
    memcpy(&u.background, background, sizeof u.background);
    return u;
}

/* ---- the fragment shader, a packet at a time --------------------------- */

/* luz_shade_power: repeated squaring for a whole exponent, else powf. */
INLINE vfloat power(vfloat x, const packet_uniforms *u)
{
    if (u->shininess_whole) {
        vfloat result = splat(1.0f), square = x;
        for (unsigned e = u->shininess_exponent; e != 0; e >>= 1) {
            if (e & 1u) result *= square;
            square *= square;
        }
        return result;
    }
    vfloat result;
    for (int i = 0; i < LANES; i++)
        result[i] = powf(x[i], u->shininess);
    return result;
}

INLINE vvec3 add_light(vvec3 sum, luz_vec3 colour, vfloat factor)
{
    return (vvec3){sum.x + colour.x * factor, sum.y + colour.y * factor,
                   sum.z + colour.z * factor};
}

/* luz_shade_spot's factor f_dir * f_dist for the lanes, given the ray's
 * cosine c and the distance over the reach. */
INLINE vfloat spot_factor(const packet_uniforms *u, vfloat c, vfloat distance,
                          vfloat window_base, unsigned mine_bits)
{
    /* Inside the inner cone f_dir is 1 whatever the smooth step gives, so
     * a pass whose lanes are all inside leaves the step out. */
    vfloat f_direction = splat(1.0f);
    if ((lane_bits(c > u->cos_inner) & mine_bits) != mine_bits) {
        const vfloat s = sqrt_lanes((c - u->cos_outer) / u->cone_width);
        const vfloat smooth = s * s * (3.0f - 2.0f * s);
        f_direction = select_float(c > u->cos_inner, splat(1.0f),
                                   select_float(c > u->cos_outer, smooth, splat(0.0f)));
    }
    const vfloat distance2 = distance * distance;
    const vfloat window = max_zero(window_base);
    const vfloat f_distance = window * window * u->spot_strength_squared / (distance2 + 1.0f);
    return f_direction * f_distance;
}

/* luz_shade_lighting: the six terms, summed in shade.h's order, for the
 * lanes of mine_bits (the others are computed or not, and never used). */
INLINE vvec3 shade_lighting(const packet_uniforms *u, vvec3 position, vvec3 normal,
                            unsigned mine_bits)
{
    vfloat unused_length;
    const vvec3 n = normalize3(normal, &unused_length);

    /* The headlight's vector, L = V = normalize(E - P); its length is
     * also the spot's distance, and P - E is -(E - P) exactly, so the
     * spot's ray is -L and its cosine -dot(L, F). */
    vfloat eye_distance;
    const vvec3 to_eye = normalize3((vvec3){u->eye.x - position.x, u->eye.y - position.y,
                                            u->eye.z - position.z},
                                    &eye_distance);
    const vfloat n_dot_l = dot3(n, to_eye);

    vvec3 light = {splat(u->ambient.x), splat(u->ambient.y), splat(u->ambient.z)};
    if (u->diffuse_on)
        light = add_light(light, u->diffuse.colour, max_zero(n_dot_l) * u->diffuse.strength);
    if (u->specular_on) {
        /* reflect(-L, N) = -L + 2 dot(N, L) N */
        const vfloat twice = 2.0f * n_dot_l;
        const vvec3 reflected = {n.x * twice - to_eye.x, n.y * twice - to_eye.y,
                                 n.z * twice - to_eye.z};
        const vfloat highlight = power(max_zero(dot3(to_eye, reflected)), u);
        light = add_light(light, u->specular.colour, u->specular.strength * highlight);
    }
    if (u->point_on) {
        vfloat unused;
        const vvec3 to_point = normalize3(
            (vvec3){u->point_position.x - position.x, u->point_position.y - position.y,
                    u->point_position.z - position.z},
            &unused);
        light = add_light(light, u->point.colour, max_zero(dot3(n, to_point)) * u->point.strength);
    }
    if (u->spot_on) {
        const vvec3 ray = {-to_eye.x, -to_eye.y, -to_eye.z};
        const vfloat c = dot3_uniform(ray, u->spot_axis);
        const vfloat distance = eye_distance / u->reach;
        const vfloat distance2 = distance * distance;
        const vfloat window_base = 1.0f - distance2 * distance2;
        /* The spot reaches a lane only inside its outer cone (c > cos
         * outer) and nearer than its reach (1 - dn^4 > 0). A lane out of
         * either, with c and dn not NaN, has f_dir = +0 or f_win = +0
         * while the other factor is finite and not negative (f_dir in
         * [0, 1]; f_dist's numerator at most Sp.a^2 over a denominator of
         * at least 1), so its term is exactly +0 and adding it changes no
         * sum (each is +0 or above, never -0, unless a light's colour is
         * -0, and a -0 that stays gives the same byte as +0). A pass none
         * of whose lanes the spot reaches skips the term, as a light of
         * strength 0 does. Most of the frame is outside the cone (about a
         * quarter of the screen is within it at the default 17.5 degrees)
         * or, with many cubes, beyond the reach. NaN compares false, so a
         * NaN lane keeps the term, and its NaN, as the reference. */
        const vint unreached = (c <= u->cos_outer) | (window_base <= 0.0f);
        if ((lane_bits(unreached) & mine_bits) != mine_bits)
            light = add_light(light, u->spot.colour,
                              spot_factor(u, c, distance, window_base, mine_bits));
    }
    if (u->directional_on)
        light = add_light(light, u->directional.colour,
                          max_zero(dot3_uniform(n, u->to_sun)) * u->directional.strength);
    return light;
}

/* ---- output: exposure and tone map ---------------------------------------- */

/* shade.h's luz_shade_min and luz_shade_max: a NaN a gives b. */
INLINE vfloat min_lanes(vfloat a, vfloat b)
{
    return select_float(a < b, a, b);
}

INLINE vfloat max_lanes(vfloat a, vfloat b)
{
    return select_float(a > b, a, b);
}

/* luz_tone_map_neutral, every lane through every step; the lanes whose
 * peak is below the start of compression keep the offset colour, as the
 * scalar form returns early. */
INLINE vvec3 tone_map_neutral(vvec3 c)
{
    const vfloat x = min_lanes(c.x, min_lanes(c.y, c.z));
    const vfloat offset = select_float(x < 0.08f, x - 6.25f * x * x, splat(0.04f));
    c = (vvec3){c.x - offset, c.y - offset, c.z - offset};

    const vfloat peak = max_lanes(c.x, max_lanes(c.y, c.z));
    const vint below = peak < LUZ_TONE_MAP_START_COMPRESSION;
    /* A lane that keeps c divides by 1 instead of a peak that may be 0. */
    const vfloat compressed_peak = select_float(below, splat(1.0f), peak);
    const float d = 1.0f - LUZ_TONE_MAP_START_COMPRESSION;
    const vfloat new_peak =
        1.0f - d * d / (compressed_peak + d - LUZ_TONE_MAP_START_COMPRESSION);
    const vfloat ratio = new_peak / compressed_peak;
    const vfloat g = 1.0f - 1.0f / (LUZ_TONE_MAP_DESATURATION *
                                    (compressed_peak - new_peak) + 1.0f);
    const vfloat keep = 1.0f - g, towards = new_peak * g;
    return (vvec3){
        select_float(below, c.x, c.x * ratio * keep + towards),
        select_float(below, c.y, c.y * ratio * keep + towards),
        select_float(below, c.z, c.z * ratio * keep + towards),
    };
}

/* luz_shade_output: times 2^EV, then the tone map. */
INLINE vvec3 output_lanes(vvec3 colour, const packet_uniforms *u)
{
    const float scale = u->exposure_scale;
    colour = (vvec3){colour.x * scale, colour.y * scale, colour.z * scale};
    return u->tone_map_neutral ? tone_map_neutral(colour) : colour;
}

/* ---- textures ------------------------------------------------------------ */

/* One texel per lane; index counts texels from the start of level 0. */
INLINE vuint gather(const uint8_t *texels, vint index)
{
#if LANES == 16 && defined(__AVX512F__)
    return (vuint)_mm512_i32gather_epi32((__m512i)index, (const void *)texels, 4);
#elif LANES == 8 && defined(__AVX2__)
    return (vuint)_mm256_i32gather_epi32((const int *)(const void *)texels, (__m256i)index, 4);
#else
    vuint out;
    for (int i = 0; i < LANES; i++) {
        uint32_t texel;
        memcpy(&texel, texels + (size_t)(uint32_t)index[i] * 4, sizeof texel);
        out[i] = texel;
    }
    return out;
#endif
}

/* A hint, not a load: the texel that the packet two steps further along
 * the row will probably want, extrapolated from this packet's first and
 * last lanes, so that its cache line is on its way while this one is
 * shaded. Texel fetches that miss the cache are what the packets wait on
 * most, and the hint wins back part of that wait (docs/performance.md,
 * "Measured in the code"). */
INLINE void prefetch_ahead(const uint8_t *texels, vint index, int32_t end)
{
    const int32_t ahead = 3 * index[LANES - 1] - 2 * index[0];
    if (ahead >= 0 && ahead < end) __builtin_prefetch(texels + (size_t)ahead * 4);
}

/* Texels index and index + 1 of each lane, as first and second: one
 * 64-bit load a lane, half the lanes a gather, then the pairs' halves
 * sorted into two registers. */
#if LANES == 16 && defined(__AVX512F__)
INLINE void gather_pairs(const uint8_t *texels, vint index, vuint *first, vuint *second)
{
    const __m512i low = _mm512_i32gather_epi64(_mm512_castsi512_si256((__m512i)index),
                                               (const void *)texels, 4);
    const __m512i high = _mm512_i32gather_epi64(_mm512_extracti32x8_epi32((__m512i)index, 1),
                                                (const void *)texels, 4);
    const __m512i even =
        _mm512_set_epi32(30, 28, 26, 24, 22, 20, 18, 16, 14, 12, 10, 8, 6, 4, 2, 0);
    const __m512i odd =
        _mm512_set_epi32(31, 29, 27, 25, 23, 21, 19, 17, 15, 13, 11, 9, 7, 5, 3, 1);
    *first = (vuint)_mm512_permutex2var_epi32(low, even, high);
    *second = (vuint)_mm512_permutex2var_epi32(low, odd, high);
}
#elif LANES == 8 && defined(__AVX2__)
INLINE void gather_pairs(const uint8_t *texels, vint index, vuint *first, vuint *second)
{
    const __m256i low = _mm256_i32gather_epi64((const long long *)(const void *)texels,
                                               _mm256_castsi256_si128((__m256i)index), 4);
    const __m256i high = _mm256_i32gather_epi64((const long long *)(const void *)texels,
                                                _mm256_extracti128_si256((__m256i)index, 1), 4);
    /* low holds a0 b0 a1 b1 | a2 b2 a3 b3, high a4 b4 ... b7: the shuffle
     * gives a0 a1 a4 a5 | a2 a3 a6 a7, and the permute swaps its middle
     * 64-bit quarters. */
    const __m256 a = _mm256_shuffle_ps((__m256)low, (__m256)high, _MM_SHUFFLE(2, 0, 2, 0));
    const __m256 b = _mm256_shuffle_ps((__m256)low, (__m256)high, _MM_SHUFFLE(3, 1, 3, 1));
    *first = (vuint)_mm256_permute4x64_epi64((__m256i)a, _MM_SHUFFLE(3, 1, 2, 0));
    *second = (vuint)_mm256_permute4x64_epi64((__m256i)b, _MM_SHUFFLE(3, 1, 2, 0));
}
#endif

INLINE vfloat channel(vuint texels, int c)
{
    return to_float((vint)((texels >> CHANNEL_SHIFT(c)) & 0xffu));
}

/* luz_texture_repeat (pipeline.h): the fractional part, NaN and |c| >= 2^23 giving 0. */
INLINE vfloat repeat(vfloat coordinate)
{
    const vint magnitude = (vint)coordinate & 0x7fffffff;
    const vint finite = (vfloat)magnitude < 8388608.0f;
    coordinate = select_float(finite, coordinate, splat(0.0f));
    vfloat whole = to_float(to_int(coordinate));
    whole = select_float(whole > coordinate, whole - 1.0f, whole);
    const vfloat fraction = coordinate - whole;
    return select_float(fraction < 1.0f, fraction, splat(0.0f));
}

/* A mip level per lane: its size and where its texels start. */
typedef struct lane_level {
    vint width, height, first_texel;
    vfloat width_float, height_float;
} lane_level;

INLINE int first_texel_of(const luz_texture *texture, int level)
{
    return (int)((texture->levels[level].texels - texture->levels[0].texels) / 4);
}

/* The levels of the lanes: one lookup when they all agree (nearly always,
 * as lambda changes slowly across a packet), else one per lane. */
INLINE lane_level level_of(const luz_texture *texture, vint level)
{
    lane_level out;
    if (lane_bits(level == level[0]) == ALL_LANES) {
        const luz_texture_level *l = &texture->levels[level[0]];
        out.width = splat_int(l->width);
        out.height = splat_int(l->height);
        out.first_texel = splat_int(first_texel_of(texture, level[0]));
    } else {
        int width[LANES], height[LANES], first_texel[LANES];
        for (int i = 0; i < LANES; i++) {
            const luz_texture_level *l = &texture->levels[level[i]];
            width[i] = l->width;
            height[i] = l->height;
            first_texel[i] = first_texel_of(texture, level[i]);
        }
        memcpy(&out.width, width, sizeof out.width);
        memcpy(&out.height, height, sizeof out.height);
        memcpy(&out.first_texel, first_texel, sizeof out.first_texel);
    }
    out.width_float = to_float(out.width);
    out.height_float = to_float(out.height);
    return out;
}

/* texture.c's bilinear_axis: the texels whose centres surround the
 * coordinate, wrapped, and the weight of the second. */
INLINE void bilinear_axis(vfloat coordinate, vint size, vfloat size_float, vint *first,
                                 vint *second, vfloat *weight)
{
    const vfloat s = repeat(coordinate) * size_float + 0.5f;
    vint i = to_int(s);
    *weight = s - to_float(i);
    i -= 1;
    *first = select_int(i < 0, size - 1, i);
    *second = select_int(i + 1 < size, i + 1, splat_int(0));
}

/* A bilinear sample's four texels per lane, fetched, and the fractions
 * that weigh them: fetching is apart from filtering so that trilinear
 * filtering sends both levels' gathers out before it waits on either. */
typedef struct bilinear_texels {
    vuint a, b, c, d;   /* (x0, y0), (x1, y0), (x0, y1), (x1, y1) */
    vfloat fx, fy;
} bilinear_texels;

INLINE bilinear_texels fetch_bilinear(const luz_texture *texture, const lane_level *level,
                                      vfloat u, vfloat v)
{
    vint x0, x1, y0, y1;
    bilinear_texels out;
    bilinear_axis(u, level->width, level->width_float, &x0, &x1, &out.fx);
    bilinear_axis(v, level->height, level->height_float, &y0, &y1, &out.fy);

    const uint8_t *texels = texture->levels[0].texels;
    const vint row0 = level->first_texel + y0 * level->width;
    const vint row1 = level->first_texel + y1 * level->width;
    const int32_t level_end = level->first_texel[0] + level->width[0] * level->height[0];
    prefetch_ahead(texels, row0 + x0, level_end);
    prefetch_ahead(texels, row1 + x0, level_end);
#if (LANES == 16 && defined(__AVX512F__)) || (LANES == 8 && defined(__AVX2__))
    /* Unless a lane's footprint wraps around the row (x0 the last column,
     * x1 the first) or the level is one texel wide, x1 = x0 + 1 in every
     * lane: each lane's two texels of a row are next to each other, and
     * one 64-bit load a lane fetches both, half as many loads, in 64-bit
     * gathers of half the lanes each (docs/performance.md, "The lab's
     * shading, second round"). Every lane's x0 and x0 + 1 are then in its
     * level's row, whether the lane is the pass's or not. */
    if (lane_bits(x1 == x0 + 1) == ALL_LANES) {
        gather_pairs(texels, row0 + x0, &out.a, &out.b);
        gather_pairs(texels, row1 + x0, &out.c, &out.d);
        return out;
    }
#endif
    out.a = gather(texels, row0 + x0);
    out.b = gather(texels, row0 + x1);
    out.c = gather(texels, row1 + x0);
    out.d = gather(texels, row1 + x1);
    return out;
}

INLINE vvec3 filter_bilinear(const bilinear_texels *t)
{
    const vfloat fx = t->fx, fy = t->fy;
    const float scale = 1.0f / 255.0f;
    const vfloat wa = (1.0f - fx) * (1.0f - fy) * scale, wb = fx * (1.0f - fy) * scale;
    const vfloat wc = (1.0f - fx) * fy * scale, wd = fx * fy * scale;
    return (vvec3){
        wa * channel(t->a, 0) + wb * channel(t->b, 0) + wc * channel(t->c, 0) +
            wd * channel(t->d, 0),
        wa * channel(t->a, 1) + wb * channel(t->b, 1) + wc * channel(t->c, 1) +
            wd * channel(t->d, 1),
        wa * channel(t->a, 2) + wb * channel(t->b, 2) + wc * channel(t->c, 2) +
            wd * channel(t->d, 2),
    };
}

/* The nearest texel of level 0, fetched. */
INLINE vuint fetch_nearest(const luz_texture *texture, vfloat u, vfloat v)
{
    const luz_texture_level *level = &texture->levels[0];
    vint x = to_int(repeat(u) * (float)level->width);
    vint y = to_int(repeat(v) * (float)level->height);
    x = select_int(x >= level->width, splat_int(level->width - 1), x);
    y = select_int(y >= level->height, splat_int(level->height - 1), y);
    return gather(texture->levels[0].texels, y * level->width + x);
}

INLINE vvec3 filter_nearest(vuint t)
{
    const float scale = 1.0f / 255.0f;
    return (vvec3){channel(t, 0) * scale, channel(t, 1) * scale, channel(t, 2) * scale};
}

/* log2(x) for x > 1, +inf included (128). x = 2^e m with m in
 * [sqrt(1/2), sqrt(2)), and log2(m) = 2 atanh(s) / ln 2 with
 * s = (m - 1) / (m + 1), |s| < 0.172: the series to s^9 leaves an error
 * under 1e-9, below float rounding. */
INLINE vfloat log2_above_one(vfloat x)
{
    const vint bits = (vint)x;
    vint exponent = ((bits >> 23) & 0xff) - 127;
    vfloat m = (vfloat)((bits & 0x007fffff) | 0x3f800000);   /* [1, 2) */
    const vint high = m > 1.41421356f;
    m = select_float(high, m * 0.5f, m);
    exponent -= high;                                          /* true is -1 */
    const vfloat s = (m - 1.0f) / (m + 1.0f);
    const vfloat s2 = s * s;
    const float c1 = 2.88539008f;            /* 2 / ln 2 */
    const float c3 = c1 / 3.0f, c5 = c1 / 5.0f, c7 = c1 / 7.0f, c9 = c1 / 9.0f;
    const vfloat series = s * (c1 + s2 * (c3 + s2 * (c5 + s2 * (c7 + s2 * c9))));
    return to_float(exponent) + series;
}

/* luz_texture_level_of_detail, per lane. */
INLINE vfloat level_of_detail(const luz_texture *texture, vfloat du_dx, vfloat dv_dx,
                                     vfloat du_dy, vfloat dv_dy)
{
    const float width = (float)texture->levels[0].width;
    const float height = (float)texture->levels[0].height;
    const vfloat x_u = du_dx * width, x_v = dv_dx * height;
    const vfloat y_u = du_dy * width, y_v = dv_dy * height;
    const vfloat x_squared = x_u * x_u + x_v * x_v;
    const vfloat y_squared = y_u * y_u + y_v * y_v;
    const vfloat rho_squared = select_float(x_squared > y_squared, x_squared, y_squared);
    const vint minified = rho_squared > 1.0f;
    if (lane_bits(minified) == 0) return splat(0.0f);
    return select_float(minified, 0.5f * log2_above_one(rho_squared), splat(0.0f));
}

/* A texture lookup of the lanes with its texels fetched and not yet
 * filtered: the lookup sends its gathers out before the lighting, and
 * the filter takes their texels after it, so that the lighting's
 * arithmetic runs while the texels are on their way. */
typedef struct texture_fetch {
    int levels;                      /* 0: nearest (its texel in fine.a), 1 or 2 bilinear */
    bilinear_texels fine, coarse;    /* coarse: when two levels */
    vfloat blend;                    /* lambda - floor(lambda), when two levels */
    vint blended;                    /* the lanes that blend the two */
} texture_fetch;

/* luz_texture_sample_trilinear's fetches, per lane; `mine` marks the
 * lanes that count (the others may hold anything). */
INLINE void fetch_trilinear(texture_fetch *out, const luz_texture *texture, vfloat u, vfloat v,
                            vfloat lambda, vint mine)
{
    const int last = texture->level_count - 1;
    const vint positive = lambda > 0.0f;
    /* lambda <= 64 (a float's log2 over 2), so the cast is safe. */
    const vfloat level_floor = to_float(to_int(select_float(positive, lambda, splat(0.0f))));
    const vint beyond_last = level_floor >= (float)last;
    const vint blended = positive & ~beyond_last & mine;
    vint lower = select_int(beyond_last, splat_int(last), to_int(level_floor));
    /* Lanes that are not ours follow a lane that is, so that a packet
     * of one level needs one lookup. */
    int first_mine = __builtin_ctz(lane_bits(mine));
    lower = select_int(mine, lower, splat_int(lower[first_mine]));

    const lane_level fine_level = level_of(texture, lower);
    if (lane_bits(blended) == 0) {
        out->levels = 1;
        out->fine = fetch_bilinear(texture, &fine_level, u, v);
        return;
    }
    /* Both levels' gathers go out before either is filtered. */
    const lane_level coarse_level = level_of(texture, select_int(lower < last, lower + 1, lower));
    out->levels = 2;
    out->fine = fetch_bilinear(texture, &fine_level, u, v);
    out->coarse = fetch_bilinear(texture, &coarse_level, u, v);
    out->blend = lambda - level_floor;
    out->blended = blended;
}

/* The texel T of a fetch: luz_texture_sample's filter. */
INLINE vvec3 filter_texture(const texture_fetch *fetched)
{
    if (fetched->levels == 0) return filter_nearest(fetched->fine.a);
    const vvec3 fine = filter_bilinear(&fetched->fine);
    if (fetched->levels == 1) return fine;
    const vvec3 coarse = filter_bilinear(&fetched->coarse);
    const vfloat blend = fetched->blend;
    const vfloat keep = 1.0f - blend;
    const vint blended = fetched->blended;
    return (vvec3){
        select_float(blended, fine.x * keep + coarse.x * blend, fine.x),
        select_float(blended, fine.y * keep + coarse.y * blend, fine.y),
        select_float(blended, fine.z * keep + coarse.z * blend, fine.z),
    };
}

/* ---- a packet ---------------------------------------------------------- */

/* A plane per lane: each lane's own triangle's, so that one pass shades
 * a packet whose pixels belong to different triangles of one draw. */
typedef struct vplane {
    vfloat value, dx, dy;
} vplane;

INLINE vfloat plane_at(vplane plane, vfloat dx, vfloat dy)
{
    return plane.value + plane.dx * dx + plane.dy * dy;
}

/* What shading reads of the lanes' triangles: each pixel centre's offset
 * from its triangle's reference point, and the 1/w and varying planes. */
typedef struct lane_triangles {
    vfloat dx, dy;
    vplane inverse_w;
    vplane varyings[LUZ_VARYING_COUNT];
} lane_triangles;

INLINE vplane splat_plane(luz_plane plane)
{
    return (vplane){splat(plane.value), splat(plane.dx), splat(plane.dy)};
}

/* Every lane the same triangle's. */
INLINE void one_triangle(lane_triangles *out, const luz_triangle *triangle, vfloat centre_x,
                         vfloat centre_y)
{
    out->dx = centre_x - triangle->reference_x;
    out->dy = centre_y - triangle->reference_y;
    out->inverse_w = splat_plane(triangle->inverse_w);
    for (int k = 0; k < LUZ_VARYING_COUNT; k++)
        out->varyings[k] = splat_plane(triangle->varyings[k]);
}

/* The loops below have a fixed 4 or 8 steps over registers: unrolled,
 * they are straight-line shuffles (GCC's -O2 does not unroll them, and
 * then keeps the registers in memory). */
#define UNROLLED _Pragma("GCC unroll 8")

/* What gather_triangles reads of a triangle: 32 floats from reference_x
 * on (reference x and y, the depth plane, the 1/w plane, the varyings'
 * planes), consecutive in luz_triangle. */
enum {
    READ_FLOATS = 32,
    READ_INVERSE_W = 5,   /* float index of inverse_w.value */
    READ_VARYINGS = 8,    /* ... of varyings[0].value */
};
_Static_assert(sizeof(luz_plane) == 3 * sizeof(float), "a plane is three floats");
_Static_assert(offsetof(luz_triangle, reference_y) ==
                   offsetof(luz_triangle, reference_x) + sizeof(float) &&
               offsetof(luz_triangle, inverse_w) ==
                   offsetof(luz_triangle, reference_x) + READ_INVERSE_W * sizeof(float) &&
               offsetof(luz_triangle, varyings) ==
                   offsetof(luz_triangle, reference_x) + READ_VARYINGS * sizeof(float) &&
               READ_VARYINGS + 3 * LUZ_VARYING_COUNT == READ_FLOATS,
               "luz_triangle's reference point and planes are the 32 floats read");

/* column[k][i] = float k of lane i's READ_FLOATS (from[i] points at
 * them): each lane's floats are a row, and a transpose makes them
 * columns, eight floats of eight lanes at a time, instead of one float
 * at a time through the stack. */
INLINE void read_columns(const float *const from[LANES], vfloat column[READ_FLOATS])
{
#if LANES == 8 && defined(__AVX2__)
    UNROLLED
    for (int block = 0; block < READ_FLOATS; block += 8) {
        __m256 rows[8];
        UNROLLED
        for (int i = 0; i < 8; i++) rows[i] = _mm256_loadu_ps(from[i] + block);
        luz_transpose8(rows);
        UNROLLED
        for (int j = 0; j < 8; j++) column[block + j] = (vfloat)rows[j];
    }
#elif LANES == 16 && defined(__AVX512DQ__)
    UNROLLED
    for (int block = 0; block < READ_FLOATS; block += 8) {
        __m256 low[8], high[8];   /* lanes 0-7, lanes 8-15 */
        UNROLLED
        for (int i = 0; i < 8; i++) {
            low[i] = _mm256_loadu_ps(from[i] + block);
            high[i] = _mm256_loadu_ps(from[8 + i] + block);
        }
        luz_transpose8(low);
        luz_transpose8(high);
        UNROLLED
        for (int j = 0; j < 8; j++)
            column[block + j] =
                (vfloat)_mm512_insertf32x8(_mm512_castps256_ps512(low[j]), high[j], 1);
    }
#else
    UNROLLED
    for (int k = 0; k < READ_FLOATS; k++)
        UNROLLED
        for (int i = 0; i < LANES; i++) column[k][i] = from[i][k];
#endif
}

/* Each lane of `lanes` its own triangle's (by_id[ids[i]]), the other lanes
 * fallback's, which they never use. The same numbers as one_triangle
 * gives each lane, so the same arithmetic gives the same bits. */
INLINE void gather_triangles(lane_triangles *out, const luz_triangle *const *by_id, vuint ids,
                             unsigned lanes, const luz_triangle *fallback, vfloat centre_x,
                             vfloat centre_y)
{
    const float *from[LANES];
    for (int i = 0; i < LANES; i++) {
        const luz_triangle *triangle = (lanes >> i & 1u) ? by_id[ids[i]] : fallback;
        /* The 32 floats as bytes of the record (not as an array at
         * &reference_x, which holds one float). */
        from[i] = (const float *)((const char *)triangle +
                                  offsetof(luz_triangle, reference_x));
    }
    vfloat column[READ_FLOATS];
    read_columns(from, column);
    out->dx = centre_x - column[0];
    out->dy = centre_y - column[1];
    out->inverse_w = (vplane){column[READ_INVERSE_W], column[READ_INVERSE_W + 1],
                              column[READ_INVERSE_W + 2]};
    for (int k = 0; k < LUZ_VARYING_COUNT; k++) {
        const int first = READ_VARYINGS + 3 * k;
        out->varyings[k] = (vplane){column[first], column[first + 1], column[first + 2]};
    }
}

/* The lanes whose bits are set, as a mask. */
INLINE vint lanes_of_bits(unsigned bits)
{
    vint bit;
    for (int i = 0; i < LANES; i++)
        bit[i] = (int32_t)(1u << i);
    return (splat_int((int32_t)bits) & bit) != 0;
}

/* SCENE.md's colour output, luz_colour_to_byte per lane. */
INLINE vuint to_byte(vfloat c)
{
    const vint above = c > 0.0f, below = c < 1.0f;
    const vint inside = above & below;
    const vint byte = to_int(select_float(inside, c, splat(0.0f)) * 255.0f + 0.5f);
    return (vuint)select_int(inside, byte, above & 255);
}

/* The lanes' pixels, four bytes each in the framebuffer's channel order.
 * The order only moves red and blue, so it costs no branch: their shifts
 * take counts chosen once per band instead of constants, which is about a
 * micro-op more per packet, lost among the hundreds of shading. */
INLINE vuint pack_pixels(vvec3 colour, const packet_uniforms *u)
{
    return to_byte(colour.x) << u->red_shift | to_byte(colour.y) << CHANNEL_SHIFT(1) |
           to_byte(colour.z) << u->blue_shift | 255u << CHANNEL_SHIFT(3);
}

/* The texels of the lanes' texture lookup, as luz_texture_sample with
 * fragment.c's level of detail, fetched (filter_texture filters them). */
INLINE void fetch_texture(texture_fetch *out, const luz_material *material,
                          const lane_triangles *triangles, vfloat w, vint mine)
{
    const luz_texture *texture = material->texture;
    const vfloat dx = triangles->dx, dy = triangles->dy;
    const vplane u_plane = triangles->varyings[LUZ_VARYING_UV + 0];
    const vplane v_plane = triangles->varyings[LUZ_VARYING_UV + 1];
    const vfloat tu = plane_at(u_plane, dx, dy) * w;
    const vfloat tv = plane_at(v_plane, dx, dy) * w;
    if (material->filter == LUZ_FILTER_NEAREST) {
        out->levels = 0;
        out->fine.a = fetch_nearest(texture, tu, tv);
        return;
    }
    if (material->filter != LUZ_FILTER_TRILINEAR) {   /* bilinear, as luz_texture_sample */
        const lane_level level = level_of(texture, splat_int(0));
        out->levels = 1;
        out->fine = fetch_bilinear(texture, &level, tu, tv);
        return;
    }
    /* du/dx = (d(u/w)/dx - u d(1/w)/dx) / (1/w), and so on. */
    const vplane inverse_w = triangles->inverse_w;
    const vfloat du_dx = (u_plane.dx - tu * inverse_w.dx) * w;
    const vfloat dv_dx = (v_plane.dx - tv * inverse_w.dx) * w;
    const vfloat du_dy = (u_plane.dy - tu * inverse_w.dy) * w;
    const vfloat dv_dy = (v_plane.dy - tv * inverse_w.dy) * w;
    const vfloat lambda = level_of_detail(texture, du_dx, dv_dx, du_dy, dv_dy);
    fetch_trilinear(out, texture, tu, tv, lambda, mine);
}

/* The packet's pixels shaded as their triangles', as fragment.c shades one
 * pixel: interpolate, sample, light, as the draw's material says (every
 * lane of `mine` belongs to a triangle of that draw; the planes of
 * `triangles` are each lane's own). */
INLINE vuint shade_lanes(const packet_uniforms *u, const luz_material *material,
                         const lane_triangles *triangles, vint mine, unsigned mine_bits)
{
    const luz_vec3 object_colour = luz_material_colour(material);
    if (material->shading == LUZ_SHADING_UNLIT)
        return pack_pixels((vvec3){splat(object_colour.x), splat(object_colour.y),
                                   splat(object_colour.z)},
                           u);

    /* luz_fragment_interpolate: a = (a/w)(x, y) / (1/w)(x, y). */
    const vfloat dx = triangles->dx, dy = triangles->dy;
    const vfloat w = 1.0f / plane_at(triangles->inverse_w, dx, dy);

    const vplane *varying = triangles->varyings;
    const vvec3 position = {
        plane_at(varying[LUZ_VARYING_POSITION + 0], dx, dy) * w,
        plane_at(varying[LUZ_VARYING_POSITION + 1], dx, dy) * w,
        plane_at(varying[LUZ_VARYING_POSITION + 2], dx, dy) * w,
    };
    const vvec3 normal = {
        plane_at(varying[LUZ_VARYING_NORMAL + 0], dx, dy) * w,
        plane_at(varying[LUZ_VARYING_NORMAL + 1], dx, dy) * w,
        plane_at(varying[LUZ_VARYING_NORMAL + 2], dx, dy) * w,
    };
    /* The texel; with no texture T = 1, and c * 1 = c, so it is skipped.
     * Its gathers go out first, its filter waits for the lighting. */
    const bool textured = material->texture != NULL;
    texture_fetch fetched = {0};
    if (textured) fetch_texture(&fetched, material, triangles, w, mine);
    const vvec3 light = shade_lighting(u, position, normal, mine_bits);
    vvec3 texel = {0};
    if (textured) texel = filter_texture(&fetched);

    /* colour = light * C * T */
    vvec3 colour = {light.x * object_colour.x, light.y * object_colour.y,
                    light.z * object_colour.z};
    if (textured) colour = (vvec3){colour.x * texel.x, colour.y * texel.y, colour.z * texel.z};
    if (!u->output_is_identity) colour = output_lanes(colour, u);
    return pack_pixels(colour, u);
}

/* ---- the band ------------------------------------------------------------ */

uint64_t VARIANT_ROWS(const luz_uniforms *uniforms, const luz_draw *draws,
                      const luz_triangle *const *by_id, luz_framebuffer *framebuffer,
                      int first_row, int end_row);

/* Pixels waiting for a pass of their own draw. A packet whose pixels
 * are all one draw's, more than half of it, is shaded where it lies, in
 * one pass (each lane with its own triangle's planes, as on a big mesh,
 * whose triangles are about a pixel); any other (an edge between two
 * cubes, or a corner of a triangle) would take a pass per draw, each
 * with most of its lanes idle: its pixels go instead to their draw's queue,
 * which is shaded in one pass when it holds LANES pixels (from anywhere
 * in the band: the rows below continue the same edges), with each lane's
 * own triangle's planes. With 1000 cubes at 1280x720 that is 32 thousand
 * passes a frame instead of 50, for 31.5 thousand registers' worth of
 * pixels. A draw's queue is the one at draw_index % QUEUE_SLOTS; another
 * draw's pixels there are shaded first (with 64 queues, 11% of the
 * queues' passes at 1000 cubes; with 256, few). Each pixel is shaded
 * with its own triangle's planes at its own centre whatever else shares
 * its pass, so the bytes are those of a pass per triangle. */
enum { QUEUE_SLOTS = 256 };

typedef struct pixel_queue {
    uint32_t draw_index;
    int count;
    uint32_t id[LANES];
    uint16_t x[LANES], y[LANES];   /* LUZ_MAX_DIMENSION is 2^14 */
    uint32_t slot[LANES];          /* where its four bytes go, in pixels */
} pixel_queue;
_Static_assert(LUZ_MAX_DIMENSION <= 65536, "a queued pixel's x and y are 16 bits");

/* The queue's pixels shaded in one pass, each written to its slot of
 * `out` (four bytes a slot: the colour buffer's pixels, or a list's
 * colours); the queue left empty. */
static void shade_queue(const packet_uniforms *u, const luz_draw *draws,
                        const luz_triangle *const *by_id, uint8_t *out, pixel_queue *queue)
{
    vuint ids = {0};
    vfloat centre_x = splat(0.5f), centre_y = splat(0.5f);
    for (int i = 0; i < queue->count; i++) {
        ids[i] = queue->id[i];
        centre_x[i] = (float)queue->x[i] + 0.5f;
        centre_y[i] = (float)queue->y[i] + 0.5f;
    }
    const unsigned lanes = queue->count == LANES ? ALL_LANES : (1u << queue->count) - 1u;
    const luz_triangle *first = by_id[queue->id[0]];
    lane_triangles triangles;
    if ((lane_bits((vint)(ids == queue->id[0])) & lanes) == lanes)
        one_triangle(&triangles, first, centre_x, centre_y);
    else
        gather_triangles(&triangles, by_id, ids, lanes, first, centre_x, centre_y);
    const vuint pixels = shade_lanes(u, &draws[queue->draw_index].material, &triangles,
                                     lanes_of_bits(lanes), lanes);
    for (int i = 0; i < queue->count; i++) {
        const uint32_t pixel = pixels[i];
        memcpy(out + (size_t)queue->slot[i] * 4, &pixel, 4);
    }
    queue->count = 0;
}

/* The lanes of `queued` (their triangles' ids) put in their draws'
 * queues, lane i as slot first_slot + i of `out`; lane i's pixel is
 * fragments[i]'s, or with no fragments (x + i, y). A full queue is
 * shaded into `out`, as is one that holds another draw's. */
INLINE void queue_lanes(const packet_uniforms *u, const luz_draw *draws,
                        const luz_triangle *const *by_id, uint8_t *out,
                        pixel_queue queues[QUEUE_SLOTS], unsigned queued, vuint ids,
                        const luz_fragment_ref *fragments, int x, int y, uint32_t first_slot)
{
    for (uint32_t id = 0, draw_index = 0; queued != 0; queued &= queued - 1) {
        const int i = __builtin_ctz(queued);
        if (ids[i] != id) {
            id = ids[i];
            draw_index = by_id[id]->draw_index;
        }
        pixel_queue *queue = &queues[draw_index % QUEUE_SLOTS];
        if (queue->count != 0 && queue->draw_index != draw_index)
            shade_queue(u, draws, by_id, out, queue);
        queue->draw_index = draw_index;
        queue->id[queue->count] = id;
        queue->x[queue->count] = fragments ? fragments[i].x : (uint16_t)(x + i);
        queue->y[queue->count] = fragments ? fragments[i].y : (uint16_t)y;
        queue->slot[queue->count] = first_slot + (uint32_t)i;
        if (++queue->count == LANES) shade_queue(u, draws, by_id, out, queue);
    }
}

/* Whether the lanes of `covered` (not none) are more than half the
 * packet and all one draw's, that of by_id[ids[first lane]]: then they
 * are shaded where they lie, in one pass. */
INLINE bool one_draw_packet(const luz_triangle *const *by_id, vuint ids, unsigned covered,
                            unsigned first_triangle, uint32_t draw_index)
{
    bool one_draw = __builtin_popcount(covered) > LANES / 2;
    for (unsigned rest = covered & ~first_triangle; one_draw && rest != 0; rest &= rest - 1)
        one_draw = by_id[ids[__builtin_ctz(rest)]]->draw_index == draw_index;
    return one_draw;
}

/* A packet of the rows or of the list, its lanes of `covered` (not none)
 * those of triangles `ids`, at centres (centre_x, centre_y): when they
 * are more than half the packet and all one draw's (one_draw_packet),
 * shaded where they lie into those lanes of *pixels, and no lane is left
 * to queue (0); else *pixels is left as it is and every lane of covered
 * is returned, for its draw's queue. */
INLINE unsigned shade_here_or_queue(const packet_uniforms *u, const luz_draw *draws,
                                    const luz_triangle *const *by_id, vuint ids,
                                    unsigned covered, vfloat centre_x, vfloat centre_y,
                                    vuint *pixels)
{
    const uint32_t first_id = ids[__builtin_ctz(covered)];
    const luz_triangle *triangle = by_id[first_id];
    const unsigned first_triangle = lane_bits((vint)(ids == first_id)) & covered;
    if (!one_draw_packet(by_id, ids, covered, first_triangle, triangle->draw_index))
        return covered;
    lane_triangles triangles;
    if (first_triangle == covered)
        one_triangle(&triangles, triangle, centre_x, centre_y);
    else
        gather_triangles(&triangles, by_id, ids, covered, triangle, centre_x, centre_y);
    const vint mine = (vint)(ids != 0u);
    const vuint shade =
        shade_lanes(u, &draws[triangle->draw_index].material, &triangles, mine, covered);
    *pixels = (vuint)select_int(mine, (vint)shade, (vint)*pixels);
    return 0;
}

/* The packet loop of this variant. */
uint64_t VARIANT_ROWS(const luz_uniforms *uniforms, const luz_draw *draws,
                      const luz_triangle *const *by_id, luz_framebuffer *framebuffer,
                      int first_row, int end_row)
{
    const packet_uniforms u = packet_uniforms_of(uniforms, framebuffer->channel_order);
    const vuint background = (vuint){0} + u.background;
    const int width = framebuffer->width;
    vfloat lane_x;
    for (int i = 0; i < LANES; i++)
        lane_x[i] = (float)i;
    uint64_t shaded = 0;
    pixel_queue queues[QUEUE_SLOTS];
    for (int q = 0; q < QUEUE_SLOTS; q++)
        queues[q].count = 0;

    for (int y = first_row; y < end_row; y++) {
        const uint32_t *visibility_row = framebuffer->visibility + (size_t)y * width;
        uint8_t *colour_row = framebuffer->colour + (size_t)y * width * 4;
        const float centre_y = (float)y + 0.5f;
        for (int x = 0; x < width; x += LANES) {
            /* The row's last packet may be short: its missing lanes read
             * as background. */
            const int count = width - x < LANES ? width - x : LANES;
            vuint ids = {0};
            if (count == LANES)
                memcpy(&ids, visibility_row + x, sizeof ids);
            else
                for (int i = 0; i < count; i++)
                    ids[i] = visibility_row[x + i];
            const unsigned covered = lane_bits((vint)(ids != 0u));
            uint8_t *out = colour_row + (size_t)x * 4;
            /* Every lane starts as the background; the triangle's pass
             * overwrites its lanes. */
            vuint pixels = background;
            unsigned queued = 0;
            if (covered != 0) {
                shaded += (uint64_t)__builtin_popcount(covered);
                /* Pixel centres as fragment.c computes them: (float)x + 0.5. */
                queued = shade_here_or_queue(&u, draws, by_id, ids, covered,
                                             (lane_x + (float)x) + 0.5f, splat(centre_y),
                                             &pixels);
            }
            /* Lanes are in memory order, so a short packet's first count
             * lanes are its pixels. Queued lanes are written again when
             * their queue is shaded, after this store. */
            if (count == LANES)
                memcpy(out, &pixels, sizeof pixels);
#if LANES > 1   /* with one lane no packet is short */
            else
                memcpy(out, &pixels, (size_t)count * 4);
#endif
            if (queued != 0)
                queue_lanes(&u, draws, by_id, framebuffer->colour, queues, queued, ids, NULL, x,
                            y, (uint32_t)((size_t)y * width + (size_t)x));
        }
    }
    for (int q = 0; q < QUEUE_SLOTS; q++)
        if (queues[q].count != 0) shade_queue(&u, draws, by_id, framebuffer->colour, &queues[q]);
    return shaded;
}

uint64_t VARIANT_LIST(const luz_uniforms *uniforms, const luz_draw *draws,
                      const luz_triangle *const *by_id, luz_channel_order order,
                      const luz_fragment_ref *fragments, size_t count, uint32_t *colours);

/* The list loop of this variant: LANES fragments of the list at a time,
 * each lane at its own pixel, shaded as the rows shade it (the same
 * centre, (float)x + 0.5, and planes: the same bits). As in the rows, a
 * packet more than half one draw's is shaded where it lies, and any
 * other's fragments go to their draws' queues: the list holds the
 * pixels an edge crosses, row by row, so a packet of it spans several
 * edges, often of as many draws (100 cubes), where a pass per draw
 * would leave most lanes idle. */
uint64_t VARIANT_LIST(const luz_uniforms *uniforms, const luz_draw *draws,
                      const luz_triangle *const *by_id, luz_channel_order order,
                      const luz_fragment_ref *fragments, size_t count, uint32_t *colours)
{
    const packet_uniforms u = packet_uniforms_of(uniforms, order);
    const vuint background = (vuint){0} + u.background;
    uint8_t *out = (uint8_t *)colours;
    pixel_queue queues[QUEUE_SLOTS];
    for (int q = 0; q < QUEUE_SLOTS; q++)
        queues[q].count = 0;
    for (size_t begin = 0; begin < count; begin += LANES) {
        const int lanes = count - begin < LANES ? (int)(count - begin) : LANES;
        const luz_fragment_ref *packet = fragments + begin;
        vuint ids = {0};
        vfloat centre_x = splat(0.5f), centre_y = splat(0.5f);
        for (int i = 0; i < lanes; i++) {
            ids[i] = packet[i].id;
            centre_x[i] = (float)packet[i].x + 0.5f;
            centre_y[i] = (float)packet[i].y + 0.5f;
        }
        /* A fragment of no triangle (id 0) is the background. */
        const unsigned covered = lane_bits((vint)(ids != 0u));
        vuint pixels = background;
        unsigned queued = 0;
        if (covered != 0) {
            queued = shade_here_or_queue(&u, draws, by_id, ids, covered, centre_x, centre_y,
                                         &pixels);
        }
        /* Queued lanes are written again when their queue is shaded. */
        memcpy(colours + begin, &pixels, (size_t)lanes * sizeof *colours);
        if (queued != 0)
            queue_lanes(&u, draws, by_id, out, queues, queued, ids, packet, 0, 0,
                        (uint32_t)begin);
    }
    for (int q = 0; q < QUEUE_SLOTS; q++)
        if (queues[q].count != 0) shade_queue(&u, draws, by_id, out, &queues[q]);
    return count;
}

/* ---- for the probe (in the baseline variant only) ---------------------- */

#if defined(BASELINE_VARIANT)

float luz_packet_level_of_detail(const luz_texture *texture, float du_dx, float dv_dx,
                                 float du_dy, float dv_dy)
{
    return level_of_detail(texture, splat(du_dx), splat(dv_dx), splat(du_dy), splat(dv_dy))[0];
}

#endif
