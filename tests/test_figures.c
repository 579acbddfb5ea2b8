/*
 * test_figures.c: tools/figures makes every picture of the gallery, and each
 * of the report's figures shows its one light term and nothing else.
 *
 * usage: test-figures FIGURES_SCRIPT LUZ_RENDER
 *
 * The script runs into a temporary directory with --manifest, which lists
 * every picture with its size, the light term it shows alone (or -) and its
 * luz-render arguments. Then:
 *
 * 1. Every picture is a PNG of the size the manifest says.
 *
 * 2. Every single-term figure, pixel by pixel, against its term. The
 *    geometry is worked out here, independently of the renderer, from
 *    SCENE.md in double precision: a ray from the eye through each pixel
 *    centre (the camera's yaw, pitch and field of view), the ten cubes
 *    (position, angle (i + 1)/3 · t · 50° about normalize(1, 0.5, 1)) and
 *    the point light's marker, intersected as boxes. That gives, at each
 *    pixel, the nearest face, the point P and the normal N. The term is
 *    SCENE.md's equation evaluated at P and N (written out again below, not
 *    taken from luz/shade.h). What the term multiplies, C · T (the cube's
 *    colour times its filtered texel), comes from the same frame rendered
 *    with the ambient light at 1 and every other light at 0, which shows
 *    exactly C · T, rounded to bytes.
 *
 *    So a figure pixel must be round(term · C · T · 255), and with
 *    A = round(C · T · 255) it lies within 0.5 + 0.5 · term (the two
 *    roundings) of term · A; a little slack covers float against double.
 *    Another term leaking in (ambient's 0.2 · A, say) is tens of levels.
 *    Pixels whose 3x3 neighbours do not all see the same face are skipped
 *    (edges and silhouettes, where a sample's side of an edge is decided
 *    by a sub-pixel snap), the background must be the clear colour, and
 *    the marker its light's colour.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <stb_image.h>

#include "luz/luz.h"
#include "app/bench.h"
#include "app/controls.h"
#include "app/options.h"
#include "app/panel.h"
#include "io/image.h"
#include "io/textures.h"
#include "lab/scene.h"
#include "lab_support.h"

#define MAX_FIGURES 64
#define MAX_ARGUMENTS 32
#define BACKGROUND 26   /* round(0.1 * 255) */

typedef struct figure {
    char name[64];
    int width, height;
    char term[32];          /* "-" for pictures that are not one term */
    char arguments[1024];
} figure;

static const char *figures_script, *luz_render;
static char directory[256];
static figure figures[MAX_FIGURES];
static int figure_count;

/* ---- running tools/figures ------------------------------------------------ */

