#!/bin/sh
# run_row.sh - one step of `make kidnap` (tools/kidnap/kidnap.mk).
#
#   run_row.sh tour WORLD        hl-sim-logs --seed KIDNAP_TOUR_SEED (default 1) of WORLD
#                                (lab: the built-in lab, else tools/sim/worlds/WORLD.world)
#                                into KIDNAP_OUT/sim/WORLD/
#   run_row.sh map WORLD         houghlocd replays that tour in batch, with the compiled-in
#                                defaults, from the tour's true start pose (so that the
#                                map's frame is the world's): KIDNAP_OUT/sim/WORLD/map.hlmap
#   run_row.sh sim WORLD         the row WORLD sonar: KIDNAP_TRIALS_SIM soundings at random
#                                free poses relocalized in that map, with the compiled-in
#                                defaults (tools/kidnap/WORLD.conf when there is one)
#   run_row.sh real BUILDING INPUT   the row BUILDING INPUT (laser or sonar): the import
#                                EVAL_OUT/input/BUILDING_INPUT_every.lcmlog (made by
#                                tools/realeval/realeval.mk's rule), KIDNAP_TRIALS_REAL
#                                test scans, each relocalized in a map of the others that
#                                leaves out those within 2 m (tools/realeval/INPUT.conf,
#                                then tools/kidnap/INPUT-search.conf when there is one)
#
# A row is one line in KIDNAP_OUT/rows/WORLD_INPUT.tsv (hl-kidnap's columns), with each
# trial in KIDNAP_OUT/trials/WORLD_INPUT.tsv. Environment: BUILD, DATA, EVAL_OUT,
# KIDNAP_OUT, KIDNAP_TRIALS_SIM, KIDNAP_TRIALS_REAL, KIDNAP_TOUR_SET (--set options of the
# map-making tour), KIDNAP_TOUR_SEED (its hl-sim-logs seed). Any failure stops with one line
#   kidnap: WHAT: STEP failed: REASON
# and exit status 1 (2 for bad usage), leaving no output file.
set -u

BUILD=${BUILD:-build}
BIN=$BUILD/bin
DATA=${DATA:-../shared/data}
EVAL_OUT=${EVAL_OUT:-$BUILD/eval}
OUT=${KIDNAP_OUT:-$BUILD/kidnap}
tour_seed=${KIDNAP_TOUR_SEED:-1}
HERE=$(dirname "$0")

usage() {
    echo "usage: run_row.sh tour|map|sim WORLD | run_row.sh real BUILDING laser|sonar" >&2
    exit 2
}

what=""
die() {     # die STEP REASON
    echo "kidnap: $what: $1 failed: $2" >&2
    exit 1
}

abs() {     # abs PATH: made absolute (liblcm's file:// URLs need it)
    case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac
}

lasterr() { # lasterr FILE: its last line that is not a syslog info/debug line
    l=$(grep -v '^<[67]>' "$1" 2>/dev/null | tail -n 1)
    [ -n "$l" ] || l=$(tail -n 1 "$1" 2>/dev/null)
    echo "$l" | sed 's/^<[0-7]>//'
}

conf_sets() {   # conf_sets FILE: its keys as --set options ([section] key = value)
    awk '/^[[:space:]]*([;#]|$)/ { next }
         /^[[:space:]]*\[/ { gsub(/[][[:space:]]/, ""); sect = $0; next }
         { k = $0; sub(/=.*/, "", k); gsub(/[[:space:]]/, "", k)
           v = $0; sub(/^[^=]*=[[:space:]]*/, "", v); sub(/[[:space:]]+$/, "", v)
           printf "--set %s.%s=%s\n", sect, k, v }' "$1"
}

[ $# -ge 2 ] || usage
cmd=$1 w=$2
case $cmd in
tour | map | sim) [ $# -eq 2 ] || usage; what="$w sonar" ;;
real) [ $# -eq 3 ] || usage
    case $3 in laser | sonar) ;; *) usage ;; esac
    what="$w $3" ;;
