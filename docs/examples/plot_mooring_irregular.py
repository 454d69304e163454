"""
Mooring line by its length in an irregular sea
==============================================

A 100 m studless chain (50 mm: 49.75 kg/m in air, EA = 2.135e8 N, volume-equivalent diameter
0.09 m) from an anchor on the seabed at (-90, 0, -30) m to a fairlead at the surface, given as a
``line`` between its ends with ``length = 100`` (the unstretched length; the chord is 94.87 m,
and rancf finds the start shape). ``rancf static`` finds the catenary with buoyancy on the
seabed plane: MoorPy 1.3 gives 34359 N at the fairlead for this line.

The run starts from that equilibrium in a JONSWAP sea (Hs = 2.5 m, Tp = 8 s, gamma = 3.3, 30 m
of water, 50 components, seed 3: the same seed gives the same sea) acting on the chain through
Morison drag, Froude-Krylov and added mass, the fairlead held fixed. The waves start at full
height at t = 0 (no build-up), so the statistics leave out the first 60 s.

Expected run time: about 7 s of CPU time (16 s wall time with other work on the machine; most
of it the 300 s simulation) on 2 cores of an AMD EPYC (Zen 2), Python 3.11.
"""

import math
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

D = 0.09  # [m] volume-equivalent diameter
AREA = math.pi * D**2 / 4
folder = Path(tempfile.mkdtemp())
(folder / "chain.toml").write_text(f"""
[geometry]
kind = "line"
start = [-90.0, 0.0, -30.0]
end = [0.0, 0.0, 0.0]
length = 100.0

[mesh]
elements = 20

[section]
area = {AREA!r}
inertia = 1.0e-9

[material]
density = {49.75 / AREA!r}
youngs_modulus = {2.135e8 / AREA!r}

[hydro]
diameter = {D!r}
drag_normal = 1.2
drag_axial = 0.4
added_mass_normal = 1.0
added_mass_axial = 0.5

[fluid]
density = 1025.0
surface = 0.0

[fluid.waves]
spectrum = "jonswap"
hs = 2.5
tp = 8.0
gamma = 3.3
depth = 30.0
components = 50
seed = 3

[loads]
gravity = [0.0, 0.0, -9.80665]

[[obstacles]]
name = "seabed"
kind = "plane"
point = [0.0, 0.0, {-30.0 - D / 2!r}]
normal = [0.0, 0.0, 1.0]

[[supports]]
at = "start"
kind = "pin"

[[supports]]
at = "end"
kind = "pin"

[solver]
t_end = 300.0
step = 0.1
output_step = 0.5
initial_state = "static"

[[sensors]]
name = "fairlead"
kind = "tension"
at = "end"

[[sensors]]
name = "eta"
kind = "wave_elevation"
at_point = [0.0, 0.0, 0.0]
""")
main(["static", str(folder / "chain.toml")])
out = folder / "run"
main(["simulate", str(folder / "chain.toml"), "--out", str(out), "--quiet"])
s = np.loadtxt(out / "sensors.csv", delimiter=",", skiprows=1)
col = (out / "sensors.csv").read_text().splitlines()[0].split(",").index
t, tension, eta = s[:, 0], s[:, col("fairlead")], s[:, col("eta")]

# %%
# Fairlead tension statistics over the last 240 s, beside the tension at t = 0 (the statics'
# catenary, with the waves' Froude-Krylov load of that instant), and the sea's elevation at the
# fairlead: its standard deviation is about Hs / 4 over a long record (240 s is some 30 peak
# periods, so expect a few per cent of scatter).
steady = t >= 60.0
ts = tension[steady]
print(f"fairlead tension at t = 0: {tension[0]:.0f} N (MoorPy, statics: 34359 N)")
print(f"fairlead tension: mean {ts.mean():.0f} N, std {ts.std():.0f} N,")
print(f"  min {ts.min():.0f} N, max {ts.max():.0f} N (max / mean {ts.max() / ts.mean():.3f})")
print(f"elevation std at the fairlead: {eta[steady].std():.3f} m (Hs / 4 = 0.625 m)")

fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 3.8), width_ratios=[2, 1])
ax.plot(t, tension / 1e3, lw=0.8, label="fairlead tension")
ax.axhline(tension[0] / 1e3, color="k", lw=0.8, ls=":", label="t = 0")
ax.axvline(60.0, color="0.6", lw=0.8)
ax.set_xlabel("t [s]")
ax.set_ylabel("tension [kN]")
ex = ax.twinx()
ex.plot(t, eta, "C1", lw=0.5, alpha=0.6)
ex.set_ylabel("elevation at the fairlead [m]", color="C1")
ax.legend(fontsize=8, loc="upper left")
bx.hist(ts / 1e3, bins=30, density=True, color="C0", alpha=0.7)
bx.axvline(ts.mean() / 1e3, color="k", lw=0.8)
bx.set_xlabel("tension after 60 s [kN]")
bx.set_ylabel("density [1/kN]")
fig.tight_layout()
