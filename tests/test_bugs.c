/*
 * test_bugs.c: luz/bug.h's classic mistakes, each against what it must
 * do, worked out by hand from SCENE.md's equations with the mistake put
 * in; and the probe's intermediates (luz_shade_steps) against the same
 * equations.
 *
 * The scene: one white untextured cube at the origin, unturned (t = 0),
 * the camera at (0, 0, 3) looking down -Z, so that its +Z face (z = 0.5,
 * N = (0, 0, 1)) fills the middle of a 64 x 48 image; each test lights it
 * with the one light its bug touches. The expected numbers are computed
 * here in double precision from P, the probed world position (itself
 * checked against the camera ray by test_probe), with SCENE.md's
 * formulas, not by luz's float code.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "renderer/pipeline.h"
#include "luz/bug.h"
#include "luz/probe.h"
#include "luz/renderer.h"
#include "luz/shade.h"
#include "lab/scene.h"
#include "lab_support.h"
#include "test_support.h"

#define WIDTH 64
#define HEIGHT 48

static const luz_light off = {{1.0f, 1.0f, 1.0f}, 0.0f};

/* The scene above with every light off. */
static luz_scene white_cube_scene(luz_object *object)
{
    luz_scene scene = luz_scene_defaults();
    *object = (luz_object){.position = {0, 0, 0}, .has_colour = true, .colour = {1, 1, 1},
                           .texture = LUZ_TEXTURE_BY_INDEX, .scale = 1.0f};
    scene.objects = object;
    scene.object_count = 1;
    scene.time_seconds = 0.0;
    luz_lights *l = &scene.lights;
    l->ambient = l->diffuse = l->specular = l->point = l->spot = l->directional = off;
    return scene;
}

/* Draws the scene with the bug and probes pixel (x, y); returns its bytes. */
static void draw_probe_textured(const luz_scene *scene, luz_bug bug, int x, int y,
                                bool reference, bool textured, luz_pixel_probe *probe)
{
    luz_frame frame = {0};
    luz_error error = {{0}};
    assert_int_equal(luz_scene_build_frame(test_lab(), scene,
                                           textured ? lab_textures()->textures : NULL,
                                           textured ? lab_textures()->count : 0,
                                           (float)WIDTH / HEIGHT, &frame, &error),
                     0);
    luz_renderer *renderer = luz_renderer_create(
        &(luz_renderer_desc){.thread_count = 2, .reference = reference}, &error);
    assert_non_null(renderer);
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(framebuffer);
    *probe = (luz_pixel_probe){.x = x, .y = y};
    luz_render_options options = luz_scene_render_options(scene);
    options.bug = bug;
    options.probe = probe;
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &options, &error), 0);
    assert_true(probe->filled);
    assert_int_equal(probe->bug, bug);
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
    luz_frame_free(&frame);
}

static void draw_probe(const luz_scene *scene, luz_bug bug, int x, int y, bool reference,
                       luz_pixel_probe *probe)
{
    draw_probe_textured(scene, bug, x, y, reference, false, probe);
}

typedef struct dvec3 {
    double x, y, z;
} dvec3;

static dvec3 d3(luz_vec3 v)
{
    return (dvec3){v.x, v.y, v.z};
}

