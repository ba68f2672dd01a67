#!/bin/sh
# Integration test of houghloc-ctl: bad arguments get exit 2 and one line naming them,
# --help and --version exit 0, with nobody answering on a private LCM port it gives up
# after --timeout with exit 6; then against real daemons on that port: save writes a map
# file that loads, set-pose moves the estimate (seen in the map file the daemon saves
# when it stops), relocalize is accepted (the daemon is lost until its scans find the
# robot; with no scans here, it stays so), and a daemon with a key refuses
# an unsigned command (exit 3) and takes a signed one.
set -u
BIN=${BUILD:-build}/bin
CTL=$BIN/houghloc-ctl
D="$BIN/houghlocd --config /dev/null"
# A port no other test uses, so that only our daemons answer.
URL='udpm://239.255.76.67:7693?ttl=0'
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
succeeds() {    # succeeds DESCRIPTION EXPECTED_TEXT COMMAND...: exit 0, one line on stdout
                # containing the text, nothing on stderr
    desc=$1; want=$2; shift 2
    "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ $rc -eq 0 ] && [ "$(wc -l <"$tmp/out")" -eq 1 ] && [ ! -s "$tmp/err" ] &&
        grep -q -F -- "$want" "$tmp/out"; then
        echo "ok: $desc"
    else
        echo "FAIL: $desc (exit $rc, want 0): $(head -c 300 "$tmp/out" "$tmp/err")"
        fail=1
    fi
}
start_daemon() {    # start_daemon NAME [ARGS...]: a fresh daemon with map $tmp/NAME.hlmap,
                    # its pid in $daemon once its log says "ready:" (10 s at most)
    name=$1; shift
    $D --fresh-map --map "$tmp/$name.hlmap" --lcm-url "$URL" "$@" 2>"$tmp/$name.err" &
    daemon=$!; pids="$pids $daemon"
    n=0
    while ! grep -q 'ready:' "$tmp/$name.err" 2>/dev/null && [ $n -lt 100 ]; do
        sleep 0.1; n=$((n + 1))
    done
    check "daemon $name is ready" grep -q 'ready:' "$tmp/$name.err"
}
stop_daemon() {     # stop_daemon NAME: SIGTERM, wait, a clean exit
    kill -TERM $daemon; wait $daemon
    check "daemon $1 stops cleanly" test $? -eq 0
}

# ---- bad usage: exit 2, one line naming the bad argument and pointing at --help -----------
exits "no command" 2 "missing COMMAND (set-pose, save, relocalize or stop)" "$CTL"
exits "unknown command" 2 'unknown command "go" (expected set-pose, save, relocalize or stop)' "$CTL" go 1 2
exits "a number is no command" 2 'unknown command "-1"' "$CTL" -1 2 3
exits "set-pose without arguments" 2 "set-pose: missing X, Y and HEADING" "$CTL" set-pose
exits "set-pose without Y" 2 "set-pose: missing Y and HEADING" "$CTL" set-pose 1
exits "set-pose without HEADING" 2 "set-pose: missing HEADING" "$CTL" set-pose 1 2
exits "set-pose, too many" 2 'too many arguments at "4" (expected set-pose X Y HEADING)' "$CTL" set-pose 1 2 3 4
exits "save takes no argument" 2 'too many arguments at "now" (save takes none)' "$CTL" save now
exits "relocalize takes no argument" 2 'too many arguments at "1" (relocalize takes none)' "$CTL" relocalize 1
exits "X not a number" 2 'X "abc" is not a number' "$CTL" set-pose abc 1 0
exits "Y nan" 2 'Y "nan" is not a finite number' "$CTL" set-pose 1 nan 0
exits "HEADING -inf" 2 'HEADING "-inf" is not a finite number' "$CTL" set-pose 1 2 -inf
exits "HEADING with a unit" 2 'HEADING "90deg" is not a number' "$CTL" set-pose 1 2 90deg
exits "X beyond 4194.304 m" 2 "X 4194.305 m is outside +-4194.304 m" "$CTL" set-pose 4194.305 0 0
exits "Y beyond -4194.304 m" 2 "Y -5000 m is outside" "$CTL" set-pose 0 -5000 0
exits "unknown option" 2 'unknown option "--no-wait"' "$CTL" --no-wait save
exits "--timeout 0" 2 '--timeout "0": give seconds from 0.1 to 3600' "$CTL" --timeout 0 save
exits "--timeout without a value" 2 "--timeout needs a value" "$CTL" save --timeout
exits "bad --prefix" 2 '--prefix "a b"' "$CTL" --prefix 'a b' save
exits "empty --lcm-url" 2 "--lcm-url is empty" "$CTL" --lcm-url= save
exits "empty --key" 2 "--key is empty" "$CTL" --key= save
exits "usage errors point at --help" 2 "; try houghloc-ctl --help" "$CTL" save 1

