"""
Where exact geometry pays
=========================

The pendulum of paper 6.1 made stiff (the shipped ``exact-geometry.toml``: E = 2e9 Pa, three
elements). A stiff cable swings like a rigid curved body, so what matters is its reference
shape: three RANCF elements carry the exact elliptic arc, three ANCF elements only the Hermite
cubic through the nodes. Both are compared with a 24-element RANCF reference, same time step.
``rancf example run exact-geometry`` runs the whole study (five moduli, 1 to 12 elements of five
element kinds).
"""

from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

import rancf

base = rancf.load_scenario(files("rancf.examples") / "exact-geometry.toml").to_dict()


def tip(element, elements):
    """The tip's path for a mesh of ``elements`` elements of kind ``element``."""
    mesh = {**base["mesh"], "element": element, "elements": elements}
    result, names, values = rancf.simulate(rancf.Scenario(**{**base, "mesh": mesh}))
    return result.t, values[:, [names.index("tip_x"), names.index("tip_y")]]


# %%
# The reference, then three elements of each kind: the tip's distance to the reference.
t, ref = tip("rancf", 24)
fig, ax = plt.subplots(figsize=(7, 3.5))
for element in ("rancf", "ancf"):
    _, r = tip(element, 3)
    err = np.linalg.norm(r - ref, axis=1)
    print(f"{element}, 3 elements: max tip error {err.max():.2e} m")
    ax.semilogy(t[1:], err[1:], label=f"3 {element.upper()} elements")
ax.set_xlabel("t [s]")
ax.set_ylabel("tip distance to the reference [m]")
ax.legend()
fig.tight_layout()
