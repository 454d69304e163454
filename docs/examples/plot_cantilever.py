"""
Cantilever: statics and modes
=============================

The shipped ``cantilever.toml``: a straight 0.5 m cable of 8 elements, clamped at the start, a
1 mN load at the tip. ``rancf example run cantilever`` runs what it is meant for, ``rancf
static`` and ``rancf modes``; here the same through the Python API.
"""

from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

import rancf
from rancf.post.plots import centerline

scenario = rancf.load_scenario(files("rancf.examples") / "cantilever.toml")
model = scenario.build_model()
modes = rancf.natural_modes(model, count=4)
print(np.round(modes.frequencies_hz, 6))

# %%
# The first four mode shapes, scaled to a tenth of the length.
fig, ax = plt.subplots(figsize=(7, 3))
ref = centerline(model, model.q0)
for i, f in enumerate(modes.frequencies_hz):
    phi = modes.modes[i]
    shape = centerline(model, model.q0 + 0.05 * phi / np.abs(model.node_positions(phi)).max())
    ax.plot(shape[:, 0], shape[:, 1], label=f"mode {i + 1}: {f:.3f} Hz")
ax.plot(ref[:, 0], ref[:, 1], "k--", lw=0.8, label="reference")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.legend(fontsize=8)
ax.set_aspect("equal")
