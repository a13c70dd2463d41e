"""The designer's outputs, child processes and integer options (docs/robustness.md, docs/designer.md):

  --out rules        design --out into the working directory (absolute, ".", ".."), into a folder of
                     the user's files (directly, with a final "/", through a symbolic link): exit 2
                     at once, every file intact; --out DIR/ works; a user's file put into an earlier
                     output survives the next run into it.
  integer options    --seed -1, --seed 18446744073709551616, --seed '', --max-cost 0x2, --max-cost ' 2',
                     --shard +0/4, --threads 1e1: exit 2, one line; controls with plain digits work.
  native compile     A compiler that hangs (SPECULA_CXX, a script that sleeps): SIGINT and SIGTERM
                     during the compile end design with 130/143 within 3 s, SIGKILL of specula
                     alone ends the compiler too (its keeper's parent-death signal); no compiler
                     process and no /tmp/specula-design-* folder of the run remain (a killed run's is
                     removed by the next run); SPECULA_COMPILE_TIMEOUT bounds the compile (the run
                     finishes, its note says why the lobes were not timed); SPECULA_CXX naming a
                     missing compiler is exit 2 before any work. The same SIGINT in `report --quick`
                     (full run only).
  server design jobs A design job's status counts the shapes as it screens them (forms_total > 0
                     while screening); the server stopped (SIGTERM) with a design job in its compile
                     leaves no compiler and no scratch folder.
"""
import glob
import json
import os
import signal
import stat
import tempfile
import time

import http_raw
import proc
import serve_cases
from cli_cases import first_line, one_line, rmtree

TINY = ["design", "--max-cost", "1", "--ops", "mul", "-q"]
HANG_MARK = "specula-hostile-hanging-compiler"
STOP_S = 3.0  # a stop during the compile ends the run within this


def hanging_compiler(directory):
    """A 'compiler' that never finishes and, as a compiler driver starts cc1plus, starts a child
    of its own: a bash script (its name the marker) waiting on a long sleep whose argv[0] is the
    marker too, so that a tool killed without its children shows as a leak."""
    path = os.path.join(directory, HANG_MARK)
    with open(path, "w") as f:
        f.write(f"#!/bin/bash\n(exec -a {HANG_MARK} sleep 600) &\nwait\n")
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
    return path


def marked_processes():
    """Pids of the hanging compiler's processes (the script, its marked sleep)."""
    pids = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                if HANG_MARK.encode() in f.read():
                    pids.append(int(entry))
        except OSError:
            pass
    return pids


def kill_marked():
    for pid in marked_processes():
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


def scratch_of(pid):
    return glob.glob(os.path.join(tempfile.gettempdir(), f"specula-design-*{pid}*"))


def wait_for(predicate, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.05)
    return predicate()


def environment(**extra):
    env = dict(os.environ)
    env.update(extra)
    return env


def tree(path):
    """{relative path: bytes} of every file under path."""
    out = {}
    for top, _, files in os.walk(path):
        for name in files:
            full = os.path.join(top, name)
            with open(full, "rb") as f:
                out[os.path.relpath(full, path)] = f.read()
    return out


# ----------------------------------------------------------------------------- --out

def refused(cli, g, args, cwd, user_dir, before, what):
    r = cli.run(args, 20, cwd)
    g.count(r.label(), r.wall, r.rss_mib)
    if r.code != 2 or not one_line(r):
        g.fault("wrong", f"{what}: exit {r.label()}, expected 2 with one line; {first_line(r.stderr)}")
    elif r.wall > 5:
        g.fault("slow", f"{what}: refused only after {r.wall:.1f} s (after the work, not before)")
    if tree(user_dir) != before:
        g.fault("loss", f"{what}: the user's files changed: {sorted(before)} -> {sorted(tree(user_dir))}")


