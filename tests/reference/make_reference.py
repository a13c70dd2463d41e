#!/usr/bin/env python3
"""Independent high-precision reference tables for specula's C++ tests.

Regenerate (from the repository root; writes next to this script, ~tens of seconds):

    python3 tests/reference/make_reference.py

Requires python3 (>= 3.9, for math.nextafter) and mpmath. Deterministic: no randomness,
every input is fixed in this file. Definitions follow docs/math.md (docs: "specula --
the mathematics"), sections "1. Conventions", "2. Models", "3. The log lobe in t-space" and
"4. Exact normalization of the log lobe".

Files written (CSV, header line first, comma separated, no quoting):

  lobes.csv          lobe,n,s,c,value
      F(c) for the lobes power (c^n), schlick, schlick-modified (parameter s; s is 0 for the
      other lobes), gauss and log, at c = 0, 1, 0.5, 0.9, 0.99, 1-1e-6, 1-1e-12,
      2^(-t/n) for t in {0.01, 0.1, 0.5, 1, 2, 2.9, 2.999}, and for `log` points at/around the
      cut-off c0 = 2^(-3/n) (c0 itself, c0 + 1, 4, 1000 ulps, c0*(1+1e-9), c0 - 1 ulp).

  normalization.csv  lobe,form,n,s,coef
      coef = 1 / (2 pi I),  rv: I = int_0^1 F(c) c dc,
                            nh: I = int_{1/sqrt2}^1 F(c) (2c^2 - 1) 4c dc.
      Computed by mpmath.quad in u = -ln c with breakpoints 0, w, 4w, 16w, ... (w = ln2/n) and
      checked (assert, 1e-25 relative) against the closed forms for power rv/nh, schlick rv and
      log rv (E1 form), against an independent quadrature in c for n <= 1000, and against the
      check values of docs/math.md section 4.

  brdfs.csv          model,p1,p2,p3,p4,lx,ly,lz,vx,vy,vz,value (p3, p4: 0.0 past a model's parameters)
      Full BRDFs (ward, ward-duer, ward-gmd, cook-torrance-1982, cook-torrance, lambert, and ggx and
      beckmann with each Fresnel kind: -schlick, -f82, -dielectric, -conductor)
      with N = (0,0,1) and L, V built in doubles from angles; the double components are used
      as given (not renormalized).

Number formats: every input (n, s, c, p1..p4, vector components) is a Python float written with
repr() (shortest round-trip form), and mpmath evaluates at exactly that double (mpf(float)).
Outputs are printed with 20 significant digits by mpmath.nstr (plain decimal or 1.2e-5 style).

Underflow: an output whose magnitude is below the smallest normal double DBL_MIN
(2.2250738585072014e-308) is written as 0.0. Such values (e.g. 0.5^1e5) are 0 or subnormal in
double arithmetic anyway, strtod cannot represent them to relative precision, and C++'s
std::stod throws std::out_of_range on them. Set FLUSH_BELOW_DBL_MIN = False to write them
exactly instead.
"""

import math
import os
import sys
import time

import mpmath
from mpmath import mp, mpf

import make_fresnel_reference as fr  # its Fresnel definitions; it sets 40 digits, so set ours after

mp.dps = 50

HERE = os.path.dirname(os.path.abspath(__file__))
FLUSH_BELOW_DBL_MIN = True
DBL_MIN = mpf(sys.float_info.min)  # 2.2250738585072014e-308, exact as mpf
LN2 = None  # set after mp.dps is fixed (mpmath constants follow the current precision)

flushed = {"lobes.csv": 0, "normalization.csv": 0, "brdfs.csv": 0}


def fin(x):
    """Format an input (a Python float) so that strtod gives back the same double."""
    assert isinstance(x, float), x
    return repr(x)


def fout(x, fname):
    """Format an mpmath output with 20 significant digits."""
    x = mpf(x)
    if x == 0:
        return "0.0"
    if FLUSH_BELOW_DBL_MIN and abs(x) < DBL_MIN:
        flushed[fname] += 1
        return "0.0"
    s = mpmath.nstr(x, 20)
    assert "mpf" not in s and "inf" not in s and "nan" not in s, s
    return s


