#!/bin/sh
# crash_trials.sh N: kills houghlocd with SIGKILL at random points of a batch replay of the
# tour, N times, and checks after each that the map file loads and is no older than one save
# period: at most daemon.save_every integrations (scans that changed the map) behind the
# last scan the daemon had logged (at log level debug, one line per scan).
# Used by test_daemon.sh (20 trials) and `make crash-trials` (100).
set -u
BIN=${BUILD:-build}/bin
N=${1:-20}
EVERY=5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
url="file://$PWD/logs/tour.lcmlog?speed=0"
run() {
    exec "$BIN/houghlocd" --config /dev/null --map "$tmp/map.hlmap" --fresh-map \
        --set daemon.save_every=$EVERY --set daemon.log_level=debug --lcm-url "$url" \
        --lcm-out "file://$tmp/out.lcmlog?mode=w" 2>"$tmp/err"
}
# how long a whole replay takes here, in milliseconds
t0=$(date +%s%N); (run); t1=$(date +%s%N)
total_ms=$(( (t1 - t0) / 1000000 ))
bad=0; seed=$$; mid=0
i=0
while [ $i -lt "$N" ]; do
    i=$((i + 1))
    rm -f "$tmp/map.hlmap" "$tmp/map.hlmap.tmp"
    seed=$(( (seed * 1103515245 + 12345) % 2147483648 ))
    delay_ms=$(( seed % (total_ms + 1) ))
    run &
    pid=$!
    sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
    kill -KILL $pid 2>/dev/null
    wait $pid 2>/dev/null
    # the last scan the daemon said it had integrated ("scan N (seq S): ...")
    last=$(sed -n 's/^<7>houghlocd: scan \([0-9]*\) (seq.*/\1/p' "$tmp/err" | tail -n 1)
    last=${last:-0}
    if [ ! -e "$tmp/map.hlmap" ]; then
        # nothing saved yet: fine only before the first save was due
        [ "$last" -le $EVERY ] || { echo "trial $i: no map file after $last scans"; bad=$((bad + 1)); }
        continue
    fi
    info=$("$BIN/houghlocd" --config /dev/null --map "$tmp/map.hlmap" --check-map 2>&1)
    if [ $? -ne 0 ]; then
        echo "trial $i (killed after ${delay_ms} ms, $last scans): map file does not load: $info"
        bad=$((bad + 1)); continue
    fi
    saved=$(echo "$info" | sed -n 's/.* \([0-9]*\) scans,.*/\1/p')
    [ "$last" -gt 0 ] && [ "$last" -lt 128 ] && mid=$((mid + 1))
    behind=$(awk -v s="${saved:-0}" '$2 == "scan" && $3 > s && /, changed$/ { n++ }
                                     END { print n + 0 }' "$tmp/err")
    if [ -z "$saved" ] || [ "$behind" -gt $EVERY ]; then
        echo "trial $i: map file holds ${saved:-?} scans, $behind integrations behind scan $last"
        bad=$((bad + 1))
    fi
done
echo "crash trials: $N kills ($mid in mid-replay), $bad bad map files"
[ $bad -eq 0 ]
