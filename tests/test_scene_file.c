/*
 * test_scene_file.c: the scene-file writer never writes what the reader
 * refuses (issue 13, item 4).
 *
 * A property over every key the writer saves, at the edges of what the
 * options take: each key's smallest and largest value and their
 * neighbours, zero, -0, the smallest float, a value that needs nine
 * digits, every name of an enum, the longest paths and texture names the
 * options hold with every byte that needs quoting, and cube and model
 * lines at the edges of theirs. For each, the options are set by hand, in
 * the struct (not through the parser, so that the values are the test's
 * own), written with luz_options_write_scene, read back with
 * luz_options_read_scene_file, and every saved setting is compared with
 * the values the test set: the expected values are the inputs, never the
 * writer's output.
 *
 * The ranges come from the option table (luz_options_row's min and max)
 * and the lab's limits (lab/scene.h), so that a range that changes is
 * followed; a key the writer saves that this file does not know fails the
 * test, so that a new key cannot be left out.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "luz/luz.h"
#include "app/options.h"
#include "lab/scene.h"

/* ---- the keys the test knows ------------------------------------------------------ */

typedef enum key_type {
    KEY_SIZE,
    KEY_DOUBLE,
    KEY_FLOAT,
    KEY_VEC3,
    KEY_LIGHT,
    KEY_SEED,
    KEY_CUBES,
    KEY_FILTER,
    KEY_VIEW,
    KEY_INTERP,
    KEY_SAMPLES,
    KEY_PATH,
    KEY_BOOL,
    KEY_EXPOSURE,   /* a float; compared as the output in force */
    KEY_TONE_MAP,
    KEY_BUG,        /* luz/bug.h's bug, and whether it is a quiz's */
    KEY_QUIZ,
} key_type;

typedef struct key_field {
    const char *name;
    key_type type;
    size_t offset;   /* of the field in luz_options */
} key_field;

#define AT(member) offsetof(luz_options, member)

/* Every key the writer saves, and where the test finds its value: written
 * out here by hand, from docs/cli.md, not taken from options.c. */
static const key_field key_fields[] = {
    {"size", KEY_SIZE, 0},
    {"time", KEY_DOUBLE, AT(scene.time_seconds)},
    {"seed", KEY_SEED, AT(scene.seed)},
    {"cubes", KEY_CUBES, AT(scene.cube_count)},
    {"camera-pos", KEY_VEC3, AT(scene.camera.position)},
    {"camera-yaw", KEY_FLOAT, AT(scene.camera.yaw_degrees)},
    {"camera-pitch", KEY_FLOAT, AT(scene.camera.pitch_degrees)},
    {"fov", KEY_FLOAT, AT(scene.camera.fov_degrees)},
    {"ambient", KEY_LIGHT, AT(scene.lights.ambient)},
    {"diffuse", KEY_LIGHT, AT(scene.lights.diffuse)},
    {"specular", KEY_LIGHT, AT(scene.lights.specular)},
    {"shininess", KEY_FLOAT, AT(scene.lights.shininess)},
    {"point", KEY_LIGHT, AT(scene.lights.point)},
    {"spot", KEY_LIGHT, AT(scene.lights.spot)},
    {"spot-inner", KEY_FLOAT, AT(scene.lights.spot_inner_degrees)},
    {"spot-outer", KEY_FLOAT, AT(scene.lights.spot_outer_degrees)},
    {"spot-reach", KEY_FLOAT, AT(scene.lights.spot_reach)},
    {"directional", KEY_LIGHT, AT(scene.lights.directional)},
    {"filter", KEY_FILTER, AT(scene.filter)},
    {"samples", KEY_SAMPLES, AT(scene.samples)},
    {"view", KEY_VIEW, AT(scene.view)},
    {"interp", KEY_INTERP, AT(scene.interpolation)},
    {"textures", KEY_PATH, AT(textures_directory)},
    {"paused", KEY_BOOL, AT(paused)},
    {"exposure", KEY_EXPOSURE, AT(scene.exposure)},
    {"tonemap", KEY_TONE_MAP, AT(scene.tone_map)},
    {"bug", KEY_BUG, AT(scene.bug)},
    {"quiz", KEY_QUIZ, AT(quiz_seed)},
};

