/*
 * setup.c: triangle setup, done once per triangle so that the per-pixel
 * loops only add and compare.
 *
 * In:  clip-space vertices (already clipped, so w > 0); luz_setup_project
 *      divides, maps and snaps each vertex once (steps 1-2, a
 *      luz_window_vertex; where a big draw's vertex pass keeps only
 *      snapped positions, setup in lanes, setup_eight.c, and geometry.c's
 *      one_triangle do it again for the corners they set up),
 *      luz_setup_projected sets up a triangle of three of them (steps
 *      3-5).
 * Out: a luz_triangle: the pixel bounding box, three fixed-point edge
 *      functions with the fill rule folded in, and screen-space planes for
 *      depth, 1/w and every varying/w (for affine interpolation: 1 and
 *      every varying); or CULLED (a back face), or OFFSCREEN (no pixel
 *      centre covered: outside the viewport, or a small triangle whose box
 *      holds centres that all fall outside it). For a frame of four
 *      samples a pixel (luz_setup_projected_samples) the box and that test
 *      are the samples', SCENE.md's pattern, not the centres.
 *
 * Steps, as in OpenGL 4.6 section 13.8 (coordinate transformations) and
 * Fabian Giesen's "Triangle rasterization in practice":
 *
 * 1. Perspective divide and viewport (SCENE.md):
 *      x_win = (x_ndc + 1) / 2 * W,  y_win = (1 - y_ndc) / 2 * H,
 *      depth = (z_ndc + 1) / 2.   Row 0 is on top, so y points down.
 * 2. Snap x_win, y_win to 1/256 pixel (8 sub-pixel bits). Coverage is then
 *    decided in exact integer arithmetic: no epsilon, no cracks.
 * 3. Cull: the doubled signed area in window coordinates is positive for a
 *    triangle that is counter-clockwise in NDC (a front face; the y flip of
 *    the viewport turns the orientation of the coordinates around, not
 *    what the viewer sees). Back faces and zero-area triangles go.
 * 4. Edge functions. For the edge from vertex i to vertex j,
 *      E(X, Y) = (Yj - Yi)(X - Xi) - (Xj - Xi)(Y - Yi)
 *    is positive on the inside of a front face. A sample exactly on an
 *    edge (E = 0) belongs to the triangle only if the edge is a top edge
 *    (horizontal, the triangle below it: it runs right to left, dx < 0,
 *    dy = 0) or a left edge (it runs downwards, dy > 0). Subtracting 1 from
 *    the other edges' constant makes "covered" simply E >= 0.
 * 5. Planes: depth is affine in window coordinates, and so are 1/w and
 *    every varying divided by w; their gradients are solved once here from
 *    the exact (unsnapped) vertex positions. Dividing the interpolated
 *    varying/w by the interpolated 1/w gives the perspective-correct
 *    value (Heckbert and Moreton, "Interpolation for polygon texture
 *    mapping and shading"). The arithmetic of each plane is planes.c's
 *    (luz_plane_through, luz_planes_solve), which can solve the 1/w and
 *    varying planes again later from the mesh triangle alone.
 *    LUZ_INTERPOLATION_AFFINE, the teaching toggle (--interp affine), solves
 *    the planes of the varyings themselves and makes the 1/w plane the
 *    constant 1, so the same division in the fragment stage returns the
 *    varying interpolated linearly in screen space, as early game consoles
 *    did: textures bend along the diagonal and swim as the view turns.
 *
 * Fixed-point range, the proof that int64 cannot overflow: the guard band
 * keeps |x_ndc|, |y_ndc| <= 4, so -1.5 W <= x_win <= 2.5 W with W <=
 * LUZ_MAX_DIMENSION = 2^14: |x_win| < 2^16 pixels, |X| < 2^24 in 1/256
 * units (coordinates are clamped to |X| <= 2^24 anyway). Then |Xj - Xi| <=
 * 2^25 (so an edge's a and b fit 32 bits), each product in E is at most
 * 2^49, the constant c below 2^51 and E at any pixel centre of the
 * viewport below 2^52: far from 2^63.
 */
