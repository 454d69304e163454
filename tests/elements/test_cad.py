import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.interpolate import BSpline

from rancf.elements.cad import (
    bspline_to_ancf,
    bspline_to_ancf_matrix,
    chain_to_nurbs,
    nurbs_to_rancf,
)
from rancf.errors import InputError, KnotVectorError, WeightError
from rancf.geometry.nurbs import NurbsCurve
from rancf.mesh.nurbs_mesh import mesh_nurbs


@st.composite
def knot_vectors(draw, degree=3, allow_c0=True):
    """Random (possibly unclamped) knot vectors with repeated interior knots."""
    n_distinct = draw(st.integers(2, 6))
    gaps = draw(st.lists(st.floats(0.1, 3.0), min_size=n_distinct - 1, max_size=n_distinct - 1))
    breaks = np.concatenate([[draw(st.floats(-2.0, 2.0))], np.cumsum(gaps)])
    breaks[1:] += breaks[0]
    top = degree if allow_c0 else degree - 1
    mult = [draw(st.integers(1, top)) for _ in range(n_distinct - 2)]
    clamped = draw(st.booleans())
    inner = np.concatenate([np.repeat(breaks[1:-1], mult)]) if mult else np.empty(0)
    if clamped:
        start = [breaks[0]] * (degree + 1)
        end = [breaks[-1]] * (degree + 1)
    else:
        step = draw(st.floats(0.2, 1.0))
        start = list(breaks[0] - step * np.arange(degree, 0, -1)) + [breaks[0]]
        end = [breaks[-1]] + list(breaks[-1] + step * np.arange(1, degree + 1))
    return np.concatenate([start, inner, end])


def _reference(knots, pts, w, degree, u):
    num = BSpline(knots, pts * w[:, None], degree)(u)
    den = BSpline(knots, w, degree)(u)
    return num / den[:, None]


@given(knot_vectors(), st.integers(2, 3), st.integers(0, 10_000))
def test_bspline_to_ancf_chain_reproduces_the_curve(knots, dim, seed):
    rng = np.random.default_rng(seed)
    n_ctrl = knots.size - 4
    pts = rng.normal(size=(n_ctrl, dim))
    curve = NurbsCurve.bspline(3, knots, pts)
    chain = bspline_to_ancf(curve)
    a, b = curve.domain
    u = np.linspace(a, b, 1000)
    ref = BSpline(knots, pts, 3)(u)  # SciPy: independent evaluation
    scale = np.abs(pts).max()
    assert np.abs(chain(u) - ref).max() <= 1e-12 * scale
    assert chain.n_elements == np.unique(knots[3 : n_ctrl + 1]).size - 1
    # the conversion is the linear map of eq. 27
    mat, scales, breaks = bspline_to_ancf_matrix(knots, n_ctrl)
    assert np.allclose(mat @ pts, chain.nodal.reshape(-1, dim), atol=1e-13 * scale)
    assert np.allclose(scales, np.diff(breaks))


@given(knot_vectors(degree=3), st.integers(0, 10_000))
def test_nurbs_rancf_nurbs_round_trip(knots, seed):
    rng = np.random.default_rng(seed)
    n_ctrl = knots.size - 4
    pts = rng.normal(size=(n_ctrl, 3))
    w = rng.uniform(0.2, 5.0, n_ctrl)
    curve = NurbsCurve(3, knots, pts, w)
    chain = nurbs_to_rancf(curve)
    back = chain_to_nurbs(chain)
    a, b = curve.domain
    u = np.linspace(a, b, 1000)
    ref = _reference(knots, pts, w, 3, u)
    scale = np.abs(pts).max()
    assert np.abs(chain(u) - ref).max() <= 1e-12 * scale
    assert np.abs(back(u) - ref).max() <= 1e-12 * scale
    # and with SciPy on the returned NURBS
    assert (
        np.abs(_reference(back.knots, back.points, back.weights, 3, u) - ref).max() <= 1e-12 * scale
    )


