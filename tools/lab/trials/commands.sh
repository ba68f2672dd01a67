#!/bin/sh
# commands.sh - the Commands trial of `make trials` : a live houghlocd with a key
# (auth.key_file, mode 0600) and no robot is sent, by hl-forge, one at a time and in a
# seeded interleaved order, COMMANDS_ROUNDS (60) rounds of: a valid destination, a valid
# command (SET_POSE or SAVE), and one forged (wrong key / flipped MAC bit / a field changed
# after signing), replayed (exact copy of an accepted request), stale (signed, seq below
# the last accepted), unsigned and out-of-fence request, destinations and commands in
# turn. "Accepted" means past the MAC, freshness and fence checks: a valid destination is
# answered NO_ROBOT (the only answer a daemon without a robot gives an admissible one), a
# valid command ACCEPTED (SET_POSE at once, SAVE once the map file is written). Every bad
# one must get its REPLY (REJECTED_AUTH, REJECTED_REPLAY, REJECTED_FENCE) and be counted in
# STATUS rejected_requests.
#
# Then the daemon is stopped and restarted on its map file, and every request of the
# first run (recorded by lcm-logger) is played into it again with lcm-logplayer: all of
# them must now be refused, since the last accepted seq is kept in the map file.
#
# The last stdout line:
#   forged_rejected=<k>/<n> valid_accepted=<k>/<n>
# n counts every bad request: the first run's (5 x rounds) plus every request replayed after
# the restart; k those refused as required and counted in STATUS (a refusal missing from
# STATUS lowers k). Progress on stderr; files of the last run stay in BUILD/trials/commands.
# Exit status 0 when every check passed. Environment: BUILD (build), COMMANDS_ROUNDS (60),
# COMMANDS_SEED (1).
set -u
BUILD=${BUILD:-build}
BIN=$BUILD/bin
ROUNDS=${COMMANDS_ROUNDS:-60}
SEED=${COMMANDS_SEED:-1}

say() { echo "commands: $*" >&2; }
die() { say "$*"; echo "forged_rejected=0/0 valid_accepted=0/0"; exit 1; }
abs() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
field() { sed -n "s/.* $2=\([^ ]*\).*/\1/p" "$1"; }     # field FILE KEY

for p in houghlocd hl-forge hl-eval; do
    [ -x "$BIN/$p" ] || die "$BIN/$p is missing: make BUILD=$BUILD all"
done
command -v lcm-logplayer >/dev/null && command -v lcm-logger >/dev/null ||
    die "lcm-logplayer and lcm-logger are needed (Debian: liblcm-bin)"

t_start=$(date +%s)
work=$(abs "$BUILD/trials/commands")
rm -rf "$work"
mkdir -p "$work" || die "cannot make $work"
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done' EXIT
(umask 077; head -c 32 /dev/urandom | xxd -p -c 64 >"$work/key") || die "cannot make a key"

url="udpm://239.255.76.67:$((9500 + $$ % 100))?ttl=0&recv_buf_size=4194304"  # 9500..9599
D="$BIN/houghlocd --config /dev/null --map $work/map.hlmap --lcm-url $url --set auth.key_file=$work/key"

wait_ready() {  # wait_ready ERRFILE: until the daemon says it is ready (10 s at most)
    n=0
    while ! grep -q 'ready:' "$1" 2>/dev/null && [ $n -lt 100 ]; do sleep 0.1; n=$((n + 1)); done
}
start() {       # start NAME [--fresh-map]: the recorder, then the daemon
    lcm-logger -q -f -c 'DESTINATION|COMMAND|REPLY|STATUS' --lcm-url="$url" \
        "$work/$1.lcmlog" >"$work/$1.logger" 2>&1 &
    logger=$!; pids="$pids $logger"
    $D ${2:-} 2>"$work/$1.err" &
    daemon=$!; pids="$pids $daemon"
    wait_ready "$work/$1.err"
}
stop() {        # stop NAME: the daemon, then the recorder; the daemon's exit status
    sleep 0.3
    kill -TERM $daemon; wait $daemon; rc=$?
    sleep 0.3
    kill -INT $logger; wait $logger
    "$BIN/hl-eval" status "$work/$1.lcmlog" >"$work/$1.status" || rc=1
    return $rc
}

