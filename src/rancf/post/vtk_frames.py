"""The ParaView files of a run's frames: one ``.vtu`` per stored state and part, and each
part's ``.pvd`` collection (:mod:`rancf.post.vtk` for lines, :mod:`rancf.post.vtk_shell` for
shells, :mod:`rancf.post.vtk_contact`), and the export's size limits.  It imports nothing of
the run readers, so a run's writer may use it (a shell's surfaces are written with its run)."""

from __future__ import annotations

import html
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet

__all__ = ["MAX_POINTS", "MAX_POINTS_PER_FRAME", "export_frames"]

#: Most centreline points of one frame (``--samples`` per element times the elements).
MAX_POINTS_PER_FRAME = 10**6
#: Most centreline points of one export (all frames): about 2 GB of ``.vtu`` files.
MAX_POINTS = 2 * 10**7


def export_frames(
    times: NDArray[np.float64],
    out: Path,
    idx: NDArray[np.int64],
    parts: list[tuple[str, Callable[[int], Any]]],
    files: FileSet,
) -> Path:
    """Every frame ``idx`` (of the stored ``times``) of every part, then each part's ``.pvd``,
    into the set ``files``."""
    import meshio

    paths = []
    for name, mesh_at in parts:
        entries = []
        for k, i in enumerate(idx):
            fname = f"{name}_{k:05d}.vtu"
            with files.path(out / fname) as tmp:
                meshio.write(tmp, mesh_at(int(i)), file_format="vtu")
            entries.append(
                f'    <DataSet timestep="{float(times[i])!r}" group="" part="0" '
                f'file="{html.escape(fname, quote=True)}"/>'
            )
        pvd = "\n".join(
            [
                '<?xml version="1.0"?>',
                '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
                "  <Collection>",
                *entries,
                "  </Collection>",
                "</VTKFile>",
                "",
            ]
        )
        paths.append(out / f"{name}.pvd")
        files.write(paths[-1], pvd)
    return paths[0]
