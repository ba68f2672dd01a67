#!/bin/sh
# Integration test of houghlocd's systemd watchdog: it is fed from the poll loop's timer,
# so a loop that stalls stops feeding it. The daemon runs with NOTIFY_SOCKET pointing at a
# unix datagram socket this test listens on (a few lines of python3 write each datagram
# with its arrival time) and WATCHDOG_USEC=200000, WATCHDOG_PID its own pid (started
# through `exec`, so the pid is known before it starts): READY=1 must arrive, then
# WATCHDOG=1 every 100 ms (half the interval, as systemd advises); SIGSTOP stalls the loop
# for a second with no WATCHDOG=1 at all, SIGCONT resumes them at once, SIGTERM gives
# STOPPING=1 and exit 0. Without WATCHDOG_USEC, or with a WATCHDOG_PID of another process,
# the watchdog is never fed. Every check counts datagrams in a time window.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -CONT $p 2>/dev/null; kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
url="udpm://239.255.76.67:$((7500 + $$ % 100))?ttl=0"

command -v python3 >/dev/null || { echo "FAIL: python3 is needed to listen on NOTIFY_SOCKET"; exit 1; }

now() { date +%s.%N; }
add() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.6f", a + b }'; }   # add X Y

listen() {  # listen NAME: a receiver on $tmp/NAME.sock writing "TIME LINE" to $tmp/NAME.notes
    python3 -u -c '
import socket, sys, time
s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
s.bind(sys.argv[1])
with open(sys.argv[2], "a", buffering=1) as out:
    while True:
        data = s.recv(4096)
        t = time.time()
        for line in data.decode("ascii", "replace").splitlines():
            out.write("%.6f %s\n" % (t, line))
' "$tmp/$1.sock" "$tmp/$1.notes" &
    pids="$pids $!"
    n=0
    while [ ! -S "$tmp/$1.sock" ] && [ $n -lt 50 ]; do sleep 0.1; n=$((n + 1)); done
    : >>"$tmp/$1.notes"
}

start() {   # start NAME WATCHDOG_USEC WATCHDOG_PID(self|N) [ARGS]: houghlocd reporting to
            # NAME.sock, its stderr in NAME.err (or wherever $errfile says)
    name=$1 usec=$2 wpid=$3
    shift 3
    listen "$name"
    NOTIFY_SOCKET=$tmp/$name.sock WD_USEC=$usec WD_PID=$wpid sh -c '
        [ -n "$WD_USEC" ] && { WATCHDOG_USEC=$WD_USEC; export WATCHDOG_USEC; }
        if [ "$WD_PID" = self ]; then WATCHDOG_PID=$$; else WATCHDOG_PID=$WD_PID; fi
        export WATCHDOG_PID
        unset WD_USEC WD_PID
        exec "$@"' houghlocd "$BIN/houghlocd" --config /dev/null --fresh-map \
        --map "$tmp/$name.map" --lcm-url "$url" "$@" 2>"${errfile:-$tmp/$name.err}" &
    daemon=$!; pids="$pids $daemon"
    n=0
    while ! grep -q ' READY=1$' "$tmp/$name.notes" && [ $n -lt 100 ]; do sleep 0.1; n=$((n + 1)); done
}

count() {   # count NAME MESSAGE FROM TO: datagrams MESSAGE that arrived in (FROM, TO]
    awk -v m="$2" -v a="$3" -v b="$4" '$2 == m && $1 > a && $1 <= b { n++ } END { print n + 0 }' \
        "$tmp/$1.notes"
}

max_gap() { # max_gap NAME FROM TO: the longest time between WATCHDOG=1 in (FROM, TO], ms
    awk -v a="$2" -v b="$3" '$2 == "WATCHDOG=1" && $1 > a && $1 <= b {
        if (p) { g = ($1 - p) * 1000; if (g > m) m = g } p = $1 }
        END { printf "%d\n", m }' "$tmp/$1.notes"
}

between() { # between VALUE LO HI
    [ "$1" -ge "$2" ] && [ "$1" -le "$3" ]
}

# ---- a healthy loop feeds the watchdog every 100 ms --------------------------------------
start wd 200000 self
check "READY=1 arrives once the daemon is ready" test "$(count wd READY=1 0 9e9)" -eq 1
sleep 1.2
t=$(now)
n=$(count wd WATCHDOG=1 "$(add "$t" -1)" "$t")
check "WATCHDOG=1 every 100 ms while the loop runs: $n in 1 s (8..12)" between "$n" 8 12
g=$(max_gap wd 0 "$t")
check "... never more than 200 ms apart (longest $g ms)" between "$g" 50 200

