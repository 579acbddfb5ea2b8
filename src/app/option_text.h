/*
 * option_text.h: the text helpers that the option files share (options.c,
 * scene_file.c, command_line.c, option_textures.c), so that all read a
 * number, print one back, and quote a user's text in a message, in exactly
 * the same way. Private to src/app; not installed.
 */
#ifndef LUZ_OPTION_TEXT_H
#define LUZ_OPTION_TEXT_H

#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A user's text quoted in a message: at most 60 bytes of it, and control
 * characters shown as '?' so that the message stays on one line. Returned
 * by value, so that it can be used inside a call's arguments. */
typedef struct option_quoted {
    char text[72];
} option_quoted;

static inline option_quoted option_quote(const char *text)
{
    option_quoted result;
    size_t length = 0;
    for (; text[length] != '\0' && length < 60; length++) {
        unsigned char c = (unsigned char)text[length];
        result.text[length] = (c < 0x20 || c == 0x7f) ? '?' : (char)c;
    }
    if (text[length] != '\0') {
        memcpy(result.text + length, "...", 3);
        length += 3;
    }
    result.text[length] = '\0';
    return result;
}

typedef enum option_parse_result {
    OPTION_PARSE_OK,
    OPTION_PARSE_MALFORMED,   /* not the expected shape, or something after it */
    OPTION_PARSE_NOT_FINITE,  /* NaN, infinity, or beyond a float's range */
} option_parse_result;

static inline const char *option_skip_blanks(const char *text)
{
    while (*text == ' ' || *text == '\t')
        text++;
    return text;
}

/* Reads `count` comma-separated numbers that make up the whole of text,
 * blanks allowed around each. With single_precision the numbers must also
 * fit a float: 1e39 is finite as a double but would become infinity. */
static inline option_parse_result option_read_numbers(const char *text, double *values,
                                                      int count, bool single_precision)
{
    const char *cursor = text;
    for (int i = 0; i < count; i++) {
        cursor = option_skip_blanks(cursor);
        /* strtod would skip a newline too, and take the next line's number */
        if (*cursor == '\0' || *cursor == ',' || isspace((unsigned char)*cursor))
            return OPTION_PARSE_MALFORMED;
        char *end;
        values[i] = strtod(cursor, &end);
        if (end == cursor)
            return OPTION_PARSE_MALFORMED;
        if (!isfinite(values[i]) || (single_precision && fabs(values[i]) > FLT_MAX))
            return OPTION_PARSE_NOT_FINITE;
        cursor = option_skip_blanks(end);
        if (i + 1 < count) {
            if (*cursor != ',')
                return OPTION_PARSE_MALFORMED;
            cursor++;
        }
    }
    return *cursor == '\0' ? OPTION_PARSE_OK : OPTION_PARSE_MALFORMED;
}

/* %g with too few digits writes -90 as -9e+01: exact, but not what a person
 * writes. Exponents are kept for the very large and the very small only. */
static inline bool option_reads_well(const char *text, double value)
{
    double magnitude = fabs(value);
    return strchr(text, 'e') == NULL || magnitude < 1e-4 || magnitude >= 1e15;
}

/* The shortest %.Ng text that the reader above, option_read_numbers,
 * takes and brings back to the same float (strtod, then a cast): "0.2"
 * rather than %.9g's "0.200000003". %.9g always round-trips a float
 * through strtof; going on to 17 digits covers the double rounding of
 * strtod-then-cast as well, since %.17g is the exact double of the float.
 * Asking the reader itself, not strtod, matters at the edge: FLT_MAX's
 * shortest text, 3.4028235e+38, is a double above FLT_MAX, which the reader
 * refuses; 3.402823466e+38 is the first it takes. */
static inline void option_format_float(char *buffer, size_t size, float value)
{
    for (int precision = 1; precision <= 17; precision++) {
        snprintf(buffer, size, "%.*g", precision, (double)value);
        double back;
        if (option_read_numbers(buffer, &back, 1, true) == OPTION_PARSE_OK &&
            (float)back == value && option_reads_well(buffer, value))
            return;
    }
}

/* The same for a double: at most %.17g's digits. */
static inline void option_format_double(char *buffer, size_t size, double value)
{
    for (int precision = 1; precision <= 17; precision++) {
        snprintf(buffer, size, "%.*g", precision, value);
        double back;
        if (option_read_numbers(buffer, &back, 1, false) == OPTION_PARSE_OK && back == value &&
            option_reads_well(buffer, value))
            return;
    }
}

#endif
