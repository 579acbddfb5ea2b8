/*
 * diagnose.c: a verdict on a student's frame (luz-render --diagnose).
 *
 * In:  the student's PNG of a SCENE.md setting and the setting's options
 *      (scene, size), the textures, a lab and a renderer.
 * Out: verdict lines on a stream (docs/teaching.md, "Check your own
 *      frame"): one weight per light term, the residual and where it
 *      sits, the silhouettes, the worst pixels beside luz's probe; a
 *      picture of the residual; LUZ_DIAGNOSIS_RIGHT or _WRONG.
 *
 * How:
 *  1. The six single-term images. SCENE.md: a light at strength 0 adds
 *     exactly 0, and the colour (ambient + ... + directional) * C * T is a
 *     sum, so term k alone is the setting with the other five strengths 0.
 *     Each is rendered at clamp, EV 0 and EV +4: the output is then the
 *     colour times 1 or 16, rounded to a byte, and a channel below 255 at
 *     EV +4 gives the colour to 1/16 of a byte (the rounding of the student
 *     frame's own bytes stays the larger error); one at 255 at EV 0 is
 *     clipped and not weighed. Whatever the setting's output, these images
 *     are linear in each term; the student's bytes are taken back through
 *     the setting's output (luz_diagnose_unmap). One sample a pixel: the
 *     pixels weighed are object interiors, which four samples shade
 *     exactly so.
 *  2. Which pixels: those inside one draw of luz's frame (all 8
 *     neighbours show the same object or mesh: a rounding of an outline
 *     between the two renderers moves no colour there; with four samples,
 *     the same triangle, as the samples mix the faces of an edge), not the
 *     point light's marker (unlit: its colour is no sum of terms), with an
 *     object in the student's frame too; each channel that neither the
 *     frame nor a term's image clips is an observation. The draws are told
 *     apart by drawing the setting's frame once more with each draw unlit
 *     in a colour that is its index.
 *  3. The fit (term_fit.h): least squares over the observations, terms
 *     with too little light in view "not measurable".
 *  4. The residual, what no weighting explains: if it is large, the term
 *     region holding most of it above its share of the pixels (where a
 *     term lights, or where it is 0: a face turned from its light) names
 *     the term whose shape is wrong; the fit is made again without that
 *     region, so the others are weighed where the shape does not disturb
 *     them.
 *  5. Silhouettes: the clear colour where luz has an object, and the
 *     reverse, inside and along the outlines; and along luz's outlines,
 *     pixels whose colour the weights do not give (another surface won:
 *     culling, the depth test).
 *  6. A frame found wrong is compared with luz's image of the setting
 *     with each classic mistake of luz/bug.h put in (find_mistake): a
 *     wrong-shaped term spreads over several weights, and a pipeline
 *     mistake over none, but the mistake's own image is the frame, give
 *     or take another GPU's rounding; named where luz's right image is
 *     clearly not.
 */
#include "app/diagnose.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "luz/framebuffer.h"
#include "luz/probe.h"
#include "luz/shade.h"
#include "app/probe_report.h"
#include "app/term_fit.h"
#include "io/image.h"
#include "io/image_decode.h"
#include "io/image_formats.h"
#include "io/input_file.h"

enum { TERMS = LUZ_TERM_COUNT };

/* ---- the student's file ------------------------------------------------------------- */

int luz_student_frame_read(const char *path, luz_student_frame *frame, luz_error *error)
{
    memset(frame, 0, sizeof *frame);
    unsigned char *bytes;
    size_t size;
    int status = luz_input_read(path, "the frame to diagnose", LUZ_IMAGE_FILE_MAX_BYTES, &bytes,
                                &size, error);
    if (status != 0) return status == LUZ_MACHINE_FAILED ? status : LUZ_BAD_INPUT;
    luz_image_header header;
    if (luz_image_format_of_signature(bytes, size) != LUZ_IMAGE_PNG) {
        free(bytes);
        return luz_error_set(error, "%s: not a PNG file; expected the PNG a canvas saves "
                                    "(docs/teaching.md, \"Check your own frame\")", path);
    }
    status = luz_image_check(bytes, size, LUZ_IMAGE_PNG, path, &header, error);
    if (status == 0)
        status = luz_image_decode(bytes, size, &header, path, &frame->rgba, error);
    free(bytes);
    if (status != 0) return status == LUZ_MACHINE_FAILED ? status : LUZ_BAD_INPUT;
    frame->width = header.width;
    frame->height = header.height;
    return 0;
}

void luz_student_frame_free(luz_student_frame *frame)
{
    free(frame->rgba);
    memset(frame, 0, sizeof *frame);
}

/* ---- the output, backwards ------------------------------------------------------------ */

int luz_diagnose_unmap(const uint8_t bytes[3], luz_output output, double colour[3],
                       bool known[3])
{
    const double scale = exp2(-(double)output.exposure);
    int count = 0;
    if (output.tone_map != LUZ_TONE_MAP_NEUTRAL) {
        for (int c = 0; c < 3; c++) {
            known[c] = bytes[c] > 0 && bytes[c] < 255;
            colour[c] = bytes[c] / 255.0 * scale;
            count += known[c];
        }
        return count;
    }
    /* SCENE.md's neutral tone map below its peak of 0.76 is c - offset
     * with offset = 0.04 for a smallest channel x >= 0.08, else
     * x - 6.25 x^2, which leaves that channel at 6.25 x^2: so a smallest
     * mapped channel m >= 0.04 had offset 0.04, a smaller one x = 0.4
     * sqrt(m). A mapped peak of 0.76 or more was compressed (and mixed
     * towards grey): not undone here. */
    int smallest = bytes[0], largest = bytes[0];
    for (int c = 1; c < 3; c++) {
        if (bytes[c] < smallest) smallest = bytes[c];
        if (bytes[c] > largest) largest = bytes[c];
    }
    const bool invertible =
        smallest > 0 && largest / 255.0 + 0.5 / 255.0 < LUZ_TONE_MAP_START_COMPRESSION;
    const double m = smallest / 255.0;
    const double offset = m >= 0.04 ? 0.04 : 0.4 * sqrt(m) - m;
    for (int c = 0; c < 3; c++) {
        known[c] = invertible;
        colour[c] = (bytes[c] / 255.0 + offset) * scale;
        count += known[c];
    }
    return count;
}

/* The bytes the output writes for a colour (luz_shade_output, then
 * luz_colour_to_byte, as the fragment stages do). */
static void map_colour(const double colour[3], luz_output output, uint8_t bytes[3])
{
    const luz_vec3 mapped = luz_shade_output(
        (luz_vec3){(float)colour[0], (float)colour[1], (float)colour[2]},
        exp2f(output.exposure), output.tone_map);
    bytes[0] = luz_colour_to_byte(mapped.x);
    bytes[1] = luz_colour_to_byte(mapped.y);
    bytes[2] = luz_colour_to_byte(mapped.z);
}

