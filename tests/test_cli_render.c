/*
 * test_cli_render.c: luz-render's pictures and reports as a user runs it:
 * --help and --version, a frame and its PNG, the textures directory, the
 * scene file under the command line, --probe (and docs/cli.md's example of
 * it), --bench, the options, exposure and tone map and --mark and --legend
 * reaching the image, and the viewer's orbit camera saved by F2 and
 * rendered to the viewer's very bytes.
 *
 * The tests run the real luz-render (its path in $LUZ_RENDER, set by
 * tests/meson.build) in a fresh sandbox (cli_support.h) and look at what a
 * user would see: the exit status, stdout and stderr, and the files left
 * behind, read back with stb_image.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "cli_support.h"

#include <math.h>

#include <stb_image.h>

#include "app/orbit.h"
#include "luz/bug.h"
#include "io/textures.h"
#include "lab/scene.h"

static void test_help(void **state)
{
    (void)state;
    static const char *const options[] = {
        "--size",         "--time",       "--seed",        "--camera-pos", "--camera-yaw",
        "--camera-pitch", "--fov",        "--ambient",     "--diffuse",    "--specular",
        "--shininess",    "--point",      "--spot",        "--spot-inner", "--spot-outer",
        "--spot-reach",   "--directional", "--filter",     "--textures",   "--cubes",
        "--threads",      "--only",       "-o",            "--frames",     "--fps",
        "--bench",        "--scene",      "--help",        "--version",    "--reference",
        "--view",         "--interp",     "--frame-range", "--shard",     "--skip-existing",
        "--probe",
    };
    /* defaults that SCENE.md and the issue fix */
    static const char *const defaults[] = {
        "1280x720", "default: 0, 0, 3", "default: -90", "default: 45", "default: 1, 1, 1, 0.2",
        "default: 32", "default: 12.5", "default: 17.5", "default: 10", "default: trilinear",
        "default: luz.png", "default: 30", "default: 1, 1, 1, 0.4", "default: color",
        "default: perspective",
    };
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--help"), NULL);
    assert_success(&result);
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++) {
        if (strstr(result.out, options[i]) == NULL)
            fail_msg("--help does not mention %s", options[i]);
    }
    for (size_t i = 0; i < sizeof defaults / sizeof defaults[0]; i++) {
        if (strstr(result.out, defaults[i]) == NULL)
            fail_msg("--help does not show '%s'", defaults[i]);
    }
    run_result_free(&result);
    sandbox_destroy(&box);
}

static void test_version(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--version"), NULL);
    assert_success(&result);
    assert_string_equal(result.out, "luz-render 0.1.0\n");
    run_result_free(&result);
    sandbox_destroy(&box);
}

static void test_tiny_render(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    run_result result = run_in(&box, ARGS("--size", "16x9", "--textures", "none", "-o", "tiny.png"),
                               NULL);
    assert_success(&result);
    assert_string_equal(result.out, "");
    assert_png_size(&box, "tiny.png", 16, 9);
    /* exactly one new file: no temporary left behind */
    list_tree(box.work, "", after, sizeof after);
    assert_new_files(before, after, ARGS("tiny.png"));
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* --name=value works as --name value does, and the default output is luz.png. */
static void test_equals_form_and_default_output(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size=16x9", "--textures=none", "--time=2"), NULL);
    assert_success(&result);
    assert_png_size(&box, "luz.png", 16, 9);
    run_result_free(&result);
    sandbox_destroy(&box);
}

static void test_textures_directory(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "12x10", "--textures", "tex", "-o", "t.png"),
                               NULL);
    assert_success(&result);
    assert_png_size(&box, "t.png", 12, 10);
    run_result_free(&result);

    /* $LUZ_TEXTURES is used without --textures, and --textures beats it */
    result = run_in(&box, ARGS("--size", "10x10", "-o", "env.png"), "tex");
    assert_success(&result);
    assert_png_size(&box, "env.png", 10, 10);
    run_result_free(&result);
    result = run_in(&box, ARGS("--size", "10x10", "--textures", "tex", "-o", "beats.png"), "empty");
    assert_success(&result);
    assert_png_size(&box, "beats.png", 10, 10);
    run_result_free(&result);
    sandbox_destroy(&box);
}


/* --probe X,Y prints the pixel's story and writes no PNG; with -o it
 * writes the image, and bytes= is that image's pixel. The background
 * says object=none and then only bytes=. */
