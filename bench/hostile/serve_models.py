"""The server groups of the newer surface: definition objects (user models sent in the request)
on every computing route, each answered within the per-request deadline plus a margin, the worst
time per route recorded, /api/glsl's shaders for hostile definitions compiled; and
`Expect: 100-continue` with short, missing, whole and oversized bodies.
"""
import copy
import json
import queue
import socket
import threading
import time

import compilers
import http_raw
import model_fixtures as mf

DEADLINE_S = 5.0       # docs/serve.md: the work of one request
MARGIN_S = 3.0         # an answer later than DEADLINE_S + MARGIN_S is a fault
CLIENT_TIMEOUT_S = 12.0
WORKERS = 3            # requests at once (the server computes 4 at once)

CHEAP = {"kind": "lobe", "form": "rv", "lobe": "max(0, 1 - n*(1-c)/4)^4", "normalization": "none",
         "params": {"n": {"default": 20, "min": 0, "min_exclusive": True, "max": 1e6}}}
QUADRATURE = dict(CHEAP, normalization="quadrature")
CHEAP_BRDF = {"kind": "brdf", "brdf": "rho/pi", "params": {"rho": {"default": 0.5, "min": 0, "max": 1}}}


def route_bodies(d):
    """Bodies that put definition d on each computing route: (route, body)."""
    at = {"theta_i": 30, "theta_o": "0:60:30"} if d.get("kind") == "brdf" else {"cos": "0:1@5"}
    return [
        ("/api/eval", dict({"model": d}, **at)),
        ("/api/normalize", {"model": d, "n": [1, 20]}),
        ("/api/albedo", {"model": d, "theta": "0,45"}),
        ("/api/check", {"model": d, "pairs": 100, "step": 5}),
        ("/api/error", {"model": d, "n": "1:3"}),
        ("/api/glsl", {"model": d, "shader": True}),
        ("/api/fit", {"model": d, "n": "1:5", "time": 1, "generations": 5}),
    ]


def heavy_definitions(quick):
    heavy = {m["id"]: m for m in mf.heavy_models()}
    defs = [("4095-char lobe, quadrature", heavy["long-lobe"]),
            ("sin(1000 n acos c), quadrature", heavy["oscillating"])]
    if not quick:
        defs += [("4094-char BRDF", heavy["long-brdf"]), ("60-deep lobe, quadrature", heavy["deep"])]
    return defs


def cases(quick):
    """(route, body, label, expect): expect None for any status < 500 or 503."""
    out = []
    for route, body in route_bodies(CHEAP):
        out.append((route, body, "a cheap lobe", (202,) if route == "/api/fit" else (200,)))
    for route, body in route_bodies(CHEAP_BRDF):
        if route not in ("/api/normalize", "/api/error", "/api/fit"):
            out.append((route, body, "a cheap BRDF", (200,)))
    defs = heavy_definitions(quick)
    if quick:  # every route once, the heavy definitions in turn
        for k, (route, _) in enumerate(route_bodies(CHEAP)):
            label, d = defs[k % len(defs)]
            out.append((route, dict(route_bodies(d))[route], label, None))
    else:
        for label, d in defs:
            out += [(route, body, label, None) for route, body in route_bodies(d)]
    heavy = {m["id"]: m for m in mf.heavy_models()}
    if quick:
        return out + [("/api/normalize", {"model": QUADRATURE, "n": "1:1e6@2000:log"}, "quadrature, n 1:1e6@2000:log",
                       None)]
    out += [
        ("/api/normalize", {"model": CHEAP, "n": "1:1e6@2000:log"}, "n 1:1e6@2000:log", None),
        ("/api/normalize", {"model": QUADRATURE, "n": "1:1e6@2000:log"}, "quadrature, n 1:1e6@2000:log", None),
        ("/api/normalize", {"model": "log", "n": [1, 2], "compare": heavy["oscillating"]}, "compare: oscillating",
         None),
        ("/api/error", {"model": "log", "n": "1:3", "reference": heavy["oscillating"]}, "reference: oscillating",
         None),
        ("/api/error", {"model": heavy["long-lobe"], "n": "1:1000@2000:log"}, "4095-char lobe, 2000 n", None),
        ("/api/check", {"model": QUADRATURE, "sweep": "n", "values": "1:1e6@50:log", "pairs": 100000},
         "quadrature, 50 n, 1e5 pairs", None),
        ("/api/albedo", {"model": heavy["oscillating"], "theta": "0:89@200", "method": "monte-carlo",
                         "samples": 50000}, "oscillating, 200 angles MC", None),
    ]
    return out


