#!/bin/sh
# Integration test of houghloc-console from the command line and over HTTP with curl:
# --help, --version and bad options; the loopback default (bound to 127.0.0.1 only, Host
# checked, every route behind the token: the page, the event stream and the POSTs, the
# page itself carrying none; ?token= exchanged for an HttpOnly SameSite=Strict cookie; a
# POST by cookie only with the console's own Origin); --token-out; the open mode
# (--listen elsewhere, any Host); 401, 403, 404, 405 and 400 answers that
# publish nothing, while one good POST publishes exactly one DESTINATION (lcm-logger
# records it), signed with --key; the event stream; no CPU use when idle; clean stops;
# --ground-truth draws the simulator's true poses in the daemon's map frame (--start).
set -u
BIN=${BUILD:-build}/bin
C=$BIN/houghloc-console
tmp=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill -9 $p 2>/dev/null; done; rm -rf "$tmp"' EXIT
. tests/integration/lib.sh
n=$(( $$ % 300 ))
URL="udpm://239.255.76.67:$(( 7900 + n ))?ttl=0"
PORT=$(( 19200 + n ))
OPORT=$(( 19600 + n ))

# ---- the command line ---------------------------------------------------------------------
"$C" --help >"$tmp/help" 2>"$tmp/err"
check "--help exits 0" test $? -eq 0
check "--help prints the usage line" grep -q "^Usage: houghloc-console \[options\]$" "$tmp/help"
check "--help names every option" sh -c 'for o in --lcm-url --prefix --key --listen --token-file --token-out --ground-truth --start --help --version; do grep -q -- "  $o" "$1" || exit 1; done' - "$tmp/help"
check "--help names the default address" grep -q "default 127.0.0.1:8047" "$tmp/help"
check "--help writes nothing on stderr" test ! -s "$tmp/err"
check "--version prints the name" sh -c "$C --version | grep -q '^houghloc-console [0-9]'"
exits "unknown option" 2 'unknown option "--bogus"' "$C" --bogus
exits "--timeout is not the console's" 2 'unknown option "--timeout"' "$C" --timeout 3
exits "--deadline is not the console's" 2 'unknown option "--deadline"' "$C" --deadline 3
exits "a stray argument" 2 'unexpected argument "extra"' "$C" extra
exits "--listen without a value" 2 "--listen needs a value" "$C" --listen
exits "--listen followed by an option" 2 "--listen needs a value" "$C" --listen --ground-truth
exits "--listen without a port" 2 '--listen "127.0.0.1": give ADDR:PORT' "$C" --listen 127.0.0.1
exits "--listen port 0" 2 '--listen "127.0.0.1:0"' "$C" --listen=127.0.0.1:0
exits "--listen port 65536" 2 '--listen "127.0.0.1:65536"' "$C" --listen 127.0.0.1:65536
exits "--listen a host name" 2 '--listen "robot.example:80"' "$C" --listen robot.example:80
exits "--token-file empty" 2 "--token-file is empty" "$C" --token-file=
exits "--token-out with --token-file" 2 "does not go with --token-file" "$C" --token-out "$tmp/x" --token-file "$tmp/y"
exits "bad --prefix" 2 '--prefix "a b"' "$C" --prefix 'a b'
exits "empty --lcm-url" 2 "--lcm-url is empty" "$C" --lcm-url=
exits "usage errors point at --help" 2 "try houghloc-console --help" "$C" --bogus
(umask 077; printf '%064x\n' 7 >"$tmp/key"; printf 'console-token-0123456789\n' >"$tmp/token")
cp "$tmp/token" "$tmp/open.token"; chmod 644 "$tmp/open.token"
cp "$tmp/key" "$tmp/open.key"; chmod 644 "$tmp/open.key"
printf 'short\n' >"$tmp/bad.token"; chmod 600 "$tmp/bad.token"
exits "token file open to others" 1 "chmod 600" "$C" --lcm-url "$URL" --token-file "$tmp/open.token"
exits "token file without a token" 1 "holds no token" "$C" --lcm-url "$URL" --token-file "$tmp/bad.token"
exits "missing token file" 1 "No such file" "$C" --lcm-url "$URL" --token-file "$tmp/none"
exits "key file open to others" 1 "chmod 600 $tmp/open.key" "$C" --lcm-url "$URL" --key "$tmp/open.key"

