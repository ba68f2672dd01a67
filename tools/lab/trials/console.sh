#!/bin/sh
# console.sh - the Console trial: houghloc-console under the two attacks on its memory
# and its connections (docs/manual/houghloc-console.md, "Limits").
#
#   (a) memory: CONSOLE_STREAMS (64) event streams with the token stop reading (their
#       header read, then nothing: hl-console-load --mode stall) while MAP messages are
#       published for CONSOLE_SECONDS (6) s each: first 1,500-vector maps (the daemon's
#       default capacity) at 50 a second, then, to a fresh set of stalled streams, maps of
#       the largest size the wire allows (2^20 vectors, 12.6 MB each) at 4 a second. The
#       console's peak resident memory (VmHWM, /proc/PID/status) must stay at most
#       CONSOLE_PEAK_MIB (64) MiB. A reader that does read counts the maps that reached
#       the pages (a datagram of a 12.6 MB message may be lost on loopback: at least one
#       large map must arrive, or the measure means nothing).
#   (b) connections: CONSOLE_LORIS (500) slowloris connections from 127.0.0.1 (the
#       operator's own address) that never finish a request header and reconnect at once
#       when closed; meanwhile, three times, the operator signs in with the token
#       (GET /?token=, the cookie, the page: 200) and opens the event stream with the
#       token (200), each within 5 s.
#
# houghloc-console runs on a private LCM group (udpm, ttl=0, a port of its own) and a
# private HTTP port, with a token from a file of mode 0600. Progress on stderr; the last
# stdout line is
#   console console_peak_rss_mib=<m> console_operator_under_slowloris=<ok|fail>
# Exit 0 when the peak is at most CONSOLE_PEAK_MIB and the operator got in every time.
# Environment: BUILD (build), CONSOLE_BIN (another houghloc-console to measure),
# CONSOLE_STREAMS, CONSOLE_SECONDS, CONSOLE_LORIS, CONSOLE_PEAK_MIB; TRIALS_KEEP=1 keeps
# the files.
set -u
BUILD=${BUILD:-build}
BIN=$BUILD/bin
CONSOLE=${CONSOLE_BIN:-$BIN/houghloc-console}
LOAD=$BIN/hl-console-load
STREAMS=${CONSOLE_STREAMS:-64}
SECS=${CONSOLE_SECONDS:-6}
LORIS=${CONSOLE_LORIS:-500}
PEAK_MAX=${CONSOLE_PEAK_MIB:-64}

say() { echo "console: $*" >&2; }
result() { echo "console console_peak_rss_mib=$1 console_operator_under_slowloris=$2"; }
die() { say "$*"; result - fail; exit 1; }

for p in "$CONSOLE" "$LOAD"; do
    [ -x "$p" ] || die "$p is missing: make BUILD=$BUILD $p"
done
command -v curl >/dev/null || die "curl is needed"

