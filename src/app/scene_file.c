/*
 * scene_file.c: scene files, read and written.
 *
 * A scene file is the command line written down, one option a line:
 *
 *     # the spot alone, seen from the side
 *     camera-pos = 4, 0, 3
 *     camera-yaw = -135
 *     only       = spot
 *     cube = 0, 0, 0
 *     cube = 2, 0, -1  colour 1, 0.5, 0  texture wood.png
 *
 * Keys are the long options without their dashes (everything but help,
 * version and scene), each set at most once; `#` starts a comment anywhere
 * on a line but inside a quoted string (below); blank lines are ignored.
 * `cube = x, y, z` lines, optionally followed by `colour r,g,b` and
 * `texture NAME`, and `model = FILE` lines, optionally followed by
 * `at x,y,z`, `scale k`, `colour r,g,b`, `texture NAME`, `up AXIS` and `still`,
 * replace the cube list with the user's own objects, in the order given. A
 * texture NAME is kept as text until the textures are loaded
 * (luz_options_resolve_textures), since the file is read before the
 * textures directory is known; a model FILE, relative to the scene file's
 * directory, is kept as an absolute path until the models are read
 * (luz_options_load_models).
 *
 * A value, or a texture NAME, may be written as a quoted string, "...", in
 * which `#` and blanks are part of the text and \" \\ \n \t \r are the only
 * escapes: `textures = "my # textures "`, `texture "old wood.png"`. Only
 * blanks, a comment, or in a cube line the next field may follow the
 * closing quote. A `"` anywhere else (inside an unquoted value) is an
 * ordinary character. luz_options_write_scene quotes only the text that
 * needs it, so that what it writes always reads back the same.
 *
 * Values go through luz_options_set_value(), the command line's own
 * setter, so a file accepts exactly what the command line accepts. Every
 * error names FILE:LINE. The writer saves the keys the option table marks
 * as saved (luz_options_row), each formatted by luz_options_format.
 *
 * Uses options.c (the table, one value set or formatted) and io; options.c
 * knows nothing of files and never calls back. command_line.c calls the
 * reader for --scene; option_textures.c resolves the texture names that
 * the cube lines leave behind.
 */
#include "app/options.h"
#include "io/input_file.h"
#include "io/new_file.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/option_text.h"

/* Longer than any key, so that a key that does not fit is not a key. */
#define KEY_MAX 24
/* Bounds on what a scene file may hold. A line holds the longest that
 * luz_options_write_scene writes, with room to spare: a model line whose
 * PATH_MAX - 1 bytes of path each need an escape (2 x 4095 + 2 quotes),
 * with `at` and `colour` (2 x 3 numbers of at most 15 characters, commas
 * and blanks), a `scale`, a texture NAME of NAME_MAX bytes likewise
 * escaped (2 x 255 + 2) and `still`: under 9000 characters. The lines are
 * enough for LUZ_MAX_CUBES cube lines with comments between them. */
#define SCENE_LINE_MAX 16384
#define SCENE_MAX_LINES (2 * LUZ_MAX_CUBES + 1000)
#define SEEN_KEYS_MAX 64
/* "FILE:LINE: what" for messages, whole for a scene file's path of up to
 * PATH_MAX bytes (a longer one cannot be opened). */
#define WHERE_SIZE (PATH_MAX + 64)
/* A texture NAME is a file name of the textures directory. */
#define TEXTURE_NAME_MAX NAME_MAX

typedef struct scene_reader {
    luz_options *options;
    const char *path;
    int line;
    int first_cube_line;   /* 0 until the file's first `cube` line */
    int cubes_key_line;    /* 0 until the file's `cubes = N` line */
    int seen_count;
    struct {
        char name[KEY_MAX];
        int line;
    } seen[SEEN_KEYS_MAX];
} scene_reader;

