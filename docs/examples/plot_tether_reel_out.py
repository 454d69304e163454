"""
Tether reel-out
===============

The shipped ``tether-reel-out.toml``: a 2 kg payload on a Dyneema tether, pushed by a steady
15 N wind, paid out by a winch from 10 m to 30 m over 16 s. The payload swings out and down as
the line lengthens; its distance from the winch is the line's length plus its small stretch.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

scenario = files("rancf.examples") / "tether-reel-out.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.genfromtxt(f"{out}/sensors.csv", delimiter=",", names=True)
distance = np.hypot(s["payload_x"], s["payload_y"])
print(f"largest |distance - length|: {np.max(np.abs(distance - s['reel_length'])):.2e} m")

# %%
# The payload's path, and the tension at the winch as the line pays out.
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(s["payload_x"], s["payload_y"])
ax.plot([0.0], [0.0], "ks", label="winch")
ax.set_aspect("equal")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.legend(fontsize=8)
bx.plot(s["t"], s["reel_tension"], label="tension [N]")
bx.plot(s["t"], s["reel_speed"], label="pay-out rate [m/s]")
bx.set_xlabel("t [s]")
bx.legend(fontsize=8)
fig.tight_layout()
