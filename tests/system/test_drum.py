"""Driven drums (rancf.system.drums; docs/derivations/variable-length.md §3): a 10 kg load on
a steel wire (radius 5 mm, 5 m) reeled by a drum of radius 0.2 m and inertia 0.5 kg m² at the
wire's top.

* a torque r (m + ρ A L) g holds the load: statics finds L = L0, and the load stays put;
* 30 % more torque lifts it, 30 % less lowers it (the drum 100 m up) as a rigid rope would,
  (J/r² + m + ρ A L) L̈ = (m + ρ A L) g − τ/r;
* without damping the torque's work equals the change of kinetic (line, load, drum), strain and
  gravity energy, and the mass the core integrates is ρ A L at every output;
* the Jacobian blocks of the drum's coordinate against central differences; modes with the
  drum's length a coordinate (its pay-out the one unstable motion);
* statics with a torque the line cannot balance is refused in one line."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import PointMass
from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.factories import mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.static import solve_static
from rancf.system import Joint, System, Winch

G, LOAD, L0, RADIUS, INERTIA = 9.81, 10.0, 5.0, 0.2, 0.5
WIRE = Section.circular(0.005)
RHO_A = 7850.0 * WIRE.area
BALANCE = RADIUS * (LOAD + RHO_A * L0) * G  # [N m]


def hoist(
    torque, n_el: int = 6, horizon: float = 2.0, strain: str = "green_lagrange", top: float = 0.0
) -> System:
    """The wire meshed L0 long from the drum at ``(0, top)`` straight down, the load pinned to
    its lower end; ``torque(t)`` [N m] on the drum (positive reels in); ``strain``: the axial
    strain of the wire's energy."""
    g = [0.0, -G]
    steel = Material(7850.0, 2.0e11, axial_strain=strain)
    wire = Model(
        mesh_line([0, top], [0, top - L0], n_el),
        "ancf",
        WIRE,
        steel,
        [Support(0, "pin")],
        gravity=g,
    )
    load = PointMass(2, LOAD, (0.0, top - L0))
    f = torque if isinstance(torque, float) else TimeFunction.from_callable(torque)
    drum = Winch("hoist", "wire:start", torque=f, radius=RADIUS, inertia=INERTIA)
    return System(
        {"wire": wire, "load": load},
        [Joint("pin", ("wire:end", "load"))],
        gravity=g,
        winches=[drum],
        horizon=horizon,
    )


def _run(s: System, t_end: float, rho_inf: float, step: float = 0.01):
    st = solve_static(s, load_steps=1, at_time=0.0)
    res = integrate(
        s, DynamicOptions(t_end=t_end, step=step, rho_inf=rho_inf, output_step=0.05), initial=st.y
    )
    assert res.status.value == "completed", res.message
    return st, res


def test_balanced_torque_holds_the_load():
    """Statics puts L where r T = τ: L0 within 2e-4 m (the line's stretch ε = T / EA = 8e-6
    changes its pull at the drum by O(ε T) = 5e-4 N, which its weight per length ρ A g = 6 N/m
    balances over 9e-5 m: measured 8.7e-5 m); from there the load stays put over 1 s (within
    1e-4 m; measured 1e-5 m: the balance is unstable, a longer line weighs more)."""
    s = hoist(BALANCE)
    st, res = _run(s, 1.0, 0.5)
    drum = s.drums["hoist"]
    assert drum == s.n - 1
    assert abs(st.y[drum] - L0) < 2e-4
    assert np.abs(res.q[:, drum] - L0).max() < 1e-4
    load = res.q[:, s.body_slice("load")][:, 1]
    assert np.abs(load - load[0]).max() < 1e-4


def test_static_length_where_the_line_balances_the_torque():
    """1.3 times the torque at L0: statics finds the length whose weight balances it, (m + ρ A
    L) g = τ / r, L = 11.37 m, within 1e-4 of it (the line's stretch changes its pull at the
    drum by O(ε) = 1e-5; measured 1.3e-5)."""
    s = hoist(1.3 * BALANCE)
    st = solve_static(s, load_steps=1, at_time=0.0)
    expected = (1.3 * BALANCE / RADIUS / G - LOAD) / RHO_A
    assert st.y[s.drums["hoist"]] == pytest.approx(expected, rel=1e-4)


