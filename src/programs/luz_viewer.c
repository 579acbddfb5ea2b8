/*
 * luz: the interactive viewer. Fly through the lighting lab of SCENE.md
 * (or orbit a model: app/orbit.h), switch its six lights, edit them in a
 * panel, and save what you find as a scene file that luz-render renders at
 * any size.
 *
 *   luz                              the default scene in a 1280x720 window
 *   luz --scene view.luz             a saved view
 *   luz --render-scale 0.5           half the pixels, scaled up: for slow machines
 *   luz --print-state > view.luz     the view at quit, as a scene file
 *
 * SDL2 opens the window and reads the keyboard and mouse. On X11 luz
 * draws each frame straight into the window's shared memory
 * (present_x11.c); elsewhere SDL presents the finished framebuffer through
 * a streaming RGBA texture. Every pixel, the HUD's text and the panel's
 * sliders included, is drawn by luz itself: the 2D layer of app/panel.h
 * is recorded first, then the renderer fills it band by band on top of
 * the scene (luz_renderer_draw with a luz_band_hook). What the keys do is
 * in app/controls.h and what the panel does in app/panel.h, both tested
 * without a window; this file maps SDL's events onto them.
 *
 * Options are luz-render's scene options, read by the same parser
 * (luz_options_parse), plus two of the viewer's own, which are taken out of
 * argv before the shared parser sees the rest: --render-scale S and
 * --print-state. luz-render's --bench N and --fps F mean the same here:
 * the same N frames, drawn and shown in the window, and the same line of
 * results, so that the two programs' frame rates can be compared (tools/
 * viewer-bench). luz-render's file options (-o, --frames, --frame-range,
 * --shard, --skip-existing) are refused: the viewer writes no frames.
 *
 * Exit status: 0 when the window is closed or Esc is pressed; 2 for a bad
 * option, scene file or textures directory, or when no display is
 * available, with one line on stderr; 1 if rendering fails (out of memory).
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <SDL.h>

#include "luz/luz.h"
#include "app/bench.h"
#include "app/controls.h"
#include "app/orbit.h"
#include "app/options.h"
#include "app/quiz.h"
#include "app/panel.h"
#include "app/probe_panel.h"
#include "io/image.h"
#include "io/input_file.h"
#include "io/textures.h"
#include "lab/scene.h"
#ifdef LUZ_VIEWER_X11
#include "present_x11.h"
#endif
#include "x11_display_probe.h"

#ifndef LUZ_VERSION
#error "src/meson.build passes LUZ_VERSION"
#endif

/* The smallest window (docs/viewer.md): every part of the HUD, the light
 * panel and the help fits in it, the help by scrolling. */
#define LUZ_VIEWER_MIN_WIDTH 480
#define LUZ_VIEWER_MIN_HEIGHT 270

enum {
    EXIT_OK = 0,
    EXIT_RUNTIME = 1,   /* rendering failed */
    EXIT_USAGE = 2,     /* bad options or files, or no display */
};

/* ---- the viewer's own options --------------------------------------------------------- */

typedef struct viewer_settings {
    float render_scale;   /* framebuffer pixels per window pixel, in
                             [LUZ_MIN_RENDER_SCALE, 1] */
    bool print_state;
} viewer_settings;

/* Does argument `text` name option `name`, as `--name` or `--name=value`?
 * Sets *value to the text after '=', or NULL. */
static bool names_option(const char *text, const char *name, const char **value)
{
    size_t length = strlen(name);
    if (strncmp(text, name, length) != 0 || (text[length] != '\0' && text[length] != '='))
        return false;
    *value = text[length] == '=' ? text + length + 1 : NULL;
    return true;
}

/* The smallest --render-scale: a 1280x720 window is then drawn from a
 * 13x7 framebuffer, which is still a picture of the scene. */
#define LUZ_MIN_RENDER_SCALE 0.01

static int read_render_scale(const char *text, float *scale, luz_error *error)
{
    char *end;
    errno = 0;
    double value = text && text[0] ? strtod(text, &end) : NAN;
    if (text == NULL || text[0] == '\0' || *end != '\0' || errno != 0 ||
        !(value >= LUZ_MIN_RENDER_SCALE) || value > 1.0)
        return luz_error_set(error,
                             "--render-scale: expected a number from 0.01 to 1, such as 0.5, "
                             "got '%s'",
                             text ? text : "");
    *scale = (float)value;
    return 0;
}

/* Takes the viewer's own options out of argv into settings and leaves the
 * rest, in order, in scene_argv for luz_options_parse(). Refuses
 * luz-render's output options. */
static int split_arguments(int argc, char **argv, viewer_settings *settings, char **scene_argv,
                           int *scene_argc, luz_error *error)
{
    static const char *const batch_only[] = {"-o", "--output", "--frames", "--frame-range",
                                             "--shard", "--skip-existing", "--legend",
                                             "--mark"};
    int count = 0;
    scene_argv[count++] = argv[0];
    for (int i = 1; i < argc; i++) {
        const char *value;
        if (names_option(argv[i], "--print-state", &value)) {
            if (value != NULL)
                return luz_error_set(error, "--print-state: takes no value, got '%s'", value);
            settings->print_state = true;
            continue;
        }
        if (names_option(argv[i], "--render-scale", &value)) {
            if (value == NULL && i + 1 < argc)
                value = argv[++i];
            if (read_render_scale(value, &settings->render_scale, error) != 0)
                return -1;
            continue;
        }
        for (size_t k = 0; k < sizeof batch_only / sizeof batch_only[0]; k++) {
            if (names_option(argv[i], batch_only[k], &value))
                return luz_error_set(error,
                                     "%s: the viewer writes no images; this is a luz-render "
                                     "option",
                                     batch_only[k]);
        }
        scene_argv[count++] = argv[i];
        /* A scene option's value goes with it, so that a value that looks
         * like one of ours (a directory named --print-state) stays a value. */
        if (strncmp(argv[i], "--", 2) == 0 && strchr(argv[i], '=') == NULL && i + 1 < argc &&
            (luz_options_is_scene_key(argv[i] + 2) || strcmp(argv[i], "--scene") == 0))
            scene_argv[count++] = argv[++i];
    }
    scene_argv[count] = NULL;
    *scene_argc = count;
    return 0;
}

