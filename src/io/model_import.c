/*
 * model_import.c: a model file through assimp's C API into its description
 * (io/model_import.h, io/model_description.h; SCENE.md, "Models").
 *
 * In:  a path to any file assimp reads (OBJ, glTF 2.0, PLY, STL, FBX, 3DS,
 *      ...), or its bytes in memory.
 * Out: the description of its triangle meshes (positions, normals, uvs,
 *      indices, colour, names, the texture each names) and of the embedded
 *      textures they use; or one line saying why not.
 *
 * assimp does the parsing with exactly SCENE.md's post-processing steps;
 * this file checks what it returns before the steps run (check_imported)
 * and copies out what luz needs, so that nothing of assimp crosses to the
 * process that renders (model_load.c, which checks it all again).
 *
 * assimp reads every file through luz's own file system (an aiFileIO):
 * the model and each file it names (an OBJ's .mtl, a glTF's .bin) are
 * opened as io/input_file.h opens any input, never blocking, regular files
 * only, at most LUZ_MODEL_FILE_MAX_BYTES each. assimp carries on without a
 * .mtl it cannot open, as without a missing one; but a file that luz
 * refused (a FIFO, a device, one too large) makes the whole model refused,
 * naming that file. Each file opened is recorded (its path, device and
 * inode) and listed in the description: they are all inputs of the run,
 * which luz-render's -o must not replace.
 */
#include "io/model_import.h"

#if defined(LUZ_HAVE_ASSIMP)

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "io/input_file.h"
#include "io/model_sandbox.h"
#include "luz/texture.h"

/* SCENE.md's steps, exactly. */
static const unsigned int model_steps =
    aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
    aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_FlipUVs |
    aiProcess_ValidateDataStructure;

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
    luz_described_file *opened;    /* every file opened, once each (by device
                                      and inode): inputs of the run, which
                                      the description lists */
    int opened_count;
    bool opened_lost;              /* memory ran out recording one */
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

/* Records the file open at descriptor, as path, unless it is recorded
 * already; false if memory ran out (the caller refuses the model: an
 * unrecorded input could be overwritten). */
static bool record_opened(model_files *files, const char *path, int descriptor)
{
    struct stat status;
    if (fstat(descriptor, &status) != 0) return true;   /* luz_input_open did: cannot fail */
    for (int i = 0; i < files->opened_count; i++)
        if (files->opened[i].device == (uint64_t)status.st_dev &&
            files->opened[i].inode == (uint64_t)status.st_ino)
            return true;
    luz_described_file *grown =
        realloc(files->opened, (size_t)(files->opened_count + 1) * sizeof *grown);
    char *copy = grown ? strdup(path) : NULL;
    if (grown) files->opened = grown;
    if (copy == NULL) return false;
    files->opened[files->opened_count++] = (luz_described_file){
        .path = copy, .device = (uint64_t)status.st_dev, .inode = (uint64_t)status.st_ino};
    return true;
}

