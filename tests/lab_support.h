/*
 * lab_support.h: one luz_lab (the lab's cube mesh) for a whole test
 * program, made on first use and freed at exit, so that tests which draw
 * SCENE.md's scene need not each make and free their own; and the default
 * scene's textures, loaded from LUZ_TEXTURES (meson test sets it) by a
 * group setup.
 */
#ifndef LUZ_TESTS_LAB_SUPPORT_H
#define LUZ_TESTS_LAB_SUPPORT_H

#include <stdio.h>
#include <stdlib.h>

#include "io/textures.h"
#include "lab/scene.h"

static luz_lab *test_lab_instance;

static void test_lab_destroy(void)
{
    luz_lab_destroy(test_lab_instance);
    test_lab_instance = NULL;
}

static inline const luz_lab *test_lab(void)
{
    if (test_lab_instance == NULL) {
        luz_error error = {{0}};
        test_lab_instance = luz_lab_create(&error);
        if (test_lab_instance == NULL) {
            fprintf(stderr, "cannot make the lab: %s\n", error.message);
            abort();
        }
        atexit(test_lab_destroy);
    }
    return test_lab_instance;
}

/* The textures, for cmocka_run_group_tests(tests, lab_textures_load,
 * lab_textures_free). */
static inline luz_texture_set *lab_textures(void)
{
    static luz_texture_set set;
    return &set;
}

static inline int lab_textures_load(void **state)
{
    (void)state;
    const char *directory = getenv("LUZ_TEXTURES");
    if (directory == NULL || directory[0] == '\0') {
        fprintf(stderr, "LUZ_TEXTURES is not set (meson test sets it)\n");
        return -1;
    }
    luz_error error = {{0}};
    if (luz_texture_set_load(lab_textures(), directory, NULL, &error) != 0) {
        fprintf(stderr, "cannot load the textures: %s\n", error.message);
        return -1;
    }
    return 0;
}

static inline int lab_textures_free(void **state)
{
    (void)state;
    luz_texture_set_free(lab_textures());
    return 0;
}

#endif
