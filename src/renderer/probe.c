/*
 * probe.c: the pixel probe, one pixel of a frame explained (luz/probe.h).
 *
 * In:  a frame the bands have just drawn: its set-up triangles by id, the
 *      final depth and visibility buffers, the draws, the uniforms; and
 *      the pixel (x, y).
 * Out: the luz_pixel_probe: the pixel's depth tests in draw order, the
 *      winner and where it comes from, its varyings, texel and light
 *      terms, and the bytes the image holds.
 *
 * Not a second renderer: each number comes from the function that made
 * it for the image, called again on the same inputs, which gives the same
 * bits.
 *
 *   history      Every triangle the raster stage drew, in id order (the
 *                order in which each band draws its triangles), through
 *                the raster's own coverage and depth arithmetic at the
 *                pixel (luz_raster_row_span, luz_raster_depth), against
 *                a one-pixel depth buffer that starts at 1.0, as each
 *                band's is cleared. Same tests, same order, same outcomes:
 *                the last that passed is the triangle the visibility
 *                buffer kept.
 *   primitive    The winner records its mesh triangle (geometry.c). Its
 *                three vertices go through the vertex stage, the clipper
 *                and setup again (as geometry.c's triangles_of_draw sends
 *                them) to find the piece of a clipped fan that won, checked
 *                against the pipeline's own triangle, field by field.
 *   corners      The vertex stage's clip-space positions of the three
 *                vertices; the winner's window corners, read back from
 *                setup's snapped reference point and edges, and its depth
 *                plane there.
 *   barycentric  The same clipping and setup with the three vertices'
 *                position varyings replaced by (1, 0, 0), (0, 1, 0) and
 *                (0, 0, 1): the clipper carries them to the vertices it
 *                cuts, setup solves their planes, and
 *                luz_fragment_interpolate divides them by 1/w exactly as
 *                it does every varying (OpenGL 4.6 equation 14.9).
 *   varyings     luz_fragment_interpolate on the winner's triangle.
 *   texture      luz_texture_footprint_squared; the level of detail of the
 *                fragment path that shaded the pixel (fragment_packet.c's
 *                polynomial logarithm, or fragment.c's log2f: the one
 *                place where the two differ); luz_texture_mip_levels and
 *                luz_texture_sample.
 *   lighting     luz_shade_terms, then luz_shade_colour: light x C x T.
 *   bytes        Read from the colour buffer as each band finishes,
 *                before the caller's hook can draw over the pixel.
 */
#include <math.h>
#include <string.h>

#include "renderer/pipeline.h"
#include "luz/probe.h"
#include "luz/shade.h"
#include "luz/texture.h"
#include "luz/view.h"

void luz_probe_begin(luz_pixel_probe *probe, const luz_framebuffer *framebuffer, luz_view view)
{
    const int x = probe->x, y = probe->y;
    memset(probe, 0, sizeof *probe);
    probe->x = x;
    probe->y = y;
    probe->view = view;
    probe->filled = x >= 0 && y >= 0 && x < framebuffer->width && y < framebuffer->height;
}

void luz_probe_capture(luz_pixel_probe *probe, const luz_framebuffer *framebuffer,
                       int first_row, int end_row, int band_index, int worker_index)
{
    if (!probe->filled || probe->y < first_row || probe->y >= end_row) return;
    const luz_pixel_layout layout = luz_pixel_layout_of(framebuffer->channel_order);
    const uint8_t *pixel =
        framebuffer->colour + ((size_t)probe->y * framebuffer->width + probe->x) * 4;
    probe->bytes[0] = pixel[layout.red];
    probe->bytes[1] = pixel[1];
    probe->bytes[2] = pixel[layout.blue];
    probe->band = band_index;
    probe->worker = worker_index;
}

/* ---- the history ---------------------------------------------------------- */

/* Does the triangle cover the pixel centre, and at what depth? With
 * samples > 1, sample `sample` of the pixel instead (raster.c's
 * luz_raster_triangle_samples). */
