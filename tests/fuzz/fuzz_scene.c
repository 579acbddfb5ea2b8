/*
 * fuzz_scene.c: the scene-file reader (app/options.h,
 * luz_options_read_scene_text, the reader of --scene files) on any text.
 *
 * In:  bytes, read as the text of the scene file /fuzz/scene.luz (NUL
 *      bytes and all).
 * Checks: no crash or undefined behaviour; a refusal gives a reason; and a
 *      scene that reads (and passes luz_options_finish) is written with
 *      luz_options_write_scene and read back to the same settings: every
 *      saved key's value and every cube and model line, bit for bit
 *      (fuzz_support.h).
 */
#include <stdint.h>

#include "fuzz_support.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* a scene file's own limit is 64 MiB; the fuzzer's inputs are small */
    if (size > (1 << 20)) return 0;
    luz_options options;
    luz_options_init(&options);
    luz_error error = {{0}};
    int status = luz_options_read_scene_text(&options, (const char *)data, size,
                                             "/fuzz/scene.luz", &error);
    if (status == 0) status = luz_options_finish(&options, &error);
    if (status == 0)
        fuzz_check_round_trip(&options);
    else
        fuzz_check_message(&error);
    luz_options_free(&options);
    return 0;
}
