/*
 * test_gen_model.c: tools/gen-model as a user runs it, and the geometry of
 * what it writes.
 *
 * Each test runs the real gen-model (its path in $GEN_MODEL, set by
 * tests/meson.build) in a fresh temporary directory, reads the OBJ file back
 * with the small strict parser below, and checks it against the geometry of
 * the shape, not against a stored file:
 *
 *   (a) the exact counts, worked out by hand from the formulas at the top of
 *       tools/gen-model.c (the table `cases` shows the arithmetic);
 *   (b) every index of every face in range, every position used, no
 *       triangle with a repeated corner, and no face whose texture
 *       coordinates jump across a seam;
 *   (c) every normal of unit length within 1e-5 and pointing out: equal to
 *       the position on the sphere, equal to the finite-difference normal
 *       of r(theta, phi) on the bumpy sphere, exactly rho from the knot's
 *       centre line on the knot, +z on the grid, the face's own normal on
 *       the cube, and on the side of every face that its winding says;
 *   (d) closed shapes watertight: every directed edge once, its reverse
 *       once (so every undirected edge in exactly two faces, in opposite
 *       directions, which is also consistent winding), and Euler's
 *       V - E + F = 2 (sphere, cube) or 0 (the knot's torus); the grid's
 *       open edges are exactly its border;
 *   (e) outward winding: the signed volume sum (a . (b x c)) / 6 is
 *       positive and near the solid's volume, within the discretisation
 *       error stated at each check;
 *   (f) the same arguments give the same bytes, and the cube is exactly the
 *       file worked out by hand;
 *   (g) bad arguments: exit status 2, one line naming the flag, no file;
 *   and an interrupted run leaves no file, and 1,000,000 triangles are
 *   written in a reasonable time (printed).
 */
/* realpath */
#define _XOPEN_SOURCE 700

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "file_support.h"
#include "test_support.h"

static const double PI = 3.14159265358979323846;

/* ---- running gen-model ------------------------------------------------------------- */

/* A fresh temporary directory: work/ is where gen-model runs, its stdout
 * and stderr are captured beside it, so work/ holds only what it made. */
typedef struct sandbox {
    char root[256];
    char work[300];
} sandbox;

static void sandbox_create(sandbox *box)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(box->root, sizeof box->root, "%s/luz-gen-model-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    assert_non_null(mkdtemp(box->root));
    snprintf(box->work, sizeof box->work, "%s/work", box->root);
    assert_int_equal(mkdir(box->work, 0755), 0);
}

static void sandbox_destroy(sandbox *box)
{
    remove_tree(box->root);
}

/* The names in box->work, sorted, one a line. */
static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void list_work(const sandbox *box, char *out, size_t size)
{
    DIR *directory = opendir(box->work);
    assert_non_null(directory);
    char *names[64];
    int count = 0;
    struct dirent *entry;
    while ((entry = readdir(directory)) != NULL && count < 64)
        if (strcmp(entry->d_name, ".") != 0 && strcmp(entry->d_name, "..") != 0)
            names[count++] = strdup(entry->d_name);
    closedir(directory);
    qsort(names, (size_t)count, sizeof *names, compare_names);
    out[0] = '\0';
    for (int i = 0; i < count; i++) {
        size_t used = strlen(out);
        snprintf(out + used, size - used, "%s\n", names[i]);
        free(names[i]);
    }
}

typedef struct run_result {
    int status;   /* the exit status, or 128 + signal */
    char *out, *err;
    double seconds;
} run_result;


/* $GEN_MODEL made absolute, since gen-model runs in another directory. */
static const char *gen_model_path(void)
{
    static char absolute[4096];
    const char *program = getenv("GEN_MODEL");
    if (program == NULL)
        fail_msg("GEN_MODEL is not set (tests/meson.build sets it to gen-model's path)");
    if (realpath(program, absolute) == NULL)
        fail_msg("GEN_MODEL=%s: %s", program, strerror(errno));
    return absolute;
}

/* Starts gen-model with the NULL-terminated arguments in box->work. */
static pid_t start_in(const sandbox *box, const char *const *arguments)
{
    const char *program = gen_model_path();
    char out_path[400], err_path[400];
    snprintf(out_path, sizeof out_path, "%s/stdout", box->root);
    snprintf(err_path, sizeof err_path, "%s/stderr", box->root);
    char *argv[32];
    int argc = 0;
    argv[argc++] = (char *)program;
    for (int i = 0; arguments[i] != NULL && argc < 31; i++)
        argv[argc++] = (char *)arguments[i];
    argv[argc] = NULL;

    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int out = open(out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int err = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || chdir(box->work) != 0 || dup2(out, STDOUT_FILENO) < 0 ||
            dup2(err, STDERR_FILENO) < 0)
            _exit(127);
        execv(program, argv);
        _exit(127);
    }
    return child;
}

static run_result finish(const sandbox *box, pid_t child, double start)
{
    int status;
    while (waitpid(child, &status, 0) < 0)
        assert_int_equal(errno, EINTR);
    run_result result;
    result.seconds = now_seconds() - start;
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    char path[400];
    snprintf(path, sizeof path, "%s/stdout", box->root);
    result.out = read_file(path, NULL);
    snprintf(path, sizeof path, "%s/stderr", box->root);
    result.err = read_file(path, NULL);
    assert_non_null(result.out);
    assert_non_null(result.err);
    return result;
}

static run_result run_in(const sandbox *box, const char *const *arguments)
{
    double start = now_seconds();
    return finish(box, start_in(box, arguments), start);
}

static void run_result_free(run_result *result)
{
    free(result->out);
    free(result->err);
}

