/*
 * lights.c: the names of the six light terms, and a term's light.
 */
#include <stddef.h>

#include "luz/frame.h"

const char *luz_term_name(luz_term term)
{
    static const char *const names[LUZ_TERM_COUNT] = {
        "ambient", "diffuse", "specular", "point", "spot", "directional",
    };
    return (unsigned)term < LUZ_TERM_COUNT ? names[term] : "unknown";
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
