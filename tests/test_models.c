/*
 * test_models.c: the user's models (docs/SCENE.md, "Models"; issue 11,
 * items 7 and 8), against the contract, with the expected values worked out
 * by hand in the comments.
 *
 * Every input is written here, into a fresh temporary directory, by the
 * group's setup: small OBJ files with their .mtl, PLY and STL text, glTF
 * with its buffers and images as data URIs, tiny PNG textures (stb's
 * writer), random bytes, a directory and a FIFO under model names. The
 * only file taken from elsewhere is Debian's assimp-testmodels'
 * BoxTextured.glb (the test that reads it is skipped without it).
 *
 * Four groups of tests:
 *  - loading (io/model.h): parts in file order, colours, textures and
 *    their texels, bounds, and every refusal naming the file;
 *  - the lab's placement (lab/scene.h), on models made here by hand:
 *    normalisation, the model matrix, colour and texture precedence, and
 *    the order of a list of cubes and models;
 *  - scene files (app/options.h): model lines read, and written back;
 *  - the real luz-render ($LUZ_RENDER, set by tests/meson.build), run in
 *    the work directory as a user would: every bad input gives exit
 *    status 2, exactly one line naming the file (and FILE:LINE for a
 *    scene file) and no file left behind; and every view, --only, --filter
 *    and --interp draws the model, with the same bytes on 1 and 3 threads.
 *
 * A build without assimp (-Dmodels=disabled) skips the tests that read a
 * model file; the lab's tests need no file and always run.
 */
#define _XOPEN_SOURCE 700
#define _DEFAULT_SOURCE   /* syscall */

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>
#if defined(__x86_64__)
#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#endif

#include <stb_image.h>
#include <stb_image_write.h>

#include "file_support.h"
#include "test_support.h"
#include "lab_support.h"

#include "luz/luz.h"
#include "app/options.h"
#include "io/model.h"
#include "io/model_sandbox.h"
#include "lab/scene.h"

#define TOLERANCE 1e-5

#define assert_vec3_near(got, expected_x, expected_y, expected_z, tolerance)                  \
    do {                                                                                      \
        const luz_vec3 vec3_got_ = (got);                                                     \
        assert_near_at(vec3_got_.x, (expected_x), (tolerance), #got ".x", __FILE__, __LINE__); \
        assert_near_at(vec3_got_.y, (expected_y), (tolerance), #got ".y", __FILE__, __LINE__); \
        assert_near_at(vec3_got_.z, (expected_z), (tolerance), #got ".z", __FILE__, __LINE__); \
    } while (0)

static void assert_contains(const char *text, const char *needle)
{
    if (strstr(text, needle) == NULL) fail_msg("'%s' lacks '%s'", text, needle);
}

/* ---- files ----------------------------------------------------------------------------- */

/* The fixture: root/ holds the captured output of luz-render runs, and
 * work/ the inputs (and whatever a run makes). */
static char root_directory[256];
static char work_directory[300];

static void work_path(const char *name, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", work_directory, name);
}

static void write_bytes(const char *name, const void *data, size_t length)
{
    char path[1024];
    work_path(name, path, sizeof path);
    FILE *file = fopen(path, "wb");
    if (file == NULL) fail_msg("cannot write %s: %s", path, strerror(errno));
    assert_int_equal(fwrite(data, 1, length, file), length);
    assert_int_equal(fclose(file), 0);
}

static void write_text(const char *name, const char *text)
{
    write_bytes(name, text, strlen(text));
}

static void make_directory(const char *name)
{
    char path[1024];
    work_path(name, path, sizeof path);
    assert_int_equal(mkdir(path, 0755), 0);
}

/* A PNG of RGBA texels, row 0 first, written with stb_image_write. */
static void write_png(const char *name, int width, int height, const uint8_t *rgba)
{
    char path[1024];
    work_path(name, path, sizeof path);
    assert_int_not_equal(stbi_write_png(path, width, height, 4, rgba, width * 4), 0);
}

/* The PNG file's bytes, for a data URI and for a truncated copy. */
typedef struct byte_buffer {
    unsigned char *bytes;
    int length;
} byte_buffer;

static void append_bytes(void *context, void *data, int size)
{
    byte_buffer *buffer = context;
    unsigned char *grown = realloc(buffer->bytes, (size_t)buffer->length + (size_t)size);
    if (grown == NULL) abort();
    memcpy(grown + buffer->length, data, (size_t)size);
    buffer->bytes = grown;
    buffer->length += size;
}

static unsigned char *png_bytes(int width, int height, const uint8_t *rgba, int *length)
{
    byte_buffer buffer = {NULL, 0};
    assert_int_not_equal(
        stbi_write_png_to_func(append_bytes, &buffer, width, height, 4, rgba, width * 4), 0);
    *length = buffer.length;
    return buffer.bytes;
}

/* Base64 (RFC 4648, with padding), for glTF's data URIs. */
static char *base64(const unsigned char *data, size_t length)
{
    static const char digits[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *text = malloc(4 * ((length + 2) / 3) + 1), *out = text;
    assert_non_null(text);
    for (size_t i = 0; i < length; i += 3) {
        uint32_t group = (uint32_t)data[i] << 16;
        if (i + 1 < length) group |= (uint32_t)data[i + 1] << 8;
        if (i + 2 < length) group |= data[i + 2];
        *out++ = digits[group >> 18 & 63];
        *out++ = digits[group >> 12 & 63];
        *out++ = i + 1 < length ? digits[group >> 6 & 63] : '=';
        *out++ = i + 2 < length ? digits[group & 63] : '=';
    }
    *out = '\0';
    return text;
}

/* SCENE.md's generator, written here from its text (x ^= x << 13;
 * x ^= x >> 17; x ^= x << 5), for random bytes and the seed's colours. */
static uint32_t xorshift(uint32_t *x)
{
    *x ^= *x << 13;
    *x ^= *x >> 17;
    *x ^= *x << 5;
    return *x;
}

/* ---- the fixture's files ---------------------------------------------------------------- */

/* tex/a.png, 2x2: red, green / blue, white (row 0 first). */
static const uint8_t texture_a[16] = {255, 0, 0, 255, 0, 255, 0, 255,
                                      0, 0, 255, 255, 255, 255, 255, 255};
/* tex/b.png, 3x1. */
static const uint8_t texture_b[12] = {10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 255};

/* Two meshes, a quad (two triangles) and a triangle, each with its own
 * material; the .mtl defines them in the order the .obj uses them (one of
 * SCENE.md's steps, PreTransformVertices, orders the meshes by material,
 * and an OBJ's materials come in the .mtl's order). The second texture is
 * written as a Windows program writes it. */
static const char two_obj[] =
    "# two meshes\n"
    "mtllib two.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "v 2 0 -1\nv 3 0 -1\nv 3 2 -1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 1\n"
    "o first\nusemtl warm\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
    "o second\nusemtl cold\nf 5/1/1 6/2/1 7/3/1\n";
static const char two_mtl[] =
    "newmtl warm\nKd 0.75 0.5 0.25\nmap_Kd tex/a.png\n"
    "newmtl cold\nKd 0.125 0.25 1\nmap_Kd .\\tex\\b.png\n";

/* Two meshes whose materials name the same texture file. */
static const char shared_obj[] =
    "mtllib shared.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "vt 0 0\nvt 1 0\nvt 0 1\n"
    "o one\nusemtl s1\nf 1/1 2/2 3/3\n"
    "o two\nusemtl s2\nf 1/1 4/2 2/3\n";
static const char shared_mtl[] = "newmtl s1\nKd 1 0 0\nmap_Kd tex/a.png\n"
                                 "newmtl s2\nKd 0 1 0\nmap_Kd tex/a.png\n";

/* A material with a texture, on a mesh without texture coordinates. */
static const char nouv_obj[] = "mtllib nouv.mtl\n"
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
                               "usemtl grey\nf 1//1 2//1 3//1\n";
static const char nouv_mtl[] = "newmtl grey\nKd 0.5 0.5 0.5\nmap_Kd tex/a.png\n";

static const char nomtl_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
static const char quad_obj[] = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n";
static const char lines_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n";
static const char nan_obj[] = "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n";
/* A quad whose one normal is NaN (of both signs): positions are checked,
 * normals are the file's business; it renders, and is probed. */
static const char nan_normal_obj[] = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                     "vn nan -nan 1\n"
                                     "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";
static const char inf_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n";
static const char zero_obj[] = "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n";
/* Corners on one line: (1, 2, 3) = -(-1, -2, -3). And the same triangle
 * beside one with an area. */
static const char flat_obj[] = "v 0 0 0\nv 1 2 3\nv -1 -2 -3\nf 1 2 3\n";
static const char half_flat_obj[] = "v 0 0 0\nv 1 2 3\nv -1 -2 -3\nv 0 1 0\nf 1 2 3\nf 1 2 4\n";
static const char range_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";

/* A triangle whose material names a texture: missing, not an image, or a
 * PNG cut after its header. */
static const char texture_obj_format[] = "mtllib %s.mtl\n"
                                         "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                         "vt 0 0\nvt 1 0\nvt 0 1\n"
                                         "usemtl m\nf 1/1 2/2 3/3\n";

/* Two quads side by side facing the camera, with texture coordinates,
 * whose materials name a texture that is not there and one that is not a
 * PNG (twobad); its twin names none (twoplain), and a third names the
 * missing one from both materials (samegone). The same colours: drawn with
 * T = 1, the three give the same pixels. */
static const char two_quads_format[] = "mtllib %s.mtl\n"
                                       "v -1 -0.5 0\nv 0 -0.5 0\nv 0 0.5 0\nv -1 0.5 0\n"
                                       "v 0 -0.5 0\nv 1 -0.5 0\nv 1 0.5 0\nv 0 0.5 0\n"
                                       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                                       "o left\nusemtl m1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
                                       "o right\nusemtl m2\nf 5/1/1 6/2/1 7/3/1 8/4/1\n";
static const char two_quads_mtl_format[] = "newmtl m1\nKd 0.5 0.25 1\n%s\n"
                                           "newmtl m2\nKd 0.25 0.75 0.5\n%s\n";

static void write_two_quads(const char *stem, const char *first_map, const char *second_map)
{
    char name[64], text[1024];
    snprintf(name, sizeof name, "models/%s.obj", stem);
    snprintf(text, sizeof text, two_quads_format, stem);
    write_text(name, text);
    snprintf(name, sizeof name, "models/%s.mtl", stem);
    snprintf(text, sizeof text, two_quads_mtl_format, first_map, second_map);
    write_text(name, text);
}

/* A quad and a triangle in ASCII PLY: three triangles, bounds
 * (0, 0, 0)-(2, 1, 4). */
static const char ply_text[] = "ply\nformat ascii 1.0\n"
                               "element vertex 5\n"
                               "property float x\nproperty float y\nproperty float z\n"
                               "element face 2\n"
                               "property list uchar int vertex_indices\n"
                               "end_header\n"
                               "0 0 0\n2 0 0\n2 1 0\n0 1 0\n1 0.5 4\n"
                               "4 0 1 2 3\n3 0 1 4\n";

/* Two facets in ASCII STL: bounds (0, 0, -2)-(1, 3, 0). */
static const char stl_text[] = "solid t\n"
                               "facet normal 0 0 1\nouter loop\n"
                               "vertex 0 0 0\nvertex 1 0 0\nvertex 0 3 0\n"
                               "endloop\nendfacet\n"
                               "facet normal 0 -1 0\nouter loop\n"
                               "vertex 0 0 0\nvertex 0 0 -2\nvertex 1 0 0\n"
                               "endloop\nendfacet\n"
                               "endsolid t\n";

/* One textured triangle in glTF 2.0, everything inline: the buffer (three
 * positions, three uvs, three 16-bit indices and two bytes of padding, 68
 * bytes) and the image as data URIs. */
static void write_gltf(const char *name, const float positions[9], const unsigned char *image,
                       size_t image_length)
{
    unsigned char buffer[68] = {0};
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    const uint16_t indices[3] = {0, 1, 2};
    memcpy(buffer, positions, 36);
    memcpy(buffer + 36, uvs, 24);
    memcpy(buffer + 60, indices, 6);
    char *buffer_text = base64(buffer, sizeof buffer);
    char *image_text = base64(image, image_length);
    size_t size = strlen(buffer_text) + strlen(image_text) + 2048;
    char *json = malloc(size);
    assert_non_null(json);
    snprintf(json, size,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
             "\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},"
             "\"indices\":2,\"material\":0}]}],"
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
             "\"textures\":[{\"source\":0}],"
             "\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
             "\"buffers\":[{\"byteLength\":68,"
             "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},"
             "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":24},"
             "{\"buffer\":0,\"byteOffset\":60,\"byteLength\":6}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
             "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"},"
             "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]}\n",
             image_text, buffer_text);
    write_text(name, json);
    free(json);
    free(image_text);
    free(buffer_text);
}

/* One untextured triangle in glTF 2.0 whose buffer (three positions, 36
 * bytes) is the file bin_name beside it. */
static void write_gltf_with_bin(const char *name, const char *bin_name)
{
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    char json[1024], bin_path[256];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
             "\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
             "\"buffers\":[{\"byteLength\":36,\"uri\":\"%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
             "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]}]}\n",
             bin_name);
    write_text(name, json);
    const char *slash = strrchr(name, '/');
    snprintf(bin_path, sizeof bin_path, "%.*s%s", slash ? (int)(slash - name + 1) : 0, name,
             bin_name);
    write_bytes(bin_path, positions, sizeof positions);
}

/* Two triangles of a quad in glTF 2.0, the buffer inline; the second
 * names vertex last_index (3 in range, 4 or more past the end). */
static void write_gltf_quad(const char *name, uint16_t last_index)
{
    unsigned char buffer[60] = {0};
    const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, last_index};
    memcpy(buffer, positions, 48);
    memcpy(buffer + 48, indices, 12);
    char *buffer_text = base64(buffer, sizeof buffer);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
             "\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
             "\"buffers\":[{\"byteLength\":60,"
             "\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
             "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":12}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,"
             "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
             "{\"bufferView\":1,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}]}\n",
             buffer_text);
    write_text(name, json);
    free(buffer_text);
}

