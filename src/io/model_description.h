/*
 * io/model_description.h: what assimp made of a model file, as plain bytes
 * with no assimp pointers in them (model_description.c).
 *
 * assimp reads a model in a process of its own (io/model_sandbox.h); what
 * it found crosses to luz's process as these bytes, which luz then turns
 * into meshes and textures (model_load.c). A process that assimp may have
 * corrupted is a stranger, so the reader checks every count and length
 * against the bytes it has before it trusts them, and allocates nothing
 * whose size the bytes choose: the arrays it returns point into the bytes.
 *
 * The bytes are a sequence of records, each a header (a tag and the
 * length of what follows, a multiple of 8) and its payload, in the byte
 * order and layout of this build (both ends are the same program):
 *   FILE     a file assimp read (the model, its .mtl, .bin, ...): its path
 *            as opened, its device and inode; these come first;
 *   TEXTURE  an embedded texture that a part uses: its name, compressed
 *            bytes (a PNG, a JPEG, ...) or raw BGRA texels;
 *   PART     a triangle mesh of the file: luz_vertex array, indices,
 *            colour, names, the texture it names;
 *   END      the description is complete;
 *   REFUSED  instead of END: assimp or luz's checks refused the file, with
 *            a status and one line.
 */
#ifndef LUZ_IO_MODEL_DESCRIPTION_H
#define LUZ_IO_MODEL_DESCRIPTION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "luz/error.h"
#include "luz/mesh.h"
#include "luz/vecmath.h"

/* The longest name a description carries (assimp's aiString holds 1024
 * bytes). */
#define LUZ_DESCRIBED_NAME_MAX 1024
/* Room for assimp's achFormatHint ("png", "jpg", ...) and its NUL. */
#define LUZ_DESCRIBED_HINT_SIZE 16

/* ---- writing ------------------------------------------------------------------------------ */

/* Where a description goes: a growing buffer (descriptor -1), or a pipe,
 * written whenever the buffer is full: a mebibyte, or the caller's own
 * buffer (bytes and capacity set, length 0; not freed here), which a
 * process out of memory can still write its refusal through. */
typedef struct luz_model_writer {
    int descriptor;           /* -1: keep the whole description in bytes */
    unsigned char *bytes;
    size_t length, capacity;
    int status;               /* 0; LUZ_MACHINE_FAILED once memory ran out
                                 or a write failed: later writes do nothing */
} luz_model_writer;

/* An embedded texture: compressed (the bytes of an image file, its
 * format in hint) or width x height raw BGRA texels (bytes NULL when
 * assimp gave none, or more than LUZ_TEXTURE_MAX_SIZE a side). */
typedef struct luz_described_texture {
    const char *name;         /* as the materials name it */
    bool compressed;
    uint32_t width, height;   /* raw only */
    char hint[LUZ_DESCRIBED_HINT_SIZE];
    const unsigned char *bytes;
    uint64_t size;
} luz_described_texture;

/* A file the import opened and read through luz's file system: an input
 * of the run, which no output may replace. */
typedef struct luz_described_file {
    const char *path;         /* as assimp asked for it */
    uint64_t device, inode;   /* fstat() of what was read */
} luz_described_file;

typedef struct luz_described_part {
    uint32_t mesh_index;      /* in the file, for messages */
    uint32_t vertex_count, triangle_count;
    const luz_vertex *vertices;
    const uint32_t *indices;  /* 3 a triangle; not yet checked against
                                 vertex_count (luz_mesh_create does) */
    bool has_colour, has_uvs;
    luz_vec3 colour;
    const char *mesh_name, *material_name, *texture_name;   /* "" for none */
    int32_t embedded;         /* the TEXTURE that texture_name is, or -1 */
} luz_described_part;

void luz_model_write_file(luz_model_writer *writer, const luz_described_file *file);
void luz_model_write_texture(luz_model_writer *writer, const luz_described_texture *texture);
/* A part, in steps, for arrays that are not in memory as such (assimp's
 * positions, normals and uvs are separate): the start (part's counts,
 * colour and names; its arrays are not read), then exactly vertex_count
 * vertices and 3 x triangle_count indices, in blocks of any size, then
 * the finish. */
void luz_model_write_part_start(luz_model_writer *writer, const luz_described_part *part);
void luz_model_write_vertices(luz_model_writer *writer, const luz_vertex *vertices, size_t count);
void luz_model_write_indices(luz_model_writer *writer, const uint32_t *indices, size_t count);
void luz_model_write_part_finish(luz_model_writer *writer, const luz_described_part *part);
void luz_model_write_end(luz_model_writer *writer, int part_count, int texture_count);
void luz_model_write_refusal(luz_model_writer *writer, int status, const char *message);
/* Writes what has gathered to the descriptor; returns writer->status. */
int luz_model_writer_flush(luz_model_writer *writer);
void luz_model_writer_free(luz_model_writer *writer);

/* ---- reading ------------------------------------------------------------------------------ */

typedef struct luz_model_description {
    luz_described_file *files;
    int file_count;
    luz_described_texture *textures;
    int texture_count;
    luz_described_part *parts;
    int part_count;
    int refusal;              /* 0, or the REFUSED record's status */
    char refusal_message[sizeof(((luz_error *)0)->message)];
} luz_model_description;

/* Reads the description in bytes (which must outlive it: its arrays and
 * names point into them). Returns 0 with *description set (refusal 0, or
 * a REFUSED record's status and line, control characters replaced);
 * LUZ_BAD_INPUT with one line naming path if the bytes are not a
 * complete, consistent description; LUZ_MACHINE_FAILED if memory ran
 * out. */
int luz_model_description_read(const unsigned char *bytes, size_t size, const char *path,
                               luz_model_description *description, luz_error *error);
void luz_model_description_free(luz_model_description *description);

#endif
