"""A finished run read back, drawn and exported: the one reader of run folders.

Every run folder (:mod:`rancf.post.run_files`) is a system's: ``results.npz`` holds the
system's history (metadata ``"bodies"``: every body's name, kind and columns in ``q``) and every
flexible body has its folder ``bodies/NAME`` (:func:`rancf.post.run_data.load_body`); a run of
a one-body file is a system of one body, ``body``.  A run written by rancf < 0.3 (one body's
arrays in the run folder itself) is read as that system of one body.

Drawing: a flexible body is its exact element curve (:func:`rancf.post.run_data.
sample_centerline`); a rigid body the polyline from its centre of mass through its named points
(and back), placed by its coordinates ``x + R p`` (2D: ``R(θ)``; 3D: the rotation of its unit
quaternion ``(p0, p1, p2, p3)``, scalar first); a point mass a dot.  The VTK export writes every
flexible body's files (:func:`rancf.post.vtk.export_vtk`) into ``OUT/NAME/`` and the rigid
bodies and point masses as points with their frames (point data ``e1``, ``e2``, ``e3``: the body
axes) into ``OUT/rigid_NNNNN.vtu`` and ``OUT/rigid.pvd``.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet, atomic_path
from rancf.errors import InputError
from rancf.post.centerline import sample_centerline
from rancf.post.plots import pyplot, save_figure
from rancf.post.run_data import RunData, frame_indices, load_body, read_results

__all__ = ["SystemRun", "load_run", "plot_system_run", "export_system_vtk", "animate_system_run"]


@dataclass(frozen=True)
class SystemRun:
    """A run: times, states, sensors, energies, the bodies' metadata and every flexible body's
    :class:`RunData`."""

    path: Path
    t: NDArray[np.float64]
    q: NDArray[np.float64]
    dim: int
    sensor_names: list[str]
    sensors: NDArray[np.float64]
    energies: dict[str, NDArray[np.float64]]
    bodies: list[dict[str, Any]]
    flexible: dict[str, RunData]
    static: bool = False

    @property
    def name(self) -> str:
        """The folder's name (bytes that are not UTF-8 shown as U+FFFD, so the name can go into
        file names, XML and figure titles)."""
        return os.fsencode(self.path.resolve().name).decode("utf-8", "replace")

    @property
    def time_label(self) -> str:
        """Axis label of ``t``: the time, or the load factor of a static load path."""
        return "load factor λ [-]" if self.static else "t [s]"

    def time_text(self, value: float, fmt: str = ".4g") -> str:
        """``t = 0.5 s``, or ``λ = 0.5`` for a static load path."""
        return f"λ = {value:{fmt}}" if self.static else f"t = {value:{fmt}} s"

    def time_index(self, time: float | None) -> int:
        """Index of the stored time closest to ``time`` (None: the last stored time)."""
        if time is None:
            return self.t.size - 1
        if not (np.isfinite(time) and self.t[0] - 1e-12 <= time <= self.t[-1] + 1e-12):
            unit = "" if self.static else " s"
            raise InputError(
                "--time",
                time,
                f"a time within the stored range [{self.t[0]:g}, {self.t[-1]:g}]{unit}",
            )
        return int(np.argmin(np.abs(self.t - time)))

    def body(self, name: str | None = None) -> RunData:
        """The flexible body ``name``'s history (None: the run's only flexible body)."""
        names = list(self.flexible)
        if name is None and len(names) == 1:
            return self.flexible[names[0]]
        if name not in self.flexible:
            key = "--body" if name is not None else "RUN_DIR"
            value = name if name is not None else str(self.path)
            allowed = f"a flexible body of the run: {', '.join(names) or 'none'}"
            raise InputError(key, value, allowed)
        return self.flexible[name]

    def rigid_frame(self, body: dict[str, Any], i: int) -> tuple[NDArray, NDArray]:
        """Centre ``(3,)`` and axes ``(3, 3)`` (rows ``e1, e2, e3``) of a rigid body or point
        mass at stored state ``i``."""
        row = self.q[i, body["offset"] : body["offset"] + body["size"]]
        x = np.r_[row[: self.dim], np.zeros(3 - self.dim)]
        if body["kind"] == "mass":
            return x, np.eye(3)
        if self.dim == 2:
            c, s = np.cos(row[2]), np.sin(row[2])
            return x, np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
        from scipy.spatial.transform import Rotation

        rot = Rotation.from_quat(row[3:7][[1, 2, 3, 0]]).as_matrix()
        return x, rot.T

    def shapes(
        self, i: int, magnify: float = 1.0, per_element: int = 16
    ) -> list[tuple[str, NDArray[np.float64]]]:
        """Every body's drawing ``(name, points (k, 3))`` at stored state ``i`` (module
        docstring; a flexible body sampled ``per_element`` times per element); ``magnify``
        scales the flexible bodies' displacements from their reference (rigid bodies are drawn
        as they are)."""
        out = []
        for b in self.bodies:
            if b["kind"] == "shell":  # drawn by its surfaces (bodies/NAME/NAME.pvd)
                continue
            if b["kind"] == "flexible":
                run = self.flexible[b["name"]]
                pts = _pad(sample_centerline(run, i, per_element).points)
                if magnify != 1.0:
                    ref = replace(run, q=run.reference[None], v=np.zeros_like(run.reference)[None])
                    base = _pad(sample_centerline(ref, 0, per_element).points)
                    pts = base + magnify * (pts - base)
                out.append((b["name"], pts))
                continue
            x, axes = self.rigid_frame(b, i)
            star = [x]  # the centre, then out to each named point and back
            for p in b.get("points", {}).values():
                local = np.r_[np.asarray(p, float), np.zeros(3 - len(p))]
                star += [x + local @ axes, x]
            out.append((b["name"], np.array(star)))
        return out


def _pad(a: NDArray) -> NDArray:
    return a if a.shape[-1] == 3 else np.concatenate([a, np.zeros(a.shape[:-1] + (1,))], axis=-1)


def _analysis(path: Path) -> str | None:
    try:
        doc = json.loads((path / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return doc.get("analysis") if isinstance(doc, dict) else None


def load_run(path: str | Path) -> SystemRun:
    """Read a run folder (``results.npz`` and every ``bodies/NAME``; module docstring).

    Raises
    ------
    InputError
        If ``path`` is not a run folder with readable, consistent results, naming the folder
        or file and what is wrong.
    """
    p = Path(path)
    data = read_results(p)
    meta = data["metadata"]
    static = _analysis(p) == "static"
    if "bodies" not in meta:  # rancf < 0.3: one body, its arrays here
        body = load_body(p, static)
        meta = {
            **meta,
            "bodies": [{"name": "body", "kind": "flexible", "offset": 0, "size": body.q.shape[1]}],
        }
        flexible = {"body": body}
    else:
        flexible = {
            b["name"]: load_body(p / b["folder"], static)
            for b in meta["bodies"]
            if b["kind"] == "flexible"
        }
    t = np.asarray(data["t"])
    names = meta.get("sensor_columns")
    q = np.asarray(data.get("q", np.empty((0, 0))))
    width = sum(b["size"] for b in [*meta["bodies"], *meta.get("drums", [])])
    if q.ndim != 2 or q.shape != (t.size, width) or not isinstance(names, list):
        raise InputError(
            "RUN_DIR",
            str(p / "results.npz"),
            "a consistent results.npz (its states, times and sensor columns do not fit together)",
        )
    sizes = {b["name"]: b["size"] for b in meta["bodies"]}
    for name, r in flexible.items():  # the run's folders are of one run (not mixed)
        if r.t.shape != t.shape or not np.array_equal(r.t, t) or r.q.shape[1] != sizes[name]:
            raise InputError(
                "RUN_DIR",
                str(p / "bodies" / name),
                f"a body folder of the run in {p} (it holds "
                f"{r.t.size} times of {r.q.shape[1]} coordinates, the run's results.npz "
                f"{t.size} times and {sizes[name]} coordinates for it)",
            )
    return SystemRun(
        path=p,
        t=t,
        q=q,
        dim=int(meta["dim"]),
        sensor_names=list(names),
        sensors=np.asarray(data["sensors"]).reshape(t.size, -1),
        energies={k: np.asarray(data[k]) for k in ("kinetic", "strain", "gravity")},
        bodies=list(meta["bodies"]),
        flexible=flexible,
        static=static,
    )


def plot_system_run(run: SystemRun, out_dir: str | Path, n_configurations: int = 6) -> list[Path]:
    """``sensors.png``, ``energy.png``, every flexible body's ``envelope_NAME.png``
    (:mod:`rancf.post.envelope`) and ``configurations.png`` (every body at
    ``n_configurations`` evenly spaced stored times), replaced together."""
    from rancf.post.envelope import plot_envelopes
    from rancf.post.run_plots import _draw, _space_axes, plot_series

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    plt = pyplot()
    with FileSet() as files:
        written = plot_series(run, out, files)
        written += plot_envelopes(run.path, list(run.flexible), out, files)
        idx = np.unique(np.linspace(0, run.t.size - 1, max(n_configurations, 1)).round())
        frames = [run.shapes(int(i)) for i in idx]
        points = [p for f in frames for _, p in f]
        if not points:  # no body drawn as a line (a shell's surfaces are its VTK files)
            return written
        allp = np.concatenate(points)
        fig = plt.figure(figsize=(7, 5), constrained_layout=True)
        ax = _space_axes(fig, run.dim, allp)
        cmap = plt.get_cmap("viridis")
        for j, (i, frame) in enumerate(zip(idx, frames, strict=True)):
            color = cmap(j / max(len(idx) - 1, 1))
            for k, (_, pts) in enumerate(frame):
                label = run.time_text(run.t[int(i)]) if k == 0 else None
                _draw(ax, pts, color=color, label=label, marker="o" if len(pts) < 3 else None)
        ax.legend(fontsize=8)
        ax.set_title(f"configurations of {run.name}")
        written.append(out / "configurations.png")
        save_figure(fig, written[-1], 100, files)
    return written


def animate_system_run(
    run: SystemRun,
    path: str | Path,
    fps: int = 20,
    every: int = 1,
    dpi: int = 80,
    magnify: float = 1.0,
) -> int:
    """Render every body's motion to ``path`` (``.gif`` or ``.mp4``); returns the frames.

    Frames are :func:`~rancf.post.run_data.frame_indices` ``(n_t, every)``; ``magnify`` scales
    the flexible bodies' displacements from their reference (small vibrations; the title says
    so)."""
    from rancf.post.run_plots import _draw, _set_line, _space_axes, animation_writer

    path = Path(path)
    writer = animation_writer(path, fps)
    plt = pyplot()
    idx = frame_indices(run.t.size, every)
    frames = [run.shapes(int(i), magnify) for i in idx]
    allp = np.concatenate([p for f in frames for _, p in f])
    fig = plt.figure(figsize=(6, 4.5))
    ax = _space_axes(fig, run.dim, allp)
    if run.dim == 2:
        lo, hi = allp[:, :2].min(axis=0), allp[:, :2].max(axis=0)
        pad = 0.05 * max(float(np.max(hi - lo)), 1e-9)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal", adjustable="box")
    lines = [_draw(ax, pts, lw=2, marker="o" if len(pts) < 3 else None) for _, pts in frames[0]]
    title = ax.set_title("")
    label = f" (displacement × {magnify:g})" if magnify != 1.0 else ""
    try:
        with atomic_path(path) as tmp, writer.saving(fig, tmp, dpi):
            for k, i in enumerate(idx):
                for line, (_, pts) in zip(lines, frames[k], strict=True):
                    _set_line(line, pts)
                title.set_text(f"{run.name}: {run.time_text(run.t[i], '.4f')}{label}")
                writer.grab_frame()
    finally:
        plt.close(fig)
    return int(idx.size)


def export_system_vtk(
    run: SystemRun, out_dir: str | Path, every: int = 1, per_element: int = 16
) -> list[Path]:
    """Every body's VTK files (module docstring); returns the ``.pvd`` paths."""
    import meshio

    from rancf.post.vtk import _export, check_export_size, export_vtk

    out = Path(out_dir)
    for r in run.flexible.values():
        check_export_size(r, every, per_element)
    paths = [export_vtk(r, out / name, every, per_element) for name, r in run.flexible.items()]
    rigid = [b for b in run.bodies if b["kind"] in ("rigid", "mass")]
    if not rigid:
        return paths

    def mesh_at(i: int) -> Any:
        frames = [run.rigid_frame(b, i) for b in rigid]
        pts = np.array([x for x, _ in frames])
        data = {f"e{k + 1}": np.array([ax[k] for _, ax in frames]) for k in range(3)}
        n = len(pts)
        return meshio.Mesh(pts, [("vertex", np.arange(n)[:, None])], point_data=data)

    parts: list[tuple[str, Callable[[int], Any]]] = [("rigid", mesh_at)]
    with FileSet() as files:
        paths.append(_export(run.t, out, frame_indices(run.t.size, every), parts, files))
    return paths