static int run_figures(void **state)
{
    (void)state;
    const char *tmp = getenv("TMPDIR");
    snprintf(directory, sizeof directory, "%s/luz-figures.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(directory)) return -1;
    char command[2048];
    snprintf(command, sizeof command,
             "sh '%s' --luz-render '%s' --out '%s' --manifest '%s/manifest.tsv' >/dev/null",
             figures_script, luz_render, directory, directory);
    if (system(command) != 0) {
        fprintf(stderr, "test-figures: %s failed\n", command);
        return -1;
    }

    char path[512];
    snprintf(path, sizeof path, "%s/manifest.tsv", directory);
    FILE *manifest = fopen(path, "r");
    if (!manifest) return -1;
    char line[2048];
    while (fgets(line, sizeof line, manifest) && figure_count < MAX_FIGURES) {
        figure *f = &figures[figure_count];
        line[strcspn(line, "\n")] = '\0';
        char *fields[5];
        char *cursor = line;
        for (int i = 0; i < 5; i++) {
            fields[i] = cursor;
            cursor = i < 4 ? strchr(cursor, '\t') : NULL;
            if (i < 4) {
                if (!cursor) return -1;
                *cursor++ = '\0';
            }
        }
        /* A field too long for its buffer is a broken list, not a name to cut. */
        if (snprintf(f->name, sizeof f->name, "%s", fields[0]) >= (int)sizeof f->name ||
            snprintf(f->term, sizeof f->term, "%s", fields[3]) >= (int)sizeof f->term ||
            snprintf(f->arguments, sizeof f->arguments, "%s", fields[4]) >=
                (int)sizeof f->arguments)
            return -1;
        f->width = atoi(fields[1]);
        f->height = atoi(fields[2]);
        figure_count++;
    }
    fclose(manifest);
    return figure_count > 0 ? 0 : -1;
}

static int remove_figures(void **state)
{
    (void)state;
    char command[512];
    snprintf(command, sizeof command, "rm -rf '%s'", directory);
    return system(command) == 0 ? 0 : -1;
}

static unsigned char *load_figure(const figure *f, int *width, int *height)
{
    char path[512];
    int channels;
    snprintf(path, sizeof path, "%.255s/%.63s.png", directory, f->name);
    return stbi_load(path, width, height, &channels, 3);
}

/* ---- 1. every picture ------------------------------------------------------- */

static void test_every_picture_is_a_png_of_its_size(void **state)
{
    (void)state;
    /* The report's nine figures and at least one picture per view. */
    int single_term = 0;
    for (int i = 0; i < figure_count; i++) single_term += strcmp(figures[i].term, "-") != 0;
    assert_int_equal(single_term, 12);   /* the report's figures 1 to 8, and 9 as four times */
    for (int v = 0; v < LUZ_VIEW_COUNT; v++) {
        char name[64];
        snprintf(name, sizeof name, "view-%s", luz_view_name((luz_view)v));
        bool found = false;
        for (int i = 0; i < figure_count; i++) found |= strcmp(figures[i].name, name) == 0;
        if (!found) fail_msg("no picture %s", name);
    }
    for (int i = 0; i < figure_count; i++) {
        int width, height;
        unsigned char *rgb = load_figure(&figures[i], &width, &height);
        if (!rgb) fail_msg("%s.png is not a PNG stb_image reads", figures[i].name);
        if (width != figures[i].width || height != figures[i].height)
            fail_msg("%s.png is %dx%d, expected %dx%d", figures[i].name, width, height,
                     figures[i].width, figures[i].height);
        stbi_image_free(rgb);
    }
}

/* ---- 2. the single-term figures --------------------------------------------- */

typedef struct dvec { double x, y, z; } dvec;

static dvec dv(double x, double y, double z) { return (dvec){x, y, z}; }
static dvec add(dvec a, dvec b) { return dv(a.x + b.x, a.y + b.y, a.z + b.z); }
static dvec sub(dvec a, dvec b) { return dv(a.x - b.x, a.y - b.y, a.z - b.z); }
static dvec scale(dvec a, double s) { return dv(a.x * s, a.y * s, a.z * s); }
static double dot(dvec a, dvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static dvec cross(dvec a, dvec b)
{
    return dv(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static dvec normalize(dvec a) { return scale(a, 1.0 / sqrt(dot(a, a))); }
static dvec from_float(luz_vec3 v) { return dv(v.x, v.y, v.z); }

/* A box: centre, rotation (columns are its local axes in world space) and
 * half-size. */
typedef struct box {
    dvec centre;
    dvec axis[3];
    double half;
} box;

/* SCENE.md's ten cube positions. */
static const double positions[10][3] = {
    {0.0, 0.0, 0.0},   {2.0, 5.0, -15.0}, {-1.5, -2.2, -2.5}, {-3.8, -2.0, -12.3},
    {2.4, -0.4, -3.5}, {-1.7, 3.0, -7.5}, {1.3, -2.0, -2.5},  {1.5, 2.0, -2.5},
    {1.5, 0.2, -1.5},  {-1.3, 1.0, -1.5},
};

/* Rodrigues: the right-handed rotation by angle about unit axis k, applied
 * to the basis vectors. */
static box cube_at(int i, double t)
{
    box b;
    b.centre = dv(positions[i][0], positions[i][1], positions[i][2]);
    b.half = 0.5;
    double angle = (i + 1) / 3.0 * t * 50.0 * LUZ_PI / 180.0;
    dvec k = normalize(dv(1.0, 0.5, 1.0));
    double c = cos(angle), s = sin(angle);
    for (int a = 0; a < 3; a++) {
        dvec e = dv(a == 0, a == 1, a == 2);
        b.axis[a] = add(add(scale(e, c), scale(cross(k, e), s)), scale(k, dot(k, e) * (1 - c)));
    }
    return b;
}

typedef struct hit {
    int id;          /* box * 6 + face + 1; 0 none */
    dvec point, normal;
    bool marker;
} hit;

/* Ray (origin, direction) against a box: the entry point and its face. */
static bool intersect(const box *b, int box_index, dvec origin, dvec direction, double *t,
                      hit *out)
{
    dvec o = sub(origin, b->centre);
    double near = -INFINITY, far = INFINITY;
    int entry_axis = 0;
    double entry_sign = 0;
    for (int a = 0; a < 3; a++) {
        double oa = dot(o, b->axis[a]), da = dot(direction, b->axis[a]);
        if (fabs(da) < 1e-300) {
            if (fabs(oa) > b->half) return false;
            continue;
        }
        double t1 = (-b->half - oa) / da, t2 = (b->half - oa) / da;
        double lo = t1 < t2 ? t1 : t2, hi = t1 < t2 ? t2 : t1;
        if (lo > near) {
            near = lo;
            entry_axis = a;
            entry_sign = da > 0 ? -1.0 : 1.0;
        }
        if (hi < far) far = hi;
    }
    if (!(near <= far) || near <= 0 || near >= *t) return false;
    *t = near;
    out->id = box_index * 6 + entry_axis * 2 + (entry_sign > 0) + 1;
    out->point = add(origin, scale(direction, near));
    out->normal = scale(b->axis[entry_axis], entry_sign);
    return true;
}

/* SCENE.md's fragment equations, in double precision: the one term. */
static dvec term_at(const char *term, const luz_scene *scene, dvec p, dvec n, dvec eye,
                    dvec front, dvec point_light, dvec sun)
{
    const luz_lights *l = &scene->lights;
    const luz_light *light;
    double f = 0.0;
    dvec to_eye = normalize(sub(eye, p));
    if (strcmp(term, "ambient") == 0) {
        light = &l->ambient;
        f = light->strength;
    } else if (strcmp(term, "diffuse") == 0) {
        light = &l->diffuse;
        f = fmax(dot(n, to_eye), 0.0) * light->strength;
    } else if (strcmp(term, "specular") == 0) {
        light = &l->specular;
        dvec r = sub(scale(n, 2.0 * dot(n, to_eye)), to_eye);   /* reflect(-L, N) */
        f = light->strength * pow(fmax(dot(to_eye, r), 0.0), l->shininess);
    } else if (strcmp(term, "point") == 0) {
        light = &l->point;
        f = fmax(dot(n, normalize(sub(point_light, p))), 0.0) * light->strength;
    } else if (strcmp(term, "spot") == 0) {
        light = &l->spot;
        double c = dot(normalize(sub(p, eye)), normalize(front));
        double ci = cos(l->spot_inner_degrees * LUZ_PI / 180.0);
        double co = cos(l->spot_outer_degrees * LUZ_PI / 180.0);
        double direction = 0.0;
        if (c > ci) {
            direction = 1.0;
        } else if (c > co) {
            double s = sqrt((c - co) / (ci - co));
            direction = s * s * (3.0 - 2.0 * s);
        }
        double dn = sqrt(dot(sub(eye, p), sub(eye, p))) / l->spot_reach;
        double window = pow(fmax(1.0 - pow(dn, 4.0), 0.0), 2.0);
        f = direction * window * light->strength * light->strength / (dn * dn + 1.0);
    } else {
        light = &l->directional;
        f = fmax(dot(n, normalize(scale(sun, -1.0))), 0.0) * light->strength;
    }
    return scale(from_float(light->colour), f);
}

/* Parses a manifest line's arguments as luz-render does. */
static void parse_arguments(const figure *f, luz_options *options)
{
    char copy[1024];
    char *argv[MAX_ARGUMENTS];
    int argc = 0;
    snprintf(copy, sizeof copy, "%s", f->arguments);
    argv[argc++] = "luz-render";
    for (char *word = strtok(copy, " "); word && argc < MAX_ARGUMENTS; word = strtok(NULL, " "))
        argv[argc++] = word;
    luz_error error = {{0}};
    luz_options_init(options);
    if (luz_options_parse(options, argc, argv, &error) != 0)
        fail_msg("%s: %s", f->name, error.message);
}

/* C . T at every pixel: the figure's frame with ambient = 1 alone. */
static luz_framebuffer *render_albedo(const luz_options *options,
                                      const luz_texture_set *textures)
{
    luz_scene scene = options->scene;
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        luz_lights_term(&scene.lights, (luz_term)term)->strength = 0.0f;
    scene.lights.ambient = (luz_light){{1.0f, 1.0f, 1.0f}, 1.0f};
    luz_error error = {{0}};
    luz_frame frame = {0};
    luz_renderer *renderer = luz_renderer_create(&(luz_renderer_desc){.thread_count = 1}, &error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(options->width, options->height, &error);
    assert_non_null(renderer);
    assert_non_null(framebuffer);
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, textures->textures, textures->count,
                                           (float)options->width / (float)options->height,
                                           &frame, NULL),
                     0);
    const luz_render_options render = luz_scene_render_options(&scene);
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &render, &error), 0);
    luz_frame_free(&frame);
    luz_renderer_destroy(renderer);
    return framebuffer;
}

static void check_single_term_figure(const figure *f)
{
    luz_options options;
    parse_arguments(f, &options);
    const luz_scene *scene = &options.scene;
    /* The ray caster knows SCENE.md's ten cubes, unmoved camera settings
     * aside. */
    assert_null(scene->objects);
    assert_int_equal(scene->cube_count, 10);
    assert_int_equal(options.width, f->width);

    luz_texture_set textures = {0};
    luz_error error = {{0}};
    if (luz_options_load_textures(&options, &textures, NULL, &error) != 0)
        fail_msg("%s: %s", f->name, error.message);
    luz_framebuffer *albedo = render_albedo(&options, &textures);
    int width, height;
    unsigned char *image = load_figure(f, &width, &height);
    assert_non_null(image);

    /* The scene at its time, in double precision. */
    const double t = scene->time_seconds;
    const int W = width, H = height;
    box boxes[11];
    int box_count = 10;
    for (int i = 0; i < 10; i++) boxes[i] = cube_at(i, t);
    dvec point_light = dv(3.0 * cos(0.5 * t), 0.5, 3.0 * sin(0.5 * t));
    dvec sun = dv(cos(0.1 * t), sin(0.1 * t), 0.0);
    if (scene->lights.point.strength > 0.0f) {
        boxes[10] = (box){point_light, {dv(1, 0, 0), dv(0, 1, 0), dv(0, 0, 1)}, 0.1};
        box_count = 11;
    }
    const double yaw = scene->camera.yaw_degrees * LUZ_PI / 180.0;
    const double pitch = scene->camera.pitch_degrees * LUZ_PI / 180.0;
    const dvec eye = from_float(scene->camera.position);
    const dvec front = normalize(dv(cos(yaw) * cos(pitch), sin(pitch), sin(yaw) * cos(pitch)));
    const dvec right = normalize(cross(front, dv(0, 1, 0)));
    const dvec up = cross(right, front);
    const double tan_half = tan(scene->camera.fov_degrees * LUZ_PI / 360.0);
    const double aspect = (double)W / H;

    hit *hits = calloc((size_t)W * H, sizeof *hits);
    assert_non_null(hits);
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            double sx = ((x + 0.5) / W * 2.0 - 1.0) * tan_half * aspect;
            double sy = (1.0 - (y + 0.5) / H * 2.0) * tan_half;
            dvec direction = add(front, add(scale(right, sx), scale(up, sy)));
            double nearest = INFINITY;
            hit *h = &hits[(size_t)y * W + x];
            for (int b = 0; b < box_count; b++) {
                if (intersect(&boxes[b], b, eye, direction, &nearest, h))
                    h->marker = b == 10;
            }
            /* A hit nearer than the near plane is clipped: not checked. */
            if (h->id != 0 && nearest * dot(direction, front) < 0.11) h->id = -1;
        }
    }

    int checked = 0, lit = 0, background = 0, marker = 0;
    double worst = 0.0;
    for (int y = 1; y + 1 < H; y++) {
        for (int x = 1; x + 1 < W; x++) {
            const hit *h = &hits[(size_t)y * W + x];
            bool interior = h->id >= 0;
            for (int dy = -1; dy <= 1 && interior; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    interior &= hits[(size_t)(y + dy) * W + x + dx].id == h->id;
            if (!interior) continue;
            const unsigned char *got = image + ((size_t)y * W + x) * 3;
            if (h->id == 0) {
                if (got[0] != BACKGROUND || got[1] != BACKGROUND || got[2] != BACKGROUND)
                    fail_msg("%s: background pixel (%d, %d) is (%d, %d, %d)", f->name, x, y,
                             got[0], got[1], got[2]);
                background++;
                continue;
            }
            if (h->marker) {
                luz_vec3 c = scene->lights.point.colour;
                if (got[0] != luz_colour_to_byte(c.x) || got[1] != luz_colour_to_byte(c.y) ||
                    got[2] != luz_colour_to_byte(c.z))
                    fail_msg("%s: marker pixel (%d, %d) is (%d, %d, %d)", f->name, x, y,
                             got[0], got[1], got[2]);
                marker++;
                continue;
            }
            dvec term = term_at(f->term, scene, h->point, h->normal, eye, front, point_light,
                                sun);
            const uint8_t *a = albedo->colour + ((size_t)y * W + x) * 4;
            const double terms[3] = {term.x, term.y, term.z};
            bool bright = false;
            for (int c = 0; c < 3; c++) {
                double expected = terms[c] * a[c];
                if (expected > 255.0) expected = 255.0;
                double off = fabs(got[c] - expected);
                double allowed = 0.5 + 0.5 * fmin(terms[c], 1.0) + 0.02;
                if (off / allowed > worst) worst = off / allowed;
                if (off > allowed)
                    fail_msg("%s: pixel (%d, %d) channel %d is %d, expected %s %.3f x C.T "
                             "%d = %.2f",
                             f->name, x, y, c, got[c], f->term, terms[c], a[c], expected);
                bright |= expected > 8.0;
            }
            lit += bright;
            checked++;
        }
    }
    print_message("%-18s %6d cube pixels checked (%d lit), %d background, %d marker; "
                  "largest error %.2f of the bound\n",
                  f->name, checked, lit, background, marker, worst);
    /* Enough of each picture is checked for the test to mean something. */
    if (checked < W * H / 20) fail_msg("%s: only %d cube pixels checked", f->name, checked);
    if (lit < 500) fail_msg("%s: only %d pixels lit by %s", f->name, lit, f->term);
    if (background < W * H / 20) fail_msg("%s: only %d background pixels", f->name, background);
    if (box_count == 11 && marker == 0 && strcmp(f->name, "fig5-point-behind") != 0)
        fail_msg("%s: the point light's marker is not in view", f->name);

    free(hits);
    stbi_image_free(image);
    luz_framebuffer_destroy(albedo);
    luz_texture_set_free(&textures);
    luz_options_free(&options);
}

static void test_single_term_figures_hold_their_term_alone(void **state)
{
    (void)state;
    for (int i = 0; i < figure_count; i++) {
        if (strcmp(figures[i].term, "-") != 0) check_single_term_figure(&figures[i]);
    }
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: test-figures FIGURES_SCRIPT LUZ_RENDER\n");
        return 2;
    }
    figures_script = argv[1];
    luz_render = argv[2];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_picture_is_a_png_of_its_size),
        cmocka_unit_test(test_single_term_figures_hold_their_term_alone),
    };
    return cmocka_run_group_tests(tests, run_figures, remove_figures);
}
