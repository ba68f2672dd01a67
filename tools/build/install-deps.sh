#!/bin/sh
# Installs the Debian packages houghloc needs, if any are missing, and says first what it
# installs and why, one line per group.
#
#   sh tools/build/install-deps.sh                    the build's and the tests' (make deps)
#   sh tools/build/install-deps.sh --for WHY PKG...   the packages given, for WHY (make fuzz
#                                                     and make trials add theirs this way)
#
# As root it runs apt-get; otherwise it prints the exact command and fails, so that
# `make test` / `make demo` never half-build on a machine without the libraries.
set -eu

# group NAME WHY PACKAGES: one group of packages and the reason it is needed.
groups=""
group() {
    groups="$groups
$1|$2|$3"
}

if [ "${1:-}" = "--for" ]; then
    [ $# -ge 3 ] || { echo "install-deps.sh: --for wants a reason and at least one package" >&2; exit 2; }
    why=$2; shift 2
    group asked "$why" "$*"
elif [ $# -gt 0 ]; then
    group asked "asked for on the command line" "$*"
else
    group build "the compiler and build tools" "make gcc g++ pkg-config"
    group libraries "the libraries houghloc links (LCM, GLib, libserialport, Eigen, cairo, inih, libsodium, libsystemd, zlib, libmicrohttpd)" \
        "liblcm-dev liblcm-bin libglib2.0-dev libserialport-dev libeigen3-dev libcairo2-dev libinih-dev libsodium-dev libsystemd-dev zlib1g-dev libmicrohttpd-dev"
    group tests "the tests (cmocka for the unit tests; python3, man-db and groff-base for integration tests)" \
        "libcmocka-dev python3 man-db groff-base"
    group browser "the console's browser test (tests/console/browser_test.sh)" \
        "chromium chromium-driver"
fi

installed() {
    dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}

# Which packages are missing, and one line per group that has any.
missing=""
plan=""
old_ifs=$IFS
IFS='
'
for g in $groups; do
    [ -n "$g" ] || continue
    why=$(echo "$g" | cut -d'|' -f2)
    pkgs=$(echo "$g" | cut -d'|' -f3)
    IFS=$old_ifs
    lacking=""
    for p in $pkgs; do
        installed "$p" || lacking="$lacking $p"
    done
    if [ -n "$lacking" ]; then
        missing="$missing$lacking"
        plan="$plan
houghloc: installing packages for $why:$lacking"
    fi
    IFS='
'
done
IFS=$old_ifs
[ -z "$missing" ] && exit 0

if [ "$(id -u)" = 0 ]; then
    echo "${plan#?}" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # shellcheck disable=SC2086
    apt-get install -y -qq --no-install-recommends $missing
else
    echo "${plan#?}" | sed 's/^houghloc: installing/houghloc: missing/' >&2
    echo "houghloc: run this, then try again:" >&2
    echo "    sudo apt-get install -y$missing" >&2
    exit 1
fi
