"""Sensors at a fixed point in space (``at_point``): the material point nearest to it, found
anew at every output."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest
import scipy.integrate
import scipy.optimize

from rancf.cli import main
from rancf.errors import ScenarioError
from rancf.scenario import Scenario

RHO, RADIUS, E, L, G = 1000.0, 0.01, 1.96e5, 1.0, 9.81
HANGING = f"""
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.0, -{L}]
[mesh]
elements = 8
element = "ancf"
[section]
radius = {RADIUS}
[material]
density = {RHO}
youngs_modulus = {E}
[[supports]]
at = "start"
kind = "clamp"
[loads]
gravity = [0.0, -{G}]
[solver]
load_steps = 4
[[sensors]]
name = "n_fixed"
kind = "axial_force"
at_point = [0.0, -0.6]
[[sensors]]
name = "foot"
kind = "position"
at_point = [0.01, -0.6]
"""


def test_a_hanging_bar_s_tension_at_a_fixed_height(tmp_path):
    """A soft bar (1 m, EA = 61.6 N) hanging from a clamp stretches by up to 5 % under its
    weight.  The tension at the fixed point 0.6 m below the clamp is that of the material
    point that has moved there: ``N(s) = ρAg (L - s)`` (equilibrium of the part below, exact),
    with ``s*`` solving ``∫₀^{s*} λ ds = 0.6``, the stretch from ``N = EA ε λ``,
    ``ε = (λ² - 1)/2`` (the element's Green-Lagrange strain).  Within 1e-5 relative (measured
    1.0e-6); a sensor at the material point first at 0.6 m would read 4.7 % less.  The position
    sensor beside the bar reads the foot of the perpendicular, (0, -0.6), within 1e-12 m."""
    path = tmp_path / "hanging.toml"
    path.write_text(HANGING)
    assert main(["static", str(path), "--out", str(tmp_path / "run")]) == 0
    rows = np.loadtxt(tmp_path / "run" / "sensors.csv", delimiter=",", skiprows=1, ndmin=2)
    header = (tmp_path / "run" / "sensors.csv").read_text().splitlines()[0].split(",")
    last = dict(zip(header, rows[-1], strict=True))
    ea, w = E * np.pi * RADIUS**2, RHO * np.pi * RADIUS**2 * G

    def stretch(s: float) -> float:
        n = w * (L - s)
        return scipy.optimize.brentq(
            lambda lam: ea * 0.5 * (lam**2 - 1) * lam - n, 1.0, 2.0, xtol=1e-15
        )

    def depth(s: float) -> float:
        return scipy.integrate.quad(stretch, 0.0, s, epsabs=1e-14, epsrel=1e-13)[0]

    s_star = scipy.optimize.brentq(lambda s: depth(s) - 0.6, 0.3, 0.6, xtol=1e-14)
    exact = w * (L - s_star)
    assert last["n_fixed"] == pytest.approx(exact, rel=1e-5)
    assert abs(last["n_fixed"] - w * (L - 0.6)) > 0.02 * exact
    assert abs(last["foot_x"]) < 1e-12 and last["foot_y"] == pytest.approx(-0.6, abs=1e-12)


def test_at_point_refuses_other_kinds_and_at_together():
    """``at_point`` on a kind without a place, or beside ``at``, is refused naming the key."""
    base = HANGING.split("[[sensors]]")[0]
    bad = (
        'kind = "energy"\nat_point = [0.0, 0.0]',
        'kind = "position"\nat = "end"\nat_point = [0.0, 0.0]',
    )
    for extra in bad:
        text = base + f'[[sensors]]\nname = "bad"\n{extra}\n'
        with pytest.raises(ScenarioError, match="at_point"):
            Scenario.from_dict(tomllib.loads(text))


def test_a_rod_s_twist_at_a_fixed_point(tmp_path):
    """A rod (0.5 m, 8 elements) clamped at its start, twisted by a 0.01 N m tip torque: the
    ``twist`` at the fixed point (0.3, 0.02, 0), beside the rod, is that of the material at
    s = 0.3 m, ``T s / GJ`` (1e-5; measured 5e-7) and 0.6 of the tip's (1e-6)."""
    text = (
        '[geometry]\nkind = "line"\nstart = [0.0, 0.0, 0.0]\nend = [0.5, 0.0, 0.0]\n'
        '[mesh]\nelements = 8\nelement = "rod"\n[section]\nradius = 0.01\n'
        "[material]\ndensity = 1000.0\nyoungs_modulus = 1.0e7\npoisson_ratio = 0.25\n"
        '[[supports]]\nat = "start"\nkind = "clamp"\n'
        '[[loads.point]]\nat = "end"\nmoment = [0.01, 0.0, 0.0]\n'
        '[[sensors]]\nname = "phi"\nkind = "twist"\nat_point = [0.3, 0.02, 0.0]\n'
        '[[sensors]]\nname = "phi_end"\nkind = "twist"\nat = "end"\n'
    )
    (tmp_path / "t.toml").write_text(text)
    assert main(["static", str(tmp_path / "t.toml"), "--out", str(tmp_path / "run")]) == 0
    rows = np.loadtxt(tmp_path / "run" / "sensors.csv", delimiter=",", skiprows=1, ndmin=2)
    phi, phi_end = rows[-1, 1], rows[-1, 2]
    gj = 1.0e7 / 2.5 * np.pi * 0.01**4 / 2
    assert phi == pytest.approx(0.01 * 0.3 / gj, rel=1e-5)
    assert phi == pytest.approx(0.6 * phi_end, rel=1e-6)
