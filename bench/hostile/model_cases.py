"""The CLI groups of user models and of the newer commands: model files and inline models in
every command, heavy formulas, malformed model files and formulas, M+ms of every model, every
export compiled, the output targets of every command that writes a file, the fit and sampling
regressions, and the documented maxima.

Runs are judged as in cli_cases (exit 0/1/2 only, one-line errors, no stray file, a cap);
the exports that runs wrote are collected in cli.exports and compiled by group_exports.
"""
import json
import os
import re
import signal
import stat
import threading
import time

import compilers
import model_fixtures as mf
from cli_cases import first_line, guard_devices, read_fifo, rmtree
from tally import shown_argv

SLOW_MODEL_S = 10.0   # a command on one user model (even 4095 characters) must end sooner
MODEL_CAP_S = 30.0
HEAVY_CAP_S = 20.0
MS_CAP_S = 30.0       # M+ms: sample 1000, render 16x16, a 4-cell lut, export cpp (the brief's cap)
PROMPT_S = 5.0        # check --sampling of a degenerate BRDF must give its verdict sooner
PROMPT_CAP_S = 15.0
EXPORT_FORMATS = ("cpp", "hlsl", "msl", "brdf")


# ----------------------------------------------------------------------------- running

def prepare(cli, repo):
    """The model files (in the run's temporary root) and the list of exports to compile."""
    cli.model_dir = os.path.join(cli.root, "models")
    cli.model_files = mf.write_model_files(cli.model_dir, repo)
    cli.exports = []
    for name in ("copies", "hostile", "heavy"):  # for the pools of the malformed-options group
        cli.fixtures[name + ".toml"] = cli.model_files[name]


def what_of(cli, args):
    return "specula " + shown_argv([cli.short_path(a) for a in args])


def run_case(cli, g, args, cap=MODEL_CAP_S, expect=(0, 1, 2), ok_codes=(0,), out=None, slow_s=None,
             need=None):
    """Runs args in a fresh work dir; returns (run, bytes of `out` or None). need: exit codes
    required (a valid model must work), slow_s: a fault past this many seconds."""
    work = cli.workdir()
    try:
        r = cli.run(args, cap, work)
        outputs = {out} if out else set()
        cli.judge(g, r, work, cap, expect=expect, outputs=outputs, ok_codes=ok_codes)
        what = what_of(cli, args)
        if need is not None and r.code not in need and not r.hung and r.signal is None:
            g.fault("wrong", f"{what}: exit {r.label()}, expected {'/'.join(map(str, need))}; {first_line(r.stderr)}")
        if slow_s is not None and not r.hung and r.wall > slow_s:
            g.fault("slow", f"{what}: took {r.wall:.1f} s (> {slow_s:g} s)")
        data = None
        if out and r.code in ok_codes and os.path.isfile(os.path.join(work, out)):
            with open(os.path.join(work, out), "rb") as f:
                data = f.read()
        elif out and r.code == 0:
            g.fault("wrong", f"{what}: exit 0 but no {out}")
        if any(a.startswith("/dev/") for a in args):
            guard_devices(g, what)
        return r, data
    finally:
        rmtree(work)


def collect(cli, what, fmt, data):
    """Keeps an export for group_exports: (what, format, text)."""
    if data is not None:
        cli.exports.append((what, fmt, data.decode("utf-8", "surrogateescape")))


class Source:
    """A model as the CLI takes it: global args (--models FILE), the model arg, -p args."""

    def __init__(self, label, model, params=(), files=(), kind="lobe", has_n=True, valid=True, heavy=False):
        self.label, self.model, self.params = label, model, list(params)
        self.files, self.kind, self.has_n, self.valid, self.heavy = list(files), kind, has_n, valid, heavy

    def m(self):
        return ["-m", self.model] + self.params

    def pre(self):
        out = []
        for f in self.files:
            out += ["--models", f]
        return out