#define KEY_COUNT (sizeof key_fields / sizeof key_fields[0])

static const key_field *find_key(const char *name)
{
    for (size_t i = 0; i < KEY_COUNT; i++)
        if (strcmp(key_fields[i].name, name) == 0)
            return &key_fields[i];
    return NULL;
}

static void *field_of(luz_options *options, const key_field *key)
{
    return (char *)options + key->offset;
}

/* ---- writing and reading back ------------------------------------------------------- */

/* A scene file in $TMPDIR, removed by the test that made it. */
static void temporary_path(char *path, size_t size)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(path, size, "%s/luz-scene-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    int descriptor = mkstemp(path);
    assert_true(descriptor >= 0);
    close(descriptor);
}

/* Writes options as a scene file and reads it back into *back (from the
 * defaults, as luz-render --scene does). Fails with the reader's message,
 * and the longest line, if it refuses what the writer wrote. */
static void write_and_read(const luz_options *options, luz_options *back)
{
    char path[512];
    temporary_path(path, sizeof path);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    luz_options_write_scene(options, file);
    assert_int_equal(fclose(file), 0);

    luz_options_init(back);
    luz_error error = {{0}};
    if (luz_options_read_scene_file(back, path, &error) != 0) {
        size_t longest = 0, length = 0;
        file = fopen(path, "r");
        for (int c; file != NULL && (c = getc(file)) != EOF;) {
            length = c == '\n' ? 0 : length + 1;
            longest = length > longest ? length : longest;
        }
        if (file != NULL)
            fclose(file);
        unlink(path);
        fail_msg("the reader refused what the writer wrote (longest line %zu): %.400s", longest,
                 error.message);
    }
    unlink(path);
}

/* ---- comparing ------------------------------------------------------------------------ */

/* Equal as numbers: 0 and -0 are the same setting (an object at -0 is
 * written with no `at`, and reads back at +0). */
static void assert_same_float(float expected, float actual, const char *what)
{
    if (!(expected == actual))
        fail_msg("%s: set %.9g, read back %.9g", what, (double)expected, (double)actual);
}