/* The box that luz-render draws: 2 x 1 x 1.5, centred, each face with the
 * whole texture and its own normal, wound counter-clockwise seen from
 * outside; a 64x64 checker of single texels, so that the filters differ
 * when it is drawn smaller than that. */
static const char box_obj[] =
    "mtllib box.mtl\n"
    "v -1 -0.5 0.75\nv 1 -0.5 0.75\nv 1 0.5 0.75\nv -1 0.5 0.75\n"
    "v -1 -0.5 -0.75\nv 1 -0.5 -0.75\nv 1 0.5 -0.75\nv -1 0.5 -0.75\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 1\nvn 0 0 -1\nvn 1 0 0\nvn -1 0 0\nvn 0 1 0\nvn 0 -1 0\n"
    "usemtl checker\n"
    "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
    "f 6/1/2 5/2/2 8/3/2 7/4/2\n"
    "f 2/1/3 6/2/3 7/3/3 3/4/3\n"
    "f 5/1/4 1/2/4 4/3/4 8/4/4\n"
    "f 4/1/5 3/2/5 7/3/5 8/4/5\n"
    "f 5/1/6 6/2/6 2/3/6 1/4/6\n";
static const char box_mtl[] = "newmtl checker\nKd 1 0.9 0.8\nmap_Kd checker.png\n";

static void write_texture_model(const char *stem, const char *texture_line)
{
    char name[64], text[512];
    snprintf(name, sizeof name, "models/%s.obj", stem);
    snprintf(text, sizeof text, texture_obj_format, stem);
    write_text(name, text);
    snprintf(name, sizeof name, "models/%s.mtl", stem);
    snprintf(text, sizeof text, "newmtl m\nKd 1 1 1\n%s\n", texture_line);
    write_text(name, text);
}

/* ---- textures named outside the model's folder (issue 32, finding 4) -------------------- */

/* models/confine/ holds one-triangle models whose material names a
 * texture: outside/secret.png (texture_b, 3x1) beside models/, reached by
 * an absolute path, by `..`, through a relative and an absolute symbolic
 * link; and img/real.png (texture_a, 2x2) inside, reached through a link
 * that stays inside and by a name that goes up and back down. */
typedef struct confinement_case {
    const char *stem;        /* models/confine/STEM.obj */
    const char *map;         /* what its material names; "@" is work/ */
    bool inside;             /* the texture lies in the folder */
    const char *rule;        /* the warning's reason when outside */
} confinement_case;

static const confinement_case confinement_cases[] = {
    {"absolute", "@/outside/secret.png", false, "named by an absolute path"},
    {"dotdot", "../../outside/secret.png", false, "through '..' or a symbolic link"},
    {"backslashes", "..\\..\\outside\\secret.png", false, "through '..' or a symbolic link"},
    {"link", "out-link.png", false, "through '..' or a symbolic link"},
    {"abslink", "abs-link.png", false, "through '..' or a symbolic link"},
    {"dirlink", "out-dir/secret.png", false, "through '..' or a symbolic link"},
    {"inlink", "in-link.png", true, NULL},
    {"updown", "img/../img/real.png", true, NULL},
};

static void write_confinement_files(void)
{
    make_directory("outside");
    write_png("outside/secret.png", 3, 1, texture_b);
    make_directory("models/confine");
    make_directory("models/confine/img");
    write_png("models/confine/img/real.png", 2, 2, texture_a);
    char target[1024], link_path[1024];
    work_path("outside/secret.png", target, sizeof target);
    work_path("models/confine/abs-link.png", link_path, sizeof link_path);
    assert_int_equal(symlink(target, link_path), 0);
    work_path("models/confine/out-link.png", link_path, sizeof link_path);
    assert_int_equal(symlink("../../outside/secret.png", link_path), 0);
    work_path("models/confine/out-dir", link_path, sizeof link_path);
    assert_int_equal(symlink("../../outside", link_path), 0);
    work_path("models/confine/in-link.png", link_path, sizeof link_path);
    assert_int_equal(symlink("img/real.png", link_path), 0);
    for (size_t c = 0; c < sizeof confinement_cases / sizeof confinement_cases[0]; c++) {
        const confinement_case *test = &confinement_cases[c];
        char name[128], text[2048], map[1024];
        if (test->map[0] == '@')
            snprintf(map, sizeof map, "%s%s", work_directory, test->map + 1);
        else
            snprintf(map, sizeof map, "%s", test->map);
        snprintf(name, sizeof name, "models/confine/%s.obj", test->stem);
        snprintf(text, sizeof text, texture_obj_format, test->stem);
        write_text(name, text);
        snprintf(name, sizeof name, "models/confine/%s.mtl", test->stem);
        snprintf(text, sizeof text, "newmtl m\nKd 1 1 1\nmap_Kd %s\n", map);
        write_text(name, text);
    }
}

/* Loads every confinement case under files and checks it; returns NULL, or
 * what went wrong (no cmocka here: it also runs in a child process). */
static const char *check_confinement(luz_model_files files, char *why, size_t size)
{
    for (size_t c = 0; c < sizeof confinement_cases / sizeof confinement_cases[0]; c++) {
        const confinement_case *test = &confinement_cases[c];
        char path[1024], name[128];
        snprintf(name, sizeof name, "models/confine/%s.obj", test->stem);
        work_path(name, path, sizeof path);
        luz_model model;
        luz_error error = {{0}};
        const luz_model_rules rules = {.files = files};
        if (luz_model_load_with(&model, path, &rules, NULL, &error) != 0) {
            snprintf(why, size, "%s: %s", test->stem, error.message);
            return why;
        }
        const bool drawn = test->inside || files == LUZ_MODEL_FILES_ANYWHERE;
        const luz_texture *texture = model.part_count == 1 ? model.parts[0].texture : NULL;
        const uint8_t *expected = test->inside ? texture_a : texture_b;
        const int width = test->inside ? 2 : 3, height = test->inside ? 2 : 1;
        if (drawn && (texture == NULL || texture->levels[0].width != width ||
                      texture->levels[0].height != height ||
                      memcmp(texture->levels[0].texels, expected, (size_t)width * height * 4)))
            snprintf(why, size, "%s: the texture is not the file's (%d warnings: %s)", test->stem,
                     model.warning_count, model.warning_count ? model.warnings[0] : "");
        else if (drawn && model.warning_count != 0)
            snprintf(why, size, "%s: drawn, yet warned: %s", test->stem, model.warnings[0]);
        else if (!drawn && (texture != NULL || model.warning_count != 1))
            snprintf(why, size, "%s: read from outside the folder (%d warnings)", test->stem,
                     model.warning_count);
        else if (!drawn && (strstr(model.warnings[0], test->rule) == NULL ||
                            strstr(model.warnings[0], "--model-files anywhere") == NULL ||
                            strstr(model.warnings[0], path) == NULL))
            snprintf(why, size, "%s: the warning does not name the rule: %s", test->stem,
                     model.warnings[0]);
        else
            why[0] = '\0';
        luz_model_free(&model);
        if (why[0] != '\0') return why;
    }
    return NULL;
}

