#!/bin/sh
# make-frames.sh BUILD_DIR: writes the student frames that test_diagnose
# weighs, into this directory, with tools/glref (SCENE.md through OpenGL on
# Mesa's llvmpipe: an implementation of the contract that shares no shading
# or transform code with luz). They are committed, so that the test runs
# where glref cannot (sanitizer builds, machines without EGL); this script
# is how they were made (Mesa 22.3 llvmpipe, the committed textures):
#
#   sh tests/diagnose/make-frames.sh build
#
# Each frame is a setting with one thing changed, whose weight SCENE.md
# predicts: a light's strength times k scales its term by k (the spot's
# by k^2: its strength enters squared), a strength of 0 removes it.
set -eu
build=${1:?usage: make-frames.sh BUILD_DIR}
glref=$build/tools/glref
here=$(dirname "$0")
size=192x108
frame() { name=$1; shift; "$glref" --size $size "$@" -o "$here/$name.png"; }

frame right                                   # the default setting
frame right-4x --samples 4                    # anti-aliased, diagnosed with --samples 4
frame right-t3 --time 3 --seed 7 --camera-pos 0.4,0.3,3.5 --camera-yaw -95 --camera-pitch -4
frame right-up --camera-pitch 40              # the spot lights no object
frame point-half --point 1,1,1,0.35           # point x 0.5
frame spot-half --spot 1,1,1,0.5              # spot x 0.25
frame ambient-1.5 --ambient 1,1,1,0.3         # ambient x 1.5
frame specular-red --specular 1,0,0,0.5       # specular's green and blue missing
frame no-diffuse --diffuse 1,1,1,0            # diffuse x 0
frame moved --camera-pos 0.05,0,3             # the camera 0.05 to the right

# A model, which SCENE.md tone-maps (neutral at EV -1): gen-model's sphere
# of 2000 triangles (the test writes the same file), the sun off.
sphere=$(mktemp -d)/sphere.obj
"$build/tools/gen-model" --shape sphere --triangles 2000 -o "$sphere" 2>/dev/null
frame sphere-no-sun --model "$sphere" --time 1 --directional 1,1,1,0
rm -r "$(dirname "$sphere")"
