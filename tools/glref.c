/*
 * glref: SCENE.md's scene through OpenGL 3.3 core on Mesa's llvmpipe.
 *
 * This is the reference luz is measured against, picture for picture
 * (tools/conformance) and millisecond for millisecond (tools/bench). It
 * renders headless, on EGL's surfaceless platform into a framebuffer object
 * (RGBA8 colour, 24-bit depth), and takes luz-render's options through the
 * library's own parser, so the two programs are always asked the same thing:
 *
 *   glref --size 640x360 --time 2 -o gl.png
 *   glref --bench 20 --threads 1          (llvmpipe's LP_NUM_THREADS=1)
 *   glref --samples 4 --model cow.ply     (4x MSAA; neutral at EV -1)
 *   glref --check-samples                 (llvmpipe's 4 sample positions)
 *
 * What it shares with luz, and what it deliberately does not:
 *
 *   - shared: option parsing, the scene's parameters (defaults, the tiled
 *     cube positions, the seeded colours) and the texture files with their
 *     mip chains, which SCENE.md defines to the bit;
 *   - its own: the cube's vertices (copied from SCENE.md's table), every
 *     transform (camera front, lookAt, perspective, the cubes' rotation, the
 *     orbits, the normal matrix), written here in double precision, and the
 *     fragment shader, GLSL that follows SCENE.md's equations line by line.
 *     A mistake in luz's math therefore shows up as a difference instead of
 *     hiding in both renderers.
 *   - models (SCENE.md, "Models"): glref reads the files with assimp's C API
 *     itself, with the contract's post-processing steps, and computes the
 *     bounds, the normalisation, the placement and each mesh's colour and
 *     texture on its own; of luz it uses only the image decoder for the
 *     textures the materials name (files, or embedded ones from memory).
 *
 * Making the two images comparable pixel for pixel:
 *
 *   - luz's row 0 is the top, OpenGL's window origin is the bottom-left.
 *     The vertex shader negates clip-space y, so GL's row 0 (the first row
 *     glReadPixels returns) is luz's row 0 and the rasteriser sees the very
 *     geometry luz sees (flipping the rows afterwards would mirror the fill
 *     rule's ties on horizontal edges). Mirroring y turns counter-clockwise
 *     into clockwise, hence glFrontFace(GL_CW).
 *   - Texture rows are uploaded as the file stores them (t = 0 is the first
 *     row, as luz's v = 0), every mip level from luz's chain with its own
 *     glTexImage2D (glGenerateMipmap's filter is not SCENE.md's), as GL_RGBA8
 *     (no sRGB decoding).
 *   - Four samples (SCENE.md, "Anti-aliasing"): multisample RGBA8 and
 *     depth24 renderbuffers, drawn, then resolved by glBlitFramebuffer into
 *     a single-sample renderbuffer that is read back. GL shades once per
 *     pixel and primitive at the pixel centre (no sample shading), as the
 *     contract does. glGetMultisamplefv gives llvmpipe's positions relative
 *     to GL's window, y up; with y mirrored in clip space that y is the
 *     image's (down), so they are SCENE.md's as reported (--check-samples).
 *   - Exposure and tone map (SCENE.md, "Output") are the fragment shader's
 *     last lines, the marker's colour and the clear colour untouched.
 *   - llvmpipe's default texture path filters with 8-bit weights and takes
 *     an approximate log2 for the level of detail; GALLIVM_PERF=no_aos_sampling
 *     makes it filter in float. tools/conformance shows the difference.
 *
 * It refuses (exit 2) to run on anything but llvmpipe: a GPU's driver would
 * make neither the pictures nor the timings mean what the tools say. Exit
 * status otherwise as luz-render: 0, 1 when rendering or writing fails, 2 for
 * a usage error.
 */
#define GL_GLEXT_PROTOTYPES 1

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#if defined(GLREF_HAVE_ASSIMP)
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>
#endif

#include "luz/luz.h"
#include "app/bench.h"
#include "app/controls.h"
#include "app/options.h"
#include "app/panel.h"
#include "io/image.h"
#include "io/textures.h"
#include "lab/scene.h"

#ifndef LUZ_VERSION
#error "tools/meson.build passes LUZ_VERSION"
#endif

enum {
    EXIT_OK = 0,
    EXIT_RUNTIME = 1,
    EXIT_USAGE = 2,   /* a bad option, or not llvmpipe */
};

#define PI 3.14159265358979323846

/* ---- what glref reads beside luz's options ------------------------------------------ */

/* SCENE.md's "Up axis": which of a model's own axes points up. */
typedef enum up_axis { UP_Y, UP_Z, UP_X, UP_MINUS_Y, UP_MINUS_Z, UP_MINUS_X, UP_AXIS_COUNT } up_axis;

/* The frame's sample count (SCENE.md, "Anti-aliasing: four samples a
 * pixel") and the output of lit fragments ("Output: exposure and tone
 * map"), once resolved from luz's options: given (on the command line or
 * in a scene file), or the contract's defaults. */
typedef struct glref_settings {
    int samples;              /* 1 or 4 */
    double exposure;          /* EV: lit colours are multiplied by 2^EV */
    bool neutral;             /* the Khronos PBR Neutral tone map, else clamp */
    bool check_samples;       /* --check-samples: print llvmpipe's positions */
} glref_settings;

/* Object i's up axis, as luz's options read it (--up for --model's model,
 * a model line's `up`); luz_up_axis lists the axes in glref's order. */
_Static_assert((int)LUZ_UP_Z == (int)UP_Z && (int)LUZ_UP_MINUS_X == (int)UP_MINUS_X &&
                   (int)LUZ_UP_AXIS_COUNT == (int)UP_AXIS_COUNT,
               "glref's up axes are luz's, in the same order");
static up_axis object_up(const luz_options *options, int i)
{
    return (up_axis)options->objects[i].up;
}

/* Whether the scene draws a model: SCENE.md's defaults of the output
 * change with it. */
static bool scene_has_model(const luz_options *options)
{
    const int count = options->scene.objects ? options->scene.object_count : 0;
    for (int i = 0; i < count; i++)
        if (options->object_sources[i].model_path != NULL) return true;
    return false;
}

/* Takes glref's own option, --check-samples, out of argv; what is left
 * goes to luz's parser. */
static void take_own_options(int *argc, char **argv, glref_settings *settings)
{
    int kept = 1;
    for (int index = 1; index < *argc; index++) {
        if (strcmp(argv[index], "--check-samples") == 0)
            settings->check_samples = true;
        else
            argv[kept++] = argv[index];
    }
    *argc = kept;
    argv[kept] = NULL;
}

/* ---- the cube of SCENE.md, copied from its table ------------------------------------ */

/* A vertex as the vertex shader reads it: the cube's, and the models'. */
typedef struct gl_vertex {
    float position[3], normal[3], uv[2];
} gl_vertex;

/* Face by face in SCENE.md's order (+Z, -Z, +X, -X, +Y, -Y); the corners of
 * each with uv (0,1), (1,1), (1,0), (0,0). */