static void print_usage(FILE *out)
{
    fprintf(out,
            "Usage: luz [OPTION]...\n"
            "Fly through the luz lighting lab (rotating textured cubes lit by six lights, as\n"
            "SCENE.md describes) in a window, rendered in real time on the CPU, or turn\n"
            "round your own model (--model FILE) with the orbit camera.\n"
            "\n"
            "The scene options are luz-render's (-o, --frames, --frame-range, --shard,\n"
            "--skip-existing, --legend and --mark are luz-render's alone; the viewer\n"
            "refuses them, and shows the view's legend in its HUD; --bench N\n"
            "shows its N frames in the window and prints the same line, window included,\n"
            "then quits):\n");
    luz_options_print_help(out);
    fprintf(out,
            "\n"
            "The viewer's own options:\n"
            "  --render-scale S             render S x the window's pixels, scaled up to\n"
            "                               fill it, 0.01 <= S <= 1 (default: 1)\n"
            "  --print-state                print the view as a scene file on stdout at\n"
            "                               quit\n"
            "\n"
            "Controls (H shows them in the window):\n");
    for (int i = 0; i < luz_controls_help_count; i++)
        fprintf(out, "  %-22s %s\n", luz_controls_help[i].keys, luz_controls_help[i].action);
    fprintf(out,
            "\n"
            "F2 and F12 write into the current directory. Without a display, render the\n"
            "same scenes to PNG files with luz-render.\n"
            "\n"
            "The window is at least %dx%d pixels: a smaller --size opens it at that size,\n"
            "and the HUD, the light panel and the help fit in it (the help scrolls).\n"
            "\n"
            "On X11 at render scale 1, frames are drawn straight into the window's\n"
            "shared memory. LUZ_PRESENT=sdl shows them through SDL instead;\n"
            "LUZ_PRESENT=x11 prints why shared memory cannot be used, if it cannot.\n"
            "\n"
            "Exit status: 0 when the window is closed, 2 for a bad option, scene file or\n"
            "textures directory or when no display is available, 1 if rendering failed.\n",
            LUZ_VIEWER_MIN_WIDTH, LUZ_VIEWER_MIN_HEIGHT);
}

/* ---- the viewer --------------------------------------------------------------------------- */

typedef struct viewer {
    luz_options *options;            /* options->scene is the live scene */
    const luz_texture_set *textures;
    viewer_settings settings;
    luz_camera start_camera;         /* where C goes back to */
    luz_light_switches switches;
    luz_panel panel;
    luz_panel_layout layout;         /* for the framebuffer's size */

    bool running;
    bool panel_open;                 /* else flying: the mouse turns the camera */
    /* O: the orbit camera (app/orbit.h), on at the start when the scene
     * holds a model. The cursor is free; a drag turns the camera round
     * orbit's target and the wheel dollies. */
    bool orbiting;
    bool orbit_dragging;             /* the left button went down on the scene */
    luz_orbit orbit;
    bool paused;
    bool hud_visible;
    bool help_visible;
    luz_help_layout help_layout;     /* for the framebuffer's size */
    int help_first;                  /* the first row shown, when it scrolls */
    bool screenshot_requested;
    luz_step_mode step;              /* G: the frame triangle by triangle */
    /* E: the pixel probe. A click marks a pixel (framebuffer pixels); it is
     * probed every frame while the animation runs, and once more after a
     * click while it is paused. probe holds the last answer, which the
     * panel and the marker show. */
    bool probe_mode;                 /* clicks probe; the cursor is free */
    bool probe_marked;               /* a pixel is marked */
    bool probe_asked;                /* probe on the next frame, paused or not */
    int probe_x, probe_y;            /* the marked pixel */
    luz_pixel_probe probe;
    luz_probe_page probe_page;       /* U: the panel's page */
    bool paused_before_step;         /* the step mode freezes the animation */
    uint32_t step_limit;             /* triangles to draw now, 0 for all */

    /* A frame is shown one of two ways: on X11 at render scale 1, drawn
     * straight into the window's shared memory (present_x11.c); else
     * through SDL, a streaming texture that SDL scales to the window. */
    SDL_Window *window;
#ifdef LUZ_VIEWER_X11
    x11_presenter *x11;
#endif
    SDL_Renderer *presenter;         /* when not x11 */
    SDL_Texture *texture;            /* the framebuffer's size, RGBA8 */
    int shown_width, shown_height;   /* the size the x11 images or the texture have */
    int window_width, window_height; /* the window's size in pixels */

    luz_renderer *renderer;
    luz_lab *lab;                    /* the lab's cube mesh */
    luz_framebuffer *framebuffer;
    luz_frame frame;
    luz_frame_stats stats;
    luz_layer layer;                 /* the HUD, panel, help and message */

    /* the HUD's frame rate and timings, averaged over half a second */
    Uint64 last_counter;
    luz_hud_timing timing;
    double present_ms;               /* showing the last frame */

    char message[640];               /* shown at the bottom for a few seconds */
    double message_seconds_left;
    int next_shot, next_scene;       /* the numbers F12 and F2 try first */
} viewer;

/* Shows message at the bottom of the window (as much of it as v->message
 * holds) and prints it, whole, on stderr. */
static void show_message(viewer *v, const char *message)
{
    snprintf(v->message, sizeof v->message, "%.*s", (int)sizeof v->message - 1, message);
    v->message_seconds_left = 4.0;
    luz_error_print("luz", message);
}

/* The first name `prefix-NNNN.suffix` that no file has, from *number on.
 * Only a first guess: another program may take the name before it is
 * written, which is why the writers below never replace a file and the
 * savers then try the next number. */
static void free_file_name(const char *prefix, const char *suffix, int *number, char *buffer,
                           size_t size)
{
    for (;; (*number)++) {
        snprintf(buffer, size, "%s-%04d.%s", prefix, *number, suffix);
        if (access(buffer, F_OK) != 0)
            return;
    }
}

/* Names taken by another program between the guess and the write, in a
 * row, before a save gives up: a bound, so that a directory being filled
 * as fast as luz looks cannot hold the viewer. */
#define MAX_NAME_RACES 100

/* What a saved scene keeps of the viewer itself: the window's size, at
 * which luz-render renders it, and the pause, which the viewer opens it
 * with (the user's pause: the step mode's own freeze is not saved). */
static void use_viewer_state(viewer *v)
{
    v->options->width = v->window_width;
    v->options->height = v->window_height;
    v->options->paused = v->step.on ? v->paused_before_step : v->paused;
}

/* --print-state: the scene as luz-render should render it. */
static void write_state(viewer *v, FILE *out)
{
    use_viewer_state(v);
    /* Standard output may be a file under ulimit -f: the write then fails
     * (main reports it when it flushes) rather than kill the viewer with
     * SIGXFSZ. */
    luz_held_signals held;
    luz_hold_write_signals(&held, false);
    luz_options_write_scene(v->options, out);
    fflush(out);
    luz_release_write_signals(&held);
}

