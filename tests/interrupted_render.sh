#!/bin/sh
# An interrupted render leaves nothing half-written: luz-render is sent
# SIGTERM while its PNG is being written (the temporary file exists), and
# afterwards there must be no temporary file and either no PNG or a
# complete one. Usage: interrupted_render.sh LUZ_RENDER
set -u
luz_render=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$luz_render" --size 8192x8192 --textures none -o "$work/big.png" &
pid=$!
i=0
until ls "$work"/big.png.tmp-* >/dev/null 2>&1; do
    i=$((i + 1))
    kill -0 "$pid" 2>/dev/null || { echo "SKIP: the render finished before it could be interrupted"; exit 77; }
    [ $i -gt 3000 ] && { kill "$pid"; fail "no temporary file after 300 s"; }
    sleep 0.1
done
kill -TERM "$pid"
wait "$pid"
status=$?
[ "$status" -eq 143 ] || fail "luz-render exited with $status, expected 143 (SIGTERM)"
leftovers=$(ls "$work"/big.png.tmp-* 2>/dev/null)
[ -z "$leftovers" ] || fail "temporary file left behind: $leftovers"
if [ -e "$work/big.png" ]; then
    # A complete PNG ends with the IEND chunk: 'IEND' and its CRC AE426082.
    tail_bytes=$(tail -c 8 "$work/big.png" | od -An -tx1 | tr -d ' \n')
    [ "$tail_bytes" = 49454e44ae426082 ] || fail "big.png is cut short (ends $tail_bytes)"
fi
echo "ok: interrupted while writing; no temporary file, and the PNG is whole"
