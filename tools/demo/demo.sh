#!/bin/sh
# make demo: houghlocd drives the simulated robot through a scripted tour.
#
#   WORLD=lab|corridor   the building (default lab): tools/demo/$WORLD.route lists the
#                        start pose and the destinations
#   DEMO_SPEED=K         the simulated robot runs K times faster than real time (default 10)
#   DEMO_SEED=N          the simulator's noise seed (default 1)
#   DEMO_SET="k=v ..."   extra houghlocd settings (--set), for experiments
#   DEMO_CONSOLE_PORT=P  the port of the operator console (default 8047)
#
# Starts houghloc-sim (the robot, over TCP on loopback), lcm-logger and houghlocd on a
# private LCM group; sends every destination with houghloc-goto and waits for each to be
# reached, with houghloc-console serving the live map on 127.0.0.1 (its address is
# printed); stops everything (also on Ctrl-C); then scores the log: the error of every
# sounding's POSE against the simulator's GROUND_TRUTH, and draws the map with the true
# and estimated paths in build/demo/demo.png. The log stays in build/demo/demo.lcmlog and
# replays with lcm-logplayer. The last line is machine-readable:
#
#   demo stops=<n> rmse_mm=<x> max_mm=<y> odometry_rmse_mm=<z> wild_accepted=<k>
set -u
BIN=${BUILD:-build}/bin
OUT=${DEMO_OUT:-${BUILD:-build}/demo}
WORLD=${WORLD:-lab}
SPEED=${DEMO_SPEED:-10}
ROUTE=tools/demo/$WORLD.route
case $WORLD in
lab) world_opt="" fence="-1,-1,11,9" ;;
corridor) world_opt="--world tools/sim/worlds/corridor.world" fence="-2,-6,29,6" ;;
*) echo "houghloc demo: WORLD must be lab or corridor, not '$WORLD'" >&2; exit 2 ;;
esac
for p in houghlocd houghloc-sim houghloc-goto hl-eval houghloc-map; do
    [ -x "$BIN/$p" ] || { echo "houghloc demo: no $BIN/$p (run make first)" >&2; exit 1; }
done
command -v lcm-logger >/dev/null || { echo "houghloc demo: lcm-logger is missing (apt-get install liblcm-bin)" >&2; exit 1; }

# A port and a multicast group of this run's own, so that two demos or a test do not meet.
n=$(( $$ % 500 ))
PORT=$(( 20000 + n ))
URL="udpm://239.255.76.67:$(( 7700 + n ))?ttl=0"
mkdir -p "$OUT"
rm -f "$OUT/demo.lcmlog" "$OUT/map.hlmap" "$OUT/demo.png"

