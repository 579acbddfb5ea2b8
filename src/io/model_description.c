/*
 * model_description.c: a model's description (io/model_description.h)
 * written by the process that runs assimp, read by luz's own.
 *
 * In:  (writing) the parts and embedded textures assimp found, or a
 *      refusal; (reading) the bytes that arrived, from a process that may
 *      have been corrupted by the file it read.
 * Out: (writing) records in a buffer or down a pipe; (reading) the parts
 *      and textures, pointing into the bytes, or one line saying what is
 *      wrong with them.
 *
 * The reader trusts no count: each record's length must fit in the bytes
 * left, each array's length in its record, each name must end with its
 * NUL where its length says, and the only allocations (the arrays of
 * parts and textures) are bounded by the number of records, which the
 * bytes themselves bound.
 */
#include "io/model_description.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/input_file.h"

enum { TAG_TEXTURE = 1, TAG_PART = 2, TAG_END = 3, TAG_REFUSED = 4, TAG_FILE = 5 };

/* What a record starts with; its payload follows, `length` bytes. */
typedef struct record_header {
    uint32_t tag, zero;
    uint64_t length;
} record_header;

typedef struct file_fixed {
    uint64_t device, inode;
    uint32_t path_length, zero;
} file_fixed;

typedef struct texture_fixed {
    uint32_t compressed, width, height, name_length;
    char hint[LUZ_DESCRIBED_HINT_SIZE];
    uint64_t size;
} texture_fixed;

typedef struct part_fixed {
    uint32_t mesh_index, vertex_count, triangle_count, flags;
    float colour[3];
    int32_t embedded;
    uint32_t name_lengths[3], zero;
} part_fixed;

enum { PART_HAS_COLOUR = 1, PART_HAS_UVS = 2 };

typedef struct refusal_fixed {
    int32_t status;
    uint32_t message_length;
} refusal_fixed;

typedef struct end_fixed {
    uint32_t part_count, texture_count;
} end_fixed;

/* A buffer gathers this much before it goes down the pipe. */
#define WRITER_CHUNK ((size_t)1 << 20)

static uint64_t padded(uint64_t length)
{
    return (length + 7) & ~(uint64_t)7;
}

/* ---- writing ------------------------------------------------------------------------------ */

int luz_model_writer_flush(luz_model_writer *writer)
{
    if (writer->status != 0 || writer->descriptor < 0) return writer->status;
    size_t done = 0;
    while (done < writer->length) {
        ssize_t wrote = write(writer->descriptor, writer->bytes + done, writer->length - done);
        if (wrote < 0 && errno == EINTR) continue;
        if (wrote <= 0) {   /* EPIPE: the reader is gone */
            writer->status = LUZ_MACHINE_FAILED;
            return writer->status;
        }
        done += (size_t)wrote;
    }
    writer->length = 0;
    return 0;
}

static void put(luz_model_writer *writer, const void *bytes, size_t length)
{
    const unsigned char *from = bytes;
    while (length > 0 && writer->status == 0) {
        if (writer->length == writer->capacity) {
            if (writer->descriptor >= 0 && writer->capacity > 0) {   /* full: down the pipe */
                luz_model_writer_flush(writer);
                continue;
            }
            size_t capacity = writer->capacity < WRITER_CHUNK ? WRITER_CHUNK : 2 * writer->capacity;
            unsigned char *grown = capacity > writer->capacity ? realloc(writer->bytes, capacity)
                                                              : NULL;
            if (grown == NULL) {
                writer->status = LUZ_MACHINE_FAILED;
                return;
            }
            writer->bytes = grown;
            writer->capacity = capacity;
        }
        size_t step = writer->capacity - writer->length;
        if (step > length) step = length;
        memcpy(writer->bytes + writer->length, from, step);
        writer->length += step;
        from += step;
        length -= step;
    }
}

static void put_padding(luz_model_writer *writer, uint64_t length)
{
    static const unsigned char zeros[8] = {0};
    put(writer, zeros, (size_t)(padded(length) - length));
}

static void put_header(luz_model_writer *writer, uint32_t tag, uint64_t length)
{
    const record_header header = {.tag = tag, .length = length};
    put(writer, &header, sizeof header);
}

