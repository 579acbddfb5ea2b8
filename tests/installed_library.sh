#!/bin/sh
# The installed libluz, as a C programmer gets it: `meson install` into a
# temporary directory, then, against that alone:
#   - the installed headers are the renderer's (include/luz/*.h), each
#     compiles on its own, and every name they declare is luz_ or LUZ_;
#   - examples/torus.c builds with `pkg-config luz` and runs;
#   - its picture has the torus where its geometry puts it (check_torus).
#
# Usage: installed_library.sh SOURCE_ROOT BUILD_ROOT CHECK_TORUS SANITIZE
# (SANITIZE: the build's b_sanitize, so that the example is built with the
# same sanitizers as the library it loads; "none" for none).
set -u
source_root=$1
build_root=$2
check_torus=$3
sanitize=${4:-none}
cc=${CC:-cc}
sanitize_flags=
[ "$sanitize" = none ] || sanitize_flags="-fsanitize=$sanitize"
work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT INT TERM
fail() {
    echo "installed-library: $*"
    exit 1
}

meson install -C "$build_root" --destdir "$work/root" --no-rebuild --quiet > "$work/install.log" 2>&1 ||
    fail "meson install failed: $(tail -n 3 "$work/install.log")"
pc=$(find "$work/root" -name luz.pc | head -n 1)
[ -n "$pc" ] || fail "no luz.pc installed"
prefix=$work/root$(sed -n 's/^prefix=//p' "$pc")
luz_pkg() {
    PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --define-variable=prefix="$prefix" "$@" luz
}
include_dir=$(luz_pkg --variable=includedir)
lib_dir=$(luz_pkg --variable=libdir)

# The renderer's headers, and nothing else.
installed=$(cd "$include_dir/luz" && ls)
expected=$(cd "$source_root/include/luz" && ls)
[ "$installed" = "$expected" ] ||
    fail "installed headers ($(echo $installed)) are not include/luz's ($(echo $expected))"

for header in "$include_dir"/luz/*.h; do
    name=luz/$(basename "$header")
    printf '#include <%s>\n' "$name" > "$work/alone.c"
    "$cc" -std=c11 -Wall -Wextra -Werror -fsyntax-only $(luz_pkg --cflags) "$work/alone.c" \
        > "$work/alone.log" 2>&1 || fail "$name does not compile on its own: $(head -n 3 "$work/alone.log")"
    # Every declared name: functions, types, macros, enum values.
    names=$(sed -e 's|/\*.*\*/||g' "$header" | grep -v '^ *\*\|^ */\*' |
            grep -oE '^(typedef [^;{]*[ *]|#define |[a-z_][a-z0-9_ *]* \**)[A-Za-z_][A-Za-z0-9_]*( *\(|;| |$)|^ +[A-Z_][A-Z0-9_]*( =|,)' |
            grep -oE '[A-Za-z_][A-Za-z0-9_]*( *\(|;| *=|,| *$)' | grep -oE '^[A-Za-z_][A-Za-z0-9_]*' |
            grep -vE '^(luz_|LUZ_|typedef|static|inline|const|struct|enum|void|int|float|double|bool|char|unsigned|uint8_t|uint16_t|uint32_t|uint64_t|size_t|return|if|else|for|while|__attribute__)')
    [ -z "$names" ] || fail "$name declares names that are not luz_: $(echo $names)"
done

# The example, built against the installed library only.
"$cc" -std=c11 -Wall -Wextra $sanitize_flags -o "$work/torus" "$source_root/examples/torus.c" \
    $(luz_pkg --cflags --libs) $(pkg-config --cflags --libs stb) -lm > "$work/build.log" 2>&1 ||
    fail "examples/torus.c does not build: $(head -n 5 "$work/build.log")"
LD_LIBRARY_PATH=$lib_dir "$work/torus" "$work/torus.png" > "$work/run.log" 2>&1 ||
    fail "examples/torus failed: $(cat "$work/run.log")"
LD_LIBRARY_PATH=$lib_dir ldd "$work/torus" | grep -q "$lib_dir/libluz" ||
    fail "examples/torus did not load the installed libluz"
"$check_torus" "$work/torus.png" || exit 1
echo "installed-library: headers alone and luz_ only; examples/torus built, ran and drew its torus"
