#!/usr/bin/python3
"""Symbolic recovery of `specula fit` on Nguyen, Keijzer and Livermore, judged as SRBench judges it.

Problems: Nguyen-1…12, Keijzer-1…15 and Livermore-1…23 (50) as DSR specifies them (Petersen et al.
2021): the formulas and training sets of dso-org/deep-symbolic-optimization, file
dso/dso/task/regression/benchmarks.csv (columns name, variables, expression, train_spec),
transcribed into PROBLEMS below (nothing is downloaded). Its x1, x2, x3 are x, y, z here; the
truths are written in specula's syntax with the benchmark's operators: ^ for pow, a^0.5 for
sqrt(a) (sqrt is not among them), -x for DSR's -1*x (neg is not among them either, but `fit`
simplifies -1*x to -x and counts 2 nodes), exact constants (pi, 1/3) where the truth has them; a
fifth is written 0.2, as `fit` prints it (x^0.2 for x^(1/5)), a third stays 1/3. A training set
is one of DSR's two specs:

    U(n, interval, …)        n points, each variable drawn uniformly from its interval (one
                             interval: every variable's, DSR's "all"), point by point
    E(start, stop, step)     np.linspace(start, stop, int((stop - start) / step) + 1), one variable

U draws with Python's random.Random(1000·seed + offset + number), offset 0 for Nguyen (the streams
of the former bench/fit/nguyen_recovery.py: the same Nguyen data), 100 for Keijzer, 200 for
Livermore, so the points are not DSR's own (NumPy's, seeded by the name's Adler-32); E has no
randomness (the seed still seeds the search). A row whose truth is not a finite real number (a
division by zero, a log of 0) is dropped, not redrawn, and counted (`dropped` in --json; listed
after the table). Unlike DSR's dataset code, which also drops rows with |f| ≥ 100 and redraws U rows
up to n, rows with large values are kept (Keijzer-5, -6, -12 and Livermore-12 have some). The data
go to CSV files in a temporary directory. Every problem is fitted with the same setting, the
release CLI's defaults plus:

    --ops +,-,*,/,sin,cos,exp,log,^  --time 20  --format json  --seed SEED

(constants fitted, RMS, max size 25, the parsimonious choice; both cores; runs one after the
other). Nothing is tuned per problem. Each problem runs once per seed of --seeds (default 1,2).

Recovered: SRBench's symbolic-solution criterion (La Cava et al. 2021, experiment/
assess_symbolic_model.py): the chosen formula, parsed by SymPy and simplified (ratio=1), with every
float rounded to 6 decimals, is a solution when truth − formula simplifies to a constant or
formula / truth is a non-zero constant. (SRBench checks only formulas with test R² > 0.5; that gate
changes nothing for an exact match and is left out.) As in SRBench, a float that rounds to an integer
stays a float: log((-1.0000000000000002 - x)·…) is not judged equal to log(x + 1) + … (but the
rounding applies to the difference and the ratio too: x^0.3333333333 / x^(1/3) = x^(-3.3e-11)
rounds to x^0, so x^0.3333333333 is judged x^(1/3)). SymPy's is_constant() evaluates at random
points, seeded the same for every judgement; one that takes SymPy over 60 s counts as not
recovered.

Recovered on the domain: the same judgement with SymPy's symbols declared positive, for a problem
whose every variable is ≥ 0 on every training row (Nguyen-7…12, Keijzer-4, -6…10, Livermore-4, -5,
-10, -13, -15…17, -19); elsewhere it is the strict judgement. SRBench's symbols carry no sign, so to it
log(x·(x² + 1)) is not log x + log(x² + 1) and √(x²) is not x, although both hold wherever the
truth is defined and the data were drawn. A formula recovered only so is marked "on the domain";
both counts are printed. Sizes and "≤ truth" count every formula recovered either way.

Sizes: the node count `specula fit` reports (every node 1: a leaf, an operator, a function, a
constant fitted or snapped, 2*pi and 1/3 included), the truth's counted by the same rule from its
text below (`node_count`, specula's grammar: a subexpression without variables is one constant).
"≤ truth" says whether a recovered formula is at most the truth's size (bloat when not).

Prints a table (problem, seed, recovered, size of the truth, size found, ≤ truth, seconds of
search, the formula with 6 significant digits), then the count recovered per suite, the total
recovered/(problems × seeds) and how many recovered formulas are larger than their truth; --json
FILE writes the same with the full formulas. --suite and --problems choose what runs (names as
Nguyen-7, or a suite's name as Keijzer), --time changes the budget (for a quick look; recorded
figures are the 20 s setting). A fit that fails (exit status, time-out, bad output) is a row not
recovered with the error for its formula, also on stderr; the run goes on. Exit 0 when every fit
ran (whatever the count), 1 when one failed. About 40 minutes for all three suites and two seeds.

Run by `make bench-fit` with Debian's /usr/bin/python3, python3-sympy and python3-numpy
(scripts/install-deps).
"""

