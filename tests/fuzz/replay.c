/*
 * replay.c: runs a fuzz harness's LLVMFuzzerTestOneInput over files, as
 * libFuzzer would run them once each, for the suite (the fuzz-replay-NAME
 * tests, under ASan and UBSan in CI) and for reproducing a finding by hand:
 *
 *   build/tests/fuzz/fuzz-replay-scene tests/fuzz/corpus/scene crash-1234
 *
 * Each argument is a file, or a directory whose files (not below) are run
 * in the order of their names. Prints how many inputs ran; exit status 0,
 * or 1 if an argument could not be read. A finding aborts (or a sanitizer
 * reports it) while its input runs: the file's name is printed first.
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_support.h"

static int run_file(const char *path)
{
    FILE *file = fopen(path, "rb");
    if (file == NULL) {
        fprintf(stderr, "replay: %s: cannot open\n", path);
        return -1;
    }
    size_t capacity = 1 << 16, length = 0, got;
    uint8_t *data = malloc(capacity);
    while (data != NULL && (got = fread(data + length, 1, capacity - length, file)) > 0) {
        length += got;
        if (length == capacity) {
            uint8_t *grown = realloc(data, capacity *= 2);
            if (grown == NULL) free(data);
            data = grown;
        }
    }
    fclose(file);
    if (data == NULL) {
        fprintf(stderr, "replay: %s: out of memory\n", path);
        return -1;
    }
    /* the name first, so that a crash's report says which input it was */
    fprintf(stderr, "replay: %s\n", path);
    /* an exact copy, so that ASan sees a read past its end */
    uint8_t *exact = malloc(length ? length : 1);
    if (exact == NULL) {
        free(data);
        return -1;
    }
    memcpy(exact, data, length);
    free(data);
    LLVMFuzzerTestOneInput(exact, length);
    free(exact);
    return 0;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int run_directory(const char *path, int *count)
{
    DIR *directory = opendir(path);
    if (directory == NULL) {
        fprintf(stderr, "replay: %s: cannot open\n", path);
        return -1;
    }
    char **names = NULL;
    size_t name_count = 0;
    struct dirent *entry;
    while ((entry = readdir(directory)) != NULL) {
        if (entry->d_name[0] == '.') continue;
        char **grown = realloc(names, (name_count + 1) * sizeof *names);
        char *copy = grown ? strdup(entry->d_name) : NULL;
        if (grown) names = grown;
        if (copy == NULL) {
            fprintf(stderr, "replay: %s: out of memory\n", path);
            closedir(directory);
            for (size_t i = 0; i < name_count; i++) free(names[i]);
            free(names);
            return -1;
        }
        names[name_count++] = copy;
    }
    closedir(directory);
    qsort(names, name_count, sizeof *names, compare_names);
    int status = 0;
    for (size_t i = 0; i < name_count; i++) {
        char file[4096];
        snprintf(file, sizeof file, "%s/%s", path, names[i]);
        struct stat info;
        if (stat(file, &info) == 0 && S_ISREG(info.st_mode)) {
            if (run_file(file) != 0) status = -1;
            else (*count)++;
        }
        free(names[i]);
    }
    free(names);
    return status;
}

int main(int argc, char **argv)
{
    int count = 0, status = 0;
    for (int i = 1; i < argc; i++) {
        struct stat info;
        if (stat(argv[i], &info) == 0 && S_ISDIR(info.st_mode)) {
            if (run_directory(argv[i], &count) != 0) status = 1;
        } else if (run_file(argv[i]) != 0) {
            status = 1;
        } else {
            count++;
        }
    }
    printf("replay: %d inputs\n", count);
    return status;
}
