"""The CLI groups: malformed invocations, bad input files, the specific regressions, special outputs,
kills and signals during long writes, and a killed report.

Each run has a fresh, empty working directory and a cap; judge() turns what happened into
counts and faults (a crash, a hang, a wrong exit code, a multi-line error, a stray file).
"""
import hashlib
import os
import re
import shutil
import signal
import stat
import tempfile
import threading
import time

import pools
import proc
from tally import shown_argv

SIGNAL_CODES = {signal.SIGINT: 130, signal.SIGTERM: 143}
SLOW_REFUSAL_S = 5.0  # bad input must be refused sooner than this


# ----------------------------------------------------------------------------- helpers

def list_tree(top):
    """Every entry under top, relative, directories with a trailing '/', links as 'x -> target'."""
    found = []
    for dirpath, dirnames, filenames in os.walk(top):
        rel = os.path.relpath(dirpath, top)
        for name in sorted(dirnames + filenames):
            path = os.path.join(dirpath, name)
            shown = name if rel == "." else os.path.join(rel, name)
            if os.path.islink(path):
                shown += " -> " + os.readlink(path)
            elif os.path.isdir(path):
                shown += "/"
            found.append(shown)
    return sorted(found)


def top_level(top):
    return sorted(os.listdir(top))


def one_line(r):
    """True when r's stderr is exactly one line ending in \\n, with no other control character."""
    e = r.extra
    return e.get("stderr_lines") == 1 and e.get("stderr_ends_in_newline") and not e.get("stderr_control")


def first_line(stderr, limit=120):
    text = stderr.decode("utf-8", "replace").strip().splitlines()
    line = text[0] if text else "(no stderr)"
    return repr(line[:limit])[1:-1]


def output_names(args):
    """Names that a successful run may leave in its work dir: the -o/--out value, if local."""
    value = None
    for i, a in enumerate(args):
        if a in ("-o", "--out") and i + 1 < len(args):
            value = args[i + 1]
        elif a.startswith("--out="):
            value = a[len("--out="):]
        elif a.startswith("-o") and not a.startswith("-o-"):  # CLI11: -oVALUE, and -o=V is the value "=V"
            value = a[2:]
    if value and "/" not in value and value not in (".", ".."):
        return {value}
    return set()


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def rmtree(path):
    def retry(func, p, _):
        try:
            os.chmod(os.path.dirname(p), 0o700)
            func(p)
        except OSError:
            pass
    shutil.rmtree(path, onerror=retry)


# ----------------------------------------------------------------------------- fixtures

CSV_FIXTURES = {
    "D.csv": "n,coef\n1,0.48274947790782\n2,0.6646892567766716\n3,0.8\n",
    "empty.csv": "",
    "header_only.csv": "n,coef\n",
    "ragged.csv": "n,coef\n1,2,3\n4\n",
    "text.csv": "n,coef\n1,abc\n2,3\n",
    "nan.csv": "n,coef\nnan,1\n2,inf\n",
    "nul.csv": "n,coef\n1\x002,3\n4,5\n",
    "dup_header.csv": "n,n\n1,2\n",
    "no_target.csv": "a,b\n1,2\n",
    "quote.csv": '"n,coef\n1,2\n',
    "crlf.csv": "n,coef\r\n1,2\r\n2,3\r\n",
    "bom.csv": "\ufeffn,coef\n1,2\n2,3\n",
    "long_line.csv": "n,coef\n" + "1" * 1_000_000 + ",2\n",
    "wide.csv": ",".join(f"c{i}" for i in range(100_000)) + ",coef\n",
    "huge_numbers.csv": "n,coef\n1e308,1e308\n-1e308,1e308\n1e-320,0\n",
    "escape.csv": "n,coef\n\x1b[2J,1\n",
    "newlines.csv": "\n\n\n",
    "one_row.csv": "n,coef\n1,2\n",
    "constant.csv": "n,coef\n1,1\n1,1\n1,1\n",
    "header_space.csv": " n , coef \n1,2\n2,3\n",
}
OBJ_FIXTURES = {
    "empty.obj": "",
    "short_vertex.obj": "v 1 2\nf 1 2 3\n",
    "no_vertices.obj": "f 1 2 3\n",
    "nan.obj": "v nan nan nan\nv 0 0 0\nv 1 1 1\nf 1 2 3\n",
    "degenerate.obj": "v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3\n",
    "huge.obj": "v 1e308 1e308 1e308\nv -1e308 0 0\nv 0 1e308 0\nf 1 2 3\n",
    "zero_index.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 0 0\n",
    "relative.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -3\nf -4 -5 -6\n",
    "big_index.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483648\n",
    "slashes.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3 2/3/4 3/4/5\nf 1// //2 3\n",
    "no_faces.obj": "v 0 0 0\n" * 100,
    "polygon.obj": "".join(f"v {i} {i % 7} 0\n" for i in range(1000)) + "f " + " ".join(map(str, range(1, 1001))) + "\n",
    "two_vertex_face.obj": "v 0 0 0\nv 1 0 0\nf 1 2\n",
    "long_line.obj": "v " + "1" * 1_000_000 + " 0 0\n",
    "escape.obj": "v 0 0 0\x1b[2J\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
}


