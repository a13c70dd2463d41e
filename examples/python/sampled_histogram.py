"""A sampled histogram (docs/python.md): GGX's importance samples at θ_i = 45°, binned in cos θ_o,
against the density the sampler states, and the mean weight against the albedo."""
import sys

import matplotlib  # type: ignore[import]
import numpy as np

import specula

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "."
ggx = specula.model("ggx", alpha=0.3)
rng = np.random.default_rng(1)
count = 200_000
wi = np.array([np.sin(np.radians(45)), 0, np.cos(np.radians(45))])
wo, pdf, weight = ggx.sample(wi, rng.random(count), rng.random(count))
kept = pdf > 0
counts, edges, _ = plt.hist(wo[kept, 2], bins=50, range=(0, 1), density=True, label="samples")
# The density the sampler states, per unit cos θ_o: its pdf per solid angle integrated over φ_o.
mu = (edges[:-1] + edges[1:]) / 2
phi = np.linspace(0, 2 * np.pi, 512, endpoint=False)[:, None]
s = np.sqrt(1 - mu * mu)
directions = np.stack(np.broadcast_arrays(s * np.cos(phi), s * np.sin(phi), mu), axis=-1)
stated = ggx.pdf(wi, directions).mean(axis=0) * 2 * np.pi / kept.mean()
plt.plot(mu, stated, label="pdf, integrated over φ")
plt.xlabel("cos θ_o")
plt.legend()
plt.savefig(f"{out}/sampled-histogram.png", dpi=100)
albedo = float(specula.albedo(ggx, [45])[0])
mean = float(weight.mean())
se = float(weight.std() / np.sqrt(count))
print(f"mean weight {mean:.5f} ± {se:.5f}, albedo {albedo:.5f}")
assert abs(mean - albedo) < 5 * se
assert np.max(np.abs(counts - stated)) < 0.05 * np.max(stated) + 0.05
assert specula.check_sampling(ggx, theta=[45], samples=100_000).passes
