/*
 * pipeline.h: the stages of luz's pipeline and the plain structs that flow
 * between them. Private to the library (and its tests).
 *
 *   luz_draw (mesh + model + material)                   luz/frame.h
 *     -> vertex.c    luz_vertex_stage: a luz_clip_vertex per mesh vertex
 *                                                        clip space + varyings
 *                    (vertex_sixteen.c: the same and luz_setup_project's
 *                    projection for 16 vertices at a time, or positions
 *                    alone: setup_eight.c shades the corners it sets up)
 *     -> clip.c      luz_clip_triangle: a luz_clip_polygon per triangle that
 *                    crosses a plane (the others pass)   inside the clip volume
 *     -> setup.c     luz_setup_project: a luz_window_vertex per vertex
 *                                                        divided, viewport, snapped
 *     -> screen.c    screening: the triangles setup would drop without
 *                    a record (back faces, no pixel centre), 16 at a time
 *                    luz_setup_projected: a luz_triangle per fan triangle
 *                                                        fixed-point edges, planes
 *                    (setup_eight.c: the same for 8 triangles at a time)
 *     -> raster.c    luz_raster_triangle: depth + visibility per pixel
 *                                                        who is nearest
 *     -> fragment.c  colour per visible pixel            interpolate, sample, shade
 *                      (texture.c samples; the six light terms are the
 *                      inline functions of luz/shade.h; fragment_packet.c
 *                      does the same for a packet of a row's pixels, as
 *                      many as the vectors of the set cpu.c picked hold,
 *                      held to fragment.c by its test)
 *     -> resolve.c   four samples a pixel: the samples'  one colour a pixel
 *                    winners sorted, then averaged
 *     or view.c      a picture of a stage (--view)       depth, normals, uv, ...
 *     and probe.c    one pixel explained (luz/probe.h)   the same functions again
 *
 * frame.c's luz_renderer_draw runs them in that order, in two phases:
 * geometry.c's luz_geometry_run the vertex stage, clipping, screening and
 * setup, in batches over the threads, and bins each band's triangles;
 * then frame.c's band_job the rest for a band of rows. bands.c spreads
 * the jobs over threads. Each stage is a function of its inputs: no
 * globals.
 */
#ifndef LUZ_PIPELINE_H
#define LUZ_PIPELINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "luz/framebuffer.h"
#include "luz/frame.h"
#include "luz/probe.h"
#include "luz/renderer.h"
#include "luz/shade.h"
#include "luz/vecmath.h"

/* ---- meshes (mesh.c) ----------------------------------------------------- */

/* A mesh as luz_mesh_create made it: its own copies of the arrays, checked,
 * with 32-bit indices whatever the caller gave. */
struct luz_mesh {
    luz_vertex *vertices;
    uint32_t vertex_count;
    uint32_t *indices;
    uint32_t index_count;
    luz_bounds bounds;
};

/* ---- the frame's uniforms (frame.c) --------------------------------------- */

/* What every stage reads that is the same for the whole frame, worked out
 * once from the frame and the render options. */
typedef struct luz_uniforms {
    luz_mat4 view_projection;
    luz_mat4 projection;               /* the depth view reads its z row */
    luz_mat4 view;                     /* the probe reports it */
    luz_shade_uniforms shade;          /* eye, lights, the spot's cosines */
    luz_vec3 clear_colour;
    /* The output of lit colours (luz_shade_output): 2^EV, the tone map,
     * and whether the two leave the colour as it is (clamp at EV 0), when
     * the fragment stages skip them. */
    float output_exposure;             /* EV, as the frame gives it */
    float exposure_scale;
    luz_tone_map tone_map;
    bool output_is_identity;
    luz_view show;                     /* what the colour buffer shows */
    luz_interpolation interpolation;   /* read by setup.c */
    int samples;                       /* a pixel's samples: 1 or 4 (the
                                          frame's; 0 read as 1) */
    luz_bug bug;                       /* the render options' (luz/bug.h):
                                          with one on, the plain paths run */
} luz_uniforms;

/* NULL options are the defaults. */
luz_uniforms luz_uniforms_of(const luz_frame *frame, const luz_render_options *options);

/* ---- vertex stage ------------------------------------------------------ */

/* The varyings: what is interpolated across a triangle for the fragment
 * shader. World-space position and normal, and texture coordinates. */
enum {
    LUZ_VARYING_POSITION = 0,   /* x, y, z */
    LUZ_VARYING_NORMAL = 3,     /* x, y, z */
    LUZ_VARYING_UV = 6,         /* u, v */
    LUZ_VARYING_COUNT = 8
};

typedef struct luz_clip_vertex {
    luz_vec4 position;                       /* clip space */
    float varyings[LUZ_VARYING_COUNT];
    unsigned outcode;                        /* luz_clip_outcode(position), once
                                                per vertex, not per triangle */
} luz_clip_vertex;

/* Transforms every vertex of draw->mesh: out[i] gets clip-space position
 * view_projection * model * p, its outcode and world-space varyings. */
void luz_vertex_stage(const luz_draw *draw, luz_mat4 view_projection, luz_clip_vertex *out);
/* The same for vertices [first, end) only: out[i] for i in that range (out
 * is still the place of vertex 0), so that ranges of one big mesh can run
 * on different threads. */
void luz_vertex_stage_range(const luz_draw *draw, luz_mat4 view_projection, uint32_t first,
                            uint32_t end, luz_clip_vertex *out);

/* What the vertex stage applies to a draw's vertices: its mesh, model
 * matrix and normal matrix (worked out once), and the frame's
 * projection * view. */
typedef struct luz_draw_transform {
    const luz_vertex *vertices;   /* the mesh's */
    luz_mat4 model;
    luz_mat3 normal_matrix;
    luz_mat4 view_projection;
} luz_draw_transform;

luz_draw_transform luz_draw_transform_of(const luz_draw *draw, luz_mat4 view_projection);
/* Mesh vertex i through the vertex stage: the luz_clip_vertex that
 * luz_vertex_stage gives it, for a stage that needs a few vertices, not
 * the draw's (setup of the corners a big draw's vertex pass did not keep,
 * geometry.c). */
luz_clip_vertex luz_vertex_stage_one(const luz_draw_transform *transform, uint32_t i);

/* The vertex stage with a bug of luz/bug.h in (normal-matrix-is-model is
 * the vertex stage's; any other bug gives luz_vertex_stage_range and
 * luz_vertex_stage_one's vertices): a frame with a bug runs these, never
 * the stage in lanes. */
void luz_vertex_stage_bug(const luz_draw *draw, luz_mat4 view_projection, luz_bug bug,
                          uint32_t first, uint32_t end, luz_clip_vertex *out);
luz_clip_vertex luz_vertex_stage_one_bug(const luz_draw_transform *transform, luz_bug bug,
                                         uint32_t i);

/* ---- clipping ---------------------------------------------------------- */

/* x and y are clipped to a guard band GUARD times wider than the viewport,
 * which keeps window coordinates inside the range setup.c proves safe. */
#define LUZ_CLIP_GUARD_BAND 4.0f
#define LUZ_CLIP_PLANE_COUNT 6
/* Each plane can add one vertex to a convex polygon. */
#define LUZ_CLIP_MAX_VERTICES (3 + LUZ_CLIP_PLANE_COUNT)

typedef struct luz_clip_polygon {
    int vertex_count;
    luz_clip_vertex vertices[LUZ_CLIP_MAX_VERTICES];
} luz_clip_polygon;

