#!/bin/sh
# run_one.sh - one cell of `make eval-real` (tools/lab/realeval/realeval.mk, docs/results/real-buildings.md).
#
#   run_one.sh import BUILDING INPUT SELECTION
#       houghloc-import-carmen: DATA/raw/BUILDING-raw.log.gz and its ground truth to
#       EVAL_OUT/input/BUILDING_INPUT_SELECTION.lcmlog (cached: made once, shared by the
#       modes; written under a temporary name and renamed, so it is whole or absent)
#   run_one.sh cell BUILDING INPUT SELECTION MODE [START]
#       imports if the import is missing, then for MODE odometry scores the odometry
#       alone (houghloc-eval --odometry); for MODE paper, improved or loops replays the
#       import through houghlocd's batch path (tools/lab/realeval/INPUT.conf for improved,
#       INPUT-paper.conf for paper, INPUT-loops.conf for loops: the improved mode with
#       loop closure) from START and scores its POSE; writes the row
#       EVAL_OUT/rows/BUILDING_INPUT_MODE_SELECTION_START.tsv
#   run_one.sh map BUILDING [INPUT]
#       draws EVAL_OUT/BUILDING.png (INPUT laser, the default) or BUILDING-sonar.png: the
#       final map of the INPUT, improved, every, origin run with its POSE path and the
#       true path moved into the estimate's frame by the ATE's alignment (houghloc-map
#       --start; the daemon never sees the truth)
#
# INPUT is laser or sonar, SELECTION every or moved, MODE odometry, paper, improved or
# loops.
# START (default origin) is where the daemon's map frame begins:
#   origin     the robot's own start frame: no start pose given, the daemon's default
#              (0, 0, 0), as a robot runs it
#   turned30   the same frame turned 30 degrees: --set start.heading_deg=30 at 0, 0
#   turned45   likewise 45 degrees
#   truth      the first true pose of the log (building's axes), for reference only: the
#              one start that takes anything from the ground truth
# Turning the start heading is a change of frame for the daemon: it predicts from the
# odometry's motion between scans in the robot's own frame (hl_pose_between), so turning
# the log's odometry about its first pose would change nothing it sees but roundings;
# the start heading turns the map frame, hence the building's walls against the vote
# raster's and the map's axes. The odometry row is scored after a rigid alignment of the
# whole path, which no start changes: it has the one row, START origin.
# Environment: BUILD (default build: programs in BUILD/bin), DATA (default
# ../shared/data), EVAL_OUT (default BUILD/eval).
#
# A row is the tab-separated cells of real.tsv's columns (report.sh writes the header):
#   dataset input mode selection scans ate_rmse_m rpe_trans_rmse_m rpe_trans_mean_m
#   max_err_m ms_per_scan wall_ms_per_scan rejected start
# `-` where a cell does not apply (odometry has no times and rejects nothing; an RPE
# that houghloc-eval reports as nan, a run shorter than one 1 m segment).
#
# Progress goes to stderr. Any failing step stops with one line
#   eval-real: BUILDING INPUT SELECTION MODE START: STEP failed: REASON
# and exit status 1 (2 for bad usage), leaving no row file.
set -u

BUILD=${BUILD:-build}
BIN=$BUILD/bin
DATA=${DATA:-../shared/data}
EVAL_OUT=${EVAL_OUT:-$BUILD/eval}
HERE=$(dirname "$0")

usage() {
    echo "usage: run_one.sh import BUILDING INPUT SELECTION" >&2
    echo "       run_one.sh cell BUILDING INPUT SELECTION MODE [origin|turned30|turned45|truth]" >&2
    echo "       run_one.sh map BUILDING [laser|sonar]" >&2
    exit 2
}

what=""
die() {     # die STEP REASON: the one line, exit 1
    echo "eval-real: $what: $1 failed: $2" >&2
    exit 1
}

abs() {     # abs PATH: PATH made absolute (liblcm's file:// URLs need it)
    case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac
}

now_ms() {  # wall clock in milliseconds (GNU date)
    t=$(date +%s%N) && case $t in *[!0-9]*) return 1 ;; esac && echo $((t / 1000000))
}