static int setup_files(void **state)
{
    (void)state;
    const char *tmp = getenv("TMPDIR");
    snprintf(root_directory, sizeof root_directory, "%s/luz-models-XXXXXX",
             tmp && *tmp ? tmp : "/tmp");
    if (mkdtemp(root_directory) == NULL) return -1;
    snprintf(work_directory, sizeof work_directory, "%s/work", root_directory);
    if (mkdir(work_directory, 0755) != 0) return -1;

    make_directory("models");
    make_directory("models/tex");
    write_png("models/tex/a.png", 2, 2, texture_a);
    write_png("models/tex/b.png", 3, 1, texture_b);
    write_text("models/two.obj", two_obj);
    write_text("models/two.mtl", two_mtl);
    write_text("models/shared.obj", shared_obj);
    write_text("models/shared.mtl", shared_mtl);
    write_text("models/nouv.obj", nouv_obj);
    write_text("models/nouv.mtl", nouv_mtl);
    write_text("models/nomtl.obj", nomtl_obj);
    write_text("models/quad.obj", quad_obj);
    write_text("models/lines.obj", lines_obj);
    write_text("models/point.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                   "property float y\nproperty float z\nend_header\n0 0 0\n");
    write_text("models/empty.stl", "solid nothing\nendsolid nothing\n");
    write_text("models/vertex.obj", "v 0 0 0\n");
    write_text("models/comment.obj", "# a cube, one day\n# (nothing yet)\n");
    write_text("models/nan.obj", nan_obj);
    write_text("models/nan-normal.obj", nan_normal_obj);
    write_text("models/inf.obj", inf_obj);
    write_text("models/zero.obj", zero_obj);
    write_text("models/range.obj", range_obj);
    write_text("models/flat.obj", flat_obj);
    write_text("models/halfflat.obj", half_flat_obj);
    write_text("models/t.ply", ply_text);
    write_text("models/t.stl", stl_text);

    write_texture_model("missingtex", "map_Kd tex/nothere.png");
    write_texture_model("badtex", "map_Kd tex/bad.png");
    write_text("models/tex/bad.png", "this is not a PNG file at all\n");
    int png_length;
    unsigned char *png = png_bytes(2, 2, texture_a, &png_length);
    write_texture_model("cuttex", "map_Kd tex/cut.png");
    write_bytes("models/tex/cut.png", png, 40);   /* the signature, IHDR, and no more */

    write_confinement_files();
    write_two_quads("twobad", "map_Kd tex/gone.png", "map_Kd tex/bad.png");
    write_two_quads("twoplain", "", "");
    write_two_quads("samegone", "map_Kd tex/gone.png", "map_Kd tex/gone.png");

    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    write_gltf("models/embedded.gltf", triangle, png, (size_t)png_length);
    static const char not_png[] = "this is not a PNG image";
    write_gltf("models/badembed.gltf", triangle, (const unsigned char *)not_png,
               sizeof not_png - 1);
    const float nan_triangle[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    write_gltf("models/nan.gltf", nan_triangle, png, (size_t)png_length);
    write_gltf_with_bin("models/external.gltf", "external.bin");
    write_gltf_quad("models/quad.gltf", 3);
    write_gltf_quad("models/outofrange.gltf", 4);
    free(png);

    /* Random bytes under a model's name and under a name no importer
     * claims, the same bytes on every run. */
    unsigned char noise[4096];
    uint32_t x = 12345;
    for (size_t i = 0; i < sizeof noise; i++) noise[i] = (unsigned char)(xorshift(&x) >> 24);
    write_bytes("models/noise.obj", noise, sizeof noise);
    write_bytes("models/noise.xyz", noise, sizeof noise);
    make_directory("models/folder.obj");
    char fifo[1024];
    work_path("models/fifo.obj", fifo, sizeof fifo);
    assert_int_equal(mkfifo(fifo, 0644), 0);

    /* a textures directory for the scene files' `texture NAME` */
    make_directory("cubetex");
    write_png("cubetex/w.png", 2, 2, texture_a);

    make_directory("box");
    uint8_t checker[64 * 64 * 4];
    for (int y = 0; y < 64; y++) {
        for (int x2 = 0; x2 < 64; x2++) {
            uint8_t *texel = checker + (y * 64 + x2) * 4;
            bool light = (x2 + y) % 2 == 0;
            texel[0] = light ? 250 : 30;
            texel[1] = light ? 200 : 60;
            texel[2] = light ? 40 : 220;
            texel[3] = 255;
        }
    }
    write_png("box/checker.png", 64, 64, checker);
    write_text("box/box.obj", box_obj);
    write_text("box/box.mtl", box_mtl);
    return 0;
}

static int teardown_files(void **state)
{
    (void)state;
    remove_tree(root_directory);
    return 0;
}

#define REQUIRE_MODELS()                                                                      \
    do {                                                                                      \
        if (!luz_models_supported()) {                                                        \
            print_message("skipped: this luz was built without model support (-Dmodels)\n"); \
            skip();                                                                           \
        }                                                                                     \
    } while (0)

/* ---- loading ----------------------------------------------------------------------------- */

static void load_model(const char *name, luz_model *model)
{
    char path[1024];
    work_path(name, path, sizeof path);
    luz_error error = {{0}};
    if (luz_model_load(model, path, NULL, &error) != 0) fail_msg("%s: %s", name, error.message);
}

static void assert_texels(const luz_texture *texture, int width, int height,
                          const uint8_t *rgba)
{
    assert_non_null(texture);
    assert_int_equal(texture->levels[0].width, width);
    assert_int_equal(texture->levels[0].height, height);
    assert_memory_equal(texture->levels[0].texels, rgba, (size_t)width * height * 4);
}

static void assert_bounds(luz_bounds bounds, luz_vec3 min, luz_vec3 max)
{
    assert_vec3_near(bounds.min, min.x, min.y, min.z, 0);
    assert_vec3_near(bounds.max, max.x, max.y, max.z, 0);
}

/* two.obj, by hand: part 0 is the quad "first" (material warm: Kd 0.75
 * 0.5 0.25, tex/a.png), two triangles over (0,0,0)-(1,1,0); part 1 the
 * triangle "second" (cold: Kd 0.125 0.25 1, .\tex\b.png read as
 * tex/b.png), over (2,0,-1)-(3,2,-1). Together (0,0,-1)-(3,2,0), three
 * triangles, two textures. The texels are the PNGs' as written: FlipUVs
 * flips the coordinates, never the image. */
static void test_obj_two_meshes_with_materials(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/two.obj", &model);
    assert_string_equal(model.name, "two.obj");
    assert_int_equal(model.part_count, 2);
    assert_int_equal(model.triangle_count, 3);
    assert_int_equal(model.texture_count, 2);
    assert_bounds(model.bounds, (luz_vec3){0, 0, -1}, (luz_vec3){3, 2, 0});

    const luz_model_part *first = &model.parts[0], *second = &model.parts[1];
    assert_int_equal(luz_mesh_triangle_count(first->mesh), 2);
    assert_bounds(luz_mesh_bounds(first->mesh), (luz_vec3){0, 0, 0}, (luz_vec3){1, 1, 0});
    assert_true(first->has_colour);
    assert_vec3_near(first->colour, 0.75, 0.5, 0.25, 0);
    assert_true(first->has_uvs);
    assert_texels(first->texture, 2, 2, texture_a);

    assert_int_equal(luz_mesh_triangle_count(second->mesh), 1);
    assert_bounds(luz_mesh_bounds(second->mesh), (luz_vec3){2, 0, -1}, (luz_vec3){3, 2, -1});
    assert_true(second->has_colour);
    assert_vec3_near(second->colour, 0.125, 0.25, 1, 0);
    assert_true(second->has_uvs);
    assert_texels(second->texture, 3, 1, texture_b);
    luz_model_free(&model);
    assert_int_equal(model.part_count, 0);
    assert_null(model.parts);
}

/* Two materials naming tex/a.png: one texture, both parts use it. */
static void test_obj_shared_texture(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/shared.obj", &model);
    assert_int_equal(model.part_count, 2);
    assert_int_equal(model.texture_count, 1);
    assert_ptr_equal(model.parts[0].texture, model.textures[0]);
    assert_ptr_equal(model.parts[1].texture, model.textures[0]);
    assert_vec3_near(model.parts[0].colour, 1, 0, 0, 0);
    assert_vec3_near(model.parts[1].colour, 0, 1, 0, 0);
    luz_model_free(&model);
}

/* No vt: no uvs, so no texture (T = 1) though the material names one. */
static void test_obj_without_uvs_has_no_texture(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/nouv.obj", &model);
    assert_int_equal(model.part_count, 1);
    assert_false(model.parts[0].has_uvs);
    assert_null(model.parts[0].texture);
    assert_int_equal(model.texture_count, 0);
    assert_true(model.parts[0].has_colour);
    assert_vec3_near(model.parts[0].colour, 0.5, 0.5, 0.5, 0);
    luz_model_free(&model);
}

/* No mtllib: assimp's stand-in "DefaultMaterial", whose colour is not the
 * model's (the seed's colour is used). */
static void test_obj_without_materials_has_no_colour(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/nomtl.obj", &model);
    assert_int_equal(model.part_count, 1);
    assert_false(model.parts[0].has_colour);
    assert_false(model.parts[0].has_uvs);
    assert_null(model.parts[0].texture);
    assert_bounds(model.bounds, (luz_vec3){0, 0, 0}, (luz_vec3){1, 1, 0});
    luz_model_free(&model);
}

/* f 1 2 3 4 is triangulated: two triangles over the four corners. */
static void test_quad_becomes_two_triangles(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/quad.obj", &model);
    assert_int_equal(model.part_count, 1);
    assert_int_equal(model.triangle_count, 2);
    assert_int_equal(luz_mesh_triangle_count(model.parts[0].mesh), 2);
    assert_int_equal(luz_mesh_vertex_count(model.parts[0].mesh), 4);
    assert_bounds(model.bounds, (luz_vec3){0, 0, 0}, (luz_vec3){2, 1, 0});
    luz_model_free(&model);
}

/* A triangle with its corners on a line, beside one with an area: both
 * kept, nothing refused. */
static void test_degenerate_triangle_beside_others(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/halfflat.obj", &model);
    assert_int_equal(model.part_count, 1);
    assert_int_equal(model.triangle_count, 2);
    assert_bounds(model.bounds, (luz_vec3){-1, -2, -3}, (luz_vec3){1, 2, 3});
    luz_model_free(&model);
}

/* PLY: a quad and a triangle, three triangles over (0,0,0)-(2,1,4).
 * STL: two facets over (0,0,-2)-(1,3,0); STL has no materials, so the
 * stand-in and no colour. */
static void test_ply_and_stl(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/t.ply", &model);
    assert_int_equal(model.part_count, 1);
    assert_int_equal(model.triangle_count, 3);
    assert_false(model.parts[0].has_uvs);
    assert_bounds(model.bounds, (luz_vec3){0, 0, 0}, (luz_vec3){2, 1, 4});
    luz_model_free(&model);

    load_model("models/t.stl", &model);
    assert_int_equal(model.part_count, 1);
    assert_int_equal(model.triangle_count, 2);
    assert_false(model.parts[0].has_colour);
    assert_bounds(model.bounds, (luz_vec3){0, 0, -2}, (luz_vec3){1, 3, 0});
    luz_model_free(&model);
}

/* A texture inside the file (glTF's data URI, assimp's "*0"), decoded from
 * memory: the 2x2 texels of tex/a.png. */
static void test_gltf_embedded_texture(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    luz_model model;
    load_model("models/embedded.gltf", &model);
    assert_int_equal(model.part_count, 1);
    assert_int_equal(model.triangle_count, 1);
    assert_true(model.parts[0].has_uvs);
    assert_texels(model.parts[0].texture, 2, 2, texture_a);
    assert_bounds(model.bounds, (luz_vec3){0, 0, 0}, (luz_vec3){1, 1, 0});
    luz_model_free(&model);
}

/* Debian's assimp-testmodels' BoxTextured.glb. Its JSON chunk says: one
 * mesh, 36 indices (12 triangles), POSITION between -0.5 and 0.5 on every
 * axis (the root node only swaps y and z), TEXCOORD_0, and a PNG image in
 * the binary chunk, whose size is read here from the PNG's own IHDR. */
#define BOX_TEXTURED_GLB "/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"

static void test_glb_embedded_texture(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    size_t length;
    unsigned char *file = (unsigned char *)read_file(BOX_TEXTURED_GLB, &length);
    if (file == NULL) {
        print_message("skipped: %s is not installed (Debian's assimp-testmodels)\n",
                      BOX_TEXTURED_GLB);
        skip();
    }
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    const unsigned char *png = NULL;
    for (size_t i = 0; i + 24 <= length && png == NULL; i++)
        if (memcmp(file + i, signature, 8) == 0) png = file + i;
    assert_non_null(png);
    assert_memory_equal(png + 12, "IHDR", 4);
    const int width = png[16] << 24 | png[17] << 16 | png[18] << 8 | png[19];
    const int height = png[20] << 24 | png[21] << 16 | png[22] << 8 | png[23];
    free(file);

    luz_model model;
    luz_error error = {{0}};
    if (luz_model_load(&model, BOX_TEXTURED_GLB, NULL, &error) != 0) fail_msg("%s", error.message);
    assert_int_equal(model.part_count, 1);
    assert_int_equal(model.triangle_count, 12);
    assert_true(model.parts[0].has_uvs);
    assert_non_null(model.parts[0].texture);
    assert_int_equal(model.parts[0].texture->levels[0].width, width);
    assert_int_equal(model.parts[0].texture->levels[0].height, height);
    assert_bounds(model.bounds, (luz_vec3){-0.5f, -0.5f, -0.5f}, (luz_vec3){0.5f, 0.5f, 0.5f});
    luz_model_free(&model);
}

/* luz_model_load refuses name with -1 and one line naming the file (its
 * path as given) and the needles; the model is left empty. */
static void assert_load_refused(const char *name, const char *needle, const char *other)
{
    char path[1024];
    work_path(name, path, sizeof path);
    luz_model model;
    luz_error error = {{0}};
    if (luz_model_load(&model, path, NULL, &error) != -1) fail_msg("%s: loaded", name);
    assert_contains(error.message, path);
    if (needle) assert_contains(error.message, needle);
    if (other) assert_contains(error.message, other);
    assert_null(strchr(error.message, '\n'));
    assert_int_equal(model.part_count, 0);
    assert_null(model.parts);
    assert_null(model.textures);
    assert_null(model.path);
}

static void test_load_refusals(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    assert_load_refused("models/lines.obj", "no triangles", NULL);
    assert_load_refused("models/nan.obj", "not finite", NULL);
    assert_load_refused("models/inf.obj", "not finite", NULL);
    assert_load_refused("models/nan.gltf", "not finite", NULL);
    assert_load_refused("models/zero.obj", "zero size", NULL);
    assert_load_refused("models/flat.obj", "no triangle has an area", NULL);
    assert_load_refused("models/range.obj", NULL, NULL);
    assert_load_refused("models/noise.obj", NULL, NULL);
    assert_load_refused("models/noise.xyz", NULL, NULL);
    assert_load_refused("models/folder.obj", "not a regular file", NULL);
    assert_load_refused("models/fifo.obj", "not a regular file", NULL);
    assert_load_refused("models/nothere.obj", "No such file", NULL);
}

/* A texture the model names that is missing or corrupt does not stop it
 * (SCENE.md, "Models"): the part has no texture (T = 1), and the model one
 * warning, one line naming the model, the texture and why. */
static void assert_loads_with_warning(const char *name, const char *texture, const char *why)
{
    char path[1024];
    work_path(name, path, sizeof path);
    luz_model model;
    luz_error error = {{0}};
    if (luz_model_load(&model, path, NULL, &error) != 0) fail_msg("%s: %s", name, error.message);
    assert_int_equal(model.part_count, 1);
    assert_true(model.parts[0].has_uvs);
    assert_null(model.parts[0].texture);
    assert_int_equal(model.texture_count, 0);
    assert_int_equal(model.texture_file_count, 0);
    assert_int_equal(model.warning_count, 1);
    assert_contains(model.warnings[0], path);
    assert_contains(model.warnings[0], texture);
    assert_contains(model.warnings[0], why);
    assert_contains(model.warnings[0], "T = 1");
    assert_null(strchr(model.warnings[0], '\n'));
    luz_model_free(&model);
}

static void test_missing_or_corrupt_texture_is_a_warning(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    assert_loads_with_warning("models/missingtex.obj", "'tex/nothere.png'", "No such file");
    assert_loads_with_warning("models/badtex.obj", "'tex/bad.png'", "not a PNG file");
    assert_loads_with_warning("models/cuttex.obj", "'tex/cut.png'", "truncated PNG");
    assert_loads_with_warning("models/badembed.gltf", "texture '*0'", "PNG");

    /* two parts naming the same missing file: one warning, both untextured */
    luz_model model;
    load_model("models/samegone.obj", &model);
    assert_int_equal(model.part_count, 2);
    assert_null(model.parts[0].texture);
    assert_null(model.parts[1].texture);
    assert_int_equal(model.warning_count, 1);
    assert_contains(model.warnings[0], "'tex/gone.png'");
    luz_model_free(&model);

    /* one missing, one corrupt: a warning each, in the parts' order */
    load_model("models/twobad.obj", &model);
    assert_int_equal(model.part_count, 2);
    assert_null(model.parts[0].texture);
    assert_null(model.parts[1].texture);
    assert_int_equal(model.warning_count, 2);
    assert_contains(model.warnings[0], "'tex/gone.png'");
    assert_contains(model.warnings[1], "'tex/bad.png'");
    /* the colours stay the materials' */
    assert_vec3_near(model.parts[0].colour, 0.5, 0.25, 1, 0);
    assert_vec3_near(model.parts[1].colour, 0.25, 0.75, 0.5, 0);
    luz_model_free(&model);
}

/* A texture named outside the model's folder is as good as missing (a
 * warning naming the file and the rule, T = 1) unless the rules say
 * anywhere; names that stay inside load. */
static void test_textures_confined_to_the_folder(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    static char why[LUZ_ERROR_MESSAGE_SIZE + 256];
    const char *failure = check_confinement(LUZ_MODEL_FILES_FOLDER, why, sizeof why);
    if (failure) fail_msg("folder: %s", failure);
    failure = check_confinement(LUZ_MODEL_FILES_ANYWHERE, why, sizeof why);
    if (failure) fail_msg("anywhere: %s", failure);
}

/* The same on a kernel without openat2 (before Linux 5.6), made here in a
 * child process whose seccomp filter answers openat2 with ENOSYS: the
 * loader then checks the file it opened against the folder's real path. */
static void test_textures_confined_without_openat2(void **state)
{
    (void)state;
    REQUIRE_MODELS();
#if defined(__x86_64__) && defined(SYS_openat2)
    fflush(NULL);
    const pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        struct sock_filter filter[] = {
            BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, arch)),
            BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, AUDIT_ARCH_X86_64, 1, 0),
            BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
            BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, nr)),
            BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, SYS_openat2, 0, 1),
            BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | ENOSYS),
            BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
        };
        struct sock_fprog program = {.len = sizeof filter / sizeof filter[0], .filter = filter};
        if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0 ||
            prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &program) != 0)
            _exit(3);
        /* openat2 is gone */
        if (syscall(SYS_openat2, AT_FDCWD, ".", NULL, 0) != -1 || errno != ENOSYS) _exit(4);
        static char why[LUZ_ERROR_MESSAGE_SIZE + 256];
        const char *failure = check_confinement(LUZ_MODEL_FILES_FOLDER, why, sizeof why);
        if (failure == NULL) failure = check_confinement(LUZ_MODEL_FILES_ANYWHERE, why, sizeof why);
        if (failure) fprintf(stderr, "without openat2: %s\n", failure);
        _exit(failure ? 1 : 0);
    }
    int status;
    while (waitpid(child, &status, 0) < 0) assert_int_equal(errno, EINTR);
    assert_true(WIFEXITED(status));
    if (WEXITSTATUS(status) == 3) {
        print_message("skipped: no seccomp filter could be set\n");
        skip();
    }
    assert_int_equal(WEXITSTATUS(status), 0);
#else
    print_message("skipped: the seccomp filter here is written for x86-64\n");
    skip();
#endif
}

/* ---- the lab's placement ------------------------------------------------------------------ */

/* A luz_lab_model made here, with no file: the lab reads only this. */
typedef struct hand_model {
    luz_mesh *meshes[3];
    luz_lab_model_part parts[3];
    luz_lab_model model;
} hand_model;

