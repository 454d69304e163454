"""
Capstan
=======

The shipped ``capstan.toml``: a rope over a fixed cylinder of radius 0.2 m (friction 0.3), a
1 kg weight on its left end, the right end pulled down at 2 cm/s. While the rope slips, the
tight span pulls e^(0.3 pi) = 2.566 times the slack one (Euler-Eytelwein); the two
``axial_force`` sensors ``tight`` and ``slack`` sit in the free spans, and the ``contact_force``
sensor is the cylinder's force on the rope.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

scenario = files("rancf.examples") / "capstan.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.loadtxt(f"{out}/sensors.csv", delimiter=",", skiprows=1)
col = open(f"{out}/sensors.csv").readline().strip().split(",").index
t, tight, slack = s[:, 0], s[:, col("tight")], s[:, col("slack")]
late = t >= 0.6
print(
    f"tight/slack while slipping: {np.mean(tight[late] / slack[late]):.4f} "
    f"(e^(0.3 pi) = {np.exp(0.3 * np.pi):.4f})"
)

# %%
# The spans' tensions and their ratio: the pulled end starts smoothly over 0.5 s; once the rope
# slips the ratio holds at e^(mu pi).
ratio = np.divide(tight, slack, out=np.full_like(tight, np.nan), where=slack > 1.0)
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(t, tight, label="tight")
ax.plot(t, slack, label="slack")
ax.set_xlabel("t [s]")
ax.set_ylabel("axial force [N]")
ax.legend(fontsize=8)
bx.plot(t, ratio, label="tight / slack")
bx.axhline(np.exp(0.3 * np.pi), color="0.5", ls="--", label="e^(0.3 pi)")
bx.set_xlabel("t [s]")
bx.set_ylim(1.0, 3.0)
bx.legend(fontsize=8)
fig.tight_layout()
