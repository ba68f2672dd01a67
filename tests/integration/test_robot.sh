#!/bin/sh
# Integration test of houghlocd driving a robot (the live-robot issue): houghloc-sim over
# TCP on loopback, recorded by lcm-logger. The daemon starts before the robot listens and
# must retry until it connects; three destinations near the start are reached with every
# sounding's position error below 100 mm against the simulator's GROUND_TRUTH; the
# simulator is killed with SIGKILL and restarted at the robot's true pose, and the daemon
# reconnects and continues with its map; a simulator that injects garbage and corrupt
# checksums still gets the robot to its destination while STATUS counts the bad packets;
# the serial transport's errors (missing device, no permission, bad baud rate) and a
# refused TCP address are clear and never fatal at run time; and a batch replay of the
# live log, and lcm-logplayer playing it into a daemon, give the live run's POSE stream
# byte for byte. Every check names what it tests.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
pids=""
nobody_dir=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp" $nobody_dir' EXIT
# a signal (Ctrl-C, a closed pipe) ends the script through the EXIT trap, which stops its
# daemon, simulator and logger
trap 'exit 130' INT TERM HUP PIPE
. tests/integration/lib.sh
. tests/integration/robot_lib.sh
need_robot_programs

# A TCP port and an LCM group of this run's own, away from those of test_daemon.sh
# (7700..7899) and make demo (20000..20499, 7700..8199), so that parallel runs do not meet.
n=$(($$ % 500))
PORT=$((21000 + n))
URL="udpm://239.255.76.67:$((8300 + n))?ttl=0&recv_buf_size=4194304"
# The lockstep clock: the robot's time advances only as the daemon deals with each SIP, so
# the run is the same however slow the daemon (a sanitizer build) or busy the machine.
write_robot_conf "$tmp/robot.conf"
echo "lockstep = true" >>"$tmp/robot.conf"     # (the [robot] section ends the file)
SIM_CLOCK="--lockstep --speed 50"
D="$BIN/houghlocd --config $tmp/robot.conf"

soundings=1     # the one when the robot first connects, then one per leg driven
goto() {        # goto DESCRIPTION X Y: houghloc-goto must report ARRIVED (exit 0)
    "$BIN/houghloc-goto" --lcm-url "$URL" --timeout 30 "$2" "$3" >"$tmp/goto.out" 2>&1
    rc=$?
    legs=$(sed -n 's/.*ARRIVED: .* after \([0-9]*\) legs*$/\1/p' "$tmp/goto.out")
    if [ $rc -eq 0 ] && [ -n "$legs" ]; then
        soundings=$((soundings + legs))
        echo "ok: $1 ($(sed -n 's/.*ARRIVED: //p' "$tmp/goto.out"))"
    else
        echo "FAIL: $1 (houghloc-goto exit $rc): $(tail -n 2 "$tmp/goto.out")"; fail=1
    fi
}
status_of() {   # status_of LOG KEY: KEY's value in the last STATUS of LOG
    "$BIN/hl-eval" status "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"
}
bad_packets_of() {  # bad_packets_of LOG: the last STATUS's bad_packets
    status_of "$1" bad_packets
}
demo_line() {   # demo_line LOG: hl-eval live's last line, "stops=.. max_mm=.." as words
    # (the daemon starts at the robot's true start, write_robot_conf: the frames agree)
    "$BIN/hl-eval" live --start "$ROBOT_START" "$1" | tail -n 1 | tr ' ' '\n'
}
value() {       # value KEY < key=value lines
    sed -n "s/^$1=//p"
}

# ---- the daemon waits for its robot, then drives it to three destinations ----------------
# (Debian's lcm-logger 1.3.1 takes only the long form of its URL option)
lcm-logger -q -f --lcm-url="$URL" "$tmp/live.lcmlog" >/dev/null 2>&1 &
logger=$!; pids="$pids $logger"
sleep 0.3
$D --fresh-map --map "$tmp/live.hlmap" 2>"$tmp/d.err" &
daemon=$!; pids="$pids $daemon"
check "no robot listening yet: the daemon logs the refused address" \
    wait_for "$tmp/d.err" "robot link: tcp:127.0.0.1:$PORT: Connection refused (retrying" 1 50
