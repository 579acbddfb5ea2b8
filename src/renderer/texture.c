/*
 * texture.c: mip chains and texture sampling, as OpenGL 4.6 section 8.14
 * ("Texture minification") describes them, with SCENE.md's exact choices.
 *
 * In:  a texture, the filter, texture coordinates (u, v) and the level of
 *      detail lambda.
 * Out: the filtered texel colour, rgb in [0, 1].
 *
 * Texel i of a level of width w covers [i / w, (i + 1) / w) and has its
 * centre at (i + 0.5) / w. Wrap mode REPEAT: only the fractional part of a
 * coordinate matters. Bilinear filtering weighs the four texels around the
 * sample point by their distance; trilinear filtering blends the bilinear
 * samples of the two mip levels around lambda. lambda = log2(rho), rho
 * the number of level-0 texels one pixel step covers (the texture's
 * "footprint"): when a pixel spans more than one texel, a smaller, averaged
 * level stands in for them, which is what keeps distant textures from
 * shimmering (Williams, "Pyramidal parametrics", 1983).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "luz/texture.h"
#include "renderer/pipeline.h"

luz_texture *luz_texture_create(int width, int height, const uint8_t *rgba, luz_error *error)
{
    if (width < 1 || height < 1 || width > LUZ_TEXTURE_MAX_SIZE ||
        height > LUZ_TEXTURE_MAX_SIZE) {
        luz_error_set(error, "texture size %dx%d is outside 1x1 to %dx%d", width, height,
                      LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
        return NULL;
    }
    if (rgba == NULL) {
        luz_error_set(error, "texture %dx%d: no pixels (expected %dx%dx4 bytes of RGBA8)",
                      width, height, width, height);
        return NULL;
    }

    /* Sizes of the chain first, to make one allocation: each level is
     * max(1, floor(w / 2)) x max(1, floor(h / 2)) of the one before; the
     * whole chain is under 4/3 of level 0 (at most 8192^2 * 4 * 4/3 bytes,
     * well inside size_t). */
    luz_texture *texture = calloc(1, sizeof *texture);
    if (!texture) {
        luz_error_set(error, "out of memory for a %dx%d texture", width, height);
        return NULL;
    }
    size_t total = 0, offsets[LUZ_TEXTURE_MAX_LEVELS];
    int w = width, h = height, count = 0;
    for (;;) {
        texture->levels[count].width = w;
        texture->levels[count].height = h;
        offsets[count] = total;
        total += (size_t)w * (size_t)h * 4;
        count++;
        if ((w == 1 && h == 1) || count == LUZ_TEXTURE_MAX_LEVELS) break;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    texture->storage = malloc(total);
    if (!texture->storage) {
        free(texture);
        luz_error_set(error, "out of memory for a %dx%d texture", width, height);
        return NULL;
    }
    texture->level_count = count;
    memcpy(texture->storage, rgba, (size_t)width * (size_t)height * 4);

    /* Each texel of level k + 1 is the rounded 2x2 box average of level k;
     * an odd last row or column of level k has no partner and is dropped. */
    for (int level = 0; level < count; level++) {
        texture->levels[level].texels = texture->storage + offsets[level];
        if (level == 0) continue;
        const luz_texture_level *source = &texture->levels[level - 1];
        uint8_t *target = texture->storage + offsets[level];
        int target_width = texture->levels[level].width;
        int target_height = texture->levels[level].height;
        for (int y = 0; y < target_height; y++) {
            /* A source of height 1 (or width 1) has a single row (column)
             * to average with itself. */
            int y0 = source->height > 1 ? 2 * y : 0, y1 = source->height > 1 ? 2 * y + 1 : 0;
            for (int x = 0; x < target_width; x++) {
                int x0 = source->width > 1 ? 2 * x : 0, x1 = source->width > 1 ? 2 * x + 1 : 0;
                const uint8_t *a = source->texels + ((size_t)y0 * source->width + x0) * 4;
                const uint8_t *b = source->texels + ((size_t)y0 * source->width + x1) * 4;
                const uint8_t *c = source->texels + ((size_t)y1 * source->width + x0) * 4;
                const uint8_t *d = source->texels + ((size_t)y1 * source->width + x1) * 4;
                uint8_t *out = target + ((size_t)y * target_width + x) * 4;
                for (int channel = 0; channel < 4; channel++)
                    out[channel] = (uint8_t)((a[channel] + b[channel] + c[channel] +
                                              d[channel] + 2) / 4);
            }
        }
    }
    return texture;
}

