/*
 * view.c: pictures of the pipeline's stages (--view), drawn by the pipeline.
 *
 * In:  what the raster stage left for a band of rows (the depth buffer, the
 *      visibility buffer of nearest triangle ids, and for the overdraw view
 *      a count of depth tests per pixel), the set-up triangles, the frame.
 * Out: the band's colour buffer, showing the view the frame asks for
 *      (luz_uniforms.show; the palettes are in luz/view.h), in the
 *      framebuffer's channel order. As in fragment.c, every pixel is
 *      written, the background's too: nothing clears colour beforehand.
 *
 * Nothing here renders a second time: every view reads what the real
 * stages computed for this frame, through the same functions the fragment
 * stage uses (luz_fragment_interpolate, luz_texture_level_of_detail). Only
 * the last step, the colour a pixel gets, is the view's own:
 *
 *   depth      the depth buffer, every pixel (the background is the far
 *              plane, black)
 *   normals    N = normalize(interpolated normal), shown as (N + 1) / 2
 *   uv         (fract(u), fract(v), 0): REPEAT's fractional part
 *   mip        the level(s) of detail the sampler used: with trilinear
 *              filtering, lambda <= 0 reads level 0, otherwise levels
 *              floor(lambda) and floor(lambda) + 1 (clamped to the last)
 *              mixed by fract(lambda), exactly as texture.c does; nearest
 *              and bilinear read level 0 only
 *   overdraw   the count raster.c kept (luz_raster_triangle_counting)
 *   bands      the shaded image (fragment.c), dimmed, under the tint of the
 *              thread that drew this band, background included
 *   triangles  each winning triangle's colour, darkened (times
 *              LUZ_VIEW_TRIANGLE_EDGE_SHADE) where a neighbouring pixel's
 *              centre is outside that triangle: the pixels along an edge,
 *              each still in its own triangle's hue, so that which of two
 *              triangles owns each pixel of their shared edge can be read
 *              off the picture (the fill rule gives it to one of them).
 *              Coverage is the rasteriser's own test (the fixed-point edge
 *              functions with the top-left rule folded in), evaluated at
 *              the neighbour's centre; it reads no other row, so a band
 *              needs nothing from the bands around it.
 *
 * depth and overdraw colour the background by their palettes (it has a
 * depth, the far plane, and a count, 0); the others give it the clear
 * colour, as the colour view does.
 *
 * The views use the plain one-pixel-at-a-time fragment stage (fragment.c),
 * never the SIMD one: they are for looking, not for speed. This file is
 * deliberately not on the colour view's path (frame.c calls it only for
 * the other views).
 */
#include <math.h>
#include <string.h>

#include "renderer/pipeline.h"
#include "luz/texture.h"
#include "luz/view.h"

/* ---- palettes (luz/view.h) ---------------------------------------------- */

bool luz_view_from_name(const char *name, luz_view *view)
{
    for (int v = 0; v < LUZ_VIEW_COUNT; v++) {
        if (strcmp(name, luz_view_name((luz_view)v)) == 0) {
            *view = (luz_view)v;
            return true;
        }
    }
    return false;
}

const char *luz_view_legend(luz_view view)
{
    switch (view) {
    case LUZ_VIEW_COLOR: return "color: the shaded image";
    case LUZ_VIEW_DEPTH: return "depth: eye distance, log scale; white near, black far";
    case LUZ_VIEW_NORMALS: return "normals: (N + 1) / 2; +x red, +y green, +z blue";
    case LUZ_VIEW_UV: return "uv: red = fract(u), green = fract(v)";
    case LUZ_VIEW_MIP:
        return "mip: level 0 red, 1 orange, 2 yellow, 3 green, 4 cyan, 5 blue, 6 violet, "
               "7 magenta, 8 white, 9 and up grey, untextured dark grey; blended by "
               "fract(lambda)";
    case LUZ_VIEW_OVERDRAW:
        return "overdraw: depth tests per pixel, 0 black, 1 dark blue, 2 blue, 3 cyan, "
               "4 green, 5 yellow, 6 orange, 7 red, 8 or more white";
    case LUZ_VIEW_BANDS:
        return "bands: tint = thread; 0 orange, 1 blue, 2 green, 3 magenta, others hues "
               "around the circle";
    case LUZ_VIEW_TRIANGLES:
        return "triangles: one colour per triangle (ids 1, 2, ... in draw order), darker "
               "where a neighbouring pixel is another triangle's";
    case LUZ_VIEW_COUNT: break;
    }
    return "";
}

