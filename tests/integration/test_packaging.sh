#!/bin/sh
# Integration test of `make install` / `make uninstall` (packaging/packaging.mk) into a
# staging folder, as a distribution package build does it: the files land where
# docs/manual/service.md says with the right modes, the unit names the installed programs and
# passes systemd-analyze (verify, and a security exposure of at most 2.0), a changed
# configuration survives a second install and an uninstall, uninstall removes the rest,
# and nothing needs root. The programs must be built (`make test` builds everything first):
# make's -o keeps this test from rebuilding them. test_install.sh checks the installed
# tree of PREFIX=/usr/local as its users meet it.
set -u
BUILD=${BUILD:-build}
CONF_SRC=${CONF_SRC:-packaging/houghlocd.conf}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# PROGS, expected_files, check, hl_make, mode_is, files_in, have_java:
. tests/integration/install_layout.sh
MULTIARCH=$(${CC:-cc} -print-multiarch 2>/dev/null)

for p in $PROGS; do
    check "$BUILD/bin/$p is built" test -x "$BUILD/bin/$p"
done
[ $fail -eq 0 ] || exit 1

# ---- install with PREFIX=/usr --------------------------------------------------------
root=$tmp/root
check "make install DESTDIR=... PREFIX=/usr succeeds" \
    hl_make "$tmp/install.log" install DESTDIR="$root" PREFIX=/usr

expected_files /usr "/usr/lib${MULTIARCH:+/$MULTIARCH}" /usr/lib/python3/dist-packages \
    /lib/systemd/system >"$tmp/expected"
files_in "$root" >"$tmp/got"
check "install lays out exactly the expected files" cmp -s "$tmp/expected" "$tmp/got"
cmp -s "$tmp/expected" "$tmp/got" || diff "$tmp/expected" "$tmp/got" | head -20

check "programs are 0755" mode_is 755 "$root/usr/bin/houghlocd"
check "houghloc-goto is 0755" mode_is 755 "$root/usr/bin/houghloc-goto"
check "houghloc-ctl is 0755" mode_is 755 "$root/usr/bin/houghloc-ctl"
check "houghloc-map is 0755" mode_is 755 "$root/usr/bin/houghloc-map"
check "the unit is 0644" mode_is 644 "$root/lib/systemd/system/houghlocd.service"
check "the configuration is 0644" mode_is 644 "$root/etc/houghloc/houghlocd.conf"
check "the Python types are 0644" mode_is 644 "$root/usr/lib/python3/dist-packages/houghloc/pose_t.py"
check "PREFIX=/usr: the library in the multiarch folder /usr/lib/$MULTIARCH" \
    test -f "$root/usr/lib/$MULTIARCH/libhoughloc.so.$LIB_VERSION"
check "PREFIX=/usr: houghloc.pc names libdir \${prefix}/lib/$MULTIARCH" \
    grep -qx "libdir=\${prefix}/lib/$MULTIARCH" "$root/usr/lib/$MULTIARCH/pkgconfig/houghloc.pc"
if [ -n "$have_java" ]; then
    check "the jar is 0644" mode_is 644 "$root/usr/share/houghloc/java/houghloc_lcmtypes.jar"
fi
check "installed houghlocd is the built one" cmp -s "$BUILD/bin/houghlocd" "$root/usr/bin/houghlocd"
check "installed configuration is $CONF_SRC" cmp -s "$CONF_SRC" "$root/etc/houghloc/houghlocd.conf"

unit=$root/lib/systemd/system/houghlocd.service
check "the unit has no @...@ left" sh -c '! grep -q "@[A-Z_]*@" "$1"' - "$unit"
check "the unit runs /usr/bin/houghlocd with the /etc configuration" \
    grep -qx 'ExecStart=/usr/bin/houghlocd --config /etc/houghloc/houghlocd.conf' "$unit"
check "the unit loads the key from /etc/houghloc/key" \
    grep -qx 'LoadCredential=key:/etc/houghloc/key' "$unit"