/* F2: the view as a scene file, written beside the screenshots, complete
 * or not at all (luz_options_save_scene), never over an existing file. */
static void save_scene(viewer *v)
{
    char path[64], message[LUZ_ERROR_MESSAGE_SIZE + 64];
    luz_error error = {{0}};
    use_viewer_state(v);
    int status = LUZ_FILE_EXISTS;
    for (int race = 0; race < MAX_NAME_RACES && status == LUZ_FILE_EXISTS; race++) {
        free_file_name("luz-scene", "luz", &v->next_scene, path, sizeof path);
        status = luz_options_save_scene(v->options, path, false, &error);
    }
    if (status == 0)
        snprintf(message, sizeof message, "saved the view to %s", path);
    else if (status == LUZ_FILE_EXISTS)
        snprintf(message, sizeof message, "cannot save the view: every name up to %s is taken",
                 path);
    else
        snprintf(message, sizeof message, "cannot save the view: %s", error.message);
    show_message(v, message);
}

/* F12: the rendered scene, before the HUD and panel are drawn over it, as
 * a PNG that never replaces an existing file. */
static void save_screenshot(viewer *v, const luz_framebuffer *framebuffer)
{
    char path[64], message[LUZ_ERROR_MESSAGE_SIZE + 64];
    luz_error error = {{0}};
    int status = LUZ_FILE_EXISTS;
    for (int race = 0; race < MAX_NAME_RACES && status == LUZ_FILE_EXISTS; race++) {
        free_file_name("luz-shot", "png", &v->next_shot, path, sizeof path);
        status = luz_framebuffer_write_new_png(framebuffer, path, &error);
    }
    if (status == 0)
        snprintf(message, sizeof message, "wrote %s (%dx%d)", path, framebuffer->width,
                 framebuffer->height);
    else if (status == LUZ_FILE_EXISTS)
        snprintf(message, sizeof message, "screenshot failed: every name up to %s is taken", path);
    else
        snprintf(message, sizeof message, "screenshot failed: %s", error.message);
    show_message(v, message);
}

/* Whether the mouse flies (turns the camera) or points (the light panel,
 * the probe mode). */
static bool cursor_free(const viewer *v)
{
    return v->panel_open || v->probe_mode || v->orbiting;
}

static void update_cursor(const viewer *v)
{
    /* Flying hides the cursor and reports relative motion; a failure (no
     * pointer grab) leaves absolute motion, which still turns the camera. */
    SDL_SetRelativeMouseMode(cursor_free(v) ? SDL_FALSE : SDL_TRUE);
}

static void set_panel_open(viewer *v, bool open)
{
    v->panel_open = open;
    luz_panel_mouse_release(&v->panel);
    update_cursor(v);
}

/* O: the orbit camera on or off. On, it turns round the point of the line
 * of sight nearest to the scene's centre, and the view stays as it is. */
static void set_orbiting(viewer *v, bool on)
{
    luz_scene *scene = &v->options->scene;
    v->orbiting = on;
    v->orbit_dragging = false;
    if (on)
        v->orbit = luz_orbit_from_camera(&scene->camera, luz_scene_bounding_sphere(scene).centre);
    update_cursor(v);
}

/* Home, Shift+O: the whole scene in view (its bounding sphere), from the
 * direction the camera looks in; flying or orbiting, the orbit's target is
 * then the scene's centre. */
static void frame_scene(viewer *v)
{
    luz_scene *scene = &v->options->scene;
    luz_orbit_frame(&v->orbit, &scene->camera, luz_scene_bounding_sphere(scene),
                    (float)v->framebuffer->width / (float)v->framebuffer->height);
}

/* A click in the probe mode: mark the pixel, and probe it on the next
 * frame even while paused. */
static void mark_probe(viewer *v, int x, int y)
{
    v->probe_marked = true;
    v->probe_asked = true;
    v->probe_x = x;
    v->probe_y = y;
}

/* A window position in pixels of the framebuffer, which is smaller than the
 * window with a render scale below 1. */
static void to_framebuffer(const viewer *v, int x, int y, int *fx, int *fy)
{
    int window_width, window_height;
    SDL_GetWindowSize(v->window, &window_width, &window_height);
    *fx = window_width > 0 ? (int)((long long)x * v->framebuffer->width / window_width) : x;
    *fy = window_height > 0 ? (int)((long long)y * v->framebuffer->height / window_height) : y;
}

/* ---- input ----------------------------------------------------------------------------------- */

/* Whether the help is open and too long for the window: then the arrow
 * keys and the wheel scroll it. */
static bool help_scrolls(const viewer *v)
{
    return v->help_visible && v->help_layout.first_max > 0;
}

