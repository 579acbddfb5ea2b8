/*
 * test_diagnose: luz-render --diagnose, a verdict on a student's frame
 * (src/app/diagnose.c, the fit in src/app/term_fit.c).
 *
 * The fit and the output's inverse are checked against systems and bytes
 * worked by hand. The verdicts are checked on frames rendered by
 * tools/glref (OpenGL on llvmpipe, SCENE.md's equations in GLSL of its
 * own), committed in tests/diagnose/ with the command that made them
 * (make-frames.sh): each frame changes one thing of a setting, and the
 * weight SCENE.md predicts for it is the expected value (a light's
 * strength times k scales its term by k; the spot's strength enters
 * squared). Then bad input: one line, exit 2, the frame untouched. And
 * the colour generator of docs/teaching.md's JavaScript, run by node.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "luz/shade.h"
#include "luz/framebuffer.h"
#include "app/diagnose.h"
#include "app/term_fit.h"
#include "file_support.h"
#include "test_support.h"
#include "cli_support.h"

/* ---- the fit, by hand ----------------------------------------------------------------- */

/* Two terms, three observations: a = (1,0), (0,1), (1,1) and y = 1, 2, 4.
 * G = [[2,1],[1,2]], h = (5, 6): w = G^-1 h = (1/3) [[2,-1],[-1,2]] (5, 6)
 * = (4/3, 7/3), and (G^-1)_kk = 2/3. The other four terms are 0 on every
 * observation: not measurable, held at weight 1. */
static void test_fit_worked_by_hand(void **state)
{
    (void)state;
    luz_term_sums sums = {0};
    const double a[3][2] = {{1, 0}, {0, 1}, {1, 1}}, y[3] = {1, 2, 4};
    for (int i = 0; i < 3; i++) {
        double basis[LUZ_TERM_COUNT] = {0};
        basis[LUZ_TERM_DIFFUSE] = a[i][0];
        basis[LUZ_TERM_SPOT] = a[i][1];
        luz_term_sums_add(&sums, basis, y[i]);
    }
    luz_term_fit fit;
    luz_term_fit_solve(&sums, 1e-9, &fit);
    assert_int_equal(fit.measurable_count, 2);
    assert_true(fit.measurable[LUZ_TERM_DIFFUSE] && fit.measurable[LUZ_TERM_SPOT]);
    assert_near(fit.weight[LUZ_TERM_DIFFUSE], 4.0 / 3.0, 1e-12);
    assert_near(fit.weight[LUZ_TERM_SPOT], 7.0 / 3.0, 1e-12);
    assert_near(fit.inverse_diagonal[LUZ_TERM_DIFFUSE], 2.0 / 3.0, 1e-12);
    assert_near(fit.inverse_diagonal[LUZ_TERM_SPOT], 2.0 / 3.0, 1e-12);
    for (int t = 0; t < LUZ_TERM_COUNT; t++)
        if (t != LUZ_TERM_DIFFUSE && t != LUZ_TERM_SPOT) {
            assert_false(fit.measurable[t]);
            assert_true(fit.weight[t] == 1.0);   /* held */
        }
}

/* Six terms of random shape and weights chosen here: y = sum w a exactly,
 * so the fit gives the chosen weights back. */
static void test_fit_recovers_chosen_weights(void **state)
{
    (void)state;
    const double chosen[LUZ_TERM_COUNT] = {1.0, 0.0, 0.5, 2.0, 0.25, -1.0};
    luz_term_sums sums = {0};
    uint32_t random = 7;
    for (int i = 0; i < 500; i++) {
        double basis[LUZ_TERM_COUNT], y = 0.0;
        for (int t = 0; t < LUZ_TERM_COUNT; t++) {
            basis[t] = test_uniform(&random, 0.0f, 1.0f);
            y += chosen[t] * basis[t];
        }
        luz_term_sums_add(&sums, basis, y);
    }
    luz_term_fit fit;
    luz_term_fit_solve(&sums, 1e-9, &fit);
    assert_int_equal(fit.measurable_count, LUZ_TERM_COUNT);
    for (int t = 0; t < LUZ_TERM_COUNT; t++) assert_near(fit.weight[t], chosen[t], 1e-9);
}

