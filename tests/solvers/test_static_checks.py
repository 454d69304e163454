"""Static results that are no equilibrium are refused: folded elements, compressive
loops of a cable, deep penetration; lines on a seabed against MoorPy's elastic catenary.

Reference numbers: MoorPy 1.3.0, ``moorpy.Catenary.catenary`` (a separate venv, not a
dependency), ``CB = 0``:

* U line, half of it from the seabed's midpoint to one end: ``catenary(50, 20, 65, EA=1e8,
  W=100)`` gives ``H = 263.1579634`` N (grounded 42.52 m of the half);
* 500 m chain: ``catenary(400, 200, 500, EA=1.2326e9, W=2456.820077)`` gives
  ``H = 295264.0633`` N, ``V = 728878.5005`` N at the fairlead.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import rancf
from rancf.errors import ConvergenceError
from rancf.scenario.scenario import load_scenario
from rancf.solvers.sag_start import SAG_START
from rancf.solvers.static import solve_equilibrium, solve_static
from rancf.solvers.static_catenary import catenary_shape
from rancf.solvers.static_checks import instability, most_compressed, static_state_problems
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system.seabed import SEABED_PENETRATION

H_U = 263.1579634329022
H_CHAIN, V_CHAIN = 295264.063277252, 728878.5005232067
#: 100 N/m over a section of radius 0.05 m, EA = 1e8 N, EI = 12.7 N m² (negligible).
U_LINE = """
[section]
area = 7.853981633974483e-3
inertia = 1.0e-9

[material]
density = 1297.8996378543961
youngs_modulus = 1.2732395447351627e10
axial_strain = "engineering"

[[supports]]
at = "start"
kind = "pin"

[[obstacles]]
name = "seabed"
kind = "plane"
point = [0.0, -20.05]
normal = [0.0, 1.0]
{stiffness}

[loads]
gravity = [0.0, -9.81]
{fluid}"""
#: A U of 130 m lying on the seabed (20 m below both ends, 100 m apart).
U_ON_SEABED = """
[geometry]
kind = "nurbs"
degree = 2
knots = [0.0, 0.0, 0.0, 0.1617063163084801, 0.8382936836915199, 1.0, 1.0, 1.0]
control_points = [[0.0, 0.0], [0.0, -20.0], [50.0, -20.0], [100.0, -20.0], [100.0, 0.0]]

[mesh]
elements = 40

[[supports]]
at = "end"
kind = "pin"
"""
#: A U of 130 m flared past both ends, 0.5 m above the seabed: it falls into a loop.
U_FLARED = """
[geometry]
kind = "nurbs"
degree = 2
knots = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]
control_points = [[0.0, 0.0], [-15.58252989878443, -19.5], [115.58252989878443, -19.5],
                  [100.0, 0.0]]

[mesh]
elements = 40

[[supports]]
at = "end"
kind = "pin"
"""
#: A straight stress-free 130 m line, its end installed 100 m from its start.
U_INSTALLED = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [130.0, 0.0]

[mesh]
elements = 40

[[supports]]
at = "end"
kind = "pin"
position = [100.0, 0.0]
"""
#: The chain of benchmarks/mooring in 2D (2456.8 N/m wet, EA = 1.2326e9 N): its section,
#: material and supports, the end installed at the fairlead (0, 0).
CHAIN_LINE = """
[section]
area = 0.03668789808917197
inertia = 1.0e-7

[material]
density = 6826.239384497652
youngs_modulus = 33596909722.222225
axial_strain = "engineering"

[[supports]]
at = "start"
kind = "pin"

[[supports]]
at = "end"
kind = "pin"
position = [0.0, 0.0]
"""
#: That chain 500 m straight on the seabed, its end installed at the fairlead 447.2 m from the
#: anchor.
CHAIN = (
    """
[geometry]
kind = "line"
start = [-400.0, -200.0]
end = [100.0, -200.0]

[mesh]
elements = 50
"""
    + CHAIN_LINE
    + """
[[obstacles]]
name = "seabed"
kind = "plane"
point = [0.0, -200.10806535367585]
normal = [0.0, 1.0]
stiffness = 1.0e6

[loads]
gravity = [0.0, -9.81]
"""
)