/* ---- rendering the setting --------------------------------------------------------------- */

/* The exposures of the single-term images: each channel is read from the
 * brightest one that does not clip. */
#define BASIS_BRIGHT_EV 4.0f
#define BASIS_CLIPPED (-1.0f)

typedef struct diagnosis {
    const luz_diagnose_setup *setup;
    const luz_student_frame *student;
    int width, height;
    size_t pixels;
    luz_output output;          /* the setting's */
    double byte_step;           /* a byte of the output, as colour: 1 / 255 / 2^EV */
    luz_framebuffer *framebuffer;
    luz_frame frame;
    /* what luz renders */
    float *basis;               /* [term][pixel][channel] colour, or BASIS_CLIPPED */
    int32_t *draw_at;           /* the frame's draw each pixel shows, -1: background */
    int marker_draw;            /* the point light's marker's draw, or -1 */
    uint32_t *triangle_at;      /* the triangle id each pixel shows, 0: background */
    uint8_t *luz_rgb;           /* the setting's image, 3 bytes a pixel */
    uint8_t clear[3];           /* the clear colour's bytes */
    bool light_on[TERMS];       /* the setting's strength above 0 */
    /* per pixel */
    uint8_t *kind;              /* pixel_kind */
    float *residual;            /* [pixel][channel] in bytes, NAN where unknown */
    /* the fit */
    luz_term_fit fit;           /* one weight a term, all channels together */
    luz_term_fit channel_fit[3];   /* one a term and channel: a term's colour */
    double weight[3][TERMS];    /* the weights the residual is taken with:
                                   the channel's, else the term's */
    double sigma;               /* rms residual of the fit, as colour */
    long fit_pixels, fit_observations;
} diagnosis;

typedef enum pixel_kind {
    PIXEL_BACKGROUND,       /* both background */
    PIXEL_INTERIOR,         /* luz's object interior, the student's an object */
    PIXEL_OUTLINE,          /* luz's object on an edge, the student's an object */
    PIXEL_MARKER,           /* the point light's marker (luz's) */
    PIXEL_MISSING_INSIDE,   /* the clear colour where luz has an object ... */
    PIXEL_MISSING_OUTLINE,  /* ... on luz's outline */
    PIXEL_EXTRA_INSIDE,     /* an object where luz has the background ... */
    PIXEL_EXTRA_OUTLINE,    /* ... beside luz's outline */
    PIXEL_KIND_COUNT
} pixel_kind;

static const uint8_t *framebuffer_rgb(const luz_framebuffer *fb, size_t i, uint8_t rgb[3]);

static int build(diagnosis *d, const luz_scene *scene, luz_error *error)
{
    const luz_diagnose_setup *setup = d->setup;
    const float aspect = (float)d->width / (float)d->height;
    return luz_scene_build_frame(setup->lab, scene, setup->textures->textures,
                                 setup->textures->count, aspect, &d->frame, error);
}

static int draw(diagnosis *d, const luz_scene *scene, luz_pixel_probe *probe, luz_error *error)
{
    luz_render_options render = luz_scene_render_options(scene);
    render.probe = probe;
    return luz_renderer_draw(d->setup->renderer, &d->frame, d->framebuffer, &render, error);
}

static int render(diagnosis *d, const luz_scene *scene, luz_pixel_probe *probe, luz_error *error)
{
    return build(d, scene, error) == 0 ? draw(d, scene, probe, error) : -1;
}

/* Which draw each pixel shows: the setting's frame with every draw
 * unlit in a colour that is its index (r + 256 g + 65536 b, one more than
 * the index), the background told by the visibility buffer. */
static int render_draws(diagnosis *d, const luz_scene *scene, int32_t *draw_at,
                        uint32_t *triangle_at, luz_error *error)
{
    if (build(d, scene, error) != 0) return -1;
    if (d->frame.draw_count >= (1 << 24) - 1)
        return luz_error_set(error, "--diagnose: more draws than it can tell apart (%d)",
                             d->frame.draw_count);
    d->marker_draw = -1;
    for (int k = 0; k < d->frame.draw_count; k++) {
        if (luz_scene_object_of_draw(scene, k, &(int){0}) == LUZ_DRAW_POINT_LIGHT)
            d->marker_draw = k;
        const int code = k + 1;
        d->frame.draws[k].material = (luz_material){
            .shading = LUZ_SHADING_UNLIT,
            .colour = {(float)(code & 255) / 255.0f, (float)((code >> 8) & 255) / 255.0f,
                       (float)(code >> 16) / 255.0f},
            .has_colour = true};
    }
    if (draw(d, scene, NULL, error) != 0) return -1;
    memcpy(triangle_at, d->framebuffer->visibility, d->pixels * sizeof *triangle_at);
    for (size_t i = 0; i < d->pixels; i++) {
        uint8_t rgb[3];
        framebuffer_rgb(d->framebuffer, i, rgb);
        draw_at[i] = d->framebuffer->visibility[i] == 0
                            ? -1
                            : (int32_t)(rgb[0] + 256 * rgb[1] + 65536 * rgb[2]) - 1;
    }
    return 0;
}

/* The setting as it is drawn here: its colour image, one sample a pixel. */
static luz_scene setting_scene(const diagnosis *d)
{
    luz_scene scene = d->setup->options->scene;
    scene.view = LUZ_VIEW_COLOR;
    scene.samples = 1;
    scene.bug = LUZ_BUG_NONE;   /* the options refuse one; luz's images are right */
    return scene;
}

/* Term k alone at the setting's strength, at clamp and exposure ev. */
static luz_scene term_scene(const diagnosis *d, luz_term term, float ev)
{
    luz_scene scene = setting_scene(d);
    for (int t = 0; t < TERMS; t++)
        if (t != (int)term) luz_lights_term(&scene.lights, (luz_term)t)->strength = 0.0f;
    scene.has_exposure = true;
    scene.exposure = ev;
    scene.has_tone_map = true;
    scene.tone_map = LUZ_TONE_MAP_CLAMP;
    return scene;
}

static const uint8_t *framebuffer_rgb(const luz_framebuffer *fb, size_t i, uint8_t rgb[3])
{
    const uint8_t *p = fb->colour + 4 * i;
    if (fb->channel_order == LUZ_CHANNELS_BGRA) {
        rgb[0] = p[2]; rgb[1] = p[1]; rgb[2] = p[0];
    } else {
        rgb[0] = p[0]; rgb[1] = p[1]; rgb[2] = p[2];
    }
    return rgb;
}

