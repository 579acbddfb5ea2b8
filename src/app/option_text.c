/*
 * option_text.c: numbers written back as the shortest decimal that reads
 * back to the same bits (see option_text.h).
 *
 * The shortest decimal of a float v is the one with the fewest significant
 * digits among those the reader (strtod, then a cast to float) turns into
 * v. Those decimals form an interval around v, from half-way to the float
 * below to half-way to the float above, so at N digits only two decimals
 * can be in it: the largest N-digit decimal at or below |v| and the
 * smallest at or above. Any other N-digit decimal is farther from v than
 * one of those two, on the same side, and an interval that holds it holds
 * that one too. The nearest N-digit decimal (what %.*e gives) is one of
 * the two, and usually the one that reads back; but where the interval is
 * lopsided (at a power of two the float below is half as far away as the
 * float above) the other one may read back when the nearest does not. So
 * each digit count tries both, and the first count where one of them reads
 * back is the shortest. The reader itself decides what "reads back" means,
 * so the text is never one the option parser would refuse (FLT_MAX's
 * 3.4028235e+38 lies above FLT_MAX, which option_read_numbers allows for
 * exactly this reason).
 *
 * The two neighbours come from |v|'s digits, printed to 41 significant
 * digits by printf (exact in glibc): truncating them to N digits gives the
 * lower neighbour, or one above it when the rounding to 41 digits carried
 * into digit N; so the candidates at N digits are that truncation t, t + 1
 * and t - 1 (the nearest first), and one of them is each neighbour.
 */
#include "app/option_text.h"

#include <inttypes.h>
#include <stdint.h>

/* A decimal m x 10^scale, m > 0 with at most 17 digits. */
typedef struct decimal {
    uint64_t mantissa;
    int scale;
} decimal;

/* Writes negative, m x 10^scale as a person writes it: positional from
 * 1e-4 up to 1e15, else with an exponent as %e writes one. */
static void write_decimal(char *buffer, size_t size, bool negative, decimal number)
{
    char digits[24];
    while (number.mantissa % 10 == 0) {   /* no trailing zeros in the digits */
        number.mantissa /= 10;
        number.scale++;
    }
    int count = snprintf(digits, sizeof digits, "%" PRIu64, number.mantissa);
    int exponent = number.scale + count - 1;   /* of the first digit */
    const char *sign = negative ? "-" : "";
    if (exponent < -4 || exponent >= 15) {
        snprintf(buffer, size, "%s%c%s%.*s%c%c%02d", sign, digits[0], count > 1 ? "." : "",
                 count - 1, digits + 1, 'e', exponent < 0 ? '-' : '+',
                 exponent < 0 ? -exponent : exponent);
    } else if (exponent < 0) {
        snprintf(buffer, size, "%s0.%.*s%s", sign, -exponent - 1, "0000", digits);
    } else if (count <= exponent + 1) {
        snprintf(buffer, size, "%s%s%.*s", sign, digits, exponent + 1 - count,
                 "000000000000000");
    } else {
        snprintf(buffer, size, "%s%.*s.%s", sign, exponent + 1, digits, digits + exponent + 1);
    }
}

/* Does text read back, through option_read_numbers, as exactly value? */
static bool reads_back(const char *text, double value, bool single_precision)
{
    double number;
    if (option_read_numbers(text, &number, 1, single_precision) != OPTION_PARSE_OK)
        return false;
    return single_precision ? (float)number == (float)value : number == value;
}

/* |value|'s first 41 significant digits and the exponent of the first. */
static void expand(double magnitude, char digits[42], int *exponent)
{
    char text[64];
    snprintf(text, sizeof text, "%.40e", magnitude);   /* d.ddd...de+XX */
    digits[0] = text[0];
    memcpy(digits + 1, text + 2, 40);
    digits[41] = '\0';
    *exponent = atoi(strchr(text, 'e') + 1);
}

static void format_shortest(char *buffer, size_t size, double value, bool single_precision)
{
    if (!isfinite(value)) {   /* a probed pixel's NaN normal, say: no digits to find */
        snprintf(buffer, size, "%s", isnan(value) ? "nan" : value < 0.0 ? "-inf" : "inf");
        return;
    }
    if (value == 0.0) {
        snprintf(buffer, size, "%s", signbit(value) ? "-0" : "0");
        return;
    }
    const bool negative = value < 0.0;
    const double magnitude = fabs(value);
    char digits[42];
    int exponent;
    expand(magnitude, digits, &exponent);
    for (int count = 1; count <= 17; count++) {
        /* The nearest decimal of `count` digits, then the truncation's
         * neighbours: see the comment at the top. */
        char nearest_text[40];
        snprintf(nearest_text, sizeof nearest_text, "%.*e", count - 1, magnitude);
        char nearest_digits[24];
        int n = 0;
        for (const char *c = nearest_text; *c != 'e'; c++)
            if (*c != '.')
                nearest_digits[n++] = *c;
        nearest_digits[n] = '\0';
        const int nearest_exponent = atoi(strchr(nearest_text, 'e') + 1);

        char truncated_digits[24];
        memcpy(truncated_digits, digits, (size_t)count);
        truncated_digits[count] = '\0';
        const uint64_t truncated = strtoull(truncated_digits, NULL, 10);
        const int scale = exponent - (count - 1);

        const decimal candidates[4] = {
            {strtoull(nearest_digits, NULL, 10), nearest_exponent - (count - 1)},
            {truncated, scale},
            {truncated + 1, scale},
            {truncated - 1, scale},   /* 0 when truncated is 1: skipped */
        };
        for (int k = 0; k < 4; k++) {
            if (candidates[k].mantissa == 0)
                continue;
            write_decimal(buffer, size, negative, candidates[k]);
            if (reads_back(buffer, value, single_precision))
                return;
        }
    }
    /* Not reached for a finite value: 17 digits give back every double,
     * and a float is one. */
    snprintf(buffer, size, "%.17g", value);
}

void option_format_float(char *buffer, size_t size, float value)
{
    format_shortest(buffer, size, (double)value, true);
}

void option_format_double(char *buffer, size_t size, double value)
{
    format_shortest(buffer, size, value, false);
}