def _scenario(tmp_path, text: str):
    path = tmp_path / "line.toml"
    path.write_text(text)
    return load_scenario(path)


def _u(tmp_path, shape: str, stiffness: str = "stiffness = 1.0e6"):
    """The U line; without a stiffness in water (no hydro coefficients: its weight is the
    100 N/m), so that the seabed default applies."""
    fluid = "" if stiffness else "[fluid]\ndensity = 1025.0\n"
    return _scenario(tmp_path, shape + U_LINE.format(stiffness=stiffness, fluid=fluid))


def _horizontal(system, res) -> float:
    from rancf.system.outputs import SystemOutputs

    return abs(SystemOutputs(system, []).static_reactions(res.y, res.lam)[-1].force[0])


@pytest.mark.parametrize("stiffness", ["stiffness = 1.0e6", ""])
def test_u_line_on_seabed_matches_moorpy(tmp_path, stiffness):
    """Given stiffness 1e6 and the seabed default: H within 0.5 % of MoorPy's."""
    sc = _u(tmp_path, U_ON_SEABED, stiffness)
    system = sc.build_system()
    res = solve_static(system, **sc.static_options())
    assert _horizontal(system, res) == pytest.approx(H_U, rel=5e-3)
    assert static_state_problems(system, res.q) == []


def test_installed_chain_matches_moorpy(tmp_path):
    sc = _scenario(tmp_path, CHAIN)
    system = sc.build_system()
    res = solve_static(system, **sc.static_options())
    from rancf.system.outputs import SystemOutputs

    force = SystemOutputs(system, []).static_reactions(res.y, res.lam)[-1].force
    assert abs(force[0]) == pytest.approx(H_CHAIN, rel=5e-3)
    assert abs(force[1]) == pytest.approx(V_CHAIN, rel=5e-3)


def _refined(shape: str, n: int) -> str:
    return shape.replace("elements = 40", f"elements = {n}")


@pytest.mark.parametrize(
    "shape, stiffness",
    [(U_FLARED, ""), (_refined(U_INSTALLED, 160), ""), (_refined(U_INSTALLED, 160), None)],
    ids=["flared", "installed", "installed-stiff"],
)
def test_slack_line_finds_moorpy_equilibrium(tmp_path, shape, stiffness):
    """The line drawn as a flared U or straight and installed (its end 100 m from its start)
    rests as MoorPy's U: H within 0.5 %.  The installed line: the load path ends folded (the old
    solver refused it, exit 3); the sagged start shape (rancf.solvers.sag_start) finds it.  160
    elements: the touchdown bends with radius H / w = 2.6 m, which a straight 40-element mesh
    (3.25 m elements) cannot follow (H 1 % low at 80 elements, refused at 40)."""
    sc = _u(tmp_path, shape, "stiffness = 1.0e6" if stiffness is None else stiffness)
    system = sc.build_system()
    res = solve_static(system, **sc.static_options())
    tol = 5e-3 if stiffness == "" else 6e-3  # 1e6 N/m²: -0.53 % (the penalty's sinking)
    assert _horizontal(system, res) == pytest.approx(H_U, rel=tol)
    assert static_state_problems(system, res.q) == []
    if shape != U_FLARED:
        assert res.method == SAG_START


def test_installed_chain_default_stiffness_matches_moorpy(tmp_path):
    """The chain dry with the default stiffness (E / 10: no fluid, no seabed default): the load
    path ran away (the old solver: exit 3); from the sagged start H and V within 0.5 %."""
    sc = _scenario(tmp_path, CHAIN.replace("stiffness = 1.0e6\n", ""))
    system = sc.build_system()
    res = solve_static(system, **sc.static_options())
    from rancf.system.outputs import SystemOutputs

    force = SystemOutputs(system, []).static_reactions(res.y, res.lam)[-1].force
    assert res.method == SAG_START
    assert abs(force[0]) == pytest.approx(H_CHAIN, rel=5e-3)
    assert abs(force[1]) == pytest.approx(V_CHAIN, rel=5e-3)


