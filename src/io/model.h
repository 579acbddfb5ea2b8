/*
 * io/model.h: the user's model files, read with assimp, as libluz meshes
 * and textures (SCENE.md, "Models").
 *
 * A luz_model is what the lab needs of a file and nothing of assimp: one
 * part per triangle mesh of the file, in the file's order, each a luz_mesh
 * with the colour and texture its material gives, and the bounding box of
 * all of them (which the lab's normalisation reads). Textures are decoded
 * with the cube textures' loader, from files beside the model or from the
 * file itself (embedded), and shared between the parts that name the same
 * one.
 */
#ifndef LUZ_IO_MODEL_H
#define LUZ_IO_MODEL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "io/textures.h"
#include "luz/error.h"
#include "luz/mesh.h"
#include "luz/texture.h"
#include "luz/vecmath.h"

/* A file, as opened, and what fstat() said it was. */
typedef struct luz_input_file_id {
    char *path;
    uint64_t device, inode;
} luz_input_file_id;

typedef struct luz_model_part {
    luz_mesh *mesh;
    bool has_colour;              /* the material's diffuse colour, if it has
                                     one and is not assimp's stand-in */
    luz_vec3 colour;
    bool has_uvs;                 /* without, T = 1 */
    const luz_texture *texture;   /* the material's first diffuse texture,
                                     NULL for none (or no uvs); owned by the
                                     model */
    /* What the file calls them (for the pixel probe); owned, NULL for
     * none or an empty name. */
    char *mesh_name;              /* the mesh's */
    char *material_name;          /* its material's */
    char *texture_name;           /* the texture's, as the material names it */
} luz_model_part;

typedef struct luz_model {
    char *path;                   /* as opened */
    char *name;                   /* the file's name, for the HUD and errors */
    luz_model_part *parts;
    int part_count;
    luz_texture **textures;       /* every texture the parts use, once */
    int texture_count;
    char **texture_files;         /* the files of those read from beside the
                                     model (not embedded), as opened: inputs
                                     that no output may replace */
    int texture_file_count;
    char **warnings;              /* one line each, for the user: a texture
                                     the file names that is missing or
                                     corrupt, drawn with T = 1 (once per
                                     texture name) */
    int warning_count;
    luz_input_file_id *read_files;   /* every file assimp read for it (the
                                        model, its .mtl, .bin, ...), by path
                                        as opened and device and inode:
                                        inputs no output may replace */
    int read_file_count;
    luz_bounds bounds;            /* around every part's vertices */
    uint64_t triangle_count;
} luz_model;

/* Where the texture files a model names may be (--model-files). */
typedef enum luz_model_files {
    LUZ_MODEL_FILES_FOLDER = 0,   /* in the model file's folder (its
                                     subfolders too): a name that is
                                     absolute, or leads out through `..`
                                     or a symbolic link, is as good as
                                     missing (the default) */
    LUZ_MODEL_FILES_ANYWHERE,     /* wherever the names lead */
} luz_model_files;

/* How a model is read; zero-initialised (or NULL), the defaults. */
typedef struct luz_model_rules {
    luz_model_files files;
    uint64_t memory_mib;          /* the address space assimp's process may
                                     take, in MiB (--model-memory); 0: the
                                     limit that grows with the file */
} luz_model_rules;

/* Whether this build reads models (built with assimp: -Dmodels). */
bool luz_models_supported(void);

/* Reads the model at path into *model (zeroed first), its textures
 * charged to *budget (NULL: a budget for this model alone). The file and
 * every file it names are opened as io/input_file.h says (never blocking,
 * regular files only, at most LUZ_MODEL_FILE_MAX_BYTES each).
 * assimp reads it in a child process (fork(): call this before starting
 * threads), within limits that grow with the file's size
 * (io/model_sandbox.h: LUZ_MODEL_SECONDS of CPU time and
 * LUZ_MODEL_SECONDS_PER_MIB more a MiB; LUZ_MODEL_MEMORY_BYTES of address
 * space and LUZ_MODEL_MEMORY_PER_BYTE more a byte of the file: 10 s and
 * 1 GiB for a small file, 550 s for a 1.1 GB OBJ; or rules->memory_mib); the
 * textures are decoded here. Returns 0;
 * LUZ_BAD_INPUT (-1) with one line naming the file and what is wrong: not
 * a regular file (it, or a file it names), unreadable, a format assimp
 * does not know, no triangles, a position that is not finite, an index out
 * of range, zero size, assimp crashing or going over a limit on it; or
 * LUZ_MACHINE_FAILED when memory runs out here, or no child process could
 * be made, or the system killed it. A texture the file names that is
 * missing, corrupt or over the budget does not stop the model: its parts
 * get no texture (T = 1) and model->warnings one line naming the model
 * and the texture (SCENE.md, "Models"). */
int luz_model_load(luz_model *model, const char *path, luz_texture_budget *budget,
                   luz_error *error);
/* luz_model_load under rules (NULL: the defaults, as luz_model_load):
 * with LUZ_MODEL_FILES_FOLDER, a texture file named outside the model's
 * folder gives a warning naming it and the rule, as a missing one does;
 * a memory_mib above 0 is assimp's memory limit (--model-memory). */
int luz_model_load_with(luz_model *model, const char *path, const luz_model_rules *rules,
                        luz_texture_budget *budget, luz_error *error);

/* The same for a model file's bytes in memory, which assimp reads as the
 * file `name` (its extension chooses the importer); no other file exists
 * for it (a .mtl it names is missing, so is a texture file). assimp runs
 * in this process, without limits: for the model fuzzer
 * (tests/fuzz/fuzz_model.c), which must see it. */
int luz_model_load_memory(luz_model *model, const unsigned char *bytes, size_t size,
                          const char *name, luz_texture_budget *budget, luz_error *error);
void luz_model_free(luz_model *model);

#endif
