/*
 * fragment.c: the fragment stage. For every visible pixel, interpolate the
 * varyings perspective-correctly, sample the texture, run the fragment
 * shader and write the colour.
 *
 * In:  the visibility buffer (which triangle is nearest at each pixel,
 *      written by raster.c), the set-up triangles, their draws'
 *      materials, the frame's uniforms.
 * Out: the colour buffer, each channel round(clamp(c, 0, 1) * 255), in the
 *      framebuffer's channel order (RGBA or BGRA); or, for a list of
 *      (pixel, triangle) fragments (the other winners of pixels four
 *      samples share, resolve.c), the bytes of each. A lit colour is first
 *      exposed and tone-mapped (luz_shade_output, SCENE.md's "Output").
 *      Every pixel is written: the background, where no triangle won,
 *      gets the clear colour. No pass clears colour beforehand, so each
 *      byte is written once a frame and colour may be memory the caller
 *      lends, holding anything.
 *
 * Perspective-correct interpolation: on the screen, a varying a is not
 * affine, but a / w and 1 / w are (the projection is a projective map;
 * Heckbert and Moreton 1991, OpenGL 4.6 equation 14.9). setup.c made a
 * plane for each, so at a pixel centre
 *      a = (a/w)(x, y) / (1/w)(x, y).
 * Affine interpolation of a directly would make textures swim and bend on
 * faces seen at an angle.
 *
 * Texture level of detail: differentiating the quotient gives the exact
 * screen-space derivatives of u and v at the pixel,
 *      du/dx = (d(u/w)/dx - u d(1/w)/dx) / (1/w),
 * so every pixel has its own footprint, with no need for neighbours (and
 * so no dependence on where a band begins).
 */
#include <string.h>

#include "renderer/pipeline.h"
#include "luz/shade.h"
#include "luz/texture.h"

static inline float plane_at(luz_plane plane, float dx, float dy)
{
    return plane.value + plane.dx * dx + plane.dy * dy;
}

void luz_fragment_interpolate(const luz_triangle *triangle, int x, int y, luz_fragment *out)
{
    const float dx = (float)x + 0.5f - triangle->reference_x;
    const float dy = (float)y + 0.5f - triangle->reference_y;
    const float inverse_w = plane_at(triangle->inverse_w, dx, dy);
    const float w = 1.0f / inverse_w;
    const luz_plane *varying = triangle->varyings;

    out->position.x = plane_at(varying[LUZ_VARYING_POSITION + 0], dx, dy) * w;
    out->position.y = plane_at(varying[LUZ_VARYING_POSITION + 1], dx, dy) * w;
    out->position.z = plane_at(varying[LUZ_VARYING_POSITION + 2], dx, dy) * w;
    out->normal.x = plane_at(varying[LUZ_VARYING_NORMAL + 0], dx, dy) * w;
    out->normal.y = plane_at(varying[LUZ_VARYING_NORMAL + 1], dx, dy) * w;
    out->normal.z = plane_at(varying[LUZ_VARYING_NORMAL + 2], dx, dy) * w;

    const luz_plane u_plane = varying[LUZ_VARYING_UV + 0];
    const luz_plane v_plane = varying[LUZ_VARYING_UV + 1];
    const float u = plane_at(u_plane, dx, dy) * w;
    const float v = plane_at(v_plane, dx, dy) * w;
    out->uv = (luz_vec2){u, v};
    out->du_dx = (u_plane.dx - u * triangle->inverse_w.dx) * w;
    out->dv_dx = (v_plane.dx - v * triangle->inverse_w.dx) * w;
    out->du_dy = (u_plane.dy - u * triangle->inverse_w.dy) * w;
    out->dv_dy = (v_plane.dy - v * triangle->inverse_w.dy) * w;
    out->depth = plane_at(triangle->depth, dx, dy);
    out->w = w;
}

/* luz_shade_output's settings, read once from the frame's uniforms. */
typedef struct output_settings {
    bool identity;             /* clamp at EV 0: the colour as it is */
    float exposure_scale;      /* 2^EV */
    luz_tone_map tone_map;
    luz_bug bug;               /* luz/bug.h: LUZ_BUG_NONE, or a mistake put in */
} output_settings;

