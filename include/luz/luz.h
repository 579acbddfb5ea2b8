/*
 * luz/luz.h: the whole public API of libluz, the renderer, in one include.
 *
 *   error.h        how a failure says why
 *   vecmath.h      vectors and matrices (OpenGL / gl-matrix conventions)
 *   texture.h      textures from pixels in memory, mip chains, sampling
 *   view.h         the teaching views' palettes and legends
 *   frame.h        what a frame draws: meshes, lights, draws
 *   shade.h        the fragment shader: six light terms
 *   framebuffer.h  colour, depth and visibility buffers
 *   renderer.h     the threaded pipeline that draws a frame
 *   probe.h        one pixel of a frame explained, test by test and term by term
 *   bug.h          classic mistakes to put in on purpose, for teaching
 */
#ifndef LUZ_LUZ_H
#define LUZ_LUZ_H

#include "luz/error.h"
#include "luz/vecmath.h"
#include "luz/texture.h"
#include "luz/view.h"
#include "luz/frame.h"
#include "luz/shade.h"
#include "luz/framebuffer.h"
#include "luz/renderer.h"
#include "luz/probe.h"
#include "luz/bug.h"

#endif
