"""A straight stress-free state (``[mesh] stress_free = "straight"``): zero reference curvature
with the reference arc length (docs/derivations/variable-length.md §1).  The elastic force and
tangent against central differences of the energy and the force, objectivity (a rigid motion
rotates the force and keeps the energy; a straight rope moved rigidly carries no force), and the
bending energy of a wrapped arc ``EI θ R / (2 R²)``."""

from __future__ import annotations

import tomllib
from importlib.resources import files

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.errors import InputError, ScenarioError
from rancf.mesh.factories import mesh_line
from rancf.mesh.mesh import mesh_from_arrays
from rancf.scenario import parse_scenario

SEC, MAT = Section.circular(0.01), Material(1000.0, 1e7, poisson_ratio=0.3)
R = 0.5


def _arc_mesh(n: int, dim: int, angle: float = np.pi / 2):
    """A circular arc of radius R as exact rational cubics (degree-elevated conics)."""
    th = np.linspace(0.0, angle, n + 1)
    pts, wts = [], []
    for t0, t1 in zip(th[:-1], th[1:], strict=True):
        c = np.cos((t1 - t0) / 2)
        p0, p2 = (R * np.array([np.cos(t), np.sin(t)]) for t in (t0, t1))
        p1 = R / c * np.array([np.cos((t0 + t1) / 2), np.sin((t0 + t1) / 2)])
        w = (1 + 2 * c) / 3
        pts.append([p0, (p0 + 2 * c * p1) / (1 + 2 * c), (2 * c * p1 + p2) / (1 + 2 * c), p2])
        wts.append([1, w, w, 1])
    pts = np.array(pts)
    if dim == 3:
        pts = np.concatenate([pts, np.zeros(pts.shape[:-1] + (1,))], axis=-1) @ _rotation(3).T
    return mesh_from_arrays(pts, np.array(wts, float))


def _model(element: str, dim: int, stress_free: str = "straight", n: int = 3) -> Model:
    return Model(_arc_mesh(n, dim), element, SEC, MAT, stress_free=stress_free)


def _rotation(dim: int) -> np.ndarray:
    a, b = 0.7, -0.4
    if dim == 2:
        return np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
    rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
    return rx @ rz


def _moved(m: Model, y: np.ndarray, rot: np.ndarray, shift: np.ndarray) -> np.ndarray:
    """Positions and gradients rotated, positions shifted (a rod's twists unchanged)."""
    q = m.q_from_y(y).reshape(m.n_nodes, m.dpn).copy()
    d = m.dim
    q[:, :d] = q[:, :d] @ rot.T + shift
    q[:, d : 2 * d] = q[:, d : 2 * d] @ rot.T
    return m.y_from_q(q.ravel())


CASES = [("rancf", 2), ("ancf", 2), ("rancf", 3), ("rod", 3)]


@pytest.mark.parametrize(("element", "dim"), CASES)
def test_force_and_tangent_against_central_differences(element, dim):
    m = _model(element, dim)
    rng = np.random.default_rng(1)
    y = m.y0 + 1e-3 * rng.standard_normal(m.n)
    f, ab = m.internal_force_and_tangent(y)
    h = 1e-6
    f_fd = np.array(
        [(m.strain_energy(y + h * e) - m.strain_energy(y - h * e)) / (2 * h) for e in np.eye(m.n)]
    )
    assert np.max(np.abs(f - f_fd)) < 1e-6 * np.max(np.abs(f))
    k = np.zeros((m.n, m.n))
    for j in range(m.n):
        for i in range(max(0, j - m.ku), min(m.n, j + m.ku + 1)):
            k[i, j] = ab[m.ku + i - j, j]
    k_fd = np.column_stack(
        [(m.internal_force(y + h * e) - m.internal_force(y - h * e)) / (2 * h) for e in np.eye(m.n)]
    )
    assert np.max(np.abs(k - k_fd)) < 1e-6 * np.max(np.abs(k))


