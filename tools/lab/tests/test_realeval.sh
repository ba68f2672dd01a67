#!/bin/sh
# Integration test of `make eval-real` (tools/lab/realeval/) without the real data: two small
# buildings written here (a laser going twice round a pillar in a rectangular room, with
# odometry that drifts), run through the whole pipeline with DATA= and BUILDINGS=, two
# jobs at a time. Checks real.tsv's header, its 104 rows in order with their starts
# (origin, turned30, turned45, truth; odometry origin only), that each start is the one
# the daemon ran from (its first POSE), the `-` cells of the odometry rows and the numbers
# everywhere else, the scan counts of both selections, real.md's tables (the origin rows
# with the peers' figures, every start with the three start frames' spread), the maps,
# that a second make reruns nothing, that a bad log and a missing building stop it with
# one line naming the building and the step, and what the configuration files set.
set -u
BUILD=${BUILD:-build}
BIN=$BUILD/bin
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
# A make inside make lab-test: not the outer make's jobserver.
unset MAKEFLAGS MFLAGS MAKELEVEL

# room NAME HALF_X HALF_Y LOOPS: DATA/raw/NAME-raw.log.gz and NAME-groundtruth.tum.
# Walls at +-HALF_X, +-HALF_Y; a 0.8 m square pillar at the centre; the robot walks a
# rectangle 1.4 m inside the walls in 0.25 m steps, facing its way, a scan (181 beams
# over 180 degrees) every 0.5 s. The odometry integrates the true steps 3 % long with 1
# degree per metre of heading drift.
room() {
    awk -v name="$1" -v hx="$2" -v hy="$3" -v loops="$4" -v dir="$tmp/data/raw" '
    function ray(x, y, a,   c, s, t, best, lo, hi, t1, t2, tmin, tmax) {
        c = cos(a); s = sin(a); best = 1e9
        if (c > 1e-9) best = (hx - x) / c; else if (c < -1e-9) best = (-hx - x) / c
        if (s > 1e-9) t = (hy - y) / s; else if (s < -1e-9) t = (-hy - y) / s; else t = 1e9
        if (t < best) best = t
        # the pillar: slab test against [-0.4, 0.4]^2
        tmin = -1e9; tmax = 1e9
        if (c > 1e-9 || c < -1e-9) {
            t1 = (-0.4 - x) / c; t2 = (0.4 - x) / c
            if (t1 > t2) { t = t1; t1 = t2; t2 = t }
            if (t1 > tmin) tmin = t1; if (t2 < tmax) tmax = t2
        } else if (x < -0.4 || x > 0.4) tmax = -1
        if (s > 1e-9 || s < -1e-9) {
            t1 = (-0.4 - y) / s; t2 = (0.4 - y) / s
            if (t1 > t2) { t = t1; t1 = t2; t2 = t }
            if (t1 > tmin) tmin = t1; if (t2 < tmax) tmax = t2
        } else if (y < -0.4 || y > 0.4) tmax = -1
        if (tmax >= tmin && tmin > 0 && tmin < best) best = tmin
        return best
    }
    BEGIN {
        pi = atan2(0, -1)
        cx[0] = -(hx - 1.4); cy[0] = -(hy - 1.4); cx[1] = hx - 1.4; cy[1] = -(hy - 1.4)
        cx[2] = hx - 1.4; cy[2] = hy - 1.4; cx[3] = -(hx - 1.4); cy[3] = hy - 1.4
        n = 0
        for (l = 0; l < loops; l++)
            for (k = 0; k < 4; k++) {
                dx = cx[(k + 1) % 4] - cx[k]; dy = cy[(k + 1) % 4] - cy[k]
                len = sqrt(dx * dx + dy * dy); steps = int(len / 0.25 + 0.5)
                for (j = 0; j < steps; j++) {
                    X[n] = cx[k] + dx * j / steps; Y[n] = cy[k] + dy * j / steps
                    T[n] = atan2(dy, dx); n++
                }
            }
        lf = dir "/" name "-raw.log"; tum = dir "/" name "-groundtruth.tum"
        print "# CARMEN log written by test_realeval.sh" > lf
        print "# time x y z qx qy qz qw" > tum
        ox = X[0]; oy = Y[0]; ot = T[0]
        for (i = 0; i < n; i++) {
            if (i > 0) {    # the true step in the frame of the previous pose, then noise
                ddx = X[i] - X[i - 1]; ddy = Y[i] - Y[i - 1]
                c = cos(T[i - 1]); s = sin(T[i - 1])
                fx = c * ddx + s * ddy; fy = -s * ddx + c * ddy
                d = sqrt(fx * fx + fy * fy)
                dt = atan2(sin(T[i] - T[i - 1]), cos(T[i] - T[i - 1])) + d * pi / 180
                fx *= 1.03; fy *= 1.03
                ox += cos(ot) * fx - sin(ot) * fy; oy += sin(ot) * fx + cos(ot) * fy
                ot = atan2(sin(ot + dt), cos(ot + dt))
            }
            t = sprintf("%.6f", 100 + 0.5 * i)
            line = "FLASER 181"
            for (b = 0; b < 181; b++)
                line = line sprintf(" %.3f", ray(X[i], Y[i], T[i] + (b - 90) * pi / 180))
            odo = sprintf("%.6f %.6f %.6f", ox, oy, ot)
            print line, odo, odo, t, "sim", t > lf
            printf "%s %.6f %.6f 0 0 0 %.9f %.9f\n", t, X[i], Y[i], sin(T[i] / 2), cos(T[i] / 2) > tum
        }
        print n
    }'
}