@pytest.mark.parametrize("shape", [U_FLARED, U_INSTALLED], ids=["flared", "installed"])
def test_coarse_touchdown_is_refused(tmp_path, shape):
    """40 elements on a 1e6 N/m² seabed: neither the load path nor the sagged start gives a
    state without a compressive loop or fold at the touchdown (elements longer than its bend
    radius): refused, not reported (the old solver before the checks: a loop carrying kN to
    1e7 N of compression, exit 0)."""
    sc = _u(tmp_path, shape)
    with pytest.raises(ConvergenceError, match="compressive loop|is folded"):
        solve_static(sc.build_system(), **sc.static_options())


def test_sag_start_shape_is_moorpy_catenary():
    """The grounded start shape of the U (ends 20 m above the bed, 100 m apart, 130 m): its
    horizontal tension per weight a = H / w is MoorPy's 263.158 / 100 (inextensible), the
    touchdown tangent to the bed and both ends reached."""
    s = np.linspace(0.0, 130.0, 1301)
    pts, tan = catenary_shape(100.0, 0.0, 130.0, s, floor=-20.0)
    assert pts[0] == pytest.approx([0.0, 0.0], abs=1e-9)
    assert pts[-1] == pytest.approx([100.0, 0.0], abs=1e-9)
    assert np.linalg.norm(np.diff(pts, axis=0), axis=1).sum() == pytest.approx(130.0, rel=1e-5)
    # the catenary z = a (cosh(x/a) - 1) from the touchdown: a from the end's slope and height
    bed = pts[:, 1] <= -20.0 + 1e-9
    a = 20.0 / (1.0 / tan[-1, 0] - 1.0)  # h = a (cosh u - 1), cosh u = 1 / t_x
    assert a == pytest.approx(H_U / 100.0, rel=2e-3)
    assert pts[:, 1].min() == pytest.approx(-20.0) and np.all(tan[bed, 1] == 0.0)
    assert bed.sum() * 0.1 == pytest.approx(130.0 - 2 * np.sqrt(400.0 + 40.0 * a), abs=0.2)
    free, _ = catenary_shape(100.0, 10.0, 130.0, np.array([0.0, 130.0]))
    assert free[1] == pytest.approx([100.0, 10.0], abs=1e-9)


