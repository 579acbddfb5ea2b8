/*
 * torus.c: libluz from a program of your own.
 *
 * Builds a torus in code, gives it a material, lights it with three of the
 * lab's six lights and writes a PNG. It uses only the installed library
 * (and stb_image_write, from Debian's libstb-dev, for the PNG: libluz
 * hands you pixels and leaves files to you):
 *
 *   cc torus.c -o torus $(pkg-config --cflags --libs luz stb) -lm
 *   ./torus torus.png
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <luz/luz.h>

#include <stb_image_write.h>

enum { SIZE = 256, RINGS = 48, SIDES = 24 };
static const float RING_RADIUS = 1.0f, TUBE_RADIUS = 0.35f;

/* A torus around the z axis: (R + r cos b) (cos a, sin a) in x and y,
 * r sin b in z; its normal points away from the tube's centre line. Each
 * quad of the grid is two counter-clockwise triangles seen from outside. */
static luz_mesh *make_torus(luz_error *error)
{
    static luz_vertex vertices[(RINGS + 1) * (SIDES + 1)];
    static uint32_t indices[RINGS * SIDES * 6];
    for (int i = 0; i <= RINGS; i++) {
        for (int j = 0; j <= SIDES; j++) {
            float a = 2.0f * (float)LUZ_PI * (float)i / RINGS;
            float b = 2.0f * (float)LUZ_PI * (float)j / SIDES;
            luz_vec3 normal = {cosf(b) * cosf(a), cosf(b) * sinf(a), sinf(b)};
            luz_vec3 centre = {RING_RADIUS * cosf(a), RING_RADIUS * sinf(a), 0.0f};
            vertices[i * (SIDES + 1) + j] = (luz_vertex){
                .position = luz_vec3_add(centre, luz_vec3_scale(normal, TUBE_RADIUS)),
                .normal = normal,
                .uv = {(float)i / RINGS, (float)j / SIDES},
            };
        }
    }
    uint32_t *index = indices;
    for (uint32_t i = 0; i < RINGS; i++) {
        for (uint32_t j = 0; j < SIDES; j++) {
            uint32_t v00 = i * (SIDES + 1) + j, v10 = v00 + SIDES + 1;
            uint32_t v01 = v00 + 1, v11 = v10 + 1;
            *index++ = v00, *index++ = v10, *index++ = v11;
            *index++ = v00, *index++ = v11, *index++ = v01;
        }
    }
    return luz_mesh_create(&(luz_mesh_desc){
                               .vertices = vertices,
                               .vertex_count = (RINGS + 1) * (SIDES + 1),
                               .indices = indices,
                               .index_count = RINGS * SIDES * 6,
                           },
                           error);
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "torus.png";
    luz_error error = {{0}};
    luz_mesh *torus = make_torus(&error);
    luz_renderer *renderer = torus ? luz_renderer_create(NULL, &error) : NULL;
    luz_framebuffer *framebuffer = renderer ? luz_framebuffer_create(SIZE, SIZE, &error) : NULL;
    if (framebuffer == NULL) {
        fprintf(stderr, "torus: %s\n", error.message);
        return 1;
    }

    /* The camera: four units in front of the torus, looking at its centre. */
    luz_frame frame = {0};
    frame.eye = (luz_vec3){0.0f, 0.0f, 4.0f};
    frame.view = luz_mat4_look_at(frame.eye, (luz_vec3){0, 0, 0}, (luz_vec3){0, 1, 0});
    frame.projection = luz_mat4_perspective(luz_radians(45.0f), 1.0f, 0.1f, 100.0f);
    frame.clear_colour = (luz_vec3){0.1f, 0.1f, 0.1f};

    /* Lights: a dim ambient term, the headlight's diffuse and specular
     * light, and a warm point light up and to the right. The others stay
     * at strength 0, which is exactly nothing. */
    frame.lights.ambient = (luz_light){{1.0f, 1.0f, 1.0f}, 0.15f};
    frame.lights.diffuse = (luz_light){{1.0f, 1.0f, 1.0f}, 0.6f};
    frame.lights.specular = (luz_light){{1.0f, 1.0f, 1.0f}, 0.4f};
    frame.lights.shininess = 32.0f;
    frame.lights.point = (luz_light){{1.0f, 0.8f, 0.6f}, 0.5f};
    frame.lights.point_position = (luz_vec3){3.0f, 3.0f, 3.0f};
    frame.lights.spot_reach = 1.0f;

    /* One draw: the torus, turned a little, in an orange material. */
    luz_draw draw = {
        .mesh = torus,
        .model = luz_mat4_rotate(luz_mat4_identity(), luz_radians(20.0f), (luz_vec3){1, 0, 0}),
        .material = {.colour = {0.9f, 0.5f, 0.2f}, .has_colour = true},
    };
    int status = luz_frame_add_draw(&frame, &draw, &error) == 0 &&
                 luz_renderer_draw(renderer, &frame, framebuffer, NULL, &error) == 0
                     ? 0
                     : 1;
    if (status != 0)
        fprintf(stderr, "torus: %s\n", error.message);
    else if (!stbi_write_png(path, SIZE, SIZE, 4, framebuffer->colour, SIZE * 4))
        fprintf(stderr, "torus: cannot write %s\n", path), status = 1;
    else
        printf("torus: %u triangles drawn into %s\n", luz_mesh_triangle_count(torus), path);

    luz_frame_free(&frame);
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
    luz_mesh_destroy(torus);
    return status;
}