import argparse
import json
import math
import random
import re
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy
import sympy
from sympy.core import random as sympy_random
from sympy.parsing.sympy_parser import parse_expr

OPERATORS = "+,-,*,/,sin,cos,exp,log,^"
TIME_S = 20
SEEDS = "1,2"
SUITES = ("nguyen", "keijzer", "livermore")
SEED_OFFSET = {"nguyen": 0, "keijzer": 100, "livermore": 200}
JUDGE_TIMEOUT_S = 60


def U(n, *intervals):
    return ("U", n, intervals)


def E(start, stop, step):
    return ("E", start, stop, step)


# (name, truth in specula's syntax, variables, training set): DSR's benchmarks.csv
PROBLEMS = [
    ("Nguyen-1", "x^3 + x^2 + x", "x", U(20, (-1, 1))),
    ("Nguyen-2", "x^4 + x^3 + x^2 + x", "x", U(20, (-1, 1))),
    ("Nguyen-3", "x^5 + x^4 + x^3 + x^2 + x", "x", U(20, (-1, 1))),
    ("Nguyen-4", "x^6 + x^5 + x^4 + x^3 + x^2 + x", "x", U(20, (-1, 1))),
    ("Nguyen-5", "sin(x^2)*cos(x) - 1", "x", U(20, (-1, 1))),
    ("Nguyen-6", "sin(x) + sin(x + x^2)", "x", U(20, (-1, 1))),
    ("Nguyen-7", "log(x + 1) + log(x^2 + 1)", "x", U(20, (0, 2))),
    ("Nguyen-8", "x^0.5", "x", U(20, (0, 4))),
    ("Nguyen-9", "sin(x) + sin(y^2)", "xy", U(20, (0, 1))),
    ("Nguyen-10", "2*sin(x)*cos(y)", "xy", U(20, (0, 1))),
    ("Nguyen-11", "x^y", "xy", U(20, (0, 1))),
    ("Nguyen-12", "x^4 - x^3 + 0.5*y^2 - y", "xy", U(20, (0, 1))),
    ("Keijzer-1", "0.3*x*sin(2*pi*x)", "x", E(-1, 1, 0.1)),
    ("Keijzer-2", "0.3*x*sin(2*pi*x)", "x", E(-2, 2, 0.1)),
    ("Keijzer-3", "0.3*x*sin(2*pi*x)", "x", E(-3, 3, 0.1)),
    ("Keijzer-4", "x^3*exp(-x)*cos(x)*sin(x)*(sin(x)^2*cos(x) - 1)", "x", E(0, 10, 0.1)),
    ("Keijzer-5", "30*x*z/((x - 10)*y^2)", "xyz", U(1000, (-1, 1), (-1, 1), (1, 2))),
    ("Keijzer-6", "x*(x + 1)/2", "x", E(1, 50, 1)),
    ("Keijzer-7", "log(x)", "x", E(1, 100, 1)),
    ("Keijzer-8", "x^0.5", "x", E(0, 100, 1)),
    ("Keijzer-9", "log(x + (x^2 + 1)^0.5)", "x", E(0, 100, 1)),
    ("Keijzer-10", "x^y", "xy", U(100, (0, 1))),
    ("Keijzer-11", "x*y + sin((x - 1)*(y - 1))", "xy", U(20, (-3, 3))),
    ("Keijzer-12", "x^4 - x^3 + 0.5*y^2 - y", "xy", U(20, (-3, 3))),
    ("Keijzer-13", "6*sin(x)*cos(y)", "xy", U(20, (-3, 3))),
    ("Keijzer-14", "8/(2 + x^2 + y^2)", "xy", U(20, (-3, 3))),
    ("Keijzer-15", "0.2*x^3 + 0.5*y^3 - y - x", "xy", U(20, (-3, 3))),
    ("Livermore-1", "1/3 + x + sin(x^2)", "x", U(1000, (-10, 10))),
    ("Livermore-2", "sin(x^2)*cos(x) - 2", "x", U(20, (-1, 1))),
    ("Livermore-3", "sin(x^3)*cos(x^2) - 1", "x", U(20, (-1, 1))),
    ("Livermore-4", "log(x + 1) + log(x^2 + 1) + log(x)", "x", U(20, (0, 2))),
    ("Livermore-5", "x^4 - x^3 + y^2 - y", "xy", U(20, (0, 1))),
    ("Livermore-6", "4*x^4 + 3*x^3 + 2*x^2 + x", "x", U(20, (-1, 1))),
    ("Livermore-7", "(exp(x) - exp(-x))/2", "x", U(20, (-1, 1))),
    ("Livermore-8", "(exp(x) + exp(-x))/2", "x", U(20, (-1, 1))),
    ("Livermore-9", "x^9 + x^8 + x^7 + x^6 + x^5 + x^4 + x^3 + x^2 + x", "x", U(20, (-1, 1))),
    ("Livermore-10", "6*sin(x)*cos(y)", "xy", U(20, (0, 1))),
    ("Livermore-11", "x^2*y^2/(x + y)", "xy", U(50, (-1, 1))),
    ("Livermore-12", "x^5/y^3", "xy", U(50, (-1, 1))),
    ("Livermore-13", "x^(1/3)", "x", U(20, (0, 4))),
    ("Livermore-14", "x^3 + x^2 + x + sin(x) + sin(y^2)", "xy", U(20, (-1, 1))),
    ("Livermore-15", "x^0.2", "x", U(20, (0, 4))),
    ("Livermore-16", "x^(2/3)", "x", U(20, (0, 4))),
    ("Livermore-17", "4*sin(x)*cos(y)", "xy", U(20, (0, 1))),
    ("Livermore-18", "sin(x^2)*cos(x) - 5", "x", U(20, (-1, 1))),
    ("Livermore-19", "log(x^2 + x) + log(x^3 + x)", "x", U(20, (0, 2))),
    ("Livermore-20", "x^5 + x^4 + x^2 + x", "x", U(20, (-1, 1))),
    ("Livermore-21", "exp(-x^2)", "x", U(20, (-1, 1))),
    ("Livermore-22", "x^8 + x^7 + x^6 + x^5 + x^4 + x^3 + x^2 + x", "x", U(20, (-1, 1))),
    ("Livermore-23", "exp(-0.5*x^2)", "x", U(20, (-1, 1))),
]

