#!/bin/sh
# tests/golden/bad_capture.sh - a damaged capture replayed (robot.link = file:) is handled
# as the same damage on a live link: garbage between packets is counted (STATUS
# bad_packets) and skipped, the stream resyncs and publishes what the intact capture
# does; a capture cut inside a packet, one of garbage only, an empty or a missing one end
# the daemon cleanly. Never a crash, never a hang. And a fresh capture (houghloc-sim
# --capture, tests/golden/capture.sh) replays to the sounding the daemon made live.
set -u
BIN=${BUILD:-build}/bin
G=tests/golden
for p in houghlocd hl-eval; do
    [ -x "$BIN/$p" ] || { echo "FAIL: no $BIN/$p (run make first)"; exit 1; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh

# replay NAME CAPTURE: houghlocd on CAPTURE (at most 60 s); its exit code in $tmp/NAME.rc,
# its output log $tmp/NAME.lcmlog, its SONAR and ODOMETRY as the goldens' text, one line
# a message ($tmp/NAME.SONAR, $tmp/NAME.ODOMETRY).
replay() {
    timeout 60 "$BIN/houghlocd" --config $G/arcos.conf --set robot.link=file:$2 \
        --fresh-map --map "$tmp/$1.hlmap" --lcm-url memq:// \
        --lcm-out "file://$tmp/$1.lcmlog?mode=w" 2>"$tmp/$1.err"
    echo $? >"$tmp/$1.rc"
    for ch in SONAR ODOMETRY; do
        "$BIN/hl-eval" text "$tmp/$1.lcmlog" $ch "$tmp/$1.$ch" 2>/dev/null || : >"$tmp/$1.$ch"
    done
}
bad_packets() { "$BIN/hl-eval" status "$tmp/$1.lcmlog" | sed -n 's/.* bad_packets=\([0-9]*\) .*/\1/p'; }
# messages FILE: how many messages a text stream holds (one a line)
messages() { wc -l <"$1"; }
# is_prefix SHORT LONG: SHORT's messages are LONG's first ones (and there are some)
is_prefix() { [ -s "$1" ] && head -n "$(messages "$1")" "$2" | cmp -s - "$1"; }

# The offsets at which the capture's packets start (0xFA 0xFB, count, count bytes).
od -An -v -tu1 $G/arcos.capture | awk '
    { for (i = 1; i <= NF; i++) b[n++] = $i }
    END { i = 0; while (i + 2 < n && b[i] == 250 && b[i + 1] == 251) { print i; i += 3 + b[i + 2] } }' \
    >"$tmp/starts"
size=$(wc -c <$G/arcos.capture)
check "the capture parses as back-to-back ARCOS packets" test "$(wc -l <"$tmp/starts")" -gt 20

# Garbage (no 0xFA: it cannot start a packet) between every 25th packet and the next.
: >"$tmp/garbled"
prev=0
for at in $(awk 'NR > 3 && NR % 25 == 0' "$tmp/starts"); do
    tail -c +$((prev + 1)) $G/arcos.capture | head -c $((at - prev)) >>"$tmp/garbled"
    printf 'noise on the line at byte %d\r\n' "$at" >>"$tmp/garbled"
    prev=$at
done
tail -c +$((prev + 1)) $G/arcos.capture >>"$tmp/garbled"
replay garbled "$tmp/garbled"
check "garbage between packets: exit 0" test "$(cat "$tmp/garbled.rc")" -eq 0
check "... the same SONAR as the intact capture" cmp -s "$tmp/garbled.SONAR" $G/arcos.SONAR.txt
check "... the same ODOMETRY" cmp -s "$tmp/garbled.ODOMETRY" $G/arcos.ODOMETRY.txt
check "... and the garbage counted in STATUS bad_packets" test "$(bad_packets garbled)" -gt 0

# Cut in the middle of the last packet but one.
cut=$(($(tail -2 "$tmp/starts" | head -1) + 5))
head -c $cut $G/arcos.capture >"$tmp/cut"
replay cut "$tmp/cut"
check "a capture cut inside a packet: exit 0" test "$(cat "$tmp/cut.rc")" -eq 0
check "... its ODOMETRY the golden's beginning" is_prefix "$tmp/cut.ODOMETRY" $G/arcos.ODOMETRY.txt
check "... one message short of it" test "$(messages "$tmp/cut.ODOMETRY")" -lt "$(messages $G/arcos.ODOMETRY.txt)"

# A byte flipped inside a SIP: its checksum fails, the rest goes on. (The sounding does
# not: one SIP fewer puts the daemon's robot time a SIP behind what the captured robot
# answered, as a replay of any conversation diverges once its input does.)
flip=$(($(awk 'NR == 40' "$tmp/starts") + 8))
head -c $flip $G/arcos.capture >"$tmp/flipped"
printf '\252' >>"$tmp/flipped"
tail -c +$((flip + 2)) $G/arcos.capture >>"$tmp/flipped"
replay flipped "$tmp/flipped"
check "a corrupted SIP: exit 0, counted in bad_packets" \
    sh -c "test $(cat "$tmp/flipped.rc") -eq 0 && test $(bad_packets flipped) -gt 0"
check "... and every other SIP is published: one ODOMETRY fewer than the golden's" \
    test "$(messages "$tmp/flipped.ODOMETRY")" -eq $(($(messages $G/arcos.ODOMETRY.txt) - 1))

# Nothing but garbage (bytes of a sonar log: 0xFA 0xFB may turn up, with wrong counts).
head -c "$size" logs/tour.lcmlog >"$tmp/junk"
replay junk "$tmp/junk"
check "a capture of garbage only: exit 0" test "$(cat "$tmp/junk.rc")" -eq 0
check "... no robot, no SONAR" test ! -s "$tmp/junk.SONAR"
check "... the garbage counted in bad_packets" test "$(bad_packets junk)" -gt 0

: >"$tmp/empty"
replay empty "$tmp/empty"
check "an empty capture: exit 0" test "$(cat "$tmp/empty.rc")" -eq 0

rejects "robot.link = file: with no file is refused" 1 "want file:CAPTURE" \
    "$BIN/houghlocd" --config /dev/null --set robot.link=file: --lcm-url memq:// --map "$tmp/x.hlmap"
replay device /dev/null
check "a capture that is not a regular file: the daemon stops with exit 1 and says so" \
    sh -c "test $(cat "$tmp/device.rc") -eq 1 && grep -q 'file:/dev/null: not a regular file' $tmp/device.err"

replay missing "$tmp/no-such-capture"
check "a missing capture: the daemon stops with exit 1 and names it" \
    sh -c "test $(cat "$tmp/missing.rc") -eq 1 && grep -q 'file:$tmp/no-such-capture: No such file' $tmp/missing.err"
# A fresh capture over TCP: its replay publishes the sounding made on connect, the same
# bytes every time.
if sh tests/golden/capture.sh "$tmp/fresh.capture" >/dev/null; then
    replay fresh1 "$tmp/fresh.capture"
    replay fresh2 "$tmp/fresh.capture"
    check "a fresh capture replays to one SONAR, the same twice" \
        sh -c "test $(messages "$tmp/fresh1.SONAR") -eq 1 && cmp -s $tmp/fresh1.SONAR $tmp/fresh2.SONAR &&
               cmp -s $tmp/fresh1.ODOMETRY $tmp/fresh2.ODOMETRY"
else
    check "houghloc-sim --capture records a connection" false
fi
exit $fail
