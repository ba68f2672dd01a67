#!/usr/bin/env python3
"""browser_test.py - the browser half of make test-console (see browser_test.sh).

Speaks chromedriver's W3C WebDriver REST API with python3's standard library only:
opens the console's page in headless Chromium, waits for the map and for the end of the
replay, clicks a point near the robot, checks that a DESTINATION with its coordinates
was published (lcm-logger's file, read here) and that the reply shows on the page;
presses Escape and clicks the Stop button, checks that each published one STOP COMMAND
with the seq the page was answered and that the daemon's reply to each shows on the
page; publishes a PATH itself (LCM's UDP multicast, its fingerprint computed from
lcmtypes/houghloc_path_t.lcm as lcm-gen does) and checks that the page draws its points,
then that an empty PATH clears them; saves the screenshot, times 15,000-vector redraws,
and prints the one summary line.
"""
import argparse
import base64
import json
import os
import re
import signal
import socket
import struct
import sys
import time
import urllib.parse
import urllib.request

CELL_MM = 24  # one map cell (localize.cell_mm): the tolerance on the clicked point
CHROME_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
               "--no-first-run", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--window-size=1280,800"]


class Driver:
    """The few WebDriver commands the test needs."""

    def __init__(self, base, profile):
        self.base = base
        caps = {"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {"binary": "/usr/bin/chromium",
                                   "args": CHROME_ARGS + ["--user-data-dir=" + profile]}}}}
        value = self.call("POST", "/session", caps)
        self.session = value["sessionId"]
        self.version = value["capabilities"].get("browserVersion", "?")

    def call(self, method, path, body=None):
        data = json.dumps(body).encode() if body is not None else None
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        with urllib.request.urlopen(req, timeout=60) as r:
            return json.loads(r.read())["value"]

    def s(self, method, path, body=None):
        return self.call(method, "/session/" + self.session + path, body)

    def js(self, script, *args):
        return self.s("POST", "/execute/sync", {"script": script, "args": list(args)})

    def click(self, x, y):
        self.s("POST", "/actions", {"actions": [{
            "type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
            "actions": [{"type": "pointerMove", "duration": 0, "x": x, "y": y, "origin": "viewport"},
                        {"type": "pointerDown", "button": 0},
                        {"type": "pointerUp", "button": 0}]}]})

    def key(self, value):
        """One key pressed and released (WebDriver's code points: Escape is U+E00C)."""
        self.s("POST", "/actions", {"actions": [{
            "type": "key", "id": "keyboard",
            "actions": [{"type": "keyDown", "value": value}, {"type": "keyUp", "value": value}]}]})

    def quit(self):
        try:
            self.s("DELETE", "")
        except OSError:
            pass


def wait_for(what, fn, timeout):
    end = time.time() + timeout
    while time.time() < end:
        value = fn()
        if value:
            return value
        time.sleep(0.2)
    print("browser_test: timed out waiting for " + what, file=sys.stderr)
    return None


def events(path):
    """(channel, payload) of every event in an LCM event log."""
    out = []
    try:
        data = open(path, "rb").read()
    except OSError:
        return out
    i = 0
    while i + 28 <= len(data):
        sync, _, _, clen, dlen = struct.unpack(">IqqII", data[i:i + 28])
        if sync != 0xEDA1DA01 or i + 28 + clen + dlen > len(data):
            break
        channel = data[i + 28:i + 28 + clen].decode("ascii", "replace")
        out.append((channel, data[i + 28 + clen:i + 28 + clen + dlen]))
        i += 28 + clen + dlen
    return out


