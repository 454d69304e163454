"""A body given another unstretched length (rancf.bodies.length; docs/derivations/
variable-length.md §2.1): its mass is ρ A L, the element force and tangent against central
differences at a scaled length, a rigid motion of the scaled unloaded state carries no force,
and statics and modes of a load hanging from a steel cable at any length."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.length import reference_length, set_unstretched_length, unstretched_length
from rancf.bodies.reactions import support_reactions
from rancf.bodies.rigid import PointMass
from rancf.errors import InputError
from rancf.mesh.factories import mesh_line
from rancf.solvers.modal import natural_modes
from rancf.solvers.static import solve_static
from rancf.system import Joint, System
from tests.bodies.test_stress_free import _arc_mesh, _moved, _rotation

G, LOAD = 9.81, 10.0
STEEL, WIRE = Material(7850.0, 2.0e11, poisson_ratio=0.3), Section.circular(0.005)
RHO_A, EA = 7850.0 * WIRE.area, 2.0e11 * WIRE.area


@pytest.mark.parametrize(("element", "dim"), [("rancf", 2), ("rancf", 3), ("rod", 3)])
def test_mass_is_rho_a_l_and_forces_match_central_differences(element, dim):
    m = Model(
        _arc_mesh(3, dim),
        element,
        Section.circular(0.01),
        Material(1000.0, 1e7, poisson_ratio=0.3),
        stress_free="straight",
    )
    l_ref = reference_length(m)
    for length in (0.3 * l_ref, 2.7 * l_ref):
        set_unstretched_length(m, length)
        assert unstretched_length(m) == pytest.approx(length, rel=1e-14)
        assert m.total_mass == pytest.approx(m.props.rho_a * length, rel=1e-12)
    rng = np.random.default_rng(3)
    y = m.y0 + 1e-3 * rng.standard_normal(m.n)
    f, ab = m.internal_force_and_tangent(y)
    h = 1e-6
    f_fd = np.array(
        [(m.strain_energy(y + h * e) - m.strain_energy(y - h * e)) / (2 * h) for e in np.eye(m.n)]
    )
    assert np.max(np.abs(f - f_fd)) < 1e-6 * np.max(np.abs(f))
    k = m.dense(ab)
    k_fd = np.column_stack(
        [(m.internal_force(y + h * e) - m.internal_force(y - h * e)) / (2 * h) for e in np.eye(m.n)]
    )
    assert np.max(np.abs(k - k_fd)) < 1e-6 * np.max(np.abs(k))


@pytest.mark.parametrize(("element", "dim"), [("rancf", 2), ("ancf", 3), ("rod", 3)])
def test_scaled_unloaded_state_moved_rigidly_carries_no_force(element, dim):
    """A curved reference given 2.5 times its length about its first node is unloaded in its
    scaled shape, anywhere (reference stress-free), and so is a straight rope (straight)."""
    sec, mat = Section.circular(0.01), Material(1000.0, 1e7, poisson_ratio=0.3)
    for mesh, sf in (
        (_arc_mesh(3, dim), "reference"),
        (mesh_line(np.zeros(dim), np.r_[1.0, 0.4, 0.3][:dim], 4), "straight"),
    ):
        m = Model(mesh, element, sec, mat, stress_free=sf)
        set_unstretched_length(m, 2.5 * reference_length(m), anchor=0)
        assert np.max(np.abs(m.internal_force(m.y0))) < 1e-9 * m.props.ea
        y = _moved(m, m.y0, _rotation(dim), np.full(dim, 0.3))
        if element == "rod":
            m.kernel.tref[...] = m.kernel.tref @ _rotation(dim).T
            m.kernel.m1ref[...] = m.kernel.m1ref @ _rotation(dim).T
        assert np.max(np.abs(m.internal_force(y))) < 1e-9 * m.props.ea


def hoist(length: float, n_el: int = 10) -> System:
    """A 10 kg load on a steel wire (radius 5 mm) hanging from a pin at the origin, the wire
    meshed 5 m long and given ``length``."""
    wire = Model(
        mesh_line([0.0, 0.0], [0.0, -5.0], n_el),
        "ancf",
        WIRE,
        STEEL,
        [Support(0, "pin")],
        gravity=[0.0, -G],
    )
    set_unstretched_length(wire, length, anchor=0)
    end = wire.q0[-4:-2]
    load = PointMass(2, LOAD, tuple(end))
    return System(
        {"wire": wire, "load": load}, [Joint("pin", ("wire:end", "load"))], gravity=[0.0, -G]
    )


def static_stretch(length: float) -> float:
    """The wire's elongation under its weight and the load: at the unstretched distance ``s``
    from the load the tension is ``T = (m + ρ A s) g`` and the stretch ``λ`` solves
    ``EA λ (λ² - 1) / 2 = T`` (Green–Lagrange strain); elongation ``∫ (λ - 1) ds``."""
    s, w = np.polynomial.legendre.leggauss(40)
    s = 0.5 * length * (s + 1)
    lam = [
        brentq(lambda x, t=t: EA * x * (x * x - 1) / 2 - t, 1.0, 1.1)
        for t in (LOAD + RHO_A * s) * G
    ]
    return float(0.5 * length * np.sum(w * (np.array(lam) - 1.0)))


@pytest.mark.parametrize("length", [5.0, 10.0, 15.0])
def test_static_tension_and_stretch_at_any_length(length):
    """Winch tension ``(m + ρ A L) g`` and the load at ``L`` plus the static stretch."""
    s = hoist(length)
    res = solve_static(s, load_steps=1)
    y = res.y
    wire = s.bodies["wire"]
    yw = y[s.body_slice("wire")]
    r = wire.internal_force(yw) - wire.external_force(0.0, yw)
    top = support_reactions(wire, yw, r)[0].force
    assert top[1] == pytest.approx((LOAD + RHO_A * length) * G, rel=1e-9)
    drop = -y[s.body_slice("load")][1]
    assert drop - length == pytest.approx(static_stretch(length), abs=1e-9)
    assert wire.total_mass == pytest.approx(RHO_A * length, rel=1e-12)


def test_axial_mode_at_any_length():
    """The load bouncing on the wire: ``β L tan(β L) = ρ A L / m`` with ``β = ω / c``,
    ``c = sqrt(E / ρ)`` (a rod fixed at one end with a mass at the other), within 0.01 %
    (measured: 1.1e-5 at 5 m, 1.4e-5 at 15 m)."""
    for length in (5.0, 15.0):
        s = hoist(length, n_el=20)
        res = solve_static(s, load_steps=1)
        modes = natural_modes(s, res.y, lam=res.lam)
        c, ratio = np.sqrt(2.0e11 / 7850.0), RHO_A * length / LOAD
        bl = brentq(lambda x, r=ratio: x * np.tan(x) - r, 1e-6, np.pi / 2 - 1e-9)
        f_exact = bl * c / length / (2 * np.pi)
        idx = s.body_slice("load")
        vertical = [abs(v[idx][1]) / (np.linalg.norm(v[idx]) + 1e-300) for v in modes.modes]
        axial = [f for f, v in zip(modes.frequencies_hz, vertical, strict=True) if v > 0.9]
        assert min(axial) == pytest.approx(f_exact, rel=1e-4)


def test_refuses_a_beam_and_a_bad_length():
    m = Model(mesh_line([0, 0], [1, 0], 2), "beam", WIRE, STEEL)
    with pytest.raises(InputError, match="cable or rod"):
        set_unstretched_length(m, 2.0)
    c = Model(mesh_line([0, 0], [1, 0], 2), "ancf", WIRE, STEEL)
    with pytest.raises(InputError, match="length"):
        set_unstretched_length(c, -1.0)