# ---------------------------------------------------------------------------------------------
# Lobes as functions of the cosine c (docs/math.md section 2). Evaluated at extra precision so that
# the 20 printed digits are exact even for the log lobe just above its cut-off.
# ---------------------------------------------------------------------------------------------

def lobe_c(lobe, n, s, c):
    """F(c) at the exact doubles n, s, c (Python floats). Returns an mpf."""
    with mp.workdps(110):
        n = mpf(n)
        s = mpf(s)
        c = mpf(c)
        if c <= 0:
            return mpf(0)
        if c >= 1:
            c = mpf(1)
        if lobe == "power":
            return c ** n
        if lobe == "schlick":
            return c / (n - n * c + c)
        if lobe == "schlick-modified":
            return (s * c) ** 2 / (n - n * c + s * c) ** 2
        if lobe == "gauss":
            theta = mpmath.acos(c)
            return mpmath.exp(-n * theta ** 2 / 2)
        if lobe == "log":
            # t = -n log2 c; F = 1 - 1/2 log2(1 + t) = -1/2 log2(1 + (t - 3)/4) for t <= 3.
            t = -n * mpmath.log(c) / mpmath.ln2
            if t >= 3 or abs(t - 3) < mpf(10) ** -100:  # exactly at (or beyond) the cut-off
                return mpf(0)
            return -mpmath.log1p((t - 3) / 4) / (2 * mpmath.ln2)
        raise ValueError(lobe)


def lobe_u(lobe, n, s, u):
    """F(e^-u) evaluated directly in u = -ln c (n, s are mpf; u an mpf >= 0)."""
    if lobe == "power":
        return mpmath.exp(-n * u)
    if lobe == "schlick":
        return 1 / (n * mpmath.expm1(u) + 1)
    if lobe == "schlick-modified":
        return (s / (n * mpmath.expm1(u) + s)) ** 2
    if lobe == "gauss":
        theta = 2 * mpmath.asin(mpmath.sqrt(-mpmath.expm1(-u) / 2))
        return mpmath.exp(-n * theta ** 2 / 2)
    if lobe == "log":
        t = n * u / mpmath.ln2
        if t > 3:
            return mpf(0)
        return 1 - mpmath.log1p(t) / (2 * mpmath.ln2)
    raise ValueError(lobe)


# ---------------------------------------------------------------------------------------------
# File 1: lobes.csv
# ---------------------------------------------------------------------------------------------

LOBE_NS = [1e-3, 0.1, 0.5, 1.0, 2.0, 7.0, 20.0, 100.0, 1000.0, 1e5, 1e7, 1e9]
T_POINTS = [0.01, 0.1, 0.5, 1.0, 2.0, 2.9, 2.999]
BASE_C = [0.0, 1.0, 0.5, 0.9, 0.99, 1.0 - 1e-6, 1.0 - 1e-12]


def up_ulps(x, k):
    for _ in range(k):
        x = math.nextafter(x, 2.0)
    return x


def c_points(lobe, n):
    cs = list(BASE_C)
    cs += [2.0 ** (-t / n) for t in T_POINTS]
    if lobe == "log":
        c0 = 2.0 ** (-3.0 / n)
        if c0 >= sys.float_info.min:  # for n = 1e-3, c0 = 2^-3000 underflows: no cut-off points
            cs += [c0, up_ulps(c0, 1), up_ulps(c0, 4), up_ulps(c0, 1000), c0 * (1.0 + 1e-9),
                   math.nextafter(c0, 0.0)]
    cs = [c for c in cs if 0.0 <= c <= 1.0]
    return sorted(set(cs))


