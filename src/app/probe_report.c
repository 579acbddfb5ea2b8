/*
 * probe_report.c: a probed pixel in the scene's words, and as
 * luz-render --probe prints it (probe_report.h; docs/cli.md, "The pixel
 * probe").
 *
 * Every number is printed as the shortest decimal that reads back to the
 * same float (option_text.h), so the text is the pipeline's value to the
 * bit: a reader, or a test, can redo the sums and products from the
 * printed numbers and get the printed results exactly.
 */
#include "app/probe_report.h"

#include <string.h>

#include "app/option_text.h"

luz_probe_source luz_probe_source_of(const luz_probe_names *names, int draw)
{
    luz_probe_source source = {0};
    source.object = luz_scene_object_of_draw(names->scene, draw, &source.mesh);
    if (source.object >= 0 && names->scene->objects != NULL) {
        const luz_lab_model *model = names->scene->objects[source.object].model;
        if (model != NULL) {
            const luz_lab_model_part *part = &model->parts[source.mesh];
            source.model = model->name;
            source.mesh_name = part->mesh_name;
            source.material_name = part->material_name;
        }
    }
    return source;
}

const char *luz_probe_texture_name(const luz_probe_names *names, int draw,
                                   const luz_texture *texture)
{
    if (texture == NULL) return "none";
    /* A file of the textures directory: every cube's, and a model's when
     * its scene line names one. */
    const luz_texture_set *set = names->textures;
    for (int i = 0; set != NULL && i < set->count; i++)
        if (set->textures[i] == texture) return set->names[i];
    /* Else the model's material's. */
    const luz_probe_source source = luz_probe_source_of(names, draw);
    if (source.model != NULL) {
        const luz_lab_model_part *part =
            &names->scene->objects[source.object].model->parts[source.mesh];
        if (part->texture == texture && part->texture_name != NULL) return part->texture_name;
    }
    return "unnamed";
}

/* ---- writing ----------------------------------------------------------------------- */

static void put_float(FILE *out, float value)
{
    char text[40];
    option_format_float(text, sizeof text, value);
    fputs(text, out);
}

static void line_float(FILE *out, const char *key, float value)
{
    fprintf(out, "%s=", key);
    put_float(out, value);
    fputc('\n', out);
}

/* key=v0,v1,...: the values comma-separated. */
static void line_floats(FILE *out, const char *key, const float *values, int count)
{
    fprintf(out, "%s=", key);
    for (int i = 0; i < count; i++) {
        if (i > 0) fputc(',', out);
        put_float(out, values[i]);
    }
    fputc('\n', out);
}

static void line_vec3(FILE *out, const char *key, luz_vec3 value)
{
    line_floats(out, key, (const float[]){value.x, value.y, value.z}, 3);
}

static void line_vec4(FILE *out, const char *key, luz_vec4 value)
{
    line_floats(out, key, (const float[]){value.x, value.y, value.z, value.w}, 4);
}

/* A name the user's files gave: any character that could break the line
 * or the terminal shows as '?'. */
static void line_name(FILE *out, const char *key, const char *name)
{
    fprintf(out, "%s=", key);
    for (const unsigned char *c = (const unsigned char *)name; *c != '\0'; c++)
        fputc(*c < 0x20 || *c == 0x7f ? '?' : *c, out);
    fputc('\n', out);
}

/* object=I (or point-light), and for a history line no more. */
static void put_object(FILE *out, const luz_probe_source *source)
{
    if (source->object == LUZ_DRAW_POINT_LIGHT)
        fputs("object=point-light", out);
    else if (source->object == LUZ_DRAW_NONE)
        fputs("object=unknown", out);
    else
        fprintf(out, "object=%d", source->object);
}

static void write_history(FILE *out, const luz_pixel_probe *probe, const luz_probe_names *names)
{
    fprintf(out, "tests=%d\n", probe->test_count);
    for (int k = 0; k < probe->tests_kept; k++) {
        const luz_probe_test *test = &probe->tests[k];
        const luz_probe_source source = luz_probe_source_of(names, test->draw);
        fprintf(out, "test=%d ", k + 1);
        if (probe->samples > 1) fprintf(out, "sample=%d ", test->sample);
        put_object(out, &source);
        fprintf(out, " mesh=%d triangle=%lu depth=", source.mesh, (unsigned long)test->triangle);
        put_float(out, test->depth);
        fputs(" stored=", out);
        put_float(out, test->stored);
        fprintf(out, " result=%s\n", test->passed ? "pass" : "fail");
    }
    if (probe->tests_kept < probe->test_count)
        fprintf(out, "tests_not_listed=%d\n", probe->test_count - probe->tests_kept);
}

