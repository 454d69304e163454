"""Systems: every constraint Jacobian and the assembled tangent of the balance against
central differences, for each joint kind and each kind of place, in 2D and 3D."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.bodies.time_function import TimeFunction
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.factories import mesh_line
from rancf.system import Joint, Load, Spring, System

SEC, MAT = Section.circular(0.01), Material(1000.0, 1e7)
ROD = Material(1000.0, 1e7, poisson_ratio=0.3)


def _rot3(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]) @ np.array(
        [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    )


def planar() -> System:
    """A cable, a beam, a rigid body and a point mass with every 2D joint kind."""
    ramp = TimeFunction.ramp(1, 1)
    cable = Model(
        mesh_line([0, 0], [1, 0], 3),
        "rancf",
        SEC,
        MAT,
        [Support(0, "clamp")],
        gravity=[0, -9.81],
        point_loads=[PointLoad(1, (0.1, 0.2), time=ramp)],
    )
    beam = Model(mesh_line([1, 0], [1.5, 0.5], 2), "beam", SEC, MAT, [], gravity=[0, -9.81])
    rot = np.array([[np.cos(0.3), -np.sin(0.3)], [np.sin(0.3), np.cos(0.3)]])
    pos = np.array([1.5, 0.5]) - rot @ [-0.2, 0.0]  # link:a at the beam's end
    link = RigidBody(2, 1.5, 0.02, tuple(pos), 0.3, points={"a": (-0.2, 0.0), "b": (0.2, 0.1)})
    axis = np.array([1.0, 0.3])
    mass = PointMass(2, 0.5, tuple(pos + rot @ [0.2, 0.1] + 0.3 * axis / np.linalg.norm(axis)))
    joints = [
        Joint("fixed", ("cable:end", "beam:start")),
        Joint("pin", ("beam:end", "link:a"), angle=TimeFunction.harmonic(1.0, 0.2)),
        Joint("slider", ("mass", "link:b"), axis=(1.0, 0.3)),
        Joint("pin", ("link", "ground"), motion=TimeFunction.ramp(1.0, [0.1, 0.0])),
    ]
    springs = [
        Spring(("cable:1", "mass"), 50.0, 2.0),
        Spring(("mass", "ground"), 20.0, 0.5),
    ]  # ground: l0 = 0
    loads = [Load("link:b", (1.0, -2.0), torque=(0.5,), time=TimeFunction.harmonic(2.0, 1.0))]
    return System(
        {"cable": cable, "beam": beam, "link": link, "mass": mass},
        joints,
        springs,
        loads,
        gravity=[0, -9.81],
        damping=0.3,
    )


def spatial() -> System:
    """A rod, a 3D cable, a rigid body and a point mass with every 3D joint kind."""
    rod = Model(
        mesh_line([0, 0, 0], [1, 0, 0], 3),
        "rod",
        SEC,
        ROD,
        [Support(0, "clamp")],
        gravity=[0, 0, -9.81],
    )
    g = [0, 0, -9.81]
    rod2 = Model(mesh_line([1, 0, 0], [1, 0.6, 0.2], 2), "rod", SEC, ROD, [], gravity=g)
    cable = Model(mesh_line([1, 0.6, 0.2], [1.4, 0.9, 0.2], 2), "rancf", SEC, MAT, [], gravity=g)
    # the body's points meet the cable's end (a) and the rod's middle node (b)
    r0, a = _rot3(0.4), np.array([-0.2, -0.1, -0.1])
    pos = np.array([1.4, 0.9, 0.2]) - r0 @ a
    b = r0.T @ (np.array([1.0, 0.3, 0.1]) - pos)
    points = {"a": tuple(a), "b": tuple(b)}
    body = RigidBody(
        3,
        2.0,
        (0.1, 0.2, 0.3),
        tuple(pos),
        r0.tolist(),
        angular_velocity=(0.3, -0.2, 0.5),
        points=points,
    )
    mass = PointMass(3, 0.5, tuple(pos + r0 @ b + 0.3 * np.array([0.0, 1.0, 1.0]) / np.sqrt(2)))
    joints = [
        Joint("fixed", ("rod:end", "rod2:start")),
        Joint("fixed", ("cable:start", "rod2:end")),  # a cable's tangent held by a rod's frame
        Joint("pin", ("body:a", "cable:end")),
        Joint("revolute", ("body:b", "rod2:1"), axis=(0.0, 0.0, 1.0)),
        Joint(
            "revolute", ("body", "ground"), axis=(1.0, 1.0, 0.0), angle=TimeFunction.ramp(1.0, 0.5)
        ),
        Joint("slider", ("mass", "body:b"), axis=(0.0, 1.0, 1.0)),
        Joint("pin", ("rod:1", "ground")),
    ]
    springs = [Spring(("rod:1", "body:b"), 30.0, 1.0), Spring(("rod2:2", "ground"), 20.0, 0.5)]
    loads = [Load("body:a", (0.0, 1.0, 0.0), torque=(0.1, 0.2, 0.3))]
    return System(
        {"rod": rod, "rod2": rod2, "cable": cable, "body": body, "mass": mass},
        joints,
        springs,
        loads,
        gravity=[0, 0, -9.81],
        damping=0.2,
    )


def _perturbed(s: System, rng: np.random.Generator, scale: float = 1e-2) -> np.ndarray:
    y = s.y0 + scale * rng.standard_normal(s.n)
    y[s.fixed] = s.y0[s.fixed]
    return y


def _residual(s: System, y, v, a, lam, t, dynamic=True) -> np.ndarray:
    r = np.empty(s.n + s.m)
    assert s.core.residual(ResidualPoint(y, lam, r, v, a), ResidualOptions(t, dynamic=dynamic))
    return r


@pytest.mark.parametrize("build", [planar, spatial])
def test_constraint_jacobian_against_differences(build, rng):
    s = build()
    y = _perturbed(s, rng)
    z = np.zeros(s.n)
    dense = np.empty((s.n + s.m) ** 2)
    assert s.core.dense_jacobian(
        StatePoint(y, z, z, np.zeros(s.m)), TangentOptions(0.3, 1.0), dense
    )
    g_rows = dense.reshape(s.n + s.m, -1)[s.n :, : s.n]
    fd = np.empty((s.m, s.n))
    g0 = np.empty(s.m)
    for j in range(s.n):
        h = 1e-6 * (1 + abs(y[j]))
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        gp, gm = np.empty(s.m), np.empty(s.m)
        s.core.constraints(yp, 0.3, gp)
        s.core.constraints(ym, 0.3, gm)
        fd[:, j] = (gp - gm) / (2 * h)
    s.core.constraints(y, 0.3, g0)
    assert np.allclose(g_rows, fd, rtol=0, atol=1e-7 * max(1.0, np.abs(fd).max()))


@pytest.mark.parametrize("build", [planar, spatial])
@pytest.mark.parametrize("which", ["y", "v", "a"])
def test_tangent_against_differences(build, which, rng):
    """ck d/dy + cv d/dv + ca d/da of the balance (elements, rigid inertia, springs, loads at
    rigid points, G^T lambda with its second derivatives) and d/dlambda, against central
    differences of the residual."""
    s = build()
    y, v, a = _perturbed(s, rng), 0.3 * rng.standard_normal(s.n), rng.standard_normal(s.n)
    v[s.fixed] = a[s.fixed] = 0.0
    lam = rng.standard_normal(s.m)
    ck, cv, ca = {"y": (1, 0, 0), "v": (0, 1, 0), "a": (0, 0, 1)}[which]
    dense = np.empty((s.n + s.m) ** 2)
    assert s.core.dense_jacobian(StatePoint(y, v, a, lam), TangentOptions(0.4, ck, cv, ca), dense)
    jac = dense.reshape(s.n + s.m, -1)[: s.n]
    free = ~s.fixed
    fd = np.zeros((s.n, s.n + s.m))
    for j in range(s.n + s.m):
        if j < s.n and not free[j]:
            continue
        args = [y, v, a, lam]
        k = {"y": 0, "v": 1, "a": 2}[which] if j < s.n else 3
        jj = j if j < s.n else j - s.n
        base = args[k]
        h = 1e-6 * (1 + abs(base[jj]))
        plus, minus = base.copy(), base.copy()
        plus[jj] += h
        minus[jj] -= h
        rp = _residual(s, *[plus if i == k else x for i, x in enumerate(args)], 0.4)
        rm = _residual(s, *[minus if i == k else x for i, x in enumerate(args)], 0.4)
        fd[:, j] = (rp[: s.n] - rm[: s.n]) / (2 * h)
    rows = np.flatnonzero(free)
    cols = np.r_[np.flatnonzero(free), s.n + np.arange(s.m)]
    if which != "y":  # d/dlambda belongs to the y test
        cols = np.flatnonzero(free)
    scale = max(1.0, np.abs(fd[np.ix_(rows, cols)]).max())
    err = np.abs(jac[np.ix_(rows, cols)] - fd[np.ix_(rows, cols)]).max()
    assert err <= 2e-6 * scale, err


def test_a_spring_to_ground_is_the_linear_spring_at_zero_length():
    """A spring to ``ground`` sits at its place's reference: zero rest length, where the axial
    law has no direction. It is F = k (x_a - x_b) + c (v_a - v_b): finite at the reference
    (the residual and tangent there were NaN), and exactly that force elsewhere."""
    from rancf.bodies.rigid import PointMass

    k, c = 20.0, 0.5
    s = System({"mass": PointMass(2, 2.0, (0.3, 0.1))}, springs=[Spring(("mass", "ground"), k, c)])
    z = np.zeros(s.n)
    r = _residual(s, s.y0, z, z, np.zeros(s.m), 0.0)
    dense = np.empty((s.n + s.m) ** 2)
    assert s.core.dense_jacobian(
        StatePoint(s.y0, z, z, np.zeros(s.m)), TangentOptions(0.0, 1.0, 1.0), dense
    )
    assert np.all(np.isfinite(r)) and np.all(np.isfinite(dense))
    assert np.abs(r).max() == 0.0
    y, v = s.y0 + np.array([0.01, -0.02]), np.array([0.4, 0.3])
    r = _residual(s, y, v, z, np.zeros(s.m), 0.0)
    assert np.allclose(r, k * (y - s.y0) + c * v, rtol=1e-14, atol=0.0)


def test_a_rest_length_where_the_places_meet_is_refused():
    """A spring with a rest length > 0 whose places meet at the reference (any spring to
    ``ground``) has no direction at the start: one line names it and says what is allowed."""
    from rancf.bodies.rigid import PointMass
    from rancf.errors import InputError

    with pytest.raises(InputError, match=r"springs\.tie\.length = 0\.3 .*0 where its places meet"):
        System(
            {"mass": PointMass(2, 2.0, (0.3, 0.1))},
            springs=[Spring(("mass", "ground"), 20.0, length=0.3, name="tie")],
        )


def test_a_flexible_body_without_gravity_in_a_system_with_gravity_is_warned():
    """A flexible body's weight comes from its Model's gravity: leaving it out while the
    System has gravity is said in one warning line (an explicit gravity is taken as meant)."""
    mesh = mesh_line([0, 0], [1, 0], 2)
    for gravity, warned in ((None, True), ((0.0, 0.0), False), ((0.0, -9.81), False)):
        cable = Model(mesh, "rancf", SEC, MAT, [Support(0, "pin")], gravity=gravity)
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            System({"cable": cable}, gravity=[0.0, -9.81])
        lines = [str(w.message) for w in seen]
        assert (len(lines) == 1 and "'cable' has no gravity of its own" in lines[0]) == warned
        assert warned or not lines