@given(knot_vectors(degree=2), st.integers(0, 10_000))
def test_quadratic_nurbs_to_rancf_and_back(knots, seed):
    rng = np.random.default_rng(seed)
    n_ctrl = knots.size - 3
    pts = rng.normal(size=(n_ctrl, 2))
    w = rng.uniform(0.2, 5.0, n_ctrl)
    curve = NurbsCurve(2, knots, pts, w)
    chain = nurbs_to_rancf(curve)
    a, b = curve.domain
    u = np.linspace(a, b, 1000)
    ref = _reference(knots, pts, w, 2, u)
    scale = np.abs(pts).max()
    assert np.abs(chain(u) - ref).max() <= 1e-12 * scale
    assert np.abs(chain_to_nurbs(chain)(u) - ref).max() <= 1e-12 * scale


def test_c1_break_points_give_consistent_shared_gradients():
    # S&S Fig. 5 knot vector; the break point u = 1 is C², u = 2 is C¹, u = 3 is C⁰
    knots = np.array([0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 5, 5, 5, 5], float)
    pts = np.random.default_rng(1).normal(size=(10, 2))
    chain = bspline_to_ancf(NurbsCurve.bspline(3, knots, pts))
    e = chain.nodal
    assert np.allclose(e[0, 2:], e[1, :2], atol=1e-14)  # u = 1
    assert np.allclose(e[1, 2:], e[2, :2], atol=1e-14)  # u = 2 (C¹)
    assert np.allclose(e[2, 2], e[3, 0], atol=1e-14)  # u = 3: positions only
    assert not np.allclose(e[2, 3], e[3, 1], atol=1e-6)


def test_quarter_circle_nurbs_becomes_an_exact_mesh():
    s = np.sqrt(0.5)
    circle = NurbsCurve(
        2,
        [0, 0, 0, 1, 1, 2, 2, 2],
        [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0]],
        [1, s, 1, s, 1],
    )
    mesh = mesh_nurbs(circle, 3)
    pts = mesh.evaluate(np.linspace(0, 1, 101)).reshape(-1, 2)
    assert np.abs(np.linalg.norm(pts, axis=1) - 1).max() < 1e-14
    assert mesh.arc_lengths().sum() == pytest.approx(np.pi, rel=1e-12)


@pytest.mark.parametrize(
    ("knots", "n_ctrl", "needle"),
    [
        ([0, 0, 0, 0, 2, 1, 3, 3, 3, 3], 6, "non-decreasing"),
        ([0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2], 8, "multiplicity"),
        ([0, 0, 0, 0, 1, 1, 1], 4, "8 knots"),
        ([1, 1, 1, 1, 1, 1, 1, 1], 4, "non-empty domain"),
    ],
)
def test_bad_knot_vectors(knots, n_ctrl, needle):
    with pytest.raises(KnotVectorError, match=needle) as info:
        NurbsCurve.bspline(3, knots, np.zeros((n_ctrl, 2)))
    assert isinstance(info.value, ValueError)


def test_decreasing_knots_message_names_the_place():
    with pytest.raises(KnotVectorError, match="non-decreasing"):
        NurbsCurve.bspline(3, [0, 0, 0, 0, 2, 1, 3, 3, 3, 3], np.zeros((6, 2)))


@pytest.mark.parametrize("w", [[1, 0, 1, 1], [1, -2, 1, 1], [1, np.nan, 1, 1]])
def test_bad_weights(w):
    with pytest.raises(WeightError, match="weights"):
        NurbsCurve(3, [0, 0, 0, 0, 1, 1, 1, 1], np.zeros((4, 2)), w)


def test_wrong_degree_and_rational_bspline():
    knots = [0, 0, 0, 0, 1, 1, 1, 1]
    with pytest.raises(WeightError):
        bspline_to_ancf(NurbsCurve(3, knots, np.eye(4, 2), [1, 2, 1, 1]))
    with pytest.raises(InputError, match="degree"):
        nurbs_to_rancf(NurbsCurve.bspline(1, [0, 0, 1, 1], np.eye(2)))
