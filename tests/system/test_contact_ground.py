"""Contact: a steel cable dropped on the ground comes to rest on it (reaction = weight,
penetration far below 1 % of the radius); with ``rho_inf = 1`` and no friction the energy never
grows; statics on the ground."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.mesh.factories import mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.static import solve_static
from rancf.system import Obstacle, System, contact_history, contact_outputs

R, L, RHO, E, G = 0.002, 1.0, 7850.0, 2e11, 9.81  # steel, radius 2 mm


def _cable(height: float, tilt: float, supports=()) -> tuple[System, float]:
    """A 1 m cable of 20 elements at ``height`` above the ground (one end ``tilt`` higher)."""
    mesh = mesh_line([0.0, R + height], [L, R + height + tilt], 20)
    cable = Model(
        mesh, "rancf", Section.circular(R), Material(RHO, E), list(supports), gravity=[0, -G]
    )
    ground = Obstacle("plane", point=(0, 0), normal=(0, 1), name="ground")
    s = System({"cable": cable}, obstacles=[ground], gravity=[0, -G])
    weight = RHO * np.pi * R**2 * np.hypot(L, tilt) * G
    return s, weight


def test_dropped_cable_comes_to_rest_on_the_ground():
    """Dropped from 2 cm, one end 5 cm higher: it lands end first, comes to rest in 1 s; the
    ground then carries the weight (1e-3), and the penetration stays below 1 % of the radius
    throughout (the default stiffness E / 10 and onset 1e-3 r)."""
    s, weight = _cable(0.02, 0.05)
    opts = DynamicOptions(t_end=1.0, step=1e-3, rho_inf=0.5, max_newton=25, output_step=5e-3)
    res = integrate(s, opts)
    assert res.status.value == "completed", res.message
    assert res.n_rejected == 0  # the step is kept through the impacts
    hist = contact_history(s, res.q, res.v)["ground"]
    hit = np.flatnonzero(hist["length"] > 0)
    assert hit.size and res.t[hit[0]] < 0.1  # it did fall onto the ground
    assert hist["penetration"].max() < 0.01 * R
    assert res.kinetic[-1] < 1e-12 * weight * L  # at rest
    assert hist["normal"][-1] == pytest.approx([0.0, weight], rel=1e-3, abs=1e-3 * weight)
    assert hist["friction"][-1] == pytest.approx([0.0, 0.0])
    assert hist["length"][-1] == pytest.approx(np.hypot(L, 0.05), rel=1e-3)


def test_energy_never_grows_with_rho_inf_one_and_no_friction():
    """Dropped flat from 2 cm with rho_inf = 1, no friction and no damping: the cable lands,
    bounces off and falls again; kinetic + strain + gravity + penalty energy never exceeds its
    initial value by more than round-off (the step's pressure is the discrete gradient of the
    penalty's potential).  (Tilted, the impact excites bending and the midpoint rule's error of
    the elastic forces - not of the contact - lets the energy grow: the report has numbers.)"""
    s, weight = _cable(0.02, 0.0)
    opts = DynamicOptions(t_end=0.4, step=1e-3, rho_inf=1.0, max_newton=25)
    res = integrate(s, opts)
    assert res.status.value == "completed", res.message
    hist = contact_history(s, res.q)["ground"]
    assert np.any(hist["length"] > 0.9 * L)  # it was on the ground, all along its length
    scale = weight * 0.02  # the energy the fall releases
    e = res.total_energy
    assert res.kinetic.max() > 0.5 * scale
    assert np.max(e - e[0]) <= 1e-9 * scale
    assert np.max(np.diff(e)) <= 1e-9 * scale


@pytest.mark.parametrize("rho", [0.0, 0.5, 0.9])
def test_bounce_energy_never_grows_with_numerical_damping(rho):
    """Dropped flat from 2 cm without friction or damping: with rho_inf < 1 the cable lands,
    bounces and comes to rest, and its energy (kinetic + strain + gravity + penalty) never
    rises above the initial one (the contact's force blended over the step, the other forces at
    real states: a balance at the new time alone gains energy in such impacts)."""
    s, weight = _cable(0.02, 0.0)
    res = integrate(s, DynamicOptions(t_end=0.6, step=1e-3, rho_inf=rho, max_newton=25))
    assert res.status.value == "completed", res.message
    scale = weight * 0.02  # the energy the fall releases
    e = res.total_energy
    assert res.kinetic.max() > 0.5 * scale
    assert np.max(e - e[0]) <= 1e-9 * scale
    assert res.kinetic[-1] < 1e-12 * scale  # at rest


def test_static_cable_on_the_ground():
    """Statics: a cable pinned at one end lies on the ground under its weight; the ground and the
    pin carry the weight exactly, and away from the pin it rests at the penalty's depth
    sqrt(2 d q / k) (q: weight per length, k = E / 10, d = 1e-3 r)."""
    s, weight = _cable(0.0, 0.0, [Support(0, "pin")])
    st = solve_static(s, load_steps=1)
    out = contact_outputs(s, st.y)["ground"]
    r = np.empty(s.n + s.m)
    s.core.residual(ResidualPoint(st.y, np.zeros(s.m), r), ResidualOptions(0.0, dynamic=False))
    pin = r[1]  # the held coordinate's residual: the pin's reaction
    assert out.normal[1] + pin == pytest.approx(weight, rel=1e-9)
    assert out.normal[1] > 0.95 * weight
    q, k, d = weight / L, E / 10, 1e-3 * R
    pts = np.empty(8 * 20 * 8)
    s.contact.points(0, st.y, None, pts)
    pts = pts.reshape(-1, 8)
    far = pts[:, 0] > 0.5  # the pin's bending disturbance has decayed
    assert -pts[far, 3] == pytest.approx(np.sqrt(2 * d * q / k), rel=1e-6)
    assert pts[far, 4] == pytest.approx(q, rel=1e-6)


@pytest.mark.parametrize("rate", [-0.01, 0.002, 0.5])
def test_linear_normal_damping_adds_to_the_pressure_and_never_pulls(rate):
    """``damping_normal`` (MoorDyn's seabed cBot, per unit contact area): a straight cable sunk
    1e-4 m into the ground everywhere, moving with ``rate`` along the normal, is pressed by
    ``(k (δ - d/2) - c D ġ) L`` (the onset d below δ, D the diameter), or not at all where a
    fast separation would pull."""
    depth, k, c_n = 1e-4, 1e6, 5e5
    cable = Model(
        mesh_line([0.0, R - depth], [L, R - depth], 10),
        "rancf",
        Section.circular(R),
        Material(RHO, E),
    )
    ground = Obstacle(
        "plane",
        point=(0, 0),
        normal=(0, 1),
        stiffness=k,
        onset=1e-6,
        damping_normal=c_n,
        name="ground",
    )
    s = System({"cable": cable}, obstacles=[ground])
    y, v = s.y0.copy(), np.zeros(s.n)
    v[1::4] = rate  # every node's vertical velocity (the gradients do not move)
    got = contact_outputs(s, y, v)["ground"].normal[1]
    want = max(k * (depth - 0.5e-6) - c_n * 2.0 * R * rate, 0.0) * L
    assert got == pytest.approx(want, rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("depth_in_onsets", [0.0, 0.25, 0.5, 1.0, 2.0])
def test_linear_normal_damping_ramps_in_over_the_onset(depth_in_onsets):
    """Within the onset depth d the linear normal damping grows with the elastic pressure,
    ``s = min(p_k / (k d / 2), 1)``: a cable approaching the ground (rate -0.01 m/s) sunk by
    a fraction of d is pressed by ``(p_k + s c D |ġ|) L``, which is zero at the surface (no
    jump where a point comes into contact) and the whole damping from d on."""
    k, d, c_n, rate = 1e6, 1e-6, 5e5, -0.01
    depth = depth_in_onsets * d
    cable = Model(
        mesh_line([0.0, R - depth], [L, R - depth], 10),
        "rancf",
        Section.circular(R),
        Material(RHO, E),
    )
    ground = Obstacle(
        "plane",
        point=(0, 0),
        normal=(0, 1),
        stiffness=k,
        onset=d,
        damping_normal=c_n,
        name="ground",
    )
    s = System({"cable": cable}, obstacles=[ground])
    y, v = s.y0.copy(), np.zeros(s.n)
    v[1::4] = rate
    got = contact_outputs(s, y, v)["ground"].normal[1]
    p_k = k * depth**2 / (2 * d) if depth <= d else k * (depth - d / 2)
    ramp = min(p_k / (k * d / 2), 1.0)
    want = (p_k - ramp * c_n * 2.0 * R * rate) * L
    assert got == pytest.approx(want, rel=1e-9, abs=1e-12)
