/*
 * image-compare: how far apart two renderings of the same scene are.
 *
 *   image-compare luz.png gl.png [--diff diff.png] [--amplify K] [--list N]
 *                 [--min-psnr DB] [--max-over8 PERCENT] [--exact-below PIXELS]
 *
 * Prints one line of figures over the RGB channels (alpha is ignored):
 *
 *   psnr=56.21 max_diff=9 max_at=312,80 over1=0.0213% over8=0.0011% over8_pixels=10 pixels=921600
 *
 *   psnr         10 log10(255^2 / MSE), the MSE over every channel of every
 *                pixel; "inf" for identical images
 *   max_diff     the largest difference of one channel, in levels of 255,
 *                and max_at the first pixel (x,y; row 0 on top) that has it
 *   over1/over8  the share of pixels with some channel off by more than 1
 *                (more than rounding) and by more than 8 levels
 *
 * With --diff it writes the difference image: |a - b| per channel times K
 * (--amplify, 32 by default), so a difference of one level shows as 32 and
 * anything from 8 up is saturated. The thresholds, when given, are checked:
 * PSNR at least DB, at most PERCENT % of the pixels over 8, and none over 8
 * at all on images of fewer than PIXELS pixels; the line then ends in
 * "pass" or "FAIL (reason)". --list N prints, after the line, the first N
 * pixels off by more than 8, with both colours, to find them in the images.
 *
 * Exit status: 0 (the thresholds hold, or none were given), 1 (they do
 * not), 2 (bad arguments, an unreadable image, or sizes that differ).
 */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "luz/error.h"
#include "io/image.h"

typedef struct compare_options {
    const char *paths[2];
    const char *diff_path;
    int amplify;
    long list;                /* pixels over 8 to print */
    double min_psnr;          /* < 0: not checked */
    double max_over8_percent; /* < 0: not checked */
    long exact_below;         /* 0: not checked */
} compare_options;

typedef struct figures {
    double psnr;
    int max_diff, max_x, max_y;
    long over1, over8, pixels;
} figures;

static int usage(const char *message)
{
    fprintf(stderr, "image-compare: %s\n"
                    "usage: image-compare A.png B.png [--diff OUT.png] [--amplify K] "
                    "[--list N] [--min-psnr DB] [--max-over8 PERCENT] [--exact-below PIXELS]\n",
            message);
    return 2;
}

static bool parse_number(const char *text, double low, double high, double *out)
{
    char *end;
    double value = strtod(text, &end);
    if (end == text || *end != '\0' || !(value >= low && value <= high)) return false;
    *out = value;
    return true;
}

static int parse_arguments(int argc, char **argv, compare_options *options)
{
    int path_count = 0;
    for (int k = 1; k < argc; k++) {
        const char *arg = argv[k];
        if (arg[0] != '-' || arg[1] == '\0') {
            if (path_count == 2) return usage("more than two images");
            options->paths[path_count++] = arg;
            continue;
        }
        if (k + 1 >= argc) return usage("an option without its value");
        const char *value = argv[++k];
        double number;
        if (strcmp(arg, "--diff") == 0) {
            options->diff_path = value;
        } else if (strcmp(arg, "--amplify") == 0) {
            if (!parse_number(value, 1, 255, &number)) return usage("--amplify: 1 to 255");
            options->amplify = (int)number;
        } else if (strcmp(arg, "--list") == 0) {
            if (!parse_number(value, 0, 1e9, &number)) return usage("--list: a count");
            options->list = (long)number;
        } else if (strcmp(arg, "--min-psnr") == 0) {
            if (!parse_number(value, 0, 1000, &number)) return usage("--min-psnr: decibels");
            options->min_psnr = number;
        } else if (strcmp(arg, "--max-over8") == 0) {
            if (!parse_number(value, 0, 100, &number)) return usage("--max-over8: a percentage");
            options->max_over8_percent = number;
        } else if (strcmp(arg, "--exact-below") == 0) {
            if (!parse_number(value, 0, 1e12, &number)) return usage("--exact-below: pixels");
            options->exact_below = (long)number;
        } else {
            return usage("unknown option");
        }
    }
    if (path_count != 2) return usage("two images are needed");
    return 0;
}