def group_out(cli):
    g = cli.summary.group("design: --out rules")
    work = cli.workdir()
    try:
        user = os.path.join(work, "user")
        os.makedirs(os.path.join(user, "sub"))
        for name, text in (("thesis.tex", "years of work\n"), ("design.csv", "a,b\n"), ("sub/data.bin", "\0\1")):
            with open(os.path.join(user, name), "w") as f:
                f.write(text)
        before = tree(user)
        os.symlink(user, os.path.join(work, "link"))
        base = TINY + ["--no-timing"]
        refused(cli, g, base + ["--out", user], work, user, before, "design --out USER_DIR")
        refused(cli, g, base + ["--out", user + "/"], work, user, before, "design --out USER_DIR/")
        refused(cli, g, base + ["--out", "link"], work, user, before, "design --out LINK_TO_USER_DIR")
        refused(cli, g, base + ["--out", os.path.abspath(user)], user, user, before, 'design --out "$PWD"')
        refused(cli, g, base + ["--out", "."], user, user, before, "design --out .")
        refused(cli, g, base + ["--out", ".."], os.path.join(user, "sub"), user, before, "design --out ..")
        refused(cli, g, ["report", "--quick", "--out", user], work, user, before, "report --out USER_DIR")
        # Controls: a new directory named with a final '/', then a user's file put into that output.
        r = cli.run(base + ["--out", "new/"], 60, work)
        g.count(r.label(), r.wall, r.rss_mib)
        out = os.path.join(work, "new")
        if r.code != 0 or not os.path.isfile(os.path.join(out, "design.json")):
            g.fault("wrong", f"design --out new/: exit {r.label()}, no new/design.json; {first_line(r.stderr)}")
            return
        with open(os.path.join(out, "notes.txt"), "w") as f:
            f.write("mine\n")
        r = cli.run(base + ["--out", "new", "--seed", "2"], 60, work)
        g.count(r.label(), r.wall, r.rss_mib)
        if r.code != 0:
            g.fault("wrong", f"design into its own earlier output: exit {r.label()}; {first_line(r.stderr)}")
        if not os.path.isfile(os.path.join(out, "notes.txt")):
            g.fault("loss", "design --out new: the user's notes.txt in the earlier output was removed")
        stray = [n for n in os.listdir(work) if n not in ("user", "link", "new")]
        if stray:
            g.fault("stray", f"design --out: left {stray[:4]} beside the outputs")
    finally:
        rmtree(work)


# ----------------------------------------------------------------------------- integers

def group_integers(cli):
    g = cli.summary.group("design: integer options")
    bad = [["--seed", "-1"], ["--seed", "18446744073709551616"], ["--seed", ""], ["--max-cost", "0x2"],
           ["--max-cost", " 2"], ["--shard", "+0/4"], ["--shard", "0/ 4"], ["--threads", "1e1"], ["--max-forms", "+5"]]
    for option in bad:
        cli.run_and_judge(g, TINY + ["--no-timing", "--out", "d"] + option, 10, expect=(2,))
    for option in (["--seed", "18446744073709551615"], ["--threads", "1"], ["--shard", "0/4"]):  # controls
        cli.run_and_judge(g, TINY + ["--no-timing", "--out", "d"] + option, 60, expect=(0,), ok_codes=(0,))


# ----------------------------------------------------------------------------- the native compile