*) usage ;;
esac
case $w in '' | */* | .*) usage ;; esac

sim=$OUT/sim/$w
mkdir -p "$sim" "$OUT/rows" "$OUT/trials" || die setup "cannot create folders in $OUT"

world_opt() {   # the world's hl-sim-logs option
    if [ "$w" = lab ]; then echo ""; else echo "--world $HERE/../sim/worlds/$w.world"; fi
}

case $cmd in
tour)
    [ "$w" = lab ] || [ -r "$HERE/../sim/worlds/$w.world" ] || die tour "no world tools/sim/worlds/$w.world"
    case $tour_seed in
    '' | *[!0-9]*) die tour "KIDNAP_TOUR_SEED '$tour_seed' is not a whole number" ;;
    esac
    echo "kidnap: $what: simulating the tour (hl-sim-logs --seed $tour_seed)" >&2
    rm -rf "$sim/logs"
    # shellcheck disable=SC2046  # the option and its value
    "$BIN/hl-sim-logs" --seed "$tour_seed" --out-dir "$sim/logs" $(world_opt) \
        >"$sim/sim.out" 2>"$sim/sim.err" ||
        die tour "$(lasterr "$sim/sim.err")"
    mv "$sim/logs/tour.lcmlog" "$sim/tour.lcmlog" || die tour "no tour.lcmlog written"
    rm -rf "$sim/logs"
    ;;
map)
    start=$("$BIN/hl-eval" start "$sim/tour.lcmlog" 2>"$sim/start.err") ||
        die map "$(lasterr "$sim/start.err")"
    # shellcheck disable=SC2086
    set -- $start
    [ $# -eq 3 ] || die map "hl-eval start printed '$start'"
    echo "kidnap: $what: the daemon's tour" >&2
    sets=""
    for kv in ${KIDNAP_TOUR_SET:-}; do sets="$sets --set $kv"; done
    rm -f "$sim/map.hlmap" "$sim/map.tmp.hlmap"
    # shellcheck disable=SC2086  # $sets is a list of options
    "$BIN/houghlocd" --config /dev/null $sets \
        --set "start.x_m=$1" --set "start.y_m=$2" --set "start.heading_deg=$3" \
        --fresh-map --map "$sim/map.tmp.hlmap" \
        --lcm-url "file://$(abs "$sim/tour.lcmlog")?speed=0" \
        --lcm-out "file://$(abs "$sim/out.lcmlog")?mode=w" 2>"$sim/daemon.err" ||
        die map "$(lasterr "$sim/daemon.err")"
    # How far the map is from the world: the tour's own error (hl-eval score).
    "$BIN/hl-eval" score "$sim/tour.lcmlog" "$sim/out.lcmlog" >"$sim/score.txt" 2>&1 ||
        die map "hl-eval score: $(lasterr "$sim/score.txt")"
    echo "kidnap: $what: the tour's $(tail -n 1 "$sim/score.txt" | sed 's/^demo //')" >&2
    mv "$sim/map.tmp.hlmap" "$sim/map.hlmap" || die map "cannot rename the map"
    ;;
sim | real)
    if [ "$cmd" = sim ]; then
        input=sonar trials=${KIDNAP_TRIALS_SIM:-200}
        world=$w
        [ "$w" = lab ] || world=$HERE/../sim/worlds/$w.world
        src="--sim-world $world --map $sim/map.hlmap --test-log $sim/tests.lcmlog"
        # The compiled-in defaults, but for what tools/kidnap/WORLD.conf says the world needs.
        conf=/dev/null
        [ -r "$HERE/$w.conf" ] && conf=$HERE/$w.conf
    else
        input=$3 trials=${KIDNAP_TRIALS_REAL:-100}
        for f in "$DATA/raw/$w-raw.log.gz" "$DATA/raw/$w-groundtruth.tum"; do
            [ -r "$f" ] || die data "no $f (set DATA=, the folder holding raw/, or BUILDINGS=)"
        done
        in_log=$EVAL_OUT/input/${w}_${input}_every.lcmlog
        [ -s "$in_log" ] || die data "no import $in_log"
        src="--log $in_log"
        conf=$HERE/../realeval/$input.conf
        # the search's own settings for this input, on top of the tracking's
        if [ -r "$HERE/$input-search.conf" ]; then
            src="$src $(conf_sets "$HERE/$input-search.conf" | tr '\n' ' ')"
        fi
    fi
    row=$OUT/rows/${w}_$input.tsv
    rm -f "$row"
    echo "kidnap: $what: $trials trials" >&2
    t0=$(date +%s)
    err=$OUT/trials/${w}_$input.err
    # Progress goes on to stderr as it comes, and into $err for the reason of a failure.
    # shellcheck disable=SC2086  # $src is a list of options
    { "$BIN/hl-kidnap" --config "$conf" --world "$w" --input "$input" --trials "$trials" \
        $src --detail "$OUT/trials/${w}_$input.tsv" 2>&1 >"$row.tmp"
      echo $? >"$err.status"; } | tee "$err" >&2
    if [ "$(cat "$err.status" 2>/dev/null)" != 0 ]; then
        rm -f "$row.tmp" "$err.status"
        die trials "$(lasterr "$err")"
    fi
    rm -f "$err.status"
    mv "$row.tmp" "$row" || die row "cannot rename $row.tmp"
    echo "kidnap: $what: done in $(( $(date +%s) - t0 )) s" >&2
    ;;
esac
