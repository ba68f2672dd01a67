#!/bin/sh
# Integration test of houghloc-import-carmen on small CARMEN logs written here (never the
# real data): known ranges import to exactly the expected readings (checked through
# --dump, which decodes the output with the daemon's codecs), gzip gives the same bytes
# as plain text, comments and unknown lines are skipped, malformed lines stop it with
# FILE:LINE and exit 1 and no output, --select moved keeps the expected scans, the
# pseudo-sonar ring takes the nearest return in each cone, a scan without a truth pose is
# refused, the no-return values are recognized, and houghlocd replays an import without
# refusing a message.
set -u
BIN=${BUILD:-build}/bin
IMP=$BIN/houghloc-import-carmen
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh

# ---- a 3-scan log with known ranges, a comment, unknown lines and PARAMs ----------------
# 5 beams over 180 degrees: bearings -90, -45, 0, 45, 90 degrees = BAM 49152, 57344, 0,
# 8192, 16384. Scan 0: 81.83 m is no return, 40 m a return beyond 32.767 m. Scan 2:
# 32.767 m fits, 32.768 m does not, 0 is no return, 12.3456 m rounds to 12346 mm.
cat >"$tmp/a.log" <<'EOF'
# CARMEN log written by test_import.sh
# message formats defined: PARAM ODOM FLASER
PARAM robot_frontlaser_offset 0.0 nohost 0
ODOM 0.1 0.2 0.0 0 0 0 100.000001 nohost 100.000001

FLASER 5 1.000 2.500 3.25 81.83 40.0 0.1 0.2 0.0 0.1 0.2 0.0 100.000001 nohost 100.000001
NEFF 1 2 3
SOMETHING else entirely
FLASER 5 0.5 0.6 0.7 0.8 0.9 1.0 -2.0 1.5707963 1.0 -2.0 1.5707963 101.5 nohost 101.5
FLASER 5 32.767 32.768 0.001 0 12.3456 -3.0 0.5 3.14159265 -3.0 0.5 3.14159265 102.25 nohost 102.25
EOF
cat >"$tmp/a.tum" <<'EOF'
# time x y z qx qy qz qw
100.000001 0.11 0.21 0 0 0 0 1
101.500000 1.01 -1.99 0 0 0 0.7071067812 0.7071067812
102.250000 -3.0 0.5 0 0 0 1 0
103.000000 9 9 0 0 0 0 1
EOF
cat >"$tmp/a.want" <<'EOF'
ODOMETRY utime=100000001 pose=100,200,0 velocity_mm_s=0 stopped=1
SONAR utime=100000001 seq=0 odometry=100,200,0 readings=5 valid=3
  reading 0 bearing=49152 range_mm=1000 transducer=-1 valid=1
  reading 1 bearing=57344 range_mm=2500 transducer=-1 valid=1
  reading 2 bearing=0 range_mm=3250 transducer=-1 valid=1
  reading 3 bearing=8192 range_mm=0 transducer=-1 valid=0
  reading 4 bearing=16384 range_mm=0 transducer=-1 valid=0
GROUND_TRUTH utime=100000001 scan_seq=0 pose=110,210,0
ODOMETRY utime=101500000 pose=1000,-2000,16384 velocity_mm_s=1585 stopped=0
SONAR utime=101500000 seq=1 odometry=1000,-2000,16384 readings=5 valid=5
  reading 0 bearing=49152 range_mm=500 transducer=-1 valid=1
  reading 1 bearing=57344 range_mm=600 transducer=-1 valid=1
  reading 2 bearing=0 range_mm=700 transducer=-1 valid=1
  reading 3 bearing=8192 range_mm=800 transducer=-1 valid=1
  reading 4 bearing=16384 range_mm=900 transducer=-1 valid=1
GROUND_TRUTH utime=101500000 scan_seq=1 pose=1010,-1990,16384
ODOMETRY utime=102250000 pose=-3000,500,32768 velocity_mm_s=6289 stopped=0
SONAR utime=102250000 seq=2 odometry=-3000,500,32768 readings=5 valid=3
  reading 0 bearing=49152 range_mm=32767 transducer=-1 valid=1
  reading 1 bearing=57344 range_mm=0 transducer=-1 valid=0
  reading 2 bearing=0 range_mm=1 transducer=-1 valid=1
  reading 3 bearing=8192 range_mm=0 transducer=-1 valid=0
  reading 4 bearing=16384 range_mm=12346 transducer=-1 valid=1
