"""HTTP/1.1 by hand (raw sockets, for requests http.client refuses to send) and by http.client.

Every call has a per-socket timeout and an overall deadline, keeps at most `keep` bytes of a body
but counts all of it, and reports a dropped connection as status None with the reason.
"""
import http.client
import json
import socket
import time
from dataclasses import dataclass, field

KEEP = 1 << 20


@dataclass
class Resp:
    status: int = None
    headers: dict = field(default_factory=dict)
    body: bytes = b""
    body_len: int = 0
    wall: float = 0.0
    error: str = None


def request_bytes(method, path, headers=(), body=None, close=True):
    """A request as bytes; method/path may be str (UTF-8, surrogates as raw bytes) or bytes."""
    def raw(x):
        return x if isinstance(x, bytes) else x.encode("utf-8", "surrogateescape")
    lines = [raw(method) + b" " + raw(path) + b" HTTP/1.1", b"Host: 127.0.0.1"]
    lines += [raw(h) for h in headers]
    if body is not None:
        lines.append(b"Content-Length: %d" % len(body))
    if close:
        lines.append(b"Connection: close")
    return b"\r\n".join(lines) + b"\r\n\r\n" + (body or b"")


def _parse_head(head):
    lines = head.split(b"\r\n")
    parts = lines[0].split(b" ", 2)
    status = int(parts[1]) if len(parts) > 1 and parts[1].isdigit() else None
    headers = {}
    for line in lines[1:]:
        name, _, value = line.partition(b":")
        headers[name.strip().lower().decode("latin-1")] = value.strip().decode("latin-1")
    return status, headers


def _dechunk(data):
    out, i = b"", 0
    while True:
        end = data.find(b"\r\n", i)
        if end < 0:
            return out
        size = int(data[i:end].split(b";")[0] or b"0", 16)
        if size == 0:
            return out
        out += data[end + 2:end + 2 + size]
        i = end + 2 + size + 2


class _Reader:
    def __init__(self, sock, deadline, keep):
        self.sock, self.deadline, self.keep = sock, deadline, keep
        self.buf = b""
        self.eof = False

    def more(self):
        if time.monotonic() > self.deadline:
            raise TimeoutError("overall deadline")
        chunk = self.sock.recv(65536)
        if not chunk:
            self.eof = True
        return chunk


def read_response(sock, deadline, keep=KEEP, head_only=False):
    r = _Reader(sock, deadline, keep)
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = r.more()
        if not chunk:
            raise ConnectionError("closed before a complete response head" + (f" ({len(data)} bytes)" if data else ""))
        data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    status, headers = _parse_head(head)
    if head_only:
        return status, headers, b"", 0
    length = headers.get("content-length")
    chunked = "chunked" in headers.get("transfer-encoding", "").lower()
    want = int(length) if length and length.isdigit() and not chunked else None
    total, kept = len(body), body[:keep]
    while (want is None or total < want) and not (chunked and kept.endswith(b"0\r\n\r\n")):
        chunk = r.more()
        if not chunk:
            break
        total += len(chunk)
        if len(kept) < keep:
            kept += chunk[:keep - len(kept)]
    if chunked:
        kept = _dechunk(kept)
    return status, headers, kept, total


def exchange(addr, raw, timeout=10.0, total=30.0, keep=KEEP, head_only=False, half_close=False):
    """Sends raw bytes on a new connection and reads one response."""
    start = time.monotonic()
    resp = Resp()
    try:
        sock = socket.create_connection(addr, timeout=timeout)
    except OSError as e:
        resp.error, resp.wall = f"connect: {e}", time.monotonic() - start
        return resp
    try:
        try:
            sock.sendall(raw)
            if half_close:
                sock.shutdown(socket.SHUT_WR)
        except OSError as e:  # the server may have answered and closed early: still read
            resp.error = f"send: {e}"
        resp.status, resp.headers, resp.body, resp.body_len = read_response(
            sock, start + total, keep, head_only)
        resp.error = None
    except (OSError, ValueError) as e:
        resp.error = f"{type(e).__name__}: {e}" if not resp.error else resp.error + f"; {e}"
    finally:
        sock.close()
        resp.wall = time.monotonic() - start
    return resp


class Client:
    """http.client on one keep-alive connection, reconnecting (once) when the server closed it."""

    def __init__(self, addr, timeout=30.0):
        self.addr, self.timeout = addr, timeout
        self.conn = None

    def _connection(self):
        if self.conn is None:
            self.conn = http.client.HTTPConnection(self.addr[0], self.addr[1], timeout=self.timeout)
        return self.conn

    def close(self):
        if self.conn is not None:
            self.conn.close()
            self.conn = None

    def request(self, method, path, body=None, headers=None):
        start = time.monotonic()
        resp = Resp()
        for attempt in (0, 1):
            try:
                conn = self._connection()
                conn.request(method, path, body=body, headers=headers or {})
                answer = conn.getresponse()
                data = answer.read(KEEP + 1)
                resp.status, resp.body, resp.body_len = answer.status, data[:KEEP], len(data)
                resp.headers = {k.lower(): v for k, v in answer.getheaders()}
                resp.error = None
                if answer.will_close:
                    self.close()
                break
            except (http.client.HTTPException, OSError) as e:
                self.close()
                resp.error = f"{type(e).__name__}: {e}"
                if isinstance(e, TimeoutError) or attempt == 1:
                    break
        resp.wall = time.monotonic() - start
        return resp


def post_json(addr, path, body, timeout=30.0):
    data = body if isinstance(body, bytes) else json.dumps(body).encode()
    c = Client(addr, timeout)
    try:
        return c.request("POST", path, data, {"Content-Type": "application/json"})
    finally:
        c.close()


def get(addr, path, timeout=30.0, method="GET"):
    c = Client(addr, timeout)
    try:
        return c.request(method, path)
    finally:
        c.close()


def error_body_ok(body):
    """A valid JSON object with an "error" key."""
    try:
        doc = json.loads(body)
    except ValueError:
        return False
    return isinstance(doc, dict) and "error" in doc
