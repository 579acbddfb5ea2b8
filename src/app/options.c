/*
 * options.c: the options of luz-render and the viewer, one table.
 *
 * Every option is a row of `option_table` below: its name, what kind of
 * value it takes, where that value lives in luz_options, the range it must
 * lie in, whether (and when) a saved scene file keeps it, and its --help
 * line. Parsing (command_line.c, through luz_options_find), setting and
 * checking a value, --help, and the scene-file reader and writer
 * (scene_file.c, through luz_options_set_value, luz_options_row and
 * luz_options_format) all read that one table, so an option cannot be
 * accepted in one place and forgotten in another.
 *
 * The rules the table enforces come from SCENE.md (pitch within [-89, 89],
 * spot angles within [0, 89], strengths in [0, 1], ...) and from the
 * renderer's limits (luz_framebuffer_check_size, LUZ_MAX_CUBES,
 * LUZ_MAX_THREADS). A value is either accepted whole or refused with one
 * line that names the flag and what was expected: no partial numbers
 * ("12abc"), no NaN or infinity, nothing after the last number.
 *
 * The bottom of the option files: it calls none of the others
 * (scene_file.c, command_line.c, option_textures.c); they call it. It
 * reads no file: its only I/O is --help's text and the look-up of the
 * default textures directory, and --scene is command_line.c's to read.
 */
#include "app/options.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "luz/framebuffer.h"
#include "luz/renderer.h"
#include "luz/view.h"
#include "app/option_text.h"
#include "app/quiz.h"
#include "io/platform.h"

#if !defined(LUZ_SOURCE_TEXTURES) || !defined(LUZ_INSTALLED_TEXTURES) || !defined(LUZ_BUILD_ROOT)
#error "src/meson.build passes LUZ_SOURCE_TEXTURES, LUZ_INSTALLED_TEXTURES and LUZ_BUILD_ROOT"
#endif

/* ---- the table of options ------------------------------------------------ */

typedef enum option_kind {
    OPTION_FLAG,      /* --help, --version: no value */
    OPTION_SIZE,      /* WIDTHxHEIGHT, checked by luz_framebuffer_check_size */
    OPTION_DOUBLE,    /* one finite double within the row's range */
    OPTION_FLOAT,     /* one finite float within the row's range */
    OPTION_INTEGER,   /* one int within the row's range */
    OPTION_SEED,      /* a uint32 */
    OPTION_CUBES,     /* an int; also drops a scene file's own cubes */
    OPTION_THREADS,   /* "auto" or an int within the row's range */
    OPTION_VEC3,      /* x,y,z */
    OPTION_LIGHT,     /* r,g,b,a, each in [0, 1] */
    OPTION_FILTER,    /* nearest | bilinear | trilinear */
    OPTION_VIEW,      /* color | depth | normals | ... (luz/view.h) */
    OPTION_INTERP,    /* perspective | affine */
    OPTION_SAMPLES,   /* 1 | 4: samples a pixel */
    OPTION_EXPOSURE,  /* a float within the row's range: the scene's EV */
    OPTION_TONE_MAP,  /* clamp | neutral */
    OPTION_YES_NO,    /* yes | no, a bool */
    OPTION_MARKS,     /* X,Y[,X,Y...]: pixels to mark in the image */
    OPTION_ONLY,      /* a comma-separated list of light terms */
    OPTION_PATH,      /* a string the options own */
    OPTION_FRAME_RANGE, /* A:B, A: or :B, frame numbers from 0 */
    OPTION_SHARD,     /* K/M with 0 <= K < M */
    OPTION_SCENE,     /* a scene file, read at once */
    OPTION_MODEL,     /* a model file, the one object (command_line.c) */
    OPTION_UP,        /* y | z | x | -y | -z | -x: --model's up axis */
    OPTION_PROBE,     /* X,Y: a pixel, checked against --size at the end */
    OPTION_MODEL_FILES, /* folder | anywhere */
    OPTION_BUG,       /* a luz/bug.h name, or help */
    OPTION_QUIZ,      /* a uint32: the seed of a hidden bug (app/quiz.h) */
    OPTION_ANSWER,    /* a luz/bug.h name: the answer to --quiz */
} option_kind;

typedef struct option_spec {
    const char *name;          /* the long option without its dashes */
    option_kind kind;
    size_t offset;             /* of the value in luz_options */
    double min, max;           /* the accepted range of a number, ends
                                  included; of each number of a vector */
    bool in_scene_file;        /* may a scene file set it? */
    luz_option_saving saving;  /* does luz_options_write_scene save it, and
                                  when? (left out: never) */
    const char *syntax;        /* the value's form, for --help */
    const char *summary;       /* what it does, for --help */
    const char *default_text;  /* --help's default when it is not a value */
} option_spec;

#define FIELD(member) offsetof(luz_options, member)
#define UNBOUNDED .min = -INFINITY, .max = INFINITY

