#!/usr/bin/env python3
"""Independent high-precision directional albedo table for specula's C++ tests.

Regenerate (from the repository root; writes next to this script, about 80 s on 2 cores):

    python3 tests/reference/make_albedo_reference.py [--jobs N]

Requires python3 (>= 3.9) and mpmath (plus the standard library's decimal module). Deterministic:
no randomness, every input is fixed in this file, and the output does not depend on --jobs
(default: 2 worker processes). Definitions follow docs/math.md (docs: "specula -- the
mathematics"), sections "1. Conventions", "2. Models" and "4. Exact normalization of the log lobe".

File written (CSV, header line first, comma separated, no quoting):

  albedo.csv   model,form,p1,p2,theta_deg,albedo

  albedo(theta_i) = int_{H^2} f(L, V) (N.V) dw_V over the upper hemisphere, N = (0, 0, 1),
  L = (sin theta_i, 0, cos theta_i), theta_i = theta_deg * pi / 180 taken exactly (not the
  double-rounded vector). `form` is `rv` or `nh` for a lobe model f = k F(c) (c = R.V or N.H,
  R = 2 (N.L) N - L, H = (L + V)/|L + V|) and `-` for a full BRDF; p1, p2 are the model
  parameters (n and 0 for the lobe models).

Two independent methods, both in polar coordinates (s, phi) around a centre, phi in [0, pi] and
doubled (every integrand here is even in phi, L lies in the xz plane):

Method A (the value written; ~30 significant digits of working precision):
  * `rv` lobes: V around the mirror direction R (frame R), s = angle(R, V), dw = sin s ds dphi.
    The lobe is F(cos s); the phi integral (of N.V only) is still done numerically.
  * `nh` lobes and full BRDFs: the half vector H around N (frame H), s = theta_h,
    V = 2 (L.H) H - L, dw_V = 4 (V.H) sin theta_h dtheta_h dphi. The microfacet distribution
    (or nh lobe) is a function of s alone.
  The factor that depends on s alone (lobe, D, exp(-tan^2/alpha^2), normalization) is computed
  with mpmath at mp.dps = 34; the rest of the integrand (N.V, L.H, G, Fresnel, Ward's
  1/sqrt(N.L N.V), GGX's Lambda) with Python's decimal module at 32 digits (+ - * / and sqrt
  only; decimal is C-accelerated, mpmath's pure-Python mpf arithmetic is ~25x slower here).
  Inner variable X = cos phi (the 1/sqrt(1 - X^2) end singularities are handled by the rule).
  Quadrature: tanh-sinh (nodes from mpmath) on every piece, both levels, refined until two
  successive step halvings agree to 1e-14 relative (the error is then ~ the square of that).
Method B (the check; double precision, different code):
  The other frame of the two (rv lobes around H, nh lobes and full BRDFs around R, where the
  lobe is no longer a function of s: the phi integral is also split along its level curves),
  inner variable phi, and the BRDF evaluated from the vectors L, V by a separate implementation
  of docs/math.md section 2 in Python floats (1 - c from |R - V|^2 / 2 or sin^2(delta)/(1 + N.H), so
  that c^1000 and exp(-tan^2/alpha^2) keep full relative accuracy). Tanh-sinh in floats,
  refined until two successive levels agree to 1e-12.

Splitting (both methods). Every kink is a sub-interval end:
  * phi: at fixed s, N.V, L.V, L.H (and R.V in frame H) are polynomials of degree <= 2 in
    X = cos phi, and so is every kink condition: the horizon N.V = 0, the Cook-Torrance masking
    switches 2(N.H)(N.V)/(V.H) = 1, 2(N.H)(N.L)/(V.H) = 1 and N.V = N.L, the log lobe's support
    end c = c0 = 2^(-3/n), c = 0 for rv lobes, and in method B the lobe's level curves. Their
    real roots in (-1, 1) above the horizon split the phi integral exactly.
  * s: lobe width multiples (t = -n log2 c in {1/4, 1, 4, 16, 64, ...}; tan(beta) = width *
    {1/2, 1, 2, 4, 8, ...} for the microfacet and Ward models) and their images in the other
    frame, the lobe's support end, the start of the horizon cut, and every s where the ordered
    set of phi-kinks changes (a root crosses X = +-1, two roots meet, a pair appears): found on
    a fine grid of s and refined by bisection to ~1e-28.

Asserted inside the script:
  * methods A and B agree to REL_TOL = 1e-12 relative for every row (the log line "worst
    relative difference" gives the achieved agreement, ~2e-15, limited by B's double precision);
  * anchors, on method A to ANCHOR_TOL = 1e-20 relative (28 rows): lambert's albedo is rho at
    every angle; phong-normalized (rv), blinn-phong-normalized (nh) and log-normalized (rv) have
    albedo 1 at theta_i = 0 (their normalization); an rv lobe whose support stays above the
    horizon (log-normalized, acos c0 <= 90 deg - theta_i) has albedo cos theta_i exactly (the
    phi integral of N.V = cos s cos ti + sin s sin ti cos phi keeps the first term only);
    blinn-phong-normalized n = 1000 at 30 deg (not clipped) has cos^2 ti + sin^2 ti * 2/(n +
    2^(-n/2)); every full BRDF at theta_i = 0 equals a hand reduction to one integral over
    u = tan^2(theta_h) (closed form for ward-gmd: rho_s (1 - a^2 + a^2 e^(-1/a^2)));
  * method B's float BRDFs equal make_reference.py's (mpmath) at 12 directions per model.
Method A's 20 printed digits are stable: tightening its tolerance to 1e-18, its minimum level
to 3 and the transition grid to 32 points per piece changes no digit of albedo.csv.

Number formats (as in make_reference.py): inputs (p1, p2, theta_deg) are Python floats written
with repr(); outputs have 20 significant digits (mpmath.nstr). Values below DBL_MIN would be
written as 0.0 (there are none: the smallest albedo is ~1.8e-3).

Options: --jobs N (worker processes, default 2); --only MODEL (debugging: that model's rows
only, nothing written).
"""

import decimal
import math
import multiprocessing
import os
import sys
import time
from decimal import Decimal

