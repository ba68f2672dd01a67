#!/bin/sh
# make test-console: houghloc-console in a real browser. houghlocd follows logs/tour
# replayed live (lcm-logplayer) on a private LCM group; houghloc-console serves it;
# headless Chromium, driven by chromedriver's W3C WebDriver API from browser_test.py,
# signs in as an operator does (the address with ?token=, the token from --token-out's
# file; the console answers with its session cookie), loads the page, waits for the map, clicks a point near the robot, and checks that a
# DESTINATION with those coordinates (within one 24 mm map cell) was published
# (lcm-logger records it) and that the daemon's reply (NO_ROBOT: no robot is attached)
# appears on the page; then presses Escape and clicks the Stop button, and checks that each
# published one STOP COMMAND (recorded too) whose reply appears on the page; then publishes
# a PATH of 5 points and checks that the page draws them, and that an empty PATH clears
# them. It saves $BUILD/console/screenshot.png (with the way drawn) and ends with one line:
#
#   console browser=<name> vectors_drawn=<n> destination_roundtrip=<ok|failed> frame_ms=<x> stop=<ok|failed> path_points=<n>
#
# where frame_ms is the median redraw time of a 15,000-vector map pushed to the page and
# path_points the number of the PATH's points the page drew (5).
# It needs /usr/bin/chromium and /usr/bin/chromedriver (make deps installs them): without
# them it fails with one line, unless HOUGHLOC_SKIP_BROWSER=1 asks to skip it.
set -u
if [ "${HOUGHLOC_SKIP_BROWSER:-0}" = 1 ]; then
    echo "test-console: skipped on request (HOUGHLOC_SKIP_BROWSER=1)"
    exit 0
fi
for f in /usr/bin/chromium /usr/bin/chromedriver; do
    [ -x "$f" ] || { echo "test-console: FAIL: no $f (make deps, or sudo apt-get install chromium chromium-driver; HOUGHLOC_SKIP_BROWSER=1 skips this test)" >&2; exit 1; }
done
BIN=${BUILD:-build}/bin
OUT=${BUILD:-build}/console
for p in houghlocd houghloc-console; do
    [ -x "$BIN/$p" ] || { echo "test-console: no $BIN/$p (run make first)" >&2; exit 1; }
done
command -v lcm-logplayer >/dev/null || { echo "test-console: lcm-logplayer is missing (apt-get install liblcm-bin)" >&2; exit 1; }
mkdir -p "$OUT"
rm -f "$OUT/screenshot.png"
tmp=$(mktemp -d)
pids=""
cleanup() {
    [ -s "$tmp/player.pid" ] && pids="$(cat "$tmp/player.pid") $pids"
    for p in $pids; do kill -TERM "$p" 2>/dev/null; done
    for p in $pids; do wait "$p" 2>/dev/null; done
    rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# This run's own multicast group and ports, so that two runs or a demo do not meet.
n=$(( $$ % 400 ))
URL="udpm://239.255.76.67:$(( 7300 + n ))?ttl=0"
HPORT=$(( 18100 + n ))
DPORT=$(( 18600 + n ))

lcm-logger -q -f -c 'DESTINATION|COMMAND' --lcm-url="$URL" "$tmp/dest.lcmlog" >/dev/null 2>&1 &
logger=$!
pids="$logger"
# The daemon at its default start pose: the console draws the truth in the map frame (its
# first pose at the start), so the true and the estimated paths overlay.
"$BIN/houghlocd" --config /dev/null --fresh-map --map "$tmp/map.hlmap" --lcm-url "$URL" \
    2>"$tmp/houghlocd.err" &
pids="$pids $!"
w=0
while ! grep -q 'ready:' "$tmp/houghlocd.err" 2>/dev/null && [ $w -lt 100 ]; do sleep 0.1; w=$((w + 1)); done
"$BIN/houghloc-console" --lcm-url "$URL" --listen "127.0.0.1:$HPORT" --ground-truth \
    --token-out "$tmp/token" 2>"$tmp/console.err" &
pids="$pids $!"
w=0
while ! grep -q 'serving' "$tmp/console.err" 2>/dev/null && [ $w -lt 50 ]; do sleep 0.1; w=$((w + 1)); done
# The tour at 50 times its speed (17 s); the file tells the browser test when it is over.
(lcm-logplayer -s 50 -e '^(SONAR|ODOMETRY|GROUND_TRUTH)$' -l "$URL" logs/tour.lcmlog \
    >/dev/null 2>&1 & echo $! >"$tmp/player.pid"; wait $!; touch "$tmp/replayed") &
pids="$pids $!"
/usr/bin/chromedriver --port="$DPORT" >"$tmp/chromedriver.log" 2>&1 &
pids="$pids $!"

python3 tests/console/browser_test.py --driver "http://127.0.0.1:$DPORT" \
    --page "http://127.0.0.1:$HPORT/?token=$(cat "$tmp/token")" --profile "$tmp/profile" --replayed "$tmp/replayed" \
    --dest-log "$tmp/dest.lcmlog" --logger-pid "$logger" --out "$OUT" --lcm-url "$URL"
rc=$?
if [ $rc -ne 0 ]; then
    echo "test-console: failed; the console said:" >&2
    tail -n 5 "$tmp/console.err" >&2
fi
exit $rc
