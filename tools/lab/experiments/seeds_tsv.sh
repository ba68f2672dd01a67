#!/bin/sh
# seeds_tsv.sh - the experiments over many layouts: for each world (the built-in lab and
# tools/sim/worlds/corridor.world) and each seed 1..N, hl-sim-logs makes a data set (its
# own 28 positions, orientation square and tour) and hl-experiments runs Table 1, the
# orientation test and the tour in both modes; the figures are summarized over the seeds
# into one table (`make experiments-seeds`, docs/results/experiments.md):
#
#   sh tools/lab/experiments/seeds_tsv.sh [N [OUT]]       (after `make`; N default 10)
#
# OUT (default BUILD/experiments/seeds.tsv): header, then one row per (world, experiment,
# mode, prior, fraction, raster_mm, metric), tab-separated:
#   world experiment mode prior fraction raster_mm metric mean min max seeds
# world lab|corridor; experiment table1|orientation|tour; mode paper|improved; prior
# yes|no (Table 1: the improved mode's prior estimate; orientation and tour: the odometry
# prior of the online cycle); fraction 1/16..3/16 and raster_mm 47|24 for Table 1, `-`
# elsewhere; metric wild_pct, tame_mean_mm (table1), sigma_deg (orientation), rmse_mm,
# wild_accepted (tour); the last four numbers only. Progress on stderr; two runs at a
# time. A failing run stops it with one line naming the world, the seed and the step.
set -u
n=${1:-10}
case $n in ''|*[!0-9]*|0) echo "seeds_tsv.sh: N must be a positive whole number, not '$n'" >&2; exit 2 ;; esac
bin=${BUILD:-build}/bin
out=${2:-${BUILD:-build}/experiments/seeds.tsv}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for p in hl-sim-logs hl-experiments; do
    [ -x "$bin/$p" ] || { echo "seeds_tsv.sh: no $bin/$p (run make first)" >&2; exit 1; }
done

run() {     # run WORLD SEED: one data set and its experiments; a failure leaves $d/failed
    w=$1 s=$2 d=$tmp/$1/$2
    mkdir -p "$d"
    wopt=""
    [ "$w" = corridor ] && wopt="--world tools/sim/worlds/corridor.world"
    # shellcheck disable=SC2086
    if ! "$bin/hl-sim-logs" --seed "$s" --out-dir "$d/logs" $wopt >"$d/sim.log" 2>&1; then
        echo "data set: $(tail -n 1 "$d/sim.log")" >"$d/failed"
        return
    fi
    if ! "$bin/hl-experiments" --logs "$d/logs" --out "$d/out" --no-figures \
        --only table1,orientation,combined >"$d/exp.log" 2>&1; then
        echo "experiments: $(tail -n 1 "$d/exp.log")" >"$d/failed"
    fi
}

total=$((2 * n)) done_runs=0
for w in lab corridor; do
    s=1
    while [ "$s" -le "$n" ]; do
        run "$w" "$s" &
        [ $((s + 1)) -le "$n" ] && run "$w" $((s + 1)) &
        wait
        for k in "$s" $((s + 1)); do
            [ "$k" -le "$n" ] || continue
            if [ -f "$tmp/$w/$k/failed" ]; then
                echo "seeds_tsv.sh: $w seed $k: $(cat "$tmp/$w/$k/failed")" >&2
                exit 1
            fi
            done_runs=$((done_runs + 1))
            echo "seeds_tsv.sh: $w seed $k done ($done_runs of $total)" >&2
        done
        s=$((s + 2))
    done
done

# One line per (key, value) from every run, then the summary per key.
for w in lab corridor; do
    for d in "$tmp/$w"/*/out; do
        awk -F'\t' -v w="$w" 'FNR > 1 {
            pr = $9 == "" ? "no" : $9
            printf "%s\ttable1\t%s\t%s\t%s\t%s\twild_pct\t%s\n", w, $1, pr, $2, $3, $6
            printf "%s\ttable1\t%s\t%s\t%s\t%s\ttame_mean_mm\t%s\n", w, $1, pr, $2, $3, $7 }' \
            "$d/table1.tsv"
        awk -F'\t' -v w="$w" 'FNR > 1 {
            printf "%s\torientation\t%s\t%s\t-\t-\tsigma_deg\t%s\n", w, $1, $1 == "paper" ? "no" : "yes", $4 }' \
            "$d/orientation.tsv"
        awk -F'\t' -v w="$w" 'FNR > 1 && $1 != "odometry" {
            pr = $1 == "paper" ? "no" : "yes"
            printf "%s\ttour\t%s\t%s\t-\t-\trmse_mm\t%s\n", w, $1, pr, $6
            printf "%s\ttour\t%s\t%s\t-\t-\twild_accepted\t%s\n", w, $1, pr, $5 }' \
            "$d/combined.tsv"
    done
done >"$tmp/all.tsv"

mkdir -p "$(dirname "$out")"
{
    printf 'world\texperiment\tmode\tprior\tfraction\traster_mm\tmetric\tmean\tmin\tmax\tseeds\n'
    awk -F'\t' '
        { k = $1 "\t" $2 "\t" $3 "\t" $4 "\t" $5 "\t" $6 "\t" $7
          if (!(k in n)) { order[++keys] = k; lo[k] = $8; hi[k] = $8 }
          n[k]++; sum[k] += $8
          if ($8 < lo[k]) lo[k] = $8
          if ($8 > hi[k]) hi[k] = $8 }
        END { for (i = 1; i <= keys; i++) { k = order[i]
                  printf "%s\t%.2f\t%.2f\t%.2f\t%d\n", k, sum[k] / n[k], lo[k], hi[k], n[k] } }' \
        "$tmp/all.tsv"
} >"$out.tmp" && mv "$out.tmp" "$out"
echo "seeds_tsv.sh: $out ($(($(wc -l <"$out") - 1)) rows, $n seeds per world)" >&2
