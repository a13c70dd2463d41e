#!/usr/bin/python3
"""Independent high-precision Fresnel values and averages for specula's C++ tests.

Regenerate (from the repository root; writes fresnel.csv next to this script, a few seconds):

    /usr/bin/python3 tests/reference/make_fresnel_reference.py

Requires python3 (>= 3.9) and mpmath. Deterministic. Definitions (docs/fresnel.md):

  dielectric  F(c; eta): the unpolarized Fresnel reflectance of a smooth interface, eta = n_t / n_i,
              from the complex amplitudes r_s, r_p with cos t = sqrt(1 - (1 - c^2) / eta^2)
              (imaginary past the critical angle: |r| = 1, total internal reflection).
  conductor   F(c; eta, kappa): the same amplitudes with the complex index eta + i kappa.
  schlick     F0 + (F90 - F0)(1 - c)^p.
  f82         Hoffman 2019 F82-tint: Schlick(p = 5, F90 = 1) - b c (1 - c)^6, clamped to [0, 1],
              b = Schlick(1/7) (1 - tint) / ((1/7)(6/7)^6).
  avg         F_avg = 2 int_0^1 F(mu) mu dmu, by mpmath's tanh-sinh quadrature at 40 digits, split at
              the kinks (the critical cosine; the clamp's edges, the real roots of the degree-7
              polynomial found by mpmath.polyroots).

The C++ code uses the real-arithmetic formula of Cook & Torrance for the dielectric and a closed form
for Schlick and F82: this file uses neither, so it checks them.

File written (CSV, header first):

  fresnel.csv   kind,a,b,p,mu,value
                dielectric: a = eta; conductor: a = eta, b = kappa; schlick: a = F0, b = F90, p = p;
                f82: a = F0, b = tint. mu is the cosine, or `avg` for F_avg. value: 17 significant digits.
"""
import os

import mpmath as mp

mp.mp.dps = 40
HERE = os.path.dirname(os.path.abspath(__file__))
MUS = ["0", "0.001", "0.1", "0.25", "0.5", "0.7", "0.9", "0.999", "1"]


def amplitudes(c, n):
    cos_t = mp.sqrt(1 - (1 - c * c) / (n * n))
    rs = (c - n * cos_t) / (c + n * cos_t)
    rp = (n * c - cos_t) / (n * c + cos_t)
    return (abs(rs) ** 2 + abs(rp) ** 2) / 2


def dielectric(c, eta):
    return mp.re(amplitudes(mp.mpc(c), mp.mpc(eta)))


def conductor(c, eta, kappa):
    return mp.re(amplitudes(mp.mpc(c), mp.mpc(eta, kappa)))


def schlick(c, f0, f90, p):
    return f0 + (f90 - f0) * (1 - c) ** p


def f82_b(f0, tint):
    s = mp.mpf(6) / 7
    return schlick(mp.mpf(1) / 7, f0, 1, 5) * (1 - tint) / (s ** 6 / 7)


def f82(c, f0, tint):
    v = schlick(c, f0, 1, 5) - f82_b(f0, tint) * c * (1 - c) ** 6
    return min(max(v, mp.mpf(0)), mp.mpf(1))


def f82_kinks(f0, tint):
    b = f82_b(f0, tint)
    # Schlick - b c (1 - c)^6 - k, k = 0 and 1, as a polynomial in c (coefficients highest first).
    kinks = []
    for k in (0, 1):
        poly = [mp.mpf(0)] * 8
        def add(coeffs):  # coeffs lowest first
            for i, v in enumerate(coeffs):
                poly[7 - i] += v
        one_minus_c = [mp.mpf(1), mp.mpf(-1)]
        def power(base, n):
            out = [mp.mpf(1)]
            for _ in range(n):
                out = [sum(out[j] * base[i - j] for j in range(len(out)) if 0 <= i - j < len(base))
                       for i in range(len(out) + len(base) - 1)]
            return out
        add([f0 - k])
        add([(1 - f0) * v for v in power(one_minus_c, 5)])
        add([mp.mpf(0)] + [-b * v for v in power(one_minus_c, 6)])
        while poly and poly[0] == 0:
            poly.pop(0)
        if len(poly) < 2:
            continue
        for r in mp.polyroots(poly, maxsteps=200, extraprec=200):
            if abs(mp.im(r)) < mp.mpf(10) ** -25 and 0 < mp.re(r) < 1:
                kinks.append(mp.re(r))
    return sorted(kinks)


def average(f, kinks):
    points = [mp.mpf(0)] + list(kinks) + [mp.mpf(1)]
    return 2 * mp.quad(lambda mu: f(mu) * mu, points)


def fmt(x):
    return mp.nstr(x, 17, min_fixed=-4, max_fixed=4, strip_zeros=False) if x != 0 else "0"


def rows():
    out = []
    for eta in ["0.5", "0.6667", "0.9", "1.05", "1.17", "1.333", "1.5", "2.5", "4"]:
        e = mp.mpf(eta)
        kinks = [mp.sqrt(1 - e * e)] if e < 1 else []
        for mu in MUS:
            out.append(["dielectric", eta, "0", "0", mu, fmt(dielectric(mp.mpf(mu), e))])
        out.append(["dielectric", eta, "0", "0", "avg", fmt(average(lambda m: dielectric(m, e), kinks))])
    # Gold, silver, aluminium (one channel each, index at about 600 nm) and a weak absorber.
    for eta, kappa in [("0.2", "3.0"), ("0.13", "3.9"), ("1.2", "7.26"), ("1.5", "0.1")]:
        e, k = mp.mpf(eta), mp.mpf(kappa)
        for mu in MUS:
            out.append(["conductor", eta, kappa, "0", mu, fmt(conductor(mp.mpf(mu), e, k))])
        out.append(["conductor", eta, kappa, "0", "avg", fmt(average(lambda m: conductor(m, e, k), []))])
    for f0, f90, p in [("0.04", "1", "5"), ("0.5", "0.8", "3.5"), ("0.9", "1", "5")]:
        a, b, q = mp.mpf(f0), mp.mpf(f90), mp.mpf(p)
        out.append(["schlick", f0, f90, p, "avg", fmt(average(lambda m: schlick(m, a, b, q), []))])
    for f0, tint in [("0.9", "0.9"), ("0.6", "0.5"), ("0.04", "1"), ("0.1", "0"), ("0", "0.3")]:
        a, t = mp.mpf(f0), mp.mpf(tint)
        for mu in MUS:
            out.append(["f82", f0, tint, "0", mu, fmt(f82(mp.mpf(mu), a, t))])
        out.append(["f82", f0, tint, "0", "avg", fmt(average(lambda m: f82(m, a, t), f82_kinks(a, t)))])
    return out


def main():
    path = os.path.join(HERE, "fresnel.csv")
    with open(path, "w") as f:
        f.write("kind,a,b,p,mu,value\n")
        for r in rows():
            f.write(",".join(r) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
