"""``[fluid]``, ``[hydro]``, ``[bodies.hydro]`` and ``[[loads.distributed]]`` (docs/guide/fluid.md):
the keys as written reach the system (one-body and multibody files alike), and bad values are
refused in one line naming the key."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from rancf.errors import ScenarioError
from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.scenario.scenario import parse_scenario
from rancf.system.fluid import Fluid, Hydro, Waves

LINE = {
    "geometry": {"kind": "line", "start": [0.0, 0.0, -10.0], "end": [2.0, 0.0, 0.0]},
    "mesh": {"elements": 3},
    "section": {"radius": 0.01},
    "material": {"density": 2000.0, "youngs_modulus": 1e9},
}
ONE = {**LINE, "supports": [{"at": "start"}], "loads": {"gravity": [0.0, 0.0, -9.81]}}
FLUID = {
    "density": 1025.0,
    "surface": 0.0,
    "current_profile": [[-10.0, 0.2, 0.0, 0.0], [0.0, 1.0, 0.1, 0.0]],
    "waves": {"height": 2.0, "period": 8.0, "direction_deg": 30.0, "depth": 50.0},
}
HYDRO = {
    "diameter": 0.03,
    "drag_normal": 1.2,
    "drag_axial": 0.1,
    "added_mass_normal": 1.0,
    "added_mass_axial": 0.2,
}


def _with(base: dict, **tables) -> dict:
    d = copy.deepcopy(base)
    d.update(copy.deepcopy(tables))
    return d


def test_one_body_keys_reach_the_system():
    d = _with(ONE, fluid=FLUID, hydro=HYDRO)
    d["loads"]["distributed"] = [{"force": [0.0, 5.0, 0.0], "time": {"ramp": 2.0}}]
    s = parse_scenario(d).build_system()
    assert s.fluid == Fluid(
        1025.0,
        0.0,
        None,
        ((-10.0, 0.2, 0.0, 0.0), (0.0, 1.0, 0.1, 0.0)),
        Waves(2.0, 8.0, 30.0, 50.0),
    )
    assert s.hydro == {"body": Hydro(0.03, 1.2, 0.1, 1.0, 0.2)}
    # the fluid and the load act: the residual differs from the same body without them
    bare = parse_scenario(ONE).build_system()
    r, r0 = np.empty(s.n + s.m), np.empty(s.n + s.m)
    static = ResidualOptions(1.0, dynamic=False)
    s.core.residual(ResidualPoint(s.y0, np.zeros(s.m), r), static)
    bare.core.residual(ResidualPoint(s.y0, np.zeros(s.m), r0), static)
    assert np.abs(r - r0).max() > 1.0


def test_bodies_hydro_per_body_and_distributed_on_one_body():
    d = {
        "bodies": [{"name": "a", **LINE, "hydro": HYDRO}, {"name": "b", **LINE}],
        "supports": [{"at": "a:start"}, {"at": "b:start"}],
        "loads": {
            "gravity": [0.0, 0.0, -9.81],
            "distributed": [{"force": [1.0, 0.0, 0.0], "body": "b"}],
        },
        "fluid": {"density": 1.225, "current": [3.0, 0.0, 0.0]},
    }
    s = parse_scenario(d).build_system()
    assert set(s.hydro) == {"a"}
    f = np.asarray(s.core.fluid_forces(s.y0, np.zeros(s.n), np.zeros(s.n), 0.0, False))
    assert np.abs(f[:3]).max() > 0 and np.abs(f[3:]).max() == 0  # b feels only its load


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"fluid": {"density": -1.0}}, "[fluid.density] must be > 0, got -1.0"),
        (
            {"fluid": {"density": 1025.0, "current_profile": [[0.0, 1, 0, 0], [-1.0, 0, 0, 0]]}},
            "[fluid.current_profile] heights must increase, got [0.0, -1.0]",
        ),
        (
            {"fluid": {"density": 1025.0, "waves": {"height": 1, "period": 5, "depth": 20}}},
            "[fluid.waves] need a free surface (give fluid.surface)",
        ),
        (
            {"fluid": {"density": 1025.0, "current": [1.0, 0.0]}},
            "[fluid.current] must be a list of 3 numbers, got [1.0, 0.0]",
        ),
        (
            {"fluid": {"density": 1025.0, "current": [1.0, 0.0, 0.0], "current_profile": [[0, 1]]}},
            "[fluid.current_profile] give current or current_profile, not both",
        ),
        (
            {"fluid": {"density": 1025.0}, "hydro": {"drag_normal": -1.0}},
            "[hydro.drag_normal] must be >= 0, got -1.0",
        ),
        ({"fluid": {"density": 1025.0}, "hydro": {"drag": 1.0}}, "[hydro.drag] unknown key"),
        ({"hydro": {"drag_normal": 1.0}}, "[hydro] coefficients of bodies in a fluid"),
        (
            {"loads": {"distributed": [{"force": [1.0, 0.0]}]}},
            "[loads.distributed[0].force] 3 components (got [1.0, 0.0])",
        ),
        (
            {"loads": {"distributed": [{"force": [1.0, 0.0, 0.0], "body": "x"}]}},
            "[loads.distributed[0].body] a flexible body (one of ['body']) (got 'x')",
        ),
        (
            {"loads": {"distributed": [{"force": [1.0, 0.0, 0.0], "time": [1.0, 2.0]}]}},
            "[loads.distributed[0].time] must be a scalar time function",
        ),
    ],
)
def test_bad_values_are_refused_in_one_line(change, message):
    """One line naming the key, the value and what is allowed."""
    with pytest.raises(ScenarioError) as err:
        parse_scenario(_with(ONE, **change)).build_system()
    text = str(err.value)
    assert "\n" not in text
    assert message in text, text


def test_beam_elements_are_refused_in_a_fluid():
    d = _with(ONE, fluid={"density": 1025.0}, hydro=HYDRO)
    d["geometry"] = {"kind": "line", "start": [0.0, -10.0], "end": [2.0, 0.0]}
    d["mesh"] = {"elements": 3, "element": "beam"}
    d["loads"] = {"gravity": [0.0, -9.81]}
    with pytest.raises(ScenarioError, match=r"\[hydro\] a body of cable or rod elements"):
        parse_scenario(d).build_system()