/* One bit per clip plane the point is outside of (0: inside them all):
 * bit k for plane k of clip.c's plane_distance, the same distances
 * (near, far, left, right, bottom, top). Inline: the vertex stage computes
 * it for every vertex. "!(d >= 0)" so that a NaN coordinate counts as
 * outside. */
static inline unsigned luz_clip_outcode(luz_vec4 p)
{
    const float guard = LUZ_CLIP_GUARD_BAND;
    return (unsigned)!(p.w + p.z >= 0.0f) << 0 | (unsigned)!(p.w - p.z >= 0.0f) << 1 |
           (unsigned)!(guard * p.w + p.x >= 0.0f) << 2 |
           (unsigned)!(guard * p.w - p.x >= 0.0f) << 3 |
           (unsigned)!(guard * p.w + p.y >= 0.0f) << 4 |
           (unsigned)!(guard * p.w - p.y >= 0.0f) << 5;
}

/* Sutherland-Hodgman: clips triangle (a, b, c) against the near, far and
 * guard-band planes. Returns the number of vertices of the result (0 if
 * nothing is left); the polygon is convex and keeps the winding. */
int luz_clip_triangle(const luz_clip_vertex *a, const luz_clip_vertex *b,
                      const luz_clip_vertex *c, luz_clip_polygon *out);

/* ---- samples (SCENE.md, "Anti-aliasing: four samples a pixel") ----------- */

#define LUZ_MAX_SAMPLES 4

/* Where sample k of a pixel lies, from the pixel's top-left corner, in
 * 1/256 of a pixel (the sub-pixel grid): one sample at the centre (128,
 * 128), or the standard 4x pattern (0.375, 0.125), (0.875, 0.375),
 * (0.125, 0.625), (0.625, 0.875), Mesa llvmpipe's, which are exact in
 * that grid (96/256 = 0.375, ...). */
typedef struct luz_sample_offset {
    int32_t x, y;
} luz_sample_offset;

static inline luz_sample_offset luz_sample_offset_of(int samples, int k)
{
    if (samples != 4) return (luz_sample_offset){128, 128};
    const luz_sample_offset four[4] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};
    return four[k & 3];
}

/* The nearest and farthest a sample lies from a pixel's left (or top)
 * edge, over the pattern's samples (setup's box of pixels a triangle may
 * cover): 128 and 128 for one sample, 32 and 224 for four. */
static inline int32_t luz_sample_reach_low(int samples)
{
    return samples == 4 ? 32 : 128;
}

static inline int32_t luz_sample_reach_high(int samples)
{
    return samples == 4 ? 224 : 128;
}

/* ---- triangle setup ---------------------------------------------------- */

/* Window coordinates are snapped to 1/256 of a pixel (8 bits of sub-pixel
 * precision, as llvmpipe). */
#define LUZ_SUBPIXEL_BITS 8
#define LUZ_SUBPIXEL_ONE (1 << LUZ_SUBPIXEL_BITS)

/* floor(a / b) and ceil(a / b) for b > 0, exactly; C's "/" truncates
 * towards 0, which is wrong for negative a. Setup and raster use them to
 * turn fixed-point positions into pixel ranges. */
static inline int64_t luz_floor_divide(int64_t a, int64_t b)
{
    int64_t quotient = a / b;
    return (a % b != 0 && a < 0) ? quotient - 1 : quotient;
}

static inline int64_t luz_ceil_divide(int64_t a, int64_t b)
{
    return -luz_floor_divide(-a, b);
}

/* An edge function E(X, Y) = a X + b Y + c in fixed-point units, positive
 * inside; the top-left rule is folded into c, so a sample is covered by
 * the edge exactly when E >= 0. a and b are differences of coordinates of
 * at most 2^24 in magnitude (setup.c), so they fit 32 bits; c and E need
 * 64 (each product is taken in 64 bits). 16 bytes an edge, not 24: the
 * record of a triangle is written once and read twice a frame. */
typedef struct luz_edge {
    int32_t a, b;
    int64_t c;
} luz_edge;

/* Whether the point (X, Y) in fixed-point units (a pixel centre or a
 * sample point) is covered: E >= 0 for all three edges, each product in
 * 64 bits. The test of setup's coverage checks, the raster's samples one
 * by one and the views' (the raster's rows compute the same values a row
 * at a time, and its lanes in 32 bits where they fit). */
static inline bool luz_edges_cover(const luz_edge edges[3], int64_t x, int64_t y)
{
    bool inside = true;
    for (int k = 0; k < 3; k++)
        inside &= (int64_t)edges[k].a * x + (int64_t)edges[k].b * y + edges[k].c >= 0;
    return inside;
}

/* A quantity that varies linearly across the screen: its value at the
 * triangle's reference point (vertex 0) and its screen-space gradient. */
typedef struct luz_plane {
    float value, dx, dy;
} luz_plane;

typedef struct luz_triangle {
    int min_x, min_y, max_x, max_y;  /* pixels that may be covered, inclusive;
                                        one sample a pixel: a box of up to
                                        2 x 2 with one centre covered is that
                                        pixel (setup.c's narrow_to_one_centre) */
    luz_edge edges[3];
    float reference_x, reference_y;  /* vertex 0 in window coordinates */
    luz_plane depth;                 /* window depth, linear on the screen */
    luz_plane inverse_w;             /* 1/w, linear on the screen */
    luz_plane varyings[LUZ_VARYING_COUNT];  /* varying/w, linear on the screen */
    uint32_t draw_index;
    uint32_t primitive;              /* the mesh triangle it came from (index / 3);
                                        set by geometry.c, not setup, which sees
                                        only vertices */
} luz_triangle;

typedef enum luz_setup_result {
    LUZ_SETUP_VISIBLE,
    LUZ_SETUP_CULLED,      /* back face or zero area */
    LUZ_SETUP_OFFSCREEN,   /* covers no pixel centre of the viewport */
} luz_setup_result;

/* A vertex after setup's steps 1 and 2 (divide, viewport, snap), which
 * depend on the vertex alone: done once per vertex rather than once per
 * triangle corner (a vertex of a closed mesh is a corner of six). Doubles:
 * the planes are solved from these exact positions. */
typedef struct luz_window_vertex {
    double x, y;                /* window position, clamped to the fixed-point range */
    double depth;               /* window depth, (z_ndc + 1) / 2 */
    double inverse_w;           /* 1 / w */
    int32_t fixed_x, fixed_y;   /* x, y snapped to 1/256 pixel (|X| <= 2^24) */
} luz_window_vertex;

/* A vertex's snapped position alone, 8 bytes: what screening (screen.c)
 * reads of each corner of every triangle, packed so that a million
 * triangles' corners are a few megabytes of cache, not forty. x holds the
 * same markers as luz_window_vertex's fixed_x. */
typedef struct luz_fixed_vertex {
    int32_t x, y;
} luz_fixed_vertex;

/* Window coordinates are clamped to +-2^24 sub-pixel units (setup.c,
 * vertex_sixteen.c): beyond the guard band, a bound that rounding can't
 * leave and that keeps setup.c's proof true for any input. */
#define LUZ_COORDINATE_LIMIT 16777216.0

/* fixed_x of a vertex with w <= 0 (or NaN) or an x, y or z that is not
 * finite: setup culls its triangles. (An infinite w passes, as it always
 * did: 1/w is 0.) */
