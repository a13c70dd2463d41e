#!/usr/bin/python3
"""Checks a `specula design` front independently: every member of DIR/front.csv is evaluated
through `specula --models DIR/models.toml eval` on a dense grid of c and of the range parameter,
against the target computed here, and its largest error may not exceed the max_abs_error
front.csv claims.

    /usr/bin/python3 bench/design/check_front.py DIR [--specula build/release/specula]

The target (DIR/design.json) is computed without specula: phong as c^n, the engine terms from
their textbook formulas (the exact dielectric and conductor Fresnel in Python's complex
arithmetic, (1 - c)^5, the height-correlated Smith G2 of GGX and of Beckmann, the latter's
Lambda through Python's math.erfc), an `expr:` target through SymPy (its own parameters from
design.json). Other lobe targets are not supported. A target of several per-pixel variables
(NoV, NoL) has its members' formulas from front.csv evaluated here too, through NumPy,
on a tensor grid of the variables (denser toward 0) at each parameter value. The split-sum terms
(env-brdf-*) are integrated here by Gauss-Legendre over the half vector, and their claims, which
specula measures against its table, may be low by the table's stated 2e-3; the pairs (env-brdf-ggx,
env-brdf-beckmann) have each member checked at output = 0 against A and at output = 1 against B.
Prints one line per
member (claimed, found on the grid, where) and exits 1 if a claim is low.
"""
import argparse
import cmath
import csv
import json
import math
import subprocess
import sys


def dielectric(c, eta):
    g2 = eta * eta - 1 + c * c
    if g2 < 0:
        return 1.0  # total internal reflection
    g = math.sqrt(g2)
    a, b = (g - c) / (g + c), (c * (g + c) - 1) / (c * (g - c) + 1)
    return 0.5 * a * a * (1 + b * b)


def conductor(c, eta, kappa):
    n = complex(eta, kappa)
    cos_t = cmath.sqrt(1 - (1 - c * c) / (n * n))
    rs = (c - n * cos_t) / (c + n * cos_t)
    rp = (n * c - cos_t) / (n * c + cos_t)
    return (abs(rs) ** 2 + abs(rp) ** 2) / 2


def smith_g2_ggx(v, l, a):
    return 2 * v * l / (l * math.sqrt(v * v * (1 - a * a) + a * a) + v * math.sqrt(l * l * (1 - a * a) + a * a))


def beckmann_lambda(cos, alpha):
    """Smith's Lambda of Beckmann (Walter et al. 2007, eq. 25), a = cos / (alpha sin)."""
    if cos >= 1:
        return 0.0
    a = cos / (alpha * math.sqrt(1 - cos * cos))
    return (math.exp(-a * a) / (a * math.sqrt(math.pi)) - math.erfc(a)) / 2


def smith_g2_beckmann(v, l, a):
    return 1 / (1 + beckmann_lambda(v, a) + beckmann_lambda(l, a))


def split_sum(part, distribution):
    """A or B of the split sum at (mu, r), alpha = r^2: the albedo with F = 1 - w or F = w,
    w = (1 - V.H)^5, by Gauss-Legendre over the half vector in s = atan(tan(theta_h) / alpha)
    (the lobe's own scale) and phi_h, the reflected direction's N.L > 0 kept."""
    import numpy
    nodes, weights = numpy.polynomial.legendre.leggauss(160)
    s = (nodes + 1) * math.pi / 4
    phi = (nodes + 1) * math.pi / 2  # over [0, pi]: the integrand is even in phi
    S, P = numpy.meshgrid(s, phi, indexing="ij")
    W = numpy.outer(weights, weights) * (math.pi / 4) * (math.pi / 2) * 2

    def lam(c, a):
        c = numpy.clip(c, 1e-150, 1)
        t2 = (1 - c * c) / (c * c)
        if distribution == "ggx":
            return (-1 + numpy.sqrt(1 + a * a * t2)) / 2
        x = 1 / (a * numpy.sqrt(t2) + 1e-300)
        return numpy.where(x > 30, 0.0, (numpy.exp(-x * x) / (x * math.sqrt(math.pi)) - numpy.vectorize(math.erfc)(x)) / 2)

    def value(mu, r):
        a = max(r * r, 0.001)
        th = numpy.arctan(a * numpy.tan(S))
        dth = a / numpy.cos(S) ** 2 / (1 + (a * numpy.tan(S)) ** 2)
        hx, hy, hz = numpy.sin(th) * numpy.cos(P), numpy.sin(th) * numpy.sin(P), numpy.cos(th)
        vx, vz = math.sqrt(1 - mu * mu), mu
        vh = vx * hx + vz * hz
        lz = 2 * vh * hz - vz
        if distribution == "ggx":
            d = a * a / (math.pi * (hz * hz * (a * a - 1) + 1) ** 2)
        else:
            d = numpy.exp(-(numpy.tan(th) / a) ** 2) / (math.pi * a * a * hz ** 4)
        g = 1 / (1 + lam(numpy.full_like(lz, mu), a) + lam(lz, a))
        w = (1 - numpy.clip(vh, 0, 1)) ** 5
        f = w if part == "b" else 1 - w
        integrand = numpy.where((lz > 0) & (vh > 0), d * g * f * vh / mu * numpy.sin(th) * dth, 0.0)
        return float(numpy.sum(integrand * W))
    return lambda v, l, p: value(v, l)


