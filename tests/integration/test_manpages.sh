#!/bin/sh
# The manual pages in man/: every page the project ships is there, renders with groff and
# with man(1) with every warning on and none given, carries the release of
# include/core/houghloc/version.h, and names every option its program's --help lists.
# Needs man-db and groff-base (apt-get install man-db groff-base).
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
PAGES="houghlocd.8 houghlocd.conf.5 houghloc-goto.1 houghloc-ctl.1 houghloc-console.1
houghloc-sim.1 houghloc-import-carmen.1 houghloc-eval.1 houghloc-map.1"

for tool in man groff; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "FAIL: '$tool' is not installed (apt-get install man-db groff-base)"
        exit 1
    fi
done

# clean PAGE: groff and man render it with all warnings on and print nothing on stderr.
clean() {
    groff -man -Tutf8 -ww -z "$1" 2>"$tmp/groff.err" &&
        [ ! -s "$tmp/groff.err" ] &&
        MANWIDTH=80 man --warnings=w -l "$1" >"$tmp/page.txt" 2>"$tmp/man.err" &&
        [ ! -s "$tmp/man.err" ] &&
        grep -q "^NAME" "$tmp/page.txt"
}

# The check itself must be able to fail: a page with an unknown macro and a bad escape.
printf '.TH BAD 1\n.SH NAME\nbad \\- a broken page\n.SH DESCRIPTION\n.NOSUCH x\nnot\\q\n' \
    >"$tmp/bad.1"
if clean "$tmp/bad.1"; then
    echo "FAIL: a page with warnings passed the check"
    fail=1
else
    echo "ok: the check refuses a page with warnings"
fi

version=$(sed -n 's/^#define HL_VERSION "\(.*\)"$/\1/p' include/core/houghloc/version.h)
[ -n "$version" ] || { echo "FAIL: no HL_VERSION in include/core/houghloc/version.h"; fail=1; }

for page in $PAGES; do
    f=man/$page
    if [ ! -f "$f" ]; then
        echo "FAIL: $f is missing"
        fail=1
        continue
    fi
    if clean "$f"; then
        echo "ok: $page renders without a warning"
    else
        echo "FAIL: $page: $(cat "$tmp/groff.err" "$tmp/man.err" | head -c 400)"
        fail=1
    fi
    if grep -q "^\.TH .*\"houghloc $version\"" "$f"; then
        echo "ok: $page is of houghloc $version"
    else
        echo "FAIL: $page: its .TH line does not name houghloc $version"
        fail=1
    fi
    # Every long option of the program's --help appears in its page (houghlocd.conf.5
    # documents a file, not a program).
    prog=${page%.[0-9]}
    case $page in *.conf.5) continue ;; esac
    if [ ! -x "$BIN/$prog" ]; then
        echo "FAIL: $BIN/$prog is not built (make BUILD=${BUILD:-build})"
        fail=1
        continue
    fi
    "$BIN/$prog" --help 2>&1 | grep -o -- '--[a-z][a-z0-9-]*' | sort -u >"$tmp/opts"
    sed 's/\\-/-/g' "$f" >"$tmp/source"   # the page's text with roff's \- as -
    missing=""
    for opt in $(cat "$tmp/opts"); do
        grep -q -F -- "$opt" "$tmp/source" || missing="$missing $opt"
    done
    if [ -z "$missing" ] && [ -s "$tmp/opts" ]; then
        echo "ok: $page names every option of $prog --help ($(wc -l <"$tmp/opts"))"
    else
        echo "FAIL: $page lacks$missing (of $prog --help)"
        fail=1
    fi
done
exit $fail
