"""
Power line in a gust
====================

The shipped ``power-line-gust.toml``: a 300 m conductor span hangs between two towers; a
2 s gust (one distributed load across the span, rising and falling) swings it out, and the
still air's drag damps the swing that follows.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

scenario = files("rancf.examples") / "power-line-gust.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.loadtxt(f"{out}/sensors.csv", delimiter=",", skiprows=1)
col = open(f"{out}/sensors.csv").readline().strip().split(",").index
print(
    f"tower tension: {s[0, col('tower_tension')] / 1e3:.1f} kN at rest, "
    f"{s[:, col('tower_tension')].max() / 1e3:.1f} kN at most"
)

# %%
# The mid-span point seen along the span (it swings out and up), and the tension at a tower.
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(s[:, col("mid_y")], s[:, col("mid_z")])
ax.set_xlabel("mid-span y [m]")
ax.set_ylabel("mid-span z [m]")
ax.set_aspect("equal")
bx.plot(s[:, 0], s[:, col("tower_tension")] / 1e3)
bx.set_xlabel("t [s]")
bx.set_ylabel("tension at the tower [kN]")
fig.tight_layout()