import mpmath
from mpmath import mp, mpf

MP_DPS = 34             # mpmath precision (factors that depend on s alone, nodes, breakpoints)
DEC_PREC = 32           # decimal precision of method A's integrand
REL_TOL = 1e-12         # required agreement of methods A and B (relative)
ANCHOR_TOL = mpf("1e-20")
TS_TOL_A = Decimal("1e-14")   # method A: stop when two successive levels agree to this
TS_TOL_B = 1e-12              # method B (floats); the error is ~ the square of the difference
TS_ABS_A = Decimal("1e-28")   # absolute floors of the same tests (the albedos here are >= 1e-3)
TS_ABS_B = 1e-18
GRID = 16               # transition scan: grid points per explicit s piece
mp.dps = MP_DPS
decimal.getcontext().prec = DEC_PREC

HERE = os.path.dirname(os.path.abspath(__file__))
DBL_MIN = mpf(sys.float_info.min)

THETAS = [0.0, 30.0, 60.0, 80.0, 89.0]
ROWS = [
    ("phong-normalized", "rv", [(1.0, 0.0), (20.0, 0.0), (1000.0, 0.0)]),
    ("log-normalized", "rv", [(1.0, 0.0), (20.0, 0.0), (1000.0, 0.0)]),
    ("log-normalized", "nh", [(20.0, 0.0), (1000.0, 0.0)]),
    ("blinn-phong-normalized", "nh", [(20.0, 0.0), (1000.0, 0.0)]),
    ("schlick", "rv", [(20.0, 0.0)]),
    ("gauss", "nh", [(100.0, 0.0)]),
    ("ward", "-", [(0.2, 1.0), (0.05, 1.0)]),
    ("ward-duer", "-", [(0.2, 1.0)]),
    ("ward-gmd", "-", [(0.2, 1.0)]),
    ("cook-torrance-1982", "-", [(0.3, 1.0)]),
    ("cook-torrance", "-", [(0.3, 1.0), (0.05, 1.0)]),
    ("ggx", "-", [(0.3, 1.0), (0.05, 1.0)]),
    ("lambert", "-", [(1.0, 0.0)]),
]
LOBE_MODELS = {"phong-normalized": "power", "log-normalized": "log",
               "blinn-phong-normalized": "power", "schlick": "schlick", "gauss": "gauss"}
BECKMANN_LIKE = ("ward", "ward-duer", "ward-gmd", "cook-torrance-1982", "cook-torrance")


def dec(x):
    """mpf (or int) -> Decimal, 36 significant digits."""
    return Decimal(mpmath.nstr(mpf(x), 36))


def to_mp(x):
    return mpf(str(x))


# ---------------------------------------------------------------------------------------------
# Models, method A: the factor that depends on s alone (mpmath) and the rest (decimal)
# ---------------------------------------------------------------------------------------------

def lobe_coef(model, n):
    """k of docs/math.md section 2 (log-normalized: coef(n) of section 4, E1 form, at 60 digits)."""
    n = mpf(n)
    pi = mpmath.pi
    if model == "phong-normalized":
        return (n + 2) / (2 * pi)
    if model == "blinn-phong-normalized":
        return (n + 2) * (n + 4) / (8 * pi * (mpf(2) ** (-n / 2) + n))
    if model == "log-normalized":
        with mp.workdps(60):
            a = 2 * mpmath.ln2 / n
            v = 1 / (pi * (1 - mpmath.exp(a) / (2 * mpmath.ln2) * (mpmath.e1(a) - mpmath.e1(4 * a))))
        return +v
    return mpf(1)  # schlick, gauss: plain lobes


def lobe_of_angle(lobe, n, s):
    """F(cos s) for the angle s in [0, pi/2] (mpmath)."""
    n = mpf(n)
    c = mpmath.cos(s)
    if c <= 0:
        return mpf(0)
    if lobe == "power":
        return c ** n
    if lobe == "schlick":
        return c / (n * (2 * mpmath.sin(s / 2) ** 2) + c)  # c / (n - n c + c), 1 - c = 2 sin^2(s/2)
    if lobe == "gauss":
        return mpmath.exp(-n * s * s / 2)
    if lobe == "log":
        t = -n * mpmath.log(c) / mpmath.ln2
        if t >= 3:
            return mpf(0)
        return 1 - mpmath.log1p(t) / (2 * mpmath.ln2)
    raise ValueError(lobe)


def s_factor(model, form, p1, p2, s):
    """Method A: the part of f that depends on s alone. Frame R (rv lobes): k F(cos s).
    Frame H: k F(cos theta_h) for nh lobes; D-like factor for the full BRDFs."""
    pi = mpmath.pi
    if model in LOBE_MODELS:
        return lobe_coef(model, p1) * lobe_of_angle(LOBE_MODELS[model], p1, s)
    a, b = mpf(p1), mpf(p2)
    if model == "lambert":
        return a / pi
    a2 = a * a
    cs = mpmath.cos(s)
    tan2 = mpmath.tan(s) ** 2
    if model in ("ward", "ward-duer"):
        return b / (4 * pi * a2) * mpmath.exp(-tan2 / a2)
    if model == "ward-gmd":
        return b / (pi * a2) * mpmath.exp(-tan2 / a2)
    if model in ("cook-torrance-1982", "cook-torrance"):
        return mpmath.exp(-tan2 / a2) / (pi * a2 * cs ** 4)  # D (cook-torrance); D / pi (1982)
    if model == "ggx":
        return a2 / (pi * (cs * cs * (a2 - 1) + 1) ** 2)
    raise ValueError(model)


