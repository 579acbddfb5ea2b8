/*
 * scene.c: SCENE.md's lighting lab as data, and its evaluation at a time t.
 *
 * Every default of SCENE.md lives in luz_scene_defaults(); every motion
 * (the cubes' rotation, the point light's orbit, the sun's) lives in
 * luz_scene_build_frame(). What comes out is a luz_frame: a camera, lights
 * and a list of draws, which is all the renderer sees.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lab/scene.h"

static const luz_vec3 cube_positions[10] = {
    { 0.0f,  0.0f,   0.0f}, { 2.0f,  5.0f, -15.0f}, {-1.5f, -2.2f,  -2.5f},
    {-3.8f, -2.0f, -12.3f}, { 2.4f, -0.4f,  -3.5f}, {-1.7f,  3.0f,  -7.5f},
    { 1.3f, -2.0f,  -2.5f}, { 1.5f,  2.0f,  -2.5f}, { 1.5f,  0.2f,  -1.5f},
    {-1.3f,  1.0f,  -1.5f},
};

static luz_light white_light(float strength)
{
    return (luz_light){{1.0f, 1.0f, 1.0f}, strength};
}

luz_scene luz_scene_defaults(void)
{
    luz_scene scene;
    memset(&scene, 0, sizeof scene);
    scene.time_seconds = 0.0;
    scene.seed = 0;
    scene.cube_count = 10;
    scene.camera = (luz_camera){{0.0f, 0.0f, 3.0f}, -90.0f, 0.0f, 45.0f};
    scene.lights.ambient = white_light(0.2f);
    scene.lights.diffuse = white_light(0.6f);
    scene.lights.specular = white_light(0.5f);
    scene.lights.point = white_light(0.7f);
    scene.lights.spot = white_light(1.0f);
    scene.lights.directional = white_light(0.4f);
    scene.lights.shininess = 32.0f;
    scene.lights.spot_inner_degrees = 12.5f;
    scene.lights.spot_outer_degrees = 17.5f;
    scene.lights.spot_reach = 10.0f;
    scene.filter = LUZ_FILTER_TRILINEAR;
    scene.view = LUZ_VIEW_COLOR;
    scene.interpolation = LUZ_INTERPOLATION_PERSPECTIVE;
    scene.samples = 1;
    return scene;
}

luz_vec3 luz_camera_front(const luz_camera *camera)
{
    double yaw = camera->yaw_degrees * (LUZ_PI / 180.0);
    double pitch = camera->pitch_degrees * (LUZ_PI / 180.0);
    luz_vec3 front = {(float)(cos(yaw) * cos(pitch)), (float)sin(pitch),
                      (float)(sin(yaw) * cos(pitch))};
    return luz_vec3_normalize(front);
}

/* floor(sqrt(n)), exactly, in integers: the binary digit-by-digit method
 * (two bits of n, one bit of the root per step; at most 16 steps), so no
 * floating-point rounding can put a perfect square on the wrong side. */
