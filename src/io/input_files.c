/*
 * input_files.c: the files a run reads (see input_files.h).
 *
 * A path is compared both ways: by its text, which holds even for a file
 * that has gone since it was read, and by device and inode, which sees
 * the same file under any other name. The list is short (the textures of
 * one directory, a scene file or two, the models), so a linear search is
 * enough even for a million frame names.
 */
#include "io/input_files.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* A new entry for path at the end of the list, not yet identified; NULL
 * if memory ran out. */
static luz_input_file *add_entry(luz_input_files *inputs, const char *path, const char *what,
                                 luz_error *error)
{
    if (inputs->count == inputs->capacity) {
        int capacity = inputs->capacity ? inputs->capacity * 2 : 16;
        luz_input_file *files = realloc(inputs->files, (size_t)capacity * sizeof *files);
        if (files == NULL) {
            luz_error_set(error, "%s: out of memory", path);
            return NULL;
        }
        inputs->files = files;
        inputs->capacity = capacity;
    }
    char *copy = strdup(path);
    if (copy == NULL) {
        luz_error_set(error, "%s: out of memory", path);
        return NULL;
    }
    luz_input_file *file = &inputs->files[inputs->count++];
    *file = (luz_input_file){.path = copy, .what = what};
    return file;
}

int luz_input_files_add(luz_input_files *inputs, const char *path, const char *what,
                        luz_error *error)
{
    luz_input_file *file = add_entry(inputs, path, what, error);
    if (file == NULL)
        return -1;
    struct stat status;
    if (stat(path, &status) == 0) {
        file->identified = true;
        file->device = status.st_dev;
        file->inode = status.st_ino;
    }
    return 0;
}

int luz_input_files_add_identified(luz_input_files *inputs, const char *path, const char *what,
                                   dev_t device, ino_t inode, luz_error *error)
{
    luz_input_file *file = add_entry(inputs, path, what, error);
    if (file == NULL)
        return -1;
    file->identified = true;
    file->device = device;
    file->inode = inode;
    return 0;
}

const luz_input_file *luz_input_files_find(const luz_input_files *inputs, const char *path)
{
    struct stat status;
    const bool exists = stat(path, &status) == 0;
    for (int i = 0; i < inputs->count; i++) {
        const luz_input_file *file = &inputs->files[i];
        if (strcmp(file->path, path) == 0)
            return file;
        if (exists && file->identified && file->device == status.st_dev &&
            file->inode == status.st_ino)
            return file;
    }
    return NULL;
}

const luz_input_file *luz_input_files_find_descriptor(const luz_input_files *inputs,
                                                      int descriptor)
{
    struct stat status;
    if (fstat(descriptor, &status) != 0) return NULL;
    for (int i = 0; i < inputs->count; i++) {
        const luz_input_file *file = &inputs->files[i];
        if (file->identified && file->device == status.st_dev && file->inode == status.st_ino)
            return file;
    }
    return NULL;
}

void luz_input_files_free(luz_input_files *inputs)
{
    for (int i = 0; i < inputs->count; i++)
        free(inputs->files[i].path);
    free(inputs->files);
    *inputs = (luz_input_files){0};
}