def make_rest_dec(model, form, p1, p2):
    """Method A, frame H: the rest of f as a function of (NL, NV, NH, VH) in Decimal, or None."""
    if model in LOBE_MODELS or model == "lambert":
        return None
    a, b = dec(p1), dec(p2)
    a2 = a * a
    one = Decimal(1)
    if model == "ward":
        return lambda NL, NV, NH, VH: one / (NL * NV).sqrt()
    if model == "ward-duer":
        return lambda NL, NV, NH, VH: one / (NL * NV)
    if model == "ward-gmd":
        # h = L + V: |h| = 2 V.H, h.N = 2 (V.H)(N.H);  (h.h)/(h.N)^4 = 1 / (4 VH^2 NH^4)
        return lambda NL, NV, NH, VH: one / (4 * VH * VH * NH ** 4)
    if model in ("cook-torrance-1982", "cook-torrance"):
        if model == "cook-torrance-1982":
            assert p2 == 1.0  # F = 1; the dielectric Fresnel factor is not used in this table

        def rest(NL, NV, NH, VH):
            G = min(one, 2 * NH * NV / VH, 2 * NH * NL / VH)
            if model == "cook-torrance-1982":
                return G / (NL * NV)
            return (b + (one - b) * (one - VH) ** 5) * G / (4 * NL * NV)
        return rest
    if model == "ggx":
        def Lam(z):  # (-1 + sqrt(1 + a2 tan^2))/2 = a2 (1 - z^2) / (2 z (sqrt(z^2 + a2 (1 - z^2)) + z))
            s2 = one - z * z
            return a2 * s2 / (2 * z * ((z * z + a2 * s2).sqrt() + z))

        def rest(NL, NV, NH, VH):
            G = one / (one + Lam(NL) + Lam(NV))
            return (b + (one - b) * (one - VH) ** 5) * G / (4 * NL * NV)
        return rest
    raise ValueError(model)


# ---------------------------------------------------------------------------------------------
# Models, method B: f(L, V) from the vectors, in Python floats (separate implementation)
# ---------------------------------------------------------------------------------------------

def make_brdf_float(model, form, p1, p2):
    pi = math.pi
    ln2 = math.log(2.0)
    if model in LOBE_MODELS:
        n = p1
        k = float(lobe_coef(model, p1))
        lobe = LOBE_MODELS[model]

        def F(c, omc, sin2d):  # omc = 1 - c, accurate
            if c <= 0.0 or omc >= 1.0:
                return 0.0
            if lobe == "power":
                return math.exp(n * math.log1p(-omc))
            if lobe == "schlick":
                return c / (n * omc + c)
            if lobe == "log":
                t = -n * math.log1p(-omc) / ln2
                return 0.0 if t >= 3.0 else 1.0 - math.log1p(t) / (2.0 * ln2)
            d = math.atan2(math.sqrt(sin2d), c)  # gauss: angle(N, H)
            return math.exp(-n * d * d / 2.0)

        def f(L, V):
            NL, NV = L[2], V[2]
            if NL <= 0.0 or NV <= 0.0:
                return 0.0
            if form == "rv":
                R = (-L[0], -L[1], L[2])  # 2 (N.L) N - L, N = (0, 0, 1)
                c = R[0] * V[0] + R[1] * V[1] + R[2] * V[2]
                omc = ((R[0] - V[0]) ** 2 + (R[1] - V[1]) ** 2 + (R[2] - V[2]) ** 2) / 2.0
                return k * F(c, omc, 0.0)
            hx, hy, hz = L[0] + V[0], L[1] + V[1], L[2] + V[2]
            perp = hx * hx + hy * hy
            hh = perp + hz * hz
            NH = hz / math.sqrt(hh)
            sin2d = perp / hh
            return k * F(NH, sin2d / (1.0 + NH), sin2d)
        return f
    a, b = p1, p2
    a2 = a * a

    def f(L, V):
        NL, NV = L[2], V[2]
        if NL <= 0.0 or NV <= 0.0:
            return 0.0
        if model == "lambert":
            return a / pi
        hx, hy, hz = L[0] + V[0], L[1] + V[1], L[2] + V[2]
        perp = hx * hx + hy * hy
        hh = perp + hz * hz
        rh = math.sqrt(hh)
        NH = hz / rh
        tan2 = perp / (hz * hz)
        VH = (V[0] * hx + V[1] * hy + V[2] * hz) / rh
        if model == "ward":
            return b / (4 * pi * a2 * math.sqrt(NL * NV)) * math.exp(-tan2 / a2)
        if model == "ward-duer":
            return b / (4 * pi * a2 * NL * NV) * math.exp(-tan2 / a2)
        if model == "ward-gmd":
            return b * hh / (pi * a2 * hz ** 4) * math.exp(-tan2 / a2)
        F = b + (1.0 - b) * (1.0 - VH) ** 5
        if model in ("cook-torrance-1982", "cook-torrance"):
            G = min(1.0, 2 * NH * NV / VH, 2 * NH * NL / VH)
            if model == "cook-torrance-1982":
                D = math.exp(-tan2 / a2) / (a2 * NH ** 4)
                return D * 1.0 * G / (pi * NL * NV)  # F = 1 (f0 = 1 only)
            D = math.exp(-tan2 / a2) / (pi * a2 * NH ** 4)
            return D * F * G / (4 * NL * NV)
        if model == "ggx":
            # (N.H)^2 (a2 - 1) + 1 = a2 (N.H)^2 + sin^2(delta), without the cancellation near N.H = 1
            D = a2 / (pi * (a2 * NH * NH + perp / hh) ** 2)

            def Lam(z):
                q = a2 * (1.0 - z * z) / (z * z)  # alpha^2 tan^2
                return q / (2.0 * (1.0 + math.sqrt(1.0 + q)))  # (-1 + sqrt(1 + q)) / 2
            G = 1.0 / (1.0 + Lam(NL) + Lam(NV))
            return D * F * G / (4 * NL * NV)
        raise ValueError(model)
    return f


# ---------------------------------------------------------------------------------------------
# Lobe width breakpoints
# ---------------------------------------------------------------------------------------------

