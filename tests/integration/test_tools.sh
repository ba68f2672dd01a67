#!/bin/sh
# Integration test of the offline tools, as a user runs them: the data sets regenerate
# byte-identically, the experiments run end to end on them and write their tables, the
# benchmark prints its parseable lines, and bad input gets a one-line error and a
# non-zero exit, never a crash.
set -u
BIN=${BUILD:-build}/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
check() {   # check DESCRIPTION COMMAND...: the command must succeed
    desc=$1; shift
    if "$@"; then echo "ok: $desc"; else echo "FAIL: $desc"; fail=1; fi
}
rejects() { # rejects DESCRIPTION EXPECTED_TEXT COMMAND...: exit 1 or 2, one line naming it
    desc=$1; want=$2; shift 2
    "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if { [ $rc -eq 1 ] || [ $rc -eq 2 ]; } && [ "$(wc -l <"$tmp/err")" -eq 1 ] &&
        grep -q -- "$want" "$tmp/err"; then
        echo "ok: $desc"
    else
        echo "FAIL: $desc (exit $rc): $(head -c 300 "$tmp/err")"
        fail=1
    fi
}

# The committed logs are what `make logs` makes.
"$BIN/hl-sim-logs" --seed 1 --out-dir "$tmp" >/dev/null
for f in lab28 orientation tour; do
    check "logs/$f.lcmlog regenerates byte-identically" cmp -s "$tmp/$f.lcmlog" "logs/$f.lcmlog"
done

# The experiments run end to end and write their tables.
"$BIN/hl-experiments" --logs logs --out "$tmp/exp" --reps 1 --no-figures 2>"$tmp/progress"
check "hl-experiments exits 0" test $? -eq 0
check "table1.tsv has 12 rows" test "$(tail -n +2 "$tmp/exp/table1.tsv" | wc -l)" -eq 12
check "table1.tsv header" grep -q "^mode	fraction	raster_mm	trials	wild	wild_pct	tame_mean_mm	tame_sigma_mm$" "$tmp/exp/table1.tsv"
check "orientation.tsv has both modes" test "$(cut -f1 "$tmp/exp/orientation.tsv" | tr '\n' ' ')" = "mode paper improved "
check "combined.tsv has paper, odometry, improved" test "$(cut -f1 "$tmp/exp/combined.tsv" | tr '\n' ' ')" = "mode paper odometry improved "
check "results.md names the three experiments and the limits" test "$(grep -c '^## ' "$tmp/exp/results.md")" -eq 4
check "limits.tsv has its six rows" test "$(tail -n +2 "$tmp/exp/limits.tsv" | wc -l)" -eq 6
check "progress goes to stderr" grep -q "^table1: " "$tmp/progress"

# The multi-seed summary runs and prints its orientation line.
BUILD=${BUILD:-build} sh tools/experiments/seeds.sh 2 --only orientation >"$tmp/seeds"
check "seeds.sh summarises two seeds" grep -q "^orientation, 2 seeds: mean |bias| [0-9.]* deg, sigma [0-9.]* deg$" "$tmp/seeds"

# The benchmark's lines parse (values are not judged here: that is `make bench`).
"$BIN/hl-bench" 3 >"$tmp/bench"
check "hl-bench prints three parseable lines" test "$(grep -cE '^bench w[123]_[a-z0-9_]+ median_us=[0-9]+ p90_us=[0-9]+ ref_median_us=[0-9]+ votes=[0-9]+ mem_bytes=[0-9]+ group_mm=[0-9]+$' "$tmp/bench")" -eq 3
check "hl-bench times echo and refinement" grep -qE '^bench w4_echo_refine median_us=[0-9]+ p90_us=[0-9]+ echo_median_us=[0-9]+ refine_median_us=[0-9]+ mem_bytes=[0-9]+$' "$tmp/bench"
check "hl-bench times a laser scan against 15,000 vectors" grep -qE '^bench w5_laser15k median_us=[0-9]+ p90_us=[0-9]+ ref_median_us=[0-9]+ votes=[0-9]+ mem_bytes=[0-9]+ group_mm=48$' "$tmp/bench"
check "hl-bench's dense workloads vote in 48 mm groups, the others alone" sh -c '
    grep -q "^bench w3_map15k .* group_mm=48$" "$1" && grep -q "^bench w2_local_xyt .* group_mm=0$" "$1"' - "$tmp/bench"
