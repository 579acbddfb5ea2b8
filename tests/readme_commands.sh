#!/bin/sh
# readme_commands.sh SOURCE_DIR LUZ_RENDER: every luz-render command that
# README.md shows in a ```sh block (a line starting `luz-render ` or
# `./build/src/luz-render `, its `# comment` cut off) runs as shown: exit
# status 0, nothing on stderr, and the PNG it names with -o written. They
# run in an empty directory with the luz-render under test as both names
# and the source tree's textures.
set -u
source_dir=$1
luz_render=$2
readme=$source_dir/README.md

work=$(mktemp -d "${TMPDIR:-/tmp}/luz-readme-commands.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/run/build/src" "$work/bin" || exit 1
target="$(cd "$(dirname "$luz_render")" && pwd)/$(basename "$luz_render")"
ln -s "$target" "$work/bin/luz-render" || exit 1
ln -s "$target" "$work/run/build/src/luz-render" || exit 1
unset LUZ_TEXTURES

awk '/^```sh/ { on = 1; next }
     /^```/ { on = 0; next }
     on && /^(\.\/build\/src\/)?luz-render / { sub(/[ \t]+#.*$/, ""); print }' \
    "$readme" >"$work/commands"

count=$(wc -l <"$work/commands")
if [ "$count" -lt 3 ]; then
    echo "FAIL: README.md: found only $count luz-render commands in its sh blocks"
    exit 1
fi
failures=0
while IFS= read -r command; do
    if ! (cd "$work/run" && PATH="$work/bin:$PATH" sh -c "$command") \
        >"$work/out" 2>"$work/err"; then
        echo "FAIL: \$ $command: exit status not 0: $(head -n 3 "$work/err")"
        failures=$((failures + 1)); continue
    fi
    if [ -s "$work/err" ]; then
        echo "FAIL: \$ $command wrote to stderr: $(head -n 3 "$work/err")"
        failures=$((failures + 1))
    fi
    output=$(printf '%s\n' "$command" | sed -n 's/.* -o \([^ ]*\).*/\1/p')
    if [ -n "$output" ]; then
        if ! head -c 8 "$work/run/$output" 2>/dev/null | od -An -tx1 | grep -q '89 50 4e 47 0d 0a 1a 0a'; then
            echo "FAIL: \$ $command: no PNG written to $output"
            failures=$((failures + 1))
        fi
    fi
done <"$work/commands"
echo "$count README commands run"
[ "$failures" -eq 0 ]
