#!/bin/sh
# power.sh - power-cut trials of the live robot (docs/results/reliability.md, "Power
# cut"): houghlocd drives houghloc-sim through tools/demo/lab.route and is killed with
# SIGKILL at a seeded random instant, RUNS times, each time restarted on the same map
# file (no --fresh-map) with the simulator (and its robot's odometry) still running.
# After every kill:
#   - the map file loads (`houghlocd --check-map`, exit 0), and the next daemon starts on
#     it and reconnects to the robot;
#   - the scans lost, i.e. the scans the daemon had published as POSE before the kill
#     (its debug line "scan N (seq S): ..." follows each POSE publish; the map file counts
#     scans over restarts) minus the scans the file holds, are at most daemon.save_every;
#     the file is saved every save_every scans that changed the map, so a REJECTED_WILD
#     scan (which changes nothing) may add to the lost scans but never to the lost map.
# The instants: half the runs uniform over KILL_MAX_MS once the robot is connected and its
# pose set (below); a quarter just after a save (within 50 ms of the daemon's "map saved"
# line); a quarter during a save: the daemon runs under strace with every fsync delayed by
# 250 ms (the temporary file's and the folder's), and is killed 0..500 ms after PATH.tmp
# appears, so before the rename, between it and the folder's fsync, or just after.
#
# A restarted daemon resumes at the pose of the last saved scan (the file's), and the
# robot went on driving after that save. The distance between the file's pose and the
# truth is reported ("restart_error"), and whether the restarted daemon found the robot:
# the robot sounds on connecting (robot.sound_on_connect, as in service), and the pose
# the daemon gives that scan is "found" when it lies within FOUND_MM of the GROUND_TRUTH
# the standing robot sends (the position alone: the sounding turns the robot in place).
# The daemon runs with its defaults for finding a lost robot (the LOST state's keys);
# LOST_KEYS adds "key = value" lines to its [slam] section (for example
# "search_every = 1" "lost_after = 2"). When it did not find the robot, as an operator
# would, the restart is told where the robot stands (houghloc-ctl set-pose at the truth)
# before the tour goes on: left alone, the estimate would fall further behind with every
# kill and the tour end against the furniture.
#
#   RUNS=100 SAVE_EVERY=2 SPEED=20 TRIALS_SEED=1 KILL_MAX_MS=3000 FOUND_MM=500 BUILD=build
#
# Progress on stderr; the last stdout line:
#   kill9=<loadable>/<runs> save_period=<n> max_lost_scans=<k> found=<f>/<restarts>
#   restart_error_mm=<median>
# Exit 0 when every run's map loaded, every restart reconnected and no run lost more than
# one save period of integrations.
set -u
BIN=${BUILD:-build}/bin
RUNS=${RUNS:-100}
EVERY=${SAVE_EVERY:-2}
SPEED=${SPEED:-20}
SEED=${TRIALS_SEED:-1}
MAX_MS=${KILL_MAX_MS:-3000}
FOUND_MM=${FOUND_MM:-500}
ROUTE=tools/demo/lab.route

say() { echo "power: $*" >&2; }
for p in houghlocd houghloc-sim houghloc-goto houghloc-ctl hl-eval; do
    [ -x "$BIN/$p" ] || { say "no $BIN/$p (run make BUILD=${BUILD:-build} first)"; exit 1; }
done
command -v lcm-logger >/dev/null || { say "lcm-logger is missing (apt-get install liblcm-bin)"; exit 1; }
have_strace=1
command -v strace >/dev/null || {
    have_strace=0
    say "strace is missing (apt-get install strace): the kills during a save become kills" \
        "after one"
}

