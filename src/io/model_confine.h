/*
 * io/model_confine.h: what assimp's process may still do once it starts
 * reading a model (model_confine.c).
 *
 * assimp is limited in time and memory (io/model_sandbox.h), but a bug in
 * it (the fuzzer found wild reads) would otherwise run with the user's
 * full rights. The child that runs it therefore confines itself, as
 * browsers and thumbnailers confine their decoders, before it reads a
 * byte of the model:
 *   - no new privileges (PR_SET_NO_NEW_PRIVS: no set-uid program, no
 *     file capability can give it more than it has);
 *   - Landlock (Linux 5.13 and later): it may read files and list
 *     directories beneath the model's folder, and the model file itself,
 *     and nothing else; it may write, create, remove or rename no file
 *     anywhere; on kernels with Landlock's network rules (6.7), no TCP
 *     bind or connect; with its scopes (6.12), no signal to a process
 *     outside it and no abstract UNIX socket;
 *   - a seccomp filter (libseccomp): only the system calls that reading
 *     files through open descriptors, memory and ending need; write() only
 *     to the pipe back to luz; openat() only for reading; mmap() and
 *     mprotect() never executable. socket(), connect(), execve(), fork()
 *     and clone() kill it (SIGSYS); any other call fails with EPERM.
 */
#ifndef LUZ_IO_MODEL_CONFINE_H
#define LUZ_IO_MODEL_CONFINE_H

#include <stdbool.h>

#include "luz/error.h"

/* What this kernel (and build) offers; the same in the parent and the
 * child it forks. */
typedef struct luz_confinement {
    int landlock_abi;   /* Landlock's ABI version, 0 without it (an old
                           kernel, or not enabled: lsm= at boot) */
    bool seccomp;       /* seccomp filters (CONFIG_SECCOMP_FILTER) */
} luz_confinement;

luz_confinement luz_confinement_available(void);

/* The missing mechanisms as words for a warning ("Landlock" / "seccomp" /
 * "Landlock and seccomp"), "" when none is missing. */
const char *luz_confinement_missing(const luz_confinement *available);

/* Confines the calling process (the child, before it reads the model at
 * model_path) to reading beneath the model's folder and writing to
 * pipe_end, with what `available` says the kernel has. Returns 0, or -1
 * with a message when a mechanism the kernel has could not be set up (the
 * caller then does not read the model). */
int luz_confine_model_reader(const char *model_path, int pipe_end,
                             const luz_confinement *available, luz_error *error);

#endif