static int render_terms(diagnosis *d, luz_error *error)
{
    for (int t = 0; t < TERMS; t++) {
        float *basis = d->basis + (size_t)t * d->pixels * 3;
        luz_scene scene = term_scene(d, (luz_term)t, BASIS_BRIGHT_EV);
        if (render(d, &scene, NULL, error) != 0) return -1;
        for (size_t i = 0; i < d->pixels; i++) {
            uint8_t rgb[3];
            framebuffer_rgb(d->framebuffer, i, rgb);
            for (int c = 0; c < 3; c++)
                basis[3 * i + c] = rgb[c] < 255 ? (float)(rgb[c] / 255.0 / exp2(BASIS_BRIGHT_EV))
                                                : BASIS_CLIPPED;
        }
        scene = term_scene(d, (luz_term)t, 0.0f);
        if (render(d, &scene, NULL, error) != 0) return -1;
        for (size_t i = 0; i < d->pixels; i++) {
            uint8_t rgb[3];
            framebuffer_rgb(d->framebuffer, i, rgb);
            for (int c = 0; c < 3; c++)
                if (basis[3 * i + c] == BASIS_CLIPPED && rgb[c] < 255)
                    basis[3 * i + c] = (float)(rgb[c] / 255.0);
        }
        d->light_on[t] = luz_lights_term(&scene.lights, (luz_term)t)->strength > 0.0f;
    }
    luz_scene scene = setting_scene(d);
    if (render_draws(d, &scene, d->draw_at, d->triangle_at, error) != 0 ||
        render(d, &scene, NULL, error) != 0)
        return -1;
    /* luz's own image of the setting, at its samples a pixel: what an
     * anti-aliased frame's outlines are compared with */
    scene.samples = d->setup->options->scene.samples;
    if (scene.samples > 1 && render(d, &scene, NULL, error) != 0) return -1;
    for (size_t i = 0; i < d->pixels; i++) framebuffer_rgb(d->framebuffer, i, d->luz_rgb + 3 * i);
    const luz_vec3 clear = d->frame.clear_colour;
    d->clear[0] = luz_colour_to_byte(clear.x);
    d->clear[1] = luz_colour_to_byte(clear.y);
    d->clear[2] = luz_colour_to_byte(clear.z);
    return 0;
}

/* ---- which pixels -------------------------------------------------------------------------- */

/* The clear colour, give or take the rounding of another GPU. */
static bool looks_like_background(const diagnosis *d, const uint8_t *rgb)
{
    for (int c = 0; c < 3; c++)
        if (abs((int)rgb[c] - (int)d->clear[c]) > 1) return false;
    return true;
}

static bool is_marker(const diagnosis *d, size_t i)
{
    return d->marker_draw >= 0 && d->draw_at[i] == d->marker_draw;
}

/* Does luz draw an object at the pixel? With one sample a pixel, its
 * centre's winner; with four, any sample's: the pixel is not the clear
 * colour. */
static bool luz_has_object(const diagnosis *d, size_t i)
{
    if (d->setup->options->scene.samples > 1)
        return !looks_like_background(d, d->luz_rgb + 3 * i);
    return d->draw_at[i] >= 0;
}

static void classify_pixels(diagnosis *d)
{
    const bool four_samples = d->setup->options->scene.samples > 1;
    for (int y = 0; y < d->height; y++)
        for (int x = 0; x < d->width; x++) {
            const size_t i = (size_t)y * d->width + x;
            const bool has_object = luz_has_object(d, i);
            bool interior = true, outline = false;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= d->width || ny >= d->height) continue;
                    const size_t n = (size_t)ny * d->width + nx;
                    if (d->draw_at[n] != d->draw_at[i] || is_marker(d, n)) interior = false;
                    /* four samples mix the faces a pixel straddles: one
                     * triangle's pixels only */
                    if (four_samples && d->triangle_at[n] != d->triangle_at[i]) interior = false;
                    if (luz_has_object(d, n) != has_object) outline = true;
                }
            const bool student_background = looks_like_background(d, d->student->rgba + 4 * i);
            pixel_kind kind;
            if (has_object && is_marker(d, i))
                kind = PIXEL_MARKER;
            else if (has_object && student_background)
                /* an object as dark as the clear colour is no evidence */
                kind = looks_like_background(d, d->luz_rgb + 3 * i)
                           ? PIXEL_BACKGROUND
                           : outline ? PIXEL_MISSING_OUTLINE : PIXEL_MISSING_INSIDE;
            else if (has_object)
                kind = interior && d->draw_at[i] >= 0 ? PIXEL_INTERIOR : PIXEL_OUTLINE;
            else if (!student_background)
                kind = outline ? PIXEL_EXTRA_OUTLINE : PIXEL_EXTRA_INSIDE;
            else
                kind = PIXEL_BACKGROUND;
            d->kind[i] = (uint8_t)kind;
        }
}

/* ---- the fit ------------------------------------------------------------------------------- */

/* A pixel's observations: the student's colour and the six terms', per
 * channel, and which channels count. */
static int observe(const diagnosis *d, size_t i, double y[3], double basis[3][TERMS],
                   bool known[3])
{
    luz_diagnose_unmap(d->student->rgba + 4 * i, d->output, y, known);
    int count = 0;
    for (int c = 0; c < 3; c++) {
        for (int t = 0; t < TERMS; t++) {
            const float b = d->basis[((size_t)t * d->pixels + i) * 3 + c];
            if (b == BASIS_CLIPPED) known[c] = false;
            basis[c][t] = b;
        }
        count += known[c];
    }
    return count;
}

/* A pixel region of one term: where it lights (its colour above 2% of its
 * brightest in the fit), or where it is exactly 0 (a face turned from its
 * light, outside the spot's cone). */
typedef struct term_region {
    luz_term term;
    bool lit;
} term_region;

static bool in_region(const diagnosis *d, size_t i, term_region region, double threshold)
{
    const float *b = d->basis + ((size_t)region.term * d->pixels + i) * 3;
    const double sum = (double)b[0] + b[1] + b[2];
    return region.lit ? sum > threshold : sum == 0.0;
}

/* The weights of the residual: a channel's own where it was measured
 * (a term's colour may differ from luz's), else the term's. */
static void choose_weights(diagnosis *d)
{
    for (int c = 0; c < 3; c++)
        for (int t = 0; t < TERMS; t++)
            d->weight[c][t] = d->channel_fit[c].measurable[t] ? d->channel_fit[c].weight[t]
                                                              : d->fit.weight[t];
}

/* Fits the interior pixels, all but those of `excluded` (NULL: none). */
static void fit(diagnosis *d, const term_region *excluded, const double *thresholds)
{
    luz_term_sums sums = {0}, channel_sums[3];
    memset(channel_sums, 0, sizeof channel_sums);
    long pixels = 0;
    for (size_t i = 0; i < d->pixels; i++) {
        if (d->kind[i] != PIXEL_INTERIOR) continue;
        if (excluded != NULL && in_region(d, i, *excluded, thresholds[excluded->term])) continue;
        double y[3], basis[3][TERMS];
        bool known[3];
        if (observe(d, i, y, basis, known) == 0) continue;
        pixels++;
        for (int c = 0; c < 3; c++)
            if (known[c]) {
                luz_term_sums_add(&sums, basis[c], y[c]);
                luz_term_sums_add(&channel_sums[c], basis[c], y[c]);
            }
    }
    /* Enough of a term to weigh: what the others do not explain of it
     * adds up to 400 squared bytes (20 pixels a byte apart in each of the
     * three channels, or 4 pixels ten bytes apart ...), which bounds the
     * weight's error from the byte rounding alone near 0.3 / 20 = 0.015. */
    const double min_pivot = 400.0 * d->byte_step * d->byte_step;
    luz_term_fit_solve(&sums, min_pivot, &d->fit);
    for (int c = 0; c < 3; c++) luz_term_fit_solve(&channel_sums[c], min_pivot, &d->channel_fit[c]);
    choose_weights(d);
    d->fit_pixels = pixels;
    d->fit_observations = sums.observations;
}