/* The whole of the file name in box->work, NUL-terminated (free it). */
static char *read_work_file(const sandbox *box, const char *name)
{
    char path[400];
    snprintf(path, sizeof path, "%s/%s", box->work, name);
    char *data = read_file(path, NULL);
    if (data == NULL) fail_msg("%s: %s", path, strerror(errno));
    return data;
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

/* Exit status 0, nothing on stdout, and exactly the one line
 * "gen-model: NAME: SHAPE, T triangles (k = K), P positions" on stderr;
 * returns T. */
static long long assert_written(const run_result *result, const char *name)
{
    if (result->status != 0)
        fail_msg("gen-model exited %d, stderr: %s", result->status, result->err);
    assert_string_equal(result->out, "");
    char prefix[300];
    snprintf(prefix, sizeof prefix, "gen-model: %s: ", name);
    if (strncmp(result->err, prefix, strlen(prefix)) != 0)
        fail_msg("stderr does not start with '%s': %s", prefix, result->err);
    const char *comma = strchr(result->err + strlen(prefix), ',');
    assert_non_null(comma);
    long long triangles = -1;
    if (sscanf(comma, ", %lld triangles", &triangles) != 1)
        fail_msg("no triangle count on stderr: %s", result->err);
    size_t length = strlen(result->err);
    if (strchr(result->err, '\n') != result->err + length - 1)
        fail_msg("stderr is not one line: %s", result->err);
    return triangles;
}

/* ---- reading OBJ files ------------------------------------------------------------------ */

/* Exactly the subset gen-model writes, and nothing else is accepted:
 * comments, "o NAME", "v x y z", "vn x y z", "vt u v" and triangles
 * "f a b c" in one of OBJ's four corner forms a, a/t, a//n, a/t/n, the
 * same form for every corner of the file. */
typedef struct {
    double *positions, *normals, *uvs;   /* 3, 3 and 2 numbers each */
    long positions_count, normals_count, uvs_count;
    long (*faces)[3][3];                 /* position, uv, normal (1-based, 0 if absent) */
    long face_count;
    bool face_uvs, face_normals;         /* the corner form */
} mesh;

static void *grow(void *array, long count, long *capacity, size_t element)
{
    if (count < *capacity)
        return array;
    *capacity = *capacity ? 2 * *capacity : 1024;
    void *grown = realloc(array, (size_t)*capacity * element);
    assert_non_null(grown);
    return grown;
}

static void parse_numbers(const char *text, double *out, int count, long line_number)
{
    char *end;
    for (int i = 0; i < count; i++) {
        out[i] = strtod(text, &end);
        if (end == text || (*end != ' ' && *end != '\n' && *end != '\0'))
            fail_msg("line %ld: expected %d numbers", line_number, count);
        text = end;
    }
    if (*text != '\n' && *text != '\0')
        fail_msg("line %ld: more than %d numbers", line_number, count);
}

static long parse_index(const char **text, long line_number)
{
    char *end;
    long value = strtol(*text, &end, 10);
    if (end == *text)
        fail_msg("line %ld: expected an index", line_number);
    *text = end;
    return value;
}

static mesh parse_obj(const char *data)
{
    mesh m;
    memset(&m, 0, sizeof m);
    long capacity[4] = {0, 0, 0, 0};
    bool form_known = false;
    long line_number = 0;
    for (const char *line = data; *line != '\0';) {
        line_number++;
        const char *end = strchr(line, '\n');
        if (end == NULL)
            fail_msg("line %ld: the file does not end with a newline", line_number);
        if (line[0] == '#' || strncmp(line, "o ", 2) == 0) {
            /* nothing to read */
        } else if (strncmp(line, "v ", 2) == 0) {
            m.positions = grow(m.positions, m.positions_count, &capacity[0], 3 * sizeof(double));
            parse_numbers(line + 2, m.positions + 3 * m.positions_count++, 3, line_number);
        } else if (strncmp(line, "vn ", 3) == 0) {
            m.normals = grow(m.normals, m.normals_count, &capacity[1], 3 * sizeof(double));
            parse_numbers(line + 3, m.normals + 3 * m.normals_count++, 3, line_number);
        } else if (strncmp(line, "vt ", 3) == 0) {
            m.uvs = grow(m.uvs, m.uvs_count, &capacity[2], 2 * sizeof(double));
            parse_numbers(line + 3, m.uvs + 2 * m.uvs_count++, 2, line_number);
        } else if (strncmp(line, "f ", 2) == 0) {
            m.faces = grow(m.faces, m.face_count, &capacity[3], sizeof *m.faces);
            long (*face)[3] = m.faces[m.face_count++];
            const char *at = line + 1;
            for (int c = 0; c < 3; c++) {
                if (*at++ != ' ')
                    fail_msg("line %ld: expected three corners", line_number);
                face[c][0] = parse_index(&at, line_number);
                face[c][1] = face[c][2] = 0;
                bool has_uv = false, has_normal = false;
                if (*at == '/') {
                    at++;
                    if (*at != '/') {
                        face[c][1] = parse_index(&at, line_number);
                        has_uv = true;
                    }
                    if (*at == '/') {
                        at++;
                        face[c][2] = parse_index(&at, line_number);
                        has_normal = true;
                    }
                }
                if (!form_known) {
                    m.face_uvs = has_uv;
                    m.face_normals = has_normal;
                    form_known = true;
                } else if (has_uv != m.face_uvs || has_normal != m.face_normals) {
                    fail_msg("line %ld: corners of different forms", line_number);
                }
            }
            if (at != end)
                fail_msg("line %ld: not a triangle: %.*s", line_number, (int)(end - line), line);
        } else {
            fail_msg("line %ld: unexpected line '%.*s'", line_number, (int)(end - line), line);
        }
        line = end + 1;
    }
    return m;
}

static void mesh_free(mesh *m)
{
    free(m->positions);
    free(m->normals);
    free(m->uvs);
    free(m->faces);
}

/* ---- vectors ---- */

typedef struct {
    double x, y, z;
} vec3;

static vec3 v3(double x, double y, double z) { return (vec3){x, y, z}; }
static vec3 sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static vec3 scale(vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static double dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double length(vec3 a) { return sqrt(dot(a, a)); }

static vec3 cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

static vec3 position(const mesh *m, long index)   /* 1-based */
{
    const double *p = m->positions + 3 * (index - 1);
    return v3(p[0], p[1], p[2]);
}

static vec3 normal(const mesh *m, long index)
{
    const double *n = m->normals + 3 * (index - 1);
    return v3(n[0], n[1], n[2]);
}

/* ---- the shapes, restated from the formulas at the top of gen-model.c ---- */

typedef enum { SPHERE, BUMPY_SPHERE, TORUS_KNOT, GRID, CUBE } shape;
static const char *const SHAPE_NAMES[] = {"sphere", "bumpy-sphere", "torus-knot", "grid", "cube"};

typedef struct {
    long triangles, positions, normals, uvs;
} counts;

static counts counts_of(shape s, long k)
{
    switch (s) {
    case SPHERE:
    case BUMPY_SPHERE:
        return (counts){4 * k * (k - 1), 2 * k * (k - 1) + 2, 2 * k * (k - 1) + 2,
                        (2 * k + 1) * (k - 1) + 4 * k};
    case TORUS_KNOT:
        return (counts){16 * k * k, 8 * k * k, 8 * k * k, (8 * k + 1) * (k + 1)};
    case GRID:
        return (counts){2 * k * k, (k + 1) * (k + 1), 1, (k + 1) * (k + 1)};
    default:
        return (counts){12, 8, 6, 4};
    }
}

static const double BUMP = 0.15;

/* The bumpy sphere's surface point at (theta, phi), phi0 = 0. */
static vec3 bumpy_point(double theta, double phi)
{
    double s = sin(theta);
    double r = 1.0 + BUMP * s * s * s * s * sin(7.0 * theta) * sin(5.0 * phi);
    return v3(r * s * cos(phi), r * s * sin(phi), r * cos(theta));
}

static const double KNOT_R = 1.0, KNOT_A = 0.45, KNOT_RHO = 0.3;

static vec3 knot_centre(double t)
{
    double radius = KNOT_R + KNOT_A * cos(3.0 * t);
    return v3(radius * cos(2.0 * t), radius * sin(2.0 * t), KNOT_A * sin(3.0 * t));
}

/* ---- checks --------------------------------------------------------------------------- */

typedef struct {
    shape shape;
    long k;
    bool normals, uvs;
} expectation;

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static bool contains(const uint64_t *sorted, long count, uint64_t key)
{
    return bsearch(&key, sorted, (size_t)count, sizeof key, compare_u64) != NULL;
}

/* (a) the counts and the corner form; (b) the indices. */
static void check_counts_and_indices(const mesh *m, const expectation *e)
{
    counts expected = counts_of(e->shape, e->k);
    assert_int_equal(m->face_count, expected.triangles);
    assert_int_equal(m->positions_count, expected.positions);
    assert_int_equal(m->normals_count, e->normals ? expected.normals : 0);
    assert_int_equal(m->uvs_count, e->uvs ? expected.uvs : 0);
    assert_true(m->face_normals == e->normals);
    assert_true(m->face_uvs == e->uvs);

    char *used = calloc((size_t)m->positions_count + 1, 1);
    assert_non_null(used);
    for (long f = 0; f < m->face_count; f++) {
        for (int corner = 0; corner < 3; corner++) {
            long p = m->faces[f][corner][0], t = m->faces[f][corner][1],
                 n = m->faces[f][corner][2];
            if (p < 1 || p > m->positions_count)
                fail_msg("face %ld: position %ld out of 1..%ld", f + 1, p, m->positions_count);
            if (e->uvs && (t < 1 || t > m->uvs_count))
                fail_msg("face %ld: texture coordinate %ld out of 1..%ld", f + 1, t, m->uvs_count);
            if (e->normals && (n < 1 || n > m->normals_count))
                fail_msg("face %ld: normal %ld out of 1..%ld", f + 1, n, m->normals_count);
            used[p] = 1;
        }
        /* three different positions: no degenerate triangle, poles included */
        long a = m->faces[f][0][0], b = m->faces[f][1][0], c = m->faces[f][2][0];
        if (a == b || b == c || a == c)
            fail_msg("face %ld repeats a position", f + 1);
    }
    for (long p = 1; p <= m->positions_count; p++)
        if (!used[p])
            fail_msg("position %ld is in no face", p);
    free(used);

    /* Texture coordinates lie in [0, 1] (the knot's u in [0, 8]), and no
     * face spans more than one parameter step, 1/k, in u or v (1.2/k for
     * the jittered grid): a face across the sphere's or the knot's seam
     * that took u = 0 on one side and u = 1 on the other would span the
     * whole texture. */
    double top = e->shape == TORUS_KNOT ? 8.0 : 1.0;
    for (long t = 0; t < 2 * m->uvs_count; t++)
        if (!(m->uvs[t] >= 0.0 && m->uvs[t] <= top))
            fail_msg("texture coordinate %ld out of range: %g", t / 2 + 1, m->uvs[t]);
    double step = e->shape == CUBE ? 1.0 : 1.2 / (double)e->k;
    for (long f = 0; e->uvs && f < m->face_count; f++) {
        for (int axis = 0; axis < 2; axis++) {
            double low = INFINITY, high = -INFINITY;
            for (int corner = 0; corner < 3; corner++) {
                double value = m->uvs[2 * (m->faces[f][corner][1] - 1) + axis];
                low = fmin(low, value);
                high = fmax(high, value);
            }
            if (high - low > step + 1e-6)
                fail_msg("face %ld spans %g in %c, more than a step (%g)", f + 1, high - low,
                         axis ? 'v' : 'u', step);
        }
    }
}

/* The geometric normal of face f, (b - a) x (c - a), unnormalised. */
static vec3 face_normal(const mesh *m, long f)
{
    vec3 a = position(m, m->faces[f][0][0]);
    return cross(sub(position(m, m->faces[f][1][0]), a), sub(position(m, m->faces[f][2][0]), a));
}

/* (c) normals: unit, on the side of each face its winding says, and the
 * shape's own exact normal. */
static void check_normals(const mesh *m, const expectation *e)
{
    /* Six decimals put each coordinate within 5e-7, so |n| within about
     * 1e-6 of 1; 1e-5 leaves room and still fails any unnormalised normal. */
    for (long n = 1; n <= m->normals_count; n++)
        assert_near(length(normal(m, n)), 1.0, 1e-5);

    for (long f = 0; f < m->face_count; f++) {
        vec3 g = face_normal(m, f);
        double area2 = length(g);
        if (!(area2 > 1e-12))
            fail_msg("face %ld has no area (|(b-a)x(c-a)| = %g)", f + 1, area2);
        for (int c = 0; c < 3; c++) {
            long p = m->faces[f][c][0], ni = m->faces[f][c][2];
            vec3 pos = position(m, p), n = normal(m, ni);
            /* Smooth normals lean off a face by up to about the angle the
             * face spans (60 degrees on the knot's triangular tube at
             * k = 3), but never to its other side. */
            if (!(dot(n, g) > 0.0))
                fail_msg("face %ld corner %d: normal (%g %g %g) against the face's (%g %g %g)",
                         f + 1, c, n.x, n.y, n.z, g.x / area2, g.y / area2, g.z / area2);
            switch (e->shape) {
            case SPHERE:
                /* exact: the unit sphere's normal is the position */
                assert_near(length(sub(n, pos)), 0.0, 1e-5);
                assert_true(dot(n, pos) > 0.0);
                break;
            case BUMPY_SPHERE: {
                assert_true(dot(n, pos) > 0.0);
                /* Against P_theta x P_phi by central differences of the
                 * surface (step 1e-5: truncation ~1e-10, rounding ~1e-11);
                 * theta and phi come from the printed position, off by
                 * ~1e-6, which moves the normal by ~1e-5 where the bumps
                 * curve most.  At a pole the parametrisation is singular
                 * and the normal must be the axis. */
                double r = length(pos);
                double theta = acos(pos.z / r), phi = atan2(pos.y, pos.x);
                vec3 expected;
                if (sin(theta) < 1e-3) {
                    expected = v3(0, 0, pos.z > 0 ? 1 : -1);
                } else {
                    const double h = 1e-5;
                    vec3 d_theta = sub(bumpy_point(theta + h, phi), bumpy_point(theta - h, phi));
                    vec3 d_phi = sub(bumpy_point(theta, phi + h), bumpy_point(theta, phi - h));
                    vec3 x = cross(d_theta, d_phi);
                    expected = scale(x, 1.0 / length(x));
                }
                if (length(sub(n, expected)) > 1e-4)
                    fail_msg("bumpy sphere at theta %.6f phi %.6f: normal (%.6f %.6f %.6f), "
                             "expected (%.6f %.6f %.6f)", theta, phi, n.x, n.y, n.z,
                             expected.x, expected.y, expected.z);
                break;
            }
            case TORUS_KNOT: {
                /* pos - rho n must lie on the centre line: its azimuth is
                 * 2t (mod 2 pi), so t is half of it or that plus pi.  An
                 * inward normal puts it 2 rho = 0.6 away. */
                vec3 c3 = sub(pos, scale(n, KNOT_RHO));
                double t = 0.5 * atan2(c3.y, c3.x);
                double miss = fmin(length(sub(c3, knot_centre(t))),
                                   length(sub(c3, knot_centre(t + PI))));
                if (miss > 1e-5)
                    fail_msg("knot vertex %ld: position - rho normal is %g off the centre line", p,
                             miss);
                break;
            }
            case GRID:
                assert_true(n.x == 0.0 && n.y == 0.0 && n.z == 1.0);
                break;
            case CUBE: {
                /* exactly the face's normal, and the corner on that face */
                vec3 unit = scale(g, 1.0 / area2);
                assert_near(length(sub(n, unit)), 0.0, 1e-12);
                assert_near(dot(pos, n), 1.0, 1e-12);
                break;
            }
            }
        }
    }
}

/* (d) edges, and Euler's formula; returns nothing, fails on the first
 * broken edge. */
static void check_edges(const mesh *m, const expectation *e)
{
    long count = 3 * m->face_count;
    uint64_t *edges = malloc(sizeof(uint64_t) * (size_t)count);
    assert_non_null(edges);
    for (long f = 0; f < m->face_count; f++)
        for (int c = 0; c < 3; c++)
            edges[3 * f + c] = (uint64_t)m->faces[f][c][0] << 32 | (uint64_t)m->faces[f][(c + 1) % 3][0];
    qsort(edges, (size_t)count, sizeof *edges, compare_u64);
    long border = 0, undirected = 0;
    for (long i = 0; i < count; i++) {
        if (i > 0 && edges[i] == edges[i - 1])
            fail_msg("edge %llu -> %llu is in two faces the same way: winding flips there",
                     (unsigned long long)(edges[i] >> 32), (unsigned long long)(edges[i] & 0xFFFFFFFF));
        uint64_t from = edges[i] >> 32, to = edges[i] & 0xFFFFFFFF;
        if (contains(edges, count, to << 32 | from)) {
            if (from < to)
                undirected++;
            continue;
        }
        if (e->shape != GRID)
            fail_msg("edge %llu -> %llu has no opposite: a hole", (unsigned long long)from,
                     (unsigned long long)to);
        /* the grid: an open edge must lie on the square's border */
        vec3 a = position(m, (long)from), b = position(m, (long)to);
        bool on_border = (fabs(a.x) == 1.0 && a.x == b.x) || (fabs(a.y) == 1.0 && a.y == b.y);
        if (!on_border)
            fail_msg("grid edge (%g %g) -> (%g %g) is open inside the square", a.x, a.y, b.x, b.y);
        border++;
        undirected++;
    }
    free(edges);
    long euler = m->positions_count - undirected + m->face_count;
    switch (e->shape) {
    case TORUS_KNOT:
        assert_int_equal(euler, 0);   /* a torus: genus 1 */
        break;
    case GRID:
        assert_int_equal(border, 4 * e->k);
        assert_int_equal(euler, 1);   /* a disc */
        break;
    default:
        assert_int_equal(euler, 2);   /* a sphere: genus 0 */
        break;
    }
}

static double signed_volume(const mesh *m)
{
    double sum = 0.0;
    for (long f = 0; f < m->face_count; f++) {
        vec3 a = position(m, m->faces[f][0][0]), b = position(m, m->faces[f][1][0]),
             c = position(m, m->faces[f][2][0]);
        sum += dot(a, cross(b, c));
    }
    return sum / 6.0;
}

/* The knot's centre-line length, integral of |C'(t)| over [0, 2 pi], by
 * the midpoint rule on 100,000 steps of the closed-form C' (periodic and
 * smooth, so this is exact to rounding). */
static double knot_length(void)
{
    const int steps = 100000;
    double sum = 0.0;
    for (int i = 0; i < steps; i++) {
        double t = 2.0 * PI * (i + 0.5) / steps;
        double radius = KNOT_R + KNOT_A * cos(3.0 * t);
        vec3 velocity = v3(-3.0 * KNOT_A * sin(3.0 * t) * cos(2.0 * t) - 2.0 * radius * sin(2.0 * t),
                           -3.0 * KNOT_A * sin(3.0 * t) * sin(2.0 * t) + 2.0 * radius * cos(2.0 * t),
                           3.0 * KNOT_A * cos(3.0 * t));
        sum += length(velocity);
    }
    return sum * 2.0 * PI / steps;
}

/* pi rho^2 L times the share of the disc that the inscribed k-gon covers. */
static double knot_volume(long k)
{
    double polygon = (double)k / 2.0 * sin(2.0 * PI / (double)k) / PI;
    return PI * KNOT_RHO * KNOT_RHO * knot_length() * polygon;
}

/* (e) the volume. */
static void check_volume(const mesh *m, const expectation *e)
{
    double volume = signed_volume(m);
    double sphere = 4.0 / 3.0 * PI;
    double step = PI / (double)e->k;   /* the spheres' angular step */
    switch (e->shape) {
    case SPHERE: {
        /* k = 2 is the octahedron with vertices at distance 1: 8 tetrahedra
         * (1/6 each) from the centre, 4/3 exactly. */
        if (e->k == 2) {
            assert_near(volume, 4.0 / 3.0, 1e-12);
            break;
        }
        /* The mesh is inscribed, so its volume is less than the ball's.
         * Between a flat a x b rectangle and the sphere over it lies
         * (a^2 + b^2) / 12 of volume per unit of area (the integral of
         * (rc^2 - r^2)/2 over the rectangle, rc its circumradius); here
         * a = step, b = step sin(theta), and the mean of 1 + sin^2 over the
         * sphere is 5/3: the deficit is about 4 pi 5 step^2 / 36, that is
         * 5 step^2 / 12 of the volume (6.4% for k = 8; the mesh has 6.3%).
         * Terms in step^4 are left out: within a tenth of it.  A wrong
         * radius, a missing band or a flipped face is far outside. */
        double deficit = (sphere - volume) / sphere, expected = 5.0 * step * step / 12.0;
        if (!(volume > 0.0) || fabs(deficit - expected) > 0.1 * expected)
            fail_msg("sphere volume %.6f: deficit %.4f of 4/3 pi, expected about %.4f", volume,
                     deficit, expected);
        break;
    }
    case BUMPY_SPHERE: {
        /* V = (1/3) int r^3 dOmega with r = 1 + f: the integrals of f and
         * f^3 vanish (odd powers of sin 5 phi over whole periods), so
         * V = 4 pi / 3 + int f^2 dOmega
         *   = 4 pi / 3 + 0.15^2 pi int_0^pi sin^9(theta) sin^2(7 theta) dtheta
         * (Simpson's rule below, exact to rounding at this smoothness).
         * The deficit of the inscribed mesh is about the sphere's,
         * 5 step^2 / 12 (0.71% for k = 24), more where the bumps curve
         * (the mesh has 0.97%): it must lie between 0 and 1.5 times that. */
        const int n = 2000;
        double integral = 0.0;
        for (int i = 0; i <= n; i++) {
            double theta = PI * i / n, s = sin(theta);
            double value = pow(s, 9) * sin(7.0 * theta) * sin(7.0 * theta);
            integral += value * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
        }
        integral *= PI / n / 3.0;
        double solid = sphere + BUMP * BUMP * PI * integral;
        double deficit = (solid - volume) / solid, expected = 5.0 * step * step / 12.0;
        if (!(deficit > 0.0 && deficit < 1.5 * expected))
            fail_msg("bumpy sphere volume %.6f, solid %.6f: deficit %.4f, expected 0 to %.4f",
                     volume, solid, deficit, 1.5 * expected);
        break;
    }
    case TORUS_KNOT: {
        /* A tube of radius rho around a curve of length L encloses
         * pi rho^2 L (Pappus/Guldin for tubes, true while rho * curvature
         * < 1).  The mesh's cross-section is the inscribed k-gon, of area
         * rho^2 (k/2) sin(2 pi/k), 90% of the disc for k = 8.  What is
         * left is of order 1/k^2: the frame turns about the centre line
         * from one ring to the next, so the quads between rings are
         * twisted, and cut with one diagonal they bulge out (measured:
         * +0.54/k^2, +16% at k = 3, +1% at k = 8).  Within 2/k^2 here;
         * test_knot_volume_converges checks the limit itself. */
        double k = (double)e->k;
        double expected = knot_volume(e->k);
        if (!(fabs(volume - expected) < 2.0 / (k * k) * expected))
            fail_msg("torus knot volume %.6f, expected %.6f within %.1f%%", volume, expected,
                     200.0 / (k * k));
        break;
    }
    case CUBE:
        assert_near(volume, 8.0, 1e-12);   /* exact: edge 2 */
        break;
    case GRID: {
        /* Flat, so no volume: each triangle counter-clockwise seen from +z
         * (positive area in x, y), and together exactly the 2 x 2 square. */
        double total = 0.0;
        for (long f = 0; f < m->face_count; f++) {
            vec3 g = face_normal(m, f);
            if (!(g.z > 0.0) || g.x != 0.0 || g.y != 0.0)
                fail_msg("grid face %ld: normal (%g %g %g) is not +z", f + 1, g.x, g.y, g.z);
            total += g.z / 2.0;
        }
        assert_near(total, 4.0, 1e-9);
        for (long p = 1; p <= m->positions_count; p++)
            assert_true(position(m, p).z == 0.0 && fabs(position(m, p).x) <= 1.0 &&
                        fabs(position(m, p).y) <= 1.0);
        break;
    }
    }
}

/* Runs gen-model with --shape SHAPE --triangles N [--no-normals]
 * [--no-uvs] [--seed S] -o m.obj in a fresh sandbox, checks that it
 * reported the expected count and left only m.obj, and reads m.obj. */
static mesh generate(const char *shape_name, const char *triangles, bool normals, bool uvs,
                     const char *seed, const expectation *e)
{
    sandbox box;
    sandbox_create(&box);
    const char *arguments[16];
    int n = 0;
    arguments[n++] = "--shape";
    arguments[n++] = shape_name;
    arguments[n++] = "--triangles";
    arguments[n++] = triangles;
    if (!normals)
        arguments[n++] = "--no-normals";
    if (!uvs)
        arguments[n++] = "--no-uvs";
    if (seed != NULL) {
        arguments[n++] = "--seed";
        arguments[n++] = seed;
    }
    arguments[n++] = "-o";
    arguments[n++] = "m.obj";
    arguments[n] = NULL;
    run_result result = run_in(&box, arguments);
    long long reported = assert_written(&result, "m.obj");
    assert_int_equal(reported, counts_of(e->shape, e->k).triangles);
    char listing[1024];
    list_work(&box, listing, sizeof listing);
    assert_string_equal(listing, "m.obj\n");   /* no temporary file left */

    char *data = read_work_file(&box, "m.obj");
    mesh m = parse_obj(data);
    free(data);
    run_result_free(&result);
    sandbox_destroy(&box);
    return m;
}

/* generate(), then every check. */
static void generate_and_check(const char *shape_name, const char *triangles, bool normals,
                               bool uvs, const char *seed, const expectation *e)
{
    mesh m = generate(shape_name, triangles, normals, uvs, seed, e);
    /* topology, then shape, then normals: a mesh turned inside out fails
     * on its volume even when it has no normals */
    check_counts_and_indices(&m, e);
    check_edges(&m, e);
    check_volume(&m, e);
    if (normals)
        check_normals(&m, e);
    mesh_free(&m);
}

/* ---- (a) to (e): every shape, with and without normals and uvs ---- */

typedef struct {
    shape shape;
    const char *triangles;   /* --triangles */
    long k;                  /* the resolution it must give, by hand */
    const char *why;
} geometry_case;

static const geometry_case cases[] = {
    {SPHERE, "250", 8, "4k(k-1): k = 8 gives 224 <= 250, k = 9 gives 288"},
    {SPHERE, "224", 8, "exactly 4*8*7"},
    {SPHERE, "223", 7, "one less: k = 7, 4*7*6 = 168"},
    {SPHERE, "1", 2, "below the smallest: k = 2, the octahedron, 8 triangles"},
    {BUMPY_SPHERE, "2300", 24, "4*24*23 = 2208 <= 2300 < 4*25*24 = 2400"},
    {TORUS_KNOT, "1100", 8, "16k^2: 16*64 = 1024 <= 1100 < 16*81 = 1296"},
    {TORUS_KNOT, "1", 3, "below the smallest: k = 3, 144 triangles"},
    {GRID, "100", 7, "2k^2: 98 <= 100 < 128"},
    {GRID, "1", 1, "below the smallest: k = 1, 2 triangles"},
    {CUBE, "1000", 1, "always 12"},
    {CUBE, "1", 1, "always 12"},
};
enum { CASE_COUNT = sizeof cases / sizeof cases[0] };

static void test_geometry(void **state)
{
    const geometry_case *c = *state;
    for (int form = 0; form < 4; form++) {
        bool normals = !(form & 1), uvs = !(form & 2);
        expectation e = {c->shape, c->k, normals, uvs};
        generate_and_check(SHAPE_NAMES[c->shape], c->triangles, normals, uvs, NULL, &e);
    }
}

/* The knot's volume against pi rho^2 L without the 2/k^2 allowance: at
 * k = 8 and 16 the error must fall by about 4 (second order), and
 * Richardson's extrapolation (4 V16 - V8) / 3 must land within 0.2% of the
 * k-gon tube's volume (it lands within 0.04%).  A wrong rho, a or
 * length moves the limit; a first-order error breaks the ratio. */
static double knot_mesh_ratio(long k)
{
    char triangles[32];
    snprintf(triangles, sizeof triangles, "%ld", 16 * k * k);
    expectation e = {TORUS_KNOT, k, false, false};
    mesh m = generate("torus-knot", triangles, false, false, NULL, &e);
    double ratio = signed_volume(&m) / knot_volume(k);
    mesh_free(&m);
    return ratio;
}

static void test_knot_volume_converges(void **state)
{
    (void)state;
    double r8 = knot_mesh_ratio(8), r16 = knot_mesh_ratio(16);
    double order = (r8 - 1.0) / (r16 - 1.0), limit = (4.0 * r16 - r8) / 3.0;
    if (!(order > 3.0 && order < 5.0) || !(fabs(limit - 1.0) < 0.002))
        fail_msg("knot volume / (pi rho^2 L k-gon share): %.5f at k = 8, %.5f at k = 16: "
                 "error ratio %.2f (expected ~4), limit %.5f (expected 1)",
                 r8, r16, order, limit);
}

/* With a seed the grid's inner vertices move and the bumpy sphere's
 * bumps turn: still counter-clockwise, the same square, the same volume
 * (the bumps' phase does not change the integral).  The grid's vertices
 * must stay within 0.1 of a square of the lattice (the bound that keeps
 * its triangles counter-clockwise), the border on it, and the inside
 * really move. */
static void test_seeded(void **state)
{
    (void)state;
    expectation grid = {GRID, 7, true, true};
    generate_and_check("grid", "100", true, true, "12345", &grid);
    mesh m = generate("grid", "100", true, true, "12345", &grid);
    double largest = 0.0;
    for (long j = 0; j <= 7; j++) {
        for (long i = 0; i <= 7; i++) {
            vec3 p = position(&m, 1 + j * 8 + i);
            /* in squares, from the lattice point (i, j) */
            double dx = (p.x + 1.0) * 3.5 - (double)i, dy = (p.y + 1.0) * 3.5 - (double)j;
            bool border = i == 0 || j == 0 || i == 7 || j == 7;
            double off = fmax(fabs(dx), fabs(dy));
            if (border ? off > 1e-5 : off > 0.1 + 1e-5)
                fail_msg("grid vertex (%ld, %ld) is %.4f of a square off the lattice", i, j, off);
            if (!border)
                largest = fmax(largest, off);
        }
    }
    mesh_free(&m);
    if (!(largest > 0.05))
        fail_msg("the seed moved no inner grid vertex by more than %.4f of a square", largest);

    /* the finite-difference normals assume phi0 = 0: no normals here,
     * the edges and the volume still hold */
    expectation bumpy = {BUMPY_SPHERE, 24, false, true};
    generate_and_check("bumpy-sphere", "2300", false, true, "12345", &bumpy);
}

/* The files are the same byte for byte, or with comment lines left out
 * (the header comment records the seed, so that alone must not count as
 * the seed changing the shape). */
static char *without_comments(char *text)
{
    char *to = text;
    for (const char *line = text; *line != '\0';) {
        const char *end = strchr(line, '\n');
        size_t length = end ? (size_t)(end - line) + 1 : strlen(line);
        if (line[0] != '#') {
            memmove(to, line, length);
            to += length;
        }
        line += length;
    }
    *to = '\0';
    return text;
}

static bool same_files(const char *a, const char *b, bool comments)
{
    size_t la, lb;
    char *x = read_file(a, &la), *y = read_file(b, &lb);
    assert_non_null(x);
    assert_non_null(y);
    bool same = comments ? la == lb && memcmp(x, y, la) == 0
                         : strcmp(without_comments(x), without_comments(y)) == 0;
    free(x);
    free(y);
    return same;
}

/* ---- (f) determinism ---- */

static void test_same_bytes(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    char a[400], b[400];
    snprintf(a, sizeof a, "%s/a.obj", box.work);
    snprintf(b, sizeof b, "%s/b.obj", box.work);
    for (int s = 0; s < 5; s++) {
        for (int seeded = 0; seeded < 2; seeded++) {
            const char *seed = seeded ? "7" : "0";
            run_result r1 = run_in(&box, ARGS("--shape", SHAPE_NAMES[s], "--triangles", "3000",
                                              "--seed", seed, "-o", "a.obj"));
            assert_written(&r1, "a.obj");
            run_result r2 = run_in(&box, ARGS("--shape", SHAPE_NAMES[s], "--triangles", "3000",
                                              "--seed", seed, "-o", "b.obj"));
            assert_written(&r2, "b.obj");
            if (!same_files(a, b, true))
                fail_msg("%s --seed %s: two runs differ", SHAPE_NAMES[s], seed);
            run_result_free(&r1);
            run_result_free(&r2);
        }
        /* The seed must change the grid and the bumpy sphere (else
         * --seed is a no-op that the checks above would not notice), and
         * only them. */
        run_result r3 = run_in(&box, ARGS("--shape", SHAPE_NAMES[s], "--triangles", "3000",
                                          "-o", "b.obj"));
        assert_written(&r3, "b.obj");
        bool seed_used = s == BUMPY_SPHERE || s == GRID;
        if (same_files(a, b, false) == seed_used)
            fail_msg("%s: --seed 7 %s the file", SHAPE_NAMES[s],
                     seed_used ? "does not change" : "changes");
        run_result_free(&r3);
    }
    sandbox_destroy(&box);
}

/* The cube, byte for byte, worked out by hand: corner 1 + x + 2y + 4z
 * (bit 0 is -1), normals +x -x +y -y +z -z, texture coordinates of the
 * square; each face's corners counter-clockwise seen from outside, e.g.
 * +x: 2 (1,-1,-1), 4 (1,1,-1), 8 (1,1,1), 6 (1,-1,1), as (0,2,0) x (0,2,2)
 * = (4,0,0) points along +x. */
static void test_cube_by_hand(void **state)
{
    (void)state;
    static const char expected[] =
        "# gen-model --shape cube --triangles 12 --no-uvs\n"
        "# k = 1: 12 triangles, 8 positions\n"
        "o cube\n"
        "v -1.000000 -1.000000 -1.000000\n"
        "v 1.000000 -1.000000 -1.000000\n"
        "v -1.000000 1.000000 -1.000000\n"
        "v 1.000000 1.000000 -1.000000\n"
        "v -1.000000 -1.000000 1.000000\n"
        "v 1.000000 -1.000000 1.000000\n"
        "v -1.000000 1.000000 1.000000\n"
        "v 1.000000 1.000000 1.000000\n"
        "vn 1.000000 0.000000 0.000000\n"
        "vn -1.000000 0.000000 0.000000\n"
        "vn 0.000000 1.000000 0.000000\n"
        "vn 0.000000 -1.000000 0.000000\n"
        "vn 0.000000 0.000000 1.000000\n"
        "vn 0.000000 0.000000 -1.000000\n"
        "f 2//1 4//1 8//1\n"
        "f 2//1 8//1 6//1\n"
        "f 1//2 5//2 7//2\n"
        "f 1//2 7//2 3//2\n"
        "f 3//3 7//3 8//3\n"
        "f 3//3 8//3 4//3\n"
        "f 1//4 2//4 6//4\n"
        "f 1//4 6//4 5//4\n"
        "f 5//5 6//5 8//5\n"
        "f 5//5 8//5 7//5\n"
        "f 1//6 3//6 4//6\n"
        "f 1//6 4//6 2//6\n";
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--shape", "cube", "--no-uvs", "-o", "cube.obj"));
    assert_int_equal(assert_written(&result, "cube.obj"), 12);
    char *data = read_work_file(&box, "cube.obj");
    assert_string_equal(data, expected);
    free(data);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* The octahedron (the sphere at k = 2) by hand too: its sines are exact
 * (quarter turns), so every digit is known without computing. */
static void test_octahedron_by_hand(void **state)
{
    (void)state;
    static const char expected[] =
        "# gen-model --shape sphere --triangles 8 --no-normals --no-uvs\n"
        "# k = 2: 8 triangles, 6 positions\n"
        "o sphere\n"
        "v 0.000000 0.000000 1.000000\n"
        "v 1.000000 0.000000 0.000000\n"
        "v 0.000000 1.000000 0.000000\n"
        "v -1.000000 0.000000 0.000000\n"
        "v 0.000000 -1.000000 0.000000\n"
        "v 0.000000 0.000000 -1.000000\n"
        "f 1 2 3\n"
        "f 1 3 4\n"
        "f 1 4 5\n"
        "f 1 5 2\n"
        "f 2 6 3\n"
        "f 3 6 4\n"
        "f 4 6 5\n"
        "f 5 6 2\n";
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--shape", "sphere", "--triangles", "10",
                                          "--no-normals", "--no-uvs", "-o", "o.obj"));
    assert_int_equal(assert_written(&result, "o.obj"), 8);
    char *data = read_work_file(&box, "o.obj");
    assert_string_equal(data, expected);
    free(data);
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* ---- (g) refused arguments ---- */

typedef struct {
    const char *name;
    const char *arguments[8];
    const char *needle;   /* the flag the line must name */
} refused_case;

static const refused_case refused[] = {
    {"no-shape", {"-o", "m.obj"}, "--shape"},
    {"unknown-shape", {"--shape", "teapot", "-o", "m.obj"}, "--shape"},
    {"shape-without-value", {"-o", "m.obj", "--shape"}, "--shape"},
    {"no-output", {"--shape", "cube"}, "-o"},
    {"empty-output", {"--shape", "cube", "-o", ""}, "-o"},
    {"output-without-value", {"--shape", "cube", "-o"}, "-o"},
    {"zero-triangles", {"--shape", "grid", "--triangles", "0", "-o", "m.obj"}, "--triangles"},
    {"negative-triangles", {"--shape", "grid", "--triangles", "-5", "-o", "m.obj"}, "--triangles"},
    {"too-many-triangles", {"--shape", "grid", "--triangles", "20000001", "-o", "m.obj"},
     "--triangles"},
    {"triangles-not-a-number", {"--shape", "grid", "--triangles", "12k", "-o", "m.obj"},
     "--triangles"},
    {"triangles-float", {"--shape", "grid", "--triangles", "1e6", "-o", "m.obj"}, "--triangles"},
    {"huge-triangles", {"--shape", "grid", "--triangles", "99999999999999999999999", "-o",
                        "m.obj"}, "--triangles"},
    {"seed-negative", {"--shape", "grid", "--seed", "-1", "-o", "m.obj"}, "--seed"},
    {"seed-too-big", {"--shape", "grid", "--seed", "4294967296", "-o", "m.obj"}, "--seed"},
    {"seed-not-a-number", {"--shape", "grid", "--seed", "abc", "-o", "m.obj"}, "--seed"},
    {"unknown-flag", {"--shape", "grid", "--frobnicate", "-o", "m.obj"}, "--frobnicate"},
    {"flag-with-value", {"--shape", "grid", "--no-uvs=1", "-o", "m.obj"}, "--no-uvs"},
    {"stray-argument", {"--shape", "grid", "-o", "m.obj", "extra"}, "extra"},
};
enum { REFUSED_COUNT = sizeof refused / sizeof refused[0] };

static void test_refused(void **state)
{
    const refused_case *c = *state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, c->arguments);
    if (result.status != 2)
        fail_msg("exit status %d, expected 2; stderr: %s", result.status, result.err);
    size_t length = strlen(result.err);
    if (length < 2 || strchr(result.err, '\n') != result.err + length - 1)
        fail_msg("stderr is not exactly one line: '%s'", result.err);
    if (strncmp(result.err, "gen-model: ", 11) != 0)
        fail_msg("stderr does not start with 'gen-model: ': %s", result.err);
    if (strstr(result.err, c->needle) == NULL)
        fail_msg("stderr does not name '%s': %s", c->needle, result.err);
    assert_string_equal(result.out, "");
    char listing[1024];
    list_work(&box, listing, sizeof listing);
    assert_string_equal(listing, "");   /* no file at all */
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* A file that cannot be written: exit 1, one line, nothing left. */
static void test_unwritable(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--shape", "cube", "-o", "missing/m.obj"));
    assert_int_equal(result.status, 1);
    size_t length = strlen(result.err);
    assert_true(length > 0 && strchr(result.err, '\n') == result.err + length - 1);
    if (strstr(result.err, "missing/m.obj") == NULL)
        fail_msg("stderr does not name the file: %s", result.err);
    char listing[1024];
    list_work(&box, listing, sizeof listing);
    assert_string_equal(listing, "");
    run_result_free(&result);
    sandbox_destroy(&box);
}

static void test_help(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--help"));
    assert_int_equal(result.status, 0);
    assert_string_equal(result.err, "");
    for (int s = 0; s < 5; s++)
        assert_non_null(strstr(result.out, SHAPE_NAMES[s]));
    static const char *const flags[] = {"--shape", "--triangles", "--no-normals", "--no-uvs",
                                        "--seed", "-o"};
    for (size_t f = 0; f < sizeof flags / sizeof *flags; f++)
        assert_non_null(strstr(result.out, flags[f]));
    char listing[1024];
    list_work(&box, listing, sizeof listing);
    assert_string_equal(listing, "");
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* Ctrl-C while the file is being written (its temporary exists): the
 * program dies of the signal and leaves neither the OBJ nor the
 * temporary.  20,000,000 triangles take seconds to write, so the signal
 * lands mid-write; it is killed long before the file is large. */
static void test_interrupted(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    double start = now_seconds();
    pid_t child = start_in(&box, ARGS("--shape", "sphere", "--triangles", "20000000", "-o",
                                      "big.obj"));
    char listing[1024];
    for (;;) {
        list_work(&box, listing, sizeof listing);
        if (strncmp(listing, "big.obj.tmp-", 12) == 0)
            break;
        if (strcmp(listing, "big.obj\n") == 0 || now_seconds() - start > 60.0) {
            kill(child, SIGKILL);
            fail_msg("no temporary file seen while writing (listing: '%s')", listing);
        }
        nanosleep(&(struct timespec){0, 2000000}, NULL);
    }
    nanosleep(&(struct timespec){0, 50000000}, NULL);
    assert_int_equal(kill(child, SIGINT), 0);
    run_result result = finish(&box, child, start);
    assert_int_equal(result.status, 128 + SIGINT);
    list_work(&box, listing, sizeof listing);
    assert_string_equal(listing, "");
    run_result_free(&result);
    sandbox_destroy(&box);
}

/* One large file, for the count and the time only: the grid of 1,000,000
 * triangles at most, k = 707 (2 * 707^2 = 999,698 <= 10^6 < 2 * 708^2). */
static void test_million(void **state)
{
    (void)state;
    sandbox box;
    sandbox_create(&box);
    run_result result = run_in(&box, ARGS("--shape", "grid", "--triangles", "1000000", "-o",
                                          "grid.obj"));
    assert_int_equal(assert_written(&result, "grid.obj"), 999698);
    char path[400];
    snprintf(path, sizeof path, "%s/grid.obj", box.work);
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    long faces = 0, vertices = 0;
    char line[256];
    while (fgets(line, sizeof line, file) != NULL) {
        faces += line[0] == 'f';
        vertices += line[0] == 'v' && line[1] == ' ';
    }
    fclose(file);
    assert_int_equal(faces, 999698);
    assert_int_equal(vertices, 708 * 708);
    print_message("gen-model: 999,698 triangles (grid) in %.2f s\n", result.seconds);
    /* Generous: it takes well under a second on a plain build; a
     * sanitizer build or a slow disk takes longer. */
    if (result.seconds > 60.0)
        fail_msg("1,000,000 triangles took %.1f s", result.seconds);
    run_result_free(&result);
    sandbox_destroy(&box);
}

int main(void)
{
    static const struct CMUnitTest fixed[] = {
        cmocka_unit_test(test_knot_volume_converges),
        cmocka_unit_test(test_seeded),
        cmocka_unit_test(test_same_bytes),
        cmocka_unit_test(test_cube_by_hand),
        cmocka_unit_test(test_octahedron_by_hand),
        cmocka_unit_test(test_unwritable),
        cmocka_unit_test(test_help),
        cmocka_unit_test(test_interrupted),
        cmocka_unit_test(test_million),
    };
    enum { FIXED = sizeof fixed / sizeof fixed[0] };
    static struct CMUnitTest tests[FIXED + CASE_COUNT + REFUSED_COUNT];
    static char names[CASE_COUNT][64];
    size_t count = 0;
    for (int i = 0; i < CASE_COUNT; i++) {
        snprintf(names[i], sizeof names[i], "geometry %s --triangles %s",
                 SHAPE_NAMES[cases[i].shape], cases[i].triangles);
        tests[count++] = (struct CMUnitTest){names[i], test_geometry, NULL, NULL,
                                             (void *)&cases[i]};
    }
    for (int i = 0; i < REFUSED_COUNT; i++)
        tests[count++] = (struct CMUnitTest){refused[i].name, test_refused, NULL, NULL,
                                             (void *)&refused[i]};
    for (size_t i = 0; i < FIXED; i++)
        tests[count++] = fixed[i];
    return _cmocka_run_group_tests("gen-model", tests, count, NULL, NULL);
}