mkdir -p "$tmp/data/raw"
n_room=$(room room 4 3 1)
n_hall=$(room hall 5 2.5 1)
gzip "$tmp/data/raw/room-raw.log" "$tmp/data/raw/hall-raw.log"
cat >"$tmp/BASELINES.md" <<'EOF'
| building | method | ATE RMSE (m) | RPE 1 m rmse / mean (m) | scans | ms per scan |
|---|---|---|---|---|---|
| room | odometry alone | 0.111 | 0.022 / 0.033 | 44 | – |
| room | CSM | 0.444 | 0.055 / 0.066 | 44 | 7.7 |
| room | BreezySLAM | 0.888 (other seeds 1–2) | 0.099 / 0.011 | 44 | 2.2 |
| elsewhere | CSM | 9.999 | 0.999 / 0.999 | 9 | 9.9 |
EOF

out=$tmp/eval
mk() {      # mk EVAL_OUT BUILDINGS: make eval-real on the data above, two jobs
    make -s --no-print-directory -j2 BUILD="$BUILD" DATA="$tmp/data" BUILDINGS="$2" \
        EVAL_OUT="$1" BASELINES="$tmp/BASELINES.md" eval-real
}
mk "$out" "room hall" >"$tmp/make.out" 2>"$tmp/make.err"
rc=$?
check "make eval-real on two small buildings exits 0" test $rc -eq 0
[ $rc -eq 0 ] || head -c 2000 "$tmp/make.err"
tsv=$out/real.tsv

check "real.tsv's header: the columns as before, start last" test "$(head -n 1 "$tsv")" = "$(printf 'dataset\tinput\tmode\tselection\tscans\tate_rmse_m\trpe_trans_rmse_m\trpe_trans_mean_m\tmax_err_m\tms_per_scan\twall_ms_per_scan\trejected\tstart')"
check "real.tsv: 104 rows (2 buildings x 2 inputs x 2 selections x (odometry + 3 modes x 4 starts))" \
    test "$(wc -l <"$tsv")" -eq 105
# The order: building as given, input, mode, selection, start.
awk -F '\t' 'NR > 1 { print $1, $2, $3, $4, $13 }' "$tsv" >"$tmp/keys"
for b in room hall; do for i in laser sonar; do for m in odometry paper improved loops; do
    starts="origin turned30 turned45 truth"
    [ $m = odometry ] && starts=origin
    for s in every moved; do for t in $starts; do echo "$b $i $m $s $t"; done; done
done; done; done >"$tmp/keys.want"
check "rows in the order building, input, mode, selection, start (odometry: origin only)" \
    cmp -s "$tmp/keys" "$tmp/keys.want"
check "every row has 13 cells" awk -F '\t' 'NF != 13 { bad = 1 } END { exit bad }' "$tsv"
check "start is origin, turned30, turned45 or truth" awk -F '\t' '
    NR > 1 && $13 !~ /^(origin|turned30|turned45|truth)$/ { bad = 1 } END { exit bad }' "$tsv"