/* The residual at every object pixel the frame and the terms let us
 * read, in bytes of the output; its sum of squares over the interior
 * (excluding `excluded`) into *rss. */
static void compute_residual(diagnosis *d)
{
    const double to_bytes = 255.0 * exp2((double)d->output.exposure);
    double rss = 0.0;
    long observations = 0;
    for (size_t i = 0; i < d->pixels; i++) {
        float *r = d->residual + 3 * i;
        r[0] = r[1] = r[2] = NAN;
        if (d->kind[i] != PIXEL_INTERIOR && d->kind[i] != PIXEL_OUTLINE) continue;
        /* an outline pixel of four samples mixes surfaces: no sum of terms */
        if (d->kind[i] == PIXEL_OUTLINE && d->setup->options->scene.samples > 1) continue;
        double y[3], basis[3][TERMS];
        bool known[3];
        observe(d, i, y, basis, known);
        for (int c = 0; c < 3; c++) {
            if (!known[c]) continue;
            double predicted = 0.0;
            for (int t = 0; t < TERMS; t++) predicted += d->weight[c][t] * basis[c][t];
            r[c] = (float)((y[c] - predicted) * to_bytes);
            if (d->kind[i] == PIXEL_INTERIOR) {
                rss += (y[c] - predicted) * (y[c] - predicted);
                observations++;
            }
        }
    }
    const long freedom = observations - d->fit.measurable_count;
    d->sigma = freedom > 0 ? sqrt(rss / (double)freedom) : 0.0;
}

/* ---- reading the residual ------------------------------------------------------------------ */

static double largest_abs(const float r[3])
{
    double m = 0.0;
    for (int c = 0; c < 3; c++)
        if (!isnan(r[c]) && fabs(r[c]) > m) m = fabs(r[c]);
    return m;
}

typedef struct residual_summary {
    long pixels;          /* interior pixels with a residual */
    double rms;           /* bytes */
    long over8;           /* pixels with a channel off by more than 8 */
    long outline_pixels;  /* outline pixels with a residual */
    long outline_over16;  /* ... off by more than 16: another surface */
} residual_summary;

static residual_summary summarise(const diagnosis *d)
{
    residual_summary s = {0};
    double squares = 0.0;
    long channels = 0;
    for (size_t i = 0; i < d->pixels; i++) {
        const float *r = d->residual + 3 * i;
        if (d->kind[i] == PIXEL_OUTLINE && d->setup->options->scene.samples > 1) {
            /* four samples: luz's own image, as it is, is the measure */
            int off = 0;
            for (int c = 0; c < 3; c++)
                off = fmax(off, abs((int)d->student->rgba[4 * i + c] - (int)d->luz_rgb[3 * i + c]));
            s.outline_pixels++;
            s.outline_over16 += off > 16;
            continue;
        }
        if (isnan(r[0]) && isnan(r[1]) && isnan(r[2])) continue;
        if (d->kind[i] == PIXEL_OUTLINE) {
            s.outline_pixels++;
            s.outline_over16 += largest_abs(r) > 16.0;
            continue;
        }
        s.pixels++;
        s.over8 += largest_abs(r) > 8.0;
        for (int c = 0; c < 3; c++)
            if (!isnan(r[c])) {
                squares += (double)r[c] * r[c];
                channels++;
            }
    }
    s.rms = channels > 0 ? sqrt(squares / (double)channels) : 0.0;
    return s;
}

/* The residual is worth a verdict: more than the rounding of two GPUs
 * (llvmpipe's 8-bit texture filter against luz's float: rms under a
 * byte, no pixel 8 off). */
static bool residual_unexplained(const residual_summary *s)
{
    return s->pixels > 0 && (s->rms > 2.0 || (double)s->over8 > 0.005 * (double)s->pixels);
}

typedef struct placement {
    bool found;
    term_region region;
    double share;        /* of the residual's energy */
    double area;         /* of the interior pixels weighed */
} placement;

/* Where the residual sits: of every term's regions, the one whose share
 * of the residual's energy most exceeds its share of the pixels. */
static placement place_residual(const diagnosis *d, const double *thresholds)
{
    placement best = {0};
    double best_excess = 0.0;
    for (int t = 0; t < TERMS; t++) {
        if (!d->light_on[t]) continue;
        for (int lit = 0; lit <= 1; lit++) {
            if (!lit && t == LUZ_TERM_AMBIENT) continue;   /* it lights every face */
            const term_region region = {(luz_term)t, lit != 0};
            double inside = 0.0, total = 0.0;
            long area = 0, pixels = 0;
            for (size_t i = 0; i < d->pixels; i++) {
                const float *r = d->residual + 3 * i;
                if (d->kind[i] != PIXEL_INTERIOR || isnan(largest_abs(r))) continue;
                double energy = 0.0;
                for (int c = 0; c < 3; c++)
                    if (!isnan(r[c])) energy += (double)r[c] * r[c];
                const bool in = in_region(d, i, region, thresholds[t]);
                total += energy;
                pixels++;
                if (in) {
                    inside += energy;
                    area++;
                }
            }
            if (total <= 0.0 || pixels == 0) continue;
            const double share = inside / total, area_share = (double)area / (double)pixels;
            if (share >= 0.5 && share - area_share > 0.3 && share - area_share > best_excess) {
                best_excess = share - area_share;
                best = (placement){true, region, share, area_share};
            }
        }
    }
    return best;
}

/* ---- the picture --------------------------------------------------------------------------- */

