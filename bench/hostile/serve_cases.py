"""The server groups: `specula serve --port 0` on loopback, a monitor GETting /api/models every
250 ms throughout, and bad requests of every kind; finally SIGTERM with work in flight.

Every answer must be < 500 (503 is documented: stopping, or a request past its deadline) and
every error answer a JSON object with an "error" key.
"""
import json
import os
import random
import signal
import socket
import threading
import time

import http_raw
import model_fixtures
import proc
import serve_models
from tally import shown

POST_ENDPOINTS = ["/api/eval", "/api/normalize", "/api/albedo", "/api/check", "/api/error", "/api/glsl", "/api/fit",
                  "/api/design"]
SLOW_S = 2.0  # a GET /api/models slower than this is a fault
HEAVY = {"model": "ggx", "step": 0.01, "pairs": 1}
ENDLESS_FIT = {"model": "log", "ops": "+", "max_size": 1, "time": 2}


# ----------------------------------------------------------------------------- the server and its monitor

class Server:
    def __init__(self, specula, scratch, pre=(), env=None):
        self.specula, self.scratch, self.pre = specula, scratch, list(pre)  # pre: --models FILE ...
        self.env = env  # None: the hostile run's own
        self.p = None
        self.addr = None

    def start(self, timeout=30.0):
        self.run = proc.Run(argv=[self.specula, "serve", "--port", "0"])
        self.p, out, err = proc.spawn([self.specula] + self.pre + ["serve", "--host", "127.0.0.1", "--port", "0"],
                                      None, self.scratch, env=self.env)
        self.files = (out, err)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            out.seek(0)
            line = out.readline()
            if line.endswith(b"\n"):
                return self._address(line)
            if self.dead():
                break
            time.sleep(0.02)
        raise RuntimeError(f"specula serve printed no 'serving' line: {self.stop_now()}")

    def _address(self, line):
        text = line.decode(errors="replace").strip()
        if not text.startswith("serving http://"):
            raise RuntimeError(f"unexpected first line {text!r}")
        host, port = text[len("serving http://"):].rstrip("/").rsplit(":", 1)
        self.addr = (host.strip("[]"), int(port))
        return self.addr

    def dead(self):
        """Whether the server has exited (reaping it, if so)."""
        if self.p.returncode is not None:
            return True
        pid, status, usage = os.wait4(self.p.pid, os.WNOHANG)
        if pid:
            proc.finish(self.p, self.files, self.run, status, usage, time.monotonic())
        return bool(pid)

    def stop(self, sig=signal.SIGTERM, cap=10.0):
        """Sends sig and reaps the server; the Run's wall is the time from the signal to the exit."""
        if self.p.returncode is not None:
            return self.run
        return proc.wait(self.p, self.files, self.run, cap, send=(sig, 0.0), start=time.monotonic())

    def stop_now(self):
        r = self.stop(signal.SIGKILL, 5.0)
        return f"exit {r.label()}: {r.stderr[:200]!r}"


class Monitor(threading.Thread):
    """GET /api/models every 250 ms on a fresh connection; the worst latency of each phase."""

    def __init__(self, addr):
        super().__init__(daemon=True)
        self.addr = addr
        self.phase = "start"
        self.done = threading.Event()
        self.samples = []  # (phase, seconds, ok, error)

    def run(self):
        while not self.done.is_set():
            phase = self.phase
            r = http_raw.get(self.addr, "/api/models", timeout=15.0)
            ok = r.status == 200 and _json_list(r.body)
            if self.phase == "shutdown":  # the server may have stopped under this request
                phase = "shutdown"
            self.samples.append((phase, r.wall, ok, r.error or (None if ok else f"status {r.status}")))
            self.done.wait(max(0.0, 0.25 - r.wall))

    def stop(self):
        self.done.set()
        self.join(20)


def _json_list(body):
    try:
        return isinstance(json.loads(body), list)
    except ValueError:
        return False


# ----------------------------------------------------------------------------- judging answers

