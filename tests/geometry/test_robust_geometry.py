"""Geometry defects: extreme conics, sharp arc-length integrands, O(n) meshing."""

import numpy as np
import pytest

from rancf.elements.mapping import gradient_ratio, kopt
from rancf.errors import InputError
from rancf.geometry.conic import conic_arc
from rancf.geometry.nurbs import NurbsCurve
from rancf.geometry.quadrature import integrate
from rancf.mesh.factories import mesh_conic
from rancf.mesh.mesh import mesh_from_arrays
from rancf.mesh.nurbs_mesh import mesh_nurbs
from tests.conftest import EXAMPLE1

EXTREME = (1.0, (1.5, 87.5), (0.97, 0.01))


def _dense_ratio(curve, n=2_000_001):
    s = np.linalg.norm(curve.derivatives(np.linspace(0, 1, n), 1)[1], axis=1)
    return s.max() / s.min()


@pytest.mark.parametrize("k", [0.004144, 0.00414, 0.01, 0.3])
def test_gradient_ratio_finds_every_extremum_of_an_extreme_conic(k):
    curve = conic_arc(*EXTREME).cubic(k)
    # the dense sample can only under-state the ratio; the exact one is never below it
    dense = _dense_ratio(curve)
    assert dense <= gradient_ratio(curve) * (1 + 1e-12)
    assert gradient_ratio(curve) == pytest.approx(dense, rel=1e-6)


def test_kopt_of_an_extreme_conic():
    c = conic_arc(*EXTREME)
    k = kopt(c)
    assert k == pytest.approx(0.00414, abs=2e-5)
    assert gradient_ratio(c.cubic(k)) == pytest.approx(3.7658, abs=1e-4)
    # no other K on a fine scan does better
    scan = np.exp(np.linspace(np.log(1e-4), np.log(0.9999), 400))
    assert gradient_ratio(c.cubic(k)) <= min(gradient_ratio(c.cubic(x)) for x in scan) + 1e-9


def test_quadrature_resolves_a_sharp_peak():
    eps = 1e-10
    exact = 2 / np.sqrt(eps) * np.arctan(1 / np.sqrt(eps))
    assert integrate(lambda x: 1 / (eps + x**2), -1, 1, rtol=1e-13) == pytest.approx(
        exact, rel=1e-12
    )


@pytest.mark.parametrize("w", [1e4, 1e6])
def test_nurbs_with_widely_varying_weights_meshes(w):
    curve = NurbsCurve(
        2,
        np.array([0, 0, 0, 1, 1, 1.0]),
        np.array([[0, 0], [0.5, 0.5], [1, 0.0]]),
        np.array([1, w, 1.0]),
    )
    mesh = mesh_nurbs(curve, 3)
    # the curve hugs its control polygon (length sqrt 2) ever closer as w grows
    assert np.sqrt(2) * (1 - 10 / np.sqrt(w)) < mesh.scales.sum() < np.sqrt(2)
    assert mesh.arc_lengths().sum() == pytest.approx(mesh.scales.sum(), rel=1e-12)


def test_degenerate_curve_is_a_geometry_error():
    pts = np.array([[[0, 0], [0, 0], [0, 0], [1, 0.0]]])
    with pytest.raises(InputError, match="vanishing derivative"):
        mesh_from_arrays(pts, np.ones((1, 4)))


def test_100k_elements_mesh_is_still_exact():
    """How long it takes is measured by benchmarks/mesh_size.py (speed is not timed here)."""
    c = conic_arc(*EXAMPLE1)
    m = mesh_conic(c, 100_000)
    assert m.n_elements == 100_000
    lengths = m.arc_lengths()
    assert np.ptp(lengths) / lengths.mean() < 1e-8  # equal arc length
    pts = m.evaluate(np.linspace(0, 1, 5)).reshape(-1, 2)
    assert np.abs(c.implicit_residual(pts)).max() < 1e-12  # still the exact conic
    assert np.all((m.k > 0.45) & (m.k < 0.55))  # Kopt of a tiny sub-arc is about 1/2
