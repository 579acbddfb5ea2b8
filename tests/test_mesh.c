/*
 * test_mesh.c: libluz as a program of its own would use it: meshes made
 * and checked once, materials per draw, zero descs as defaults, and every
 * failure saying why.
 *
 * The frames here are built by hand, not by the lab: a camera at the
 * origin looking down -z with a 90-degree field of view on a square image,
 * so that the point (x, y, -d) lands on NDC (x / d, y / d), and no light
 * but the ambient term, so that a lit pixel is ambient * colour * texel.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "luz/luz.h"

enum { SIZE = 32 };

static luz_frame camera_frame(void)
{
    luz_frame frame = {0};
    frame.view = luz_mat4_identity();
    frame.projection = luz_mat4_perspective((float)(LUZ_PI / 2.0), 1.0f, 0.1f, 100.0f);
    frame.lights.ambient = (luz_light){{1.0f, 1.0f, 1.0f}, 1.0f};
    frame.lights.spot_reach = 1.0f;
    frame.clear_colour = (luz_vec3){0.0f, 0.0f, 0.0f};
    return frame;
}

/* A quad over NDC [x0, x1] x [y0, y1] at depth 2, counter-clockwise, uv
 * over [0, 1] with v = 0 on top. */
static void quad_vertices(luz_vertex vertices[4], float x0, float x1, float y0, float y1)
{
    const float d = 2.0f;
    const luz_vec3 n = {0.0f, 0.0f, 1.0f};
    vertices[0] = (luz_vertex){{x0 * d, y0 * d, -d}, n, {0.0f, 1.0f}};
    vertices[1] = (luz_vertex){{x1 * d, y0 * d, -d}, n, {1.0f, 1.0f}};
    vertices[2] = (luz_vertex){{x1 * d, y1 * d, -d}, n, {1.0f, 0.0f}};
    vertices[3] = (luz_vertex){{x0 * d, y1 * d, -d}, n, {0.0f, 0.0f}};
}

static luz_framebuffer *render_frame(const luz_frame *frame, const luz_render_options *options,
                                     int threads)
{
    luz_error error = {{0}};
    luz_renderer *renderer =
        luz_renderer_create(&(luz_renderer_desc){.thread_count = threads}, &error);
    assert_non_null(renderer);
    luz_framebuffer *framebuffer = luz_framebuffer_create(SIZE, SIZE, &error);
    assert_non_null(framebuffer);
    assert_int_equal(luz_renderer_draw(renderer, frame, framebuffer, options, &error), 0);
    luz_renderer_destroy(renderer);
    return framebuffer;
}

static luz_framebuffer *draw_image(const luz_frame *frame)
{
    return render_frame(frame, NULL, 2);
}

static const uint8_t *pixel(const luz_framebuffer *framebuffer, int x, int y)
{
    return framebuffer->colour + ((size_t)y * framebuffer->width + x) * 4;
}

static void assert_pixel(const luz_framebuffer *framebuffer, int x, int y, int r, int g, int b)
{
    const uint8_t *p = pixel(framebuffer, x, y);
    if (p[0] != r || p[1] != g || p[2] != b)
        fail_msg("pixel (%d, %d) is (%d, %d, %d), expected (%d, %d, %d)", x, y, p[0], p[1], p[2],
                 r, g, b);
}

static void assert_error_says(int status, const luz_error *error, const char *words)
{
    assert_int_equal(status, -1);
    if (strstr(error->message, words) == NULL)
        fail_msg("error '%s' does not say '%s'", error->message, words);
}

/* ---- making meshes ------------------------------------------------------------------ */

/* Each malformed desc is refused, and the message names what is wrong. */
static void test_bad_meshes_are_refused_with_a_reason(void **state)
{
    (void)state;
    luz_vertex vertices[4];
    quad_vertices(vertices, -1, 1, -1, 1);
    const uint32_t past_the_end[3] = {0, 1, 4};
    const uint32_t good[6] = {0, 1, 2, 0, 2, 3};
    const uint16_t good16[3] = {0, 1, 2};
    struct {
        luz_mesh_desc desc;
        const char *says;
    } cases[] = {
        {{.vertices = vertices, .vertex_count = 4, .indices = past_the_end, .index_count = 3},
         "index 2 is 4, past the last of 4 vertices"},
        {{.vertices = vertices, .vertex_count = 4, .indices = good, .index_count = 5},
         "5 indices, expected a multiple of 3"},
        {{.vertices = vertices, .vertex_count = 4}, "4 vertices and no indices"},
        {{.vertex_count = 3, .indices = good, .index_count = 3}, "no vertex array"},
        {{.vertices = vertices, .vertex_count = 4, .index_count = 3}, "no index array"},
        {{.vertices = vertices, .vertex_count = 4, .indices = good, .indices16 = good16,
          .index_count = 3},
         "both indices and indices16"},
        {{.vertices = vertices, .vertex_count = LUZ_MESH_MAX_VERTICES + 1u, .indices = good,
          .index_count = 3},
         "expected at most"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        luz_error error = {{0}};
        luz_mesh *mesh = luz_mesh_create(&cases[i].desc, &error);
        assert_null(mesh);
        if (strstr(error.message, cases[i].says) == NULL)
            fail_msg("case %zu: '%s' does not say '%s'", i, error.message, cases[i].says);
    }

    /* A position that is not finite would reach clipping as NaN. */
    vertices[2].position.y = NAN;
    luz_error error = {{0}};
    assert_null(luz_mesh_create(&(luz_mesh_desc){.vertices = vertices, .vertex_count = 4,
                                                 .indices = good, .index_count = 6},
                                &error));
    assert_non_null(strstr(error.message, "vertex 2 has a position that is not finite"));
}

/* The zero desc (and NULL) is an empty mesh: no vertices, no triangles,
 * and a frame that draws it shows the background everywhere. */
static void test_zero_desc_is_an_empty_mesh(void **state)
{
    (void)state;
    luz_error error = {{0}};
    luz_mesh *empty = luz_mesh_create(&(luz_mesh_desc){0}, &error);
    luz_mesh *null_desc = luz_mesh_create(NULL, &error);
    assert_non_null(empty);
    assert_non_null(null_desc);
    assert_int_equal(luz_mesh_vertex_count(empty), 0);
    assert_int_equal(luz_mesh_triangle_count(empty), 0);
    luz_bounds bounds = luz_mesh_bounds(empty);
    assert_true(bounds.min.x == 0 && bounds.max.z == 0);

    luz_frame frame = camera_frame();
    frame.clear_colour = (luz_vec3){0.2f, 0.4f, 0.6f};
    assert_int_equal(luz_frame_add_draw(&frame, &(luz_draw){.mesh = empty,
                                                            .model = luz_mat4_identity()},
                                        &error),
                     0);
    luz_framebuffer *framebuffer = render_frame(&frame, NULL, 1);
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++) assert_pixel(framebuffer, x, y, 51, 102, 153);
    luz_framebuffer_destroy(framebuffer);
    luz_frame_free(&frame);
    luz_mesh_destroy(empty);
    luz_mesh_destroy(null_desc);
}

