/*
 * test_setup_eight.c: setup in lanes, every variant this machine runs
 * (src/renderer/setup_eight.c, setup_lanes.c), against setup one
 * triangle at a time (luz_setup_projected), the implementation the other
 * setup tests derive by hand.
 *
 * Its contract: all eight lanes are left to the caller when one of the
 * triangles has a marked vertex (outside a clip plane, or not projected),
 * and none otherwise; then each lane's result is luz_setup_projected's
 * with small_box_checked (a box of 3 to LUZ_SETUP_SMALL_BOX_PIXELS
 * centres tested for a covered one), and a visible triangle's record is
 * the same bytes: box, edges, reference point and all ten planes, where
 * setup in lanes shades and projects each corner from its mesh vertex
 * itself and luz_setup_projected reads the clip and window vertices
 * luz_vertex_stage_one and luz_setup_project_vertex made of it. Random
 * triangles, most a pixel or two across, some large, some off the
 * viewport, some back faces, with a few vertices marked, a few whose
 * exact window positions lie on a line while their snapped ones do not
 * (a front face whose double-precision determinant is zero), both
 * interpolations; the first pass under an identity model and a
 * projection of ones and zeros (which place each vertex), the second
 * under a turned model and camera, where a term summed in another order
 * or taken from the wrong row shows. (A determinant that is not finite
 * cannot come from
 * projected corners, clamped to 2^16 pixels: setup's check for it is
 * defensive, and so is the lanes'.) Then triangles whose planes' values
 * at the reference point cancel to almost nothing, where the order of
 * each plane's operations shows through the rounding to float.
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

#include "test_support.h"
#include "geometry_support.h"

#include "renderer/cpu.h"
#include "renderer/pipeline.h"

#define WIDTH 40
#define HEIGHT 24

/* A draw: its mesh vertices in object space and its transforms, as
 * setup in lanes reads them, and what the vertex stage and projection
 * make of each vertex one at a time (clip, window, fixed), as setup one
 * at a time reads them. */
typedef struct mesh {
    uint32_t vertex_count, triangle_count;
    luz_vertex *vertices;
    luz_draw_transform transform;
    luz_clip_vertex *clip;
    luz_window_vertex *window;
    luz_fixed_vertex *fixed;
    uint32_t *indices;
} mesh;

static mesh mesh_create(uint32_t vertex_count, uint32_t triangle_count)
{
    mesh m = {vertex_count,
              triangle_count,
              calloc(vertex_count, sizeof(luz_vertex)),
              {0},
              calloc(vertex_count, sizeof(luz_clip_vertex)),
              calloc(vertex_count, sizeof(luz_window_vertex)),
              calloc(vertex_count, sizeof(luz_fixed_vertex)),
              calloc(3 * (size_t)triangle_count, sizeof(uint32_t))};
    assert_true(m.vertices && m.clip && m.window && m.fixed && m.indices);
    m.transform = (luz_draw_transform){m.vertices, luz_mat4_identity(),
                                       luz_mat3_normal_matrix(luz_mat4_identity()),
                                       test_w_from_z()};
    return m;
}

static void mesh_destroy(mesh *m)
{
    free(m->vertices);
    free(m->clip);
    free(m->window);
    free(m->fixed);
    free(m->indices);
}

/* How the vertex pass sees vertex i: its clip vertex (the vertex stage's,
 * but for the outcode, which a test may set: 0 keeps a vertex beyond the
 * guard band, -1 leaves the stage's), window and snapped positions. */
static void project_with(mesh *m, uint32_t i, int outcode)
{
    m->clip[i] = luz_vertex_stage_one(&m->transform, i);
    if (outcode >= 0) m->clip[i].outcode = (unsigned)outcode;
    m->window[i] = luz_setup_project_vertex(&m->clip[i], WIDTH, HEIGHT);
    m->fixed[i] = (luz_fixed_vertex){m->window[i].fixed_x, m->window[i].fixed_y};
}

static void project(mesh *m, uint32_t i)
{
    project_with(m, i, -1);
}

/* Vertex i at clip w, test_vertex_at's, projected. Inside the guard band
 * or not, it is not marked (as if the clipper had made it). */
static void set_vertex_at(mesh *m, uint32_t i, int32_t fixed_x, int32_t fixed_y, float w,
                          uint32_t *random)
{
    m->vertices[i] = test_vertex_at(fixed_x, fixed_y, w, WIDTH, HEIGHT, random);
    project_with(m, i, 0);
}

