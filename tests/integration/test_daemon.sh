#!/bin/sh
# Integration test of houghlocd as a user runs it: options and configuration, batch replay
# (deterministic, byte for byte), live replay with lcm-logplayer and lcm-logger, hostile
# input, map persistence across restarts and kill -9, bad map files, requests with
# houghloc-goto, and bad logs. Every check names what it tests.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
TOUR=logs/tour.lcmlog
D="$BIN/houghlocd --config /dev/null"

replay() {  # replay IN OUT MAP [ARGS...]: batch replay of IN into OUT with map MAP
    in=$1; out=$2; map=$3; shift 3
    case $in in /*) ;; *) in=$PWD/$in ;; esac
    $D --map "$map" --lcm-url "file://$in?speed=0" --lcm-out "file://$out?mode=w" "$@"
}

# ---- options and configuration -----------------------------------------------------------
check "--help exits 0 and names the channels" sh -c "$BIN/houghlocd --help | grep -q 'POSE (one per scan)'"
check "--version exits 0" sh -c "$BIN/houghlocd --version | grep -q '^houghlocd [0-9]'"
$D --print-config >"$tmp/a.conf"
check "--print-config exits 0" test $? -eq 0
$BIN/houghlocd --config "$tmp/a.conf" --print-config >"$tmp/b.conf"
check "--print-config output reads back to the same values" cmp -s "$tmp/a.conf" "$tmp/b.conf"
check "packaging/houghlocd.conf is the commented defaults" cmp -s "$tmp/a.conf" packaging/houghlocd.conf
check "packaging/houghlocd.conf: the operator's 25 keys, under 90 lines" \
    sh -c 'test "$(grep -c "^[a-z_0-9]* = " "$1")" -eq 25 && test "$(wc -l <"$1")" -lt 90' - packaging/houghlocd.conf
$D --print-config=all >"$tmp/all.conf"
$BIN/houghlocd --config "$tmp/all.conf" --print-config=all >"$tmp/all2.conf"
check "--print-config=all prints every key, and reads back the same" \
    sh -c "cmp -s $tmp/all.conf $tmp/all2.conf && grep -q '^coarse_max_cells = ' $tmp/all.conf"
check "--print-config=all: at most 73 keys, the tracker's included" \
    sh -c 'test "$(grep -c "^[a-z_0-9]* = " "$1")" -le 73' - "$tmp/all.conf"
$D --set slam.window_mm=700 --print-config >"$tmp/changed.conf"
check "--print-config shows a research key set away from its default" grep -q '^window_mm = 700$' "$tmp/changed.conf"
rejects "--print-config takes only =all" 2 "takes no value or '=all'" $D --print-config=some
$D --set slam.profile=paper --print-config=all >"$tmp/paper.conf"
check "slam.profile=paper turns echo bearings off" grep -q '^echo_bearings = false' "$tmp/paper.conf"
printf '[slam]\nmap_capacity = 800\nprofile = paper\n' >"$tmp/order.conf"
check "slam.profile applies before other keys wherever it is written" \
    sh -c "$BIN/houghlocd --config $tmp/order.conf --print-config | grep -q '^map_capacity = 800'"
# Keys that are settings no more: their fixed value warns, another stops the start.
printf '[slam]\nmode = improved\n[link]\npulse_ms = 500\n' >"$tmp/old.conf"
check "a retired key at its fixed value: a warning naming it, then the configuration" \
    sh -c "$BIN/houghlocd --config $tmp/old.conf --print-config 2>&1 >/dev/null |
           grep -q \"old.conf:2: key 'slam.mode' is no longer a setting (fixed at improved): ignored\""
rejects "a retired key at another value: refused, naming its fixed value" 1 \
    "slam.mode=paper: no longer a setting, fixed at improved (the paper's method is slam.profile = paper)" \
    $D --set slam.mode=paper --print-config
rejects "a key of the laboratory's studies: not houghlocd's" 1 \
    "--set reloc.max_ratio=0.4: a setting of the laboratory's studies" $D --set reloc.max_ratio=0.4

# ---- sensor and robot profiles ------------------------------------------------------------
for p in sonar-stops sonar-continuous laser paper; do
    $BIN/houghlocd --print-profile $p >"$tmp/$p.frag"
    $D --set slam.profile=$p --print-config=all >"$tmp/$p.key"
    $BIN/houghlocd --config "$tmp/$p.frag" --set slam.profile=$p --print-config=all >"$tmp/$p.file"
    check "--print-profile $p: a fragment that sets what the key does" cmp -s "$tmp/$p.key" "$tmp/$p.file"
done
check "--print-profile laser names its keys in their sections" \
    sh -c "grep -q '^\[slam\]$' $tmp/laser.frag && grep -q '^map_capacity = 15000$' $tmp/laser.frag"
rejects "an unknown sensor profile: the four names" 1 "'sonar' is not one of sonar-stops, sonar-continuous, laser or paper" $D --set slam.profile=sonar
rejects "--print-profile of an unknown name: the four names" 2 "unknown sensor profile 'x' (sonar-stops, sonar-continuous, laser or paper)" $BIN/houghlocd --print-profile x
check "robot.profile=houghloc-sim carries the simulator's calibration" \
    sh -c "$D --set robot.profile=houghloc-sim --print-config | grep -q '^gain_q16 = 70124$'"
printf '[calibration]\noffset_mm = -20\n[robot]\nprofile = houghloc-sim\n' >"$tmp/calib.conf"
check "... and calibration.* keys override it wherever written" \
    sh -c "$BIN/houghlocd --config $tmp/calib.conf --print-config | grep -q '^offset_mm = -20$'"
printf '[slam]\nmap_capacity = 1500\nbogus = 3\n' >"$tmp/bad.conf"
rejects "unknown key: file, line and key" 1 "bad.conf:3: unknown key 'bogus'" $BIN/houghlocd --config "$tmp/bad.conf" --print-config
printf '[localize]\n\ncell_mm = twelve\n' >"$tmp/bad.conf"
rejects "bad value: file, line, key and value" 1 "bad.conf:3: key 'localize.cell_mm': 'twelve' is not a number" $BIN/houghlocd --config "$tmp/bad.conf"
printf '[slam]\nmap_capacity = 0\n' >"$tmp/bad.conf"
rejects "value out of range" 1 "bad.conf:2: key 'slam.map_capacity': 0 is outside 1..1048576" $BIN/houghlocd --config "$tmp/bad.conf"
printf 'this is not ini\n' >"$tmp/bad.conf"
rejects "a line that is not key = value" 1 "bad.conf:1: not a 'key = value' line" $BIN/houghlocd --config "$tmp/bad.conf"
printf '[fence]\npolygon = 0,0 1,1 0,1 1,0\n' >"$tmp/bad.conf"
rejects "a crossed fence polygon" 1 "bad.conf:2: key 'fence.polygon'" $BIN/houghlocd --config "$tmp/bad.conf"
awk 'BEGIN { printf "[fence]\npolygon ="; for (i = 0; i < 40; i++) printf " %d,%d", i, i * i; print "" }' >"$tmp/bad.conf"
rejects "a line longer than the reader takes: its number, not a misread" 1 "bad.conf:2: longer than" $BIN/houghlocd --config "$tmp/bad.conf"
printf '[daemon]\nmap_file=a\n  b ;c\n' >"$tmp/bad.conf"
rejects "a value that would print as a comment (found by fuzzing)" 1 "bad.conf:3: key 'daemon.map_file': 'b ;c'" $BIN/houghlocd --config "$tmp/bad.conf"
rejects "--set of a value starting with ';'" 1 "would read back as a comment" $D --set 'daemon.map_file=;x'
rejects "--set of an unknown key" 1 "unknown key 'slam.nope'" $D --set slam.nope=1
rejects "--set without =" 1 "expected SECTION.KEY=VALUE" $D --set slam.map_capacity
rejects "a combination the core refuses, its keys named" 1 "config: slam.window_mm (1000) needs 119952 raster cells of localize.cell_mm (24)" $D --set localize.max_cells=1000
rejects "a bad prefix" 1 "lcm.prefix" $D --prefix 'a b'
rejects "a missing --config file" 1 "cannot open" $BIN/houghlocd --config "$tmp/none.conf"
rejects "an unknown option" 2 "unknown option" $D --frobnicate
rejects "a stray argument" 2 "unexpected argument" $D extra
rejects "a map folder that cannot be written" 1 "give --map FILE" $D --map /proc/nope/map.hlmap --lcm-url "file://$PWD/$TOUR?speed=0"

# ---- the default map file: the service's folder, else the system's, else the user's ------
mkdir "$tmp/home"
if [ -w /var/lib/houghloc ]; then user_map=/var/lib/houghloc/map.hlmap
else user_map=$tmp/home/.local/state/houghloc/map.hlmap; fi
(unset STATE_DIRECTORY XDG_STATE_HOME; HOME=$tmp/home $D --fresh-map --lcm-url "file://$PWD/$TOUR?speed=0" \
    --lcm-out "file://$tmp/home.lcmlog?mode=w" 2>"$tmp/home.err")
check "no --map, a user: the map goes to \$XDG_STATE_HOME/houghloc (~/.local/state), logged" \
    sh -c "test -s $user_map && grep -q 'map file $user_map: the default location' $tmp/home.err"
[ "$user_map" = /var/lib/houghloc/map.hlmap ] ||
    check "... its folder made 0700" test "$(stat -c %a "$tmp/home/.local/state/houghloc")" = 700
mkdir "$tmp/service"
(STATE_DIRECTORY=$tmp/service $D --fresh-map --lcm-url "file://$PWD/$TOUR?speed=0" \
    --lcm-out "file://$tmp/service.lcmlog?mode=w" 2>/dev/null)
check "\$STATE_DIRECTORY comes first (the service)" test -s "$tmp/service/map.hlmap"
if [ ! -w /var/lib/houghloc ]; then
    rejects "nowhere for the map: the locations tried, and --map" 1 "tried /var/lib/houghloc" \
        env -u STATE_DIRECTORY XDG_STATE_HOME=/proc/nope $D --lcm-url "file://$PWD/$TOUR?speed=0"
fi

# ---- a map larger than the configured one: the setting to raise, not only --fresh-map ----
replay $TOUR "$tmp/big.out" "$tmp/big.map" --fresh-map --set slam.map_capacity=16000 2>/dev/null
n_big=$($D --map "$tmp/big.map" --check-map | sed -n 's/.* \([0-9]*\) of 16000 vectors.*/\1/p')
check "a 16000-vector map of the tour holds more than 1500 vectors ($n_big)" test "${n_big:-0}" -gt 1500
cp "$tmp/big.map" "$tmp/big.orig"
rejects "... refused under the default, naming slam.map_capacity and the value to set" 1 \
    "holds $n_big vectors, more than slam.map_capacity = 1500: raise it (--set slam.map_capacity=$n_big, or slam.profile = sonar-continuous)" \
    $D --map "$tmp/big.map" --lcm-url "file://$PWD/$TOUR?speed=0" --lcm-out "file://$tmp/big2.out?mode=w"
check "... left as it was" cmp -s "$tmp/big.map" "$tmp/big.orig"
"$BIN/hl-eval" split $TOUR 4 "$tmp/four.lcmlog" /dev/null
replay "$tmp/four.lcmlog" "$tmp/big3.out" "$tmp/big.map" --set slam.map_capacity=$n_big 2>/dev/null
check "... and loads with the capacity it names" test $? -eq 0

# ---- batch replay: every scan answered, byte-identical twice ----------------------------
replay $TOUR "$tmp/run1.lcmlog" "$tmp/run1.map" --fresh-map 2>"$tmp/run1.err"
check "batch replay exits 0 at the end of the log" test $? -eq 0
replay $TOUR "$tmp/run2.lcmlog" "$tmp/run2.map" --fresh-map 2>/dev/null
for ch in POSE MAP; do
    "$BIN/hl-eval" extract "$tmp/run1.lcmlog" $ch "$tmp/run1.$ch"
    "$BIN/hl-eval" extract "$tmp/run2.lcmlog" $ch "$tmp/run2.$ch"
    check "two batch replays give byte-identical $ch" cmp -s "$tmp/run1.$ch" "$tmp/run2.$ch"
done
"$BIN/hl-eval" text "$tmp/run1.lcmlog" POSE "$tmp/run1.POSE.txt"
check "the POSE stream equals the golden one (tests/golden/tour.sonar-stops.POSE.txt; make golden)" \
    cmp -s "$tmp/run1.POSE.txt" tests/golden/tour.sonar-stops.POSE.txt
check "the replay answers every scan with one POSE" sh -c "$BIN/hl-eval score --quiet $TOUR $tmp/run1.lcmlog | grep -q '^demo stops=128 '"
check "the replay writes STATUS too" sh -c "$BIN/hl-eval extract $tmp/run1.lcmlog STATUS $tmp/st && test -s $tmp/st"
check "the map file is saved at the end" sh -c "$D --map $tmp/run1.map --check-map | grep -q 'map version'"
cmp -s "$tmp/run1.map" "$tmp/run2.map"
check "two batch replays save byte-identical map files" test $? -eq 0

# ---- hostile input between the real messages ---------------------------------------------
"$BIN/hl-eval" garble $TOUR "$tmp/garbled.lcmlog"
replay "$tmp/garbled.lcmlog" "$tmp/garbled.out" "$tmp/garbled.map" --fresh-map 2>"$tmp/garbled.err"
check "a log full of garbage replays to the end" test $? -eq 0
"$BIN/hl-eval" extract "$tmp/garbled.out" POSE "$tmp/garbled.POSE"
check "garbage, truncated, replayed and mistyped messages leave POSE byte-identical" cmp -s "$tmp/run1.POSE" "$tmp/garbled.POSE"
check "each kind of fault is logged once, not per message" test "$(grep -c 'further faults of this kind' "$tmp/garbled.err")" -lt 20

# ---- bad logs are refused before liblcm reads them -----------------------------------------
head -c 100000 $TOUR >"$tmp/trunc.lcmlog"
rejects "a truncated log: one line naming the byte offset" 1 "byte " $D --map "$tmp/x.map" --lcm-url "file://$tmp/trunc.lcmlog?speed=0"
{ head -c 3000 $TOUR | "$BIN/hl-eval" split /dev/stdin 1 "$tmp/first.lcmlog" /dev/null 2>/dev/null; } || true
"$BIN/hl-eval" split $TOUR 1 "$tmp/one.lcmlog" "$tmp/rest.lcmlog"
printf '\355\241\332\001\0\0\0\0\0\0\0\1\0\0\0\0\0\0\0\1\0\0\0\5\177\377\377\377SONARxxxx' >>"$tmp/one.lcmlog"
rejects "an event declaring 0x7fffffff bytes: exit 1, no crash" 1 "byte " $D --map "$tmp/x.map" --lcm-url "file://$tmp/one.lcmlog?speed=0"

# ---- persistence: a restart continues exactly -------------------------------------------
"$BIN/hl-eval" split $TOUR 64 "$tmp/half1.lcmlog" "$tmp/half2.lcmlog"
replay "$tmp/half1.lcmlog" "$tmp/h1.out" "$tmp/halves.map" --fresh-map 2>/dev/null
replay "$tmp/half2.lcmlog" "$tmp/h2.out" "$tmp/halves.map" 2>"$tmp/h2.err"
check "the second half replays on the saved map" test $? -eq 0
"$BIN/hl-eval" extract "$tmp/h1.out" POSE "$tmp/h1.POSE"
"$BIN/hl-eval" extract "$tmp/h2.out" POSE "$tmp/h2.POSE"
cat "$tmp/h1.POSE" "$tmp/h2.POSE" >"$tmp/halves.POSE"
check "stop, restart, continue: the same POSE stream as one uninterrupted run" cmp -s "$tmp/run1.POSE" "$tmp/halves.POSE"
check "... and the same map file" cmp -s "$tmp/run1.map" "$tmp/halves.map"

# a private group; a larger receive buffer, so that a busy machine does not drop datagrams
url="udpm://239.255.76.67:$((7700 + $$ % 200))?ttl=0&recv_buf_size=4194304"
cp "$tmp/run1.map" "$tmp/idle.map"
$D --map "$tmp/idle.map" --lcm-url "$url" 2>"$tmp/idle.err" &
pid=$!; pids="$pids $pid"
sleep 1
kill -TERM $pid; wait $pid
check "SIGTERM stops the daemon with exit 0" test $? -eq 0
check "SIGTERM then restart: the identical map file" cmp -s "$tmp/run1.map" "$tmp/idle.map"

# ---- bad map files are refused and never overwritten ------------------------------------
size=$(wc -c <"$tmp/run1.map")
head -c $((size - 7)) "$tmp/run1.map" >"$tmp/short.map"
cp "$tmp/short.map" "$tmp/short.orig"
rejects "a truncated map file is refused" 1 "short.map" $D --map "$tmp/short.map" --lcm-url "file://$PWD/$TOUR?speed=0"
check "... and left as it was" cmp -s "$tmp/short.map" "$tmp/short.orig"
cp "$tmp/run1.map" "$tmp/flip.map"
printf '\377' | dd of="$tmp/flip.map" bs=1 seek=$((size / 2)) conv=notrunc 2>/dev/null
rejects "a map file with a flipped byte is refused" 1 "flip.map" $D --map "$tmp/flip.map" --lcm-url "file://$PWD/$TOUR?speed=0"
cp "$tmp/run1.map" "$tmp/ver.map"
printf '\011' | dd of="$tmp/ver.map" bs=1 seek=8 conv=notrunc 2>/dev/null
rejects "a map file of another format version is refused, naming it" 1 "version 9" $D --map "$tmp/ver.map" --check-map
replay $TOUR "$tmp/fresh.out" "$tmp/flip.map" --fresh-map 2>/dev/null
check "--fresh-map moves the bad file aside and starts" test $? -eq 0 -a -f "$tmp/flip.map.bad-1"
check "... the moved file is the bad one, unchanged" sh -c "! $D --map $tmp/flip.map.bad-1 --check-map 2>/dev/null"

# ---- kill -9 at random points: the map file always loads, at most one save period old -----
check "20 kill -9 trials leave a loadable, recent map file" sh tests/integration/crash_trials.sh 20

# ---- live: lcm-logplayer into a running daemon, lcm-logger records it, twice ------------
wait_ready() {  # wait_ready ERRFILE: until the daemon says it is ready (10 s at most)
    n=0
    while ! grep -q 'ready:' "$1" 2>/dev/null && [ $n -lt 100 ]; do sleep 0.1; n=$((n + 1)); done
}
live_run() {    # live_run NAME: replays the tour live; the recording in $tmp/NAME.lcmlog
    # (Debian's lcm-logger 1.3.1 takes only the long form of its URL option)
    lcm-logger -q -f -c 'POSE|MAP' --lcm-url="$url" "$tmp/$1.lcmlog" &
    logger=$!; pids="$pids $logger"
    $D --fresh-map --map "$tmp/$1.map" --lcm-url "$url" --set daemon.log_level=debug \
        2>"$tmp/$1.err" &
    daemon=$!; pids="$pids $daemon"
    wait_ready "$tmp/$1.err"
    lcm-logplayer -s 50 -e '^(SONAR|ODOMETRY)$' -l "$url" $TOUR
    # until every scan is answered (its debug line follows its POSE), however slow the
    # build (the sanitizers) or the machine: 60 s at most
    n=0
    while [ "$(grep -c 'houghlocd: scan [0-9]* (seq' "$tmp/$1.err")" -lt 128 ] && [ $n -lt 600 ]; do
        sleep 0.1; n=$((n + 1))
    done
    kill -TERM $daemon; wait $daemon; rc=$?
    sleep 0.5
    kill -INT $logger; wait $logger
    return $rc
}
live_run live1
check "live: the daemon stops cleanly after the replay" test $? -eq 0
live_run live2
"$BIN/hl-eval" extract "$tmp/live1.lcmlog" POSE "$tmp/live1.POSE"
"$BIN/hl-eval" extract "$tmp/live2.lcmlog" POSE "$tmp/live2.POSE"
check "live: lcm-logger recorded a POSE for every scan" sh -c "$BIN/hl-eval score --quiet $TOUR $tmp/live1.lcmlog | grep -q '^demo stops=128 '"
check "live: two lcm-logplayer replays give identical POSE events" \
    sh -c "test -s $tmp/live1.POSE && cmp -s $tmp/live1.POSE $tmp/live2.POSE"
check "live and batch replays give identical POSE events" cmp -s "$tmp/live1.POSE" "$tmp/run1.POSE"

# ---- requests: houghloc-goto against the daemon, with and without a key -------------------
(umask 077; printf '%064x\n' 7 >"$tmp/key"; printf '%064x\n' 8 >"$tmp/wrong.key")
cp "$tmp/key" "$tmp/open.key"; chmod 644 "$tmp/open.key"
rejects "a key file readable by others is refused at start" 1 "chmod 600" $D --set auth.key_file="$tmp/open.key" --map "$tmp/k.map" --lcm-url "$url"
$D --fresh-map --map "$tmp/k.map" --lcm-url "$url" --set auth.key_file="$tmp/key" 2>"$tmp/k.err" &
daemon=$!; pids="$pids $daemon"
wait_ready "$tmp/k.err"
G="$BIN/houghloc-goto --lcm-url $url --timeout 5"
rejects "goto, signed, inside the fence: no robot is connected (exit 4)" 4 "NO_ROBOT" $G --key "$tmp/key" 1.5 -2
rejects "goto outside the geofence: REJECTED_FENCE (exit 3)" 3 "REJECTED_FENCE" $G --key "$tmp/key" 50 0
rejects "goto unsigned to a daemon with a key: REJECTED_AUTH (exit 3)" 3 "REJECTED_AUTH" $G 1 1
rejects "goto signed with the wrong key: REJECTED_AUTH (exit 3)" 3 "REJECTED_AUTH" $G --key "$tmp/wrong.key" 1 1
kill -TERM $daemon; wait $daemon
check "the daemon with a key stops cleanly" test $? -eq 0
check "refused requests are logged" grep -q 'REJECTED_AUTH' "$tmp/k.err"
check "with a key, the request state file sits beside the map" \
    grep -q '^hlseq 1 [0-9]* [0-9a-f]\{8\}$' "$tmp/requests.seq"
cp "$tmp/requests.seq" "$tmp/requests.seq.good"
printf 'hlseq 1 17\n' >"$tmp/requests.seq"
rejects "a request state file cut short stops the start, saying how to reset it" 1 \
    "request state $tmp/requests.seq: cut short\|request state $tmp/requests.seq: malformed" \
    $D --map "$tmp/k.map" --lcm-url "$url" --set auth.key_file="$tmp/key"
check "... naming the way out" grep -q "remove the file" "$tmp/err"
mv "$tmp/requests.seq.good" "$tmp/requests.seq"
rejects "goto with no daemon times out (exit 6)" 6 "no reply from houghlocd" $BIN/houghloc-goto --lcm-url "$url" --timeout 0.3 1 1

# ---- a channel prefix: robots sharing one network hear only their own channels ----------
$D --fresh-map --map "$tmp/p.map" --lcm-url "$url" --prefix robot7/ 2>"$tmp/p.err" &
daemon=$!; pids="$pids $daemon"
wait_ready "$tmp/p.err"
rejects "the daemon answers on its prefixed channels" 4 "NO_ROBOT" $G --prefix robot7/ 1 1
rejects "... and not on the bare ones" 6 "no reply from houghlocd" $BIN/houghloc-goto --lcm-url "$url" --timeout 0.5 1 1
kill -TERM $daemon; wait $daemon

[ $fail -eq 0 ]
