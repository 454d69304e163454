"""
Spatial pendulum (paper 6.2)
============================

The shipped ``spatial-pendulum.toml``: the arc lies in the vertical x–z plane, pinned at A,
gravity along −z; its free end B starts with 1 m/s out of the plane, so the motion is truly
three-dimensional. ``rancf example run spatial-pendulum`` adds the convergence study and the
rerun with the rod element.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main
from rancf.post.centerline import sample_centerline
from rancf.post.system_run import load_run

scenario = files("rancf.examples") / "spatial-pendulum.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
whole = load_run(out)  # the run: times, sensors, every body
run = whole.body()  # its one flexible body

# %%
# Configurations in 3D, and how far the tip leaves the plane of the arc.
fig = plt.figure(figsize=(10, 4))
ax = fig.add_subplot(1, 2, 1, projection="3d")
for i in np.linspace(0, len(run.t) - 1, 6).astype(int):
    pts = sample_centerline(run, int(i)).points
    ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], label=f"t = {run.t[i]:.1f} s")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.set_zlabel("z [m]")
ax.legend(fontsize=7)
bx = fig.add_subplot(1, 2, 2)
bx.plot(run.t, whole.sensors[:, whole.sensor_names.index("tip_y")])
bx.set_xlabel("t [s]")
bx.set_ylabel("tip y (out of plane) [m]")
fig.tight_layout()