static const option_spec option_table[] = {
    {.name = "size", .kind = OPTION_SIZE,
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED,
     .syntax = "WxH", .summary = "image size in pixels"},
    {.name = "time", .kind = OPTION_DOUBLE, .offset = FIELD(scene.time_seconds),
     .min = -LUZ_SCENE_MAX_TIME, .max = LUZ_SCENE_MAX_TIME,
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "T",
     .summary = "scene time in seconds, -1e9 to 1e9: the cubes' angles and the lights' "
                "orbits"},
    {.name = "seed", .kind = OPTION_SEED, .min = 0, .max = UINT32_MAX,
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "N",
     .summary = "seed of the cube colours, 0 to 4294967295 (0 means 0x9E3779B9)"},
    /* not saved when there are custom cubes: the cube lines stand for it */
    {.name = "cubes", .kind = OPTION_CUBES, .offset = FIELD(scene.cube_count), .min = 1,
     .max = LUZ_MAX_CUBES, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "N",
     .summary = "number of cubes, 1 to 100000, the ten repeated in tiles (SCENE.md)"},
    {.name = "camera-pos", .kind = OPTION_VEC3, .offset = FIELD(scene.camera.position),
     .min = -LUZ_SCENE_MAX_COORDINATE, .max = LUZ_SCENE_MAX_COORDINATE,
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "x,y,z",
     .summary = "camera position, each from -10000 to 10000"},
    {.name = "camera-yaw", .kind = OPTION_FLOAT, .offset = FIELD(scene.camera.yaw_degrees),
     UNBOUNDED, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "D",
     .summary = "camera yaw in degrees, any finite number (-90 looks down -Z)"},
    {.name = "camera-pitch", .kind = OPTION_FLOAT, .offset = FIELD(scene.camera.pitch_degrees),
     .min = -89, .max = 89, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "D",
     .summary = "camera pitch in degrees, -89 to 89"},
    /* 0 and 180 degrees make the projection's cot(fov / 2) infinite or 0;
     * a degree either side of them still shows the scene. */
    {.name = "fov", .kind = OPTION_FLOAT, .offset = FIELD(scene.camera.fov_degrees), .min = 1,
     .max = 179, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "D",
     .summary = "vertical field of view in degrees, 1 to 179"},
    {.name = "ambient", .kind = OPTION_LIGHT, .min = 0, .max = 1, .offset = FIELD(scene.lights.ambient),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "r,g,b,a",
     .summary = "ambient light: colour and strength, each from 0 to 1"},
    {.name = "diffuse", .kind = OPTION_LIGHT, .min = 0, .max = 1, .offset = FIELD(scene.lights.diffuse),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "r,g,b,a",
     .summary = "diffuse headlight at the camera"},
    {.name = "specular", .kind = OPTION_LIGHT, .min = 0, .max = 1, .offset = FIELD(scene.lights.specular),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "r,g,b,a",
     .summary = "specular headlight at the camera"},
    /* pow(cos a, S) is 1/2 at a = sqrt(2 ln 2 / S) radians: beyond 100000
     * the highlight is under a fifth of a degree wide. */
    {.name = "shininess", .kind = OPTION_FLOAT, .offset = FIELD(scene.lights.shininess), .min = 0,
     .max = 100000, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "S",
     .summary = "specular exponent, 0 to 100000"},
    {.name = "point", .kind = OPTION_LIGHT, .min = 0, .max = 1, .offset = FIELD(scene.lights.point),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "r,g,b,a",
     .summary = "point light orbiting the origin (drawn as a small cube)"},
    {.name = "spot", .kind = OPTION_LIGHT, .min = 0, .max = 1, .offset = FIELD(scene.lights.spot),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "r,g,b,a",
     .summary = "spot light riding on the camera"},
    {.name = "spot-inner", .kind = OPTION_FLOAT, .offset = FIELD(scene.lights.spot_inner_degrees),
     .min = 0, .max = 89, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "D",
     .summary = "spot's full-intensity cone in degrees, 0 to 89, at most --spot-outer"},
    {.name = "spot-outer", .kind = OPTION_FLOAT, .offset = FIELD(scene.lights.spot_outer_degrees),
     .min = 0, .max = 89, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "D",
     .summary = "spot's cut-off cone in degrees, 0 to 89"},
    /* The near plane is 0.1 away: a shorter reach would light nothing
     * that can be seen. */
    {.name = "spot-reach", .kind = OPTION_FLOAT, .offset = FIELD(scene.lights.spot_reach),
     .min = 0.1, .max = 10000, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "R",
     .summary = "distance at which the spot fades out, 0.1 to 10000"},
    {.name = "directional", .kind = OPTION_LIGHT, .min = 0, .max = 1, .offset = FIELD(scene.lights.directional),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "r,g,b,a",
     .summary = "directional light (the sun)"},
    /* not saved: its effect is already in the strengths it set to 0 */
    {.name = "only", .kind = OPTION_ONLY, .in_scene_file = true, .syntax = "TERM[,TERM...]",
     .summary = "keep only these lights, the others' strength set to 0; terms: ambient "
                "diffuse specular point spot directional",
     .default_text = "all six"},
    {.name = "filter", .kind = OPTION_FILTER,
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED,
     .syntax = "nearest|bilinear|trilinear", .summary = "texture filter"},
    /* Always saved: the viewer's default may differ from luz-render's. */
    {.name = "samples", .kind = OPTION_SAMPLES, .offset = FIELD(scene.samples),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "1|4",
     .summary = "samples a pixel: 1 (at its centre) or 4 (anti-aliased: SCENE.md's 4x "
                "pattern, each pixel's samples averaged)",
     .default_text = "1"},
    /* The output of lit colours (SCENE.md, "Output"), saved and shown as
     * in force: the user's, else the default of a scene with or without
     * models (luz_options_output). 2^10 takes a colour of 1/1000 to 1,
     * and 2^-10 a thousand to 1. */
    {.name = "exposure", .kind = OPTION_EXPOSURE, .offset = FIELD(scene.exposure), .min = -10,
     .max = 10, .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "EV",
     .summary = "exposure in stops, -10 to 10: each lit colour (cubes and models, not the "
                "point light's marker nor the background) is multiplied by 2^EV",
     .default_text = "0; -1 with a model"},
    {.name = "tonemap", .kind = OPTION_TONE_MAP, .in_scene_file = true,
     .saving = LUZ_OPTION_SAVED, .syntax = "clamp|neutral",
     .summary = "how a lit colour becomes bytes: clamp to [0, 1] (the report's), or the "
                "Khronos PBR Neutral tone map first, which keeps a light model's shading",
     .default_text = "clamp; neutral with a model"},
    /* The teaching settings, saved when changed: a view saved while looking
     * at the depth buffer renders the depth buffer. */
    {.name = "view", .kind = OPTION_VIEW,
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED_IF_CHANGED, .syntax = "NAME",
     .summary = "what the image shows: color, or a picture of a pipeline stage: depth, "
                "normals, uv, mip, overdraw, bands, triangles (docs/pipeline.md)"},
    {.name = "interp", .kind = OPTION_INTERP,
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED_IF_CHANGED,
     .syntax = "perspective|affine",
     .summary = "interpolation of texture coordinates and the other varyings: "
                "perspective-correct, or affine in screen space (textures swim)"},
    /* A bug is a teaching setting like the view; a quiz's is saved as
     * the quiz, never by its name. */
    {.name = "bug", .kind = OPTION_BUG, .in_scene_file = true,
     .saving = LUZ_OPTION_SAVED_IF_CHANGED, .syntax = "NAME|help",
     .summary = "draw with one classic mistake put in, in the shading or the pipeline "
                "(the probe's numbers follow it); help lists them (docs/teaching.md)",
     .default_text = "none"},
    {.name = "quiz", .kind = OPTION_QUIZ, .in_scene_file = true, .saving = LUZ_OPTION_SAVED,
     .syntax = "SEED",
     .summary = "draw with one of the bugs, chosen from SEED (0 to 4294967295) and not named "
                "anywhere (the probe says 'hidden'); find it, then check with --answer",
     .default_text = "off"},
    {.name = "answer", .kind = OPTION_ANSWER, .syntax = "NAME",
     .summary = "with --quiz SEED: say whether the quiz's bug is NAME (exit 0) or not "
                "(exit 1), and what it was, without drawing",
     .default_text = "off"},
    /* The viewer's pause (T), saved when on, so that a view saved while
     * paused opens paused. luz-render's pictures are stills at `time`
     * anyway, and its --frames animate whatever this says. */
    {.name = "paused", .kind = OPTION_YES_NO, .offset = FIELD(paused),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED_IF_CHANGED, .syntax = "yes|no",
     .summary = "the viewer starts with the animation paused (its T key); luz-render "
                "ignores it: its images are at --time, and --frames animate"},
    /* saved once set (luz_options_format has nothing to write before) */
    {.name = "textures", .kind = OPTION_PATH, .offset = FIELD(textures_directory),
     .in_scene_file = true, .saving = LUZ_OPTION_SAVED, .syntax = "DIR|none",
     .summary = "directory of cube images (.png .jpg .jpeg .bmp .tga); none: all white",
     .default_text = "$LUZ_TEXTURES, else the built-in textures"},
    /* The settings of a run, which a file may give but the writer leaves
     * out: a saved view is a scene, not a render job. */
    {.name = "threads", .kind = OPTION_THREADS, .offset = FIELD(thread_count), .min = 0,
     .max = LUZ_MAX_THREADS, .in_scene_file = true, .syntax = "N|auto",
     .summary = "rendering threads, 0 to 256 (0 and 1: the calling thread only)"},
    {.name = "output", .kind = OPTION_PATH, .offset = FIELD(output_path), .in_scene_file = true,
     .syntax = "FILE.png",
.summary = "output PNG; with --frames a pattern such as out_%04d.png; - writes the PNGs "
                "to standard output, one after another; replaces only a regular file, and "
                "none the run reads",
     .default_text = "luz.png; luz_%04d.png for frames"},
    {.name = "frames", .kind = OPTION_INTEGER, .offset = FIELD(frame_count), .min = 1,
     .max = LUZ_MAX_FRAMES, .in_scene_file = true, .syntax = "N",
     .summary = "render N frames, frame k at time T + k / fps, into the -o pattern"},
    /* Frame k's time T + k / fps stays finite, and within 1e9 seconds of
     * T for every k below LUZ_MAX_FRAMES. */
    {.name = "fps", .kind = OPTION_DOUBLE, .offset = FIELD(frames_per_second), .min = 0.001,
     .max = 1000000, .in_scene_file = true, .syntax = "F",
     .summary = "frames per second of --frames and --bench, 0.001 to 1000000"},
    /* Which frames of the sequence this run renders, and whether it
     * renders those already written: a job's slice of the sequence, given
     * by the scheduler to each task, so not in scene files. */
    {.name = "frame-range", .kind = OPTION_FRAME_RANGE, .syntax = "A:B",
     .summary = "render only frames A to B of --frames (from 0, both included), with the "
                "names and bytes the whole run gives them; A: and :B leave an end open",
     .default_text = "all"},
    {.name = "shard", .kind = OPTION_SHARD, .min = 1, .max = LUZ_MAX_FRAMES, .syntax = "K/M",
     .summary = "render the K-th of M contiguous shares of the frames (of --frame-range, "
                "else all), 0 <= K < M <= 1000000; the first N mod M shares get one frame "
                "more; a share may be empty",
     .default_text = "off"},
    {.name = "skip-existing", .kind = OPTION_FLAG, .offset = FIELD(skip_existing),
     .summary = "do not render a frame whose output file exists (resumes a sequence)",
     .default_text = "off"},
    {.name = "bench", .kind = OPTION_INTEGER, .offset = FIELD(bench_frames), .min = 1,
     .max = LUZ_MAX_FRAMES, .in_scene_file = true, .syntax = "N",
     .summary = "time N frames, write no file, print one line of key=value results",
     .default_text = "off"},
    /* What luz-render draws over the image: for the pages that explain
     * the pipeline. A run's setting, not part of a scene. */
    {.name = "legend", .kind = OPTION_FLAG, .offset = FIELD(legend),
     .summary = "draw the --view's legend into the image, bottom left: a swatch for "
                "each colour the view uses and what it means (nothing for color)",
     .default_text = "off"},
    {.name = "mark", .kind = OPTION_MARKS, .syntax = "X,Y[,X,Y...]",
     .summary = "draw a ring around each of these pixels (column X, row Y from the top "
                "left, at most 8), leaving the pixel itself as rendered",
     .default_text = "none"},
    {.name = "reference", .kind = OPTION_FLAG, .offset = FIELD(reference),
     .summary = "shade with the plain scalar fragment stage (src/renderer/fragment.c) "
                "instead of the SIMD one; the images agree",
     .default_text = "off"},
    /* A question about one run, not part of a scene. */
    {.name = "probe", .kind = OPTION_PROBE, .syntax = "X,Y",
     .summary = "explain pixel X,Y (row 0 on top): its depth tests, the winning triangle "
                "and its corners in clip space and on the screen, its varyings, texel, six "
                "light terms and bytes; luz-render prints them on "
                "stdout, one key=value a line, and writes a PNG only with -o; the viewer "
                "opens its probe panel on the pixel",
     .default_text = "off"},
    {.name = "diagnose", .kind = OPTION_PATH, .offset = FIELD(diagnose_path),
     .syntax = "FRAME.png",
     .summary = "weigh a frame of one's own (a WebGL canvas saved as PNG) against this "
                "setting's six single-term images: one weight per light term, the residual, "
                "the silhouettes and the worst pixels; -o names the residual picture "
                "(default FRAME-residual.png); exit 0 when every term is right, 1 when one "
                "is not, 2 for a file that cannot be compared",
     .default_text = "off"},
    {.name = "model", .kind = OPTION_MODEL, .syntax = "FILE",
     .summary = "draw this model (OBJ, glTF, PLY, STL, FBX, ... read with assimp) instead of "
                "the cubes, at the origin, turning as cube 0; a scene file places models with "
                "model lines",
     .default_text = "none: the cubes"},
    /* A model line's `up` in a scene file; on the command line, for the
     * one model --model names (luz_options_finish). */
    {.name = "up", .kind = OPTION_UP, .syntax = "y|z|x|-y|-z|-x",
     .summary = "with --model: which of the model's own axes points up, turned to +Y before "
                "it is centred and scaled (SCENE.md, Up axis); CAD and STL files are often z",
     .default_text = "y"},
    /* A trust decision of the run's, which a saved view does not keep: a
     * file shared with others says nothing of where their images are. */
    {.name = "model-files", .kind = OPTION_MODEL_FILES, .in_scene_file = true,
     .syntax = "folder|anywhere",
     .summary = "where the texture files a model names may be: folder, in the model file's "
                "folder (a name that is absolute, or leads out through .. or a symbolic link, "
                "is drawn as a missing texture, with a warning); anywhere, wherever the names "
                "lead",
     .default_text = "folder"},
    /* A run's setting: what this machine can spare, not part of a view. */
    {.name = "model-memory", .kind = OPTION_INTEGER, .offset = FIELD(model_memory_mib),
     .min = 64, .max = 1048576, .in_scene_file = true, .syntax = "MiB",
     .summary = "address space assimp may take to read each model, 64 to 1048576 MiB, in "
                "place of the limit that grows with the file; raises it for a file refused "
                "as over its memory limit",
     .default_text = "1024 MiB + 128 bytes a byte of the file"},
    {.name = "scene", .kind = OPTION_SCENE, .syntax = "FILE",
     .summary = "read options and cubes from a scene file (the command line wins)",
     .default_text = "none"},
    {.name = "help", .kind = OPTION_FLAG, .offset = FIELD(help),
     .summary = "print this help and exit"},
    {.name = "version", .kind = OPTION_FLAG, .offset = FIELD(version),
     .summary = "print the version and exit"},
};

