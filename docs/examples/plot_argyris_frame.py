"""
Argyris frame: lateral-torsional buckling of a jointed frame
============================================================

The shipped ``argyris-frame.toml``: two 0.24 m aluminium strips (30 mm wide in the frame's
plane, 0.6 mm thick), the first clamped at the origin, joined at the corner by a ``fixed``
joint, a 1.088 N force along +x at the free end. ``rancf buckling`` finds the load at which it
buckles sideways (Argyris et al. 1979: 1.088 N); ``rancf modes --about static`` shows the first
frequency falling to zero as the load approaches it.
"""

from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

import rancf
from rancf.solvers.buckling import linear_buckling
from rancf.solvers.static import solve_static
from rancf.studies.common import load_example

path = files("rancf.examples") / "argyris-frame.toml"
system = rancf.load_scenario(path).build_system()
res = linear_buckling(system, 1)
print(f"critical load: {1.088 * res.load_factors[0]:.4f} N")

# %%
# The first two frequencies about the static state, against the load: the first falls to zero
# at the critical load; beyond it the squared frequency is negative (a growth rate).
shares = np.linspace(0.0, 1.1, 12)
first, second, growth = [], [], []
for share in shares:
    d = load_example("argyris-frame")
    d["loads"]["point"][0]["force"] = [share * 1.088, 0.0, 0.0]
    s = rancf.parse_scenario(d, str(path)).build_system()
    st = solve_static(s, 4)
    m = rancf.natural_modes(s, st.y, 2, st.lam)
    first.append(m.frequencies_hz[0])
    second.append(m.frequencies_hz[1])
    growth.append(m.growth_rates[0])
fig, ax = plt.subplots(figsize=(6, 3.5))
ax.plot(shares * 1.088, first, "o-", label="mode 1 [Hz]")
ax.plot(shares * 1.088, second, "s-", label="mode 2 [Hz]")
ax.plot(shares * 1.088, growth, "^--", label="growth rate of mode 1 [1/s]")
ax.axvline(1.088 * res.load_factors[0], color="k", lw=0.8, label="buckling load")
ax.set_xlabel("tip force [N]")
ax.legend(fontsize=8)
fig.tight_layout()
