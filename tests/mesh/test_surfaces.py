"""Exact surface meshes for shells: areas, points and normals against closed forms, continuity
across element edges, the mapping factor K per direction, and NURBS surfaces cut into elements."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.elements.mapping import gradient_ratio, kopt
from rancf.errors import InputError
from rancf.geometry.bezier import RationalBezier
from rancf.geometry.conic_curve import Conic
from rancf.geometry.nurbs import basis_functions
from rancf.mesh.surface_kinds import circle_pieces, mesh_surface
from rancf.mesh.surfaces import SurfaceMesh

TOL = 1e-12
MESHES = [(1, 1), (3, 2), (5, 7)]
GRID = np.linspace(0.0, 1.0, 7)
R, L = 25.0, 50.0


def _rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


def _cylinder(n, k="opt", angles=(50.0, 130.0)) -> SurfaceMesh:
    geo = {"kind": "cylinder", "radius": R, "length": L, "angles_deg": list(angles)}
    return mesh_surface(geo, n, k)


def _cone(n, k="opt") -> SurfaceMesh:
    geo = {"kind": "cone", "radius": [3.0, 1.5], "length": 4.0, "angles_deg": [-30.0, 140.0]}
    return mesh_surface(geo, n, k)


def _sphere(n, k="opt") -> SurfaceMesh:
    geo = {"kind": "sphere", "radius": 10.0, "azimuth_deg": [0.0, 90.0], "polar_deg": [18.0, 90.0]}
    return mesh_surface(geo, n, k)


@pytest.mark.parametrize("n", MESHES)
@pytest.mark.parametrize("k", ["opt", 0.3, 0.8])
def test_cylinder_is_exact(n, k):
    m = _cylinder(n, k)
    assert _rel(m.element_areas().sum(), R * np.radians(80.0) * L) < TOL
    p = m.evaluate(GRID, GRID)
    assert np.abs(np.hypot(p[..., 0], p[..., 2]) / R - 1.0).max() < TOL
    a = np.arctan2(p[..., 2], p[..., 0])
    inward = -np.stack([np.cos(a), np.zeros_like(a), np.sin(a)], axis=-1)
    assert np.abs(m.normals(GRID, GRID) - inward).max() < TOL
    for u, v in [(0.0, 0.0), (0.3, 0.7), (0.5, 0.5), (1.0, 0.25), (0.99, 1.0)]:
        ang = np.radians(50.0 + 80.0 * u)
        want = np.array([R * np.cos(ang), L * v, R * np.sin(ang)])
        assert np.abs(m.point([u, v]) - want).max() < TOL * R


@pytest.mark.parametrize("n", MESHES)
def test_cone_frustum_is_exact(n):
    m = _cone(n)
    r0, r1, length, span = 3.0, 1.5, 4.0, np.radians(170.0)
    slant = np.hypot(length, r1 - r0)
    assert _rel(m.element_areas().sum(), 0.5 * span * (r0 + r1) * slant) < TOL
    p = m.evaluate(GRID, GRID)
    r = r0 + (r1 - r0) * p[..., 1] / length
    assert np.abs(np.hypot(p[..., 0], p[..., 2]) / r - 1.0).max() < TOL
    a = np.arctan2(p[..., 2], p[..., 0])
    grad = np.stack([np.cos(a), np.full_like(a, -(r1 - r0) / length), np.sin(a)], axis=-1)
    grad /= np.linalg.norm(grad, axis=-1, keepdims=True)
    assert np.abs(m.normals(GRID, GRID) + grad).max() < TOL
    ang = np.radians(-30.0 + 170.0 * 0.4)
    rr = r0 + 0.6 * (r1 - r0)
    want = np.array([rr * np.cos(ang), 0.6 * length, rr * np.sin(ang)])
    assert np.abs(m.point([0.4, 0.6]) - want).max() < TOL * r0


@pytest.mark.parametrize("n", MESHES)
@pytest.mark.parametrize("k", ["opt", [0.35, 0.6]])
def test_spherical_zone_is_exact(n, k):
    m = _sphere(n, k)
    th0, th1 = np.radians([18.0, 90.0])
    assert _rel(m.element_areas().sum(), 100.0 * (np.pi / 2) * (np.cos(th0) - np.cos(th1))) < TOL
    p = m.evaluate(GRID, GRID)
    assert np.abs(np.linalg.norm(p, axis=-1) / 10.0 - 1.0).max() < TOL
    assert np.abs(m.normals(GRID, GRID) + p / 10.0).max() < TOL
    phi, th = np.radians(90.0 * 0.3), np.radians(18.0 + 72.0 * 0.8)
    want = 10.0 * np.array([np.sin(th) * np.cos(phi), np.sin(th) * np.sin(phi), np.cos(th)])
    assert np.abs(m.point([0.3, 0.8]) - want).max() < TOL * 10.0


@pytest.mark.parametrize("n", MESHES)
def test_rectangle_is_exact(n):
    m = mesh_surface({"kind": "rectangle", "corner": [1.0, -2.0, 0.5], "size": [3.0, 2.0]}, n)
    assert _rel(m.element_areas().sum(), 6.0) < TOL
    assert np.abs(m.normals(GRID, GRID) - [0.0, 0.0, 1.0]).max() < TOL
    assert np.abs(m.point([0.25, 0.75]) - [1.75, -0.5, 0.5]).max() < TOL
    assert np.abs(m.evaluate(GRID, GRID)[..., 2] - 0.5).max() < TOL


def _edge_jumps(m: SurfaceMesh) -> tuple[float, float, float]:
    """Largest jumps across interior element edges (both directions): position, the scaled
    cross derivative ``r_x`` (``r_y``) relative to its size, and the normal."""
    x = np.linspace(0.0, 1.0, 9)
    ends = np.array([0.0, 1.0])
    pos, grad, nrm = [0.0], [0.0], [0.0]
    for axis, (a, b) in ((1, (ends, x)), (0, (x, ends))):
        order = (1, 0) if axis == 1 else (0, 1)
        scales = (m.u if axis == 1 else m.v).scales
        p = m.evaluate(a, b)
        d = m.evaluate(a, b, order=order)
        d = d / (
            scales[None, :, None, None, None] if axis == 1 else scales[:, None, None, None, None]
        )
        nn = m.normals(a, b)
        for f, out in ((p, pos), (d, grad), (nn, nrm)):
            if axis == 1 and m.u.n > 1:
                jump = f[:, 1:, 0] - f[:, :-1, 1]
            elif axis == 0 and m.v.n > 1:
                jump = f[1:, :, :, 0] - f[:-1, :, :, 1]
            else:
                continue
            size = np.abs(f).max()
            out.append(float(np.abs(jump).max() / size))
    return max(pos), max(grad), max(nrm)


@pytest.mark.parametrize(
    "make", [lambda: _cylinder((4, 3), 0.3), lambda: _cone((5, 2)), lambda: _sphere((3, 4))]
)
def test_elements_join_c0_and_g1(make):
    pos, grad, nrm = _edge_jumps(make())
    assert pos < TOL and grad < 1e-11 and nrm < 1e-11


def test_full_cylinder_closes_on_itself():
    m = _cylinder((4, 2), angles=(0.0, 360.0))
    assert m.u.closed and not m.v.closed
    first, last = m.nodes[:, 0], m.nodes[:, -1]
    assert np.abs(first[:, 0] - last[:, 0]).max() < TOL * R
    t0, t1 = first[:, 1], last[:, 1]  # same tangent direction at the seam
    assert np.abs(np.cross(t0, t1)).max() < TOL * np.abs(t0).max() ** 2


def test_edges_are_the_parameter_lines():
    m = _cylinder((3, 2))
    pos = m.nodes.reshape(-1, 4, 3)[:, 0]
    np.testing.assert_allclose(pos[m.edge_nodes("v1"), 1], L, rtol=TOL)
    np.testing.assert_allclose(pos[m.edge_nodes("v0"), 1], 0.0, atol=TOL * L)
    ang = np.degrees(np.arctan2(pos[m.edge_nodes("u1"), 2], pos[m.edge_nodes("u1"), 0]))
    np.testing.assert_allclose(ang, 130.0, rtol=TOL)
    with pytest.raises(InputError, match="u2"):
        m.edge_nodes("u2")


def _directional_ratios(m: SurfaceMesh, axis: int) -> np.ndarray:
    """max/min of |∂r/∂ξ| (axis 1) or |∂r/∂η| (axis 0) along each parameter line of each
    element, on 2001 samples: shape (nv, nu, lines)."""
    s = np.linspace(0.0, 1.0, 2001)
    lines = np.linspace(0.0, 1.0, 5)
    if axis == 1:
        d = np.linalg.norm(m.evaluate(s, lines, order=(1, 0)), axis=-1)
        return d.max(axis=2) / d.min(axis=2)
    d = np.linalg.norm(m.evaluate(lines, s, order=(0, 1)), axis=-1)
    return d.max(axis=3) / d.min(axis=3)


def test_mapping_factor_carries_over_from_the_directrix():
    # every u-line of a surface of revolution is a scaled copy of the circular directrix, so the
    # directional gradient ratio is the cable element's, whatever the line and the profile
    for k in (0.2, 0.5, 0.75):
        m = _cone((2, 3), k)
        _, w, _ = circle_pieces(np.radians(-30.0), np.radians(140.0), 2, k)
        pts = circle_pieces(np.radians(-30.0), np.radians(140.0), 2, k)[0]
        cable = [gradient_ratio(RationalBezier(pts[i], w[i])) for i in range(2)]
        ratios = _directional_ratios(m, axis=1)
        assert np.abs(ratios / np.array(cable)[None, :, None] - 1.0).max() < 1e-6
        assert np.all(m.u.k == k) and np.all(np.isnan(m.v.k))
    assert np.abs(_directional_ratios(_cone((2, 3)), axis=0) - 1.0).max() < 1e-12  # straight


def test_kopt_of_circular_directions_is_one_half():
    # a circular element is symmetric about its bisector: Kopt = 1/2 (ordinary elevation)
    for m in (_cylinder((3, 2)), _cone((4, 1)), _sphere((2, 3))):
        for d in (m.u, m.v):
            if np.all(np.isfinite(d.k)):
                assert np.abs(d.k - 0.5).max() < 1e-6
    alpha = np.radians(40.0)  # the exact Kopt of one 80° element
    arc = Conic(
        [1.0, 0.0], [1.0, np.tan(alpha)], [np.cos(2 * alpha), np.sin(2 * alpha)], np.cos(alpha)
    )
    assert abs(kopt(arc) - 0.5) < 1e-8
    best = _directional_ratios(_cylinder((1, 1)), axis=1).max()
    for k in (0.3, 0.45, 0.55, 0.7):
        assert _directional_ratios(_cylinder((1, 1), k), axis=1).max() > best


def test_sphere_meridian_factor_is_its_own():
    m = _sphere((2, 2), [0.5, 0.3])
    assert np.all(m.u.k == 0.5) and np.all(m.v.k == 0.3)
    r = _directional_ratios(m, axis=0)
    assert np.ptp(r, axis=(1, 2)).max() < 1e-9  # every meridian line of an element alike


def _reference_nurbs(spec: dict, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The NURBS surface by the Cox–de Boor basis (no Bézier extraction), points (n_u, n_v, 3)."""
    p, q = spec["degree"]
    ku, kv = np.asarray(spec["knots_u"]), np.asarray(spec["knots_v"])
    nu, nv = ku.size - p - 1, kv.size - q - 1
    cp = np.asarray(spec["control_points"], float).reshape(nv, nu, 3)
    w = np.asarray(spec["weights"], float).reshape(nv, nu)
    a, b = ku[p] + u * (ku[nu] - ku[p]), kv[q] + v * (kv[nv] - kv[q])
    bu, bv = basis_functions(ku, p, nu, a), basis_functions(kv, q, nv, b)
    num = np.einsum("ui,vj,ji,jix->uvx", bu, bv, w, cp)
    return num / np.einsum("ui,vj,ji->uv", bu, bv, w)[..., None]


