/*
 * term_fit.c: the least-squares weights of the six light terms.
 *
 * In:  the normal equations' sums over every observation (a pixel's
 *      channel): G = sum a a^T (6 x 6, symmetric, positive semi-definite)
 *      and h = sum a y, a the six single-term colours, y the colour to
 *      explain; and the smallest pivot that counts as measurable.
 * Out: a luz_term_fit: which terms are measurable, their weights w
 *      (G_mm w_m = h_m - G_mu 1 over the measurable set m, the others u
 *      held at 1), and (G_mm^-1)_kk for each, from which the caller gets
 *      a weight's uncertainty.
 *
 * Why a pivoted Cholesky: G is 6 x 6 and sums at most millions of
 * products, so forming it costs nothing and loses little in double
 * precision, but it may be singular: a light that lights nothing in view
 * (the spot pointing at the background) gives a zero column, and two
 * terms may look alike in a frame (ambient and a sun behind the camera
 * both light every face evenly). Choosing the largest remaining diagonal
 * entry as the next pivot (Higham, "Accuracy and Stability of Numerical
 * Algorithms", 2nd ed., section 10.3) factors the well-determined part
 * first; the remaining diagonal entry of term k is then the energy of k
 * that the terms chosen before it cannot explain, and once the largest
 * falls below min_pivot nothing measurable is left. Those terms are
 * reported "not measurable" instead of a wild number from a near-zero
 * pivot, and held at weight 1 (as luz has them) while the others are
 * weighed: a term the frame cannot tell from another one then leaves the
 * other's weight alone rather than lending it its light.
 */
#include "app/term_fit.h"

#include <math.h>
#include <string.h>

enum { N = LUZ_TERM_COUNT };

void luz_term_sums_add(luz_term_sums *sums, const double basis[N], double y)
{
    for (int i = 0; i < N; i++) {
        if (basis[i] == 0.0) continue;   /* most terms are 0 on most pixels */
        for (int j = 0; j < N; j++) sums->gram[i][j] += basis[i] * basis[j];
        sums->projection[i] += basis[i] * y;
    }
    sums->observations++;
}

/* Solves L L^T x = b for the leading `rank` rows of the factor. */
static void solve_factored(const double factor[N][N], int rank, const double *b, double *x)
{
    double z[N];
    for (int i = 0; i < rank; i++) {   /* L z = b */
        double s = b[i];
        for (int j = 0; j < i; j++) s -= factor[i][j] * z[j];
        z[i] = s / factor[i][i];
    }
    for (int i = rank - 1; i >= 0; i--) {   /* L^T x = z */
        double s = z[i];
        for (int j = i + 1; j < rank; j++) s -= factor[j][i] * x[j];
        x[i] = s / factor[i][i];
    }
}

void luz_term_fit_solve(const luz_term_sums *sums, double min_pivot, luz_term_fit *fit)
{
    memset(fit, 0, sizeof *fit);
    double a[N][N];
    memcpy(a, sums->gram, sizeof a);
    int order[N];   /* order[i]: the term in row i of the permuted system */
    for (int i = 0; i < N; i++) order[i] = i;

    /* Outer-product Cholesky with diagonal pivoting: at step j, a[j..][j..]
     * holds the Schur complement, whose diagonal is what each remaining
     * term adds to the terms already chosen. */
    int rank = 0;
    for (int j = 0; j < N; j++) {
        int pivot = j;
        for (int i = j + 1; i < N; i++)
            if (a[i][i] > a[pivot][pivot]) pivot = i;
        if (!(a[pivot][pivot] > min_pivot) || !(a[pivot][pivot] > 0.0)) break;
        if (pivot != j) {   /* swap row and column j with pivot */
            for (int k = 0; k < N; k++) {
                double t = a[j][k]; a[j][k] = a[pivot][k]; a[pivot][k] = t;
            }
            for (int k = 0; k < N; k++) {
                double t = a[k][j]; a[k][j] = a[k][pivot]; a[k][pivot] = t;
            }
            int t = order[j]; order[j] = order[pivot]; order[pivot] = t;
        }
        fit->unexplained[order[j]] = a[j][j];
        const double diagonal = sqrt(a[j][j]);
        a[j][j] = diagonal;
        for (int i = j + 1; i < N; i++) a[i][j] /= diagonal;
        for (int i = j + 1; i < N; i++)
            for (int k = j + 1; k <= i; k++) {
                a[i][k] -= a[i][j] * a[k][j];
                a[k][i] = a[i][k];
            }
        rank = j + 1;
    }

    /* The terms left out are held at weight 1, as luz has them: what they
     * add is taken from y first, h_m - sum_u G_mu 1, so that a term that
     * looks like one left out is not given its light too. */
    double h[N] = {0}, w[N] = {0};
    for (int i = 0; i < rank; i++) {
        h[i] = sums->projection[order[i]];
        for (int u = rank; u < N; u++) h[i] -= sums->gram[order[i]][order[u]];
    }
    for (int u = rank; u < N; u++) fit->weight[order[u]] = 1.0;
    solve_factored(a, rank, h, w);
    for (int i = 0; i < rank; i++) {
        fit->measurable[order[i]] = true;
        fit->weight[order[i]] = w[i];
        /* (G^-1)_kk: the k-th entry of G^-1 e_k */
        double e[N] = {0}, column[N];
        e[i] = 1.0;
        solve_factored(a, rank, e, column);
        fit->inverse_diagonal[order[i]] = column[i];
    }
    fit->measurable_count = rank;
}
