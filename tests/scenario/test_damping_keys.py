"""``[damping] axial / bending / torsion`` and ``[bodies.damping]`` (Kelvin-Voigt strain-rate
damping, docs/derivations/strain-rate-damping.md): the keys as written reach each flexible body,
a body's own table replaces them, the system's balance carries the force and its velocity
Jacobian, and a key an element cannot take is refused in one line naming the key and the value."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from rancf.bodies.properties import StrainRateDamping
from rancf.bodies.strain_rate import damping_force
from rancf.errors import ScenarioError
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.scenario.scenario import parse_scenario

LINE = {
    "geometry": {"kind": "line", "start": [0.0, 0.0], "end": [1.0, 0.0]},
    "mesh": {"elements": 4},
    "section": {"radius": 0.005},
    "material": {"density": 7850.0, "youngs_modulus": 2.1e11},
}
ONE = {
    **LINE,
    "supports": [{"at": "start", "kind": "clamp"}],
    "damping": {"axial": 300.0, "bending": 0.7, "mass_proportional": 0.1},
}


def test_one_body_keys_reach_the_body_and_the_balance():
    s = parse_scenario(copy.deepcopy(ONE)).build_system()
    body = s.bodies["body"]
    assert body.strain_rate_damping == StrainRateDamping(300.0, 0.7)
    assert s.damping == 0.1  # the Rayleigh keys as before
    rng = np.random.default_rng(2)
    y = s.y0 + 1e-3 * rng.normal(size=s.n)
    v, z, lam = rng.normal(size=s.n), np.zeros(s.n), np.zeros(s.m)
    r1, r0 = np.empty(s.n + s.m), np.empty(s.n + s.m)
    s.core.residual(ResidualPoint(y, lam, r1, v, z), ResidualOptions(0.0))
    s.core.residual(ResidualPoint(y, lam, r0, np.zeros(s.n), z), ResidualOptions(0.0))
    mass_part = 0.1 * body.mass_times(v)
    f_d = damping_force(body, y, v)
    assert np.abs(f_d).max() > 1e-3 * np.abs(mass_part).max()
    assert np.allclose((r1 - r0)[: s.n], f_d + mass_part, rtol=0, atol=1e-10 * np.abs(f_d).max())
    # statics: no velocities, no damping force
    rs = np.empty(s.n + s.m)
    s.core.residual(ResidualPoint(y, lam, rs), ResidualOptions(0.0, dynamic=False))
    assert np.allclose(rs, r0, rtol=0, atol=1e-12 * np.abs(r0).max())
    # the balance's velocity Jacobian: cv (c M + d f_d / dv)
    nm = s.n + s.m
    jac = np.empty(nm * nm)
    assert s.core.dense_jacobian(StatePoint(y, v, z, lam), TangentOptions(0.0, 0.0, 1.0), jac)
    _, ab = damping_force(body, y, v, ck=0.0, cv=1.0)
    expect = body.dense(ab) + 0.1 * body.dense(body.mass_band)
    free = np.flatnonzero(~body.fixed)
    got = jac.reshape(nm, nm)[: s.n, : s.n]
    assert np.allclose(
        got[np.ix_(free, free)],
        expect[np.ix_(free, free)],
        rtol=0,
        atol=1e-10 * np.abs(expect).max(),
    )


def test_a_bodys_own_table_replaces_the_keys_of_damping():
    d = {
        "bodies": [{"name": "a", **LINE, "damping": {"bending": 0.2}}, {"name": "b", **LINE}],
        "supports": [{"at": "a:start"}, {"at": "b:start"}],
        "damping": {"axial": 50.0, "bending": 0.5},
    }
    s = parse_scenario(d).build_system()
    assert s.bodies["a"].strain_rate_damping == StrainRateDamping(0.0, 0.2)
    assert s.bodies["b"].strain_rate_damping == StrainRateDamping(50.0, 0.5)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (
            {"damping": {"torsion": 2.0}},
            "[damping.torsion] 0 with rancf elements (a twist rate needs rod elements: "
            'mesh.element = "rod") (got 2)',
        ),
        (
            {"mesh": {"elements": 2, "element": "beam"}, "damping": {"torsion": 5.0}},
            "[damping.torsion] 0 with beam elements",
        ),
        (
            {
                "bodies": [{"name": "a", **LINE, "damping": {"torsion": 1.5}}],
                "supports": [{"at": "a:start"}],
            },
            "[bodies[0].damping.torsion] 0 with rancf elements",
        ),
        ({"damping": {"bending": -1.0}}, "damping.bending"),
        (
            {
                "bodies": [{"name": "a", **LINE, "damping": {"mass_proportional": 1.0}}],
                "supports": [{"at": "a:start"}],
            },
            "mass_proportional",
        ),
    ],
)
def test_keys_an_element_cannot_take_are_refused_in_one_line(change, message):
    d = {**copy.deepcopy(LINE), "supports": [{"at": "start"}], **copy.deepcopy(change)}
    if "bodies" in change:
        for k in LINE:
            d.pop(k)
    with pytest.raises(ScenarioError) as exc:
        parse_scenario(d).build_system()
    text = str(exc.value)
    assert message in text, text
    assert "\n" not in text.strip()


def test_a_rod_takes_torsion():
    d = {
        **copy.deepcopy(LINE),
        "supports": [{"at": "start", "kind": "clamp"}],
        "damping": {"torsion": 0.01, "bending": 0.02},
    }
    d["geometry"] = {"kind": "line", "start": [0.0, 0.0, 0.0], "end": [1.0, 0.0, 0.0]}
    d["mesh"] = {"elements": 3, "element": "rod"}
    d["material"]["poisson_ratio"] = 0.3
    body = parse_scenario(d).build_system().bodies["body"]
    assert body.strain_rate_damping == StrainRateDamping(0.0, 0.02, 0.01)


def test_the_balances_position_jacobian_carries_the_damping():
    # ck d/dy of the system's balance (elements, damping) against central differences of it
    s = parse_scenario(copy.deepcopy(ONE)).build_system()
    rng = np.random.default_rng(5)
    y, v = s.y0 + 1e-3 * rng.normal(size=s.n), 50.0 * rng.normal(size=s.n)
    z, lam, nm = np.zeros(s.n), np.zeros(s.m), s.n + s.m
    jac = np.empty(nm * nm)
    assert s.core.dense_jacobian(StatePoint(y, v, z, lam), TangentOptions(0.0, 1.0), jac)
    free = np.flatnonzero(~s.bodies["body"].fixed)
    got = jac.reshape(nm, nm)[np.ix_(free, free)]
    h, rp, rm = 1e-7, np.empty(nm), np.empty(nm)
    fd = np.empty_like(got)
    for k, j in enumerate(free):
        d = np.zeros(s.n)
        d[j] = h
        s.core.residual(ResidualPoint(y + d, lam, rp, v, z), ResidualOptions(0.0))
        s.core.residual(ResidualPoint(y - d, lam, rm, v, z), ResidualOptions(0.0))
        fd[:, k] = ((rp - rm) / (2 * h))[free]
    body = s.bodies["body"]
    _, ab = damping_force(body, y, v, ck=1.0, cv=0.0)
    part = body.dense(ab)[np.ix_(free, free)]
    assert np.abs(part).max() > 1e-4 * np.abs(got).max()  # the damping's share is not lost
    assert np.abs(fd - got).max() <= 1e-6 * np.abs(got).max()