def exited(pid):
    """True once pid has exited (a zombie its parent has not reaped yet counts)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z" or None
    except OSError:
        return True


def destinations(path):
    """(seq, x_mm, y_mm) of every DESTINATION in an LCM event log."""
    return [struct.unpack(">qqqii", p[:32])[2:] for c, p in events(path)
            if c == "DESTINATION" and len(p) >= 32]


def commands(path):
    """(seq, kind, mac) of every COMMAND in an LCM event log (8 hash, 8 utime, 8 seq,
    1 kind, 4 x, 4 y, 2 heading, 32 mac)."""
    return [(struct.unpack(">q", p[16:24])[0], struct.unpack(">b", p[24:25])[0], p[35:67])
            for c, p in events(path) if c == "COMMAND" and len(p) == 67]


# ---- publishing on LCM without its Python module: lcm-gen's fingerprint, LCM's UDP ------
M64 = (1 << 64) - 1
LCM_PRIMITIVES = {"int8_t", "int16_t", "int32_t", "int64_t", "byte", "float", "double",
                  "string", "boolean"}


def _s64(v):
    v &= M64
    return v - (1 << 64) if v >> 63 else v


def _hash_update(v, c):
    return _s64(((v << 8) ^ (v >> 55)) + c)


def _hash_string(v, text):
    v = _hash_update(v, len(text))
    for c in text.encode():
        v = _hash_update(v, c)
    return v


def lcm_fingerprint(lcm_file):
    """The fingerprint lcm-gen gives a struct of primitive members (lcmgen.c's hash of
    the member names, types and dimensions, rotated left by one bit)."""
    text = re.sub(r"//[^\n]*", "", open(lcm_file).read())
    v = 0x12345678
    for stmt in text[text.index("{") + 1:text.rindex("}")].split(";"):
        stmt = stmt.strip()
        if not stmt or stmt.startswith("const"):
            continue
        m = re.fullmatch(r"(\w+)\s+(\w+)((?:\s*\[\s*\w+\s*\])*)", stmt)
        if not m or m.group(1) not in LCM_PRIMITIVES:
            raise ValueError("%s: cannot fingerprint %r" % (lcm_file, stmt))
        dims = re.findall(r"\[\s*(\w+)\s*\]", m.group(3))
        v = _hash_string(v, m.group(2))
        v = _hash_string(v, m.group(1))
        v = _hash_update(v, len(dims))
        for dim in dims:
            v = _hash_update(v, 0 if dim.isdigit() else 1)
            v = _hash_string(v, dim)
    u = v & M64
    return ((u << 1) & M64) | (u >> 63)


class Publisher:
    """LCM's small-message UDP multicast: "LC02", a sequence number, the channel and its
    NUL, the payload, to the group and port of a udpm:// URL."""

    def __init__(self, url):
        u = urllib.parse.urlparse(url)
        self.dest = (u.hostname, u.port or 7667)
        ttl = int(urllib.parse.parse_qs(u.query).get("ttl", ["0"])[0])
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, ttl)
        self.sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
        self.seqno = 0

    def publish(self, channel, payload):
        self.sock.sendto(struct.pack(">II", 0x4C433032, self.seqno) + channel.encode() + b"\0"
                         + payload, self.dest)
        self.seqno += 1


def path_message(fingerprint, seq, points):
    """A houghloc.path_t: utime, destination_seq, npoints, the x's, the y's."""
    xs = [int(x) for x, _ in points]
    ys = [int(y) for _, y in points]
    n = len(points)
    return struct.pack(">Qqqi%di%di" % (n, n), fingerprint, int(time.time() * 1e6), seq, n,
                       *(xs + ys))


def main():
    sys.stdout.reconfigure(line_buffering=True)
    ap = argparse.ArgumentParser()
    for opt in ("--driver", "--page", "--profile", "--replayed", "--dest-log", "--out",
                "--lcm-url"):
        ap.add_argument(opt, required=True)
    ap.add_argument("--logger-pid", type=int, required=True)
    ap.add_argument("--lcm-types", default="lcmtypes")
    a = ap.parse_args()
    d = wait_for("chromedriver", lambda: _try(lambda: Driver(a.driver, a.profile)), 20)
    if not d:
        return 1
    try:
        return run(d, a)
    finally:
        d.quit()


def _try(fn):
    try:
        return fn()
    except OSError:
        return None