/* The same at a random w, 1/w from 0.05 to 10. */
static void set_vertex(mesh *m, uint32_t i, int32_t fixed_x, int32_t fixed_y, uint32_t *random)
{
    set_vertex_at(m, i, fixed_x, fixed_y, 1.0f / test_uniform(random, 0.05f, 10.0f), random);
}

/* Triangle t as a front face whose window corners lie exactly on a line,
 * so that setup's determinant (x1 - x0) (y2 - y0) - (x2 - x0) (y1 - y0)
 * is 0 in double, while their snapped positions make a triangle with a
 * pixel centre in its box: setup gets as far as the planes and culls it
 * there. At w = 1 the window position is 20 (x_ndc + 1) and 12 (1 -
 * y_ndc), exact in double, so clip x and y in steps of 2^-13 and 2^-12
 * (0.625 and 0.75 sub-pixel units) keep the corners exactly in line, and
 * snapping rounds them off it. Returns whether a try found one. */
static bool set_collinear_front_face(mesh *m, uint32_t t, uint32_t *random)
{
    const int32_t centre_x = 256 * (int32_t)(2 + test_random(random) % (WIDTH - 4)) + 128;
    const int32_t centre_y = 256 * (int32_t)(2 + test_random(random) % (HEIGHT - 4)) + 128;
    const float step_x = (test_random(random) & 1) ? 0x1p-13f : -0x1p-13f;
    const float step_y = (test_random(random) & 1) ? 0x1p-12f : -0x1p-12f;
    const uint32_t i = 3 * t;
    set_vertex_at(m, i, centre_x, centre_y, 1.0f, random);
    for (uint32_t k = 1; k < 3; k++) {
        set_vertex_at(m, i + k, centre_x, centre_y, 1.0f, random);   /* its normal and uv */
        m->vertices[i + k].position.x = m->vertices[i].position.x + (float)k * step_x;
        m->vertices[i + k].position.y = m->vertices[i].position.y + (float)k * step_y;
        project_with(m, i + k, 0);
    }
    const luz_window_vertex *w = &m->window[i];
    const double determinant =
        (w[1].x - w[0].x) * (w[2].y - w[0].y) - (w[2].x - w[0].x) * (w[1].y - w[0].y);
    const int64_t area = ((int64_t)w[1].fixed_y - w[0].fixed_y) * (w[2].fixed_x - w[0].fixed_x) -
                         ((int64_t)w[1].fixed_x - w[0].fixed_x) * (w[2].fixed_y - w[0].fixed_y);
    if (determinant != 0.0 || area == 0) return false;
    if (area < 0) {   /* the other way round: a front face */
        m->indices[i + 1] = i + 2;
        m->indices[i + 2] = i + 1;
    }
    return true;
}

static bool is_marker(int32_t fixed_x)
{
    return fixed_x == LUZ_WINDOW_CLIPPED || fixed_x == LUZ_WINDOW_INVALID;
}

typedef struct tally {
    int left, visible, culled, offscreen;
} tally;

/* Every group of eight of m's triangles through setup_eight, for pixels
 * of `samples` samples, against luz_setup_projected_samples: trusting
 * screening's test of the small boxes (small_box_checked), as the lanes
 * do, or testing them too where the variant screens itself (the scalar
 * set's, lanes_scalar.c). */