static const float face_normals[6][3] = {
    {0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
};
static const float face_corners[6][4][3] = {
    {{-.5f, -.5f, .5f}, {.5f, -.5f, .5f}, {.5f, .5f, .5f}, {-.5f, .5f, .5f}},
    {{.5f, -.5f, -.5f}, {-.5f, -.5f, -.5f}, {-.5f, .5f, -.5f}, {.5f, .5f, -.5f}},
    {{.5f, -.5f, .5f}, {.5f, -.5f, -.5f}, {.5f, .5f, -.5f}, {.5f, .5f, .5f}},
    {{-.5f, -.5f, -.5f}, {-.5f, -.5f, .5f}, {-.5f, .5f, .5f}, {-.5f, .5f, -.5f}},
    {{-.5f, .5f, .5f}, {.5f, .5f, .5f}, {.5f, .5f, -.5f}, {-.5f, .5f, -.5f}},
    {{-.5f, -.5f, -.5f}, {.5f, -.5f, -.5f}, {.5f, -.5f, .5f}, {-.5f, -.5f, .5f}},
};
static const float corner_uvs[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};

/* ---- transforms, in double precision, independent of luz's vecmath.c ------------- */

/* Column-major like GL: element (row r, column c) is m[c * 4 + r]. */
typedef struct matrix {
    double m[16];
} matrix;

#define M(a, r, c) ((a).m[(c) * 4 + (r)])

static matrix matrix_identity(void)
{
    matrix a = {{0}};
    M(a, 0, 0) = M(a, 1, 1) = M(a, 2, 2) = M(a, 3, 3) = 1.0;
    return a;
}

static void normalize3(double v[3])
{
    double length = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++) v[k] /= length;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* T(p) * R(angle, axis) * S(s): glm::translate, glm::rotate (the
 * right-handed rotation about a unit axis, Rodrigues), glm::scale. */
static matrix model_matrix(const double position[3], double angle_radians, double scale)
{
    double axis[3] = {1.0, 0.5, 1.0};   /* SCENE.md: normalize(1, 0.5, 1) */
    normalize3(axis);
    double c = cos(angle_radians), s = sin(angle_radians), t = 1.0 - c;
    double x = axis[0], y = axis[1], z = axis[2];
    matrix a = matrix_identity();
    M(a, 0, 0) = t * x * x + c;     M(a, 0, 1) = t * x * y - s * z; M(a, 0, 2) = t * x * z + s * y;
    M(a, 1, 0) = t * x * y + s * z; M(a, 1, 1) = t * y * y + c;     M(a, 1, 2) = t * y * z - s * x;
    M(a, 2, 0) = t * x * z - s * y; M(a, 2, 1) = t * y * z + s * x; M(a, 2, 2) = t * z * z + c;
    for (int r = 0; r < 3; r++) {
        for (int k = 0; k < 3; k++) M(a, r, k) *= scale;
        M(a, r, 3) = position[r];
    }
    return a;
}

/* glm::lookAt(eye, eye + front, up). */
static matrix look_along(const double eye[3], const double front[3])
{
    const double up[3] = {0.0, 1.0, 0.0};
    double f[3] = {front[0], front[1], front[2]}, s[3], u[3];
    normalize3(f);
    cross3(f, up, s);
    normalize3(s);
    cross3(s, f, u);
    matrix a = matrix_identity();
    for (int k = 0; k < 3; k++) {
        M(a, 0, k) = s[k];
        M(a, 1, k) = u[k];
        M(a, 2, k) = -f[k];
    }
    M(a, 0, 3) = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    M(a, 1, 3) = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    M(a, 2, 3) = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
    return a;
}

/* glm::perspective (OpenGL's clip z in [-w, w]). */
static matrix perspective(double fovy_radians, double aspect, double near, double far)
{
    double f = 1.0 / tan(fovy_radians / 2.0);
    matrix a = {{0}};
    M(a, 0, 0) = f / aspect;
    M(a, 1, 1) = f;
    M(a, 2, 2) = (far + near) / (near - far);
    M(a, 2, 3) = 2.0 * far * near / (near - far);
    M(a, 3, 2) = -1.0;
    return a;
}

static matrix matrix_multiply(matrix a, matrix b)
{
    matrix product = {{0}};
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            for (int k = 0; k < 4; k++) M(product, r, c) += M(a, r, k) * M(b, k, c);
    return product;
}

/* The inverse transpose of a's upper 3x3 (SCENE.md: normals go to world
 * space with it), column-major like GL's mat3: the cofactor matrix divided
 * by the determinant. */
static void normal_matrix(matrix a, float out[9])
{
    double cofactor[3][3];
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) {
            int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
            cofactor[r][c] = M(a, r0, c0) * M(a, r1, c1) - M(a, r0, c1) * M(a, r1, c0);
        }
    }
    double determinant = M(a, 0, 0) * cofactor[0][0] + M(a, 0, 1) * cofactor[0][1] +
                         M(a, 0, 2) * cofactor[0][2];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) out[c * 3 + r] = (float)(cofactor[r][c] / determinant);
}

/* Up: the turn that makes the named axis +Y, written from SCENE.md's maps
 * of (x, y, z) (each row is one output coordinate). */
static matrix up_matrix(up_axis up)
{
    matrix a = matrix_identity();
    if (up == UP_Y) return a;
    M(a, 0, 0) = M(a, 1, 1) = M(a, 2, 2) = 0.0;
    switch (up) {
    case UP_Z:         /* (x, z, -y): -90 degrees about X */
        M(a, 0, 0) = 1.0; M(a, 1, 2) = 1.0; M(a, 2, 1) = -1.0;
        break;
    case UP_MINUS_Z:   /* (x, -z, y): +90 degrees about X */
        M(a, 0, 0) = 1.0; M(a, 1, 2) = -1.0; M(a, 2, 1) = 1.0;
        break;
    case UP_X:         /* (-y, x, z): +90 degrees about Z */
        M(a, 0, 1) = -1.0; M(a, 1, 0) = 1.0; M(a, 2, 2) = 1.0;
        break;
    case UP_MINUS_X:   /* (y, -x, z): -90 degrees about Z */
        M(a, 0, 1) = 1.0; M(a, 1, 0) = -1.0; M(a, 2, 2) = 1.0;
        break;
    default:           /* -y: (-x, -y, z), 180 degrees about Z */
        M(a, 0, 0) = -1.0; M(a, 1, 1) = -1.0; M(a, 2, 2) = 1.0;
        break;
    }
    return a;
}

static void matrix_to_floats(matrix a, float out[16])
{
    for (int k = 0; k < 16; k++) out[k] = (float)a.m[k];
}

/* ---- shaders: SCENE.md's equations in GLSL --------------------------------------- */

static const char *const vertex_shader_source =
    "#version 330 core\n"
    "layout(location = 0) in vec3 position;\n"
    "layout(location = 1) in vec3 normal;\n"
    "layout(location = 2) in vec2 uv;\n"
    "uniform mat4 model;\n"
    "uniform mat3 normal_matrix;   // inverse transpose of mat3(model), in double on the CPU\n"
    "uniform mat4 view;\n"
    "uniform mat4 projection;\n"
    "out vec3 world_position;\n"
    "out vec3 world_normal;\n"
    "out vec2 texture_coordinate;\n"
    "void main()\n"
    "{\n"
    "    vec4 world = model * vec4(position, 1.0);\n"
    "    world_position = world.xyz;\n"
    "    world_normal = normal_matrix * normal;\n"
    "    texture_coordinate = uv;\n"
    "    gl_Position = projection * view * world;\n"
    "    gl_Position.y = -gl_Position.y;   // luz's row 0 is the top\n"
    "}\n";

/* Each light is vec4(colour, strength). The comments are SCENE.md's lines. */
static const char *const fragment_shader_source =
    "#version 330 core\n"
    "in vec3 world_position;\n"
    "in vec3 world_normal;\n"
    "in vec2 texture_coordinate;\n"
    "out vec4 fragment_colour;\n"
    "uniform vec4 A, D, S, Pt, Sp, Dl;\n"
    "uniform float shininess;\n"
    "uniform vec3 camera_position, camera_front, point_position, sun_direction;\n"
    "uniform float cos_inner, cos_outer, reach;\n"
    "uniform vec3 object_colour;\n"
    "uniform int unlit, textured;\n"
    "uniform sampler2D image;\n"
    "uniform float exposure_scale;\n"
    "uniform int neutral;\n"
    "// The Khronos PBR Neutral tone mapper, line by line as SCENE.md writes it.\n"
    "vec3 pbr_neutral(vec3 c)\n"
    "{\n"
    "    float x = min(c.r, min(c.g, c.b));\n"
    "    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;\n"
    "    c -= offset;\n"
    "    float peak = max(c.r, max(c.g, c.b));\n"
    "    if (peak < 0.76) return c;\n"
    "    float d = 0.24;   // 1 - 0.76\n"
    "    float new_peak = 1.0 - d * d / (peak + d - 0.76);\n"
    "    c *= new_peak / peak;\n"
    "    float g = 1.0 - 1.0 / (0.15 * (peak - new_peak) + 1.0);\n"
    "    return mix(c, new_peak * vec3(1.0, 1.0, 1.0), g);\n"
    "}\n"
    "void main()\n"
    "{\n"
    "    if (unlit != 0) {          // the point light's marker: Pt.rgb as it is\n"
    "        fragment_colour = vec4(object_colour, 1.0);\n"
    "        return;\n"
    "    }\n"
    "    vec3 P = world_position, N = normalize(world_normal);\n"
    "    vec3 E = camera_position, F = camera_front, C = object_colour;\n"
    "    vec3 T = textured != 0 ? texture(image, texture_coordinate).rgb : vec3(1.0);\n"
    "    vec3 ambient = A.a * A.rgb;\n"
    "    vec3 L = normalize(E - P);\n"
    "    vec3 diffuse = max(dot(N, L), 0.0) * D.rgb * D.a;\n"
    "    vec3 V = normalize(E - P);\n"
    "    vec3 R = reflect(-L, N);\n"
    "    // pow follows C: pow(0, 0) is 1 (GLSL leaves it undefined)\n"
    "    float highlight = shininess == 0.0 ? 1.0 : pow(max(dot(V, R), 0.0), shininess);\n"
    "    vec3 specular = S.a * highlight * S.rgb;\n"
    "    vec3 Lp = normalize(point_position - P);\n"
    "    vec3 point = max(dot(N, Lp), 0.0) * Pt.rgb * Pt.a;\n"
    "    float c = dot(normalize(P - E), normalize(F));\n"
    "    float ci = cos_inner, co = cos_outer;\n"
    "    float f_dir;\n"
    "    if (c > ci) {\n"
    "        f_dir = 1.0;\n"
    "    } else if (co < c) {\n"
    "        float s = sqrt((c - co) / (ci - co));\n"
    "        f_dir = s * s * (3.0 - 2.0 * s);\n"
    "    } else {\n"
    "        f_dir = 0.0;\n"
    "    }\n"
    "    float dn = length(E - P) / reach;\n"
    "    float dn2 = dn * dn;\n"
    "    float window = max(1.0 - dn2 * dn2, 0.0);   // max(1 - dn^4, 0)\n"
    "    float f_win = window * window;\n"
    "    float f_dist = f_win * Sp.a * Sp.a / (dn2 + 1.0);\n"
    "    vec3 spot = Sp.rgb * f_dir * f_dist;\n"
    "    vec3 directional = max(dot(N, normalize(-sun_direction)), 0.0) * Dl.rgb * Dl.a;\n"
    "    vec3 colour = (ambient + diffuse + specular + point + spot + directional) * C * T;\n"
    "    // SCENE.md, Output: the exposure, then the tone map\n"
    "    colour *= exposure_scale;   // 2^EV, worked out in double on the CPU\n"
    "    if (neutral != 0) colour = pbr_neutral(colour);\n"
    "    fragment_colour = vec4(colour, 1.0);   // GL clamps and rounds to 8 bits\n"
    "}\n";