def _cli_static(tmp_path, text: str) -> subprocess.CompletedProcess:
    (tmp_path / "u.toml").write_text(text)
    src = str(Path(rancf.__file__).resolve().parents[1])
    return subprocess.run(
        [sys.executable, "-m", "rancf", "static", "u.toml", "--json"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": src},
    )


def test_coarse_touchdown_is_solved_on_a_refined_mesh_with_a_warning(tmp_path):
    """``rancf static`` of the straight 40-element line installed as a U on a 1e6 N/m² seabed
    (the solver alone refuses it, test_coarse_touchdown_is_refused): the static run refines the
    line to 320 elements, says so in one warning line, and gives MoorPy's H (the penalty's
    sinking and the line's EI: -0.26 %)."""
    import json

    p = _cli_static(tmp_path, U_INSTALLED + U_LINE.format(stiffness="stiffness = 1.0e6", fluid=""))
    assert p.returncode == 0, p.stderr
    assert p.stderr.count("warning") == 1 and "40 elements refined to 320" in p.stderr
    out = json.loads(p.stdout)
    assert abs(out["reactions"][-1]["force"][0]) == pytest.approx(H_U, rel=4e-3)
    assert len(out["positions"]["body"]) == 321


def test_refused_state_exits_3_in_one_line(tmp_path):
    """The same line with a sensor at node 20: the static run does not refine a mesh whose
    nodes the scenario names by index, and the state is refused: exit 3, one line."""
    sensor = '[[sensors]]\nname = "mid"\nkind = "position"\nat = 20\n'
    text = U_INSTALLED + U_LINE.format(stiffness="stiffness = 1.0e6", fluid="") + sensor
    p = _cli_static(tmp_path, text)
    assert p.returncode == 3
    lines = [x for x in p.stderr.splitlines() if "no equilibrium" in x]
    assert len(lines) == 1 and "no equilibrium" in lines[0]


def test_folded_element_is_named(tmp_path):
    """A state with one node pushed back past its neighbour: folded, and compressed."""
    sc = _u(tmp_path, U_INSTALLED)
    system = sc.build_system()
    q = system.q_from_y(system.y_from_q(system.q0)).copy() if hasattr(system, "q0") else None
    q = system.q_from_y(system.y0.copy()) if q is None else q
    model, sl = system.flex[0], system.body_slice(system.names[0])
    nodes = q[sl].reshape(model.n_nodes, model.dpn)
    nodes[20, 0] -= 2.0 * (nodes[21, 0] - nodes[20, 0])  # node 20 behind node 19
    q[sl] = nodes.ravel()
    problems = static_state_problems(system, q)
    assert any("folded" in p for p in problems), problems


def test_deep_penetration_is_named(tmp_path):
    """The U's reference 2 m inside a raised seabed."""
    text = _u(tmp_path, U_ON_SEABED)  # noqa: F841 (builds the file)
    raised = (U_ON_SEABED + U_LINE.format(stiffness="stiffness = 1.0e6", fluid="")).replace(
        "point = [0.0, -20.05]", "point = [0.0, -18.0]"
    )
    system = _scenario(tmp_path, raised).build_system()
    q = system.q_from_y(system.y0.copy())
    problems = static_state_problems(system, q)
    assert any("penetrated" in p and "seabed" in p for p in problems), problems


def test_seabed_default_stiffness_formula(tmp_path):
    """k = w_n / (0.01 D) on a seabed; E / 10 where the weight does not press on it."""
    sc = _u(tmp_path, U_ON_SEABED, "")
    system = sc.build_system()
    w, d = 100.0, 0.1
    k = system.contact_data_stiffness if hasattr(system, "contact_data_stiffness") else None
    from rancf.system.seabed import seabed_stiffness

    ob = system.obstacles[0]
    got = seabed_stiffness(system, "body", ob, np.array([0.0, 1.0, 0.0]))
    assert got == pytest.approx(w / (SEABED_PENETRATION * d), rel=1e-6) and k is None
    assert seabed_stiffness(system, "body", ob, np.array([0.0, -1.0, 0.0])) is None  # a ceiling


def test_a_sagged_start_run_folder_holds_its_solve_only(tmp_path):
    """``rancf static`` of the installed line: the run folder is the sagged start's solve (one
    step), not the abandoned load path, whose folded states would warn of a 44 % strain."""
    import json

    from rancf.cli import main

    water = "[fluid]\ndensity = 1025.0\n"
    text = _refined(U_INSTALLED, 160) + U_LINE.format(stiffness="", fluid=water)
    (tmp_path / "s.toml").write_text(text)
    assert main(["static", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r")]) == 0
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["method"] == SAG_START and summary["warnings"] == []
    assert len((tmp_path / "r" / "sensors.csv").read_text().splitlines()) == 2


def test_a_line_passing_through_itself_is_found():
    from types import SimpleNamespace

    from rancf.solvers.static_checks import self_crossing

    model = SimpleNamespace(section=SimpleNamespace(radius=0.1), mesh=SimpleNamespace(closed=False))
    t = np.linspace(0.0, 1.0, 200)
    assert self_crossing(model, np.c_[10.0 * t, 0.0 * t], 10.0 * t) == ""
    th = np.linspace(-0.3, 2.0 * np.pi + 0.3, 400)  # a loop of radius 2 m drawn along x
    loop = np.c_[2.0 * np.sin(th) + 0.1 * th, 2.0 - 2.0 * np.cos(th)]
    s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(loop, axis=0), axis=1))]
    assert "passes through itself" in self_crossing(model, loop, s)
    # a hairpin whose arms stay two radii apart (touching, not passing through) is no crossing
    arm = np.linspace(0.0, 5.0, 100)
    bend = (
        0.1 * np.c_[np.sin(np.linspace(0.0, np.pi, 40)), 1.0 - np.cos(np.linspace(0.0, np.pi, 40))]
    )
    hairpin = np.r_[np.c_[-arm[::-1], 0.0 * arm], bend[1:-1], np.c_[-arm, 0.2 + 0.0 * arm]]
    s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(hairpin, axis=0), axis=1))]
    assert self_crossing(model, hairpin, s) == ""
    # a cantilever rolled into a full circle: its end meets its root, and touches it
    th = np.linspace(0.0, 2.0 * np.pi, 120)
    assert self_crossing(model, np.c_[np.sin(th), 1.0 - np.cos(th)], th) == ""


