"""Figure and animation helpers of finished runs (``rancf plot``, ``rancf animate``:
:mod:`rancf.post.system_run`).

The configurations are the densely sampled exact element curves
(:func:`rancf.post.centerline.sample_centerline`), never the node polyline.  Animations use
Matplotlib's ``FuncAnimation``: GIF through Pillow, MP4 through the ``ffmpeg`` executable that the
optional ``imageio-ffmpeg`` package ships (``pip install 'rancf[mp4]'``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet
from rancf.errors import InputError
from rancf.extras import require
from rancf.post.plots import pyplot, save_figure

__all__ = ["plot_series", "animation_writer"]


def _space_axes(fig: Any, dim: int, pts: NDArray, position: Any = 111) -> Any:
    """Axes for centrelines ``pts (..., 3)``: x–y for planar runs; for spatial runs 3D axes
    (mplot3d) with equal scales and every coordinate labelled, so no coordinate is lost."""
    if dim == 2:
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