field() {   # field FILE KEY: the value after " KEY=" in a key=value line
    tr ' ' '\n' <"$1" | sed -n "s/^$2=//p" | head -n 1
}

lasterr() { # lasterr FILE: its last line that is not a syslog info/debug line, for die
    l=$(grep -v '^<[67]>' "$1" 2>/dev/null | tail -n 1)
    [ -n "$l" ] || l=$(tail -n 1 "$1" 2>/dev/null)
    echo "$l" | sed 's/^<[0-7]>//'
}

# first_pose TUM: the first pose of a TUM file as "X_M Y_M HEADING_DEG" (the heading
# from the planar quaternion; 4 decimals, finer than the daemon's 1/65536 turn).
first_pose() {
    awk 'NF >= 8 && $1 !~ /^#/ {
            printf "%.3f %.3f %.4f\n", $2, $3, atan2($7, $8) * 360 / atan2(0, -1); f = 1; exit
         }
         END { exit !f }' "$1"
}

# ---- map -----------------------------------------------------------------------------
# The ATE's alignment A (estimate -> truth: rotation by angle, then + t) read from
# houghloc-eval; houghloc-map lays the truth's first pose F on its --start S, so the truth
# T is drawn at S (+) F^-1 (+) T; S = A^-1 (+) F draws it at A^-1 (+) T, in the estimate's
# frame as the ATE compares them.
do_map() {
    cell=${b}_${input}_improved_every_origin
    run=$EVAL_OUT/runs/$cell
    in_log=$EVAL_OUT/input/${b}_${input}_every.lcmlog
    "$BIN/houghloc-eval" --tum-gt "$run/truth.tum" "$in_log" "$run/out.lcmlog" \
        >"$run/align.txt" 2>"$run/align.err" || die align "$(lasterr "$run/align.err")"
    first=$(first_pose "$run/truth.tum") || die align "no pose in $run/truth.tum"
    start=$(awk -v f="$first" '
        /^alignment / {
            a = $3 * atan2(0, -1) / 180
            t = $0; sub(/.*\(/, "", t); sub(/\).*/, "", t); split(t, xy, ", *")
            split(f, p, " "); c = cos(a); s = sin(a)
            dx = p[1] - xy[1]; dy = p[2] - xy[2]
            printf "%.4f,%.4f,%.4f\n", c * dx + s * dy, -s * dx + c * dy, p[3] - $3; ok = 1
        }
        END { exit !ok }' "$run/align.txt") || die align "no alignment line in $run/align.txt"
    "$BIN/houghloc-map" --start "$start" --trajectory "$run/out.lcmlog" \
        --trajectory "$in_log" "$run/map.hlmap" "$run/map" >"$run/map.err" 2>&1 ||
        die map "$(lasterr "$run/map.err")"
    png=$EVAL_OUT/$b.png
    [ "$input" = laser ] || png=$EVAL_OUT/$b-$input.png
    cp "$run/map.png" "$png" || die map "cannot copy $run/map.png"
}

[ $# -ge 2 ] || usage
cmd=$1 b=$2
if [ "$cmd" = map ]; then
    [ $# -eq 2 ] || [ $# -eq 3 ] || usage
    input=${3:-laser}
    case $input in laser | sonar) ;; *) usage ;; esac
    what="$b $input every improved origin"
    do_map
    exit 0
fi
[ $# -ge 4 ] || usage
input=$3 sel=$4 mode="" start=""
case $input in laser | sonar) ;; *) usage ;; esac
case $sel in every | moved) ;; *) usage ;; esac
case $cmd in
import) [ $# -eq 4 ] || usage ;;
cell) [ $# -eq 5 ] || [ $# -eq 6 ] || usage
    mode=$5 start=${6:-origin}
    case $mode in odometry | paper | improved | loops) ;; *) usage ;; esac
    case $start in origin | turned30 | turned45 | truth) ;; *) usage ;; esac
    [ "$mode" != odometry ] || [ "$start" = origin ] || usage ;;
