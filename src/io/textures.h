/*
 * io/textures.h: image files into luz_textures (texture_load.c).
 *
 * A luz_texture_set is the sorted list of image files of a directory (the
 * cube textures); cube i uses image i mod N. A model's textures, files
 * beside it or embedded in it, go through the same loader.
 *
 * luz reads PNG, JPEG, BMP and TGA files (io/image_formats.h), each named
 * for its format, at most LUZ_IMAGE_FILE_MAX_BYTES (io/input_file.h) and
 * LUZ_TEXTURE_MAX_SIZE pixels a side; and all the textures of a run
 * together take at most a budget of memory.
 */
#ifndef LUZ_IO_TEXTURES_H
#define LUZ_IO_TEXTURES_H

#include <stddef.h>
#include <stdint.h>

#include "luz/error.h"
#include "luz/texture.h"

/* The memory all the textures of a run may take together, cube textures
 * and models' alike: each texture's RGBA8 texels and its mip chain, about
 * 4/3 x 4 bytes a pixel. 1 GiB holds three textures of 8192 x 8192, or
 * 48 of 2048 x 2048. While a file is decoded, luz needs about its size and
 * twice its image's more, for a moment. */
#define LUZ_TEXTURE_BUDGET_BYTES ((uint64_t)1 << 30)

/* The memory a run's textures may still take. Zero-initialised, the limit
 * is LUZ_TEXTURE_BUDGET_BYTES; a test may set a smaller one. */
typedef struct luz_texture_budget {
    uint64_t limit;   /* 0: LUZ_TEXTURE_BUDGET_BYTES */
    uint64_t used;    /* by the textures loaded so far */
} luz_texture_budget;

/* The bytes a width x height texture takes, as luz_texture_create
 * allocates them: the luz_texture, its texels and its mip chain. */
uint64_t luz_texture_bytes(int width, int height);

/* Whether a width x height texture fits in what is left of *budget (NULL:
 * a budget of its own): 0, or LUZ_BAD_INPUT with a message naming name,
 * the texture's size and the budget's. Nothing is charged. */
int luz_texture_budget_check(const luz_texture_budget *budget, int width, int height,
                             const char *name, luz_error *error);

/* luz_texture_create within *budget: checks it, creates the texture from
 * width x height RGBA8 texels (copied), and charges it. Returns 0,
 * LUZ_BAD_INPUT (over the budget, or a size luz_texture_create refuses),
 * or LUZ_MACHINE_FAILED when memory runs out. */
int luz_texture_create_in_budget(int width, int height, const uint8_t *rgba, const char *name,
                                 luz_texture_budget *budget, luz_texture **texture,
                                 luz_error *error);

/* Loads an image file (.png .jpg .jpeg .bmp .tga, case-insensitive: the
 * name chooses the format, the file's signature must agree) into
 * *texture, charging it to *budget (NULL: a budget for this texture
 * alone). The file is opened as io/input_file.h says: never blocking, a
 * regular file only. Returns 0; LUZ_BAD_INPUT (-1) for a file at fault;
 * LUZ_MACHINE_FAILED when memory runs out; with one line naming path. */
int luz_texture_load(const char *path, luz_texture_budget *budget, luz_texture **texture,
                     luz_error *error);

/* luz_texture_load of the file name names within directory, which it may
 * not leave (io/input_file.h's luz_input_open_beneath: an absolute name,
 * a `..` above it or a symbolic link out of it gives
 * LUZ_OUTSIDE_DIRECTORY); messages name DIRECTORY/NAME. For a model's
 * textures, kept in its folder. */
int luz_texture_load_beneath(const char *directory, const char *name,
                             luz_texture_budget *budget, luz_texture **texture,
                             luz_error *error);

/* The same for an encoded image in memory (a model's embedded texture);
 * name is what errors call it. The format is format_hint's ("png", "jpg",
 * ...: assimp's achFormatHint) if it is not NULL or empty, else name's
 * extension if it has one, else that of the bytes' signature (TGA, which
 * has none, needs a hint or a name). */
int luz_texture_load_memory(const unsigned char *bytes, size_t size, const char *name,
                            const char *format_hint, luz_texture_budget *budget,
                            luz_texture **texture, luz_error *error);

/* ---- a directory of textures ------------------------------------------ */

typedef struct luz_texture_set {
    luz_texture **textures;
    char **names;            /* file names, sorted by their bytes */
    int count;
} luz_texture_set;

/* Loads every image (.png .jpg .jpeg .bmp .tga, case-insensitive; names
 * starting with a dot skipped) of a directory, sorted by name, charging
 * them to *budget (NULL: a budget for this set alone). A directory with
 * none gives an error; use an empty set for SCENE.md's `none`. Returns 0,
 * LUZ_BAD_INPUT or LUZ_MACHINE_FAILED, with a message. */
int luz_texture_set_load(luz_texture_set *set, const char *directory,
                         luz_texture_budget *budget, luz_error *error);
/* The index of a file name in the set, or -1. */
int luz_texture_set_find(const luz_texture_set *set, const char *name);
void luz_texture_set_free(luz_texture_set *set);

#endif
