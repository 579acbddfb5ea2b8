/*
 * test_support.h: what several test programs share. Include after
 * <cmocka.h>.
 *
 * assert_near(got, expected, tolerance) fails the test, naming the
 * expression and both values, when |got - expected| > tolerance.
 */
#ifndef LUZ_TEST_SUPPORT_H
#define LUZ_TEST_SUPPORT_H

#include <math.h>

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

#endif