static double ddot(dvec3 a, dvec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static dvec3 dnormalize(dvec3 a)
{
    const double n = sqrt(ddot(a, a));
    return (dvec3){a.x / n, a.y / n, a.z / n};
}

static double dlength(dvec3 a)
{
    return sqrt(ddot(a, a));
}

static uint8_t byte_of(double c)
{
    return c <= 0.0 ? 0 : c >= 1.0 ? 255 : (uint8_t)floor(c * 255.0 + 0.5);
}

/* The probed pixel is the +Z face's, lit, with N = (0, 0, 1) and P on
 * the face. */
static void assert_on_front_face(const luz_pixel_probe *probe)
{
    assert_int_not_equal(probe->triangle, 0);
    assert_int_equal(probe->shading, LUZ_SHADING_LIT);
    assert_near(probe->position.z, 0.5, 1e-6);
    assert_near(probe->normal.z, 1.0, 1e-6);
}

/* ---- the report's three errata ---------------------------------------------- */

/* diffuse = max(dot(N, normalize(P - E)), 0): a face that looks at the
 * headlight gets dot = -N.L_right, about -1, so no diffuse light at all,
 * where the contract gives about 1. */
static void diffuse_reversed(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    scene.lights.diffuse = (luz_light){{1, 1, 1}, 1.0f};
    luz_pixel_probe right, wrong;
    draw_probe(&scene, LUZ_BUG_NONE, WIDTH / 2, HEIGHT / 2, false, &right);
    draw_probe(&scene, LUZ_BUG_DIFFUSE_REVERSED, WIDTH / 2, HEIGHT / 2, false, &wrong);
    assert_on_front_face(&wrong);

    const dvec3 P = d3(wrong.position), E = {0, 0, 3}, N = {0, 0, 1};
    const dvec3 towards = dnormalize((dvec3){E.x - P.x, E.y - P.y, E.z - P.z});
    const double n_dot_l = ddot(N, towards);   /* about 0.99 */
    assert_true(n_dot_l > 0.99);
    /* the contract: max(N.L, 0) */
    assert_near(right.terms[LUZ_TERM_DIFFUSE].x, n_dot_l, 1e-6);
    assert_int_equal(right.bytes[0], byte_of(n_dot_l));
    /* the bug: L = -towards, max(-N.L, 0) = 0 */
    assert_near(wrong.steps.to_light.x, -towards.x, 1e-6);
    assert_near(wrong.steps.to_light.z, -towards.z, 1e-6);
    assert_near(wrong.steps.n_dot_l, -n_dot_l, 1e-6);
    assert_true(wrong.terms[LUZ_TERM_DIFFUSE].x == 0.0f);
    assert_int_equal(wrong.bytes[0], 0);
    assert_int_equal(wrong.bytes[1], 0);
}

/* directional = dot(N, normalize(-d)) Dl.a with no clamp. At t = 0 the
 * sun travels along d = (cos 0, sin 0, 0) = +X, so the cube's +X face,
 * seen from (3, 0, 0), has dot(N, -d) = -1: the ambient 0.5 loses 0.3,
 * 0.2 and byte 51, where the contract keeps 0.5, byte 128. */
static void directional_unclamped(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    scene.lights.ambient = (luz_light){{1, 1, 1}, 0.5f};
    scene.lights.directional = (luz_light){{1, 1, 1}, 0.3f};
    scene.camera.position = (luz_vec3){3, 0, 0};
    scene.camera.yaw_degrees = 180.0f;   /* front (-1, 0, 0) */
    luz_pixel_probe right, wrong;
    draw_probe(&scene, LUZ_BUG_NONE, WIDTH / 2, HEIGHT / 2, false, &right);
    draw_probe(&scene, LUZ_BUG_DIRECTIONAL_UNCLAMPED, WIDTH / 2, HEIGHT / 2, false, &wrong);
    assert_int_not_equal(wrong.triangle, 0);
    assert_near(wrong.normal.x, 1.0, 1e-6);
    assert_near(wrong.steps.to_sun.x, -1.0, 1e-6);
    assert_near(wrong.steps.n_dot_sun, -1.0, 1e-6);
    assert_true(right.terms[LUZ_TERM_DIRECTIONAL].x == 0.0f);
    assert_int_equal(right.bytes[0], 128);
    assert_near(wrong.terms[LUZ_TERM_DIRECTIONAL].x, -0.3, 1e-6);
    assert_near(wrong.colour.x, 0.2, 1e-6);
    assert_int_equal(wrong.bytes[0], 51);
}

/* f_win = max(1 - (dn / reach)^4, 0)^2 with dn = |E - P| / reach: with
 * reach 3 and |E - P| about 2.5 the contract's window is about 0.27, the
 * report's about 0.99. */
static void spot_reach_twice(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    scene.lights.spot = (luz_light){{1, 1, 1}, 1.0f};
    scene.lights.spot_reach = 3.0f;
    luz_pixel_probe right, wrong;
    draw_probe(&scene, LUZ_BUG_NONE, WIDTH / 2, HEIGHT / 2, false, &right);
    draw_probe(&scene, LUZ_BUG_SPOT_REACH_TWICE, WIDTH / 2, HEIGHT / 2, false, &wrong);
    assert_on_front_face(&wrong);

    const dvec3 P = d3(wrong.position), E = {0, 0, 3};
    const double dn = dlength((dvec3){E.x - P.x, E.y - P.y, E.z - P.z}) / 3.0;
    /* the pixel is within the inner cone: f_dir = 1 */
    assert_true(right.steps.f_dir == 1.0f && wrong.steps.f_dir == 1.0f);
    const double win_right = pow(fmax(1.0 - pow(dn, 4.0), 0.0), 2.0);
    const double win_wrong = pow(fmax(1.0 - pow(dn / 3.0, 4.0), 0.0), 2.0);
    const double dist_right = win_right / (dn * dn + 1.0);
    const double dist_wrong = win_wrong / (dn * dn + 1.0);
    assert_near(right.steps.dn, dn, 1e-6);
    assert_near(wrong.steps.dn, dn, 1e-6);
    assert_near(right.steps.f_win, win_right, 1e-5);
    assert_near(wrong.steps.f_win, win_wrong, 1e-5);
    assert_near(right.terms[LUZ_TERM_SPOT].x, dist_right, 1e-5);
    assert_near(wrong.terms[LUZ_TERM_SPOT].x, dist_wrong, 1e-5);
    assert_true(win_wrong > 0.98 && win_right < 0.3);
    assert_int_equal(right.bytes[0], byte_of(dist_right));
    assert_int_equal(wrong.bytes[0], byte_of(dist_wrong));
}

/* ---- the other shading and vertex bugs ---------------------------------------- */

/* specular = pow(max(N.H, 0), 32) with H = normalize(L + V) = L (the
 * headlight): N.L ~ 0.99 where V.R = 2 (N.L)^2 - 1 ~ 0.98, so the bug's
 * highlight is pow(N.L, 32), brighter. */
static void specular_half_vector(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    scene.lights.specular = (luz_light){{1, 1, 1}, 1.0f};
    scene.lights.shininess = 32.0f;
    const int x = WIDTH / 2 + 9, y = HEIGHT / 2 + 5;   /* off the axis: N.L < 1 */
    luz_pixel_probe right, wrong;
    draw_probe(&scene, LUZ_BUG_NONE, x, y, false, &right);
    draw_probe(&scene, LUZ_BUG_SPECULAR_HALF_VECTOR, x, y, false, &wrong);
    assert_on_front_face(&wrong);
    const dvec3 P = d3(wrong.position), E = {0, 0, 3}, N = {0, 0, 1};
    const double nl = ddot(N, dnormalize((dvec3){E.x - P.x, E.y - P.y, E.z - P.z}));
    assert_true(nl < 0.995);
    assert_near(right.steps.v_dot_r, 2 * nl * nl - 1, 1e-6);
    assert_near(wrong.steps.v_dot_r, nl, 1e-6);
    assert_near(right.terms[LUZ_TERM_SPECULAR].x, pow(2 * nl * nl - 1, 32), 1e-5);
    assert_near(wrong.terms[LUZ_TERM_SPECULAR].x, pow(nl, 32), 1e-5);
    assert_int_equal(wrong.bytes[0], byte_of(pow(nl, 32)));
    assert_int_equal(right.bytes[0], byte_of(pow(2 * nl * nl - 1, 32)));
}

/* normal-matrix-is-model: a cube at (1, 0, 0), unturned, seen from
 * (1, 0, 3): its +Z face's normal (0, 0, 1) becomes (M (N, 1)).xyz =
 * (0, 0, 1) + (1, 0, 0) = (1, 0, 1), re-normalised (0.7071, 0, 0.7071);
 * the diffuse term follows it. */
static void normal_matrix_is_model(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    object.position = (luz_vec3){1, 0, 0};
    scene.camera.position = (luz_vec3){1, 0, 3};
    scene.lights.diffuse = (luz_light){{1, 1, 1}, 1.0f};
    luz_pixel_probe right, wrong;
    draw_probe(&scene, LUZ_BUG_NONE, WIDTH / 2, HEIGHT / 2, false, &right);
    draw_probe(&scene, LUZ_BUG_NORMAL_MATRIX_IS_MODEL, WIDTH / 2, HEIGHT / 2, false, &wrong);
    assert_near(right.normal.x, 0.0, 1e-6);
    assert_near(right.normal.z, 1.0, 1e-6);
    const double h = sqrt(0.5);
    assert_near(wrong.normal.x, h, 1e-6);
    assert_near(wrong.normal.y, 0.0, 1e-6);
    assert_near(wrong.normal.z, h, 1e-6);
    const dvec3 P = d3(wrong.position), E = {1, 0, 3};
    const dvec3 L = dnormalize((dvec3){E.x - P.x, E.y - P.y, E.z - P.z});
    const double expected = fmax(ddot((dvec3){h, 0, h}, L), 0.0);
    assert_near(wrong.terms[LUZ_TERM_DIFFUSE].x, expected, 1e-5);
    assert_int_equal(wrong.bytes[0], byte_of(expected));
}

/* normal-not-normalised: the cube scaled by 1/2 has the normal matrix
 * (its inverse transpose) 2 I, so N = (0, 0, 2) as interpolated; the
 * terms read it as it is: |N| = 2 and the diffuse term twice the right
 * one (0.4 N.L against 0.2 N.L at D.a 0.2). */
static void normal_not_normalised(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    scene.lights.diffuse = (luz_light){{1, 1, 1}, 0.2f};
    luz_frame frame = {0};
    luz_error error = {{0}};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, NULL, 0, (float)WIDTH / HEIGHT,
                                           &frame, &error),
                     0);
    frame.draws[0].model = luz_mat4_scale(frame.draws[0].model, (luz_vec3){0.5f, 0.5f, 0.5f});
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    luz_pixel_probe probe[2];
    for (int bug = 0; bug < 2; bug++) {
        probe[bug] = (luz_pixel_probe){.x = WIDTH / 2, .y = HEIGHT / 2};
        const luz_render_options options = {
            .probe = &probe[bug], .bug = bug ? LUZ_BUG_NORMAL_NOT_NORMALISED : LUZ_BUG_NONE};
        assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &options, &error), 0);
    }
    assert_near(probe[0].position.z, 0.25, 1e-6);
    const dvec3 P = d3(probe[1].position), E = {0, 0, 3};
    const double nl = dnormalize((dvec3){E.x - P.x, E.y - P.y, E.z - P.z}).z;
    assert_near(probe[0].steps.normal_length, 1.0, 1e-6);
    assert_near(probe[1].steps.normal_length, 2.0, 1e-6);
    assert_near(probe[0].terms[LUZ_TERM_DIFFUSE].x, 0.2 * nl, 1e-6);
    assert_near(probe[1].terms[LUZ_TERM_DIFFUSE].x, 0.4 * nl, 1e-6);
    assert_int_equal(probe[1].bytes[0], byte_of(0.4 * nl));
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
    luz_frame_free(&frame);
}

