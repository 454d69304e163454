"""The nonlinear axial law of cables and rods (``material.axial_law``, a tension-strain table in
the engineering strain; docs/derivations/axial-law.md): forces against finite differences of the
energy, tangents against finite differences of the forces, objectivity, a linear table against
``EA``, the interpolant's shape and the refusal of bad tables."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.axial_law import AxialLaw, pchip_coefficients
from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.section_outputs import SectionSampler
from rancf.errors import InputError
from rancf.mesh.factories import mesh_line
from tests.kernels.test_elements import _fd_check, _mesh, _rotation
from tests.kernels.test_rod import deformed, fd_gradient, mesh_of, rigid, rotation

SEC = Section(area=1.0, inertia=2.0e-3)
#: A stiffening rope-like curve [strain, N]: slope 1000 N at 0, ten times that at 2 %.
ROWS = [[0.0, 0.0], [0.004, 4.5], [0.01, 14.0], [0.02, 45.0], [0.03, 140.0]]
LAW = AxialLaw(ROWS)
MAT = Material(density=3.0, youngs_modulus=1.0e3, axial_law=LAW)
ROD_SEC = Section(3.0e-4, 1.2e-8, 2.0e-8, 2.5e-8, (0.0, 0.0, 1.0))
ROD_MAT = Material(
    6000.0, 2.0e6, poisson_ratio=0.3, axial_law=AxialLaw([[0, 0], [0.01, 8.0], [0.05, 90.0]])
)
SCALE = 140.0  # the largest tension of the table [N]

CABLES = [(2, "line", None), (2, "conic", 0.2), (3, "line", None), (3, "conic", "opt")]


def _strains(model: Model, y: np.ndarray) -> np.ndarray:
    """Engineering strains at the section points."""
    return np.sqrt(1.0 + 2.0 * SectionSampler(model, 8).values(y)[:, 0]) - 1.0


@pytest.mark.parametrize(("dim", "geo", "k"), CABLES)
def test_cable_forces_and_tangent_against_finite_differences(dim, geo, k):
    model = Model(_mesh(dim, geo, k), "rancf", SEC, MAT)
    y = model.y0 + 0.03 * np.random.default_rng(5).normal(size=model.n)
    e = _strains(model, y)
    assert e.min() < 0.0 and e.max() > LAW.max_strain  # compression, table and beyond it
    _fd_check(model, y)


@pytest.mark.parametrize("geo", ["conic Kopt", "straight"])
def test_rod_forces_and_tangent_against_finite_differences(geo):
    m = Model(mesh_of(geo), "rod", ROD_SEC, ROD_MAT)
    y = rigid(m, deformed(m, np.random.default_rng(4)), rotation([1.0, 2.0, 0.5], 0.7), [1, 2, 3])
    f, kb = m.internal_force_and_tangent(y)
    k = m.dense(kb)
    assert np.abs(fd_gradient(m.strain_energy, y, 1e-6) - f).max() <= 1e-6 * np.abs(f).max()
    k_fd = fd_gradient(m.internal_force, y, 1e-6).T
    assert np.abs(k_fd - k).max() <= 1e-6 * np.abs(k).max()
    assert np.abs(k - k.T).max() <= 1e-12 * np.abs(k).max()


@pytest.mark.parametrize(("dim", "geo", "k"), CABLES)
def test_cable_rigid_motions_are_stress_free(dim, geo, k):
    model = Model(_mesh(dim, geo, k), "rancf", SEC, MAT)
    assert np.abs(model.internal_force(model.y0)).max() <= 1e-10 * SCALE
    nodes = model.y0.reshape(model.n_nodes, 2, dim) @ _rotation(dim, 2.1).T
    nodes[:, 0] += np.arange(1, dim + 1) * 0.7
    assert np.abs(model.internal_force(nodes.ravel())).max() <= 1e-10 * SCALE


def test_rod_rigid_motions_are_stress_free():
    m = Model(mesh_of("conic Kopt", 4), "rod", ROD_SEC, ROD_MAT)
    y = rigid(m, m.y0.copy(), rotation([0.3, -1.0, 2.0], 2.4), [0.5, -1.0, 2.0])
    assert np.abs(m.internal_force(y)).max() <= 1e-10 * 90.0
    assert abs(m.strain_energy(y)) <= 1e-20 * 90.0


@pytest.mark.parametrize("dim", [2, 3])
def test_a_linear_table_is_the_engineering_ea_to_round_off(dim):
    """``[[0, 0], [0.1, 0.1 EA]]`` gives the forces, tangent and energy of ``EA`` with the
    engineering strain at a random finite deformation."""
    mesh = _mesh(dim, "conic", 0.2)
    lin = Material(3.0, 1.0e3, axial_law=AxialLaw([[0.0, 0.0], [0.1, 100.0]]))
    a = Model(mesh, "rancf", SEC, lin)
    b = Model(mesh, "rancf", SEC, Material(3.0, 1.0e3, axial_strain="engineering"))
    y = a.y0 + 0.03 * np.random.default_rng(2).normal(size=a.n)
    (fa, ka), (fb, kb) = a.internal_force_and_tangent(y), b.internal_force_and_tangent(y)
    assert np.abs(fa - fb).max() <= 1e-13 * np.abs(fb).max()
    assert np.abs(ka - kb).max() <= 1e-13 * np.abs(kb).max()
    assert a.strain_energy(y) == pytest.approx(b.strain_energy(y), rel=1e-13)


@pytest.mark.parametrize("element", ["rancf", "rod"])
def test_a_uniform_stretch_carries_the_tables_tension(element):
    """A straight bar stretched uniformly to the strain e of a row carries that row's tension
    at every section and at its ends; its energy is the table's integral times the length."""
    dim, length = 3, 0.8
    mat = Material(3.0, 1.0e3, poisson_ratio=0.3 if element == "rod" else None, axial_law=LAW)
    sec = Section(1.0, 2.0e-3, orientation=(0.0, 0.0, 1.0) if element == "rod" else None)
    model = Model(mesh_line([0.0] * dim, [length, 0.0, 0.0], 4), element, sec, mat)
    for e, tension in ROWS[1:]:
        q = model.q0.reshape(model.n_nodes, -1).copy()
        q[:, [0, 3]] *= 1.0 + e  # positions and gradients stretched along x
        y = model.y_from_q(q.ravel())
        vals = SectionSampler(model, 4).values(y)
        assert np.abs(vals[:, 1] - tension).max() <= 1e-11 * tension
        f = model.q_from_y(model.internal_force(y)) if element == "rancf" else None
        if f is not None:
            assert f.reshape(model.n_nodes, -1)[-1, 0] == pytest.approx(tension, rel=1e-11)
        w = float(LAW.evaluate(e)[2])
        assert model.strain_energy(y) == pytest.approx(w * length, rel=1e-11)


