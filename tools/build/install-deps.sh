#!/bin/sh
# Installs the Debian packages houghloc needs, if any are missing: those of the build
# and the tests, or the ones given as arguments (make fuzz, make trials add theirs).
# As root it runs apt-get; otherwise it prints the exact command and fails, so that
# `make test` / `make demo` never half-build on a machine without the libraries.
set -eu

PKGS="make gcc g++ pkg-config liblcm-dev liblcm-bin libglib2.0-dev libserialport-dev \
libcmocka-dev libeigen3-dev libcairo2-dev libinih-dev libsodium-dev libsystemd-dev zlib1g-dev \
libmicrohttpd-dev"
[ $# -gt 0 ] && PKGS="$*"

missing=""
for p in $PKGS; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing="$missing $p"
    fi
done
[ -z "$missing" ] && exit 0

echo "houghloc: missing Debian packages:$missing" >&2
if [ "$(id -u)" = 0 ]; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # shellcheck disable=SC2086
    apt-get install -y -qq --no-install-recommends $missing
else
    echo "houghloc: run this, then try again:" >&2
    echo "    sudo apt-get install -y$missing" >&2
    exit 1
fi
