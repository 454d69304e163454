"""
Atwood machine through two guides
=================================

The shipped ``atwood-guides.toml``: a rope with 2 kg and 3 kg on its ends runs through two
frictionless guides (``kind = "sliding"`` joints) at the top corners of a 0.2 m wide frame, and
the heavier side drops. One rope, no pulleys: each guide holds the rope's point at its place
while the material runs through it. The run starts from the static equilibrium with the 3 kg
mass held by 9.81 N, let go over the first millisecond (the rope, straight when unloaded, is
then at rest in its corners). The drop ``x`` of the 3 kg mass follows the Atwood machine
whose rope's weight moves from one side to the other as it runs,
``x = Δm / (2 ρA) (cosh ωt − 1)``, ``ω² = 2 ρA g / (m1 + m2 + ρA L)``.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.cli import main

scenario = files("rancf.examples") / "atwood-guides.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
s = np.genfromtxt(f"{out}/sensors.csv", delimiter=",", names=True)
x = (s["left_y"] - s["right_y"]) / 2  # the 3 kg mass's drop (the 2 kg mass rises as much)
rho_a, g, m1, m2 = 4000.0 * 1e-5, 9.81, 2.0, 3.0
length = 2 * 0.49 + 0.18 + np.pi * 0.01  # legs, top, two quarter circles [m]
omega = np.sqrt(2 * rho_a * g / (m1 + m2 + rho_a * length))
rigid = (m2 - m1) / (2 * rho_a) * (np.cosh(omega * s["t"]) - 1)
run = s["guide_left_s"][0] - s["guide_left_s"][-1]
print(
    f"drop at {s['t'][-1]:.1f} s: {x[-1]:.4f} m (rigid rope: {rigid[-1]:.4f} m); "
    f"rope run through the left guide: {run:.4f} m"
)

# %%
# The drop follows the rigid rope once the rope's start stretch has settled; the guide's force
# on the rope is normal to it (no friction) and carries both legs' tension round the corner.
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(s["t"], x, label="drop of the 3 kg mass [m]")
ax.plot(s["t"], rigid, "--", label="rigid rope with its weight [m]")
ax.set_xlabel("t [s]")
ax.legend(fontsize=8)
bx.plot(s["t"], np.hypot(s["guide_left_x"], s["guide_left_y"]), label="left guide's force [N]")
bx.set_xlabel("t [s]")
bx.legend(fontsize=8)
fig.tight_layout()
