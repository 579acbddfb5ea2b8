/*
 * command_line.c: argv into luz_options, --scene files included.
 *
 * The top of the option files, and the only one that knows both of the
 * others: it uses options.c (the table's rows, setting one value,
 * finishing) and scene_file.c (reading a --scene file); neither calls back
 * into this file, and options.c calls neither of them. That is why
 * luz_options_set, which reads a file for "scene", lives here, while
 * options.c's luz_options_set_value sets every other option and is what
 * scene_file.c uses.
 *
 * luz_options_parse reads the command line in three passes so that the
 * command line wins over a scene file whatever the order of the arguments
 * (docs/cli.md, Precedence): the shape of every argument first, so that a
 * typo is reported before any file is opened; then the --scene files, in
 * order; then every other argument, over them.
 */
#include "app/options.h"

#include <stdio.h>
#include <string.h>

#include "app/option_text.h"

int luz_options_set(luz_options *options, const char *name, const char *value,
                    const char *where, luz_error *error)
{
    /* A missing value goes to luz_options_set_value like any other, for
     * the same message ("--scene: missing value (expected FILE)"). */
    if (strcmp(name, "scene") == 0 && value != NULL && value[0] != '\0')
        return luz_options_read_scene_file(options, value, error);
    if (strcmp(name, "model") == 0 && value != NULL && value[0] != '\0') {
        /* The model replaces every object: it is object 0, at the origin,
         * scale 1, turning as cube 0. */
        char path[4096];
        if (luz_options_model_path(NULL, value, path, sizeof path, error) != 0) return -1;
        luz_options_clear_objects(options);
        const luz_object model = {.texture = LUZ_TEXTURE_BY_INDEX, .scale = 1.0f};
        return luz_options_add_object(options, &model, NULL, path, 0, where ? where : "--model",
                                      error);
    }
    return luz_options_set_value(options, name, value, where, error);
}

/* One argument (and its value) of the command line. */
typedef struct command_argument {
    luz_option_info option;
    const char *value;   /* NULL for a flag */
    char where[32];      /* "--size" or "-o", for messages */
} command_argument;

/* Reads argv[*index] (and its value) and moves *index past them. Checks the
 * shape only: a known option, a value present when one is needed. */
static int read_argument(int argc, char **argv, int *index, command_argument *argument,
                         luz_error *error)
{
    const char *text = argv[(*index)++];
    const char *equals = NULL;
    if (strcmp(text, "-o") == 0) {
        luz_options_find("output", 6, &argument->option);
        snprintf(argument->where, sizeof argument->where, "-o");
    } else if (text[0] == '-' && text[1] == '-' && text[2] != '\0') {
        const char *name = text + 2;
        equals = strchr(name, '=');
        size_t length = equals ? (size_t)(equals - name) : strlen(name);
        /* "--o" is not -o: only the short form is short */
        if (!luz_options_find(name, length, &argument->option) || length == 1) {
            char flag[64];
            snprintf(flag, sizeof flag, "%.*s", (int)(length + 2 < 60 ? length + 2 : 60), text);
            return luz_error_set(error, "unknown option '%s' (see --help)",
                                 option_quote(flag).text);
        }
        snprintf(argument->where, sizeof argument->where, "--%s", argument->option.name);
    } else if (text[0] == '-' && text[1] != '\0') {
        return luz_error_set(error, "unknown option '%s' (see --help)", option_quote(text).text);
    } else {
        return luz_error_set(error,
                             "unexpected argument '%s' (options start with --; see --help)",
                             option_quote(text).text);
    }

    if (argument->option.is_flag) {
        if (equals != NULL)
            return luz_error_set(error, "%s: takes no value, got '%s'", argument->where,
                                 option_quote(equals + 1).text);
        argument->value = NULL;
        return 0;
    }
    if (equals != NULL)
        argument->value = equals + 1;
    else if (*index < argc)
        argument->value = argv[(*index)++];
    else
        argument->value = NULL;
    if (argument->value == NULL || argument->value[0] == '\0')
        return luz_error_set(error, "%s: missing value (expected %s)", argument->where,
                             argument->option.syntax);
    return 0;
}

int luz_options_parse(luz_options *options, int argc, char **argv, luz_error *error)
{
    command_argument argument;
    for (int index = 1; index < argc;) {
        if (read_argument(argc, argv, &index, &argument, error) != 0)
            return -1;
    }
    /* Every argument was read once already, so these reads cannot fail. */
    for (int index = 1; index < argc;) {
        read_argument(argc, argv, &index, &argument, error);
        if (strcmp(argument.option.name, "scene") == 0 &&
            luz_options_set(options, argument.option.name, argument.value, argument.where,
                            error) != 0)
            return -1;
    }
    for (int index = 1; index < argc;) {
        read_argument(argc, argv, &index, &argument, error);
        if (strcmp(argument.option.name, "scene") != 0 &&
            luz_options_set(options, argument.option.name, argument.value, argument.where,
                            error) != 0)
            return -1;
    }
    return luz_options_finish(options, error);
}
