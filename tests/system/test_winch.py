"""Winches (rancf.system.winches; docs/derivations/variable-length.md §2): a 10 kg load on a
steel wire (radius 5 mm) paid out by a winch at the wire's top.

* 5 m to 15 m in 10 s (a smooth law): the load follows L(t) plus the static stretch, and the
  mass the compiled core integrates is ρ A L(t) at every output;
* slow pay-out: the winch's tension is (m + ρ A L) g;
* a pay-out and reel-in cycle without damping: the winch's work equals the change of kinetic,
  strain and gravity energy, and the kinetic energy is that of the material's own speed;
* the tangent against central differences, and rigid motions of the stretched wire carry no
  elastic force; statics at any winch length."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import PointMass
from rancf.bodies.time_function import TimeFunction
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.factories import mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.static import solve_static
from rancf.system import Joint, System, Winch
from rancf.system.outputs import SystemOutputs
from tests.bodies.test_length import static_stretch

G, LOAD = 9.81, 10.0
STEEL, WIRE = Material(7850.0, 2.0e11), Section.circular(0.005)
EA, RHO_A = 2.0e11 * WIRE.area, 7850.0 * WIRE.area


def hoist(law, horizon: float, n_el: int = 10, gravity: float = G) -> System:
    """The wire meshed 5 m long from the winch at the origin straight down, the load pinned to
    its lower end; the winch sets the unstretched length ``law(t)`` (``law(0) = 5``; a
    callable or a TimeFunction)."""
    g = [0.0, -gravity]
    wire = Model(
        mesh_line([0, 0], [0, -5.0], n_el), "ancf", WIRE, STEEL, [Support(0, "pin")], gravity=g
    )
    load = PointMass(2, LOAD, (0.0, -5.0))
    f = law if isinstance(law, TimeFunction) else TimeFunction.from_callable(law)
    winch = Winch("hoist", "wire:start", length=f)
    return System(
        {"wire": wire, "load": load},
        [Joint("pin", ("wire:end", "load"))],
        gravity=g,
        winches=[winch],
        horizon=horizon,
    )


def payout(t: float, duration: float = 10.0) -> float:
    """5 m to 15 m over ``duration``, starting and ending at rest."""
    x = min(max(t / duration, 0.0), 1.0)
    return 5.0 + 10.0 * (x - np.sin(2 * np.pi * x) / (2 * np.pi))


def cycle(t: float, duration: float = 20.0) -> float:
    """5 m out to 15 m and back over ``duration``."""
    return 5.0 + 10.0 * np.sin(np.pi * t / duration) ** 2


def _run(s: System, t_end: float, step: float, rho_inf: float = 0.5, output: float = 0.5):
    st = solve_static(s, load_steps=1, at_time=0.0)  # the wire loaded at its start length
    res = integrate(
        s, DynamicOptions(t_end=t_end, step=step, rho_inf=rho_inf, output_step=output), initial=st.y
    )
    assert res.status.value == "completed", res.message
    return res


def _mass_in_core(s: System, y: np.ndarray, t: float) -> float:
    """The wire's mass as the core integrates it at t: the x rows of ``M a`` for a = e_x."""
    z, a = np.zeros(s.n), np.zeros(s.n)
    sl = s.body_slice("wire")
    a[sl] = np.tile([1.0, 0.0, 0.0, 0.0], s.bodies["wire"].n_nodes)
    r1, r0 = np.empty(s.n + s.m), np.empty(s.n + s.m)
    s.core.residual(ResidualPoint(y, np.zeros(s.m), r1, z, a), ResidualOptions(t))
    s.core.residual(ResidualPoint(y, np.zeros(s.m), r0, z, z), ResidualOptions(t))
    return float((r1 - r0)[sl][0::4].sum())


def test_payout_follows_the_length_and_keeps_the_mass():
    """5 m to 15 m in 10 s: the load within 1 mm of L(t) plus the static stretch (measured:
    2e-5 m), the mass ρ A L(t) to 1e-9 at every output."""
    s = hoist(payout, 10.0)
    res = _run(s, 10.0, 0.01)
    for t, q in zip(res.t, res.q, strict=True):
        y = s.y_from_q(q)
        drop = -y[s.body_slice("load")][1]
        length = payout(t)
        assert abs(drop - length - static_stretch(length)) < 1e-3
        assert _mass_in_core(s, y, float(t)) == pytest.approx(RHO_A * length, rel=1e-9)
    worst = max(
        abs(-s.y_from_q(q)[s.body_slice("load")][1] - payout(t) - static_stretch(payout(t)))
        for t, q in zip(res.t, res.q, strict=True)
    )
    assert worst < 5e-5


