#!/bin/sh
# usage: check-textures.sh GEN_TEXTURES COMMITTED_DIR
#
# Runs GEN_TEXTURES into a fresh temporary directory and checks that it
# writes exactly the PNGs in COMMITTED_DIR: the same file names, and every
# file byte-identical.  If this fails after an intended change to
# gen-textures.c, regenerate with `ninja -C build textures` and commit.
set -u

if [ "$#" -ne 2 ]; then
    echo "usage: check-textures.sh GEN_TEXTURES COMMITTED_DIR" >&2
    exit 2
fi
generator=$1
committed=$2

fresh=$(mktemp -d "${TMPDIR:-/tmp}/luz-textures.XXXXXX") || exit 1
trap 'rm -rf "$fresh"' EXIT

if ! "$generator" "$fresh"; then
    echo "check-textures: $generator failed" >&2
    exit 1
fi

# The two sets of names, one per line, sorted the same way.
list_pngs() {
    (cd "$1" && for file in *.png; do [ -e "$file" ] && echo "$file"; done) | LC_ALL=C sort
}
list_pngs "$fresh" > "$fresh/.generated-names"
list_pngs "$committed" > "$fresh/.committed-names"

status=0
if ! cmp -s "$fresh/.generated-names" "$fresh/.committed-names"; then
    echo "check-textures: the PNG names in $committed differ from those generated:" >&2
    diff "$fresh/.committed-names" "$fresh/.generated-names" | sed -n 's/^[<>]/  &/p' >&2
    echo "  (< only committed, > only generated)" >&2
    status=1
fi

while read -r name; do
    if [ -e "$committed/$name" ] && ! cmp -s "$fresh/$name" "$committed/$name"; then
        echo "check-textures: $committed/$name differs from what gen-textures writes" >&2
        status=1
    fi
done < "$fresh/.generated-names"

if [ "$status" -eq 0 ]; then
    echo "check-textures: $(wc -l < "$fresh/.generated-names") textures match"
else
    echo "check-textures: regenerate with 'ninja -C build textures' if the change is intended" >&2
fi
exit "$status"
