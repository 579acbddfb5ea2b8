/*
 * test_probe.c: the pixel probe (luz/probe.h) against the image it
 * explains and against SCENE.md's equations.
 *
 * Each case draws a small frame once for its image and once in the
 * overdraw view, then once more for every one of its pixels with that
 * pixel probed, and holds the probe to:
 *
 *   the image      the probe's bytes are the image's pixel, the image is
 *                  the same with a probe as without, and
 *                  round(clamp(colour) x 255) is that pixel: the probe's
 *                  arithmetic made the image's byte (a view: its `shown`);
 *   its own sums   the six terms, added in order, are `light` to the bit,
 *                  and light x C x T is `colour` to the bit;
 *   the history    as many tests as the overdraw view counts at the pixel;
 *                  each test passes exactly when its depth is LESS than
 *                  the depth stored before it, and stores it; the last
 *                  test that passed is the winner, the depth buffer's
 *                  value is its depth (several tests can pass: a nearer
 *                  triangle drawn later passes after a farther one did);
 *   geometry       worked out here in double precision from the mesh, the
 *                  model matrix and the camera: the barycentric coordinates
 *                  of the pixel centre (solved in clip space, so
 *                  perspective-correct), P, uv, N, w and the window depth
 *                  from them, and uv's screen derivatives by central
 *                  differences;
 *   SCENE.md       each light term from its equation, in double, at the
 *                  probe's P and N; the texel from a sampler written here
 *                  (REPEAT, texel centres at (i + 0.5) / w, bilinear
 *                  weights, the two levels blended), rho from the
 *                  derivatives, lambda = log2(rho) where rho > 1;
 *   the path       lambda is exactly the level of detail of the fragment
 *                  path that shaded the image (the SIMD one's, or with
 *                  --reference and for the views fragment.c's).
 *
 * The cases: each light term alone, each filter (trilinear minified),
 * affine interpolation, a face the near plane clips, a model of two
 * meshes among cubes, the point light's unlit marker, every view, two
 * threads and the reference fragment stage. Each case also checks that
 * it shows what it is there for (a clipped piece, a mip blend, the
 * marker, a pixel where two tests pass, ...), so that none passes by
 * drawing nothing.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "luz/luz.h"
#include "app/probe_report.h"
#include "io/textures.h"
#include "lab/scene.h"
#include "lab_support.h"
#include "renderer/pipeline.h"
#include "test_support.h"

#define WIDTH 48
#define HEIGHT 27

/* ---- double precision, worked out here ------------------------------------------- */

typedef struct dvec3 {
    double x, y, z;
} dvec3;

