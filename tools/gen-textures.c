/*
 * gen-textures: writes the procedural textures that luz's scenes sample.
 *
 * What it is for
 *   The scene puts a texture on every cube, multiplied by a random colour and
 *   lit.  Rather than ship pictures of unknown origin, the PNGs in textures/
 *   are computed by this program from Perlin noise (stb_perlin) and a little
 *   geometry, and written with stb_image_write.  Every texture is 256 x 256
 *   RGB, fairly bright (so the per-cube colour and the lighting have something
 *   to work with) and tiles seamlessly under REPEAT wrapping: column 255
 *   continues into column 0 and row 255 into row 0.
 *
 * What it deliberately is not
 *   Not a texture editor or a general noise library: there are no options, no
 *   sizes to choose and no random seeds.  Every number is fixed, so the same
 *   program writes byte-identical files on every run; a test checks the
 *   committed PNGs against a fresh run.  For that reason it uses only plain
 *   float arithmetic (no rand(), no clock, no locale, no sin/cos/pow from the
 *   C library, whose last bits may differ between C libraries).
 *
 * How to regenerate the committed textures
 *   ninja -C build textures          (runs the tool into the source textures/)
 *   build/tools/gen-textures textures
 *
 * About tiling and stb_perlin
 *   stb_perlin_noise3() takes wrap periods (powers of two only) and
 *   stb_perlin_noise3_wrap_nonpow2() any period up to 256: with a period
 *   equal to the number of noise cells across the texture, the noise repeats
 *   exactly once per texture, so it tiles.  The fractal sums stb_perlin_fbm_noise3(),
 *   stb_perlin_turbulence_noise3() and stb_perlin_ridge_noise3() take no wrap
 *   periods (they only repeat every 256 cells), so a texture sampling them
 *   continuously would show a seam.  The tiling_fbm(), tiling_turbulence() and
 *   tiling_ridge() helpers below therefore repeat stb's formulas octave by
 *   octave with stb_perlin_noise3_wrap_nonpow2(), giving each octave a wrap
 *   period equal to its frequency.  stb's own fractal functions are still used
 *   where tiling cannot suffer: evaluated once per brick, tile or plank at that
 *   cell's (wrapped) index, they give neighbouring cells related shades.
 */

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* libstb.so already contains the implementations of both headers. */
#include <stb_image_write.h>
#include <stb_perlin.h>

/* Compilers may fuse a*b+c into one rounding on machines with FMA, which
 * changes the last bits of the results and so the PNG bytes.  clang obeys
 * this pragma; GCC ignores it, so the build also passes -ffp-contract=off
 * (and GCC does not fuse in -std=c11 mode anyway). */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

enum { TEXTURE_SIZE = 256, CHANNELS = 3 };

/* Colours are sRGB values in [0, 1]; they become bytes only at the end. */
typedef struct {
    float red, green, blue;
} Colour;

/* What a texture function says about one pixel: its colour and a height,
 * used only to shade bumps (mortar lower than bricks, bevelled edges). */
typedef struct {
    Colour colour;
    float height;
} Surface;

typedef struct {
    const char *name; /* file name without ".png" */
    Surface (*surface_at)(int x, int y);
    float relief; /* how strongly height slopes brighten or darken */
} TextureRecipe;

/* ---------------------------------------------------------------------- */
/* Small arithmetic helpers                                               */
/* ---------------------------------------------------------------------- */

static float clamp01(float value)
{
    return value < 0.0f ? 0.0f : value > 1.0f ? 1.0f : value;
}

static float lerp(float from, float to, float amount)
{
    return from + (to - from) * amount;
}

/* 0 below edge0, 1 above edge1, a smooth S-curve between. */
static float smoothstep(float edge0, float edge1, float value)
{
    float t = clamp01((value - edge0) / (edge1 - edge0));
    return t * t * (3.0f - 2.0f * t);
}

static float fraction(float value)
{
    return value - floorf(value);
}

/* A wave of period 1 and range [0, 1] that looks like 0.5 - 0.5 cos(2 pi t):
 * a triangle wave rounded off by smoothstep.  Built from plain arithmetic so
 * that it is bit-for-bit the same everywhere, unlike the C library's cosf. */
static float smooth_wave(float t)
{
    float triangle = 1.0f - fabsf(2.0f * fraction(t) - 1.0f);
    return smoothstep(0.0f, 1.0f, triangle);
}

static Colour rgb(float red, float green, float blue)
{
    Colour colour = { red, green, blue };
    return colour;
}

static Colour mix(Colour from, Colour to, float amount)
{
    return rgb(lerp(from.red, to.red, amount), lerp(from.green, to.green, amount),
               lerp(from.blue, to.blue, amount));
}

static Colour scale(Colour colour, float factor)
{
    return rgb(colour.red * factor, colour.green * factor, colour.blue * factor);
}

/* Texture coordinate of a pixel centre, in [0, 1).  Exact in float. */
static float texture_coordinate(int pixel)
{
    return ((float)pixel + 0.5f) / (float)TEXTURE_SIZE;
}

/* Wraps a possibly negative index into [0, count). */
static int wrap_index(int index, int count)
{
    int wrapped = index % count;
    return wrapped < 0 ? wrapped + count : wrapped;
}

/* A well-mixed 32-bit integer hash of a grid cell, for the few places that
 * need an unrelated random number per cell rather than smooth noise. */