def make_fixtures(top, rng):
    os.makedirs(top)
    paths = {}
    for name, text in {**CSV_FIXTURES, **OBJ_FIXTURES}.items():
        paths[name] = os.path.join(top, name)
        with open(paths[name], "w", encoding="utf-8", newline="") as f:
            f.write(text)
    for name in ("binary.csv", "binary.obj"):
        paths[name] = os.path.join(top, name)
        with open(paths[name], "wb") as f:
            f.write(bytes(rng.randrange(256) for _ in range(4096)))
    paths["rows_over_cap.csv"] = os.path.join(top, "rows_over_cap.csv")
    with open(paths["rows_over_cap.csv"], "w") as f:
        f.write("n,coef\n" + "1,1\n" * 1_000_001)
    paths["a_directory"] = os.path.join(top, "a_directory")
    os.mkdir(paths["a_directory"])
    return paths


# ----------------------------------------------------------------------------- the runner

class Cli:
    def __init__(self, specula, root, rng, quick, summary):
        self.specula, self.root, self.rng, self.quick, self.summary = specula, root, rng, quick, summary
        self.scratch = os.path.join(root, "scratch")
        self.works = os.path.join(root, "work")
        os.makedirs(self.scratch)
        os.makedirs(self.works)
        self.fixture_dir = os.path.join(root, "fixtures")
        self.fixtures = make_fixtures(self.fixture_dir, rng)

    def short_path(self, arg):
        """arg with the run's temporary fixture and model folders as FIXTURES/ and MODELS/."""
        arg = arg.replace(self.fixture_dir + "/", "FIXTURES/")
        model_dir = getattr(self, "model_dir", None)  # (set by model_cases.prepare)
        return arg.replace(model_dir + "/", "MODELS/") if model_dir else arg

    def workdir(self):
        return tempfile.mkdtemp(dir=self.works)

    def run(self, args, cap, cwd, send=None):
        r = proc.run([self.specula] + list(args), cwd, self.scratch, cap, send=send)
        for _ in range(30):  # the binary is being relinked: wait for it (a minute at most)
            if not r.extra.get("spawn_error"):
                break
            time.sleep(2)
            r = proc.run([self.specula] + list(args), cwd, self.scratch, cap, send=send)
        return r

    def judge(self, g, r, work, cap, expect=(0, 1, 2), outputs=(), ok_codes=(0,), sent=None):
        """Counts r in g and records what went wrong; returns the top-level names left in work."""
        g.count(r.label(), r.wall, r.rss_mib)
        what = "specula " + shown_argv([self.short_path(a) for a in r.argv[1:]])
        if r.wall >= g.worst_wall:
            g.note = f"slowest: {what[:110]} ({r.wall:.1f} s)"
        if r.code == 2 and r.wall > SLOW_REFUSAL_S:
            g.fault("slow", f"{what}: refused (exit 2) only after {r.wall:.1f} s")
        if r.hung:
            g.fault("hang", f"{what}: still running after {cap:g} s (killed)")
        elif r.signal is not None and r.signal != sent:
            g.fault("crash", f"{what}: killed by {signal.Signals(r.signal).name}; {first_line(r.stderr)}")
        elif r.code is not None and r.code not in expect:
            kind = "crash" if r.code >= 3 else "wrong"
            g.fault(kind, f"{what}: exit {r.code}, expected {'/'.join(map(str, expect))}; {first_line(r.stderr)}")
        if r.code == 2 and not one_line(r):
            e = r.extra
            g.fault("lines", f"{what}: exit 2 with {e.get('stderr_lines')} stderr lines"
                             f"{' and raw control characters' if e.get('stderr_control') else ''}: "
                             f"{r.stderr[:160]!r}")
        left = top_level(work)
        allowed = set(outputs) if r.code in ok_codes else set()
        stray = [n for n in left if n not in allowed]
        if stray:
            g.fault("stray", f"{what}: exit {r.label()} left {', '.join(repr(s) for s in stray[:4])}")
        return left

    def run_and_judge(self, g, args, cap, expect=(0, 1, 2), ok_codes=(0,)):
        work = self.workdir()
        try:
            r = self.run(args, cap, work)
            self.judge(g, r, work, cap, expect=expect, outputs=output_names(args), ok_codes=ok_codes)
            if any(a.startswith("/dev/") for a in args):
                guard_devices(g, "specula " + shown_argv(args))
            return r
        finally:
            rmtree(work)


