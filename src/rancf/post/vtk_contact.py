"""ParaView output of contact: ``contact_NNNNN.vtu`` per stored time and
``contact.pvd``, one ``vertex`` per obstacle at its point (a plane's point, a cylinder's or
sphere's centre; moving with the rigid body that carries it) with point data ``normal_force``
and ``friction_force`` (3 components: the force the obstacle exerts on the bodies [N]),
``contact_force`` (their sum), ``contact_length`` [m] and ``penetration`` [m] — the obstacle's
columns of ``reactions`` (:mod:`rancf.system.outputs`).  ParaView's Glyph filter draws the
forces as arrows.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet
from rancf.post.results import load_results
from rancf.post.run_data import frame_indices

__all__ = ["export_contact_vtk"]

Frame = Callable[[dict[str, Any], int], tuple[NDArray, NDArray]]


def export_contact_vtk(
    run_dir: str | Path, out_dir: str | Path, every: int = 1, frame: Frame | None = None
) -> Path | None:
    """Write the contact files (module docstring) of the run in ``run_dir`` into ``out_dir``;
    None if the run has no obstacles.  ``frame(body, i)``: a carrying body's centre ``(3,)``
    and axes ``(3, 3)`` at stored state ``i`` (:meth:`rancf.post.system_run.SystemRun.
    rigid_frame`)."""
    import meshio

    from rancf.post.vtk import _export

    data = load_results(Path(run_dir) / "results.npz")
    meta = data["metadata"]
    obstacles = meta.get("obstacles") or []
    if not obstacles:
        return None
    t = np.asarray(data["t"])
    reactions = np.asarray(data["reactions"]).reshape(t.size, -1)
    columns = list(meta["reaction_columns"])
    dim = 3 if any(c.endswith("_z") for c in columns) else 2
    bodies = {b["name"]: b for b in meta.get("bodies", [])}

    def cols(name: str, part: str) -> list[int]:
        if part in ("length", "penetration"):
            return [columns.index(f"{name}_{part}")]
        return [columns.index(f"{name}_{part}_{a}") for a in "xyz"[:dim]]

    index = {
        ob["name"]: {
            p: cols(ob["name"], p) for p in ("normal", "friction", "length", "penetration")
        }
        for ob in obstacles
    }

    def mesh_at(i: int) -> Any:
        pts: list[NDArray] = []
        data_: dict[str, list] = {"normal_force": [], "friction_force": []}
        scalars: dict[str, list] = {"contact_length": [], "penetration": []}
        for ob in obstacles:
            p = np.asarray(ob["point"], float)
            if ob["body"] is not None and frame is not None:
                x, axes = frame(bodies[ob["body"]], i)
                p = x + p @ axes
            pts.append(p)
            row = reactions[i]
            for key, part in (("normal_force", "normal"), ("friction_force", "friction")):
                f = np.zeros(3)
                f[:dim] = row[index[ob["name"]][part]]
                data_[key].append(f)
            scalars["contact_length"].append(row[index[ob["name"]]["length"][0]])
            scalars["penetration"].append(row[index[ob["name"]]["penetration"][0]])
        point_data = {k: np.array(v) for k, v in data_.items()}
        point_data["contact_force"] = point_data["normal_force"] + point_data["friction_force"]
        point_data.update({k: np.array(v) for k, v in scalars.items()})
        n = len(pts)
        cells = [("vertex", np.arange(n)[:, None])]
        return meshio.Mesh(np.array(pts), cells, point_data=point_data)

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with FileSet() as files:
        return _export(t, out, frame_indices(t.size, every), [("contact", mesh_at)], files)
