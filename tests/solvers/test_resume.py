"""A run stopped anywhere and taken up again from its state (:class:`DynamicState`, through a
file) takes the same steps as a run that never stopped: its outputs continue the first part's
and end in the same state to 1e-12, for a pendulum, a mechanism with joints (modified Newton:
the compiled loop's factors are rebuilt), a rope with friction over a capstan and a rod (whose
nodal triads go along)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

import rancf.examples
from rancf.errors import InputError
from rancf.scenario import parse_scenario
from rancf.scenario.system_build import build_system
from rancf.solvers import dynamic
from rancf.solvers.dynamic import integrate
from rancf.solvers.start import start_state
from rancf.solvers.state import DynamicState

EXAMPLES = Path(rancf.examples.__file__).parent
RTOL = 1e-12

CASES = [
    ("planar-pendulum", {"t_end": 0.3}),
    ("slider-crank", {"t_end": 0.01}),
    ("capstan", {"t_end": 0.06}),
    ("planar-pendulum", {"t_end": 0.3, "adaptive": True}),
    ("rod", {"t_end": 0.03}),
    ("stiff-line", {"t_end": 0.03}),
]

#: A pinned line of 192 stiff elements falling from the horizontal: its first steps start again
#: from the last state, and the steps after them start there at once (docs/derivations/newton.md),
#: a count the state carries.
STIFF = {
    "geometry": {"kind": "line", "start": [0, 0], "end": [1.2, 0]},
    "mesh": {"elements": 192, "element": "ancf"},
    "section": {"radius": 0.02},
    "material": {"density": 6000.0, "youngs_modulus": 2e11},
    "supports": [{"at": "start", "kind": "pin"}],
    "loads": {"gravity": [0, -9.81]},
    "solver": {"t_end": 0.03, "step": 1e-3, "output_step": 5e-3, "rho_inf": 0.9},
}

#: A clamped spatial rod swinging down under gravity (its nodal triads are carried along).
ROD = {
    "geometry": {"kind": "line", "start": [0, 0, 0], "end": [1, 0.2, 0.1]},
    "mesh": {"elements": 4, "element": "rod"},
    "section": {"radius": 0.02},
    "material": {"density": 7800.0, "youngs_modulus": 2e9, "poisson_ratio": 0.3},
    "supports": [{"at": "start", "kind": "clamp"}],
    "loads": {"gravity": [0, 0, -9.81]},
    "solver": {"t_end": 0.03, "step": 1e-3, "output_step": 2e-3},
}


def _scenario(name: str, **solver: object):
    if name in ("rod", "stiff-line"):
        raw = ROD if name == "rod" else STIFF
        return parse_scenario({**raw, "solver": {**raw["solver"], **solver}})
    path = EXAMPLES / f"{name}.toml"
    raw = tomllib.loads(path.read_text(encoding="utf-8"))
    raw["solver"].update(solver)
    return parse_scenario(raw, str(path))


def _close(a: np.ndarray, b: np.ndarray) -> float:
    """Largest difference relative to the largest entry."""
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def _run(sc, options=None, stop_at: float | None = None, start=None):
    system = build_system(sc)
    y0 = None
    if start is None:
        y0, _ = start_state(sc, system)
    seen = {"t": 0.0, "polls": 0}

    def on_output(t, snapshot):
        seen["t"] = t

    def should_stop() -> bool:  # a few steps after the output at stop_at: between outputs
        if stop_at is not None and seen["t"] >= stop_at:
            seen["polls"] += 1
        return seen["polls"] > 3

    o = options or sc.dynamic_options()
    return integrate(system, o, on_output, should_stop, initial=y0, start=start)


@pytest.mark.parametrize(("name", "solver"), CASES, ids=[f"{n}-{len(s)}" for n, s in CASES])
def test_stopped_and_resumed_is_one_run(name, solver, tmp_path, monkeypatch):
    # the compiled loop hands back after every step: the stop falls between output times
    monkeypatch.setattr(dynamic, "CALL_SECONDS", 0.0)
    sc = _scenario(name, **solver)
    whole = _run(sc)
    assert whole.status.value == "completed"
    half = 0.5 * sc.solver.t_end
    first = _run(sc, stop_at=half)
    assert first.status.value == "interrupted" and first.t[-1] < sc.solver.t_end
    assert first.state.t > first.t[-1]  # stopped between output times
    first.state.save(tmp_path / "state.npz")
    state = DynamicState.load(tmp_path / "state.npz")
    second = _run(sc, start=state)  # a new system, as in a new process
    assert second.status.value == "completed"
    t = np.concatenate([first.t, second.t])
    np.testing.assert_array_equal(t, whole.t)
    for key in ("q", "v"):
        both = np.concatenate([getattr(first, key), getattr(second, key)])
        assert _close(both, getattr(whole, key)) <= RTOL, key
    assert _close(second.state.a, whole.state.a) <= RTOL
    assert second.n_steps == whole.n_steps and second.n_outputs == whole.n_outputs
    if name == "stiff-line":  # stopped among the steps that start from the last state
        assert 0 < state.memory[0] <= 8
    if sc.solver.newton == "modified":
        assert state.memory.size > 0  # the factors' point went along
        assert second.n_factorizations == whole.n_factorizations


def test_a_finished_run_extended_to_a_later_end():
    sc = _scenario("slider-crank", t_end=0.01)
    longer = _scenario("slider-crank", t_end=0.02)
    whole = _run(longer)
    first = _run(sc)
    second = _run(longer, start=first.state)
    assert second.t[0] > first.t[-1] == 0.01
    assert _close(second.q, whole.q[-second.t.size :]) <= RTOL
    assert _close(second.state.lam, whole.state.lam) <= RTOL


def test_a_state_of_another_system_is_refused(tmp_path):
    first = _run(_scenario("planar-pendulum", t_end=0.01))
    other = _scenario("slider-crank", t_end=0.01)
    with pytest.raises(InputError, match="a state of this system"):
        _run(other, start=first.state)
    (tmp_path / "bad.npz").write_text("not a state")
    with pytest.raises(InputError, match="bad.npz"):
        DynamicState.load(tmp_path / "bad.npz")


def test_resumed_from_any_output_counts_as_one_run(monkeypatch):
    # compiled calls of many outputs, and steps too hard for 3 iterations: calls end at failed
    # steps after storing outputs, where a snapshot (a checkpoint) may be taken
    monkeypatch.setattr(dynamic, "CALL_TARGET_SECONDS", 10.0)
    sc = _scenario("stiff-line", max_newton=3, output_step=1e-3, t_end=0.05)
    states = []

    def run(start=None):
        system = build_system(sc)
        y0 = None if start is not None else start_state(sc, system)[0]
        snap = None if start is not None else lambda t, s: states.append(s().state)
        return integrate(system, sc.dynamic_options(), snap, lambda: False, y0, start=start)

    whole = run()
    assert whole.n_rejected > 10 and len(states) > 10
    counts = {(whole.n_newton, whole.n_rejected, whole.n_steps)}
    for state in states[:-1]:
        again = run(start=state)
        counts.add((again.n_newton, again.n_rejected, again.n_steps))
        assert _close(again.state.y, whole.state.y) <= RTOL
    assert counts == {(whole.n_newton, whole.n_rejected, whole.n_steps)}
