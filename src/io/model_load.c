/*
 * model_load.c: a model file into a luz_model, through assimp's C API
 * (SCENE.md, "Models").
 *
 * In:  a path to any file assimp reads (OBJ, glTF 2.0, PLY, STL, FBX, 3DS,
 *      ...).
 * Out: one luz_mesh per triangle mesh of the file, in its order, with the
 *      colour and the texture of its material, and the bounds of them all.
 *
 * assimp does the parsing with exactly SCENE.md's post-processing steps;
 * this file then checks what it returns as it would check any stranger's
 * data (luz_mesh_create refuses an index out of range or a position that
 * is not finite; the positions are also checked before the steps, which
 * could merge a NaN away) and keeps nothing of assimp once it returns.
 */
#include "io/model.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/textures.h"

#if defined(LUZ_HAVE_ASSIMP)
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#endif

void luz_model_free(luz_model *model)
{
    for (int i = 0; i < model->part_count; i++) {
        luz_mesh_destroy(model->parts[i].mesh);
        free(model->parts[i].mesh_name);
        free(model->parts[i].material_name);
        free(model->parts[i].texture_name);
    }
    for (int i = 0; i < model->texture_count; i++) luz_texture_destroy(model->textures[i]);
    free(model->parts);
    free(model->textures);
    for (int i = 0; i < model->texture_file_count; i++) free(model->texture_files[i]);
    free(model->texture_files);
    free(model->path);
    free(model->name);
    memset(model, 0, sizeof *model);
}

#if !defined(LUZ_HAVE_ASSIMP)

bool luz_models_supported(void)
{
    return false;
}

int luz_model_load(luz_model *model, const char *path, luz_error *error)
{
    memset(model, 0, sizeof *model);
    return luz_error_set(error, "%s: this luz was built without model support (assimp; "
                                "-Dmodels=enabled needs libassimp-dev)", path);
}

#else

bool luz_models_supported(void)
{
    return true;
}

/* SCENE.md's steps, exactly. */
static const unsigned int model_steps =
    aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
    aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_FlipUVs |
    aiProcess_ValidateDataStructure;

static char *copy_text(const char *text)
{
    size_t length = strlen(text) + 1;
    char *copy = malloc(length);
    if (copy) memcpy(copy, text, length);
    return copy;
}

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *backslash = strrchr(path, '\\');
    if (backslash && (!slash || backslash > slash)) slash = backslash;
    return slash ? slash + 1 : path;
}

/* ---- textures --------------------------------------------------------------------------- */

/* The textures already decoded, by the name the materials use, so that the
 * parts that share one share its memory. */
typedef struct texture_cache {
    char **keys;
    int count;
} texture_cache;

static int remember_texture(luz_model *model, texture_cache *cache, const char *key,
                            luz_texture *texture, luz_error *error)
{
    luz_texture **textures =
        realloc(model->textures, (size_t)(model->texture_count + 1) * sizeof *textures);
    if (textures) model->textures = textures;
    char **keys = realloc(cache->keys, (size_t)(cache->count + 1) * sizeof *keys);
    if (keys) cache->keys = keys;
    char *copy = copy_text(key);
    if (!textures || !keys || !copy) {
        free(copy);
        luz_texture_destroy(texture);
        return luz_error_set(error, "%s: out of memory for its textures", model->path);
    }
    model->textures[model->texture_count++] = texture;
    cache->keys[cache->count++] = copy;
    return 0;
}

/* A texture file read from beside the model, kept by path for luz-render's
 * check that no output replaces an input. */
static int remember_texture_file(luz_model *model, const char *path, luz_error *error)
{
    char **files = realloc(model->texture_files,
                           (size_t)(model->texture_file_count + 1) * sizeof *files);
    if (files) model->texture_files = files;
    char *copy = copy_text(path);
    if (!files || !copy) {
        free(copy);
        return luz_error_set(error, "%s: out of memory for its textures", model->path);
    }
    model->texture_files[model->texture_file_count++] = copy;
    return 0;
}

/* An embedded texture: compressed (mHeight 0: mWidth bytes of a PNG, JPEG,
 * ...) and decoded like a file, or raw BGRA texels. */