static tally check_groups(const mesh *m, luz_setup_eight_function *setup_eight,
                          bool screens_itself, luz_interpolation interpolation, int samples)
{
    tally count = {0, 0, 0, 0};
    for (uint32_t group = 0; group + 8 <= m->triangle_count; group += 8) {
        uint32_t triangles[8];
        for (int lane = 0; lane < 8; lane++)   /* not in order: any eight */
            triangles[lane] = (group * 5 + (uint32_t)lane * 3) % m->triangle_count;
        luz_triangle out[8];
        luz_setup_result result[8];
        memset(out, 0xA5, sizeof out);
        const bool left = setup_eight(m->indices, triangles, &m->transform, m->fixed, WIDTH,
                                      HEIGHT, 7, interpolation, out, result);
        bool group_marked = false;   /* then the eight are left, else none */
        for (int lane = 0; lane < 8; lane++)
            for (int k = 0; k < 3; k++) {
                const uint32_t vertex = m->indices[3 * (size_t)triangles[lane] + (size_t)k];
                group_marked = group_marked || is_marker(m->fixed[vertex].x);
            }
        if (left != group_marked)
            fail_msg("triangles %u.. %s, their group %s a marked vertex", triangles[0],
                     left ? "left to setup" : "set up in lanes", group_marked ? "has" : "has no");
        if (left) {
            count.left += 8;
            continue;
        }
        for (int lane = 0; lane < 8; lane++) {
            const uint32_t t = triangles[lane];
            const uint32_t *index = &m->indices[3 * (size_t)t];
            luz_triangle expected;
            memset(&expected, 0x5A, sizeof expected);
            const luz_setup_result one = luz_setup_projected_samples(
                &m->clip[index[0]], &m->clip[index[1]], &m->clip[index[2]], &m->window[index[0]],
                &m->window[index[1]], &m->window[index[2]], WIDTH, HEIGHT, 7, interpolation,
                !screens_itself, samples, &expected);
            if (result[lane] != one)
                fail_msg("triangle %u: result %d, setup says %d", t, (int)result[lane], (int)one);
            if (one == LUZ_SETUP_VISIBLE) {
                count.visible++;
                /* Every byte but the primitive, which the caller sets. */
                if (memcmp(&out[lane], &expected, offsetof(luz_triangle, primitive)) != 0)
                    fail_msg("triangle %u: its record differs from setup's", t);
            } else if (one == LUZ_SETUP_CULLED) {
                count.culled++;
            } else {
                count.offscreen++;
            }
        }
    }
    return count;
}

/* check_groups in interpolation mode 0 (perspective) or 1 (affine), its
 * tally printed after label. */
static tally check_mode(const mesh *m, luz_setup_eight_function *setup_eight,
                        bool screens_itself, int mode, int samples, const char *label)
{
    const luz_interpolation interpolation =
        mode ? LUZ_INTERPOLATION_AFFINE : LUZ_INTERPOLATION_PERSPECTIVE;
    const tally count = check_groups(m, setup_eight, screens_itself, interpolation, samples);
    print_message("%s%s, %d sample%s: %d visible, %d culled, %d off screen, %d left to setup\n",
                  label, luz_interpolation_name(interpolation), samples, samples > 1 ? "s" : "",
                  count.visible, count.culled, count.offscreen, count.left);
    return count;
}

/* The record's fields are whole words: comparing its bytes compares its
 * fields (no padding to differ). */
_Static_assert(offsetof(luz_triangle, primitive) + sizeof(uint32_t) == sizeof(luz_triangle),
               "luz_triangle has no padding");

/* The setup in lanes of every instruction set this build and CPU have
 * (AVX-512's setup_eight.c, AVX2's, SSE2's and NEON's setup_lanes.c, the
 * scalar set's lanes_scalar.c), widest first, for pixels of `samples`
 * samples (1: setup_eight, 4: setup_eight_four); returns how many, their
 * names in names and in screens_itself whether each drops what screening
 * would itself (the scalar set's). */
static int setup_variants(luz_setup_eight_function *variants[LUZ_ISA_COUNT],
                          const char *names[LUZ_ISA_COUNT], bool screens_itself[LUZ_ISA_COUNT],
                          int samples)
{
    int count = 0;
    for (int isa = LUZ_ISA_COUNT - 1; isa >= 0; isa--) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        const luz_kernels kernels = luz_kernels_of((luz_isa)isa);
        luz_setup_eight_function *setup_eight =
            samples == 1 ? kernels.setup_eight : kernels.setup_eight_four;
        if (setup_eight == NULL) continue;
        names[count] = luz_isa_name((luz_isa)isa);
        screens_itself[count] = samples == 1 && kernels.setup_eight_screens;
        variants[count++] = setup_eight;
    }
    return count;
}

/* Each variant's tally must equal the first's of its kind (a variant that
 * screens itself also drops the small boxes screening would have); the
 * first's is returned, the widest set's. */
static void same_tally(tally *first, tally *first_screening, int v, bool screens_itself,
                       tally got)
{
    if (v == 0) *first = got;
    tally *same = screens_itself ? first_screening : first;
    if (same->left < 0) *same = got;
    assert_memory_equal(&got, same, sizeof got);
}

