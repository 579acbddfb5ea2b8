/*
 * model_load.c: a model file into a luz_model (SCENE.md, "Models").
 *
 * In:  a path to any file assimp reads (OBJ, glTF 2.0, PLY, STL, FBX, 3DS,
 *      ...).
 * Out: one luz_mesh per triangle mesh of the file, in its order, with the
 *      colour and the texture of its material, and the bounds of them all.
 *
 * assimp reads the file in a child process, within a time and memory limit
 * (io/model_sandbox.h, io/model_import.h), and sends back a description
 * of the model with no assimp in it (io/model_description.h). This file
 * turns that description into luz meshes and textures, checking it as it
 * would check any stranger's data (luz_mesh_create refuses an index out of
 * range or a position that is not finite), and decodes the textures the
 * parts name, files beside the model or embedded in it, with
 * io/textures.h, within the run's texture budget: the image decoders, the
 * budget and the files a run reads stay in luz's own process.
 * luz_model_load_memory (the fuzzer's) runs the import in this process.
 */
#include "io/model.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/input_file.h"
#include "io/model_confine.h"
#include "io/model_description.h"
#include "io/model_guards.h"
#include "io/model_import.h"
#include "io/model_sandbox.h"
#include "io/textures.h"

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
    for (int i = 0; i < model->warning_count; i++) free(model->warnings[i]);
    free(model->warnings);
    for (int i = 0; i < model->read_file_count; i++) free(model->read_files[i].path);
    free(model->read_files);
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

