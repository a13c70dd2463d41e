#!/usr/bin/env python3
"""The reference for the GGX energy table (bench/lut_bench.cpp, tests/analysis/energy_test.cpp):
E(mu, alpha) = directional albedo of GGX (Trowbridge-Reitz D, Smith height-correlated G2,
F = 1) on the 32 x 32 grid alpha = 0.05:1@32, mu = 0.03125:1@32, written to ggx_lut.csv.

Independent of the C++ code and of make_albedo_reference.py's integration code: a second method,
a tensor Gauss-Legendre rule over the microfacet normal m = (theta_m, phi_m) in double precision,
   E = 2 int_0^theta_max sin(theta_m) int_0^phi_max(theta_m) D(m) G2(i, o) (i.m) / mu_i dphi dtheta_m,
o = 2 (i.m) m - i, with phi_max where o reaches the horizon (closed form), theta_m split where the
horizon starts cutting ((90 deg - theta_i)/2), at theta_max = (90 deg + theta_i)/2 and at
atan(alpha 2^k), k = -3..5; every piece and the phi range mapped by x = a + (b - a)(1 - cos(pi t))/2,
which makes the (1 + kappa)^(3/2) endpoint behaviour at the cut's ends smooth in t.
32 x 32 cells at mpmath precision would take hours; instead this script asserts
  - convergence: order 48 and order 64 agree to 1e-13 on every cell (the file holds order 64);
  - agreement with the 10 GGX rows of albedo.csv (mpmath, 20 digits, make_albedo_reference.py) to
    2e-13 absolute, and E(mu = 1) against the 1-D integral at normal incidence (mpmath, 30 digits).
Regenerate from the repository root (pure Python, about 3 minutes on 2 cores):
    python3 tests/reference/make_ggx_lut_reference.py [--jobs N]
"""
import argparse
import csv
import math
import multiprocessing
import os

import mpmath

HERE = os.path.dirname(os.path.abspath(__file__))
ALPHAS = [0.05 + (1 - 0.05) * i / 31 for i in range(32)]
MUS = [0.03125 + (1 - 0.03125) * j / 31 for j in range(32)]


def spaced(a, b, count):
    """What specula's a:b@count gives: a + (b - a) i / (count - 1), the last exactly b."""
    return [a + (b - a) * i / (count - 1) if i < count - 1 else b for i in range(count)]


ALPHAS, MUS = spaced(0.05, 1.0, 32), spaced(0.03125, 1.0, 32)