static output_settings output_of(const luz_uniforms *uniforms)
{
    return (output_settings){uniforms->output_is_identity, uniforms->exposure_scale,
                             uniforms->tone_map, uniforms->bug};
}

/* Pixel (x, y) shaded as triangle's: interpolate, sample, light, and a lit
 * colour exposed and tone-mapped. */
static inline luz_vec3 shade_pixel(const luz_shade_uniforms *uniforms,
                                   const output_settings *output, const luz_draw *draws,
                                   const luz_triangle *triangle, int x, int y)
{
    const luz_material *material = &draws[triangle->draw_index].material;
    if (material->shading == LUZ_SHADING_UNLIT) return luz_material_colour(material);
    luz_fragment fragment;
    luz_fragment_interpolate(triangle, x, y, &fragment);
    float lambda = 0.0f;
    if (material->texture && material->filter == LUZ_FILTER_TRILINEAR) {
        lambda = luz_texture_level_of_detail(material->texture, fragment.du_dx, fragment.dv_dx,
                                             fragment.du_dy, fragment.dv_dy);
        if (output->bug == LUZ_BUG_LOD_OFF_BY_ONE) lambda += 1.0f;   /* luz/bug.h */
    }
    luz_vec3 texel = luz_texture_sample(material->texture, material->filter, fragment.uv, lambda);
    luz_vec3 colour;
    if (output->bug == LUZ_BUG_NONE) {
        colour = luz_shade_fragment(uniforms, fragment.position, fragment.normal,
                                    luz_material_colour(material), texel);
    } else {   /* a shading bug, if it is one, is shade_steps.c's */
        luz_vec3 terms[LUZ_TERM_COUNT];
        colour = luz_shade_colour(luz_shade_terms_explained(uniforms, output->bug,
                                                            fragment.position, fragment.normal,
                                                            terms, NULL),
                                  luz_material_colour(material), texel);
    }
    return output->identity ? colour
                            : luz_shade_output(colour, output->exposure_scale, output->tone_map);
}

uint64_t luz_fragment_shade_list(const luz_uniforms *frame_uniforms, const luz_draw *draws,
                                 const luz_triangle *const *by_id, luz_channel_order order,
                                 const luz_fragment_ref *fragments, size_t count,
                                 uint32_t *colours)
{
    const luz_shade_uniforms uniforms = frame_uniforms->shade;
    const output_settings output = output_of(frame_uniforms);
    const luz_pixel_layout layout = luz_pixel_layout_of(order);
    for (size_t i = 0; i < count; i++) {
        const luz_fragment_ref *fragment = &fragments[i];
        uint8_t pixel[4];
        luz_pixel_write(pixel, layout,
                        shade_pixel(&uniforms, &output, draws, by_id[fragment->id],
                                    fragment->x, fragment->y));
        memcpy(&colours[i], pixel, sizeof pixel);
    }
    return count;
}

uint64_t luz_fragment_shade_rows(const luz_uniforms *frame_uniforms, const luz_draw *draws,
                                 const luz_triangle *const *by_id, luz_framebuffer *framebuffer,
                                 int first_row, int end_row)
{
    /* A local copy: the colour writes below go through a uint8_t pointer,
     * which C allows to alias anything, so without it the compiler would
     * have to reload every uniform after every pixel. */
    const luz_shade_uniforms uniforms = frame_uniforms->shade;
    const output_settings output = output_of(frame_uniforms);
    const int width = framebuffer->width;
    const luz_pixel_layout layout = luz_pixel_layout_of(framebuffer->channel_order);
    uint8_t background[4];   /* the clear colour's bytes, worked out once */
    luz_pixel_write(background, layout, frame_uniforms->clear_colour);
    uint64_t shaded = 0;

    for (int y = first_row; y < end_row; y++) {
        const uint32_t *visibility_row = framebuffer->visibility + (size_t)y * width;
        uint8_t *colour_row = framebuffer->colour + (size_t)y * width * 4;
        for (int x = 0; x < width; x++) {
            const uint32_t id = visibility_row[x];
            uint8_t *pixel = colour_row + (size_t)x * 4;
            if (id == 0) {
                memcpy(pixel, background, sizeof background);
                continue;
            }
            luz_pixel_write(pixel, layout, shade_pixel(&uniforms, &output, draws, by_id[id], x, y));
            shaded++;
        }
    }
    return shaded;
}