#define LUZ_WINDOW_INVALID INT32_MIN
/* fixed_x of a vertex outside a clip plane (a non-zero outcode): only the
 * clipper reads such a vertex, and it projects its own; the marker tells
 * screening (screen.c) to leave the triangle to it. */
#define LUZ_WINDOW_CLIPPED (INT32_MIN + 1)

/* Step 3 of setup alone: whether the projected triangle (p0, p1, p2) is a
 * front face, with a positive doubled area in fixed point (setup.c), and
 * its three vertices valid. luz_setup_projected culls by it; inline, so
 * that geometry.c drops a back face, half of a closed mesh, before it
 * pays for the call. |X| <= 2^24, so each product is at most 2^50. */
static inline bool luz_setup_front_facing(const luz_window_vertex *p0,
                                          const luz_window_vertex *p1,
                                          const luz_window_vertex *p2)
{
    if (p0->fixed_x == LUZ_WINDOW_INVALID || p1->fixed_x == LUZ_WINDOW_INVALID ||
        p2->fixed_x == LUZ_WINDOW_INVALID)
        return false;
    const int64_t doubled_area =
        ((int64_t)p1->fixed_y - p0->fixed_y) * ((int64_t)p2->fixed_x - p0->fixed_x) -
        ((int64_t)p1->fixed_x - p0->fixed_x) * ((int64_t)p2->fixed_y - p0->fixed_y);
    return doubled_area > 0;
}

/* Projects one vertex for a width x height viewport (setup's steps 1
 * and 2: divide, viewport, snap); a vertex with a non-zero outcode is
 * only marked, fixed_x = LUZ_WINDOW_CLIPPED (its triangles go to the
 * clipper, whose polygon vertices are projected afresh), one that cannot
 * be projected LUZ_WINDOW_INVALID; a marked vertex's other fields are 0. */
luz_window_vertex luz_setup_project_vertex(const luz_clip_vertex *vertex, int width, int height);
/* The same for vertices[first, end): into out[first, end) and its snapped
 * positions into fixed[first, end), each unless NULL. */
void luz_setup_project(const luz_clip_vertex *vertices, uint32_t first, uint32_t end, int width,
                       int height, luz_window_vertex *out, luz_fixed_vertex *fixed);

/* Sets up triangle (v0, v1, v2), projected as (p0, p1, p2) by
 * luz_setup_project, for a width x height viewport. small_box_checked:
 * the caller knows that if the triangle's box holds at most 2 x 2 pixel
 * centres, one of them is covered (screening checked it, screen.c),
 * so setup does not test them again; false: setup tests. */
luz_setup_result luz_setup_projected(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                     const luz_clip_vertex *v2, const luz_window_vertex *p0,
                                     const luz_window_vertex *p1, const luz_window_vertex *p2,
                                     int width, int height, uint32_t draw_index,
                                     luz_interpolation interpolation, bool small_box_checked,
                                     luz_triangle *out);

/* The same for a pixel of `samples` samples (1 or 4): the box holds the
 * pixels one of whose samples may be inside, and a small triangle is kept
 * if it covers one of its box's samples (small_box_checked: screening for
 * that many samples, luz_kernels' screen_four, has tested a box of up to
 * 2 x 2 pixels). samples 1 is luz_setup_projected. */
luz_setup_result luz_setup_projected_samples(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                             const luz_clip_vertex *v2,
                                             const luz_window_vertex *p0,
                                             const luz_window_vertex *p1,
                                             const luz_window_vertex *p2, int width, int height,
                                             uint32_t draw_index, luz_interpolation interpolation,
                                             bool small_box_checked, int samples,
                                             luz_triangle *out);

/* luz_setup_projected_samples with a bug of luz/bug.h in: with
 * no-backface-culling a back face is set up with v1 and v2 traded (a
 * front face over the same pixels), with fill-rule-bottom-right the
 * samples on a bottom or right edge are covered, not those on a top or
 * left one; any other bug sets up as luz_setup_projected_samples does. A
 * frame with a bug sets up every triangle this way (geometry.c), and the
 * probe finds them again through luz_setup_triangle_bug. */
luz_setup_result luz_setup_projected_bug(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                         const luz_clip_vertex *v2, const luz_window_vertex *p0,
                                         const luz_window_vertex *p1,
                                         const luz_window_vertex *p2, int width, int height,
                                         uint32_t draw_index, luz_interpolation interpolation,
                                         int samples, luz_bug bug, luz_triangle *out);
luz_setup_result luz_setup_triangle_bug(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                        const luz_clip_vertex *v2, int width, int height,
                                        uint32_t draw_index, luz_interpolation interpolation,
                                        int samples, luz_bug bug, luz_triangle *out);

/* Projects, snaps and sets up triangle (v0, v1, v2) for a width x height
 * viewport: luz_setup_project and luz_setup_projected in one. With
 * LUZ_INTERPOLATION_AFFINE the varying planes hold the varyings
 * themselves and inverse_w is the constant 1 (the teaching toggle); the
 * fragment stages read both kinds the same way. */
luz_setup_result luz_setup_triangle(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                    const luz_clip_vertex *v2, int width, int height,
                                    uint32_t draw_index, luz_interpolation interpolation,
                                    luz_triangle *out);
/* The same for pixels of `samples` samples (luz_setup_projected_samples). */
luz_setup_result luz_setup_triangle_samples(const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                                            const luz_clip_vertex *v2, int width, int height,
                                            uint32_t draw_index, luz_interpolation interpolation,
                                            int samples, luz_triangle *out);

/* ---- the shading planes (planes.c) ---------------------------------------- */

/* What the stages that shade a pixel interpolate across a triangle and
 * the raster stage never reads: 1/w and every varying/w (for affine
 * interpolation: 1 and every varying), each a plane through the
 * triangle's reference point (setup.c's step 5). Laid out as the
 * record's inverse_w and varyings. */
typedef struct luz_shading_planes {
    luz_plane inverse_w;
    luz_plane varyings[LUZ_VARYING_COUNT];
} luz_shading_planes;

/* What every plane of a triangle is solved from: its corners' exact
 * window positions, 1 / the determinant of its edge vectors, and the
 * reference point, the snapped vertex 0. */
typedef struct luz_plane_basis {
    double x[3], y[3];
    double inverse_determinant;
    double rx, ry;
} luz_plane_basis;

/* The basis of triangle (p0, p1, p2); false, and out untouched, when no
 * plane can be solved (a determinant of 0 or not finite: setup culls). */
bool luz_plane_basis_of(const luz_window_vertex *p0, const luz_window_vertex *p1,
                        const luz_window_vertex *p2, luz_plane_basis *out);

/* The plane through (x_k, y_k, value_k), k = 0..2 (Cramer's rule on the
 * two edge vectors), given by its value at the reference point, each
 * rounded to float. Inlined, so that the ten planes of a triangle share
 * the differences of x and y (computed once; the arithmetic of each plane
 * is unchanged). setup.c's depth plane and planes.c's others. */
static inline __attribute__((always_inline)) luz_plane
luz_plane_through(const luz_plane_basis *basis, double value0, double value1, double value2)
{
    const double *x = basis->x, *y = basis->y;
    double d1 = value1 - value0, d2 = value2 - value0;
    double dx = (d1 * (y[2] - y[0]) - d2 * (y[1] - y[0])) * basis->inverse_determinant;
    double dy = (d2 * (x[1] - x[0]) - d1 * (x[2] - x[0])) * basis->inverse_determinant;
    luz_plane plane;
    plane.value = (float)(value0 + dx * (basis->rx - x[0]) + dy * (basis->ry - y[0]));
    plane.dx = (float)dx;
    plane.dy = (float)dy;
    return plane;
}

