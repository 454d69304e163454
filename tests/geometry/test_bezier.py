from math import comb

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from rancf.errors import WeightError
from rancf.geometry.bezier import (
    RationalBezier,
    bernstein,
    degree_elevation_matrix,
    restriction_matrix,
)

T = np.linspace(0.0, 1.0, 101)


def random_curve(rng, degree, dim=2):
    return RationalBezier(rng.normal(size=(degree + 1, dim)), rng.uniform(0.3, 3.0, degree + 1))


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_bernstein_partition_of_unity_and_derivatives(n):
    b = bernstein(n, T)
    assert np.allclose(b.sum(axis=1), 1.0, atol=1e-15)
    # derivatives against numpy polynomial derivatives of the power form
    poly = np.polynomial.Polynomial
    for i in range(n + 1):
        coef = comb(n, i) * poly([0.0, 1.0]) ** i * poly([1.0, -1.0]) ** (n - i)
        assert np.allclose(coef(T), b[:, i], atol=1e-13)
        assert np.allclose(coef.deriv(1)(T), bernstein(n, T, 1)[:, i], atol=1e-12)
        assert np.allclose(coef.deriv(2)(T), bernstein(n, T, 2)[:, i], atol=1e-11)


def test_rational_derivatives_against_finite_differences(rng):
    c = random_curve(rng, 3, 3)
    h = 1e-6
    t = np.linspace(0.05, 0.95, 7)
    r, r1, r2 = c.derivatives(t)
    fd1 = (c(t + h) - c(t - h)) / (2 * h)
    fd2 = (c.derivatives(t + h, 1)[1] - c.derivatives(t - h, 1)[1]) / (2 * h)
    assert np.allclose(r1, fd1, rtol=1e-7, atol=1e-8)
    assert np.allclose(r2, fd2, rtol=1e-7, atol=1e-7)


@given(st.integers(1, 5), st.integers(0, 10_000))
def test_degree_elevation_keeps_the_curve(n, seed):
    c = random_curve(np.random.default_rng(seed), n)
    e = c.elevated()
    assert e.degree == n + 1
    assert np.abs(e(T) - c(T)).max() <= 1e-12 * np.abs(c.points).max()
    assert degree_elevation_matrix(n).sum(axis=1) == pytest.approx(np.ones(n + 2))


@given(st.integers(1, 4), st.floats(0.0, 0.9), st.floats(0.05, 1.0), st.integers(0, 10_000))
def test_restriction_is_exact(n, a, width, seed):
    b = min(a + width, 1.0)
    c = random_curve(np.random.default_rng(seed), n)
    s = c.restricted(a, b)
    ref = c(a + (b - a) * T)
    assert np.abs(s(T) - ref).max() <= 1e-12 * np.abs(c.points).max()
    assert restriction_matrix(n, 0.0, 1.0) == pytest.approx(np.eye(n + 1))


def test_split_and_moebius(rng):
    c = random_curve(rng, 3)
    left, right = c.split(0.3)
    assert np.allclose(left(T), c(0.3 * T), atol=1e-14)
    assert np.allclose(right(T), c(0.3 + 0.7 * T), atol=1e-14)
    rho = 1.7
    m = c.reparameterized(rho)
    assert np.allclose(m(T), c(rho * T / (1 - T + rho * T)), atol=1e-14)
    st_ = c.standardized()
    assert st_.weights[0] == pytest.approx(1.0) and st_.weights[-1] == pytest.approx(1.0)
    # same point set: the standardized curve is a reparameterization
    w = c.weights
    r = (w[0] / w[-1]) ** (1 / 3)
    assert np.allclose(st_(T), c(r * T / (1 - T + r * T)), atol=1e-14)


def test_bad_weights_raise():
    with pytest.raises(WeightError, match="weights"):
        RationalBezier(np.zeros((3, 2)), np.array([1.0, -0.5, 1.0]))
    with pytest.raises(ValueError):
        RationalBezier(np.zeros((3, 2)), np.array([1.0, 0.0, 1.0]))
