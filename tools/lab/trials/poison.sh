#!/bin/sh
# poison.sh - the Poison trial of `make trials`: sensor streams from the network that try to
# stop localization. hl-poison copies logs/tour.lcmlog (128 real scans) with, among the
# real messages, one well-formed SONAR whose seq is 2^31 - 6 and utime 2^62, one ODOMETRY
# at utime 2^63 - 1, and, from the 40th scan on, a restarted publisher (seq counted from
# 0 again, its clock 2 h back). houghlocd replays the copy (file:// at full speed, so the
# run is the same on any machine) and every POSE it publishes is counted: a real scan
# without one is lost. The stream rule (docs/manual/channels.md) drops a lone outlier
# and follows a restarted source after 3 messages in order, so the restart costs 2.
#
# The last stdout line:
#   poisoned_scans_lost=<n> real_scans=<k> bad_messages=<b>
# Exit status 0 when n <= 3 and the daemon ended cleanly. Progress on stderr; the files
# of the last run stay in BUILD/trials/poison. Environment: BUILD (build).
set -u
BUILD=${BUILD:-build}
BIN=$BUILD/bin
MAX_LOST=3
say() { echo "poison: $*" >&2; }
die() { say "$*"; echo "poisoned_scans_lost=- real_scans=- bad_messages=-"; exit 1; }

for p in houghlocd hl-poison hl-eval; do
    [ -x "$BIN/$p" ] || die "$BIN/$p is missing: make BUILD=$BUILD all lab"
done
work=$BUILD/trials/poison
rm -rf "$work" && mkdir -p "$work" || die "cannot make $work"
work=$(cd "$work" && pwd)

made=$("$BIN/hl-poison" make logs/tour.lcmlog "$work/poisoned.lcmlog") ||
    die "hl-poison could not write the poisoned log"
real=$(echo "$made" | sed -n 's/.*real_scans=\([0-9]*\).*/\1/p')
say "$made"

"$BIN/houghlocd" --config /dev/null --fresh-map --map "$work/map.hlmap" \
    --set daemon.status_period_ms=100 \
    --lcm-url "file://$work/poisoned.lcmlog?speed=0" \
    --lcm-out "file://$work/out.lcmlog?mode=w" 2>"$work/daemon.err"
rc=$?
[ $rc -eq 0 ] || die "houghlocd exited $rc: $(tail -n 2 "$work/daemon.err")"
poses=$("$BIN/hl-poison" count "$work/out.lcmlog" POSE) || die "cannot read its output log"
bad=$("$BIN/hl-eval" status "$work/out.lcmlog" | tr ' ' '\n' | sed -n 's/^bad_messages=//p')
lost=$((real - poses))
say "$poses POSE for $real real scans; STATUS bad_messages=${bad:--}"
echo "poisoned_scans_lost=$lost real_scans=$real bad_messages=${bad:--}"
[ "$lost" -le $MAX_LOST ]
