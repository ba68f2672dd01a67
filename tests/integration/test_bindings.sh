#!/bin/sh
# Integration test of the LCM bindings handed to users (`make bindings`): the generated
# Python types import and encode without the lcm runtime, round-trip every message, and
# encode a pose byte for byte as the C types the daemon is built from do
# (build/bin/hl-pose-bytes); the Java jar, when it was built, is found by lcm-spy's own
# type lookup (lcm.spy.LCMTypeDatabase, through $CLASSPATH as Debian's lcm-spy script
# leaves it) and encodes the same bytes. The counters of STATUS and MAP's version are
# 64-bit in every binding: values past 2^32 (up to 2^63 - 1) encode and decode whole in
# Python and Java, as the C encoder wrote them (the fuzz seeds of tests/fuzz/corpus, made by
# hl_bus_encode_status and hl_bus_encode_map).
set -u
BUILD=${BUILD:-build}
LCM_JAR=${LCM_JAR:-/usr/share/java/lcm.jar}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
check() {   # check DESCRIPTION COMMAND...: the command must succeed
    desc=$1; shift
    if "$@"; then echo "ok: $desc"; else echo "FAIL: $desc"; fail=1; fi
}

# One pose, every field away from zero and of both signs; 0.75 is exact in a float.
POSE="1700000000123456 42 -1234 5678 -16384 1 0.75 65536 1024 9000 0.5 -300 400 8192 0.25"
# shellcheck disable=SC2086
c_hex=$("$BUILD/bin/hl-pose-bytes" $POSE)
check "hl-pose-bytes encodes a pose (8 + 57 bytes)" test "${#c_hex}" -eq 130
check "hl-pose-bytes rejects a heading out of int16 range" \
    sh -c '! "$1" 1 2 3 4 40000 1 0.5 1 1 1 0 0 0 0 0 2>/dev/null' - "$BUILD/bin/hl-pose-bytes"

if command -v python3 >/dev/null 2>&1; then
    names=$(for f in lcmtypes/houghloc_*.lcm; do basename "$f" .lcm; done |
        sed 's/^houghloc_//' | tr '\n' ' ')
    # shellcheck disable=SC2086
    PYTHONDONTWRITEBYTECODE=1 python3 - "$BUILD/python" "$c_hex" $POSE $names \
        >"$tmp/py" 2>&1 <<'EOF'
import sys
sys.path.insert(0, sys.argv[1])
sys.modules["lcm"] = None          # any "import lcm" now fails: the types must not need it
import houghloc

c_bytes = bytes.fromhex(sys.argv[2])
v = sys.argv[3:18]
names = sys.argv[18:]
C_STATUS = open("tests/fuzz/corpus/bus_status/past-32-bits", "rb").read()
C_MAP = open("tests/fuzz/corpus/bus_map/three-past-32-bits", "rb").read()
bad = 0
def expect(desc, ok):
    global bad
    print(("ok: " if ok else "FAIL: ") + desc)
    bad |= not ok

for n in names:
    t = getattr(houghloc, n, None)
    if t is None:
        expect("python type %s exists" % n, False)
        continue
    b = t().encode()
    expect("python %s round-trips a default message" % n,
           t.decode(b).encode() == b and b[:8] == t._get_packed_fingerprint())

p = houghloc.pose_t()
(p.utime, p.scan_seq, p.x_mm, p.y_mm, p.heading_bam, p.status) = map(int, v[0:6])
p.confidence = float(v[6])
(p.peak, p.second_peak, p.votes) = map(int, v[7:10])
p.search_score = float(v[10])
(p.runner_up_x_mm, p.runner_up_y_mm, p.runner_up_heading_bam) = map(int, v[11:14])
p.runner_up_score = float(v[14])
expect("python pose_t encodes the bytes the C types do", p.encode() == c_bytes)
expect("python pose_t fingerprint is the C hash", houghloc.pose_t._get_packed_fingerprint() == c_bytes[:8])
q = houghloc.pose_t.decode(c_bytes)
expect("python pose_t decodes the C bytes to the same fields",
       [q.utime, q.scan_seq, q.x_mm, q.y_mm, q.heading_bam, q.status, q.confidence,
        q.peak, q.second_peak, q.votes, q.search_score, q.runner_up_x_mm, q.runner_up_y_mm,
        q.runner_up_heading_bam, q.runner_up_score] ==
       [int(x) for x in v[0:6]] + [0.75] + [int(x) for x in v[7:10]] + [0.5] +
       [int(x) for x in v[11:14]] + [0.25])
try:
    houghloc.odometry_t.decode(c_bytes)
    expect("python refuses a pose as odometry (fingerprint)", False)
except ValueError:
    expect("python refuses a pose as odometry (fingerprint)", True)

# 64-bit counters: the C encoder's bytes decode whole, and encode back to the same bytes
s = houghloc.status_t.decode(C_STATUS)
expect("python status_t decodes the C counters past 32 bits",
       (s.scans, s.bad_messages, s.map_version, s.rejected_requests, s.map_vectors) ==
       (5000000000, 2**31 + 3, 2**32 + 40, 2**63 - 1, 812))
