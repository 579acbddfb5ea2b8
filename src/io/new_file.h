/*
 * new_file.h: files that appear complete or not at all (new_file.c).
 *
 * A new file is written under a temporary name beside its path (mkstemp,
 * so two writers never share one) and put under its path only once every
 * byte is written and the file is closed. A reader, or a write that fails
 * half-way, never sees part of a file under the path.
 *
 * Only a regular file is ever replaced: a device (/dev/null), a FIFO, a
 * socket, a directory or a symbolic link at the path is refused, since the
 * rename would put the image in its place (as root, /dev/null itself).
 *
 * While a file is open, the termination signals (SIGINT, SIGTERM, SIGHUP,
 * SIGQUIT) wait until it is committed or abandoned, so that none leaves
 * the temporary file behind; and SIGXFSZ is held and dropped, so that a
 * file-size limit (ulimit -f) makes the write fail with EFBIG, reported
 * and cleaned up like a full disk, instead of killing the program.
 *
 *   luz_new_file file;
 *   if (luz_new_file_open(&file, path, error) != 0) return -1;
 *   ... write to file.stream ...
 *   status = luz_new_file_commit(&file, replace, error);   0, LUZ_FILE_EXISTS or -1
 */
#ifndef LUZ_IO_NEW_FILE_H
#define LUZ_IO_NEW_FILE_H

#include <signal.h>
#include <stdbool.h>
#include <stdio.h>

#include "luz/error.h"

/* What a write that never replaces a file returns when the name is taken
 * (luz_new_file_commit, luz_framebuffer_write_new_png,
 * luz_options_save_scene). */
#define LUZ_FILE_EXISTS 1

/* The calling thread's signal mask from before a write held signals. */
typedef struct luz_held_signals {
    sigset_t previous;
} luz_held_signals;

/* Holds SIGXFSZ (a write past ulimit -f then fails with EFBIG) and, with
 * termination, SIGINT, SIGTERM, SIGHUP and SIGQUIT, on the calling thread.
 * Release with luz_release_write_signals on the same thread: a SIGXFSZ
 * the write raised is dropped, the others are delivered then. */
void luz_hold_write_signals(luz_held_signals *held, bool termination);
void luz_release_write_signals(const luz_held_signals *held);

typedef struct luz_new_file {
    FILE *stream;       /* write here */
    const char *path;   /* the caller's, for messages and the final name */
    char *temporary;    /* PATH.tmp-XXXXXX */
    luz_held_signals signals;   /* held from open to commit or abandon */
} luz_new_file;

/* Whether path may take a new file: 0 if nothing is there or a regular
 * file is (to be replaced), -1 with "PATH: ..." saying what is there
 * instead (a directory, a device, a FIFO, a socket, a symbolic link), or
 * that a path ending in '/' names no file. Other troubles (a directory
 * that does not exist) are left to the write, which reports them. */
int luz_new_file_check_target(const char *path, luz_error *error);

/* The folders above path (its parent, and theirs), as `mkdir -p` makes
 * them. create false only checks: 0 if each that exists is a folder (the
 * missing ones can be made later), else -1 with "PATH: FOLDER is not a
 * folder (it is ...)". create true also makes the missing ones, mode 0777
 * less the umask, and says "PATH: cannot create the folder FOLDER (why)"
 * for the first it cannot make. A path without a '/' has none. */
int luz_new_file_folders(const char *path, bool create, luz_error *error);

/* Creates the temporary file, with the mode a plain fopen would give
 * (0666 less the umask), and holds the write signals. Returns 0, or -1
 * with a message naming path (the signals released again). */
int luz_new_file_open(luz_new_file *file, const char *path, luz_error *error);

/* Closes the stream and puts the file under its path. replace: rename()
 * over a regular file that is there (luz_new_file_check_target once more,
 * right before). !replace: never replace a file; link() makes the name
 * atomically or fails because it exists, and then the temporary file is
 * removed and LUZ_FILE_EXISTS returned. If writing failed (the stream's
 * error flag, a failed close: EFBIG, ENOSPC) nothing is left behind and -1
 * is returned with a message. Releases the signals. */
int luz_new_file_commit(luz_new_file *file, bool replace, luz_error *error);

/* Gives up: closes and removes the temporary file, releases the signals. */
void luz_new_file_abandon(luz_new_file *file);

#endif
