#!/bin/sh
# Integration test of houghloc-map: on a tiny map file written here byte by byte (two
# vectors whose cells are known), the PGM's header, size and cells (surface occupied,
# the beam back to the sensor free, elsewhere unknown) and the YAML's keys; on the map
# the daemon makes of the tour, the PGM's size and values and that the cells of its
# surface points are occupied and most beams free; the last MAP of a log; --trajectory;
# and bad usage and bad input get one line and exit 2 / 1.
set -u
BIN=${BUILD:-build}/bin
MAP=$BIN/houghloc-map
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh

# ---- writing a map file (docs/manual/mapfile.md) -------------------------------------------
u8() {      # one byte
    printf "\\$(printf %03o "$1")"
}
le() {      # le BYTES VALUE: little-endian, two's complement
    n=$1; v=$2; i=0
    [ "$v" -lt 0 ] && v=$((v + (1 << (8 * n))))
    while [ $i -lt "$n" ]; do u8 $(((v >> (8 * i)) & 255)); i=$((i + 1)); done
}
mapfile() { # mapfile FILE [X Y NORMAL RANGE]...: a format version 1 map (still read) with
            # these vectors
    f=$1; shift
    {
        printf 'HLMAP\r\n\032'
        le 4 1; le 4 93; le 4 16; le 4 $(($# / 4)); le 4 1; u8 1
        le 4 0; le 4 0; le 2 0; le 4 0; le 4 0; le 2 0     # pose, odometry reference
        le 4 0; le 8 12345; le 8 1; le 8 0; le 8 0; le 8 0 # peak, PRNG, seq, utime, scans
        while [ $# -ge 4 ]; do le 4 "$1"; le 4 "$2"; le 2 "$3"; le 2 "$4"; shift 4; done
    } >"$f"
    # gzip's trailer holds the CRC-32 of its input, little-endian: zlib's crc32.
    gzip -c "$f" | tail -c 8 | head -c 4 >>"$f"
}

# ---- reading a PGM --------------------------------------------------------------------
hdr() {     # header bytes of a PGM: its first four lines
    head -n 4 "$1" | wc -c
}
yaml() {    # yaml FILE KEY: the value
    sed -n "s/^$2: //p" "$1"
}
cell() {    # cell BASE X_MM Y_MM: the PGM value of the cell holding that point
    set -- "$1" "$2" "$3" "$(yaml "$1.yaml" resolution)" "$(yaml "$1.yaml" origin)" \
        "$(sed -n 3p "$1.pgm")" "$(hdr "$1.pgm")"
    off=$(echo "$2 $3 $4 $5 $6 $7" | tr -d '[],' | awk '{
        i = int(($1 / 1000 - $4) / $3); j = int(($2 / 1000 - $5) / $3)
        print $9 + ($8 - 1 - j) * $7 + i }')
    od -An -tu1 -j "$off" -N1 "$1.pgm" | tr -d ' '
}

# ---- a tiny map: two vectors, cells of 0.1 m ------------------------------------------
# A: surface (1.05, 0.05) m, normal 180 deg, range 2 m: the sensor stood at (-0.95, 0.05).
# B: surface (0.05, 1.55) m, normal 270 deg, range 1.5 m: the sensor stood at (0.05, 0.05).
mapfile "$tmp/tiny.hlmap" 1050 50 32768 2000 50 1550 49152 1500
check "the tiny map file loads in the daemon's checker" \
    sh -c '"$1" --config /dev/null --map "$2" --check-map >/dev/null 2>&1' - "$BIN/houghlocd" "$tmp/tiny.hlmap"
check "the checker reads it as format 1, its map version widened" \
    sh -c '"$1" --config /dev/null --map "$2" --check-map 2>&1 | grep -q ": format 1, 2 of 16 vectors, map version 1,"' \
    - "$BIN/houghlocd" "$tmp/tiny.hlmap"
"$MAP" --resolution 0.1 "$tmp/tiny.hlmap" "$tmp/tiny" >"$tmp/out"
check "houghloc-map exits 0 on the tiny map" test $? -eq 0
check "it writes the PNG" sh -c 'head -c 8 "$1" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a"' - "$tmp/tiny.png"
# x: cells -10..10 of the data, 2 of margin each side: 25; y: 0..15 and margins: 20.
check "PGM magic P5" test "$(head -n 1 "$tmp/tiny.pgm")" = P5
check "PGM size 25 x 20" test "$(sed -n 3p "$tmp/tiny.pgm")" = "25 20"
check "PGM maxval 255" test "$(sed -n 4p "$tmp/tiny.pgm")" = 255
check "PGM file size: header + 25 x 20" test "$(wc -c <"$tmp/tiny.pgm")" -eq $(($(hdr "$tmp/tiny.pgm") + 500))
check "YAML image" test "$(yaml "$tmp/tiny.yaml" image)" = tiny.pgm
check "YAML resolution" test "$(yaml "$tmp/tiny.yaml" resolution)" = 0.100000
check "YAML origin" test "$(yaml "$tmp/tiny.yaml" origin)" = "[-1.200000, -0.200000, 0.000000]"
check "YAML negate" test "$(yaml "$tmp/tiny.yaml" negate)" = 0
check "YAML occupied_thresh" test "$(yaml "$tmp/tiny.yaml" occupied_thresh)" = 0.65
check "YAML free_thresh" test "$(yaml "$tmp/tiny.yaml" free_thresh)" = 0.196
check "YAML mode" test "$(yaml "$tmp/tiny.yaml" mode)" = trinary
check "surface A occupied" test "$(cell "$tmp/tiny" 1050 50)" = 0
check "surface B occupied" test "$(cell "$tmp/tiny" 50 1550)" = 0
check "A's beam free halfway" test "$(cell "$tmp/tiny" 550 50)" = 254
check "A's beam free just before the surface" test "$(cell "$tmp/tiny" 950 50)" = 254
check "A's sensor free" test "$(cell "$tmp/tiny" -950 50)" = 254
check "B's beam free" test "$(cell "$tmp/tiny" 50 750)" = 254
check "behind A unknown" test "$(cell "$tmp/tiny" 1150 50)" = 205
check "off both beams unknown" test "$(cell "$tmp/tiny" 550 550)" = 205
# A's beam crosses 20 cells before its surface, B's 15, sharing B's sensor cell.
check "cells: 2 occupied, 34 free, 464 unknown" test "$(tail -c 500 "$tmp/tiny.pgm" |
    od -An -tu1 -v | tr -s ' ' '\n' | grep . | sort -n | uniq -c | tr -s ' ' | tr '\n' ,)" = " 2 0, 464 205, 34 254,"

# ---- the map the daemon makes of the tour --------------------------------------------
"$BIN/houghlocd" --config /dev/null --fresh-map --map "$tmp/m.hlmap" \
    --lcm-url "file://$PWD/logs/tour.lcmlog?speed=0" --lcm-out "file://$tmp/o.lcmlog?mode=w" 2>/dev/null
check "the daemon replays the tour" test $? -eq 0
"$MAP" "$tmp/m.hlmap" "$tmp/tour" >/dev/null
check "houghloc-map exits 0 on the tour's map" test $? -eq 0
wh=$(sed -n 3p "$tmp/tour.pgm" 2>/dev/null)
[ -n "$wh" ] || wh="0 0"
check "tour PGM: header + width x height bytes" test "$(wc -c <"$tmp/tour.pgm")" -eq \
    $(($(hdr "$tmp/tour.pgm") + ${wh% *} * ${wh#* }))
check "tour PGM holds only 0, 205 and 254" test "$(tail -c $((${wh% *} * ${wh#* })) "$tmp/tour.pgm" |
    od -An -tu1 -v | tr -s ' ' '\n' | grep . | sort -un | tr '\n' ' ')" = "0 205 254 "
check "tour YAML resolution 0.05" test "$(yaml "$tmp/tour.yaml" resolution)" = 0.050000
# Every vector of the file (docs/manual/mapfile.md, format 2 as the daemon saves it: 12
# bytes each from byte 97): its surface
# cell occupied; halfway to its sensor, the cell or a neighbour (Bresenham's cells stray
# up to one cell from the exact line) free, unless another surface lies there.
count=$(od -An -tu1 -j20 -N4 "$tmp/m.hlmap" | awk '{ print $1 + 256 * ($2 + 256 * ($3 + 256 * $4)) }')
check "the daemon saves format 2" test "$(od -An -tu1 -j8 -N1 "$tmp/m.hlmap" | tr -d ' ')" = 2
od -An -tu1 -v -j97 -N$((12 * count)) "$tmp/m.hlmap" >"$tmp/vectors"
tail -c $((${wh% *} * ${wh#* })) "$tmp/tour.pgm" | od -An -tu1 -v >"$tmp/cells"
awk -v w="${wh% *}" -v h="${wh#* }" -v res="$(yaml "$tmp/tour.yaml" resolution)" \
    -v origin="$(yaml "$tmp/tour.yaml" origin | tr -d '[],')" '
    function s32(a, b, c, d,    u) { u = a + 256 * (b + 256 * (c + 256 * d)); return u >= 2147483648 ? u - 4294967296 : u }
    function at(x, y,    i, j) {
        i = int((x / 1000 - ox) / res + 1e6) - 1e6; j = int((y / 1000 - oy) / res + 1e6) - 1e6
        return cell[(h - 1 - j) * w + i]
    }
    function near_free(x, y,    di, dj) {  # Bresenham cells can be a neighbour off the line
        for (di = -1; di <= 1; di++) for (dj = -1; dj <= 1; dj++)
            if (at(x + di * res * 1000, y + dj * res * 1000) == 254) return 1
        return 0
    }
    BEGIN { split(origin, o, " "); ox = o[1]; oy = o[2]; pi = atan2(0, -1) }
    FNR == NR { for (k = 1; k <= NF; k++) b[nb++] = $k; next }
    { for (k = 1; k <= NF; k++) cell[nc++] = $k }
    END {
        for (v = 0; v + 12 <= nb; v += 12) {
            x = s32(b[v], b[v + 1], b[v + 2], b[v + 3]); y = s32(b[v + 4], b[v + 5], b[v + 6], b[v + 7])
            a = (b[v + 8] + 256 * b[v + 9]) * 2 * pi / 65536; r = b[v + 10] + 256 * b[v + 11]
            n++; if (at(x, y) == 0) occ++
            if (r >= 500) { mx = x + r / 2 * cos(a); my = y + r / 2 * sin(a); rays++
                            if (near_free(mx, my)) free++; else if (at(mx, my) != 0) bad++ }
        }
        printf "%d vectors, %d surface cells occupied, %d beams of 0.5 m or more: %d free halfway, %d neither\n", n, occ, rays, free, bad
        exit !(n == 1500 && occ == n && rays > 100 && bad == 0 && free >= 0.9 * rays)
    }' "$tmp/vectors" "$tmp/cells" >"$tmp/summary"
check "tour: $(cat "$tmp/summary")" test $? -eq 0

# The last MAP message of the daemon's output log; --trajectory adds two legend lines.
"$MAP" --normals "$tmp/o.lcmlog" "$tmp/fromlog" >/dev/null
check "the last MAP of a log" test $? -eq 0
check "it has the map's size" test "$(sed -n 3p "$tmp/fromlog.pgm")" = "$wh"
"$MAP" --trajectory "$tmp/o.lcmlog" --trajectory logs/tour.lcmlog "$tmp/m.hlmap" "$tmp/traj" >/dev/null
check "--trajectory exits 0" test $? -eq 0
png_h() {   # a PNG's height, from its IHDR
    od -An -tu1 -j20 -N4 "$1" | awk '{ print (($1 * 256 + $2) * 256 + $3) * 256 + $4 }'
}
check "--trajectory: the picture gains its two legend lines" \
    test "$(png_h "$tmp/traj.png")" -gt "$(png_h "$tmp/tour.png")"
check "the PGM ignores the trajectories" cmp -s "$tmp/traj.pgm" "$tmp/tour.pgm"
# The truth is drawn in the map frame: its first pose at the daemon's start pose (--start,
# default the origin, as the daemon that made the map), so the true path lies on the map
# as the estimated one does and the picture keeps its size; a start 20 m north moves it
# off the map, and the picture grows to hold it.
png_w() {   # a PNG's width
    od -An -tu1 -j16 -N4 "$1" | awk '{ print (($1 * 256 + $2) * 256 + $3) * 256 + $4 }'
}
"$MAP" --trajectory "$tmp/o.lcmlog" "$tmp/m.hlmap" "$tmp/est" >/dev/null
"$MAP" --trajectory logs/tour.lcmlog "$tmp/m.hlmap" "$tmp/truth" >/dev/null
check "the true path on the map: the picture as with the estimated one" \
    test "$(png_w "$tmp/truth.png")x$(png_h "$tmp/truth.png")" = "$(png_w "$tmp/est.png")x$(png_h "$tmp/est.png")"
"$MAP" --start 0,20,0 --trajectory logs/tour.lcmlog "$tmp/m.hlmap" "$tmp/north" >/dev/null
check "--start 0,20,0: the true path 20 m north, a taller picture" \
    test "$(png_h "$tmp/north.png")" -gt "$(png_w "$tmp/north.png")"
rejects "--start not a pose" 2 "--start '1,2,x' is not X,Y,DEG" "$MAP" --start 1,2,x "$tmp/m.hlmap" "$tmp/x"

# ---- usage and bad input ------------------------------------------------------------
check "--help exits 0 and shows the usage" sh -c '"$1" --help | grep -q "^Usage: houghloc-map"' - "$MAP"
check "--version prints the release" sh -c '"$1" --version | grep -q "^houghloc-map [0-9]"' - "$MAP"
rejects "no arguments" 2 "expected INPUT and OUTBASE" "$MAP"
rejects "--resolution 0" 2 "--resolution '0'" "$MAP" --resolution 0 "$tmp/m.hlmap" "$tmp/x"
rejects "unknown option" 2 "unknown option '--bogus'" "$MAP" --bogus "$tmp/m.hlmap" "$tmp/x"
head -c 500 "$tmp/m.hlmap" >"$tmp/trunc.hlmap"
rejects "a truncated map file" 1 "trunc.hlmap: .*truncated" "$MAP" "$tmp/trunc.hlmap" "$tmp/x"
check "nothing written for it" test ! -e "$tmp/x.pgm" -a ! -e "$tmp/x.png"
head -c 4 "$tmp/m.hlmap" >"$tmp/short.hlmap"
rejects "a map file cut in its magic" 1 "short.hlmap" "$MAP" "$tmp/short.hlmap" "$tmp/x"
mapfile "$tmp/empty.hlmap"
rejects "an empty map" 1 "holds no vector" "$MAP" "$tmp/empty.hlmap" "$tmp/x"
rejects "a log without MAP" 1 "no MAP message" "$MAP" logs/tour.lcmlog "$tmp/x"
head -c 3000 /dev/urandom >"$tmp/junk"
rejects "random bytes" 1 "junk" "$MAP" "$tmp/junk" "$tmp/x"
rejects "a missing input" 1 "nowhere" "$MAP" "$tmp/nowhere.hlmap" "$tmp/x"
rejects "a trajectory that is not a log" 1 "tiny.hlmap" "$MAP" --trajectory "$tmp/tiny.hlmap" "$tmp/m.hlmap" "$tmp/x"
rejects "an unwritable output" 1 "cannot" "$MAP" "$tmp/m.hlmap" "$tmp/no/such/dir/x"
rejects "too fine a grid for the map" 1 "coarser --resolution" "$MAP" --resolution 0.001 "$tmp/m.hlmap" "$tmp/x"
exit $fail