"$BIN/hl-bench" 2 w2 >"$tmp/bench_one"
check "hl-bench RUNS WORKLOAD runs that workload alone" sh -c '
    test "$(wc -l <"$1")" -eq 1 && grep -q "^bench w2_local_xyt " "$1"' - "$tmp/bench_one"

# Bad input: one line, non-zero exit.
rejects "missing log folder" "cannot open" "$BIN/hl-experiments" --logs "$tmp/nowhere" --out "$tmp/x" --no-figures
mkdir -p "$tmp/trunc"
head -c 5000 logs/lab28.lcmlog >"$tmp/trunc/lab28.lcmlog"
rejects "truncated log" "lab28.lcmlog" "$BIN/hl-experiments" --logs "$tmp/trunc" --only table1 --out "$tmp/x" --no-figures
mkdir -p "$tmp/garbage"
head -c 20000 /dev/urandom >"$tmp/garbage/lab28.lcmlog"
rejects "random bytes as a log" "lab28.lcmlog" "$BIN/hl-experiments" --logs "$tmp/garbage" --only table1 --out "$tmp/x" --no-figures
# A valid first event, then a header declaring 0x7fffffff data bytes and a few of them:
# liblcm would trust that length and crash; the log check refuses the file first, naming
# the byte where the bad header starts, and the program exits 1 (not on a signal).
od_first=$(od -An -tu1 -j20 -N8 logs/lab28.lcmlog)
first=$(echo "$od_first" | awk '{ print 28 + $1 * 16777216 + $2 * 65536 + $3 * 256 + $4 + $5 * 16777216 + $6 * 65536 + $7 * 256 + $8 }')
mkdir -p "$tmp/huge"
{
    head -c "$first" logs/lab28.lcmlog
    printf '\355\241\332\001\0\0\0\0\0\0\0\1\0\0\0\0\0\0\0\2\0\0\0\005\177\377\377\377'
    printf 'SONARsome data bytes'
} >"$tmp/huge/lab28.lcmlog"
"$BIN/hl-experiments" --logs "$tmp/huge" --only table1 --out "$tmp/x" --no-figures >"$tmp/out" 2>"$tmp/err"
rc=$?
check "data length 0x7fffffff after a valid event: exit 1, one line naming byte $first" \
    sh -c '[ "$1" -eq 1 ] && [ "$(wc -l <"$2")" -eq 1 ] &&
           grep -q "lab28.lcmlog: byte $3: event data length 2147483647" "$2"' - "$rc" "$tmp/err" "$first"
rejects "bad --reps" "--reps" "$BIN/hl-experiments" --reps 0
rejects "bad --set" "unknown parameter" "$BIN/hl-experiments" --set improved.nonsense=1
rejects "bad --only" "--only" "$BIN/hl-experiments" --only nonsense
mkdir -p "$tmp/made"
"$BIN/hl-sim-logs" --seed 3 --out-dir "$tmp/made/deeper/logs" >/dev/null
check "hl-sim-logs creates its output folder" test -s "$tmp/made/deeper/logs/tour.lcmlog"
"$BIN/hl-sim-logs" --rotation-sigma-deg 0.3 --out-dir "$tmp/rot_default" >/dev/null
check "--rotation-sigma-deg 0.3 is the default" cmp -s "$tmp/rot_default/lab28.lcmlog" logs/lab28.lcmlog
"$BIN/hl-sim-logs" --rotation-sigma-deg 0 --out-dir "$tmp/rot_none" >/dev/null
check "--rotation-sigma-deg 0 changes the soundings" sh -c '! cmp -s "$1" logs/lab28.lcmlog' - "$tmp/rot_none/lab28.lcmlog"
rejects "bad --rotation-sigma-deg" "--rotation-sigma-deg" "$BIN/hl-sim-logs" --rotation-sigma-deg -1 --out-dir "$tmp/w"
rejects "bad bench runs" "usage" "$BIN/hl-bench" -5
rejects "unknown bench workload" "no workload 'w9'" "$BIN/hl-bench" 2 w9
printf 'segment 0 0 1000\n' >"$tmp/bad.world"
rejects "bad world file" "bad.world:1" "$BIN/hl-sim-logs" --world "$tmp/bad.world" --out-dir "$tmp/w"
rejects "bad limits world" "bad.world:1" "$BIN/hl-experiments" --only limits --world "$tmp/bad.world" --out "$tmp/x"
printf '1000 935\n2000 abc\n' >"$tmp/bad.pairs"
rejects "bad calibration pairs" "bad.pairs:2" "$BIN/hl-calibrate" "$tmp/bad.pairs"

exit $fail
