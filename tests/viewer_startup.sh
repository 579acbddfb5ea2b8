#!/bin/sh
# The viewer's start-up, without a display: what a user sees when something
# is wrong (exit status 2 and exactly one line on stderr that says what),
# --help and --version, and docs/viewer.md's controls table against the
# program's own (the H overlay and --help print the same list).
#
#   tests/viewer_startup.sh LUZ docs/viewer.md
set -u

luz=$1
viewer_page=$2
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
expect_refusal "--fov: expected a number in \\[1, 179\\]" --fov 1e-45
expect_refusal "--render-scale: expected a number from 0.01 to 1" --render-scale 0
expect_refusal "--render-scale: expected a number from 0.01 to 1" --render-scale 0.009
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
expect_refusal "--legend: .*luz-render" --legend
expect_refusal "--mark: .*luz-render" --mark 10,10
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
# forever. One line, status 2, at once: the plain build takes about 0.2 s
# (the textures are off); the bound leaves room for the sanitizer builds
# on a busy machine, and catches a viewer that does not exit.
now_ms() {
    echo $(($(date +%s%N) / 1000000))
}
# expect_no_display NAME PATTERN COMMAND...: COMMAND luz --textures none
# (COMMAND sets the environment) exits with 2 within 5 s, with one line on
# stderr that starts with PATTERN (grep, basic).
expect_no_display() {
    name=$1
    pattern=$2
    shift 2
    start=$(now_ms)
    timeout 10 "$@" "$luz" --textures none >"$work/out" 2>"$work/err"
    status=$?
    elapsed=$(($(now_ms) - start))
    if [ "$status" -ne 2 ] || [ "$(wc -l <"$work/err")" -ne 1 ] ||
       ! grep -q "^$pattern" "$work/err"; then
        fail "$name: status $status, stderr '$(cat "$work/err")'"
    elif [ "$elapsed" -gt 5000 ]; then
        fail "$name: luz took $elapsed ms to give up"
    fi
}
mkdir "$work/runtime"
chmod 700 "$work/runtime"
# a Wayland socket nobody listens on any more (a compositor that died)
python3 -c "import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])" \
    "$work/runtime/wayland-7" 2>/dev/null
for case in "no display" "dead X11" "dead Wayland" "dead Wayland, no runtime dir" \
            "stale Wayland socket" "dead X11 and Wayland"; do
    set -- env -u DISPLAY -u WAYLAND_DISPLAY -u XDG_RUNTIME_DIR -u SDL_VIDEODRIVER
    case $case in
    "dead X11") set -- "$@" DISPLAY=:97 ;;
    "dead Wayland") set -- "$@" XDG_RUNTIME_DIR="$work/runtime" WAYLAND_DISPLAY=wayland-9 ;;
    "dead Wayland, no runtime dir") set -- "$@" WAYLAND_DISPLAY=wayland-9 ;;
    "stale Wayland socket")
        [ -S "$work/runtime/wayland-7" ] || continue
        set -- "$@" XDG_RUNTIME_DIR="$work/runtime" WAYLAND_DISPLAY=wayland-7 ;;
    "dead X11 and Wayland") set -- "$@" DISPLAY=:97 WAYLAND_DISPLAY=wayland-9 ;;
    esac
    expect_no_display "$case, SDL's choice" 'luz: cannot open a window: no display available' "$@"
done

# Fake X servers on loopback TCP (a free port from 6100, DISPLAY=127.0.0.1:N
# for port 6000 + N), each accepting connections for 30 s and answering
# every one as MODE says:
#   silent   nothing (a server that hangs, or a path that drops replies)
#   one-byte the first byte of a Success reply (1), then nothing
#   garbage  bytes no X server sends ("HTTP/1.0 ..."), then nothing
#   header   a whole 8-byte header announcing 4 more bytes, then nothing
#   probe    a whole Failed reply to the first connection (luz's probe),
#            nothing to the next (Xlib's, under SDL)
# Xlib would wait forever for any of them but the first answer of probe;
# luz reads the whole answer, for a second, before SDL sees the display.
# start_fake_x11 MODE: starts one, sets fake_pid and fake_number (empty if
# none could be started).
start_fake_x11() {
    rm -f "$work/fake-display"
    python3 -c "
import socket, sys, time
mode = sys.argv[2]
reason = b'fake'
failed = bytes([0, len(reason), 11, 0, 0, 0, 1, 0]) + reason
answers = {'silent': b'', 'one-byte': b'\\x01', 'garbage': b'HTTP/1.0 400 Bad Request\\r\\n',
           'header': bytes([1, 0, 11, 0, 0, 0, 1, 0]), 'probe': failed}
for port in range(6100, 6200):
    s = socket.socket()
    try:
        s.bind(('127.0.0.1', port))
    except OSError:
        continue
    s.listen(4)
    open(sys.argv[1], 'w').write(str(port - 6000))
    held = []
    end = time.time() + 30
    while time.time() < end:
        s.settimeout(1)
        try:
            connection, _ = s.accept()
        except OSError:
            continue
        held.append(connection)
        answer = answers[mode] if mode != 'probe' or len(held) == 1 else b''
        if answer:
            connection.sendall(answer)
    break
" "$work/fake-display" "$1" 2>/dev/null &
    fake_pid=$!
    waited=0
    while [ ! -s "$work/fake-display" ] && [ "$waited" -lt 50 ] && kill -0 "$fake_pid" 2>/dev/null; do
        sleep 0.1
        waited=$((waited + 1))
    done
    fake_number=$(cat "$work/fake-display" 2>/dev/null)
}
stop_fake_x11() {
    kill "$fake_pid" 2>/dev/null
    wait "$fake_pid" 2>/dev/null
}
for mode in silent one-byte garbage header; do
    start_fake_x11 $mode
    if [ -z "$fake_number" ]; then
        echo "fake X11 server ($mode): not checked (no python3, or no free port from 6100 to 6199)"
    else
        expect_no_display "fake X11 server, $mode" \
            "luz: cannot open a window: no display available (the X display 127.0.0.1:$fake_number did not answer as an X server within 1 s" \
            env -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER DISPLAY="127.0.0.1:$fake_number"
    fi
    stop_fake_x11