def hostile_glsl_cases(quick):
    """/api/glsl for every hostile model (--quick: every other), the function and the shader."""
    out = []
    for m in mf.hostile_models()[::2 if quick else 1]:
        d = copy.deepcopy(m)
        out.append(("/api/glsl", {"model": d}, f"hostile {m['id']}", (200, 400)))
        out.append(("/api/glsl", {"model": d, "shader": True}, f"hostile {m['id']} shader", (200, 400)))
    return out


def short(body):
    text = json.dumps(body)
    return text if len(text) <= 90 else text[:60] + f"…({len(text)} chars)"


def post(ctx, route, body):
    return http_raw.post_json(ctx.addr, route, body, timeout=CLIENT_TIMEOUT_S)


def file_model_cases():
    """Models of the server's --models files, by id: (route, body, label, expect)."""
    return [
        ("/api/glsl", {"model": "hostile-0", "shader": True}, "file model hostile-0", (200,)),
        ("/api/glsl", {"model": "hostile-3"}, "file model hostile-3", (200,)),
        ("/api/eval", {"model": "hostile-3", "theta_i": 30, "theta_o": "0:60:30"}, "file model hostile-3", (200,)),
        ("/api/normalize", {"model": "my-log", "n": [1, 20]}, "file model my-log", (200,)),
        ("/api/error", {"model": "my-log", "reference": "my-phong", "n": "1:3"}, "file models my-log, my-phong",
         (200,)),
        ("/api/albedo", {"model": "my-ggx", "theta": "0,45"}, "file model my-ggx", (200,)),
        ("/api/check", {"model": "my-ggx+ms", "pairs": 100, "step": 5}, "file model my-ggx+ms", None),
        ("/api/fit", {"model": "my-log", "n": "1:5", "time": 1, "generations": 5}, "file model my-log", (202,)),
    ]


