"""A driven drum whose line is in the fluid (docs/derivations/variable-length.md §3.5): the
hoist of test_drum.py (10 kg on a steel wire of radius 5 mm, drum radius 0.2 m, inertia
0.5 kg m²) lowered into sea water with a hydrodynamic diameter of 2 cm (the wire weighs
0.616 kg/m in air, 0.294 kg/m in water).

* the fluid's share of the drum's balance and of its Jacobian against central differences;
* statics puts the length where r T = τ with the line's weight in water (and in air above the
  surface);
* a torque lifts the load at the rigid rope's rate with the line's buoyancy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import PointMass
from rancf.bodies.time_function import TimeFunction
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.factories import mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.static import solve_static
from rancf.system import Joint, System, Winch
from rancf.system.fluid import Fluid, Hydro

G, LOAD, L0, RADIUS, INERTIA = 9.81, 10.0, 5.0, 0.2, 0.5
WIRE_RADIUS, DIAMETER = 0.005, 0.02
RHO_A = 7850.0 * math.pi * WIRE_RADIUS**2
WET = RHO_A - 1025.0 * math.pi * DIAMETER**2 / 4.0  # [kg/m]


def hoist(torque, n_el=6, surface=None, fluid=True, hydro=(1.2, 0.5, 1.0, 0.3), current=None):
    """The wire L0 long from the drum at the origin straight down to the load; in sea water
    (its still surface at ``surface``, None: everywhere) with the drag and added-mass
    coefficients ``hydro`` (normal, axial, normal, axial) unless ``fluid`` is False."""
    g = [0.0, -G]
    wire = Model(
        mesh_line([0, 0], [0, -L0], n_el),
        "ancf",
        Section.circular(WIRE_RADIUS),
        Material(7850.0, 2.0e11),
        [Support(0, "pin")],
        gravity=g,
    )
    f = torque if isinstance(torque, float) else TimeFunction.from_callable(torque)
    water = {}
    if fluid:
        water = {
            "fluid": Fluid(1025.0, surface=surface, current=current),
            "hydro": {"wire": Hydro(DIAMETER, *hydro)},
        }
    return System(
        {"wire": wire, "load": PointMass(2, LOAD, (0.0, -L0))},
        [Joint("pin", ("wire:end", "load"))],
        gravity=g,
        winches=[Winch("hoist", "wire:start", torque=f, radius=RADIUS, inertia=INERTIA)],
        horizon=2.0,
        **water,
    )


def _jacobians(s, state, dynamic, k):
    """The core's Jacobian ``d/dy``, ``d/dv`` or ``d/da`` (``k``) of the balance rows and its
    central differences (steps 1e-5 in y, 1e-3 in v and a), and the residual."""
    n, m = s.n, s.m
    lam = np.random.default_rng(5).standard_normal(m)

    def res(x):
        r = np.empty(n + m)
        y, v, a = x
        s.core.residual(ResidualPoint(y, lam, r, v, a), ResidualOptions(0.7, 1.0, False, dynamic))
        return r[:n]

    coef = [0.0, 0.0, 0.0]
    coef[k] = 1.0
    jac = np.empty((n + m) ** 2)
    s.core.dense_jacobian(StatePoint(*state, lam), TangentOptions(0.7, *coef, dynamic), jac)
    fd = np.zeros((n, n))
    for j in np.flatnonzero(~s.fixed):
        plus, minus = [x.copy() for x in state], [x.copy() for x in state]
        h = 1e-5 * (1.0 + abs(plus[k][j])) if k == 0 else 1e-3
        plus[k][j] += h
        minus[k][j] -= h
        fd[:, j] = (res(plus) - res(minus)) / (2 * h)
    return jac.reshape(n + m, n + m)[:n, :n], fd, res(state)


@pytest.mark.parametrize(("dynamic", "surface"), [(True, None), (True, -2.0), (False, -2.0)])
def test_the_fluids_share_of_the_drum_against_central_differences(dynamic, surface):
    """At a perturbed, moving state in a current of 0.4 m/s: the fluid's part of the drum's
    residual (the system's residual less the same system's without the fluid) is not zero,
    and the fluid's part of every Jacobian block (ck d/dy, cv d/dv, ca d/da: the drum's row,
    its column in the line's rows and the line's own) matches central differences within 1e-5
    of its largest entry (the residual is 2e6 N: the differences' round-off)."""
    wet = hoist(1.2 * RADIUS * LOAD * G, surface=surface, current=(0.4, 0.0))
    dry = hoist(1.2 * RADIUS * LOAD * G, fluid=False)
    n, free = wet.n, ~wet.fixed
    rng = np.random.default_rng(3)
    y = wet.y0 + 1e-3 * rng.standard_normal(n) * free
    drum = wet.drums["hoist"]
    y[drum] = 5.3
    v = 0.3 * rng.standard_normal(n) * free if dynamic else np.zeros(n)
    a = rng.standard_normal(n) * free if dynamic else np.zeros(n)
    sub = np.ix_(free, free)
    for k in range(3 if dynamic else 1):
        j1, f1, r1 = _jacobians(wet, [y, v, a], dynamic, k)
        j0, f0, r0 = _jacobians(dry, [y, v, a], dynamic, k)
        assert abs(r1[drum] - r0[drum]) > 1.0
        fluid, fd = (j1 - j0)[sub], (f1 - f0)[sub]
        assert np.abs(fluid - fd).max() < 1e-5 * np.abs(fd).max(), k
        if k < 2:
            assert np.abs(fd[-1, :-1]).max() > 0.01  # the drum's row has a fluid part


@pytest.mark.parametrize(("surface", "n_el", "tol"), [(None, 12, 1e-4), (-2.0, 48, 1e-3)])
def test_static_length_balances_the_torque_with_the_weight_in_water(surface, n_el, tol):
    """A torque r g (m + μ) with μ the line's mass less the water it displaces over 7 m (wholly
    submerged; or 2 m in air above the surface at -2 m, 5 m below): statics puts the drum's
    length at 7 m, r T = τ with the line's weight in water (the dry weight would balance at
    3.3 m), within 1e-4 (the stretch) and, crossing the surface, 1e-3 at 48 elements (the
    buoyancy acts at the Gauss points under water: 0.5 %, 0.2 %, 0.04 % at 12, 24, 48)."""
    above = 0.0 if surface is None else 2.0
    tau = RADIUS * G * (LOAD + RHO_A * above + WET * (7.0 - above))
    s = hoist(tau, n_el=n_el, surface=surface)
    st = solve_static(s, load_steps=1, at_time=0.0)
    assert st.y[s.drums["hoist"]] == pytest.approx(7.0, rel=tol)


def test_torque_lifts_the_load_in_water_at_the_rigid_rope_rate():
    """20 % more torque than the balance in water (ramped over 0.05 s), the line moving along
    itself (no axial drag or added mass): the drum's length over 1 s follows the rigid rope
    (J/r² − ρA (L − L0) + m + ρA L) L̈ = (m + μ L) g − τ/r, μ the mass less the displaced
    water, within 0.5 % of the lift (measured 1.6e-4 m of 0.42 m; with the dry weight the
    rigid rope ends 0.31 m elsewhere)."""
    balance = RADIUS * G * (LOAD + WET * L0)

    def torque(x):
        return balance * (1.0 + 0.2 * min(x / 0.05, 1.0))

    s = hoist(torque, hydro=(1.2, 0.0, 1.0, 0.0))
    st = solve_static(s, load_steps=1, at_time=0.0)
    opts = DynamicOptions(t_end=1.0, step=0.01, rho_inf=0.5, output_step=0.05)
    res = integrate(s, opts, initial=st.y)
    assert res.status.value == "completed", res.message
    length = res.q[:, s.drums["hoist"]]

    def rhs(x, z):
        mass = INERTIA / RADIUS**2 - RHO_A * (z[0] - L0) + LOAD + RHO_A * z[0]
        return [z[1], ((LOAD + WET * z[0]) * G - torque(x) / RADIUS) / mass]

    rigid = solve_ivp(rhs, (0.0, 1.0), [L0, 0.0], t_eval=res.t, rtol=1e-10, atol=1e-12).y[0]
    lift = L0 - rigid[-1]
    assert lift > 0.3
    assert np.abs(length - rigid).max() < 5e-3 * lift