/* Directional = 2 x ambient on every observation: the two cannot be told
 * apart, so one is not measurable and held at 1, and the other gets the
 * rest of y = a + d + p: 1, never two wild numbers nor one term carrying
 * both (ambient 3, or directional 1.5). */
static void test_fit_alike_terms_not_measurable(void **state)
{
    (void)state;
    luz_term_sums sums = {0};
    uint32_t random = 11;
    for (int i = 0; i < 200; i++) {
        double basis[LUZ_TERM_COUNT] = {0};
        basis[LUZ_TERM_AMBIENT] = test_uniform(&random, 0.1f, 1.0f);
        basis[LUZ_TERM_DIRECTIONAL] = 2.0 * basis[LUZ_TERM_AMBIENT];
        basis[LUZ_TERM_POINT] = test_uniform(&random, 0.0f, 1.0f);
        luz_term_sums_add(&sums, basis,
                          basis[LUZ_TERM_AMBIENT] + basis[LUZ_TERM_DIRECTIONAL] +
                              basis[LUZ_TERM_POINT]);
    }
    luz_term_fit fit;
    luz_term_fit_solve(&sums, 1e-6, &fit);
    assert_int_equal(fit.measurable_count, 2);
    assert_true(fit.measurable[LUZ_TERM_POINT]);
    assert_near(fit.weight[LUZ_TERM_POINT], 1.0, 1e-9);
    assert_true(fit.measurable[LUZ_TERM_AMBIENT] != fit.measurable[LUZ_TERM_DIRECTIONAL]);
    assert_near(fit.weight[LUZ_TERM_AMBIENT], 1.0, 1e-9);
    assert_near(fit.weight[LUZ_TERM_DIRECTIONAL], 1.0, 1e-9);
}

/* ---- the output, backwards ------------------------------------------------------------- */

static void test_unmap_clamp(void **state)
{
    (void)state;
    double colour[3];
    bool known[3];
    /* clamp at EV 0: byte / 255; 0 and 255 may hide anything beyond */
    assert_int_equal(luz_diagnose_unmap((const uint8_t[3]){0, 128, 255},
                                        (luz_output){0.0f, LUZ_TONE_MAP_CLAMP}, colour, known),
                     1);
    assert_false(known[0]);
    assert_true(known[1]);
    assert_false(known[2]);
    assert_near(colour[1], 128.0 / 255.0, 1e-12);
    /* EV -1 halved the colour: byte 128 was 2 x 128 / 255 */
    luz_diagnose_unmap((const uint8_t[3]){1, 128, 254}, (luz_output){-1.0f, LUZ_TONE_MAP_CLAMP},
                       colour, known);
    assert_true(known[0] && known[1] && known[2]);
    assert_near(colour[1], 256.0 / 255.0, 1e-12);
}

/* SCENE.md's neutral tone map below its peak of 0.76: c - 0.04 where the
 * smallest channel is 0.08 or more; else c - (x - 6.25 x^2), x the
 * smallest. */
static void test_unmap_neutral(void **state)
{
    (void)state;
    double colour[3];
    bool known[3];
    const luz_output neutral = {0.0f, LUZ_TONE_MAP_NEUTRAL};
    /* bytes 51, 102, 153 are 0.2, 0.4, 0.6: smallest >= 0.04, so the
     * colour was 0.24, 0.44, 0.64 */
    assert_int_equal(luz_diagnose_unmap((const uint8_t[3]){51, 102, 153}, neutral, colour, known),
                     3);
    assert_near(colour[0], 0.24, 1e-12);
    assert_near(colour[1], 0.44, 1e-12);
    assert_near(colour[2], 0.64, 1e-12);
    /* byte 4 is m = 4/255 < 0.04 = 6.25 x^2: x = 0.4 sqrt(m) = 0.0500979,
     * offset x - m = 0.0344117; 100/255 + offset = 0.4265685 */
    luz_diagnose_unmap((const uint8_t[3]){4, 100, 100}, neutral, colour, known);
    assert_true(known[0]);
    assert_near(colour[0], 0.4 * sqrt(4.0 / 255.0), 1e-12);
    assert_near(colour[0], 0.0500979, 1e-7);
    assert_near(colour[1], 0.4265685, 1e-7);
    /* and luz's tone map takes that colour back to the bytes */
    const luz_vec3 mapped = luz_tone_map_neutral(
        (luz_vec3){(float)colour[0], (float)colour[1], (float)colour[2]});
    assert_int_equal(luz_colour_to_byte(mapped.x), 4);
    assert_int_equal(luz_colour_to_byte(mapped.y), 100);
    /* at EV -1 the colour was twice that */
    luz_diagnose_unmap((const uint8_t[3]){51, 102, 153}, (luz_output){-1.0f, LUZ_TONE_MAP_NEUTRAL},
                       colour, known);
    assert_near(colour[2], 1.28, 1e-12);
    /* a peak of 0.76 or more was compressed; a 0 channel may hide anything */
    assert_int_equal(luz_diagnose_unmap((const uint8_t[3]){51, 102, 194}, neutral, colour, known),
                     0);
    assert_int_equal(luz_diagnose_unmap((const uint8_t[3]){51, 102, 193}, neutral, colour, known),
                     3);
    assert_int_equal(luz_diagnose_unmap((const uint8_t[3]){0, 102, 153}, neutral, colour, known),
                     0);
}

