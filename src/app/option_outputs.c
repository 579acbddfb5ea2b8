/*
 * option_outputs.c: the files a run will write, checked before it renders
 * anything.
 *
 * In:  the options, once the textures and models are loaded (so that
 *      options->inputs holds every file the run reads).
 * Out: 0, or one line naming the -o file that must not be written: a
 *      device, FIFO, socket, directory or symbolic link at its path (the
 *      rename into place would replace it: as root, /dev/null itself), or
 *      an input of the run (the image would replace the texture or the
 *      scene file it came from); for -o -, standard output when it is
 *      one of the inputs (redirected or appended to it).
 *
 * Every frame of a sequence is checked, not just the first: `-o
 * tex/%d.bmp --frames 3` reaches tex/1.bmp only at frame 1, and a half
 * written sequence is what the check is there to prevent. new_file.c
 * checks the path once more right before its rename, for what appears
 * meanwhile.
 *
 * Uses options.c (the frames, the -o pattern) and io (new_file.c,
 * input_files.c); nothing calls back.
 */
#include "app/options.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "io/new_file.h"

/* What a user who named a device or /proc's links most likely wanted. */
static const char *stdout_hint(const char *path)
{
    return strncmp(path, "/dev/", 5) == 0 || strncmp(path, "/proc/", 6) == 0
               ? " (-o - writes the PNGs to standard output)"
               : "";
}

static int check_output(const luz_options *options, const char *path, luz_error *error)
{
    luz_error refused;
    if (luz_new_file_check_target(path, &refused) != 0)
        return luz_error_set(error, "-o: %s%s", refused.message, stdout_hint(path));
    if (luz_new_file_folders(path, false, &refused) != 0)
        return luz_error_set(error, "-o: %s; expected folders that exist or can be made",
                             refused.message);
    const luz_input_file *input = luz_input_files_find(&options->inputs, path);
    if (input == NULL)
        return 0;
    const bool same_text = strcmp(input->path, path) == 0;
    return luz_error_set(error,
                         "-o: %s: is %s this run reads%s%s%s; expected an output file that "
                         "is none of its inputs",
                         path, input->what, same_text ? "" : " (", same_text ? "" : input->path,
                         same_text ? "" : ")");
}

/* -o -: standard output may be a file (`> frames.bin`), but not one this
 * run reads: `-o - >> tex/a.png` would append PNGs to the texture, and a
 * redirection without truncation (`1<> scene.luz`) overwrite the scene. */
static int check_stdout(const luz_options *options, luz_error *error)
{
    const luz_input_file *input = luz_input_files_find_descriptor(&options->inputs,
                                                                  STDOUT_FILENO);
    if (input == NULL)
        return 0;
    return luz_error_set(error, "-o -: standard output is %s this run reads (%s); expected a "
                                "pipe or a file that is none of its inputs",
                         input->what, input->path);
}

/* Does the name say PNG? A user who writes out.jpg expects a JPEG, and
 * a viewer that trusts the name fails on the PNG bytes under it. The
 * pattern is checked, not each frame: a %d comes before the end. */
static bool names_a_png(const char *path)
{
    size_t length = strlen(path);
    return length >= 4 && strcasecmp(path + length - 4, ".png") == 0;
}

int luz_options_check_outputs(const luz_options *options, luz_error *error)
{
    if (options->bench_frames > 0 || options->output_path == NULL)   /* --probe alone */
        return 0;
    if (luz_options_output_is_stdout(options))
        return check_stdout(options, error);
    int first, count;
    luz_options_frames_to_render(options, &first, &count);
    char path[PATH_MAX + 64];
    for (int k = first; k < first + count; k++) {
        if (luz_options_output_path(options, k, path, sizeof path, error) != 0 ||
            check_output(options, path, error) != 0)
            return -1;
    }
    /* after the checks above, whose reasons (a directory, an input of the
     * run) say more than the name's ending */
    if (count > 0 && !names_a_png(options->output_path))
        return luz_error_set(error, "-o: %s: expected a name ending in .png (luz-render "
                                    "writes PNG images only)", options->output_path);
    return 0;
}

int luz_options_make_output_folders(const luz_options *options, luz_error *error)
{
    if (options->bench_frames > 0 || options->output_path == NULL ||
        luz_options_output_is_stdout(options))
        return 0;
    int first, count;
    luz_options_frames_to_render(options, &first, &count);
    char path[PATH_MAX + 64], made[PATH_MAX + 64] = "";
    for (int k = first; k < first + count; k++) {
        if (luz_options_output_path(options, k, path, sizeof path, error) != 0)
            return -1;
        /* a sequence's frames mostly share their folder: make it once */
        const char *slash = strrchr(path, '/');
        size_t folder_length = slash != NULL ? (size_t)(slash - path) : 0;
        if (folder_length == strlen(made) && strncmp(path, made, folder_length) == 0)
            continue;
        luz_error refused;
        if (luz_new_file_folders(path, true, &refused) != 0)
            return luz_error_set(error, "-o: %s", refused.message);
        memcpy(made, path, folder_length);
        made[folder_length] = '\0';
    }
    return 0;
}
