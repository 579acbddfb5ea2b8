/*
 * app/options.h: the scene options both programs share.
 *
 * luz-render and the viewer take the same long options (the knobs of
 * SCENE.md) and the same scene files, through this one parser. A scene file
 * holds `name = value` lines whose names are the long options without their
 * dashes, `#` comments, "quoted" values (for a path or texture name with
 * `#` or blanks in it), and `cube = ...` lines that replace the cube list;
 * options given on the command line override the file whatever their order.
 * docs/cli.md is the user's reference for both.
 *
 * Five files stand behind this header, each calling only those listed
 * before it: options.c (the option table), scene_file.c (scene files),
 * command_line.c (argv), option_textures.c (the textures named) and
 * option_outputs.c (the files a run will write); all read and write
 * numbers with option_text.h's helpers (option_text.c). option_models.c
 * reads the models named.
 *
 * Every error is one line naming the flag (or file:line) and what was
 * expected, e.g. "--size: expected WIDTHxHEIGHT such as 1280x720, got '0x5'".
 *
 * A luz_options owns its strings and cube arrays, and scene.objects
 * points into its own `cubes`: initialise it with luz_options_init(), release
 * it with luz_options_free(), and do not copy the struct by value (the copy's
 * scene.objects would point into the original).
 */
#ifndef LUZ_OPTIONS_H
#define LUZ_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "luz/error.h"
#include "luz/renderer.h"
#include "lab/scene.h"
#include "io/input_files.h"
#include "io/model.h"
#include "io/textures.h"

/* Where an object of the user's own came from: its `texture NAME` field is
 * kept as a name until the textures are loaded (luz_options_resolve_textures),
 * a model's file as a path until the models are (luz_options_load_models),
 * and its line for the error message if either fails. */
typedef struct luz_object_source {
    char *texture_name;   /* owned; NULL: SCENE.md's image i mod N (a cube)
                             or the materials' textures (a model) */
    char *model_path;     /* owned; NULL for a cube, else the model file,
                             absolute (a scene file's relative FILE joined
                             to the file's directory) */
    int line;             /* line in scene_path, 0 if not from a file */
} luz_object_source;

/* The upper bound of --frames and --bench: it bounds the memory that timing
 * a benchmark takes, and no sequence needs more. */
#define LUZ_MAX_FRAMES 1000000

/* The most pixels --mark rings in one image. */
#define LUZ_MAX_MARKS 8

/* --frame-range's B when the range runs to the last frame (A: or no range). */
#define LUZ_FRAME_RANGE_OPEN (-1)

typedef struct luz_options {
    luz_scene scene;            /* objects points into `objects` below */
    int width, height;          /* default 1280 x 720 */
    int thread_count;           /* LUZ_THREADS_AUTO unless --threads */
    char *textures_directory;   /* NULL: luz_default_textures_directory();
                                   "none": every texel white */
    char *output_path;          /* -o; NULL until luz_options_finish() sets
                                   the default, luz.png (luz_%04d.png for
                                   more than one frame) */
    char *scene_path;           /* the last scene file read (--scene) */
    int frame_count;            /* --frames, default 1 */
    double frames_per_second;   /* --fps, default 30 */
    int range_first;            /* --frame-range A:B: A, default 0 */
    int range_last;             /* B, or LUZ_FRAME_RANGE_OPEN (the default):
                                   to the last frame */
    int shard_index;            /* --shard K/M: K */
    int shard_count;            /* M; 0 (the default): no --shard */
    bool skip_existing;         /* --skip-existing: leave frames whose file
                                   exists */
    int bench_frames;           /* --bench N, 0 when not benchmarking */
    int model_memory_mib;       /* --model-memory MiB, 0: the limit that grows
                                   with each model file (io/model_sandbox.h) */
    unsigned only_terms;        /* --only: bit (1u << luz_term) per light term
                                   kept; 0 keeps them all */
    bool reference;             /* --reference: the plain scalar fragment stage */
    bool paused;                /* --paused yes: the viewer starts paused (T) */
    bool legend;                /* --legend: the view's legend in the image */
    int mark_count;             /* --mark: pixels ringed in the image */
    int marks[LUZ_MAX_MARKS][2];    /* x, y of each */
    bool up_given;              /* --up AXIS: the up axis of --model's model */
    luz_up_axis up;
    bool bug_given;             /* --bug NAME (not none): scene.bug */
    bool bug_help;              /* --bug help: list the bugs and exit */
    bool quiz;                  /* --quiz SEED: scene.bug chosen from quiz_seed
                                   (app/quiz.h), hidden */
    uint32_t quiz_seed;
    bool answer_given;          /* --answer NAME: is the quiz's bug `answer`? */
    luz_bug answer;
    bool probe;                 /* --probe X,Y: explain pixel (probe_x, probe_y) */
    int probe_x, probe_y;       /* column and row, row 0 on top */
    char *diagnose_path;        /* --diagnose FRAME.png: a student's frame to
                                   weigh against the setting (app/diagnose.h);
                                   -o then names the residual picture */
    bool size_given;            /* --size (or a scene file's size) was set:
                                   else --diagnose takes the frame's size */
    bool help;
    bool version;
    luz_object *objects;        /* the user's own cubes and models (owned), as
                                   many as scene.object_count */
    luz_object_source *object_sources;  /* one per object (owned) */
    int object_capacity;
    luz_model_files model_files;   /* --model-files: where a model's
                                      texture files may be (folder) */
    luz_input_files inputs;     /* every file read: the scene files, and once
                                   loaded the textures, the models and the
                                   textures they name (owned); no output may
                                   replace one (luz_options_check_outputs) */
} luz_options;

