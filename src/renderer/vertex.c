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
 */
#include "renderer/pipeline.h"

void luz_vertex_stage(const luz_draw *draw, luz_mat4 view_projection, luz_clip_vertex *out)
{
    luz_vertex_stage_range(draw, view_projection, 0, draw->mesh->vertex_count, out);
}

void luz_vertex_stage_range(const luz_draw *draw, luz_mat4 view_projection, uint32_t first,
                            uint32_t end, luz_clip_vertex *out)
{
    const luz_mesh *mesh = draw->mesh;
    const luz_mat3 normal_matrix = luz_mat3_normal_matrix(draw->model);
    for (uint32_t i = first; i < end; i++) {
        const luz_vertex *vertex = &mesh->vertices[i];
        luz_vec3 world = luz_mat4_transform_point(draw->model, vertex->position);
        luz_vec3 normal = luz_mat3_transform(normal_matrix, vertex->normal);

        out[i].position = luz_mat4_transform(view_projection,
                                             (luz_vec4){world.x, world.y, world.z, 1.0f});
        out[i].outcode = luz_clip_outcode(out[i].position);
        float *varying = out[i].varyings;
        varying[LUZ_VARYING_POSITION + 0] = world.x;
        varying[LUZ_VARYING_POSITION + 1] = world.y;
        varying[LUZ_VARYING_POSITION + 2] = world.z;
        varying[LUZ_VARYING_NORMAL + 0] = normal.x;
        varying[LUZ_VARYING_NORMAL + 1] = normal.y;
        varying[LUZ_VARYING_NORMAL + 2] = normal.z;
        varying[LUZ_VARYING_UV + 0] = vertex->uv.x;
        varying[LUZ_VARYING_UV + 1] = vertex->uv.y;
    }
}