# ---- loopback (the default mode) ----------------------------------------------------------
lcm-logger -q -f -c 'DESTINATION' --lcm-url="$URL" "$tmp/dest.lcmlog" >/dev/null 2>&1 &
logger=$!; pids="$pids $logger"
"$C" --lcm-url "$URL" --listen "127.0.0.1:$PORT" --key "$tmp/key" 2>"$tmp/c.err" &
console=$!; pids="$pids $console"
w=0; while ! grep -q "serving" "$tmp/c.err" && [ $w -lt 50 ]; do sleep 0.1; w=$((w + 1)); done
TOKEN=$(sed -n 's/.*serving http:[^ ]*?token=\([0-9a-f]*\) .*/\1/p' "$tmp/c.err")
check "says where it serves with a fresh token, signed" sh -c "echo '$TOKEN' | grep -Eqx '[0-9a-f]{32}' && grep -qF 'houghloc-console: serving http://127.0.0.1:$PORT/?token=$TOKEN on LCM $URL, destinations signed' $tmp/c.err"
exits "a port in use is refused" 1 "cannot serve on 127.0.0.1:$PORT" "$C" --lcm-url "$URL" --listen "127.0.0.1:$PORT"
check "bound to the loopback address only" sh -c "ss -ltn | grep -q ' 127.0.0.1:$PORT ' && ! ss -ltn | grep -q ' 0.0.0.0:$PORT '"
B="http://127.0.0.1:$PORT"
A="Authorization: Bearer $TOKEN"
code() { curl -s --max-time 5 -o "$tmp/body" -w '%{http_code}' "$@"; }
check "GET / without a token: 401" test "$(code "$B/")" = 401
check "... says why in one line" sh -c "grep -q '\"error\":\"sign in first' $tmp/body && test \$(wc -l <$tmp/body) -eq 1"
check "the event stream without a token: 401" test "$(code "$B/events")" = 401
check "the event stream with a wrong token: 401" test "$(code -H "Authorization: Bearer ${TOKEN}0" "$B/events")" = 401
check "the page with a wrong ?token=: 401" test "$(code "$B/?token=${TOKEN}0")" = 401
curl -s -D "$tmp/headers" -o /dev/null "$B/?token=$TOKEN"
check "?token= is exchanged for a cookie: 303 to /" sh -c "head -n 1 $tmp/headers | grep -q ' 303' && grep -qi '^Location: /.\?\$' $tmp/headers"
check "... HttpOnly, SameSite=Strict, named by the port, not the token" sh -c "grep -qi '^Set-Cookie: houghloc_$PORT=[0-9a-f]\{32\}; Path=/; HttpOnly; SameSite=Strict' $tmp/headers && ! grep -i '^Set-Cookie' $tmp/headers | grep -q $TOKEN"
check "the page after the exchange: 200" test "$(code -c "$tmp/jar" -b "$tmp/jar" -L "$B/?token=$TOKEN")" = 200
check "the page is HTML with its scripts inline" grep -q '<canvas id="map">' "$tmp/body"
check "the page loads nothing from elsewhere" sh -c "! grep -Eqi '(src|href)=|https?://|@import|url\(' $tmp/body"
check "the page carries no token" sh -c "! grep -q '$TOKEN' $tmp/body && ! grep -q 'HOUGHLOC_TOKEN' $tmp/body"
check "the page with the cookie: 200" test "$(code -b "$tmp/jar" "$B/")" = 200
check "the page with the bearer token: 200" test "$(code -H "$A" "$B/")" = 200
curl -s -D "$tmp/headers" -o /dev/null -H "$A" "$B/"
check "the page forbids other origins' scripts and framing" grep -qi "^Content-Security-Policy: default-src 'none'.*frame-ancestors 'none'" "$tmp/headers"
check "no CORS grant" sh -c "! grep -qi '^Access-Control' $tmp/headers"
check "another Host (DNS rebinding): 403" test "$(code -H "$A" -H 'Host: evil.example:'$PORT "$B/")" = 403
check "localhost is a good Host" test "$(code -H "$A" -H "Host: localhost:$PORT" "$B/")" = 200
J='Content-Type: application/json'
post() { code -X POST -H "$J" "$@"; }
check "POST without the token: 401" test "$(post -d '{"x_m":1,"y_m":2}' "$B/destination")" = 401
check "POST with a wrong token: 401" test "$(post -H "X-Houghloc-Token: ${TOKEN}0" -d '{"x_m":1,"y_m":2}' "$B/destination")" = 401
check "POST with the token in the URL only: 401" test "$(post -d '{"x_m":1,"y_m":2}' "$B/destination?token=$TOKEN")" = 401
check "POST with the token in a cookie named token: 401" test "$(post -b "token=$TOKEN" -d '{"x_m":1,"y_m":2}' "$B/destination")" = 401
check "POST with the session cookie but no Origin: 403" test "$(post -b "$tmp/jar" -d '{"x_m":1,"y_m":2}' "$B/destination")" = 403
check "POST with the session cookie from another port's page: 403" test "$(post -b "$tmp/jar" -H "Origin: http://127.0.0.1:1" -d '{"x_m":1,"y_m":2}' "$B/destination")" = 403
check "a STOP with the session cookie from the console's page: 202" test "$(code -X POST -b "$tmp/jar" -H "Origin: $B" "$B/stop")" = 202
check "a STOP with the bearer token: 202" test "$(code -X POST -H "$A" "$B/stop")" = 202
T="X-Houghloc-Token: $TOKEN"
check "POST of broken JSON: 400" test "$(post -H "$T" -d '{"x_m":1,' "$B/destination")" = 400
check "... says why" grep -q '"error":' "$tmp/body"
check "POST of an unknown member: 400" test "$(post -H "$T" -d '{"x_m":1,"y_m":2,"go":1}' "$B/destination")" = 400
check "POST of NaN: 400" test "$(post -H "$T" -d '{"x_m":NaN,"y_m":2}' "$B/destination")" = 400
check "POST beyond the coordinates: 400" test "$(post -H "$T" -d '{"x_m":5000,"y_m":2}' "$B/destination")" = 400
head -c 5000 /dev/zero | tr '\0' ' ' >"$tmp/big"
check "POST of 5000 bytes: 400" test "$(post -H "$T" --data-binary @"$tmp/big" "$B/destination")" = 400
check "POST as a form: 400" test "$(code -X POST -H "$T" -d 'x_m=1&y_m=2' "$B/destination")" = 400
check "OPTIONS (a CORS preflight): 405" test "$(code -X OPTIONS -H "$T" "$B/destination")" = 405
check "GET /destination: 405" test "$(code -H "$T" "$B/destination")" = 405
check "DELETE /: 405" test "$(code -X DELETE -H "$T" "$B/")" = 405
check "an unknown path: 404" test "$(code -H "$T" "$B/etc/passwd")" = 404
check "an unknown path without the token: 401" test "$(code "$B/etc/passwd")" = 401
check "a good POST: 202" test "$(post -H "$T" -d '{"x_m":1.25,"y_m":-2,"heading_deg":90}' "$B/destination")" = 202
check "... answers what it sent, signed" grep -q '"x_mm":1250,"y_mm":-2000,"heading_deg":90.00,"signed":true' "$tmp/body"
curl -s -N --max-time 1 -b "$tmp/jar" "$B/events" >"$tmp/events"
check "the event stream with the cookie starts with hello" sh -c "head -n 1 $tmp/events | grep -q '^event: hello$'"
check "a late page gets the destination sent" grep -q '^data: {"utime":[0-9]*,"seq":"[0-9]*","x_mm":1250' "$tmp/events"
check "the console is idle: no CPU time over 2 s" sh -c '
    a=$(awk "{print \$14 + \$15}" /proc/$1/stat); sleep 2; b=$(awk "{print \$14 + \$15}" /proc/$1/stat)
    [ $((b - a)) -le 2 ]' - "$console"
