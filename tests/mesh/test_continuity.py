"""C² reduced coordinates: the control points of the cubic (rational) B-spline of a
mesh as its generalized coordinates (Sanborn & Shabana 2009, sec. 6; rancf.mesh.continuity).

* a cubic B-spline of n spans is reproduced exactly by n + 3 control points per coordinate, and
  *any* control points give that B-spline (the map q = T y is the seed's transformation);
* the maps are banded, the mass is Tᵀ M T, the tangent is the derivative of the force;
* C¹ and C² converge to the same static and dynamic answers; the cantilever's first frequency
  is approached from above with fewer unknowns in C² at equal accuracy;
* supports (also inside the curve), loads and closed rings (cables and rods).
"""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.properties import PointLoad
from rancf.bodies.reactions import support_reactions
from rancf.geometry.ellipse import Ellipse, ellipse_axes
from rancf.geometry.nurbs import NurbsCurve
from rancf.kernels.call_records import StatePoint, TangentOptions
from rancf.mesh.ellipse_mesh import mesh_ellipse
from rancf.mesh.factories import mesh_line
from rancf.mesh.nurbs_mesh import mesh_nurbs
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.modal import natural_modes
from rancf.solvers.static import solve_static
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system import System, as_system

#: Euler-Bernoulli first frequency of the cantilever (L = 0.5 m, radius 0.03 m, ρ = 6000,
#: E = 2e7): (1.8751² / 2π) sqrt(EI / ρA L⁴); the shipped cantilever (8 C¹ elements) gives
#: 1.938485 Hz.
F1 = 1.875104068711961**2 / (2 * np.pi) * np.sqrt(2e7 * 0.03**2 / 4 / 6000 / 0.5**4)


def _bspline(dim: int, n: int, rational: bool = False) -> NurbsCurve:
    rng = np.random.default_rng(7 + dim + n)
    inner = np.sort(rng.uniform(0.15, 0.85, n - 1))  # non-uniform simple knots
    knots = np.r_[[0.0] * 4, inner, [1.0] * 4] * 2.0
    pts = np.c_[np.linspace(0, 1, n + 3), np.zeros((n + 3, dim - 1))] + rng.uniform(
        -0.15, 0.15, (n + 3, dim)
    )
    w = rng.uniform(0.6, 1.6, n + 3) if rational else np.ones(n + 3)
    return NurbsCurve(3, knots, pts, w)


def _cable(mesh, **kw) -> Model:
    return Model(mesh, "rancf", Section.circular(0.01), Material(1000.0, 1e7), **kw)


def _spline_y(model: Model, curve: NurbsCurve) -> np.ndarray:
    """The model coordinates of a polynomial B-spline's control points: [r, r_x] at the ends
    (r_0 = P_0, r_x,0 = 3 (P_1 - P_0) / l_0 for the first element's scale l_0), P_2 … P_n."""
    p, d, sc = curve.points, curve.dim, model.mesh.scales
    ends = [
        np.r_[p[0], 3 * (p[1] - p[0]) / sc[0]],
        np.r_[p[-1], 3 * (p[-1] - p[-2]) / sc[-1]],
    ]
    y = np.zeros(model.n)
    y[: model.reduction.n_real] = np.concatenate([ends[0], p[2:-2].ravel(), ends[1]])
    assert model.reduction.n_real == d * (curve.n_ctrl)
    return y


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("n", [1, 2, 3, 6])
def test_bspline_of_n_spans_is_n_plus_3_control_points(dim, n):
    """Reference reproduced to 1e-14 (the mesh's curve against the B-spline), the coordinates
    are its control points, and random control points give the B-spline of those points."""
    curve = _bspline(dim, n)
    mesh = mesh_nurbs(curve)
    mod = _cable(mesh, continuity="C2")
    assert mod.reduction.n_real == dim * (n + 3)
    assert int(np.sum(~mod.fixed)) == dim * (n + 3)
    u = np.linspace(0.0, 1.0, 9)
    span = curve.domain[1] - curve.domain[0]
    q = mod.q_from_y(mod.y0)
    pts = mesh.evaluate(u, q)  # (n_el, n_u, dim), element e on its knot span
    breaks = np.unique(curve.knots)
    want = np.stack([curve(breaks[e] + u * (breaks[e + 1] - breaks[e])) for e in range(n)])
    assert np.abs(pts - want).max() < 1e-14 * span
    assert np.abs(mod.y0 - _spline_y(mod, curve)).max() < 1e-14 * span
    rng = np.random.default_rng(3)
    other = NurbsCurve(3, curve.knots, rng.normal(size=curve.points.shape), np.ones(n + 3))
    got = mesh.evaluate(u, mod.q_from_y(_spline_y(mod, other)))
    want = np.stack([other(breaks[e] + u * (breaks[e + 1] - breaks[e])) for e in range(n)])
    assert np.abs(got - want).max() < 1e-13


