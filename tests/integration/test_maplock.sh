#!/bin/sh
# Integration test of the map file's guards: one daemon per map (the lock on MAP.lock,
# which a killed daemon does not leave behind), saves of a changed map only (an idle
# daemon leaves the file as it found it, inode and mtime included), and --fresh-map
# keeping the old map as MAP.old-N. Every check names what it tests.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
TOUR=$PWD/logs/tour.lcmlog
D="$BIN/houghlocd --config /dev/null"
CTL="$BIN/houghloc-ctl --timeout 5"
# an LCM group of this run's own
url="udpm://239.255.76.71:$((7600 + $$ % 300))?ttl=0"

wait_ready() {  # wait_ready ERRFILE: until the daemon says it is ready (10 s at most)
    n=0
    while ! grep -q 'ready:' "$1" 2>/dev/null && [ $n -lt 100 ]; do sleep 0.1; n=$((n + 1)); done
    grep -q 'ready:' "$1"
}
start() {       # start NAME ARGS...: a live daemon on $url; its pid in $daemon
    name=$1; shift
    $D --lcm-url "$url" "$@" 2>"$tmp/$name.err" &
    daemon=$!; pids="$pids $daemon"
    wait_ready "$tmp/$name.err"
}
stamp() {       # stamp FILE: inode, size, mtime in nanoseconds
    stat -c '%i %s %.9Y' "$1"
}

# ---- a map to guard: the tour, replayed ------------------------------------------------
map=$tmp/map.hlmap
$D --map "$map" --lcm-url "file://$TOUR?speed=0" --lcm-out "file://$tmp/tour.out?mode=w" 2>/dev/null
n_vec=$($D --map "$map" --check-map | sed -n 's/.*, \([0-9]*\) of [0-9]* vectors.*/\1/p')
check "the tour makes a map of 1000 or more vectors (${n_vec:-none})" test "${n_vec:-0}" -ge 1000
cp "$map" "$tmp/map.orig"
check "... and a lock file beside it, empty once the daemon stopped" \
    sh -c "test -f '$map.lock' && ! test -s '$map.lock'"

# ---- one daemon per map ------------------------------------------------------------------
start holder --map "$map"
check "a daemon starts on the map" test $? -eq 0
holder=$daemon
before=$(stamp "$map")
check "the lock file holds the holder's pid" test "$(cat "$map.lock")" = "$holder"
# (timeout: a second daemon that started would otherwise run until stopped)
exits "a second daemon on the held map: exit 1, one line naming the map, the holder's pid and the lock" \
    1 "houghlocd: map $map is in use by houghlocd pid $holder (lock $map.lock)" \
    timeout 10 $D --map "$map" --lcm-url "$url"
exits "... the same with --fresh-map, a replay and an output log" 1 "is in use by houghlocd pid $holder" \
    timeout 10 $D --map "$map" --fresh-map --lcm-url "file://$TOUR?speed=0" \
    --lcm-out "file://$tmp/second.out?mode=w"
check "... the map file is untouched, byte for byte, inode and mtime" \
    sh -c "cmp -s '$map' '$tmp/map.orig' && test \"\$(stat -c '%i %s %.9Y' '$map')\" = '$before'"
check "... nothing set aside, no output log written" \
    test -z "$(ls -d "$map".old-* "$map".bad-* "$tmp/second.out" 2>/dev/null)"
check "... and the lock still names the holder" test "$(cat "$map.lock")" = "$holder"
check "--check-map reads a held map (it takes no lock)" \
    sh -c "$D --map '$map' --check-map | grep -q '$n_vec of 1500 vectors'"
mkdir "$tmp/ro"
cp "$map" "$tmp/ro/map.hlmap"
chmod 555 "$tmp/ro"
if [ ! -w "$tmp/ro" ]; then     # root writes anywhere
    check "--check-map of a map in a read-only folder: no lock file needed" \
        sh -c "$D --map '$tmp/ro/map.hlmap' --check-map >/dev/null && ! test -e '$tmp/ro/map.hlmap.lock'"
fi
chmod 755 "$tmp/ro"

# ---- an idle daemon leaves the map as it found it ----------------------------------------
kill -HUP $holder
sleep 0.5
check "SIGHUP on an unchanged map: logged as unchanged since the last save" \
    grep -q "map $map unchanged since the last save: not written" "$tmp/holder.err"
kill -TERM $holder; wait $holder
check "the idle daemon stops with exit 0" test $? -eq 0
check "... having saved nothing: its map file is byte for byte the same, same inode and mtime" \
    sh -c "cmp -s '$map' '$tmp/map.orig' && test \"\$(stat -c '%i %s %.9Y' '$map')\" = '$before'"

