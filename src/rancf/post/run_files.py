"""The history files of a run folder, from stored rows and their derived values.

One writer for every run (a system of one body is a one-body run):

* ``sensors.csv`` (``t`` then one column per sensor scalar), ``energy.csv`` (``t, kinetic,
  strain, gravity, total`` [J]) and ``reactions.csv`` (supports, then joints; see
  :mod:`rancf.system.outputs`);
* ``results.npz``: ``t``, the states ``q``, ``v``, the consistent accelerations ``a``, the
  energies, ``sensors``, ``reactions``, the multipliers ``lam`` (``(n_t, 0)`` without
  constraints), the ``reference`` and JSON ``metadata``: ``dim``, ``sensor_columns``,
  ``reaction_columns``, ``obstacles`` (a list, empty without contact) and ``"bodies"``, every
  body (name, kind, its columns ``offset`` and ``size`` in ``q``; a flexible body's
  ``element`` and ``folder``; a rigid body's ``mass`` and ``points``) and ``"drums"``, the
  coordinates after the bodies' (a driven drum's length outside it: name, ``offset``, ``size``);
* every flexible body's ``bodies/NAME/results.npz``: its coordinates, accelerations,
  energies, support reactions, section values (``along`` and ``along_s``), rods' ``directors``,
  the mesh's ``weights`` and ``scales`` and the metadata readers need
  (:mod:`rancf.post.run_data`), and ``bodies/NAME/envelope.csv``: the extremes of its section
  values over the run (:mod:`rancf.post.envelope`), gathered while ``along`` is written.

The layout is the same for every run: a run of a one-body file is a system of one body
(``bodies/body``), read by :func:`rancf.post.system_run.load_run`.

Histories are written in chunks of rows (:data:`CHUNK_BYTES`), so a long run's files are built
without holding them in memory; the files go into a :class:`~rancf.atomic.FileSet` and replace
the old ones together.
"""

from __future__ import annotations

import json
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet
from rancf.bodies.flexible import Model
from rancf.bodies.rigid import PointMass
from rancf.post.csv_rows import write_rows
from rancf.post.envelope import Envelope
from rancf.system.outputs import SystemOutputs

__all__ = ["write_history_files", "reader_metadata", "CHUNK_BYTES", "DERIVED"]

#: Bytes of a history handled at once when writing files.
CHUNK_BYTES = 1 << 24

#: The derived streams of :meth:`SystemOutputs.rows` the files hold.
DERIVED = ("a", "lam", "r", "s", "c", "eb")


def reader_metadata(model: Model) -> dict[str, Any]:
    """What readers of a body's results need besides the states: ``section_radius``
    (``sqrt(A / π)``) and, for beams, the reference nodal ``tangent_angles`` [rad]."""
    meta: dict[str, Any] = {"section_radius": model.section.radius}
    if not model.family.gradient:
        t = model.mesh.nodes[:, 1]
        meta["tangent_angles"] = np.arctan2(t[:, 1], t[:, 0]).tolist()
    return meta