SYMPY_NAMES = {
    "sin": sympy.sin, "cos": sympy.cos, "exp": sympy.exp, "log": sympy.log, "sqrt": sympy.sqrt,
    "pow": sympy.Pow, "abs": sympy.Abs, "min": sympy.Min, "max": sympy.Max, "pi": sympy.pi,
}


def suite_of(name):
    return name.split("-")[0].lower()


# ---- sizes ----------------------------------------------------------------------------------------

TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)|([A-Za-z_]\w*)|(.))")


def node_count(text):
    """Nodes of `text` as specula's parser builds them (src/expr/parse.cpp): sum := product
    (± product)*, product := unary (×÷ unary)*, unary := - unary | power, power := primary
    (^ unary)?, primary := number | variable | f(sum, …) | (sum). Each leaf, operator and call is one;
    a subexpression without variables (2*pi, 1/3, -1) is one, the constant `fit` would hold."""
    tokens = [m.group(m.lastindex) for m in TOKEN.finditer(text) if m.group(m.lastindex).strip()]
    position = 0

    def peek():
        return tokens[position] if position < len(tokens) else None

    def take():
        nonlocal position
        position += 1
        return tokens[position - 1]

    def folded(count, constant):  # (nodes, whether free of variables)
        return (1, True) if constant else (count, False)

    def binary_chain(operand, symbols):
        count, constant = operand()
        while peek() in symbols:
            take()
            right, right_constant = operand()
            count, constant = folded(count + right + 1, constant and right_constant)
        return count, constant

    def total():
        return binary_chain(product, ("+", "-"))

    def product():
        return binary_chain(unary, ("*", "/"))

    def unary():
        if peek() == "-":
            take()
            count, constant = unary()
            return folded(count + 1, constant)
        count, constant = primary()
        if peek() == "^":
            take()
            exponent, exponent_constant = unary()
            return folded(count + exponent + 1, constant and exponent_constant)
        return count, constant

    def primary():
        token = take()
        if token == "(":
            inner = total()
            take()  # ')'
            return inner
        if peek() == "(":  # a call: one node over its arguments
            take()
            count, constant = total()
            count += 1
            while take() == ",":
                argument, argument_constant = total()
                count, constant = count + argument, constant and argument_constant
            return folded(count, constant)
        return 1, token[0].isdigit() or token[0] == "." or token == "pi"

    count, _ = total()
    if position != len(tokens):
        raise ValueError(f"cannot count the nodes of {text!r}")
    return count


