#!/bin/sh
# tests/golden/check.sh - the goldens, kept as gpsd keeps its regression logs: houghlocd's
# output for fixed inputs, committed, compared byte for byte, so that any change of output
# is a visible diff. One golden a line below (GOLDENS); each is
#   pose NAME LOG KEY=VALUE...   the POSE stream of houghlocd's batch replay of LOG with
#                                those settings (hl-eval extract OUT POSE)
#   arcos                        the SONAR and ODOMETRY houghlocd publishes from a captured
#                                ARCOS byte stream (arcos.capture, replayed with
#                                robot.link = file:, settings arcos.conf)
#
#   sh tests/golden/check.sh               compare every golden (make test); a failure
#                                          names the first differing record
#   sh tests/golden/check.sh --regenerate  rewrite them and say which changed (make golden)
#
# GOLDEN_SET="KEY=VALUE ..." adds those --set options to every run: a way to see the check
# fail, e.g. GOLDEN_SET=localize.blur_mm=40. $BUILD names the build folder (default build).
set -u
BIN=${BUILD:-build}/bin
G=tests/golden
regenerate=false
case ${1:-} in
--regenerate) regenerate=true ;;
"") ;;
*) echo "usage: sh tests/golden/check.sh [--regenerate]" >&2; exit 2 ;;
esac
for p in houghlocd hl-eval; do
    [ -x "$BIN/$p" ] || { echo "FAIL: no $BIN/$p (run make first)"; exit 1; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
changed=0
extra=""
for kv in ${GOLDEN_SET:-}; do extra="$extra --set $kv"; done

# records FILE: one line per record of an extracted stream (4-byte big-endian length, then
# the payload): its number, length and payload in hex, so that a difference has a line.
records() {
    od -An -v -tu1 "$1" | awk '
        { for (i = 1; i <= NF; i++) b[n++] = $i }
        END {
            i = 0; r = 0
            while (i + 4 <= n) {
                len = ((b[i] * 256 + b[i + 1]) * 256 + b[i + 2]) * 256 + b[i + 3]; i += 4
                line = ""
                for (k = 0; k < len && i < n; k++) line = line sprintf("%02x", b[i++])
                printf "record %d (%d bytes) %s\n", r++, len, line
            }
        }'
}

# verdict FILE WHAT: $tmp/FILE against the golden $G/FILE (or into it, regenerating).
verdict() {
    new=$tmp/$1 old=$G/$1
    if $regenerate; then
        if cmp -s "$new" "$old"; then
            echo "unchanged: $old"
        else
            cp "$new" "$old"
            changed=$((changed + 1))
            echo "CHANGED: $old ($(records "$old" | wc -l) records)"
        fi
        return
    fi
    if [ ! -f "$old" ]; then
        echo "FAIL: $old is missing (make golden)"; fail=1
    elif cmp -s "$new" "$old"; then
        echo "ok: $2 equals $old"
    else
        records "$old" >"$tmp/golden.txt"
        records "$new" >"$tmp/run.txt"
        at=$(cmp "$tmp/golden.txt" "$tmp/run.txt" 2>&1 | sed -n 's/.*line \([0-9]*\).*/\1/p')
        echo "FAIL: $2 differs from $old (make golden to accept): golden $(wc -l <"$tmp/golden.txt")" \
             "records, this run $(wc -l <"$tmp/run.txt")"
        if [ -n "$at" ]; then
            sed -n "${at}p" "$tmp/golden.txt" >"$tmp/golden.line"
            sed -n "${at}p" "$tmp/run.txt" >"$tmp/run.line"
            # the payloads' hex from the first differing byte (an even column of the hex)
            awk 'NR == FNR { a = $NF; head = $1 " " $2 " " $3 " " $4; next }
                 { b = $NF; i = 1; while (i <= length(a) && substr(a, i, 2) == substr(b, i, 2)) i += 2
                   printf "  first difference: %s, payload byte %d\n", head, (i - 1) / 2
                   printf "    golden:   ...%s\n    this run: ...%s\n", substr(a, i, 64), substr(b, i, 64) }' \
                "$tmp/golden.line" "$tmp/run.line"
        else
            echo "  $(cmp "$tmp/golden.txt" "$tmp/run.txt" 2>&1 | head -1)"
        fi
        fail=1
    fi
}

# run NAME COMMAND...: houghlocd, which must exit 0 within two minutes (a replay takes a
# second or two); its stderr kept in $tmp/NAME.err.
run() {
    name=$1; shift
    if ! timeout 120 "$@" 2>"$tmp/$name.err"; then
        echo "FAIL: $name: houghlocd failed: $(grep -v '^<[67]>' "$tmp/$name.err" | tail -1)"
        fail=1
        return 1
    fi
}

pose() {
    name=$1 log=$2; shift 2
    sets=""
    for kv in "$@"; do sets="$sets --set $kv"; done
    # shellcheck disable=SC2086 # the settings are words
    run "$name" "$BIN/houghlocd" --config /dev/null $sets $extra --fresh-map \
        --map "$tmp/$name.hlmap" --lcm-url "file://$PWD/$log?speed=0" \
        --lcm-out "file://$tmp/$name.lcmlog?mode=w" || return
    "$BIN/hl-eval" extract "$tmp/$name.lcmlog" POSE "$tmp/$name.POSE"
    verdict "$name.POSE" "POSE of $log with $*"
}

arcos() {
    # shellcheck disable=SC2086
    run arcos "$BIN/houghlocd" --config $G/arcos.conf --set robot.link=file:$G/arcos.capture \
        $extra --fresh-map --map "$tmp/arcos.hlmap" --lcm-url memq:// \
        --lcm-out "file://$tmp/arcos.lcmlog?mode=w" || return
    for ch in SONAR ODOMETRY; do
        "$BIN/hl-eval" extract "$tmp/arcos.lcmlog" $ch "$tmp/arcos.$ch"
        verdict "arcos.$ch" "$ch from $G/arcos.capture"
    done
}

# ---- GOLDENS ------------------------------------------------------------------------------
pose tour.sonar-stops            logs/tour.lcmlog       slam.profile=sonar-stops
pose tour.close-loops            logs/tour.lcmlog       slam.profile=sonar-stops slam.close_loops=true
pose continuous.sonar-continuous logs/continuous.lcmlog slam.profile=sonar-continuous
pose laser.laser                 logs/laser.lcmlog      slam.profile=laser
arcos

if $regenerate; then
    echo "goldens: $changed changed$([ $changed -gt 0 ] && echo ' (git diff --stat tests/golden shows them; commit with the reason)')"
fi
exit $fail