def _rows(n: int, width: int) -> Iterator[slice]:
    step = max(1, CHUNK_BYTES // (8 * max(width, 1)))
    for i in range(0, n, step):
        yield slice(i, min(n, i + step))


def _npy(zf: zipfile.ZipFile, name: str, shape: tuple[int, ...], chunks: Any) -> None:
    with zf.open(f"{name}.npy", "w", force_zip64=True) as f:
        header = {"descr": "<f8", "fortran_order": False, "shape": shape}
        np.lib.format.write_array_header_2_0(f, header)
        for c in chunks:
            f.write(np.ascontiguousarray(c, dtype="<f8").reshape(-1).data.cast("B"))


def _small(zf: zipfile.ZipFile, arrays: dict[str, Any]) -> None:
    for name, arr in arrays.items():
        with zf.open(f"{name}.npy", "w") as f:
            np.lib.format.write_array(f, np.asarray(arr), allow_pickle=False)


def _body_meta(model: Model, out: SystemOutputs, name: str) -> dict[str, Any]:
    return {
        "element": model.element,
        "dim": model.dim,
        "dofs_per_node": model.dpn,
        "n_nodes": model.n_nodes,
        "n_elements": model.n_el,
        "section_names": list(out.section_names[name]),
        **reader_metadata(model),
    }


def write_history_files(
    out_dir: Path,
    outputs: SystemOutputs,
    t: NDArray,
    q: NDArray,
    v: NDArray,
    energy: NDArray,
    directors: NDArray | None = None,
    derived: dict[str, NDArray] | None = None,
    static: bool = False,
    files: FileSet | None = None,
    lam: NDArray | None = None,
    alpha: NDArray | None = None,
) -> list[str]:
    """Write the history files of rows ``t (n,)``, ``q, v (n, n_q)``, ``energy (n, 3)`` and rods'
    ``directors (n, n_directors)`` (module docstring); any may be memory maps.

    ``derived``: the rows' :meth:`SystemOutputs.rows` arrays (keys :data:`DERIVED`), else they
    are computed chunk by chunk (``static``: rows of a load path, ``t`` its parameter, ``lam``
    the solver's multipliers; ``alpha``: the steps' generalized-α points of a dynamic run with
    contact, :class:`~rancf.solvers.dynamic.DynamicResult`).  Into the set ``files``
    (committed by the caller), else atomically on their own.  Returns the sensor column names.
    """
    if files is None:
        with FileSet() as own:
            return write_history_files(
                out_dir, outputs, t, q, v, energy, directors, derived, static, own, lam, alpha
            )
    s = outputs.system
    n = t.shape[0]
    m1 = None if directors is None else np.asarray(directors).reshape(n, -1)

    def chunk(r: slice) -> dict[str, NDArray]:
        if derived is not None:
            return {k: derived[k][r] for k in DERIVED if k in derived}
        mm, ll, aa = (None if x is None else x[r] for x in (m1, lam, alpha))
        return outputs.rows(t[r], q[r], v[r], mm, energy[r], ll, static, per_body=True, alpha=aa)

    chunks = [(r, chunk(r)) for r in _rows(n, 3 * q.shape[1] + outputs.n_along)]
    names = outputs.sensor_names
    with files.file(out_dir / "sensors.csv") as fh:
        fh.write((",".join(["t", *names]) + "\n").encode())
        for r, c in chunks:
            write_rows(fh, np.column_stack([t[r], c["c"]]))
    with files.file(out_dir / "energy.csv") as fh:
        fh.write(b"t,kinetic,strain,gravity,total\n")
        for r in _rows(n, 5):
            e = energy[r]
            write_rows(fh, np.column_stack([t[r], e, e.sum(axis=1)]))
    if outputs.reaction_names:
        with files.file(out_dir / "reactions.csv") as fh:
            fh.write((",".join(["t", *outputs.reaction_names]) + "\n").encode())
            for r, c in chunks:
                write_rows(fh, np.column_stack([t[r], c["r"]]))
    meta: dict[str, Any] = {
        "system": True,
        "dim": s.dim,
        "bodies": _bodies(outputs),
        "drums": _drums(outputs),
        "sensor_columns": names,
        "reaction_columns": outputs.reaction_names,
        "obstacles": _obstacles(s),
    }
    with (
        files.file(out_dir / "results.npz") as fh,
        zipfile.ZipFile(fh, "w", zipfile.ZIP_STORED, allowZip64=True) as z,
    ):
        _npy(z, "t", (n,), (t[r] for r, _ in chunks))
        _npy(z, "q", q.shape, (q[r] for r, _ in chunks))
        _npy(z, "v", v.shape, (v[r] for r, _ in chunks))
        _npy(z, "a", q.shape, (c["a"] for _, c in chunks))
        _npy(z, "lam", (n, s.m), (c["lam"] for _, c in chunks))
        for j, key in enumerate(("kinetic", "strain", "gravity")):
            _npy(z, key, (n,), (energy[r, j] for r, _ in chunks))
        _npy(z, "sensors", (n, len(names)), (c["c"] for _, c in chunks))
        _npy(z, "reactions", (n, len(outputs.reaction_names)), (c["r"] for _, c in chunks))
        _small(z, {"reference": s.q_from_y(s.y0), "metadata": np.array(json.dumps(meta))})
    for name, model in outputs.flex:
        k = s.names.index(name)  # its energies' place among the flexible bodies
        _body_folder(out_dir, outputs, name, model, k, t, q, v, m1, chunks, files)
    for name, model in outputs.shells:
        _shell_folder(out_dir, name, model, t, q[:, s.body_slice(name)], files)
    return names


#: Points per element side of a shell's surfaces in its run folder (:mod:`rancf.post.vtk_shell`).
SHELL_SAMPLES = 5


def _shell_folder(
    out_dir: Path, name: str, model: Any, t: NDArray, q: NDArray, files: FileSet
) -> None:
    """``bodies/NAME/NAME.pvd`` and its ``.vtu`` frames: the shell's surfaces at every stored
    state (:func:`rancf.post.vtk_shell.surface_grid`, ``q`` its full coordinates), for
    ParaView."""
    from rancf.post.vtk_frames import export_frames
    from rancf.post.vtk_shell import surface_grid

    folder = out_dir / "bodies" / name
    folder.mkdir(parents=True, exist_ok=True)

    def frame(i: int) -> Any:
        return surface_grid(model.body.mesh, model.to_body(q[i]), SHELL_SAMPLES)

    export_frames(np.asarray(t), folder, np.arange(t.shape[0]), [(name, frame)], files)


def _bodies(outputs: SystemOutputs) -> list[dict[str, Any]]:
    s = outputs.system
    rows = []
    for name in s.names:
        b, sl = s.bodies[name], s.body_slice(name)
        row: dict[str, Any] = {"name": name, "offset": sl.start, "size": sl.stop - sl.start}
        if isinstance(b, Model) and b.family.surface:  # its surfaces in its folder
            row.update({"kind": "shell", "element": b.element, "folder": f"bodies/{name}"})
        elif isinstance(b, Model):
            row.update({"kind": "flexible", "element": b.element, "folder": f"bodies/{name}"})
        else:
            row["kind"] = "mass" if isinstance(b, PointMass) else "rigid"
            row["mass"] = b.mass
            if not isinstance(b, PointMass):
                row["points"] = {k: list(map(float, p)) for k, p in b.points.items()}
        rows.append(row)
    return rows


def _obstacles(s: Any) -> list[dict[str, Any]]:
    """Every obstacle as plain data (:func:`rancf.system.contact.obstacle_records`; a system
    without obstacles loads no contact module)."""
    if not getattr(s, "obstacles", ()):
        return []
    from rancf.system.contact import obstacle_records

    return obstacle_records(s)


def _drums(outputs: SystemOutputs) -> list[dict[str, Any]]:
    """The driven drums' coordinates after the bodies' (:mod:`rancf.system.drums`): each
    drum's unstretched length outside it [m], its column ``offset`` in ``q`` (size 1)."""
    return [{"name": k, "offset": int(i), "size": 1} for k, i in outputs.system.drums.items()]


def _director_cut(outputs: SystemOutputs, name: str) -> slice:
    start = 0
    for n, b in outputs.flex:
        if not b.family.has_triads:
            continue
        if n == name:
            return slice(start, start + 3 * b.n_nodes)
        start += 3 * b.n_nodes
    return slice(0, 0)


def _body_arrays(
    z: zipfile.ZipFile,
    outputs: SystemOutputs,
    name: str,
    t: NDArray,
    chunks: list,
    m1: NDArray | None,
    envelope: Envelope,
) -> None:
    """The arrays of one flexible body a reader needs besides its states; the section values
    pass through ``envelope``."""
    n = t.shape[0]
    model = outputs.system.bodies[name]
    assert isinstance(model, Model)
    along_shape = (n, outputs.samplers[name].n_points, len(outputs.section_names[name]))
    _npy(
        z,
        "along",
        along_shape,
        (envelope.update(t[r], outputs.body_along(c["s"], name)) for r, c in chunks),
    )
    if model.family.has_triads and m1 is not None:
        cut = _director_cut(outputs, name)
        _npy(z, "directors", (n, model.n_nodes, 3), (m1[r, cut] for r, _ in chunks))
    _small(
        z,
        {
            "weights": model.mesh.weights,
            "scales": model.mesh.scales,
            "along_s": outputs.samplers[name].s,
        },
    )


def _body_folder(
    out_dir: Path,
    outputs: SystemOutputs,
    name: str,
    model: Model,
    k: int,
    t: NDArray,
    q: NDArray,
    v: NDArray,
    m1: NDArray | None,
    chunks: list,
    files: FileSet,
) -> None:
    """``bodies/NAME/results.npz`` of the ``k``-th flexible body: a one-body run's file."""
    folder = out_dir / "bodies" / name
    folder.mkdir(parents=True, exist_ok=True)
    sl = outputs.system.body_slice(name)
    n = t.shape[0]
    rcols = _support_columns(outputs, name)
    meta = {
        **_body_meta(model, outputs, name),
        "sensor_columns": [],
        "reaction_columns": outputs.support_names[name],
        "body": name,
    }
    with (
        files.file(folder / "results.npz") as fh,
        zipfile.ZipFile(fh, "w", zipfile.ZIP_STORED, allowZip64=True) as z,
    ):
        _npy(z, "t", (n,), (t[r] for r, _ in chunks))
        _npy(z, "q", (n, model.n), (q[r, sl] for r, _ in chunks))
        _npy(z, "v", (n, model.n), (v[r, sl] for r, _ in chunks))
        _npy(z, "a", (n, model.n), (c["a"][:, sl] for _, c in chunks))
        for j, key in enumerate(("kinetic", "strain", "gravity")):
            _npy(z, key, (n,), (c["eb"][:, 3 * k + j] for _, c in chunks))
        _npy(z, "sensors", (n, 0), (np.empty((r.stop - r.start, 0)) for r, _ in chunks))
        _npy(z, "reactions", (n, rcols.stop - rcols.start), (c["r"][:, rcols] for _, c in chunks))
        envelope = Envelope(outputs.samplers[name].s, outputs.section_names[name])
        _body_arrays(z, outputs, name, t, chunks, m1, envelope)
        _small(z, {"reference": model.q0, "metadata": np.array(json.dumps(meta))})
    with files.file(folder / "envelope.csv") as fh:
        envelope.write(fh)


def _support_columns(outputs: SystemOutputs, name: str) -> slice:
    start = 0
    for n, cols in outputs.support_names.items():
        if n == name:
            return slice(start, start + len(cols))
        start += len(cols)
    raise KeyError(name)
