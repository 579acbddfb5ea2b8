/*
 * model_guards.c: what a model file must look like before assimp is let
 * near it.
 *
 * In:  the first bytes of a model file and its size.
 * Out: 0, or one line saying why assimp would misbehave on it.
 *
 * luz cannot fix Debian's assimp, only keep from it the inputs its fuzzer
 * found to hang or crash it, where a check costs little. assimp 5.2.5's
 * PLY parser loops forever on a header that never reaches its
 * end_header line (reproducers in tests/fuzz/assimp-findings/), and
 * believes any element count; so a PLY header (Turk, "The PLY Polygon
 * File Format") is read here first: it must end, within its first
 * LUZ_PLY_HEADER_MAX_BYTES, with an end_header line, and each
 * `element NAME COUNT` must give its count in decimal digits, no more
 * than the file has bytes. Other lines are left to assimp, which skips
 * what it does not know (Blender once wrote comments without `comment`).
 * A binary glTF's lengths are checked against the file's size, since
 * assimp allocates what they say before it reads.
 */
#include "io/model_guards.h"

#include <stdbool.h>
#include <string.h>

#include "io/input_file.h"

/* The next line of the header, without its end (\n, or \r\n). Returns
 * false at the end of the bytes. */
static bool next_line(const unsigned char **cursor, const unsigned char *end,
                      const unsigned char **line, size_t *length)
{
    if (*cursor >= end) return false;
    const unsigned char *newline = memchr(*cursor, '\n', (size_t)(end - *cursor));
    if (newline == NULL) return false;
    *line = *cursor;
    *length = (size_t)(newline - *cursor);
    if (*length > 0 && (*line)[*length - 1] == '\r') (*length)--;
    *cursor = newline + 1;
    return true;
}

/* Splits a line into at most `capacity` words at blanks. */
static int split_words(const unsigned char *line, size_t length, const unsigned char **words,
                       size_t *lengths, int capacity)
{
    int count = 0;
    for (size_t i = 0; i < length;) {
        while (i < length && (line[i] == ' ' || line[i] == '\t')) i++;
        if (i == length) break;
        size_t start = i;
        while (i < length && line[i] != ' ' && line[i] != '\t') i++;
        if (count == capacity) return capacity + 1;
        words[count] = line + start;
        lengths[count] = i - start;
        count++;
    }
    return count;
}

static bool word_is(const unsigned char *word, size_t length, const char *text)
{
    return length == strlen(text) && memcmp(word, text, length) == 0;
}

static int check_ply(const unsigned char *start, size_t length, uint64_t file_size,
                     const char *name, luz_error *error)
{
    const unsigned char *end = start + length, *cursor = start, *line;
    size_t line_length;
    int number = 0;
    while (next_line(&cursor, end, &line, &line_length)) {
        number++;
        const unsigned char *words[4];
        size_t lengths[4];
        int count = split_words(line, line_length, words, lengths, 3);
        if (count == 0) continue;
        if (count == 1 && word_is(words[0], lengths[0], "end_header")) return 0;
        if (!word_is(words[0], lengths[0], "element")) continue;
        /* element NAME COUNT: a count in decimal digits, no more elements
         * than the file has bytes */
        bool valid = count == 3 && lengths[2] <= 19;
        uint64_t elements = 0;
        for (size_t i = 0; i < lengths[2] && valid; i++) {
            valid = words[2][i] >= '0' && words[2][i] <= '9';
            elements = elements * 10 + (uint64_t)(words[2][i] - '0');
        }
        if (!valid)
            return luz_error_set(error, "%s: PLY header line %d: expected `element NAME COUNT`, "
                                        "COUNT in decimal digits", name, number);
        if (elements > file_size)
            return luz_error_set(error, "%s: PLY header line %d: %llu elements in a file of "
                                        "%llu bytes", name, number, (unsigned long long)elements,
                                 (unsigned long long)file_size);
    }
    return luz_error_set(error, "%s: a PLY header without its end_header line in its first %d "
                                "bytes", name, LUZ_PLY_HEADER_MAX_BYTES);
}

static uint32_t little_endian_32(const unsigned char *p)
{
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

/* A binary glTF (glTF 2.0 specification, "GLB File Format"; glTF 1.0's
 * KHR_binary_glTF): the 12-byte header (magic, version, length), then a
 * JSON chunk (2.0: its length and type; 1.0: the content's length and
 * format). assimp allocates, and fills with zeros, as many bytes as the
 * lengths say before it reads them: 4 GiB for a file of a kilobyte. */
static int check_glb(const unsigned char *start, size_t length, uint64_t file_size,
                     const char *name, luz_error *error)
{
    if (length < 20)
        return luz_error_set(error, "%s: a binary glTF of %llu bytes, shorter than its headers",
                             name, (unsigned long long)file_size);
    const uint32_t version = little_endian_32(start + 4);
    const uint32_t total = little_endian_32(start + 8), chunk = little_endian_32(start + 12);
    if (total > file_size || chunk > file_size - 20)
        return luz_error_set(error, "%s: a binary glTF %s %u bytes, the file has %llu", name,
                             total > file_size ? "whose header claims" : "whose JSON claims",
                             (unsigned)(total > file_size ? total : chunk),
                             (unsigned long long)file_size);
    if (version != 1 && version != 2)
        return luz_error_set(error, "%s: a binary glTF of version %u, expected 1 or 2", name,
                             (unsigned)version);
    return 0;
}

int luz_model_check_start(const unsigned char *start, size_t length, uint64_t file_size,
                          const char *name, luz_error *error)
{
    if (length > LUZ_PLY_HEADER_MAX_BYTES) length = LUZ_PLY_HEADER_MAX_BYTES;
    /* assimp's PLY parser reads on from a magic of p, l, y in either
     * case, whatever follows */
    const bool ply = length >= 3 && (start[0] | 0x20) == 'p' && (start[1] | 0x20) == 'l' &&
                     (start[2] | 0x20) == 'y';
    if (ply && check_ply(start, length, file_size, name, error) != 0) return LUZ_BAD_INPUT;
    if (length >= 4 && memcmp(start, "glTF", 4) == 0 &&
        check_glb(start, length, file_size, name, error) != 0)
        return LUZ_BAD_INPUT;
    return 0;
}
