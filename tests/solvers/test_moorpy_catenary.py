"""MoorPy's catenary test suite (``tests/test_catenary.py`` of NREL/MoorPy) through ``rancf
static``: the end forces within 0.5 % of the fairlead tension, from the default start, with
the default seabed stiffness.

Inputs and expected values are copies (:mod:`tests.solvers.moorpy_catenary_cases`).  MoorPy's
"near-taut (hardest one)" expected values do not balance the line's weight (``fAV + fBV = 0``
for a line of 1113 N): there the reference is the exact elastic catenary (engineering strain),
which MoorPy's own tolerance-1e-5 value misses by 1.9 % of the tension.
"""

from __future__ import annotations

import numpy as np
import pytest

from rancf.runs.static import StaticRun, run_static
from rancf.scenario.scenario import load_scenario
from rancf.solvers.static import solve_static
from rancf.solvers.static_checks import static_state_problems
from tests.solvers.moorpy_catenary_cases import (
    CASES,
    Case,
    grounded_elastica,
    scenario_text,
    section_ei,
    suspended_catenary,
)

#: Forces within this fraction of the fairlead tension.
TOL = 5e-3


def expected(case: Case) -> np.ndarray:
    """MoorPy's forces; the exact elastic catenary where MoorPy's do not balance the weight."""
    if case.name == "near-taut":
        return np.array(suspended_catenary(case, (-case.expected[2], -case.expected[3])))
    return np.array(case.expected)


def solved_forces(tmp_path, case: Case, elements: int) -> tuple[np.ndarray, str]:
    """``(fAH, fAV, fBH, fBV)`` of the line on its supports (MoorPy's signs) and the method, as
    ``rancf static`` solves the case (:func:`rancf.runs.static.run_static`: the mesh refined
    where a touchdown needs it)."""
    run = _run(tmp_path, case, elements)
    assert static_state_problems(run.system, run.result.q) == []
    ends = run.outputs.static_reactions(run.result.y, run.result.lam)
    return -np.r_[ends[0].force[:2], ends[-1].force[:2]], run.result.method


def _run(tmp_path, case: Case, elements: int) -> StaticRun:
    path = tmp_path / f"{case.name}.toml"
    path.write_text(scenario_text(case, elements))
    return run_static(load_scenario(path))


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_moorpy_case_at_40_elements(tmp_path, case):
    got, _ = solved_forces(tmp_path, case, 40)
    want = expected(case)
    tension = np.hypot(*want[2:])
    assert np.abs(got - want).max() <= TOL * tension, (got, want)


def test_suspended_references_agree_with_moorpy():
    """The exact catenary agrees with MoorPy's expected values to 1e-5 of the tension for every
    suspended case but the hardest near-taut one (1.9 %: MoorPy's expected value)."""
    for case in CASES[3:10]:
        want = np.array(case.expected)
        exact = np.array(suspended_catenary(case, (-want[2], -want[3])))
        off = np.abs(exact - want).max() / np.hypot(*want[2:])
        assert (off > 1e-2) if case.name == "near-taut" else (off < 1e-5), (case.name, off)


@pytest.mark.parametrize("name", ["seabed-cb5", "u-shape", "u-half"])
def test_moorpy_touchdown_at_160_elements(tmp_path, name):
    """Lines on the seabed at 160 elements, from the catenary start shape."""
    case = next(c for c in CASES if c.name == name)
    got, method = solved_forces(tmp_path, case, 160)
    want = expected(case)
    assert np.abs(got - want).max() <= TOL * np.hypot(*want[2:]), (got, want)
    assert method.startswith("sag start+newton")


def test_the_stiff_u_converges_by_newton_through_its_axial_stiffness(tmp_path):
    """The full U (EA = 1e12 N, 4e9 times its tension at the touchdowns) at 320 elements (its
    touchdowns resolved: no refinement): from its sagged start Newton converges with the line's
    EA continued from 1e4 times its weight (no relaxation; about 200 iterations at its own EA
    alone), to the U's half's forces at 160 elements (the same element length) within 1e-5 of
    the tension, and the model keeps its own EA."""
    u, half = (next(c for c in CASES if c.name == n) for n in ("u-shape", "u-half"))
    run = _run(tmp_path, u, 320)
    assert run.notes == [] and run.system.flex[0].n_el == 320
    assert run.result.method == "sag start+newton" and run.result.relaxation_steps == 0
    assert run.result.n_newton <= 80, run.result.n_newton
    assert run.system.flex[0].core.axial_stiffness == u.ea
    ends = run.outputs.static_reactions(run.result.y, run.result.lam)
    got = -np.r_[ends[-1].force[:2]]
    want, _ = solved_forces(tmp_path, half, 160)
    assert np.abs(got - want[2:]).max() <= 1e-5 * np.hypot(*want[2:]), (got, want)