# ---- data and the fit -----------------------------------------------------------------------------

def intervals_of(spec, variables):
    """A U spec's interval per variable (one interval: every variable's)."""
    intervals = spec[2]
    return intervals * len(variables) if len(intervals) == 1 else intervals


def points(name, spec, variables, seed):
    """The training points of the spec (see the docstring): a list of tuples, one value per variable."""
    if spec[0] == "E":
        _, start, stop, step = spec
        return [(float(v),) for v in numpy.linspace(start, stop, int((stop - start) / step) + 1)]
    n = spec[1]
    intervals = intervals_of(spec, variables)
    rng = random.Random(1000 * seed + SEED_OFFSET[suite_of(name)] + int(name.split("-")[1]))
    return [tuple(rng.uniform(*interval) for interval in intervals) for _ in range(n)]


def truth_values(truth, variables, rows):
    """The truth at each row: a float, or None where it is not a finite real number."""
    symbols = {name: sympy.Symbol(name) for name in variables}
    f = sympy.lambdify(list(symbols.values()), to_sympy(truth, symbols), "math")
    values = []
    for row in rows:
        try:
            value = f(*row)
        except (ArithmeticError, ValueError):  # ZeroDivisionError, OverflowError, log(0)
            value = None
        finite = isinstance(value, (int, float)) and math.isfinite(value)
        values.append(float(value) if finite else None)
    return values


def write_samples(problem, seed, directory):
    """The problem's training set as a CSV file (columns: the variables, then f), and the count of
    rows dropped for a truth that is not finite."""
    name, truth, variables, spec = problem
    rows = points(name, spec, variables, seed)
    lines = [",".join(list(variables) + ["f"])]
    for row, value in zip(rows, truth_values(truth, variables, rows)):
        if value is not None:
            lines.append(",".join(repr(v) for v in row + (value,)))
    path = Path(directory) / f"{name}-seed{seed}.csv"
    path.write_text("\n".join(lines) + "\n")
    return path, len(rows) + 1 - len(lines)


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


def positive_domain(spec, variables):
    """Whether every variable of the training set is ≥ 0 on every row (the truth's domain there)."""
    if spec[0] == "E":
        return spec[1] >= 0
    return all(low >= 0 for low, _ in intervals_of(spec, variables))


def recovered(formula, truth, variables, positive=False):
    """SRBench's symbolic solution: the difference is a constant or the ratio a non-zero one.
    positive: the variables are SymPy symbols known to be positive (the judgement on the domain)."""
    sympy_random.seed(0)  # is_constant() tries random points: the same ones every run
    symbols = {name: sympy.Symbol(name, positive=True) if positive else sympy.Symbol(name)
               for name in variables}
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

def run_problem(problem, seed, args, directory):
    """One row of the table; a fit that fails is a row not recovered, its error for the formula."""
    name, truth, variables, spec = problem
    csv, dropped = write_samples(problem, seed, directory)
    row = {"problem": name, "suite": suite_of(name), "seed": seed, "truth": truth, "dropped": dropped,
           "truth_size": node_count(truth), "positive_domain": positive_domain(spec, variables),
           "failed": False}
    try:
        result = fit(args.specula, csv, variables, seed, args.time)
        chosen = result["chosen"]
    except (OSError, RuntimeError, subprocess.TimeoutExpired, ValueError, KeyError) as error:
        print(f"recovery: {name} seed {seed}: {error}", file=sys.stderr, flush=True)
        return {**row, "failed": True, "recovered": False, "recovered_on_domain": False, "size": None,
                "size_le_truth": None, "seconds": None, "train_rms": None, "formula": str(error)}
    strict = recovered(chosen["formula"], truth, variables)
    on_domain = strict or (row["positive_domain"] and recovered(chosen["formula"], truth, variables, True))
    return {**row, "recovered": strict, "recovered_on_domain": on_domain, "size": chosen["size"],
            "size_le_truth": chosen["size"] <= row["truth_size"], "seconds": result["seconds"],
            "train_rms": chosen["train_error"], "formula": chosen["formula"]}


def print_row(row):
    smaller = ("yes" if row["size_le_truth"] else "no") if row["recovered_on_domain"] else "–"
    judged = "yes" if row["recovered"] else "on the domain" if row["recovered_on_domain"] else "no"
    if row["failed"]:
        error = " ".join(row["formula"].split()).replace("|", "\\|")  # one table cell
        size, seconds, formula = "–", "–", f"failed: {error}"
    else:
        size, seconds, formula = row["size"], f"{row['seconds']:.1f}", f"`{rounded_text(row['formula'])}`"
    print(f"| {row['problem']} | {row['seed']} | {judged} | "
          f"{row['truth_size']} | {size} | {smaller} | {seconds} | {formula} |", flush=True)


