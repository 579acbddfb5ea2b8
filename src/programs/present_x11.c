/*
 * present_x11.c: showing frames on X11 without copying them on the client.
 *
 * SDL's way to show a frame made on the CPU (a streaming texture and its
 * software renderer) copies the framebuffer into the texture, converts it
 * to the window's pixel order, and then waits while the X server copies
 * the result into the window (SDL calls XSync after XShmPutImage). Against
 * a frame of the default scene that was a third of the time
 * (docs/performance.md, "Measured in the code"), and the renderer's
 * threads sit idle through all of it.
 *
 * Here luz draws each frame straight into an X shared-memory image (the
 * MIT-SHM extension, libXext) in the window's own pixel order, BGRX, so
 * the client copies nothing. There are two images: while the X server
 * copies one into the window, luz draws the next frame into the other.
 * Each copy is asked for with a completion event (XShmPutImage's
 * send_event), and an image is drawn into again only once the X server has
 * reported that it is done with it, which it had a whole frame's time to
 * be; so luz rarely waits, and never for the copy of the frame it has just
 * shown, as an XSync would make it. The X server's copy still takes CPU
 * time, but on a core of its own or between the renderer's bands, not as
 * a pause in the frame.
 *
 * SDL still opens the window and reads its input. This file talks to the
 * X server over a connection of its own to the same display, so that its
 * completion events never pass through SDL's event loop, which would
 * discard them.
 */
#include "present_x11.h"

#include <errno.h>
#include <poll.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/ipc.h>
#include <sys/shm.h>

#include <SDL_syswm.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>

typedef struct shared_image {
    XImage *image;                /* NULL when not made */
    XShmSegmentInfo segment;
    bool attached;                /* the X server has mapped the segment */
    bool being_copied;            /* shown, and its completion not yet seen */
} shared_image;

struct x11_presenter {
    Display *display;             /* our own connection to SDL's display */
    int completion_event;         /* the event type of MIT-SHM's ShmCompletion */
    Window window;
    Visual *visual;
    int depth;
    GC graphics_context;
    int width, height;
    shared_image images[2];
    int next;                     /* the image the next frame is drawn into */
};

/* Xlib reports a failed request (here: XShmAttach on a remote display,
 * which cannot map our memory) to one error handler per process, and its
 * default handler exits. So while the attach is checked, a handler of
 * ours notes the error here. This is the only state outside the
 * presenter, forced by that Xlib interface, and it is only touched on the
 * thread that runs SDL's event loop. */
static bool attach_failed;

static int note_attach_error(Display *display, XErrorEvent *event)
{
    (void)display;
    (void)event;
    attach_failed = true;
    return 0;
}

static void release_image(x11_presenter *presenter, shared_image *shared)
{
    if (shared->attached)
        XShmDetach(presenter->display, &shared->segment);
    if (shared->image != NULL)
        XDestroyImage(shared->image);   /* the XImage only: MIT-SHM's data is ours */
    if (shared->segment.shmaddr != NULL && shared->segment.shmaddr != (char *)-1)
        shmdt(shared->segment.shmaddr);
    memset(shared, 0, sizeof *shared);
}

static void release_images(x11_presenter *presenter)
{
    /* No copy from them is under way after this round trip; completion
     * events still queued are for segments that are gone, and
     * wait_until_copied() passes over them. */
    XSync(presenter->display, False);
    presenter->images[0].being_copied = presenter->images[1].being_copied = false;
    release_image(presenter, &presenter->images[0]);
    release_image(presenter, &presenter->images[1]);
}

