#!/bin/sh
# report.sh - assembles the tables of `make eval-real` (tools/lab/realeval/realeval.mk).
#
#   report.sh tsv EVAL_OUT 'BUILDING ...'
#       prints real.tsv: the header, then the row files
#       EVAL_OUT/rows/B_INPUT_MODE_SEL_START.tsv that run_one.sh wrote, in the order
#       building (as given), input (laser, sonar), mode (odometry, paper, improved, loops),
#       selection (every, moved), start (origin, turned30, turned45, truth; odometry: origin)
#   report.sh md EVAL_OUT 'BUILDING ...' BASELINES
#       prints real.md from EVAL_OUT/real.tsv: one table per input of the origin rows,
#       each building's peers (CSM, BreezySLAM and odometry alone, read from the table of
#       BASELINES, ../shared/BASELINES.md) above them; then one table per input of the ATE
#       from every start with the spread of the three start frames (origin, turned30,
#       turned45): max - min, and that over their median. A building BASELINES does not
#       list, or a BASELINES file that is missing, just has no peer rows.
#
# Exit status 1, with one line on stderr, when a row file is missing or malformed.
set -u

HEADER="dataset	input	mode	selection	scans	ate_rmse_m	rpe_trans_rmse_m	rpe_trans_mean_m	max_err_m	ms_per_scan	wall_ms_per_scan	rejected	start"

usage() {
    echo "usage: report.sh tsv EVAL_OUT 'BUILDING ...' | md EVAL_OUT 'BUILDING ...' BASELINES" >&2
    exit 2
}

tsv() {     # tsv EVAL_OUT BUILDINGS
    printf '%s\n' "$HEADER"
    for b in $2; do
        for i in laser sonar; do
            for m in odometry paper improved loops; do
                starts="origin turned30 turned45 truth"
                [ "$m" = odometry ] && starts=origin
                for s in every moved; do for t in $starts; do
                    f=$1/rows/${b}_${i}_${m}_${s}_${t}.tsv
                    if [ ! -r "$f" ]; then
                        echo "eval-real: $b $i $s $m $t: report failed: no row $f" >&2
                        exit 1
                    fi
                    # one line of 13 cells: numbers, or `-`, and the start
                    if ! awk -F '\t' -v b="$b" -v i="$i" -v m="$m" -v s="$s" -v t="$t" '
                        NR > 1 || NF != 13 || $1 != b || $2 != i || $3 != m || $4 != s || $13 != t { bad = 1 }
                        { for (k = 5; k <= 12; k++) if ($k != "-" && $k !~ /^[0-9]+(\.[0-9]+)?$/) bad = 1 }
                        END { exit bad || NR != 1 }' "$f"; then
                        echo "eval-real: $b $i $s $m $t: report failed: $f is not one row of 13 cells" >&2
                        exit 1
                    fi
                    cat "$f"
                done; done
            done
        done
    done
}