def lobe_angles(model, form, p1, fine):
    """Angles beta (from the lobe's centre: R for rv lobes, N otherwise) of the lobe's level
    curves, and the support end (log lobe: acos c0) or None. fine=False: the s breakpoints;
    fine=True: the denser level curves that split method B's phi integral."""
    half_pi = mpmath.pi / 2
    if model == "lambert":
        return [], None
    if model in LOBE_MODELS:
        n = mpf(p1)
        lobe = LOBE_MODELS[model]
        if lobe == "log":
            ts = [mpf(1) / 4, mpf(1), mpf(2)] if not fine else \
                [mpf(1) / 4, mpf(1) / 2, mpf(1), mpf(3) / 2, mpf(2), mpf(5) / 2]
            return [mpmath.acos(mpf(2) ** (-t / n)) for t in ts], mpmath.acos(mpf(2) ** (-3 / n))
        if not fine:
            ts = [mpf(4) ** j / 4 for j in range(16)]  # 1/4, 1, 4, 16, 64, ...
        else:
            ts = [mpf(1) / 4, mpf(1) / 2, 1, 2, 4, 8, 12, 16, 24, 32, 48, 64, 96, 128]
            ts = [mpf(t) for t in ts] + [mpf(2) ** j for j in range(8, 30)]
        out = []
        for t in ts:
            c = mpf(2) ** (-t / n)
            if lobe == "schlick":
                if c < mpf("1e-6"):
                    break
            elif t > 160:  # F ~ 2^-t < 1e-48: no further splits needed
                break
            out.append(mpmath.acos(c))
        return out, None
    w = mpf(p1)
    if model in BECKMANN_LIKE:  # exp(-tan^2 / w^2): E = tan^2 / w^2
        Es = [mpf(1) / 4, 1, 4, 16, 64] if not fine else \
            [mpf(1) / 16, mpf(1) / 4, 1, 2, 4, 8, 12, 16, 24, 32, 48, 64]
        return [mpmath.atan(w * mpmath.sqrt(E)) for E in Es], None
    out = []  # ggx: algebraic tail, geometric all the way
    step = mpf(2) if not fine else mpmath.sqrt(2)
    q = w / 2
    while True:
        beta = mpmath.atan(q)
        if beta > half_pi - mpf("1e-6"):
            break
        out.append(beta)
        q *= step
    return out, None


# ---------------------------------------------------------------------------------------------
# Frames. At fixed s, the kink conditions are polynomials in X = cos(phi).
#   Frame R: V = cos s R + sin s (X e1 + sin(phi) e2), R = (-sin ti, 0, cos ti),
#            e1 = (cos ti, 0, sin ti), e2 = (0, 1, 0); N.V = cos s cos ti + sin s sin ti X,
#            L.V = cos s cos 2ti + sin s sin 2ti X; dw = sin s ds dphi.
#   Frame H: H = (sin s X, sin s sin(phi), cos s), L.H = cos ti cos s + sin ti sin s X,
#            V = 2 (L.H) H - L, N.V = 2 cos s (L.H) - cos ti; dw = 4 (L.H) sin s ds dphi.
# ---------------------------------------------------------------------------------------------

class Incidence:
    """sin, cos of theta_i and 2 theta_i in one number type (conv: mpf -> that type)."""

    def __init__(self, theta_deg, conv):
        ti = mpf(theta_deg) * mpmath.pi / 180
        sti = mpmath.sin(ti) if theta_deg != 0 else mpf(0)
        cti = mpmath.cos(ti)
        self.cti, self.sti = conv(cti), conv(sti)
        self.c2ti, self.s2ti = conv(cti * cti - sti * sti), conv(2 * sti * cti)


def _roots(label, c0, c1, c2, sqrt, eps):
    """Real roots of c0 + c1 X + c2 X^2 with |X| < 1, labelled."""
    scale = abs(c0) + abs(c1) + abs(c2)
    if scale == 0:
        return []
    if abs(c2) <= eps * scale:
        if abs(c1) <= eps * scale:
            return []
        out = [(-c0 / c1, label)]
    else:
        disc = c1 * c1 - 4 * c0 * c2
        if disc < 0:
            return []
        sq = sqrt(disc)
        q = -(c1 + (sq if c1 >= 0 else -sq)) / 2
        if q == 0:
            r = [q / c2, q / c2]
        else:
            r = sorted([q / c2, c0 / q])
        out = [(r[0], label + "-"), (r[1], label + "+")]
    return [(x, l) for x, l in out if -1 < x < 1]


def circle_polys(frame, inc, cs, ss, ct, levels):
    """Kink conditions on the circle s (cos s = cs, sin s = ss) as polynomials in X = cos phi:
    [(label, c0, c1, c2)], the horizon first. ct: Cook-Torrance masking switches; levels:
    [(label, c)] level curves (frame R: N.H = c, frame H: R.V = c)."""
    NL = inc.cti
    if frame == "R":
        nv0, nv1 = cs * inc.cti, ss * inc.sti
        lv0, lv1 = cs * inc.c2ti, ss * inc.s2ti
        S0 = NL + nv0
        polys = [("hor", nv0, nv1, 0)]
        if ct:  # 2 NH NV = VH <=> 4 (NL + NV) NV = |L + V|^2 = 2 + 2 LV;  2 NH NL = VH;  NV = NL
            polys += [("gV", 4 * S0 * nv0 - 2 - 2 * lv0, 4 * S0 * nv1 + 4 * nv1 * nv0 - 2 * lv1,
                       4 * nv1 * nv1),
                      ("gL", 4 * NL * S0 - 2 - 2 * lv0, 4 * NL * nv1 - 2 * lv1, 0),
                      ("eq", nv0 - NL, nv1, 0)]
        for lab, c in levels:  # N.H = c <=> (NL + NV)^2 = c^2 (2 + 2 LV)
            c2 = c * c
            polys.append((lab, S0 * S0 - c2 * (2 + 2 * lv0), 2 * S0 * nv1 - 2 * c2 * lv1, nv1 * nv1))
    else:
        a, b = inc.cti * cs, inc.sti * ss  # L.H = a + b X
        nv0, nv1 = 2 * cs * a - NL, 2 * cs * b
        polys = [("hor", nv0, nv1, 0)]
        if ct:  # 2 cs NV = LH;  2 cs NL = LH;  NV = NL
            polys += [("gV", 2 * cs * nv0 - a, 2 * cs * nv1 - b, 0),
                      ("gL", 2 * cs * NL - a, -b, 0),
                      ("eq", nv0 - NL, nv1, 0)]
        for lab, c in levels:  # R.V = 2 NL NV - (2 LH^2 - 1) = c; the X term cancels (a = NL cs)
            polys.append((lab, 2 * NL * nv0 - 2 * a * a + 1 - c, 0, -2 * b * b))
    return polys


