#!/bin/sh
# counters.sh - the Counters trial: houghlocd keeps publishing MAP and STATUS, and saving
# its map, after its map version passes 2^31 and 2^32 (the edges of the 32-bit counters
# MAP and STATUS once carried; the version lives as long as the map file, growing by one
# per vector added: a laser's map passes 2^31 in about 28 days).
#
# A real map is made first: houghlocd replays logs/tour.lcmlog onto a fresh map file.
# For each edge E (2^31 and 2^32), a copy of that file is given the map version
# E - COUNTERS_BELOW (1000; hl-counter-edge set), and houghlocd replays the tour again onto
# it (at full speed, STATUS every 100 ms), so that the tour's changes (some 13,000) take the
# version across the edge. Checked, on each (hl-counter-edge scan of the output log):
#   - MAP messages went out below and past the edge, each version above the one before,
#     the first the loaded map's (the file's version) and the last past E;
#   - STATUS messages went out past the edge, the last one's map_version the last MAP's;
#   - no MAP or STATUS message fails to decode, and the daemon logged no encoding fault;
#   - the map file the daemon saved at its stop loads (houghlocd --check-map), in format
#     version 2, with the last MAP's version.
#
# Run as `BUILD=build sh tools/lab/trials/counters.sh` (after `make all lab`). The last
# stdout line:
#   counter_edge=<ok|fail>
# Progress and each edge's figures on stderr; files of the last run stay in
# BUILD/trials/counters. Exit status 0 when every check passed.
# Environment: BUILD (build), COUNTERS_BELOW (1000).
set -u
BUILD=${BUILD:-build}
BIN=$BUILD/bin
BELOW=${COUNTERS_BELOW:-1000}
LOG=logs/tour.lcmlog

say() { echo "counters: $*" >&2; }
die() { say "$*"; echo "counter_edge=fail"; exit 1; }
abs() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
field() { sed -n "s/.*\<$2=\([^ ]*\).*/\1/p" "$1"; }     # field FILE KEY

for p in houghlocd hl-counter-edge; do
    [ -x "$BIN/$p" ] || die "$BIN/$p is missing: make BUILD=$BUILD all lab"
done
[ -r "$LOG" ] || die "$LOG is missing (run from the source tree)"
case $BELOW in '' | *[!0-9]*) die "COUNTERS_BELOW '$BELOW' is not a number" ;; esac

work=$(abs "$BUILD/trials/counters")
rm -rf "$work"
mkdir -p "$work" || die "cannot make $work"

replay() {      # replay MAPFILE NAME [--fresh-map]: the tour onto MAPFILE, output NAME.lcmlog
    "$BIN/houghlocd" --config /dev/null ${3:-} -m "$1" \
        --set daemon.status_period_ms=100 \
        -u "file://$(abs "$LOG")?speed=0" -o "file://$work/$2.lcmlog?mode=w" \
        2>"$work/$2.err"
}

say "a real map: houghlocd replays $LOG onto a fresh map file"
replay "$work/base.hlmap" base --fresh-map || die "the first replay failed (see $work/base.err)"
"$BIN/houghlocd" --config /dev/null -m "$work/base.hlmap" --check-map >"$work/base.check" \
    2>&1 || die "the first replay's map does not load: $(cat "$work/base.check")"
say "  $(cat "$work/base.check")"

ok=1
check() {       # check WHAT CONDITION...: a failed condition fails the trial, saying WHAT
    what=$1; shift
    if ! "$@"; then say "  FAIL: $what"; ok=0; fi
}

for edge in 2147483648 4294967296; do
    start=$((edge - BELOW))
    name=edge-$edge
    cp "$work/base.hlmap" "$work/$name.hlmap" || die "cannot copy the map"
    "$BIN/hl-counter-edge" set "$work/$name.hlmap" "$start" >/dev/null 2>"$work/$name.set" ||
        die "cannot set the map version: $(cat "$work/$name.set")"
    say "edge $edge: the tour again onto the map at version $start"
    replay "$work/$name.hlmap" "$name" || { say "  FAIL: houghlocd exited $?"; ok=0; }
    "$BIN/hl-counter-edge" scan "$work/$name.lcmlog" "$edge" >"$work/$name.scan" ||
        { say "  FAIL: cannot read $work/$name.lcmlog"; ok=0; continue; }
    "$BIN/houghlocd" --config /dev/null -m "$work/$name.hlmap" --check-map \
        >"$work/$name.check" 2>&1 || { say "  FAIL: $(cat "$work/$name.check")"; ok=0; }
    s=$work/$name.scan
    maps=$(field "$s" maps); past=$(field "$s" maps_past)
    first=$(field "$s" map_first); last=$(field "$s" map_last)
    statuses=$(field "$s" statuses); spast=$(field "$s" statuses_past)
    slast=$(field "$s" status_last)
    saved=$(sed -n 's/.* map version \([0-9]*\),.*/\1/p' "$work/$name.check")
    format=$(sed -n 's/.*: format \([0-9]*\),.*/\1/p' "$work/$name.check")
    say "  MAP: $maps messages, $past past the edge, versions $first .. $last" \
        "(rising: $(field "$s" map_rising)); STATUS: $statuses, $spast past the edge," \
        "last map_version $slast; saved map: format ${format:-?}, version ${saved:-?}"
    check "MAP went out below the edge" test "$((maps - past))" -ge 1
    check "MAP went out past the edge" test "$past" -ge 1
    check "MAP versions rise" test "$(field "$s" map_rising)" = yes
    check "the first MAP is the loaded map, at the file's version" test "$first" = "$start"
    check "the last MAP is past the edge" test "$last" -ge "$edge"
    check "STATUS went out past the edge" test "$spast" -ge 1
    check "the last STATUS has the last MAP's version" test "$slast" = "$last"
    check "every MAP and STATUS decodes" test "$(field "$s" undecodable)" = 0
    check "no encoding fault logged" sh -c '! grep -q "does not encode" "$1"' - "$work/$name.err"
    check "the saved map loads in format 2" test "${format:-0}" = 2
    check "the saved map has the last MAP's version" test "${saved:-0}" = "$last"
done

if [ $ok -eq 1 ]; then echo "counter_edge=ok"; else echo "counter_edge=fail"; exit 1; fi
