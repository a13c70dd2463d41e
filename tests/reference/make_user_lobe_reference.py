#!/usr/bin/env python3
"""Independent references for lobes specula has never seen (user-defined models, docs/models.md).

Regenerate (from the repository root; writes user_lobes.csv next to this script, ~1 min):

    python3 tests/reference/make_user_lobe_reference.py

Requires python3 and mpmath; deterministic. The lobes, as a user writes them:

  quartic   F = max(0, 1 - n (1 - c)/4)^4        (support 1 - c <= 4/n; a kink there)
  cauchy    F = 1/(1 + n u)^2, u = -ln c        (in u: exact for n up to 1e9)
  clipped   F = min(1, 2 c^n)                    (a kink at c = 2^(-1/n))

user_lobes.csv  lobe,n,coef_rv,coef_nh,max_abs_vs_power
  coef = 1/(2 pi I) with rv: I = int_0^1 F c dc and nh: I = int_{1/sqrt2}^1 F (2c^2-1) 4c dc
  (docs/math.md section 1), integrated in u = -ln c split at the lobe's kinks and at
  0, w, 4w, 16w, ... (w its half-maximum width); the quartic's coefficients are also checked
  against its closed form (assert, 1e-30). max_abs_vs_power = max over u in [0, 40] of
  |F(u) - e^(-n u)|, the quantity `specula error --model LOBE --reference phong` reports, from a
  dense grid refined by golden-section search at 50 digits.
"""

import os

import mpmath
from mpmath import mp, mpf

mp.dps = 50
HERE = os.path.dirname(os.path.abspath(__file__))
U_END = mpf(40)


def quartic(n):
    def f(u):
        x = -mpmath.expm1(-u)  # 1 - c
        return max(mpf(0), 1 - n * x / 4) ** 4
    support = -mpmath.log1p(-mpf(4) / n) if n > 4 else mpmath.inf
    half = -mpmath.log1p(-4 * (1 - mpf(2) ** mpf(-0.25)) / n) if n > 4 * (1 - mpf(2) ** mpf(-0.25)) else mpf(1)
    return f, [support] if support != mpmath.inf else [], half


def cauchy(n):
    return (lambda u: 1 / (1 + n * u) ** 2), [], (mpmath.sqrt(2) - 1) / n


def clipped(n):
    kink = mpmath.log(2) / n
    return (lambda u: min(mpf(1), 2 * mpmath.exp(-n * u))), [kink], kink + mpmath.log(2) / n


LOBES = {
    "quartic": (quartic, [1.0, 4.0, 10.0, 100.0, 1e4]),
    "cauchy": (cauchy, [0.1, 1.0, 100.0, 1e6, 1e9]),
    "clipped": (clipped, [1.0, 20.0, 1000.0]),
}


def pieces(end, width, kinks):
    cuts = {mpf(0), end}
    s = width
    while s < end:
        cuts.add(s)
        s *= 4
    cuts.update(k for k in kinks if 0 < k < end)
    return sorted(cuts)


def coef(f, kinks, width, form):
    if form == "rv":
        end, weight = U_END, lambda u: mpmath.exp(-2 * u)
    else:
        end = mpmath.log(2) / 2
        weight = lambda u: (2 * mpmath.exp(-2 * u) - 1) * 4 * mpmath.exp(-2 * u)
    integral = mpmath.quad(lambda u: f(u) * weight(u), pieces(end, width, kinks))
    return 1 / (2 * mpmath.pi * integral)


def quartic_closed_form_rv(n):
    a = mpf(n) / 4
    if a >= 1:  # support inside [0, 1]: I = 1/(5a) - 1/(30 a^2)
        return 1 / (2 * mpmath.pi * (1 / (5 * a) - 1 / (30 * a * a)))
    return None


def max_abs_vs_power(f, n, width, kinks):
    g = lambda u: abs(f(u) - mpmath.exp(-n * u))
    grid = [width * mpf(k) / 64 for k in range(0, 64 * 16)]
    grid += [width * 16 * (U_END / (width * 16)) ** (mpf(k) / 400) for k in range(401)] if width * 16 < U_END else []
    grid = sorted(set(u for u in grid + list(kinks) if u <= U_END))
    values = [g(u) for u in grid]
    best = max(range(len(grid)), key=lambda i: values[i])
    lo, hi = grid[max(best - 1, 0)], grid[min(best + 1, len(grid) - 1)]
    phi = (mpmath.sqrt(5) - 1) / 2
    a, b = lo, hi
    for _ in range(200):
        x1, x2 = b - phi * (b - a), a + phi * (b - a)
        if g(x1) > g(x2):
            b = x2
        else:
            a = x1
    return max(values[best], g((a + b) / 2), *(g(k) for k in kinks if k <= U_END))


def main():
    rows = ["lobe,n,coef_rv,coef_nh,max_abs_vs_power"]
    for name, (make, ns) in LOBES.items():
        for n in ns:
            f, kinks, width = make(mpf(n))
            rv, nh = coef(f, kinks, width, "rv"), coef(f, kinks, width, "nh")
            if name == "quartic" and quartic_closed_form_rv(n) is not None:
                exact = quartic_closed_form_rv(n)
                assert abs(rv / exact - 1) < mpf(10) ** -30, (n, rv, exact)
            err = max_abs_vs_power(f, mpf(n), width, kinks)
            rows.append(",".join([name, repr(n)] + [mpmath.nstr(v, 20) for v in (rv, nh, err)]))
            print(rows[-1], flush=True)
    with open(os.path.join(HERE, "user_lobes.csv"), "w") as out:
        out.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
