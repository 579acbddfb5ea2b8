/*
 * luz/scene.h: the lighting lab of SCENE.md, as plain data.
 *
 * A luz_scene is everything a user can set: the time, the colour seed, the
 * cubes, the camera, the six lights and the texture filter. A zero scene is
 * not meaningful; start from luz_scene_defaults(), which holds every default
 * of SCENE.md in one place, and change what you need.
 *
 * luz_scene_build_frame() evaluates a scene at its time into a luz_frame:
 * the per-frame uniforms (matrices, camera, light positions) and the list of
 * objects to draw (ten rotated cubes, then the point-light marker). The
 * renderer draws luz_frames; it does not know about scenes, so a test can
 * hand it any mesh it likes.
 */
#ifndef LUZ_SCENE_H
#define LUZ_SCENE_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/vecmath.h"

struct luz_texture;
struct luz_texture_set;

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

/* The unit cube of SCENE.md: 24 vertices, 36 indices, static storage. */
const luz_mesh *luz_cube_mesh(void);

/* ---- camera and lights ------------------------------------------------- */

typedef struct luz_camera {
    luz_vec3 position;
    float yaw_degrees;    /* -90 looks down -Z */
    float pitch_degrees;  /* within [-89, 89] */
    float fov_degrees;    /* vertical field of view */
} luz_camera;

/* The camera's unit front vector from its yaw and pitch (SCENE.md). */
luz_vec3 luz_camera_front(const luz_camera *camera);

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

typedef enum luz_filter {
    LUZ_FILTER_NEAREST,
    LUZ_FILTER_BILINEAR,
    LUZ_FILTER_TRILINEAR,
} luz_filter;

const char *luz_filter_name(luz_filter filter);    /* "nearest", ... */

/* What the pipeline writes into the colour buffer: the shaded image, or a
 * picture of one of its stages (src/pipeline/view.c draws them). Every view
 * is drawn by the same pipeline, from the same triangles. */
typedef enum luz_view {
    LUZ_VIEW_COLOR,       /* the shaded image (the default) */
    LUZ_VIEW_DEPTH,       /* the z-buffer, as eye distance on a log scale */
    LUZ_VIEW_NORMALS,     /* world normal * 0.5 + 0.5 */
    LUZ_VIEW_UV,          /* (fract(u), fract(v), 0) */
    LUZ_VIEW_MIP,         /* the mip level the sampler read, one colour each */
    LUZ_VIEW_OVERDRAW,    /* depth tests per pixel, as a heat map */
    LUZ_VIEW_BANDS,       /* each band tinted by the thread that drew it */
    LUZ_VIEW_TRIANGLES,   /* each triangle in its own colour, with its edges */
    LUZ_VIEW_COUNT
} luz_view;

const char *luz_view_name(luz_view view);          /* "color", "depth", ... */

/* How varyings are interpolated across a triangle on the screen. */
typedef enum luz_interpolation {
    LUZ_INTERPOLATION_PERSPECTIVE,   /* perspective-correct (the default) */
    LUZ_INTERPOLATION_AFFINE,        /* linear in screen space: textures swim */
} luz_interpolation;

const char *luz_interpolation_name(luz_interpolation interpolation);  /* "perspective", ... */

/* ---- the scene ---------------------------------------------------------- */

#define LUZ_TEXTURE_BY_INDEX (-1)

/* A cube of the user's own (a scene file's `cube` line). */
typedef struct luz_cube {
    luz_vec3 position;
    bool has_colour;     /* else the seed's colour for its index */
    luz_vec3 colour;
    int texture;         /* index into the texture set, or LUZ_TEXTURE_BY_INDEX
                            for SCENE.md's "image i mod N" */
} luz_cube;

#define LUZ_MAX_CUBES 100000

typedef struct luz_scene {
    double time_seconds;
    uint32_t seed;           /* 0 means 0x9E3779B9 */
    int cube_count;          /* SCENE.md's tiling of the ten positions */
    const luz_cube *custom_cubes;   /* if non-NULL, replaces the tiling */
    int custom_cube_count;
    luz_camera camera;
    luz_lights lights;
    luz_filter filter;
    luz_view view;                   /* LUZ_VIEW_COLOR */
    luz_interpolation interpolation; /* LUZ_INTERPOLATION_PERSPECTIVE */
} luz_scene;

luz_scene luz_scene_defaults(void);

/* Cube i (i >= 0) of SCENE.md's tiled set: one of the ten positions plus
 * its tile's offset. */
luz_vec3 luz_scene_tiled_position(int cube_index);

/* One step of Marsaglia's xorshift32 (13, 17, 5), SCENE.md's generator:
 * every non-zero state maps to a non-zero state. */
uint32_t luz_xorshift32(uint32_t state);

/* objectColor for every cube index below count, from SCENE.md's xorshift32
 * generator; colours must hold count entries. */
void luz_scene_random_colours(uint32_t seed, int count, luz_vec3 *colours);

/* ---- a frame: what the renderer draws ---------------------------------- */

/* One object to draw: a mesh, where it is, and what it is made of. */
typedef struct luz_draw {
    const luz_mesh *mesh;
    luz_mat4 model;
    luz_mat3 normal_matrix;              /* inverse transpose of model's 3x3 */
    luz_vec3 colour;                     /* objectColor C */
    const struct luz_texture *texture;   /* NULL: white, T = 1 */
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

/* The uniforms of a scene's camera and lights at the scene's time, for an
 * image of the given aspect ratio (width / height). */
luz_uniforms luz_scene_uniforms(const luz_scene *scene, float aspect);

/* Fills frame with the scene at its time: uniforms, then one draw per cube
 * in index order, then the point-light marker while its strength is above
 * 0. textures may be NULL or empty (every texel white). Returns 0, or -1 if
 * memory ran out. The frame's draw array is reused between calls. */
int luz_scene_build_frame(const luz_scene *scene, const struct luz_texture_set *textures,
                          float aspect, luz_frame *frame);

/* Appends a draw; returns 0, or -1 if memory ran out or the draw's mesh is
 * not one the pipeline can read (NULL arrays, an index count that is not a
 * multiple of 3, an index past the last vertex). */
int luz_frame_add_draw(luz_frame *frame, const luz_draw *draw);
void luz_frame_free(luz_frame *frame);

#endif