# ----------------------------------------------------------------------------- malformed invocations

RANDOM_ALPHABET = "abcxyz0123456789.:,@-+eE \t\n\r\x1b[]{}\"'\\/%$é\udcff"
ALIASES = {"-m": "--model", "-p": "--param", "-o": "--out", "-c": "--cos", "-t": "--theta", "-r": "--reference"}
UNKNOWN = ["--bogus", "-Z", "--model-", "---", "extra", "--=", "-" + "x" * 100, "--help=x", "-", "--"]
COUNTS = {"eval": 40, "normalize": 30, "albedo": 25, "check": 25, "error": 25, "fit": 30, "render": 30,
          "compare": 15, "glsl": 20, "export": 20, "models": 10, "bench": 4,
          "lut": 12, "sample": 10, "check --sampling": 12, "render --env": 10, "design": 25}
CAPS = {"bench": 60, "serve": 5, "design": 120}


def random_string(rng):
    return "".join(rng.choice(RANDOM_ALPHABET) for _ in range(rng.randint(1, 24)))


def pick(rng, pool):
    roll = rng.random()
    if roll < 0.6:
        return rng.choice(pool)
    return rng.choice(pools.COMMON) if roll < 0.9 else random_string(rng)


def set_option(rng, args, opt, value):
    names = {opt, ALIASES.get(opt, opt)} | {k for k, v in ALIASES.items() if v == opt}
    for i, a in enumerate(args[:-1]):
        if a in names:
            args[i + 1] = value
            return
    args.extend([f"{opt}={value}"] if rng.random() < 0.15 else [opt, value])


def drop_option(rng, args):
    options = [i for i, a in enumerate(args) if a.startswith("-")]
    if options:
        i = rng.choice(options)
        has_value = i + 1 < len(args) and not args[i + 1].startswith("-")
        del args[i:i + 2 if has_value else i + 1]


def mutated(rng, base, options, flags):
    args = list(base)
    for _ in range(rng.choices([1, 2, 3], [70, 25, 5])[0]):
        kind = rng.choices(["set", "drop", "unknown", "flag", "twice"], [75, 8, 8, 5, 4])[0]
        if kind == "set":
            opt = rng.choice(sorted(options))
            set_option(rng, args, opt, pick(rng, options[opt]))
        elif kind == "drop":
            drop_option(rng, args)
        elif kind == "unknown":
            args.append(rng.choice(UNKNOWN))
        elif kind == "flag":
            args.append((rng.choice(flags) if flags else "--help") + "=" + pick(rng, pools.COMMON))
        else:
            opt = rng.choice(sorted(options))
            args += [opt, pick(rng, options[opt]), opt, pick(rng, options[opt])]
    return args


def malformed_cases(rng, fixtures, scale):
    specs = pools.commands(fixtures)
    cases = [[name, "--help"] for name in list(specs) + ["report", "serve"] if " " not in name]
    for name, count in COUNTS.items():  # ("check --sampling" is check with --sampling in its base)
        base, options, flags = specs[name]
        cases += [name.split()[:1] + mutated(rng, base, options, flags) for _ in range(max(1, round(count * scale)))]
    cases += [["report"] + c for c in pools.REPORT_CASES]
    cases += [["serve"] + c for c in pools.SERVE_CASES]
    cases += [[], ["nope"], ["--bogus"], ["eval\n"], ["\udcff"], ["-" * 3000]]
    return cases


def group_malformed(cli, budget_s):
    g = cli.summary.group("cli: malformed options")
    cases = malformed_cases(cli.rng, cli.fixtures, 0.25 if cli.quick else 1.0)
    deadline = time.monotonic() + budget_s
    for args in cases:
        if time.monotonic() > deadline:
            g.note = f"budget: {g.runs} of {len(cases)}"
            break
        cap = CAPS.get(args[0] if args else "", 20)
        cli.run_and_judge(g, args, cap, ok_codes=(0, 1) if args[:1] == ["check"] else (0,))