def summary(rows):
    """Counts per suite and in all, as printed and as --json writes them."""
    suites = {suite: [row for row in rows if row["suite"] == suite] for suite in SUITES}
    return {
        "suites": {suite: {"recovered": sum(row["recovered"] for row in some),
                           "recovered_on_domain": sum(row["recovered_on_domain"] for row in some),
                           "fits": len(some)}
                   for suite, some in suites.items() if some},
        "recovered": sum(row["recovered"] for row in rows),
        "recovered_on_domain": sum(row["recovered_on_domain"] for row in rows),
        "fits": len(rows),
        "recovered_larger_than_truth": sum(row["recovered_on_domain"] and not row["size_le_truth"]
                                           for row in rows),
        "failed": sum(row["failed"] for row in rows),
        "dropped": {f"{row['problem']} seed {row['seed']}": row["dropped"]
                    for row in rows if row["dropped"]},
    }


def print_summary(counts):
    print()
    for suite, count in counts["suites"].items():
        print(f"{suite}: recovered {count['recovered']}/{count['fits']}, on the domain "
              f"{count['recovered_on_domain']}/{count['fits']}")
    print(f"total: recovered {counts['recovered']}/{counts['fits']}, on the domain "
          f"{counts['recovered_on_domain']}/{counts['fits']}")
    print(f"recovered but larger than the truth: {counts['recovered_larger_than_truth']}")
    for where, dropped in counts["dropped"].items():
        print(f"{where}: {dropped} rows dropped (truth not finite)")
    if counts["failed"]:
        print(f"failed fits: {counts['failed']}")


def chosen_problems(parser, args):
    """PROBLEMS in --suite and, if given, named by --problems (a name or a suite's name)."""
    suites = {part.strip().lower() for part in args.suite.split(",")}
    if not suites <= set(SUITES):
        parser.error(f"--suite takes some of {','.join(SUITES)}")
    problems = [p for p in PROBLEMS if suite_of(p[0]) in suites]
    if args.problems:
        wanted = {part.strip().lower() for part in args.problems.split(",")}
        known = {p[0].lower() for p in PROBLEMS} | set(SUITES)
        if not wanted <= known:
            unknown = ", ".join(sorted(wanted - known))
            parser.error(f"--problems: unknown {unknown} (e.g. Nguyen-1,Keijzer)")
        problems = [p for p in problems if p[0].lower() in wanted or suite_of(p[0]) in wanted]
    if not problems:
        parser.error("--suite and --problems leave no problem")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--specula", default="build/release/specula", help="the CLI to run")
    parser.add_argument("--suite", default=",".join(SUITES), help="some of nguyen,keijzer,livermore")
    parser.add_argument("--problems", help="names or suites, e.g. Nguyen-1,Keijzer-4 or Keijzer")
    parser.add_argument("--seeds", default=SEEDS, help="seeds of the data and of the search, e.g. 1,2")
    parser.add_argument("--time", type=float, default=TIME_S,
                        help="search seconds per fit (the benchmark's setting: 20)")
    parser.add_argument("--json", metavar="FILE", help="write the table and the counts as JSON too")
    args = parser.parse_args()
    problems = chosen_problems(parser, args)
    if not re.fullmatch(r"\d+(,\d+)*", args.seeds):
        parser.error(f"bad --seeds {args.seeds!r} (expected e.g. 1,2)")
    seeds = [int(seed) for seed in args.seeds.split(",")]

    print(f"DSR's Nguyen, Keijzer and Livermore problems: seeds {args.seeds}; specula fit --ops "
          f"{OPERATORS} --time {args.time:g}; SRBench's symbolic-solution criterion.\n")
    print("| problem | seed | recovered | truth size | size found | ≤ truth | seconds | formula |")
    print("|---|---|---|---|---|---|---|---|")
    rows = []
    with tempfile.TemporaryDirectory(prefix="recovery-") as directory:
        for problem in problems:
            for seed in seeds:
                rows.append(run_problem(problem, seed, args, directory))
                print_row(rows[-1])
    counts = summary(rows)
    print_summary(counts)
    if args.json:
        record = {"operators": OPERATORS, "time_s": args.time, "seeds": seeds, **counts, "rows": rows}
        Path(args.json).write_text(json.dumps(record, indent=2) + "\n")
    return 1 if counts["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
