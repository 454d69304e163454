import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support
from rancf.geometry.conic import conic_arc, conic_arc_through
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.modal import natural_modes
from rancf.solvers.static import solve_static
from tests.conftest import EXAMPLE1, EXAMPLE3

L, R, RHO, E = 0.5, 0.03, 6000.0, 2.0e7
SEC = Section.circular(R)
MAT = Material(RHO, E)
F1 = 1.8751**2 / (2 * np.pi) * np.sqrt(E * SEC.inertia / (RHO * SEC.area * L**4))


def test_reference_frequency_value():
    assert F1 == pytest.approx(1.9385, abs=1e-4)


@pytest.mark.parametrize("dim", [2, 3])
def test_cantilever_first_frequency(dim):
    end = [L] + [0.0] * (dim - 1)
    m = Model(mesh_line([0.0] * dim, end, 8), "rancf", SEC, MAT, [Support(0, "clamp")])
    res = natural_modes(m, count=4)
    assert res.n_rigid == 0
    assert res.frequencies_hz[0] == pytest.approx(F1, rel=1e-3)
    assert np.all(np.diff(res.frequencies_hz) >= 0)
    if dim == 3:  # two equal bending directions
        assert res.frequencies_hz[1] == pytest.approx(res.frequencies_hz[0], rel=1e-9)


def test_cantilever_clamp_in_any_direction():
    d = np.array([np.cos(0.7), np.sin(0.7)])
    m = Model(
        mesh_line([0.1, 0.2], [0.1, 0.2] + L * d, 8), "rancf", SEC, MAT, [Support(0, "clamp")]
    )
    assert natural_modes(m, count=1).frequencies_hz[0] == pytest.approx(F1, rel=1e-3)


def test_beam_cantilever_converges():
    freqs = []
    for n in (4, 16):
        m = Model(mesh_line([0, 0], [L, 0], n), "beam", SEC, MAT, [Support(0, "clamp")])
        freqs.append(natural_modes(m, count=1).frequencies_hz[0])
    # rotary inertia (ρI) lowers the beam's frequency slightly below Euler–Bernoulli
    assert abs(freqs[1] / F1 - 1) < abs(freqs[0] / F1 - 1) < 0.02
    assert abs(freqs[1] / F1 - 1) < 5e-3


@pytest.mark.parametrize("element", ["rancf", "beam"])
def test_static_tip_deflection(element):
    force = 1e-3
    m = Model(
        mesh_line([0, 0], [L, 0], 8),
        element,
        SEC,
        MAT,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, (0.0, -force))],
    )
    res = solve_static(m, 5)
    tip = m.node_positions(res.q)[-1]
    expected = force * L**3 / (3 * E * SEC.inertia)
    assert -tip[1] == pytest.approx(expected, rel=5e-3)
    assert res.load_factors[-1] == 1.0


def test_large_static_deflection_elements_agree():
    ei = E * SEC.inertia
    tips = {}
    for el in ("rancf", "beam"):
        m = Model(
            mesh_line([0, 0], [L, 0], 32),
            el,
            SEC,
            MAT,
            [Support(0, "clamp")],
            point_loads=[PointLoad(-1, (0.0, -3 * ei / L**2))],
        )
        tips[el] = m.node_positions(solve_static(m, 20).q)[-1]
    # large deflection (about 60 % of L); the two curvature measures differ at the strain level
    assert -tips["rancf"][1] > 0.25
    assert np.abs(tips["rancf"] - tips["beam"]).max() < 5e-3 * L


def test_pendulum_has_one_rigid_mode_and_no_static_equilibrium_near_its_reference():
    """Modes about the reference remove the swing as a rigid mode; Newton cannot leave the
    reference (no stiffness against the swing there), so the static solve ends by relaxation
    (the hanging state: :mod:`tests.solvers.test_equilibrium`)."""
    m = Model(
        mesh_conic(conic_arc(*EXAMPLE1), 4),
        "rancf",
        Section.circular(0.02),
        Material(6000, 2e6),
        [Support(0, "pin")],
        gravity=[0, -9.81],
    )
    res = natural_modes(m, count=3)
    assert res.n_rigid == 1
    assert res.frequencies_hz[0] > 0.1
    res = solve_static(m, 2, max_iter=6)
    assert res.method == "relaxation+newton" and res.load_factors[-2] == 0.0


def test_curved_spatial_cable_has_zero_out_of_plane_stiffness():
    chord, ang, pt = EXAMPLE3
    arc3 = conic_arc_through([0, 0, 0], [chord, 0, 0], ang, [pt[0], pt[1], 0.0])
    m3 = Model(mesh_conic(arc3, 6), "rancf", SEC, MAT, [Support(0, "clamp")])
    res3 = natural_modes(m3)
    assert res3.n_rigid == 0  # a clamped arc has no rigid-body modes; zero modes are kept
    zero = res3.frequencies_hz < 1e-3
    assert zero.sum() >= 1
    # the zero modes move out of the plane of the arc only
    for shape in res3.modes[zero]:
        pos = m3.node_positions(shape)
        assert np.abs(pos[:, :2]).max() <= 1e-8 * np.abs(pos[:, 2]).max()
    # the in-plane frequencies equal those of the planar model
    m2 = Model(mesh_conic(conic_arc(*EXAMPLE3), 6), "rancf", SEC, MAT, [Support(0, "clamp")])
    f2 = natural_modes(m2, count=3).frequencies_hz
    assert np.allclose(res3.frequencies_hz[~zero][:3], f2, rtol=1e-8)