static uint32_t hash_cell(uint32_t x, uint32_t y, uint32_t seed)
{
    uint32_t hash = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    hash ^= hash >> 16;
    hash *= 0x7feb352du;
    hash ^= hash >> 15;
    hash *= 0x846ca68bu;
    hash ^= hash >> 16;
    return hash;
}

/* The hash as a float in [0, 1). */
static float hash_unit(uint32_t x, uint32_t y, uint32_t seed)
{
    return (float)(hash_cell(x, y, seed) >> 8) * (1.0f / 16777216.0f);
}

/* ---------------------------------------------------------------------- */
/* Noise that tiles                                                       */
/* ---------------------------------------------------------------------- */

/* Most noise cells one texture can have: stb_perlin's tables repeat every
 * 256 cells, and 256 cells over 256 pixels is already one cell per pixel. */
enum { MOST_NOISE_CELLS = 256 };

/* One octave of Perlin noise, roughly in [-1, 1], over the texture square
 * (u, v in [0, 1)) with `cells_across` x `cells_down` noise cells.  The wrap
 * period equals the cell count, so the noise repeats exactly once per
 * texture.  `depth` picks a slice of the 3-D noise: different depths give
 * unrelated patterns.  A depth that is not a whole number also keeps the
 * noise from being exactly zero at every cell corner. */
static float tiling_noise(float u, float v, int cells_across, int cells_down, float depth,
                          unsigned char seed)
{
    return stb_perlin_noise3_wrap_nonpow2(u * (float)cells_across, v * (float)cells_down,
                                          depth, cells_across, cells_down, 0, seed);
}

/* The same octave sums as stb_perlin_fbm_noise3 / _turbulence_noise3 /
 * _ridge_noise3 with lacunarity 2 and gain 0.5, but every octave wraps at its
 * own frequency so the sum tiles.  Octaves that would need more cells than
 * the texture has pixels are skipped: they could not be seen anyway. */

/* Fractal Brownian motion: soft, cloudy variation, roughly in [-1, 1]. */
static float tiling_fbm(float u, float v, int cells_across, int cells_down, int octaves,
                        float depth, unsigned char seed)
{
    float sum = 0.0f;
    float amplitude = 1.0f;
    for (int octave = 0; octave < octaves; octave++) {
        int across = cells_across << octave;
        int down = cells_down << octave;
        if (across > MOST_NOISE_CELLS || down > MOST_NOISE_CELLS)
            break;
        sum += amplitude *
               tiling_noise(u, v, across, down, depth, (unsigned char)(seed + octave));
        amplitude *= 0.5f;
    }
    return sum;
}

/* Turbulence: sums |noise|, so it has sharp creases where the noise crosses
 * zero; roughly in [0, 1].  The creases make cracks and flow lines. */
static float tiling_turbulence(float u, float v, int cells_across, int cells_down,
                               int octaves, float depth, unsigned char seed)
{
    float sum = 0.0f;
    float amplitude = 1.0f;
    for (int octave = 0; octave < octaves; octave++) {
        int across = cells_across << octave;
        int down = cells_down << octave;
        if (across > MOST_NOISE_CELLS || down > MOST_NOISE_CELLS)
            break;
        sum += amplitude * fabsf(tiling_noise(u, v, across, down, depth,
                                              (unsigned char)(seed + octave)));
        amplitude *= 0.5f;
    }
    return sum;
}

/* Ridged noise: the creases of turbulence turned into bright ridges, each
 * octave weighted by the one before so detail gathers along the ridges;
 * roughly in [0, 1]. */
static float tiling_ridge(float u, float v, int cells_across, int cells_down, int octaves,
                          float depth, unsigned char seed)
{
    const float offset = 1.0f;
    float sum = 0.0f;
    float amplitude = 0.5f;
    float previous = 1.0f;
    for (int octave = 0; octave < octaves; octave++) {
        int across = cells_across << octave;
        int down = cells_down << octave;
        if (across > MOST_NOISE_CELLS || down > MOST_NOISE_CELLS)
            break;
        float ridge = offset - fabsf(tiling_noise(u, v, across, down, depth,
                                                  (unsigned char)(seed + octave)));
        ridge *= ridge;
        sum += ridge * amplitude * previous;
        previous = ridge;
        amplitude *= 0.5f;
    }
    return sum;
}

/* Distances from a point to the nearest and second-nearest of a set of
 * scattered points, one jittered point per cell of a `cells` x `cells` grid
 * that wraps around the texture ("cellular" or Worley noise).  Where the two
 * distances are nearly equal, the point lies on a border between cells. */
typedef struct {
    float nearest;
    float second_nearest;
    int nearest_cell_x, nearest_cell_y; /* wrapped, for a per-cell colour */
} CellDistances;