/* Strips blanks (and the line's \r\n) at both ends, in place. */
static char *trim(char *text)
{
    while (*text == ' ' || *text == '\t')
        text++;
    size_t length = strlen(text);
    while (length > 0 && strchr(" \t\r\n", text[length - 1]) != NULL)
        text[--length] = '\0';
    return text;
}

/* ---- quoted values ------------------------------------------------------------- */

/* Just after the quoted string that starts at text (its '"'), or NULL if it
 * is not closed on the line. Escapes are skipped whole, good or bad: only
 * unquote() judges them. */
static char *skip_quoted(char *text)
{
    for (char *p = text + 1; *p != '\0'; p++) {
        if (*p == '\\' && p[1] != '\0')
            p++;
        else if (*p == '"')
            return p + 1;
    }
    return NULL;
}

/* Where the line's comment starts: its first `#` outside a quoted string,
 * or NULL. A quoted string can start only where a value can: at the first
 * character of a `name = value` line's value, and, in a cube or model
 * line, at the start of a word (the texture NAME; anywhere else
 * read_object refuses it).
 * A `"` elsewhere is an ordinary character, as it always was. An
 * unterminated quote hides the rest of the line, and unquote() says so. */
static char *find_comment(char *text)
{
    char *mark = strpbrk(text, "#=");
    if (mark == NULL || *mark == '#')
        return mark;
    char *name = text;
    while (*name == ' ' || *name == '\t')
        name++;
    char *name_end = mark;
    while (name_end > name && (name_end[-1] == ' ' || name_end[-1] == '\t'))
        name_end--;
    bool object = (name_end - name == 4 && memcmp(name, "cube", 4) == 0) ||
                  (name_end - name == 5 && memcmp(name, "model", 5) == 0);

    char *value = mark + 1;
    while (*value == ' ' || *value == '\t')
        value++;
    for (char *p = value; *p != '\0'; p++) {
        if (*p == '#')
            return p;
        bool word_start = p == value || p[-1] == ' ' || p[-1] == '\t';
        if (*p == '"' && (p == value || (object && word_start))) {
            char *end = skip_quoted(p);
            if (end == NULL)
                return NULL;
            p = end - 1;
        }
    }
    return NULL;
}

/* Decodes, in place, the quoted string that starts at text (its '"'): the
 * bytes between the quotes, with \" \\ \n \t \r replaced by what they
 * stand for. *end is set just after the closing quote, whose place (or an
 * earlier one) now holds the decoded text's NUL. Returns 0, or -1 with an
 * error starting with `where`. */
static int unquote(char *text, char **end, const char *where, luz_error *error)
{
    option_quoted original = option_quote(text);
    char *out = text;
    for (char *in = text + 1;; in++) {
        if (*in == '\0')
            return luz_error_set(error,
                                 "%s: expected a closing \" to end the quoted text, got '%s'",
                                 where, original.text);
        if (*in == '"') {
            *out = '\0';
            *end = in + 1;
            return 0;
        }
        if (*in != '\\') {
            *out++ = *in;
            continue;
        }
        in++;
        switch (*in) {
        case '"': *out++ = '"'; break;
        case '\\': *out++ = '\\'; break;
        case 'n': *out++ = '\n'; break;
        case 't': *out++ = '\t'; break;
        case 'r': *out++ = '\r'; break;
        case '\0':
            return luz_error_set(error,
                                 "%s: expected a closing \" to end the quoted text, got '%s'",
                                 where, original.text);
        default: {
            /* the whole character, when it is a UTF-8 sequence */
            char escape[5] = {*in, '\0'};
            if ((unsigned char)*in >= 0x80) {
                for (int k = 1; k < 4 && ((unsigned char)in[k] & 0xc0) == 0x80; k++)
                    escape[k] = in[k];
            }
            return luz_error_set(error,
                                 "%s: unknown escape '\\%s' in quoted text (expected \\\" "
                                 "\\\\ \\n \\t or \\r)",
                                 where, option_quote(escape).text);
        }
        }
    }
}

/* ---- cube lines ---------------------------------------------------------------- */