static luz_texture *decode_embedded(const struct aiTexture *embedded, const char *name,
                                    luz_error *error)
{
    if (embedded->mHeight == 0)
        return luz_texture_load_memory((const unsigned char *)embedded->pcData,
                                       embedded->mWidth, name, error);
    const unsigned width = embedded->mWidth, height = embedded->mHeight;
    if (width > LUZ_TEXTURE_MAX_SIZE || height > LUZ_TEXTURE_MAX_SIZE) {
        luz_error_set(error, "%s: image is %ux%u, expected at most %dx%d", name, width, height,
                      LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
        return NULL;
    }
    uint8_t *rgba = malloc((size_t)width * height * 4 + 1);
    if (!rgba) {
        luz_error_set(error, "%s: out of memory for a %ux%u texture", name, width, height);
        return NULL;
    }
    for (size_t i = 0; i < (size_t)width * height; i++) {
        const struct aiTexel *texel = &embedded->pcData[i];
        rgba[i * 4 + 0] = texel->r;
        rgba[i * 4 + 1] = texel->g;
        rgba[i * 4 + 2] = texel->b;
        rgba[i * 4 + 3] = texel->a;
    }
    luz_error inner;
    luz_texture *texture = luz_texture_create((int)width, (int)height, rgba, &inner);
    free(rgba);
    if (!texture) luz_error_set(error, "%s: %s", name, inner.message);
    return texture;
}

/* The embedded texture a material names: "*N", or the embedded texture's
 * own file name (glTF binaries name them so). NULL if there is none. */
static const struct aiTexture *find_embedded(const struct aiScene *scene, const char *name)
{
    if (name[0] == '*') {
        char *end;
        errno = 0;
        unsigned long index = strtoul(name + 1, &end, 10);
        if (errno == 0 && end != name + 1 && *end == '\0' && index < scene->mNumTextures)
            return scene->mTextures[index];
        return NULL;
    }
    for (unsigned i = 0; i < scene->mNumTextures; i++) {
        const char *own = scene->mTextures[i]->mFilename.data;
        if (own[0] != '\0' && (strcmp(own, name) == 0 || strcmp(base_name(own), base_name(name)) == 0))
            return scene->mTextures[i];
    }
    return NULL;
}

/* The texture a material names, decoded once: embedded in the file, else
 * a file relative to the model's directory, a backslash read as a slash
 * (files written on Windows say `.\tex\a.jpg`). */
static int load_texture(luz_model *model, texture_cache *cache, const struct aiScene *scene,
                        const char *name, const luz_texture **out, luz_error *error)
{
    for (int i = 0; i < cache->count; i++) {
        if (strcmp(cache->keys[i], name) == 0) {
            *out = model->textures[i];
            return 0;
        }
    }
    luz_error inner = {{0}};
    luz_texture *texture = NULL;
    const struct aiTexture *embedded = find_embedded(scene, name);
    if (embedded != NULL) {
        texture = decode_embedded(embedded, name, &inner);
    } else if (name[0] == '*') {
        luz_error_set(&inner, "%s: no such embedded texture", name);
    } else {
        char relative[4096];
        snprintf(relative, sizeof relative, "%s", name);
        for (char *c = relative; *c; c++)
            if (*c == '\\') *c = '/';
        const char *file = relative;
        while (file[0] == '.' && file[1] == '/') file += 2;
        char path[8192];
        const char *slash = strrchr(model->path, '/');
        if (file[0] == '/' || slash == NULL)
            snprintf(path, sizeof path, "%s", file);
        else
            snprintf(path, sizeof path, "%.*s/%s", (int)(slash - model->path), model->path, file);
        struct stat status;
        if (stat(path, &status) != 0)
            luz_error_set(&inner, "%s: %s", path, strerror(errno));
        else if (!S_ISREG(status.st_mode))
            luz_error_set(&inner, "%s: not a regular file", path);
        else
            texture = luz_texture_load(path, &inner);
        if (texture != NULL && remember_texture_file(model, path, &inner) != 0) {
            luz_texture_destroy(texture);
            texture = NULL;
        }
    }
    if (texture == NULL)
        return luz_error_set(error, "%s: texture '%s': %s", model->path, name, inner.message);
    if (remember_texture(model, cache, name, texture, error) != 0) return -1;
    *out = texture;
    return 0;
}

/* ---- meshes ------------------------------------------------------------------------------ */

static bool is_finite_colour(struct aiColor4D c)
{
    return isfinite(c.r) && isfinite(c.g) && isfinite(c.b);
}

/* The colour of a material: its diffuse colour, unless it is assimp's
 * stand-in for a file without materials ("DefaultMaterial") or has none. */
static bool material_colour(const struct aiMaterial *material, luz_vec3 *colour)
{
    struct aiString name;
    if (aiGetMaterialString(material, AI_MATKEY_NAME, &name) == aiReturn_SUCCESS &&
        strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0)
        return false;
    struct aiColor4D diffuse;
    if (aiGetMaterialColor(material, AI_MATKEY_COLOR_DIFFUSE, &diffuse) != aiReturn_SUCCESS ||
        !is_finite_colour(diffuse))
        return false;
    *colour = (luz_vec3){diffuse.r, diffuse.g, diffuse.b};
    return true;
}

/* How many of the triangles have an area: corners not all on one line.
 * The indices are in range (luz_mesh_create has checked them). */
static uint32_t count_with_area(const luz_vertex *vertices, const uint32_t *indices,
                                uint32_t triangles)
{
    uint32_t count = 0;
    for (uint32_t t = 0; t < triangles; t++) {
        const luz_vec3 a = vertices[indices[3 * t]].position;
        const luz_vec3 b = vertices[indices[3 * t + 1]].position;
        const luz_vec3 c = vertices[indices[3 * t + 2]].position;
        const double ux = (double)b.x - a.x, uy = (double)b.y - a.y, uz = (double)b.z - a.z;
        const double vx = (double)c.x - a.x, vy = (double)c.y - a.y, vz = (double)c.z - a.z;
        count += uy * vz - uz * vy != 0.0 || uz * vx - ux * vz != 0.0 || ux * vy - uy * vx != 0.0;
    }
    return count;
}

/* A copy of a name the file gives, NULL for an empty one; false if memory
 * ran out. */
static bool name_part(char **out, const char *name)
{
    *out = NULL;
    if (name[0] == '\0') return true;
    *out = copy_text(name);
    return *out != NULL;
}

static void free_part_names(luz_model_part *part)
{
    free(part->mesh_name);
    free(part->material_name);
    free(part->texture_name);
}

/* One assimp mesh's triangles as a part; *added is false for a mesh with
 * none (points or lines only), which is dropped. *with_area grows by the
 * number of its triangles that have an area. */
static int add_part(luz_model *model, texture_cache *cache, const struct aiScene *scene,
                    unsigned mesh_index, bool *added, uint64_t *with_area, luz_error *error)
{
    const struct aiMesh *source = scene->mMeshes[mesh_index];
    *added = false;
    if (source == NULL || !(source->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return 0;
    uint32_t triangles = 0;
    for (unsigned f = 0; f < source->mNumFaces; f++)
        triangles += source->mFaces[f].mNumIndices == 3;
    if (triangles == 0) return 0;
    if (triangles > LUZ_MESH_MAX_TRIANGLES)
        return luz_error_set(error, "%s: mesh %u has %u triangles, more than %u", model->path,
                             mesh_index, (unsigned)triangles, (unsigned)LUZ_MESH_MAX_TRIANGLES);

    const unsigned vertex_count = source->mNumVertices;
    if (vertex_count > LUZ_MESH_MAX_VERTICES)
        return luz_error_set(error, "%s: mesh %u has %u vertices, more than %u", model->path,
                             mesh_index, vertex_count, (unsigned)LUZ_MESH_MAX_VERTICES);
    luz_vertex *vertices = malloc((size_t)vertex_count * sizeof *vertices + 1);
    uint32_t *indices = malloc((size_t)triangles * 3 * sizeof *indices);
    if (!vertices || !indices) {
        free(vertices);
        free(indices);
        return luz_error_set(error, "%s: out of memory for mesh %u (%u vertices)", model->path,
                             mesh_index, vertex_count);
    }
    const struct aiVector3D *uvs = source->mTextureCoords[0];
    for (unsigned v = 0; v < vertex_count; v++) {
        const struct aiVector3D p = source->mVertices[v];
        const struct aiVector3D n = source->mNormals ? source->mNormals[v]
                                                     : (struct aiVector3D){0.0f, 0.0f, 0.0f};
        vertices[v] = (luz_vertex){{p.x, p.y, p.z}, {n.x, n.y, n.z},
                                   {uvs ? uvs[v].x : 0.0f, uvs ? uvs[v].y : 0.0f}};
    }
    uint32_t *index = indices;
    for (unsigned f = 0; f < source->mNumFaces; f++) {
        const struct aiFace *face = &source->mFaces[f];
        if (face->mNumIndices != 3) continue;
        for (int k = 0; k < 3; k++) *index++ = face->mIndices[k];
    }
    luz_error inner;
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices,
                                                      .vertex_count = vertex_count,
                                                      .indices = indices,
                                                      .index_count = triangles * 3},
                                     &inner);
    if (mesh != NULL) *with_area += count_with_area(vertices, indices, triangles);
    free(vertices);
    free(indices);
    if (mesh == NULL)
        return luz_error_set(error, "%s: mesh %u: %s", model->path, mesh_index, inner.message);

    luz_model_part part = {.mesh = mesh, .has_uvs = uvs != NULL};
    bool names_fit = name_part(&part.mesh_name, source->mName.data);
    const struct aiMaterial *material =
        source->mMaterialIndex < scene->mNumMaterials ? scene->mMaterials[source->mMaterialIndex]
                                                      : NULL;
    if (material != NULL) {
        part.has_colour = material_colour(material, &part.colour);
        struct aiString material_name;
        if (aiGetMaterialString(material, AI_MATKEY_NAME, &material_name) == aiReturn_SUCCESS)
            names_fit = name_part(&part.material_name, material_name.data) && names_fit;
        struct aiString texture_name;
        if (part.has_uvs && aiGetMaterialTextureCount(material, aiTextureType_DIFFUSE) > 0 &&
            aiGetMaterialTexture(material, aiTextureType_DIFFUSE, 0, &texture_name, NULL, NULL,
                                 NULL, NULL, NULL, NULL) == aiReturn_SUCCESS &&
            texture_name.data[0] != '\0') {
            names_fit = name_part(&part.texture_name, texture_name.data) && names_fit;
            if (load_texture(model, cache, scene, texture_name.data, &part.texture, error) != 0) {
                free_part_names(&part);
                luz_mesh_destroy(mesh);
                return -1;
            }
        }
    }

    luz_model_part *parts = names_fit ? realloc(model->parts,
                                                (size_t)(model->part_count + 1) * sizeof *parts)
                                      : NULL;
    if (!parts) {
        free_part_names(&part);
        luz_mesh_destroy(mesh);
        return luz_error_set(error, "%s: out of memory for its meshes", model->path);
    }
    model->parts = parts;
    model->parts[model->part_count++] = part;
    model->triangle_count += triangles;
    *added = true;
    return 0;
}

/* Every position the file gives, checked before the steps run: a NaN
 * compares equal to nothing, so JoinIdenticalVertices can merge a NaN
 * vertex into a finite one and leave a degenerate triangle that draws
 * nothing, and the file would load as if it were sound. */
static int check_positions(const struct aiScene *scene, const char *path, luz_error *error)
{
    for (unsigned m = 0; m < scene->mNumMeshes; m++) {
        const struct aiMesh *mesh = scene->mMeshes[m];
        if (mesh == NULL || mesh->mVertices == NULL) continue;
        for (unsigned v = 0; v < mesh->mNumVertices; v++) {
            const struct aiVector3D p = mesh->mVertices[v];
            if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(p.z))
                return luz_error_set(error, "%s: mesh %u: vertex %u has a position that is not "
                                            "finite", path, m, v);
        }
    }
    return 0;
}

