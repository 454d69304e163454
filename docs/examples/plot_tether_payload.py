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
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(s[:, col("payload_x")], s[:, col("payload_y")])
ax.set_aspect("equal")
ax.set_xlabel("payload x [m]")
ax.set_ylabel("payload y [m]")
force = np.hypot(s[:, col("hook_force_x")], s[:, col("hook_force_y")])
bx.plot(s[:, 0], force)
bx.set_xlabel("t [s]")
bx.set_ylabel("force of the hook [N]")
fig.tight_layout()