#define OPTION_COUNT (sizeof option_table / sizeof option_table[0])

/* Finds a row by the first `length` characters of name; "o" is -o. */
static const option_spec *find_option(const char *name, size_t length)
{
    if (length == 1 && name[0] == 'o')
        return find_option("output", 6);
    for (size_t i = 0; i < OPTION_COUNT; i++) {
        if (strlen(option_table[i].name) == length &&
            memcmp(option_table[i].name, name, length) == 0)
            return &option_table[i];
    }
    return NULL;
}

static luz_option_info option_info(const option_spec *spec)
{
    return (luz_option_info){.name = spec->name,
                             .syntax = spec->syntax,
                             .is_flag = spec->kind == OPTION_FLAG,
                             .saving = spec->saving,
                             .min = spec->min,
                             .max = spec->max};
}

bool luz_options_row(size_t index, luz_option_info *info)
{
    if (index >= OPTION_COUNT)
        return false;
    *info = option_info(&option_table[index]);
    return true;
}

bool luz_options_find(const char *name, size_t length, luz_option_info *info)
{
    const option_spec *spec = find_option(name, length);
    if (spec == NULL)
        return false;
    *info = option_info(spec);
    return true;
}

static void *option_field(luz_options *options, const option_spec *spec)
{
    return (char *)options + spec->offset;
}

static const void *option_field_const(const luz_options *options, const option_spec *spec)
{
    return (const char *)options + spec->offset;
}

/* ---- reading numbers ------------------------------------------------------- */

/* Reads a decimal integer at *cursor (blanks before it allowed) and moves
 * the cursor past it. Values beyond long long saturate, so that "1e30"-sized
 * digits are reported as out of range rather than malformed. */
static bool read_integer_prefix(const char **cursor, long long *value)
{
    const char *start = option_skip_blanks(*cursor);
    const char *digits = start;
    if (*digits == '+' || *digits == '-')
        digits++;
    if (!isdigit((unsigned char)*digits))
        return false;
    char *end;
    errno = 0;
    *value = strtoll(start, &end, 10);
    *cursor = end;
    return true;
}

/* A whole text that is one integer in [min, max]. */
static bool read_integer(const char *text, long long min, long long max, long long *value)
{
    const char *cursor = text;
    if (!read_integer_prefix(&cursor, value))
        return false;
    if (errno == ERANGE || *option_skip_blanks(cursor) != '\0')
        return false;
    return *value >= min && *value <= max;
}

/* Whether a number lies in the row's range. A float option's number is
 * judged as the float it becomes, the value that is kept and that a saved
 * scene file writes back: "0.001" is below the double 0.001f, yet it is
 * that float. */
static bool in_range(const option_spec *spec, double value)
{
    if (spec->kind == OPTION_FLOAT || spec->kind == OPTION_EXPOSURE ||
        spec->kind == OPTION_VEC3 || spec->kind == OPTION_LIGHT)
        value = (float)value;   /* option_read_numbers kept it within a float's range */
    return value >= spec->min && value <= spec->max;
}

/* "a number in [1, 179]", or "a number" for an unbounded row, for
 * messages. */
static void describe_range(const option_spec *spec, char *buffer, size_t size)
{
    if (isfinite(spec->min) && isfinite(spec->max))
        snprintf(buffer, size, "a number in [%.10g, %.10g]", spec->min, spec->max);
    else
        snprintf(buffer, size, "a number");
}

/* ---- setting one option ------------------------------------------------------ */

static int set_size(luz_options *options, const char *value, const char *where, luz_error *error)
{
    const char *cursor = value;
    long long width, height;
    bool well_formed = read_integer_prefix(&cursor, &width);
    if (well_formed) {
        cursor = option_skip_blanks(cursor);
        well_formed = *cursor == 'x' || *cursor == 'X';
    }
    if (well_formed) {
        cursor++;
        well_formed = read_integer_prefix(&cursor, &height) && *option_skip_blanks(cursor) == '\0';
    }
    if (!well_formed)
        return luz_error_set(error, "%s: expected WIDTHxHEIGHT such as 1280x720, got '%s'", where,
                             option_quote(value).text);
    if (width < 1 || height < 1)
        return luz_error_set(error, "%s: expected a width and height of at least 1, got '%s'",
                             where, option_quote(value).text);
    /* The check works on ints; anything beyond INT_MAX is too large anyway,
     * and is refused here without allocating anything. */
    if (luz_framebuffer_check_size(width > INT_MAX ? INT_MAX : (int)width,
                                   height > INT_MAX ? INT_MAX : (int)height, NULL) != 0)
        return luz_error_set(error,
                             "%s: expected a size the renderer supports (at most %d a side and "
                             "%d pixels in all, such as 8192x8192), got '%s'",
                             where, LUZ_MAX_DIMENSION, LUZ_MAX_PIXELS, option_quote(value).text);
    options->width = (int)width;
    options->height = (int)height;
    return 0;
}