/* Counts and bounds are the mesh's; the mesh owns copies of the arrays, so
 * the caller may change or free them at once. */
static void test_mesh_copies_its_arrays_and_knows_its_bounds(void **state)
{
    (void)state;
    luz_vertex vertices[4];
    quad_vertices(vertices, -0.5f, 0.25f, -0.75f, 1.0f);
    uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    luz_error error = {{0}};
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices, .vertex_count = 4,
                                                      .indices = indices, .index_count = 6},
                                     &error);
    assert_non_null(mesh);
    assert_int_equal(luz_mesh_vertex_count(mesh), 4);
    assert_int_equal(luz_mesh_triangle_count(mesh), 2);
    luz_bounds bounds = luz_mesh_bounds(mesh);
    /* x from -0.5 * 2 to 0.25 * 2, y from -0.75 * 2 to 1 * 2, z = -2. */
    assert_true(bounds.min.x == -1.0f && bounds.max.x == 0.5f);
    assert_true(bounds.min.y == -1.5f && bounds.max.y == 2.0f);
    assert_true(bounds.min.z == -2.0f && bounds.max.z == -2.0f);

    luz_frame frame = camera_frame();
    luz_draw quad = {.mesh = mesh, .model = luz_mat4_identity()};
    quad.material.colour = (luz_vec3){1.0f, 1.0f, 1.0f};
    assert_int_equal(luz_frame_add_draw(&frame, &quad, &error), 0);
    luz_framebuffer *before = render_frame(&frame, NULL, 1);
    /* Scribble over the caller's arrays: the mesh does not see it. */
    memset(vertices, 0xff, sizeof vertices);
    memset(indices, 0xff, sizeof indices);
    luz_framebuffer *after = render_frame(&frame, NULL, 1);
    assert_memory_equal(before->colour, after->colour, (size_t)SIZE * SIZE * 4);
    /* The quad covers NDC x in [-0.5, 0.25]: pixel columns 8 to 19. */
    assert_pixel(after, 12, 16, 255, 255, 255);
    assert_pixel(after, 4, 16, 0, 0, 0);
    luz_framebuffer_destroy(before);
    luz_framebuffer_destroy(after);
    luz_frame_free(&frame);
    luz_mesh_destroy(mesh);
}

/* 32-bit indices, 16-bit indices and no indices at all describe the same
 * triangles, and draw the same image. */
static void test_index_kinds_draw_the_same_image(void **state)
{
    (void)state;
    luz_vertex quad[4];
    quad_vertices(quad, -0.75f, 0.5f, -0.5f, 0.875f);
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    const uint16_t indices16[6] = {0, 1, 2, 0, 2, 3};
    const luz_vertex unrolled[6] = {quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]};
    const luz_mesh_desc descs[3] = {
        {.vertices = quad, .vertex_count = 4, .indices = indices, .index_count = 6},
        {.vertices = quad, .vertex_count = 4, .indices16 = indices16, .index_count = 6},
        {.vertices = unrolled, .vertex_count = 6},
    };
    luz_framebuffer *images[3];
    for (int k = 0; k < 3; k++) {
        luz_error error = {{0}};
        luz_mesh *mesh = luz_mesh_create(&descs[k], &error);
        assert_non_null(mesh);
        assert_int_equal(luz_mesh_triangle_count(mesh), 2);
        luz_frame frame = camera_frame();
        luz_draw draw = {.mesh = mesh, .model = luz_mat4_identity()};
        draw.material.colour = (luz_vec3){0.5f, 1.0f, 0.25f};
        draw.material.has_colour = true;
        assert_int_equal(luz_frame_add_draw(&frame, &draw, &error), 0);
        images[k] = draw_image(&frame);
        luz_frame_free(&frame);
        luz_mesh_destroy(mesh);
    }
    assert_pixel(images[0], 10, 12, 128, 255, 64);
    assert_memory_equal(images[0]->colour, images[1]->colour, (size_t)SIZE * SIZE * 4);
    assert_memory_equal(images[0]->colour, images[2]->colour, (size_t)SIZE * SIZE * 4);
    for (int k = 0; k < 3; k++) luz_framebuffer_destroy(images[k]);
}