static CellDistances tiling_cells(float u, float v, int cells, uint32_t seed)
{
    float x = u * (float)cells;
    float y = v * (float)cells;
    int cell_x = (int)floorf(x);
    int cell_y = (int)floorf(y);
    CellDistances result = { 1e9f, 1e9f, 0, 0 };

    /* Each point lies in the middle 70% of its own cell.  Then the point in
     * the pixel's own cell is at most 1.2 cells away and some point of a
     * neighbouring cell at most 2.1, while any point outside the 5 x 5 block
     * of cells around the pixel is more than 2.15 away: the block is sure to
     * hold the two nearest points. */
    for (int dy = -2; dy <= 2; dy++) {
        for (int dx = -2; dx <= 2; dx++) {
            int neighbour_x = wrap_index(cell_x + dx, cells);
            int neighbour_y = wrap_index(cell_y + dy, cells);
            /* Keeping points off the cell borders also keeps stones from
             * being too thin. */
            float point_x = (float)(cell_x + dx) + 0.15f +
                            0.7f * hash_unit((uint32_t)neighbour_x, (uint32_t)neighbour_y, seed);
            float point_y = (float)(cell_y + dy) + 0.15f +
                            0.7f * hash_unit((uint32_t)neighbour_x, (uint32_t)neighbour_y,
                                             seed + 1u);
            float distance = sqrtf((point_x - x) * (point_x - x) + (point_y - y) * (point_y - y));
            if (distance < result.nearest) {
                result.second_nearest = result.nearest;
                result.nearest = distance;
                result.nearest_cell_x = neighbour_x;
                result.nearest_cell_y = neighbour_y;
            } else if (distance < result.second_nearest) {
                result.second_nearest = distance;
            }
        }
    }
    return result;
}

/* ---------------------------------------------------------------------- */
/* The textures: one function per texture, giving a pixel's surface.      */
/* ---------------------------------------------------------------------- */

/* Red bricks in running bond: 8 courses of 32 pixels, bricks 64 pixels long,
 * every other course shifted by half a brick, with light mortar joints. */
static Surface bricks_at(int x, int y)
{
    enum { COURSE_HEIGHT = 32, BRICK_LENGTH = 64, MORTAR_WIDTH = 4 };
    enum { BRICKS_PER_COURSE = TEXTURE_SIZE / BRICK_LENGTH };
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    int course = y / COURSE_HEIGHT;
    int shifted_x = x + (course % 2) * (BRICK_LENGTH / 2);
    int column = (shifted_x / BRICK_LENGTH) % BRICKS_PER_COURSE;
    float inside_x = (float)(shifted_x % BRICK_LENGTH) + 0.5f;
    float inside_y = (float)(y % COURSE_HEIGHT) + 0.5f;

    /* Distance into the brick from its nearest edge; the mortar sits along
     * the top and left edge of every brick.  Noise on the edge chips it. */
    float edge_distance = fminf(fminf(inside_x - MORTAR_WIDTH, BRICK_LENGTH - inside_x),
                                fminf(inside_y - MORTAR_WIDTH, COURSE_HEIGHT - inside_y));
    edge_distance += 1.6f * tiling_fbm(u, v, 32, 32, 3, 0.31f, 10);
    float in_brick = smoothstep(-0.5f, 0.5f, edge_distance);

    /* A shade per brick, from stb's fbm at the brick's wrapped index, so the
     * wall has lighter and darker bricks; some bricks are over-fired. */
    float shade = stb_perlin_fbm_noise3((float)column * 0.71f + 0.23f,
                                        (float)course * 0.59f + 0.41f, 3.3f, 2.0f, 0.5f, 4);
    Colour brick = mix(rgb(0.80f, 0.36f, 0.24f), rgb(0.88f, 0.52f, 0.34f),
                       clamp01(0.5f + shade));
    if (shade < -0.25f)
        brick = mix(brick, rgb(0.55f, 0.27f, 0.20f), 0.6f);

    /* Clay texture: fine speckle plus a soft blotch across each brick. */
    float speckle = tiling_noise(u, v, 128, 128, 0.63f, 11);
    float blotch = tiling_fbm(u, v, 8, 8, 3, 0.87f, 12);
    brick = scale(brick, 1.0f + 0.12f * speckle + 0.10f * blotch);

    float grain = tiling_fbm(u, v, 64, 64, 2, 0.17f, 13);
    Colour mortar = scale(rgb(0.80f, 0.77f, 0.70f), 1.0f + 0.10f * grain);

    Surface surface;
    surface.colour = mix(mortar, brick, in_brick);
    surface.height = smoothstep(-0.5f, 3.0f, edge_distance) + 0.15f * blotch;
    return surface;
}

/* An 8 x 8 checkerboard of warm white and slate blue.  Crisp on purpose:
 * it is the texture for judging perspective correction and filtering. */
static Surface checker_at(int x, int y)
{
    enum { SQUARE_SIZE = 32 };
    int is_dark = (x / SQUARE_SIZE + y / SQUARE_SIZE) % 2;
    Surface surface;
    surface.colour = is_dark ? rgb(0.33f, 0.47f, 0.66f) : rgb(0.96f, 0.93f, 0.86f);
    surface.height = 0.0f;
    return surface;
}

/* A lawn: thin upright blades (noise squeezed across and stretched down),
 * lit blades over darker shadow between them, and drier yellow patches. */