def test_the_axial_stiffness_is_restored_when_a_solve_fails(tmp_path, monkeypatch):
    """A continuation interrupted by an error in a Newton solve leaves every line's EA as it
    was."""
    import rancf.solvers.axial_continuation as ac
    from rancf.solvers.system_equilibrium import SystemEquilibrium

    case = next(c for c in CASES if c.name == "u-half")
    path = tmp_path / "u.toml"
    path.write_text(scenario_text(case, 40))
    system = load_scenario(path).build_system()
    problem = SystemEquilibrium(system)
    lines = ac.stiff_lines(system, system.names, problem.start())
    assert len(lines) == 1 and lines[0][1] == case.ea

    def fail(*args, **kwargs):
        assert system.flex[0].core.axial_stiffness == pytest.approx(ac.START_RATIO * lines[0][2])
        raise RuntimeError("stop")

    monkeypatch.setattr(ac, "newton", fail)
    with pytest.raises(RuntimeError, match="stop"):
        ac.continued_newton(problem, problem.start(), 1.0, 1e-10, lines)
    assert system.flex[0].core.axial_stiffness == case.ea


def test_moorpy_friction_holding_the_whole_tension_at_80_elements(tmp_path):
    """CB = 5: the friction on the grounded length takes the whole tension (MoorPy: no force on
    the anchor), also at 80 elements."""
    case = next(c for c in CASES if c.name == "seabed-cb5")
    got, method = solved_forces(tmp_path, case, 80)
    want = expected(case)
    assert np.abs(got - want).max() <= TOL * np.hypot(*want[2:]), (got, want)
    assert method == "sag start+newton+friction"


def test_an_unresolved_touchdown_is_refused_not_reported(tmp_path):
    """The full U at 40 elements solved on its own mesh (the static solver, as a time-domain
    run's static start uses it): its stiff line (EA = 1e12) cannot bend within one 3.25 m
    element where it meets the seabed; no state is reported (a state it settles into there is
    refused by the touchdown check, its fairlead force 4.5 times too small), and the failure
    names the start shape's bend radius ``H / w`` and the element's length."""
    from rancf.errors import ConvergenceError

    case = next(c for c in CASES if c.name == "u-shape")
    path = tmp_path / "u.toml"
    path.write_text(scenario_text(case, 40))
    sc = load_scenario(path)
    with pytest.raises(
        ConvergenceError,
        match=r"radius (T/w = .* shorter than its element \(3.25 m\): the touchdown is not "
        r"resolved|H/w = 2.63 m, shorter than its 3.25 m elements there)",
    ):
        solve_static(sc.build_system(), **sc.static_options())


def test_the_static_run_refines_an_unresolved_touchdown_and_says_so(tmp_path):
    """``rancf static`` of the full U at 40 elements: the sagged start's touchdown bends with
    the radius ``H / w = 2.63`` m; the body is solved with 320 elements (0.41 m, under a sixth
    of it), one warning line naming it; the U's half at 160 elements is left as it is."""
    u, half = (next(c for c in CASES if c.name == n) for n in ("u-shape", "u-half"))
    run = _run(tmp_path, u, 40)
    assert run.system.flex[0].n_el == 320
    assert len(run.notes) == 1
    assert "40 elements refined to 320" in run.notes[0] and "T/w = 2.63 m" in run.notes[0]
    run = _run(tmp_path, half, 160)
    assert run.system.flex[0].n_el == 160 and run.notes == []


def test_the_u_converges_to_the_heavy_elastica_of_its_bending_stiffness(tmp_path):
    """The U's half at 160 and 320 elements against the exact inextensible heavy elastica with
    the scenario's own EI (127 N m², on a rigid seabed): H and V within 1e-4 of the fairlead
    tension, while that elastica's H is 2 % below MoorPy's (EI = 0): the rest of the error
    against MoorPy is the line's bending stiffness, not the discretization."""
    case = next(c for c in CASES if c.name == "u-half")
    h, v = grounded_elastica(case, section_ei(case), nodes=501)
    assert abs(h - case.expected[0]) > 1e-2 * case.expected[0]
    for n in (160, 320):
        got, _ = solved_forces(tmp_path, case, n)
        assert abs(-got[2] - h) < 1e-4 * v and abs(-got[3] - v) < 1e-4 * v, (n, got, h, v)