/* ---- options.c: the option table, one option at a time ---------------------
 * The bottom of the four files behind this header: it calls none of the
 * others and knows nothing of files. */

/* The renderer the options ask for: --threads and --reference. --threads 0
 * means the caller's thread, as 1 does, where a renderer desc's 0 means
 * one thread per CPU. */
luz_renderer_desc luz_options_renderer_desc(const luz_options *options);

/* The defaults of every option. */
void luz_options_init(luz_options *options);
void luz_options_free(luz_options *options);

/* Sets one option from its text, as the command line and scene files do:
 * every option but scene, whose file luz_options_set reads (setting it
 * here is an error). name is a long option without its dashes ("size",
 * "camera-pos"; "o" is -o); value is NULL for the flags help, version and
 * reference. Error messages start with `where` ("--size" on the command
 * line, "scene.luz:3: size" in a file); NULL means "--NAME". Returns 0, or
 * -1 with a message. */
int luz_options_set_value(luz_options *options, const char *name, const char *value,
                          const char *where, luz_error *error);

/* True for the names a scene file may set with `name = value`: every long
 * option that takes a value, except scene. (`cube` lines are the scene
 * file's own.) */
bool luz_options_is_scene_key(const char *name);

/* Whether and when luz_options_write_scene saves an option: a column of
 * the option table, so that the writer follows the table rather than a
 * list of its own that could forget a key. */
typedef enum luz_option_saving {
    LUZ_OPTION_NOT_SAVED,         /* the flags, scene, only (its effect is in
                                     the strengths) and a run's settings */
    LUZ_OPTION_SAVED,             /* whenever it has a value (textures: once
                                     set) */
    LUZ_OPTION_SAVED_IF_CHANGED,  /* only when it is not the default */
} luz_option_saving;

/* One row of the option table, as the rest of the app sees it. */
typedef struct luz_option_info {
    const char *name;          /* the long option without its dashes */
    const char *syntax;        /* the value's form ("WxH"), for messages;
                                  NULL for a flag */
    bool is_flag;              /* takes no value: help, version, reference */
    luz_option_saving saving;
    double min, max;           /* a number's range, ends included (each
                                  number of x,y,z or r,g,b,a); +-INFINITY:
                                  any finite value; 0, 0 for the rest */
} luz_option_info;

/* Row `index` of the option table, in --help's order, into *info. Returns
 * false past the last row. */
bool luz_options_row(size_t index, luz_option_info *info);

/* The row named by the first `length` characters of name ("o" is output),
 * into *info. Returns false if there is none. */
bool luz_options_find(const char *name, size_t length, luz_option_info *info);

/* Writes the current value of option `name` in the text form that
 * luz_options_set() reads back exactly: each number the shortest decimal
 * that reads back to the same bits (option_text.h). Returns 0, or -1 for
 * a flag, an unknown name, a value left at "unset" (textures, output,
 * only, bench) or a buffer too small. */
int luz_options_format(const luz_options *options, const char *name,
                       char *buffer, size_t size);

/* The output in force (SCENE.md, "Output"): exposure and tone map as the
 * user set them, the rest the default of a scene with or without models
 * (lab/scene.h), the models counted by the files the objects name. What
 * --print-state shows and the viewer starts with. */
