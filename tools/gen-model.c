/*
 * gen-model: writes a procedural triangle mesh as a Wavefront OBJ file.
 *
 *   gen-model --shape sphere|bumpy-sphere|torus-knot|grid|cube
 *             [--triangles N] [--no-normals] [--no-uvs] [--seed S] -o FILE.obj
 *
 * What it is for
 *   luz loads the user's own models (OBJ and friends, through assimp).  Its
 *   tests and benchmarks need meshes of any size, from a dozen triangles to
 *   twenty million, without committing large files: this program computes
 *   them.  Every shape is a closed-form surface, so a test can check what it
 *   reads against the geometry (normals, volume, watertightness) rather than
 *   against a stored file.
 *
 * The shapes (angles in radians; every shape is centred on the origin)
 *   sphere        the UV sphere of radius 1:
 *                   P(theta, phi) = (sin theta cos phi, sin theta sin phi, cos theta)
 *                 theta in [0, pi] from the north pole (+z), phi in [0, 2 pi).
 *                 Normal: P itself.
 *   bumpy-sphere  the same parametrisation with a radius that varies:
 *                   P = r(theta, phi) * (sin theta cos phi, sin theta sin phi, cos theta)
 *                   r = 1 + 0.15 sin^4(theta) sin(7 theta) sin(5 (phi - phi0))
 *                 The sin^4(theta) factor is there on purpose: sin(7 theta) sin(5 phi)
 *                 alone has r - 1 ~ 1.05 theta sin(5 phi) near a pole, a cone
 *                 whose normal depends on the direction one comes from.  With
 *                 it, (r - 1) = 0.15 Im((x + iy)^5) U_6(z) on the unit sphere
 *                 (x + iy = sin theta e^(i phi), sin 7 theta = sin theta U_6(cos theta)),
 *                 a polynomial in x, y, z: smooth everywhere, poles included.
 *                 Normal, from the cross product of the partial derivatives
 *                 P_theta x P_phi divided by r sin theta > 0:
 *                   N ~ r e_r - r_theta e_theta - (r_phi / sin theta) e_phi
 *                 with e_r, e_theta, e_phi the unit spherical basis;
 *                 r_phi / sin theta = 0.75 sin^3 theta sin 7 theta cos 5(phi - phi0)
 *                 has no division, and at the poles N = e_r.  N . e_r = r >= 0.85.
 *                 phi0 = 0 unless --seed is given (see below).
 *   torus-knot    a tube of radius rho = 0.3 around the (p, q) = (2, 3) torus
 *                 knot (a trefoil) that lies on the torus of radii R = 1,
 *                 a = 0.45:
 *                   C(t) = ((R + a cos qt) cos pt, (R + a cos qt) sin pt, a sin qt)
 *                   P(t, s) = C(t) + rho (cos s n(t) + sin s b(t))
 *                 t, s in [0, 2 pi), n(t) = (cos qt cos pt, cos qt sin pt, sin qt)
 *                 the torus's outward normal at C(t) (perpendicular to C'(t),
 *                 since C lies on the torus), b = C'/|C'| x n.  Normal:
 *                 cos s n + sin s b, exactly: P_s is perpendicular to it, and
 *                 so is P_t = C' + rho d/dt(unit vector).  The frame (n, b)
 *                 is periodic and never degenerate, unlike Frenet's.  The
 *                 centre line is 15.34 long and its curvature at most 1.36,
 *                 strands come no closer than 0.89 (> 2 rho), and
 *                 rho * 1.36 < 1, so the tube never meets itself.  It fits
 *                 in |x|, |y| <= 1.75, |z| <= 0.75.
 *   grid          the square [-1, 1] x [-1, 1] in the plane z = 0, facing +z,
 *                 cut into k x k squares of two triangles each.  Normal +z.
 *                 With 1,000,000 triangles and the square filling a 1280x720
 *                 screen, each triangle covers about one pixel or less.
 *   cube          the cube [-1, 1]^3: 8 corners, 6 face normals, 12 triangles.
 *
 * The triangle counts, as a function of the resolution k
 *   sphere, bumpy-sphere  k stacks (theta steps of pi / k) and 2k slices
 *                         (phi steps of pi / k, so quads are square at the
 *                         equator); the two poles are single vertices with
 *                         fans of 2k triangles, no degenerate triangle:
 *                           triangles 4k(k - 1), positions 2k(k - 1) + 2,
 *                           texture coordinates (2k + 1)(k - 1) + 4k, k >= 2
 *                         (k = 2 is an octahedron).
 *   torus-knot            8k steps along the knot, k around the tube (the
 *                         knot is about 8 times longer than the tube's
 *                         circumference, so quads are about square):
 *                           triangles 16k^2, positions 8k^2,
 *                           texture coordinates (8k + 1)(k + 1), k >= 3
 *   grid                  triangles 2k^2, positions (k + 1)^2, k >= 1
 *   cube                  always 12 triangles, 8 positions.
 *   --triangles N picks the largest k whose count is at most N, or the
 *   shape's smallest k when even that is more than N; the exact count is
 *   printed on stderr.  N is at most 20,000,000 (default 100,000).
 *   Normals, where written, are one per position (one in all for the grid,
 *   one per face for the cube).  Texture coordinates are separate from
 *   positions where a seam needs it: positions are shared across the
 *   sphere's phi = 0 seam and the knot's two seams (so the surfaces are
 *   watertight), texture coordinates are not (u runs 0 to 1 and must jump).
 *
 * Face winding
 *   Counter-clockwise seen from outside (from +z for the grid): for each
 *   triangle (A, B, C), (B - A) x (C - A) points out, as luz's back-face
 *   culling expects.  For the spheres P_theta x P_phi points out, so a quad
 *   (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1) in (theta, phi) steps is
 *   counter-clockwise; for the knot P_s x P_t points out (P_t ~ |C'| tangent,
 *   tangent x (d/ds of the offset) = -offset), so the quad runs s first.
 *   Every edge of a closed shape is shared by exactly two triangles, in
 *   opposite directions.
 *
 * --seed S (0 to 4294967295, default 0)
 *   0 gives the regular shapes above.  Any other S perturbs two shapes
 *   deterministically: the bumpy sphere's pattern turns about z by
 *   phi0 = 2 pi m / 65536, m a hash of S; the grid's interior vertices move
 *   by up to 0.1 of a square in x and in y (its border stays put, so it
 *   still covers exactly the square).  0.1 keeps every triangle
 *   counter-clockwise: with both edge vectors off by at most 0.2 in each
 *   coordinate, twice the area in squares is at least (1 - 0.2)^2 -
 *   0.2 (1 + 0.2) = 1 - 6 * 0.1 = 0.4 of its regular value.  The sphere,
 *   the knot and the cube have nothing to perturb and ignore the seed.
 *
 * Same bytes on every machine
 *   Everything is computed in double with +, -, *, / and sqrt, which IEEE
 *   754 rounds the same way everywhere (and -ffp-contract=off forbids fused
 *   multiply-adds).  No sin or cos from the C library, whose last bits
 *   differ between libraries: every angle here is a rational fraction of a
 *   turn, 2 pi n / d, so turn_sincos() reduces it exactly, in integers, to
 *   an eighth of a turn and evaluates Taylor polynomials there.  That also
 *   makes symmetric points exactly symmetric (sin pi is 0, not 1.2e-16).
 *   Numbers are printed with six decimals by fixed-point integer
 *   arithmetic (put_fixed), not printf, which is also about ten times
 *   faster.  The file records the shape and k but not its own name.
 *
 * Large meshes
 *   The mesh is never held in memory: positions, normals, texture
 *   coordinates and faces are written in turn, each computed from (i, j)
 *   when written, through one 1 MiB buffer.  Only per-row tables of sines
 *   (O(k) numbers) are kept.  The file is written under a temporary name
 *   beside FILE (src/io/new_file.c) and renamed into place when complete;
 *   Ctrl-C (or SIGTERM, SIGHUP, SIGQUIT) removes the temporary file, so an
 *   interrupted run leaves nothing.  Only SIGKILL can leave NAME.tmp-XXXXXX.
 *
 * Errors
 *   A bad argument gets one line on stderr naming the flag and what was
 *   expected, exit status 2, and no file.  A file that cannot be written
 *   gets one line and exit status 1, and no file either.
 */

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/new_file.h"
#include "luz/error.h"

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