def command_table(src):
    """(name, argv, out, format of out, exit codes a valid model needs, ok codes)."""
    m = src.m()
    lobe_n = src.kind == "lobe" and src.has_n
    pairs = [src.params[i:i + 2] for i in range(0, len(src.params), 2)]
    no_n = ["-m", src.model] + [a for p in pairs if not p[1].startswith("n=") for a in p]  # n comes from --n
    table = [
        ("eval", ["eval"] + m + ["--cos", "0:1@5"], None, None, (0,) if src.kind == "lobe" else None, (0,)),
        ("eval directions", ["eval"] + m + ["--theta-i", "30", "--theta-o", "0:60:30"], None, None, (0,), (0,)),
        ("normalize", ["normalize"] + no_n + ["--n", "1,20"], None, None, (0,) if lobe_n else None, (0,)),
        ("albedo", ["albedo"] + m + ["--theta", "0,45"], None, None, (0,), (0,)),
        ("check", ["check"] + m + ["--pairs", "100", "--step", "5"], None, None, (0, 1), (0, 1)),
        ("check --sampling", ["check"] + m + ["--sampling", "--samples", "1000", "--theta-i", "30"], None, None,
         (0, 1), (0, 1)),
        ("error", ["error"] + no_n + ["--n", "1:3"], None, None, (0,) if lobe_n else None, (0,)),
        ("fit", ["fit"] + no_n + ["--n", "1:5", "--time", "1", "--generations", "5", "-q"], None, None,
         (0,) if lobe_n else None, (0,)),
        ("render", ["render"] + m + ["--size", "16x16", "-o", "y.png"], "y.png", None, (0,), (0,)),
        ("render --env", ["render"] + m + ["--env", "white", "--samples", "2", "--size", "16x16", "-o", "y.exr"],
         "y.exr", None, (0,), (0,)),
        ("compare", ["compare", "--models", src.model + ",phong"] + src.params + ["--size", "16x16", "-o", "c.png",
                                                                                 "-q"], "c.png", None, None, (0,)),
        ("glsl", ["glsl"] + m + ["-o", "g.glsl"], "g.glsl", "glsl", (0,), (0,)),
        ("glsl --shader", ["glsl"] + m + ["--shader", "-o", "s.frag"], "s.frag", "frag", (0,), (0,)),
        ("lut", ["lut"] + m + ["--mu", "0.25:1@4", "-q"], None, None, (0,), (0,)),
        ("sample", ["sample"] + m + ["--count", "1000", "--theta-i", "30"], None, None, (0,), (0,)),
    ]
    table += [(f"export {f}", ["export"] + m + ["--format", f, "-o", "e." + f], "e." + f, f, (0,), (0,))
              for f in EXPORT_FORMATS]
    return table


def run_command(cli, g, src, entry, cap=MODEL_CAP_S, slow_s=None):
    name, argv, out, fmt, need, ok_codes = entry
    args = src.pre() + argv
    r, data = run_case(cli, g, args, cap=cap, ok_codes=ok_codes, out=out, slow_s=slow_s,
                       need=need if src.valid else None)
    if fmt:
        collect(cli, f"{src.label}: {name}", fmt, data)
    return r


# ----------------------------------------------------------------------------- sources

def sources(cli):
    p = cli.model_files
    out = [
        Source("file my-log", "my-log", ["-p", "n=50"], [p["copies"]]),
        Source("file my-ggx", "my-ggx", ["-p", "alpha=0.3"], [p["copies"]], kind="brdf", has_n=False),
        Source("file my-lambert", "my-lambert", [], [p["copies"]], kind="brdf", has_n=False),
        Source("hostile lobe", "hostile-0", [], [p["hostile"]], valid=False),
        Source("hostile BRDF", "hostile-3", [], [p["hostile"]], kind="brdf", has_n=False, valid=False),
    ]
    for i, (text, params) in enumerate(mf.INLINE):
        kind = "brdf" if text.startswith("brdf") else "lobe"
        out.append(Source(f"inline {i}", text, params, kind=kind, has_n="n" in text, valid=i < 2))
    return out


def heavy_sources(cli):
    p = cli.model_files
    out = [Source("file long-lobe (4095 chars)", "long-lobe", [], [p["heavy"]], valid=False, heavy=True),
           Source("file long-brdf (4094 chars)", "long-brdf", [], [p["heavy"]], kind="brdf", valid=False,
                  heavy=True),
           Source("file oscillating (quadrature)", "oscillating", [], [p["heavy"]], valid=False, heavy=True),
           Source("file deep", "deep", [], [p["heavy"]], valid=False, heavy=True)]
    for i, (text, params) in enumerate(mf.INLINE_HEAVY):
        out.append(Source(f"inline heavy {i}", text, params, kind=text[:4], valid=False, heavy=True))
    return out


# ----------------------------------------------------------------------------- every command

def budgeted(g, cases, budget_s, run):
    deadline = time.monotonic() + budget_s
    for i, case in enumerate(cases):
        if time.monotonic() > deadline:
            g.note = (g.note + "; " if g.note else "") + f"budget: {i} of {len(cases)} cases"
            return
        run(case)