def make_lobes():
    rows = []
    combos = []
    for lobe in ["power", "schlick", "schlick-modified", "gauss", "log"]:
        for n in LOBE_NS:
            if lobe == "schlick-modified":
                combos.append((lobe, n, 1.25))
                if n == 20.0:
                    combos.append((lobe, n, 1.0))
                    combos.append((lobe, n, 2.0))
            else:
                combos.append((lobe, n, 0.0))
    for lobe, n, s in combos:
        for c in c_points(lobe, n):
            v = lobe_c(lobe, n, s, c)
            assert 0 <= v <= 1, (lobe, n, s, c, v)
            rows.append([lobe, fin(n), fin(s), fin(c), fout(v, "lobes.csv")])
    # Sanity checks on the table itself.
    for lobe, n, s in combos:
        assert lobe_c(lobe, n, s, 1.0) == 1
        assert lobe_c(lobe, n, s, 0.0) == 0
    for n in LOBE_NS:  # F_log - c^n = 1 - 1/2 log2(1+t) - 2^-t, n-independent (docs/math.md section 3)
        c = 2.0 ** (-1.0 / n)
        if c > 0:
            with mp.workdps(110):
                t = -mpf(n) * mpmath.log(mpf(c)) / mpmath.ln2
                want = 1 - mpmath.log(1 + t, 2) / 2
                got = lobe_c("log", n, 0.0, c)
                assert abs(got - want) < mpf(10) ** -90, (n, got, want)
    return ["lobe,n,s,c,value"] + [",".join(r) for r in rows]


# ---------------------------------------------------------------------------------------------
# File 2: normalization.csv
# ---------------------------------------------------------------------------------------------

NORM_NS = [1e-3, 0.01, 0.1, 0.5, 0.9, 1.0, 1.1, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 10.0, 20.0,
           50.0, 100.0, 1000.0, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9]
NORM_COMBOS = [("power", "rv", 0.0), ("power", "nh", 0.0), ("schlick", "rv", 0.0),
               ("schlick", "nh", 0.0), ("schlick-modified", "rv", 1.25), ("gauss", "rv", 0.0),
               ("gauss", "nh", 0.0), ("log", "rv", 0.0), ("log", "nh", 0.0)]
REL_TOL = mpf("1e-25")


def breakpoints(lobe, form, n):
    """Sub-interval endpoints in u: 0, w, 4w, 16w, ... (w = ln2/n), plus a few fixed points
    (1/8, 1/2, 2, 8, 32) so that small-n lobes, whose width is set by the e^-2u weight rather
    than by w, are also split sensibly; the log lobe's support end 3 ln2/n is an endpoint."""
    n = mpf(n)
    end = mpmath.inf if form == "rv" else mpmath.ln2 / 2
    if lobe == "log":
        end = min(end, 3 * mpmath.ln2 / n)
    w = mpmath.ln2 / n
    pts = set()
    b = w
    while b < end and b < 64:
        pts.add(b)
        b *= 4
    for f in [mpf(1) / 8, mpf(1) / 2, mpf(2), mpf(8), mpf(32)]:
        if f < end:
            pts.add(f)
    pts = sorted(p for p in pts if 0 < p < end)
    # Drop points closer than 1e-30 (relative) to the end, e.g. log nh at n = 6 where
    # 3 ln2/n == ln2/2 up to rounding.
    if end != mpmath.inf:
        pts = [p for p in pts if abs(end - p) > end * mpf(10) ** -30]
    return [mpf(0)] + pts + [end]


def integral_u(lobe, form, n, s):
    nn, ss = mpf(n), mpf(s)
    if form == "rv":
        def f(u):
            return lobe_u(lobe, nn, ss, u) * mpmath.exp(-2 * u)
    else:
        def f(u):
            e2 = mpmath.exp(-2 * u)
            return lobe_u(lobe, nn, ss, u) * (2 * e2 - 1) * 4 * e2
    pts = breakpoints(lobe, form, n)
    total = mpf(0)
    for a, b in zip(pts[:-1], pts[1:]):
        total += mpmath.quad(f, [a, b])
    return total