MOORING_3D = """
[geometry]
kind = "conic"
start = [-300.0, 0.0, -100.0]
end = [0.0, 0.0, 0.0]
angles_deg = [18.43494882292201, 71.56505117707799]
point = [-96.55665347288583, 0.0, -67.81444884237139]
[mesh]
elements = {n}
quadrature_points = 5
[section]
area = 0.03668789808917197
inertia = 1.0e-7
[material]
density = 7850.0
youngs_modulus = 33596909722.222225
axial_strain = "engineering"
[fluid]
density = 1025.0
[hydro]
diameter = 0.216
[[supports]]
at = "start"
kind = "pin"
[[supports]]
at = "end"
kind = "pin"
[[obstacles]]
name = "seabed"
kind = "plane"
point = [0.0, 0.0, -100.10806535367585]
normal = [0.0, 0.0, 1.0]
stiffness = 648000.0
[loads]
gravity = [0.0, 0.0, -9.81]
"""


def test_a_looped_mooring_line_is_not_an_equilibrium(tmp_path):
    # the 330 m chain of benchmarks/mooring/mooring-surge-3d.toml at 15 elements: the sagged
    # start settled into a loop near the anchor (16.6 % strain, 66 MN at the fairlead); refused,
    # the load path finds the line on the seabed: 751 kN, 2.8 % under the 40-element 773 kN
    from rancf.system.outputs import SystemOutputs

    tension = {}
    for n in (15, 40):
        path = tmp_path / f"line{n}.toml"
        path.write_text(MOORING_3D.format(n=n))
        sc = load_scenario(path)
        system = sc.build_system()
        res = solve_static(system, **sc.static_options())
        assert static_state_problems(system, res.q) == []
        tip = system.y_from_q(res.q)[system.body_slice(system.names[0])]
        assert np.all(np.diff(tip.reshape(-1, 6)[:, 0]) > 0.0)  # x grows along the line: no loop
        ends = SystemOutputs(system, []).static_reactions(res.y, res.lam)
        tension[n] = float(np.linalg.norm(ends[1].force))
    assert abs(tension[15] / tension[40] - 1.0) < 0.05, tension