/* Where the next field (`colour` or `texture`) of a cube line starts: the
 * first word that begins with a letter which is not a number. strtod is
 * asked, so that "inf" and "nan" stay numbers and are refused as such. */
static char *find_field(char *text)
{
    for (size_t i = 0; text[i] != '\0'; i++) {
        bool word_start = i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' ||
                          text[i - 1] == ',';
        bool letter = (text[i] >= 'a' && text[i] <= 'z') || (text[i] >= 'A' && text[i] <= 'Z');
        if (word_start && letter) {
            char *end;
            (void)strtod(text + i, &end);
            if (end == text + i)
                return text + i;
        }
    }
    return text + strlen(text);
}

/* A quoted or plain word at text (a texture NAME, a model FILE): sets
 * *word to it, ends it with a NUL, and returns where the next field
 * starts; NULL with a message if it is malformed. what is for messages
 * ("cube: texture"). */
static char *read_word(scene_reader *reader, char *text, const char *what, char **word,
                       luz_error *error)
{
    char where[WHERE_SIZE];
    snprintf(where, sizeof where, "%s:%d: %s", reader->path, reader->line, what);
    if (text[0] == '"') {
        char *after;
        if (unquote(text, &after, where, error) != 0)
            return NULL;
        if (*after != '\0' && *after != ' ' && *after != '\t') {
            luz_error_set(error,
                          "%s: expected blanks then the next field after the closing quote, "
                          "got '%s'",
                          where, option_quote(after).text);
            return NULL;
        }
        *word = text;
        return after + strspn(after, " \t");
    }
    size_t length = strcspn(text, " \t");
    if (length == 0) {
        luz_error_set(error, "%s: missing", where);
        return NULL;
    }
    char *after = text + length;
    char *next = after + strspn(after, " \t");
    *after = '\0';
    *word = text;
    return next;
}

/* Is each of the three numbers, as the float it becomes, a coordinate the
 * lab takes (LUZ_SCENE_MAX_COORDINATE)? */
static bool coordinates_in_range(const double numbers[3])
{
    for (int i = 0; i < 3; i++) {
        const float coordinate = (float)numbers[i];
        if (!(coordinate >= -LUZ_SCENE_MAX_COORDINATE && coordinate <= LUZ_SCENE_MAX_COORDINATE))
            return false;
    }
    return true;
}

/* Three numbers up to the next field; *next is moved to it. */
static option_parse_result read_triple(char *text, double numbers[3], char **next)
{
    char *end = find_field(text);
    char saved = *end;
    *end = '\0';
    option_parse_result result = option_read_numbers(text, numbers, 3, true);
    *end = saved;
    *next = end;
    return result;
}

/* The object lines:
 *   cube = x, y, z [colour r,g,b] [texture NAME]
 *   model = FILE [at x,y,z] [scale k] [colour r,g,b] [texture NAME] [up AXIS] [still]
 * the fields in any order. A model's FILE is relative to the scene file's
 * directory and kept absolute. */