# ----------------------------------------------------------------------------- input files

def group_files(cli, budget_s):
    g = cli.summary.group("cli: bad input files")
    fx = cli.fixtures
    csvs = [p for n, p in fx.items() if n.endswith(".csv")] + ["/dev/zero", "/dev/null", fx["a_directory"],
                                                               os.path.join(fx["a_directory"], "missing.csv")]
    objs = [p for n, p in fx.items() if n.endswith(".obj")] + ["/dev/zero", fx["a_directory"]]
    cases = [["fit", "--data", p, "--target", "coef", "--time", "1", "--generations", "5", "-q"] for p in csvs]
    cases += [["render", "-m", "phong", "--scene", p, "--size", "32x32", "-o", "y.png"] for p in objs]
    if cli.quick:
        cases = cases[::3] + [c for c in cases if "/dev/zero" in c]
    deadline = time.monotonic() + budget_s
    for args in cases:
        if time.monotonic() > deadline:
            g.note = f"budget: {g.runs} of {len(cases)}"
            break
        cli.run_and_judge(g, args, 30)


# ----------------------------------------------------------------------------- specific regressions

def group_specific(cli):
    g = cli.summary.group("cli: specific cases")
    data = cli.fixtures["D.csv"]
    fit = ["fit", "--data", data, "--target", "coef", "-q", "--time", "1"]
    cases = [
        (["fit", "--data", data, "--target", "coef", "--max-size", "1", "--time", "2", "-q"], 30, (0,)),
        (fit + ["--islands", "2147483647"], 10, (2,)),
        (fit + ["--population", "1000000"], 10, (2,)),
        (fit + ["--enumerate-size", "2147483647"], 10, (2,)),
        (fit + ["--max-size", "1000"], 10, (2,)),
        (fit + ["--threads", "100000"], 10, (2,)),
        (["check", "--model", "log-normalized", "--n", "1:1e7"], 3, (2,)),
        (["error", "--model", "log", "--n", "1:1e7"], 3, (2,)),
        (["normalize", "--model", "log", "--n", "1:1e7"], 3, (2,)),
        (["check", "--model", "phong", "--pairs", "100000000"], 3, (2,)),
        (["design", "--max-cost", "24", "--max-forms", "10", "--no-timing", "--out", "d", "-q"], 60, (0,)),
        (["design", "--max-cost", "24", "--time", "2", "--no-timing", "--out", "d", "-q"], 120, (0,)),
        (["design", "--range", "n=1:1e13", "--out", "d"], 3, (2,)),
        (["design", "--target", "lambert", "--out", "d"], 3, (2,)),
        (["design", "--shard", "3/2", "--out", "d"], 3, (2,)),
        (["eval", "-m", "log", "--cos", "1", "--coef", "1\n2"], 5, (2,)),
        (["eval", "-m", "lo\ng", "--cos", "1"], 5, (2,)),
        (["eval", "-m", "log", "--cos", "1\r\x1b[2J"], 5, (2,)),
    ]
    for args, cap, expect in cases:
        cli.run_and_judge(g, args, cap, expect=expect)


# ----------------------------------------------------------------------------- special outputs

EVAL = ["eval", "-m", "log", "--cos", "1"]


def expect_csv(g, what, data):
    if not data.startswith(b"cos,value\n"):
        g.fault("wrong", f"{what}: wrote {data[:60]!r}, expected the cos,value table")


DEVICES = {"/dev/null": os.makedev(1, 3), "/dev/full": os.makedev(1, 7)}


def guard_devices(g, what):
    """A run given -o /dev/null or /dev/full must leave them character devices; else restore them."""
    for path, rdev in DEVICES.items():
        try:
            info = os.lstat(path)
            if stat.S_ISCHR(info.st_mode) and info.st_rdev == rdev:
                continue
        except FileNotFoundError:
            pass
        g.fault("wrong", f"{what}: {path} is no longer the character device (restored)")
        try:
            if os.path.lexists(path):
                os.unlink(path)
            os.mknod(path, 0o666 | stat.S_IFCHR, rdev)
            os.chmod(path, 0o666)
        except OSError as e:
            g.fault("wrong", f"cannot restore {path}: {e}")


def output_dev_null(cli, g):
    work = cli.workdir()
    r = cli.run(EVAL + ["-o", "/dev/null"], 10, work)
    cli.judge(g, r, work, 10, expect=(0,))
    guard_devices(g, "specula eval -o /dev/null")
    rmtree(work)


