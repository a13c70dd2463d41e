"""A fitted normalization (docs/python.md, the paper's Figs. 5-9): k(n) of F_log by quadrature at
50 values of n, a formula for it by symbolic regression, and its error Δ(n) = k_fit/k − 1."""
import sys

import matplotlib  # type: ignore[import]
import numpy as np

import specula

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "."
n = np.geomspace(1, 1000, 50)
k = specula.normalize("log", n=n)
# Forms up to size 7 enumerated, then 10 generations of the genetic search (the default enumerates
# to size 11: a larger search, here a formula no better).
result = specula.fit(n, k, variables=["n"], ops="+,*,/", time=30, generations=10, threads=1, enumerate_size=7)
k_fit = result.best({"n": n})
print("k(n) ≈", result.best, f"(rms {result.best.train_error:.3g}, {result.evaluations} formulas tried)")
fig, (top, bottom) = plt.subplots(2, 1, sharex=True)
top.loglog(n, k, "o", label="k(n), quadrature")
top.loglog(n, k_fit, label=f"k = {result.best}")
top.legend(fontsize=7)
bottom.semilogx(n, k_fit / k - 1)
bottom.set_xlabel("n")
bottom.set_ylabel("Δ(n)")
fig.savefig(f"{out}/fitted-normalization.png", dpi=100)
assert np.max(np.abs(k_fit / k - 1)) < 0.05
