"""Stiffness-proportional (Rayleigh) damping ``[damping] stiffness_proportional = β``: the force
``β K_T(y) v``; its tangent (``d/dv = β K_T``; ``d/dy`` the tangent's derivative along ``v``)
against central differences of the residual, for a planar cable and a spatial rod; and the
modal damping ratio ``β ω / 2`` of a cantilever's first mode in free vibration."""

from __future__ import annotations

import tomllib
from importlib.resources import files

import numpy as np
import pytest

from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.scenario import parse_scenario
from rancf.scenario.system_build import build_system
from rancf.solvers.dynamic import integrate
from rancf.solvers.modal import natural_modes

CANTILEVER = tomllib.loads((files("rancf.examples") / "cantilever.toml").read_text())
ROD = {
    "geometry": {"kind": "line", "start": [0, 0, 0], "end": [1, 0.2, 0.1]},
    "mesh": {"elements": 4, "element": "rod"},
    "section": {"radius": 0.02},
    "material": {"density": 7800.0, "youngs_modulus": 2e9, "poisson_ratio": 0.3},
    "supports": [{"at": "start", "kind": "clamp"}],
}


def _system(raw: dict, beta: float):
    return build_system(parse_scenario({**raw, "damping": {"stiffness_proportional": beta}}))


def _residual(s, y, v, a):
    r = np.empty(s.n + s.m)
    assert s.core.residual(ResidualPoint(y, np.zeros(s.m), r, v, a), ResidualOptions(0.1))
    return r[: s.n]


@pytest.mark.parametrize("raw", [CANTILEVER, ROD], ids=["cable", "rod"])
def test_force_and_tangent(raw, rng):
    beta = 2e-3
    s, s0 = _system(raw, beta), _system(raw, 0.0)
    free = ~s.fixed
    y = s.y0 + 1e-2 * rng.standard_normal(s.n) * free  # a bent, stretched state
    v = rng.standard_normal(s.n) * free
    a = rng.standard_normal(s.n)
    dense = np.empty((s.n + s.m) ** 2)
    # the force: beta K_T v, K_T the elements' tangent (the statics' Jacobian, no inertia)
    point = StatePoint(y, v, a, np.zeros(s.m))
    assert s0.core.dense_jacobian(point, TangentOptions(0.1, 1.0, dynamic=False), dense)
    k = dense.reshape(s.n + s.m, -1)[: s.n, : s.n]
    extra = _residual(s, y, v, a) - _residual(s0, y, v, a)
    np.testing.assert_allclose(
        extra[free], beta * (k @ v)[free], rtol=1e-10, atol=1e-12 * np.abs(beta * k @ v).max()
    )
    for ck, cv in ((1.0, 0.0), (0.0, 1.0)):  # d/dy and d/dv against differences
        assert s.core.dense_jacobian(point, TangentOptions(0.1, ck, cv), dense)
        jac = dense.reshape(s.n + s.m, -1)[: s.n, : s.n]
        fd = np.zeros((s.n, s.n))
        for j in np.flatnonzero(free):
            h = 1e-6 * (1 + abs((y if ck else v)[j]))
            e = np.zeros(s.n)
            e[j] = h
            if ck:
                fd[:, j] = (_residual(s, y + e, v, a) - _residual(s, y - e, v, a)) / (2 * h)
            else:
                fd[:, j] = (_residual(s, y, v + e, a) - _residual(s, y, v - e, a)) / (2 * h)
        sub = np.ix_(free, free)
        err = np.abs(jac[sub] - fd[sub]).max()
        assert err <= 1e-6 * np.abs(fd[sub]).max(), (ck, err)


def test_modal_damping_ratio_of_the_first_mode():
    """Released from the static deflection under a tip load, the cantilever swings in (nearly)
    its first mode; the decay of the tip's swings gives the damping ratio, beta omega_1 / 2
    (the higher modes, damped in proportion to their frequency, are gone after a period)."""
    beta = 4e-3
    raw = {
        **CANTILEVER,
        "solver": {"t_end": 1.0, "step": 1e-3, "rho_inf": 1.0, "initial_state": "static"},
    }
    sc = parse_scenario({**raw, "damping": {"stiffness_proportional": beta}})
    system = build_system(sc)
    omega = 2 * np.pi * natural_modes(system, count=1).frequencies_hz[0]
    from rancf.solvers.start import start_state

    y0, _ = start_state(sc, system)
    free = build_system(
        parse_scenario(
            {
                **{k: v for k, v in raw.items() if k != "loads"},
                "damping": {"stiffness_proportional": beta},
            }
        )
    )
    res = integrate(free, sc.dynamic_options(), initial=y0)
    tip = res.q[:, free.body_slice("body")][:, -4 + 1]  # the end node's y
    peaks = [
        i
        for i in range(1, tip.size - 1)
        if abs(tip[i]) >= abs(tip[i - 1]) and abs(tip[i]) > abs(tip[i + 1])
    ]
    amp = np.abs(tip[peaks])
    t = res.t[peaks]
    rate = -np.polyfit(t[len(t) // 3 :], np.log(amp[len(t) // 3 :]), 1)[0]  # zeta omega
    zeta = rate / omega
    assert zeta == pytest.approx(beta * omega / 2, rel=0.01), (zeta, beta * omega / 2, omega)
