/*
 * test_cli_output.c: what a write may replace. luz-render's -o replaces a
 * regular file that is none of the run's inputs and nothing else (a FIFO,
 * a socket, a symbolic link, a device, a texture or the scene file it
 * reads, by any name), checked before the first frame and again right
 * before the rename (io/new_file.h); the viewer's F2 (luz_options_save_scene)
 * never replaces a file unless asked, and under a file-size limit fails
 * with one message and leaves no temporary behind.
 */
/* mknod, for a device of the sandbox's own */
#define _XOPEN_SOURCE 700

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "cli_support.h"

#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/sysmacros.h>
#include <sys/un.h>

#include "io/new_file.h"

/* luz_options_save_scene (the viewer's F2): the file reads back as the
 * options; saved again without replace, under the same name, it is
 * refused with LUZ_FILE_EXISTS and the first file stays as it was, with
 * no temporary file left; with replace it is replaced. A directory that
 * does not exist gives -1 and a message naming the path. */
static void test_save_scene_never_replaces_unless_asked(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600], missing[600];
    sandbox_path(&box, "view.luz", path, sizeof path);
    sandbox_path(&box, "no-such-directory/view.luz", missing, sizeof missing);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);

    luz_options first, second, copy;
    parse_or_fail(&first, 3, (char *[]){"luz", "--seed", "11", NULL});
    parse_or_fail(&second, 3, (char *[]){"luz", "--seed", "22", NULL});
    luz_error error = {{0}};
    assert_int_equal(luz_options_save_scene(&first, path, false, &error), 0);
    char *text = read_file(path, NULL);
    assert_int_equal(luz_options_save_scene(&second, path, false, &error), LUZ_FILE_EXISTS);
    char *unchanged = read_file(path, NULL);
    assert_string_equal(text, unchanged);
    read_scene_from(&copy, path);
    assert_int_equal(copy.scene.seed, 11);
    luz_options_free(&copy);
    list_tree(box.work, "", after, sizeof after);
    assert_new_files(before, after, ARGS("view.luz"));

    assert_int_equal(luz_options_save_scene(&second, path, true, &error), 0);
    read_scene_from(&copy, path);
    assert_int_equal(copy.scene.seed, 22);
    luz_options_free(&copy);

    assert_int_equal(luz_options_save_scene(&first, missing, false, &error), -1);
    assert_non_null(strstr(error.message, missing));

    free(text);
    free(unchanged);
    luz_options_free(&first);
    luz_options_free(&second);
    sandbox_destroy(&box);
}

/* A thing at a path, as lstat sees it: luz-render must leave it as it was. */
typedef struct file_identity {
    mode_t type;
    dev_t device;
    ino_t inode;
} file_identity;

static file_identity identity_of(const char *path)
{
    struct stat status;
    if (lstat(path, &status) != 0)
        fail_msg("%s: %s", path, strerror(errno));
    return (file_identity){status.st_mode & S_IFMT, status.st_dev, status.st_ino};
}

/* luz-render -o NAME, with NAME something the rename would replace: exit
 * status 2, one line naming NAME and what it is, nothing written, NAME
 * still the same thing. */
static void assert_output_refused(const sandbox *box, const char *name, const char *what)
{
    char path[600], before[8192] = "", after[8192] = "";
    sandbox_path(box, name, path, sizeof path);
    const file_identity was = identity_of(path);
    list_tree(box->work, "", before, sizeof before);
    run_result result = run_in(box, ARGS("--size", "8x8", "--textures", "none", "-o", name), NULL);
    char needle[700];
    snprintf(needle, sizeof needle, "luz-render: -o: %s: is %s, not a regular file", name, what);
    if (result.status != 2 || strncmp(result.err, needle, strlen(needle)) != 0 ||
        strchr(result.err, '\n') != result.err + strlen(result.err) - 1)
        fail_msg("-o %s: exit %d, stderr '%s'; expected 2 and '%s...'", name, result.status,
                 result.err, needle);
    const file_identity is = identity_of(path);
    assert_int_equal(is.type, was.type);
    assert_int_equal(is.inode, was.inode);
    assert_int_equal(is.device, was.device);
    list_tree(box->work, "", after, sizeof after);
    assert_string_equal(before, after);
    run_result_free(&result);
}

/* The case: as root, -o /dev/null replaced the system's /dev/null
 * with a PNG, since a rename replaces whatever has the name. Only a regular
 * file is replaced now; everything else at the path is refused. (The
 * devices are made in the sandbox, never the system's own, so that a
 * regression cannot harm the machine that runs the test.) */
