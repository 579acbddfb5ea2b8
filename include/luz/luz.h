/*
 * luz/luz.h: the whole public API of libluz in one include.
 *
 *   vecmath.h      vectors and matrices (OpenGL / gl-matrix conventions)
 *   scene.h        SCENE.md's cubes, camera and lights; frames to draw
 *   texture.h      textures, mip chains, sampling, a directory of them
 *   shade.h        the fragment shader: six light terms
 *   framebuffer.h  colour, depth and visibility buffers
 *   renderer.h     the threaded pipeline that draws a frame
 *   view.h         the teaching views' palettes and legends (--view)
 *   image.h        PNG output that never leaves a partial file
 *   options.h      the command-line and scene-file options both programs share
 *   controls.h     the viewer's keys and mouse as functions on scene data
 *   panel.h        the viewer's text, light panel, HUD and help, drawn into a framebuffer
 *   bench.h        the median behind every --bench line
 */
#ifndef LUZ_LUZ_H
#define LUZ_LUZ_H

#include "luz/error.h"
#include "luz/vecmath.h"
#include "luz/scene.h"
#include "luz/texture.h"
#include "luz/shade.h"
#include "luz/framebuffer.h"
#include "luz/renderer.h"
#include "luz/view.h"
#include "luz/image.h"
#include "luz/options.h"
#include "luz/controls.h"
#include "luz/panel.h"
#include "luz/bench.h"

#endif
