"""The rod element: derivatives, objectivity, closed forms, mass.

Everything goes through the public :class:`~rancf.bodies.flexible.Model` and its compiled core as a
black box: forces against central differences of the strain energy, tangents against central
differences of the forces, the load stiffness of point moments against central differences of
the external force, rigid motions, and the closed forms of ``docs/derivations/rod-kernel.md``
(docs/derivations/rod.md §7)
(restated in docs/guide/rods.md).
"""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Model
from rancf.bodies.properties import Material, PointLoad, Section, Support
from rancf.geometry.conic import conic_arc_through
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.static import solve_static

MAT = Material(6000.0, 2.0e6, poisson_ratio=0.3)
SEC = Section(3.0e-4, 1.2e-8, 2.0e-8, 2.5e-8, (0.0, 0.0, 1.0))  # unequal principal inertias
ARC = conic_arc_through([0, 0, 0], [0.5, 0.1, 0.2], [35, 50], [0.2, 0.15, 0.05])  # 3D ellipse


def rotation(axis, angle: float) -> np.ndarray:
    """Rodrigues' rotation matrix."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def mesh_of(geo: str, n: int = 3):
    if geo == "straight":
        return mesh_line([0.1, -0.2, 0.3], [0.4, 0.2, 0.1], n)
    return mesh_conic(ARC, n, "opt" if geo == "conic Kopt" else 0.3)


def rigid(model: Model, y: np.ndarray, q_rot: np.ndarray, shift) -> np.ndarray:
    """``y`` rotated by ``q_rot`` and shifted; the model's nodal triads are rotated along."""
    q = model.q_from_y(y).reshape(model.n_nodes, 7)
    out = q.copy()
    out[:, :3] = q[:, :3] @ q_rot.T + np.asarray(shift)
    out[:, 3:6] = q[:, 3:6] @ q_rot.T
    k = model.kernel
    k.tref[...] = k.tref @ q_rot.T
    k.m1ref[...] = k.m1ref @ q_rot.T
    return model.y_from_q(out.ravel())


def deformed(model: Model, rng, amp: float = 0.05) -> np.ndarray:
    """A random finite deformation with twists of order ``amp`` rad."""
    return model.y0 + amp * rng.standard_normal(model.n) * np.tile(
        [0.3] * 3 + [1.0] * 4, model.n_nodes
    )


def fd_gradient(fun, y: np.ndarray, h: float) -> np.ndarray:
    return np.array([(fun(y + h * e) - fun(y - h * e)) / (2 * h) for e in np.eye(y.size)])


GEOS = ["conic Kopt", "conic K=0.3", "straight"]


@pytest.mark.parametrize("clamped", [False, True], ids=["free", "clamped"])
@pytest.mark.parametrize("geo", GEOS)
def test_force_and_tangent_against_finite_differences(geo, clamped):
    rng = np.random.default_rng(hash((geo, clamped)) % 2**32)
    sups = [Support(0, "clamp"), Support(2, "pin", fix_twist=True)] if clamped else []
    m = Model(mesh_of(geo), "rod", SEC, MAT, sups)
    y = deformed(m, rng)
    # an arbitrary rigid rotation of the deformed state (nodal triads not re-referenced)
    y = rigid(m, y, rotation(rng.standard_normal(3), rng.uniform(0, np.pi)), rng.standard_normal(3))
    f, kb = m.internal_force_and_tangent(y)
    k = m.dense(kb)
    assert np.abs(f).max() > 1e-3 * m.props.ea * 1e-3  # a real deformation, not the reference
    f_fd = fd_gradient(m.strain_energy, y, 1e-6)
    assert np.abs(f_fd - f).max() <= 1e-6 * np.abs(f).max()
    k_fd = fd_gradient(m.internal_force, y, 1e-6).T
    assert np.abs(k_fd - k).max() <= 1e-6 * np.abs(k).max()
    # the Hessian is symmetric: analytically and by finite differences
    assert np.abs(k - k.T).max() <= 1e-12 * np.abs(k).max()
    assert np.abs(k_fd - k_fd.T).max() <= 1e-6 * np.abs(k).max()