static int read_object(scene_reader *reader, char *value, bool is_model, luz_error *error)
{
    const char *path = reader->path;
    const int line = reader->line;
    const char *kind = is_model ? "model" : "cube";
    const char *syntax = is_model ? "FILE [at x,y,z] [scale k] [colour r,g,b] [texture NAME] "
                                    "[up AXIS] [still]"
                                  : "x,y,z [colour r,g,b] [texture NAME]";
    if (reader->cubes_key_line != 0)
        return luz_error_set(error,
                             "%s:%d: %s: expected either `cubes = N` or cube and model lines, "
                             "not both (cubes is set on line %d)",
                             path, line, kind, reader->cubes_key_line);
    if (value[0] == '\0')
        return luz_error_set(error, "%s:%d: %s: missing value (expected %s)", path, line, kind,
                             syntax);
    option_quoted original = option_quote(value);

    luz_object object = {.texture = LUZ_TEXTURE_BY_INDEX, .scale = 1.0f};
    const char *texture_name = NULL;
    char model_path[PATH_MAX];
    char *fields;
    double numbers[3];
    bool has_position = false, has_scale = false, has_up = false;
    if (is_model) {
        char *file;
        if ((fields = read_word(reader, value, "model: FILE", &file, error)) == NULL)
            return -1;
        /* The scene file's directory: "" for the working one, "/" for a
         * file in the root. */
        char directory[PATH_MAX];
        const char *slash = strrchr(path, '/');
        if (slash == path)
            snprintf(directory, sizeof directory, "/");
        else
            snprintf(directory, sizeof directory, "%.*s", slash ? (int)(slash - path) : 0, path);
        char where[WHERE_SIZE];
        snprintf(where, sizeof where, "%s:%d: model", path, line);
        luz_error inner;
        if (luz_options_model_path(directory, file, model_path, sizeof model_path, &inner) != 0)
            return luz_error_set(error, "%s: %s", where, inner.message);
    } else {
        option_parse_result position = read_triple(value, numbers, &fields);
        if (position == OPTION_PARSE_NOT_FINITE)
            return luz_error_set(error, "%s:%d: cube: expected finite numbers, got '%s'", path,
                                 line, original.text);
        if (position != OPTION_PARSE_OK)
            return luz_error_set(error,
                                 "%s:%d: cube: expected x,y,z (three numbers) then optional "
                                 "colour r,g,b and texture NAME, got '%s'",
                                 path, line, original.text);
        if (!coordinates_in_range(numbers))
            return luz_error_set(error,
                                 "%s:%d: cube: expected x,y,z each in [%g, %g], got '%s'",
                                 path, line, -(double)LUZ_SCENE_MAX_COORDINATE,
                                 (double)LUZ_SCENE_MAX_COORDINATE, original.text);
        object.position = luz_vec3_make((float)numbers[0], (float)numbers[1], (float)numbers[2]);
    }

    while (*fields != '\0') {
        size_t length = strcspn(fields, " \t");
        char *rest = fields + length + strspn(fields + length, " \t");
#define FIELD_IS(word) (length == sizeof word - 1 && memcmp(fields, word, length) == 0)
        if (FIELD_IS("colour") || FIELD_IS("color")) {
            if (object.has_colour)
                return luz_error_set(error, "%s:%d: %s: duplicate colour field in '%s'", path,
                                     line, kind, original.text);
            option_parse_result colour = read_triple(rest, numbers, &fields);
            bool in_range = colour == OPTION_PARSE_OK;
            for (int i = 0; i < 3 && in_range; i++)
                in_range = numbers[i] >= 0.0 && numbers[i] <= 1.0;
            if (!in_range)
                return luz_error_set(error,
                                     "%s:%d: %s: expected colour r,g,b, each in [0, 1], got "
                                     "'%s'",
                                     path, line, kind, original.text);
            object.has_colour = true;
            object.colour = luz_vec3_make((float)numbers[0], (float)numbers[1], (float)numbers[2]);
        } else if (FIELD_IS("texture")) {
            if (texture_name != NULL)
                return luz_error_set(error, "%s:%d: %s: duplicate texture field in '%s'", path,
                                     line, kind, original.text);
            char what[32], *name;
            snprintf(what, sizeof what, "%s: texture", kind);
            if (rest[0] == '\0')
                return luz_error_set(error,
                                     "%s:%d: %s: expected texture NAME, a file of the textures "
                                     "directory, got '%s'",
                                     path, line, kind, original.text);
            if ((fields = read_word(reader, rest, what, &name, error)) == NULL)
                return -1;
            if (strlen(name) > TEXTURE_NAME_MAX)
                return luz_error_set(error,
                                     "%s:%d: %s: expected texture NAME, a file name of at most "
                                     "%d bytes, got '%s'",
                                     path, line, kind, TEXTURE_NAME_MAX, option_quote(name).text);
            texture_name = name;
        } else if (is_model && FIELD_IS("at")) {
            option_parse_result at = read_triple(rest, numbers, &fields);
            if (has_position || at != OPTION_PARSE_OK || !coordinates_in_range(numbers))
                return luz_error_set(error,
                                     "%s:%d: model: expected `at x,y,z` once, three numbers "
                                     "each in [%g, %g], got '%s'",
                                     path, line, -(double)LUZ_SCENE_MAX_COORDINATE,
                                     (double)LUZ_SCENE_MAX_COORDINATE, original.text);
            has_position = true;
            object.position = luz_vec3_make((float)numbers[0], (float)numbers[1], (float)numbers[2]);
        } else if (is_model && FIELD_IS("scale")) {
            char *end = find_field(rest);
            char saved = *end;
            *end = '\0';
            option_parse_result scale = option_read_numbers(rest, numbers, 1, true);
            *end = saved;
            /* judged as the float it becomes, as the options are */
            const float k = scale == OPTION_PARSE_OK ? (float)numbers[0] : 0.0f;
            if (has_scale || !(k >= LUZ_SCENE_MIN_SCALE && k <= LUZ_SCENE_MAX_SCALE))
                return luz_error_set(error,
                                     "%s:%d: model: expected `scale k` once, k a number in "
                                     "[%g, %g], got '%s'",
                                     path, line, (double)LUZ_SCENE_MIN_SCALE,
                                     (double)LUZ_SCENE_MAX_SCALE, original.text);
            has_scale = true;
            object.scale = k;
            fields = end;
        } else if (is_model && FIELD_IS("up")) {
            /* The axis is one word (its letters would start a field). */
            char *end = rest + strcspn(rest, " \t");
            char saved = *end;
            *end = '\0';
            const bool known = rest[0] != '\0' && luz_up_axis_from_name(rest, &object.up);
            *end = saved;
            if (has_up || !known)
                return luz_error_set(error,
                                     "%s:%d: model: expected `up AXIS` once, AXIS one of y, z, "
                                     "x, -y, -z, -x, got '%s'",
                                     path, line, original.text);
            has_up = true;
            fields = end + strspn(end, " \t");
        } else if (is_model && FIELD_IS("still")) {
            if (object.still)
                return luz_error_set(error, "%s:%d: model: duplicate still field in '%s'", path,
                                     line, original.text);
            object.still = true;
            fields = rest;
        } else {
            fields[length] = '\0';
            return luz_error_set(error, "%s:%d: %s: unknown field '%s' (expected %s)", path,
                                 line, kind, option_quote(fields).text,
                                 is_model ? "at x,y,z, scale k, colour r,g,b, texture NAME, "
                                            "up AXIS or still"
                                          : "colour r,g,b or texture NAME");
        }
#undef FIELD_IS
    }

    /* The file's first object line replaces whatever objects came before
     * (an earlier file, the tiling); the later ones add to it. */
    if (reader->first_cube_line == 0) {
        luz_options_clear_objects(reader->options);
        reader->first_cube_line = line;
    }
    char where[WHERE_SIZE];
    snprintf(where, sizeof where, "%s:%d: %s", path, line, kind);
    return luz_options_add_object(reader->options, &object, texture_name,
                                  is_model ? model_path : NULL, line, where, error);
}

