/*
 * luz/frame.h: what the renderer draws, as plain data.
 *
 * A luz_frame is the per-frame uniforms (matrices, camera, lights) and a
 * list of draws, each a mesh, where it is and what it is made of. The
 * renderer (luz/renderer.h) draws luz_frames; it knows nothing of where
 * they come from, so a program or a test can hand it any mesh it likes.
 */
#ifndef LUZ_FRAME_H
#define LUZ_FRAME_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/texture.h"
#include "luz/vecmath.h"
#include "luz/view.h"

/* ---- meshes ------------------------------------------------------------ */

typedef struct luz_vertex {
    luz_vec3 position;  /* object space */
    luz_vec3 normal;    /* object space, unit length */
    luz_vec2 uv;        /* v = 0 is the top row of the image file */
} luz_vertex;

/* An indexed triangle list; counter-clockwise triangles are front faces. */
typedef struct luz_mesh {
    const luz_vertex *vertices;
    int vertex_count;
    const uint16_t *indices;
    int index_count;          /* a multiple of 3 */
} luz_mesh;

/* ---- lights ------------------------------------------------------------- */

/* A light's colour (the report's colour picker) and strength (its alpha). */
typedef struct luz_light {
    luz_vec3 colour;
    float strength;  /* in [0, 1]; 0 switches the term off exactly */
} luz_light;

typedef struct luz_lights {
    luz_light ambient;
    luz_light diffuse;      /* headlight at the camera */
    luz_light specular;     /* same headlight */
    luz_light point;        /* orbits the origin */
    luz_light spot;         /* rides on the camera */
    luz_light directional;  /* the sun */
    float shininess;
    float spot_inner_degrees;  /* full intensity inside this angle */
    float spot_outer_degrees;  /* cut-off */
    float spot_reach;
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

const char *luz_term_name(luz_term term);          /* "ambient", ... */
luz_light *luz_lights_term(luz_lights *lights, luz_term term);

/* How varyings are interpolated across a triangle on the screen. */
typedef enum luz_interpolation {
    LUZ_INTERPOLATION_PERSPECTIVE,   /* perspective-correct (the default) */
    LUZ_INTERPOLATION_AFFINE,        /* linear in screen space: textures swim */
} luz_interpolation;

const char *luz_interpolation_name(luz_interpolation interpolation);  /* "perspective", ... */

/* ---- a frame: what the renderer draws ---------------------------------- */

/* One object to draw: a mesh, where it is, and what it is made of. */
typedef struct luz_draw {
    const luz_mesh *mesh;
    luz_mat4 model;
    luz_mat3 normal_matrix;              /* inverse transpose of model's 3x3 */
    luz_vec3 colour;                     /* objectColor C */
    const luz_texture *texture;           /* NULL: white, T = 1 */
    bool unlit;                          /* output colour as is (the marker) */
} luz_draw;

/* Everything the fragment shader reads that is the same for all fragments. */
typedef struct luz_uniforms {
    luz_mat4 view;
    luz_mat4 projection;
    luz_vec3 camera_position;          /* E */
    luz_vec3 camera_front;             /* F, unit length */
    luz_vec3 point_light_position;
    luz_vec3 directional_direction;    /* d(t), the direction light travels */
    luz_lights lights;
    float spot_cos_inner;              /* cos(inner), precomputed per frame */
    float spot_cos_outer;
    luz_filter filter;
    luz_vec3 clear_colour;
    luz_view show;                     /* what the colour buffer shows (the
                                          scene's view; `view` is the matrix) */
    luz_interpolation interpolation;   /* read by setup.c */
    uint32_t triangle_limit;           /* 0: rasterise every triangle; N: only
                                          the first N that survive clipping
                                          and culling, in submission order
                                          (the viewer's step mode) */
} luz_uniforms;

typedef struct luz_frame {
    luz_uniforms uniforms;
    luz_draw *draws;
    int draw_count;
    int draw_capacity;
} luz_frame;

/* Appends a draw; returns 0, or -1 if memory ran out or the draw's mesh is
 * not one the pipeline can read (NULL arrays, an index count that is not a
 * multiple of 3, an index past the last vertex). */
int luz_frame_add_draw(luz_frame *frame, const luz_draw *draw);
void luz_frame_free(luz_frame *frame);

#endif