def run(d, a):
    d.s("POST", "/url", {"url": a.page})
    api = "return window.houghloc"
    ok = wait_for("the map on the page", lambda: d.js(api + " && window.houghloc.vectorsDrawn"), 60)
    wait_for("the end of the replay", lambda: os.path.exists(a.replayed), 90)
    time.sleep(1.5)  # the last MAP and POSE
    vectors = d.js(api + ".vectorsDrawn") or 0
    pose = d.js(api + ".pose()")
    # centred on the robot and zoomed in (a pixel about 5 mm), so the pixel clicked
    # stands for a point well within a cell of the one wanted: 0.6 m left of the robot,
    # 0.4 m above, inside the default fence
    d.js("document.getElementById('follow').click()")
    d.js("for (let i = 0; i < 40 && window.houghloc.scale() < 0.2; i++)"
         " document.getElementById('zin').click()")
    tx = round((pose["x_mm"] if pose else 0) / 1000.0 - 0.6, 3)
    ty = round((pose["y_mm"] if pose else 0) / 1000.0 + 0.4, 3)
    px, py = d.js(api + ".worldToScreen(arguments[0], arguments[1])", tx, ty)
    px, py = int(round(px)), int(round(py))
    # the world point that pixel stands for is the target; within a cell of the wanted one
    wx, wy = d.js(api + ".screenToWorld(arguments[0], arguments[1])", px, py)
    d.click(px, py)
    reply = wait_for("the reply on the page", lambda: d.js(
        "const r = window.houghloc.replies.find((r) => r.mine && r.result !== 'ACCEPTED');"
        "return r && document.getElementById('replies').textContent.indexOf(r.result) >= 0"
        " ? r.result : null"), 15)
    sent = d.js(api + ".lastRequest")

    # STOP: Escape anywhere on the page, then the Stop button, each one STOP whose reply
    # (the daemon takes a STOP from anyone: ACCEPTED) shows on the page
    stop_seqs, stop_replies = [], []
    for how in ("Escape", "the Stop button"):
        if how == "Escape":
            d.key("\ue00c")
        else:
            bx, by = d.js("const r = document.getElementById('stop').getBoundingClientRect();"
                          " return [r.left + r.width / 2, r.top + r.height / 2]")
            d.click(int(round(bx)), int(round(by)))
        k = len(stop_seqs) + 1
        seq = wait_for("the answer to the STOP by " + how, lambda: d.js(
            "const s = window.houghloc.stops; return s.length >= arguments[0] ? s[arguments[0] - 1] : null",
            k), 10)
        stop_seqs.append(seq)
        shown = seq and wait_for("the reply to the STOP by " + how + " on the page", lambda: d.js(
            "const r = window.houghloc.replies.find((r) => r.mine && r.seq === arguments[0]);"
            "return r && document.getElementById('replies').textContent.indexOf('(seq ' + r.seq + ')') >= 0"
            " ? r.result + (r.message ? ': ' + r.message : '') : null", seq), 10)
        stop_replies.append(shown)
        print("browser_test: STOP by %s: seq %s, reply %s" % (how, seq, shown))
    requested = d.js(api + ".stopsRequested")

    # PATH: a way from the robot to a point 1.6 m off, drawn; then an empty one clears it
    fp = lcm_fingerprint(a.lcm_types + "/houghloc_path_t.lcm")
    pub = Publisher(a.lcm_url)
    rx, ry = (pose["x_mm"], pose["y_mm"]) if pose else (0, 0)
    way = [(rx, ry), (rx + 400, ry + 300), (rx + 800, ry + 300), (rx + 1200, ry - 200),
           (rx + 1600, ry - 200)]
    path_seq = 424242424242424242  # beyond 2^53: the page must keep it as a string

    def drawn(msg, want):
        pub.publish("PATH", msg)  # again until seen: a datagram may be lost
        return d.js("const h = window.houghloc; return h.pathSeq === arguments[0] &&"
                    " h.frames > 0 && h.pathPoints === arguments[1] ? [h.pathPoints] : null",
                    want[0], want[1])
    got = wait_for("the PATH drawn", lambda: drawn(path_message(fp, path_seq, way),
                                                   (str(path_seq), len(way))), 10)
    path_points = got[0] if got else 0
    d.js("document.getElementById('follow').click(); document.getElementById('fit').click()")
    time.sleep(0.3)
    png = base64.b64decode(d.s("GET", "/screenshot"))  # with the way drawn
    with open(os.path.join(a.out, "screenshot.png"), "wb") as f:
        f.write(png)
    cleared = wait_for("the PATH cleared", lambda: drawn(path_message(fp, -1, []), (None, 0)), 10)
    path_ok = path_points == len(way) and bool(cleared)
    print("browser_test: PATH of %d points drawn: %d points; the empty PATH cleared it: %s"
          % (len(way), path_points, "yes" if cleared else "no"))

    os.kill(a.logger_pid, signal.SIGINT)  # lcm-logger writes its file out on SIGINT
    wait_for("lcm-logger to finish its file", lambda: exited(a.logger_pid), 10)
    found = destinations(a.dest_log)
    cmds = commands(a.dest_log)
    stops = [(seq, mac) for seq, kind, mac in cmds if kind == 4]
    print("browser_test: COMMANDs published: %s"
          % ", ".join("seq %d kind %d" % (seq, kind) for seq, kind, _ in cmds))
    stop_ok = (requested == 2 and len(cmds) == 2 and len(stops) == 2
               and [str(seq) for seq, _ in stops] == stop_seqs and all(stop_replies)
               and all(mac == bytes(32) for _, mac in stops))  # no --key: unsigned
    roundtrip = bool(ok and reply and found and sent)
    for seq, x, y in found:
        err = max(abs(x - wx * 1000), abs(y - wy * 1000), abs(x - tx * 1000), abs(y - ty * 1000))
        print("browser_test: DESTINATION seq %d at (%d, %d) mm, clicked (%.0f, %.0f) mm, "
              "wanted (%.0f, %.0f) mm: %.1f mm off; reply %s"
              % (seq, x, y, wx * 1000, wy * 1000, tx * 1000, ty * 1000, err, reply))
        roundtrip = roundtrip and len(found) == 1 and err <= CELL_MM
    bench = d.js(api + ".benchRedraw(15000, 30)")
    print("browser_test: 15,000-vector redraw: median %.2f ms, min %.2f, max %.2f (%d vectors)"
          % (bench["median_ms"], bench["min_ms"], bench["max_ms"], bench["vectors"]))
    if bench["median_ms"] >= 16:
        print("browser_test: warning: the redraw takes 16 ms or more", file=sys.stderr)
    print("console browser=chromium-%s vectors_drawn=%d destination_roundtrip=%s frame_ms=%.2f"
          " stop=%s path_points=%d"
          % (d.version, vectors, "ok" if roundtrip else "failed", bench["median_ms"],
             "ok" if stop_ok else "failed", path_points), flush=True)
    return 0 if (roundtrip and vectors > 0 and bench["vectors"] == 15000 and stop_ok
                 and path_ok) else 1


if __name__ == "__main__":
    sys.exit(main())