luz_vec3 luz_view_overdraw_colour(uint32_t count)
{
    static const luz_vec3 ramp[9] = {
        {0.00f, 0.00f, 0.00f}, {0.05f, 0.10f, 0.45f}, {0.10f, 0.35f, 0.90f},
        {0.10f, 0.75f, 0.85f}, {0.30f, 0.85f, 0.25f}, {0.95f, 0.90f, 0.20f},
        {1.00f, 0.55f, 0.10f}, {0.90f, 0.15f, 0.10f}, {1.00f, 1.00f, 1.00f},
    };
    return ramp[count < 8 ? count : 8];
}

luz_vec3 luz_view_mip_colour(int level)
{
    static const luz_vec3 levels[9] = {
        {0.90f, 0.15f, 0.15f}, {0.95f, 0.60f, 0.10f}, {0.95f, 0.95f, 0.20f},
        {0.30f, 0.85f, 0.25f}, {0.15f, 0.80f, 0.85f}, {0.20f, 0.40f, 0.95f},
        {0.60f, 0.30f, 0.90f}, {0.90f, 0.30f, 0.80f}, {0.95f, 0.95f, 0.95f},
    };
    if (level < 0) level = 0;
    return level < 9 ? levels[level] : (luz_vec3){0.60f, 0.60f, 0.60f};
}

/* A colour from a hue in [0, 1) at the given saturation and value. */
static luz_vec3 from_hsv(float hue, float saturation, float value)
{
    float h = (hue - floorf(hue)) * 6.0f;
    int sector = (int)h;
    float f = h - (float)sector;
    float p = value * (1.0f - saturation), q = value * (1.0f - saturation * f);
    float t = value * (1.0f - saturation * (1.0f - f));
    switch (sector) {
    case 0: return (luz_vec3){value, t, p};
    case 1: return (luz_vec3){q, value, p};
    case 2: return (luz_vec3){p, value, t};
    case 3: return (luz_vec3){p, q, value};
    case 4: return (luz_vec3){t, p, value};
    default: return (luz_vec3){value, p, q};
    }
}

luz_vec3 luz_view_thread_colour(int worker)
{
    static const luz_vec3 first[4] = {
        {1.00f, 0.55f, 0.10f}, {0.10f, 0.55f, 1.00f}, {0.30f, 0.90f, 0.20f},
        {0.90f, 0.20f, 0.85f},
    };
    if (worker >= 0 && worker < 4) return first[worker];
    return from_hsv(0.1f + 0.618034f * (float)worker, 0.8f, 0.95f);
}

luz_vec3 luz_view_triangle_colour(uint32_t id)
{
    /* Golden-ratio steps around the hue circle: consecutive ids, such as
     * the two triangles of a face, land far apart. */
    double hue = fmod((double)id * 0.6180339887498949, 1.0);
    return from_hsv((float)hue, 0.55f, (id & 1u) ? 0.95f : 0.78f);
}

float luz_view_depth_brightness(float depth, const luz_mat4 *projection)
{
    const double a = projection->m[10], b = projection->m[14];
    const double near = b / (a - 1.0), far = b / (a + 1.0);
    double z_ndc = 2.0 * depth - 1.0;
    double distance = b / (z_ndc + a);
    if (!(distance > near)) distance = near;   /* also for a NaN */
    if (distance > far) distance = far;
    return (float)(1.0 - log(distance / near) / log(far / near));
}

/* ---- drawing the views ------------------------------------------------- */

static luz_vec3 mix(luz_vec3 a, luz_vec3 b, float t)
{
    return luz_vec3_add(luz_vec3_scale(a, 1.0f - t), luz_vec3_scale(b, t));
}