static void test_probe(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    /* the middle of 32x18 is cube 0's front face at t = 0 */
    run_result result = run_in(&box, ARGS("--size", "32x18", "--textures", "tex", "--probe",
                                          "16,9"), NULL);
    assert_success(&result);
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);   /* no file without -o */
    char value[256];
    assert_string_equal(key_value(result.out, "pixel", value, sizeof value), "16,9");
    assert_string_equal(key_value(result.out, "size", value, sizeof value), "32,18");
    assert_string_equal(key_value(result.out, "time", value, sizeof value), "0");
    assert_string_equal(key_value(result.out, "object", value, sizeof value), "0");
    assert_string_equal(key_value(result.out, "mesh", value, sizeof value), "0");
    assert_string_equal(key_value(result.out, "texture", value, sizeof value), "a.bmp");
    assert_string_equal(key_value(result.out, "N", value, sizeof value), "0,0,1");
    assert_contains(result.out, "\ntest=1 object=0 mesh=0 triangle=");
    assert_contains(result.out, " result=pass\n");
    static const char *const keys[] = {"triangle", "barycentric", "w", "P", "uv", "rho",
                                       "lod", "levels", "weight", "texel", "ambient",
                                       "diffuse", "specular", "point", "spot", "directional",
                                       "light", "C", "colour", "exposure", "tonemap",
                                       "exposed", "mapped", "bytes"};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (key_value(result.out, keys[i], value, sizeof value) == NULL)
            fail_msg("no %s= in:\n%s", keys[i], result.out);
    char bytes_without_png[64];
    key_value(result.out, "bytes", bytes_without_png, sizeof bytes_without_png);
    run_result_free(&result);

    /* With -o: the image, and the pixel the probe read is in it. */
    const int probed[2][2] = {{16, 9}, {0, 0}};
    for (int i = 0; i < 2; i++) {
        char pixel[32];
        snprintf(pixel, sizeof pixel, "%d,%d", probed[i][0], probed[i][1]);
        result = run_in(&box, ARGS("--size", "32x18", "--textures", "tex", "--probe", pixel, "-o",
                                   "p.png"), NULL);
        assert_success(&result);
        char path[600];
        sandbox_path(&box, "p.png", path, sizeof path);
        int width, height, channels;
        unsigned char *image = stbi_load(path, &width, &height, &channels, 3);
        assert_non_null(image);
        assert_int_equal(width, 32);
        const unsigned char *p = image + ((size_t)probed[i][1] * width + probed[i][0]) * 3;
        char expected[64];
        snprintf(expected, sizeof expected, "%u,%u,%u", p[0], p[1], p[2]);
        assert_string_equal(key_value(result.out, "bytes", value, sizeof value), expected);
        if (i == 0) {
            assert_string_equal(expected, bytes_without_png);
        } else {
            /* the clear colour, round(0.1 x 255) */
            assert_string_equal(expected, "26,26,26");
            assert_non_null(strstr(result.out, "\nobject=none\nbytes=26,26,26\n"));
            const char *none = strstr(result.out, "object=none");
            assert_string_equal(none, "object=none\nbytes=26,26,26\n");
        }
        stbi_image_free(image);
        run_result_free(&result);
    }

    /* A view: what it shows, and the overdraw it counts is the history's. */
    result = run_in(&box, ARGS("--size", "32x18", "--textures", "none", "--probe", "16,9",
                               "--view", "overdraw"), NULL);
    assert_success(&result);
    assert_string_equal(key_value(result.out, "view", value, sizeof value), "overdraw");
    char tests[32];
    assert_non_null(key_value(result.out, "tests", tests, sizeof tests));
    assert_string_equal(key_value(result.out, "overdraw", value, sizeof value), tests);
    assert_non_null(key_value(result.out, "shown", value, sizeof value));
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* docs/cli.md shows what `luz-render --probe 700,450` prints: it must be
 * what it prints (the default scene, the source tree's textures, which a
 * luz-render of the build tree reads). */
