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
 *
 * assimp reads every file through luz's own file system (an aiFileIO):
 * the model and each file it names (an OBJ's .mtl, a glTF's .bin) are
 * opened as io/input_file.h opens any input, never blocking, regular files
 * only, at most LUZ_MODEL_FILE_MAX_BYTES each. assimp carries on without a
 * .mtl it cannot open, as without a missing one; but a file that luz
 * refused (a FIFO, a device, one too large) makes the whole model refused,
 * naming that file. Textures are decoded by io/textures.h, within the
 * run's texture budget.
 */
#include "io/model.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/input_file.h"
#include "io/model_guards.h"
#include "io/textures.h"

#if defined(LUZ_HAVE_ASSIMP)
#include <assimp/cfileio.h>
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

int luz_model_load(luz_model *model, const char *path, luz_texture_budget *budget,
                   luz_error *error)
{
    (void)budget;
    memset(model, 0, sizeof *model);
    return luz_error_set(error, "%s: this luz was built without model support (assimp; "
                                "-Dmodels=enabled needs libassimp-dev)", path);
}

int luz_model_load_memory(luz_model *model, const unsigned char *bytes, size_t size,
                          const char *name, luz_texture_budget *budget, luz_error *error)
{
    (void)bytes;
    (void)size;
    return luz_model_load(model, name, budget, error);
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

/* ---- the files assimp reads ------------------------------------------------------------- */

/* luz's file system for assimp: every file it asks for (the model, then
 * whatever the model names) is opened with luz_input_open, or, for a model
 * in memory, is that model or nothing. */
typedef struct model_files {
    const unsigned char *memory;   /* a model in memory (the fuzzer's), else NULL */
    size_t memory_size;
    const char *memory_name;       /* the one name it answers to */
    int refusal;                   /* 0, or the status of the first file refused */
    luz_error refusal_error;       /* its message */
} model_files;

/* One open file: a descriptor, or the model in memory. */
typedef struct model_file {
    struct aiFile file;            /* first: assimp's handle is this struct */
    int descriptor;                /* -1 for the model in memory */
    const unsigned char *memory;
    uint64_t size, position;
} model_file;

static size_t file_read(struct aiFile *handle, char *buffer, size_t size, size_t count)
{
    model_file *file = (model_file *)handle;
    if (size == 0 || file->position >= file->size) return 0;
    const uint64_t left = file->size - file->position;
    if (count > left / size) count = (size_t)(left / size);
    size_t wanted = size * count, done = 0;
    while (done < wanted) {
        if (file->memory != NULL) {
            memcpy(buffer, file->memory + file->position, wanted);
            done = wanted;
            break;
        }
        ssize_t got = pread(file->descriptor, buffer + done, wanted - done,
                            (off_t)(file->position + done));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) break;   /* an error, or the file shrank: what was read */
        done += (size_t)got;
    }
    file->position += done;
    return done / size;
}

static size_t file_write(struct aiFile *handle, const char *buffer, size_t size, size_t count)
{
    (void)handle;
    (void)buffer;
    (void)size;
    (void)count;
    return 0;   /* opened for reading only */
}

static size_t file_tell(struct aiFile *handle)
{
    return (size_t)((model_file *)handle)->position;
}

static size_t file_size(struct aiFile *handle)
{
    return (size_t)((model_file *)handle)->size;
}

/* assimp passes a negative offset (from the end, or back from here) as a
 * size_t, wrapped around, as C's fseek would take a long. */
static enum aiReturn file_seek(struct aiFile *handle, size_t offset, enum aiOrigin origin)
{
    model_file *file = (model_file *)handle;
    const uint64_t base = origin == aiOrigin_SET   ? 0
                          : origin == aiOrigin_CUR ? file->position
                          : origin == aiOrigin_END ? file->size
                                                   : UINT64_MAX;
    if (base == UINT64_MAX) return aiReturn_FAILURE;
    const uint64_t target = base + (uint64_t)offset;   /* modulo 2^64: a wrapped offset subtracts */
    if (target > file->size) return aiReturn_FAILURE;
    file->position = target;
    return aiReturn_SUCCESS;
}