static void handle_key(viewer *v, const SDL_KeyboardEvent *key)
{
    luz_scene *scene = &v->options->scene;
    bool shift = (key->keysym.mod & KMOD_SHIFT) != 0;
    SDL_Keycode code = key->keysym.sym;

    /* Keys that repeat while held: the cone and the panel's arrows. */
    switch (code) {
    case SDLK_p:
        luz_spot_press(&scene->lights, shift ? LUZ_CONE_WIDEN_INNER : LUZ_CONE_WIDEN_OUTER);
        return;
    case SDLK_m:
        luz_spot_press(&scene->lights, shift ? LUZ_CONE_NARROW_INNER : LUZ_CONE_NARROW_OUTER);
        return;
    case SDLK_UP:
    case SDLK_DOWN:
    case SDLK_LEFT:
    case SDLK_RIGHT:
        if (help_scrolls(v)) {
            if (code == SDLK_UP || code == SDLK_DOWN)
                v->help_first = luz_help_scroll(&v->help_layout, v->help_first,
                                                code == SDLK_UP ? -1 : 1);
        } else if (v->panel_open) {
            luz_panel_key panel_key = code == SDLK_UP     ? LUZ_PANEL_UP
                                      : code == SDLK_DOWN ? LUZ_PANEL_DOWN
                                      : code == SDLK_LEFT ? LUZ_PANEL_LEFT
                                                          : LUZ_PANEL_RIGHT;
            luz_panel_key_press(&v->panel, &scene->lights, panel_key, shift);
        }
        return;
    default:
        break;
    }
    if (key->repeat)
        return;

    if (code >= SDLK_1 && code <= SDLK_6) {
        luz_light_toggle(&scene->lights, &v->switches, (luz_term)(code - SDLK_1));
        return;
    }
    switch (code) {
    case SDLK_ESCAPE: v->running = false; break;
    case SDLK_TAB: set_panel_open(v, !v->panel_open); break;
    case SDLK_c:
        luz_camera_reset(&scene->camera, &v->start_camera);
        if (v->orbiting)
            set_orbiting(v, true);   /* round what the start view looks at */
        break;
    case SDLK_o:
        if (shift)
            frame_scene(v);
        else
            set_orbiting(v, !v->orbiting);
        break;
    case SDLK_HOME: frame_scene(v); break;
    case SDLK_r: luz_lights_reset(&scene->lights, &v->switches); break;
    case SDLK_F5: scene->seed = luz_seed_next(scene->seed, (uint32_t)SDL_GetPerformanceCounter()); break;
    case SDLK_f: scene->filter = luz_filter_next(scene->filter); break;
    case SDLK_v: scene->view = luz_view_next(scene->view, shift); break;
    case SDLK_x: scene->interpolation = luz_interpolation_next(scene->interpolation); break;
    case SDLK_LEFTBRACKET: luz_exposure_step(scene, -1); break;
    case SDLK_RIGHTBRACKET: luz_exposure_step(scene, +1); break;
    case SDLK_n: luz_tone_map_toggle(scene); break;
    case SDLK_b: scene->samples = luz_samples_next(scene->samples); break;
    case SDLK_g:
        /* The step mode freezes the animation, so the triangles keep their
         * order while they are drawn one by one; leaving it restores the
         * animation as it was. */
        v->step = (luz_step_mode){.on = !v->step.on};
        if (v->step.on) {
            v->paused_before_step = v->paused;
            v->paused = true;
        } else {
            v->paused = v->paused_before_step;
        }
        break;
    case SDLK_e:
        if (shift) {
            v->probe_marked = false;
        } else {
            v->probe_mode = !v->probe_mode;
            update_cursor(v);
        }
        break;
    case SDLK_u: v->probe_page = luz_probe_page_next(v->probe_page, shift); break;
    case SDLK_t: v->paused = !v->paused; break;
    case SDLK_i: v->hud_visible = !v->hud_visible; break;
    case SDLK_h:
        v->help_visible = !v->help_visible;
        v->help_first = 0;
        /* The panel is hidden under the help: let go of its slider. */
        luz_panel_mouse_release(&v->panel);
        break;
    case SDLK_F2: save_scene(v); break;
    case SDLK_F12: v->screenshot_requested = true; break;
    case SDLK_F11: {
        bool fullscreen = (SDL_GetWindowFlags(v->window) & SDL_WINDOW_FULLSCREEN) != 0;
#ifdef LUZ_VIEWER_X11
        if (!fullscreen && !x11_can_go_fullscreen(v->window)) {
            show_message(v, "F11: no window manager here can make the window fullscreen");
            break;
        }
#endif
        SDL_SetWindowFullscreen(v->window, fullscreen ? 0 : SDL_WINDOW_FULLSCREEN_DESKTOP);
        break;
    }
    default: break;
    }
}

static void handle_event(viewer *v, const SDL_Event *event)
{
    luz_lights *lights = &v->options->scene.lights;
    int x, y;
    switch (event->type) {
    case SDL_QUIT:
        v->running = false;
        break;
    case SDL_KEYDOWN:
        handle_key(v, &event->key);
        break;
    case SDL_MOUSEMOTION:
        if (!cursor_free(v)) {
            luz_camera_turn(&v->options->scene.camera, (float)event->motion.xrel,
                            (float)event->motion.yrel);
        } else if (v->panel_open && v->panel.dragging >= 0) {
            to_framebuffer(v, event->motion.x, event->motion.y, &x, &y);
            luz_panel_mouse_drag(&v->panel, &v->layout, lights, x);
        } else if (v->orbit_dragging) {
            /* in the window's pixels, whatever the render scale */
            luz_orbit_turn(&v->orbit, &v->options->scene.camera, (float)event->motion.xrel,
                           (float)event->motion.yrel);
        }
        break;
    case SDL_MOUSEBUTTONDOWN:
        /* The help covers the panel (which is not drawn meanwhile): a
         * click on the help must not reach a slider hidden under it. */
        if (!v->help_visible && cursor_free(v) && event->button.button == SDL_BUTTON_LEFT) {
            to_framebuffer(v, event->button.x, event->button.y, &x, &y);
            /* The light panel takes the clicks that land on it; the probe
             * mode the others. */
            bool on_panel = v->panel_open && luz_panel_mouse_press(&v->panel, &v->layout, lights,
                                                                   &v->switches, x, y);
            if (!on_panel && v->probe_mode)
                mark_probe(v, x, y);
            /* the orbit camera takes a drag on the scene */
            else if (!on_panel && v->orbiting)
                v->orbit_dragging = true;
        }
        break;
    case SDL_MOUSEWHEEL:
        if (help_scrolls(v)) {
            v->help_first = luz_help_scroll(&v->help_layout, v->help_first,
                                            event->wheel.y > 0 ? -3 : 3);
        } else if (v->orbiting) {
            /* y > 0 rolls away from the user: closer to the target */
            int notches = event->wheel.y;
            if (event->wheel.direction == SDL_MOUSEWHEEL_FLIPPED)
                notches = -notches;
            luz_orbit_dolly(&v->orbit, &v->options->scene.camera, (float)notches);
        }
        break;
    case SDL_MOUSEBUTTONUP:
        if (event->button.button == SDL_BUTTON_LEFT) {
            luz_panel_mouse_release(&v->panel);
            v->orbit_dragging = false;
        }
        break;
    default:
        break;
    }
}

/* The motion keys held now. Letters are read by what they type (W and Z,
 * A and Q are both there for QWERTY and AZERTY, as in the report), arrows
 * by where they are; the arrows belong to the panel while it is open, and
 * to the help while it is open and scrolls. */
static luz_motion held_motion(const viewer *v)
{
    const Uint8 *keys = SDL_GetKeyboardState(NULL);
#define HELD(keycode) (keys[SDL_GetScancodeFromKey(keycode)] != 0)
    bool arrows = !v->panel_open && !help_scrolls(v);
    bool space = HELD(SDLK_SPACE);
    bool shift = (SDL_GetModState() & KMOD_SHIFT) != 0;
    luz_motion motion = {
        .forward = HELD(SDLK_w) || HELD(SDLK_z) || (arrows && keys[SDL_SCANCODE_UP]),
        .back = HELD(SDLK_s) || (arrows && keys[SDL_SCANCODE_DOWN]),
        .left = HELD(SDLK_a) || HELD(SDLK_q) || (arrows && keys[SDL_SCANCODE_LEFT]),
        .right = HELD(SDLK_d) || (arrows && keys[SDL_SCANCODE_RIGHT]),
        .up = space && !shift,
        .down = space && shift,
    };
#undef HELD
    return motion;
}