def gauss_legendre(n):
    mpmath.mp.dps = 40
    nodes = []
    for k in range(1, n + 1):
        x = mpmath.cos(mpmath.pi * (k - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = mpmath.mpf(1), x
            for j in range(2, n + 1):
                p0, p1 = p1, ((2 * j - 1) * x * p1 - (j - 1) * p0) / j
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < mpmath.mpf(10) ** -35:
                break
        nodes.append((float((x + 1) / 2), float(1 / ((1 - x * x) * dp * dp))))  # on [0, 1], weights sum 1
    return nodes


def cos_mapped(nodes, a, b):
    """(x, weight) on [a, b] through x = a + (b - a)(1 - cos(pi t))/2."""
    return [(a + (b - a) * (1 - math.cos(math.pi * t)) / 2, w * (b - a) * math.pi * math.sin(math.pi * t) / 2)
            for t, w in nodes]


def smith_lambda(mu, a2):
    return (math.sqrt(1 + a2 * (1 - mu * mu) / (mu * mu)) - 1) / 2


def albedo(alpha, mu_i, nodes):
    a2 = alpha * alpha
    si, ci = math.sqrt(max(0.0, 1 - mu_i * mu_i)), mu_i
    theta_i = math.acos(mu_i)
    lam_i = smith_lambda(mu_i, a2)
    cut_start, theta_max = (math.pi / 2 - theta_i) / 2, (math.pi / 2 + theta_i) / 2
    cuts = {0.0, cut_start, theta_max}
    cuts.update(math.atan(alpha * 2.0 ** k) for k in range(-3, 6))
    cuts = sorted(c for c in cuts if 0 <= c <= theta_max)
    total = 0.0
    for a, b in zip(cuts, cuts[1:]):
        for tm, wt in cos_mapped(nodes, a, b):
            st, ct = math.sin(tm), math.cos(tm)
            if si * st == 0:
                phi_max = math.pi if 2 * ct * ct > 1 else 0.0
            else:
                kappa = ci * (1 / (2 * ct) - ct) / (si * st)
                phi_max = 0.0 if kappa >= 1 else (math.pi if kappa <= -1 else math.acos(kappa))
            if phi_max == 0:
                continue
            q = ct * ct * a2 + st * st
            d = a2 / (math.pi * q * q)
            inner = 0.0
            for phi, wp in cos_mapped(nodes, 0.0, phi_max):
                im = si * st * math.cos(phi) + ci * ct
                mu_o = 2 * im * ct - ci
                if mu_o <= 0 or im <= 0:
                    continue
                inner += wp * im / (1 + lam_i + smith_lambda(mu_o, a2))
            total += wt * st * d * inner
    return 2 * total / mu_i


def normal_incidence(alpha):
    """E(mu = 1) as a 1-D integral over theta_m (o = reflection of N about m), mpmath 30 digits."""
    mpmath.mp.dps = 30
    a2 = mpmath.mpf(alpha) ** 2

    def f(tm):
        ct, st = mpmath.cos(tm), mpmath.sin(tm)
        mu_o = 2 * ct * ct - 1
        if mu_o <= 0:
            return mpmath.mpf(0)
        q = ct * ct * a2 + st * st
        lam_o = (mpmath.sqrt(1 + a2 * (1 - mu_o ** 2) / mu_o ** 2) - 1) / 2
        return 2 * mpmath.pi * st * ct * (a2 / (mpmath.pi * q * q)) / (1 + lam_o)

    points = sorted({mpmath.mpf(0), mpmath.pi / 4} | {mpmath.atan(alpha * 2 ** k) for k in range(-3, 6) if mpmath.atan(alpha * 2 ** k) < mpmath.pi / 4})
    return mpmath.quad(f, points)


def cell(args):
    alpha, mu, orders = args
    return [albedo(alpha, mu, gauss_legendre(n)) for n in orders]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--jobs", type=int, default=2)
    jobs = parser.parse_args().jobs
    with open(os.path.join(HERE, "albedo.csv")) as f:
        rows = [r for r in csv.DictReader(f) if r["model"] == "ggx"]
    for r in rows:
        mu = math.cos(math.radians(float(r["theta_deg"])))
        e = albedo(float(r["p1"]), mu, gauss_legendre(64))
        assert abs(e - float(r["albedo"])) < 2e-13, (r, e)
    for alpha in (ALPHAS[0], ALPHAS[15], ALPHAS[31]):
        e, exact = albedo(alpha, 1.0, gauss_legendre(64)), float(normal_incidence(alpha))
        assert abs(e - exact) < 2e-13, (alpha, e, exact)
    cells = [(alpha, mu, (48, 64)) for alpha in ALPHAS for mu in MUS]
    with multiprocessing.Pool(jobs) as pool:
        results = pool.map(cell, cells, chunksize=8)
    worst = max(abs(a - b) for a, b in results)
    assert worst < 1e-13, worst
    with open(os.path.join(HERE, "ggx_lut.csv"), "w", newline="") as f:
        f.write("alpha,mu,E\n")
        for (alpha, mu, _), (_, e) in zip(cells, results):
            f.write(f"{alpha!r},{mu!r},{e!r}\n")
    print(f"ggx_lut.csv: {len(cells)} cells; order 48 vs 64: max {worst:.2g}")


if __name__ == "__main__":
    main()