static int set_number(luz_options *options, const option_spec *spec, const char *value,
                      const char *where, luz_error *error)
{
    double number;
    char range[64];
    describe_range(spec, range, sizeof range);
    const bool is_float = spec->kind == OPTION_FLOAT || spec->kind == OPTION_EXPOSURE;
    switch (option_read_numbers(value, &number, 1, is_float)) {
    case OPTION_PARSE_MALFORMED:
        return luz_error_set(error, "%s: expected %s, got '%s'", where, range,
                             option_quote(value).text);
    case OPTION_PARSE_NOT_FINITE:
        return luz_error_set(error, "%s: expected a finite number, got '%s'", where,
                             option_quote(value).text);
    case OPTION_PARSE_OK:
        break;
    }
    if (!in_range(spec, number))
        return luz_error_set(error, "%s: expected %s, got '%s'", where, range,
                             option_quote(value).text);
    if (is_float)
        *(float *)option_field(options, spec) = (float)number;
    else
        *(double *)option_field(options, spec) = number;
    return 0;
}

static int set_integer(luz_options *options, const option_spec *spec, const char *value,
                       const char *where, luz_error *error)
{
    long long number;
    if (spec->kind == OPTION_THREADS && strcmp(value, "auto") == 0) {
        options->thread_count = LUZ_THREADS_AUTO;
        return 0;
    }
    if (!read_integer(value, (long long)spec->min, (long long)spec->max, &number))
        return luz_error_set(error, "%s: expected %san integer from %lld to %lld, got '%s'", where,
                             spec->kind == OPTION_THREADS ? "auto or " : "",
                             (long long)spec->min, (long long)spec->max, option_quote(value).text);
    switch (spec->kind) {
    case OPTION_SEED:
        options->scene.seed = (uint32_t)number;
        break;
    case OPTION_CUBES:
        /* A count replaces any cube list a scene file gave: the command line
         * overrides the file. */
        luz_options_clear_objects(options);
        options->scene.cube_count = (int)number;
        break;
    default:
        *(int *)option_field(options, spec) = (int)number;
        break;
    }
    return 0;
}

static int set_vector(luz_options *options, const option_spec *spec, const char *value,
                      const char *where, luz_error *error)
{
    double numbers[4];
    bool light = spec->kind == OPTION_LIGHT;
    char expected[96];
    snprintf(expected, sizeof expected, "%s (%s numbers, each in [%.10g, %.10g])",
             light ? "r,g,b,a" : "x,y,z", light ? "four" : "three", spec->min, spec->max);
    switch (option_read_numbers(value, numbers, light ? 4 : 3, true)) {
    case OPTION_PARSE_MALFORMED:
        return luz_error_set(error, "%s: expected %s, got '%s'", where, expected,
                             option_quote(value).text);
    case OPTION_PARSE_NOT_FINITE:
        return luz_error_set(error, "%s: expected finite numbers, got '%s'", where,
                             option_quote(value).text);
    case OPTION_PARSE_OK:
        break;
    }
    for (int i = 0; i < (light ? 4 : 3); i++) {
        if (!in_range(spec, numbers[i]))
            return luz_error_set(error, "%s: expected %s, got '%s'", where, expected,
                                 option_quote(value).text);
    }
    luz_vec3 vector = luz_vec3_make((float)numbers[0], (float)numbers[1], (float)numbers[2]);
    if (light)
        *(luz_light *)option_field(options, spec) =
            (luz_light){.colour = vector, .strength = (float)numbers[3]};
    else
        *(luz_vec3 *)option_field(options, spec) = vector;
    return 0;
}

static int set_view(luz_options *options, const char *value, const char *where,
                    luz_error *error)
{
    if (luz_view_from_name(value, &options->scene.view))
        return 0;
    return luz_error_set(error,
                         "%s: expected color, depth, normals, uv, mip, overdraw, bands or "
                         "triangles, got '%s'",
                         where, option_quote(value).text);
}

static int set_interpolation(luz_options *options, const char *value, const char *where,
                             luz_error *error)
{
    static const luz_interpolation modes[] = {LUZ_INTERPOLATION_PERSPECTIVE,
                                              LUZ_INTERPOLATION_AFFINE};
    for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++) {
        if (strcmp(value, luz_interpolation_name(modes[i])) == 0) {
            options->scene.interpolation = modes[i];
            return 0;
        }
    }
    return luz_error_set(error, "%s: expected perspective or affine, got '%s'", where,
                         option_quote(value).text);
}

static int set_samples(luz_options *options, const char *value, const char *where,
                       luz_error *error)
{
    if (strcmp(value, "1") == 0 || strcmp(value, "4") == 0) {
        options->scene.samples = value[0] - '0';
        return 0;
    }
    return luz_error_set(error, "%s: expected 1 or 4 (samples a pixel), got '%s'", where,
                         option_quote(value).text);
}

static int set_tone_map(luz_options *options, const char *value, const char *where,
                        luz_error *error)
{
    for (int i = 0; i < LUZ_TONE_MAP_COUNT; i++) {
        if (strcmp(value, luz_tone_map_name((luz_tone_map)i)) == 0) {
            options->scene.tone_map = (luz_tone_map)i;
            options->scene.has_tone_map = true;
            return 0;
        }
    }
    return luz_error_set(error, "%s: expected clamp or neutral, got '%s'", where,
                         option_quote(value).text);
}

static int set_model_files(luz_options *options, const char *value, const char *where,
                           luz_error *error)
{
    if (strcmp(value, "folder") == 0 || strcmp(value, "anywhere") == 0) {
        options->model_files =
            value[0] == 'f' ? LUZ_MODEL_FILES_FOLDER : LUZ_MODEL_FILES_ANYWHERE;
        return 0;
    }
    return luz_error_set(error, "%s: expected folder or anywhere, got '%s'", where,
                         option_quote(value).text);
}

static int set_yes_no(luz_options *options, const option_spec *spec, const char *value,
                      const char *where, luz_error *error)
{
    bool *field = option_field(options, spec);
    if (strcmp(value, "yes") == 0 || strcmp(value, "no") == 0) {
        *field = value[0] == 'y';
        return 0;
    }
    return luz_error_set(error, "%s: expected yes or no, got '%s'", where,
                         option_quote(value).text);
}

static int set_filter(luz_options *options, const char *value, const char *where,
                      luz_error *error)
{
    static const luz_filter filters[] = {LUZ_FILTER_NEAREST, LUZ_FILTER_BILINEAR,
                                         LUZ_FILTER_TRILINEAR};
    for (size_t i = 0; i < sizeof filters / sizeof filters[0]; i++) {
        if (strcmp(value, luz_filter_name(filters[i])) == 0) {
            options->scene.filter = filters[i];
            return 0;
        }
    }
    return luz_error_set(error, "%s: expected nearest, bilinear or trilinear, got '%s'", where,
                         option_quote(value).text);
}

/* --only: terms separated by commas, blanks allowed around each. The
 * strengths are only zeroed in luz_options_finish(), once every light
 * option is known, so that `--only spot` means the same before or after
 * `--ambient ...`. */
static int set_only(luz_options *options, const char *value, const char *where,
                    luz_error *error)
{
    unsigned terms = 0;
    const char *cursor = value;
    for (;;) {
        cursor = option_skip_blanks(cursor);
        size_t length = strcspn(cursor, ", \t");
        int found = -1;
        for (int term = 0; term < LUZ_TERM_COUNT && length > 0; term++) {
            const char *name = luz_term_name((luz_term)term);
            if (strlen(name) == length && memcmp(name, cursor, length) == 0)
                found = term;
        }
        if (found < 0)
            break;
        terms |= 1u << found;
        cursor = option_skip_blanks(cursor + length);
        if (*cursor == '\0') {
            options->only_terms = terms;
            return 0;
        }
        if (*cursor != ',')
            break;
        cursor++;
    }
    return luz_error_set(error,
                         "%s: expected light terms separated by commas (ambient, diffuse, "
                         "specular, point, spot, directional), got '%s'",
                         where, option_quote(value).text);
}

