/*
 * option_textures.c: the textures the options name, loaded, and the custom
 * cubes' texture names resolved against them.
 *
 * Both programs start this way once the options are read. A scene file's
 * `texture NAME` is kept as text while the file is read (scene_file.c),
 * since the textures directory is only known once every option is; here
 * the names become indices of the loaded set, and an unknown one is
 * reported at its FILE:LINE.
 *
 * Uses options.c (the default textures directory) and io; no other file of
 * the app calls it.
 */
#include "app/options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/option_text.h"
#include "io/input_file.h"

int luz_options_resolve_textures(luz_options *options, const luz_texture_set *textures,
                                 luz_error *error)
{
    for (int i = 0; i < options->scene.object_count; i++) {
        const luz_object_source *source = &options->object_sources[i];
        if (source->texture_name == NULL) {
            options->objects[i].texture = LUZ_TEXTURE_BY_INDEX;
            continue;
        }
        int index = textures ? luz_texture_set_find(textures, source->texture_name) : -1;
        if (index >= 0) {
            options->objects[i].texture = index;
            continue;
        }
        /* Name a few of the images that are there, which is usually enough to
         * spot the typo. */
        char available[200] = "";
        int count = textures ? textures->count : 0;
        for (int k = 0; k < count && k < 6; k++) {
            size_t used = strlen(available);
            snprintf(available + used, sizeof available - used, "%s%s", k ? ", " : "",
                     option_quote(textures->names[k]).text);
        }
        if (count > 6) {
            size_t used = strlen(available);
            snprintf(available + used, sizeof available - used, ", ...");
        }
        return luz_error_set(error,
                             "%s:%d: %s: texture '%s' is not an image of the textures "
                             "directory (expected one of: %s)",
                             options->scene_path ? options->scene_path : "scene", source->line,
                             source->model_path ? "model" : "cube",
                             option_quote(source->texture_name).text,
                             count ? available : "none, textures are off");
    }
    return 0;
}

/* Records the set's files, directory/name, among the run's inputs. */
static int add_texture_inputs(luz_options *options, const char *directory,
                              const luz_texture_set *textures, luz_error *error)
{
    for (int i = 0; i < textures->count; i++) {
        size_t length = strlen(directory) + 1 + strlen(textures->names[i]) + 1;
        char *path = malloc(length);
        if (path == NULL)
            return luz_error_set(error, "%s: out of memory", directory);
        snprintf(path, length, "%s/%s", directory, textures->names[i]);
        int status = luz_input_files_add(&options->inputs, path, "a texture", error);
        free(path);
        if (status != 0)
            return -1;
    }
    return 0;
}

/* Loads the textures the options name; see options.h. */
int luz_options_load_textures(luz_options *options, luz_texture_set *textures,
                              luz_texture_budget *budget, luz_error *error)
{
    char default_directory[4096];
    const char *directory = options->textures_directory;
    const char *source = "--textures";
    if (directory == NULL) {
        const char *environment = getenv("LUZ_TEXTURES");
        source = environment && environment[0] ? "LUZ_TEXTURES"
                                               : "default textures (see --textures)";
        directory = luz_default_textures_directory(default_directory, sizeof default_directory);
    }
    if (strcmp(directory, "none") != 0) {
        luz_error load_error = {{0}};
        int status = luz_texture_set_load(textures, directory, budget, &load_error);
        if (status != 0) {
            luz_error_set(error, "%s: %s", source, load_error.message);
            return status;
        }
        if (add_texture_inputs(options, directory, textures, error) != 0)
            return LUZ_MACHINE_FAILED;   /* out of memory is its only failure */
    }
    return luz_options_resolve_textures(options, textures, error);
}
