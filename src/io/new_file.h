/*
 * new_file.h: files that appear complete or not at all (new_file.c).
 *
 * A new file is written under a temporary name beside its path (mkstemp,
 * so two writers never share one) and put under its path only once every
 * byte is written and the file is closed. A reader, or a write that fails
 * half-way, never sees part of a file under the path.
 *
 *   luz_new_file file;
 *   if (luz_new_file_open(&file, path, error) != 0) return -1;
 *   ... write to file.stream ...
 *   status = luz_new_file_commit(&file, replace, error);   0, LUZ_FILE_EXISTS or -1
 */
#ifndef LUZ_IO_NEW_FILE_H
#define LUZ_IO_NEW_FILE_H

#include <stdbool.h>
#include <stdio.h>

#include "luz/error.h"

/* What a write that never replaces a file returns when the name is taken
 * (luz_new_file_commit, luz_framebuffer_write_new_png,
 * luz_options_save_scene). */
#define LUZ_FILE_EXISTS 1

typedef struct luz_new_file {
    FILE *stream;       /* write here */
    const char *path;   /* the caller's, for messages and the final name */
    char *temporary;    /* PATH.tmp-XXXXXX */
} luz_new_file;

/* Creates the temporary file, with the mode a plain fopen would give
 * (0666 less the umask). Returns 0, or -1 with a message naming path. */
int luz_new_file_open(luz_new_file *file, const char *path, luz_error *error);

/* Closes the stream and puts the file under its path. replace: rename()
 * over whatever is there. !replace: never replace a file; link() makes the
 * name atomically or fails because it exists, and then the temporary file
 * is removed and LUZ_FILE_EXISTS returned. If writing failed (the stream's
 * error flag, a failed close) nothing is left behind and -1 is returned
 * with a message. */
int luz_new_file_commit(luz_new_file *file, bool replace, luz_error *error);

/* Gives up: closes and removes the temporary file. */
void luz_new_file_abandon(luz_new_file *file);

#endif