/* Splits value at its first separator into the text before it (copied into
 * first, which holds size bytes) and the text after it (*second): false
 * when there is no separator or the first part does not fit. */
static bool split_pair(const char *value, char separator, char *first, size_t size,
                       const char **second)
{
    const char *at = strchr(value, separator);
    if (at == NULL || (size_t)(at - value) >= size) return false;
    memcpy(first, value, (size_t)(at - value));
    first[at - value] = '\0';
    *second = at + 1;
    return true;
}

/* --frame-range A:B, A: or :B (or :, every frame). Whether the frames
 * exist is luz_options_finish()'s question, once --frames is known. */
static int set_frame_range(luz_options *options, const char *value, const char *where,
                           luz_error *error)
{
    char text[64];
    const char *after;
    long long first = 0, last = LUZ_FRAME_RANGE_OPEN;
    bool well_formed = split_pair(value, ':', text, sizeof text, &after);
    /* A: and :B, with blanks allowed around each number */
    if (well_formed && *option_skip_blanks(text) != '\0')
        well_formed = read_integer(text, 0, LUZ_MAX_FRAMES - 1, &first);
    if (well_formed && *option_skip_blanks(after) != '\0')
        well_formed = read_integer(after, 0, LUZ_MAX_FRAMES - 1, &last);
    if (!well_formed)
        return luz_error_set(error,
                             "%s: expected A:B, A: or :B, frame numbers from 0 (such as 0:99), "
                             "got '%s'",
                             where, option_quote(value).text);
    options->range_first = (int)first;
    options->range_last = (int)last;
    return 0;
}

/* --shard K/M. */
static int set_shard(luz_options *options, const option_spec *spec, const char *value,
                     const char *where, luz_error *error)
{
    char first[64];
    const char *second;
    long long index = -1, count = 0;
    /* M first: it bounds K. */
    const bool well_formed =
        split_pair(value, '/', first, sizeof first, &second) &&
        read_integer(second, (long long)spec->min, (long long)spec->max, &count) &&
        read_integer(first, 0, count - 1, &index);
    if (!well_formed)
        return luz_error_set(error,
                             "%s: expected K/M, share K of M with 0 <= K < M <= %lld "
                             "(such as 0/4), got '%s'",
                             where, (long long)spec->max, option_quote(value).text);
    options->shard_index = (int)index;
    options->shard_count = (int)count;
    return 0;
}

/* --mark X,Y[,X,Y...]: pairs of pixel coordinates. Whether they lie in
 * the image is luz_options_finish()'s question, once --size is known. */
static int set_marks(luz_options *options, const char *value, const char *where,
                     luz_error *error)
{
    int marks[LUZ_MAX_MARKS][2];
    int count = 0, coordinate = 0;
    const char *cursor = value;
    bool well_formed = true;
    for (;;) {
        long long number;
        if (!read_integer_prefix(&cursor, &number) || errno == ERANGE || number < 0 ||
            number >= LUZ_MAX_DIMENSION || count == LUZ_MAX_MARKS) {
            well_formed = false;
            break;
        }
        marks[count][coordinate] = (int)number;
        if (coordinate == 1)
            count++;
        coordinate ^= 1;
        cursor = option_skip_blanks(cursor);
        if (*cursor == '\0')
            break;
        if (*cursor != ',') {
            well_formed = false;
            break;
        }
        cursor++;
    }
    if (!well_formed || coordinate != 0)
        return luz_error_set(error,
                             "%s: expected X,Y pixel pairs (at most %d, such as 700,450 or "
                             "10,20,30,40), got '%s'",
                             where, LUZ_MAX_MARKS, option_quote(value).text);
    memcpy(options->marks, marks, sizeof marks);
    options->mark_count = count;
    return 0;
}

/* --probe X,Y. Whether the pixel is in the image is luz_options_finish()'s
 * question, once --size is known. */
static int set_probe(luz_options *options, const char *value, const char *where,
                     luz_error *error)
{
    char first[64];
    const char *second;
    long long x = -1, y = -1;
    const bool well_formed = split_pair(value, ',', first, sizeof first, &second) &&
                             read_integer(first, 0, LUZ_MAX_DIMENSION - 1, &x) &&
                             read_integer(second, 0, LUZ_MAX_DIMENSION - 1, &y);
    if (!well_formed)
        return luz_error_set(error,
                             "%s: expected X,Y, a pixel's column and row counted from 0 at the "
                             "top left (such as 700,450), got '%s'",
                             where, option_quote(value).text);
    options->probe = true;
    options->probe_x = (int)x;
    options->probe_y = (int)y;
    return 0;
}

static int set_path(luz_options *options, const option_spec *spec, const char *value,
                    const char *where, luz_error *error)
{
    /* A longer path cannot be opened (ENAMETOOLONG), and this bound is
     * what keeps a saved scene file's lines within the reader's. */
    if (strlen(value) > PATH_MAX - 1)
        return luz_error_set(error, "%s: expected a path of at most %d bytes, got %zu bytes",
                             where, PATH_MAX - 1, strlen(value));
    char *copy = strdup(value);
    if (copy == NULL)
        return luz_error_set(error, "%s: out of memory", where);
    char **field = option_field(options, spec);
    free(*field);
    *field = copy;
    return 0;
}

int luz_options_set_value(luz_options *options, const char *name, const char *value,
                          const char *where, luz_error *error)
{
    const option_spec *spec = find_option(name, strlen(name));
    char default_where[32];
    if (spec == NULL)
        return luz_error_set(error, "%s: unknown option '%s'", where ? where : "options",
                             option_quote(name).text);
    if (where == NULL) {
        snprintf(default_where, sizeof default_where, "--%s", spec->name);
        where = default_where;
    }
    if (spec->kind == OPTION_FLAG) {
        if (value != NULL)
            return luz_error_set(error, "%s: takes no value, got '%s'", where,
                                 option_quote(value).text);
        *(bool *)option_field(options, spec) = true;
        return 0;
    }
    if (value == NULL || value[0] == '\0')
        return luz_error_set(error, "%s: missing value (expected %s)", where, spec->syntax);

    switch (spec->kind) {
    case OPTION_SIZE:
        if (set_size(options, value, where, error) != 0) return -1;
        options->size_given = true;
        return 0;
    case OPTION_DOUBLE:
    case OPTION_FLOAT:
        return set_number(options, spec, value, where, error);
    case OPTION_INTEGER:
    case OPTION_SEED:
    case OPTION_CUBES:
    case OPTION_THREADS:
        return set_integer(options, spec, value, where, error);
    case OPTION_VEC3:
    case OPTION_LIGHT:
        return set_vector(options, spec, value, where, error);
    case OPTION_FILTER:
        return set_filter(options, value, where, error);
    case OPTION_VIEW:
        return set_view(options, value, where, error);
    case OPTION_INTERP:
        return set_interpolation(options, value, where, error);
    case OPTION_SAMPLES:
        return set_samples(options, value, where, error);
    case OPTION_EXPOSURE:
        if (set_number(options, spec, value, where, error) != 0) return -1;
        options->scene.has_exposure = true;
        return 0;
    case OPTION_TONE_MAP:
        return set_tone_map(options, value, where, error);
    case OPTION_YES_NO:
        return set_yes_no(options, spec, value, where, error);
    case OPTION_MODEL_FILES:
        return set_model_files(options, value, where, error);
    case OPTION_MARKS:
        return set_marks(options, value, where, error);
    case OPTION_ONLY:
        return set_only(options, value, where, error);
    case OPTION_PATH:
        return set_path(options, spec, value, where, error);
    case OPTION_FRAME_RANGE:
        return set_frame_range(options, value, where, error);
    case OPTION_SHARD:
        return set_shard(options, spec, value, where, error);
    case OPTION_PROBE:
        return set_probe(options, value, where, error);
    case OPTION_BUG:
        if (strcmp(value, "help") == 0) {
            options->bug_help = true;
            return 0;
        }
        if (!luz_bug_from_name(value, &options->scene.bug))
            return luz_error_set(error, "%s: expected a bug's name (--bug help lists them), "
                                        "got '%s'", where, option_quote(value).text);
        options->bug_given = options->scene.bug != LUZ_BUG_NONE;
        return 0;
    case OPTION_QUIZ: {
        long long seed;
        if (!read_integer(value, 0, UINT32_MAX, &seed))
            return luz_error_set(error, "%s: expected an integer from 0 to %lu, got '%s'",
                                 where, (unsigned long)UINT32_MAX, option_quote(value).text);
        options->quiz_seed = (uint32_t)seed;
        options->quiz = true;
        return 0;
    }
    case OPTION_ANSWER:
        if (!luz_bug_from_name(value, &options->answer))
            return luz_error_set(error, "%s: expected a bug's name (--bug help lists them), "
                                        "got '%s'", where, option_quote(value).text);
        options->answer_given = true;
        return 0;
    case OPTION_UP:
        if (!luz_up_axis_from_name(value, &options->up))
            return luz_error_set(error, "%s: expected y, z, x, -y, -z or -x, got '%s'", where,
                                 option_quote(value).text);
        options->up_given = true;
        return 0;
    case OPTION_SCENE:
    case OPTION_MODEL:
        /* Files are not this file's business: luz_options_set
         * (command_line.c) reads a scene file with scene_file.c, and takes
         * a model's path to its absolute form. */
        return luz_error_set(error, "%s: a file option is set by luz_options_set, not here",
                             where);
    case OPTION_FLAG:
        break;
    }
    return luz_error_set(error, "%s: unknown option", where);
}

