#!/bin/sh
# Integration test of MAP's rate (src/daemon/cycle_map.c): a batch replay of the tour
# writes MAP within daemon.map_input_ratio (default 4) bytes per byte of SONAR and
# ODOMETRY taken, plus the first map and the last; the bound leaves POSE as it was; the
# log's last MAP is the final map; and the key refuses a value out of range. Every check
# names what it tests.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
TOUR=$PWD/logs/tour.lcmlog
D="$BIN/houghlocd --config /dev/null"

replay() {  # replay NAME [ARGS...]: the tour into $tmp/NAME.lcmlog, map $tmp/NAME.hlmap
    name=$1; shift
    $D --fresh-map --map "$tmp/$name.hlmap" --lcm-url "file://$TOUR?speed=0" \
        --lcm-out "file://$tmp/$name.lcmlog?mode=w" "$@" 2>"$tmp/$name.err"
}

bytes() {   # bytes LOG CHANNEL: the channel's payloads, as hl-eval extract writes them
            # (each with its 4-byte length)
    "$BIN/hl-eval" extract "$1" "$2" "$tmp/x.$2" && wc -c <"$tmp/x.$2"
}

replay bounded
check "a replay with the default bound exits 0" test $? -eq 0
replay unbounded --set daemon.map_input_ratio=0
check "a replay without the bound in bytes exits 0" test $? -eq 0

input=$(( $(bytes "$TOUR" SONAR) + $(bytes "$TOUR" ODOMETRY) ))
bounded=$(bytes "$tmp/bounded.lcmlog" MAP)
unbounded=$(bytes "$tmp/unbounded.lcmlog" MAP)
largest=$((4 + 28 + 12 * 1500))     # a MAP of the default 1500 vectors, with its length
limit=$((4 * input + 2 * largest))
echo "  SONAR+ODOMETRY $input bytes; MAP $bounded bytes bounded, $unbounded without the bound; limit $limit"
check "MAP stays within 4 bytes per byte of input, plus the first map and the last" \
    test "$bounded" -le "$limit"
check "... which a MAP on every change would exceed (the check can fail)" \
    test "$unbounded" -gt "$limit"

for run in bounded unbounded; do
    "$BIN/hl-eval" extract "$tmp/$run.lcmlog" POSE "$tmp/$run.POSE"
done
check "the bound leaves POSE byte-identical" cmp -s "$tmp/bounded.POSE" "$tmp/unbounded.POSE"
"$BIN/hl-eval" text "$tmp/bounded.lcmlog" POSE "$tmp/bounded.POSE.txt"
check "... and equal to the golden stream (tests/golden/tour.sonar-stops.POSE.txt)" \
    cmp -s "$tmp/bounded.POSE.txt" tests/golden/tour.sonar-stops.POSE.txt
check "... and the saved map file" cmp -s "$tmp/bounded.hlmap" "$tmp/unbounded.hlmap"

# houghloc-map draws a log's last MAP: the same picture as the map file's
"$BIN/houghloc-map" "$tmp/bounded.lcmlog" "$tmp/fromlog" >/dev/null 2>&1 &&
    "$BIN/houghloc-map" "$tmp/bounded.hlmap" "$tmp/fromfile" >/dev/null 2>&1
check "the log's last MAP is the final map (houghloc-map draws the map file's cells)" \
    cmp -s "$tmp/fromlog.pgm" "$tmp/fromfile.pgm"

replay again
"$BIN/hl-eval" extract "$tmp/bounded.lcmlog" MAP "$tmp/a.MAP"
"$BIN/hl-eval" extract "$tmp/again.lcmlog" MAP "$tmp/b.MAP"
check "two replays give the byte-identical bounded MAP stream" cmp -s "$tmp/a.MAP" "$tmp/b.MAP"

rejects "a ratio above 1000 is refused, naming the key" 1 \
    "map_input_ratio.*1001 is outside 0\.\.1000" \
    $D --set daemon.map_input_ratio=1001 --print-config
rejects "a negative ratio is refused" 1 "daemon.map_input_ratio" \
    $D --set daemon.map_input_ratio=-1 --print-config

exit $fail
