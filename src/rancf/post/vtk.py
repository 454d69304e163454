"""ParaView output: one VTK unstructured grid (``.vtu``, written by meshio) per stored time and a
``.pvd`` collection that lists them with their times.

Each ``.vtu`` holds the densely sampled centreline (:func:`rancf.post.centerline.sample_centerline`)
as a polyline of ``line`` cells with point data ``displacement``, ``velocity`` (3 components; zero
``z`` for planar runs), ``axial_strain``, ``curvature``, ``radius`` (for ParaView's Tube filter,
"Vary Radius: By Scalar" or a constant radius), ``element`` and the section quantities of the run
(:mod:`rancf.bodies.section_outputs`: ``axial_force``, ``bending_moment``, ...; stored at
``ξ = 0, 1/4, 1/2, 3/4, 1`` of every element, interpolated linearly in ``ξ`` within the element;
their names prefixed ``section_``, so the stored ``section_strain`` and ``section_curvature``
stand beside the sampled ``axial_strain`` and ``curvature``).

Rod runs also get ``<run>_nodes.pvd`` with one ``.vtu`` per stored time holding the nodes as
``vertex`` cells with point data ``twist`` (the nodal ``φ``), ``tangent`` and the material frame
``m1``, ``m2`` (ParaView's Glyph filter draws them as arrows), ``displacement`` and ``velocity``:
the frames are those the run carried along its path (:func:`rancf.post.centerline.nodal_frames`).
The files of one export are written under temporary names and renamed into place together once
all are written (:class:`rancf.atomic.FileSet`): a failing or interrupted export (a full disk,
Ctrl-C) leaves the folder as it was, never ``.vtu`` files without their ``.pvd``.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet
from rancf.errors import InputError
from rancf.geometry.conic_params import pad3
from rancf.post.centerline import nodal_frames, sample_centerline
from rancf.post.run_data import RunData, frame_indices
from rancf.post.vtk_frames import MAX_POINTS, MAX_POINTS_PER_FRAME
from rancf.post.vtk_frames import export_frames as _export

__all__ = ["export_vtk", "centerline_mesh", "nodes_mesh", "check_export_size"]


def check_export_size(run: RunData, every: int, per_element: int) -> None:
    """Refuse, before anything is written, an export of more than :data:`MAX_POINTS_PER_FRAME`
    points a frame (``--samples``) or :data:`MAX_POINTS` in all (``--every``)."""
    n_el = run.weights.shape[0]
    n_frames = frame_indices(run.t.size, every).size
    if isinstance(per_element, bool) or not isinstance(per_element, int) or per_element < 1:
        raise InputError("--samples", per_element, "an integer >= 1")
    if per_element * n_el > MAX_POINTS_PER_FRAME:
        most = max(1, MAX_POINTS_PER_FRAME // n_el)
        raise InputError(
            "--samples",
            per_element,
            f"at most {most} points per element for this run of {n_el} elements "
            f"({MAX_POINTS_PER_FRAME:.0e} points a frame)",
        )
    total = per_element * n_el * n_frames
    if total > MAX_POINTS:
        raise InputError(
            "--every",
            every,
            f"fewer frames: {n_frames} frames of {per_element * n_el} points would be "
            f"{total:.3g} points, more than {MAX_POINTS:.0e} (about 2 GB); raise --every or "
            "lower --samples",
        )


def centerline_mesh(run: RunData, i: int, per_element: int = 16):  # -> meshio.Mesh
    """The meshio mesh of stored state ``i`` (see the module docstring for its fields)."""
    import meshio

    c = sample_centerline(run, i, per_element)
    n = c.points.shape[0]
    cells = np.stack([np.arange(n - 1), np.arange(1, n)], axis=1)
    data = {
        "displacement": pad3(c.displacement),
        "velocity": pad3(c.velocity),
        "axial_strain": c.axial_strain,
        "curvature": c.curvature,
        "element": c.element.astype(np.int32),
    }
    if run.radius is not None:
        data["radius"] = np.full(n, run.radius)
    if run.along is not None:
        data.update(_section_fields(run, run.along[i], per_element))
    return meshio.Mesh(pad3(c.points), [("line", cells)], point_data=data)


def _section_fields(run: RunData, stored: NDArray, per_element: int) -> dict[str, np.ndarray]:
    """The section quantities ``stored`` at a state (``run.along[i]``) at the centreline samples
    (module docstring)."""
    along = np.asarray(stored)  # (4 n_el + 1, n_names)
    n_el = (along.shape[0] - 1) // 4
    idx = np.arange(n_el)[:, None] * 4 + np.arange(5)[None, :]  # element e: rows 4e .. 4e + 4
    xi = np.linspace(0.0, 1.0, per_element + 1)
    w = np.clip(xi * 4.0, 0.0, 4.0)
    lo = np.minimum(np.floor(w).astype(int), 3)
    frac = w - lo
    vals = (
        along[idx[:, lo]] * (1.0 - frac)[None, :, None]
        + along[idx[:, lo + 1]] * frac[None, :, None]
    )  # (n_el, per_element + 1, n_names)
    pts = np.concatenate([vals[:, :-1].reshape(-1, vals.shape[-1]), vals[-1, -1:]])
    return {f"section_{name}": pts[:, k] for k, name in enumerate(run.section_names)}


def nodes_mesh(run: RunData, i: int):  # -> meshio.Mesh
    """The meshio mesh of a rod's nodes and material frames at stored state ``i``."""
    import meshio

    f = nodal_frames(run, i)
    n = f.points.shape[0]
    data = {
        "twist": f.twist,
        "tangent": f.tangent,
        "m1": f.m1,
        "m2": f.m2,
        "displacement": f.displacement,
        "velocity": f.velocity,
    }
    return meshio.Mesh(f.points, [("vertex", np.arange(n)[:, None])], point_data=data)


def export_vtk(run: RunData, out_dir: str | Path, every: int = 1, per_element: int = 16) -> Path:
    """Write ``OUT_DIR/<run>_NNNNN.vtu`` for every ``every``-th stored time and ``<run>.pvd``
    (rods: also ``<run>_nodes_NNNNN.vtu`` and ``<run>_nodes.pvd``).

    Returns the path of the centreline's ``.pvd`` file.
    """
    check_export_size(run, every, per_element)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise InputError("--vtk", str(out), "a directory (it exists and is a file)")
    out.mkdir(parents=True, exist_ok=True)
    idx = frame_indices(run.t.size, every)
    parts: list[tuple[str, Callable[[int], Any]]]
    parts = [(run.name, lambda i: centerline_mesh(run, i, per_element))]
    if run.family.has_triads and run.directors is not None:
        parts.append((f"{run.name}_nodes", lambda i: nodes_mesh(run, i)))
    with FileSet() as files:
        return _export(run.t, out, idx, parts, files)
