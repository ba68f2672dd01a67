# robot_lib.sh - what the live-robot tests share (sourced after lib.sh, POSIX sh): the
# daemon's configuration for houghloc-sim's lab, and helpers. The caller sets BIN, tmp,
# PORT (houghloc-sim's TCP port) and URL (the LCM network) first.

# write_robot_conf FILE: houghlocd on the robot at PORT, starting where tools/demo/lab.route
# starts (the south-east leg's open floor); the calibration is what hl-calibrate measures
# for the simulated transducers (as tools/demo/demo.sh).
write_robot_conf() {
    cat >"$1" <<CONF
[lcm]
url = $URL
[start]
x_m = 5.4
y_m = 1.5
heading_deg = 0
[fence]
rect = -1,-1,11,9
[robot]
link = tcp:127.0.0.1:$PORT
profile = bonnie
[calibration]
gain_q16 = 70124
offset_mm = -35
CONF
}

wait_for() {    # wait_for FILE TEXT COUNT TENTHS: until FILE has COUNT lines with TEXT
    w=0
    while c=$(grep -c -- "$2" "$1" 2>/dev/null); [ "${c:-0}" -lt "$3" ]; do
        [ $w -ge "$4" ] && return 1
        sleep 0.1; w=$((w + 1))
    done
}

start_sim() {   # start_sim NAME [OPTIONS...]: houghloc-sim on PORT at 10x real time
    name=$1; shift
    "$BIN/houghloc-sim" --port $PORT --speed 10 --lcm-url "$URL" "$@" 2>"$tmp/$name.err" &
    sim=$!; pids="$pids $sim"
    wait_for "$tmp/$name.err" "listening on 127.0.0.1:$PORT" 1 50 ||
        { echo "FAIL: houghloc-sim $name did not listen on $PORT: $(cat "$tmp/$name.err")"; fail=1; }
}

true_pose() {   # true_pose: "X,Y,DEG", the simulator's last GROUND_TRUTH (the robot stands)
    # A short recording of its own (the main log is still being written), longer if the
    # logger was too slow to hear anything.
    for t in 0.5 1 2; do
        lcm-logger -q -f -c GROUND_TRUTH --lcm-url="$URL" "$tmp/truth.lcmlog" >/dev/null 2>&1 &
        probe=$!
        sleep $t
        kill -INT $probe; wait $probe
        "$BIN/hl-eval" truth "$tmp/truth.lcmlog" >/dev/null 2>&1 && break
    done
    "$BIN/hl-eval" truth "$tmp/truth.lcmlog"
}