def group_everywhere(cli, budget_s):
    """Model files and inline models in every command; valid ones must work (exit 0, check 0/1)."""
    g = cli.summary.group("cli: user models in every command")
    srcs = sources(cli)
    cases = [(s, e) for s in srcs for e in command_table(s)]
    per_file = [["--models", cli.model_files[k], "models", "--json"] for k in ("copies", "hostile", "heavy")]
    per_file.append(["--models", cli.model_files["copies"], "--models", cli.model_files["hostile"], "models"])
    if cli.quick:  # every command, with three of the sources (always the first file and the hostile lobe)
        picks = {0, 3, cli.rng.randrange(5, len(srcs))}
        cases = [(s, e) for s, e in cases if srcs.index(s) in picks]
    cli.rng.shuffle(cases)
    for args in per_file:
        run_case(cli, g, args, need=(0,) if "heavy" not in args[1] else None, slow_s=SLOW_MODEL_S)
    budgeted(g, cases, budget_s, lambda c: run_command(cli, g, c[0], c[1], slow_s=SLOW_MODEL_S))


def group_heavy(cli, budget_s):
    """Formulas at the limits (4095 characters, 60 deep, an oscillating lobe under quadrature) in
    every command: each ends within SLOW_MODEL_S."""
    g = cli.summary.group("cli: heavy user models")
    srcs = heavy_sources(cli)
    first = ("eval", "albedo", "normalize", "check", "export cpp", "render")
    table = command_table(srcs[0])
    if cli.quick:  # the two heaviest sources on the first commands, alternately
        picks = [srcs[0], srcs[-1]]
        cases = [(picks[k % 2], e) for k, e in enumerate(e for e in table if e[0] in first)]
    else:  # every command once (the sources in turn), then the first commands with every source
        cases = [(srcs[k % len(srcs)], command_table(srcs[k % len(srcs)])[k]) for k in range(len(table))]
        done = {(s.label, e[0]) for s, e in cases}
        cases += [(s, e) for s in srcs for e in command_table(s) if e[0] in first and (s.label, e[0]) not in done]
    budgeted(g, cases, budget_s, lambda c: run_command(cli, g, c[0], c[1], cap=HEAVY_CAP_S, slow_s=SLOW_MODEL_S))


# ----------------------------------------------------------------------------- malformed model files

