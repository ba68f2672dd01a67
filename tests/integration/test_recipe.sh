#!/bin/sh
# Integration test of the README's simulated-robot recipe, followed as a user types it:
#
#   houghloc-sim &
#   houghlocd --set robot.link=tcp:127.0.0.1:8101 --set robot.profile=houghloc-sim
#   houghloc-goto 0.5 -1.5
#   houghloc-goto 0 0
#
# with three differences that keep parallel runs apart and the test short: the simulator
# takes any free port (--port 0, read from its log) and runs 10 times faster than real
# time, and every program finds an LCM group of the test's own in $LCM_DEFAULT_URL (as
# every LCM program does). HOME and XDG_STATE_HOME point into a temporary folder, so the
# daemon's default map location for a user is exercised. Both houghloc-goto calls use
# their default timeout, which must follow the robot's progress (the trip takes longer
# than it): each must exit 0 with ARRIVED. Then the map file must be where the default
# says. Every wait is on a condition, with a generous bound; nothing is timed.
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

# houghloc-sim &
"$BIN/houghloc-sim" --port 0 --speed 10 2>"$tmp/sim.err" &
sim=$!; pids="$sim"
wait_for "$tmp/sim.err" "listening on" 100
PORT=$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$tmp/sim.err" | head -n 1)
check "houghloc-sim listens on a free port (${PORT:-none})" test -n "$PORT"

# houghlocd --set robot.link=... --set robot.profile=houghloc-sim
profile_sets="--set robot.profile=houghloc-sim"
# shellcheck disable=SC2086  # lists of options
"$BIN/houghlocd" $map_opt --set "robot.link=tcp:127.0.0.1:$PORT" $profile_sets 2>"$tmp/d.err" &
daemon=$!; pids="$daemon $pids"
check "houghlocd connects to the robot" wait_for "$tmp/d.err" "robot .* connected" 300
check "houghlocd runs with the default map location" kill -0 $daemon

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
goto 0.5 -1.5
goto 0 0

kill -TERM $daemon; wait $daemon
check "SIGTERM stops houghlocd with exit 0" test $? -eq 0
kill -TERM $sim; wait $sim
pids=""
check "the map file is where the default says: $MAP" test -s "$MAP"
check "the daemon's map folder is private (0700)" \
    test "$(stat -c %a "$(dirname "$MAP")")" = 700
check "nothing was written outside the temporary folder: no /var/lib/houghloc" \
    sh -c '[ -n "$1" ] || [ ! -e /var/lib/houghloc ]' - "$map_opt"
[ $fail -eq 0 ] || { echo "  the daemon's log:"; tail -n 12 "$tmp/d.err" | sed 's/^/    /'; }
exit $fail