enum { EXIT_USAGE = 2, EXIT_RUNTIME = 1 };

#define PROGRAM "gen-model"
#define MAX_TRIANGLES 20000000
#define DEFAULT_TRIANGLES 100000

/* pi / 4 to the nearest double. */
static const double QUARTER_PI = 0.78539816339744830962;

/* ---------------------------------------------------------------------- */
/* Sines and cosines of fractions of a turn                               */
/* ---------------------------------------------------------------------- */

/* Taylor polynomials of sin and cos around 0, for |x| <= pi / 4.  The first
 * term left out is x^17 / 17! < 5e-17 for sin and x^18 / 18! < 3e-18 for
 * cos, below half an ulp of the results, so these are within about one ulp.
 * The coefficients are exact divisions by factorials (all below 2^53), which
 * every compiler rounds the same way. */
static double sin_kernel(double x)
{
    double x2 = x * x;
    return x + x * x2 *
               (-1.0 / 6.0 +
                x2 * (1.0 / 120.0 +
                      x2 * (-1.0 / 5040.0 +
                            x2 * (1.0 / 362880.0 +
                                  x2 * (-1.0 / 39916800.0 +
                                        x2 * (1.0 / 6227020800.0 +
                                              x2 * (-1.0 / 1307674368000.0)))))));
}

static double cos_kernel(double x)
{
    double x2 = x * x;
    return 1.0 +
           x2 * (-1.0 / 2.0 +
                 x2 * (1.0 / 24.0 +
                       x2 * (-1.0 / 720.0 +
                             x2 * (1.0 / 40320.0 +
                                   x2 * (-1.0 / 3628800.0 +
                                         x2 * (1.0 / 479001600.0 +
                                               x2 * (-1.0 / 87178291200.0 +
                                                     x2 * (1.0 / 20922789888000.0))))))));
}

/* sin and cos of 2 pi numerator / denominator, denominator > 0 and
 * |8 numerator| < 2^63.  The fraction is reduced in integers to an octant
 * o (an eighth of a turn) and a remainder r / denominator of one; the
 * angle within the octant, pi/4 r/d, or its complement for odd octants, is
 * at most pi / 4, where the kernels are accurate, and the octant's
 * symmetries (sin(pi/2 - y) = cos y, a quarter turn swaps sin and cos with
 * a sign) give the rest.  Multiples of a quarter turn come out exact. */
