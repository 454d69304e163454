"""The shell body: numbering, points, supports as constraint rows and loads as consistent nodal
vectors, checked against closed forms and rigid motions."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.shell import NODE_DOFS, ShellBody, ShellSupport
from rancf.bodies.shell_loads import distributed_load, edge_load, point_load, resultant
from rancf.bodies.shell_supports import constraint_rows
from rancf.errors import InputError
from rancf.mesh.surface_kinds import mesh_surface

R, L = 25.0, 50.0
TOL = 1e-12


def _body(geometry: dict, elements=(3, 2), supports=()) -> ShellBody:
    m = mesh_surface(geometry, list(elements))
    return ShellBody(m, 0.25, 4.32e8, 0.0, 1.0, supports=list(supports))


def _roof(a0=50.0, a1=130.0, elements=(3, 2), supports=()) -> ShellBody:
    geo = {"kind": "cylinder", "radius": R, "length": L, "angles_deg": [a0, a1]}
    return _body(geo, elements, supports)


def _plate(elements=(3, 2)) -> ShellBody:
    return _body({"kind": "rectangle", "corner": [1.0, 2.0], "size": [12.0, 1.0]}, elements)


def _rotate(body: ShellBody, axis, angle: float, about=(0.0, 0.0, 0.0)) -> np.ndarray:
    """The reference turned rigidly: every nodal vector rotated, positions about ``about``."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    rot = np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx
    e = body.q0.reshape(-1, 4, 3).copy()
    e[:, 0] -= about
    e = e @ rot.T
    e[:, 0] += about
    return e.ravel()


def _translate(body: ShellBody, d) -> np.ndarray:
    e = body.q0.reshape(-1, 4, 3).copy()
    e[:, 0] += d
    return e.ravel()


def _held(body: ShellBody, q: np.ndarray) -> float:
    """Largest violation of the body's constraint rows at ``q``, relative to the motion."""
    c, d = constraint_rows(body)
    return float(np.abs(c @ q - d).max() / max(np.abs(q - body.q0).max(), 1e-300))


# ---------------------------------------------------------------- numbering and points
def test_numbering_is_node_by_node_twelve_a_node():
    b = _roof(elements=(3, 2))
    assert b.n_dofs == NODE_DOFS * 4 * 3 == b.q0.size
    en = b.mesh.element_nodal()
    for j in range(2):
        for i in range(3):
            np.testing.assert_array_equal(b.q0[b.element_dofs(i, j)], en[j, i])
    assert b.dof(5, 2, 1) == 12 * 5 + 3 * 2 + 1


@pytest.mark.parametrize("at", [(0.0, 0.0), (0.37, 0.81), (1.0, 0.5), (0.5, 1.0)])
def test_position_sensor_is_the_surface_point(at):
    b = _roof()
    a = np.radians(50.0 + at[0] * 80.0)
    exact = [R * np.cos(a), L * at[1], R * np.sin(a)]
    np.testing.assert_allclose(b.position(at), exact, rtol=0, atol=TOL * R * 10)
    np.testing.assert_allclose(b.shape_matrix(at) @ b.q0, exact, rtol=0, atol=TOL * R * 10)
    moved = _translate(b, [1.0, -2.0, 3.0])
    np.testing.assert_allclose(b.position(at, moved), np.add(exact, [1, -2, 3]), atol=1e-10)


# ---------------------------------------------------------------- loads
def test_distributed_load_on_the_roof_sums_to_p_times_the_area():
    b = _roof(elements=(4, 3))
    p = np.array([0.0, 0.0, -90.0])
    f, m = resultant(b, distributed_load(b, p))
    th = np.radians(80.0)
    area = R * th * L
    np.testing.assert_allclose(f, p * area, rtol=1e-12, atol=1e-9)
    a0, a1 = np.radians([50.0, 130.0])
    first = np.array(
        [
            R * R * (np.sin(a1) - np.sin(a0)) * L,
            R * th * L * L / 2,
            R * R * (np.cos(a0) - np.cos(a1)) * L,
        ]
    )
    np.testing.assert_allclose(m, np.cross(first, p), rtol=1e-11, atol=1e-6)