/* A mesh past 16-bit indices: a strip of 70,000 vertices whose only
 * triangle uses the last three. It lands where they put it. */
static void test_more_than_65536_vertices(void **state)
{
    (void)state;
    enum { COUNT = 70000 };
    luz_vertex *vertices = calloc(COUNT, sizeof *vertices);
    assert_non_null(vertices);
    for (int i = 0; i < COUNT - 3; i++)   /* far behind the camera: never seen */
        vertices[i] = (luz_vertex){{0.0f, 0.0f, 50.0f}, {0, 0, 1}, {0, 0}};
    luz_vertex quad[4];
    quad_vertices(quad, 0.0f, 1.0f, 0.0f, 1.0f);   /* the upper right quarter */
    vertices[COUNT - 3] = quad[0];
    vertices[COUNT - 2] = quad[1];
    vertices[COUNT - 1] = quad[2];
    const uint32_t indices[3] = {COUNT - 3, COUNT - 2, COUNT - 1};
    luz_error error = {{0}};
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices, .vertex_count = COUNT,
                                                      .indices = indices, .index_count = 3},
                                     &error);
    free(vertices);
    assert_non_null(mesh);
    luz_frame frame = camera_frame();
    luz_draw draw = {.mesh = mesh, .model = luz_mat4_identity()};
    draw.material.colour = (luz_vec3){1.0f, 1.0f, 1.0f};
    assert_int_equal(luz_frame_add_draw(&frame, &draw, &error), 0);
    luz_framebuffer *framebuffer = draw_image(&frame);
    /* The triangle (0, 0), (1, 0), (1, 1) in NDC: below the diagonal of the
     * upper right quarter, which is pixels x >= 16, y < 16, x + y > 31. */
    assert_pixel(framebuffer, 28, 10, 255, 255, 255);
    assert_pixel(framebuffer, 18, 3, 0, 0, 0);
    assert_pixel(framebuffer, 8, 24, 0, 0, 0);
    luz_framebuffer_destroy(framebuffer);
    luz_frame_free(&frame);
    luz_mesh_destroy(mesh);
}

/* ---- materials ------------------------------------------------------------------------ */

/* Each draw is shaded by its own material: in one frame, an unlit quad
 * shows its colour as it is, a lit one ambient * colour * texel, and two
 * textured quads sample with their own filters (each the same as a frame
 * that holds that quad alone). */
static void test_each_draw_has_its_own_material(void **state)
{
    (void)state;
    /* A 2 x 2 texture: nearest and bilinear sampling differ between the
     * texel centres. */
    const uint8_t texels[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255,
                                255};
    luz_error error = {{0}};
    luz_texture *texture = luz_texture_create(2, 2, texels, &error);
    assert_non_null(texture);

    luz_vertex left[4], right[4], top[4];
    quad_vertices(left, -1.0f, 0.0f, -1.0f, 0.0f);
    quad_vertices(right, 0.0f, 1.0f, -1.0f, 0.0f);
    quad_vertices(top, -1.0f, 1.0f, 0.0f, 1.0f);
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    luz_mesh *meshes[3];
    const luz_vertex *arrays[3] = {left, right, top};
    for (int k = 0; k < 3; k++) {
        meshes[k] = luz_mesh_create(&(luz_mesh_desc){.vertices = arrays[k], .vertex_count = 4,
                                                     .indices = indices, .index_count = 6},
                                    &error);
        assert_non_null(meshes[k]);
    }
    const luz_material nearest = {.colour = {1, 1, 1}, .texture = texture,
                                  .filter = LUZ_FILTER_NEAREST};
    const luz_material bilinear = {.colour = {1, 1, 1}, .texture = texture,
                                   .filter = LUZ_FILTER_BILINEAR};
    const luz_material unlit = {.shading = LUZ_SHADING_UNLIT, .colour = {0.2f, 0.6f, 1.0f},
                                .has_colour = true, .texture = texture};

    luz_frame frame = camera_frame();
    frame.lights.ambient.strength = 0.5f;
    const luz_draw draws[3] = {
        {meshes[0], luz_mat4_identity(), nearest},
        {meshes[1], luz_mat4_identity(), bilinear},
        {meshes[2], luz_mat4_identity(), unlit},
    };
    for (int k = 0; k < 3; k++) assert_int_equal(luz_frame_add_draw(&frame, &draws[k], &error), 0);
    luz_framebuffer *together = draw_image(&frame);

    /* The unlit quad: its colour, no light, no texture. */
    assert_pixel(together, 16, 4, 51, 153, 255);
    /* Each textured quad equals itself drawn alone. */
    for (int k = 0; k < 2; k++) {
        luz_frame alone = camera_frame();
        alone.lights.ambient.strength = 0.5f;
        assert_int_equal(luz_frame_add_draw(&alone, &draws[k], &error), 0);
        luz_framebuffer *image = draw_image(&alone);
        for (int y = SIZE / 2; y < SIZE; y++)
            for (int x = k * SIZE / 2; x < (k + 1) * SIZE / 2; x++)
                assert_memory_equal(pixel(image, x, y), pixel(together, x, y), 4);
        luz_framebuffer_destroy(image);
        luz_frame_free(&alone);
    }
    /* Nearest: pixel (2, 18) is in the top left texel, red, at half
     * strength. Bilinear at the same spot of the right quad mixes in the
     * neighbours, so it is not pure red. */
    assert_pixel(together, 2, 18, 128, 0, 0);
    const uint8_t *mixed = pixel(together, 16 + 6, 18 + 4);
    assert_true(mixed[1] > 0 || mixed[2] > 0);

    luz_framebuffer_destroy(together);
    luz_frame_free(&frame);
    for (int k = 0; k < 3; k++) luz_mesh_destroy(meshes[k]);
    luz_texture_destroy(texture);
}