static Surface grass_at(int x, int y)
{
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    /* Two layers of blades at different sizes; the nearer, larger layer
     * covers the finer one wherever it is bright.  The fine layer calls
     * stb_perlin_noise3 directly, the plain unseeded form of the wrapping
     * noise: its wrap periods must be powers of two, as 128 and 16 are. */
    float fine_blades = stb_perlin_noise3(u * 128.0f, v * 16.0f, 0.41f, 128, 16, 0);
    float long_blades = tiling_noise(u, v, 64, 8, 0.77f, 21);
    float blades = fmaxf(fine_blades, long_blades * 1.2f);
    float blade_light = smoothstep(-0.45f, 0.55f, blades);

    /* Patches: where the lawn is lusher or drier. */
    float patches = tiling_fbm(u, v, 4, 4, 4, 0.29f, 22);
    float dryness = smoothstep(-0.1f, 0.6f, patches);

    Colour shadow = rgb(0.26f, 0.48f, 0.14f);
    Colour lit_blade = rgb(0.52f, 0.82f, 0.28f);
    Colour dry_blade = rgb(0.80f, 0.82f, 0.38f);
    Colour blade = mix(lit_blade, dry_blade, dryness * 0.8f);
    Colour colour = mix(shadow, blade, blade_light);

    /* A faint clover-like mottling so the green is not too uniform. */
    colour = scale(colour, 1.0f + 0.08f * tiling_noise(u, v, 32, 32, 0.53f, 23));

    Surface surface = { colour, 0.0f };
    return surface;
}

/* A lava lake: rivers of glowing yellow-orange molten rock winding between
 * plates of cooling red crust that still glows in places. */
static Surface lava_at(int x, int y)
{
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    /* Warp the sampling point by an amount that itself tiles; since the
     * noise sampled there also tiles, the warped result still tiles. */
    float warp_u = 0.05f * tiling_fbm(u, v, 4, 4, 3, 0.11f, 30);
    float warp_v = 0.05f * tiling_fbm(u, v, 4, 4, 3, 0.59f, 31);

    /* Ridged noise is high along a network of lines: the molten rivers. */
    float rivers = tiling_ridge(u + warp_u, v + warp_v, 4, 4, 5, 0.37f, 32);
    /* Slow variation in how hot the crust still is. */
    float warmth = tiling_fbm(u, v, 2, 2, 4, 0.83f, 33);
    /* Small glowing cracks in the crust where turbulence creases. */
    float cracks = 1.0f - smoothstep(0.0f, 0.05f,
                                     tiling_turbulence(u + warp_v, v + warp_u, 16, 16, 2,
                                                       0.13f, 34));
    float heat = smoothstep(0.45f, 0.95f, rivers) + 0.45f * smoothstep(-0.4f, 0.4f, warmth);
    heat = clamp01(fmaxf(heat, 0.6f * cracks));

    /* Heat ramp: cool crust -> red -> orange -> yellow. */
    Colour crust = rgb(0.55f, 0.20f, 0.10f);
    Colour red = rgb(0.86f, 0.26f, 0.07f);
    Colour orange = rgb(1.00f, 0.56f, 0.12f);
    Colour yellow = rgb(1.00f, 0.90f, 0.48f);
    Colour colour;
    if (heat < 0.35f)
        colour = mix(crust, red, smoothstep(0.0f, 0.35f, heat));
    else if (heat < 0.7f)
        colour = mix(red, orange, smoothstep(0.35f, 0.7f, heat));
    else
        colour = mix(orange, yellow, smoothstep(0.7f, 1.0f, heat));
    /* Crust is rough; the melt is smooth. */
    float rock = tiling_noise(u, v, 64, 64, 0.71f, 35);
    colour = scale(colour, 1.0f + 0.12f * rock * (1.0f - heat));

    Surface surface = { colour, 0.0f };
    return surface;
}

/* White Carrara-like marble: soft grey clouding, a few bold blue-grey veins
 * running roughly diagonally, and a web of hair-thin veins between them. */
static Surface marble_at(int x, int y)
{
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    /* The bold veins follow a wave across u + v.  Its frequency is a whole
     * number, so moving u or v by 1 (one texture) shifts the wave by whole
     * periods: the veins meet themselves at the edges.  The bending noise is
     * kept gentle so the wave still climbs steadily along the diagonal;
     * stronger bending would close the veins into rings. */
    float bend = 0.8f * tiling_fbm(u, v, 2, 2, 4, 0.47f, 40) +
                 0.12f * tiling_turbulence(u, v, 8, 8, 4, 0.19f, 41);
    float wave = smooth_wave(2.0f * (u + v) + bend);
    /* Slow noise makes each vein strong in some places and faint in others. */
    float strength = smoothstep(-0.5f, 0.4f, tiling_fbm(u, v, 2, 2, 3, 0.29f, 43));
    float vein = (1.0f - smoothstep(0.0f, 0.035f, wave)) * (0.35f + 0.65f * strength);
    float halo = (1.0f - smoothstep(0.0f, 0.2f, wave)) * strength;

    /* Hair-thin veins: where smooth noise crosses zero it draws meandering
     * lines that split and rejoin. */
    float web = fabsf(tiling_fbm(u, v, 3, 3, 5, 0.13f, 42));
    float thin_vein = (1.0f - smoothstep(0.0f, 0.04f, web)) *
                      smoothstep(-0.3f, 0.3f, tiling_fbm(u, v, 4, 4, 2, 0.61f, 45));

    float clouds = tiling_fbm(u, v, 4, 4, 5, 0.71f, 44);
    Colour stone = mix(rgb(0.87f, 0.86f, 0.84f), rgb(0.72f, 0.73f, 0.77f),
                       smoothstep(-0.4f, 0.5f, clouds));
    stone = mix(stone, rgb(0.72f, 0.74f, 0.79f), 0.5f * halo);
    Colour colour = mix(stone, rgb(0.56f, 0.60f, 0.67f), 0.8f * thin_vein);
    colour = mix(colour, rgb(0.38f, 0.42f, 0.51f), 0.9f * vein);

    Surface surface = { colour, 0.0f };
    return surface;
}

