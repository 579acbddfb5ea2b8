/*
 * luz/probe.h: why is this pixel this colour? The pipeline's own account
 * of one pixel of a frame.
 *
 * Give luz_renderer_draw a luz_pixel_probe (luz_render_options.probe) with
 * the pixel's x and y, and the draw fills in the story of that pixel while
 * it draws the frame as usual:
 *
 *   the history   every depth test made at the pixel, in draw order: the
 *                 triangle, its depth there, the depth the buffer held and
 *                 whether it passed (LESS); the last test that passed is
 *                 the winner, the triangle the visibility buffer keeps
 *   the winner    its draw, its triangle in the draw's mesh, that
 *                 triangle's corners in clip space and in window
 *                 coordinates, the perspective-correct barycentric
 *                 coordinates of the pixel centre in it, and w
 *   the varyings  world position P, normal N (re-normalised), uv
 *   the texture   the footprint rho, the level of detail the sampler used,
 *                 the mip levels and their blend, the texel T
 *   the lighting  the six terms (luz/shade.h), their sum, the colour C,
 *                 light x C x T
 *   the output    the exposure, the colour times 2^EV, the tone-mapped
 *                 colour before the clamp
 *   the bytes     what the image holds at the pixel
 *   the samples   with four samples a pixel (luz_frame.samples): each
 *                 sample's position, winner and 8-bit colour, and the
 *                 history lists every sample's depth tests (each test
 *                 says which sample); the winner above is the pixel's
 *                 first (that of its first sample not background), and
 *                 bytes = floor((s0 + s1 + s2 + s3 + 2) / 4) per channel
 *
 * Every number is produced by the code that drew the image: the raster
 * stage's coverage and depth arithmetic, luz_fragment_interpolate, the
 * sampler, the level of detail of the fragment path that shaded the pixel
 * (the SIMD one's polynomial logarithm, or the reference's log2f), and
 * luz_shade_terms, luz_shade_output. round(clamp(mapped) x 255) is the image's byte; the
 * tests check it at every pixel.
 *
 * Asking costs one branch per band of rows and the probe's own work after
 * the frame, on the calling thread: a frame without a probe is drawn
 * exactly as before.
 */
#ifndef LUZ_PROBE_H
#define LUZ_PROBE_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/bug.h"
#include "luz/frame.h"
#include "luz/shade.h"
#include "luz/texture.h"
#include "luz/vecmath.h"
#include "luz/view.h"

/* The history keeps the first LUZ_PROBE_MAX_TESTS depth tests of the pixel
 * (test_count counts them all). */
#define LUZ_PROBE_MAX_TESTS 256

/* With four samples a pixel, what the probe says of each sample. */
#define LUZ_PROBE_MAX_SAMPLES 4

typedef struct luz_probe_sample {
    float x, y;          /* its position in the image: x + sx, y + sy */
    int test_count;      /* depth tests made there */
    uint32_t triangle;   /* its winner's id (0: none, the clear colour) */
    float depth_buffer;  /* the depth it kept (1: none won) */
    uint8_t bytes[3];    /* the colour it took: its winner's, shaded once
                            for the pixel at its centre (the clear colour
                            where none won), red, green, blue */
} luz_probe_sample;

/* One depth test at the pixel. */
typedef struct luz_probe_test {
    int sample;          /* which of the pixel's samples (0 with one) */
    uint32_t triangle;   /* its id: 1, 2, ... in submission order, as the
                            visibility buffer holds it */
    int draw;            /* its draw: an index into the frame's draws */
    float depth;         /* the fragment's window depth at the pixel centre */
    float stored;        /* what the depth buffer held before the test */
    bool passed;         /* depth < stored (LESS): the buffer now holds depth */
} luz_probe_test;

/* An edge of the winner at the pixel centre (setup.c, step 4): edge k
 * runs from corner k + 1 to corner k + 2 (window coordinates snapped to
 * 1/256 pixel, X = 256 x), and E(X, Y) = (Yj - Yi)(X - Xi) - (Xj - Xi)(Y - Yi)
 * is positive inside; value is E at the centre, in 1/256 pixel units
 * squared (twice the area of the triangle the edge and the centre make,
 * times 65536), before the fill rule. A centre with E = 0 lies on the
 * edge, and is the triangle's if owns_its_samples. */
typedef struct luz_probe_edge {
    int64_t value;
    bool top;                /* horizontal, the triangle below it */
    bool left;               /* the triangle to its right (it runs downwards) */
    bool owns_its_samples;   /* top or left (SCENE.md's rule; bottom or
                                right under fill-rule-bottom-right) */
} luz_probe_edge;

/* One texel the sampler read: where, what, and its weight in T. */
typedef struct luz_probe_tap {
    int level;               /* the mip level */
    int x, y;                /* the texel, wrapped (REPEAT) */
    luz_vec3 texel;          /* its colour, bytes / 255 */
    float weight;            /* bilinear weight times the level's: the taps'
                                weights add up to 1 */
} luz_probe_tap;

#define LUZ_PROBE_MAX_TAPS 8

/* (renderer.h declares the type too, for luz_render_options.probe.) */
typedef struct luz_pixel_probe luz_pixel_probe;

struct luz_pixel_probe {
    /* ---- asked: the pixel, row 0 on top ---- */
    int x, y;

