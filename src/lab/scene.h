/*
 * lab/scene.h: the lighting lab of SCENE.md, as plain data.
 *
 * A luz_scene is everything a user can set: the time, the colour seed, the
 * cubes, the camera, the six lights and the texture filter. A zero scene is
 * not meaningful; start from luz_scene_defaults(), which holds every default
 * of SCENE.md in one place, and change what you need.
 *
 * luz_scene_build_frame() evaluates a scene at its time into a luz_frame
 * (luz/frame.h): the per-frame uniforms (matrices, camera, light positions)
 * and the list of objects to draw (the rotated cubes, then the point-light
 * marker). The lab is a user of libluz like any other program: it includes
 * only the renderer's headers.
 */
#ifndef LUZ_LAB_SCENE_H
#define LUZ_LAB_SCENE_H

#include <stdbool.h>
#include <stdint.h>

#include "luz/error.h"
#include "luz/frame.h"
#include "luz/mesh.h"
#include "luz/renderer.h"
#include "luz/texture.h"
#include "luz/vecmath.h"

/* The unit cube of SCENE.md as a mesh of its own: 24 vertices, 36
 * indices (cube_mesh.c). */
luz_mesh *luz_cube_mesh_create(luz_error *error);

/* ---- camera and lights ------------------------------------------------- */

typedef struct luz_camera {
    luz_vec3 position;
    float yaw_degrees;    /* -90 looks down -Z */
    float pitch_degrees;  /* within [-89, 89] */
    float fov_degrees;    /* vertical field of view */
} luz_camera;

/* The camera's unit front vector from its yaw and pitch (SCENE.md). */
luz_vec3 luz_camera_front(const luz_camera *camera);

/* ---- the scene ---------------------------------------------------------- */

#define LUZ_TEXTURE_BY_INDEX (-1)

/* ---- models --------------------------------------------------------------- */

/* What the lab needs of a model file (SCENE.md, "Models"): its triangle
 * meshes in the file's order, each with the colour and texture of its
 * material, and the box around them all. The programs read files into this
 * (src/io/model.h, through src/app); the lab reads nothing itself. */
typedef struct luz_lab_model_part {
    const luz_mesh *mesh;
    bool has_colour;               /* the material's diffuse colour */
    luz_vec3 colour;
    bool has_uvs;                  /* without, T = 1 */
    const luz_texture *texture;    /* the material's, or NULL */
    /* What the file calls them, or NULL (the pixel probe names them). */
    const char *mesh_name;
    const char *material_name;
    const char *texture_name;      /* as the material names its texture */
} luz_lab_model_part;

typedef struct luz_lab_model {
    const char *name;              /* the file's name */
    const luz_lab_model_part *parts;
    int part_count;
    luz_bounds bounds;             /* around every part's vertices */
} luz_lab_model;

/* SCENE.md's "Up axis": which of a model's own axes points up. The model
 * is first turned so that this axis becomes +Y: */
typedef enum luz_up_axis {
    LUZ_UP_Y,        /* the default: as the file is */
    LUZ_UP_Z,        /* -90 degrees about X: (x, y, z) -> (x, z, -y) */
    LUZ_UP_X,        /* +90 degrees about Z: (x, y, z) -> (-y, x, z) */
    LUZ_UP_MINUS_Y,  /* 180 degrees about Z: (x, y, z) -> (-x, -y, z) */
    LUZ_UP_MINUS_Z,  /* +90 degrees about X: (x, y, z) -> (x, -z, y) */
    LUZ_UP_MINUS_X,  /* -90 degrees about Z: (x, y, z) -> (y, -x, z) */
    LUZ_UP_AXIS_COUNT
} luz_up_axis;

/* "y", "z", "x", "-y", "-z", "-x"; "unknown" for another value. */
const char *luz_up_axis_name(luz_up_axis up);
/* The axis of a name, into *up; false for a name that is none. */
bool luz_up_axis_from_name(const char *name, luz_up_axis *up);
/* The turn itself, as a matrix: a permutation of the axes with signs, so
 * every vertex is turned exactly. */
luz_mat4 luz_up_axis_matrix(luz_up_axis up);

/* Norm = Scale(2 / s) * Translate(-c) * Up: the model turned so that its
 * `up` axis is +Y, then c the centre of its box and s the box's largest
 * side after the turn, so the model is centred on the origin and spans
 * [-1, 1] along its longest axis. s must be above 0. */
luz_mat4 luz_lab_model_normalisation(const luz_lab_model *model, luz_up_axis up);

/* ---- the scene's objects -------------------------------------------------- */


/* An object of the user's own: a cube (a scene file's `cube` line) or a
 * model (`model` line, or --model). */
typedef struct luz_object {
    luz_vec3 position;
    bool has_colour;     /* else the seed's colour for its index (a model:
                            its materials' colours first) */
    luz_vec3 colour;
    int texture;         /* index into the texture set, or LUZ_TEXTURE_BY_INDEX:
                            SCENE.md's "image i mod N" for a cube, the
                            materials' textures for a model */
    const luz_lab_model *model;   /* NULL: a cube */
    float scale;         /* a model's k; 0 means 1 */
    bool still;          /* a model that does not turn */
    luz_up_axis up;      /* a model's up axis (SCENE.md, "Up axis") */
} luz_object;

#define LUZ_MAX_CUBES 100000

/* ---- the ranges a scene keeps to --------------------------------------------
 * Within these the lab draws something meaningful; the options
 * (src/app/options.c) refuse anything outside them, and the viewer's
 * controls stay inside, so that a saved view always reads back. */