void luz_texture_destroy(luz_texture *texture)
{
    if (!texture) return;
    free(texture->storage);
    free(texture);
}

float luz_texture_level_of_detail(const luz_texture *texture,
                                  float du_dx, float dv_dx, float du_dy, float dv_dy)
{
    /* log2(rho) = log2(rho^2) / 2: no square root needed. */
    float rho_squared = luz_texture_footprint_squared(texture, du_dx, dv_dx, du_dy, dv_dy);
    /* Magnified (a texel covers a pixel or more): lambda <= 0, level 0.
     * Most pixels of a close-up are, and they skip the logarithm. */
    if (!(rho_squared > 1.0f)) return 0.0f;
    return 0.5f * log2f(rho_squared);
}

static inline const uint8_t *texel_address(const luz_texture_level *level, int x, int y)
{
    return level->texels + ((size_t)y * level->width + x) * 4;
}

luz_vec3 luz_texture_sample_nearest(const luz_texture *texture, int level_index, luz_vec2 uv)
{
    const luz_texture_level *level = &texture->levels[level_index];
    /* The texel whose square contains the point: floor(u * w). */
    int x = (int)(luz_texture_repeat(uv.x) * level->width);
    int y = (int)(luz_texture_repeat(uv.y) * level->height);
    if (x >= level->width) x = level->width - 1;   /* u just below 1 rounding up */
    if (y >= level->height) y = level->height - 1;
    const uint8_t *p = texel_address(level, x, y);
    const float scale = 1.0f / 255.0f;
    return (luz_vec3){p[0] * scale, p[1] * scale, p[2] * scale};
}

/* Along one axis: the two texels whose centres surround the coordinate,
 * wrapped around the edge, and the weight of the second. Texel centres
 * sit at whole numbers once the coordinate is scaled by the size and
 * shifted by half a texel. */
static inline void bilinear_axis(float coordinate, int size, int *first, int *second,
                                 float *weight)
{
    /* shifted by one texel: > 0 */
    float s = luz_texture_repeat(coordinate) * (float)size + 0.5f;
    int i = (int)s;                                      /* floor, as s > 0 */
    *weight = s - (float)i;
    i -= 1;                                              /* in [-1, size - 1] */
    *first = i < 0 ? size - 1 : i;
    *second = i + 1 < size ? i + 1 : 0;
}

luz_vec3 luz_texture_sample_bilinear(const luz_texture *texture, int level_index, luz_vec2 uv)
{
    const luz_texture_level *level = &texture->levels[level_index];
    int x0, x1, y0, y1;
    float fx, fy;
    bilinear_axis(uv.x, level->width, &x0, &x1, &fx);
    bilinear_axis(uv.y, level->height, &y0, &y1, &fy);

    const uint8_t *a = texel_address(level, x0, y0), *b = texel_address(level, x1, y0);
    const uint8_t *c = texel_address(level, x0, y1), *d = texel_address(level, x1, y1);
    /* Weights of the four texels; they sum to 1. The 1/255 that turns
     * bytes into [0, 1] is folded into them. */
    const float scale = 1.0f / 255.0f;
    float wa = (1.0f - fx) * (1.0f - fy) * scale, wb = fx * (1.0f - fy) * scale;
    float wc = (1.0f - fx) * fy * scale, wd = fx * fy * scale;
    return (luz_vec3){
        wa * a[0] + wb * b[0] + wc * c[0] + wd * d[0],
        wa * a[1] + wb * b[1] + wc * c[1] + wd * d[1],
        wa * a[2] + wb * b[2] + wc * c[2] + wd * d[2],
    };
}

luz_texture_mip_pair luz_texture_mip_levels(const luz_texture *texture, float lambda)
{
    const int last = texture->level_count - 1;
    /* "!(lambda > 0)" also sends NaN to level 0. */
    if (!(lambda > 0.0f)) return (luz_texture_mip_pair){0, 0, 0.0f};
    float level_floor = floorf(lambda);
    if (level_floor >= (float)last) return (luz_texture_mip_pair){last, last, 0.0f};
    int lower = (int)level_floor;
    return (luz_texture_mip_pair){lower, lower + 1, lambda - level_floor};
}