/* The shading planes of triangle (v0, v1, v2), projected as (p0, p1,
 * p2), whose basis is basis: the bits setup writes in its record. */
void luz_planes_solve(const luz_plane_basis *basis, const luz_window_vertex *p0,
                      const luz_window_vertex *p1, const luz_window_vertex *p2,
                      const luz_clip_vertex *v0, const luz_clip_vertex *v1,
                      const luz_clip_vertex *v2, luz_interpolation interpolation,
                      luz_shading_planes *out);

typedef enum luz_planes_result {
    LUZ_PLANES_SOLVED,
    LUZ_PLANES_CLIPPED,   /* a corner outside a clip plane: the records are
                             the clipper's fan, not this triangle */
    LUZ_PLANES_NONE,      /* setup makes no record of it (a corner not
                             projectable, or no plane to solve) */
} luz_planes_result;

/* The shading planes of mesh triangle `primitive` (vertices indices[3
 * primitive ..]) of a draw whose transforms are transform, in a frame of
 * width x height with bug in (luz/bug.h): its corners through the vertex
 * stage and projection again (luz_vertex_stage_one_bug,
 * luz_setup_project_vertex), then luz_planes_solve, with corners 1 and 2
 * traded where no-backface-culling sets a back face up so. SOLVED: the
 * planes of the record setup made of it, bit for bit. */
luz_planes_result luz_planes_of_primitive(const luz_draw_transform *transform,
                                          const uint32_t *indices, uint32_t primitive, int width,
                                          int height, luz_interpolation interpolation, luz_bug bug,
                                          luz_shading_planes *out);

/* ---- rasterisation and depth test -------------------------------------- */

/* The per-pixel arithmetic of the raster stage, shared by raster.c's loops
 * and the pixel probe (probe.c), so that the probe's account of which
 * triangles covered a pixel, at what depth, is the rasteriser's own
 * operations and not a second copy of them. raster.c explains the maths.
 * Always inlined: they are the raster loop's body (GCC 12 leaves the span
 * out of line otherwise, and the raster stage then runs 4% more
 * instructions). */
#define LUZ_RASTER_INLINE static inline __attribute__((always_inline))

/* Narrows [*first, *last] to the x where edge E(x) = e + s x >= 0. */
LUZ_RASTER_INLINE void luz_raster_narrow_span(int64_t e, int64_t s, int64_t *first, int64_t *last)
{
    if (s > 0) {
        int64_t bound = luz_ceil_divide(-e, s);
        if (bound > *first) *first = bound;
    } else if (s < 0) {
        int64_t bound = luz_floor_divide(e, -s);
        if (bound < *last) *last = bound;
    } else if (e < 0) {
        *last = *first - 1;                        /* empty */
    }
}

/* Bounding boxes at most this wide test pixels rather than divide. */
#define LUZ_RASTER_SMALL_SPAN 8

LUZ_RASTER_INLINE bool luz_raster_is_small(const luz_triangle *triangle)
{
    return triangle->max_x - triangle->min_x < LUZ_RASTER_SMALL_SPAN;
}

/* The pixels of row y whose sample at offset (sample.x, sample.y) in
 * 1/256 pixel (luz_sample_offset) the triangle covers, [*first, *last]
 * (empty when *first > *last), for a row y within [min_y, max_y]; small
 * is luz_raster_is_small(triangle), worked out once per triangle. */
LUZ_RASTER_INLINE void luz_raster_row_span_at(const luz_triangle *triangle, int y, bool small,
                                              luz_sample_offset sample, int64_t *first,
                                              int64_t *last)
{
    const int64_t sample_y = (int64_t)y * LUZ_SUBPIXEL_ONE + sample.y;
    *first = triangle->min_x;
    *last = triangle->max_x;
    int64_t e[3], step[3];
    for (int k = 0; k < 3; k++) {
        const luz_edge *edge = &triangle->edges[k];
        /* E at the sample of pixel 0 of this row, and its step per pixel. */
        e[k] = (int64_t)edge->a * sample.x + edge->b * sample_y + edge->c;
        step[k] = (int64_t)edge->a * LUZ_SUBPIXEL_ONE;
    }
    if (small) {
        int64_t covered_first = *last + 1, covered_last = *first - 1;
        for (int64_t x = *first; x <= *last; x++) {
            if (e[0] + step[0] * x >= 0 && e[1] + step[1] * x >= 0 && e[2] + step[2] * x >= 0) {
                if (covered_first > x) covered_first = x;
                covered_last = x;
            }
        }
        *first = covered_first;
        *last = covered_last;
    } else {
        for (int k = 0; k < 3; k++) luz_raster_narrow_span(e[k], step[k], first, last);
    }
}

/* The pixels of row y whose centres the triangle covers: the one-sample
 * span. */
LUZ_RASTER_INLINE void luz_raster_row_span(const luz_triangle *triangle, int y, bool small,
                                           int64_t *first, int64_t *last)
{
    luz_raster_row_span_at(triangle, y, small, (luz_sample_offset){128, 128}, first, last);
}

/* Window depth at the centres of row y, at x = reference_x... */
LUZ_RASTER_INLINE float luz_raster_row_depth(luz_plane depth, float reference_y, int y)
{
    return depth.value + depth.dy * ((float)y + 0.5f - reference_y);
}

/* ... and at the centre of pixel x of that row: one multiply-add a pixel
 * from the row's value, each pixel computed directly so that its value
 * never depends on where a span began. */
LUZ_RASTER_INLINE float luz_raster_depth(luz_plane depth, float reference_x, float row_depth, int x)
{
    return row_depth + depth.dx * ((float)x + 0.5f - reference_x);
}

/* The same two at a sample offset_x, offset_y pixels from the pixel's
 * corner (luz_sample_offset / 256, exact in a float). */
LUZ_RASTER_INLINE float luz_raster_sample_row_depth(luz_plane depth, float reference_y, int y,
                                                    float offset_y)
{
    return depth.value + depth.dy * ((float)y + offset_y - reference_y);
}

LUZ_RASTER_INLINE float luz_raster_sample_depth(luz_plane depth, float reference_x,
                                                float row_depth, int x, float offset_x)
{
    return row_depth + depth.dx * ((float)x + offset_x - reference_x);
}

/* Covers the pixel centres of rows [first_row, end_row) that lie inside the
 * triangle; where a sample is nearer than the depth buffer (LESS), writes
 * its depth and triangle_id into the visibility buffer. Returns the number
 * of depth tests made. */
uint64_t luz_raster_triangle(const luz_triangle *triangle, uint32_t triangle_id,
                             luz_framebuffer *framebuffer, int first_row, int end_row);

/* The same, and adds 1 to overdraw[y * width + x] for every depth test
 * (the overdraw view); the plain function above does no counting. */
uint64_t luz_raster_triangle_counting(const luz_triangle *triangle, uint32_t triangle_id,
                                      luz_framebuffer *framebuffer, int first_row,
                                      int end_row, uint32_t *overdraw);

/* The depth tests of a row's span of pixel centres, x in [first, last]:
 * where luz_raster_depth is LESS than depth_row[x], that and
 * visibility_row[x] take it and triangle_id (cpu.h's table has each
 * instruction set's copy, sample_loops.c). */