/* check_mode for every variant. */
static tally check_mode_all(const mesh *m, int mode, int samples, const char *label)
{
    luz_setup_eight_function *variants[LUZ_ISA_COUNT];
    const char *names[LUZ_ISA_COUNT];
    bool screens_itself[LUZ_ISA_COUNT];
    const int count = setup_variants(variants, names, screens_itself, samples);
    tally first = {0, 0, 0, 0}, first_screening = {-1, 0, 0, 0};
    for (int v = 0; v < count; v++) {
        char labelled[64];
        snprintf(labelled, sizeof labelled, "%s%s, ", label, names[v]);
        same_tally(&first, &first_screening, v, screens_itself[v],
                   check_mode(m, variants[v], screens_itself[v], mode, samples, labelled));
    }
    return first;
}

/* check_groups for every variant. */
static tally check_groups_all(const mesh *m, luz_interpolation interpolation)
{
    luz_setup_eight_function *variants[LUZ_ISA_COUNT];
    const char *names[LUZ_ISA_COUNT];
    bool screens_itself[LUZ_ISA_COUNT];
    const int count = setup_variants(variants, names, screens_itself, 1);
    tally first = {0, 0, 0, 0}, first_screening = {-1, 0, 0, 0};
    for (int v = 0; v < count; v++)
        same_tally(&first, &first_screening, v, screens_itself[v],
                   check_groups(m, variants[v], screens_itself[v], interpolation, 1));
    return first;
}

/* Whether any variant runs here (else the tests skip). */
static bool have_setup_variants(void)
{
    luz_setup_eight_function *variants[LUZ_ISA_COUNT];
    const char *names[LUZ_ISA_COUNT];
    bool screens_itself[LUZ_ISA_COUNT];
    return setup_variants(variants, names, screens_itself, 1) > 0;
}

