#!/bin/sh
# tests/golden/capture.sh - records tests/golden/arcos.capture, the ARCOS golden's input:
# houghloc-sim --capture writes every byte it sends while houghlocd connects (the SYNC
# handshake, OPEN) and makes its sounding on connect (tests/golden/arcos.conf), and a
# second of SIPs after it. Timing on a live link varies from run to run, so a new capture
# differs from the last: run it (make golden-capture) only when the robot's side of the
# protocol changed, then make golden.
#   sh tests/golden/capture.sh [FILE]    (default: tests/golden/arcos.capture)
set -u
BIN=${BUILD:-build}/bin
G=tests/golden
out=${1:-$G/arcos.capture}
for p in houghlocd houghloc-sim; do
    [ -x "$BIN/$p" ] || { echo "capture: no $BIN/$p (run make first)" >&2; exit 1; }
done
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill $p 2>/dev/null; done; rm -rf "$tmp"' EXIT

# lines FILE TEXT TENTHS: until FILE has a line with TEXT, at most TENTHS tenths of a second
lines() {
    w=0
    until grep -q -- "$2" "$1" 2>/dev/null; do
        [ $w -ge "$3" ] && { echo "capture: no '$2' in $1: $(tail -3 "$1")" >&2; exit 1; }
        sleep 0.1; w=$((w + 1))
    done
}

"$BIN/houghloc-sim" --port 0 --speed 10 --no-truth --capture "$tmp/arcos.capture" 2>"$tmp/sim.err" &
sim=$!; pids="$pids $sim"
lines "$tmp/sim.err" "listening on" 50
port=$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$tmp/sim.err")
"$BIN/houghlocd" --config $G/arcos.conf --set robot.link=tcp:127.0.0.1:$port \
    --set daemon.log_level=debug --lcm-url memq:// --fresh-map --map "$tmp/map" 2>"$tmp/d.err" &
daemon=$!; pids="$pids $daemon"
lines "$tmp/d.err" "scan 1 (seq 1)" 300
sleep 0.1                               # a second of robot time (10 SIPs) after it
kill $sim; wait $sim                    # the capture ends with the connection
kill $daemon; wait $daemon
pids=""
grep -q -- "--capture: .* written" "$tmp/sim.err" || { echo "capture: $(tail -2 "$tmp/sim.err")" >&2; exit 1; }
mv "$tmp/arcos.capture" "$out"
echo "$out: $(wc -c <"$out") bytes"
