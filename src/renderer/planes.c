/*
 * planes.c: a triangle's shading planes, the 1/w plane and one plane per
 * varying (setup.c's step 5 but for depth), solved from its corners.
 *
 * In:  the three corners of a triangle as setup sees them: their exact
 *      window positions, 1/w and depth (luz_window_vertex, from
 *      luz_setup_project_vertex) and their varyings (luz_clip_vertex);
 *      or a draw's mesh triangle (its transforms, index buffer and
 *      primitive number), whose corners are run through the vertex stage
 *      and projected again here (luz_planes_of_primitive).
 * Out: the plane basis (the corners' positions, 1 / the determinant, the
 *      reference point: luz_plane_basis_of) and the planes
 *      (luz_shading_planes): the same bits as the record setup.c, setup in
 *      lanes (setup_eight.c, setup_lanes.c) write for that triangle.
 *
 * Why a stage of its own: the raster stage reads a record's box, edges,
 * reference point and depth plane (84 bytes); the 1/w and varying planes
 * (108 bytes) are read only by the stages that shade a pixel the triangle
 * won (fragment.c, fragment_packet.c, view.c, probe.c), yet setup writes
 * them for every triangle and the frame reads them back from memory: on
 * the 1M-triangle sphere 238k records of 200 bytes a frame (issue 29,
 * "a slim raster record"; docs/pipeline.md, "Slim raster records"). Here
 * they can be solved later, only for triangles that won a pixel, from
 * (draw, primitive) alone, with setup's own operations, so the image
 * stays the same bytes. setup.c solves its records' planes through this
 * file: there is one copy of the arithmetic.
 *
 * The arithmetic (setup.c, step 5): each plane through (x_k, y_k, v_k) by
 * Cramer's rule on the two edge vectors, in double, no fused multiply-add
 * (-ffp-contract=off), then rounded to float as a C cast does; its value
 * given at the reference point, the snapped vertex 0, which a float holds
 * exactly. For perspective-correct interpolation the planes are of 1/w
 * and of each varying times 1/w (Heckbert and Moreton, "Interpolation for
 * polygon texture mapping and shading"); for affine, of 1 and of each
 * varying.
 *
 * A mesh triangle that crossed a clip plane became a fan of new
 * triangles (clip.c) whose corners are not the mesh's: its planes cannot
 * be found from (draw, primitive), and luz_planes_of_primitive says so
 * (LUZ_PLANES_CLIPPED).
 */
#include <math.h>
#include <string.h>

#include "renderer/pipeline.h"

bool luz_plane_basis_of(const luz_window_vertex *p0, const luz_window_vertex *p1,
                        const luz_window_vertex *p2, luz_plane_basis *out)
{
    const double x[3] = {p0->x, p1->x, p2->x}, y[3] = {p0->y, p1->y, p2->y};
    const double determinant = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (!(determinant != 0.0) || !isfinite(determinant)) return false;
    memcpy(out->x, x, sizeof x);
    memcpy(out->y, y, sizeof y);
    out->inverse_determinant = 1.0 / determinant;
    /* fixed / 256: exact, a power of two. */
    out->rx = (double)p0->fixed_x / LUZ_SUBPIXEL_ONE;
    out->ry = (double)p0->fixed_y / LUZ_SUBPIXEL_ONE;
    return true;
}

/* The nine planes of a triangle set up one at a time. Compiled once, for
 * the build's target: a big mesh's triangles are set up in lanes (cpu.h's
 * table), which solve their planes themselves. */
static void solve_planes(const luz_plane_basis *basis, const double inverse_w[3],
                         const float *varyings0, const float *varyings1, const float *varyings2,
                         luz_interpolation interpolation, luz_shading_planes *out)
{
    /* The weight each vertex's varyings are divided by: 1/w for
     * perspective-correct interpolation, 1 for affine. */
    double weight[3] = {inverse_w[0], inverse_w[1], inverse_w[2]};
    if (interpolation == LUZ_INTERPOLATION_AFFINE) weight[0] = weight[1] = weight[2] = 1.0;
    out->inverse_w = luz_plane_through(basis, weight[0], weight[1], weight[2]);
    for (int i = 0; i < LUZ_VARYING_COUNT; i++)
        out->varyings[i] = luz_plane_through(basis, varyings0[i] * weight[0],
                                             varyings1[i] * weight[1], varyings2[i] * weight[2]);
}

void luz_planes_solve(const luz_plane_basis *basis, const luz_window_vertex *p0,
                      const luz_window_vertex *p1, const luz_window_vertex *p2,
                      const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                      const luz_clip_vertex *v2, luz_interpolation interpolation,
                      luz_shading_planes *out)
{
    const double inverse_w[3] = {p0->inverse_w, p1->inverse_w, p2->inverse_w};
    solve_planes(basis, inverse_w, v0->varyings, v1->varyings, v2->varyings, interpolation, out);
}

luz_planes_result luz_planes_of_primitive(const luz_draw_transform *transform,
                                          const uint32_t *indices, uint32_t primitive, int width,
                                          int height, luz_interpolation interpolation, luz_bug bug,
                                          luz_shading_planes *out)
{
    luz_clip_vertex corner[3];
    luz_window_vertex window[3];
    for (int k = 0; k < 3; k++) {
        corner[k] = luz_vertex_stage_one_bug(transform, bug, indices[3 * (size_t)primitive + k]);
        if (corner[k].outcode != 0) return LUZ_PLANES_CLIPPED;
        window[k] = luz_setup_project_vertex(&corner[k], width, height);
    }
    /* luz/bug.h's no-backface-culling sets a back face up with corners 1
     * and 2 traded (luz_setup_projected_bug): so are its planes. */
    int second = 1, third = 2;
    if (bug == LUZ_BUG_NO_BACKFACE_CULLING &&
        !luz_setup_front_facing(&window[0], &window[1], &window[2]))
        second = 2, third = 1;
    luz_plane_basis basis;
    if (window[0].fixed_x == LUZ_WINDOW_INVALID || window[1].fixed_x == LUZ_WINDOW_INVALID ||
        window[2].fixed_x == LUZ_WINDOW_INVALID ||
        !luz_plane_basis_of(&window[0], &window[second], &window[third], &basis))
        return LUZ_PLANES_NONE;
    luz_planes_solve(&basis, &window[0], &window[second], &window[third], &corner[0],
                     &corner[second], &corner[third], interpolation, out);
    return LUZ_PLANES_SOLVED;
}
