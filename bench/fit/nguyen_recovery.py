#!/usr/bin/python3
"""Symbolic recovery of `specula fit` on Nguyen-1…12, judged as SRBench judges it.

The problems as DSR (Petersen et al. 2021, Table 1) specifies them: 20 points drawn uniformly from
U[-1, 1] (Nguyen-1…6), U[0, 2] (7), U[0, 4] (8) or U[0, 1]² (9…12), with a fixed seed (--seed,
also the search's seed), written to CSV files in a temporary directory. Every problem is fitted
with the same setting, the release CLI's defaults plus:

    --ops +,-,*,/,sin,cos,exp,log,^  --time 20  --format json  --seed SEED

(^ for Nguyen-8's square root, x^0.5, and Nguyen-11's x^y; constants fitted, RMS, max size 25, the
parsimonious choice; both cores). Nothing is tuned per problem.

Recovered: SRBench's symbolic-solution criterion (La Cava et al. 2021, experiment/
assess_symbolic_model.py): the chosen formula, parsed by SymPy and simplified (ratio=1), with every
float rounded to 6 decimals, is a solution when truth − formula simplifies to a constant or
formula / truth is a non-zero constant. (SRBench checks only formulas with test R² > 0.5; that gate
changes nothing for an exact match and is left out.) As in SRBench, a float that rounds to an integer
stays a float: log((-1.0000000000000002 - x)·…) is not judged equal to log(x + 1) + …. SymPy's
is_constant() evaluates at random points, seeded the same for every judgement; one that takes SymPy
over 60 s counts as not recovered.

Sizes: the node count `specula fit` reports (every node 1: a leaf, an operator, a function), the
truth's counted by the same rule from its text below (`node_count`, specula's grammar), written
with the benchmark's operators (Nguyen-8 as x^0.5, since sqrt is not among them).

Prints a table (problem, recovered, size of the truth, size found, seconds of search, the formula
with 6 significant digits) and the count recovered/12; --json FILE writes the same with the full
formulas. --problems runs some of them, --time changes the budget (for a quick look; the figures
in docs/fit.md are the 20 s setting). Exit 0 when every fit ran (whatever the count), 2 when the
CLI could not.

Run by `make bench-fit` with Debian's /usr/bin/python3 and python3-sympy (scripts/install-deps).
"""

import argparse
import json
import random
import re
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import sympy
from sympy.core import random as sympy_random
from sympy.parsing.sympy_parser import parse_expr

OPERATORS = "+,-,*,/,sin,cos,exp,log,^"
TIME_S = 20
SAMPLES = 20
JUDGE_TIMEOUT_S = 60

# (number, truth in specula's syntax, variables, interval of each variable)
PROBLEMS = [
    (1, "x^3 + x^2 + x", ["x"], (-1, 1)),
    (2, "x^4 + x^3 + x^2 + x", ["x"], (-1, 1)),
    (3, "x^5 + x^4 + x^3 + x^2 + x", ["x"], (-1, 1)),
    (4, "x^6 + x^5 + x^4 + x^3 + x^2 + x", ["x"], (-1, 1)),
    (5, "sin(x^2)*cos(x) - 1", ["x"], (-1, 1)),
    (6, "sin(x) + sin(x + x^2)", ["x"], (-1, 1)),
    (7, "log(x + 1) + log(x^2 + 1)", ["x"], (0, 2)),
    (8, "x^0.5", ["x"], (0, 4)),
    (9, "sin(x) + sin(y^2)", ["x", "y"], (0, 1)),
    (10, "2*sin(x)*cos(y)", ["x", "y"], (0, 1)),
    (11, "x^y", ["x", "y"], (0, 1)),
    (12, "x^4 - x^3 + 0.5*y^2 - y", ["x", "y"], (0, 1)),
]

SYMPY_NAMES = {
    "sin": sympy.sin, "cos": sympy.cos, "exp": sympy.exp, "log": sympy.log, "sqrt": sympy.sqrt,
    "pow": sympy.Pow, "abs": sympy.Abs, "min": sympy.Min, "max": sympy.Max, "pi": sympy.pi,
}


# ---- sizes ----------------------------------------------------------------------------------------

TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)|([A-Za-z_]\w*)|(.))")


def node_count(text):
    """Nodes of `text` as specula's parser builds them (src/expr/parse.cpp): sum := product
    (± product)*, product := unary (×÷ unary)*, unary := - unary | power, power := primary
    (^ unary)?, primary := number | variable | f(sum, …) | (sum). Each leaf, operator and call is one."""
    tokens = [m.group(m.lastindex) for m in TOKEN.finditer(text) if m.group(m.lastindex).strip()]
    position = 0

    def peek():
        return tokens[position] if position < len(tokens) else None

    def take():
        nonlocal position
        position += 1
        return tokens[position - 1]

    def binary_chain(operand, symbols):
        count = operand()
        while peek() in symbols:
            take()
            count += operand() + 1
        return count

    def total():
        return binary_chain(product, ("+", "-"))

    def product():
        return binary_chain(unary, ("*", "/"))

    def unary():
        if peek() == "-":
            take()
            return unary() + 1
        count = primary()
        if peek() == "^":
            take()
            count += unary() + 1
        return count

    def primary():
        token = take()
        if token == "(":
            count = total()
            take()  # ')'
            return count
        if peek() == "(":  # a call: one node over its arguments
            take()
            count = total() + 1
            while take() == ",":
                count += total()
            return count
        return 1

    count = total()
    if position != len(tokens):
        raise ValueError(f"cannot count the nodes of {text!r}")
    return count


# ---- data and the fit -----------------------------------------------------------------------------