typedef void luz_centre_span_function(luz_plane depth, float reference_x, float row_depth,
                                      int first, int last, float *depth_row,
                                      uint32_t *visibility_row, uint32_t triangle_id);

/* luz_raster_triangle, with the rows' long spans (more than 16 pixels)
 * tested by test_span: the same pixels and the same bits. */
uint64_t luz_raster_triangle_spans(const luz_triangle *triangle, uint32_t triangle_id,
                                   luz_framebuffer *framebuffer, int first_row, int end_row,
                                   luz_centre_span_function *test_span);

/* luz/bug.h's no-depth-test: every sample at offset `sample` (one
 * sample: the centre) of rows [first_row, end_row) inside the triangle
 * passes; its winner, visibility[(y * width + x) * stride] (stride 1 for
 * a framebuffer's, the samples a pixel for luz_sample_buffers' from its
 * sample's entry), takes triangle_id, depth is not written; overdraw,
 * if not NULL, counts (overdraw[y * width + x]). Returns the tests made. */
uint64_t luz_raster_triangle_always(const luz_triangle *triangle, uint32_t triangle_id,
                                    uint32_t *visibility, int width, int stride,
                                    luz_sample_offset sample, int first_row, int end_row,
                                    uint32_t *overdraw);

/* ---- four samples: the buffers (frame.c), raster, resolve (resolve.c) --- */

/* What a frame of more than one sample a pixel keeps beside the
 * framebuffer. A pixel's samples lie side by side: sample k of pixel
 * i = y * width + x has its depth at depth[i * LUZ_MAX_SAMPLES + k] and
 * its winner at visibility[i * LUZ_MAX_SAMPLES + k], so that one vector holds the
 * samples of several neighbouring pixels (raster.c), and a pixel's four
 * are one 16-byte load (resolve.c). first_winner is a one-sample
 * visibility buffer of each pixel's first winner, which
 * luz_samples_sort_winners writes and the fragment stage shades. The
 * planes are for the teaching views alone, which shade every sample as a
 * one-sample framebuffer of the image's size: plane[k]'s depth and
 * visibility are sample k's (copied out of the side-by-side arrays by
 * luz_samples_split_rows), its colour sample k's colour; they are
 * allocated only when a view asks. */
typedef struct luz_sample_buffers {
    int samples;                               /* 1 (none of this is used) or 4 */
    int width, height;                         /* the framebuffer's */
    float *depth;                              /* width * height * 4 */
    uint32_t *visibility;                      /* width * height * 4 */
    uint32_t *first_winner;                    /* width * height */
    luz_framebuffer plane[LUZ_MAX_SAMPLES];    /* the views' */
} luz_sample_buffers;

/* Depth 1.0 and winner 0 for every sample of rows [first_row, end_row). */
void luz_samples_clear_rows(luz_sample_buffers *buffers, int first_row, int end_row);

/* The views' planes of rows [first_row, end_row): plane[k]'s depth and
 * visibility become sample k's. */
void luz_samples_split_rows(luz_sample_buffers *buffers, int first_row, int end_row);

/* The pixels of a row that raster_lanes.c tests together, their four
 * samples each. */
#define LUZ_RASTER_GROUP_PIXELS 4

/* raster_lanes.c's kernel, one per instruction set (cpu.h): the samples of
 * rows [y_begin, y_end) (within the triangle's box) of a triangle, in
 * buffers at least LUZ_RASTER_GROUP_PIXELS wide, small when the
 * triangle's box is (luz_raster_is_small; the kernel checks whether its
 * edge functions stay below 2^30 there, raster.c). Returns the tests
 * made. */
typedef uint64_t luz_raster_groups_function(const luz_triangle *triangle, uint32_t triangle_id,
                                            luz_sample_buffers *buffers, int y_begin, int y_end,
                                            bool small);

/* The same kernel for a band's list of triangles in one call: by_id[ids[k]]
 * for k in [begin, end), each with id ids[k], the rows [first_row,
 * end_row) of its box, in list order; buffers at four samples and at
 * least LUZ_RASTER_GROUP_PIXELS wide. The same depths, winners and test
 * count as luz_raster_triangle_samples on each in turn: on pixel-sized
 * triangles a call's fixed cost (the lanes' constants, the count summed
 * across the lanes) was a fifth of the raster's time. It asks for the
 * records ahead as luz_prefetch_triangle_ahead says. */
typedef uint64_t luz_raster_list_function(const luz_triangle *const *by_id, const uint32_t *ids,
                                          size_t begin, size_t end, luz_sample_buffers *buffers,
                                          int first_row, int end_row);

/* Triangles of a band's list ahead of its raster whose records are
 * prefetched: about the time a line takes to come from memory, at a few
 * tens of nanoseconds a small triangle. */
#define LUZ_PREFETCH_AHEAD 16

/* Before the raster of list entry k of [k, end): each is read through
 * by_id at an address phase 1 wrote long before, scattered (ids rise, but
 * a band's are far apart), which the hardware prefetcher cannot guess, and
 * on a mesh of a million triangles waiting for them was half the raster's
 * time. The list says which come next, so they are asked for ahead:
 * by_id's entry 2 * LUZ_PREFETCH_AHEAD triangles ahead, and the triangle
 * LUZ_PREFETCH_AHEAD ahead, every line of it (the raster reads its box and
 * edges, the fragment stage, after the band's raster, its planes). */
static inline __attribute__((always_inline)) void
luz_prefetch_triangle_ahead(const luz_triangle *const *by_id, const uint32_t *ids, size_t k,
                            size_t end)
{
    if (k + 2 * LUZ_PREFETCH_AHEAD < end) __builtin_prefetch(&by_id[ids[k + 2 * LUZ_PREFETCH_AHEAD]]);
    if (k + LUZ_PREFETCH_AHEAD < end) {
        const char *ahead = (const char *)by_id[ids[k + LUZ_PREFETCH_AHEAD]];
        /* Every line the record touches (200 bytes: at most four). */
        for (size_t offset = 0; offset < sizeof(luz_triangle); offset += 64)
            __builtin_prefetch(ahead + offset);
        __builtin_prefetch(ahead + sizeof(luz_triangle) - 1);
    }
}

/* Whether the raster in lanes (a luz_raster_groups_function or
 * luz_raster_list_function) may test these buffers: four samples, at
 * least LUZ_RASTER_GROUP_PIXELS wide, and no overdraw to count (the
 * kernels count none). One test for raster.c's one triangle and frame.c's
 * band list, so the two paths take the kernels on the same frames. */
static inline bool luz_raster_in_lanes(const luz_sample_buffers *buffers, const uint32_t *overdraw)
{
    return overdraw == NULL && buffers->samples == LUZ_MAX_SAMPLES &&
           buffers->width >= LUZ_RASTER_GROUP_PIXELS;
}

/* Covers every sample of rows [first_row, end_row) inside the triangle
 * (sample k at luz_sample_offset_of(buffers->samples, k)) into buffers'
 * depth and visibility: depth interpolated at the sample, LESS, the
 * winner's id; with groups (a luz_raster_groups_function; NULL: one
 * sample at a time, the plain form); overdraw, if not NULL, counts each
 * sample's depth tests (sample k's count of pixel i at
 * overdraw[k * width * height + i]). Returns the tests made. */
