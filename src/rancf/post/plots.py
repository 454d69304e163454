"""Plots of models and results (Matplotlib, headless)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.elements.cable import cable_shape_functions
from rancf.model.system import Model

__all__ = ["centerline", "plot_modes", "pyplot"]


def pyplot() -> Any:
    """Matplotlib's pyplot with the non-interactive Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def centerline(model: Model, q: NDArray, per_element: int = 16) -> NDArray[np.float64]:
    """Points along the centreline of configuration ``q``, shape ``(n_points, dim)``.

    Cable elements are evaluated with their shape functions; beam elements as their chords.
    """
    q = np.asarray(q, dtype=float)
    if model.element == "beam":
        return model.node_positions(q)
    xi = np.linspace(0.0, 1.0, per_element + 1)
    n = cable_shape_functions(model.mesh.weights, model.mesh.scales, xi)[0]
    e = model.gather(q).reshape(model.n_el, 4, model.dim)
    pts = np.einsum("eqk,ekd->eqd", n, e)
    return np.concatenate([pts[:, :-1].reshape(-1, model.dim), pts[-1:, -1]], axis=0)


def plot_modes(model: Model, modal: Any, path: str | Path, y: NDArray | None = None) -> Path:
    """Mode shapes over the configuration they linearize about, one panel per mode."""
    plt = pyplot()
    path = Path(path)
    base = model.q0 if y is None else model.q_from_y(y)
    ref = centerline(model, base)
    size = float(np.ptp(ref, axis=0).max())
    n = len(modal.frequencies_hz)
    cols = min(3, n)
    rows = int(np.ceil(n / cols))
    three = model.dim == 3
    fig = plt.figure(figsize=(4.5 * cols, 3.8 * rows), constrained_layout=True)
    for i in range(n):
        ax = fig.add_subplot(rows, cols, i + 1, projection="3d" if three else None)
        shape = modal.modes[i]
        amp = 0.15 * size / max(np.abs(model.node_positions(shape)).max(), 1e-300)
        cur = centerline(model, base + amp * shape)
        ax.plot(*ref.T, color="0.6", lw=1, label="configuration")
        ax.plot(*cur.T, color="C3", lw=2, label="mode (scaled)")
        ax.set_title(f"mode {i + 1}: {modal.frequencies_hz[i]:.4f} Hz")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        if three:
            ax.set_zlabel("z [m]")
        else:
            ax.set_aspect("equal", adjustable="datalim")
        if i == 0:
            ax.legend(fontsize=7)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