*) usage ;;
esac
what="$b $input $sel${mode:+ $mode}${start:+ $start}"

in_log=$EVAL_OUT/input/${b}_${input}_${sel}.lcmlog

# ---- import --------------------------------------------------------------------------
do_import() {
    raw=$DATA/raw/$b-raw.log.gz
    gt=$DATA/raw/$b-groundtruth.tum
    [ -r "$raw" ] || die import "no $raw"
    [ -r "$gt" ] || die import "no $gt"
    mkdir -p "$EVAL_OUT/input" || die import "cannot create $EVAL_OUT/input"
    tmp_log=$in_log.tmp.$$
    echo "eval-real: $b $input $sel: importing" >&2
    if ! "$BIN/houghloc-import-carmen" --input "$input" --select "$sel" --truth "$gt" \
        "$raw" "$tmp_log" 2>"$in_log.sum"; then
        rm -f "$tmp_log"
        die import "$(lasterr "$in_log.sum")"
    fi
    mv "$tmp_log" "$in_log" || die import "cannot rename $tmp_log"
}

if [ "$cmd" = import ]; then
    do_import
    exit 0
fi
[ -s "$in_log" ] || do_import
# The importer's count of scans written: every scored row must cover all of them.
want_scans=$(sed -n 's/.*: wrote .*: scans=\([0-9]*\) .*/\1/p' "$in_log.sum" 2>/dev/null)

# ---- replay and score ----------------------------------------------------------------
cell=${b}_${input}_${mode}_${sel}_${start}
run=$EVAL_OUT/runs/$cell
row=$EVAL_OUT/rows/$cell.tsv
mkdir -p "$run" "$EVAL_OUT/rows" || die setup "cannot create $run"
rm -f "$row"
echo "eval-real: $what: running" >&2

score=$run/score.txt
ms="-" wall="-" rejected="-"
if [ "$mode" = odometry ]; then
    "$BIN/houghloc-eval" --odometry --tsv "$in_log" >"$score" 2>"$run/score.err" ||
        die score "$(lasterr "$run/score.err")"
    secs=""
else
    conf=$HERE/$input.conf          # the improved mode
    [ "$mode" = paper ] && conf=$HERE/$input-paper.conf
    [ "$mode" = loops ] && conf=$HERE/$input-loops.conf
    [ -r "$conf" ] || die replay "no $conf"
    # The start pose (none for origin: the daemon's default).
    case $start in
    origin) set -- ;;
    turned30) set -- --set start.heading_deg=30 ;;
    turned45) set -- --set start.heading_deg=45 ;;
    truth)
        "$BIN/houghloc-eval" --odometry --tsv --tum-gt "$run/truth.tum" "$in_log" \
            >/dev/null 2>"$run/start.err" || die start "$(lasterr "$run/start.err")"
        pose=$(first_pose "$run/truth.tum") || die start "no pose in $run/truth.tum"
        # shellcheck disable=SC2086
        set -- $pose
        set -- --set "start.x_m=$1" --set "start.y_m=$2" --set "start.heading_deg=$3" ;;
    esac
    out=$run/out.lcmlog
    rm -f "$out" "$run/map.hlmap"
    t0=$(now_ms) || die replay "date +%s%N does not give nanoseconds"
    # The window of the compute-time median covers every scan (the longest building has
    # 4791), so STATUS's median is over the whole run.
    "$BIN/houghlocd" --config "$conf" --set daemon.compute_window=10000 "$@" \
        --fresh-map --map "$run/map.hlmap" \
        --lcm-url "file://$(abs "$in_log")?speed=0" \
        --lcm-out "file://$(abs "$out")?mode=w" 2>"$run/daemon.err" ||
        die replay "$(lasterr "$run/daemon.err")"
    t1=$(now_ms) || die replay "date"
    "$BIN/hl-eval" status "$out" >"$run/status.txt" 2>"$run/status.err" ||
        die status "$(lasterr "$run/status.err")"
    "$BIN/houghloc-eval" --tsv "$in_log" "$out" >"$score" 2>"$run/score.err" ||
        die score "$(lasterr "$run/score.err")"
    status_scans=$(field "$run/status.txt" scans)
    samples=$(field "$run/status.txt" compute_samples)
    median_us=$(field "$run/status.txt" compute_median_us)
    case $median_us in '' | *[!0-9]*) die status "no compute_median_us in the last STATUS" ;; esac
    [ "$samples" = "$status_scans" ] ||
        echo "eval-real: $what: warning: the compute median covers $samples of $status_scans scans" >&2
    ms=$(awk -v u="$median_us" 'BEGIN { printf "%.3f", u / 1000 }')
    rejected=$(field "$score" rejected_wild)
    case $rejected in '' | *[!0-9]*) die score "no rejected_wild in houghloc-eval's line" ;; esac
    secs=$(awk -v a="$t0" -v z="$t1" 'BEGIN { printf "%.1f", (z - a) / 1000 }')
