"""
Polyester rope
==============

The shipped ``polyester-rope.toml``: 100 m of 0.1 m polyester rope hangs from a pin with a 15 t
weight on its end. Its axial stiffness is a tension-strain table (``[material] axial_law``): the
curve whose slope is the fibre-rope stiffness model ``EA(T) = MBL (α + β T / MBL)`` (Del Vecchio
1992) with MoorPy's default polyester coefficients (α = 11.6, β = 40, MBL = 3.08 MN), i.e.
``T(e) = MBL α / β (exp(β e) − 1)``, sampled every 0.25 % of strain (the scenario's header says
more). The same rope with a linear ``EA = 14 MBL`` (MoorPy's quasi-static stiffness,
``axial_strain = "engineering"``) is the comparison. Both ropes are loaded step by step to the
full weight (``rancf static``) and their modes found about the equilibrium (``rancf modes``).
This script takes about 4 s on an AMD EPYC (Zen 2, 2 cores; a loaded machine); the example
(``rancf example run polyester-rope``) 3.1 s (the performance guide's table).
"""

import math
import re
import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

from rancf import load_scenario
from rancf.runs.modes import run_modes
from rancf.runs.static import run_static

poly = files("rancf.examples") / "polyester-rope.toml"
text = poly.read_text()
linear_text = re.sub(
    r"axial_law = \{ table = \[.*?\] \}", 'axial_strain = "engineering"', text, flags=re.S
)
tmp = tempfile.mkdtemp()
linear = f"{tmp}/linear-rope.toml"
open(linear, "w").write(linear_text)

MBL, ALPHA, BETA = 3.08e6, 11.6, 40.0
L, W, M = 100.0, 15000.0 * 9.81, 15000.0
rho_a = 1380.0 * math.pi * 0.05**2
w = rho_a * 9.81  # the rope's weight per unstretched length
EA = 5.49e9 * math.pi * 0.05**2  # the linear rope's (14 MBL)

stretch = {}
for name, path in (("polyester table", str(poly)), ("linear EA = 14 MBL", linear)):
    out = f"{tmp}/{name.split()[0]}"
    run_static(load_scenario(path), out)  # the load path written to the folder
    s = np.genfromtxt(f"{out}/sensors.csv", delimiter=",", names=True)
    stretch[name] = (s["t"], -s["weight_y"] - L)  # load factor, stretch


# %%
# The stretch along the load path (gravity and the weight grow together with the load factor)
# against the integral over the rope of the strain of its tension: the inverse of the curve the
# table samples, ``e(T) = ln(1 + β T / (α MBL)) / β``, and ``T / EA`` for the linear rope.
def curve_stretch(lam: float) -> float:
    def e(s: float) -> float:
        return math.log1p(BETA * lam * (W + w * (L - s)) / (ALPHA * MBL)) / BETA

    return quad(e, 0.0, L)[0]


lams = np.linspace(0.0, 1.0, 41)
fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4))
ax.plot(
    lams * M / 1e3, [curve_stretch(x) for x in lams], "k-", lw=1, label="∫ e(T) ds, polyester curve"
)
ax.plot(lams * M / 1e3, lams * (W * L + 0.5 * w * L * L) / EA, "k--", lw=1, label="∫ T / EA ds")
for name, (lf, d) in stretch.items():
    ax.plot(lf * M / 1e3, d, "o", label=f"rancf, {name}")
ax.set_xlabel("weight [t] (load factor × 15 t, the rope's weight scaled with it)")
ax.set_ylabel("stretch [m]")
ax.legend(fontsize=8)
full = stretch["polyester table"][1][-1]
print(
    f"stretch at 15 t: table {full:.5f} m (the curve's integral {curve_stretch(1.0):.5f} m), "
    f"linear EA {stretch['linear EA = 14 MBL'][1][-1]:.5f} m"
)

# %%
# The tension-strain curves, and the weight's bounce (the mode with the most vertical motion of
# the weight) about the equilibrium: rancf's against the rod with a tip mass, ``β tan β = ρA L /
# M``, ``f = β / (2 π L) sqrt(EA_t / ρA)``, with the tangent ``EA_t = dT/de`` of the polyester
# curve at the weight's tension and at the top's (the rope's own weight pulls there too, 7 % more
# tension, 1 % more tangent stiffness): rancf's bounce lies between the two.
e = np.linspace(0.0, 0.035, 200)
bx.plot(e * 100, MBL * ALPHA / BETA * np.expm1(BETA * e) / 1e3, "-", label="polyester table")
bx.plot(e * 100, EA * e / 1e3, "--", label="linear EA = 14 MBL")
bx.set_xlabel("strain [%]")
bx.set_ylabel("tension [kN]")
bx.legend(fontsize=8)
fig.tight_layout()

root = brentq(lambda b: b * math.tan(b) - rho_a * L / M, 1e-9, 1.5)


def closed(ea_t: float) -> float:
    return root / (2 * math.pi * L) * math.sqrt(ea_t / rho_a)


for name, path, tangents in (
    ("polyester table", str(poly), [MBL * ALPHA + BETA * t for t in (W, W + w * L)]),
    ("linear EA = 14 MBL", linear, [EA]),
):
    run = run_modes(load_scenario(path))
    k = run.system.body_slice("weight")
    bounce = int(np.argmax([abs(m[k][1]) / np.linalg.norm(m[k]) for m in run.result.modes]))
    forms = ", ".join(f"EA_t = {t / 1e6:.2f} MN: {closed(t):.4f} Hz" for t in tangents)
    print(
        f"{name}: bounce {run.result.frequencies_hz[bounce]:.4f} Hz; rod with a tip mass, {forms}"
    )