def test_modes_take_the_drum_as_a_coordinate():
    """Modes about the balanced static state: the drum's length is a coordinate, and its
    pay-out is the one unstable motion (a longer line weighs more), growing at
    √(ρ A g / (J/r² + m + ρ A L)) = 0.486 /s (within 1e-3: the line's stretch)."""
    from rancf.solvers.modal import natural_modes

    s = hoist(BALANCE)
    st = solve_static(s, load_steps=1, at_time=0.0)
    modes = natural_modes(s, st.y, 4, lam=st.lam)
    rate = np.sqrt(RHO_A * G / (INERTIA / RADIUS**2 + LOAD + RHO_A * L0))
    assert modes.growth_rates[0] == pytest.approx(rate, rel=1e-3)
    assert np.all(modes.growth_rates[1:] == 0.0)


def _rigid_rope(torque, t: np.ndarray) -> np.ndarray:
    """L(t) of the rigid rope: (J/r² − ρA (L − L0) + m + ρA L) L̈ = (m + ρA L) g − τ/r."""

    def rhs(x, z):
        length, rate = z
        mass = INERTIA / RADIUS**2 - RHO_A * (length - L0) + LOAD + RHO_A * length
        return [rate, ((LOAD + RHO_A * length) * G - torque(x) / RADIUS) / mass]

    sol = solve_ivp(rhs, (0.0, t[-1]), [L0, 0.0], t_eval=t, rtol=1e-10, atol=1e-12)
    return sol.y[0]


@pytest.mark.parametrize(("factor", "height"), [(1.3, 0.0), (0.7, 100.0)])
def test_torque_moves_the_load_at_the_rigid_rope_rate(factor, height):
    """30 % more torque (ramped over 0.05 s) lifts the load, 30 % less lowers it with the drum
    100 m up (where gravity's potential is zero must not matter: the rope on the drum carries
    its weight to the exit); the motion over 1 s matches the rigid rope's within 0.5 % (the
    steel line's stretch changes by (m + ρAL) L̈ / (EA/L), a few µm, and the axial waves the
    ramp starts are damped by rho_inf = 0.5; measured: 1.1e-4 m of a 0.73 m lift, 8.7e-5 m
    of a 0.73 m descent, the latter the same to 6e-12 m with the drum at the origin)."""

    def torque(x):
        return BALANCE * (1.0 + (factor - 1.0) * min(x / 0.05, 1.0))

    s = hoist(torque, top=height)
    _, res = _run(s, 1.0, 0.5)
    length = res.q[:, s.drums["hoist"]]
    rigid = _rigid_rope(torque, res.t)
    moved = abs(L0 - rigid[-1])
    assert moved > 0.7
    assert np.abs(length - rigid).max() < 5e-3 * moved


def test_energy_balance_and_mass():
    """The torque rises to 1.3 times the balance and back (sin²) over 2 s, no damping
    (rho_inf = 1): −∫ τ L̇ / r dt equals the change of kinetic (line, load, drum J(L) θ̇²/2),
    strain and gravity energy (the rope wound off the drum at the exit's height) within 0.5 %
    (measured 4e-5 of 234 J: the trapezoidal rule on the 0.05 s outputs);
    the wire's mass in the core is ρ A L(t) at every output (1e-9)."""

    def torque(x):
        return BALANCE * (1.0 + 0.3 * np.sin(np.pi * x / 2.0) ** 2)

    s = hoist(torque)
    _, res = _run(s, 2.0, 1.0, step=0.005)
    drum = s.drums["hoist"]
    t, rate = res.t, res.v[:, drum]
    power = -np.array([torque(x) for x in t]) * rate / RADIUS
    work = np.sum(0.5 * (power[1:] + power[:-1]) * np.diff(t))
    energy = res.kinetic + res.strain + res.gravity
    assert work > 10.0
    assert abs(energy[-1] - energy[0] - work) < 5e-3 * work
    sl = s.body_slice("wire")
    for i in range(len(t)):
        y = s.y_from_q(res.q[i])
        z, a = np.zeros(s.n), np.zeros(s.n)
        a[sl] = np.tile([1.0, 0.0, 0.0, 0.0], s.bodies["wire"].n_nodes)
        r1, r0 = np.empty(s.n + s.m), np.empty(s.n + s.m)
        s.core.residual(ResidualPoint(y, np.zeros(s.m), r1, z, a), ResidualOptions(t[i]))
        s.core.residual(ResidualPoint(y, np.zeros(s.m), r0, z, z), ResidualOptions(t[i]))
        mass = float((r1 - r0)[sl][0::4].sum())
        assert mass == pytest.approx(RHO_A * y[drum], rel=1e-9)


