#!/bin/sh
# Integration test of houghloc-goto. Without a daemon: bad arguments get exit 2 and one
# line naming them, --help and --version exit 0, a key file open to others or holding no
# key is refused (exit 1), and with nobody answering on a private LCM port it gives up
# after --timeout with exit 6 and says where it listened. With houghlocd driving the
# simulated robot (3 times real time): a trip several times longer than --timeout arrives
# (exit 0), as the daemon's STATUS shows the robot's progress, and --deadline bounds the
# whole wait (exit 6, naming it). (Its answers to the refusals are tested against the
# real daemon in test_daemon.sh and test_robot.sh; forged REPLY messages, which need the
# laboratory's forger, in tools/lab/tests/test_forged_replies.sh.)
set -u
BIN=${BUILD:-build}/bin
GOTO=$BIN/houghloc-goto
# A port no daemon uses, so that nothing answers.
URL='udpm://239.255.76.67:7689?ttl=0'
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM HUP PIPE
. tests/integration/lib.sh

# Bad usage: exit 2, one line naming the bad argument and pointing at --help.
exits "missing Y" 2 "missing Y" "$GOTO" 1.5
exits "missing X and Y" 2 "missing X and Y" "$GOTO"
exits "X not a number" 2 'X "abc" is not a number' "$GOTO" abc 1
exits "Y nan" 2 'Y "nan" is not a finite number' "$GOTO" 1 nan
exits "X 1e999" 2 'X "1e999" is not a finite number' "$GOTO" 1e999 1
exits "HEADING -inf" 2 'HEADING "-inf" is not a finite number' "$GOTO" 1 2 -inf
exits "X beyond 4194.304 m" 2 "X 4194.305 m is outside +-4194.304 m" "$GOTO" 4194.305 0
exits "Y beyond -4194.304 m" 2 "Y -5000 m is outside" "$GOTO" 0 -5000
exits "trailing garbage" 2 'Y "2m" is not a number' "$GOTO" 1 2m
exits "too many arguments" 2 'too many arguments at "4"' "$GOTO" 1 2 3 4
exits "unknown option" 2 'unknown option "--bogus"' "$GOTO" --bogus 1 2
exits "unknown short option" 2 'unknown option "-x"' "$GOTO" -x 1 2
exits "--timeout 0" 2 '--timeout "0"' "$GOTO" --timeout 0 1 2
exits "--timeout 3601" 2 '--timeout "3601"' "$GOTO" --timeout 3601 1 2
exits "--timeout abc" 2 '--timeout "abc"' "$GOTO" --timeout=abc 1 2
exits "--timeout without a value" 2 "--timeout needs a value" "$GOTO" 1 2 --timeout
exits "--deadline 0" 2 '--deadline "0": give seconds from 0.1 to 86400' "$GOTO" --deadline 0 1 2
exits "--deadline 86401" 2 '--deadline "86401"' "$GOTO" --deadline=86401 1 2
exits "--deadline without a value" 2 "--deadline needs a value" "$GOTO" 1 2 --deadline
exits "bad --prefix" 2 '--prefix "a b"' "$GOTO" --prefix 'a b' 1 2
exits "--prefix too long" 2 "--prefix" "$GOTO" --prefix aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa 1 2
exits "empty --lcm-url" 2 "--lcm-url is empty" "$GOTO" --lcm-url= 1 2
exits "usage errors point at --help" 2 "try houghloc-goto --help" "$GOTO" 1

# --help and --version: exit 0, on stdout.
"$GOTO" --help >"$tmp/help" 2>"$tmp/err"
check "--help exits 0" test $? -eq 0
check "--help prints the usage line" grep -q "^Usage: houghloc-goto \[options\] X Y \[HEADING\]$" "$tmp/help"
check "--help lists the exit codes" test "$(grep -cE '^  [0-6]  ' "$tmp/help")" -eq 7
check "--help names every option" sh -c 'for o in --lcm-url --prefix --key --timeout --deadline --no-wait --help --version; do grep -q -- "  $o" "$1" || exit 1; done' - "$tmp/help"
check "--help writes nothing on stderr" test ! -s "$tmp/err"
"$GOTO" --version >"$tmp/version"
check "--version exits 0" test $? -eq 0
check "--version prints the name" grep -q "^houghloc-goto [0-9]" "$tmp/version"

# Key files: refused before anything is sent (exit 1, one line naming the file).
head -c 32 /dev/urandom | od -An -tx1 -v | tr -d ' \n' >"$tmp/key"
echo >>"$tmp/key"
chmod 644 "$tmp/key"
exits "key file open to others" 1 "chmod 600 $tmp/key" "$GOTO" --lcm-url "$URL" --key "$tmp/key" 1 2
printf 'not a key\n' >"$tmp/badkey"
chmod 600 "$tmp/badkey"
exits "key file without a key" 1 "key file $tmp/badkey: key has a character" "$GOTO" --lcm-url "$URL" --key "$tmp/badkey" 1 2
exits "missing key file" 1 "key file $tmp/nokey: No such file" "$GOTO" --lcm-url "$URL" --key "$tmp/nokey" 1 2
ln -s "$tmp/key" "$tmp/keylink"
chmod 600 "$tmp/key"
exits "key file through a symbolic link" 1 "symbolic link" "$GOTO" --lcm-url "$URL" --key "$tmp/keylink" 1 2
# liblcm prints its own line about a bad URL first: only ours is checked here.
"$GOTO" --lcm-url nonsense://x 1 2 >/dev/null 2>"$tmp/err"
check "LCM that cannot start: exit 1" test $? -eq 1
check "LCM that cannot start: says so" grep -q -F 'houghloc-goto: cannot start LCM with URL "nonsense://x"' "$tmp/err"