static void assert_same_key(const luz_options *set, const luz_options *back,
                            const key_field *key)
{
    const void *a = (const char *)set + key->offset, *b = (const char *)back + key->offset;
    char what[64];
    switch (key->type) {
    case KEY_SIZE:
        assert_int_equal(back->width, set->width);
        assert_int_equal(back->height, set->height);
        break;
    case KEY_DOUBLE:
        if (!(*(const double *)a == *(const double *)b))
            fail_msg("%s: set %.17g, read back %.17g", key->name, *(const double *)a,
                     *(const double *)b);
        break;
    case KEY_FLOAT:
        assert_same_float(*(const float *)a, *(const float *)b, key->name);
        break;
    case KEY_VEC3:
    case KEY_LIGHT: {
        const float *x = a, *y = b;   /* luz_vec3, then a light's strength */
        for (int i = 0; i < (key->type == KEY_LIGHT ? 4 : 3); i++) {
            snprintf(what, sizeof what, "%s[%d]", key->name, i);
            const float expected = i < 3 ? x[i] : ((const luz_light *)a)->strength;
            const float actual = i < 3 ? y[i] : ((const luz_light *)b)->strength;
            assert_same_float(expected, actual, what);
        }
        break;
    }
    case KEY_SEED:
        assert_int_equal(back->scene.seed, set->scene.seed);
        break;
    case KEY_CUBES:
        if (set->scene.object_count == 0)   /* object lines replace the count */
            assert_int_equal(back->scene.cube_count, set->scene.cube_count);
        break;
    case KEY_FILTER:
        assert_int_equal(back->scene.filter, set->scene.filter);
        break;
    case KEY_VIEW:
        assert_int_equal(back->scene.view, set->scene.view);
        break;
    case KEY_INTERP:
        assert_int_equal(back->scene.interpolation, set->scene.interpolation);
        break;
    case KEY_SAMPLES:
        assert_int_equal(back->scene.samples, set->scene.samples);
        break;
    case KEY_BOOL:
        assert_int_equal(*(const bool *)b, *(const bool *)a);
        break;
    /* What is in force, given or the default of a scene with or without
     * models, is what must come back. */
    case KEY_EXPOSURE:
        assert_same_float(luz_options_output(set).exposure, luz_options_output(back).exposure,
                          key->name);
        break;
    case KEY_TONE_MAP:
        assert_int_equal(luz_options_output(back).tone_map, luz_options_output(set).tone_map);
        break;
    /* A quiz is saved as its seed, its bug never by name: luz_options_finish
     * chooses it again (app/quiz.h). */
    case KEY_BUG:
        if (!set->quiz) assert_int_equal(back->scene.bug, set->scene.bug);
        break;
    case KEY_QUIZ:
        assert_int_equal(back->quiz, set->quiz);
        if (set->quiz) assert_int_equal(back->quiz_seed, set->quiz_seed);
        break;
    case KEY_PATH: {
        const char *expected = *(char *const *)a, *actual = *(char *const *)b;
        if (expected == NULL)
            assert_null(actual);
        else if (actual == NULL || strcmp(expected, actual) != 0)
            fail_msg("%s: set %zu bytes '%.40s...', read back '%.40s...'", key->name,
                     strlen(expected), expected, actual ? actual : "(none)");
        break;
    }
    }
}

static void assert_same_objects(const luz_options *set, const luz_options *back)
{
    assert_int_equal(back->scene.object_count, set->scene.object_count);
    for (int i = 0; i < set->scene.object_count; i++) {
        const luz_object *a = &set->objects[i], *b = &back->objects[i];
        const luz_object_source *sa = &set->object_sources[i], *sb = &back->object_sources[i];
        char what[64];
        snprintf(what, sizeof what, "object %d position", i);
        assert_same_float(a->position.x, b->position.x, what);
        assert_same_float(a->position.y, b->position.y, what);
        assert_same_float(a->position.z, b->position.z, what);
        assert_int_equal(b->has_colour, a->has_colour);
        if (a->has_colour) {
            snprintf(what, sizeof what, "object %d colour", i);
            assert_same_float(a->colour.x, b->colour.x, what);
            assert_same_float(a->colour.y, b->colour.y, what);
            assert_same_float(a->colour.z, b->colour.z, what);
        }
        assert_int_equal(sb->texture_name != NULL, sa->texture_name != NULL);
        if (sa->texture_name != NULL)
            assert_string_equal(sb->texture_name, sa->texture_name);
        assert_int_equal(sb->model_path != NULL, sa->model_path != NULL);
        if (sa->model_path != NULL) {
            assert_string_equal(sb->model_path, sa->model_path);
            snprintf(what, sizeof what, "object %d scale", i);
            assert_same_float(a->scale, b->scale, what);
            assert_int_equal(b->still, a->still);
            assert_int_equal(b->up, a->up);
        }
    }
}

/* Writes, reads back, compares every saved key and the objects. */
static void assert_round_trip(const luz_options *options)
{
    luz_options back;
    write_and_read(options, &back);
    for (size_t i = 0; i < KEY_COUNT; i++)
        assert_same_key(options, &back, &key_fields[i]);
    assert_same_objects(options, &back);
    luz_options_free(&back);
}

/* ---- the edges of a range -------------------------------------------------------------- */