expect("python status_t encodes them back to the C bytes", s.encode() == C_STATUS)
m = houghloc.map_t.decode(C_MAP)
expect("python map_t decodes a C version past 32 bits", m.version == 2**32 + 2 and m.nvectors == 3)
expect("python map_t encodes it back to the C bytes", m.encode() == C_MAP)
s.saves = 2**63 - 1
s.lost = 2**40
expect("python status_t round-trips counters up to 2^63 - 1",
       houghloc.status_t.decode(s.encode()).saves == 2**63 - 1 and
       houghloc.status_t.decode(s.encode()).lost == 2**40)
expect("the lcm runtime was never imported", sys.modules.get("lcm") is None)
sys.exit(bad)
EOF
    rc=$?
    cat "$tmp/py"
    check "python checks ran and passed" test "$rc" -eq 0
else
    echo "note: python3 is missing; the Python bindings are not checked"
fi

jar="$BUILD/java/houghloc_lcmtypes.jar"
if [ -f "$jar" ] && [ -f "$LCM_JAR" ] && command -v javac >/dev/null 2>&1; then
    # The probe knows no houghloc class: it asks lcm-spy's type database for the class of
    # the C fingerprint, as lcm-spy does for each message it hears, then fills it by name.
    # The database chats on stdout, so the probe's answer is the line starting "probe ".
    cat >"$tmp/Probe.java" <<'EOF'
import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.lang.reflect.Field;

public class Probe {
    public static void main(String[] a) throws Exception {
        long fp = Long.parseUnsignedLong(a[0], 16);
        Class<?> c = new lcm.spy.LCMTypeDatabase().getClassByFingerprint(fp);
        if (c == null) {
            System.out.println("probe none");
            return;
        }
        Object m = c.getConstructor().newInstance();
        for (int i = 1; i < a.length; i++) {
            String[] kv = a[i].split("=", 2);
            Field f = c.getField(kv[0]);
            Class<?> t = f.getType();
            if (t == long.class) f.setLong(m, Long.parseLong(kv[1]));
            else if (t == int.class) f.setInt(m, Integer.parseInt(kv[1]));
            else if (t == short.class) f.setShort(m, Short.parseShort(kv[1]));
            else if (t == byte.class) f.setByte(m, Byte.parseByte(kv[1]));
            else if (t == float.class) f.setFloat(m, Float.parseFloat(kv[1]));
            else throw new IllegalArgumentException(kv[0]);
        }
        ByteArrayOutputStream bo = new ByteArrayOutputStream();
        ((lcm.lcm.LCMEncodable) m).encode(new DataOutputStream(bo));
        StringBuilder s = new StringBuilder("probe " + c.getName() + " ");
        for (byte b : bo.toByteArray()) s.append(String.format("%02x", b & 0xff));
        System.out.println(s);
    }
}
EOF
    javac -nowarn -cp "$LCM_JAR" -d "$tmp" "$tmp/Probe.java" 2>"$tmp/javac.err"
    check "the Java probe compiles" test $? -eq 0
    set -- $POSE
    fields="utime=$1 scan_seq=$2 x_mm=$3 y_mm=$4 heading_bam=$5 status=$6 confidence=$7 peak=$8 second_peak=$9 votes=${10}"
    fields="$fields search_score=${11} runner_up_x_mm=${12} runner_up_y_mm=${13} runner_up_heading_bam=${14} runner_up_score=${15}"
    fp=$(printf '%s' "$c_hex" | cut -c1-16)
    # shellcheck disable=SC2086
    CLASSPATH=$jar java -Djava.awt.headless=true -cp "$LCM_JAR:$tmp" Probe "$fp" $fields \
        >"$tmp/java" 2>"$tmp/java.err"
    check "lcm-spy's type lookup finds houghloc.pose_t in the jar via CLASSPATH" \
        grep -q "^probe houghloc.pose_t " "$tmp/java"
    check "java pose_t encodes the bytes the C types do" \
        test "$(grep "^probe " "$tmp/java" | cut -d' ' -f3)" = "$c_hex"
    # MAP's version is a Java long: the C encoder's 2^63 - 1 comes out of it byte for byte
    m_hex=$(od -An -tx1 -v tests/fuzz/corpus/bus_map/empty-last-version | tr -d ' \n')
    CLASSPATH=$jar java -Djava.awt.headless=true -cp "$LCM_JAR:$tmp" Probe \
        "$(printf '%s' "$m_hex" | cut -c1-16)" utime=1 version=9223372036854775807 \
        capacity=1500 nvectors=0 >"$tmp/java3" 2>>"$tmp/java.err"
    check "java map_t encodes a version of 2^63 - 1 as the C types do" \
        test "$(grep "^probe " "$tmp/java3")" = "probe houghloc.map_t $m_hex"
    java -Djava.awt.headless=true -cp "$LCM_JAR:$tmp" Probe "$fp" >"$tmp/java2" 2>&1
    check "without the jar lcm-spy would not know the type" \
        test "$(grep "^probe " "$tmp/java2")" = "probe none"
    [ $fail -eq 0 ] || cat "$tmp/javac.err" "$tmp/java.err" 2>/dev/null | head -20
else
    echo "note: $jar, $LCM_JAR or javac missing; the Java bindings are not checked"
fi

exit $fail
