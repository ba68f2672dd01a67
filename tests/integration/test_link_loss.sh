#!/bin/sh
# Integration test of a one-way link loss: houghloc-sim stops sending SIPs while it still
# reads and obeys commands (--mute-after: a broken receive wire, a wedged reader), in the
# middle of a destination houghloc-goto is waiting for. The robot runs without its own
# ARCOS watchdog (--watchdog 0), so that only the daemon can stop it. After robot.link's
# silence the daemon must send STOP before it closes the link: the simulator logs and
# counts the STOP it got while muted (muted_stops in its summary) and the robot stands
# still (GROUND_TRUTH); the daemon logs the loss saying the stop was sent, and houghloc-goto exits
# 5 with the destination's FAILED reply "robot link lost: no packet from the robot for N
# ms; stop sent".
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM HUP PIPE
. tests/integration/lib.sh
. tests/integration/robot_lib.sh
need_robot_programs

# A port and an LCM group of its own (test_robot.sh: 21000..21499, 8300..8799 and
# 8900..9399; test_drive.sh and test_lost.sh: theirs), so that parallel runs do not meet.
n=$(($$ % 200))
PORT=$((22600 + n))
URL="udpm://239.255.76.68:$((9400 + n))?ttl=0&recv_buf_size=4194304"
write_robot_conf "$tmp/robot.conf"

# Real time: the daemon's silence (2 s, wall clock) then lasts 2 s of robot time, so the
# robot is still under way when it is noticed. The destination is 4 m ahead: the sounding
# at the start takes the first 11 s or so, the first leg the next 6; the SIPs stop at 13 s
# of robot time, 1.5 s into that leg, and the silence is noticed at 15 s.
"$BIN/houghloc-sim" --port $PORT --speed 1 --lcm-url "$URL" --start 5.4,1.5,0 \
    --watchdog 0 --mute-after 13 2>"$tmp/sim.err" &
sim=$!; pids="$pids $sim"
wait_for "$tmp/sim.err" "listening on 127.0.0.1:$PORT" 1 50 ||
    { echo "FAIL: houghloc-sim did not listen: $(cat "$tmp/sim.err")"; exit 1; }
"$BIN/houghlocd" --config "$tmp/robot.conf" --fresh-map --map "$tmp/map.hlmap" 2>"$tmp/d.err" &
daemon=$!; pids="$pids $daemon"
check "the daemon connects to the robot" \
    wait_for "$tmp/d.err" "robot 'houghloc-sim' (Pioneer bonnie) connected" 1 100

"$BIN/houghloc-goto" --lcm-url "$URL" --timeout 30 9.4 1.5 >"$tmp/goto.out" 2>&1
rc=$?
echo "  houghloc-goto (exit $rc): $(tail -n 1 "$tmp/goto.out")"
check "houghloc-goto reports the failure (exit 5)" test $rc -eq 5
check "... FAILED: the link lost to silence, the stop sent" \
    grep -q "FAILED: robot link lost: no packet from the robot for [0-9]* ms; stop sent$" "$tmp/goto.out"
check "the simulator went silent mid-destination" grep -q "fault: no SIP goes out from now on" "$tmp/sim.err"
check "the daemon logs the loss, saying the stop was sent" \
    grep -q "robot link: no packet from the robot for [0-9]* ms; stop sent (retrying" "$tmp/d.err"
# the STOP reached the robot while it still drove, before the CLOSE and the hang-up
first_stop=$(grep -n "fault: muted: the client sent STOP" "$tmp/sim.err" | head -n 1)
speed=$(echo "$first_stop" | sed -n 's/.* at \([0-9-]*\) mm\/s and .*/\1/p')
check "the muted robot got a STOP while it was moving (${speed:-no STOP} mm/s)" \
    test "${speed:-0}" -gt 0
stop_line=${first_stop%%:*}
close_line=$(grep -n "CLOSE: the connection ends" "$tmp/sim.err" | head -n 1 | cut -d: -f1)
check "... before the CLOSE that ends the connection" \
    test -n "$stop_line" -a -n "$close_line" -a "${stop_line:-0}" -lt "${close_line:-0}"

# Muted still, the robot stands: each new connection is lost to silence in turn, every time
# with a STOP; GROUND_TRUTH (which goes on while muted) shows it still, a second apart.
check "the daemon connects to the muted robot again" \
    wait_for "$tmp/d.err" "robot 'houghloc-sim' (Pioneer bonnie) connected" 2 100
check "... and, the robot having driven on unseen, is lost until soundings find it" \
    grep -q "lost: the robot moved while its link was silent; each scan now searches" "$tmp/d.err"
pose1=$(true_pose)
sleep 1
pose2=$(true_pose)
check "the robot stands still: true pose $pose1, a second later $pose2" \
    test -n "$pose1" -a "$pose1" = "$pose2"
kill -TERM $daemon; wait $daemon
check "SIGTERM stops the daemon with exit 0" test $? -eq 0
kill -TERM $sim; wait $sim
summary=$(grep "summary:" "$tmp/sim.err")
stops=$(echo "$summary" | sed -n 's/.* muted_stops=\([0-9]*\) .*/\1/p')
mutes=$(echo "$summary" | sed -n 's/.*, mute \([0-9]*\)).*/\1/p')
echo "  simulator: mute $mutes, muted_stops $stops"
check "the simulator's summary counts the mute (1) and the STOPs it got muted (>= 1)" \
    test "${mutes:-0}" = 1 -a "${stops:-0}" -ge 1
check "the robot hit nothing" sh -c "echo '$summary' | grep -q 'collisions=0$'"
if [ $fail -ne 0 ]; then
    echo "  the daemon's log ends:"; tail -n 8 "$tmp/d.err" | sed 's/^/    /'
    echo "  the simulator's log ends:"; tail -n 8 "$tmp/sim.err" | sed 's/^/    /'
fi
exit $fail
