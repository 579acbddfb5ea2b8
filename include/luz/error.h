/*
 * luz/error.h: how luz reports a failure.
 *
 * Functions that can fail on bad input (a file, a size, a number) return a
 * status and fill a luz_error with one line that names the culprit and what
 * was expected, in the style "textures/wood.png: not an image (corrupt PNG
 * header)". Callers print it as it is. Internal invariants use assert().
 */
#ifndef LUZ_ERROR_H
#define LUZ_ERROR_H

#include "luz/api.h"

/* Room for a message that names three paths of up to PATH_MAX (4096) bytes
 * each, such as a scene file, a model it places and a texture the model
 * names, and says what is wrong: a path is never cut short. A longer
 * message, which no path the system can open gives, ends in "...". */
#define LUZ_ERROR_MESSAGE_SIZE (4 * 4096)

typedef struct luz_error {
    char message[LUZ_ERROR_MESSAGE_SIZE];
} luz_error;

/* printf-style; a NULL error is allowed and ignored. Returns -1 so that a
 * failing function can end with `return luz_error_set(error, ...);`. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
LUZ_API int luz_error_set(luz_error *error, const char *format, ...);

/* Prints "program: message" as one line on stderr: control characters in
 * the message (a file name with a newline in it, say) are shown as '?', so
 * that users and tests always see exactly one line. */
LUZ_API void luz_error_print(const char *program, const char *message);

#endif