static bool covers(const luz_triangle *triangle, int x, int y, int samples, int sample,
                   float *depth)
{
    if (y < triangle->min_y || y > triangle->max_y || x < triangle->min_x ||
        x > triangle->max_x)
        return false;
    int64_t first, last;
    if (samples == 1) {
        luz_raster_row_span(triangle, y, luz_raster_is_small(triangle), &first, &last);
        if (x < first || x > last) return false;
        const float row_depth = luz_raster_row_depth(triangle->depth, triangle->reference_y, y);
        *depth = luz_raster_depth(triangle->depth, triangle->reference_x, row_depth, x);
        return true;
    }
    const luz_sample_offset offset = luz_sample_offset_of(samples, sample);
    luz_raster_row_span_at(triangle, y, luz_raster_is_small(triangle), offset, &first, &last);
    if (x < first || x > last) return false;
    const float row_depth = luz_raster_sample_row_depth(
        triangle->depth, triangle->reference_y, y, (float)offset.y / LUZ_SUBPIXEL_ONE);
    *depth = luz_raster_sample_depth(triangle->depth, triangle->reference_x, row_depth, x,
                                     (float)offset.x / LUZ_SUBPIXEL_ONE);
    return true;
}

/* Every depth test of the pixel (of each sample in turn), in the order
 * the raster stage made them; with samples > 1, each sample's winner and
 * depth too. */
static void record_history(luz_pixel_probe *probe, const luz_triangle *const *by_id,
                           size_t triangle_count, int samples, luz_bug bug)
{
    for (int sample = 0; sample < samples; sample++) {
        float stored = 1.0f;   /* the cleared depth buffer */
        uint32_t winner = 0;
        int tests = 0;
        for (size_t id = 1; id <= triangle_count; id++) {
            float depth;
            if (!covers(by_id[id], probe->x, probe->y, samples, sample, &depth)) continue;
            /* GL_LESS, as raster.c; every test passes with the bug
             * no-depth-test, which writes no depth (luz/bug.h) */
            const bool no_depth_test = bug == LUZ_BUG_NO_DEPTH_TEST;
            const bool passed = no_depth_test || depth < stored;
            if (probe->tests_kept < LUZ_PROBE_MAX_TESTS)
                probe->tests[probe->tests_kept++] = (luz_probe_test){
                    .sample = sample,
                    .triangle = (uint32_t)id,
                    .draw = (int)by_id[id]->draw_index,
                    .depth = depth,
                    .stored = stored,
                    .passed = passed,
                };
            probe->test_count++;
            tests++;
            if (passed) {
                if (!no_depth_test) stored = depth;
                winner = (uint32_t)id;
            }
        }
        if (samples > 1) {
            const luz_sample_offset offset = luz_sample_offset_of(samples, sample);
            probe->sample[sample] = (luz_probe_sample){
                .x = (float)probe->x + (float)offset.x / LUZ_SUBPIXEL_ONE,
                .y = (float)probe->y + (float)offset.y / LUZ_SUBPIXEL_ONE,
                .test_count = tests,
                .triangle = winner,
                .depth_buffer = stored,
            };
        }
    }
}

/* ---- where the winner comes from -------------------------------------- */

/* Equal, or both NaN: a mesh's NaN normals make NaN planes, and a NaN
 * compares unequal even to itself (nor need its sign and payload be
 * setup's: setup in lanes may give the other sign, setup_eight.c). */
static bool same_float(float a, float b)
{
    return a == b || (isnan(a) && isnan(b));
}

static bool same_plane(luz_plane a, luz_plane b)
{
    return same_float(a.value, b.value) && same_float(a.dx, b.dx) && same_float(a.dy, b.dy);
}

/* Field by field: a struct's padding may hold anything. */
static bool same_triangle(const luz_triangle *a, const luz_triangle *b)
{
    if (a->min_x != b->min_x || a->min_y != b->min_y || a->max_x != b->max_x ||
        a->max_y != b->max_y || a->reference_x != b->reference_x ||
        a->reference_y != b->reference_y || a->draw_index != b->draw_index ||
        !same_plane(a->depth, b->depth) || !same_plane(a->inverse_w, b->inverse_w))
        return false;
    for (int k = 0; k < 3; k++)
        if (a->edges[k].a != b->edges[k].a || a->edges[k].b != b->edges[k].b ||
            a->edges[k].c != b->edges[k].c)
            return false;
    for (int i = 0; i < LUZ_VARYING_COUNT; i++)
        if (!same_plane(a->varyings[i], b->varyings[i])) return false;
    return true;
}