# systemd-analyze verify wants the program to exist: check a copy that names the staged one.
if command -v systemd-analyze >/dev/null 2>&1; then
    sed "s|^ExecStart=/usr/bin/|ExecStart=$root/usr/bin/|" "$unit" >"$tmp/houghlocd.service"
    systemd-analyze verify "$tmp/houghlocd.service" >"$tmp/verify" 2>&1
    rc=$?
    # verify exits 0 on unknown keys and bad values too: any message at all is a failure.
    check "systemd-analyze verify: no complaint" \
        sh -c '[ "$1" -eq 0 ] && [ ! -s "$2" ]' - "$rc" "$tmp/verify"
    cat "$tmp/verify"
    if systemd-analyze security --offline=yes "$unit" >"$tmp/security" 2>&1; then
        score=$(sed -n 's/.*Overall exposure level for houghlocd.service: \([0-9.]*\).*/\1/p' "$tmp/security")
        echo "  systemd-analyze security: exposure $score"
        check "security exposure is at most 2.0" \
            awk -v s="$score" 'BEGIN { exit !(s != "" && s + 0 <= 2.0) }'
    else
        echo "note: systemd-analyze security --offline=yes is not supported here; not scored"
    fi
else
    echo "note: systemd-analyze is missing; the unit is not verified"
fi

# ---- PREFIX=/usr/local: the unit follows the prefix ------------------------------------
check "make install PREFIX=/usr/local succeeds" \
    hl_make "$tmp/local.log" install DESTDIR="$tmp/local" PREFIX=/usr/local
check "PREFIX=/usr/local: unit in /usr/local/lib/systemd/system runs /usr/local/bin/houghlocd" \
    grep -qx 'ExecStart=/usr/local/bin/houghlocd --config /etc/houghloc/houghlocd.conf' \
    "$tmp/local/usr/local/lib/systemd/system/houghlocd.service"
check "PREFIX=/usr/local: programs in /usr/local/bin" test -x "$tmp/local/usr/local/bin/houghlocd"

# ---- a changed configuration is the administrator's ------------------------------------
conf=$root/etc/houghloc/houghlocd.conf
echo "# changed by the administrator" >>"$conf"
cp "$conf" "$tmp/changed.conf"
check "a second install succeeds" hl_make "$tmp/install2.log" install DESTDIR="$root" PREFIX=/usr
check "a second install keeps the changed configuration" cmp -s "$tmp/changed.conf" "$conf"
check "... and puts the new default beside it as .dist" cmp -s "$CONF_SRC" "$conf.dist"

check "make uninstall succeeds" hl_make "$tmp/uninstall.log" uninstall DESTDIR="$root" PREFIX=/usr
check "uninstall keeps only the changed configuration" \
    test "$(files_in "$root")" = etc/houghloc/houghlocd.conf
check "... unchanged" cmp -s "$tmp/changed.conf" "$conf"

# ---- an unchanged installation goes away entirely --------------------------------------
hl_make "$tmp/uninstall2.log" uninstall DESTDIR="$tmp/local" PREFIX=/usr/local
check "uninstall of an unchanged installation leaves no file" test -z "$(files_in "$tmp/local")"
check "... nor its own folders" \
    sh -c '[ ! -e "$1/usr/local/share/houghloc" ] && [ ! -e "$1/etc/houghloc" ]' - "$tmp/local"

# ---- nothing needs root ------------------------------------------------------------------
if [ "$(id -u)" = 0 ]; then
    if command -v setpriv >/dev/null 2>&1 && id nobody >/dev/null 2>&1 &&
        setpriv --reuid=nobody --regid="$(id -g nobody)" --clear-groups test -r Makefile; then
        chmod 755 "$tmp"
        mkdir "$tmp/user"
        chown nobody "$tmp/user"
        check "make install works as an ordinary user (nobody)" \
            setpriv --reuid=nobody --regid="$(id -g nobody)" --clear-groups \
            sh -c 'make --no-print-directory -s BUILD="$1" $3 install DESTDIR="$2" \
                PREFIX=/usr >"$2.log" 2>&1' \
            - "$BUILD" "$tmp/user/root" "$(keep_built "$BUILD")"
        [ -f "$tmp/user/root/usr/bin/houghlocd" ] || head -20 "$tmp/user/root.log" 2>/dev/null
        check "... and installs the programs" test -x "$tmp/user/root/usr/bin/houghlocd"
    else
        echo "note: cannot run as nobody here; the install as an ordinary user is not checked"
    fi
else
    echo "note: running as an ordinary user: the installs above needed no root"
fi

exit $fail