static void test_lanes_agree_with_setup(void **state)
{
    (void)state;
    if (!have_setup_variants()) {
        print_message("skipped: this build or CPU has no setup in lanes (one by one only)\n");
        skip();
    }
    const uint32_t triangle_count = 30000;
    mesh m = mesh_create(3 * triangle_count, triangle_count);
    uint32_t random = 77;
    for (uint32_t t = 0; t < triangle_count; t++) {
        const uint32_t kind = test_random(&random) % 100;
        const int32_t base_x = (int32_t)(test_random(&random) % (256 * (WIDTH + 8))) - 256 * 4;
        const int32_t base_y = (int32_t)(test_random(&random) % (256 * (HEIGHT + 8))) - 256 * 4;
        /* Corners within a pixel, 2.5 and 12 pixels of a point, and for
         * kinds 90-94 within 200 pixels: a doubled area past 2^31, which
         * setup_lanes.c's 32-bit lanes for near corners (NEAR_EXTENT) must
         * leave to the 64-bit ones. */
        const int32_t reach = kind < 50   ? 256
                              : kind < 80 ? 640
                              : kind >= 90 && kind <= 94 ? 256 * 200
                                                         : 256 * 12;
        for (int k = 0; k < 3; k++) {
            const uint32_t i = 3 * t + (uint32_t)k;
            m.indices[i] = i;
            const uint32_t span = (uint32_t)(2 * reach + 1);
            int32_t x = base_x + (int32_t)(test_random(&random) % span) - reach;
            int32_t y = base_y + (int32_t)(test_random(&random) % span) - reach;
            if (kind == 99) {   /* huge: corners at the fixed-point limit */
                x = (test_random(&random) & 1) ? (1 << 24) : -(1 << 24);
                y = (test_random(&random) & 1) ? (1 << 24) : -(1 << 24);
            }
            set_vertex(&m, i, x, y, &random);
            if (kind == 97 && k == 1) project_with(&m, i, 1);   /* outside a clip plane */
            if (kind == 98 && k == 2) {   /* not projectable */
                m.vertices[i].position.z = -1.0f;   /* w */
                project_with(&m, i, 0);
            }
        }
        if (kind >= 95 && kind <= 96)   /* no plane to solve */
            while (!set_collinear_front_face(&m, t, &random)) continue;
    }
    for (int mode = 0; mode < 2; mode++) {
        const tally count = check_mode_all(&m, mode, 1, "");
        /* Each verdict is seen, often. */
        assert_true(count.visible > 3000);
        assert_true(count.culled > 3000);
        assert_true(count.offscreen > 1000);
        assert_true(count.left > 300);
    }
    /* Four samples a pixel (setup_eight_four): the box and the small
     * boxes' test are the samples', so more triangles are visible and
     * fewer off screen, but still many (a box of 3 to 16 pixels with no
     * sample covered, or none in the viewport). */
    const tally one = check_mode_all(&m, 0, 1, "");
    const tally four = check_mode_all(&m, 0, 4, "");
    assert_true(four.visible > one.visible);
    assert_true(four.offscreen < one.offscreen);
    assert_true(four.offscreen > 500);
    assert_int_equal(four.left, one.left);
    /* The collinear front faces reached the determinant: setup culls each
     * there, not before (some are in groups left to setup). */
    int collinear_culled = 0;
    for (uint32_t t = 0; t < triangle_count; t++) {
        const luz_window_vertex *w = &m.window[3 * t];
        const bool in_line =
            (w[1].x - w[0].x) * (w[2].y - w[0].y) - (w[2].x - w[0].x) * (w[1].y - w[0].y) == 0.0;
        luz_triangle record;
        if (in_line && luz_setup_projected(&m.clip[m.indices[3 * t]], &m.clip[m.indices[3 * t + 1]],
                                           &m.clip[m.indices[3 * t + 2]],
                                           &m.window[m.indices[3 * t]],
                                           &m.window[m.indices[3 * t + 1]],
                                           &m.window[m.indices[3 * t + 2]], WIDTH, HEIGHT, 7,
                                           LUZ_INTERPOLATION_PERSPECTIVE, true,
                                           &record) == LUZ_SETUP_CULLED &&
            luz_setup_front_facing(&m.window[m.indices[3 * t]], &m.window[m.indices[3 * t + 1]],
                                   &m.window[m.indices[3 * t + 2]]))
            collinear_culled++;
    }
    print_message("%d front faces culled for a zero determinant\n", collinear_culled);
    assert_true(collinear_culled > 300);
    /* The same triangles under a model matrix that turns and moves them
     * (and a normal matrix that is not the identity) and a camera turned
     * a little (a projection * view with no zero to hide a term), the
     * outcodes now the vertex stage's own: a transform done differently
     * in lanes, a sum taken in another order, shows here. */
    test_turn(&m.transform);
    for (uint32_t i = 0; i < m.vertex_count; i++) project(&m, i);
    for (int mode = 0; mode < 2; mode++)
        for (int samples = 1; samples <= 4; samples += 3)
            assert_true(check_mode_all(&m, mode, samples, "turned, ").visible > 3000);
    mesh_destroy(&m);
}

/* HAND-MADE: two slivers along the diagonal y = x from (0.4, 0.4) to (2.6,
 * 2.6), one on each side of it, each with a 3 x 3 box of pixel centres
 * (tested in lanes) and no centre but the three on the diagonal, exactly
 * on an edge: for one sliver it is a left edge (dy > 0: the centres are
 * its, VISIBLE), for the other a right edge (OFFSCREEN). */
static void test_centres_on_an_edge(void **state)
{
    (void)state;
    if (!have_setup_variants()) skip();
    mesh m = mesh_create(6, 8);
    uint32_t random = 5;
    const int32_t corners[6][2] = {{102, 102}, {666, 666}, {666, 640},    /* below y = x */
                                   {102, 102}, {666, 666}, {640, 666}};   /* above it */
    for (uint32_t i = 0; i < 6; i++) set_vertex(&m, i, corners[i][0], corners[i][1], &random);
    for (uint32_t t = 0; t < 8; t++) {
        const uint32_t first = 3 * (t % 2);
        /* Counter-clockwise on the screen's y-down axes: a front face. */
        const luz_fixed_vertex *p = &m.fixed[first];
        const int64_t area = ((int64_t)p[1].y - p[0].y) * ((int64_t)p[2].x - p[0].x) -
                             ((int64_t)p[1].x - p[0].x) * ((int64_t)p[2].y - p[0].y);
        const bool swap = area < 0;
        m.indices[3 * t] = first;
        m.indices[3 * t + 1] = first + (swap ? 2 : 1);
        m.indices[3 * t + 2] = first + (swap ? 1 : 2);
    }
    const tally count = check_groups_all(&m, LUZ_INTERPOLATION_PERSPECTIVE);
    assert_int_equal(count.left, 0);
    assert_int_equal(count.visible, 4);
    assert_int_equal(count.offscreen, 4);
    mesh_destroy(&m);
}

