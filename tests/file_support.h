/*
 * file_support.h: the files and directories the tests that run programs
 * share (the test_cli_* programs through cli_support.h, test_options,
 * test_models, test_gen_model). Include after <cmocka.h>.
 *
 *   read_file(path, &length)   the whole file, NUL-terminated (NULL if it
 *                              cannot be opened); free() it
 *   remove_tree(path)          a file, or a directory and all below it
 *   list_tree(dir, "", out, n) every path under dir, sorted, one a line:
 *                              equal before and after a run that made no
 *                              file (neither an image nor a temporary)
 *   key_value(text, key, buf, n) the value of a `key=value` line of a
 *                              program's output (--probe's), NULL if none
 *   now_seconds()              the monotonic clock, for deadlines
 */
#ifndef LUZ_TEST_FILE_SUPPORT_H
#define LUZ_TEST_FILE_SUPPORT_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static inline char *read_file(const char *path, size_t *length_out)
{
    if (length_out != NULL) *length_out = 0;
    FILE *file = fopen(path, "rb");
    if (file == NULL) return NULL;
    size_t capacity = 1 << 16, length = 0, got;
    char *data = malloc(capacity + 1);
    while (data != NULL && (got = fread(data + length, 1, capacity - length, file)) > 0) {
        length += got;
        if (length == capacity) {
            capacity *= 2;
            char *grown = realloc(data, capacity + 1);
            if (grown == NULL) free(data);
            data = grown;
        }
    }
    fclose(file);
    if (data == NULL) return NULL;
    data[length] = '\0';
    if (length_out != NULL) *length_out = length;
    return data;
}

static inline void remove_tree(const char *path)
{
    struct stat info;
    if (lstat(path, &info) != 0) return;
    if (S_ISDIR(info.st_mode)) {
        DIR *directory = opendir(path);
        if (directory != NULL) {
            struct dirent *entry;
            while ((entry = readdir(directory)) != NULL) {
                if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
                    continue;
                char child[4096];
                int written = snprintf(child, sizeof child, "%s/%s", path, entry->d_name);
                if (written > 0 && (size_t)written < sizeof child) remove_tree(child);
            }
            closedir(directory);
        }
        rmdir(path);
    } else {
        unlink(path);
    }
}

static inline int file_support_compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static inline void list_tree(const char *directory, const char *prefix, char *out, size_t size)
{
    enum { MAX_ENTRIES = 512 };
    DIR *handle = opendir(directory);
    assert_non_null(handle);
    char *names[MAX_ENTRIES];
    int count = 0;
    struct dirent *entry;
    while ((entry = readdir(handle)) != NULL && count < MAX_ENTRIES) {
        if (strcmp(entry->d_name, ".") != 0 && strcmp(entry->d_name, "..") != 0)
            names[count++] = strdup(entry->d_name);
    }
    closedir(handle);
    qsort(names, (size_t)count, sizeof *names, file_support_compare_names);
    for (int i = 0; i < count; i++) {
        char path[4096], relative[4096];
        /* A test's own directories: a path that does not fit is its bug. */
        assert_true(snprintf(path, sizeof path, "%s/%s", directory, names[i]) <
                    (int)sizeof path);
        assert_true(snprintf(relative, sizeof relative, "%s%s", prefix, names[i]) <
                    (int)sizeof relative - 1);   /* room for the "/" below */
        size_t used = strlen(out);
        snprintf(out + used, size - used, "%s\n", relative);
        struct stat info;
        if (lstat(path, &info) == 0 && S_ISDIR(info.st_mode)) {
            strcat(relative, "/");
            list_tree(path, relative, out, size);
        }
        free(names[i]);
    }
}

static inline const char *key_value(const char *text, const char *key, char *buffer, size_t size)
{
    const size_t length = strlen(key);
    for (const char *line = text; *line != '\0';) {
        const char *end = strchr(line, '\n');
        const size_t line_length = end ? (size_t)(end - line) : strlen(line);
        if (line_length > length && strncmp(line, key, length) == 0 && line[length] == '=') {
            snprintf(buffer, size, "%.*s", (int)(line_length - length - 1), line + length + 1);
            return buffer;
        }
        if (end == NULL) break;
        line = end + 1;
    }
    return NULL;
}

static inline double now_seconds(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + (double)now.tv_nsec * 1e-9;
}

#endif