#include <math.h>
#include <string.h>

#include "renderer/pipeline.h"

/* Keeps a window coordinate within +-2^24 sub-pixel units. */
static double clamp_to_limit(double window_coordinate)
{
    const double limit = LUZ_COORDINATE_LIMIT / LUZ_SUBPIXEL_ONE;
    if (window_coordinate > limit) return limit;
    if (window_coordinate < -limit) return -limit;
    return window_coordinate;
}

static int64_t snap(double window_coordinate)
{
    return (int64_t)llrint(window_coordinate * LUZ_SUBPIXEL_ONE);
}


/* bottom_right: luz/bug.h's fill-rule-bottom-right, where the samples on
 * an edge belong to the triangle if the edge is a bottom edge (dy = 0,
 * dx > 0) or a right edge (dy < 0), every edge that is neither top nor
 * left: the 1 is subtracted from the top and left edges instead. */
static luz_edge make_edge(int64_t xi, int64_t yi, int64_t xj, int64_t yj, bool bottom_right)
{
    luz_edge edge;
    int64_t dx = xj - xi, dy = yj - yi;
    edge.a = (int32_t)dy;   /* |dy|, |dx| <= 2^25 (the proof at the top) */
    edge.b = (int32_t)-dx;
    edge.c = -(dy * xi - dx * yi);
    bool top_edge = dy == 0 && dx < 0;
    bool left_edge = dy > 0;
    if ((top_edge || left_edge) == bottom_right) edge.c -= 1;
    return edge;
}

/* Whether any pixel centre of the triangle's box passes its three edge
 * functions: E(X, Y) = a X + b Y + c >= 0 at X = 256 x + 128, Y = 256 y +
 * 128, as raster.c tests them (the fill rule is in c; setup_eight.c's
 * covered_lanes is the same test in lanes). Each centre's three
 * values are computed afresh, independent multiplies: stepping them from
 * the box's first centre by 256 a and 256 b runs fewer instructions but
 * was slower on the 1M-triangle sphere (each step waits for the one
 * before, and most boxes find a centre at once). Not raster's
 * luz_raster_row_span: that finds a row's whole span, where this stops at
 * the first centre, and on a million-triangle mesh calling it cost a
 * share of the frame (docs/performance.md, "Measured in the code"). */
static bool covers_a_centre(const luz_triangle *triangle)
{
    const int64_t half = LUZ_SUBPIXEL_ONE / 2;
    for (int y = triangle->min_y; y <= triangle->max_y; y++) {
        const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + half;
        for (int x = triangle->min_x; x <= triangle->max_x; x++) {
            const int64_t sample_x = (int64_t)x * LUZ_SUBPIXEL_ONE + half;
            if (luz_edges_cover(triangle->edges, sample_x, sample_y)) return true;
        }
    }
    return false;
}

/* The same for the samples of a pixel of `samples` samples (luz_sample_offset_of):
 * whether any sample of the box passes the three edges. */
static bool covers_a_sample(const luz_triangle *triangle, int samples)
{
    for (int y = triangle->min_y; y <= triangle->max_y; y++) {
        for (int x = triangle->min_x; x <= triangle->max_x; x++) {
            for (int s = 0; s < samples; s++) {
                const luz_sample_offset offset = luz_sample_offset_of(samples, s);
                const int64_t sample_x = (int64_t)x * LUZ_SUBPIXEL_ONE + offset.x;
                const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + offset.y;
                if (luz_edges_cover(triangle->edges, sample_x, sample_y)) return true;
            }
        }
    }
    return false;
}

/* A box of up to 2 x 2 pixels whose triangle covers one pixel centre
 * alone becomes that pixel (the box is what may be covered, and that is
 * all): the raster then tests one centre, not the box's four, and binning
 * gives the triangle to that pixel's band alone. On a mesh of a million
 * triangles of about a pixel, most are such "points" (the 1M sphere: 84%
 * of its records, 12% with a box of one pixel before). The same E >= 0 at
 * X = 256 x + 128, Y = 256 y + 128 as covers_a_centre and the raster;
 * setup in lanes (setup_eight.c, setup_lanes.c) narrows the same boxes. */