# Each start is where the daemon began: its first POSE (the first scan, on an empty map,
# follows the odometry from the start pose) is 0, 0 and 0 / 30 / 45 degrees, or the
# first true pose; only the truth row takes anything from the ground truth.
first_est() {   # first_est RUN: the run's first POSE as "X Y DEG"
    "$BIN/houghloc-eval" --tsv --tum-est "$tmp/est.tum" "$out/input/room_laser_every.lcmlog" \
        "$out/runs/$1/out.lcmlog" >/dev/null 2>&1 &&
        awk 'NR == 1 { printf "%.3f %.3f %.1f\n", $2, $3, atan2($7, $8) * 360 / atan2(0, -1) }' "$tmp/est.tum"
}
"$BIN/houghloc-eval" --odometry --tsv --tum-gt "$tmp/gt.tum" "$out/input/room_laser_every.lcmlog" >/dev/null
gt0=$(awk 'NR == 1 { printf "%.3f %.3f %.1f\n", $2, $3, atan2($7, $8) * 360 / atan2(0, -1) }' "$tmp/gt.tum")
check "the room's first true pose is not the origin ($gt0)" test "$gt0" != "0.000 0.000 0.0"
for pair in "origin:0.000 0.000 0.0" "turned30:0.000 0.000 30.0" "turned45:0.000 0.000 45.0" \
    "truth:$gt0"; do
    t=${pair%%:*}
    check "room laser every improved $t: the first POSE is ${pair#*:}" \
        test "$(first_est "room_laser_improved_every_$t")" = "${pair#*:}"
done
check "odometry rows: ms_per_scan, wall_ms_per_scan and rejected are -" awk -F '\t' '
    NR > 1 && $3 == "odometry" && ($10 != "-" || $11 != "-" || $12 != "-") { bad = 1 }
    END { exit bad }' "$tsv"
num='^[0-9]+\.[0-9]+$'
check "numbers: scans whole, metres and ms decimals, times and rejected on daemon rows" \
    awk -F '\t' -v num="$num" '
    NR == 1 { next }
    $5 !~ /^[1-9][0-9]*$/ { bad = 1 }
    { for (k = 6; k <= 9; k++) if ($k !~ num) bad = 1 }
    $3 != "odometry" && ($10 !~ num || $11 !~ num || $12 !~ /^[0-9]+$/) { bad = 1 }
    $3 != "odometry" && ($10 <= 0 || $11 <= 0) { bad = 1 }
    $9 + 0 < $6 + 0 { bad = 1 }         # the largest error is at least the RMSE
    END { exit bad }' "$tsv"
check "every: all $n_room and $n_hall scans scored" awk -F '\t' -v r="$n_room" -v h="$n_hall" '
    NR > 1 && $4 == "every" && $5 != ($1 == "room" ? r : h) { bad = 1 } END { exit bad }' "$tsv"
check "moved: fewer scans, the same in every mode and input" awk -F '\t' -v r="$n_room" '
    NR > 1 && $1 == "room" && $4 == "moved" { if ($5 >= r || (seen != "" && $5 != seen)) bad = 1; seen = $5 }
    END { exit bad || seen == "" }' "$tsv"
check "odometry alone: drift scored (ATE above 1 cm), the same for both inputs" awk -F '\t' '
    NR > 1 && $3 == "odometry" { if ($6 < 0.01) bad = 1; k = $1 $4; if (k in a && a[k] != $6) bad = 1; a[k] = $6 }
    END { exit bad }' "$tsv"
# The odometry row is houghloc-eval's own figure on the cached import.
ate=$("$BIN/houghloc-eval" --odometry --tsv "$out/input/room_laser_every.lcmlog" |
    tr ' ' '\n' | sed -n 's/^ate_rmse_m=//p')
check "odometry row = houghloc-eval --odometry on the import ($ate)" awk -F '\t' -v a="$ate" '
    $1 == "room" && $2 == "laser" && $3 == "odometry" && $4 == "every" { found = ($6 == a) }
    END { exit !found }' "$tsv"
# A clean room and a laser: the improved mode must beat the drifting odometry by far from
# every start (a wiring fault, such as the POSE of another run, would not).
check "room, laser, every: improved ATE below a quarter of the odometry's from each start" awk -F '\t' '
    $1 == "room" && $2 == "laser" && $4 == "every" && $3 == "odometry" { odo = $6 }
    $1 == "room" && $2 == "laser" && $4 == "every" && $3 == "improved" { a[$13] = $6; n++ }
    END { if (n != 4 || odo == "") exit 1; for (t in a) if (a[t] >= odo / 4) exit 1 }' "$tsv"
check "rejected = the daemon's rejected_wild (room laser every improved turned30)" sh -c '
    w=$(tr " " "\n" <"$1/runs/room_laser_improved_every_turned30/status.txt" | sed -n "s/^rejected_wild=//p")
    awk -F "\t" -v w="$w" "\$1 == \"room\" && \$2 == \"laser\" && \$3 == \"improved\" && \$4 == \"every\" && \$13 == \"turned30\" { f = (\$12 == w) } END { exit !f }" "$2"' \
    - "$out" "$tsv"