static void test_probe_example_in_the_docs(void **state)
{
    (void)state;
    const char *doc_path = getenv("LUZ_CLI_DOC");
    if (doc_path == NULL) fail_msg("LUZ_CLI_DOC is not set (tests/meson.build sets it)");
    char *doc = read_file(doc_path, NULL);
    assert_non_null(doc);
    const char *command = "$ luz-render --probe 700,450\n";
    const char *start = strstr(doc, command);
    if (start == NULL) fail_msg("%s has no '%s'", doc_path, command);
    start += strlen(command);
    const char *end = strstr(start, "```");
    assert_non_null(end);
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--probe", "700,450"), NULL);
    assert_success(&result);
    if (strlen(result.out) != (size_t)(end - start) ||
        memcmp(result.out, start, (size_t)(end - start)) != 0)
        fail_msg("docs/cli.md's example differs from the output:\n%s", result.out);
    run_result_free(&result);
    sandbox_destroy(&box);
    free(doc);
}

static void test_bench(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);
    run_result result = run_in(&box, ARGS("--bench", "2", "--size", "16x9", "--textures", "none",
                                          "--threads", "1", "--cubes", "20"),
                               NULL);
    assert_success(&result);
    /* one line */
    assert_non_null(strchr(result.out, '\n'));
    assert_string_equal(strchr(result.out, '\n'), "\n");
    static const char *const fields[] = {"frames=2 ", "size=16x9 ", "threads=1 ", "cubes=20 ",
                                         "filter=trilinear ", "median_ms=", "min_ms=", "fps=",
                                         "cpu_ms=", "geometry_ms=", "raster_ms="};
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
        assert_contains(result.out, fields[i]);
    assert_null(strstr(result.out, "speedup="));
    double median_ms = atof(strstr(result.out, "median_ms=") + 10);
    double min_ms = atof(strstr(result.out, "min_ms=") + 7);
    assert_true(median_ms > 0.0);
    assert_true(min_ms > 0.0 && min_ms <= median_ms);
    run_result_free(&result);

    /* with threads, the single-thread comparison */
    result = run_in(&box, ARGS("--bench=2", "--size", "16x9", "--textures", "none", "--threads",
                               "2", "--filter", "nearest"),
                    NULL);
    assert_success(&result);
    assert_contains(result.out, "threads=2 ");
    assert_contains(result.out, "filter=nearest ");
    assert_contains(result.out, "single_thread_median_ms=");
    assert_contains(result.out, "speedup=");
    run_result_free(&result);

    /* no file written */
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);
    sandbox_destroy(&box);
}

/* The command line overrides the scene file whatever the order. */
static void test_scene_file_and_precedence(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    write_text(box.work, "s.luz",
               "# a small scene\n"
               "size = 20x10\n"
               "textures = none   # all white\n"
               "\n"
               "camera-pos = 0, 0, 4\n");
    run_result result = run_in(&box, ARGS("--scene", "s.luz", "-o", "file.png"), NULL);
    assert_success(&result);
    assert_png_size(&box, "file.png", 20, 10);
    run_result_free(&result);

    result = run_in(&box, ARGS("--size", "16x9", "--scene", "s.luz", "-o", "before.png"), NULL);
    assert_success(&result);
    assert_png_size(&box, "before.png", 16, 9);
    run_result_free(&result);
    result = run_in(&box, ARGS("--scene", "s.luz", "--size=16x9", "-o", "after.png"), NULL);
    assert_success(&result);
    assert_png_size(&box, "after.png", 16, 9);
    run_result_free(&result);

    /* --textures on the command line beats the file's `none` */
    write_text(box.work, "cubes.luz",
               "size = 24x16\n"
               "textures = none\n"
               "cube = 0, 0, 0 colour 1, 0, 0 texture b.bmp\n"
               "cube = 1.5, 0.5, -1   texture a.bmp colour 0, 1, 0.5\n"
               "cube = -1.5, -0.5, -1\n");
    result = run_in(&box, ARGS("--scene", "cubes.luz", "--textures", "tex", "-o", "cubes.png"),
                    NULL);
    assert_success(&result);
    assert_png_size(&box, "cubes.png", 24, 16);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* The options reach the picture: with --only ambient and a black ambient
 * light, every cube is black and the background keeps SCENE.md's clear
 * colour 0.1 (26 of 255); the point light's marker is not drawn since its
 * strength is 0. With the default lights some pixel is something else. */
static void test_options_reach_the_image(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "64x36", "--textures", "none", "--only",
                                          "ambient", "--ambient", "0,0,0,1", "-o", "dark.png"),
                               NULL);
    assert_success(&result);
    run_result_free(&result);
    result = run_in(&box, ARGS("--size", "64x36", "--textures", "none", "-o", "lit.png"), NULL);
    assert_success(&result);
    run_result_free(&result);

    char path[600];
    int width, height, channels;
    sandbox_path(&box, "dark.png", path, sizeof path);
    unsigned char *dark = stbi_load(path, &width, &height, &channels, 3);
    assert_non_null(dark);
    assert_int_equal(width, 64);
    assert_int_equal(height, 36);
    int black = 0, background = 0;
    for (int i = 0; i < width * height; i++) {
        const unsigned char *p = dark + 3 * i;
        if (p[0] == 0 && p[1] == 0 && p[2] == 0)
            black++;
        else if (p[0] == 26 && p[1] == 26 && p[2] == 26)
            background++;
        else
            fail_msg("pixel %d is %d,%d,%d: neither black cube nor background", i, p[0], p[1],
                     p[2]);
    }
    assert_true(black > 0);
    assert_true(background > 0);
    stbi_image_free(dark);

    sandbox_path(&box, "lit.png", path, sizeof path);
    unsigned char *lit = stbi_load(path, &width, &height, &channels, 3);
    assert_non_null(lit);
    int other = 0;
    for (int i = 0; i < width * height * 3; i++)
        other += lit[i] != 0 && lit[i] != 26;
    assert_true(other > 0);
    stbi_image_free(lit);
    sandbox_destroy(&box);
}

