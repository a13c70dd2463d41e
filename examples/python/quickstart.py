"""The README's Python example (docs/python.md): the paper's lobe, its normalization and its error."""
import numpy as np

import specula

log = specula.model("log-normalized", n=20)
c = np.linspace(0.9, 1.0, 5)
print("F_log(c) at n = 20:", np.round(log.lobe(c), 6))
print("k(n) for n = 1, 20, 1000:", np.round(specula.normalize("log", n=[1, 20, 1000]), 6))
print("max |F_log - c^n| at n = 20:", round(float(specula.error("log", n=[20])["max_abs"][0]), 6))
print("energy conserved at every angle:", bool(specula.check(log, pairs=1000, step=5)))