static void test_output_replaces_only_regular_files(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600];

    sandbox_path(&box, "fifo.png", path, sizeof path);
    assert_int_equal(mkfifo(path, 0644), 0);
    assert_output_refused(&box, "fifo.png", "a FIFO");

    sandbox_path(&box, "socket.png", path, sizeof path);
    int listener = socket(AF_UNIX, SOCK_STREAM, 0);
    assert_true(listener >= 0);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (strlen(path) < sizeof address.sun_path) {   /* a socket's path is short */
        memcpy(address.sun_path, path, strlen(path) + 1);
        assert_int_equal(bind(listener, (struct sockaddr *)&address, sizeof address), 0);
        assert_output_refused(&box, "socket.png", "a socket");
    }
    close(listener);

    /* a symbolic link is replaced itself, so it is refused whatever it
     * points to: a device (/dev/stdout is a link), or a file */
    sandbox_path(&box, "null-link.png", path, sizeof path);
    assert_int_equal(symlink("/dev/null", path), 0);
    assert_output_refused(&box, "null-link.png", "a symbolic link");
    sandbox_path(&box, "file-link.png", path, sizeof path);
    assert_int_equal(symlink("tex/a.bmp", path), 0);
    assert_output_refused(&box, "file-link.png", "a symbolic link");

    /* a character device of the sandbox's own (1, 3 is null's number);
     * only root may make one */
    sandbox_path(&box, "device.png", path, sizeof path);
    if (mknod(path, S_IFCHR | 0666, makedev(1, 3)) == 0)
        assert_output_refused(&box, "device.png", "a character device");
    else
        print_message("device case skipped: mknod: %s\n", strerror(errno));

    /* the check itself, on the system's devices: it writes nothing */
    luz_error error;
    assert_int_equal(luz_new_file_check_target("/dev/null", &error), -1);
    assert_string_equal(error.message, "/dev/null: is a character device, not a regular file; "
                                       "expected a new file or a regular file to replace");
    assert_int_equal(luz_new_file_check_target("/dev/stdout", &error), -1);
    assert_non_null(strstr(error.message, "/dev/stdout: is a symbolic link"));
    sandbox_destroy(&box);
}

/* A sequence's every frame is checked before the first is rendered: frame
 * 1 of tex/%d.bmp is tex/1.bmp, a texture, so nothing is written at all
 * (not frame 0 either) and the texture stays as it was. */
static void test_no_frame_replaces_an_input(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char texture[600], frame0[600];
    sandbox_path(&box, "tex/1.bmp", texture, sizeof texture);
    sandbox_path(&box, "tex/0.bmp", frame0, sizeof frame0);
    write_bmp(texture, 2, 2, 10, 20, 30);
    size_t length_before, length_after;
    char *bytes_before = read_file(texture, &length_before);
    run_result result = run_in(&box, ARGS("--size", "8x8", "--textures", "tex", "--frames", "3",
                                          "-o", "tex/%d.bmp"), NULL);
    assert_int_equal(result.status, 2);
    assert_string_equal(result.err, "luz-render: -o: tex/1.bmp: is a texture this run reads; "
                                    "expected an output file that is none of its inputs\n");
    assert_int_equal(access(frame0, F_OK), -1);
    char *bytes_after = read_file(texture, &length_after);
    assert_int_equal(length_after, length_before);
    assert_memory_equal(bytes_after, bytes_before, length_before);
    free(bytes_before);
    free(bytes_after);
    run_result_free(&result);

    /* the same file by a hard link elsewhere: its device and inode */
    char link_path[600];
    sandbox_path(&box, "same.bmp", link_path, sizeof link_path);
    assert_int_equal(link(texture, link_path), 0);
    result = run_in(&box, ARGS("--size", "8x8", "--textures", "tex", "-o", "same.bmp"), NULL);
    assert_int_equal(result.status, 2);
    assert_string_equal(result.err, "luz-render: -o: same.bmp: is a texture this run reads "
                                    "(tex/1.bmp); expected an output file that is none of its "
                                    "inputs\n");
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* Missing folders of -o are made, as mkdir -p makes them (issue 31: the
 * README's -o frames/... failed on a fresh clone after frame 0, exit 1);
 * a pattern whose folder changes with the frame gets each; .PNG is a
 * PNG's name too. */
static void test_output_folders_are_made(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "8x6", "--textures", "none", "--frames", "3",
                                          "-o", "new/deeper/f_%d.png"), NULL);
    assert_int_equal(result.status, 0);
    assert_string_equal(result.err, "");
    run_result_free(&result);
    for (int k = 0; k < 3; k++) {
        char name[64];
        snprintf(name, sizeof name, "new/deeper/f_%d.png", k);
        assert_png_size(&box, name, 8, 6);
    }
    result = run_in(&box, ARGS("--size", "8x6", "--textures", "none", "--frames", "2", "-o",
                               "shot_%d//f.PNG"), NULL);
    assert_int_equal(result.status, 0);
    run_result_free(&result);
    assert_png_size(&box, "shot_0/f.PNG", 8, 6);
    assert_png_size(&box, "shot_1/f.PNG", 8, 6);

    /* a folder that cannot be made, even by root (sysfs refuses mkdir):
     * one line naming it, exit 2, no frame */
    struct stat sys;
    if (stat("/sys/kernel", &sys) == 0 && S_ISDIR(sys.st_mode)) {
        result = run_in(&box, ARGS("--size", "8x6", "--textures", "none", "-o",
                                   "/sys/luz-no-folder/f.png"), NULL);
        assert_int_equal(result.status, 2);
        assert_non_null(strstr(result.err, "luz-render: -o: /sys/luz-no-folder/f.png: cannot "
                                           "create the folder /sys/luz-no-folder ("));
        assert_int_equal(strchr(result.err, '\n') - result.err, strlen(result.err) - 1);
        run_result_free(&result);
    } else {
        print_message("the folder that cannot be made: skipped, no sysfs at /sys\n");
    }
    sandbox_destroy(&box);
}

