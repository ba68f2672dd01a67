#!/bin/sh
# Integration test of houghloc-eval on a real replay of the tour: its last line parses,
# the counts match the daemon's, the aligned ATE is never above hl-eval's unaligned RMSE
# (the alignment minimizes exactly that sum), the TUM exports hold one line per scan and
# start at the first true pose, and bad usage or bad input get one line and exit 2 / 1.
set -u
BIN=${BUILD:-build}/bin
EVAL=$BIN/houghloc-eval
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
LOG=logs/tour.lcmlog

"$BIN/houghlocd" --config /dev/null --fresh-map --map "$tmp/m.hlmap" \
    --lcm-url "file://$PWD/$LOG?speed=0" --lcm-out "file://$tmp/o.lcmlog?mode=w" 2>/dev/null
check "the daemon replays the tour" test $? -eq 0

# The summary's last line is the --tsv line.
"$EVAL" "$LOG" "$tmp/o.lcmlog" >"$tmp/sum"
check "houghloc-eval exits 0" test $? -eq 0
"$EVAL" --tsv --tum-gt "$tmp/gt.tum" --tum-est "$tmp/est.tum" "$LOG" "$tmp/o.lcmlog" >"$tmp/tsv"
check "--tsv prints one line" test "$(wc -l <"$tmp/tsv")" -eq 1
check "the summary ends with that line" test "$(tail -n 1 "$tmp/sum")" = "$(cat "$tmp/tsv")"
num='[0-9]+\.[0-9]{6}'
check "the line parses" grep -qE "^ate_rmse_m=$num rpe_trans_rmse_m=$num rpe_trans_mean_m=$num max_err_m=$num scans=128 rpe_pairs=[1-9][0-9]* accepted=[0-9]+ rejected_wild=[0-9]+ odometry_only=[0-9]+$" "$tmp/tsv"
# Statuses agree with the daemon's own count in its last STATUS.
"$BIN/hl-eval" status "$tmp/o.lcmlog" >"$tmp/status"
for k in accepted rejected_wild odometry_only; do
    want=$(tr ' ' '\n' <"$tmp/status" | grep "^$k=")
    check "$want as in STATUS" grep -q " $want\( \|$\)" "$tmp/tsv"
done
val() {     # val FILE KEY: the number after KEY=
    tr ' ' '\n' <"$1" | sed -n "s/^$2=//p"
}
"$BIN/hl-eval" score --quiet "$LOG" "$tmp/o.lcmlog" >"$tmp/hl"
rmse=$(sed -n 's/.* rmse_mm=\([0-9.]*\) .*/\1/p' "$tmp/hl")
odo=$(sed -n 's/.* odometry_rmse_mm=\([0-9.]*\) wild_accepted=[0-9]*$/\1/p' "$tmp/hl")
check "aligned ATE <= hl-eval's unaligned RMSE ($rmse mm)" \
    awk -v a="$(val "$tmp/tsv" ate_rmse_m)" -v b="$rmse" 'BEGIN { exit !(a * 1000 <= b + 0.05) }'
check "max error >= ATE RMSE" \
    awk -v a="$(val "$tmp/tsv" ate_rmse_m)" -v m="$(val "$tmp/tsv" max_err_m)" 'BEGIN { exit !(m >= a) }'

# hl-eval compares in the daemon's map frame: the truth's first pose at the daemon's start
# (--start, default the origin, where this daemon started), so the first scan, placed at
# the start, is 0 mm off; told the wrong start (the world's), it is off by that much.
"$BIN/hl-eval" score "$LOG" "$tmp/o.lcmlog" >"$tmp/hlfull"
check "hl-eval score: the first scan 0 mm and 0 degrees from the truth in the map frame" \
    grep -qE '^stop +1 +scan +0 +error +0 mm +[+-]0\.0 deg  odometry +0 mm +[+-]0\.0 deg$' "$tmp/hlfull"
"$BIN/hl-eval" score --start "$(hl_start=$("$BIN/hl-eval" start "$LOG"); echo "$hl_start" | tr ' ' ',')" \
    "$LOG" "$tmp/o.lcmlog" >"$tmp/hlworld"
check "hl-eval score --start at the world's start: the first scan 6734 mm off (the origin)" \
    grep -qE '^stop +1 +scan +0 +error +6734 mm' "$tmp/hlworld"
"$BIN/hl-eval" live --quiet --start=0,0,0 "$LOG" "$tmp/o.lcmlog" >"$tmp/hllive"
check "hl-eval live --quiet --start=0,0,0 LOG OUT: takes the option, prints the one line" \
    grep -qx 'demo stops=[0-9]* rmse_mm=[0-9.]* max_mm=[0-9.]* odometry_rmse_mm=[0-9.]* wild_accepted=[0-9]*' "$tmp/hllive"
