"""
Mooring line
============

The shipped ``mooring-line.toml``: a 330 m chain (288 kg/m in air, EA = 1.2326e9 N, hydrodynamic
diameter 0.216 m) from an anchor on the seabed at 100 m depth to a fairlead at the surface, in
seawater.  ``rancf static`` finds the catenary with buoyancy and the seabed; the run starts
there and surges the fairlead by 5 m over a 20 s period, with Morison drag and added mass: the
surge builds up over its first period (``build_up = 20``) and runs at full amplitude in the
second.
MoorPy's quasi-static fairlead force for this line is (-527.6, 0, -565.2) kN.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

scenario = files("rancf.examples") / "mooring-line.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["static", str(scenario)])
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.loadtxt(f"{out}/sensors.csv", delimiter=",", skiprows=1)
col = open(f"{out}/sensors.csv").readline().strip().split(",").index
res = np.load(f"{out}/results.npz")

# %%
# The line's profile at a few instants (the nodes' positions: 6 coordinates per node, the
# first three the position), and the tension at the fairlead and the anchor over the two
# periods: the build-up, then the full 5 m surge.
q = res["q"].reshape(len(res["t"]), -1, 6)
fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 3.8))
for k in np.linspace(0, len(res["t"]) - 1, 5).astype(int):
    ax.plot(q[k, :, 0], q[k, :, 2], label=f"t = {res['t'][k]:.0f} s")
ax.axhline(-100.0, color="0.5", lw=0.8)
ax.set_xlabel("x [m]")
ax.set_ylabel("z [m]")
ax.legend(fontsize=8)
bx.plot(s[:, 0], s[:, col("fairlead_tension")] / 1e3, label="fairlead")
bx.plot(s[:, 0], s[:, col("anchor_tension")] / 1e3, label="anchor")
bx.set_xlabel("t [s]")
bx.set_ylabel("tension [kN]")
bx.legend(fontsize=8)
fig.tight_layout()
