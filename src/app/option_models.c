/*
 * option_models.c: the model files the options name, read, and each model
 * object pointed at what the lab needs of its file.
 *
 * A model's path is made absolute as soon as it is given (a scene file's
 * FILE is relative to the scene file's directory, --model's to the working
 * directory), so that a saved scene re-opens the same view from anywhere.
 * Both programs then call luz_options_load_models once the options are
 * read: each file is read once, however many objects place it, and an
 * error names the file (and the scene file's line that named it).
 *
 * Uses options.c and io's model loader; scene_file.c and command_line.c
 * use its path helper.
 */
#include "app/options.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "app/bench.h"
#include "io/input_file.h"

int luz_options_model_path(const char *base_directory, const char *path, char *buffer,
                           size_t size, luz_error *error)
{
    int written;
    if (path[0] == '/') {
        written = snprintf(buffer, size, "%s", path);
    } else if (base_directory != NULL && base_directory[0] == '/') {
        const bool root = base_directory[1] == '\0';
        written = snprintf(buffer, size, "%s/%s", root ? "" : base_directory, path);
    } else {
        char cwd[4096];
        if (getcwd(cwd, sizeof cwd) == NULL)
            return luz_error_set(error, "%s: cannot tell the working directory", path);
        if (base_directory != NULL && base_directory[0] != '\0')
            written = snprintf(buffer, size, "%s/%s/%s", cwd, base_directory, path);
        else
            written = snprintf(buffer, size, "%s/%s", cwd, path);
    }
    if (written < 0 || (size_t)written >= size)
        return luz_error_set(error, "%s: path too long (at most %zu bytes)", path, size - 1);
    return 0;
}

/* ---- a note on stderr while a big file loads --------------------------------------------- */

/* Reading a file of millions of triangles takes seconds; a person at a
 * terminal is told what is going on once a second has passed (and nothing
 * is said for a quick load, or into a log). */
typedef struct slow_notice {
    pthread_mutex_t lock;
    pthread_cond_t done_changed;
    bool done, said;
    const char *path;
    double start_ms;
} slow_notice;

static void *watch_slow_load(void *context)
{
    slow_notice *notice = context;
    struct timespec deadline;
    clock_gettime(CLOCK_REALTIME, &deadline);
    deadline.tv_sec += 1;
    pthread_mutex_lock(&notice->lock);
    while (!notice->done) {
        if (pthread_cond_timedwait(&notice->done_changed, &notice->lock, &deadline) != 0) {
            if (!notice->done) {
                fprintf(stderr, "luz: reading %s ...\n", notice->path);
                notice->said = true;
            }
            break;
        }
    }
    pthread_mutex_unlock(&notice->lock);
    return NULL;
}

static int load_noting_slowness(luz_model *model, const char *path, const luz_model_rules *rules,
                                luz_texture_budget *budget, luz_error *error)
{
    if (!isatty(STDERR_FILENO)) return luz_model_load_with(model, path, rules, budget, error);
    slow_notice notice = {.path = path, .start_ms = luz_wall_ms()};
    pthread_mutex_init(&notice.lock, NULL);
    pthread_cond_init(&notice.done_changed, NULL);
    pthread_t watcher;
    bool watching = pthread_create(&watcher, NULL, watch_slow_load, &notice) == 0;
    int status = luz_model_load_with(model, path, rules, budget, error);
    pthread_mutex_lock(&notice.lock);
    notice.done = true;
    pthread_cond_signal(&notice.done_changed);
    pthread_mutex_unlock(&notice.lock);
    if (watching) pthread_join(watcher, NULL);
    if (notice.said && status == 0)
        fprintf(stderr, "luz: read %s: %llu triangle%s in %d mesh%s, %.1f s\n", model->name,
                (unsigned long long)model->triangle_count,
                model->triangle_count == 1 ? "" : "s", model->part_count,
                model->part_count == 1 ? "" : "es",
                (luz_wall_ms() - notice.start_ms) / 1000.0);
    pthread_cond_destroy(&notice.done_changed);
    pthread_mutex_destroy(&notice.lock);
    return status;
}

/* ---- the set of models ------------------------------------------------------------------ */

void luz_model_set_free(luz_model_set *set)
{
    for (int i = 0; i < set->count; i++) {
        luz_model_free(&set->models[i]);
        free((void *)set->views[i].parts);
    }
    free(set->models);
    free(set->views);
    memset(set, 0, sizeof *set);
}

