"""The rod's rotary inertia: forces and tangents against finite differences of the
kinetic energy and of the forces, objectivity, the exact spin of rigid motions, re-referencing,
and the kinetic energy of a rigid rotation against the body's ½ ωᵀ I ω for any mesh.

Through the public :class:`~rancf.bodies.flexible.Model` and its compiled core only
(``core.inertia``, ``core.rotary_kinetic_energy``, ``core.rotary_angular_momentum``).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from rancf.bodies.flexible import Model, RigidMotion
from rancf.bodies.motion import angular_momentum
from rancf.bodies.properties import Material, Section, Support
from rancf.geometry.conic import conic_arc, conic_arc_through
from rancf.mesh.factories import mesh_conic, mesh_line
from tests.kernels.test_rod import ARC, deformed, rigid, rotation

MAT = Material(6000.0, 2.0e6, poisson_ratio=0.3)
ROUND = Section(3.0e-4, 1.5e-8, torsion_constant=2.5e-8)
SECTIONS = {"torsion": ROUND, "full": Section(3.0e-4, 1.5e-8, rotary_inertia="full")}


def inertia(m: Model, y, v, a, c=0.0, ck=0.0, cv=0.0, ca=0.0):
    """Inertial force and the combined tangent ``ck dF/dy + cv dF/dv + ca dF/da`` (dense)."""
    f, ab = np.empty(m.n), np.empty((2 * m.ku + 1, m.n))
    m.core.inertia(y, v, a, c, ck, cv, ca, f, ab)
    return f, m.dense(ab)


def fd_jacobian(fun, x: np.ndarray, h: float = 1e-6) -> np.ndarray:
    return np.array([(fun(x + h * e) - fun(x - h * e)) / (2 * h) for e in np.eye(x.size)]).T


def state(m: Model, rng, amp: float = 0.05):
    """A deformed, twisted configuration (triads not re-referenced) with random rates."""
    y = deformed(m, rng, amp)
    v, a = rng.standard_normal(m.n), rng.standard_normal(m.n)
    for x in (y, v, a):
        x[m.fixed] = 0.0 if x is not y else m.y0[m.fixed]
    return y, v, a


@pytest.mark.parametrize("rotary", ["torsion", "full"])
@pytest.mark.parametrize("geo", ["conic", "straight"])
def test_inertia_tangents_against_finite_differences_of_the_force(geo, rotary):
    """dF/dy, dF/dv, dF/da (damping c = 0.7 included) against central differences of F."""
    rng = np.random.default_rng(5)
    mesh = mesh_conic(ARC, 3) if geo == "conic" else mesh_line([0.1, -0.2, 0.3], [0.4, 0.2, 0.1], 3)
    m = Model(mesh, "rod", SECTIONS[rotary], MAT, [Support(0, "clamp")])
    y, v, a = state(m, rng)
    c = 0.7
    free = ~m.fixed
    for k, (coef, fun, x) in enumerate(
        (
            ((1, 0, 0), lambda z: inertia(m, z, v, a, c)[0], y),
            ((0, 1, 0), lambda z: inertia(m, y, z, a, c)[0], v),
            ((0, 0, 1), lambda z: inertia(m, y, v, z, c)[0], a),
        )
    ):
        jac = inertia(m, y, v, a, c, *coef)[1][np.ix_(free, free)]
        fd = fd_jacobian(fun, x)[np.ix_(free, free)]
        assert np.abs(jac).max() > 0
        # the mass (k = 2) is exactly linear: round-off of F / h only
        assert np.abs(fd - jac).max() <= (1e-7 if k < 2 else 1e-6) * np.abs(jac).max()
    mass = inertia(m, y, v, a, 0.0, 0, 0, 1)[1]
    assert np.abs(mass - mass.T).max() <= 1e-14 * np.abs(mass).max()


@pytest.mark.parametrize("rotary", ["torsion", "full"])
def test_inertial_force_is_the_lagrange_derivative_of_the_kinetic_energy(rotary):
    """F(y, v, a) = d/dt ∂T/∂v − ∂T/∂y with T the core's rotary kinetic energy, all by finite
    differences of T (d/dt along y' = v, v' = a); ½ vᵀ M v = T; damping adds c ∂T/∂v."""
    rng = np.random.default_rng(9)
    m = Model(mesh_conic(ARC, 3), "rod", SECTIONS[rotary], MAT)
    y, v, a = state(m, rng)

    def kin(yy, vv):
        return m.core.rotary_kinetic_energy(yy, vv)

    def momentum(yy, vv, h=1e-6):  # ∂T/∂v
        return np.array(
            [(kin(yy, vv + h * e) - kin(yy, vv - h * e)) / (2 * h) for e in np.eye(m.n)]
        )

    eps = 1e-5
    dpdt = (momentum(y + eps * v, v + eps * a) - momentum(y - eps * v, v - eps * a)) / (2 * eps)
    dtdy = np.array([(kin(y + 1e-6 * e, v) - kin(y - 1e-6 * e, v)) / 2e-6 for e in np.eye(m.n)])
    f = inertia(m, y, v, a)[0]
    assert np.abs(f).max() > 0
    assert np.abs(dpdt - dtdy - f).max() <= 1e-5 * np.abs(f).max()
    mass = inertia(m, y, v, a, 0.0, 0, 0, 1)[1]
    assert 0.5 * v @ mass @ v == pytest.approx(kin(y, v), rel=1e-12)
    assert inertia(m, y, v, a, 0.3)[0] - f == pytest.approx(
        0.3 * mass @ v, abs=1e-12 * np.abs(f).max()
    )


def turn(m: Model, x: np.ndarray, qr: np.ndarray) -> np.ndarray:
    """Rates ``x`` (model coordinates) of positions and gradients rotated by ``qr``."""
    q = m.q_from_y(x).reshape(-1, 7)
    return m.y_from_q(np.concatenate([q[:, :3] @ qr.T, q[:, 3:6] @ qr.T, q[:, 6:]], 1).ravel())


def test_inertia_is_objective():
    """A rigid rotation of the state (positions, gradients, their rates; triads rotated along)
    leaves T unchanged and rotates F; the twist components are unchanged."""
    rng = np.random.default_rng(2)
    m = Model(mesh_conic(ARC, 4), "rod", SECTIONS["full"], MAT)
    y, v, a = state(m, rng)
    t0, f0 = m.core.rotary_kinetic_energy(y, v), inertia(m, y, v, a)[0].reshape(m.n_nodes, 7)
    for ang in (np.pi / 3, 2.5):
        qr = rotation(rng.standard_normal(3), ang)
        triads = (m.kernel.tref.copy(), m.kernel.m1ref.copy())
        yr = rigid(m, y, qr, rng.standard_normal(3))  # rotates the triads too
        vr, ar = (turn(m, x, qr) for x in (v, a))
        assert m.core.rotary_kinetic_energy(yr, vr) == pytest.approx(t0, rel=1e-12)
        fr = inertia(m, yr, vr, ar)[0].reshape(m.n_nodes, 7)
        want = np.concatenate([f0[:, :3] @ qr.T, f0[:, 3:6] @ qr.T, f0[:, 6:]], 1)
        assert np.abs(fr - want).max() <= 1e-12 * np.abs(f0).max()
        m.kernel.tref[...], m.kernel.m1ref[...] = triads


def test_spin_of_a_rigid_motion_is_omega_dot_t_everywhere():
    """At a deformed, re-referenced state moving rigidly (twist rates ω·t at the nodes), the
    spin at every quadrature point of the curved elements is ω·t(ξ) exactly, though the
    smallest-rotation terms do not vanish there: T = ½ Σ w ρ I_p (ω·t)² to 1e-13."""
    rng = np.random.default_rng(4)
    m = Model(mesh_conic(ARC, 4), "rod", SECTIONS["torsion"], MAT)
    y = deformed(m, rng, 0.05)
    m.core.rereference(y)
    q = m.q_from_y(y).reshape(m.n_nodes, 7)
    w = np.array([0.4, -1.3, 2.2])
    vq = np.zeros_like(q)
    vq[:, :3] = np.cross(w, q[:, :3])
    vq[:, 3:6] = np.cross(w, q[:, 3:6])
    vq[:, 6] = q[:, 3:6] @ w / np.linalg.norm(q[:, 3:6], axis=1)
    c = m.kernel.cable
    el = np.stack([q[:-1, :3], q[:-1, 3:6], q[1:, :3], q[1:, 3:6]], axis=1)  # (n_el, 4, 3)
    tq = np.einsum("eqk,eki->eqi", c.n1, el)
    tq /= np.linalg.norm(tq, axis=2, keepdims=True)
    rho_p = MAT.density * ROUND.polar
    want = 0.5 * rho_p * np.sum(c.wj * (tq @ w) ** 2)
    got = m.core.rotary_kinetic_energy(y, m.y_from_q(vq.ravel()))
    assert got == pytest.approx(want, rel=1e-13)
    sq = np.einsum("eqi,eqi->eq", tq, np.cross(w, tq))  # a twist-free check of the setup: 0
    assert np.abs(sq).max() < 1e-15
    m.reset_triads()


def test_rereferencing_keeps_the_spin_and_its_rate():
    """core.rereference(y, v, a) moves the references to the current tangents and changes the
    twist rates so that kinetic energy, angular momentum and the physical inertial force are
    the same: the twist component of F and F · δq for a motion that keeps the twist angle of
    the new references are unchanged."""
    rng = np.random.default_rng(8)
    m = Model(mesh_conic(ARC, 4), "rod", SECTIONS["torsion"], MAT)
    y, v, a = state(m, rng, 0.08)
    t0 = m.core.rotary_kinetic_energy(y, v)
    l0 = m.core.rotary_angular_momentum(y, v)
    f0 = inertia(m, y, v, a)[0]
    v1, a1 = v.copy(), a.copy()
    m.core.rereference(y, v1, a1)
    assert np.abs(v1 - v).max() > 1e-3  # the twist rates changed
    assert np.array_equal(np.delete(v1, np.s_[6::7]), np.delete(v, np.s_[6::7]))
    assert m.core.rotary_kinetic_energy(y, v1) == pytest.approx(t0, rel=1e-12)
    assert np.allclose(m.core.rotary_angular_momentum(y, v1), l0, rtol=1e-12, atol=0)
    f1 = inertia(m, y, v1, a1)[0]
    assert f1[6::7] == pytest.approx(f0[6::7], rel=1e-10, abs=1e-12 * np.abs(f0).max())
    m.reset_triads()


# ------------------------------------------------------------------ rigid rotation, any mesh
ARC62 = conic_arc_through([0, 0, 0], [0.5, 0, 0], [60, 30], [0.264, 0, 0.069])  # example 6.2
W, C = np.array([0.3, -0.5, 2.0]), np.array([0.1, 0.2, -0.1])


def _exact_energy(arc, sec: Section, rho: float, w, c, rotary: str | None) -> float:
    """½ ωᵀ I ω of the modelled body by adaptive quadrature on the exact curve (1e-13)."""

    def density(u: float) -> float:
        r, ru = (d[0] for d in arc.derivatives([u], 1))
        sp = np.linalg.norm(ru)
        t = ru / sp
        vel = np.cross(w, r - c) if r.size == 3 else w * np.array([c[1] - r[1], r[0] - c[0]])
        e = rho * sec.area * vel @ vel
        if rotary is not None:
            e += rho * sec.polar * (w @ t) ** 2
        if rotary == "full":
            e += rho * sec.inertia * (w @ w - (w @ t) ** 2)
        return 0.5 * e * sp

    return quad(density, 0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)[0]


@pytest.mark.parametrize("kind", ["cable 2D", "cable 3D", "rod", "rod full"])
def test_kinetic_energy_of_a_rigid_rotation_is_exact_for_any_mesh(kind):
    """[initial_motion] gives every coordinate its rigid-body velocity, so T = ½ ωᵀ I ω of the
    body (rod: with ρ I_p about the tangent, "full" also ρ I about both bending axes) to 1e-10
    at 4, 8, 16, 32 and 64 elements (measured <= 1e-13); the per-node [[initial_velocity]] of
    the same tip speed gives an energy that depends on the mesh without a limit (it halves with
    every refinement; with the bending rotary inertia it does not even settle)."""
    sec = SECTIONS["full"] if kind == "rod full" else Section.circular(0.02)
    if kind == "cable 2D":
        arc, w, c = conic_arc(0.5, [60, 30], [0.264, 0.069]), np.array([2.0]), C[:2]
        rotary = None
    else:
        arc, w, c = ARC62, W, C
        rotary = None if kind == "cable 3D" else sec.rotary_inertia
    element = "rancf" if kind.startswith("cable") else "rod"
    exact = _exact_energy(arc, sec, MAT.density, w, c, rotary)
    tip = []
    for n in (4, 8, 16, 32, 64):
        m = Model(
            mesh_conic(arc, n),
            element,
            sec,
            MAT,
            initial_motion=RigidMotion(angular_velocity=w, about=c),
        )
        assert m.kinetic_energy(m.v0) == pytest.approx(exact, rel=1e-10)
        # angular momentum of a rigid rotation: L · ω = 2 T
        lmom = angular_momentum(m, m.q0, m.q_from_y(m.v0), c)[0]
        assert lmom @ w == pytest.approx(2 * exact, rel=1e-10)
        v_tip = m.q_from_y(m.v0).reshape(m.n_nodes, -1)[-1, : m.dim]
        one = Model(mesh_conic(arc, n), element, sec, MAT, initial_velocities={-1: v_tip})
        tip.append(one.kinetic_energy(one.v0))
    ratios = np.array(tip[:-1]) / np.array(tip[1:])
    if kind == "rod full":  # the node's bending rotary energy ~ ρ I (v / h)² h grows instead
        assert np.all(np.abs(ratios - 1.0) > 0.02)
    else:
        assert np.all(np.abs(ratios - 2.0) < 0.2)  # mesh dependent, no limit


def test_beam_rigid_rotation_momentum_and_energy_agree():
    """The planar beam's angular momentum (its own consistent mass) satisfies L ω = 2 T."""
    motion = RigidMotion(angular_velocity=1.5, about=[0.1, 0.0])
    mesh = mesh_conic(conic_arc(0.5, [30, 40], [0.315, 0.077]), 6)
    m = Model(mesh, "beam", Section.circular(0.02), MAT, initial_motion=motion)
    lz = angular_momentum(m, m.q0, m.q_from_y(m.v0), [0.1, 0.0])[0, 0]
    assert lz * 1.5 == pytest.approx(2 * m.kinetic_energy(m.v0), rel=1e-12)
