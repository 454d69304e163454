"""
Belt drive
==========

The shipped ``belt-drive.toml``: a closed belt (a ring) over two pulleys of radius 0.1 m carried
by rigid bodies; the left one is driven at 2 rad/s, the right one slides on a guide, pushed out
by 20 N, and is braked by a torque rising past the most the belt can transmit,
R_c F0 (e^(mu pi) - 1) / (e^(mu pi) + 1) = 0.896 N m. The belt's material points travel around
it, so the spans' tensions are read where the belt is, from the stored states.
"""

import tempfile
from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from rancf.bodies.section_outputs import SectionSampler
from rancf.cli import main
from rancf.scenario import load_scenario

scenario = files("rancf.examples") / "belt-drive.toml"
out = f"{tempfile.mkdtemp()}/run"
main(["simulate", str(scenario), "--out", out, "--quiet"])
system = load_scenario(str(scenario)).build_system()
z = np.load(f"{out}/results.npz")
t, q, v = z["t"], z["q"], z["v"]
sampler = SectionSampler(system.bodies["belt"], 4)
tight, slack = [], []
for row in q:
    y = system.y_from_q(row)[system.body_slice("belt")]
    force, pos = sampler.values(y)[:, 1], sampler.positions(y)
    mid = (pos[:, 0] > 0.2) & (pos[:, 0] < 0.3)
    tight.append(force[mid & (pos[:, 1] > 0)].mean())
    slack.append(force[mid & (pos[:, 1] < 0)].mean())
tight, slack = np.array(tight), np.array(slack)
slips = t >= 3.4
print(
    f"while slipping: tight/slack {np.mean(tight[slips] / slack[slips]):.4f} "
    f"(e^(0.3 pi) = {np.exp(0.3 * np.pi):.4f}), torque "
    f"{np.mean(0.102 * (tight[slips] - slack[slips])):.4f} N m (0.8960)"
)

# %%
# The torque the belt transmits follows the brake until it reaches the limit; then the belt
# slips, the braked pulley is spun backwards, and the spans keep the ratio e^(mu pi).
brake = 1.2 * 0.895967546524253 * np.clip((t - 0.6) / 3.0, 0.0, 1.0)
w_a = v[:, system.body_slice("driver")][:, 2]
w_b = v[:, system.body_slice("driven")][:, 2]
fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 3.5))
ax.plot(t, 0.102 * (tight - slack), label="transmitted R_c (T_tight - T_slack)")
ax.plot(t, brake, ls="--", label="brake torque")
ax.set_xlabel("t [s]")
ax.set_ylabel("torque [N m]")
ax.legend(fontsize=8)
bx.plot(t, w_a, label="driver")
bx.plot(t, w_b, label="braked pulley")
bx.set_ylim(-5.0, 3.0)
bx.set_xlabel("t [s]")
bx.set_ylabel("angular velocity [rad/s]")
bx.legend(fontsize=8)
fig.tight_layout()