luz_vec3 luz_texture_sample_trilinear(const luz_texture *texture, luz_vec2 uv, float lambda)
{
    luz_texture_mip_pair levels = luz_texture_mip_levels(texture, lambda);
    luz_vec3 fine = luz_texture_sample_bilinear(texture, levels.lower, uv);
    if (levels.lower == levels.upper) return fine;
    luz_vec3 coarse = luz_texture_sample_bilinear(texture, levels.upper, uv);
    return luz_vec3_add(luz_vec3_scale(fine, 1.0f - levels.blend),
                        luz_vec3_scale(coarse, levels.blend));
}

luz_vec3 luz_texture_sample(const luz_texture *texture, luz_filter filter, luz_vec2 uv,
                            float lambda)
{
    if (!texture) return (luz_vec3){1.0f, 1.0f, 1.0f};
    switch (filter) {
    case LUZ_FILTER_NEAREST: return luz_texture_sample_nearest(texture, 0, uv);
    case LUZ_FILTER_BILINEAR: return luz_texture_sample_bilinear(texture, 0, uv);
    case LUZ_FILTER_TRILINEAR: break;
    }
    return luz_texture_sample_trilinear(texture, uv, lambda);
}

const char *luz_filter_name(luz_filter filter)
{
    switch (filter) {
    case LUZ_FILTER_NEAREST: return "nearest";
    case LUZ_FILTER_BILINEAR: return "bilinear";
    case LUZ_FILTER_TRILINEAR: return "trilinear";
    }
    return "unknown";
}

/* The probe's account of a sample: the same wrap, texel and weight
 * arithmetic as the samplers above. */
static int bilinear_taps(const luz_texture *texture, int level_index, luz_vec2 uv,
                         float level_weight, luz_probe_tap *taps)
{
    const luz_texture_level *level = &texture->levels[level_index];
    int x[2], y[2];
    float fx, fy;
    bilinear_axis(uv.x, level->width, &x[0], &x[1], &fx);
    bilinear_axis(uv.y, level->height, &y[0], &y[1], &fy);
    const float wx[2] = {1.0f - fx, fx}, wy[2] = {1.0f - fy, fy};
    const float scale = 1.0f / 255.0f;
    for (int k = 0; k < 4; k++) {
        const int i = k & 1, j = k >> 1;
        const uint8_t *p = texel_address(level, x[i], y[j]);
        taps[k] = (luz_probe_tap){level_index, x[i], y[j],
                                  {p[0] * scale, p[1] * scale, p[2] * scale},
                                  wx[i] * wy[j] * level_weight};
    }
    return 4;
}

int luz_texture_taps(const luz_texture *texture, luz_filter filter, luz_vec2 uv, float lambda,
                     luz_probe_tap *taps)
{
    if (!texture) return 0;
    if (filter == LUZ_FILTER_NEAREST) {
        const luz_texture_level *level = &texture->levels[0];
        int x = (int)(luz_texture_repeat(uv.x) * level->width);
        int y = (int)(luz_texture_repeat(uv.y) * level->height);
        if (x >= level->width) x = level->width - 1;
        if (y >= level->height) y = level->height - 1;
        const uint8_t *p = texel_address(level, x, y);
        const float scale = 1.0f / 255.0f;
        taps[0] = (luz_probe_tap){0, x, y, {p[0] * scale, p[1] * scale, p[2] * scale}, 1.0f};
        return 1;
    }
    if (filter == LUZ_FILTER_BILINEAR) return bilinear_taps(texture, 0, uv, 1.0f, taps);
    const luz_texture_mip_pair levels = luz_texture_mip_levels(texture, lambda);
    if (levels.lower == levels.upper) return bilinear_taps(texture, levels.lower, uv, 1.0f, taps);
    bilinear_taps(texture, levels.lower, uv, 1.0f - levels.blend, taps);
    return 4 + bilinear_taps(texture, levels.upper, uv, levels.blend, taps + 4);
}