/* ---- the GL state ---------------------------------------------------------------------- */

typedef struct uniform_locations {
    GLint model, normal_matrix, view, projection;
    GLint lights[LUZ_TERM_COUNT];
    GLint shininess, camera_position, camera_front, point_position, sun_direction;
    GLint cos_inner, cos_outer, reach, object_colour, unlit, textured, image;
    GLint exposure_scale, neutral;
} uniform_locations;

/* One triangle mesh of a model file, in GL buffers (uploaded once), with
 * its colour and texture by SCENE.md's rules for the material. */
typedef struct gl_model_mesh {
    GLuint vertex_array, vertex_buffer, index_buffer;
    GLsizei index_count;
    bool has_colour;      /* the material's diffuse colour (not DefaultMaterial's) */
    float colour[3];
    bool has_uvs;         /* without, T = 1 */
    GLuint texture;       /* the material's first diffuse texture; 0: white */
} gl_model_mesh;

/* One model file, read once however many objects place it. */
typedef struct gl_model {
    const char *path;     /* the options' absolute path */
    up_axis up;           /* the same file turned another way is another model */
    gl_model_mesh *meshes;
    int mesh_count;
    GLuint *textures;     /* every texture its materials name, once */
    char **texture_names;
    int texture_count;
    matrix normalisation; /* Norm = Scale(2 / s) * Translate(-c) * Up */
    uint64_t triangle_count;
} gl_model;

typedef struct gl_reference {
    EGLDisplay display;
    EGLContext context;
    /* What the frame is drawn into: single-sample, or with 4 samples
     * multisample renderbuffers that glBlitFramebuffer resolves into
     * resolve_framebuffer's single-sample colour, which is read back. */
    GLuint framebuffer, colour_buffer, depth_buffer;
    GLuint resolve_framebuffer, resolve_buffer;   /* 0 with one sample */
    int samples;
    GLuint program, vertex_array, vertex_buffer, index_buffer;   /* the cube */
    GLuint *textures;   /* one per texture in the set */
    int texture_count;
    gl_model *models;   /* the model files the objects name */
    int model_count;
    uniform_locations uniforms;
    int width, height;
} gl_reference;

static const char *egl_error_name(EGLint code)
{
    switch (code) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    default: return "an EGL error";
    }
}

/* EGL's surfaceless platform on Mesa's software rasteriser; GL 3.3 core with
 * no window and no config (EGL_KHR_no_config_context). Returns 0, or -1 with
 * a message; the caller reports it as a usage error, since it means this
 * machine has no llvmpipe to compare with. */
static int open_context(gl_reference *gl, luz_error *error)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (client == NULL || strstr(client, "EGL_MESA_platform_surfaceless") == NULL)
        return luz_error_set(error, "EGL has no surfaceless platform "
                                    "(EGL_MESA_platform_surfaceless): is Mesa's EGL "
                                    "(libegl-mesa0) installed?");
    gl->display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA,
                                        (void *)EGL_DEFAULT_DISPLAY, NULL);
    EGLint major, minor;
    if (gl->display == EGL_NO_DISPLAY || !eglInitialize(gl->display, &major, &minor)) {
        gl->display = EGL_NO_DISPLAY;
        return luz_error_set(error, "cannot initialise EGL's surfaceless display (%s)",
                             egl_error_name(eglGetError()));
    }
    const char *extensions = eglQueryString(gl->display, EGL_EXTENSIONS);
    if (extensions == NULL || strstr(extensions, "EGL_KHR_no_config_context") == NULL ||
        strstr(extensions, "EGL_KHR_surfaceless_context") == NULL)
        return luz_error_set(error, "EGL lacks EGL_KHR_no_config_context or "
                                    "EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API))
        return luz_error_set(error, "EGL offers no desktop OpenGL (%s)",
                             egl_error_name(eglGetError()));
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION, 3,
        EGL_CONTEXT_MINOR_VERSION, 3,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_NONE,
    };
    gl->context = eglCreateContext(gl->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (gl->context == EGL_NO_CONTEXT)
        return luz_error_set(error, "cannot create an OpenGL 3.3 core context (%s)",
                             egl_error_name(eglGetError()));
    if (!eglMakeCurrent(gl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, gl->context))
        return luz_error_set(error, "cannot make the OpenGL context current (%s)",
                             egl_error_name(eglGetError()));
    return 0;
}

static int compile_shader(GLenum kind, const char *source, GLuint *out, luz_error *error)
{
    GLuint shader = glCreateShader(kind);
    glShaderSource(shader, 1, &source, NULL);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[400] = "";
        glGetShaderInfoLog(shader, sizeof log, NULL, log);
        glDeleteShader(shader);
        return luz_error_set(error, "the %s shader does not compile: %s",
                             kind == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
    }
    *out = shader;
    return 0;
}

static int build_program(gl_reference *gl, luz_error *error)
{
    GLuint vertex, fragment;
    if (compile_shader(GL_VERTEX_SHADER, vertex_shader_source, &vertex, error) != 0)
        return -1;
    if (compile_shader(GL_FRAGMENT_SHADER, fragment_shader_source, &fragment, error) != 0) {
        glDeleteShader(vertex);
        return -1;
    }
    gl->program = glCreateProgram();
    glAttachShader(gl->program, vertex);
    glAttachShader(gl->program, fragment);
    glLinkProgram(gl->program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = GL_FALSE;
    glGetProgramiv(gl->program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[400] = "";
        glGetProgramInfoLog(gl->program, sizeof log, NULL, log);
        return luz_error_set(error, "the shaders do not link: %s", log);
    }
    glUseProgram(gl->program);

    uniform_locations *u = &gl->uniforms;
    GLuint p = gl->program;
    u->model = glGetUniformLocation(p, "model");
    u->normal_matrix = glGetUniformLocation(p, "normal_matrix");
    u->view = glGetUniformLocation(p, "view");
    u->projection = glGetUniformLocation(p, "projection");
    static const char *const light_names[LUZ_TERM_COUNT] = {"A", "D", "S", "Pt", "Sp", "Dl"};
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        u->lights[term] = glGetUniformLocation(p, light_names[term]);
    u->shininess = glGetUniformLocation(p, "shininess");
    u->camera_position = glGetUniformLocation(p, "camera_position");
    u->camera_front = glGetUniformLocation(p, "camera_front");
    u->point_position = glGetUniformLocation(p, "point_position");
    u->sun_direction = glGetUniformLocation(p, "sun_direction");
    u->cos_inner = glGetUniformLocation(p, "cos_inner");
    u->cos_outer = glGetUniformLocation(p, "cos_outer");
    u->reach = glGetUniformLocation(p, "reach");
    u->object_colour = glGetUniformLocation(p, "object_colour");
    u->unlit = glGetUniformLocation(p, "unlit");
    u->textured = glGetUniformLocation(p, "textured");
    u->image = glGetUniformLocation(p, "image");
    u->exposure_scale = glGetUniformLocation(p, "exposure_scale");
    u->neutral = glGetUniformLocation(p, "neutral");
    glUniform1i(u->image, 0);
    return 0;
}

/* The layout of gl_vertex for the vertex array and buffer bound. */
static void describe_vertices(void)
{
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(gl_vertex),
                          (void *)offsetof(gl_vertex, position));
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(gl_vertex),
                          (void *)offsetof(gl_vertex, normal));
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(gl_vertex),
                          (void *)offsetof(gl_vertex, uv));
    for (GLuint k = 0; k < 3; k++) glEnableVertexAttribArray(k);
}

