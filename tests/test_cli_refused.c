/*
 * test_cli_refused.c: every input luz-render refuses, as a user meets it.
 *
 * Each case runs the real luz-render (its path in $LUZ_RENDER, set by
 * tests/meson.build) in a fresh sandbox (cli_support.h), with a scene file
 * s.luz where the case gives one. Every refused input must give exit
 * status 2, exactly one line naming the flag (or FILE:LINE) and what was
 * expected, and no file at all: neither the PNG nor the writer's
 * temporary. Then a NUL byte in a scene file, a size refused before any
 * allocation, and error messages that name long paths whole.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "cli_support.h"

typedef struct error_case {
    const char *name;
    const char *arguments[16];       /* NULL-terminated */
    const char *scene;               /* the text of s.luz, or NULL */
    const char *textures_environment;
    const char *needles[4];          /* each must appear in the one line */
} error_case;

/* Ten copies of a string literal: for a scene line longer than the reader
 * accepts. */
#define TEN(text) text text text text text text text text text text

static const error_case error_cases[] = {
    /* the shape of the command line */
    {"unknown-option", {"--bogus"}, NULL, NULL, {"--bogus", "unknown"}},
    {"unknown-option-with-value", {"--colour=red"}, NULL, NULL, {"--colour", "unknown"}},
    {"unknown-short-option", {"-x"}, NULL, NULL, {"-x", "unknown"}},
    {"stray-argument", {"picture.png"}, NULL, NULL, {"picture.png", "unexpected"}},
    {"missing-value-at-end", {"--size", "16x9", "--time"}, NULL, NULL, {"--time", "missing"}},
    {"missing-value-after-equals", {"--time="}, NULL, NULL, {"--time", "missing"}},
    {"missing-value-empty", {"--textures", ""}, NULL, NULL, {"--textures", "missing"}},
    {"missing-output", {"-o"}, NULL, NULL, {"-o", "missing"}},
    {"flag-with-value", {"--help=yes"}, NULL, NULL, {"--help", "no value"}},
    /* numbers */
    {"time-malformed", {"--time", "abc"}, NULL, NULL, {"--time", "number"}},
    {"time-trailing-junk", {"--time", "1.5s"}, NULL, NULL, {"--time", "number"}},
    {"time-nan", {"--time", "nan"}, NULL, NULL, {"--time", "finite"}},
    {"time-inf", {"--time=-inf"}, NULL, NULL, {"--time", "finite"}},
    {"time-overflow", {"--time", "1e400"}, NULL, NULL, {"--time", "finite"}},
    /* finite, but cube i's angle (i + 1) / 3 * 50 t overflows at 1e302 */
    {"time-beyond-range", {"--time", "1.7e308"}, NULL, NULL,
     {"--time", "[-1000000000, 1000000000]"}},
    {"time-just-beyond-range", {"--time=-1000000000.5"}, NULL, NULL,
     {"--time", "[-1000000000, 1000000000]", "'-1000000000.5'"}},
    {"seed-trailing-junk", {"--seed", "12abc"}, NULL, NULL, {"--seed", "integer"}},
    {"seed-negative", {"--seed", "-1"}, NULL, NULL, {"--seed", "0 to 4294967295"}},
    {"seed-too-large", {"--seed", "4294967296"}, NULL, NULL, {"--seed", "0 to 4294967295"}},
    {"seed-fraction", {"--seed", "1.5"}, NULL, NULL, {"--seed", "integer"}},
    {"camera-pos-two", {"--camera-pos", "1,2"}, NULL, NULL, {"--camera-pos", "x,y,z"}},
    {"camera-pos-four", {"--camera-pos", "1,2,3,4"}, NULL, NULL, {"--camera-pos", "x,y,z"}},
    {"camera-pos-empty-field", {"--camera-pos", "1,,3"}, NULL, NULL, {"--camera-pos", "x,y,z"}},
    {"camera-pos-inf", {"--camera-pos", "0,0,-inf"}, NULL, NULL, {"--camera-pos", "finite"}},
    {"camera-pos-beyond-range", {"--camera-pos", "0,3e38,0"}, NULL, NULL,
     {"--camera-pos", "each in [-10000, 10000]"}},
    {"camera-pos-just-beyond-range", {"--camera-pos", "-10000.01,0,0"}, NULL, NULL,
     {"--camera-pos", "each in [-10000, 10000]"}},
    {"camera-yaw-beyond-float", {"--camera-yaw", "1e39"}, NULL, NULL,
     {"--camera-yaw", "finite"}},
    {"camera-yaw-nan", {"--camera-yaw", "NaN"}, NULL, NULL, {"--camera-yaw", "finite"}},
    /* just past FLT_MAX's rounding range (FLT_MAX's own 3.4028235e38 reads) */
    {"camera-yaw-rounds-to-infinity", {"--camera-yaw", "3.40282357e38"}, NULL, NULL,
     {"--camera-yaw", "finite"}},
    {"paused-not-yes-no", {"--paused", "true"}, NULL, NULL, {"--paused", "yes or no"}},
    {"mark-odd", {"--mark", "10,20,30"}, NULL, NULL, {"--mark", "X,Y"}},
    {"mark-negative", {"--mark", "-1,5"}, NULL, NULL, {"--mark", "X,Y"}},
    {"mark-junk", {"--mark", "10;20"}, NULL, NULL, {"--mark", "X,Y"}},
    {"mark-outside", {"--size", "64x36", "--mark", "10,36"}, NULL, NULL,
     {"--mark", "inside the 64x36 image"}},
    {"mark-too-many", {"--mark", "1,1,2,2,3,3,4,4,5,5,6,6,7,7,8,8,9,9"}, NULL, NULL,
     {"--mark", "at most 8"}},
    {"legend-with-value", {"--legend=yes"}, NULL, NULL, {"--legend", "no value"}},
    {"scene-mark", {"--scene", "s.luz"}, "mark = 1,1\n", NULL, {"s.luz:1", "mark"}},
    {"scene-paused-not-yes-no", {"--scene", "s.luz"}, "paused = 1\n", NULL,
     {"s.luz:1: paused", "yes or no"}},
    {"camera-pitch-above", {"--camera-pitch", "90"}, NULL, NULL,
     {"--camera-pitch", "[-89, 89]"}},
    {"camera-pitch-below", {"--camera-pitch=-89.5"}, NULL, NULL,
     {"--camera-pitch", "[-89, 89]"}},
    {"fov-zero", {"--fov", "0"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-180", {"--fov", "180"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-negative", {"--fov", "-5"}, NULL, NULL, {"--fov", "[1, 179]"}},
    /* the issue's case: a blank image after dividing by tan(fov / 2) = 0 */
    {"fov-denormal", {"--fov", "1e-45"}, NULL, NULL, {"--fov", "[1, 179]", "'1e-45'"}},
    {"fov-below-one", {"--fov", "0.999"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-above-179", {"--fov", "179.001"}, NULL, NULL, {"--fov", "[1, 179]"}},
    {"fov-inf", {"--fov=inf"}, NULL, NULL, {"--fov", "finite"}},
    {"shininess-negative", {"--shininess", "-1"}, NULL, NULL, {"--shininess", "[0, 100000]"}},
    {"shininess-beyond-range", {"--shininess", "3e38"}, NULL, NULL,
     {"--shininess", "[0, 100000]"}},
    {"spot-reach-zero", {"--spot-reach", "0"}, NULL, NULL, {"--spot-reach", "[0.1, 10000]"}},
    {"spot-reach-negative", {"--spot-reach", "-2"}, NULL, NULL,
     {"--spot-reach", "[0.1, 10000]"}},
    {"spot-reach-denormal", {"--spot-reach", "1e-45"}, NULL, NULL,
     {"--spot-reach", "[0.1, 10000]"}},
    {"spot-reach-beyond-range", {"--spot-reach", "10001"}, NULL, NULL,
     {"--spot-reach", "[0.1, 10000]"}},
    {"spot-inner-negative", {"--spot-inner", "-1"}, NULL, NULL, {"--spot-inner", "[0, 89]"}},
    {"spot-outer-above", {"--spot-outer", "90"}, NULL, NULL, {"--spot-outer", "[0, 89]"}},
    {"spot-inner-wider-than-default-outer", {"--spot-inner", "20"}, NULL, NULL,
     {"--spot-inner", "--spot-outer"}},
    {"spot-inner-wider-than-outer", {"--spot-inner", "10", "--spot-outer", "5"}, NULL, NULL,
     {"--spot-inner", "--spot-outer"}},
    /* colours and strengths */
    {"ambient-strength-above-one", {"--ambient", "1,1,1,1.5"}, NULL, NULL,
     {"--ambient", "[0, 1]"}},
    {"diffuse-negative", {"--diffuse", "-0.1,1,1,1"}, NULL, NULL, {"--diffuse", "[0, 1]"}},
    {"specular-colour-above-one", {"--specular=2,0,0,1"}, NULL, NULL,
     {"--specular", "[0, 1]"}},
    {"point-three-values", {"--point", "1,1,1"}, NULL, NULL, {"--point", "r,g,b,a"}},
    {"spot-nan", {"--spot", "1,nan,1,1"}, NULL, NULL, {"--spot", "finite"}},
    {"directional-trailing-junk", {"--directional", "1,1,1,1x"}, NULL, NULL,
     {"--directional", "r,g,b,a"}},
    /* sizes */
    {"size-zero", {"--size", "0x5"}, NULL, NULL, {"--size", "at least 1"}},
    {"size-negative", {"--size", "-16x9"}, NULL, NULL, {"--size", "at least 1"}},
    {"size-no-height", {"--size", "1280"}, NULL, NULL, {"--size", "WIDTHxHEIGHT"}},
    {"size-trailing-junk", {"--size", "16x9px"}, NULL, NULL, {"--size", "WIDTHxHEIGHT"}},
    {"size-fraction", {"--size", "16.5x9"}, NULL, NULL, {"--size", "WIDTHxHEIGHT"}},
    {"size-too-wide", {"--size", "16385x1"}, NULL, NULL, {"--size", "16384"}},
    {"size-too-many-pixels", {"--size", "10000x10000"}, NULL, NULL, {"--size", "67108864"}},
    {"size-huge", {"--size", "100000x100000"}, NULL, NULL, {"--size", "supports"}},
    {"size-beyond-int", {"--size", "99999999999999999999x9"}, NULL, NULL,
     {"--size", "supports"}},
    /* counts */
    {"cubes-zero", {"--cubes", "0"}, NULL, NULL, {"--cubes", "from 1 to 100000"}},
    {"cubes-above", {"--cubes", "100001"}, NULL, NULL, {"--cubes", "from 1 to 100000"}},
    {"cubes-fraction", {"--cubes", "2.5"}, NULL, NULL, {"--cubes", "integer"}},
    {"threads-negative", {"--threads", "-1"}, NULL, NULL, {"--threads", "from 0 to 256"}},
    {"threads-above", {"--threads", "257"}, NULL, NULL, {"--threads", "from 0 to 256"}},
    {"fps-zero", {"--fps", "0"}, NULL, NULL, {"--fps", "[0.001, 1000000]"}},
    {"fps-negative", {"--fps", "-30"}, NULL, NULL, {"--fps", "[0.001, 1000000]"}},
    /* frame 1's time would be 1e300 seconds on */
    {"fps-tiny", {"--frames", "2", "--fps", "1e-300", "-o", "f%d.png"}, NULL, NULL,
     {"--fps", "[0.001, 1000000]"}},
    {"fps-beyond-range", {"--fps", "1e7"}, NULL, NULL, {"--fps", "[0.001, 1000000]"}},
    {"frames-zero", {"--frames", "0"}, NULL, NULL, {"--frames", "from 1"}},
    {"frames-negative", {"--frames", "-2"}, NULL, NULL, {"--frames", "from 1"}},
    {"bench-zero", {"--bench", "0"}, NULL, NULL, {"--bench", "from 1"}},
    {"bench-junk", {"--bench", "two"}, NULL, NULL, {"--bench", "integer"}},
    /* names */
    {"filter-unknown", {"--filter", "cubic"}, NULL, NULL, {"--filter", "trilinear"}},
    /* samples a pixel: 1 or 4, nothing else */
    {"samples-zero", {"--samples", "0"}, NULL, NULL, {"--samples", "expected 1 or 4", "'0'"}},
    {"samples-two", {"--samples", "2"}, NULL, NULL, {"--samples", "expected 1 or 4", "'2'"}},
    {"samples-eight", {"--samples", "8"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-negative", {"--samples", "-4"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-trailing-junk", {"--samples", "4x"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-leading-zero", {"--samples", "04"}, NULL, NULL, {"--samples", "expected 1 or 4"}},
    {"samples-empty", {"--samples="}, NULL, NULL, {"--samples", "missing"}},
    {"only-unknown-term", {"--only", "spot,moon"}, NULL, NULL, {"--only", "directional"}},
    {"only-trailing-comma", {"--only", "spot,"}, NULL, NULL, {"--only", "ambient"}},
    /* the -o pattern */
    {"output-frames-without-conversion", {"--frames", "3", "-o", "out.png"}, NULL, NULL,
     {"-o", "%d"}},
    {"output-two-conversions", {"--frames", "2", "-o", "a%d_%d.png"}, NULL, NULL, {"-o", "%d"}},
    {"output-string-conversion", {"-o", "out_%s.png"}, NULL, NULL, {"-o", "%d"}},
    {"output-minus-flag", {"--frames", "2", "-o", "out_%-4d.png"}, NULL, NULL, {"-o", "%d"}},
    {"output-trailing-percent", {"-o", "out%"}, NULL, NULL, {"-o", "%d"}},
    {"output-default-pattern-long-option", {"--frames", "2", "--output", "x%5x.png"}, NULL, NULL,
     {"-o", "%d"}},
    /* what -o may replace: a regular file that is none of the run's inputs */
    {"output-is-a-texture", {"--size", "8x8", "--textures", "tex", "-o", "tex/a.bmp"}, NULL,
     NULL, {"-o: tex/a.bmp: is a texture this run reads", "expected an output file"}},
    {"output-is-a-texture-by-another-name",
     {"--size", "8x8", "--textures", "tex", "-o", "./tex/../tex/b.bmp"}, NULL, NULL,
     {"-o: ./tex/../tex/b.bmp: is a texture this run reads (tex/b.bmp)"}},
    {"output-is-the-scene-file", {"--scene", "s.luz", "-o", "s.luz"},
     "size = 8x8\ntextures = none\n", NULL, {"-o: s.luz: is the scene file this run reads"}},
    {"output-key-is-the-scene-file", {"--scene", "s.luz"},
     "size = 8x8\ntextures = none\noutput = s.luz\n", NULL,
     {"-o: s.luz: is the scene file this run reads"}},
    {"output-is-a-directory", {"--size", "8x8", "--textures", "none", "-o", "tex"}, NULL, NULL,
     {"-o: tex: is a directory", "expected a file name (such as tex/luz.png)"}},
    {"output-is-a-directory-with-slash", {"--size", "8x8", "--textures", "none", "-o", "tex/"},
     NULL, NULL, {"-o: tex/: is a directory", "(such as tex/luz.png)"}},
    {"output-ends-in-slash", {"--size", "8x8", "--textures", "none", "-o", "nowhere/"}, NULL,
     NULL, {"-o: nowhere/: ends in '/'", "(such as nowhere/luz.png)"}},
    /* what the name says: PNG (issue 31) */
    {"output-jpg", {"--size", "8x8", "--textures", "none", "-o", "out.jpg"}, NULL, NULL,
     {"-o: out.jpg: expected a name ending in .png"}},
    {"output-pattern-without-extension", {"--frames", "2", "-o", "f_%04d"}, NULL, NULL,
     {"-o: f_%04d: expected a name ending in .png"}},
    {"output-key-jpeg", {"--scene", "s.luz"}, "size = 8x8\ntextures = none\noutput = a.jpeg\n",
     NULL, {"-o: a.jpeg: expected a name ending in .png"}},
    /* a folder of the path that is a file: refused before any frame */
    {"output-folder-is-a-file", {"--frames", "2", "-o", "corrupt/bad.png/f_%d.png"}, NULL, NULL,
     {"-o: corrupt/bad.png/f_0.png: corrupt/bad.png is not a folder (it is a file)",
      "expected folders that exist or can be made"}},
    /* a slice of a sequence (--frame-range, --shard) and its files */
    {"frame-range-reversed", {"--frames", "24", "--frame-range", "7:3"}, NULL, NULL,
     {"--frame-range", "0 <= A <= B <= 23", "'7:3'"}},
    {"frame-range-past-the-end", {"--frame-range", "0:24", "--frames", "24"}, NULL, NULL,
     {"--frame-range", "0 <= A <= B <= 23", "'0:24'"}},
    {"frame-range-open-start-past-the-end", {"--frames", "24", "--frame-range", "24:"}, NULL,
     NULL, {"--frame-range", "<= 23", "'24:'"}},
    {"frame-range-without-frames", {"--frame-range", "1:1"}, NULL, NULL,
     {"--frame-range", "<= 0", "--frames 1"}},
    {"frame-range-one-number", {"--frames", "24", "--frame-range", "3"}, NULL, NULL,
     {"--frame-range", "A:B", "'3'"}},
    {"frame-range-negative", {"--frames", "24", "--frame-range", "-1:2"}, NULL, NULL,
     {"--frame-range", "A:B"}},
    {"frame-range-three-numbers", {"--frames", "24", "--frame-range", "1:2:3"}, NULL, NULL,
     {"--frame-range", "A:B"}},
    {"frame-range-words", {"--frames", "24", "--frame-range=a:b"}, NULL, NULL,
     {"--frame-range", "A:B"}},
    {"frame-range-missing-value", {"--frames", "24", "--frame-range"}, NULL, NULL,
     {"--frame-range", "missing", "A:B"}},
    {"shard-index-equals-count", {"--frames", "24", "--shard", "4/4"}, NULL, NULL,
     {"--shard", "0 <= K < M", "'4/4'"}},
    {"shard-no-shards", {"--frames", "24", "--shard", "0/0"}, NULL, NULL,
     {"--shard", "0 <= K < M"}},
    {"shard-negative", {"--frames", "24", "--shard", "-1/4"}, NULL, NULL,
     {"--shard", "K/M"}},
    {"shard-no-slash", {"--frames", "24", "--shard", "2"}, NULL, NULL, {"--shard", "K/M"}},
    {"shard-fraction", {"--frames", "24", "--shard", "1.5/4"}, NULL, NULL, {"--shard", "K/M"}},
    {"shard-too-many", {"--frames", "24", "--shard", "0/1000001"}, NULL, NULL,
     {"--shard", "1000000"}},
    {"skip-existing-with-stdout", {"--frames", "2", "-o", "-", "--skip-existing"}, NULL, NULL,
     {"--skip-existing", "-o -", "standard output"}},
    {"skip-existing-with-value", {"--skip-existing=yes"}, NULL, NULL,
     {"--skip-existing", "no value"}},
    {"scene-frame-range-key", {"--scene", "s.luz"}, "frames = 24\nframe-range = 1:2\n", NULL,
     {"s.luz:2", "frame-range", "not allowed"}},
    {"scene-shard-key", {"--scene", "s.luz"}, "shard = 1/4\n", NULL,
     {"s.luz:1", "shard", "not allowed"}},
    {"scene-skip-existing-key", {"--scene", "s.luz"}, "skip-existing = 1\n", NULL,
     {"s.luz:1", "skip-existing", "not allowed"}},
    {"scene-reference-key", {"--scene", "s.luz"}, "reference = 1\n", NULL,
     {"s.luz:1", "reference", "not allowed"}},
    /* --bug, --quiz and --answer (docs/teaching.md) */
    {"bug-unknown", {"--bug", "diffuse-backwards"}, NULL, NULL,
     {"--bug", "--bug help", "'diffuse-backwards'"}},
    {"bug-unknown-in-scene", {"--scene", "s.luz"}, "bug = no-clipping\n", NULL,
     {"s.luz:1", "bug", "'no-clipping'"}},
    {"bug-with-quiz", {"--quiz", "7", "--bug", "uv-affine"}, NULL, NULL,
     {"--quiz", "no --bug"}},
    {"quiz-not-a-number", {"--quiz", "seven"}, NULL, NULL, {"--quiz", "'seven'"}},
    {"quiz-too-large", {"--quiz", "4294967296"}, NULL, NULL, {"--quiz", "4294967295"}},
    {"answer-without-quiz", {"--answer", "uv-affine"}, NULL, NULL, {"--answer", "--quiz"}},
    {"answer-unknown", {"--quiz", "7", "--answer", "everything"}, NULL, NULL,
     {"--answer", "'everything'"}},
    /* --exposure EV and --tonemap clamp|neutral (SCENE.md, "Output") */
    {"exposure-nan", {"--exposure", "nan"}, NULL, NULL, {"--exposure", "finite", "'nan'"}},
    {"exposure-infinite", {"--exposure", "-inf"}, NULL, NULL, {"--exposure", "finite"}},
    {"exposure-above-ten", {"--exposure", "10.5"}, NULL, NULL,
     {"--exposure", "[-10, 10]", "'10.5'"}},
    {"exposure-below-minus-ten", {"--exposure", "-11"}, NULL, NULL, {"--exposure", "[-10, 10]"}},
    {"exposure-word", {"--exposure", "bright"}, NULL, NULL, {"--exposure", "a number"}},
    {"exposure-missing-value", {"--exposure"}, NULL, NULL, {"--exposure", "missing", "EV"}},
    {"tonemap-unknown", {"--tonemap", "aces"}, NULL, NULL,
     {"--tonemap", "clamp or neutral", "'aces'"}},
    {"tonemap-case", {"--tonemap", "Neutral"}, NULL, NULL, {"--tonemap", "clamp or neutral"}},
    {"scene-exposure", {"--scene", "s.luz"}, "\nexposure = 1e3\n", NULL,
     {"s.luz:2", "exposure", "[-10, 10]"}},
    {"scene-tonemap", {"--scene", "s.luz"}, "tonemap = reinhard\n", NULL,
     {"s.luz:1", "tonemap", "clamp or neutral"}},
    /* --up AXIS, with --model only (SCENE.md, "Up axis") */
    {"up-without-model", {"--up", "z"}, NULL, NULL, {"--up", "--model FILE"}},
    {"up-with-cube-lines", {"--scene", "s.luz", "--up", "x"}, "cube = 0, 0, 0\n", NULL,
     {"--up", "--model FILE"}},
    {"up-unknown", {"--up", "+z", "--model", "m.obj"}, NULL, NULL,
     {"--up", "y, z, x, -y, -z or -x", "'+z'"}},
    {"up-missing-value", {"--up"}, NULL, NULL, {"--up", "missing"}},
    {"scene-up-key", {"--scene", "s.luz"}, "up = z\n", NULL, {"s.luz:1", "up", "not allowed"}},
    {"scene-model-up-unknown", {"--scene", "s.luz"}, "\nmodel = m.obj up w\n", NULL,
     {"s.luz:2", "up AXIS", "y, z, x, -y, -z, -x"}},
    {"scene-model-up-twice", {"--scene", "s.luz"}, "model = m.obj up z up x\n", NULL,
     {"s.luz:1", "up AXIS", "once"}},
    /* --probe X,Y */
    {"probe-malformed", {"--probe", "abc"}, NULL, NULL, {"--probe", "X,Y", "'abc'"}},
    {"probe-one-number", {"--probe", "5"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-three-numbers", {"--probe", "1,2,3"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-negative", {"--probe", "-1,5"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-fraction", {"--probe", "1.5,2"}, NULL, NULL, {"--probe", "X,Y"}},
    {"probe-missing-value", {"--probe"}, NULL, NULL, {"--probe", "missing"}},
    {"probe-right-of-the-image", {"--size", "16x9", "--probe", "16,0"}, NULL, NULL,
     {"--probe", "16x9", "X from 0 to 15", "'16,0'"}},
    {"probe-below-the-image", {"--probe", "0,9", "--size", "16x9"}, NULL, NULL,
     {"--probe", "Y from 0 to 8", "'0,9'"}},
    {"probe-with-bench", {"--probe", "1,1", "--bench", "3"}, NULL, NULL,
     {"--probe", "one frame", "--bench"}},
    {"probe-with-frames", {"--probe", "1,1", "--frames", "2", "-o", "f_%d.png"}, NULL, NULL,
     {"--probe", "one frame", "--frames 2"}},
    {"probe-with-shard", {"--probe", "1,1", "--shard", "0/2"}, NULL, NULL,
     {"--probe", "--shard"}},
    {"probe-with-stdout", {"--probe", "1,1", "-o", "-"}, NULL, NULL, {"--probe", "-o -"}},
    {"scene-probe-key", {"--scene", "s.luz"}, "probe = 1,1\n", NULL,
     {"s.luz:1", "probe", "not allowed"}},
    /* textures */
    {"textures-missing-directory", {"--size", "8x8", "--textures", "nowhere"}, NULL, NULL,
     {"--textures", "nowhere"}},
    {"textures-no-images", {"--size", "8x8", "--textures", "empty"}, NULL, NULL,
     {"--textures", "empty", "image"}},
    {"textures-corrupt-image", {"--size", "8x8", "--textures=corrupt"}, NULL, NULL,
     {"--textures", "bad.png"}},
    {"textures-environment-no-images", {"--size", "8x8"}, NULL, "empty",
     {"LUZ_TEXTURES", "empty"}},
    {"texture-name-unknown", {"--size", "8x8", "--textures", "tex", "--scene", "s.luz"},
     "cube = 0, 0, 0 texture nope.png\n", NULL, {"s.luz:1", "nope.png", "a.bmp"}},
    {"texture-name-with-textures-off", {"--textures", "none", "--scene", "s.luz"},
     "# one cube\ncube = 0, 0, 0 texture a.bmp\n", NULL, {"s.luz:2", "a.bmp"}},
    /* scene files */
    {"scene-missing", {"--scene", "nope.luz"}, NULL, NULL, {"nope.luz", "cannot open"}},
    {"scene-is-a-directory", {"--scene", "tex"}, NULL, NULL, {"tex", "not a regular file"}},
    /* a device would feed the reader forever; a huge line must not grow it */
    {"scene-is-a-device", {"--scene", "/dev/zero"}, NULL, NULL,
     {"/dev/zero", "not a regular file"}},
    /* 16384 characters, and 20000 */
    {"scene-line-too-long", {"--scene", "s.luz"}, "time = 1\n" TEN(TEN(TEN("####################"))),
     NULL, {"s.luz:2", "longer than 16384"}},
    {"scene-texture-name-too-long", {"--scene", "s.luz"},
     "cube = 0, 0, 0 texture " TEN(TEN("abc")) TEN("abcdefgh") "aaaaaa.png\n", NULL,
     {"s.luz:1", "at most 255 bytes"}},
    {"scene-syntax", {"--scene", "s.luz"}, "size = 16x9\nthis is not an option\n", NULL,
     {"s.luz:2", "name = value"}},
    {"scene-empty-name", {"--scene", "s.luz"}, "= 5\n", NULL, {"s.luz:1", "name = value"}},
    {"scene-unknown-key", {"--scene", "s.luz"}, "colour = 1, 0, 0\n", NULL,
     {"s.luz:1", "unknown key", "colour"}},
    {"scene-short-output-key", {"--scene", "s.luz"}, "o = x.png\n", NULL,
     {"s.luz:1", "unknown key"}},
    {"scene-help-key", {"--scene", "s.luz"}, "\n\nhelp = 1\n", NULL, {"s.luz:3", "not allowed"}},
    {"scene-version-key", {"--scene", "s.luz"}, "version = 1\n", NULL,
     {"s.luz:1", "not allowed"}},
    {"scene-scene-key", {"--scene", "s.luz"}, "scene = other.luz\n", NULL,
     {"s.luz:1", "not allowed"}},
    {"scene-bad-value", {"--scene", "s.luz"}, "# a comment\nfov = 200  # too wide\n", NULL,
     {"s.luz:2", "fov", "[1, 179]"}},
    {"scene-malformed-number", {"--scene", "s.luz"}, "seed = 12abc\n", NULL,
     {"s.luz:1", "seed", "integer"}},
    {"scene-missing-value", {"--scene", "s.luz"}, "fov =\n", NULL, {"s.luz:1", "missing"}},
    {"scene-bad-samples", {"--scene", "s.luz"}, "\nsamples = 16\n", NULL,
     {"s.luz:2", "samples", "expected 1 or 4"}},
    {"scene-duplicate-key", {"--scene", "s.luz"}, "seed = 1\nseed = 2\n", NULL,
     {"s.luz:2", "duplicate", "line 1"}},
    {"scene-spot-cone", {"--scene", "s.luz"}, "spot-inner = 30\n", NULL,
     {"--spot-inner", "--spot-outer"}},
    {"scene-cube-duplicate-colour", {"--scene", "s.luz"},
     "cube = 0, 0, 0 colour 1, 0, 0 colour 0, 1, 0\n", NULL, {"s.luz:1", "duplicate colour"}},
    {"scene-cube-duplicate-texture", {"--textures", "tex", "--scene", "s.luz"},
     "cube = 0,0,0 texture a.bmp texture b.bmp\n", NULL, {"s.luz:1", "duplicate texture"}},
    {"scene-cube-unknown-field", {"--scene", "s.luz"}, "cube = 0, 0, 0 shiny\n", NULL,
     {"s.luz:1", "shiny", "colour"}},
    {"scene-cube-two-numbers", {"--scene", "s.luz"}, "\ncube = 0, 0\n", NULL,
     {"s.luz:2", "x,y,z"}},
    {"scene-cube-colour-range", {"--scene", "s.luz"}, "cube = 0,0,0 colour 2, 0, 0\n", NULL,
     {"s.luz:1", "[0, 1]"}},
    {"scene-cube-infinite", {"--scene", "s.luz"}, "cube = inf, 0, 0\n", NULL,
     {"s.luz:1", "finite"}},
    {"scene-cube-beyond-range", {"--scene", "s.luz"}, "\ncube = 0, 0, -3e38\n", NULL,
     {"s.luz:2", "cube", "each in [-10000, 10000]"}},
    {"scene-cube-just-beyond-range", {"--scene", "s.luz"}, "cube = 10000.001, 0, 0\n", NULL,
     {"s.luz:1", "cube", "each in [-10000, 10000]"}},
    {"scene-cube-texture-without-name", {"--scene", "s.luz"}, "cube = 0,0,0 texture\n", NULL,
     {"s.luz:1", "texture NAME"}},
    {"scene-cubes-and-cube-lines", {"--scene", "s.luz"}, "cubes = 20\ncube = 0, 0, 0\n", NULL,
     {"s.luz:2", "cubes"}},
    {"scene-cube-lines-then-cubes", {"--scene", "s.luz"}, "cube = 0, 0, 0\ncubes = 20\n", NULL,
     {"s.luz:2", "cubes"}},
    {"scene-quote-unterminated", {"--scene", "s.luz"}, "seed = 1\ntextures = \"tex # x\n",
     NULL, {"s.luz:2", "textures", "closing \""}},
    {"scene-quote-ends-in-backslash", {"--scene", "s.luz"}, "textures = \"tex\\\n", NULL,
     {"s.luz:1", "textures", "closing \""}},
    {"scene-quote-unknown-escape", {"--scene", "s.luz"}, "textures = \"a\\qb\"\n", NULL,
     {"s.luz:1", "textures", "escape '\\q'", "\\\""}},
    {"scene-quote-junk-after", {"--scene", "s.luz"}, "textures = \"a\" b\n", NULL,
     {"s.luz:1", "textures", "after the closing quote", "'b'"}},
    {"scene-cube-quote-unterminated", {"--scene", "s.luz"},
     "\ncube = 0, 0, 0 texture \"old wood.png colour 1, 0, 0\n", NULL,
     {"s.luz:2", "texture", "closing \""}},
    {"scene-cube-quote-junk-after", {"--scene", "s.luz"},
     "cube = 0, 0, 0 texture \"a\"colour 1, 0, 0\n", NULL,
     {"s.luz:1", "texture", "after the closing quote", "colour"}},
    {"scene-error-before-command-line", {"--size", "8x8", "--scene", "s.luz"}, "time = soon\n",
     NULL, {"s.luz:1", "time", "number"}},
};

#define ERROR_CASE_COUNT (sizeof error_cases / sizeof error_cases[0])

static void test_refused(void **state)
{
    const error_case *test = *state;
    sandbox box;
    sandbox_create(&box);
    if (test->scene != NULL)
        write_text(box.work, "s.luz", test->scene);
    char before[8192] = "", after[8192] = "";
    list_tree(box.work, "", before, sizeof before);

    run_result result = run_in(&box, test->arguments, test->textures_environment);

    if (result.status != 2)
        fail_msg("exit status %d, expected 2; stderr: %s", result.status, result.err);
    /* exactly one line, with the program's name in front */
    size_t length = strlen(result.err);
    if (length < 2 || result.err[length - 1] != '\n' ||
        strchr(result.err, '\n') != result.err + length - 1)
        fail_msg("stderr is not exactly one line: '%s'", result.err);
    if (strncmp(result.err, "luz-render: ", 12) != 0)
        fail_msg("stderr does not start with 'luz-render: ': %s", result.err);
    for (int i = 0; i < 4 && test->needles[i] != NULL; i++) {
        if (strstr(result.err, test->needles[i]) == NULL)
            fail_msg("stderr lacks '%s': %s", test->needles[i], result.err);
    }
    assert_string_equal(result.out, "");
    /* no PNG, no temporary file, nothing */
    list_tree(box.work, "", after, sizeof after);
    assert_string_equal(before, after);

    run_result_free(&result);
    sandbox_destroy(&box);
}

/* A NUL byte anywhere in a scene file is refused at its line. fgets took
 * a NUL for the end of its string, so a NUL in a last line without a
 * newline, or a file of one NUL byte, passed unseen. */
static void test_scene_nul_bytes(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        size_t length;
        const char *where;
    } cases[] = {
        {"seed = 1\nfov = 4\0", 17, "s.luz:2: "},            /* the last line, no newline */
        {"\0", 1, "s.luz:1: "},                               /* one NUL byte */
        {"seed = 1\0 2\nfov = 30\n", 21, "s.luz:1: "},       /* within a line */
        {"\ntextures = \"a\0b\"\n", 18, "s.luz:2: "},       /* within quotes */
        {"# c\n\n# x\0", 9, "s.luz:3: "},                    /* after a comment */
        {"seed = 1\n\0\n", 11, "s.luz:2: "},                 /* a line of one NUL */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        sandbox box;
        sandbox_create(&box);
        char path[600], expected[100];
        sandbox_path(&box, "s.luz", path, sizeof path);
        write_file(path, cases[c].text, cases[c].length);
        run_result result = run_in(&box, ARGS("--scene", "s.luz", "--textures", "none"), NULL);
        snprintf(expected, sizeof expected, "luz-render: %sexpected text, found a NUL byte\n",
                 cases[c].where);
        if (result.status != 2 || strcmp(result.err, expected) != 0)
            fail_msg("case %zu: exit %d, stderr '%s'; expected 2 and '%s'", c, result.status,
                     result.err, expected);
        run_result_free(&result);
        sandbox_destroy(&box);
    }
}

/* 100000x100000 would be 130 GB: the refusal must come from the check, at
 * once, not from an allocation that fails (or, worse, succeeds). */
static void test_huge_size_refused_at_once(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--size", "100000x100000", "--textures", "none"), NULL);
    assert_int_equal(result.status, 2);
    if (result.seconds > 2.0)
        fail_msg("took %.2f s to refuse the size", result.seconds);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* Makes `levels` nested directories under box->work, each named by 250
 * copies of `letter`, and writes their relative path into out. */
static void make_deep_directory(const sandbox *box, char letter, int levels, char *out,
                                size_t size)
{
    char name[251];
    memset(name, letter, 250);
    name[250] = '\0';
    out[0] = '\0';
    for (int level = 0; level < levels; level++) {
        size_t used = strlen(out);
        snprintf(out + used, size - used, "%s%s", level ? "/" : "", name);
        char absolute[4096];
        snprintf(absolute, sizeof absolute, "%s/%s", box->work, out);
        assert_int_equal(mkdir(absolute, 0755), 0);
    }
}

/* Exit status 2 and one line on stderr that holds every needle whole. */
static void assert_refused_naming(const run_result *result, const char *const *needles)
{
    if (result->status != 2)
        fail_msg("exit status %d, expected 2; stderr: %.300s", result->status, result->err);
    size_t length = strlen(result->err);
    assert_true(length > 0 && result->err[length - 1] == '\n');
    assert_ptr_equal(strchr(result->err, '\n'), result->err + length - 1);
    for (int i = 0; needles[i] != NULL; i++) {
        if (strstr(result->err, needles[i]) == NULL)
            fail_msg("stderr (%zu bytes) lacks the whole of the %zu-byte '%.60s...'", length,
                     strlen(needles[i]), needles[i]);
    }
}

/* An error message names its paths whole, however long: a 1506-byte
 * scene path, a 3000-byte model path beside it, a 1506-byte output
 * directory. (luz_error once held 512 bytes and cut them off.) */
static void test_long_paths_come_through_whole(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char scene_directory[2048], model_directory[2048], scene[2100], model_line[2100];
    char model[4096], output[2100];
    make_deep_directory(&box, 's', 6, scene_directory, sizeof scene_directory);
    assert_true(strlen(scene_directory) > 1500);

    /* a bad value in a scene file deep down: FILE:LINE with the whole FILE */
    snprintf(scene, sizeof scene, "%s/s.luz", scene_directory);
    char scene_absolute[4096];
    snprintf(scene_absolute, sizeof scene_absolute, "%s/%s", box.work, scene);
    write_file(scene_absolute, "seed = 1\nfov = 0\n", 17);
    char where[2200];
    snprintf(where, sizeof where, "%s:2: fov", scene);
    run_result result = run_in(&box, ARGS("--scene", scene, "--textures", "none"), NULL);
    assert_refused_naming(&result, ARGS(where, "[1, 179]"));
    run_result_free(&result);

    /* a model that is not there, 1500 more bytes below the scene file's
     * directory: the scene file and the model's absolute path, both whole */
    make_deep_directory(&box, 'm', 6, model_directory, sizeof model_directory);
    snprintf(model_line, sizeof model_line, "model = %s/nothere.obj\n", model_directory);
    write_file(scene_absolute, model_line, strlen(model_line));
    snprintf(where, sizeof where, "%s:1: model", scene);
    snprintf(model, sizeof model, "%s/%s/%s/nothere.obj", box.work, scene_directory,
             model_directory);
    assert_true(strlen(model) > 3000);
    result = run_in(&box, ARGS("--scene", scene, "--textures", "none"), NULL);
    assert_refused_naming(&result, ARGS(where, model));
    run_result_free(&result);

    /* an output folder that is a file (the scene file): exit 2, the path
     * whole */
    snprintf(output, sizeof output, "%s/s.luz/out.png", scene_directory);
    result = run_in(&box, ARGS("--size", "8x8", "--textures", "none", "-o", output), NULL);
    assert_int_equal(result.status, 2);
    if (strstr(result.err, output) == NULL)
        fail_msg("stderr lacks the whole output path: %.300s", result.err);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* luz_error holds three PATH_MAX paths and some words whole; what does not
 * fit ends in "...", so a cut is never silent. */
static void test_error_message_room(void **state)
{
    (void)state;
    char *path = malloc(4096);
    assert_non_null(path);
    memset(path, 'p', 4095);
    path[4095] = '\0';
    luz_error error;
    assert_int_equal(luz_error_set(&error, "%s:12: model: %s: texture '%s': cannot open it",
                                   path, path, path), -1);
    /* 3 x 4095 + the words between, counted by hand: ":12: model: " is 12,
     * ": texture '" 11, "': cannot open it" 17 */
    assert_int_equal(strlen(error.message), 3 * 4095 + 12 + 11 + 17);
    assert_string_equal(error.message + strlen(error.message) - 17, "': cannot open it");

    luz_error_set(&error, "%s%s%s%s%s", path, path, path, path, path);
    assert_int_equal(strlen(error.message), LUZ_ERROR_MESSAGE_SIZE - 1);
    assert_string_equal(error.message + LUZ_ERROR_MESSAGE_SIZE - 4, "...");
    free(path);
}

int main(void)
{
    static const struct CMUnitTest fixed_tests[] = {
        cmocka_unit_test(test_huge_size_refused_at_once),
        cmocka_unit_test(test_scene_nul_bytes),
        cmocka_unit_test(test_long_paths_come_through_whole),
        cmocka_unit_test(test_error_message_room),
    };
    enum { FIXED = sizeof fixed_tests / sizeof fixed_tests[0] };
    /* One named test per refused input, so that a failure says which. */
    static struct CMUnitTest tests[FIXED + ERROR_CASE_COUNT];
    for (size_t i = 0; i < FIXED; i++)
        tests[i] = fixed_tests[i];
    for (size_t i = 0; i < ERROR_CASE_COUNT; i++) {
        tests[FIXED + i] = (struct CMUnitTest){
            .name = error_cases[i].name,
            .test_func = test_refused,
            .initial_state = (void *)&error_cases[i],
        };
    }
    return _cmocka_run_group_tests("cli-refused", tests, FIXED + ERROR_CASE_COUNT, NULL, NULL);
}