@pytest.mark.parametrize("geo", ["conic Kopt", "straight"])
def test_load_stiffness_of_point_moments_against_finite_differences(geo):
    rng = np.random.default_rng(7)
    loads = [
        PointLoad(-1, moment=(0.01, 0.02, -0.03)),
        PointLoad(1, (0.1, 0, 0), 2.0, (0, 0.05, 0)),
    ]
    m = Model(mesh_of(geo), "rod", SEC, MAT, [Support(0, "clamp")], point_loads=loads)
    y = deformed(m, rng)
    for t in (0.0, 0.1):
        ab = np.empty((2 * m.ku + 1, m.n))
        m.core.load_stiffness(t, y, ab, False)
        lk = m.dense(ab)
        lk_fd = fd_gradient(lambda z, t=t: m.external_force(t, z), y, 1e-6).T
        assert np.abs(lk).max() > 1e-3
        assert np.abs(lk_fd - lk).max() <= 1e-7 * np.abs(lk).max()


def test_point_moment_is_conjugate_to_the_rotation_at_a_rereferenced_state():
    """At a re-referenced node (φ = 0) the generalized force of M is M·t on φ and M × t / |r_x|
    on r_x (docs/derivations/rod.md §5): a tiny rotation of the tip section by ``δθ`` does work
    ``M·δθ``."""
    m = Model(mesh_of("straight"), "rod", SEC, MAT, point_loads=[PointLoad(-1, moment=(1, 2, 3))])
    f = m.external_force(0.0, m.y0)
    tip = f.reshape(m.n_nodes, 7)[-1]
    g = m.q0.reshape(m.n_nodes, 7)[-1, 3:6]
    t = g / np.linalg.norm(g)
    for dtheta in np.eye(3):
        dg = np.cross(dtheta, g)  # the gradient rotates with the section
        work = tip[3:6] @ dg + tip[6] * (dtheta @ t)
        assert work == pytest.approx(np.array([1.0, 2.0, 3.0]) @ dtheta, abs=1e-12)


def _triad_rotation(m: Model, y_minus: np.ndarray, y_plus: np.ndarray, node: int) -> np.ndarray:
    """Rotation vector between two nearby nodal triads, ``½ Σ a × δa`` over (t, m1, m2)."""
    frames = []
    for y in (y_minus, y_plus):
        t, m1 = np.empty((m.n_nodes, 3)), np.empty((m.n_nodes, 3))
        m.core.nodal_triads(y, t, m1)
        frames.append((t[node], m1[node], np.cross(t[node], m1[node])))
    return 0.5 * sum(np.cross(a, b - a) for a, b in zip(*frames, strict=True))


def test_point_moment_does_the_work_of_the_triad_rotation_at_any_state():
    """Away from the re-referenced state too: ``g · δ(r_x, φ) = M · δθ`` of the nodal triad."""
    rng = np.random.default_rng(11)
    moment = np.array([0.7, -1.1, 0.4])
    m = Model(
        mesh_of("conic Kopt"), "rod", SEC, MAT, point_loads=[PointLoad(-1, moment=tuple(moment))]
    )
    y = deformed(m, rng, 0.2)  # tangents and twists far from the nodal reference triads
    f = m.external_force(0.0, y)
    o = (m.n_nodes - 1) * 7 + 3
    for _ in range(5):
        d = np.zeros(m.n)
        d[o : o + 4] = rng.normal(size=4)
        h = 1e-6
        dtheta = _triad_rotation(m, y - h * d, y + h * d, m.n_nodes - 1)
        assert f[o : o + 4] @ (2 * h * d[o : o + 4]) == pytest.approx(moment @ dtheta, rel=1e-6)


def test_spatial_moment_answer_does_not_depend_on_the_load_steps():
    length = 1.0
    ei = MAT.youngs_modulus * SEC.inertia
    mom = (np.pi * ei / length, 0.0, np.pi * ei / length)
    tips = []
    for steps in (10, 40):
        m = Model(
            mesh_line([0, 0, 0], [length, 0, 0], 8),
            "rod",
            SEC,
            MAT,
            [Support(0, "clamp")],
            point_loads=[PointLoad(-1, moment=mom)],
        )
        tips.append(m.node_positions(solve_static(m, steps).q)[-1])
    assert np.linalg.norm(tips[0]) > 0.1 * length  # a large spatial deformation
    assert np.abs(tips[0] - tips[1]).max() <= 1e-8 * length