def circle_kinks(frame, inc, cs, ss, ct, levels, sqrt, eps):
    """phi-kinks on the circle s: sorted [(X, label)], real roots in (-1, 1) above the horizon."""
    polys = circle_polys(frame, inc, cs, ss, ct, levels)
    r = []
    for lab, c0, c1, c2 in polys:
        r += _roots(lab, c0, c1, c2, sqrt, eps)
    # Roots below the horizon are dropped: the integrand is 0 there, and the level curves of
    # frame R all meet at V = -L (H undefined), where they would only add noisy splits.
    _, nv0, nv1, _ = polys[0]
    r = [(x, l) for x, l in r if l == "hor" or nv0 + nv1 * x > 0]
    r.sort(key=lambda t: t[0])
    return r


class Setup:
    """Everything about one row in one frame that does not depend on s."""

    def __init__(self, model, form, p1, p2, theta_deg, frame):
        self.model, self.form, self.p1, self.p2, self.theta = model, form, p1, p2, theta_deg
        self.frame = frame
        self.ct = model in ("cook-torrance-1982", "cook-torrance")
        self.rv = form == "rv"
        ti = mpf(theta_deg) * mpmath.pi / 180
        half_pi = mpmath.pi / 2
        cti = mpmath.cos(ti)
        self.lobe_in_s = (frame == "R") == self.rv  # method A's frame
        soft, hard = lobe_angles(model, form, p1, False)
        fine, _ = lobe_angles(model, form, p1, True)
        # Kink levels in this frame (only where the lobe is not a function of s): hard ones are
        # real kinks (support end; c = 0 for rv lobes), soft ones only split the phi integral.
        self.hard_levels, self.soft_levels = [], []
        if not self.lobe_in_s:
            if hard is not None:
                self.hard_levels.append(("end", mpmath.cos(hard)))
            if self.rv:
                self.hard_levels.append(("zero", mpf(0)))
            self.soft_levels = [("lvl%d" % i, mpmath.cos(b)) for i, b in enumerate(fine)]
        # Domain of s.
        if frame == "R":
            s_end = half_pi if self.rv else half_pi + ti  # rv: c = cos s > 0; else N.V > 0
            if self.rv and hard is not None:
                s_end = min(s_end, hard)
        else:
            s_end = mpmath.pi / 4 + ti / 2  # N.V > 0 somewhere on the circle
            if not self.rv and hard is not None:
                s_end = min(s_end, hard)
        self.s_end = s_end
        # Explicit s breakpoints.
        pts = []
        ends = soft + ([hard] if hard is not None else [])
        if self.lobe_in_s:
            pts += ends
        elif frame == "H":  # rv lobe seen from the half vector: in-plane / perpendicular extent
            for b in ends:
                pts.append(b / 2)
                x = mpmath.sin(b / 2) / cti
                if x < 1:
                    pts.append(mpmath.asin(x))
        else:  # nh lobe or microfacet distribution seen from R
            for b in ends:
                pts.append(2 * b)
                pts.append(2 * mpmath.asin(cti * mpmath.sin(b)))
        pts.append(half_pi - ti if frame == "R" else mpmath.pi / 4 - ti / 2)  # horizon cut starts
        tiny = mpf(10) ** -25
        self.explicit = sorted(set(p for p in pts if tiny * s_end < p < s_end * (1 - tiny)))


# ---------------------------------------------------------------------------------------------
# Transitions: s where the ordered set of (hard) phi-kinks changes
# ---------------------------------------------------------------------------------------------

def signature(S, inc_d, levels_d, s):
    """The labels of the kinks in phi order, and the sign of every kink polynomial at X = 1
    (phi = 0). The signs catch circles on which a condition holds for every phi: at
    theta_i = 0 the polynomials do not depend on X and their kinks are kinks in s alone
    (e.g. Cook-Torrance's 2 (N.H)(N.V)/(V.H) = 1 at theta_h = 30 deg)."""
    sm = to_mp(s)
    cs, ss = dec(mpmath.cos(sm)), dec(mpmath.sin(sm))
    r = circle_kinks(S.frame, inc_d, cs, ss, S.ct, levels_d, Decimal.sqrt, Decimal("1e-28"))
    polys = circle_polys(S.frame, inc_d, cs, ss, S.ct, levels_d)
    signs = tuple((c0 + c1 + c2) > 0 for _, c0, c1, c2 in polys)
    return tuple(l for _, l in r), signs


def outer_points(S):
    """Sorted s breakpoints (Decimal): 0, explicit points, transitions, s_end."""
    inc_d = Incidence(S.theta, dec)
    levels_d = [(l, dec(c)) for l, c in S.hard_levels]
    end = dec(S.s_end)
    grid = [Decimal(0)] + [dec(p) for p in S.explicit] + [end]
    grid = sorted(set(grid + [end * j / 16 for j in range(1, 16)]))
    fine = []
    for a, b in zip(grid[:-1], grid[1:]):
        for j in range(GRID):
            fine.append(a + (b - a) * j / GRID)
    fine.append(end)
    eps = Decimal("1e-26")
    fine[0] = end * eps  # avoid the degenerate circle s = 0 itself
    fine[-1] = end * (1 - eps)
    sigs = [signature(S, inc_d, levels_d, s) for s in fine]
    found = []
    tol = Decimal("1e-28")

    def bisect(a, b, sa, sb, depth):
        if sa == sb:
            return
        if b - a < tol or depth > 200:
            found.append((a + b) / 2)
            return
        m = (a + b) / 2
        sm = signature(S, inc_d, levels_d, m)
        bisect(a, m, sa, sm, depth + 1)
        bisect(m, b, sm, sb, depth + 1)

    for i in range(len(fine) - 1):
        bisect(fine[i], fine[i + 1], sigs[i], sigs[i + 1], 0)
    if len(found) > 200:
        raise RuntimeError("too many transitions (%d) for %r" % (len(found), S.__dict__))
    pts = sorted(set([dec(p) for p in S.explicit] + found))
    out = [Decimal(0)]
    gap = Decimal("1e-24")
    for p in pts:
        if p - out[-1] > gap and end - p > gap:
            out.append(p)
    out.append(end)
    return out, len(found)


