#!/bin/sh
# seeds.sh - the improved mode over many simulated data sets, not just seed 1: makes the
# data sets of seeds 1..N (hl-sim-logs), runs the experiments on each and prints the
# means that docs/results/experiments.md quotes.
#   sh tools/lab/experiments/seeds.sh [N [HL-EXPERIMENTS ARGS...]]      (after `make`)
#   sh tools/lab/experiments/seeds.sh 24 --only combined --set improved.refine_heading=0
#   SIM_ARGS="--rotation-sigma-deg 0" sh tools/lab/experiments/seeds.sh 12 --only orientation,limits
# SIM_ARGS goes to hl-sim-logs (the same data sets with one simulated effect changed).
# Default: N = 12, all experiments except limits (add `--only limits` for the oracles'
# floors). Two runs at a time.
set -eu
n=${1:-12}
[ $# -gt 0 ] && shift
case $n in
    ''|*[!0-9]*) echo "seeds.sh: N must be a whole number, not '$n'" >&2; exit 2 ;;
esac
[ $# -gt 0 ] || set -- --only table1,orientation,combined
bin=${BUILD:-build}/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

run() {     # run SEED ARGS...: data set, then experiments, quietly
    seed=$1
    shift
    # shellcheck disable=SC2086  # SIM_ARGS is a list of options
    "$bin/hl-sim-logs" --seed "$seed" --out-dir "$tmp/logs$seed" ${SIM_ARGS:-} >/dev/null
    "$bin/hl-experiments" --logs "$tmp/logs$seed" --out "$tmp/out$seed" --no-figures "$@" 2>/dev/null
}
s=1
while [ "$s" -le "$n" ]; do
    a=$s
    b=$((s + 1))
    run "$a" "$@" &
    [ "$b" -le "$n" ] && { run "$b" "$@" & }
    wait
    s=$((s + 2))
done

cat "$tmp"/out*/combined.tsv 2>/dev/null | awk -F'\t' -v n="$n" '
    $1 == "improved" { r += $6; f += $8; w += $5; k++; ir[k] = $6; iff[k] = $8 }
    $1 == "odometry" { o += $6; of += $8; j++; orr[j] = $6; off[j] = $8 }
    END { if (k == 0) exit
          for (i = 1; i <= k; i++) { if (ir[i] < orr[i]) beat++; if (iff[i] * 5 <= off[i]) five++ }
          printf "tour, %d seeds: improved RMSE %.0f mm, final %.0f mm, wild accepted %.1f; odometry RMSE %.0f mm, final %.0f mm; better than odometry in %d, final 5x lower in %d\n",
                 k, r / k, f / k, w / k, o / j, of / j, beat, five }'
cat "$tmp"/out*/table1.tsv 2>/dev/null | awk -F'\t' '
    $1 == "improved" { k = $3 " mm, " $2; t[k] += $4; w[k] += $5; m[k] += $7; c[k]++ }
    END { for (k in c) printf "Table 1, %s, %d seeds: wild %.2f %%, tame mean %.1f mm\n", k, c[k], 100 * w[k] / t[k], m[k] / c[k] }' | sort
cat "$tmp"/out*/orientation.tsv 2>/dev/null | awk -F'\t' '
    $1 == "improved" { a += ($3 < 0 ? -$3 : $3); s += $4; k++ }
    END { if (k) printf "orientation, %d seeds: mean |bias| %.2f deg, sigma %.2f deg\n", k, a / k, s / k }'
cat "$tmp"/out*/limits.tsv 2>/dev/null | awk -F'\t' '
    $1 == "what" { next }
    { k = $1; if (!(k in n)) order[++rows] = k
      n[k]++; t[k] += $2; w[k] += $3; p[k] += $4; m[k] += ($5 < 0 ? -$5 : $5); s[k] += $6
      if ($4 > worst[k]) worst[k] = $4
      if (!(k in best) || $4 < best[k]) best[k] = $4 }
    END { for (i = 1; i <= rows; i++) { k = order[i]
              printf "limits, %d seeds: %s: wild %.1f %%", n[k], k, 100 * w[k] / t[k]
              if (p[k] > 0) printf ", position %.1f mm (seeds %.1f to %.1f)", p[k] / n[k], best[k], worst[k]
              if (s[k] > 0) printf ", heading |bias| %.2f deg, sigma %.2f deg", m[k] / n[k], s[k] / n[k]
              printf "\n" } }'