def judge(g, label, resp, expect=None, must_answer=True, head=False):
    """Counts resp in g; faults: a 5xx other than 503, a bad error body, no answer, an unexpected status."""
    if resp.status is None:
        g.count("drop", resp.wall)
        if must_answer:
            kind = "hang" if "timed out" in (resp.error or "") or "deadline" in (resp.error or "") else "wrong"
            g.fault(kind, f"{label}: no answer after {resp.wall:.1f} s ({resp.error})")
        return
    g.count(resp.status, resp.wall)
    if resp.status >= 500 and resp.status != 503:
        g.fault("500", f"{label}: status {resp.status}: {resp.body[:120]!r}")
    if resp.status >= 400 and not head and not http_raw.error_body_ok(resp.body):
        g.fault("body", f"{label}: status {resp.status} with a body that is not a JSON error: {resp.body[:100]!r}")
    if expect and resp.status not in expect and not (resp.status >= 500):
        g.fault("wrong", f"{label}: status {resp.status}, expected {'/'.join(map(str, expect))}: {resp.body[:100]!r}")


def raw_label(raw, limit=90):
    first = raw.split(b"\r\n", 1)[0]
    return shown(first, limit)


# ----------------------------------------------------------------------------- paths

TRAVERSALS = ["/%c0%ae%c0%ae/etc/passwd", "/../../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd",
              "/..%2f..%2f..%2fetc/passwd", "/%2e%2e%2f%2e%2e%2fetc%2fpasswd", "//etc/passwd", "/etc/passwd",
              "/./app.js/../../etc/passwd", "/app.js%00.html", "/app.js/", "/%252e%252e/etc/passwd",
              "/..\\..\\etc\\passwd", "/web/app.js", "/index.html?../../etc/passwd", "/api/../../etc/passwd",
              "/api/models/../../etc/passwd", "/..%c0%af..%c0%afetc/passwd", "http://127.0.0.1/etc/passwd",
              "/%2E%2E/%2E%2E/proc/self/environ", "file:///etc/passwd"]
ODD_PATHS = [b"/\xff\xfe", b"/\xc0\xae\xc0\xae/etc/passwd", b"/api/\xed\xa0\x80", b"/%ff%fe", b"/%", b"/%zz",
             b"/%0d%0aSet-Cookie:x=1", b"/\x7f", b"/api/models\x00", b"/a b", b"/\x1b[2J", b"*", b"",
             b"/api", b"/api/", b"/api/models/", b"/api/models?x=1", b"/API/MODELS", b"/api/fit", b"/api/fit/",
             b"/api/fit/0", b"/api/fit/-1", b"/api/fit/abc", b"/api/fit/1e3", b"/api/fit/99999999999999999999",
             b"/api/fit/9223372036854775807", b"/api/fit/1/", b"/api/fit/%31", b"/api/eval", b"/api/nope",
             b"/", b"/index.html", b"/app.js", b"/style.css", b"/favicon.ico", b"/api/models#x",
             b"/" + b"a" * 8000, b"/" + b"a" * 70000, b"/api/" + b"%41" * 5000, b"/?" + b"a=b&" * 5000,
             b"/" + b"a/" * 20000]
PATH_ALPHABET = [b"a", b"/", b"%", b"%2e", b"%2f", b"..", b".", b"%00", b"%c0%ae", b"\xff", b"\xc3\xa9", b"api",
                 b"fit", b"models", b"?", b"#", b"=", b"&", b";", b"~", b"\\", b"%25", b"1", b"-"]


def random_path(rng):
    return b"/" + b"".join(rng.choice(PATH_ALPHABET) for _ in range(rng.randint(1, 30)))


def group_paths(ctx, g, count):
    paths = [p.encode() for p in TRAVERSALS] + ODD_PATHS + [random_path(ctx.rng) for _ in range(count)]
    for path in paths:
        raw = http_raw.request_bytes(b"GET", path)
        r = http_raw.exchange(ctx.addr, raw)
        label = raw_label(raw)
        wellformed = 0 < len(path) < 8000 and all(0x20 < b < 0x7F for b in path)
        judge(g, label, r, must_answer=wellformed)
        if b"root:" in r.body or b"PATH=" in r.body:
            g.fault("wrong", f"{label}: the answer holds a system file: {r.body[:60]!r}")


