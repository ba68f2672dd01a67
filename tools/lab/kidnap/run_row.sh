#!/bin/sh
# run_row.sh - one step of `make kidnap` (tools/lab/kidnap/kidnap.mk).
#
#   run_row.sh tour WORLD SEED   hl-sim-logs --seed SEED of WORLD (lab: the built-in lab,
#                                else tools/sim/worlds/WORLD.world) into
#                                KIDNAP_OUT/sim/WORLD/SEED/tour.lcmlog
#   run_row.sh map WORLD SEED    houghlocd replays that tour in batch, with the compiled-in
#                                defaults and KIDNAP_TOUR_SET, from the tour's true start
#                                pose (so that the map's frame is the world's):
#                                KIDNAP_OUT/sim/WORLD/SEED/map.hlmap
#   run_row.sh sim WORLD         the row WORLD sonar: the same KIDNAP_TRIALS_SIM soundings
#                                at random free poses, each with the robot's next ones,
#                                relocalized in the map of each tour
#                                of KIDNAP_TOUR_SEEDS, with the compiled-in defaults
#                                (tools/lab/kidnap/WORLD.conf when there is one)
#   run_row.sh real BUILDING INPUT   the row BUILDING INPUT (laser or sonar): the import
#                                EVAL_OUT/input/BUILDING_INPUT_every.lcmlog (made by
#                                tools/lab/realeval/realeval.mk's rule), KIDNAP_TRIALS_REAL
#                                test scans with their robot's next ones, each relocalized
#                                in a map of the others that leaves out those within 2 m
#                                of any of them (tools/lab/realeval/INPUT.conf, then
#                                tools/lab/kidnap/INPUT-search.conf when there is one)
#
# A row is one line in KIDNAP_OUT/rows/WORLD_INPUT.tsv (hl-kidnap's columns), with each
# trial in KIDNAP_OUT/trials/WORLD_INPUT.tsv. Environment: BUILD, DATA, EVAL_OUT,
# KIDNAP_OUT, KIDNAP_TRIALS_SIM, KIDNAP_TRIALS_REAL, KIDNAP_TOUR_SET (--set options of the
# map-making tours), KIDNAP_TOUR_SEEDS (their hl-sim-logs seeds, whole numbers, default
# 1 2 3 4 5 6 7 8). Any failure stops with one line
#   kidnap: WHAT: STEP failed: REASON
# and exit status 1 (2 for bad usage), leaving no output file.
set -u

BUILD=${BUILD:-build}
BIN=$BUILD/bin
DATA=${DATA:-../shared/data}
EVAL_OUT=${EVAL_OUT:-$BUILD/eval}
OUT=${KIDNAP_OUT:-$BUILD/kidnap}
tour_seeds=${KIDNAP_TOUR_SEEDS-1 2 3 4 5 6 7 8}
HERE=$(dirname "$0")

usage() {
    echo "usage: run_row.sh tour|map WORLD SEED | run_row.sh sim WORLD" \
         "| run_row.sh real BUILDING laser|sonar" >&2
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

seed_ok() {     # seed_ok WORD: a whole number (hl-sim-logs --seed)
    case $1 in '' | *[!0-9]*) return 1 ;; esac
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
tour | map) [ $# -eq 3 ] || usage; what="$w sonar"
    seed_ok "$3" || die $cmd "the tour seed '$3' is not a whole number"
    what="$w sonar, tour $3" ;;
sim) [ $# -eq 2 ] || usage; what="$w sonar"
    [ -n "$(echo $tour_seeds)" ] || die sim "KIDNAP_TOUR_SEEDS is empty"
    for s in $tour_seeds; do
        seed_ok "$s" || die sim "KIDNAP_TOUR_SEEDS '$s' is not a whole number"
    done ;;
real) [ $# -eq 3 ] || usage
    case $3 in laser | sonar) ;; *) usage ;; esac
    what="$w $3" ;;