@pytest.mark.parametrize(("element", "dim"), CASES)
def test_rigid_motion_rotates_the_force_and_keeps_the_energy(element, dim):
    """The curved start is loaded (it is bent away from straight); a rigid motion of any state
    changes nothing but the direction of the forces."""
    m = _model(element, dim)
    rng = np.random.default_rng(2)
    y = m.y0 + 1e-3 * rng.standard_normal(m.n)
    rot, shift = _rotation(dim), np.arange(1.0, dim + 1.0)
    y2 = _moved(m, y, rot, shift)
    u, f = m.strain_energy(y), m.q_from_y(m.internal_force(y)).reshape(m.n_nodes, m.dpn)
    if element == "rod":  # the nodal reference triads (the rod's state) move with it
        m.kernel.tref[...] = m.kernel.tref @ rot.T
        m.kernel.m1ref[...] = m.kernel.m1ref @ rot.T
    assert abs(m.strain_energy(y2) - u) < 1e-12 * u
    f2 = m.q_from_y(m.internal_force(y2)).reshape(m.n_nodes, m.dpn)
    d = m.dim
    scale = np.max(np.abs(f))
    assert np.max(np.abs(f2[:, :d] - f[:, :d] @ rot.T)) < 1e-10 * scale
    assert np.max(np.abs(f2[:, d : 2 * d] - f[:, d : 2 * d] @ rot.T)) < 1e-10 * scale


@pytest.mark.parametrize(("element", "dim"), CASES)
def test_straight_rope_moved_rigidly_carries_no_force(element, dim):
    start, end = np.zeros(dim), np.r_[1.0, 0.4, 0.3][:dim]
    m = Model(mesh_line(start, end, 4), element, SEC, MAT, stress_free="straight")
    y = _moved(m, m.y0, _rotation(dim), np.full(dim, 0.3))
    assert np.max(np.abs(m.internal_force(y))) < 1e-9 * m.props.ea
    ref = Model(mesh_line(start, end, 4), element, SEC, MAT)  # the same as the reference state
    assert np.allclose(ref.internal_force(y + 1e-3), m.internal_force(y + 1e-3), rtol=0, atol=1e-9)


@pytest.mark.parametrize(("element", "dim"), CASES)
def test_wrapped_arc_stores_its_bending_energy(element, dim):
    """A quarter circle unloaded straight: ``U = EI (π/2) R / (2 R²)`` at the start (2D; the
    tilted 3D arc is a circle of radius R sqrt(1.01) over the same angle); the reference
    stress-free state stores nothing."""
    m = _model(element, dim, n=8)
    expected = m.props.ei * (np.pi / 2) * R / (2 * R**2)
    # exact circles to the quadrature's error; ANCF: the Hermite cubic through the circle's nodes
    tol = 1e-5 if element == "ancf" else 1e-9
    assert abs(m.strain_energy(m.y0) - expected) < tol * expected
    assert _model(element, dim, "reference").strain_energy(_model(element, dim).y0) < 1e-20


def test_bad_stress_free_names_the_key():
    with pytest.raises(InputError, match="mesh.stress_free"):
        Model(mesh_line([0, 0], [1, 0], 2), "beam", SEC, MAT, stress_free="straight")
    with pytest.raises(InputError, match="mesh.stress_free"):
        Model(mesh_line([0, 0], [1, 0], 2), "rancf", SEC, MAT, stress_free="bent")


def test_scenario_key_reaches_every_body_and_is_checked():
    """``[mesh] stress_free`` reaches a system's body (the capstan example's rope); a wrong value
    is one line naming the key."""

    raw = tomllib.loads((files("rancf.examples") / "capstan.toml").read_text())
    raw["bodies"][0]["mesh"]["stress_free"] = "straight"
    rope = parse_scenario(raw, "capstan.toml").build_system().bodies["rope"]
    assert rope.stress_free == "straight" and rope.strain_energy(rope.y0) > 0.0
    raw["bodies"][0]["mesh"]["stress_free"] = "bent"
    with pytest.raises(ScenarioError, match="stress_free"):
        parse_scenario(raw, "capstan.toml")
