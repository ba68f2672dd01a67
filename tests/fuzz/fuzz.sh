#!/bin/sh
# tests/fuzz/fuzz.sh - runs the libFuzzer targets for `make fuzz` (tests/fuzz/fuzz.mk).
#
#   fuzz.sh run NAME OUT SECONDS RUNS TIMEOUT
#       runs OUT/fuzz_NAME for SECONDS (or, when RUNS is not empty, until RUNS executions)
#       over a scratch corpus OUT/corpus/NAME: the committed seeds of tests/fuzz/corpus/NAME
#       join whatever earlier runs found there, and the committed folder is never written.
#       Crash inputs go to OUT/crashes/NAME/, libFuzzer's output to OUT/logs/NAME.log, the
#       figures (name, execs, crashes, seconds, corpus files, corpus bytes) to
#       OUT/results/NAME.tsv. Exits 0 even after a crash, so that every target runs.
#       $FUZZ_FLAGS adds libFuzzer options.
#   fuzz.sh summary OUT NAME...
#       one line per target, "fuzz NAME: execs=E crashes=K", then
#       "fuzz targets=T execs=E crashes=K"; OUT/summary.tsv with all the figures. Exits 1
#       if any target crashed or has no figures.
set -u

run() {
    name=$1 out=$2 seconds=$3 runs=$4 timeout=$5
    bin=$out/fuzz_$name
    corpus=$out/corpus/$name
    crashes=$out/crashes/$name
    log=$out/logs/$name.log
    mkdir -p "$corpus" "$crashes" "$out/logs" "$out/results"
    cp tests/fuzz/corpus/"$name"/* "$corpus"/ 2>/dev/null
    stamp=$out/results/$name.stamp
    : > "$stamp"
    if [ -n "$runs" ]; then
        limit="-runs=$runs"
        echo "fuzz: $name until $runs executions" >&2
    else
        limit="-max_total_time=$seconds"
        echo "fuzz: $name for $seconds s" >&2
    fi
    start=$(date +%s)
    # shellcheck disable=SC2086
    "$bin" -artifact_prefix="$crashes/" -print_final_stats=1 -timeout="$timeout" \
        $limit ${FUZZ_FLAGS:-} "$corpus" > "$log" 2>&1
    rc=$?
    secs=$(( $(date +%s) - start ))
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    if [ -z "$execs" ]; then    # no final stats: the last progress line
        execs=$(sed -n 's/^#\([0-9][0-9]*\).*/\1/p' "$log" | tail -n 1)
    fi
    found=$(find "$crashes" -type f -newer "$stamp" | wc -l)
    # A failure that left no input (a crash while loading the corpus, a broken build)
    # still counts.
    if [ "$rc" -ne 0 ] && [ "$found" -eq 0 ]; then
        found=1
    fi
    files=$(find "$corpus" -type f | wc -l)
    bytes=$(find "$corpus" -type f -exec cat {} + | wc -c)
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "${execs:-0}" "$found" "$secs" "$files" \
        "$bytes" > "$out/results/$name.tsv"
    if [ "$found" -gt 0 ]; then
        echo "fuzz: $name: $found crash(es), inputs in $crashes/ (newest first):" >&2
        ls -t "$crashes" | head -n 5 | sed "s|^|    $crashes/|" >&2
        echo "    log: $log" >&2
    fi
    return 0
}

summary() {
    out=$1
    shift
    targets=0 total=0 crashed=0
    printf 'name\texecs\tcrashes\tseconds\tcorpus_files\tcorpus_bytes\n' > "$out/summary.tsv"
    for name in "$@"; do
        targets=$((targets + 1))
        f=$out/results/$name.tsv
        if [ ! -f "$f" ]; then
            echo "fuzz $name: execs=0 crashes=1 (not run)"
            crashed=$((crashed + 1))
            continue
        fi
        cat "$f" >> "$out/summary.tsv"
        IFS='	' read -r _ execs found _ < "$f"
        echo "fuzz $name: execs=$execs crashes=$found"
        total=$((total + execs))
        crashed=$((crashed + found))
    done
    echo "fuzz targets=$targets execs=$total crashes=$crashed"
    [ "$crashed" -eq 0 ]
}

cmd=${1:-}
[ $# -gt 0 ] && shift
case $cmd in
run) run "$@" ;;
summary) summary "$@" ;;
*) echo "usage: fuzz.sh run NAME OUT SECONDS RUNS TIMEOUT | summary OUT NAME..." >&2; exit 2 ;;
esac
