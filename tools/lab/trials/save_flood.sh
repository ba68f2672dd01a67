#!/bin/sh
# save_flood.sh - the Save-flood trial: a live houghlocd replays a log at real speed twice,
# once quiet and once while hl-flood --kind save sends it SF_RATE (1,000) well-formed
# unsigned SAVE requests a second (the daemon has no key, so it takes them all), and the
# POSE latency of the two runs is compared. SAVE requests write the map at most once per
# 5 s (cycle.h, HL_CYCLE_SAVE_MIN_INTERVAL_MS), so the flood must not hold up POSE: the
# flooded run's 99th percentile must stay within 2 times the quiet run's, the map file
# the flooded daemon leaves must load (houghlocd --check-map), and the flooded daemon
# must have written no more map files than the rate allows: one per started 5 s of the
# flood, plus the quiet run's saves (daemon.save_every's and the one at the stop, which
# the rate does not hold back).
#
# POSE latency here is end to end: two lcm-loggers on this host record SONAR where the
# daemon reads it and POSE where it publishes it, and hl-eval latency pairs them by seq
# (the recorders' receipt times). Unlike STATUS compute_p99_us (flood.sh's measure, which
# starts in the SONAR handler) it counts the time a scan waits while the loop writes the
# map. The runs are measured the same way, so the recorders' own delay cancels out.
#
# The input: logs/laser.lcmlog (139 laser scans over 28 s; slam.profile laser) by default,
# played with lcm-logplayer at speed 1 (real time). Each run: houghlocd listens on a
# private ttl=0 group and publishes on a second one; the daemon starts with a fresh map.
#
# Environment: BUILD (build), SF_LOG (logs/laser.lcmlog), SF_PROFILE (laser), SF_RATE
# (1000 a second). Files of the last run stay in BUILD/trials/save_flood/. Progress on
# stderr; the last stdout line is
#   save_flood_pose_p99_ms=<x> quiet_pose_p99_ms=<y> saves=<n>
# (saves: the flooded daemon's STATUS saves: map files written, the last at its stop).
# Exit status 0 when x <= 2 y, the flooded run's map file loads and its saves are within
# the rate, 1 otherwise (the last line is printed anyway).
#
#   BUILD=build sh tools/lab/trials/save_flood.sh
set -u
BUILD=${BUILD:-build}
BIN=$BUILD/bin
LOG=${SF_LOG:-logs/laser.lcmlog}
PROFILE=${SF_PROFILE:-laser}
RATE=${SF_RATE:-1000}

say() { echo "save_flood: $*" >&2; }
x=nan y=nan saves=nan
result() { echo "save_flood_pose_p99_ms=$x quiet_pose_p99_ms=$y saves=$saves"; }
die() { say "$*"; result; exit 1; }
abs() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }

for p in houghlocd hl-flood hl-eval; do
    [ -x "$BIN/$p" ] || die "$BIN/$p is missing: make BUILD=$BUILD all lab"
done
command -v lcm-logplayer >/dev/null && command -v lcm-logger >/dev/null ||
    die "lcm-logplayer and lcm-logger are needed (Debian: liblcm-bin)"
[ -r "$LOG" ] || die "$LOG is missing (SF_LOG)"
case $RATE in *[!0-9]* | '' | 0) die "SF_RATE must be a whole number from 1 up, not '$RATE'" ;; esac

t_start=$(date +%s)
work=$(abs "$BUILD/trials/save_flood")
rm -rf "$work"
mkdir -p "$work" || die "cannot make $work"
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done' EXIT
trap 'exit 130' INT TERM

# a port pair of its own: 9600..9799 (flood.sh 9100..9499, link.sh 9900..10299)
port=$((9600 + $$ % 100 * 2))
url_in="udpm://239.255.76.69:$port?ttl=0&recv_buf_size=4194304"
url_out="udpm://239.255.76.69:$((port + 1))?ttl=0&recv_buf_size=4194304"
D="$BIN/houghlocd --config /dev/null --fresh-map --set slam.profile=$PROFILE"

wait_ready() {  # wait_ready ERRFILE: until the daemon says it is ready (10 s at most)
    n=0
    while ! grep -q 'ready:' "$1" 2>/dev/null && [ $n -lt 100 ]; do sleep 0.1; n=$((n + 1)); done
}

