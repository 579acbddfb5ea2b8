#!/bin/sh
# What the installed libluz exports: exactly the functions its public
# headers declare LUZ_API (luz/api.h), so nothing of the lab, io, the
# command line or the viewer, and none of the pipeline's internal stages.
#
# Usage: exports.sh LIBLUZ_SO INCLUDE_DIR
set -u
library=$1
include_dir=$2
if ! command -v nm >/dev/null 2>&1; then
    echo "exports: nm (binutils) is not installed"
    exit 77
fi
work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
nm -D --defined-only "$library" | awk '$2 ~ /^[TDBRVWi]$/ { print $3 }' |
    grep -vxE '_init|_fini|_edata|_end|__bss_start' | sort -u > "$work/exported"
# A declaration runs from LUZ_API to the name's parenthesis, maybe over a
# line break; join each header's lines first.
for header in "$include_dir"/luz/*.h; do
    [ "$(basename "$header")" = api.h ] && continue
    tr '\n' ' ' < "$header" | grep -oE 'LUZ_API [^;(]*\(' | grep -oE '[A-Za-z_][A-Za-z0-9_]* *\($' |
        tr -d ' ('
done | sort -u > "$work/declared"
[ -s "$work/declared" ] || { echo "exports: no LUZ_API declaration found in $include_dir"; exit 1; }

status=0
for symbol in $(comm -23 "$work/exported" "$work/declared"); do
    echo "exports: libluz exports $symbol, which no public header declares LUZ_API"
    status=1
done
for symbol in $(comm -13 "$work/exported" "$work/declared"); do
    echo "exports: $symbol is declared LUZ_API but libluz does not export it"
    status=1
done
[ "$status" -eq 0 ] && echo "exports: $(wc -l < "$work/exported") functions, exactly the public headers' LUZ_API ones"
exit "$status"
