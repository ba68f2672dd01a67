#!/usr/bin/env python3
"""browser_test.py - the browser half of make test-console (see browser_test.sh).

Speaks chromedriver's W3C WebDriver REST API with python3's standard library only:
opens the console's page in headless Chromium, waits for the map and for the end of the
replay, clicks a point near the robot, checks that a DESTINATION with its coordinates
was published (lcm-logger's file, read here) and that the reply shows on the page,
saves the screenshot, times 15,000-vector redraws, and prints the one summary line.
"""
import argparse
import base64
import json
import os
import signal
import struct
import sys
import time
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


def destinations(path):
    """(seq, x_mm, y_mm) of every DESTINATION in an LCM event log."""
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
        payload = data[i + 28 + clen:i + 28 + clen + dlen]
        if channel == "DESTINATION" and len(payload) >= 32:
            _, _, seq, x, y = struct.unpack(">qqqii", payload[:32])
            out.append((seq, x, y))
        i += 28 + clen + dlen
    return out


def main():
    sys.stdout.reconfigure(line_buffering=True)
    ap = argparse.ArgumentParser()
    for opt in ("--driver", "--page", "--profile", "--replayed", "--dest-log", "--out"):
        ap.add_argument(opt, required=True)
    ap.add_argument("--logger-pid", type=int, required=True)
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
    os.kill(a.logger_pid, signal.SIGINT)  # lcm-logger writes its file out on SIGINT
    found = wait_for("the DESTINATION in the log", lambda: destinations(a.dest_log), 5) or []
    roundtrip = bool(ok and reply and found and sent)
    for seq, x, y in found:
        err = max(abs(x - wx * 1000), abs(y - wy * 1000), abs(x - tx * 1000), abs(y - ty * 1000))
        print("browser_test: DESTINATION seq %d at (%d, %d) mm, clicked (%.0f, %.0f) mm, "
              "wanted (%.0f, %.0f) mm: %.1f mm off; reply %s"
              % (seq, x, y, wx * 1000, wy * 1000, tx * 1000, ty * 1000, err, reply))
        roundtrip = roundtrip and len(found) == 1 and err <= CELL_MM
    d.js("document.getElementById('follow').click(); document.getElementById('fit').click()")
    time.sleep(0.3)
    png = base64.b64decode(d.s("GET", "/screenshot"))
    with open(os.path.join(a.out, "screenshot.png"), "wb") as f:
        f.write(png)
    bench = d.js(api + ".benchRedraw(15000, 30)")
    print("browser_test: 15,000-vector redraw: median %.2f ms, min %.2f, max %.2f (%d vectors)"
          % (bench["median_ms"], bench["min_ms"], bench["max_ms"], bench["vectors"]))
    if bench["median_ms"] >= 16:
        print("browser_test: warning: the redraw takes 16 ms or more", file=sys.stderr)
    print("console browser=chromium-%s vectors_drawn=%d destination_roundtrip=%s frame_ms=%.2f"
          % (d.version, vectors, "ok" if roundtrip else "failed", bench["median_ms"]), flush=True)
    return 0 if roundtrip and vectors > 0 and bench["vectors"] == 15000 else 1


if __name__ == "__main__":
    sys.exit(main())
