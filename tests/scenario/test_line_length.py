"""A line's unstretched ``length`` (``[geometry] kind = "line"``): slack or taut between its held
ends, in one-body files and in ``[[bodies]]``.

Reference: MoorPy 1.3.0 (a separate venv, not a dependency), ``System(depth=30, g=9.80665)``,
one line of 100 m from the anchor at (-90, 0, -30) to the fairlead at (0, 0, 0), in seawater
(1025 kg/m³), of the 50 mm studless chain of MoorPy's ``MoorProps`` (its "Orcaflex-original"
rules: 19.9e3 d² = 49.75 kg/m, EA = 0.854e11 d² = 2.135e8 N, volume-equivalent diameter 1.8 d
= 0.09 m), ``solveEquilibrium()``: fairlead tension 34359.35 N (H 21642.98 N, V 26686.07 N),
37.05 m on the seabed.
"""

from __future__ import annotations

import math

import pytest

from rancf.errors import ScenarioError
from rancf.runs.static import run_static
from rancf.scenario.scenario import Scenario, parse_scenario

T_MOORPY = 34359.35
D_VOL = 0.09
AREA = math.pi * D_VOL**2 / 4
MASS = 49.75
EA = 2.135e8

#: The chain's tables, one-body form (``{geometry}``: the geometry table's keys).
CHAIN = {
    "mesh": {"elements": 40},
    "section": {"area": AREA, "inertia": 1.0e-9},
    "material": {"density": MASS / AREA, "youngs_modulus": EA / AREA},
    "hydro": {"diameter": D_VOL},
}
WORLD = {
    "fluid": {"density": 1025.0, "surface": 0.0},
    "loads": {"gravity": [0.0, 0.0, -9.80665]},
}
LINE = {"kind": "line", "start": [-90.0, 0.0, -30.0], "end": [0.0, 0.0, 0.0], "length": 100.0}


def _seabed(depth: float) -> list[dict]:
    return [{"name": "seabed", "kind": "plane", "point": [0.0, 0.0, depth], "normal": [0, 0, 1]}]


def _one_body(depth: float) -> Scenario:
    return parse_scenario(
        {
            "geometry": LINE,
            **CHAIN,
            **WORLD,
            "obstacles": _seabed(depth),
            "supports": [{"at": "start", "kind": "pin"}, {"at": "end", "kind": "pin"}],
            "sensors": [{"name": "fairlead", "kind": "tension", "at": "end"}],
        }
    )


def _system(depth: float) -> Scenario:
    return parse_scenario(
        {
            "bodies": [{"name": "chain", "geometry": LINE, **CHAIN}],
            **WORLD,
            "obstacles": _seabed(depth),
            "supports": [
                {"at": "chain:start", "kind": "pin"},
                {"at": "chain:end", "kind": "pin"},
            ],
            "sensors": [{"name": "fairlead", "kind": "tension", "at": "chain:end"}],
        }
    )


@pytest.mark.parametrize("build", [_one_body, _system], ids=["one-body", "bodies"])
@pytest.mark.parametrize("depth", [-30.0, -30.0 - D_VOL / 2], ids=["plane", "resting"])
def test_chain_by_length_matches_moorpy(build, depth):
    """The 100 m chain drawn as its chord (94.87 m) with ``length = 100``: the fairlead tension
    within 0.5 % of MoorPy's, with the seabed plane at -30 m (the chain's centreline then rests
    a tube radius higher than MoorPy's line) and one tube radius lower (it rests at -30 m)."""
    run = run_static(build(depth))
    assert run.sensors["fairlead"] == pytest.approx(T_MOORPY, rel=5e-3)
    if depth < -30.0:  # as MoorPy's line: measured 34362.2 N
        assert run.sensors["fairlead"] == pytest.approx(T_MOORPY, rel=5e-4)


def test_taut_line_is_stretched_onto_its_chord():
    """A weightless line of 9.99 m between pins 10 m apart: the tension EA (10 / 9.99 - 1)
    (engineering strain)."""
    sc = parse_scenario(
        {
            "geometry": {"kind": "line", "start": [0.0, 0.0], "end": [10.0, 0.0], "length": 9.99},
            "mesh": {"elements": 8},
            "section": {"radius": 0.005},
            "material": {"density": 1000.0, "youngs_modulus": 1e9, "axial_strain": "engineering"},
            "supports": [{"at": "start", "kind": "pin"}, {"at": "end", "kind": "pin"}],
            "sensors": [{"name": "pull", "kind": "tension", "at": "end"}],
        }
    )
    ea = 1e9 * math.pi * 0.005**2
    assert run_static(sc).sensors["pull"] == pytest.approx(ea * (10.0 / 9.99 - 1.0), rel=1e-6)


def test_length_refused_where_it_does_not_apply():
    base = {
        "mesh": {"elements": 4, "element": "beam"},
        "section": {"radius": 0.01},
        "material": {"density": 1000.0, "youngs_modulus": 1e9},
    }
    line = {"kind": "line", "start": [0.0, 0.0], "end": [1.0, 0.0], "length": 2.0}
    with pytest.raises(ScenarioError, match=r"geometry\.length.*cable and rod") as e:
        parse_scenario({"geometry": line, **base})
    assert "\n" not in str(e.value)
    base["mesh"] = {"elements": 4}
    with pytest.raises(ScenarioError, match=r"geometry\.length"):
        parse_scenario({"geometry": {**line, "length": -1.0}, **base})
    conic = {"kind": "conic", "start": [0, 0], "end": [1, 0], "angles_deg": [20, 20]}
    with pytest.raises(ScenarioError, match=r"geometry\.length.*does not apply"):
        parse_scenario({"geometry": {**conic, "point": [0.5, 0.09], "length": 2.0}, **base})


def test_reference_start_of_a_slack_line_is_refused():
    """A dynamic run from the reference would start the chain compressed onto its chord."""
    from rancf.solvers.start import start_state

    sc = _one_body(-30.0)
    with pytest.raises(ScenarioError, match=r"geometry\.length.*initial_state") as e:
        start_state(sc, sc.build_system())
    assert "\n" not in str(e.value)
