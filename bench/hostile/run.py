#!/usr/bin/env python3
"""The hostile test of specula: the CLI and `specula serve` against bad input, kills and load.

Python 3 standard library only (and, to compile the exports, g++ and glslangValidator where they
are installed). Bounded: every child process and socket has a cap, every group a count (and the
long ones a time budget); the full run takes ~7.5 min, --quick about 2.5 min (more while faults make
runs hit their caps). Exit code 0: no fault; 1: at least one fault (each named in one line); 2: it
could not run. --only PARTS runs some groups (the parts are listed by --help).

What each group proves (docs/robustness.md, docs/serve.md and docs/models.md state the rules):

CLI (each run in a fresh, empty working directory, its max RSS from os.wait4):
  malformed options  A few hundred invocations of every command, seeded, with options given garbage
                     (random strings, nan, inf, -1, 1e308, 2147483647, 1:1e7, embedded \\n \\r and
                     escape sequences, empty strings, unknown models, malformed ranges, huge sizes):
                     exit 0, 1 or 2, never >= 3 nor a signal; exit 2 prints exactly one line with no
                     raw control character, within 5 s; nothing is left in the work dir unless the run
                     succeeded with -o (then only that file); each run ends within its cap (20 s).
  bad input files    Malformed CSV (fit --data) and OBJ (render --scene) contents (ragged, NUL bytes,
                     a 1 MB line, a 100000-column header, 10^6+1 rows, ...), /dev/zero, a directory, a
                     missing file: the same rules (cap 30 s).
  specific cases     Regressions: a fit whose formula space is smaller than its population stops at
                     --time 2; out-of-range --islands/--population/--enumerate-size/--pairs and lists
                     over a command's cap (check/error/normalize --n 1:1e7) are exit 2 at once; a
                     value holding a newline gives a one-line error.
  specific cases (models, fit, sampling)
                     fit with the ops asin, expm1, log1p and their --size-weights: every size printed
                     (JSON and table) is in [1, --max-size]; check --sampling of degenerate models
                     (brdf: -nl, lobe: -c, 0, 1e308, nan, ...) at theta_i 0 and 60 gives its verdict
                     (exit 0/1) within 5 s (cap 15 s); sample and render --env of them end as fast;
                     compare with inline models beside built-ins works (exit 0);
                     the documented refusals of sample, lut, check --sampling, render --env, inline
                     formulas (4097 characters, 71 deep), a model file given twice: exit 2, one line.
                     (The malformed-options group also mutates lut, sample, check --sampling and
                     render --env, with inline models, M+ms ids and --models files in its pools.)
  special outputs    -o /dev/null stays a character device; -o FIFO is written into (read
                     concurrently) and stays a FIFO; -o SYMLINK keeps the link and replaces its
                     target; 254- and 255-byte output names work.
  outputs of every command
                     The same for every command that writes a file (models, normalize, albedo, check,
                     check --sampling's PNG, error, fit, render PNG and EXR, compare, glsl, export,
                     lut csv/exr/png16, sample): /dev/null, a FIFO, a symlink, a 255-byte name (the
                     file starts as the command's regular output does) and a 256-byte name (exit 2,
                     one line). --quick: one of the five per command, in turn.
  SIGKILL mid-write  ~20 SIGKILLs at seeded random times during a 3000x3000 EXR render and a
                     3000001-line eval: the work dir holds nothing or the complete file (the same
                     bytes as an uninterrupted run), never a temporary.
  SIGINT/SIGTERM     The same commands stopped by SIGINT or SIGTERM exit 130 or 143 (0 if they had
                     finished) within 2 s of the signal (3 s allowed under load), leaving no file.
  user models in every command
                     Model files (--models: the repository's builtin-copies.toml, a file of hostile
                     texts) and inline models (lobe: and brdf: formulas, some holding \\n and \\r) in
                     every command: eval (cosines, directions), normalize, albedo, check, check
                     --sampling, error, fit --model, render (lights, --env white), compare, glsl,
                     glsl --shader, export (4 formats), lut, sample, models: the rules above, each
                     within 10 s, and a valid model works (exit 0; check 0/1). --quick: a 6-s sample.
  heavy user models  Formulas at the limits: 4095 characters (c*c*...), a 4094-character BRDF, 60
                     parentheses deep, sin(1000 n acos c) normalized by quadrature, from a file and
                     inline: every command once (the formulas in turn), then eval, albedo,
                     normalize, check, export cpp and render with each (--quick: those six, two
                     formulas); each ends within 10 s (cap 20 s).
  malformed model files
                     Seeded mutations of a valid model file (values replaced by TOML garbage, lines
                     deleted, duplicated, cut, bytes inserted, keys renamed), files wrong in shape or
                     size (1001 models, 65 parameters, a built-in's id, 5000-deep tables, a 1 MB line,
                     BOM and CRLF, Latin-1, binary, NUL, a 2 MB name), /dev/zero, a directory, and
                     random token strings as inline formulas: exit 0/1/2 within 10 s, one line.
  M+ms of every model
                     M+ms of every model of `specula models` (and of model-file models) on sample
                     --count 1000, render 16x16, a 4-cell lut, export cpp: each within 30 s. The
                     full run puts every model on one command, in turn (cook-torrance and
                     cook-torrance-1982 first; a 60-s budget), --quick the first five, --long every
                     model on all four; M+ms+ms, +ms, nope+ms, ggx+MS are exit 2. The worst time is
                     in the totals.
  exports compiled   Every export the groups above wrote, and every format (glsl, glsl --shader, cpp,
                     hlsl, msl, brdf) of hostile inline formulas ($'lobe: c\\n^n', ...) and of hostile
                     model files: names, sources, summaries, parameter
                     meanings and formulas holding newlines, a lone CR, a final backslash or ??/
                     trigraph, */, control and non-ASCII characters, BRDF Explorer section lines; the
                     model file in a directory whose name holds a newline; ids such as 9lives, x__y,
                     class, main; all compiled (C++ by g++ -std=c++20 -Werror=comment, Metal by g++
                     -std=c++14 against a shim of its types, trigraphs on, HLSL by glslang's HLSL
                     front end, GLSL and .brdf files, loaded as BRDF Explorer does, in its lit-sphere
                     template, by glslangValidator), no line starting with "#error" or holding the
                     marker word outside a // comment, GLSL in ASCII. A negative control per format
                     (an export with a broken line) must fail both checks, else they are blind.
  report killed      `report --quick --out R` into a new R (and, if that fails, into an existing
                     empty one), then a second run SIGKILLed midway: R is still the first report (same
                     file list, index.html identical). Full run only.
  documented maxima  lut at 65536 cells (ggx), check --sampling at 3e7 samples and render --env white
                     at 2^26 pairs (256x256 at 1024; log-normalized, the slowest sampler), each
                     SIGINTed 2-4 s in: exit 130 within 2 s, no file. Full run only; --long also
                     runs each to its end (--long), within 90 s (docs: lut 1.5 min, the others 82-106 s at a
                     load average of 7; "about a minute").
design --merge (merge_cases.py; in part `specific`): forged shard files (a claimed error of 0,
a NaN lobe, 81 or 10^6 members, /dev/zero, settings the CLI refuses, wrong JSON types, other zones)
are refused in one line naming the file and key, or merged with every error measured again;
--no-timing holds under --merge; a subnormal target designs and its files read back; targets the
fits cannot take are refused at once; every models.toml written loads, the empty front's too.
The designer (design_cases.py; part `design`): --out never replaces a folder of the user's files
(the working directory, ".", "..", a link to one: exit 2 before any work, every file intact) and
keeps a user's file put into an earlier output; strict integer options (--seed -1, 0x2, ' 2',
+0/4: exit 2); a hanging compiler (SPECULA_CXX) stopped by SIGINT/SIGTERM (130/143 within 3 s) or
SIGKILL leaves no compiler process and no scratch folder (a killed run's goes with the next run),
SPECULA_COMPILE_TIMEOUT bounds it, a missing SPECULA_CXX is exit 2 at once; a design job's status
counts shapes while screening; a server stopped with a design compiling leaves nothing running.
Server (`specula serve --port 0` on 127.0.0.1; a monitor GETs /api/models every 250 ms throughout):
  bad paths          Traversals (/%c0%ae%c0%ae/etc/passwd, ...), invalid UTF-8, very long and random
                     paths: no 5xx, never a system file, every error body JSON with "error".
  methods, framing   Unknown methods, and broken HTTP (bad versions, huge or many headers, both
                     Content-Length and chunked, bad chunk sizes, TLS and HTTP/2 prefaces; these may
                     be dropped); a POST or PUT without Content-Length has no body: answered at once.
  bad JSON bodies    Malformed JSON to each POST endpoint (400/413), then seeded mutations of a cheap
                     valid body (wrong types, huge numbers, unknown keys, oversized lists, definition
                     objects with injected keys and texts): < 500 or 503.
  Range x1500        Range: bytes=0-,0-,... x1500 on /app.js and /api/models: the answer is never
                     larger than the resource itself.
  Content-Length     Content-Length: 1000000000000 with no body (and 65537): 413 within 2 s, not a
                     wait for the body.
  slow-drip          12 clients sending one header byte per second for ~10 s (the monitor shows
                     whether they starve everyone else).
  fit jobs           A fit that used to never stop ({"model":"log","ops":"+","max_size":1,"time":2})
                     ends by itself; DELETE frees its slot; a third running fit is 429 and a new fit
                     is accepted again after DELETEs. A last 60-s fit is left running for the end.
  heavy checks       8 concurrent POST /api/check {"model":"ggx","step":0.01,"pairs":1}: each answered
                     (200, or 503 past the server's deadline) within 30 s, else a hang.
  SIGTERM in flight  SIGTERM with a heavy request and that fit running: exit 0 within 1 s.
  (then a second server, started with --models (the copies and the hostile file), so that work
   left behind cannot fail the SIGTERM group:)
  Expect: 100-continue
                     With a body that stops short or never comes: 408 with a JSON error within 5 + 3 s
                     (not a silent close); the whole body after the 100, or at once: 200; with
                     Content-Length 10^12: 413/417 within 2 s; on a GET, and Expect: bogus: answered.
  definition objects User models in the request (cheap ones, which must answer 200/202, and heavy
                     ones: 4095 characters, sin(1000 n acos c) by quadrature, 60 deep, a 4094-character
                     BRDF) on every computing route: eval, normalize (also as compare, and with n
                     1:1e6@2000:log), albedo, check, error (also as reference), glsl, fit; 3 at once,
                     each answered within the 5-s deadline + 3 s; the worst time per route is in the
                     totals and the JSON. /api/glsl's function and shaders for every hostile model
                     compiled by glslangValidator, with no injected line. The server's own model
                     files by id (hostile-0, my-log, my-ggx+ms, ...) on the same routes.
  monitor            Every GET /api/models answered 200 with JSON; the worst latency per group
                     (over 2 s is a fault).
"""
import argparse
import atexit
import os
import random
import shutil
import signal
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ beside the sources

