/* error.c: filling a luz_error (see luz/error.h). */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "luz/error.h"

int luz_error_set(luz_error *error, const char *format, ...)
{
    if (error) {
        va_list arguments;
        va_start(arguments, format);
        int length = vsnprintf(error->message, sizeof error->message, format, arguments);
        va_end(arguments);
        /* Cut short: say so, rather than end in the middle of a path. */
        if (length >= (int)sizeof error->message)
            memcpy(error->message + sizeof error->message - 4, "...", 4);
    }
    return -1;
}

void luz_error_print(const char *program, const char *message)
{
    fprintf(stderr, "%s: ", program);
    for (const char *c = message; *c != '\0'; c++)
        fputc(((unsigned char)*c < 0x20 || *c == 0x7f) ? '?' : *c, stderr);
    fputc('\n', stderr);
}
