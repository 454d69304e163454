"""The scenario models are the Python API: a scenario built in Python (nested models or plain
dictionaries) equals the one read from a file; saved as TOML and read back it is equal again;
bad values raise the same one-line error, naming ``<scenario>`` instead of a file."""

from __future__ import annotations

import math
import os
import tomllib

import numpy as np
import pytest
from pydantic import ValidationError

from rancf.bodies.time_function import TimeFunction
from rancf.errors import ScenarioError
from rancf.scenario import (
    ConicGeometry,
    MaterialTable,
    MeshTable,
    Scenario,
    SectionTable,
    SensorTable,
    SupportTable,
    load_scenario,
    parse_scenario,
)
from tests.scenario.systems import SLIDER_CRANK, TETHER_3D
from tests.scenario.test_scenario import BASE


def _python_base(**overrides) -> Scenario:
    tables = dict(
        geometry=ConicGeometry(
            kind="conic",
            start=[0.0, 0.0],
            end=[0.5, 0.0],
            angles_deg=[30.0, 40.0],
            point=[0.315, 0.077],
        ),
        mesh=MeshTable(elements=3, element="rancf", k="opt"),
        section=SectionTable(radius=0.02),
        material=MaterialTable(density=6000.0, youngs_modulus=2.0e6),
        supports=[SupportTable(at="start", kind="pin")],
        loads={"gravity": [0.0, -9.81]},
        solver={"t_end": 0.02, "step": 1.0e-3},
        sensors=[
            SensorTable(name="AB", kind="distance", between=["start", "end"]),
            {"name": "tip", "kind": "position", "at": "end"},
        ],
    )
    return Scenario(**{**tables, **overrides})


def test_built_in_python_equals_the_file():
    sc = _python_base()
    from_file = parse_scenario(tomllib.loads(BASE), "base.toml")
    assert sc == from_file
    assert sc.data == from_file.data and sc.sensors == from_file.sensors
    assert sc.path == "<scenario>" and from_file.path == "base.toml"
    m1, m2 = sc.build_model(), from_file.build_model()
    assert m1.n == m2.n and np.array_equal(m1.q0, m2.q0)
    # tables read like the dictionaries of earlier versions
    assert sc.solver["t_end"] == sc.solver.t_end == 0.02 and sc.mesh.get("k") == "opt"


@pytest.mark.parametrize("text", [BASE, SLIDER_CRANK, TETHER_3D], ids=["one-body", "2d", "3d"])
def test_save_and_load_round_trip(tmp_path, text):
    sc = parse_scenario(tomllib.loads(text), str(tmp_path / "a.toml"))
    f = tmp_path / "b.toml"
    sc.save(f)
    back = load_scenario(f)
    assert back == sc and back.data == sc.data and back.sensors == sc.sensors
    assert Scenario.from_toml(f).to_toml() == sc.to_toml()
    assert back.path == str(f) and not list(tmp_path.glob(".b.toml*"))  # no temporary left


def test_saved_file_honours_the_umask(tmp_path):
    old = os.umask(0o027)
    try:
        _python_base().save(tmp_path / "s.toml")
    finally:
        os.umask(old)
    assert (tmp_path / "s.toml").stat().st_mode & 0o777 == 0o640


def test_defaults_are_not_written():
    text = _python_base().to_toml()
    assert "rho_inf" not in text and "quadrature_points" not in text
    assert tomllib.loads(text)["mesh"] == {"elements": 3, "element": "rancf", "k": "opt"}


def test_time_functions_in_python():
    motion = TimeFunction.table([[0.0, 0.0, 0.0], [1.0, 0.0, 0.1]], "cubic")
    sc = _python_base(supports=[{"at": "start"}, {"at": "end", "motion": motion}])
    assert sc.supports[1].motion is motion and sc.data["supports"][1]["motion"] is motion
    back = tomllib.loads(sc.to_toml())["supports"][1]["motion"]
    assert back == {"table": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.1]], "interpolation": "cubic"}
    path = lambda t: [0.2 * math.sin(t), 0.0]  # noqa: E731 - a callable is a time function
    sc2 = _python_base(supports=[{"at": "start"}, {"at": "end", "motion": path}])
    f = sc2.data["supports"][1]["motion"]
    assert f.kind == "callable" and f.rate(0.0)[0] == pytest.approx(0.2, rel=1e-9)
    with pytest.raises(ScenarioError, match=r"^<scenario>: \[supports\[1\]\.motion\] is a Python"):
        sc2.to_toml()
    with pytest.raises(
        ScenarioError,
        match=r"\[supports\[0\]\.motion\] must be a displacement "
        "of 2 components, got 3",
    ):
        _python_base(supports=[{"at": "end", "motion": lambda t: [t, t, t]}])


def test_numpy_values_are_accepted():
    sc = _python_base(
        geometry={"kind": "line", "start": np.zeros(2), "end": (np.float64(0.5), 0)},
        mesh={"elements": np.int64(4)},
    )
    assert sc.geometry.end == [0.5, 0.0] and type(sc.geometry.end[0]) is float
    assert sc.mesh.elements == 4 and type(sc.mesh.elements) is int


def _deep(n: int) -> list:
    x: list | float = 1.0
    for _ in range(n):
        x = [x]
    return x  # type: ignore[return-value]


@pytest.mark.parametrize(
    ("overrides", "message"),
    [
        ({"mesh": {"elements": 0}}, "<scenario>: [mesh.elements] must be >= 1, got 0"),
        (
            {"section": {"radius": 10**401}},
            "<scenario>: [section.radius] must be finite, got an integer of 402 digits",
        ),
        (
            {"mesh": {"elements": -(10**500)}},
            "<scenario>: [mesh.elements] must be >= 1, got an integer of 501 digits",
        ),
        ({"solver": {"t_end": float("nan")}}, "<scenario>: [solver.t_end] must be finite, got nan"),
        (
            {"solver": {"step": 1e308}},
            "<scenario>: [solver.step] a finite number > 0 and <= t_end = 1 (got 1e+308)",
        ),
        (
            {"geometry": {"kind": "line", "start": _deep(3000), "end": [1.0, 0.0]}},
            "<scenario>: [geometry.start] must be a list of 2 or 3 numbers, got a list nested too "
            "deeply to show",
        ),
        (
            {"material": {"density": "7800", "youngs_modulus": 1.0}},
            "<scenario>: [material.density] must be a number, got '7800'",
        ),
        (
            {"sensors": [{"name": "x" * 500, "kind": "energy"}] * 2},
            f"<scenario>: [sensors[1].name] '{'x' * 37}...{'x' * 37}' is used twice or reserved",
        ),
        (
            {"supports": [{"at": True}]},
            '<scenario>: [supports[0].at] must be a place ("start", "end", a node index, '
            '"BODY:..."; a shell\'s edge "u0" or point [u, v]), got True',
        ),
    ],
)
def test_bad_values_in_python_are_one_line(overrides, message):
    with pytest.raises(ScenarioError) as info:
        _python_base(**overrides)
    assert str(info.value) == message


def test_tables_alone_and_immutability():
    with pytest.raises(ScenarioError, match=r"^<MeshTable>: \[k\] must be \"opt\" or a number"):
        MeshTable(elements=2, k=2.0)
    sc = _python_base()
    with pytest.raises(ValidationError):
        sc.mesh.elements = 7  # validated once: a scenario cannot become invalid