/* CANCELLATION: varyings sampled from steep planes f = A (x - rx) + B (y -
 * ry) through each triangle's reference point (its snapped vertex 0), so
 * that setup's value there, v0 + dx (rx - x0) + dy (ry - y0), is the
 * rounding left of terms thousands of times larger: summed in another
 * order, or with a fused multiply-add, it comes out different. */
static void test_planes_that_cancel(void **state)
{
    (void)state;
    if (!have_setup_variants()) skip();
    const uint32_t triangle_count = 4000;
    mesh m = mesh_create(3 * triangle_count, triangle_count);
    uint32_t random = 4242;
    for (uint32_t t = 0; t < triangle_count; t++) {
        /* A front face a pixel or two across, inside the viewport. */
        const int32_t x0 = 256 * 5 + (int32_t)(test_random(&random) % (256 * 30));
        const int32_t y0 = 256 * 5 + (int32_t)(test_random(&random) % (256 * 14));
        const int32_t long_side = 200 + (int32_t)(test_random(&random) % 300);
        const int32_t short_side = (int32_t)(test_random(&random) % 100);
        const int32_t corner[3][2] = {{x0, y0},
                                      {x0 + long_side, y0 + short_side},
                                      {x0 + short_side, y0 + long_side}};
        const uint32_t order[3] = {0, 2, 1};   /* counter-clockwise, y down */
        for (int k = 0; k < 3; k++) {
            const uint32_t i = 3 * t + (uint32_t)k;
            m.indices[i] = i;
            set_vertex_at(&m, i, corner[order[k]][0], corner[order[k]][1], 1.0f, &random);
        }
        const double rx = m.fixed[3 * t].x / (double)LUZ_SUBPIXEL_ONE;
        const double ry = m.fixed[3 * t].y / (double)LUZ_SUBPIXEL_ONE;
        /* The normal and uv are the varyings a mesh vertex sets (with
         * the identity model, the varyings are these floats); the world
         * position is where the vertex is. */
        for (int v = 0; v < 5; v++) {
            const double a = test_uniform(&random, 1000.0f, 30000.0f);
            const double b = test_uniform(&random, -30000.0f, 30000.0f);
            for (int k = 0; k < 3; k++) {
                const uint32_t i = 3 * t + (uint32_t)k;
                const luz_window_vertex *w = &m.window[i];
                float *free_floats[5] = {&m.vertices[i].normal.x, &m.vertices[i].normal.y,
                                         &m.vertices[i].normal.z, &m.vertices[i].uv.x,
                                         &m.vertices[i].uv.y};
                *free_floats[v] = (float)(a * (w->x - rx) + b * (w->y - ry));
            }
        }
        for (uint32_t k = 0; k < 3; k++) project_with(&m, 3 * t + k, 0);
    }
    const tally count = check_groups_all(&m, LUZ_INTERPOLATION_PERSPECTIVE);
    assert_true(count.visible > 3000);
    /* The cancellation happened: values far below their terms. */
    int tiny = 0, planes = 0;
    for (uint32_t t = 0; t < triangle_count; t++) {
        luz_triangle triangle;
        const uint32_t *index = &m.indices[3 * (size_t)t];
        if (luz_setup_projected(&m.clip[index[0]], &m.clip[index[1]], &m.clip[index[2]],
                                &m.window[index[0]], &m.window[index[1]], &m.window[index[2]],
                                WIDTH, HEIGHT, 7, LUZ_INTERPOLATION_PERSPECTIVE, true,
                                &triangle) != LUZ_SETUP_VISIBLE)
            continue;
        planes += LUZ_VARYING_COUNT;
        for (int v = 0; v < LUZ_VARYING_COUNT; v++)
            tiny += fabsf(triangle.varyings[v].value) < 1e-3f &&
                    fabsf(triangle.varyings[v].dx) > 500.0f;
    }
    print_message("%d of %d planes' values cancel to below 1e-3\n", tiny, planes);
    assert_true(tiny > 1000);
    mesh_destroy(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lanes_agree_with_setup),
        cmocka_unit_test(test_centres_on_an_edge),
        cmocka_unit_test(test_planes_that_cancel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
