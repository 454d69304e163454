"""Time functions (T.1–T.5): value, rate and acceleration against closed forms."""

import math

import numpy as np
import pytest

from rancf.bodies.time_function import TimeFunction, spin_up_angle
from rancf.bodies.time_record import table_coefficients
from rancf.errors import InputError

TIMES = [-0.5, 0.0, 0.13, 0.7, 1.0, 1.9, 2.0, 3.3]


def _derivatives_by_differences(f: TimeFunction, t: float) -> tuple[float, float]:
    """Central differences of the value (to check rate and acceleration independently)."""
    h = 1e-5
    v = [f.value(t + k * h) for k in (-1, 0, 1)]
    return (v[2] - v[0]) / (2 * h), (v[2] - 2 * v[1] + v[0]) / h**2


def test_constant():
    f = TimeFunction.constant(2.5)
    assert [f.value(t) for t in TIMES] == [2.5] * len(TIMES)
    assert f.rate(1.0) == 0.0 and f.acceleration(1.0) == 0.0 and not f.vector
    g = TimeFunction.constant([1.0, -2.0])
    assert g.vector and g.value(3.0).tolist() == [1.0, -2.0] and g.rate(3.0).tolist() == [0, 0]


def test_ramp():
    f = TimeFunction.ramp(2.0, 3.0)
    for t in TIMES:
        assert f.value(t) == pytest.approx(3.0 * min(max(t, 0.0) / 2.0, 1.0), rel=1e-15)
        assert f.rate(t) == (1.5 if 0.0 <= t < 2.0 else 0.0)
        assert f.acceleration(t) == 0.0
    v = TimeFunction.ramp(0.5, [0.0, 0.2])
    assert v.value(0.25).tolist() == pytest.approx([0.0, 0.1], rel=1e-15)


def test_harmonic():
    f = TimeFunction.harmonic(1.5, 0.2, 30.0)
    w, ph = 2 * math.pi * 1.5, math.radians(30.0)
    for t in TIMES:
        assert f.value(t) == pytest.approx(0.2 * math.sin(w * t + ph), rel=1e-14, abs=1e-16)
        assert f.rate(t) == pytest.approx(0.2 * w * math.cos(w * t + ph), rel=1e-14, abs=1e-15)
        a = -0.2 * w * w * math.sin(w * t + ph)
        assert f.acceleration(t) == pytest.approx(a, rel=1e-14, abs=1e-14)


def test_spin_up_law_of_kane_ryan_banerjee():
    """theta(t) = (W/T)[t^2/2 + (T/2pi)^2 (cos(2 pi t/T) - 1)] for t <= T, W (t - T/2) after."""
    big_t, w = 15.0, 6.0
    f = TimeFunction.spin_up(big_t, w)
    for t in [0.0, 1.0, 5.0, 7.5, 14.999, 15.0, 20.0]:
        if t <= big_t:
            th = (
                w
                / big_t
                * (
                    t**2 / 2
                    + (big_t / (2 * math.pi)) ** 2 * (math.cos(2 * math.pi * t / big_t) - 1)
                )
            )
        else:
            th = w * (t - big_t / 2)
        assert f.value(t) == pytest.approx(th, rel=1e-13, abs=1e-14)
        rate, acc = _derivatives_by_differences(f, t)
        if abs(t - big_t) > 1e-3:  # away from the join (one-sided there)
            assert f.rate(t) == pytest.approx(rate, rel=1e-8, abs=1e-9)
            assert f.acceleration(t) == pytest.approx(acc, rel=1e-4, abs=1e-5)
    # smooth join: rate W and acceleration 0 from both sides at t = T
    assert f.rate(big_t - 1e-9) == pytest.approx(w, rel=1e-9) and f.rate(big_t) == w
    assert abs(f.acceleration(big_t - 1e-9)) < 1e-9 and f.acceleration(big_t) == 0.0
    assert f.value(-1.0) == f.rate(-1.0) == f.acceleration(-1.0) == 0.0
    assert spin_up_angle(np.array([20.0]), big_t, w).tolist() == [w * 12.5]


def test_linear_table_holds_outside():
    f = TimeFunction.table([[0.0, 1.0], [1.0, 3.0], [2.0, 2.0]])
    assert f.value(-1.0) == 1.0 and f.rate(-1.0) == 0.0
    assert f.value(0.5) == pytest.approx(2.0, rel=1e-15) and f.rate(0.5) == 2.0
    assert f.value(1.0) == 3.0 and f.rate(1.0) == -1.0  # the interval starting there
    assert f.value(5.0) == 2.0 and f.rate(5.0) == 0.0 and f.acceleration(1.5) == 0.0


