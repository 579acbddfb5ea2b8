/*
 * programs/x11_display_probe.h: does the X server DISPLAY names answer?
 * (x11_display_probe.c: the viewer asks before SDL's Xlib would wait for it
 * without a limit.)
 */
#ifndef LUZ_PROGRAMS_X11_DISPLAY_PROBE_H
#define LUZ_PROGRAMS_X11_DISPLAY_PROBE_H

#include <stdbool.h>
#include <stddef.h>

/* False, with why (one phrase naming the display and what happened), when
 * a connection to display is taken and the X11 setup request gets no
 * whole answer within seconds (nothing, a part of one: Xlib would wait
 * forever), or bytes no X server sends; true otherwise (a whole answer,
 * or a failure Xlib reports itself at once, or a display form left to
 * Xlib). */
bool luz_x11_display_answers(const char *display, double seconds, char *why, size_t why_size);

#endif
