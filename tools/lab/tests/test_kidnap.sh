#!/bin/sh
# Integration test of `make kidnap` (tools/lab/kidnap/) on a tiny configuration, without the
# real data: the simulated lab with 10 trials (its tour, the daemon's map of it, the
# row), then the table's header, its one row (names, numbers in range, shares adding up
# to 100) and the summary line; the per-trial file; the leave-one-stretch-out path of
# hl-kidnap on a log with ground truth (the lab tour stands in for a building); a
# building without data stops with a line naming it; bad usage of hl-kidnap.
set -u
BUILD=${BUILD:-build}
BIN=$BUILD/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
# A make inside make lab-test: not the outer make's jobserver.
unset MAKEFLAGS MFLAGS MAKELEVEL

out=$tmp/kidnap
tsv=$tmp/kidnap.tsv
header=$(printf 'world\tinput\ttrials\tsuccess_pct\tambiguous_pct\twrong_pct\tmedian_ms\tp90_ms')

make --no-print-directory BUILD="$BUILD" kidnap BUILDINGS= KIDNAP_WORLDS=lab \
    KIDNAP_TRIALS_SIM=10 KIDNAP_TOUR_SEEDS='1 2' KIDNAP_OUT="$out" KIDNAP_TSV="$tsv" \
    >"$tmp/make.out" 2>"$tmp/make.err"
rc=$?
check "make kidnap on the lab, two tours, 10 trials each, exits 0" [ $rc -eq 0 ]
[ $rc -eq 0 ] || tail -n 5 "$tmp/make.err"
check "kidnap.tsv's header" [ "$(head -n 1 "$tsv" 2>/dev/null)" = "$header" ]
check "kidnap.tsv has the header and one row" [ "$(wc -l <"$tsv" 2>/dev/null)" -eq 2 ]
check "the row: lab sonar 20, numbers in range, shares add up to 100, median <= p90" \
    awk -F'\t' 'NR == 2 {
        if (NF != 8 || $1 != "lab" || $2 != "sonar" || $3 != 20) exit 1
        for (k = 4; k <= 8; k++) if ($k !~ /^[0-9]+(\.[0-9]+)?$/) exit 1
        for (k = 4; k <= 6; k++) if ($k < 0 || $k > 100) exit 1
        s = $4 + $5 + $6; if (s < 99.8 || s > 100.2) exit 1
        # twenty trials: every share a whole multiple of 5 %
        for (k = 4; k <= 6; k++) if (($k * 10) % 50 != 0) exit 1
        if ($7 <= 0 || $7 > $8 || $8 > 60000) exit 1
        ok = 1 }
        END { exit !ok }' "$tsv"
check "stdout ends with the table and the summary line" \
    sh -c "tail -n 1 '$tmp/make.out' | grep -q '^kidnap rows=1 trials=20 worst_success_pct=[0-9.]* (lab sonar) worst_wrong_pct=[0-9.]* (lab sonar) seconds=[0-9]*\$' &&
           grep -q '^lab	sonar	20	' '$tmp/make.out'"
check "progress on stderr: each tour's error and each map's trials" \
    sh -c "grep -q '^kidnap: lab sonar, tour 1: the tour.s stops=' '$tmp/make.err' &&
           grep -q '^kidnap: lab sonar, tour 2: the tour.s stops=' '$tmp/make.err' &&
           grep -q '^kidnap: lab sonar: map 1/2: 10/10 trials: success' '$tmp/make.err' &&
           grep -q '^kidnap: lab sonar: map 2/2: 10/10 trials: success' '$tmp/make.err'"
check "one line per trial in the detail file, ten in each map" \
    [ "$(awk -F'\t' 'NR > 1 && ($2 == "success" || $2 == "ambiguous" || $2 == "wrong") &&
                      $24 >= 1 && $24 <= 2 { n[$24]++ } END { print n[1] + 0, n[2] + 0 }' \
        "$out/trials/lab_sonar.tsv")" = "10 10" ]
# The answers judged in each tour's own frame: one line per tour whose counts add up.
check "the map-frame judgement: a line per tour, counts adding up to 10, aligned to the found" \
    awk '{ for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
           if (v["trials"] != 10 || v["found_right"] + v["found_wrong"] + v["ambiguous"] != 10 ||
               v["aligned_right"] + v["aligned_wrong"] != v["found_right"] + v["found_wrong"] ||
               v["tour"] != NR || v["map"] != NR) exit 1 }
         END { exit NR != 2 }' "$out/trials/lab_sonar.map_frame"