static void grow_bounds(luz_bounds *bounds, luz_bounds more, bool first)
{
    if (first) {
        *bounds = more;
        return;
    }
    bounds->min = (luz_vec3){fminf(bounds->min.x, more.min.x), fminf(bounds->min.y, more.min.y),
                             fminf(bounds->min.z, more.min.z)};
    bounds->max = (luz_vec3){fmaxf(bounds->max.x, more.max.x), fmaxf(bounds->max.y, more.max.y),
                             fmaxf(bounds->max.z, more.max.z)};
}

int luz_model_load(luz_model *model, const char *path, luz_error *error)
{
    memset(model, 0, sizeof *model);
    struct stat status;
    if (stat(path, &status) != 0)
        return luz_error_set(error, "%s: cannot open the model (%s)", path, strerror(errno));
    if (!S_ISREG(status.st_mode))
        return luz_error_set(error, "%s: not a regular file", path);
    model->path = copy_text(path);
    model->name = copy_text(base_name(path));
    if (!model->path || !model->name) {
        luz_model_free(model);
        return luz_error_set(error, "%s: out of memory", path);
    }

    /* SCENE.md's steps in the order assimp's own aiImportFile(path, steps)
     * runs them, validation first and then the rest, with the positions
     * checked in between (check_positions). */
    const struct aiScene *scene = aiImportFile(path, aiProcess_ValidateDataStructure);
    if (scene == NULL) {
        luz_error_set(error, "%s: not a model luz can read (%s)", path, aiGetErrorString());
        luz_model_free(model);
        return -1;
    }
    if (check_positions(scene, path, error) != 0) {
        aiReleaseImport(scene);
        luz_model_free(model);
        return -1;
    }
    /* On failure this releases the scene itself, and sets no error string. */
    scene = aiApplyPostProcessing(scene, model_steps & ~(unsigned)aiProcess_ValidateDataStructure);
    if (scene == NULL) {
        luz_error_set(error, "%s: not a model luz can read (assimp's post-processing failed)",
                      path);
        luz_model_free(model);
        return -1;
    }
    texture_cache cache = {0};
    int status_code = 0;
    uint64_t with_area = 0;
    for (unsigned m = 0; m < scene->mNumMeshes && status_code == 0; m++) {
        bool added;
        status_code = add_part(model, &cache, scene, m, &added, &with_area, error);
        if (status_code == 0 && added)
            grow_bounds(&model->bounds, luz_mesh_bounds(model->parts[model->part_count - 1].mesh),
                        model->part_count == 1);
    }
    aiReleaseImport(scene);
    for (int i = 0; i < cache.count; i++) free(cache.keys[i]);
    free(cache.keys);

    if (status_code == 0 && model->part_count == 0)
        status_code = luz_error_set(error, "%s: no triangles (only points or lines, or nothing)",
                                    path);
    if (status_code == 0) {
        /* SCENE.md's s, the largest side, in double: the float difference
         * of two huge coordinates would overflow to infinity. The lab
         * scales by 2 / s, which must be a float above 0. */
        const luz_bounds b = model->bounds;
        double side = (double)b.max.x - (double)b.min.x;
        if ((double)b.max.y - (double)b.min.y > side) side = (double)b.max.y - (double)b.min.y;
        if ((double)b.max.z - (double)b.min.z > side) side = (double)b.max.z - (double)b.min.z;
        if (!(side > 0.0))
            status_code = luz_error_set(error, "%s: the model has zero size (every vertex at "
                                               "one point)", path);
        else if (!((float)(2.0 / side) > 0.0f))
            status_code = luz_error_set(error, "%s: the model is %g units across, too large to "
                                               "scale to [-1, 1] in single precision", path,
                                        side);
    }
    /* Nothing to see from any side: every triangle a line or a point. */
    if (status_code == 0 && with_area == 0)
        status_code = luz_error_set(error, "%s: no triangle has an area (the corners of each "
                                           "are on one line)", path);
    if (status_code != 0) luz_model_free(model);
    return status_code;
}

#endif
