# install_layout.sh - what `make install` lays out, and the helpers of the tests that
# check it (sourced, POSIX sh, by test_packaging.sh and test_install.sh after they set
# BUILD and tmp). The expected layout is written out here, independently of
# packaging/*.mk, so that a file the makefiles forget or add shows up as a difference.

PROGS="houghlocd houghloc-goto houghloc-ctl houghloc-console houghloc-sim houghloc-map \
houghloc-import-carmen houghloc-eval"
# The core's public headers: those of the robot link and the bus stay out (they need
# libserialport, LCM, libsodium).
PUBLIC_HEADERS=$(cd include/core/houghloc && echo *.h)
SENSOR_PROFILES="sonar-stops sonar-continuous laser paper"
LIB_VERSION=$(sed -n 's/^#define HL_VERSION "\([0-9][0-9.]*\)"$/\1/p' include/core/houghloc/version.h)
LIB_MAJOR=${LIB_VERSION%%.*}
# The python3 that make install asks for its version: Debian's, not a pyenv's first on PATH.
PYTHON=python3
[ -x /usr/bin/python3 ] && PYTHON=/usr/bin/python3
PYTHON_VERSION=$("$PYTHON" -c 'import sys; print("%d.%d" % sys.version_info[:2])')

have_java=
if command -v javac >/dev/null 2>&1 && command -v jar >/dev/null 2>&1 &&
    [ -f /usr/share/java/lcm.jar ]; then
    have_java=yes
fi

fail=0
check() {   # check DESCRIPTION COMMAND...: the command must succeed
    desc=$1; shift
    if "$@"; then echo "ok: $desc"; else echo "FAIL: $desc"; fail=1; fi
}
# make's -o for each program: the install must not rebuild what make test built
keep_built() { for p in $PROGS; do printf ' -o %s' "$1/bin/$p"; done; }
hl_make() { # hl_make LOG TARGET VAR=VALUE...: make quietly, the output in LOG
    log=$1; shift
    # shellcheck disable=SC2046
    make --no-print-directory -s BUILD="$BUILD" $(keep_built "$BUILD") "$@" >"$log" 2>&1
    rc=$?
    [ $rc -eq 0 ] || { echo "make $*:"; head -20 "$log"; }
    return $rc
}
mode_is() { # mode_is MODE FILE
    [ "$(stat -c %a "$2" 2>/dev/null)" = "$1" ] || { echo "  $2: mode $(stat -c %a "$2" 2>&1)"; return 1; }
}
# Everything but folders (symbolic links too), relative to the root given, sorted.
files_in() { (cd "$1" && find . ! -type d | sed 's|^\./||' | sort); }

# expected_files PREFIX LIBDIR PYTHONDIR UNITDIR: every file and link `make install`
# lays out with those folders, relative to DESTDIR, sorted.
expected_files() {
    p=${1#/}; lib=${2#/}; py=${3#/}; unit=${4#/}
    {
        echo etc/houghloc/houghlocd.conf
        echo "$unit/houghlocd.service"
        for x in $PROGS; do echo "$p/bin/$x"; done
        for m in man/*.[158]; do
            [ -e "$m" ] && echo "$p/share/man/man${m##*.}/${m##*/}.gz"
        done
        for f in lcmtypes/houghloc_*.lcm; do echo "$p/share/houghloc/lcmtypes/${f##*/}"; done
        for n in $SENSOR_PROFILES; do echo "$p/share/houghloc/profiles/$n.conf"; done
        echo "$py/houghloc/__init__.py"
        for f in lcmtypes/houghloc_*.lcm; do
            echo "$py/houghloc/$(basename "$f" .lcm | sed 's/^houghloc_//').py"
        done
        if [ -n "$have_java" ]; then echo "$p/share/houghloc/java/houghloc_lcmtypes.jar"; fi
        echo "$lib/libhoughloc.a"
        echo "$lib/libhoughloc.so.$LIB_VERSION"
        echo "$lib/libhoughloc.so.$LIB_MAJOR"
        echo "$lib/libhoughloc.so"
        echo "$lib/pkgconfig/houghloc.pc"
        for h in $PUBLIC_HEADERS; do echo "$p/include/houghloc/$h"; done
        for f in README.md LICENSE CHANGELOG.md; do echo "$p/share/doc/houghloc/$f"; done
        for f in docs/manual/*.md docs/design/*.md docs/results/*.md docs/results/img/*.png; do
            echo "$p/share/doc/houghloc/${f#docs/}"
        done
    } | sort
}