/* ---- the renderer's defaults and errors -------------------------------------------------- */

static void test_zero_desc_is_one_thread_per_cpu(void **state)
{
    (void)state;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    int expected = cpus < 1 ? 1 : cpus > LUZ_MAX_THREADS ? LUZ_MAX_THREADS : (int)cpus;
    luz_error error = {{0}};
    luz_renderer *zero = luz_renderer_create(&(luz_renderer_desc){0}, &error);
    luz_renderer *null_desc = luz_renderer_create(NULL, &error);
    luz_renderer *one = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    assert_non_null(zero);
    assert_non_null(null_desc);
    assert_non_null(one);
    assert_int_equal(luz_renderer_thread_count(zero), expected);
    assert_int_equal(luz_renderer_thread_count(null_desc), expected);
    assert_int_equal(luz_renderer_thread_count(one), 1);
    luz_renderer_destroy(zero);
    luz_renderer_destroy(null_desc);
    luz_renderer_destroy(one);

    assert_null(luz_renderer_create(&(luz_renderer_desc){.thread_count = LUZ_MAX_THREADS + 1},
                                    &error));
    assert_non_null(strstr(error.message, "thread count 257"));
    assert_null(luz_renderer_create(&(luz_renderer_desc){.thread_count = -2}, &error));
    assert_non_null(strstr(error.message, "thread count -2"));
}

/* Textures and framebuffers refuse what they cannot hold, and say why. */
static void test_textures_and_framebuffers_say_why(void **state)
{
    (void)state;
    luz_error error = {{0}};
    assert_null(luz_texture_create(4, 4, NULL, &error));
    assert_non_null(strstr(error.message, "texture 4x4: no pixels"));
    const uint8_t texel[4] = {0};
    assert_null(luz_texture_create(0, 1, texel, &error));
    assert_non_null(strstr(error.message, "texture size 0x1"));
    assert_null(luz_framebuffer_create(LUZ_MAX_DIMENSION + 1, 1, &error));
    assert_true(error.message[0] != '\0');
}

/* A frame whose draw has no mesh, and render options that name no view,
 * are refused with a reason before anything is drawn. */
static void test_bad_frames_are_refused_with_a_reason(void **state)
{
    (void)state;
    luz_error error = {{0}};
    luz_frame frame = camera_frame();
    assert_error_says(luz_frame_add_draw(&frame, &(luz_draw){0}, &error), &error,
                      "draw 0: no mesh");
    assert_int_equal(frame.draw_count, 0);

    luz_draw by_hand = {0};
    luz_frame bad = camera_frame();
    bad.draws = &by_hand;
    bad.draw_count = 1;
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(SIZE, SIZE, &error);
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    assert_error_says(luz_renderer_draw(renderer, &bad, framebuffer, NULL, &error), &error,
                      "draw 0: no mesh");
    assert_error_says(luz_renderer_draw(renderer, &frame, framebuffer,
                                        &(luz_render_options){.view = LUZ_VIEW_COUNT}, &error),
                      &error, "is not a luz_view");
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
}


/* ---- zero means the default (luz/frame.h) ------------------------------------------------- */

/* A quad over the middle of the view, at depth 2, facing the camera. */
static luz_mesh *middle_quad(void)
{
    luz_vertex vertices[4];
    quad_vertices(vertices, -0.5f, 0.5f, -0.5f, 0.5f);
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    luz_error error = {{0}};
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices, .vertex_count = 4,
                                                      .indices = indices, .index_count = 6},
                                     &error);
    assert_non_null(mesh);
    return mesh;
}

/* A zero material is lit, white and untextured: under ambient light alone
 * of strength 0.5, SCENE.md's colour is 0.5 x C x T = 0.5 x 1 x 1, byte
 * round(127.5) = 128 (it was 0: black). An unlit zero material is white,
 * 255. A colour other than (0, 0, 0) is used as given, with or without
 * has_colour (a caller who sets only the colour gets it); black needs
 * has_colour. */
