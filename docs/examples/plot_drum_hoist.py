"""
Driven drum
===========

The shipped ``drum-hoist.toml``: a torque on a winch drum (radius 0.2 m, inertia 0.5 kg m²)
reels in a steel wire with a 10 kg load. The unstretched length outside the drum is a
coordinate of the system: the torque, the drum's inertia and the wire's pull decide it. From the
static balance the torque rises to 1.3 times the holding torque, and the load rises as on a rigid
rope, ``(J / r² + m + ρA L) L̈ = (m + ρA L) g − torque / r``.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np
from scipy.integrate import solve_ivp

from rancf.cli import main

scenario = files("rancf.examples") / "drum-hoist.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.genfromtxt(f"{out}/sensors.csv", delimiter=",", names=True)

# the rigid rope with the same drum (wire rho A = 7850 pi 0.005^2 kg/m)
rho_a, m, r, j, g = 7850.0 * np.pi * 0.005**2, 10.0, 0.2, 0.5, 9.81
l0 = s["drum_length"][0]


def torque(t: float) -> float:
    return float(np.interp(t, [0.0, 0.05, 10.0], [25.668, 33.368, 33.368]))


def rigid(t: float, z: np.ndarray) -> list[float]:
    length, rate = z
    inertia = (j - rho_a * r**2 * (length - l0)) / r**2 + m + rho_a * length
    return [rate, ((m + rho_a * length) * g - torque(t) / r) / inertia]


ref = solve_ivp(rigid, (0.0, 2.0), [l0, 0.0], t_eval=s["t"], rtol=1e-10, atol=1e-12)
print(
    f"length at 2 s: {s['drum_length'][-1]:.4f} m (rigid rope: {ref.y[0][-1]:.4f} m); "
    f"tension at the drum {s['drum_tension'][-1]:.1f} N"
)

# %%
# The length the drum holds and the load's height, against the rigid rope; the pull at the
# drum is the load's weight and the wire's, plus what accelerates them.
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(s["t"], s["drum_length"], label="wire outside the drum [m]")
ax.plot(s["t"], ref.y[0], "--", label="rigid rope [m]")
ax.plot(s["t"], -s["load_y"], label="depth of the load [m]")
ax.set_xlabel("t [s]")
ax.legend(fontsize=8)
bx.plot(s["t"], s["drum_tension"], label="tension at the drum [N]")
bx.set_xlabel("t [s]")
bx.legend(fontsize=8)
fig.tight_layout()
