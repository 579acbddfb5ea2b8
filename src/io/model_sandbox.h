/*
 * io/model_sandbox.h: assimp's import of a model in a child process with a
 * time and memory limit (model_sandbox.c).
 *
 * Some of assimp's bugs (tests/fuzz/assimp-findings/) no cheap check keeps
 * out: a parser that reads past its buffer and loops forever, a count in a
 * file's body that makes it allocate a gigabyte. luz_model_load therefore
 * runs assimp in a child (fork, before the renderer's threads exist; the
 * only other thread then may be option_models.c's watcher, which prints
 * "reading FILE" on a terminal, and which the child never touches),
 * under limits that grow with the file's size, and reads the description
 * of the model it sends back (io/model_description.h) as a stranger's
 * bytes. However the child ends (refused, crashed, over a limit), the
 * model is refused with one line naming the file.
 */
#ifndef LUZ_IO_MODEL_SANDBOX_H
#define LUZ_IO_MODEL_SANDBOX_H

#include <stddef.h>
#include <stdint.h>

#include "io/model_description.h"
#include "luz/error.h"

/* The limits for a model file of file_size bytes: 10 s of CPU time and
 * 0.5 s more a MiB; a wall-clock deadline of twice that and 10 s more
 * (the machine may be busy); 1 GiB of address space and 128 bytes more
 * for each byte of the file, on top of what the child shares with luz's
 * process when it starts. 128: an OBJ of nothing but faces ("f 1 2 3",
 * 8 bytes each; 24 MB for 3 million) peaks at 3.4 GB of address space in
 * assimp 5.2.5 (its post-processing), 96 bytes a byte past the first GiB;
 * a sphere of a million triangles (104 MB) at 1.3 GB. A 1.1 GB OBJ of 10
 * million triangles (gen-model's torus knot) takes under 70 s of CPU time
 * and 13 GB of address space, within its 550 s; the fuzzer's OpenGEX file
 * that loops is stopped after 10 s, its PLY file that allocates 1 GB at
 * once. --model-memory sets the memory limit instead.
 * Descriptions may be at most as long as the memory limit. Under
 * AddressSanitizer or ThreadSanitizer, which reserve terabytes of address
 * space, the address space is not limited (memory_bytes 0). */
#define LUZ_MODEL_SECONDS 10.0
#define LUZ_MODEL_SECONDS_PER_MIB 0.5
#define LUZ_MODEL_MEMORY_BYTES ((uint64_t)1 << 30)
#define LUZ_MODEL_MEMORY_PER_BYTE 128

typedef struct luz_model_limits {
    double cpu_seconds;        /* RLIMIT_CPU of the child */
    double wall_seconds;       /* from fork to the child's end */
    uint64_t memory_bytes;     /* RLIMIT_AS of the child, above what it has
                                  from the parent; 0: none */
    uint64_t description_bytes;   /* the most the child may send */
} luz_model_limits;

luz_model_limits luz_model_limits_for(uint64_t file_size);
/* The memory limit the user chose (--model-memory), in place of the one
 * that grows with the file (none under the sanitizers, as above). */
void luz_model_limits_set_memory(luz_model_limits *limits, uint64_t memory_mib);

/* "PATH: assimp needs more than N MiB to read it (its memory limit;
 * --model-memory MiB raises it)": the one line for a model over the
 * limit, however the child found out (an allocation that failed, or a
 * crash at the limit). Returns LUZ_BAD_INPUT. */
int luz_model_memory_refusal(const char *path, uint64_t memory_bytes, luz_error *error);

/* What the child runs: writes a description to writer (or returns a
 * status and one line, which the child sends as a refusal). */
typedef int (*luz_model_child_work)(const void *context, uint64_t memory_limit,
                                    luz_model_writer *writer, luz_error *error);

/* Runs work(context, ...) in a child under limits and returns the bytes it
 * sent (*description, malloc'd; free() it) once it has exited normally;
 * they are not yet read (luz_model_description_read). Returns 0;
 * LUZ_BAD_INPUT with one line naming path when the child crashed (a
 * signal), went over a limit, exited with a failure or sent more than
 * limits->description_bytes; LUZ_MACHINE_FAILED when no child or pipe could
 * be made, memory ran out, or the system killed the child (SIGKILL that
 * luz did not send, as the out-of-memory killer does). The child's stdout
 * and stderr are /dev/null: its only voice is the pipe. */
int luz_model_run_isolated(const char *path, const luz_model_limits *limits,
                           luz_model_child_work work, const void *context,
                           unsigned char **description, size_t *size, luz_error *error);

#endif
