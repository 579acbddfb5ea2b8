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
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <stb_image.h>

#include "io/textures.h"

luz_texture *luz_texture_load(const char *path, luz_error *error)
{
    int width, height, channels;
    if (!stbi_info(path, &width, &height, &channels)) {
        luz_error_set(error, "%s: not a readable image (%s)", path, stbi_failure_reason());
        return NULL;
    }
    if (width < 1 || height < 1 || width > LUZ_TEXTURE_MAX_SIZE ||
        height > LUZ_TEXTURE_MAX_SIZE) {
        luz_error_set(error, "%s: image is %dx%d, expected at most %dx%d", path, width, height,
                      LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
        return NULL;
    }
    unsigned char *pixels = stbi_load(path, &width, &height, &channels, 4);
    if (!pixels) {
        luz_error_set(error, "%s: corrupt or unsupported image (%s)", path,
                      stbi_failure_reason());
        return NULL;
    }
    luz_error inner;
    luz_texture *texture = luz_texture_create(width, height, pixels, &inner);
    stbi_image_free(pixels);
    if (!texture) luz_error_set(error, "%s: %s", path, inner.message);
    return texture;
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
