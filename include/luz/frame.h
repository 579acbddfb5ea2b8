/*
 * luz/frame.h: what the renderer draws, as plain data.
 *
 * A luz_frame is a camera (view and projection matrices, and the eye's
 * position), the lights, and a list of draws: each a mesh (luz/mesh.h),
 * where it is (its model matrix) and what it is made of (its material).
 * The renderer (luz/renderer.h) draws luz_frames and knows nothing of where
 * they come from: SCENE.md's lab builds one per frame (src/lab), a program
 * of yours builds its own.
 *
 * The lighting is SCENE.md's six terms, each a light with a colour and a
 * strength: ambient light, diffuse and specular light from a headlight at
 * the eye, a point light, a spot light that rides on the eye, and a
 * directional light (luz/shade.h has the equations). A light whose
 * strength is 0 adds exactly nothing, so a zero luz_lights is darkness.
 *
 * Zero means the default (as in sokol's descs): a zero luz_material is
 * lit, white and untextured, sampled trilinearly; a zero spot_reach is
 * SCENE.md's 10; a zero luz_output is clamp at EV 0; zero samples is one.
 * luz_renderer_draw refuses, through luz_error, a value this header
 * forbids.
 */
#ifndef LUZ_FRAME_H
#define LUZ_FRAME_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/api.h"
#include "luz/error.h"
#include "luz/mesh.h"
#include "luz/texture.h"
#include "luz/vecmath.h"

/* ---- lights ------------------------------------------------------------- */

/* A light's colour (the report's colour picker) and strength (its alpha). */
typedef struct luz_light {
    luz_vec3 colour;
    float strength;  /* in [0, 1]; 0 switches the term off exactly */
} luz_light;

/* SCENE.md's spot reach, what a spot_reach of 0 means. */
#define LUZ_SPOT_REACH_DEFAULT 10.0f

typedef struct luz_lights {
    luz_light ambient;
    luz_light diffuse;      /* headlight at the eye */
    luz_light specular;     /* same headlight */
    luz_light point;
    luz_light spot;         /* at the eye, shining along spot_direction */
    luz_light directional;
    float shininess;           /* the specular exponent, >= 0 (0: pow(x, 0)
                                  is 1, SCENE.md) */
    float spot_inner_degrees;  /* full intensity inside this angle */
    float spot_outer_degrees;  /* cut-off; 0 <= inner <= outer <= 89 */
    float spot_reach;          /* distance at which the spot fades out: > 0,
                                  or 0 for LUZ_SPOT_REACH_DEFAULT (10) */
    /* Where the lights are, in world space: in the lab these move with
     * time and with the camera. */
    luz_vec3 point_position;
    luz_vec3 spot_direction;         /* need not be unit length */
    luz_vec3 directional_direction;  /* the way the light travels */
} luz_lights;

/* The six terms, in the order SCENE.md's equations list them. */
typedef enum luz_term {
    LUZ_TERM_AMBIENT,
    LUZ_TERM_DIFFUSE,
    LUZ_TERM_SPECULAR,
    LUZ_TERM_POINT,
    LUZ_TERM_SPOT,
    LUZ_TERM_DIRECTIONAL,
    LUZ_TERM_COUNT
} luz_term;

LUZ_API const char *luz_term_name(luz_term term);          /* "ambient", ... */
/* The light of a term; NULL for a value that is not a term. */
LUZ_API luz_light *luz_lights_term(luz_lights *lights, luz_term term);

/* ---- materials ---------------------------------------------------------- */

/* How a material's pixels get their colour. */
typedef enum luz_shading {
    LUZ_SHADING_LIT,     /* SCENE.md: (the six terms) * colour * texel */
    LUZ_SHADING_UNLIT,   /* colour as it is, no light, no texture (the lab's
                            point-light marker) */
} luz_shading;

/* What a draw is made of. A zero material is lit, white (C = 1, 1, 1) and
 * untextured (T = 1), sampled trilinearly: SCENE.md's white, the colour
 * of an untextured texel. A colour that is not (0, 0, 0) is used as it
 * is; has_colour asks for the colour even when it is black. */
