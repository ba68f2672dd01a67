#!/bin/sh
# make demo: houghlocd drives the simulated robot through a scripted tour, started and
# driven exactly as a user does it (README, "Quick start"), every setting on the command
# lines it prints.
#
#   WORLD=lab|corridor   the building (default lab): tools/demo/$WORLD.route lists where
#                        the robot is set down and the destinations
#   DEMO_SPEED=K         the simulated robot runs at most K times faster than real time
#                        (default 10; the run is the same at any K)
#   DEMO_SEED=N          the simulator's noise seed (default 1)
#   DEMO_SET="k=v ..."   extra houghlocd settings (--set), for experiments
#   DEMO_CONSOLE_PORT=P  the port of the operator console (default 8047)
#
# houghloc-sim (the robot, over TCP on loopback), lcm-logger, houghloc-console and
# houghlocd on an LCM group of this run's own; the daemon gets only its link, its robot
# profile, a map file of the demo's own (fresh) and that LCM group, so its map frame is
# where the robot is set down (the default start pose, the origin). The simulator and the
# daemon share a lockstep clock (houghloc-sim --lockstep, robot.lockstep): the robot's
# time moves on only as the daemon deals with each of its packets, so a run is the same,
# pose for pose, on an idle machine and on a busy one. Each destination goes
# to houghloc-goto with its default timeout, which follows the robot's progress. Then it
# stops everything (also on Ctrl-C) and scores the log: the error of every sounding's
# POSE against the simulator's GROUND_TRUTH, moved into the map frame (the first true
# pose is the start pose), and draws the map with the true and estimated paths in
# $OUT/demo.png. The log stays in $OUT/demo.lcmlog and replays with lcm-logplayer.
# The target: every destination reached, rmse_mm <= 50, odometry_rmse_mm at least 5 times
# rmse_mm, wild_accepted = 0, collisions = 0 (the simulator's count of the robot's body
# touching a surface; blocked counts the daemon's safety stops, which are no fault). The
# last line is machine-readable:
#
#   demo stops=<n> rmse_mm=<x> max_mm=<y> odometry_rmse_mm=<z> wild_accepted=<k> collisions=<n> blocked=<n> result=PASS|MISS
#
# Exit status 0 when the run was made and scored (PASS or MISS), 1 when it could not be.
set -u
BIN=${BUILD:-build}/bin
OUT=${DEMO_OUT:-${BUILD:-build}/demo}
WORLD=${WORLD:-lab}
SPEED=${DEMO_SPEED:-10}
SEED=${DEMO_SEED:-1}
ROUTE=tools/demo/$WORLD.route
case $WORLD in
lab) world_opt="" ;;
corridor) world_opt="--world tools/sim/worlds/corridor.world" ;;
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