rejects "hl-eval --start not a pose" 2 "--start 'a,b,c' is not X,Y,DEG" \
    "$BIN/hl-eval" score --start a,b,c "$LOG" "$tmp/o.lcmlog"
rejects "hl-eval --start without a value" 2 "--start needs X,Y,DEG" "$BIN/hl-eval" live "$LOG" --start
rejects "hl-eval score with one log" 2 "expected IN.lcmlog OUT.lcmlog" "$BIN/hl-eval" score "$LOG"
check "hl-eval --version prints the release" sh -c '"$1" --version | grep -q "^hl-eval [0-9]"' - "$BIN/hl-eval"

# --odometry needs no OUT; its ATE is at most hl-eval's odometry RMSE.
"$EVAL" --odometry --tsv "$LOG" >"$tmp/odo"
check "--odometry exits 0" test $? -eq 0
check "--odometry line has no statuses" grep -qE "^ate_rmse_m=$num rpe_trans_rmse_m=$num rpe_trans_mean_m=$num max_err_m=$num scans=128 rpe_pairs=[1-9][0-9]*$" "$tmp/odo"
check "odometry ATE <= hl-eval's odometry RMSE ($odo mm)" \
    awk -v a="$(val "$tmp/odo" ate_rmse_m)" -v b="$odo" 'BEGIN { exit !(a * 1000 <= b + 0.05) }'

# TUM exports: 128 lines of 8 numbers, z = 0, unit quaternions; the truth starts at the
# first true pose (hl-eval start), the estimate at the daemon's start, the origin.
for f in gt est; do
    check "$f.tum: 128 lines of 8 fields, z 0, unit quaternion" awk '
        NF != 8 || $4 != 0 || $5 != 0 || $6 != 0 { bad = 1 }
        { q = $7 * $7 + $8 * $8; if (q < 0.999999 || q > 1.000001) bad = 1 }
        END { exit bad || NR != 128 }' "$tmp/$f.tum"
done
start=$("$BIN/hl-eval" start "$LOG")
check "gt.tum starts at the first true pose" awk -v s="$start" '
    NR == 1 { split(s, p, " "); exit !($2 - p[1] < 0.0005 && p[1] - $2 < 0.0005 &&
                                       $3 - p[2] < 0.0005 && p[2] - $3 < 0.0005) }' "$tmp/gt.tum"
check "est.tum starts at the origin" awk 'NR == 1 { exit !($2 == 0 && $3 == 0) }' "$tmp/est.tum"
check "times increase" awk 'NR > 1 && $1 <= t { bad = 1 } { t = $1 } END { exit bad }' "$tmp/gt.tum"

# Usage: --help and --version exit 0; bad usage exits 2 with one line.
check "--help exits 0 and shows the usage" sh -c '"$1" --help | grep -q "^Usage: houghloc-eval"' - "$EVAL"
check "--version prints the release" sh -c '"$1" --version | grep -q "^houghloc-eval [0-9]"' - "$EVAL"
rejects "no arguments" 2 "expected IN and OUT" "$EVAL"
rejects "one argument without --odometry" 2 "expected IN and OUT" "$EVAL" "$LOG"
rejects "unknown option" 2 "unknown option '--bogus'" "$EVAL" --bogus "$LOG" "$tmp/o.lcmlog"
rejects "--delta 0" 2 "--delta '0'" "$EVAL" --delta 0 "$LOG" "$tmp/o.lcmlog"
rejects "--delta beyond 100 km" 2 "--delta '1e20'" "$EVAL" --delta 1e20 "$LOG" "$tmp/o.lcmlog"
rejects "--tum-gt without a value" 2 "needs a value" "$EVAL" "$LOG" "$tmp/o.lcmlog" --tum-gt

# Bad input: exit 1, one line naming the file.
head -c 5000 "$LOG" >"$tmp/trunc.lcmlog"
rejects "truncated input log" 1 "trunc.lcmlog: byte" "$EVAL" "$tmp/trunc.lcmlog" "$tmp/o.lcmlog"
rejects "missing output log" 1 "nowhere.lcmlog" "$EVAL" "$LOG" "$tmp/nowhere.lcmlog"
rejects "POSE of another run" 1 "which the input lacks" "$EVAL" logs/lab28.lcmlog "$tmp/o.lcmlog"
rejects "an output log without POSE" 1 "no POSE for any scan" "$EVAL" "$LOG" "$LOG"
rejects "an unwritable TUM file" 1 "cannot create" "$EVAL" --tum-est "$tmp/no/such/dir/e.tum" "$LOG" "$tmp/o.lcmlog"
exit $fail