static void turn_sincos(int64_t numerator, int64_t denominator, double *sine, double *cosine)
{
    int64_t turn = numerator % denominator;
    if (turn < 0)
        turn += denominator;
    int64_t octant = 8 * turn / denominator;          /* 0 .. 7 */
    int64_t rest = 8 * turn - octant * denominator;   /* 0 .. denominator - 1 */
    double s, c;   /* of the angle within the quarter turn */
    if (octant % 2 == 0) {
        double x = QUARTER_PI * ((double)rest / (double)denominator);
        s = sin_kernel(x);
        c = cos_kernel(x);
    } else {
        double y = QUARTER_PI * ((double)(denominator - rest) / (double)denominator);
        s = cos_kernel(y);
        c = sin_kernel(y);
    }
    switch (octant / 2) {
    case 0: *sine = s;  *cosine = c;  break;
    case 1: *sine = c;  *cosine = -s; break;
    case 2: *sine = -s; *cosine = -c; break;
    default: *sine = -c; *cosine = s; break;
    }
}

/* ---------------------------------------------------------------------- */
/* Vectors                                                                */
/* ---------------------------------------------------------------------- */

typedef struct {
    double x, y, z;
} vec3;

static vec3 v3(double x, double y, double z)
{
    vec3 v = {x, y, z};
    return v;
}

static vec3 add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static vec3 scale(vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }

static vec3 cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

static vec3 normalize(vec3 a)
{
    double length = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return scale(a, 1.0 / length);
}

/* A 64-bit mixing function (splitmix64's finaliser, Steele, Lea and Flood,
 * "Fast splittable pseudorandom number generators", 2014): every input bit
 * affects every output bit, so neighbouring seeds and vertices differ. */
static uint64_t mix64(uint64_t z)
{
    z += 0x9E3779B97F4A7C15u;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}

/* ---------------------------------------------------------------------- */
/* Buffered output                                                        */
/* ---------------------------------------------------------------------- */

enum { OUTPUT_BUFFER = 1 << 20, LONGEST_LINE = 256 };

typedef struct {
    FILE *stream;
    size_t length;
    char *buffer;   /* OUTPUT_BUFFER bytes */
} writer;

static void flush(writer *out)
{
    /* A short write sets the stream's error flag, which the commit checks. */
    fwrite(out->buffer, 1, out->length, out->stream);
    out->length = 0;
}

/* Makes room for one line: no line is longer than LONGEST_LINE. */
static char *line_start(writer *out)
{
    if (out->length > OUTPUT_BUFFER - LONGEST_LINE)
        flush(out);
    return out->buffer + out->length;
}

static void line_end(writer *out, char *end)
{
    *end++ = '\n';
    out->length = (size_t)(end - out->buffer);
}

static char *put_text(char *at, const char *text)
{
    while (*text)
        *at++ = *text++;
    return at;
}

static char *put_uint(char *at, uint64_t value)
{
    char digits[20];
    int count = 0;
    do {
        digits[count++] = (char)('0' + value % 10);
        value /= 10;
    } while (value != 0);
    while (count > 0)
        *at++ = digits[--count];
    return at;
}

/* value with exactly six decimals, rounded half away from zero from
 * |value| * 10^6 (one IEEE multiplication and add, so the same everywhere).
 * Like printf's %.6f but for ties of the binary value, and it never writes
 * "-0.000000": a value that rounds to zero is written "0.000000". */
static char *put_fixed(char *at, double value)
{
    double scaled = floor(fabs(value) * 1e6 + 0.5);
    uint64_t micro = (uint64_t)scaled;   /* |value| < 10 here, far from overflow */
    if (value < 0 && micro != 0)
        *at++ = '-';
    at = put_uint(at, micro / 1000000);
    *at++ = '.';
    uint64_t fraction = micro % 1000000;
    for (uint64_t unit = 100000; unit != 0; unit /= 10)
        *at++ = (char)('0' + fraction / unit % 10);
    return at;
}

static void put_vector(writer *out, const char *tag, vec3 v)
{
    char *at = put_text(line_start(out), tag);
    at = put_fixed(at, v.x);
    *at++ = ' ';
    at = put_fixed(at, v.y);
    *at++ = ' ';
    at = put_fixed(at, v.z);
    line_end(out, at);
}

static void put_uv(writer *out, double u, double v)
{
    char *at = put_text(line_start(out), "vt ");
    at = put_fixed(at, u);
    *at++ = ' ';
    at = put_fixed(at, v);
    line_end(out, at);
}

/* ---------------------------------------------------------------------- */
/* Models                                                                 */
/* ---------------------------------------------------------------------- */

typedef enum { SPHERE, BUMPY_SPHERE, TORUS_KNOT, GRID, CUBE } shape;

static const char *const SHAPE_NAMES[] = {"sphere", "bumpy-sphere", "torus-knot", "grid", "cube"};

typedef struct {
    shape shape;
    int64_t k;          /* the resolution (see the header comment) */
    bool normals, uvs;
    uint32_t seed;
} model;

typedef struct {
    int64_t triangles, positions, normals, uvs;
} counts;