static dvec3 d3(luz_vec3 v)
{
    return (dvec3){v.x, v.y, v.z};
}
static dvec3 add(dvec3 a, dvec3 b)
{
    return (dvec3){a.x + b.x, a.y + b.y, a.z + b.z};
}
static dvec3 sub(dvec3 a, dvec3 b)
{
    return (dvec3){a.x - b.x, a.y - b.y, a.z - b.z};
}
static dvec3 scale(dvec3 a, double s)
{
    return (dvec3){a.x * s, a.y * s, a.z * s};
}
static double dot(dvec3 a, dvec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static double length(dvec3 a)
{
    return sqrt(dot(a, a));
}
static dvec3 normalize(dvec3 a)
{
    double l = length(a);
    return l > 0 ? scale(a, 1.0 / l) : a;
}

/* m * (x, y, z, w), m column-major. */
static void transform(const luz_mat4 *m, const double in[4], double out[4])
{
    for (int r = 0; r < 4; r++) {
        out[r] = 0;
        for (int c = 0; c < 4; c++) out[r] += (double)m->m[c * 4 + r] * in[c];
    }
}

/* The inverse transpose of m's 3x3, applied to n (the normal matrix). */
static dvec3 normal_transform(const luz_mat4 *m, luz_vec3 n)
{
    double a[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = m->m[c * 4 + r];
    /* cofactor matrix = det * inverse transpose; the scale does not
     * matter once normalised */
    double cof[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[r][c] = a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1];
        }
    double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
    const double v[3] = {n.x, n.y, n.z};
    double out[3];
    for (int r = 0; r < 3; r++)
        out[r] = (cof[r][0] * v[0] + cof[r][1] * v[1] + cof[r][2] * v[2]) / det;
    return (dvec3){out[0], out[1], out[2]};
}

/* ---- one case -------------------------------------------------------------------- */

typedef struct probe_case {
    const char *name;
    luz_scene scene;
    luz_render_options options;
    int threads;
    bool reference;
    bool unlit_allowed;        /* the marker may be probed */
} probe_case;

/* What a case saw, for its own checks of coverage. */
typedef struct case_summary {
    int lit, background, unlit, clipped, multiple_passes, blended_levels, magnified;
    int term_on[LUZ_TERM_COUNT];
    int by_mesh[4];             /* pixels won by a model's meshes 0 .. 3 */
    int max_tests;
    int output_applied;         /* lit pixels under an exposure or tone map */
} case_summary;

typedef struct drawn {
    luz_frame frame;
    luz_renderer *renderer;
    luz_framebuffer *framebuffer;
    uint8_t image[WIDTH * HEIGHT * 4];
    uint32_t overdraw[WIDTH * HEIGHT];
} drawn;

static const uint8_t *pixel_of(const uint8_t *image, int x, int y)
{
    return image + ((size_t)y * WIDTH + x) * 4;
}

static void draw(drawn *d, const probe_case *c, luz_view view, luz_pixel_probe *probe)
{
    luz_render_options options = c->options;
    options.view = view;
    options.probe = probe;
    luz_error error = {{0}};
    assert_int_equal(luz_renderer_draw(d->renderer, &d->frame, d->framebuffer, &options, &error),
                     0);
}

/* The count of depth tests the overdraw view shows: the palette entry its
 * bytes are (8 means 8 or more). */
static uint32_t overdraw_of(const uint8_t *pixel)
{
    for (uint32_t count = 0; count <= 8; count++) {
        luz_vec3 c = luz_view_overdraw_colour(count);
        if (pixel[0] == luz_colour_to_byte(c.x) && pixel[1] == luz_colour_to_byte(c.y) &&
            pixel[2] == luz_colour_to_byte(c.z))
            return count;
    }
    fail_msg("an overdraw pixel (%d, %d, %d) that is no colour of the palette", pixel[0],
             pixel[1], pixel[2]);
    return 0;
}

static void prepare(drawn *d, const probe_case *c)
{
    memset(&d->frame, 0, sizeof d->frame);
    assert_int_equal(luz_scene_build_frame(test_lab(), &c->scene, lab_textures()->textures,
                                           lab_textures()->count, (float)WIDTH / HEIGHT, &d->frame,
                                           NULL),
                     0);
    luz_error error = {{0}};
    d->renderer = luz_renderer_create(
        &(luz_renderer_desc){.thread_count = c->threads, .reference = c->reference}, &error);
    assert_non_null(d->renderer);
    d->framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(d->framebuffer);

    draw(d, c, LUZ_VIEW_OVERDRAW, NULL);
    for (int y = 0; y < HEIGHT; y++)
        for (int x = 0; x < WIDTH; x++)
            d->overdraw[y * WIDTH + x] = overdraw_of(pixel_of(d->framebuffer->colour, x, y));
    draw(d, c, c->options.view, NULL);
    memcpy(d->image, d->framebuffer->colour, sizeof d->image);
}

static void release(drawn *d)
{
    luz_framebuffer_destroy(d->framebuffer);
    luz_renderer_destroy(d->renderer);
    luz_frame_free(&d->frame);
}

/* ---- the checks ---------------------------------------------------------------------- */

static void check_history(const luz_pixel_probe *probe, uint32_t counted, case_summary *summary)
{
    if (counted < 8)
        assert_int_equal(probe->test_count, (int)counted);
    else
        assert_true(probe->test_count >= 8);
    assert_int_equal(probe->tests_kept, probe->test_count);   /* small scenes */
    float stored = 1.0f;
    uint32_t last_pass = 0;
    int passes = 0;
    for (int k = 0; k < probe->tests_kept; k++) {
        const luz_probe_test *test = &probe->tests[k];
        assert_true(test->stored == stored);
        assert_int_equal(test->passed, test->depth < stored);
        if (k > 0) assert_true(test->triangle > probe->tests[k - 1].triangle);   /* draw order */
        if (test->passed) {
            stored = test->depth;
            last_pass = test->triangle;
            passes++;
        }
    }
    assert_int_equal(probe->triangle, last_pass);
    assert_true(probe->depth_buffer == stored);
    if (passes > 1) summary->multiple_passes++;
    if (probe->test_count > summary->max_tests) summary->max_tests = probe->test_count;
}

/* Clip-space positions, world positions, normals and uvs of the winner's
 * mesh triangle, from the mesh and the matrices, in double. */
typedef struct corner_data {
    double clip[3][4];
    dvec3 world[3], normal[3];
    double u[3], v[3];
} corner_data;

static corner_data corners_of(const luz_frame *frame, const luz_pixel_probe *probe)
{
    corner_data corners;
    const luz_draw *draw = &frame->draws[probe->draw];
    for (int k = 0; k < 3; k++) {
        const luz_vertex *vertex = &draw->mesh->vertices[probe->vertices[k]];
        const double object[4] = {vertex->position.x, vertex->position.y, vertex->position.z, 1};
        double world[4], eye[4];
        transform(&draw->model, object, world);
        transform(&frame->view, world, eye);
        transform(&frame->projection, eye, corners.clip[k]);
        corners.world[k] = (dvec3){world[0], world[1], world[2]};
        corners.normal[k] = normal_transform(&draw->model, vertex->normal);
        corners.u[k] = vertex->uv.x;
        corners.v[k] = vertex->uv.y;
    }
    return corners;
}

/* The barycentric coordinates of the point of the triangle that projects
 * to window position (px, py): perspective-correct, solved in clip space
 * (sum b_k (x_k - xn w_k) = 0, the same for y, sum b_k = 1), or for affine
 * interpolation in NDC. */
static dvec3 barycentric_at(const corner_data *corners, double px, double py, bool affine)
{
    const double xn = px / WIDTH * 2.0 - 1.0, yn = 1.0 - py / HEIGHT * 2.0;
    double m[3][3], rhs[3] = {0, 0, 1};
    for (int k = 0; k < 3; k++) {
        const double *c = corners->clip[k];
        if (affine) {
            m[0][k] = c[0] / c[3];
            m[1][k] = c[1] / c[3];
            rhs[0] = xn;
            rhs[1] = yn;
        } else {
            m[0][k] = c[0] - xn * c[3];
            m[1][k] = c[1] - yn * c[3];
        }
        m[2][k] = 1.0;
    }
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    double b[3];
    for (int k = 0; k < 3; k++) {
        double n[3][3];
        memcpy(n, m, sizeof n);
        for (int r = 0; r < 3; r++) n[r][k] = rhs[r];
        b[k] = (n[0][0] * (n[1][1] * n[2][2] - n[1][2] * n[2][1]) -
                n[0][1] * (n[1][0] * n[2][2] - n[1][2] * n[2][0]) +
                n[0][2] * (n[1][0] * n[2][1] - n[1][1] * n[2][0])) /
               det;
    }
    return (dvec3){b[0], b[1], b[2]};
}

static void uv_at(const corner_data *corners, dvec3 b, double *u, double *v)
{
    *u = b.x * corners->u[0] + b.y * corners->u[1] + b.z * corners->u[2];
    *v = b.x * corners->v[0] + b.y * corners->v[1] + b.z * corners->v[2];
}

static void check_geometry(const luz_frame *frame, const probe_case *c,
                           const luz_pixel_probe *probe)
{
    assert_true(probe->primitive >= 0);
    const luz_mesh *mesh = frame->draws[probe->draw].mesh;
    for (int k = 0; k < 3; k++)
        assert_int_equal(probe->vertices[k], mesh->indices[3 * probe->primitive + k]);
    const corner_data corners = corners_of(frame, probe);
    const bool affine = c->options.interpolation == LUZ_INTERPOLATION_AFFINE;
    /* Affine interpolation runs across each piece the clipper made, so its
     * weights are the original triangle's only where nothing was cut. */
    const bool comparable = !affine || probe->clipped_pieces == 0;
    const double px = probe->x + 0.5, py = probe->y + 0.5;

    /* The corners: the vertex stage's clip-space positions, and setup's
     * window positions, snapped to 1/256 of a pixel, with the depth there. */
    double exact[3][3];   /* window x, y and depth of the unsnapped corners */
    for (int k = 0; k < 3; k++) {
        const double *p = corners.clip[k];
        exact[k][0] = (p[0] / p[3] + 1.0) / 2.0 * WIDTH;
        exact[k][1] = (1.0 - p[1] / p[3]) / 2.0 * HEIGHT;
        exact[k][2] = (p[2] / p[3] + 1.0) / 2.0;
    }
    for (int k = 0; k < 3; k++) {
        const float *clip = &probe->corner_clip[k].x;
        for (int j = 0; j < 4; j++)
            assert_near(clip[j], corners.clip[k][j], 1e-5 * (1.0 + fabs(corners.clip[k][j])));
        const luz_vec3 window = probe->corner_window[k];
        assert_true(window.x * 256.0f == floorf(window.x * 256.0f));
        assert_true(window.y * 256.0f == floorf(window.y * 256.0f));
        if (probe->clipped_pieces == 0) {
            assert_near(window.x, exact[k][0], 1.0 / 512 + 1e-4);
            assert_near(window.y, exact[k][1], 1.0 / 512 + 1e-4);
            /* Window depth is affine on the screen: the plane through the
             * exact corners, at the snapped one. */
            const double ax = exact[1][0] - exact[0][0], ay = exact[1][1] - exact[0][1];
            const double bx = exact[2][0] - exact[0][0], by = exact[2][1] - exact[0][1];
            const double da = exact[1][2] - exact[0][2], db = exact[2][2] - exact[0][2];
            const double determinant = ax * by - bx * ay;
            const double dx = (da * by - db * ay) / determinant;
            const double dy = (db * ax - da * bx) / determinant;
            assert_near(window.z,
                        exact[0][2] + dx * (window.x - exact[0][0]) +
                            dy * (window.y - exact[0][1]),
                        2e-5);
        }
    }
    /* The pixel centre lies in the window triangle, which is
     * counter-clockwise in NDC, so clockwise with y down: each edge
     * function (x_j - x_i)(py - y_i) - (y_j - y_i)(px - x_i) <= 0. */
    for (int k = 0; k < 3; k++) {
        const luz_vec3 from = probe->corner_window[(k + 1) % 3],
                       to = probe->corner_window[(k + 2) % 3];
        const double e = ((double)to.x - from.x) * (py - from.y) -
                         ((double)to.y - from.y) * (px - from.x);
        assert_true(e <= 1e-9);
    }

    const dvec3 b = d3(probe->barycentric);
    assert_near(b.x + b.y + b.z, 1.0, 1e-5);
    if (comparable) {
        const dvec3 expected = barycentric_at(&corners, px, py, affine);
        assert_near(b.x, expected.x, 2e-4);
        assert_near(b.y, expected.y, 2e-4);
        assert_near(b.z, expected.z, 2e-4);
    }
    /* P, uv, N, w and depth are the corners' values weighted by b. */
    dvec3 world = add(add(scale(corners.world[0], b.x), scale(corners.world[1], b.y)),
                      scale(corners.world[2], b.z));
    const double position_tolerance = 2e-4 * (1.0 + length(world));
    assert_near(probe->position.x, world.x, position_tolerance);
    assert_near(probe->position.y, world.y, position_tolerance);
    assert_near(probe->position.z, world.z, position_tolerance);
    double u, v;
    uv_at(&corners, b, &u, &v);
    assert_near(probe->uv.x, u, 2e-4 * (1.0 + fabs(u)));
    assert_near(probe->uv.y, v, 2e-4 * (1.0 + fabs(v)));
    const dvec3 n0 = scale(corners.normal[0], b.x), n1 = scale(corners.normal[1], b.y);
    dvec3 normal = normalize(add(n0, add(n1, scale(corners.normal[2], b.z))));
    assert_near(length(d3(probe->normal)), 1.0, 1e-5);
    assert_near(probe->normal.x, normal.x, 2e-4);
    assert_near(probe->normal.y, normal.y, 2e-4);
    assert_near(probe->normal.z, normal.z, 2e-4);
    if (!affine) {
        double w = b.x * corners.clip[0][3] + b.y * corners.clip[1][3] + b.z * corners.clip[2][3];
        double z = b.x * corners.clip[0][2] + b.y * corners.clip[1][2] + b.z * corners.clip[2][2];
        assert_near(probe->w, w, 2e-4 * w);
        assert_near(probe->depth, (z / w + 1.0) / 2.0, 2e-5);
    } else {
        assert_true(probe->w == 1.0f);
    }

    /* uv's screen derivatives: central differences of the interpolation. */
    if (comparable) {
        const double h = 1e-3;
        double u0, v0, u1, v1;
        uv_at(&corners, barycentric_at(&corners, px - h, py, affine), &u0, &v0);
        uv_at(&corners, barycentric_at(&corners, px + h, py, affine), &u1, &v1);
        double du_dx = (u1 - u0) / (2 * h), dv_dx = (v1 - v0) / (2 * h);
        uv_at(&corners, barycentric_at(&corners, px, py - h, affine), &u0, &v0);
        uv_at(&corners, barycentric_at(&corners, px, py + h, affine), &u1, &v1);
        double du_dy = (u1 - u0) / (2 * h), dv_dy = (v1 - v0) / (2 * h);
        assert_near(probe->du_dx, du_dx, 1e-3 * (fabs(du_dx) + 1e-2));
        assert_near(probe->dv_dx, dv_dx, 1e-3 * (fabs(dv_dx) + 1e-2));
        assert_near(probe->du_dy, du_dy, 1e-3 * (fabs(du_dy) + 1e-2));
        assert_near(probe->dv_dy, dv_dy, 1e-3 * (fabs(dv_dy) + 1e-2));
    }
}

/* SCENE.md's six terms, in double, at the probe's P and N. */
static void expected_terms(const luz_frame *frame, const luz_pixel_probe *probe,
                           dvec3 terms[LUZ_TERM_COUNT])
{
    const luz_lights *lights = &frame->lights;
    const dvec3 p = d3(probe->position), n = normalize(d3(probe->normal)), e = d3(frame->eye);
    const dvec3 to_eye = normalize(sub(e, p));
    const double n_dot_l = dot(n, to_eye);
    terms[LUZ_TERM_AMBIENT] = scale(d3(lights->ambient.colour), lights->ambient.strength);
    terms[LUZ_TERM_DIFFUSE] =
        scale(d3(lights->diffuse.colour), fmax(n_dot_l, 0) * lights->diffuse.strength);
    const dvec3 reflected = sub(scale(n, 2 * n_dot_l), to_eye);
    terms[LUZ_TERM_SPECULAR] =
        scale(d3(lights->specular.colour),
              lights->specular.strength * pow(fmax(dot(to_eye, reflected), 0), lights->shininess));
    const dvec3 to_point = normalize(sub(d3(lights->point_position), p));
    terms[LUZ_TERM_POINT] =
        scale(d3(lights->point.colour), fmax(dot(n, to_point), 0) * lights->point.strength);
    const double c = dot(normalize(sub(p, e)), normalize(d3(lights->spot_direction)));
    const double ci = cos(lights->spot_inner_degrees * LUZ_PI / 180);
    const double co = cos(lights->spot_outer_degrees * LUZ_PI / 180);
    double f_direction = 0;
    if (c > ci) {
        f_direction = 1;
    } else if (c > co) {
        double s = sqrt((c - co) / (ci - co));
        f_direction = s * s * (3 - 2 * s);
    }
    const double dn = length(sub(e, p)) / lights->spot_reach;
    const double window = fmax(1 - pow(dn, 4), 0);
    const double f_distance = window * window * lights->spot.strength * lights->spot.strength /
                              (dn * dn + 1);
    terms[LUZ_TERM_SPOT] = scale(d3(lights->spot.colour), f_direction * f_distance);
    const dvec3 to_sun = normalize(scale(d3(lights->directional_direction), -1));
    terms[LUZ_TERM_DIRECTIONAL] = scale(d3(lights->directional.colour),
                                        fmax(dot(n, to_sun), 0) * lights->directional.strength);
}

/* A texel of level `level`, wrapped (REPEAT), in [0, 1]. */
static dvec3 texel_at(const luz_texture *texture, int level, int x, int y)
{
    const luz_texture_level *l = &texture->levels[level];
    x = ((x % l->width) + l->width) % l->width;
    y = ((y % l->height) + l->height) % l->height;
    const uint8_t *t = l->texels + ((size_t)y * l->width + x) * 4;
    return (dvec3){t[0] / 255.0, t[1] / 255.0, t[2] / 255.0};
}

/* Bilinear on one level: the texel centres around the point, (i + 0.5) / w. */
static dvec3 bilinear(const luz_texture *texture, int level, double u, double v)
{
    const luz_texture_level *l = &texture->levels[level];
    const double su = (u - floor(u)) * l->width - 0.5, sv = (v - floor(v)) * l->height - 0.5;
    const int x0 = (int)floor(su), y0 = (int)floor(sv);
    const double fx = su - x0, fy = sv - y0;
    return add(add(scale(texel_at(texture, level, x0, y0), (1 - fx) * (1 - fy)),
                   scale(texel_at(texture, level, x0 + 1, y0), fx * (1 - fy))),
               add(scale(texel_at(texture, level, x0, y0 + 1), (1 - fx) * fy),
                   scale(texel_at(texture, level, x0 + 1, y0 + 1), fx * fy)));
}

static void check_texture(const luz_frame *frame, const probe_case *c, const luz_pixel_probe *probe,
                          case_summary *summary)
{
    const luz_material *material = &frame->draws[probe->draw].material;
    assert_ptr_equal(probe->texture, material->texture);
    const luz_texture *texture = material->texture;
    if (texture == NULL) {
        assert_true(probe->texel.x == 1.0f && probe->texel.y == 1.0f && probe->texel.z == 1.0f);
        return;
    }
    assert_int_equal(probe->filter, material->filter);
    /* rho from the derivatives, in texels of level 0 */
    const double w = texture->levels[0].width, h = texture->levels[0].height;
    const double rho = fmax(hypot(probe->du_dx * w, probe->dv_dx * h),
                            hypot(probe->du_dy * w, probe->dv_dy * h));
    assert_near(probe->rho, rho, 1e-5 * (1 + rho));

    dvec3 expected;
    const double u = probe->uv.x, v = probe->uv.y;
    switch (material->filter) {
    case LUZ_FILTER_NEAREST: {
        assert_true(probe->lambda == 0.0f);
        /* floor(fract(u) w), in the float arithmetic the sampler is
         * specified with */
        float fu = probe->uv.x - floorf(probe->uv.x), fv = probe->uv.y - floorf(probe->uv.y);
        int x = (int)(fu * (float)w), y = (int)(fv * (float)h);
        expected = texel_at(texture, 0, x, y);
        break;
    }
    case LUZ_FILTER_BILINEAR:
        assert_true(probe->lambda == 0.0f);
        expected = bilinear(texture, 0, u, v);
        break;
    default: {
        /* The level of detail of the path that shaded this pixel. */
        const bool packet = !c->reference && c->options.view == LUZ_VIEW_COLOR;
        const float lambda =
            packet ? luz_packet_level_of_detail(texture, probe->du_dx, probe->dv_dx,
                                                probe->du_dy, probe->dv_dy)
                   : luz_texture_level_of_detail(texture, probe->du_dx, probe->dv_dx,
                                                 probe->du_dy, probe->dv_dy);
        assert_true(probe->lambda == lambda);
        assert_near(probe->lambda, rho > 1 ? log2(rho) : 0.0, 1e-4);
        /* levels floor(lambda) and the next, clamped, blended by fract */
        const int last = texture->level_count - 1;
        int lower = 0, upper = 0;
        double blend = 0;
        if (lambda > 0) {
            lower = (int)floor(lambda);
            if (lower >= last) {
                lower = upper = last;
            } else {
                upper = lower + 1;
                blend = lambda - lower;
            }
        }
        assert_int_equal(probe->levels.lower, lower);
        assert_int_equal(probe->levels.upper, upper);
        assert_near(probe->levels.blend, blend, 1e-6);
        expected = add(scale(bilinear(texture, lower, u, v), 1 - blend),
                       scale(bilinear(texture, upper, u, v), blend));
        if (blend > 0.05 && blend < 0.95) summary->blended_levels++;
        if (rho < 1) summary->magnified++;
        break;
    }
    }
    assert_near(probe->texel.x, expected.x, 1e-4);
    assert_near(probe->texel.y, expected.y, 1e-4);
    assert_near(probe->texel.z, expected.z, 1e-4);
}

static void check_lit(const luz_frame *frame, const probe_case *c, const luz_pixel_probe *probe,
                      case_summary *summary)
{
    check_geometry(frame, c, probe);
    check_texture(frame, c, probe, summary);

    /* The terms add up to light, in luz_term's order, to the bit ... */
    luz_vec3 sum = probe->terms[0];
    for (int term = 1; term < LUZ_TERM_COUNT; term++) {
        sum.x += probe->terms[term].x;
        sum.y += probe->terms[term].y;
        sum.z += probe->terms[term].z;
    }
    assert_memory_equal(&sum, &probe->light, sizeof sum);
    /* ... and colour is light x C x T. */
    const luz_vec3 C = frame->draws[probe->draw].material.colour;
    assert_memory_equal(&probe->object_colour, &C, sizeof C);
    const luz_vec3 colour = {probe->light.x * C.x * probe->texel.x,
                             probe->light.y * C.y * probe->texel.y,
                             probe->light.z * C.z * probe->texel.z};
    assert_memory_equal(&colour, &probe->colour, sizeof colour);
    /* The output: the frame's exposure and tone map; exposed is colour x
     * 2^EV and mapped the tone map of that (or the colour itself at clamp
     * and EV 0, which the fragment stages leave alone). */
    assert_float_equal(probe->exposure, frame->output.exposure, 0.0);
    assert_int_equal(probe->tone_map, frame->output.tone_map);
    assert_float_equal(probe->exposure_scale, exp2(frame->output.exposure), 0.0);
    const float scale = probe->exposure_scale;
    const luz_vec3 exposed = {colour.x * scale, colour.y * scale, colour.z * scale};
    assert_memory_equal(&exposed, &probe->exposed, sizeof exposed);
    const luz_vec3 mapped =
        frame->output.tone_map == LUZ_TONE_MAP_NEUTRAL ? luz_tone_map_neutral(exposed) : exposed;
    assert_memory_equal(&mapped, &probe->mapped, sizeof mapped);
    if (frame->output.tone_map != LUZ_TONE_MAP_CLAMP || frame->output.exposure != 0.0f)
        summary->output_applied++;

    /* Each term is its equation. */
    dvec3 expected[LUZ_TERM_COUNT];
    expected_terms(frame, probe, expected);
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        assert_near(probe->terms[term].x, expected[term].x, 2e-4);
        assert_near(probe->terms[term].y, expected[term].y, 2e-4);
        assert_near(probe->terms[term].z, expected[term].z, 2e-4);
        if (probe->terms[term].x + probe->terms[term].y + probe->terms[term].z > 0.01f)
            summary->term_on[term]++;
    }
    if (probe->clipped_pieces > 0) summary->clipped++;
}

