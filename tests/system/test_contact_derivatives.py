"""Contact: the tangent of the contact forces against central differences of the
residual, for fixed obstacles and obstacles carried by rigid bodies, with friction and damping,
in 2D and 3D, in statics, in dynamics at one state, and with the discrete gradient over a step;
the potential energy against the forces; objectivity of the law."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import RigidBody
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.factories import mesh_line
from rancf.system import Obstacle, System, contact_outputs

SEC, MAT = Section.circular(0.01), Material(1000.0, 1e7)
ROD = Material(1000.0, 1e7, poisson_ratio=0.3)


def planar() -> System:
    """A clamped cable (rotated blocks) over a plane, a fixed circle and a wheel's circle (the
    last two with deep onsets: points on both pieces of the penalty)."""
    cable = Model(
        mesh_line([0, 0], [1, 0], 4), "rancf", SEC, MAT, [Support(0, "clamp")], gravity=[0, -9.81]
    )
    wheel = RigidBody(2, 1.0, 0.01, (0.7, -0.1), 0.2)
    obs = [
        Obstacle(
            "plane",
            point=(0, -0.005),
            normal=(0.1, 1),
            friction=0.3,
            damping=3.0,
            damping_normal=2e5,
            name="ground",
        ),
        Obstacle(
            "cylinder", center=(0.5, -0.2), radius=0.195, friction=0.5, onset=4e-3, name="post"
        ),
        Obstacle(
            "cylinder",
            center=(0.0, 0.0),
            radius=0.095,
            friction=0.4,
            body="wheel",
            damping=2.0,
            onset=3e-3,
            name="wheel",
        ),
    ]
    return System({"cable": cable, "wheel": wheel}, obstacles=obs, gravity=[0, -9.81])


def spatial() -> System:
    """A clamped rod and a cable against a plane, a cylinder and a sphere on a rigid body."""
    rod = Model(mesh_line([0, 0, 0], [1, 0, 0], 3), "rod", SEC, ROD, [Support(0, "clamp")])
    cable = Model(mesh_line([0, 0.3, 0], [1, 0.3, 0.05], 3), "rancf", SEC, MAT, [])
    rot = np.array([[0.8, -0.6, 0.0], [0.6, 0.8, 0.0], [0.0, 0.0, 1.0]])
    ball = RigidBody(
        3, 2.0, (0.1, 0.2, 0.3), (0.5, 0.15, -0.1), rot.tolist(), angular_velocity=(0.3, -0.2, 0.5)
    )
    obs = [
        Obstacle(
            "plane",
            point=(0, 0, -0.005),
            normal=(0.1, 0.0, 1),
            friction=0.3,
            damping=2.0,
            name="ground",
        ),
        Obstacle(
            "cylinder",
            center=(0.8, 0.0, 0.2),
            radius=0.195,
            axis=(0.1, 1.0, 0.0),
            friction=0.5,
            onset=2e-2,
            damping_normal=5e4,
            name="bar",
        ),
        Obstacle(
            "sphere",
            center=(0.0, 0.0, 0.01),
            radius=0.195,
            friction=0.4,
            body="ball",
            damping=1.0,
            name="ball",
        ),
    ]
    return System({"rod": rod, "cable": cable, "ball": ball}, obstacles=obs)


def _state(s: System, rng: np.random.Generator, speed: float = 0.3):
    y = s.y0 + 1e-3 * rng.standard_normal(s.n)
    v = speed * rng.standard_normal(s.n)
    y[s.fixed], v[s.fixed] = s.y0[s.fixed], 0.0
    return y, v


def _residual(s: System, y, v, a, dynamic=True) -> np.ndarray:
    r = np.empty(s.n + s.m)
    assert s.core.residual(
        ResidualPoint(y, np.zeros(s.m), r, v, a), ResidualOptions(0.3, dynamic=dynamic)
    )
    return r[: s.n]


def _check(jac: np.ndarray, fd: np.ndarray, free: np.ndarray, r: float, h: float = 1e-6) -> None:
    """Agreement to 1e-7 of the largest entry, above the differences' round-off (about
    1e-16 |r| / h; 1e-15 |r| / h with a margin)."""
    sub = np.ix_(free, free)
    scale = max(1.0, np.abs(fd[sub]).max())
    err = np.abs(jac[sub] - fd[sub]).max()
    assert err <= 1e-7 * scale + 1e-15 * r / h, (err, scale, r)


@pytest.mark.parametrize("build", [planar, spatial])
@pytest.mark.parametrize("which", ["y", "v", "static"])
@pytest.mark.parametrize("speed", [0.3, 3e-4])
def test_system_tangent_with_contact(build, which, speed, rng):
    """ck d/dy and cv d/dv of the whole balance (contact included) against differences, sliding
    fast and near the friction's regularization (slip velocity 1e-4)."""
    s = build()
    y, v = _state(s, rng, speed)
    a = rng.standard_normal(s.n)
    out = contact_outputs(s, y, v)
    assert all(c.length > 0 for c in out.values()), "every obstacle must be touched"
    dyn = which != "static"
    ck, cv = (0.0, 1.0) if which == "v" else (1.0, 0.0)
    dense = np.empty((s.n + s.m) ** 2)
    assert s.core.dense_jacobian(
        StatePoint(y, v, a, np.zeros(s.m)), TangentOptions(0.3, ck, cv, 0.0, dyn), dense
    )
    jac = dense.reshape(s.n + s.m, -1)[: s.n, : s.n]
    fd = np.zeros((s.n, s.n))
    step = 1e-8 if which == "v" else 1e-6  # the friction varies on the scale of 1e-4 in v
    for j in np.flatnonzero(~s.fixed):
        x = v if which == "v" else y
        h = step * (1 + abs(x[j]))
        xp, xm = x.copy(), x.copy()
        xp[j] += h
        xm[j] -= h
        if which == "v":
            fd[:, j] = (_residual(s, y, xp, a) - _residual(s, y, xm, a)) / (2 * h)
        else:
            fd[:, j] = (_residual(s, xp, v, a, dyn) - _residual(s, xm, v, a, dyn)) / (2 * h)
    _check(jac, fd, ~s.fixed, np.abs(_residual(s, y, v, a, dyn)).max(), step)