# ---- --help and --version: exit 0, on stdout ----------------------------------------------
"$CTL" --help >"$tmp/help" 2>"$tmp/err"
check "--help exits 0" test $? -eq 0
check "--help prints the usage line" grep -q "^Usage: houghloc-ctl \[options\] COMMAND \[ARGS\]$" "$tmp/help"
check "--help names every command" sh -c 'for c in "set-pose X Y HEADING" save relocalize; do grep -q "^  $c\$" "$1" || exit 1; done' - "$tmp/help"
check "--help names every option" sh -c 'for o in --lcm-url --prefix --key --timeout --help --version; do grep -q -- "^  $o " "$1" || exit 1; done' - "$tmp/help"
check "--help has examples" test "$(grep -c '^  houghloc-ctl ' "$tmp/help")" -ge 3
check "--help lists the exit codes" test "$(grep -cE '^  [0-6]  ' "$tmp/help")" -eq 7
check "--help writes nothing on stderr" test ! -s "$tmp/err"
"$CTL" --version >"$tmp/version"
check "--version exits 0" test $? -eq 0
check "--version prints the name and version" grep -qx "houghloc-ctl [0-9][0-9.]*" "$tmp/version"

# ---- nobody answers: exit 6 after the timeout, naming the reply channel --------------------
(umask 077; printf '%064x\n' 7 >"$tmp/key")
exits "timeout without a daemon" 6 \
    "no reply from houghlocd within 0.3 s on channel REPLY: is it running, with the same --lcm-url and prefix?" \
    "$CTL" --lcm-url "$URL" --timeout 0.3 save
exits "timeout, signed, prefixed, negative numbers" 6 \
    "no reply from houghlocd within 0.2 s on channel robot7/REPLY:" \
    "$CTL" --lcm-url="$URL" --prefix robot7/ --timeout 0.2 --key "$tmp/key" set-pose -1.5 -2 -90
exits "timeout, options after the command and --" 6 "within 0.2 s on channel REPLY" \
    env LCM_DEFAULT_URL="$URL" "$CTL" set-pose --timeout 0.2 -- -4194.304 4194.304 725
cp "$tmp/key" "$tmp/open.key"; chmod 644 "$tmp/open.key"
exits "key file open to others: exit 1" 1 "chmod 600 $tmp/open.key" "$CTL" --lcm-url "$URL" --key "$tmp/open.key" save

# ---- a daemon without a key ------------------------------------------------------------------
C="$CTL --lcm-url $URL --timeout 5"
start_daemon open
check "no map file before save" test ! -e "$tmp/open.hlmap"
succeeds "save: ACCEPTED (exit 0)" "houghloc-ctl: ACCEPTED: map saved" $C save
check "... the saved map file loads" sh -c "$D --map $tmp/open.hlmap --check-map >/dev/null"
succeeds "set-pose 1 2 90: ACCEPTED (exit 0)" \
    "houghloc-ctl: ACCEPTED: pose set to (1.000, 2.000) m, 90.0 deg; map kept" $C set-pose 1 2 90
succeeds "relocalize: ACCEPTED (exit 0)" \
    "houghloc-ctl: ACCEPTED: lost: the next scans search the whole map" $C relocalize
stop_daemon open
$D --map "$tmp/open.hlmap" --check-map >"$tmp/check" 2>&1
check "the daemon kept the pose set: (1, 2) m, 90 deg" grep -q -F "pose (1.000, 2.000) m 90.00 deg" "$tmp/check"

# ---- a daemon with a key -------------------------------------------------------------------
start_daemon keyed --set auth.key_file="$tmp/key"
exits "unsigned set-pose: REJECTED_AUTH (exit 3)" 3 "houghloc-ctl: REJECTED_AUTH: " $C set-pose 1 2 90
exits "unsigned save: REJECTED_AUTH (exit 3)" 3 "houghloc-ctl: REJECTED_AUTH: " $C save
succeeds "signed set-pose: ACCEPTED (exit 0)" "houghloc-ctl: ACCEPTED: pose set to (-3.250, 0.500) m, -90.0 deg" \
    $C --key "$tmp/key" set-pose -3.25 0.5 270
succeeds "signed save: ACCEPTED (exit 0)" "houghloc-ctl: ACCEPTED: map saved" $C --key "$tmp/key" save
succeeds "signed relocalize: ACCEPTED (exit 0)" "houghloc-ctl: ACCEPTED: lost: " $C --key "$tmp/key" relocalize
stop_daemon keyed
check "the keyed daemon logged the refusal" grep -q 'REJECTED_AUTH' "$tmp/keyed.err"

exit $fail
