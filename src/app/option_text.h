/*
 * option_text.h: the text helpers that the option files share (options.c,
 * scene_file.c, command_line.c, option_textures.c), so that all read a
 * number, print one back, and quote a user's text in a message, in exactly
 * the same way. Private to src/app; not installed. The number writers are
 * in option_text.c; the rest is inline here.
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

/* Above this magnitude a double rounds to a float's infinity: FLT_MAX plus
 * half its last place, 2^128 - 2^103 (a tie rounds to even, and FLT_MAX's
 * last bit is odd). FLT_MAX's own shortest text, 3.4028235e+38, lies above
 * FLT_MAX and below this, and must read back. */
#define OPTION_FLOAT_OVERFLOW 0x1.ffffffp+127

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
        if (!isfinite(values[i]) ||
            (single_precision && fabs(values[i]) >= OPTION_FLOAT_OVERFLOW))
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

/* The shortest decimal that the reader above brings back to exactly the
 * same float (strtod, then a cast to float): "0.2" for 0.2f, "0.98999995"
 * for the float just below 0.99f (which "0.99" would not give back), and
 * never more significant digits than some decimal that does read back.
 * Written as a person writes numbers, "-90" and "0.0015", with an exponent
 * only below 1e-4 and from 1e15 on ("6.711322e-17", "3.4028235e+38").
 * A value that is not finite (a probed pixel's, from NaN normals, say)
 * is written "nan", "inf" or "-inf", which the reader refuses.
 * buffer holds at least OPTION_NUMBER_SIZE bytes. (option_text.c) */
#define OPTION_NUMBER_SIZE 32
void option_format_float(char *buffer, size_t size, float value);

/* The same for a double, read back by strtod alone (the time). */
void option_format_double(char *buffer, size_t size, double value);

#endif