static void narrow_to_one_centre(luz_triangle *triangle)
{
    if (triangle->min_x == triangle->max_x && triangle->min_y == triangle->max_y) return;
    const int64_t half = LUZ_SUBPIXEL_ONE / 2;
    int covered = 0, covered_x = 0, covered_y = 0;
    for (int y = triangle->min_y; y <= triangle->max_y; y++) {
        const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + half;
        for (int x = triangle->min_x; x <= triangle->max_x; x++) {
            const int64_t sample_x = (int64_t)x * LUZ_SUBPIXEL_ONE + half;
            if (luz_edges_cover(triangle->edges, sample_x, sample_y))
                covered++, covered_x = x, covered_y = y;
        }
    }
    if (covered != 1) return;
    triangle->min_x = triangle->max_x = covered_x;
    triangle->min_y = triangle->max_y = covered_y;
}

luz_window_vertex luz_setup_project_vertex(const luz_clip_vertex *vertex, int width, int height)
{
    const luz_vec4 p = vertex->position;
    luz_window_vertex window = {0};
    if (vertex->outcode != 0) {   /* only the clipper reads it */
        window.fixed_x = LUZ_WINDOW_CLIPPED;
        return window;
    }
    if (!(p.w > 0.0f) || !isfinite(p.x) || !isfinite(p.y) || !isfinite(p.z)) {
        window.fixed_x = LUZ_WINDOW_INVALID;   /* unreachable unless NaN */
        return window;
    }
    /* 1-2. Divide, viewport, snap. */
    window.inverse_w = 1.0 / p.w;
    double x_ndc = p.x * window.inverse_w, y_ndc = p.y * window.inverse_w;
    window.x = clamp_to_limit((x_ndc + 1.0) * 0.5 * width);
    window.y = clamp_to_limit((1.0 - y_ndc) * 0.5 * height);
    window.fixed_x = (int32_t)snap(window.x);
    window.fixed_y = (int32_t)snap(window.y);
    window.depth = (p.z * window.inverse_w + 1.0) * 0.5;
    return window;
}

void luz_setup_project(const luz_clip_vertex *vertices, uint32_t first, uint32_t end, int width,
                       int height, luz_window_vertex *out, luz_fixed_vertex *fixed)
{
    for (uint32_t i = first; i < end; i++) {
        const luz_window_vertex window = luz_setup_project_vertex(&vertices[i], width, height);
        if (out != NULL) out[i] = window;
        if (fixed != NULL) fixed[i] = (luz_fixed_vertex){window.fixed_x, window.fixed_y};
    }
}

/* luz_setup_projected for pixels of `samples` samples; inlined into both
 * public functions, so that the one-sample one compiles as it did. */
