import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import quad

from rancf.errors import AngleError, ChordError, InteriorPointError, MappingFactorError
from rancf.geometry.conic import Conic, circular_arc, conic_arc, conic_arc_through
from rancf.geometry.conic_params import cubic_parameter, quadratic_parameter
from tests.conftest import EXAMPLE1, EXAMPLE3

U = np.linspace(0.0, 1.0, 1000)


def test_example1_weight_type_and_arc_length(example1):
    assert example1.omega == pytest.approx(0.86501, abs=5e-6)
    assert example1.kind == "ellipse"
    assert not example1.is_circular()
    # arc length: our adaptive rule against SciPy's QUADPACK at its tightest setting
    ref, _ = quad(lambda u: example1.speed([u])[0], 0, 1, epsabs=0, epsrel=2e-14, limit=200)
    assert example1.arc_length() == pytest.approx(ref, rel=1e-12)
    assert example1.arc_length() == pytest.approx(0.53303, abs=5e-6)


def test_example3_is_nearly_circular():
    c = conic_arc(*EXAMPLE3)
    assert c.omega == pytest.approx(0.8663, abs=5e-5)
    assert c.circularity() < 1e-3  # the paper's rounded point: close to cos 30°, not exact
    assert not c.is_circular()


@pytest.mark.parametrize("theta", [5.0, 30.0, 60.0, 85.0])
def test_circular_arc_is_recognised_and_exact(theta):
    c = circular_arc(0.5, theta)
    assert c.is_circular()
    radius = 0.5 / (2 * np.sin(np.radians(theta)))
    assert c.radius() == pytest.approx(radius, rel=1e-14)
    centre = np.array([0.25, -radius * np.cos(np.radians(theta))])
    assert np.abs(np.linalg.norm(c(U) - centre, axis=1) / radius - 1).max() < 1e-14
    assert np.allclose(c.curvature(U), -1 / radius, rtol=1e-12)  # clockwise from P0 to P2
    assert c.arc_length() == pytest.approx(2 * radius * np.radians(theta), rel=1e-13)
    # the intuitive constructor with an interior point of that circle gives the same conic
    mid = c([0.37])[0]
    c2 = conic_arc(0.5, [theta, theta], mid)
    assert c2.omega == pytest.approx(np.cos(np.radians(theta)), rel=1e-12)
    assert c2.is_circular()


def test_classification():
    base = conic_arc(0.5, [30, 60], [0.219, 0.072])
    assert base.kind == "ellipse"
    p1 = base.p1
    par = Conic(base.p0, p1, base.p2, 1.0)
    assert par.kind == "parabola"
    assert Conic(base.p0, p1, base.p2, 1.5).kind == "hyperbola"
    # The paper's Fig. 10 configurations: its points are consistent with θ0 = 60°, θ1 = 30°
    # (as printed, θ0 = 30°, θ1 = 60°, the "parabola" point gives ω = 2.68 and the
    # "hyperbola" point lies outside the tangent triangle).
    assert conic_arc(0.5, [60, 30], [0.219, 0.072]).kind == "ellipse"
    assert conic_arc(0.5, [60, 30], [0.196, 0.108]).omega == pytest.approx(1.0, abs=0.003)
    assert conic_arc(0.5, [60, 30], [0.159, 0.144]).kind == "hyperbola"


def test_point_weight_is_independent_of_the_point(example1):
    # every point of the arc gives back the same ω (paper eq. 12)
    for u in (0.1, 0.5, 0.93):
        p = example1([u])[0]
        assert conic_arc(0.5, [30, 40], p).omega == pytest.approx(example1.omega, rel=1e-12)


def test_tangent_and_curvature_against_finite_differences(example1):
    u = np.linspace(0.1, 0.9, 5)
    h = 1e-5
    fd = (example1(u + h) - example1(u - h)) / (2 * h)
    t = example1.tangent(u)
    assert np.allclose(t, fd / np.linalg.norm(fd, axis=1, keepdims=True), atol=1e-9)
    # curvature = dθ/ds with θ the tangent angle
    ang = lambda x: np.unwrap(np.arctan2(*example1.tangent(x).T[::-1]))  # noqa: E731
    kfd = (ang(u + h) - ang(u - h)) / (2 * h) / example1.speed(u)
    assert np.allclose(example1.curvature(u), kfd, rtol=1e-7)
    # end tangents make the prescribed angles with the chord
    t0, t1 = example1.tangent([0.0, 1.0])
    assert np.degrees(np.arctan2(t0[1], t0[0])) == pytest.approx(30.0, abs=1e-12)
    assert np.degrees(np.arctan2(-t1[1], t1[0])) == pytest.approx(40.0, abs=1e-12)


def test_implicit_equation_holds_on_the_curve(example1):
    assert np.abs(example1.implicit_residual(example1(U))).max() < 1e-14
    off = example1(U[1:-1]) + np.array([0.0, 1e-3])
    assert np.abs(example1.implicit_residual(off)).min() > 1e-6