import cli_cases  # noqa: E402  (after the line above)
import design_cases  # noqa: E402
import merge_cases  # noqa: E402
import model_cases  # noqa: E402
import proc  # noqa: E402
import serve_cases  # noqa: E402
import serve_models  # noqa: E402
from tally import Summary  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def arguments():
    p = argparse.ArgumentParser(description="The hostile test of specula (CLI and serve).")
    p.add_argument("--specula", default=os.path.join(REPO, "build", "release", "specula"),
                   help="the binary (default: build/release/specula in this repository)")
    p.add_argument("--quick", action="store_true", help="fewer cases, no report, no maxima: about 2.5 min")
    p.add_argument("--seed", type=int, default=1, help="seed of every generated case and kill time")
    p.add_argument("--json", metavar="FILE", help="also write the summary and every fault as JSON")
    p.add_argument("--only", metavar="PARTS", type=only_parts,
                   help="comma-separated parts to run, of: " + ", ".join(PARTS) + " (cli = every CLI part, "
                        "serve = every server part; default: all)")
    p.add_argument("--long", action="store_true",
                   help="also the long checks: each documented maximum run to its end, and M+ms of every model "
                        "on all four commands (many minutes; not part of the full run)")
    return p.parse_args()


# The parts --only chooses from: the CLI's (old, then new) and the server's.
CLI_PARTS = ["malformed", "files", "specific", "outputs", "kills", "models", "ms", "exports", "report", "maxima",
             "design"]
