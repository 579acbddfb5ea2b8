/*
 * lights.c: the names of the six light terms and of the tone maps, a
 * term's light, and the shading uniforms worked out once a frame.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "luz/frame.h"
#include "luz/shade.h"

const char *luz_term_name(luz_term term)
{
    static const char *const names[LUZ_TERM_COUNT] = {
        "ambient", "diffuse", "specular", "point", "spot", "directional",
    };
    return (unsigned)term < LUZ_TERM_COUNT ? names[term] : "unknown";
}

const char *luz_tone_map_name(luz_tone_map tone_map)
{
    static const char *const names[LUZ_TONE_MAP_COUNT] = {"clamp", "neutral"};
    return (unsigned)tone_map < LUZ_TONE_MAP_COUNT ? names[tone_map] : "unknown";
}

luz_light *luz_lights_term(luz_lights *lights, luz_term term)
{
    switch (term) {
    case LUZ_TERM_AMBIENT: return &lights->ambient;
    case LUZ_TERM_DIFFUSE: return &lights->diffuse;
    case LUZ_TERM_SPECULAR: return &lights->specular;
    case LUZ_TERM_POINT: return &lights->point;
    case LUZ_TERM_SPOT: return &lights->spot;
    case LUZ_TERM_DIRECTIONAL: return &lights->directional;
    default: return NULL;
    }
}

luz_shade_uniforms luz_shade_uniforms_of(luz_vec3 eye, const luz_lights *lights)
{
    luz_shade_uniforms uniforms;
    memset(&uniforms, 0, sizeof uniforms);
    uniforms.eye = eye;
    uniforms.lights = *lights;
    /* Zero means SCENE.md's reach (luz/frame.h); luz_renderer_draw has
     * refused any other value that is not above 0. */
    if (uniforms.lights.spot_reach == 0.0f) uniforms.lights.spot_reach = LUZ_SPOT_REACH_DEFAULT;
    /* In double, then rounded once: the cone's cosines as the lab has
     * always computed them. */
    uniforms.spot_cos_inner = (float)cos(lights->spot_inner_degrees * (LUZ_PI / 180.0));
    uniforms.spot_cos_outer = (float)cos(lights->spot_outer_degrees * (LUZ_PI / 180.0));
    return uniforms;
}