static figures compare(const uint8_t *a, const uint8_t *b, int width, int height,
                       uint8_t *diff, int amplify)
{
    figures f = {0};
    f.pixels = (long)width * height;
    double squared_sum = 0.0;
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            size_t i = ((size_t)y * width + x) * 4;
            int largest = 0;
            for (int c = 0; c < 3; c++) {
                int d = abs((int)a[i + c] - (int)b[i + c]);
                squared_sum += (double)d * d;
                if (d > largest) largest = d;
                if (diff) diff[i + c] = (uint8_t)(d * amplify > 255 ? 255 : d * amplify);
            }
            if (diff) diff[i + 3] = 255;
            if (largest > f.max_diff) {
                f.max_diff = largest;
                f.max_x = x;
                f.max_y = y;
            }
            f.over1 += largest > 1;
            f.over8 += largest > 8;
        }
    }
    double mse = squared_sum / ((double)f.pixels * 3.0);
    f.psnr = mse > 0.0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
    return f;
}

int main(int argc, char **argv)
{
    compare_options options = {.amplify = 32, .min_psnr = -1, .max_over8_percent = -1};
    int status = parse_arguments(argc, argv, &options);
    if (status != 0) return status;

    int width[2], height[2];
    uint8_t *pixels[2] = {NULL, NULL};
    uint8_t *diff = NULL;
    status = 2;
    for (int k = 0; k < 2; k++) {
        int channels;
        pixels[k] = stbi_load(options.paths[k], &width[k], &height[k], &channels, 4);
        if (pixels[k] == NULL) {
            fprintf(stderr, "image-compare: %s: %s\n", options.paths[k], stbi_failure_reason());
            goto done;
        }
    }
    if (width[0] != width[1] || height[0] != height[1]) {
        fprintf(stderr, "image-compare: %s is %dx%d but %s is %dx%d\n", options.paths[0],
                width[0], height[0], options.paths[1], width[1], height[1]);
        goto done;
    }
    if (options.diff_path) {
        diff = malloc((size_t)width[0] * height[0] * 4);
        if (diff == NULL) {
            fprintf(stderr, "image-compare: out of memory\n");
            goto done;
        }
    }

    figures f = compare(pixels[0], pixels[1], width[0], height[0], diff, options.amplify);
    if (isinf(f.psnr))
        printf("psnr=inf");
    else
        printf("psnr=%.2f", f.psnr);
    printf(" max_diff=%d max_at=%d,%d over1=%.4f%% over8=%.4f%% over8_pixels=%ld pixels=%ld",
           f.max_diff, f.max_x, f.max_y, 100.0 * f.over1 / f.pixels,
           100.0 * f.over8 / f.pixels, f.over8, f.pixels);

    /* The thresholds, every failed one named. */
    char reasons[256] = "";
    if (options.min_psnr >= 0 && f.psnr < options.min_psnr)
        snprintf(reasons + strlen(reasons), sizeof reasons - strlen(reasons),
                 "%sPSNR below %g dB", reasons[0] ? ", " : "", options.min_psnr);
    if (options.max_over8_percent >= 0 &&
        100.0 * f.over8 / f.pixels > options.max_over8_percent)
        snprintf(reasons + strlen(reasons), sizeof reasons - strlen(reasons),
                 "%smore than %g%% of pixels off by more than 8", reasons[0] ? ", " : "",
                 options.max_over8_percent);
    if (f.pixels < options.exact_below && f.over8 > 0)
        snprintf(reasons + strlen(reasons), sizeof reasons - strlen(reasons),
                 "%sa pixel off by more than 8 on an image under %ld pixels",
                 reasons[0] ? ", " : "", options.exact_below);
    bool checked = options.min_psnr >= 0 || options.max_over8_percent >= 0 ||
                   options.exact_below > 0;
    if (checked && reasons[0]) printf(" FAIL (%s)", reasons);
    else if (checked) printf(" pass");
    printf("\n");
    status = reasons[0] ? 1 : 0;

    /* The pixels off by more than 8, for a closer look. */
    long listed = 0;
    for (long i = 0; i < f.pixels && listed < options.list; i++) {
        const uint8_t *a = pixels[0] + i * 4, *b = pixels[1] + i * 4;
        int largest = 0;
        for (int c = 0; c < 3; c++)
            if (abs(a[c] - b[c]) > largest) largest = abs(a[c] - b[c]);
        if (largest <= 8) continue;
        printf("  pixel %ld,%ld: %d,%d,%d against %d,%d,%d\n", i % width[0], i / width[0], a[0],
               a[1], a[2], b[0], b[1], b[2]);
        listed++;
    }

    if (diff) {
        luz_error error = {{0}};
        if (luz_png_write(options.diff_path, width[0], height[0], diff, &error) != 0) {
            fprintf(stderr, "image-compare: %s\n", error.message);
            status = 2;
        }
    }

done:
    free(diff);
    stbi_image_free(pixels[0]);
    stbi_image_free(pixels[1]);
    if (fflush(stdout) != 0 && status == 0) status = 2;
    return status;
}
