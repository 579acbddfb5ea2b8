/*
 * fuzz_options.c: the command-line parser (app/options.h,
 * luz_options_parse) on any argv.
 *
 * In:  bytes, split at NUL bytes into arguments (at most 64, 4 KiB in
 *      all), after argv[0] "luz-render".
 * Checks: no crash or undefined behaviour; a refusal gives a reason; and
 *      options that parse write a scene file that reads back to the same
 *      settings (fuzz_support.h).
 * Inputs that name --scene are skipped: that option reads a file, which a
 *      fuzzer must not pick from the machine's; fuzz_scene.c covers the
 *      reader.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_support.h"

enum { MAX_ARGUMENTS = 64, MAX_BYTES = 4096 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > MAX_BYTES) return 0;
    for (size_t i = 0; i + 7 <= size; i++)
        if (memcmp(data + i, "--scene", 7) == 0) return 0;
    char text[MAX_BYTES + 1];
    memcpy(text, data, size);
    text[size] = '\0';
    char *argv[MAX_ARGUMENTS + 2] = {"luz-render"};
    int argc = 1;
    for (size_t start = 0; start <= size && argc <= MAX_ARGUMENTS;) {
        argv[argc++] = text + start;
        start += strlen(text + start) + 1;
    }
    argv[argc] = NULL;
    /* a trailing NUL ends the last argument; it does not start another */
    if (size > 0 && data[size - 1] == '\0') argv[--argc] = NULL;

    luz_options options;
    luz_options_init(&options);
    luz_error error = {{0}};
    if (luz_options_parse(&options, argc, argv, &error) == 0)
        fuzz_check_round_trip(&options);
    else
        fuzz_check_message(&error);
    luz_options_free(&options);
    return 0;
}