/* Brushed steel plates held by rivets, with rust blooming in patches and
 * streaking down from the rivets. */
static Surface metal_rust_at(int x, int y)
{
    enum { PLATE_HEIGHT = 128, RIVET_SPACING = 32, RIVET_ROW = 10 };
    const float rivet_radius = 5.0f;
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    /* Brushing: long horizontal streaks, i.e. noise with few cells across
     * and many cells down. */
    float streaks = tiling_noise(u, v, 2, 128, 0.19f, 50) +
                    0.5f * tiling_noise(u, v, 4, 256, 0.67f, 51);
    float sheen = tiling_fbm(u, v, 2, 2, 2, 0.37f, 56);
    Colour steel = scale(rgb(0.70f, 0.72f, 0.75f), 1.0f + 0.10f * streaks + 0.06f * sheen);

    /* A seam along the top of each plate, a row of rivets just below it. */
    float inside_y = (float)(y % PLATE_HEIGHT) + 0.5f;
    float rivet_dx = (float)(x % RIVET_SPACING) + 0.5f - RIVET_SPACING / 2.0f;
    float rivet_dy = inside_y - RIVET_ROW;
    float rivet_distance = sqrtf(rivet_dx * rivet_dx + rivet_dy * rivet_dy);
    float rivet = 1.0f - smoothstep(rivet_radius - 1.0f, rivet_radius + 0.5f, rivet_distance);
    float seam = 1.0f - smoothstep(0.5f, 2.0f, fminf(inside_y, PLATE_HEIGHT - inside_y));

    /* Rust: patches where slow noise is high, their edges frayed by finer
     * turbulence so they look eaten rather than painted.  Around each patch
     * a wider, fainter orange stain fades into the steel. */
    float patches = tiling_fbm(u, v, 4, 4, 5, 0.23f, 52) +
                    0.3f * tiling_turbulence(u, v, 16, 16, 3, 0.91f, 53);
    float rust_amount = smoothstep(0.32f, 0.58f, patches);
    float stain = smoothstep(0.0f, 0.4f, patches);

    /* Water running off each rivet leaves a rust streak that narrows and
     * fades as it goes down, broken up by noise. */
    float below_rivet = inside_y - RIVET_ROW;
    if (below_rivet > 0.0f) {
        float fade = 1.0f - smoothstep(0.0f, 50.0f, below_rivet);
        float width = 1.0f - smoothstep(1.0f, 2.5f + 2.5f * fade, fabsf(rivet_dx));
        float broken = smoothstep(-0.3f, 0.4f, tiling_noise(u, v, 32, 16, 0.39f, 54));
        float drip = width * fade * broken;
        stain = fmaxf(stain, drip);
        rust_amount = fmaxf(rust_amount, 0.45f * drip);
    }

    /* Thin rust is a light orange stain; thick rust is dark and flaky,
     * pitted with darker specks. */
    float flakes = tiling_fbm(u, v, 32, 32, 3, 0.57f, 55);
    float pits = smoothstep(0.25f, 0.5f, tiling_noise(u, v, 128, 128, 0.83f, 57));
    Colour thick_rust = mix(rgb(0.70f, 0.38f, 0.19f), rgb(0.52f, 0.27f, 0.14f),
                            smoothstep(-0.3f, 0.4f, flakes));
    thick_rust = scale(thick_rust, 1.0f - 0.25f * pits);
    Colour colour = mix(steel, rgb(0.76f, 0.55f, 0.38f), 0.55f * stain);
    colour = mix(colour, thick_rust, rust_amount);

    /* The seam is a dark groove; rivets are bright domes with a shadow
     * ring where they meet the plate. */
    colour = scale(colour, 1.0f - 0.35f * seam);
    float rivet_rim = smoothstep(rivet_radius - 1.5f, rivet_radius, rivet_distance) *
                      (1.0f - smoothstep(rivet_radius + 0.5f, rivet_radius + 1.5f,
                                         rivet_distance));
    colour = scale(colour, 1.0f - 0.3f * rivet_rim);
    colour = mix(colour, scale(steel, 1.12f), rivet * (1.0f - 0.6f * rust_amount));

    Surface surface;
    surface.colour = colour;
    /* Domed rivets, a groove at the seam, and thick rust slightly raised. */
    surface.height = 3.0f * rivet * (1.0f - rivet_distance / (rivet_radius + 1.0f)) -
                     1.5f * seam + 0.6f * rust_amount * flakes;
    return surface;
}

/* Wood grain shared by the wood and planks textures: the growth rings of a
 * flat-sawn board show as long, gently wandering bands along it (along u),
 * light earlywood darkening into a thin latewood line, crossed by fine
 * fibres.  `ring_count` bands fit down the texture; it is a whole number so
 * the bands meet at the top and bottom edges.  `depth` picks the piece of
 * wood.  Returns how dark the pixel is: 0 for earlywood, 1 for latewood. */
