#!/bin/sh
# Integration test of the installed tree as its users meet it: `make install
# PREFIX=/usr/local` into a staging folder lays out every file with its mode; the man
# pages render with no warning; the Python types import from where Python looks; the
# profiles are what the daemon applies; each public header compiles alone; a program
# built with `pkg-config --cflags --libs houghloc` (packaging/example/localize_scan.c)
# localizes a scan to within 30 mm and 1 degree of the truth, linked static and shared;
# and `make uninstall` leaves no file. The programs must be built (`make test` builds
# everything first): make's -o keeps this test from rebuilding them.
set -u
BUILD=${BUILD:-build}
CC=${CC:-cc}
CXX=${CXX:-c++}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# PROGS, PUBLIC_HEADERS, SENSOR_PROFILES, LIB_VERSION, LIB_MAJOR, PYTHON,
# PYTHON_VERSION, expected_files, check, hl_make, mode_is, files_in:
. tests/integration/install_layout.sh

for p in $PROGS; do
    check "$BUILD/bin/$p is built" test -x "$BUILD/bin/$p"
done
check "the library's version is read from include/core/houghloc/version.h" test -n "$LIB_VERSION"
[ $fail -eq 0 ] || exit 1

root=$tmp/root
pre=$root/usr/local
libdir=$pre/lib
pydir=/usr/local/lib/python$PYTHON_VERSION/dist-packages
check "make install DESTDIR=... PREFIX=/usr/local succeeds" \
    hl_make "$tmp/install.log" install DESTDIR="$root" PREFIX=/usr/local
[ $fail -eq 0 ] || exit 1

# ---- every file, with its mode ------------------------------------------------------------
expected_files /usr/local /usr/local/lib "$pydir" /usr/local/lib/systemd/system >"$tmp/expected"
files_in "$root" >"$tmp/got"
check "install lays out exactly the expected files ($(wc -l <"$tmp/expected"))" \
    cmp -s "$tmp/expected" "$tmp/got"
cmp -s "$tmp/expected" "$tmp/got" || diff "$tmp/expected" "$tmp/got" | head -20

bad=
while read -r f; do
    [ -L "$root/$f" ] && continue
    case $f in usr/local/bin/*) want=755 ;; *) want=644 ;; esac
    mode_is "$want" "$root/$f" || bad="$bad $f"
done <"$tmp/expected"
check "programs are 0755, every other file 0644" test -z "$bad"
bad=$(find "$root" -type d ! -perm 755)
check "every folder is 0755" test -z "$bad"

check "libhoughloc.so.$LIB_MAJOR -> libhoughloc.so.$LIB_VERSION" \
    test "$(readlink "$libdir/libhoughloc.so.$LIB_MAJOR")" = "libhoughloc.so.$LIB_VERSION"
check "libhoughloc.so -> libhoughloc.so.$LIB_MAJOR" \
    test "$(readlink "$libdir/libhoughloc.so")" = "libhoughloc.so.$LIB_MAJOR"
check "the shared library's soname is libhoughloc.so.$LIB_MAJOR" \
    sh -c 'readelf -d "$1" | grep -q "(SONAME).*\[libhoughloc.so.$2\]"' - \
    "$libdir/libhoughloc.so.$LIB_VERSION" "$LIB_MAJOR"
nm -D --defined-only "$libdir/libhoughloc.so.$LIB_VERSION" | awk '{ print $3 }' >"$tmp/exported"
check "it exports the public API (hl_slam_update, hl_params_set, hl_map_vectors)" \
    sh -c 'grep -qx hl_slam_update "$1" && grep -qx hl_params_set "$1" && grep -qx hl_map_vectors "$1"' \
    - "$tmp/exported"
check "... and not the core's internal modules (stages, closure, posegraph, vgroups)" \
    sh -c '! grep -qE "^hl_(closure|posegraph|vgroups|judge|peak|loc_run|reloc_run|map_create|echo|normals|refine)" "$1"' - "$tmp/exported"
check "... at most 45 functions, each documented in docs/design/api.md" sh -c '
    test "$(wc -l <"$1")" -le 45 || exit 1
    while read -r f; do grep -q "\`$f\`" docs/design/api.md || { echo "  $f"; exit 1; }; done <"$1"' \
    - "$tmp/exported"
check "... nor anything but hl_ names" sh -c '! grep -qv "^hl_" "$1"' - "$tmp/exported"
# Exactly the functions the public headers mark HL_API (houghloc/export.h): the core is
# compiled with hidden visibility, so nothing else can leave the library.
sed -n 's/^HL_API .*\<\(hl_[a-z0-9_]*\) *(.*/\1/p' include/core/houghloc/*.h | sort -u >"$tmp/marked"
sort -u "$tmp/exported" >"$tmp/exported.sorted"
check "... exactly the $(wc -l <"$tmp/marked") functions the public headers mark HL_API" \
    cmp -s "$tmp/marked" "$tmp/exported.sorted"
