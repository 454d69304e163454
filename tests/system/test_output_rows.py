"""Derived output rows taken a block at a time by the core (``SystemOutputs.rows`` without
contact) equal those of the row-by-row formulas: the consistent acceleration and multipliers
(``initial_acceleration``), the balance residual with them (``System.residual``) and the
reactions of supports and joints from it (``SystemOutputs._reactions``); a system of one body
takes the energies stored with each row as its body's."""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest

from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.scenario import load_scenario
from rancf.system.outputs import SystemOutputs


def _system(name: str):
    with resources.as_file(resources.files("rancf.examples") / f"{name}.toml") as p:
        return load_scenario(p).build_system()


def _states(system, k: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """k states near the reference: small displacements and velocities."""
    rng = np.random.default_rng(seed)
    y = system.y0 + 1e-3 * rng.standard_normal((k, system.n))
    v = 1e-1 * rng.standard_normal((k, system.n))
    y[:, system.fixed] = system.y0[system.fixed]  # held coordinates stay held
    v[:, system.fixed] = 0.0
    return np.linspace(0.0, 0.04, k), y, v


def _row_by_row(out: SystemOutputs, t: float, y: np.ndarray, v: np.ndarray):
    s = out.system
    a, lam, res = np.zeros(s.n), np.zeros(s.m), np.empty(s.n + s.m)
    out.integrator.initial_acceleration(y, v, t, a, lam)
    s.core.residual(ResidualPoint(y, lam, res, v, a), ResidualOptions(t))
    return s.q_from_y(a), lam, out._reactions(y, res[: s.n], t, lam, v)


@pytest.mark.parametrize("name", ["slider-crank", "spin-up-beam", "cantilever"])
def test_block_rows_equal_row_by_row(name):
    """Joints and rigid bodies (the crank, the hub: the full assembly a row) and one clamped
    cable (constant mass: the residual as the known one plus ``M Δa``): the same values to
    1e-9 of each quantity's size."""
    system = _system(name)
    out = SystemOutputs(system)
    t, y, v = _states(system, 4, 7)
    q, qv = system.q_from_y(y), system.q_from_y(v)
    got = out.rows(t, q, qv)
    assert got["r"].shape == (4, len(out.reaction_names)) and got["r"].size
    for i in range(4):
        a, lam, r = _row_by_row(out, float(t[i]), y[i], v[i])
        for key, want in (("a", a), ("lam", lam), ("r", r)):
            scale = max(1.0, np.abs(want).max(initial=0.0))
            assert np.abs(got[key][i] - want).max(initial=0.0) <= 1e-9 * scale, (key, i)


def test_one_body_energies_are_the_stored_ones():
    """A system of one flexible body: ``eb`` is the energy stored with each row, and equals the
    body's own energies from the core (1e-12)."""
    system = _system("cantilever")
    out = SystemOutputs(system)
    t, y, v = _states(system, 3, 11)
    energy = np.array([system.core.energies(y[i], v[i], float(t[i])) for i in range(3)])
    got = out.rows(t, system.q_from_y(y), system.q_from_y(v), energy=energy, per_body=True)
    np.testing.assert_array_equal(got["eb"], energy)
    for i in range(3):
        body = out._body_energies(y[i], v[i], float(t[i]))
        assert np.abs(body - energy[i]).max() <= 1e-12 * max(1.0, np.abs(energy[i]).max())


@pytest.mark.parametrize("name", ["slider-crank", "cantilever"])
def test_block_equals_the_row_loop_in_every_output(name, monkeypatch):
    """Every derived output of a block (accelerations, multipliers, reactions, section values
    with the nodal axial forces, sensors, every body's energies) equals the row loop's, which
    the block replaces (1e-9 of each output's size)."""
    system = _system(name)
    t, y, v = _states(system, 3, 5)
    q, qv = system.q_from_y(y), system.q_from_y(v)
    block = SystemOutputs(system).rows(t, q, qv, per_body=True)
    monkeypatch.setattr("rancf.system.outputs.takes_block", lambda *args: False)
    loop = SystemOutputs(system).rows(t, q, qv, per_body=True)
    assert block["eb"].shape == (3, 3 * len(system.flex)) and np.abs(loop["eb"]).max() > 0
    for key in ("a", "lam", "r", "s", "c", "eb"):
        scale = max(1.0, np.abs(loop[key]).max(initial=0.0))
        assert np.abs(block[key] - loop[key]).max(initial=0.0) <= 1e-9 * scale, key


@pytest.mark.parametrize("name", ["mooring-line", "belt-drive"])
@pytest.mark.parametrize("with_alpha", [False, True])
def test_block_with_contact_equals_the_row_loop(name, with_alpha, monkeypatch):
    """Rows with contact (a chain in water on the seabed; a belt on its pulleys, friction):
    the block takes each row's contact forces from its step's generalized-α point (``alpha``)
    or, without it, from the row itself, as the row loop does; every output equals the loop's
    to 1e-12 of its size, and the obstacles' columns carry a force (the contact is closed)."""
    system = _system(name)
    t, y, v = _states(system, 3, 13)
    q, qv = system.q_from_y(y), system.q_from_y(v)
    alpha = None
    if with_alpha:  # a point between the row and a nearby state, as a step's alpha point is
        rng = np.random.default_rng(3)
        alpha = np.concatenate([y + 1e-4 * rng.standard_normal(y.shape), 0.9 * v], axis=1)
        alpha[:, : system.n][:, system.fixed] = y[:, system.fixed]
    block_out = SystemOutputs(system)
    block = block_out.rows(t, q, qv, alpha=alpha)
    contact = block["r"][:, block_out.contact_start :]
    assert contact.size and np.abs(contact).max() > 0.0
    monkeypatch.setattr("rancf.system.outputs.takes_block", lambda *args: False)
    loop = SystemOutputs(system).rows(t, q, qv, alpha=alpha)
    for key in ("a", "lam", "r", "s", "c"):
        scale = max(1.0, np.abs(loop[key]).max(initial=0.0))
        assert np.abs(block[key] - loop[key]).max(initial=0.0) <= 1e-12 * scale, key


def test_rows_in_water_take_each_rows_added_mass():
    """A line in water off the seabed (the mooring line without its obstacle): the added mass
    turns with the line's tangent, so each row's consistent accelerations need that row's
    matrix; a row among others gives what it gives alone (1e-12 of its size; the first row's
    factors reused were 1 % off)."""
    import tomllib

    from rancf.scenario import parse_scenario

    with resources.as_file(resources.files("rancf.examples") / "mooring-line.toml") as p:
        raw = tomllib.loads(p.read_text())
    raw.pop("obstacles")
    raw["sensors"] = [x for x in raw.get("sensors", []) if "obstacle" not in x]
    system = parse_scenario(raw).build_system()
    assert not system.has_contact
    rng = np.random.default_rng(1)
    y = system.y0 + rng.standard_normal((2, system.n)) * np.array([[1e-2], [0.5]])
    y[:, system.fixed] = system.y0[system.fixed]
    q, qv, t = system.q_from_y(y), np.zeros_like(y), np.zeros(2)
    both = SystemOutputs(system).rows(t, q, qv)
    alone = SystemOutputs(system).rows(t[1:], q[1:], qv[1:])
    for key in ("a", "r"):
        scale = np.abs(alone[key][0]).max()
        assert np.abs(both[key][1] - alone[key][0]).max() <= 1e-12 * scale, key