fi

scans=$(field "$score" scans)
case $scans in '' | *[!0-9]*) die score "no scans= in houghloc-eval's line" ;; esac
[ "$scans" -gt 0 ] || die score "no scan scored"
if [ -n "$want_scans" ] && [ "$scans" != "$want_scans" ]; then
    # The daemon refuses a sensor stream's messages at a step of its clock until the new
    # clock holds (csail's log jumps 10,000 s): those scans have no POSE. Scored without
    # them, said on stderr; any other shortfall is a fault.
    bad=$(field "$run/status.txt" bad_messages 2>/dev/null)
    if [ "$mode" = odometry ] || [ "$scans" -gt "$want_scans" ] ||
        [ "${bad:-0}" -lt $((want_scans - scans)) ]; then
        die score "$scans scans scored of the $want_scans imported (see $run/score.err)"
    fi
    echo "eval-real: $what: warning: $((want_scans - scans)) of the $want_scans imported scans have no POSE (the daemon refused $bad messages: $run/daemon.err)" >&2
fi
if [ "$mode" != odometry ]; then
    [ "$status_scans" = "$scans" ] ||
        die status "STATUS counts $status_scans scans, houghloc-eval scored $scans"
    wall=$(awk -v a="$t0" -v z="$t1" -v n="$scans" 'BEGIN { printf "%.3f", (z - a) / n }')
fi

# The row: houghloc-eval's figures as printed (6 decimals), nan as `-`.
tmp_row=$row.tmp.$$
awk -v b="$b" -v i="$input" -v m="$mode" -v s="$sel" -v n="$scans" -v ms="$ms" \
    -v wall="$wall" -v rej="$rejected" -v st="$start" '
    { for (k = 1; k <= NF; k++) { split($k, kv, "="); v[kv[1]] = kv[2] } }
    function cell(key,   x) {
        x = v[key]
        if (x == "" ) { bad = key; return "" }
        if (x ~ /^(-?nan|-?inf)$/) return "-"
        if (x !~ /^[0-9]+(\.[0-9]+)?$/) { bad = key; return "" }
        return x
    }
    END {
        line = b "\t" i "\t" m "\t" s "\t" n
        line = line "\t" cell("ate_rmse_m") "\t" cell("rpe_trans_rmse_m")
        line = line "\t" cell("rpe_trans_mean_m") "\t" cell("max_err_m")
        line = line "\t" ms "\t" wall "\t" rej "\t" st
        if (bad != "") { print "no number for " bad > "/dev/stderr"; exit 1 }
        print line
    }' "$score" >"$tmp_row" 2>"$run/row.err" || {
    rm -f "$tmp_row"
    die score "houghloc-eval's line: $(lasterr "$run/row.err")"
}
mv "$tmp_row" "$row" || die row "cannot rename $tmp_row"

done_rows=$(find "$EVAL_OUT/rows" -name '*.tsv' | wc -l)
ate=$(field "$score" ate_rmse_m)
echo "eval-real: $what: done, ATE $ate m, $scans scans${secs:+ in $secs s} ($done_rows${REALEVAL_TOTAL:+ of $REALEVAL_TOTAL} rows)" >&2
