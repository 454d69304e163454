"""
Robot cable: a support on a prescribed path
===========================================

The shipped ``robot-cable.toml``: a 1 m cable hangs between a fixed clamp and a gripper 0.7 m
away; the gripper carries its end once around a circle of radius 0.2 m in 2 s (a motion table,
cubic interpolation). The run starts from the static equilibrium; the force the gripper exerts
on the cable is a sensor.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main
from rancf.post.centerline import sample_centerline
from rancf.post.system_run import load_run

scenario = files("rancf.examples") / "robot-cable.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
whole = load_run(out)  # the run: times, sensors, every body
run = whole.body()  # its one flexible body
col = whole.sensor_names.index

# %%
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
for i in np.linspace(0, len(run.t) - 1, 8).astype(int):
    pts = sample_centerline(run, int(i)).points
    ax.plot(pts[:, 0], pts[:, 1], lw=1, label=f"t = {run.t[i]:.2f} s")
gripper = whole.sensors[:, [col("gripper_x"), col("gripper_y")]]
ax.plot(gripper[:, 0], gripper[:, 1], "k:", label="gripper")
ax.set_aspect("equal")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.legend(fontsize=6)
for c in ("gripper_force_x", "gripper_force_y"):
    bx.plot(run.t, whole.sensors[:, col(c)], label=c)
bx.set_xlabel("t [s]")
bx.set_ylabel("force on the cable [N]")
bx.legend()
fig.tight_layout()