def test_the_interpolant_passes_the_rows_and_rises_everywhere():
    e = np.linspace(-0.01, 0.05, 6001)
    t, dt, w = LAW.evaluate(e)
    rows = np.array(ROWS)
    assert np.abs(LAW.tension(rows[:, 0]) - rows[:, 1]).max() <= 1e-12 * SCALE
    assert dt.min() > 0.0  # monotone: a positive tangent everywhere
    assert np.all(np.diff(t) > 0.0)
    # C1: the slope has no jump at the rows (one-sided slopes agree)
    h = 1e-9
    for x in rows[1:-1, 0]:
        assert float(LAW.tangent(x - h)) == pytest.approx(float(LAW.tangent(x + h)), rel=1e-6)
    # the energy is the integral of the tension (trapezoids on a fine grid)
    trap = np.concatenate([[0.0], np.cumsum(0.5 * (t[1:] + t[:-1]) * np.diff(e))])
    zero = np.searchsorted(e, 0.0)
    assert np.abs((trap - trap[zero]) - w).max() <= 1e-6 * SCALE * 0.05
    # compression: the slope at 0; beyond the table: the last slope
    assert float(LAW.tension(-0.01)) == pytest.approx(-0.01 * LAW.ea0, rel=1e-12)
    last = float(LAW.tangent(0.03))
    assert float(LAW.tension(0.05)) == pytest.approx(140.0 + 0.02 * last, rel=1e-12)


def test_monotone_slopes_lie_in_fritsch_and_carlsons_region():
    """Every piece's end slopes over its secant are in (0, 3]: the cubic does not overshoot."""
    rng = np.random.default_rng(9)
    for _ in range(50):
        x = np.r_[0.0, np.cumsum(rng.uniform(0.001, 0.02, 8))]
        y = np.r_[0.0, np.cumsum(rng.uniform(1.0, 1000.0, 8) ** rng.uniform(0.5, 2.0))]
        c = pchip_coefficients(x, y)
        delta = np.diff(y) / np.diff(x)
        d_start = c[:, 1]
        h = np.diff(x)
        d_end = c[:, 1] + 2 * c[:, 2] * h + 3 * c[:, 3] * h**2
        for d in (d_start / delta, d_end / delta):
            assert d.min() > 0.0 and d.max() <= 3.0 + 1e-12


@pytest.mark.parametrize(
    ("rows", "match"),
    [
        ([[0.0, 0.0]], "2 or more"),
        ([[0.0, 1.0], [0.01, 2.0]], "first row"),
        ([[0.0, 0.0], [0.01, 2.0], [0.01, 3.0]], r"table\[2\].*strain above"),
        ([[0.0, 0.0], [0.01, 2.0], [0.02, 1.0]], r"table\[2\].*tension above"),
        ([[0.0, 0.0], [0.01, np.nan]], "finite"),
        ([[0.0, 0.0, 1.0], [0.01, 2.0, 3.0]], "rows"),
    ],
)
def test_bad_tables_are_refused_in_one_line(rows, match):
    with pytest.raises(InputError, match=match) as info:
        AxialLaw(rows)
    assert info.value.parameter.startswith("material.axial_law.table")


def test_a_beam_refuses_the_law():
    with pytest.raises(InputError, match="material.axial_law.*cable and rod"):
        Model(mesh_line([0.0, 0.0], [1.0, 0.0], 2), "beam", SEC, MAT)


def test_strain_rate_damping_damps_the_laws_engineering_strain():
    """A bar stretching uniformly at the rate dλ/dt with ``[damping] axial = c`` is pulled back
    by ``c dλ/dt`` at its end: the rate of the engineering strain the table is written in (the
    Green–Lagrange rate would be ``λ dλ/dt``)."""
    from rancf.bodies.properties import StrainRateDamping
    from rancf.bodies.strain_rate import damping_force

    c, lam, rate = 7.0, 1.25, 0.3
    model = Model(
        mesh_line([0.0, 0.0], [0.8, 0.0], 4),
        "rancf",
        SEC,
        MAT,
        strain_rate_damping=StrainRateDamping(axial=c),
    )
    q = model.q0.reshape(model.n_nodes, 2, 2)
    y = (q * [[[lam, 1.0]]]).ravel()  # positions and gradients stretched along x
    v = (q * [[[rate, 0.0]]]).ravel()
    f = np.asarray(damping_force(model, y, v)).reshape(model.n_nodes, 2, 2)
    assert f[-1, 0, 0] == pytest.approx(c * rate, rel=1e-12)
    assert f[0, 0, 0] == pytest.approx(-c * rate, rel=1e-12)