SEVERAL = {"smith-g2-ggx": smith_g2_ggx, "smith-g2-beckmann": smith_g2_beckmann,
           **{f"env-brdf-{part}-{d}": split_sum(part, d) for part in "ab" for d in ("ggx", "beckmann")}}
# Targets of several outputs: each output's function, the member evaluated at output = 0, 1, ...
OUTPUTS = {f"env-brdf-{d}": [SEVERAL[f"env-brdf-a-{d}"], SEVERAL[f"env-brdf-b-{d}"]] for d in ("ggx", "beckmann")}


def target_function(design):
    """f(c, p): the target at cosine c and range-parameter value p."""
    target, params = design["target"], design["params"]
    if target == "phong":
        return lambda c, p: c ** p
    if target == "fresnel-dielectric":
        return lambda c, p: dielectric(c, p)
    if target == "fresnel-conductor":
        kappa = params.get("kappa", 1.0)
        return lambda c, p: conductor(c, p, kappa)
    if target == "schlick-weight":
        return lambda c, p: (1 - c) ** 5
    if target.startswith("expr:"):
        import sympy
        symbols = {name: sympy.Symbol(name) for name in ["c", design["param"], *params] if name}
        expression = sympy.sympify(target[5:].replace("^", "**"), locals=symbols).subs(params)
        f = sympy.lambdify([symbols["c"], symbols.get(design["param"], sympy.Symbol("unused"))], expression, "math")
        return lambda c, p: float(f(c, p))
    raise SystemExit(f"check_front: no independent formula for the target '{target}'")


def member_values(specula, models, member, param, value, cosines):
    extra = ["-p", f"{param}={value!r}"] if param else []
    out = subprocess.run([specula, "--models", models, "eval", "--model", member, *extra, "--cos", cosines, "--lobe"],
                         check=True, capture_output=True, text=True).stdout
    rows = list(csv.reader(out.splitlines()))[1:]
    return [(float(c), float(v)) for c, v in rows]


