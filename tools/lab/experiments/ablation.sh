#!/bin/sh
# ablation.sh - what each change of the improved mode buys: reruns the experiments with
# the improved mode minus one change at a time and prints one table row per variant.
#   sh tools/lab/experiments/ablation.sh [LOGS_DIR]      (after `make`)
set -eu
logs=${1:-logs}
bin=${BUILD:-build}/bin/hl-experiments
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

row() {   # row LABEL ARGS...
    label=$1; shift
    "$bin" --logs "$logs" --out "$tmp" --no-figures --only table1,orientation,combined "$@" 2>/dev/null
    t1=$(awk -F'\t' '$1=="improved" && $3==24 && $2=="3/16" {printf "%s %% / %s mm", $6, $7}' "$tmp/table1.tsv")
    or=$(awk -F'\t' '$1=="improved" {printf "%s / %s deg", $3, $4}' "$tmp/orientation.tsv")
    co=$(awk -F'\t' '$1=="improved" {printf "%s / %s mm, %s wild", $6, $7, $5}' "$tmp/combined.tsv")
    printf '| %s | %s | %s | %s |\n' "$label" "$t1" "$or" "$co"
}

echo "| variant | Table 1, 24 mm, 3/16: wild / tame mean | orientation: mean / sigma | combined: RMSE / max, wild accepted |"
echo "|---|---|---|---|"
row "improved (all changes)"
row "without echo-bearing estimation (readings on their beam axes)" --set improved.echo_bearings=0
row "without refinement (the Hough pose)" --set improved.refine=0
row "refinement of x and y only (the Hough's heading)" --set improved.refine_heading=0
row "blur 36 mm instead of 60" --set improved.blur_sigma_mm=36
row "without sub-cell interpolation" --set improved.interpolate=0
row "without the odometry prior (Table 1: no prior estimate, so a global search)" --set improved.use_prior=0 --set improved.table1_prior_sigma_mm=0
row "without the guard (accept every pose)" --set improved.guarded=0
row "global search (no window, no prior)" --set improved.window_mm=0 --set improved.use_prior=0 --set improved.table1_prior_sigma_mm=0