@pytest.mark.parametrize("dim", [2, 3])
def test_rational_bspline_and_conics_are_in_the_c2_space(dim):
    """A rational cubic B-spline and an ellipse (Kopt per element: not a parametric C² chain,
    but curvature continuous) are reproduced to round-off."""
    for mesh in (
        mesh_nurbs(_bspline(dim, 5, rational=True), 2),
        mesh_ellipse(Ellipse(np.zeros(dim), 0.5, 0.3, *ellipse_axes(dim)), 7, start_deg=37.0),
    ):
        mod = _cable(mesh, continuity="C2")
        q = mod.q_from_y(mod.y0)
        assert np.abs(q - mesh.q0).max() < 1e-13 * np.abs(mesh.q0).max()


def test_maps_are_banded_and_the_matrices_are_their_projections(rng):
    mesh = mesh_nurbs(_bspline(3, 6), 2)
    mod = Model(
        mesh,
        "rod",
        Section.circular(0.01),
        Material(1000.0, 1e7, poisson_ratio=0.3),
        supports=[Support(0, "clamp"), Support(5, "pin")],
        continuity="C2",
    )
    red = mod.reduction
    assert red.width <= 22 and red.node_width <= 15 and mod.ku == red.width - 1
    t = red.t.toarray() @ np.eye(mod.n)
    # element maps: rows of T over the window, nothing outside it
    for e in range(mod.n_el):
        rows = t[e * mod.dpn : e * mod.dpn + 2 * mod.dpn]
        s = red.el_start[e]
        assert np.array_equal(rows[:, s : s + red.width], red.el_map[e])
        assert not np.any(np.delete(rows, np.s_[s : s + red.width], axis=1))
    # mass: Tᵀ M T of the C¹ model's mass (no supports: the same T without rotations)
    c1 = Model(mesh, "rod", Section.circular(0.01), Material(1000.0, 1e7, poisson_ratio=0.3))
    m_q = c1.dense(c1.mass_band)
    assert np.allclose(mod.dense(mod.mass_band), t.T @ m_q @ t, rtol=0, atol=1e-14 * m_q.max())
    # tangent against central differences of the force, at a deformed state
    y = mod.y0 + 1e-3 * rng.normal(size=mod.n) * ~mod.fixed
    f, ab = mod.internal_force_and_tangent(y)
    k = mod.dense(ab)
    h = 1e-7
    for j in rng.choice(np.flatnonzero(~mod.fixed), 12, replace=False):
        e = np.zeros(mod.n)
        e[j] = h
        fd = (mod.internal_force(y + e) - mod.internal_force(y - e)) / (2 * h)
        assert np.abs(fd - k[:, j]).max() < 1e-5 * np.abs(k).max()


def _cantilever(n: int, continuity: str) -> Model:
    return Model(
        mesh_line([0, 0], [0.5, 0], n),
        "ancf",
        Section.circular(0.03),
        Material(6000.0, 2e7),
        supports=[Support(0, "clamp")],
        continuity=continuity,
    )


def test_cantilever_frequency_from_above_with_fewer_unknowns():
    runs = {}
    for c in ("C1", "C2"):
        runs[c] = [
            (int(np.sum(~m.fixed)), natural_modes(m, count=1).frequencies_hz[0])
            for m in (_cantilever(n, c) for n in (2, 4, 8, 16))
        ]
        f = np.array([x[1] for x in runs[c]])
        assert np.all(f > F1) and np.all(np.diff(f) < 0)  # from above, monotonically
    # C² with 19 unknowns is as accurate as C¹ with 33 (8 elements each): 2.1e-6
    (n1, f1), (n2, f2) = runs["C1"][2], runs["C2"][2]
    assert n2 < 0.6 * n1
    assert abs(f2 / F1 - 1) < 1.05 * abs(f1 / F1 - 1)
    assert abs(runs["C1"][2][1] - 1.938485) < 5e-7  # the shipped example's number


