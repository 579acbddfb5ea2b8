/*
 * test_numbers.c: the numbers --print-state, F2 and luz_options_write_scene
 * write are the shortest decimals that read back to the same bits.
 *
 * Each value goes through the option table as a saved scene does: set by
 * hand, written by luz_options_format, read back by luz_options_set_value
 * (the parser a scene file goes through). Two things must hold:
 *
 *   1. the text reads back to exactly the same bits (the sign of zero too);
 *   2. no decimal with fewer significant digits reads back to them.
 *
 * The second is checked here on its own, not with the writer's method: for
 * each shorter digit count N, every N-digit decimal within two units of the
 * value's own N-digit truncation, at the scales around its decade (worked
 * out with long double logarithms and division, with that margin for their
 * rounding), is given to the parser; none may come back as the value.
 * Any N-digit decimal that reads back lies between the value and one of
 * those, so none is missed.
 *
 * The values are the ones that break simple writers: 0.99f and the float
 * below it (0.98999995, whose neighbour 0.99 reads as another float),
 * 6.711322e-17, FLT_MAX (whose shortest text lies above FLT_MAX, which the
 * reader must accept), the smallest normal and the denormals, every power
 * of two (where the float below is half as far away as the float above,
 * so the nearest decimal of a length may miss while another of the same
 * length reads back; 2^-96 is one), integers past 2^24, negative numbers,
 * zeros, and a sweep of bit patterns across the whole range.
 */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "app/option_text.h"
#include "app/options.h"

/* Significant digits of a decimal text: from the first non-zero digit to
 * the last non-zero one, the exponent left out. */
static int significant_digits(const char *text)
{
    int first = -1, last = -1, index = 0;
    for (const char *c = text; *c != '\0' && *c != 'e' && *c != 'E'; c++) {
        if (*c < '0' || *c > '9')
            continue;
        if (*c != '0') {
            if (first < 0)
                first = index;
            last = index;
        }
        index++;
    }
    return first < 0 ? 1 : last - first + 1;   /* "0" has one */
}

/* What the scene-file reader makes of text for a float option, or false
 * if it refuses it. */
static bool read_float(const char *text, float *value)
{
    luz_options options;
    luz_options_init(&options);
    luz_error error = {{0}};
    bool ok = luz_options_set_value(&options, "camera-yaw", text, NULL, &error) == 0;
    *value = options.scene.camera.yaw_degrees;
    luz_options_free(&options);
    return ok;
}

static bool read_double(const char *text, double *value)
{
    luz_options options;
    luz_options_init(&options);
    luz_error error = {{0}};
    bool ok = luz_options_set_value(&options, "time", text, NULL, &error) == 0;
    *value = options.scene.time_seconds;
    luz_options_free(&options);
    return ok;
}

