/*
 * lab_support.h: one luz_lab (the lab's cube mesh) for a whole test
 * program, made on first use and freed at exit, so that tests which draw
 * SCENE.md's scene need not each make and free their own.
 */
#ifndef LUZ_TESTS_LAB_SUPPORT_H
#define LUZ_TESTS_LAB_SUPPORT_H

#include <stdio.h>
#include <stdlib.h>

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

#endif