/* The frame's setup, as geometry.c calls it. */
static luz_setup_result set_up(const luz_clip_vertex *a, const luz_clip_vertex *b,
                               const luz_clip_vertex *c, const luz_framebuffer *framebuffer,
                               const luz_uniforms *uniforms, uint32_t draw_index,
                               luz_triangle *out)
{
    if (uniforms->bug != LUZ_BUG_NONE)
        return luz_setup_triangle_bug(a, b, c, framebuffer->width, framebuffer->height,
                                      draw_index, uniforms->interpolation, uniforms->samples,
                                      uniforms->bug, out);
    return luz_setup_triangle_samples(a, b, c, framebuffer->width, framebuffer->height,
                                      draw_index, uniforms->interpolation, uniforms->samples,
                                      out);
}

/* The three vertices with their position varyings replaced by the
 * barycentric coordinates of the corners. */
static void barycentric_corners(const luz_clip_vertex *const corners[3], luz_clip_vertex out[3])
{
    for (int k = 0; k < 3; k++) {
        out[k] = *corners[k];
        for (int j = 0; j < 3; j++)
            out[k].varyings[LUZ_VARYING_POSITION + j] = j == k ? 1.0f : 0.0f;
    }
}

/* The corners of a set-up triangle, read back from setup's own output:
 * vertex 0 is the reference point, which setup snapped to 1/256 of a pixel
 * and a float holds exactly, and edge k runs from vertex k + 1 to vertex
 * k + 2 with a = dy and b = -dx in those units (setup.c, step 4), so
 * vertex 1 = vertex 0 + (-b, a) of edge 2 and vertex 2 = vertex 0 + (b, -a)
 * of edge 1. The depth there is the triangle's depth plane's. */
static void window_corners(const luz_triangle *triangle, luz_vec3 out[3])
{
    const double one = LUZ_SUBPIXEL_ONE;
    const int64_t x0 = llrint((double)triangle->reference_x * one);
    const int64_t y0 = llrint((double)triangle->reference_y * one);
    const int64_t x[3] = {x0, x0 - triangle->edges[2].b, x0 + triangle->edges[1].b};
    const int64_t y[3] = {y0, y0 + triangle->edges[2].a, y0 - triangle->edges[1].a};
    const luz_plane depth = triangle->depth;
    for (int k = 0; k < 3; k++) {
        const float window_x = (float)((double)x[k] / one), window_y = (float)((double)y[k] / one);
        out[k] = (luz_vec3){window_x, window_y,
                            depth.value + depth.dx * (window_x - triangle->reference_x) +
                                depth.dy * (window_y - triangle->reference_y)};
    }
}

/* Explains the winner's mesh triangle (geometry.c records its index):
 * its three vertices through the vertex stage (whose clip-space positions
 * the probe keeps), the clipper and setup again, to find which triangle of
 * a clipped fan won and to carry the barycentric coordinates through the
 * same clip, setup and interpolation as varyings. Leaves primitive at -1
 * if (never expected) setup does not give the pipeline's triangle again. */
