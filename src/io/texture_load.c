/*
 * texture_load.c: image files into luz_textures, within a budget.
 *
 * In:  an image file's path (or an encoded image in memory, a model's
 *      embedded texture) and the run's texture budget.
 * Out: a luz_texture with its mip chain, or one line saying why not.
 *
 * A file goes through three gates before a pixel is decoded: it is opened
 * as every input is (io/input_file.h: never blocking, a regular file, at
 * most LUZ_IMAGE_FILE_MAX_BYTES); its name's format and its bytes must
 * agree and its headers and structure must be sound (image_formats.c),
 * which gives its width and height; and the texture those imply must fit
 * in what is left of the budget. Only then is it decoded
 * (image_decode.c). So a tiny file that claims to be huge costs nothing,
 * and six files that are each allowed cannot add up to gigabytes.
 *
 * A texture set is a directory's image files sorted by the bytes of their
 * names (strcmp, not the locale), so that "cube i uses image i mod N"
 * means the same on every machine.
 */
#include <dirent.h>
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "io/image_decode.h"
#include "io/image_formats.h"
#include "io/input_file.h"
#include "io/textures.h"

uint64_t luz_texture_bytes(int width, int height)
{
    /* what luz_texture_create allocates: the texture itself, then its
     * chain, each side halved down to 1 until 1x1, at most
     * LUZ_TEXTURE_MAX_LEVELS levels */
    uint64_t total = sizeof(luz_texture);
    uint64_t w = width > 0 ? (uint64_t)width : 0, h = height > 0 ? (uint64_t)height : 0;
    for (int level = 0; level < LUZ_TEXTURE_MAX_LEVELS; level++) {
        total += w * h * 4;
        if (w <= 1 && h <= 1) break;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    return total;
}

static double mebibytes(uint64_t bytes)
{
    return (double)bytes / (1024.0 * 1024.0);
}

int luz_texture_budget_check(const luz_texture_budget *budget, int width, int height,
                             const char *name, luz_error *error)
{
    static const luz_texture_budget unused = {0};
    if (budget == NULL) budget = &unused;
    const uint64_t limit = budget->limit ? budget->limit : LUZ_TEXTURE_BUDGET_BYTES;
    const uint64_t cost = luz_texture_bytes(width, height);
    if (budget->used > limit || cost > limit - budget->used)
        return luz_error_set(error, "%s: a %dx%d texture takes %.1f MiB, and the textures "
                                    "before it %.1f MiB: over luz's budget of %.0f MiB for all "
                                    "textures",
                             name, width, height, mebibytes(cost), mebibytes(budget->used),
                             mebibytes(limit));
    return 0;
}

int luz_texture_create_in_budget(int width, int height, const uint8_t *rgba, const char *name,
                                 luz_texture_budget *budget, luz_texture **texture,
                                 luz_error *error)
{
    *texture = NULL;
    if (luz_texture_budget_check(budget, width, height, name, error) != 0) return LUZ_BAD_INPUT;
    if (width < 1 || height < 1 || width > LUZ_TEXTURE_MAX_SIZE || height > LUZ_TEXTURE_MAX_SIZE)
        return luz_error_set(error, "%s: image is %dx%d, expected 1x1 to %dx%d", name, width,
                             height, LUZ_TEXTURE_MAX_SIZE, LUZ_TEXTURE_MAX_SIZE);
    luz_error inner;
    *texture = luz_texture_create(width, height, rgba, &inner);
    if (*texture == NULL) {
        /* the size is valid and the texels are there: only memory is
         * missing */
        luz_error_set(error, "%s: %s", name, inner.message);
        return LUZ_MACHINE_FAILED;
    }
    if (budget != NULL) budget->used += luz_texture_bytes(width, height);
    return 0;
}

/* The checks, the budget, the pixels: what a file and an embedded image
 * share. The budget is checked from the header's size, before anything is
 * decoded. */
static int load_encoded(const unsigned char *bytes, size_t size, luz_image_format format,
                        const char *name, luz_texture_budget *budget, luz_texture **texture,
                        luz_error *error)
{
    *texture = NULL;
    luz_image_header header;
    if (luz_image_check(bytes, size, format, name, &header, error) != 0) return LUZ_BAD_INPUT;
    if (luz_texture_budget_check(budget, header.width, header.height, name, error) != 0)
        return LUZ_BAD_INPUT;
    uint8_t *rgba;
    int status = luz_image_decode(bytes, size, &header, name, &rgba, error);
    if (status != 0) return status;
    status = luz_texture_create_in_budget(header.width, header.height, rgba, name, budget,
                                          texture, error);
    free(rgba);
    return status;
}

int luz_texture_load(const char *path, luz_texture_budget *budget, luz_texture **texture,
                     luz_error *error)
{
    *texture = NULL;
    const luz_image_format format = luz_image_format_of_name(path);
    if (format == LUZ_IMAGE_UNKNOWN)
        return luz_error_set(error, "%s: not an image file luz reads (expected a name ending "
                                    "in .png, .jpg, .jpeg, .bmp or .tga)", path);
    unsigned char *bytes;
    size_t size;
    int status = luz_input_read(path, "an image file", LUZ_IMAGE_FILE_MAX_BYTES, &bytes, &size,
                                error);
    if (status != 0) return status == LUZ_MACHINE_FAILED ? status : LUZ_BAD_INPUT;
    status = load_encoded(bytes, size, format, path, budget, texture, error);
    free(bytes);
    return status;
}

int luz_texture_load_beneath(const char *directory, const char *name,
                             luz_texture_budget *budget, luz_texture **texture,
                             luz_error *error)
{
    *texture = NULL;
    char path[8192];
    snprintf(path, sizeof path, "%s/%s", directory, name);
    const luz_image_format format = luz_image_format_of_name(name);
    if (format == LUZ_IMAGE_UNKNOWN)
        return luz_error_set(error, "%s: not an image file luz reads (expected a name ending "
                                    "in .png, .jpg, .jpeg, .bmp or .tga)", path);
    int fd;
    uint64_t expected;
    int status = luz_input_open_beneath(directory, name, "an image file",
                                        LUZ_IMAGE_FILE_MAX_BYTES, &fd, &expected, error);
    if (status != 0) return status == LUZ_OUTSIDE_DIRECTORY ? status : LUZ_BAD_INPUT;
    unsigned char *bytes;
    size_t size;
    status = luz_input_read_descriptor(fd, expected, path, "an image file",
                                       LUZ_IMAGE_FILE_MAX_BYTES, &bytes, &size, error);
    if (status != 0) return status == LUZ_MACHINE_FAILED ? status : LUZ_BAD_INPUT;
    status = load_encoded(bytes, size, format, path, budget, texture, error);
    free(bytes);
    return status;
}

int luz_texture_load_memory(const unsigned char *bytes, size_t size, const char *name,
                            const char *format_hint, luz_texture_budget *budget,
                            luz_texture **texture, luz_error *error)
{
    *texture = NULL;
    if (bytes == NULL || size == 0)
        return luz_error_set(error, "%s: an empty image (0 bytes)", name);
    if (size > LUZ_IMAGE_FILE_MAX_BYTES)
        return luz_error_set(error, "%s: %zu bytes, expected an image of at most %llu MiB", name,
                             size, (unsigned long long)(LUZ_IMAGE_FILE_MAX_BYTES >> 20));
    luz_image_format format;
    if (format_hint != NULL && format_hint[0] != '\0') {
        format = luz_image_format_of_hint(format_hint);
        if (format == LUZ_IMAGE_UNKNOWN)
            return luz_error_set(error, "%s: an image of format '%.16s', expected PNG, JPEG, BMP "
                                        "or TGA", name, format_hint);
    } else {
        format = luz_image_format_of_name(name);
        if (format == LUZ_IMAGE_UNKNOWN) format = luz_image_format_of_signature(bytes, size);
        if (format == LUZ_IMAGE_UNKNOWN)
            return luz_error_set(error, "%s: not an image luz reads (no PNG, JPEG or BMP "
                                        "signature, and no name or format hint to say TGA)",
                                 name);
    }
    return load_encoded(bytes, size, format, name, budget, texture, error);
}

static bool is_image_name(const char *name)
{
    return name[0] != '.' && luz_image_format_of_name(name) != LUZ_IMAGE_UNKNOWN;
}

static int out_of_memory(const char *directory, luz_error *error)
{
    luz_error_set(error, "%s: out of memory listing the textures", directory);
    return LUZ_MACHINE_FAILED;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int luz_texture_set_load(luz_texture_set *set, const char *directory,
                         luz_texture_budget *budget, luz_error *error)
{
    luz_texture_budget own = {0};
    if (budget == NULL) budget = &own;
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
                return out_of_memory(directory, error);
            }
            set->names = names;
        }
        set->names[set->count] = strdup(entry->d_name);
        if (!set->names[set->count]) {
            closedir(dir);
            luz_texture_set_free(set);
            return out_of_memory(directory, error);
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
        return out_of_memory(directory, error);
    }
    for (int i = 0; i < set->count; i++) {
        size_t length = strlen(directory) + strlen(set->names[i]) + 2;
        char *path = malloc(length);
        if (!path) {
            luz_texture_set_free(set);
            return out_of_memory(directory, error);
        }
        snprintf(path, length, "%s/%s", directory, set->names[i]);
        int status = luz_texture_load(path, budget, &set->textures[i], error);
        free(path);
        if (status != 0) {
            luz_texture_set_free(set);
            return status;
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
