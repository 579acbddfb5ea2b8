/*
 * app/quiz.h: --bug help, --quiz SEED and --answer NAME (docs/teaching.md,
 * "Find the bug").
 *
 * A quiz draws the scene with one of luz/bug.h's bugs, chosen from the
 * seed and named nowhere (the probe says "bug=hidden (quiz)", a saved view
 * keeps `quiz = SEED`); the student finds it with the views and the probe
 * and checks with --answer.
 *
 * The choice: SCENE.md's generator, xorshift32 (x ^= x << 13; x ^= x >> 17;
 * x ^= x << 5), four steps from the seed (0 means 0x9E3779B9, as for the
 * colours), and bug number floor((x >> 8) / 2^24 * n) of the quiz's n
 * bugs in luz_quiz_bugs' order: every bug but normal-not-normalised and
 * fill-rule-bottom-right, which change nothing a student can see in the
 * lab's cubes (a flat face's interpolated normal is already unit length;
 * hardly a pixel centre lies exactly on an edge).
 */
#ifndef LUZ_QUIZ_H
#define LUZ_QUIZ_H

#include <stdint.h>
#include <stdio.h>

#include "luz/bug.h"

/* The bugs a quiz chooses from, in order; returns how many. */
int luz_quiz_bugs(const luz_bug **bugs);

/* The bug of quiz `seed`. */
luz_bug luz_quiz_bug(uint32_t seed);

/* --bug help: every bug, its name and what it changes, one a line, and
 * whether a quiz may choose it. */
void luz_quiz_print_bugs(FILE *out);

/* --answer NAME --quiz SEED: one line saying right or wrong and what the
 * bug was. Returns 0 when answer is the quiz's bug, 1 when not. */
int luz_quiz_answer(FILE *out, uint32_t seed, luz_bug answer);

#endif
