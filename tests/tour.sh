#!/bin/sh
# tour.sh SOURCE_DIR LUZ_RENDER: the guided tour (docs/pipeline.md, "Guided
# tour") says nothing that the program contradicts.
#
# In the section from "## Guided tour" to "### Further reading":
#
#   commands   a code block whose first line is "$ luz-render ..." must
#              hold exactly what that command line prints (run by sh, with
#              the luz-render under test first in PATH, the source tree's
#              textures, in an empty directory);
#   numbers    each `key=value` in backticks outside code blocks is checked
#              against the nearest output above it (of the commands above)
#              that has a line "key=...": the same count of comma-separated
#              values, each number equal to the output's rounded to the
#              decimals the page writes ("0.961" is 0.960961 to three
#              places), anything else equal as written;
#   names      a name in backticks next to a link to a source file,
#              "`name` in [`file`](path)" or "[`file`](path) (`name`)",
#              occurs in that file; every other name in backticks with an
#              underscore in it (a function, a type, a constant) occurs
#              somewhere in src/ or include/, unless it is a key the
#              commands print.
#
# HTML comments are skipped. The page's numbers are not written down
# here a second time: the page and the program are compared with each
# other, so a change to either shows up as a difference.
set -u

source_dir=$1
luz_render=$2
readme=$source_dir/docs/pipeline.md

