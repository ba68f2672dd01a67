#!/bin/sh
# table.sh - the last step of `make kidnap` (tools/lab/kidnap/kidnap.mk): joins the rows into
# the table, prints it and one summary line.
#
#   table.sh OUT SECONDS ROW...
#
# OUT gets hl-kidnap's header and the ROW files' lines in the order given. Every ROW must
# exist and hold one well-formed line (a row that failed has said why already); else one
# line naming the missing rows, exit status 1, and OUT is not written. The summary,
# printed last on stdout:
#   kidnap rows=N trials=T worst_success_pct=P (WORLD INPUT) worst_wrong_pct=Q (WORLD INPUT) seconds=S
set -u
[ $# -ge 2 ] || { echo "usage: table.sh OUT SECONDS ROW..." >&2; exit 2; }
out=$1 secs=$2
shift 2
bin=${BUILD:-build}/bin

missing=""
for r in "$@"; do
    [ -s "$r" ] || missing="$missing $(basename "$r" .tsv)"
done
if [ -n "$missing" ]; then
    echo "kidnap: no table: rows failed or missing:$missing (see the lines above)" >&2
    exit 1
fi
mkdir -p "$(dirname "$out")" || exit 1
tmp=$out.tmp.$$
{ "$bin/hl-kidnap" --header && cat "$@"; } >"$tmp" || { rm -f "$tmp"; exit 1; }
# Numbers only after the two names; the three shares add up to 100.
if ! awk -F'\t' 'NR > 1 {
        if (NF != 8) exit 1
        for (k = 3; k <= 8; k++) if ($k !~ /^[0-9]+(\.[0-9]+)?$/) exit 1
        s = $4 + $5 + $6; if (s < 99.8 || s > 100.2) exit 1 }' "$tmp"; then
    rm -f "$tmp"
    echo "kidnap: no table: a malformed row in$(printf ' %s' "$@")" >&2
    exit 1
fi
mv "$tmp" "$out" || exit 1
cat "$out"
awk -F'\t' -v secs="$secs" 'NR > 1 {
        n++; t += $3
        if (n == 1 || $4 < ws) { ws = $4; wsw = $1 " " $2 }
        if (n == 1 || $6 > ww) { ww = $6; www = $1 " " $2 } }
    END { printf "kidnap rows=%d trials=%d worst_success_pct=%s (%s) worst_wrong_pct=%s (%s) seconds=%s\n",
                 n, t, ws, wsw, ww, www, secs }' "$out"