static int write_picture(const diagnosis *d, luz_error *error)
{
    uint8_t *image = malloc(d->pixels * 4);
    if (image == NULL) return luz_error_set(error, "out of memory for the residual picture");
    for (size_t i = 0; i < d->pixels; i++) {
        uint8_t *p = image + 4 * i;
        const uint8_t *l = d->luz_rgb + 3 * i;
        /* luz's frame, dim and grey, to find one's way */
        const int grey = (int)((l[0] * 3 + l[1] * 6 + l[2]) / 10 * 0.3);
        int rgb[3] = {grey, grey, grey};
        switch ((pixel_kind)d->kind[i]) {
        case PIXEL_MISSING_INSIDE:
        case PIXEL_MISSING_OUTLINE:
            rgb[0] = 255; rgb[1] = 255; rgb[2] = 0;   /* yellow */
            break;
        case PIXEL_EXTRA_INSIDE:
        case PIXEL_EXTRA_OUTLINE:
            rgb[0] = 0; rgb[1] = 255; rgb[2] = 255;   /* cyan */
            break;
        case PIXEL_INTERIOR:
        case PIXEL_OUTLINE: {
            const float *r = d->residual + 3 * i;
            double sum = 0.0;
            int known = 0;
            for (int c = 0; c < 3; c++)
                if (!isnan(r[c])) {
                    sum += r[c];
                    known++;
                }
            if (known == 0) break;
            /* 16 levels a byte: 8 bytes off is half bright, 16 full */
            const int level = (int)fmin(255.0, fabs(sum / known) * 16.0);
            if (sum > 0) rgb[0] = grey + level > 255 ? 255 : grey + level;   /* red: brighter */
            else rgb[2] = grey + level > 255 ? 255 : grey + level;           /* blue: darker */
            break;
        }
        default:
            break;
        }
        p[0] = (uint8_t)rgb[0];
        p[1] = (uint8_t)rgb[1];
        p[2] = (uint8_t)rgb[2];
        p[3] = 255;
    }
    const int status = luz_png_write(d->setup->residual_path, d->width, d->height, image, error);
    free(image);
    return status;
}

/* ---- the verdict --------------------------------------------------------------------------- */

/* The interior pixels term t lights at all. */
static long lit_pixels(const diagnosis *d, luz_term t)
{
    long count = 0;
    for (size_t i = 0; i < d->pixels; i++) {
        if (d->kind[i] != PIXEL_INTERIOR) continue;
        const float *b = d->basis + ((size_t)t * d->pixels + i) * 3;
        count += b[0] != 0.0f || b[1] != 0.0f || b[2] != 0.0f;
    }
    return count;
}

/* The weight's tolerance: 5%, or three standard errors if the frame's
 * noise is larger. */
static double tolerance(const diagnosis *d, int t)
{
    const double se = d->sigma * sqrt(fmax(d->fit.inverse_diagonal[t], 0.0));
    return fmax(0.05, 3.0 * se);
}

static const char *region_words(term_region region)
{
    static const char *lit[TERMS] = {
        "on every face", "where the diffuse headlight falls", "in the specular highlights",
        "where the point light falls", "in the spot's cone", "where the sun falls"};
    static const char *dark[TERMS] = {
        "nowhere", "on faces turned from the camera", "outside the specular highlights",
        "on faces turned from the point light", "outside the spot's cone",
        "on faces turned from the sun"};
    return region.lit ? lit[region.term] : dark[region.term];
}

static const char *shape_hint(term_region region)
{
    if (!region.lit)
        return "a term that must be 0 there is not: is it clamped with max(..., 0)?";
    switch (region.term) {
    case LUZ_TERM_SPOT:
        return "its cone or its fall-off with distance differs (SCENE.md's f_dir, f_win, f_dist)";
    case LUZ_TERM_SPECULAR:
        return "the highlights differ in size or place (R = reflect(-L, N), V, the shininess)";
    default:
        return "its fall-off over the faces differs (the light vector, the normal)";
    }
}

/* How far the frame's bytes are from luz's at pixel i. */
static int byte_difference(const diagnosis *d, size_t i)
{
    int largest = 0;
    for (int c = 0; c < 3; c++) {
        const int off = abs((int)d->student->rgba[4 * i + c] - (int)d->luz_rgb[3 * i + c]);
        if (off > largest) largest = off;
    }
    return largest;
}

/* Up to five pixels where the frame is furthest from luz's image (more
 * than 8 off), 12 pixels apart, inside objects: the student's bytes
 * beside luz's and the weighted terms', and luz's probe of the pixel. */
static int write_worst(diagnosis *d, FILE *out, luz_error *error)
{
    enum { WORST = 5, APART = 12 };
    int chosen[WORST][2];
    int count = 0;
    for (; count < WORST; count++) {
        int largest = 8;
        long best = -1;
        for (size_t i = 0; i < d->pixels; i++) {
            if (d->kind[i] != PIXEL_INTERIOR) continue;
            const int m = byte_difference(d, i);
            if (m <= largest) continue;
            const int x = (int)(i % d->width), y = (int)(i / d->width);
            bool near = false;
            for (int k = 0; k < count; k++)
                if (abs(chosen[k][0] - x) < APART && abs(chosen[k][1] - y) < APART) near = true;
            if (near) continue;
            largest = m;
            best = (long)i;
        }
        if (best < 0) break;
        chosen[count][0] = (int)(best % d->width);
        chosen[count][1] = (int)(best / d->width);
    }
    if (count == 0) {
        fprintf(out, "worst: no pixel inside an object more than 8 off luz's\n");
        return 0;
    }
    const luz_scene scene = setting_scene(d);
    const luz_probe_names names = {.scene = &scene, .textures = d->setup->textures};
    for (int k = 0; k < count; k++) {
        const int x = chosen[k][0], y = chosen[k][1];
        const size_t i = (size_t)y * d->width + x;
        luz_pixel_probe probe = {.x = x, .y = y};
        if (render(d, &scene, &probe, error) != 0) return -1;
        double colour[3] = {0};
        for (int c = 0; c < 3; c++)
            for (int t = 0; t < TERMS; t++) {
                const float b = d->basis[((size_t)t * d->pixels + i) * 3 + c];
                colour[c] += d->weight[c][t] * (b == BASIS_CLIPPED ? 1.0 : b);
            }
        uint8_t weighted[3];
        map_colour(colour, d->output, weighted);
        const uint8_t *s = d->student->rgba + 4 * i;
        const luz_probe_source source = luz_probe_source_of(&names, probe.draw);
        fprintf(out, "worst: %d,%d frame=%d,%d,%d weighted=%d,%d,%d luz=%d,%d,%d object=%d", x,
                y, s[0], s[1], s[2], weighted[0], weighted[1], weighted[2], probe.bytes[0],
                probe.bytes[1], probe.bytes[2], source.object);
        const luz_vec3 C = probe.object_colour, T = probe.texel;
        fprintf(out, " C=%.3f,%.3f,%.3f T=%.3f,%.3f,%.3f", C.x, C.y, C.z, T.x, T.y, T.z);
        for (int t = 0; t < TERMS; t++) {
            const luz_vec3 v = probe.terms[t];
            fprintf(out, " %s=%.3f,%.3f,%.3f", luz_term_name((luz_term)t), v.x, v.y, v.z);
        }
        fputc('\n', out);
    }
    fprintf(out, "worst: each pixel's whole story: luz-render --probe X,Y with the same "
                 "options\n");
    return 0;
}

/* ---- the classic mistakes (luz/bug.h) ----------------------------------------------------- */

/* How well luz's image of the setting with one classic mistake put in
 * (luz-render --bug NAME) matches the frame: its silhouettes against the
 * frame's, as the silhouette line counts them, and its bytes inside its
 * own objects (8 neighbours the same draw in its frame, so that another
 * GPU's rounding of an outline weighs nothing) against the frame's. */
