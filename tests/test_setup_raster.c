/*
 * test_setup_raster.c: triangle setup and rasterisation (src/renderer/
 * setup.c, raster.c) on a 16x16 framebuffer, driven directly with clip
 * vertices placed on exact window coordinates. With w = 1 clip space is
 * NDC, and x_ndc = 2 x_win / 16 - 1, y_ndc = 1 - 2 y_win / 16 (SCENE.md's
 * viewport); every coordinate used is a multiple of 1/2, so it is exact in
 * float and lands on the 1/256 sub-pixel grid without rounding.
 *
 * Pixel (x, y) samples its centre (x + 0.5, y + 0.5); the fill rule is
 * top-left in image coordinates (y down). A triangle is a front face when
 * counter-clockwise in NDC, i.e. clockwise as listed in window coordinates
 * with y down: (0, 0), (0, 1), (1, 0) is a front face.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "renderer/cpu.h"
#include "renderer/pipeline.h"

#define SIZE 16

typedef struct window_point {
    double x, y;
} window_point;

/* The clip-space vertex (w = 1) that lands at window point p of a
 * width x height framebuffer, at depth z_ndc. */
static luz_clip_vertex vertex_in(window_point p, float z_ndc, int width, int height)
{
    luz_clip_vertex vertex;
    memset(&vertex, 0, sizeof vertex);
    vertex.position = (luz_vec4){(float)(2.0 * p.x / width - 1.0),
                                 (float)(1.0 - 2.0 * p.y / height), z_ndc, 1.0f};
    return vertex;
}

static luz_clip_vertex vertex_at(window_point p, float z_ndc)
{
    return vertex_in(p, z_ndc, SIZE, SIZE);
}

/* Four samples' setup of the triangle v, or of its corners the other way
 * round where v is a back face: whether either is visible. */
static bool set_up_either_way(const luz_clip_vertex v[3], int width, int height,
                              luz_triangle *out)
{
    return luz_setup_triangle_samples(&v[0], &v[1], &v[2], width, height, 0,
                                      LUZ_INTERPOLATION_PERSPECTIVE, 4, out) == LUZ_SETUP_VISIBLE ||
           luz_setup_triangle_samples(&v[0], &v[2], &v[1], width, height, 0,
                                      LUZ_INTERPOLATION_PERSPECTIVE, 4, out) == LUZ_SETUP_VISIBLE;
}

static int setup_framebuffer(void **state)
{
    luz_error error;
    luz_framebuffer *framebuffer = luz_framebuffer_create(SIZE, SIZE, &error);
    *state = framebuffer;
    return framebuffer ? 0 : -1;
}

static int teardown_framebuffer(void **state)
{
    luz_framebuffer_destroy(*state);
    return 0;
}

static void clear(luz_framebuffer *framebuffer)
{
    luz_framebuffer_clear_rows(framebuffer, 0, SIZE);
}

static luz_setup_result set_up(window_point a, window_point b, window_point c, float z_ndc,
                               luz_triangle *triangle)
{
    luz_clip_vertex va = vertex_at(a, z_ndc), vb = vertex_at(b, z_ndc), vc = vertex_at(c, z_ndc);
    return luz_setup_triangle(&va, &vb, &vc, SIZE, SIZE, 0, LUZ_INTERPOLATION_PERSPECTIVE,
                              triangle);
}

/* Adds 1 to hits[] at every pixel the triangle covers, found alone in a
 * cleared buffer. */
static void add_coverage(luz_framebuffer *framebuffer, window_point a, window_point b,
                         window_point c, int hits[SIZE * SIZE])
{
    luz_triangle triangle;
    assert_int_equal(set_up(a, b, c, 0.0f, &triangle), LUZ_SETUP_VISIBLE);
    clear(framebuffer);
    luz_raster_triangle(&triangle, 1, framebuffer, 0, SIZE);
    for (int i = 0; i < SIZE * SIZE; i++) hits[i] += framebuffer->visibility[i] == 1;
}

/* THE FILL RULE on a mesh: a rectangle from (2.5, 1.5) to (14.5, 10.5),
 * cut into a 4 x 3 grid of 3x3-pixel quads, each split into two triangles
 * along a diagonal that alternates from quad to quad, and each triangle
 * listed from a different starting vertex. Every vertex and every shared
 * edge (horizontal, vertical, both diagonals) runs through pixel centres.
 * The rectangle's left and top sides are left and top edges, its right
 * and bottom sides are not, so the pixels covered are exactly those with
 * centres in [2.5, 14.5) x [1.5, 10.5): x = 2..13, y = 1..9, each once. */
static void test_fill_rule_tiles_a_rectangle_exactly_once(void **state)
{
    luz_framebuffer *framebuffer = *state;
    int hits[SIZE * SIZE] = {0};
    for (int row = 0; row < 3; row++) {
        for (int column = 0; column < 4; column++) {
            double x0 = 2.5 + 3 * column, x1 = x0 + 3, y0 = 1.5 + 3 * row, y1 = y0 + 3;
            window_point top_left = {x0, y0}, top_right = {x1, y0};
            window_point bottom_left = {x0, y1}, bottom_right = {x1, y1};
            /* Front faces, clockwise in window coordinates. */
            const window_point split_top_left_to_bottom_right[2][3] = {
                {top_left, bottom_left, bottom_right}, {top_left, bottom_right, top_right}};
            const window_point split_bottom_left_to_top_right[2][3] = {
                {top_left, bottom_left, top_right}, {bottom_left, bottom_right, top_right}};
            const window_point(*triangles)[3] = (row + column) % 2 == 0
                                                     ? split_top_left_to_bottom_right
                                                     : split_bottom_left_to_top_right;
            for (int t = 0; t < 2; t++) {
                int first = (row + 2 * column + t) % 3;
                add_coverage(framebuffer, triangles[t][first], triangles[t][(first + 1) % 3],
                             triangles[t][(first + 2) % 3], hits);
            }
        }
    }
    for (int y = 0; y < SIZE; y++) {
        for (int x = 0; x < SIZE; x++) {
            int expected = x >= 2 && x <= 13 && y >= 1 && y <= 9;
            if (hits[y * SIZE + x] != expected)
                fail_msg("pixel (%d, %d) covered %d times, expected %d", x, y,
                         hits[y * SIZE + x], expected);
        }
    }
}

