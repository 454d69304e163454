"""Seabed friction in statics (``[solver] static_friction``) against MoorPy.

Reference numbers: MoorPy 1.3.0, ``moorpy.Catenary.catenary`` (a separate venv, not a
dependency): ``catenary(447, 100, 500, EA=1.2326e9, W=2456.820077, CB=CB)`` gives at the anchor
``fAH`` and at the fairlead ``(fBH, fBV)``:

* ``CB = 0``: 124397.503 N; (124397.503, 348493.392) N;
* ``CB = 0.1``: 36503.262 N; (124488.514, 348557.515) N (``L_B`` = 358.13 m);
* ``CB = 0.5``: 0 N (friction beyond ``H``: the tension is zero at the anchor);
  (124618.889, 348649.352) N.

The shipped example ``mooring-line`` (3D, in seawater, 330 m, ``w`` = 2456.819 N/m, EA =
1.23259e9 N, anchor 300 m from the fairlead and 100 m below it, its seabed's friction 0.3):
``catenary(300, 100, 330, EA=3.36376e10 * 0.036643536711471, W=2456.818868731118, CB=0.3)``
gives ``fAH = 454105.944`` N and ``(fBH, fBV) = (527762.642, 565227.899)`` N (``CB = 0``:
``fAH = 527645.423`` N).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rancf.errors import ScenarioError
from rancf.scenario.scenario import load_scenario
from rancf.solvers.static import solve_static
from rancf.solvers.static_friction import FrictionEquilibrium, seabed_friction
from tests.solvers.test_static_checks import CHAIN_LINE

#: MoorPy's (anchor H, fairlead H, fairlead V) by CB (module docstring).
MOORPY = {
    0.0: (124397.50300587031, 124397.50300587031, 348493.39177853917),
    0.1: (36503.262145810775, 124488.5144646459, 348557.51531164884),
    0.5: (0.0, 124618.8886302105, 348649.3518853202),
}
#: A 500 m chain (w = 2456.82 N/m, EA = 1.2326e9 N), anchor pinned on the seabed, the fairlead
#: installed 447 m away and 100 m up; drawn straight on the seabed.
CHAIN = (
    """
[geometry]
kind = "line"
start = [-447.0, -100.0]
end = [53.0, -100.0]

[mesh]
elements = 100
"""
    + CHAIN_LINE
    + """
[[obstacles]]
name = "seabed"
kind = "plane"
point = [0.0, -100.10806535367585]
normal = [0.0, 1.0]
stiffness = 1.0e6
friction = {cb}

[loads]
gravity = [0.0, -9.81]
{solver}"""
)


def _ends(tmp_path, cb: float, solver: str = "[solver]\nstatic_friction = true\n"):
    """(anchor force, fairlead force) [N] at the static equilibrium: the supports' reactions
    (the held rows of the balance with the friction load)."""
    path = tmp_path / "chain.toml"
    path.write_text(CHAIN.format(cb=cb, solver=solver))
    sc = load_scenario(path)
    system = sc.build_system()
    res = solve_static(system, **sc.static_options())
    load = seabed_friction(system, res.y) if sc.solver.static_friction else np.zeros(system.n)
    problem = FrictionEquilibrium(system, None, load)
    problem.stage = len(problem.stages) - 1
    r = problem.full_residual(np.r_[res.y, res.lam], float(res.load_factors[-1]))
    model = system.bodies["body"]
    end = (model.n_nodes - 1) * model.dpn
    return r[0:2], r[end : end + 2]


@pytest.mark.parametrize("cb", [0.1, 0.5])
def test_anchor_and_fairlead_forces_match_moorpy(tmp_path, cb):
    anchor, fairlead = _ends(tmp_path, cb)
    ha, hb, vb = MOORPY[cb]
    assert math.hypot(*fairlead) == pytest.approx(math.hypot(hb, vb), rel=5e-3)
    assert fairlead[0] == pytest.approx(hb, rel=5e-3)
    # the anchor's horizontal force: MoorPy's within 0.5 % of the line's tension H
    assert abs(-anchor[0] - ha) < 5e-3 * hb


def test_friction_is_off_by_default(tmp_path):
    """Without the option the seabed's friction does not act in statics: the anchor holds the
    whole horizontal tension (MoorPy's CB = 0), far from MoorPy's CB = 0.1."""
    anchor, fairlead = _ends(tmp_path, 0.1, solver="")
    ha0, hb0, _ = MOORPY[0.0]
    assert -anchor[0] == pytest.approx(ha0, rel=5e-3)
    assert fairlead[0] == pytest.approx(hb0, rel=5e-3)
    assert abs(-anchor[0] - MOORPY[0.1][0]) > 0.5 * MOORPY[0.1][1]


def test_frictionless_seabed_is_unchanged(tmp_path):
    """``friction = 0``: the option changes nothing."""
    on = _ends(tmp_path, 0.0)
    off = _ends(tmp_path, 0.0, solver="")
    np.testing.assert_allclose(np.r_[on], np.r_[off], rtol=0, atol=1e-6)


def test_option_is_a_flag(tmp_path):
    path = tmp_path / "chain.toml"
    path.write_text(CHAIN.format(cb=0.1, solver='[solver]\nstatic_friction = "yes"\n'))
    with pytest.raises(ScenarioError, match="static_friction"):
        load_scenario(path)


def test_run_reactions_and_contact_count_the_friction(tmp_path):
    """``rancf static``'s reactions and the seabed's friction output: the anchor holds what the
    friction leaves (MoorPy's within 0.5 % of H), and the supports balance the friction."""
    from rancf.post.static_run import reactions_json
    from rancf.runs.static import run_static

    path = tmp_path / "chain.toml"
    path.write_text(CHAIN.format(cb=0.1, solver="[solver]\nstatic_friction = true\n"))
    sc = load_scenario(path)
    run = run_static(sc, folder=tmp_path / "out")
    assert run.result.method.endswith("+friction")
    anchor, fairlead = (
        np.array(r["force"]) for r in reactions_json(run.outputs, run.result.y, run.result.lam)
    )
    ha, hb, _ = MOORPY[0.1]
    assert abs(-anchor[0] - ha) < 5e-3 * hb
    rows = np.genfromtxt(tmp_path / "out" / "reactions.csv", delimiter=",", names=True)
    assert rows.size == 1  # the path's frictionless states are not kept
    assert float(rows["seabed_friction_x"]) < -0.5 * MOORPY[0.0][0]
    total = rows["start_fx"] + rows["end_fx"] + rows["seabed_friction_x"]
    assert abs(float(total)) < 1e-6 * hb


def test_example_mooring_line_in_3d_matches_moorpy(tmp_path):
    """The shipped 3D example in seawater with its seabed's friction 0.3 (module docstring)."""
    from importlib.resources import files

    from rancf.post.static_run import reactions_json
    from rancf.runs.static import run_static

    text = (files("rancf.examples") / "mooring-line.toml").read_text()
    path = tmp_path / "mooring-line.toml"
    path.write_text(text.replace("[solver]", "[solver]\nstatic_friction = true", 1))
    run = run_static(load_scenario(path))
    anchor, fairlead = (
        np.array(r["force"]) for r in reactions_json(run.outputs, run.result.y, run.result.lam)
    )
    hb, vb = 527762.6421923696, 565227.8989316114
    assert abs(-anchor[0] - 454105.9438674723) < 5e-3 * hb
    assert fairlead[0] == pytest.approx(hb, rel=5e-3)
    assert fairlead[2] == pytest.approx(vb, rel=5e-3)
