/*
 * test_support.h: what several test programs share. Include after
 * <cmocka.h>.
 *
 * assert_near(got, expected, tolerance) fails the test, naming the
 * expression and both values, when |got - expected| > tolerance.
 * test_random and test_uniform: a small generator whose sequence is the
 * same on every machine, for tests that draw many random cases.
 */
#ifndef LUZ_TEST_SUPPORT_H
#define LUZ_TEST_SUPPORT_H

#include <math.h>
#include <stdint.h>

#define assert_near(got, expected, tolerance) \
    assert_near_at((got), (expected), (tolerance), #got, __FILE__, __LINE__)

static inline void assert_near_at(double got, double expected, double tolerance,
                                  const char *expression, const char *file, int line)
{
    if (fabs(got - expected) <= tolerance) return;
    print_error("%s = %.9g, expected %.9g (tolerance %.2g)\n", expression, got, expected,
                tolerance);
    _fail(file, line);
}

/* The next number of a linear congruential sequence (Numerical Recipes'
 * constants), its high 24 bits. */
static inline uint32_t test_random(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

/* A float in [low, high), in steps of (high - low) / 65536. */
static inline float test_uniform(uint32_t *state, float low, float high)
{
    return low + (high - low) * (float)(test_random(state) & 0xffff) / 65536.0f;
}

#endif
