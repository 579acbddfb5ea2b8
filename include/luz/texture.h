/*
 * luz/texture.h: textures, their mip chains, and sampling.
 *
 * A luz_texture is an RGBA8 image and its mip chain, built exactly as
 * SCENE.md says: level k+1 is max(1, floor(w/2)) x max(1, floor(h/2)), each
 * texel the 2x2 box average (a + b + c + d + 2) / 4 of level k (an odd last
 * row or column is dropped). Texel values are used as stored: no sRGB decode.
 *
 * Sampling follows OpenGL with wrap mode REPEAT: texel i of a level of width
 * w has its centre at u = (i + 0.5) / w, and v = 0 is the image's top row.
 *
 * Textures are made from pixels in memory: libluz reads no files (the
 * programs load image files with src/io/textures.h).
 */
#ifndef LUZ_TEXTURE_H
#define LUZ_TEXTURE_H

#include <stdint.h>

#include "luz/api.h"
#include "luz/error.h"
#include "luz/vecmath.h"

#define LUZ_TEXTURE_MAX_SIZE 8192   /* per side; bounds memory for any file */
#define LUZ_TEXTURE_MAX_LEVELS 14   /* log2(8192) + 1 */

/* Texture filtering, as OpenGL's minification filters. Zero is trilinear,
 * the best, so that a zero material samples as well as it can. */
typedef enum luz_filter {
    LUZ_FILTER_TRILINEAR,   /* GL_LINEAR_MIPMAP_LINEAR */
    LUZ_FILTER_BILINEAR,    /* GL_LINEAR, level 0 only */
    LUZ_FILTER_NEAREST,     /* GL_NEAREST, level 0 only */
} luz_filter;

LUZ_API const char *luz_filter_name(luz_filter filter);    /* "nearest", ... */

typedef struct luz_texture_level {
            int width;
    int height;
    const uint8_t *texels;  /* RGBA8, row 0 first */
} luz_texture_level;

typedef struct luz_texture {
    int level_count;
    luz_texture_level levels[LUZ_TEXTURE_MAX_LEVELS];
    uint8_t *storage;       /* all levels, one allocation */
} luz_texture;

/* Builds a texture and its mip chain from RGBA8 texels (copied). */
LUZ_API luz_texture *luz_texture_create(int width, int height, const uint8_t *rgba, luz_error *error);
LUZ_API void luz_texture_destroy(luz_texture *texture);

/* The level of detail lambda = log2(rho) from the derivatives of (u, v) in
 * texture coordinates per pixel; rho is measured in texels of level 0:
 * rho = max(|(du/dx, dv/dx)|, |(du/dy, dv/dy)|) * (width, height). */
LUZ_API float luz_texture_level_of_detail(const luz_texture *texture,
                                          float du_dx, float dv_dx, float du_dy, float dv_dy);

LUZ_API luz_vec3 luz_texture_sample_nearest(const luz_texture *texture, int level, luz_vec2 uv);
LUZ_API luz_vec3 luz_texture_sample_bilinear(const luz_texture *texture, int level, luz_vec2 uv);
/* The two mip levels trilinear filtering reads at level of detail lambda
 * and the weight of the upper one: lambda <= 0 (or NaN) reads level 0
 * alone, lambda past the last level reads the last alone (lower == upper,
 * blend 0), else floor(lambda) and floor(lambda) + 1 mixed by
 * fract(lambda). */
typedef struct luz_texture_mip_pair {
    int lower, upper;
    float blend;
} luz_texture_mip_pair;

LUZ_API luz_texture_mip_pair luz_texture_mip_levels(const luz_texture *texture, float lambda);

/* Trilinear (GL_LINEAR_MIPMAP_LINEAR) at the given level of detail. */
LUZ_API luz_vec3 luz_texture_sample_trilinear(const luz_texture *texture, luz_vec2 uv, float lambda);
/* Dispatches on the filter; a NULL texture samples white. */
LUZ_API luz_vec3 luz_texture_sample(const luz_texture *texture, luz_filter filter, luz_vec2 uv,
                                    float lambda);

#endif