md() {      # md EVAL_OUT BUILDINGS BASELINES
    [ -r "$1/real.tsv" ] || { echo "eval-real: report failed: no $1/real.tsv" >&2; exit 1; }
    base=$3
    [ -r "$base" ] || base=/dev/null
    cat <<EOF
# houghloc on the real buildings

Written by \`make eval-real\` (tools/lab/realeval/, docs/results/real-buildings.md): every figure of ours is
houghlocd's batch replay of an import of \`raw/<building>-raw.log.gz\`, scored by
houghloc-eval against \`raw/<building>-groundtruth.tum\` as evo scores (ATE: RMSE of
position after rigid alignment; RPE: translation error over 1 m segments). The tables
of methods are the runs from the robot's own start frame (*origin*: no start pose given,
the daemon's default 0, 0, 0; no ground truth reaches the run); the last tables give
every start beside it.
The peers' figures are those of \`$(basename "$3")\`$( [ "$base" = /dev/null ] && printf ' (not found: none shown)')
(CSM, BreezySLAM, and odometry alone as it scored it); they used every scan.

- *every*: every laser scan; *moved*: a scan when the odometry moved 0.5 m or turned 15
  degrees (houghloc-import-carmen --select moved), as the paper's robot sounded.
- *ms per scan*: ours, compute = the median time of localize + integrate per scan as
  the daemon measures it (STATUS); wall = the daemon process's whole wall time / scans
  (reading the log, writing POSE, MAP and STATUS, saving the map), as the peers were
  timed. Their figure is wall time.
- *rejected / odometry only*: scans the improved mode's guard refused, and scans the
  daemon did not localize (a map too small to match, a localization that failed); the
  estimate follows the odometry over both. The paper mode has no guard.
- *starts*: *origin* the robot's own frame; *turned 30 / 45* that frame turned 30 / 45
  degrees (start.heading_deg, at 0, 0: the map's axes turned against the building's);
  *first true pose* the daemon started at the log's first true pose, in the building's
  own axes, which no robot knows: for reference only. *Spread*: the largest minus the
  smallest ATE of the three start frames (origin, turned 30, turned 45), and that over
  their median. The odometry's error, aligned as a whole, does not depend on the start.
EOF
    awk -F '\t' -v blist="$2" -v basefile="$base" -v runs="$1/runs" '
    function trim(x) { gsub(/^[ \t]+|[ \t]+$/, "", x); return x }
    function m3(x) { return x == "-" || x == "" ? "–" : sprintf("%.3f", x) }
    function ms2(x) { return x == "-" ? "–" : sprintf("%.2f", x) }
    function odonly(cell,   f, l, n, kv, w, j, r) {   # odometry_only= of the run, or ?
        f = runs "/" cell "/score.txt"; r = "?"
        while ((getline l < f) > 0) {
            n = split(l, w, " ")
            for (j = 1; j <= n; j++)
                if (split(w[j], kv, "=") == 2 && kv[1] == "odometry_only") r = kv[2]
        }
        close(f)
        return r
    }
    BEGIN {
        nb = split(blist, bs, " ")
        # BASELINES: | building | method | ATE RMSE (m) | RPE rmse / mean (m) | scans | ms |
        while ((getline line < basefile) > 0) {
            n = split(line, c, "|")
            if (n < 8) continue
            b = trim(c[2]); meth = trim(c[3])
            if (meth != "odometry alone" && meth != "CSM" && meth != "BreezySLAM") continue
            k = b SUBSEP meth
            peer[k] = 1; pate[k] = trim(c[4]); prpe[k] = trim(c[5])
            pscans[k] = trim(c[6]); pms[k] = trim(c[7])
        }
        close(basefile)
    }
    NR == 1 { next }
    { key = $1 SUBSEP $2 SUBSEP $3 SUBSEP $4; ate[key, $13] = $6; if ($13 == "origin") row[key] = $0 }
    END {
        split("odometry alone|CSM|BreezySLAM", peers, "|")
        split("odometry|paper|improved|loops", modes, "|")
        split("every|moved", sels, "|")
        label["odometry"] = "odometry alone"
        label["paper"] = "houghloc, paper mode"
        label["improved"] = "houghloc, improved mode"
        label["loops"] = "houghloc, improved mode with loop closure"
        for (ii = 1; ii <= 2; ii++) {
            inp = ii == 1 ? "laser" : "sonar"
            printf "\n## %s input\n\n", inp == "laser" ? "Laser" : "Pseudo-sonar"
            print "| building | method | scans | ATE RMSE (m) | RPE 1 m rmse / mean (m) | max error (m) | ms per scan: compute / wall | rejected / odometry only |"
            print "|---|---|---|---|---|---|---|---|"
            for (bi = 1; bi <= nb; bi++) {
                b = bs[bi]
                for (p = 1; p <= 3; p++) {
                    k = b SUBSEP peers[p]
                    if (!(k in peer)) continue
                    printf "| %s | %s (peers%s) | %s | %s | %s | – | – / %s | – |\n", b, peers[p],
                        p == 1 ? "" : ", every", pscans[k], pate[k], prpe[k], pms[k]
                }
                for (si = 1; si <= 2; si++)
                    for (mi = 1; mi <= 4; mi++) {
                        k = b SUBSEP inp SUBSEP modes[mi] SUBSEP sels[si]
                        if (!(k in row)) continue
                        split(row[k], v, "\t")
                        rej = v[12] == "-" ? "–" : v[12] " / " odonly(b "_" inp "_" modes[mi] "_" sels[si] "_origin")
                        printf "| %s | %s, %s | %s | %s | %s / %s | %s | %s / %s | %s |\n", b,
                            label[modes[mi]], sels[si], v[5], m3(v[6]), m3(v[7]), m3(v[8]),
                            m3(v[9]), ms2(v[10]), ms2(v[11]), rej
                    }
            }
        }
        split("origin|turned30|turned45", frames, "|")
        for (ii = 1; ii <= 2; ii++) {
            inp = ii == 1 ? "laser" : "sonar"
            printf "\n## Start frames, %s input (ATE RMSE, m)\n\n", inp == "laser" ? "laser" : "pseudo-sonar"
            print "| building | method | origin | turned 30 | turned 45 | spread: max - min (of the median) | first true pose (reference) |"
            print "|---|---|---|---|---|---|---|"
            for (bi = 1; bi <= nb; bi++)
                for (mi = 4; mi >= 2; mi--)
                    for (si = 1; si <= 2; si++) {
                        k = bs[bi] SUBSEP inp SUBSEP modes[mi] SUBSEP sels[si]
                        if (!((k, "origin") in ate)) continue
                        lo = ""; hi = ""; n3 = 0
                        for (f = 1; f <= 3; f++) {
                            if (!((k, frames[f]) in ate) || ate[k, frames[f]] == "-") continue
                            x[++n3] = ate[k, frames[f]] + 0
                            if (lo == "" || x[n3] < lo) lo = x[n3]
                            if (hi == "" || x[n3] > hi) hi = x[n3]
                        }
                        # the median of three: the sum less the largest and the smallest
                        med = x[1] + x[2] + x[3] - hi - lo
                        spread = n3 < 3 ? "–" : med <= 0 ? sprintf("%.3f", hi - lo) : \
                            sprintf("%.3f (%.0f %%)", hi - lo, 100 * (hi - lo) / med)
                        printf "| %s | %s, %s | %s | %s | %s | %s | %s |\n", bs[bi],
                            label[modes[mi]], sels[si], m3(ate[k, "origin"]), m3(ate[k, "turned30"]),
                            m3(ate[k, "turned45"]), spread, m3(ate[k, "truth"])
                    }
        }
    }' "$1/real.tsv"
}

[ $# -ge 1 ] || usage
case $1 in
tsv) [ $# -eq 3 ] || usage; tsv "$2" "$3" ;;
md) [ $# -eq 4 ] || usage; md "$2" "$3" "$4" ;;
*) usage ;;
esac