/* ---- luz-render --diagnose -------------------------------------------------------------- */

typedef struct run {
    int status;
    char *out, *err;
} run;

static char work[256];   /* a temporary directory, one per test */

static int make_work(void **state)
{
    (void)state;
    snprintf(work, sizeof work, "/tmp/luz-test-diagnose-XXXXXX");
    return mkdtemp(work) == NULL ? -1 : 0;
}

static int remove_work(void **state)
{
    (void)state;
    remove_tree(work);
    return 0;
}

/* gen-model's UV sphere of about `triangles` triangles, written to
 * work/sphere.obj, whose path goes to path. */
static void make_sphere(int triangles, char *path, size_t size)
{
    const char *gen_model = getenv("GEN_MODEL");
    if (gen_model == NULL) fail_msg("GEN_MODEL is not set (tests/meson.build)");
    snprintf(path, size, "%s/sphere.obj", work);
    char command[1200];
    snprintf(command, sizeof command,
             "'%s' --shape sphere --triangles %d -o '%s' 2>/dev/null", gen_model, triangles,
             path);
    assert_int_equal(system(command), 0);
}

static const char *frames_directory(void)
{
    const char *directory = getenv("LUZ_DIAGNOSE_FRAMES");
    if (directory == NULL) fail_msg("LUZ_DIAGNOSE_FRAMES is not set (tests/meson.build)");
    return directory;
}

/* luz-render with the arguments (NULL-terminated), in the work directory,
 * its stdout and stderr captured there (cli_support.h's runner). */
static run run_luz_render(const char *const *arguments)
{
    sandbox box;
    snprintf(box.root, sizeof box.root, "%s", work);
    snprintf(box.work, sizeof box.work, "%s", work);
    const run_result result = run_in(&box, arguments, NULL);
    return (run){result.status, result.out, result.err};
}

static void run_free(run *r)
{
    free(r->out);
    free(r->err);
}

/* Copies a committed frame into the work directory (its residual picture
 * is written beside it). */
static void copy_frame(const char *name)
{
    char from[512], to[512];
    snprintf(from, sizeof from, "%s/%s", frames_directory(), name);
    snprintf(to, sizeof to, "%s/%s", work, name);
    size_t length;
    char *bytes = read_file(from, &length);
    assert_non_null(bytes);
    FILE *file = fopen(to, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(bytes, 1, length, file), length);
    assert_int_equal(fclose(file), 0);
    free(bytes);
}

/* The line of the output that starts with prefix ("point: "), or fail. */
static const char *line_of(const char *out, const char *prefix)
{
    for (const char *line = out; line != NULL && *line != '\0';) {
        if (strncmp(line, prefix, strlen(prefix)) == 0) return line;
        line = strchr(line, '\n');
        if (line != NULL) line++;
    }
    fail_msg("no line starting '%s' in:\n%s", prefix, out);
    return NULL;
}

static bool line_has(const char *out, const char *prefix, const char *words)
{
    const char *line = line_of(out, prefix);
    const char *end = strchr(line, '\n');
    const char *found = strstr(line, words);
    return found != NULL && (end == NULL || found < end);
}

