"""``build_up = B`` (T.6): any time function times the quintic smooth step over ``[0, B]``;
value, rate and acceleration start from zero and join the function at ``B``, the same in the
compiled core; a harmonic support motion that would start with a jump of its rate builds up by
default (one line says so): the tether example, hung from a heaving top, then has no
compressive top tension (and has one without the build-up)."""

from __future__ import annotations

import tomllib
from importlib.resources import files

import numpy as np
import pytest

from rancf.bodies.time_function import TimeFunction
from rancf.cli import main
from rancf.scenario import parse_scenario
from rancf.scenario.joints import JointTable
from rancf.scenario.loads import SupportTable
from rancf.scenario.system_build import build_system
from rancf.scenario.time_functions import time_function
from rancf.solvers.generalized_alpha import GeneralizedAlpha

FUNCTIONS = [
    TimeFunction.harmonic(2.0, [0.0, 0.1], 30.0),
    TimeFunction.spin_up(0.3, 5.0),
    TimeFunction.table([[0.0, 1.0], [0.2, 3.0], [1.0, 2.0]], "cubic"),
    TimeFunction.constant(2.0),
]


def _fd(f: TimeFunction, t: float, h: float = 1e-5) -> tuple[np.ndarray, np.ndarray]:
    v = [np.atleast_1d(f.value(t + k * h)) for k in (-1, 0, 1)]
    return (v[2] - v[0]) / (2 * h), (v[2] - 2 * v[1] + v[0]) / h**2


@pytest.mark.parametrize("f", FUNCTIONS, ids=["harmonic", "spin_up", "table", "constant"])
def test_build_up_law(f):
    b = 0.5
    g = f.with_build_up(b)
    for t in (-0.1, 0.0):
        assert np.all(np.atleast_1d(g.value(t)) == 0) and np.all(np.atleast_1d(g.rate(t)) == 0)
        assert np.all(np.atleast_1d(g.acceleration(t)) == 0)
    for t in (0.5, 0.8, 1.3):  # from B on: the function itself
        np.testing.assert_array_equal(g.value(t), f.value(t))
        np.testing.assert_array_equal(g.rate(t), f.rate(t))
    s = 0.3  # inside: r = 10 s^3 - 15 s^4 + 6 s^5 times f
    r = 10 * s**3 - 15 * s**4 + 6 * s**5
    np.testing.assert_allclose(g.value(s * b), r * np.asarray(f.value(s * b)), rtol=1e-14)
    for t in (0.05, 0.15, 0.25, 0.45):  # rate and acceleration against differences
        rate, acc = _fd(g, t)
        np.testing.assert_allclose(np.atleast_1d(g.rate(t)), rate, rtol=1e-7, atol=1e-8)
        np.testing.assert_allclose(np.atleast_1d(g.acceleration(t)), acc, rtol=1e-4, atol=1e-4)
    # smooth at both ends: rate and acceleration continuous
    for t in (1e-9, b - 1e-9):
        np.testing.assert_allclose(g.rate(t), f.rate(t) if t > b / 2 else 0 * f.rate(t), atol=1e-6)
    # the file form carries it (a constant as a table of two equal rows)
    if f.vector:
        back = time_function(SupportTable(at="end", motion=g.to_toml()).motion)
    else:
        back = time_function(
            JointTable(name="j", kind="pin", between=["a", "b"], angle=g.to_toml()).angle
        )
    assert back.build_up == b
    np.testing.assert_allclose(back.value(0.2), g.value(0.2), rtol=1e-13)


def test_the_core_evaluates_the_same_build_up():
    sc = parse_scenario(
        {
            "geometry": {"kind": "line", "start": [0, 0], "end": [1, 0]},
            "mesh": {"elements": 2},
            "section": {"radius": 0.01},
            "material": {"density": 1000.0, "youngs_modulus": 1e9},
            "supports": [
                {
                    "at": "start",
                    "kind": "pin",
                    "motion": {
                        "harmonic": 2.0,
                        "amplitude": [0.03, 0.1],
                        "phase_deg": 30.0,
                        "build_up": 0.4,
                    },
                }
            ],
        }
    )
    f = sc.data["supports"][0]["motion"]
    assert f.build_up == 0.4 and sc.notes == []  # stated: no default, no note
    system = build_system(sc)
    integ = GeneralizedAlpha(system, 0.9, 1e-10, 10)
    y0 = system.y0.copy()
    for t in (0.0, 0.1, 0.25, 0.39, 0.4, 0.7):
        y, v = y0.copy(), np.zeros_like(y0)
        integ.prescribe(t, y, v)
        np.testing.assert_allclose(y[:2] - y0[:2], f.value(t), rtol=1e-14, atol=1e-17)
        np.testing.assert_allclose(v[:2], f.rate(t), rtol=1e-14, atol=1e-16)


def _tether(motion: str) -> str:
    text = (files("rancf.examples") / "tether-payload.toml").read_text(encoding="utf-8")
    text = text.replace("[0.5, -0.8660254037844386]", "[0.0, -1.0]")  # hung straight down
    text = text.replace(
        'kind = "pin"\n\n[[joints]]', f'kind = "pin"\nmotion = {motion}\n\n[[joints]]'
    )
    text = text.replace("rho_inf = 1.0", 'rho_inf = 1.0\ninitial_state = "static"')
    return text + '\n[[sensors]]\nname = "top_tension"\nkind = "axial_force"\nat = "tether:start"\n'


def _top_tension(run) -> np.ndarray:
    rows = np.genfromtxt(run / "sensors.csv", delimiter=",", names=True)
    return rows["top_tension"]


def test_a_heaving_tether_builds_up_without_compression(tmp_path, monkeypatch, capsys):
    """A 0.1 m heave at 1 Hz (top acceleration up to 3.9 m/s^2 < g) of the tether example
    hung from its top at its static equilibrium: with the default build-up the top tension
    stays between m (g - a) and m (g + a) (about 12 and 29 N); starting the harmonic at once
    (a jump of the top's velocity to 0.63 m/s) sends stress waves of about 1.8 kN."""
    monkeypatch.chdir(tmp_path)
    heave = "{ harmonic = 1.0, amplitude = [0.0, 0.1] }"
    (tmp_path / "heave.toml").write_text(_tether(heave))
    (tmp_path / "jump.toml").write_text(_tether(heave.replace(" }", ", build_up = 0 }")))
    assert tomllib.loads(_tether(heave))["supports"][0]["motion"]["harmonic"] == 1.0
    capsys.readouterr()
    assert main(["simulate", "heave.toml", "--out", "heave", "--quiet"]) == 0
    err = capsys.readouterr().err.splitlines()
    note = [x for x in err if "build" in x]
    assert note == [
        "rancf: supports[0].motion: the harmonic would start with a jump of its "
        "rate to 0.628; it builds up over 2 s (2 periods; give build_up = 0 to "
        "start it at once)"
    ]
    tension = _top_tension(tmp_path / "heave")
    assert tension.min() > 10.0 and tension.max() < 31.0, (tension.min(), tension.max())
    assert main(["simulate", "jump.toml", "--out", "jump", "--quiet"]) == 0
    assert not any("build" in x for x in capsys.readouterr().err.splitlines())
    assert _top_tension(tmp_path / "jump").min() < -100.0  # compressed by the jump
