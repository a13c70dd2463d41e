"""The paper's Figs. 3 and 4 (docs/python.md): the largest relative error in the epicenter and the
largest absolute error of F_log and Schlick's lobe against c^n, for n from 1 to 1000."""
import sys

import matplotlib  # type: ignore[import]
import numpy as np

import specula

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "."
n = np.geomspace(1, 1000, 60)
errors = {label: specula.error(lobe_id, reference="phong", n=n) for lobe_id, label in [("log", "F_log"), ("schlick", "Schlick")]}
for figure, column, title in [(3, "max_rel_epicenter", "max relative error, F >= 0.5"), (4, "max_abs", "max absolute error")]:
    plt.figure()
    for label, e in errors.items():
        plt.semilogx(n, e[column], label=label)
    plt.xlabel("n")
    plt.title(title)
    plt.legend()
    plt.savefig(f"{out}/fig{figure}.png", dpi=100)
print("F_log's largest absolute error over n:", round(float(errors["F_log"]["max_abs"].max()), 4))  # the paper: 0.12
