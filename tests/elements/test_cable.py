import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from rancf.elements.cable import (
    ancf_shape_functions,
    ancf_to_bezier_matrix,
    bezier_from_nodal,
    bezier_to_ancf_matrix,
    cable_shape_functions,
    control_to_nodal_matrix,
    nodal_from_bezier,
    nodal_to_control_matrix,
)
from rancf.elements.mapping import conic_element
from rancf.geometry.bezier import RationalBezier, bernstein
from rancf.geometry.conic import conic_arc

XI = np.linspace(0.0, 1.0, 201)


@pytest.mark.parametrize("scale", [0.1, 1.0, 2.5])
def test_unit_weights_give_the_classical_ancf_cable(scale):
    n = cable_shape_functions(np.ones((1, 4)), [scale], XI)[0][0]
    assert np.abs(n - ancf_shape_functions(scale, XI)).max() < 1e-15


def test_nearly_straight_conic_gives_classical_ancf_shape_functions():
    chord, theta = 0.5, 1e-4  # degrees
    p1y = 0.25 * np.tan(np.radians(theta))
    mid = np.array([0.25, p1y / 2])  # parabola (ω = 1) apex: the interior point (P0 + 2 P1 + P2)/4
    el = conic_element(conic_arc(chord, [theta, theta], mid))
    assert el.k == pytest.approx(0.5, abs=1e-6)
    assert el.weights == pytest.approx(np.ones(4), abs=1e-12)
    n = cable_shape_functions(el.weights[None], [el.scale], XI)[0][0]
    assert np.abs(n - ancf_shape_functions(el.scale, XI)).max() < 1e-12
    assert el.scale == pytest.approx(chord, rel=1e-8)


def test_shape_functions_reproduce_the_curve_and_rigid_motion(rng):
    w = np.array([1.0, 0.8, 1.3, 1.0])
    curve = RationalBezier(rng.normal(size=(4, 3)), w)
    e = nodal_from_bezier(curve, 0.7)
    n, n1, n2 = cable_shape_functions(w[None], [0.7], XI)
    r, r1, r2 = curve.derivatives(XI)
    assert np.abs(n[0] @ e - r).max() < 1e-13
    assert np.abs(n1[0] @ e - r1).max() < 1e-12
    assert np.abs(n2[0] @ e - r2).max() < 1e-11
    # partition of unity on positions: a translation moves every point by the same vector
    assert np.allclose(n[0][:, 0] + n[0][:, 2], 1.0, atol=1e-15)


def test_shape_function_derivatives_against_finite_differences(rng):
    w = rng.uniform(0.5, 2.0, (3, 4))
    s = rng.uniform(0.2, 2.0, 3)
    x = np.linspace(0.05, 0.95, 9)
    h = 1e-6
    n, n1, n2 = cable_shape_functions(w, s, x)
    p = cable_shape_functions(w, s, x + h)
    m = cable_shape_functions(w, s, x - h)
    assert np.allclose(n1, (p[0] - m[0]) / (2 * h), rtol=1e-7, atol=1e-8)
    assert np.allclose(n2, (p[1] - m[1]) / (2 * h), rtol=1e-7, atol=1e-7)


@given(st.lists(st.floats(0.1, 10.0), min_size=4, max_size=4), st.floats(0.05, 20.0))
def test_nodal_control_transformations_are_exact_inverses(w, scale):
    t = control_to_nodal_matrix(w, scale)
    ti = nodal_to_control_matrix(w, scale)
    assert np.abs(t @ ti - np.eye(4)).max() < 1e-12 * max(1.0, np.abs(t).max())
    assert np.abs(ti @ t - np.eye(4)).max() < 1e-12 * max(1.0, np.abs(ti).max())


@given(st.floats(0.05, 20.0), st.integers(0, 1000))
def test_ancf_bezier_eq9_pair(scale, seed):
    # Sanborn & Shabana eq. 9: e = T P; the ANCF element with nodal e is the Bézier curve of P
    p = np.random.default_rng(seed).normal(size=(4, 2))
    e = bezier_to_ancf_matrix(scale) @ p
    assert np.abs(ancf_to_bezier_matrix(scale) @ e - p).max() < 1e-12 * max(1, np.abs(p).max())
    a = ancf_shape_functions(scale, XI) @ e
    b = bernstein(3, XI) @ p
    assert np.abs(a - b).max() < 1e-12 * max(1, np.abs(p).max())
    assert np.allclose(e[1], 3 * (p[1] - p[0]) / scale) and np.allclose(
        e[3], 3 * (p[3] - p[2]) / scale
    )


def test_bezier_round_trip(rng):
    curve = RationalBezier(rng.normal(size=(4, 2)), np.array([1.0, 2.0, 0.5, 1.5]))
    back = bezier_from_nodal(nodal_from_bezier(curve, 0.3), curve.weights, 0.3)
    assert np.allclose(back.points, curve.points, atol=1e-14)
