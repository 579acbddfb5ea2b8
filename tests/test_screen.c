/*
 * test_screen.c: screening (src/renderer/screen.c), which drops back faces
 * and triangles that cover no pixel centre, many at a time, before setup.
 *
 * What it may drop is defined without it: a triangle is a back face when
 * its doubled area in fixed point, (Y1 - Y0)(X2 - X0) - (X1 - X0)(Y2 - Y0),
 * is not positive; it covers a pixel centre (X, Y) = (256 x + 128, 256 y +
 * 128) of the viewport when for each edge i -> j, E = (Yj - Yi)(X - Xi) -
 * (Xj - Xi)(Y - Yi) > 0, or = 0 on a top edge (dy = 0, dx < 0) or a left
 * edge (dy > 0). The tests count the centres by trying every pixel of the
 * viewport, and hold every variant to it: nothing dropped that covers a
 * centre, every back face dropped counted, and each screening variant
 * (screen_lanes.c for AVX-512, AVX2, SSE2 and NEON) dropping every
 * triangle it is meant to (a back face, a box with no
 * centre of the viewport, a box of up to 2 x 2 pixels with none covered).
 * luz_setup_projected, the other implementation, must agree on each
 * dropped triangle. Vertices outside a clip plane, or invalid, leave their
 * triangles to setup.
 *
 * The same for four samples a pixel (luz_kernels' screen_four): the
 * samples are SCENE.md's (x + sx, y + sy), (sx, sy) = (0.375, 0.125),
 * (0.875, 0.375), (0.125, 0.625), (0.625, 0.875), in the definitions
 * instead of the centre, and luz_setup_projected_samples(..., 4, ...)
 * the other implementation.
 */
#define _DEFAULT_SOURCE   /* MAP_ANONYMOUS */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cmocka.h>

#include "test_support.h"

#include "renderer/cpu.h"
#include "renderer/pipeline.h"

#define WIDTH 40
#define HEIGHT 24

/* Every instruction set's table (cpu.h); a set without a screening
 * variant lets every triangle through. */
static const luz_isa variants[] = {LUZ_ISA_SCALAR, LUZ_ISA_BASELINE, LUZ_ISA_AVX2,
                                   LUZ_ISA_AVX512};
#define VARIANT_COUNT (int)(sizeof variants / sizeof variants[0])

/* Variant v's screening for pixels of `samples` samples (1 or 4);
 * *screens: whether it drops any triangle (it then promises to check the
 * small boxes). */
static luz_screen_function *screening(int v, int samples, bool *screens)
{
    const luz_kernels kernels = luz_kernels_of(variants[v]);
    if (samples == 4) {
        *screens = kernels.screen_four != NULL;
        return *screens ? kernels.screen_four : luz_screen_every_triangle;
    }
    *screens = kernels.screen != luz_screen_every_triangle;
    assert_int_equal(kernels.screen_checks_small_boxes, *screens);
    return kernels.screen;
}

/* A pixel's sample points, from its corner, in 1/256 pixel (SCENE.md,
 * "Anti-aliasing": the centre for one sample, else the 4x pattern). */
static const int64_t centre_offset[1][2] = {{128, 128}};
static const int64_t four_offsets[4][2] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};

static const int64_t (*offsets_of(int samples))[2]
{
    return samples == 4 ? four_offsets : centre_offset;
}

/* A mesh of projected vertices, as luz_setup_project leaves them. */
typedef struct mesh {
    uint32_t vertex_count, triangle_count;
    luz_window_vertex *window;
    luz_fixed_vertex *fixed;
    luz_clip_vertex *clip;   /* zero: setup reads only the varyings */
    uint32_t *indices;
} mesh;

static void set_vertex(mesh *m, uint32_t i, int32_t fixed_x, int32_t fixed_y)
{
    m->window[i] = (luz_window_vertex){
        .x = fixed_x / (double)LUZ_SUBPIXEL_ONE, .y = fixed_y / (double)LUZ_SUBPIXEL_ONE,
        .depth = 0.5, .inverse_w = 1.0, .fixed_x = fixed_x, .fixed_y = fixed_y};
    m->fixed[i] = (luz_fixed_vertex){fixed_x, fixed_y};
}

