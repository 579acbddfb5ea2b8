/*
 * io/model_import.h: assimp's reading of a model file, in the process
 * that calls it (model_import.c).
 *
 * luz_model_load runs this in a child process with a time and memory limit
 * (io/model_sandbox.h), since no cheap check keeps every one of assimp's
 * bugs out; the fuzzer (luz_model_load_memory) runs it in its own process,
 * where the sanitizers see it.
 */
#ifndef LUZ_IO_MODEL_IMPORT_H
#define LUZ_IO_MODEL_IMPORT_H

#include <stddef.h>
#include <stdint.h>

#include "io/model_description.h"
#include "luz/error.h"

/* A model file: at path, or (memory not NULL) memory_size bytes that
 * assimp reads as the file `path`, beside which no other file exists. */
typedef struct luz_model_source {
    const char *path;
    const unsigned char *memory;
    size_t memory_size;
} luz_model_source;

/* Imports the model with assimp (SCENE.md's post-processing steps), every
 * file through io/input_file.h, checks what assimp returns (faces with
 * corners, indices in range, finite positions, at most LUZ_MESH_MAX_*
 * vertices and triangles a mesh) and writes its description: the
 * embedded textures its parts use, then its triangle meshes, then END.
 * memory_limit is the limit the caller runs under (0 for none), named in
 * the message when assimp runs out of memory. Returns 0, or LUZ_BAD_INPUT
 * or LUZ_MACHINE_FAILED with one line naming path (and without END). */
int luz_model_import(const luz_model_source *source, uint64_t memory_limit,
                     luz_model_writer *writer, luz_error *error);

#endif