def several_variables(design, members, points):
    """Members of a target of several per-pixel variables, their formulas evaluated here."""
    import numpy
    variables, param, lo, hi = design["variables"], design["param"], design["lo"], design["hi"]
    outputs = OUTPUTS.get(design["target"])
    if design["target"] not in SEVERAL and not outputs:
        raise SystemExit(f"check_front: no independent formula for the target '{design['target']}'")
    targets = outputs or [SEVERAL[design["target"]]]
    tabulated = design["target"].startswith("env-brdf-")  # each value a cubature here: a coarser grid
    axis = (sorted({(i / 24) ** 2 for i in range(1, 25)} | {i / 12 for i in range(1, 13)}) if tabulated else
            sorted({(i / 160) ** 2 for i in range(1, 161)} | {i / 160 for i in range(1, 161)} | {1e-6, 1e-4}))
    grid = [lo + (hi - lo) * i / (points - 1) for i in range(points)] if param else [lo]
    functions = {"max": numpy.maximum, "min": numpy.minimum, "sqrt": numpy.sqrt, "exp": numpy.exp, "log": numpy.log,
                 "log2": numpy.log2, "abs": numpy.abs, "pi": math.pi, "__builtins__": {}}
    known = [{} for _ in targets]

    def cached(o, x, y):  # the tabulated terms' cubature, once per point for every member
        if not known[o]:
            known[o].update({(v, l): targets[o](v, l, None) for v, l in zip(x.flat, y.flat)})
        return numpy.vectorize(lambda v, l: known[o][(v, l)])(x, y)
    low = 0
    for m in members:
        code = compile(m["formula"].replace("^", "**"), m["id"], "eval")

        def f(x, y, o, p, code=code):
            point = [x, y, o] if outputs else [x, y]
            with numpy.errstate(all="ignore"):
                return eval(code, functions, dict(zip([*variables, param], [*point, p])))
        claimed, found, where = float(m["max_abs_error"]), 0.0, None
        for p in grid + ([float(m["argmax_param"])] if param else []):
            for o, target in enumerate(targets):
                x, y = numpy.meshgrid(axis, axis)
                values = numpy.broadcast_to(f(x, y, o, p), x.shape)
                exact = numpy.vectorize(lambda v, l: target(v, l, p))(x, y) if not tabulated else cached(o, x, y)
                errors = numpy.abs(values - exact)
                k = int(numpy.nanargmax(errors))
                if errors.flat[k] > found:
                    found, where = float(errors.flat[k]), (x.flat[k], y.flat[k], p)
        # A tabulated term's claims are measured against its table, within 2e-3 of the cubature.
        ok = found <= claimed * (1 + 1e-9) + (2e-3 if tabulated else 1e-15)
        low += not ok
        at_param = f", {param} = {where[2]:.6g}" if param else ""
        print(f"{m['id']:<24} claimed {claimed:.6g}  found {found:.6g} at {variables[0]} = {where[0]:.6g}, "
              f"{variables[1]} = {where[1]:.6g}{at_param}  {'ok' if ok else 'CLAIM TOO LOW'}")
    return 1 if low else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir")
    parser.add_argument("--specula", default="build/release/specula")
    parser.add_argument("--points", type=int, default=48, help="values of the range parameter over its range")
    args = parser.parse_args()
    models = f"{args.dir}/models.toml"
    with open(f"{args.dir}/design.json") as f:
        design = json.load(f)
    with open(f"{args.dir}/front.csv", newline="") as f:
        members = [r for r in csv.DictReader(f) if r["kind"] == "member"]
    if len(design.get("variables", ["c"])) > 1:
        return several_variables(design, members, min(args.points, 24))
    target = target_function(design)
    param, lo, hi = design["param"], design["lo"], design["hi"]
    log = lo > 0 and hi / lo >= 4
    grid = [lo * (hi / lo) ** (i / (args.points - 1)) if log else lo + (hi - lo) * i / (args.points - 1)
            for i in range(args.points)] if param else [lo]
    # Lobes live near c = 1; functions of c anywhere, grazing (c -> 0) included.
    cosine_grids = ("0:1@2001", "0.95:1@2001", "0.999:1@1001", "1e-6:0.01@1001")
    low = 0
    for m in members:
        claimed = float(m["max_abs_error"])
        found, where = 0.0, None
        for p in grid + ([float(m["argmax_param"])] if param else []):
            for cosines in cosine_grids:
                for c, v in member_values(args.specula, models, m["id"], param, p, cosines):
                    if c <= 0:
                        continue  # the target is defined on (0, 1]
                    e = abs(v - target(c, p))
                    if e > found:
                        found, where = e, (c, p)
        ok = found <= claimed * (1 + 1e-9) + 1e-15
        low += not ok
        print(f"{m['id']:<24} claimed {claimed:.6g}  found {found:.6g} at c = {where[0]:.6g}"
              f"{f', {param} = {where[1]:.6g}' if param else ''}  {'ok' if ok else 'CLAIM TOO LOW'}")
    return 1 if low else 0


if __name__ == "__main__":
    sys.exit(main())