static mesh mesh_create(uint32_t vertex_count, uint32_t triangle_count)
{
    mesh m = {vertex_count, triangle_count, calloc(vertex_count, sizeof(luz_window_vertex)),
              calloc(vertex_count, sizeof(luz_fixed_vertex)),
              calloc(vertex_count, sizeof(luz_clip_vertex)),
              calloc(3 * (size_t)triangle_count, sizeof(uint32_t))};
    assert_non_null(m.window);
    assert_non_null(m.fixed);
    assert_non_null(m.clip);
    assert_non_null(m.indices);
    return m;
}

static void mesh_destroy(mesh *m)
{
    free(m->window);
    free(m->fixed);
    free(m->clip);
    free(m->indices);
}

static bool is_marker(int32_t fixed_x)
{
    return fixed_x == LUZ_WINDOW_CLIPPED || fixed_x == LUZ_WINDOW_INVALID;
}

/* The definitions at the top, by brute force. */
static int64_t doubled_area(const luz_fixed_vertex p[3])
{
    return ((int64_t)p[1].y - p[0].y) * ((int64_t)p[2].x - p[0].x) -
           ((int64_t)p[1].x - p[0].x) * ((int64_t)p[2].y - p[0].y);
}

/* The sample points of the viewport the triangle covers (one sample a
 * pixel: its centre). */
static int samples_covered(const luz_fixed_vertex p[3], int samples)
{
    int count = 0;
    for (int y = 0; y < HEIGHT; y++)
        for (int x = 0; x < WIDTH; x++)
            for (int s = 0; s < samples; s++) {
                const int64_t sx = 256 * (int64_t)x + offsets_of(samples)[s][0];
                const int64_t sy = 256 * (int64_t)y + offsets_of(samples)[s][1];
                bool inside = true;
                for (int k = 0; k < 3; k++) {
                    const luz_fixed_vertex from = p[(k + 1) % 3], to = p[(k + 2) % 3];
                    const int64_t dx = (int64_t)to.x - from.x, dy = (int64_t)to.y - from.y;
                    const int64_t e = dy * (sx - from.x) - dx * (sy - from.y);
                    const bool top = dy == 0 && dx < 0, left = dy > 0;
                    inside = inside && (e > 0 || (e == 0 && (top || left)));
                }
                count += inside;
            }
    return count;
}

static int centres_covered(const luz_fixed_vertex p[3])
{
    return samples_covered(p, 1);
}

/* The pixels one of whose samples (one: the centre) lies within the
 * triangle's box, clamped to the viewport: -1 if none, else the larger of
 * its width and height. */
static int64_t box_size(const luz_fixed_vertex p[3], int samples)
{
    int64_t nearest = 256, farthest = 0;   /* a sample from the pixel's corner */
    for (int s = 0; s < samples; s++)
        for (int axis = 0; axis < 2; axis++) {
            const int64_t offset = offsets_of(samples)[s][axis];
            if (offset < nearest) nearest = offset;
            if (offset > farthest) farthest = offset;
        }
    int64_t lo_x = INT64_MAX, hi_x = INT64_MIN, lo_y = INT64_MAX, hi_y = INT64_MIN;
    for (int k = 0; k < 3; k++) {
        if (p[k].x < lo_x) lo_x = p[k].x;
        if (p[k].x > hi_x) hi_x = p[k].x;
        if (p[k].y < lo_y) lo_y = p[k].y;
        if (p[k].y > hi_y) hi_y = p[k].y;
    }
    /* A sample of pixel x within [lo, hi]: 256 x + farthest >= lo and
     * 256 x + nearest <= hi, x within the viewport. */
    int64_t first_x = 0, last_x = WIDTH - 1, first_y = 0, last_y = HEIGHT - 1;
    while (first_x < WIDTH && 256 * first_x + farthest < lo_x) first_x++;
    while (last_x >= 0 && 256 * last_x + nearest > hi_x) last_x--;
    while (first_y < HEIGHT && 256 * first_y + farthest < lo_y) first_y++;
    while (last_y >= 0 && 256 * last_y + nearest > hi_y) last_y--;
    if (first_x > last_x || first_y > last_y) return -1;
    const int64_t w = last_x - first_x + 1, h = last_y - first_y + 1;
    return w > h ? w : h;
}

typedef struct tally {
    int dropped_back, dropped_uncovered, kept;
} tally;