def integral_c(lobe, form, n, s):
    """Independent check: the same integral in c with the direct lobe definition lobe_c."""
    lo = mpf(0) if form == "rv" else 1 / mpmath.sqrt(2)
    pts_u = breakpoints(lobe, form, n)
    pts = sorted(set([lo, mpf(1)] + [mpmath.exp(-u) for u in pts_u if u != mpmath.inf
                                      and mpmath.exp(-u) > lo]))
    nn, ss = mpf(n), mpf(s)

    def F(c):  # lobe_c at mpf arguments, same formulas
        if lobe == "power":
            return c ** nn
        if lobe == "schlick":
            return c / (nn - nn * c + c)
        if lobe == "schlick-modified":
            return (ss * c) ** 2 / (nn - nn * c + ss * c) ** 2
        if lobe == "gauss":
            return mpmath.exp(-nn * mpmath.acos(c) ** 2 / 2)
        if lobe == "log":
            t = -nn * mpmath.log(c, 2)
            return mpf(0) if t >= 3 else 1 - mpmath.log(1 + t, 2) / 2
        raise ValueError(lobe)

    if form == "rv":
        g = lambda c: F(c) * c
    else:
        g = lambda c: F(c) * (2 * c * c - 1) * 4 * c
    return mpmath.quad(g, pts)


def closed_form_coef(lobe, form, n):
    """Closed forms of docs/math.md section 2 ("Known exact normalizations") and section 4, or None."""
    with mp.workdps(int(50 + 2 * max(0.0, math.log10(n))) + 10):
        nn = mpf(n)
        if lobe == "power" and form == "rv":
            return +((nn + 2) / (2 * mpmath.pi))
        if lobe == "power" and form == "nh":
            return +((nn + 2) * (nn + 4) / (8 * mpmath.pi * (mpf(2) ** (-nn / 2) + nn)))
        if lobe == "schlick" and form == "rv":
            if n == 1.0:
                return +(3 / (2 * mpmath.pi))
            bracket = (nn ** 2 * mpmath.log(nn) / (nn - 1) ** 3 - nn / (nn - 1) ** 2
                       - 1 / (2 * (nn - 1)))
            return +(1 / (2 * mpmath.pi * bracket))
        if lobe == "log" and form == "rv":
            a = 2 * mpmath.ln2 / nn
            return +(1 / (mpmath.pi * (1 - mpmath.exp(a) / (2 * mpmath.ln2)
                                       * (mpmath.e1(a) - mpmath.e1(4 * a)))))
    return None


def make_normalization(log):
    rows = []
    checks = 0
    worst = mpf(0)
    for lobe, form, s in NORM_COMBOS:
        for n in NORM_NS:
            I = integral_u(lobe, form, n, s)
            coef = 1 / (2 * mpmath.pi * I)
            cf = closed_form_coef(lobe, form, n)
            if cf is not None:
                rel = abs(coef / cf - 1)
                worst = max(worst, rel)
                checks += 1
                if not rel < REL_TOL:
                    raise AssertionError("closed form mismatch %s %s n=%r: quad %s closed %s rel %s"
                                         % (lobe, form, n, coef, cf, mpmath.nstr(rel, 3)))
            if n <= 1000.0:
                Ic = integral_c(lobe, form, n, s)
                rel = abs(Ic / I - 1)
                worst = max(worst, rel)
                checks += 1
                if not rel < REL_TOL:
                    raise AssertionError("c-space mismatch %s %s n=%r: u %s c %s rel %s"
                                         % (lobe, form, n, I, Ic, mpmath.nstr(rel, 3)))
            rows.append([lobe, form, fin(n), fin(s), fout(coef, "normalization.csv")])
            if lobe == "log" and form == "rv":
                for nv, want in [(1.0, "0.48274947790781993"), (1000.0, "197.49861008019521")]:
                    if n == nv:
                        # The check values are 17-digit doubles; docs/math.md's coef(1000) is one
                        # ulp (1.6e-16 relative) above the correctly rounded double
                        # 197.4986100801952, so compare to 1e-15 relative.
                        rel = abs(coef / mpf(want) - 1)
                        log("log rv check value coef(%r) = %s: docs/math.md %s, relative difference %s"
                            % (n, mpmath.nstr(coef, 20), want, mpmath.nstr(rel, 3)))
                        if not rel < mpf("1e-15"):
                            raise AssertionError("log rv check value n=%r: %s vs %s" % (n, coef, want))
    log("normalization: %d cross-checks passed, worst relative difference %s"
        % (checks, mpmath.nstr(worst, 3)))
    return ["lobe,form,n,s,coef"] + [",".join(r) for r in rows]


# ---------------------------------------------------------------------------------------------
# File 3: brdfs.csv
# ---------------------------------------------------------------------------------------------

