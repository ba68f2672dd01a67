# lib.sh - helpers the integration scripts share (sourced, POSIX sh).
# Each script sets BIN and tmp before sourcing, and reads $fail at its end.
fail=0
check() {   # check DESCRIPTION COMMAND...: the command must succeed
    desc=$1; shift
    if "$@"; then echo "ok: $desc"; else echo "FAIL: $desc"; fail=1; fi
}
rejects() { # rejects DESCRIPTION EXIT_CODE EXPECTED_TEXT COMMAND...: that exit code, and
            # one line on stderr containing the text
    desc=$1; code=$2; want=$3; shift 3
    "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ $rc -eq "$code" ] && [ "$(grep -vc '^<[0-7]>' "$tmp/err")" -eq 1 ] &&
        grep -v '^<[0-7]>' "$tmp/err" | grep -q -- "$want"; then
        echo "ok: $desc"
    else
        echo "FAIL: $desc (exit $rc, wanted $code): $(head -c 400 "$tmp/err")"
        fail=1
    fi
}
exits() {   # exits DESCRIPTION CODE EXPECTED_TEXT COMMAND...: that exit code, one line on
            # stderr containing the text, nothing on stdout
    desc=$1; want_rc=$2; want=$3; shift 3
    "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ $rc -eq "$want_rc" ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && [ ! -s "$tmp/out" ] &&
        grep -q -F -- "$want" "$tmp/err"; then
        echo "ok: $desc"
    else
        echo "FAIL: $desc (exit $rc, want $want_rc): $(head -c 300 "$tmp/err")"
        fail=1
    fi
}