static void file_flush(struct aiFile *handle)
{
    (void)handle;
}

static struct aiFile *files_open(struct aiFileIO *io, const char *path, const char *mode)
{
    model_files *files = (model_files *)io->UserData;
    if (path == NULL || mode == NULL || strpbrk(mode, "wa+") != NULL) return NULL;
    int descriptor = -1;
    uint64_t size = 0;
    const unsigned char *memory = NULL;
    if (files->memory != NULL) {
        if (strcmp(path, files->memory_name) != 0) return NULL;   /* nothing else exists */
        memory = files->memory;
        size = files->memory_size;
    } else {
        luz_error refusal;
        int status = luz_input_open(path, "a file the model names", LUZ_MODEL_FILE_MAX_BYTES,
                                    &descriptor, &size, &refusal);
        if (status == LUZ_NO_SUCH_FILE) return NULL;   /* assimp decides what that means */
        if (status != 0) {
            if (files->refusal == 0) {
                files->refusal = status;
                files->refusal_error = refusal;
            }
            return NULL;
        }
    }
    model_file *file = calloc(1, sizeof *file);
    if (file == NULL) {
        if (descriptor >= 0) close(descriptor);
        return NULL;
    }
    file->file = (struct aiFile){.ReadProc = file_read, .WriteProc = file_write,
                                 .TellProc = file_tell, .FileSizeProc = file_size,
                                 .SeekProc = file_seek, .FlushProc = file_flush};
    file->descriptor = descriptor;
    file->memory = memory;
    file->size = size;
    return &file->file;
}

static void files_close(struct aiFileIO *io, struct aiFile *handle)
{
    (void)io;
    model_file *file = (model_file *)handle;
    if (file == NULL) return;
    if (file->descriptor >= 0) close(file->descriptor);
    free(file);
}

/* ---- textures --------------------------------------------------------------------------- */

/* What reading one model needs besides the model: assimp's scene, where
 * its files come from, the run's texture budget, and the textures already
 * decoded, by the name the materials use, so that the parts that share
 * one share its memory. */
typedef struct model_reading {
    luz_model *model;
    const struct aiScene *scene;
    model_files *files;
    luz_texture_budget *budget;
    char **texture_keys;
    int texture_key_count;
} model_reading;

static int remember_texture(model_reading *reading, const char *key, luz_texture *texture,
                            luz_error *error)
{
    luz_model *model = reading->model;
    luz_texture **textures =
        realloc(model->textures, (size_t)(model->texture_count + 1) * sizeof *textures);
    if (textures) model->textures = textures;
    char **keys =
        realloc(reading->texture_keys, (size_t)(reading->texture_key_count + 1) * sizeof *keys);
    if (keys) reading->texture_keys = keys;
    char *copy = copy_text(key);
    if (!textures || !keys || !copy) {
        free(copy);
        luz_texture_destroy(texture);
        luz_error_set(error, "%s: out of memory for its textures", model->path);
        return LUZ_MACHINE_FAILED;
    }
    model->textures[model->texture_count++] = texture;
    reading->texture_keys[reading->texture_key_count++] = copy;
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
 * ..., the format in achFormatHint) and decoded like a file, or raw BGRA
 * texels. */