run() {         # run NAME FLOOD(0|1): one live replay; files $work/NAME.*
    name=$1
    lcm-logger -q -f -c 'SONAR' --lcm-url="$url_in" "$work/$name.in.lcmlog" >/dev/null 2>&1 &
    in_logger=$!
    lcm-logger -q -f -c 'POSE|STATUS' --lcm-url="$url_out" "$work/$name.out.lcmlog" >/dev/null 2>&1 &
    out_logger=$!
    pids="$pids $in_logger $out_logger"
    $D --map "$work/$name.hlmap" --lcm-url "$url_in" --lcm-out "$url_out" 2>"$work/$name.err" &
    daemon=$!; pids="$pids $daemon"
    wait_ready "$work/$name.err"
    if [ "$2" = 1 ]; then
        # bounded well past the replay's length; stopped when the replay is over
        "$BIN/hl-flood" --kind save --lcm-url "$url_in" --rate "$RATE" --seconds 600 \
            >"$work/$name.flood" 2>"$work/$name.flood.err" &
        flood=$!; pids="$pids $flood"
        sleep 0.5
    fi
    t0=$(date +%s)
    lcm-logplayer -s 1 -e '^(SONAR|ODOMETRY)$' -l "$url_in" "$LOG" >/dev/null 2>&1
    sleep 1.5           # the daemon answers the last scans
    if [ "$2" = 1 ]; then
        kill -TERM $flood; wait $flood
        say "  $(cat "$work/$name.flood")"
    fi
    kill -TERM $daemon; wait $daemon; rc=$?
    sleep 0.5
    kill -INT $in_logger $out_logger; wait $in_logger $out_logger
    say "  $name: replay took $(($(date +%s) - t0)) s, daemon exit $rc"
    return $rc
}

field() { sed -n "s/.* $2=\([^ ]*\).*/\1/p" "$1"; }   # field FILE KEY

ok=1
for run in quiet:0 flooded:1; do
    name=${run%:*} flooded=${run#*:}
    say "live replay '$name' of $LOG at real speed$([ "$flooded" = 1 ] && echo ", $RATE SAVE requests a second")"
    run "$name" "$flooded" || { say "  $name: the daemon did not stop cleanly"; ok=0; }
    "$BIN/hl-eval" latency "$work/$name.in.lcmlog" "$work/$name.out.lcmlog" >"$work/$name.latency" ||
        { say "  $name: no POSE latency"; ok=0; }
    "$BIN/hl-eval" status "$work/$name.out.lcmlog" >"$work/$name.status" || ok=0
    say "  $name: $(cat "$work/$name.latency") saves=$(field "$work/$name.status" saves)"
    say "  $name: $(grep 'stopped:' "$work/$name.err" | sed 's/^<[0-9]>houghlocd: //')"
done
x=$(field "$work/flooded.latency" p99_ms)
y=$(field "$work/quiet.latency" p99_ms)
saves=$(field "$work/flooded.status" saves)
x=${x:-nan} y=${y:-nan} saves=${saves:-nan}

if $D --map "$work/flooded.hlmap" --check-map >"$work/check.out" 2>&1; then
    say "the flooded run's map file loads: $(head -n 1 "$work/check.out")"
else
    say "the flooded run's map file does not load: $(tail -n 1 "$work/check.out")"
    ok=0
fi
sent=$(field "$work/flooded.flood" sent)
secs=$(field "$work/flooded.flood" seconds)
quiet_saves=$(field "$work/quiet.status" saves)
allowed=$(awk -v s="${secs:-0}" -v q="${quiet_saves:-0}" 'BEGIN { printf "%d", int(s / 5) + 1 + q }')
say "flooded: ${sent:-?} SAVE requests in ${secs:-?} s, $saves map files written" \
    "(allowed: $allowed, one per started 5 s and the quiet run's $quiet_saves)"
[ "$saves" != nan ] && [ "$saves" -le "$allowed" ] ||
    { say "more map files written than one per 5 s allows"; ok=0; }
awk -v x="$x" -v y="$y" 'BEGIN { exit !(x != "nan" && y != "nan" && x + 0 <= 2 * y) }' ||
    { say "POSE p99 $x ms flooded is above 2 x $y ms quiet"; ok=0; }
say "done in $(($(date +%s) - t_start)) s; files in $work"
result
[ $ok -eq 1 ]
