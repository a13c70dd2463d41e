"""Child processes with a wall-clock cap, a signal at a chosen time and the max RSS (os.wait4).

Every child runs in its own session, so it and anything it starts can be killed as a group;
kill_leftovers() (registered at exit by run.py) SIGKILLs whatever is still alive.
"""
import os
import re
import signal
import subprocess
import time
from dataclasses import dataclass, field

_LIVE = set()  # pids (= process-group ids) of children not yet reaped

STDERR_KEEP = 64 * 1024  # bytes of stderr kept per run
STDOUT_KEEP = 4 * 1024
STDERR_SCAN = 64 << 20  # bytes of stderr scanned for newlines and control characters


@dataclass
class Run:
    argv: list
    code: int = None          # exit code, None when killed by a signal
    signal: int = None        # the signal that ended it, if one did
    wall: float = 0.0         # seconds from spawn to reaping
    rss_mib: float = 0.0      # max resident set size
    stdout: bytes = b""       # first STDOUT_KEEP bytes
    stdout_size: int = 0
    stderr: bytes = b""       # first STDERR_KEEP bytes
    hung: bool = False        # still running at the cap (then SIGKILLed)
    sent: int = None          # the signal we sent, if any
    sent_at: float = None
    extra: dict = field(default_factory=dict)

    def label(self):
        """'0', '2', 'sig9', 'hang'."""
        if self.hung:
            return "hang"
        return f"sig{self.signal}" if self.signal is not None else str(self.code)


def _decode_status(run, status):
    if os.WIFSIGNALED(status):
        run.signal = os.WTERMSIG(status)
    else:
        run.code = os.WEXITSTATUS(status)


def _read_head(f, keep):
    f.seek(0, os.SEEK_END)
    size = f.tell()
    f.seek(0)
    return f.read(keep), size


def _kill_group(pid, sig=signal.SIGKILL):
    try:
        os.killpg(pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def spawn(argv, cwd, scratch, stdin=subprocess.DEVNULL, env=None):
    """Starts argv in its own session; stdout and stderr go to files in `scratch`."""
    out = open(os.path.join(scratch, "stdout"), "w+b")
    err = open(os.path.join(scratch, "stderr"), "w+b")
    p = subprocess.Popen(argv, cwd=cwd, stdin=stdin, stdout=out, stderr=err,
                         start_new_session=True, env=env)
    _LIVE.add(p.pid)
    return p, out, err


def wait(p, files, run, cap, send=None, start=None):
    """Reaps p with os.wait4; sends send=(signal, after_s) once; SIGKILLs the group at cap."""
    start = start if start is not None else time.monotonic()
    delay = 0.001
    while True:
        pid, status, usage = os.wait4(p.pid, os.WNOHANG)
        now = time.monotonic() - start
        if pid:
            break
        if send and run.sent is None and now >= send[1]:
            _kill_group(p.pid, send[0]) if send[0] == signal.SIGKILL else os.kill(p.pid, send[0])
            run.sent, run.sent_at = send[0], now
        if now >= cap and not run.hung:
            run.hung = True
            _kill_group(p.pid)
        time.sleep(delay)
        delay = min(delay * 1.5, 0.02)
    return finish(p, files, run, status, usage, start)


def finish(p, files, run, status, usage, start):
    """Records a reaped child's status, max RSS and output in run."""
    p.returncode = os.waitstatus_to_exitcode(status)  # tell Popen it is reaped
    _LIVE.discard(p.pid)
    _kill_group(p.pid)  # anything it left behind
    run.wall = time.monotonic() - start
    run.rss_mib = usage.ru_maxrss / 1024.0
    _decode_status(run, status)
    out, err = files
    run.stdout, run.stdout_size = _read_head(out, STDOUT_KEEP)
    run.stderr, size = _read_head(err, STDERR_KEEP)
    err.seek(0)
    whole = err.read(STDERR_SCAN)
    run.extra["stderr_lines"] = whole.count(b"\n")
    run.extra["stderr_size"] = size
    run.extra["stderr_control"] = re.search(rb"[\x00-\x09\x0b-\x1f\x7f]", whole) is not None
    run.extra["stderr_ends_in_newline"] = whole.endswith(b"\n")
    out.close()
    err.close()
    return run


def run(argv, cwd, scratch, cap, send=None, stdin=subprocess.DEVNULL, env=None):
    """Runs argv to the end (or the cap); send=(signal, seconds after start) delivers a signal."""
    r = Run(argv=list(argv))
    start = time.monotonic()
    try:
        p, out, err = spawn(argv, cwd, scratch, stdin=stdin, env=env)
    except OSError as e:  # e.g. the binary is missing
        r.code, r.stderr = 127, str(e).encode()
        r.extra["spawn_error"] = True
        return r
    return wait(p, (out, err), r, cap, send=send, start=start)


def kill_leftovers():
    for pid in list(_LIVE):
        _kill_group(pid)
        try:
            os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:
            pass
    _LIVE.clear()
