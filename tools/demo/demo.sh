#!/bin/sh
# make demo: houghlocd on the simulated robot's recorded tour (logs/tour.lcmlog).
#
#   DEMO_MODE=batch (default)  the daemon replays the log through liblcm's file provider
#                              as fast as it can and records its output the same way
#   DEMO_MODE=live             the daemon listens on a private UDP multicast group,
#                              lcm-logplayer plays the log into it (at DEMO_SPEED, default
#                              20x) and lcm-logger records what the daemon publishes
#
# Either way the daemon starts at the first stop's true pose (as an operator places the
# robot), and hl-eval prints the error at every stop against ground truth; the last line
# is machine-readable:  demo stops=<n> rmse_mm=<x> max_mm=<y> odometry_rmse_mm=<z>
set -eu
BIN=${BUILD:-build}/bin
OUT=${BUILD:-build}/demo
LOG=${DEMO_LOG:-logs/tour.lcmlog}
MODE=${DEMO_MODE:-batch}
mkdir -p "$OUT"
case $LOG in /*) abs_log=$LOG ;; *) abs_log=$PWD/$LOG ;; esac
case $OUT in /*) abs_out=$OUT ;; *) abs_out=$PWD/$OUT ;; esac
rm -f "$OUT/houghlocd.lcmlog" "$OUT/map.hlmap"

set -- $("$BIN/hl-eval" start "$LOG")
start="--set start.x_m=$1 --set start.y_m=$2 --set start.heading_deg=$3"
echo "houghloc demo: houghlocd on $LOG ($MODE), starting at the first stop's true pose ($1 m, $2 m, $3 deg)"

case $MODE in
batch)
    # shellcheck disable=SC2086
    "$BIN/houghlocd" --config /dev/null --fresh-map --map "$OUT/map.hlmap" $start \
        --lcm-url "file://$abs_log?speed=0" --lcm-out "file://$abs_out/houghlocd.lcmlog?mode=w" \
        2>"$OUT/houghlocd.err" || { cat "$OUT/houghlocd.err" >&2; exit 1; }
    ;;
live)
    url="udpm://239.255.76.67:7671?ttl=0"
    lcm-logger -q -f --lcm-url="$url" "$OUT/houghlocd.lcmlog" &  # no -l in 1.3.1
    logger=$!
    # shellcheck disable=SC2086
    "$BIN/houghlocd" --config /dev/null --fresh-map --map "$OUT/map.hlmap" $start \
        --lcm-url "$url" 2>"$OUT/houghlocd.err" &
    daemon=$!
    sleep 1
    lcm-logplayer -s "${DEMO_SPEED:-20}" -e 'SONAR|ODOMETRY' -l "$url" "$LOG"
    sleep 1
    kill -TERM "$daemon"
    wait "$daemon" || { cat "$OUT/houghlocd.err" >&2; kill "$logger"; exit 1; }
    sleep 0.5
    kill -INT "$logger"
    wait "$logger" || true
    ;;
*)
    echo "houghloc demo: DEMO_MODE must be batch or live" >&2
    exit 2
    ;;
esac
grep -v '^<7>' "$OUT/houghlocd.err" | sed 's/^<[0-9]>/  /' || true
echo "houghloc demo: output in $OUT/houghlocd.lcmlog, map in $OUT/map.hlmap"
"$BIN/hl-eval" score "$LOG" "$OUT/houghlocd.lcmlog"