luz_output luz_options_output(const luz_options *options);

/* What must wait until every option is known, called by luz_options_parse()
 * and by anyone who sets options one by one or reads a scene file directly:
 * applies --only (the strengths of the other terms become 0), checks the
 * spot's inner angle against its outer one, sets the default output path
 * (none with --probe: a probe writes a PNG only when -o asks), checks the
 * -o pattern, checks --frame-range against --frames, refuses
 * --skip-existing with -o -, and checks that --probe names a pixel of the
 * image in a run of one frame. Returns 0, or -1 with a message. */
int luz_options_finish(luz_options *options, luz_error *error);

/* Drops the custom cubes: the scene goes back to SCENE.md's tiling of
 * scene.cube_count cubes. */
void luz_options_clear_objects(luz_options *options);

/* Appends an object to the user's list (a copy of *object, with copies of
 * texture_name and model_path, either NULL; line for messages). Errors
 * start with `where`. Returns 0, or -1 with a message. */
int luz_options_add_object(luz_options *options, const luz_object *object,
                           const char *texture_name, const char *model_path, int line,
                           const char *where, luz_error *error);

/* ---- option_outputs.c: the files a run will write (uses options.c) ---------- */

/* Checks every file this run will write before anything is rendered:
 * each frame that luz_options_frames_to_render gives, named by the -o
 * pattern (none for -o - or --bench). Only a regular file may be at its
 * path, to be replaced (luz_new_file_check_target: not a device, a FIFO, a
 * socket, a directory or a symbolic link), and it may not be one of
 * options->inputs, by name or by device and inode: call it once the
 * textures and models are loaded. For -o -, standard output may not be
 * one of the inputs (by device and inode). Each folder above it that exists
 * must be a folder (luz_new_file_folders), and the name must end in .png.
 * Returns 0, or -1 with a message that starts "-o: " ("-o -: " for
 * standard output). */
int luz_options_check_outputs(const luz_options *options, luz_error *error);

/* Makes the missing folders of every file luz_options_check_outputs
 * checked, as `mkdir -p` does (Blender's habit: `-o frames/f_%04d.png`
 * works on a fresh clone). Call it after that check and before the first
 * frame. Returns 0, or -1 with "-o: PATH: cannot create the folder ...". */
int luz_options_make_output_folders(const luz_options *options, luz_error *error);

/* ---- models (option_models.c) ---- */

/* The model files the options name, each read once, and the lab's view of
 * each; the objects point into views. */
typedef struct luz_model_set {
    luz_model *models;
    luz_lab_model *views;
    int count;
} luz_model_set;

/* Reads every model file the objects name into an empty set and points
 * each model object at its view; their textures are charged to *budget
 * (the run's, shared with the cube textures; NULL: one of their own). A
 * file that takes more than a second to read is announced on stderr when
 * that is a terminal. A model's warnings (a texture it names that is
 * missing or corrupt: drawn with T = 1) are printed on stderr, one line
 * each, "luz: warning: ...", once per run. Returns 0, or LUZ_BAD_INPUT (-1) or
 * LUZ_MACHINE_FAILED (io/input_file.h) with a message naming the file (and
 * FILE:LINE of the scene file's model line). */
int luz_options_load_models(luz_options *options, luz_model_set *set,
                            luz_texture_budget *budget, luz_error *error);
void luz_model_set_free(luz_model_set *set);

/* path as an absolute path: as it is if it is one, else joined to
 * base_directory (a scene file's directory; NULL or "" for the working
 * directory), itself joined to the working directory if relative. Returns
 * 0, or -1 if it does not fit in buffer. */
int luz_options_model_path(const char *base_directory, const char *path, char *buffer,
                           size_t size, luz_error *error);

/* The file that frame frame_index goes to: output_path with its %d
 * conversion (if any) replaced by the index and %% by %. Returns 0, or -1 if
 * the pattern is malformed or the name does not fit in buffer. */
int luz_options_output_path(const luz_options *options, int frame_index,
                            char *buffer, size_t size, luz_error *error);

/* Whether -o is `-`: the PNGs go to standard output, one after another. */
bool luz_options_output_is_stdout(const luz_options *options);

/* Share shard_index of shard_count contiguous shares of `count` frames
 * starting at `first` (0 <= shard_index < shard_count): with
 * q = count / shard_count and r = count % shard_count, shares 0 to r - 1
 * get q + 1 frames and the others q, in order. Sets *shard_first and
 * *shard_frames; *shard_frames is 0 for an empty share (more shares than
 * frames), and *shard_first is then where it would start. */
