"""The shipped example ``belt-drive`` through ``rancf simulate`` (issue 20): a closed belt over
two pulleys carried by rigid bodies, the left one driven, the right one braked by a torque rising
past the most the belt can transmit.  Euler-Eytelwein: while the belt slips the span tensions'
ratio is e^(mu pi) = 2.5663 and the transmitted torque R_c (T_tight - T_slack) is
M_max = R_c F0 (e^(mu pi) - 1) / (e^(mu pi) + 1) = 0.89597 N m, both within 2 %; below M_max the
braked pulley follows the driver.  The spans' tensions are the section values (axial force) of
the belt's samples that lie in the middle fifth of each span at that time (the belt moves: a
fixed node travels around it)."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.section_outputs import SectionSampler
from rancf.cli import main
from rancf.scenario import load_scenario
from rancf.studies.common import example_path

RC, F0, MU = 0.102, 20.0, 0.3
RATIO = np.exp(MU * np.pi)
M_MAX = RC * F0 * (RATIO - 1) / (RATIO + 1)


def test_belt_drive_euler_eytelwein(tmp_path):
    """Measured: slipping from t = 3.4 s on, ratio 2.5660 .. 2.5688 and torque 0.8936 .. 0.8976
    N m (the spans' vibrations: 0.3 %)."""
    assert M_MAX == pytest.approx(0.89597, rel=1e-5) and RATIO == pytest.approx(2.5663, abs=1e-4)
    path = example_path("belt-drive")
    assert main(["simulate", str(path), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    s = load_scenario(path).build_system()
    z = np.load(tmp_path / "run" / "results.npz")
    t, q, v = z["t"], z["q"], z["v"]
    belt = s.bodies["belt"]
    sampler = SectionSampler(belt, 4)
    tight, slack = [], []
    for row in q:
        y = s.y_from_q(row)[s.body_slice("belt")]
        force, pos = sampler.values(y)[:, 1], sampler.positions(y)
        mid = (pos[:, 0] > 0.2) & (pos[:, 0] < 0.3)
        tight.append(force[mid & (pos[:, 1] > 0)].mean())  # the top span (the driver pulls it)
        slack.append(force[mid & (pos[:, 1] < 0)].mean())
    tight, slack = np.array(tight), np.array(slack)
    w_a = v[:, s.body_slice("driver")][:, 2]
    w_b = v[:, s.body_slice("driven")][:, 2]
    brake = 1.2 * M_MAX * np.clip((t - 0.6) / 3.0, 0.0, 1.0)
    follows = (t > 0.6) & (brake < 0.8 * M_MAX)
    assert np.all(w_b[follows] > 0.97 * w_a[follows])  # below M_max: it follows
    assert np.all(tight[follows] + slack[follows] == pytest.approx(F0, rel=0.05))
    slips = t >= 3.4
    assert np.all(w_b[slips] < 0.5 * w_a[slips]) and w_b[-1] < 0  # above it: it slips
    assert np.all(tight[slips] / slack[slips] == pytest.approx(RATIO, rel=0.02))
    torque = RC * (tight[slips] - slack[slips])
    assert np.all(torque == pytest.approx(M_MAX, rel=0.02))
    assert np.mean(torque) == pytest.approx(M_MAX, rel=0.01)
    assert np.max(RC * (tight - slack)) < 1.02 * M_MAX  # it never transmits more