/* What the view shows, from the probe's numbers and luz/view.h's
 * palettes. */
static void check_view(const probe_case *c, const luz_frame *frame,
                       const luz_pixel_probe *probe, const uint8_t *pixel)
{
    const luz_vec3 s = probe->shown;
    assert_int_equal(pixel[0], luz_colour_to_byte(s.x));
    assert_int_equal(pixel[1], luz_colour_to_byte(s.y));
    assert_int_equal(pixel[2], luz_colour_to_byte(s.z));
    luz_vec3 expected = s;
    switch (c->options.view) {
    case LUZ_VIEW_DEPTH: {
        float grey = luz_view_depth_brightness(probe->depth_buffer, &frame->projection);
        expected = (luz_vec3){grey, grey, grey};
        break;
    }
    case LUZ_VIEW_OVERDRAW:
        assert_int_equal(probe->overdraw, (uint32_t)probe->test_count);
        expected = luz_view_overdraw_colour(probe->overdraw);
        break;
    case LUZ_VIEW_NORMALS:
        if (probe->triangle == 0) return;
        expected = (luz_vec3){probe->normal.x * 0.5f + 0.5f, probe->normal.y * 0.5f + 0.5f,
                              probe->normal.z * 0.5f + 0.5f};
        break;
    case LUZ_VIEW_UV:
        if (probe->triangle == 0) return;
        expected = (luz_vec3){probe->uv.x - floorf(probe->uv.x), probe->uv.y - floorf(probe->uv.y),
                              0};
        break;
    case LUZ_VIEW_MIP: {
        if (probe->triangle == 0 || probe->texture == NULL) return;
        luz_vec3 lower = luz_view_mip_colour(probe->levels.lower);
        luz_vec3 upper = luz_view_mip_colour(probe->levels.upper);
        float t = probe->levels.blend;
        expected = luz_vec3_add(luz_vec3_scale(lower, 1 - t), luz_vec3_scale(upper, t));
        break;
    }
    case LUZ_VIEW_TRIANGLES:
        if (probe->triangle == 0) return;
        expected = luz_view_triangle_colour(probe->triangle);
        if (probe->on_edge) expected = luz_vec3_scale(expected, LUZ_VIEW_TRIANGLE_EDGE_SHADE);
        break;
    case LUZ_VIEW_BANDS: {
        /* the colour view's bytes under the tint of the band's thread */
        luz_vec3 colour = probe->triangle ? probe->mapped : frame->clear_colour;
        luz_vec3 tint = luz_view_thread_colour(probe->worker);
        const float k = LUZ_VIEW_BANDS_TINT;
        expected = (luz_vec3){(1 - k) * luz_colour_to_byte(colour.x) / 255.0f + k * tint.x,
                              (1 - k) * luz_colour_to_byte(colour.y) / 255.0f + k * tint.y,
                              (1 - k) * luz_colour_to_byte(colour.z) / 255.0f + k * tint.z};
        assert_int_equal(probe->band, probe->y / 16);
        break;
    }
    default:
        break;
    }
    assert_near(s.x, expected.x, 1e-5);
    assert_near(s.y, expected.y, 1e-5);
    assert_near(s.z, expected.z, 1e-5);
}