static void test_zero_material_is_lit_and_white(void **state)
{
    (void)state;
    _Static_assert(LUZ_FILTER_TRILINEAR == 0 && LUZ_SHADING_LIT == 0,
                   "a zero material samples trilinearly and is lit");
    luz_mesh *quad = middle_quad();
    static const struct {
        luz_material material;
        int byte[3];
    } cases[] = {
        {{0}, {128, 128, 128}},
        {{.shading = LUZ_SHADING_UNLIT}, {255, 255, 255}},
        {{.colour = {0.0f, 0.0f, 0.0f}, .has_colour = true}, {0, 0, 0}},
        /* 0.5 x (1, 0.5, 0.2): 127.5, 63.75, 25.5 */
        {{.colour = {1.0f, 0.5f, 0.2f}, .has_colour = true}, {128, 64, 26}},
        {{.colour = {1.0f, 0.5f, 0.2f}}, {128, 64, 26}},
        /* 0.5 x (0, 0.5, 0): a colour with one zero channel stays itself */
        {{.colour = {0.0f, 0.5f, 0.0f}}, {0, 64, 0}},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        luz_frame frame = camera_frame();
        frame.lights.ambient.strength = 0.5f;
        frame.draws = &(luz_draw){.mesh = quad, .model = luz_mat4_identity(),
                                  .material = cases[c].material};
        frame.draw_count = 1;
        luz_framebuffer *framebuffer = draw_image(&frame);
        assert_pixel(framebuffer, SIZE / 2, SIZE / 2, cases[c].byte[0], cases[c].byte[1],
                     cases[c].byte[2]);
        assert_pixel(framebuffer, 0, 0, 0, 0, 0);   /* the clear colour, outside the quad */
        luz_framebuffer_destroy(framebuffer);
    }
    luz_mesh_destroy(quad);
}

/* A zero spot_reach is SCENE.md's 10, not a division by 0 (which left the
 * spot dark): the spot alone, white at strength 1, on the quad at depth 2,
 * gives reach 0 and reach 10 the same image; the middle pixel worked from
 * SCENE.md's equations in double: the pixel centre (16.5, 16.5) of 32x32
 * is NDC (1/32, -1/32), P = (1/16, -1/16, -2), inside the inner cone (c =
 * 0.99902 > cos 12.5 = 0.97630, f_dir = 1), dn = |E - P| / 10 = 0.200195,
 * f_dist = (1 - dn^4)^2 / (dn^2 + 1) = 0.958380: byte 244. */
static void test_zero_spot_reach_is_scene_default(void **state)
{
    (void)state;
    luz_mesh *quad = middle_quad();
    luz_framebuffer *images[2];
    const float reaches[2] = {0.0f, 10.0f};
    for (int k = 0; k < 2; k++) {
        luz_frame frame = camera_frame();
        frame.lights.ambient.strength = 0.0f;
        frame.lights.spot = (luz_light){{1.0f, 1.0f, 1.0f}, 1.0f};
        frame.lights.spot_direction = (luz_vec3){0.0f, 0.0f, -1.0f};
        frame.lights.spot_inner_degrees = 12.5f;
        frame.lights.spot_outer_degrees = 17.5f;
        frame.lights.spot_reach = reaches[k];
        frame.draws = &(luz_draw){.mesh = quad, .model = luz_mat4_identity()};
        frame.draw_count = 1;
        images[k] = draw_image(&frame);
    }
    const double x = 1.0 / 16.0, y = -1.0 / 16.0, z = -2.0;
    const double distance = sqrt(x * x + y * y + z * z);
    assert_true(-z / distance > cos(12.5 * LUZ_PI / 180.0));
    const double dn = distance / 10.0;
    const double window = 1.0 - dn * dn * dn * dn;
    const double spot = window * window / (dn * dn + 1.0);
    const int byte = (int)lround(spot * 255.0);
    assert_int_equal(byte, 244);
    assert_pixel(images[0], SIZE / 2, SIZE / 2, byte, byte, byte);
    assert_memory_equal(images[0]->colour, images[1]->colour, (size_t)SIZE * SIZE * 4);
    luz_framebuffer_destroy(images[0]);
    luz_framebuffer_destroy(images[1]);
    luz_mesh_destroy(quad);
}

/* Lights luz/frame.h forbids are refused by luz_renderer_draw, each with
 * a message naming the field, and the framebuffer is left as it was. */
static void test_forbidden_lights_are_refused(void **state)
{
    (void)state;
    luz_mesh *quad = middle_quad();
    luz_error error = {{0}};
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(SIZE, SIZE, &error);
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    memset(framebuffer->colour, 77, (size_t)SIZE * SIZE * 4);
    enum { REACH, SHININESS, INNER, OUTER, AMBIENT, SPOT };
    static const struct {
        int field;
        float value;
        const char *words;
    } cases[] = {
        {REACH, -1.0f, "spot_reach -1: expected a finite number above 0"},
        {REACH, NAN, "spot_reach nan"},
        {REACH, INFINITY, "spot_reach inf"},
        {SHININESS, -0.5f, "shininess -0.5: expected a finite number >= 0"},
        {SHININESS, INFINITY, "shininess inf"},
        {INNER, 20.0f, "spot cone 20 to 17.5 degrees: expected 0 <= inner <= outer <= 89"},
        {INNER, -1.0f, "spot cone -1 to 17.5"},
        {OUTER, 90.0f, "spot cone 12.5 to 90"},
        {OUTER, NAN, "spot cone 12.5 to nan"},
        {AMBIENT, 1.5f, "the ambient light's strength 1.5: expected a number in [0, 1]"},
        {AMBIENT, -0.25f, "the ambient light's strength -0.25"},
        {SPOT, NAN, "the spot light's strength nan"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        luz_frame frame = camera_frame();
        frame.lights.spot_inner_degrees = 12.5f;
        frame.lights.spot_outer_degrees = 17.5f;
        switch (cases[c].field) {
        case REACH: frame.lights.spot_reach = cases[c].value; break;
        case SHININESS: frame.lights.shininess = cases[c].value; break;
        case INNER: frame.lights.spot_inner_degrees = cases[c].value; break;
        case OUTER: frame.lights.spot_outer_degrees = cases[c].value; break;
        case AMBIENT: frame.lights.ambient.strength = cases[c].value; break;
        default: frame.lights.spot.strength = cases[c].value; break;
        }
        frame.draws = &(luz_draw){.mesh = quad, .model = luz_mat4_identity()};
        frame.draw_count = 1;
        assert_error_says(luz_renderer_draw(renderer, &frame, framebuffer, NULL, &error), &error,
                          cases[c].words);
        for (size_t i = 0; i < (size_t)SIZE * SIZE * 4; i++)
            if (framebuffer->colour[i] != 77) fail_msg("case %zu drew byte %zu", c, i);
    }
    /* the edges themselves are allowed: reach 0 (the default), shininess
     * 0, a cone of 0 to 0 and of 89 to 89, strengths 0 and 1 */
    const float cones[2] = {0.0f, 89.0f};
    for (int k = 0; k < 2; k++) {
        luz_frame frame = camera_frame();
        frame.lights.spot_inner_degrees = frame.lights.spot_outer_degrees = cones[k];
        frame.lights.spot_reach = 0.0f;
        frame.lights.spot.strength = 1.0f;
        frame.draws = &(luz_draw){.mesh = quad, .model = luz_mat4_identity()};
        frame.draw_count = 1;
        assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, NULL, &error), 0);
    }
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
    luz_mesh_destroy(quad);
}

