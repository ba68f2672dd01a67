#!/bin/sh
# Integration test of the README's simulated-robot recipe, pasted into a shell as one
# block, as a user does:
#
#   houghloc-sim &
#   houghlocd --set robot.link=tcp:127.0.0.1:8101 --set robot.profile=houghloc-sim &
#   houghloc-goto 2 1
#   houghloc-goto 0 0
#
# with three differences that keep parallel runs apart and the test short: the simulator
# listens on a port of this test's own (--port, chosen from the process id) and runs 10
# times faster than real time, and every program finds an LCM group of the test's own in
# $LCM_DEFAULT_URL (as every LCM program does). Nothing waits between the lines: the
# first houghloc-goto starts while the daemon is still connecting to the robot, and must
# wait for it (within its default timeout) rather than fail. The robot starts at the
# simulator's default start; "2 1" lies 2 m ahead and 1 m to the left. HOME and
# XDG_STATE_HOME point into a temporary folder, so the daemon's default map location for
# a user is exercised. Both houghloc-goto calls use their default timeout, which must
# follow the robot's progress (the trip takes longer than it): each must exit 0 with
# ARRIVED. Then the map file must be where the default says, and the robot must never
# have touched anything (the simulator's collision count). Every wait is on a condition,
# with a generous bound; nothing is timed.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM HUP PIPE
. tests/integration/lib.sh
for p in houghlocd houghloc-sim houghloc-goto; do
    [ -x "$BIN/$p" ] || { echo "FAIL: no $BIN/$p (run make first)"; exit 1; }
done

# An LCM group of this test's own (a multicast address no other test uses).
n=$(($$ % 500))
LCM_DEFAULT_URL="udpm://239.255.76.69:$((7700 + n))?ttl=0"
HOME=$tmp/home
XDG_STATE_HOME=$tmp/state
export LCM_DEFAULT_URL HOME XDG_STATE_HOME
unset STATE_DIRECTORY
mkdir -p "$HOME"

wait_for() {    # wait_for FILE TEXT TENTHS: until FILE holds TEXT
    w=0
    until grep -q -- "$2" "$1" 2>/dev/null; do
        [ $w -ge "$3" ] && return 1
        sleep 0.1; w=$((w + 1))
    done
}

# The map's default location for a user; a machine where the system folder is writable
# would get the system map instead, which a test must not touch: then --map is given.
MAP=$XDG_STATE_HOME/houghloc/map.hlmap
map_opt=""
if [ -d /var/lib/houghloc ] && [ -w /var/lib/houghloc ]; then
    echo "note: /var/lib/houghloc is writable here: the daemon would keep its map there," \
         "so the test gives --map $MAP instead"
    map_opt="--map $MAP"
fi

# The recipe, pasted at once.
PORT=$((20000 + $$ % 20000))
"$BIN/houghloc-sim" --port $PORT --speed 10 2>"$tmp/sim.err" &
sim=$!; pids="$sim"
# shellcheck disable=SC2086  # lists of options
"$BIN/houghlocd" $map_opt --set "robot.link=tcp:127.0.0.1:$PORT" \
    --set robot.profile=houghloc-sim 2>"$tmp/d.err" &
daemon=$!; pids="$daemon $pids"

goto() {        # goto X Y: as typed, default timeout; must exit 0 with ARRIVED
    start=$(date +%s)
    "$BIN/houghloc-goto" "$1" "$2" >"$tmp/goto.out" 2>"$tmp/goto.err"
    rc=$?
    took=$(($(date +%s) - start))
    if [ $rc -eq 0 ] && grep -q "^houghloc-goto: ARRIVED: " "$tmp/goto.out"; then
        echo "ok: houghloc-goto $1 $2: exit 0 after ${took} s, $(sed -n 's/.*ARRIVED: //p' "$tmp/goto.out")"
    else
        echo "FAIL: houghloc-goto $1 $2: exit $rc after ${took} s: $(tail -n 2 "$tmp/goto.err" "$tmp/goto.out")"
        fail=1
        tail -n 5 "$tmp/d.err" | sed 's/^/    houghlocd: /'
    fi
}
goto 2 1
goto 0 0
check "houghlocd ran with the default map location" kill -0 $daemon

kill -TERM $daemon; wait $daemon
check "SIGTERM stops houghlocd with exit 0" test $? -eq 0
kill -TERM $sim; wait $sim
pids=""
check "the robot never touched anything (houghloc-sim: collisions=0)" \
    grep -q "summary:.* collisions=0$" "$tmp/sim.err"
check "the map file is where the default says: $MAP" test -s "$MAP"
check "the daemon's map folder is private (0700)" \
    test "$(stat -c %a "$(dirname "$MAP")")" = 700
check "nothing was written outside the temporary folder: no /var/lib/houghloc" \
    sh -c '[ -n "$1" ] || [ ! -e /var/lib/houghloc ]' - "$map_opt"
[ $fail -eq 0 ] || { echo "  the daemon's log:"; tail -n 12 "$tmp/d.err" | sed 's/^/    /'; }
exit $fail