static case_summary run_case(const probe_case *c)
{
    drawn *d = calloc(1, sizeof *d);
    assert_non_null(d);
    prepare(d, c);
    case_summary summary = {0};
    luz_pixel_probe *probe = calloc(1, sizeof *probe);
    assert_non_null(probe);
    const luz_probe_names names = {.scene = &c->scene, .textures = lab_textures()};

    for (int y = 0; y < HEIGHT; y++) {
        for (int x = 0; x < WIDTH; x++) {
            *probe = (luz_pixel_probe){.x = x, .y = y};
            draw(d, c, c->options.view, probe);
            /* A probe changes nothing in the image; but with two threads
             * the bands view shows whichever thread drew a band. */
            const bool same_every_time = c->options.view != LUZ_VIEW_BANDS || c->threads == 1;
            if (same_every_time)
                assert_memory_equal(d->framebuffer->colour, d->image, sizeof d->image);
            const uint8_t *pixel = pixel_of(d->framebuffer->colour, x, y);
            assert_true(probe->filled);
            assert_int_equal(probe->x, x);
            assert_int_equal(probe->y, y);
            assert_int_equal(probe->view, c->options.view);
            assert_memory_equal(probe->bytes, pixel, 3);
            check_history(probe, d->overdraw[y * WIDTH + x], &summary);
            if (c->options.view != LUZ_VIEW_COLOR) check_view(c, &d->frame, probe, pixel);

            if (probe->triangle == 0) {
                summary.background++;
                continue;
            }
            const luz_probe_source source = luz_probe_source_of(&names, probe->draw);
            if (source.object >= 0 && source.mesh < 4) summary.by_mesh[source.mesh]++;
            if (probe->shading == LUZ_SHADING_UNLIT) {
                assert_true(c->unlit_allowed);
                assert_int_equal(source.object, LUZ_DRAW_POINT_LIGHT);
                summary.unlit++;
            } else {
                check_lit(&d->frame, c, probe, &summary);
                summary.lit++;
            }
            /* the probe's mapped colour made the colour view's byte (the
             * marker's is its colour as it is) */
            if (c->options.view == LUZ_VIEW_COLOR) {
                assert_int_equal(pixel[0], luz_colour_to_byte(probe->mapped.x));
                assert_int_equal(pixel[1], luz_colour_to_byte(probe->mapped.y));
                assert_int_equal(pixel[2], luz_colour_to_byte(probe->mapped.z));
                if (probe->shading == LUZ_SHADING_UNLIT)
                    assert_memory_equal(&probe->mapped, &probe->colour, sizeof probe->colour);
            }
        }
    }
    free(probe);
    release(d);
    free(d);
    return summary;
}

