#!/bin/sh
# The layers point one way (src/meson.build): a file may include headers of
# its own layer and of the layers below it, never above. The renderer's
# public headers include nothing but each other.
#
#   programs -> app -> lab -> renderer,   app -> io -> renderer
#
# Usage: layers.sh SOURCE_ROOT
set -u
root=$1
status=0

# allowed LAYER: the quoted include prefixes a file of LAYER may use.
allowed() {
    case $1 in
    include)  echo "luz" ;;
    renderer) echo "luz renderer" ;;
    lab)      echo "luz lab" ;;
    io)       echo "luz io" ;;
    app)      echo "luz lab io app" ;;
    programs) echo "luz lab io app programs" ;;
    esac
}

check() {   # check LAYER FILE...
    layer=$1
    shift
    ok=$(allowed "$layer")
    for file in "$@"; do
        [ -f "$file" ] || continue
        # #include "prefix/name.h": the prefix is the layer it belongs to.
        grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$file" |
        while IFS= read -r line; do
            header=$(printf '%s\n' "$line" | sed 's/.*include[[:space:]]*"\([^"]*\)".*/\1/')
            case $header in
            */*) prefix=${header%%/*} ;;
            *)   prefix=$layer ;;   # a header beside the file
            esac
            case " $ok " in
            *" $prefix "*) ;;
            *) echo "layers: ${file#"$root"/}:${line%%:*}: $layer includes \"$header\" ($prefix is not below it)"
               echo x >> "$work/failed" ;;
            esac
        done
    done
}

work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
check include "$root"/include/luz/*.h
for layer in renderer lab io app programs; do
    check "$layer" "$root/src/$layer"/*.c "$root/src/$layer"/*.h
done
# The renderer links nothing that reads files or images.
if grep -ln 'stb_image\|fopen\|opendir' "$root"/src/renderer/*.c "$root"/include/luz/*.h; then
    echo "layers: the files above, in libluz, read files (that is io's job)"
    echo x >> "$work/failed"
fi
if [ -s "$work/failed" ]; then
    exit 1
fi
echo "layers: every include points down"