@pytest.mark.parametrize("geo", GEOS)
def test_objectivity_and_stress_free_reference(geo):
    rng = np.random.default_rng(3)
    m = Model(mesh_of(geo, 4), "rod", SEC, MAT)
    ea = m.props.ea
    y0 = m.y0.copy()
    y_def = deformed(m, rng)
    u_def = m.strain_energy(y_def)
    f_def = m.internal_force(y_def).reshape(m.n_nodes, 7)
    assert m.strain_energy(y0) <= 1e-20 * ea
    assert np.abs(m.internal_force(y0)).max() <= 1e-10 * ea
    angles = [np.pi, np.pi / 2, *rng.uniform(0, np.pi, 4)]
    for ang in angles:
        q_rot = rotation(rng.standard_normal(3), ang)
        shift = rng.standard_normal(3)
        triads = (m.kernel.tref.copy(), m.kernel.m1ref.copy())
        y_ref = rigid(m, y0, q_rot, shift)  # rotates the triads too
        assert m.strain_energy(y_ref) <= 1e-20 * ea
        assert np.abs(m.internal_force(y_ref)).max() <= 1e-10 * ea
        m.kernel.tref[...], m.kernel.m1ref[...] = triads
        y_rot = rigid(m, y_def, q_rot, shift)
        assert m.strain_energy(y_rot) == pytest.approx(u_def, rel=1e-11)
        f_rot = m.internal_force(y_rot).reshape(m.n_nodes, 7)
        want = np.concatenate([f_def[:, :3] @ q_rot.T, f_def[:, 3:6] @ q_rot.T, f_def[:, 6:]], 1)
        assert np.abs(f_rot - want).max() <= 1e-10 * ea
        m.kernel.tref[...], m.kernel.m1ref[...] = triads


def test_rereferencing_changes_nothing_physical():
    """Re-referencing the nodal triads at a deformed state keeps the energy (the triads are
    the same; only their bookkeeping changes)."""
    rng = np.random.default_rng(11)
    m = Model(mesh_of("conic Kopt", 4), "rod", SEC, MAT)
    y = deformed(m, rng)
    u = m.strain_energy(y)
    m.core.rereference(y)
    assert m.strain_energy(y) == pytest.approx(u, rel=1e-12)
    m.reset_triads()


def test_mass_matrix_total_mass_and_torsional_inertia():
    sec = Section.circular(0.02)
    straight = float(np.linalg.norm(np.subtract([0.4, 0.2, 0.1], [0.1, -0.2, 0.3])))
    for mesh, length in (
        (mesh_of("conic Kopt", 5), ARC.arc_length()),
        (mesh_of("straight"), straight),
    ):
        m = Model(mesh, "rod", sec, MAT)
        rho = MAT.density
        assert m.total_mass == pytest.approx(rho * sec.area * length, rel=1e-12)
        spin = np.zeros((m.n_nodes, 7))
        spin[:, 6] = 3.0  # uniform spin rate about the tangents
        ke = m.kinetic_energy(spin.ravel())
        assert ke == pytest.approx(0.5 * rho * sec.polar * length * 9.0, rel=1e-12)
        mass = m.dense(m.mass_matrix())  # the constant translation plus the rotary M_r(y0)
        assert np.abs(mass - mass.T).max() <= 1e-15 * np.abs(mass).max()
        assert np.linalg.eigvalsh(mass).min() > 0
        # gravity: the weight, on the positions only
        fg = m.kernel.gravity_forces([0.0, 0.0, -9.81])
        assert m.assemble_vector(fg).reshape(m.n_nodes, 7)[:, 2].sum() == pytest.approx(
            -9.81 * m.total_mass, rel=1e-12
        )


# ------------------------------------------------------------------------------ closed forms
E, NU, RHO = 2.0e9, 0.3, 1000.0
STEEL = Material(RHO, E, poisson_ratio=NU)


def test_straight_rod_twists_by_tl_over_gj():
    sec = Section.circular(0.01)
    gj = STEEL.shear * sec.torsion
    a, b = np.array([0.1, 0.2, -0.3]), np.array([0.7, -0.1, 0.5])
    length = float(np.linalg.norm(b - a))
    t = (b - a) / length
    torque = 1e-3 * gj / length  # a twist of 1e-3 rad
    m = Model(
        mesh_line(a, b, 6),
        "rod",
        sec,
        STEEL,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, moment=tuple(torque * t))],
    )
    res = solve_static(m, load_steps=1)
    phi = res.q.reshape(m.n_nodes, 7)[:, 6]
    s = np.linspace(0.0, length, m.n_nodes)
    assert phi == pytest.approx(torque * s / gj, rel=1e-6, abs=1e-12)
    # the centerline stays put up to the second-order stretch of a twist per current length,
    # about GJ K1² / EA ~ (K1 r)² = 1e-10
    assert np.abs(m.node_positions(res.q) - m.node_positions(m.q0)).max() < 1e-9 * length


