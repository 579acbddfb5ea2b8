/*
 * model_confine_none.c: io/model_confine.h where luz has no confinement
 * for assimp's process (every system but Linux; model_confine.c is
 * Linux's: Landlock, seccomp, no new privileges).
 *
 * In:  the model's path and the pipe the child writes to.
 * Out: nothing confined. luz_model_load says once per model that its
 *      process was limited (time, memory: io/model_sandbox.h) but not
 *      confined, as it does on a Linux kernel without Landlock and seccomp.
 */
#include "io/model_confine.h"

luz_confinement luz_confinement_available(void)
{
    return (luz_confinement){.landlock_abi = 0, .seccomp = false};
}

const char *luz_confinement_missing(const luz_confinement *available)
{
    (void)available;
    return "Landlock and seccomp";
}

int luz_confine_model_reader(const char *model_path, int pipe_end,
                             const luz_confinement *available, luz_error *error)
{
    (void)model_path;
    (void)pipe_end;
    (void)available;
    (void)error;
    return 0;
}