/* Renders args into NAME.png in the box and loads it as RGB. */
static unsigned char *render_and_load(const sandbox *box, const char *const *arguments,
                                      const char *name, int width, int height)
{
    run_result result = run_in(box, arguments, NULL);
    assert_success(&result);
    run_result_free(&result);
    char path[600];
    int w, h, channels;
    sandbox_path(box, name, path, sizeof path);
    unsigned char *image = stbi_load(path, &w, &h, &channels, 3);
    assert_non_null(image);
    assert_int_equal(w, width);
    assert_int_equal(h, height);
    return image;
}

static bool same_pixel(const unsigned char *a, const unsigned char *b, int width, int x, int y)
{
    return memcmp(a + 3 * ((size_t)y * width + x), b + 3 * ((size_t)y * width + x), 3) == 0;
}

static void assert_rgb(const unsigned char *image, int width, int x, int y, int r, int g, int b)
{
    const unsigned char *p = image + 3 * ((size_t)y * width + x);
    if (p[0] != r || p[1] != g || p[2] != b)
        fail_msg("pixel (%d, %d) is (%d, %d, %d), expected (%d, %d, %d)", x, y, p[0], p[1],
                 p[2], r, g, b);
}

/* --exposure and --tonemap reach the image, worked by hand: a white cube
 * lit by the ambient light alone at strength 0.5 is 0.5 everywhere, byte
 * round(127.5) = 128. EV 1 doubles it to 1 (255), EV -1 halves it to 0.25
 * (63.75: 64). Neutral at EV 0 takes off 0.04 (0.46: 117.3, 117); at
 * EV 1, white: 1 - 0.04 = 0.96, compressed to 1 - 0.0576 / 0.44 =
 * 0.8690909 (221.6: 222). The background stays 26 whatever the output.
 * The same keys in a scene file give the same image. */