*) usage ;;
esac
case $w in '' | */* | .*) usage ;; esac

sim=$OUT/sim/$w
tour=$sim           # tour and map: the tour's own folder
case $cmd in tour | map) tour=$sim/$3 ;; esac
mkdir -p "$tour" "$OUT/rows" "$OUT/trials" || die setup "cannot create folders in $OUT"

world_opt() {   # the world's hl-sim-logs option
    if [ "$w" = lab ]; then echo ""; else echo "--world $HERE/../../sim/worlds/$w.world"; fi
}

case $cmd in
tour)
    [ "$w" = lab ] || [ -r "$HERE/../../sim/worlds/$w.world" ] || die tour "no world tools/sim/worlds/$w.world"
    echo "kidnap: $what: simulating the tour (hl-sim-logs --seed $3)" >&2
    rm -rf "$tour/logs"
    # shellcheck disable=SC2046  # the option and its value
    "$BIN/hl-sim-logs" --seed "$3" --out-dir "$tour/logs" $(world_opt) \
        >"$tour/sim.out" 2>"$tour/sim.err" ||
        die tour "$(lasterr "$tour/sim.err")"
    mv "$tour/logs/tour.lcmlog" "$tour/tour.lcmlog" || die tour "no tour.lcmlog written"
    rm -rf "$tour/logs"
    ;;
map)
    start=$("$BIN/hl-eval" start "$tour/tour.lcmlog" 2>"$tour/start.err") ||
        die map "$(lasterr "$tour/start.err")"
    # shellcheck disable=SC2086
    set -- $start
    [ $# -eq 3 ] || die map "hl-eval start printed '$start'"
    echo "kidnap: $what: the daemon's tour" >&2
    sets=""
    for kv in ${KIDNAP_TOUR_SET:-}; do sets="$sets --set $kv"; done
    rm -f "$tour/map.hlmap" "$tour/map.tmp.hlmap"
    # shellcheck disable=SC2086  # $sets is a list of options
    "$BIN/houghlocd" --config /dev/null $sets \
        --set "start.x_m=$1" --set "start.y_m=$2" --set "start.heading_deg=$3" \
        --fresh-map --map "$tour/map.tmp.hlmap" \
        --lcm-url "file://$(abs "$tour/tour.lcmlog")?speed=0" \
        --lcm-out "file://$(abs "$tour/out.lcmlog")?mode=w" 2>"$tour/daemon.err" ||
        die map "$(lasterr "$tour/daemon.err")"
    # How far the map is from the world: the tour's own error (hl-eval score).
    "$BIN/hl-eval" score --start "$1,$2,$3" "$tour/tour.lcmlog" "$tour/out.lcmlog" \
        >"$tour/score.txt" 2>&1 ||
        die map "hl-eval score: $(lasterr "$tour/score.txt")"
    echo "kidnap: $what: the tour's $(tail -n 1 "$tour/score.txt" | sed 's/^demo //')" >&2
    # ... and its poses, true and estimated, for judging answers in the map's own frame
    "$BIN/houghloc-eval" --tsv --tum-gt "$tour/truth.tum" --tum-est "$tour/estimate.tum" \
        "$tour/tour.lcmlog" "$tour/out.lcmlog" >"$tour/eval.txt" 2>&1 ||
        die map "houghloc-eval: $(lasterr "$tour/eval.txt")"
    mv "$tour/map.tmp.hlmap" "$tour/map.hlmap" || die map "cannot rename the map"
    ;;
sim | real)
    if [ "$cmd" = sim ]; then
        input=sonar trials=${KIDNAP_TRIALS_SIM:-200}
        world=$w
        [ "$w" = lab ] || world=$HERE/../../sim/worlds/$w.world
        src="--sim-world $world --test-log $sim/tests.lcmlog"
        for s in $tour_seeds; do
            [ -s "$sim/$s/map.hlmap" ] || die sim "no map of tour $s ($sim/$s/map.hlmap)"
            src="$src --map $sim/$s/map.hlmap"
        done
        # The compiled-in defaults, but for what tools/lab/kidnap/WORLD.conf says the world needs.
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
    if [ "$cmd" = sim ]; then
        frame=$OUT/trials/${w}_$input.map_frame
        i=0
        for s in $tour_seeds; do
            i=$((i + 1))
            line=$(sh "$HERE/map_frame.sh" "$sim/$s/truth.tum" "$sim/$s/estimate.tum" \
                   "$OUT/trials/${w}_$input.tsv" $i 2>"$frame.err") ||
                die "map frame" "$(lasterr "$frame.err")"
            echo "tour=$s $line"
        done >"$frame"
        rm -f "$frame.err"
        echo "kidnap: $what: in the maps' own frames: $(awk '{ for (i = 1; i <= NF; i++) {
            split($i, kv, "="); sum[kv[1]] += kv[2] } }
            END { printf "found %.1f %% right, %.1f %% wrong (of %d trials); with each " \
                         "map aligned to the world as a whole, %.1f %% right, %.1f %% wrong",
                  100 * sum["found_right"] / sum["trials"],
                  100 * sum["found_wrong"] / sum["trials"], sum["trials"],
                  100 * sum["aligned_right"] / sum["trials"],
                  100 * sum["aligned_wrong"] / sum["trials"] }' "$frame")" >&2
    fi
    mv "$row.tmp" "$row" || die row "cannot rename $row.tmp"
    echo "kidnap: $what: done in $(( $(date +%s) - t0 )) s" >&2
    ;;
esac