def read_fifo(path, box):
    with open(path, "rb") as f:
        box["data"] = f.read(1 << 20)


def output_fifo(cli, g):
    work = cli.workdir()
    fifo = os.path.join(work, "f")
    os.mkfifo(fifo)
    box = {}
    reader = threading.Thread(target=read_fifo, args=(fifo, box), daemon=True)
    reader.start()
    r = cli.run(EVAL + ["-o", "f"], 10, work)
    cli.judge(g, r, work, 10, expect=(0,), outputs={"f"})
    reader.join(2)
    if reader.is_alive():  # it never opened the FIFO: unblock our reader
        fd = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)
        os.close(fd)
        reader.join(2)
    what = "specula eval -o FIFO"
    if not stat.S_ISFIFO(os.lstat(fifo).st_mode):
        g.fault("wrong", f"{what}: the FIFO was replaced by a regular file")
    expect_csv(g, what + " (read concurrently)", box.get("data", b""))
    rmtree(work)


def output_symlink(cli, g):
    work = cli.workdir()
    with open(os.path.join(work, "target.csv"), "w") as f:
        f.write("old\n")
    link = os.path.join(work, "link.csv")
    os.symlink("target.csv", link)
    r = cli.run(EVAL + ["-o", "link.csv"], 10, work)
    cli.judge(g, r, work, 10, expect=(0,), outputs={"link.csv", "target.csv"})
    what = "specula eval -o SYMLINK"
    if not os.path.islink(link):
        g.fault("wrong", f"{what}: the link was replaced by a regular file")
    with open(os.path.join(work, "target.csv"), "rb") as f:
        expect_csv(g, what + " (its target)", f.read(200))
    rmtree(work)


def output_long_name(cli, g, length):
    work = cli.workdir()
    name = "n" * (length - 4) + ".csv"
    r = cli.run(EVAL + ["-o", name], 10, work)
    cli.judge(g, r, work, 10, expect=(0,), outputs={name})
    path = os.path.join(work, name)
    if os.path.exists(path):
        with open(path, "rb") as f:
            expect_csv(g, f"specula eval -o NAME({length} chars)", f.read(200))
    elif r.code == 0:
        g.fault("wrong", f"specula eval -o NAME({length} chars): exit 0 but no file")
    rmtree(work)


def group_outputs(cli):
    g = cli.summary.group("cli: special outputs")
    output_dev_null(cli, g)
    output_fifo(cli, g)
    output_symlink(cli, g)
    output_long_name(cli, g, 254)
    output_long_name(cli, g, 255)


# ----------------------------------------------------------------------------- kills and signals

class LongWrite:
    """A command writing one big file, and its uninterrupted result."""

    def __init__(self, name, args, out, lines=None):
        self.name, self.args, self.out, self.lines = name, args, out, lines
        self.seconds = None
        self.digest = None

    def reference(self, cli, g):
        work = cli.workdir()
        r = cli.run(self.args, 300, work)
        cli.judge(g, r, work, 300, expect=(0,), outputs={self.out})
        path = os.path.join(work, self.out)
        if r.code == 0 and os.path.isfile(path):
            self.seconds, self.digest = r.wall, sha256(path)
            self.check_lines(g, path, "uninterrupted")
        rmtree(work)

    def check_lines(self, g, path, when):
        if self.lines is None:
            return
        with open(path, "rb") as f:
            n = sum(block.count(b"\n") for block in iter(lambda: f.read(1 << 20), b""))
        if n != self.lines:
            g.fault("wrong", f"specula {shown_argv(self.args)} ({when}): {n} lines, expected {self.lines}")

    def check_left(self, g, work, r, what):
        """The work dir holds nothing or the complete output; returns whether the output is there."""
        path = os.path.join(work, self.out)
        if not os.path.lexists(path):
            return False
        if sha256(path) != self.digest:
            g.fault("wrong", f"{what}: left an incomplete or different {self.out} "
                             f"({os.path.getsize(path)} bytes) after exit {r.label()}")
        return True


def long_writes():
    return [LongWrite("render", ["render", "--model", "ggx", "--size", "3000x3000", "-o", "y.exr"], "y.exr"),
            LongWrite("eval", ["eval", "--model", "log", "--cos", "0:1@3000000", "-o", "e.csv"], "e.csv",
                      lines=3_000_001)]