/* ---- reading ------------------------------------------------------------------------- */

static int read_line(scene_reader *reader, char *text, luz_error *error)
{
    const char *path = reader->path;
    int line = reader->line;
    char *comment = find_comment(text);
    if (comment != NULL)
        *comment = '\0';
    text = trim(text);
    if (text[0] == '\0')
        return 0;

    option_quoted original = option_quote(text);
    char *equals = strchr(text, '=');
    if (equals == NULL)
        return luz_error_set(error, "%s:%d: expected `name = value`, got '%s'", path, line,
                             original.text);
    *equals = '\0';
    char *name = trim(text);
    char *value = trim(equals + 1);
    if (name[0] == '\0')
        return luz_error_set(error, "%s:%d: expected `name = value`, got '%s'", path, line,
                             original.text);

    if (strcmp(name, "cube") == 0 || strcmp(name, "model") == 0)
        return read_object(reader, value, name[0] == 'm', error);
    /* An option of the command line that a file may not set (help,
     * reference, scene, shard, ...): say so, rather than "unknown". */
    luz_option_info row;
    if (strcmp(name, "o") != 0 && luz_options_find(name, strlen(name), &row) &&
        !luz_options_is_scene_key(name))
        return luz_error_set(error, "%s:%d: `%s` is not allowed in a scene file", path, line,
                             name);
    if (!luz_options_is_scene_key(name) || strlen(name) >= KEY_MAX)
        return luz_error_set(error,
                             "%s:%d: unknown key '%s' (expected a long option of luz-render "
                             "--help without its dashes, or cube)",
                             path, line, option_quote(name).text);

    /* A key set twice is almost always an edit that forgot the first one;
     * saying so beats silently taking the last. */
    for (int i = 0; i < reader->seen_count; i++) {
        if (strcmp(reader->seen[i].name, name) == 0)
            return luz_error_set(error, "%s:%d: duplicate key `%s` (already set on line %d)",
                                 path, line, name, reader->seen[i].line);
    }
    if (reader->seen_count < SEEN_KEYS_MAX) {
        snprintf(reader->seen[reader->seen_count].name, KEY_MAX, "%s", name);
        reader->seen[reader->seen_count].line = line;
        reader->seen_count++;
    }
    if (strcmp(name, "cubes") == 0) {
        if (reader->first_cube_line != 0)
            return luz_error_set(error,
                                 "%s:%d: cubes: expected either `cubes = N` or cube and model "
                                 "lines, not both (the first is line %d)",
                                 path, line, reader->first_cube_line);
        reader->cubes_key_line = line;
    }

    char where[WHERE_SIZE];
    snprintf(where, sizeof where, "%s:%d: %s", path, line, name);
    if (value[0] == '"') {
        char *after;
        if (unquote(value, &after, where, error) != 0)
            return -1;
        /* the comment is gone and the line trimmed: nothing may be left */
        if (*after != '\0')
            return luz_error_set(error,
                                 "%s: expected only blanks or a comment after the closing "
                                 "quote, got '%s'",
                                 where, option_quote(after + strspn(after, " \t")).text);
    }
    return luz_options_set_value(reader->options, name, value, where, error);
}

