/*
 * test_clip.c: clipping in homogeneous clip space (src/renderer/clip.c)
 * against crossing points computed by hand: OpenGL's clip volume is
 * -w <= z <= w, and luz clips x and y to a guard band |x|, |y| <= 4 w.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "test_support.h"

#include "renderer/pipeline.h"

#define TOLERANCE 1e-6

/* A clip vertex whose varying i is first + step * i, so that every
 * varying interpolates differently. */
static luz_clip_vertex make_vertex(float x, float y, float z, float w, float first, float step)
{
    luz_clip_vertex vertex;
    vertex.position = (luz_vec4){x, y, z, w};
    for (int i = 0; i < LUZ_VARYING_COUNT; i++) vertex.varyings[i] = first + step * (float)i;
    return vertex;
}

/* The vertex on segment (from, to) at parameter t, in double precision:
 * the hand computation the clipper is compared against. */
static void assert_vertex_at(const luz_clip_vertex *got, const luz_clip_vertex *from,
                             const luz_clip_vertex *to, double t)
{
    const float *g = &got->position.x, *a = &from->position.x, *b = &to->position.x;
    for (int k = 0; k < 4; k++) assert_near(g[k], a[k] + t * (b[k] - a[k]), TOLERANCE);
    for (int i = 0; i < LUZ_VARYING_COUNT; i++)
        assert_near(got->varyings[i],
                    from->varyings[i] + t * (to->varyings[i] - from->varyings[i]), 1e-5);
}

