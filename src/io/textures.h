/*
 * io/textures.h: image files into luz_textures, through stb_image.
 *
 * A luz_texture_set is the sorted list of image files of a directory (the
 * cube textures); cube i uses image i mod N.
 */
#ifndef LUZ_IO_TEXTURES_H
#define LUZ_IO_TEXTURES_H

#include <stddef.h>

#include "luz/error.h"
#include "luz/texture.h"

/* Loads a .png/.jpg/.bmp/.tga file through stb_image. */
luz_texture *luz_texture_load(const char *path, luz_error *error);
/* The same for an encoded image in memory (a model's embedded texture);
 * name is what an error calls it. */
luz_texture *luz_texture_load_memory(const unsigned char *bytes, size_t size, const char *name,
                                     luz_error *error);

/* ---- a directory of textures ------------------------------------------ */

typedef struct luz_texture_set {
    luz_texture **textures;
    char **names;            /* file names, sorted by their bytes */
    int count;
} luz_texture_set;

/* Loads every image (.png .jpg .jpeg .bmp .tga, case-insensitive; names
 * starting with a dot skipped) of a directory, sorted by name. A directory
 * with none gives an error; use an empty set for SCENE.md's `none`. */
int luz_texture_set_load(luz_texture_set *set, const char *directory, luz_error *error);
/* The index of a file name in the set, or -1. */
int luz_texture_set_find(const luz_texture_set *set, const char *name);
void luz_texture_set_free(luz_texture_set *set);

#endif
