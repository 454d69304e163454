"""
Power line by sag
=================

The shipped ``power-line-sag.toml``: a 200 m conductor span (1.628 kg/m, EA = 3.23e7 N) strung
to a 5 m sag. The file gives the sag (``[form] sag = 5.0``), as a line engineer does; rancf
finds the unstretched length that meets it in statics and uses it for every analysis. The
profile agrees with the elastic catenary of that length (Irvine's equations).
"""

from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf import load_scenario
from rancf.runs.static import run_static
from rancf.solvers.catenary import catenary

sc = load_scenario(files("rancf.examples") / "power-line-sag.toml")
run = run_static(sc)  # finds the length first ([form]), then solves the span with it
length = run.form["unstretched_length"]
print(run.form_lines[0])

system = run.system
body = system.bodies["body"]
q = body.q_from_y(run.result.y[system.body_slice("body")]).reshape(body.n_nodes, body.dpn)
x, z = q[:, 0], q[:, 2]
h_fe = -run.outputs.static_reactions(run.result.y, run.result.lam)[0].force[0]

# %%
# The elastic catenary of the same unstretched length (engineering strain; rancf's cable uses
# the Green-Lagrange strain, a difference of the order of the strain squared).
w, ea = 1.628 * 9.81, 3.23e7
cat = catenary(200.0, 0.0, length, w, ea)
xc, zc = cat.points(np.linspace(0.0, length, 401))
print(f"sag {-z.min():.4f} m; horizontal tension {h_fe:.1f} N (elastic catenary {cat.h:.1f} N)")

fig, (ax, bx) = plt.subplots(2, 1, figsize=(8, 5), sharex=True)
ax.plot(xc, zc, "k-", lw=1, label="elastic catenary")
ax.plot(x, z, "o", ms=3, label="rancf, 40 elements")
ax.set_ylabel("z [m]")
ax.legend()
bx.plot(x, (z - np.interp(x, xc, zc)) * 1e3, "o-", ms=3)
bx.set_xlabel("x [m]")
bx.set_ylabel("rancf - catenary [mm]")
fig.tight_layout()
