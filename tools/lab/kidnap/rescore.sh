#!/bin/sh
# rescore.sh - a kidnap row again under other "found" bars, from hl-kidnap's --detail file.
#
#   rescore.sh [--max-ratio R] [--max-edge-ratio E] [--min-explained P] DETAIL.tsv
#
# The search's answer, its runner-up and their scores do not depend on the bar that
# calls an answer found (reloc.max_ratio, reloc.max_edge_ratio, reloc.min_explained_pct;
# reloc.h), so a bar can be studied on trials already run instead of running them again.
# The rule is hl_reloc_run's: found when the answer explains at least P % of the
# readings and either the runner-up scores at most R times as much, or (E > 0) the
# readings that favour the runner-up are at most E times those that favour the answer
# and these are a tenth of the readings or more. An answer that becomes found is judged
# as hl-kidnap judges one: success within 0.5 m and 5 degrees. The readings are
# recovered from the score and explained_pct (a whole number, so the share is exact);
# the errors are the file's, to their one decimal, so an answer that becomes found at
# 5.0 degrees counts as a success. Defaults: the parameter table's (0.7, 0 for off, 35). At them it
# gives the row the file came from. Prints one line:
#   rescore max_ratio=R max_edge_ratio=E min_explained_pct=P trials=N success_pct=S ambiguous_pct=A wrong_pct=W
# Exit status 1 with one line on stderr on an unreadable or foreign file or a line that is
# not a whole trial (a cut file), 2 on bad usage.
set -u
usage() {
    echo "usage: rescore.sh [--max-ratio R] [--max-edge-ratio E] [--min-explained P] DETAIL.tsv" >&2
    exit 2
}
number() { # NAME VALUE LOW HIGH: VALUE a decimal number in LOW..HIGH, or bad usage
    case $2 in '' | *[!0-9.]* | *.*.* | .) echo "rescore.sh: $1 wants a number, not '$2'" >&2; exit 2 ;; esac
    awk -v v="$2" -v lo="$3" -v hi="$4" 'BEGIN { exit !(v + 0 >= lo && v + 0 <= hi) }' ||
        { echo "rescore.sh: $1 $2 is outside $3..$4" >&2; exit 2; }
}
ratio=0.7 edge=0 explained=35
while [ $# -gt 1 ]; do
    case $1 in
    --max-ratio) number "$1" "$2" 0.000001 1; ratio=$2 ;;
    --max-edge-ratio) number "$1" "$2" 0 1; edge=$2 ;;
    --min-explained) number "$1" "$2" 0 100; explained=$2 ;;
    *) usage ;;
    esac
    shift 2
done
[ $# -eq 1 ] || usage
case $1 in -*) usage ;; esac
[ -r "$1" ] || { echo "rescore.sh: cannot read $1" >&2; exit 1; }
awk -F'\t' -v num='^[0-9]+(\\.[0-9]+)?$' -v mr="$ratio" -v er="$edge" -v me="$explained" -v file="$1" '
NR == 1 {
    # The columns this reads, by name, as hl-kidnap writes them.
    if ($2 != "outcome" || $10 != "error_mm" || $11 != "error_deg" || $12 != "explained_pct" ||
        $13 != "score" || $14 != "runner_up_score" || $22 != "edge" || $23 != "runner_edge") {
        print "rescore.sh: " file ": not a hl-kidnap detail file (its header differs)" > "/dev/stderr"
        bad = 1; exit 1
    }
    fields = NF
    next
}
$2 == "success" || $2 == "ambiguous" || $2 == "wrong" {
    # A cut or mangled line would count with wrong numbers: refuse it.
    if (NF != fields || $10 !~ num || $11 !~ num || $12 !~ num || $13 !~ num ||
        $14 !~ num || $22 !~ num || $23 !~ num) {
        print "rescore.sh: " file ": line " NR " is not a whole trial (" NF " fields, want " fields ")" > "/dev/stderr"
        bad = 1; exit 1
    }
    n++
    # The readings a whole number: the explained share again, to more than its decimal.
    readings = $12 > 0 ? int($13 * 100 / $12 + 0.5) : 0
    share = readings > 0 ? 100 * $13 / readings : 0
    found = share >= me && ($14 <= mr * $13 ||
            (er > 0 && 10 * $22 >= readings - 0.5 && $23 <= er * $22))
    if (!found) a++
    else if ($2 != "ambiguous") { if ($2 == "success") s++; else w++ }   # judged already
    else if ($10 <= 500 && $11 <= 5) s++
    else w++
}
END {
    if (bad) exit 1
    if (n == 0) { print "rescore.sh: " file ": no trials" > "/dev/stderr"; exit 1 }
    printf "rescore max_ratio=%s max_edge_ratio=%s min_explained_pct=%s trials=%d success_pct=%.1f ambiguous_pct=%.1f wrong_pct=%.1f\n",
           mr, er, me, n, 100 * s / n, 100 * a / n, 100 * w / n
}' "$1"
