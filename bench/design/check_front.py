#!/usr/bin/python3
"""Checks a `specula design` front independently: every member of DIR/front.csv is evaluated
through `specula --models DIR/models.toml eval` on a dense grid of c and n, against c^n computed
here, and its largest error may not exceed the max_abs_error front.csv claims.

    /usr/bin/python3 bench/design/check_front.py DIR [--specula build/release/specula]

Prints one line per member (claimed, found on the grid, where) and exits 1 if a claim is low.
Only for a front designed against phong (c^n) over a range of n.
"""
import argparse
import csv
import math
import subprocess
import sys


def lobe_values(specula, models, member, n, cosines):
    out = subprocess.run([specula, "--models", models, "eval", "--model", member, "-p", f"n={n!r}",
                          "--cos", cosines, "--lobe"], check=True, capture_output=True, text=True).stdout
    rows = list(csv.reader(out.splitlines()))[1:]
    return [(float(c), float(v)) for c, v in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir")
    parser.add_argument("--specula", default="build/release/specula")
    parser.add_argument("--points", type=int, default=48, help="n values, log-spaced over the range")
    args = parser.parse_args()
    models = f"{args.dir}/models.toml"
    with open(f"{args.dir}/front.csv", newline="") as f:
        members = [r for r in csv.DictReader(f) if r["kind"] == "member"]
    with open(models) as f:
        header = f.readline()
    lo, hi = (float(x) for x in header.split("in [")[1].split("]")[0].split(", "))
    grid = [lo * (hi / lo) ** (i / (args.points - 1)) for i in range(args.points)]
    low = 0
    for m in members:
        claimed = float(m["max_abs_error"])
        found, where = 0.0, None
        for n in grid + [float(m["argmax_param"])]:
            for cosines in ("0:1@2001", "0.95:1@2001", "0.999:1@1001"):
                for c, v in lobe_values(args.specula, models, m["id"], n, cosines):
                    e = abs(v - c ** n)
                    if e > found:
                        found, where = e, (c, n)
        ok = found <= claimed * (1 + 1e-9)
        low += not ok
        print(f"{m['id']:<14} claimed {claimed:.6g}  found {found:.6g} at c = {where[0]:.6g}, n = {where[1]:.6g}"
              f"  {'ok' if ok else 'CLAIM TOO LOW'}")
    return 1 if low else 0


if __name__ == "__main__":
    sys.exit(main())