/* Who owns the draws (luz/frame.h): an array of the caller's, on the stack
 * here, is never freed by luz_frame_free (free() of it aborted, and
 * AddressSanitizer names it), and luz_frame_add_draw copies it into an
 * array of the frame's own, leaving the caller's as it was; that one
 * luz_frame_free frees (LeakSanitizer would see it left). */
static void test_frame_owns_only_its_own_draws(void **state)
{
    (void)state;
    luz_mesh *quad = middle_quad();
    luz_error error = {{0}};
    luz_draw mine[2] = {{.mesh = quad, .model = luz_mat4_identity()},
                        {.mesh = quad, .model = luz_mat4_translate(luz_mat4_identity(),
                                                                   (luz_vec3){1, 0, 0})}};
    luz_frame frame = camera_frame();
    frame.draws = mine;
    frame.draw_count = 2;
    luz_frame_free(&frame);
    assert_null(frame.draws);
    assert_int_equal(frame.draw_count, 0);
    assert_ptr_equal(mine[0].mesh, quad);   /* the caller's array, untouched */

    frame.draws = mine;
    frame.draw_count = 2;
    const luz_draw third = {.mesh = quad, .model = luz_mat4_identity(),
                            .material = {.shading = LUZ_SHADING_UNLIT}};
    assert_int_equal(luz_frame_add_draw(&frame, &third, &error), 0);
    assert_true(frame.draws != mine);
    assert_true(frame.draw_capacity >= 3);
    assert_int_equal(frame.draw_count, 3);
    assert_memory_equal(frame.draws, mine, sizeof mine);
    assert_int_equal(frame.draws[2].material.shading, LUZ_SHADING_UNLIT);
    assert_int_equal(mine[1].material.shading, LUZ_SHADING_LIT);
    luz_frame_free(&frame);
    assert_null(frame.draws);
    assert_int_equal(frame.draw_capacity, 0);
    luz_mesh_destroy(quad);
}

/* ---- big meshes: batches --------------------------------------------------------------- */

/* 10,000 small coplanar triangles, all at depth 2: with the LESS depth test
 * the first triangle (in submission order) that covers a pixel centre
 * keeps it. Triangle k's three uvs all point at texel k mod 251 of a
 * texture whose texels all differ, so a pixel says which triangle won.
 * The renderer cuts a mesh this big into batches over its threads; the
 * expected winner is worked out here, pixel by pixel, by testing the
 * triangles in order in double precision. */
enum { BIG_TRIANGLES = 10000, TEXELS = 251 };

typedef struct big_mesh {
    luz_vertex vertices[3 * BIG_TRIANGLES];
    double ndc[BIG_TRIANGLES][3][2];
    uint8_t texels[TEXELS * 4];
} big_mesh;

static void make_big_mesh(big_mesh *big)
{
    uint32_t random = 12345;
    for (int t = 0; t < TEXELS; t++) {
        big->texels[4 * t + 0] = (uint8_t)t;
        big->texels[4 * t + 1] = (uint8_t)(255 - t);
        big->texels[4 * t + 2] = (uint8_t)(t * 7);
        big->texels[4 * t + 3] = 255;
    }
    for (int k = 0; k < BIG_TRIANGLES; k++) {
        double x[3], y[3];
        double cx, cy;
        random = random * 1664525u + 1013904223u;
        cx = (random >> 8) / 16777216.0 * 2.0 - 1.0;
        random = random * 1664525u + 1013904223u;
        cy = (random >> 8) / 16777216.0 * 2.0 - 1.0;
        for (int v = 0; v < 3; v++) {
            random = random * 1664525u + 1013904223u;
            x[v] = cx + ((random >> 8) / 16777216.0 - 0.5) * 0.4;
            random = random * 1664525u + 1013904223u;
            y[v] = cy + ((random >> 8) / 16777216.0 - 0.5) * 0.4;
        }
        /* Counter-clockwise in NDC: a front face. */
        if ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]) < 0.0) {
            double swap_x = x[1], swap_y = y[1];
            x[1] = x[2], y[1] = y[2];
            x[2] = swap_x, y[2] = swap_y;
        }
        const luz_vec2 uv = {((float)(k % TEXELS) + 0.5f) / TEXELS, 0.5f};
        for (int v = 0; v < 3; v++) {
            /* Stored as the float the vertex holds, so that both sides see
             * the same triangle. */
            const float d = 2.0f;
            big->vertices[3 * k + v] = (luz_vertex){{(float)x[v] * d, (float)y[v] * d, -d},
                                                    {0.0f, 0.0f, 1.0f}, uv};
            big->ndc[k][v][0] = big->vertices[3 * k + v].position.x / 2.0;
            big->ndc[k][v][1] = big->vertices[3 * k + v].position.y / 2.0;
        }
    }
}