@pytest.mark.parametrize("blend", [False, True], ids=["gap-at-yf", "gaps-blended"])
@pytest.mark.parametrize("build", [planar, spatial])
def test_discrete_gradient_tangent(build, blend, rng):
    """Over a step: y_f = (1 - af) y1 + af y0, v_f = v* + c (y1 - y*), the pressure the mean over
    [2 g_s - g(y1), g(y1)], g_s = g(y_f) or (fixed curved obstacles, step_alpha_f = af) the
    blend (1 - af) g(y1) + af g(y0); d r / d y1 (ck = 1 - af, cv = c) against differences in
    y1."""
    s = build()
    y1, v = _state(s, rng)
    y0 = y1 + 2e-4 * rng.standard_normal(s.n)
    y0[s.fixed] = y1[s.fixed]
    af, c = 0.4, 30.0
    s.contact.step_alpha_f = af if blend else 0.0
    ystar = y1.copy()

    def contact_r(yy1: np.ndarray, jac: np.ndarray | None = None) -> np.ndarray:
        yf = (1 - af) * yy1 + af * y0
        vf = v + c * (yy1 - ystar)
        r = np.empty(s.n)
        s.contact.assemble(yf, vf, yy1, 1 - af, c, r, jac)
        return r

    jac = np.empty(s.n * s.n)
    contact_r(y1, jac)
    jac = jac.reshape(s.n, s.n)
    fd = np.zeros((s.n, s.n))
    for j in np.flatnonzero(~s.fixed):
        h = 1e-6 * (1 + abs(y1[j]))
        yp, ym = y1.copy(), y1.copy()
        yp[j] += h
        ym[j] -= h
        fd[:, j] = (contact_r(yp) - contact_r(ym)) / (2 * h)
    assert np.abs(fd).max() > 0
    _check(jac, fd, ~s.fixed, np.abs(contact_r(y1)).max())


@pytest.mark.parametrize("build", [planar, spatial])
def test_static_forces_are_the_energy_gradient(build, rng):
    """Frictionless statics: the contact forces are minus the gradient of the penalty energy
    (central differences of contact.energy)."""
    s = build()
    y, _ = _state(s, rng)
    r = np.empty(s.n)
    s.contact.assemble(y, None, y, 1.0, 0.0, r)
    grad = np.zeros(s.n)
    for j in np.flatnonzero(~s.fixed):
        h = 1e-7 * (1 + abs(y[j]))
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        grad[j] = (s.contact.energy(yp) - s.contact.energy(ym)) / (2 * h)
    free = ~s.fixed
    assert np.allclose(r[free], grad[free], rtol=0, atol=1e-6 * np.abs(grad).max())