/* ---- the pipeline's bugs ---------------------------------------------------------- */

/* uv-affine: seen at 45 degrees from (2, 0, 2), the cube's faces are not
 * parallel to the screen; with the bug the probe's barycentric
 * coordinates are the 2D ones of the pixel centre in the window corners
 * (linear on the screen) and w = 1, where perspective-correct ones differ
 * from them. */
static void uv_affine(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    scene.lights.ambient = (luz_light){{1, 1, 1}, 1.0f};
    scene.camera.position = (luz_vec3){2, 0.3f, 2};
    scene.camera.yaw_degrees = -135.0f;
    const int x = WIDTH / 2 - 6, y = HEIGHT / 2 + 3;
    for (int bug = 0; bug < 2; bug++) {
        luz_pixel_probe probe;
        draw_probe(&scene, bug ? LUZ_BUG_UV_AFFINE : LUZ_BUG_NONE, x, y, false, &probe);
        assert_int_not_equal(probe.triangle, 0);
        assert_int_equal(probe.clipped_pieces, 0);
        const luz_vec3 *c = probe.corner_window;
        const double px = x + 0.5, py = y + 0.5;
        const double area = (c[1].x - c[0].x) * (c[2].y - c[0].y) -
                            (c[2].x - c[0].x) * (c[1].y - c[0].y);
        const double b1 = ((px - c[0].x) * (c[2].y - c[0].y) - (c[2].x - c[0].x) * (py - c[0].y)) /
                          area;
        const double b2 = ((c[1].x - c[0].x) * (py - c[0].y) - (px - c[0].x) * (c[1].y - c[0].y)) /
                          area;
        const double gap = fabs(probe.barycentric.y - b1) + fabs(probe.barycentric.z - b2);
        if (bug) {
            assert_true(gap < 1e-4);
            assert_true(probe.w == 1.0f);
        } else {
            assert_true(gap > 1e-3);
            assert_true(probe.w > 1.5f);
        }
    }
}