def group_definitions(ctx, g, summary, quick, judge, cancel_job, with_files=False):
    """Definition objects on every computing route (and, with_files, the server's model files by
    id), WORKERS at once: each answered within DEADLINE_S + MARGIN_S (the cheap ones 200); the
    worst per route is recorded."""
    pending = queue.Queue()
    all_cases = cases(quick) + hostile_glsl_cases(quick) + (file_model_cases() if with_files else [])
    for c in all_cases:
        pending.put(c)
    results = []
    lock = threading.Lock()

    def worker():
        while True:
            try:
                route, body, label, expect = pending.get_nowait()
            except queue.Empty:
                return
            r = post(ctx, route, body)
            with lock:
                results.append((route, body, label, expect, r))

    threads = [threading.Thread(target=worker, daemon=True) for _ in range(WORKERS)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(len(all_cases) * (CLIENT_TIMEOUT_S + 2))
    worst = {}
    shaders = []  # (what, key, text, format) of /api/glsl answers
    for route, body, label, expect, r in results:
        what = f"POST {route} {label}: {short(body)}"
        judge(g, what, r, expect=expect)
        if r.status == 202:
            cancel_job(ctx, r)
        if r.status is not None and r.wall > DEADLINE_S + MARGIN_S:
            g.fault("slow", f"POST {route} {label}: answered {r.status} after {r.wall:.1f} s "
                            f"(deadline {DEADLINE_S:g} s + {MARGIN_S:g} s)")
        if r.wall > worst.get(route, (0.0, ""))[0]:
            worst[route] = (r.wall, label)
        if route == "/api/glsl" and r.status == 200:
            shaders += glsl_answer(g, what, r.body)
    for (what, key, text, fmt), err in zip(shaders, compilers.check_exports([(f, t) for _, _, t, f in shaders])):
        if err:
            g.fault("wrong", f"{what}: its {key} does not compile: {err}")
        injected = compilers.injected_lines(text)
        if injected:
            g.fault("wrong", f"{what}: its {key} holds injected text outside a comment: {'; '.join(injected)}")
    summary.measures["definition objects: worst answer per route"] = {k: round(v[0], 2) for k, v in
                                                                      sorted(worst.items())}
    if worst:
        route, (seconds, label) = max(worst.items(), key=lambda kv: kv[1][0])
        g.note = f"worst {route} ({label}) {seconds:.1f} s; {len(results)} requests, {WORKERS} at once"


def glsl_answer(g, what, body):
    """The function and shaders of a /api/glsl answer: [(what, key, text, format)]."""
    try:
        doc = json.loads(body)
    except ValueError:
        g.fault("wrong", f"{what}: 200 with a body that is not JSON: {body[:80]!r}")
        return []
    out = []
    for key, fmt in (("function", "glsl"), ("fragment_shader", "frag"), ("vertex_shader", "vert")):
        if isinstance(doc.get(key), str):
            out.append((what, key, doc[key], fmt))
    return out


# ----------------------------------------------------------------------------- Expect: 100-continue

def _read_head(sock, buf, deadline):
    while b"\r\n\r\n" not in buf:
        if time.monotonic() > deadline:
            raise TimeoutError("overall deadline")
        chunk = sock.recv(65536)
        if not chunk:
            raise ConnectionError("closed before a response" + (f" ({len(buf)} bytes)" if buf else ""))
        buf += chunk
    head, _, rest = buf.partition(b"\r\n\r\n")
    return head, rest


def expect_exchange(addr, head, after_100=b"", before=b"", total=15.0):
    """Sends head (+ before), reads an interim 100 (then sends after_100) and the final answer:
    (interim status or None, final http_raw.Resp)."""
    start = time.monotonic()
    resp = http_raw.Resp()
    interim = None
    try:
        sock = socket.create_connection(addr, timeout=total)
    except OSError as e:
        resp.error, resp.wall = f"connect: {e}", time.monotonic() - start
        return interim, resp
    try:
        sock.sendall(head + before)
        deadline = start + total
        raw, rest = _read_head(sock, b"", deadline)
        status, headers = http_raw._parse_head(raw)
        if status == 100:
            interim = 100
            if after_100:
                sock.sendall(after_100)
            raw, rest = _read_head(sock, rest, deadline)
            status, headers = http_raw._parse_head(raw)
        resp.status, resp.headers = status, headers
        length = headers.get("content-length")
        body = rest
        while length and length.isdigit() and len(body) < int(length):
            chunk = sock.recv(65536)
            if not chunk:
                break
            body += chunk
        resp.body, resp.body_len = body, len(body)
    except (OSError, ValueError) as e:
        resp.error = f"{type(e).__name__}: {e}"
    finally:
        sock.close()
        resp.wall = time.monotonic() - start
    return interim, resp


EVAL_BODY = json.dumps({"model": "log", "cos": "0:1@3"}).encode()


def expect_cases():
    """(label, head, before, after_100, final statuses accepted, answer within s)."""
    def head(method, path, length, expect="100-continue"):
        lines = [f"{method} {path} HTTP/1.1", "Host: 127.0.0.1", "Content-Type: application/json",
                 f"Expect: {expect}", "Connection: close"]
        if length is not None:
            lines.append(f"Content-Length: {length}")
        return ("\r\n".join(lines) + "\r\n\r\n").encode()
    limit = DEADLINE_S + MARGIN_S
    return [
        ("Expect: 100-continue, Content-Length 100, 10 bytes of body", head("POST", "/api/eval", 100), b"",
         b'{"model":"', (408,), limit),
        ("Expect: 100-continue, Content-Length 100, no body", head("POST", "/api/eval", 100), b"", b"", (408,), limit),
        ("Expect: 100-continue, the whole body after the 100", head("POST", "/api/eval", len(EVAL_BODY)), b"",
         EVAL_BODY, (200,), 3.0),
        ("Expect: 100-continue, the whole body at once", head("POST", "/api/eval", len(EVAL_BODY)), EVAL_BODY, b"",
         (200,), 3.0),
        ("Expect: 100-continue, Content-Length 1e12", head("POST", "/api/eval", 10 ** 12), b"", b"", (413, 417), 2.0),
        ("Expect: 100-continue on a GET", head("GET", "/api/models", None), b"", b"", (200, 417), 2.0),
        ("Expect: bogus", head("POST", "/api/eval", len(EVAL_BODY), "bogus"), EVAL_BODY, b"", (200, 417), 3.0),
    ]


def group_expect(ctx, g, judge):
    """Expect: 100-continue: a body that never arrives whole is 408 (a JSON error) within the read
    deadline + a margin, never a silent close; a whole body is answered; an oversized one 413/417."""
    specs = expect_cases()
    results = [None] * len(specs)

    def one(i):
        label, head, before, after, _, _ = specs[i]
        results[i] = expect_exchange(ctx.addr, head, after_100=after, before=before)
    threads = [threading.Thread(target=one, args=(i,), daemon=True) for i in range(len(specs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join(20)
    for (label, _, _, _, statuses, within), result in zip(specs, results):
        interim, r = result or (None, http_raw.Resp(error="timed out"))
        what = f"POST /api/eval with {label}" if "GET" not in label else f"GET /api/models with {label}"
        if r.status is None and "closed" in (r.error or ""):
            g.count("closed", r.wall)
            g.fault("wrong", f"{what}: {'100 Continue, then ' if interim else ''}closed without an answer after "
                             f"{r.wall:.1f} s (documented: 408 with a JSON error)")
            continue
        judge(g, what, r, expect=statuses)
        if r.status is not None and r.wall > within:
            g.fault("slow", f"{what}: answered {r.status} after {r.wall:.1f} s (> {within:g} s)")