/* The counts of the header comment. */
static counts counts_of(shape which, int64_t k)
{
    counts c;
    switch (which) {
    case SPHERE:
    case BUMPY_SPHERE:
        c.triangles = 4 * k * (k - 1);
        c.positions = 2 * k * (k - 1) + 2;
        c.normals = c.positions;
        c.uvs = (2 * k + 1) * (k - 1) + 4 * k;
        break;
    case TORUS_KNOT:
        c.triangles = 16 * k * k;
        c.positions = 8 * k * k;
        c.normals = c.positions;
        c.uvs = (8 * k + 1) * (k + 1);
        break;
    case GRID:
        c.triangles = 2 * k * k;
        c.positions = (k + 1) * (k + 1);
        c.normals = 1;
        c.uvs = c.positions;
        break;
    default:
        c.triangles = 12;
        c.positions = 8;
        c.normals = 6;
        c.uvs = 4;
        break;
    }
    return c;
}

static int64_t smallest_k(shape which)
{
    switch (which) {
    case SPHERE:
    case BUMPY_SPHERE: return 2;
    case TORUS_KNOT: return 3;
    default: return 1;
    }
}

/* The largest k whose count is at most wanted, or the smallest k. */
static int64_t choose_k(shape which, int64_t wanted)
{
    int64_t k = smallest_k(which);
    if (which == CUBE)
        return k;
    while (counts_of(which, k + 1).triangles <= wanted)
        k++;
    return k;
}

/* One corner of a face: 1-based indices into the positions, texture
 * coordinates and normals. */
typedef struct {
    int64_t position, uv, normal;
} corner;

static void put_triangle(writer *out, const model *m, corner a, corner b, corner c)
{
    const corner corners[3] = {a, b, c};
    char *at = line_start(out);
    *at++ = 'f';
    for (int i = 0; i < 3; i++) {
        *at++ = ' ';
        at = put_uint(at, (uint64_t)corners[i].position);
        if (m->uvs || m->normals)
            *at++ = '/';
        if (m->uvs)
            at = put_uint(at, (uint64_t)corners[i].uv);
        if (m->normals) {
            *at++ = '/';
            at = put_uint(at, (uint64_t)corners[i].normal);
        }
    }
    line_end(out, at);
}

/* ---- the spheres ---- */

/* Per-row and per-column sines, so that each vertex costs no trigonometry. */
typedef struct {
    int64_t stacks, slices;    /* k and 2k */
    bool bumpy;
    double *sin_theta, *cos_theta, *sin_7theta, *cos_7theta;   /* stacks + 1 */
    double *sin_phi, *cos_phi, *sin_5psi, *cos_5psi;           /* slices */
} sphere_tables;

static const double BUMP = 0.15;

static bool sphere_tables_make(sphere_tables *t, const model *m)
{
    t->stacks = m->k;
    t->slices = 2 * m->k;
    t->bumpy = m->shape == BUMPY_SPHERE;
    size_t rows = (size_t)t->stacks + 1, columns = (size_t)t->slices;
    double *all = malloc(sizeof(double) * 4 * (rows + columns));
    if (all == NULL)
        return false;
    t->sin_theta = all;
    t->cos_theta = all + rows;
    t->sin_7theta = all + 2 * rows;
    t->cos_7theta = all + 3 * rows;
    t->sin_phi = all + 4 * rows;
    t->cos_phi = t->sin_phi + columns;
    t->sin_5psi = t->sin_phi + 2 * columns;
    t->cos_5psi = t->sin_phi + 3 * columns;

    /* theta_i = pi i / k = one turn times i / 2k. */
    for (int64_t i = 0; i <= t->stacks; i++) {
        turn_sincos(i, 2 * t->stacks, &t->sin_theta[i], &t->cos_theta[i]);
        turn_sincos(7 * i, 2 * t->stacks, &t->sin_7theta[i], &t->cos_7theta[i]);
    }
    /* phi_j = 2 pi j / 2k; 5 (phi_j - phi0) with phi0 = 2 pi m / 65536 is
     * the turn 5 (65536 j - m 2k) / (65536 2k). */
    int64_t m_phase = m->seed == 0 ? 0 : (int64_t)(mix64(m->seed) & 0xFFFF);
    for (int64_t j = 0; j < t->slices; j++) {
        turn_sincos(j, t->slices, &t->sin_phi[j], &t->cos_phi[j]);
        turn_sincos(5 * (65536 * j - m_phase * t->slices), 65536 * t->slices, &t->sin_5psi[j],
                    &t->cos_5psi[j]);
    }
    return true;
}

/* The position and the unit outward normal at (theta_i, phi_j). */
static void sphere_point(const sphere_tables *t, int64_t i, int64_t j, vec3 *position,
                         vec3 *normal)
{
    double st = t->sin_theta[i], ct = t->cos_theta[i];
    double sp = t->sin_phi[j], cp = t->cos_phi[j];
    vec3 e_r = v3(st * cp, st * sp, ct);
    if (!t->bumpy) {
        *position = e_r;
        *normal = e_r;
        return;
    }
    /* r = 1 + A sin^4 theta sin 7theta sin 5psi (psi = phi - phi0), and
     * r_theta = A sin 5psi (4 sin^3 theta cos theta sin 7theta + 7 sin^4 theta cos 7theta),
     * r_phi / sin theta = 5 A sin^3 theta sin 7theta cos 5psi. */
    double s3 = st * st * st, s4 = s3 * st;
    double s7 = t->sin_7theta[i], c7 = t->cos_7theta[i];
    double s5 = t->sin_5psi[j], c5 = t->cos_5psi[j];
    double r = 1.0 + BUMP * s4 * s7 * s5;
    double r_theta = BUMP * s5 * (4.0 * s3 * ct * s7 + 7.0 * s4 * c7);
    double r_phi_over_sin = 5.0 * BUMP * s3 * s7 * c5;
    vec3 e_theta = v3(ct * cp, ct * sp, -st);
    vec3 e_phi = v3(-sp, cp, 0.0);
    *position = scale(e_r, r);
    *normal = normalize(add(add(scale(e_r, r), scale(e_theta, -r_theta)),
                            scale(e_phi, -r_phi_over_sin)));
}