kill -TERM $console; wait $console
check "SIGTERM: a clean stop (exit 0)" test $? -eq 0
sleep 0.3
kill -INT $logger; wait $logger
"$BIN/hl-eval" extract "$tmp/dest.lcmlog" DESTINATION "$tmp/dest.bin"
check "exactly one DESTINATION was published (67 bytes, framed)" test "$(wc -c <"$tmp/dest.bin")" -eq 71
check "... at (1250, -2000) mm" test "$(od -An -tx1 -j 28 -N 8 "$tmp/dest.bin" | tr -d ' \n')" = "000004e2fffff830"
check "... signed (its MAC is not zero)" sh -c "od -An -tx1 -j 39 -N 32 $tmp/dest.bin | tr -d ' 0\n' | grep -q ."

# ---- another address: every request needs the token -------------------------------------
"$C" --lcm-url "$URL" --listen "0.0.0.0:$OPORT" --token-file "$tmp/token" 2>"$tmp/o.err" &
console=$!; pids="$pids $console"
w=0; while ! grep -q "serving" "$tmp/o.err" && [ $w -lt 50 ]; do sleep 0.1; w=$((w + 1)); done
check "prints the address with the token" grep -q "serving http://0.0.0.0:$OPORT/?token=console-token-0123456789 " "$tmp/o.err"
O="http://127.0.0.1:$OPORT"
check "open mode: GET / without the token: 401" test "$(code "$O/")" = 401
check "open mode: any Host, but a token: 401" test "$(code -H 'Host: robot.example' "$O/")" = 401
check "open mode: GET /?token=: 303 with the cookie" test "$(code "$O/?token=console-token-0123456789")" = 303
check "open mode: GET / with the header: 200" test "$(code -H 'X-Houghloc-Token: console-token-0123456789' "$O/")" = 200
check "open mode: the stream with a wrong token: 401" test "$(code -H 'Authorization: Bearer console-token-0123456780' "$O/events")" = 401
check "open mode: POST with the token in the URL only: 401" test "$(post -d '{"x_m":1,"y_m":2}' "$O/destination?token=console-token-0123456789")" = 401
check "open mode: POST with the header: 202, unsigned" sh -c "test \"\$(curl -s -o $tmp/body -w '%{http_code}' -X POST -H '$J' -H 'X-Houghloc-Token: console-token-0123456789' -d '{\"x_m\":0,\"y_m\":0}' $O/destination)\" = 202 && grep -q '\"signed\":false' $tmp/body"
kill -INT $console; wait $console
check "SIGINT: a clean stop (exit 0)" test $? -eq 0