# ---- a stalled loop does not -------------------------------------------------------------
kill -STOP $daemon
t_stop=$(now)
sleep 1
t_cont=$(now)
kill -CONT $daemon
sleep 1.2
t_end=$(now)
n=$(count wd WATCHDOG=1 "$(add "$t_stop" 0.05)" "$t_cont")
check "no WATCHDOG=1 while the loop is stopped for 1 s: $n" test "$n" -eq 0
g=$(max_gap wd "$(add "$t_stop" -0.5)" "$t_end")
check "... a gap of the whole stall ($g ms, 950..1300)" between "$g" 950 1300
n=$(count wd WATCHDOG=1 "$t_cont" "$(add "$t_cont" 0.15)")
check "SIGCONT: WATCHDOG=1 again within 150 ms ($n)" test "$n" -ge 1
n=$(count wd WATCHDOG=1 "$(add "$t_cont" 0.1)" "$(add "$t_cont" 1.1)")
check "... then every 100 ms again: $n in 1 s (8..12)" between "$n" 8 12

# ---- a clean stop ------------------------------------------------------------------------
kill -TERM $daemon
wait $daemon
check "SIGTERM: exit 0" test $? -eq 0
sleep 0.2
check "STOPPING=1 on the way out" test "$(count wd STOPPING=1 0 9e9)" -eq 1

# ---- only the loop stalls: its log cannot be written ------------------------------------
# The daemon's stderr is a FIFO of one page that a helper holds open without reading (as a
# hung journald would): once a replay at log level debug has filled it, the loop blocks in
# a write while liblcm's receive thread runs on. The helper drains it on SIGUSR1.
mkfifo "$tmp/log.fifo"
python3 -c '
import fcntl, os, signal, sys
fd = os.open(sys.argv[1], os.O_RDWR)    # a FIFO opened read-write never blocks
fcntl.fcntl(fd, 1031, 4096)             # F_SETPIPE_SZ: one page
signal.signal(signal.SIGUSR1, lambda *a: None)
signal.pause()
with open(sys.argv[2], "wb") as out:
    while True:
        out.write(os.read(fd, 65536))
        out.flush()
' "$tmp/log.fifo" "$tmp/blocked.err" &
drainer=$!; pids="$pids $drainer"
sleep 0.3
# the global search off: it would make the 128 scans take seconds, not the drain above
errfile=$tmp/log.fifo start blocked 200000 self --set daemon.log_level=debug \
    --set slam.search_every=0 --set slam.lost_after=0
sleep 0.5
t=$(now)
n=$(count blocked WATCHDOG=1 "$(add "$t" -0.5)" "$t")
check "log blocking test: the watchdog is fed before the replay ($n in 0.5 s)" between "$n" 3 7
lcm-logplayer -s 500 -e '^(SONAR|ODOMETRY)$' -l "$url" logs/tour.lcmlog >/dev/null 2>&1
sleep 0.5
t_blocked=$(now)
sleep 1
t=$(now)
n=$(count blocked WATCHDOG=1 "$t_blocked" "$t")
check "a loop blocked on its log feeds no watchdog: $n WATCHDOG=1 in 1 s" test "$n" -eq 0
kill -USR1 $drainer
t_drain=$(now)
sleep 1.2
n=$(count blocked WATCHDOG=1 "$t_drain" "$(add "$t_drain" 0.15)")
check "... the log drained: WATCHDOG=1 again within 150 ms ($n)" test "$n" -ge 1
n=$(count blocked WATCHDOG=1 "$(add "$t_drain" 0.1)" "$(add "$t_drain" 1.1)")
check "... then every 100 ms: $n in 1 s (8..12)" between "$n" 8 12
kill -TERM $daemon
wait $daemon
check "... and it stops with exit 0" test $? -eq 0
sleep 0.2
check "... having logged every one of the 128 scans meanwhile" \
    test "$(grep -c 'houghlocd: scan [0-9]* (seq' "$tmp/blocked.err")" -eq 128

# ---- no watchdog asked for, or asked for another process: never fed ---------------------
start nowd "" self
start otherpid 200000 1
sleep 0.6
check "without WATCHDOG_USEC: READY=1 but no WATCHDOG=1" \
    test "$(count nowd READY=1 0 9e9)" -eq 1 -a "$(count nowd WATCHDOG=1 0 9e9)" -eq 0
check "with WATCHDOG_PID of another process: READY=1 but no WATCHDOG=1" \
    test "$(count otherpid READY=1 0 9e9)" -eq 1 -a "$(count otherpid WATCHDOG=1 0 9e9)" -eq 0
for p in $pids; do kill -TERM $p 2>/dev/null; done
wait 2>/dev/null

[ $fail -eq 0 ]
