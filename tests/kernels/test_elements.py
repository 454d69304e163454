"""Element mechanics: finite-difference checks, stress-free references, mass properties."""

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.geometry.conic import conic_arc, conic_arc_through
from rancf.geometry.quadrature import integrate
from rancf.kernels.cable import CableKernel, CableProperties
from rancf.mesh.factories import mesh_conic, mesh_line, to_ancf
from rancf.mesh.mesh import CableMesh
from tests.conftest import EXAMPLE1, EXAMPLE2

PROPS = CableProperties(ea=1.0e3, ei=2.0, rho_a=3.0)
# a section and material with EA = 1e3, EI = 2 and rho A = 3 (as PROPS)
SEC = Section(area=1.0, inertia=2.0e-3)
MAT = Material(density=3.0, youngs_modulus=1.0e3)


def _mesh(dim, geometry, k):
    if geometry == "line":
        return mesh_line([0.0] * dim, [0.8] + [0.3] * (dim - 1), 3)
    if dim == 2:
        conic = conic_arc(*EXAMPLE1)
    else:
        chord, ang, pt = EXAMPLE2
        conic = conic_arc_through([0, 0, 0], [chord, 0.1, 0.2], ang, [pt[0], 0.05, pt[1]])
    if k == "ancf":
        return to_ancf(mesh_conic(conic, 3))
    return mesh_conic(conic, 3, k)


CASES = [
    (dim, geo, k)
    for dim in (2, 3)
    for geo, k in [
        ("line", None),
        ("conic", 0.2),
        ("conic", "opt"),
        ("conic", 0.6),
        ("conic", "ancf"),
    ]
]


def _model(mesh: CableMesh, element: str = "rancf", n_qp: int | None = None) -> Model:
    """A free (unsupported) model: model coordinates are the nodal coordinates."""
    return Model(mesh, element, SEC, MAT, n_qp=n_qp)


def _fd_check(model: Model, y: np.ndarray) -> None:
    """Force = FD of the energy, tangent = FD of the force (central differences)."""
    f, kb = model.internal_force_and_tangent(y)
    kt = model.dense(kb)
    assert np.abs(model.internal_force(y) - f).max() <= 1e-13 * np.abs(f).max()
    h = 1e-6
    fd_f = np.zeros_like(f)
    fd_k = np.zeros_like(kt)
    for i in range(y.size):
        d = np.zeros_like(y)
        d[i] = h
        fd_f[i] = (model.strain_energy(y + d) - model.strain_energy(y - d)) / (2 * h)
        fd_k[:, i] = (model.internal_force(y + d) - model.internal_force(y - d)) / (2 * h)
    assert np.abs(fd_f - f).max() <= 1e-7 * np.abs(f).max()
    assert np.abs(fd_k - kt).max() <= 1e-7 * np.abs(kt).max()
    assert np.abs(kt - kt.T).max() <= 1e-13 * np.abs(kt).max()


@pytest.mark.parametrize(("dim", "geo", "k"), CASES)
def test_forces_and_tangent_against_finite_differences(dim, geo, k):
    model = _model(_mesh(dim, geo, k))
    y = model.y0 + 0.03 * np.random.default_rng(7).normal(size=model.n)
    _fd_check(model, y)


def _rotation(dim, angle):
    c, s = np.cos(angle), np.sin(angle)
    if dim == 2:
        return np.array([[c, -s], [s, c]])
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    kx = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + s * kx + (1 - c) * kx @ kx


@pytest.mark.parametrize(("dim", "geo", "k"), CASES)
def test_reference_and_its_rigid_motions_are_stress_free(dim, geo, k):
    model = _model(_mesh(dim, geo, k))
    scale = PROPS.ea  # force of a unit strain
    assert np.abs(model.internal_force(model.y0)).max() <= 1e-10 * scale
    rot = _rotation(dim, 2.1)
    nodes = model.y0.reshape(model.n_nodes, 2, dim) @ rot.T
    nodes[:, 0] += np.arange(1, dim + 1) * 0.7  # translate positions only
    moved = nodes.ravel()
    assert np.abs(model.internal_force(moved)).max() <= 1e-10 * scale
    kern = model.kernel
    bending_scale = PROPS.ei * np.sum(kern.wj * kern.kappa0**2) + 1e-30
    assert model.strain_energy(moved) <= 1e-12 * bending_scale + 1e-24 * PROPS.ea