# ---- --token-out: the token in a new file of mode 0600, not in the log -------------------
printf 'stale\n' >"$tmp/out.token"; chmod 644 "$tmp/out.token"
"$C" --lcm-url "$URL" --listen "127.0.0.1:$OPORT" --token-out "$tmp/out.token" 2>"$tmp/t.err" &
console=$!; pids="$pids $console"
w=0; while ! grep -q "serving" "$tmp/t.err" && [ $w -lt 50 ]; do sleep 0.1; w=$((w + 1)); done
check "--token-out: the log names the file, not the token" grep -q "serving http://127.0.0.1:$OPORT/?token=<the token in $tmp/out.token> on LCM" "$tmp/t.err"
check "--token-out: the file holds a fresh token, mode 600" sh -c "grep -Eqx '[0-9a-f]{32}' $tmp/out.token && test \$(stat -c %a $tmp/out.token) = 600"
OT=$(cat "$tmp/out.token")
check "--token-out: the token is not in the log" sh -c "! grep -q '$OT' $tmp/t.err"
check "--token-out: the token works" test "$(code -H "Authorization: Bearer $OT" "http://127.0.0.1:$OPORT/")" = 200
kill -TERM $console; wait $console
check "no log line without the prefix" sh -c "! grep -hv '^houghloc-console: ' $tmp/c.err $tmp/o.err $tmp/t.err"