# Each model's parameter sets, in the registry's order (the roughness first).
FRESNEL_PARAMS = {
    "schlick": [(0.3, 0.04, 1.0, 5.0), (0.5, 0.2, 0.8, 3.0)],
    "f82": [(0.3, 0.9, 0.8), (0.6, 0.5, 1.0)],
    "dielectric": [(0.3, 1.5), (0.5, 0.66)],  # 0.66: from the denser side, total internal reflection
    "conductor": [(0.3, 0.2, 3.1), (0.6, 1.5, 0.0)],
}
BRDF_PARAMS = [
    ("ward", [(0.05, 1.0), (0.2, 1.0), (0.5, 0.7)]),
    ("ward-duer", [(0.05, 1.0), (0.2, 1.0), (0.5, 0.7)]),
    ("ward-gmd", [(0.05, 1.0), (0.2, 1.0), (0.5, 0.7)]),
    ("cook-torrance-1982", [(0.1, 1.0), (0.3, 0.04), (0.6, 1.0)]),
    ("cook-torrance", [(0.1, 1.0), (0.3, 0.04), (0.6, 1.0)]),
    ("ggx", [(0.05, 1.0), (0.3, 0.04), (0.8, 1.0)]),
    ("lambert", [(1.0, 0.0), (0.5, 0.0)]),
    ("beckmann", [(0.05, 1.0), (0.3, 0.04), (0.8, 1.0)]),
] + [("%s-%s" % (family, kind), params) for family in ("ggx", "beckmann")
     for kind, params in FRESNEL_PARAMS.items()]
PARAM_COLUMNS = 4  # p1..p4: a model's parameters, 0.0 past its own
THETA_L = [0.0, 30.0, 60.0, 85.0]
THETA_V = [0.0, 20.0, 45.0, 80.0, 89.0]
PHI_V = [0.0, 90.0, 180.0]


def directions():
    out = []
    seen = set()
    for tl in THETA_L:
        a = math.radians(tl)
        L = (math.sin(a), 0.0, math.cos(a))
        for tv in THETA_V:
            for pv in PHI_V:
                b, p = math.radians(tv), math.radians(pv)
                V = (math.sin(b) * math.cos(p), math.sin(b) * math.sin(p), math.cos(b))
                key = L + V
                if key in seen:  # theta_v = 0 gives the same V for every phi_v
                    continue
                seen.add(key)
                out.append((L, V))
    return out


def fresnel(kind, c, p):
    """The Fresnel of `kind` at cosine c with parameters p (after the roughness), from
    make_fresnel_reference.py's definitions (complex amplitudes for the dielectric and conductor)."""
    if kind == "schlick":
        return fr.schlick(c, p[0], p[1], p[2])
    if kind == "f82":
        return fr.f82(c, p[0], p[1])
    if kind == "dielectric":
        return fr.dielectric(c, p[0])
    if kind == "conductor":
        return fr.conductor(c, p[0], p[1])
    return p[0] + (1 - p[0]) * (1 - c) ** 5  # Schlick's F0