/* ---- the cases ------------------------------------------------------------------------- */

static probe_case case_of(const char *name)
{
    probe_case c = {.name = name, .scene = luz_scene_defaults(), .threads = 1};
    return c;
}

static void set_camera(luz_scene *scene, float x, float y, float z, float yaw, float pitch)
{
    scene->camera.position = (luz_vec3){x, y, z};
    scene->camera.yaw_degrees = yaw;
    scene->camera.pitch_degrees = pitch;
}

static void only(luz_scene *scene, luz_term kept)
{
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        if (term != (int)kept) luz_lights_term(&scene->lights, (luz_term)term)->strength = 0.0f;
}

static void each_term_alone(void **state)
{
    (void)state;
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        /* t = 0: the point light to the right lights the cubes' +x faces
         * seen on the left, the sun (travelling along +x) their -x faces
         * seen on the right, the headlights the faces towards the camera */
        probe_case c = case_of(luz_term_name((luz_term)term));
        only(&c.scene, (luz_term)term);
        c.unlit_allowed = true;
        case_summary s = run_case(&c);
        print_message("only %s: %d lit pixels, %d with the term on\n", c.name, s.lit,
                      s.term_on[term]);
        assert_true(s.term_on[term] > 20);
        for (int other = 0; other < LUZ_TERM_COUNT; other++)
            if (other != term) assert_int_equal(s.term_on[other], 0);
    }
}

static void each_filter(void **state)
{
    (void)state;
    const luz_filter filters[] = {LUZ_FILTER_NEAREST, LUZ_FILTER_BILINEAR, LUZ_FILTER_TRILINEAR};
    for (int i = 0; i < 3; i++) {
        /* far enough that the textures are minified: mip levels mix */
        probe_case c = case_of(luz_filter_name(filters[i]));
        c.scene.filter = filters[i];
        c.scene.time_seconds = 2.0;
        set_camera(&c.scene, 0.0f, 0.5f, 5.0f, -90.0f, -5.0f);
        c.unlit_allowed = true;
        case_summary s = run_case(&c);
        print_message("%s: %d lit, %d blending two levels, %d background\n", c.name, s.lit,
                      s.blended_levels, s.background);
        assert_true(s.lit > 100);
        if (filters[i] == LUZ_FILTER_TRILINEAR) assert_true(s.blended_levels > 10);
    }
}

static void magnified_and_reference(void **state)
{
    (void)state;
    /* A camera almost touching cube 0: its texture magnified, lambda 0
     * (the level of detail's early return); and the far scene again with
     * the reference fragment stage, whose level of detail is log2f's. */
    probe_case c = case_of("magnified");
    set_camera(&c.scene, 0.1f, 0.1f, 0.605f, -90.0f, 0.0f);
    case_summary s = run_case(&c);
    print_message("magnified: %d lit, %d with rho < 1\n", s.lit, s.magnified);
    assert_true(s.magnified > 500);

    c = case_of("reference");
    c.scene.time_seconds = 2.0;
    set_camera(&c.scene, 0.0f, 0.5f, 5.0f, -90.0f, -5.0f);
    c.reference = true;
    c.unlit_allowed = true;
    s = run_case(&c);
    print_message("reference: %d lit, %d blending two levels\n", s.lit, s.blended_levels);
    assert_true(s.blended_levels > 10);
}

static void affine(void **state)
{
    (void)state;
    probe_case c = case_of("affine");
    c.scene.time_seconds = 3.0;
    set_camera(&c.scene, 0.7f, 0.4f, 1.4f, -110.0f, -12.0f);
    c.options.interpolation = LUZ_INTERPOLATION_AFFINE;
    c.scene.interpolation = LUZ_INTERPOLATION_AFFINE;
    c.unlit_allowed = true;
    case_summary s = run_case(&c);
    assert_true(s.lit > 300);
}