/* The floats at the edges of [min, max] (the table's doubles) and some
 * awkward ones inside: the smallest float at or above min and its next,
 * the largest at or below max and its previous, 0 and -0, the smallest
 * subnormal float, 1/3 (nine digits) and 0.1 (not a binary fraction).
 * An unbounded end is a float's largest. Returns how many. */
static int float_edges(double min, double max, float *values)
{
    float low = isfinite(min) ? (float)min : -FLT_MAX;
    if ((double)low < min)
        low = nextafterf(low, INFINITY);
    float high = isfinite(max) ? (float)max : FLT_MAX;
    if ((double)high > max)
        high = nextafterf(high, -INFINITY);
    const float candidates[] = {low,  nextafterf(low, INFINITY), high, nextafterf(high, -INFINITY),
                                0.0f, -0.0f, FLT_TRUE_MIN, -FLT_TRUE_MIN, FLT_MIN,
                                1.0f / 3.0f, 0.1f, -1.0f / 3.0f};
    int count = 0;
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++)
        if (candidates[i] >= low && candidates[i] <= high)
            values[count++] = candidates[i];
    return count;
}

/* The same for a double. */
static int double_edges(double min, double max, double *values)
{
    const double low = isfinite(min) ? min : -DBL_MAX, high = isfinite(max) ? max : DBL_MAX;
    const double candidates[] = {low,  nextafter(low, INFINITY), high, nextafter(high, -INFINITY),
                                 0.0,  -0.0, DBL_TRUE_MIN, -DBL_TRUE_MIN, DBL_MIN,
                                 1.0 / 3.0, 0.1, -1.0 / 3.0};
    int count = 0;
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++)
        if (candidates[i] >= low && candidates[i] <= high)
            values[count++] = candidates[i];
    return count;
}

/* ---- texts that need quoting ----------------------------------------------------------- */

/* length bytes of every kind the writer must quote or escape: '#', '"',
 * '\', control characters (\n \t \r and the rest), DEL, UTF-8, blanks,
 * with a blank at both ends; starting with '/' when absolute. */
static char *awkward_text(size_t length, bool absolute)
{
    static const char pieces[] = "# \"\\\n\t\r\x01\x1f\x7f\xc3\xa9 a=b,c";
    char *text = malloc(length + 1);
    assert_non_null(text);
    for (size_t i = 0; i < length; i++)
        text[i] = pieces[i % (sizeof pieces - 1)];
    text[0] = absolute ? '/' : ' ';
    text[length - 1] = ' ';
    text[length] = '\0';
    return text;
}

/* length bytes that each take two in a quoted text (\" \\ \n \t \r),
 * but a leading '/' when absolute: the longest line for its length. */
static char *escaped_text(size_t length, bool absolute)
{
    static const char escaped[] = "\"\\\n\t\r";
    char *text = malloc(length + 1);
    assert_non_null(text);
    for (size_t i = 0; i < length; i++)
        text[i] = escaped[i % (sizeof escaped - 1)];
    if (absolute)
        text[0] = '/';
    text[length] = '\0';
    return text;
}

/* length bytes of plain letters, absolute if asked. */
static char *plain_text(size_t length, bool absolute)
{
    char *text = malloc(length + 1);
    assert_non_null(text);
    for (size_t i = 0; i < length; i++)
        text[i] = (char)('a' + i % 26);
    if (absolute)
        text[0] = '/';
    text[length] = '\0';
    return text;
}

/* ---- the tests -------------------------------------------------------------------------- */

/* Every saved key of the table is one this file knows, and no key it
 * knows is missing from the table's saved ones. */
static void test_every_saved_key_is_covered(void **state)
{
    (void)state;
    luz_option_info row;
    size_t saved = 0;
    for (size_t i = 0; luz_options_row(i, &row); i++) {
        if (row.saving == LUZ_OPTION_NOT_SAVED)
            continue;
        saved++;
        if (find_key(row.name) == NULL)
            fail_msg("the writer saves `%s`, which test_scene_file.c does not know: add it",
                     row.name);
    }
    assert_int_equal(saved, KEY_COUNT);
}