static void upload_cube(gl_reference *gl)
{
    gl_vertex vertices[24];
    uint16_t indices[36];
    for (int face = 0; face < 6; face++) {
        for (int corner = 0; corner < 4; corner++) {
            gl_vertex *v = &vertices[face * 4 + corner];
            memcpy(v->position, face_corners[face][corner], sizeof v->position);
            memcpy(v->normal, face_normals[face], sizeof v->normal);
            memcpy(v->uv, corner_uvs[corner], sizeof v->uv);
        }
        /* SCENE.md: triangles (4k, 4k+1, 4k+2) and (4k, 4k+2, 4k+3). */
        static const int pattern[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; k++) indices[face * 6 + k] = (uint16_t)(face * 4 + pattern[k]);
    }
    glGenVertexArrays(1, &gl->vertex_array);
    glBindVertexArray(gl->vertex_array);
    glGenBuffers(1, &gl->vertex_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, gl->vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, sizeof vertices, vertices, GL_STATIC_DRAW);
    glGenBuffers(1, &gl->index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl->index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof indices, indices, GL_STATIC_DRAW);
    describe_vertices();
}

/* Every level of luz's chain (SCENE.md's box filter) as it is, rows in file
 * order, with the filter --filter names, into the texture object `name`. */
static void upload_texture(GLuint name, const luz_texture *texture, luz_filter filter)
{
    GLint minify = filter == LUZ_FILTER_NEAREST    ? GL_NEAREST
                   : filter == LUZ_FILTER_BILINEAR ? GL_LINEAR
                                                   : GL_LINEAR_MIPMAP_LINEAR;
    GLint magnify = filter == LUZ_FILTER_NEAREST ? GL_NEAREST : GL_LINEAR;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glBindTexture(GL_TEXTURE_2D, name);
    for (int level = 0; level < texture->level_count; level++) {
        const luz_texture_level *l = &texture->levels[level];
        glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA8, l->width, l->height, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, l->texels);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, texture->level_count - 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minify);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, magnify);
}

/* The cube textures: the set's images, in its order. */
static int upload_textures(gl_reference *gl, const luz_texture_set *set, luz_filter filter,
                           luz_error *error)
{
    gl->texture_count = set->count;
    if (set->count == 0) return 0;
    gl->textures = calloc((size_t)set->count, sizeof *gl->textures);
    if (gl->textures == NULL) return luz_error_set(error, "out of memory for the textures");
    glGenTextures(set->count, gl->textures);
    for (int i = 0; i < set->count; i++) upload_texture(gl->textures[i], set->textures[i], filter);
    if (glGetError() != GL_NO_ERROR)
        return luz_error_set(error, "OpenGL refused the textures");
    return 0;
}

/* ---- models: SCENE.md's "Models", read with assimp here, not with luz's io ---------- */

static void free_model(gl_model *model)
{
    for (int m = 0; m < model->mesh_count; m++) {
        gl_model_mesh *mesh = &model->meshes[m];
        glDeleteBuffers(1, &mesh->vertex_buffer);
        glDeleteBuffers(1, &mesh->index_buffer);
        glDeleteVertexArrays(1, &mesh->vertex_array);
    }
    if (model->texture_count > 0) glDeleteTextures(model->texture_count, model->textures);
    for (int k = 0; k < model->texture_count; k++) free(model->texture_names[k]);
    free(model->texture_names);
    free(model->textures);
    free(model->meshes);
    memset(model, 0, sizeof *model);
}

#if !defined(GLREF_HAVE_ASSIMP)

static int load_model(gl_model *model, const char *path, up_axis up, luz_filter filter,
                      luz_error *error)
{
    (void)model;
    (void)up;
    (void)filter;
    return luz_error_set(error, "%s: this glref was built without assimp (libassimp-dev), "
                                "so it draws no models", path);
}

#else

/* SCENE.md's post-processing steps, exactly. */
static const unsigned int model_steps =
    aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
    aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_FlipUVs |
    aiProcess_ValidateDataStructure;

/* The embedded texture a material names: "*N", or the embedded texture's
 * own file name. NULL if there is none. */
static const struct aiTexture *embedded_texture(const struct aiScene *scene, const char *name)
{
    if (name[0] == '*') {
        char *end;
        errno = 0;
        unsigned long index = strtoul(name + 1, &end, 10);
        if (errno != 0 || end == name + 1 || *end != '\0' || index >= scene->mNumTextures)
            return NULL;
        return scene->mTextures[index];
    }
    for (unsigned k = 0; k < scene->mNumTextures; k++)
        if (strcmp(scene->mTextures[k]->mFilename.data, name) == 0) return scene->mTextures[k];
    return NULL;
}

/* An embedded texture decoded: an encoded image of mWidth bytes (mHeight
 * 0), or mWidth x mHeight aiTexels (b, g, r, a). */
static luz_texture *decode_embedded(const struct aiTexture *embedded, const char *name,
                                    luz_error *error)
{
    if (embedded->mHeight == 0) {
        /* the format is in achFormatHint, as luz's model loader reads it */
        char hint[sizeof embedded->achFormatHint + 1] = {0};
        memcpy(hint, embedded->achFormatHint, sizeof embedded->achFormatHint);
        luz_texture *texture = NULL;
        luz_texture_load_memory((const unsigned char *)embedded->pcData, embedded->mWidth,
                                name, hint, NULL, &texture, error);
        return texture;
    }
    size_t count = (size_t)embedded->mWidth * embedded->mHeight;
    uint8_t *rgba = malloc(count * 4 + 1);
    if (rgba == NULL) {
        luz_error_set(error, "out of memory");
        return NULL;
    }
    for (size_t k = 0; k < count; k++) {
        rgba[k * 4 + 0] = embedded->pcData[k].r;
        rgba[k * 4 + 1] = embedded->pcData[k].g;
        rgba[k * 4 + 2] = embedded->pcData[k].b;
        rgba[k * 4 + 3] = embedded->pcData[k].a;
    }
    luz_texture *texture =
        luz_texture_create((int)embedded->mWidth, (int)embedded->mHeight, rgba, error);
    free(rgba);
    return texture;
}

/* The texture a material names, as a GL texture, decoded and uploaded once
 * per model: embedded in the file, else a file relative to the model's
 * directory with backslashes read as slashes. One that is missing or
 * corrupt is *out = 0 (T = 1) with one warning line naming the model and
 * the texture (SCENE.md, "Models"); remembered, so warned about once. */
static int model_texture(gl_model *model, const struct aiScene *scene, const char *name,
                         luz_filter filter, GLuint *out, luz_error *error)
{
    for (int k = 0; k < model->texture_count; k++) {
        if (strcmp(model->texture_names[k], name) == 0) {
            *out = model->textures[k];
            return 0;
        }
    }
    luz_error inner = {{0}};
    luz_texture *texture = NULL;
    const struct aiTexture *embedded = embedded_texture(scene, name);
    if (embedded != NULL) {
        texture = decode_embedded(embedded, name, &inner);
    } else if (name[0] == '*') {
        luz_error_set(&inner, "no such embedded texture");
    } else {
        char file[4096], joined[8192];
        snprintf(file, sizeof file, "%s", name);
        for (char *c = file; *c != '\0'; c++)
            if (*c == '\\') *c = '/';
        const char *slash = strrchr(model->path, '/');
        if (file[0] == '/' || slash == NULL)
            snprintf(joined, sizeof joined, "%s", file);
        else
            snprintf(joined, sizeof joined, "%.*s/%s", (int)(slash - model->path), model->path,
                     file);
        struct stat status;
        if (stat(joined, &status) != 0)
            luz_error_set(&inner, "%s: %s", joined, strerror(errno));
        else if (!S_ISREG(status.st_mode))
            luz_error_set(&inner, "%s: not a regular file", joined);
        else
            luz_texture_load(joined, NULL, &texture, &inner);
    }
    if (texture == NULL) {
        char safe[sizeof inner.message];
        snprintf(safe, sizeof safe, "%s", inner.message);
        for (char *c = safe; *c != '\0'; c++)
            if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
        fprintf(stderr, "glref: warning: %s: texture '%s': %s; drawn untextured (T = 1)\n",
                model->path, name, safe);
    }

    GLuint *textures = realloc(model->textures, (size_t)(model->texture_count + 1) *
                                                    sizeof *textures);
    if (textures != NULL) model->textures = textures;
    char **names = realloc(model->texture_names, (size_t)(model->texture_count + 1) *
                                                     sizeof *names);
    if (names != NULL) model->texture_names = names;
    char *copy = malloc(strlen(name) + 1);
    if (textures == NULL || names == NULL || copy == NULL) {
        free(copy);
        if (texture != NULL) luz_texture_destroy(texture);
        return luz_error_set(error, "%s: out of memory for its textures", model->path);
    }
    strcpy(copy, name);
    GLuint gl_name = 0;   /* 0: missing or corrupt, T = 1 */
    if (texture != NULL) {
        glGenTextures(1, &gl_name);
        upload_texture(gl_name, texture, filter);
        luz_texture_destroy(texture);
    }
    model->textures[model->texture_count] = gl_name;
    model->texture_names[model->texture_count++] = copy;
    *out = gl_name;
    return 0;
}