uint64_t luz_raster_triangle_samples(const luz_triangle *triangle, uint32_t triangle_id,
                                     luz_sample_buffers *buffers, int first_row, int end_row,
                                     uint32_t *overdraw, luz_raster_groups_function *groups);

/* A fragment of a list: pixel (x, y) to be shaded as triangle id's, at
 * the pixel centre (the other winners of a pixel whose samples differ,
 * resolve.c). */
typedef struct luz_fragment_ref {
    uint32_t id;
    uint16_t x, y;   /* LUZ_MAX_DIMENSION is 2^14 */
} luz_fragment_ref;
_Static_assert(LUZ_MAX_DIMENSION <= 65536, "a fragment's x and y are 16 bits");

/* A pixel whose samples were not all won by one triangle (or all by
 * none): where each sample's colour comes from. */
enum {
    LUZ_SAMPLE_FROM_CLEAR = 0,    /* no triangle: the clear colour */
    LUZ_SAMPLE_FROM_FIRST = 1,    /* the pixel's first winner: its colour
                                     in the framebuffer */
    /* 2 + j: the pixel's j-th other winner, extra[first_extra + j] */
};

typedef struct luz_mixed_pixel {
    uint32_t index;              /* y * width + x */
    uint32_t first_extra;        /* its other winners in the extra list */
    uint8_t source[LUZ_MAX_SAMPLES];
} luz_mixed_pixel;

/* What luz_samples_sort_winners makes of a pixel's four winners depends
 * only on which samples no triangle won and which pairs one triangle won
 * (not on the ids themselves): ten bits, the key of
 * luz_samples_winner_key. For each key, what the sort writes: each
 * sample's source (as luz_mixed_pixel's), the sample whose winner is the
 * pixel's first, and the samples whose winners are its other winners, in
 * order. */
#define LUZ_WINNER_PATTERNS 1024
typedef struct luz_winner_pattern {
    uint8_t source[LUZ_MAX_SAMPLES];
    uint8_t first;              /* the first sample a triangle won (0 if none) */
    uint8_t extra_count;        /* other winners: 0 to 3 */
    uint8_t extra_sample[3];    /* their samples; 0 past extra_count */
} luz_winner_pattern;

/* Bit k (0 to 3): sample k's winner is 0; bits 4 to 9: the winners of
 * samples (0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3) are equal. */
static inline unsigned luz_samples_winner_key(const uint32_t id[LUZ_MAX_SAMPLES])
{
    return (unsigned)(id[0] == 0) | (unsigned)(id[1] == 0) << 1 | (unsigned)(id[2] == 0) << 2 |
           (unsigned)(id[3] == 0) << 3 | (unsigned)(id[0] == id[1]) << 4 |
           (unsigned)(id[0] == id[2]) << 5 | (unsigned)(id[0] == id[3]) << 6 |
           (unsigned)(id[1] == id[2]) << 7 | (unsigned)(id[1] == id[3]) << 8 |
           (unsigned)(id[2] == id[3]) << 9;
}

/* Every key's pattern, worked out by the sort's definition (one pixel at
 * a time, resolve.c) on winners that have the key. */
void luz_samples_winner_patterns(luz_winner_pattern patterns[LUZ_WINNER_PATTERNS]);

/* The work of a band of four samples a pixel beyond one sample's: its mixed
 * pixels and, in the same order, their other winners to shade. Room for
 * every pixel of a band (BAND_HEIGHT x width), one per thread;
 * extra_colour is zeroed when allocated (the resolve reads a pixel's
 * three entries whether it has them or not, then uses its own). */
typedef struct luz_sample_band {
    luz_mixed_pixel *mixed;
    size_t mixed_count;
    luz_fragment_ref *extra;     /* (pixel, triangle) shaded at the centre */
    uint32_t *extra_colour;      /* their bytes, by the fragment stage */
    size_t extra_count;
    uint16_t *row_mixed;         /* scratch: a row's mixed pixels' x */
    const luz_winner_pattern *patterns;   /* luz_samples_winner_patterns' */
} luz_sample_band;

/* The fragment stage's work for rows [first_row, end_row), from the
 * samples' winners: band gets the mixed pixels (whose four samples were
 * not all won by one triangle, or all by none) and their other winners
 * than the first (each triangle once per pixel, in the order of the
 * samples it first won), and first_winner each pixel's first winner
 * (that of its first sample not background; 0 if all are): the fragment
 * stage shades it as a one-sample visibility buffer. mixed_pixels
 * looks at a row: ids holds its winners, a pixel's four side by side; it
 * writes each pixel's sample 0 into first, the x of the pixels whose four
 * differ into mixed_x, in order, and returns how many (cpu.h's table has
 * each instruction set's copy, sample_loops.c). */
typedef int luz_mixed_pixels_function(const uint32_t *ids, int width, uint32_t *first,
                                      uint16_t *mixed_x);
void luz_samples_sort_winners(luz_sample_buffers *buffers, int first_row, int end_row,
                              luz_sample_band *band, luz_mixed_pixels_function *mixed_pixels);

/* The resolve of the band's mixed pixels, after the fragment stage shaded
 * the first winners (the framebuffer's colour) and the others
 * (band->extra_colour): each sample takes the colour of the triangle that
 * won it, the clear colour's bytes `background` where none did, and the
 * pixel becomes, per channel, floor((s0 + s1 + s2 + s3 + 2) / 4). A
 * pixel whose samples agree already holds its colour. */
void luz_samples_resolve_winners(const luz_sample_band *band, luz_framebuffer *framebuffer,
                                 const uint8_t background[4]);

/* The resolve from a colour per sample (plane k's colour holds sample
 * k's: the teaching views shade every plane), every pixel of the rows. */
void luz_samples_resolve_planes(const luz_sample_buffers *buffers, luz_framebuffer *framebuffer,
                                int first_row, int end_row);

/* floor((s0 + s1 + s2 + s3 + 2) / 4), SCENE.md's resolve of one channel. */
static inline uint8_t luz_samples_resolve_channel(unsigned s0, unsigned s1, unsigned s2,
                                                  unsigned s3)
{
    return (uint8_t)((s0 + s1 + s2 + s3 + 2) >> 2);
}

/* ---- fragment stage ---------------------------------------------------- */

/* Where a colour's channels go in a pixel's four bytes: red and blue trade
 * places between the two orders, green (byte 1) and alpha (byte 3) stay.
 * Worked out once per band, not per pixel. */
typedef struct luz_pixel_layout {
    int red, blue;   /* byte offsets */
} luz_pixel_layout;

static inline luz_pixel_layout luz_pixel_layout_of(luz_channel_order order)
{
    return order == LUZ_CHANNELS_BGRA ? (luz_pixel_layout){2, 0} : (luz_pixel_layout){0, 2};
}

/* Writes colour, as luz_colour_to_byte rounds it, and alpha 255. */
static inline void luz_pixel_write(uint8_t *pixel, luz_pixel_layout layout, luz_vec3 colour)
{
    pixel[layout.red] = luz_colour_to_byte(colour.x);
    pixel[1] = luz_colour_to_byte(colour.y);
    pixel[layout.blue] = luz_colour_to_byte(colour.z);
    pixel[3] = 255;
}

