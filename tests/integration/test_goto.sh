#!/bin/sh
# Integration test of houghloc-goto without a daemon: bad arguments get exit 2 and one
# line naming them, --help and --version exit 0, a key file open to others or holding no
# key is refused (exit 1), and with nobody answering on a private LCM port it gives up
# after --timeout with exit 6 and says where it listened. (Its answers to ACCEPTED,
# ARRIVED and the refusals are tested against the real daemon.)
set -u
BIN=${BUILD:-build}/bin
GOTO=$BIN/houghloc-goto
# A port no daemon uses, so that nothing answers.
URL='udpm://239.255.76.67:7689?ttl=0'
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
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
exits "bad --prefix" 2 '--prefix "a b"' "$GOTO" --prefix 'a b' 1 2
exits "--prefix too long" 2 "--prefix" "$GOTO" --prefix aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa 1 2
exits "empty --lcm-url" 2 "--lcm-url is empty" "$GOTO" --lcm-url= 1 2
exits "usage errors point at --help" 2 "try houghloc-goto --help" "$GOTO" 1

# --help and --version: exit 0, on stdout.
"$GOTO" --help >"$tmp/help" 2>"$tmp/err"
check "--help exits 0" test $? -eq 0
check "--help prints the usage line" grep -q "^Usage: houghloc-goto \[options\] X Y \[HEADING\]$" "$tmp/help"
check "--help lists the exit codes" test "$(grep -cE '^  [0-6]  ' "$tmp/help")" -eq 7
check "--help names every option" sh -c 'for o in --lcm-url --prefix --key --timeout --no-wait --help --version; do grep -q -- "  $o" "$1" || exit 1; done' - "$tmp/help"
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

exit $fail