def test_sag_start_shape_on_a_sloped_seabed_is_moorpy_catenary():
    """MoorPy's sloped line (anchor on a 10° slope, fairlead 60 m on and 40 m up, 80 m long):
    straight on the slope from the anchor, then the catenary tangent to it with MoorPy's
    ``a = H / w = 13.0987`` m; the same line seen from its other end (the slope falling) is its
    mirror image."""
    import math

    slope = math.tan(math.radians(10.0))
    s = np.linspace(0.0, 80.0, 8001)
    pts, tan = catenary_shape(60.0, 40.0, 80.0, s, floor=0.0, slope=slope)
    assert pts[0] == pytest.approx([0.0, 0.0], abs=1e-9)
    assert pts[-1] == pytest.approx([60.0, 40.0], abs=1e-9)
    assert np.linalg.norm(np.diff(pts, axis=0), axis=1).sum() == pytest.approx(80.0, rel=1e-6)
    assert np.all(pts[:, 1] >= pts[:, 0] * slope - 1e-9)  # nowhere below the seabed
    on = np.abs(pts[:, 1] - pts[:, 0] * slope) < 1e-9
    lift = np.flatnonzero(on)[-1]  # the touchdown: the tangent along the slope
    assert tan[lift, 1] / tan[lift, 0] == pytest.approx(slope, rel=1e-6)
    h = 1309.865537260965 / 100.0  # MoorPy's fairlead H over w
    # the catenary's a from the tangent angles at the touchdown and the fairlead
    u_t, u_f = math.asinh(slope), math.asinh(tan[-1, 1] / tan[-1, 0])
    assert (pts[-1, 0] - pts[lift, 0]) / (u_f - u_t) == pytest.approx(h, rel=1e-3)
    down, _ = catenary_shape(60.0, -40.0, 80.0, s, floor=-40.0 + 60.0 * slope, slope=-slope)
    assert np.abs(down[::-1] - np.c_[60.0 - pts[:, 0], pts[:, 1] - 40.0]).max() < 1e-9


def test_a_chain_without_rest_curvature_starts_resting_and_converges_at_160_elements(tmp_path):
    """The 330 m chain on 160 elements with ``stress_free = "straight"``: its sagged start lies
    on the seabed at the depth its wet weight presses it to (its contact stiffness acting from
    the start: at the onset of contact, with no tension yet, Newton's first steps moved it by
    kilometres), and Newton alone converges from there."""
    from rancf.solvers.sag_start import sag_state
    from rancf.solvers.system_equilibrium import SystemEquilibrium
    from rancf.system.seabed import pressing_weight

    path = tmp_path / "chain.toml"
    text = MOORING_3D.format(n=160).replace("[mesh]\n", '[mesh]\nstress_free = "straight"\n')
    path.write_text(text)
    sc = load_scenario(path)
    system = sc.build_system()
    z = sag_state(SystemEquilibrium(system), True)
    assert z is not None
    x = system.q_from_y(z[: system.n]).reshape(-1, 6)
    w = pressing_weight(system, "body", np.array([0.0, 0.0, 1.0]))
    radius = system.flex[0].section.radius
    sink = w / 648000.0 + 0.5e-3 * radius  # the penalty's sinking w/k + d/2, d = 1e-3 r
    assert x[1, 2] == pytest.approx(-100.10806535367585 + radius - sink, abs=1e-9)
    res = solve_static(system, **sc.static_options())
    assert res.method == SAG_START and res.relaxation_steps == 0 and res.n_newton <= 15


def test_a_failed_solve_of_a_curved_spatial_cable_names_its_kink(tmp_path, monkeypatch):
    """A static solve that fails on a spatial cable unloaded as drawn curved (the chain as a
    conic, ``stress_free = "reference"``) names the kink of its bending energy where it lies
    straight, and what to set; the same chain with ``stress_free = "straight"`` has no such
    line."""
    import rancf.solvers.static as static

    def fail(*args, **kwargs):
        raise ConvergenceError("static equilibrium not found: stopped", 0.0)

    monkeypatch.setattr(static, "_sagged", lambda *args, **kwargs: None)
    monkeypatch.setattr(static, "solve_equilibrium", fail)
    for straight in (False, True):
        text = MOORING_3D.format(n=8)
        state = "straight" if straight else "reference"
        text = text.replace("[mesh]\n", f'[mesh]\nstress_free = "{state}"\n')
        path = tmp_path / "chain.toml"
        path.write_text(text)
        with pytest.raises(ConvergenceError) as err:
            solve_static(load_scenario(path).build_system())
        kink = "has a kink where it lies straight" in str(err.value)
        assert kink != straight and str(err.value).startswith("static equilibrium not found")
        assert ('stress_free = "straight"' in str(err.value)) != straight