static luz_mesh *triangle_mesh(float z)
{
    const luz_vertex vertices[3] = {
        {{0, 0, z}, {0, 0, 1}, {0, 0}}, {{1, 0, z}, {0, 0, 1}, {1, 0}}, {{0, 1, z}, {0, 0, 1}, {0, 1}}};
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices, .vertex_count = 3},
                                     NULL);
    assert_non_null(mesh);
    return mesh;
}

/* Bounds (1, 2, 3)-(5, 3, 4): c = (3, 2.5, 3.5), s = 4 (along x), so
 * Norm(q) = (q - c) / 2. */
static void make_hand_model(hand_model *hand, int part_count)
{
    memset(hand, 0, sizeof *hand);
    for (int p = 0; p < part_count; p++) hand->meshes[p] = triangle_mesh((float)p);
    hand->model = (luz_lab_model){.name = "hand", .parts = hand->parts, .part_count = part_count,
                                  .bounds = {{1, 2, 3}, {5, 3, 4}}};
    for (int p = 0; p < part_count; p++) hand->parts[p].mesh = hand->meshes[p];
}

static void free_hand_model(hand_model *hand)
{
    for (int p = 0; p < 3; p++) luz_mesh_destroy(hand->meshes[p]);
}

/* Norm maps c to the origin and the longest side (x, 4 long) to [-1, 1];
 * the other sides shrink by the same 2 / 4: min -> (-1, -0.25, -0.25),
 * max -> (1, 0.25, 0.25), (3, 3, 3) -> (0, 0.25, -0.25). */
static void test_normalisation(void **state)
{
    (void)state;
    hand_model hand;
    make_hand_model(&hand, 1);
    const luz_mat4 norm = luz_lab_model_normalisation(&hand.model, LUZ_UP_Y);
    assert_vec3_near(luz_mat4_transform_point(norm, (luz_vec3){3, 2.5f, 3.5f}), 0, 0, 0,
                     TOLERANCE);
    assert_vec3_near(luz_mat4_transform_point(norm, (luz_vec3){1, 2, 3}), -1, -0.25, -0.25,
                     TOLERANCE);
    assert_vec3_near(luz_mat4_transform_point(norm, (luz_vec3){5, 3, 4}), 1, 0.25, 0.25,
                     TOLERANCE);
    assert_vec3_near(luz_mat4_transform_point(norm, (luz_vec3){3, 3, 3}), 0, 0.25, -0.25,
                     TOLERANCE);

    /* The longest side along z instead: (0,0,0)-(1,1,10), k = 0.2. */
    hand.model.bounds = (luz_bounds){{0, 0, 0}, {1, 1, 10}};
    const luz_mat4 tall = luz_lab_model_normalisation(&hand.model, LUZ_UP_Y);
    assert_vec3_near(luz_mat4_transform_point(tall, (luz_vec3){1, 1, 10}), 0.1, 0.1, 1,
                     TOLERANCE);
    assert_vec3_near(luz_mat4_transform_point(tall, (luz_vec3){0, 0, 0}), -0.1, -0.1, -1,
                     TOLERANCE);

    /* Huge but finite: (-3e38, -1, 0)-(3e38, 1, 0), whose max - min and
     * min + max overflow a float. s = 6e38, so Norm takes (3e38, 0, 0) to
     * (1, 0, 0) and (0, 1, 0) to (0, 1/3e38, 0), about 0. */
    hand.model.bounds = (luz_bounds){{-3e38f, -1, 0}, {3e38f, 1, 0}};
    const luz_mat4 huge = luz_lab_model_normalisation(&hand.model, LUZ_UP_Y);
    assert_vec3_near(luz_mat4_transform_point(huge, (luz_vec3){3e38f, 0, 0}), 1, 0, 0, 1e-3);
    assert_vec3_near(luz_mat4_transform_point(huge, (luz_vec3){-3e38f, 1, 0}), -1, 0, 0, 1e-3);
    free_hand_model(&hand);
}

/* SCENE.md's "Up axis", on a model whose three vertices differ along
 * every axis: A = (0, 1, -1), B = (4, 2, 0), P = (1, 2, -1), its box
 * (0, 1, -1)-(4, 2, 0) taken by luz_mesh_bounds. Each axis turns the
 * vertices by SCENE.md's table first, then the box of the turned vertices
 * gives c and s (4, the x extent, in every case here, so k = 1/2):
 *
 *   y   as they are; c = (2, 1.5, -0.5)
 *   z   (x, z, -y):  A (0, -1, -1)  B (4, 0, -2)  P (1, -1, -2);  c = (2, -0.5, -1.5)
 *   -z  (x, -z, y):  A (0, 1, 1)    B (4, 0, 2)   P (1, 1, 2);    c = (2, 0.5, 1.5)
 *   x   (-y, x, z):  A (-1, 0, -1)  B (-2, 4, 0)  P (-2, 1, -1);  c = (-1.5, 2, -0.5)
 *   -x  (y, -x, z):  A (1, 0, -1)   B (2, -4, 0)  P (2, -1, -1);  c = (1.5, -2, -0.5)
 *   -y  (-x, -y, z): A (0, -1, -1)  B (-4, -2, 0) P (-1, -2, -1); c = (-2, -1.5, -0.5)
 *
 * and Norm(v) = (turned v - c) / 2, written out below. A turn in the
 * wrong direction, or bounds taken before the turn, moves some vertex. */
static void test_up_axis_turns_then_normalises(void **state)
{
    (void)state;
    const luz_vertex vertices[3] = {{{0, 1, -1}, {0, 0, 1}, {0, 0}},
                                    {{4, 2, 0}, {0, 0, 1}, {1, 0}},
                                    {{1, 2, -1}, {0, 0, 1}, {0, 1}}};
    luz_mesh *mesh = luz_mesh_create(&(luz_mesh_desc){.vertices = vertices, .vertex_count = 3},
                                     NULL);
    assert_non_null(mesh);
    const luz_lab_model_part part = {.mesh = mesh};
    const luz_lab_model model = {.name = "asymmetric", .parts = &part, .part_count = 1,
                                 .bounds = luz_mesh_bounds(mesh)};
    static const struct {
        const char *name;
        float expected[3][3];   /* A, B, P normalised */
    } cases[] = {
        {"y", {{-1, -0.25f, -0.25f}, {1, 0.25f, 0.25f}, {-0.5f, 0.25f, -0.25f}}},
        {"z", {{-1, -0.25f, 0.25f}, {1, 0.25f, -0.25f}, {-0.5f, -0.25f, -0.25f}}},
        {"-z", {{-1, 0.25f, -0.25f}, {1, -0.25f, 0.25f}, {-0.5f, 0.25f, 0.25f}}},
        {"x", {{0.25f, -1, -0.25f}, {-0.25f, 1, 0.25f}, {-0.25f, -0.5f, -0.25f}}},
        {"-x", {{-0.25f, 1, -0.25f}, {0.25f, -1, 0.25f}, {0.25f, 0.5f, -0.25f}}},
        {"-y", {{1, 0.25f, -0.25f}, {-1, -0.25f, 0.25f}, {0.5f, -0.25f, -0.25f}}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        luz_up_axis up;
        assert_true(luz_up_axis_from_name(cases[i].name, &up));
        assert_string_equal(luz_up_axis_name(up), cases[i].name);
        const luz_mat4 norm = luz_lab_model_normalisation(&model, up);
        for (int v = 0; v < 3; v++) {
            const luz_vec3 got = luz_mat4_transform_point(norm, vertices[v].position);
            if (fabsf(got.x - cases[i].expected[v][0]) > 1e-6f ||
                fabsf(got.y - cases[i].expected[v][1]) > 1e-6f ||
                fabsf(got.z - cases[i].expected[v][2]) > 1e-6f)
                fail_msg("up %s, vertex %d: got (%g, %g, %g), expected (%g, %g, %g)",
                         cases[i].name, v, (double)got.x, (double)got.y, (double)got.z,
                         (double)cases[i].expected[v][0], (double)cases[i].expected[v][1],
                         (double)cases[i].expected[v][2]);
        }
    }
    luz_up_axis up;
    assert_false(luz_up_axis_from_name("+z", &up));
    assert_false(luz_up_axis_from_name("Z", &up));
    luz_mesh_destroy(mesh);
}

/* The model at index 1 (after a cube), p = (1, -2, 0.5), k = 2, at
 * t = 2.7: angle_1 = 2/3 * 2.7 * 50 = 90 degrees about
 * a = normalize(1, 0.5, 1) = (2/3, 1/3, 2/3).
 *
 * The bounds' max corner (5, 3, 4): Norm -> (1, 0.25, 0.25), Scale(2) ->
 * v = (2, 0.5, 0.5). A right-handed 90-degree turn is
 * R v = a x v + a (a . v): a . v = 4/3 + 1/6 + 1/3 = 11/6,
 * a x v = (1/6 - 1/3, 4/3 - 1/3, 1/3 - 2/3) = (-1/6, 1, -1/3),
 * a (a . v) = (11/9, 11/18, 11/9), so R v = (19/18, 29/18, 16/18) and
 * M (5, 3, 4) = p + R v = (37/18, -7/18, 25/18). The min corner is -v:
 * p - R v = (-1/18, -65/18, -7/18). The centre goes to p.
 * `still`: no turn, M (5, 3, 4) = p + v = (3, -1.5, 1) at any t. */
static void test_model_matrix(void **state)
{
    (void)state;
    hand_model hand;
    make_hand_model(&hand, 2);
    luz_object objects[2] = {
        {.position = {4, 4, 4}, .texture = LUZ_TEXTURE_BY_INDEX},
        {.position = {1, -2, 0.5f}, .texture = LUZ_TEXTURE_BY_INDEX, .model = &hand.model,
         .scale = 2},
    };
    luz_scene scene = luz_scene_defaults();
    scene.objects = objects;
    scene.object_count = 2;
    scene.time_seconds = 2.7;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, NULL, 0, 1.5f, &frame, NULL), 0);
    /* the cube, the model's two parts in order, the point light's marker */
    assert_int_equal(frame.draw_count, 4);
    assert_ptr_equal(frame.draws[0].mesh, luz_lab_cube_mesh(test_lab()));
    assert_ptr_equal(frame.draws[1].mesh, hand.meshes[0]);
    assert_ptr_equal(frame.draws[2].mesh, hand.meshes[1]);
    assert_ptr_equal(frame.draws[3].mesh, luz_lab_cube_mesh(test_lab()));
    for (int d = 1; d <= 2; d++) {
        const luz_mat4 m = frame.draws[d].model;
        assert_vec3_near(luz_mat4_transform_point(m, (luz_vec3){3, 2.5f, 3.5f}), 1, -2, 0.5,
                         TOLERANCE);
        assert_vec3_near(luz_mat4_transform_point(m, (luz_vec3){5, 3, 4}), 37.0 / 18,
                         -7.0 / 18, 25.0 / 18, TOLERANCE);
        assert_vec3_near(luz_mat4_transform_point(m, (luz_vec3){1, 2, 3}), -1.0 / 18,
                         -65.0 / 18, -7.0 / 18, TOLERANCE);
    }

    /* scale 0 means 1: M (5, 3, 4) = p + R (1, 0.25, 0.25) = p + R v / 2 */
    objects[1].scale = 0;
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, NULL, 0, 1.5f, &frame, NULL), 0);
    assert_vec3_near(luz_mat4_transform_point(frame.draws[1].model, (luz_vec3){5, 3, 4}),
                     1 + 19.0 / 36, -2 + 29.0 / 36, 0.5 + 16.0 / 36, TOLERANCE);

    objects[1].scale = 2;
    objects[1].still = true;
    const double times[3] = {0, 2.7, 1234.5};
    for (int k = 0; k < 3; k++) {
        scene.time_seconds = times[k];
        assert_int_equal(luz_scene_build_frame(test_lab(), &scene, NULL, 0, 1.5f, &frame, NULL),
                         0);
        assert_vec3_near(luz_mat4_transform_point(frame.draws[1].model, (luz_vec3){5, 3, 4}), 3,
                         -1.5, 1, TOLERANCE);
        assert_vec3_near(luz_mat4_transform_point(frame.draws[2].model, (luz_vec3){1, 2, 3}), -1,
                         -2.5, 0, TOLERANCE);
    }
    luz_frame_free(&frame);
    free_hand_model(&hand);
}

/* The seed's colour for index i, from SCENE.md's text: three floats per
 * index, (x >> 8) / 16777216 after one step each; seed 0 means
 * 0x9E3779B9. */
static luz_vec3 seed_colour(uint32_t seed, int index)
{
    uint32_t x = seed == 0 ? 0x9E3779B9u : seed;
    float c[3] = {0, 0, 0};
    for (int i = 0; i <= index; i++)
        for (int k = 0; k < 3; k++) c[k] = (float)(xorshift(&x) >> 8) / 16777216.0f;
    return (luz_vec3){c[0], c[1], c[2]};
}

/* C, per part: the object's colour; else the material's; else the seed's
 * for the object's index. */
static void test_colour_precedence(void **state)
{
    (void)state;
    hand_model hand;
    make_hand_model(&hand, 2);
    hand.parts[0].has_colour = true;
    hand.parts[0].colour = (luz_vec3){0.25f, 0.5f, 0.75f};
    luz_object objects[3] = {
        {.texture = LUZ_TEXTURE_BY_INDEX},
        {.texture = LUZ_TEXTURE_BY_INDEX, .model = &hand.model},
        {.texture = LUZ_TEXTURE_BY_INDEX, .model = &hand.model, .has_colour = true,
         .colour = {1, 0.5f, 0}},
    };
    luz_scene scene = luz_scene_defaults();
    scene.seed = 7;
    scene.objects = objects;
    scene.object_count = 3;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, NULL, 0, 1.5f, &frame, NULL), 0);
    assert_int_equal(frame.draw_count, 6);   /* cube, 2 + 2 parts, marker */
    const luz_vec3 seed0 = seed_colour(7, 0), seed1 = seed_colour(7, 1);
    assert_vec3_near(frame.draws[0].material.colour, seed0.x, seed0.y, seed0.z, 0);
    assert_vec3_near(frame.draws[1].material.colour, 0.25, 0.5, 0.75, 0);   /* material */
    assert_vec3_near(frame.draws[2].material.colour, seed1.x, seed1.y, seed1.z, 0);
    assert_vec3_near(frame.draws[3].material.colour, 1, 0.5, 0, 0);            /* object */
    assert_vec3_near(frame.draws[4].material.colour, 1, 0.5, 0, 0);
    /* the seed's colour for index 1 is not index 0's or 2's */
    const luz_vec3 seed2 = seed_colour(7, 2);
    assert_true(seed1.x != seed0.x && seed1.x != seed2.x);
    luz_frame_free(&frame);
    free_hand_model(&hand);
}