/* Screens triangles [first, end) with variant v for pixels of `samples`
 * samples and checks every verdict. */
static tally screen_and_check(const mesh *m, int v, int samples, uint32_t first, uint32_t end)
{
    bool checks_small_boxes = false;
    luz_screen_function *screen = screening(v, samples, &checks_small_boxes);
    uint32_t *survivors = malloc((end - first + 1) * sizeof *survivors);
    assert_non_null(survivors);
    uint32_t culled = 12345;
    const size_t count = screen(m->indices, first, end, m->fixed, WIDTH, HEIGHT, survivors,
                                &culled);
    assert_true(count <= end - first);

    tally result = {0, 0, 0};
    size_t next = 0;
    for (uint32_t t = first; t < end; t++) {
        const bool kept = next < count && survivors[next] == t;
        if (kept) next++;
        luz_fixed_vertex p[3];
        bool eligible = true;
        for (int k = 0; k < 3; k++) {
            p[k] = m->fixed[m->indices[3 * (size_t)t + k]];
            eligible = eligible && !is_marker(p[k].x);
        }
        const uint32_t *index = &m->indices[3 * (size_t)t];
        luz_triangle triangle;
        if (kept) {
            result.kept++;
            if (!eligible || !checks_small_boxes) continue;
            /* What a screening variant must not leave to setup, the last
             * triangles of a range (fewer than 16) included. */
            const int64_t size = box_size(p, samples);
            if (doubled_area(p) <= 0 || size < 0 ||
                (size <= 2 && samples_covered(p, samples) == 0))
                fail_msg("%s kept triangle %u, which it should drop (%d samples)",
                         luz_isa_name(variants[v]), t, samples);
            /* So setup told that screening checked the small boxes
             * decides as setup testing them itself (a larger box it still
             * tests either way). */
            const luz_setup_result trusting = luz_setup_projected_samples(
                &m->clip[index[0]], &m->clip[index[1]], &m->clip[index[2]],
                &m->window[index[0]], &m->window[index[1]], &m->window[index[2]], WIDTH, HEIGHT,
                0, LUZ_INTERPOLATION_PERSPECTIVE, checks_small_boxes, samples, &triangle);
            assert_int_equal(trusting, luz_setup_projected_samples(
                &m->clip[index[0]], &m->clip[index[1]], &m->clip[index[2]],
                &m->window[index[0]], &m->window[index[1]], &m->window[index[2]], WIDTH,
                HEIGHT, 0, LUZ_INTERPOLATION_PERSPECTIVE, false, samples, &triangle));
            continue;
        }
        /* Dropped: it must be eligible, and a back face or cover nothing. */
        if (!eligible)
            fail_msg("%s dropped triangle %u with a marked vertex", luz_isa_name(variants[v]), t);
        if (doubled_area(p) <= 0) result.dropped_back++;
        else if (samples_covered(p, samples) == 0) result.dropped_uncovered++;
        else
            fail_msg("%s dropped triangle %u, which covers a sample (%d a pixel)",
                     luz_isa_name(variants[v]), t, samples);
        /* And setup, the other implementation, says the same. */
        const luz_setup_result setup = luz_setup_projected_samples(
            &m->clip[index[0]], &m->clip[index[1]], &m->clip[index[2]], &m->window[index[0]],
            &m->window[index[1]], &m->window[index[2]], WIDTH, HEIGHT, 0,
            LUZ_INTERPOLATION_PERSPECTIVE, false, samples, &triangle);
        assert_int_equal(setup, doubled_area(p) <= 0 ? LUZ_SETUP_CULLED : LUZ_SETUP_OFFSCREEN);
    }
    /* The survivors are in order, each once, and within the range. */
    assert_int_equal(next, count);
    assert_int_equal(culled, (uint32_t)result.dropped_back);
    free(survivors);
    return result;
}

/* Screens the random mesh m with every variant for pixels of `samples`
 * samples: whole, and in pieces. */
