#!/bin/sh
# portable-build: libluz and luz-render ask nothing of Linux outside
# src/io/platform_linux.c and src/io/model_confine.c (io/platform.h;
# issue 28) and src/renderer/huge_pages_linux.c (renderer/huge_pages.h),
# so that they build on macOS and the BSDs, which CI does not have.
# Checked here, on Linux:
#   - no other file of src/ (the viewer's aside: SDL and X11) includes a
#     Linux header or names /proc/self, pipe2, prctl, openat2, O_PATH,
#     syscall(), madvise() or MADV_HUGEPAGE;
#   - every source file of libluz and luz-render, with
#     io/platform_posix.c, io/model_confine_none.c and
#     renderer/huge_pages_posix.c (what the other systems build) in place
#     of the Linux ones, compiles with -std=c11
#     -D_POSIX_C_SOURCE=200809L and no _GNU_SOURCE (glibc then declares
#     POSIX's names alone), with Linux's own headers replaced by ones that
#     stop the compiler.
#   Each file is compiled with its own command from BUILD's
#   compile_commands.json (its instruction-set flags and defines; the
#   project's -std=c11 -D_POSIX_C_SOURCE=200809L), -fsyntax-only.
# Usage: portable_build.sh SOURCE_ROOT BUILD
set -u
root=$1
build=$2
work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT INT TERM
fail() {
    echo "portable-build: $*"
    exit 1
}

linux_only='src/io/platform_linux.c|src/io/model_confine.c|src/renderer/huge_pages_linux.c'
viewer='src/programs/luz_viewer.c|src/programs/x11_display_probe|src/programs/present_x11'
cd "$root" || exit 1
found=$(grep -nE '#include <(linux/|sys/prctl\.h|sys/syscall\.h|sys/epoll\.h|seccomp\.h)|/proc/self|\b(pipe2|prctl|openat2|syscall|madvise) *\(|\b(O_PATH|MADV_HUGEPAGE)\b|_GNU_SOURCE' \
            src/*/*.c src/*/*.h | grep -vE "^($linux_only|$viewer)" |
            grep -vE '^[^:]*:[0-9]+: *(/?\*|//)')
[ -z "$found" ] || fail "Linux's own calls outside io/platform_linux.c: $found"

# Linux's headers, each an error
for header in linux/openat2.h linux/landlock.h linux/seccomp.h linux/prctl.h sys/prctl.h \
              sys/syscall.h sys/epoll.h sys/inotify.h sys/signalfd.h sys/eventfd.h \
              sys/timerfd.h sys/sysinfo.h sys/sendfile.h seccomp.h; do
    mkdir -p "$work/poisoned/$(dirname "$header")"
    printf '#error "<%s> is Linux'"'"'s: keep it in src/io/platform_linux.c"\n' "$header" \
        > "$work/poisoned/$header"
done

# Each file's own command from the build (compile_commands.json: its
# instruction-set flags, its defines), checked only (-fsyntax-only), with
# the poisoned headers; the POSIX pair with input_file.c's command.
commands=$build/compile_commands.json
[ -f "$commands" ] || fail "no $commands"
sed -n 's/^ *"command": "\(.*\)",$/\1/p' "$commands" | sed 's/\\"/"/g; s/\\\\/\\/g' |
    grep -E ' -c [^ ]*src/(renderer|lab|io|app)/[a-z_0-9]+\.c$| -c [^ ]*src/programs/luz_render\.c$' |
    grep -vE " -c [^ ]*($linux_only)$" > "$work/commands"
io_command=$(grep ' -c [^ ]*src/io/input_file\.c$' "$work/commands") ||
    fail "input_file.c is not in $commands"
for pair in platform_posix.c model_confine_none.c; do
    echo "${io_command%input_file.c}$pair" >> "$work/commands"
done
renderer_command=$(grep ' -c [^ ]*src/renderer/geometry\.c$' "$work/commands") ||
    fail "geometry.c is not in $commands"
echo "${renderer_command%geometry.c}huge_pages_posix.c" >> "$work/commands"
count=0
while read -r command; do
    source=${command##* -c }
    # the command without its outputs (-o, and -MD -MQ -MF's dependency file)
    checked=$(echo "$command" | sed -e 's/ -MD / /; s/ -MQ [^ ]*/ /; s/ -MF [^ ]*/ /; s/ -o [^ ]*/ /')
    if ! (cd "$build" && eval "$checked -fsyntax-only -Werror -fdiagnostics-color=never -I$work/poisoned") \
            > "$work/log" 2>&1; then
        fail "$source does not compile with POSIX alone: $(head -n 5 "$work/log")"
    fi
    count=$((count + 1))
done < "$work/commands"
[ "$count" -ge 40 ] || fail "only $count files found in $commands"
echo "portable-build: $count files of libluz and luz-render compile with POSIX alone, no Linux header"