def _bspline_spec() -> dict:
    rng = np.random.default_rng(7)
    nu, nv = 6, 4
    x, y = np.meshgrid(np.linspace(0, 5, nu), np.linspace(0, 3, nv))
    z = 0.4 * rng.standard_normal((nv, nu))
    pts = np.stack([x + 0.1 * rng.standard_normal((nv, nu)), y, z], axis=-1).reshape(-1, 3)
    return {
        "kind": "nurbs_surface",
        "degree": [3, 2],
        "knots_u": [0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1],
        "knots_v": [0, 0, 0, 0.4, 1, 1, 1],
        "control_points": pts.tolist(),
        "weights": [1.0] * (nu * nv),
    }


def _torus_spec() -> dict:
    s = np.sqrt(0.5)  # half a torus around z (two spans), a quarter of its tube
    circ = np.array([[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0]], float)
    wu = np.array([1, s, 1, s, 1])
    prof = np.array([[4.0, 0.0], [4.0, 1.0], [3.0, 1.0]])  # (radius, z): tube radius 1 at 3
    wv = np.array([1.0, s, 1.0])
    pts = [[pr[0] * c[0], pr[0] * c[1], pr[1]] for pr in prof for c in circ]
    return {
        "kind": "nurbs_surface",
        "degree": [2, 2],
        "knots_u": [0, 0, 0, 0.5, 0.5, 1, 1, 1],
        "knots_v": [0, 0, 0, 1, 1, 1],
        "control_points": pts,
        "weights": np.outer(wv, wu).ravel().tolist(),
    }


