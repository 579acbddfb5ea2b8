/*
 * cpu.c: which instruction set this CPU runs, asked once, and the one
 * table of kernels for it (cpu.h).
 *
 * In:  the CPU (cpuid, through the compiler's __builtin_cpu_supports),
 *      the variants this build compiled (LUZ_HAVE_* from meson.build),
 *      and LUZ_ISA from the environment.
 * Out: a luz_kernels table: every stage in lanes of the same set.
 *
 * Why one place: each stage used to ask the CPU itself, and the fragment
 * stage's own choice decided the others'. Here a set is chosen once, by
 * name, and LUZ_ISA can force a narrower one, so that the AVX2, SSE2 and
 * scalar paths run (and are compared, byte for byte) on a machine that
 * has AVX-512. The table lives in the renderer: no global state.
 */
#include <stdlib.h>
#include <string.h>

#include "renderer/cpu.h"

/* The variants this build compiled (src/renderer/meson.build). */
luz_packet_rows_function luz_fragment_packet_rows_scalar, luz_fragment_packet_rows_baseline;
luz_packet_list_function luz_fragment_packet_list_scalar, luz_fragment_packet_list_baseline;
luz_screen_function luz_screen_every_triangle;
luz_setup_eight_function luz_setup_eight_scalar;
luz_vertex_project_function luz_vertex_project_scalar;
luz_mixed_pixels_function luz_mixed_pixels_of_row_baseline;
luz_centre_span_function luz_centre_span_test_baseline;
#if defined(LUZ_HAVE_SSE2)
luz_raster_groups_function luz_raster_groups_sse2;
luz_raster_list_function luz_raster_list_sse2;
luz_screen_function luz_screen_triangles_sse2, luz_screen_triangles_four_sse2;
luz_setup_eight_function luz_setup_eight_sse2, luz_setup_eight_four_sse2;
luz_vertex_project_function luz_vertex_project_sse2;
#endif
#if defined(LUZ_HAVE_AVX2)
luz_raster_groups_function luz_raster_groups_avx2;
luz_raster_list_function luz_raster_list_avx2;
luz_packet_rows_function luz_fragment_packet_rows_avx2;
luz_packet_list_function luz_fragment_packet_list_avx2;
luz_screen_function luz_screen_triangles_avx2, luz_screen_triangles_four_avx2;
luz_setup_eight_function luz_setup_eight_avx2, luz_setup_eight_four_avx2;
luz_vertex_project_function luz_vertex_project_avx2;
luz_mixed_pixels_function luz_mixed_pixels_of_row_avx2;
luz_centre_span_function luz_centre_span_test_avx2;
#endif
#if defined(LUZ_HAVE_NEON)
luz_raster_groups_function luz_raster_groups_neon;
luz_raster_list_function luz_raster_list_neon;
luz_screen_function luz_screen_triangles_neon, luz_screen_triangles_four_neon;
luz_setup_eight_function luz_setup_eight_neon, luz_setup_eight_four_neon;
luz_vertex_project_function luz_vertex_project_neon;
#endif
#if defined(LUZ_HAVE_AVX512)
luz_raster_groups_function luz_raster_groups_avx512;
luz_raster_list_function luz_raster_list_avx512;
luz_packet_rows_function luz_fragment_packet_rows_avx512;
luz_packet_list_function luz_fragment_packet_list_avx512;
luz_screen_function luz_screen_triangles_avx512, luz_screen_triangles_four_avx512;
luz_setup_eight_function luz_setup_eight_avx512, luz_setup_eight_four_avx512;
luz_vertex_project_function luz_vertex_project_avx512;
luz_mixed_pixels_function luz_mixed_pixels_of_row_avx512;
luz_centre_span_function luz_centre_span_test_avx512;
#endif