def test_beam_against_finite_differences_and_rigid_motion():
    x = np.array([[0, 0], [0.2, 0.05], [0.4, 0.03], [0.55, -0.05]])
    ang = np.array([0.3, 0.1, -0.2, -0.6])
    t = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    mesh = CableMesh(
        nodes=np.stack([x, t], axis=1),
        weights=np.ones((3, 4)),
        scales=np.linalg.norm(np.diff(x, axis=0), axis=1),
        kind="ancf",
    )
    model = _model(mesh, "beam")
    ref = model.y0
    assert np.abs(model.internal_force(ref)).max() < 1e-12 * PROPS.ea
    rot = _rotation(2, 2.5)
    moved = np.concatenate([x @ rot.T + [1.0, -2.0], 2.5 * np.ones((4, 1))], 1).ravel()
    assert np.abs(model.internal_force(moved)).max() < 1e-10 * PROPS.ea
    _fd_check(model, ref + 0.05 * np.random.default_rng(3).normal(size=ref.size))


def _arc_integral(conic, fn):
    return integrate(lambda u: fn(conic(u)) * conic.speed(u), 0.0, 1.0, rtol=1e-14)


@pytest.mark.parametrize("k", ["opt", 0.2, 0.7])
def test_mass_matrix_reproduces_mass_centre_and_inertia(k):
    conic = conic_arc(*EXAMPLE1)
    m = mesh_conic(conic, 4, k)
    kern = CableKernel(m.weights, m.scales, m.element_nodal(), PROPS, 10)
    me = kern.mass_matrices()
    q = m.element_nodal().reshape(m.n_elements, -1)
    n_el = m.n_elements

    def field(fn):  # element-wise nodal vector of a field (position -> value, gradient -> dvalue)
        return np.array([fn(e) for e in m.element_nodal()]).reshape(n_el, -1)

    ux = field(lambda e: np.array([[1, 0], [0, 0], [1, 0], [0, 0]]))
    mass = np.einsum("ei,eij,ej->", ux, me, ux)
    length = conic.arc_length()
    assert mass == pytest.approx(PROPS.rho_a * length, rel=1e-12)
    centre = np.array([np.einsum("ei,eij,ej->", ux, me, q), 0.0])
    uy = field(lambda e: np.array([[0, 1], [0, 0], [0, 1], [0, 0]]))
    centre[1] = np.einsum("ei,eij,ej->", uy, me, q)
    ref = np.array([_arc_integral(conic, lambda p, i=i: p[:, i]) for i in (0, 1)])
    assert centre == pytest.approx(PROPS.rho_a * ref, rel=1e-12)
    # rotation about the origin: velocity field ez × r acts on positions and gradients
    rot = np.array([[0.0, -1.0], [1.0, 0.0]])
    vr = (m.element_nodal() @ rot.T).reshape(n_el, -1)
    inertia = np.einsum("ei,eij,ej->", vr, me, vr)
    ref_i = _arc_integral(conic, lambda p: np.sum(p**2, axis=1))
    assert inertia == pytest.approx(PROPS.rho_a * ref_i, rel=1e-12)


def test_gravity_force_is_weight_and_quadrature_converged():
    conic = conic_arc(*EXAMPLE1)
    m = mesh_conic(conic, 3, 0.3)
    k10 = CableKernel(m.weights, m.scales, m.element_nodal(), PROPS, 10)
    k20 = CableKernel(m.weights, m.scales, m.element_nodal(), PROPS, 20)
    g = k10.gravity_forces([0.0, -9.81]).reshape(3, 4, 2)
    assert g[:, [0, 2], 1].sum() == pytest.approx(
        -9.81 * PROPS.rho_a * conic.arc_length(), rel=1e-12
    )
    assert (
        np.abs(k10.mass_matrices() - k20.mass_matrices()).max()
        < 1e-12 * np.abs(k20.mass_matrices()).max()
    )
    y = m.q0 * 1.01
    f10, f20 = _model(m, n_qp=10).internal_force(y), _model(m, n_qp=20).internal_force(y)
    assert np.abs(f10 - f20).max() < 1e-9 * np.abs(f20).max()


def test_planar_curvature_is_signed():
    m = mesh_conic(conic_arc(*EXAMPLE1), 2)
    kern = CableKernel(m.weights, m.scales, m.element_nodal(), PROPS, 10)
    assert np.all(kern.kappa0 < 0)  # the arc turns clockwise from start to end
    mirrored = m.element_nodal() * np.array([1.0, -1.0])
    assert np.allclose(kern.curvatures(mirrored), -kern.kappa0, rtol=1e-13)
