"""
Tether with a payload
=====================

The shipped ``tether-payload.toml``: a 1 m steel cable pinned at the top, a 2 kg point mass
pinned to its end, released at 30° from the vertical: a pendulum of two bodies joined by a pin.
The joint's reaction is a sensor, and so is the total energy (``rho_inf = 1``: no numerical
dissipation).
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

scenario = files("rancf.examples") / "tether-payload.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.loadtxt(f"{out}/sensors.csv", delimiter=",", skiprows=1)
col = open(f"{out}/sensors.csv").readline().strip().split(",").index
energy = s[:, col("energy")]
print(f"energy drift over {s[-1, 0]:g} s: {np.ptp(energy):.2e} J")

# %%
# The payload's path, and the force of the hook. The cable is stress free when it is released,
# so the payload's weight starts a fast axial vibration of the steel cable that
# ``rho_inf = 1`` never damps: the thin band. Its mean over 0.1 s (the thick line) follows the
# pendulum's tension, highest as the payload passes the bottom.
force = np.hypot(s[:, col("hook_force_x")], s[:, col("hook_force_y")])
window = int(round(0.1 / (s[1, 0] - s[0, 0])))
mean = np.convolve(force, np.ones(window) / window, mode="valid")
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(s[:, col("payload_x")], s[:, col("payload_y")])
ax.set_xlabel("payload x [m]")
ax.set_ylabel("payload y [m]")
bx.plot(s[:, 0], force, lw=0.2, color="0.6", label="force")
bx.plot(s[window // 2 : window // 2 + len(mean), 0], mean, lw=2, label="mean over 0.1 s")
bx.set_xlabel("t [s]")
bx.set_ylabel("force of the hook [N]")
bx.legend(fontsize=8)
fig.tight_layout()
