#!/bin/sh
# trials.sh - `make trials`: every reliability trial in one run, progress on stderr, and
# the last stdout line
#
#   trials kill9=<loadable>/<runs> save_period=<n> max_lost_scans=<k> link=<survived>/<runs> flood_identical=<yes|no> flood_p99_ratio=<r> forged_rejected=<k>/<n> valid_accepted=<k>/<n> fuzz_crashes=<c> restart_found=<f>/<restarts> restart_error_mm=<median> poisoned_scans_lost=<n> replay_after_crash=<accepted>/<tried> console_peak_rss_mib=<m> console_operator_under_slowloris=<ok|fail> forged_reply_accepted=<n> counter_edge=<ok|fail> save_flood_pose_p99_ms=<x>
#
# The trials (each a script of its own, whose last stdout line is taken):
#   fuzz        `make fuzz FUZZ_SECONDS=N` (tests/fuzz/fuzz.mk), then every regression
#               replay $BUILD/tests/fuzz/replay_*; fuzz_crashes = this run's crashes plus
#               the replays that fail
#   power       tools/lab/trials/power.sh    kill -9 of the live daemon, 100 times
#   link        tools/lab/trials/link.sh     link faults from the simulated robot
#   commands    tools/lab/trials/commands.sh forged, replayed, stale, unsigned requests
#   flood       tools/lab/trials/flood.sh    malformed LCM messages during a replay
#   poison      tools/lab/trials/poison.sh   sensor streams that try to stop localization
#   console     tools/lab/trials/console.sh  stalled event streams and slowloris
#               connections against houghloc-console
#   counters    tools/lab/trials/counters.sh map versions past 2^31 and 2^32
#   save_flood  tools/lab/trials/save_flood.sh  SAVE flooded during a replay
#   sanitizers  tools/lab/trials/sanitizers.sh  ASan+UBSan integration tests, valgrind
# Fuzzing keeps one core busy for FUZZ_SECONDS x targets, so it runs in the background
# while the trials that mostly wait or count (sanitizers' tests, power, link, commands,
# poison, console, counters) run; flood and save_flood measure latency, so they run alone
# once fuzzing is over. A trial whose script is
# missing is said on stderr and given "-" / "no". Exit 1 if any trial failed (named on
# stderr).
#
#   BUILD=build FUZZ_SECONDS=30 TRIALS_SKIP="flood sanitizers" (skip some, for a quick run)
set -u
BUILD=${BUILD:-build}
MAKE=${MAKE:-make}
FUZZ_SECONDS=${FUZZ_SECONDS:-30}
SKIP=${TRIALS_SKIP:-}
D=tools/lab/trials
OUT=$BUILD/trials/driver
mkdir -p "$OUT" || exit 1
say() { echo "trials: $*" >&2; }
t0=$(date +%s)
elapsed() { echo "$(($(date +%s) - t0)) s"; }
failed=""
fail() { failed="$failed $1"; }
skipped() { case " $SKIP " in *" $1 "*) say "$1: skipped (TRIALS_SKIP)"; return 0 ;; esac; return 1; }

# run_trial NAME: $D/NAME.sh, its stderr passed through as progress, its stdout kept in
# $OUT/NAME.out; the last line in $last ("" if the script is missing)
run_trial() {
    last=""
    if skipped "$1"; then fail "$1(skipped)"; return; fi
    if [ ! -f "$D/$1.sh" ]; then
        say "$1: $D/$1.sh is missing: not run"
        fail "$1(missing)"
        return
    fi
    say "$1 ... ($(elapsed) so far)"
    t=$(date +%s)
    BUILD=$BUILD sh "$D/$1.sh" >"$OUT/$1.out"
    rc=$?
    last=$(tail -n 1 "$OUT/$1.out")
    say "$1: exit $rc in $(($(date +%s) - t)) s: $last"
    [ $rc -eq 0 ] || fail "$1"
}
field() { echo "$last" | tr ' ' '\n' | sed -n "s/^$1=//p"; }   # field KEY: from $last

# ---- fuzzing, in the background ----------------------------------------------------------
fuzz_pid=""
if skipped fuzz; then
    fail "fuzz(skipped)"
