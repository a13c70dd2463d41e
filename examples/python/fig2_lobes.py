"""The paper's Fig. 2 (docs/python.md): F_log, c^n and Schlick's lobe at n = 20 over the angle."""
import sys

import matplotlib  # type: ignore[import]
import numpy as np

import specula

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "."
x = np.linspace(0, 90, 901)                      # the angle between R and V, in degrees
c = np.cos(np.radians(x))
for lobe_id, label in [("log", "F_log"), ("phong", "c^n"), ("schlick", "Schlick")]:
    plt.plot(x, specula.model(lobe_id, n=20).lobe(c), label=label)
plt.xlim(0, 40)
plt.xlabel("angle (degrees)")
plt.legend()
plt.title("lobes at n = 20")
plt.savefig(f"{out}/fig2.png", dpi=100)
# F_log stays above c^n past its half-width, and reaches 0 where n·log2(c) = -3.
print("F_log reaches 0 at", x[np.argmax(specula.model("log", n=20).lobe(c) == 0)], "degrees")
