import numpy as np
import pytest

from rancf.elements.mapping import conic_element, gradient_ratio, kopt
from rancf.geometry.conic import conic_arc
from tests.conftest import EXAMPLE2, EXAMPLE3


def test_example1_kopt_and_gradient_ratios(example1):
    k = kopt(example1)
    assert k == pytest.approx(0.4065, abs=5e-4)
    ratios = [gradient_ratio(example1.cubic(kk)) for kk in (0.2, k, 0.6)]
    assert ratios == pytest.approx([1.960, 1.042, 1.685], abs=5e-4)


def test_example3_kopt_is_one_half():
    assert kopt(conic_arc(*EXAMPLE3)) == pytest.approx(0.5, abs=1e-6)


def test_example2_kopt():
    assert kopt(conic_arc(*EXAMPLE2)) == pytest.approx(0.695, abs=5e-4)


def test_gradient_ratio_is_unimodal_in_k(example1):
    ks = np.linspace(0.05, 0.95, 91)
    r = np.array([gradient_ratio(example1.cubic(k)) for k in ks])
    i = int(np.argmin(r))
    assert np.all(np.diff(r[: i + 1]) < 0) and np.all(np.diff(r[i:]) > 0)
    assert kopt(example1) == pytest.approx(ks[i], abs=0.01)


def test_gradient_ratio_extrema_are_exact(example1):
    c = example1.cubic(0.3)
    fine = np.linspace(0, 1, 200_001)
    sp = np.linalg.norm(c.derivatives(fine, 1)[1], axis=1)
    assert gradient_ratio(c) == pytest.approx(sp.max() / sp.min(), rel=1e-9)


def test_symmetric_conic_has_kopt_one_half():
    for om_point in ((0.25, 0.05), (0.25, 0.1), (0.25, 0.13)):
        assert kopt(conic_arc(0.5, [30, 30], om_point)) == pytest.approx(0.5, abs=1e-6)


def test_single_element_definition(example1):
    e = conic_element(example1, 0.2)
    assert e.scale == pytest.approx(example1.arc_length(), rel=1e-14)
    assert np.allclose(e.nodal[0], example1.p0) and np.allclose(e.nodal[2], example1.p2)
    # end gradients are the curve derivative divided by l, along the end tangents
    d = e.curve.derivatives([0.0, 1.0], 1)[1]
    assert np.allclose(e.nodal[1], d[0] / e.scale, atol=1e-15)
    assert np.allclose(e.nodal[3], d[1] / e.scale, atol=1e-15)
    assert conic_element(example1).k == pytest.approx(kopt(example1), abs=1e-12)