/* Each numeric key at each of its edges, alone; then every key at its
 * smallest, and every key at its largest, together. */
static void test_numbers_at_their_edges(void **state)
{
    (void)state;
    luz_options lowest, highest;
    luz_options_init(&lowest);
    luz_options_init(&highest);
    luz_option_info row;
    for (size_t r = 0; luz_options_row(r, &row); r++) {
        const key_field *key = row.saving != LUZ_OPTION_NOT_SAVED ? find_key(row.name) : NULL;
        if (key == NULL)
            continue;
        float floats[16];
        double doubles[16];
        int count = 0;
        switch (key->type) {
        case KEY_FLOAT:
        case KEY_EXPOSURE:
        case KEY_VEC3:
        case KEY_LIGHT:
            count = float_edges(row.min, row.max, floats);
            break;
        case KEY_DOUBLE:
            count = double_edges(row.min, row.max, doubles);
            break;
        default:
            continue;
        }
        assert_true(count >= 4);
        for (int v = 0; v < count; v++) {
            luz_options options;
            luz_options_init(&options);
            void *field = field_of(&options, key);
            if (key->type == KEY_DOUBLE) {
                *(double *)field = doubles[v];
            } else if (key->type == KEY_FLOAT || key->type == KEY_EXPOSURE) {
                *(float *)field = floats[v];
                options.scene.has_exposure = true;
            } else {
                /* x,y,z (and a) at this edge, and at the next edges round */
                float *components = field;
                for (int i = 0; i < 3; i++)
                    components[i] = floats[(v + i) % count];
                if (key->type == KEY_LIGHT)
                    ((luz_light *)field)->strength = floats[(v + 3) % count];
            }
            assert_round_trip(&options);
            luz_options_free(&options);
        }
        /* the first two edges are the lowest and the next; 2 the highest */
        void *low = field_of(&lowest, key), *high = field_of(&highest, key);
        if (key->type == KEY_DOUBLE) {
            *(double *)low = doubles[0];
            *(double *)high = doubles[2];
        } else {
            lowest.scene.has_exposure = highest.scene.has_exposure = true;
            for (int i = 0; i < (key->type == KEY_LIGHT ? 4 : key->type == KEY_VEC3 ? 3 : 1); i++) {
                ((float *)low)[i] = floats[0];
                ((float *)high)[i] = floats[2];
            }
        }
    }
    assert_round_trip(&lowest);
    assert_round_trip(&highest);
    luz_options_free(&lowest);
    luz_options_free(&highest);
}

/* The whole numbers and names: the sizes at the renderer's limits, the
 * seeds and cube counts at theirs, every filter, view and interpolation. */
static void test_counts_sizes_and_names(void **state)
{
    (void)state;
    const int sizes[][2] = {{1, 1},
                            {LUZ_MAX_DIMENSION, LUZ_MAX_PIXELS / LUZ_MAX_DIMENSION},
                            {LUZ_MAX_PIXELS / LUZ_MAX_DIMENSION, LUZ_MAX_DIMENSION},
                            {LUZ_MAX_DIMENSION, 1},
                            {1, LUZ_MAX_DIMENSION}};
    luz_option_info cubes;
    assert_true(luz_options_find("cubes", 5, &cubes));
    const uint32_t seeds[] = {0, 1, UINT32_MAX};
    const int counts[] = {(int)cubes.min, (int)cubes.max};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        luz_options options;
        luz_options_init(&options);
        options.width = sizes[i][0];
        options.height = sizes[i][1];
        options.scene.seed = seeds[i % 3];
        options.scene.cube_count = counts[i % 2];
        assert_round_trip(&options);
        luz_options_free(&options);
    }
    const luz_filter filters[] = {LUZ_FILTER_NEAREST, LUZ_FILTER_BILINEAR, LUZ_FILTER_TRILINEAR};
    const luz_interpolation modes[] = {LUZ_INTERPOLATION_PERSPECTIVE, LUZ_INTERPOLATION_AFFINE};
    for (int view = 0; view < LUZ_VIEW_COUNT; view++) {
        luz_options options;
        luz_options_init(&options);
        options.scene.view = (luz_view)view;
        options.scene.filter = filters[view % 3];
        options.scene.interpolation = modes[view % 2];
        options.paused = view % 2 == 1;   /* both values of the one yes/no key */
        options.scene.samples = view % 2 == 1 ? 4 : 1;   /* both sample counts */
        options.scene.has_tone_map = true;
        options.scene.tone_map = (luz_tone_map)(view % LUZ_TONE_MAP_COUNT);
        assert_round_trip(&options);
        luz_options_free(&options);
    }
}