static int make_image(x11_presenter *presenter, shared_image *shared, luz_error *why)
{
    const int width = presenter->width, height = presenter->height;
    shared->image = XShmCreateImage(presenter->display, presenter->visual,
                                    (unsigned)presenter->depth, ZPixmap, NULL, &shared->segment,
                                    (unsigned)width, (unsigned)height);
    if (shared->image == NULL)
        return luz_error_set(why, "the X server made no %dx%d shared image", width, height);
    /* luz writes rows of width * 4 bytes, B, G, R, A: the image must be
     * laid out exactly so. */
    if (shared->image->bits_per_pixel != 32 || shared->image->byte_order != LSBFirst ||
        shared->image->bytes_per_line != width * 4)
        return luz_error_set(why, "the window's images are not rows of 32-bit BGRX pixels");

    shared->segment.shmid = shmget(IPC_PRIVATE, (size_t)width * (size_t)height * 4,
                                   IPC_CREAT | 0600);
    if (shared->segment.shmid < 0)
        return luz_error_set(why, "no shared memory for a %dx%d image: %s", width, height,
                             strerror(errno));
    shared->segment.shmaddr = shmat(shared->segment.shmid, NULL, 0);
    if (shared->segment.shmaddr == (char *)-1) {
        int error_number = errno;
        shmctl(shared->segment.shmid, IPC_RMID, NULL);
        return luz_error_set(why, "cannot map shared memory: %s", strerror(error_number));
    }
    shared->image->data = shared->segment.shmaddr;
    shared->segment.readOnly = True;   /* the X server only reads it */

    XSync(presenter->display, False);  /* no earlier error is blamed on the attach */
    attach_failed = false;
    int (*previous_handler)(Display *, XErrorEvent *) = XSetErrorHandler(note_attach_error);
    Status sent = XShmAttach(presenter->display, &shared->segment);
    XSync(presenter->display, False);
    XSetErrorHandler(previous_handler);
    /* Marked for removal now, the segment goes away when both processes
     * have let go of it, even if luz is killed. */
    shmctl(shared->segment.shmid, IPC_RMID, NULL);
    if (!sent || attach_failed)
        return luz_error_set(why, "the X server cannot share memory with luz (a remote display?)");
    shared->attached = true;
    return 0;
}

static int make_images(x11_presenter *presenter, int width, int height, luz_error *why)
{
    presenter->width = width;
    presenter->height = height;
    presenter->next = 0;
    for (int i = 0; i < 2; i++) {
        if (make_image(presenter, &presenter->images[i], why) != 0) {
            release_images(presenter);
            return -1;
        }
    }
    return 0;
}

x11_presenter *x11_presenter_create(SDL_Window *window, int width, int height, luz_error *why)
{
    SDL_SysWMinfo info;
    SDL_VERSION(&info.version);
    if (!SDL_GetWindowWMInfo(window, &info) || info.subsystem != SDL_SYSWM_X11) {
        luz_error_set(why, "not an X11 window");
        return NULL;
    }
    x11_presenter *presenter = calloc(1, sizeof *presenter);
    if (presenter == NULL) {
        luz_error_set(why, "out of memory");
        return NULL;
    }
    presenter->display = XOpenDisplay(DisplayString(info.info.x11.display));
    if (presenter->display == NULL) {
        luz_error_set(why, "cannot open a second connection to the X server");
        free(presenter);
        return NULL;
    }
    Display *display = presenter->display;
    XWindowAttributes attributes;
    if (!XShmQueryExtension(display)) {
        luz_error_set(why, "the X server has no MIT-SHM extension");
        goto failed;
    }
    if (!XGetWindowAttributes(display, info.info.x11.window, &attributes)) {
        luz_error_set(why, "cannot read the window's attributes");
        goto failed;
    }
    /* BGRX: red in bits 16-23 of a little-endian 32-bit pixel. */
    const Visual *visual = attributes.visual;
    if ((attributes.depth != 24 && attributes.depth != 32) || visual->red_mask != 0xff0000 ||
        visual->green_mask != 0x00ff00 || visual->blue_mask != 0x0000ff) {
        luz_error_set(why, "the window's pixels are not 8-bit BGRX");
        goto failed;
    }

    presenter->completion_event = XShmGetEventBase(display) + ShmCompletion;
    presenter->window = info.info.x11.window;
    presenter->visual = attributes.visual;
    presenter->depth = attributes.depth;
    presenter->graphics_context = XCreateGC(display, presenter->window, 0, NULL);
    if (make_images(presenter, width, height, why) != 0) {
        x11_presenter_destroy(presenter);
        return NULL;
    }
    return presenter;

failed:
    XCloseDisplay(presenter->display);
    free(presenter);
    return NULL;
}

int x11_presenter_resize(x11_presenter *presenter, int width, int height, luz_error *error)
{
    if (width == presenter->width && height == presenter->height)
        return 0;
    release_images(presenter);
    return make_images(presenter, width, height, error);
}

/* How long to wait for a completion event before asking the X server
 * directly. The event comes within a frame or two; a server that dropped
 * it must not freeze the viewer. */