SERVE_PARTS = ["server", "defs"]
PARTS = CLI_PARTS + SERVE_PARTS


def only_parts(text):
    parts = set()
    for word in filter(None, (w.strip() for w in text.split(","))):
        if word == "cli":
            parts |= set(CLI_PARTS)
        elif word == "serve":
            parts |= set(SERVE_PARTS)
        elif word in PARTS:
            parts.add(word)
        else:
            raise argparse.ArgumentTypeError(f"unknown part {word!r} (known: cli, serve, {', '.join(PARTS)})")
    return parts


def wait_for_binary(path, seconds=120):
    """The binary may be relinked by a build right now: wait a while for it to appear."""
    deadline = time.monotonic() + seconds
    while not os.access(path, os.X_OK):
        if time.monotonic() > deadline:
            return False
        time.sleep(2)
    return True


def stop_on_signal(signum, _frame):
    raise SystemExit(f"hostile: stopped by {signal.Signals(signum).name}")


def run_cli_groups(cli, quick, parts, long_checks=False):
    if "malformed" in parts:
        cli_cases.group_malformed(cli, budget_s=25 if quick else 110)
    if "files" in parts:
        cli_cases.group_files(cli, budget_s=10 if quick else 45)
    if "specific" in parts:
        cli_cases.group_specific(cli)
        model_cases.group_specific(cli)
        merge_cases.group_merge(cli)
    if "outputs" in parts:
        cli_cases.group_outputs(cli)
        model_cases.group_outputs(cli)
    if "kills" in parts:
        cli_cases.group_kills(cli)
    if "models" in parts:
        model_cases.group_everywhere(cli, budget_s=6 if quick else 25)
        model_cases.group_heavy(cli, budget_s=8 if quick else 25)
        model_cases.group_malformed_models(cli, count=16 if quick else 60, budget_s=5 if quick else 12)
    if "ms" in parts:
        model_cases.group_ms(cli, budget_s=12 if quick else 60)
    if "ms" in parts and long_checks:
        model_cases.group_ms(cli, budget_s=None, every=True)
    if "exports" in parts or "models" in parts or "ms" in parts:
        model_cases.group_exports(cli, budget_s=8 if quick else 24)
    if "design" in parts:
        design_cases.run_all(cli)