def test_cubic_table_is_exact_for_a_cubic():
    """The not-a-knot spline reproduces a cubic polynomial: value, rate, acceleration."""
    p = np.polynomial.Polynomial([0.3, -1.0, 0.5, 0.25])
    ts = np.array([0.0, 0.4, 1.1, 1.5, 2.6, 3.0])
    f = TimeFunction.table(np.column_stack([ts, p(ts)]), "cubic")
    for t in np.linspace(0.0, 2.99, 37):
        assert f.value(t) == pytest.approx(p(t), rel=1e-12, abs=1e-12)
        assert f.rate(t) == pytest.approx(p.deriv()(t), rel=1e-11, abs=1e-11)
        assert f.acceleration(t) == pytest.approx(p.deriv(2)(t), rel=1e-10, abs=1e-10)
    assert f.value(4.0) == pytest.approx(p(3.0), rel=1e-14) and f.rate(4.0) == 0.0
    # the packed piecewise coefficients evaluate to the same function
    breaks, coef = table_coefficients(f)
    i, s = 3, 0.3
    assert breaks.tolist() == ts.tolist()
    assert np.polyval(coef[i, ::-1, 0], s) == pytest.approx(p(ts[i] + s), rel=1e-12)


def test_vector_table_and_interpolation_checks():
    f = TimeFunction.table([[0.0, 0.0, 0.0], [2.0, 0.2, -0.4]])
    assert f.vector and f.size == 2
    assert f.value(1.0).tolist() == pytest.approx([0.1, -0.2], rel=1e-15)
    assert f.rate(1.0).tolist() == pytest.approx([0.1, -0.2], rel=1e-15)
    with pytest.raises(InputError, match="increasing"):
        TimeFunction.table([[0.0, 1.0], [0.0, 2.0]])
    with pytest.raises(InputError, match="linear"):
        TimeFunction.table([[0.0, 1.0], [1.0, 2.0]], "quintic")
    with pytest.raises(InputError, match="two rows"):
        TimeFunction.table([[0.0, 1.0]])


def test_from_callable_central_differences():
    f = TimeFunction.from_callable(lambda t: math.sin(3.0 * t))
    for t in [0.0, 0.4, 2.5, 40.0]:
        assert f.value(t) == math.sin(3.0 * t)
        assert f.rate(t) == pytest.approx(3.0 * math.cos(3.0 * t), abs=1e-8)
        assert f.acceleration(t) == pytest.approx(-9.0 * math.sin(3.0 * t), abs=1e-5)
    g = TimeFunction.from_callable(lambda t: [t, t * t])
    assert g.vector and g.rate(2.0).tolist() == pytest.approx([1.0, 4.0], rel=1e-9)
    s = f.sampled(1.0, 401)  # a cubic table of the function
    assert s.kind == "table" and s.value(0.3) == pytest.approx(math.sin(0.9), abs=1e-9)
    with pytest.raises(InputError):
        f.to_toml()


@pytest.mark.parametrize(
    "f",
    [
        TimeFunction.constant(2.0),
        TimeFunction.constant([1.0, 2.0, 3.0]),
        TimeFunction.ramp(0.5, [0.0, 1.0]),
        TimeFunction.harmonic(2.0, 0.5, 45.0),
        TimeFunction.spin_up(0.05, 150.0),
        TimeFunction.table([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]], "cubic"),
    ],
    ids=["constant", "vector", "ramp", "harmonic", "spin_up", "table"],
)
def test_file_form_round_trip(f):
    from rancf.scenario.loads import SupportTable
    from rancf.scenario.time_functions import time_function

    if f.vector and f.size == 2:
        back = time_function(SupportTable(at="end", motion=f.to_toml()).motion)
    else:
        back = _from_toml(f.to_toml())
    assert back == f
    assert back.value(0.3) == pytest.approx(f.value(0.3), rel=1e-14)


def _from_toml(v):
    from rancf.scenario.joints import JointTable
    from rancf.scenario.time_functions import time_function

    if isinstance(v, list):
        return TimeFunction.constant(v)
    j = JointTable(name="j", kind="pin", between=["a", "b"], angle=v)
    return time_function(j.angle)


def test_bad_arguments():
    for bad in (
        lambda: TimeFunction.ramp(0.0),
        lambda: TimeFunction.harmonic(-1.0),
        lambda: TimeFunction.spin_up(1.0, [1.0, 2.0]),
        lambda: TimeFunction.constant(float("nan")),
        lambda: TimeFunction.from_callable(3.0),
    ):
        with pytest.raises(InputError):
            bad()
