"""Linear buckling: Euler columns and the lateral–torsional buckling of a strip."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support
from rancf.errors import ConvergenceError
from rancf.mesh.factories import mesh_line
from rancf.solvers.buckling import linear_buckling
from rancf.solvers.static import solve_static

SEC, MAT = Section.circular(0.01), Material(7850.0, 2e11)
EI = 2e11 * np.pi * 0.01**4 / 4.0


def column(supports: list[Support], n: int = 16, element: str = "rancf") -> Model:
    """A 1 m column along x, a unit compressive force at its end."""
    return Model(
        mesh_line([0.0, 0.0], [1.0, 0.0], n),
        element,
        SEC,
        MAT,
        supports,
        point_loads=[PointLoad(-1, (-1.0, 0.0))],
    )


@pytest.mark.parametrize(("element", "rtol"), [("rancf", 1e-3), ("ancf", 1e-3), ("beam", 5e-3)])
def test_pinned_pinned_euler_column(element, rtol):
    """π² EI / L² within 0.1 % at 16 cable elements (measured 2e-5); the end is a roller along
    the axis.  The co-rotational beam's geometric stiffness is that of its chord: 0.37 %."""
    m = column([Support(0), Support(-1, "roller", axis=(1.0, 0.0))], element=element)
    res = linear_buckling(m, count=2)
    assert res.load_factors[0] == pytest.approx(np.pi**2 * EI, rel=rtol)
    assert res.load_factors[1] == pytest.approx(4 * np.pi**2 * EI, rel=4 * rtol)  # second mode
    assert res.symmetric


def test_cantilever_column():
    m = column([Support(0, "clamp")])
    res = linear_buckling(m, count=1)
    assert res.load_factors[0] == pytest.approx(np.pi**2 * EI / 4.0, rel=1e-3)
    shape = m.node_positions(res.modes[0])
    assert np.abs(shape[:, 1]).argmax() == 16  # it sways most at the tip


def test_about_a_preloaded_state():
    """Pre-loaded with 0.25 of its own critical load, the cantilever buckles at the same total
    load: factor 1 + 3 for the loads as given (0.25 P_cr)."""
    m = column([Support(0, "clamp")])
    pcr = np.pi**2 * EI / 4.0
    m2 = Model(
        mesh_line([0.0, 0.0], [1.0, 0.0], 16),
        "rancf",
        SEC,
        MAT,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, (-0.25 * pcr, 0.0))],
    )
    res = linear_buckling(m2, 1, "static", solve_static(m2).y)
    assert res.load_factors[0] == pytest.approx(4.0, rel=2e-3)  # 4 x 0.25 P_cr
    del m


def test_a_mechanism_is_refused():
    with pytest.raises(ConvergenceError, match="mechanism"):
        linear_buckling(column([Support(0)]), 1)


def test_tension_never_buckles():
    m = Model(
        mesh_line([0.0, 0.0], [1.0, 0.0], 4),
        "rancf",
        SEC,
        MAT,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, (1.0, 0.0))],
    )
    with pytest.raises(ConvergenceError, match="never buckle"):
        linear_buckling(m, 1)


def test_lateral_torsional_buckling_of_a_strip():
    """Timoshenko & Gere: a 0.6 mm x 30 mm aluminium strip cantilever, L = 0.24 m, tip load at
    the centroid in its stiff plane: P_cr = 4.013 sqrt(E I_weak G J) / L² = 3.312 N (J = b t³/3)
    within 2 %.  The rod's width along z: m1 = z carries the weak bending, m2 the stiff one."""
    b, t, length, e_mod, nu = 0.03, 0.6e-3, 0.24, 71.24e9, 0.31
    i_weak, i_stiff, j = b * t**3 / 12.0, t * b**3 / 12.0, b * t**3 / 3.0
    sec = Section(b * t, i_weak, i_stiff, j, (0.0, 0.0, 1.0))
    mat = Material(2700.0, e_mod, poisson_ratio=nu)
    m = Model(
        mesh_line([0.0, 0.0, 0.0], [length, 0.0, 0.0], 16),
        "rod",
        sec,
        mat,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, (0.0, 0.0, -1.0))],
    )
    g = e_mod / (2.0 * (1.0 + nu))
    pcr = 4.013 * np.sqrt(e_mod * i_weak * g * j) / length**2
    assert pcr == pytest.approx(3.312, abs=1e-3)
    res = linear_buckling(m, 1)
    assert res.load_factors[0] == pytest.approx(pcr, rel=2e-2)
    tip = m.node_positions(res.modes[0])[-1]
    assert abs(tip[1]) > 10 * abs(tip[2])  # the mode is lateral (out of the load's plane)
