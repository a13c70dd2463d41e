"""The lab in a real browser for the scripts of bench/lab: `specula serve` on a free loopback port
and Debian's chromium (headless, SwiftShader WebGL2) under chromedriver, driven through the W3C
WebDriver protocol with the standard library alone (the C++ page tests use tests/serve/webdriver.h)."""
import base64
import contextlib
import json
import socket
import subprocess
import tempfile
import time
import urllib.error
import urllib.parse
import urllib.request


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until(check, seconds=120):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            if check():
                return
        except OSError:
            pass
        time.sleep(0.1)
    raise SystemExit(f"timed out after {seconds} s")


class Browser:
    """One chromium session on the page of one server."""

    def __init__(self, driver_port, server_port, session):
        self.driver_port, self.server_port, self.session = driver_port, server_port, session

    def command(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(f"http://127.0.0.1:{self.driver_port}/session/{self.session}{path}", data=data,
                                         method=method, headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=300) as answer:
                return json.loads(answer.read())["value"]
        except urllib.error.HTTPError as e:
            raise SystemExit(f"webdriver {method} {path}: {json.loads(e.read())['value'].get('message', '')[:300]}") from None

    def run(self, script, *args):
        return self.command("POST", "/execute/sync", {"script": script, "args": list(args)})

    def open(self, state):
        """The page in `state` (the URL's state), once it says ready."""
        url = f"http://127.0.0.1:{self.server_port}/#" + urllib.parse.urlencode({"state": json.dumps(state)})
        self.command("POST", "/url", {"url": url})
        self.wait("return document.getElementById('status').textContent === 'ready';")

    def wait(self, condition, seconds=120):
        wait_until(lambda: self.run(condition), seconds)

    def screenshot(self, css):
        """The PNG bytes of the element `css` selects, scrolled into view."""
        element = self.command("POST", "/element", {"using": "css selector", "value": css})
        self.run("arguments[0].scrollIntoView();", element)
        return base64.b64decode(self.command("GET", f"/element/{next(iter(element.values()))}/screenshot"))


@contextlib.contextmanager
def lab(specula, width=1400, height=1000):
    """A Browser on a fresh server; both stop on leaving."""
    server_port, driver_port = free_port(), free_port()
    server = subprocess.Popen([specula, "serve", "--port", str(server_port)], stdout=subprocess.DEVNULL)
    driver = subprocess.Popen(["chromedriver", f"--port={driver_port}"], stdout=subprocess.DEVNULL)
    try:
        with tempfile.TemporaryDirectory() as profile:
            status = lambda: json.loads(urllib.request.urlopen(f"http://127.0.0.1:{driver_port}/status").read())["value"]["ready"]
            wait_until(status)
            flags = ["--headless", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                     f"--window-size={width},{height}", f"--user-data-dir={profile}"]
            capabilities = {"capabilities": {"alwaysMatch": {"browserName": "chrome", "goog:chromeOptions": {
                "binary": "/usr/bin/chromium", "args": flags}}}}
            request = urllib.request.Request(f"http://127.0.0.1:{driver_port}/session", data=json.dumps(capabilities).encode(),
                                             method="POST", headers={"Content-Type": "application/json"})
            session = json.loads(urllib.request.urlopen(request, timeout=120).read())["value"]["sessionId"]
            browser = Browser(driver_port, server_port, session)
            try:
                yield browser
            finally:
                browser.command("DELETE", "")
    finally:
        driver.terminate()
        server.terminate()