elif [ ! -f tests/fuzz/fuzz.mk ]; then
    say "fuzz: tests/fuzz does not exist yet: 0 targets"
else
    say "fuzz: make fuzz FUZZ_SECONDS=$FUZZ_SECONDS in the background (log $OUT/fuzz.out)"
    $MAKE --no-print-directory BUILD="$BUILD" fuzz FUZZ_SECONDS="$FUZZ_SECONDS" \
        >"$OUT/fuzz.out" 2>"$OUT/fuzz.err" &
    fuzz_pid=$!
fi
trap '[ -n "$fuzz_pid" ] && kill $fuzz_pid 2>/dev/null; exit 130' INT TERM

# ---- the trials that mostly wait, meanwhile ----------------------------------------------
run_trial sanitizers
run_trial power
kill9=$(field kill9) save_period=$(field save_period) max_lost=$(field max_lost_scans)
restart_found=$(field found) restart_error=$(field restart_error_mm)
run_trial link
link=$(field link)
run_trial commands
forged=$(field forged_rejected) valid=$(field valid_accepted)
replay_after_crash=$(field replay_after_crash) forged_reply=$(field forged_reply_accepted)
run_trial poison
poisoned=$(field poisoned_scans_lost)
run_trial console
console_rss=$(field console_peak_rss_mib) console_loris=$(field console_operator_under_slowloris)
run_trial counters
counter_edge=$(field counter_edge)

# ---- fuzzing's figures, then the regression replays --------------------------------------
fuzz_crashes=0
if [ -n "$fuzz_pid" ]; then
    say "fuzz: waiting for make fuzz ($(elapsed) so far)"
    wait $fuzz_pid
    rc=$?
    fuzz_pid=""
    grep '^fuzz ' "$OUT/fuzz.out" >&2
    summary=$(grep '^fuzz targets=' "$OUT/fuzz.out" | tail -n 1)
    crashes=$(echo "$summary" | tr ' ' '\n' | sed -n 's/^crashes=//p')
    if [ -z "$crashes" ]; then
        say "fuzz: make fuzz exited $rc without its summary line:"; tail -n 5 "$OUT/fuzz.err" >&2
        fail fuzz
        crashes=0
    elif [ $rc -ne 0 ] || [ "$crashes" -ne 0 ]; then
        fail fuzz
    fi
    fuzz_crashes=$crashes
    replays=$(ls "$BUILD"/tests/fuzz/replay_* 2>/dev/null)   # built by make trials
    [ -n "$replays" ] || say "fuzz: no $BUILD/tests/fuzz/replay_* (make trials builds them)"
    n=0 bad=0
    for r in $replays; do
        [ -x "$r" ] || continue
        n=$((n + 1))
        "$r" >"$OUT/replay.out" 2>&1 ||
            { bad=$((bad + 1)); say "fuzz: regression replay $r fails: $(tail -n 2 "$OUT/replay.out" | tr '\n' ' ')"; }
    done
    say "fuzz: $n regression replays, $bad failing"
    [ $bad -eq 0 ] || fail fuzz-replays
    fuzz_crashes=$((fuzz_crashes + bad))
fi

# ---- the latency trial, on a quiet machine -----------------------------------------------
run_trial flood
flood_identical=$(field flood_identical) flood_ratio=$(field flood_p99_ratio)
run_trial save_flood
save_flood=$(field save_flood_pose_p99_ms)

say "all done in $(elapsed)"
[ -z "$failed" ] || say "FAILED:$failed"
echo "trials kill9=${kill9:--} save_period=${save_period:--} max_lost_scans=${max_lost:--} link=${link:--} flood_identical=${flood_identical:-no} flood_p99_ratio=${flood_ratio:--} forged_rejected=${forged:--} valid_accepted=${valid:--} fuzz_crashes=$fuzz_crashes restart_found=${restart_found:--} restart_error_mm=${restart_error:--} poisoned_scans_lost=${poisoned:--} replay_after_crash=${replay_after_crash:--} console_peak_rss_mib=${console_rss:--} console_operator_under_slowloris=${console_loris:-fail} forged_reply_accepted=${forged_reply:--} counter_edge=${counter_edge:-fail} save_flood_pose_p99_ms=${save_flood:--}"
[ -z "$failed" ]
