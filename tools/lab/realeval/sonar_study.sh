#!/bin/sh
# sonar_study.sh [BUILDING ...] - where the pseudo-sonar ring's error comes from
# (docs/results/real-buildings.md, "Where the sonar's error goes"): for each building
# (default intel aces freiburg-079), hl-sonar-study's echo placement and normals against
# the laser under four preparations, then the localizer against a map drawn at the true
# poses under four settings and with multiscans of 2 and 4 scans, and how well the ground
# truth itself agrees with the laser from one scan to the next and where the robot comes
# back 300 scans or more later. One line a figure,
# prefixed with the building and the variant. Environment: BUILD (default build), DATA
# (default ../shared/data), EVAL_OUT (default BUILD/eval; the imports are shared with
# make eval-real). A failing step stops with one line naming it, exit status 1.
set -u
BUILD=${BUILD:-build}
EVAL_OUT=${EVAL_OUT:-$BUILD/eval}
BIN=$BUILD/bin
HERE=$(dirname "$0")
[ $# -gt 0 ] || set -- intel aces freiburg-079
die() { echo "sonar_study: $1" >&2; exit 1; }
for b in "$@"; do
    for input in sonar laser; do
        log=$EVAL_OUT/input/${b}_${input}_every.lcmlog
        [ -s "$log" ] || BUILD=$BUILD EVAL_OUT=$EVAL_OUT sh "$HERE/run_one.sh" import "$b" "$input" every ||
            die "$b: import $input failed"
    done
    sonar=$EVAL_OUT/input/${b}_sonar_every.lcmlog laser=$EVAL_OUT/input/${b}_laser_every.lcmlog
    while read -r name settings; do
        # shellcheck disable=SC2086
        line=$("$BIN/hl-sonar-study" echo "$sonar" "$laser" $settings) ||
            die "$b: hl-sonar-study echo $name failed"
        echo "$b $name $line"
    done <<'VARIANTS'
beam-axis slam.echo_bearings=false echo.flank_normals=false
echo-bearings echo.flank_normals=false
fitted-normals echo.flank_normals=false slam.fit_normals=true normals.keep_unfitted=true
flank-normals echo.flank_normals=true
VARIANTS
    while read -r name window settings; do
        # shellcheck disable=SC2086
        line=$(WINDOW=$window "$BIN/hl-sonar-study" oracle "$sonar" 30 $settings) ||
            die "$b: hl-sonar-study oracle $name failed"
        echo "$b $name $line"
    done <<'VARIANTS'
beam-normals,polish 0 slam.refine=true echo.flank_normals=false
beam-normals 0 echo.flank_normals=false
flank-normals,polish 0 slam.refine=true
the-profile 0
multiscan-2 2
multiscan-4 4
VARIANTS
    line=$("$BIN/hl-sonar-study" truth "$laser") || die "$b: hl-sonar-study truth failed"
    echo "$b ground-truth $line"
    line=$("$BIN/hl-sonar-study" revisits "$laser") || die "$b: hl-sonar-study revisits failed"
    echo "$b ground-truth-revisits $line"
done