typedef enum scene_line {
    LINE_TEXT,       /* a line, without its '\n', in the buffer */
    LINE_NONE,       /* the end of the file (or a read error: ferror says) */
    LINE_TOO_LONG,   /* longer than the buffer holds */
    LINE_WITH_NUL,   /* a NUL byte in it, anywhere */
} scene_line;

/* Reads the next line of file into text (size - 1 characters at most, then
 * a NUL), byte by byte: fgets cannot tell a NUL byte in the file from its
 * own end of string, so a NUL in the last line, or a file of one NUL
 * byte, went unseen. A last line without a '\n' is a line. */
static scene_line next_line(FILE *file, char *text, size_t size)
{
    size_t length = 0;
    bool nul = false;
    int c;
    while ((c = getc_unlocked(file)) != EOF && c != '\n') {
        if (length + 1 == size)
            return LINE_TOO_LONG;
        nul = nul || c == '\0';
        text[length++] = (char)c;
    }
    text[length] = '\0';
    if (c == EOF && length == 0)
        return LINE_NONE;
    return nul ? LINE_WITH_NUL : LINE_TEXT;
}

/* Reads the scene text of an open stream, path naming it in messages;
 * closes the stream. */
static int read_scene_stream(luz_options *options, FILE *file, const char *path,
                             luz_error *error)
{
    char *path_copy = strdup(path);
    if (path_copy == NULL) {
        fclose(file);
        return luz_error_set(error, "%s: out of memory", path);
    }
    free(options->scene_path);
    options->scene_path = path_copy;
    if (luz_input_files_add(&options->inputs, path, "the scene file", error) != 0) {
        fclose(file);
        return -1;
    }

    /* Lines are read into a fixed buffer, so no input can make the reader
     * allocate without bound; a line that does not fit is an error. */
    scene_reader reader = {.options = options, .path = options->scene_path};
    char text[SCENE_LINE_MAX + 1];
    int status = 0;
    scene_line got;
    flockfile(file);   /* next_line's getc_unlocked */
    while (status == 0 && (got = next_line(file, text, sizeof text)) != LINE_NONE) {
        reader.line++;
        if (got == LINE_TOO_LONG)
            status = luz_error_set(error, "%s:%d: line longer than %d characters", path,
                                   reader.line, SCENE_LINE_MAX);
        else if (got == LINE_WITH_NUL)
            status = luz_error_set(error, "%s:%d: expected text, found a NUL byte", path,
                                   reader.line);
        else if (reader.line > SCENE_MAX_LINES)
            status = luz_error_set(error, "%s:%d: more than %d lines", path, reader.line,
                                   SCENE_MAX_LINES);
        else
            status = read_line(&reader, text, error);
    }
    funlockfile(file);
    /* The end, or an error (a directory gives EISDIR). */
    if (status == 0 && ferror(file))
        status = luz_error_set(error, "%s: cannot read the scene file (%s)", path,
                               strerror(errno));
    fclose(file);
    return status;
}

