/*
 * fuzz_model.c: model loading (io/model.h, luz_model_load_memory): assimp's
 * importers, then luz's checks of what assimp returns.
 *
 * In:  a first byte that picks the file name assimp sees, whose extension
 *      chooses the importer (OBJ, glTF, GLB, PLY, STL, FBX, 3DS, Collada,
 *      OFF, DirectX .x, or no extension: assimp then tries every importer
 *      on the bytes), then the file's bytes. No other file exists: a .mtl
 *      or a texture file the model names is missing.
 * Checks: no crash or undefined behaviour in luz (assimp itself is
 *      Debian's, not instrumented, so its own bugs show only when they
 *      crash); a refusal gives a reason and leaves the model empty; a
 *      model that loads has at least one part, every part a mesh with at
 *      least one triangle, the model's triangle count their sum, finite
 *      bounds with some extent, and textures that are the model's own.
 * The texture budget is 16 MiB, as in fuzz_texture.c.
 */
#include <math.h>
#include <stdint.h>

#include "fuzz_support.h"
#include "io/input_file.h"
#include "io/model.h"

static bool is_finite(luz_vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const names[] = {"m.obj", "m.gltf", "m.glb", "m.ply", "m.stl", "m.fbx",
                                        "m.3ds", "m.dae", "m.off", "m.x", "model"};
    if (size < 1 || size > (1 << 20)) return 0;
    const char *name = names[data[0] % (sizeof names / sizeof names[0])];
    luz_texture_budget budget = {.limit = (uint64_t)16 << 20};
    luz_model model;
    luz_error error = {{0}};
    int status = luz_model_load_memory(&model, data + 1, size - 1, name, &budget, &error);
    if (status != 0) {
        FUZZ_CHECK(status == LUZ_BAD_INPUT || status == LUZ_MACHINE_FAILED, "status %d", status);
        FUZZ_CHECK(model.part_count == 0 && model.parts == NULL && model.textures == NULL &&
                       model.path == NULL,
                   "a refused model is not empty");
        fuzz_check_message(&error);
        return 0;
    }
    FUZZ_CHECK(model.part_count >= 1, "%d parts", model.part_count);
    uint64_t triangles = 0;
    for (int p = 0; p < model.part_count; p++) {
        const luz_model_part *part = &model.parts[p];
        FUZZ_CHECK(part->mesh != NULL, "part %d has no mesh", p);
        FUZZ_CHECK(luz_mesh_triangle_count(part->mesh) >= 1, "part %d has no triangle", p);
        triangles += luz_mesh_triangle_count(part->mesh);
        bool owned = part->texture == NULL;
        for (int t = 0; t < model.texture_count && !owned; t++)
            owned = model.textures[t] == part->texture;
        FUZZ_CHECK(owned, "part %d's texture is not the model's", p);
        FUZZ_CHECK(!part->has_colour || is_finite(part->colour), "part %d's colour", p);
    }
    FUZZ_CHECK(triangles == model.triangle_count, "%llu triangles in the parts, %llu counted",
               (unsigned long long)triangles, (unsigned long long)model.triangle_count);
    FUZZ_CHECK(is_finite(model.bounds.min) && is_finite(model.bounds.max),
               "bounds not finite");
    FUZZ_CHECK(model.bounds.max.x - model.bounds.min.x > 0.0f ||
                   model.bounds.max.y - model.bounds.min.y > 0.0f ||
                   model.bounds.max.z - model.bounds.min.z > 0.0f,
               "a model of zero size");
    luz_model_free(&model);
    return 0;
}
