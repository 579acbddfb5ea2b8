/*
 * vertex.c: the vertex stage, luz's vertex shader.
 *
 * In:  a luz_draw (a mesh in object space and its model matrix) and the
 *      frame's projection * view matrix.
 * Out: one luz_clip_vertex per mesh vertex: the clip-space position that
 *      the clipper and rasteriser need, and the varyings the fragment
 *      shader needs (world-space position and normal, texture coordinates).
 *
 * As in the report's GLSL, lighting happens in world space, so the vertex
 * stage passes world-space position and normal along. Normals go through
 * the normal matrix (the inverse transpose of the model's 3x3) and are not
 * normalised here: the fragment shader re-normalises them after
 * interpolation, which SCENE.md asks for.
 *
 * luz/bug.h's normal-matrix-is-model sends the normal through the model
 * matrix as a point, (M (N, 1)).xyz. (The model's plain 3x3 would be the
 * subtler mistake, but for the lab's rigid motions and uniform scales it
 * gives the normal matrix's direction, which re-normalising cannot tell
 * apart: nothing would show.)
 */
#include "renderer/pipeline.h"

/* vecmath.c's luz_mat4_transform and luz_mat3_transform, the same
 * operations in the same order, here so that they inline: called across
 * files, each call copied its matrix and cost a tenth of a big mesh's
 * geometry phase. Column-major: element (row, column) is m[column * 4 +
 * row]. */
static inline luz_vec4 transform4(const luz_mat4 *m, float x, float y, float z, float w)
{
    const float *a = m->m;
    return (luz_vec4){
        a[0] * x + a[4] * y + a[8] * z + a[12] * w,
        a[1] * x + a[5] * y + a[9] * z + a[13] * w,
        a[2] * x + a[6] * y + a[10] * z + a[14] * w,
        a[3] * x + a[7] * y + a[11] * z + a[15] * w,
    };
}

static inline luz_vec3 transform3(const luz_mat3 *m, luz_vec3 v)
{
    const float *a = m->m;
    return (luz_vec3){
        a[0] * v.x + a[3] * v.y + a[6] * v.z,
        a[1] * v.x + a[4] * v.y + a[7] * v.z,
        a[2] * v.x + a[5] * v.y + a[8] * v.z,
    };
}

/* One vertex: world position and normal, clip position and outcode. */
static inline luz_clip_vertex shade_vertex(const luz_vertex *vertex, const luz_mat4 *model,
                                           const luz_mat3 *normal_matrix,
                                           const luz_mat4 *view_projection,
                                           bool normal_as_point)
{
    const luz_vec4 world4 =
        transform4(model, vertex->position.x, vertex->position.y, vertex->position.z, 1.0f);
    const luz_vec3 world = {world4.x, world4.y, world4.z};
    luz_vec3 normal;
    if (normal_as_point) {   /* the bug */
        const luz_vec4 n =
            transform4(model, vertex->normal.x, vertex->normal.y, vertex->normal.z, 1.0f);
        normal = (luz_vec3){n.x, n.y, n.z};
    } else {
        normal = transform3(normal_matrix, vertex->normal);
    }
    luz_clip_vertex out;
    out.position = transform4(view_projection, world.x, world.y, world.z, 1.0f);
    out.outcode = luz_clip_outcode(out.position);
    float *varying = out.varyings;
    varying[LUZ_VARYING_POSITION + 0] = world.x;
    varying[LUZ_VARYING_POSITION + 1] = world.y;
    varying[LUZ_VARYING_POSITION + 2] = world.z;
    varying[LUZ_VARYING_NORMAL + 0] = normal.x;
    varying[LUZ_VARYING_NORMAL + 1] = normal.y;
    varying[LUZ_VARYING_NORMAL + 2] = normal.z;
    varying[LUZ_VARYING_UV + 0] = vertex->uv.x;
    varying[LUZ_VARYING_UV + 1] = vertex->uv.y;
    return out;
}

void luz_vertex_stage(const luz_draw *draw, luz_mat4 view_projection, luz_clip_vertex *out)
{
    luz_vertex_stage_range(draw, view_projection, 0, draw->mesh->vertex_count, out);
}

void luz_vertex_stage_bug(const luz_draw *draw, luz_mat4 view_projection, luz_bug bug,
                          uint32_t first, uint32_t end, luz_clip_vertex *out)
{
    if (bug != LUZ_BUG_NORMAL_MATRIX_IS_MODEL) {
        luz_vertex_stage_range(draw, view_projection, first, end, out);
        return;
    }
    for (uint32_t i = first; i < end; i++)
        out[i] = shade_vertex(&draw->mesh->vertices[i], &draw->model, NULL, &view_projection,
                              true);
}

/* Compiled once, for the build's target: a big mesh's vertices go through
 * the table's vertex pass in lanes (cpu.h), and what is left here (small
 * draws, the clipper's corners) took no measurable time from a wider copy. */
void luz_vertex_stage_range(const luz_draw *draw, luz_mat4 view_projection, uint32_t first,
                            uint32_t end, luz_clip_vertex *out)
{
    const luz_mat3 normal_matrix = luz_mat3_normal_matrix(draw->model);
    for (uint32_t i = first; i < end; i++)
        out[i] = shade_vertex(&draw->mesh->vertices[i], &draw->model, &normal_matrix,
                              &view_projection, false);
}

luz_draw_transform luz_draw_transform_of(const luz_draw *draw, luz_mat4 view_projection)
{
    return (luz_draw_transform){draw->mesh->vertices, draw->model,
                                luz_mat3_normal_matrix(draw->model), view_projection};
}

luz_clip_vertex luz_vertex_stage_one(const luz_draw_transform *transform, uint32_t i)
{
    return shade_vertex(&transform->vertices[i], &transform->model, &transform->normal_matrix,
                        &transform->view_projection, false);
}

luz_clip_vertex luz_vertex_stage_one_bug(const luz_draw_transform *transform, luz_bug bug,
                                         uint32_t i)
{
    return shade_vertex(&transform->vertices[i], &transform->model, &transform->normal_matrix,
                        &transform->view_projection, bug == LUZ_BUG_NORMAL_MATRIX_IS_MODEL);
}