/* THE FILL RULE on a fan: eight triangles around (8.5, 8.5) to a convex
 * rim of vertices at whole-pixel offsets from it, so the eight shared
 * edges (slopes 0, -1/2, -5/3, 5/2, 1/3, -1/2, -6, 5/4) and the rim pass
 * through many pixel centres. Expected, from the polygon alone: a centre
 * strictly inside is covered once, one strictly outside never; one on the
 * rim is covered only if every rim edge through it is a left edge
 * (interior at larger x: it runs downwards, dy > 0, in window
 * coordinates) or a top edge (horizontal with the interior below: it runs
 * right to left, dx < 0), as SCENE.md's rule says. The rim is listed in the
 * front-face order (clockwise in window coordinates), so inside means
 * cross(edge, point - start) < 0 for every edge. */
static void test_fill_rule_on_a_fan(void **state)
{
    luz_framebuffer *framebuffer = *state;
    enum { RIM = 8 };
    const int rim[RIM][2] = {{6, 0}, {6, -3}, {3, -5}, {-2, -5},
                             {-6, -2}, {-6, 3}, {-1, 6}, {4, 5}};
    const window_point centre = {8.5, 8.5};
    int hits[SIZE * SIZE] = {0};
    for (int k = 0; k < RIM; k++) {
        window_point a = {centre.x + rim[k][0], centre.y + rim[k][1]};
        window_point b = {centre.x + rim[(k + 1) % RIM][0], centre.y + rim[(k + 1) % RIM][1]};
        add_coverage(framebuffer, centre, a, b, hits);
    }
    int inside_count = 0;
    for (int y = 0; y < SIZE; y++) {
        for (int x = 0; x < SIZE; x++) {
            /* The pixel centre as a whole-number offset from the centre. */
            int px = x - 8, py = y - 8;
            bool outside = false, excluded_by_rule = false;
            for (int k = 0; k < RIM; k++) {
                int sx = rim[k][0], sy = rim[k][1];
                int ex = rim[(k + 1) % RIM][0] - sx, ey = rim[(k + 1) % RIM][1] - sy;
                int cross = ex * (py - sy) - ey * (px - sx);
                if (cross > 0) outside = true;
                bool top_or_left = ey > 0 || (ey == 0 && ex < 0);
                if (cross == 0 && !top_or_left) excluded_by_rule = true;
            }
            int expected = !outside && !excluded_by_rule;
            inside_count += expected;
            if (hits[y * SIZE + x] != expected)
                fail_msg("pixel (%d, %d) covered %d times, expected %d", x, y,
                         hits[y * SIZE + x], expected);
        }
    }
    assert_true(inside_count > 100);   /* the fan is not trivially small */
}

/* Covered pixels of one triangle in a row or a column. */
static int covered_in_row(const luz_framebuffer *framebuffer, int y, int x_first, int x_last)
{
    int count = 0;
    for (int x = x_first; x <= x_last; x++) count += framebuffer->visibility[y * SIZE + x] != 0;
    return count;
}

static void raster_alone(luz_framebuffer *framebuffer, window_point a, window_point b,
                         window_point c)
{
    luz_triangle triangle;
    assert_int_equal(set_up(a, b, c, 0.0f, &triangle), LUZ_SETUP_VISIBLE);
    clear(framebuffer);
    luz_raster_triangle(&triangle, 1, framebuffer, 0, SIZE);
}

/* Top edge against bottom edge on the row of centres y = 4.5:
 * A = (2.5, 4.5), (6.5, 10.5), (10.5, 4.5) has it as its top edge; its
 * vertex (2.5, 4.5) also lies on a left edge (in), its vertex (10.5, 4.5)
 * on a right edge (out), so row 4 has x = 2..9 covered.
 * B = (2.5, 4.5), (10.5, 4.5), (6.5, 0.5) has it as its bottom edge:
 * nothing of row 4. Together, row 4 is covered once. */
static void test_top_edge_in_bottom_edge_out(void **state)
{
    luz_framebuffer *framebuffer = *state;
    raster_alone(framebuffer, (window_point){2.5, 4.5}, (window_point){6.5, 10.5},
                 (window_point){10.5, 4.5});
    assert_int_equal(covered_in_row(framebuffer, 4, 0, SIZE - 1), 8);
    assert_int_equal(covered_in_row(framebuffer, 4, 2, 9), 8);

    raster_alone(framebuffer, (window_point){2.5, 4.5}, (window_point){10.5, 4.5},
                 (window_point){6.5, 0.5});
    assert_int_equal(covered_in_row(framebuffer, 4, 0, SIZE - 1), 0);
    assert_int_equal(covered_in_row(framebuffer, 3, 0, SIZE - 1), 6);   /* 3.5..8.5 */
}

/* Left edge against right edge on the column of centres x = 6.5:
 * L = (6.5, 2.5), (2.5, 6.5), (6.5, 10.5) has it as its right edge: none
 * of column 6. R = (6.5, 2.5), (6.5, 10.5), (10.5, 6.5) has it as its left
 * edge: rows 3..9 of column 6; rows 2 and 10 are its vertices, which also
 * lie on R's right-hand edges, so they stay out. */
static void test_left_edge_in_right_edge_out(void **state)
{
    luz_framebuffer *framebuffer = *state;
    raster_alone(framebuffer, (window_point){6.5, 2.5}, (window_point){2.5, 6.5},
                 (window_point){6.5, 10.5});
    for (int y = 0; y < SIZE; y++) assert_int_equal(framebuffer->visibility[y * SIZE + 6], 0);
    assert_int_equal(framebuffer->visibility[6 * SIZE + 5], 1);

    raster_alone(framebuffer, (window_point){6.5, 2.5}, (window_point){6.5, 10.5},
                 (window_point){10.5, 6.5});
    for (int y = 0; y < SIZE; y++)
        assert_int_equal(framebuffer->visibility[y * SIZE + 6], y >= 3 && y <= 9 ? 1 : 0);
}

