/*
 * app/diagnose.h: luz-render --diagnose FRAME.png, a verdict on a
 * student's own frame of a SCENE.md setting (diagnose.c; the fit itself is
 * term_fit.h's).
 *
 * The student renders the lab in their own WebGL practical at a setting
 * (time, seed, camera, lights) and saves the canvas; luz renders the six
 * single-term images of the same setting, weighs them to explain the
 * student's colours by least squares, and says which term is missing,
 * scaled or of the wrong shape, and whether the silhouettes agree
 * (docs/teaching.md, "Check your own frame").
 */
#ifndef LUZ_DIAGNOSE_H
#define LUZ_DIAGNOSE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "luz/error.h"
#include "luz/frame.h"
#include "luz/renderer.h"
#include "app/options.h"
#include "io/textures.h"
#include "lab/scene.h"

/* The student's frame: RGBA8, row 0 on top. */
typedef struct luz_student_frame {
    int width, height;
    uint8_t *rgba;
} luz_student_frame;

/* Reads a PNG file. Returns 0, or LUZ_BAD_INPUT (not a PNG, unreadable:
 * one line naming the file and what was expected) or LUZ_MACHINE_FAILED. */
int luz_student_frame_read(const char *path, luz_student_frame *frame, luz_error *error);
void luz_student_frame_free(luz_student_frame *frame);

/* The colour (before the output: SCENE.md's equations' colour) that the
 * output wrote as these bytes, channel by channel, and whether each is
 * known: clamp at EV e reads byte / 255 / 2^e for bytes 1 to 254 (0 and
 * 255 may hide any colour below or above); neutral inverts the tone map
 * where it only shifts the colour (the mapped peak below 0.76, no channel
 * 0), and knows nothing of a pixel above. Returns how many are known. */
int luz_diagnose_unmap(const uint8_t bytes[3], luz_output output, double colour[3],
                       bool known[3]);

/* What the diagnosis is given. */
typedef struct luz_diagnose_setup {
    const luz_options *options;        /* the setting: scene, size, threads */
    const luz_texture_set *textures;
    const luz_lab *lab;
    luz_renderer *renderer;
    const char *frame_name;            /* the student's file, for messages */
    const char *residual_path;         /* the picture written */
} luz_diagnose_setup;

/* The verdict's exit statuses. */
enum { LUZ_DIAGNOSIS_RIGHT = 0, LUZ_DIAGNOSIS_WRONG = 1 };

/* Renders the setting's single-term images, fits the frame, writes the
 * verdict lines on out and the residual picture. Returns
 * LUZ_DIAGNOSIS_RIGHT or LUZ_DIAGNOSIS_WRONG, or -1 with a message (memory,
 * rendering or writing failed). The frame's size must be the options'. */
int luz_diagnose(const luz_diagnose_setup *setup, const luz_student_frame *frame, FILE *out,
                 luz_error *error);

#endif