/* A matrix, row by row: key_row0= ... key_row3=, four numbers each. */
static void line_matrix(FILE *out, const char *key, const luz_mat4 *m)
{
    char name[40];
    for (int row = 0; row < 4; row++) {
        snprintf(name, sizeof name, "%s_row%d", key, row);
        /* column-major: element (row, column) is m[column * 4 + row] */
        line_floats(out, name,
                    (const float[]){m->m[row], m->m[4 + row], m->m[8 + row], m->m[12 + row]}, 4);
    }
}

/* The six terms' intermediates, in SCENE.md's names (docs/cli.md). */
static void write_steps(FILE *out, const luz_shade_steps *steps)
{
    line_float(out, "N_length", steps->normal_length);
    line_vec3(out, "L", steps->to_light);
    line_float(out, "N_dot_L", steps->n_dot_l);
    line_vec3(out, "V", steps->to_viewer);
    line_vec3(out, "R", steps->reflected);
    line_float(out, "V_dot_R", steps->v_dot_r);
    line_vec3(out, "Lp", steps->to_point);
    line_float(out, "N_dot_Lp", steps->n_dot_lp);
    line_float(out, "c", steps->spot_cos);
    line_float(out, "ci", steps->spot_cos_inner);
    line_float(out, "co", steps->spot_cos_outer);
    line_float(out, "f_dir", steps->f_dir);
    line_float(out, "dn", steps->dn);
    line_float(out, "f_win", steps->f_win);
    line_float(out, "f_dist", steps->f_dist);
    line_vec3(out, "sun", steps->to_sun);
    line_float(out, "N_dot_sun", steps->n_dot_sun);
}

static void write_winner(FILE *out, const luz_pixel_probe *probe, const luz_probe_names *names)
{
    const luz_probe_source source = luz_probe_source_of(names, probe->draw);
    put_object(out, &source);
    fputc('\n', out);
    if (source.model != NULL) line_name(out, "model", source.model);
    fprintf(out, "mesh=%d\n", source.mesh);
    if (source.mesh_name != NULL) line_name(out, "mesh_name", source.mesh_name);
    if (source.material_name != NULL) line_name(out, "material", source.material_name);
    fprintf(out, "triangle=%lu\n", (unsigned long)probe->triangle);
    if (probe->primitive >= 0) {
        fprintf(out, "primitive=%d\nvertices=%lu,%lu,%lu\n", probe->primitive,
                (unsigned long)probe->vertices[0], (unsigned long)probe->vertices[1],
                (unsigned long)probe->vertices[2]);
        char key[32];
        for (int k = 0; k < 3; k++) {
            snprintf(key, sizeof key, "corner%d_clip", k);
            line_vec4(out, key, probe->corner_clip[k]);
        }
        if (probe->clipped_pieces > 0)
            fprintf(out, "clipped=yes\npiece=%d\npieces=%d\n", probe->piece,
                    probe->clipped_pieces);
        else
            fputs("clipped=no\n", out);
        for (int k = 0; k < 3; k++) {
            snprintf(key, sizeof key, "corner%d_window", k);
            line_vec3(out, key, probe->corner_window[k]);
        }
        for (int k = 0; k < 3; k++) {
            const luz_probe_edge *edge = &probe->edges[k];
            fprintf(out, "edge%d=%lld top=%s left=%s owns_its_samples=%s\n", k,
                    (long long)edge->value, edge->top ? "yes" : "no",
                    edge->left ? "yes" : "no", edge->owns_its_samples ? "yes" : "no");
        }
        line_vec3(out, "barycentric", probe->barycentric);
    } else {
        fputs("primitive=unknown\n", out);
    }
    line_matrix(out, "model", &probe->model_matrix);
    line_matrix(out, "view", &probe->view_matrix);
    line_matrix(out, "projection", &probe->projection_matrix);
    line_float(out, "w", probe->w);
    line_float(out, "depth", probe->depth);

    /* the varyings */
    line_vec3(out, "P", probe->position);
    line_vec3(out, "N", probe->normal);
    line_floats(out, "uv", (const float[]){probe->uv.x, probe->uv.y}, 2);
    line_floats(out, "uv_dx", (const float[]){probe->du_dx, probe->dv_dx}, 2);
    line_floats(out, "uv_dy", (const float[]){probe->du_dy, probe->dv_dy}, 2);

    if (probe->shading == LUZ_SHADING_UNLIT) {
        fputs("shading=unlit\n", out);
        line_vec3(out, "C", probe->object_colour);
        line_vec3(out, "colour", probe->colour);
        return;
    }

    /* the texture */
    line_name(out, "texture", luz_probe_texture_name(names, probe->draw, probe->texture));
    if (probe->texture != NULL) {
        fprintf(out, "filter=%s\n", luz_filter_name(probe->filter));
        line_float(out, "rho", probe->rho);
        line_float(out, "lod", probe->lambda);
        fprintf(out, "levels=%d,%d\n", probe->levels.lower, probe->levels.upper);
        line_float(out, "weight", probe->levels.blend);
        for (int k = 0; k < probe->tap_count; k++) {
            const luz_probe_tap *tap = &probe->taps[k];
            fprintf(out, "tap=%d level=%d texel=%d,%d colour=", k, tap->level, tap->x, tap->y);
            put_float(out, tap->texel.x);
            fputc(',', out);
            put_float(out, tap->texel.y);
            fputc(',', out);
            put_float(out, tap->texel.z);
            fputs(" weight=", out);
            put_float(out, tap->weight);
            fputc('\n', out);
        }
    }
    line_vec3(out, "texel", probe->texel);

    /* the numbers in between (luz_shade_steps), then the lighting */
    write_steps(out, &probe->steps);
    for (int term = 0; term < LUZ_TERM_COUNT; term++)
        line_vec3(out, luz_term_name((luz_term)term), probe->terms[term]);
    line_vec3(out, "light", probe->light);
    line_vec3(out, "C", probe->object_colour);
    line_vec3(out, "colour", probe->colour);

    /* the output (SCENE.md, "Output"): colour x 2^EV, then the tone map,
     * whose result round(clamp(mapped) x 255) is the bytes */
    line_float(out, "exposure", probe->exposure);
    fprintf(out, "tonemap=%s\n", luz_tone_map_name(probe->tone_map));
    line_vec3(out, "exposed", probe->exposed);
    line_vec3(out, "mapped", probe->mapped);
}

