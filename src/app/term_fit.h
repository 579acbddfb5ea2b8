/*
 * app/term_fit.h: a colour explained as a weighted sum of the six light
 * terms, by least squares (term_fit.c); what --diagnose weighs a student's
 * frame with (diagnose.h).
 *
 * Each observation is one channel of one pixel: y, the student's colour
 * there (linear, before the output), and a[k], what luz's term k alone
 * gives there (SCENE.md: colour = (ambient + ... + directional) * C * T is
 * linear in each term). The fit finds the weights w minimising
 * sum (y - sum_k w_k a_k)^2: w = 1 for a term the student has right, 0 for
 * one missing, another value for one scaled.
 */
#ifndef LUZ_TERM_FIT_H
#define LUZ_TERM_FIT_H

#include <stdbool.h>

#include "luz/frame.h"

/* The sums the normal equations are made of, gathered observation by
 * observation: G = sum a a^T, h = sum a y. Zero-initialise, then add. */
typedef struct luz_term_sums {
    double gram[LUZ_TERM_COUNT][LUZ_TERM_COUNT];
    double projection[LUZ_TERM_COUNT];
    long observations;
} luz_term_sums;

void luz_term_sums_add(luz_term_sums *sums, const double basis[LUZ_TERM_COUNT], double y);

/* The answer. */
typedef struct luz_term_fit {
    bool measurable[LUZ_TERM_COUNT];   /* false: too little of the term is
                                          in view, or what is there another
                                          term (or several) explains as well;
                                          its weight is left out of the fit */
    double weight[LUZ_TERM_COUNT];     /* the least-squares weight; 1 when
                                          not measurable: held there, as luz
                                          has it, while the others are
                                          weighed */
    double unexplained[LUZ_TERM_COUNT];   /* the energy of term k that the
                                             terms chosen before it do not
                                             explain (the pivot of the
                                             Cholesky factor; 0 if never
                                             chosen) */
    double inverse_diagonal[LUZ_TERM_COUNT];   /* (G^-1)_kk over the measurable
                                                  terms: the weight's variance
                                                  is sigma^2 times it */
    int measurable_count;
} luz_term_fit;

/* Solves G w = h by a Cholesky factorisation with diagonal pivoting
 * (G = P L L^T P^T, the largest remaining pivot first; Golub and Van Loan,
 * "Matrix Computations", 4th ed., algorithm 4.2.1 with pivoting as in
 * Higham, "Accuracy and Stability of Numerical Algorithms", 10.3): a term
 * whose remaining pivot is below min_pivot (a sum of squared colours, the
 * caller's measure of "enough light to weigh") is not measurable, and the
 * terms after it neither. The factor of a positive semi-definite G is
 * stable with this pivoting; the terms left out make the rest well
 * conditioned, and are held at weight 1 (their light taken from h first). */
void luz_term_fit_solve(const luz_term_sums *sums, double min_pivot, luz_term_fit *fit);

#endif