check "progress on stderr, one line per row" \
    test "$(grep -c '^eval-real: .*: done, ATE .* rows)$' "$tmp/make.err")" -eq 104

md=$out/real.md
check "real.md exists" test -s "$md"
check "real.md: a laser and a pseudo-sonar table" \
    sh -c 'grep -q "^## Laser input" "$1" && grep -q "^## Pseudo-sonar input" "$1"' - "$md"
check "real.md: the origin tables, 2 x (3 peers + 16 of ours) rows, then the starts', 2 x 12" sh -c '
    sed "/^## Start frames/q" "$2" >"$1.methods"
    test "$(grep -c "^| \(room\|hall\) |" "$1.methods")" -eq 38 &&
    test "$(grep -c "^## Start frames, " "$2")" -eq 2 &&
    test "$(sed -n "/^## Start frames/,\$p" "$2" | grep -c "^| \(room\|hall\) |")" -eq 24' \
    - "$tmp/md" "$md"
# The headline rows are the origin's: real.md's improved row for room, laser, every, up
# to its times (which differ from run to run).
head0=$(awk -F '\t' '$1 == "room" && $2 == "laser" && $3 == "improved" && $4 == "every" && $13 == "origin" {
    printf "| room | houghloc, improved mode, every | %s | %.3f | %.3f / %.3f | %.3f | %.2f / %.2f | %s / ",
        $5, $6, $7, $8, $9, $10, $11, $12 }' "$tsv")
check "real.md: the headline improved row is the origin run's ($head0)" \
    grep -q -F -- "$head0" "$md"
# The spread of the three start frames, from real.tsv: max - min and over the median.
want=$(awk -F '\t' '$1 == "hall" && $2 == "laser" && $3 == "improved" && $4 == "every" && $13 != "truth" {
        x[++n] = $6 } END {
        lo = x[1]; hi = x[1]; for (k = 2; k <= 3; k++) { if (x[k] < lo) lo = x[k]; if (x[k] > hi) hi = x[k] }
        printf "%.3f (%.0f %%)", hi - lo, 100 * (hi - lo) / (x[1] + x[2] + x[3] - hi - lo) }' "$tsv")
check "real.md: hall, laser, improved, every: the spread of the start frames is $want" sh -c '
    sed -n "/^## Start frames, laser/,/^## /p" "$1" |
        grep -q "^| hall | houghloc, improved mode, every | [0-9.]* | [0-9.]* | [0-9.]* | $2 | [0-9.]* |$"' \
    - "$md" "$want"
check "real.md: the peers' CSM and BreezySLAM figures beside ours" sh -c '
    grep -q "^| room | CSM (peers, every) | 44 | 0.444 | 0.055 / 0.066 | – | – / 7.7 | – |$" "$1" &&
    grep -q "^| room | BreezySLAM (peers, every) | 44 | 0.888 (other seeds 1–2) |" "$1" &&
    ! grep -q "elsewhere" "$1"' - "$md"
check "real.md: our improved row for room, laser, every" \
    grep -q '^| room | houghloc, improved mode, every | '"$n_room"' | [0-9.]* | [0-9.]* / [0-9.]* | ' "$md"
for png in room hall room-sonar hall-sonar; do
    check "$png.png: a PNG" sh -c 'test "$(head -c 4 "$1" | od -An -c | tr -d " ")" = "211PNG"' - "$out/$png.png"
done

# Up to date: a second make reruns no cell.
mk "$out" "room hall" >/dev/null 2>"$tmp/make2.err"
rc=$?
check "a second make exits 0 and reruns nothing" \
    sh -c 'test $1 -eq 0 && ! grep -q "running\|importing" "$2"' - $rc "$tmp/make2.err"

# A failing step: one line naming the building and the step, exit non-zero, no table.
printf 'FLASER 3 1 2 3 0 0 0 0 0 0 5.0 h 5.0\nFLASER 3 1 oops 3 0 0 0 0 0 0 6.0 h 6.0\n' |
    gzip >"$tmp/data/raw/bad-raw.log.gz"
printf '5.0 0 0 0 0 0 0 1\n6.0 0 0 0 0 0 0 1\n' >"$tmp/data/raw/bad-groundtruth.tum"
mk "$tmp/bad" bad >/dev/null 2>"$tmp/bad.err"
rc=$?
check "a bad log: make fails" test $rc -ne 0
check "a bad log: one line naming the building, the step and the line" \
    grep -q "^eval-real: bad \(laser\|sonar\) \(every\|moved\): import failed: .*bad-raw.log.gz:2: FLASER with 3 beams: beam 2 'oops' is not a number$" "$tmp/bad.err"