void luz_shard_frames(int first, int count, int shard_index, int shard_count,
                      int *shard_first, int *shard_frames);

/* The frames a run renders, after luz_options_finish(): --frame-range's
 * (all of --frames without it), then --shard's share of those. Sets *first
 * and *count (0: nothing to render). */
void luz_options_frames_to_render(const luz_options *options, int *first, int *count);

/* The usage text of the scene options, for --help: every option, its value
 * and its default. */
void luz_options_print_help(FILE *out);

/* Where textures are found when --textures is not given: $LUZ_TEXTURES if
 * set and not empty; else the source tree's textures/ for a program run from
 * inside the build directory; else the installed ones. Writes into buffer and
 * returns it. */
const char *luz_default_textures_directory(char *buffer, size_t size);

/* ---- scene_file.c: scene files, read and written (uses options.c) ---------- */

/* Reads a scene file into options (luz_options_parse() does it for --scene)
 * and records its path in scene_path. Its `cube` lines replace the cube
 * list. Does not call luz_options_finish(). Returns 0, or -1 with a message
 * that starts with FILE:LINE. */
int luz_options_read_scene_file(luz_options *options, const char *path, luz_error *error);

/* The same for the text of a scene file in memory (length bytes, NUL bytes
 * and all), which messages and scene_path call `name`; for the scene
 * fuzzer (tests/fuzz/fuzz_scene.c). A relative model FILE is taken from
 * name's directory, as from a file's. */
int luz_options_read_scene_text(luz_options *options, const char *text, size_t length,
                                const char *name, luz_error *error);

/* Writes the scene part of options in the scene-file format, so that what
 * the viewer shows can be rendered again with luz-render --scene; reading
 * the file back gives the same options. The keys written are the option
 * table's saved rows (luz_options_row): first those saved whenever they
 * have a value, then those saved only when changed (view, interp), each
 * group in the table's order; then the custom cubes' lines, which replace
 * `cubes`. Not written: only, and a run's settings (threads, output,
 * frames, fps, bench). */
void luz_options_write_scene(const luz_options *options, FILE *out);

/* The same text as a file at path, complete or absent (written to a
 * temporary name first). replace false: an existing file is never
 * replaced; LUZ_FILE_EXISTS is returned instead, as the viewer's F2 needs
 * to number its files safely. Returns 0, LUZ_FILE_EXISTS or -1 with a
 * message naming path. */
int luz_options_save_scene(const luz_options *options, const char *path, bool replace,
                           luz_error *error);

/* ---- command_line.c: argv, --scene files included (uses both above) -------- */

/* Parses argv (argv[0] is the program name) and, with --scene, the file:
 * first every argument's shape is checked, then the scene file is read, then
 * the other arguments are applied over it, then luz_options_finish() runs.
 * Accepts `--name value` and `--name=value`. Returns 0, or -1 with a
 * one-line message. */
int luz_options_parse(luz_options *options, int argc, char **argv, luz_error *error);

/* Sets one option from its text, as the command line does: "scene" reads
 * that scene file (luz_options_read_scene_file), any other name goes to
 * luz_options_set_value, with the same arguments and messages. Returns 0,
 * or -1 with a message. */
int luz_options_set(luz_options *options, const char *name, const char *value,
                    const char *where, luz_error *error);

/* ---- option_textures.c: the textures the options name (uses options.c) ---- */

/* Turns the custom cubes' texture names into indices of the loaded set.
 * Returns 0, or -1 naming FILE:LINE of a cube whose texture is not in it. */
int luz_options_resolve_textures(luz_options *options, const luz_texture_set *textures,
                                 luz_error *error);

/* Loads the textures the options name (--textures, else $LUZ_TEXTURES,
 * else luz_default_textures_directory()) into an empty set, "none" leaving
 * it empty (every texel white), charging them to *budget (the run's; NULL:
 * one of their own), then resolves the custom cubes' texture names
 * (luz_options_resolve_textures). Both programs start this way. Returns 0,
 * or LUZ_BAD_INPUT (-1) or LUZ_MACHINE_FAILED (io/input_file.h) with a
 * message that says where the directory came from. */
int luz_options_load_textures(luz_options *options, luz_texture_set *textures,
                              luz_texture_budget *budget, luz_error *error);

#endif