/* Culling: the clockwise (in NDC) order of a front face is a back face;
 * three collinear vertices have zero area; both are CULLED. A tiny front
 * face between pixel centres, (1, 1), (1, 1.4), (1.4, 1), and one right of
 * the viewport cover no centre: OFFSCREEN. */
static void test_back_faces_and_degenerate_triangles_are_culled(void **state)
{
    (void)state;
    luz_triangle triangle;
    const window_point a = {2.5, 4.5}, b = {6.5, 10.5}, c = {10.5, 4.5};
    assert_int_equal(set_up(a, b, c, 0.0f, &triangle), LUZ_SETUP_VISIBLE);
    assert_int_equal(set_up(a, c, b, 0.0f, &triangle), LUZ_SETUP_CULLED);
    assert_int_equal(set_up((window_point){2.5, 2.5}, (window_point){6.5, 6.5},
                            (window_point){10.5, 10.5}, 0.0f, &triangle),
                     LUZ_SETUP_CULLED);
    assert_int_equal(set_up((window_point){1, 1}, (window_point){1, 1.4}, (window_point){1.4, 1},
                            0.0f, &triangle),
                     LUZ_SETUP_OFFSCREEN);
    assert_int_equal(set_up((window_point){20, 2}, (window_point){20, 8}, (window_point){26, 2},
                            0.0f, &triangle),
                     LUZ_SETUP_OFFSCREEN);
}

/* The front face (0, 0), (0, 16), (16, 0) covers the centres with
 * x + y + 1 < 16 (its hypotenuse is a right edge, so centres on it, where
 * x + y = 15, stay out): x + y <= 14, 1 + 2 + ... + 15 = 120 pixels. */
static const window_point big_a = {0, 0}, big_b = {0, 16}, big_c = {16, 0};
#define BIG_TRIANGLE_PIXELS 120

static void raster_big(luz_framebuffer *framebuffer, float z_ndc, uint32_t id)
{
    luz_triangle triangle;
    assert_int_equal(set_up(big_a, big_b, big_c, z_ndc, &triangle), LUZ_SETUP_VISIBLE);
    assert_int_equal(luz_raster_triangle(&triangle, id, framebuffer, 0, SIZE),
                     BIG_TRIANGLE_PIXELS);
}

static int count_id(const luz_framebuffer *framebuffer, uint32_t id)
{
    int count = 0;
    for (int i = 0; i < SIZE * SIZE; i++) count += framebuffer->visibility[i] == id;
    return count;
}

/* The depth test is LESS: of two triangles over the same pixels, at
 * z_ndc 0.2 (depth 0.6, id 1) and -0.4 (depth 0.3, id 2), the nearer one,
 * id 2, wins in either draw order, and the depth buffer holds 0.3. At equal
 * depth the first one drawn stays (LEQUAL would let the second win). */
static void test_depth_test_less(void **state)
{
    luz_framebuffer *framebuffer = *state;
    clear(framebuffer);
    raster_big(framebuffer, 0.2f, 1);
    raster_big(framebuffer, -0.4f, 2);
    assert_int_equal(count_id(framebuffer, 2), BIG_TRIANGLE_PIXELS);
    assert_true(fabsf(framebuffer->depth[3 * SIZE + 3] - 0.3f) < 1e-6f);

    clear(framebuffer);
    raster_big(framebuffer, -0.4f, 2);
    raster_big(framebuffer, 0.2f, 1);
    assert_int_equal(count_id(framebuffer, 2), BIG_TRIANGLE_PIXELS);

    clear(framebuffer);
    raster_big(framebuffer, 0.2f, 1);
    raster_big(framebuffer, 0.2f, 2);
    assert_int_equal(count_id(framebuffer, 1), BIG_TRIANGLE_PIXELS);
}

/* Depth = (z_ndc + 1) / 2, affine on the screen. With z_ndc -1, 0 and 1 at
 * (0, 0), (0, 16) and (16, 0), depth = x / 16 + y / 32: at the centre of
 * pixel (3, 5), 3.5 / 16 + 5.5 / 32 = 0.390625; of (10, 2),
 * 10.5 / 16 + 2.5 / 32 = 0.734375; of (0, 0), 0.5 / 16 + 0.5 / 32 =
 * 0.046875. */
static void test_depth_is_interpolated_linearly(void **state)
{
    luz_framebuffer *framebuffer = *state;
    luz_clip_vertex a = vertex_at(big_a, -1.0f), b = vertex_at(big_b, 0.0f);
    luz_clip_vertex c = vertex_at(big_c, 1.0f);
    luz_triangle triangle;
    assert_int_equal(luz_setup_triangle(&a, &b, &c, SIZE, SIZE, 0, LUZ_INTERPOLATION_PERSPECTIVE,
                                        &triangle),
                     LUZ_SETUP_VISIBLE);
    clear(framebuffer);
    luz_raster_triangle(&triangle, 7, framebuffer, 0, SIZE);
    assert_int_equal(framebuffer->visibility[5 * SIZE + 3], 7);
    assert_true(fabsf(framebuffer->depth[5 * SIZE + 3] - 0.390625f) < 1e-6f);
    assert_true(fabsf(framebuffer->depth[2 * SIZE + 10] - 0.734375f) < 1e-6f);
    assert_true(fabsf(framebuffer->depth[0] - 0.046875f) < 1e-6f);
}

/* Rasterising in bands of rows (as the threads do) covers the same pixels
 * with the same depths as one pass over all rows. */