@given(st.floats(0.02, 0.98), st.floats(0.02, 0.98))
def test_every_k_gives_the_same_curve(k1, k2):
    c = conic_arc(*EXAMPLE1)
    a, b = c.cubic(k1), c.cubic(k2)
    xi = np.linspace(0, 1, 1000)
    # points of one definition lie on the curve of the other, at the mapped parameter
    xi2 = cubic_parameter(quadratic_parameter(xi, k1), k2)
    assert np.abs(a(xi) - b(xi2)).max() <= 1e-12 * c.chord
    assert np.abs(c.implicit_residual(a(xi))).max() <= 1e-12
    assert np.abs(a(xi) - c(quadratic_parameter(xi, k1))).max() <= 1e-12 * c.chord
    assert a.weights[0] == 1.0 and a.weights[3] == 1.0


def test_k_half_is_ordinary_degree_elevation(example1):
    a = example1.cubic(0.5)
    e = example1.bezier.elevated()
    assert np.allclose(a.points, e.points, atol=1e-15)
    assert np.allclose(a.weights, e.weights, atol=1e-15)


@given(st.floats(0.0, 0.9), st.floats(0.01, 1.0))
def test_sub_arc_is_exact(ua, width):
    c = conic_arc(*EXAMPLE1)
    ub = min(ua + width, 1.0)
    s = c.sub_arc(ua, ub)
    pts = s(U)
    assert np.abs(c.implicit_residual(pts)).max() < 1e-13
    assert np.allclose(s([0.0, 1.0]), c([ua, ub]), atol=1e-15)
    assert s.arc_length() == pytest.approx(c.arc_length(ua, ub), rel=1e-12)
    a, b, sigma = c.sub_arc_map(ua, ub)
    t = sigma * U / (1 - U + sigma * U)
    assert np.abs(pts - c(a + (b - a) * t)).max() < 1e-14


def test_arc_length_inverse(example1):
    s = np.linspace(0, example1.arc_length(), 7)[1:-1]
    u = example1.parameters_at_arc_lengths(s)
    for uu, ss in zip(u, s, strict=True):
        assert example1.arc_length(0, uu) == pytest.approx(ss, rel=1e-13)


def test_placement_in_3d_is_rigid_and_planar():
    start, end = np.array([0.1, -0.2, 0.3]), np.array([0.4, 0.1, 0.5])
    local = conic_arc(*EXAMPLE1)
    chord = np.linalg.norm(end - start)
    # build a global interior point from the local one in some plane through the chord
    e1 = (end - start) / chord
    e2 = np.cross(e1, [0.0, 0.0, 1.0])
    e2 /= np.linalg.norm(e2)
    loc_point = local([0.42])[0] * chord / 0.5
    point = start + loc_point[0] * e1 + loc_point[1] * e2
    c = conic_arc_through(start, end, [30, 40], point)
    assert c.dim == 3
    assert np.allclose(c([0.0, 1.0]), [start, end], atol=1e-15)
    assert c.omega == pytest.approx(local.omega, rel=1e-12)
    assert c.arc_length() == pytest.approx(local.arc_length() * chord / 0.5, rel=1e-12)
    n = np.cross(e1, e2)
    assert np.abs((c(U) - start) @ n).max() < 1e-15
    # the arc lies on the side of the interior point
    assert np.all((c(U[1:-1]) - start) @ e2 > 0)


def test_placement_2d_either_side():
    up = conic_arc_through([0, 0], [0.5, 0], [30, 40], [0.315, 0.077])
    down = conic_arc_through([0, 0], [0.5, 0], [30, 40], [0.315, -0.077])
    assert np.allclose(up(U) * [1, -1], down(U), atol=1e-15)
    assert np.all(up.curvature(U) < 0) and np.all(down.curvature(U) > 0)


@pytest.mark.parametrize(
    ("args", "exc", "needle"),
    [
        ((0.5, (0.0, 40.0), (0.3, 0.05)), AngleError, "theta0"),
        ((0.5, (30.0, 90.0), (0.3, 0.05)), AngleError, "theta1"),
        ((0.5, (-5.0, 40.0), (0.3, 0.05)), AngleError, "(0, 90)"),
        ((0.0, (30.0, 40.0), (0.3, 0.05)), ChordError, "chord"),
        ((-0.5, (30.0, 40.0), (0.3, 0.05)), ChordError, "chord"),
        ((0.5, (30.0, 40.0), (0.3, 0.5)), InteriorPointError, "point"),
        ((0.5, (30.0, 40.0), (0.3, 0.0)), InteriorPointError, "point"),
        ((0.5, (30.0, 40.0), (0.6, 0.01)), InteriorPointError, "triangle"),
    ],
)
def test_bad_input_is_named(args, exc, needle):
    with pytest.raises(exc) as info:
        conic_arc(*args)
    assert isinstance(info.value, ValueError)
    assert needle in str(info.value)
    assert "not allowed" in str(info.value)


@pytest.mark.parametrize("k", [0.0, 1.0, -0.1, 1.5, float("nan")])
def test_bad_mapping_factor(example1, k):
    with pytest.raises(MappingFactorError, match="K"):
        example1.cubic(k)