/* Names, each with its NUL, padded together to 8 bytes. */
static uint64_t names_length(const char *const *names, int count)
{
    uint64_t length = 0;
    for (int i = 0; i < count; i++) length += strlen(names[i]) + 1;
    return padded(length);
}

static void put_names(luz_model_writer *writer, const char *const *names, int count)
{
    uint64_t length = 0;
    for (int i = 0; i < count; i++) {
        put(writer, names[i], strlen(names[i]) + 1);
        length += strlen(names[i]) + 1;
    }
    put_padding(writer, length);
}

void luz_model_write_file(luz_model_writer *writer, const luz_described_file *file)
{
    const file_fixed fixed = {.device = file->device, .inode = file->inode,
                              .path_length = (uint32_t)strlen(file->path)};
    const char *names[] = {file->path};
    put_header(writer, TAG_FILE, sizeof fixed + names_length(names, 1));
    put(writer, &fixed, sizeof fixed);
    put_names(writer, names, 1);
}

void luz_model_write_texture(luz_model_writer *writer, const luz_described_texture *texture)
{
    texture_fixed fixed = {.compressed = texture->compressed,
                           .width = texture->width,
                           .height = texture->height,
                           .name_length = (uint32_t)strlen(texture->name),
                           .size = texture->bytes != NULL ? texture->size : 0};
    memcpy(fixed.hint, texture->hint, sizeof fixed.hint);
    fixed.hint[sizeof fixed.hint - 1] = '\0';
    const char *names[] = {texture->name};
    put_header(writer, TAG_TEXTURE, sizeof fixed + names_length(names, 1) + padded(fixed.size));
    put(writer, &fixed, sizeof fixed);
    put_names(writer, names, 1);
    if (fixed.size > 0) put(writer, texture->bytes, (size_t)fixed.size);
    put_padding(writer, fixed.size);
}

static uint64_t vertex_bytes(uint64_t count)
{
    return count * sizeof(luz_vertex);
}

static uint64_t index_bytes(uint64_t triangles)
{
    return triangles * 3 * sizeof(uint32_t);
}

void luz_model_write_part_start(luz_model_writer *writer, const luz_described_part *part)
{
    part_fixed fixed = {.mesh_index = part->mesh_index,
                        .vertex_count = part->vertex_count,
                        .triangle_count = part->triangle_count,
                        .flags = (part->has_colour ? PART_HAS_COLOUR : 0u) |
                                 (part->has_uvs ? PART_HAS_UVS : 0u),
                        .colour = {part->colour.x, part->colour.y, part->colour.z},
                        .embedded = part->embedded,
                        .name_lengths = {(uint32_t)strlen(part->mesh_name),
                                         (uint32_t)strlen(part->material_name),
                                         (uint32_t)strlen(part->texture_name)}};
    const char *names[] = {part->mesh_name, part->material_name, part->texture_name};
    put_header(writer, TAG_PART,
               sizeof fixed + names_length(names, 3) + padded(vertex_bytes(part->vertex_count)) +
                   padded(index_bytes(part->triangle_count)));
    put(writer, &fixed, sizeof fixed);
    put_names(writer, names, 3);
}

void luz_model_write_vertices(luz_model_writer *writer, const luz_vertex *vertices, size_t count)
{
    put(writer, vertices, (size_t)vertex_bytes(count));
}

void luz_model_write_indices(luz_model_writer *writer, const uint32_t *indices, size_t count)
{
    put(writer, indices, count * sizeof *indices);
}

void luz_model_write_part_finish(luz_model_writer *writer, const luz_described_part *part)
{
    /* the vertices' padding, then the indices' (written in between) are
     * laid out as the reader expects only if the vertices pad to 8 on
     * their own: a luz_vertex is 32 bytes */
    _Static_assert(sizeof(luz_vertex) % 8 == 0, "vertices pad themselves");
    put_padding(writer, index_bytes(part->triangle_count));
}

void luz_model_write_end(luz_model_writer *writer, int part_count, int texture_count)
{
    const end_fixed fixed = {(uint32_t)part_count, (uint32_t)texture_count};
    put_header(writer, TAG_END, sizeof fixed);
    put(writer, &fixed, sizeof fixed);
}

void luz_model_write_refusal(luz_model_writer *writer, int status, const char *message)
{
    const refusal_fixed fixed = {status, (uint32_t)strlen(message)};
    const char *names[] = {message};
    put_header(writer, TAG_REFUSED, sizeof fixed + names_length(names, 1));
    put(writer, &fixed, sizeof fixed);
    put_names(writer, names, 1);
}

