#!/bin/sh
# Integration test of the product's programs as a user first meets them: each answers
# --help on stdout with exit 0, and a bad number (letters, trailing junk, out of range,
# leading spaces, hexadecimal) gets exit 2 and one line naming the option and the value,
# before anything runs. (The laboratory's programs: tools/lab/tests/test_tools.sh.)
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh

for p in hl-eval hl-pose-bytes houghloc-ctl houghloc-eval houghloc-goto houghloc-import-carmen \
         houghloc-map houghlocd; do
    "$BIN/$p" --help >"$tmp/out" 2>"$tmp/err"
    check "$p --help: exit 0, usage on stdout" sh -c '[ "$1" -eq 0 ] && [ ! -s "$3" ] &&
        grep -qi "usage" "$2"' - $? "$tmp/out" "$tmp/err"
done

exits "hl-eval split count out of range" 2 "split: '99999999999999999999'" \
    "$BIN/hl-eval" split logs/lab28.lcmlog 99999999999999999999 "$tmp/a.lcmlog" "$tmp/b.lcmlog"
exits "houghloc-eval --delta 0x1" 2 "--delta '0x1'" "$BIN/houghloc-eval" --delta 0x1 "$tmp/none" "$tmp/none"
exits "houghloc-map --resolution ' 1'" 2 "--resolution ' 1'" \
    "$BIN/houghloc-map" --resolution " 1" "$tmp/none" "$tmp/map"
# (on a port of their own, so that even a client that took the value disturbs no daemon)
quiet_url='udpm://239.255.76.67:7611?ttl=0'
exits "houghloc-goto --timeout ' 0.2'" 2 "--timeout \" 0.2\"" \
    "$BIN/houghloc-goto" --lcm-url "$quiet_url" --timeout " 0.2" 1 1
exits "houghloc-ctl --timeout 0x0.4" 2 "--timeout \"0x0.4\"" \
    "$BIN/houghloc-ctl" --lcm-url "$quiet_url" --timeout 0x0.4 save
exits "houghloc-import-carmen --fov-deg 5x" 2 "--fov-deg '5x'" \
    "$BIN/houghloc-import-carmen" --fov-deg 5x "$tmp/none" "$tmp/none.lcmlog"
exit $fail
