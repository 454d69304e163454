"""The RANCF Kirchhoff–Love shell kernel (``src/cpp/elements/shell.cpp``,
docs/derivations/shell.md sec. 4–6): forces and tangents against central differences of the
energy, objectivity and the rigid modes, stress-free references on every surface kind, the
mass and area loads against the exact areas, the membrane patch test, and input errors."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.kernels.shell import MEMBRANE, ShellKernel, ShellRecord, surface_connectivity
from rancf.mesh.surface_kinds import mesh_surface

#: Surfaces of every kind, with their exact areas.
SURFACES = {
    "cylinder": (
        {"kind": "cylinder", "radius": 2.0, "length": 3.0, "angles_deg": [10.0, 170.0]},
        np.radians(160.0) * 2.0 * 3.0,
    ),
    "cone": (
        {"kind": "cone", "radius": [1.0, 2.0], "length": 3.0, "angles_deg": [0.0, 120.0]},
        0.5 * np.radians(120.0) * 3.0 * np.hypot(3.0, 1.0),
    ),
    "sphere": (
        {"kind": "sphere", "radius": 2.0, "azimuth_deg": [0.0, 90.0], "polar_deg": [30.0, 150.0]},
        4.0 * np.radians(90.0) * 2.0 * np.cos(np.radians(30.0)),
    ),
    "rectangle": ({"kind": "rectangle", "corner": [0.5, -1.0], "size": [2.0, 1.5]}, 3.0),
}
E, NU, T, RHO = 2.0e5, 0.3, 0.02, 7.0


def _kernel(kind, n=(2, 2), membrane="projected", gauss=5, k="opt"):
    mesh = mesh_surface(SURFACES[kind][0], list(n), k)
    return mesh, ShellKernel.from_mesh(mesh, T, E, NU, RHO, gauss=gauss, membrane=membrane)


def _rotation(angle, axis):
    a = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    w = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + np.sin(angle) * w + (1.0 - np.cos(angle)) * w @ w


def _moved(q, rot, shift):
    """Every nodal vector rotated, the positions also shifted."""
    nodes = q.reshape(-1, 4, 3) @ rot.T
    nodes[:, 0] += shift
    return nodes.ravel()


def _central(fun, q, h):
    cols = []
    for i in range(q.size):
        dq = np.zeros(q.size)
        dq[i] = h
        cols.append((np.asarray(fun(q + dq)) - np.asarray(fun(q - dq))) / (2.0 * h))
    return np.array(cols).T


@pytest.mark.parametrize("membrane", MEMBRANE)
@pytest.mark.parametrize("kind", ["cylinder", "sphere"])
def test_forces_and_tangent_are_the_derivatives_of_the_energy(kind, membrane):
    """f against central differences of W and K against central differences of f, relative to
    their largest entries, at 1e-6, in a state far from the reference (large rotations of the
    nodal gradients, stretch and bending)."""
    mesh, k = _kernel(kind, (2, 1), membrane)
    rng = np.random.default_rng(3)
    q = _moved(mesh.q0 + 0.05 * rng.normal(size=k.n), _rotation(0.7, [1, 2, 3]), [1, 2, 3])
    f, kt = k.forces(q), k.tangent(q).toarray()
    fd = _central(k.energy, q, 1e-6).ravel()
    assert np.abs(f - fd).max() <= 1e-6 * np.abs(f).max()
    kd = _central(k.forces, q, 1e-7)
    assert np.abs(kt - kd).max() <= 1e-6 * np.abs(kt).max()
    assert np.abs(kt - kt.T).max() <= 1e-12 * np.abs(kt).max()


@pytest.mark.parametrize("kind", sorted(SURFACES))
def test_reference_and_its_rigid_motions_are_stress_free(kind):
    """W = 0 and f = 0 to round-off in the reference of every kind and after a finite rotation
    and translation of it; the scale is the force of a strain of 1e-9."""
    mesh, k = _kernel(kind, (3, 2))
    scale = 1e-9 * E * T * np.abs(mesh.q0).max()
    for q in (mesh.q0, _moved(mesh.q0, _rotation(2.5, [0.3, -1.0, 0.4]), [4.0, -2.0, 7.0])):
        assert abs(k.energy(q)) <= 1e-18 * E * T * SURFACES[kind][1]
        assert np.abs(k.forces(q)).max() <= scale


def test_a_closed_cylinder_reference_is_stress_free():
    mesh = mesh_surface(
        {"kind": "cylinder", "radius": 1.0, "length": 2.0, "angles_deg": [0, 360]}, [4, 2]
    )
    k = ShellKernel.from_mesh(mesh, T, E, NU, RHO)
    assert k.energy(mesh.q0) == 0.0
    assert np.abs(k.forces(mesh.q0)).max() <= 1e-9 * E * T


def _rigid_modes(q):
    """Three translations and three infinitesimal rotations of every nodal vector."""
    nodes = q.reshape(-1, 4, 3)
    modes = []
    for d in range(3):
        t = np.zeros_like(nodes)
        t[:, 0, d] = 1.0
        modes.append(t.ravel())
        w = np.zeros(3)
        w[d] = 1.0
        modes.append(np.cross(w, nodes).ravel())
    return np.array(modes).T


@pytest.mark.parametrize("membrane", ["full", "projected"])
@pytest.mark.parametrize("kind", sorted(SURFACES))
def test_the_tangent_has_exactly_the_six_rigid_modes(kind, membrane):
    """K's null space: the rigid modes are in it (to round-off), and a free element and a free
    patch have exactly six zero eigenvalues (no spurious zero-energy mode), the seventh at
    least 1e-9 of the largest."""
    for n in ((1, 1), (2, 2)):
        mesh, k = _kernel(kind, n, membrane, gauss=4 if n == (1, 1) else 5)
        kt = k.tangent(mesh.q0).toarray()
        modes = _rigid_modes(mesh.q0)
        assert np.abs(kt @ modes).max() <= 1e-12 * np.abs(kt).max() * np.abs(modes).max()
        ev = np.linalg.eigvalsh(kt) / np.abs(kt).max()
        assert np.all(np.abs(ev[:6]) <= 1e-13) and ev[6] >= 1e-9, ev[:8]


def test_reduced_membrane_integration_has_spurious_modes():
    """The 3 × 3 membrane rule (the fallback, kept for the convergence study) leaves a free flat
    element with three zero-energy modes beyond the rigid ones: why the projection is the
    default."""
    mesh, k = _kernel("rectangle", (1, 1), "reduced")
    ev = np.linalg.eigvalsh(k.tangent(mesh.q0).toarray())
    assert int(np.sum(np.abs(ev) <= 1e-13 * np.abs(ev).max())) == 9


@pytest.mark.parametrize("kind", ["cylinder", "cone", "sphere", "rectangle"])
def test_total_mass_and_load_are_exact_on_exact_surfaces(kind):
    """A translation's kinetic mass ``1ᵀ M 1 = ρ t A`` and the total of a load per area ``p A``
    to 1e-12 relative (16 × 16 points resolve the rational area element to round-off)."""
    area = SURFACES[kind][1]
    for n in ((1, 1), (3, 2)):
        if kind == "cylinder" and n == (1, 1):
            continue  # one element may not turn through 160°: two at least
        _, k = _kernel(kind, n, gauss=16)
        mass = k.mass()
        for d in range(3):
            t = np.zeros(k.n)
            t[d::12] = 1.0
            assert t @ (mass @ t) == pytest.approx(RHO * T * area, rel=1e-12)
        p = np.array([0.3, -2.0, 1.1])
        load = k.area_load(p).reshape(-1, 4, 3)[:, 0].sum(axis=0)
        np.testing.assert_allclose(load, p * area, rtol=1e-12)
        np.testing.assert_allclose(
            k.gravity([0, 0, -9.81]).reshape(-1, 4, 3)[:, 0].sum(axis=0),
            [0, 0, -9.81 * RHO * T * area],
            rtol=1e-12,
        )
        assert np.linalg.eigvalsh(mass.toarray()).min() > 0.0


@pytest.mark.parametrize("membrane", MEMBRANE)
def test_a_uniform_membrane_stretch_gives_the_exact_energy(membrane):
    """Patch test: every nodal vector of a flat 3 × 2 patch mapped by one deformation gradient F
    (stretch and shear, then a rotation out of the plane): W = t A ψ(E) with the Green–Lagrange
    strain E = (FᵀF - I)/2 and the plane-stress density ψ to 1e-12, and no force at the
    interior nodes."""
    mesh = mesh_surface(SURFACES["rectangle"][0], [3, 2])
    k = ShellKernel.from_mesh(mesh, T, E, NU, RHO, membrane=membrane)
    f = np.array([[1.1, 0.05, 0.0], [0.02, 0.95, 0.0], [0.0, 0.0, 1.0]])
    q = _moved(mesh.q0, _rotation(0.9, [1.0, 1.0, 0.2]) @ f, [1.0, 0.0, 2.0])
    g = 0.5 * (f.T @ f - np.eye(3))
    psi = E / (2 * (1 - NU**2)) * (g[0, 0] ** 2 + g[1, 1] ** 2 + 2 * NU * g[0, 0] * g[1, 1])
    psi += E / (2 * (1 - NU**2)) * 2 * (1 - NU) * g[0, 1] ** 2
    assert k.energy(q) == pytest.approx(T * SURFACES["rectangle"][1] * psi, rel=1e-12)
    forces = k.forces(q).reshape(3, 4, 12)  # nodes [j, i]
    interior = forces[1, 1:3]
    assert np.abs(interior).max() <= 1e-10 * np.abs(forces).max()


def test_a_mesh_record_by_hand_matches_from_mesh():
    mesh, k = _kernel("sphere", (2, 2))
    rec = k.record
    assert rec.connectivity.tolist()[3] == [4, 5, 7, 8]
    np.testing.assert_array_equal(surface_connectivity(2, 2), rec.connectivity)
    again = ShellKernel(ShellRecord(**{**rec.__dict__}))
    q = mesh.q0 * 1.01
    assert again.energy(q) == k.energy(q)


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("membrane", "bogus", "shell.membrane: expected one of full, projected, reduced"),
        ("gauss", 3, "shell.gauss: expected 4 to 16 points per direction"),
        ("thickness", -1.0, "shell.thickness: expected a number > 0, got -1"),
        ("poisson_ratio", 0.5, "shell.poisson_ratio: expected a number in (-1, 0.5), got 0.5"),
        ("q0", np.zeros(7), "shell.q0: expected 12 coordinates a node, got 7"),
        ("connectivity", np.zeros((1, 4)), "shell.connectivity: expected an array of integers"),
        ("connectivity", np.array([[0, 1, 2, 4]]), "shell.connectivity: expected node indices"),
    ],
)
def test_bad_input_is_one_line_naming_the_field(field, value, message):
    _, k = _kernel("rectangle", (1, 1))
    with pytest.raises((ValueError, TypeError)) as err:
        ShellKernel(ShellRecord(**{**k.record.__dict__, field: value}))
    assert str(err.value).startswith(message)
    assert "\n" not in str(err.value)


def test_a_wrong_state_size_is_refused():
    _, k = _kernel("rectangle", (1, 1))
    with pytest.raises(ValueError, match="q: expected 48 values, got 47"):
        k.forces(np.zeros(47))


def test_pressure_forces_and_their_tangent():
    """A follower pressure along a3 (toward the axis on a cylinder): on the half cylinder
    ``[0°, 180°]`` its total force is ``-2 p R L e_z`` to 1e-12; in a deformed state its tangent
    is the central difference of its forces (1e-6) and not symmetric."""
    geo = {"kind": "cylinder", "radius": 2.0, "length": 3.0, "angles_deg": [0.0, 180.0]}
    mesh = mesh_surface(geo, [3, 2])
    k = ShellKernel.from_mesh(mesh, T, E, NU, RHO, gauss=16)
    total = k.pressure(mesh.q0, 5.0).reshape(-1, 4, 3)[:, 0].sum(axis=0)
    np.testing.assert_allclose(total, [0.0, 0.0, -2.0 * 5.0 * 2.0 * 3.0], atol=1e-12 * 60.0)
    k = ShellKernel.from_mesh(mesh, T, E, NU, RHO)
    q = mesh.q0 + 0.05 * np.random.default_rng(5).normal(size=k.n)
    kt = k.pressure_tangent(q, 5.0).toarray()
    kd = _central(lambda x: k.pressure(x, 5.0), q, 1e-6)
    assert np.abs(kt - kd).max() <= 1e-6 * np.abs(kt).max()
    assert np.abs(kt - kt.T).max() >= 1e-3 * np.abs(kt).max()


def test_pressure_on_a_flat_patch_is_p_times_area_along_the_normal():
    mesh, k = _kernel("rectangle", (3, 2))
    total = k.pressure(mesh.q0, -2.0).reshape(-1, 4, 3)[:, 0].sum(axis=0)
    np.testing.assert_allclose(total, [0.0, 0.0, -2.0 * 3.0], atol=1e-12)


def test_the_tangent_is_the_same_with_two_threads():
    """The element loop shared by two threads gives the same triplets bit for bit."""
    from rancf.kernels import _core

    mesh, k = _kernel("sphere", (8, 8))
    q = mesh.q0 + 0.01 * np.random.default_rng(2).normal(size=k.n)
    before = _core.assembly_threads()
    try:
        _core.set_assembly_threads(1)
        one = k.core.tangent(q)
        _core.set_assembly_threads(2)
        two = k.core.tangent(q)
    finally:
        _core.set_assembly_threads(before)
    assert all(np.array_equal(a, b) for a, b in zip(one, two, strict=True))