static void find_primitive(luz_pixel_probe *probe, const luz_uniforms *uniforms,
                           const luz_draw *draw, const luz_triangle *winner,
                           const luz_framebuffer *framebuffer)
{
    probe->primitive = -1;
    const luz_mesh *mesh = draw->mesh;
    const uint32_t i = 3 * winner->primitive;
    /* The three corners through the vertex stage. */
    const luz_draw_transform transform = luz_draw_transform_of(draw, uniforms->view_projection);
    luz_clip_vertex shaded[3];
    for (int k = 0; k < 3; k++)
        shaded[k] = luz_vertex_stage_one_bug(&transform, uniforms->bug, mesh->indices[i + k]);
    const luz_clip_vertex *corners[3] = {&shaded[0], &shaded[1], &shaded[2]};

    luz_clip_polygon polygon;
    int pieces = 1;
    const bool clipped = (corners[0]->outcode | corners[1]->outcode | corners[2]->outcode) != 0;
    if (clipped) pieces = luz_clip_triangle(corners[0], corners[1], corners[2], &polygon) - 2;
    luz_triangle triangle;
    for (int piece = 0; piece < pieces; piece++) {
        const luz_clip_vertex *a = clipped ? &polygon.vertices[0] : corners[0];
        const luz_clip_vertex *b = clipped ? &polygon.vertices[piece + 1] : corners[1];
        const luz_clip_vertex *c = clipped ? &polygon.vertices[piece + 2] : corners[2];
        if (set_up(a, b, c, framebuffer, uniforms, winner->draw_index, &triangle) !=
                LUZ_SETUP_VISIBLE ||
            !same_triangle(&triangle, winner))
            continue;

        /* Found. The barycentric coordinates ride along as varyings. */
        probe->primitive = (int)winner->primitive;
        for (int k = 0; k < 3; k++) {
            probe->vertices[k] = mesh->indices[i + (uint32_t)k];
            probe->corner_clip[k] = corners[k]->position;
        }
        window_corners(winner, probe->corner_window);
        probe->clipped_pieces = clipped ? pieces : 0;
        probe->piece = piece;
        luz_clip_vertex weighted[3];
        barycentric_corners(corners, weighted);
        if (clipped) {
            luz_clip_polygon weighted_polygon;
            luz_clip_triangle(&weighted[0], &weighted[1], &weighted[2], &weighted_polygon);
            weighted[0] = weighted_polygon.vertices[0];
            weighted[1] = weighted_polygon.vertices[piece + 1];
            weighted[2] = weighted_polygon.vertices[piece + 2];
        }
        luz_triangle barycentric;
        set_up(&weighted[0], &weighted[1], &weighted[2], framebuffer, uniforms,
               winner->draw_index, &barycentric);
        luz_fragment fragment;
        luz_fragment_interpolate(&barycentric, probe->x, probe->y, &fragment);
        probe->barycentric = fragment.position;
        break;
    }
}

/* The winner's edge functions at the pixel centre, as setup.c made them:
 * a = dy and b = -dx of the edge, and c with the fill rule's 1 taken off
 * the edges that do not own their samples (setup.c's make_edge). */
static void explain_edges(luz_pixel_probe *probe, const luz_triangle *winner, luz_bug bug)
{
    const int64_t X = (int64_t)probe->x * LUZ_SUBPIXEL_ONE + LUZ_SUBPIXEL_ONE / 2;
    const int64_t Y = (int64_t)probe->y * LUZ_SUBPIXEL_ONE + LUZ_SUBPIXEL_ONE / 2;
    for (int k = 0; k < 3; k++) {
        const luz_edge *edge = &winner->edges[k];
        luz_probe_edge *out = &probe->edges[k];
        const int64_t dy = edge->a, dx = -(int64_t)edge->b;
        out->top = dy == 0 && dx < 0;
        out->left = dy > 0;
        out->owns_its_samples = (out->top || out->left) != (bug == LUZ_BUG_FILL_RULE_BOTTOM_RIGHT);
        out->value = (int64_t)edge->a * X + (int64_t)edge->b * Y + edge->c +
                     (out->owns_its_samples ? 0 : 1);
    }
}

/* ---- the winner's shading ----------------------------------------------- */