const char *luz_isa_name(luz_isa isa)
{
    switch (isa) {
    case LUZ_ISA_SCALAR:
        return "scalar";
    case LUZ_ISA_BASELINE:
#if defined(__x86_64__)
        return "sse2";
#elif defined(__aarch64__)
        return "neon";
#else
        return "vector";
#endif
    case LUZ_ISA_AVX2:
        return "avx2";
    case LUZ_ISA_AVX512:
        return "avx512";
    }
    return "?";
}

bool luz_isa_available(luz_isa isa)
{
    switch (isa) {
    case LUZ_ISA_SCALAR:
    case LUZ_ISA_BASELINE:   /* the build's own target */
        return true;
    case LUZ_ISA_AVX2:
#if defined(LUZ_HAVE_AVX2)
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
        return false;
#endif
    case LUZ_ISA_AVX512:
#if defined(LUZ_HAVE_AVX512)
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
        return false;
#endif
    }
    return false;
}

luz_isa luz_isa_widest(void)
{
    luz_isa widest = LUZ_ISA_SCALAR;
    for (int isa = LUZ_ISA_SCALAR; isa < LUZ_ISA_COUNT; isa++)
        if (luz_isa_available((luz_isa)isa)) widest = (luz_isa)isa;
    return widest;
}

/* The names this build knows: every set it compiles for its CPU family. */
static bool known_here(luz_isa isa)
{
#if defined(__x86_64__)
    (void)isa;
    return true;
#else
    return isa == LUZ_ISA_SCALAR || isa == LUZ_ISA_BASELINE;
#endif
}

/* "avx512, avx2, sse2 or scalar": the sets for which included() holds,
 * widest first, the last after `last` ("or", "and"). */
static void list_sets(char *text, size_t size, bool (*included)(luz_isa), const char *last)
{
    int count = 0, listed = 0;
    for (int isa = 0; isa < LUZ_ISA_COUNT; isa++) count += included((luz_isa)isa);
    text[0] = '\0';
    for (int isa = LUZ_ISA_COUNT - 1; isa >= 0; isa--) {
        if (!included((luz_isa)isa)) continue;
        if (listed > 0) strncat(text, listed == count - 1 ? " " : ", ", size - strlen(text) - 1);
        if (listed > 0 && listed == count - 1) {
            strncat(text, last, size - strlen(text) - 1);
            strncat(text, " ", size - strlen(text) - 1);
        }
        strncat(text, luz_isa_name((luz_isa)isa), size - strlen(text) - 1);
        listed++;
    }
}

int luz_isa_chosen(luz_isa *out, luz_error *error)
{
    const char *name = getenv("LUZ_ISA");
    if (name == NULL || name[0] == '\0') {
        *out = luz_isa_widest();
        return 0;
    }
    char runs[64], expected[64];
    list_sets(runs, sizeof runs, luz_isa_available, "and");
    list_sets(expected, sizeof expected, luz_isa_available, "or");
    for (int isa = 0; isa < LUZ_ISA_COUNT; isa++) {
        if (!known_here((luz_isa)isa) || strcmp(name, luz_isa_name((luz_isa)isa)) != 0)
            continue;
        if (!luz_isa_available((luz_isa)isa))
            return luz_error_set(error, "LUZ_ISA=%s: this CPU lacks it; expected %s", name,
                                 expected);
        *out = (luz_isa)isa;
        return 0;
    }
    char known[64];
    list_sets(known, sizeof known, known_here, "or");
    return luz_error_set(error, "LUZ_ISA=%.40s: expected %s (this CPU runs %s)", name, known,
                         runs);
}

/* A set's geometry in lanes: screening that checks the small boxes, for
 * one sample and four, setup in lanes for each, and the vertex pass. */
static void set_geometry(luz_kernels *kernels, luz_screen_function *screen,
                         luz_screen_function *screen_four, luz_setup_eight_function *setup_eight,
                         luz_setup_eight_function *setup_eight_four,
                         luz_vertex_project_function *vertex_project)
{
    kernels->screen = screen;
    kernels->screen_checks_small_boxes = true;
    kernels->setup_eight = setup_eight;
    kernels->screen_four = screen_four;
    kernels->setup_eight_four = setup_eight_four;
    kernels->vertex_project = vertex_project;
}

