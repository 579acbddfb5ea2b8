#!/bin/sh
# orphaned_import.sh: assimp's process dies with luz-render (issue 32,
# finding 2). luz-render reads a big generated model (seconds of assimp
# in its child process) and is sent SIGKILL, then SIGTERM, while the
# child works; the child, found by its parent's pid, must be gone (or a
# zombie, dead) within 3 s, where it used to run on under PID 1 until the
# import ended or its CPU limit.
# Usage: orphaned_import.sh LUZ_RENDER GEN_MODEL
set -u
luz_render=$1
gen_model=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$luz_render" --help | grep -q -- '--model' || { echo "SKIP: luz-render without models"; exit 77; }
"$gen_model" --shape bumpy-sphere --triangles 1000000 -o "$work/big.obj" >/dev/null 2>&1 ||
    fail "gen-model could not write the model"

# The pid of process $1's child, or nothing.
child_of() {
    cat /proc/"$1"/task/*/children 2>/dev/null | tr ' ' '\n' | grep -m 1 .
}
# Whether process $1 is gone or a zombie.
dead() {
    [ ! -e /proc/"$1"/stat ] && return 0
    state=$(sed 's/.*) //' /proc/"$1"/stat 2>/dev/null | cut -d ' ' -f 1)
    [ -z "$state" ] || [ "$state" = Z ]
}

for signal in KILL TERM; do
    "$luz_render" --model "$work/big.obj" --size 64x64 -o "$work/out.png" 2>/dev/null &
    pid=$!
    child=
    i=0
    while [ -z "$child" ]; do
        i=$((i + 1))
        [ $i -gt 600 ] && { kill -KILL "$pid"; fail "no import process after 60 s"; }
        kill -0 "$pid" 2>/dev/null || fail "luz-render ended before it started the import"
        sleep 0.1
        child=$(child_of "$pid")
    done
    sleep 1   # well into the import
    dead "$child" && { echo "SKIP: the import ended within a second"; exit 77; }
    kill -"$signal" "$pid"
    wait "$pid" 2>/dev/null
    i=0
    until dead "$child"; do
        i=$((i + 1))
        if [ $i -gt 30 ]; then
            kill -KILL "$child" 2>/dev/null
            fail "SIG$signal to luz-render: its import process $child still runs 3 s later"
        fi
        sleep 0.1
    done
    echo "ok: SIG$signal to luz-render ended its import process $child too"
done