def write_samples(number, truth, variables, interval, seed, directory):
    """20 points of the problem drawn with `seed`, as a CSV file (columns: the variables, then f)."""
    rng = random.Random(seed * 1000 + number)
    symbols = {name: sympy.Symbol(name) for name in variables}
    f = sympy.lambdify(list(symbols.values()), to_sympy(truth, symbols), "math")
    path = Path(directory) / f"nguyen{number}.csv"
    lines = [",".join(variables + ["f"])]
    for _ in range(SAMPLES):
        point = [rng.uniform(*interval) for _ in variables]
        lines.append(",".join(repr(v) for v in point + [float(f(*point))]))
    path.write_text("\n".join(lines) + "\n")
    return path


def fit(specula, csv, variables, seed, time_s):
    command = [specula, "fit", "--data", str(csv), "--target", "f", "--vars", ",".join(variables),
               "--ops", OPERATORS, "--time", str(time_s), "--seed", str(seed), "--format", "json", "-q"]
    run = subprocess.run(command, capture_output=True, text=True, timeout=time_s * 10 + 60)
    if run.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: exit {run.returncode}: {run.stderr.strip()}")
    return json.loads(run.stdout)


# ---- the judgement --------------------------------------------------------------------------------

def to_sympy(text, symbols):
    return parse_expr(text.replace("^", "**"), local_dict={**SYMPY_NAMES, **symbols})


def round_floats(expression):
    """SRBench's rounding: every float to 6 decimals."""
    rounded = expression
    for node in sympy.preorder_traversal(expression):
        if isinstance(node, sympy.Float):
            rounded = rounded.subs(node, round(node, 6))
    return rounded


class JudgeTimeout(Exception):
    pass


def _alarm(signum, frame):
    raise JudgeTimeout()


def recovered(formula, truth, variables):
    """SRBench's symbolic solution: the difference is a constant or the ratio a non-zero one."""
    sympy_random.seed(0)  # is_constant() tries random points: the same ones every run
    symbols = {name: sympy.Symbol(name) for name in variables}
    true_model = to_sympy(truth, symbols)
    signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(JUDGE_TIMEOUT_S)
    try:
        model = round_floats(sympy.simplify(to_sympy(formula, symbols), ratio=1))
        difference = round_floats(true_model - model)
        ratio = round_floats(model / true_model)
        if not difference.is_constant() or ratio.is_constant():
            difference = sympy.simplify(difference, ratio=1)
        return bool(difference.is_constant() or (ratio.is_constant() and ratio != 0))
    except Exception:  # JudgeTimeout, or (as in SRBench) a formula SymPy cannot handle: no solution
        return False
    finally:
        signal.alarm(0)


def rounded_text(formula):
    """The formula with its numbers shown to 6 significant digits, for the table."""
    return TOKEN.sub(lambda m: m.group(0).replace(m.group(1), f"{float(m.group(1)):.6g}")
                     if m.group(1) else m.group(0), formula)


# ---- the run --------------------------------------------------------------------------------------

def run_problem(problem, args, directory):
    number, truth, variables, interval = problem
    csv = write_samples(number, truth, variables, interval, args.seed, directory)
    result = fit(args.specula, csv, variables, args.seed, args.time)
    chosen = result["chosen"]
    return {
        "problem": f"Nguyen-{number}",
        "truth": truth,
        "recovered": recovered(chosen["formula"], truth, variables),
        "truth_size": node_count(truth),
        "size": chosen["size"],
        "seconds": result["seconds"],
        "train_rms": chosen["train_error"],
        "formula": chosen["formula"],
    }


def print_row(row):
    print(f"| {row['problem']} | {'yes' if row['recovered'] else 'no'} | {row['truth_size']} | "
          f"{row['size']} | {row['seconds']:.1f} | `{rounded_text(row['formula'])}` |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--specula", default="build/release/specula", help="the CLI to run")
    parser.add_argument("--seed", type=int, default=1, help="seed of the data and of the search")
    parser.add_argument("--problems", default="1-12", help="e.g. 1-12 or 1,5,8")
    parser.add_argument("--time", type=float, default=TIME_S,
                        help="search seconds per problem (the benchmark's setting: 20)")
    parser.add_argument("--json", metavar="FILE", help="write the table and the count as JSON too")
    args = parser.parse_args()
    wanted = set()
    for part in args.problems.split(","):
        first, _, last = part.partition("-")
        if not (first.isdigit() and (last or first).isdigit()):
            parser.error(f"bad --problems part {part!r} (expected e.g. 1-12 or 1,5,8)")
        wanted.update(range(int(first), int(last or first) + 1))
    problems = [p for p in PROBLEMS if p[0] in wanted]
    if not problems:
        parser.error("--problems names none of 1…12")

    print(f"Nguyen benchmark (DSR's specification): {SAMPLES} points, seed {args.seed}; "
          f"specula fit --ops {OPERATORS} --time {args.time:g}; SRBench's symbolic-solution criterion.\n")
    print("| problem | recovered | truth size | size found | seconds | formula |")
    print("|---|---|---|---|---|---|")
    rows = []
    try:
        with tempfile.TemporaryDirectory(prefix="nguyen-") as directory:
            for problem in problems:
                rows.append(run_problem(problem, args, directory))
                print_row(rows[-1])
    except (OSError, RuntimeError, subprocess.TimeoutExpired, json.JSONDecodeError) as error:
        print(f"nguyen_recovery: {error}", file=sys.stderr)
        return 2
    count = sum(row["recovered"] for row in rows)
    print(f"\nrecovered {count}/{len(rows)}")
    if args.json:
        summary = {"operators": OPERATORS, "time_s": args.time, "samples": SAMPLES, "seed": args.seed,
                   "recovered": count, "problems": len(rows), "rows": rows}
        Path(args.json).write_text(json.dumps(summary, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
