"""
Planar pendulum (paper 6.1)
===========================

The shipped ``planar-pendulum.toml``: an elliptic-arc cable (chord 0.5 m, end angles 30° and
40°, through (0.315, 0.077) m), five RANCF elements with their Kopt, pinned at A and released
under gravity. Here the scenario itself is run, as ``rancf simulate`` does; the whole study
(``rancf example run planar-pendulum``: convergence against ANCF and a beam, the element
efficiency table) takes about 6 s and is described in the user guide's *paper's studies*.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main
from rancf.post.centerline import sample_centerline
from rancf.post.system_run import load_run

scenario = files("rancf.examples") / "planar-pendulum.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
whole = load_run(out)  # the run: times, sensors, every body
run = whole.body()  # its one flexible body

# %%
# The exact element curves at six times, and the distance AB the paper monitors.
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
for i in np.linspace(0, len(run.t) - 1, 6).astype(int):
    pts = sample_centerline(run, int(i)).points
    ax.plot(pts[:, 0], pts[:, 1], label=f"t = {run.t[i]:.1f} s")
ax.set_aspect("equal")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.legend(fontsize=7)
bx.plot(run.t, whole.sensors[:, whole.sensor_names.index("AB")])
bx.set_xlabel("t [s]")
bx.set_ylabel("distance AB [m]")
fig.tight_layout()