/* ---- one frame --------------------------------------------------------------------------------- */

/* Seconds since the last call; the first call gives 0. Feeds the HUD's
 * averages. */
static double tick(viewer *v)
{
    Uint64 now = SDL_GetPerformanceCounter();
    double seconds = v->last_counter ? (double)(now - v->last_counter) /
                                           (double)SDL_GetPerformanceFrequency()
                                     : 0.0;
    v->last_counter = now;
    /* The seconds since the last tick are the last frame's, and so are
     * the renderer's timings in v->stats: counted together. */
    luz_hud_timing_add(&v->timing, seconds, v->stats.geometry_ms, v->stats.raster_ms);
    return seconds;
}

/* The window's size in pixels (which a HiDPI screen may make larger than
 * its size in SDL's units). */
static void measure_window(viewer *v)
{
    if (v->presenter == NULL ||
        SDL_GetRendererOutputSize(v->presenter, &v->window_width, &v->window_height) != 0)
        SDL_GetWindowSize(v->window, &v->window_width, &v->window_height);
}

/* How frames reach the window, for the --bench line. */
static const char *presenter_name(const viewer *v)
{
#ifdef LUZ_VIEWER_X11
    if (v->x11 != NULL)
        return "x11-shm";
#endif
    (void)v;
    return "sdl";
}

/* SDL_SetWindowMinimumSize is a hint to the window manager; with none
 * (a bare X server, a kiosk) a resize below it is granted and the HUD cut
 * off. A window found smaller is made the minimum again, as a window
 * manager would have kept it. */
static void keep_minimum_size(viewer *v)
{
    if (SDL_GetWindowFlags(v->window) & (SDL_WINDOW_FULLSCREEN | SDL_WINDOW_MINIMIZED))
        return;
    int width, height;
    SDL_GetWindowSize(v->window, &width, &height);
    if (width >= LUZ_VIEWER_MIN_WIDTH && height >= LUZ_VIEWER_MIN_HEIGHT)
        return;
    SDL_SetWindowSize(v->window, width < LUZ_VIEWER_MIN_WIDTH ? LUZ_VIEWER_MIN_WIDTH : width,
                      height < LUZ_VIEWER_MIN_HEIGHT ? LUZ_VIEWER_MIN_HEIGHT : height);
}

/* Matches the framebuffer, and the images or the texture that show it, to
 * the window's size in pixels times the render scale. */
static int fit_framebuffer(viewer *v, luz_error *error)
{
    keep_minimum_size(v);
    measure_window(v);
    float scale = v->settings.render_scale;
    int width = (int)lroundf((float)v->window_width * scale);
    int height = (int)lroundf((float)v->window_height * scale);
    width = width < 1 ? 1 : width;
    height = height < 1 ? 1 : height;
    if (width == v->shown_width && height == v->shown_height)
        return 0;
    if (luz_framebuffer_resize(v->framebuffer, width, height, error) != 0)
        return -1;
    v->layout = luz_panel_layout_for(width, height);
    v->help_layout = luz_help_layout_for(width, height);
    v->help_first = luz_help_scroll(&v->help_layout, v->help_first, 0);
#ifdef LUZ_VIEWER_X11
    if (v->x11 != NULL) {
        if (x11_presenter_resize(v->x11, width, height, error) != 0)
            return -1;
        v->shown_width = width;
        v->shown_height = height;
        return 0;
    }
#endif
    if (v->texture != NULL)
        SDL_DestroyTexture(v->texture);
    /* SDL_PIXELFORMAT_RGBA32 is bytes R, G, B, A in memory whatever the
     * machine's byte order: luz's own layout, so the upload is a copy. */
    v->texture = SDL_CreateTexture(v->presenter, SDL_PIXELFORMAT_RGBA32,
                                   SDL_TEXTUREACCESS_STREAMING, width, height);
    if (v->texture == NULL)
        return luz_error_set(error, "cannot create a %dx%d texture: %s", width, height,
                             SDL_GetError());
    v->shown_width = width;
    v->shown_height = height;
    return 0;
}

/* Records the 2D layer over the scene: the help alone when it is open,
 * else the HUD and the panel as they are switched, the HUD kept left of
 * the panel; a message on top of anything. It is recorded before the
 * frame is drawn, so the HUD shows the last frame's timings. */
static int record_overlays(viewer *v, luz_error *error)
{
    luz_layer *layer = &v->layer;
    luz_layer_begin(layer, v->framebuffer->width, v->framebuffer->height);
    if (v->help_visible) {
        luz_help_draw(layer, &v->help_layout, v->help_first);
    } else {
        if (v->hud_visible) {
            luz_hud hud = {
                .frames_per_second = v->timing.frames_per_second,
                .frame_ms = v->timing.frame_ms,
                .geometry_ms = v->timing.geometry_ms,
                .raster_ms = v->timing.raster_ms,
                .window_width = v->window_width,
                .window_height = v->window_height,
                .render_scale = v->settings.render_scale,
                .threads = luz_renderer_thread_count(v->renderer),
                .paused = v->paused,
                .panel_open = v->panel_open,
                .orbiting = v->orbiting,
                .orbit_distance = v->orbit.distance,
                .step_shown = v->step_limit,
                .step_total = v->stats.triangles_rasterised,
                .triangles = v->stats.triangles_submitted,
                .scene = &v->options->scene,
                /* left of the open panel, with a margin's gap */
                .max_width = v->panel_open ? v->layout.box.x : 0,
            };
            luz_hud_draw(layer, &hud);
        }
        /* The probe's last answer: its pixel marked, its story in the
         * bottom-left corner. */
        if (v->probe_marked && v->probe.filled) {
            const luz_probe_names names = {.scene = &v->options->scene, .textures = v->textures};
            luz_probe_panel_draw(layer, &v->probe, &names, v->paused && !v->probe_asked,
                                 v->probe_page);
            luz_probe_marker_draw(layer, v->probe.x, v->probe.y);
        }
        if (v->panel_open)
            luz_panel_draw(layer, &v->layout, &v->panel, &v->options->scene.lights,
                           luz_scene_output(&v->options->scene));
    }
    if (v->message_seconds_left > 0.0)
        luz_hud_draw_message(layer, v->message);
    if (luz_layer_finish(layer) != 0)
        return luz_error_set(error, "out of memory for the HUD and panel");
    return 0;
}

