#!/usr/bin/env python3
"""Opens HTML pages in headless Chromium and checks them (issue 19: the report page and rk-nightly's index).

  browser_check.py PAGE.html [--expect TEXT]... [--screenshot OUT.png [--full]] [--width W] [--height H]
                   [--repeat N] [--chromium PATH]

Talks to Chromium over the DevTools protocol on a pipe (--remote-debugging-pipe: fd 3 in, fd 4 out, JSON
messages ended by NUL), so it needs the standard library only. Every network access is refused twice: the
proxy is an unused local port and every host name resolves to nothing; any request the page makes other than
the page itself and data: URLs is a failure, as is any console error, uncaught exception or log entry of
level error (a Content-Security-Policy refusal included). Each --expect text must appear in the page's
rendered text (document.body.innerText). Prints the render time: navigation start to the end of the load
event and to the first contentful paint, from the page's own performance timing (the minimum over --repeat
loads). Exit 0 when every check passes, 1 when one fails, 77 when Chromium is not installed (the test is then
reported skipped)."""
import argparse
import base64
import fcntl
import json
import os
import select
import shutil
import subprocess
import sys
import tempfile
import time

SKIP = 77


class Browser:
    def __init__(self, exe, width, height):
        self.tmp = tempfile.mkdtemp(prefix="rk-browser-")
        # The child's fd 3 reads our commands and its fd 4 carries the answers. The pipe ends are first
        # moved above 10, so that putting one on 3 cannot overwrite the other.
        r, self.to_child = os.pipe()
        self.from_child, w = os.pipe()
        child_r, child_w = fcntl.fcntl(r, fcntl.F_DUPFD_CLOEXEC, 10), fcntl.fcntl(w, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(r)
        os.close(w)

        def fds():
            os.dup2(child_r, 3)  # inheritable: survives exec, unlike every other descriptor of ours
            os.dup2(child_w, 4)
        args = [exe, "--headless", "--remote-debugging-pipe", "--no-sandbox", "--disable-gpu",
                "--no-first-run", "--no-default-browser-check", "--disable-background-networking",
                "--disable-component-update", "--disable-default-apps", "--disable-sync", "--disable-extensions",
                "--disable-features=MediaRouter,OptimizationHints,Translate", "--metrics-recording-only",
                "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND",
                "--user-data-dir=" + self.tmp, "--window-size=%d,%d" % (width, height), "about:blank"]
        self.proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=open(os.path.join(self.tmp, "stderr.log"), "w"), preexec_fn=fds,
                                     close_fds=False)
        os.close(child_r)
        os.close(child_w)
        os.set_inheritable(self.to_child, False)
        self.buf = b""
        self.next_id = 0
        self.events = []
        self.session = None

    def send(self, method, params=None, session=True, timeout=60):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        data = json.dumps(msg).encode() + b"\0"
        while data:
            data = data[os.write(self.to_child, data):]
        want = self.next_id
        deadline = time.monotonic() + timeout
        while True:
            m = self.read(deadline)
            if m.get("id") == want:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"]))
                return m.get("result", {})

    def read(self, deadline):
        while b"\0" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("no answer from Chromium")
            r, _, _ = select.select([self.from_child], [], [], left)
            if r:
                chunk = os.read(self.from_child, 1 << 20)
                if not chunk:
                    with open(os.path.join(self.tmp, "stderr.log")) as f:
                        raise RuntimeError("Chromium closed the pipe: " + f.read()[-2000:])
                self.buf += chunk
        raw, self.buf = self.buf.split(b"\0", 1)
        m = json.loads(raw)
        if "method" in m:
            self.events.append(m)
        return m

    def wait_event(self, method, timeout=60):
        deadline = time.monotonic() + timeout
        seen = len(self.events)
        while True:
            for e in self.events[seen:]:
                if e["method"] == method:
                    return e
            seen = len(self.events)
            self.read(deadline)

    def close(self):
        try:
            self.send("Browser.close", session=False, timeout=5)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)