/* The mip levels the sampler reads at this fragment, as colours. */
static luz_vec3 mip_colour(const luz_texture *texture, luz_filter filter,
                           const luz_fragment *fragment)
{
    if (!texture) return LUZ_VIEW_MIP_UNTEXTURED;
    if (filter != LUZ_FILTER_TRILINEAR) return luz_view_mip_colour(0);
    float lambda = luz_texture_level_of_detail(texture, fragment->du_dx, fragment->dv_dx,
                                               fragment->du_dy, fragment->dv_dy);
    luz_texture_mip_pair levels = luz_texture_mip_levels(texture, lambda);
    return mix(luz_view_mip_colour(levels.lower), luz_view_mip_colour(levels.upper),
               levels.blend);
}

double luz_view_edge_distance(const luz_triangle *triangle, int x, int y)
{
    const int64_t sample_x = (int64_t)x * LUZ_SUBPIXEL_ONE + LUZ_SUBPIXEL_ONE / 2;
    const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + LUZ_SUBPIXEL_ONE / 2;
    double nearest = INFINITY;
    for (int k = 0; k < 3; k++) {
        const luz_edge *edge = &triangle->edges[k];
        /* E is the doubled area of the sample with the edge, in sub-pixel
         * units squared; over the edge's length it is a distance. */
        double e = (double)(edge->a * sample_x + edge->b * sample_y + edge->c);
        double length = sqrt((double)edge->a * (double)edge->a +
                             (double)edge->b * (double)edge->b);
        double distance = fabs(e) / (length * LUZ_SUBPIXEL_ONE);
        if (distance < nearest) nearest = distance;
    }
    return nearest;
}

/* Whether the triangle covers pixel (x, y)'s centre: the rasteriser's
 * test, E >= 0 for the three edge functions, in the same exact integers
 * (raster.c computes the same values a row at a time). */
static bool covers(const luz_triangle *triangle, int x, int y)
{
    const int64_t sample_x = (int64_t)x * LUZ_SUBPIXEL_ONE + LUZ_SUBPIXEL_ONE / 2;
    const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + LUZ_SUBPIXEL_ONE / 2;
    return luz_edges_cover(triangle->edges, sample_x, sample_y);
}

/* A pixel of the triangle is on its edge when one of its four neighbours
 * in the image lies outside it: that neighbour belongs to another
 * triangle, or to none. (A neighbour inside the triangle that a nearer
 * triangle won is marked on the nearer one's side, whose edge it is.) */
bool luz_view_on_edge(const luz_triangle *triangle, int x, int y, int width, int height)
{
    return (x > 0 && !covers(triangle, x - 1, y)) ||
           (x + 1 < width && !covers(triangle, x + 1, y)) ||
           (y > 0 && !covers(triangle, x, y - 1)) ||
           (y + 1 < height && !covers(triangle, x, y + 1));
}

luz_vec3 luz_view_bands_colour(const uint8_t rgb[3], int worker_index)
{
    const luz_vec3 tint = luz_view_thread_colour(worker_index);
    return (luz_vec3){
        (1.0f - LUZ_VIEW_BANDS_TINT) * (rgb[0] / 255.0f) + LUZ_VIEW_BANDS_TINT * tint.x,
        (1.0f - LUZ_VIEW_BANDS_TINT) * (rgb[1] / 255.0f) + LUZ_VIEW_BANDS_TINT * tint.y,
        (1.0f - LUZ_VIEW_BANDS_TINT) * (rgb[2] / 255.0f) + LUZ_VIEW_BANDS_TINT * tint.z,
    };
}

/* Mixes the tint into the rows fragment.c has just shaded, reading each
 * channel back from the byte the channel order put it in. */
