"""
Scordelis-Lo roof: a shell on an exact cylinder
===============================================

The shipped ``scordelis-lo-roof.toml``: one quarter of the roof of MacNeal and Harder's shell
obstacle course (R = 25, L = 50, 80 deg, t = 0.25, E = 4.32e8, nu = 0, 90 per unit area, rigid
end diaphragms) on 4 x 4 exact cylindrical elements. ``rancf static`` solves it geometrically
nonlinear (the free edge's middle moves down 0.2529; the benchmark's 0.3006 is linear, see the
shells guide) and writes the surfaces of every load step; ``rancf modes`` gives its natural
frequencies.
"""

import tempfile
from importlib.resources import files
from pathlib import Path

import matplotlib.pyplot as plt
import meshio

from rancf.cli import main

path = files("rancf.examples") / "scordelis-lo-roof.toml"
out = Path(tempfile.mkdtemp()) / "roof"
main(["static", str(path), "--out", str(out)])
main(["modes", str(path)])

# %%
# The deformed quarter roof at the full load, coloured by its vertical displacement (the
# surfaces the run wrote for ParaView, read back with meshio; displacements drawn 10 times).
last = sorted((out / "bodies" / "body").glob("body_*.vtu"))[-1]
surface = meshio.read(last)
u = surface.point_data["displacement"]
x = surface.points + 10.0 * u
tris = [t for q in surface.cells_dict["quad"] for t in ([q[0], q[1], q[2]], [q[0], q[2], q[3]])]
fig = plt.figure(figsize=(7, 5))
ax = fig.add_subplot(projection="3d")
art = ax.plot_trisurf(x[:, 0], x[:, 1], x[:, 2], triangles=tris, cmap="viridis", lw=0)
art.set_array(u[:, 2][tris].mean(axis=1))
fig.colorbar(art, ax=ax, shrink=0.6, label="vertical displacement")
ax.set_xlabel("x")
ax.set_ylabel("y")
ax.set_zlabel("z")
ax.set_title("Scordelis-Lo roof, displacements x 10")
