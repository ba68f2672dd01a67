#!/bin/sh
# tests/golden/check.sh - the goldens, kept as gpsd keeps its regression logs: houghlocd's
# output for fixed inputs, committed as text, one line per message with every field
# (hl-eval text; the format in tests/golden/README.md), compared byte for byte, so that
# any change of output is a visible diff. One golden a line below (GOLDENS); each is
#   pose NAME LOG KEY=VALUE...   NAME.POSE.txt: the POSE stream of houghlocd's batch replay
#                                of LOG with those settings
#   arcos                        arcos.SONAR.txt and arcos.ODOMETRY.txt: the SONAR and
#                                ODOMETRY houghlocd publishes from a captured ARCOS byte
#                                stream (arcos.capture, replayed with robot.link = file:,
#                                settings arcos.conf)
#
#   sh tests/golden/check.sh               compare every golden (make test); a failure
#                                          names the first differing message and its
#                                          differing fields
#   sh tests/golden/check.sh --regenerate  rewrite them and say which changed (make golden)
#
# GOLDEN_SET="KEY=VALUE ..." adds those --set options to every run: a way to see the check
# fail, e.g. GOLDEN_SET=localize.blur_sigma_mm=40. $BUILD names the build folder (default build).
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

# verdict FILE WHAT: $tmp/FILE against the golden $G/FILE (or into it, regenerating).
verdict() {
    new=$tmp/$1 old=$G/$1
    if $regenerate; then
        if cmp -s "$new" "$old"; then
            echo "unchanged: $old"
        else
            cp "$new" "$old"
            changed=$((changed + 1))
            echo "CHANGED: $old ($(wc -l <"$old") messages)"
        fi
        return
    fi
    if [ ! -f "$old" ]; then
        echo "FAIL: $old is missing (make golden)"; fail=1
    elif cmp -s "$new" "$old"; then
        echo "ok: $2 equals $old"
    else
        echo "FAIL: $2 differs from $old (make golden to accept): golden $(wc -l <"$old")" \
             "messages, this run $(wc -l <"$new")"
        # the first differing message (its line) and the fields that differ in it
        at=$(cmp "$old" "$new" 2>&1 | sed -n 's/.* line \([0-9]*\).*/\1/p')
        awk -v at="${at:-0}" '
            FNR == at { if (FILENAME == ARGV[1]) g = $0; else r = $0 }
            END {
                printf "  first difference: message %d\n", at
                n = split(g, a, " "); m = split(r, b, " "); shown = 0
                for (i = 1; i <= (n > m ? n : m) && shown < 6; i++)
                    if (a[i] != b[i]) {
                        printf "    golden:   %s\n    this run: %s\n", substr(a[i], 1, 120),
                               substr(b[i], 1, 120)
                        shown++
                    }
            }' "$old" "$new"
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
    "$BIN/hl-eval" text "$tmp/$name.lcmlog" POSE "$tmp/$name.POSE.txt" || { fail=1; return; }
    verdict "$name.POSE.txt" "POSE of $log with $*"
}

arcos() {
    # shellcheck disable=SC2086
    run arcos "$BIN/houghlocd" --config $G/arcos.conf --set robot.link=file:$G/arcos.capture \
        $extra --fresh-map --map "$tmp/arcos.hlmap" --lcm-url memq:// \
        --lcm-out "file://$tmp/arcos.lcmlog?mode=w" || return
    for ch in SONAR ODOMETRY; do
        "$BIN/hl-eval" text "$tmp/arcos.lcmlog" $ch "$tmp/arcos.$ch.txt" || { fail=1; continue; }
        verdict "arcos.$ch.txt" "$ch from $G/arcos.capture"
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