def run_groups(args, root, summary):
    rng = random.Random(args.seed)
    parts = args.only or set(PARTS)
    cli = cli_cases.Cli(args.specula, root, rng, args.quick, summary)
    model_cases.prepare(cli, REPO)
    run_cli_groups(cli, args.quick, parts, args.long)
    if parts & set(SERVE_PARTS):
        try:
            serve_cases.run_all(args.specula, cli.scratch, summary, args.seed, args.quick, parts,
                                cli.model_files)
        except RuntimeError as e:
            summary.group("srv: start").fault("crash", f"specula serve --port 0: {e}")
    if "report" in parts and not args.quick:
        cli_cases.group_report(cli)
    if "maxima" in parts and (not args.quick or args.long):
        model_cases.group_maxima(cli, to_the_end=False)
    if "maxima" in parts and args.long:
        model_cases.group_maxima(cli, to_the_end=True)


def report(summary, args):
    print()
    print(summary.table())
    print()
    print("totals:")
    print(summary.totals_text())
    faults = summary.faults_text()
    print()
    print(faults if faults else "no faults")
    if args.json:
        with open(args.json, "w") as f:
            f.write(summary.to_json() + "\n")


def main():
    args = arguments()
    args.specula = os.path.abspath(args.specula)
    if not wait_for_binary(args.specula):
        print(f"hostile: {args.specula} is not an executable (build it first)", file=sys.stderr)
        return 2
    signal.signal(signal.SIGTERM, stop_on_signal)
    atexit.register(proc.kill_leftovers)
    root = tempfile.mkdtemp(prefix="specula-hostile-")
    summary = Summary()
    start = time.monotonic()
    print(f"hostile: {args.specula} (built {time.ctime(os.path.getmtime(args.specula))}), "
          f"seed {args.seed}{', quick' if args.quick else ''}", flush=True)
    try:
        run_groups(args, root, summary)
    except (KeyboardInterrupt, SystemExit) as e:
        summary.group("interrupted").fault("wrong", f"the hostile run itself was stopped ({e or 'SIGINT'}): partial")
    finally:
        proc.kill_leftovers()
        summary.close_group()
        summary.elapsed_s = time.monotonic() - start
        shutil.rmtree(root, ignore_errors=True)
    report(summary, args)
    return 1 if summary.faults() else 0


if __name__ == "__main__":
    sys.exit(main())