/* |t| in seconds, about 32 years. Cube i turns (i + 1) / 3 * 50 t degrees,
 * reduced to one turn in double precision (scene.c): up to here that angle
 * is good to a quarter of a degree for every one of LUZ_MAX_CUBES cubes;
 * near t = 1e302 the product overflows and nothing would be drawn. */
#define LUZ_SCENE_MAX_TIME 1e9

/* |x|, |y| and |z| of the camera's and every object's position: a hundred
 * times the far plane's distance (100), with positions still resolved to
 * a thousandth of a unit (a float's step near 10000 is 1/1024). */
#define LUZ_SCENE_MAX_COORDINATE 10000.0f

/* A model's scale k: it spans [-k, k], from a fiftieth of the near plane's
 * distance to twice LUZ_SCENE_MAX_COORDINATE. */
#define LUZ_SCENE_MIN_SCALE 0.001f
#define LUZ_SCENE_MAX_SCALE 10000.0f

typedef struct luz_scene {
    double time_seconds;
    uint32_t seed;           /* 0 means 0x9E3779B9 */
    int cube_count;          /* SCENE.md's tiling of the ten positions */
    const luz_object *objects;   /* if non-NULL, replaces the tiling: cubes
                                    and models in the order drawn */
    int object_count;
    luz_camera camera;
    luz_lights lights;
    luz_filter filter;
    luz_view view;                   /* LUZ_VIEW_COLOR */
    luz_interpolation interpolation; /* LUZ_INTERPOLATION_PERSPECTIVE */
    luz_bug bug;                     /* LUZ_BUG_NONE, or a mistake put in
                                        (luz/bug.h) */
    bool bug_hidden;                 /* a quiz's bug: no output names it */
    int samples;                     /* a pixel's: 1 (the default) or 4 */
    /* The output of lit colours (SCENE.md, "Output"), as far as the user
     * set it: exposure only if has_exposure, tone_map only if
     * has_tone_map; the rest is the defaults' (luz_scene_output). */
    bool has_exposure, has_tone_map;
    float exposure;                  /* EV */
    luz_tone_map tone_map;
} luz_scene;

luz_scene luz_scene_defaults(void);

/* ---- output: exposure and tone map ------------------------------------------
 * SCENE.md: a scene without models keeps the report's output, clamp at
 * EV 0 (every lab image as it was); a scene with at least one model
 * defaults to neutral at EV -1, where a white model keeps its shading. A
 * setting the user gave wins in both cases. */
#define LUZ_MODEL_EXPOSURE (-1.0f)
#define LUZ_MODEL_TONE_MAP LUZ_TONE_MAP_NEUTRAL

/* Whether one of the scene's objects is a model (objects[i].model). */
bool luz_scene_has_model(const luz_scene *scene);
/* The output in force for the scene, if it holds a model (has_model) or
 * not: what the user set, the rest its default. */
luz_output luz_scene_output_for(const luz_scene *scene, bool has_model);
/* luz_scene_output_for(scene, luz_scene_has_model(scene)). */
luz_output luz_scene_output(const luz_scene *scene);

/* Cube i (i >= 0) of SCENE.md's tiled set: one of the ten positions plus
 * its tile's offset. */
luz_vec3 luz_scene_tiled_position(int cube_index);

/* One step of Marsaglia's xorshift32 (13, 17, 5), SCENE.md's generator:
 * every non-zero state maps to a non-zero state. */
uint32_t luz_xorshift32(uint32_t state);

/* objectColor for every cube index below count, from SCENE.md's xorshift32
 * generator; colours must hold count entries. */
void luz_scene_random_colours(uint32_t seed, int count, luz_vec3 *colours);

/* ---- the scene as a frame ------------------------------------------------ */

/* What the lab keeps from frame to frame: its meshes (the cube). */
typedef struct luz_lab luz_lab;

luz_lab *luz_lab_create(luz_error *error);
void luz_lab_destroy(luz_lab *lab);
/* The unit cube of SCENE.md, 24 vertices and 12 triangles, that every
 * cube and the point light's marker draw. */
const luz_mesh *luz_lab_cube_mesh(const luz_lab *lab);

/* The frame's camera and lights at the scene's time, for an image of the
 * given aspect ratio (width / height): the view and projection matrices,
 * the eye, the lights with the point light and the sun where their orbits
 * have them and the spot along the camera's front, the clear colour, the
 * samples a pixel and the output in force (luz_scene_output).
 * The draws are left as they are. */
void luz_scene_set_camera_and_lights(const luz_scene *scene, float aspect, luz_frame *frame);

/* The render options the scene's teaching settings ask for (its view,
 * interpolation and bug); every other field zero. */
luz_render_options luz_scene_render_options(const luz_scene *scene);

/* Fills frame with the scene at its time: camera and lights, then one draw
 * per cube in index order, then the point-light marker while its strength
 * is above 0. textures holds texture_count textures, cube i using
 * textures[i mod texture_count]; none (NULL, 0) makes every texel white.
 * Returns 0, or -1 with the reason if memory ran out. The frame's draw
 * array is reused between calls. */
int luz_scene_build_frame(const luz_lab *lab, const luz_scene *scene,
                          luz_texture *const *textures, int texture_count, float aspect,
                          luz_frame *frame, luz_error *error);

/* Which object made draw `draw_index` of the frame luz_scene_build_frame
 * builds from the scene: returns the object's index (cube i of SCENE.md's
 * tiling, or the scene's objects[i]) and sets *part to the model's mesh
 * (0 for a cube). Returns LUZ_DRAW_POINT_LIGHT for the point light's
 * marker, the draw after the objects', and LUZ_DRAW_NONE past it. */
#define LUZ_DRAW_POINT_LIGHT (-1)
#define LUZ_DRAW_NONE (-2)
int luz_scene_object_of_draw(const luz_scene *scene, int draw_index, int *part);


#endif