/* lod-off-by-one: the same pixel's level of detail one more than the
 * contract's, and the levels read floor of it and the next. */
static void lod_off_by_one(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    object.texture = 0;
    scene.lights.ambient = (luz_light){{1, 1, 1}, 1.0f};
    scene.camera.position = (luz_vec3){0, 0, 12};   /* far: minified, lambda > 0 */
    luz_pixel_probe right, wrong;
    draw_probe_textured(&scene, LUZ_BUG_NONE, WIDTH / 2, HEIGHT / 2, true, true, &right);
    draw_probe_textured(&scene, LUZ_BUG_LOD_OFF_BY_ONE, WIDTH / 2, HEIGHT / 2, true, true,
                        &wrong);
    assert_non_null(right.texture);
    assert_true(right.lambda > 0.0f);
    assert_near(right.lambda, log2(right.rho), 1e-5);
    assert_true(wrong.lambda == right.lambda + 1.0f);
    assert_int_equal(wrong.levels.lower, (int)floor(right.lambda) + 1);
}

/* A square of two triangles in NDC (identity view and projection) whose
 * shared edge is the vertical line x_ndc = 1/64, through the centres of
 * column 32 of a 64-wide image: left triangle first, then the right one. */
static void draw_split_square(luz_bug bug, int y, luz_pixel_probe *probe)
{
    const float e = 1.0f / 64.0f;
    const luz_vertex vertices[6] = {
        {{-0.5f, -0.5f, 0}, {0, 0, 1}, {0, 0}}, {{e, -0.5f, 0}, {0, 0, 1}, {0, 0}},
        {{e, 0.5f, 0}, {0, 0, 1}, {0, 0}},      {{-0.5f, -0.5f, 0}, {0, 0, 1}, {0, 0}},
        {{e, 0.5f, 0}, {0, 0, 1}, {0, 0}},      {{-0.5f, 0.5f, 0}, {0, 0, 1}, {0, 0}},
    };
    const luz_vertex right_vertices[3] = {
        {{e, -0.5f, 0}, {0, 0, 1}, {0, 0}}, {{0.5f, -0.5f, 0}, {0, 0, 1}, {0, 0}},
        {{e, 0.5f, 0}, {0, 0, 1}, {0, 0}}};
    luz_error error = {{0}};
    /* the left part: a rectangle, two triangles; its right edge is x = e */
    luz_mesh *left = luz_mesh_create(&(luz_mesh_desc){vertices, 6, NULL, NULL, 0}, &error);
    luz_mesh *right = luz_mesh_create(&(luz_mesh_desc){right_vertices, 3, NULL, NULL, 0}, &error);
    assert_non_null(left);
    assert_non_null(right);
    luz_frame frame = {.view = luz_mat4_identity(), .projection = luz_mat4_identity(),
                       .eye = {0, 0, 3}};
    frame.lights.ambient = (luz_light){{1, 1, 1}, 1.0f};
    luz_draw draw = {.mesh = left, .model = luz_mat4_identity(),
                     .material = {.colour = {1, 0, 0}, .has_colour = true}};
    assert_int_equal(luz_frame_add_draw(&frame, &draw, &error), 0);
    draw.mesh = right;
    draw.material.colour = (luz_vec3){0, 0, 1};
    assert_int_equal(luz_frame_add_draw(&frame, &draw, &error), 0);
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    *probe = (luz_pixel_probe){.x = WIDTH / 2, .y = y};
    const luz_render_options options = {.probe = probe, .bug = bug};
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &options, &error), 0);
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
    luz_frame_free(&frame);
    luz_mesh_destroy(left);
    luz_mesh_destroy(right);
}