static void shade(luz_pixel_probe *probe, const luz_uniforms *uniforms,
                  const luz_material *material, const luz_fragment *fragment, bool packet_path)
{
    probe->shading = material->shading;
    probe->object_colour = luz_material_colour(material);
    probe->exposure = uniforms->output_exposure;
    probe->exposure_scale = uniforms->exposure_scale;
    probe->tone_map = uniforms->tone_map;
    if (material->shading == LUZ_SHADING_UNLIT) {
        /* The marker is written as it is (SCENE.md, "Output"). */
        probe->colour = probe->exposed = probe->mapped = probe->object_colour;
        return;
    }

    const luz_texture *texture = material->texture;
    probe->texture = texture;
    probe->filter = material->filter;
    if (texture != NULL) {
        const float rho_squared = luz_texture_footprint_squared(
            texture, fragment->du_dx, fragment->dv_dx, fragment->du_dy, fragment->dv_dy);
        probe->rho = sqrtf(rho_squared);
        /* Nearest and bilinear read level 0 and never ask for lambda. */
        if (material->filter == LUZ_FILTER_TRILINEAR) {
            probe->lambda = packet_path
                                ? luz_packet_level_of_detail(texture, fragment->du_dx,
                                                             fragment->dv_dx, fragment->du_dy,
                                                             fragment->dv_dy)
                                : luz_texture_level_of_detail(texture, fragment->du_dx,
                                                              fragment->dv_dx, fragment->du_dy,
                                                              fragment->dv_dy);
            if (uniforms->bug == LUZ_BUG_LOD_OFF_BY_ONE) probe->lambda += 1.0f;   /* as fragment.c */
            probe->levels = luz_texture_mip_levels(texture, probe->lambda);
        }
    }
    probe->texel = luz_texture_sample(texture, material->filter, fragment->uv, probe->lambda);
    probe->tap_count =
        luz_texture_taps(texture, material->filter, fragment->uv, probe->lambda, probe->taps);
    /* The terms the image was shaded with (luz_shade_terms, or the
     * bug's), and the numbers in between. */
    luz_vec3 terms[LUZ_TERM_COUNT];
    const luz_vec3 explained = luz_shade_terms_explained(
        &uniforms->shade, uniforms->bug, fragment->position, fragment->normal, terms,
        &probe->steps);
    if (uniforms->bug == LUZ_BUG_NONE) {
        probe->light = luz_shade_terms(&uniforms->shade, fragment->position, fragment->normal,
                                       probe->terms);
    } else {
        probe->light = explained;
        memcpy(probe->terms, terms, sizeof terms);
    }
    probe->colour = luz_shade_colour(probe->light, probe->object_colour, probe->texel);
    /* The fragment stages skip the output at clamp and EV 0, where it
     * leaves the colour as it is; so does the probe, to give their bits. */
    if (uniforms->output_is_identity) {
        probe->exposed = probe->mapped = probe->colour;
    } else {
        probe->exposed = luz_shade_output(probe->colour, uniforms->exposure_scale,
                                          LUZ_TONE_MAP_CLAMP);
        probe->mapped = luz_shade_output(probe->colour, uniforms->exposure_scale,
                                         uniforms->tone_map);
    }
}

/* With four samples: the colour each sample took, by the functions that
 * gave it in the image: the fragment stage's list (shading is once per
 * pixel and triangle, at the centre, so the sample's winner shaded there
 * again is its bytes), or, for the teaching views, the view of the
 * sample's plane. */
static void sample_bytes(luz_pixel_probe *probe, const luz_uniforms *uniforms,
                         const luz_draw *draws, const luz_triangle *const *by_id,
                         const luz_sample_buffers *samples, luz_packet_list_function *list)
{
    const luz_pixel_layout layout = luz_pixel_layout_of(samples->plane[0].channel_order);
    const size_t index = (size_t)probe->y * samples->plane[0].width + (size_t)probe->x;
    for (int k = 0; k < samples->samples; k++) {
        luz_probe_sample *sample = &probe->sample[k];
        uint8_t pixel[4];
        if (uniforms->show != LUZ_VIEW_COLOR && uniforms->show != LUZ_VIEW_BANDS) {
            memcpy(pixel, samples->plane[k].colour + index * 4, sizeof pixel);
        } else if (sample->triangle == 0) {
            luz_pixel_write(pixel, layout, uniforms->clear_colour);
        } else {
            const luz_fragment_ref fragment = {sample->triangle, (uint16_t)probe->x,
                                               (uint16_t)probe->y};
            uint32_t colour;
            (list != NULL && uniforms->show == LUZ_VIEW_COLOR ? list : luz_fragment_shade_list)(
                uniforms, draws, by_id, samples->plane[0].channel_order, &fragment, 1, &colour);
            memcpy(pixel, &colour, sizeof pixel);
        }
        sample->bytes[0] = pixel[layout.red];
        sample->bytes[1] = pixel[1];
        sample->bytes[2] = pixel[layout.blue];
    }
}