/* Shades rows [first_row, end_row): each pixel whose visibility id is not 0
 * gets its varyings interpolated perspective-correctly, its texel sampled
 * and its material's colour; by_id[id] is the triangle with that id, and
 * draws[triangle->draw_index] its draw. Every other pixel, the background,
 * gets the clear colour (uniforms->clear_colour): colour is not cleared
 * beforehand, so
 * after this every byte of the rows' colour is written, in the
 * framebuffer's channel order. Returns the number of pixels shaded (the
 * background not counted). */
uint64_t luz_fragment_shade_rows(const luz_uniforms *uniforms, const luz_draw *draws,
                                 const luz_triangle *const *by_id, luz_framebuffer *framebuffer,
                                 int first_row, int end_row);

/* The same stage, a packet of pixels at a time (fragment_packet.c): the
 * same equations in the same order, as SIMD vectors, and the background
 * written the same way. It agrees with luz_fragment_shade_rows to within
 * rounding (the level of detail's logarithm is the one operation computed
 * differently) and, like it, gives each pixel a colour that depends on
 * nothing but that pixel.
 *
 * Each instruction set has its variant (cpu.h's table of kernels). */
typedef uint64_t luz_packet_rows_function(const luz_uniforms *uniforms, const luz_draw *draws,
                                          const luz_triangle *const *by_id,
                                          luz_framebuffer *framebuffer, int first_row,
                                          int end_row);

/* colours[i] = the four bytes (in order's channel order) fragment i gets,
 * exactly as a row's shading would give that pixel for that triangle:
 * fragment.c's one pixel at a time (luz_fragment_shade_list) or a
 * variant's packets of any fragments (the packet_list of cpu.h's
 * table). Returns count. */
uint64_t luz_fragment_shade_list(const luz_uniforms *uniforms, const luz_draw *draws,
                                 const luz_triangle *const *by_id, luz_channel_order order,
                                 const luz_fragment_ref *fragments, size_t count,
                                 uint32_t *colours);
typedef uint64_t luz_packet_list_function(const luz_uniforms *uniforms, const luz_draw *draws,
                                          const luz_triangle *const *by_id,
                                          luz_channel_order order,
                                          const luz_fragment_ref *fragments, size_t count,
                                          uint32_t *colours);

/* ---- screening (screen.c) ---------------------------------------------- */

/* Screening (screen.c): of triangles [first, end) of an index buffer
 * (vertex indices indices[3 t .. 3 t + 2], projected at window), lists in
 * survivors, in order, those that luz_setup_projected or the clipper must
 * still see, and returns how many; the others are back faces (counted in
 * *culled) or have no pixel centre to cover, exactly as setup would find.
 * survivors has room for end - first. An instruction set without a
 * variant lets every triangle through (luz_screen_every_triangle). The
 * variant's table (cpu.h) says whether it checks small boxes: whether it
 * drops every triangle with valid vertices whose box of at most 2 x 2
 * pixel centres has none covered, so that luz_setup_projected need not
 * test a survivor's (its small_box_checked). */
typedef size_t luz_screen_function(const uint32_t *indices, uint32_t first, uint32_t end,
                                   const luz_fixed_vertex *fixed, int width, int height,
                                   uint32_t *survivors, uint32_t *culled);
luz_screen_function luz_screen_every_triangle;

/* ---- setup in lanes (setup_eight.c) ------------------------------------ */

/* luz_setup_projected tests a box of up to this many pixel centres for a
 * covered one before it solves the planes. */
#define LUZ_SETUP_SMALL_BOX_PIXELS 16

/* luz_setup_projected(..., small_box_checked = true, ...) for eight
 * triangles of one draw at once, triangles[lane] (vertex indices
 * indices[3 t .. 3 t + 2] of transform's mesh, fixed as
 * luz_setup_project left them): result[lane] and, where VISIBLE,
 * out[lane] (all but its primitive) are what setup gives for the corners'
 * luz_vertex_stage_one and luz_setup_project_vertex, bit for bit (it runs
 * both itself: no clip or window vertex is read), up to the sign of a NaN
 * that NaN normals, uv or matrix entries make (setup_eight.c).
 * Returns true, and then the results and records mean nothing, when it
 * leaves all eight to the caller: one has a marked vertex (the clipper's,
 * or setup's own culling). Only for triangles screening let through (the
 * small-box promise is screening's). */
typedef bool luz_setup_eight_function(const uint32_t *indices, const uint32_t triangles[8],
                                          const luz_draw_transform *transform,
                                          const luz_fixed_vertex *fixed, int width, int height,
                                          uint32_t draw_index, luz_interpolation interpolation,
                                          luz_triangle out[8], luz_setup_result result[8]);

/* ---- vertices in lanes (vertex_sixteen.c) ------------------------------- */

/* luz_vertex_stage_range and then luz_setup_project for vertices [first,
 * end) of draw, sixteen at a time: the same bytes in out, in window (but
 * for the fields of a marked vertex other than its marker, which mean
 * nothing either way) and in fixed, each unless NULL, up to the sign of a
 * NaN that NaN normals, uv or matrix entries make (vertex_sixteen.c). */
typedef void luz_vertex_project_function(const luz_draw *draw, luz_mat4 view_projection,
                                         uint32_t first, uint32_t end, int width, int height,
                                         luz_clip_vertex *out, luz_window_vertex *window,
                                         luz_fixed_vertex *fixed);

/* For the pixel probe (probe.c): the level of detail exactly as the
 * packets compute it (their polynomial logarithm included), for one
 * pixel. Every variant's lanes perform the same IEEE operations, so this
 * is the value of whichever variant shaded the image. */
float luz_packet_level_of_detail(const luz_texture *texture, float du_dx, float dv_dx,
                                 float du_dy, float dv_dy);

/* The varyings and texture-coordinate derivatives at a pixel centre. */
typedef struct luz_fragment {
    luz_vec3 position;
    luz_vec3 normal;
    luz_vec2 uv;
    float du_dx, dv_dx, du_dy, dv_dy;
    float depth;
    float w;          /* 1 / (1/w): the clip w (1 for affine interpolation) */
} luz_fragment;

void luz_fragment_interpolate(const luz_triangle *triangle, int x, int y, luz_fragment *out);

/* ---- texture coordinates (texture.c) ------------------------------------ */

/* Wrap mode REPEAT: the fractional part of a texture coordinate, in
 * [0, 1). A float of magnitude 2^23 or more has no fractional part, and
 * NaN samples texel 0: both give 0. Inline, for texture.c's samplers and
 * view.c's uv picture. */
static inline float luz_texture_repeat(float coordinate)
{
    if (!(coordinate < 8388608.0f && coordinate > -8388608.0f)) return 0.0f;
    float whole = (float)(int)coordinate;           /* truncates towards 0 */
    if (whole > coordinate) whole -= 1.0f;          /* now floor */
    float fraction = coordinate - whole;
    return fraction < 1.0f ? fraction : 0.0f;       /* -1e-9 - (-1) rounds to 1 */
}

/* rho^2 for the level of detail, in texels of level 0 per pixel step:
 * max(|(du/dx, dv/dx)|^2, |(du/dy, dv/dy)|^2) * (width, height)^2, no
 * square root (log2(rho) = log2(rho^2) / 2). luz_texture_level_of_detail
 * takes its logarithm; the probe reports its root as rho.
 * fragment_packet.c's level_of_detail is the same operations per lane. */