static void screen_random_mesh(const mesh *m, int samples, uint32_t *random,
                               int *uncovered_of_one)
{
    const uint32_t triangle_count = m->triangle_count;
    for (int v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) {
            print_message("%s: not on this CPU or build, skipped\n", luz_isa_name(variants[v]));
            continue;
        }
        /* Whole, and in pieces that start and end anywhere. */
        tally whole = screen_and_check(m, v, samples, 0, triangle_count);
        tally pieces = {0, 0, 0};
        for (uint32_t first = 0; first < triangle_count;) {
            const uint32_t end = first + 1 + test_random(random) % 70;
            const tally piece = screen_and_check(m, v, samples, first,
                                                 end < triangle_count ? end : triangle_count);
            pieces.dropped_back += piece.dropped_back;
            pieces.dropped_uncovered += piece.dropped_uncovered;
            pieces.kept += piece.kept;
            first = end;
        }
        print_message("%s, %d sample%s: %d back faces and %d covering no sample dropped, %d "
                      "kept\n", luz_isa_name(variants[v]), samples, samples > 1 ? "s" : "",
                      whole.dropped_back, whole.dropped_uncovered, whole.kept);
        bool screens;
        screening(v, samples, &screens);
        if (!screens) {
            assert_int_equal(whole.kept, triangle_count);
            continue;
        }
        /* Both kinds of drop happen, often, and each triangle's verdict
         * is its own: the pieces (most of them shorter than 16, screened
         * in masked lanes) drop exactly what the whole range does. Four
         * samples cover more: fewer triangles cover none. */
        assert_true(whole.dropped_back > 5000);
        assert_true(whole.dropped_uncovered > (samples == 1 ? 2000 : 1000));
        if (samples == 1) *uncovered_of_one = whole.dropped_uncovered;
        else assert_true(whole.dropped_uncovered < *uncovered_of_one);
        assert_int_equal(pieces.kept, whole.kept);
        assert_int_equal(pieces.dropped_back, whole.dropped_back);
        assert_int_equal(pieces.dropped_uncovered, whole.dropped_uncovered);
    }
}

/* RANDOM TRIANGLES, most a pixel or two across, around and beyond a 40 x
 * 24 viewport, in shuffled vertex order; a few with a vertex marked
 * outside a clip plane or invalid, a few degenerate, a few huge (corners
 * near the +-2^24 limit of setup.c's proof). */
static void test_screening_drops_what_setup_would(void **state)
{
    (void)state;
    const uint32_t triangle_count = 20011;   /* not a multiple of 16 */
    mesh m = mesh_create(3 * triangle_count, triangle_count);
    uint32_t random = 2024;
    uint32_t *order = malloc(m.vertex_count * sizeof *order);
    assert_non_null(order);
    for (uint32_t i = 0; i < m.vertex_count; i++) order[i] = i;
    for (uint32_t i = m.vertex_count - 1; i > 0; i--) {
        const uint32_t j = test_random(&random) % (i + 1), swap = order[i];
        order[i] = order[j];
        order[j] = swap;
    }
    for (uint32_t t = 0; t < triangle_count; t++) {
        const uint32_t kind = test_random(&random) % 100;
        const int32_t base_x = (int32_t)(test_random(&random) % (256 * (WIDTH + 8))) - 256 * 4;
        const int32_t base_y = (int32_t)(test_random(&random) % (256 * (HEIGHT + 8))) - 256 * 4;
        const int32_t reach = kind < 60 ? 256 : kind < 90 ? 768 : 256 * 12;
        for (int k = 0; k < 3; k++) {
            const uint32_t i = order[3 * t + (uint32_t)k];
            m.indices[3 * (size_t)t + (size_t)k] = i;
            const uint32_t span = (uint32_t)(2 * reach + 1);
            int32_t x = base_x + (int32_t)(test_random(&random) % span) - reach;
            int32_t y = base_y + (int32_t)(test_random(&random) % span) - reach;
            if (kind == 99) {   /* huge: corners at the limit */
                x = (test_random(&random) & 1) ? (1 << 24) : -(1 << 24);
                y = (test_random(&random) & 1) ? (1 << 24) : -(1 << 24);
            }
            set_vertex(&m, i, x, y);
            if (kind == 97 && k == 1) m.fixed[i].x = m.window[i].fixed_x = LUZ_WINDOW_CLIPPED;
            if (kind == 98 && k == 2) m.fixed[i].x = m.window[i].fixed_x = LUZ_WINDOW_INVALID;
        }
        if (kind == 96) {   /* degenerate: two corners the same vertex */
            m.indices[3 * (size_t)t + 2] = m.indices[3 * (size_t)t];
        }
    }
    int uncovered_of_one = 0;   /* the last variant's drops at one sample */
    screen_random_mesh(&m, 1, &random, &uncovered_of_one);
    screen_random_mesh(&m, 4, &random, &uncovered_of_one);
    free(order);
    mesh_destroy(&m);
}