static void write_sphere(writer *out, const model *m, const sphere_tables *t)
{
    const int64_t k = t->stacks, n = t->slices;
    vec3 position, normal;
    /* Positions: the north pole, rings i = 1 .. k - 1 of n vertices, the
     * south pole.  Normals follow the same order. */
    for (int pass = 0; pass < (m->normals ? 2 : 1); pass++) {
        const char *tag = pass == 0 ? "v " : "vn ";
        sphere_point(t, 0, 0, &position, &normal);
        put_vector(out, tag, pass == 0 ? position : normal);
        for (int64_t i = 1; i < k; i++) {
            for (int64_t j = 0; j < n; j++) {
                sphere_point(t, i, j, &position, &normal);
                put_vector(out, tag, pass == 0 ? position : normal);
            }
        }
        sphere_point(t, k, 0, &position, &normal);
        put_vector(out, tag, pass == 0 ? position : normal);
    }
    /* Texture coordinates: rings of n + 1 (u = 1 repeats u = 0 at the
     * seam), then one per pole triangle at the middle of its u range. */
    if (m->uvs) {
        for (int64_t i = 1; i < k; i++)
            for (int64_t j = 0; j <= n; j++)
                put_uv(out, (double)j / (double)n, 1.0 - (double)i / (double)k);
        for (int64_t j = 0; j < n; j++)
            put_uv(out, ((double)j + 0.5) / (double)n, 1.0);
        for (int64_t j = 0; j < n; j++)
            put_uv(out, ((double)j + 0.5) / (double)n, 0.0);
    }
    /* Faces.  ring(i, j) for 1 <= i <= k - 1 wraps j around the seam. */
    const int64_t north = 1, south = 2 + (k - 1) * n;
    const int64_t north_uv = 1 + (k - 1) * (n + 1), south_uv = north_uv + n;
#define RING(i, j) ((corner){2 + ((i) - 1) * n + (j) % n, 1 + ((i) - 1) * (n + 1) + (j), \
                             2 + ((i) - 1) * n + (j) % n})
    for (int64_t j = 0; j < n; j++) {
        corner pole = {north, north_uv + j, north};
        put_triangle(out, m, pole, RING(1, j), RING(1, j + 1));
    }
    for (int64_t i = 1; i < k - 1; i++) {
        for (int64_t j = 0; j < n; j++) {
            put_triangle(out, m, RING(i, j), RING(i + 1, j), RING(i + 1, j + 1));
            put_triangle(out, m, RING(i, j), RING(i + 1, j + 1), RING(i, j + 1));
        }
    }
    for (int64_t j = 0; j < n; j++) {
        corner pole = {south, south_uv + j, south};
        put_triangle(out, m, RING(k - 1, j), pole, RING(k - 1, j + 1));
    }
#undef RING
}

/* ---- the torus knot ---- */

static const double KNOT_R = 1.0, KNOT_A = 0.45, KNOT_RHO = 0.3;
enum { KNOT_P = 2, KNOT_Q = 3 };

typedef struct {
    int64_t along, around;   /* 8k and k */
    vec3 *centre, *n, *b;    /* along */
    double *sin_s, *cos_s;   /* around */
} knot_tables;

static bool knot_tables_make(knot_tables *t, const model *m)
{
    t->along = 8 * m->k;
    t->around = m->k;
    size_t along = (size_t)t->along, around = (size_t)t->around;
    t->centre = malloc(sizeof(vec3) * 3 * along);
    t->sin_s = malloc(sizeof(double) * 2 * around);
    if (t->centre == NULL || t->sin_s == NULL) {
        free(t->centre);
        free(t->sin_s);
        return false;
    }
    t->n = t->centre + along;
    t->b = t->centre + 2 * along;
    t->cos_s = t->sin_s + around;
    for (int64_t i = 0; i < t->along; i++) {
        /* t_i = 2 pi i / along: p t and q t are p i and q i turns / along. */
        double sp, cp, sq, cq;
        turn_sincos(KNOT_P * i, t->along, &sp, &cp);
        turn_sincos(KNOT_Q * i, t->along, &sq, &cq);
        double radius = KNOT_R + KNOT_A * cq;
        t->centre[i] = v3(radius * cp, radius * sp, KNOT_A * sq);
        /* C'(t), differentiated by hand. */
        vec3 velocity = v3(-KNOT_A * KNOT_Q * sq * cp - radius * KNOT_P * sp,
                           -KNOT_A * KNOT_Q * sq * sp + radius * KNOT_P * cp,
                           KNOT_A * KNOT_Q * cq);
        t->n[i] = v3(cq * cp, cq * sp, sq);
        t->b[i] = normalize(cross(normalize(velocity), t->n[i]));
    }
    for (int64_t j = 0; j < t->around; j++)
        turn_sincos(j, t->around, &t->sin_s[j], &t->cos_s[j]);
    return true;
}