/* The term's weight, from "NAME: weight W +- S ..." */
static double weight_of(const char *out, const char *term)
{
    char prefix[32];
    snprintf(prefix, sizeof prefix, "%s: weight ", term);
    const char *line = line_of(out, prefix);
    double weight;
    assert_int_equal(sscanf(line + strlen(prefix), "%lf", &weight), 1);
    return weight;
}

static const char *const terms[] = {"ambient", "diffuse", "specular", "point", "spot",
                                    "directional"};

/* Diagnoses a committed frame with the options of its setting. */
static run diagnose(const char *name, const char *const *options)
{
    copy_frame(name);
    const char *arguments[32] = {"--diagnose", name};
    int count = 2;
    for (int i = 0; options != NULL && options[i] != NULL; i++) arguments[count++] = options[i];
    arguments[count] = NULL;
    return run_luz_render(arguments);
}

/* Every term right, within 3% of 1: glref's frames of three settings, one
 * anti-aliased, and a model under the neutral tone map with the sun off
 * (there directional alone is wrong). */
static void expect_right(const char *name, const char *const *options)
{
    run r = diagnose(name, options);
    if (r.status != 0) fail_msg("%s: exit %d\n%s%s", name, r.status, r.out, r.err);
    for (int t = 0; t < 6; t++) {
        char prefix[32];
        snprintf(prefix, sizeof prefix, "%s: ", terms[t]);
        if (line_has(r.out, prefix, "not measurable")) continue;
        assert_near(weight_of(r.out, terms[t]), 1.0, 0.03);
        assert_true(line_has(r.out, prefix, "right"));
    }
    assert_true(line_has(r.out, "verdict: ", "right"));
    assert_true(line_has(r.out, "silhouette: ", "right"));
    assert_true(line_has(r.out, "residual: ", "the weights explain the frame"));
    run_free(&r);
}

static void test_glref_frames_are_right(void **state)
{
    (void)state;
    expect_right("right.png", NULL);
    expect_right("right-4x.png", (const char *const[]){"--samples", "4", NULL});
    expect_right("right-t3.png",
                 (const char *const[]){"--time", "3", "--seed", "7", "--camera-pos",
                                       "0.4,0.3,3.5", "--camera-yaw", "-95", "--camera-pitch",
                                       "-4", NULL});
}

/* Pitched up 40 degrees, the spot (and the headlight's highlights) falls
 * on no object: not measurable, and the frame is still right. */
static void test_term_out_of_view_not_measurable(void **state)
{
    (void)state;
    run r = diagnose("right-up.png", (const char *const[]){"--camera-pitch", "40", NULL});
    assert_int_equal(r.status, 0);
    assert_true(line_has(r.out, "spot: ", "not measurable"));
    assert_true(line_has(r.out, "verdict: ", "right"));
    run_free(&r);
}

/* One term scaled by k: that term's weight is k, the verdict names it
 * alone, exit 1. */
static void expect_scaled(const char *name, const char *term, double k, const char *words)
{
    run r = diagnose(name, NULL);
    assert_int_equal(r.status, 1);
    for (int t = 0; t < 6; t++) {
        const bool this = strcmp(terms[t], term) == 0;
        assert_near(weight_of(r.out, terms[t]), this ? k : 1.0, this ? 0.02 : 0.03);
        char prefix[32];
        snprintf(prefix, sizeof prefix, "%s: ", terms[t]);
        assert_true(line_has(r.out, prefix, this ? words : "right"));
    }
    char verdict[64];
    snprintf(verdict, sizeof verdict, "wrong: %s", term);
    assert_true(line_has(r.out, "verdict: ", verdict));
    /* No classic mistake draws a scaled term. Diffuse at 0 is what
     * diffuse-reversed draws here (its vector lights no face in view): the
     * GL frame, within that GPU's rounding, is its image. */
    if (k == 0.0 && strcmp(term, "diffuse") == 0)
        assert_true(line_has(r.out, "mistake: ", "--bug diffuse-reversed's"));
    else {
        assert_true(line_has(r.out, "mistake: ", "none of luz-render --bug's"));
        /* no mistake named: the term lines are the whole story */
        assert_null(strstr(r.out, "\nreading: "));
    }
    run_free(&r);
}