set -- $(sed -n 's/#.*//; s/^start //p' "$ROUTE")
[ $# -eq 3 ] || { echo "houghloc demo: $ROUTE has no 'start X Y HEADING' line" >&2; exit 1; }
sx=$1 sy=$2 sh=$3
cat >"$OUT/houghlocd.conf" <<EOF
; written by tools/demo/demo.sh for this run
[lcm]
url = $URL
[daemon]
map_file = $OUT/map.hlmap
[start]
x_m = $sx
y_m = $sy
heading_deg = $sh
[fence]
rect = $fence
[robot]
link = tcp:127.0.0.1:$PORT
profile = bonnie
[calibration]
; what hl-calibrate --simulate measures for the simulated transducers
gain_q16 = 70124
offset_mm = -35
EOF

pids="" client="" console=""
cleanup() {
    for p in $client $pids; do kill -TERM "$p" 2>/dev/null; done
    for p in $client $pids; do wait "$p" 2>/dev/null; done
    pids="" client=""
}
trap 'cleanup; exit 130' INT TERM
trap cleanup EXIT

echo "houghloc demo: $WORLD, robot at ${DEMO_SPEED:-10}x real time, log $OUT/demo.lcmlog"
# shellcheck disable=SC2086
"$BIN/houghloc-sim" --port "$PORT" --speed "$SPEED" --seed "${DEMO_SEED:-1}" --start "$sx,$sy,$sh" $world_opt \
    --lcm-url "$URL" 2>"$OUT/houghloc-sim.err" &
sim=$!
lcm-logger -q -f --lcm-url="$URL" "$OUT/demo.lcmlog" &  # 1.3.1 has no -l
logger=$!
sets=""
for kv in ${DEMO_SET:-}; do sets="$sets --set $kv"; done
# shellcheck disable=SC2086
"$BIN/houghlocd" --config "$OUT/houghlocd.conf" --fresh-map $sets 2>"$OUT/houghlocd.err" &
daemon=$!
pids="$daemon $sim $logger"
# The operator console on the run's LCM group, to watch the robot map the lab.
CPORT=${DEMO_CONSOLE_PORT:-8047}
if [ -x "$BIN/houghloc-console" ]; then
    "$BIN/houghloc-console" --lcm-url "$URL" --listen "127.0.0.1:$CPORT" --ground-truth \
        2>"$OUT/houghloc-console.err" &
    console=$!
    pids="$pids $console"
    w=0
    while ! grep -q "serving" "$OUT/houghloc-console.err" 2>/dev/null && [ $w -lt 30 ]; do sleep 0.1; w=$((w + 1)); done
    if grep -q "serving" "$OUT/houghloc-console.err"; then
        echo "houghloc demo: console at http://127.0.0.1:$CPORT/"
    else
        echo "houghloc demo: no console: $(tail -n 1 "$OUT/houghloc-console.err")" >&2
    fi
fi

# The first destination waits until the robot is connected and the first sounding is made.
waited=0
until grep -q "robot .* connected" "$OUT/houghlocd.err" 2>/dev/null; do
    kill -0 "$daemon" 2>/dev/null || { echo "houghloc demo: houghlocd stopped:" >&2; tail -n 3 "$OUT/houghlocd.err" >&2; exit 1; }
    waited=$((waited + 1))
    [ $waited -le 150 ] || { echo "houghloc demo: the robot did not connect in 15 s" >&2; exit 1; }
    sleep 0.1
done

failed=0 i=0
grep -v '^#\|^start\|^ *$' "$ROUTE" >"$OUT/route"
while read -r x y h; do
    i=$((i + 1))
    tries=0
    while :; do
        # in the background, so that a signal interrupts the wait and the trap runs at once
        # shellcheck disable=SC2086
        "$BIN/houghloc-goto" --lcm-url "$URL" --timeout 120 "$x" "$y" $h >"$OUT/goto.out" 2>&1 &
        client=$!
        wait "$client"
        rc=$?
        client=""
        # 4: the robot link is not up yet (the daemon is starting): ask again
        [ $rc -eq 4 ] && [ $tries -lt 100 ] || break
        tries=$((tries + 1))
        sleep 0.2
    done
    if [ $rc -eq 0 ]; then
        echo "  destination $i ($x, $y): $(sed -n 's/.*ARRIVED: //p' "$OUT/goto.out")"
    else
        echo "  destination $i ($x, $y): FAILED (houghloc-goto exit $rc): $(tail -n 1 "$OUT/goto.out")"
        failed=$((failed + 1))
    fi
done <"$OUT/route"

kill -TERM "$daemon"
wait "$daemon"
daemon_rc=$?
kill -TERM "$sim"
wait "$sim"
sleep 0.3
kill -INT "$logger"
wait "$logger"
[ -n "$console" ] && { kill -TERM "$console"; wait "$console"; }
pids=""
[ $daemon_rc -eq 0 ] || { echo "houghloc demo: houghlocd exited $daemon_rc:" >&2; tail -n 5 "$OUT/houghlocd.err" >&2; exit 1; }
[ $failed -eq 0 ] || echo "houghloc demo: $failed of $i destinations failed" >&2

"$BIN/houghloc-map" --trajectory "$OUT/demo.lcmlog" "$OUT/demo.lcmlog" "$OUT/demo" >/dev/null ||
    echo "houghloc demo: no picture" >&2
echo "houghloc demo: picture $OUT/demo.png, map $OUT/map.hlmap; errors at every sounding:"
"$BIN/hl-eval" live "$OUT/demo.lcmlog"