/* The mesh's colour C by SCENE.md (before the object's own): the
 * material's diffuse colour, unless the material is assimp's stand-in
 * "DefaultMaterial" or has none. */
static bool material_colour(const struct aiMaterial *material, float colour[3])
{
    struct aiString name;
    if (aiGetMaterialString(material, AI_MATKEY_NAME, &name) == aiReturn_SUCCESS &&
        strcmp(name.data, "DefaultMaterial") == 0)
        return false;
    struct aiColor4D diffuse;
    if (aiGetMaterialColor(material, AI_MATKEY_COLOR_DIFFUSE, &diffuse) != aiReturn_SUCCESS)
        return false;
    colour[0] = diffuse.r;
    colour[1] = diffuse.g;
    colour[2] = diffuse.b;
    return true;
}

/* One mesh of the file with its triangles (faces of 3 indices; points and
 * lines dropped): its vertices and 32-bit indices into GL buffers, its
 * colour and texture. *kept is false for a mesh with no triangles. bounds
 * grows by its vertices turned by the model's up axis (min x, y, z, then
 * max); the buffers keep them as the file has them. */
static int load_mesh(gl_model *model, const struct aiScene *scene, unsigned index,
                     luz_filter filter, bool *kept, double bounds[6], luz_error *error)
{
    const struct aiMesh *source = scene->mMeshes[index];
    *kept = false;
    size_t triangles = 0;
    for (unsigned f = 0; f < source->mNumFaces; f++) triangles += source->mFaces[f].mNumIndices == 3;
    if (triangles == 0 || source->mNumVertices == 0) return 0;

    gl_vertex *vertices = malloc((size_t)source->mNumVertices * sizeof *vertices);
    uint32_t *indices = malloc(triangles * 3 * sizeof *indices);
    if (vertices == NULL || indices == NULL) {
        free(vertices);
        free(indices);
        return luz_error_set(error, "%s: out of memory for mesh %u", model->path, index);
    }
    const struct aiVector3D *uvs = source->mTextureCoords[0];
    for (unsigned v = 0; v < source->mNumVertices; v++) {
        const struct aiVector3D p = source->mVertices[v];
        if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(p.z)) {
            free(vertices);
            free(indices);
            return luz_error_set(error, "%s: mesh %u: vertex %u is not finite", model->path,
                                 index, v);
        }
        const matrix up = up_matrix(model->up);
        double position[3];
        for (int k = 0; k < 3; k++) position[k] = M(up, k, 0) * p.x + M(up, k, 1) * p.y +
                                                  M(up, k, 2) * p.z;
        for (int k = 0; k < 3; k++) {
            bounds[k] = fmin(bounds[k], position[k]);
            bounds[3 + k] = fmax(bounds[3 + k], position[k]);
        }
        gl_vertex *out = &vertices[v];
        *out = (gl_vertex){{p.x, p.y, p.z}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f}};
        if (source->mNormals != NULL) {
            out->normal[0] = source->mNormals[v].x;
            out->normal[1] = source->mNormals[v].y;
            out->normal[2] = source->mNormals[v].z;
        }
        if (uvs != NULL) {
            out->uv[0] = uvs[v].x;
            out->uv[1] = uvs[v].y;
        }
    }
    size_t written = 0;
    for (unsigned f = 0; f < source->mNumFaces; f++) {
        const struct aiFace *face = &source->mFaces[f];
        if (face->mNumIndices != 3) continue;
        for (int k = 0; k < 3; k++) {
            if (face->mIndices[k] >= source->mNumVertices) {
                free(vertices);
                free(indices);
                return luz_error_set(error, "%s: mesh %u: index %u out of range", model->path,
                                     index, face->mIndices[k]);
            }
            indices[written++] = face->mIndices[k];
        }
    }

    gl_model_mesh mesh = {.index_count = (GLsizei)(triangles * 3), .has_uvs = uvs != NULL};
    glGenVertexArrays(1, &mesh.vertex_array);
    glBindVertexArray(mesh.vertex_array);
    glGenBuffers(1, &mesh.vertex_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, mesh.vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(source->mNumVertices * sizeof *vertices), vertices,
                 GL_STATIC_DRAW);
    glGenBuffers(1, &mesh.index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(triangles * 3 * sizeof *indices), indices,
                 GL_STATIC_DRAW);
    describe_vertices();
    free(vertices);
    free(indices);
    gl_model_mesh *meshes = realloc(model->meshes, (size_t)(model->mesh_count + 1) * sizeof *meshes);
    if (meshes == NULL) {
        glDeleteBuffers(1, &mesh.vertex_buffer);
        glDeleteBuffers(1, &mesh.index_buffer);
        glDeleteVertexArrays(1, &mesh.vertex_array);
        return luz_error_set(error, "%s: out of memory for its meshes", model->path);
    }
    model->meshes = meshes;
    model->meshes[model->mesh_count++] = mesh;
    model->triangle_count += triangles;
    *kept = true;

    /* Colour and texture of its material: the first diffuse texture, for a
     * mesh with texture coordinates. */
    gl_model_mesh *added = &model->meshes[model->mesh_count - 1];
    if (source->mMaterialIndex >= scene->mNumMaterials) return 0;
    const struct aiMaterial *material = scene->mMaterials[source->mMaterialIndex];
    added->has_colour = material_colour(material, added->colour);
    struct aiString texture_name;
    if (added->has_uvs && aiGetMaterialTextureCount(material, aiTextureType_DIFFUSE) > 0 &&
        aiGetMaterialTexture(material, aiTextureType_DIFFUSE, 0, &texture_name, NULL, NULL, NULL,
                             NULL, NULL, NULL) == aiReturn_SUCCESS &&
        texture_name.data[0] != '\0')
        return model_texture(model, scene, texture_name.data, filter, &added->texture, error);
    return 0;
}

/* Reads the model file at path (absolute, from the options) into GL
 * buffers and textures, and computes its normalisation with the up axis.
 * Returns 0, or -1 with a message naming the file. */