typedef struct bug_match {
    luz_bug bug;
    bool differs;        /* the bug changes luz's image of the setting (a
                            pixel more than 8 off, or a silhouette) */
    bool explains;       /* the frame is that image, give or take a GPU's
                            rounding: residual_unexplained's bounds */
    long pixels;         /* interior pixels compared */
    double rms;          /* bytes */
    long over8;          /* pixels with a channel more than 8 off */
    long inside, along;  /* silhouette disagreements */
} bug_match;

static int match_bug(diagnosis *d, luz_bug bug, int32_t *draw_at, uint32_t *triangle_at,
                     uint8_t *rgb, bug_match *m, luz_error *error)
{
    memset(m, 0, sizeof *m);
    m->bug = bug;
    luz_scene scene = setting_scene(d);
    scene.bug = bug;
    if (render_draws(d, &scene, draw_at, triangle_at, error) != 0) return -1;
    scene.samples = d->setup->options->scene.samples;
    if (render(d, &scene, NULL, error) != 0) return -1;
    for (size_t i = 0; i < d->pixels; i++) framebuffer_rgb(d->framebuffer, i, rgb + 3 * i);

    const bool four_samples = scene.samples > 1;
    long objects = 0, outlines = 0;
    double squares = 0.0;
    long channels = 0;
    for (int y = 0; y < d->height; y++)
        for (int x = 0; x < d->width; x++) {
            const size_t i = (size_t)y * d->width + x;
            const uint8_t *mine = rgb + 3 * i, *frame = d->student->rgba + 4 * i;
            for (int c = 0; c < 3; c++)
                if (abs((int)mine[c] - (int)d->luz_rgb[3 * i + c]) > 8) m->differs = true;
            const bool marker = d->marker_draw >= 0 && draw_at[i] == d->marker_draw;
            const bool has = four_samples ? !looks_like_background(d, mine) : draw_at[i] >= 0;
            if (has != luz_has_object(d, i)) m->differs = true;
            bool interior = true, outline = false;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= d->width || ny >= d->height) continue;
                    const size_t n = (size_t)ny * d->width + nx;
                    if (draw_at[n] != draw_at[i]) interior = false;
                    if (four_samples && triangle_at[n] != triangle_at[i]) interior = false;
                    const bool n_has =
                        four_samples ? !looks_like_background(d, rgb + 3 * n) : draw_at[n] >= 0;
                    if (n_has != has) outline = true;
                }
            if (marker) continue;
            const bool frame_background = looks_like_background(d, frame);
            objects += has;
            outlines += outline;
            if ((has && frame_background && !looks_like_background(d, mine)) ||
                (!has && !frame_background)) {
                if (outline)
                    m->along++;
                else
                    m->inside++;
                continue;
            }
            if (!has || !interior || frame_background) continue;
            int largest = 0;
            for (int c = 0; c < 3; c++) {
                const int off = (int)frame[c] - (int)mine[c];
                squares += (double)off * off;
                channels++;
                largest = abs(off) > largest ? abs(off) : largest;
            }
            m->pixels++;
            m->over8 += largest > 8;
        }
    m->rms = channels > 0 ? sqrt(squares / (double)channels) : 0.0;
    m->explains = (m->differs || bug == LUZ_BUG_NONE) && m->pixels > 0 && m->rms <= 2.0 &&
                  (double)m->over8 <= 0.005 * (double)m->pixels &&
                  m->inside <= 4 + objects / 500 && m->along <= 8 + outlines / 20;
    return 0;
}

/* What a mistake makes wrong, in the verdict's words. */
static const char *mistake_subject(luz_bug bug)
{
    switch (bug) {
    case LUZ_BUG_DIFFUSE_REVERSED: return "diffuse";
    case LUZ_BUG_DIRECTIONAL_UNCLAMPED: return "directional";
    case LUZ_BUG_SPOT_REACH_TWICE: return "spot";
    case LUZ_BUG_SPECULAR_HALF_VECTOR: return "specular";
    case LUZ_BUG_NORMAL_NOT_NORMALISED:
    case LUZ_BUG_NORMAL_MATRIX_IS_MODEL: return "the normal, in every term";
    case LUZ_BUG_UV_AFFINE: return "the texture coordinates";
    case LUZ_BUG_LOD_OFF_BY_ONE: return "the texture's level of detail";
    case LUZ_BUG_FILL_RULE_BOTTOM_RIGHT: return "the outlines";
    case LUZ_BUG_NO_DEPTH_TEST: return "the depth test";
    case LUZ_BUG_NO_BACKFACE_CULLING: return "culling";
    default: return "the frame";
    }
}

/* Of the classic mistakes, the one whose image the frame is and luz's
 * right image is not, if any (the closest, when several are), with
 * *others the count of those that explain it as well (within 0.05 bytes
 * rms: the frame cannot tell them apart). */
static int find_mistake(diagnosis *d, bug_match *best, bug_match *right, int *others,
                        luz_error *error)
{
    memset(best, 0, sizeof *best);
    *others = 0;
    int32_t *draw_at = malloc(d->pixels * sizeof *draw_at);
    uint32_t *triangle_at = malloc(d->pixels * sizeof *triangle_at);
    uint8_t *rgb = malloc(d->pixels * 3);
    int status = 0;
    if (draw_at == NULL || triangle_at == NULL || rgb == NULL) {
        status = luz_error_set(error, "out of memory for the diagnosis");
        goto done;
    }
    bug_match matches[LUZ_BUG_COUNT];
    /* luz's right image, measured alike (*right): a mistake is named only
     * where it explains the frame clearly better, so that a frame the
     * right image explains as well is no evidence of it (the other
     * GPU's rounding is some 0.7 bytes rms; a mistake whose change is
     * about that small is not told from it) */
    status = match_bug(d, LUZ_BUG_NONE, draw_at, triangle_at, rgb, right, error);
    if (status != 0) goto done;
    for (int bug = LUZ_BUG_NONE + 1; bug < LUZ_BUG_COUNT; bug++) {
        status = match_bug(d, (luz_bug)bug, draw_at, triangle_at, rgb, &matches[bug], error);
        if (status != 0) goto done;
        bug_match *m = &matches[bug];
        m->explains = m->explains && (!right->explains || right->rms > 2.0 * m->rms + 0.5);
        if (m->explains && (!best->explains || m->rms < best->rms)) *best = *m;
    }
    for (int bug = LUZ_BUG_NONE + 1; bug < LUZ_BUG_COUNT && best->explains; bug++)
        *others += bug != (int)best->bug && matches[bug].explains &&
                   matches[bug].rms <= best->rms + 0.05;
done:
    free(draw_at);
    free(triangle_at);
    free(rgb);
    return status;
}

