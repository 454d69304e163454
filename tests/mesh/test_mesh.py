import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from rancf.elements.mapping import kopt
from rancf.errors import ElementCountError, InputError, MappingFactorError
from rancf.geometry.conic import conic_arc, conic_arc_through
from rancf.mesh.factories import conic_breakpoints, mesh_conic, mesh_line, to_ancf
from tests.conftest import EXAMPLE1, EXAMPLE2

XI = np.linspace(0.0, 1.0, 101)


def _shared_node_mismatch(mesh):
    """Largest disagreement of element ends with the shared nodal vectors, relative."""
    d = mesh.evaluate([0.0, 1.0], order=1) / mesh.scales[:, None, None]
    p = mesh.evaluate([0.0, 1.0])
    size = np.abs(mesh.nodes).max()
    return (
        max(
            np.abs(np.concatenate([d[:-1, 1] - d[1:, 0], p[:-1, 1] - p[1:, 0]])).max(initial=0.0),
            np.abs(p[:, 0] - mesh.nodes[:-1, 0]).max(),
            np.abs(d[:, 0] - mesh.nodes[:-1, 1]).max(),
        )
        / size
    )


@given(
    st.integers(1, 12),
    st.sampled_from(["opt", 0.2, 0.6, 0.9]),
    st.sampled_from(["arc", "parameter"]),
)
def test_subdivided_mesh_reproduces_the_conic(n, k, spacing):
    c = conic_arc(*EXAMPLE1)
    m = mesh_conic(c, n, k, spacing)
    pts = m.evaluate(XI).reshape(-1, 2)
    assert np.abs(c.implicit_residual(pts)).max() < 1e-12
    assert np.allclose(m.nodes[[0, -1], 0], [c.p0, c.p2], atol=1e-15)
    assert _shared_node_mismatch(m) < 1e-13
    assert m.arc_lengths().sum() == pytest.approx(c.arc_length(), rel=1e-12)
    assert m.scales.sum() == pytest.approx(c.arc_length(), rel=1e-12)


def test_equal_arc_length_spacing(example1):
    m = mesh_conic(example1, 7)
    s = m.arc_lengths()
    assert np.allclose(s, example1.arc_length() / 7, rtol=1e-12)
    u = conic_breakpoints(example1, 7, "parameter")
    assert np.allclose(np.diff(u), 1 / 7)


def test_kopt_per_element_and_single_k(example1):
    m = mesh_conic(example1, 4)
    for j in range(4):
        sub = example1.sub_arc(m.parameters[j], m.parameters[j + 1])
        assert m.k[j] == pytest.approx(kopt(sub), abs=1e-6)  # vectorized Kopt (conic_chain)
    assert np.all(m.k > 0.4) and np.all(m.gradient_ratios() < 1.01)
    m2 = mesh_conic(example1, 4, 0.3)
    assert np.all(m2.k == 0.3)


def test_spatial_mesh_is_exact():
    chord, angles, point = EXAMPLE2
    c = conic_arc_through([0, 0, 0], [chord, 0, 0], angles, [point[0], 0.0, point[1]])
    m = mesh_conic(c, 6)
    pts = m.evaluate(XI).reshape(-1, 3)
    assert np.abs(c.implicit_residual(pts)).max() < 1e-13
    assert np.abs(pts[:, 1]).max() == 0.0
    assert _shared_node_mismatch(m) < 1e-13


def test_line_mesh_is_classical_ancf():
    m = mesh_line([0, 0], [1.2, 0], 8)
    assert np.all(m.weights == 1.0)
    assert np.allclose(m.scales, 0.15)
    assert np.allclose(m.nodes[:, 1], [1.0, 0.0])


def test_ancf_mesh_interpolates_nodes_and_tangents(example1):
    exact = mesh_conic(example1, 5)
    a = to_ancf(exact)
    assert np.allclose(a.nodes[:, 0], exact.nodes[:, 0], atol=1e-15)
    assert np.allclose(np.linalg.norm(a.nodes[:, 1], axis=1), 1.0)
    assert _shared_node_mismatch(a) < 1e-13
    # it only approximates the conic inside the elements, and better with more elements
    err5 = np.abs(example1.implicit_residual(a.evaluate(XI).reshape(-1, 2))).max()
    a10 = to_ancf(mesh_conic(example1, 10))
    err10 = np.abs(example1.implicit_residual(a10.evaluate(XI).reshape(-1, 2))).max()
    assert 1e-9 < err10 < err5


@pytest.mark.parametrize("n", [0, -3, 2.5, "x"])
def test_bad_element_counts(example1, n):
    with pytest.raises(ElementCountError, match="elements"):
        mesh_conic(example1, n)


def test_bad_k_and_spacing(example1):
    with pytest.raises(MappingFactorError):
        mesh_conic(example1, 3, 1.0)
    with pytest.raises(InputError, match="spacing"):
        mesh_conic(example1, 3, spacing="chord")  # type: ignore[arg-type]