static void free_opened(model_files *files)
{
    for (int i = 0; i < files->opened_count; i++) free((char *)files->opened[i].path);
    free(files->opened);
    files->opened = NULL;
    files->opened_count = 0;
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
        if (!record_opened(files, path, descriptor)) {
            files->opened_lost = true;
            close(descriptor);
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

/* ---- what assimp says ---------------------------------------------------------------------- */

/* Some importers drop what they cannot use and say so only in assimp's
 * log: the glTF 2 importer drops the faces that name a vertex past the
 * end ("Some faces had out-of-range indices. Those faces were dropped."),
 * so that glTF2/IndexOutOfRange.gltf loads as a cube with a face missing.
 * SCENE.md calls an index out of range an error: the log is listened to
 * during the import, and the model refused when it says so. */
typedef struct import_log {
    bool dropped_faces;
} import_log;

static void log_line(const char *message, char *user)
{
    import_log *log = (import_log *)(void *)user;
    if (strstr(message, "out-of-range indices") != NULL) log->dropped_faces = true;
}

/* ---- what the parts use ------------------------------------------------------------------ */

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

/* ---- the description ------------------------------------------------------------------------ */

/* What the part of one assimp mesh is, before its arrays are written:
 * its counts, colour, names and texture (the names in the aiStrings). */
typedef struct mesh_part {
    luz_described_part part;
    struct aiString material_name, texture_name;
    const struct aiTexture *embedded;   /* what texture_name is, or NULL */
} mesh_part;

/* The part a mesh makes, if any: *made is false for a mesh with no
 * triangles (points or lines only), which is dropped. */
static int describe_mesh(const struct aiScene *scene, unsigned mesh_index, const char *path,
                         mesh_part *out, bool *made, luz_error *error)
{
    const struct aiMesh *source = scene->mMeshes[mesh_index];
    *made = false;
    if (source == NULL || !(source->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return 0;
    uint64_t triangles = 0;
    for (unsigned f = 0; f < source->mNumFaces; f++)
        triangles += source->mFaces[f].mNumIndices == 3;
    if (triangles == 0) return 0;
    if (triangles > LUZ_MESH_MAX_TRIANGLES)
        return luz_error_set(error, "%s: mesh %u has %u triangles, more than %u", path,
                             mesh_index, (unsigned)triangles, (unsigned)LUZ_MESH_MAX_TRIANGLES);
    if (source->mNumVertices > LUZ_MESH_MAX_VERTICES)
        return luz_error_set(error, "%s: mesh %u has %u vertices, more than %u", path,
                             mesh_index, source->mNumVertices, (unsigned)LUZ_MESH_MAX_VERTICES);
    out->part = (luz_described_part){.mesh_index = mesh_index,
                                     .vertex_count = source->mNumVertices,
                                     .triangle_count = (uint32_t)triangles,
                                     .has_uvs = source->mTextureCoords[0] != NULL,
                                     .mesh_name = source->mName.data,
                                     .material_name = "",
                                     .texture_name = "",
                                     .embedded = -1};
    out->embedded = NULL;
    *made = true;
    const struct aiMaterial *material =
        source->mMaterialIndex < scene->mNumMaterials ? scene->mMaterials[source->mMaterialIndex]
                                                      : NULL;
    if (material == NULL) return 0;
    out->part.has_colour = material_colour(material, &out->part.colour);
    if (aiGetMaterialString(material, AI_MATKEY_NAME, &out->material_name) == aiReturn_SUCCESS)
        out->part.material_name = out->material_name.data;
    if (out->part.has_uvs && aiGetMaterialTextureCount(material, aiTextureType_DIFFUSE) > 0 &&
        aiGetMaterialTexture(material, aiTextureType_DIFFUSE, 0, &out->texture_name, NULL, NULL,
                             NULL, NULL, NULL, NULL) == aiReturn_SUCCESS &&
        out->texture_name.data[0] != '\0') {
        out->part.texture_name = out->texture_name.data;
        out->embedded = find_embedded(scene, out->texture_name.data);
    }
    return 0;
}

/* The embedded textures the parts use, each once, in the order of first
 * use. */
typedef struct used_textures {
    const struct aiTexture **textures;
    int count;
} used_textures;

/* The index of texture in used, -1 if it is not there. */
static int find_used(const used_textures *used, const struct aiTexture *texture)
{
    for (int i = 0; i < used->count; i++)
        if (used->textures[i] == texture) return i;
    return -1;
}

static void write_texture(luz_model_writer *writer, const struct aiTexture *embedded,
                          const char *name)
{
    luz_described_texture texture = {.name = name, .compressed = embedded->mHeight == 0};
    _Static_assert(sizeof embedded->achFormatHint < sizeof texture.hint, "room for the hint");
    memcpy(texture.hint, embedded->achFormatHint, sizeof embedded->achFormatHint);
    if (texture.compressed) {
        texture.bytes = (const unsigned char *)embedded->pcData;
        texture.size = embedded->mWidth;
    } else {
        texture.width = embedded->mWidth;
        texture.height = embedded->mHeight;
        /* the texels only if there are some of a size luz can take */
        if (embedded->pcData != NULL && embedded->mWidth <= LUZ_TEXTURE_MAX_SIZE &&
            embedded->mHeight <= LUZ_TEXTURE_MAX_SIZE) {
            texture.bytes = (const unsigned char *)embedded->pcData;
            texture.size = (uint64_t)embedded->mWidth * embedded->mHeight * sizeof(struct aiTexel);
        }
    }
    luz_model_write_texture(writer, &texture);
}

/* One part's vertices (luz's layout) and indices, a block at a time. */
static void write_arrays(luz_model_writer *writer, const struct aiMesh *source)
{
    luz_vertex block[4096];
    const struct aiVector3D *uvs = source->mTextureCoords[0];
    for (unsigned v = 0; v < source->mNumVertices;) {
        unsigned n = 0;
        for (; n < sizeof block / sizeof block[0] && v < source->mNumVertices; n++, v++) {
            const struct aiVector3D p = source->mVertices[v];
            const struct aiVector3D normal = source->mNormals
                                                 ? source->mNormals[v]
                                                 : (struct aiVector3D){0.0f, 0.0f, 0.0f};
            block[n] = (luz_vertex){{p.x, p.y, p.z}, {normal.x, normal.y, normal.z},
                                    {uvs ? uvs[v].x : 0.0f, uvs ? uvs[v].y : 0.0f}};
        }
        luz_model_write_vertices(writer, block, n);
    }
    uint32_t indices[3 * 4096];
    size_t n = 0;
    for (unsigned f = 0; f < source->mNumFaces; f++) {
        const struct aiFace *face = &source->mFaces[f];
        if (face->mNumIndices != 3) continue;
        for (int k = 0; k < 3; k++) indices[n++] = face->mIndices[k];
        if (n == sizeof indices / sizeof indices[0]) {
            luz_model_write_indices(writer, indices, n);
            n = 0;
        }
    }
    luz_model_write_indices(writer, indices, n);
}

/* The scene, post-processed, as its description: the files the import
 * read, then the embedded textures the parts use (the reader wants them
 * before the parts that name them), then the parts. */
static int describe_scene(const struct aiScene *scene, const model_files *files,
                          const char *path, luz_model_writer *writer, luz_error *error)
{
    for (int i = 0; i < files->opened_count; i++) luz_model_write_file(writer, &files->opened[i]);
    used_textures used = {0};
    used.textures = calloc((size_t)scene->mNumTextures + 1, sizeof *used.textures);
    mesh_part *described = malloc(sizeof *described);
    int status = 0, parts = 0;
    if (!used.textures || !described) {
        status = LUZ_MACHINE_FAILED;
        luz_error_set(error, "%s: out of memory", path);
    }
    for (unsigned m = 0; m < scene->mNumMeshes && status == 0; m++) {
        bool made;
        status = describe_mesh(scene, m, path, described, &made, error);
        if (status != 0 || !made || described->embedded == NULL ||
            find_used(&used, described->embedded) >= 0)
            continue;
        used.textures[used.count] = described->embedded;
        write_texture(writer, described->embedded, described->part.texture_name);
        used.count++;
    }
    for (unsigned m = 0; m < scene->mNumMeshes && status == 0; m++) {
        bool made;
        status = describe_mesh(scene, m, path, described, &made, error);
        if (status != 0 || !made) continue;
        if (described->embedded != NULL)
            described->part.embedded = find_used(&used, described->embedded);
        luz_model_write_part_start(writer, &described->part);
        write_arrays(writer, scene->mMeshes[m]);
        luz_model_write_part_finish(writer, &described->part);
        parts++;
    }
    if (status == 0) luz_model_write_end(writer, parts, used.count);
    if (status == 0 && writer->status != 0) {
        status = LUZ_MACHINE_FAILED;
        luz_error_set(error, "%s: out of memory for its description", path);
    }
    free(used.textures);
    free(described);
    return status;
}

/* assimp's refusal in luz's words, where it says the file holds nothing
 * to draw: its words name its own structures (its validation's "Mesh
 * contains no faces", an importer's "OBJ-file is too small."). Meshes
 * without faces or vertices are what model_load.c calls a file of points
 * or lines; no mesh at all is also what assimp makes of random bytes
 * under a text format's name, so that says both. NULL for any other
 * refusal. Matched without case, as found in assimp 5.2's strings. */
static const char *nothing_to_draw(const char *why)
{
    static const char *const empty_meshes[] = {
        "contains no faces", "contains no vertices", "no faces", "no vertices",
        "file is empty",     "file is too small",
    };
    static const char *const no_meshes[] = {"mnummeshes is 0", "no meshes", "no data remains"};
    char lower[256];
    size_t n = 0;
    for (; why[n] != '\0' && n + 1 < sizeof lower; n++)
        lower[n] = (char)tolower((unsigned char)why[n]);
    lower[n] = '\0';
    for (size_t i = 0; i < sizeof no_meshes / sizeof no_meshes[0]; i++)
        if (strstr(lower, no_meshes[i]) != NULL)
            return "not a model luz can read, or an empty one (no meshes in it)";
    for (size_t i = 0; i < sizeof empty_meshes / sizeof empty_meshes[0]; i++)
        if (strstr(lower, empty_meshes[i]) != NULL)
            return "no triangles (only points or lines, or nothing)";
    return NULL;
}

int luz_model_import(const luz_model_source *source, uint64_t memory_limit,
                     luz_model_writer *writer, luz_error *error)
{
    const char *path = source->path;
    static const unsigned char nothing[1] = {0};
    model_files files = {.memory = source->memory == NULL      ? NULL
                                   : source->memory_size > 0 ? source->memory
                                                              : nothing,
                         .memory_size = source->memory_size,
                         .memory_name = path};
    struct aiFileIO io = {.OpenProc = files_open, .CloseProc = files_close,
                          .UserData = (aiUserData)&files};
    /* SCENE.md's steps in the order assimp's own aiImportFile(path, steps)
     * runs them, validation first and then the rest, with the positions
     * checked in between (check_imported). */
    import_log log = {0};
    struct aiLogStream listener = {.callback = log_line, .user = (char *)(void *)&log};
    aiAttachLogStream(&listener);
    const struct aiScene *scene = aiImportFileEx(path, aiProcess_ValidateDataStructure, &io);
    aiDetachLogStream(&listener);
    if (scene != NULL && files.refusal == 0 && log.dropped_faces) {
        aiReleaseImport(scene);
        free_opened(&files);
        return luz_error_set(error, "%s: some faces name a vertex that is not there (an index "
                                    "out of range; assimp's importer dropped them)", path);
    }
    if (files.refusal != 0 || files.opened_lost) {
        /* a file the model names was refused (and assimp may have carried
         * on without it): the model is refused with it */
        if (scene != NULL) aiReleaseImport(scene);
        free_opened(&files);
        if (files.refusal == 0) {
            luz_error_set(error, "%s: out of memory for the names of the files it reads", path);
            return LUZ_MACHINE_FAILED;
        }
        luz_error_set(error, "%s: %s", path, files.refusal_error.message);
        return files.refusal;
    }
    if (scene == NULL) {
        free_opened(&files);
        const char *why = aiGetErrorString();
        if (memory_limit > 0 && strstr(why, "bad_alloc") != NULL)
            return luz_model_memory_refusal(path, memory_limit, error);
        if (nothing_to_draw(why) != NULL)
            return luz_error_set(error, "%s: %s", path, nothing_to_draw(why));
        return luz_error_set(error, "%s: not a model luz can read (%s)", path, why);
    }
    if (check_imported(scene, path, error) != 0) {
        aiReleaseImport(scene);
        free_opened(&files);
        return LUZ_BAD_INPUT;
    }
    /* On failure this releases the scene itself, and sets no error string. */
    scene = aiApplyPostProcessing(scene, model_steps & ~(unsigned)aiProcess_ValidateDataStructure);
    if (scene == NULL) {
        free_opened(&files);
        return luz_error_set(error, "%s: not a model luz can read (assimp's post-processing "
                                    "failed)", path);
    }
    int status = describe_scene(scene, &files, path, writer, error);
    aiReleaseImport(scene);
    free_opened(&files);
    return status;
}

#endif