/* The renderer's hook: the 2D layer's share of a band, filled by the
 * thread that has just shaded it. */
static void fill_layer_rows(void *context, luz_framebuffer *framebuffer, int first_row,
                            int end_row)
{
    luz_layer_draw_rows(context, framebuffer, first_row, end_row);
}

/* One frame: the scene as luz-render would draw it with the 2D layer on
 * top, filled band by band by the renderer's threads, then shown. A frame
 * that F12 asked for is drawn without the layer, saved (the scene alone),
 * and then gets its layer in one pass.
 *
 * Frames are drawn and shown in turn, not pipelined on a second thread:
 * the renderer already keeps every core busy, and a render thread drawing
 * frame k + 1 while frame k is shown measured slower under Xvfb, where
 * showing a frame mostly waits for the X server's copy, which then has to
 * compete with the renderer for a core. */
static int draw_frame(viewer *v, luz_error *error)
{
    if (fit_framebuffer(v, error) != 0)
        return -1;
#ifdef LUZ_VIEWER_X11
    if (v->x11 != NULL)
        luz_framebuffer_use_colour(v->framebuffer, x11_presenter_next_image(v->x11),
                                   LUZ_CHANNELS_BGRA);
#endif
    float aspect = (float)v->framebuffer->width / (float)v->framebuffer->height;
    if (luz_scene_build_frame(v->lab, &v->options->scene, v->textures->textures,
                              v->textures->count, aspect, &v->frame, error) != 0)
        return -1;
    if (record_overlays(v, error) != 0)
        return -1;
    const luz_band_hook fill_layer = {fill_layer_rows, &v->layer};
    const bool screenshot = v->screenshot_requested;
    luz_render_options render = luz_scene_render_options(&v->options->scene);
    render.triangle_limit = v->step_limit;
    render.hook = screenshot ? NULL : &fill_layer;
    render.stats = &v->stats;
    render.colour_only = true;   /* the window shows colour alone */
    /* The marked pixel, followed as the scene moves; while paused, its
     * story stays as it was, unless a click asks again. A pixel that a
     * smaller window has left is forgotten. */
    if (v->probe_marked &&
        (v->probe_x >= v->framebuffer->width || v->probe_y >= v->framebuffer->height))
        v->probe_marked = false;
    const bool probing = v->probe_marked && (!v->paused || v->probe_asked);
    if (probing) {
        v->probe.x = v->probe_x;
        v->probe.y = v->probe_y;
        render.probe = &v->probe;
    }
    if (luz_renderer_draw(v->renderer, &v->frame, v->framebuffer, &render, error) != 0)
        return -1;
    if (probing)
        v->probe_asked = false;
    if (screenshot) {
        v->screenshot_requested = false;
        save_screenshot(v, v->framebuffer);
        luz_layer_draw(&v->layer, v->framebuffer);
    }
    double present_start = luz_wall_ms();
#ifdef LUZ_VIEWER_X11
    if (v->x11 != NULL) {
        x11_presenter_show(v->x11);
        v->present_ms = luz_wall_ms() - present_start;
        return 0;
    }
#endif
    SDL_UpdateTexture(v->texture, NULL, v->framebuffer->colour, v->framebuffer->width * 4);
    SDL_RenderCopy(v->presenter, v->texture, NULL, NULL);
    SDL_RenderPresent(v->presenter);
    v->present_ms = luz_wall_ms() - present_start;
    return 0;
}

static int run(viewer *v, luz_error *error)
{
    v->running = true;
    while (v->running) {
        SDL_Event event;
        /* A minimised window shows nothing: wait for events instead of
         * rendering frames nobody sees. */
        if (SDL_GetWindowFlags(v->window) & SDL_WINDOW_MINIMIZED) {
            if (SDL_WaitEventTimeout(&event, 100))
                handle_event(v, &event);
            v->last_counter = 0;   /* no time passes while hidden */
        }
        while (SDL_PollEvent(&event))
            handle_event(v, &event);
        if (!v->running || (SDL_GetWindowFlags(v->window) & SDL_WINDOW_MINIMIZED))
            continue;

        /* Motion and animation follow the clock, not the frame count. A
         * long stall (the window dragged, the machine busy) counts as at
         * most half a second, so the camera never leaps. */
        double seconds = tick(v);
        if (seconds > 0.5)
            seconds = 0.5;
        if (v->orbiting)
            luz_orbit_move(&v->orbit, &v->options->scene.camera, held_motion(v), (float)seconds);
        else
            luz_camera_move(&v->options->scene.camera, held_motion(v), (float)seconds);
        /* The animation stops at the options' last time (about 32 years
         * on), so that a saved view always reads back. */
        if (!v->paused && v->options->scene.time_seconds < LUZ_SCENE_MAX_TIME)
            v->options->scene.time_seconds =
                fmin(v->options->scene.time_seconds + seconds, LUZ_SCENE_MAX_TIME);
        /* The step mode's count grows with time; the frame's triangles
         * are the last frame's (the scene is frozen meanwhile). */
        v->step_limit = luz_step_advance(&v->step, seconds, v->stats.triangles_rasterised);
        v->message_seconds_left -= seconds;

        if (draw_frame(v, error) != 0)
            return -1;
    }
    return 0;
}

/* --bench N: luz-render --bench N's frames (one warm-up frame at --time,
 * then frame k at --time + k / --fps), each drawn and shown as run() does,
 * events included, and luz-render's line of results for them, window
 * included, so that tools/viewer-bench can set the two side by side. Time
 * follows that schedule, not the clock, and the camera stays put, so the
 * frames are luz-render's own. present_ms is what showing a frame costs on
 * top of drawing it (the copy to the window, the X server's copy); the 2D
 * layer is filled within raster_ms, band by band.
 * Esc or closing the window ends the run early; the line then covers the
 * frames shown so far. */
static int bench_frame(void *context, double time_seconds, double parts[LUZ_BENCH_MAX_PARTS],
                       luz_error *error)
{
    viewer *v = context;
    SDL_Event event;
    while (SDL_PollEvent(&event))
        handle_event(v, &event);
    if (!v->running)
        return 1;
    tick(v);   /* for the HUD */
    v->options->scene.time_seconds = time_seconds;
    if (draw_frame(v, error) != 0)
        return -1;
    parts[0] = v->stats.geometry_ms;
    parts[1] = v->stats.raster_ms;
    parts[2] = v->present_ms;
    return 0;
}

