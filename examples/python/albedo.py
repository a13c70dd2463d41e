"""The directional albedo ρ(θ_i) of the normalized F_log and of normalized Phong (docs/python.md):
1 at normal incidence by construction, and at most 1 at every angle (energy conservation)."""
import sys

import matplotlib  # type: ignore[import]
import numpy as np

import specula

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "."
theta = np.linspace(0, 89, 90)
for model_id in ["log-normalized", "phong-normalized"]:
    for n in [5, 50, 500]:
        rho = specula.albedo(specula.model(model_id, n=n), theta)
        plt.plot(theta, rho, label=f"{model_id}, n = {n}")
        assert rho.max() <= 1 + 1e-6, (model_id, n, rho.max())
plt.xlabel("θ_i (degrees)")
plt.ylabel("albedo")
plt.legend(fontsize=7)
plt.savefig(f"{out}/albedo.png", dpi=100)
print("every albedo is at most 1")