# ---- kill -9 leaves no lock behind --------------------------------------------------------
start killed --map "$map"
killed=$daemon
kill -KILL $killed; wait $killed 2>/dev/null
check "a daemon killed with SIGKILL leaves its pid in the lock file" test "$(cat "$map.lock")" = "$killed"
start after --map "$map"
check "... yet the next daemon starts on the map at once" test $? -eq 0
check "... and takes the lock, writing its own pid" test "$(cat "$map.lock")" = "$daemon"
kill -TERM $daemon; wait $daemon
check "... and stops with exit 0, the map untouched" \
    sh -c "test $? -eq 0 && cmp -s '$map' '$tmp/map.orig' && test \"\$(stat -c '%i %s %.9Y' '$map')\" = '$before'"

# ---- a SAVE request on an unchanged map ----------------------------------------------------
start saver --map "$map"
saver=$daemon
$CTL --lcm-url "$url" save >"$tmp/save.out" 2>&1
check "a SAVE request on an unchanged map: ACCEPTED, unchanged since the last save" \
    grep -q "ACCEPTED: map unchanged since the last save" "$tmp/save.out"
check "... and the file is untouched" \
    sh -c "cmp -s '$map' '$tmp/map.orig' && test \"\$(stat -c '%i %s %.9Y' '$map')\" = '$before'"
kill -TERM $saver; wait $saver
unseq() { $D --map "$1" --check-map | sed 's/^[^:]*: //; s/last request seq [-0-9]*//'; }
unseq "$map" >"$tmp/now.info"; unseq "$tmp/map.orig" >"$tmp/orig.info"
check "... the stop then writes the SAVE's seq (the replay guard), the map otherwise the same" \
    sh -c "! cmp -s '$map' '$tmp/map.orig' && cmp -s '$tmp/now.info' '$tmp/orig.info'"
cp "$map" "$tmp/map.orig"

# ---- a change is saved --------------------------------------------------------------------
start changed --map "$map"
changed=$daemon
$CTL --lcm-url "$url" set-pose 1.25 -0.5 30 >/dev/null 2>&1
$CTL --lcm-url "$url" save >"$tmp/save2.out" 2>&1
check "a SAVE request after SET_POSE: ACCEPTED, map saved" grep -q "ACCEPTED: map saved" "$tmp/save2.out"
check "... the file holds the new pose" \
    sh -c "$D --map '$map' --check-map | grep -q 'pose (1.250, -0.500) m 30.00 deg'"
cp "$map" "$tmp/map.posed"
kill -TERM $changed; wait $changed
check "... and the stop after it writes nothing more" cmp -s "$map" "$tmp/map.posed"

# ---- --fresh-map sets the old map aside ----------------------------------------------------
cp "$tmp/map.orig" "$tmp/fresh.hlmap"
start fresh1 --map "$tmp/fresh.hlmap" --fresh-map
kill -TERM $daemon; wait $daemon
check "--fresh-map moves a good map to MAP.old-1, byte for byte" cmp -s "$tmp/fresh.hlmap.old-1" "$tmp/map.orig"
check "... and says so in one line naming it" \
    test "$(grep -c "fresh-map: moved the map ($n_vec vectors, [0-9]* scans) to $tmp/fresh.hlmap.old-1; starting empty" "$tmp/fresh1.err")" -eq 1
check "... and the stop writes the new, empty map" \
    sh -c "$D --map '$tmp/fresh.hlmap' --check-map | grep -q ', 0 of 1500 vectors'"
cp "$tmp/map.posed" "$tmp/fresh.hlmap"
$D --map "$tmp/fresh.hlmap" --fresh-map --lcm-url "file://$TOUR?speed=0" \
    --lcm-out "file://$tmp/fresh2.out?mode=w" 2>"$tmp/fresh2.err"
check "a second --fresh-map takes the first free number, MAP.old-2" \
    sh -c "cmp -s '$tmp/fresh.hlmap.old-2' '$tmp/map.posed' && cmp -s '$tmp/fresh.hlmap.old-1' '$tmp/map.orig'"
check "... and the replay after it saves its own map" \
    sh -c "$D --map '$tmp/fresh.hlmap' --check-map | grep -q ' 128 scans'"
head -c 500 "$tmp/map.orig" >"$tmp/fresh.hlmap"
cp "$tmp/fresh.hlmap" "$tmp/short.orig"
start fresh3 --map "$tmp/fresh.hlmap" --fresh-map
kill -TERM $daemon; wait $daemon
check "--fresh-map moves a map that does not load to MAP.bad-1, its reason logged" \
    sh -c "cmp -s '$tmp/fresh.hlmap.bad-1' '$tmp/short.orig' && grep -q 'moved the unloadable map to $tmp/fresh.hlmap.bad-1 (.*truncated' '$tmp/fresh3.err'"

[ $fail -eq 0 ]