# ---------------------------------------------------------------------------------------------
# Tanh-sinh quadrature, nested levels h = 1, 1/2, 1/4, ... (nodes computed with mpmath)
# ---------------------------------------------------------------------------------------------

class TanhSinh:
    """Nodes as (d, w): on [a, b] the abscissas are a + (b - a) d and b - (b - a) d (d = distance
    fraction from the nearer end, computed without cancellation), weight (b - a) h w."""

    def __init__(self, conv, tmax, maxlevel):
        self.levels = []
        pi = mpmath.pi
        for k in range(maxlevel + 1):
            h = mpf(2) ** -k
            if k == 0:
                ts = [mpf(j) for j in range(0, int(tmax) + 1)]
            else:
                ts = [h * j for j in range(1, int(tmax / h) + 1, 2)]
            nodes = []
            for t in ts:
                u = pi / 2 * mpmath.sinh(t)
                d = 1 / (1 + mpmath.exp(2 * u))
                w = pi / 4 * mpmath.cosh(t) / mpmath.cosh(u) ** 2
                nodes.append((conv(d), conv(w), t == 0))
            self.levels.append((conv(h), nodes))

    def integrate(self, f, a, b, rel, absfloor, minlevel=2):
        """f(x, da, db): x and its distances to a and b. Stops when two successive levels agree
        to rel (relative) or absfloor (absolute; for pieces that contribute nothing, e.g. slivers
        at the horizon where double rounding noise would never let them converge)."""
        L = b - a
        S = 0
        prev = None
        I = 0
        for k, (h, nodes) in enumerate(self.levels):
            for d, w, centre in nodes:
                if centre:
                    S += w * f(a + L / 2, L / 2, L / 2)
                else:
                    dl = L * d
                    S += w * (f(a + dl, dl, L - dl) + f(b - dl, L - dl, dl))
            I = S * L * h
            if k >= minlevel and abs(I - prev) <= rel * abs(I) + absfloor:
                return I
            prev = I
        return I


_TS = {}


def ts_rule(kind):
    if kind not in _TS:
        if kind == "dec":
            _TS[kind] = TanhSinh(dec, 4.5, 8)  # d down to 1e-61: 1/sqrt end singularities fine
        else:
            _TS[kind] = TanhSinh(lambda x: float(x), 3.5, 9)
    return _TS[kind]


# ---------------------------------------------------------------------------------------------
# Method A (decimal integrand, X = cos phi) and method B (floats, phi)
# ---------------------------------------------------------------------------------------------

def albedo_A(S):
    assert S.lobe_in_s
    pts, ntrans = outer_points(S)
    inc = Incidence(S.theta, dec)
    rest = make_rest_dec(S.model, S.form, S.p1, S.p2)
    ts = ts_rule("dec")
    one, zero = Decimal(1), Decimal(0)
    NL = inc.cti
    sqrt = Decimal.sqrt

    def I(s, da, db):
        sm = to_mp(s)
        cs_m, ss_m = mpmath.cos(sm), mpmath.sin(sm)
        cs, ss = dec(cs_m), dec(ss_m)
        W = dec(s_factor(S.model, S.form, S.p1, S.p2, sm)) * ss  # frame-R Jacobian sin s
        if W == 0:
            return zero
        r = circle_kinks(S.frame, inc, cs, ss, S.ct, [], sqrt, Decimal("1e-28"))
        if S.frame == "R":
            nv0, nv1 = cs * inc.cti, ss * inc.sti

            def g(X, dA, dB):
                NV = nv0 + nv1 * X
                if NV <= 0:
                    return zero
                return NV / sqrt(om(X, dB) * op(X, dA))
        else:
            W *= 4
            a, b = inc.cti * cs, inc.sti * ss

            def g(X, dA, dB):
                LH = a + b * X
                NV = 2 * cs * LH - NL
                if NV <= 0:
                    return zero
                v = LH * NV / sqrt(om(X, dB) * op(X, dA))
                if rest is not None:
                    v *= rest(NL, NV, cs, LH)
                return v
        ends = [-one] + [x for x, _ in r] + [one]
        tot = zero
        for xa, xb in zip(ends[:-1], ends[1:]):
            if not xb > xa:
                continue
            # 1 - X and 1 + X from the distance to the end at +-1 (no cancellation there).
            om = (lambda X, dB: dB) if xb == one else (lambda X, dB: one - X)
            op = (lambda X, dA: dA) if xa == -one else (lambda X, dA: one + X)
            mid = (xa + xb) / 2
            if g(mid, mid - xa, xb - mid) == 0:  # outside the support: exactly 0 on the piece
                continue
            tot += ts.integrate(g, xa, xb, TS_TOL_A, TS_ABS_A)
        return 2 * W * tot

    total = zero
    for a, b in zip(pts[:-1], pts[1:]):
        total += ts.integrate(I, a, b, TS_TOL_A, TS_ABS_A)
    return to_mp(total), len(pts) - 1, ntrans