#define COMPLETION_WAIT_MS 1000

static double monotonic_ms(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec * 1e3 + (double)now.tv_nsec / 1e6;
}

/* Reads this connection's events until the X server has reported that it
 * has finished copying the image (or, after COMPLETION_WAIT_MS without a
 * word, until a round trip shows that it has). */
static void wait_until_copied(x11_presenter *presenter, shared_image *shared)
{
    Display *display = presenter->display;
    const double deadline = monotonic_ms() + COMPLETION_WAIT_MS;
    while (shared->being_copied) {
        if (XPending(display) == 0) {
            /* Nothing queued: wait on the connection, until the deadline.
             * Past it, XSync: once the server has answered it, it has
             * handled every earlier request, the copy included, so the
             * image is free whether or not its event ever comes. */
            double left = deadline - monotonic_ms();
            struct pollfd connection = {.fd = ConnectionNumber(display), .events = POLLIN};
            if (left <= 0.0 || poll(&connection, 1, (int)left + 1) == 0) {
                XSync(display, False);
                shared->being_copied = false;
                break;
            }
            continue;
        }
        XEvent event;
        XNextEvent(display, &event);
        if (event.type != presenter->completion_event)
            continue;
        const XShmCompletionEvent *done = (const XShmCompletionEvent *)&event;
        for (int i = 0; i < 2; i++) {
            shared_image *image = &presenter->images[i];
            if (image->attached && image->segment.shmseg == done->shmseg)
                image->being_copied = false;
        }
    }
}

uint8_t *x11_presenter_next_image(x11_presenter *presenter)
{
    shared_image *shared = &presenter->images[presenter->next];
    wait_until_copied(presenter, shared);
    return (uint8_t *)shared->image->data;
}

void x11_presenter_show(x11_presenter *presenter)
{
    shared_image *shared = &presenter->images[presenter->next];
    XShmPutImage(presenter->display, presenter->window, presenter->graphics_context,
                 shared->image, 0, 0, 0, 0, (unsigned)presenter->width,
                 (unsigned)presenter->height, True);
    shared->being_copied = true;
    XFlush(presenter->display);
    presenter->next ^= 1;
}

void x11_presenter_destroy(x11_presenter *presenter)
{
    if (presenter == NULL)
        return;
    release_images(presenter);
    XFreeGC(presenter->display, presenter->graphics_context);
    XCloseDisplay(presenter->display);
    free(presenter);
}

/* ---- fullscreen ----------------------------------------------------------------- */

/* Fullscreen on X11 is a request to the window manager (EWMH's
 * _NET_WM_STATE_FULLSCREEN), so it needs one that says it supports it: a
 * window manager announces itself with _NET_SUPPORTING_WM_CHECK on the
 * root window and lists what it supports in _NET_SUPPORTED. */
static bool root_property_lists(Display *display, const char *property, Atom wanted,
                                bool any_value)
{
    Atom type;
    int format;
    unsigned long count, bytes_after;
    unsigned char *data = NULL;
    Atom name = XInternAtom(display, property, True);
    if (name == None)
        return false;
    if (XGetWindowProperty(display, DefaultRootWindow(display), name, 0, 4096, False,
                           AnyPropertyType, &type, &format, &count, &bytes_after,
                           &data) != Success)
        return false;
    bool found = false;
    if (data != NULL && format == 32) {
        /* Xlib hands 32-bit properties back as longs. */
        const long *values = (const long *)data;
        for (unsigned long i = 0; i < count && !found; i++)
            found = any_value || (Atom)values[i] == wanted;
    }
    if (data != NULL)
        XFree(data);
    return found;
}

bool x11_can_go_fullscreen(SDL_Window *window)
{
    SDL_SysWMinfo info;
    SDL_VERSION(&info.version);
    if (!SDL_GetWindowWMInfo(window, &info) || info.subsystem != SDL_SYSWM_X11)
        return true;
    Display *display = info.info.x11.display;
    Atom fullscreen = XInternAtom(display, "_NET_WM_STATE_FULLSCREEN", False);
    return root_property_lists(display, "_NET_SUPPORTING_WM_CHECK", None, true) &&
           root_property_lists(display, "_NET_SUPPORTED", fullscreen, false);
}
