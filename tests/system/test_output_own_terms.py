"""The block of output rows takes the nodal axial forces' inputs from the assembly that gives
the balance residual (``SystemIntegrator.derived_rows``' ``res0`` and ``internal``): the bodies'
own terms equal a separate ``distributed_only`` residual without multipliers (point loads,
loads at places, springs and joints taken out; weight, inertia, fluid kept), and the element
forces equal each body's ``internal_force``."""

from __future__ import annotations

import tomllib
from importlib import resources

import numpy as np
import pytest

from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.scenario import load_scenario
from rancf.scenario.scenario import parse_scenario
from rancf.system.outputs import SystemOutputs
from tests.scenario.systems import TETHER_3D


def _example(name: str):
    with resources.as_file(resources.files("rancf.examples") / f"{name}.toml") as p:
        return load_scenario(p).build_system()


def _system(name: str):
    if name == "tether-3d":  # springs, a point load with a moment at a place, a moving support
        return parse_scenario(tomllib.loads(TETHER_3D), "s.toml").build_system()
    return _example(name)


def _states(system, k: int, seed: int):
    rng = np.random.default_rng(seed)
    y = system.y0 + 1e-3 * rng.standard_normal((k, system.n))
    v = 1e-1 * rng.standard_normal((k, system.n))
    y[:, system.fixed] = system.y0[system.fixed]
    v[:, system.fixed] = 0.0
    return np.linspace(0.01, 0.05, k), y, v


@pytest.mark.parametrize(
    "name",
    # one clamped cable with a tip load (constant mass: one assembly a row), rods with point
    # loads and joints, a line in wind (fluid), a crank and slider (rigid bodies, joints), a
    # 3D tether (springs, a load at a place, a moving support)
    ["cantilever", "argyris-frame", "power-line-gust", "slider-crank", "tether-3d"],
)
def test_own_terms_and_element_forces_of_the_block(name):
    """``res0`` equals ``System.residual(..., distributed_only=True)`` with zero multipliers at
    the block's consistent accelerations (1e-12 of its size; round-off of ``M Δa`` added to
    the known acceleration's terms), ``internal`` every body's ``internal_force`` (1e-14)."""
    system = _system(name)
    out = SystemOutputs(system)
    s, k = system, 3
    t, y, v = _states(s, k, 4)
    a, lam, res = np.empty((k, s.n)), np.empty((k, s.m)), np.empty((k, s.n + s.m))
    jr, own, fint = np.empty((k, len(s.joints), 6)), np.empty((k, s.n)), np.empty((k, s.n))
    out.integrator.derived_rows(t, y, v, a, lam, res, jr, len(s.joints), own, fint)
    assert np.abs(own).max() > 0.0
    for i in range(k):
        want = np.empty(s.n + s.m)
        s.core.residual(
            ResidualPoint(y[i], np.zeros(s.m), want, v[i], a[i]),
            ResidualOptions(float(t[i]), distributed_only=True),
        )
        scale = max(1.0, np.abs(want[: s.n]).max())
        assert np.abs(own[i] - want[: s.n]).max() <= 1e-12 * scale, i
        for body, b in zip(s.names, s.flex, strict=False):
            sl = s.body_slice(body)
            f = b.internal_force(y[i, sl])
            assert np.abs(fint[i, sl] - f).max() <= 1e-14 * max(1.0, np.abs(f).max()), body


def test_own_terms_leave_out_what_acts_at_places():
    """The check above can fail: with the multipliers' forces, the point loads and the springs
    the full residual differs from the own terms on the tether's rows (by more than 1e-6 of
    their size)."""
    s = _system("tether-3d")
    out = SystemOutputs(s)
    k = 2
    t, y, v = _states(s, k, 9)
    a, lam, res = np.empty((k, s.n)), np.empty((k, s.m)), np.empty((k, s.n + s.m))
    jr, own, fint = np.empty((k, len(s.joints), 6)), np.empty((k, s.n)), np.empty((k, s.n))
    out.integrator.derived_rows(t, y, v, a, lam, res, jr, len(s.joints), own, fint)
    scale = np.abs(res[:, : s.n]).max()
    assert np.abs(res[:, : s.n] - own).max() > 1e-6 * scale