def test_point_load_sums_to_its_force_and_moment():
    b = _roof()
    at, f = (0.3, 0.7), np.array([1.0, -2.0, 3.0])
    tot, mom = resultant(b, point_load(b, at, f), about=(1.0, 1.0, 1.0))
    np.testing.assert_allclose(tot, f, rtol=0, atol=1e-13)
    np.testing.assert_allclose(mom, np.cross(b.position(at) - 1.0, f), rtol=1e-13, atol=1e-11)


def test_edge_force_on_a_curved_edge_sums_to_its_force_and_moment():
    b = _roof(elements=(4, 2))
    f = np.array([0.0, 2.0, -5.0])
    tot, mom = resultant(b, edge_load(b, "v1", force=f))
    np.testing.assert_allclose(tot, f, rtol=0, atol=1e-13)
    a0, a1 = np.radians([50.0, 130.0])
    centroid = np.array(
        [R * (np.sin(a1) - np.sin(a0)), L * (a1 - a0), R * (np.cos(a0) - np.cos(a1))]
    ) / (a1 - a0)
    np.testing.assert_allclose(mom, np.cross(centroid, f), rtol=1e-12, atol=1e-10)


@pytest.mark.parametrize(
    ("edge", "moment"),
    [("u1", [0.0, 3.0, 0.0]), ("u1", [0.4, -3.0, 0.0]), ("v0", [2.0, 0.5, 0.0])],
)
def test_edge_moment_on_a_straight_edge_sums_to_its_moment(edge, moment):
    b = _plate()
    tot, mom = resultant(b, edge_load(b, edge, moment=moment), about=(5.0, -3.0, 2.0))
    np.testing.assert_allclose(tot, 0.0, atol=1e-13)
    np.testing.assert_allclose(mom, moment, rtol=0, atol=1e-12)


def test_a_drilling_edge_moment_is_refused():
    with pytest.raises(InputError, match="moment = .* drilling"):
        edge_load(_plate(), "u1", moment=[0.0, 1.0, 1e-3])


# ---------------------------------------------------------------- supports
def test_diaphragm_allows_motion_normal_to_its_plane_only():
    b = _roof(supports=[ShellSupport("diaphragm", "v0"), ShellSupport("diaphragm", "v1")])
    c, d = constraint_rows(b)
    assert c.shape[0] == 2 * 2 * 2 * b.mesh.nodes.shape[1]  # 2 edges, r and r_x, 2 in-plane
    assert np.abs(c @ b.q0 - d).max() == 0.0
    assert _held(b, _translate(b, [0.0, 0.7, 0.0])) < TOL
    assert _held(b, _translate(b, [0.7, 0.0, 0.0])) > 0.5
    assert _held(b, _translate(b, [0.0, 0.0, 0.7])) > 0.5
    assert _held(b, _rotate(b, [0, 1, 0], 0.2)) > 0.1


def test_diaphragm_on_a_straight_edge_is_refused():
    b = _roof(supports=[ShellSupport("diaphragm", "u0")])
    with pytest.raises(InputError, match="curved edge"):
        constraint_rows(b)


def test_symmetry_allows_the_motions_in_its_plane():
    b = _roof(90.0, 130.0, supports=[ShellSupport("symmetry", "u0", normal=(1.0, 0.0, 0.0))])
    assert _held(b, _translate(b, [0.0, 0.4, -0.3])) < TOL
    assert _held(b, _rotate(b, [1, 0, 0], 0.3)) < 1e-12
    assert _held(b, _translate(b, [0.4, 0.0, 0.0])) > 0.5
    assert _held(b, _rotate(b, [0, 0, 1], 0.3)) > 0.1