# A port and an LCM group of this run's own (tests use 20000..21499 and 7700..9399, the
# other trials 9100..10299 and 23000..23899).
n=$(($$ % 200))
HPORT=$((24000 + n))
URL="udpm://239.255.77.3:$((10300 + n))?ttl=0&recv_buf_size=4194304"
B="http://127.0.0.1:$HPORT"
T=$(mktemp -d)
pids=""
cleanup() {
    for p in $pids; do kill -9 "$p" 2>/dev/null; done
    wait 2>/dev/null
    if [ -n "${TRIALS_KEEP:-}" ]; then say "files kept in $T"; else rm -rf "$T"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

(umask 077; head -c 16 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$T/token") ||
    die "cannot make a token"
TOKEN=$(cat "$T/token")
"$CONSOLE" --lcm-url "$URL" --listen "127.0.0.1:$HPORT" --token-file "$T/token" \
    2>"$T/console.err" &
console=$!
pids="$console"
w=0
while ! grep -q "serving" "$T/console.err" 2>/dev/null && [ $w -lt 50 ]; do sleep 0.1; w=$((w + 1)); done
grep -q "serving" "$T/console.err" || die "the console did not start: $(tail -n 1 "$T/console.err")"
hwm() { sed -n 's/^VmHWM:[[:space:]]*\([0-9]*\) kB/\1/p' "/proc/$console/status"; }
say "houghloc-console on $B, LCM $URL; resident at start $(hwm) kB"

# ---- (a) stalled streams, large maps ------------------------------------------------------
# A reader that reads: how many maps reach the pages.
curl -s -N -H "Authorization: Bearer $TOKEN" "$B/events" >"$T/reader.events" 2>/dev/null &
reader=$!
pids="$pids $reader"
phase() {   # phase NAME VECTORS RATE: stalled streams while maps of VECTORS are published
    "$LOAD" --mode stall --port "$HPORT" --token "$TOKEN" --count "$STREAMS" \
        --seconds $((SECS + 3)) >"$T/stall-$1.out" 2>"$T/stall-$1.err" &
    stall=$!
    pids="$pids $stall"
    w=0
    while ! grep -q "not reading" "$T/stall-$1.err" 2>/dev/null && [ $w -lt 100 ]; do
        sleep 0.1; w=$((w + 1))
    done
    "$LOAD" --mode maps --lcm-url "$URL" --vectors "$2" --rate "$3" --seconds "$SECS" \
        >"$T/maps-$1.out" 2>"$T/maps-$1.err"
    kill -TERM $stall 2>/dev/null
    wait $stall
    say "  $1: $(tail -n 1 "$T/stall-$1.out"); $(tail -n 1 "$T/maps-$1.out"); peak so far $(hwm) kB"
    # every stream must have been let in, or the measure would be of fewer pages
    grep -q "^stall opened=$STREAMS ok=$STREAMS\$" "$T/stall-$1.out" ||
        { say "  $1: not every stream was answered 200"; ok=0; }
}
ok=1
say "(a) $STREAMS streams that stop reading, ${SECS} s of 1,500-vector maps at 50/s"
phase default 1500 50
say "(a) $STREAMS new streams that stop reading, ${SECS} s of 2^20-vector maps at 4/s"
phase largest 1048576 4
sleep 1
kill -TERM $reader 2>/dev/null
wait $reader 2>/dev/null
peak_kb=$(hwm)
[ -n "$peak_kb" ] || die "the console is gone: $(tail -n 2 "$T/console.err")"
peak=$(( (peak_kb + 1023) / 1024 ))
maps=$(grep -c '^event: map$' "$T/reader.events")
large=$(grep '^data: {"utime"' "$T/reader.events" | awk 'length($0) > 1000000' | wc -l)
say "a reading page got $maps maps, $large of them from the largest ones"
[ "$large" -ge 1 ] || { say "no large map reached the reading page: the measure is void"; ok=0; }
say "peak resident memory ${peak} MiB (target at most $PEAK_MAX)"
[ "$peak" -le "$PEAK_MAX" ] || ok=0

# ---- (b) slowloris ------------------------------------------------------------------------
say "(b) $LORIS slowloris connections from 127.0.0.1, reconnecting, for 20 s"
"$LOAD" --mode slowloris --port "$HPORT" --count "$LORIS" --seconds 20 \
    >"$T/loris.out" 2>"$T/loris.err" &
loris=$!
pids="$pids $loris"
sleep 6     # past the header deadline: the attack at its full strength
operator=ok
for i in 1 2 3; do
    page=$(curl -s -o "$T/page.html" -w '%{http_code} %{time_total}' --max-time 5 \
        -c "$T/jar" -b "$T/jar" -L "$B/?token=$TOKEN")
    stream=$(curl -s -N -o "$T/stream.events" -w '%{http_code} %{time_starttransfer}' \
        --max-time 3 -H "Authorization: Bearer $TOKEN" "$B/events")
    say "  operator $i: the page ${page% *} in ${page#* } s, the event stream ${stream% *} in ${stream#* } s"
    [ "${page% *}" = 200 ] && grep -q '<canvas id="map">' "$T/page.html" || operator=fail
    [ "${stream% *}" = 200 ] && grep -q '^event: hello$' "$T/stream.events" || operator=fail
    sleep 3
done
wait $loris
say "  $(tail -n 1 "$T/loris.out")"
[ "$operator" = ok ] || ok=0
kill -0 $console 2>/dev/null || { say "the console died: $(tail -n 2 "$T/console.err")"; ok=0; }
kill -TERM $console 2>/dev/null
wait $console 2>/dev/null
tail -n 3 "$T/console.err" | sed 's/^/  /' >&2

result "$peak" "$operator"
[ $ok -eq 1 ]