def test_a_touchdown_found_unresolved_after_the_solve_is_solved_again_refined(
    tmp_path, monkeypatch
):
    """Without the start shape's radius (a line the sagged start does not know), the U's half
    at 40 elements is solved, its solved touchdown (``T / w`` about 2.2 m at 1.6 m elements)
    asks for 320 elements (under a sixth of it), and the run is solved again on them: one
    warning line, the forces within 0.5 %."""
    import rancf.runs.static_mesh as static_mesh

    monkeypatch.setattr(static_mesh, "start_ratios", lambda system: {})
    case = next(c for c in CASES if c.name == "u-half")
    run = _run(tmp_path, case, 40)
    assert run.system.flex[0].n_el == 320 and len(run.notes) == 1, run.notes
    ends = run.outputs.static_reactions(run.result.y, run.result.lam)
    got = -np.r_[ends[0].force[:2], ends[-1].force[:2]]
    want = expected(case)
    assert np.abs(got - want).max() <= TOL * np.hypot(*want[2:]), (got, want)


def test_a_mesh_named_by_node_index_is_kept_with_a_warning(tmp_path):
    """The U's half at 40 elements with a sensor at node 20: the static run keeps the mesh (its
    nodes would move) and says that its elements do not resolve the touchdown."""
    case = next(c for c in CASES if c.name == "u-half")
    path = tmp_path / "u.toml"
    sensor = '[[sensors]]\nname = "mid"\nkind = "position"\nat = 20\n'
    path.write_text(scenario_text(case, 40) + sensor)
    run = run_static(load_scenario(path))
    assert run.system.flex[0].n_el == 40 and len(run.notes) == 1, run.notes
    assert "do not resolve" in run.notes[0] and "keeps its 40 elements" in run.notes[0]


@pytest.mark.parametrize("name", ["sloped-up", "sloped-down"])
def test_a_line_anchored_on_a_sloped_seabed_starts_on_its_sloped_catenary(tmp_path, name):
    """MoorPy's sloped pair: the sagged start lies on the sloped seabed from the grounded end and
    lifts off tangent to it (MoorPy's shape), from which Newton alone converges (no
    relaxation) to forces within 0.5 %."""
    case = next(c for c in CASES if c.name == name)
    run = _run(tmp_path, case, 40)
    assert run.result.method == "sag start+newton" and run.result.relaxation_steps == 0
    ends = run.outputs.static_reactions(run.result.y, run.result.lam)
    got = -np.r_[ends[0].force[:2], ends[-1].force[:2]]
    want = expected(case)
    assert np.abs(got - want).max() <= TOL * np.hypot(*want[2:]), (got, want)


def test_a_run_from_its_static_state_refines_the_touchdown_as_the_static_run(tmp_path):
    """``initial_state = "static"`` on the full U at 40 elements: the run is planned, solved and
    integrated on the 320 elements ``rancf static`` solves it on, with the same warning line
    (naming the static start and the run) in its warnings and its ``mesh_refinement``."""
    from rancf.runs.simulate import run_simulate

    case = next(c for c in CASES if c.name == "u-shape")
    path = tmp_path / "u.toml"
    solver = '\n[solver]\ninitial_state = "static"\nt_end = 0.01\nstep = 0.01\n'
    path.write_text(scenario_text(case, 40) + solver)
    run = run_simulate(load_scenario(path))
    assert run.system.flex[0].n_el == 320
    lines = [w for w in run.warnings if "refined to 320" in w]
    assert len(lines) == 1 and "for the static start and the run" in lines[0]
    assert run.start["mesh_refinement"] == lines
    assert run.result.status.value == "completed"


@pytest.mark.parametrize("elements", [10, 160])
def test_buoyant_line_arches_up_and_solves_by_newton(tmp_path, elements):
    """A line lighter than the water it displaces (buoyancy from its ``[hydro]`` diameter in a
    ``[fluid]``) starts from the upturned catenary and converges by Newton from it (no
    relaxation) within 0.5 % of MoorPy; 10 elements, longer than the crest's bend radius
    H/w = 7.3 m, are refined to 20 with a note saying so."""
    case = next(c for c in CASES if c.name == "buoyant")
    run = _run(tmp_path, case, elements)
    assert run.result.method == "sag start+newton" and run.result.relaxation_steps == 0
    assert run.system.flex[0].n_el == max(elements, 20)
    assert (len(run.notes) == 1 and "H/w = 7.3" in str(run.notes[0])) == (elements == 10)
    ends = run.outputs.static_reactions(run.result.y, run.result.lam)
    got = -np.r_[ends[0].force[:2], ends[-1].force[:2]]
    want = expected(case)
    assert np.abs(got - want).max() <= TOL * np.hypot(*want[2:]), (got, want)
    crest = run.result.q.reshape(-1, run.system.flex[0].dpn)[:, 1].max()
    assert crest > 50.0  # arched up above both ends (20.5 m), not hanging below them