def test_static_answers_converge_to_the_same_values():
    """A large deflection (tip load) of a clamped quarter arc: C¹ and C² tip positions meet."""
    tips = {}
    for c in ("C1", "C2"):
        tips[c] = []
        for n in (4, 8, 16, 32):
            mesh = mesh_nurbs(_quarter(), n)
            m = _cable(
                mesh,
                supports=[Support(0, "clamp")],
                point_loads=[PointLoad(-1, (0.0, -0.1))],
                continuity=c,
            )
            tips[c].append(m.node_positions(solve_static(m).q)[-1])
    d1 = np.linalg.norm(np.diff(tips["C1"], axis=0), axis=1)
    d2 = np.linalg.norm(np.diff(tips["C2"], axis=0), axis=1)
    assert np.linalg.norm(tips["C1"][0] - mesh_nurbs(_quarter(), 4).nodes[-1, 0]) > 0.1
    assert np.all(np.diff(d1) < 0) and np.all(np.diff(d2) < 0)  # converging
    assert np.linalg.norm(tips["C1"][-1] - tips["C2"][-1]) < 1e-6


def _quarter() -> NurbsCurve:
    s = np.sqrt(0.5)
    return NurbsCurve(2, [0, 0, 0, 1, 1, 1], [[0.5, 0], [0.5, 0.5], [0, 0.5]], [1, s, 1])


def test_dynamic_answers_converge_to_the_same_values():
    """A pinned curved cable falling under gravity (the 6.1 pendulum's kind): tip at 0.2 s."""
    tips = {}
    for c in ("C1", "C2"):
        tips[c] = []
        for n in (4, 8, 16):
            m = Model(
                mesh_nurbs(_quarter(), n),
                "rancf",
                Section.circular(0.02),
                Material(6000.0, 2e6),
                supports=[Support(0, "pin")],
                gravity=(0.0, -9.81),
                continuity=c,
            )
            res = integrate(m, DynamicOptions(t_end=0.2, step=1e-3, rho_inf=0.9))
            tips[c].append(m.node_positions(res.q[-1])[-1])
    assert np.linalg.norm(tips["C1"][-1] - tips["C1"][0]) > 1e-4  # the meshes differ
    assert np.linalg.norm(tips["C1"][-1] - tips["C2"][-1]) < 2e-5
    assert np.linalg.norm(tips["C2"][-1] - tips["C2"][-2]) < np.linalg.norm(
        tips["C2"][1] - tips["C2"][0]
    )


