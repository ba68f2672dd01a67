#!/bin/sh
# Integration test of driving that can be trusted, with houghloc-sim and houghlocd on
# loopback:
#
#  - the safety stop before a wall: no map yet (robot.sound_on_connect off, a leg long
#    enough to reach the wall), a destination 50 mm from the lab's south wall: the sonar
#    stops the robot before the wall, and the destination fails "blocked", naming how far
#    the obstacle was; no stall, no contact;
#  - the safety stop before a chair leg (tests/integration/worlds/chairleg.world): the
#    sonar stops the robot, the planner takes the leg round it, the robot arrives;
#  - a straight line blocked by furniture planned round: the lab's cardboard box between
#    the robot and its destination; the way has corners (PATH), the robot arrives;
#  - STOP from houghloc-ctl, and Ctrl-C on houghloc-goto, each stop a moving robot at
#    once: its true pose stands still afterwards, and the destination is given up;
#  - a daemon whose cycle stalls (SIGSTOP) leaves the robot to ARCOS's watchdog, which
#    stops it; a daemon that exits (SIGTERM) or dies (SIGKILL) stops it too.
#
# The first three run on the lockstep clock (the same run whatever the machine's load);
# the stops run on the live clock at 10 times real time, since a stopped robot must stay
# stopped while its time goes on. Every wait is on a condition with a generous bound.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; [ -n "${KEEP:-}" ] || rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM HUP PIPE
. tests/integration/lib.sh
. tests/integration/robot_lib.sh
need_robot_programs
[ -x "$BIN/houghloc-ctl" ] || { echo "FAIL: no $BIN/houghloc-ctl (run make first)"; exit 1; }

n=$(($$ % 500))
URL="udpm://239.255.76.67:$((8400 + n))?ttl=0"
PORT=$((30000 + n * 7))