/* HAND-MADE: pixel (1, 1)'s square split along x + y = 3, through its
 * centre. The lower half has the centre on its left edge (kept), the upper
 * half on its right edge (dropped); the same upper half listed the other
 * way round is a back face (dropped, counted); the lower half with a
 * vertex outside a clip plane is left to setup (kept); a front face left
 * of the viewport, x < 0, has no centre to cover (dropped). Then the top
 * edge: two front faces share the horizontal edge y = 1.5 from x = 1 to 3,
 * through the centres of pixels (1, 1) and (2, 1); the one below it (y
 * grows down) has it as its top edge (dx < 0) and owns both centres
 * (kept), the one above has it as a bottom edge and covers nothing
 * (dropped). Sixteen triangles, so that the AVX-512 variant screens them
 * all at once. */
static void test_screening_the_split_pixel(void **state)
{
    (void)state;
    mesh m = mesh_create(12, 16);
    const int32_t one = LUZ_SUBPIXEL_ONE, half = LUZ_SUBPIXEL_ONE / 2;
    set_vertex(&m, 0, 1 * one, 2 * one);
    set_vertex(&m, 1, 2 * one, 2 * one);
    set_vertex(&m, 2, 2 * one, 1 * one);
    set_vertex(&m, 3, 1 * one, 1 * one);
    set_vertex(&m, 4, 2 * one, 2 * one);
    m.fixed[4].x = m.window[4].fixed_x = LUZ_WINDOW_CLIPPED;
    set_vertex(&m, 5, -3 * one, 2 * one);
    set_vertex(&m, 6, -2 * one, 2 * one);
    set_vertex(&m, 7, -2 * one, 1 * one);
    set_vertex(&m, 8, 1 * one, 1 * one + half);
    set_vertex(&m, 9, 3 * one, 1 * one + half);
    set_vertex(&m, 10, 2 * one, 2 * one + half);   /* below the shared edge */
    set_vertex(&m, 11, 2 * one, 0 * one + half);   /* above it */
    const uint32_t triangles[16][3] = {
        {0, 1, 2},   /* lower half: kept */
        {3, 0, 2},   /* upper half: dropped */
        {3, 2, 0},   /* upper half, back face: dropped */
        {0, 4, 2},   /* clipped vertex: kept */
        {5, 6, 7},   /* left of the viewport: dropped */
        {8, 10, 9},  /* below, the shared edge 9 -> 8 on top: kept */
        {8, 9, 11},  /* above, the shared edge 8 -> 9 below: dropped */
    };
    for (uint32_t t = 0; t < 16; t++)
        for (int k = 0; k < 3; k++)
            m.indices[3 * t + (uint32_t)k] = t < 7 ? triangles[t][k] : triangles[0][k];
    /* The definitions agree with the comments above. */
    for (uint32_t t = 0; t < 7; t++) {
        luz_fixed_vertex p[3];
        for (int k = 0; k < 3; k++) p[k] = m.fixed[triangles[t][k]];
        if (t == 3) continue;   /* its clipped vertex has no position */
        static const int64_t covered[7] = {1, 0, 0, 0, 0, 2, 0};
        assert_int_equal(doubled_area(p) > 0, t != 2);
        assert_int_equal(centres_covered(p), covered[t]);
    }

    for (int v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) continue;
        uint32_t survivors[16], culled = 99;
        bool screens;
        const size_t count = screening(v, 1, &screens)(m.indices, 0, 16, m.fixed, WIDTH,
                                                       HEIGHT, survivors, &culled);
        if (!screens) {
            assert_int_equal(count, 16);
            assert_int_equal(culled, 0);
            continue;
        }
        /* 0, 3, 5 and the nine copies of 0 (7..15). */
        assert_int_equal(count, 12);
        assert_int_equal(culled, 1);
        assert_int_equal(survivors[0], 0);
        assert_int_equal(survivors[1], 3);
        assert_int_equal(survivors[2], 5);
        for (uint32_t k = 3; k < 12; k++) assert_int_equal(survivors[k], k + 4);
        /* And each verdict against the definitions and setup. */
        screen_and_check(&m, v, 1, 0, 16);
    }
    mesh_destroy(&m);
}

