"""
An installed hose: statics with moving supports
===============================================

The shipped ``installed-hose.toml``: a 1 m hose, straight and stress free in its reference,
clamped horizontally at both ends; the end is installed 0.8 m from the start. ``rancf static``
loads it first (gravity), then moves the end in: the hose sags further instead of meeting a
bifurcation. The load path is a run folder that ``rancf plot`` and ``rancf export`` read.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt

from rancf.cli import main
from rancf.post.centerline import sample_centerline
from rancf.post.system_run import load_run

scenario = files("rancf.examples") / "installed-hose.toml"
out = f"{tempfile.mkdtemp()}/static"
main(["static", str(scenario), "--out", out])
path = load_run(out).body()

# %%
# The shapes along the load path: the factor λ runs from 0 to 1 while gravity is applied, and
# from 1 to 2 while the end moves to its installed place.
fig, ax = plt.subplots(figsize=(7, 3.5))
for i, lam in enumerate(path.t):
    pts = sample_centerline(path, i).points
    ax.plot(pts[:, 0], pts[:, 1], color=plt.cm.viridis(lam / 2), lw=1 + (i == len(path.t) - 1))
ax.set_aspect("equal")
ax.set_xlabel("x [m]")
ax.set_ylabel("y [m]")
ax.set_title(f"{len(path.t)} converged load steps, λ = 0 … 2")
fig.tight_layout()