work=$(mktemp -d "${TMPDIR:-/tmp}/luz-tour.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
mkdir "$work/run" "$work/bin" || exit 1
# The commands run as from the top of the source tree: docs/ is there
# (the gallery's scene files), nothing else.
ln -s "$(cd "$source_dir" && pwd)/docs" "$work/run/docs" || exit 1
# The reader's `luz-render`: the one under test, under that name.
ln -s "$(cd "$(dirname "$luz_render")" && pwd)/$(basename "$luz_render")" \
    "$work/bin/luz-render" || exit 1
unset LUZ_TEXTURES

failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# ---- 1. The tour, cut into its pieces -----------------------------------
# Writes, in page order:
#   $work/command.N, $work/expected.N   the N-th command block
#   $work/items                         one item a line, tab-separated:
#     span   LINE BLOCKS KEY VALUE      (BLOCKS: commands above it)
#     link   LINE NAME PATH
#     name   LINE NAME
awk -v work="$work" '
function flush(   text, rest, span, m, name, path, before, after) {
    if (paragraph == "") return
    text = paragraph
    paragraph = ""
    # `name` in [`file`](path)  and  [`file`](path) (`name`)
    rest = text
    while (match(rest, /`[A-Za-z_][A-Za-z0-9_]*` in \[`[^`]*`\]\([^)]*\)/)) {
        m = substr(rest, RSTART, RLENGTH)
        rest = substr(rest, RSTART + RLENGTH)
        name = m; sub(/^`/, "", name); sub(/`.*/, "", name)
        path = m; sub(/.*\]\(/, "", path); sub(/\)$/, "", path)
        printf "link\t%d\t%s\t%s\n", start, name, path > (work "/items")
    }
    rest = text
    while (match(rest, /\[`[^`]*`\]\([^)]*\) \(`[A-Za-z_][A-Za-z0-9_]*`\)/)) {
        m = substr(rest, RSTART, RLENGTH)
        rest = substr(rest, RSTART + RLENGTH)
        path = m; sub(/^[^(]*\(/, "", path); sub(/\).*/, "", path)
        name = m; sub(/.*\(`/, "", name); sub(/`\)$/, "", name)
        printf "link\t%d\t%s\t%s\n", start, name, path > (work "/items")
    }
    # every span in backticks
    rest = text
    while (match(rest, /`[^`]+`/)) {
        span = substr(rest, RSTART + 1, RLENGTH - 2)
        rest = substr(rest, RSTART + RLENGTH)
        if (span ~ /^[A-Za-z_][A-Za-z0-9_]*=[^ ]+$/) {
            before = span; sub(/=.*/, "", before)
            after = span; sub(/^[^=]*=/, "", after)
            printf "span\t%d\t%d\t%s\t%s\n", start, blocks, before, after > (work "/items")
        } else if (span ~ /^[A-Za-z_][A-Za-z0-9_]*$/ && span ~ /_/) {
            printf "name\t%d\t%s\n", start, span > (work "/items")
        }
    }
}
/^## Guided tour/ { inside = 1; next }
/^### Further reading/ { flush(); inside = 0 }
!inside { next }
comment { if ($0 ~ /-->/) comment = 0; next }
/^<!--/ { flush(); if ($0 !~ /-->/) comment = 1; next }
/^```/ {
    flush()
    if (!fenced) { fenced = 1; first = 1; block_open = 0; next }
    fenced = 0
    if (block_open) close(work "/expected." blocks)
    next
}
fenced {
    if (first && /^\$ /) {
        blocks++
        block_open = 1
        command = substr($0, 3)
        printf "%s\n", command > (work "/command." blocks)
        close(work "/command." blocks)
        printf "" > (work "/expected." blocks)
    } else if (block_open) {
        print > (work "/expected." blocks)
    }
    first = 0
    next
}
/^[[:space:]]*$/ { flush(); next }
{
    if (paragraph == "") { start = NR; paragraph = $0 } else paragraph = paragraph " " $0
}
END { flush(); print blocks + 0 > (work "/blocks") }
' "$readme"
touch "$work/items"

blocks=$(cat "$work/blocks")
if [ "$blocks" -eq 0 ]; then
    fail "docs/pipeline.md: no command blocks (\"\$ luz-render ...\") in the Guided tour"
fi

# ---- 2. Each command prints what its block shows --------------------------
n=1
while [ "$n" -le "$blocks" ]; do
    command=$(cat "$work/command.$n")
    case $command in
    "luz-render "*) ;;
    *) fail "docs/pipeline.md: a tour command that is not luz-render's: $command"
       n=$((n + 1)); continue ;;
    esac
    (cd "$work/run" && PATH="$work/bin:$PATH" sh -c "$command") \
        >"$work/output.$n" 2>"$work/errors.$n"
    if [ -s "$work/errors.$n" ]; then
        fail "\$ $command wrote to stderr:"
        cat "$work/errors.$n"
    fi
    if ! cmp -s "$work/output.$n" "$work/expected.$n"; then
        fail "docs/pipeline.md shows for \$ $command what it does not print (- page, + program):"
        diff "$work/expected.$n" "$work/output.$n"
    fi
    n=$((n + 1))
done

# ---- 3. Every number quoted is the output's, rounded as written ------------
spans=$(awk -F '\t' '$1 == "span"' "$work/items" | wc -l)
[ "$spans" -gt 0 ] || fail "docs/pipeline.md: no \`key=value\` quoted in the Guided tour"
awk -F '\t' -v work="$work" '
function numeric(x) { return x ~ /^-?[0-9]+(\.[0-9]+)?$/ }
# the value of "key=" in output n, or "" (found[0] says whether)
function lookup(n, key,   file, line, value) {
    file = work "/output." n
    value = ""; found = 0
    while ((getline line < file) > 0)
        if (!found && index(line, key "=") == 1) { value = substr(line, length(key) + 2); found = 1 }
    close(file)
    return value
}
$1 == "span" {
    line = $2; above = $3; key = $4; quoted = $5
    value = ""; found = 0
    for (n = above; n >= 1 && !found; n--) { value = lookup(n, key); source = n }
    if (!found) {
        printf "FAIL: docs/pipeline.md:%d: `%s=%s`: no command above it prints a %s= line\n", line, key, quoted, key
        bad++; next
    }
    count = split(quoted, want, ","); got_count = split(value, got, ",")
    if (count != got_count) {
        printf "FAIL: docs/pipeline.md:%d: `%s=%s` has %d values, the output of command %d %d: %s=%s\n", line, key, quoted, count, source, got_count, key, value
        bad++; next
    }
    for (k = 1; k <= count; k++) {
        if (numeric(want[k]) && got[k] ~ /^-?[0-9.]+([eE][-+]?[0-9]+)?$/) {
            decimals = index(want[k], ".") ? length(want[k]) - index(want[k], ".") : 0
            rounded = sprintf("%." decimals "f", got[k] + 0)
            if (rounded ~ /^-0(\.0*)?$/) sub(/^-/, "", rounded)
            ok = rounded == want[k]
        } else {
            rounded = got[k]
            ok = got[k] == want[k]
        }
        if (!ok) {
            printf "FAIL: docs/pipeline.md:%d: `%s=%s`: value %d is %s in the output (%s=%s), %s rounded as written\n", line, key, quoted, k, got[k], key, value, rounded
            bad++
        }
    }
    checked++
}
END {
    printf "%d numbers quoted as key=value checked\n", checked
    exit bad > 0
}' "$work/items" || failures=$((failures + 1))

# ---- 4. The functions named are where the tour says ------------------------
tab=$(printf '\t')
links=0
while IFS="$tab" read -r kind line name path; do
    case $kind in
    link)
        links=$((links + 1))
        # relative to docs/, where the page is
        path=${path#../}
        case $path in
        src/* | include/*) ;;
        *) fail "docs/pipeline.md:$line: \`$name\` is linked to $path, not a source file"
           continue ;;
        esac
        if [ ! -f "$source_dir/$path" ]; then
            fail "docs/pipeline.md:$line: \`$name\` in $path: there is no such file"
        elif ! grep -qw -- "$name" "$source_dir/$path"; then
            fail "docs/pipeline.md:$line: \`$name\` is not in $path"
        fi ;;
    name)
        # a line the commands above print (`corner0_window`) is no C name
        if cat "$work"/output.* 2>/dev/null | grep -q "^$name="; then
            continue
        fi
        if ! grep -rqw -- "$name" "$source_dir/src" "$source_dir/include"; then
            fail "docs/pipeline.md:$line: \`$name\` occurs nowhere in src/ or include/"
        fi ;;
    esac
done <"$work/items"
[ "$links" -gt 0 ] || fail "docs/pipeline.md: no \`function\` in [\`file\`](path) in the Guided tour"

echo "$blocks commands run, $links linked names checked"
[ "$failures" -eq 0 ]
