#!/bin/sh
# link.sh - link-fault trials of the live robot (docs/results/reliability.md, "Link
# faults"): one houghlocd drives houghloc-sim through tools/demo/lab.route (a background
# driver sends each destination until it is ARRIVED) while the simulated robot injects,
# EPISODES times each:
#   drop     the connection closed (houghloc-sim --drop-every)
#   garbage  random bytes before SIPs (--garbage-every)
#   corrupt  SIPs with a wrong checksum (--corrupt-every)
#   stall    wheels that stop turning (--stall-after): the destination under way must fail
#            naming the stall, and the daemon go on
#   mute     (only with MUTE_EPISODES > 0) a one-way loss: no SIP reaches the daemon
#            while the robot still obeys (--mute-after 60, 3 s after the simulator starts
#            at 20x): the daemon must send it STOP before it closes the silent link (the
#            simulator counts a STOP taken while muted), and connect again; a robot that
#            moved unseen is lost until soundings find it, and refuses destinations
#            meanwhile. Off by default: the link's silence is wall-clock time, so at 20x a
#            muted robot drives blind 20 times longer than a real one would, and a silence
#            scaled down to match is one a loaded machine reaches by itself; the pose over
#            the run then says more about the time scale than about the daemon
#            (docs/results/reliability.md). tests/integration/test_link_loss.sh covers the
#            one-way loss at real speed.
#   restart  the robot killed (SIGKILL of houghloc-sim) and started again where it truly
#            stood (`hl-eval truth`), its odometry back at zero
# An episode is survived when afterwards the daemon is running, is connected again (drop,
# stall, mute, restart: a new "connected" line, after the backoff), counted it (STATUS
# bad_packets for garbage and corrupt; reconnections and "robot link:" lines for the
# others) and kept its map (STATUS map_vectors never smaller than before). Garbage and
# corrupt episodes arrive several a second in one stream: they are judged together.
# Then the tour must be finished (every destination ARRIVED at least once in order;
# failures only from a lost link or a stall), and the pose kept (hl-eval live over the
# whole run: no wild pose accepted). Last, RECONNECTS drops in a row (--drop-every 2, the
# robot idle): the daemon's open fds and VmRSS after the 10th and after the last
# reconnection must not grow.
#
#   EPISODES=20 MUTE_EPISODES=0 RECONNECTS=100 SPEED=20 TRIALS_SEED=1 BUILD=build
#
# Progress on stderr; stdout: one line per kind, the fd/RSS line, and last
#   link=<survived>/<runs>
# where runs counts the fault episodes injected (the RECONNECTS drops not included).
set -u
BIN=${BUILD:-build}/bin
EPISODES=${EPISODES:-20}
MUTE_EPISODES=${MUTE_EPISODES:-0}
RECONNECTS=${RECONNECTS:-100}
SPEED=${SPEED:-20}
SEED=${TRIALS_SEED:-1}
ROUTE=tools/demo/lab.route

say() { echo "link: $*" >&2; }
case $RECONNECTS in
*[!0-9]* | '' | ? | 10) say "RECONNECTS must be a whole number from 11 up (the fds and VmRSS after the 10th reconnection are compared with the last), not '$RECONNECTS'"; exit 2 ;;
esac
for p in houghlocd houghloc-sim houghloc-goto hl-eval; do
    [ -x "$BIN/$p" ] || { say "no $BIN/$p (run make BUILD=${BUILD:-build} first)"; exit 1; }
done
command -v lcm-logger >/dev/null || { say "lcm-logger is missing (apt-get install liblcm-bin)"; exit 1; }