static void test_exposure_and_tone_map_reach_the_image(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    write_text(box.work, "white.luz",
               "size = 32x18\ntextures = none\nonly = ambient\nambient = 1, 1, 1, 0.5\n"
               "cube = 0, 0, 0 colour 1, 1, 1\n");
    static const struct {
        const char *exposure, *tone_map;
        int byte;
    } cases[] = {
        {"0", "clamp", 128},   {"1", "clamp", 255},    {"-1", "clamp", 64},
        {"0", "neutral", 117}, {"1", "neutral", 222},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        unsigned char *image = render_and_load(
            &box,
            ARGS("--scene", "white.luz", "--exposure", cases[i].exposure, "--tonemap",
                 cases[i].tone_map, "-o", "out.png"),
            "out.png", 32, 18);
        assert_rgb(image, 32, 16, 9, cases[i].byte, cases[i].byte, cases[i].byte);
        assert_rgb(image, 32, 0, 0, 26, 26, 26);
        stbi_image_free(image);
    }
    /* The probe at the cube's centre pixel, worked by hand: colour 0.5
     * (ambient 0.5 x C 1 x T 1), exposure 1, tonemap neutral, exposed
     * 0.5 x 2 = 1, mapped 1 - 0.0576 / 0.44 = 0.8690909 after the offset
     * 0.04, bytes 222. */
    run_result probed = run_in(&box,
                               ARGS("--scene", "white.luz", "--exposure", "1", "--tonemap",
                                    "neutral", "--probe", "16,9"),
                               NULL);
    assert_success(&probed);
    char value[256];
    assert_string_equal(key_value(probed.out, "colour", value, sizeof value), "0.5,0.5,0.5");
    assert_string_equal(key_value(probed.out, "exposure", value, sizeof value), "1");
    assert_string_equal(key_value(probed.out, "tonemap", value, sizeof value), "neutral");
    assert_string_equal(key_value(probed.out, "exposed", value, sizeof value), "1,1,1");
    key_value(probed.out, "mapped", value, sizeof value);
    float mapped[3];
    assert_int_equal(sscanf(value, "%f,%f,%f", &mapped[0], &mapped[1], &mapped[2]), 3);
    for (int c = 0; c < 3; c++) assert_true(fabsf(mapped[c] - 0.8690909f) < 1e-6f);
    assert_string_equal(key_value(probed.out, "bytes", value, sizeof value), "222,222,222");
    /* the lines in this order, after colour */
    assert_non_null(strstr(probed.out, "\ncolour=0.5,0.5,0.5\nexposure=1\ntonemap=neutral\n"
                                       "exposed=1,1,1\nmapped="));
    run_result_free(&probed);
    /* and clamp at EV -1: exposed = mapped = 0.25, bytes 64 */
    probed = run_in(&box, ARGS("--scene", "white.luz", "--exposure", "-1", "--probe", "16,9"),
                    NULL);
    assert_success(&probed);
    assert_string_equal(key_value(probed.out, "tonemap", value, sizeof value), "clamp");
    assert_string_equal(key_value(probed.out, "exposed", value, sizeof value), "0.25,0.25,0.25");
    assert_string_equal(key_value(probed.out, "mapped", value, sizeof value), "0.25,0.25,0.25");
    assert_string_equal(key_value(probed.out, "bytes", value, sizeof value), "64,64,64");
    run_result_free(&probed);

    write_text(box.work, "neutral.luz",
               "size = 32x18\ntextures = none\nonly = ambient\nambient = 1, 1, 1, 0.5\n"
               "cube = 0, 0, 0 colour 1, 1, 1\nexposure = 1\ntonemap = neutral\n");
    unsigned char *image = render_and_load(&box, ARGS("--scene", "neutral.luz", "-o", "out.png"),
                                           "out.png", 32, 18);
    assert_rgb(image, 32, 16, 9, 222, 222, 222);
    stbi_image_free(image);
    sandbox_destroy(&box);
}

/* --mark rings a pixel and leaves it and the pixels around it as rendered:
 * along the marked row, the ring is black 8 pixels out, white 7 and 6, and
 * black 5 (at an image under 1000 wide); 4 pixels out and nearer nothing
 * changes. --legend draws the view's key bottom left and nothing else;
 * with the colour view it draws nothing at all. */