luz_kernels luz_kernels_of(luz_isa isa)
{
    /* Without a variant of its own, a stage runs its plain form:
     * screening lets every triangle through, and vertices and triangles
     * go one at a time. */
    luz_kernels kernels = {
        .isa = isa,
        .packet_rows = luz_fragment_packet_rows_baseline,
        .packet_list = luz_fragment_packet_list_baseline,
        .screen = luz_screen_every_triangle,
        .screen_checks_small_boxes = false,
        .setup_eight = NULL,
        .setup_eight_screens = false,
        .vertex_project = NULL,
        .screen_four = NULL,
        .setup_eight_four = NULL,
        .mixed_pixels = luz_mixed_pixels_of_row_baseline,
        .centre_span_test = luz_centre_span_test_baseline,
        .raster_groups = NULL,
        .raster_list = NULL,
    };
    switch (isa) {
    case LUZ_ISA_SCALAR:
        kernels.packet_rows = luz_fragment_packet_rows_scalar;
        kernels.packet_list = luz_fragment_packet_list_scalar;
        /* The reference's functions one at a time (lanes_scalar.c), in
         * the wider sets' data flow. */
        kernels.setup_eight = luz_setup_eight_scalar;
        kernels.setup_eight_screens = true;
        kernels.vertex_project = luz_vertex_project_scalar;
        break;
    case LUZ_ISA_BASELINE:
#if defined(LUZ_HAVE_NEON)
        set_geometry(&kernels, luz_screen_triangles_neon, luz_screen_triangles_four_neon,
                     luz_setup_eight_neon, luz_setup_eight_four_neon, luz_vertex_project_neon);
        kernels.raster_groups = luz_raster_groups_neon;
        kernels.raster_list = luz_raster_list_neon;
#elif defined(LUZ_HAVE_SSE2)
        set_geometry(&kernels, luz_screen_triangles_sse2, luz_screen_triangles_four_sse2,
                     luz_setup_eight_sse2, luz_setup_eight_four_sse2, luz_vertex_project_sse2);
        kernels.raster_groups = luz_raster_groups_sse2;
        kernels.raster_list = luz_raster_list_sse2;
#endif
        break;
    case LUZ_ISA_AVX2:
#if defined(LUZ_HAVE_AVX2)
        kernels.packet_rows = luz_fragment_packet_rows_avx2;
        kernels.packet_list = luz_fragment_packet_list_avx2;
        set_geometry(&kernels, luz_screen_triangles_avx2, luz_screen_triangles_four_avx2,
                     luz_setup_eight_avx2, luz_setup_eight_four_avx2, luz_vertex_project_avx2);
        kernels.raster_groups = luz_raster_groups_avx2;
        kernels.raster_list = luz_raster_list_avx2;
        kernels.mixed_pixels = luz_mixed_pixels_of_row_avx2;
        kernels.centre_span_test = luz_centre_span_test_avx2;
#endif
        break;
    case LUZ_ISA_AVX512:
#if defined(LUZ_HAVE_AVX512)
        kernels.packet_rows = luz_fragment_packet_rows_avx512;
        kernels.packet_list = luz_fragment_packet_list_avx512;
        set_geometry(&kernels, luz_screen_triangles_avx512, luz_screen_triangles_four_avx512,
                     luz_setup_eight_avx512, luz_setup_eight_four_avx512,
                     luz_vertex_project_avx512);
        kernels.mixed_pixels = luz_mixed_pixels_of_row_avx512;
        kernels.centre_span_test = luz_centre_span_test_avx512;
        kernels.raster_groups = luz_raster_groups_avx512;
        kernels.raster_list = luz_raster_list_avx512;
#endif
        break;
    }
    return kernels;
}
