# robot_lib.sh - what the live-robot tests share (sourced after lib.sh, POSIX sh): the
# daemon's configuration for houghloc-sim's lab, and helpers. The caller sets BIN, tmp,
# PORT (houghloc-sim's TCP port) and URL (the LCM network) before calling them.

# need_robot_programs: fails the test unless the programs it runs are there.
need_robot_programs() {
    for p in houghlocd houghloc-sim houghloc-goto hl-eval; do
        [ -x "$BIN/$p" ] || { echo "FAIL: no $BIN/$p (run make first)"; exit 1; }
    done
    command -v lcm-logger >/dev/null || { echo "FAIL: lcm-logger is missing (liblcm-bin)"; exit 1; }
}

# write_robot_conf FILE: houghlocd on the robot at PORT, starting where tools/demo/lab.route
# starts (the south-east leg's open floor), ROBOT_START: the map frame is the lab's, so
# that tests name places and true poses in one frame (hl-eval live --start "$ROBOT_START").
. tools/houghloc-sim/daemon_conf.sh
ROBOT_START=5.4,1.5,0
write_robot_conf() {
    write_lab_robot_conf "$1" 5.4 1.5 0
}

wait_for() {    # wait_for FILE TEXT COUNT TENTHS: until FILE has COUNT lines with TEXT
    w=0
    while c=$(grep -c -- "$2" "$1" 2>/dev/null); [ "${c:-0}" -lt "$3" ]; do
        [ $w -ge "$4" ] && return 1
        sleep 0.1; w=$((w + 1))
    done
}

# start_sim NAME [OPTIONS...]: houghloc-sim on PORT, with SIM_CLOCK's options (default
# 10x real time; a lockstep test sets "--lockstep --speed N" and robot.lockstep=true)
start_sim() {
    name=$1; shift
    # shellcheck disable=SC2086  # a list of options
    "$BIN/houghloc-sim" --port $PORT ${SIM_CLOCK:---speed 10} --lcm-url "$URL" "$@" 2>"$tmp/$name.err" &
    sim=$!; pids="$pids $sim"
    wait_for "$tmp/$name.err" "listening on 127.0.0.1:$PORT" 1 50 ||
        { echo "FAIL: houghloc-sim $name did not listen on $PORT: $(cat "$tmp/$name.err")"; fail=1; }
}

true_pose() {   # true_pose [LOG]: "X,Y,DEG", the simulator's last GROUND_TRUTH (the robot stands)
    if [ $# -gt 0 ]; then
        # The lockstep clock is held while the robot stands, so nothing new is published:
        # the last GROUND_TRUTH is in LOG, which lcm-logger is still writing (flushed every
        # 100 ms); a copy that ends inside an event is read again a little later.
        for t in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
            cp "$1" "$tmp/truth.lcmlog"
            "$BIN/hl-eval" truth "$tmp/truth.lcmlog" 2>/dev/null && return 0
            sleep 0.25
        done
    else
        # A short recording of its own (the main log is still being written), longer if
        # the logger was too slow to hear anything.
        for t in 0.5 1 2; do
            lcm-logger -q -f -c GROUND_TRUTH --lcm-url="$URL" "$tmp/truth.lcmlog" >/dev/null 2>&1 &
            probe=$!
            sleep $t
            kill -INT $probe; wait $probe
            "$BIN/hl-eval" truth "$tmp/truth.lcmlog" >/dev/null 2>&1 && break
        done
    fi
    "$BIN/hl-eval" truth "$tmp/truth.lcmlog"
}
