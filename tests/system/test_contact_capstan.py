"""Contact: the capstan (Euler-Eytelwein).  A rope over a fixed cylinder, wrap angle
pi, a 1 kg weight pinned to one end, the other end pulled down slowly by a moving support: while
the rope slips, the tension ratio of the two free spans is e^(mu phi) within 1 % (mu = 0.3:
2.5663, mu = 0.5: 4.8105); frictionless, the tensions are equal and the pressure is T / R
within 1 %.  Span tensions are the section quantities' axial force."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import PointMass
from rancf.bodies.section_outputs import SectionSampler
from rancf.bodies.time_function import TimeFunction
from rancf.mesh.routes import rope_over_pulley
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.system import Joint, Obstacle, System, contact_outputs

RP, RT, SPAN, MASS, G = 0.2, 0.002, 0.3, 1.0, 9.81  # pulley, rope radius, free spans, weight
RC = RP + RT  # the centre line's radius on the pulley (its pitch radius)
#: A synthetic-fibre rope: E = 10 GPa, a thousandth of a solid bar's bending stiffness.
SECTION = Section(np.pi * RT**2, 1e-3 * np.pi * RT**4 / 4)
MATERIAL = Material(1000.0, 1e10)


def capstan(mu: float, n_arc: int, n_span: int, speed: float, damping: float = 0.0) -> System:
    """The rope in its wrapped reference (exact arcs), weight at the left end, right end pulled
    down at ``speed`` after a 0.5 s smooth start (no gravity on the rope itself)."""
    mesh = rope_over_pulley(RC, SPAN, n_arc, n_span)
    ramp = 0.5

    def pull(t: float) -> list[float]:
        return [0.0, -speed * (t * t / (2 * ramp) if t < ramp else t - ramp / 2)]

    motion = TimeFunction.from_callable(pull).sampled(2.0, 401)
    end = Support(mesh.n_nodes - 1, "pin", motion=motion)
    rope = Model(mesh, "rancf", SECTION, MATERIAL, [end], gravity=(0.0, 0.0))  # weightless
    weight = PointMass(2, MASS, (-RC, -SPAN))
    pulley = Obstacle("cylinder", center=(0, 0), radius=RP, friction=mu, name="pulley")
    return System(
        {"rope": rope, "weight": weight},
        [Joint("pin", ("rope:start", "weight"))],
        gravity=[0, -G],
        obstacles=[pulley],
        damping=damping,
    )


def span_tensions(s: System, y: np.ndarray, sampler: SectionSampler) -> tuple[float, float]:
    """Mean axial force of the section samples in the slack (left) and tight (right) spans,
    5 cm to 25 cm below the pulley's centre."""
    yr = y[s.body_slice("rope")]
    force, pos = sampler.values(yr)[:, 1], sampler.positions(yr)
    band = (pos[:, 1] < -0.05) & (pos[:, 1] > -0.25)
    return float(force[band & (pos[:, 0] < 0)].mean()), float(force[band & (pos[:, 0] > 0)].mean())


def _run(s: System, t_end: float):
    opts = DynamicOptions(t_end=t_end, step=1e-3, rho_inf=0.5, max_newton=25, output_step=0.01)
    res = integrate(s, opts)
    assert res.status.value == "completed", res.message
    return res


@pytest.mark.parametrize(("mu", "ratio"), [(0.3, 2.5663), (0.5, 4.8105)])
def test_capstan_ratio_while_slipping(mu, ratio):
    """Pulled at 2 cm/s (20 times the friction's slip velocity): over 1 s of steady slip the
    span tensions' ratio is e^(mu pi) within 1 % (and the slack span carries the weight)."""
    assert ratio == pytest.approx(np.exp(mu * np.pi), abs=1e-4)
    s = capstan(mu, 32, 15, 0.02)
    res = _run(s, 1.5)
    sampler = SectionSampler(s.bodies["rope"], 4)
    late = np.flatnonzero(res.t >= 0.5)
    tens = np.array([span_tensions(s, s.y_from_q(res.q[i]), sampler) for i in late])
    assert np.all(tens[:, 1] / tens[:, 0] == pytest.approx(ratio, rel=0.01))
    assert np.mean(tens[:, 1] / tens[:, 0]) == pytest.approx(ratio, rel=0.005)
    assert np.mean(tens[:, 0]) == pytest.approx(MASS * G, rel=0.01)
    v_weight = res.v[late][:, s.body_slice("weight")][:, 1]
    assert v_weight == pytest.approx(0.02, rel=0.05)  # it is lifted: the rope slips


def _at_rest(n_arc: int, n_span: int):
    s = capstan(0.0, n_arc, n_span, 0.0, damping=20.0)
    res = _run(s, 1.0)
    y = s.y_from_q(res.q[-1])
    assert res.kinetic[-1] < 1e-9
    return s, y