#: MoorPy 1.3's force of the 330 m chain on its fairlead [N] (``python
#: benchmarks/mooring/moorpy_statics.py`` in an environment with MoorPy: its exact elastic
#: catenary with 99.96 m on a frictionless seabed).
MOORPY_CHAIN_FAIRLEAD = (-527645.5065459731, 0.0, -565177.2291925576)


@pytest.mark.parametrize("n", [40, 80, 160])
def test_a_spatial_chain_drawn_curved_is_unloaded_straight_and_meets_moorpy(tmp_path, n):
    """The 330 m chain drawn as a conic in space, with the default ``stress_free = "auto"``:
    its rest curvature's moment (EI max κ0 = 164 N m) is far below its weight's (w L²/8 =
    3.9e7 N m), so it is unloaded straight, with a note, and Newton from the sagged start
    converges at 40, 80 and 160 elements (unloaded as drawn, 160 elements failed) to MoorPy's
    fairlead force within 0.5 %."""
    from rancf.post.checks import element_notes
    from rancf.system.outputs import SystemOutputs

    path = tmp_path / "chain.toml"
    path.write_text(MOORING_3D.format(n=n))
    sc = load_scenario(path)
    system = sc.build_system()
    assert system.flex[0].stress_free == "straight"
    (note,) = element_notes(system)
    assert 'unloaded straight (mesh.stress_free = "auto")' in note
    res = solve_static(system, **sc.static_options())
    assert res.method == SAG_START and res.relaxation_steps == 0
    force = -SystemOutputs(system, []).static_reactions(res.y, res.lam)[1].force
    ref = np.array(MOORPY_CHAIN_FAIRLEAD)
    assert np.linalg.norm(force - ref) / np.linalg.norm(ref) < 0.005