static void write_knot(writer *out, const model *m, const knot_tables *t)
{
    const int64_t along = t->along, around = t->around;
    for (int pass = 0; pass < (m->normals ? 2 : 1); pass++) {
        for (int64_t i = 0; i < along; i++) {
            for (int64_t j = 0; j < around; j++) {
                vec3 offset = normalize(add(scale(t->n[i], t->cos_s[j]),
                                            scale(t->b[i], t->sin_s[j])));
                if (pass == 0)
                    put_vector(out, "v ", add(t->centre[i], scale(offset, KNOT_RHO)));
                else
                    put_vector(out, "vn ", offset);
            }
        }
    }
    /* u = i / k runs 0 to 8 along the knot, v = j / k 0 to 1 around: square
     * texels on about square quads (luz repeats textures). */
    if (m->uvs)
        for (int64_t i = 0; i <= along; i++)
            for (int64_t j = 0; j <= around; j++)
                put_uv(out, (double)i / (double)m->k, (double)j / (double)m->k);
#define AT(i, j) ((corner){1 + (i) % along * around + (j) % around, 1 + (i) * (around + 1) + (j), \
                           1 + (i) % along * around + (j) % around})
    for (int64_t i = 0; i < along; i++) {
        for (int64_t j = 0; j < around; j++) {
            /* s first, then t: counter-clockwise from outside. */
            put_triangle(out, m, AT(i, j), AT(i, j + 1), AT(i + 1, j + 1));
            put_triangle(out, m, AT(i, j), AT(i + 1, j + 1), AT(i + 1, j));
        }
    }
#undef AT
}

/* ---- the grid ---- */

/* The jitter of interior vertex (i, j) along one axis, in squares, within
 * [-0.1, 0.1); 0 on the border and without a seed. */
static double grid_jitter(const model *m, int64_t i, int64_t j, uint64_t axis)
{
    if (m->seed == 0 || i == 0 || j == 0 || i == m->k || j == m->k)
        return 0.0;
    uint64_t h = mix64(mix64(mix64(m->seed) ^ (uint64_t)i) ^ ((uint64_t)j << 1 | axis));
    double unit = (double)(h >> 11) / 9007199254740992.0;   /* [0, 1), 53 bits */
    return 0.2 * unit - 0.1;
}

static vec3 grid_point(const model *m, int64_t i, int64_t j)
{
    double k = (double)m->k;
    return v3(2.0 * ((double)i + grid_jitter(m, i, j, 0)) / k - 1.0,
              2.0 * ((double)j + grid_jitter(m, i, j, 1)) / k - 1.0, 0.0);
}

static void write_grid(writer *out, const model *m)
{
    const int64_t k = m->k;
    /* Rows of constant y from -1 up, x from -1 across: position (i, j) is
     * number 1 + j (k + 1) + i, and so is its texture coordinate. */
    for (int64_t j = 0; j <= k; j++)
        for (int64_t i = 0; i <= k; i++)
            put_vector(out, "v ", grid_point(m, i, j));
    if (m->normals)
        put_vector(out, "vn ", v3(0.0, 0.0, 1.0));
    if (m->uvs) {
        for (int64_t j = 0; j <= k; j++) {
            for (int64_t i = 0; i <= k; i++) {
                vec3 p = grid_point(m, i, j);
                put_uv(out, (p.x + 1.0) * 0.5, (p.y + 1.0) * 0.5);
            }
        }
    }
#define AT(i, j) ((corner){1 + (j) * (k + 1) + (i), 1 + (j) * (k + 1) + (i), 1})
    for (int64_t j = 0; j < k; j++) {
        for (int64_t i = 0; i < k; i++) {
            put_triangle(out, m, AT(i, j), AT(i + 1, j), AT(i + 1, j + 1));
            put_triangle(out, m, AT(i, j), AT(i + 1, j + 1), AT(i, j + 1));
        }
    }
#undef AT
}

/* ---- the cube ---- */

