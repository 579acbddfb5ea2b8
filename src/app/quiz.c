/*
 * quiz.c: which bug a quiz draws, the list of bugs, and the verdict on an
 * answer (app/quiz.h says how a seed chooses).
 */
#include "app/quiz.h"

#include "lab/scene.h"

static const luz_bug quiz_bugs[] = {
    LUZ_BUG_DIFFUSE_REVERSED,   LUZ_BUG_DIRECTIONAL_UNCLAMPED, LUZ_BUG_SPOT_REACH_TWICE,
    LUZ_BUG_NORMAL_MATRIX_IS_MODEL, LUZ_BUG_SPECULAR_HALF_VECTOR, LUZ_BUG_UV_AFFINE,
    LUZ_BUG_LOD_OFF_BY_ONE,     LUZ_BUG_NO_DEPTH_TEST,         LUZ_BUG_NO_BACKFACE_CULLING,
};

#define QUIZ_BUG_COUNT ((int)(sizeof quiz_bugs / sizeof quiz_bugs[0]))

int luz_quiz_bugs(const luz_bug **bugs)
{
    *bugs = quiz_bugs;
    return QUIZ_BUG_COUNT;
}

luz_bug luz_quiz_bug(uint32_t seed)
{
    /* Four steps: after one, a small seed is still small (1 gives
     * 0x42021), and every seed below 2^9 would choose the first bug. */
    uint32_t x = seed != 0 ? seed : 0x9E3779B9u;
    for (int step = 0; step < 4; step++) x = luz_xorshift32(x);
    /* floor((x >> 8) / 2^24 * n), in integers: (x >> 8) * n < 2^28 */
    return quiz_bugs[((x >> 8) * (uint32_t)QUIZ_BUG_COUNT) >> 24];
}

static bool in_quiz(luz_bug bug)
{
    for (int i = 0; i < QUIZ_BUG_COUNT; i++)
        if (quiz_bugs[i] == bug) return true;
    return false;
}

void luz_quiz_print_bugs(FILE *out)
{
    fprintf(out, "--bug NAME draws with one classic mistake put in (docs/teaching.md):\n");
    for (int bug = 1; bug < LUZ_BUG_COUNT; bug++)
        fprintf(out, "  %-24s %s%s\n", luz_bug_name((luz_bug)bug),
                luz_bug_description((luz_bug)bug), in_quiz((luz_bug)bug) ? "" : " (not in quizzes)");
}

int luz_quiz_answer(FILE *out, uint32_t seed, luz_bug answer)
{
    const luz_bug bug = luz_quiz_bug(seed);
    if (answer == bug) {
        fprintf(out, "right: quiz %lu's bug is %s: %s\n", (unsigned long)seed,
                luz_bug_name(bug), luz_bug_description(bug));
        return 0;
    }
    fprintf(out, "wrong: quiz %lu's bug is %s, not %s: %s\n", (unsigned long)seed,
            luz_bug_name(bug), luz_bug_name(answer), luz_bug_description(bug));
    return 1;
}