/* Pixel (32, 24)'s centre, x = 32.5 = (1/64 + 1) / 2 x 64, lies on the
 * shared vertical edge: a left edge of the right (blue) triangle and a
 * right edge of the left (red) one. Top-left: blue's; bottom-right: red's. */
static void fill_rule_bottom_right(void **state)
{
    (void)state;
    luz_pixel_probe right, wrong;
    draw_split_square(LUZ_BUG_NONE, HEIGHT / 2 + 3, &right);
    draw_split_square(LUZ_BUG_FILL_RULE_BOTTOM_RIGHT, HEIGHT / 2 + 3, &wrong);
    assert_int_equal(right.test_count, 1);
    assert_int_equal(wrong.test_count, 1);
    assert_int_equal(right.draw, 1);
    assert_int_equal(wrong.draw, 0);
    assert_int_equal(right.bytes[2], 255);
    assert_int_equal(wrong.bytes[0], 255);
}

/* no-depth-test: a cube at the origin, then one behind it at z = -3 (drawn
 * second): the centre pixel, covered by both, shows the far one, every
 * test passes and the depth buffer keeps its 1. */
static void no_depth_test(void **state)
{
    (void)state;
    luz_object objects[2];
    luz_scene scene = white_cube_scene(&objects[0]);
    objects[1] = objects[0];
    objects[1].position = (luz_vec3){0, 0, -3};
    scene.objects = objects;
    scene.object_count = 2;
    scene.lights.ambient = (luz_light){{1, 1, 1}, 1.0f};
    luz_pixel_probe right, wrong;
    draw_probe(&scene, LUZ_BUG_NONE, WIDTH / 2, HEIGHT / 2, false, &right);
    draw_probe(&scene, LUZ_BUG_NO_DEPTH_TEST, WIDTH / 2, HEIGHT / 2, false, &wrong);
    assert_int_equal(right.draw, 0);
    assert_int_equal(wrong.draw, 1);
    assert_int_equal(wrong.test_count, 2);
    for (int k = 0; k < wrong.tests_kept; k++) assert_true(wrong.tests[k].passed);
    assert_true(wrong.depth_buffer == 1.0f);
    assert_near(wrong.position.z, -2.5, 1e-5);
}

