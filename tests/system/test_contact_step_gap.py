"""The gap of a time step on a curved obstacle: a cable segment pressed into a circle (a fixed
sheave, or a pulley on a rigid body turning with it) and turned rigidly about its centre within
the step keeps every point's gap, so the step's contact force keeps its size.  With the gaps of
the step's two ends blended (the integrator's form) it does, to round-off, in the residual and
in the outputs; with the gap of the blended positions (a chord of the circle,
``step_alpha_f = 0``) the force grows by the penalty times the chord's depth
``αf (1 − αf) ρ θ² / 2`` over the contact length."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.rigid import RigidBody
from rancf.mesh.factories import mesh_line
from rancf.system import Obstacle, System, contact_outputs

R, RT, DEPTH, HALF, K = 0.5, 0.01, 2e-3, 0.02, 1e7


def _sheave(carried: bool) -> tuple[System, float]:
    """A short straight cable (ANCF, two elements) pressed DEPTH into a circle of radius R at
    the top, fixed or on a rigid body (the pulley) at the origin; returns the system and the
    radius of the cable's midpoint."""
    rho = R + RT - DEPTH
    cable = Model(
        mesh_line([-HALF, rho], [HALF, rho], 2),
        "ancf",
        Section.circular(RT),
        Material(1000.0, 1e9),
        [],
    )
    where = {"center": (0, 0), "radius": R, "stiffness": K, "onset": 1e-5, "name": "sheave"}
    bodies: dict = {"cable": cable}
    if carried:
        bodies["pulley"] = RigidBody(2, 1.0, 0.1, (0.0, 0.0), 0.3)
        where["body"] = "pulley"
    return System(bodies, obstacles=[Obstacle("cylinder", **where)]), rho


def _turned(system: System, y: np.ndarray, angle: float) -> np.ndarray:
    """The state turned rigidly by angle about the origin: the cable's positions and gradients
    (the 2-vectors of ANCF's nodes) and the pulley's angle."""
    c, s = np.cos(angle), np.sin(angle)
    out = y.copy()
    pairs = y[system.body_slice("cable")].reshape(-1, 2)
    turned = np.column_stack([c * pairs[:, 0] - s * pairs[:, 1], s * pairs[:, 0] + c * pairs[:, 1]])
    out[system.body_slice("cable")] = turned.ravel()
    if "pulley" in system.names:
        out[system.body_slice("pulley")][2] += angle
    return out


def _force(system: System, y0: np.ndarray, y1: np.ndarray, af: float) -> tuple[float, float]:
    """The size of the step's total contact force from the residual (the rows of the nodes'
    positions summed) and from the outputs, for the step from y0 to y1 (α point blended)."""
    yf = (1.0 - af) * y1 + af * y0
    vf = np.zeros_like(y1)
    r = np.empty(system.n)
    system.contact.assemble(yf, vf, y1, 1.0 - af, 0.0, r)
    rc = r[system.body_slice("cable")]
    total = -np.array([rc[0::4].sum(), rc[1::4].sum()])
    out = contact_outputs(system, yf, vf, y1)["sheave"]
    return float(np.linalg.norm(total)), float(np.linalg.norm(out.normal))


@pytest.mark.parametrize("carried", [False, True], ids=["fixed", "on-a-pulley"])
@pytest.mark.parametrize("rho_inf", [0.5, 0.9, 1.0])
def test_a_turn_within_the_step_keeps_the_contact_force(rho_inf, carried):
    system, rho = _sheave(carried)
    af = rho_inf / (1.0 + rho_inf)
    theta = 0.05  # a rope at 10 m/s over a 0.5 m sheave with 2.5 ms steps
    y1 = system.y0.copy()
    y0 = _turned(system, y1, -theta)
    system.contact.step_alpha_f = af
    still = _force(system, y1, y1, af)
    turned = _force(system, y0, y1, af)
    assert still[0] > 0.5 * K * DEPTH * 2 * HALF  # pressed in along its length
    np.testing.assert_allclose(turned, still, rtol=1e-9)
    np.testing.assert_allclose(still[1], still[0], rtol=1e-9)
    # the gap of the blended positions: short by the chord's depth, the force high by k times it
    system.contact.step_alpha_f = 0.0
    chord = _force(system, y0, y1, af)
    excess = K * af * (1.0 - af) * rho * theta**2 / 2.0 * 2 * HALF
    assert (chord[0] - still[0]) / excess == pytest.approx(1.0, rel=0.02)
    assert chord[1] == pytest.approx(chord[0], rel=1e-9)
