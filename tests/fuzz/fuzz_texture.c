/*
 * fuzz_texture.c: texture loading from memory (io/textures.h,
 * luz_texture_load_memory): the format checks of image_formats.c, the
 * budget, and the decoders (libpng, libjpeg-turbo, stb_image's BMP and TGA).
 *
 * In:  a first byte that picks the name the bytes come under (x.png,
 *      x.jpg, x.bmp, x.tga, or "*0", an embedded texture with no hint:
 *      the signature decides), then the file's bytes.
 * Checks: no crash or undefined behaviour (under ASan and UBSan); a
 *      refusal gives a reason and no texture; a texture is the size its
 *      header gave, within luz's limits, and the budget has counted it.
 * The budget is 16 MiB, so that the fuzzer spends its time on formats
 *      rather than on decoding huge images (a texture up to about
 *      1770 x 1770).
 */
#include <stdint.h>

#include "fuzz_support.h"
#include "io/input_file.h"
#include "io/textures.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const names[] = {"x.png", "x.jpg", "x.bmp", "x.tga", "*0"};
    if (size < 1) return 0;
    const char *name = names[data[0] % (sizeof names / sizeof names[0])];
    luz_texture_budget budget = {.limit = (uint64_t)16 << 20};
    luz_texture *texture = NULL;
    luz_error error = {{0}};
    int status =
        luz_texture_load_memory(data + 1, size - 1, name, NULL, &budget, &texture, &error);
    if (status != 0) {
        FUZZ_CHECK(texture == NULL, "a texture with status %d", status);
        FUZZ_CHECK(status == LUZ_BAD_INPUT || status == LUZ_MACHINE_FAILED, "status %d", status);
        FUZZ_CHECK(strncmp(error.message, name, strlen(name)) == 0,
                   "the message does not name %s: %s", name, error.message);
        fuzz_check_message(&error);
        return 0;
    }
    FUZZ_CHECK(texture != NULL, "no texture");
    const int width = texture->levels[0].width, height = texture->levels[0].height;
    FUZZ_CHECK(width >= 1 && height >= 1 && width <= LUZ_TEXTURE_MAX_SIZE &&
                   height <= LUZ_TEXTURE_MAX_SIZE,
               "a texture of %dx%d", width, height);
    FUZZ_CHECK(budget.used == luz_texture_bytes(width, height), "the budget counted %llu bytes",
               (unsigned long long)budget.used);
    luz_texture_destroy(texture);
    return 0;
}
