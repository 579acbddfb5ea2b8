/*
 * io/model_guards.h: checks a model file passes before assimp reads it, for
 * the bugs of Debian's assimp 5.2.5 that luz's fuzzer met and that a
 * cheap check can keep out (model_guards.c). The bugs no check can keep
 * out are listed in tests/fuzz/assimp-findings/.
 */
#ifndef LUZ_IO_MODEL_GUARDS_H
#define LUZ_IO_MODEL_GUARDS_H

#include <stddef.h>
#include <stdint.h>

#include "luz/error.h"

/* The longest PLY header luz reads: real ones hold a few lines and
 * comments. */
#define LUZ_PLY_HEADER_MAX_BYTES 65536

/* Checks the start of a model file (`start`, its first `length` bytes,
 * at most LUZ_PLY_HEADER_MAX_BYTES are needed) of `file_size` bytes in
 * all:
 *  - a PLY file ("ply" in any case) must have a header assimp reads
 *    without looping forever: an end_header line within
 *    LUZ_PLY_HEADER_MAX_BYTES, element counts in decimal digits no larger
 *    than the file has bytes;
 *  - a binary glTF ("glTF") must not claim more bytes than the file has,
 *    which assimp would allocate first.
 * Returns 0, or LUZ_BAD_INPUT with one line starting "NAME: ". */
int luz_model_check_start(const unsigned char *start, size_t length, uint64_t file_size,
                          const char *name, luz_error *error);

#endif