static float wood_grain(float u, float v, int ring_count, float depth)
{
    /* The noise bending the rings has only 1 or 2 cells across but several
     * down, so the bends are long and slow like a real board's. */
    float bend = tiling_fbm(u, v, 1, 3, 4, depth, 90) +
                 0.12f * tiling_noise(u, v, 4, 32, depth, 91);
    float ring = fraction(v * (float)ring_count + 1.4f * bend);
    float darkening = 0.35f * ring;
    float latewood = smoothstep(0.78f, 0.93f, ring) * (1.0f - smoothstep(0.95f, 1.0f, ring));
    float fibres = tiling_noise(u, v, 8, 256, depth, 92) +
                   0.5f * tiling_noise(u, v, 4, 128, depth, 93);
    return clamp01(fmaxf(darkening, latewood) + 0.10f * fibres);
}

/* Oak floorboards: eight rows of narrow boards, each 128 pixels long with
 * the joints staggered, each with its own grain and shade. */
static Surface planks_at(int x, int y)
{
    enum { BOARD_WIDTH = 32, BOARD_LENGTH = 128, GAP_WIDTH = 2 };
    enum { BOARDS_PER_ROW = TEXTURE_SIZE / BOARD_LENGTH };
    /* Where each row's joints fall: scattered, so that neither neighbouring
     * rows nor every other row line up into a visible staircase. */
    static const int joint_offset[TEXTURE_SIZE / BOARD_WIDTH] = { 0, 80, 40, 112,
                                                                  16, 64, 96, 32 };
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    int row = y / BOARD_WIDTH;
    int shifted_x = wrap_index(x - joint_offset[row], TEXTURE_SIZE);
    int board = row * BOARDS_PER_ROW + shifted_x / BOARD_LENGTH;
    float inside_x = (float)(shifted_x % BOARD_LENGTH) + 0.5f;
    float inside_y = (float)(y % BOARD_WIDTH) + 0.5f;
    float edge_distance = fminf(fminf(inside_x - GAP_WIDTH, BOARD_LENGTH - inside_x),
                                fminf(inside_y - GAP_WIDTH, BOARD_WIDTH - inside_y));

    /* Each board takes its grain from its own depth in the noise, so the
     * grain does not run on from one board into the next. */
    float grain = wood_grain(u, v, 36, 0.5f + 1.37f * (float)board);

    /* A shade per board from stb's ridged noise at the board's index (it
     * gives values from about 0.1 to 0.7 here). */
    float shade = smoothstep(0.1f, 0.7f, stb_perlin_ridge_noise3((float)board * 0.83f + 0.37f,
                                                                 0.61f, 1.9f, 2.0f, 0.5f,
                                                                 1.0f, 3));
    Colour light = mix(rgb(0.90f, 0.72f, 0.48f), rgb(0.76f, 0.54f, 0.32f), shade);
    Colour wood = mix(light, rgb(0.58f, 0.39f, 0.22f), grain);

    float in_board = smoothstep(-0.5f, 0.5f, edge_distance);
    Surface surface;
    surface.colour = mix(rgb(0.34f, 0.23f, 0.13f), wood, in_board);
    surface.height = smoothstep(-0.5f, 2.5f, edge_distance);
    return surface;
}

/* Cobblestones: rounded grey stones of irregular shape, each with its own
 * warm or cool tint, set in darker packed earth. */
static Surface stone_at(int x, int y)
{
    enum { STONES_ACROSS = 6 };
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    /* Bend the sampling point a little so the stones are not polygons. */
    float wobble_u = 0.012f * tiling_fbm(u, v, 8, 8, 3, 0.21f, 70);
    float wobble_v = 0.012f * tiling_fbm(u, v, 8, 8, 3, 0.79f, 71);
    CellDistances cells = tiling_cells(u + wobble_u, v + wobble_v, STONES_ACROSS, 72);

    /* The gap between two stones is where the two nearest points are about
     * equally far; the stone is domed, highest near its point. */
    float border = cells.second_nearest - cells.nearest;
    float in_stone = smoothstep(0.06f, 0.12f, border);
    float dome = 1.0f - smoothstep(0.0f, 0.8f, cells.nearest);

    uint32_t stone_x = (uint32_t)cells.nearest_cell_x;
    uint32_t stone_y = (uint32_t)cells.nearest_cell_y;
    float brightness = 0.58f + 0.22f * hash_unit(stone_x, stone_y, 73);
    float warmth = hash_unit(stone_x, stone_y, 74);
    Colour stone = mix(rgb(brightness * 0.95f, brightness * 0.97f, brightness * 1.04f),
                       rgb(brightness * 1.06f, brightness * 0.98f, brightness * 0.88f), warmth);

    /* Rough, speckled surface like granite. */
    float speckle = tiling_noise(u, v, 128, 128, 0.43f, 75);
    float roughness = tiling_fbm(u, v, 16, 16, 4, 0.93f, 76);
    stone = scale(stone, 1.0f + 0.10f * speckle + 0.12f * roughness);

    Colour earth = scale(rgb(0.42f, 0.38f, 0.32f), 1.0f + 0.15f * roughness);
    Surface surface;
    surface.colour = mix(earth, stone, in_stone);
    surface.height = in_stone * (0.6f + 0.8f * dome) + 0.1f * roughness;
    return surface;
}

/* Victorian floor tiles: cream octagons with small blue diamonds where four
 * octagons meet, separated by grey grout. */