/* T, per part: none without uvs; else the object's texture (an index into
 * the set); else the material's; else none. */
static void test_texture_precedence(void **state)
{
    (void)state;
    const uint8_t white[4] = {255, 255, 255, 255}, black[4] = {0, 0, 0, 255};
    luz_texture *set[2] = {luz_texture_create(1, 1, white, NULL),
                           luz_texture_create(1, 1, black, NULL)};
    luz_texture *own = luz_texture_create(1, 1, white, NULL);
    assert_true(set[0] && set[1] && own);
    hand_model hand;
    make_hand_model(&hand, 3);
    hand.parts[0] = (luz_lab_model_part){.mesh = hand.meshes[0], .has_uvs = true,
                                         .texture = own};
    hand.parts[1] = (luz_lab_model_part){.mesh = hand.meshes[1], .has_uvs = true};
    hand.parts[2] = (luz_lab_model_part){.mesh = hand.meshes[2], .has_uvs = false,
                                         .texture = own};
    luz_object objects[2] = {
        {.texture = LUZ_TEXTURE_BY_INDEX, .model = &hand.model},
        {.texture = 1, .model = &hand.model},
    };
    luz_scene scene = luz_scene_defaults();
    scene.objects = objects;
    scene.object_count = 2;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, set, 2, 1.5f, &frame, NULL), 0);
    assert_int_equal(frame.draw_count, 7);
    assert_ptr_equal(frame.draws[0].material.texture, own);      /* the material's */
    assert_null(frame.draws[1].material.texture);                /* none: not i mod N */
    assert_null(frame.draws[2].material.texture);                /* no uvs */
    assert_ptr_equal(frame.draws[3].material.texture, set[1]);   /* the object's */
    assert_ptr_equal(frame.draws[4].material.texture, set[1]);
    assert_null(frame.draws[5].material.texture);                /* no uvs, still none */

    /* no texture set at all: the materials' textures stay */
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, NULL, 0, 1.5f, &frame, NULL), 0);
    assert_ptr_equal(frame.draws[0].material.texture, own);
    assert_ptr_equal(frame.draws[3].material.texture, own);
    luz_frame_free(&frame);
    free_hand_model(&hand);
    luz_texture_destroy(own);
    luz_texture_destroy(set[0]);
    luz_texture_destroy(set[1]);
}

/* cube, model, cube, model: the draws follow the list (a model's parts in
 * order), the cubes at their own positions with the seed's colours and
 * textures i mod N of their own indices 0 and 2. */
static void test_cubes_and_models_in_order(void **state)
{
    (void)state;
    const uint8_t texel[4] = {255, 255, 255, 255};
    luz_texture *set[3] = {luz_texture_create(1, 1, texel, NULL),
                           luz_texture_create(1, 1, texel, NULL),
                           luz_texture_create(1, 1, texel, NULL)};
    hand_model hand;
    make_hand_model(&hand, 2);
    luz_object objects[4] = {
        {.position = {1, 0, 0}, .texture = LUZ_TEXTURE_BY_INDEX},
        {.position = {0, 1, 0}, .texture = LUZ_TEXTURE_BY_INDEX, .model = &hand.model},
        {.position = {0, 0, 1}, .texture = LUZ_TEXTURE_BY_INDEX},
        {.position = {2, 2, 2}, .texture = LUZ_TEXTURE_BY_INDEX, .model = &hand.model},
    };
    luz_scene scene = luz_scene_defaults();
    scene.objects = objects;
    scene.object_count = 4;
    luz_frame frame = {0};
    assert_int_equal(luz_scene_build_frame(test_lab(), &scene, set, 3, 1.5f, &frame, NULL), 0);
    assert_int_equal(frame.draw_count, 7);
    const luz_mesh *cube = luz_lab_cube_mesh(test_lab());
    const luz_mesh *expected_meshes[7] = {cube, hand.meshes[0], hand.meshes[1], cube,
                                          hand.meshes[0], hand.meshes[1], cube};
    const int expected_index[6] = {0, 1, 1, 2, 3, 3};
    for (int d = 0; d < 7; d++) assert_ptr_equal(frame.draws[d].mesh, expected_meshes[d]);
    for (int d = 0; d < 6; d++) {
        const luz_vec3 expected = seed_colour(0, expected_index[d]);
        assert_vec3_near(frame.draws[d].material.colour, expected.x, expected.y, expected.z, 0);
        const luz_object *object = &objects[expected_index[d]];
        const luz_vec3 centre = object->model ? (luz_vec3){3, 2.5f, 3.5f} : (luz_vec3){0, 0, 0};
        assert_vec3_near(luz_mat4_transform_point(frame.draws[d].model, centre),
                         object->position.x, object->position.y, object->position.z, TOLERANCE);
    }
    assert_ptr_equal(frame.draws[0].material.texture, set[0]);
    assert_ptr_equal(frame.draws[3].material.texture, set[2]);
    luz_frame_free(&frame);
    free_hand_model(&hand);
    for (int i = 0; i < 3; i++) luz_texture_destroy(set[i]);
}

/* ---- scene files ------------------------------------------------------------------------- */

static void read_scene(luz_options *options, const char *path)
{
    luz_options_init(options);
    luz_error error = {{0}};
    if (luz_options_read_scene_file(options, path, &error) != 0) fail_msg("%s", error.message);
}

/* Every field of a model line, in two different orders, FILE quoted with a
 * blank in it, relative to the scene file's directory: read from /, and
 * from the work directory through a relative scene path. */
static void test_scene_model_fields(void **state)
{
    (void)state;
    make_directory("scenes");
    make_directory("scenes/sub");
    write_text("scenes/sub/my model.obj", quad_obj);
    write_text("scenes/sub/s.luz",
               "# a model, then the same one placed\n"
               "model = \"my model.obj\" still texture \"old wood.png\" scale 2.5 "
               "colour 0.25, 0.5, 1 at 1, -2, 0.5\n"
               "cube = 0, 0, -4\n"
               "model = \"my model.obj\" at 0,0,-3  # a comment\n"
               "model = \"my model.obj\" at 3, 2, 1 colour 1,0,0 scale 0.5 still texture w.png\n");
    char scene_path[1024], model_path[1024], saved[1024];
    work_path("scenes/sub/s.luz", scene_path, sizeof scene_path);
    work_path("scenes/sub/my model.obj", model_path, sizeof model_path);
    assert_non_null(getcwd(saved, sizeof saved));

    for (int pass = 0; pass < 2; pass++) {
        luz_options options;
        if (pass == 0) {
            assert_int_equal(chdir("/"), 0);
            read_scene(&options, scene_path);
        } else {
            assert_int_equal(chdir(work_directory), 0);
            read_scene(&options, "scenes/sub/s.luz");
        }
        assert_int_equal(options.scene.object_count, 4);
        const luz_object *o = options.objects;
        const luz_object_source *source = options.object_sources;
        assert_string_equal(source[0].model_path, model_path);
        assert_vec3_near(o[0].position, 1, -2, 0.5, 0);
        assert_near(o[0].scale, 2.5, 0);
        assert_true(o[0].has_colour);
        assert_vec3_near(o[0].colour, 0.25, 0.5, 1, 0);
        assert_true(o[0].still);
        assert_string_equal(source[0].texture_name, "old wood.png");
        assert_int_equal(source[0].line, 2);

        assert_null(source[1].model_path);
        assert_null(o[1].model);
        assert_vec3_near(o[1].position, 0, 0, -4, 0);

        assert_string_equal(source[2].model_path, model_path);
        assert_vec3_near(o[2].position, 0, 0, -3, 0);
        assert_near(o[2].scale, 1, 0);
        assert_false(o[2].has_colour);
        assert_false(o[2].still);
        assert_null(source[2].texture_name);

        assert_string_equal(source[3].model_path, model_path);
        assert_vec3_near(o[3].position, 3, 2, 1, 0);
        assert_vec3_near(o[3].colour, 1, 0, 0, 0);
        assert_near(o[3].scale, 0.5, 0);
        assert_true(o[3].still);
        assert_string_equal(source[3].texture_name, "w.png");

        if (luz_models_supported()) {
            /* read from the other directory still: one file, read once */
            luz_model_set set;
            luz_error error = {{0}};
            if (luz_options_load_models(&options, &set, NULL, &error) != 0)
                fail_msg("%s", error.message);
            assert_int_equal(set.count, 1);
            assert_ptr_equal(options.objects[0].model, &set.views[0]);
            assert_ptr_equal(options.objects[2].model, &set.views[0]);
            assert_null(options.objects[1].model);
            assert_int_equal(set.views[0].part_count, 1);
            luz_model_set_free(&set);
        }
        luz_options_free(&options);
    }
    assert_int_equal(chdir(saved), 0);
}

static char *scene_text(const luz_options *options)
{
    char *text = NULL;
    size_t length = 0;
    FILE *stream = open_memstream(&text, &length);
    assert_non_null(stream);
    luz_options_write_scene(options, stream);
    assert_int_equal(fclose(stream), 0);
    return text;
}

/* Cubes and models mixed, written back and read again (from another
 * directory): the same objects, the same text, absolute model paths. The
 * texture names need quotes: a blank, and a '#' that is not a comment. */
static void test_scene_round_trip(void **state)
{
    (void)state;
    make_directory("trip");
    make_directory("trip/elsewhere");
    write_text("trip/a b.obj", quad_obj);
    write_text("trip/m.obj", nomtl_obj);
    write_text("trip/s.luz",
               "seed = 3\n"
               "cube = 1, 2, 3 colour 0.5, 0.25, 0\n"
               "model = \"a b.obj\" at 0.5, 0, -1 scale 1.5 colour 1, 1, 0 "
               "texture \"x # y.png\" still\n"
               "cube = -1, 0, 0 texture \"my wood.png\"\n"
               "model = m.obj\n"
               "model = m.obj at 0, 0, 1e-3 scale 3\n");
    char path[1024], model_ab[1024], model_m[1024];
    work_path("trip/s.luz", path, sizeof path);
    work_path("trip/a b.obj", model_ab, sizeof model_ab);
    work_path("trip/m.obj", model_m, sizeof model_m);
    luz_options first;
    read_scene(&first, path);
    assert_int_equal(first.scene.object_count, 5);
    char *text = scene_text(&first);

    /* the models' lines hold their absolute paths, the first quoted */
    char line[2048];
    snprintf(line, sizeof line, "\nmodel = \"%s\" at 0.5, 0, -1 scale 1.5 colour 1, 1, 0 "
                                "texture \"x # y.png\" still\n", model_ab);
    assert_contains(text, line);
    snprintf(line, sizeof line, "\nmodel = %s\n", model_m);
    assert_contains(text, line);

    work_path("trip/elsewhere/saved.luz", path, sizeof path);
    write_text("trip/elsewhere/saved.luz", text);
    luz_options second;
    read_scene(&second, path);
    assert_int_equal(second.scene.object_count, first.scene.object_count);
    for (int i = 0; i < first.scene.object_count; i++) {
        const luz_object *a = &first.objects[i], *b = &second.objects[i];
        assert_memory_equal(&a->position, &b->position, sizeof a->position);
        assert_int_equal(a->has_colour, b->has_colour);
        assert_memory_equal(&a->colour, &b->colour, sizeof a->colour);
        assert_memory_equal(&a->scale, &b->scale, sizeof a->scale);
        assert_int_equal(a->still, b->still);
        assert_int_equal(a->texture, b->texture);
        const luz_object_source *sa = &first.object_sources[i], *sb = &second.object_sources[i];
        assert_int_equal(sa->model_path == NULL, sb->model_path == NULL);
        if (sa->model_path) assert_string_equal(sa->model_path, sb->model_path);
        assert_int_equal(sa->texture_name == NULL, sb->texture_name == NULL);
        if (sa->texture_name) assert_string_equal(sa->texture_name, sb->texture_name);
    }
    assert_string_equal(first.object_sources[1].model_path, model_ab);
    assert_string_equal(first.object_sources[1].texture_name, "x # y.png");
    assert_string_equal(first.object_sources[3].model_path, model_m);
    char *again = scene_text(&second);
    assert_string_equal(text, again);
    free(again);
    free(text);
    luz_options_free(&second);
    luz_options_free(&first);
}

/* ---- running luz-render ------------------------------------------------------------------ */

typedef struct run_result {
    int status;   /* the exit status, or 128 + signal */
    char *out;
    char *err;
} run_result;

/* Runs luz-render in the work directory with the NULL-terminated
 * arguments, stdout and stderr captured beside it; $LUZ_TEXTURES unset. */
static run_result run_render(const char *const *arguments)
{
    const char *program = getenv("LUZ_RENDER");
    if (program == NULL)
        fail_msg("LUZ_RENDER is not set (tests/meson.build sets it to luz-render's path)");
    char out_path[400], err_path[400];
    snprintf(out_path, sizeof out_path, "%s/stdout", root_directory);
    snprintf(err_path, sizeof err_path, "%s/stderr", root_directory);
    char *argv[64];
    int argc = 0;
    argv[argc++] = (char *)program;
    for (int i = 0; arguments[i] != NULL && argc < 63; i++) argv[argc++] = (char *)arguments[i];
    argv[argc] = NULL;

    fflush(NULL);
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        int out = open(out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int err = open(err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || chdir(work_directory) != 0 || dup2(out, STDOUT_FILENO) < 0 ||
            dup2(err, STDERR_FILENO) < 0)
            _exit(127);
        unsetenv("LUZ_TEXTURES");
        execv(program, argv);
        _exit(127);
    }
    int status;
    while (waitpid(child, &status, 0) < 0) assert_int_equal(errno, EINTR);
    run_result result;
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    result.out = read_file(out_path, NULL);
    result.err = read_file(err_path, NULL);
    assert_non_null(result.out);
    assert_non_null(result.err);
    return result;
}