# A port and an LCM group of this run's own (tests use 20000..21499 and 7700..9399,
# power.sh 23000..23399 and 9500..9899).
n=$(($$ % 400))
PORT=$((23500 + n))
URL="udpm://239.255.77.2:$((9900 + n))?ttl=0&recv_buf_size=4194304"
T=$(mktemp -d)
LOG=$T/run.lcmlog
sim="" daemon="" driver="" logger=""
cleanup() {
    for p in $driver $daemon $sim $logger; do kill -9 "$p" 2>/dev/null; done
    wait 2>/dev/null
    if [ -n "${TRIALS_KEEP:-}" ]; then say "files kept in $T"; else rm -rf "$T"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

set -- $(sed -n 's/#.*//; s/^start //p' "$ROUTE")
pose="$1,$2,$3"
start_pose=$pose   # the daemon starts there too: hl-eval live lays the truth on it
# one destination a line, its comment (whole-line or trailing) dropped
sed 's/#.*//' "$ROUTE" | grep -v '^start\|^ *$' >"$T/route"
nroute=$(wc -l <"$T/route")
. tools/houghloc-sim/daemon_conf.sh
write_lab_robot_conf "$T/conf" "$1" "$2" "$3"
printf '[daemon]\nmap_file = %s\n' "$T/map.hlmap" >>"$T/conf"
# With mute episodes, the link's silence (wall-clock time) is scaled to the robot's: the
# default 2 s would let a muted robot drive on blind for 2 x SPEED s of its own time (40 s
# at 20x: metres past its destination, into walls). 4 s of the robot's time (200 ms at
# 20x; the key's least is 100 ms).
silence_ms=$((4000 / SPEED > 100 ? 4000 / SPEED : 100))
[ "$MUTE_EPISODES" -gt 0 ] || silence_ms=2000
printf '[link]\nsilence_ms = %s\n' "$silence_ms" >>"$T/conf"

count() {       # count TEXT FILE: the lines of FILE holding TEXT (0 if no FILE yet)
    c=$(grep -c -- "$1" "$2" 2>/dev/null)
    echo "${c:-0}"
}
reconnects() { count "robot 'houghloc-sim' .* connected" "$T/d.err"; }
wait_until() {  # wait_until TENTHS COMMAND...: until COMMAND succeeds, polled every 0.1 s
    lim=$1; shift
    w=0
    until "$@"; do
        [ $w -ge "$lim" ] && return 1
        sleep 0.1; w=$((w + 1))
    done
}
at_least() { [ "$("$1")" -ge "$2" ]; }     # at_least FUNCTION N
logged() {      # logged WHAT: hl-eval WHAT LOG, tried again while the logger is
    # halfway through writing an event (it writes every 100 ms; hl-eval refuses a log
    # that ends inside one)
    for try in 1 2 3 4 5 6 7 8 9 10; do
        "$BIN/hl-eval" "$1" "$LOG" 2>/dev/null && return 0
        sleep 0.05
    done
    return 1
}
status_of() {   # status_of KEY: KEY in the last STATUS the logger has written
    logged status | tr ' ' '\n' | sed -n "s/^$1=//p"
}
now_ms() { echo $(($(date +%s%N) / 1000000)); }
median_max() {  # median_max N...: "median M max X"
    echo "$@" | tr ' ' '\n' | sort -n |
        awk 'NF { a[++n] = $1 } END { if (n) printf "median %d max %d", a[int((n + 1) / 2)], a[n] }'
}

sims=0 nudged=0
start_sim() {   # start_sim OPTIONS...: the robot at $pose, with these faults
    # GROUND_TRUTH is in whole millimetres, so a robot that stopped right at its 250 mm
    # clearance may come back 249 mm from the wall, which --start refuses: then it is set
    # down 10 or 20 mm away, in the first direction that is free (and that is said).
    for d in "0 0" "10 0" "-10 0" "0 10" "0 -10" "20 0" "-20 0" "0 20" "0 -20"; do
        at=$(echo "$pose $d" | tr ',' ' ' |
            awk '{ printf "%.3f,%.3f,%s", $1 + $4 / 1000, $2 + $5 / 1000, $3 }')
        sims=$((sims + 1))
        SIMERR=$T/sim$sims.err
        "$BIN/houghloc-sim" --port $PORT --speed "$SPEED" --seed $((SEED + sims)) --start "$at" \
            --lcm-url "$URL" "$@" 2>"$SIMERR" &
        sim=$!
        wait_until 50 grep -qs "listening on\|not in free space" "$SIMERR"
        grep -q "not in free space" "$SIMERR" || break
        wait $sim 2>/dev/null
        nudged=$((nudged + 1))
        say "houghloc-sim refused $at: $(cut -d: -f3- "$SIMERR"); moving it"
    done
    grep -q "listening on" "$SIMERR" ||
        { say "houghloc-sim $* did not listen: $(cat "$SIMERR")"; exit 1; }
}
stop_sim() {    # stop_sim SIGNAL: the robot stops; $pose becomes where it truly stood
    kill "-$1" $sim
    wait $sim 2>/dev/null
    sim=""
    # The daemon's STATUS saying FAULT (5) comes after the robot's last GROUND_TRUTH, on
    # the same network: once it is in the log, so is that pose, however late the logger.
    wait_until 50 eval '[ "$(status_of state)" = 5 ]' || say "no FAULT state after the robot stopped"
    p=$(logged truth) && pose=$p
}
injected() {    # injected TEXT: the current simulator's fault lines holding TEXT
    count "fault: .*$1" "$SIMERR"
}

# The tour: each destination sent again until ARRIVED (4: not connected, asked again);
# every answer goes to $T/answers as "PHASE INDEX EXIT TEXT".
drive() {
    trap 'kill $g 2>/dev/null; exit 0' TERM
    g="" k=1
    while :; do
        # shellcheck disable=SC2046
        "$BIN/houghloc-goto" --lcm-url "$URL" --timeout 60 $(sed -n "${k}p" "$T/route") \
            >"$T/goto.out" 2>&1 &
        g=$!
        wait $g
        rc=$?
        [ $rc -eq 4 ] && { sleep 0.1; continue; }
        echo "$(cat "$T/phase") $k $rc $(tail -n 1 "$T/goto.out")" >>"$T/answers"
        if [ $rc -eq 0 ]; then k=$((k % nroute + 1)); else sleep 0.1; fi
    done
}
arrived() { count "^$phase [0-9]* 0 " "$T/answers"; }
stalled() { count "^stall [0-9]* 5 .*stall" "$T/answers"; }

runs=0 survived=0 mv=0 bad=0
episode() {     # episode KIND OK: one episode injected, survived if OK is 1 and the map kept
    runs=$((runs + 1))
    m=$(status_of map_vectors)
    if ! kill -0 "$daemon" 2>/dev/null; then
        say "$1: the daemon is gone: $(tail -n 3 "$T/d.err" | tr '\n' ' ')"; bad=1
    elif [ -z "$m" ]; then
        say "$1: no STATUS readable in the log"; bad=1
    elif [ "$m" -lt $mv ]; then
        say "$1: map_vectors fell from $mv to $m"; bad=1
    elif [ "$2" -eq 1 ]; then
        survived=$((survived + 1)) k_ok=$((k_ok + 1))
    fi
    mv=${m:-$mv}
}
begin_kind() {  # begin_kind KIND: the episodes that follow are of this kind
    phase=$1 k_ok=0 k_runs=$runs t_kind=$(date +%s)
    echo "$1" >"$T/phase"
    say "$1 ..."
}
end_kind() {    # end_kind KIND WHAT: one line on stdout
    echo "link $1: survived=$k_ok/$((runs - k_runs)) $2"
    say "$1: $k_ok of $((runs - k_runs)) survived in $(($(date +%s) - t_kind)) s; $2"
}

t0=$(date +%s)
lcm-logger -q -f -c 'POSE|SONAR|STATUS|GROUND_TRUTH' --lcm-url="$URL" "$LOG" >/dev/null 2>&1 &
logger=$!
echo clean >"$T/phase"
phase=clean
start_sim
"$BIN/houghlocd" --config "$T/conf" --fresh-map 2>"$T/d.err" &
daemon=$!
wait_until 100 at_least reconnects 1 ||
    { say "the daemon did not connect: $(tail -n 3 "$T/d.err")"; exit 1; }
drive &
driver=$!
wait_until 300 at_least arrived 2 || say "clean: no two destinations reached in 30 s"
say "clean start: $(arrived) destinations reached, map_vectors $(status_of map_vectors)"
stop_sim TERM

# ---- drop: the connection closed every DROP_S s of robot time ------------------------
begin_kind drop
base=$(reconnects)
start_sim --drop-every "${DROP_S:-20}"
delays=""
e=0
while [ $e -lt "$EPISODES" ]; do
    e=$((e + 1))
    wait_until 200 at_least reconnects $((base + e)) || true  # connected for this period
    if ! wait_until 200 eval '[ "$(injected "dropping the client")" -ge $e ]'; then
        say "drop $e: no drop in 20 s"; bad=1; break
    fi
    t=$(now_ms)
    ok=0
    wait_until 100 at_least reconnects $((base + e + 1)) && ok=1
    delays="$delays $(($(now_ms) - t))"
    [ $ok -eq 1 ] || say "drop $e: no reconnection in 10 s"
    episode drop $ok
done
stop_sim TERM
end_kind drop "reconnected after (ms): $(median_max $delays), arrived=$(arrived)"

# ---- garbage and corrupt: bad bytes in the stream, counted in STATUS bad_packets -----
stream_kind() { # stream_kind KIND OPTION TEXT: EPISODES faults at least, and 3 arrivals
    begin_kind "$1"
    r0=$(reconnects)
    bp0=$(status_of bad_packets)    # the link is down: this STATUS is the last word
    start_sim "$2" "${EVERY_SIP:-40}"
    wait_until 100 at_least reconnects $((r0 + 1)) || say "$1: no reconnection"
    what=$3
    wait_until 600 eval '[ "$(injected "$what")" -ge "$EPISODES" ] && [ "$(arrived)" -ge 3 ]' ||
        say "$1: fewer than $EPISODES faults or 3 arrivals in 60 s"
    extra=$(($(reconnects) - r0 - 1))
    stop_sim TERM   # every fault is in: the daemon's STATUS on losing the link counts them
    sleep 0.3
    got=$(injected "$3")
    bp=$(status_of bad_packets)
    ok=0
    [ $((${bp:-0} - ${bp0:-0})) -ge "$got" ] && ok=1
    [ $ok -eq 1 ] || say "$1: $got injected, bad_packets only ${bp0:-?} -> ${bp:-?}"
    e=0
    while [ $e -lt "$got" ]; do e=$((e + 1)); episode "$1" $ok; done
    end_kind "$1" "bad_packets ${bp0:-?} -> ${bp:-?} for $got injected, \
reconnections $extra, arrived=$(arrived)"
}
stream_kind garbage --garbage-every "garbage bytes"
stream_kind corrupt --corrupt-every "wrong checksum"

# ---- stall: the wheels freeze; the destination fails naming the stall -----------------
begin_kind stall
e=0
while [ $e -lt "$EPISODES" ]; do
    e=$((e + 1))
    r0=$(reconnects) s0=$(stalled)
    start_sim --stall-after 1
    ok=0
    if wait_until 100 at_least reconnects $((r0 + 1)); then
        wait_until 300 at_least stalled $((s0 + 1)) && ok=1
        [ $ok -eq 1 ] ||
            say "stall $e: no destination failed with a stall: $(tail -n 1 "$T/answers")"
    else
        say "stall $e: no reconnection in 10 s"
    fi
    stop_sim TERM
    episode stall $ok
done
example=$(grep '^stall [0-9]* 5 .*stall' "$T/answers" | tail -n 1 | cut -d' ' -f4-)
end_kind stall "destinations failed naming the stall: $(stalled), e.g. \"$example\""

# ---- mute: the robot falls silent but still obeys; the daemon must stop it ------------
if [ "$MUTE_EPISODES" -gt 0 ]; then
begin_kind mute
muted_stops() { count "fault: muted: the client sent STOP" "$SIMERR"; }
stops=0
e=0
while [ $e -lt "$MUTE_EPISODES" ]; do
    e=$((e + 1))
    r0=$(reconnects)
    start_sim --mute-after "${MUTE_AFTER_S:-60}"
    ok=0
    if wait_until 200 at_least muted_stops 1; then
        wait_until 100 at_least reconnects $((r0 + 2)) && ok=1    # and connected again
        [ $ok -eq 1 ] || say "mute $e: no reconnection after the STOP"
    else
        say "mute $e: the muted robot got no STOP in 20 s: $(tail -n 1 "$T/d.err")"
    fi
    stops=$((stops + $(muted_stops)))
    stop_sim TERM
    episode mute $ok
done
sent=$(count "no packet from the robot for [0-9]* ms; stop sent" "$T/answers")
end_kind mute "STOPs taken by the muted robots: $stops, destinations failed with \"stop sent\": $sent"
fi

# ---- restart: the robot killed at a random moment, started again where it stood --------
begin_kind restart
start_sim
rand=$SEED
delays=""
e=0
while [ $e -lt "$EPISODES" ]; do
    e=$((e + 1))
    rand=$(( (rand * 1103515245 + 12345) % 2147483648 ))
    ms=$((300 + rand / 65536 % 1500))
    sleep "$(printf '%d.%03d' $((ms / 1000)) $((ms % 1000)))"
    r0=$(reconnects)
    stop_sim KILL
    t=$(now_ms)
    start_sim
    ok=0
    wait_until 100 at_least reconnects $((r0 + 1)) && ok=1
    delays="$delays $(($(now_ms) - t))"
    [ $ok -eq 1 ] || say "restart $e: no reconnection in 10 s"
    episode restart $ok
done
end_kind restart "reconnected after (ms): $(median_max $delays), arrived=$(arrived)"

# ---- the tour goes on to its end, fault-free ------------------------------------------
echo finish >"$T/phase"
phase=finish
# (the robot of the last restart drives on)
total_arrived() { count "^[a-z]* [0-9]* 0 " "$T/answers"; }
wait_until 600 at_least total_arrived "$nroute" || say "the tour did not finish in 60 s"
kill -TERM $driver; wait $driver 2>/dev/null; driver=""
tour=$(total_arrived)
# failures other than a lost link (any phase), a stall (stall phase) or a robot being
# found again after a link fault (the daemon lost, relocalizing it before it drives: a
# robot that moved unseen, or one the tracker doubts after a restart): none expected
grep -v "^[a-z]* [0-9]* 0 " "$T/answers" | grep -v "robot link lost" |
    grep -v "^stall .*stall" | grep -v "lost: the pose is unknown" >"$T/odd"
odd=$(wc -l <"$T/odd")
[ "$odd" -eq 0 ] || { say "$odd unexpected failures:"; head -n 5 "$T/odd" >&2; }
link_lost=$(grep -c "robot link lost" "$T/answers")
say "tour: $tour destinations arrived (route of $nroute), $link_lost failed on a lost link" \
    "and were sent again, $odd other failures"

# ---- RECONNECTS drops in a row: fds and memory ----------------------------------------
say "$RECONNECTS reconnections ..."
t_fd=$(date +%s)
stop_sim TERM
sleep 0.5
base=$(reconnects)
start_sim --drop-every 2
sample() {      # sample N: fds and VmRSS (kB) right after the Nth reconnection
    wait_until $((RECONNECTS * 10)) at_least reconnects $((base + $1)) ||
        { echo "- -"; return; }
    echo "$(ls "/proc/$daemon/fd" | wc -l) $(awk '/^VmRSS:/ { print $2 }' "/proc/$daemon/status")"
}
set -- $(sample 10)
fd10=$1 rss10=$2
set -- $(sample "$RECONNECTS")
fd100=$1 rss100=$2
echo "link reconnects=$RECONNECTS fds_after_10=$fd10 fds_after_$RECONNECTS=$fd100" \
    "rss_kb_after_10=$rss10 rss_kb_after_$RECONNECTS=$rss100"
say "$RECONNECTS reconnections in $(($(date +%s) - t_fd)) s: fds $fd10 -> $fd100, VmRSS $rss10 -> $rss100 kB"
growth=1
[ "$fd100" != - ] && [ "$fd100" -le "$fd10" ] &&
    [ "$rss100" -le $((rss10 + ${RSS_SLACK_KB:-256})) ] && growth=0
[ $growth -eq 0 ] || say "fds or memory grew (allowed: none, and ${RSS_SLACK_KB:-256} kB of RSS)"

# ---- the end: SIGTERM, the map loads, the pose was kept ---------------------------------
stop_sim TERM
kill -TERM $daemon; wait $daemon; rc=$?
daemon=""
[ $rc -eq 0 ] || { say "the daemon exited $rc on SIGTERM"; bad=1; }
"$BIN/houghlocd" --config "$T/conf" --check-map >"$T/check" 2>&1 ||
    { say "the map file does not load: $(cat "$T/check")"; bad=1; }
sleep 0.3
kill -INT $logger; wait $logger 2>/dev/null; logger=""
score=$("$BIN/hl-eval" live --start "$start_pose" "$LOG" 2>&1 | tail -n 1)
say "pose over the whole run: $score"
wild=$(echo "$score" | tr ' ' '\n' | sed -n 's/^wild_accepted=//p')
[ "${wild:-1}" -eq 0 ] || { say "wild poses accepted (${wild:-?}): the pose was not kept"; bad=1; }
say "$(grep -c 'robot link:' "$T/d.err") 'robot link:' lines, $(reconnects) connections in all," \
    "$(($(date +%s) - t0)) s"
[ "$tour" -ge "$nroute" ] && [ "$odd" -eq 0 ] || bad=1
echo "link=$survived/$runs"
[ $bad -eq 0 ] && [ $growth -eq 0 ] && [ $survived -eq $runs ]