def albedo_B(S):
    assert not S.lobe_in_s
    pts_d, ntrans = outer_points(S)
    pts = []
    for p in pts_d:
        x = float(p)
        if not pts or x > pts[-1]:
            pts.append(x)
    inc = Incidence(S.theta, float)
    f = make_brdf_float(S.model, S.form, S.p1, S.p2)
    levels = [(l, float(c)) for l, c in S.hard_levels + S.soft_levels]
    ts = ts_rule("float")
    sti, cti = inc.sti, inc.cti
    L = (sti, 0.0, cti)
    R = (-sti, 0.0, cti)
    e1 = (cti, 0.0, sti)

    def I(s, da, db):
        cs, ss = math.cos(s), math.sin(s)
        r = circle_kinks(S.frame, inc, cs, ss, S.ct, levels, math.sqrt, 1e-14)
        if S.frame == "R":
            def g(phi, dA, dB):
                cp, sp = math.cos(phi), math.sin(phi)
                V = (cs * R[0] + ss * cp * e1[0], ss * sp, cs * R[2] + ss * cp * e1[2])
                if V[2] <= 0.0:
                    return 0.0
                return f(L, V) * V[2] * ss
        else:
            def g(phi, dA, dB):
                cp, sp = math.cos(phi), math.sin(phi)
                H = (ss * cp, ss * sp, cs)
                LH = L[0] * H[0] + L[2] * H[2]
                V = (2 * LH * H[0] - L[0], 2 * LH * H[1], 2 * LH * H[2] - L[2])
                if V[2] <= 0.0 or LH <= 0.0:
                    return 0.0
                return f(L, V) * V[2] * 4 * LH * ss
        phis = [0.0] + sorted(math.acos(x) for x, _ in r) + [math.pi]
        tot = 0.0
        for a, b in zip(phis[:-1], phis[1:]):
            if not b > a:
                continue
            m = (a + b) / 2
            if g(m, m - a, b - m) == 0.0:
                continue
            tot += ts.integrate(g, a, b, TS_TOL_B, TS_ABS_B)
        return 2 * tot

    total = math.fsum(ts.integrate(I, a, b, TS_TOL_B, TS_ABS_B) for a, b in zip(pts[:-1], pts[1:]))
    return mpf(total), len(pts) - 1, ntrans


# ---------------------------------------------------------------------------------------------
# Anchors: closed forms and one-dimensional reductions (independent of both methods)
# ---------------------------------------------------------------------------------------------

def normal_incidence_1d(model, p1, p2):
    """Albedo at theta_i = 0 reduced by hand to one integral over u = tan^2(theta_h) in [0, 1]:
    with L = N, N.V = cos 2 theta_h = (1 - u)/(1 + u), V.H = N.H = (1 + u)^(-1/2), and
    dw_V = 4 (V.H) sin theta_h dtheta_h dphi_h = 4 pi du / (1 + u)^2 after the phi_h integral
    (sin theta_h dtheta_h = cos^3 theta_h du / 2). N.V > 0 is u < 1. E.g. Cook-Torrance:
    f N.V = D G / 4 with D = e^(-u/m^2) (1 + u)^2 / (pi m^2) gives (1/m^2) int_0^1 e^(-u/m^2) G du.
    None where no such form is set up."""
    a, b = mpf(p1), mpf(p2)
    a2 = a * a
    E = lambda u: mpmath.exp(-u / a2)
    if model == "ward-gmd":  # rho_s / a2 * int_0^1 (1 - u) e^{-u/a2} du, elementary:
        return b * (1 - a2 + a2 * mpmath.exp(-1 / a2))
    if model == "ward":
        return b / a2 * mpmath.quad(lambda u: mpmath.sqrt((1 - u) / (1 + u)) * E(u) / (1 + u) ** 2,
                                    [0, a2, 1])
    if model == "ward-duer":
        return b / a2 * mpmath.quad(lambda u: E(u) / (1 + u) ** 2, [0, a2, 1])
    if model in ("cook-torrance", "cook-torrance-1982"):
        # G = min(1, 2 N.V) = min(1, 2 (1 - u)/(1 + u)): the switch is at u = 1/3 (30 deg).
        third = mpf(1) / 3
        v = -mpmath.expm1(-third / a2) + mpmath.quad(lambda u: 2 * (1 - u) / (1 + u) * E(u),
                                                     [third, 1]) / a2
        return v * b * (4 if model == "cook-torrance-1982" else 1)  # f0 = 1: F = 1
    if model == "ggx":
        def G(u):  # 1 / (1 + Lambda(V)), tan^2(2 theta_h) = 4u / (1 - u)^2
            if u >= 1:
                return mpf(0)
            q = a2 * 4 * u / (1 - u) ** 2
            return 1 / (1 + q / (2 * (1 + mpmath.sqrt(1 + q))))
        return b * mpmath.quad(lambda u: a2 * G(u) / (a2 + u) ** 2, [0, a2, 1])
    return None


def anchor(row):
    """Known value of a row (to ANCHOR_TOL), or None."""
    model, form, p1, p2, th = row
    ti = mpf(th) * mpmath.pi / 180
    if model == "lambert":
        return mpf(p1)
    if th == 0 and (model, form) in (("phong-normalized", "rv"), ("blinn-phong-normalized", "nh"),
                                     ("log-normalized", "rv")):
        return mpf(1)  # the normalization condition
    if (model, form) == ("log-normalized", "rv") and \
            mpmath.acos(mpf(2) ** (-3 / mpf(p1))) <= mpmath.pi / 2 - ti:
        return mpmath.cos(ti)  # support above the horizon: the phi integral of N.V leaves cos ti
    if (model, form, p1, th) == ("blinn-phong-normalized", "nh", 1000.0, 30.0):
        # Lobe not clipped (cos(30 deg)^1000 ~ 1e-63): the phi_h average of N.V (L.H) is
        # cos^2 ti c (2c^2 - 1) + sin^2 ti c (1 - c^2) (c = N.H), so the albedo is cos^2 ti
        # (the normalization integral) + sin^2 ti * k 2 pi int F(c) 4 c (1 - c^2) dc
        # = cos^2 ti + sin^2 ti * 2 / (n + 2^(-n/2)).
        n = mpf(p1)
        return mpmath.cos(ti) ** 2 + mpmath.sin(ti) ** 2 * 2 / (n + mpf(2) ** (-n / 2))
    if th == 0:
        return normal_incidence_1d(model, p1, p2)
    return None