static void test_scaled_and_missing_terms(void **state)
{
    (void)state;
    expect_scaled("point-half.png", "point", 0.5, "scaled by 0.50");       /* 0.35 / 0.7 */
    expect_scaled("spot-half.png", "spot", 0.25, "scaled by 0.25");        /* 0.5^2 */
    expect_scaled("ambient-1.5.png", "ambient", 1.5, "scaled by 1.50");    /* 0.3 / 0.2 */
    expect_scaled("no-diffuse.png", "diffuse", 0.0, "missing");
}

/* Specular of colour (1, 0, 0): red right, green and blue missing. */
static void test_term_of_another_colour(void **state)
{
    (void)state;
    run r = diagnose("specular-red.png", NULL);
    assert_int_equal(r.status, 1);
    const char *line = line_of(r.out, "specular: ");
    double red, green, blue;
    const char *colour = strstr(line, "its colour, red ");
    assert_non_null(colour);
    assert_int_equal(sscanf(colour, "its colour, red %lf green %lf blue %lf", &red, &green, &blue),
                     3);
    assert_near(red, 1.0, 0.03);
    assert_near(green, 0.0, 0.03);
    assert_near(blue, 0.0, 0.03);
    assert_true(line_has(r.out, "verdict: ", "wrong: specular\n"));
    run_free(&r);
}

/* A model: SCENE.md tone-maps it (neutral at EV -1), which the fit
 * undoes; glref drew it with the sun off. */
static void test_model_under_the_tone_map(void **state)
{
    (void)state;
    char sphere[400];
    make_sphere(2000, sphere, sizeof sphere);
    run r = diagnose("sphere-no-sun.png",
                     (const char *const[]){"--model", sphere, "--time", "1", NULL});
    assert_int_equal(r.status, 1);
    assert_true(line_has(r.out, "diagnose: ", "neutral at EV -1"));
    assert_near(weight_of(r.out, "directional"), 0.0, 0.02);
    assert_true(line_has(r.out, "directional: ", "missing"));
    for (int t = 0; t < 5; t++) {
        char prefix[32];
        snprintf(prefix, sizeof prefix, "%s: ", terms[t]);
        assert_true(line_has(r.out, prefix, "right"));
    }
    assert_true(line_has(r.out, "verdict: ", "wrong: directional\n"));
    run_free(&r);
}

/* The camera 0.05 to the right: the silhouettes differ inside and along
 * the outlines, and the verdict names the silhouette. The residual
 * picture is written beside the frame, of its size, yellow where the
 * frame has the background and luz an object. */
static void test_moved_camera_is_a_silhouette(void **state)
{
    (void)state;
    char frame[400];
    snprintf(frame, sizeof frame, "%s/moved.png", work);
    run r = diagnose("moved.png", NULL);
    assert_int_equal(r.status, 1);
    long missing, extra, inside, along;
    const char *line = line_of(r.out, "silhouette: ");
    assert_int_equal(sscanf(line,
                            "silhouette: %ld pixels background where luz has an object, %ld an "
                            "object where luz has background (%ld inside, %ld along",
                            &missing, &extra, &inside, &along),
                     4);
    assert_true(missing > 50 && extra > 50 && inside > 50);
    assert_true(line_has(r.out, "silhouette: ", "wrong: the camera"));
    assert_true(line_has(r.out, "verdict: ", "wrong: the silhouette"));
    assert_true(line_has(r.out, "picture: ", "moved-residual.png"));

    char picture[400];
    snprintf(picture, sizeof picture, "%s/moved-residual.png", work);
    luz_student_frame residual, student;
    luz_error error;
    assert_int_equal(luz_student_frame_read(picture, &residual, &error), 0);
    assert_int_equal(luz_student_frame_read(frame, &student, &error), 0);
    assert_int_equal(residual.width, 192);
    assert_int_equal(residual.height, 108);
    long yellow = 0;
    for (int i = 0; i < residual.width * residual.height; i++) {
        const uint8_t *p = residual.rgba + 4 * i;
        yellow += p[0] == 255 && p[1] == 255 && p[2] == 0;
    }
    assert_int_equal(yellow, missing);
    /* the frame itself untouched: the committed bytes */
    char committed[512];
    snprintf(committed, sizeof committed, "%s/moved.png", frames_directory());
    size_t a_length, b_length;
    char *a = read_file(committed, &a_length), *b = read_file(frame, &b_length);
    assert_true(a_length == b_length && memcmp(a, b, a_length) == 0);
    free(a);
    free(b);
    luz_student_frame_free(&residual);
    luz_student_frame_free(&student);
    run_free(&r);
}