GROUND_TRUTH utime=102250000 scan_seq=2 pose=-3000,500,32768
EOF
"$IMP" --truth "$tmp/a.tum" "$tmp/a.log" "$tmp/a.lcmlog" 2>"$tmp/a.sum"
check "3-scan log imports (exit 0)" test $? -eq 0
"$IMP" --dump "$tmp/a.lcmlog" >"$tmp/a.dump"
check "3-scan log: the exact readings, odometry and truth" cmp -s "$tmp/a.want" "$tmp/a.dump"
check "summary: 10 lines, 3 FLASER, 1 PARAM, 6 skipped (comments, empty, ODOM, unknown)" \
    grep -q "read $tmp/a.log: lines=10 flaser=3 param=1 skipped=6$" "$tmp/a.sum"
check "summary: 3 scans, 3 odometry, 3 ground truth" \
    grep -q "scans=3 odometry=3 ground_truth=3 skipped_by_selection=0 input=laser select=every" "$tmp/a.sum"
check "summary: 5 beams, 180 degrees by default, maximum 81.83 m is no return" \
    grep -q "beams_per_scan=5 fov_deg=180.0000 (default) step_deg=45.0000 (spread over the field of view) max_range_m=81.830 (1 beams, no return)" "$tmp/a.sum"
check "summary: 2 no-return beams, 2 beyond 32.767 m counted" \
    grep -q "valid=11 no_return=2 beyond_32.767m=2 " "$tmp/a.sum"
check "hl-eval reads the import (one STATUS-less log)" sh -c '"$1" extract "$2" SONAR "$3" && test -s "$3"' - \
    "$BIN/hl-eval" "$tmp/a.lcmlog" "$tmp/a.sonar"

# gzip input gives the same output as plain text.
gzip -c "$tmp/a.log" >"$tmp/a.log.gz"
"$IMP" --truth "$tmp/a.tum" "$tmp/a.log.gz" "$tmp/agz.lcmlog" 2>/dev/null
check "gzip input: byte-identical output" cmp -s "$tmp/a.lcmlog" "$tmp/agz.lcmlog"
# CRLF line ends read the same too.
sed 's/$/\r/' "$tmp/a.log" >"$tmp/crlf.log"
"$IMP" --truth "$tmp/a.tum" "$tmp/crlf.log" "$tmp/crlf.lcmlog" 2>/dev/null
check "CRLF input: byte-identical output" cmp -s "$tmp/a.lcmlog" "$tmp/crlf.lcmlog"

# houghlocd replays the import without refusing a message.
rm -f "$tmp/x.hlmap"
"$BIN/houghlocd" --config /dev/null --fresh-map --map "$tmp/x.hlmap" \
    --lcm-url "file://$tmp/a.lcmlog?speed=0" --lcm-out "file://$tmp/o.lcmlog?mode=w" \
    --set slam.echo_bearings=false 2>"$tmp/d.err"
check "houghlocd replays the import" test $? -eq 0
"$BIN/hl-eval" status "$tmp/o.lcmlog" >"$tmp/status"
check "houghlocd: 3 scans, bad_messages=0" grep -q "scans=3 .*bad_messages=0 " "$tmp/status"

# ---- malformed lines: exit 1, one line FILE:LINE, no output ------------------------------
bad() {     # bad DESCRIPTION EXPECTED_TEXT LINE: a.log's lines 1-6 (one FLASER), LINE as line 7
    head -n 6 "$tmp/a.log" >"$tmp/bad.log"
    printf '%s\n' "$3" >>"$tmp/bad.log"
    rm -f "$tmp/bad.lcmlog"
    rejects "$1" 1 "$2" "$IMP" "$tmp/bad.log" "$tmp/bad.lcmlog"
    check "$1: no output file" test ! -e "$tmp/bad.lcmlog"
}
bad "too few numbers" "bad.log:7: FLASER with 5 beams: the line ends after 3 numbers" \
    "FLASER 5 1 2 3"
bad "a word for a range" "bad.log:7: FLASER with 3 beams: beam 2 'abc' is not a number" \
    "FLASER 3 1.0 abc 2.0 0 0 0 0 0 0 5.0 nohost 5.0"