def test_auto_keeps_the_curved_reference_where_its_moment_counts():
    """``stress_free = "auto"`` keeps the drawn shape unloaded for a spatial cable whose rest
    curvature's moment is not negligible against its weight's (a steel wire bent to a 0.5 m
    radius), for one without gravity, and for a planar one; the chain's rule, checked on the
    moments: EI max κ0 against 1e-3 w L²/8."""
    from rancf.bodies.stress_free import REST_MOMENT_SHARE
    from rancf.geometry.conic import conic_arc_through
    from rancf.mesh.factories import mesh_conic

    def wire(dim, gravity, inertia=7.85e-9):
        c = 0.5 * np.sqrt(0.5)
        ends = [[0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [c, c, 0.0]]  # a quarter circle, radius 0.5
        arc = conic_arc_through(*(p[:dim] for p in ends[:2]), [45.0, 45.0], ends[2][:dim])
        mesh = mesh_conic(arc, 4)
        sec = rancf.Section(3.14e-4, inertia)
        return rancf.Model(mesh, "rancf", sec, rancf.Material(7850.0, 2e11), gravity=gravity)

    g3 = [0.0, 0.0, -9.81]
    assert wire(3, g3).stress_free == "reference"  # EI κ0 = 3140 N m against 2.4 N m
    assert wire(3, None).stress_free == "reference"
    assert wire(2, [0.0, -9.81]).stress_free == "reference"
    # a wire whose EI max κ0 is just under / over 1e-3 of its weight's moment
    weight = 7850.0 * 3.14e-4 * 9.81 * (0.25 * np.pi) ** 2 / 8.0
    limit = REST_MOMENT_SHARE * weight / (2e11 * 2.0)  # the inertia at the share, κ0 = 2 / m
    assert wire(3, g3, 0.99 * limit).stress_free == "straight"
    assert wire(3, g3, 1.01 * limit).stress_free == "reference"


#: A 1 m column (EI = 0.0785 N m², EA = 3142 N) clamped at its start, pushed along its axis at
#: its free end: its Euler load π² EI / (4 L²) is 0.194 N.
COLUMN = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [1.0, 0.0]

[mesh]
elements = 8

[section]
radius = 0.01

[material]
density = 1200.0
youngs_modulus = 1.0e7

[[supports]]
at = "start"
kind = "clamp"

[[loads.point]]
at = "end"
force = [{push}, 0.0]
"""


def test_a_column_past_its_euler_load_exits_3_naming_the_instability(tmp_path):
    """Pushed by 1 N (5 times its Euler load, a quarter of its elements' own), the straight
    column converges and passes the per-element compression check, but its tangent has a
    negative eigenvalue: refused, exit 3, one line naming it and the compression."""
    p = _cli_static(tmp_path, COLUMN.format(push=-1.0))
    assert p.returncode == 3, p.stdout
    lines = [x for x in p.stderr.splitlines() if "unstable equilibrium" in x]
    assert len(lines) == 1 and "1 negative eigenvalue" in lines[0]
    assert "compression 1 N in element" in lines[0] and "arc_length" in lines[0]


def test_a_column_below_its_euler_load_is_an_equilibrium(tmp_path):
    """Pushed by 0.1 N (half its Euler load) the straight column is a stable equilibrium."""
    (tmp_path / "c.toml").write_text(COLUMN.format(push=-0.1))
    system = load_scenario(tmp_path / "c.toml").build_system()
    res = solve_static(system)
    assert instability(system, res.y, res.lam) == ""
    assert np.abs(res.y[1::4]).max() < 1e-9  # straight: no transverse displacement


def test_a_compressed_straight_hose_is_unstable_and_its_buckled_state_is_found(tmp_path):
    """The installed hose under a 1e-3 m/s² gravity: its load path ends straight, compressed by
    452 N (20 %) between its clamps; that state is found unstable and the buckled one
    (compression near the clamped Euler load 4 π² EI / L² = 3.1 N, sagging by 0.27 m) is
    returned instead."""
    text = (Path(rancf.__file__).parent / "examples" / "installed-hose.toml").read_text()
    (tmp_path / "h.toml").write_text(text.replace("-9.81", "-1.0e-3"))
    system = load_scenario(tmp_path / "h.toml").build_system()
    path = solve_equilibrium(SystemEquilibrium(system), 10)
    assert most_compressed(system, path.q)[2] > 400.0  # straight and crushed
    why = instability(system, path.y, path.lam)
    assert why.startswith("unstable equilibrium") and "negative eigenvalue" in why
    res = solve_static(system)
    q = res.q.reshape(-1, 4)
    assert q[:, 1].min() < -0.2
    assert 3.1 < most_compressed(system, res.q)[2] < 5.0


def test_an_unstable_end_of_an_arc_length_path_is_kept_with_a_warning(tmp_path, capsys):
    """The column pushed by 1 N along an arc-length path (which passes unstable states on
    purpose) stays straight: the end state is returned, with one warning line naming it, which
    ``rancf static`` prints as its other warnings (no Python warning) and keeps in its
    summary."""
    from rancf.cli import main

    text = COLUMN.format(push=-1.0) + '\n[solver]\nstatic_method = "arc_length"\n'
    (tmp_path / "c.toml").write_text(text)
    sc = load_scenario(tmp_path / "c.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no Python warning
        res = solve_static(sc.build_system(), **sc.static_options())
    assert res.method == "arc_length" and res.load_factors[-1] == pytest.approx(1.0)
    (line,) = res.warnings
    assert line.startswith("the arc-length path ends in an unstable equilibrium")
    for out in ([], ["--out", str(tmp_path / "r")]):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert main(["static", str(tmp_path / "c.toml"), *out]) == 0
        err = capsys.readouterr().err.splitlines()
        assert err == [f"rancf: warning: {line}"], err
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["warnings"] == [line]