cmp -s "$tmp/marked" "$tmp/exported.sorted" || diff "$tmp/marked" "$tmp/exported.sorted" | head

# ---- installed copies are the sources -------------------------------------------------------
check "installed houghlocd is the built one" cmp -s "$BUILD/bin/houghlocd" "$pre/bin/houghlocd"
check "installed houghloc-sim is the built one" cmp -s "$BUILD/bin/houghloc-sim" "$pre/bin/houghloc-sim"
bad=
for f in lcmtypes/houghloc_*.lcm; do
    cmp -s "$f" "$pre/share/houghloc/lcmtypes/${f##*/}" || bad="$bad $f"
done
check "the LCM type definitions are lcmtypes/*.lcm" test -z "$bad"
bad=
for h in $PUBLIC_HEADERS; do cmp -s "include/core/houghloc/$h" "$pre/include/houghloc/$h" || bad="$bad $h"; done
check "the headers are include/core/houghloc's" test -z "$bad"

# ---- man pages ------------------------------------------------------------------------------
bad=
for p in $PROGS; do
    [ -f "$pre/share/man/man1/$p.1.gz" ] || [ -f "$pre/share/man/man8/$p.8.gz" ] || bad="$bad $p"
done
[ -f "$pre/share/man/man5/houghlocd.conf.5.gz" ] || bad="$bad houghlocd.conf(5)"
check "every installed program has a man page, and the configuration file too" test -z "$bad"
[ -n "$bad" ] && echo "  missing:$bad"
bad=
for m in man/*.[158]; do
    [ -e "$m" ] || continue
    gzip -9n <"$m" | cmp -s - "$pre/share/man/man${m##*.}/${m##*/}.gz" || bad="$bad $m"
done
check "the pages are man/*.[158], gzip -9n (no name, no time: the same bytes every time)" \
    test -z "$bad"
if command -v man >/dev/null 2>&1 && command -v groff >/dev/null 2>&1; then
    bad=
    for page in "$pre"/share/man/man*/*.gz; do
        [ -e "$page" ] || continue
        # --warnings=w: every groff warning; any line on stderr is a failure.
        man --warnings=w -E UTF-8 -l "$page" >"$tmp/page" 2>"$tmp/page.err"
        rc=$?
        if [ $rc -ne 0 ] || [ -s "$tmp/page.err" ] || [ ! -s "$tmp/page" ]; then
            bad="$bad ${page##*/}"
            sed 's/^/  /' "$tmp/page.err" | head -5
        fi
    done
    check "man -l renders every installed page with no warning" test -z "$bad"
else
    echo "FAIL: man or groff is missing: apt-get install man-db groff-base"
    fail=1
fi

# ---- sensor profiles ------------------------------------------------------------------------
bad=
for n in $SENSOR_PROFILES; do
    f=$pre/share/houghloc/profiles/$n.conf
    "$BUILD/bin/houghlocd" --print-profile "$n" >"$tmp/profile" 2>&1 && cmp -s "$tmp/profile" "$f" ||
        bad="$bad $n"
done
check "the profiles are what houghlocd --print-profile NAME prints" test -z "$bad"
bad=
for n in sonar-continuous laser paper; do   # sonar-stops is the compiled-in defaults: no key
    grep -qE '^[a-z_]+ *= *[^ ]' "$pre/share/houghloc/profiles/$n.conf" || bad="$bad $n"
done
check "sonar-continuous, laser and paper set keys" test -z "$bad"
bad=
for n in $SENSOR_PROFILES; do
    "$BUILD/bin/houghlocd" --config "$pre/share/houghloc/profiles/$n.conf" --print-config \
        >/dev/null 2>"$tmp/err" || { bad="$bad $n"; head -3 "$tmp/err"; }
done
check "each installed profile loads as a configuration file (houghlocd --config)" test -z "$bad"

# ---- Python types ---------------------------------------------------------------------------
check "the Python folder $pydir is on $PYTHON's sys.path" \
    "$PYTHON" -c 'import sys; sys.exit(sys.argv[1] not in sys.path)' "$pydir"
check "python3 -c 'import houghloc' with PYTHONPATH=\$DESTDIR$pydir (and a pose encodes)" \
    env PYTHONPATH="$root$pydir" PYTHONDONTWRITEBYTECODE=1 "$PYTHON" -c '
import sys, houghloc
from houghloc import pose_t
assert houghloc.__file__.startswith(sys.argv[1]), houghloc.__file__
assert len(pose_t().encode()) > 8' "$root"

# ---- public headers -------------------------------------------------------------------------
bad=
for h in $PUBLIC_HEADERS; do
    # Only the installed folder on the include path; a declaration so that version.h (only
    # a macro) is not an empty translation unit.
    printf '#include <houghloc/%s>\ntypedef int hl_test_unit;\n' "$h" >"$tmp/one.c"
    "$CC" -std=c11 -Wall -Wextra -Werror -pedantic -fsyntax-only -I"$pre/include" "$tmp/one.c" ||
        bad="$bad $h(C)"
    "$CXX" -std=c++17 -Wall -Wextra -Werror -pedantic -fsyntax-only -I"$pre/include" -x c++ \
        "$tmp/one.c" || bad="$bad $h(C++)"