# ----------------------------------------------------------------------------- methods and framing

METHODS = ["FOO", "PROPFIND", "TRACE", "CONNECT", "HEAD", "PUT", "PATCH", "OPTIONS", "DELETE", "get", "POST",
           "A" * 1000, "GE\x01T", "\udcff", "M-SEARCH"]
BODY_METHODS = ("POST", "PUT", "PATCH")  # sent with Content-Length: 0 (see NO_LENGTH for without)
METHOD_PATHS = ["/", "/api/models", "/api/eval", "/api/fit/1", "/app.js"]
FRAMING = [
    b"\r\n\r\n", b"GET\r\n\r\n", b"GET /\r\n\r\n", b"GET / HTTP/9.9\r\n\r\n", b"GET / HTTP/1.1\r\n\r\n",
    b"GET / HTTP/1.1\r\nHost\r\n\r\n", b"GET / HTTP/1.1\r\nHost: x\r\nX: " + b"a" * 100_000 + b"\r\n\r\n",
    b"GET / HTTP/1.1\r\nHost: x\r\n" + b"X-A: b\r\n" * 1000 + b"\r\n", b"GET / HTTP/1.1\r\nHost: x\r\n folded\r\n\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: 5\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: -1\r\n\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: abc\r\n\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: 2\r\nContent-Length: 3\r\n\r\n{}",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: 99999999999999999999999\r\n\r\n{}",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n{}\r\n0\r\n\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\nffffffffffffffff\r\n{}\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n2\r\n{}\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: gzip, chunked\r\n\r\n0\r\n\r\n",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Encoding: gzip\r\nContent-Length: 4\r\n\r\n\x1f\x8b\x08\x00",
    b"POST /api/eval HTTP/1.1\r\nHost: x\r\n\r\n{\"model\":\"log\",\"cos\":1}",
    b"GET / HTTP/1.1\nHost: x\n\n", b"GET / HTTP/1.1\r\nHost: \x00x\r\n\r\n", b"G", b"",
    b"GET / HTTP/1.1\r\nHost: x\r\nExpect: 100-continue\r\nContent-Length: 10\r\n\r\n",
    b"GET / HTTP/1.1\r\nHost: x\r\nUpgrade: h2c\r\nConnection: Upgrade, HTTP2-Settings\r\n\r\n",
    b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n", b"\x16\x03\x01\x00\xa5\x01\x00\x00\xa1\x03\x03" + b"\x00" * 64,
    b"GET /api/models HTTP/1.1\r\nHost: x\r\n\r\nGET /api/models HTTP/1.1\r\nHost: x\r\n\r\n" * 50,
]


def group_methods(ctx, g):
    for method in METHODS:
        for path in METHOD_PATHS:
            raw = http_raw.request_bytes(method, path, body=b"" if method in BODY_METHODS else None)
            head = method == "HEAD"
            r = http_raw.exchange(ctx.addr, raw, head_only=head)
            wellformed = method.isalpha() and method.isupper() and len(method) < 100
            judge(g, raw_label(raw), r, must_answer=wellformed and method != "CONNECT", head=head)
    for raw in FRAMING:  # many are incomplete: half-close, so that the server sees the end at once
        r = http_raw.exchange(ctx.addr, raw, half_close=True, total=15.0)
        judge(g, raw_label(raw) or "(empty)", r, must_answer=False)
    no_length(ctx, g)


NO_LENGTH = [http_raw.request_bytes("POST", "/api/eval"), http_raw.request_bytes("PUT", "/")]


def no_length(ctx, g):
    """A POST or PUT with neither Content-Length nor chunking has no body (RFC 9112 6.3): answer at once."""
    results = [None] * len(NO_LENGTH)

    def send(i):
        results[i] = http_raw.exchange(ctx.addr, NO_LENGTH[i], timeout=15.0, total=15.0)
    threads = [threading.Thread(target=send, args=(i,), daemon=True) for i in range(len(NO_LENGTH))]
    for t in threads:
        t.start()
    for t in threads:
        t.join(20)
    for raw, r in zip(NO_LENGTH, results):
        label = raw_label(raw) + " without Content-Length"
        r = r or http_raw.Resp(error="timed out")
        judge(g, label, r)
        if r.wall > 2.0:
            g.fault("slow", f"{label}: answered {r.status} only after {r.wall:.1f} s (it waited for a body)")


