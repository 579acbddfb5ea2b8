/*
 * shade_steps.c: SCENE.md's six light terms step by step, for the pixel
 * probe and for the shading bugs of luz/bug.h.
 *
 * In:  the frame's shading uniforms, a bug (LUZ_BUG_NONE for the
 *      contract), the fragment's world position P and interpolated
 *      normal N.
 * Out: the six terms and their sum, and every number in between
 *      (luz_shade_steps: N.L, R, V.R, Lp, N.Lp, c, f_dir, dn, f_win,
 *      f_dist, the sun's direction).
 *
 * Not the fragment stage's shader: that is luz/shade.h's inline functions,
 * which this file follows operation for operation, so that without a bug
 * it gives their bits (tests/test_bugs.c checks it on random fragments).
 * A frame drawn with a shading bug is shaded by this function (fragment.c,
 * the reference path), so the probe's numbers are the image's.
 */
#include <stddef.h>

#include "luz/shade.h"

luz_vec3 luz_shade_terms_explained(const luz_shade_uniforms *uniforms, luz_bug bug,
                                   luz_vec3 position, luz_vec3 normal,
                                   luz_vec3 terms[LUZ_TERM_COUNT], luz_shade_steps *steps)
{
    luz_shade_steps local;
    luz_shade_steps *s = steps != NULL ? steps : &local;
    const luz_lights *lights = &uniforms->lights;
    const luz_vec3 eye = uniforms->eye;
    /* SCENE.md re-normalises N after interpolation. */
    const luz_vec3 n =
        bug == LUZ_BUG_NORMAL_NOT_NORMALISED ? normal : luz_vec3_normalize(normal);
    s->normal = n;
    s->normal_length = luz_vec3_length(n);

    terms[LUZ_TERM_AMBIENT] = luz_shade_ambient(&lights->ambient);

    /* diffuse = max(dot(N, L), 0) D.rgb D.a, L = normalize(E - P); the
     * report printed normalize(P - E). */
    const luz_vec3 to_light = luz_vec3_normalize(luz_vec3_sub(eye, position));
    s->to_light = bug == LUZ_BUG_DIFFUSE_REVERSED
                      ? luz_vec3_normalize(luz_vec3_sub(position, eye))
                      : to_light;
    s->n_dot_l = luz_vec3_dot(n, s->to_light);
    terms[LUZ_TERM_DIFFUSE] = luz_vec3_scale(
        lights->diffuse.colour, luz_shade_max(s->n_dot_l, 0.0f) * lights->diffuse.strength);

    /* specular = S.a pow(max(dot(V, R), 0), s) S.rgb, V = L (the
     * headlight), R = reflect(-L, N); Blinn's dot(N, H) with the bug. */
    s->to_viewer = to_light;
    s->reflected = luz_vec3_sub(luz_vec3_scale(n, 2.0f * luz_vec3_dot(n, to_light)), to_light);
    s->v_dot_r = bug == LUZ_BUG_SPECULAR_HALF_VECTOR
                     ? luz_vec3_dot(n, luz_vec3_normalize(luz_vec3_add(to_light, s->to_viewer)))
                     : luz_vec3_dot(s->to_viewer, s->reflected);
    const float highlight =
        luz_shade_power(luz_shade_max(s->v_dot_r, 0.0f), lights->shininess);
    terms[LUZ_TERM_SPECULAR] =
        luz_vec3_scale(lights->specular.colour, lights->specular.strength * highlight);

    /* point = max(dot(N, Lp), 0) Pt.rgb Pt.a */
    s->to_point = luz_vec3_normalize(luz_vec3_sub(lights->point_position, position));
    s->n_dot_lp = luz_vec3_dot(n, s->to_point);
    terms[LUZ_TERM_POINT] = luz_vec3_scale(
        lights->point.colour, luz_shade_max(s->n_dot_lp, 0.0f) * lights->point.strength);

    /* spot = Sp.rgb f_dir f_dist (luz_shade_spot) */
    const luz_vec3 ray = luz_vec3_normalize(luz_vec3_sub(position, eye));
    const float c = luz_vec3_dot(ray, luz_vec3_normalize(lights->spot_direction));
    const float cos_inner = uniforms->spot_cos_inner, cos_outer = uniforms->spot_cos_outer;
    s->spot_cos = c;
    s->spot_cos_inner = cos_inner;
    s->spot_cos_outer = cos_outer;
    if (c > cos_inner) {
        s->f_dir = 1.0f;
    } else if (c > cos_outer) {
        const float t = sqrtf((c - cos_outer) / (cos_inner - cos_outer));
        s->f_dir = t * t * (3.0f - 2.0f * t);
    } else {
        s->f_dir = 0.0f;
    }
    const float reach = lights->spot_reach;
    s->dn = luz_vec3_length(luz_vec3_sub(eye, position)) / reach;
    const float dn2 = s->dn * s->dn;
    /* The report's window divides dn by the reach once more. */
    const float windowed = bug == LUZ_BUG_SPOT_REACH_TWICE ? s->dn / reach : s->dn;
    const float windowed2 = windowed * windowed;
    const float window = luz_shade_max(1.0f - windowed2 * windowed2, 0.0f);
    s->f_win = window * window;
    s->f_dist = window * window * (lights->spot.strength * lights->spot.strength) / (dn2 + 1.0f);
    terms[LUZ_TERM_SPOT] = luz_vec3_scale(lights->spot.colour, s->f_dir * s->f_dist);

    /* directional = max(dot(N, normalize(-d)), 0) Dl.rgb Dl.a; the report
     * had no max. */
    s->to_sun = luz_vec3_normalize(luz_vec3_scale(lights->directional_direction, -1.0f));
    s->n_dot_sun = luz_vec3_dot(n, s->to_sun);
    const float sun = bug == LUZ_BUG_DIRECTIONAL_UNCLAMPED ? s->n_dot_sun
                                                           : luz_shade_max(s->n_dot_sun, 0.0f);
    terms[LUZ_TERM_DIRECTIONAL] =
        luz_vec3_scale(lights->directional.colour, sun * lights->directional.strength);

    luz_vec3 light = terms[LUZ_TERM_AMBIENT];
    for (int term = LUZ_TERM_DIFFUSE; term < LUZ_TERM_COUNT; term++)
        light = luz_vec3_add(light, terms[term]);
    return light;
}