bool luz_options_is_scene_key(const char *name)
{
    const option_spec *spec = find_option(name, strlen(name));
    /* "o" is a short flag, not a key: files use `output`. */
    return spec != NULL && spec->in_scene_file && strcmp(name, "o") != 0;
}

/* ---- formatting a value back ------------------------------------------------- */

/* Whether the options name a model: their objects' files, known before
 * the models are read (objects[i].model is set only then). */
static bool options_name_a_model(const luz_options *options)
{
    for (int i = 0; i < options->scene.object_count; i++)
        if (options->object_sources[i].model_path != NULL) return true;
    return false;
}

luz_output luz_options_output(const luz_options *options)
{
    return luz_scene_output_for(&options->scene, options_name_a_model(options));
}


int luz_options_format(const luz_options *options, const char *name, char *buffer,
                       size_t size)
{
    const option_spec *spec = find_option(name, strlen(name));
    if (spec == NULL || size == 0)
        return -1;
    const void *field = option_field_const(options, spec);
    char number[4][32];
    int written = -1;
    /* Numbers are written with the fewest digits that read back to the same
     * bits (option_text.h), so that a written scene file renders the same
     * picture and still reads well: 0.2, not 0.200000003. */
    switch (spec->kind) {
    case OPTION_SIZE:
        written = snprintf(buffer, size, "%dx%d", options->width, options->height);
        break;
    case OPTION_DOUBLE:
        option_format_double(number[0], sizeof number[0], *(const double *)field);
        written = snprintf(buffer, size, "%s", number[0]);
        break;
    case OPTION_FLOAT:
        option_format_float(number[0], sizeof number[0], *(const float *)field);
        written = snprintf(buffer, size, "%s", number[0]);
        break;
    case OPTION_SEED:
        written = snprintf(buffer, size, "%lu", (unsigned long)options->scene.seed);
        break;
    case OPTION_INTEGER:
        if (spec->offset == FIELD(bench_frames) && options->bench_frames == 0)
            return -1;
        written = snprintf(buffer, size, "%d", *(const int *)field);
        break;
    case OPTION_CUBES:
        written = snprintf(buffer, size, "%d", options->scene.cube_count);
        break;
    case OPTION_THREADS:
        written = options->thread_count == LUZ_THREADS_AUTO
                      ? snprintf(buffer, size, "auto")
                      : snprintf(buffer, size, "%d", options->thread_count);
        break;
    case OPTION_VEC3: {
        const luz_vec3 *vector = field;
        option_format_float(number[0], sizeof number[0], vector->x);
        option_format_float(number[1], sizeof number[1], vector->y);
        option_format_float(number[2], sizeof number[2], vector->z);
        written = snprintf(buffer, size, "%s, %s, %s", number[0], number[1], number[2]);
        break;
    }
    case OPTION_LIGHT: {
        const luz_light *light = field;
        option_format_float(number[0], sizeof number[0], light->colour.x);
        option_format_float(number[1], sizeof number[1], light->colour.y);
        option_format_float(number[2], sizeof number[2], light->colour.z);
        option_format_float(number[3], sizeof number[3], light->strength);
        written = snprintf(buffer, size, "%s, %s, %s, %s", number[0], number[1], number[2],
                           number[3]);
        break;
    }
    case OPTION_FILTER:
        written = snprintf(buffer, size, "%s", luz_filter_name(options->scene.filter));
        break;
    case OPTION_VIEW:
        written = snprintf(buffer, size, "%s", luz_view_name(options->scene.view));
        break;
    case OPTION_INTERP:
        written = snprintf(buffer, size, "%s",
                           luz_interpolation_name(options->scene.interpolation));
        break;
    case OPTION_SAMPLES:
        written = snprintf(buffer, size, "%d", options->scene.samples);
        break;
    case OPTION_YES_NO:
        written = snprintf(buffer, size, "%s", *(const bool *)field ? "yes" : "no");
        break;
    case OPTION_EXPOSURE:
        option_format_float(number[0], sizeof number[0], luz_options_output(options).exposure);
        written = snprintf(buffer, size, "%s", number[0]);
        break;
    case OPTION_TONE_MAP:
        written = snprintf(buffer, size, "%s",
                           luz_tone_map_name(luz_options_output(options).tone_map));
        break;
    case OPTION_MODEL_FILES:
        written = snprintf(buffer, size, "%s",
                           options->model_files == LUZ_MODEL_FILES_FOLDER ? "folder"
                                                                          : "anywhere");
        break;
    case OPTION_BUG:
        /* A quiz's bug is not told: the quiz line stands for it. */
        if (options->quiz) return -1;
        written = snprintf(buffer, size, "%s", luz_bug_name(options->scene.bug));
        break;
    case OPTION_QUIZ:
        if (!options->quiz) return -1;
        written = snprintf(buffer, size, "%lu", (unsigned long)options->quiz_seed);
        break;
    case OPTION_ANSWER:
        if (!options->answer_given) return -1;
        written = snprintf(buffer, size, "%s", luz_bug_name(options->answer));
        break;
    case OPTION_MARKS: {
        if (options->mark_count == 0)
            return -1;
        written = 0;
        buffer[0] = '\0';
        for (int i = 0; i < options->mark_count; i++) {
            size_t used = strlen(buffer);
            int n = snprintf(buffer + used, size - used, "%s%d,%d", used ? "," : "",
                             options->marks[i][0], options->marks[i][1]);
            if (n < 0 || (size_t)n >= size - used)
                return -1;
            written = (int)(used + (size_t)n);
        }
        break;
    }
    case OPTION_ONLY: {
        if (options->only_terms == 0)
            return -1;
        written = 0;
        buffer[0] = '\0';
        for (int term = 0; term < LUZ_TERM_COUNT; term++) {
            if (!(options->only_terms & (1u << term)))
                continue;
            size_t used = strlen(buffer);
            written = snprintf(buffer + used, size - used, "%s%s", used ? "," : "",
                               luz_term_name((luz_term)term));
            if (written < 0 || (size_t)written >= size - used)
                return -1;
            written = (int)(used + (size_t)written);
        }
        break;
    }
    case OPTION_PATH: {
        const char *path = *(char *const *)field;
        if (path == NULL)
            return -1;
        written = snprintf(buffer, size, "%s", path);
        break;
    }
    case OPTION_FRAME_RANGE: {
        if (options->range_first == 0 && options->range_last == LUZ_FRAME_RANGE_OPEN)
            return -1;
        char last[16] = "";
        if (options->range_last != LUZ_FRAME_RANGE_OPEN)
            snprintf(last, sizeof last, "%d", options->range_last);
        written = snprintf(buffer, size, "%d:%s", options->range_first, last);
        break;
    }
    case OPTION_SHARD:
        if (options->shard_count == 0)
            return -1;
        written = snprintf(buffer, size, "%d/%d", options->shard_index, options->shard_count);
        break;
    case OPTION_PROBE:
        if (!options->probe)
            return -1;
        written = snprintf(buffer, size, "%d,%d", options->probe_x, options->probe_y);
        break;
    case OPTION_UP:
        if (!options->up_given)
            return -1;
        written = snprintf(buffer, size, "%s", luz_up_axis_name(options->up));
        break;
    case OPTION_FLAG:
    case OPTION_SCENE:
    case OPTION_MODEL:
        return -1;
    }
    return (written >= 0 && (size_t)written < size) ? 0 : -1;
}

/* ---- defaults, freeing, finishing ----------------------------------------------- */