static void run_result_free(run_result *result)
{
    free(result->out);
    free(result->err);
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

/* ---- bad input through luz-render (issue 11, item 7) ---------------------------------------- */

typedef struct refusal_case {
    const char *name;
    const char *model;       /* --model this (relative to work/), or NULL */
    const char *scene;       /* else the text of refusal.luz, read with --scene */
    const char *needles[3];  /* each in the one line; "@" stands for the model's absolute path */
} refusal_case;

static const refusal_case refusal_cases[] = {
    {"missing file", "models/nothere.obj", NULL, {"@", "No such file"}},
    {"directory", "models/folder.obj", NULL, {"@", "not a regular file"}},
    {"fifo", "models/fifo.obj", NULL, {"@", "not a regular file"}},
    {"random bytes, .obj", "models/noise.obj", NULL, {"@", "not a model"}},
    {"random bytes, unknown extension", "models/noise.xyz", NULL, {"@", "not a model"}},
    {"lines only", "models/lines.obj", NULL, {"@", "no triangles"}},
    /* assimp's own refusals of a file with nothing to draw, in luz's words
     * (issue 31: "Validation failed: Mesh  contains no faces" reached the
     * user) */
    {"PLY of one point", "models/point.ply", NULL,
     {"@", ": no triangles (only points or lines, or nothing)"}},
    {"STL without a facet", "models/empty.stl", NULL,
     {"@", ": no triangles (only points or lines, or nothing)"}},
    {"OBJ of one vertex", "models/vertex.obj", NULL,
     {"@", ": no triangles (only points or lines, or nothing)"}},
    {"OBJ of a comment", "models/comment.obj", NULL,
     {"@", ": not a model luz can read, or an empty one (no meshes in it)"}},
    {"NaN position", "models/nan.obj", NULL, {"@", "not finite"}},
    {"infinite position", "models/inf.obj", NULL, {"@", "not finite"}},
    {"NaN position in glTF", "models/nan.gltf", NULL, {"@", "not finite"}},
    {"index out of range", "models/range.obj", NULL, {"@"}},
    {"zero size", "models/zero.obj", NULL, {"@", "zero size"}},
    {"no triangle with an area", "models/flat.obj", NULL, {"@", "no triangle has an area"}},
    /* model lines: FILE:LINE, and for a file that will not load the file too */
    {"scene: bad model file", NULL, "# models\nsize = 96x64\nmodel = models/zero.obj\n",
     {"refusal.luz:3: model", "models/zero.obj", "zero size"}},
    {"scene: missing model file", NULL, "\n\nmodel = \"no such.obj\"\n",
     {"refusal.luz:3: model", "no such.obj"}},
    {"scene: at with two numbers", NULL, "# x\n\nmodel = models/quad.obj at 1 2\n",
     {"refusal.luz:3: model", "at x,y,z"}},
    {"scene: at with a blank", NULL, "model = models/quad.obj at 1, 2\n",
     {"refusal.luz:1: model", "at x,y,z"}},
    {"scene: at twice", NULL, "model = models/quad.obj at 1,2,3 at 1,2,3\n",
     {"refusal.luz:1: model", "at x,y,z"}},
    {"scene: scale 0", NULL, "seed = 1\nmodel = models/quad.obj scale 0\n",
     {"refusal.luz:2: model", "scale k"}},
    {"scene: scale -1", NULL, "model = models/quad.obj scale -1\n",
     {"refusal.luz:1: model", "scale k"}},
    {"scene: scale nan", NULL, "model = models/quad.obj scale nan\n",
     {"refusal.luz:1: model", "scale k"}},
    {"scene: scale beyond a float", NULL, "model = models/quad.obj scale 1e39\n",
     {"refusal.luz:1: model", "scale k"}},
    {"scene: scale missing", NULL, "model = models/quad.obj scale\n",
     {"refusal.luz:1: model", "scale k"}},
    {"scene: scale below the range", NULL, "model = models/quad.obj scale 0.0009\n",
     {"refusal.luz:1: model", "scale k", "[0.001, 10000]"}},
    {"scene: scale above the range", NULL, "model = models/quad.obj scale 10001\n",
     {"refusal.luz:1: model", "scale k", "[0.001, 10000]"}},
    {"scene: at beyond the range", NULL, "model = models/quad.obj at 0, 20000, 0\n",
     {"refusal.luz:1: model", "at x,y,z", "[-10000, 10000]"}},
    {"scene: still still", NULL, "model = models/quad.obj still still\n",
     {"refusal.luz:1: model", "still"}},
    {"scene: unknown word", NULL, "\nmodel = models/quad.obj shiny\n",
     {"refusal.luz:2: model", "shiny"}},
    {"scene: colour out of range", NULL, "model = models/quad.obj colour 2, 0, 0\n",
     {"refusal.luz:1: model", "colour"}},
    {"scene: texture without a name", NULL, "model = models/quad.obj texture\n",
     {"refusal.luz:1: model", "texture"}},
    {"scene: missing FILE", NULL, "model =\n", {"refusal.luz:1: model", "FILE"}},
    {"scene: FILE's quote not closed", NULL, "model = \"models/quad.obj at 1,2,3\n",
     {"refusal.luz:1: model", "closing"}},
    {"scene: texture not in the set", NULL, "model = models/quad.obj texture nothere.png\n",
     {"refusal.luz:1: model", "nothere.png"}},
};

/* Exit status 2, one line on stderr holding every needle, nothing on
 * stdout, and no file made. */
static void test_refusals_through_luz_render(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    for (size_t c = 0; c < sizeof refusal_cases / sizeof refusal_cases[0]; c++) {
        const refusal_case *test = &refusal_cases[c];
        char model_path[1024] = "";
        if (test->model) work_path(test->model, model_path, sizeof model_path);
        if (test->scene) write_text("refusal.luz", test->scene);
        static char before[65536], after[65536];
        before[0] = after[0] = '\0';
        list_tree(work_directory, "", before, sizeof before);
        run_result result =
            test->model ? run_render(ARGS("--model", test->model, "--size", "96x64", "-o",
                                          "refused.png"))
                        : run_render(ARGS("--scene", "refusal.luz", "--textures", "cubetex",
                                          "-o", "refused.png"));
        print_message("%s: %s", test->name, result.err);
        if (result.status != 2) fail_msg("%s: exit status %d, expected 2", test->name, result.status);
        const char *newline = strchr(result.err, '\n');
        if (newline == NULL || newline[1] != '\0')
            fail_msg("%s: expected one line on stderr, got '%s'", test->name, result.err);
        assert_string_equal(result.out, "");
        for (int n = 0; n < 3 && test->needles[n] != NULL; n++)
            assert_contains(result.err, strcmp(test->needles[n], "@") == 0 ? model_path
                                                                           : test->needles[n]);
        list_tree(work_directory, "", after, sizeof after);
        assert_string_equal(before, after);
        run_result_free(&result);
    }
    char path[1024];
    work_path("refusal.luz", path, sizeof path);
    unlink(path);
}

/* ---- missing and corrupt textures through luz-render (issue 27) ------------------------------ */

/* The lines of text, each ending in '\n', counted; 0 if the text does not
 * end in one. */
static int count_lines(const char *text)
{
    int lines = 0;
    for (const char *c = text; *c; c++) lines += *c == '\n';
    return text[0] && text[strlen(text) - 1] != '\n' ? 0 : lines;
}

/* The bytes of work/name (which must exist), for comparing two images. */
static char *work_file(const char *name, size_t *length)
{
    char path[1024];
    work_path(name, path, sizeof path);
    char *bytes = read_file(path, length);
    if (bytes == NULL) fail_msg("%s: not written", name);
    return bytes;
}

static void assert_same_files(const char *a, const char *b)
{
    size_t length_a, length_b;
    char *bytes_a = work_file(a, &length_a), *bytes_b = work_file(b, &length_b);
    if (length_a != length_b || memcmp(bytes_a, bytes_b, length_a) != 0)
        fail_msg("%s and %s differ", a, b);
    free(bytes_a);
    free(bytes_b);
}

static void remove_work_file(const char *name)
{
    char path[1024];
    work_path(name, path, sizeof path);
    unlink(path);
}

/* twobad.obj names a texture that is not there and one that is not a PNG:
 * exit 0, one warning line for each naming the model and the texture,
 * and the same image as its twin that names no texture (both quads drawn
 * with T = 1 in their materials' colours). A `colour` or `texture` on a
 * scene file's model line applies to it as to the twin, and with a
 * texture of the line's own there is nothing to warn about. */
static void test_missing_textures_through_luz_render(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    char model[1024];
    work_path("models/twobad.obj", model, sizeof model);
    run_result bad = run_render(ARGS("--model", "models/twobad.obj", "--size", "64x48", "-o",
                                     "twobad.png"));
    run_result plain = run_render(ARGS("--model", "models/twoplain.obj", "--size", "64x48",
                                       "-o", "twoplain.png"));
    print_message("%s", bad.err);
    assert_int_equal(bad.status, 0);
    assert_int_equal(plain.status, 0);
    assert_string_equal(plain.err, "");
    assert_int_equal(count_lines(bad.err), 2);
    const char *second = strchr(bad.err, '\n') + 1;
    assert_true(strncmp(bad.err, "luz: warning: ", 14) == 0);
    assert_true(strncmp(second, "luz: warning: ", 14) == 0);
    assert_contains(bad.err, model);
    assert_contains(second, model);
    assert_true(strstr(bad.err, "'tex/gone.png'") < second);   /* the first line's */
    assert_contains(second, "'tex/bad.png'");
    assert_same_files("twobad.png", "twoplain.png");
    /* the quads are in the picture: its centre row is not all clear colour */
    int width, height, channels;
    char path[1024];
    work_path("twobad.png", path, sizeof path);
    unsigned char *pixels = stbi_load(path, &width, &height, &channels, 4);
    assert_non_null(pixels);
    int clear = 0;
    for (int x = 0; x < width; x++) {
        const unsigned char *p = pixels + ((size_t)(height / 2) * width + x) * 4;
        clear += p[0] == pixels[0] && p[1] == pixels[1] && p[2] == pixels[2];
    }
    assert_true(clear < width / 2);
    stbi_image_free(pixels);
    run_result_free(&bad);
    run_result_free(&plain);

    static const char *const lines[] = {"colour 0.9, 0.1, 0.2", "texture w.png"};
    for (size_t l = 0; l < sizeof lines / sizeof lines[0]; l++) {
        char text[256];
        snprintf(text, sizeof text, "size = 64x48\nmodel = models/twobad.obj %s\n", lines[l]);
        write_text("bad.luz", text);
        snprintf(text, sizeof text, "size = 64x48\nmodel = models/twoplain.obj %s\n", lines[l]);
        write_text("plain.luz", text);
        bad = run_render(ARGS("--scene", "bad.luz", "--textures", "cubetex", "-o", "bad.png"));
        plain = run_render(ARGS("--scene", "plain.luz", "--textures", "cubetex", "-o",
                                "plain.png"));
        assert_int_equal(bad.status, 0);
        assert_int_equal(plain.status, 0);
        assert_int_equal(count_lines(bad.err), l == 0 ? 2 : 0);
        assert_same_files("bad.png", "plain.png");
        /* and the line changed the picture */
        size_t length_a, length_b;
        char *a = work_file("bad.png", &length_a), *b = work_file("twoplain.png", &length_b);
        assert_false(length_a == length_b && memcmp(a, b, length_a) == 0);
        free(a);
        free(b);
        run_result_free(&bad);
        run_result_free(&plain);
    }
    static const char *const made[] = {"twobad.png", "twoplain.png", "bad.png", "plain.png",
                                       "bad.luz", "plain.luz"};
    for (size_t i = 0; i < sizeof made / sizeof made[0]; i++) remove_work_file(made[i]);
}

/* luz-render and --model-files: the `..` case warns (one line naming the
 * file and the rule) and draws the triangle untextured, as a missing
 * texture; anywhere, from the command line or a scene file, draws the
 * outside texture without a word, and -o may not then replace it; a
 * value other than folder or anywhere is refused. */
static void test_model_files_through_luz_render(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    char secret[1024];
    work_path("outside/secret.png", secret, sizeof secret);
    run_result folder = run_render(ARGS("--model", "models/confine/dotdot.obj", "--size", "48x32",
                                        "-o", "folder.png"));
    assert_int_equal(folder.status, 0);
    assert_int_equal(count_lines(folder.err), 1);
    assert_contains(folder.err, "luz: warning: ");
    assert_contains(folder.err, "outside/secret.png");
    assert_contains(folder.err, "unless --model-files anywhere");
    run_result anywhere = run_render(ARGS("--model", "models/confine/dotdot.obj", "--size",
                                          "48x32", "--model-files", "anywhere", "-o",
                                          "anywhere.png"));
    assert_int_equal(anywhere.status, 0);
    assert_string_equal(anywhere.err, "");
    write_text("anywhere.luz", "size = 48x32\nmodel-files = anywhere\n"
                               "model = models/confine/dotdot.obj\n");
    run_result scene = run_render(ARGS("--scene", "anywhere.luz", "-o", "scene.png"));
    assert_int_equal(scene.status, 0);
    assert_string_equal(scene.err, "");
    assert_same_files("anywhere.png", "scene.png");
    size_t length_a, length_b;
    char *a = work_file("folder.png", &length_a), *b = work_file("anywhere.png", &length_b);
    assert_false(length_a == length_b && memcmp(a, b, length_a) == 0);
    free(a);
    free(b);
    run_result_free(&folder);
    run_result_free(&anywhere);
    run_result_free(&scene);

    run_result replace = run_render(ARGS("--model", "models/confine/dotdot.obj",
                                         "--model-files", "anywhere", "-o", secret));
    assert_int_equal(replace.status, 2);
    assert_contains(replace.err, "is a texture of a model this run reads");
    run_result_free(&replace);
    run_result bad = run_render(ARGS("--model", "models/confine/dotdot.obj", "--model-files",
                                     "everywhere", "-o", "bad.png"));
    assert_int_equal(bad.status, 2);
    assert_int_equal(count_lines(bad.err), 1);
    assert_contains(bad.err, "--model-files: expected folder or anywhere");
    run_result_free(&bad);
    static const char *const made[] = {"folder.png", "anywhere.png", "scene.png",
                                       "anywhere.luz"};
    for (size_t i = 0; i < sizeof made / sizeof made[0]; i++) remove_work_file(made[i]);
}

/* Debian's assimp-testmodels: files that name their author's disk
 * (spider.fbx: D:\projects\...\drkwood2.jpg and three more) or a
 * texture not shipped beside them (cube_with_diffuse_texture.3DS:
 * TEST.PNG) are drawn, with a warning naming each texture once. */
static void test_corpus_files_with_missing_textures(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    static const struct {
        const char *file, *texture;
        int warnings;
    } cases[] = {
        {"/usr/share/assimp/models/FBX/spider.fbx", "drkwood2.jpg'", 4},
        {"/usr/share/assimp/models/3DS/cube_with_diffuse_texture.3DS", "'TEST.PNG'", 1},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        if (access(cases[c].file, R_OK) != 0) {
            print_message("skipped: %s is not installed (Debian's assimp-testmodels)\n",
                          cases[c].file);
            continue;
        }
        run_result result = run_render(ARGS("--model", cases[c].file, "--size", "64x48", "-o",
                                            "corpus.png"));
        print_message("%s", result.err);
        assert_int_equal(result.status, 0);
        assert_int_equal(count_lines(result.err), cases[c].warnings);
        for (const char *line = result.err; *line; line = strchr(line, '\n') + 1) {
            assert_true(strncmp(line, "luz: warning: ", 14) == 0);
            assert_true(strncmp(line + 14, cases[c].file, strlen(cases[c].file)) == 0);
        }
        assert_contains(result.err, cases[c].texture);
        size_t length;
        free(work_file("corpus.png", &length));
        remove_work_file("corpus.png");
        run_result_free(&result);
    }
}

/* An OBJ of 9 vertices and a million faces, each "f a b c" of single
 * digits (8 bytes a face: the densest triangles an OBJ holds), 8 MB that
 * assimp needs about 1.1 GB of address space to read. */
static void write_face_dense_obj(const char *name)
{
    static const char corners[8][4] = {"125", "154", "236", "265", "458", "487", "569", "598"};
    const size_t faces = 1000000;
    char *text = malloc(200 + faces * 8);
    assert_non_null(text);
    size_t length = 0;
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 3; x++)
            length += (size_t)sprintf(text + length, "v %d %d %d\n", x, y, (x * y) % 2);
    for (size_t f = 0; f < faces; f++) {
        const char *c = corners[f % 8];
        memcpy(text + length, (char[8]){'f', ' ', c[0], ' ', c[1], ' ', c[2], '\n'}, 8);
        length += 8;
    }
    write_bytes(name, text, length);
    free(text);
}