def problems_of(events, page_url):
    out = []
    for e in events:
        m, p = e["method"], e.get("params", {})
        if m == "Network.requestWillBeSent":
            url = p.get("request", {}).get("url", "")
            if url != page_url and not url.startswith("data:") and url != "about:blank":
                out.append("network request: %s" % url)
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append("console %s: %s" % (p["type"], " ".join(str(a.get("value", a.get("description", "")))
                                                              for a in p.get("args", []))))
        elif m == "Runtime.exceptionThrown":
            out.append("exception: %s" % p.get("exceptionDetails", {}).get("text"))
        elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            out.append("log error: %s (%s)" % (p["entry"].get("text"), p["entry"].get("url", "")))
    return out


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    ap.add_argument("page")
    ap.add_argument("--expect", action="append", default=[])
    ap.add_argument("--screenshot")
    ap.add_argument("--full", action="store_true", help="screenshot of the whole page, not the window")
    ap.add_argument("--width", type=int, default=1200)
    ap.add_argument("--height", type=int, default=900)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--chromium", default=os.environ.get("RK_CHROMIUM"))
    a = ap.parse_args(argv)
    exe = a.chromium or shutil.which("chromium") or shutil.which("chromium-browser")
    if not exe:
        print("SKIPPED: chromium is not installed (apt-get install chromium, or scripts/setup.sh --browser)")
        return SKIP
    url = "file://" + os.path.abspath(a.page)
    b = Browser(exe, a.width, a.height)
    failures = []
    try:
        target = b.send("Target.createTarget", {"url": "about:blank"}, session=False)["targetId"]
        b.session = b.send("Target.attachToTarget", {"targetId": target, "flatten": True}, session=False)["sessionId"]
        for domain in ("Page", "Network", "Runtime", "Log"):
            b.send(domain + ".enable")
        b.send("Emulation.setDeviceMetricsOverride", {"width": a.width, "height": a.height,
                                                      "deviceScaleFactor": 1, "mobile": False})
        loads, paints = [], []
        for _ in range(max(1, a.repeat)):
            b.send("Page.navigate", {"url": url})
            b.wait_event("Page.loadEventFired")
            t = b.send("Runtime.evaluate", {"expression": (
                "(()=>{const n=performance.getEntriesByType('navigation')[0];"
                "const p=performance.getEntriesByName('first-contentful-paint')[0];"
                "return JSON.stringify({load:n?n.loadEventEnd:null, fcp:p?p.startTime:null});})()"),
                "returnByValue": True})["result"]["value"]
            t = json.loads(t)
            if not t["load"]:  # the load event's end is recorded just after the event: ask again
                time.sleep(0.05)
                t["load"] = b.send("Runtime.evaluate", {"expression": "performance.getEntriesByType('navigation')[0]"
                                                        ".loadEventEnd", "returnByValue": True})["result"]["value"]
            loads.append(t["load"])
            paints.append(t["fcp"])
        text = b.send("Runtime.evaluate", {"expression": "document.body.innerText",
                                           "returnByValue": True})["result"]["value"]
        for want in a.expect:
            if want not in text:
                failures.append("the page does not show %r" % want)
        time.sleep(0.2)  # late console or network events
        failures += problems_of(b.events, url)
        svgs = b.send("Runtime.evaluate", {"expression": "document.querySelectorAll('svg').length",
                                           "returnByValue": True})["result"]["value"]
        if a.screenshot:
            params = {"format": "png"}
            if a.full:
                m = b.send("Page.getLayoutMetrics")
                size = m.get("cssContentSize") or m["contentSize"]
                params.update({"captureBeyondViewport": True,
                               "clip": {"x": 0, "y": 0, "width": size["width"], "height": size["height"], "scale": 1}})
            png = base64.b64decode(b.send("Page.captureScreenshot", params)["data"])
            with open(a.screenshot, "wb") as f:
                f.write(png)
    finally:
        b.close()
    ok_paints = [p for p in paints if p is not None]
    print("%s: %d bytes, %d figures; render: load event end %.0f ms, first contentful paint %s (min of %d)" % (
        a.page, os.path.getsize(a.page), svgs, min(loads), "%.0f ms" % min(ok_paints) if ok_paints else "?", len(loads)))
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
