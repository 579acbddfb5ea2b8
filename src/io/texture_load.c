/*
 * texture_load.c: image files into luz_textures, through stb_image.
 *
 * A texture set is a directory's image files sorted by the bytes of their
 * names (strcmp, not the locale), so that "cube i uses image i mod N" means
 * the same on every machine. Files are checked before they are decoded:
 * stbi_info reads only the header, so a file that claims to be 100000 x
 * 100000 pixels is refused without allocating anything.
 */
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <stb_image.h>

#include "io/textures.h"

/* The checks and the decoding both paths share: the size from the header
 * first, so that an image claiming to be huge is refused before anything
 * is allocated; then the pixels, as RGBA8. name is what errors call it. */
static luz_texture *decode(const char *name, int (*info)(const void *, int *, int *, int *),
                           unsigned char *(*load)(const void *, int *, int *, int *, int),
                           const void *source, luz_error *error)
{
    int width, height, channels;
    if (!info(source, &width, &height, &channels)) {
        luz_error_set(error, "%s: not a readable image (%s)", name, stbi_failure_reason());
        return NULL;
    }
    if (width < 1 || height < 1 || width > LUZ_TEXTURE_MAX_SIZE ||
        height > LUZ_TEXTURE_MAX_SIZE) {
        luz_error_set(error, "%s: image is %dx%d, expected at most %dx%d", name, width, height,
                      LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
        return NULL;
    }
    unsigned char *pixels = load(source, &width, &height, &channels, 4);
    if (!pixels) {
        luz_error_set(error, "%s: corrupt or unsupported image (%s)", name,
                      stbi_failure_reason());
        return NULL;
    }
    luz_error inner;
    luz_texture *texture = luz_texture_create(width, height, pixels, &inner);
    stbi_image_free(pixels);
    if (!texture) luz_error_set(error, "%s: %s", name, inner.message);
    return texture;
}

static int file_info(const void *path, int *width, int *height, int *channels)
{
    return stbi_info(path, width, height, channels);
}

static unsigned char *file_load(const void *path, int *width, int *height, int *channels,
                                int wanted)
{
    return stbi_load(path, width, height, channels, wanted);
}

luz_texture *luz_texture_load(const char *path, luz_error *error)
{
    return decode(path, file_info, file_load, path, error);
}

/* An encoded image in memory, for stb's _from_memory functions. */
typedef struct memory_image {
    const unsigned char *bytes;
    int size;
} memory_image;

static int memory_info(const void *source, int *width, int *height, int *channels)
{
    const memory_image *image = source;
    return stbi_info_from_memory(image->bytes, image->size, width, height, channels);
}

static unsigned char *memory_load(const void *source, int *width, int *height, int *channels,
                                  int wanted)
{
    const memory_image *image = source;
    return stbi_load_from_memory(image->bytes, image->size, width, height, channels, wanted);
}

luz_texture *luz_texture_load_memory(const unsigned char *bytes, size_t size, const char *name,
                                     luz_error *error)
{
    if (bytes == NULL || size == 0 || size > INT_MAX) {
        luz_error_set(error, "%s: %zu bytes is not an image", name, size);
        return NULL;
    }
    const memory_image image = {bytes, (int)size};
    return decode(name, memory_info, memory_load, &image, error);
}

static bool is_image_name(const char *name)
{
    static const char *const extensions[] = {".png", ".jpg", ".jpeg", ".bmp", ".tga"};
    if (name[0] == '.') return false;
    const char *dot = strrchr(name, '.');
    if (!dot) return false;
    for (size_t i = 0; i < sizeof extensions / sizeof extensions[0]; i++)
        if (strcasecmp(dot, extensions[i]) == 0) return true;
    return false;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int luz_texture_set_load(luz_texture_set *set, const char *directory, luz_error *error)
{
    memset(set, 0, sizeof *set);
    DIR *dir = opendir(directory);
    if (!dir)
        return luz_error_set(error, "%s: cannot open textures directory (%s)", directory,
                             strerror(errno));

    int capacity = 0;
    struct dirent *entry;
    while ((entry = readdir(dir)) != NULL) {
        if (!is_image_name(entry->d_name)) continue;
        if (set->count == capacity) {
            capacity = capacity ? capacity * 2 : 16;
            char **names = realloc(set->names, (size_t)capacity * sizeof *names);
            if (!names) {
                closedir(dir);
                luz_texture_set_free(set);
                return luz_error_set(error, "%s: out of memory", directory);
            }
            set->names = names;
        }
        set->names[set->count] = strdup(entry->d_name);
        if (!set->names[set->count]) {
            closedir(dir);
            luz_texture_set_free(set);
            return luz_error_set(error, "%s: out of memory", directory);
        }
        set->count++;
    }
    closedir(dir);
    if (set->count == 0) {
        luz_texture_set_free(set);
        return luz_error_set(error,
                             "%s: no images (.png .jpg .jpeg .bmp .tga) in textures directory",
                             directory);
    }
    qsort(set->names, (size_t)set->count, sizeof *set->names, compare_names);

    set->textures = calloc((size_t)set->count, sizeof *set->textures);
    if (!set->textures) {
        luz_texture_set_free(set);
        return luz_error_set(error, "%s: out of memory", directory);
    }
    for (int i = 0; i < set->count; i++) {
        size_t length = strlen(directory) + strlen(set->names[i]) + 2;
        char *path = malloc(length);
        if (!path) {
            luz_texture_set_free(set);
            return luz_error_set(error, "%s: out of memory", directory);
        }
        snprintf(path, length, "%s/%s", directory, set->names[i]);
        set->textures[i] = luz_texture_load(path, error);
        free(path);
        if (!set->textures[i]) {
            luz_texture_set_free(set);
            return -1;
        }
    }
    return 0;
}

int luz_texture_set_find(const luz_texture_set *set, const char *name)
{
    for (int i = 0; i < set->count; i++)
        if (strcmp(set->names[i], name) == 0) return i;
    return -1;
}

void luz_texture_set_free(luz_texture_set *set)
{
    for (int i = 0; i < set->count; i++) {
        if (set->textures) luz_texture_destroy(set->textures[i]);
        if (set->names) free(set->names[i]);
    }
    free(set->textures);
    free(set->names);
    memset(set, 0, sizeof *set);
}