static bool same_vertex(const luz_clip_vertex *a, const luz_clip_vertex *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

/* Inside every plane the code is 0, also exactly on a plane (z = -w) and
 * inside the guard band (x = 3 w, beyond the viewport's x = w). Each plane
 * crossed sets its own bit: the six single-plane codes are distinct single
 * bits, a point outside two planes has both bits, and a NaN coordinate
 * counts as outside. */
static void test_outcodes(void **state)
{
    (void)state;
    assert_int_equal(luz_clip_outcode((luz_vec4){0, 0, 0, 1}), 0);
    assert_int_equal(luz_clip_outcode((luz_vec4){0, 0, -2, 2}), 0);
    assert_int_equal(luz_clip_outcode((luz_vec4){3, -3, 0.5f, 1}), 0);

    const luz_vec4 outside[LUZ_CLIP_PLANE_COUNT] = {
        {0, 0, -3, 2},    /* behind the near plane, z < -w */
        {0, 0, 3, 2},     /* beyond the far plane, z > w */
        {-9, 0, 0, 2},    /* left of the guard band, x < -4 w */
        {9, 0, 0, 2},     /* right, x > 4 w */
        {0, -9, 0, 2},    /* below, y < -4 w */
        {0, 9, 0, 2},     /* above, y > 4 w */
    };
    unsigned seen = 0;
    for (int plane = 0; plane < LUZ_CLIP_PLANE_COUNT; plane++) {
        unsigned code = luz_clip_outcode(outside[plane]);
        assert_int_not_equal(code, 0);
        assert_int_equal(code & (code - 1), 0);  /* a single bit */
        assert_int_equal(code & seen, 0);        /* not another plane's */
        seen |= code;
    }
    unsigned near_and_left = luz_clip_outcode((luz_vec4){-9, 0, -3, 2});
    assert_int_equal(near_and_left,
                     luz_clip_outcode(outside[0]) | luz_clip_outcode(outside[2]));
    assert_int_not_equal(luz_clip_outcode((luz_vec4){NAN, 0, 0, 1}), 0);
}

/* A triangle inside the clip volume comes out as it went in, bit for
 * bit, in the same order. */
static void test_inside_triangle_is_unchanged(void **state)
{
    (void)state;
    luz_clip_vertex a = make_vertex(-0.5f, -0.5f, 0.1f, 1, 1, 1);
    luz_clip_vertex b = make_vertex(0.5f, -0.5f, 0.2f, 1.5f, 2, 1);
    luz_clip_vertex c = make_vertex(0, 0.5f, 0.3f, 2, 3, 1);
    luz_clip_polygon polygon;
    assert_int_equal(luz_clip_triangle(&a, &b, &c, &polygon), 3);
    assert_int_equal(polygon.vertex_count, 3);
    assert_true(same_vertex(&polygon.vertices[0], &a));
    assert_true(same_vertex(&polygon.vertices[1], &b));
    assert_true(same_vertex(&polygon.vertices[2], &c));
}

/* a = (0, 0, -3, 1) is behind the near plane (w + z = -2), b = (1, 0, 0, 1)
 * (w + z = 1) and c = (0, 1, 0.5, 2) (w + z = 2.5) are in front. The near
 * plane cuts
 *   b -> a at t = 1 / (1 + 2) = 1/3:   (2/3, 0, -1, 1),
 *   c -> a at t = 2.5 / (2.5 + 2) = 5/9: (0, 4/9, -13/9, 13/9),
 * both with z = -w, and every varying at the same t. Sutherland-Hodgman
 * keeps the winding a, b, c with a replaced by its two crossings: the
 * quad (X_ca, X_ab, b, c), up to where the cycle starts. */
static void test_one_vertex_behind_near_plane_gives_a_quad(void **state)
{
    (void)state;
    luz_clip_vertex a = make_vertex(0, 0, -3, 1, 10, 1);
    luz_clip_vertex b = make_vertex(1, 0, 0, 1, 20, 2);
    luz_clip_vertex c = make_vertex(0, 1, 0.5f, 2, 40, -1);
    luz_clip_polygon polygon;
    assert_int_equal(luz_clip_triangle(&a, &b, &c, &polygon), 4);

    int start = -1;   /* where b sits in the cycle */
    for (int k = 0; k < 4; k++)
        if (same_vertex(&polygon.vertices[k], &b)) start = k;
    assert_true(start >= 0);
    const luz_clip_vertex *after_b = &polygon.vertices[(start + 1) % 4];
    const luz_clip_vertex *crossing_ca = &polygon.vertices[(start + 2) % 4];
    const luz_clip_vertex *crossing_ab = &polygon.vertices[(start + 3) % 4];
    assert_true(same_vertex(after_b, &c));
    assert_vertex_at(crossing_ab, &b, &a, 1.0 / 3.0);
    assert_vertex_at(crossing_ca, &c, &a, 5.0 / 9.0);
    assert_near(crossing_ab->position.z, -1.0, TOLERANCE);
    assert_near(crossing_ab->position.w, 1.0, TOLERANCE);
    assert_near(crossing_ca->position.z, -13.0 / 9.0, TOLERANCE);
    assert_near(crossing_ca->position.w, 13.0 / 9.0, TOLERANCE);
}

/* a and b behind the near plane, c in front: a triangle remains, c and
 * the two crossings. a = (0, 0, -2, 1) (w + z = -1), b = (1, 0, -3, 1)
 * (-2), c = (0, 1, 1, 1) (2): c -> a at t = 2/3, b -> c at t = 2/4 from c,
 * i.e. c + 1/2 (b - c). */
static void test_two_vertices_behind_near_plane_give_a_triangle(void **state)
{
    (void)state;
    luz_clip_vertex a = make_vertex(0, 0, -2, 1, 0, 1);
    luz_clip_vertex b = make_vertex(1, 0, -3, 1, 5, 1);
    luz_clip_vertex c = make_vertex(0, 1, 1, 1, 9, 1);
    luz_clip_polygon polygon;
    assert_int_equal(luz_clip_triangle(&a, &b, &c, &polygon), 3);
    int start = -1;
    for (int k = 0; k < 3; k++)
        if (same_vertex(&polygon.vertices[k], &c)) start = k;
    assert_true(start >= 0);
    /* The winding a, b, c becomes (X_bc, c, X_ca): after c comes the
     * crossing on c -> a, then the one on b -> c. */
    assert_vertex_at(&polygon.vertices[(start + 1) % 3], &c, &a, 2.0 / 3.0);
    assert_vertex_at(&polygon.vertices[(start + 2) % 3], &c, &b, 0.5);
}

/* a = (8, 0, 0, 1) is right of the guard band (x <= 4 w); b = (0, 1, 0, 1)
 * and c = (0, -1, 0, 1) are inside. Distances 4 w - x: a -4, b and c 4, so
 * both edges are cut halfway: (4, 0.5, 0, 1) on b -> a and (4, -0.5, 0, 1)
 * on c -> a. */
static void test_guard_band_clips_x(void **state)
{
    (void)state;
    luz_clip_vertex a = make_vertex(8, 0, 0, 1, 0, 1);
    luz_clip_vertex b = make_vertex(0, 1, 0, 1, 2, 1);
    luz_clip_vertex c = make_vertex(0, -1, 0, 1, 4, 1);
    luz_clip_polygon polygon;
    assert_int_equal(luz_clip_triangle(&a, &b, &c, &polygon), 4);
    int start = -1;
    for (int k = 0; k < 4; k++)
        if (same_vertex(&polygon.vertices[k], &b)) start = k;
    assert_true(start >= 0);
    assert_true(same_vertex(&polygon.vertices[(start + 1) % 4], &c));
    assert_vertex_at(&polygon.vertices[(start + 2) % 4], &c, &a, 0.5);
    assert_vertex_at(&polygon.vertices[(start + 3) % 4], &b, &a, 0.5);
}

/* Three vertices beyond the far plane (z > w), or all behind the near
 * plane: nothing is left. */
static void test_triangle_outside_one_plane_vanishes(void **state)
{
    (void)state;
    luz_clip_vertex a = make_vertex(0, 0, 2, 1, 0, 1);
    luz_clip_vertex b = make_vertex(1, 0, 3, 1, 0, 1);
    luz_clip_vertex c = make_vertex(0, 1, 5, 2, 0, 1);
    luz_clip_polygon polygon;
    assert_int_equal(luz_clip_triangle(&a, &b, &c, &polygon), 0);
    assert_int_equal(polygon.vertex_count, 0);

    a.position.z = b.position.z = -4;
    c.position.z = -5;
    assert_int_equal(luz_clip_triangle(&a, &b, &c, &polygon), 0);
}

/* The crossing on segment (from, to), interpolated from `from`: what a
 * clipper that does not order the edge would compute for one of the two
 * triangles. */
static float naive_crossing_y(luz_vec4 from, luz_vec4 to)
{
    float from_distance = from.w + from.z, to_distance = to.w + to.z;
    float t = from_distance / (from_distance - to_distance);
    return from.y + t * (to.y - from.y);
}

static const luz_clip_vertex *find_crossing(const luz_clip_polygon *polygon)
{
    /* By hand: t = 2.6 / 5.3 on p -> q gives (-0.38679245, -0.13584906,
     * -1.16037736, 1.16037736). */
    for (int k = 0; k < polygon->vertex_count; k++) {
        luz_vec4 p = polygon->vertices[k].position;
        if (fabs(p.x + 0.38679245) < 1e-5 && fabs(p.y + 0.13584906) < 1e-5 &&
            fabs(p.z + 1.16037736) < 1e-5 && fabs(p.w - 1.16037736) < 1e-5)
            return &polygon->vertices[k];
    }
    return NULL;
}

/* The crack rule: two triangles share the edge p -> q, which crosses the
 * near plane (p: w + z = 2.6, q: w + z = -2.7). The first lists it as
 * (p, q), its neighbour as (q, p), as adjacent front faces do. Both must
 * produce the same crossing vertex bit for bit, or a hairline crack can
 * open between them. For these numbers, interpolating from p and from q
 * give different floats (checked first), so a clipper that does not fix
 * the direction of the edge fails this test. */
static void test_shared_edge_crossing_is_bit_identical(void **state)
{
    (void)state;
    luz_clip_vertex p = make_vertex(0.3f, -0.7f, 0.9f, 1.7f, 0.1f, 0.3f);
    luz_clip_vertex q = make_vertex(-1.1f, 0.45f, -3.3f, 0.6f, 0.7f, -0.2f);
    luz_clip_vertex r1 = make_vertex(1.2f, 0.8f, 0.1f, 1.5f, 0.5f, 0.5f);
    luz_clip_vertex r2 = make_vertex(-0.9f, -1.0f, 0.2f, 1.4f, 0.9f, 0.1f);
    assert_true(naive_crossing_y(p.position, q.position) !=
                naive_crossing_y(q.position, p.position));

    luz_clip_polygon first, second;
    assert_true(luz_clip_triangle(&p, &q, &r1, &first) >= 3);
    assert_true(luz_clip_triangle(&q, &p, &r2, &second) >= 3);
    const luz_clip_vertex *first_crossing = find_crossing(&first);
    const luz_clip_vertex *second_crossing = find_crossing(&second);
    assert_non_null(first_crossing);
    assert_non_null(second_crossing);
    assert_vertex_at(first_crossing, &p, &q, 2.6 / 5.3);
    assert_true(same_vertex(first_crossing, second_crossing));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_outcodes),
        cmocka_unit_test(test_inside_triangle_is_unchanged),
        cmocka_unit_test(test_one_vertex_behind_near_plane_gives_a_quad),
        cmocka_unit_test(test_two_vertices_behind_near_plane_give_a_triangle),
        cmocka_unit_test(test_guard_band_clips_x),
        cmocka_unit_test(test_triangle_outside_one_plane_vanishes),
        cmocka_unit_test(test_shared_edge_crossing_is_bit_identical),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