typedef struct luz_material {
    luz_shading shading;          /* 0: lit */
    luz_vec3 colour;              /* objectColor C, each channel in [0, 1]
                                     (a model's may be more); (0, 0, 0)
                                     means white unless has_colour */
    bool has_colour;              /* true: C = colour, black included */
    const luz_texture *texture;   /* NULL: every texel white, T = 1 */
    luz_filter filter;            /* how the texture is sampled; 0: trilinear */
} luz_material;

/* The material's colour C: its colour if it has one (has_colour, or any
 * channel not zero), else white. */
static inline luz_vec3 luz_material_colour(const luz_material *material)
{
    const luz_vec3 c = material->colour;
    const bool given = material->has_colour || c.x != 0.0f || c.y != 0.0f || c.z != 0.0f;
    return given ? c : (luz_vec3){1.0f, 1.0f, 1.0f};
}

/* ---- output: exposure and tone map ---------------------------------------- */

/* How a lit colour becomes bytes (SCENE.md, "Output: exposure and tone
 * map"). The six terms add up to more than 1 where several lights meet, so
 * a light material clips to a flat silhouette; an exposure below 0 and a
 * tone map that rolls off towards 1 keep its shading. */
typedef enum luz_tone_map {
    LUZ_TONE_MAP_CLAMP,     /* round(clamp(c, 0, 1) * 255), the report's */
    LUZ_TONE_MAP_NEUTRAL,   /* the Khronos PBR Neutral tone mapper first
                               (luz_tone_map_neutral in luz/shade.h) */
    LUZ_TONE_MAP_COUNT
} luz_tone_map;

LUZ_API const char *luz_tone_map_name(luz_tone_map tone_map);   /* "clamp", "neutral" */

/* Applied to lit fragments only: an unlit material (the point-light
 * marker) and the clear colour are written as they are. A zero luz_output
 * is clamp at EV 0: the colour as the equations give it. */
typedef struct luz_output {
    float exposure;          /* EV, finite: the colour is multiplied by 2^EV */
    luz_tone_map tone_map;
} luz_output;

/* ---- a frame ------------------------------------------------------------ */

/* One object to draw: a mesh, where it is, and what it is made of. */
typedef struct luz_draw {
    const luz_mesh *mesh;
    luz_mat4 model;               /* object to world space */
    luz_material material;
} luz_draw;

/* Who owns what: the frame never owns the meshes and textures its draws
 * name. Its draws array is the frame's own once luz_frame_add_draw has
 * made it (draw_capacity > 0), and luz_frame_free frees it then; an array
 * of the caller's (draws and draw_count set by hand, draw_capacity left 0)
 * stays the caller's: luz_frame_free and luz_frame_add_draw never free it
 * (add_draw copies it into an array of the frame's own first). */
typedef struct luz_frame {
    luz_mat4 view;                /* world to eye space (luz_mat4_look_at) */
    luz_mat4 projection;          /* eye to clip space (luz_mat4_perspective) */
    luz_vec3 eye;                 /* E: the eye's position in the world */
    luz_lights lights;
    luz_vec3 clear_colour;        /* the background */
    int samples;                  /* samples a pixel: 0 or 1 (one, at the
                                     centre), or 4 (SCENE.md's 4x pattern,
                                     resolved); others are an error */
    luz_output output;            /* exposure and tone map of lit colours */
    luz_draw *draws;              /* drawn in this order */
    int draw_count;
    int draw_capacity;            /* > 0: draws is the frame's own (made by
                                     luz_frame_add_draw); 0: the caller's */
} luz_frame;

/* Appends a copy of *draw to the frame's list (which grows as needed, and
 * is kept from frame to frame: set draw_count to 0 to reuse it). A list of
 * the caller's (draw_capacity 0) is first copied into one of the frame's
 * own and left as it was. Returns 0, or -1 with the reason if the draw has
 * no mesh or memory ran out. */
LUZ_API int luz_frame_add_draw(luz_frame *frame, const luz_draw *draw, luz_error *error);
/* Frees the draw list if it is the frame's own (draw_capacity > 0), never
 * an array of the caller's, nor the meshes or textures the draws name;
 * then the frame has no draws. */
LUZ_API void luz_frame_free(luz_frame *frame);

#endif
