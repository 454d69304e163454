"""
Crane hoist
===========

The shipped ``crane-hoist.toml``: a 100 kg load lifted 10 m by a winch whose steel wire rope
runs over a frictionless sheave of radius 1 m at the jib head. The winch reels in 10 m over
14 s; the ``winch`` sensor gives the rope's unstretched length outside the drum, its rate and
the tension at the drum, the ``position`` sensor the load's height.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

scenario = files("rancf.examples") / "crane-hoist.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.genfromtxt(f"{out}/sensors.csv", delimiter=",", names=True)
print(
    f"load lifted {s['hook_y'][-1] - s['hook_y'][0]:.4f} m "
    f"(rope reeled in: {s['hoist_length'][0] - s['hoist_length'][-1]:.4f} m)"
)

# %%
# The load's height follows the rope taken in; the tension at the drum carries the wire's
# weight on the winch's side and the axial vibration the rope's run over the sheave excites.
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(s["t"], s["hook_y"], label="load height [m]")
ax.plot(s["t"], s["hoist_length"], label="rope outside the winch [m]")
ax.set_xlabel("t [s]")
ax.legend(fontsize=8)
bx.plot(s["t"], s["hoist_tension"], label="tension at the winch [N]")
bx.set_xlabel("t [s]")
bx.legend(fontsize=8)
fig.tight_layout()
