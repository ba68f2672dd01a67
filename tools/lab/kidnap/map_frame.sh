#!/bin/sh
# map_frame.sh - the kidnap answers of one tour's map judged in that map's own frame.
#
#   map_frame.sh TRUTH.tum ESTIMATE.tum DETAIL.tsv MAP
#
# A tour that drifts draws each place where it believed it was, so a search can be right
# about the map and wrong about the world. This carries each trial's true pose into the
# map's frame by the tour stop nearest to it (TRUTH.tum and ESTIMATE.tum: that tour's
# true and estimated poses, houghloc-eval --tum-gt/--tum-est, in stop order): the pose
# the stop's estimate puts it at. The trials are hl-kidnap's --detail rows whose map
# column is MAP. It also carries them by the one rigid motion that best lays the tour's
# true stops onto its estimated ones (least squares, as an ATE's alignment): what is left
# once the map's frame as a whole is forgiven, and only its bends count. Prints one line:
#   map=MAP trials=N found_right=A found_wrong=B ambiguous=C aligned_right=D aligned_wrong=E
# found_right: found within 0.5 m and 5 degrees of that map-frame pose (hl-kidnap's
# success bar), found_wrong: found farther off; aligned_*: the same against the aligned
# truth. Exit status 1 with one line on stderr on a missing file or no such trial, 2 on
# bad usage.
set -u
[ $# -eq 4 ] || { echo "usage: map_frame.sh TRUTH.tum ESTIMATE.tum DETAIL.tsv MAP" >&2; exit 2; }
for f in "$1" "$2" "$3"; do
    [ -r "$f" ] || { echo "map_frame.sh: cannot read $f" >&2; exit 1; }
done
awk -F'\t' -v map="$4" '
function heading(qz, qw) { return 2 * atan2(qz, qw) }
function wrapdeg(d) { while (d > 180) d -= 360; while (d <= -180) d += 360; return d }
# TUM lines (space separated): t x y z qx qy qz qw; metres.
FILENAME == ARGV[1] || FILENAME == ARGV[2] {
    n = split($0, f, " ")
    if (n < 8 || f[1] ~ /^#/) next
    k = FILENAME == ARGV[1] ? ng++ : ne++
    x = f[2] * 1000; y = f[3] * 1000; h = heading(f[7], f[8])
    if (FILENAME == ARGV[1]) { gx[k] = x; gy[k] = y; gh[k] = h }
    else { ex[k] = x; ey[k] = y; eh[k] = h }
    next
}
# The rigid alignment of the true stops onto the estimated ones (2-D Umeyama, no scale):
# rotation ar, translation (ax, ay).
function align(   i, n, gmx, gmy, emx, emy, sxx, sxy, dx, dy, fx, fy) {
    n = ng < ne ? ng : ne
    for (i = 0; i < n; i++) { gmx += gx[i]; gmy += gy[i]; emx += ex[i]; emy += ey[i] }
    gmx /= n; gmy /= n; emx /= n; emy /= n
    for (i = 0; i < n; i++) {
        dx = gx[i] - gmx; dy = gy[i] - gmy; fx = ex[i] - emx; fy = ey[i] - emy
        sxx += dx * fx + dy * fy; sxy += dx * fy - dy * fx
    }
    ar = atan2(sxy, sxx)
    ax = emx - (cos(ar) * gmx - sin(ar) * gmy); ay = emy - (sin(ar) * gmx + cos(ar) * gmy)
    aligned = 1
}
function judge(x, y, h,   e, ed) {   # 1 when the answer is within the bar of (x, y, h)
    e = sqrt(($col["x_mm"] - x) ^ 2 + ($col["y_mm"] - y) ^ 2)
    ed = wrapdeg($col["deg"] - h * 180 / atan2(0, -1)); if (ed < 0) ed = -ed
    return e <= 500 && ed <= 5
}
FNR == 1 {      # the detail header: columns by name
    for (i = 1; i <= NF; i++) col[$i] = i
    if (!("map" in col) || !("outcome" in col)) { bad = "no map or outcome column"; exit 1 }
    next
}
$col["map"] == map {
    tx = $col["true_x_mm"]; ty = $col["true_y_mm"]; th = $col["true_deg"] * atan2(0, -1) / 180
    n = ng < ne ? ng : ne
    best = -1
    for (i = 0; i < n; i++) {
        d = (gx[i] - tx) ^ 2 + (gy[i] - ty) ^ 2
        if (best < 0 || d < bd) { best = i; bd = d }
    }
    if (best < 0) { bad = "no tour poses"; exit 1 }
    # the trial relative to the stop, in the stop true frame, then from the estimate
    dx = tx - gx[best]; dy = ty - gy[best]
    c = cos(gh[best]); s = sin(gh[best])
    rx = c * dx + s * dy; ry = -s * dx + c * dy
    c = cos(eh[best]); s = sin(eh[best])
    mx = ex[best] + c * rx - s * ry; my = ey[best] + s * rx + c * ry
    mh = eh[best] + (th - gh[best])
    if (!aligned) align()
    trials++
    if ($col["outcome"] == "ambiguous") { amb++; next }
    if (judge(mx, my, mh)) right++; else wrong++
    if (judge(cos(ar) * tx - sin(ar) * ty + ax, sin(ar) * tx + cos(ar) * ty + ay, th + ar))
        aright++
    else
        awrong++
}
END {
    if (bad != "") { print "map_frame.sh: " bad > "/dev/stderr"; exit 1 }
    if (trials == 0) { print "map_frame.sh: no trial of map " map > "/dev/stderr"; exit 1 }
    printf "map=%s trials=%d found_right=%d found_wrong=%d ambiguous=%d aligned_right=%d aligned_wrong=%d\n",
           map, trials, right + 0, wrong + 0, amb + 0, aright + 0, awrong + 0
}' "$1" "$2" "$3"
