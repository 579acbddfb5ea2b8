/*
 * clip.c: clipping in homogeneous clip space (Sutherland-Hodgman).
 *
 * In:  a triangle of clip-space vertices.
 * Out: a convex polygon of up to 9 vertices inside the clip volume, in the
 *      same winding, to be fanned into triangles.
 *
 * Why clip at all: a vertex behind the camera has w < 0, and dividing by w
 * would fling it to the wrong side of the screen. Clipping against the near
 * plane (z >= -w, OpenGL's clip volume) first keeps w >= near > 0 for every
 * vertex that reaches the divide; the far plane (z <= w) keeps depth <= 1.
 *
 * x and y are not clipped to the screen but to a guard band, |x|, |y| <=
 * 4 w: the rasteriser only visits pixels inside the viewport anyway, and
 * the band keeps window coordinates within the fixed-point range proven in
 * setup.c. Few triangles ever touch it, so little clipping happens.
 *
 * Why clip in clip space, before the divide: clip coordinates and the
 * varyings are linear along an edge in clip space (they are affine
 * functions of the object-space position), so interpolating them there
 * with the plane's crossing parameter t is exact. After the divide that no
 * longer holds (that is what perspective-correct interpolation is about).
 *
 * Cracks: two triangles sharing an edge must produce the same crossing
 * point on it, or a hairline gap can open. The crossing is therefore always
 * computed from the inside vertex towards the outside one, whichever order
 * the triangle lists them in, so the arithmetic is the same for both.
 */
#include "renderer/pipeline.h"

/* Signed distance of a point to each plane: >= 0 means inside. */
static float plane_distance(luz_vec4 p, int plane)
{
    const float guard = LUZ_CLIP_GUARD_BAND;
    switch (plane) {
    case 0: return p.w + p.z;          /* near:   z >= -w */
    case 1: return p.w - p.z;          /* far:    z <=  w */
    case 2: return guard * p.w + p.x;  /* left:   x >= -g w */
    case 3: return guard * p.w - p.x;  /* right:  x <=  g w */
    case 4: return guard * p.w + p.y;  /* bottom: y >= -g w */
    default: return guard * p.w - p.y; /* top:    y <=  g w */
    }
}

/* The point where the edge from inside to outside crosses the plane. */
static luz_clip_vertex crossing(const luz_clip_vertex *inside, float inside_distance,
                                const luz_clip_vertex *outside, float outside_distance)
{
    float t = inside_distance / (inside_distance - outside_distance);
    luz_clip_vertex result;
    result.position.x = inside->position.x + t * (outside->position.x - inside->position.x);
    result.position.y = inside->position.y + t * (outside->position.y - inside->position.y);
    result.position.z = inside->position.z + t * (outside->position.z - inside->position.z);
    result.position.w = inside->position.w + t * (outside->position.w - inside->position.w);
    for (int i = 0; i < LUZ_VARYING_COUNT; i++)
        result.varyings[i] =
            inside->varyings[i] + t * (outside->varyings[i] - inside->varyings[i]);
    result.outcode = luz_clip_outcode(result.position);
    return result;
}

/* One Sutherland-Hodgman pass: keeps the part of the polygon inside one
 * plane. Walking each edge (previous -> current): an inside vertex is kept,
 * and an edge that crosses the plane contributes its crossing point.
 *
 * A convex polygon crosses a plane at most twice, so it gains at most one
 * vertex a plane and 3 + 6 = LUZ_CLIP_MAX_VERTICES always suffice. Only a
 * sliver so thin that rounding zig-zags its vertices across a plane could
 * cross more often; such a triangle covers no more than a hairline, and
 * it is dropped (-1) rather than allowed to overrun the buffer. */
static int clip_against_plane(const luz_clip_vertex *in, int count, int plane,
                              luz_clip_vertex *out)
{
    int out_count = 0;
    for (int i = 0; i < count; i++) {
        const luz_clip_vertex *previous = &in[(i + count - 1) % count];
        const luz_clip_vertex *current = &in[i];
        float previous_distance = plane_distance(previous->position, plane);
        float current_distance = plane_distance(current->position, plane);
        bool previous_inside = previous_distance >= 0.0f;
        bool current_inside = current_distance >= 0.0f;

        int writes = (current_inside != previous_inside) + current_inside;
        if (out_count + writes > LUZ_CLIP_MAX_VERTICES) return -1;
        if (current_inside != previous_inside) {
            out[out_count++] = current_inside
                ? crossing(current, current_distance, previous, previous_distance)
                : crossing(previous, previous_distance, current, current_distance);
        }
        if (current_inside) out[out_count++] = *current;
    }
    return out_count;
}

int luz_clip_triangle(const luz_clip_vertex *a, const luz_clip_vertex *b,
                      const luz_clip_vertex *c, luz_clip_polygon *out)
{
    luz_clip_vertex scratch[LUZ_CLIP_MAX_VERTICES];
    unsigned any_outside = luz_clip_outcode(a->position) | luz_clip_outcode(b->position) |
                           luz_clip_outcode(c->position);

    out->vertices[0] = *a;
    out->vertices[1] = *b;
    out->vertices[2] = *c;
    out->vertex_count = 3;

    /* One plane at a time, through scratch and back, skipping planes no
     * vertex is outside of. */
    for (int plane = 0; plane < LUZ_CLIP_PLANE_COUNT && out->vertex_count > 0; plane++) {
        if (!(any_outside & (1u << plane))) continue;
        int count = clip_against_plane(out->vertices, out->vertex_count, plane, scratch);
        if (count < 0) return out->vertex_count = 0;
        for (int i = 0; i < count; i++) out->vertices[i] = scratch[i];
        out->vertex_count = count;
    }
    return out->vertex_count < 3 ? (out->vertex_count = 0) : out->vertex_count;
}
