"""Closed curves: the exact ellipse, the seam's constraint rows, statics independent of
where the seam lies (planar and spatial rings, the holonomy of a spatial centreline), free rings
in dynamics."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.closure import closure_rows
from rancf.bodies.flexible import Material, Model, PointLoad, RigidMotion, Section, Support
from rancf.errors import InputError
from rancf.geometry.ellipse import Ellipse, ellipse_axes
from rancf.geometry.nurbs import NurbsCurve
from rancf.kernels import _core
from rancf.kernels.call_records import StatePoint, TangentOptions
from rancf.mesh.ellipse_mesh import mesh_ellipse
from rancf.mesh.nurbs_mesh import mesh_nurbs
from rancf.options import DynamicOptions
from rancf.solvers.dynamic import integrate
from rancf.solvers.static import solve_static
from rancf.system import System

STEEL = Material(7850.0, 2e11, poisson_ratio=0.3)
SEC = Section.circular(0.01)


def _ellipse(dim: int) -> Ellipse:
    if dim == 2:
        return Ellipse([0.2, -0.1], 0.5, 0.3, *ellipse_axes(2, 30.0))
    return Ellipse([0.2, -0.1, 0.4], 0.5, 0.3, *ellipse_axes(3, axes=[[1, 1, 0], [0, 0, 2]]))


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("n", [4, 8, 16])
@pytest.mark.parametrize("start", [0.0, 37.0, 90.0])
def test_ellipse_is_exact(dim, n, start):
    e = _ellipse(dim)
    m = mesh_ellipse(e, n, start_deg=start)
    assert m.closed and m.n_nodes == n + 1 and m.n_distinct_nodes == n
    pts = m.evaluate(np.linspace(0.0, 1.0, 51)).reshape(-1, dim)
    assert np.abs(e.implicit_residual(pts)).max() < 1e-13
    assert abs(m.arc_lengths().sum() / e.perimeter() - 1.0) < 1e-12
    # the perimeter itself against an independent quadrature of the speed
    t = np.linspace(0.0, 2.0 * np.pi, 20001)
    ds = np.hypot(0.5 * np.sin(t), 0.3 * np.cos(t))
    simpson = (t[1] - t[0]) / 3.0 * (ds[0] + ds[-1] + 4 * ds[1:-1:2].sum() + 2 * ds[2:-1:2].sum())
    assert abs(e.perimeter() / simpson - 1.0) < 1e-12
    # the last stored node is the first one
    assert np.array_equal(m.nodes[-1, 0], m.nodes[0, 0])
    assert np.allclose(np.cross(np.r_[m.nodes[-1, 1], 0][:3], np.r_[m.nodes[0, 1], 0][:3]), 0)


def test_ellipse_needs_three_elements_and_perpendicular_axes():
    with pytest.raises(InputError, match="at least 3 elements"):
        mesh_ellipse(_ellipse(2), 2)
    with pytest.raises(InputError, match="perpendicular"):
        ellipse_axes(3, axes=[[1, 0, 0], [1, 1, 0]])


def _ring(n: int, element: str, start: float = 0.0, **kw) -> Model:
    dim = 3 if element == "rod" else 2
    return Model(
        mesh_ellipse(Ellipse(np.zeros(dim), 1.0, 1.0, *ellipse_axes(dim)), n, start_deg=start),
        element,
        SEC,
        STEEL,
        **kw,
    )


@pytest.mark.parametrize("element", ["rancf", "ancf", "beam", "rod"])
def test_seam_rows_hold_and_their_jacobian_is_exact(element, rng):
    """The seam's linear rows hold in the reference (also with a clamp rotating node 0's blocks)
    and the assembled Jacobian equals central differences of g."""
    mod = _ring(6, element, 37.0, supports=[Support(0, "clamp")])
    s = System({"ring": mod})
    assert s.m == mod.dpn
    g = np.empty(s.m)
    s.core.constraints(s.y0, 0.0, g)
    assert np.abs(g).max() < 1e-15
    y = s.y0 + 1e-2 * rng.standard_normal(s.n)
    z = np.zeros(s.n)
    dense = np.empty((s.n + s.m) ** 2)
    assert s.core.dense_jacobian(
        StatePoint(y, z, z, np.zeros(s.m)), TangentOptions(0.0, 1.0), dense
    )
    rows = dense.reshape(s.n + s.m, -1)[s.n :, : s.n]
    fd = np.empty((s.m, s.n))
    for j in range(s.n):
        h = 1e-6 * (1 + abs(y[j]))
        gp, gm = np.empty(s.m), np.empty(s.m)
        s.core.constraints(y + h * np.eye(s.n)[j], 0.0, gp)
        s.core.constraints(y - h * np.eye(s.n)[j], 0.0, gm)
        fd[:, j] = (gp - gm) / (2 * h)
    free = ~s.fixed
    assert np.abs(rows[:, free] - fd[:, free]).max() < 1e-8
    # and they are the documented rows: q_n - s q_0 in full coordinates
    r, c, v = closure_rows(mod)
    a = np.zeros((mod.dpn, mod.n))
    a[r, c] = v
    q = mod.q_from_y(y)
    want = (
        q[-mod.dpn :]
        - q[: mod.dpn]
        * np.r_[np.ones(mod.dim), np.full(mod.dpn - mod.dim, mod.mesh.seam_ratio)][: mod.dpn]
        if element != "beam"
        else q[-3:] - q[:3]
    )
    if element == "rod":
        want[6] = q[-1] - q[6]
    assert np.allclose(a @ y, want, rtol=0, atol=1e-14)


def _opposite_forces(
    n: int, seam: float, element: str = "rod", continuity: str = "C1"
) -> np.ndarray:
    """Node positions (in the order of their angle from 0) of a ring of ``n`` elements clamped
    at 0 deg and pulled apart at 0 and 180 deg (out of its plane too: the rod twists), with the
    seam at ``seam`` deg."""
    step = 360 // n
    k0, k180 = ((0 - int(seam)) % 360) // step, ((180 - int(seam)) % 360) // step
    f = (-2000.0, 0.0, 1000.0)
    mod = _ring(
        n,
        element,
        seam,
        supports=[Support(k0, "clamp")],
        point_loads=[PointLoad(k180, f), PointLoad(k0, tuple(-x for x in f))],
        continuity=continuity,
    )
    res = solve_static(mod)
    pos = mod.node_positions(res.q)
    assert np.abs(pos[-1] - pos[0]).max() < 1e-14  # the seam holds (linear rows)
    return np.roll(pos[:-1], int(seam) // step, axis=0)


@pytest.mark.parametrize("continuity", ["C1", "C2"])
def test_static_answer_does_not_depend_on_the_seam(continuity):
    """Rod ring (R = 1 m, 360 elements: 0, 37 and 90 deg are nodes of every mesh), clamped at
    0 deg, opposite forces at 0 and 180 deg with an out-of-plane part: the same deformed shape
    to 1e-9 wherever the seam lies (C²: the held node is a C¹ node, the seam C² by its rows)."""
    ref = _opposite_forces(360, 0.0, continuity=continuity)
    assert ref[180, 2] > 0.1  # a large deflection, out of the plane too
    for seam in (37.0, 90.0):
        assert np.abs(_opposite_forces(360, seam, continuity=continuity) - ref).max() < 1e-9


def _loop(shift: int) -> NurbsCurve:
    """A closed spatial curve (a periodic cubic B-spline of 8 spans near a figure eight lifted out
    of its plane), its seam ``shift`` spans on."""
    th = 2 * np.pi * (np.arange(8) + shift) / 8
    pts = np.stack([np.sin(th), np.sin(th) * np.cos(th), 0.5 * np.cos(th)], axis=1)
    return NurbsCurve.bspline(3, np.arange(15.0), np.concatenate([pts, pts[:3]]))


def test_spatial_ring_closes_its_material_frame():
    """A non-planar centreline: the director carried once around comes back turned (holonomy);
    the reference triads spread that turn, so the last node's director is the first's; the
    static answer does not depend on where the seam lies."""
    mesh = mesh_nurbs(_loop(0), 3)
    assert mesh.closed
    t = mesh.nodes[:, 1] / np.linalg.norm(mesh.nodes[:, 1], axis=1, keepdims=True)
    m1 = np.cross([0.0, 0.0, 1.0], t[0])
    m1 /= np.linalg.norm(m1)
    carried = m1
    for k in range(1, len(t)):
        _, carried = _core.rod_nodal_triad(t[k - 1], np.asarray(carried), t[k], 0.0)
    holonomy = np.arctan2(np.cross(carried, m1) @ t[0], carried @ m1)
    assert abs(holonomy) > 1.0  # a real case (-2.06 rad)
    mod = Model(mesh, "rod", SEC, STEEL)
    d = mod.nodal_directors(mod.y0)
    assert np.abs(d[-1] - d[0]).max() < 1e-15
    shapes = []
    for shift in (0, 3):
        load = PointLoad((21 - 3 * shift) % 24, (0.0, 300.0, -400.0))
        clamp = Support((9 - 3 * shift) % 24, "clamp")
        mod = Model(
            mesh_nurbs(_loop(shift), 3), "rod", SEC, STEEL, supports=[clamp], point_loads=[load]
        )
        pos = mod.node_positions(solve_static(mod).q)[:-1]
        shapes.append(np.roll(pos, 3 * shift, axis=0))
    assert np.abs(shapes[0][21] - mesh.nodes[21, 0]).max() > 1e-3  # it moved
    assert np.abs(shapes[1] - shapes[0]).max() < 1e-9


@pytest.mark.parametrize("element", ["rancf", "rod"])
def test_free_ring_in_dynamics(element):
    """A free ring set spinning (about a tilted axis in 3D: it wobbles and bends): the seam holds;
    the energy drifts only by the time discretization's second-order error (ρ∞ = 1: a quarter
    with half the step)."""
    spin = RigidMotion(angular_velocity=20.0 if element != "rod" else (4.0, -3.0, 20.0))
    drift = []
    for step in (5e-4, 2.5e-4):
        mod = _ring(24, element, 37.0, initial_motion=spin)
        res = integrate(mod, DynamicOptions(t_end=0.05, step=step, rho_inf=1.0))
        pos = res.q.reshape(len(res.t), mod.n_nodes, mod.dpn)
        assert np.abs(pos[:, -1, : mod.dim] - pos[:, 0, : mod.dim]).max() < 1e-12
        assert np.abs(pos[-1, 0, : mod.dim] - pos[0, 0, : mod.dim]).max() > 0.5  # it turned
        e = res.kinetic + res.strain
        drift.append(np.ptp(e) / e[0])
    assert drift[0] < 2e-4 and drift[1] < drift[0] / 3.0