luz_renderer_desc luz_options_renderer_desc(const luz_options *options)
{
    return (luz_renderer_desc){
        .thread_count = options->thread_count == 0 ? 1 : options->thread_count,
        .reference = options->reference,
    };
}

void luz_options_init(luz_options *options)
{
    *options = (luz_options){
        .scene = luz_scene_defaults(),
        .width = 1280,
        .height = 720,
        .thread_count = LUZ_THREADS_AUTO,
        .frame_count = 1,
        .frames_per_second = 30.0,
        .range_last = LUZ_FRAME_RANGE_OPEN,
    };
}

int luz_options_add_object(luz_options *options, const luz_object *object,
                           const char *texture_name, const char *model_path, int line,
                           const char *where, luz_error *error)
{
    int count = options->scene.object_count;
    if (count >= LUZ_MAX_CUBES)
        return luz_error_set(error, "%s: too many objects (at most %d)", where, LUZ_MAX_CUBES);
    if (count == options->object_capacity) {
        int capacity = count ? count * 2 : 16;
        luz_object *objects = realloc(options->objects, (size_t)capacity * sizeof *objects);
        if (objects == NULL) return luz_error_set(error, "%s: out of memory", where);
        options->objects = objects;
        if (count > 0) options->scene.objects = objects;   /* never left dangling */
        luz_object_source *sources =
            realloc(options->object_sources, (size_t)capacity * sizeof *sources);
        if (sources == NULL) return luz_error_set(error, "%s: out of memory", where);
        options->object_sources = sources;
        options->object_capacity = capacity;
    }
    char *name = NULL, *path = NULL;
    if ((texture_name != NULL && (name = strdup(texture_name)) == NULL) ||
        (model_path != NULL && (path = strdup(model_path)) == NULL)) {
        free(name);
        return luz_error_set(error, "%s: out of memory", where);
    }
    options->objects[count] = *object;
    options->object_sources[count] =
        (luz_object_source){.texture_name = name, .model_path = path, .line = line};
    options->scene.objects = options->objects;
    options->scene.object_count = count + 1;
    return 0;
}

void luz_options_clear_objects(luz_options *options)
{
    for (int i = 0; i < options->scene.object_count; i++) {
        free(options->object_sources[i].texture_name);
        free(options->object_sources[i].model_path);
    }
    free(options->objects);
    free(options->object_sources);
    options->objects = NULL;
    options->object_sources = NULL;
    options->object_capacity = 0;
    options->scene.objects = NULL;
    options->scene.object_count = 0;
}

void luz_options_free(luz_options *options)
{
    luz_options_clear_objects(options);
    free(options->textures_directory);
    free(options->output_path);
    free(options->scene_path);
    free(options->diagnose_path);
    luz_input_files_free(&options->inputs);
    options->textures_directory = NULL;
    options->output_path = NULL;
    options->scene_path = NULL;
    options->diagnose_path = NULL;
}

/* An -o pattern: at most one conversion, %d with an optional 0 flag and a
 * width of 1 to 32 (%d, %4d, %04d), and %% for a percent sign. A name
 * without a conversion is a plain file name. */
typedef struct output_pattern {
    int conversions;
    size_t conversion_start;   /* the '%' of the conversion */
    size_t conversion_end;     /* just after its 'd' */
    bool zero_padded;
    int width;                 /* 0: none */
} output_pattern;

static bool scan_output_pattern(const char *path, output_pattern *pattern)
{
    *pattern = (output_pattern){0};
    for (size_t i = 0; path[i] != '\0'; i++) {
        if (path[i] != '%')
            continue;
        size_t start = i++;
        if (path[i] == '%')
            continue;
        bool zero = path[i] == '0';
        if (zero)
            i++;
        int width = 0;
        if (path[i] >= '1' && path[i] <= '9') {
            while (isdigit((unsigned char)path[i]) && width <= 32)
                width = width * 10 + (path[i++] - '0');
            if (width > 32)
                return false;
        }
        if (path[i] != 'd')
            return false;
        pattern->conversions++;
        pattern->conversion_start = start;
        pattern->conversion_end = i + 1;
        pattern->zero_padded = zero;
        pattern->width = width;
    }
    return pattern->conversions <= 1;
}

int luz_options_output_path(const luz_options *options, int frame_index, char *buffer,
                            size_t size, luz_error *error)
{
    const char *path = options->output_path ? options->output_path : "luz.png";
    output_pattern pattern;
    if (!scan_output_pattern(path, &pattern))
        return luz_error_set(error,
                             "-o: expected a file name with at most one %%d conversion "
                             "(%%d, %%4d or %%04d; %%%% for a percent sign), got '%s'",
                             option_quote(path).text);
    size_t used = 0;
    for (size_t i = 0; path[i] != '\0'; i++) {
        char piece[48];
        if (pattern.conversions == 1 && i == pattern.conversion_start) {
            if (pattern.zero_padded)
                snprintf(piece, sizeof piece, "%0*d", pattern.width, frame_index);
            else
                snprintf(piece, sizeof piece, "%*d", pattern.width, frame_index);
            i = pattern.conversion_end - 1;
        } else {
            piece[0] = path[i];
            piece[1] = '\0';
            if (path[i] == '%')
                i++;   /* a %% outside the conversion */
        }
        size_t length = strlen(piece);
        if (used + length >= size)
            return luz_error_set(error, "-o: the file name '%s' is too long",
                                 option_quote(path).text);
        memcpy(buffer + used, piece, length);
        used += length;
    }
    buffer[used] = '\0';
    return 0;
}

bool luz_options_output_is_stdout(const luz_options *options)
{
    return options->output_path != NULL && strcmp(options->output_path, "-") == 0;
}

void luz_shard_frames(int first, int count, int shard_index, int shard_count,
                      int *shard_first, int *shard_frames)
{
    const int share = count / shard_count, remainder = count % shard_count;
    /* shares before this one: shard_index of them, the first `remainder`
     * of which have one frame more */
    *shard_first = first + shard_index * share +
                   (shard_index < remainder ? shard_index : remainder);
    *shard_frames = share + (shard_index < remainder ? 1 : 0);
}

void luz_options_frames_to_render(const luz_options *options, int *first, int *count)
{
    const int last = options->range_last == LUZ_FRAME_RANGE_OPEN ? options->frame_count - 1
                                                                 : options->range_last;
    *first = options->range_first;
    *count = last - options->range_first + 1;
    if (options->shard_count > 0)
        luz_shard_frames(*first, *count, options->shard_index, options->shard_count, first,
                         count);
}