static int diagnose_fitted(diagnosis *d, FILE *out, luz_error *error)
{
    const luz_diagnose_setup *setup = d->setup;
    bool wrong[TERMS] = {false};
    bool any_wrong = false;

    /* The 2% threshold of each term's "lit" region. */
    double thresholds[TERMS] = {0};
    for (int t = 0; t < TERMS; t++) {
        double brightest = 0.0;
        for (size_t i = 0; i < d->pixels; i++) {
            if (d->kind[i] != PIXEL_INTERIOR) continue;
            const float *b = d->basis + ((size_t)t * d->pixels + i) * 3;
            if (b[0] == BASIS_CLIPPED || b[1] == BASIS_CLIPPED || b[2] == BASIS_CLIPPED)
                continue;
            brightest = fmax(brightest, (double)b[0] + b[1] + b[2]);
        }
        thresholds[t] = 0.02 * brightest;
    }

    fit(d, NULL, thresholds);
    compute_residual(d);
    residual_summary summary = summarise(d);
    placement place = {0};
    const luz_term_fit first = d->fit;
    luz_term_fit first_channel[3];
    memcpy(first_channel, d->channel_fit, sizeof first_channel);
    if (residual_unexplained(&summary)) {
        place = place_residual(d, thresholds);
        if (place.found) {
            /* weigh the others where the wrong shape is not */
            fit(d, &place.region, thresholds);
            const luz_term k = place.region.term;
            d->fit.weight[k] = first.weight[k];
            d->fit.measurable[k] = first.measurable[k];
            d->fit.inverse_diagonal[k] = first.inverse_diagonal[k];
            for (int c = 0; c < 3; c++) {
                d->channel_fit[c].weight[k] = first_channel[c].weight[k];
                d->channel_fit[c].measurable[k] = first_channel[c].measurable[k];
            }
            choose_weights(d);
            compute_residual(d);
        }
    }

    fprintf(out, "fit: %ld pixels (%ld channels) inside objects, clipped by no image\n",
            d->fit_pixels, d->fit_observations);
    for (int t = 0; t < TERMS; t++) {
        const char *name = luz_term_name((luz_term)t);
        if (!d->fit.measurable[t]) {
            fprintf(out, "%s: not measurable (%s)\n", name,
                    !d->light_on[t]       ? "the setting has it off"
                    : d->fit.unexplained[t] == 0.0 && lit_pixels(d, (luz_term)t) == 0
                        ? "its light falls on no object in view"
                        : "too little of its light in view, or another term's light looks "
                          "the same here");
            continue;
        }
        const double w = d->fit.weight[t], tol = tolerance(d, t);
        const double se = d->sigma * sqrt(fmax(d->fit.inverse_diagonal[t], 0.0));
        fprintf(out, "%s: weight %.3f +- %.3f ", name, w, se);
        const bool shape = place.found && place.region.term == (luz_term)t;
        /* its colour: the channels' weights apart by more than twice the
         * tolerance */
        double lowest = w, highest = w, channel_tol[3];
        for (int c = 0; c < 3; c++) {
            lowest = fmin(lowest, d->weight[c][t]);
            highest = fmax(highest, d->weight[c][t]);
            const luz_term_fit *f = &d->channel_fit[c];
            channel_tol[c] = f->measurable[t]
                ? fmax(tol, 3.0 * d->sigma * sqrt(fmax(f->inverse_diagonal[t], 0.0)))
                : tol;
        }
        const bool colour =
            highest - lowest > 2.0 * fmax(channel_tol[0], fmax(channel_tol[1], channel_tol[2]));
        if (colour) {
            fprintf(out, "wrong: its colour, red %.2f green %.2f blue %.2f of luz's\n",
                    d->weight[0][t], d->weight[1][t], d->weight[2][t]);
            wrong[t] = true;
            any_wrong = true;
            continue;
        }
        bool channels_right = true;
        for (int c = 0; c < 3; c++)
            if (fabs(d->weight[c][t] - 1.0) > channel_tol[c]) channels_right = false;
        if (fabs(w - 1.0) <= tol && channels_right && !shape) {
            fprintf(out, "right\n");
            continue;
        }
        wrong[t] = true;
        any_wrong = true;
        if (fabs(w) <= tol)
            fprintf(out, "wrong: missing (the frame has none of it%s)\n",
                    t == LUZ_TERM_DIFFUSE ? "; a light vector pointing away from the light "
                                            "lights no face in view"
                                          : "");
        else if (shape)
            fprintf(out, "wrong: its shape (see residual)%s\n",
                    fabs(w - 1.0) > tol ? ", and scaled" : "");
        else
            fprintf(out, "wrong: scaled by %.2f (its colour or strength%s)\n", w,
                    t == LUZ_TERM_SPOT ? "; the spot's strength enters squared" : "");
    }

    summary = summarise(d);
    fprintf(out, "residual: rms %.2f bytes, %.2f%% of %ld pixels off by more than 8", summary.rms,
            summary.pixels > 0 ? 100.0 * (double)summary.over8 / (double)summary.pixels : 0.0,
            summary.pixels);
    if (place.found)
        fprintf(out, "; %.0f%% of it %s (%.0f%% of the pixels): %s is wrong there: %s\n",
                100.0 * place.share, region_words(place.region), 100.0 * place.area,
                luz_term_name(place.region.term), shape_hint(place.region));
    else if (residual_unexplained(&summary)) {
        fprintf(out, "; it sits where no one light falls: the colour C or the texture T "
                     "(its coordinates, its filter), which every term multiplies, or the "
                     "depth test\n");
        any_wrong = true;
    } else
        fprintf(out, ": the weights explain the frame\n");

    /* silhouettes and outlines */
    long counts[PIXEL_KIND_COUNT] = {0};
    for (size_t i = 0; i < d->pixels; i++) counts[d->kind[i]]++;
    const long objects = counts[PIXEL_INTERIOR] + counts[PIXEL_OUTLINE] +
                         counts[PIXEL_MISSING_INSIDE] + counts[PIXEL_MISSING_OUTLINE];
    const long inside = counts[PIXEL_MISSING_INSIDE] + counts[PIXEL_EXTRA_INSIDE];
    const long along = counts[PIXEL_MISSING_OUTLINE] + counts[PIXEL_EXTRA_OUTLINE];
    long outline_total = 0;
    for (int y = 0; y < d->height; y++)
        for (int x = 0; x < d->width; x++) {
            const pixel_kind k = (pixel_kind)d->kind[(size_t)y * d->width + x];
            outline_total += k == PIXEL_OUTLINE || k == PIXEL_MISSING_OUTLINE ||
                             k == PIXEL_EXTRA_OUTLINE;
        }
    const bool silhouette_wrong =
        inside > 4 + objects / 500 || along > 8 + outline_total / 20;
    fprintf(out,
            "silhouette: %ld pixels background where luz has an object, %ld an object where "
            "luz has background (%ld inside, %ld along outlines): %s\n",
            counts[PIXEL_MISSING_INSIDE] + counts[PIXEL_MISSING_OUTLINE],
            counts[PIXEL_EXTRA_INSIDE] + counts[PIXEL_EXTRA_OUTLINE], inside, along,
            !silhouette_wrong ? "right"
            : inside == 0 && d->setup->options->scene.samples == 1
                ? "wrong along the outlines only: the fill rule, or an anti-aliased canvas "
                  "(then diagnose with --samples 4, or ask for antialias: false)"
                : "wrong: the camera (position, yaw, pitch, field of view, aspect) or "
                  "culling differ");
    /* The outline's colours are the weighted terms' only where the
     * weights explain the inside: judged only then (a texture or normal
     * read wrong leaves the edges as far off as the faces, which said
     * "another surface wins" of lod-off-by-one and normal-matrix-is-model).
     * With four samples the outline is compared with luz's image as it
     * is, which a wrong term changes too: judged only when the terms are
     * right. */
    const bool inside_explained = !residual_unexplained(&summary);
    const bool outline_judged =
        inside_explained && (d->setup->options->scene.samples == 1 || !any_wrong);
    const bool outline_wrong =
        outline_judged && summary.outline_over16 > 8 + summary.outline_pixels / 20;
    fprintf(out, "outline: %ld of %ld pixels along luz's edges off by more than 16: %s\n",
            summary.outline_over16, summary.outline_pixels,
            !inside_explained ? "not judged (the weights do not explain the inside, so they "
                                "say nothing of the edges)"
            : !outline_judged ? "not judged (four samples a pixel, and a term is wrong)"
            : outline_wrong   ? "wrong: another surface wins there (back faces drawn: culling; "
                                "or the depth test)"
                              : "right");
    any_wrong = any_wrong || silhouette_wrong || outline_wrong;

    if (write_picture(d, error) != 0) return -1;
    fprintf(out,
            "picture: %s (red: the frame brighter than the weighted terms, blue: darker, 16 "
            "levels a byte; yellow: background where luz has an object; cyan: an object where "
            "luz has background)\n",
            setup->residual_path);
    if (write_worst(d, out, error) != 0) return -1;

    /* A frame that is not luz's: is it luz's with one classic mistake?
     * The term weights above read it against the right images, where a
     * wrong-shaped term spreads over several; the mistake's own image
     * names it. */
    bug_match mistake = {0}, right = {0};
    int alike = 0;
    if (any_wrong) {
        if (find_mistake(d, &mistake, &right, &alike, error) != 0) return -1;
        if (mistake.explains)
            fprintf(out, "mistake: the frame is luz-render --bug %s's (rms %.2f bytes over %ld "
                         "pixels inside objects, %ld off by more than 8, silhouettes agree; "
                         "luz's right image: rms %.2f, %ld off)%s: %s\n",
                    luz_bug_name(mistake.bug), mistake.rms, mistake.pixels, mistake.over8,
                    right.rms, right.over8, alike > 0 ? ", or as well another's" : "",
                    luz_bug_description(mistake.bug));
        else
            fprintf(out, "mistake: none of luz-render --bug's (--bug help) draws this frame\n");
        /* The weight and residual lines were printed before the search and
         * may name a term (lod-off-by-one reads as "spot is wrong there"):
         * say how to read them, so that a student does not chase two
         * errors where there is one. */
        if (mistake.explains)
            fprintf(out, "reading: the term, residual and outline lines above compare the frame "
                         "with luz's right image: what they call wrong is this mistake's effect, "
                         "not a second error\n");
    }

    fprintf(out, "verdict: ");
    if (!any_wrong) {
        fprintf(out, "right: every term measured has weight 1 and the frame is luz's\n");
        return LUZ_DIAGNOSIS_RIGHT;
    }
    if (mistake.explains) {
        fprintf(out, "wrong: %s; the likely mistake is %s: %s\n", mistake_subject(mistake.bug),
                luz_bug_name(mistake.bug), luz_bug_description(mistake.bug));
        return LUZ_DIAGNOSIS_WRONG;
    }
    if (silhouette_wrong) {
        /* the pixels compared are not the same surfaces: the weights of
         * another picture say nothing of the terms */
        fprintf(out, "wrong: the silhouette; the weights mean little until the silhouettes "
                     "agree\n");
        return LUZ_DIAGNOSIS_WRONG;
    }
    const char *separator = "wrong: ";
    for (int t = 0; t < TERMS; t++)
        if (wrong[t]) {
            fprintf(out, "%s%s", separator, luz_term_name((luz_term)t));
            separator = ", ";
        }
    if (!place.found && residual_unexplained(&summary)) {
        fprintf(out, "%sthe residual", separator);
        separator = ", ";
    }
    if (outline_wrong) fprintf(out, "%sthe outlines", separator);
    fputc('\n', out);
    return LUZ_DIAGNOSIS_WRONG;
}