static void test_bands_match_one_pass(void **state)
{
    luz_framebuffer *framebuffer = *state;
    luz_clip_vertex a = vertex_at((window_point){1.3, 0.7}, -0.5f);
    luz_clip_vertex b = vertex_at((window_point){4.1, 15.2}, 0.3f);
    luz_clip_vertex c = vertex_at((window_point){14.9, 6.6}, 0.8f);
    luz_triangle triangle;
    assert_int_equal(luz_setup_triangle(&a, &b, &c, SIZE, SIZE, 0, LUZ_INTERPOLATION_PERSPECTIVE,
                                        &triangle),
                     LUZ_SETUP_VISIBLE);
    clear(framebuffer);
    luz_raster_triangle(&triangle, 1, framebuffer, 0, SIZE);
    float depth[SIZE * SIZE];
    uint32_t visibility[SIZE * SIZE];
    memcpy(depth, framebuffer->depth, sizeof depth);
    memcpy(visibility, framebuffer->visibility, sizeof visibility);

    clear(framebuffer);
    const int band_starts[4] = {0, 5, 6, 11};
    for (int band = 0; band < 4; band++) {
        int end = band < 3 ? band_starts[band + 1] : SIZE;
        luz_raster_triangle(&triangle, 1, framebuffer, band_starts[band], end);
    }
    assert_memory_equal(visibility, framebuffer->visibility, sizeof visibility);
    assert_memory_equal(depth, framebuffer->depth, sizeof depth);
    assert_true(count_id(framebuffer, 1) > 50);
}

/* Small triangles, which setup drops when they cover no pixel centre
 * (before solving their planes), against the fill rule written out from
 * its definition: random front faces with corners on the 1/256 sub-pixel
 * grid, up to 3 pixels across, their covered centres counted in exact
 * double arithmetic. Setup says OFFSCREEN exactly when that count is 0,
 * and otherwise the rasteriser covers exactly those centres. Among them
 * the split square of a pixel whose centre lies on the diagonal: one half
 * has it, the other none. */
static int centres_covered(const double x[3], const double y[3], int pixels[SIZE * SIZE])
{
    int count = 0;
    for (int py = 0; py < SIZE; py++)
        for (int px = 0; px < SIZE; px++) {
            const double sx = px + 0.5, sy = py + 0.5;
            bool inside = true;
            for (int k = 0; k < 3; k++) {
                /* Edge k runs from corner k+1 to corner k+2. */
                const int i = (k + 1) % 3, j = (k + 2) % 3;
                const double dx = x[j] - x[i], dy = y[j] - y[i];
                const double e = dy * (sx - x[i]) - dx * (sy - y[i]);
                const bool top = dy == 0 && dx < 0, left = dy > 0;
                inside = inside && (e > 0 || (e == 0 && (top || left)));
            }
            pixels[py * SIZE + px] = inside;
            count += inside;
        }
    return count;
}

/* Small triangles: those that cover no pixel centre are dropped; the
 * others rasterise to exactly the centres they cover, and their box is
 * the pixels whose centres lie within the corners' ranges, or the one
 * pixel whose centre a triangle of a box of up to 2 x 2 covers alone. */
static void test_small_triangles_covering_no_centre_are_dropped(void **state)
{
    luz_framebuffer *framebuffer = *state;
    luz_triangle triangle;
    /* The pixel (1, 1) square split along x + y = 3, through its centre:
     * the diagonal is the lower triangle's left edge... */
    assert_int_equal(set_up((window_point){1, 2}, (window_point){2, 2}, (window_point){2, 1}, 0.0f,
                            &triangle),
                     LUZ_SETUP_VISIBLE);
    /* ... and the upper one's right edge: no centre. */
    assert_int_equal(set_up((window_point){1, 1}, (window_point){1, 2}, (window_point){2, 1}, 0.0f,
                            &triangle),
                     LUZ_SETUP_OFFSCREEN);

    uint32_t random = 12345;
    int dropped = 0, kept = 0, points = 0, wider = 0;
    for (int n = 0; n < 4000; n++) {
        double x[3], y[3];
        const unsigned span = (unsigned)(n % 3 + 1);   /* pixels across, at most */
        for (int k = 0; k < 3; k++) {
            random = random * 1664525u + 1013904223u;
            x[k] = 4.0 + (double)((random >> 8) % (256u * span + 1)) / 256.0;
            random = random * 1664525u + 1013904223u;
            y[k] = 4.0 + (double)((random >> 8) % (256u * span + 1)) / 256.0;
        }
        /* Front faces only: positive doubled area as setup measures it. */
        double area = (y[1] - y[0]) * (x[2] - x[0]) - (x[1] - x[0]) * (y[2] - y[0]);
        if (area == 0) continue;
        if (area < 0) {
            double t = x[1]; x[1] = x[2]; x[2] = t;
            t = y[1]; y[1] = y[2]; y[2] = t;
        }
        int expected[SIZE * SIZE];
        const int count = centres_covered(x, y, expected);
        luz_setup_result result = set_up((window_point){x[0], y[0]}, (window_point){x[1], y[1]},
                                         (window_point){x[2], y[2]}, 0.0f, &triangle);
        if (count == 0) {
            assert_int_equal(result, LUZ_SETUP_OFFSCREEN);
            dropped++;
            continue;
        }
        assert_int_equal(result, LUZ_SETUP_VISIBLE);
        kept++;
        /* The box: the pixels whose centres lie within the corners' x
         * and y ranges, or, when that holds up to 2 x 2 pixels and the
         * triangle covers one centre alone, that pixel (setup's points,
         * which the raster tests at one centre). */
        double low_x = x[0], high_x = x[0], low_y = y[0], high_y = y[0];
        for (int k = 1; k < 3; k++) {
            low_x = fmin(low_x, x[k]), high_x = fmax(high_x, x[k]);
            low_y = fmin(low_y, y[k]), high_y = fmax(high_y, y[k]);
        }
        int box[4] = {(int)ceil(low_x - 0.5), (int)ceil(low_y - 0.5), (int)floor(high_x - 0.5),
                      (int)floor(high_y - 0.5)};
        if (count == 1 && box[2] - box[0] <= 1 && box[3] - box[1] <= 1) {
            for (int i = 0; i < SIZE * SIZE; i++)
                if (expected[i]) box[0] = box[2] = i % SIZE, box[1] = box[3] = i / SIZE;
            points++;
        } else if (box[2] - box[0] <= 1 && box[3] - box[1] <= 1 && box[2] > box[0]) {
            wider++;   /* two or more centres of a small box: kept whole */
        }
        assert_int_equal(triangle.min_x, box[0]);
        assert_int_equal(triangle.min_y, box[1]);
        assert_int_equal(triangle.max_x, box[2]);
        assert_int_equal(triangle.max_y, box[3]);
        clear(framebuffer);
        assert_int_equal(luz_raster_triangle(&triangle, 1, framebuffer, 0, SIZE), count);
        for (int i = 0; i < SIZE * SIZE; i++)
            assert_int_equal(framebuffer->visibility[i] == 1, expected[i]);
    }
    /* Both outcomes are exercised many times. */
    assert_true(dropped > 500);
    assert_true(kept > 500);
    assert_true(points > 200);
    assert_true(wider > 50);
}