int luz_options_read_scene_file(luz_options *options, const char *path, luz_error *error)
{
    /* Only a regular file, opened without blocking: a FIFO would block the
     * open, and a device (/dev/zero, say) could feed the reader forever. */
    int descriptor;
    uint64_t size;
    if (luz_input_open(path, "a scene file", LUZ_SCENE_FILE_MAX_BYTES, &descriptor, &size,
                       error) != 0)
        return -1;
    FILE *file = fdopen(descriptor, "r");
    if (file == NULL) {
        close(descriptor);
        return luz_error_set(error, "%s: cannot read the scene file (%s)", path,
                             strerror(errno));
    }
    return read_scene_stream(options, file, path, error);
}

int luz_options_read_scene_text(luz_options *options, const char *text, size_t length,
                                const char *name, luz_error *error)
{
    /* glibc's fmemopen takes a buffer of no bytes: an empty file. */
    static const char nothing[1] = "";
    FILE *file = fmemopen((void *)(length > 0 ? text : nothing), length, "r");
    if (file == NULL)
        return luz_error_set(error, "%s: cannot read the scene text (%s)", name,
                             strerror(errno));
    return read_scene_stream(options, file, name, error);
}

/* ---- writing ------------------------------------------------------------------------ */

/* Writes text as the reader will read it back: as it is when it can be,
 * else quoted. A value is quoted when it is empty, holds `#`, `"`, `\` or
 * a control character, or begins or ends with a blank (which the reader
 * would trim); a cube's texture NAME (is_word) also when it holds a blank
 * anywhere, since an unquoted NAME ends at the first. Text that needs none
 * of this is written as before quoting existed, so saved files and their
 * diffs do not change. */
static void write_text(FILE *out, const char *text, bool is_word)
{
    size_t length = strlen(text);
    bool quote = length == 0 || text[0] == ' ' || text[length - 1] == ' ';
    for (size_t i = 0; i < length && !quote; i++) {
        unsigned char c = (unsigned char)text[i];
        quote = c == '#' || c == '"' || c == '\\' || c < 0x20 || c == 0x7f ||
                (is_word && c == ' ');
    }
    if (!quote) {
        fputs(text, out);
        return;
    }
    fputc('"', out);
    for (size_t i = 0; i < length; i++) {
        switch (text[i]) {
        case '"': fputs("\\\"", out); break;
        case '\\': fputs("\\\\", out); break;
        case '\n': fputs("\\n", out); break;
        case '\t': fputs("\\t", out); break;
        case '\r': fputs("\\r", out); break;
        default: fputc(text[i], out); break;   /* other bytes as they are */
        }
    }
    fputc('"', out);
}