/* HAND-MADE, four samples: two front faces inside pixel (1, 1), neither
 * over its centre (384, 384): one over its sample 0, (1.375, 1.125) =
 * (352, 288), which four-sample screening keeps, one between the
 * samples, which it drops as one-sample screening drops both; then
 * fourteen copies of the first. */
static void test_screening_four_samples(void **state)
{
    (void)state;
    mesh m = mesh_create(6, 16);
    set_vertex(&m, 0, 340, 280);   /* legs of 30 and 20 round (352, 288) */
    set_vertex(&m, 1, 340, 300);
    set_vertex(&m, 2, 370, 280);
    set_vertex(&m, 3, 290, 290);   /* (290..310, 290..310): no sample */
    set_vertex(&m, 4, 290, 310);
    set_vertex(&m, 5, 310, 290);
    for (uint32_t t = 0; t < 16; t++)
        for (uint32_t k = 0; k < 3; k++) m.indices[3 * t + k] = (t == 1 ? 3 : 0) + k;
    for (uint32_t t = 0; t < 2; t++) {
        const luz_fixed_vertex p[3] = {m.fixed[3 * t], m.fixed[3 * t + 1], m.fixed[3 * t + 2]};
        assert_true(doubled_area(p) > 0);
        assert_int_equal(centres_covered(p), 0);
        assert_int_equal(samples_covered(p, 4), t == 0 ? 1 : 0);
    }
    int screened = 0;
    for (int v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) continue;
        for (int samples = 1; samples <= 4; samples += 3) {
            uint32_t survivors[16], culled = 99;
            bool screens;
            const size_t count = screening(v, samples, &screens)(m.indices, 0, 16, m.fixed,
                                                                 WIDTH, HEIGHT, survivors,
                                                                 &culled);
            assert_int_equal(culled, 0);
            if (!screens) {
                assert_int_equal(count, 16);
                continue;
            }
            screened += samples == 4;
            if (samples == 1) {
                assert_int_equal(count, 0);
                continue;
            }
            assert_int_equal(count, 15);   /* all but triangle 1 */
            assert_int_equal(survivors[0], 0);
            for (uint32_t k = 1; k < 15; k++) assert_int_equal(survivors[k], k + 1);
            screen_and_check(&m, v, 4, 0, 16);
        }
    }
    print_message("%d variants screen four samples\n", screened);
    mesh_destroy(&m);
}

/* bytes ending where an unreadable, unwritable page starts: an access one
 * element past them faults (AddressSanitizer does not check masked loads
 * and stores; the page does). */
static void *guarded(size_t bytes, void **mapping, size_t *mapping_size)
{
    const size_t page = (size_t)sysconf(_SC_PAGESIZE);
    const size_t usable = (bytes + page - 1) / page * page;
    *mapping_size = usable + page;
    char *base = mmap(NULL, *mapping_size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS,
                      -1, 0);
    assert_true(base != MAP_FAILED);
    assert_int_equal(mprotect(base + usable, page, PROT_NONE), 0);
    *mapping = base;
    return base + usable - bytes;
}

/* TAILS AT THE EDGE: ranges of 1 to 48 triangles, starting at 0 or 7, with
 * the index array ending and the survivors (end - first of them, as
 * pipeline.h promises) ending at a guard page, every triangle kept or
 * every one dropped: no index read past the range's last, no survivor
 * written past the room promised. */