void luz_model_writer_free(luz_model_writer *writer)
{
    free(writer->bytes);
    writer->bytes = NULL;
    writer->length = writer->capacity = 0;
}

/* ---- reading ------------------------------------------------------------------------------ */

/* The bytes of one record's payload, taken from the front. */
typedef struct cursor {
    const unsigned char *at;
    uint64_t left;
} cursor;

static const void *take(cursor *from, uint64_t length)
{
    if (length > from->left) return NULL;
    const void *start = from->at;
    from->at += length;
    from->left -= length;
    return start;
}

/* count names of the given lengths, each with its NUL, padded together. */
static bool take_names(cursor *from, const uint32_t *lengths, int count, const char **names)
{
    uint64_t total = 0;
    for (int i = 0; i < count; i++) {
        if (lengths[i] > LUZ_DESCRIBED_NAME_MAX) return false;
        total += (uint64_t)lengths[i] + 1;
    }
    const char *text = take(from, padded(total));
    if (text == NULL) return false;
    for (int i = 0; i < count; i++) {
        if (memchr(text, '\0', lengths[i]) != NULL || text[lengths[i]] != '\0') return false;
        names[i] = text;
        text += lengths[i] + 1;
    }
    return true;
}

static bool read_file(cursor payload, luz_described_file *file)
{
    file_fixed fixed;
    const void *start = take(&payload, sizeof fixed);
    if (start == NULL) return false;
    memcpy(&fixed, start, sizeof fixed);
    if (fixed.zero != 0 || fixed.path_length == 0) return false;
    *file = (luz_described_file){.device = fixed.device, .inode = fixed.inode};
    return take_names(&payload, &fixed.path_length, 1, &file->path) && payload.left == 0;
}

static bool read_texture(cursor payload, luz_described_texture *texture)
{
    texture_fixed fixed;
    const void *start = take(&payload, sizeof fixed);
    if (start == NULL) return false;
    memcpy(&fixed, start, sizeof fixed);
    if (fixed.compressed > 1 || memchr(fixed.hint, '\0', sizeof fixed.hint) == NULL) return false;
    *texture = (luz_described_texture){.compressed = fixed.compressed,
                                       .width = fixed.width,
                                       .height = fixed.height,
                                       .size = fixed.size};
    memcpy(texture->hint, fixed.hint, sizeof fixed.hint);
    if (!take_names(&payload, &fixed.name_length, 1, &texture->name)) return false;
    if (fixed.size > payload.left) return false;
    texture->bytes = fixed.size > 0 ? take(&payload, fixed.size) : NULL;
    return padded(fixed.size) == payload.left + fixed.size;
}

static bool read_part(cursor payload, int texture_count, luz_described_part *part)
{
    part_fixed fixed;
    const void *start = take(&payload, sizeof fixed);
    if (start == NULL) return false;
    memcpy(&fixed, start, sizeof fixed);
    if ((fixed.flags & ~(uint32_t)(PART_HAS_COLOUR | PART_HAS_UVS)) != 0 ||
        fixed.embedded < -1 || fixed.embedded >= texture_count)
        return false;
    *part = (luz_described_part){.mesh_index = fixed.mesh_index,
                                 .vertex_count = fixed.vertex_count,
                                 .triangle_count = fixed.triangle_count,
                                 .has_colour = fixed.flags & PART_HAS_COLOUR,
                                 .has_uvs = fixed.flags & PART_HAS_UVS,
                                 .colour = {fixed.colour[0], fixed.colour[1], fixed.colour[2]},
                                 .embedded = fixed.embedded};
    const char *names[3];
    if (!take_names(&payload, fixed.name_lengths, 3, names)) return false;
    part->mesh_name = names[0];
    part->material_name = names[1];
    part->texture_name = names[2];
    /* the counts are at most 2^32 - 1: their byte counts fit in 64 bits */
    part->vertices = take(&payload, vertex_bytes(fixed.vertex_count));
    part->indices = take(&payload, padded(index_bytes(fixed.triangle_count)));
    return part->vertices != NULL && part->indices != NULL && payload.left == 0;
}