/* no-backface-culling: the centre pixel of one cube is covered by its
 * front face (+Z) and its back face (-Z): two depth tests, the front
 * face nearer and the winner; one test with culling. */
static void no_backface_culling(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    scene.lights.ambient = (luz_light){{1, 1, 1}, 1.0f};
    luz_pixel_probe right, wrong;
    draw_probe(&scene, LUZ_BUG_NONE, WIDTH / 2, HEIGHT / 2, false, &right);
    draw_probe(&scene, LUZ_BUG_NO_BACKFACE_CULLING, WIDTH / 2, HEIGHT / 2, false, &wrong);
    assert_int_equal(right.test_count, 1);
    assert_int_equal(wrong.test_count, 2);
    assert_near(wrong.position.z, 0.5, 1e-6);
    /* the -Z face at z = -0.5 is the farther: window depth larger */
    const luz_probe_test *a = &wrong.tests[0], *b = &wrong.tests[1];
    assert_true((a->passed && b->depth > a->depth) || (b->passed && a->depth > b->depth));
    assert_memory_equal(wrong.bytes, right.bytes, 3);
}

/* ---- the probe's intermediates: matrices, edges, taps ------------------------- */

/* The default camera's matrices worked by hand (SCENE.md: lookAt from
 * (0, 0, 3) down -Z is a translation by -3; perspective 45 degrees,
 * aspect 64/48, near 0.1, far 100); each edge function at the pixel
 * centre from the window corners; the bilinear taps' texels and weights
 * from uv and the texture's size, adding up to T. */