static void test_mark_and_legend(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    enum { W = 160, H = 90, X = 80, Y = 50 };
    unsigned char *plain = render_and_load(
        &box, ARGS("--size", "160x90", "--textures", "none", "-o", "plain.png"), "plain.png", W, H);
    unsigned char *marked = render_and_load(
        &box, ARGS("--size", "160x90", "--textures", "none", "--mark", "80,50", "-o", "marked.png"),
        "marked.png", W, H);
    for (int dy = -4; dy <= 4; dy++)
        for (int dx = -4; dx <= 4; dx++)
            if (!same_pixel(plain, marked, W, X + dx, Y + dy))
                fail_msg("--mark changed pixel (%d, %d), inside its ring", X + dx, Y + dy);
    for (int side = -1; side <= 1; side += 2) {
        assert_rgb(marked, W, X + side * 8, Y, 0, 0, 0);
        assert_rgb(marked, W, X + side * 7, Y, 255, 255, 255);
        assert_rgb(marked, W, X + side * 6, Y, 255, 255, 255);
        assert_rgb(marked, W, X + side * 5, Y, 0, 0, 0);
        assert_rgb(marked, W, X, Y + side * 8, 0, 0, 0);
    }
    /* far from the ring and its ticks: untouched */
    assert_true(same_pixel(plain, marked, W, 10, 10));
    assert_true(same_pixel(plain, marked, W, 150, 80));

    /* The legend: only in the bottom-left corner, only for a view. */
    enum { LW = 320, LH = 180 };
    unsigned char *mip = render_and_load(
        &box, ARGS("--size", "320x180", "--textures", "none", "--view", "mip", "-o", "mip.png"),
        "mip.png", LW, LH);
    unsigned char *keyed = render_and_load(
        &box,
        ARGS("--size", "320x180", "--textures", "none", "--view", "mip", "--legend", "-o",
             "keyed.png"),
        "keyed.png", LW, LH);
    int changed_bottom = 0;
    for (int y = 0; y < LH; y++) {
        for (int x = 0; x < LW; x++) {
            bool same = same_pixel(mip, keyed, LW, x, y);
            if ((y < LH / 2 || x > LW - 6) && !same)
                fail_msg("--legend changed pixel (%d, %d), outside the bottom left", x, y);
            changed_bottom += !same;
        }
    }
    assert_true(changed_bottom > 2000);
    unsigned char *colour_keyed = render_and_load(
        &box, ARGS("--size", "160x90", "--textures", "none", "--legend", "-o", "colour.png"),
        "colour.png", W, H);
    assert_memory_equal(colour_keyed, plain, (size_t)W * H * 3);

    stbi_image_free(plain);
    stbi_image_free(marked);
    stbi_image_free(mip);
    stbi_image_free(keyed);
    stbi_image_free(colour_keyed);
    sandbox_destroy(&box);
}

/* The viewer's orbit camera end to end: a view set through the controls
 * (the scene framed, turned round its target, dollied), saved as F2 saves
 * it, is rendered by luz-render to the very bytes of the viewer's frame
 * (the scene drawn in this process as luz_viewer.c's draw_frame draws it,
 * without its HUD). The orbit's view is not the default one, so the check
 * would catch a camera saved from the wrong place. */
static void test_orbit_view_renders_the_same_in_luz_render(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char textures_path[600], scene_path[600];
    sandbox_path(&box, "tex", textures_path, sizeof textures_path);
    sandbox_path(&box, "orbit.luz", scene_path, sizeof scene_path);
    enum { WIDTH = 96, HEIGHT = 54 };
    const float aspect = (float)WIDTH / (float)HEIGHT;

    luz_options options;
    char *argv[] = {"luz", "--size", "96x54", "--textures", textures_path, "--time", "1.25",
                    NULL};
    parse_or_fail(&options, 7, argv);
    luz_error error = {{0}};
    luz_texture_set textures = {0};
    assert_int_equal(luz_options_load_textures(&options, &textures, NULL, &error), 0);

    luz_scene *scene = &options.scene;
    luz_orbit orbit = luz_orbit_from_camera(&scene->camera, (luz_vec3){0.0f, 0.0f, 0.0f});
    luz_orbit_frame(&orbit, &scene->camera, luz_scene_bounding_sphere(scene), aspect);
    luz_orbit_turn(&orbit, &scene->camera, 157.0f, -63.0f);
    luz_orbit_dolly(&orbit, &scene->camera, 3.0f);
    assert_true(scene->camera.yaw_degrees != -90.0f && scene->camera.pitch_degrees != 0.0f);

    /* The viewer's frame. */
    const luz_renderer_desc desc = luz_options_renderer_desc(&options);
    luz_renderer *renderer = luz_renderer_create(&desc, &error);
    luz_lab *lab = luz_lab_create(&error);
    luz_framebuffer *framebuffer = luz_framebuffer_create(WIDTH, HEIGHT, &error);
    assert_non_null(renderer);
    assert_non_null(lab);
    assert_non_null(framebuffer);
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(lab, scene, textures.textures, textures.count, aspect,
                                           &frame, &error),
                     0);
    const luz_render_options render = luz_scene_render_options(scene);
    assert_int_equal(luz_renderer_draw(renderer, &frame, framebuffer, &render, &error), 0);

    /* F2's file, rendered by luz-render. */
    assert_int_equal(luz_options_save_scene(&options, scene_path, false, &error), 0);
    unsigned char *saved = render_and_load(&box, ARGS("--scene", "orbit.luz", "-o", "orbit.png"),
                                           "orbit.png", WIDTH, HEIGHT);
    int differing = 0;
    for (int i = 0; i < WIDTH * HEIGHT; i++)
        differing += memcmp(saved + 3 * i, framebuffer->colour + 4 * i, 3) != 0;
    assert_int_equal(differing, 0);

    /* and the default camera's picture is another one */
    unsigned char *start = render_and_load(
        &box, ARGS("--size", "96x54", "--textures", "tex", "--time", "1.25", "-o", "start.png"),
        "start.png", WIDTH, HEIGHT);
    differing = 0;
    for (int i = 0; i < WIDTH * HEIGHT; i++)
        differing += memcmp(start + 3 * i, saved + 3 * i, 3) != 0;
    assert_true(differing > WIDTH * HEIGHT / 4);

    stbi_image_free(start);
    stbi_image_free(saved);
    luz_frame_free(&frame);
    luz_framebuffer_destroy(framebuffer);
    luz_lab_destroy(lab);
    luz_renderer_destroy(renderer);
    luz_texture_set_free(&textures);
    luz_options_free(&options);
    sandbox_destroy(&box);
}

