#!/bin/sh
# Integration test of the layering the build enforces (docs/design/layers.md), in what
# the include paths alone cannot catch: no source reaches another folder by a relative
# include ("../"), which would bypass the per-layer include paths; and `make test` builds
# nothing of the laboratory (tools/lab: `make lab-test` tests it), checked on a dry run
# of `make test` into an empty build folder.
set -u
BUILD=${BUILD:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
# A make inside make test: not the outer make's jobserver.
unset MAKEFLAGS MFLAGS MAKELEVEL

grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*["<]\.\./' \
    --include='*.c' --include='*.h' --include='*.cpp' --include='*.hpp' \
    src include tools tests packaging >"$tmp/relative"
check "no #include by a relative path (use the folder's include path in its .mk)" \
    test ! -s "$tmp/relative"
sed 's/^/  /' "$tmp/relative"

make --no-print-directory -n BUILD="$tmp/build" test >"$tmp/dry" 2>&1
rc=$?
check "make -n test runs (exit $rc)" test $rc -eq 0
[ $rc -eq 0 ] || tail -n 5 "$tmp/dry"
check "make test compiles the product's files (a dry run names src/daemon/main.c)" \
    grep -q 'src/daemon/main\.c' "$tmp/dry"
grep 'tools/lab' "$tmp/dry" >"$tmp/lab"
check "make test builds and runs nothing under tools/lab" test ! -s "$tmp/lab"
head -n 5 "$tmp/lab" | sed 's/^/  /'
exit $fail
