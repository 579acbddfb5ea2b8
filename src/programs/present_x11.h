/*
 * present_x11.h: the viewer's fast way to show a frame on X11, two
 * shared-memory images that luz draws into directly (see present_x11.c).
 */
#ifndef LUZ_PRESENT_X11_H
#define LUZ_PRESENT_X11_H

#include <stdbool.h>
#include <stdint.h>

#include <SDL.h>

#include "luz/error.h"

typedef struct x11_presenter x11_presenter;

/* A presenter for the window at width x height pixels, or NULL with the
 * reason in *why when the window is not an X11 one, or its X server cannot
 * share memory with luz (a remote display, no MIT-SHM) or stores pixels
 * in another order than BGRA; the caller then shows frames through SDL. */
x11_presenter *x11_presenter_create(SDL_Window *window, int width, int height, luz_error *why);

/* New images for a new window size; -1 with a message if that fails. */
int x11_presenter_resize(x11_presenter *presenter, int width, int height, luz_error *error);

/* The image to draw the next frame into: width * height * 4 bytes, rows
 * packed, BGRA (luz's LUZ_CHANNELS_BGRA). The X server is done with it. */
uint8_t *x11_presenter_next_image(x11_presenter *presenter);

/* Shows the image that x11_presenter_next_image returned, and returns at
 * once: the X server copies it into the window while luz draws the next
 * frame into the other image. */
void x11_presenter_show(x11_presenter *presenter);

void x11_presenter_destroy(x11_presenter *presenter);

/* False when window is an X11 window and no window manager is running
 * that can make it fullscreen (a bare Xvfb, say). SDL would then believe
 * the window had the screen's size while it stays as it was, so F11
 * refuses instead. True for any other window. */
bool x11_can_go_fullscreen(SDL_Window *window);

#endif