def test_discrete_gradient_balances_the_energy_of_a_plane(rng):
    """Plane contact: the work of the discrete-gradient force over a step, F . (y1 - y0), is the
    change of the penalty energy exactly (to round-off), entering or leaving contact."""
    s = planar()
    for _ in range(5):
        y0, _v = _state(s, rng)
        y1 = y0 + 3e-3 * rng.standard_normal(s.n)
        y1[s.fixed] = y0[s.fixed]
        ground = System(s.bodies, obstacles=[s.obstacles[0]], gravity=[0, -9.81])
        r = np.empty(s.n)
        ground.contact.assemble(0.5 * (y0 + y1), np.zeros(s.n), y1, 0.5, 0.0, r)
        work = -r @ (y1 - y0)  # the contact forces' work: minus the energy change
        de = ground.contact.energy(y1) - ground.contact.energy(y0)
        assert -work == pytest.approx(de, rel=1e-10, abs=1e-12 * abs(ground.contact.energy(y0)))


def test_rigid_motion_leaves_the_contact_forces_unchanged(rng):
    """Objectivity: moving a body and its obstacles rigidly rotates the contact forces with them
    (a 2D system turned by 30 degrees and shifted; the frictionless plane, circle and a wheel)."""
    a = np.deg2rad(30.0)
    rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    shift = np.array([0.3, -0.2])

    def build(turned: bool) -> System:
        tr = (lambda x: rot @ np.asarray(x) + shift) if turned else (lambda x: np.asarray(x))
        start, end = tr([0.0, 0.0]), tr([1.0, 0.0])
        cable = Model(mesh_line(start, end, 4), "rancf", SEC, MAT, [])
        wheel = RigidBody(2, 1.0, 0.01, tr([0.7, -0.1]), 0.2 + (a if turned else 0.0))
        normal = (rot @ [0.1, 1.0]) if turned else np.array([0.1, 1.0])
        obs = [
            Obstacle("plane", point=tr([0, -0.005]), normal=normal, name="ground"),
            Obstacle("cylinder", center=tr([0.5, -0.2]), radius=0.195, name="post"),
            Obstacle("cylinder", center=(0.0, 0.0), radius=0.095, body="wheel", name="wheel"),
        ]
        return System({"cable": cable, "wheel": wheel}, obstacles=obs)

    s0, s1 = build(False), build(True)
    y0 = s0.y0 + 1e-3 * rng.standard_normal(s0.n)
    y1 = y0.copy()  # the same state, turned: positions and gradients rotated, wheel angle + a
    cab = y0[:20].reshape(5, 2, 2)
    y1[:20] = np.einsum("ij,nkj->nki", rot, cab).ravel()
    y1[:20].reshape(5, 2, 2)[:, 0] += shift
    y1[20:22] = rot @ y0[20:22] + shift
    y1[22] = y0[22] + a
    o0, o1 = contact_outputs(s0, y0), contact_outputs(s1, y1)
    for name in o0:
        assert o0[name].length > 0
        assert np.allclose(rot @ o0[name].normal, o1[name].normal, rtol=1e-10, atol=1e-9)
        assert o1[name].length == pytest.approx(o0[name].length, rel=1e-10)
        assert o1[name].moment == pytest.approx(o0[name].moment, rel=1e-9, abs=1e-9)


def test_points_on_both_pieces_of_the_penalty(rng):
    """The states of these checks put contact points on the onset and on the linear piece."""
    s = planar()
    y, _ = _state(s, rng)
    gaps = []
    for k, (_f, o) in enumerate(s.contact_pairs):
        pts = np.empty(8 * 4 * 8)
        s.contact.points(k, y, None, pts)
        onset = s.obstacles[s.obstacle_names.index(o)].onset or 1e-5
        gaps.append(pts.reshape(-1, 8)[:, 3] / onset)
    g = np.concatenate(gaps)
    assert np.any((g < 0) & (g > -1)) and np.any(g < -1)