static void write_cube(writer *out, const model *m)
{
    /* Corner number 1 + x + 2y + 4z for x, y, z in {0, 1} (0 is -1). */
    for (int c = 0; c < 8; c++)
        put_vector(out, "v ", v3(c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0));
    if (m->normals) {
        static const vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                        {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (int f = 0; f < 6; f++)
            put_vector(out, "vn ", normals[f]);
    }
    if (m->uvs) {
        put_uv(out, 0.0, 0.0);
        put_uv(out, 1.0, 0.0);
        put_uv(out, 1.0, 1.0);
        put_uv(out, 0.0, 1.0);
    }
    /* Each face's corners a, b, c, d counter-clockwise seen from outside,
     * checked with (b - a) x (c - a): for +x, (0,1,0) x (0,1,1) = (1,0,0).
     * The face takes texture coordinates (0,0), (1,0), (1,1), (0,1). */
    static const int faces[6][4] = {
        {1, 3, 7, 5},                   /* +x: the corners with x = 1 */
        {0, 4, 6, 2},                   /* -x */
        {2, 6, 7, 3},                   /* +y */
        {0, 1, 5, 4},                   /* -y */
        {4, 5, 7, 6},                   /* +z */
        {0, 2, 3, 1},                   /* -z */
    };
    for (int f = 0; f < 6; f++) {
        corner q[4];
        for (int c = 0; c < 4; c++)
            q[c] = (corner){1 + faces[f][c], 1 + c, 1 + f};
        put_triangle(out, m, q[0], q[1], q[2]);
        put_triangle(out, m, q[0], q[2], q[3]);
    }
}

/* ---------------------------------------------------------------------- */
/* The command line                                                       */
/* ---------------------------------------------------------------------- */

static void usage(FILE *stream)
{
    fputs("usage: gen-model --shape SHAPE [--triangles N] [--no-normals] [--no-uvs]\n"
          "                 [--seed S] -o FILE.obj\n"
          "\n"
          "Writes a procedural triangle mesh as a Wavefront OBJ file.\n"
          "\n"
          "  --shape SHAPE    sphere, bumpy-sphere, torus-knot, grid or cube\n"
          "  --triangles N    about N triangles: the largest count the shape has at\n"
          "                   most N, or its smallest (1 to 20000000, default 100000;\n"
          "                   the cube always has 12); the exact count goes to stderr\n"
          "  --no-normals     write no vertex normals (vn)\n"
          "  --no-uvs         write no texture coordinates (vt)\n"
          "  --seed S         0 to 4294967295 (default 0, the regular shapes): turns\n"
          "                   the bumpy sphere's bumps, jitters the grid's vertices\n"
          "  -o FILE.obj      the output, written whole or not at all\n"
          "  --help           this text\n"
          "\n"
          "Shapes, equations and triangle counts: the comment at the top of\n"
          "tools/gen-model.c.\n",
          stream);
}

/* "PROGRAM: message" on stderr, one line, and the status to exit with. */
static int refuse(const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

static int refuse(const char *format, ...)
{
    luz_error error;
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(error.message, sizeof error.message, format, arguments);
    va_end(arguments);
    luz_error_print(PROGRAM, error.message);
    return EXIT_USAGE;
}

/* A decimal number of digits only, 0 to max; false if anything else. */
static bool parse_count(const char *text, uint64_t max, uint64_t *value)
{
    if (text == NULL || *text == '\0')
        return false;
    uint64_t result = 0;
    for (const char *c = text; *c; c++) {
        if (*c < '0' || *c > '9')
            return false;
        unsigned digit = (unsigned)(*c - '0');
        if (result > (max - digit) / 10)
            return false;
        result = result * 10 + digit;
    }
    *value = result;
    return true;
}

typedef struct {
    model model;
    uint64_t triangles;
    const char *output;
    bool shape_given;
} arguments;

/* Returns -1 to go on, or the status to exit with (0 after --help). */
static int parse_arguments(int argc, char **argv, arguments *a)
{
    *a = (arguments){.model = {.normals = true, .uvs = true}, .triangles = DEFAULT_TRIANGLES};
    for (int index = 1; index < argc; index++) {
        const char *flag = argv[index];
        /* --flag=value is the same as --flag value. */
        char name[32];
        const char *value = NULL;
        const char *equals = strncmp(flag, "--", 2) == 0 ? strchr(flag, '=') : NULL;
        if (equals != NULL && (size_t)(equals - flag) < sizeof name) {
            memcpy(name, flag, (size_t)(equals - flag));
            name[equals - flag] = '\0';
            flag = name;
            value = equals + 1;
        }
        bool takes_value = strcmp(flag, "--shape") == 0 || strcmp(flag, "--triangles") == 0 ||
                           strcmp(flag, "--seed") == 0 || strcmp(flag, "-o") == 0 ||
                           strcmp(flag, "--output") == 0;
        if (takes_value && value == NULL && index + 1 < argc)
            value = argv[++index];
        if (!takes_value && value != NULL)
            return refuse("%s: takes no value", flag);

        if (strcmp(flag, "--help") == 0 || strcmp(flag, "-h") == 0) {
            usage(stdout);
            return fflush(stdout) == 0 ? 0 : EXIT_RUNTIME;
        } else if (strcmp(flag, "--no-normals") == 0) {
            a->model.normals = false;
        } else if (strcmp(flag, "--no-uvs") == 0) {
            a->model.uvs = false;
        } else if (strcmp(flag, "--shape") == 0) {
            int found = -1;
            for (int s = 0; s < 5 && value != NULL; s++)
                if (strcmp(value, SHAPE_NAMES[s]) == 0)
                    found = s;
            if (found < 0)
                return refuse("--shape: expected sphere, bumpy-sphere, torus-knot, grid or cube%s%s%s",
                              value ? ", not '" : "", value ? value : "", value ? "'" : "");
            a->model.shape = (shape)found;
            a->shape_given = true;
        } else if (strcmp(flag, "--triangles") == 0) {
            if (!parse_count(value, MAX_TRIANGLES, &a->triangles) || a->triangles == 0)
                return refuse("--triangles: expected a whole number from 1 to %d%s%s%s",
                              MAX_TRIANGLES, value ? ", not '" : "", value ? value : "",
                              value ? "'" : "");
        } else if (strcmp(flag, "--seed") == 0) {
            uint64_t seed;
            if (!parse_count(value, UINT32_MAX, &seed))
                return refuse("--seed: expected a whole number from 0 to 4294967295%s%s%s",
                              value ? ", not '" : "", value ? value : "", value ? "'" : "");
            a->model.seed = (uint32_t)seed;
        } else if (strcmp(flag, "-o") == 0 || strcmp(flag, "--output") == 0) {
            if (value == NULL || *value == '\0')
                return refuse("%s: expected the name of the OBJ file to write", flag);
            a->output = value;
        } else if (flag[0] == '-') {
            return refuse("%s: unknown option (see --help)", flag);
        } else {
            return refuse("'%s': unexpected argument (options start with --; see --help)",
                          flag);
        }
    }
    if (!a->shape_given)
        return refuse("--shape: missing; expected sphere, bumpy-sphere, torus-knot, grid or cube");
    if (a->output == NULL)
        return refuse("-o: missing; expected the name of the OBJ file to write");
    a->model.k = choose_k(a->model.shape, (int64_t)a->triangles);
    return -1;
}

/* ---------------------------------------------------------------------- */
/* Writing the file                                                       */
/* ---------------------------------------------------------------------- */

/* The temporary file for the signal handler to remove.  It is set and
 * cleared only while the termination signals are blocked, so the handler
 * never sees a name that is being freed. */
static char *volatile temporary_to_remove;

static void remove_temporary_and_die(int signal_number)
{
    char *name = temporary_to_remove;
    if (name != NULL)
        unlink(name);   /* async-signal-safe, as are signal() and raise() */
    signal(signal_number, SIG_DFL);
    raise(signal_number);
}

static const int TERMINATION_SIGNALS[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

static void block_termination(sigset_t *previous)
{
    sigset_t set;
    sigemptyset(&set);
    for (size_t s = 0; s < sizeof TERMINATION_SIGNALS / sizeof *TERMINATION_SIGNALS; s++)
        sigaddset(&set, TERMINATION_SIGNALS[s]);
    sigprocmask(SIG_BLOCK, &set, previous);
}

static void write_header(writer *out, const model *m, counts c)
{
    char *at = put_text(line_start(out), "# gen-model --shape ");
    at = put_text(at, SHAPE_NAMES[m->shape]);
    at = put_text(at, " --triangles ");
    at = put_uint(at, (uint64_t)c.triangles);
    if (!m->normals)
        at = put_text(at, " --no-normals");
    if (!m->uvs)
        at = put_text(at, " --no-uvs");
    /* Only where the seed changes the shape, so that the other shapes'
     * files do not depend on it at all. */
    if (m->seed != 0 && (m->shape == BUMPY_SPHERE || m->shape == GRID)) {
        at = put_text(at, " --seed ");
        at = put_uint(at, m->seed);
    }
    line_end(out, at);
    at = put_text(line_start(out), "# k = ");
    at = put_uint(at, (uint64_t)m->k);
    at = put_text(at, ": ");
    at = put_uint(at, (uint64_t)c.triangles);
    at = put_text(at, " triangles, ");
    at = put_uint(at, (uint64_t)c.positions);
    at = put_text(at, " positions");
    line_end(out, at);
    at = put_text(line_start(out), "o ");
    at = put_text(at, SHAPE_NAMES[m->shape]);
    line_end(out, at);
}

/* Writes the whole file to out; false if a table could not be allocated. */
static bool write_model(writer *out, const model *m, counts c)
{
    write_header(out, m, c);
    switch (m->shape) {
    case SPHERE:
    case BUMPY_SPHERE: {
        sphere_tables tables;
        if (!sphere_tables_make(&tables, m))
            return false;
        write_sphere(out, m, &tables);
        free(tables.sin_theta);
        break;
    }
    case TORUS_KNOT: {
        knot_tables tables;
        if (!knot_tables_make(&tables, m))
            return false;
        write_knot(out, m, &tables);
        free(tables.centre);
        free(tables.sin_s);
        break;
    }
    case GRID:
        write_grid(out, m);
        break;
    case CUBE:
        write_cube(out, m);
        break;
    }
    flush(out);
    return true;
}

int main(int argc, char **argv)
{
    arguments a;
    int status = parse_arguments(argc, argv, &a);
    if (status >= 0)
        return status;
    const model *m = &a.model;
    counts c = counts_of(m->shape, m->k);

    writer out = {.buffer = malloc(OUTPUT_BUFFER)};
    if (out.buffer == NULL) {
        luz_error_print(PROGRAM, "out of memory");
        return EXIT_RUNTIME;
    }

    /* The handler is in place before the temporary file exists, and the
     * name is published to it with the signals blocked. */
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = remove_temporary_and_die;
    sigemptyset(&action.sa_mask);
    for (size_t s = 0; s < sizeof TERMINATION_SIGNALS / sizeof *TERMINATION_SIGNALS; s++)
        sigaction(TERMINATION_SIGNALS[s], &action, NULL);

    sigset_t previous;
    luz_error error = {{0}};
    luz_new_file file;
    block_termination(&previous);
    int opened = luz_new_file_open(&file, a.output, &error);
    if (opened == 0)
        temporary_to_remove = file.temporary;
    sigprocmask(SIG_SETMASK, &previous, NULL);
    if (opened != 0) {
        luz_error_print(PROGRAM, error.message);
        free(out.buffer);
        return EXIT_RUNTIME;
    }

    out.stream = file.stream;
    bool written = write_model(&out, m, c);

    block_termination(&previous);
    if (written) {
        status = luz_new_file_commit(&file, true, &error) == 0 ? 0 : EXIT_RUNTIME;
    } else {
        luz_new_file_abandon(&file);
        luz_error_set(&error, "%s: out of memory", a.output);
        status = EXIT_RUNTIME;
    }
    temporary_to_remove = NULL;
    sigprocmask(SIG_SETMASK, &previous, NULL);
    free(out.buffer);

    if (status != 0) {
        luz_error_print(PROGRAM, error.message);
        return status;
    }
    fprintf(stderr, "%s: %s: %s, %lld triangles (k = %lld), %lld positions\n", PROGRAM,
            a.output, SHAPE_NAMES[m->shape], (long long)c.triangles, (long long)m->k,
            (long long)c.positions);
    return 0;
}