static int unreadable(const char *path, const char *what, luz_error *error)
{
    luz_error_set(error, "%s: assimp's process sent a description luz cannot read (%s)", path,
                  what);
    return LUZ_BAD_INPUT;
}

/* The next record: its tag and payload; false at the end of the bytes or
 * for a record longer than what is left. */
static bool next_record(cursor *from, uint32_t *tag, cursor *payload)
{
    record_header header;
    const void *start = take(from, sizeof header);
    if (start == NULL) return false;
    memcpy(&header, start, sizeof header);
    if (header.zero != 0 || header.length % 8 != 0 || header.length > from->left) return false;
    *tag = header.tag;
    *payload = (cursor){from->at, header.length};
    take(from, header.length);
    return true;
}

int luz_model_description_read(const unsigned char *bytes, size_t size, const char *path,
                               luz_model_description *description, luz_error *error)
{
    memset(description, 0, sizeof *description);
    /* First the records' kinds and count, up to END or REFUSED: each
     * record is at least 16 bytes, so the counts are bounded by size. */
    cursor from = {bytes, size};
    uint32_t tag = 0;
    cursor payload;
    uint64_t parts = 0, textures = 0, files = 0;
    bool ended = false;
    while (!ended && next_record(&from, &tag, &payload)) {
        if (tag == TAG_FILE && parts == 0 && textures == 0) files++;   /* files first */
        else if (tag == TAG_TEXTURE && parts == 0) textures++;   /* then textures */
        else if (tag == TAG_PART) parts++;
        else if (tag == TAG_END || tag == TAG_REFUSED) ended = true;
        else return unreadable(path, "a record of an unknown kind, or out of order", error);
    }
    if (!ended) return unreadable(path, "it ends before its last record", error);
    if (from.left != 0) return unreadable(path, "bytes after its last record", error);
    if (tag == TAG_REFUSED) {
        refusal_fixed fixed;
        const void *start = take(&payload, sizeof fixed);
        const char *message;
        if (start != NULL) memcpy(&fixed, start, sizeof fixed);
        if (start == NULL || fixed.status == 0 ||
            (fixed.status != LUZ_BAD_INPUT && fixed.status != LUZ_MACHINE_FAILED) ||
            fixed.message_length >= sizeof description->refusal_message ||
            !take_names(&payload, &fixed.message_length, 1, &message) || payload.left != 0)
            return unreadable(path, "a refusal that is not one line", error);
        description->refusal = fixed.status;
        memcpy(description->refusal_message, message, fixed.message_length + 1);
        for (char *c = description->refusal_message; *c; c++)
            if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
        return 0;
    }
    end_fixed end;
    if (payload.left != sizeof end) return unreadable(path, "an END record of the wrong size", error);
    memcpy(&end, payload.at, sizeof end);
    if (end.part_count != parts || end.texture_count != textures || parts >= INT32_MAX ||
        textures >= INT32_MAX)
        return unreadable(path, "its END record counts other records than it has", error);

    description->files = calloc((size_t)files + 1, sizeof *description->files);
    description->textures = calloc((size_t)textures + 1, sizeof *description->textures);
    description->parts = calloc((size_t)parts + 1, sizeof *description->parts);
    if (description->files == NULL || description->textures == NULL ||
        description->parts == NULL) {
        luz_model_description_free(description);
        luz_error_set(error, "%s: out of memory for its %llu meshes", path,
                      (unsigned long long)parts);
        return LUZ_MACHINE_FAILED;
    }
    from = (cursor){bytes, size};
    while (next_record(&from, &tag, &payload) && tag != TAG_END) {
        if (tag == TAG_FILE) {
            if (!read_file(payload, &description->files[description->file_count++])) {
                luz_model_description_free(description);
                return unreadable(path, "a file's path", error);
            }
            continue;
        }
        bool sound = tag == TAG_TEXTURE
                         ? read_texture(payload,
                                        &description->textures[description->texture_count++])
                         : read_part(payload, (int)textures,
                                     &description->parts[description->part_count++]);
        if (!sound) {
            luz_model_description_free(description);
            return unreadable(path, tag == TAG_TEXTURE ? "an embedded texture's lengths"
                                                       : "a mesh's counts or names",
                              error);
        }
    }
    return 0;
}

void luz_model_description_free(luz_model_description *description)
{
    free(description->files);
    free(description->textures);
    free(description->parts);
    memset(description, 0, sizeof *description);
}