# ----------------------------------------------------------------------------- JSON bodies

BASES = {
    "/api/eval": {"model": "log", "cos": "0:1@5"},
    "/api/normalize": {"model": "log", "n": [1, 2]},
    "/api/albedo": {"model": "log-normalized", "params": {"n": 20}, "theta": "0,45"},
    "/api/check": {"model": "phong", "n": [1, 20], "pairs": 100, "step": 5},
    "/api/error": {"model": "log", "n": "1:3"},
    "/api/glsl": {"model": "ggx"},
    "/api/fit": {"model": "log", "n": "1:5", "time": 1, "generations": 5},
    "/api/design": {"range": [1, 10], "ops": "fma", "max_cost": 1, "time": 1, "timing": False},
}
KEYS = {
    "/api/eval": ["model", "params", "form", "coef", "cos", "lobe", "theta_i", "theta_o", "phi_o"],
    "/api/normalize": ["model", "params", "form", "n", "method", "compare", "condition", "step"],
    "/api/albedo": ["model", "params", "form", "coef", "theta", "method", "samples", "seed"],
    "/api/check": ["model", "params", "form", "coef", "n", "sweep", "values", "pairs", "seed", "step", "grazing"],
    "/api/error": ["model", "params", "reference", "n", "zone"],
    "/api/glsl": ["model", "params", "form", "coef", "dialect", "shader", "light", "size"],
    "/api/fit": ["data", "model", "params", "form", "n", "round", "ops", "constants", "size_weights", "metric",
                 "choose", "max_size", "seed", "generations", "population", "islands", "enumerate_size",
                 "test_fraction"],
    "/api/design": ["target", "params", "form", "param", "range", "objective", "zone", "ops", "max_cost", "max_forms",
                    "time", "seed", "timing"],
}
JSON_VALUES = [None, True, False, 0, -1, 1e308, -1e308, 2147483648, 9223372036854775808, 1e-320, "", "nan", "inf",
               "1:1e7", "1:", "a:b@c", "paper50", "1:1000000000", [], [None], [1e308], ["x"], {}, {"n": "x"},
               "x" * 5000, list(range(10001)), "\u0000\u001b[2J", "log\n", "nope", "ggx", "lambert",
               "cook-torrance-1982", {"n": -1}, {"alpha": 0}, {"n": 1e308}, [0, 0, 0], [1, 1], [2049, 2049],
               [[1]], 1.5, -0.0, "1e999", {"columns": {"n": [1, 2]}, "target": "n"},
               {"columns": {"n": [1, 2], "c": [1, 2]}, "target": "c", "vars": "n"}, {"columns": "x"},
               # definition objects (cheap ones: a mutated body must not hit the deadline)
               {"kind": "lobe", "form": "rv", "lobe": "c^n", "normalization": "none",
                "params": {"n": {"default": 2, "min": 0, "max": 10}}}, {"kind": "brdf", "brdf": "nl"},
               {"kind": "lobe"}, {"lobe = \"c\"\n[[model]]\nid": "x"}, {"kind": "brdf", "brdf": "nl", "let": [1, None, {}]},
               {"kind": "brdf", "brdf": "nl", "params": {"a\"]\n[x": {"default": 1, "min": 0, "max": 2}}},
               {"kind": "brdf", "brdf": "rho", "name": model_fixtures.HOSTILE_TEXTS[0],
                "params": {"rho": {"default": 1, "min": 0, "max": 2, "meaning": model_fixtures.HOSTILE_TEXTS[4]}}},
               {"kind": "lobe", "form": "nh", "lobe": "c^n", "normalization": "(n+2)/(2*pi)", "params": []},
               {"kind": "brdf", "brdf": "nl", "id": "ggx"}, {"kind": "brdf", "brdf": "nl", "id": "x+ms"},
               {"kind": "brdf", "brdf": "nl", "params": {"n": None}}, {"kind": ["brdf"], "brdf": {"a": 1}}]