def test_symmetry_needs_the_cross_tangent_along_its_normal():
    b = _roof(supports=[ShellSupport("symmetry", "u0", normal=(1.0, 0.0, 0.0))])
    with pytest.raises(InputError, match="normal"):
        constraint_rows(b)


def test_pin_on_a_straight_edge_allows_turning_about_it_and_clamp_does_not():
    about = _roof().position((1.0, 0.0))
    pin = _roof(supports=[ShellSupport("pin", "u1")])
    assert _held(pin, _rotate(pin, [0, 1, 0], 0.0)) == 0.0
    assert _held(pin, _rotate(pin, [0, 1, 0], 0.4, about)) < 1e-12
    assert _held(pin, _translate(pin, [0.0, 1.0, 0.0])) > 0.5
    clamp = _roof(supports=[ShellSupport("clamp", "u1")])
    assert _held(clamp, _rotate(clamp, [0, 1, 0], 0.4, about)) > 1e-3


@pytest.mark.parametrize("at", [(0.5, 0.5), (1.0 / 3.0, 0.5)])
def test_point_supports(at):
    roller = _roof(supports=[ShellSupport("roller", at, axis=(0.0, 0.0, 1.0))])
    assert _held(roller, _translate(roller, [0.0, 0.0, 0.3])) < TOL
    assert _held(roller, _translate(roller, [0.3, 0.0, 0.0])) > 0.1
    pin = _roof(supports=[ShellSupport("pin", at)])
    assert _held(pin, _rotate(pin, [1, 1, 0], 0.3, pin.position(at))) < 1e-12
    clamp = _roof(supports=[ShellSupport("clamp", at)])
    assert _held(clamp, _rotate(clamp, [1, 1, 0], 0.3, clamp.position(at))) > 1e-3


def test_a_closed_cylinder_ties_its_seam_and_turns_freely():
    b = _roof(0.0, 360.0, elements=(4, 2))
    c, d = constraint_rows(b)
    assert c.shape[0] == 12 * 3
    assert np.abs(d).max() < 1e-12 * R
    assert _held(b, _rotate(b, [0, 1, 0], 0.7)) < 1e-12
    seam = _translate(b, 0.0)
    seam[b.dof(b.mesh.edge_nodes("u1"), 0, 0)] += 0.1
    assert _held(b, seam) > 0.5


def test_supports_meeting_at_corners_hold_each_coordinate_once():
    b = _roof(
        90.0,
        130.0,
        supports=[
            ShellSupport("clamp", "u1"),
            ShellSupport("pin", "v0"),
            ShellSupport("symmetry", "u0", normal=(1.0, 0.0, 0.0)),
            ShellSupport("roller", (0.5, 0.5), axis=(0.0, 0.0, 1.0)),
        ],
    )
    c, _ = constraint_rows(b)
    assert np.linalg.matrix_rank(c.toarray()) == c.shape[0]
    n_v = b.mesh.nodes.shape[0]
    n_u = b.mesh.nodes.shape[1]
    # the clamped edge u1: 12 a node; v0 (pinned) 6 a node between the corners; u0 (symmetry)
    # 6 a node between the corners and at (u0, v1); at (u0, v0) the pin holds r and r_x, the
    # symmetry adds x . r_y and the in-plane r_xy (3); the roller off the nodes 2
    assert c.shape[0] == 12 * n_v + 6 * (n_u - 2) + 6 * (n_v - 2) + 6 + (6 + 3) + 2


def test_a_clamped_closed_cylinder_holds_its_seam_once():
    b = _roof(0.0, 360.0, elements=(4, 2), supports=[ShellSupport("clamp", "v0")])
    c, _ = constraint_rows(b)
    assert np.linalg.matrix_rank(c.toarray()) == c.shape[0]
    assert c.shape[0] == 12 * 5 + 12 * 2  # v0's 5 stored nodes, the seam at the 2 others
    assert _held(b, _translate(b, [0.0, 0.0, 0.2])) > 0.5