# ---- --ground-truth: the simulator's poses drawn in the daemon's map frame ---------------
# The first scans of logs/lab28, whose robot starts at (0.614, -0.004) m facing -92
# degrees in the world: the console must draw its first true pose at the daemon's start
# pose (--start, default the origin) and the last one moved rigidly with it.
exits "--start not a pose" 2 "--start '1,2' is not X,Y,DEG" "$C" --start 1,2
exits "--start beyond the map" 2 "outside +-4194.304 m" "$C" --start=5000,0,0
"$BIN/hl-eval" split logs/lab28.lcmlog 3 "$tmp/first.lcmlog" "$tmp/rest.lcmlog"
first=$("$BIN/hl-eval" start "$tmp/first.lcmlog")
last=$("$BIN/hl-eval" truth "$tmp/first.lcmlog" | tr ',' ' ')
GPORT=$(( 19500 + n % 100 ))
GURL="udpm://239.255.76.67:$(( 9400 + n ))?ttl=0"
for start in "0,0,0" "2,-1,90"; do
    "$C" --lcm-url "$GURL" --listen "127.0.0.1:$GPORT" --ground-truth --start "$start" \
        2>"$tmp/g.err" &
    console=$!; pids="$pids $console"
    w=0; while ! grep -q "serving" "$tmp/g.err" && [ $w -lt 50 ]; do sleep 0.1; w=$((w + 1)); done
    lcm-logplayer -s 20 -e '^GROUND_TRUTH$' -l "$GURL" "$tmp/first.lcmlog" >/dev/null
    GT=$(sed -n 's/.*serving http:[^ ]*?token=\([0-9a-f]*\) .*/\1/p' "$tmp/g.err")
    curl -s -N --max-time 1 -H "Authorization: Bearer $GT" "http://127.0.0.1:$GPORT/events" >"$tmp/gevents"
    kill -TERM $console; wait $console
    # the kept track's first point, and the last true pose sent
    track=$(sed -n 's/^data: {"estimate":\[[^]]*\],"truth":\[\([-0-9]*\),\([-0-9]*\).*/\1 \2/p' "$tmp/gevents")
    pose=$(grep -A1 '^event: truth$' "$tmp/gevents" | tail -n 1 |
           sed -n 's/.*"scan_seq":[0-9]*,"x_mm":\([-0-9]*\),"y_mm":\([-0-9]*\),"heading_deg":\([-0-9.]*\).*/\1 \2 \3/p')
    check "--start $start: the first true pose drawn at the start ($track)" \
        awk -v t="$track" -v s="$start" 'BEGIN { split(t, a, " "); split(s, b, ",")
            exit !(a[1] != "" && a[1] == b[1] * 1000 && a[2] == b[2] * 1000) }'
    check "--start $start: the last true pose moved rigidly with it ($pose)" \
        awk -v f="$first" -v l="$last" -v p="$pose" -v s="$start" 'BEGIN {
            split(f, F, " "); split(l, L, " "); split(p, P, " "); split(s, S, ",")
            r = atan2(0, -1) / 180; t = (S[3] - F[3]) * r; c = cos(t); n = sin(t)
            dx = L[1] - F[1]; dy = L[2] - F[2]
            x = 1000 * (S[1] + c * dx - n * dy); y = 1000 * (S[2] + n * dx + c * dy)
            h = L[3] - F[3] + S[3]; while (h < 0) h += 360; while (h >= 360) h -= 360
            dh = P[3] - h; if (dh > 180) dh -= 360; if (dh < -180) dh += 360
            exit !(P[1] != "" && (P[1] - x) ^ 2 + (P[2] - y) ^ 2 <= 9 && dh * dh < 0.01) }'
done

exit $fail