static int run_bench(viewer *v, luz_error *error)
{
    luz_bench measured = {.part_names = {"geometry_ms", "raster_ms", "present_ms"}};
    v->running = true;
    if (luz_bench_run(&measured, v->options->bench_frames, v->options->scene.time_seconds,
                      v->options->frames_per_second, bench_frame, v, error) != 0) {
        luz_bench_free(&measured);
        return -1;
    }
    if (measured.frames > 0) {
        luz_bench_print_case(stdout, v->options, measured.frames, v->window_width,
                             v->window_height, luz_renderer_thread_count(v->renderer),
                             luz_bench_triangles(&v->frame), luz_renderer_isa(v->renderer));
        if (v->settings.render_scale != 1.0f)
            printf("render_scale=%g ", v->settings.render_scale);
        printf("present=%s ", presenter_name(v));
        luz_bench_print_figures(stdout, &measured);
        printf("\n");
    }
    luz_bench_free(&measured);
    return 0;
}

/* ---- start-up ----------------------------------------------------------------------------------- */

/* Opens the window and picks how frames reach it. On X11 at render scale 1,
 * luz draws into the window's shared memory itself (present_x11.c), which
 * copies nothing on the client. Otherwise SDL shows a texture: on X11
 * through SDL's software renderer, since luz's pixels are made on the CPU
 * anyway, and where OpenGL is Mesa's llvmpipe (Xvfb, a machine without a
 * GPU) its textured quad costs several times the plain copy's CPU time
 * (docs/performance.md, "Measured in the code"). LUZ_PRESENT=sdl asks
 * for SDL's way on X11 too, and the environment (SDL_RENDER_DRIVER,
 * SDL_FRAMEBUFFER_ACCELERATION) still overrides SDL's choice of
 * renderer. */
/* Whether WAYLAND_DISPLAY names a socket that is there, where libwayland
 * looks for it: the name itself when absolute, else in $XDG_RUNTIME_DIR.
 * Without one, asking libwayland for a display only adds its own complaint
 * on stderr ("XDG_RUNTIME_DIR is invalid or not set") to luz's one line. */
static bool wayland_socket_exists(void)
{
    const char *name = getenv("WAYLAND_DISPLAY");
    if (name == NULL || name[0] == '\0')
        return false;
    char path[PATH_MAX];
    const char *runtime = getenv("XDG_RUNTIME_DIR");
    int written;
    if (name[0] == '/')
        written = snprintf(path, sizeof path, "%s", name);
    else if (runtime != NULL && runtime[0] != '\0')
        written = snprintf(path, sizeof path, "%s/%s", runtime, name);
    else
        return false;
    struct stat status;
    return written > 0 && (size_t)written < sizeof path && stat(path, &status) == 0 &&
           S_ISSOCK(status.st_mode);
}

static int open_window(viewer *v, luz_error *error)
{
    SDL_SetHint(SDL_HINT_RENDER_VSYNC, "0");          /* as fast as it renders */
    SDL_SetHint(SDL_HINT_RENDER_SCALE_QUALITY, "nearest");   /* luz's own pixels */
    SDL_SetHint(SDL_HINT_VIDEO_MINIMIZE_ON_FOCUS_LOSS, "0");
    /* Without a Wayland socket to reach, try X11 alone, unless the user
     * chose a driver. */
    const char *asked = getenv("SDL_VIDEODRIVER");
    const bool x11_only = (asked == NULL || asked[0] == '\0') ? !wayland_socket_exists()
                                                              : strcmp(asked, "x11") == 0;
    if (x11_only && (asked == NULL || asked[0] == '\0'))
        SDL_SetHint(SDL_HINT_VIDEODRIVER, "x11");
    /* Xlib waits for an X server's first answer without a limit: a server
     * that hangs, or a network path that drops its packets, would keep
     * luz waiting with no window and no word. Ask it first, for a
     * second. */
    const char *display = getenv("DISPLAY");
    char silent[1024];
    if (x11_only && display != NULL && display[0] != '\0' &&
        !luz_x11_display_answers(display, 1.0, silent, sizeof silent))
        return luz_error_set(error,
                             "cannot open a window: no display available (%s); luz-render "
                             "renders the same scene to PNG files",
                             silent);
    /* SDL turns SIGINT and SIGTERM into an event, with handlers it
     * installs as its event subsystem starts. While the video subsystem
     * connects, nobody reads events, and Xlib may still wait on a server
     * that answered the probe but not Xlib: the signals would only be
     * noted, and the viewer hang on. So the events start first, and the
     * two signals end the process, as by default, until the connection is
     * made; then SDL's handlers are back. */
    if (SDL_Init(SDL_INIT_EVENTS) != 0)
        return luz_error_set(error, "cannot start SDL's events: %s", SDL_GetError());
    struct sigaction sdl_interrupt, sdl_terminate, by_default = {.sa_handler = SIG_DFL};
    sigemptyset(&by_default.sa_mask);
    sigaction(SIGINT, &by_default, &sdl_interrupt);
    sigaction(SIGTERM, &by_default, &sdl_terminate);
    const int video = SDL_InitSubSystem(SDL_INIT_VIDEO);
    sigaction(SIGINT, &sdl_interrupt, NULL);
    sigaction(SIGTERM, &sdl_terminate, NULL);
    if (video != 0)
        return luz_error_set(error,
                             "cannot open a window: no display available (%s); luz-render "
                             "renders the same scene to PNG files",
                             SDL_GetError());
    const char *driver = SDL_GetCurrentVideoDriver();
    /* With no display to reach, SDL falls back to drivers that show
     * nothing (offscreen, dummy): a window nobody can see, rendered into
     * forever. Only a user who asked for such a driver gets one. */
    if ((asked == NULL || asked[0] == '\0') && driver != NULL &&
        (strcmp(driver, "offscreen") == 0 || strcmp(driver, "dummy") == 0))
        return luz_error_set(error,
                             "cannot open a window: no display available (no X11 or Wayland "
                             "display could be reached); luz-render renders the same scene to "
                             "PNG files");
    if (driver != NULL && strcmp(driver, "x11") == 0) {
        SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
        SDL_SetHint(SDL_HINT_RENDER_DRIVER, "software");
    }
    v->window = SDL_CreateWindow("luz", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                                 v->options->width, v->options->height, SDL_WINDOW_RESIZABLE);
    if (v->window == NULL)
        return luz_error_set(error, "cannot open a %dx%d window: %s", v->options->width,
                             v->options->height, SDL_GetError());
    /* The HUD, the panel and the help are laid out for any window from
     * this size up; SDL makes a smaller --size this size. */
    SDL_SetWindowMinimumSize(v->window, LUZ_VIEWER_MIN_WIDTH, LUZ_VIEWER_MIN_HEIGHT);
#ifdef LUZ_VIEWER_X11
    const char *wanted = getenv("LUZ_PRESENT");
    if (v->settings.render_scale == 1.0f && !(wanted != NULL && strcmp(wanted, "sdl") == 0)) {
        luz_error why = {{0}};
        int width, height;
        SDL_GetWindowSize(v->window, &width, &height);
        v->x11 = x11_presenter_create(v->window, width, height, &why);
        if (v->x11 != NULL) {
            measure_window(v);
            return 0;   /* the first frame's fit_framebuffer lays out the panel */
        }
        /* Not an error: SDL shows the frames instead, a little slower. */
        if (wanted != NULL && strcmp(wanted, "x11") == 0)
            luz_error_print("luz", why.message);
    }
#endif
    v->presenter = SDL_CreateRenderer(v->window, -1, 0);
    if (v->presenter == NULL)
        return luz_error_set(error, "cannot draw into the window: %s", SDL_GetError());
    measure_window(v);
    return 0;
}