start_sim sim1 --start 5.4,1.5,0
check "... keeps retrying, and connects once the robot listens" \
    wait_for "$tmp/d.err" "robot 'houghloc-sim' (Pioneer bonnie) connected" 1 100
goto "destination 1 (6.3, 1.5) reached" 6.3 1.5
goto "destination 2 (7.0, 1.0) reached" 7.0 1.0
goto "destination 3 (6.3, 1.5) reached" 6.3 1.5
part1=$soundings

# ---- SIGKILL the robot, restart it where it truly stands: the daemon continues ------------
pose=$(true_pose "$tmp/live.lcmlog")
check "the robot's true pose is read from GROUND_TRUTH ($pose)" test -n "$pose"
kill -9 $sim; wait $sim 2>/dev/null
start_sim sim2 --start "$pose"
check "after SIGKILL and a restart the daemon connects a second time" \
    wait_for "$tmp/d.err" "robot 'houghloc-sim' (Pioneer bonnie) connected" 2 100
# (a closed connection, or a reset or broken pipe when the kill left bytes unread)
lost=$(sed -n "/robot 'houghloc-sim' .* connected/,\$ s/.*robot link: tcp:127.0.0.1:$PORT: \(.*\) (retrying.*/\1/p" \
    "$tmp/d.err" | head -n 1)
check "... having logged the lost connection ($lost)" test -n "$lost"
goto "after the restart, destination 4 (7.0, 1.0) reached" 7.0 1.0

# ---- a robot that sends garbage and corrupt checksums ------------------------------------
pose=$(true_pose "$tmp/live.lcmlog")
kill -TERM $sim; wait $sim
start_sim sim3 --start "$pose" --garbage-every 5 --corrupt-every 7
check "the daemon connects to the faulty robot" \
    wait_for "$tmp/d.err" "robot 'houghloc-sim' (Pioneer bonnie) connected" 3 100
goto "through injected garbage and bad checksums, destination 5 (6.3, 1.5) reached" 6.3 1.5

kill -TERM $daemon; wait $daemon
check "SIGTERM stops the daemon with exit 0" test $? -eq 0
kill -TERM $sim; wait $sim
sleep 0.3
kill -INT $logger; wait $logger
if [ $fail -ne 0 ]; then
    echo "  the daemon's log ends:"; tail -n 8 "$tmp/d.err" | sed 's/^/    /'
    for f in sim1 sim2 sim3; do tail -n 2 "$tmp/$f.err" 2>/dev/null | sed "s/^/    $f: /"; done
fi

# the soundings at the start and on the way to destinations 1 to 3, before any restart
"$BIN/hl-eval" split "$tmp/live.lcmlog" $part1 "$tmp/part1.lcmlog" "$tmp/rest.lcmlog"
demo_line "$tmp/part1.lcmlog" >"$tmp/part1.demo"
echo "  three destinations: $(tr '\n' ' ' <"$tmp/part1.demo")"
check "three destinations: $part1 soundings scored (one per leg, one at the start)" \
    test "$(value stops <"$tmp/part1.demo")" = $part1
check "three destinations: every sounding's position error below 100 mm" \
    awk -v m="$(value max_mm <"$tmp/part1.demo")" 'BEGIN { exit !(m != "" && m < 100) }'
demo_line "$tmp/live.lcmlog" >"$tmp/all.demo"
echo "  whole run: $(tr '\n' ' ' <"$tmp/all.demo")"
check "whole run: $soundings soundings scored" test "$(value stops <"$tmp/all.demo")" = $soundings
check "whole run, restarts and faults included: every position error below 100 mm" \
    awk -v m="$(value max_mm <"$tmp/all.demo")" 'BEGIN { exit !(m != "" && m < 100) }'