# Nobody answers: exit 6 after the timeout, naming the reply channel. Negative numbers
# need no "--", a good key signs, and the prefix shows in the channel's name.
exits "timeout without a daemon" 6 \
    "no reply from houghlocd within 0.3 s on channel REPLY: is it running, with the same --lcm-url and prefix?" \
    "$GOTO" --lcm-url "$URL" --timeout 0.3 1 2
exits "timeout, signed, prefixed, negative numbers" 6 \
    "no reply from houghlocd within 0.2 s on channel robot7/REPLY:" \
    "$GOTO" --lcm-url="$URL" --prefix robot7/ --timeout 0.2 --key "$tmp/key" -1.5 -2 -90
exits "timeout with --no-wait and after --" 6 "within 0.2 s on channel REPLY" \
    env LCM_DEFAULT_URL="$URL" "$GOTO" --no-wait --timeout 0.2 -- -4194.304 4194.304 725
exits "--deadline before --timeout, nobody answering" 6 "within the --deadline of 0.3 s" \
    "$GOTO" --lcm-url "$URL" --timeout 30 --deadline 0.3 1 2

# ---- with houghlocd and the simulated robot --------------------------------------------
for p in houghlocd houghloc-sim; do
    [ -x "$BIN/$p" ] || { echo "FAIL: no $BIN/$p (run make first)"; exit 1; }
done
n=$(($$ % 500))
URL="udpm://239.255.76.70:$((7700 + n))?ttl=0"
wait_for() {    # wait_for FILE TEXT TENTHS: until FILE holds TEXT
    w=0
    until grep -q -- "$2" "$1" 2>/dev/null; do
        [ $w -ge "$3" ] && return 1
        sleep 0.1; w=$((w + 1))
    done
}
# the robot at the lab's tour start (north-west corner), where the trips below were timed
"$BIN/houghloc-sim" --port 0 --speed 3 --start 0.6096,6.7056,0 --lcm-url "$URL" 2>"$tmp/sim.err" &
sim=$!; pids=$sim
wait_for "$tmp/sim.err" "listening on" 100
PORT=$(sed -n 's/.*listening on 127\.0\.0\.1:\([0-9]*\).*/\1/p' "$tmp/sim.err" | head -n 1)
profile_sets="--set robot.profile=houghloc-sim"
# shellcheck disable=SC2086  # a list of options
"$BIN/houghlocd" --lcm-url "$URL" --map "$tmp/map.hlmap" --fresh-map \
    --set "robot.link=tcp:127.0.0.1:${PORT:-1}" $profile_sets 2>"$tmp/d.err" &
daemon=$!; pids="$daemon $sim"
check "houghlocd connects to the simulated robot" wait_for "$tmp/d.err" "robot .* connected" 300

# 1.6 m from the simulator's start, two legs with a sounding each: about 13 s at 3 times
# real time, over four times the silence allowed. STATUS comes once a second.
t0=$(date +%s)
"$GOTO" --lcm-url "$URL" --timeout 3 0.5 -1.5 >"$tmp/out" 2>"$tmp/err"
rc=$? took=$(($(date +%s) - t0))
check "a trip longer than --timeout 3 arrives: exit $rc after $took s: $(tail -n 1 "$tmp/out")" \
    sh -c '[ "$1" -eq 0 ] && grep -q "^houghloc-goto: ARRIVED: " "$2"' - $rc "$tmp/out"
check "that trip outlasted --timeout ($took s > 3 s)" test "$took" -gt 3
# the way back, bounded by --deadline: it gives up long before the robot could arrive
"$GOTO" --lcm-url "$URL" --deadline 2 0 0 >"$tmp/out" 2>"$tmp/err"
rc=$?
check "--deadline 2 on a longer trip: exit 6" test $rc -eq 6
check "--deadline: accepted first" grep -q "^houghloc-goto: ACCEPTED: " "$tmp/out"
check "--deadline: one line names it and the last STATUS" \
    grep -q "^houghloc-goto: accepted, but no ARRIVED within the --deadline of 2 s (last STATUS: [A-Z]* at (" "$tmp/err"
# the robot drives on: the same destination again, with the default timeout, arrives
"$GOTO" --lcm-url "$URL" 0 0 >"$tmp/out" 2>"$tmp/err"
check "the same trip again with the default timeout arrives: exit $?" \
    grep -q "^houghloc-goto: ARRIVED: " "$tmp/out"
kill -TERM $daemon; wait $daemon
check "houghlocd stops with exit 0" test $? -eq 0
kill -TERM $sim; wait $sim
pids=""
[ $fail -eq 0 ] || { echo "  the daemon's log ends:"; tail -n 8 "$tmp/d.err" | sed 's/^/    /'; }

exit $fail