static int load_model(gl_model *model, const char *path, up_axis up, luz_filter filter,
                      luz_error *error)
{
    memset(model, 0, sizeof *model);
    model->path = path;
    model->up = up;
    const struct aiScene *scene = aiImportFile(path, model_steps);
    if (scene == NULL)
        return luz_error_set(error, "%s: assimp cannot read it (%s)", path, aiGetErrorString());
    double bounds[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
    int status = 0;
    for (unsigned m = 0; m < scene->mNumMeshes && status == 0; m++) {
        bool kept;
        status = load_mesh(model, scene, m, filter, &kept, bounds, error);
    }
    aiReleaseImport(scene);
    glBindVertexArray(0);
    if (status != 0) return -1;
    if (model->mesh_count == 0) return luz_error_set(error, "%s: no triangles", path);
    if (glGetError() != GL_NO_ERROR)
        return luz_error_set(error, "%s: OpenGL refused its buffers or textures", path);

    /* Norm = Scale(2 / s) * Translate(-c) * Up: c the centre of the turned
     * vertices' box, s its largest side. */
    double centre[3], side = 0.0;
    for (int k = 0; k < 3; k++) {
        centre[k] = (bounds[k] + bounds[3 + k]) / 2.0;
        side = fmax(side, bounds[3 + k] - bounds[k]);
    }
    if (!(side > 0.0)) return luz_error_set(error, "%s: the model has zero size", path);
    matrix norm = matrix_identity();
    for (int k = 0; k < 3; k++) {
        M(norm, k, k) = 2.0 / side;
        M(norm, k, 3) = -centre[k] * (2.0 / side);
    }
    model->normalisation = matrix_multiply(norm, up_matrix(up));
    return 0;
}

#endif

/* Every model file the objects name, each read once per up axis;
 * object_models[i] is object i's model (an index into gl->models), or -1
 * for a cube. */
static int load_models(gl_reference *gl, const luz_options *options, int *object_models,
                       luz_error *error)
{
    const int count = options->scene.objects ? options->scene.object_count : 0;
    for (int i = 0; i < count; i++) {
        const char *path = options->object_sources[i].model_path;
        object_models[i] = -1;
        if (path == NULL) continue;
        up_axis up = object_up(options, i);
        for (int m = 0; m < gl->model_count && object_models[i] < 0; m++)
            if (strcmp(gl->models[m].path, path) == 0 && gl->models[m].up == up)
                object_models[i] = m;
        if (object_models[i] >= 0) continue;
        gl_model *models = realloc(gl->models, (size_t)(gl->model_count + 1) * sizeof *models);
        if (models == NULL) return luz_error_set(error, "out of memory for the models");
        gl->models = models;
        gl_model *model = &gl->models[gl->model_count++];
        if (load_model(model, path, up, options->scene.filter, error) != 0) {
            const luz_object_source *source = &options->object_sources[i];
            if (source->line > 0 && options->scene_path != NULL) {
                luz_error inner = *error;
                luz_error_set(error, "%s:%d: model: %s", options->scene_path, source->line,
                              inner.message);
            }
            return -1;
        }
        object_models[i] = gl->model_count - 1;
    }
    return 0;
}

/* An RGBA8 renderbuffer, or a depth24 one, with `samples` samples (1: an
 * ordinary one). */
static GLuint create_renderbuffer(GLenum format, int samples, int width, int height)
{
    GLuint name;
    glGenRenderbuffers(1, &name);
    glBindRenderbuffer(GL_RENDERBUFFER, name);
    if (samples > 1)
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
    else
        glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
    return name;
}

/* The frame's framebuffer: RGBA8 and depth24 with one sample, or with
 * `samples` (4) and a single-sample RGBA8 one to resolve them into. */
static int create_framebuffer(gl_reference *gl, int width, int height, int samples,
                              luz_error *error)
{
    GLint limit = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &limit);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    if (width > limit || height > limit || width > viewport[0] || height > viewport[1])
        return luz_error_set(error, "--size: %dx%d is larger than llvmpipe's %dx%d", width,
                             height, viewport[0] < limit ? viewport[0] : limit,
                             viewport[1] < limit ? viewport[1] : limit);
    gl->width = width;
    gl->height = height;
    gl->samples = samples;
    if (samples > 1) {
        GLint most = 0;
        glGetIntegerv(GL_MAX_SAMPLES, &most);
        if (most < samples)
            return luz_error_set(error, "--samples: llvmpipe offers at most %d samples, not %d",
                                 most, samples);
        gl->resolve_buffer = create_renderbuffer(GL_RGBA8, 1, width, height);
        glGenFramebuffers(1, &gl->resolve_framebuffer);
        glBindFramebuffer(GL_FRAMEBUFFER, gl->resolve_framebuffer);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  gl->resolve_buffer);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return luz_error_set(error, "cannot make a %dx%d RGBA8 framebuffer to resolve "
                                        "into", width, height);
    }
    gl->colour_buffer = create_renderbuffer(GL_RGBA8, samples, width, height);
    gl->depth_buffer = create_renderbuffer(GL_DEPTH_COMPONENT24, samples, width, height);
    glGenFramebuffers(1, &gl->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, gl->framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              gl->colour_buffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              gl->depth_buffer);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return luz_error_set(error, "cannot make a %dx%d RGBA8 + depth24 framebuffer with %d "
                                    "sample%s", width, height, samples, samples > 1 ? "s" : "");
    if (samples > 1) {
        /* The driver may round the count up: SCENE.md asks for exactly 4. */
        GLint granted = 0;
        glBindRenderbuffer(GL_RENDERBUFFER, gl->colour_buffer);
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &granted);
        if (granted != samples)
            return luz_error_set(error, "--samples: llvmpipe made %d samples a pixel, not %d",
                                 granted, samples);
    }
    glViewport(0, 0, width, height);

    /* SCENE.md's fixed state: depth LESS cleared to 1, back faces culled
     * (front faces are clockwise once y is mirrored), clear colour 0.1. */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearDepth(1.0);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CW);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    return 0;
}

/* --check-samples: the positions of the bound 4-sample framebuffer as
 * llvmpipe reports them (glGetMultisamplefv), against SCENE.md's pattern.
 * GL gives each relative to the pixel's corner with y counting up GL's
 * window; glref mirrors y in clip space so that GL's row 0 is the image's
 * top row, so in glref's frames GL's y is the image's y (down), and the
 * reported pair is the image position as it is. Prints them; returns 0
 * when all four are SCENE.md's, else 1. */
static int check_sample_positions(const gl_reference *gl)
{
    static const float expected[4][2] = {
        {0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f},
    };
    int status = 0;
    printf("llvmpipe's %d sample positions (glGetMultisamplefv; in glref's frames, image "
           "coordinates, y down):\n", gl->samples);
    for (int k = 0; k < gl->samples; k++) {
        GLfloat position[2] = {-1.0f, -1.0f};
        glGetMultisamplefv(GL_SAMPLE_POSITION, (GLuint)k, position);
        bool same = k < 4 && position[0] == expected[k][0] && position[1] == expected[k][1];
        printf("  sample %d: (%.4f, %.4f)%s\n", k, position[0], position[1],
               same ? "" : "  differs from SCENE.md's");
        if (!same) status = 1;
    }
    printf("%s\n", status == 0 ? "SCENE.md's pattern: (0.375, 0.125), (0.875, 0.375), "
                                 "(0.125, 0.625), (0.625, 0.875)"
                               : "NOT SCENE.md's pattern");
    return status;
}