/* The winner at pixel (px, py) among triangles [0, count): its index, -1
 * for none, or -2 when a pixel centre lies so near an edge of a triangle
 * tested before the winner that the fill rule, not geometry, decides. */
static int expected_winner(const big_mesh *big, int count, int px, int py)
{
    const double x = (px + 0.5) / (SIZE / 2.0) - 1.0, y = 1.0 - (py + 0.5) / (SIZE / 2.0);
    for (int k = 0; k < count; k++) {
        bool inside = true, near_or_inside = true;
        for (int e = 0; e < 3; e++) {
            const double *a = big->ndc[k][e], *b = big->ndc[k][(e + 1) % 3];
            /* The distance from the edge's line, positive inside. */
            const double distance = ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])) /
                                    hypot(b[0] - a[0], b[1] - a[1]);
            if (distance < 1e-3) inside = false;
            if (distance < -1e-3) near_or_inside = false;
        }
        if (near_or_inside && !inside) return -2;
        if (inside) return k;
    }
    return -1;
}

static luz_framebuffer *draw_big(const big_mesh *big, luz_texture *texture, int draw_size,
                                 uint32_t triangle_limit, int threads)
{
    luz_frame frame = camera_frame();
    luz_error error = {{0}};
    enum { MAX_DRAWS = BIG_TRIANGLES };
    static luz_mesh *meshes[MAX_DRAWS];
    int mesh_count = 0;
    for (int first = 0; first < BIG_TRIANGLES; first += draw_size) {
        int count = BIG_TRIANGLES - first < draw_size ? BIG_TRIANGLES - first : draw_size;
        luz_mesh *mesh = luz_mesh_create(
            &(luz_mesh_desc){.vertices = &big->vertices[3 * first],
                             .vertex_count = (uint32_t)(3 * count)},
            &error);
        assert_non_null(mesh);
        meshes[mesh_count++] = mesh;
        luz_draw draw = {.mesh = mesh, .model = luz_mat4_identity()};
        draw.material.colour = (luz_vec3){1.0f, 1.0f, 1.0f};
        draw.material.texture = texture;
        draw.material.filter = LUZ_FILTER_NEAREST;
        assert_int_equal(luz_frame_add_draw(&frame, &draw, &error), 0);
    }
    luz_frame_stats stats = {0};
    luz_render_options options = {.triangle_limit = triangle_limit, .stats = &stats};
    luz_framebuffer *framebuffer = render_frame(&frame, &options, threads);
    assert_int_equal(stats.triangles_submitted, BIG_TRIANGLES);
    luz_frame_free(&frame);
    for (int m = 0; m < mesh_count; m++) luz_mesh_destroy(meshes[m]);
    return framebuffer;
}

static void assert_winners(const big_mesh *big, const luz_framebuffer *framebuffer, int count)
{
    int checked = 0;
    for (int py = 0; py < SIZE; py++)
        for (int px = 0; px < SIZE; px++) {
            int winner = expected_winner(big, count, px, py);
            if (winner == -2) continue;
            const uint8_t *rgba = pixel(framebuffer, px, py);
            if (winner == -1) {
                assert_pixel(framebuffer, px, py, 0, 0, 0);
            } else {
                const uint8_t *texel = &big->texels[4 * (winner % TEXELS)];
                if (memcmp(rgba, texel, 3) != 0)
                    fail_msg("pixel %d,%d: %d %d %d, expected triangle %d's %d %d %d", px, py,
                             rgba[0], rgba[1], rgba[2], winner, texel[0], texel[1], texel[2]);
            }
            checked++;
        }
    assert_true(checked > SIZE * SIZE * 9 / 10);
}

/* One draw of 10,000 triangles (cut into batches over the threads) and the
 * same triangles as 40 draws of 250 (drawn whole, several to a batch): each
 * pixel is its first triangle's, for 1, 2 and 3 threads; and with
 * triangle_limit only the first 5,000 triangles take part. */
static void test_big_mesh_draws_its_triangles_in_order(void **state)
{
    (void)state;
    big_mesh *big = malloc(sizeof *big);
    assert_non_null(big);
    make_big_mesh(big);
    luz_error error = {{0}};
    luz_texture *texture = luz_texture_create(TEXELS, 1, big->texels, &error);
    assert_non_null(texture);

    const int draw_sizes[2] = {BIG_TRIANGLES, 250};
    for (int s = 0; s < 2; s++)
        for (int threads = 1; threads <= 3; threads++) {
            luz_framebuffer *framebuffer = draw_big(big, texture, draw_sizes[s], 0, threads);
            assert_winners(big, framebuffer, BIG_TRIANGLES);
            luz_framebuffer_destroy(framebuffer);
        }
    for (int threads = 1; threads <= 2; threads++) {
        luz_framebuffer *framebuffer = draw_big(big, texture, BIG_TRIANGLES, 5000, threads);
        assert_winners(big, framebuffer, 5000);
        luz_framebuffer_destroy(framebuffer);
    }
    luz_texture_destroy(texture);
    free(big);
}

