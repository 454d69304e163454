"""
Flexible slider-crank
=====================

The shipped ``slider-crank.toml``: a rigid crank driven through the spin-up law (150 rad/s
reached in 0.05 s), a flexible steel connecting rod pinned to it and to a slider that a slider
joint keeps on the x axis. A system: its run folder holds the system's files and one folder per
flexible body (``bodies/rod``).
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main
from rancf.post.centerline import sample_centerline
from rancf.post.system_run import load_run

scenario = files("rancf.examples") / "slider-crank.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
run = load_run(out).body("rod")
s = np.loadtxt(f"{out}/sensors.csv", delimiter=",", skiprows=1)
names = open(f"{out}/sensors.csv").readline().strip().split(",")
col = names.index

# %%
# The connecting rod (its exact element curves) at a few times, the slider's position, and the
# rod's midpoint deflection from its chord.
fig, (cx, ax, bx) = plt.subplots(1, 3, figsize=(12, 3.5))
for i in np.linspace(100, len(run.t) - 1, 5).astype(int):
    pts = sample_centerline(run, int(i)).points
    cx.plot(pts[:, 0], pts[:, 1], label=f"t = {run.t[i]:.2f} s")
cx.set_xlabel("x [m]")
cx.set_ylabel("y [m]")
cx.legend(fontsize=7)
start, mid, end = (s[:, [col(f"rod_{p}_x"), col(f"rod_{p}_y")]] for p in ("start", "mid", "end"))
chord, arm = end - start, mid - start
cross = chord[:, 0] * arm[:, 1] - chord[:, 1] * arm[:, 0]
deflection = cross / np.linalg.norm(chord, axis=1)
ax.plot(s[:, 0], s[:, col("slider_x")])
ax.set_xlabel("t [s]")
ax.set_ylabel("slider x [m]")
bx.plot(s[:, 0], 1e3 * deflection)
bx.set_xlabel("t [s]")
bx.set_ylabel("rod midpoint deflection [mm]")
fig.tight_layout()
