#!/bin/sh
# tests/fuzz/make_seeds.sh - remakes the seed corpora of tests/fuzz/corpus/ (make
# fuzz-seeds). Every seed is small and comes from the project itself: packets and
# messages made by its encoders (gen_seeds.c), messages and log heads from logs/ and from
# a short houghlocd replay of logs/tour.lcmlog, the map file that replay saves, the
# configuration files, CARMEN lines like those of tests/integration/test_import.sh, and
# the simulator's world files. The regression inputs (tests/fuzz/regress/) are never
# touched here.
set -eu
B=${BUILD:-build}
C=tests/fuzz/corpus
G=$B/tests/fuzz/gen_seeds
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM

# the targets of tests/fuzz/fuzz.mk whose seeds are made here; those of keyfile,
# console_body and cycle (operation sequences, see fuzz_cycle.c) are written by hand
# and kept
for t in arcos rlink bus_scan bus_odometry bus_pose bus_map bus_status bus_destination \
         bus_command bus_reply logcheck config mapstore carmen carmen_reader world; do
    rm -rf "${C:?}/$t"
    mkdir -p "$C/$t"
done

# ---- encoders and logs -----------------------------------------------------------------
"$G" encode "$C"
for log in logs/tour.lcmlog logs/lab28.lcmlog logs/orientation.lcmlog; do
    "$G" log "$C" "$log"
done
# A short replay: POSE, MAP, STATUS from the daemon, and the map file it saves.
"$G" head logs/tour.lcmlog 200 "$tmp/head.lcmlog"
"$B/bin/houghlocd" --config /dev/null --fresh-map --map "$tmp/tour-head.hlmap" \
    --set daemon.status_period_ms=100 \
    --lcm-url "file://$tmp/head.lcmlog?speed=0" \
    --lcm-out "file://$tmp/daemon-out.lcmlog?mode=w" 2>/dev/null
"$G" log "$C" "$tmp/daemon-out.lcmlog"
cp "$tmp/tour-head.hlmap" "$C/mapstore/tour-head.hlmap"
"$G" head logs/tour.lcmlog 50 "$tmp/first.lcmlog"
"$B/bin/houghlocd" --config /dev/null --fresh-map --map "$tmp/one-scan.hlmap" \
    --lcm-url "file://$tmp/first.lcmlog?speed=0" \
    --lcm-out "file://$tmp/first-out.lcmlog?mode=w" 2>/dev/null
cp "$tmp/one-scan.hlmap" "$C/mapstore/one-scan.hlmap"

# ---- configuration -----------------------------------------------------------------------
cp packaging/houghlocd.conf "$C/config/houghlocd.conf"
for f in tools/lab/realeval/*.conf; do cp "$f" "$C/config/realeval-$(basename "$f")"; done
for f in tools/lab/kidnap/*.conf; do cp "$f" "$C/config/kidnap-$(basename "$f")"; done
"$B/bin/houghlocd" --config /dev/null --print-config > "$C/config/printed.conf"
printf '[slam]\nprofile = paper\n[daemon]\nsave_every = 0\n' > "$C/config/paper"
printf '[fence]\npolygon = -5,-5 5,-5 5,5 -5,5\n[lcm]\nprefix = robot1/\n' > "$C/config/fence"
printf '[robot]\nlink = tcp:127.0.0.1:8101\nprofile = pioneer3\n' > "$C/config/robot"
printf '; comment\n# another\n\n[start]\nx_m = 1.5\ny_m = -2\nheading_deg = 90\n' > "$C/config/start"
printf '[daemon]\nlog_level = debug\nmap_file = /tmp/x.hlmap\n[auth]\nkey_file = /k\n' \
    > "$C/config/daemon"

# ---- CARMEN ------------------------------------------------------------------------------
n=0
line() { n=$((n + 1)); printf '%s' "$1" > "$C/carmen/line-$n"; }
line 'PARAM robot_frontlaser_offset 0.0 nohost 0'
line 'FLASER 5 1.000 2.500 3.25 81.83 40.0 0.1 0.2 0.0 0.1 0.2 0.0 100.000001 nohost 100.000001'
line 'FLASER 5 0.5 0.6 0.7 0.8 0.9 1.0 -2.0 1.5707963 1.0 -2.0 1.5707963 101.5 nohost 101.5'
line 'FLASER 5 32.767 32.768 0.001 0 12.3456 -3.0 0.5 3.14159265 -3.0 0.5 3.14159265 102.25'
line 'FLASER 3 1.0 1.5 2.0 0 0 0 nan 0 0 5.0 nohost 5.0'
line 'FLASER 2 1.0 2.0 3.0 0 0 0 0 0 0 5.0 nohost 5.0'
line 'ODOM 0.1 0.2 0.0 0 0 0 100.000001 nohost 100.000001'
line '# CARMEN log written by test_import.sh'
line 'FLASER 4 1e-3 +2 .5 7. 1E2 -0.0 3 4 5 6 1134860000.0012345 host 1134860000.0012345'
# a 180-beam scan, as the real logs have
awk 'BEGIN { printf "FLASER 180"; for (i = 0; i < 180; i++) printf " %.3f", 1 + (i % 37) * 0.25;
             printf " 1.5 -2.25 0.7853 1.5 -2.25 0.7853 1134860000.123456 nohost 1134860000.2" }' \
    > "$C/carmen/line-180"
cat > "$tmp/a.log" <<'LOG'
# CARMEN log written by make_seeds.sh
PARAM robot_frontlaser_offset 0.0 nohost 0
ODOM 0.1 0.2 0.0 0 0 0 100.000001 nohost 100.000001

FLASER 5 1.000 2.500 3.25 81.83 40.0 0.1 0.2 0.0 0.1 0.2 0.0 100.000001 nohost 100.000001
NEFF 1 2 3
FLASER 5 0.5 0.6 0.7 0.8 0.9 1.0 -2.0 1.5707963 1.0 -2.0 1.5707963 101.5 nohost 101.5
LOG
cp "$tmp/a.log" "$C/carmen_reader/plain.log"
printf 'FLASER 2 1 2 0 0 0 0 0 0 7\r\nPARAM a b\r\n' > "$C/carmen_reader/crlf.log"
gzip -n -c "$tmp/a.log" > "$C/carmen_reader/gzip.log.gz"
cp "$C/carmen/line-180" "$C/carmen_reader/long-line.log"

# ---- worlds ------------------------------------------------------------------------------
for f in tools/sim/worlds/*.world; do cp "$f" "$C/world/$(basename "$f")"; done
printf 'segment 0 0 1000 0 rough\ncircle 500 500 50 thin\nposition a 100 100 90\n' \
    > "$C/world/shapes"
printf 'polygon 0 0 4000 0 4000 3000 0 3000\nrbox 2000 1500 400 600 30\ntiles 500\n' \
    > "$C/world/room"
printf 'open 0 0 10 10\norientation 1 1\ntour 2 2\nbox 0 0 5 5 # a comment\n' \
    > "$C/world/layout"

echo "seeds: $(find "$C" -type f | wc -l) files, $(cat $(find "$C" -type f) | wc -c) bytes"
