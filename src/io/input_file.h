/*
 * io/input_file.h: opening the files luz reads, so that none can make it
 * block or read without bound (input_file.c).
 *
 * Every file luz reads comes through here: scene files, textures, models
 * and each file a model names (its .mtl, .bin, textures). A file is
 * opened without blocking, must be a regular file (not a FIFO, a device,
 * a socket or a directory) and at most as large as the limit its kind
 * has; only then is it read.
 */
#ifndef LUZ_IO_INPUT_FILE_H
#define LUZ_IO_INPUT_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "luz/error.h"

/* The largest file of each kind luz reads, in bytes. A scene file of
 * 100000 cube lines with colours and texture names takes about 10 MiB; an
 * image of 8192 x 8192 pixels (the largest a texture may be) takes
 * 256 MiB uncompressed as a 32-bit BMP or TGA; a model file and each file
 * it names up to 2 GiB (tens of millions of triangles). */
#define LUZ_SCENE_FILE_MAX_BYTES ((uint64_t)64 << 20)
#define LUZ_IMAGE_FILE_MAX_BYTES ((uint64_t)512 << 20)
#define LUZ_MODEL_FILE_MAX_BYTES ((uint64_t)2 << 30)

/* What io's readers and loaders return besides 0, each with one line in
 * their luz_error. The programs exit with status 2 for the input's faults
 * and 1 for the machine's. */
enum {
    LUZ_BAD_INPUT = -1,        /* the file is at fault: missing, not a
                                  regular file, too large, corrupt */
    LUZ_MACHINE_FAILED = -2,   /* out of memory, a read error of the disk */
    LUZ_NO_SUCH_FILE = -3,     /* luz_input_open only: nothing at the path
                                  (ENOENT, ENOTDIR); a fault of the input,
                                  which a caller may choose to ignore */
    LUZ_OUTSIDE_DIRECTORY = -4,   /* luz_input_open_beneath only: the name
                                     leads out of the directory; a fault
                                     of the input */
};

/* Opens path for reading, never blocking: stat() first, so that a FIFO, a
 * device or a directory is refused without being opened; then open() with
 * O_NONBLOCK (a FIFO that appears in between opens at once, and is then
 * refused), O_CLOEXEC and O_NOCTTY; then fstat() of the descriptor, which
 * must be a regular file of at most max_bytes. `what` names the kind of
 * file in messages, with its article ("a scene file").
 * Returns 0 with *descriptor and *size set, or LUZ_NO_SUCH_FILE,
 * LUZ_BAD_INPUT with a message naming path ("x.png: not a regular file (a
 * FIFO; expected an image file)"). */
int luz_input_open(const char *path, const char *what, uint64_t max_bytes, int *descriptor,
                   uint64_t *size, luz_error *error);

/* luz_input_open, then the whole file into *bytes (malloc'd, with a NUL
 * after the last byte; free() it) and its length into *size. A file that
 * grows past max_bytes while it is read (or a regular file whose size
 * stat() does not tell, as in /proc) is refused as too large. Returns 0,
 * LUZ_NO_SUCH_FILE, LUZ_BAD_INPUT (also a file that refuses to be read, as
 * /proc/self/pagemap does) or LUZ_MACHINE_FAILED (out of memory, EIO),
 * with a message. */
int luz_input_read(const char *path, const char *what, uint64_t max_bytes,
                   unsigned char **bytes, size_t *size, luz_error *error);

/* luz_input_open for the file `name` names within directory, when name
 * must not lead out of it (a model's textures, SCENE.md's "Models"): an
 * absolute name, a `..` above the directory, or a symbolic link whose
 * target lies outside it (or is an absolute path, where the kernel checks)
 * gives LUZ_OUTSIDE_DIRECTORY with "DIRECTORY/NAME: outside DIRECTORY
 * (how)". The kernel resolves the name within the directory (openat2's
 * RESOLVE_BENEATH, Linux 5.6); without it, the file opened is checked
 * against the directory's real path through /proc/self/fd. The file is
 * found without being opened for reading (O_PATH), must be a regular file
 * of at most max_bytes, and is then opened as luz_input_open opens one;
 * the check is of the file opened, so nothing changed in between escapes
 * it. Returns 0 with *descriptor and *size, or LUZ_NO_SUCH_FILE,
 * LUZ_BAD_INPUT, LUZ_OUTSIDE_DIRECTORY with a message naming
 * DIRECTORY/NAME. */
int luz_input_open_beneath(const char *directory, const char *name, const char *what,
                           uint64_t max_bytes, int *descriptor, uint64_t *size,
                           luz_error *error);

/* luz_input_read's reading, of a descriptor that luz_input_open or
 * luz_input_open_beneath gave with its size: reads it whole and closes
 * it; path names it in messages. */
int luz_input_read_descriptor(int descriptor, uint64_t size, const char *path, const char *what,
                              uint64_t max_bytes, unsigned char **bytes, size_t *byte_count,
                              luz_error *error);

/* "a FIFO", "a directory", ... for a stat() mode; "a regular file" for one. */
const char *luz_input_file_kind(unsigned mode);

#endif
