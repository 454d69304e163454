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
from rancf.cli import main
from rancf.post.plots import centerline

path = files("rancf.examples") / "cantilever.toml"
main(["static", str(path)])
main(["modes", str(path), "--count", "4"])

# %%
# The same from Python: the model of the scenario, its natural modes.
model = rancf.load_scenario(path).build_model()
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