@pytest.mark.parametrize("direction", [(0, 1, 0), (0, 0, 1)])
def test_straight_cantilever_tip_deflection(direction):
    sec = Section.circular(0.01)
    ei = E * sec.inertia
    length, n = 1.0, 8
    force = 1e-5 * 3 * ei / length**3  # tip deflection 1e-5 L
    m = Model(
        mesh_line([0, 0, 0], [length, 0, 0], n),
        "rod",
        sec,
        STEEL,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, tuple(force * np.array(direction)))],
    )
    tip = m.node_positions(solve_static(m, load_steps=1).q)[-1]
    want = force * length**3 / (3 * ei)
    assert tip @ np.array(direction) == pytest.approx(want, rel=1e-4)


def quarter_circle_tip(n: int) -> tuple[float, float]:
    """Out-of-plane tip deflection of a clamped quarter circle under P, and the closed form."""
    r = 1.0
    sec = Section.circular(0.01)
    ei, gj = E * sec.inertia, STEEL.shear * sec.torsion
    p = 1e-6 * ei / r**2
    arc = conic_arc_through([0, 0, 0], [r, r, 0], [45, 45], [r - r / np.sqrt(2), r / np.sqrt(2), 0])
    m = Model(
        mesh_conic(arc, n),
        "rod",
        sec,
        STEEL,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, (0.0, 0.0, p))],
    )
    tip = m.node_positions(solve_static(m, load_steps=1).q)[-1, 2]
    return tip, p * r**3 * (np.pi / (4 * ei) + (3 * np.pi / 4 - 2) / gj)


def test_quarter_circle_out_of_plane_tip_converges_to_castigliano():
    errors = []
    for n in (4, 8, 16):
        tip, want = quarter_circle_tip(n)
        errors.append(abs(tip / want - 1))
    assert errors[1] < 5e-3  # 8 elements: within 0.5 %
    assert errors[0] > errors[1] > errors[2]
    assert errors[1] / errors[2] > 3  # about second order (measured 4.0)


@pytest.mark.parametrize(("radius", "gap"), [(0.002, 1e-3), (0.01, 3e-3)])
def test_end_moment_rolls_a_cantilever_into_a_circle(radius, gap):
    """M = 2π EI / L rolls the cantilever up: the tip returns to the clamp.  The curvature is per
    current arc length and the strain Green–Lagrange, so pure bending also stretches the rod by
    about (κ r)² / 4 (docs/guide/rods.md); the gap is then about that stretch times L."""
    sec = Section.circular(radius)
    length = 1.0
    moment = 2 * np.pi * E * sec.inertia / length
    m = Model(
        mesh_line([0, 0, 0], [length, 0, 0], 16),
        "rod",
        sec,
        STEEL,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, moment=(0.0, 0.0, moment))],
    )
    res = solve_static(m, load_steps=20)
    pos = m.node_positions(res.q)
    assert np.linalg.norm(pos[-1]) < gap * length
    centre = np.array([0.0, length / (2 * np.pi), 0.0])
    radii = np.linalg.norm(pos - centre, axis=1)
    assert np.abs(radii / (length / (2 * np.pi)) - 1).max() < 5e-3
    # the stretch (κ r)² / 4 makes the moment roll the rod by 2π (1 + ε)², so its tip overlaps
    # the clamp by about 2 ε L
    k, eps = m.kernel.kref.copy(), np.empty(m.kernel.kref.shape[:2])
    m.core.rod_curvatures(res.y, k, eps)
    assert eps.mean() == pytest.approx((2 * np.pi / length * radius) ** 2 / 4, rel=0.1)
    if radius == 0.01:  # the discretization error (~4e-5 L at 16 elements) is below 2 ε L
        assert np.linalg.norm(pos[-1]) == pytest.approx(2 * eps.mean() * length, rel=0.1)