static inline float luz_texture_footprint_squared(const luz_texture *texture, float du_dx,
                                                  float dv_dx, float du_dy, float dv_dy)
{
    float width = (float)texture->levels[0].width, height = (float)texture->levels[0].height;
    float x_u = du_dx * width, x_v = dv_dx * height;
    float y_u = du_dy * width, y_v = dv_dy * height;
    float x_squared = x_u * x_u + x_v * x_v;
    float y_squared = y_u * y_u + y_v * y_v;
    return x_squared > y_squared ? x_squared : y_squared;
}

/* The texels luz_texture_sample reads at uv and level of detail lambda,
 * and each one's weight in the result (texture.c, the sampler's own
 * arithmetic): for the pixel probe. Returns how many (at most
 * LUZ_PROBE_MAX_TAPS); 0 without a texture. */
int luz_texture_taps(const luz_texture *texture, luz_filter filter, luz_vec2 uv, float lambda,
                     luz_probe_tap *taps);

/* ---- views (view.c) ----------------------------------------------------- */

/* Colours rows [first_row, end_row) as uniforms->show asks (see
 * luz/view.h), from what the raster stage left there: the visibility and
 * depth buffers, and overdraw (depth tests per pixel, counted only for the
 * overdraw view; NULL otherwise). worker_index is the thread drawing the
 * band (the bands view). The colour view is fragment.c's image. Like the
 * fragment stage, it writes every pixel of the rows, the background too,
 * in the framebuffer's channel order. Returns the number of visible
 * pixels. */
uint64_t luz_view_shade_rows(const luz_uniforms *uniforms, const luz_draw *draws,
                             const luz_triangle *const *by_id, luz_framebuffer *framebuffer,
                             int first_row, int end_row, const uint32_t *overdraw,
                             int worker_index);

/* What luz_view_shade_rows gives pixel (x, y), before it becomes bytes,
 * for every view but color and bands (the pixel probe asks too). */
luz_vec3 luz_view_pixel(const luz_uniforms *uniforms, const luz_draw *draws,
                        const luz_triangle *const *by_id, const luz_framebuffer *framebuffer,
                        int x, int y, const uint32_t *overdraw);

/* The bands view: a pixel whose colour view is bytes rgb, drawn by
 * worker thread worker_index (luz/view.h's LUZ_VIEW_BANDS_TINT). */
luz_vec3 luz_view_bands_colour(const uint8_t rgb[3], int worker_index);

/* The bands view's tint over rows [first_row, end_row) of the colour the
 * colour view drew (luz_view_shade_rows does it for one sample; frame.c
 * after the resolve of four). */
void luz_view_tint_rows(luz_framebuffer *framebuffer, int first_row, int end_row,
                        int worker_index);

/* The triangles view: the distance in pixels from pixel (x, y)'s centre to
 * the nearest of the triangle's three edges (lines through them). */
double luz_view_edge_distance(const luz_triangle *triangle, int x, int y);
/* Whether one of pixel (x, y)'s four neighbours in a width x height image
 * lies outside the triangle: the triangles view shades such a pixel as
 * its triangle's edge. */
bool luz_view_on_edge(const luz_triangle *triangle, int x, int y, int width, int height);

/* ---- the pixel probe (probe.c, luz/probe.h) ------------------------------ */

/* Before the bands: marks the probe filled if (x, y) is in the
 * framebuffer, empties its answers, and notes the view. */
void luz_probe_begin(luz_pixel_probe *probe, const luz_framebuffer *framebuffer, luz_view view);

/* Each band, right after its fragment stage (or view) and before the
 * caller's hook: if the probe's pixel lies in rows [first_row, end_row),
 * keeps the bytes the image holds there and which band and thread drew
 * them. */
void luz_probe_capture(luz_pixel_probe *probe, const luz_framebuffer *framebuffer,
                       int first_row, int end_row, int band_index, int worker_index);

/* After the bands: the rest of the story, from the frame's set-up
 * triangles (ids 1 .. triangle_count were rasterised) and the final depth
 * and visibility buffers, or with four samples (samples not NULL) the
 * samples' planes. packet_list: not NULL when the image's colour was
 * shaded by fragment_packet.c, whose level of detail the probe then
 * reports (else fragment.c's), and whose list shades each sample's
 * winner again for its bytes. overdraw: the overdraw view's counts, or
 * NULL. */
void luz_probe_explain(luz_pixel_probe *probe, const luz_uniforms *uniforms,
                       const luz_draw *draws, const luz_triangle *const *by_id,
                       size_t triangle_count, const luz_framebuffer *framebuffer,
                       const luz_sample_buffers *samples, const uint32_t *overdraw,
                       luz_packet_list_function *packet_list);

/* ---- threads ----------------------------------------------------------- */

typedef struct luz_thread_pool luz_thread_pool;

/* job(context, job_index, worker_index) for every job_index in
 * [0, job_count); worker_index < the pool's thread count says which thread
 * runs it (0 is the caller). */
typedef void luz_job_function(void *context, int job_index, int worker_index);

/* thread_count threads in all, the caller's included (so thread_count - 1
 * workers are started); 1 runs every job on the caller's thread. */
luz_thread_pool *luz_thread_pool_create(int thread_count);
void luz_thread_pool_destroy(luz_thread_pool *pool);
int luz_thread_pool_thread_count(const luz_thread_pool *pool);
/* Runs the jobs and returns when all are done. Thread k of n runs jobs
 * from [k * job_count / n, (k + 1) * job_count / n) first, then helps
 * with the others' (bands.c): passes cut alike give a thread the same part
 * of the data. */
void luz_thread_pool_run(luz_thread_pool *pool, int job_count, luz_job_function *job,
                         void *context);

/* ---- phase 1: geometry (geometry.c) -------------------------------------- */

/* The buffers phase 1 keeps from frame to frame (the renderer owns one). */
typedef struct luz_geometry luz_geometry;

luz_geometry *luz_geometry_create(int thread_count);
void luz_geometry_destroy(luz_geometry *geometry);
/* The bytes its buffers hold. */
size_t luz_geometry_memory(const luz_geometry *geometry);
/* The block of records on huge pages (geometry.c's place_records) after
 * the last run: its capacity in records (0: no block), and in
 * *records_in_block how many of that run's records lie in it. */
size_t luz_geometry_record_block(const luz_geometry *geometry, size_t *records_in_block);

/* What phase 1 hands to phase 2; the arrays belong to the luz_geometry and
 * last until its next run. */
typedef struct luz_geometry_result {
    const luz_triangle *const *by_id;   /* by_id[id], id = 1 .. triangle_total */
    size_t triangle_total;              /* triangles set up */
    size_t triangle_count;              /* of which ids 1 .. count are binned */
    int band_count;
    const size_t *band_start;           /* band b's ids: band_ids[band_start[b] ..
                                           band_start[b + 1]), in id order */
    const uint32_t *band_ids;
    uint64_t triangles_submitted, triangles_clipped, triangles_culled;
    uint64_t draws_culled;              /* wholly outside the clip volume */
} luz_geometry_result;

/* Vertex stage, clipping, setup, numbering and binning to bands of
 * band_height rows (a power of two), over the pool's threads; only the
 * first triangle_limit triangles are binned (0: all). Returns 0, or -1
 * with the reason (out of memory, too many triangles). */
int luz_geometry_run(luz_geometry *geometry, luz_thread_pool *pool, const luz_frame *frame,
                     const luz_uniforms *uniforms, const luz_framebuffer *framebuffer,
                     int band_height, uint32_t triangle_limit, luz_geometry_result *out,
                     luz_error *error);

#endif