static void clipped_face(void **state)
{
    (void)state;
    /* the camera just above cube 0's top face: the near plane cuts it
     * (docs/figures' clip-color.png) */
    probe_case c = case_of("clipped");
    set_camera(&c.scene, 0.1f, 0.56f, 0.2f, -100.0f, -25.0f);
    c.unlit_allowed = true;
    case_summary s = run_case(&c);
    print_message("clipped: %d lit pixels, %d of clipped pieces\n", s.lit, s.clipped);
    assert_true(s.clipped > 100);
}

static void overlapping_cubes_and_the_marker(void **state)
{
    (void)state;
    /* t = 8: the point light's unlit marker in view; cubes overlap on the
     * screen, and where a nearer one is drawn later two tests pass */
    probe_case c = case_of("marker");
    c.scene.time_seconds = 8.0;
    c.unlit_allowed = true;
    c.threads = 2;   /* bands on two threads: the bytes are kept by either */
    case_summary s = run_case(&c);
    print_message("t = 8: %d lit, %d unlit (marker), %d with two passes, at most %d tests\n",
                  s.lit, s.unlit, s.multiple_passes, s.max_tests);
    assert_true(s.unlit > 0);
    assert_true(s.multiple_passes > 0);
}

static void equal_depths_fail(void **state)
{
    (void)state;
    /* Two cubes in one place: the second one's fragments have exactly the
     * first one's depths, and LESS turns every one of them away. */
    const luz_object objects[2] = {
        {.position = {0, 0, 0}, .has_colour = true, .colour = {1, 0, 0},
         .texture = LUZ_TEXTURE_BY_INDEX},
        {.position = {0, 0, 0}, .has_colour = true, .colour = {0, 0, 1},
         .texture = LUZ_TEXTURE_BY_INDEX},
    };
    probe_case c = case_of("equal depths");
    c.scene.objects = objects;
    c.scene.object_count = 2;
    /* t = 0: cube i turns at (i + 1) / 3 t 50 degrees, so only then do
     * the two coincide; and no point light, whose marker would be drawn */
    c.scene.lights.point.strength = 0.0f;
    drawn *d = calloc(1, sizeof *d);
    assert_non_null(d);
    prepare(d, &c);
    luz_pixel_probe *probe = calloc(1, sizeof *probe);
    int ties = 0;
    for (int y = 0; y < HEIGHT; y++)
        for (int x = 0; x < WIDTH; x++) {
            *probe = (luz_pixel_probe){.x = x, .y = y};
            draw(d, &c, LUZ_VIEW_COLOR, probe);
            if (probe->triangle == 0) continue;
            assert_int_equal(probe->test_count, 2);
            assert_int_equal(probe->tests[0].draw, 0);
            assert_int_equal(probe->tests[1].draw, 1);
            assert_true(probe->tests[1].depth == probe->tests[0].depth);
            assert_true(probe->tests[0].passed);
            assert_false(probe->tests[1].passed);
            assert_int_equal(probe->draw, 0);
            ties++;
        }
    assert_true(ties > 100);
    free(probe);
    release(d);
    free(d);
}

/* A model of two meshes, each its own draw: a sphere and a ring around
 * it, textured, among two cubes. */
static luz_mesh *sphere_mesh(double radius, double ring_radius, int rings, int segments)
{
    const int vertex_count = (rings + 1) * (segments + 1);
    luz_vertex *vertices = calloc((size_t)vertex_count, sizeof *vertices);
    uint32_t *indices = calloc((size_t)rings * segments * 6, sizeof *indices);
    assert_true(vertices && indices);
    for (int r = 0; r <= rings; r++)
        for (int s = 0; s <= segments; s++) {
            /* a torus when ring_radius > 0, else a sphere */
            double theta = (double)r / rings * (ring_radius > 0 ? 2 * LUZ_PI : LUZ_PI);
            double phi = (double)s / segments * 2 * LUZ_PI;
            dvec3 n, p;
            if (ring_radius > 0) {
                n = (dvec3){cos(theta) * cos(phi), sin(theta), cos(theta) * sin(phi)};
                p = add((dvec3){ring_radius * cos(phi), 0, ring_radius * sin(phi)},
                        scale(n, radius));
            } else {
                n = (dvec3){sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi)};
                p = scale(n, radius);
            }
            vertices[r * (segments + 1) + s] = (luz_vertex){
                {(float)p.x, (float)p.y, (float)p.z},
                {(float)n.x, (float)n.y, (float)n.z},
                {(float)(2.0 * s / segments), (float)((double)r / rings)}};
        }
    int k = 0;
    for (int r = 0; r < rings; r++)
        for (int s = 0; s < segments; s++) {
            uint32_t a = (uint32_t)(r * (segments + 1) + s), b = a + 1;
            uint32_t c = a + (uint32_t)(segments + 1), d = c + 1;
            /* counter-clockwise seen from outside */
            uint32_t quad[6] = {a, b, c, b, d, c};
            if (ring_radius > 0) {
                uint32_t flipped[6] = {a, c, b, b, c, d};
                memcpy(quad, flipped, sizeof quad);
            }
            memcpy(indices + k, quad, sizeof quad);
            k += 6;
        }
    luz_error error = {{0}};
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices,
                                                      .vertex_count = (uint32_t)vertex_count,
                                                      .indices = indices,
                                                      .index_count = (uint32_t)k},
                                     &error);
    assert_non_null(mesh);
    free(vertices);
    free(indices);
    return mesh;
}

static void a_model(void **state)
{
    (void)state;
    luz_mesh *sphere = sphere_mesh(0.6, 0, 12, 16);
    luz_mesh *ring = sphere_mesh(0.12, 0.9, 10, 24);
    const luz_lab_model_part parts[2] = {
        {.mesh = sphere, .has_uvs = true, .texture = lab_textures()->textures[0],
         .mesh_name = "ball", .material_name = "stone", .texture_name = "ball.png"},
        {.mesh = ring, .has_colour = true, .colour = {0.9f, 0.6f, 0.2f}, .has_uvs = true,
         .mesh_name = "ring", .material_name = "gold"},
    };
    luz_lab_model model = {.name = "planet.obj", .parts = parts, .part_count = 2};
    model.bounds = (luz_bounds){{-1.02f, -0.6f, -1.02f}, {1.02f, 0.6f, 1.02f}};
    const luz_object objects[3] = {
        {.position = {-1.2f, 0.3f, -1.0f}, .texture = LUZ_TEXTURE_BY_INDEX},
        {.position = {0.2f, 0.0f, 0.0f}, .texture = LUZ_TEXTURE_BY_INDEX, .model = &model,
         .scale = 0.9f},
        {.position = {1.4f, -0.2f, -0.8f}, .texture = 2},
    };
    probe_case c = case_of("model");
    c.scene.objects = objects;
    c.scene.object_count = 3;
    c.scene.time_seconds = 1.2;
    c.unlit_allowed = true;
    case_summary s = run_case(&c);
    print_message("model: %d lit; mesh 0 (cubes and the ball) %d, mesh 1 (the ring) %d\n", s.lit,
                  s.by_mesh[0], s.by_mesh[1]);
    assert_true(s.by_mesh[1] > 20);
    /* A scene with a model: neutral at EV -1 on every lit pixel. */
    assert_int_equal(s.output_applied, s.lit);
    /* and clamp at EV 1.5, given */
    c.scene.has_exposure = c.scene.has_tone_map = true;
    c.scene.exposure = 1.5f;
    c.scene.tone_map = LUZ_TONE_MAP_CLAMP;
    s = run_case(&c);
    assert_int_equal(s.output_applied, s.lit);

    /* The names: the draws are cube 0, the ball, the ring, cube 2, the
     * marker. */
    const luz_probe_names names = {.scene = &c.scene, .textures = lab_textures()};
    luz_probe_source source = luz_probe_source_of(&names, 2);
    assert_int_equal(source.object, 1);
    assert_int_equal(source.mesh, 1);
    assert_string_equal(source.model, "planet.obj");
    assert_string_equal(source.mesh_name, "ring");
    assert_string_equal(source.material_name, "gold");
    source = luz_probe_source_of(&names, 3);
    assert_int_equal(source.object, 2);
    assert_null(source.model);
    assert_int_equal(luz_probe_source_of(&names, 4).object, LUZ_DRAW_POINT_LIGHT);
    assert_int_equal(luz_probe_source_of(&names, 5).object, LUZ_DRAW_NONE);
    /* the ball's texture is a file of the directory (the set's name wins);
     * cube 2 names its own */
    assert_string_equal(luz_probe_texture_name(&names, 1, lab_textures()->textures[0]), lab_textures()->names[0]);
    assert_string_equal(luz_probe_texture_name(&names, 3, lab_textures()->textures[2]), lab_textures()->names[2]);
    assert_string_equal(luz_probe_texture_name(&names, 3, NULL), "none");
    luz_mesh_destroy(sphere);
    luz_mesh_destroy(ring);
}