/* A model over its memory limit is refused as such, naming the flag that
 * raises it, exit 2 and one line, whether assimp's allocation failed
 * cleanly (64 MiB: std::bad_alloc) or it crashed at the limit (256 MiB: a
 * failed mmap, then SIGSEGV, reported as "crashed" before the child told
 * the two apart); given enough (4096 MiB), the same file draws. The scene
 * file's key does the same; values outside 64 to 1048576 are refused.
 * Builds with AddressSanitizer or ThreadSanitizer set no memory limit:
 * there only the refused values are checked. */
static void test_model_memory_limit(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    static const struct {
        const char *value, *expected;
    } bad[] = {
        {"63", "luz-render: --model-memory: expected an integer from 64 to 1048576, got '63'\n"},
        {"lots", "luz-render: --model-memory: expected an integer from 64 to 1048576, got "
                 "'lots'\n"},
    };
    for (size_t b = 0; b < sizeof bad / sizeof bad[0]; b++) {
        run_result result = run_render(ARGS("--model", "models/quad.obj", "--model-memory",
                                            bad[b].value, "-o", "memory.png"));
        assert_int_equal(result.status, 2);
        assert_string_equal(result.err, bad[b].expected);
        run_result_free(&result);
    }
    write_text("memory.luz", "model-memory = 0\nmodel = models/quad.obj\n");
    run_result scene = run_render(ARGS("--scene", "memory.luz", "-o", "memory.png"));
    assert_int_equal(scene.status, 2);
    assert_int_equal(count_lines(scene.err), 1);
    assert_contains(scene.err, "memory.luz:1: model-memory: expected an integer from 64 to 1048576");
    run_result_free(&scene);
    if (luz_model_limits_for(1).memory_bytes == 0) {
        print_message("skipped: no memory limit under the sanitizers\n");
        remove_work_file("memory.luz");
        return;
    }

    write_face_dense_obj("models/dense.obj");
    char model[1024];
    work_path("models/dense.obj", model, sizeof model);
    static const char *const limits[] = {"64", "256"};
    for (size_t l = 0; l < 2; l++) {
        run_result result = run_render(ARGS("--model", "models/dense.obj", "--model-memory",
                                            limits[l], "--size", "32x32", "-o", "memory.png"));
        char expected[1400];
        snprintf(expected, sizeof expected, "luz-render: %s: assimp needs more than %s MiB to "
                                             "read it (its memory limit; --model-memory MiB "
                                             "raises it)\n", model, limits[l]);
        assert_int_equal(result.status, 2);
        assert_string_equal(result.err, expected);
        run_result_free(&result);
    }
    write_text("memory.luz", "model-memory = 256\nsize = 32x32\nmodel = models/dense.obj\n");
    scene = run_render(ARGS("--scene", "memory.luz", "-o", "memory.png"));
    assert_int_equal(scene.status, 2);
    assert_int_equal(count_lines(scene.err), 1);
    assert_contains(scene.err, "assimp needs more than 256 MiB to read it (its memory limit; "
                               "--model-memory MiB raises it)");
    run_result_free(&scene);
    char path[1024];
    work_path("memory.png", path, sizeof path);
    assert_int_equal(access(path, F_OK), -1);

    run_result enough = run_render(ARGS("--model", "models/dense.obj", "--model-memory", "4096",
                                        "--size", "32x32", "-o", "memory.png"));
    assert_int_equal(enough.status, 0);
    assert_string_equal(enough.err, "");
    run_result_free(&enough);
    remove_work_file("memory.png");
    remove_work_file("memory.luz");
    remove_work_file("models/dense.obj");
}

/* assimp's glTF importer drops a face that names a vertex past the end and
 * says so only in its log: luz refuses the model (SCENE.md: an index out
 * of range is an error), exit 2, one line naming the file; the same quad
 * with its indices in range draws. So does the corpus's
 * glTF2/IndexOutOfRange.gltf (a cube with one face dropped), when
 * installed. */
static void test_gltf_index_out_of_range(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    run_result sound = run_render(ARGS("--model", "models/quad.gltf", "--size", "32x32", "-o",
                                       "quad.png"));
    assert_int_equal(sound.status, 0);
    assert_string_equal(sound.err, "");
    run_result_free(&sound);
    remove_work_file("quad.png");
    static const char corpus[] = "/usr/share/assimp/models/glTF2/IndexOutOfRange/"
                                 "IndexOutOfRange.gltf";
    char model[1024];
    work_path("models/outofrange.gltf", model, sizeof model);
    const char *files[] = {model, corpus};
    for (size_t f = 0; f < 2; f++) {
        if (access(files[f], R_OK) != 0) {
            print_message("skipped: %s is not installed (Debian's assimp-testmodels)\n",
                          files[f]);
            continue;
        }
        run_result result = run_render(ARGS("--model", files[f], "--size", "32x32", "-o",
                                            "range.png"));
        assert_int_equal(result.status, 2);
        assert_int_equal(count_lines(result.err), 1);
        char expected[1200];
        snprintf(expected, sizeof expected, "luz-render: %s: ", files[f]);
        assert_true(strncmp(result.err, expected, strlen(expected)) == 0);
        assert_contains(result.err, "out of range");
        char path[1024];
        work_path("range.png", path, sizeof path);
        assert_int_equal(access(path, F_OK), -1);
        run_result_free(&result);
    }
}

/* -o naming a model or a file it read is refused (exit 2, one line
 * saying which input it is) and the file stays as it was: the image would
 * have replaced it. models/two.obj reads models/two.mtl (through assimp),
 * models/tex/a.png and, as .\tex\b.png, models/tex/b.png;
 * models/external.gltf reads its buffer, models/external.bin. */
static void test_output_is_never_a_model_input(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    static const struct {
        const char *model, *output, *expected;
    } cases[] = {
        {"models/two.obj", "models/two.obj",
         "luz-render: -o: models/two.obj: is a model this run reads (@); "
         "expected an output file that is none of its inputs\n"},
        {"models/two.obj", "models/two.mtl",
         "luz-render: -o: models/two.mtl: is a file of a model this run reads (@/../two.mtl); "
         "expected an output file that is none of its inputs\n"},
        {"models/external.gltf", "models/external.bin",
         "luz-render: -o: models/external.bin: is a file of a model this run reads "
         "(@/../external.bin); expected an output file that is none of its inputs\n"},
        {"models/external.gltf", "models/./external.bin",
         "luz-render: -o: models/./external.bin: is a file of a model this run reads "
         "(@/../external.bin)"},
        {"models/two.obj", "models/tex/a.png",
         "luz-render: -o: models/tex/a.png: is a texture of a model this run reads "
         "(@/../tex/a.png)"},
        {"models/two.obj", "models/./tex/b.png",
         "luz-render: -o: models/./tex/b.png: is a texture of a model this run reads "
         "(@/../tex/b.png)"},
    };
    char directory[1024];
    work_path("models", directory, sizeof directory);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char model[1024], path[1024], expected[4096] = "";
        work_path(cases[c].model, model, sizeof model);
        work_path(cases[c].output, path, sizeof path);
        /* "@" is the model's absolute path; "@/.." its directory's */
        const char *at = strchr(cases[c].expected, '@');
        const bool directory_part = strncmp(at, "@/../", 5) == 0;
        snprintf(expected, sizeof expected, "%.*s%s%s", (int)(at - cases[c].expected),
                 cases[c].expected, directory_part ? directory : model,
                 directory_part ? at + 4 : at + 1);
        size_t length_before, length_after;
        char *before = read_file(path, &length_before);
        assert_non_null(before);
        run_result result = run_render(ARGS("--model", cases[c].model, "--size", "32x32", "-o",
                                            cases[c].output));
        assert_int_equal(result.status, 2);
        if (strncmp(result.err, expected, strlen(expected)) != 0)
            fail_msg("-o %s: stderr '%s', expected '%s'", cases[c].output, result.err, expected);
        char *after = read_file(path, &length_after);
        assert_int_equal(length_after, length_before);
        assert_memory_equal(after, before, length_before);
        free(before);
        free(after);
        run_result_free(&result);
    }
}

/* A file that cannot be read. Root reads every file whatever its mode, so
 * the case is left to other users. */
static void test_unreadable_model(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    if (geteuid() == 0) {
        print_message("skipped: root reads a file whatever its mode\n");
        skip();
    }
    write_text("models/locked.obj", nomtl_obj);
    char path[1024];
    work_path("models/locked.obj", path, sizeof path);
    assert_int_equal(chmod(path, 0), 0);
    run_result result = run_render(ARGS("--model", "models/locked.obj", "-o", "locked.png"));
    assert_int_equal(result.status, 2);
    assert_contains(result.err, path);
    assert_non_null(strchr(result.err, '\n'));
    assert_true(strchr(result.err, '\n')[1] == '\0');
    work_path("locked.png", path, sizeof path);
    assert_int_equal(access(path, F_OK), -1);
    run_result_free(&result);
}

/* ---- the views and options on a model (issue 11, item 8) ------------------------------------ */

typedef struct image {
    int width, height;
    unsigned char *pixels;   /* RGB */
} image;

static image render_image(const char *const *arguments, const char *output)
{
    run_result result = run_render(arguments);
    if (result.status != 0 || result.err[0] != '\0')
        fail_msg("luz-render exited %d: %s", result.status, result.err);
    run_result_free(&result);
    char path[1024];
    work_path(output, path, sizeof path);
    image picture;
    int channels;
    picture.pixels = stbi_load(path, &picture.width, &picture.height, &channels, 3);
    if (picture.pixels == NULL) fail_msg("%s: %s", output, stbi_failure_reason());
    assert_int_equal(picture.width, 96);
    assert_int_equal(picture.height, 64);
    return picture;
}

static int pixels_differing(const image *a, const image *b)
{
    int count = 0;
    for (int i = 0; i < a->width * a->height; i++)
        count += memcmp(a->pixels + 3 * i, b->pixels + 3 * i, 3) != 0;
    return count;
}


/* --probe on two.obj: its quad and its triangle land, at t = 0 in a
 * 64x36 image, on pixels (21, 23) and (42, 20) (the model scaled by 2/3
 * about (1.5, 1, -0.5), seen from (0, 0, 3) with 45 degrees: worked out
 * by hand). The probe names the file, each mesh and its material, and the
 * texture as the material names it, Windows path and all; bytes= is the
 * PNG's pixel. */
/* --probe on a pixel whose normal is NaN: the probe prints "nan" where
 * its numbers would be (it crashed writing NaN as digits) and still finds
 * the mesh triangle: the quad's upper-left half (its second, 1 3 4) at
 * the pixel left of and above the centre of the 64x36 image. */