/* ---- four samples a pixel, in lanes (raster_lanes.c) -------------------- */

/* The definition, sample by sample: SCENE.md's four positions, each
 * sample inside when E = a X + b Y + c >= 0 for the three edges at its
 * sub-pixel point (X = 256 x + sx, Y = 256 y + sy, exact integers), its
 * depth the plane's value there in luz_raster_sample_depth's float
 * operations, LESS. Returns the tests made. */
static uint64_t four_samples_by_definition(const luz_triangle *t, uint32_t id, int width,
                                           int height, float *depth, uint32_t *visibility)
{
    static const int sample_x[4] = {96, 224, 32, 160}, sample_y[4] = {32, 96, 160, 224};
    uint64_t tests = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int s = 0; s < 4; s++) {
                const int64_t X = 256 * (int64_t)x + sample_x[s], Y = 256 * (int64_t)y + sample_y[s];
                bool inside = true;
                for (int k = 0; k < 3; k++)
                    if ((int64_t)t->edges[k].a * X + (int64_t)t->edges[k].b * Y + t->edges[k].c < 0)
                        inside = false;
                if (!inside) continue;
                const float row = t->depth.value +
                                  t->depth.dy * ((float)y + sample_y[s] / 256.0f - t->reference_y);
                const float z =
                    row + t->depth.dx * ((float)x + sample_x[s] / 256.0f - t->reference_x);
                const size_t at = ((size_t)y * width + (size_t)x) * 4 + (size_t)s;
                tests++;
                if (z < depth[at]) {
                    depth[at] = z;
                    visibility[at] = id;
                }
            }
    return tests;
}

/* A window coordinate in [low, high), on the 1/256 grid. */
static double random_coordinate(unsigned *seed, double low, double high)
{
    *seed = *seed * 1103515245u + 12345u;
    const double unit = (double)((*seed >> 8) & 0xffff) / 65536.0;
    return floor((low + unit * (high - low)) * 256.0) / 256.0;
}

/* Every instruction set's lanes give the definition's depths, winners and
 * test counts, bit for bit, on overlapping triangles of every kind: pixel
 * sized (the 32-bit edges), large (the spans), tall and thin (a small box
 * whose edges pass 2^30: the spans again), vertices off the viewport,
 * widths that are not a multiple of four (the group moved left at the
 * row's end), drawn in bands of 16 rows as frame.c does: a triangle at a
 * time (luz_raster_triangle_samples), and each band's list of them in one
 * call (the set's list kernel) into buffers of their own. */
static void test_four_samples_in_lanes_match_the_definition(void **state)
{
    (void)state;
    const int sizes[][2] = {{4, 9}, {5, 40}, {13, 2100}, {37, 29}, {64, 64}};
    for (int isa = LUZ_ISA_SCALAR; isa < LUZ_ISA_COUNT; isa++) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        luz_raster_groups_function *groups = luz_kernels_of((luz_isa)isa).raster_groups;
        luz_raster_list_function *list = luz_kernels_of((luz_isa)isa).raster_list;
        for (size_t size = 0; size < sizeof sizes / sizeof sizes[0]; size++) {
            const int width = sizes[size][0], height = sizes[size][1];
            const size_t count = (size_t)width * height * 4;
            float *depth = malloc(count * sizeof *depth), *expected_depth = malloc(count * sizeof *depth);
            uint32_t *ids = calloc(count, sizeof *ids), *expected_ids = calloc(count, sizeof *ids);
            assert_non_null(depth);
            assert_non_null(expected_depth);
            assert_non_null(ids);
            assert_non_null(expected_ids);
            for (size_t i = 0; i < count; i++) depth[i] = expected_depth[i] = 1.0f;
            luz_sample_buffers buffers = {.samples = 4, .width = width, .height = height,
                                          .depth = depth, .visibility = ids};
            /* The drawn triangles by id, and their ids in order: the list. */
            luz_triangle *stored = calloc(301, sizeof *stored);
            const luz_triangle **by_id = calloc(301, sizeof *by_id);
            uint32_t drawn_ids[300];
            uint64_t expected_tests = 0;
            assert_true(stored && by_id);
            unsigned seed = 2026u + (unsigned)size;
            int drawn = 0, small_tall = 0;
            for (uint32_t id = 1; id <= 300; id++) {
                /* A centre, and corners around it at the kind's reach. */
                const int kind = (int)(id % 4);
                const double cx = random_coordinate(&seed, -2.0, width + 2.0);
                const double cy = random_coordinate(&seed, -2.0, height + 2.0);
                const double reach_x = kind == 0 ? 1.5 : kind == 1 ? 0.6 : kind == 2 ? width : 3.0;
                const double reach_y = kind == 0 ? 1.5 : kind == 1 ? 0.6 : kind == 2 ? height : height;
                luz_clip_vertex v[3];
                for (int j = 0; j < 3; j++) {
                    const double x = cx + random_coordinate(&seed, -reach_x, reach_x);
                    const double y = cy + random_coordinate(&seed, -reach_y, reach_y);
                    v[j] = vertex_in((window_point){x, y},
                                     (float)random_coordinate(&seed, -0.9, 0.9), width, height);
                }
                luz_triangle triangle;
                if (!set_up_either_way(v, width, height, &triangle)) continue;
                drawn++;
                small_tall += kind == 3 && luz_raster_is_small(&triangle) &&
                              triangle.max_y - triangle.min_y > 1500;
                uint64_t tests = 0;
                for (int band = 0; band < height; band += 16)
                    tests += luz_raster_triangle_samples(&triangle, id, &buffers, band,
                                                         band + 16 < height ? band + 16 : height,
                                                         NULL, groups);
                const uint64_t defined = four_samples_by_definition(&triangle, id, width, height,
                                                                    expected_depth, expected_ids);
                assert_int_equal(tests, defined);
                expected_tests += defined;
                stored[id] = triangle;
                by_id[id] = &stored[id];
                drawn_ids[drawn - 1] = id;
            }
            assert_true(drawn > 100);
            if (list != NULL && width >= LUZ_RASTER_GROUP_PIXELS) {
                float *list_depth = malloc(count * sizeof *list_depth);
                uint32_t *list_ids = calloc(count, sizeof *list_ids);
                assert_true(list_depth && list_ids);
                for (size_t i = 0; i < count; i++) list_depth[i] = 1.0f;
                luz_sample_buffers list_buffers = {.samples = 4, .width = width,
                                                   .height = height, .depth = list_depth,
                                                   .visibility = list_ids};
                uint64_t list_tests = 0;
                for (int band = 0; band < height; band += 16)
                    list_tests += list(by_id, drawn_ids, 0, (size_t)drawn, &list_buffers, band,
                                       band + 16 < height ? band + 16 : height);
                assert_int_equal(list_tests, expected_tests);
                assert_memory_equal(list_depth, expected_depth, count * sizeof *list_depth);
                assert_memory_equal(list_ids, expected_ids, count * sizeof *list_ids);
                free(list_depth);
                free(list_ids);
            }
            free(stored);
            free(by_id);
            if (height > 2000) assert_true(small_tall > 0);
            assert_memory_equal(depth, expected_depth, count * sizeof *depth);
            assert_memory_equal(ids, expected_ids, count * sizeof *ids);
            free(depth);
            free(expected_depth);
            free(ids);
            free(expected_ids);
        }
    }
}