def group_malformed_models(cli, count, budget_s):
    """Seeded mutations of a valid model file, files wrong in shape or size, and random formulas:
    exit 0 or 2 (check: 1) within 5 s, one line, nothing written; exports of what parses compiled."""
    g = cli.summary.group("cli: malformed model files")
    top = os.path.join(cli.model_dir, "malformed")
    os.makedirs(top, exist_ok=True)
    files = list(mf.structural_files())
    files += [(f"mutant{i}.toml", mf.mutated_file(cli.rng)) for i in range(count)]
    commands = [["eval", "-m", "mut-lobe", "--cos", "0.5"], ["models", "--json"],
                ["check", "-m", "mut-brdf", "--pairs", "10", "--step", "10"],
                ["export", "-m", "mut-lobe", "--format", "cpp", "-o", "e.cpp"],
                ["glsl", "-m", "mut-brdf", "-o", "g.glsl"]]
    cases = []
    for i, (name, data) in enumerate(files):
        path = os.path.join(top, name)
        with open(path, "wb") as f:
            f.write(data)
        cases.append(["--models", path] + commands[i % len(commands)])
    cases += [["--models", p] + commands[0] for p in ("/dev/zero", "/dev/null", top, os.path.join(top, "missing"))]
    formulas = [mf.mutated_formula(cli.rng) for _ in range(count // 2)]
    formula_commands = [["eval", "--cos", "0:1@3"], ["albedo", "--theta", "0"], ["normalize", "--n", "1,2"],
                        ["export", "--format", "cpp", "-o", "e.cpp"], ["check", "--pairs", "10", "--step", "10"]]
    cases += [formula_commands[i % len(formula_commands)][:1] + ["-m", f] + formula_commands[i % len(formula_commands)][1:]
              for i, f in enumerate(formulas)]

    def run(args):
        out = next((a for a in args if a.startswith(("e.", "g."))), None)
        check = "check" in args
        r, data = run_case(cli, g, args, cap=MODEL_CAP_S, ok_codes=(0, 1) if check else (0,), out=out,
                           slow_s=SLOW_MODEL_S)
        if out:
            collect(cli, f"{what_of(cli, args)[:90]}", "cpp" if out == "e.cpp" else "glsl", data)
    budgeted(g, cases, budget_s, run)


# ----------------------------------------------------------------------------- M+ms

def model_ids(cli, g):
    r, data = run_case(cli, g, ["models", "--json", "-o", "m.json"], out="m.json", need=(0,))
    try:
        doc = json.loads(data)
        return [m["id"] for m in doc]
    except (TypeError, ValueError, KeyError):
        g.fault("wrong", f"specula models --json: not a JSON list of models: {(data or b'')[:80]!r}")
        return []


MS_FIRST = ("cook-torrance", "cook-torrance-1982", "ggx")  # (the first two were slowest)


def group_ms(cli, budget_s, every=False):
    """M+ms of every model (and of model-file models) on sample --count 1000, render 16x16, a
    4-cell lut and export cpp: each within MS_CAP_S; the worst is noted (and in the totals).
    The full run puts each model on one command (the two cook-torrances first) within budget_s;
    every=True (--long) puts every model on all four, without a budget."""
    g = cli.summary.group("cli: M+ms of every model" + (" (all four commands)" if every else ""))
    ids = model_ids(cli, g)
    rest = [i for i in ids if i not in MS_FIRST]
    cli.rng.shuffle(rest)
    order = [i for i in MS_FIRST if i in ids] + rest
    commands = [("sample", ["sample", "--count", "1000", "--theta-i", "30"], None),
                ("render", ["render", "--size", "16x16", "-o", "y.png"], "y.png"),
                ("lut", ["lut", "--mu", "0.25:1@4", "-q"], None),
                ("export cpp", ["export", "--format", "cpp", "-o", "e.cpp"], "e.cpp")]
    files = cli.model_files
    if every:
        cases = [(ident, c) for ident in order for c in commands]
        budget_s = float("inf")
    else:  # one command each, in turn (--quick: the first five models)
        cases = [(ident, commands[k % len(commands)]) for k, ident in enumerate(order[:5] if cli.quick else order)]
    cases[2:2] = [("my-ggx", commands[3], files["copies"]), ("hostile-0", commands[3], files["hostile"])]
    worst = [0.0, ""]

    def run(case):
        ident, (name, argv, out), *file = case
        args = (["--models", file[0]] if file else []) + [argv[0], "-m", ident + "+ms"] + argv[1:]
        r, data = run_case(cli, g, args, cap=MS_CAP_S, out=out,
                           need=(0,) if not file or ident == "my-ggx" else None)
        if r.wall > worst[0]:
            worst[:] = [r.wall, f"{ident}+ms {name}"]
        if name == "export cpp":
            collect(cli, f"{ident}+ms: export cpp", "cpp", data)
    budgeted(g, cases, budget_s, run)
    for args in (["eval", "-m", "ggx+ms+ms", "--cos", "0.5"], ["eval", "-m", "+ms", "--cos", "0.5"],
                 ["eval", "-m", "nope+ms", "--cos", "0.5"], ["eval", "-m", "ggx+MS", "--cos", "0.5"]):
        run_case(cli, g, args, need=(2,))
    g.note = (g.note + "; " if g.note else "") + f"worst {worst[1]} {worst[0]:.1f} s ({len(ids)} models)"
    cli.summary.measures["worst M+ms command" + (" (all four)" if every else "")] = f"{worst[0]:.1f} s ({worst[1]})"


# ----------------------------------------------------------------------------- exports compiled

def group_exports(cli, budget_s):
    """Every format exported for the hostile and odd-id model files and hostile inline formulas,
    and everything the other groups exported, compiled: C++ headers by g++ -std=c++20, Metal
    against a shim (g++ -std=c++14), both with a comment continued onto the next line an error,
    HLSL by glslang's HLSL front end, GLSL and .brdf files (in BRDF Explorer's template) by
    glslangValidator; no line of injected text outside a comment."""
    g = cli.summary.group("cli: exports compiled")
    files = cli.model_files
    models = [("hostile", f"hostile-{i}") for i in range(len(mf.HOSTILE_TEXTS))]
    models += [("hostile-path", "hostile-0"), ("hostile-path", "hostile-1")]
    odd = [(f"odd:{i}", i) for i in mf.ODD_IDS]
    if cli.quick:  # every hostile text in two fields at least, the path, a few ids
        models = models[:2] + models[3:4] + models[6:7] + models[8:9]
        odd = odd[::5]
    srcs = [Source(f"{f.split(':')[0]} {ident}", ident, [], [files[f]], valid=False) for f, ident in models]
    srcs += [Source(f"inline {text!r}", text, params, valid=False) for text, params in mf.INLINE[2:5]]
    srcs += [Source("inline 4095-char lobe", mf.INLINE_HEAVY[0][0], [], valid=False)]
    srcs += [Source(f"odd-id {ident}", ident, [], [files[f]], valid=False) for f, ident in odd]
    cases = [(src, e) for src in srcs for e in command_table(src) if e[3]]
    budgeted(g, cases, budget_s, lambda c: run_command(cli, g, c[0], c[1]))
    compile_all(cli, g)


def negative_control(fmt, text):
    """text with a line of code that must not compile, as injected text would be."""
    bad = "static int pwned = ;"
    if fmt == "brdf":
        return text.replace("::begin shader\n", "::begin shader\n" + bad + "\n", 1)
    if fmt in ("frag", "vert"):  # after the #version line
        head, _, rest = text.partition("\n")
        return head + "\n" + bad + "\n" + rest
    return bad + "\n" + text


def compile_all(cli, g):
    """Compiles cli.exports; first, for each format, a negative control (an export with a broken
    line of code) that the compiler and the scan must both reject, or the checks are blind."""
    exports = cli.exports
    missing = compilers.missing()
    started = time.monotonic()
    firsts = {}
    for what, fmt, text in exports:
        firsts.setdefault(fmt, (what, text))
    controls = [(fmt, negative_control(fmt, text)) for fmt, (_, text) in sorted(firsts.items())]
    results = compilers.check_exports(controls + [(fmt, text) for _, fmt, text in exports])
    for (fmt, text), err in zip(controls, results):
        caught = (err is not None or fmt in compilers.skipped_formats()) and compilers.injected_lines(text, fmt)
        g.count("control:" + ("ok" if caught else "blind"))
        if not caught:
            g.fault("wrong", f"negative control ({fmt}, {firsts[fmt][0]} with a broken line): "
                             f"{'compiled' if err is None else 'the scan missed it'}: the checks of {fmt} are blind")
    results = results[len(controls):]
    for (what, fmt, text), err in zip(exports, results):
        g.count(f"{fmt}:{'ok' if err is None else 'fail'}")
        if err is not None:
            g.fault("wrong", f"{what}: the {fmt} output does not compile: {err}")
        injected = compilers.injected_lines(text, fmt)
        if injected:
            g.fault("wrong", f"{what}: injected text outside a comment: {'; '.join(injected)}")
        if fmt in ("glsl", "frag", "vert") and not text.isascii():
            g.fault("wrong", f"{what}: GLSL that is not ASCII (documented: ASCII only)")
    g.note = (g.note + "; " if g.note else "") + (
        f"{len(exports)} exports compiled in {time.monotonic() - started:.0f} s"
        + (f"; not found: {', '.join(missing)} (those checks skipped)" if missing else ""))
    exports.clear()


# ----------------------------------------------------------------------------- outputs of every command

def writers(cli):
    """(name, argv with OUT for the output, extension, magic the file starts with or None)."""
    d = cli.fixtures["D.csv"]
    return [
        ("models", ["models", "-o", "OUT"], ".txt", None),
        ("normalize", ["normalize", "-m", "log", "--n", "1,2", "-o", "OUT"], ".csv", b"n,coef"),
        ("albedo", ["albedo", "-m", "phong", "--theta", "0", "-o", "OUT"], ".csv", b"theta_deg"),
        ("check", ["check", "-m", "phong", "--pairs", "10", "--step", "10", "-o", "OUT"], ".txt", None),
        ("check --sampling", ["check", "-m", "phong", "--sampling", "--samples", "1000", "--theta-i", "30", "-o",
                              "OUT"], ".png", b"\x89PNG"),
        ("error", ["error", "-m", "log", "--n", "1:2", "-o", "OUT"], ".csv", b"n,max_abs"),
        ("fit", ["fit", "--data", d, "--target", "coef", "--time", "1", "--generations", "3", "-q", "--out", "OUT"],
         ".txt", None),
        ("render png", ["render", "-m", "phong", "--size", "8x8", "-o", "OUT"], ".png", b"\x89PNG"),
        ("render exr", ["render", "-m", "phong", "--size", "8x8", "-o", "OUT"], ".exr", b"v/1\x01"),
        ("compare", ["compare", "--models", "phong,ggx", "--size", "8x8", "-q", "-o", "OUT"], ".png", b"\x89PNG"),
        ("glsl", ["glsl", "-m", "ggx", "-o", "OUT"], ".glsl", b"// specula glsl"),
        ("export", ["export", "-m", "ggx", "--format", "cpp", "-o", "OUT"], ".h", b"// specula export"),
        ("lut csv", ["lut", "-m", "ggx", "--mu", "0.5,1", "-q", "-o", "OUT"], ".csv", None),
        ("lut exr", ["lut", "-m", "ggx", "--mu", "0.5,1", "--format", "exr", "-q", "-o", "OUT"], ".exr", b"v/1\x01"),
        ("lut png16", ["lut", "-m", "ggx", "--mu", "0.5,1", "--format", "png16", "-q", "-o", "OUT"], ".png",
         b"\x89PNG"),
        ("sample", ["sample", "-m", "ggx", "--count", "10", "-o", "OUT"], ".csv", None),
    ]


def with_out(argv, value):
    return [value if a == "OUT" else a for a in argv]


def reference(cli, g, entry):
    """The command's output written to a regular file: its first bytes (or None if it failed)."""
    name, argv, ext, magic = entry
    r, data = run_case(cli, g, with_out(argv, "ref" + ext), out="ref" + ext, need=(0, 1))
    if data is not None and magic and not data.startswith(magic):
        g.fault("wrong", f"specula {shown_argv(with_out(argv, 'ref' + ext))}: the file starts {data[:16]!r}, "
                         f"expected {magic!r}")
    return data[:64] if data else None


def out_target(cli, g, entry, head, target):
    """-o onto /dev/null, a FIFO (read concurrently), a symlink, or a 255- or 256-byte name."""
    name, argv, ext, magic = entry
    work = cli.workdir()
    try:
        reader, box, left = None, {}, set()
        if target == "devnull":
            value, expect = "/dev/null", (0, 1, 2)
        elif target == "fifo":
            value = "f" + ext
            os.mkfifo(os.path.join(work, value))
            reader = threading.Thread(target=read_fifo, args=(os.path.join(work, value), box), daemon=True)
            reader.start()
            left, expect = {value}, (0, 1)
        elif target == "symlink":
            value = "link" + ext
            with open(os.path.join(work, "target" + ext), "wb") as f:
                f.write(b"old\n")
            os.symlink("target" + ext, os.path.join(work, value))
            left, expect = {value, "target" + ext}, (0, 1)
        else:
            length = 255 if target == "name255" else 256
            value = "n" * (length - len(ext)) + ext
            left, expect = ({value}, (0, 1)) if length == 255 else (set(), (2,))
        args = with_out(argv, value)
        r = cli.run(args, 30, work)
        label = {"devnull": "/dev/null", "fifo": "FIFO", "symlink": "SYMLINK", "name255": "NAME_OF_255_BYTES",
                 "name256": "NAME_OF_256_BYTES"}[target]
        r.argv = [r.argv[0]] + with_out(argv, label)
        shown = what_of(cli, r.argv[1:])
        cli.judge(g, r, work, 30, expect=expect, outputs=left, ok_codes=(0, 1))
        if reader is not None:  # it is done, or blocked for good if specula never opened the FIFO
            reader.join(1)
            if reader.is_alive():
                fd = os.open(os.path.join(work, value), os.O_WRONLY | os.O_NONBLOCK)
                os.close(fd)
                reader.join(2)
        if target == "devnull":
            guard_devices(g, shown)
            return
        if r.code not in (0, 1):
            return
        path = os.path.join(work, "target" + ext if target == "symlink" else value)
        if target == "fifo":
            if not stat.S_ISFIFO(os.lstat(os.path.join(work, value)).st_mode):
                g.fault("wrong", f"{shown}: the FIFO was replaced by a regular file")
            data = box.get("data", b"")
        elif target == "symlink" and not os.path.islink(os.path.join(work, value)):
            g.fault("wrong", f"{shown}: the link was replaced by a regular file")
            return
        else:
            if not os.path.exists(path):
                g.fault("wrong", f"{shown}: exit {r.code} but no file")
                return
            with open(path, "rb") as f:
                data = f.read(64)
        want = magic or (head or b"")[:12]
        if want and not data.startswith(want):
            g.fault("wrong", f"{shown}: wrote {data[:24]!r}, expected it to start {want!r}")
    finally:
        rmtree(work)


TARGETS = ("devnull", "fifo", "symlink", "name255", "name256")


def group_outputs(cli):
    """-o of every command that writes a file onto /dev/null (stays the device), a FIFO (written
    into, read concurrently, stays a FIFO), a symlink (the link stays, its target is replaced) and
    names of 255 bytes (work) and 256 bytes (exit 2, one line)."""
    g = cli.summary.group("cli: outputs of every command")
    for k, entry in enumerate(writers(cli)):
        head = reference(cli, g, entry)
        targets = TARGETS if not cli.quick else (TARGETS[k % len(TARGETS)],)
        for target in targets:
            out_target(cli, g, entry, head, target)


# ----------------------------------------------------------------------------- specific cases

def coef_csv(cli):
    path = os.path.join(cli.fixture_dir, "coef.csv")
    if not os.path.exists(path):
        with open(path, "w") as f:
            f.write("n,coef\n" + "".join(f"{n},{0.48 * n ** 0.9 + 0.1 * (n % 3):.12g}\n" for n in range(1, 41)))
    return path


FRONT_SIZE = re.compile(r'"size"\s*:\s*(-?\d+)')


def fit_sizes(cli, g):
    """fit with the ops asin, expm1, log1p (and their --size-weights): every size printed is in
    [1, --max-size] (garbage sizes and an out-of-bounds write were seen)."""
    data = coef_csv(cli)
    base = ["fit", "--data", data, "--target", "coef", "--vars", "n", "--generations", "3", "-q", "--time", "5"]
    cases = [["--ops", "+,*,/,asin"], ["--ops", "+,*,/,expm1"], ["--ops", "+,*,/,log1p"],
             ["--ops", "+,*,/,asin,expm1,log1p", "--max-size", "12"],
             ["--ops", "+,*,/,asin", "--size-weights", "asin=2"],
             ["--ops", "+,*,/,expm1,log1p", "--size-weights", "expm1=3,log1p=2"],
             ["--ops", "asin,expm1,log1p,+", "--size-weights", "asin=7", "--max-size", "7"]]
    if cli.quick:
        cases = [cases[0], cases[4], cases[5]]
    for k, extra in enumerate(cases):
        for fmt in ("json",) if cli.quick or k % 3 else ("json", "table"):
            args = base + extra + ["--format", fmt, "--out", "o.txt"]
            r, out = run_case(cli, g, args, cap=30, out="o.txt", need=(0,))
            if out is None:
                continue
            max_size = int(extra[extra.index("--max-size") + 1]) if "--max-size" in extra else 25
            text = out.decode("utf-8", "replace")
            if fmt == "json":
                sizes = [int(s) for s in FRONT_SIZE.findall(text)]
            else:  # the table's rows start with the size
                sizes = [int(m) for m in re.findall(r"(?m)^ *(-?\d+)  ", text)]
            bad = [s for s in sizes if not 1 <= s <= max_size]
            if bad or not sizes:
                g.fault("wrong", f"{what_of(cli, args)}: sizes {bad[:5] or 'none found'} "
                                 f"(each must be in [1, {max_size}])")


DEGENERATE = ["brdf: -nl", "brdf: 0", "brdf: 1e308", "brdf: 1/(nl-nl)", "brdf: sqrt(-nl)", "lobe: -c", "lobe: 0*c",
              "lobe: 1e308*c", "brdf: nl*1e-308", "brdf: max(0, 1 - 100*abs(nh - 0.5))"]


def group_specific(cli):
    """Regressions of the new surface: fit sizes with asin/expm1/log1p, check --sampling of a
    degenerate model ends within PROMPT_S with a verdict, the documented refusals."""
    g = cli.summary.group("cli: specific cases (models, fit, sampling)")
    fit_sizes(cli, g)
    degenerate = DEGENERATE if not cli.quick else [DEGENERATE[i] for i in (0, 3, 4, 5)]
    for model in degenerate:
        for theta in ("0", "60") if not cli.quick else ("0",):
            run_case(cli, g, ["check", "-m", model, "--sampling", "--samples", "1000", "--theta-i", theta],
                     cap=PROMPT_CAP_S, ok_codes=(0, 1), need=(0, 1), slow_s=PROMPT_S)
    for models in ("lobe: c^n,phong", "brdf: rho/pi,ggx", "phong,lobe: c^n"):  # inline models in compare
        run_case(cli, g, ["compare", "--models", models, "--size", "16x16", "-o", "c.png", "-q"], out="c.png",
                 need=(0,))
    for args in (["sample", "-m", "brdf: -nl", "--count", "1000"], ["sample", "-m", "lobe: 0*c", "--count", "1000"],
                 ["render", "-m", "brdf: -nl", "--env", "white", "--samples", "4", "--size", "8x8", "-o", "y.exr"]):
        run_case(cli, g, args, cap=PROMPT_CAP_S, out=args[-1] if "-o" in args else None, slow_s=PROMPT_S)
    refusals = [["check", "-m", "ggx", "--sampling", "--samples", "999"],
                ["check", "-m", "ggx", "--sampling", "--samples", "100000001"],
                ["check", "-m", "ggx", "--sampling", "--samples", "30000001"],
                ["check", "-m", "ggx", "--sampling", "--samples", "20000000", "--theta-i", "0,30"],
                ["check", "-m", "ggx", "--sampling", "--theta-i", "90"],
                ["check", "-m", "ggx", "--sampling", "--theta-i", "0:89@21"],
                ["sample", "-m", "ggx", "--count", "1000001"], ["sample", "-m", "ggx", "--theta-i", "90"],
                ["lut", "-m", "ggx", "--mu", "0:1@5"], ["lut", "-m", "ggx", "--mu", "0.5:1@1025"],
                ["lut", "-m", "ggx", "--sweep", "alpha=0.05:1@256", "--mu", "0.00390625:1@257"],
                ["lut", "-m", "ggx", "--mu", "1,0.5"], ["lut", "-m", "ggx", "--format", "exr"],
                ["render", "-m", "ggx", "--env", "white", "--samples", "65537", "-o", "y.exr"],
                ["render", "-m", "ggx", "--env", "white", "--samples", "65536", "--size", "256x256", "-o", "y.exr"],
                ["render", "-m", "ggx", "--env", "white", "--samples", "65", "--size", "1024x1024", "-o", "y.exr"],
                ["render", "-m", "ggx", "--env", "white", "--samples", "65536", "--size", "16384x16384",
                 "-o", "y.exr"],
                ["eval", "-m", "lobe: " + mf.LONG_LOBE + "*c", "--cos", "0.5"],
                ["eval", "-m", "lobe: " + "1+(" * 70 + "c" + ")" * 70, "--cos", "0.5"],
                ["eval", "-m", "lobe: c^n", "-p", "n=nan", "--cos", "0.5"],
                ["--models", cli.model_files["hostile"], "--models", cli.model_files["hostile"], "models"]]
    for args in refusals:
        run_case(cli, g, args, cap=10, need=(2,))


# ----------------------------------------------------------------------------- documented maxima

MAXIMA = [  # (argv, output, seconds allowed to the end: docs/energy-compensation.md, docs/robustness.md)
    (["lut", "-m", "ggx", "--sweep", "alpha=0.05:1@256", "--mu", "0.00390625:1@256", "-q", "-o", "lut.csv"],
     "lut.csv", 90),
    (["check", "-m", "log-normalized", "--sampling", "--samples", "30000000", "--theta-i", "30"], None, 90),
    (["render", "-m", "log-normalized", "--env", "white", "--samples", "1024", "--size", "256x256", "-o", "y.exr"],
     "y.exr", 90),
]


def group_maxima(cli, to_the_end):
    """Each documented maximum (lut 65536 cells, check --sampling 3e7 samples, render --env white
    2^26 pairs): stopped by SIGINT 2-4 s in, it exits 130 within 2 s and
    leaves no file; with --maxima it runs to its end, within the documented time."""
    g = cli.summary.group("cli: documented maxima" + (" (to the end)" if to_the_end else " (SIGINT)"))
    for argv, out, documented in MAXIMA:
        work = cli.workdir()
        try:
            if to_the_end:
                cap = 2 * documented + 30
                r = cli.run(argv, cap, work)
                cli.judge(g, r, work, cap, outputs={out} if out else set(), ok_codes=(0, 1))
                if not r.hung and r.wall > documented:
                    g.fault("slow", f"specula {shown_argv(argv)}: took {r.wall:.0f} s (documented: {documented} s)")
                continue
            after = cli.rng.uniform(2.0, 4.0)
            r = cli.run(argv, 60, work, send=(signal.SIGINT, after))
            r.argv = r.argv + [f"[SIGINT@{after:.1f}s]"]
            cli.judge(g, r, work, 60, expect=(0, 1, 130), outputs={out} if out else set(), ok_codes=(0, 1),
                      sent=signal.SIGINT)
            if r.sent is not None and not r.hung and r.wall - r.sent_at > 2.0:
                g.fault("slow", f"specula {shown_argv(argv)}: stopped {r.wall - r.sent_at:.1f} s after SIGINT "
                                f"(documented: at most 2 s)")
        finally:
            rmtree(work)
