#!/bin/sh
# Runs each integration test script given as an argument (each starts real processes on
# loopback and exits non-zero on failure) and prints one summary line.
set -u
pass=0
fail=0
failed=""
for t in "$@"; do
    echo "== $t"
    if sh "$t"; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        failed="$failed $t"
    fi
done
[ $# -eq 0 ] && exit 0
echo
echo "integration: $pass passed, $fail failed"
[ -n "$failed" ] && echo "failed:$failed"
[ "$fail" -eq 0 ]
