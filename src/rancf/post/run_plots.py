"""Figures and animations of any finished run (``rancf plot``, ``rancf animate``).

The configurations are the densely sampled exact element curves
(:func:`rancf.post.run_data.sample_centerline`), never the node polyline.  Animations use
Matplotlib's ``FuncAnimation``: GIF through Pillow, MP4 through the ``ffmpeg`` executable that the
optional ``imageio-ffmpeg`` package ships (``pip install 'rancf[mp4]'``).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet, atomic_path
from rancf.errors import InputError
from rancf.extras import require
from rancf.post.plots import pyplot, save_figure
from rancf.post.run_data import RunData, frame_indices, sample_centerline

__all__ = ["plot_run", "animate_run", "plot_series"]


def _space_axes(fig: Any, run: RunData, pts: NDArray, position: Any = 111) -> Any:
    """Axes for centrelines ``pts (..., 3)``: x–y for planar runs; for spatial runs 3D axes
    (mplot3d) with equal scales and every coordinate labelled, so no coordinate is lost."""
    if run.dim == 2:
        ax = fig.add_subplot(position)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        return ax
    ax = fig.add_subplot(position, projection="3d")
    flat = pts.reshape(-1, 3)
    lo, hi = flat.min(axis=0), flat.max(axis=0)
    half = 0.55 * max(float(np.max(hi - lo)), 1e-9)
    mid = 0.5 * (lo + hi)
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_box_aspect((1.0, 1.0, 1.0))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    return ax


def _draw(ax: Any, pts: NDArray, **kw: Any) -> Any:
    """One centreline on planar or 3D axes; returns the line."""
    if getattr(ax, "name", "") == "3d":
        return ax.plot(pts[:, 0], pts[:, 1], pts[:, 2], **kw)[0]
    return ax.plot(pts[:, 0], pts[:, 1], **kw)[0]


def _set_line(line: Any, pts: NDArray) -> None:
    if hasattr(line, "set_data_3d"):
        line.set_data_3d(pts[:, 0], pts[:, 1], pts[:, 2])
    else:
        line.set_data(pts[:, 0], pts[:, 1])


def plot_run(run: RunData, out_dir: str | Path, n_configurations: int = 6) -> list[Path]:
    """Write ``sensors.png`` (every sensor column over time), ``energy.png`` and
    ``configurations.png`` (the centreline at ``n_configurations`` evenly spaced stored times).

    The three files replace earlier ones together (:class:`rancf.atomic.FileSet`).  Returns the
    written paths.
    """
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise InputError("--out", str(out), "a directory (it exists and is a file)")
    out.mkdir(parents=True, exist_ok=True)
    with FileSet() as files:
        return _plot_run(run, out, n_configurations, files)


def plot_series(run: Any, out: Path, files: FileSet) -> list[Path]:
    """``sensors.png`` (every sensor column over time; none without sensors) and ``energy.png``
    of a run (a :class:`RunData` or a system's run) into the set ``files``."""
    plt = pyplot()
    written = []
    cols = run.sensor_names
    if cols:
        fig, axes = plt.subplots(
            len(cols),
            1,
            figsize=(7, 1.9 * len(cols) + 0.6),
            sharex=True,
            squeeze=False,
            constrained_layout=True,
        )
        for k, name in enumerate(cols):
            axes[k, 0].plot(run.t, run.sensors[:, k])
            axes[k, 0].set_ylabel(name)
        axes[-1, 0].set_xlabel(run.time_label)
        fig.suptitle(f"sensors of {run.name} (SI units)")
        written.append(out / "sensors.png")
        save_figure(fig, written[-1], 100, files)

    fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
    e = run.energies
    for key in ("kinetic", "strain", "gravity"):
        ax.plot(run.t, e[key], label=key)
    ax.plot(run.t, e["kinetic"] + e["strain"] + e["gravity"], "k--", label="total")
    ax.set_xlabel(run.time_label)
    ax.set_ylabel("energy [J]")
    ax.legend()
    ax.set_title(f"energies of {run.name}")
    written.append(out / "energy.png")
    save_figure(fig, written[-1], 100, files)
    return written


def _plot_run(run: RunData, out: Path, n_configurations: int, files: FileSet) -> list[Path]:
    plt = pyplot()
    written = plot_series(run, out, files)

    idx = np.unique(np.linspace(0, run.t.size - 1, max(n_configurations, 1)).round().astype(int))
    lines = _pad(np.array([sample_centerline(run, int(i)).points for i in idx]))
    fig = plt.figure(figsize=(7, 5), constrained_layout=True)
    ax = _space_axes(fig, run, lines)
    cmap = plt.get_cmap("viridis")
    for j, (i, pts) in enumerate(zip(idx, lines, strict=True)):
        color = cmap(j / max(len(idx) - 1, 1))
        _draw(ax, pts, color=color, label=run.time_text(run.t[i]))
    ax.legend(fontsize=8)
    ax.set_title(f"configurations of {run.name}")
    written.append(out / "configurations.png")
    save_figure(fig, written[-1], 100, files)
    return written


def _pad(a: NDArray) -> NDArray:
    return a if a.shape[-1] == 3 else np.concatenate([a, np.zeros(a.shape[:-1] + (1,))], axis=-1)


def animation_writer(path: Path, fps: int) -> Any:
    """The Matplotlib writer of an animation file ``path`` (``.gif`` or ``.mp4``) at ``fps``
    frames per second, after checking both and that ``path``'s folder exists."""
    from matplotlib import animation

    if isinstance(fps, bool) or not isinstance(fps, int) or fps < 1:
        raise InputError("--fps", fps, "an integer >= 1")
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise InputError("--out", str(path), "a file name ending in .gif or .mp4")
    if not path.parent.is_dir():
        raise InputError("--out", str(path), "a file in an existing directory")
    if suffix == ".gif":
        return animation.PillowWriter(fps=fps)
    imageio_ffmpeg = require("imageio_ffmpeg", "mp4", "MP4 animations")
    import matplotlib

    matplotlib.rcParams["animation.ffmpeg_path"] = imageio_ffmpeg.get_ffmpeg_exe()
    return animation.FFMpegWriter(fps=fps, codec="libx264", extra_args=["-pix_fmt", "yuv420p"])


def animate_run(
    run: RunData,
    path: str | Path,
    fps: int = 20,
    every: int = 1,
    dpi: int = 80,
    magnify: float = 1.0,
) -> int:
    """Render the motion to ``path`` (``.gif`` or ``.mp4``); one frame per selected stored time.

    Frames are :func:`~rancf.post.run_data.frame_indices` ``(n_t, every)``; ``magnify`` scales
    the displacement from the reference configuration (small vibrations; the title says so).
    Returns the number of frames written.
    """
    path = Path(path)
    writer = animation_writer(path, fps)
    plt = pyplot()
    idx = frame_indices(run.t.size, every)
    lines = np.array([_pad(sample_centerline(run, int(i)).points) for i in idx])
    if magnify != 1.0:
        ref = replace(run, q=run.reference[None], v=np.zeros_like(run.reference)[None])
        base = _pad(sample_centerline(ref, 0).points)
        lines = base + magnify * (lines - base)
    fig = plt.figure(figsize=(6, 4.5))
    ax = _space_axes(fig, run, lines)
    if run.dim == 2:
        lo, hi = lines[..., :2].min(axis=(0, 1)), lines[..., :2].max(axis=(0, 1))
        pad = 0.05 * max(float(np.max(hi - lo)), 1e-9)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal", adjustable="box")
    _draw(ax, lines[0], color="0.75", lw=1, label=run.time_text(0.0))
    line = _draw(ax, lines[0], color="C0", lw=2)
    title = ax.set_title("")
    label = f" (displacement × {magnify:g})" if magnify != 1.0 else ""
    try:
        with atomic_path(path) as tmp, writer.saving(fig, tmp, dpi):
            for k, i in enumerate(idx):
                _set_line(line, lines[k])
                title.set_text(f"{run.name}: {run.time_text(run.t[i], '.4f')}{label}")
                writer.grab_frame()
    finally:
        plt.close(fig)
    return int(idx.size)