    /* ---- answered by luz_renderer_draw ---- */
    luz_bug bug;            /* the frame's (luz/bug.h): every number below
                               follows it */
    bool filled;            /* false: (x, y) lies outside the framebuffer,
                               and nothing below is set */
    luz_view view;          /* what the image shows there (the options') */
    uint8_t bytes[3];       /* red, green, blue: what the image holds at the
                               pixel (before a band hook draws on top) */
    int samples;            /* the frame's samples a pixel: 1 or 4 */
    luz_probe_sample sample[LUZ_PROBE_MAX_SAMPLES];   /* with 4: each sample;
                               bytes is their resolve */

    /* The history. */
    int test_count;         /* every depth test made at the pixel */
    int tests_kept;         /* the first min(test_count, LUZ_PROBE_MAX_TESTS) */
    luz_probe_test tests[LUZ_PROBE_MAX_TESTS];
    float depth_buffer;     /* the depth buffer's final value there (1: the
                               far plane, for the background) */

    /* The winner; triangle 0 is the background, and then nothing below is
     * set but what the view shows. */
    uint32_t triangle;      /* its id */
    int draw;               /* index into the frame's draws */
    int primitive;          /* the triangle of the draw's mesh it comes from:
                               indices 3 primitive .. 3 primitive + 2; -1 if
                               it could not be told (never expected: the
                               probe's setup did not find the pipeline's
                               record again) */
    uint32_t vertices[3];   /* those indices */
    luz_vec4 corner_clip[3];   /* those vertices in clip space, as the vertex
                                  stage gives them: projection x view x
                                  model x position */
    luz_vec3 corner_window[3]; /* the winner's corners (for a clipped
                                  primitive, those of its piece) as setup
                                  placed them: window x and y in pixels,
                                  row 0 on top, snapped to 1/256 of a pixel,
                                  and the window depth that the triangle's
                                  depth plane gives there */
    int clipped_pieces;     /* 0: not clipped; else the primitive was cut
                               into a fan of this many triangles ... */
    int piece;              /* ... of which this is the piece-th (from 0) */
    luz_vec3 barycentric;   /* weights of the primitive's three vertices at
                               the pixel centre: perspective-correct (affine
                               with LUZ_INTERPOLATION_AFFINE), as every
                               varying is interpolated */
    float w;                /* clip-space w there, 1 / (1/w): the distance in
                               front of the eye (1 for affine) */
    float depth;            /* its window depth, the winning test's */

    /* The matrices of the winner's vertex stage: its draw's model matrix
     * and the frame's view and projection. */
    luz_mat4 model_matrix, view_matrix, projection_matrix;
    /* The winner's three edge functions at the pixel centre. */
    luz_probe_edge edges[3];

    /* The varyings, perspective-correct (luz_fragment_interpolate). */
    luz_vec3 position;      /* P, world space */
    luz_vec3 normal;        /* N, re-normalised as the shader does */
    luz_vec2 uv;
    float du_dx, dv_dx, du_dy, dv_dy;   /* uv's screen derivatives */

    /* The texture (all zero but texel, T = 1, when the material has none). */
    const luz_texture *texture;
    luz_filter filter;
    float rho;              /* texels of level 0 per pixel step: the root of
                               the rho^2 the level of detail is taken from */
    float lambda;           /* the level of detail the sampler used: 0 for
                               nearest and bilinear, which read level 0 */
    luz_texture_mip_pair levels;   /* the levels read and the upper's weight */
    luz_vec3 texel;         /* T */
    int tap_count;          /* the texels read: 1 (nearest), 4 (bilinear, or
                               trilinear at one level) or 8 */
    luz_probe_tap taps[LUZ_PROBE_MAX_TAPS];

    /* The lighting (luz_shade_terms); for an unlit material only
     * object_colour and colour are set. */
    luz_shading shading;
    luz_vec3 terms[LUZ_TERM_COUNT];   /* in luz_term's order */
    luz_vec3 light;         /* their sum, added in that order */
    luz_shade_steps steps;  /* the numbers in between: N.L, R, V.R, Lp,
                               N.Lp, c, f_dir, dn, f_win, f_dist, the sun's
                               direction (luz_shade_terms_explained) */
    luz_vec3 object_colour; /* C */
    luz_vec3 colour;        /* light x C x T, before the output (unlit: C) */
    /* The output (SCENE.md, "Output"; luz_shade_output), for a lit
     * material: the frame's exposure and tone map, the colour times 2^EV,
     * and that colour tone-mapped, which luz_colour_to_byte makes the
     * bytes. Unlit: exposed and mapped are the colour as it is. */
    float exposure;         /* EV */
    float exposure_scale;   /* 2^EV */
    luz_tone_map tone_map;
    luz_vec3 exposed;       /* colour x 2^EV */
    luz_vec3 mapped;        /* the tone map's output, before the clamp */

    /* What a view other than LUZ_VIEW_COLOR shows (luz/view.h). */
    luz_vec3 shown;         /* the view's colour before it became bytes */
    uint32_t overdraw;      /* LUZ_VIEW_OVERDRAW: the depth tests counted */
    int band;               /* the band of rows the pixel is in ... */
    int worker;             /* ... and the thread that drew it (0: the
                               caller's), which LUZ_VIEW_BANDS tints by */
    float edge_distance;    /* LUZ_VIEW_TRIANGLES: pixels from the centre to
                               the winner's nearest edge */
    bool on_edge;           /* LUZ_VIEW_TRIANGLES: a neighbour pixel lies
                               outside the winner, so the view shades it
                               darker (LUZ_VIEW_TRIANGLE_EDGE_SHADE) */
};

#endif