# A port and an LCM group of this run's own (tests use 20000..21499 and 7700..9399).
n=$(($$ % 400))
PORT=$((23000 + n))
URL="udpm://239.255.77.1:$((9500 + n))?ttl=0&recv_buf_size=4194304"
T=$(mktemp -d)
MAP=$T/map.hlmap
pids="" driver="" daemon="" spid=""
cleanup() {
    for p in $driver $daemon $spid $pids; do kill -9 "$p" 2>/dev/null; done
    wait 2>/dev/null
    if [ -n "${TRIALS_KEEP:-}" ]; then say "files kept in $T"; else rm -rf "$T"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

set -- $(sed -n 's/#.*//; s/^start //p' "$ROUTE")
sx=$1 sy=$2 sh=$3
sed 's/#.*//' "$ROUTE" | grep -v '^start\|^ *$' >"$T/route"   # comments (whole-line or trailing) dropped
nroute=$(wc -l <"$T/route")
echo 1 >"$T/next"
cat >"$T/conf" <<EOF
; written by tools/lab/trials/power.sh
[lcm]
url = $URL
[daemon]
map_file = $MAP
save_every = $EVERY
log_level = debug
[slam]
$(for kv in ${LOST_KEYS:-}; do echo "$kv"; done)
[start]
x_m = $sx
y_m = $sy
heading_deg = $sh
[fence]
rect = -1,-1,11,9
[robot]
link = tcp:127.0.0.1:$PORT
profile = bonnie
sound_on_connect = true
[calibration]
gain_q16 = 70124
offset_mm = -35
EOF

rand=$SEED
next_rand() {   # a 31-bit LCG, as tests/integration/crash_trials.sh: reproducible delays
    rand=$(( (rand * 1103515245 + 12345) % 2147483648 ))
    r=$(( rand / 65536 ))
}
msleep() { sleep "$(printf '%d.%03d' $(($1 / 1000)) $(($1 % 1000)))"; }
count() { grep -c -- "$1" "$2" 2>/dev/null || true; }   # lines of $2 holding $1

# The tour, one destination after another, continuing across restarts ($T/next). Killed
# (TERM) with the daemon: the houghloc-goto under way goes with it.
drive() {
    trap 'kill $g 2>/dev/null; exit 0' TERM
    g=""
    while :; do
        k=$(cat "$T/next")
        # shellcheck disable=SC2046
        "$BIN/houghloc-goto" --lcm-url "$URL" --timeout 30 $(sed -n "${k}p" "$T/route") \
            >"$T/goto.out" 2>&1 &
        g=$!
        wait $g
        rc=$?
        [ $rc -eq 4 ] && { sleep 0.2; continue; }    # the robot is not connected yet
        echo $((k % nroute + 1)) >"$T/next"
        echo $rc >>"$T/goto.rc"
        [ $rc -eq 0 ] || tail -n 1 "$T/goto.out" >>"$T/goto.failed"
    done
}

start_daemon() {    # start_daemon [strace]: houghlocd on the kept map, pid in $daemon
    : >"$T/d.err"
    if [ "${1:-}" = strace ]; then
        strace -f --seccomp-bpf -e trace=fsync -e inject=fsync:delay_enter=250000 \
            -o "$T/strace.out" -- "$BIN/houghlocd" --config "$T/conf" 2>"$T/d.err" &
        spid=$!
        daemon=""
        w=0
        # strace's child once it runs houghlocd (strace forks short-lived children of
        # its own first, to probe the kernel)
        while [ -z "$daemon" ] && [ $w -lt 300 ]; do
            for p in $(cat "/proc/$spid/task/$spid/children" 2>/dev/null); do
                [ "$(cat "/proc/$p/comm" 2>/dev/null)" = houghlocd ] && daemon=$p
            done
            [ -n "$daemon" ] || { sleep 0.01; w=$((w + 1)); }
        done
    else
        "$BIN/houghlocd" --config "$T/conf" 2>"$T/d.err" &
        daemon=$!
        spid=""
    fi
}
connected() {   # connected TENTHS: until this run's daemon says the robot is connected
    w=0
    until grep -q "robot 'houghloc-sim' .* connected" "$T/d.err" 2>/dev/null; do
        [ $w -ge "$1" ] && return 1
        kill -0 "$daemon" 2>/dev/null || return 1
        sleep 0.1; w=$((w + 1))
    done
}
wait_until() {  # wait_until HUNDREDTHS COMMAND...: until COMMAND succeeds, polled every 10 ms
    lim=$1; shift
    w=0
    until "$@"; do
        [ $w -ge "$lim" ] && return 1
        sleep 0.01; w=$((w + 1))
    done
}
true_pose() {    # true_pose: "X,Y,DEG", the GROUND_TRUTH the robot sends now (it stands)
    for t in 0.3 0.6 1.2; do
        lcm-logger -q -f -c GROUND_TRUTH --lcm-url="$URL" "$T/truth.lcmlog" >/dev/null 2>&1 &
        probe=$!
        sleep $t
        kill -INT $probe; wait $probe
        "$BIN/hl-eval" truth "$T/truth.lcmlog" 2>/dev/null && return 0
    done
    return 1
}
saves_beyond() { [ "$(count 'map saved to' "$T/d.err")" -gt "$saves0" ]; }
# first_scan: "STATUS X Y" of this daemon's first scan (its debug line), or nothing yet
first_scan() {
    sed -n 's/^<7>houghlocd: scan [0-9]* (seq [0-9]*): \([A-Z_]*\) at (\([-0-9.]*\), \([-0-9.]*\)) m.*/\1 \2 \3/p' \
        "$T/d.err" | head -n 1
}
scanned() { [ -n "$(first_scan)" ]; }
tmp_exists() { [ -e "$MAP.tmp" ]; }

lcm-logger -q -f -c POSE --lcm-url="$URL" "$T/run.lcmlog" >/dev/null 2>&1 &
logger=$!
"$BIN/houghloc-sim" --port $PORT --speed "$SPEED" --seed "$SEED" --start "$sx,$sy,$sh" \
    --lcm-url "$URL" 2>"$T/sim.err" &
sim=$!
pids="$sim $logger"
w=0
until grep -q "listening on" "$T/sim.err"; do
    [ $w -lt 50 ] || { say "houghloc-sim did not listen: $(cat "$T/sim.err")"; exit 1; }
    sleep 0.1; w=$((w + 1))
done
say "$RUNS runs, save_every=$EVERY, robot at ${SPEED}x, seed $SEED, port $PORT, files $T"

t0=$(date +%s)
restarts=0 found=0
i=0 mid_tmp=0 loadable=0 max_lost=0 max_behind=0 logged=0 mid=0 after=0 uniform=0 empty=0 bad=0
prev_ok=1 prev_desc="" filepose=""
while [ $i -lt "$RUNS" ]; do
    i=$((i + 1))
    next_rand
    mode=$((r % 4))
    [ $mode -eq 3 ] && [ $have_strace -eq 0 ] && mode=2
    rm -f "$T/strace.out"
    if [ $mode -eq 3 ]; then start_daemon strace; else start_daemon; fi
    # the previous kill counts as survived once this restart on its map reconnects
    if connected 100; then
        [ $i -gt 1 ] && [ $prev_ok -eq 1 ] && loadable=$((loadable + 1))
    else
        [ $i -gt 1 ] && say "run $((i - 1)): $prev_desc; the restarted daemon did not" \
            "reconnect: $(tail -n 2 "$T/d.err" | tr '\n' ' ')"
        [ $i -gt 1 ] && bad=$((bad + 1))
    fi
    loaded=$(sed -n 's/.*houghlocd: map .*: [0-9]* vectors, \([0-9]*\) scans$/\1/p' "$T/d.err" |
        head -n 1)
    loaded=${loaded:-0}
    # the operator's word: where the robot stands. It stopped when the killed daemon's
    # connection closed and stands still until told to move; GROUND_TRUTH goes out only
    # to a connected client, so it is heard now, on a recording of its own (a lagging
    # logger cannot hand over a pose from before the robot stopped).
    truth="" e=""
    [ $i -gt 1 ] && truth=$(true_pose)
    [ $i -gt 1 ] && [ -z "$truth" ] && say "run $i: no GROUND_TRUTH heard: the pose is not set"
    if [ -n "$filepose" ] && [ -n "$truth" ]; then
        e=$(echo "$filepose $truth" | tr ',' ' ' |
            awk '{ printf "%d", sqrt(($1 - $3) ^ 2 + ($2 - $4) ^ 2) * 1000 + 0.5 }')
        echo "$e" >>"$T/restart_error"
    fi
    # the sounding made on connecting: did the restarted daemon find the robot?
    here=no
    if [ -n "$truth" ]; then
        restarts=$((restarts + 1))
        wait_until 1000 scanned || say "run $i: no scan from the sounding on connecting"
        set -- $(first_scan) $(echo "$truth" | tr ',' ' ')
        if [ $# -ge 5 ]; then
            off=$(echo "$2 $3 $4 $5" | awk '{ printf "%d", sqrt(($1 - $3) ^ 2 + ($2 - $4) ^ 2) * 1000 + 0.5 }')
            echo "$1 $off ${e:-0}" >>"$T/found"
            [ "$off" -le "$FOUND_MM" ] && here=yes found=$((found + 1))
        fi
    fi
    if [ -n "$truth" ] && [ $here = no ]; then
        # shellcheck disable=SC2046
        "$BIN/houghloc-ctl" --lcm-url "$URL" --timeout 5 set-pose $(echo "$truth" | tr ',' ' ') \
            >"$T/ctl.out" 2>&1 || say "run $i: set-pose $truth: $(tail -n 1 "$T/ctl.out")"
    fi
    drive &
    driver=$!
    saves0=$(count 'map saved to' "$T/d.err")
    next_rand
    case $mode in
    0 | 1) how="at random"; uniform=$((uniform + 1)); msleep $((r % (MAX_MS + 1))) ;;
    2) how="after a save"; wait_until 800 saves_beyond; msleep $((r % 51)) ;;
    3) how="during a save"; wait_until 800 tmp_exists; msleep $((r % 501)) ;;
    esac
    if [ -z "$daemon" ] || ! kill -KILL "$daemon"; then
        say "run $i: no daemon to kill (strace did not start it?)"
        [ -n "$spid" ] && kill -KILL "$spid"
        bad=$((bad + 1))
    fi
    if [ -n "$spid" ]; then
        wait "$spid" 2>/dev/null    # strace ends with its tracee (the daemon is not our child)
    else
        wait "$daemon" 2>/dev/null
    fi
    kill -TERM "$driver" 2>/dev/null
    wait "$driver" 2>/dev/null
    daemon="" spid="" driver=""
    # killed inside a save: PATH.tmp left behind (before the rename), or an fsync the
    # kill interrupted (strace ends its line "= ?", or says "unfinished")
    in_save=0
    if tmp_exists; then
        in_save=1 mid_tmp=$((mid_tmp + 1))
    elif [ -e "$T/strace.out" ] && grep -q 'fsync(.*\(unfinished\|= ?$\)' "$T/strace.out"; then
        in_save=1       # the new file is in place: its folder's fsync was cut
    fi
    [ $in_save -eq 1 ] && mid=$((mid + 1))
    [ $mode -eq 2 ] && after=$((after + 1))

    # the last scan the daemon published, counted over restarts as the map file does
    last=$(sed -n 's/^<7>houghlocd: scan \([0-9]*\) (seq.*/\1/p' "$T/d.err" | tail -n 1)
    last=${last:-$loaded}
    logged=$((logged + last - loaded))
    if [ ! -e "$MAP" ]; then
        saved=0
        info="no map file yet"
        empty=$((empty + 1))
        rc=0
    else
        info=$("$BIN/houghlocd" --config "$T/conf" --check-map 2>&1)
        rc=$?
        saved=$(echo "$info" | sed -n 's/.* \([0-9]*\) scans,.*/\1/p')
    fi
    lost=$((last - ${saved:-0}))
    filepose=$(echo "$info" | sed -n 's/.* pose (\(.*\), \(.*\)) m .*/\1 \2/p')
    # integrations (scans that changed the map) not in the file
    behind=$(awk -v s="${saved:-0}" '$2 == "scan" && $3 > s && /, changed$/ { n++ }
                                     END { print n + 0 }' "$T/d.err")
    [ $lost -gt $max_lost ] && max_lost=$lost
    [ "$behind" -gt $max_behind ] && max_behind=$behind
    inside=""
    [ $in_save -eq 1 ] && inside="inside the save, "
    prev_desc="killed $how (${inside}$last scans published, file holds ${saved:-?})"
    prev_ok=1
    if [ $rc -ne 0 ] || [ -z "$saved" ]; then
        say "run $i: $prev_desc: the map file does not load: $info"
        prev_ok=0 bad=$((bad + 1))
    elif [ "$behind" -gt "$EVERY" ]; then
        say "run $i: $prev_desc: $behind integrations lost, more than save_every=$EVERY"
        prev_ok=0 bad=$((bad + 1))
    fi
    rm -f "$MAP.tmp"    # (the daemon truncates a stale one; removed so the next run sees its own)
    [ $((i % 10)) -eq 0 ] && say "$i runs, $(($(date +%s) - t0)) s: $((loadable + prev_ok)) good," \
        "worst loss $max_lost scans ($max_behind integrations), $mid inside a save"
done

# The last kill: a final restart must reconnect, and stop cleanly on SIGTERM.
start_daemon
if connected 100; then
    [ $prev_ok -eq 1 ] && loadable=$((loadable + 1))
    kill -TERM "$daemon"; wait "$daemon"; rc=$?
    [ $rc -eq 0 ] || { say "the final daemon exited $rc on SIGTERM"; bad=$((bad + 1)); }
else
    say "run $RUNS: $prev_desc; the restarted daemon did not reconnect"
    bad=$((bad + 1))
fi
daemon=""
final=$("$BIN/houghlocd" --config "$T/conf" --check-map 2>&1) ||
    { say "the final map does not load: $final"; bad=$((bad + 1)); }
kill -TERM $sim; wait $sim
sleep 0.3
kill -INT $logger; wait $logger 2>/dev/null
pids=""

# Cross-check of the scan counting: every POSE the logger heard against the scans the
# daemons' debug lines counted (a POSE is published just before its line).
"$BIN/hl-eval" extract "$T/run.lcmlog" POSE "$T/pose.bin" >/dev/null 2>&1
pose_bytes=$(wc -c <"$T/pose.bin" 2>/dev/null || echo 0)
poses=$((pose_bytes / 69))     # 4-byte length + 65-byte pose_t per POSE
arrived=$(grep -c '^0$' "$T/goto.rc" 2>/dev/null || echo 0)
answered=$(wc -l <"$T/goto.rc" 2>/dev/null || echo 0)
say "$RUNS kills in $(($(date +%s) - t0)) s: $uniform at random, $after just after a save," \
    "$mid inside a save ($mid_tmp before its rename), $empty before any save;" \
    "$arrived of $answered destinations answered arrived"
errs=$(sort -n "$T/restart_error" 2>/dev/null | awk '{ a[NR] = $1 } END {
    if (NR) printf "median %d mm, max %d mm over %d restarts", a[int((NR + 1) / 2)], a[NR], NR }')
say "restart_error (the file's pose against the truth at the kill): ${errs:-none}"
# found: within FOUND_MM after the sounding on connecting; by how far the robot had
# moved from its saved pose (restart_error), and the status of that first scan
if [ -s "$T/found" ]; then
    awk -v lim="$FOUND_MM" '{
            band = $3 <= 500 ? "moved <= 0.5 m" : $3 <= 2000 ? "moved 0.5-2 m" : "moved > 2 m"
            n[band]++; if ($2 <= lim) f[band]++; st[$1]++
        } END {
            for (b in n) printf "power: found %d of %d restarts that had %s\n", f[b], n[b], b
            for (s in st) printf "power: first scan %s: %d\n", s, st[s]
        }' "$T/found" >&2
fi
say "found after a restart: $found of $restarts (within $FOUND_MM mm of the truth)"
restart_median=$(sort -n "$T/restart_error" 2>/dev/null | awk '{ a[NR] = $1 } END {
    if (NR) print a[int((NR + 1) / 2)]; else print "-" }')
say "scans: $logged counted from the daemons' logs, $poses POSE in the log; worst loss" \
    "$max_lost scans, $max_behind integrations (save_every=$EVERY)"
if [ $poses -gt $logged ]; then
    # a kill between a POSE and its line: count the worst case against us
    say "$((poses - logged)) POSE more than the logs counted: added to the worst loss"
    max_lost=$((max_lost + poses - logged))
fi
[ $max_lost -le "$EVERY" ] || say "the worst loss, $max_lost scans, is more than save_every=$EVERY:" \
    "REJECTED_WILD scans, which change nothing, do not count towards a save"
echo "kill9=$loadable/$RUNS save_period=$EVERY max_lost_scans=$max_lost found=$found/$restarts restart_error_mm=$restart_median"
[ $bad -eq 0 ] && [ $loadable -eq "$RUNS" ] && [ $max_behind -le "$EVERY" ]