/* ---- luz's own --bug frames ----------------------------------------------------------------- */

/* Renders a --bug frame of a setting with luz-render, then diagnoses it
 * with the same setting. */
static run diagnose_bug(const char *bug, const char *const *setting)
{
    const char *render[32] = {"--size", "192x108", "--bug", bug, "-o", "bug.png"};
    int count = 6;
    for (int i = 0; setting != NULL && setting[i] != NULL; i++) render[count++] = setting[i];
    render[count] = NULL;
    run made = run_luz_render(render);
    assert_int_equal(made.status, 0);
    run_free(&made);
    const char *arguments[32] = {"--diagnose", "bug.png"};
    count = 2;
    for (int i = 0; setting != NULL && setting[i] != NULL; i++) arguments[count++] = setting[i];
    arguments[count] = NULL;
    return run_luz_render(arguments);
}

/* diffuse-reversed: L points away from the headlight, so no face in view
 * gets diffuse light: weight 0, the other terms 1. */
static void test_bug_diffuse_reversed(void **state)
{
    (void)state;
    run r = diagnose_bug("diffuse-reversed", NULL);
    assert_int_equal(r.status, 1);
    assert_near(weight_of(r.out, "diffuse"), 0.0, 0.02);
    assert_true(line_has(r.out, "diffuse: ", "missing"));
    assert_true(line_has(r.out, "verdict: ", "wrong: diffuse; the likely mistake is "
                                             "diffuse-reversed: "));
    run_free(&r);
}

/* spot-reach-twice with a short reach (3): f_win hardly falls off, the
 * spot is far brighter than luz's: the spot is named. */
static void test_bug_spot_reach_twice(void **state)
{
    (void)state;
    run r = diagnose_bug("spot-reach-twice", (const char *const[]){"--spot-reach", "3", NULL});
    assert_int_equal(r.status, 1);
    assert_true(weight_of(r.out, "spot") > 1.5);
    assert_true(line_has(r.out, "spot: ", "wrong"));
    assert_true(line_has(r.out, "verdict: ", "spot"));
    run_free(&r);
}

/* no-backface-culling with the camera inside cube 0: luz culls the
 * cube's faces (all turned away) and sees the background; the bug draws
 * them over the whole frame. */
static void test_bug_no_backface_culling(void **state)
{
    (void)state;
    run r = diagnose_bug("no-backface-culling",
                         (const char *const[]){"--camera-pos", "0,0,0", NULL});
    assert_int_equal(r.status, 1);
    long missing, extra, inside, along;
    assert_int_equal(sscanf(line_of(r.out, "silhouette: "),
                            "silhouette: %ld pixels background where luz has an object, %ld an "
                            "object where luz has background (%ld inside, %ld along",
                            &missing, &extra, &inside, &along),
                     4);
    assert_true(extra > 192 * 108 / 2 && inside > 192 * 108 / 2);
    assert_true(line_has(r.out, "verdict: ", "wrong: culling; the likely mistake is "
                                             "no-backface-culling: "));
    run_free(&r);
}

/* fill-rule-bottom-right on one face seen head-on, its edges through
 * pixel centres: a field of view of 2 atan(1/2) with the face 2 units
 * away puts its edges at NDC y = +-0.5 and x = +-0.5 / aspect, pixels
 * y = 27.5 and 82.5, x = 71.5 and 126.5 at 198x110. The bug gives the
 * pixels on them to the other side: along the outline only. */
static void test_bug_fill_rule(void **state)
{
    (void)state;
    const char *const setting[] = {"--cubes", "1", "--camera-pos", "0,0,2.5", "--fov",
                                   "53.13010235415598", "--size", "198x110", NULL};
    run r = diagnose_bug("fill-rule-bottom-right", setting);
    assert_int_equal(r.status, 1);
    long missing, extra, inside, along;
    assert_int_equal(sscanf(line_of(r.out, "silhouette: "),
                            "silhouette: %ld pixels background where luz has an object, %ld an "
                            "object where luz has background (%ld inside, %ld along",
                            &missing, &extra, &inside, &along),
                     4);
    assert_int_equal(inside, 0);
    assert_true(missing > 50 && extra > 50);
    assert_true(line_has(r.out, "silhouette: ", "along the outlines only: the fill rule"));
    run_free(&r);
}