def test_frictionless_capstan_equal_tensions_and_pressure():
    """Frictionless, held at rest (damped): equal span tensions T = m g, and the pressure on the
    wrap is T / R_c (R_c = R + r, the centre line's radius) within 1 % at every point but those
    within 15 degrees of the spans (where the rope's small bending stiffness shifts the load)."""
    s, y = _at_rest(32, 15)
    tl, tr = span_tensions(s, y, SectionSampler(s.bodies["rope"], 4))
    assert tl == pytest.approx(MASS * G, rel=1e-3)
    assert tr == pytest.approx(tl, rel=1e-3)
    pts = np.empty(8 * s.bodies["rope"].n_el * 8)
    s.contact.points(0, y, None, pts)
    pts = pts.reshape(-1, 8)
    angle = np.degrees(np.arctan2(pts[:, 1], pts[:, 0]))
    wrap = (angle > 15) & (angle < 165)
    assert pts[wrap, 4] == pytest.approx(tl / RC, rel=0.01)
    assert contact_outputs(s, y)["pulley"].normal == pytest.approx([0, 2 * tl], rel=1e-3, abs=1e-2)


def test_four_elements_wrap_smoothly():
    """Four (exact-arc) elements over the half circle: every contact point of the wrap is in
    contact, the centre line's distance from the pulley varies by less than 2e-5 of the rope's
    radius along it (contact along the curve, not at the nodes: it sinks uniformly by about
    sqrt(2 d p / k)), and the pulley's force is 2 T."""
    s, y = _at_rest(4, 3)
    pts = np.empty(8 * s.bodies["rope"].n_el * 8)
    s.contact.points(0, y, None, pts)
    pts = pts.reshape(-1, 8)
    angle = np.degrees(np.arctan2(pts[:, 1], pts[:, 0]))
    wrap = (angle > 5) & (angle < 175)
    assert wrap.sum() >= 28  # every point of the four arc elements but the ends'
    assert np.all(pts[wrap, 4] > 0)  # in contact everywhere on the wrap
    assert np.ptp(pts[wrap, 3]) < 2e-5 * RT
    tl, tr = span_tensions(s, y, SectionSampler(s.bodies["rope"], 4))
    depth = np.sqrt(2 * 1e-3 * RT * (tl / RC) / (MATERIAL.youngs_modulus / 10))
    assert -np.mean(pts[wrap, 3]) == pytest.approx(depth, rel=0.05)
    assert contact_outputs(s, y)["pulley"].normal[1] == pytest.approx(tl + tr, rel=1e-3)


def test_atwood_machine_on_a_turning_pulley():
    """The obstacle carried by a rigid body: the rope over a pulley (a disc of 2 kg pinned to the
    ground, friction 0.5: the rope sticks) with 1.2 kg and 1 kg at its ends.  The masses
    accelerate at a = (m1 - m2) g / (m1 + m2 + J / R_c^2 + m_rope) within 1 %, and the pulley
    turns with the rope: R_c omega = v.  (Straight elements bend onto the pulley as it turns:
    with 8 elements on the wrap the acceleration is 6 % low, with 16 1.5 %, with 32 0.3 %.)"""
    from rancf.bodies.rigid import RigidBody

    n_span, n_arc = 12, 32
    mesh = rope_over_pulley(RC, SPAN, n_arc, n_span)
    rope = Model(mesh, "rancf", SECTION, Material(100.0, 1e10), gravity=(0.0, 0.0))  # weightless
    disc, j = 2.0, 0.5 * 2.0 * RP**2
    bodies = {
        "rope": rope,
        "heavy": PointMass(2, 1.2, (-RC, -SPAN)),
        "light": PointMass(2, 1.0, (RC, -SPAN)),
        "pulley": RigidBody(2, disc, j, (0.0, 0.0), 0.0),
    }
    joints = [
        Joint("pin", ("rope:start", "heavy")),
        Joint("pin", ("rope:end", "light")),
        Joint("pin", ("pulley", "ground")),
    ]
    wheel = Obstacle("cylinder", center=(0, 0), radius=RP, friction=0.5, body="pulley")
    s = System(bodies, joints, gravity=[0, -G], obstacles=[wheel])
    res = _run(s, 0.15)
    m_rope = 100.0 * SECTION.area * rope.mesh.arc_lengths().sum()
    a = (1.2 - 1.0) * G / (1.2 + 1.0 + j / RC**2 + m_rope)
    late = res.t >= 0.05  # after the start's transient (the unstressed rope snaps taut)
    v_heavy = -res.v[late][:, s.body_slice("heavy")][:, 1]
    fit = np.polyfit(res.t[late], v_heavy, 1)
    assert fit[0] == pytest.approx(a, rel=0.01)
    omega = res.v[late][:, s.body_slice("pulley")][:, 2]  # counterclockwise
    assert RC * omega == pytest.approx(v_heavy, rel=0.01, abs=1e-3)