static Surface tiles_at(int x, int y)
{
    enum { TILE_SIZE = 64 };
    const float half_size = TILE_SIZE / 2.0f;
    const float corner_cut = 44.0f;    /* |x| + |y| beyond this is the diamond */
    const float grout_half_width = 1.5f;
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    /* Pixel position relative to the centre of its tile, and its distance
     * from the nearest octagon edge: the square sides or the cut corners.
     * 0.7071 = 1/sqrt(2) turns |x| + |y| into a distance. */
    float local_x = fabsf((float)(x % TILE_SIZE) + 0.5f - half_size);
    float local_y = fabsf((float)(y % TILE_SIZE) + 0.5f - half_size);
    float corner_distance = (corner_cut - (local_x + local_y)) * 0.70710678f;
    float side_distance = half_size - fmaxf(local_x, local_y);

    Colour grout = scale(rgb(0.66f, 0.65f, 0.62f),
                         1.0f + 0.08f * tiling_noise(u, v, 64, 64, 0.27f, 80));
    Colour colour;
    float height;
    if (corner_distance < -grout_half_width) {
        /* Inside the small diamond (shared by four tiles, no grout across). */
        float inside = -corner_distance - grout_half_width;
        Colour diamond = rgb(0.22f, 0.36f, 0.62f);
        colour = mix(grout, diamond, smoothstep(0.0f, 1.0f, inside));
        height = smoothstep(0.0f, 2.5f, inside);
    } else {
        float inside = fminf(corner_distance, side_distance) - grout_half_width;
        /* A shade per tile from stb's turbulence at the tile's index. */
        int tile_column = x / TILE_SIZE;
        int tile_row = y / TILE_SIZE;
        /* (Values run from about 0.1 to 0.85 here.) */
        float shade = smoothstep(0.1f, 0.85f,
                                 stb_perlin_turbulence_noise3((float)tile_column * 0.67f + 0.29f,
                                                              (float)tile_row * 0.73f + 0.11f,
                                                              2.7f, 2.0f, 0.5f, 3));
        Colour glaze = mix(rgb(0.93f, 0.90f, 0.82f), rgb(0.86f, 0.80f, 0.70f), shade);
        /* Glazes are not perfectly even: faint clouding. */
        glaze = scale(glaze, 1.0f + 0.05f * tiling_fbm(u, v, 16, 16, 3, 0.77f, 81));
        colour = mix(grout, glaze, smoothstep(0.0f, 1.0f, inside));
        height = smoothstep(0.0f, 2.5f, inside);
    }
    Surface surface = { colour, height };
    return surface;
}

/* A wide board of reddish wood seen along its length: broad growth rings
 * drifting across it, with slow changes of tone. */
static Surface wood_at(int x, int y)
{
    float u = texture_coordinate(x);
    float v = texture_coordinate(y);

    float grain = wood_grain(u, v, 9, 0.33f);
    float tone = smoothstep(-0.4f, 0.4f, tiling_fbm(u, v, 2, 2, 3, 0.89f, 94));
    Colour earlywood = mix(rgb(0.90f, 0.64f, 0.44f), rgb(0.82f, 0.55f, 0.36f), tone);
    Colour colour = mix(earlywood, rgb(0.55f, 0.30f, 0.17f), grain);

    Surface surface = { colour, 0.0f };
    return surface;
}

/* Listed in the byte order of their names, the order the files sort in. */
static const TextureRecipe recipes[] = {
    { "bricks", bricks_at, 0.10f },
    { "checker", checker_at, 0.0f },
    { "grass", grass_at, 0.0f },
    { "lava", lava_at, 0.0f },
    { "marble", marble_at, 0.0f },
    { "metal-rust", metal_rust_at, 0.06f },
    { "planks", planks_at, 0.10f },
    { "stone", stone_at, 0.12f },
    { "tiles", tiles_at, 0.10f },
    { "wood", wood_at, 0.0f },
};

/* ---------------------------------------------------------------------- */
/* Rendering and writing                                                  */
/* ---------------------------------------------------------------------- */

typedef struct {
    Colour colour[TEXTURE_SIZE][TEXTURE_SIZE]; /* [y][x] */
    float height[TEXTURE_SIZE][TEXTURE_SIZE];
    unsigned char pixels[TEXTURE_SIZE * TEXTURE_SIZE * CHANNELS];
} Canvas;

static unsigned char to_byte(float value)
{
    return (unsigned char)(clamp01(value) * 255.0f + 0.5f);
}

/* Fills the canvas with one texture.  Bumps are lit as if by a light at the
 * top left: a surface rising towards the bottom right faces the light.
 * Neighbours wrap around the edges, so the lighting tiles too. */
static void render(const TextureRecipe *recipe, Canvas *canvas)
{
    for (int y = 0; y < TEXTURE_SIZE; y++) {
        for (int x = 0; x < TEXTURE_SIZE; x++) {
            Surface surface = recipe->surface_at(x, y);
            canvas->colour[y][x] = surface.colour;
            canvas->height[y][x] = surface.height;
        }
    }

    for (int y = 0; y < TEXTURE_SIZE; y++) {
        int above = wrap_index(y - 1, TEXTURE_SIZE);
        int below = wrap_index(y + 1, TEXTURE_SIZE);
        for (int x = 0; x < TEXTURE_SIZE; x++) {
            int left = wrap_index(x - 1, TEXTURE_SIZE);
            int right = wrap_index(x + 1, TEXTURE_SIZE);
            float slope = (canvas->height[y][right] - canvas->height[y][left]) +
                          (canvas->height[below][x] - canvas->height[above][x]);
            float light = 1.0f + recipe->relief * slope;
            if (light < 0.6f)
                light = 0.6f;
            if (light > 1.3f)
                light = 1.3f;
            Colour lit = scale(canvas->colour[y][x], light);
            unsigned char *pixel = &canvas->pixels[(y * TEXTURE_SIZE + x) * CHANNELS];
            pixel[0] = to_byte(lit.red);
            pixel[1] = to_byte(lit.green);
            pixel[2] = to_byte(lit.blue);
        }
    }
}