/* Each classic mistake, at a setting where it shows, diagnoses as
 * itself: the mistake line names it and no other mistake's image
 * explains the frame as well, and the verdict names what it makes wrong.
 * Without the search for mistakes these came out as other terms:
 * directional-unclamped as specular, spot-reach-twice "outside the cone",
 * specular-half-vector, normal-matrix-is-model, lod-off-by-one and
 * no-depth-test as several scaled terms, uv-affine as ambient 0.954. */
static void expect_mistake(const char *bug, const char *const *setting, const char *subject)
{
    run r = diagnose_bug(bug, setting);
    if (r.status != 1) fail_msg("%s: exit %d\n%s%s", bug, r.status, r.out, r.err);
    char words[160];
    snprintf(words, sizeof words, "the frame is luz-render --bug %s's (rms 0.00 bytes", bug);
    if (!line_has(r.out, "mistake: ", words) || line_has(r.out, "mistake: ", "as well another"))
        fail_msg("%s:\n%s", bug, r.out);
    snprintf(words, sizeof words, "wrong: %s; the likely mistake is %s: ", subject, bug);
    if (!line_has(r.out, "verdict: ", words)) fail_msg("%s:\n%s", bug, r.out);
    /* the term lines above were read against the right image: say so */
    if (!line_has(r.out, "reading: ", "this mistake's effect, not a second error"))
        fail_msg("%s: no reading line\n%s", bug, r.out);
    run_free(&r);
}

static void test_every_mistake_named(void **state)
{
    (void)state;
    expect_mistake("directional-unclamped", NULL, "directional");
    expect_mistake("spot-reach-twice", (const char *const[]){"--spot-reach", "3", NULL},
                   "spot");
    expect_mistake("specular-half-vector", NULL, "specular");
    expect_mistake("normal-matrix-is-model", NULL, "the normal, in every term");
    /* the faces seen at an angle, where affine uv bends the bricks */
    expect_mistake("uv-affine", (const char *const[]){"--camera-yaw", "-60", NULL},
                   "the texture coordinates");
    expect_mistake("lod-off-by-one", NULL, "the texture's level of detail");
    /* its inside is not explained by any weighting of the right terms, so
     * its edges are not judged either (they read "another surface wins"
     * before: 162 of 878 pixels) */
    run r = diagnose_bug("lod-off-by-one", NULL);
    assert_true(line_has(r.out, "outline: ", "not judged (the weights do not explain"));
    run_free(&r);
    expect_mistake("no-depth-test", NULL, "the depth test");
    /* the two settings of the silhouette tests above */
    expect_mistake("no-backface-culling", (const char *const[]){"--camera-pos", "0,0,0", NULL},
                   "culling");
    expect_mistake("fill-rule-bottom-right",
                   (const char *const[]){"--cubes", "1", "--camera-pos", "0,0,2.5", "--fov",
                                         "53.13010235415598", "--size", "198x110", NULL},
                   "the outlines");
    /* a coarse sphere (200 triangles), whose interpolated normals are
     * visibly shorter between its vertices */
    char sphere[400];
    make_sphere(200, sphere, sizeof sphere);
    expect_mistake("normal-not-normalised",
                   (const char *const[]){"--model", sphere, "--time", "1", NULL},
                   "the normal, in every term");
}

/* ---- frames that cannot be compared ------------------------------------------------------ */

/* Exit 2 and one line naming the file (or flag) and what was expected;
 * no residual picture. */
static void expect_refused(const char *const *arguments, const char *words)
{
    run r = run_luz_render(arguments);
    if (r.status != 2 || strstr(r.err, words) == NULL)
        fail_msg("exit %d, expected 2 and '%s' in: %s", r.status, words, r.err);
    const char *end = strchr(r.err, '\n');   /* one line */
    assert_non_null(end);
    assert_true(end[1] == '\0');
    assert_true(r.out[0] == '\0');
    run_free(&r);
}