# run_robot NAME CLOCK [SIM OPTIONS...] -- [DAEMON SETTINGS...]: the simulator (CLOCK
# lockstep or live) and houghlocd on it, with a fresh map; waits until they connect.
run_robot() {
    name=$1; clock=$2; shift 2
    sim_opts="" sets=""
    while [ $# -gt 0 ] && [ "$1" != "--" ]; do sim_opts="$sim_opts $1"; shift; done
    [ $# -gt 0 ] && shift
    for kv in "$@"; do sets="$sets --set $kv"; done
    if [ "$clock" = lockstep ]; then
        sim_opts="$sim_opts --lockstep --speed 200"; sets="$sets --set robot.lockstep=true"
    else
        sim_opts="$sim_opts --speed 10"
    fi
    PORT=$((PORT + 1))
    # shellcheck disable=SC2086  # lists of options
    "$BIN/houghloc-sim" --port $PORT --lcm-url "$URL" $sim_opts 2>"$tmp/$name.sim" &
    sim=$!; pids="$pids $sim"
    wait_for "$tmp/$name.sim" "listening on" 1 100
    # shellcheck disable=SC2086
    "$BIN/houghlocd" --lcm-url "$URL" --map "$tmp/$name.hlmap" --fresh-map \
        --set robot.link=tcp:127.0.0.1:$PORT --set robot.profile=houghloc-sim \
        --set daemon.log_level=debug $sets 2>"$tmp/$name.d" &
    daemon=$!; pids="$pids $daemon"
    wait_for "$tmp/$name.d" "robot .* connected" 1 300 ||
        { echo "FAIL: $name: houghlocd did not connect: $(tail -n 3 "$tmp/$name.d")"; fail=1; }
}

stop_robot() {  # stop_robot NAME: houghlocd and the simulator, in that order
    kill -TERM $daemon 2>/dev/null; wait $daemon 2>/dev/null
    kill -TERM $sim 2>/dev/null; wait $sim 2>/dev/null
}

goto() {        # goto NAME X Y [OPTIONS...]: houghloc-goto; its exit code in $rc
    name=$1; shift
    "$BIN/houghloc-goto" --lcm-url "$URL" --timeout 30 "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"
    rc=$?
}

no_contact() {  # no_contact NAME: the simulator counted no collision, nothing stalled
    grep -q "summary:.* collisions=0$" "$tmp/$1.sim" && ! grep -q "stalled" "$tmp/$1.d"
}

# ---- the safety stop before a wall ----------------------------------------------------
run_robot wall lockstep -- robot.sound_on_connect=false drive.max_leg_mm=6000
goto wall 0 -2.0
check "wall: the destination by the wall fails (exit 5, got $rc)" test $rc -eq 5
check "wall: ... saying it is blocked and how far: $(cat "$tmp/wall.err")" \
    grep -q "FAILED: blocked: an obstacle 0\.[23][0-9] m ahead" "$tmp/wall.err"
check "wall: the sonar stopped the robot before the wall" \
    grep -q "safety stop: a sonar reading 0\.[23][0-9] m ahead" "$tmp/wall.d"
stop_robot wall
check "wall: no contact, no stall ($(grep -o 'collisions=[0-9]*' "$tmp/wall.sim"))" no_contact wall

# ---- the safety stop before a chair leg -----------------------------------------------
run_robot leg lockstep --world tests/integration/worlds/chairleg.world -- \
    robot.sound_on_connect=false
goto leg 3.2 0
check "chair leg: the robot arrives beyond it (exit $rc): $(cat "$tmp/leg.out")" test $rc -eq 0
check "chair leg: the sonar stopped the robot before it" grep -q "safety stop" "$tmp/leg.d"
check "chair leg: the way after the stop goes round it (a plan with corners)" \
    sh -c "sed -n '/safety stop/,\$p' '$tmp/leg.d' | grep -q 'planned [3-9] points'"
stop_robot leg
check "chair leg: no contact, no stall" no_contact leg

# ---- a straight line blocked by furniture ---------------------------------------------
# The lab's cardboard box (tools/sim/worlds/lab.world) lies across the straight line from
# the start to (3.2, 0.3) m: the robot's soundings show it, and the planner goes round.
run_robot box lockstep
goto box 3.2 0.3
check "box: the robot arrives behind the box (exit $rc): $(cat "$tmp/box.out")" test $rc -eq 0
check "box: the way has corners (planned round the box)" grep -q "planned [3-9] points" "$tmp/box.d"
stop_robot box
check "box: no contact, no stall" no_contact box

# ---- a daemon killed while driving: the next one's sounding completes ------------------
# While a leg is driven the robot fires its front transducers alone (the safety stop's
# POLLING), and ARCOS keeps that order after the client is gone: the next daemon must set
# the whole ring again, or its sounding on connecting waits for readings that never come.
run_robot killed live
goto killed 3.5 0.6 &
client=$!; pids="$pids $client"
wait_for "$tmp/killed.d" "state .* -> MOVING" 1 300
kill -9 $daemon; wait $daemon 2>/dev/null
kill $client 2>/dev/null; wait $client 2>/dev/null
"$BIN/houghlocd" --lcm-url "$URL" --map "$tmp/killed.hlmap" \
    --set robot.link=tcp:127.0.0.1:$PORT --set robot.profile=houghloc-sim \
    --set daemon.log_level=debug 2>"$tmp/killed2.d" &
daemon=$!; pids="$pids $daemon"
check "killed while driving: the next daemon's sounding on connecting completes" \
    wait_for "$tmp/killed2.d" "^<7>houghlocd: scan [0-9]* (seq" 1 300
check "... with no transducer left silent" sh -c "! grep -q 'gave no reading' '$tmp/killed2.d'"
stop_robot killed

# ---- a robot that falls silent while driving: the destination fails, naming why --------
run_robot mute lockstep -- robot.sound_on_connect=false
goto mute 3.5 0.6 &
client=$!; pids="$pids $client"
wait_for "$tmp/mute.d" "state .* -> MOVING" 1 300
kill -STOP $sim
wait $client
kill -CONT $sim
check "mute: the destination fails with the link's loss and its cause: $(cat "$tmp/mute.err")" \
    grep -q "FAILED: robot link lost: [a-z]" "$tmp/mute.err"
stop_robot mute

# ---- stops: STOP, Ctrl-C, a stalled daemon, a daemon that exits -----------------------
# moving NAME: waits until the robot drives; still NAME: its true pose now and half a
# second (5 s of robot time) later are the same.
moving() { wait_for "$tmp/$1.d" "state .* -> MOVING" 1 300; }
still() {
    a=$(true_pose); sleep 0.5; b=$(true_pose)
    [ -n "$a" ] && [ "$a" = "$b" ] || { echo "    (true pose $a, then $b)"; return 1; }
}

run_robot stop live
goto stop 3.5 0.6 --no-wait
check "STOP: the destination is accepted" test $rc -eq 0
check "STOP: the robot drives" moving stop
"$BIN/houghloc-ctl" --lcm-url "$URL" stop >"$tmp/ctl.out" 2>&1
check "STOP: houghloc-ctl stop is answered ACCEPTED ($(cat "$tmp/ctl.out"))" \
    grep -q "^houghloc-ctl: ACCEPTED: stopped" "$tmp/ctl.out"
check "STOP: the daemon logs it with the sender's seq" grep -q "STOP (request seq [0-9]" "$tmp/stop.d"
check "STOP: the destination is given up" grep -q "stopped by STOP" "$tmp/stop.d"
check "STOP: the robot stands still" still

# Ctrl-C on a waiting houghloc-goto sends STOP for it.
"$BIN/houghloc-goto" --lcm-url "$URL" --timeout 30 3.5 0.6 >"$tmp/int.out" 2>"$tmp/int.err" &
client=$!; pids="$pids $client"
wait_for "$tmp/stop.d" "state .* -> MOVING" 2 300
kill -INT $client; wait $client; rc=$?
check "Ctrl-C: houghloc-goto exits 130 (got $rc)" test $rc -eq 130
check "Ctrl-C: ... after sending STOP, answered" \
    sh -c "grep -q 'SIGINT: sending STOP' '$tmp/int.err' && grep -q 'ACCEPTED: stopped' '$tmp/int.out'"
check "Ctrl-C: the daemon took a second STOP" test "$(grep -c 'houghlocd: STOP (request seq' "$tmp/stop.d")" -eq 2
check "Ctrl-C: the robot stands still" still

# A stalled daemon: ARCOS's watchdog stops the robot.
goto stop 3.5 0.6 --no-wait
wait_for "$tmp/stop.d" "state .* -> MOVING" 3 300
kill -STOP $daemon
check "stall: the simulator's watchdog stops the robot" \
    wait_for "$tmp/stop.sim" "watchdog: no client packet" 1 100
check "stall: the robot stands still" still
kill -CONT $daemon

# A daemon that exits stops the robot on its way out; one killed drops the link.
wait_for "$tmp/stop.d" "destination .*: \(arrived\|robot link\|the base\|timed out\)" 1 300
goto stop 0 0 --no-wait
wait_for "$tmp/stop.d" "state .* -> MOVING" 4 300
kill -TERM $daemon; wait $daemon
check "exit: houghlocd closed the connection, which stops the robot" \
    wait_for "$tmp/stop.sim" "CLOSE: the connection ends; the robot stops" 1 50
"$BIN/houghlocd" --lcm-url "$URL" --map "$tmp/stop.hlmap" --set robot.link=tcp:127.0.0.1:$PORT \
    --set robot.profile=houghloc-sim 2>"$tmp/stop2.d" &
daemon=$!; pids="$pids $daemon"
wait_for "$tmp/stop2.d" "robot .* connected" 1 300
wait_for "$tmp/stop2.d" "state SOUNDING -> " 1 300
goto stop 3.5 0.6 --no-wait
wait_for "$tmp/stop2.d" "state .* -> MOVING" 1 300
kill -KILL $daemon; wait $daemon 2>/dev/null
# A killed client's kernel closes its socket with FIN, or with RST when SIPs were still
# unread in it (then the simulator's recv fails "Connection reset by peer"): either way
# the simulator sees the client go.
check "kill -9: the simulator saw the client go, which stops the robot" \
    wait_for "$tmp/stop.sim" \
        "\(the client disconnected\|Connection reset by peer\): connection closed; the robot is stopped" 1 50
kill -TERM $sim; wait $sim
check "stops: no contact, no stall" grep -q "summary:.* collisions=0$" "$tmp/stop.sim"

[ $fail -eq 0 ] || for f in "$tmp"/*.d; do echo "  $f:"; tail -n 8 "$f" | sed 's/^/    /'; done
exit $fail