def check_brdf_float():
    """Method B's BRDF code against make_reference.py's (mpmath, 50 digits) at a few (L, V)."""
    sys.dont_write_bytecode = True  # no __pycache__ next to the tables
    sys.path.insert(0, HERE)
    import make_reference as ref  # sets mp.dps = 50 on import
    mp.dps = MP_DPS
    worst = 0.0
    dirs = []
    for tl in (0.0, 30.0, 80.0):
        L = (math.sin(math.radians(tl)), 0.0, math.cos(math.radians(tl)))
        for tv, pv in ((10.0, 0.0), (45.0, 120.0), (85.0, 180.0), (30.0, 180.0)):
            b, p = math.radians(tv), math.radians(pv)
            dirs.append((L, (math.sin(b) * math.cos(p), math.sin(b) * math.sin(p), math.cos(b))))
    for model, form, params in ROWS:
        for p1, p2 in params:
            f = make_brdf_float(model, form, p1, p2)
            for L, V in dirs:
                with mp.workdps(50):
                    if model in LOBE_MODELS:
                        Lm, Vm = [mpf(x) for x in L], [mpf(x) for x in V]
                        if form == "rv":
                            c = -Lm[0] * Vm[0] - Lm[1] * Vm[1] + Lm[2] * Vm[2]
                        else:
                            h = [Lm[i] + Vm[i] for i in range(3)]
                            c = h[2] / mpmath.sqrt(sum(x * x for x in h))
                        c = float(c)  # lobe_c takes a double; the rounding of c is ~1e-16
                        want = lobe_coef(model, p1) * ref.lobe_c(LOBE_MODELS[model], p1, 0.0, c)
                    else:
                        want = ref.brdf(model, p1, p2, L, V)
                got = f(L, V)
                # 1000 * 1e-16: a 1-ulp change of c moves c^1000 by ~1e-13 relative; near c = 0
                # (R.V ~ 1e-17 at one of the directions) only an absolute comparison makes sense.
                err = float(abs(got - want))
                if abs(want) > 1e-12:
                    worst = max(worst, err / float(abs(want)))
                if not err <= 1e-11 * float(abs(want)) + 1e-15:
                    raise AssertionError("float BRDF %s %s %r %r: %r vs %s"
                                         % (model, form, (p1, p2), (L, V), got, mpmath.nstr(want, 17)))
    return worst


# ---------------------------------------------------------------------------------------------
# Driver
# ---------------------------------------------------------------------------------------------

def primary_frame(form):
    return "R" if form == "rv" else "H"


def task(args):
    model, form, p1, p2, theta, method = args
    mp.dps = MP_DPS
    decimal.getcontext().prec = DEC_PREC
    t0 = time.time()
    pf = primary_frame(form)
    if method == "A":
        v, npieces, ntrans = albedo_A(Setup(model, form, p1, p2, theta, pf))
    else:
        v, npieces, ntrans = albedo_B(Setup(model, form, p1, p2, theta, "H" if pf == "R" else "R"))
    return args, v, npieces, ntrans, time.time() - t0


def all_rows():
    out = []
    for model, form, params in ROWS:
        for p1, p2 in params:
            for th in THETAS:
                out.append((model, form, p1, p2, th))
    return out


def fout(x):
    x = mpf(x)
    if x == 0 or abs(x) < DBL_MIN:
        return "0.0"
    s = mpmath.nstr(x, 20)
    assert "mpf" not in s and "inf" not in s and "nan" not in s, s
    return s


def expected_cost(t):
    model, form, p1, p2, theta, method = t
    c = 1.0 if theta == 0 else 3.0 + theta / 30
    if model in LOBE_MODELS or model == "lambert":
        return c
    return 4 * c * (2 if model in ("ggx", "cook-torrance", "cook-torrance-1982") else 1)


def main():
    jobs = 2
    if "--jobs" in sys.argv:
        jobs = int(sys.argv[sys.argv.index("--jobs") + 1])
    only = None
    if "--only" in sys.argv:  # debugging: --only MODEL (no file written)
        only = sys.argv[sys.argv.index("--only") + 1]
    t0 = time.time()

    def log(msg):
        print("[%6.1fs] %s" % (time.time() - t0, msg), flush=True)

    log("method B's float BRDFs vs make_reference.py: worst relative difference %.2g"
        % check_brdf_float())
    rows = all_rows()
    if only:
        rows = [r for r in rows if r[0] == only]
    tasks = sorted([r + (m,) for r in rows for m in "AB"], key=expected_cost, reverse=True)
    results = {}

    def record(res):
        args, v, npieces, ntrans, dt = res
        results[args] = v
        log("%-22s %-2s %6r %4r %4r %s: %-24s (%2d s-pieces, %2d transitions, %5.1fs)"
            % (args + (mpmath.nstr(v, 20), npieces, ntrans, dt)))

    if jobs > 1:
        with multiprocessing.Pool(jobs) as pool:
            for res in pool.imap_unordered(task, tasks):
                record(res)
    else:
        for t in tasks:
            record(task(t))

    worst, worst_row = mpf(0), None
    nanchors, worst_anchor = 0, mpf(0)
    lines = ["model,form,p1,p2,theta_deg,albedo"]
    for r in rows:
        a, b = results[r + ("A",)], results[r + ("B",)]
        rel = abs(a - b) / abs(a)
        if rel > worst:
            worst, worst_row = rel, r
        if not rel < REL_TOL:
            raise AssertionError("methods disagree %r: A %s B %s rel %s"
                                 % (r, mpmath.nstr(a, 20), mpmath.nstr(b, 20), mpmath.nstr(rel, 3)))
        model, form, p1, p2, th = r
        want = anchor(r)
        if want is not None:
            nanchors += 1
            arel = abs(a - want) / abs(want)
            worst_anchor = max(worst_anchor, arel)
            if not arel < ANCHOR_TOL:
                raise AssertionError("anchor %r: %s, expected %s"
                                     % (r, mpmath.nstr(a, 25), mpmath.nstr(want, 25)))
        assert a > 0, (r, a)
        lines.append(",".join([model, form, repr(p1), repr(p2), repr(th), fout(a)]))
    log("methods A and B: worst relative difference %s (%r)" % (mpmath.nstr(worst, 3), worst_row))
    log("anchors (closed forms, 1-D reductions at theta_i = 0): %d rows, worst relative difference %s"
        % (nanchors, mpmath.nstr(worst_anchor, 3)))
    if only:
        return
    path = os.path.join(HERE, "albedo.csv")
    with open(path, "w", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")
    log("wrote %s: %d rows" % (os.path.relpath(path), len(lines) - 1))


if __name__ == "__main__":
    main()