static inline __attribute__((always_inline)) luz_setup_result
setup_projected(const luz_clip_vertex *v0, const luz_clip_vertex *v1, const luz_clip_vertex *v2,
                const luz_window_vertex *p0, const luz_window_vertex *p1,
                const luz_window_vertex *p2, int width, int height, uint32_t draw_index,
                luz_interpolation interpolation, bool small_box_checked, int samples,
                bool bottom_right, luz_triangle *out)
{
    /* 3. Cull back faces and degenerate triangles (and any vertex that
     * luz_setup_project found invalid). */
    if (!luz_setup_front_facing(p0, p1, p2)) return LUZ_SETUP_CULLED;
    const int64_t fixed_x[3] = {p0->fixed_x, p1->fixed_x, p2->fixed_x};
    const int64_t fixed_y[3] = {p0->fixed_y, p1->fixed_y, p2->fixed_y};

    /* The pixels whose centre (x + 0.5, y + 0.5) can be inside: centre X =
     * 256 x + 128 must lie within [min X, max X]. With four samples, the
     * pixels one of whose samples can be: 256 x + 32 <= max X and
     * 256 x + 224 >= min X (luz_sample_reach_low, _high). */
    int64_t min_fx = fixed_x[0], max_fx = fixed_x[0], min_fy = fixed_y[0], max_fy = fixed_y[0];
    for (int k = 1; k < 3; k++) {
        if (fixed_x[k] < min_fx) min_fx = fixed_x[k];
        if (fixed_x[k] > max_fx) max_fx = fixed_x[k];
        if (fixed_y[k] < min_fy) min_fy = fixed_y[k];
        if (fixed_y[k] > max_fy) max_fy = fixed_y[k];
    }
    const int64_t low = luz_sample_reach_low(samples), high = luz_sample_reach_high(samples);
    int64_t min_x = luz_ceil_divide(min_fx - high, LUZ_SUBPIXEL_ONE);
    int64_t max_x = luz_floor_divide(max_fx - low, LUZ_SUBPIXEL_ONE);
    int64_t min_y = luz_ceil_divide(min_fy - high, LUZ_SUBPIXEL_ONE);
    int64_t max_y = luz_floor_divide(max_fy - low, LUZ_SUBPIXEL_ONE);
    if (min_x < 0) min_x = 0;
    if (min_y < 0) min_y = 0;
    if (max_x > width - 1) max_x = width - 1;
    if (max_y > height - 1) max_y = height - 1;
    if (min_x > max_x || min_y > max_y) return LUZ_SETUP_OFFSCREEN;
    out->min_x = (int)min_x;
    out->max_x = (int)max_x;
    out->min_y = (int)min_y;
    out->max_y = (int)max_y;

    /* 4. Edge k is opposite vertex k. */
    out->edges[0] = make_edge(fixed_x[1], fixed_y[1], fixed_x[2], fixed_y[2], bottom_right);
    out->edges[1] = make_edge(fixed_x[2], fixed_y[2], fixed_x[0], fixed_y[0], bottom_right);
    out->edges[2] = make_edge(fixed_x[0], fixed_y[0], fixed_x[1], fixed_y[1], bottom_right);

    /* A small triangle often covers no pixel centre at all (a triangle of
     * a million-triangle mesh is about a pixel in size, and half of those
     * fall between centres). Its planes would never be read: test the few
     * centres of its box with the rasteriser's own E >= 0 and drop it as
     * if it were off screen. Screening may have tested a box of up to 2 x 2
     * already (small_box_checked). */
    const bool up_to_2x2 = max_x - min_x <= 1 && max_y - min_y <= 1;
    if ((max_x - min_x + 1) * (max_y - min_y + 1) <= LUZ_SETUP_SMALL_BOX_PIXELS &&
        !(small_box_checked && up_to_2x2) &&
        !(samples == 1 ? covers_a_centre(out) : covers_a_sample(out, samples)))
        return LUZ_SETUP_OFFSCREEN;
    if (samples == 1 && up_to_2x2) narrow_to_one_centre(out);

    /* 5. Planes. Snapping is for coverage only: the planes are solved from
     * the exact window positions (as llvmpipe's lp_setup_tri.c does), or
     * every varying would be read as if its vertices had moved by up to
     * 1/512 pixel, enough to flip a nearest-filtered texel. They are stored
     * relative to the snapped vertex 0, which a float holds exactly. */
    luz_plane_basis basis;
    if (!luz_plane_basis_of(p0, p1, p2, &basis)) return LUZ_SETUP_CULLED;
    out->reference_x = (float)basis.rx;
    out->reference_y = (float)basis.ry;
    out->depth = luz_plane_through(&basis, p0->depth, p1->depth, p2->depth);
    /* 1/w and the varyings: planes.c's, which can solve them again later
     * from the mesh triangle alone. */
    luz_shading_planes shading;
    luz_planes_solve(&basis, p0, p1, p2, v0, v1, v2, interpolation, &shading);
    out->inverse_w = shading.inverse_w;
    memcpy(out->varyings, shading.varyings, sizeof out->varyings);
    out->draw_index = draw_index;
    return LUZ_SETUP_VISIBLE;
}

