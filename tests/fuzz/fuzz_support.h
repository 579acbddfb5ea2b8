/*
 * fuzz_support.h: what the harnesses share. Each harness defines
 * LLVMFuzzerTestOneInput (libFuzzer's entry point), which replay.c also
 * calls; it keeps no state between calls and frees all it allocates.
 *
 *   FUZZ_CHECK(condition, ...)    abort()s with a message when a property
 *                                 fails, so that libFuzzer (or the suite's
 *                                 replay) reports the input
 *   fuzz_check_message(error)     a refusal gives a reason
 *   fuzz_check_round_trip(options)     the scene writer's text reads back
 *                                 to the same settings
 */
#ifndef LUZ_FUZZ_SUPPORT_H
#define LUZ_FUZZ_SUPPORT_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/options.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FUZZ_CHECK(condition, ...)                                            \
    do {                                                                      \
        if (!(condition)) {                                                   \
            fprintf(stderr, "fuzz: %s:%d: failed: %s: ", __FILE__, __LINE__,  \
                    #condition);                                              \
            fprintf(stderr, __VA_ARGS__);                                     \
            fputc('\n', stderr);                                              \
            abort();                                                          \
        }                                                                     \
    } while (0)

/* A refusal says why: an empty message tells the user nothing. (Control
 * characters are allowed: luz_error_print shows them as '?'.) */
static inline void fuzz_check_message(const luz_error *error)
{
    FUZZ_CHECK(error->message[0] != '\0', "an empty message");
}

/* The scene part of options, as luz_options_write_scene saves it, read
 * back: the same settings. Every saved key's text (luz_options_format
 * reads back exactly, so equal text is an equal value) and every
 * object's fields, bit for bit. */
static inline void fuzz_check_round_trip(const luz_options *options)
{
    char *text = NULL;
    size_t length = 0;
    FILE *out = open_memstream(&text, &length);
    FUZZ_CHECK(out != NULL, "open_memstream");
    luz_options_write_scene(options, out);
    FUZZ_CHECK(fclose(out) == 0, "fclose");

    luz_options back;
    luz_options_init(&back);
    luz_error error = {{0}};
    int status = luz_options_read_scene_text(&back, text, length, "/fuzz/written.luz", &error);
    if (status == 0) status = luz_options_finish(&back, &error);
    FUZZ_CHECK(status == 0, "the written scene is refused: %s\n--- written ---\n%s",
               error.message, text);

    luz_option_info row;
    for (size_t i = 0; luz_options_row(i, &row); i++) {
        if (row.saving == LUZ_OPTION_NOT_SAVED) continue;
        char first[8192], second[8192];
        int first_status = luz_options_format(options, row.name, first, sizeof first);
        int second_status = luz_options_format(&back, row.name, second, sizeof second);
        if (strcmp(row.name, "cubes") == 0 && options->scene.object_count > 0) continue;
        FUZZ_CHECK(first_status == second_status &&
                       (first_status != 0 || strcmp(first, second) == 0),
                   "%s: '%s' written, '%s' read back\n--- written ---\n%s", row.name,
                   first_status == 0 ? first : "(unset)", second_status == 0 ? second : "(unset)",
                   text);
    }
    FUZZ_CHECK(back.scene.object_count == options->scene.object_count,
               "%d objects written, %d read back\n--- written ---\n%s",
               options->scene.object_count, back.scene.object_count, text);
    for (int i = 0; i < options->scene.object_count; i++) {
        const luz_object *a = &options->objects[i], *b = &back.objects[i];
        const luz_object_source *sa = &options->object_sources[i], *sb = &back.object_sources[i];
        const bool same_names =
            (sa->texture_name == NULL) == (sb->texture_name == NULL) &&
            (sa->texture_name == NULL || strcmp(sa->texture_name, sb->texture_name) == 0) &&
            (sa->model_path == NULL) == (sb->model_path == NULL) &&
            (sa->model_path == NULL || strcmp(sa->model_path, sb->model_path) == 0);
        FUZZ_CHECK(memcmp(&a->position, &b->position, sizeof a->position) == 0 &&
                       a->has_colour == b->has_colour &&
                       (!a->has_colour || memcmp(&a->colour, &b->colour, sizeof a->colour) == 0) &&
                       memcmp(&a->scale, &b->scale, sizeof a->scale) == 0 &&
                       a->still == b->still && same_names,
                   "object %d differs once read back\n--- written ---\n%s", i, text);
    }
    luz_options_free(&back);
    free(text);
}

#endif