def test_slow_payout_tension_is_the_weight_outside_the_winch():
    """5 m to 15 m in 60 s: the winch's reaction (the line tension) is (m + ρ A L) g within
    0.5 % at every output (measured: 0.3 %, of which 0.15 % is the load's acceleration).  The
    stored states' positions are off the quasi-static ones by a multiple of ``h² L''``
    (generalized-α, second order): on a steel wire that is a strain error of order
    ``h² L'' / L``: 10 % of the tension with a 0.05 s step, 0.6 % with 0.0125 s, 0.1 % with
    the 0.005 s taken here."""
    s = hoist(lambda t: payout(t, 60.0), 60.0)
    res = _run(s, 60.0, 0.005, output=5.0)
    rows = SystemOutputs(s).rows(res.t, res.q, res.v, lam=res.lam)
    for t, r in zip(res.t, rows["r"], strict=True):
        tension = np.hypot(r[0], r[1])
        assert tension == pytest.approx((LOAD + RHO_A * payout(t, 60.0)) * G, rel=5e-3)


def _exit_power(s: System, y: np.ndarray, law, t: float) -> float:
    """The winch's power into the line: the drum's force on the material leaving it, -N t,
    times that material's velocity L' λ t, plus the energy that material carries in
    (kinetic ½ ρ A (L' λ)², strain ½ EA ε²; its gravity energy is zero at the origin); N, λ
    and ε of the wire at the winch (its first node's gradient; the mesh's length 5 m)."""
    f = TimeFunction.from_callable(law)
    length, rate = float(law(t)), float(np.ravel(f.rate(t))[0])
    stretch = np.linalg.norm(y[2:4]) * 5.0 / length
    eps = (stretch**2 - 1.0) / 2.0
    tension = EA * eps * stretch
    return rate * (-tension * stretch + 0.5 * RHO_A * (rate * stretch) ** 2 + 0.5 * EA * eps**2)


def test_energy_balance_over_a_payout_and_reel_in_cycle():
    """No damping (ρ∞ = 1): the winch's work equals the change of kinetic + strain + gravity
    energy within 0.5 % of the largest work at every output (measured: 0.38 %; it converges
    at second order in the step), and the kinetic energy is ½ (m + ρ A L) L'² within 1 % while
    the line moves at more than 0.5 m/s (the material moving through the mesh: the mesh's own
    velocities alone would give the wire a third of it)."""
    s = hoist(cycle, 20.0)
    res = _run(s, 20.0, 0.004, rho_inf=1.0, output=0.004)
    power = np.array(
        [_exit_power(s, s.y_from_q(q), cycle, t) for t, q in zip(res.t, res.q, strict=True)]
    )
    work = np.r_[0.0, np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(res.t))]
    energy = res.kinetic + res.strain + res.gravity
    change = energy - energy[0]
    assert np.max(np.abs(work - change)) < 5e-3 * np.max(np.abs(work))
    f = TimeFunction.from_callable(cycle)
    rate = np.array([float(np.ravel(f.rate(t))[0]) for t in res.t])
    lengths = np.array([cycle(t) for t in res.t])
    moving = np.abs(rate) > 0.5
    expected = 0.5 * (LOAD + RHO_A * lengths) * rate**2
    np.testing.assert_allclose(res.kinetic[moving], expected[moving], rtol=1e-2)