void luz_view_tint_rows(luz_framebuffer *framebuffer, int first_row, int end_row,
                        int worker_index)
{
    const luz_pixel_layout layout = luz_pixel_layout_of(framebuffer->channel_order);
    const size_t begin = (size_t)first_row * framebuffer->width;
    const size_t end = (size_t)end_row * framebuffer->width;
    for (size_t i = begin; i < end; i++) {
        uint8_t *pixel = framebuffer->colour + i * 4;
        const uint8_t rgb[3] = {pixel[layout.red], pixel[1], pixel[layout.blue]};
        luz_pixel_write(pixel, layout, luz_view_bands_colour(rgb, worker_index));
    }
}

luz_vec3 luz_view_pixel(const luz_uniforms *uniforms, const luz_draw *draws,
                        const luz_triangle *const *by_id, const luz_framebuffer *framebuffer,
                        int x, int y, const uint32_t *overdraw)
{
    const luz_view view = uniforms->show;
    const size_t index = (size_t)y * framebuffer->width + x;
    const uint32_t id = framebuffer->visibility[index];
    /* Two views colour the background by their palettes: it has a depth
     * (the far plane) and a count of depth tests (0). The others give it
     * the clear colour, below. */
    if (view == LUZ_VIEW_DEPTH) {
        float grey = luz_view_depth_brightness(framebuffer->depth[index], &uniforms->projection);
        return (luz_vec3){grey, grey, grey};
    }
    if (view == LUZ_VIEW_OVERDRAW)
        return luz_view_overdraw_colour(overdraw ? overdraw[index] : 0);
    if (id == 0) return uniforms->clear_colour;

    const luz_triangle *triangle = by_id[id];
    const luz_material *material = &draws[triangle->draw_index].material;
    luz_fragment fragment;
    if (view != LUZ_VIEW_TRIANGLES) luz_fragment_interpolate(triangle, x, y, &fragment);
    switch (view) {
    case LUZ_VIEW_NORMALS: {
        luz_vec3 n = luz_vec3_normalize(fragment.normal);
        return (luz_vec3){n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f, n.z * 0.5f + 0.5f};
    }
    case LUZ_VIEW_UV:
        return (luz_vec3){luz_texture_repeat(fragment.uv.x), luz_texture_repeat(fragment.uv.y),
                          0.0f};
    case LUZ_VIEW_MIP:
        return mip_colour(material->texture, material->filter, &fragment);
    case LUZ_VIEW_TRIANGLES: {
        const luz_vec3 colour = luz_view_triangle_colour(id);
        return luz_view_on_edge(triangle, x, y, framebuffer->width, framebuffer->height)
                   ? luz_vec3_scale(colour, LUZ_VIEW_TRIANGLE_EDGE_SHADE)
                   : colour;
    }
    default:
        return (luz_vec3){0.0f, 0.0f, 0.0f};
    }
}

uint64_t luz_view_shade_rows(const luz_uniforms *uniforms, const luz_draw *draws,
                             const luz_triangle *const *by_id, luz_framebuffer *framebuffer,
                             int first_row, int end_row, const uint32_t *overdraw,
                             int worker_index)
{
    if (uniforms->show == LUZ_VIEW_BANDS) {
        uint64_t shaded = luz_fragment_shade_rows(uniforms, draws, by_id, framebuffer,
                                                  first_row, end_row);
        luz_view_tint_rows(framebuffer, first_row, end_row, worker_index);
        return shaded;
    }

    const int width = framebuffer->width;
    const luz_pixel_layout layout = luz_pixel_layout_of(framebuffer->channel_order);
    uint64_t shaded = 0;
    for (int y = first_row; y < end_row; y++) {
        const size_t row = (size_t)y * width;
        uint8_t *colour_row = framebuffer->colour + row * 4;
        for (int x = 0; x < width; x++) {
            luz_pixel_write(colour_row + (size_t)x * 4, layout,
                            luz_view_pixel(uniforms, draws, by_id, framebuffer, x, y, overdraw));
            shaded += framebuffer->visibility[row + x] != 0;
        }
    }
    return shaded;
}

const char *luz_view_name(luz_view view)
{
    static const char *const names[LUZ_VIEW_COUNT] = {
        "color", "depth", "normals", "uv", "mip", "overdraw", "bands", "triangles",
    };
    return (unsigned)view < LUZ_VIEW_COUNT ? names[view] : "unknown";
}