bad "a word for a pose value" "bad.log:7: FLASER with 3 beams: odom_x 'nan' is not a number" \
    "FLASER 3 1.0 1.5 2.0 0 0 0 nan 0 0 5.0 nohost 5.0"
bad "beam count above the ranges" "bad.log:7: FLASER declares 4 beams but holds 10 numbers before 'nohost'" \
    "FLASER 4 1.0 2.0 3.0 0 0 0 0 0 0 5.0 nohost 5.0"
bad "beam count below the ranges" "bad.log:7: FLASER declares 2 beams but holds 10 numbers before the hostname" \
    "FLASER 2 1.0 2.0 3.0 0 0 0 0 0 0 5.0 nohost 5.0"
bad "beam count not a number" "bad.log:7: FLASER beam count 'five' is not 2..8192" \
    "FLASER five 1 2 3 4 5 0 0 0 0 0 0 5.0"
bad "negative range" "bad.log:7: FLASER: beam 2 range -1.0 is negative" \
    "FLASER 3 1.0 -1.0 2.0 0 0 0 0 0 0 5.0 nohost 5.0"
bad "PARAM without a value" "bad.log:7: PARAM without a name and a value" "PARAM laser_front_laser_fov"
bad "field of view not a number" "bad.log:7: PARAM laser_front_laser_fov 'wide' is not a positive number" \
    "PARAM laser_front_laser_fov wide nohost 0"
bad "time going backwards" "bad.log:7: timestamp 99.000000 s goes back from line 6's 100.000001 s" \
    "FLASER 3 1 2 3 0 0 0 0 0 0 99.0 nohost 99.0"
bad "1100 beams in laser mode" "bad.log:7: 1100 beams: a scan holds at most 1024 readings" \
    "FLASER 1100 $(awk 'BEGIN { for (i = 0; i < 1100; i++) printf "1 " }') 0 0 0 0 0 0 200 nohost 200"

# ---- equal timestamps: one microsecond apart -------------------------------------------
printf 'FLASER 2 1 2 0 0 0 0 0 0 7.5 h 7.5\nFLASER 2 1 2 0 0 0 0 0 0 7.5 h 7.5\n' >"$tmp/eq.log"
"$IMP" "$tmp/eq.log" "$tmp/eq.lcmlog" 2>"$tmp/eq.sum"
"$IMP" --dump "$tmp/eq.lcmlog" | grep '^SONAR' | cut -d' ' -f2,3 | tr '\n' ' ' >"$tmp/eq.got"
check "equal timestamps: utimes 7500000 and 7500001" test "$(cat "$tmp/eq.got")" = "utime=7500000 seq=0 utime=7500001 seq=1 "
check "equal timestamps: counted" grep -q "timestamps_bumped=1$" "$tmp/eq.sum"

# ---- --select moved ------------------------------------------------------------------
# Odometry: (0,0,0) keep; (0.1,0,0) skip; (0.5,0,0) keep (0.5 m); (0.6,0,10 deg) skip
# (0.1 m, 10 deg); (0.6,0,16 deg) keep (16 deg); (0.7,0,20 deg) skip.
{
    for p in "0 0 0" "0.1 0 0" "0.5 0 0" "0.6 0 0.17453293" "0.6 0 0.27925268" "0.7 0 0.34906585"; do
        t=$((${t:-0} + 1))
        echo "FLASER 3 1 1 1 $p $p $t.0 h $t.0"
    done
} >"$tmp/mv.log"
"$IMP" --select moved "$tmp/mv.log" "$tmp/mv.lcmlog" 2>"$tmp/mv.sum"
"$IMP" --dump "$tmp/mv.lcmlog" | grep '^SONAR' | cut -d' ' -f2,3 | tr '\n' ' ' >"$tmp/mv.got"
check "moved (0.5 m, 15 deg): scans at 1, 3, 5 s, seq 0-2" \
    test "$(cat "$tmp/mv.got")" = "utime=1000000 seq=0 utime=3000000 seq=1 utime=5000000 seq=2 "
check "moved: ODOMETRY for all 6 lines, 3 skipped" \
    grep -q "scans=3 odometry=6 ground_truth=0 skipped_by_selection=3 input=laser select=moved move_m=0.5 turn_deg=15" "$tmp/mv.sum"