void luz_options_write_scene(const luz_options *options, FILE *out)
{
    /* The keys, and when each is written, come from the option table's
     * `saving` column. Those saved whenever they have a value come first,
     * then those saved only when changed, each group in the table's order:
     * the order files have always had (textures before view and interp),
     * so that a view saved again diffs only where it changed. */
    static const luz_option_saving groups[] = {LUZ_OPTION_SAVED,
                                               LUZ_OPTION_SAVED_IF_CHANGED};
    luz_options defaults;
    luz_options_init(&defaults);
    char value[4200], default_value[4200];
    luz_option_info row;
    fprintf(out, "# luz scene: render it with luz-render --scene FILE (see docs/cli.md)\n");
    for (size_t group = 0; group < sizeof groups / sizeof groups[0]; group++) {
        for (size_t i = 0; luz_options_row(i, &row); i++) {
            if (row.saving != groups[group])
                continue;
            /* The cube lines below replace the tiling's count, and a file
             * may not have both. */
            if (strcmp(row.name, "cubes") == 0 && options->scene.object_count > 0)
                continue;
            /* Nothing to write: a value left unset (textures). */
            if (luz_options_format(options, row.name, value, sizeof value) != 0)
                continue;
            /* The text reads back exactly, so equal text is an equal value. */
            if (row.saving == LUZ_OPTION_SAVED_IF_CHANGED &&
                luz_options_format(&defaults, row.name, default_value,
                                   sizeof default_value) == 0 &&
                strcmp(value, default_value) == 0)
                continue;
            fprintf(out, "%s = ", row.name);
            write_text(out, value, false);
            fputc('\n', out);
        }
    }
    luz_options_free(&defaults);
    for (int i = 0; i < options->scene.object_count; i++) {
        const luz_object *object = &options->objects[i];
        const luz_object_source *source = &options->object_sources[i];
        char x[32], y[32], z[32];
        option_format_float(x, sizeof x, object->position.x);
        option_format_float(y, sizeof y, object->position.y);
        option_format_float(z, sizeof z, object->position.z);
        if (source->model_path != NULL) {
            /* The path is absolute, so the file opens from anywhere. */
            fputs("model = ", out);
            write_text(out, source->model_path, true);
            /* `at` is left out only for the origin the reader gives
             * without it, +0 exactly: -0 compares equal to 0 but is
             * another float, which the file must keep */
            if (object->position.x != 0.0f || object->position.y != 0.0f ||
                object->position.z != 0.0f || signbit(object->position.x) ||
                signbit(object->position.y) || signbit(object->position.z))
                fprintf(out, " at %s, %s, %s", x, y, z);
            if (object->scale != 1.0f && object->scale > 0.0f) {
                option_format_float(x, sizeof x, object->scale);
                fprintf(out, " scale %s", x);
            }
        } else {
            fprintf(out, "cube = %s, %s, %s", x, y, z);
        }
        if (object->has_colour) {
            option_format_float(x, sizeof x, object->colour.x);
            option_format_float(y, sizeof y, object->colour.y);
            option_format_float(z, sizeof z, object->colour.z);
            fprintf(out, " colour %s, %s, %s", x, y, z);
        }
        if (source->texture_name != NULL) {
            fputs(" texture ", out);
            write_text(out, source->texture_name, true);
        }
        if (source->model_path != NULL && object->up != LUZ_UP_Y)
            fprintf(out, " up %s", luz_up_axis_name(object->up));
        if (source->model_path != NULL && object->still)
            fputs(" still", out);
        fputc('\n', out);
    }
}

int luz_options_save_scene(const luz_options *options, const char *path, bool replace,
                           luz_error *error)
{
    luz_new_file file;
    if (luz_new_file_open(&file, path, error) != 0)
        return -1;
    luz_options_write_scene(options, file.stream);
    return luz_new_file_commit(&file, replace, error);
}