static void close_reference(gl_reference *gl)
{
    if (gl->display == EGL_NO_DISPLAY) return;
    if (gl->context != EGL_NO_CONTEXT) {
        if (gl->textures != NULL) glDeleteTextures(gl->texture_count, gl->textures);
        if (gl->program != 0) glDeleteProgram(gl->program);
        for (int m = 0; m < gl->model_count; m++) free_model(&gl->models[m]);
        glDeleteBuffers(1, &gl->vertex_buffer);
        glDeleteBuffers(1, &gl->index_buffer);
        glDeleteVertexArrays(1, &gl->vertex_array);
        glDeleteFramebuffers(1, &gl->framebuffer);
        glDeleteRenderbuffers(1, &gl->colour_buffer);
        glDeleteRenderbuffers(1, &gl->depth_buffer);
        glDeleteFramebuffers(1, &gl->resolve_framebuffer);
        glDeleteRenderbuffers(1, &gl->resolve_buffer);
        eglMakeCurrent(gl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(gl->display, gl->context);
    }
    eglTerminate(gl->display);
    free(gl->textures);
    free(gl->models);
}

/* ---- one frame ---------------------------------------------------------------------------- */

typedef struct scene_data {
    const luz_options *options;
    const glref_settings *settings;
    luz_vec3 *colours;   /* objectColor per object index (the seed's) */
    int object_count;    /* cubes and models */
    int *object_models;  /* per object: index into gl->models, -1 a cube */
} scene_data;

/* The model matrix and its normal matrix, from double precision. */
static void set_model(const uniform_locations *u, matrix model)
{
    float floats[16], normals[9];
    matrix_to_floats(model, floats);
    normal_matrix(model, normals);
    glUniformMatrix4fv(u->model, 1, GL_FALSE, floats);
    glUniformMatrix3fv(u->normal_matrix, 1, GL_FALSE, normals);
}

static void set_light(GLint location, const luz_light *light)
{
    glUniform4f(location, light->colour.x, light->colour.y, light->colour.z, light->strength);
}

/* Times are split for --bench: issuing the draws (where llvmpipe shades
 * vertices and bins triangles) and glFinish (where it rasterises and
 * shades fragments). */
typedef struct frame_times {
    double submit_ms, finish_ms;
} frame_times;

static void draw_frame(gl_reference *gl, const scene_data *data, double t, frame_times *times)
{
    const luz_scene *scene = &data->options->scene;
    luz_lights lights_copy = scene->lights;   /* luz_lights_term takes a non-const */
    const luz_lights *lights = &lights_copy;
    const uniform_locations *u = &gl->uniforms;
    double start = luz_wall_ms();

    /* Camera: SCENE.md's front from yaw and pitch, lookAt and perspective. */
    double yaw = scene->camera.yaw_degrees * (PI / 180.0);
    double pitch = scene->camera.pitch_degrees * (PI / 180.0);
    double front[3] = {cos(yaw) * cos(pitch), sin(pitch), sin(yaw) * cos(pitch)};
    normalize3(front);
    double eye[3] = {scene->camera.position.x, scene->camera.position.y,
                     scene->camera.position.z};
    float view[16], projection[16];
    matrix_to_floats(look_along(eye, front), view);
    matrix_to_floats(perspective(scene->camera.fov_degrees * (PI / 180.0),
                                 (double)gl->width / gl->height, 0.1, 100.0),
                     projection);

    /* The orbits: point light radius 3 at y = 0.5, the sun d(t). */
    double point[3] = {3.0 * cos(0.5 * t), 0.5, 3.0 * sin(0.5 * t)};

    glUniformMatrix4fv(u->view, 1, GL_FALSE, view);
    glUniformMatrix4fv(u->projection, 1, GL_FALSE, projection);
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        set_light(u->lights[term], luz_lights_term(&lights_copy, (luz_term)term));
    glUniform1f(u->shininess, lights->shininess);
    glUniform3f(u->camera_position, (float)eye[0], (float)eye[1], (float)eye[2]);
    glUniform3f(u->camera_front, (float)front[0], (float)front[1], (float)front[2]);
    glUniform3f(u->point_position, (float)point[0], (float)point[1], (float)point[2]);
    glUniform3f(u->sun_direction, (float)cos(0.1 * t), (float)sin(0.1 * t), 0.0f);
    glUniform1f(u->cos_inner, (float)cos(lights->spot_inner_degrees * (PI / 180.0)));
    glUniform1f(u->cos_outer, (float)cos(lights->spot_outer_degrees * (PI / 180.0)));
    glUniform1f(u->reach, lights->spot_reach);
    glUniform1i(u->unlit, 0);
    glUniform1f(u->exposure_scale, (float)exp2(data->settings->exposure));
    glUniform1i(u->neutral, data->settings->neutral);

    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    /* Objects 0 .. N-1 in order, cubes and models: M_i = T(p_i) R(angle_i)
     * for a cube, T(p_i) R(angle_i) S(k) Norm for a model (angle_i 0 if it
     * is still), angle_i = (i + 1) / 3 * t * 50 degrees. */
    const luz_object *custom = scene->objects;
    int textured = -1;
    GLuint bound_array = 0;
    for (int i = 0; i < data->object_count; i++) {
        luz_vec3 p = custom ? custom[i].position : luz_scene_tiled_position(i);
        double position[3] = {p.x, p.y, p.z};
        const gl_model *model = custom && data->object_models[i] >= 0
                                    ? &gl->models[data->object_models[i]]
                                    : NULL;
        double degrees = model && custom[i].still ? 0.0 : fmod((i + 1) / 3.0 * t * 50.0, 360.0);
        /* A texture of the textures directory given for the object. */
        int chosen = custom ? custom[i].texture : LUZ_TEXTURE_BY_INDEX;
        if (model == NULL) {
            luz_vec3 colour = custom && custom[i].has_colour ? custom[i].colour : data->colours[i];
            set_model(u, model_matrix(position, degrees * (PI / 180.0), 1.0));
            glUniform3f(u->object_colour, colour.x, colour.y, colour.z);
            int has_texture = gl->texture_count > 0;
            if (has_texture) {
                int index = chosen != LUZ_TEXTURE_BY_INDEX ? chosen : i;
                glBindTexture(GL_TEXTURE_2D, gl->textures[index % gl->texture_count]);
            }
            if (has_texture != textured) {
                glUniform1i(u->textured, has_texture);
                textured = has_texture;
            }
            if (bound_array != gl->vertex_array) {
                glBindVertexArray(gl->vertex_array);
                bound_array = gl->vertex_array;
            }
            glDrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_SHORT, NULL);
            continue;
        }

        /* A model: its meshes in the file's order. C: the object's colour,
         * else the material's, else the seed's for index i. T: white
         * without texture coordinates, else the object's texture, else
         * the material's, else white. */
        double k = custom[i].scale > 0.0f ? custom[i].scale : 1.0;
        set_model(u, matrix_multiply(model_matrix(position, degrees * (PI / 180.0), k),
                                     model->normalisation));
        for (int m = 0; m < model->mesh_count; m++) {
            const gl_model_mesh *mesh = &model->meshes[m];
            luz_vec3 colour = custom[i].has_colour ? custom[i].colour
                              : mesh->has_colour
                                  ? (luz_vec3){mesh->colour[0], mesh->colour[1], mesh->colour[2]}
                                  : data->colours[i];
            glUniform3f(u->object_colour, colour.x, colour.y, colour.z);
            GLuint texture = 0;
            if (mesh->has_uvs)
                texture = chosen != LUZ_TEXTURE_BY_INDEX && gl->texture_count > 0
                              ? gl->textures[chosen % gl->texture_count]
                              : mesh->texture;
            int has_texture = texture != 0;
            if (has_texture) glBindTexture(GL_TEXTURE_2D, texture);
            if (has_texture != textured) {
                glUniform1i(u->textured, has_texture);
                textured = has_texture;
            }
            glBindVertexArray(mesh->vertex_array);
            bound_array = mesh->vertex_array;
            glDrawElements(GL_TRIANGLES, mesh->index_count, GL_UNSIGNED_INT, NULL);
        }
    }

    /* The point light's marker: scale 0.2, unrotated, unlit, Pt.rgb, drawn
     * while the light shines. */
    if (lights->point.strength > 0.0f) {
        set_model(u, model_matrix(point, 0.0, 0.2));
        glUniform3f(u->object_colour, lights->point.colour.x, lights->point.colour.y,
                    lights->point.colour.z);
        glUniform1i(u->unlit, 1);
        if (bound_array != gl->vertex_array) glBindVertexArray(gl->vertex_array);
        glDrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_SHORT, NULL);
    }

    double submitted = luz_wall_ms();
    /* Four samples: the resolve, the average of each pixel's samples
     * (SCENE.md writes it floor((s0 + s1 + s2 + s3 + 2) / 4)); it waits
     * for the draws, so it counts with glFinish as rasterisation. */
    if (gl->samples > 1) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, gl->framebuffer);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl->resolve_framebuffer);
        glBlitFramebuffer(0, 0, gl->width, gl->height, 0, 0, gl->width, gl->height,
                          GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, gl->framebuffer);
    }
    glFinish();
    if (times != NULL) {
        times->submit_ms = submitted - start;
        times->finish_ms = luz_wall_ms() - submitted;
    }
}

/* ---- programs: files and --bench -------------------------------------------------------- */