static void test_screening_stays_within_its_arrays(void **state)
{
    (void)state;
    const int32_t one = LUZ_SUBPIXEL_ONE;
    mesh vertices = mesh_create(6, 1);
    set_vertex(&vertices, 0, 1 * one, 1 * one);   /* front, covers (1,1) .. (4,4) */
    set_vertex(&vertices, 1, 1 * one, 6 * one);
    set_vertex(&vertices, 2, 6 * one, 1 * one);
    set_vertex(&vertices, 3, -3 * one, 1 * one);   /* front, left of the viewport */
    set_vertex(&vertices, 4, -3 * one, 2 * one);
    set_vertex(&vertices, 5, -2 * one, 1 * one);
    luz_fixed_vertex p[3] = {vertices.fixed[0], vertices.fixed[1], vertices.fixed[2]};
    assert_true(doubled_area(p) > 0 && centres_covered(p) > 0);
    for (int v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) continue;
        bool screens;
        luz_screen_function *screen = screening(v, 1, &screens);
        for (uint32_t first = 0; first <= 7; first += 7)
            for (uint32_t length = 1; length <= 48; length++)
                for (int dropped = 0; dropped < 2; dropped++) {
                    const uint32_t end = first + length;
                    void *index_mapping, *survivor_mapping;
                    size_t index_size, survivor_size;
                    uint32_t *indices = guarded(3 * (size_t)end * sizeof *indices,
                                                &index_mapping, &index_size);
                    uint32_t *survivors = guarded(length * sizeof *survivors,
                                                  &survivor_mapping, &survivor_size);
                    for (uint32_t i = 0; i < 3 * end; i++)
                        indices[i] = (uint32_t)(dropped ? 3 + i % 3 : i % 3);
                    uint32_t culled = 99;
                    const size_t count = screen(indices, first, end, vertices.fixed, WIDTH,
                                                HEIGHT, survivors, &culled);
                    const bool drops = dropped && screens;
                    assert_int_equal(count, drops ? 0 : length);
                    assert_int_equal(culled, 0);
                    for (size_t k = 0; k < count; k++)
                        assert_int_equal(survivors[k], first + k);
                    munmap(index_mapping, index_size);
                    munmap(survivor_mapping, survivor_size);
                }
    }
    mesh_destroy(&vertices);
}

/* LONG THIN TRIANGLES AT THE VIEWPORT'S CORNER: one vertex within 3
 * pixels of the top-left corner, the other two up to R sub-pixel units
 * away, R from 2^13 to 2^16 for a run of 8 triangles (a step of AVX2),
 * so that boxes clamped to the viewport are often 2 x 2 or less while
 * the edges and the distances to the centres are long. Around 2^14 to
 * 2^15 the doubled area and the edge functions stop fitting 32-bit lanes
 * (a product of two 2^16 is 2^32): a variant that takes a 32-bit path too
 * far drops or keeps the wrong ones. Checked against the brute force. */
static void test_screening_long_triangles_at_a_corner(void **state)
{
    (void)state;
    const uint32_t triangle_count = 4096;
    mesh m = mesh_create(3 * triangle_count, triangle_count);
    uint32_t random = 99;
    for (uint32_t t = 0; t < triangle_count; t++) {
        const int32_t reach = 1 << (13 + (int)(t / 8 % 4));
        const int32_t base_x = (int32_t)(test_random(&random) % (256 * 3));
        const int32_t base_y = (int32_t)(test_random(&random) % (256 * 3));
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t i = 3 * t + k;
            m.indices[i] = i;
            const uint32_t span = (uint32_t)(2 * reach + 1);
            int32_t x = base_x, y = base_y;
            if (k > 0) {
                x += (int32_t)(test_random(&random) % span) - reach;
                y += (int32_t)(test_random(&random) % span) - reach;
            }
            set_vertex(&m, i, x, y);
        }
    }
    for (int v = 0; v < VARIANT_COUNT; v++) {
        if (!luz_isa_available(variants[v])) continue;
        for (int samples = 1; samples <= 4; samples += 3) {
            const tally whole = screen_and_check(&m, v, samples, 0, triangle_count);
            print_message("%s, %d sample%s: %d back faces and %d covering no sample dropped, "
                          "%d kept\n", luz_isa_name(variants[v]), samples, samples > 1 ? "s" : "",
                          whole.dropped_back, whole.dropped_uncovered, whole.kept);
            bool screens;
            screening(v, samples, &screens);
            if (screens) assert_true(whole.dropped_back > 1000 && whole.dropped_uncovered > 50);
        }
    }
    mesh_destroy(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_screening_drops_what_setup_would),
        cmocka_unit_test(test_screening_the_split_pixel),
        cmocka_unit_test(test_screening_four_samples),
        cmocka_unit_test(test_screening_stays_within_its_arrays),
        cmocka_unit_test(test_screening_long_triangles_at_a_corner),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