"$IMP" --select moved --move-m 1 --turn-deg 90 "$tmp/mv.log" "$tmp/mv2.lcmlog" 2>"$tmp/mv2.sum"
check "moved --move-m 1 --turn-deg 90: only the first" grep -q "scans=1 odometry=6 " "$tmp/mv2.sum"
"$IMP" --select every "$tmp/mv.log" "$tmp/mv3.lcmlog" 2>"$tmp/mv3.sum"
check "every: all 6" grep -q "scans=6 odometry=6 ground_truth=0 skipped_by_selection=0" "$tmp/mv3.sum"

# ---- pseudo-sonar ring ---------------------------------------------------------------
# 181 beams, 1 degree apart (beam i at i - 90 degrees), 10 m except: +5 deg 2 m, -40 deg
# 3 m, +49 deg 1.5 m, and no return (81.83) from +60 to +90 deg. 64 readings at
# (j - 31.5) * 2.8125 deg = (2j - 63) * 256 BAM. The +5 deg beam is the nearest return of
# readings 30..37 (cones -4.2..15.5 deg), off their axes; -40 deg that of readings 14..21;
# +49 deg that of 46..52 but not of 45 and 53, 11.03 and 11.47 deg away; readings 57..63
# see only no-return beams.
awk 'BEGIN {
    printf "FLASER 181";
    for (i = 0; i <= 180; i++) {
        b = i - 90; r = "10.0";
        if (b == 5) r = "2.0"; else if (b == -40) r = "3.0"; else if (b == 49) r = "1.5";
        else if (b >= 60) r = "81.83";
        printf " %s", r;
    }
    print " 0 0 0 0 0 0 1.0 h 1.0";
}' >"$tmp/s.log"
"$IMP" --input sonar "$tmp/s.log" "$tmp/s.lcmlog" 2>"$tmp/s.sum"
"$IMP" --dump "$tmp/s.lcmlog" >"$tmp/s.dump"
check "sonar: 64 readings, 57 valid" grep -q "^SONAR utime=1000000 seq=0 odometry=0,0,0 readings=64 valid=57$" "$tmp/s.dump"
reading() { # reading J BEARING RANGE VALID: the dump's line for reading J
    grep -q "^  reading $1 bearing=$2 range_mm=$3 transducer=$1 valid=$4\$" "$tmp/s.dump"
}
check "sonar: reading 0 at -88.6 deg: 10 m" reading 0 49408 10000 1
check "sonar: reading 13 (-52.0 deg) does not reach -40 deg" reading 13 56064 10000 1
check "sonar: reading 14 (-49.2 deg): the -40 deg beam" reading 14 56576 3000 1
check "sonar: reading 21 (-29.5 deg): the -40 deg beam" reading 21 60160 3000 1
check "sonar: reading 22 (-26.7 deg) does not reach it" reading 22 60672 10000 1
check "sonar: reading 29 (-7.0 deg) does not reach +5 deg" reading 29 64256 10000 1
check "sonar: reading 30 (-4.2 deg): the +5 deg beam, off-axis" reading 30 64768 2000 1
check "sonar: reading 31 (-1.4 deg): the +5 deg beam" reading 31 65280 2000 1
check "sonar: reading 37 (+15.5 deg): the +5 deg beam" reading 37 2816 2000 1
check "sonar: reading 38 (+18.3 deg): 10 m" reading 38 3328 10000 1
check "sonar: reading 45 (+38.0 deg) does not reach +49 deg (11.03 deg)" reading 45 6912 10000 1
check "sonar: reading 46 (+40.8 deg): the +49 deg beam" reading 46 7424 1500 1
check "sonar: reading 52 (+57.7 deg): the +49 deg beam" reading 52 10496 1500 1
check "sonar: reading 53 (+60.5 deg) does not reach +49 deg (11.47 deg)" reading 53 11008 10000 1
check "sonar: reading 56 (+68.9 deg) reaches 10 m at 58-59 deg" reading 56 12544 10000 1
check "sonar: reading 57 (+71.7 deg): no return" reading 57 13056 0 0
check "sonar: reading 63 (+88.6 deg): no return" reading 63 16128 0 0
check "sonar: summary" grep -q "readings: total=64 valid=57 per_scan=64" "$tmp/s.sum"
"$IMP" --input sonar --fov-deg 360 "$tmp/s.log" "$tmp/s360.lcmlog" 2>/dev/null
check "sonar over 360 degrees: 128 readings" sh -c '"$1" --dump "$2" | grep -q "readings=128 "' - "$IMP" "$tmp/s360.lcmlog"

