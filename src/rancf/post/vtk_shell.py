"""ParaView output of shells: each element evaluated on a ``k × k`` grid of its parameters as
``quad`` cells, one ``.vtu`` per stored state and a ``.pvd`` collection (as for lines,
:mod:`rancf.post.vtk`).

Each ``.vtu`` holds the points ``r(ξ, η)`` of every element (eq. 3.2 of
docs/derivations/shell.md, :meth:`rancf.mesh.surfaces.SurfaceMesh.evaluate`; points on shared
element edges are repeated, one grid per element), point data ``displacement`` (from the
reference at the same parameters) and ``normal`` (the unit normal ``a3`` of the deformed surface,
eq. 4.2), and cell data ``element`` (``j nu + i``).  Quads run counter-clockwise in ``(ξ, η)``,
so their normals agree with ``a3``.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.atomic import FileSet
from rancf.errors import InputError
from rancf.mesh.surfaces import SurfaceMesh
from rancf.post.vtk_frames import MAX_POINTS, MAX_POINTS_PER_FRAME
from rancf.post.vtk_frames import export_frames as _export

__all__ = ["surface_grid", "export_shell_vtk"]


def _check(mesh: SurfaceMesh, k: int, frames: int) -> None:
    if isinstance(k, bool) or not isinstance(k, int) or k < 2:
        raise InputError("--samples", k, "an integer >= 2 (points per element side)")
    n = mesh.u.n * mesh.v.n * k * k
    if n > MAX_POINTS_PER_FRAME or n * frames > MAX_POINTS:
        raise InputError(
            "--samples",
            k,
            f"fewer points: {n} a frame and {n * frames} in all are more than "
            f"{MAX_POINTS_PER_FRAME:.0e} and {MAX_POINTS:.0e}",
        )


def _quads(n_el: int, k: int) -> NDArray[np.int64]:
    """Quad cells ``(n_el (k-1)², 4)`` of ``n_el`` grids of ``k × k`` points (``p k + q``)."""
    p, q = np.meshgrid(np.arange(k - 1), np.arange(k - 1), indexing="ij")
    a = (p * k + q).ravel()
    one = np.stack([a, a + k, a + k + 1, a + 1], axis=1)
    return (np.arange(n_el)[:, None, None] * k * k + one[None]).reshape(-1, 4)


def surface_grid(mesh: SurfaceMesh, q: ArrayLike | None = None, k: int = 5):  # -> meshio.Mesh
    """The meshio mesh of the shell in configuration ``q`` (default the reference), each
    element on a ``k × k`` grid (module docstring)."""
    import meshio

    _check(mesh, k, 1)
    x = np.linspace(0.0, 1.0, k)
    pts = mesh.evaluate(x, x, q)
    ref = mesh.evaluate(x, x)
    a3 = np.cross(mesh.evaluate(x, x, q, (1, 0)), mesh.evaluate(x, x, q, (0, 1)))
    a3 /= np.linalg.norm(a3, axis=-1, keepdims=True)
    n_el = mesh.u.n * mesh.v.n
    data = {"displacement": (pts - ref).reshape(-1, 3), "normal": a3.reshape(-1, 3)}
    element = np.repeat(np.arange(n_el, dtype=np.int32), (k - 1) ** 2)
    return meshio.Mesh(
        pts.reshape(-1, 3),
        [("quad", _quads(n_el, k))],
        point_data=data,
        cell_data={"element": [element]},
    )


def export_shell_vtk(
    mesh: SurfaceMesh,
    times: ArrayLike,
    states: Sequence[ArrayLike] | NDArray,
    out_dir: str | Path,
    name: str = "shell",
    k: int = 5,
) -> Path:
    """Write ``OUT_DIR/<name>_NNNNN.vtu`` for every state (one per time) and ``<name>.pvd``;
    returns the ``.pvd`` path.  All files are renamed into place together (as for lines)."""
    t = np.atleast_1d(np.asarray(times, dtype=float))
    if len(states) != t.size:
        raise InputError("states", len(states), f"one state per time ({t.size})")
    _check(mesh, k, t.size)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise InputError("--vtk", str(out), "a directory (it exists and is a file)")
    out.mkdir(parents=True, exist_ok=True)

    def frame(i: int) -> Any:
        return surface_grid(mesh, states[i], k)

    with FileSet() as files:
        return _export(t, out, np.arange(t.size), [(name, frame)], files)