void luz_probe_explain(luz_pixel_probe *probe, const luz_uniforms *uniforms,
                       const luz_draw *draws, const luz_triangle *const *by_id,
                       size_t triangle_count, const luz_framebuffer *framebuffer,
                       const luz_sample_buffers *samples, const uint32_t *overdraw,
                       luz_packet_list_function *packet_list)
{
    probe->bug = uniforms->bug;
    if (!probe->filled) return;
    const bool packet_path = packet_list != NULL;
    const int x = probe->x, y = probe->y;
    const size_t index = (size_t)y * framebuffer->width + x;
    const int sample_count = samples ? samples->samples : 1;
    probe->samples = sample_count;

    record_history(probe, by_id, triangle_count, sample_count, uniforms->bug);
    uint32_t id;
    if (samples) {
        /* The first winner (resolve.c): that of the first sample a
         * triangle won, the one the fragment stage shades as the pixel's
         * own; its depth there. */
        id = 0;
        probe->depth_buffer = 1.0f;
        for (int k = 0; k < sample_count && id == 0; k++) {
            id = probe->sample[k].triangle;
            if (id != 0) probe->depth_buffer = probe->sample[k].depth_buffer;
        }
        sample_bytes(probe, uniforms, draws, by_id, samples, packet_list);
        const size_t pixels = (size_t)framebuffer->width * (size_t)framebuffer->height;
        if (overdraw != NULL)
            for (int k = 0; k < sample_count; k++) probe->overdraw += overdraw[k * pixels + index];
    } else {
        probe->depth_buffer = framebuffer->depth[index];
        if (overdraw != NULL) probe->overdraw = overdraw[index];
        /* The winner is whom the visibility buffer names, as the fragment
         * stage reads it. */
        id = framebuffer->visibility[index];
    }
    probe->triangle = id;
    if (id != 0) {
        const luz_triangle *winner = by_id[id];
        probe->draw = (int)winner->draw_index;
        probe->depth = probe->depth_buffer;
        if (uniforms->bug == LUZ_BUG_NO_DEPTH_TEST)   /* no depth written: the winner's */
            for (int k = 0; k < probe->tests_kept; k++)
                if (probe->tests[k].triangle == id) probe->depth = probe->tests[k].depth;
        probe->edge_distance = (float)luz_view_edge_distance(winner, x, y);
        probe->on_edge =
            luz_view_on_edge(winner, x, y, framebuffer->width, framebuffer->height);

        find_primitive(probe, uniforms, &draws[winner->draw_index], winner, framebuffer);
        probe->model_matrix = draws[winner->draw_index].model;
        probe->view_matrix = uniforms->view;
        probe->projection_matrix = uniforms->projection;
        explain_edges(probe, winner, uniforms->bug);

        luz_fragment fragment;
        luz_fragment_interpolate(winner, x, y, &fragment);
        probe->w = fragment.w;
        probe->position = fragment.position;
        probe->normal = luz_vec3_normalize(fragment.normal);
        probe->uv = fragment.uv;
        probe->du_dx = fragment.du_dx;
        probe->dv_dx = fragment.dv_dx;
        probe->du_dy = fragment.du_dy;
        probe->dv_dy = fragment.dv_dy;
        /* The colour view of a teaching view is fragment.c's. */
        shade(probe, uniforms, &draws[winner->draw_index].material, &fragment,
              packet_path && uniforms->show == LUZ_VIEW_COLOR);
    }

    /* What a teaching view shows, by view.c's own functions. */
    if (uniforms->show == LUZ_VIEW_BANDS && samples) {
        /* The tint goes over the resolved colour. */
        uint8_t rgb[3];
        for (int c = 0; c < 3; c++)
            rgb[c] = luz_samples_resolve_channel(probe->sample[0].bytes[c],
                                                 probe->sample[1].bytes[c],
                                                 probe->sample[2].bytes[c],
                                                 probe->sample[3].bytes[c]);
        probe->shown = luz_view_bands_colour(rgb, probe->worker);
    } else if (uniforms->show == LUZ_VIEW_BANDS) {
        const luz_vec3 colour = id != 0 ? probe->mapped : uniforms->clear_colour;
        const uint8_t rgb[3] = {luz_colour_to_byte(colour.x), luz_colour_to_byte(colour.y),
                                luz_colour_to_byte(colour.z)};
        probe->shown = luz_view_bands_colour(rgb, probe->worker);
    } else if (uniforms->show != LUZ_VIEW_COLOR && samples) {
        /* Sample 0's view, one of the four the pixel resolves. */
        probe->shown = luz_view_pixel(uniforms, draws, by_id, &samples->plane[0], x, y,
                                      overdraw);
    } else if (uniforms->show != LUZ_VIEW_COLOR) {
        probe->shown = luz_view_pixel(uniforms, draws, by_id, framebuffer, x, y, overdraw);
    }
}