/* The output's defaults depend on the models (SCENE.md, "Output"): clamp
 * at EV 0 without, neutral at EV -1 with one. A scene file keeps what is
 * in force, always written: with a model, clamp at EV 0 given by the user
 * reads back as clamp at EV 0, not as the model's default, and a model's
 * default is written out as neutral at EV -1. */
static void test_output_defaults_follow_the_models(void **state)
{
    (void)state;
    static const struct {
        bool model, given;
        float exposure;
        luz_tone_map tone_map;
        const char *written;   /* the lines expected */
    } cases[] = {
        {false, false, 0.0f, LUZ_TONE_MAP_CLAMP, "exposure = 0\ntonemap = clamp\n"},
        {false, true, 0.0f, LUZ_TONE_MAP_CLAMP, "exposure = 0\ntonemap = clamp\n"},
        {false, true, -1.0f, LUZ_TONE_MAP_NEUTRAL, "exposure = -1\ntonemap = neutral\n"},
        {true, false, -1.0f, LUZ_TONE_MAP_NEUTRAL, "exposure = -1\ntonemap = neutral\n"},
        {true, true, -1.0f, LUZ_TONE_MAP_NEUTRAL, "exposure = -1\ntonemap = neutral\n"},
        {true, true, 0.0f, LUZ_TONE_MAP_CLAMP, "exposure = 0\ntonemap = clamp\n"},
        {true, true, 0.5f, LUZ_TONE_MAP_NEUTRAL, "exposure = 0.5\ntonemap = neutral\n"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        luz_options options;
        luz_options_init(&options);
        luz_error error = {{0}};
        if (cases[i].model) {
            const luz_object object = {.texture = LUZ_TEXTURE_BY_INDEX, .scale = 1.0f};
            assert_int_equal(luz_options_add_object(&options, &object, NULL, "/models/a.obj", 1,
                                                    "test", &error),
                             0);
        }
        if (cases[i].given) {
            options.scene.has_exposure = options.scene.has_tone_map = true;
            options.scene.exposure = cases[i].exposure;
            options.scene.tone_map = cases[i].tone_map;
        }
        const luz_output output = luz_options_output(&options);
        assert_true(output.exposure == cases[i].exposure);
        assert_int_equal(output.tone_map, cases[i].tone_map);

        char *text = NULL;
        size_t size = 0;
        FILE *memory = open_memstream(&text, &size);
        assert_non_null(memory);
        luz_options_write_scene(&options, memory);
        assert_int_equal(fclose(memory), 0);
        const char *at = strstr(text, "exposure = ");
        if (at == NULL || strncmp(at, cases[i].written, strlen(cases[i].written)) != 0) {
            fail_msg("case %zu: expected '%s' in:\n%s", i, cases[i].written, text);
        }
        free(text);

        luz_options back;
        write_and_read(&options, &back);
        const luz_output read = luz_options_output(&back);
        assert_true(read.exposure == cases[i].exposure);
        assert_int_equal(read.tone_map, cases[i].tone_map);
        luz_options_free(&back);
        luz_options_free(&options);
    }
}

/* `bug NAME` round-trips for every bug (none is not written); a quiz is
 * written as `quiz = SEED` and its bug's name appears nowhere in the file,
 * and reading it back and finishing chooses the same bug. */
static void test_bug_and_quiz(void **state)
{
    (void)state;
    for (int bug = 0; bug < LUZ_BUG_COUNT; bug++) {
        luz_options options;
        luz_options_init(&options);
        luz_error error = {{0}};
        assert_int_equal(luz_options_set_value(&options, "bug", luz_bug_name((luz_bug)bug),
                                               NULL, &error),
                         0);
        char *text = NULL;
        size_t size = 0;
        FILE *memory = open_memstream(&text, &size);
        assert_non_null(memory);
        luz_options_write_scene(&options, memory);
        assert_int_equal(fclose(memory), 0);
        char line[64];
        snprintf(line, sizeof line, "\nbug = %s\n", luz_bug_name((luz_bug)bug));
        assert_int_equal(strstr(text, line) != NULL, bug != LUZ_BUG_NONE);
        free(text);
        assert_round_trip(&options);
        luz_options_free(&options);
    }
    for (uint32_t seed = 0; seed < 40; seed++) {
        luz_options options;
        luz_options_init(&options);
        luz_error error = {{0}};
        char value[16];
        snprintf(value, sizeof value, "%lu", (unsigned long)seed);
        assert_int_equal(luz_options_set_value(&options, "quiz", value, NULL, &error), 0);
        assert_int_equal(luz_options_finish(&options, &error), 0);
        assert_true(options.scene.bug_hidden);
        assert_int_not_equal(options.scene.bug, LUZ_BUG_NONE);
        char *text = NULL;
        size_t size = 0;
        FILE *memory = open_memstream(&text, &size);
        assert_non_null(memory);
        luz_options_write_scene(&options, memory);
        assert_int_equal(fclose(memory), 0);
        assert_null(strstr(text, luz_bug_name(options.scene.bug)));
        assert_null(strstr(text, "bug ="));
        char line[40];
        snprintf(line, sizeof line, "\nquiz = %lu\n", (unsigned long)seed);
        assert_non_null(strstr(text, line));
        free(text);
        luz_options back;
        write_and_read(&options, &back);
        assert_int_equal(luz_options_finish(&back, &error), 0);
        assert_int_equal(back.scene.bug, options.scene.bug);
        assert_true(back.scene.bug_hidden);
        luz_options_free(&back);
        luz_options_free(&options);
    }
}

/* The textures directory: the longest path the options hold (PATH_MAX - 1
 * bytes), plain and with a byte that needs quoting or escaping at every
 * turn (so its line is over 8000 characters), and the short oddities. */
static void test_textures_paths(void **state)
{
    (void)state;
    char *texts[] = {plain_text(PATH_MAX - 1, true), awkward_text(PATH_MAX - 1, false),
                     escaped_text(PATH_MAX - 1, false),
                     awkward_text(PATH_MAX - 1, true), strdup("none"), strdup(" "),
                     strdup("#"), strdup("\""), strdup("\\"), strdup("a b"), strdup("x=y")};
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        luz_options options;
        luz_options_init(&options);
        luz_error error = {{0}};
        /* through the setter, which also checks the length */
        if (luz_options_set_value(&options, "textures", texts[i], NULL, &error) != 0)
            fail_msg("textures of %zu bytes refused: %s", strlen(texts[i]), error.message);
        assert_round_trip(&options);
        luz_options_free(&options);
        free(texts[i]);
    }
    /* one byte more is refused, by the setter: the bound the writer relies on */
    char *longer = plain_text(PATH_MAX, true);
    luz_options options;
    luz_options_init(&options);
    luz_error error;
    assert_int_equal(luz_options_set_value(&options, "textures", longer, NULL, &error), -1);
    luz_options_free(&options);
    free(longer);
}

