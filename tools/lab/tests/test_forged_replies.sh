#!/bin/sh
# Integration test of houghloc-goto against forged answers (tests/integration/test_goto.sh
# tests the rest of it): with --key, forged REPLY messages (hl-forge's ARRIVED, unsigned,
# wrongly signed or signed for another prefix) are ignored with one warning and never make
# it exit 0, and the keyed daemon's own signed answer is the one taken. hl-forge is the
# laboratory's (the Commands trial, tools/lab/trials), so this runs in make lab-test.
set -u
BIN=${BUILD:-build}/bin
GOTO=$BIN/houghloc-goto
# A port no other test uses.
URL='udpm://239.255.76.67:7695?ttl=0'
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM HUP PIPE
. tests/integration/lib.sh

head -c 32 /dev/urandom | od -An -tx1 -v | tr -d ' \n' >"$tmp/key"
echo >>"$tmp/key"
chmod 600 "$tmp/key"

# ---- forged answers: with --key only the daemon's signed REPLY counts ------------------
# hl-forge (the lab's Commands trial) answers every request it sees with a forged ARRIVED:
# unsigned, signed with another key, signed with this key for another prefix.
for p in houghlocd hl-forge; do
    [ -x "$BIN/$p" ] || { echo "FAIL: no $BIN/$p (run make all lab first)"; exit 1; }
done
"$BIN/hl-forge" --lcm-url "$URL" --key "$tmp/key" --prefix forged/ --forge-replies 8 \
    >"$tmp/forge.out" 2>"$tmp/forge.err" &
forger=$!; pids=$forger
sleep 0.3
"$GOTO" --lcm-url "$URL" --prefix forged/ --timeout 1.5 --key "$tmp/key" 1 2 >"$tmp/out" 2>"$tmp/err"
rc=$?
check "with --key, forged ARRIVED replies do not end the wait: exit $rc, wanted 6" test $rc -eq 6
check "... nothing on stdout" test ! -s "$tmp/out"
check "... one warning, once, names the ignored reply" \
    sh -c 'test "$(grep -c "ignoring a REPLY (ARRIVED) to seq [0-9]* without a valid MAC" "$1")" -eq 1' - "$tmp/err"
check "... and the timeout counts them" grep -q "REPLY message(s) without a valid MAC were ignored" "$tmp/err"
"$GOTO" --lcm-url "$URL" --prefix forged/ --timeout 1.5 1 2 >"$tmp/out" 2>"$tmp/err"
check "without --key nothing can be verified: the forged ARRIVED is taken (exit $?)" \
    grep -q "^houghloc-goto: ARRIVED: forged" "$tmp/out"
# the daemon, with the key and no robot, answers NO_ROBOT (signed) while the forger
# answers ARRIVED: the daemon's answer is the one taken
"$BIN/houghlocd" --config /dev/null --lcm-url "$URL" --prefix forged/ --map "$tmp/k.hlmap" \
    --fresh-map --set auth.key_file="$tmp/key" 2>"$tmp/k.err" &
kd=$!; pids="$forger $kd"
n=0; until grep -q 'ready:' "$tmp/k.err" 2>/dev/null || [ $n -ge 100 ]; do sleep 0.1; n=$((n + 1)); done
"$GOTO" --lcm-url "$URL" --prefix forged/ --timeout 3 --key "$tmp/key" 1 2 >"$tmp/out" 2>"$tmp/err"
rc=$?
check "with --key and the daemon answering, its NO_ROBOT wins over the forged ARRIVED: exit $rc, wanted 4" \
    test $rc -eq 4
kill -TERM $kd; wait $kd
check "the keyed daemon stops with exit 0" test $? -eq 0
wait $forger
check "hl-forge forged replies: $(tail -n 1 "$tmp/forge.out")" \
    grep -q "^forge replies requests=[1-9][0-9]* forged=[1-9]" "$tmp/forge.out"
pids=""
exit $fail