static void every_view(void **state)
{
    (void)state;
    for (int view = LUZ_VIEW_DEPTH; view < LUZ_VIEW_COUNT; view++) {
        probe_case c = case_of(luz_view_name((luz_view)view));
        c.scene.time_seconds = 3.0;
        c.options.view = (luz_view)view;
        c.unlit_allowed = true;
        c.threads = view == LUZ_VIEW_BANDS ? 2 : 1;
        case_summary s = run_case(&c);
        print_message("view %s: %d lit, %d background\n", c.name, s.lit, s.background);
        assert_true(s.lit > 100 && s.background > 100);
    }
}

/* ---- the probe's edges ------------------------------------------------------------------ */

static void outside_the_image(void **state)
{
    (void)state;
    probe_case c = case_of("outside");
    drawn *d = calloc(1, sizeof *d);
    assert_non_null(d);
    prepare(d, &c);
    const int places[4][2] = {{-1, 0}, {0, -1}, {WIDTH, 0}, {0, HEIGHT}};
    for (int i = 0; i < 4; i++) {
        luz_pixel_probe probe = {.x = places[i][0], .y = places[i][1], .test_count = 99};
        draw(d, &c, LUZ_VIEW_COLOR, &probe);
        assert_false(probe.filled);
        assert_int_equal(probe.test_count, 0);
        assert_int_equal(probe.x, places[i][0]);
        assert_memory_equal(d->framebuffer->colour, d->image, sizeof d->image);
    }
    release(d);
    free(d);
}

/* The band hook draws over the pixel after the probe kept its bytes. */
static void paint_red(void *context, luz_framebuffer *framebuffer, int first_row, int end_row)
{
    (void)context;
    const size_t width = (size_t)framebuffer->width;
    for (size_t i = (size_t)first_row * width; i < (size_t)end_row * width; i++)
        memcpy(framebuffer->colour + i * 4, (uint8_t[4]){255, 0, 0, 255}, 4);
}

static void bytes_before_the_hook_in_bgra(void **state)
{
    (void)state;
    probe_case c = case_of("hook");
    drawn *d = calloc(1, sizeof *d);
    assert_non_null(d);
    prepare(d, &c);
    const luz_band_hook hook = {paint_red, NULL};
    c.options.hook = &hook;
    luz_framebuffer_use_colour(d->framebuffer, NULL, LUZ_CHANNELS_BGRA);
    luz_pixel_probe probe = {.x = WIDTH / 2, .y = HEIGHT / 2};
    draw(d, &c, LUZ_VIEW_COLOR, &probe);
    assert_memory_equal(probe.bytes, pixel_of(d->image, WIDTH / 2, HEIGHT / 2), 3);
    /* the hook's red, in BGRA memory order */
    assert_memory_equal(pixel_of(d->framebuffer->colour, WIDTH / 2, HEIGHT / 2),
                        ((uint8_t[4]){255, 0, 0, 255}), 4);
    release(d);
    free(d);
}

/* The step mode draws only the first triangles: the history has only
 * those. */
static void only_the_triangles_drawn(void **state)
{
    (void)state;
    probe_case c = case_of("step");
    drawn *d = calloc(1, sizeof *d);
    assert_non_null(d);
    prepare(d, &c);
    /* a pixel whose first test is not the frame's first triangle */
    luz_pixel_probe *probe = calloc(1, sizeof *probe);
    uint32_t first = 0;
    for (int i = 0; i < WIDTH * HEIGHT && first < 2; i++) {
        *probe = (luz_pixel_probe){.x = i % WIDTH, .y = i / WIDTH};
        draw(d, &c, LUZ_VIEW_COLOR, probe);
        first = probe->test_count > 0 ? probe->tests[0].triangle : 0;
    }
    assert_true(first >= 2);
    const luz_pixel_probe all = *probe;
    c.options.triangle_limit = first - 1;
    draw(d, &c, LUZ_VIEW_COLOR, probe);
    assert_int_equal(probe->test_count, 0);
    assert_int_equal(probe->triangle, 0);
    c.options.triangle_limit = first;
    draw(d, &c, LUZ_VIEW_COLOR, probe);
    assert_int_equal(probe->test_count, 1);
    assert_int_equal(probe->tests[0].triangle, first);
    assert_true(all.test_count >= 1);
    free(probe);
    release(d);
    free(d);
}

/* ---- the text luz-render prints ------------------------------------------------------------ */

/* The value of `key=` on its own line of text, or NULL. */
static const char *value_of(const char *text, const char *key, char *buffer, size_t size)
{
    size_t length = strlen(key);
    for (const char *line = text; line && *line;
         line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        if (strncmp(line, key, length) == 0 && line[length] == '=') {
            const char *end = strchr(line, '\n');
            size_t n = end ? (size_t)(end - line - length - 1) : strlen(line + length + 1);
            snprintf(buffer, size, "%.*s", (int)n, line + length + 1);
            return buffer;
        }
    }
    return NULL;
}

static void read_vec3(const char *text, const char *key, luz_vec3 *out)
{
    char buffer[128];
    assert_non_null(value_of(text, key, buffer, sizeof buffer));
    assert_int_equal(sscanf(buffer, "%f,%f,%f", &out->x, &out->y, &out->z), 3);
}

static char *written(const luz_pixel_probe *probe, const luz_probe_names *names)
{
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    assert_non_null(out);
    luz_probe_write(out, probe, names, WIDTH, HEIGHT, 2.5);
    fclose(out);
    return text;
}