/* ---- draws out of sight ---------------------------------------------------------------- */

/* 400 quads, each a draw of its own, scattered around the edges of the
 * view volume (the 90-degree camera's sides, behind it, across the near
 * plane at 0.1 and the far plane at 100, in the guard band): the
 * renderer drops a draw whose bounding box is wholly outside a clip plane
 * without looking at its triangles. Whatever it drops must draw nothing:
 * each quad alone, dropped or not, is drawn again with culling out of
 * reach (its box made huge by a far-off fifth vertex no triangle uses),
 * and the two images must be the same; a dropped quad's image is all
 * background. Some quads must be dropped, and the dropped ones' triangles
 * still count as submitted. */
static void test_draws_out_of_sight_are_dropped_and_only_those(void **state)
{
    (void)state;
    uint32_t random = 777;
    int dropped = 0, kept = 0;
    for (int q = 0; q < 400; q++) {
        float p[3], size;
        for (int k = 0; k < 3; k++) {
            random = random * 1664525u + 1013904223u;
            p[k] = (float)((random >> 8) / 16777216.0);
        }
        random = random * 1664525u + 1013904223u;
        size = 0.05f + 2.0f * (float)((random >> 8) / 16777216.0);
        /* Depth from 0.01 behind the camera to 150 in front: some across
         * the near or far plane; x and y within +-6 depths, beyond the
         * guard band's 4. */
        const float depth = q % 4 == 0 ? -0.3f + 0.6f * p[2] : 150.0f * p[2] * p[2];
        const float x = (p[0] * 12.0f - 6.0f) * fabsf(depth), y = (p[1] * 12.0f - 6.0f) * fabsf(depth);
        const luz_vec3 n = {0.0f, 0.0f, 1.0f};
        luz_vertex vertices[5] = {
            {{x, y, -depth}, n, {0, 0}},
            {{x + size, y, -depth}, n, {1, 0}},
            {{x + size, y + size, -depth - size}, n, {1, 1}},
            {{x, y + size, -depth - size}, n, {0, 1}},
            {{0.0f, 0.0f, -5.0f}, n, {0, 0}},   /* inside the view: the box with it is seen */
        };
        const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
        luz_framebuffer *images[2];
        luz_frame_stats stats[2];
        for (int variant = 0; variant < 2; variant++) {
            luz_error error = {{0}};
            luz_mesh *mesh = luz_mesh_create(
                &(luz_mesh_desc){.vertices = vertices, .vertex_count = variant ? 5 : 4,
                                 .indices = indices, .index_count = 6},
                &error);
            assert_non_null(mesh);
            luz_frame frame = camera_frame();
            luz_draw draw = {.mesh = mesh, .model = luz_mat4_identity()};
            draw.material.colour = (luz_vec3){1.0f, 1.0f, 1.0f};
            draw.material.shading = LUZ_SHADING_UNLIT;
            assert_int_equal(luz_frame_add_draw(&frame, &draw, &error), 0);
            luz_render_options options = {.stats = &stats[variant]};
            images[variant] = render_frame(&frame, &options, 1);
            assert_int_equal(stats[variant].triangles_submitted, 2);
            luz_frame_free(&frame);
            luz_mesh_destroy(mesh);
        }
        assert_int_equal(stats[1].draws_culled, 0);
        if (memcmp(images[0]->colour, images[1]->colour, (size_t)SIZE * SIZE * 4) != 0)
            fail_msg("quad %d (%g, %g, %g, size %g): %s, and drawn differently", q, x, y,
                     -depth, size, stats[0].draws_culled ? "dropped" : "kept");
        if (stats[0].draws_culled) {
            dropped++;
            for (int i = 0; i < SIZE * SIZE; i++) assert_int_equal(images[0]->visibility[i], 0);
        } else {
            kept++;
        }
        luz_framebuffer_destroy(images[0]);
        luz_framebuffer_destroy(images[1]);
    }
    print_message("%d quads dropped whole, %d kept\n", dropped, kept);
    assert_true(dropped > 100);
    assert_true(kept > 50);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_meshes_are_refused_with_a_reason),
        cmocka_unit_test(test_zero_desc_is_an_empty_mesh),
        cmocka_unit_test(test_mesh_copies_its_arrays_and_knows_its_bounds),
        cmocka_unit_test(test_index_kinds_draw_the_same_image),
        cmocka_unit_test(test_more_than_65536_vertices),
        cmocka_unit_test(test_each_draw_has_its_own_material),
        cmocka_unit_test(test_zero_desc_is_one_thread_per_cpu),
        cmocka_unit_test(test_textures_and_framebuffers_say_why),
        cmocka_unit_test(test_bad_frames_are_refused_with_a_reason),
        cmocka_unit_test(test_zero_material_is_lit_and_white),
        cmocka_unit_test(test_zero_spot_reach_is_scene_default),
        cmocka_unit_test(test_forbidden_lights_are_refused),
        cmocka_unit_test(test_frame_owns_only_its_own_draws),
        cmocka_unit_test(test_big_mesh_draws_its_triangles_in_order),
        cmocka_unit_test(test_draws_out_of_sight_are_dropped_and_only_those),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
