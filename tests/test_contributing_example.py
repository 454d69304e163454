"""The worked example of CONTRIBUTING.md: a new spring law is one module.  The module is taken
from the page, imported from a temporary folder, and a point mass hanging on the spring under
gravity comes to rest where the law's tension equals the weight (the real root of the cubic
k3 e^3 + k e - W = 0, by Cardano's formula)."""

from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from rancf.bodies.rigid import PointMass
from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.solvers.static import solve_static
from rancf.system import Joint, System

ROOT = Path(__file__).resolve().parents[1]
K, K3, MASS, G = 100.0, 5000.0, 2.0, 9.81


def _example_module(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    """The module of the page's one Python block, written to a folder on the path."""
    text = (ROOT / "CONTRIBUTING.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) == 1, "the page shows one module"
    (tmp_path / "hardening_spring.py").write_text(blocks[0], encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    sys.modules.pop("hardening_spring", None)
    return importlib.import_module("hardening_spring")


def _stretch(weight: float) -> float:
    """The real root of k3 e^3 + k e - W = 0 (one: the cubic increases)."""
    p, q = K / K3, -weight / K3
    d = np.sqrt((q / 2) ** 2 + (p / 3) ** 3)
    return float(np.cbrt(-q / 2 + d) + np.cbrt(-q / 2 - d))


def _hanging(spring) -> System:
    bodies = {"top": PointMass(2, 1.0, (0.0, 0.0)), "bob": PointMass(2, MASS, (0.0, -1.0))}
    return System(
        bodies, joints=[Joint("pin", ("top", "ground"))], springs=[spring], gravity=(0.0, -G)
    )


def test_a_new_spring_law_is_one_module(tmp_path, monkeypatch):
    module = _example_module(tmp_path, monkeypatch)
    spring = module.HardeningSpring(("top", "bob"), k=K, k3=K3, name="hard")
    system = _hanging(spring)
    y = solve_static(system).y
    e = _stretch(MASS * G)
    assert K * e + K3 * e**3 == pytest.approx(MASS * G, rel=1e-12)
    assert e < 0.6 * MASS * G / K  # the cubic term carries 40 % of the weight or more
    bob = system.body_slice("bob")
    assert y[bob][1] == pytest.approx(-1.0 - e, abs=1e-9)
    assert spring.tension(spring.stretch(system, y)) == pytest.approx(MASS * G, rel=1e-9)
    _, strain, _ = system.energies(y, np.zeros(system.n))
    assert strain == pytest.approx(K * e**2 / 2 + K3 * e**4 / 4, rel=1e-9)  # its integral


def test_beyond_its_range_the_law_goes_on_linearly(tmp_path, monkeypatch):
    """Past stretch_range the tension continues with the end slope (k + 3 k3 e_max^2)."""
    module = _example_module(tmp_path, monkeypatch)
    spring = module.HardeningSpring(("top", "bob"), k=K, k3=K3, name="hard")
    system = _hanging(spring)
    y, e, hi = system.y0.copy(), 0.7, 0.5
    y[system.body_slice("bob")][1] = -1.0 - e
    r = np.empty(system.n + system.m)
    system.core.residual(
        ResidualPoint(y, np.zeros(system.m), r), ResidualOptions(0.0, 0.0, dynamic=False)
    )
    tension = K * hi + K3 * hi**3 + (K + 3 * K3 * hi**2) * (e - hi)
    assert -r[system.body_slice("bob")][1] == pytest.approx(tension, rel=1e-9)  # pulls it up