MALFORMED = [b"", b"{", b"}", b"[", b"[]", b"null", b"1", b'"x"', b"{'model':'log'}", b'{"model":"log",}',
             b'{"model":"log"', b"\xff\xfe", b'{"model":"\xff"}', b'{"a":NaN}', b'{"a":Infinity}',
             b'{"model":"log"}garbage', b"\x00", b"[" * 30000 + b"]" * 30000, b'{"a":' * 10000 + b"1" + b"}" * 10000,
             b"x" * 70000, b"\xef\xbb\xbf{}", b"/*x*/{}", b'{"n":1e999}',
             b'{"model":"\\ud800"}', b'{"model":"log","n":01}', b'{"model":"log","n":-}', b'{"model":"log","n":.5}',
             b'{"model":"log","n":0x10}', b"\t\n  ", b'{"model":"log"}\x00', b'[{"model":"log"}]']
BAD_JSON_EXPECT = (400, 413)
LENIENT = [b'{"model":"log","model":"ggx"}', b'{"model":"ggx","params":{"alpha":0.2,"alpha":0.3}}']  # any < 500


def body_variant(rng, endpoint):
    """A mutation of the endpoint's cheap valid body: values replaced, keys added or removed."""
    body = dict(BASES[endpoint])
    for _ in range(rng.choices([1, 2, 3], [60, 30, 10])[0]):
        roll = rng.random()
        if roll < 0.7:
            body[rng.choice(KEYS[endpoint])] = rng.choice(JSON_VALUES)
        elif roll < 0.85:
            body[rng.choice(["nope", "Model", "model ", "", "n\n", "time_s", "__proto__"])] = rng.choice(JSON_VALUES)
        elif body:
            del body[rng.choice(sorted(body))]
    if endpoint in ("/api/fit", "/api/design"):
        body.setdefault("time", 1)
    return body


def cancel_job(ctx, resp):
    """DELETEs a fit or design job the fuzz started, so that it does not hold a slot."""
    try:
        url = json.loads(resp.body)["url"]
        http_raw.get(ctx.addr, url, method="DELETE")
    except (ValueError, KeyError, TypeError):
        pass


def group_bodies(ctx, g, per_endpoint):
    client = http_raw.Client(ctx.addr, timeout=60.0)
    headers = {"Content-Type": "application/json"}
    for endpoint in POST_ENDPOINTS:
        for raw in MALFORMED:  # raw sockets: a server may answer 413 and close before reading it all
            request = http_raw.request_bytes("POST", endpoint, ["Content-Type: application/json"], raw)
            r = http_raw.exchange(ctx.addr, request, total=30.0)
            judge(g, f"POST {endpoint} {shown(raw, 60)}", r, expect=BAD_JSON_EXPECT,
                  must_answer=len(raw) <= 65536)
        for raw in LENIENT:
            r = client.request("POST", endpoint, raw, headers)
            judge(g, f"POST {endpoint} {shown(raw, 60)}", r)
            if r.status == 202:
                cancel_job(ctx, r)
        for _ in range(per_endpoint):
            body = body_variant(ctx.rng, endpoint)
            data = json.dumps(body).encode()
            r = client.request("POST", endpoint, data, headers)
            judge(g, f"POST {endpoint} {shown(data, 120)}", r)
            if r.status == 202:
                cancel_job(ctx, r)
    client.close()


# ----------------------------------------------------------------------------- Range, Content-Length

def group_ranges(ctx, g):
    sizes = []
    for path in ("/app.js", "/api/models"):
        own = http_raw.exchange(ctx.addr, http_raw.request_bytes("GET", path))
        judge(g, f"GET {path}", own, expect=(200,))
        largest = 0
        variants = [("0-," * 1500)[:-1], ("0-0," * 1500)[:-1], ("-1," * 1500)[:-1], "0-9", "999999999-"]
        for spec in variants:
            raw = http_raw.request_bytes("GET", path, [f"Range: bytes={spec}"])
            r = http_raw.exchange(ctx.addr, raw, total=30.0)
            label = f"GET {path} with Range: bytes={shown(spec, 24)}"
            judge(g, label, r)
            if r.body_len > own.body_len > 0:
                g.fault("wrong", f"{label}: answered {r.body_len} bytes for a {own.body_len}-byte resource")
            largest = max(largest, r.body_len)
        sizes.append(f"{path} {own.body_len} B: largest answer {largest} B")
    g.note = "; ".join(sizes)


