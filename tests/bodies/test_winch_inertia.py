"""The inertia of material flowing through a cable's mesh (rancf.bodies.winch_inertia;
docs/derivations/variable-length.md §2.2): a rope paid out rigidly along a straight line, at
either end, has the material acceleration ``L̈ e`` everywhere and the kinetic energy
``½ ρ A L L̇²``; both to round-off for any ``L, L̇, L̈`` (the matrices are exact for it)."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.length import reference_length, set_unstretched_length
from rancf.bodies.winch_inertia import convective_matrices
from rancf.mesh.factories import mesh_line

SEC, MAT = Section.circular(0.005), Material(7850.0, 2e11)


def _band_times(m: Model, ab: np.ndarray, x: np.ndarray) -> np.ndarray:
    return m.dense(ab) @ x


@pytest.mark.parametrize("element", ["ancf", "rancf"])
@pytest.mark.parametrize("at", ["start", "end"])
def test_rigid_payout_has_the_material_acceleration_and_energy(element, at):
    e = np.array([0.6, -0.8])
    w = np.array([0.3, 0.2])
    start, end = (w, w + 5.0 * e) if at == "start" else (w - 5.0 * e, w)
    m = Model(mesh_line(start, end, 7), element, SEC, MAT)
    l_ref = reference_length(m)
    c1, c2, d2 = convective_matrices(m, at)
    rng = np.random.default_rng(4)
    for length, rate, acc in rng.uniform([3.0, -2.0, -1.0], [15.0, 2.0, 1.0], (3, 3)):
        set_unstretched_length(m, length)
        lam = length / l_ref
        q0 = m.q_from_y(m.y0).reshape(m.n_nodes, m.dpn)

        # the rope stretched about the winch point w: positions w + f (r - w), gradients f r_x
        def shape(f: float, q0: np.ndarray = q0) -> np.ndarray:
            q = q0.copy()
            q[:, :2] = w + f * (q0[:, :2] - w)
            q[:, 2:] = f * q0[:, 2:]
            return m.y_from_q(q.ravel())

        y = shape(lam)
        v = shape(rate / l_ref) - shape(0.0)  # d/dt of w + λ (r - w): λ̇ (r - w)
        a = shape(acc / l_ref) - shape(0.0)
        force = (
            m.mass_times(a)
            + 2 * rate * _band_times(m, c1, v)
            + _band_times(m, (acc - 2 * rate**2 / length) * c1 + rate**2 / length * c2, y)
        )
        sign = 1.0 if at == "start" else -1.0  # material moves away from the winch
        expected = m.to_y(m.assemble_vector(m.kernel.gravity_forces(sign * acc * e)))
        assert np.max(np.abs(force - expected)) < 1e-10 * np.max(np.abs(expected))
        kinetic = (
            0.5 * v @ m.mass_times(v)
            + rate * v @ _band_times(m, c1, y)
            + 0.5 * rate**2 / length * y @ _band_times(m, d2, y)
        )
        assert kinetic == pytest.approx(0.5 * m.props.rho_a * length * rate**2, rel=1e-12)


@pytest.mark.parametrize("at", ["start", "end"])
def test_curved_motion_against_material_time_differences(at):
    """Any motion ``q(t)`` (curved, random) and any ``L(t)``: the generalized inertia force and
    the kinetic energy of the formulas against those of the material points' accelerations and
    velocities by central differences in time, following each material point through the mesh
    (a straight uniform ANCF mesh, where ``σ`` is linear in ``ξ``)."""
    from rancf.elements.cable import cable_shape_functions

    n_el = 6
    m = Model(mesh_line([0.0, 0.0], [2.0, 0.0], n_el), "ancf", SEC, MAT)
    c1, c2, d2 = convective_matrices(m, at)
    rng = np.random.default_rng(5)
    q0 = m.q_from_y(m.y0)
    q1, q2 = 0.3 * rng.standard_normal((2, m.n))

    def q_of(t: float) -> np.ndarray:
        return q0 + t * q1 + t * t * q2

    def length_of(t: float) -> float:
        return 2.0 + 0.7 * t + 0.4 * t * t

    t0, h = 0.3, 1e-4
    k = m.kernel
    set_unstretched_length(m, length_of(t0))
    # material points: those at the Gauss points at t0; mass per point ρA L dσ
    sig0 = ((np.arange(n_el)[:, None] + k.xi[None, :]) / n_el).ravel()
    dm = m.props.rho_a * length_of(t0) * np.tile(k.gw, n_el) / n_el

    def frac(s0: float, t: float) -> float:  # the material point's σ at t
        if at == "start":  # m = (1 - σ) L fixed
            return 1.0 - (1.0 - s0) * length_of(t0) / length_of(t)
        return s0 * length_of(t0) / length_of(t)

    def position(s: float, t: float) -> np.ndarray:
        e = min(int(s * n_el), n_el - 1)
        n0 = cable_shape_functions(k.weights[e : e + 1], k.scales[e : e + 1], [s * n_el - e])[0]
        qe = q_of(t).reshape(m.n_nodes, 4)[e : e + 2].reshape(4, 2)
        return n0[0, 0] @ qe

    force_fd = np.zeros(m.n)
    kinetic_fd = 0.0
    for s0, w in zip(sig0, dm, strict=True):
        r = [position(frac(s0, t0 + j * h), t0 + j * h) for j in (-1, 0, 1)]
        acc, vel = (r[2] - 2 * r[1] + r[0]) / h**2, (r[2] - r[0]) / (2 * h)
        e = min(int(s0 * n_el), n_el - 1)
        n0 = cable_shape_functions(k.weights[e : e + 1], k.scales[e : e + 1], [s0 * n_el - e])[0]
        idx = (4 * e + np.arange(8)).reshape(4, 2)
        force_fd[idx] += w * np.outer(n0[0, 0], acc)
        kinetic_fd += 0.5 * w * vel @ vel
    ll, rate, acc2 = length_of(t0), 0.7 + 0.8 * t0, 0.8
    y, v, a = q_of(t0), q1 + 2 * t0 * q2, 2 * q2
    force = (
        m.mass_times(a)
        + 2 * rate * _band_times(m, c1, v)
        + _band_times(m, (acc2 - 2 * rate**2 / ll) * c1 + rate**2 / ll * c2, y)
    )
    assert np.max(np.abs(force - force_fd)) < 1e-5 * np.max(np.abs(force))
    kinetic = (
        0.5 * v @ m.mass_times(v)
        + rate * v @ _band_times(m, c1, y)
        + 0.5 * rate**2 / ll * y @ _band_times(m, d2, y)
    )
    assert kinetic == pytest.approx(kinetic_fd, rel=1e-6)