static void test_probe_of_nan_normals(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    run_result result = run_render(ARGS("--model", "models/nan-normal.obj", "--size", "64x36",
                                        "--textures", "none", "--probe", "28,16", "-o",
                                        "nan-probe.png"));
    if (result.status != 0 || result.err[0] != '\0')
        fail_msg("luz-render exited %d: %s", result.status, result.err);
    char value[256];
    assert_string_equal(key_value(result.out, "N", value, sizeof value), "nan,nan,nan");
    assert_string_equal(key_value(result.out, "primitive", value, sizeof value), "1");
    run_result_free(&result);
}

static void test_probe_names_a_model(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    static const struct {
        const char *pixel, *mesh, *mesh_name, *material, *texture, *colour;
    } expected[2] = {
        {"21,23", "0", "first", "warm", "tex/a.png", "0.75,0.5,0.25"},
        {"42,20", "1", "second", "cold", ".\\tex\\b.png", "0.125,0.25,1"},
    };
    for (int i = 0; i < 2; i++) {
        run_result result = run_render(ARGS("--model", "models/two.obj", "--size", "64x36",
                                            "--textures", "none", "--probe", expected[i].pixel,
                                            "-o", "probe.png"));
        if (result.status != 0 || result.err[0] != '\0')
            fail_msg("luz-render exited %d: %s", result.status, result.err);
        char value[256];
        assert_string_equal(key_value(result.out, "object", value, sizeof value), "0");
        assert_string_equal(key_value(result.out, "model", value, sizeof value), "two.obj");
        assert_string_equal(key_value(result.out, "mesh", value, sizeof value), expected[i].mesh);
        assert_string_equal(key_value(result.out, "mesh_name", value, sizeof value),
                            expected[i].mesh_name);
        assert_string_equal(key_value(result.out, "material", value, sizeof value),
                            expected[i].material);
        assert_string_equal(key_value(result.out, "texture", value, sizeof value),
                            expected[i].texture);
        assert_string_equal(key_value(result.out, "C", value, sizeof value),
                            expected[i].colour);
        char path[1024];
        work_path("probe.png", path, sizeof path);
        int width, height, channels, x, y;
        unsigned char *pixels = stbi_load(path, &width, &height, &channels, 3);
        assert_non_null(pixels);
        assert_int_equal(sscanf(expected[i].pixel, "%d,%d", &x, &y), 2);
        const unsigned char *p = pixels + ((size_t)y * width + x) * 3;
        char bytes[64];
        snprintf(bytes, sizeof bytes, "%u,%u,%u", p[0], p[1], p[2]);
        assert_string_equal(key_value(result.out, "bytes", value, sizeof value), bytes);
        stbi_image_free(pixels);
        run_result_free(&result);
    }
}

/* The box, turned at t = 2, and the same scene with the box out of sight
 * (behind the camera), small; the textures directory plays no part. */
#define BOX "--model", "box/box.obj", "--size", "96x64", "--time", "2", "--textures", "none"
#define AWAY "--scene", "box/away.luz", "--size", "96x64", "--time", "2", "--textures", "none"

/* The box (a third of the picture's height or more) must change many
 * pixels; a bug that drew nothing, or only an edge, changes few. */
#define MANY_PIXELS 400

static bool same_file(const char *a, const char *b)
{
    char path_a[1024], path_b[1024];
    work_path(a, path_a, sizeof path_a);
    work_path(b, path_b, sizeof path_b);
    size_t length_a, length_b;
    char *data_a = read_file(path_a, &length_a), *data_b = read_file(path_b, &length_b);
    assert_non_null(data_a);
    assert_non_null(data_b);
    bool same = length_a == length_b && memcmp(data_a, data_b, length_a) == 0;
    free(data_a);
    free(data_b);
    return same;
}

/* The box bigger, 384x256: sixteen bands of rows, so that the other
 * threads take some of them (at 96x64 the calling thread often draws all
 * four before the others wake). */
#define BIG_BOX "--model", "box/box.obj", "--size", "384x256", "--time", "2", "--textures", "none"

/* The same bytes on 1 and 3 threads, with one more option. */
static void assert_same_on_threads(const char *option, const char *value)
{
    run_result one = run_render(ARGS(BIG_BOX, option, value, "--threads", "1", "-o", "t1.png"));
    run_result three = run_render(ARGS(BIG_BOX, option, value, "--threads", "3", "-o", "t3.png"));
    if (one.status != 0 || three.status != 0)
        fail_msg("%s %s: exit %d and %d: %s%s", option, value, one.status, three.status, one.err,
                 three.err);
    if (!same_file("t1.png", "t3.png"))
        fail_msg("%s %s: 1 and 3 threads give different files", option, value);
    run_result_free(&one);
    run_result_free(&three);
}

/* Each view drawn with the box, against the same view with the box out of
 * sight (behind the camera): the box must show. And each view but the
 * colour one must differ from the colour image. The same bytes on 1 and 3
 * threads (bigger), but for the bands view, whose colours say which thread
 * drew a band. */
static void test_views_on_a_model(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    write_text("box/away.luz", "model = box.obj at 0, 0, 50\n");
    static const char *const views[] = {"color", "depth", "normals", "uv", "mip",
                                        "overdraw", "bands", "triangles"};
    image colour = {0};
    for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
        image shown = render_image(ARGS(BOX, "--view", views[v],
                                        "--threads", "1", "-o", "view1.png"),
                                   "view1.png");
        image away = render_image(ARGS(AWAY, "--view", views[v],
                                       "--threads", "1", "-o", "away.png"),
                                  "away.png");
        const int changed = pixels_differing(&shown, &away);
        print_message("view %s: %d pixels show the box\n", views[v], changed);
        if (changed < MANY_PIXELS)
            fail_msg("view %s: only %d pixels differ from the empty view", views[v], changed);
        if (v == 0) {
            colour = shown;
        } else {
            const int from_colour = pixels_differing(&shown, &colour);
            if (from_colour < MANY_PIXELS)
                fail_msg("view %s: only %d pixels differ from the colour view", views[v],
                         from_colour);
            free(shown.pixels);
        }
        free(away.pixels);
        if (strcmp(views[v], "bands") != 0) assert_same_on_threads("--view", views[v]);
    }
    free(colour.pixels);
}

/* --only TERM: the box lit by one term differs from the empty picture
 * and from the box under all six; --filter: the 64x64 checker drawn
 * smaller than itself comes out differently from each filter; --interp
 * affine bends the textures of the turned box. Each the same on 1 and 3
 * threads. */
/* The box of pixels that are not the background (26, 26, 26). */
static void covered_box(const image *picture, int *width, int *height)
{
    int low_x = picture->width, high_x = -1, low_y = picture->height, high_y = -1;
    for (int y = 0; y < picture->height; y++)
        for (int x = 0; x < picture->width; x++) {
            const unsigned char *p = picture->pixels + 3 * (y * picture->width + x);
            if (p[0] == 26 && p[1] == 26 && p[2] == 26) continue;
            if (x < low_x) low_x = x;
            if (x > high_x) high_x = x;
            if (y < low_y) low_y = y;
            if (y > high_y) high_y = y;
        }
    *width = high_x - low_x + 1;
    *height = high_y - low_y + 1;
}

/* --up through luz-render, on box.obj (2 wide in x, 1 tall in y, 1.5 deep
 * in z) at t = 0, facing the camera: y draws it 2 wide and 1 tall; z
 * turns its depth up (x, z, -y), 2 wide and 1.5 tall; x stands its width
 * up (-y, x, z), 1 wide and 2 tall; -y (-x, -y, z) keeps the sizes. And
 * `up AXIS` on a model line gives --up's bytes. */
static void test_up_axis_through_luz_render(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    static const char *const axes[] = {"y", "z", "x", "-y"};
    int widths[4], heights[4];
    for (int i = 0; i < 4; i++) {
        image turned = render_image(ARGS(BOX, "--time", "0", "--up", axes[i], "-o", "up.png"),
                                    "up.png");
        covered_box(&turned, &widths[i], &heights[i]);
        print_message("--up %s: %d x %d pixels\n", axes[i], widths[i], heights[i]);
        char scene[96];
        snprintf(scene, sizeof scene, "model = box.obj up %s\n", axes[i]);
        write_text("box/up.luz", scene);
        image line = render_image(ARGS("--scene", "box/up.luz", "--size", "96x64", "--time", "0",
                                       "--textures", "none", "-o", "line.png"),
                                  "line.png");
        assert_int_equal(pixels_differing(&turned, &line), 0);
        free(turned.pixels);
        free(line.pixels);
    }
    /* y: twice as wide as tall (68 x 34); z: still wider than tall, but
     * 1.5 / 1 taller (62 x 46: its front face, 0.5 from the centre instead
     * of 0.75, is a little farther); x: twice as tall as wide (34 x 64,
     * the top and bottom rows cut); -y: y's sizes. */
    assert_true(10 * widths[0] > 17 * heights[0]);
    assert_true(heights[1] > heights[0] + 8 && heights[1] < widths[1]);
    assert_true(10 * heights[2] > 17 * widths[2]);
    assert_int_equal(widths[3], widths[0]);
    assert_int_equal(heights[3], heights[0]);
}

static void test_options_on_a_model(void **state)
{
    (void)state;
    REQUIRE_MODELS();
    write_text("box/away.luz", "model = box.obj at 0, 0, 50\n");
    image all = render_image(ARGS(BOX, "-o", "all.png"),
                             "all.png");
    image away = render_image(ARGS(AWAY, "-o", "away.png"),
                              "away.png");
    assert_true(pixels_differing(&all, &away) >= MANY_PIXELS);
    static const char *const terms[] = {"ambient", "diffuse", "specular",
                                        "point", "spot", "directional"};
    for (size_t t = 0; t < sizeof terms / sizeof terms[0]; t++) {
        image one = render_image(ARGS(BOX, "--only", terms[t], "-o", "one.png"),
                                 "one.png");
        const int from_away = pixels_differing(&one, &away);
        const int from_all = pixels_differing(&one, &all);
        print_message("--only %s: %d pixels differ from the empty picture, %d from all six\n",
                      terms[t], from_away, from_all);
        if (from_away < MANY_PIXELS || from_all < MANY_PIXELS)
            fail_msg("--only %s: %d pixels from the empty picture, %d from all six", terms[t],
                     from_away, from_all);
        free(one.pixels);
    }

    static const char *const filters[] = {"nearest", "bilinear", "trilinear"};
    image filtered[3];
    for (int f = 0; f < 3; f++) {
        filtered[f] = render_image(ARGS(BOX, "--filter", filters[f], "-o", "filter.png"),
                                   "filter.png");
        assert_true(pixels_differing(&filtered[f], &away) >= MANY_PIXELS);
    }
    for (int f = 0; f < 3; f++) {
        const int differ = pixels_differing(&filtered[f], &filtered[(f + 1) % 3]);
        print_message("--filter %s and %s: %d pixels differ\n", filters[f],
                      filters[(f + 1) % 3], differ);
        if (differ < 100)
            fail_msg("--filter %s and %s: only %d pixels differ", filters[f],
                     filters[(f + 1) % 3], differ);
    }
    /* the default is trilinear */
    assert_int_equal(pixels_differing(&filtered[2], &all), 0);
    for (int f = 0; f < 3; f++) free(filtered[f].pixels);

    image affine = render_image(ARGS(BOX, "--interp", "affine", "-o", "affine.png"),
                                "affine.png");
    assert_true(pixels_differing(&affine, &away) >= MANY_PIXELS);
    const int bent = pixels_differing(&affine, &all);
    print_message("--interp affine: %d pixels differ from perspective\n", bent);
    if (bent < 100) fail_msg("--interp affine: only %d pixels differ from perspective", bent);
    free(affine.pixels);

    assert_same_on_threads("--interp", "affine");
    assert_same_on_threads("--filter", "nearest");
    assert_same_on_threads("--only", "spot");
    free(all.pixels);
    free(away.pixels);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_obj_two_meshes_with_materials),
        cmocka_unit_test(test_obj_shared_texture),
        cmocka_unit_test(test_obj_without_uvs_has_no_texture),
        cmocka_unit_test(test_obj_without_materials_has_no_colour),
        cmocka_unit_test(test_quad_becomes_two_triangles),
        cmocka_unit_test(test_degenerate_triangle_beside_others),
        cmocka_unit_test(test_ply_and_stl),
        cmocka_unit_test(test_gltf_embedded_texture),
        cmocka_unit_test(test_glb_embedded_texture),
        cmocka_unit_test(test_load_refusals),
        cmocka_unit_test(test_missing_or_corrupt_texture_is_a_warning),
        cmocka_unit_test(test_textures_confined_to_the_folder),
        cmocka_unit_test(test_textures_confined_without_openat2),
        cmocka_unit_test(test_normalisation),
        cmocka_unit_test(test_up_axis_turns_then_normalises),
        cmocka_unit_test(test_model_matrix),
        cmocka_unit_test(test_colour_precedence),
        cmocka_unit_test(test_texture_precedence),
        cmocka_unit_test(test_cubes_and_models_in_order),
        cmocka_unit_test(test_scene_model_fields),
        cmocka_unit_test(test_scene_round_trip),
        cmocka_unit_test(test_refusals_through_luz_render),
        cmocka_unit_test(test_unreadable_model),
        cmocka_unit_test(test_output_is_never_a_model_input),
        cmocka_unit_test(test_missing_textures_through_luz_render),
        cmocka_unit_test(test_corpus_files_with_missing_textures),
        cmocka_unit_test(test_model_files_through_luz_render),
        cmocka_unit_test(test_gltf_index_out_of_range),
        cmocka_unit_test(test_model_memory_limit),
        cmocka_unit_test(test_views_on_a_model),
        cmocka_unit_test(test_probe_names_a_model),
        cmocka_unit_test(test_probe_of_nan_normals),
        cmocka_unit_test(test_options_on_a_model),
        cmocka_unit_test(test_up_axis_through_luz_render),
    };
    return cmocka_run_group_tests(tests, setup_files, teardown_files);
}