def interrupted_run(cli, g, job, sig, after):
    """Runs job, sends sig `after` seconds in, and checks the exit code and what was left."""
    work = cli.workdir()
    cap = max(60.0, 4 * job.seconds)
    r = cli.run(job.args, cap, work, send=(sig, after))
    name = signal.Signals(sig).name
    what = f"specula {shown_argv(job.args)} with {name} at {after:.2f} s"
    if sig == signal.SIGKILL:
        expect = (0,)
    else:
        expect = (0, SIGNAL_CODES[sig])
    r.argv = [r.argv[0]] + job.args + [f"[{name}@{after:.2f}s]"]
    cli.judge(g, r, work, cap, expect=expect, outputs={job.out}, ok_codes=(0, None, 130, 143), sent=sig)
    present = job.check_left(g, work, r, what)
    if r.code == 0 and not present:
        g.fault("wrong", f"{what}: exit 0 but no {job.out}")
    if r.code in SIGNAL_CODES.values() and present:
        g.fault("wrong", f"{what}: exit {r.code} but {job.out} was written")
    if r.sent is not None and sig != signal.SIGKILL and r.wall - r.sent_at > 3.0:
        g.fault("slow", f"{what}: took {r.wall - r.sent_at:.1f} s to stop (documented: at most 2 s)")
    rmtree(work)


def group_kills(cli):
    gk = cli.summary.group("cli: SIGKILL mid-write")
    kills = 2 if cli.quick else 10
    jobs = long_writes()
    for job in jobs:
        job.reference(cli, gk)
        if job.digest is None:
            gk.fault("wrong", f"specula {shown_argv(job.args)}: the uninterrupted run failed; its kills skipped")
            continue
        for _ in range(kills):
            interrupted_run(cli, gk, job, signal.SIGKILL, cli.rng.uniform(0.02, 1.1 * job.seconds))
    gs = cli.summary.group("cli: SIGINT/SIGTERM mid-write")
    for job in (j for j in jobs if j.digest is not None):
        for sig in (signal.SIGINT, signal.SIGTERM):
            for _ in range(1 if cli.quick else 3):
                interrupted_run(cli, gs, job, sig, cli.rng.uniform(0.05, 1.1 * job.seconds))


# ----------------------------------------------------------------------------- a killed report

def report_state(path):
    files = list_tree(path) if os.path.isdir(path) else []
    index = os.path.join(path, "index.html")
    return files, (sha256(index) if os.path.isfile(index) else None)


def group_report(cli):
    g = cli.summary.group("cli: report killed")
    work = cli.workdir()
    args = ["report", "--quick", "--out", "R"]
    first = cli.run(args, 300, work)
    cli.judge(g, first, work, 300, expect=(0,), outputs={"R"})
    if first.code != 0 and not os.path.exists(os.path.join(work, "R")):  # a new DIR fails: try an existing one
        os.mkdir(os.path.join(work, "R"))
        first = cli.run(args, 300, work)
        first.argv = first.argv + ["[into an existing, empty R]"]
        cli.judge(g, first, work, 300, expect=(0,), outputs={"R"})
    files, index = report_state(os.path.join(work, "R"))
    if first.code != 0 or index is None:
        g.fault("wrong", "specula report --quick --out R: no complete first report; the kill is skipped")
        rmtree(work)
        return
    after = cli.rng.uniform(0.3, 0.7) * first.wall
    second = cli.run(args, 300, work, send=(signal.SIGKILL, after))
    second.argv = second.argv + [f"[SIGKILL@{after:.1f}s]"]
    staging = [n for n in top_level(work) if re.fullmatch(r"\.R\.specula-\d+", n)]
    cli.judge(g, second, work, 300, expect=(0,), outputs={"R", *staging}, ok_codes=(0, None), sent=signal.SIGKILL)
    what = f"specula report --quick --out R with SIGKILL at {after:.1f} s"
    g.note = f"first run {first.wall:.1f} s; killed at {after:.1f} s" + (
        ", but it had finished" if second.code == 0 else "")
    files2, index2 = report_state(os.path.join(work, "R"))
    if files2 != files:
        g.fault("wrong", f"{what}: R's file list changed ({len(files)} -> {len(files2)} entries; "
                         f"e.g. {sorted(set(files) ^ set(files2))[:3]})")
    if index2 != index:
        g.fault("wrong", f"{what}: R/index.html is not the first report's")
    if staging:
        g.note += f"; the kill left {staging[0]!r} (documented: the next run removes it)"
    rmtree(work)
