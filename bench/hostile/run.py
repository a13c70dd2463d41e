#!/usr/bin/env python3
"""The hostile test of specula: the CLI and `specula serve` against bad input, kills and load.

Python 3 standard library only. Bounded: every child process and socket has a cap, every group a
count (and the long ones a time budget); the full run takes a few minutes (~6), --quick about 90 s.
Exit code 0: no fault; 1: at least one fault (each named in one line); 2: it could not run.

What each group proves (docs/robustness.md and docs/serve.md state the rules):

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
  special outputs    -o /dev/null stays a character device; -o FIFO is written into (read
                     concurrently) and stays a FIFO; -o SYMLINK keeps the link and replaces its
                     target; 254- and 255-byte output names work.
  SIGKILL mid-write  ~20 SIGKILLs at seeded random times during a 3000x3000 EXR render and a
                     3000001-line eval: the work dir holds nothing or the complete file (the same
                     bytes as an uninterrupted run), never a temporary.
  SIGINT/SIGTERM     The same commands stopped by SIGINT or SIGTERM exit 130 or 143 (0 if they had
                     finished) within 2 s of the signal (3 s allowed under load), leaving no file.
  report killed      `report --quick --out R` into a new R (and, if that fails, into an existing
                     empty one), then a second run SIGKILLed midway: R is still the first report (same
                     file list, index.html identical). Full run only.
Server (`specula serve --port 0` on 127.0.0.1; a monitor GETs /api/models every 250 ms throughout):
  bad paths          Traversals (/%c0%ae%c0%ae/etc/passwd, ...), invalid UTF-8, very long and random
                     paths: no 5xx, never a system file, every error body JSON with "error".
  methods, framing   Unknown methods, and broken HTTP (bad versions, huge or many headers, both
                     Content-Length and chunked, bad chunk sizes, TLS and HTTP/2 prefaces; these may
                     be dropped); a POST or PUT without Content-Length has no body: answered at once.
  bad JSON bodies    Malformed JSON to each POST endpoint (400/413), then seeded mutations of a cheap
                     valid body (wrong types, huge numbers, unknown keys, oversized lists): < 500 or 503.
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
import proc  # noqa: E402
import serve_cases  # noqa: E402
from tally import Summary  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def arguments():
    p = argparse.ArgumentParser(description="The hostile test of specula (CLI and serve).")
    p.add_argument("--specula", default=os.path.join(REPO, "build", "release", "specula"),
                   help="the binary (default: build/release/specula in this repository)")
    p.add_argument("--quick", action="store_true", help="fewer cases, no report: about 90 s")
    p.add_argument("--seed", type=int, default=1, help="seed of every generated case and kill time")
    p.add_argument("--json", metavar="FILE", help="also write the summary and every fault as JSON")
    p.add_argument("--only", choices=["cli", "serve"], help="run only the CLI or only the server groups")
    return p.parse_args()


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


def run_cli_groups(cli, quick):
    cli_cases.group_malformed(cli, budget_s=25 if quick else 110)
    cli_cases.group_files(cli, budget_s=10 if quick else 45)
    cli_cases.group_specific(cli)
    cli_cases.group_outputs(cli)
    cli_cases.group_kills(cli)


def run_groups(args, root, summary):
    rng = random.Random(args.seed)
    cli = cli_cases.Cli(args.specula, root, rng, args.quick, summary)
    if args.only != "serve":
        run_cli_groups(cli, args.quick)
    if args.only != "cli":
        try:
            serve_cases.run_all(args.specula, cli.scratch, summary, args.seed, args.quick)
        except RuntimeError as e:
            summary.group("srv: start").fault("crash", f"specula serve --port 0: {e}")
    if args.only != "serve" and not args.quick:
        cli_cases.group_report(cli)


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