/* What a view other than color shows at the pixel. */
static void write_view(FILE *out, const luz_pixel_probe *probe)
{
    switch (probe->view) {
    case LUZ_VIEW_COLOR:
        return;
    case LUZ_VIEW_DEPTH:
        line_float(out, "depth_buffer", probe->depth_buffer);
        break;
    case LUZ_VIEW_OVERDRAW:
        fprintf(out, "overdraw=%lu\n", (unsigned long)probe->overdraw);
        break;
    case LUZ_VIEW_BANDS:
        fprintf(out, "band=%d\nthread=%d\n", probe->band, probe->worker);
        break;
    case LUZ_VIEW_TRIANGLES:
        if (probe->triangle != 0) {
            line_float(out, "edge_distance", probe->edge_distance);
            fprintf(out, "on_edge=%s\n", probe->on_edge ? "yes" : "no");
        }
        break;
    default:
        break;
    }
    line_vec3(out, "shown", probe->shown);
}

/* With four samples: each sample, its winner and colour, and the resolve
 * of each channel written out (SCENE.md: floor((s0 + s1 + s2 + s3 + 2) / 4)). */
static void write_samples(FILE *out, const luz_pixel_probe *probe)
{
    fprintf(out, "samples=%d\n", probe->samples);
    for (int k = 0; k < probe->samples; k++) {
        const luz_probe_sample *sample = &probe->sample[k];
        fprintf(out, "sample=%d position=", k);
        put_float(out, sample->x);
        fputc(',', out);
        put_float(out, sample->y);
        fprintf(out, " tests=%d triangle=%lu depth=", sample->test_count,
                (unsigned long)sample->triangle);
        put_float(out, sample->depth_buffer);
        fprintf(out, " bytes=%u,%u,%u\n", sample->bytes[0], sample->bytes[1], sample->bytes[2]);
    }
    static const char *const channels[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; c++) {
        unsigned sum = 0;
        fprintf(out, "resolve_%s=floor((", channels[c]);
        for (int k = 0; k < probe->samples; k++) {
            fprintf(out, "%s%u", k ? "+" : "", probe->sample[k].bytes[c]);
            sum += probe->sample[k].bytes[c];
        }
        fprintf(out, "+2)/4)=%u\n", (sum + 2) / 4);
    }
}

void luz_probe_write(FILE *out, const luz_pixel_probe *probe, const luz_probe_names *names,
                     int width, int height, double time_seconds)
{
    char time[40];
    option_format_double(time, sizeof time, time_seconds);
    fprintf(out, "pixel=%d,%d\nsize=%d,%d\ntime=%s\nview=%s\n", probe->x, probe->y, width,
            height, time, luz_view_name(probe->view));
    /* The bug, if one is on; a quiz's is not told (app/quiz.h). */
    if (names->scene != NULL && names->scene->bug_hidden)
        fputs("bug=hidden (quiz)\n", out);
    else if (probe->bug != LUZ_BUG_NONE)
        fprintf(out, "bug=%s\n", luz_bug_name(probe->bug));
    if (!probe->filled) return;
    write_history(out, probe, names);
    if (probe->triangle == 0)
        fputs("object=none\n", out);
    else
        write_winner(out, probe, names);
    write_view(out, probe);
    if (probe->samples > 1) write_samples(out, probe);
    fprintf(out, "bytes=%u,%u,%u\n", probe->bytes[0], probe->bytes[1], probe->bytes[2]);
}