int main(int argc, char **argv)
{
    luz_options options;
    luz_texture_set textures = {0};
    luz_model_set models = {0};
    viewer v = {
        .options = &options,
        .textures = &textures,
        .settings = {.render_scale = 1.0f},
        .hud_visible = true,
        .next_shot = 1,
        .next_scene = 1,
    };
    luz_error error = {{0}};
    int status = EXIT_USAGE;
    bool answer_wrong = false;
    char **scene_argv = calloc((size_t)argc + 1, sizeof *scene_argv);
    int scene_argc = 0;

    luz_options_init(&options);
    /* The viewer anti-aliases unless told otherwise (--samples 1, a scene
     * file's samples 1): on the default scene at 1280x720 on two threads,
     * four samples are well within the 60 fps issue 27 asks of them
     * (tools/viewer-bench; docs/performance.md, "Four samples a pixel").
     * luz-render keeps one, so every image made before stays the same. */
    options.scene.samples = 4;
    if (scene_argv == NULL) {
        luz_error_set(&error, "out of memory");
        goto done;
    }
    if (split_arguments(argc, argv, &v.settings, scene_argv, &scene_argc, &error) != 0 ||
        luz_options_parse(&options, scene_argc, scene_argv, &error) != 0)
        goto done;
    if (options.help) {
        print_usage(stdout);
        status = EXIT_OK;
        goto done;
    }
    if (options.version) {
        printf("luz %s\n", LUZ_VERSION);
        status = EXIT_OK;
        goto done;
    }
    /* As luz-render: answered without a window (app/quiz.h). */
    if (options.bug_help) {
        luz_quiz_print_bugs(stdout);
        status = EXIT_OK;
        goto done;
    }
    if (options.answer_given) {
        answer_wrong = luz_quiz_answer(stdout, options.quiz_seed, options.answer) != 0;
        status = EXIT_OK;
        goto done;
    }
    /* LUZ_ISA names the renderer's instruction set: a bad one is a usage
     * error, refused before a window opens. */
    if (luz_isa_check(&error) != 0)
        goto done;
    /* The run's texture budget, shared by the cube textures and the
     * models' (io/textures.h). */
    luz_texture_budget budget = {0};
    int loaded = luz_options_load_textures(&options, &textures, &budget, &error);
    if (loaded == 0) loaded = luz_options_load_models(&options, &models, &budget, &error);
    if (loaded != 0) {
        /* out of memory is the machine's failure, not the input's */
        if (loaded == LUZ_MACHINE_FAILED) status = EXIT_RUNTIME;
        goto done;
    }
    if (open_window(&v, &error) != 0)
        goto done;

    status = EXIT_RUNTIME;
    v.start_camera = options.scene.camera;
    v.paused = options.paused;   /* a view saved while paused opens paused */
    if (options.probe)
        mark_probe(&v, options.probe_x, options.probe_y);
    luz_panel_init(&v.panel);
    const luz_renderer_desc desc = luz_options_renderer_desc(&options);
    v.renderer = luz_renderer_create(&desc, &error);
    if (v.renderer == NULL)
        goto done;
    v.lab = luz_lab_create(&error);
    if (v.lab == NULL)
        goto done;
    v.framebuffer = luz_framebuffer_create(options.width, options.height, &error);
    if (v.framebuffer == NULL)
        goto done;
    set_panel_open(&v, false);
    /* A model is looked at from round it; the lab is flown through. */
    bool holds_model = false;
    for (int i = 0; options.scene.objects && i < options.scene.object_count; i++)
        holds_model = holds_model || options.scene.objects[i].model != NULL;
    set_orbiting(&v, holds_model);
    if ((options.bench_frames > 0 ? run_bench(&v, &error) : run(&v, &error)) != 0)
        goto done;
    if (v.settings.print_state)
        write_state(&v, stdout);
    status = EXIT_OK;

done:
    if (status != EXIT_OK)
        luz_error_print("luz", error.message[0] ? error.message : "failed");
    luz_frame_free(&v.frame);
    if (v.framebuffer != NULL)
        luz_framebuffer_destroy(v.framebuffer);
    luz_layer_free(&v.layer);
    if (v.renderer != NULL)
        luz_renderer_destroy(v.renderer);
    luz_lab_destroy(v.lab);
#ifdef LUZ_VIEWER_X11
    x11_presenter_destroy(v.x11);
#endif
    if (v.texture != NULL)
        SDL_DestroyTexture(v.texture);
    if (v.presenter != NULL)
        SDL_DestroyRenderer(v.presenter);
    if (v.window != NULL)
        SDL_DestroyWindow(v.window);
    SDL_Quit();
    luz_model_set_free(&models);
    luz_texture_set_free(&textures);
    luz_options_free(&options);
    free(scene_argv);
    /* ferror too: a write that failed earlier (--print-state past
     * ulimit -f) leaves nothing for this flush to fail on */
    if ((fflush(stdout) != 0 || ferror(stdout)) && status == EXIT_OK) {
        luz_error_print("luz", "cannot write to standard output");
        status = EXIT_RUNTIME;
    }
    return status == EXIT_OK && answer_wrong ? EXIT_RUNTIME : status;
}