# ---- field of view from PARAM (degrees or radians) -----------------------------------
for fov in 90 1.5707963; do
    printf 'PARAM laser_front_laser_fov %s h 0\nFLASER 3 1 2 3 0 0 0 0 0 0 1.0 h 1.0\n' "$fov" >"$tmp/f.log"
    "$IMP" "$tmp/f.log" "$tmp/f.lcmlog" 2>"$tmp/f.sum"
    check "PARAM laser_front_laser_fov $fov: bearings -45, 0, 45 deg" \
        test "$("$IMP" --dump "$tmp/f.lcmlog" | grep -o 'bearing=[0-9]*' | tr '\n' ' ')" = "bearing=57344 bearing=0 bearing=8192 "
    check "PARAM laser_front_laser_fov $fov: summary says PARAM" grep -q "fov_deg=90.0000 (PARAM)" "$tmp/f.sum"
done

# csail's PARAM, 3.14159 rad (179.9998 degrees), still makes a ring of 64.
printf 'PARAM laser_front_laser_fov 3.14159 h 0\nFLASER 3 1 2 3 0 0 0 0 0 0 1.0 h 1.0\n' >"$tmp/f.log"
"$IMP" --input sonar "$tmp/f.log" "$tmp/f.lcmlog" 2>/dev/null
check "PARAM laser_front_laser_fov 3.14159, sonar: 64 readings" \
    sh -c '"$1" --dump "$2" | grep -q "readings=64 "' - "$IMP" "$tmp/f.lcmlog"

# A resolution PARAM that does not fit 180 degrees, without a field of view: refused.
printf 'PARAM laser_front_laser_resolution 0.25 h 0\nFLASER 3 1 2 3 0 0 0 0 0 0 1.0 h 1.0\n' >"$tmp/r.log"
rejects "resolution 0.25 with 3 beams and no field of view" 1 \
    "r.log: PARAM laser_front_laser_resolution 0.25 degrees does not fit 3 to 3 beams" \
    "$IMP" "$tmp/r.log" "$tmp/r.lcmlog"
"$IMP" --fov-deg 0.5 "$tmp/r.log" "$tmp/r.lcmlog" 2>"$tmp/r.sum"
check "... imports with --fov-deg 0.5" grep -q "fov_deg=0.5000 (--fov-deg)" "$tmp/r.sum"
printf 'PARAM laser_front_laser_resolution 0.5 h 0\nFLASER 360 %s 0 0 0 0 0 0 1.0 h 1.0\n' \
    "$(awk 'BEGIN { for (i = 0; i < 360; i++) printf "1 " }')" >"$tmp/r2.log"
"$IMP" "$tmp/r2.log" "$tmp/r2.lcmlog" 2>"$tmp/r2.sum"
check "resolution 0.5 with 360 beams fits 180 degrees (freiburg)" grep -q "fov_deg=180.0000 (default)" "$tmp/r2.sum"

# ---- where the beams point (CARMEN's reader of FLASER lines) ---------------------------
# 180 beams without a PARAM: the SICK's 1 degree from -90, the last at +89 (the 181st
# dropped); with --fov-deg 180 spread evenly, the last at +90. 360 beams: 0.5 degrees,
# the last at +89.5. BAM: 65536 a turn, so 89 deg = 16202, 89.5 deg = 16293.
beams() { # beams N FILE: a FLASER line of N beams, 1 m each
    awk -v n="$1" 'BEGIN { printf "FLASER %d", n; for (i = 0; i < n; i++) printf " 1";
                           print " 0 0 0 0 0 0 1.0 h 1.0" }' >"$2"
}
bearing_of() { # bearing_of LCMLOG I: the bearing of reading I
    "$IMP" --dump "$1" | sed -n "s/^  reading $2 bearing=\([0-9]*\) .*/\1/p"
}
beams 180 "$tmp/b180.log"
"$IMP" "$tmp/b180.log" "$tmp/b180.lcmlog" 2>"$tmp/b180.sum"
check "180 beams: the first at -90 deg" test "$(bearing_of "$tmp/b180.lcmlog" 0)" = 49152
check "180 beams: beam 90 at 0 deg" test "$(bearing_of "$tmp/b180.lcmlog" 90)" = 0
check "180 beams: the last at +89 deg" test "$(bearing_of "$tmp/b180.lcmlog" 179)" = 16202
check "180 beams: summary names the SICK's step" \
    grep -q "fov_deg=180.0000 (default) step_deg=1.0000 (the SICK's for the beam count)" "$tmp/b180.sum"