int luz_model_load_with(luz_model *model, const char *path, const luz_model_rules *rules,
                        luz_texture_budget *budget, luz_error *error)
{
    (void)rules;
    return luz_model_load(model, path, budget, error);
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

/* What building one model needs besides the model: its description, whether
 * it was read from memory (then no other file exists), the run's texture
 * budget, and the textures already decoded, by the name the materials use,
 * so that the parts that share one share its memory. */
typedef struct model_reading {
    luz_model *model;
    const luz_model_description *description;
    bool from_memory;
    luz_model_files files;        /* where its texture files may be */
    luz_texture_budget *budget;
    char **texture_keys;
    const luz_texture **keyed_textures;   /* one per key; NULL for a texture
                                             that could not be read (warned
                                             about once) */
    int texture_key_count;
} model_reading;

/* Remembers what the name key gave: a texture (then the model owns it),
 * or NULL for one that is missing or corrupt, so that the parts naming
 * it again neither read it nor warn again. */
static int remember_texture(model_reading *reading, const char *key, luz_texture *texture,
                            luz_error *error)
{
    luz_model *model = reading->model;
    luz_texture **textures =
        texture ? realloc(model->textures, (size_t)(model->texture_count + 1) * sizeof *textures)
                : model->textures;
    if (textures) model->textures = textures;
    const int count = reading->texture_key_count;
    char **keys = realloc(reading->texture_keys, (size_t)(count + 1) * sizeof *keys);
    if (keys) reading->texture_keys = keys;
    const luz_texture **keyed =
        realloc(reading->keyed_textures, (size_t)(count + 1) * sizeof *keyed);
    if (keyed) reading->keyed_textures = keyed;
    char *copy = copy_text(key);
    if ((texture && !textures) || !keys || !keyed || !copy) {
        free(copy);
        luz_texture_destroy(texture);
        luz_error_set(error, "%s: out of memory for its textures", model->path);
        return LUZ_MACHINE_FAILED;
    }
    if (texture) model->textures[model->texture_count++] = texture;
    reading->texture_keys[count] = copy;
    reading->keyed_textures[count] = texture;
    reading->texture_key_count = count + 1;
    return 0;
}

/* A warning for the user, kept on the model (the programs print them
 * once, after loading): one line. */
static int add_warning(luz_model *model, const char *text, luz_error *error)
{
    char **warnings =
        realloc(model->warnings, (size_t)(model->warning_count + 1) * sizeof *warnings);
    if (warnings) model->warnings = warnings;
    char *copy = copy_text(text);
    if (!warnings || !copy) {
        free(copy);
        luz_error_set(error, "%s: out of memory for its warnings", model->path);
        return LUZ_MACHINE_FAILED;
    }
    model->warnings[model->warning_count++] = copy;
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

/* An embedded texture: compressed (the bytes of a PNG, JPEG, ..., the
 * format in the hint) and decoded like a file, or raw BGRA texels. */
static int decode_embedded(const luz_described_texture *embedded, const char *name,
                           luz_texture_budget *budget, luz_texture **texture, luz_error *error)
{
    if (embedded->compressed)
        return luz_texture_load_memory(embedded->bytes, (size_t)embedded->size, name,
                                       embedded->hint, budget, texture, error);
    const unsigned width = embedded->width, height = embedded->height;
    if (embedded->bytes == NULL || width > LUZ_TEXTURE_MAX_SIZE || height > LUZ_TEXTURE_MAX_SIZE)
        return luz_error_set(error, "%s: image is %ux%u, expected 1x1 to %dx%d", name, width,
                             height, LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
    /* BGRA texels, 4 bytes each, as many as the size says */
    if (embedded->size != (uint64_t)width * height * 4)
        return luz_error_set(error, "%s: %llu bytes of texels for a %ux%u image", name,
                             (unsigned long long)embedded->size, width, height);
    if (luz_texture_budget_check(budget, (int)width, (int)height, name, error) != 0)
        return LUZ_BAD_INPUT;
    uint8_t *rgba = malloc((size_t)width * height * 4 + 1);
    if (!rgba) {
        luz_error_set(error, "%s: out of memory for a %ux%u texture", name, width, height);
        return LUZ_MACHINE_FAILED;
    }
    for (size_t i = 0; i < (size_t)width * height; i++) {
        const unsigned char *texel = embedded->bytes + 4 * i;   /* assimp's aiTexel: b g r a */
        rgba[i * 4 + 0] = texel[2];
        rgba[i * 4 + 1] = texel[1];
        rgba[i * 4 + 2] = texel[0];
        rgba[i * 4 + 3] = texel[3];
    }
    int status = luz_texture_create_in_budget((int)width, (int)height, rgba, name, budget,
                                              texture, error);
    free(rgba);
    return status;
}

/* The texture a material names, decoded once: embedded in the file (the
 * import found it, as "*N" or by the embedded texture's own file name),
 * else a file relative to the model's directory, a backslash read as a
 * slash (files written on Windows say `.\tex\a.jpg`). One that is
 * missing or corrupt gives *out = NULL (T = 1) and one warning on the
 * model (SCENE.md, "Models": files from the web often name textures on
 * their author's disk); only running out of memory is an error. */
static int load_texture(model_reading *reading, const char *name, int32_t embedded,
                        const luz_texture **out, luz_error *error)
{
    luz_model *model = reading->model;
    *out = NULL;
    for (int i = 0; i < reading->texture_key_count; i++) {
        if (strcmp(reading->texture_keys[i], name) == 0) {
            *out = reading->keyed_textures[i];
            return 0;
        }
    }
    luz_error inner = {{0}};
    luz_texture *texture = NULL;
    int status;
    if (embedded >= 0) {
        status = decode_embedded(&reading->description->textures[embedded], name,
                                 reading->budget, &texture, &inner);
    } else if (name[0] == '*') {
        status = luz_error_set(&inner, "%s: no such embedded texture", name);
    } else {
        char relative[4096];
        snprintf(relative, sizeof relative, "%s", name);
        for (char *c = relative; *c; c++)
            if (*c == '\\') *c = '/';
        const char *file = relative;
        while (file[0] == '.' && file[1] == '/') file += 2;
        /* the model's folder: its path up to the last slash ("/" for a
         * file at the root, "." for a bare name) */
        char folder[4096], path[8192];
        const char *slash = strrchr(model->path, '/');
        if (slash == NULL)
            snprintf(folder, sizeof folder, ".");
        else if (slash == model->path)
            snprintf(folder, sizeof folder, "/");
        else
            snprintf(folder, sizeof folder, "%.*s", (int)(slash - model->path), model->path);
        if (file[0] == '/')
            snprintf(path, sizeof path, "%s", file);
        else
            snprintf(path, sizeof path, "%s%s%s", folder, slash == model->path ? "" : "/", file);
        if (reading->from_memory) {
            status = luz_error_set(&inner, "%s: no such file (the model is read from memory)",
                                   path);
        } else if (reading->files == LUZ_MODEL_FILES_FOLDER) {
            /* Within the model's folder: a name that leads out of it is
             * as good as missing (issue 32: a stranger's file must not
             * pull any image of the machine into the picture). */
            status = luz_texture_load_beneath(folder, file, reading->budget, &texture, &inner);
            if (status == LUZ_OUTSIDE_DIRECTORY) {
                luz_error rule = inner;
                luz_error_set(&inner, "%s; a model's textures are read from its folder only, "
                                      "unless --model-files anywhere", rule.message);
            }
        } else {
            status = luz_texture_load(path, reading->budget, &texture, &inner);
        }
        if (!reading->from_memory) {
            if (status == 0 && remember_texture_file(model, path, &inner) != 0) {
                luz_texture_destroy(texture);
                texture = NULL;
                status = LUZ_MACHINE_FAILED;
            }
        }
    }
    if (status == LUZ_MACHINE_FAILED) {
        luz_error_set(error, "%s: texture '%s': %s", model->path, name, inner.message);
        return status;
    }
    if (status != 0) {
        luz_error warning;
        luz_error_set(&warning, "%s: texture '%s': %s; drawn without it (T = 1)", model->path,
                      name, inner.message);
        status = add_warning(model, warning.message, error);
        if (status != 0) return status;
        texture = NULL;
    }
    status = remember_texture(reading, name, texture, error);
    if (status != 0) return status;
    *out = texture;
    return 0;
}

/* ---- meshes ------------------------------------------------------------------------------ */

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

/* One described part as a luz part, its texture decoded. *with_area
 * grows by the number of its triangles that have an area. */
static int add_part(model_reading *reading, const luz_described_part *source,
                    uint64_t *with_area, luz_error *error)
{
    luz_model *model = reading->model;
    const unsigned mesh_index = source->mesh_index;
    const uint32_t triangles = source->triangle_count;
    if (triangles == 0)
        return luz_error_set(error, "%s: mesh %u has no triangles", model->path, mesh_index);
    if (triangles > LUZ_MESH_MAX_TRIANGLES)
        return luz_error_set(error, "%s: mesh %u has %u triangles, more than %u", model->path,
                             mesh_index, (unsigned)triangles, (unsigned)LUZ_MESH_MAX_TRIANGLES);
    const unsigned vertex_count = source->vertex_count;
    if (vertex_count > LUZ_MESH_MAX_VERTICES)
        return luz_error_set(error, "%s: mesh %u has %u vertices, more than %u", model->path,
                             mesh_index, vertex_count, (unsigned)LUZ_MESH_MAX_VERTICES);
    luz_error inner;
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = source->vertices,
                                                      .vertex_count = vertex_count,
                                                      .indices = source->indices,
                                                      .index_count = triangles * 3},
                                     &inner);
    if (mesh == NULL)
        return luz_error_set(error, "%s: mesh %u: %s", model->path, mesh_index, inner.message);
    *with_area += count_with_area(source->vertices, source->indices, triangles);

    luz_model_part part = {.mesh = mesh, .has_uvs = source->has_uvs,
                           .has_colour = source->has_colour, .colour = source->colour};
    bool names_fit = name_part(&part.mesh_name, source->mesh_name) &&
                     name_part(&part.material_name, source->material_name);
    if (part.has_uvs && source->texture_name[0] != '\0') {
        names_fit = name_part(&part.texture_name, source->texture_name) && names_fit;
        int status = load_texture(reading, source->texture_name, source->embedded,
                                  &part.texture, error);
        if (status != 0) {
            free_part_names(&part);
            luz_mesh_destroy(mesh);
            return status;
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

/* The files the import read, kept for luz-render's check that no output
 * replaces an input. */
static int keep_read_files(luz_model *model, const luz_model_description *description,
                           luz_error *error)
{
    if (description->file_count == 0) return 0;
    model->read_files = calloc((size_t)description->file_count, sizeof *model->read_files);
    if (model->read_files == NULL) {
        luz_error_set(error, "%s: out of memory for the names of the files it read", model->path);
        return LUZ_MACHINE_FAILED;
    }
    for (int i = 0; i < description->file_count; i++) {
        const luz_described_file *file = &description->files[i];
        char *path = copy_text(file->path);
        if (path == NULL) {
            luz_error_set(error, "%s: out of memory for the names of the files it read",
                          model->path);
            return LUZ_MACHINE_FAILED;
        }
        model->read_files[model->read_file_count++] =
            (luz_input_file_id){.path = path, .device = file->device, .inode = file->inode};
    }
    return 0;
}

/* The description's parts as the model's, then the checks of the whole:
 * some triangle, a size, some area. model->path is set. */
static int build_model(luz_model *model, const luz_model_description *description,
                       bool from_memory, luz_model_files files, luz_texture_budget *budget,
                       luz_error *error)
{
    const char *path = model->path;
    model_reading reading = {.model = model, .description = description,
                             .from_memory = from_memory, .files = files, .budget = budget};
    int status = 0;
    uint64_t with_area = 0;
    for (int p = 0; p < description->part_count && status == 0; p++) {
        status = add_part(&reading, &description->parts[p], &with_area, error);
        if (status == 0)
            grow_bounds(&model->bounds, luz_mesh_bounds(model->parts[model->part_count - 1].mesh),
                        model->part_count == 1);
    }
    for (int i = 0; i < reading.texture_key_count; i++) free(reading.texture_keys[i]);
    free(reading.texture_keys);
    free(reading.keyed_textures);
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

/* The description in bytes, read and built into model (path and name
 * set first); the model is left empty on failure. */
static int build(luz_model *model, const char *path, const unsigned char *bytes, size_t size,
                 bool from_memory, luz_model_files files, luz_texture_budget *budget,
                 luz_error *error)
{
    model->path = copy_text(path);
    model->name = copy_text(base_name(path));
    if (!model->path || !model->name) {
        luz_model_free(model);
        luz_error_set(error, "%s: out of memory", path);
        return LUZ_MACHINE_FAILED;
    }
    luz_model_description description;
    int status = luz_model_description_read(bytes, size, path, &description, error);
    if (status == 0 && description.refusal != 0) {
        luz_error_set(error, "%s", description.refusal_message);
        status = description.refusal;
    }
    luz_texture_budget own = {0};
    if (status == 0) status = keep_read_files(model, &description, error);
    if (status == 0)
        status = build_model(model, &description, from_memory, files, budget ? budget : &own,
                             error);
    luz_model_description_free(&description);
    if (status != 0) luz_model_free(model);
    return status;
}

/* The child's work: the import, its description down the pipe. */
static int import_in_child(const void *context, uint64_t memory_limit, luz_model_writer *writer,
                           luz_error *error)
{
    return luz_model_import(context, memory_limit, writer, error);
}

int luz_model_load(luz_model *model, const char *path, luz_texture_budget *budget,
                   luz_error *error)
{
    return luz_model_load_with(model, path, NULL, budget, error);
}

int luz_model_load_with(luz_model *model, const char *path, const luz_model_rules *rules,
                        luz_texture_budget *budget, luz_error *error)
{
    static const luz_model_rules defaults = {0};
    if (rules == NULL) rules = &defaults;
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
    luz_model_limits limits = luz_model_limits_for(size);
    if (rules->memory_mib > 0) luz_model_limits_set_memory(&limits, rules->memory_mib);
    const luz_model_source source = {.path = path};
    unsigned char *bytes;
    size_t byte_count;
    status = luz_model_run_isolated(path, &limits, import_in_child, &source, &bytes, &byte_count,
                                    error);
    if (status != 0) return status;
    status = build(model, path, bytes, byte_count, false, rules->files, budget, error);
    free(bytes);
    /* Read, but less confined than luz means it to be: said once, with
     * the model's other warnings (io/model_confine.h). */
    const luz_confinement available = luz_confinement_available();
    const char *missing = luz_confinement_missing(&available);
    if (status == 0 && missing[0] != '\0') {
        luz_error warning;
        luz_error_set(&warning, "%s: read by assimp without %s (this kernel or build has none): "
                                "its process was limited but not confined", path, missing);
        status = add_warning(model, warning.message, error);
        if (status != 0) luz_model_free(model);
    }
    return status;
}

int luz_model_load_memory(luz_model *model, const unsigned char *bytes, size_t size,
                          const char *name, luz_texture_budget *budget, luz_error *error)
{
    memset(model, 0, sizeof *model);
    if (luz_model_check_start(bytes, size, size, name, error) != 0) return LUZ_BAD_INPUT;
    const luz_model_source source = {.path = name, .memory = bytes, .memory_size = size};
    luz_model_writer writer = {.descriptor = -1};
    int status = luz_model_import(&source, 0, &writer, error);
    if (status != 0) {
        luz_model_writer_free(&writer);
        return status;
    }
    status = build(model, name, writer.bytes, writer.length, true, LUZ_MODEL_FILES_FOLDER,
                   budget, error);
    luz_model_writer_free(&writer);
    return status;
}

#endif