check "a bad log: no table" test ! -e "$tmp/bad/real.tsv"
mk "$tmp/none" nowhere >/dev/null 2>"$tmp/none.err"
rc=$?
check "a missing building: make fails with one line naming it" \
    sh -c 'test $1 -ne 0 && grep -q "^eval-real: nowhere-raw.log.gz: missing in " "$2"' - $rc "$tmp/none.err"

# The paper files are the paper preset whole but for the raster bound; the improved
# files keep the improved mode, the laser's with thin beams and a map for a building.
"$BIN/houghlocd" --config /dev/null --set slam.profile=paper --print-config=all >"$tmp/paper" 2>&1
for c in laser sonar; do
    "$BIN/houghlocd" --config "tools/lab/realeval/$c-paper.conf" --print-config=all >"$tmp/$c.paper" 2>&1
    check "$c-paper.conf: the preset's values (47 mm cells, global search, no guard)" \
        sh -c 'grep -q "^profile = paper$" "$1" && grep -q "^cell_mm = 47$" "$1" &&
               grep -q "^window_mm = 0$" "$1" && grep -q "^guarded = false$" "$1" &&
               grep -q "^echo_bearings = false$" "$1" && grep -q "^group_mm = 0$" "$1" &&
               grep -q "^map_per_place = 0$" "$1"' - "$tmp/$c.paper"
    check "$c-paper.conf: [slam] .. [reloc] as the bare preset but max_cells 64 Mi" sh -c '
        sed -n "/^\[slam\]/,\$p" "$1" | grep -v "^max_cells = " >"$1.tail"
        sed -n "/^\[slam\]/,\$p" "$2" | grep -v "^max_cells = " >"$2.tail"
        cmp -s "$1.tail" "$2.tail" && grep -q "^max_cells = 67108864$" "$1"' - "$tmp/$c.paper" "$tmp/paper"
done
"$BIN/houghlocd" --config tools/lab/realeval/laser.conf --print-config=all >"$tmp/laser.improved" 2>&1
check "laser.conf in improved mode: echo bearings off, fitted normals keeping the unfitted, the guard on, a bounded 15,000-vector map" sh -c '
    grep -q "^profile = laser$" "$1" && grep -q "^echo_bearings = false$" "$1" &&
    grep -q "^fit_normals = true$" "$1" && grep -q "^keep_unfitted = true$" "$1" &&
    grep -q "^guarded = true$" "$1" && grep -q "^map_capacity = 15000$" "$1" &&
    grep -q "^map_per_place = 1$" "$1"' - "$tmp/laser.improved"
"$BIN/houghlocd" --config tools/lab/realeval/sonar.conf --print-config=all >"$tmp/sonar.improved" 2>&1
check "sonar.conf in improved mode: echo bearings on" sh -c '
    grep -q "^profile = sonar-continuous$" "$1" && grep -q "^echo_bearings = true$" "$1"' - "$tmp/sonar.improved"

# The real-data evaluation runs the product's profiles: its improved-mode files name them.
check "make eval-real's laser and pseudo-sonar rows run slam.profile = laser / sonar-continuous" \
    sh -c "grep -qx 'profile = laser' tools/lab/realeval/laser.conf &&
           grep -qx 'profile = sonar-continuous' tools/lab/realeval/sonar.conf"
for pair in laser:laser sonar-continuous:sonar; do
    "$BIN/houghlocd" --config /dev/null --set slam.profile=${pair%%:*} --print-config=all >"$tmp/prof.a"
    "$BIN/houghlocd" --config "tools/lab/realeval/${pair#*:}.conf" --print-config=all >"$tmp/prof.b"
    check "tools/lab/realeval/${pair#*:}.conf is slam.profile=${pair%%:*}, nothing else changed" \
        cmp -s "$tmp/prof.a" "$tmp/prof.b"
    # The loops mode: the same profile with loop closure turned on, and nothing else.
    "$BIN/houghlocd" --config /dev/null --set slam.profile=${pair%%:*} --set slam.close_loops=true \
        --print-config=all >"$tmp/prof.c"
    "$BIN/houghlocd" --config "tools/lab/realeval/${pair#*:}-loops.conf" --print-config=all >"$tmp/prof.d"
    check "tools/lab/realeval/${pair#*:}-loops.conf is slam.profile=${pair%%:*} with close_loops = true" \
        sh -c 'cmp -s "$1" "$2" && grep -q "^close_loops = true$" "$2" &&
               grep -q "^closure_correlative = true$" "$2"' - "$tmp/prof.c" "$tmp/prof.d"
done

exit $fail