static int decode_embedded(const struct aiTexture *embedded, const char *name,
                           luz_texture_budget *budget, luz_texture **texture, luz_error *error)
{
    if (embedded->mHeight == 0) {
        char hint[sizeof embedded->achFormatHint + 1] = {0};
        memcpy(hint, embedded->achFormatHint, sizeof embedded->achFormatHint);
        return luz_texture_load_memory((const unsigned char *)embedded->pcData,
                                       embedded->mWidth, name, hint, budget, texture, error);
    }
    const unsigned width = embedded->mWidth, height = embedded->mHeight;
    if (embedded->pcData == NULL || width > LUZ_TEXTURE_MAX_SIZE || height > LUZ_TEXTURE_MAX_SIZE)
        return luz_error_set(error, "%s: image is %ux%u, expected 1x1 to %dx%d", name, width,
                             height, LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
    if (luz_texture_budget_check(budget, (int)width, (int)height, name, error) != 0)
        return LUZ_BAD_INPUT;
    uint8_t *rgba = malloc((size_t)width * height * 4 + 1);
    if (!rgba) {
        luz_error_set(error, "%s: out of memory for a %ux%u texture", name, width, height);
        return LUZ_MACHINE_FAILED;
    }
    for (size_t i = 0; i < (size_t)width * height; i++) {
        const struct aiTexel *texel = &embedded->pcData[i];
        rgba[i * 4 + 0] = texel->r;
        rgba[i * 4 + 1] = texel->g;
        rgba[i * 4 + 2] = texel->b;
        rgba[i * 4 + 3] = texel->a;
    }
    int status = luz_texture_create_in_budget((int)width, (int)height, rgba, name, budget,
                                              texture, error);
    free(rgba);
    return status;
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
        if (scene->mTextures[i] == NULL) continue;
        const char *own = scene->mTextures[i]->mFilename.data;
        if (own[0] != '\0' && (strcmp(own, name) == 0 || strcmp(base_name(own), base_name(name)) == 0))
            return scene->mTextures[i];
    }
    return NULL;
}

/* The texture a material names, decoded once: embedded in the file, else
 * a file relative to the model's directory, a backslash read as a slash
 * (files written on Windows say `.\tex\a.jpg`). */
static int load_texture(model_reading *reading, const char *name, const luz_texture **out,
                        luz_error *error)
{
    luz_model *model = reading->model;
    for (int i = 0; i < reading->texture_key_count; i++) {
        if (strcmp(reading->texture_keys[i], name) == 0) {
            *out = model->textures[i];
            return 0;
        }
    }
    luz_error inner = {{0}};
    luz_texture *texture = NULL;
    int status;
    const struct aiTexture *embedded = find_embedded(reading->scene, name);
    if (embedded != NULL) {
        status = decode_embedded(embedded, name, reading->budget, &texture, &inner);
    } else if (name[0] == '*') {
        status = luz_error_set(&inner, "%s: no such embedded texture", name);
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
        if (reading->files->memory != NULL)
            status = luz_error_set(&inner, "%s: no such file (the model is read from memory)",
                                   path);
        else {
            status = luz_texture_load(path, reading->budget, &texture, &inner);
            if (status == 0 && remember_texture_file(model, path, &inner) != 0) {
                luz_texture_destroy(texture);
                texture = NULL;
                status = LUZ_MACHINE_FAILED;
            }
        }
    }
    if (status != 0) {
        luz_error_set(error, "%s: texture '%s': %s", model->path, name, inner.message);
        return status == LUZ_MACHINE_FAILED ? status : LUZ_BAD_INPUT;
    }
    status = remember_texture(reading, name, texture, error);
    if (status != 0) return status;
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
static int add_part(model_reading *reading, unsigned mesh_index, bool *added,
                    uint64_t *with_area, luz_error *error)
{
    luz_model *model = reading->model;
    const struct aiScene *scene = reading->scene;
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
        luz_error_set(error, "%s: out of memory for mesh %u (%u vertices)", model->path,
                      mesh_index, vertex_count);
        return LUZ_MACHINE_FAILED;
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
            int status = load_texture(reading, texture_name.data, &part.texture, error);
            if (status != 0) {
                free_part_names(&part);
                luz_mesh_destroy(mesh);
                return status;
            }
        }
    }

    luz_model_part *parts = names_fit ? realloc(model->parts,
                                                (size_t)(model->part_count + 1) * sizeof *parts)
                                      : NULL;
    if (!parts) {
        free_part_names(&part);
        luz_mesh_destroy(mesh);
        luz_error_set(error, "%s: out of memory for its meshes", model->path);
        return LUZ_MACHINE_FAILED;
    }
    model->parts = parts;
    model->parts[model->part_count++] = part;
    model->triangle_count += triangles;
    *added = true;
    return 0;
}