def brdf(model, params, L, V):
    L = [mpf(x) for x in L]
    V = [mpf(x) for x in V]
    params = [mpf(x) for x in params]
    p1, p2 = params[0], params[1] if len(params) > 1 else mpf(0)
    NL, NV = L[2], V[2]
    if NL <= 0 or NV <= 0:
        return mpf(0)
    if model == "lambert":
        return p1 / mpmath.pi
    h = [L[i] + V[i] for i in range(3)]
    hh = sum(x * x for x in h)
    hlen = mpmath.sqrt(hh)
    H = [x / hlen for x in h]
    NH = H[2]
    VH = sum(V[i] * H[i] for i in range(3))
    tan2d = (1 - NH ** 2) / NH ** 2
    if model in ("ward", "ward-duer", "ward-gmd"):
        alpha, rho = p1, p2
        e = mpmath.exp(-tan2d / alpha ** 2)
        if model == "ward":
            return rho / (4 * mpmath.pi * alpha ** 2 * mpmath.sqrt(NL * NV)) * e
        if model == "ward-duer":
            return rho / (4 * mpmath.pi * alpha ** 2 * NL * NV) * e
        return rho * hh / (mpmath.pi * alpha ** 2 * h[2] ** 4) * e

    def schlick_F(f0):
        return f0 + (1 - f0) * (1 - VH) ** 5

    if model in ("cook-torrance-1982", "cook-torrance"):
        m, f0 = p1, p2
        G = min(mpf(1), 2 * NH * NV / VH, 2 * NH * NL / VH)
        cos4 = NH ** 4
        if model == "cook-torrance-1982":
            D = mpmath.exp(-tan2d / m ** 2) / (m ** 2 * cos4)
            if f0 == 1:
                F = mpf(1)
            else:
                sf = mpmath.sqrt(f0)
                eta = (1 + sf) / (1 - sf)
                c = VH
                g = mpmath.sqrt(eta ** 2 + c ** 2 - 1)
                F = (mpf(1) / 2 * (g - c) ** 2 / (g + c) ** 2
                     * (1 + (c * (g + c) - 1) ** 2 / (c * (g - c) + 1) ** 2))
            return D * F * G / (mpmath.pi * NL * NV)
        D = mpmath.exp(-tan2d / m ** 2) / (mpmath.pi * m ** 2 * cos4)
        return D * schlick_F(f0) * G / (4 * NL * NV)
    family, _, kind = model.partition("-")
    if family in ("ggx", "beckmann"):
        a2 = p1 ** 2
        F = fresnel(kind, VH, params[1:])
        if family == "ggx":
            D = a2 / (mpmath.pi * (NH ** 2 * (a2 - 1) + 1) ** 2)

            def Lam(z):
                t2 = (1 - z ** 2) / z ** 2
                return (-1 + mpmath.sqrt(1 + a2 * t2)) / 2
        else:
            D = mpmath.exp(-tan2d / a2) / (mpmath.pi * a2 * NH ** 4)

            def Lam(z):  # Smith's Beckmann Lambda, a = cot(theta) / alpha
                a = z / (p1 * mpmath.sqrt(1 - z ** 2)) if z < 1 else mpmath.inf
                return (mpmath.exp(-a ** 2) / (a * mpmath.sqrt(mpmath.pi)) - mpmath.erfc(a)) / 2
        return D * F / ((1 + Lam(NL) + Lam(NV)) * 4 * NL * NV)
    raise ValueError(model)


def make_brdfs():
    rows = []
    dirs = directions()
    for model, sets in BRDF_PARAMS:
        for params in sets:
            columns = list(params) + [0.0] * (PARAM_COLUMNS - len(params))
            for L, V in dirs:
                v = brdf(model, params, L, V)
                assert v >= 0, (model, params, L, V, v)
                rows.append([model] + [fin(p) for p in columns] + [fin(x) for x in L] + [fin(x) for x in V]
                            + [fout(v, "brdfs.csv")])
    # Helmholtz reciprocity of the formulas (swap L and V): exact in math for unit vectors; here
    # ~1e-16, since the double vectors are not exactly unit (V.H != L.H in the last bits).
    for model, sets in BRDF_PARAMS:
        for params in sets:
            for L, V in dirs[:20]:
                a, b = brdf(model, params, L, V), brdf(model, params, V, L)
                assert abs(a - b) <= mpf(10) ** -13 * max(abs(a), mpf(10) ** -300), (model, L, V)
    return ["model,p1,p2,p3,p4,lx,ly,lz,vx,vy,vz,value"] + [",".join(r) for r in rows]


def write(name, lines):
    path = os.path.join(HERE, name)
    with open(path, "w", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")
    return path


def main():
    t0 = time.time()

    def log(msg):
        print("[%6.1fs] %s" % (time.time() - t0, msg), flush=True)

    only = sys.argv[1:]  # table names to write (default: all)
    for name, make in [("lobes.csv", make_lobes), ("brdfs.csv", make_brdfs),
                       ("normalization.csv", lambda: make_normalization(log))]:
        if only and name not in only:
            continue
        lines = make()
        path = write(name, lines)
        log("wrote %s: %d rows (%d values below DBL_MIN written as 0.0)"
            % (os.path.relpath(path), len(lines) - 1, flushed[name]))
    log("done")


if __name__ == "__main__":
    main()