static void probe_intermediates(void **state)
{
    (void)state;
    luz_object object;
    luz_scene scene = white_cube_scene(&object);
    object.texture = 0;
    scene.filter = LUZ_FILTER_BILINEAR;
    scene.lights.ambient = (luz_light){{1, 1, 1}, 1.0f};
    const int x = WIDTH / 2 + 7, y = HEIGHT / 2 - 5;
    luz_pixel_probe probe;
    draw_probe_textured(&scene, LUZ_BUG_NONE, x, y, true, true, &probe);
    assert_on_front_face(&probe);

    const double f = 1.0 / tan(22.5 * 3.14159265358979323846 / 180.0), aspect = (double)WIDTH / HEIGHT;
    const double expected_projection[16] = {f / aspect, 0, 0, 0, 0, f, 0, 0,
                                            0, 0, -100.1 / 99.9, -1, 0, 0, -20.0 / 99.9, 0};
    const double expected_view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1};
    for (int i = 0; i < 16; i++) {
        assert_near(probe.projection_matrix.m[i], expected_projection[i], 1e-6);
        assert_near(probe.view_matrix.m[i], expected_view[i], 1e-6);
        assert_near(probe.model_matrix.m[i], i % 5 == 0 ? 1.0 : 0.0, 1e-7);   /* t = 0 */
    }

    /* edge k from corner k + 1 to corner k + 2, in 1/256 pixel */
    const double X = 256.0 * x + 128, Y = 256.0 * y + 128;
    for (int k = 0; k < 3; k++) {
        const luz_vec3 i = probe.corner_window[(k + 1) % 3], j = probe.corner_window[(k + 2) % 3];
        const double xi = 256.0 * i.x, yi = 256.0 * i.y, xj = 256.0 * j.x, yj = 256.0 * j.y;
        const double e = (yj - yi) * (X - xi) - (xj - xi) * (Y - yi);
        assert_true((double)probe.edges[k].value == e);
        assert_int_equal(probe.edges[k].top, yj == yi && xj < xi);
        assert_int_equal(probe.edges[k].left, yj > yi);
        assert_int_equal(probe.edges[k].owns_its_samples,
                         probe.edges[k].top || probe.edges[k].left);
        assert_true(probe.edges[k].value >= 0);   /* the centre is inside */
    }

    /* bilinear: the texel centres around (u w - 1/2, v h - 1/2), wrapped */
    const luz_texture *texture = probe.texture;
    assert_non_null(texture);
    assert_int_equal(probe.tap_count, 4);
    const int w = texture->levels[0].width, h = texture->levels[0].height;
    const double su = (probe.uv.x - floor(probe.uv.x)) * w - 0.5;
    const double sv = (probe.uv.y - floor(probe.uv.y)) * h - 0.5;
    const double fx = su - floor(su), fy = sv - floor(sv);
    const int x0 = ((int)floor(su) + w) % w, y0 = ((int)floor(sv) + h) % h;
    double sum = 0, red = 0;
    for (int k = 0; k < 4; k++) {
        const luz_probe_tap *tap = &probe.taps[k];
        const int dx = tap->x == x0 ? 0 : 1, dy = tap->y == y0 ? 0 : 1;
        assert_int_equal(tap->x, (x0 + dx) % w);
        assert_int_equal(tap->y, (y0 + dy) % h);
        assert_int_equal(tap->level, 0);
        assert_near(tap->weight, (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy), 1e-5);
        const uint8_t *texel = texture->levels[0].texels + ((size_t)tap->y * w + tap->x) * 4;
        assert_near(tap->texel.x, texel[0] / 255.0, 1e-7);
        sum += tap->weight;
        red += tap->weight * tap->texel.x;
    }
    assert_near(sum, 1.0, 1e-6);
    assert_near(red, probe.texel.x, 1e-6);
}

/* ---- without a bug, the steps are the shader's own numbers ------------------ */

/* luz_shade_terms_explained with no bug gives luz_shade_terms' terms to the
 * bit, on random fragments and lights, and its steps are SCENE.md's
 * intermediates worked in double. */
