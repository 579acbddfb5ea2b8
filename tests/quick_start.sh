#!/bin/sh
# tools/run, the README's first command, in a copy of the repository whose
# tools it calls are stand-ins (no packages installed, nothing compiled):
#
# - the program runs in the caller's folder, so relative -o, --scene and
#   --model paths and the viewer's F2 and F12 files are the caller's
#   (issue 31: it ran in the repository's root);
# - build/ is configured as the README's `meson setup build` is, tests
#   included (issue 31: -Dtests=false left `meson test -C build` two of
#   the suite's tests).
#
# Usage: quick_start.sh SOURCE_ROOT
set -u
source_root=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/luz-quick-start-XXXXXX")
trap 'rm -rf "$work"' EXIT
status=0
fail() { echo "FAIL: $*"; status=1; }

repository="$work/repository"
mkdir -p "$repository/tools" "$work/bin" "$work/caller/sub"
cp "$source_root/tools/run" "$repository/tools/run"
# stand-ins: install-deps installs nothing; meson records its arguments and
# makes build/src/luz-render, a program that prints its folder and
# arguments; ninja builds nothing
printf '#!/bin/sh\nexit 0\n' > "$repository/tools/install-deps"
cat > "$work/bin/meson" <<STUB
#!/bin/sh
echo "\$*" > "$work/meson-arguments"
mkdir -p build/src
printf '#!/bin/sh\\necho "\$(pwd) \$*" > "$work/ran"\\n' > build/src/luz-render
chmod +x build/src/luz-render
STUB
printf '#!/bin/sh\nexit 0\n' > "$work/bin/ninja"
chmod +x "$repository/tools/run" "$repository/tools/install-deps" "$work/bin/meson" \
    "$work/bin/ninja"

(cd "$work/caller/sub" && env -u DISPLAY -u WAYLAND_DISPLAY PATH="$work/bin:$PATH" \
    ../../repository/tools/run --time 8 -o t8.png) >/dev/null 2>"$work/err"
[ "$(cat "$work/ran" 2>/dev/null)" = "$work/caller/sub --time 8 -o t8.png" ] ||
    fail "tools/run ran '$(cat "$work/ran" 2>/dev/null)', expected '$work/caller/sub --time 8 -o t8.png' (the caller's folder)"
[ "$(cat "$work/meson-arguments" 2>/dev/null)" = "setup build" ] ||
    fail "tools/run configured with 'meson $(cat "$work/meson-arguments" 2>/dev/null)', expected 'meson setup build' (the README's, tests included)"
grep -q "rendered with luz-render" "$work/err" || fail "stderr: $(cat "$work/err")"
[ $status -eq 0 ] && echo "tools/run: the caller's folder, build/ as meson setup build"
exit $status
