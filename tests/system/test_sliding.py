"""Sliding joints (``kind = "sliding"``): a rope runs through a place without friction
(docs/derivations/sliding.md).  The Jacobian of the balance and the joint's rows with respect to
the coordinates, the multipliers and the material coordinate against central differences
(cables and rods, 2D and 3D, the place on the ground, a point mass, a rigid body); a rigid
motion of the whole set-up gives zero elastic force, keeps the joint's rows and turns its forces
with it; and a rope through two frictionless guides with 2 and 3 kg on its ends runs as the
Atwood machine with the rope's mass."""

from __future__ import annotations

import re

import numpy as np
import pytest
import scipy.linalg

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.errors import InputError
from rancf.geometry.ellipse import Ellipse, ellipse_axes
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.ellipse_mesh import mesh_ellipse
from rancf.mesh.factories import mesh_line
from rancf.mesh.mesh import mesh_from_arrays
from rancf.solvers.buckling import linear_buckling
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.linearized import linearize, system_jacobian
from rancf.solvers.modal import natural_modes
from rancf.solvers.static import solve_static
from rancf.system import Joint, System
from rancf.system.outputs import SystemOutputs
from rancf.system.sliding import sliding_values, start_multipliers
from tests.system.test_system_derivatives import MAT, ROD, SEC, _rot3


def through(place: str, dim: int = 2, element: str = "rancf", supports: bool = True) -> System:
    """A rope of 4 elements along x through a guide at x = 0.55 on the ground, a point mass or
    a point of a rigid body (turned, so its point's position depends on its angle)."""
    end = [1.0, 0.0, 0.0][:dim]
    sup = [Support(0, "pin")] if supports else []
    rope = Model(
        mesh_line([0.0] * dim, end, 4),
        element,
        SEC,
        ROD if element == "rod" else MAT,
        sup,
        gravity=[0.0] * (dim - 1) + [-9.81],
    )
    bodies: dict = {"rope": rope}
    x = np.array([0.55, 0.0, 0.0][:dim])
    if place == "ground":
        joint = Joint("sliding", ("rope", "ground"), position=tuple(x), name="guide")
    elif place == "mass":
        bodies["ring"] = PointMass(dim, 0.5, tuple(x))
        joint = Joint("sliding", ("rope", "ring"), name="guide")
    else:
        a = np.array([0.1, 0.1, 0.05][:dim])
        if dim == 2:
            rot = np.array([[np.cos(0.3), -np.sin(0.3)], [np.sin(0.3), np.cos(0.3)]])
            body = RigidBody(2, 1.5, 0.02, tuple(x - rot @ a), 0.3, points={"a": tuple(a)})
        else:
            rot = _rot3(0.4)
            body = RigidBody(
                3, 1.5, (0.1, 0.2, 0.3), tuple(x - rot @ a), rot.tolist(), points={"a": tuple(a)}
            )
        bodies["block"] = body
        joint = Joint("sliding", ("rope", "block:a"), name="guide")
    return System(bodies, [joint], gravity=[0.0] * (dim - 1) + [-9.81])


def _residual(s: System, y: np.ndarray, lam: np.ndarray) -> np.ndarray:
    r = np.empty(s.n + s.m)
    assert s.core.residual(ResidualPoint(y, lam, r), ResidualOptions(0.0, dynamic=False))
    return r


