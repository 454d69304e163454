"""Shell surfaces in ParaView files: each element a grid of quads on the exact surface, read back
with meshio."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.errors import InputError
from rancf.mesh.surface_kinds import mesh_surface
from rancf.post.vtk_shell import export_shell_vtk, surface_grid

meshio = pytest.importorskip("meshio")

R, L = 25.0, 50.0


def _roof():
    geo = {"kind": "cylinder", "radius": R, "length": L, "angles_deg": [50.0, 130.0]}
    return mesh_surface(geo, [3, 2])


def _quad_areas(points, quads):
    p = points[quads]
    return 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]), axis=1), np.cross(
        p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]
    )


def test_surface_grid_lies_on_the_cylinder_and_faces_its_normal(tmp_path):
    m = _roof()
    g = surface_grid(m, k=6)
    path = tmp_path / "roof.vtu"
    meshio.write(path, g)
    back = meshio.read(path)
    quads = back.cells_dict["quad"]
    assert back.points.shape == (3 * 2 * 36, 3) and quads.shape == (3 * 2 * 25, 4)
    radius = np.hypot(back.points[:, 0], back.points[:, 2])
    np.testing.assert_allclose(radius, R, rtol=1e-12)
    areas, normals = _quad_areas(back.points, quads)
    exact = R * np.radians(80.0) * L
    assert 0.99 * exact < areas.sum() < exact  # chords inside the arc
    centre = back.points[quads].mean(axis=1)
    inward = -np.stack([centre[:, 0], np.zeros(len(centre)), centre[:, 2]], axis=1)
    assert np.all(np.einsum("nc,nc->n", normals, inward) > 0.0)  # a3 points toward the axis
    n = back.point_data["normal"]
    np.testing.assert_allclose(n[:, [0, 2]], -back.points[:, [0, 2]] / R, atol=1e-12)
    assert set(back.cell_data["element"][0]) == set(range(6))


def test_export_writes_a_frame_per_state_with_displacements(tmp_path):
    m = _roof()
    q0 = m.q0
    moved = q0.reshape(-1, 4, 3).copy()
    moved[:, 0] += [0.0, 0.0, -0.3]
    pvd = export_shell_vtk(m, [0.0, 1.0], [q0, moved.ravel()], tmp_path / "vtk", "roof", k=3)
    assert pvd.name == "roof.pvd" and 'timestep="1.0"' in pvd.read_text()
    last = meshio.read(tmp_path / "vtk" / "roof_00001.vtu")
    np.testing.assert_allclose(last.point_data["displacement"], [[0.0, 0.0, -0.3]] * 54, atol=1e-12)
    first = meshio.read(tmp_path / "vtk" / "roof_00000.vtu")
    np.testing.assert_allclose(last.points - first.points, last.point_data["displacement"])


def test_too_few_samples_are_refused(tmp_path):
    with pytest.raises(InputError, match="--samples"):
        surface_grid(_roof(), k=1)
