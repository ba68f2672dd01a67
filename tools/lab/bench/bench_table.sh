#!/bin/sh
# bench_table.sh LOCALIZER.txt DAEMON.txt - the figures of one `make bench` as a Markdown
# page (make bench writes it to docs/results/bench-table.md, which README.md and
# docs/results/performance.md link instead of carrying numbers of their own).
#   LOCALIZER.txt  hl-bench's lines ("bench w1_global_xy median_us=... ...")
#   DAEMON.txt     bench_daemon.sh's lines ("bench daemon_replay scans=... ...")
# Fails (exit 1, nothing on stdout) when a line the page needs is missing: a benchmark
# that failed leaves the last page in place.
set -eu
[ $# -eq 2 ] || { echo "usage: bench_table.sh LOCALIZER.txt DAEMON.txt" >&2; exit 2; }
loc=$1 daemon=$2

# field FILE NAME KEY: KEY's value on FILE's line "bench NAME ..."
field() {
    awk -v n="$2" -v k="$3" '$1 == "bench" && $2 == n {
        for (i = 3; i <= NF; i++)
            if (index($i, k "=") == 1) { print substr($i, length(k) + 2); exit }
    }' "$1"
}
need() {
    v=$(field "$@")
    [ -n "$v" ] || { echo "bench_table.sh: no $3 on the '$2' line of $1" >&2; exit 1; }
    echo "$v"
}
# thousands FIGURE: 12345 -> 12,345
thousands() {
    echo "$1" | sed ':a; s/\([0-9]\)\([0-9]\{3\}\)\($\|[,.]\)/\1,\2\3/; ta'
}
mib() {
    awk -v k="$1" 'BEGIN { printf "%.1f MiB", k / 1024 }'
}

w2=$(need "$loc" w2_local_xyt median_us)
replay=$(need "$daemon" daemon_replay compute_median_us)
for name in daemon_replay daemon_replay_watch daemon_replay_loops; do
    for key in scans compute_median_us compute_p99_us scans_per_s peak_rss_kib; do
        need "$daemon" $name $key >/dev/null
    done
done
cpu=$(sed -n 's/^model name[^:]*: *//p' /proc/cpuinfo 2>/dev/null | head -n 1)
load=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)
ratio=$(awk -v a="$replay" -v b="$w2" 'BEGIN { printf "%.1f", a / b }')
verdict=$(awk -v a="$replay" -v b="$w2" 'BEGIN { print (a <= 4 * b) ? "within" : "OVER" }')

cat <<EOF
# \`make bench\`: the latest figures

Written by \`make bench\` (\`tools/lab/bench/bench_table.sh\`), not by hand: $(date -u +%Y-%m-%d),
$cpu, $(nproc 2>/dev/null || echo "?") cores, load average $load at the end of the run. On a
loaded machine the times scatter; what they mean and how they are made:
[performance.md](performance.md).

## The daemon replaying \`logs/tour.lcmlog\`

\`houghlocd\` in batch mode, five runs; the per-scan figures are its own STATUS over
every scan of the last run (SONAR decoded to POSE published), the whole process's rate
the median run's, memory the peak resident set.

| line | scans | per-scan median | p99 | whole process | peak RSS |
|---|---|---|---|---|---|
EOF
row() {     # row NAME WHAT
    printf '| `%s` (%s) | %s | %s us | %s us | %s scans/s | %s |\n' "$1" "$2" \
        "$(field "$daemon" "$1" scans)" \
        "$(thousands "$(field "$daemon" "$1" compute_median_us)")" \
        "$(thousands "$(field "$daemon" "$1" compute_p99_us)")" \
        "$(thousands "$(field "$daemon" "$1" scans_per_s)")" \
        "$(mib "$(field "$daemon" "$1" peak_rss_kib)")"
}
row daemon_replay "the defaults"
row daemon_replay_watch "\`slam.search_every = 1\`: the global search on every scan"
row daemon_replay_loops "\`slam.close_loops\`"
cat <<EOF

The defaults' per-scan median is $ratio times \`w2_local_xyt\`'s (one local search,
below): $verdict the budget of 4.

## The localizer (\`hl-bench\`)

| workload | median | p90 | reference |
|---|---|---|---|
EOF
for w in w1_global_xy w2_local_xyt w3_map15k w4_echo_refine w5_laser15k w6_reloc_lab \
         w7_map_round; do
    m=$(field "$loc" $w median_us)
    [ -n "$m" ] || continue
    ref=$(field "$loc" $w ref_median_us)
    printf '| `%s` | %s us | %s us | %s |\n' $w "$(thousands "$m")" \
        "$(thousands "$(field "$loc" $w p90_us)")" "${ref:+$(thousands "$ref") us}"
done