static void the_text(void **state)
{
    (void)state;
    probe_case c = case_of("text");
    c.scene.time_seconds = 2.5;
    drawn *d = calloc(1, sizeof *d);
    assert_non_null(d);
    prepare(d, &c);
    const luz_probe_names names = {.scene = &c.scene, .textures = lab_textures()};

    /* A lit pixel: the keys in the order, and numbers that read
     * back to the probe's floats exactly. */
    luz_pixel_probe *probe = calloc(1, sizeof *probe);
    *probe = (luz_pixel_probe){.x = WIDTH / 2, .y = HEIGHT / 2};
    draw(d, &c, LUZ_VIEW_COLOR, probe);
    assert_true(probe->triangle != 0);
    char *text = written(probe, &names);
    const char *order[] = {"pixel=", "size=", "time=", "test=1 ", "object=", "mesh=",
                           "triangle=", "corner0_clip=", "corner1_clip=", "corner2_clip=",
                           "clipped=", "corner0_window=", "corner1_window=", "corner2_window=",
                           "barycentric=", "w=", "P=", "N=", "uv=", "texture=",
                           "rho=", "lod=", "levels=", "weight=", "texel=", "ambient=",
                           "diffuse=", "specular=", "point=", "spot=", "directional=",
                           "light=", "C=", "colour=", "bytes="};
    assert_true(strncmp(text, order[0], strlen(order[0])) == 0);
    const char *cursor = text;
    for (size_t i = 1; i < sizeof order / sizeof order[0]; i++) {
        char key[32];
        snprintf(key, sizeof key, "\n%s", order[i]);
        const char *found = strstr(cursor, key);
        if (found == NULL)
            fail_msg("'%s' missing after position %td of:\n%s", order[i], cursor - text, text);
        cursor = found + 1;
    }
    char buffer[128];
    assert_string_equal(value_of(text, "pixel", buffer, sizeof buffer), "24,13");
    assert_string_equal(value_of(text, "size", buffer, sizeof buffer), "48,27");
    assert_string_equal(value_of(text, "time", buffer, sizeof buffer), "2.5");
    luz_vec3 v;
    read_vec3(text, "light", &v);
    assert_memory_equal(&v, &probe->light, sizeof v);
    read_vec3(text, "colour", &v);
    assert_memory_equal(&v, &probe->colour, sizeof v);
    read_vec3(text, "barycentric", &v);
    assert_memory_equal(&v, &probe->barycentric, sizeof v);
    for (int term = 0; term < LUZ_TERM_COUNT; term++) {
        read_vec3(text, luz_term_name((luz_term)term), &v);
        assert_memory_equal(&v, &probe->terms[term], sizeof v);
    }
    unsigned bytes[3];
    assert_int_equal(sscanf(value_of(text, "bytes", buffer, sizeof buffer), "%u,%u,%u", &bytes[0],
                            &bytes[1], &bytes[2]),
                     3);
    for (int k = 0; k < 3; k++) assert_int_equal(bytes[k], probe->bytes[k]);
    /* one test line per test, as the issue spells it */
    char line[160];
    snprintf(line, sizeof line, "test=1 object=%d mesh=0 triangle=%lu depth=",
             luz_probe_source_of(&names, probe->tests[0].draw).object,
             (unsigned long)probe->tests[0].triangle);
    assert_non_null(strstr(text, line));
    free(text);

    /* The background: object=none, then only bytes. */
    *probe = (luz_pixel_probe){.x = 0, .y = 0};
    draw(d, &c, LUZ_VIEW_COLOR, probe);
    assert_int_equal(probe->triangle, 0);
    text = written(probe, &names);
    const char *none = strstr(text, "object=none\n");
    assert_non_null(none);
    assert_string_equal(none, "object=none\nbytes=26,26,26\n");
    free(text);
    free(probe);
    release(d);
    free(d);
}

/* The guided tour (docs/pipeline.md) follows pixel (700, 450) of the default frame at
 * 1280x720: its corners, worked out here by hand from SCENE.md's numbers
 * (the cube table's +Z face, cube 0 at the origin and not yet turned at
 * t = 0, the camera at (0, 0, 3) looking down -z, a 45 degree field of
 * view, near 0.1, far 100), not from the frame's matrices. */
static void the_tour_pixel(void **state)
{
    (void)state;
    enum { TOUR_WIDTH = 1280, TOUR_HEIGHT = 720 };
    const luz_scene scene = luz_scene_defaults();
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, lab_textures()->textures, lab_textures()->count,
                                           (float)TOUR_WIDTH / TOUR_HEIGHT, &frame, NULL),
                     0);
    luz_error error = {{0}};
    luz_renderer *renderer =
        luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    assert_non_null(renderer);
    luz_framebuffer *framebuffer = luz_framebuffer_create(TOUR_WIDTH, TOUR_HEIGHT, &error);
    assert_non_null(framebuffer);
    luz_pixel_probe *probe = calloc(1, sizeof *probe);
    assert_non_null(probe);
    *probe = (luz_pixel_probe){.x = 700, .y = 450};
    assert_int_equal(
        luz_renderer_draw(renderer, &frame, framebuffer, &(luz_render_options){.probe = probe},
                          &error),
        0);

    /* The first triangle of the +Z face, vertices 0, 1, 2, drawn first. */
    assert_int_equal(probe->triangle, 1);
    assert_int_equal(probe->draw, 0);
    assert_int_equal(probe->primitive, 0);
    assert_int_equal(probe->clipped_pieces, 0);
    const double corner[3][3] = {{-0.5, -0.5, 0.5}, {0.5, -0.5, 0.5}, {0.5, 0.5, 0.5}};
    const double pi = 3.14159265358979323846;
    const double f = 1.0 / tan(45.0 / 2.0 * pi / 180.0), aspect = 1280.0 / 720.0;
    const double near = 0.1, far = 100.0;
    for (int k = 0; k < 3; k++) {
        assert_int_equal(probe->vertices[k], k);
        /* eye space: the camera's translation only */
        const double x = corner[k][0], y = corner[k][1], z = corner[k][2] - 3.0;
        const double clip[4] = {f / aspect * x, f * y,
                                (far + near) / (near - far) * z + 2 * far * near / (near - far),
                                -z};
        const float *got = &probe->corner_clip[k].x;
        for (int j = 0; j < 4; j++) assert_near(got[j], clip[j], 1e-6 * (1.0 + fabs(clip[j])));
        const double window_x = (clip[0] / clip[3] + 1.0) / 2.0 * TOUR_WIDTH;
        const double window_y = (1.0 - clip[1] / clip[3]) / 2.0 * TOUR_HEIGHT;
        /* setup's snap to the nearest 1/256 pixel */
        assert_near(probe->corner_window[k].x, round(window_x * 256.0) / 256.0, 1e-9);
        assert_near(probe->corner_window[k].y, round(window_y * 256.0) / 256.0, 1e-9);
        assert_near(probe->corner_window[k].z, (clip[2] / clip[3] + 1.0) / 2.0, 1e-6);
    }
    free(probe);
    luz_framebuffer_destroy(framebuffer);
    luz_renderer_destroy(renderer);
    luz_frame_free(&frame);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(each_term_alone),
        cmocka_unit_test(each_filter),
        cmocka_unit_test(magnified_and_reference),
        cmocka_unit_test(affine),
        cmocka_unit_test(clipped_face),
        cmocka_unit_test(overlapping_cubes_and_the_marker),
        cmocka_unit_test(equal_depths_fail),
        cmocka_unit_test(a_model),
        cmocka_unit_test(every_view),
        cmocka_unit_test(outside_the_image),
        cmocka_unit_test(bytes_before_the_hook_in_bgra),
        cmocka_unit_test(only_the_triangles_drawn),
        cmocka_unit_test(the_text),
        cmocka_unit_test(the_tour_pixel),
    };
    return cmocka_run_group_tests(tests, lab_textures_load, lab_textures_free);
}
