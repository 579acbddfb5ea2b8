/*
 * app/probe_report.h: a probed pixel (luz/probe.h) in the scene's words.
 *
 * The renderer's probe speaks of draws and textures; the user thinks of
 * cube 3, mesh 2 of spider.obj, bricks.png. This file names them, from the
 * scene the frame was built from and the textures the options loaded, and
 * writes the probe as luz-render --probe prints it: one key=value a line
 * (docs/cli.md, "The pixel probe"). The viewer's probe panel
 * (probe_panel.h) names things the same way.
 */
#ifndef LUZ_PROBE_REPORT_H
#define LUZ_PROBE_REPORT_H

#include <stdio.h>

#include "luz/probe.h"
#include "io/textures.h"
#include "lab/scene.h"

/* What the names come from. */
typedef struct luz_probe_names {
    const luz_scene *scene;            /* the scene the frame was built from */
    const luz_texture_set *textures;   /* the cube textures (may be NULL) */
} luz_probe_names;

/* Where a draw of the scene's frame comes from. */
typedef struct luz_probe_source {
    int object;                 /* the object's index (cube i, or the scene's
                                   objects[i]); LUZ_DRAW_POINT_LIGHT for the
                                   point light's marker; LUZ_DRAW_NONE */
    int mesh;                   /* the model's mesh, 0 for a cube */
    const char *model;          /* the model file's name; NULL for a cube */
    const char *mesh_name;      /* what the file calls the mesh, or NULL */
    const char *material_name;  /* ... and its material, or NULL */
} luz_probe_source;

luz_probe_source luz_probe_source_of(const luz_probe_names *names, int draw);

/* The name of the texture a draw samples: a file of the textures
 * directory, or the name the model's material gives it; "none" for NULL. */
const char *luz_probe_texture_name(const luz_probe_names *names, int draw,
                                   const luz_texture *texture);

/* Writes the probe of a width x height frame at time_seconds as
 * luz-render --probe prints it: pixel, size, time, view, the history, the
 * winner, its varyings, texture and lighting, what a view shows, bytes. */
void luz_probe_write(FILE *out, const luz_pixel_probe *probe, const luz_probe_names *names,
                     int width, int height, double time_seconds);

#endif