static int write_frame(gl_reference *gl, uint8_t *pixels, const char *path, luz_error *error)
{
    /* GL's row 0 is luz's row 0 (y is mirrored in clip space); with four
     * samples, the pixels are the resolved ones. */
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (gl->samples > 1) glBindFramebuffer(GL_READ_FRAMEBUFFER, gl->resolve_framebuffer);
    glReadPixels(0, 0, gl->width, gl->height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    if (gl->samples > 1) glBindFramebuffer(GL_READ_FRAMEBUFFER, gl->framebuffer);
    if (glGetError() != GL_NO_ERROR) return luz_error_set(error, "glReadPixels failed");
    return luz_png_write(path, gl->width, gl->height, pixels, error);
}

static int render_files(gl_reference *gl, const scene_data *data, luz_error *error)
{
    const luz_options *options = data->options;
    uint8_t *pixels = malloc((size_t)gl->width * (size_t)gl->height * 4);
    if (pixels == NULL) return luz_error_set(error, "out of memory for the image");
    int status = 0;
    char path[4096];
    for (int k = 0; k < options->frame_count && status == 0; k++) {
        double t = options->scene.time_seconds + k / options->frames_per_second;
        status = luz_options_output_path(options, k, path, sizeof path, error);
        if (status == 0) {
            draw_frame(gl, data, t, NULL);
            status = write_frame(gl, pixels, path, error);
        }
    }
    free(pixels);
    return status;
}

/* llvmpipe's thread count: LP_NUM_THREADS, else one per online CPU. */
static int llvmpipe_threads(void)
{
    const char *text = getenv("LP_NUM_THREADS");
    if (text != NULL && text[0] != '\0') return atoi(text);
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    return cpus > 0 ? (int)cpus : 1;
}

/* The frames of luz-render --bench (one warm-up at --time, then frame k at
 * time + k / fps), and its line of figures. */
typedef struct bench_context {
    gl_reference *gl;
    const scene_data *data;
} bench_context;

static int bench_frame(void *context, double time_seconds, double parts[LUZ_BENCH_MAX_PARTS],
                       luz_error *error)
{
    (void)error;
    bench_context *bench = context;
    frame_times times;
    draw_frame(bench->gl, bench->data, time_seconds, &times);
    parts[0] = times.submit_ms;
    parts[1] = times.finish_ms;
    return 0;
}

static int bench(gl_reference *gl, const scene_data *data, luz_error *error)
{
    const luz_options *options = data->options;
    /* submit and finish stand where luz-render has geometry and raster, so
     * that tools/bench reads both lines alike. */
    luz_bench measured = {.part_names = {"geometry_ms", "raster_ms"}};
    if (luz_bench_run(&measured, options->bench_frames, options->scene.time_seconds,
                      options->frames_per_second, bench_frame, &(bench_context){gl, data},
                      error) != 0)
        return -1;
    /* cubes= and triangles= as luz-render's line: the cubes among the
     * objects, and every triangle a frame draws (the marker's included). */
    int cubes = 0;
    uint64_t triangles = options->scene.lights.point.strength > 0.0f ? 12 : 0;
    for (int i = 0; i < data->object_count; i++) {
        int model = options->scene.objects ? data->object_models[i] : -1;
        cubes += model < 0;
        triangles += model < 0 ? 12 : gl->models[model].triangle_count;
    }
    printf("frames=%d size=%dx%d threads=%d cubes=%d triangles=%llu filter=%s ", measured.frames,
           gl->width, gl->height, llvmpipe_threads(), cubes, (unsigned long long)triangles,
           luz_filter_name(options->scene.filter));
    luz_bench_print_figures(stdout, &measured);
    printf("\n");
    luz_bench_free(&measured);
    return 0;
}

/* ---- main ------------------------------------------------------------------------------------ */

static void print_error(const char *message)
{
    fputs("glref: ", stderr);
    for (const char *c = message; *c != '\0'; c++)
        fputc(((unsigned char)*c < 0x20 || *c == 0x7f) ? '?' : *c, stderr);
    fputc('\n', stderr);
}

static void print_usage(FILE *out)
{
    fprintf(out,
            "Usage: glref [OPTION]...\n"
            "Render SCENE.md's scene through OpenGL 3.3 core on Mesa's llvmpipe (headless,\n"
            "EGL surfaceless), the reference luz is compared with. The options are\n"
            "luz-render's; --threads N sets llvmpipe's LP_NUM_THREADS.\n"
            "\n"
            "--samples 4 draws into multisample renderbuffers that glBlitFramebuffer\n"
            "resolves. glref's own option:\n"
            "  --check-samples              print llvmpipe's 4 sample positions and check\n"
            "                               them against SCENE.md's (exit 1 if they differ)\n"
            "\n");
    luz_options_print_help(out);
    fprintf(out,
            "\n"
            "GALLIVM_PERF=no_aos_sampling makes llvmpipe filter textures in float instead\n"
            "of with 8-bit weights. glref refuses to run on any renderer but llvmpipe.\n"
            "\n"
            "Exit status: 0 on success, 2 for a bad option or no llvmpipe, 1 if rendering\n"
            "or writing failed.\n");
}

static int load_textures(luz_options *options, luz_texture_set *textures, luz_error *error)
{
    char default_directory[4096];
    const char *directory = options->textures_directory;
    if (directory == NULL)
        directory = luz_default_textures_directory(default_directory, sizeof default_directory);
    if (strcmp(directory, "none") != 0) {
        luz_error load_error = {{0}};
        if (luz_texture_set_load(textures, directory, NULL, &load_error) != 0)
            return luz_error_set(error, "--textures: %s", load_error.message);
    }
    return luz_options_resolve_textures(options, textures, error);
}

int main(int argc, char **argv)
{
    luz_options options;
    luz_texture_set textures = {0};
    gl_reference gl = {.display = EGL_NO_DISPLAY, .context = EGL_NO_CONTEXT};
    glref_settings settings = {.samples = 1};
    scene_data data = {.options = &options, .settings = &settings};
    luz_error error = {{0}};
    int status = EXIT_USAGE;

    luz_options_init(&options);
    take_own_options(&argc, argv, &settings);
    if (luz_options_parse(&options, argc, argv, &error) != 0) goto done;
    settings.samples = options.scene.samples == 4 ? 4 : 1;   /* 0 means 1 */
    /* SCENE.md's defaults, worked out here from what the user gave: clamp
     * at EV 0, and neutral at EV -1 when the scene has a model. */
    const bool has_model = scene_has_model(&options);
    settings.exposure = options.scene.has_exposure ? options.scene.exposure
                        : has_model                ? -1.0
                                                   : 0.0;
    settings.neutral = options.scene.has_tone_map
                           ? options.scene.tone_map == LUZ_TONE_MAP_NEUTRAL
                           : has_model;
    if (options.help) {
        print_usage(stdout);
        status = EXIT_OK;
        goto done;
    }
    if (!options.version && load_textures(&options, &textures, &error) != 0) goto done;

    /* llvmpipe, whatever GPU the machine has; its thread count from
     * --threads (0 renders on the calling thread, as luz's --threads 0). */
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    setenv("GALLIUM_DRIVER", "llvmpipe", 0);
    if (options.thread_count != LUZ_THREADS_AUTO) {
        char threads[16];
        snprintf(threads, sizeof threads, "%d", options.thread_count);
        setenv("LP_NUM_THREADS", threads, 1);
    }
    if (open_context(&gl, &error) != 0) goto done;
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    if (renderer == NULL || strstr(renderer, "llvmpipe") == NULL) {
        luz_error_set(&error, "the OpenGL renderer is '%s', not Mesa's "
                      "llvmpipe; glref compares with llvmpipe only",
                      renderer ? renderer : "unknown");
        goto done;
    }

    if (options.version) {
        /* The version, and which llvmpipe it runs on (tools/conformance
         * prints it, and uses it to see whether llvmpipe is there at all). */
#if defined(GLREF_HAVE_ASSIMP)
        printf("glref (luz %s, models read with assimp %u.%u.%u)\n", LUZ_VERSION,
               aiGetVersionMajor(), aiGetVersionMinor(), aiGetVersionRevision());
#else
        printf("glref (luz %s, no models: built without assimp)\n", LUZ_VERSION);
#endif
        printf("OpenGL %s on %s\n", (const char *)glGetString(GL_VERSION), renderer);
        status = EXIT_OK;
        goto done;
    }

    status = EXIT_RUNTIME;
    data.object_count = options.scene.objects ? options.scene.object_count
                                              : options.scene.cube_count;
    size_t slots = (size_t)(data.object_count > 0 ? data.object_count : 1);
    data.colours = malloc(slots * sizeof *data.colours);
    data.object_models = malloc(slots * sizeof *data.object_models);
    if (data.colours == NULL || data.object_models == NULL) {
        luz_error_set(&error, "out of memory for %d objects", data.object_count);
        goto done;
    }
    luz_scene_random_colours(options.scene.seed, data.object_count, data.colours);
    if (build_program(&gl, &error) != 0) goto done;
    upload_cube(&gl);
    if (upload_textures(&gl, &textures, options.scene.filter, &error) != 0) goto done;
    /* A model that cannot be read is the user's error, as in luz-render. */
    if (load_models(&gl, &options, data.object_models, &error) != 0) {
        status = EXIT_USAGE;
        goto done;
    }
    glBindVertexArray(gl.vertex_array);
    if (create_framebuffer(&gl, options.width, options.height,
                           settings.check_samples ? 4 : settings.samples, &error) != 0) {
        status = EXIT_USAGE;
        goto done;
    }
    if (settings.check_samples) {
        status = check_sample_positions(&gl) == 0 ? EXIT_OK : EXIT_RUNTIME;
        if (status != EXIT_OK) luz_error_set(&error, "llvmpipe's 4 samples are not SCENE.md's");
        goto done;
    }
    if ((options.bench_frames > 0 ? bench(&gl, &data, &error)
                                  : render_files(&gl, &data, &error)) != 0)
        goto done;
    status = EXIT_OK;

done:
    if (status != EXIT_OK) print_error(error.message[0] ? error.message : "failed");
    close_reference(&gl);
    free(data.colours);
    free(data.object_models);
    luz_texture_set_free(&textures);
    luz_options_free(&options);
    if (fflush(stdout) != 0 && status == EXIT_OK) {
        print_error("cannot write to standard output");
        status = EXIT_RUNTIME;
    }
    return status;
}