def test_inner_support_and_point_load_match_c1():
    """A pin inside the curve (its node keeps its own coordinates: a C¹ node) and a point load:
    the pinned node stays put, the reactions balance the load, and C² meets C¹ as the mesh is
    refined (the sag under the load: both converge at first order here, their difference too)."""
    gaps = []
    for n in (12, 48):
        out = {}
        for c in ("C1", "C2"):
            m = _cable(
                mesh_line([0, 0], [1, 0], n),
                supports=[Support(0, "pin"), Support(n // 2, "pin"), Support(-1, "pin")],
                point_loads=[PointLoad(n // 4, (0.0, -0.5))],
                continuity=c,
            )
            res = solve_static(m)
            pos = m.node_positions(res.q)
            assert np.abs(pos[n // 2] - [0.5, 0.0]).max() < 1e-14
            out[c] = pos[n // 4]
            full = SystemEquilibrium(as_system(m)).full_residual(res.y, 1.0)
            total = sum(r.force for r in support_reactions(m, res.y, full))
            assert np.abs(total + [0.0, -0.5]).max() < 1e-9
        assert out["C1"][1] < -0.008  # it sags
        gaps.append(np.linalg.norm(out["C1"] - out["C2"]) / abs(out["C1"][1]))
    assert gaps[1] < gaps[0] / 3 and gaps[1] < 1e-3


@pytest.mark.parametrize("element", ["rancf", "rod"])
def test_closed_c2_ring(element):
    """A free C² ring: n unknowns per coordinate once its seam rows hold, 3 / 6 rigid-body
    modes, frequencies approaching the C¹ ones from above."""
    dim = 3 if element == "rod" else 2
    ring = Ellipse(np.zeros(dim), 1.0, 1.0, *ellipse_axes(dim))
    freqs = {}
    for c in ("C1", "C2"):
        m = Model(
            mesh_ellipse(ring, 32, start_deg=37.0),
            element,
            Section.circular(0.01),
            Material(7850.0, 2e11, poisson_ratio=0.3),
            continuity=c,
        )
        res = natural_modes(m, count=4)
        assert res.n_rigid == (6 if dim == 3 else 3)
        freqs[c] = res.frequencies_hz
        s = System({"ring": m})
        seam = m.dpn + (dim if c == "C2" else 0)  # C²: the (C2) condition across the seam too
        assert s.m == seam
        g = np.zeros(s.m)
        s.core.constraints(s.y0, 0.0, g)
        assert np.abs(g).max() < 1e-12  # the reference satisfies every seam row
        if c == "C2":  # 32 control points per coordinate (and 32 twists): a periodic spline
            assert int(np.sum(~m.fixed)) - s.m == (dim + (element == "rod")) * 32
    assert np.all(freqs["C2"] > freqs["C1"]) and np.all(freqs["C2"] < 1.02 * freqs["C1"])


def test_rod_dynamics_with_a_point_moment_converge_to_the_same_values():
    """A clamped spatial rod arc (rational quadratic, lifted out of its plane) under gravity and
    a point moment at its tip: C¹ and C² tips after 0.2 s meet as the mesh is refined."""
    s = np.sqrt(0.5)
    arc = NurbsCurve(
        2, [0, 0, 0, 1, 1, 1], [[0.5, 0, 0], [0.5, 0.5, 0.1], [0, 0.5, 0.2]], [1, s, 1]
    )
    tips = {}
    for c in ("C1", "C2"):
        for n in (4, 16):
            m = Model(
                mesh_nurbs(arc, n),
                "rod",
                Section.circular(0.02),
                Material(6000.0, 2e6, poisson_ratio=0.3),
                supports=[Support(0, "clamp")],
                gravity=(0, 0, -9.81),
                point_loads=[PointLoad(-1, None, (0.0, 0.0, 0.01))],
                continuity=c,
            )
            res = integrate(m, DynamicOptions(t_end=0.2, step=1e-3, rho_inf=0.9))
            tips[c, n] = m.node_positions(res.q[-1])[-1]
    moved = np.linalg.norm(tips["C1", 16] - [0.0, 0.5, 0.2])
    assert moved > 0.1
    coarse = np.linalg.norm(tips["C1", 4] - tips["C2", 4])
    fine = np.linalg.norm(tips["C1", 16] - tips["C2", 16])
    assert fine < coarse / 100 and fine < 1e-5  # 1.9e-2 m with 4 elements, 6e-6 m with 16


@pytest.mark.parametrize("dim", [2, 3])
def test_closed_c2_curves_have_continuous_curvature_across_the_seam(dim, rng):
    """Any C² state of a ring that keeps its seam rows (random coordinates projected onto their
    null space) is a closed curve whose curvature vector is continuous at every node but the
    supported one, the seam included (G²: r_R' = α r_L', r_R'' = α² r_L'' + β r_L' leave κ
    unchanged); a C¹ state is not.  The seam rows' Jacobian is their constant matrix (against
    central differences)."""
    ring = Ellipse(np.zeros(dim), 0.5, 0.3, *ellipse_axes(dim))
    for c in ("C2", "C1"):
        m = _cable(
            mesh_ellipse(ring, 9, start_deg=37.0), supports=[Support(3, "clamp")], continuity=c
        )
        s = System({"ring": m})
        assert s.m == m.dpn + (dim if c == "C2" else 0)  # positions, gradients (, curvature)
        dense = np.empty((s.n + s.m) ** 2)
        z = np.zeros(s.n)
        assert s.core.dense_jacobian(
            StatePoint(s.y0, z, z, np.zeros(s.m)), TangentOptions(0.0, 1.0), dense
        )
        a = dense.reshape(s.n + s.m, -1)[s.n :, : s.n]
        free = ~s.fixed
        for j in rng.choice(np.flatnonzero(free), 6, replace=False):
            gp, gm, e = np.empty(s.m), np.empty(s.m), np.zeros(s.n)
            e[j] = 1e-3
            s.core.constraints(s.y0 + e, 0.0, gp)
            s.core.constraints(s.y0 - e, 0.0, gm)
            assert np.abs((gp - gm) / 2e-3 - a[:, j]).max() < 1e-9 * np.abs(a).max()
        null = np.linalg.svd(a[:, free])[2][np.linalg.matrix_rank(a[:, free]) :].T
        y = s.y0.copy()
        y[free] += 0.05 * null @ rng.normal(size=null.shape[1])
        q = m.q_from_y(y)
        d1 = m.mesh.evaluate([0.0, 1.0], q, 1)
        d2 = m.mesh.evaluate([0.0, 1.0], q, 2)

        def kappa(a1, a2):
            c3 = np.cross(np.r_[a1, 0][:3], np.r_[a2, 0][:3])
            return c3 / np.linalg.norm(a1) ** 3

        left = [kappa(d1[e, 1], d2[e, 1]) for e in range(m.n_el)]  # end of element e
        right = [kappa(d1[(e + 1) % m.n_el, 0], d2[(e + 1) % m.n_el, 0]) for e in range(m.n_el)]
        jumps = np.abs(np.array(left) - np.array(right)).reshape(m.n_el, -1).max(axis=1)
        jump = np.delete(jumps, 2).max() / np.abs(left).max()  # node 3 is held: a C¹ node
        pos = m.node_positions(q)
        assert np.abs(pos[-1] - pos[0]).max() < 1e-13
        if c == "C2":
            assert jump < 1e-9
        else:
            assert jump > 1e-3


def test_a_curvature_jump_keeps_its_node_c1():
    """A cubic B-spline with a double knot (C¹ there, its curvature jumps): the node is a C¹ node,
    one more control point per coordinate (n + 4), and the reference is reproduced."""
    knots = [0, 0, 0, 0, 1, 2, 2, 3, 4, 4, 4, 4]
    pts = [[0, 0], [1, 1], [2, 0.5], [3, 1.5], [4, -1], [5, 0], [6, 1], [7, 0]]
    curve = NurbsCurve(3, knots, pts, np.ones(8))
    mesh = mesh_nurbs(curve)
    assert mesh.n_elements == 4
    mod = _cable(mesh, continuity="C2")
    assert mod.reduction.n_real == 2 * (4 + 4) and mod.reduction.node_base[2] >= 0
    assert np.abs(mod.q_from_y(mod.y0) - mesh.q0).max() < 1e-13 * np.abs(mesh.q0).max()


def test_rigid_motions_are_in_the_c2_space_and_strain_free():
    """Objectivity: the reference moved rigidly (turned and shifted) is a C² state with zero
    elastic force; a free C² cable has exactly 3 rigid-body modes."""
    mesh = mesh_nurbs(_bspline(2, 6, rational=True), 2)
    mod = _cable(mesh, continuity="C2")
    c, s = np.cos(0.7), np.sin(0.7)
    rot = np.array([[c, -s], [s, c]])
    nodes = mesh.nodes @ rot.T
    nodes[:, 0] += [0.3, -1.2]
    y = mod.y_from_q(nodes.ravel())
    assert np.abs(mod.q_from_y(y) - nodes.ravel()).max() < 1e-13
    scale = np.abs(mod.internal_force(mod.y0 + 1e-3 * mod.y0)).max()  # a 0.1 % stretch
    assert np.abs(mod.internal_force(y)).max() < 1e-9 * scale
    assert natural_modes(mod, count=3).n_rigid == 3


def test_initial_velocity_of_a_node_is_exact():
    """A node given an initial velocity keeps its own coordinates (a C¹ node): its velocity is
    the given one exactly (the C² space has no field moving one node alone)."""
    mod = _cable(
        mesh_line([0, 0], [1, 0], 10),
        supports=[Support(0, "clamp")],
        initial_velocities={4: (0.0, 0.3)},
        continuity="C2",
    )
    v = mod.q_from_y(mod.v0).reshape(mod.n_nodes, mod.dpn)
    assert np.array_equal(v[4, :2], [0.0, 0.3]) and mod.reduction.node_base[4] >= 0
    assert np.abs(v[0]).max() == 0.0 and np.abs(v[7:]).max() == 0.0  # only near node 4
    assert np.count_nonzero(mod.v0) == 1