done
check "each public header compiles alone (C11 and C++17) against the installed folder" \
    test -z "$bad"
[ -n "$bad" ] && echo "  failed:$bad"
bad=
for h in $PUBLIC_HEADERS; do
    for inc in $(sed -n 's|^#include "houghloc/\([^"]*\)".*|\1|p' "$pre/include/houghloc/$h"); do
        case " $PUBLIC_HEADERS " in *" $inc "*) ;; *) bad="$bad $h:$inc" ;; esac
    done
done
check "no public header includes a header that is not installed (robot link, bus)" test -z "$bad"
[ -n "$bad" ] && echo "  includes:$bad"

# ---- a program of one's own, through pkg-config -----------------------------------------------
pc() { PKG_CONFIG_PATH=$libdir/pkgconfig PKG_CONFIG_SYSROOT_DIR=$root pkg-config "$@"; }
check "pkg-config --modversion houghloc is $LIB_VERSION" test "$(pc --modversion houghloc)" = "$LIB_VERSION"
check "pkg-config --cflags --libs houghloc names the installed folders" \
    test "$(pc --cflags --libs houghloc | xargs)" = "-I$pre/include -L$libdir -lhoughloc"
check "... as --define-prefix does" test "$(PKG_CONFIG_PATH=$libdir/pkgconfig \
    pkg-config --define-prefix --cflags --libs houghloc | xargs)" = "-I$pre/include -L$libdir -lhoughloc"
example=packaging/example/localize_scan.c
# shellcheck disable=SC2046
check "the example builds against the shared library" \
    "$CC" -std=c11 -Wall -Wextra -Werror -o "$tmp/shared" "$example" $(pc --cflags --libs houghloc)
# The static archive sits beside the shared library: -l:libhoughloc.a picks it, and
# --static adds what it needs itself (-lm).
# shellcheck disable=SC2046
check "... and against the static library" \
    "$CC" -std=c11 -Wall -Wextra -Werror -o "$tmp/static" "$example" \
    $(pc --cflags --static --libs houghloc | sed 's/-lhoughloc\b/-l:libhoughloc.a/')
check "the shared build needs libhoughloc.so.$LIB_MAJOR" \
    sh -c 'readelf -d "$1" | grep -q "(NEEDED).*\[libhoughloc.so.$2\]"' - "$tmp/shared" "$LIB_MAJOR"
check "the static build does not" sh -c '! readelf -d "$1" | grep -q "NEEDED.*libhoughloc"' - "$tmp/static"

near() { # near OUTPUT X Y HEADING: the printed pose within 30 mm and 1 degree of the truth
    echo "$1" | awk -v x="$2" -v y="$3" -v h="$4" '
        /^pose / { for (i = 2; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
                   dh = v["heading_deg"] - h; dh -= 360 * int(dh / 360 + (dh >= 0 ? 0.5 : -0.5))
                   dx = v["x_mm"] - x; dy = v["y_mm"] - y
                   ok = (dx * dx <= 900 && dy * dy <= 900 && dh * dh <= 1); found = 1 }
        END { exit !(found && ok) }'
}
for truth in "400 -250 12" "-1200 900 -100" "1300 1300 179.5" "0 0 -45"; do
    # shellcheck disable=SC2086
    out=$(LD_LIBRARY_PATH=$libdir "$tmp/shared" $truth 2>&1)
    # shellcheck disable=SC2086
    check "shared: localizes a scan taken at $truth: $out" near "$out" $truth
    # shellcheck disable=SC2086
    out=$(env -u LD_LIBRARY_PATH "$tmp/static" $truth 2>&1)
    # shellcheck disable=SC2086
    check "static: localizes a scan taken at $truth: $out" near "$out" $truth
done
check "the example refuses a pose outside the room, in one line" \
    sh -c '"$1" 1600 0 0 2>"$2"; [ $? -eq 2 ] && [ "$(wc -l <"$2")" -eq 1 ]' - "$tmp/static" "$tmp/err"

# ---- uninstall --------------------------------------------------------------------------------
check "make uninstall DESTDIR=... PREFIX=/usr/local succeeds" \
    hl_make "$tmp/uninstall.log" uninstall DESTDIR="$root" PREFIX=/usr/local
left=$(files_in "$root")
check "uninstall leaves no file nor link" test -z "$left"
[ -n "$left" ] && echo "$left" | head -10 | sed 's/^/  left: /'
check "... nor houghloc's own folders" sh -c '
    for d in usr/local/share/houghloc usr/local/include/houghloc etc/houghloc \
        "usr/local/lib/python$2/dist-packages/houghloc"; do
        [ ! -e "$1/$d" ] || { echo "  left: $d"; exit 1; }
    done' - "$root" "$PYTHON_VERSION"

exit $fail