/* Which corners of the box raster_lanes.c checks (edges_fit_32_bits:
 * the sample points the kernel's groups of rows may test, from 3 pixels
 * left of min_x to the right of max_x + 3, rows min_y to max_y) have an
 * edge with |E| >= limit there: bit 0 top left, 1 top right, 2 bottom
 * left, 3 bottom right. */
static unsigned corners_past(const luz_triangle *t, int64_t limit)
{
    const int64_t x[2] = {((int64_t)t->min_x - 3) * 256, ((int64_t)t->max_x + 4) * 256};
    const int64_t y[2] = {(int64_t)t->min_y * 256, ((int64_t)t->max_y + 1) * 256};
    unsigned corners = 0;
    for (int corner = 0; corner < 4; corner++)
        for (int k = 0; k < 3; k++) {
            const int64_t e = (int64_t)t->edges[k].a * x[corner & 1] +
                              (int64_t)t->edges[k].b * y[corner >> 1] + t->edges[k].c;
            if (e >= limit || e <= -limit) corners |= 1u << corner;
        }
    return corners;
}

/* Whether a sample of a pixel in the triangle's box is inside by E in 64
 * bits and not by E wrapped to 32 bits, or the other way round: where
 * 32-bit edges would go wrong. */
static bool wraps_in_box(const luz_triangle *t)
{
    static const int sample_x[4] = {96, 224, 32, 160}, sample_y[4] = {32, 96, 160, 224};
    for (int y = t->min_y; y <= t->max_y; y++)
        for (int x = t->min_x; x <= t->max_x; x++)
            for (int s = 0; s < 4; s++) {
                const int64_t X = 256 * (int64_t)x + sample_x[s];
                const int64_t Y = 256 * (int64_t)y + sample_y[s];
                bool inside = true, inside_wrapped = true;
                for (int k = 0; k < 3; k++) {
                    const int64_t e =
                        (int64_t)t->edges[k].a * X + (int64_t)t->edges[k].b * Y + t->edges[k].c;
                    inside &= e >= 0;
                    inside_wrapped &= (int32_t)(uint32_t)(uint64_t)e >= 0;
                }
                if (inside != inside_wrapped) return true;
            }
    return false;
}

/* The kernel's 32-bit edges are exact only while |E| < 2^31 wherever it
 * tests a sample, which its 2^30 check on the four corners of a box 3
 * pixels wider on each side makes sure of. Tall thin triangles (vertices
 * at random on the 1/256 grid around a frame of 16 x 4400 pixels) whose
 * edges pass 2^30 at one corner of that box alone and whose 32-bit edges
 * would go wrong somewhere in it, one for each corner (they lie against
 * a side of the frame, where the wider box's corner is outside it),
 * drawn under every instruction set against the definition. With any one
 * corner left out of the check the lanes take the 32-bit edges for that
 * corner's triangle, and the test fails. */
static void test_four_samples_edges_past_2_30_at_one_corner(void **state)
{
    (void)state;
    enum { WIDTH = 16, HEIGHT = 4400 };
    const size_t count = (size_t)WIDTH * HEIGHT * 4;
    luz_triangle found[4];
    unsigned corners_found = 0;
    unsigned seed = 230u;
    for (int attempt = 0; attempt < 2000000 && corners_found != 15u; attempt++) {
        luz_clip_vertex v[3];
        for (int j = 0; j < 3; j++) {
            const double x = random_coordinate(&seed, -24.0, WIDTH + 24.0);
            const double y = random_coordinate(&seed, -400.0, HEIGHT + 400.0);
            v[j] = vertex_in((window_point){x, y}, (float)random_coordinate(&seed, -0.9, 0.9),
                             WIDTH, HEIGHT);
        }
        luz_triangle triangle;
        if (!set_up_either_way(v, WIDTH, HEIGHT, &triangle)) continue;
        if (!luz_raster_is_small(&triangle)) continue;
        const unsigned past = corners_past(&triangle, (int64_t)1 << 30);
        if (past == 0 || (past & (past - 1)) != 0 || (corners_found & past) != 0) continue;
        if (!wraps_in_box(&triangle)) continue;
        found[__builtin_ctz(past)] = triangle;
        corners_found |= past;
    }
    assert_int_equal(corners_found, 15u);

    float *depth = malloc(count * sizeof *depth), *expected_depth = malloc(count * sizeof *depth);
    uint32_t *ids = malloc(count * sizeof *ids), *expected_ids = malloc(count * sizeof *ids);
    assert_true(depth && expected_depth && ids && expected_ids);
    for (int isa = LUZ_ISA_SCALAR; isa < LUZ_ISA_COUNT; isa++) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        luz_raster_groups_function *groups = luz_kernels_of((luz_isa)isa).raster_groups;
        for (int t = 0; t < 4; t++) {
            for (size_t i = 0; i < count; i++) {
                depth[i] = expected_depth[i] = 1.0f;
                ids[i] = expected_ids[i] = 0;
            }
            luz_sample_buffers buffers = {.samples = 4, .width = WIDTH, .height = HEIGHT,
                                          .depth = depth, .visibility = ids};
            uint64_t tests = 0;
            for (int band = 0; band < HEIGHT; band += 16)
                tests += luz_raster_triangle_samples(&found[t], 1, &buffers, band, band + 16,
                                                     NULL, groups);
            assert_int_equal(tests, four_samples_by_definition(&found[t], 1, WIDTH, HEIGHT,
                                                               expected_depth, expected_ids));
            assert_memory_equal(ids, expected_ids, count * sizeof *ids);
            assert_memory_equal(depth, expected_depth, count * sizeof *depth);
        }
    }
    free(depth);
    free(expected_depth);
    free(ids);
    free(expected_ids);
}