/* What the importer gave, checked before the steps run:
 *  - every position: a NaN compares equal to nothing, so
 *    JoinIdenticalVertices can merge a NaN vertex into a finite one and
 *    leave a degenerate triangle that draws nothing, and the file would
 *    load as if it were sound;
 *  - every face, and every mesh's primitive types against its faces: for
 *    files luz's fuzzer made, assimp 5.2.5's PLY importer gives faces of
 *    no corners, on which SortByPType crashes, or, in a mesh it marks as
 *    holding polygons, on which an assertion in Triangulate (that a mesh
 *    marked so has a polygon) aborts the program. ValidateDataStructure
 *    lets both through: it checks only that each face's kind is marked.
 *    (tests/fuzz/assimp-findings/) */
static int check_imported(const struct aiScene *scene, const char *path, luz_error *error)
{
    for (unsigned m = 0; m < scene->mNumMeshes; m++) {
        const struct aiMesh *mesh = scene->mMeshes[m];
        if (mesh == NULL) continue;
        bool polygon = false;
        for (unsigned f = 0; f < mesh->mNumFaces && mesh->mFaces != NULL; f++) {
            const struct aiFace *face = &mesh->mFaces[f];
            if (face->mNumIndices == 0 || face->mIndices == NULL)
                return luz_error_set(error, "%s: not a model luz can read (assimp's importer "
                                            "gave mesh %u a face with no corners)", path, m);
            for (unsigned k = 0; k < face->mNumIndices; k++)
                if (face->mIndices[k] >= mesh->mNumVertices)
                    return luz_error_set(error, "%s: mesh %u: face %u names vertex %u of %u",
                                         path, m, f, face->mIndices[k], mesh->mNumVertices);
            polygon = polygon || face->mNumIndices > 3;
        }
        if ((mesh->mPrimitiveTypes & aiPrimitiveType_POLYGON) && !polygon)
            return luz_error_set(error, "%s: not a model luz can read (assimp's importer gave "
                                        "mesh %u polygons it does not have)", path, m);
        if (mesh->mVertices == NULL) continue;
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

/* assimp's import of path through files, then luz's checks of what it
 * returns. model->path and ->name are set. */
static int read_model(luz_model *model, const char *path, model_files *files,
                      luz_texture_budget *budget, luz_error *error)
{
    struct aiFileIO io = {.OpenProc = files_open, .CloseProc = files_close,
                          .UserData = (aiUserData)files};
    /* SCENE.md's steps in the order assimp's own aiImportFile(path, steps)
     * runs them, validation first and then the rest, with the positions
     * checked in between (check_imported). */
    const struct aiScene *scene = aiImportFileEx(path, aiProcess_ValidateDataStructure, &io);
    if (files->refusal != 0) {
        /* a file the model names was refused (and assimp may have carried
         * on without it): the model is refused with it */
        if (scene != NULL) aiReleaseImport(scene);
        luz_error_set(error, "%s: %s", path, files->refusal_error.message);
        return files->refusal;
    }
    if (scene == NULL)
        return luz_error_set(error, "%s: not a model luz can read (%s)", path,
                             aiGetErrorString());
    if (check_imported(scene, path, error) != 0) {
        aiReleaseImport(scene);
        return LUZ_BAD_INPUT;
    }
    /* On failure this releases the scene itself, and sets no error string. */
    scene = aiApplyPostProcessing(scene, model_steps & ~(unsigned)aiProcess_ValidateDataStructure);
    if (scene == NULL)
        return luz_error_set(error, "%s: not a model luz can read (assimp's post-processing "
                                    "failed)", path);
    model_reading reading = {.model = model, .scene = scene, .files = files, .budget = budget};
    int status = 0;
    uint64_t with_area = 0;
    for (unsigned m = 0; m < scene->mNumMeshes && status == 0; m++) {
        bool added;
        status = add_part(&reading, m, &added, &with_area, error);
        if (status == 0 && added)
            grow_bounds(&model->bounds, luz_mesh_bounds(model->parts[model->part_count - 1].mesh),
                        model->part_count == 1);
    }
    aiReleaseImport(scene);
    for (int i = 0; i < reading.texture_key_count; i++) free(reading.texture_keys[i]);
    free(reading.texture_keys);
    if (status != 0) return status;

    if (model->part_count == 0)
        return luz_error_set(error, "%s: no triangles (only points or lines, or nothing)", path);
    /* SCENE.md's s, the largest side, in double: the float difference of
     * two huge coordinates would overflow to infinity. The lab scales by
     * 2 / s, which must be a float above 0. */
    const luz_bounds b = model->bounds;
    double side = (double)b.max.x - (double)b.min.x;
    if ((double)b.max.y - (double)b.min.y > side) side = (double)b.max.y - (double)b.min.y;
    if ((double)b.max.z - (double)b.min.z > side) side = (double)b.max.z - (double)b.min.z;
    if (!(side > 0.0))
        return luz_error_set(error, "%s: the model has zero size (every vertex at one point)",
                             path);
    if (!((float)(2.0 / side) > 0.0f))
        return luz_error_set(error, "%s: the model is %g units across, too large to scale to "
                                    "[-1, 1] in single precision", path, side);
    /* Nothing to see from any side: every triangle a line or a point. */
    if (with_area == 0)
        return luz_error_set(error, "%s: no triangle has an area (the corners of each are on "
                                    "one line)", path);
    return 0;
}

/* Sets the model's path and name, reads it, and leaves it empty on
 * failure. */
static int load(luz_model *model, const char *path, model_files *files,
                luz_texture_budget *budget, luz_error *error)
{
    model->path = copy_text(path);
    model->name = copy_text(base_name(path));
    if (!model->path || !model->name) {
        luz_model_free(model);
        luz_error_set(error, "%s: out of memory", path);
        return LUZ_MACHINE_FAILED;
    }
    luz_texture_budget own = {0};
    int status = read_model(model, path, files, budget ? budget : &own, error);
    if (status != 0) luz_model_free(model);
    return status;
}

int luz_model_load(luz_model *model, const char *path, luz_texture_budget *budget,
                   luz_error *error)
{
    memset(model, 0, sizeof *model);
    /* the model itself first, for a message of luz's own about it */
    int descriptor;
    uint64_t size;
    int status = luz_input_open(path, "a model file", LUZ_MODEL_FILE_MAX_BYTES, &descriptor,
                                &size, error);
    if (status != 0) return LUZ_BAD_INPUT;
    /* its start, for the checks that keep assimp's known bugs out */
    unsigned char start[LUZ_PLY_HEADER_MAX_BYTES];
    size_t length = 0;
    while (length < sizeof start) {
        ssize_t got = pread(descriptor, start + length, sizeof start - length, (off_t)length);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) break;
        length += (size_t)got;
    }
    close(descriptor);
    if (luz_model_check_start(start, length, size, path, error) != 0) return LUZ_BAD_INPUT;
    model_files files = {0};
    return load(model, path, &files, budget, error);
}

int luz_model_load_memory(luz_model *model, const unsigned char *bytes, size_t size,
                          const char *name, luz_texture_budget *budget, luz_error *error)
{
    memset(model, 0, sizeof *model);
    if (luz_model_check_start(bytes, size, size, name, error) != 0) return LUZ_BAD_INPUT;
    static const unsigned char nothing[1] = {0};
    model_files files = {.memory = size > 0 ? bytes : nothing, .memory_size = size,
                         .memory_name = name};
    return load(model, name, &files, budget, error);
}

#endif