"$IMP" --fov-deg 180 "$tmp/b180.log" "$tmp/b180s.lcmlog" 2>"$tmp/b180s.sum"
check "180 beams, --fov-deg 180: the last at +90 deg" test "$(bearing_of "$tmp/b180s.lcmlog" 179)" = 16384
check "180 beams, --fov-deg 180: summary says spread" \
    grep -q "step_deg=1.0056 (spread over --fov-deg)" "$tmp/b180s.sum"
beams 360 "$tmp/b360.log"
"$IMP" "$tmp/b360.log" "$tmp/b360.lcmlog" 2>/dev/null
check "360 beams: the last at +89.5 deg" test "$(bearing_of "$tmp/b360.lcmlog" 359)" = 16293
{ printf 'PARAM laser_front_laser_resolution 0.5 h 0\n'; cat "$tmp/b360.log"; } >"$tmp/b360r.log"
"$IMP" "$tmp/b360r.log" "$tmp/b360r.lcmlog" 2>"$tmp/b360r.sum"
check "360 beams, resolution PARAM 0.5: the last at +89.5 deg" \
    test "$(bearing_of "$tmp/b360r.lcmlog" 359)" = 16293
check "360 beams, resolution PARAM 0.5: summary says PARAM" grep -q "step_deg=0.5000 (PARAM)" "$tmp/b360r.sum"
beams 7 "$tmp/b7.log"
"$IMP" "$tmp/b7.log" "$tmp/b7.lcmlog" 2>"$tmp/b7.sum"
check "7 beams: no SICK step, spread over 180 deg (the last at +90)" \
    test "$(bearing_of "$tmp/b7.lcmlog" 6)" = 16384
check "7 beams: summary says spread" grep -q "step_deg=30.0000 (spread over the field of view)" "$tmp/b7.sum"
{ printf 'PARAM laser_front_laser_fov 90 h 0\n'; cat "$tmp/b180.log"; } >"$tmp/b180f.log"
"$IMP" "$tmp/b180f.log" "$tmp/b180f.lcmlog" 2>/dev/null
check "180 beams over a 90-degree PARAM: spread, the last at +45 deg" \
    test "$(bearing_of "$tmp/b180f.lcmlog" 179)" = 8192

# ---- no-return values ----------------------------------------------------------------
# 49.9 m and above is no return; 49.89 m is a return beyond 32.767 m.
printf 'FLASER 3 49.9 49.89 50 0 0 0 0 0 0 1.0 h 1.0\n' >"$tmp/n1.log"
"$IMP" "$tmp/n1.log" "$tmp/n1.lcmlog" 2>"$tmp/n1.sum"
check "49.9 and 50 m no return, 49.89 m beyond" grep -q "valid=0 no_return=2 beyond_32.767m=1 " "$tmp/n1.sum"
# A log whose maximum, 32.767 m, repeats: that is its no-return value.
printf 'FLASER 3 1.5 32.767 2 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 32.767 1 2 0 0 0 0 0 0 2.0 h 2.0\n' >"$tmp/n2.log"
"$IMP" "$tmp/n2.log" "$tmp/n2.lcmlog" 2>"$tmp/n2.sum"
check "repeated maximum 32.767 m: the no-return value" \
    grep -q "max_range_m=32.767 (2 beams, the no-return value)" "$tmp/n2.sum"