def test_tangent_against_central_differences():
    """d/dy, d/dv, d/da of the balance with the winch's convective inertia, at a time where
    L, L' and L'' are all nonzero (the balance is linear in v and a: a large step there, away
    from the round-off of the wire's large elastic forces)."""
    s = hoist(payout, 10.0)
    rng = np.random.default_rng(7)
    y = s.y0 + 1e-3 * rng.standard_normal(s.n)
    y[s.fixed] = s.y0[s.fixed]
    v, a = rng.standard_normal(s.n), rng.standard_normal(s.n)
    v[s.fixed] = a[s.fixed] = 0.0
    lam = rng.standard_normal(s.m)
    t, free = 3.3, np.flatnonzero(~s.fixed)
    for k, (ck, cv, ca) in enumerate([(1, 0, 0), (0, 1, 0), (0, 0, 1)]):
        dense = np.empty((s.n + s.m) ** 2)
        assert s.core.dense_jacobian(StatePoint(y, v, a, lam), TangentOptions(t, ck, cv, ca), dense)
        jac = dense.reshape(s.n + s.m, -1)[: s.n, : s.n]
        fd = np.zeros((s.n, s.n))
        for j in free:
            args = [y.copy(), v.copy(), a.copy()]
            h = 1e-6 * (1 + abs(args[k][j])) if k == 0 else 0.1  # linear in v and a
            rs = []
            for sign in (1, -1):
                xs = [x.copy() for x in args]
                xs[k][j] += sign * h
                r = np.empty(s.n + s.m)
                assert s.core.residual(
                    ResidualPoint(xs[0], lam, r, xs[1], xs[2]), ResidualOptions(t)
                )
                rs.append(r[: s.n])
            fd[:, j] = (rs[0] - rs[1]) / (2 * h)
        sub = np.ix_(free, free)
        assert np.abs(jac[sub] - fd[sub]).max() <= 2e-6 * max(1.0, np.abs(fd[sub]).max())


def test_stretched_wire_moved_rigidly_carries_no_elastic_force():
    """Without gravity, paid out at a constant 1 m/s: the wire at L(t), straight in any
    direction from the winch (rotated about it), its material moving at the pay-out speed (the
    mesh stretching, ``v = (L' / L) (r - a)``): no acceleration, no force on the free rows."""
    s = hoist(TimeFunction.table([[0.0, 5.0], [10.0, 15.0]]), 10.0, gravity=0.0)
    t = 4.0
    factor = (5.0 + t) / 5.0
    c, sn = np.cos(0.6), np.sin(0.6)
    y = s.y0.copy()
    sl = s.body_slice("wire")
    q = y[sl].reshape(-1, 4)
    rot = np.array([[c, -sn], [sn, c]])
    q[:, :2] = factor * q[:, :2] @ rot.T
    q[:, 2:] = factor * q[:, 2:] @ rot.T
    y[sl] = q.ravel()
    y[s.body_slice("load")] = q[-1, :2]
    v = y / (5.0 + t)  # the winch at the origin
    z = np.zeros(s.n)
    r = np.empty(s.n + s.m)
    s.core.residual(ResidualPoint(y, np.zeros(s.m), r, v, z), ResidualOptions(t))
    assert np.max(np.abs(r[: s.n][~s.fixed])) < 1e-9 * EA


@pytest.mark.parametrize("t", [0.0, 5.0, 10.0])
def test_statics_at_any_winch_length(t):
    """The static equilibrium at time t: the wire L(t) long plus its stretch."""
    s = hoist(payout, 10.0)
    res = solve_static(s, load_steps=4, at_time=t)
    drop = -res.y[s.body_slice("load")][1]
    assert drop - payout(t) == pytest.approx(static_stretch(payout(t)), abs=1e-9)


def test_a_length_law_reaching_zero_stops_the_run_at_the_step_before():
    """A system built in Python whose winch reels in 5 m at 10 m/s (no scenario file to refuse
    it): the run stops at the first step whose length is not > 0, naming the winch, the time
    and the length, and stores nothing past it."""
    s = hoist(TimeFunction.table([[0.0, 5.0], [1.0, -5.0]]), horizon=1.0)
    st = solve_static(s, load_steps=1, at_time=0.0)
    res = integrate(s, DynamicOptions(t_end=1.0, step=0.01, output_step=0.05), initial=st.y)
    assert res.status.value == "failed"
    assert res.message == (
        "winch 'hoist': its length law gives 0 m at t = 0.5 s, not > 0; the "
        "run stops at the step before"
    ), res.message
    assert res.state.t == pytest.approx(0.49) and res.t[-1] == pytest.approx(0.45)
