/* The compiler's one-lane vector masks, compiled with the flags of the
 * scalar fragment stage (src/renderer/meson.build's
 * luz_packet_scalar_args): GCC 12.2 folds a mask and-ed from one-lane
 * comparisons to 0 at -O2 unless its value-range pass is off
 * (docs/platforms.md, "A GCC bug in one-lane vectors"). The scalar
 * variant of fragment_packet.c is built on such masks, and whether the
 * bug shows there depends on how its functions are inlined; this is the
 * reduced case, so the flag that works round the bug is checked on every
 * build whatever fragment_packet.c's shape. Without -fno-tree-vrp, GCC
 * 12.2 fails it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

/* Kept out of line, as in the reduced case: inlined, its arguments would
 * be constants and nothing left to miscompile. */
#if defined(__clang__)
#define OUT_OF_LINE __attribute__((noinline))
#else
#define OUT_OF_LINE __attribute__((noipa))
#endif

typedef float one_float __attribute__((vector_size(4)));
typedef int one_int __attribute__((vector_size(4)));
typedef unsigned one_uint __attribute__((vector_size(4)));

/* Trilinear's choice in one lane: no level for a lane without a
 * triangle, two (blended) where lambda is below the last level, else one. */
OUT_OF_LINE static int levels_of(one_float lambda, int last, one_uint ids)
{
    if ((ids != 0u)[0] == 0) return 0;
    const one_int beyond_last = lambda >= (float)last;
    const one_int blended = ~beyond_last & (one_int)(ids != 0u);
    return blended[0] != 0 ? 2 : 1;
}

/* By hand: a lane with triangle 5 at lambda 3.5 of a chain whose last
 * level is 8 blends two levels; at lambda 8 or beyond it takes one; a
 * lane without a triangle none. */
static void test_one_lane_mask_and(void **state)
{
    (void)state;
    assert_int_equal(levels_of((one_float){3.5f}, 8, (one_uint){5}), 2);
    assert_int_equal(levels_of((one_float){8.0f}, 8, (one_uint){5}), 1);
    assert_int_equal(levels_of((one_float){3.5f}, 8, (one_uint){0}), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_lane_mask_and),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
