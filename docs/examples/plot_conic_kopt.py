"""
Conic arcs and the optimal mapping factor Kopt
==============================================

A conic arc from its chord, two end-tangent angles and one interior point; as a rational cubic
with mapping factor K its parametrization speed ``|r_ξ|`` varies along the arc, least at Kopt
(the gradient ratio, max over min of ``|r_ξ|``, closest to 1). The paper's example 1 arc.
"""

import matplotlib.pyplot as plt
import numpy as np

import rancf

arc = rancf.conic_arc(0.5, [30, 40], [0.315, 0.077])
k_opt = rancf.kopt(arc)
print(f"{arc.kind}, omega = {arc.omega:.5f}, Kopt = {k_opt:.4f}")

# %%
# The arc, and the speed ``|r_ξ|`` of its cubic form for three values of K.
xi = np.linspace(0.0, 1.0, 201)
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
pts = arc.cubic(k_opt)(xi)
ax.plot(pts[:, 0], pts[:, 1], "k")
ax.set_aspect("equal")
ax.set_title("the arc")
for k in (0.2, k_opt, 0.6):
    cubic = arc.cubic(k)
    speed = np.linalg.norm(cubic.derivatives(xi, 1)[1], axis=1)
    label = f"K = {k:.4f}{' (Kopt)' if k == k_opt else ''}: ratio {rancf.gradient_ratio(cubic):.3f}"
    bx.plot(xi, speed, label=label)
bx.set_xlabel("ξ")
bx.set_ylabel("|r_ξ| [m]")
bx.legend(fontsize=8)
fig.tight_layout()