static uint32_t integer_square_root(uint32_t n)
{
    uint32_t root = 0;
    uint32_t bit = UINT32_C(1) << 30;   /* the highest power of 4 in 32 bits */
    while (bit > n) bit >>= 2;
    while (bit != 0) {
        if (n >= root + bit) {
            n -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return root;
}

/* SCENE.md "More cubes": tiles around the original ten, ring by ring; in
 * ring r the cells (gx, gy) with max(|gx|, |gy|) = r, row by row.
 *
 * In closed form, O(1) per cube (the frame asks for every cube every
 * frame). Rings 0..r-1 fill the (2r - 1)^2 square, so tile t >= 1 is in
 * the ring r with (2r - 1)^2 <= t < (2r + 1)^2, that is
 * 2r - 1 <= floor(sqrt(t)) <= 2r: r = (floor(sqrt(t)) + 1) / 2. Its index
 * j = t - (2r - 1)^2 in the ring, 0 <= j < 8r, falls in one of three runs
 * of the row-by-row order:
 *   gy = -r, the whole row:         2r + 1 cells, gx = -r + j;
 *   gy = -r + 1 .. r - 1, two ends: 2(2r - 1) cells, gx = -r then r;
 *   gy = r, the whole row:          2r + 1 cells. */
luz_vec3 luz_scene_tiled_position(int cube_index)
{
    if (cube_index < 0) cube_index = 0;   /* not a cube: stay in the table */
    int tile = cube_index / 10;
    luz_vec3 base = cube_positions[cube_index % 10];
    if (tile == 0) return base;
    int ring = ((int)integer_square_root((uint32_t)tile) + 1) / 2;
    int index_in_ring = tile - (2 * ring - 1) * (2 * ring - 1);
    int full_row = 2 * ring + 1;
    int gx, gy;
    if (index_in_ring < full_row) {
        gy = -ring;
        gx = -ring + index_in_ring;
    } else if (index_in_ring < full_row + 2 * (2 * ring - 1)) {
        int k = index_in_ring - full_row;
        gy = -ring + 1 + k / 2;
        gx = k % 2 == 0 ? -ring : ring;
    } else {
        gy = ring;
        gx = -ring + (index_in_ring - full_row - 2 * (2 * ring - 1));
    }
    luz_vec3 offset = {9.0f * gx, 8.0f * gy, -16.0f * ring};
    return luz_vec3_add(base, offset);
}

/* xorshift32 (Marsaglia 2003). */
uint32_t luz_xorshift32(uint32_t x)
{
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return x;
}

/* One step per float; the top 24 bits make a float in [0, 1) that is
 * exact in single precision. */
static float next_random_float(uint32_t *state)
{
    *state = luz_xorshift32(*state);
    return (float)(*state >> 8) / 16777216.0f;
}

static uint32_t seed_state(uint32_t seed)
{
    return seed == 0 ? 0x9E3779B9u : seed;
}

void luz_scene_random_colours(uint32_t seed, int count, luz_vec3 *colours)
{
    uint32_t state = seed_state(seed);
    for (int i = 0; i < count; i++) {
        colours[i].x = next_random_float(&state);
        colours[i].y = next_random_float(&state);
        colours[i].z = next_random_float(&state);
    }
}

/* Angles in degrees reduced to one turn in double precision before they
 * become float, so a long-running animation keeps its precision. */
static float turn_radians(double degrees)
{
    return (float)(fmod(degrees, 360.0) * (LUZ_PI / 180.0));
}

struct luz_lab {
    luz_mesh *cube;
};

luz_lab *luz_lab_create(luz_error *error)
{
    luz_lab *lab = calloc(1, sizeof *lab);
    if (lab == NULL) {
        luz_error_set(error, "out of memory for the lab");
        return NULL;
    }
    lab->cube = luz_cube_mesh_create(error);
    if (lab->cube == NULL) {
        free(lab);
        return NULL;
    }
    return lab;
}

void luz_lab_destroy(luz_lab *lab)
{
    if (lab == NULL) return;
    luz_mesh_destroy(lab->cube);
    free(lab);
}

const luz_mesh *luz_lab_cube_mesh(const luz_lab *lab)
{
    return lab->cube;
}

void luz_scene_set_camera_and_lights(const luz_scene *scene, float aspect, luz_frame *frame)
{
    double t = scene->time_seconds;
    const luz_camera *camera = &scene->camera;
    const luz_vec3 front = luz_camera_front(camera);

    frame->eye = camera->position;
    frame->view = luz_mat4_look_at(camera->position, luz_vec3_add(camera->position, front),
                                   (luz_vec3){0.0f, 1.0f, 0.0f});
    frame->projection = luz_mat4_perspective(luz_radians(camera->fov_degrees), aspect,
                                             0.1f, 100.0f);

    frame->lights = scene->lights;
    double orbit = fmod(0.5 * t, 2.0 * LUZ_PI);
    frame->lights.point_position = (luz_vec3){(float)(3.0 * cos(orbit)), 0.5f,
                                              (float)(3.0 * sin(orbit))};
    double sun = fmod(0.1 * t, 2.0 * LUZ_PI);
    frame->lights.directional_direction = (luz_vec3){(float)cos(sun), (float)sin(sun), 0.0f};
    frame->lights.spot_direction = front;   /* the spot rides on the camera */
    frame->clear_colour = (luz_vec3){0.1f, 0.1f, 0.1f};
    frame->samples = scene->samples;
    frame->output = luz_scene_output(scene);
}

bool luz_scene_has_model(const luz_scene *scene)
{
    for (int i = 0; scene->objects != NULL && i < scene->object_count; i++)
        if (scene->objects[i].model != NULL) return true;
    return false;
}

luz_output luz_scene_output_for(const luz_scene *scene, bool has_model)
{
    luz_output output = {.exposure = has_model ? LUZ_MODEL_EXPOSURE : 0.0f,
                         .tone_map = has_model ? LUZ_MODEL_TONE_MAP : LUZ_TONE_MAP_CLAMP};
    if (scene->has_exposure) output.exposure = scene->exposure;
    if (scene->has_tone_map) output.tone_map = scene->tone_map;
    return output;
}

luz_output luz_scene_output(const luz_scene *scene)
{
    return luz_scene_output_for(scene, luz_scene_has_model(scene));
}

luz_render_options luz_scene_render_options(const luz_scene *scene)
{
    return (luz_render_options){
        .view = scene->view, .interpolation = scene->interpolation, .bug = scene->bug};
}

const char *luz_up_axis_name(luz_up_axis up)
{
    static const char *const names[LUZ_UP_AXIS_COUNT] = {"y", "z", "x", "-y", "-z", "-x"};
    return (unsigned)up < LUZ_UP_AXIS_COUNT ? names[up] : "unknown";
}

bool luz_up_axis_from_name(const char *name, luz_up_axis *up)
{
    for (int axis = 0; axis < LUZ_UP_AXIS_COUNT; axis++) {
        if (strcmp(name, luz_up_axis_name((luz_up_axis)axis)) == 0) {
            *up = (luz_up_axis)axis;
            return true;
        }
    }
    return false;
}

/* The turned vector's coordinates, each a coordinate of (x, y, z) or its
 * negation: SCENE.md's table. */
static luz_vec3 turn_up(luz_up_axis up, luz_vec3 v)
{
    switch (up) {
    case LUZ_UP_Z: return (luz_vec3){v.x, v.z, -v.y};
    case LUZ_UP_X: return (luz_vec3){-v.y, v.x, v.z};
    case LUZ_UP_MINUS_Y: return (luz_vec3){-v.x, -v.y, v.z};
    case LUZ_UP_MINUS_Z: return (luz_vec3){v.x, -v.z, v.y};
    case LUZ_UP_MINUS_X: return (luz_vec3){v.y, -v.x, v.z};
    default: return v;
    }
}

luz_mat4 luz_up_axis_matrix(luz_up_axis up)
{
    /* Column j is the turn of the unit vector e_j. */
    luz_mat4 matrix = luz_mat4_identity();
    const luz_vec3 units[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int j = 0; j < 3; j++) {
        const luz_vec3 column = turn_up(up, units[j]);
        matrix.m[j * 4 + 0] = column.x;
        matrix.m[j * 4 + 1] = column.y;
        matrix.m[j * 4 + 2] = column.z;
    }
    return matrix;
}

luz_mat4 luz_lab_model_normalisation(const luz_lab_model *model, luz_up_axis up)
{
    /* The box after the turn: the turn of the box's corners, each
     * coordinate turned exactly (a permutation with signs), sorted back
     * into min and max. */
    const luz_vec3 a = turn_up(up, model->bounds.min), c = turn_up(up, model->bounds.max);
    const luz_bounds b = {{fminf(a.x, c.x), fminf(a.y, c.y), fminf(a.z, c.z)},
                          {fmaxf(a.x, c.x), fmaxf(a.y, c.y), fmaxf(a.z, c.z)}};
    /* In double: min + max and max - min of huge coordinates overflow a
     * float. */
    const luz_vec3 centre = {(float)(0.5 * ((double)b.min.x + b.max.x)),
                             (float)(0.5 * ((double)b.min.y + b.max.y)),
                             (float)(0.5 * ((double)b.min.z + b.max.z))};
    double side = (double)b.max.x - b.min.x;
    if ((double)b.max.y - b.min.y > side) side = (double)b.max.y - b.min.y;
    if ((double)b.max.z - b.min.z > side) side = (double)b.max.z - b.min.z;
    const float k = (float)(2.0 / side);
    const luz_mat4 scale_and_centre = luz_mat4_translate(
        luz_mat4_scale(luz_mat4_identity(), (luz_vec3){k, k, k}), luz_vec3_scale(centre, -1.0f));
    /* Up is the identity for y: the product then changes no bit. */
    return up == LUZ_UP_Y ? scale_and_centre
                          : luz_mat4_multiply(scale_and_centre, luz_up_axis_matrix(up));
}

/* Object i, a model: M_i(t) = Translate(p) Rotate(angle_i, axis) Scale(k)
 * Norm (placed holds the first two), one draw per part in the file's
 * order. C: the object's colour, else the part's material's, else the
 * seed's for index i. T: none without texture coordinates, else the
 * object's texture, else the material's, else white. */
static int add_model(luz_frame *frame, const luz_scene *scene, const luz_object *object,
                     luz_mat4 placed, luz_vec3 seed_colour, luz_texture *const *textures,
                     int texture_count, luz_error *error)
{
    const luz_lab_model *model = object->model;
    const float k = object->scale > 0.0f ? object->scale : 1.0f;
    const luz_mat4 matrix = luz_mat4_multiply(luz_mat4_scale(placed, (luz_vec3){k, k, k}),
                                              luz_lab_model_normalisation(model, object->up));
    for (int p = 0; p < model->part_count; p++) {
        const luz_lab_model_part *part = &model->parts[p];
        luz_draw draw = {.mesh = part->mesh, .model = matrix};
        draw.material.filter = scene->filter;
        draw.material.colour = object->has_colour ? object->colour
                               : part->has_colour ? part->colour
                                                  : seed_colour;
        draw.material.has_colour = true;
        if (part->has_uvs) {
            if (object->texture != LUZ_TEXTURE_BY_INDEX && texture_count > 0)
                draw.material.texture = textures[object->texture % texture_count];
            else
                draw.material.texture = part->texture;
        }
        if (luz_frame_add_draw(frame, &draw, error) != 0) return -1;
    }
    return 0;
}

int luz_scene_build_frame(const luz_lab *lab, const luz_scene *scene,
                          luz_texture *const *textures, int texture_count, float aspect,
                          luz_frame *frame, luz_error *error)
{
    luz_scene_set_camera_and_lights(scene, aspect, frame);
    frame->draw_count = 0;

    const bool custom = scene->objects != NULL;
    const int object_count = custom ? scene->object_count : scene->cube_count;
    const luz_vec3 axis = {1.0f, 0.5f, 1.0f};
    uint32_t colour_state = seed_state(scene->seed);

    for (int i = 0; i < object_count; i++) {
        /* objectColor: drawn in index order whether used or not, so an
         * object keeps its colour when an earlier one has a colour of its
         * own. */
        luz_vec3 random_colour;
        random_colour.x = next_random_float(&colour_state);
        random_colour.y = next_random_float(&colour_state);
        random_colour.z = next_random_float(&colour_state);

        const luz_object *object = custom ? &scene->objects[i] : NULL;
        const luz_vec3 position = object ? object->position : luz_scene_tiled_position(i);
        const bool turning = !(object && object->model && object->still);
        const double angle_degrees = turning ? (i + 1) / 3.0 * scene->time_seconds * 50.0 : 0.0;
        const luz_mat4 placed = luz_mat4_rotate(luz_mat4_translate(luz_mat4_identity(), position),
                                                turn_radians(angle_degrees), axis);
        if (object && object->model) {
            if (add_model(frame, scene, object, placed, random_colour, textures, texture_count,
                          error) != 0)
                return -1;
            continue;
        }

        luz_draw draw = {0};
        draw.mesh = lab->cube;
        draw.model = placed;
        draw.material.filter = scene->filter;
        draw.material.colour = object && object->has_colour ? object->colour : random_colour;
        draw.material.has_colour = true;
        if (texture_count > 0) {
            int texture = object ? object->texture : LUZ_TEXTURE_BY_INDEX;
            int index = texture == LUZ_TEXTURE_BY_INDEX ? i : texture;
            draw.material.texture = textures[index % texture_count];
        }
        if (luz_frame_add_draw(frame, &draw, error) != 0) return -1;
    }

    /* The point light's marker: a small unrotated cube, unlit, in the
     * light's colour (not scaled by its strength), drawn while it shines. */
    if (scene->lights.point.strength > 0.0f) {
        luz_draw marker = {0};
        marker.mesh = lab->cube;
        marker.model = luz_mat4_scale(
            luz_mat4_translate(luz_mat4_identity(), frame->lights.point_position),
            (luz_vec3){0.2f, 0.2f, 0.2f});
        marker.material = (luz_material){.shading = LUZ_SHADING_UNLIT,
                                         .colour = scene->lights.point.colour,
                                         .has_colour = true};
        if (luz_frame_add_draw(frame, &marker, error) != 0) return -1;
    }
    return 0;
}

int luz_scene_object_of_draw(const luz_scene *scene, int draw_index, int *part)
{
    *part = 0;
    if (draw_index < 0) return LUZ_DRAW_NONE;
    /* One draw a cube, one a model's mesh, in the objects' order, as
     * luz_scene_build_frame adds them. */
    int first = 0;
    if (scene->objects == NULL) {
        if (draw_index < scene->cube_count) return draw_index;
        first = scene->cube_count;
    } else {
        for (int i = 0; i < scene->object_count; i++) {
            const luz_lab_model *model = scene->objects[i].model;
            const int draws = model ? model->part_count : 1;
            if (draw_index < first + draws) {
                *part = draw_index - first;
                return i;
            }
            first += draws;
        }
    }
    if (draw_index == first && scene->lights.point.strength > 0.0f) return LUZ_DRAW_POINT_LIGHT;
    return LUZ_DRAW_NONE;
}