static void steps_are_the_shader(void **state)
{
    (void)state;
    uint32_t random = 12345;
    for (int i = 0; i < 2000; i++) {
        luz_lights lights = {0};
        luz_light *each[6] = {&lights.ambient, &lights.diffuse, &lights.specular,
                              &lights.point,   &lights.spot,    &lights.directional};
        for (int k = 0; k < 6; k++)
            *each[k] = (luz_light){{test_uniform(&random, 0, 1), test_uniform(&random, 0, 1),
                                    test_uniform(&random, 0, 1)},
                                   test_uniform(&random, 0, 1)};
        lights.shininess = (float)(int)test_uniform(&random, 1, 64);
        lights.spot_inner_degrees = test_uniform(&random, 0, 30);
        lights.spot_outer_degrees = lights.spot_inner_degrees + test_uniform(&random, 0, 30);
        lights.spot_reach = test_uniform(&random, 1, 20);
        lights.point_position =
            (luz_vec3){test_uniform(&random, -3, 3), 0.5f, test_uniform(&random, -3, 3)};
        lights.spot_direction = (luz_vec3){test_uniform(&random, -1, 1),
                                           test_uniform(&random, -1, 1), -1.0f};
        lights.directional_direction =
            (luz_vec3){test_uniform(&random, -1, 1), test_uniform(&random, -1, 1), 0.3f};
        const luz_vec3 eye = {test_uniform(&random, -2, 2), test_uniform(&random, -2, 2), 3.0f};
        const luz_shade_uniforms uniforms = luz_shade_uniforms_of(eye, &lights);
        const luz_vec3 P = {test_uniform(&random, -1, 1), test_uniform(&random, -1, 1),
                            test_uniform(&random, -1, 1)};
        const luz_vec3 N = {test_uniform(&random, -1, 1), test_uniform(&random, -1, 1),
                            test_uniform(&random, 0.2f, 1)};
        luz_vec3 plain[LUZ_TERM_COUNT], explained[LUZ_TERM_COUNT];
        luz_shade_steps steps;
        const luz_vec3 a = luz_shade_terms(&uniforms, P, N, plain);
        const luz_vec3 b = luz_shade_terms_explained(&uniforms, LUZ_BUG_NONE, P, N, explained,
                                                     &steps);
        assert_memory_equal(&a, &b, sizeof a);
        assert_memory_equal(plain, explained, sizeof plain);

        /* the steps, in double */
        const dvec3 n = dnormalize(d3(N)), p = d3(P), e = d3(eye);
        const dvec3 l = dnormalize((dvec3){e.x - p.x, e.y - p.y, e.z - p.z});
        const double nl = ddot(n, l);
        const dvec3 r = {2 * nl * n.x - l.x, 2 * nl * n.y - l.y, 2 * nl * n.z - l.z};
        assert_near(steps.n_dot_l, nl, 1e-5);
        assert_near(steps.reflected.x, r.x, 1e-5);
        assert_near(steps.reflected.z, r.z, 1e-5);
        assert_near(steps.v_dot_r, ddot(l, r), 1e-5);
        const dvec3 lp = dnormalize((dvec3){lights.point_position.x - p.x,
                                            lights.point_position.y - p.y,
                                            lights.point_position.z - p.z});
        assert_near(steps.n_dot_lp, ddot(n, lp), 1e-5);
        const dvec3 ray = dnormalize((dvec3){p.x - e.x, p.y - e.y, p.z - e.z});
        const double c = ddot(ray, dnormalize(d3(lights.spot_direction)));
        assert_near(steps.spot_cos, c, 1e-5);
        const double dn = dlength((dvec3){e.x - p.x, e.y - p.y, e.z - p.z}) / lights.spot_reach;
        assert_near(steps.dn, dn, 1e-5);
        const double win = pow(fmax(1 - pow(dn, 4), 0), 2);
        assert_near(steps.f_win, win, 1e-5);
        assert_near(steps.f_dist, win * lights.spot.strength * lights.spot.strength /
                                      (dn * dn + 1), 1e-5);
        const dvec3 sun = dnormalize((dvec3){-lights.directional_direction.x,
                                             -lights.directional_direction.y,
                                             -lights.directional_direction.z});
        assert_near(steps.to_sun.y, sun.y, 1e-6);
        assert_near(steps.n_dot_sun, ddot(n, sun), 1e-5);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(diffuse_reversed),
        cmocka_unit_test(directional_unclamped),
        cmocka_unit_test(spot_reach_twice),
        cmocka_unit_test(specular_half_vector),
        cmocka_unit_test(normal_matrix_is_model),
        cmocka_unit_test(normal_not_normalised),
        cmocka_unit_test(uv_affine),
        cmocka_unit_test(lod_off_by_one),
        cmocka_unit_test(fill_rule_bottom_right),
        cmocka_unit_test(no_depth_test),
        cmocka_unit_test(no_backface_culling),
        cmocka_unit_test(steps_are_the_shader),
        cmocka_unit_test(probe_intermediates),
    };
    return cmocka_run_group_tests(tests, lab_textures_load, lab_textures_free);
}