done
# A server that answers the probe and then leaves Xlib waiting: SIGTERM
# ends the viewer while it connects (SDL's handler would only note it).
start_fake_x11 probe
if [ -z "$fake_number" ]; then
    echo "fake X11 server (probe): not checked (no python3, or no free port from 6100 to 6199)"
else
    env -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER DISPLAY="127.0.0.1:$fake_number" \
        "$luz" --textures none >"$work/out" 2>"$work/err" &
    viewer=$!
    sleep 2
    kill -TERM "$viewer" 2>/dev/null
    waited=0
    while kill -0 "$viewer" 2>/dev/null && [ "$waited" -lt 50 ]; do
        sleep 0.1
        waited=$((waited + 1))
    done
    if kill -0 "$viewer" 2>/dev/null; then
        kill -KILL "$viewer" 2>/dev/null
        wait "$viewer"
        fail "fake X11 server answering the probe only: luz still running 5 s after SIGTERM"
    else
        wait "$viewer"
        status=$?
        [ "$status" -eq 143 ] ||
            fail "fake X11 server answering the probe only: status $status after SIGTERM: $(cat "$work/err")"
    fi
fi
stop_fake_x11

# --help and --version succeed on stdout.
"$luz" --version >"$work/out" 2>"$work/err" || fail "luz --version failed"
grep -q '^luz [0-9]' "$work/out" || fail "luz --version printed '$(cat "$work/out")'"
"$luz" --help >"$work/help" 2>"$work/err" || fail "luz --help failed"
for option in --render-scale --print-state --scene --camera-pos --spot-outer; do
    grep -q -- "$option" "$work/help" || fail "luz --help does not mention $option"
done

# The options' descriptions start in one column, the viewer's own too
# (issue 31: --render-scale's and --print-state's were two further right):
# on an option's line after its gap of two or more blanks, on the lines
# that go on with it after blanks alone.
awk '/^Controls/ { exit }
     /^  -/ { if (match($0, /[^ ]  +[^ ]/)) print RSTART + RLENGTH - 1 "|" $0; next }
     /^   / { match($0, /[^ ]/); print RSTART "|" $0 }' "$work/help" |
    awk -F'|' '{ print $1 }' | sort -u >"$work/help-columns"
[ "$(cat "$work/help-columns")" = 32 ] ||
    fail "luz --help: descriptions start in columns $(tr '\n' ' ' <"$work/help-columns"), expected 32 alone"

# The controls: --help's list (keys padded to 22 columns, as the H overlay
# lists them) and docs/viewer.md's table under "## Controls", as "keys|action".
awk '/^Controls/ { on = 1; next }
     on && /^$/ { exit }
     on { keys = substr($0, 3, 22); sub(/ +$/, "", keys); print keys "|" substr($0, 26) }' \
    "$work/help" >"$work/help-controls"
awk '/^## Controls/ { viewer = 1 }
     viewer && /^\| keys \| action \|/ { table = 1; next }
     table && /^\| ---/ { next }
     table && !/^\|/ { exit }
     table { line = $0; sub(/^\| /, "", line); sub(/ \|$/, "", line); sub(/ \| /, "|", line); print line }' \
    "$viewer_page" >"$work/page-controls"
if [ "$(wc -l <"$work/help-controls")" -lt 20 ]; then
    fail "found only $(wc -l <"$work/help-controls") controls in luz --help"
fi
if ! diff -u "$work/page-controls" "$work/help-controls" >"$work/controls.diff"; then
    fail "docs/viewer.md's controls table differs from luz --help (and the H overlay):"
    cat "$work/controls.diff"
fi

[ "$failures" -eq 0 ] || exit 1
echo "ok: start-up errors, --help, --version, docs/viewer.md's controls"