/* The lab's view of a model read by io: the same meshes and textures. */
static int make_view(const luz_model *model, luz_lab_model *view, luz_error *error)
{
    luz_lab_model_part *parts = calloc((size_t)model->part_count + 1, sizeof *parts);
    if (parts == NULL) return luz_error_set(error, "%s: out of memory", model->path);
    for (int p = 0; p < model->part_count; p++) {
        const luz_model_part *part = &model->parts[p];
        parts[p] = (luz_lab_model_part){.mesh = part->mesh,
                                        .has_colour = part->has_colour,
                                        .colour = part->colour,
                                        .has_uvs = part->has_uvs,
                                        .texture = part->texture,
                                        .mesh_name = part->mesh_name,
                                        .material_name = part->material_name,
                                        .texture_name = part->texture_name};
    }
    *view = (luz_lab_model){.name = model->name, .parts = parts,
                            .part_count = model->part_count, .bounds = model->bounds};
    return 0;
}

static int find_model(const luz_model_set *set, const char *path)
{
    for (int i = 0; i < set->count; i++)
        if (strcmp(set->models[i].path, path) == 0) return i;
    return -1;
}

/* Whether every object that places the model at path names a texture of
 * its own (its `texture NAME`). */
static bool each_gives_a_texture(const luz_options *options, const char *path)
{
    for (int i = 0; i < options->scene.object_count; i++) {
        const luz_object_source *source = &options->object_sources[i];
        if (source->model_path != NULL && strcmp(source->model_path, path) == 0 &&
            source->texture_name == NULL)
            return false;
    }
    return true;
}

int luz_options_load_models(luz_options *options, luz_model_set *set,
                            luz_texture_budget *budget, luz_error *error)
{
    memset(set, 0, sizeof *set);
    const int count = options->scene.object_count;
    int distinct = 0;
    for (int i = 0; i < count; i++) distinct += options->object_sources[i].model_path != NULL;
    if (distinct == 0) return 0;
    set->models = calloc((size_t)distinct, sizeof *set->models);
    set->views = calloc((size_t)distinct, sizeof *set->views);
    if (set->models == NULL || set->views == NULL) {
        luz_model_set_free(set);
        return luz_error_set(error, "out of memory for %d models", distinct);
    }
    /* Read every file once, then point the objects at them: the arrays do
     * not move after this. */
    for (int i = 0; i < count; i++) {
        const luz_object_source *source = &options->object_sources[i];
        if (source->model_path == NULL || find_model(set, source->model_path) >= 0) continue;
        luz_error inner;
        const luz_model_rules rules = {.files = options->model_files,
                                       .memory_mib = (uint64_t)options->model_memory_mib};
        int status = load_noting_slowness(&set->models[set->count], source->model_path, &rules,
                                          budget, &inner);
        if (status != 0) {
            if (source->line > 0 && options->scene_path != NULL)
                luz_error_set(error, "%s:%d: model: %s", options->scene_path, source->line,
                              inner.message);
            else
                luz_error_set(error, "%s", inner.message);
            luz_model_set_free(set);
            return status;
        }
        if (make_view(&set->models[set->count], &set->views[set->count], error) != 0) {
            set->count++;
            luz_model_set_free(set);
            return -1;
        }
        set->count++;
        /* What does not stop the model (a texture it names that is
         * missing or corrupt) is said once, as it is read: one line each,
         * control characters shown as '?'; not when every object placing
         * it gives a texture of its own, which replaces the material's. */
        const luz_model *model = &set->models[set->count - 1];
        const int warnings = each_gives_a_texture(options, model->path) ? 0 : model->warning_count;
        for (int k = 0; k < warnings; k++) {
            char line[LUZ_ERROR_MESSAGE_SIZE + 16];
            snprintf(line, sizeof line, "warning: %s", model->warnings[k]);
            luz_error_print("luz", line);
        }
        /* The model and the texture files it read are inputs that no
         * output may replace. */
        status = luz_input_files_add(&options->inputs, model->path, "a model", error);
        for (int k = 0; k < model->texture_file_count && status == 0; k++)
            status = luz_input_files_add(&options->inputs, model->texture_files[k],
                                         "a texture of a model", error);
        /* and every file assimp read for it: the .mtl, the .bin, ... */
        for (int k = 0; k < model->read_file_count && status == 0; k++)
            status = luz_input_files_add_identified(
                &options->inputs, model->read_files[k].path, "a file of a model",
                (dev_t)model->read_files[k].device, (ino_t)model->read_files[k].inode, error);
        if (status != 0) {   /* out of memory, its only failure */
            luz_model_set_free(set);
            return LUZ_MACHINE_FAILED;
        }
    }
    for (int i = 0; i < count; i++) {
        const char *path = options->object_sources[i].model_path;
        options->objects[i].model = path ? &set->views[find_model(set, path)] : NULL;
    }
    return 0;
}