# Where the simulator sets the robot down (its world's frame) and the daemon's fence.
set -- $(sed -n 's/#.*//; s/^start //p' "$ROUTE")
[ $# -eq 3 ] || { echo "houghloc demo: $ROUTE has no 'start X Y HEADING' line" >&2; exit 1; }
sx=$1 sy=$2 sh=$3
fence=$(sed -n 's/#.*//; s/^fence  *\([^ ]*\).*/\1/p' "$ROUTE")
# The destinations in the map frame: the route draws them in the building's frame, and the
# daemon's map frame is the start pose's, so each (X, Y, HEADING) becomes start^-1 (+) it.
grep -v '^ *#\|^start\|^fence\|^ *$' "$ROUTE" | sed 's/#.*//' |
    awk -v sx="$sx" -v sy="$sy" -v sh="$sh" '
        BEGIN { r = sh * atan2(0, -1) / 180; c = cos(r); s = sin(r) }
        NF >= 2 {
            dx = $1 - sx; dy = $2 - sy
            line = sprintf("%.3f %.3f", c * dx + s * dy, -s * dx + c * dy)
            if (NF >= 3) { h = ($3 - sh) % 360; line = line sprintf(" %.1f", h) }
            print line, "#", $1, $2
        }' >"$OUT/route"

# The robot profile houghloc-sim: bonnie's ring with the calibration hl-calibrate measures
# for the simulated transducers.
sets="--set robot.link=tcp:127.0.0.1:$PORT --set robot.profile=houghloc-sim --set robot.lockstep=true"
[ -n "$fence" ] && sets="$sets --set fence.rect=$fence"
for kv in ${DEMO_SET:-}; do sets="$sets --set $kv"; done

pids="" client="" console=""
cleanup() {
    for p in $client $pids; do kill -TERM "$p" 2>/dev/null; done
    for p in $client $pids; do wait "$p" 2>/dev/null; done
    pids="" client=""
}
trap 'cleanup; exit 130' INT TERM
trap cleanup EXIT
show() { echo "  \$ $*"; }   # a command as the user would type it

echo "houghloc demo: $WORLD, robot at ${SPEED}x real time, log $OUT/demo.lcmlog; the commands:"
# The logger and the console first: they must hear the robot's first true pose, which the
# simulator sends once the daemon connects (the map frame's anchor, truth_frame.h).
show lcm-logger -q -f --lcm-url="'$URL'" "$OUT/demo.lcmlog" "&"
lcm-logger -q -f --lcm-url="$URL" "$OUT/demo.lcmlog" &  # 1.3.1 has no -l
logger=$!
pids="$logger"
# The operator console on the run's LCM group, to watch the robot map the lab.
CPORT=${DEMO_CONSOLE_PORT:-8047}
if [ -x "$BIN/houghloc-console" ]; then
    show "$BIN/houghloc-console" --lcm-url "'$URL'" --listen "127.0.0.1:$CPORT" --ground-truth "&"
    "$BIN/houghloc-console" --lcm-url "$URL" --listen "127.0.0.1:$CPORT" --ground-truth \
        2>"$OUT/houghloc-console.err" &
    console=$!
    pids="$pids $console"
    w=0
    while ! grep -q "serving" "$OUT/houghloc-console.err" 2>/dev/null && [ $w -lt 30 ]; do sleep 0.1; w=$((w + 1)); done
    if grep -q "serving" "$OUT/houghloc-console.err"; then
        # the address with the console's token: it signs the page in (a cookie)
        echo "houghloc demo: console at $(sed -n 's/.* serving \(http:[^ ]*\) .*/\1/p' "$OUT/houghloc-console.err")"
    else
        echo "houghloc demo: no console: $(tail -n 1 "$OUT/houghloc-console.err")" >&2
    fi
fi
w=0
while [ ! -e "$OUT/demo.lcmlog" ] && [ $w -lt 50 ]; do sleep 0.1; w=$((w + 1)); done
sleep 0.2   # lcm-logger subscribes just after it creates its file

show "$BIN/houghloc-sim" --lockstep --port "$PORT" --speed "$SPEED" --seed "$SEED" --start "$sx,$sy,$sh" $world_opt --lcm-url "'$URL'" "&"
# shellcheck disable=SC2086
"$BIN/houghloc-sim" --lockstep --port "$PORT" --speed "$SPEED" --seed "$SEED" --start "$sx,$sy,$sh" \
    $world_opt --lcm-url "$URL" 2>"$OUT/houghloc-sim.err" &
sim=$!
show "$BIN/houghlocd" --lcm-url "'$URL'" --map "$OUT/map.hlmap" --fresh-map $sets "&"
# shellcheck disable=SC2086
"$BIN/houghlocd" --lcm-url "$URL" --map "$OUT/map.hlmap" --fresh-map $sets 2>"$OUT/houghlocd.err" &
daemon=$!
pids="$daemon $sim $pids"

# The first destination waits until the robot is connected.
waited=0
until grep -q "robot .* connected" "$OUT/houghlocd.err" 2>/dev/null; do
    kill -0 "$daemon" 2>/dev/null || { echo "houghloc demo: houghlocd stopped:" >&2; tail -n 3 "$OUT/houghlocd.err" >&2; exit 1; }
    waited=$((waited + 1))
    [ $waited -le 150 ] || { echo "houghloc demo: the robot did not connect in 15 s" >&2; exit 1; }
    sleep 0.1
done

failed=0 i=0
while read -r x y rest; do
    i=$((i + 1))
    h=${rest%%#*}
    world=${rest#*# }
    show "$BIN/houghloc-goto" --lcm-url "'$URL'" "$x" "$y" $h "  # the building's ($(echo $world | tr ' ' ,))"
    # in the background, so that a signal interrupts the wait and the trap runs at once
    # shellcheck disable=SC2086
    "$BIN/houghloc-goto" --lcm-url "$URL" "$x" "$y" $h >"$OUT/goto.out" 2>&1 &
    client=$!
    wait "$client"
    rc=$?
    client=""
    if [ $rc -eq 0 ]; then
        echo "    destination $i: $(sed -n 's/.*ARRIVED: //p' "$OUT/goto.out")"
    else
        echo "    destination $i: FAILED (houghloc-goto exit $rc): $(tail -n 1 "$OUT/goto.out")"
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
echo "houghloc demo: picture $OUT/demo.png, map $OUT/map.hlmap; errors at every sounding" \
     "(truth in the map frame):"
"$BIN/hl-eval" live "$OUT/demo.lcmlog" >"$OUT/score.txt" || { cat "$OUT/score.txt"; exit 1; }
sed '$d' "$OUT/score.txt"
# The simulator's count of contacts (its summary line at exit), the daemon's safety stops.
collisions=$(sed -n 's/.*summary:.* collisions=\([0-9]*\).*/\1/p' "$OUT/houghloc-sim.err" | tail -n 1)
[ -n "$collisions" ] || { echo "houghloc demo: houghloc-sim printed no collision count" >&2; exit 1; }
blocked=$(grep -c "safety stop" "$OUT/houghlocd.err")
last="$(tail -n 1 "$OUT/score.txt") collisions=$collisions blocked=$blocked"
verdict=$(echo "$last" | tr ' ' '\n' | awk -F= -v failed="$failed" '
    { v[$1] = $2 }
    END {
        ok = failed == 0 && v["rmse_mm"] <= 50 && v["odometry_rmse_mm"] >= 5 * v["rmse_mm"] &&
             v["wild_accepted"] == 0 && v["collisions"] == 0
        print ok ? "PASS" : "MISS"
    }')
echo "houghloc demo: target: every destination reached ($((i - failed)) of $i), rmse_mm <= 50," \
     "odometry_rmse_mm >= 5 x rmse_mm, wild_accepted = 0, collisions = 0: $verdict"
echo "$last result=$verdict"
# A MISS is a measurement, not a failure of the run: the exit status is 0 either way (1
# only when the run itself could not be made or scored, above).