def reap_alone(p, seconds):
    """(status, rusage) of p once it exits, within seconds; None if it is still running."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        pid, status, usage = os.wait4(p.pid, os.WNOHANG)
        if pid:
            return status, usage
        time.sleep(0.01)
    return None


def stop_during_compile(cli, g, args, sig, env, expect_codes, what, cap=240):
    """Starts args, waits for the hanging compiler, sends sig to specula alone; judges the end."""
    work = cli.workdir()
    try:
        p, out, err = proc.spawn([cli.specula] + args, work, cli.scratch, env=env)
        run = proc.Run(argv=[cli.specula] + args)
        start = time.monotonic()
        wait_for(lambda: marked_processes() or p.poll() is not None, cap)
        if not marked_processes():
            proc.wait(p, (out, err), run, cap=30)
            g.fault("wrong", f"{what}: the compiler never started (exit {run.label()}; {first_line(run.stderr)})")
            return p.pid
        sent = time.monotonic()
        os.kill(p.pid, sig)
        reaped = reap_alone(p, 30)  # not proc.wait: it kills specula's process group, hiding a leak
        took = time.monotonic() - sent
        leaked = not wait_for(lambda: not marked_processes(), 2.0)
        if reaped:
            proc.finish(p, (out, err), run, reaped[0], reaped[1], start)
        else:
            proc.wait(p, (out, err), run, cap=time.monotonic() - start)
        g.count(run.label(), took, run.rss_mib)
        if sig != signal.SIGKILL and (run.code not in expect_codes):
            g.fault("wrong", f"{what}: exit {run.label()}, expected {'/'.join(map(str, expect_codes))}; "
                             f"{first_line(run.stderr)}")
        if sig != signal.SIGKILL and took > STOP_S:
            g.fault("slow", f"{what}: ended {took:.1f} s after the signal")
        if leaked:
            g.fault("leak", f"{what}: the compiler is still running after specula ended")
        if sig != signal.SIGKILL and scratch_of(p.pid):
            g.fault("stray", f"{what}: left {scratch_of(p.pid)}")
        return p.pid
    finally:
        kill_marked()
        rmtree(work)


def group_compile(cli):
    g = cli.summary.group("design: native compile")
    hang = hanging_compiler(cli.scratch)
    env = environment(SPECULA_CXX=hang)
    args = TINY + ["--out", "d"]
    for sig, codes in ((signal.SIGINT, (130,)), (signal.SIGTERM, (143,))):
        stop_during_compile(cli, g, args, sig, env, codes, f"design, {signal.Signals(sig).name} during the compile")
    killed = stop_during_compile(cli, g, args, signal.SIGKILL, env, (), "design, SIGKILL during the compile")
    # The next run removes the killed run's scratch folder (and finishes, its compile bounded).
    work = cli.workdir()
    try:
        r = proc.run([cli.specula] + args, work, cli.scratch, 120, env=environment(SPECULA_CXX=hang, SPECULA_COMPILE_TIMEOUT="2"))
        g.count(r.label(), r.wall, r.rss_mib)
        if r.code != 0 or b"took over 2 s" not in r.stdout:
            g.fault("wrong", f"design with a hanging compiler and SPECULA_COMPILE_TIMEOUT=2: exit {r.label()}, "
                             f"stdout {r.stdout[-160:]!r}; {first_line(r.stderr)}")
        if scratch_of(killed):
            g.fault("stray", f"the SIGKILLed run's {scratch_of(killed)} was not removed by the next run")
        if marked_processes():
            g.fault("leak", "the timed-out compiler is still running")
    finally:
        kill_marked()
        rmtree(work)
    for bad in ({"SPECULA_CXX": "/nonexistent/c++"}, {"SPECULA_CXX": "no-such-compiler"},
                {"SPECULA_COMPILE_TIMEOUT": "0"}, {"SPECULA_COMPILE_TIMEOUT": "2x"}):
        work = cli.workdir()
        try:
            r = proc.run([cli.specula] + args, work, cli.scratch, 20, env=environment(**bad))
            g.count(r.label(), r.wall, r.rss_mib)
            if r.code != 2 or not one_line(r) or r.wall > 5 or os.listdir(work):
                g.fault("wrong", f"design with {bad}: exit {r.label()} after {r.wall:.1f} s, left {os.listdir(work)}; "
                                 f"expected exit 2 at once; {first_line(r.stderr)}")
        finally:
            rmtree(work)
    if not cli.quick:
        stop_during_compile(cli, g, ["report", "--quick", "--out", "r"], signal.SIGINT, env, (130,),
                            "report --quick, SIGINT during the designer's compile", cap=600)


# ----------------------------------------------------------------------------- the server's design jobs

def job_status(addr, url):
    r = http_raw.get(addr, url, timeout=10.0)
    try:
        return json.loads(r.body)
    except ValueError:
        return {}


def group_server(cli):
    g = cli.summary.group("design: server jobs")
    hang = hanging_compiler(cli.scratch)
    server = serve_cases.Server(cli.specula, cli.scratch, env=environment(SPECULA_CXX=hang))
    try:
        addr = server.start()
    except RuntimeError as e:
        g.fault("crash", f"specula serve: {e}")
        return
    try:
        body = {"range": [1, 100], "ops": "fma,mul,max", "max_cost": 4, "time": 60, "timing": True}
        r = http_raw.post_json(addr, "/api/design", body)
        g.count(str(r.status), r.wall)
        url = json.loads(r.body).get("url") if r.status == 202 else None
        if not url:
            g.fault("wrong", f"POST /api/design: {r.status} {r.body[:120]!r}")
            return
        statuses = []

        def past_screening():
            statuses.append(job_status(addr, url))
            return statuses[-1].get("phase") not in ("starting", "screening shapes")

        wait_for(past_screening, 120)
        screening = [s for s in statuses if s.get("phase") == "screening shapes"]
        if any(s.get("forms_total", 0) <= 0 for s in screening):
            bad = next(s for s in screening if s.get("forms_total", 0) <= 0)
            g.fault("wrong", f"design job status while screening: forms_screened {bad.get('forms_screened')}/"
                             f"{bad.get('forms_total')}")
        if not wait_for(marked_processes, 180):
            g.fault("wrong", "the design job never reached its compile")
        pid = server.p.pid
        stopped = server.stop(signal.SIGTERM, cap=30.0)
        g.count(stopped.label(), stopped.wall)
        if stopped.code not in (0, 143):
            g.fault("wrong", f"SIGTERM with a design compiling: exit {stopped.label()}; {first_line(stopped.stderr)}")
        if not wait_for(lambda: not marked_processes(), 2.0):
            g.fault("leak", "the design job's compiler outlived the server")
        if scratch_of(pid):
            g.fault("stray", f"the stopped server left {scratch_of(pid)}")
    finally:
        if server.p.returncode is None:
            server.stop_now()
        kill_marked()


def run_all(cli):
    group_out(cli)
    group_integers(cli)
    group_compile(cli)
    group_server(cli)

