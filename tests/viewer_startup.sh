#!/bin/sh
# The viewer's start-up, without a display: what a user sees when something
# is wrong (exit status 2 and exactly one line on stderr that says what),
# --help and --version, and the README's controls table against the
# program's own (the H overlay and --help print the same list).
#
#   tests/viewer_startup.sh LUZ README.md
set -u

luz=$1
readme=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# expect_refusal PATTERN ARGS...: luz ARGS exits with 2, writes one line on
# stderr that matches PATTERN (grep -E), and nothing on stdout.
expect_refusal() {
    pattern=$1
    shift
    "$luz" "$@" >"$work/out" 2>"$work/err" </dev/null
    status=$?
    lines=$(wc -l <"$work/err")
    if [ "$status" -ne 2 ]; then
        fail "luz $*: exit status $status, expected 2"
    elif [ "$lines" -ne 1 ]; then
        fail "luz $*: $lines lines on stderr, expected 1: $(cat "$work/err")"
    elif ! grep -Eq "^luz: .*$pattern" "$work/err"; then
        fail "luz $*: '$(cat "$work/err")' does not match '$pattern'"
    elif [ -s "$work/out" ]; then
        fail "luz $*: wrote on stdout"
    fi
}

# Bad options, the shared parser's and the viewer's own.
expect_refusal "unknown option '--bogus'" --bogus
expect_refusal "--size" --size 0x5
expect_refusal "--camera-pitch" --camera-pitch 95
expect_refusal "--render-scale: expected a number above 0 and at most 1" --render-scale 0
expect_refusal "--render-scale" --render-scale 1.5
expect_refusal "--render-scale" --render-scale=abc
expect_refusal "--render-scale" --render-scale
expect_refusal "--print-state: takes no value" --print-state=yes
expect_refusal "--frames: .*luz-render" --frames 5
expect_refusal "--frame-range: .*luz-render" --frame-range 0:3
expect_refusal "--shard: .*luz-render" --shard=1/4
expect_refusal "--skip-existing: .*luz-render" --skip-existing
expect_refusal "--bench" --bench -1
expect_refusal "-o: .*luz-render" -o out.png
expect_refusal "--probe: expected a pixel of the 480x270 image" --size 480x270 --probe 480,5
expect_refusal "--probe: expected one frame" --probe 1,1 --bench 3
expect_refusal "missing.luz: cannot open" --scene "$work/missing.luz"
# Textures are checked before any window opens.
expect_refusal "--textures: .*$work/no-such-dir" --textures "$work/no-such-dir"
# No display: say so, and point to the batch renderer.
env -u DISPLAY -u WAYLAND_DISPLAY SDL_VIDEODRIVER=x11 "$luz" >"$work/out" 2>"$work/err"
status=$?
if [ "$status" -ne 2 ] || [ "$(wc -l <"$work/err")" -ne 1 ] ||
   ! grep -q '^luz: cannot open a window: no display available .*luz-render' "$work/err"; then
    fail "without a display: status $status, stderr '$(cat "$work/err")'"
fi
# The same when SDL is left to choose, with no display or a dead one: SDL
# would fall back to its offscreen driver and luz would render into nothing
# forever. One line, status 2, well within the time limit.
for display in "" ":97"; do
    if [ -n "$display" ]; then
        DISPLAY=$display timeout 10 env -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$luz" \
            >"$work/out" 2>"$work/err"
    else
        timeout 10 env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$luz" \
            >"$work/out" 2>"$work/err"
    fi
    status=$?
    if [ "$status" -ne 2 ] || [ "$(wc -l <"$work/err")" -ne 1 ] ||
       ! grep -q '^luz: cannot open a window: no display available' "$work/err"; then
        fail "no display '${display:-unset}', SDL's choice: status $status, stderr '$(cat "$work/err")'"
    fi
done

# --help and --version succeed on stdout.
"$luz" --version >"$work/out" 2>"$work/err" || fail "luz --version failed"
grep -q '^luz [0-9]' "$work/out" || fail "luz --version printed '$(cat "$work/out")'"
"$luz" --help >"$work/help" 2>"$work/err" || fail "luz --help failed"
for option in --render-scale --print-state --scene --camera-pos --spot-outer; do
    grep -q -- "$option" "$work/help" || fail "luz --help does not mention $option"
done

# The controls: --help's list (keys padded to 22 columns, as the H overlay
# lists them) and the README's table under "## Viewer", as "keys|action".
awk '/^Controls/ { on = 1; next }
     on && /^$/ { exit }
     on { keys = substr($0, 3, 22); sub(/ +$/, "", keys); print keys "|" substr($0, 26) }' \
    "$work/help" >"$work/help-controls"
awk '/^## Viewer/ { viewer = 1 }
     viewer && /^\| keys \| action \|/ { table = 1; next }
     table && /^\| ---/ { next }
     table && !/^\|/ { exit }
     table { line = $0; sub(/^\| /, "", line); sub(/ \|$/, "", line); sub(/ \| /, "|", line); print line }' \
    "$readme" >"$work/readme-controls"
if [ "$(wc -l <"$work/help-controls")" -lt 20 ]; then
    fail "found only $(wc -l <"$work/help-controls") controls in luz --help"
fi
if ! diff -u "$work/readme-controls" "$work/help-controls" >"$work/controls.diff"; then
    fail "README.md's controls table differs from luz --help (and the H overlay):"
    cat "$work/controls.diff"
fi

[ "$failures" -eq 0 ] || exit 1
echo "ok: start-up errors, --help, --version, README controls"