/* The check is new_file's, right before the rename too: a FIFO that
 * appears while the PNG is written is not replaced, and the temporary
 * file is removed. */
static void test_commit_checks_the_path_again(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600], before[8192] = "", after[8192] = "";
    sandbox_path(&box, "late.png", path, sizeof path);
    list_tree(box.work, "", before, sizeof before);
    luz_new_file file;
    luz_error error;
    assert_int_equal(luz_new_file_open(&file, path, &error), 0);
    fputs("not yet a PNG", file.stream);
    assert_int_equal(mkfifo(path, 0644), 0);
    assert_int_equal(luz_new_file_commit(&file, true, &error), -1);
    assert_non_null(strstr(error.message, "late.png: is a FIFO, not a regular file"));
    assert_int_equal(identity_of(path).type, S_IFIFO);
    list_tree(box.work, "", after, sizeof after);
    assert_new_files(before, after, ARGS("late.png"));   /* the FIFO, and no temporary */
    sandbox_destroy(&box);
}

/* A file-size limit (ulimit -f) made the write die of SIGXFSZ and leave
 * NAME.tmp-XXXXXX behind. Now the write fails with EFBIG: -1, one message,
 * no file, and the signal is not delivered once the mask is restored. In
 * a child, whose limit the test can lower: the defaults' scene text is
 * about 400 bytes, the limit 100. This is the viewer's F2 path. */
static void test_save_scene_past_the_file_size_limit(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char path[600], before[8192] = "", after[8192] = "";
    sandbox_path(&box, "view.luz", path, sizeof path);
    list_tree(box.work, "", before, sizeof before);
    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        luz_options options;
        luz_options_init(&options);
        struct rlimit limit = {100, 100};
        luz_error error = {{0}};
        int status = setrlimit(RLIMIT_FSIZE, &limit) == 0
                         ? luz_options_save_scene(&options, path, false, &error)
                         : 9;
        /* 0: the expected failure and message; else what went wrong */
        bool expected = status == -1 && strstr(error.message, "view.luz: cannot write (File "
                                                             "too large)") != NULL;
        _exit(expected ? 0 : status == 0 ? 3 : 4);
    }
    int status;
    while (waitpid(child, &status, 0) < 0)
        assert_int_equal(errno, EINTR);
    if (!WIFEXITED(status))
        fail_msg("the child died of signal %d", WTERMSIG(status));
    assert_int_equal(WEXITSTATUS(status), 0);
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

int main(void)
{
    static const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_save_scene_never_replaces_unless_asked),
        cmocka_unit_test(test_output_replaces_only_regular_files),
        cmocka_unit_test(test_no_frame_replaces_an_input),
        cmocka_unit_test(test_output_folders_are_made),
        cmocka_unit_test(test_commit_checks_the_path_again),
        cmocka_unit_test(test_save_scene_past_the_file_size_limit),
    };
    return _cmocka_run_group_tests("cli-output", tests, sizeof tests / sizeof tests[0], NULL, NULL);
}