int luz_options_finish(luz_options *options, luz_error *error)
{
    luz_lights *lights = &options->scene.lights;
    if (options->only_terms != 0) {
        for (int term = 0; term < LUZ_TERM_COUNT; term++) {
            if (!(options->only_terms & (1u << term)))
                luz_lights_term(lights, (luz_term)term)->strength = 0.0f;
        }
    }
    /* Checked here rather than in set_number: `--spot-inner 20 --spot-outer
     * 25` is valid although the inner angle exceeds the default outer one
     * until the second option is read. */
    if (lights->spot_inner_degrees > lights->spot_outer_degrees)
        return luz_error_set(error,
                             "--spot-inner: expected an angle no wider than --spot-outer (%.9g), "
                             "got %.9g",
                             (double)lights->spot_outer_degrees,
                             (double)lights->spot_inner_degrees);

    /* --up names the axis of the model --model gives, whatever the order:
     * that model alone, object 0, placed by no scene-file line. */
    if (options->up_given) {
        if (options->scene.object_count != 1 || options->object_sources[0].model_path == NULL ||
            options->object_sources[0].line != 0)
            return luz_error_set(error, "--up: expected --model FILE, whose up axis it names "
                                        "(a scene file's model lines take `up AXIS`)");
        options->objects[0].up = options->up;
    }

    /* A quiz draws a bug of its own (app/quiz.h), which no output names;
     * an answer is an answer to a quiz. */
    if (options->quiz && options->bug_given)
        return luz_error_set(error, "--quiz: expected no --bug with it (the quiz chooses the "
                                    "bug), got --bug %s", luz_bug_name(options->scene.bug));
    if (options->answer_given && !options->quiz)
        return luz_error_set(error, "--answer: expected --quiz SEED, the quiz it answers");
    if (options->quiz) {
        options->scene.bug = luz_quiz_bug(options->quiz_seed);
        options->scene.bug_hidden = true;
    }

    /* The marks are checked once --size is known, whatever the order. */
    for (int i = 0; i < options->mark_count; i++) {
        if (options->marks[i][0] >= options->width || options->marks[i][1] >= options->height)
            return luz_error_set(error,
                                 "--mark: expected pixels inside the %dx%d image (X below %d, "
                                 "Y below %d), got %d,%d",
                                 options->width, options->height, options->width,
                                 options->height, options->marks[i][0], options->marks[i][1]);
    }

    /* The range is checked once --frames is known, whatever the order. */
    const int last_frame = options->frame_count - 1;
    if (options->range_first > last_frame ||
        (options->range_last != LUZ_FRAME_RANGE_OPEN &&
         (options->range_last > last_frame || options->range_first > options->range_last))) {
        char range[40] = "";
        luz_options_format(options, "frame-range", range, sizeof range);
        return luz_error_set(error,
                             "--frame-range: expected A:B with 0 <= A <= B <= %d, frames of "
                             "--frames %d (A: and :B leave an end open), got '%s'",
                             last_frame, options->frame_count, range);
    }

    if (options->diagnose_path != NULL) {
        if (options->bug_given || options->quiz || options->answer_given)
            return luz_error_set(error, "--diagnose: expected the setting without --bug, --quiz "
                                        "or --answer (luz weighs the frame against its right "
                                        "images)");
        if (options->probe || options->bench_frames > 0 || options->frame_count > 1 ||
            options->shard_count > 0 || options->skip_existing || options->range_first != 0 ||
            options->range_last != LUZ_FRAME_RANGE_OPEN)
            return luz_error_set(error, "--diagnose: expected one frame to weigh, without "
                                        "--probe, --bench, --frames, --frame-range, --shard or "
                                        "--skip-existing");
        if (luz_options_output_is_stdout(options))
            return luz_error_set(error, "--diagnose: expected -o to name the residual picture's "
                                        "file, got -o -");
        if (options->output_path == NULL) {
            /* FRAME.png -> FRAME-residual.png, beside the frame */
            const char *path = options->diagnose_path;
            size_t stem = strlen(path);
            if (stem >= 4 && strcasecmp(path + stem - 4, ".png") == 0) stem -= 4;
            char *residual = malloc(stem + sizeof "-residual.png");
            if (residual == NULL)
                return luz_error_set(error, "--diagnose: out of memory");
            memcpy(residual, path, stem);
            memcpy(residual + stem, "-residual.png", sizeof "-residual.png");
            options->output_path = residual;
        }
    }

    if (options->probe) {
        if (options->probe_x >= options->width || options->probe_y >= options->height)
            return luz_error_set(error,
                                 "--probe: expected a pixel of the %dx%d image, X from 0 to %d "
                                 "and Y from 0 to %d, got '%d,%d'",
                                 options->width, options->height, options->width - 1,
                                 options->height - 1, options->probe_x, options->probe_y);
        if (options->bench_frames > 0)
            return luz_error_set(error, "--probe: expected one frame to explain, but --bench "
                                        "times %d", options->bench_frames);
        if (options->frame_count > 1)
            return luz_error_set(error, "--probe: expected one frame to explain (choose it "
                                        "with --time), got --frames %d", options->frame_count);
        if (options->shard_count > 0 || options->skip_existing ||
            options->range_first != 0 || options->range_last != LUZ_FRAME_RANGE_OPEN)
            return luz_error_set(error, "--probe: expected one frame to explain, without "
                                        "--frame-range, --shard or --skip-existing, which "
                                        "pick frames of a sequence");
        if (luz_options_output_is_stdout(options))
            return luz_error_set(error, "--probe: expected standard output for the probe's "
                                        "lines, but -o - writes the PNG there");
        /* A probe writes an image only when -o asks for one. */
        if (options->output_path == NULL)
            return 0;
    }
    if (options->output_path == NULL) {
        options->output_path = strdup(options->frame_count > 1 ? "luz_%04d.png" : "luz.png");
        if (options->output_path == NULL)
            return luz_error_set(error, "-o: out of memory");
    }
    output_pattern pattern;
    if (!scan_output_pattern(options->output_path, &pattern))
        return luz_error_set(error,
                             "-o: expected a file name with at most one %%d conversion "
                             "(%%d, %%4d or %%04d; %%%% for a percent sign), got '%s'",
                             option_quote(options->output_path).text);
    if (luz_options_output_is_stdout(options)) {
        if (options->skip_existing)
            return luz_error_set(error,
                                 "--skip-existing: expected output files to look for, but "
                                 "-o - writes to standard output");
        return 0;
    }
    if (options->frame_count > 1 && pattern.conversions == 0)
        return luz_error_set(error,
                             "-o: expected a pattern with a %%d conversion such as out_%%04d.png "
                             "for %d frames, got '%s'",
                             options->frame_count, option_quote(options->output_path).text);
    return 0;
}

/* ---- --help -------------------------------------------------------------------------- */

/* A blank that print_wrapped() does not break a line at. */
#define NON_BREAKING '\x01'

/* Prints words from `text`, wrapped before column 80 and indented to
 * `indent` on every line after the first; `column` is where the first
 * starts. */
static void print_wrapped(FILE *out, const char *text, int indent, int column)
{
    while (*text != '\0') {
        int length = (int)strcspn(text, " ");
        if (column > indent && column + 1 + length > 79) {
            fprintf(out, "\n%*s", indent, "");
            column = indent;
        } else if (column > indent) {
            fputc(' ', out);
            column++;
        }
        for (int i = 0; i < length; i++)
            fputc(text[i] == NON_BREAKING ? ' ' : text[i], out);
        column += length;
        text += length;
        text += strspn(text, " ");
    }
    fputc('\n', out);
}

void luz_options_print_help(FILE *out)
{
    enum { INDENT = 31 };
    luz_options defaults;
    luz_options_init(&defaults);
    for (size_t i = 0; i < OPTION_COUNT; i++) {
        const option_spec *spec = &option_table[i];
        char left[64], value[160], directory[4096], line[4096 + 512];
        int used = snprintf(left, sizeof left, "%s--%s",
                            strcmp(spec->name, "output") == 0 ? "-o, " : "", spec->name);
        if (spec->syntax != NULL && used > 0 && (size_t)used < sizeof left)
            snprintf(left + used, sizeof left - (size_t)used, " %s", spec->syntax);
        const char *default_text = spec->default_text;
        if (strcmp(spec->name, "textures") == 0)
            default_text = luz_default_textures_directory(directory, sizeof directory);
        else if (default_text == NULL &&
                 luz_options_format(&defaults, spec->name, value, sizeof value) == 0)
            default_text = value;
        if (default_text != NULL) {
            snprintf(line, sizeof line, "%s (default: %s)", spec->summary, default_text);
            /* the default stays on one line: its blanks become unbreakable */
            for (char *c = line + strlen(spec->summary) + 1; *c != '\0'; c++)
                if (*c == ' ')
                    *c = NON_BREAKING;
        } else {
            snprintf(line, sizeof line, "%s", spec->summary);
        }

        if (strlen(left) + 2 >= INDENT) {
            fprintf(out, "  %s\n%*s", left, INDENT, "");
        } else {
            fprintf(out, "  %-*s", INDENT - 2, left);
        }
        print_wrapped(out, line, INDENT, INDENT);
    }
    luz_options_free(&defaults);
}

/* ---- the default textures directory ------------------------------------------------ */

/* Is path inside directory (or the directory itself)? A plain prefix test
 * would take /build-old/luz-render for a file under /build. */
static bool path_is_under(const char *path, const char *directory)
{
    size_t length = strlen(directory);
    while (length > 1 && directory[length - 1] == '/')
        length--;
    return strncmp(path, directory, length) == 0 &&
           (path[length] == '/' || path[length] == '\0');
}

const char *luz_default_textures_directory(char *buffer, size_t size)
{
    const char *directory = getenv("LUZ_TEXTURES");
    if (directory == NULL || directory[0] == '\0') {
        /* A program run from the build tree should show the textures of the
         * tree it was built from, not whatever an older install left behind;
         * an installed program has no source tree to look at. */
        char executable[4096];
        directory = LUZ_INSTALLED_TEXTURES;
        if (luz_platform_executable_path(executable, sizeof executable) == 0 &&
            path_is_under(executable, LUZ_BUILD_ROOT))
            directory = LUZ_SOURCE_TEXTURES;
    }
    if (size > 0)
        snprintf(buffer, size, "%s", directory);
    return buffer;
}
