/*
 * check_torus.c: checks the picture examples/torus.c draws, against the
 * torus's geometry worked out by hand.
 *
 * The camera is 4 units in front of the origin, looking at it, with a
 * 45-degree field of view on a 256 x 256 image: a point (x, y, z) of the
 * world lands at pixel column 128 + x / (4 - z) / tan(22.5 deg) * 128.
 * The torus (ring radius R = 1, tube radius r = 0.35) is turned about the
 * x axis, which moves nothing on the horizontal line through the centre:
 *
 *   - the tube's front at (+-1, 0, 0.35) projects to 128 +- 1 / 3.65 /
 *     0.41421 * 128 = 128 +- 84.7: covered, and orange (the material is
 *     (0.9, 0.5, 0.2) under white and warm light, so red > green > blue);
 *   - the hole: the inner silhouette is no nearer the centre than
 *     (R - r) / (4 + r) / 0.41421 * 128 = 46.2 pixels, so within 40
 *     pixels of the centre is background, (0.1, 0.1, 0.1) = 26;
 *   - the outer silhouette is no farther than (R + r) / (4 - r) / 0.41421
 *     * 128 = 114.3 pixels, so from 120 on is background too, as are the
 *     corners.
 *
 * Usage: check_torus FILE.png. Exit status 0 if every check holds.
 */
#include <stdio.h>
#include <stdlib.h>

#include <stb_image.h>

static int failures;

static const unsigned char *at(const unsigned char *image, int x, int y)
{
    return image + ((size_t)y * 256 + (size_t)x) * 4;
}

static void expect_background(const unsigned char *image, int x, int y)
{
    const unsigned char *p = at(image, x, y);
    if (p[0] != 26 || p[1] != 26 || p[2] != 26 || p[3] != 255) {
        fprintf(stderr, "check_torus: pixel (%d, %d) is (%d, %d, %d, %d), expected the "
                        "background (26, 26, 26, 255)\n", x, y, p[0], p[1], p[2], p[3]);
        failures++;
    }
}

static void expect_orange(const unsigned char *image, int x, int y)
{
    const unsigned char *p = at(image, x, y);
    if (!(p[0] > p[1] && p[1] > p[2] && p[0] > 60)) {
        fprintf(stderr, "check_torus: pixel (%d, %d) is (%d, %d, %d), expected the lit "
                        "orange torus (red > green > blue)\n", x, y, p[0], p[1], p[2]);
        failures++;
    }
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: check_torus FILE.png\n");
        return 2;
    }
    int width, height, channels;
    unsigned char *image = stbi_load(argv[1], &width, &height, &channels, 4);
    if (image == NULL || width != 256 || height != 256) {
        fprintf(stderr, "check_torus: %s: expected a 256x256 PNG\n", argv[1]);
        return 1;
    }
    for (int side = -1; side <= 1; side += 2) {
        expect_orange(image, 128 + side * 85, 128);
        expect_orange(image, 128 + side * 80, 128);
        for (int d = 0; d <= 40; d += 10) expect_background(image, 128 + side * d, 128);
        for (int d = 120; d <= 127; d++) expect_background(image, 128 + side * d, 128);
    }
    expect_background(image, 0, 0);
    expect_background(image, 255, 0);
    expect_background(image, 0, 255);
    expect_background(image, 255, 255);
    stbi_image_free(image);
    if (failures == 0) printf("check_torus: %s: the torus where its geometry puts it\n", argv[1]);
    return failures == 0 ? 0 : 1;
}