/* raster_lanes.c's shortcut before its corner check: a triangle whose
 * edges all have |a|, |b| below 2^14 has |E| below 2^29 + 2^25 over the
 * box the corners bound (its proof: the box lies within the samples'
 * reach of the corners' box). Triangles up to 64 pixels across, many
 * with corners off a 40 x 40 viewport (clamped boxes), under four
 * samples' setup: every one that passes the shortcut stays below the
 * bound at all four corners, and the largest |E| comes within a factor
 * of four of it (the bound is not loose enough to hide a wrong proof).
 * This checks the proof, with its own copy of the shortcut's condition:
 * edges_fit_32_bits itself is static in raster_lanes.c, and a wrong
 * threshold there shows only where it lets an edge past 2^30, in the list
 * kernel's comparison with the definition (today's review: raising the
 * threshold to 2^16 leaves this suite green, since no triangle that
 * reaches the shortcut is that long). */
static void test_four_samples_short_edges_fit_32_bits(void **state)
{
    (void)state;
    enum { WIDTH = 40, HEIGHT = 40 };
    const int64_t bound = ((int64_t)1 << 29) + ((int64_t)1 << 25);
    unsigned seed = 1414u;
    int checked = 0;
    int64_t largest = 0;
    for (int attempt = 0; attempt < 200000; attempt++) {
        luz_clip_vertex v[3];
        const double cx = random_coordinate(&seed, -40.0, WIDTH + 40.0);
        const double cy = random_coordinate(&seed, -40.0, HEIGHT + 40.0);
        for (int j = 0; j < 3; j++) {
            const double x = cx + random_coordinate(&seed, -32.0, 32.0);
            const double y = cy + random_coordinate(&seed, -32.0, 32.0);
            v[j] = vertex_in((window_point){x, y}, 0.5f, WIDTH, HEIGHT);
        }
        luz_triangle t;
        if (!set_up_either_way(v, WIDTH, HEIGHT, &t)) continue;
        bool short_edges = true;
        for (int k = 0; k < 3; k++)
            short_edges &= llabs(t.edges[k].a) < (1 << 14) && llabs(t.edges[k].b) < (1 << 14);
        if (!short_edges) continue;
        checked++;
        assert_int_equal(corners_past(&t, bound), 0u);
        const int64_t x[2] = {((int64_t)t.min_x - 3) * 256, ((int64_t)t.max_x + 4) * 256};
        const int64_t y[2] = {(int64_t)t.min_y * 256, ((int64_t)t.max_y + 1) * 256};
        for (int corner = 0; corner < 4; corner++)
            for (int k = 0; k < 3; k++) {
                const int64_t e = llabs((int64_t)t.edges[k].a * x[corner & 1] +
                                        (int64_t)t.edges[k].b * y[corner >> 1] + t.edges[k].c);
                if (e > largest) largest = e;
            }
    }
    assert_true(checked > 10000);
    assert_true(largest > bound / 4);
}

/* A colour for (triangle id, pixel): the fragment stage's stand-in. */
static uint32_t colour_of(uint32_t id, int x, int y)
{
    uint32_t h = id * 2654435761u ^ (uint32_t)x * 40503u ^ (uint32_t)y * 9973u;
    h ^= h >> 13;
    return h * 2246822519u;
}

/* The sort of four samples' winners and the resolve (resolve.c) against
 * the definition written here, under every instruction set's mixed-pixel
 * loop: rows of 37 pixels whose samples are won by few triangles (0, 1,
 * 2, 3, 9: every way four winners can agree or differ comes up). The
 * first winner of each pixel is its first non-zero sample's; the list of
 * other winners holds, pixel by pixel in order, the other distinct
 * winners in the order of the samples they first won; and with a colour
 * for each (triangle, pixel) and the clear colour for 0, each byte of a
 * pixel is floor((s0 + s1 + s2 + s3 + 2) / 4) of its samples' bytes. */