check "the map-frame summary on stderr" \
    grep -q "^kidnap: lab sonar: in the maps' own frames: found [0-9.]* % right" "$tmp/make.err"

# rescore.sh: at the search's own bar it gives the row back; with no bar at all every
# answer is found, so nothing is ambiguous and success can only grow.
detail=$out/trials/lab_sonar.tsv
row=$(awk -F'\t' 'NR == 2 { print $4, $5, $6 }' "$tsv")
again=$(sh tools/lab/kidnap/rescore.sh "$detail" |
        sed -n 's/^rescore .* trials=20 success_pct=\([0-9.]*\) ambiguous_pct=\([0-9.]*\) wrong_pct=\([0-9.]*\)$/\1 \2 \3/p')
check "rescore.sh at the search's bar gives the row ($row)" [ "${again:-none}" = "$row" ]
check "rescore.sh with no bar: none ambiguous, success no lower" \
    sh -c "sh tools/lab/kidnap/rescore.sh --max-ratio 1 --min-explained 0 '$detail' |
           awk -v s0='${row%% *}' '{ for (i = 1; i <= NF; i++) { split(\$i, kv, \"=\"); v[kv[1]] = kv[2] } }
               END { exit !(v[\"ambiguous_pct\"] == 0 && v[\"success_pct\"] >= s0 &&
                            v[\"success_pct\"] + v[\"wrong_pct\"] == 100) }'"
exits "rescore.sh --max-ratio 2 is bad usage" 2 "--max-ratio 2 is outside" \
    sh tools/lab/kidnap/rescore.sh --max-ratio 2 "$detail"
exits "rescore.sh on a file that is not a detail file" 1 "not a hl-kidnap detail file" \
    sh tools/lab/kidnap/rescore.sh "$tsv"
# a detail file cut inside its trials: five whole lines, then ten fields of the sixth
{ head -n 6 "$detail"; sed -n 7p "$detail" | cut -f 1-10; } >"$tmp/cut.tsv"
exits "rescore.sh on a cut detail file names the cut line" 1 "is not a whole trial" \
    sh tools/lab/kidnap/rescore.sh "$tmp/cut.tsv"

# hl-tour-study replays tour 1 as the daemon did (the tours' settings, from make's stamp
# file): the same RMSE and far poses as hl-eval score on the daemon's own output.
tour_sets=$(for kv in $(cat "$out/sim/tour-set"); do printf -- '--set %s ' "$kv"; done)
# shellcheck disable=SC2086  # a list of options
"$BIN/hl-tour-study" --config /dev/null $tour_sets --quiet "$out/sim/lab/1/tour.lcmlog" \
    >"$tmp/study.out" 2>"$tmp/study.err"
study=$(sed -n 's/^tour_study mode=track stops=128 rmse_mm=\([0-9.]*\) .* far=\([0-9]*\)$/\1 \2/p' \
        "$tmp/study.out")
daemon=$(tail -n 1 "$out/sim/lab/1/score.txt" |
         sed -n 's/.* rmse_mm=\([0-9.]*\) .* wild_accepted=\([0-9]*\)$/\1 \2/p')
check "hl-tour-study --mode track matches the daemon's tour (hl-eval score: $daemon)" \
    [ "${daemon:-no score}" = "$study" ]
# Each scan alone from its true pose against a drift-free map: never 0.5 m off (none of
# the 24 lab tours' 3,048 stops was, docs/results/relocalization.md).
# shellcheck disable=SC2086
"$BIN/hl-tour-study" --config /dev/null $tour_sets --mode oracle --quiet \
    "$out/sim/lab/1/tour.lcmlog" >"$tmp/oracle.out" 2>&1
check "hl-tour-study --mode oracle: 127 stops scored, none far" \
    grep -q '^tour_study mode=oracle stops=127 rmse_mm=[0-9.]* heading_rms_deg=[0-9.]* heading_mean_deg=-*[0-9.]* far=0$' \
    "$tmp/oracle.out"
# hl-tour-study's map of the tour is the daemon's own (the same picture). Loop closure,
# after the tour (--mode graph) or as it goes (houghlocd's slam.close_loops, which the
# tours use), brings tour 1 nearer the truth than tracking alone (the figures:
# docs/results/relocalization.md).
# shellcheck disable=SC2086
"$BIN/hl-tour-study" --config /dev/null $tour_sets --quiet --write-map "$tmp/redrawn.hlmap" \
    "$out/sim/lab/1/tour.lcmlog" >/dev/null 2>&1
"$BIN/houghloc-map" "$tmp/redrawn.hlmap" "$tmp/redrawn" >/dev/null 2>&1
"$BIN/houghloc-map" "$out/sim/lab/1/map.hlmap" "$tmp/daemon" >/dev/null 2>&1
check "hl-tour-study --write-map writes the daemon's map of the tour" \
    cmp -s "$tmp/redrawn.pgm" "$tmp/daemon.pgm"
# shellcheck disable=SC2086
plain=$("$BIN/hl-tour-study" --config /dev/null $tour_sets --set slam.close_loops=false \
        --set slam.square_walls=false --quiet \
        "$out/sim/lab/1/tour.lcmlog" 2>/dev/null |
        sed -n 's/^tour_study mode=track stops=128 rmse_mm=\([0-9.]*\) .* far=\([0-9]*\)$/\1 \2/p')
for how in "--set slam.close_loops=false --set slam.square_walls=false --mode graph" \
           "--set slam.close_loops=true"; do
    # shellcheck disable=SC2086
    "$BIN/hl-tour-study" --config /dev/null $tour_sets $how --quiet \
        --write-map "$tmp/closed.hlmap" "$out/sim/lab/1/tour.lcmlog" >"$tmp/closed.out" 2>"$tmp/closed.err"
    closed=$(sed -n "s/^tour_study mode=[a-z]* stops=128 rmse_mm=\([0-9.]*\) .* far=\([0-9]*\)\$/\1 \2/p" \
             "$tmp/closed.out")
    check "hl-tour-study $how: nearer the truth than tracking ($closed against $plain), none far" \
        awk -v c="$closed" -v t="$plain" 'BEGIN { split(c, a, " "); split(t, b, " ")
            exit !(a[1] > 0 && a[1] < b[1] && a[2] == 0) }'
    check "hl-tour-study $how: a map hl-kidnap reads" \
        sh -c "'$BIN/hl-kidnap' --config /dev/null --world lab --input sonar --trials 2 --sim-world lab \
                   --test-log '$tmp/closed.tests.lcmlog' --map '$tmp/closed.hlmap' 2>/dev/null |
               grep -q '^lab	sonar	2	'"
done
# Square walls (slam.square_walls, which the tours use): each stop's readings tie its
# heading to the world, so tour 1 ends nearer the truth than with loop closure alone
# (docs/results/relocalization.md).
# shellcheck disable=SC2086
loops_only=$("$BIN/hl-tour-study" --config /dev/null $tour_sets --set slam.square_walls=false \
             --quiet "$out/sim/lab/1/tour.lcmlog" 2>/dev/null |
             sed -n 's/^tour_study mode=track stops=128 rmse_mm=\([0-9.]*\) .*$/\1/p')
check "hl-tour-study: square walls nearer the truth than loop closure alone ($study against $loops_only)" \
    awk -v s="$study" -v l="$loops_only" 'BEGIN { split(s, a, " "); exit !(l > 0 && a[1] < l) }'
check "hl-tour-study --mode graph: its matches on stderr" \
    sh -c "'$BIN/hl-tour-study' --config /dev/null $tour_sets --mode graph --quiet '$out/sim/lab/1/tour.lcmlog' 2>&1 >/dev/null |
           grep -q '^hl-tour-study: graph: [0-9]* matches tried, [0-9]* counted, [0-9]* kept\$'"
exits "hl-tour-study --write-map with --mode oracle is bad usage" 2 "--write-map is for a tracked tour" \
    "$BIN/hl-tour-study" --config /dev/null --mode oracle --write-map "$tmp/x.hlmap" \
    "$out/sim/lab/1/tour.lcmlog"
exits "hl-tour-study --write-map into a missing folder" 1 "not saved: cannot create" \
    "$BIN/hl-tour-study" --config /dev/null --write-map "$tmp/none/x.hlmap" "$out/sim/lab/1/tour.lcmlog"
exits "hl-tour-study --mode bogus is bad usage" 2 "--mode wants track, exact, oracle or graph" \
    "$BIN/hl-tour-study" --config /dev/null --mode bogus "$out/sim/lab/1/tour.lcmlog"
exits "hl-tour-study on a file that is not a log" 1 "not an LCM log" \
    "$BIN/hl-tour-study" --config /dev/null "$tsv"

# A tour seed that is not a whole number: the row fails with one line naming it.
make --no-print-directory BUILD="$BUILD" kidnap BUILDINGS= KIDNAP_WORLDS=lab \
    KIDNAP_TRIALS_SIM=10 KIDNAP_TOUR_SEEDS='x1' KIDNAP_OUT="$out" KIDNAP_TSV="$tsv" \
    >"$tmp/seed.out" 2>"$tmp/seed.err"
rc=$?
check "KIDNAP_TOUR_SEEDS=x1 fails, naming the seed" \
    sh -c "[ $rc -ne 0 ] && grep -q \"^kidnap: lab sonar: tour failed: the tour seed 'x1' is not a whole number\" '$tmp/seed.err'"

# The real buildings' path (a map of every scan more than 2 m away, at its true pose) on
# any log with ground truth: the lab tour's 128 soundings.
"$BIN/hl-kidnap" --config /dev/null --world tour --input sonar --trials 4 \
    --log "$out/sim/lab/1/tour.lcmlog" >"$tmp/real.row" 2>"$tmp/real.err"
check "hl-kidnap --log: one row of 4 trials" \
    awk -F'\t' 'NR == 1 && NF == 8 && $1 == "tour" && $3 == 4 { ok = 1 } END { exit !(ok && NR == 1) }' \
    "$tmp/real.row"
check "hl-kidnap --log reports its largest map" grep -q '^kidnap: tour sonar: largest map: ' "$tmp/real.err"

# A building without data: its two rows fail with one line each, and no table.
rm -f "$tsv"
make --no-print-directory BUILD="$BUILD" kidnap BUILDINGS=nowhere KIDNAP_WORLDS= \
    DATA="$tmp/nodata" KIDNAP_OUT="$out" KIDNAP_TSV="$tsv" >"$tmp/make.out" 2>"$tmp/make.err"
rc=$?
check "a building without data: make kidnap fails" [ $rc -ne 0 ]
check "... with one line per row naming the building and the file" \
    [ "$(grep -c "^kidnap: nowhere \(laser\|sonar\): data failed: no $tmp/nodata/raw/nowhere-raw.log.gz" "$tmp/make.err")" -eq 2 ]
check "... and no table" [ ! -e "$tsv" ]

exits "hl-kidnap --trials 0 is bad usage" 2 "--trials wants 1..100000" \
    "$BIN/hl-kidnap" --config /dev/null --world w --input sonar --trials 0 --log x
exits "hl-kidnap without a source is bad usage" 2 "one of --sim-world and --log" \
    "$BIN/hl-kidnap" --config /dev/null --world w --input sonar --trials 3
exits "hl-kidnap with a bad config key" 1 "nosuch" \
    "$BIN/hl-kidnap" --config /dev/null --set reloc.nosuch=1 --world w --input sonar --trials 3 --log x
exits "hl-kidnap with a missing second map fails before any trial, naming it" 1 \
    "$tmp/nomap.hlmap: cannot open" \
    "$BIN/hl-kidnap" --config /dev/null --world lab --input sonar --trials 2 --sim-world lab \
    --map "$out/sim/lab/1/map.hlmap" --map "$tmp/nomap.hlmap" --test-log "$tmp/t.lcmlog"
check "hl-kidnap --header" [ "$("$BIN/hl-kidnap" --header)" = "$header" ]
exit $fail