/* stbi_write_png() ignores errors from fwrite() and fclose(), so the PNG
 * goes through stbi_write_png_to_func() into our own FILE, whose errors we
 * check. */
typedef struct {
    FILE *file;
    int write_failed;
    int saved_errno;
} PngSink;

static void write_to_sink(void *context, void *data, int size)
{
    PngSink *sink = context;
    if (sink->write_failed)
        return;
    if (fwrite(data, 1, (size_t)size, sink->file) != (size_t)size) {
        sink->write_failed = 1;
        sink->saved_errno = errno;
    }
}

static char *join_path(const char *directory, const char *name, const char *suffix)
{
    size_t directory_length = strlen(directory);
    int needs_slash = directory_length > 0 && directory[directory_length - 1] != '/';
    size_t length = directory_length + 1 + strlen(name) + strlen(suffix) + 1;
    char *path = malloc(length);
    if (path != NULL)
        snprintf(path, length, "%s%s%s%s", directory, needs_slash ? "/" : "", name, suffix);
    return path;
}

/* Encodes the pixels as PNG into the file at `path`.  Returns NULL on
 * success, otherwise the reason for the failure. */
static const char *encode_png_file(const char *path, const unsigned char *pixels)
{
    FILE *file = fopen(path, "wb");
    if (file == NULL)
        return strerror(errno);

    PngSink sink = { file, 0, 0 };
    int encoded = stbi_write_png_to_func(write_to_sink, &sink, TEXTURE_SIZE, TEXTURE_SIZE,
                                         CHANNELS, pixels, TEXTURE_SIZE * CHANNELS);
    /* Buffered data may only fail to reach the disk at fflush or fclose. */
    if (fflush(file) != 0 && !sink.write_failed) {
        sink.write_failed = 1;
        sink.saved_errno = errno;
    }
    if (fclose(file) != 0 && !sink.write_failed) {
        sink.write_failed = 1;
        sink.saved_errno = errno;
    }
    if (!encoded)
        return "PNG encoding failed (out of memory?)";
    if (sink.write_failed)
        return sink.saved_errno != 0 ? strerror(sink.saved_errno) : "write error";
    return NULL;
}

/* Writes the pixels to DIRECTORY/NAME.png.tmp, then renames that over
 * DIRECTORY/NAME.png, so a failure never leaves a half-written PNG behind.
 * Returns 0 on success; on failure prints why and returns -1. */
static int write_png(const char *directory, const char *name, const unsigned char *pixels)
{
    char *final_path = join_path(directory, name, ".png");
    char *temporary_path = join_path(directory, name, ".png.tmp");
    const char *reason = NULL;

    if (final_path == NULL || temporary_path == NULL) {
        reason = "out of memory";
    } else {
        reason = encode_png_file(temporary_path, pixels);
        if (reason == NULL && rename(temporary_path, final_path) != 0)
            reason = strerror(errno);
        if (reason != NULL)
            remove(temporary_path);
    }

    if (reason != NULL) {
        if (final_path != NULL)
            fprintf(stderr, "gen-textures: cannot write %s: %s\n", final_path, reason);
        else
            fprintf(stderr, "gen-textures: cannot write %s/%s.png: %s\n", directory, name,
                    reason);
    }
    free(final_path);
    free(temporary_path);
    return reason == NULL ? 0 : -1;
}

static void print_usage(FILE *stream)
{
    fprintf(stream,
            "usage: gen-textures OUTPUT_DIR\n"
            "Writes luz's procedural textures (256x256 RGB PNG, seamlessly tiling)\n"
            "into the existing directory OUTPUT_DIR, replacing files of the same name.\n"
            "The output is the same, byte for byte, on every run.\n");
}

int main(int argc, char **argv)
{
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        print_usage(stdout);
        return 0;
    }
    if (argc != 2) {
        fprintf(stderr, "gen-textures: expected exactly one argument, OUTPUT_DIR "
                        "(try 'gen-textures --help')\n");
        return 2;
    }
    const char *directory = argv[1];
    if (directory[0] == '-') {
        /* A directory whose name starts with '-' can be given as ./-name. */
        fprintf(stderr, "gen-textures: unknown option '%s' (try 'gen-textures --help')\n",
                directory);
        return 2;
    }
    if (directory[0] == '\0') {
        fprintf(stderr, "gen-textures: OUTPUT_DIR is empty (try 'gen-textures --help')\n");
        return 2;
    }

    /* About 1.3 MB: too big to be comfortable on the stack. */
    Canvas *canvas = malloc(sizeof *canvas);
    if (canvas == NULL) {
        fprintf(stderr, "gen-textures: out of memory\n");
        return 2;
    }
    int status = 0;
    for (size_t index = 0; index < sizeof recipes / sizeof recipes[0]; index++) {
        render(&recipes[index], canvas);
        if (write_png(directory, recipes[index].name, canvas->pixels) != 0) {
            status = 2;
            break;
        }
    }
    free(canvas);
    return status;
}