/* --bug help lists every bug; --quiz SEED hides its bug from the probe,
 * which names a --bug; --answer says right (0) or wrong (1). The quiz's
 * bug is worked out here from docs/teaching.md's rule: xorshift32 four
 * times from the seed, then floor((x >> 8) / 2^24 x 9) into its list. */
static void test_bug_quiz_and_answer(void **state)
{
    (void)state;
    static const char *const quiz_list[9] = {
        "diffuse-reversed", "directional-unclamped", "spot-reach-twice",
        "normal-matrix-is-model", "specular-half-vector", "uv-affine", "lod-off-by-one",
        "no-depth-test", "no-backface-culling"};
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--bug", "help"), NULL);
    assert_success(&result);
    for (int bug = 1; bug < LUZ_BUG_COUNT; bug++)
        assert_contains(result.out, luz_bug_name((luz_bug)bug));
    run_result_free(&result);

    for (uint32_t seed = 1; seed <= 3; seed++) {
        uint32_t x = seed;
        for (int step = 0; step < 4; step++) {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
        }
        const char *bug = quiz_list[((x >> 8) * 9u) >> 24];
        char seed_text[8];
        snprintf(seed_text, sizeof seed_text, "%u", (unsigned)seed);
        result = run_in(&box, ARGS("--quiz", seed_text, "--answer", bug), NULL);
        assert_success(&result);
        assert_true(strncmp(result.out, "right: ", 7) == 0);
        assert_contains(result.out, bug);
        run_result_free(&result);
        const char *other = strcmp(bug, "uv-affine") == 0 ? "no-depth-test" : "uv-affine";
        result = run_in(&box, ARGS("--quiz", seed_text, "--answer", other), NULL);
        assert_int_equal(result.status, 1);
        assert_string_equal(result.err, "");
        assert_true(strncmp(result.out, "wrong: ", 7) == 0);
        assert_contains(result.out, bug);
        run_result_free(&result);
        /* the probe does not tell */
        result = run_in(&box, ARGS("--size", "32x18", "--textures", "none", "--quiz", seed_text,
                                   "--probe", "16,9"),
                        NULL);
        assert_success(&result);
        assert_contains(result.out, "\nbug=hidden (quiz)\n");
        assert_null(strstr(result.out, bug));
        run_result_free(&result);
    }
    result = run_in(&box, ARGS("--size", "32x18", "--textures", "none", "--bug",
                               "diffuse-reversed", "--probe", "16,9"),
                    NULL);
    assert_success(&result);
    assert_contains(result.out, "\nbug=diffuse-reversed\n");
    run_result_free(&result);
    sandbox_destroy(&box);
}

int main(void)
{
    static const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bug_quiz_and_answer),
        cmocka_unit_test(test_help),
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_tiny_render),
        cmocka_unit_test(test_probe),
        cmocka_unit_test(test_probe_example_in_the_docs),
        cmocka_unit_test(test_equals_form_and_default_output),
        cmocka_unit_test(test_textures_directory),
        cmocka_unit_test(test_bench),
        cmocka_unit_test(test_scene_file_and_precedence),
        cmocka_unit_test(test_options_reach_the_image),
        cmocka_unit_test(test_mark_and_legend),
        cmocka_unit_test(test_exposure_and_tone_map_reach_the_image),
        cmocka_unit_test(test_orbit_view_renders_the_same_in_luz_render),
    };
    return _cmocka_run_group_tests("cli-render", tests, sizeof tests / sizeof tests[0], NULL, NULL);
}