@pytest.mark.parametrize(
    ("dynamic", "strain"),
    [(True, "green_lagrange"), (False, "green_lagrange"), (True, "engineering")],
)
def test_drum_jacobian_against_central_differences(dynamic, strain):
    """Every column and row of the Jacobian (ck d/dy + cv d/dv + ca d/da) at a perturbed,
    moving state against central differences of the residual (balance rows; both axial
    strains, the drum's strain derivatives rest on their scaling in λ): steps 1e-6 in y,
    0.1 in v and a (the residual is at most quadratic in them: central differences exact up
    to round-off, 1e-16 of the 1e6 N residual over the step); within 1e-7 of the largest
    entry."""
    s = hoist(BALANCE * 1.2, strain=strain)
    n, m = s.n, s.m
    rng = np.random.default_rng(3)
    free = ~s.fixed
    y = s.y0 + 1e-3 * rng.standard_normal(n) * free
    y[s.drums["hoist"]] = 5.3
    v = 0.3 * rng.standard_normal(n) * free if dynamic else np.zeros(n)
    a = rng.standard_normal(n) * free if dynamic else np.zeros(n)
    lam = rng.standard_normal(m)

    def res(state):
        r = np.empty(n + m)
        yy, vv, aa = state
        s.core.residual(ResidualPoint(yy, lam, r, vv, aa), ResidualOptions(0.7, dynamic=dynamic))
        return r[:n]

    for k in range(3 if dynamic else 1):
        coef = [0.0, 0.0, 0.0]
        coef[k] = 1.0
        jac = np.empty((n + m) ** 2)
        s.core.dense_jacobian(StatePoint(y, v, a, lam), TangentOptions(0.7, *coef, dynamic), jac)
        jac = jac.reshape(n + m, n + m)[:n, :n]
        fd = np.zeros((n, n))
        for j in np.flatnonzero(free):
            plus, minus = [y.copy(), v.copy(), a.copy()], [y.copy(), v.copy(), a.copy()]
            h = 1e-6 * (1.0 + abs(plus[k][j])) if k == 0 else 0.1
            plus[k][j] += h
            minus[k][j] -= h
            fd[:, j] = (res(plus) - res(minus)) / (2 * h)
        sub = np.ix_(free, free)
        err = np.abs(jac[sub] - fd[sub]).max()
        assert err < 1e-7 * np.abs(fd[sub]).max(), (k, err)
        drum = s.drums["hoist"]  # the new blocks themselves are not zero
        assert np.abs(jac[drum, :drum]).max() > 0 and np.abs(jac[:drum, drum]).max() > 0


def test_static_torque_the_line_cannot_balance_is_refused():
    """Below m g r even a line of no length cannot pull the torque back: one line naming the
    winch."""
    s = hoist(0.5 * RADIUS * LOAD * G)
    with pytest.raises(InputError, match=r"winches\.hoist\.torque"):
        solve_static(s, load_steps=1, at_time=0.0)


def test_drum_in_a_scenario_file(tmp_path):
    """``[[winches]]`` with ``torque``, ``radius`` and ``inertia``: the ``winch`` sensor's
    ``NAME_length`` and ``NAME_speed`` are the drum's state (the load hangs at L plus its
    stretch, below 0.2 mm; L grows with the integral of the speed), ``NAME_tension`` the
    force of the winch's support, at the static start (m + ρ A L0) g (statics' L within 2e-4
    m of L0: the test above)."""
    from tests.scenario.test_winch_scenario import HOIST, _sensors

    lift = f"[[0.0, {BALANCE!r}], [0.05, {1.3 * BALANCE!r}], [5.0, {1.3 * BALANCE!r}]]"
    text = HOIST.replace(
        "speed = { ramp = 2.0, value = 1.0 }",
        f"torque = {{ table = {lift} }}\nradius = {RADIUS}\ninertia = {INERTIA}",
    ).replace("t_end = 4.0", "t_end = 1.0")
    text = text.replace("elements = 10", "elements = 6").replace(
        "output_step = 0.5", "output_step = 0.1"
    )
    s = _sensors(tmp_path, text)
    t, length, speed = s["t"], s["drum_length"], s["drum_speed"]
    assert length[0] == pytest.approx(L0, abs=2e-4)
    assert L0 - length[-1] > 0.5  # lifted
    assert np.all(np.abs(-s["hook_y"] - length) < 2e-4)
    mid = 0.5 * (speed[1:] + speed[:-1]) * np.diff(t)
    np.testing.assert_allclose(np.diff(length), mid, rtol=0, atol=2e-3)
    assert s["drum_tension"][0] == pytest.approx((LOAD + RHO_A * length[0]) * G, rel=1e-4)
