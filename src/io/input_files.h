/*
 * input_files.h: the files a run reads, so that no output replaces one
 * (input_files.c).
 *
 * In:  the path of every file read: a scene file, a texture, a model, a
 *      texture that a model names.
 * Out: for an output path, the input it is, if any: the same path, or the
 *      same file under another name (the same device and inode: a hard
 *      link, ./x.png for x.png, a path through a symbolic link).
 *
 * `luz-render -o wood.png` beside wood.png the texture, or `-o view.luz`
 * for the scene file being read, would otherwise replace the input with the
 * image; luz-render checks every file name it will write against this list
 * before it renders anything.
 *
 *   luz_input_files inputs = {0};
 *   luz_input_files_add(&inputs, "scene.luz", "the scene file", error);
 *   const luz_input_file *input = luz_input_files_find(&inputs, "out.png");
 *   luz_input_files_free(&inputs);
 */
#ifndef LUZ_IO_INPUT_FILES_H
#define LUZ_IO_INPUT_FILES_H

#include <stdbool.h>
#include <sys/types.h>

#include "luz/error.h"

typedef struct luz_input_file {
    char *path;          /* as it was opened (owned) */
    const char *what;    /* "the scene file", "a texture", ... (static text) */
    bool identified;     /* device and inode known: stat succeeded */
    dev_t device;
    ino_t inode;
} luz_input_file;

typedef struct luz_input_files {
    luz_input_file *files;
    int count, capacity;
} luz_input_files;

/* Records path (stat'ed now, for its device and inode) as an input; what
 * says what it is, for messages, and must outlive the list. Returns 0, or
 * -1 if memory ran out. */
int luz_input_files_add(luz_input_files *inputs, const char *path, const char *what,
                        luz_error *error);

/* The same for a file another process read and identified (assimp's, with
 * fstat() of the descriptor it read: io/model_import.c): path as it was
 * opened there, device and inode as it found them. */
int luz_input_files_add_identified(luz_input_files *inputs, const char *path, const char *what,
                                   dev_t device, ino_t inode, luz_error *error);

/* The input that path names, by its text or by its device and inode, or
 * NULL if it is none of them. */
const luz_input_file *luz_input_files_find(const luz_input_files *inputs, const char *path);

/* The input that an open descriptor is (by device and inode: standard
 * output redirected or appended to a texture, `-o - >> tex/a.png`), or
 * NULL if it is none of them or fstat fails. */
const luz_input_file *luz_input_files_find_descriptor(const luz_input_files *inputs,
                                                      int descriptor);

void luz_input_files_free(luz_input_files *inputs);

#endif