check "repeated maximum 32.767 m: 2 no-return beams, 4 valid" grep -q "valid=4 no_return=2 beyond" "$tmp/n2.sum"
check "repeated maximum: readings invalid" test "$("$IMP" --dump "$tmp/n2.lcmlog" | grep -c 'range_mm=0 transducer=-1 valid=0')" -eq 2
# A single longest return is a return.
printf 'FLASER 3 1.5 32.767 2 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 3 1 2 0 0 0 0 0 0 2.0 h 2.0\n' >"$tmp/n3.log"
"$IMP" "$tmp/n3.log" "$tmp/n3.lcmlog" 2>"$tmp/n3.sum"
check "single maximum 32.767 m: a return" grep -q "max_range_m=32.767 (1 beams, a return)" "$tmp/n3.sum"
check "single maximum 32.767 m: a valid 32767 mm reading" sh -c '"$1" --dump "$2" | grep -q "range_mm=32767 transducer=-1 valid=1"' - "$IMP" "$tmp/n3.lcmlog"
# A repeated maximum outnumbered by the ranges within 1 m below it is a return too.
printf 'FLASER 5 3.0 3.0 2.5 2.6 2.7 0 0 0 0 0 0 1.0 h 1.0\n' >"$tmp/n5.log"
"$IMP" "$tmp/n5.log" "$tmp/n5.lcmlog" 2>"$tmp/n5.sum"
check "maximum 3 m twice, 3 ranges within 1 m below: a return" \
    grep -q "max_range_m=3.000 (2 beams, a return)" "$tmp/n5.sum"
"$IMP" --no-return-m 2 "$tmp/n3.log" "$tmp/n4.lcmlog" 2>"$tmp/n4.sum"
check "--no-return-m 2: 2 m and more no return" grep -q "valid=2 no_return=4 beyond" "$tmp/n4.sum"

# ---- ground truth ----------------------------------------------------------------------
grep -v '^101.5' "$tmp/a.tum" >"$tmp/miss.tum"
rm -f "$tmp/miss.lcmlog"
rejects "a scan without a truth pose" 1 "a.log:9: the scan at 101.500000 s has no pose in $tmp/miss.tum" \
    "$IMP" --truth "$tmp/miss.tum" "$tmp/a.log" "$tmp/miss.lcmlog"
check "missing truth: no output file" test ! -e "$tmp/miss.lcmlog"
printf '1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0.5\n' >"$tmp/badtum.tum"
rejects "malformed TUM line" 1 "badtum.tum:2: expected 8 fields" "$IMP" --truth "$tmp/badtum.tum" "$tmp/a.log" "$tmp/x.lcmlog"
printf '1.0 0 0 0 0 0 0 2\n' >"$tmp/badq.tum"
rejects "TUM quaternion not unit" 1 "badq.tum:1: quaternion norm 2.000000 is not 1" "$IMP" --truth "$tmp/badq.tum" "$tmp/a.log" "$tmp/x.lcmlog"

# ---- usage -----------------------------------------------------------------------------
check "--help exits 0 and names the options" sh -c '"$1" --help | grep -q -- "--input laser|sonar"' - "$IMP"
check "--version prints the version" sh -c '"$1" --version | grep -q "^houghloc-import-carmen [0-9][0-9.]*$"' - "$IMP"
rejects "unknown option" 2 "unknown option '--frobnicate'" "$IMP" --frobnicate a b
rejects "bad --input" 2 "--input 'radar'" "$IMP" --input radar a b
rejects "bad --move-m" 2 "--move-m '-1'" "$IMP" --move-m -1 a b
rejects "missing OUT" 2 "expected IN and OUT" "$IMP" "$tmp/a.log"
rejects "missing input file" 1 "nowhere.log: cannot open" "$IMP" "$tmp/nowhere.log" "$tmp/x.lcmlog"
rejects "OUT is IN" 1 "is the input too" "$IMP" "$tmp/a.log" "$tmp/a.log"
printf 'no flaser here\n' >"$tmp/empty.log"
rejects "no FLASER line" 1 "empty.log: no FLASER line" "$IMP" "$tmp/empty.log" "$tmp/x.lcmlog"
head -c "$(($(wc -c <"$tmp/a.log.gz") / 2))" "$tmp/a.log.gz" >"$tmp/trunc.log.gz"
rejects "truncated gzip" 1 "trunc.log.gz: read error" "$IMP" "$tmp/trunc.log.gz" "$tmp/x.lcmlog"

exit $fail
