"""Kelvin-Voigt strain-rate damping of cable elements (docs/derivations/strain-rate-damping.md):
the force against its definition's finite differences, its Jacobians ``∂f/∂y`` and ``∂f/∂v``
against central differences of the force, zero force under rigid motions of curved references,
and the coefficients reaching the core by name."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.flexible_core import section_stiffness
from rancf.bodies.motion import RigidMotion, rigid_velocity
from rancf.bodies.properties import StrainRateDamping
from rancf.bodies.strain_rate import damping_force
from rancf.errors import InputError
from rancf.geometry.conic import conic_arc
from rancf.mesh.factories import mesh_conic, mesh_line
from tests.conftest import EXAMPLE1
from tests.kernels.test_elements import CASES, _mesh, _rotation
from tests.kernels.test_rod import deformed, mesh_of

SEC = Section(area=1.0e-4, inertia=2.0e-9)
E_MOD = 2.0e11
CA, CB = 3.0e4, 0.7  # N s, N m^2 s


def _model(mesh, axial=CA, bending=CB, strain="green_lagrange"):
    mat = Material(density=7850.0, youngs_modulus=E_MOD, axial_strain=strain)
    return Model(mesh, "rancf", SEC, mat, strain_rate_damping=StrainRateDamping(axial, bending))


def _state(model, seed=3):
    rng = np.random.default_rng(seed)
    scale = np.abs(model.y0).max()
    return model.y0 + 0.02 * scale * rng.normal(size=model.n), rng.normal(size=model.n)


def _dissipation(model, y, v):
    """``D = ½ ∫ (c_a ε̇² + c_b κ̇²) dx`` by the force: ``f_d · v = 2 D`` and ``f_d`` linear in v."""
    return 0.5 * damping_force(model, y, v) @ v


@pytest.mark.parametrize("strain", ["green_lagrange", "engineering"])
@pytest.mark.parametrize(("dim", "geo", "k"), CASES)
def test_force_is_the_gradient_of_the_dissipation_in_v(dim, geo, k, strain):
    # f_d = dD/dv (D quadratic in v): central differences of D are exact up to rounding
    model = _model(_mesh(dim, geo, k), strain=strain)
    y, v = _state(model)
    f = damping_force(model, y, v)
    h = 1e-3
    fd = np.array(
        [
            (_dissipation(model, y, v + h * e) - _dissipation(model, y, v - h * e)) / (2 * h)
            for e in np.eye(model.n)
        ]
    )
    assert np.abs(fd - f).max() <= 1e-9 * np.abs(f).max()


@pytest.mark.parametrize("strain", ["green_lagrange", "engineering"])
@pytest.mark.parametrize(("dim", "geo", "k"), CASES)
def test_jacobians_against_central_differences(dim, geo, k, strain):
    model = _model(_mesh(dim, geo, k), strain=strain)
    y, v = _state(model)
    f, ab_y = damping_force(model, y, v, ck=1.0, cv=0.0)
    _, ab_v = damping_force(model, y, v, ck=0.0, cv=1.0)
    _, ab_mix = damping_force(model, y, v, ck=0.3, cv=2.0)
    jy, jv = model.dense(ab_y), model.dense(ab_v)
    assert np.abs(model.dense(ab_mix) - (0.3 * jy + 2.0 * jv)).max() <= 1e-12 * np.abs(jy).max()
    assert np.abs(damping_force(model, y, v) - f).max() == 0.0
    _check_differences(model, y, v, jy, jv, 1e-6 * np.abs(y).max())
    assert np.abs(jy - jy.T).max() > 1e-3 * np.abs(jy).max()  # not symmetric: a real check
    assert np.abs(jv - jv.T).max() <= 1e-12 * np.abs(jv).max()  # c B^T B: symmetric


def _rigid_velocity(model, y, dim, seed=5):
    """``v = u + ω × (r − p)`` on positions, ``ω × r_x`` on gradients (nodal layout)."""
    rng = np.random.default_rng(seed)
    nodes = y.reshape(model.n_nodes, 2, dim)
    u, p = rng.normal(size=dim), rng.normal(size=dim)
    if dim == 2:
        w = rng.normal()
        skew = np.array([[0.0, -w], [w, 0.0]])
    else:
        w = rng.normal(size=3)
        skew = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    v = np.empty_like(nodes)
    v[:, 0] = u + (nodes[:, 0] - p) @ skew.T
    v[:, 1] = nodes[:, 1] @ skew.T
    return v.ravel()


@pytest.mark.parametrize("strain", ["green_lagrange", "engineering"])
@pytest.mark.parametrize(("dim", "geo", "k"), CASES)
def test_rigid_motion_is_not_damped(dim, geo, k, strain):
    # a curved reference, moved and turned away from it, in a rigid velocity field
    model = _model(_mesh(dim, geo, k), strain=strain)
    nodes = model.y0.reshape(model.n_nodes, 2, dim) @ _rotation(dim, 0.9).T
    nodes[:, 0] += 0.4
    y = nodes.ravel()
    v = _rigid_velocity(model, y, dim)
    rng = np.random.default_rng(8)
    deform = rng.normal(size=model.n)  # the same speed in a deforming field: a large force
    scale = np.abs(damping_force(model, y, deform * np.abs(v).max())).max()
    assert scale > 0.0
    assert np.abs(damping_force(model, y, v)).max() <= 1e-10 * scale


def test_no_coefficients_no_force_and_the_coefficients_reach_the_core():
    mesh = mesh_line([0.0, 0.0], [1.0, 0.0], 4)
    model = _model(mesh, 0.0, 0.0)
    y, v = _state(model)
    assert np.all(damping_force(model, y, v) == 0.0)
    axial, bend = _model(mesh, CA, 0.0), _model(mesh, 0.0, CB)
    st = section_stiffness(_model(mesh))
    assert (st.damping_axial, st.damping_bending, st.damping_torsion) == (CA, CB, 0.0)
    both = damping_force(_model(mesh), y, v)
    assert np.allclose(
        both,
        damping_force(axial, y, v) + damping_force(bend, y, v),
        rtol=1e-12,
        atol=1e-12 * np.abs(both).max(),
    )
    twice = damping_force(_model(mesh, 2 * CA, 2 * CB), y, v)
    assert np.allclose(twice, 2 * both, rtol=1e-12, atol=0.0)


@pytest.mark.parametrize(
    ("element", "kw", "key"),
    [
        ("rancf", {"torsion": 1.0}, "damping.torsion"),
        ("beam", {"torsion": 1.0}, "damping.torsion"),
        ("rancf", {"axial": -1.0}, "damping.axial"),
    ],
)
def test_keys_an_element_cannot_take_are_refused(element, kw, key):
    mesh = (
        mesh_line([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 2)
        if element == "rod"
        else mesh_line([0.0, 0.0], [1.0, 0.0], 2)
    )
    mat = Material(7850.0, E_MOD, poisson_ratio=0.3)
    with pytest.raises(InputError) as exc:
        Model(mesh, element, SEC, mat, strain_rate_damping=StrainRateDamping(**kw))
    assert exc.value.parameter == key


@pytest.mark.parametrize("strain", ["green_lagrange", "engineering"])
@pytest.mark.parametrize(("dim", "geo", "k"), [c for c in CASES if c[:2] != (3, "line")])
def test_velocity_jacobian_at_the_reference_is_the_scaled_elastic_tangent(dim, geo, k, strain):
    # at the stress-free reference d2U/dq2 = EA ∫ ε_q^T ε_q + EI ∫ κ_q^T κ_q: with c_a / EA =
    # c_b / EI = β the damping's (4) is β K_T, which ties ε_q, κ_q to the elastic law's (a
    # spatial straight reference's K_T is the Hessian of κ², which has no rate: left out)
    beta = 1.3e-4
    model = _model(_mesh(dim, geo, k), beta * E_MOD * SEC.area, beta * E_MOD * SEC.inertia, strain)
    _, kt = model.internal_force_and_tangent(model.y0)
    v = np.random.default_rng(4).normal(size=model.n)
    f, ab = damping_force(model, model.y0, v, ck=0.0, cv=1.0)
    expect = beta * model.dense(kt)
    assert np.abs(model.dense(ab) - expect).max() <= 1e-9 * np.abs(expect).max()
    assert np.abs(f - expect @ v).max() <= 1e-9 * np.abs(expect @ v).max()


# ---- rods: axial, torsion (K1) and bending (K2, K3) rates (src/cpp/elements/rod_damping.hpp)

ROD_MAT = Material(6000.0, 2.0e6, poisson_ratio=0.3)
ROD_SEC = Section(3.0e-4, 1.2e-8, 2.0e-8, 2.5e-8, (0.0, 0.0, 1.0))  # unequal principal inertias
ROD_KV = StrainRateDamping(axial=40.0, bending=3e-3, torsion=2e-3)


def _rod(geo: str, kv: StrainRateDamping = ROD_KV) -> Model:
    return Model(mesh_of(geo), "rod", ROD_SEC, ROD_MAT, strain_rate_damping=kv)


@pytest.mark.parametrize("geo", ["straight", "conic"])
def test_rod_jacobians_against_central_differences(geo):
    model = _rod(geo)
    rng = np.random.default_rng(6)
    y, v = deformed(model, rng), rng.normal(size=model.n)
    f, ab_y = damping_force(model, y, v, ck=1.0, cv=0.0)
    _, ab_v = damping_force(model, y, v, ck=0.0, cv=1.0)
    jy, jv = model.dense(ab_y), model.dense(ab_v)
    assert np.abs(f - jv @ v).max() <= 1e-12 * np.abs(f).max()  # linear in v
    _check_differences(model, y, v, jy, jv, 1e-6)


@pytest.mark.parametrize("geo", ["straight", "conic"])
def test_rod_rigid_motion_is_not_damped(geo):
    model = _rod(geo)
    motion = RigidMotion(
        velocity=(0.3, -0.2, 0.5), angular_velocity=(1.1, -0.7, 0.4), about=(0.2, 0.1, -0.3)
    )
    v = model.y_from_q(rigid_velocity(model, motion))
    deform = np.random.default_rng(9).normal(size=model.n) * np.abs(v).max()
    scale = np.abs(damping_force(model, model.y0, deform)).max()
    assert scale > 0.0
    assert np.abs(damping_force(model, model.y0, v)).max() <= 1e-10 * scale


def test_rod_velocity_jacobian_at_the_reference_is_the_scaled_elastic_tangent():
    # c_a / EA = c_t / GJ = c_b / EI = beta on a section with equal bending stiffnesses
    sec = Section(3.0e-4, 2.0e-8, 2.0e-8, 2.5e-8, (0.0, 0.0, 1.0))
    beta, e_mod = 2.0e-3, ROD_MAT.youngs_modulus
    kv = StrainRateDamping(
        beta * e_mod * sec.area, beta * e_mod * sec.inertia, beta * ROD_MAT.shear * sec.torsion
    )
    model = Model(mesh_of("conic"), "rod", sec, ROD_MAT, strain_rate_damping=kv)
    _, kt = model.internal_force_and_tangent(model.y0)
    _, ab = damping_force(model, model.y0, np.zeros(model.n), ck=0.0, cv=1.0)
    expect = beta * model.dense(kt)
    assert np.abs(model.dense(ab) - expect).max() <= 1e-9 * np.abs(expect).max()


# ---- the co-rotational beam: axial strain and the rotations relative to the chord (beam.cpp)

BEAM_KV = StrainRateDamping(30.0, 0.4)


def _beam(kv: StrainRateDamping = BEAM_KV) -> Model:
    mat = Material(density=7850.0, youngs_modulus=E_MOD)
    return Model(mesh_conic(conic_arc(*EXAMPLE1), 4), "beam", SEC, mat, strain_rate_damping=kv)


def test_beam_jacobians_against_central_differences_and_rigid_motion():
    model = _beam()
    rng = np.random.default_rng(12)
    y, v = model.y0 + 0.02 * rng.normal(size=model.n), rng.normal(size=model.n)
    _, ab_y = damping_force(model, y, v, ck=1.0, cv=0.0)
    _, ab_v = damping_force(model, y, v, ck=0.0, cv=1.0)
    jy, jv = model.dense(ab_y), model.dense(ab_v)
    eye, hy, hv = np.eye(model.n), 1e-6, 1e-3
    fd_y = np.array(
        [damping_force(model, y + hy * d, v) - damping_force(model, y - hy * d, v) for d in eye]
    ).T / (2 * hy)
    fd_v = np.array(
        [damping_force(model, y, v + hv * d) - damping_force(model, y, v - hv * d) for d in eye]
    ).T / (2 * hv)
    assert np.abs(fd_y - jy).max() <= 1e-6 * np.abs(jy).max()
    assert np.abs(fd_v - jv).max() <= 1e-9 * np.abs(jv).max()
    motion = RigidMotion(velocity=(0.4, -0.3), angular_velocity=1.7, about=(0.1, 0.2))
    vr = model.y_from_q(rigid_velocity(model, motion))
    scale = np.abs(damping_force(model, model.y0, rng.normal(size=model.n) * np.abs(vr).max()))
    assert np.abs(damping_force(model, model.y0, vr)).max() <= 1e-10 * scale.max()


def _check_differences(model, y, v, jy, jv, hy: float, hv: float = 1e-3) -> None:
    """The position and velocity Jacobians ``jy``, ``jv`` of the damping force against central
    differences (steps ``hy``, ``hv``): within 1e-6 and 1e-9 of their largest entry."""
    fd_y, fd_v = np.zeros_like(jy), np.zeros_like(jv)
    for i in range(model.n):
        d = np.zeros(model.n)
        d[i] = 1.0
        fd_y[:, i] = (damping_force(model, y + hy * d, v) - damping_force(model, y - hy * d, v)) / (
            2 * hy
        )
        fd_v[:, i] = (damping_force(model, y, v + hv * d) - damping_force(model, y, v - hv * d)) / (
            2 * hv
        )
    err_y = np.abs(fd_y - jy).max() / np.abs(jy).max()
    err_v = np.abs(fd_v - jv).max() / np.abs(jv).max()
    assert err_y <= 1e-6, err_y
    assert err_v <= 1e-9, err_v
