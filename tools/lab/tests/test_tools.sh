#!/bin/sh
# Integration test of the laboratory's programs, as a user runs them: the data sets
# regenerate byte-identically, the experiments run end to end on them and write their
# tables, the benchmark prints its parseable lines, and bad input gets a one-line error
# and a non-zero exit, never a crash. (The product's programs: tests/integration/test_usage.sh.)
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
usage_error() { # usage_error DESCRIPTION EXPECTED_TEXT COMMAND...: exit 2, nothing on stdout,
                # one line on stderr containing the text (fixed string)
    desc=$1; want=$2; shift 2
    "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ $rc -eq 2 ] && [ ! -s "$tmp/out" ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] &&
        grep -q -F -- "$want" "$tmp/err"; then
        echo "ok: $desc"
    else
        echo "FAIL: $desc (exit $rc, wanted 2): $(head -c 300 "$tmp/err")"
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
check "table1.tsv has 18 rows (paper; improved without and with a prior)" test "$(tail -n +2 "$tmp/exp/table1.tsv" | wc -l)" -eq 18
check "table1.tsv header" grep -q "^mode	fraction	raster_mm	trials	wild	wild_pct	tame_mean_mm	tame_sigma_mm	prior$" "$tmp/exp/table1.tsv"
check "table1.tsv: 6 improved rows with the prior, 6 without" sh -c '
    test "$(grep -c "^improved	.*	yes$" "$1")" -eq 6 && test "$(grep -c "^improved	.*	no$" "$1")" -eq 6' - "$tmp/exp/table1.tsv"
check "orientation.tsv has both modes" test "$(cut -f1 "$tmp/exp/orientation.tsv" | tr '\n' ' ')" = "mode paper improved "
check "combined.tsv has paper, odometry, improved" test "$(cut -f1 "$tmp/exp/combined.tsv" | tr '\n' ' ')" = "mode paper odometry improved "
check "results.md names the three experiments and the limits" test "$(grep -c '^## ' "$tmp/exp/results.md")" -eq 4
check "limits.tsv has its six rows" test "$(tail -n +2 "$tmp/exp/limits.tsv" | wc -l)" -eq 6
check "progress goes to stderr" grep -q "^table1: " "$tmp/progress"

# The multi-seed summary runs and prints its orientation line.
BUILD=${BUILD:-build} sh tools/lab/experiments/seeds.sh 2 --only orientation >"$tmp/seeds"
check "seeds.sh summarises two seeds" grep -q "^orientation, 2 seeds: mean |bias| [0-9.]* deg, sigma [0-9.]* deg$" "$tmp/seeds"

# The benchmark's lines parse (values are not judged here: that is `make bench`).
"$BIN/hl-bench" 3 >"$tmp/bench"
check "hl-bench prints three parseable lines" test "$(grep -cE '^bench w[123]_[a-z0-9_]+ median_us=[0-9]+ p90_us=[0-9]+ ref_median_us=[0-9]+ votes=[0-9]+ mem_bytes=[0-9]+ group_mm=[0-9]+$' "$tmp/bench")" -eq 3
check "hl-bench times echo and refinement" grep -qE '^bench w4_echo_refine median_us=[0-9]+ p90_us=[0-9]+ echo_median_us=[0-9]+ refine_median_us=[0-9]+ mem_bytes=[0-9]+$' "$tmp/bench"
check "hl-bench times a laser scan against 15,000 vectors" grep -qE '^bench w5_laser15k median_us=[0-9]+ p90_us=[0-9]+ ref_median_us=[0-9]+ votes=[0-9]+ mem_bytes=[0-9]+ group_mm=48$' "$tmp/bench"
check "hl-bench times the map's round places" grep -qE '^bench w7_map_round median_us=[0-9]+ p90_us=[0-9]+ ns_per_vector=[0-9]+ vectors=[0-9]+ mem_bytes=[0-9]+$' "$tmp/bench"
check "hl-bench's dense workloads vote in 48 mm groups, the others alone" sh -c '
    grep -q "^bench w3_map15k .* group_mm=48$" "$1" && grep -q "^bench w2_local_xyt .* group_mm=0$" "$1"' - "$tmp/bench"
"$BIN/hl-bench" 2 w2 >"$tmp/bench_one"
check "hl-bench RUNS WORKLOAD runs that workload alone" sh -c '
    test "$(wc -l <"$1")" -eq 1 && grep -q "^bench w2_local_xyt " "$1"' - "$tmp/bench_one"
# Loop closure's fit on its synthetic tour: the line parses, and the fit takes back the
# steps' drift past 5 % wrong matches (the worst stop 136 mm from its truth at 256 stops).
"$BIN/hl-bench-posegraph" --stops 256 >"$tmp/pg"
check "hl-bench-posegraph prints its line" grep -qE \
    '^bench posegraph_fit stops=256 edges=[0-9]+ dropped=[0-9]+ first_ms=[0-9.]+ refit_ms=[0-9.]+ next_ms=[0-9.]+ worst_mm=[0-9]+$' "$tmp/pg"
check "hl-bench-posegraph: the fit lands every stop within 200 mm of its truth" \
    awk '{ split($NF, w, "="); exit !(w[2] + 0 < 200) }' "$tmp/pg"
# hl-bench-cycle's loop closure, with and without square walls: each run repeatable (exit
# 0), and the walls change the tour (another checksum).
"$BIN/hl-bench-cycle" --reps 2 --close-loops >"$tmp/cyc_loops"
loops_rc=$?
"$BIN/hl-bench-cycle" --reps 2 --square-walls >"$tmp/cyc_walls"
walls_rc=$?
check "hl-bench-cycle --close-loops and --square-walls: repeatable, different tours" sh -c '
    [ "$1" -eq 0 ] && [ "$2" -eq 0 ] &&
    a=$(sed -n "s/^cycle summary .* checksum=\([0-9a-f]*\)$/\1/p" "$3") &&
    b=$(sed -n "s/^cycle summary .* checksum=\([0-9a-f]*\)$/\1/p" "$4") &&
    [ -n "$a" ] && [ -n "$b" ] && [ "$a" != "$b" ]' - "$loops_rc" "$walls_rc" \
    "$tmp/cyc_loops" "$tmp/cyc_walls"
# ... and with long drives (logs/tour.lcmlog has drives of 2 m or more; with the paper's
# settings a turned one is taken there, so the tour differs; with loop closure's fits
# the tour holds its heading and none is).
"$BIN/hl-bench-cycle" --reps 2 --paper >"$tmp/cyc_paper"
paper_rc=$?
"$BIN/hl-bench-cycle" --reps 2 --paper --long-drives >"$tmp/cyc_drives"
drives_rc=$?
check "hl-bench-cycle --long-drives: repeatable, another tour" sh -c '
    [ "$1" -eq 0 ] && [ "$2" -eq 0 ] &&
    a=$(sed -n "s/^cycle summary .* checksum=\([0-9a-f]*\)$/\1/p" "$3") &&
    b=$(sed -n "s/^cycle summary .* checksum=\([0-9a-f]*\)$/\1/p" "$4") &&
    [ -n "$a" ] && [ -n "$b" ] && [ "$a" != "$b" ]' - "$paper_rc" "$drives_rc" \
    "$tmp/cyc_paper" "$tmp/cyc_drives"

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
printf 'polygon 0 0 5000 0 5000 5000\n\001\002\377garbage 1 2\n' >"$tmp/binary.world"
rejects "a world with binary bytes: one line, no raw bytes echoed" "binary.world:2: unknown keyword a 10-byte non-text word" \
    "$BIN/hl-sim-logs" --world "$tmp/binary.world" --out-dir "$tmp/w"
rejects "bad --soundings" "--soundings" "$BIN/hl-sim-logs" --soundings 0 --out-dir "$tmp/w"
rejects "bad --sonar-model" "--sonar-model" "$BIN/hl-sim-logs" --sonar-model laser --out-dir "$tmp/w"
"$BIN/hl-sim-logs" --seed 1 --sonar-model cone --out-dir "$tmp/cone" >/dev/null
check "--sonar-model cone: the first simulator's echoes, other logs than the default's" \
    sh -c 'test -s "$1/lab28.lcmlog" && ! cmp -s "$1/lab28.lcmlog" logs/lab28.lcmlog' - "$tmp/cone"
rejects "a seed beyond 64 bits" "--seed" "$BIN/hl-sim-logs" --seed 99999999999999999999 --out-dir "$tmp/w"
rejects "an unknown option to hl-sim-logs, in one line" "--bogus" "$BIN/hl-sim-logs" --bogus
# Another building: the corridor world's own layout, orientation square and tour.
"$BIN/hl-sim-logs" --seed 2 --world tools/sim/worlds/corridor.world --out-dir "$tmp/corr" >/dev/null
check "hl-sim-logs makes the corridor world's three logs" \
    sh -c 'test -s "$1/lab28.lcmlog" && test -s "$1/orientation.lcmlog" && test -s "$1/tour.lcmlog" &&
           test -z "$(ls -A "$1" | grep -v lcmlog)"' - "$tmp/corr"
check "... and hl-experiments runs on them" sh -c '"$1" --logs "$2" --out "$3" --no-figures \
    --only table1 --reps 1 2>/dev/null' - "$BIN/hl-experiments" "$tmp/corr" "$tmp/corr_out"
check "... 28 positions (two soundings each): 28 Table 1 trials a row with one map subset" \
    awk -F '\t' 'NR == 2 { exit !($4 == 28) }' "$tmp/corr_out/table1.tsv"
# A world open on one side is refused with one line, and a failed run leaves the folder
# as it was: the old set stays whole.
printf 'segment 0 0 10000 0\nsegment 10000 0 10000 10000\nsegment 0 10000 10000 10000\nopen 1000 1000 9000 9000\norientation 3000 3000\ntour 5000 5000\n' >"$tmp/open.world"
cp -r "$tmp/corr" "$tmp/keep"
rejects "unclosed world" "not closed around" "$BIN/hl-sim-logs" --world "$tmp/open.world" --out-dir "$tmp/keep"
check "a refused world leaves the old logs untouched and no temporary folder" \
    sh -c 'cmp -s "$1/lab28.lcmlog" "$2/lab28.lcmlog" && cmp -s "$1/tour.lcmlog" "$2/tour.lcmlog" &&
           test "$(ls -A "$2" | wc -l)" -eq 3' - "$tmp/corr" "$tmp/keep"
rejects "bad bench runs" "RUNS '-5'" "$BIN/hl-bench" -5
rejects "unknown bench workload" "no workload 'w9'" "$BIN/hl-bench" 2 w9
printf 'segment 0 0 1000\n' >"$tmp/bad.world"
rejects "bad world file" "bad.world:1" "$BIN/hl-sim-logs" --world "$tmp/bad.world" --out-dir "$tmp/w"
rejects "bad limits world" "bad.world:1" "$BIN/hl-experiments" --only limits --world "$tmp/bad.world" --out "$tmp/x"
printf '1000 935\n2000 abc\n' >"$tmp/bad.pairs"
rejects "bad calibration pairs" "bad.pairs:2" "$BIN/hl-calibrate" "$tmp/bad.pairs"

# hl-calibrate prints only what the core accepts (hl_calib_error), and reads stdin only
# when told to.
printf '20000 300\n21000 400\n22000 500\n' >"$tmp/far.pairs"
"$BIN/hl-calibrate" "$tmp/far.pairs" >"$tmp/out" 2>"$tmp/err"
check "hl-calibrate refuses an offset the core rejects: exit 1, one line, nothing printed" \
    sh -c '[ "$1" -eq 1 ] && [ ! -s "$2" ] && [ "$(wc -l <"$3")" -eq 1 ] &&
           grep -q "offset must be within +-10000 mm" "$3"' - $? "$tmp/out" "$tmp/err"
usage_error "hl-calibrate without a file" "input file ('-' for stdin)" "$BIN/hl-calibrate"
printf '1000 935\n2000 1870\n3000 2800\n' | "$BIN/hl-calibrate" - >"$tmp/out" 2>"$tmp/err"
check "hl-calibrate - reads stdin" sh -c '[ "$1" -eq 0 ] &&
    grep -q "^calibration.gain_q16 = 70280$" "$2" && grep -q "^calibration.offset_mm = -4$" "$2"' \
    - $? "$tmp/out"

# A log whose scan seqs repeat (the first ten scans twice) is refused by the experiments'
# reader, naming the file, the event and both seqs.
mkdir -p "$tmp/dup"
"$BIN/hl-eval" split logs/lab28.lcmlog 10 "$tmp/first10.lcmlog" "$tmp/rest.lcmlog"
cat "$tmp/first10.lcmlog" "$tmp/first10.lcmlog" >"$tmp/dup/lab28.lcmlog"
rejects "repeated scan seq in a log" "dup/lab28.lcmlog: event 33: SONAR: seq 0 after seq 9" \
    "$BIN/hl-experiments" --logs "$tmp/dup" --only table1 --out "$tmp/x" --no-figures
cat "$tmp/rest.lcmlog" "$tmp/first10.lcmlog" >"$tmp/dup/lab28.lcmlog"
rejects "decreasing scan seq in a log" "SONAR: seq 0 after seq " \
    "$BIN/hl-experiments" --logs "$tmp/dup" --only table1 --out "$tmp/x" --no-figures

# Every program answers --help on stdout with exit 0.
for p in hl-bench hl-bench-cycle hl-bench-posegraph hl-calibrate hl-experiments hl-sim-draw hl-sim-logs; do
    "$BIN/$p" --help >"$tmp/out" 2>"$tmp/err"
    check "$p --help: exit 0, usage on stdout" sh -c '[ "$1" -eq 0 ] && [ ! -s "$3" ] &&
        grep -qi "usage" "$2"' - $? "$tmp/out" "$tmp/err"
done

# Bad numbers: exit 2 and one line naming the option and the value (letters, trailing
# junk, out of range, leading spaces, hexadecimal), before anything runs.
usage_error "hl-sim-draw --seed abc" "--seed 'abc'" "$BIN/hl-sim-draw" --seed abc --out "$tmp/w.png"
usage_error "hl-bench-posegraph --stops 1" "--stops wants 2..4096, not '1'" "$BIN/hl-bench-posegraph" --stops 1
usage_error "hl-bench-posegraph --wrong abc" "--wrong wants a per cent, 0..100, not 'abc'" \
    "$BIN/hl-bench-posegraph" --wrong abc
usage_error "hl-bench-posegraph --bogus" "not '--bogus'" "$BIN/hl-bench-posegraph" --bogus
usage_error "hl-sim-draw --seed 2^64" "--seed '18446744073709551616'" \
    "$BIN/hl-sim-draw" --seed 18446744073709551616 --out "$tmp/w.png"
usage_error "hl-sim-draw --px-per-m 50x" "--px-per-m '50x'" "$BIN/hl-sim-draw" --px-per-m 50x --out "$tmp/w.png"
usage_error "hl-sim-draw unknown option" "'--bogus'" "$BIN/hl-sim-draw" --bogus
usage_error "hl-calibrate --seed 2^64" "'18446744073709551616'" \
    "$BIN/hl-calibrate" --simulate --seed 18446744073709551616
usage_error "hl-calibrate unknown option" "'--bogus'" "$BIN/hl-calibrate" --bogus
usage_error "hl-bench RUNS 5x" "RUNS '5x'" "$BIN/hl-bench" 5x
usage_error "hl-bench extra argument" "'extra'" "$BIN/hl-bench" 1 w1 extra
usage_error "hl-bench-cycle --reps 5x" "--reps wants a whole number 1..1000, not '5x'" \
    "$BIN/hl-bench-cycle" --reps 5x
usage_error "hl-bench-cycle --start with trailing junk" "'1,2,3abc'" "$BIN/hl-bench-cycle" --start 1,2,3abc
usage_error "hl-bench-cycle --start out of range" "'99999999999999999999,0,0'" \
    "$BIN/hl-bench-cycle" --start 99999999999999999999,0,0
usage_error "hl-experiments --reps ' 5'" "--reps must be a whole number 1..100, not ' 5'" \
    "$BIN/hl-experiments" --reps " 5" --logs "$tmp/nowhere" --out "$tmp/x"
usage_error "hl-experiments unknown option" "unknown option '--bogus'" "$BIN/hl-experiments" --bogus
usage_error "hl-experiments --reps without a value" "--reps needs a value" "$BIN/hl-experiments" --reps
exit $fail
