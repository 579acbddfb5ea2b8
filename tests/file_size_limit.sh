#!/bin/sh
# luz-render under a file-size limit (ulimit -f), which the kernel enforces
# with SIGXFSZ, a signal that kills by default: the write must instead fail
# with EFBIG and be reported as any failed write is, in one line with exit
# status 1, leaving neither the PNG nor its temporary NAME.tmp-XXXXXX, and
# an older file under the name as it was.
#
#   tests/file_size_limit.sh LUZ_RENDER
set -u

# absolute: the test runs in a directory of its own
case $1 in
/*) render=$1 ;;
*) render=$(pwd)/$1 ;;
esac
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0

fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# limited LINE ARGS...: luz-render ARGS with a limit of 4 blocks (2 KB for
# sh's 512-byte blocks, 4 KB for 1024): a 320x180 PNG is some 17 KB. Expects
# exit status 1 and exactly LINE on stderr.
limited() {
    line=$1
    shift
    (ulimit -f 4 && exec "$render" --size 320x180 --textures none "$@") >"$work/out" 2>"$work/err"
    status=$?
    if [ "$status" -ne 1 ]; then
        fail "luz-render $*: exit status $status, expected 1 (153 is death by SIGXFSZ)"
    fi
    if [ "$(cat "$work/err")" != "$line" ] || [ "$(wc -l <"$work/err")" -ne 1 ]; then
        fail "luz-render $*: stderr '$(cat "$work/err")', expected '$line'"
    fi
}

# no_leftovers: nothing in the directory but what the test made.
no_leftovers() {
    left=$(ls -A | grep -v -e '^out$' -e '^err$' -e '^old.png$' -e '^stream.bin$')
    [ -z "$left" ] || fail "$1: left behind: $left"
}

limited "luz-render: one.png: cannot write (File too large)" -o one.png
no_leftovers "a single image"

limited "luz-render: frame_0.png: cannot write (File too large)" --frames 3 -o 'frame_%d.png'
no_leftovers "a sequence"

# an older file under the name stays whole
printf 'an older file\n' >old.png
limited "luz-render: old.png: cannot write (File too large)" -o old.png
[ "$(cat old.png)" = "an older file" ] || fail "old.png was changed"
no_leftovers "replacing a file"

# standard output redirected to a file: a stream, cut short, but reported
(ulimit -f 4 && exec "$render" --size 320x180 --textures none -o - >stream.bin) 2>"$work/err"
status=$?
[ "$status" -eq 1 ] || fail "-o - >stream.bin: exit status $status, expected 1"
[ "$(cat "$work/err")" = "luz-render: standard output: cannot write (File too large)" ] ||
    fail "-o - >stream.bin: stderr '$(cat "$work/err")'"

# and without a limit the same run writes the file: the limit was the cause
"$render" --size 320x180 --textures none -o one.png 2>"$work/err" ||
    fail "without a limit: $(cat "$work/err")"
[ -s one.png ] || fail "without a limit: no one.png"

if [ "$failures" -ne 0 ]; then
    echo "file-size-limit: $failures failure(s)"
    exit 1
fi
echo "file-size-limit: every write past ulimit -f failed cleanly"