/* Cube and model lines at their edges: positions at +-LUZ_SCENE_MAX_COORDINATE
 * and tiny, colours 0 and 1, texture names of NAME_MAX bytes with blanks,
 * quotes and escapes, absolute model paths of PATH_MAX - 1 such bytes,
 * scales at LUZ_SCENE_MIN_SCALE and LUZ_SCENE_MAX_SCALE, still or not;
 * every field on one line, and the longest line the writer can write. */
static void test_object_lines(void **state)
{
    (void)state;
    const float edge = LUZ_SCENE_MAX_COORDINATE;
    const luz_vec3 positions[] = {{edge, -edge, nextafterf(edge, 0)},
                                  {-edge, FLT_TRUE_MIN, -0.0f},
                                  {0.0f, 0.0f, 0.0f},
                                  {1.0f / 3.0f, -FLT_TRUE_MIN, 0.1f}};
    const luz_vec3 colours[] = {{0, 0, 0}, {1, 1, 1}, {FLT_TRUE_MIN, nextafterf(1, 0), 0.1f}};
    const float scales[] = {LUZ_SCENE_MIN_SCALE, LUZ_SCENE_MAX_SCALE,
                            nextafterf(LUZ_SCENE_MIN_SCALE, 1), 1.0f / 3.0f};
    char *names[] = {escaped_text(NAME_MAX, false), plain_text(NAME_MAX, false),
                     awkward_text(NAME_MAX, false), NULL};
    char *models[] = {escaped_text(PATH_MAX - 1, true), plain_text(PATH_MAX - 1, true),
                      awkward_text(PATH_MAX - 1, true)};

    luz_options options;
    luz_options_init(&options);
    luz_error error = {{0}};
    for (int i = 0; i < 24; i++) {
        const bool model = i % 2 == 1;
        luz_object object = {.position = positions[i % 4],
                             .has_colour = i % 3 != 2,
                             .colour = colours[i % 3],
                             .texture = LUZ_TEXTURE_BY_INDEX,
                             .scale = model ? scales[(i / 2) % 4] : 1.0f,
                             .still = model && i % 4 == 1,
                             .up = model ? (luz_up_axis)((i / 2) % LUZ_UP_AXIS_COUNT)
                                         : LUZ_UP_Y};
        if (luz_options_add_object(&options, &object, names[(i / 2) % 4],
                                   model ? models[(i / 2) % 3] : NULL, i + 1, "test",
                                   &error) != 0)
            fail_msg("%s", error.message);
    }
    /* The test reaches the longest lines: object 1 is a model with every
     * field, every byte of its path and NAME but the first escaped, well
     * over 8000 characters; the reader takes 16384 (docs/cli.md). */
    char *text = NULL;
    size_t text_size = 0, longest = 0, length = 0;
    FILE *memory = open_memstream(&text, &text_size);
    assert_non_null(memory);
    luz_options_write_scene(&options, memory);
    assert_int_equal(fclose(memory), 0);
    for (size_t i = 0; i < text_size; i++) {
        length = text[i] == '\n' ? 0 : length + 1;
        longest = length > longest ? length : longest;
    }
    free(text);
    if (!(longest > 8000 && longest <= 16384))
        fail_msg("the longest line has %zu characters", longest);
    assert_round_trip(&options);
    luz_options_free(&options);
    for (int i = 0; i < 4; i++)
        free(names[i]);
    for (int i = 0; i < 3; i++)
        free(models[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_saved_key_is_covered),
        cmocka_unit_test(test_numbers_at_their_edges),
        cmocka_unit_test(test_counts_sizes_and_names),
        cmocka_unit_test(test_output_defaults_follow_the_models),
        cmocka_unit_test(test_textures_paths),
        cmocka_unit_test(test_object_lines),
        cmocka_unit_test(test_bug_and_quiz),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
