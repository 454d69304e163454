"""Envelopes of a flexible body's section values over a run: ``bodies/NAME/envelope.csv``.

At every output station ``s`` (the reference arc length of the section samples,
:class:`rancf.bodies.section_outputs.SectionSampler`) and for every section quantity (strain,
axial force, curvature(s), twist rate, bending and twisting moments:
:func:`rancf.bodies.section_outputs.section_names`) the file holds the smallest and largest value
over the run's output rows and the time of each (the first row that reaches it; a load path's
load factor in place of the time).  The extremes are gathered chunk by chunk while the run's
files are written (:mod:`rancf.post.run_files`), so no history is read twice.

Columns: ``s``, then ``NAME_min, NAME_min_t, NAME_max, NAME_max_t`` for every quantity.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import IO

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet
from rancf.post.csv_rows import write_rows

__all__ = ["Envelope", "read_envelope", "plot_envelopes"]


class Envelope:
    """Running minima and maxima of section values ``(k, n_points, n_names)`` over rows.

    Parameters
    ----------
    s : ndarray
        ``(n_points,)`` reference arc length of the stations.
    names : sequence of str
        The quantities, in the last axis's order.
    """

    def __init__(self, s: NDArray, names: Sequence[str]) -> None:
        self.s = np.asarray(s, dtype=float)
        self.names = tuple(names)
        shape = (self.s.size, len(self.names))
        self.low, self.high = np.full(shape, np.inf), np.full(shape, -np.inf)
        self.t_low, self.t_high = np.full(shape, np.nan), np.full(shape, np.nan)

    def update(self, t: NDArray, along: NDArray) -> NDArray:
        """Take rows at times ``t (k,)`` with values ``along (k, n_points, n_names)``; returns
        ``along`` (to pass a chunk on to its writer)."""
        a = np.asarray(along, dtype=float)
        if a.shape[0] == 0:
            return along
        i_lo, i_hi = np.argmin(a, axis=0), np.argmax(a, axis=0)
        lo = np.take_along_axis(a, i_lo[None], axis=0)[0]
        hi = np.take_along_axis(a, i_hi[None], axis=0)[0]
        tt = np.asarray(t, dtype=float)
        better = lo < self.low  # strictly: the first row reaching the extreme keeps its time
        self.low[better], self.t_low[better] = lo[better], tt[i_lo][better]
        better = hi > self.high
        self.high[better], self.t_high[better] = hi[better], tt[i_hi][better]
        return along

    def columns(self) -> list[str]:
        """The header of :meth:`write`."""
        out = ["s"]
        for n in self.names:
            out += [f"{n}_min", f"{n}_min_t", f"{n}_max", f"{n}_max_t"]
        return out

    def table(self) -> NDArray[np.float64]:
        """``(n_points, 1 + 4 n_names)`` in the order of :meth:`columns`."""
        parts = [self.s[:, None]]
        for j in range(len(self.names)):
            parts.append(
                np.column_stack(
                    [self.low[:, j], self.t_low[:, j], self.high[:, j], self.t_high[:, j]]
                )
            )
        return np.concatenate(parts, axis=1)

    def write(self, fh: IO[bytes]) -> None:
        """The CSV file (module docstring)."""
        fh.write((",".join(self.columns()) + "\n").encode())
        write_rows(fh, self.table())


def read_envelope(path: str) -> dict[str, NDArray[np.float64]]:
    """An ``envelope.csv`` as named columns."""
    with open(path, encoding="utf-8") as fh:
        names = fh.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {n: data[:, i] for i, n in enumerate(names)}


def plot_envelopes(run_path: Path, names: Sequence[str], out: Path, files: FileSet) -> list[Path]:
    """``envelope_NAME.png`` for every flexible body ``NAME`` whose ``envelope.csv`` the run
    holds: each quantity's band between its minimum and maximum along ``s``."""
    from rancf.post.plots import pyplot, save_figure

    plt = pyplot()
    written = []
    for name in names:
        path = Path(run_path) / "bodies" / name / "envelope.csv"
        if not path.is_file():  # a run written before envelopes existed
            continue
        env = read_envelope(str(path))
        quantities = [k[: -len("_min")] for k in env if k.endswith("_min")]
        fig, axes = plt.subplots(
            len(quantities),
            1,
            figsize=(7, 1.7 * len(quantities) + 0.6),
            sharex=True,
            squeeze=False,
            constrained_layout=True,
        )
        for ax, q in zip(axes[:, 0], quantities, strict=True):
            ax.fill_between(env["s"], env[f"{q}_min"], env[f"{q}_max"], alpha=0.4)
            ax.plot(env["s"], env[f"{q}_min"], lw=0.8)
            ax.plot(env["s"], env[f"{q}_max"], lw=0.8)
            ax.set_ylabel(q.replace("_", " "), fontsize=8)
        axes[-1, 0].set_xlabel("s [m]")
        fig.suptitle(f"envelopes of {name} over the run (min to max, SI units)")
        written.append(out / f"envelope_{name}.png")
        save_figure(fig, written[-1], 100, files)
    return written
