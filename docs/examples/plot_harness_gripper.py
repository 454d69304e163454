"""
Robot harness: a gripper on an absolute path that turns
=======================================================

A 0.6 m harness cable (8 mm, 1500 kg/m³, E = 100 MPa) is clamped at the robot's base at the
origin, pointing along x; its other end is held by the gripper. The robot's controller gives the
gripper's path as a CSV file of absolute positions with a header row (``t, x, y``: a cubic from
(0.6, 0) to (0.35, 0.15) m in 1.5 s) and its turn as a second file (``t, angle``: 90 degrees,
in radians, along the same cubic). The gripper is a support with
``motion = { table = "path.csv", absolute = true }`` and, a clamp, ``rotation = { table =
"turn.csv" }``: its clamped direction turns by the angle (docs/derivations/clamp-paths.md). The
path starts at the cable's end, so the run may start at rest; it starts from the static sag.

Expected run time: about 1.5 s of CPU time (4 s wall time with other work on the machine; most
of it importing and plotting) on 2 cores of an AMD EPYC (Zen 2), Python 3.11.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main
from rancf.post.system_run import load_run

T_MOVE = 1.5  # [s]
folder = Path(tempfile.mkdtemp())
t = np.linspace(0.0, T_MOVE, 16)
s = t / T_MOVE
h = 3 * s**2 - 2 * s**3  # the cubic: from rest to rest
path = np.c_[t, 0.6 - 0.25 * h, 0.15 * h]
turn = np.c_[t, 0.5 * np.pi * h]
np.savetxt(folder / "path.csv", path, delimiter=",", header="t,x,y", comments="", fmt="%.9f")
np.savetxt(folder / "turn.csv", turn, delimiter=",", header="t,angle", comments="", fmt="%.12f")

(folder / "harness.toml").write_text("""
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.6, 0.0]

[mesh]
elements = 12

[section]
radius = 0.004

[material]
density = 1500.0
youngs_modulus = 1.0e8

[[supports]]
at = "start"
kind = "clamp"

[[supports]]
at = "end"
kind = "clamp"
motion = { table = "path.csv", absolute = true, interpolation = "cubic" }
rotation = { table = "turn.csv", interpolation = "cubic" }

[loads]
gravity = [0.0, -9.81]

[damping]
mass_proportional = 2.0

[solver]
t_end = 2.0
step = 1.0e-3
output_step = 0.02
initial_state = "static"

[[sensors]]
name = "gripper"
kind = "position"
at = "end"

[[sensors]]
name = "grip_force"
kind = "reaction"
at = "end"
""")
out = folder / "run"
main(["simulate", str(folder / "harness.toml"), "--out", str(out), "--quiet"])
whole = load_run(out)
run = whole.body()
col = whole.sensor_names.index

# %%
# The gripper is on its path at every stored state (the path is the table's cubic spline,
# which reproduces the cubic exactly), and the cable's end tangent is the clamped direction:
# the reference tangent (along x) turned by the commanded angle.
q = run.q.reshape(len(run.t), run.n_nodes, -1)
end, grad = q[:, -1, :2], q[:, -1, 2:4]
sr = np.clip(run.t / T_MOVE, 0.0, 1.0)
hs = 3 * sr**2 - 2 * sr**3  # the cubic at the stored times
exact = np.c_[0.6 - 0.25 * hs, 0.15 * hs]
angle = np.degrees(np.arctan2(grad[:, 1], grad[:, 0]))
print(f"largest distance of the gripper from its path: {np.abs(end - exact).max():.2e} m")
print(f"end tangent after the turn: {angle[-1]:.6f} deg (commanded 90)")
moment = whole.sensors[:, col("grip_force_mz")]
print(f"gripper moment on the cable: {moment[0]:.4f} N m at rest, {moment[-1]:.4f} N m after")

fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4))
for k in np.linspace(0, np.searchsorted(run.t, T_MOVE), 6).astype(int):
    (line,) = ax.plot(q[k, :, 0], q[k, :, 1], lw=1, label=f"t = {run.t[k]:.2f} s")
    d = 0.06 * grad[k] / np.linalg.norm(grad[k])
    ax.annotate("", end[k] + d, end[k], arrowprops={"arrowstyle": "->", "color": line.get_color()})
ax.plot(path[:, 1], path[:, 2], "k.", ms=3, label="path.csv rows")
ax.set_aspect("equal")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.set_title("the harness and the gripper's clamped direction")
ax.legend(fontsize=7)
bx.plot(run.t, angle, label="end tangent [deg]")
bx.plot(t, np.degrees(turn[:, 1]), "k.", ms=4, label="turn.csv [deg]")
bx.set_xlabel("t [s]")
bx.set_ylabel("angle [deg]")
cx = bx.twinx()
cx.plot(run.t, moment, "C3", lw=1)
cx.set_ylabel("gripper moment on the cable [N m]", color="C3")
bx.legend(fontsize=8, loc="center right")
fig.tight_layout()