ok=1
# ---- the first run: valid requests interleaved with bad ones -----------------------------
say "first run: $ROUNDS rounds of hl-forge against a daemon with a key"
start first --fresh-map
t0=$(date +%s)
"$BIN/hl-forge" --lcm-url "$url" --key "$work/key" --rounds "$ROUNDS" --seed "$SEED" \
    >"$work/forge.out" 2>"$work/forge.err" || ok=0
say "  $(tail -1 "$work/forge.out") ($(($(date +%s) - t0)) s)"
[ -s "$work/forge.err" ] && sed 's/^/  /' "$work/forge.err" >&2
stop first || { say "  the daemon did not stop cleanly"; ok=0; }
say "  $(grep 'stopped:' "$work/first.err" | sed 's/^<[0-9]>houghlocd: //')"

bad=$(sed -n 's/.* bad_rejected=[0-9]*\/\([0-9]*\).*/\1/p' "$work/forge.out")
bad_ok=$(sed -n 's/.* bad_rejected=\([0-9]*\)\/.*/\1/p' "$work/forge.out")
valid=$(sed -n 's/.* valid_accepted=[0-9]*\/\([0-9]*\).*/\1/p' "$work/forge.out")
valid_ok=$(sed -n 's/.* valid_accepted=\([0-9]*\)\/.*/\1/p' "$work/forge.out")
[ -n "$bad" ] && [ -n "$valid" ] || die "hl-forge gave no summary: $(tail -2 "$work/forge.err")"
counted=$(field "$work/first.status" rejected_requests)
say "  STATUS rejected_requests=$counted for $bad bad requests"
if [ "${counted:-0}" -ne "$bad" ]; then
    ok=0
    [ "${counted:-0}" -lt "$bad_ok" ] && bad_ok=${counted:-0}
fi
[ "$bad" -ge $((5 * 50)) ] && [ "$valid" -ge 50 ] || { say "  fewer than 50 of a kind"; ok=0; }

# ---- after a restart, the first run's requests again: everything refused --------------
# hl-eval extract writes a 4-byte length before each request of 67 bytes (bus.h)
"$BIN/hl-eval" extract "$work/first.lcmlog" DESTINATION "$work/first.DESTINATION"
"$BIN/hl-eval" extract "$work/first.lcmlog" COMMAND "$work/first.COMMAND"
replayed=$((($(wc -c <"$work/first.DESTINATION") + $(wc -c <"$work/first.COMMAND")) / 71))
say "restart on the saved map, then the first run's $replayed requests played again"
start restart
lcm-logplayer -e '^(DESTINATION|COMMAND)$' -l "$url" "$work/first.lcmlog" >/dev/null 2>&1
stop restart || { say "  the restarted daemon did not stop cleanly"; ok=0; }
refused=$(field "$work/restart.status" rejected_requests)
say "  STATUS rejected_requests=$refused of $replayed replayed"
[ "${refused:-0}" -eq "$replayed" ] || ok=0
# The recorder is a separate process: under load it may miss some of the first run (it does
# not slow the sender). What it missed is not played again, and n below counts what was.
[ "$replayed" -eq $((bad + valid)) ] ||
    say "  note: the recording holds $replayed of the first run's $((bad + valid)) requests"
[ "${refused:-0}" -gt "$replayed" ] && refused=$replayed

n=$((bad + replayed))
k=$((bad_ok + ${refused:-0}))
[ "$bad_ok" -eq "$bad" ] && [ "$valid_ok" -eq "$valid" ] || ok=0
say "done in $(($(date +%s) - t_start)) s; files in $work"
echo "forged_rejected=$k/$n valid_accepted=$valid_ok/$valid"
[ $ok -eq 1 ]