int luz_diagnose(const luz_diagnose_setup *setup, const luz_student_frame *student, FILE *out,
                 luz_error *error)
{
    const luz_options *options = setup->options;
    diagnosis d = {.setup = setup, .student = student, .width = options->width,
                   .height = options->height};
    d.pixels = (size_t)d.width * d.height;
    d.output = luz_scene_output(&options->scene);
    d.byte_step = 1.0 / 255.0 * exp2(-(double)d.output.exposure);
    int status = -1;
    d.basis = malloc(d.pixels * 3 * TERMS * sizeof *d.basis);
    d.draw_at = malloc(d.pixels * sizeof *d.draw_at);
    d.triangle_at = malloc(d.pixels * sizeof *d.triangle_at);
    d.luz_rgb = malloc(d.pixels * 3);
    d.kind = malloc(d.pixels);
    d.residual = malloc(d.pixels * 3 * sizeof *d.residual);
    if (d.basis == NULL || d.draw_at == NULL || d.triangle_at == NULL || d.luz_rgb == NULL ||
        d.kind == NULL || d.residual == NULL) {
        luz_error_set(error, "out of memory for the diagnosis");
        goto done;
    }
    d.framebuffer = luz_framebuffer_create(d.width, d.height, error);
    if (d.framebuffer == NULL) goto done;
    if (render_terms(&d, error) != 0) goto done;
    classify_pixels(&d);
    fprintf(out, "diagnose: %s, %dx%d, against luz at time %g, %s at EV %g, %d sample%s a "
                 "pixel\n",
            setup->frame_name, d.width, d.height, options->scene.time_seconds,
            d.output.tone_map == LUZ_TONE_MAP_NEUTRAL ? "neutral" : "clamp",
            (double)d.output.exposure, options->scene.samples,
            options->scene.samples > 1 ? "s" : "");
    status = diagnose_fitted(&d, out, error);
done:
    luz_frame_free(&d.frame);
    if (d.framebuffer != NULL) luz_framebuffer_destroy(d.framebuffer);
    free(d.basis);
    free(d.draw_at);
    free(d.triangle_at);
    free(d.luz_rgb);
    free(d.kind);
    free(d.residual);
    return status;
}