@pytest.mark.parametrize("n", [(1, 1), (2, 3)])
def test_nurbs_surface_is_reproduced(n):
    u, v = np.linspace(0.0, 1.0, 11), np.linspace(0.0, 1.0, 9)
    for spec in (_bspline_spec(), _torus_spec()):
        m = mesh_surface(spec, n)
        ref = _reference_nurbs(spec, u, v)
        got = np.array([[m.point([a, b]) for b in v] for a in u])
        assert np.abs(got - ref).max() < TOL * np.abs(ref).max()
        pos, grad, nrm = _edge_jumps(m)
        assert pos < TOL and grad < 1e-11 and nrm < 1e-11
    m = mesh_surface(_torus_spec(), n)
    p = m.evaluate(GRID, GRID)
    tube = np.hypot(np.hypot(p[..., 0], p[..., 1]) - 3.0, p[..., 2])
    assert np.abs(tube - 1.0).max() < TOL * 4.0


@pytest.mark.parametrize(
    ("geometry", "elements", "key"),
    [
        ({"kind": "torus"}, [1, 1], "geometry.kind"),
        (
            {"kind": "cylinder", "radius": -1.0, "length": 1, "angles_deg": [0, 90]},
            [1, 1],
            "radius",
        ),
        (
            {"kind": "cylinder", "radius": 1, "length": 1, "angles_deg": [0, 360]},
            [1, 1],
            "elements",
        ),
        (
            {"kind": "cylinder", "radius": 1, "length": 1, "angles_deg": [0, 90], "x": 1},
            [1, 1],
            "x",
        ),
        (
            {"kind": "sphere", "radius": 1, "azimuth_deg": [0, 90], "polar_deg": [0, 90]},
            [1, 1],
            "polar",
        ),
        ({"kind": "cone", "radius": [1, 0], "length": 1, "angles_deg": [0, 90]}, [1, 1], "radius"),
        ({"kind": "rectangle", "corner": [0, 0], "size": [1, 0]}, [1, 1], "size"),
        ({"kind": "rectangle", "corner": [0, 0], "size": [1, 1]}, [1, 0], "elements"),
    ],
)
def test_bad_input_names_the_key(geometry, elements, key):
    with pytest.raises(InputError, match=key):
        mesh_surface(geometry, elements)