luz_setup_result luz_setup_projected(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                     const luz_clip_vertex *v2, const luz_window_vertex *p0,
                                     const luz_window_vertex *p1, const luz_window_vertex *p2,
                                     int width, int height, uint32_t draw_index,
                                     luz_interpolation interpolation, bool small_box_checked,
                                     luz_triangle *out)
{
    return setup_projected(v0, v1, v2, p0, p1, p2, width, height, draw_index, interpolation,
                           small_box_checked, 1, false, out);
}

luz_setup_result luz_setup_projected_samples(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                             const luz_clip_vertex *v2,
                                             const luz_window_vertex *p0,
                                             const luz_window_vertex *p1,
                                             const luz_window_vertex *p2, int width, int height,
                                             uint32_t draw_index, luz_interpolation interpolation,
                                             bool small_box_checked, int samples,
                                             luz_triangle *out)
{
    if (samples <= 1)
        return luz_setup_projected(v0, v1, v2, p0, p1, p2, width, height, draw_index,
                                   interpolation, small_box_checked, out);
    return setup_projected(v0, v1, v2, p0, p1, p2, width, height, draw_index, interpolation,
                           small_box_checked, samples, false, out);
}

luz_setup_result luz_setup_projected_bug(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                         const luz_clip_vertex *v2, const luz_window_vertex *p0,
                                         const luz_window_vertex *p1,
                                         const luz_window_vertex *p2, int width, int height,
                                         uint32_t draw_index, luz_interpolation interpolation,
                                         int samples, luz_bug bug, luz_triangle *out)
{
    /* no-backface-culling: a back face is a front face with two corners
     * traded, the same triangle on the screen, its varyings carried
     * along. */
    if (bug == LUZ_BUG_NO_BACKFACE_CULLING && !luz_setup_front_facing(p0, p1, p2)) {
        const luz_clip_vertex *v = v1;
        const luz_window_vertex *p = p1;
        v1 = v2, p1 = p2;
        v2 = v, p2 = p;
    }
    return setup_projected(v0, v1, v2, p0, p1, p2, width, height, draw_index, interpolation,
                           false, samples > 1 ? samples : 1,
                           bug == LUZ_BUG_FILL_RULE_BOTTOM_RIGHT, out);
}

luz_setup_result luz_setup_triangle_bug(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                        const luz_clip_vertex *v2, int width, int height,
                                        uint32_t draw_index, luz_interpolation interpolation,
                                        int samples, luz_bug bug, luz_triangle *out)
{
    luz_clip_vertex vertices[3] = {*v0, *v1, *v2};
    luz_window_vertex window[3];
    for (int k = 0; k < 3; k++) vertices[k].outcode = 0;   /* project all three */
    luz_setup_project(vertices, 0, 3, width, height, window, NULL);
    return luz_setup_projected_bug(v0, v1, v2, &window[0], &window[1], &window[2], width,
                                   height, draw_index, interpolation, samples, bug, out);
}

luz_setup_result luz_setup_triangle_samples(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                            const luz_clip_vertex *v2, int width, int height,
                                            uint32_t draw_index, luz_interpolation interpolation,
                                            int samples, luz_triangle *out)
{
    luz_clip_vertex vertices[3] = {*v0, *v1, *v2};
    luz_window_vertex window[3];
    for (int k = 0; k < 3; k++) vertices[k].outcode = 0;   /* project all three */
    luz_setup_project(vertices, 0, 3, width, height, window, NULL);
    return luz_setup_projected_samples(v0, v1, v2, &window[0], &window[1], &window[2], width,
                                       height, draw_index, interpolation, false, samples, out);
}

luz_setup_result luz_setup_triangle(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                    const luz_clip_vertex *v2, int width, int height,
                                    uint32_t draw_index, luz_interpolation interpolation,
                                    luz_triangle *out)
{
    return luz_setup_triangle_samples(v0, v1, v2, width, height, draw_index, interpolation, 1,
                                      out);
}

const char *luz_interpolation_name(luz_interpolation interpolation)
{
    switch (interpolation) {
    case LUZ_INTERPOLATION_PERSPECTIVE: return "perspective";
    case LUZ_INTERPOLATION_AFFINE: return "affine";
    }
    return "unknown";
}