static void test_four_samples_sort_and_resolve_match_the_definition(void **state)
{
    (void)state;
    enum { WIDTH = 37, ROWS = 24, FIRST_ROW = 5, END_ROW = 21 };
    const uint32_t choices[5] = {0, 1, 2, 3, 9};
    const uint8_t background[4] = {10, 200, 33, 255};
    uint32_t background_word;
    memcpy(&background_word, background, 4);
    luz_winner_pattern *patterns = malloc(LUZ_WINNER_PATTERNS * sizeof *patterns);
    assert_non_null(patterns);
    luz_samples_winner_patterns(patterns);
    const size_t band_pixels = (size_t)(END_ROW - FIRST_ROW) * WIDTH;
    for (int isa = LUZ_ISA_SCALAR; isa < LUZ_ISA_COUNT; isa++) {
        if (!luz_isa_available((luz_isa)isa)) continue;
        uint32_t *ids = malloc((size_t)WIDTH * ROWS * 4 * sizeof *ids);
        uint32_t *first = calloc((size_t)WIDTH * ROWS, sizeof *first);
        uint8_t *colour = malloc((size_t)WIDTH * ROWS * 4);
        luz_sample_band band = {
            .mixed = malloc(band_pixels * sizeof(luz_mixed_pixel)),
            .extra = malloc(3 * band_pixels * sizeof(luz_fragment_ref)),
            .extra_colour = calloc(3 * band_pixels, sizeof(uint32_t)),
            .row_mixed = malloc(WIDTH * sizeof(uint16_t)),
            .patterns = patterns};
        assert_true(ids && first && colour && band.mixed && band.extra && band.extra_colour &&
                    band.row_mixed);
        unsigned seed = 27u + (unsigned)isa;
        for (size_t i = 0; i < (size_t)WIDTH * ROWS * 4; i++) {
            seed = seed * 1103515245u + 12345u;
            ids[i] = choices[(seed >> 16) % 5];
        }
        /* A run of pixels whose samples agree, as inside a surface. */
        for (int i = 8 * 4; i < 20 * 4; i++) ids[(size_t)FIRST_ROW * WIDTH * 4 + (size_t)i] = 3;
        luz_sample_buffers buffers = {.samples = 4, .width = WIDTH, .height = ROWS,
                                      .visibility = ids, .first_winner = first};
        luz_samples_sort_winners(&buffers, FIRST_ROW, END_ROW, &band,
                                 luz_kernels_of((luz_isa)isa).mixed_pixels);

        size_t mixed = 0, extra = 0;
        for (int y = FIRST_ROW; y < END_ROW; y++)
            for (int x = 0; x < WIDTH; x++) {
                const size_t pixel = (size_t)y * WIDTH + (size_t)x;
                const uint32_t *id = ids + pixel * 4;
                uint32_t winner = 0;
                for (int k = 3; k >= 0; k--)
                    if (id[k] != 0) winner = id[k];
                assert_int_equal(first[pixel], winner);
                if (id[0] == id[1] && id[0] == id[2] && id[0] == id[3]) continue;
                assert_true(mixed < band.mixed_count);
                assert_int_equal(band.mixed[mixed].index, pixel);
                assert_int_equal(band.mixed[mixed].first_extra, extra);
                mixed++;
                for (int k = 0; k < 4; k++) {
                    bool seen = id[k] == 0 || id[k] == winner;
                    for (int j = 0; j < k; j++) seen = seen || id[j] == id[k];
                    if (seen) continue;
                    assert_true(extra < band.extra_count);
                    assert_int_equal(band.extra[extra].id, id[k]);
                    assert_int_equal(band.extra[extra].x, x);
                    assert_int_equal(band.extra[extra].y, y);
                    extra++;
                }
            }
        assert_int_equal(band.mixed_count, mixed);
        assert_int_equal(band.extra_count, extra);
        assert_true(mixed > band_pixels / 2 && mixed < band_pixels);

        /* The fragment stage's part: each pixel its first winner's colour
         * (the clear colour for 0), each listed other winner its own. */
        for (int y = FIRST_ROW; y < END_ROW; y++)
            for (int x = 0; x < WIDTH; x++) {
                const size_t pixel = (size_t)y * WIDTH + (size_t)x;
                const uint32_t word =
                    first[pixel] ? colour_of(first[pixel], x, y) : background_word;
                memcpy(colour + pixel * 4, &word, 4);
            }
        for (size_t e = 0; e < band.extra_count; e++)
            band.extra_colour[e] = colour_of(band.extra[e].id, band.extra[e].x, band.extra[e].y);
        luz_framebuffer framebuffer = {.width = WIDTH, .height = ROWS, .colour = colour};
        luz_samples_resolve_winners(&band, &framebuffer, background);
        for (int y = FIRST_ROW; y < END_ROW; y++)
            for (int x = 0; x < WIDTH; x++) {
                const size_t pixel = (size_t)y * WIDTH + (size_t)x;
                unsigned sum[4] = {2, 2, 2, 2};
                for (int k = 0; k < 4; k++) {
                    const uint32_t id = ids[pixel * 4 + (size_t)k];
                    const uint32_t word = id ? colour_of(id, x, y) : background_word;
                    uint8_t bytes[4];
                    memcpy(bytes, &word, 4);
                    for (int c = 0; c < 4; c++) sum[c] += bytes[c];
                }
                for (int c = 0; c < 4; c++)
                    assert_int_equal(colour[pixel * 4 + (size_t)c], sum[c] / 4);
            }
        free(ids);
        free(first);
        free(colour);
        free(band.mixed);
        free(band.extra);
        free(band.extra_colour);
        free(band.row_mixed);
    }
    free(patterns);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_fill_rule_tiles_a_rectangle_exactly_once,
                                        setup_framebuffer, teardown_framebuffer),
        cmocka_unit_test_setup_teardown(test_fill_rule_on_a_fan, setup_framebuffer,
                                        teardown_framebuffer),
        cmocka_unit_test_setup_teardown(test_top_edge_in_bottom_edge_out, setup_framebuffer,
                                        teardown_framebuffer),
        cmocka_unit_test_setup_teardown(test_left_edge_in_right_edge_out, setup_framebuffer,
                                        teardown_framebuffer),
        cmocka_unit_test(test_back_faces_and_degenerate_triangles_are_culled),
        cmocka_unit_test(test_four_samples_in_lanes_match_the_definition),
        cmocka_unit_test(test_four_samples_edges_past_2_30_at_one_corner),
        cmocka_unit_test(test_four_samples_short_edges_fit_32_bits),
        cmocka_unit_test(test_four_samples_sort_and_resolve_match_the_definition),
        cmocka_unit_test_setup_teardown(test_depth_test_less, setup_framebuffer,
                                        teardown_framebuffer),
        cmocka_unit_test_setup_teardown(test_depth_is_interpolated_linearly, setup_framebuffer,
                                        teardown_framebuffer),
        cmocka_unit_test_setup_teardown(test_bands_match_one_pass, setup_framebuffer,
                                        teardown_framebuffer),
        cmocka_unit_test_setup_teardown(test_small_triangles_covering_no_centre_are_dropped,
                                        setup_framebuffer, teardown_framebuffer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