def test_general_rational_weights_are_refused():
    spec = _torus_spec()
    w = np.asarray(spec["weights"]).reshape(3, 5)
    w[1, 2] *= 1.5
    spec["weights"] = w.ravel().tolist()
    with pytest.raises(InputError, match="product weights"):
        mesh_surface(spec, [1, 1])


def test_mapping_factor_only_on_curved_directions():
    with pytest.raises(InputError, match="straight"):
        _cylinder((2, 2), [0.5, 0.4])
    with pytest.raises(InputError, match="mesh.k"):
        mesh_surface(_bspline_spec(), [1, 1], 0.4)


@pytest.mark.parametrize(
    ("change", "key"),
    [
        ({"degree": [4, 2]}, "geometry.degree"),
        ({"degree": "cubic"}, "geometry.degree"),
        ({"knots_u": [0, 0, 0, 0, 0.7, 0.3, 1, 1, 1, 1]}, "geometry.knots_u"),
        ({"knots_v": [0, 0, 0, 1, 1, 1]}, "geometry.control_points"),
        ({"control_points": [[0, 0, "a"]] * 24}, "geometry.control_points"),
        ({"weights": [1.0] * 23}, "geometry.weights"),
        ({"weights": [1.0] * 23 + [-1.0]}, "geometry.weights"),
    ],
)
def test_bad_nurbs_surface_names_the_key(change, key):
    spec = {**_bspline_spec(), **change}
    with pytest.raises(InputError, match=key.replace(".", r"\.")) as err:
        mesh_surface(spec, [1, 1])
    assert "\n" not in str(err.value)
