#!/bin/sh
# The daemon's benchmark (make bench): replays logs/tour.lcmlog through houghlocd in batch
# mode RUNS times (default 5) and prints one line:
#   bench daemon_replay scans=<n> wall_ms=<median> scans_per_s=<n> compute_median_us=<n>
#         compute_p99_us=<n> peak_rss_kib=<n>
# for the defaults (whose time budget docs/results/performance.md gives: the watch
# searches the whole map only on scans in doubt and every slam.search_every-th), then
# the same line named daemon_replay_watch with slam.search_every=1, where every scan
# also runs the global search that notices a kidnapped robot
# (docs/design/relocalization.md), then daemon_replay_loops with slam.close_loops=true
# (loop closure, slam.h; off by default). make bench makes a page of them
# (bench_table.sh: docs/results/bench-table.md).
# wall_ms is the whole process (start, replay, map save, exit); the compute figures are
# houghlocd's own STATUS (the cycle's latency per scan, SONAR handler entry to POSE out,
# over all scans of the last run);
# peak_rss_kib is the largest resident set of the last run (getrusage).
set -eu
BIN=${BUILD:-build}/bin
RUNS=${1:-5}
LOG=$PWD/logs/tour.lcmlog
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
replay() {  # replay NAME [ARGS...]: RUNS replays, one line
    name=$1; shift
    rm -f "$tmp/wall_us"
    i=0
    while [ $i -lt "$RUNS" ]; do
        i=$((i + 1))
        t0=$(date +%s%N)
        "$BIN/houghlocd" --config /dev/null --fresh-map --map "$tmp/map.hlmap" \
            --set daemon.compute_window=10000 --lcm-url "file://$LOG?speed=0" \
            --lcm-out "file://$tmp/out.lcmlog?mode=w" "$@" 2>"$tmp/err"
        t1=$(date +%s%N)
        echo $(( (t1 - t0) / 1000 )) >>"$tmp/wall_us"
    done
    wall_us=$(sort -n "$tmp/wall_us" | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
    status=$("$BIN/hl-eval" status "$tmp/out.lcmlog")
    field() { echo "$status" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
    scans=$(field scans)
    rss=$(sed -n 's/.*peak memory \([0-9]*\) KiB.*/\1/p' "$tmp/err")
    echo "bench $name scans=$scans wall_ms=$((wall_us / 1000)) scans_per_s=$((scans * 1000000 / wall_us)) compute_median_us=$(field compute_median_us) compute_p99_us=$(field compute_p99_us) peak_rss_kib=$rss"
}
replay daemon_replay
replay daemon_replay_watch --set slam.search_every=1
replay daemon_replay_loops --set slam.close_loops=true