static bool same_float(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static bool same_double(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Does some decimal of `digits` significant digits read back as value?
 * (single: through the float reader, else the double one.) */
static bool shorter_reads_back(long double value, int digits, bool single, char *found,
                               size_t size)
{
    const long double magnitude = fabsl(value);
    const int decade = (int)floorl(log10l(magnitude));
    for (int exponent = decade - 1; exponent <= decade + 1; exponent++) {
        const int scale = exponent - digits + 1;
        const long double truncated = floorl(magnitude / powl(10.0L, (long double)scale));
        for (long double d = truncated - 2; d <= truncated + 2; d += 1) {
            if (d <= 0 || d >= powl(10.0L, (long double)digits))
                continue;
            snprintf(found, size, "%s%.0Lfe%d", value < 0 ? "-" : "", d, scale);
            if (single) {
                float back;
                if (read_float(found, &back) && same_float(back, (float)value))
                    return true;
            } else {
                double back;
                if (read_double(found, &back) && same_double(back, (double)value))
                    return true;
            }
        }
    }
    return false;
}

static void check_float(float value)
{
    luz_options options;
    luz_options_init(&options);
    options.scene.camera.yaw_degrees = value;
    char text[64];
    assert_int_equal(luz_options_format(&options, "camera-yaw", text, sizeof text), 0);
    luz_options_free(&options);

    float back;
    if (!read_float(text, &back))
        fail_msg("%.9g written as '%s', which the reader refuses", (double)value, text);
    if (!same_float(back, value))
        fail_msg("%.9g written as '%s', which reads back as %.9g", (double)value, text,
                 (double)back);
    if (value == 0.0f)
        return;
    int digits = significant_digits(text);
    char shorter[64];
    for (int n = 1; n < digits; n++)
        if (shorter_reads_back(value, n, true, shorter, sizeof shorter))
            fail_msg("%.9g written as '%s' (%d digits), but '%s' (%d) reads back too",
                     (double)value, text, digits, shorter, n);
}

static void check_double(double value)
{
    luz_options options;
    luz_options_init(&options);
    options.scene.time_seconds = value;
    char text[64];
    assert_int_equal(luz_options_format(&options, "time", text, sizeof text), 0);
    luz_options_free(&options);

    double back;
    if (!read_double(text, &back))
        fail_msg("%.17g written as '%s', which the reader refuses", value, text);
    if (!same_double(back, value))
        fail_msg("%.17g written as '%s', which reads back as %.17g", value, text, back);
    if (value == 0.0)
        return;
    int digits = significant_digits(text);
    char shorter[64];
    for (int n = 1; n < digits; n++)
        if (shorter_reads_back(value, n, false, shorter, sizeof shorter))
            fail_msg("%.17g written as '%s' (%d digits), but '%s' (%d) reads back too", value,
                     text, digits, shorter, n);
}

static float float_from_bits(uint32_t bits)
{
    float value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

/* The texts themselves, where the answer is known by hand. */
static void test_known_texts(void **state)
{
    (void)state;
    static const struct {
        float value;
        const char *text;
    } cases[] = {
        {0.2f, "0.2"},
        {0.99f, "0.99"},
        {0.98999995f, "0.98999995"},   /* the float below 0.99f */
        {6.711322e-17f, "6.711322e-17"},
        {FLT_MAX, "3.4028235e+38"},
        {-FLT_MAX, "-3.4028235e+38"},
        {FLT_MIN, "1.1754944e-38"},
        {1.4e-45f, "1e-45"},   /* the smallest denormal, 2^-149 */
        {-90.0f, "-90"},
        {1e15f, "1e+15"},
        {0.0015f, "0.0015"},
        {0.0001f, "0.0001"},
        {0.00001f, "1e-05"},
        {16777216.0f, "16777216"},
        {33871888.0f, "33871890"},   /* 7 digits; 33871888 has 8 */
        {0x1p-96f, "1.2621775e-29"}, /* the nearest 8-digit decimal, 1.2621774e-29,
                                        does not read back: the float below is closer */
        {-0.0f, "-0"},
        {0.0f, "0"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        luz_options options;
        luz_options_init(&options);
        options.scene.camera.yaw_degrees = cases[i].value;
        char text[64];
        assert_int_equal(luz_options_format(&options, "camera-yaw", text, sizeof text), 0);
        assert_string_equal(text, cases[i].text);
        luz_options_free(&options);
        check_float(cases[i].value);
    }
    /* Not finite (never a setting: a probed pixel's value can be): a
     * word, not digits, and not something the reader takes back. */
    const struct {
        float value;
        const char *text;
    } words[] = {{NAN, "nan"}, {-NAN, "nan"}, {INFINITY, "inf"}, {-INFINITY, "-inf"}};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++) {
        char text[OPTION_NUMBER_SIZE];
        option_format_float(text, sizeof text, words[i].value);
        assert_string_equal(text, words[i].text);
        option_format_double(text, sizeof text, (double)words[i].value);
        assert_string_equal(text, words[i].text);
        double number;
        assert_int_not_equal(option_read_numbers(text, &number, 1, true), OPTION_PARSE_OK);
    }
    /* 0.98999995 is not 0.99f: the test above would mean nothing else. */
    assert_true(0.98999995f != 0.99f);
    assert_true(nextafterf(0.99f, 0.0f) == 0.98999995f);
}

static void test_tricky_floats(void **state)
{
    (void)state;
    const float values[] = {
        0.99f, 0.98999995f, 6.711322e-17f, FLT_MAX, -FLT_MAX, nextafterf(FLT_MAX, 0.0f),
        FLT_MIN, nextafterf(FLT_MIN, 0.0f), nextafterf(FLT_MIN, 1.0f),
        float_from_bits(1), float_from_bits(2), float_from_bits(3), float_from_bits(0x7fffff),
        float_from_bits(0x400000), float_from_bits(0x123456), -float_from_bits(5),
        0.1f, 1.0f / 3.0f, 2.0f / 3.0f, 1e-4f, nextafterf(1e-4f, 0.0f), 1e15f,
        nextafterf(1e15f, 0.0f), 1e10f, 1e-10f, 123456789.0f, 0.3f, 12.5f, -89.0f, 17.5f,
        0.7f, 0.6f, 0.05f * 19.0f, 3.14159265f, 100.0f, 1000000.0f, 9999999.0f, 1e38f,
    };
    for (size_t i = 0; i < sizeof values / sizeof values[0]; i++)
        check_float(values[i]);
    /* Every power of two and its neighbours: the lopsided intervals. */
    for (int k = -149; k <= 127; k++) {
        float power = ldexpf(1.0f, k);
        check_float(power);
        check_float(nextafterf(power, 0.0f));
        check_float(nextafterf(power, INFINITY));
        check_float(-power);
    }
    /* Powers of ten and their neighbours: decades change digit counts. */
    for (int k = -45; k <= 38; k++) {
        float power = (float)pow(10.0, k);
        if (power == 0.0f || isinf(power))
            continue;
        check_float(power);
        check_float(nextafterf(power, 0.0f));
        check_float(nextafterf(power, INFINITY));
    }
}

static void test_float_sweep(void **state)
{
    (void)state;
    /* About 12,000 finite floats spread over every exponent, both signs. */
    for (uint32_t bits = 0; bits < 0x7f800000u; bits += 0x7f800000u / 6007u + 1u) {
        check_float(float_from_bits(bits));
        check_float(float_from_bits(bits | 0x80000000u));
    }
}

static void test_tricky_doubles(void **state)
{
    (void)state;
    /* The time, the one double written, lies within -1e9 to 1e9 seconds
     * (docs/cli.md): the values are tricky ones within that range. */
    const double values[] = {
        0.1, 1.0 / 3.0, 2.5, 1.2345678901234567, 0.30000000000000004, 123456789.123456789,
        1e9, -1e9, nextafter(1e9, 0.0), DBL_MIN, nextafter(DBL_MIN, 0.0),
        4.9406564584124654e-324, 0x1p-96, 97.3, 1e-4, 5e-324 * 3, 39.27, 10.9956, -0.0, 0.0,
    };
    for (size_t i = 0; i < sizeof values / sizeof values[0]; i++)
        check_double(values[i]);
    for (int k = -1074; k <= 29; k += 7) {   /* 2^29 < 1e9 < 2^30 */
        double power = ldexp(1.0, k);
        check_double(power);
        check_double(nextafter(power, 0.0));
    }
    /* A time the viewer reaches by adding frame after frame. */
    double time = 0.0;
    for (int frame = 0; frame < 1000; frame++)
        time += 0.016667;
    check_double(time);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_known_texts),
        cmocka_unit_test(test_tricky_floats),
        cmocka_unit_test(test_float_sweep),
        cmocka_unit_test(test_tricky_doubles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
