/*
 * programs/x11_display_probe.h: does the X server DISPLAY names answer?
 * (x11_display_probe.c: the viewer asks before SDL's Xlib would wait for it
 * without a limit.)
 */
#ifndef LUZ_PROGRAMS_X11_DISPLAY_PROBE_H
#define LUZ_PROGRAMS_X11_DISPLAY_PROBE_H

#include <stdbool.h>
#include <stddef.h>

/* True when a server at display answered the X11 setup request within
 * seconds, or display is a form left to Xlib; false with why (one phrase
 * naming the display and what happened) otherwise. */
bool luz_x11_display_answers(const char *display, double seconds, char *why, size_t why_size);

#endif