static void test_bad_frames_refused(void **state)
{
    (void)state;
    copy_frame("right.png");
    char path[400];
    snprintf(path, sizeof path, "%s/text.png", work);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    fputs("not an image\n", file);
    fclose(file);
    expect_refused((const char *const[]){"--diagnose", "text.png", NULL},
                   "text.png: not a PNG file");
    expect_refused((const char *const[]){"--diagnose", "right.png", "--size", "320x180", NULL},
                   "right.png: 192x108 pixels; expected the 320x180");
    expect_refused((const char *const[]){"--diagnose", "absent.png", NULL}, "absent.png");
    expect_refused((const char *const[]){"--diagnose", "right.png", "-o", "right.png", NULL},
                   "-o: right.png: is the frame to diagnose");
    expect_refused((const char *const[]){"--diagnose", "right.png", "--bench", "3", NULL},
                   "--diagnose: expected one frame");
    /* nothing written but the text file and the frame */
    char listing[4096] = "";
    list_tree(work, "", listing, sizeof listing);
    assert_string_equal(listing, "right.png\nstderr\nstdout\ntext.png\n");
}

/* ---- the page's JavaScript ----------------------------------------------------------------- */

/* docs/teaching.md's cubeColours, run by node where it is installed, gives
 * the lab's colours (SCENE.md's generator as luz implements it) for the
 * default seed and for seed 7. */
static void test_page_colour_generator(void **state)
{
    (void)state;
    if (system("node --version >/dev/null 2>&1") != 0) {
        print_message("node is not installed: the page's JavaScript is not run\n");
        skip();
    }
    const char *page_path = getenv("LUZ_TEACHING_DOC");
    if (page_path == NULL) fail_msg("LUZ_TEACHING_DOC is not set (tests/meson.build)");
    char *page = read_file(page_path, NULL);
    assert_non_null(page);
    const char *start = strstr(page, "function cubeColours(");
    assert_non_null(start);
    const char *end = strstr(start, "\n   }\n");
    assert_non_null(end);
    char script[600];
    snprintf(script, sizeof script, "%s/colours.js", work);
    FILE *file = fopen(script, "w");
    assert_non_null(file);
    fprintf(file, "%.*s\n", (int)(end + 5 - start), start);
    fputs("for (const seed of [0, 7]) for (const c of cubeColours(10, seed))\n"
          "  console.log(c.map(v => v.toPrecision(9)).join(' '));\n", file);
    assert_int_equal(fclose(file), 0);
    char command[1200], output[400];
    snprintf(output, sizeof output, "%s/colours.txt", work);
    snprintf(command, sizeof command, "node '%s' > '%s'", script, output);
    assert_int_equal(system(command), 0);
    char *text = read_file(output, NULL);
    assert_non_null(text);
    const uint32_t seeds[2] = {0, 7};
    const char *cursor = text;
    for (int k = 0; k < 2; k++) {
        luz_vec3 colours[10];
        luz_scene_random_colours(seeds[k], 10, colours);
        for (int i = 0; i < 10; i++) {
            double r, g, b;
            int used;
            assert_int_equal(sscanf(cursor, "%lf %lf %lf%n", &r, &g, &b, &used), 3);
            cursor += used;
            assert_near(r, colours[i].x, 1e-7);
            assert_near(g, colours[i].y, 1e-7);
            assert_near(b, colours[i].z, 1e-7);
        }
    }
    free(text);
    free(page);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fit_worked_by_hand),
        cmocka_unit_test(test_fit_recovers_chosen_weights),
        cmocka_unit_test(test_fit_alike_terms_not_measurable),
        cmocka_unit_test(test_unmap_clamp),
        cmocka_unit_test(test_unmap_neutral),
        cmocka_unit_test_setup_teardown(test_glref_frames_are_right, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_term_out_of_view_not_measurable, make_work,
                                        remove_work),
        cmocka_unit_test_setup_teardown(test_scaled_and_missing_terms, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_term_of_another_colour, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_model_under_the_tone_map, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_moved_camera_is_a_silhouette, make_work,
                                        remove_work),
        cmocka_unit_test_setup_teardown(test_bad_frames_refused, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_bug_diffuse_reversed, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_bug_spot_reach_twice, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_bug_no_backface_culling, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_bug_fill_rule, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_every_mistake_named, make_work, remove_work),
        cmocka_unit_test_setup_teardown(test_page_colour_generator, make_work, remove_work),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