def _jacobians(s: System, y: np.ndarray, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The core's static Jacobian of ``(y, λ)`` and its central differences (steps 1e-6 of
    each unknown's size)."""
    size = s.n + s.m
    jac = np.empty(size * size)
    z = np.zeros(s.n)
    assert s.core.dense_jacobian(
        StatePoint(y, z, z, lam), TangentOptions(0.0, 1.0, dynamic=False), jac
    )
    x0, fd = np.r_[y, lam], np.zeros((size, size))
    for c in range(size):
        h = 1e-6 * (1.0 + abs(x0[c]))
        xp, xm = x0.copy(), x0.copy()
        xp[c] += h
        xm[c] -= h
        fd[:, c] = (_residual(s, xp[: s.n], xp[s.n :]) - _residual(s, xm[: s.n], xm[s.n :])) / (
            2 * h
        )
    return jac.reshape(size, size), fd


CASES = [
    ("ground", 2, "rancf"),
    ("mass", 2, "ancf"),
    ("rigid", 2, "rancf"),
    ("ground", 3, "rancf"),
    ("rigid", 3, "rancf"),
    ("mass", 3, "rod"),
    ("rigid", 3, "rod"),
]


@pytest.mark.parametrize(("place", "dim", "element"), CASES)
def test_jacobian_is_exact(place, dim, element):
    """The assembled Jacobian over ``(y, λ, σ)`` against central differences of the residual
    at a perturbed state, with a reaction and the guide moved into the next element: to 1e-7
    of the largest entry (the differences' own error; the rigid place's second derivatives are
    differenced in the core too)."""
    s = through(place, dim, element)
    rng = np.random.default_rng(7)
    y = s.y0 + 1e-2 * rng.standard_normal(s.n)
    y[s.fixed] = s.y0[s.fixed]
    lam = start_multipliers(s)
    slot = s.joint_rows[0] + dim
    assert lam[slot] == pytest.approx(2.2, abs=1e-12)  # 0.55 m of 4 elements of 0.25 m
    lam[slot - dim : slot] = rng.standard_normal(dim) * 3.0
    lam[slot] += 0.37  # into element 2
    jac, fd = _jacobians(s, y, lam)
    free = np.r_[~s.fixed, np.ones(s.m, dtype=bool)]
    err = np.abs(jac - fd)[np.ix_(free, free)]
    assert err.max() <= 1e-7 * np.abs(fd).max()
    # the joint's own blocks (its rows, its slot's row and column) to a tighter bound
    joint = np.r_[s.n + slot - dim : s.n + slot + 1]
    rows = np.abs(jac - fd)[joint][:, free]
    assert rows.max() <= 1e-7 * max(np.abs(fd[joint]).max(), 1.0)


def _turn(dim: int) -> np.ndarray:
    if dim == 2:
        return np.array([[np.cos(0.7), -np.sin(0.7)], [np.sin(0.7), np.cos(0.7)]])
    return _rot3(0.7)


@pytest.mark.parametrize(("dim", "element"), [(2, "rancf"), (3, "rancf"), (3, "rod")])
def test_rigid_motion_of_the_whole_set_up(dim, element):
    """A rope through a ring (a point mass), both turned by ``Q`` and shifted by ``c``: the
    joint's rows stay zero at the same ``σ``, the elastic forces vanish, and with a reaction
    ``λ`` the forces on the rope and the ring are ``Q`` times those at the reference with
    ``Qᵀλ`` (1e-12 of their size)."""
    s = through("mass", dim, element, supports=False)
    q, c = _turn(dim), np.array([0.3, -0.2, 0.1][:dim])
    rope = s.bodies["rope"]
    nodes = rope.q_from_y(s.y0[s.body_slice("rope")]).reshape(rope.n_nodes, rope.dpn)
    moved = nodes.copy()
    moved[:, :dim] = nodes[:, :dim] @ q.T + c
    moved[:, dim : 2 * dim] = nodes[:, dim : 2 * dim] @ q.T
    y = s.y0.copy()
    y[s.body_slice("rope")] = rope.y_from_q(moved.ravel())
    y[s.body_slice("ring")] = q @ s.y0[s.body_slice("ring")] + c
    s_nograv = System(
        {
            "rope": Model(rope.mesh, element, SEC, ROD if element == "rod" else MAT),
            "ring": s.bodies["ring"],
        },
        s.joints,
    )
    lam0 = start_multipliers(s_nograv)
    slot = s_nograv.joint_rows[0] + dim
    ref = _residual(s_nograv, s_nograv.y0, lam0)
    now = _residual(s_nograv, y, lam0)
    scale = MAT.youngs_modulus * SEC.area
    assert np.abs(ref).max() <= 1e-12 * scale
    assert np.abs(now).max() <= 1e-9 * scale  # elastic forces of a rigid motion, round-off
    force = np.array([1.5, -2.0, 0.7][:dim])
    lam_ref, lam_now = lam0.copy(), lam0.copy()
    lam_ref[slot - dim : slot] = force
    lam_now[slot - dim : slot] = q @ force
    r0 = _residual(s_nograv, s_nograv.y0, lam_ref) - ref
    r1 = _residual(s_nograv, y, lam_now) - now
    n = rope.n_nodes
    g0 = rope.q_from_y(r0[s_nograv.body_slice("rope")]).reshape(n, rope.dpn)
    g1 = rope.q_from_y(r1[s_nograv.body_slice("rope")]).reshape(n, rope.dpn)
    tol = 1e-12 * np.abs(g0).max()
    np.testing.assert_allclose(g1[:, :dim], g0[:, :dim] @ q.T, rtol=0, atol=tol)
    np.testing.assert_allclose(g1[:, dim : 2 * dim], g0[:, dim : 2 * dim] @ q.T, rtol=0, atol=tol)
    ring = s_nograv.body_slice("ring")
    np.testing.assert_allclose(r1[ring], q @ r0[ring], rtol=0, atol=tol)
    np.testing.assert_allclose(
        r1[s_nograv.n + slot], r0[s_nograv.n + slot], rtol=0, atol=1e-12 * np.abs(force).max()
    )


# ---------------------------------------------------------------- Atwood through two guides
G, M1, M2 = 9.81, 2.0, 3.0
SPAN, HALF, RC = 0.5, 0.1, 0.01
AREA, RHO, E_MOD, EI = 1e-5, 4000.0, 1e10, 2.4e-3
RHO_A = RHO * AREA


def _line(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return [a, a + (b - a) / 3, a + 2 * (b - a) / 3, b], [1.0, 1.0, 1.0, 1.0]


def _arc(centre, t0: float, t1: float):
    c = np.cos((t1 - t0) / 2)
    p0, p2 = (centre + RC * np.array([np.cos(t), np.sin(t)]) for t in (t0, t1))
    p1 = centre + RC / c * np.array([np.cos((t0 + t1) / 2), np.sin((t0 + t1) / 2)])
    w = (1 + 2 * c) / 3
    return [p0, (p0 + 2 * c * p1) / (1 + 2 * c), (2 * c * p1 + p2) / (1 + 2 * c), p2], [1, w, w, 1]


def _points(a: float, b: float, h: float) -> np.ndarray:
    return np.linspace(a, b, max(1, int(round(abs(b - a) / h))) + 1)


def atwood(dim: int = 2) -> System:
    """The rope hangs from two guides at the corners of its path (left leg at x = -0.1, a
    horizontal part, right leg at x = 0.1; corners of radius 1 cm): 5 mm elements where the
    guides pass, unloaded straight (its bends carry the same energy wherever they are).  In 3D
    the same in the x-z plane, gravity along -z."""
    ys = np.r_[_points(-SPAN, -0.3, 0.05)[:-1], _points(-0.3, -RC, 0.005)]
    els = [_line((-HALF, ys[i]), (-HALF, ys[i + 1])) for i in range(len(ys) - 1)]
    cl, cr = np.array([-HALF + RC, -RC]), np.array([HALF - RC, -RC])
    th = np.linspace(np.pi, np.pi / 2, 4)
    els += [_arc(cl, th[i], th[i + 1]) for i in range(3)]
    xs = _points(-HALF + RC, HALF - RC, 0.005)
    els += [_line((xs[i], 0.0), (xs[i + 1], 0.0)) for i in range(len(xs) - 1)]
    th = np.linspace(np.pi / 2, 0.0, 4)
    els += [_arc(cr, th[i], th[i + 1]) for i in range(3)]
    yr = ys[::-1]
    els += [_line((HALF, yr[i]), (HALF, yr[i + 1])) for i in range(len(ys) - 1)]

    def space(p: np.ndarray) -> np.ndarray:  # the plane's points in the system's space
        p = np.asarray(p, dtype=float)
        return p if dim == 2 else np.stack([p[..., 0], np.zeros(p.shape[:-1]), p[..., 1]], -1)

    points = space(np.array([e[0] for e in els]))
    mesh = mesh_from_arrays(points, np.array([e[1] for e in els], float))
    gravity = tuple(space(np.array([0.0, -G])))
    rope = Model(
        mesh,
        "rancf",
        Section(AREA, EI / E_MOD),
        Material(RHO, E_MOD),
        gravity=gravity,
        stress_free="straight",
    )
    g1 = space(cl + RC * np.array([-1.0, 1.0]) / np.sqrt(2))
    g2 = space(cr + RC * np.array([1.0, 1.0]) / np.sqrt(2))
    joints = [
        Joint("pin", ("rope:start", "left")),
        Joint("pin", ("rope:end", "right")),
        Joint("sliding", ("rope", "ground"), position=tuple(g1), name="g1"),
        Joint("sliding", ("rope", "ground"), position=tuple(g2), name="g2"),
    ]
    bodies = {
        "rope": rope,
        "left": PointMass(dim, M1, tuple(space([-HALF, -SPAN]))),
        "right": PointMass(dim, M2, tuple(space([HALF, -SPAN]))),
    }
    return System(bodies, joints, gravity=list(gravity))


def rigid_rope_drop(t: np.ndarray, length: float) -> np.ndarray:
    """The drop ``x(t)`` of the 3 kg mass for a rigid rope: with the hanging lengths
    ``l - x`` and ``l + x``, ``(m1 + m2 + ρ A L) ẍ = g (m2 - m1 + 2 ρ A x)``, so
    ``x = Δm / (2 ρ A) (cosh ω t - 1)``, ``ω² = 2 ρ A g / (m1 + m2 + ρ A L)``: the Atwood
    acceleration ``(m2 - m1) g / (m1 + m2 + ρ A L)`` at the start, growing with the rope's
    weight moved from one side to the other."""
    omega = np.sqrt(2 * RHO_A * G / (M1 + M2 + RHO_A * length))
    return (M2 - M1) / (2 * RHO_A) * (np.cosh(omega * t) - 1.0)


@pytest.fixture(scope="module", params=[2, 3])
def atwood_run(request):
    s = atwood(request.param)
    res = integrate(
        s, DynamicOptions(t_end=0.4, step=2e-3, rho_inf=0.5, max_newton=25, output_step=0.01)
    )
    assert res.status.value == "completed", res.message
    return s, res


def test_rope_through_guides_runs_as_atwood_machine(atwood_run):
    """The mean acceleration of ``x = (y_left - y_right) / 2`` over 0.1 s to 0.4 s (a quadratic
    fit, after the start's release of the rope's stretch and bends) within 1 % of the rigid
    rope's from the same fit (measured: +0.6 %)."""
    s, res = atwood_run
    ys = np.array([s.y_from_q(q) for q in res.q])
    up = s.dim - 1
    x = (ys[:, s.body_slice("left")][:, up] - ys[:, s.body_slice("right")][:, up]) / 2
    length = float(np.sum(s.bodies["rope"].mesh.arc_lengths()))
    late = res.t >= 0.1 - 1e-9
    fit = 2 * np.polyfit(res.t[late], x[late], 2)[0]
    rigid = 2 * np.polyfit(res.t[late], rigid_rope_drop(res.t[late], length), 2)[0]
    atwood_formula = (M2 - M1) * G / (M1 + M2 + RHO_A * length)
    assert rigid == pytest.approx(atwood_formula, rel=0.03)  # the rope's weight moved: +1.5 %
    assert abs(fit / rigid - 1.0) < 0.01


def test_guides_report_normal_force_and_material_run_through(atwood_run):
    """The reactions (``reactions.csv``'s columns): normal to the rope at the guide (the slot's
    equation, to 1e-9) and so along the corner's bisector, into it (to 3 degrees; the rope
    turns by 90 degrees at each guide); and the arc length at the guides ``NAME_s`` follows the
    masses: the left guide's material runs to the right as the right mass drops (``Δs = -x``
    to 2 mm: the rope's stretch)."""
    s, res = atwood_run
    out = SystemOutputs(s)
    k = -1
    rows = out.rows(res.t[[0, k]], res.q[[0, k]], res.v[[0, k]], lam=res.lam[[0, k]])
    r, names = rows["r"], out.reaction_names
    y, d = s.y_from_q(res.q[k]), s.dim
    axes = "xy" if d == 2 else "xz"
    for j, name, inward in ((2, "g1", (-1.0, 1.0)), (3, "g2", (1.0, 1.0))):
        slot = s.joint_rows[j] + d
        _, tangent, _ = s.core.sliding_point(0, y, float(res.lam[k][slot]))
        f = np.array([r[1, names.index(f"{name}_f{a}")] for a in axes])
        tangent = np.asarray(tangent)[[0, d - 1]]
        if d == 3:
            assert abs(r[1, names.index(f"{name}_fy")]) <= 1e-9 * np.linalg.norm(f)
        assert abs(f @ tangent) <= 1e-9 * np.linalg.norm(f) * np.linalg.norm(tangent)
        cos = f @ np.asarray(inward) / (np.linalg.norm(f) * np.sqrt(2.0))
        assert cos > np.cos(np.radians(3.0))
    ys = s.y_from_q(res.q[k])
    x = (ys[s.body_slice("left")][d - 1] - ys[s.body_slice("right")][d - 1]) / 2
    ds = r[1, names.index("g1_s")] - r[0, names.index("g1_s")]
    assert ds == pytest.approx(-x, abs=2e-3)


# ---------------------------------------------------------------- a beam over a guide
BEAM_SEC, STEEL = Section.circular(0.01), Material(1000.0, 1e11, poisson_ratio=0.3)


def two_spans(dim: int, element: str, at: float, n_el: int = 20) -> System:
    """A stiff rope (a beam) of 2 m, ``n_el`` elements, pinned at both ends, through a guide on
    the ground at ``x = at``: a continuous beam of two spans on three simple supports (the
    guide lets the beam slide along itself, which the pinned ends do not)."""
    sup = [Support(0, "pin", fix_twist=element == "rod"), Support(n_el, "pin")]
    beam = Model(
        mesh_line([0.0] * dim, [2.0, 0.0, 0.0][:dim], n_el),
        element,
        BEAM_SEC,
        STEEL,
        sup,
        gravity=[0.0] * (dim - 1) + [-9.81],
    )
    guide = Joint("sliding", ("beam", "ground"), position=tuple([at, 0.0, 0.0][:dim]), name="guide")
    return System({"beam": beam}, [guide])


@pytest.mark.parametrize(("dim", "element"), [(2, "ancf"), (3, "rod")])
def test_guide_carries_the_middle_support_of_a_continuous_beam(dim, element):
    """Statics: under its weight ``w`` the guide at 0.95 m carries the middle reaction of the
    two-span beam, ``R = w (a + b) / 2 - M_B (1/a + 1/b)`` with the three-moment equation's
    ``M_B = -w (a³ + b³) / (8 (a + b))`` (measured: 3e-5 relative; the rest is the membrane
    action of the pinned ends), normal to the beam."""
    s = two_spans(dim, element, 0.95)
    res = solve_static(s)
    react = {r.at: r for r in SystemOutputs(s).static_reactions(res.y, res.lam)}
    w, a, b = 1000.0 * BEAM_SEC.area * 9.81, 0.95, 1.05
    mb = -w * (a**3 + b**3) / (8 * (a + b))
    f = react["guide"].force
    assert f[-1] == pytest.approx(w * (a + b) / 2 - mb / a - mb / b, rel=2e-4)
    assert abs(f[0]) < 1e-4 * abs(f[-1])
    assert react["guide"].extra[0] == pytest.approx(0.95, abs=1e-9)  # s: where it is along


def test_guide_as_middle_support_in_modes():
    """Modes: with the guide in the middle (inside an element) the two spans of 1 m vibrate
    as simply supported spans, ``ω₁ = (π / ℓ)² √(EI / ρA)``, and next as pinned-clamped ones,
    ``(3.9266 / ℓ)² √(EI / ρA)`` (Euler-Bernoulli; measured 8e-6 and 3e-4: the guide's shear
    jump inside an element)."""
    s = two_spans(2, "ancf", 1.0, n_el=21)
    res = solve_static(s)
    modes = natural_modes(s, res.y, count=2, lam=res.lam)
    c = np.sqrt(STEEL.youngs_modulus * BEAM_SEC.inertia / (1000.0 * BEAM_SEC.area))
    exact = np.array([np.pi**2, 3.926602312**2]) * c / (2 * np.pi)
    f = modes.frequencies_hz
    assert f[0] == pytest.approx(exact[0], rel=2e-5)
    assert f[1] == pytest.approx(exact[1], rel=5e-4)


def test_end_through_the_guide_stops_the_run():
    """A rope falling freely through a guide near its top end: the run stops at the step before
    its end passes through (the joint never runs on along the end element's continuation
    beyond the body), on the compiled loop's fixed steps and on adaptive ones; the
    outputs of a state past it say so in one warning line, once."""
    rope = Model(mesh_line([0.0, 0.0], [0.0, -0.5], 10), "ancf", SEC, MAT, gravity=[0, -9.81])
    s = System(
        {"rope": rope, "weight": PointMass(2, 1.0, (0.0, -0.5))},
        [
            Joint("pin", ("rope:end", "weight")),
            Joint("sliding", ("rope", "ground"), position=(0.0, -0.05), name="eye"),
        ],
        gravity=[0, -9.81],
    )
    for adaptive in (False, True):
        res = integrate(
            s, DynamicOptions(t_end=0.2, step=2e-3, output_step=0.01, adaptive=adaptive)
        )
        assert res.status.value == "failed", res.message
        found = re.match(
            r"sliding joint 'eye': the start of body 'rope' passes through its "
            r"place at t = (\S+) s \(material coordinate -",
            res.message,
        )
        assert found, res.message
        t_out = float(found[1])  # free fall of 0.05 m, the start to the eye: 0.101 s
        assert 0.1 < t_out < 0.12
        slot = s.joint_rows[1] + s.dim
        assert 0.0 <= res.state.lam[slot] and res.state.t < t_out  # the step before
        assert res.t[-1] <= res.state.t
    lam = np.zeros(s.m)
    lam[slot] = -0.5
    with pytest.warns(
        UserWarning,
        match=r"^rancf: sliding joint 'eye': the start of body "
        r"'rope' has passed through its place",
    ) as seen:
        sliding_values(s, 1, s.y0, lam)
        sliding_values(s, 1, s.y0, lam)
    assert len(seen) == 1 and "\n" not in str(seen[0].message)


def test_buckling_refuses_sliding_joints_in_one_line():
    with pytest.raises(InputError, match=r"joints\.kind.*sliding") as err:
        linear_buckling(two_spans(2, "ancf", 0.95))
    assert "\n" not in str(err.value)


def test_joint_point_is_the_elements_centre_line():
    """The core's point of the rope at ``σ`` and its first two ``σ``-derivatives are those of
    the rational element (:meth:`CableMesh.evaluate`, the elements' own shape functions) at a
    deformed state, on the rope's rational corner elements and its straight ones (1e-12)."""
    s = atwood(2)
    rope = s.bodies["rope"]
    rng = np.random.default_rng(3)
    y = s.y0 + 1e-3 * rng.standard_normal(s.n)
    nodal = rope.q_from_y(y[s.body_slice("rope")]).reshape(rope.n_nodes, 2, 2)
    curved = int(np.flatnonzero(np.any(rope.mesh.weights != 1.0, axis=1))[0])
    for e in (curved, curved + 1, 3):
        xi = 0.37
        want = [rope.mesh.evaluate([xi], nodal, order)[e, 0] for order in range(3)]
        got = s.core.sliding_point(0, y, e + xi)
        for w, g in zip(want, got, strict=True):
            np.testing.assert_allclose(np.asarray(g)[:2], w, rtol=0, atol=1e-12 * np.abs(w).max())


def test_modes_condensation_is_the_full_pencil():
    """The material coordinate condensed out of the modes (docs/derivations/sliding.md §4)
    gives the finite eigenvalues of the pencil that keeps it and the multipliers (zero mass
    on them), about a loaded equilibrium (the guide carries 3.9 N): to 1e-8."""
    s = two_spans(2, "ancf", 0.95, n_el=10)
    res = solve_static(s)
    lin = linearize(s, res.y, res.lam)
    basis = scipy.linalg.null_space(lin.g.toarray())
    k, m = basis.T @ lin.k.toarray() @ basis, basis.T @ lin.mass.toarray() @ basis
    condensed = np.sort(scipy.linalg.eigvals(k, m).real)[:4]
    j = system_jacobian(s, res.y, res.lam, 1.0, 0.0, 1.0, True, 0.0).toarray()
    mj = system_jacobian(s, res.y, res.lam, 0.0, 1.0, 1.0, True, 0.0).toarray()
    free = np.r_[~s.fixed, np.ones(s.m, dtype=bool)]
    jj, mm = j[np.ix_(free, free)], mj[np.ix_(free, free)]
    mm[:, -s.m :] = 0.0
    mm[-s.m :, :] = 0.0
    full = scipy.linalg.eigvals(jj, mm)
    full = np.sort(full[np.isfinite(full)].real)[:4]
    np.testing.assert_allclose(condensed, full, rtol=1e-8)


# ---------------------------------------------------------------- 2:1 reeving
MB, MF = 4.0, 1.5


def reeving() -> System:
    """A rope anchored at (-0.05, 0) runs down and under a movable block (4 kg, a rigid body
    with two guides at its lower corners), up over two fixed guides at the top and down to a
    1.5 kg weight: 2:1 reeving, one body for the rope, four sliding joints (two on a moving
    body).  Corners of radius 1 cm, 5 mm elements where the guides pass; the rope is light
    (5.5 g)."""
    w, yb, ym, q = 0.05, -0.4, -0.4, np.sqrt(0.5)
    els: list = []

    def seg(p, r, h):
        p, r = np.asarray(p, float), np.asarray(r, float)
        n = max(1, int(round(np.linalg.norm(r - p) / h)))
        els.extend(_line(p + (r - p) * i / n, p + (r - p) * (i + 1) / n) for i in range(n))

    def corner(c, t0, t1):
        th = np.linspace(t0, t1, 4)
        els.extend(_arc(np.asarray(c, float), th[i], th[i + 1]) for i in range(3))

    cl, cr, ct1, ct2 = (-w + RC, yb + RC), (w - RC, yb + RC), (w + RC, -RC), (3 * w - RC, -RC)
    seg((-w, 0.0), (-w, yb + 0.15), 0.05)
    seg((-w, yb + 0.15), (-w, yb + RC), 0.005)
    corner(cl, np.pi, 1.5 * np.pi)
    seg((-w + RC, yb), (w - RC, yb), 0.005)
    corner(cr, 1.5 * np.pi, 2 * np.pi)
    seg((w, yb + RC), (w, yb + 0.12), 0.005)
    seg((w, yb + 0.12), (w, -0.25), 0.05)
    seg((w, -0.25), (w, -RC), 0.005)
    corner(ct1, np.pi, 0.5 * np.pi)
    seg((w + RC, 0.0), (3 * w - RC, 0.0), 0.005)
    corner(ct2, 0.5 * np.pi, 0.0)
    seg((3 * w, -RC), (3 * w, ym + 0.1), 0.005)
    seg((3 * w, ym + 0.1), (3 * w, ym), 0.05)
    mesh = mesh_from_arrays(np.array([e[0] for e in els]), np.array([e[1] for e in els], float))
    rope = Model(
        mesh,
        "rancf",
        Section(AREA, EI / E_MOD),
        Material(400.0, E_MOD),
        [Support(0, "pin")],
        gravity=(0.0, -G),
        stress_free="straight",
    )
    gl = np.array(cl) + RC * np.array([-q, -q])
    gr = np.array(cr) + RC * np.array([q, -q])
    points = {"l": tuple(gl - [0.0, yb]), "r": tuple(gr - [0.0, yb])}
    block = RigidBody(2, MB, MB * (2 * w) ** 2 / 12, (0.0, yb), 0.0, points=points)
    top = [np.array(ct1) + RC * np.array([-q, q]), np.array(ct2) + RC * np.array([q, q])]
    joints = [
        Joint("pin", ("rope:end", "weight")),
        Joint("sliding", ("rope", "block:l"), name="sheave_l"),
        Joint("sliding", ("rope", "block:r"), name="sheave_r"),
    ]
    joints += [
        Joint("sliding", ("rope", "ground"), position=tuple(p), name=f"top_{side}")
        for p, side in zip(top, "lr", strict=True)
    ]
    bodies = {"rope": rope, "block": block, "weight": PointMass(2, MF, (3 * w, ym))}
    return System(bodies, joints, gravity=[0.0, -G])


def test_two_to_one_reeving_with_a_movable_block():
    """The block falls and the weight rises twice as fast: with a massless rope
    ``(M + 4 m) ÿ_b = -(M - 2 m) g``.  The mean accelerations over 0.1 s to 0.4 s within 2 %
    of it (measured: block +0.8 %, weight -0.4 %; the rope is 0.1 % of the mass, the rest the
    rope's axial bounce from the start and the block's rocking)."""
    s = reeving()
    res = integrate(
        s, DynamicOptions(t_end=0.4, step=2e-3, rho_inf=0.5, max_newton=25, output_step=0.01)
    )
    assert res.status.value == "completed", res.message
    ys = np.array([s.y_from_q(q) for q in res.q])
    late = res.t >= 0.1 - 1e-9
    accel = {}
    for name in ("block", "weight"):
        y = ys[:, s.body_slice(name)][:, 1]
        accel[name] = 2 * np.polyfit(res.t[late], y[late], 2)[0]
    block = -(MB - 2 * MF) * G / (MB + 4 * MF)
    assert accel["block"] == pytest.approx(block, rel=0.02)
    assert accel["weight"] == pytest.approx(-2 * block, rel=0.02)


def test_a_ring_runs_round_through_its_place():
    """A closed body (a ring of 8 elements, radius 1 m) through a bead: the material
    coordinate is taken modulo the elements (the rows hold a lap later), the arc length counts
    the laps, and the Jacobian is exact across the seam (central differences, 1e-7)."""
    ring = Model(
        mesh_ellipse(Ellipse(np.zeros(2), 1.0, 1.0, *ellipse_axes(2)), 8), "rancf", SEC, MAT
    )
    s = System(
        {"ring": ring, "bead": PointMass(2, 0.5, (0.0, -1.0))},
        [Joint("sliding", ("ring", "bead"), name="bead")],
    )
    lam, slot = start_multipliers(s), s.joint_rows[0] + 2
    assert lam[slot] == pytest.approx(6.0, abs=1e-12)  # three quarters round
    g = np.empty(s.m)
    for laps in (-1, 1):
        later = lam.copy()
        later[slot] += 8 * laps
        s.core.constraints(s.y0, 0.0, g, later)
        assert np.abs(g[:2]).max() <= 1e-12
        arc = sliding_values(s, 0, s.y0, later)
        assert arc == pytest.approx(1.5 * np.pi + 2 * np.pi * laps, rel=1e-9)
    rng = np.random.default_rng(5)
    y = s.y0 + 1e-3 * rng.standard_normal(s.n)
    lam[slot - 2 : slot + 1] = [1.0, -2.0, 7.9]  # the last element, at the seam
    jac, fd = _jacobians(s, y, lam)
    assert np.abs(jac - fd).max() <= 1e-7 * np.abs(fd).max()


def test_shipped_atwood_example_is_the_system_tested_here():
    """``atwood-guides.toml`` (the gallery's Atwood machine, a degree-2 NURBS meshed one element
    per knot span) builds the rope, masses, joints and gravity of :func:`atwood` in 2D: the same
    reference coordinates and weights to round-off (1e-12)."""
    from rancf.scenario import load_scenario
    from rancf.studies.common import example_path

    shipped = load_scenario(example_path("atwood-guides")).build_system()
    tested = atwood(2)
    assert shipped.n == tested.n and shipped.dim == 2
    a, b = shipped.bodies["rope"], tested.bodies["rope"]
    np.testing.assert_allclose(a.q0, b.q0, rtol=0, atol=1e-12 * np.abs(b.q0).max())
    np.testing.assert_allclose(a.mesh.weights, b.mesh.weights, rtol=1e-12, atol=0)
    for m in ("left", "right"):
        assert shipped.bodies[m].mass == tested.bodies[m].mass
        np.testing.assert_allclose(
            shipped.bodies[m].position, tested.bodies[m].position, rtol=0, atol=1e-15
        )
    np.testing.assert_array_equal(shipped.gravity, tested.gravity)
    assert [j.kind for j in shipped.joints] == [j.kind for j in tested.joints]
    for j, k in zip(shipped.joints[2:], tested.joints[2:], strict=True):
        np.testing.assert_allclose(j.position, k.position, rtol=0, atol=1e-15)
