#!/bin/sh
# Runs each cmocka test program given as an argument and prints one summary line.
# Exits non-zero if any program fails or none was given.
set -u
pass=0
fail=0
failed=""
for t in "$@"; do
    if "$t"; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        failed="$failed $(basename "$t")"
    fi
done
echo
echo "unit: $pass passed, $fail failed"
[ -n "$failed" ] && echo "failed:$failed"
[ $# -gt 0 ] && [ "$fail" -eq 0 ]