check "whole run: no wild pose accepted" test "$(value wild_accepted <"$tmp/all.demo")" = 0

# the last STATUS before the first sounding after the restart comes after the SIGKILL
before=$(status_of "$tmp/part1.lcmlog" map_vectors)
after=$(status_of "$tmp/live.lcmlog" map_vectors)
echo "  map_vectors: $before before the restart, $after at the end"
check "the map survives the restart: map_vectors $after >= $before > 0" \
    test "${before:-0}" -gt 0 -a "${after:-0}" -ge "${before:-0}"
check "... only the very first sounding had no map to localize against (odometry_only=1)" \
    test "$(status_of "$tmp/live.lcmlog" odometry_only)" = 1
check "a clean link drops no packets (bad_packets=0 before the faults)" \
    test "$(bad_packets_of "$tmp/part1.lcmlog")" = 0
bad=$(bad_packets_of "$tmp/live.lcmlog")
garbage=$(sed -n 's/.*summary:.* garbage \([0-9]*\),.*/\1/p' "$tmp/sim3.err")
corrupt=$(sed -n 's/.*summary:.* corrupt \([0-9]*\),.*/\1/p' "$tmp/sim3.err")
echo "  injected: garbage $garbage, corrupt $corrupt; the daemon's bad_packets: $bad"
check "the simulator injected both kinds of fault" test "${garbage:-0}" -gt 0 -a "${corrupt:-0}" -gt 0
check "STATUS counts the skipped packets (bad_packets=$bad > 0)" test "${bad:-0}" -gt 0

# ---- a batch replay of the live log gives the same POSE stream ---------------------------
$D --set robot.link= --fresh-map --map "$tmp/replay.hlmap" --lcm-url "file://$tmp/live.lcmlog?speed=0" \
    --lcm-out "file://$tmp/replay.lcmlog?mode=w" 2>"$tmp/replay.err"
check "the batch replay of the live log exits 0" test $? -eq 0
for ch in POSE MAP; do
    "$BIN/hl-eval" extract "$tmp/live.lcmlog" $ch "$tmp/live.$ch"
    "$BIN/hl-eval" extract "$tmp/replay.lcmlog" $ch "$tmp/replay.$ch"
done
check "the replay's POSE stream equals the live run's, byte for byte" \
    sh -c "test -s $tmp/live.POSE && cmp -s $tmp/live.POSE $tmp/replay.POSE"
check "... and so does its MAP stream" cmp -s "$tmp/live.MAP" "$tmp/replay.MAP"
check "... and the saved map file" cmp -s "$tmp/live.hlmap" "$tmp/replay.hlmap"

# ---- ... and so does lcm-logplayer playing it into a daemon on the network ----------------
URL2="udpm://239.255.76.67:$((8900 + n))?ttl=0&recv_buf_size=4194304"
lcm-logger -q -f --lcm-url="$URL2" "$tmp/played.lcmlog" >/dev/null 2>&1 &
player_logger=$!; pids="$pids $player_logger"
$D --set robot.link= --set lcm.url="$URL2" --fresh-map --map "$tmp/played.hlmap" 2>"$tmp/played.err" &
player_daemon=$!; pids="$pids $player_daemon"
sleep 0.5
lcm-logplayer -s 4 -e 'SONAR|ODOMETRY' -l "$URL2" "$tmp/live.lcmlog" >/dev/null 2>&1
sleep 0.5
kill -TERM $player_daemon; wait $player_daemon
kill -INT $player_logger; wait $player_logger
"$BIN/hl-eval" extract "$tmp/played.lcmlog" POSE "$tmp/played.POSE"
check "lcm-logplayer into a live daemon: the same POSE stream as the live run" \
    cmp -s "$tmp/live.POSE" "$tmp/played.POSE"