def content_length_case(ctx, g, raw, results, i):
    results[i] = http_raw.exchange(ctx.addr, raw, timeout=15.0, total=15.0)


def group_content_length(ctx, g):
    heads = [b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: 1000000000000\r\n\r\n",
             b"POST /api/fit HTTP/1.1\r\nHost: x\r\nContent-Length: 1000000000000\r\n\r\n",
             b"GET /api/models HTTP/1.1\r\nHost: x\r\nContent-Length: 1000000000000\r\n\r\n",
             b"POST /api/eval HTTP/1.1\r\nHost: x\r\nContent-Length: 65537\r\n\r\n{"]
    expects = [(413,), (413,), (200, 400, 413), (413,)]
    results = [None] * len(heads)
    threads = [threading.Thread(target=content_length_case, args=(ctx, g, raw, results, i), daemon=True)
               for i, raw in enumerate(heads)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(20)
    for raw, r, expect in zip(heads, results, expects):
        body = " (no body)" if raw.endswith(b"\r\n\r\n") else " (1 byte of body)"
        label = raw_label(raw) + " + " + shown(raw.split(b"\r\n")[-3], 40) + body
        r = r or http_raw.Resp(error="timed out")
        judge(g, label, r, expect=expect)
        if r.status is not None and r.wall > 2.0:
            g.fault("slow", f"{label}: answered {r.status} only after {r.wall:.1f} s (it waited for the body)")


# ----------------------------------------------------------------------------- slow clients, heavy requests

def slow_drip(ctx, seconds, outcome, i):
    """One header byte per second; records 'held' or 'closed@Ns' (the server hung up)."""
    start = time.monotonic()
    line = b"GET /api/models HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: " + b"a" * 64
    try:
        sock = socket.create_connection(ctx.addr, timeout=5.0)
    except OSError as e:
        outcome[i] = f"connect-failed ({e})"
        return
    sock.settimeout(1.0)
    try:
        for byte in line[:int(seconds)]:
            sock.sendall(bytes([byte]))
            try:
                if sock.recv(4096) == b"":
                    outcome[i] = f"closed@{time.monotonic() - start:.0f}s"
                    return
            except TimeoutError:
                pass
        outcome[i] = "held"
    except OSError:
        outcome[i] = f"closed@{time.monotonic() - start:.0f}s"
    finally:
        sock.close()


def group_slow_drip(ctx, g, seconds):
    outcome = [None] * 12
    threads = [threading.Thread(target=slow_drip, args=(ctx, seconds, outcome, i), daemon=True) for i in range(12)]
    for t in threads:
        t.start()
    start = time.monotonic()
    for t in threads:
        t.join(seconds + 10)
    for o in outcome:
        g.count(o.split("@")[0] if o else "stuck", time.monotonic() - start)


def heavy_request(ctx, results, i, timeout):
    results[i] = http_raw.post_json(ctx.addr, "/api/check", HEAVY, timeout=timeout)


def start_heavy(ctx, results, timeout):
    threads = [threading.Thread(target=heavy_request, args=(ctx, results, i, timeout), daemon=True)
               for i in range(len(results))]
    for t in threads:
        t.start()
    return threads


def group_heavy(ctx, g, count, timeout):
    """`count` heavy checks at once; those not answered within `timeout` are hangs (left running)."""
    results = [None] * count
    for t in start_heavy(ctx, results, timeout):
        t.join(timeout + 5)
    for r in results:
        judge(g, f"POST /api/check {json.dumps(HEAVY)} (x{count} at once)",
              r or http_raw.Resp(error=f"timed out after {timeout} s", wall=timeout))


# ----------------------------------------------------------------------------- fit jobs

def start_fit(ctx, g, body, expect=(202,)):
    r = http_raw.post_json(ctx.addr, "/api/fit", body)
    judge(g, f"POST /api/fit {json.dumps(body)}", r, expect=expect)
    try:
        return json.loads(r.body)["job"] if r.status == 202 else None
    except (ValueError, KeyError, TypeError):
        g.fault("wrong", f"POST /api/fit {json.dumps(body)}: 202 without a job id: {r.body[:80]!r}")
        return None


def wait_fit(ctx, g, job, limit):
    """Polls the job until it is not running or `limit` seconds passed; returns its last state."""
    deadline = time.monotonic() + limit
    state = None
    while time.monotonic() < deadline:
        r = http_raw.get(ctx.addr, f"/api/fit/{job}")
        judge(g, f"GET /api/fit/{job}", r, expect=(200,))
        try:
            state = json.loads(r.body).get("state")
        except (ValueError, AttributeError):
            state = None
        if state != "running":
            return state
        time.sleep(0.25)
    return state


def delete_fit(ctx, g, job):
    r = http_raw.get(ctx.addr, f"/api/fit/{job}", method="DELETE")
    judge(g, f"DELETE /api/fit/{job}", r, expect=(200,))
    gone = http_raw.get(ctx.addr, f"/api/fit/{job}")
    judge(g, f"GET /api/fit/{job} after DELETE", gone, expect=(404,))


def group_fit(ctx, g):
    jobs = [start_fit(ctx, g, ENDLESS_FIT) for _ in range(2)]
    for job in filter(None, jobs):
        state = wait_fit(ctx, g, job, ENDLESS_FIT["time"] + 4)
        if state == "running":
            g.fault("hang", f"POST /api/fit {json.dumps(ENDLESS_FIT)}: still running "
                            f"{ENDLESS_FIT['time'] + 4} s after its start (time budget 2 s)")
    for job in filter(None, jobs):
        delete_fit(ctx, g, job)
    long_fit = {"model": "log", "n": "1:5", "time": 30}
    jobs = [start_fit(ctx, g, long_fit) for _ in range(2)]
    jobs.append(start_fit(ctx, g, long_fit, expect=(429,)))  # a third while two run
    for job in filter(None, jobs):
        delete_fit(ctx, g, job)
    time.sleep(3)
    job = start_fit(ctx, g, {"model": "log", "n": "1:5", "time": 1})
    if job:
        delete_fit(ctx, g, job)


# ----------------------------------------------------------------------------- shutdown

SHUTDOWN_FIT = {"model": "log", "n": "paper50", "time": 60, "generations": 100000}


def group_shutdown(ctx, g, summary):
    """SIGTERM with a heavy check and a fit in flight (the fit was started before the heavy burst)."""
    results = [None]
    heavy = start_heavy(ctx, results, 30.0)[0]
    time.sleep(0.5)
    ctx.monitor.phase = "shutdown"  # its failures from now on are expected
    ctx.monitor.done.set()
    r = ctx.server.stop(signal.SIGTERM, cap=10.0)
    summary.server_exit_s = r.wall
    g.count(f"exit{r.label()}", r.wall, r.rss_mib)
    what = "SIGTERM to specula serve with a heavy check and a fit in flight"
    if r.hung:
        g.fault("hang", f"{what}: still running after 10 s (killed)")
    elif r.signal is not None:
        g.fault("crash", f"{what}: died of {signal.Signals(r.signal).name}")
    elif r.code != 0:
        g.fault("crash" if r.code >= 3 else "wrong", f"{what}: exit {r.code}: {r.stderr[:120]!r}")
    if r.wall > 1.0:
        g.fault("slow", f"{what}: exited after {r.wall:.2f} s (documented: within 1 s)")
    heavy.join(5)
    if results[0] is not None and results[0].status is not None:
        judge(g, "POST /api/check during the shutdown", results[0])


# ----------------------------------------------------------------------------- all of it

class Context:
    def __init__(self, specula, scratch, rng, pre=()):
        self.server = Server(specula, scratch, pre)
        self.rng = rng
        self.addr = None
        self.monitor = None

    def start(self):
        self.addr = self.server.start()
        self.monitor = Monitor(self.addr)
        self.monitor.start()


def check_alive(ctx, g, phase):
    """A server that died is a crash; start a new one so that the other groups still run."""
    if not ctx.server.dead():
        return
    r = ctx.server.stop(signal.SIGKILL, 5.0)
    g.fault("crash", f"specula serve died during {phase}: exit {r.label()}; {r.stderr[-200:]!r}")
    ctx.monitor.stop()
    ctx.start()


def monitor_group(summary, contexts):
    g = summary.group("srv: GET /api/models monitor")
    worst = {}
    for ctx in contexts:
        for phase, seconds, ok, error in ctx.monitor.samples:
            if phase == "shutdown":
                continue
            g.count("200" if ok else "fail", seconds)
            if not ok:
                g.fault("wrong", f"GET /api/models during {phase}: {error} after {seconds:.2f} s")
            if seconds > worst.get(phase, (0,))[0]:
                worst[phase] = (seconds, phase)
    for seconds, phase in worst.values():
        if seconds > SLOW_S:
            g.fault("slow", f"GET /api/models during {phase}: took {seconds:.2f} s (> {SLOW_S:g} s)")
    if worst:
        summary.models_latency = max(worst.values())


def run_groups(ctx, summary, groups):
    for name, body in groups:
        g = summary.group(name)
        ctx.monitor.phase = name
        body(g)
        check_alive(ctx, g, name)


def finish(ctx):
    if ctx.monitor:
        ctx.monitor.stop()
    if ctx.server.p and ctx.server.p.returncode is None and not ctx.server.dead():
        ctx.server.stop_now()


def run_all(specula, scratch, summary, seed, quick, parts=("server", "defs"), model_files=None):
    """The server groups on one server, ending with its SIGTERM; then (part "defs") the groups of
    definition objects and Expect on a server of their own, started with --models (the hostile
    and the copies' model files), so that work they leave behind (a deadline that does not hold)
    cannot make the SIGTERM group fail."""
    contexts = []
    try:
        if "server" in parts:
            ctx = Context(specula, scratch, random.Random(seed + 1))
            contexts.append(ctx)
            ctx.start()
            heavy = 3 if quick else 8
            run_groups(ctx, summary, [
                ("srv: bad paths", lambda g: group_paths(ctx, g, 80 if quick else 400)),
                ("srv: methods, framing", lambda g: group_methods(ctx, g)),
                ("srv: bad JSON bodies", lambda g: group_bodies(ctx, g, 30 if quick else 250)),
                ("srv: Range x1500", lambda g: group_ranges(ctx, g)),
                ("srv: Content-Length 1e12", lambda g: group_content_length(ctx, g)),
                ("srv: 12 slow-drip clients", lambda g: group_slow_drip(ctx, g, 5 if quick else 10)),
                ("srv: fit jobs", lambda g: (group_fit(ctx, g), start_fit(ctx, g, SHUTDOWN_FIT))),  # the last runs on
                (f"srv: {heavy} heavy checks at once", lambda g: group_heavy(ctx, g, heavy, 15 if quick else 30)),
            ])
            group_shutdown(ctx, summary.group("srv: SIGTERM in flight"), summary)
        if "defs" in parts:
            pre = [a for k in ("copies", "hostile") if model_files for a in ("--models", model_files[k])]
            ctx2 = Context(specula, scratch, random.Random(seed + 2), pre)
            contexts.append(ctx2)
            ctx2.start()
            run_groups(ctx2, summary, [
                ("srv: Expect: 100-continue", lambda g: serve_models.group_expect(ctx2, g, judge)),
                ("srv: definition objects", lambda g: serve_models.group_definitions(
                    ctx2, g, summary, quick, judge, cancel_job, with_files=bool(pre))),
            ])
            ctx2.monitor.phase = "shutdown"
            r = ctx2.server.stop(signal.SIGTERM, cap=10.0)
            summary.measures["second server's exit after SIGTERM"] = (
                f"{r.wall:.2f} s, exit {r.label()} (after the definition objects; not judged)")
    finally:
        for c in contexts:
            finish(c)
        monitor_group(summary, contexts)
