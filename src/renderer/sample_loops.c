/*
 * sample_loops.c: the plain loops of the raster and the resolve that wider
 * vectors speed up, compiled once per instruction set (cpu.h's table).
 *
 * In, out: luz_mixed_pixels_function's (pipeline.h): the pixels of a row
 * whose four samples' winners differ (resolve.c's
 * luz_samples_sort_winners); and luz_centre_span_function's, one sample a
 * pixel's long spans (raster.c's luz_raster_triangle_spans). (Four
 * samples' depth tests, once here too, are in lanes in raster_lanes.c.)
 *
 * Why a file of their own: these are plain C that the compiler
 * vectorises, and the AVX-512 copy does sixteen lanes at once where the
 * build's target does four. Each instruction set gets its copy from this one
 * source (src/renderer/meson.build: the build's target, AVX2 and AVX-512,
 * each at -O3, where GCC vectorises such loops), and cpu.c puts the set's
 * copy in the renderer's table with the other kernels: LUZ_ISA=sse2 runs
 * no AVX code here either. (They used to be target_clones, which the
 * loader chose by the CPU alone.)
 */
#include "renderer/pipeline.h"

#if defined(LUZ_LOOPS_AVX512)
#define LOOPS_NAME(name) name##_avx512
#elif defined(LUZ_LOOPS_AVX2)
#define LOOPS_NAME(name) name##_avx2
#else
#define LOOPS_NAME(name) name##_baseline
#endif

luz_mixed_pixels_function LOOPS_NAME(luz_mixed_pixels_of_row);
luz_centre_span_function LOOPS_NAME(luz_centre_span_test);

/* The depth tests of a row's span for one sample a pixel, at each pixel
 * centre (raster.c's long spans: a face of the lab's cubes), each
 * independent of its neighbours: GL_LESS. */
void LOOPS_NAME(luz_centre_span_test)(luz_plane depth, float reference_x, float row_depth,
                                      int first, int last, float *depth_row,
                                      uint32_t *visibility_row, uint32_t triangle_id)
{
    for (int x = first; x <= last; x++) {
        float z = luz_raster_depth(depth, reference_x, row_depth, x);
        if (z < depth_row[x]) {
            depth_row[x] = z;
            visibility_row[x] = triangle_id;
        }
    }
}

/* Pixels looked at together for "do all four samples agree?": one AVX-512
 * vector of ids, or two AVX2 ones. Most chunks of a row agree (inside a
 * surface, or the background) and are passed over at a few instructions
 * each. */
#define CHUNK 16

int LOOPS_NAME(luz_mixed_pixels_of_row)(const uint32_t *ids, int width, uint32_t *first,
                                        uint16_t *mixed_x)
{
    int count = 0;
    for (int x0 = 0; x0 < width; x0 += CHUNK) {
        const int end = width - x0 < CHUNK ? width : x0 + CHUNK;
        uint32_t differ = 0;
        for (int x = x0; x < end; x++) {
            const uint32_t *id = ids + (size_t)x * LUZ_MAX_SAMPLES;
            differ |= (id[0] ^ id[1]) | (id[0] ^ id[2]) | (id[0] ^ id[3]);
            first[x] = id[0];
        }
        if (differ == 0) continue;
        /* Without a branch per pixel (a chunk an edge crosses mixes
         * pixels that differ with pixels that agree, and the branches
         * were mispredicted): each x is written, and kept when its pixel
         * differs. There is room: count <= x < width. */
        for (int x = x0; x < end; x++) {
            const uint32_t *id = ids + (size_t)x * LUZ_MAX_SAMPLES;
            mixed_x[count] = (uint16_t)x;
            count += (id[0] != id[1]) | (id[0] != id[2]) | (id[0] != id[3]);
        }
    }
    return count;
}