# ---- transport errors: clear, and never fatal once running -------------------------------
# link_fails NAME TEXT [RUNNER...]: the daemon with robot.link=NAME keeps running for 1 s,
# logs the fault naming the link with TEXT (one fault, repeated only as the retry delay
# grows), and stops with exit 0 on SIGTERM. RUNNER (e.g. setpriv) runs the daemon.
link_fails() {
    link=$1 text=$2; shift 2
    "$@" "$BIN/houghlocd" --config /dev/null --set robot.link="$link" --lcm-url "$URL" \
        --fresh-map --map "$map_dir/fail.hlmap" 2>"$tmp/fail.err" &
    p=$!; pids="$pids $p"
    sleep 1
    kill -0 $p 2>/dev/null; alive=$?
    kill -TERM $p; wait $p; rc=$?
    faults=$(grep 'robot link:' "$tmp/fail.err" | sed 's/ (retrying.*//' | sort -u)
    if [ $alive -eq 0 ] && [ $rc -eq 0 ] && [ "$(echo "$faults" | wc -l)" -eq 1 ] &&
        echo "$faults" | grep -q -F -- "robot link: $link: $text"; then
        echo "ok: robot.link=$link: \"${faults#*robot link: }\", retried, SIGTERM exit 0"
    else
        echo "FAIL: robot.link=$link (running after 1 s: $alive, exit $rc): $(head -c 400 "$tmp/fail.err")"
        fail=1
    fi
}
map_dir=$tmp
link_fails serial:/dev/ttyNOPE "No such file or directory (is the robot's cable plugged in?)"
link_fails tcp:127.0.0.1:1 "Connection refused"
rejects "a bad baud rate: --print-config exits 1 naming it" 1 "baud rate '1234' is not one ARCOS speaks" \
    "$BIN/houghlocd" --config /dev/null --set robot.link=serial:/dev/ttyS0,1234 --print-config
printf '[robot]\nlink = serial:/dev/ttyS0,1234\n' >"$tmp/baud.conf"
rejects "a bad baud rate in the file: exit 1 at start, naming the line and the rate" 1 \
    "baud.conf:2: key 'robot.link': robot link 'serial:/dev/ttyS0,1234': baud rate '1234'" \
    "$BIN/houghlocd" --config "$tmp/baud.conf" --map "$tmp/baud.hlmap" --lcm-url "$URL"

# A permission error needs a serial port that libserialport knows (it looks the name up
# in /sys/class/tty) and that this user may not open: as root, run the daemon as nobody.
dev="" as_nobody="--reuid=nobody --regid=$(id -g nobody 2>/dev/null) --clear-groups"
for d in /dev/ttyS0 /dev/ttyS1 /dev/ttyUSB0 /dev/ttyACM0; do
    [ -c "$d" ] && [ -e "/sys/class/tty/${d#/dev/}" ] && { dev=$d; break; }
done
if [ -z "$dev" ]; then
    echo "skip: permission error: no serial port in /sys/class/tty here"
elif [ "$(id -u)" -ne 0 ] && [ ! -w "$dev" ]; then
    link_fails "serial:$dev" "cannot open: Permission denied (is this user in the 'dialout' group?)"
elif [ "$(id -u)" -eq 0 ] && command -v setpriv >/dev/null &&
    ! setpriv $as_nobody test -w "$dev" 2>/dev/null &&
    setpriv $as_nobody test -x "$BIN/houghlocd" 2>/dev/null; then
    nobody_dir=$(mktemp -d)     # the map file, where nobody may write
    chmod 777 "$nobody_dir"
    map_dir=$nobody_dir
    link_fails "serial:$dev" "cannot open: Permission denied (is this user in the 'dialout' group?)" \
        setpriv $as_nobody
else
    echo "skip: permission error: $dev is open to this user, or nobody cannot run $BIN/houghlocd"
fi

[ $fail -eq 0 ]
