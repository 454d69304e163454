"""Plots of models and results (Matplotlib, headless)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet, atomic_path
from rancf.bodies.flexible import Model
from rancf.elements.cable import cable_shape_functions
from rancf.system import System

__all__ = ["centerline", "plot_campbell", "plot_modes", "pyplot", "save_figure"]


def pyplot() -> Any:
    """Matplotlib's pyplot with the non-interactive Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig: Any, path: str | Path, dpi: int = 100, files: FileSet | None = None) -> Path:
    """Write ``fig`` to ``path`` atomically (format from the extension, :mod:`rancf.atomic`),
    or as one file of the set ``files``, and close it."""
    path = Path(path)
    try:
        with atomic_path(path) if files is None else files.path(path) as tmp:
            fig.savefig(tmp, dpi=dpi)
    finally:
        pyplot().close(fig)
    return path


def centerline(model: Model, q: NDArray, per_element: int = 16) -> NDArray[np.float64]:
    """Points along the centreline of configuration ``q``, shape ``(n_points, dim)``.

    Cable and rod elements are evaluated with their shape functions (a rod's twist is left out);
    beam elements as their chords.
    """
    q = np.asarray(q, dtype=float)
    if not model.family.gradient:
        return model.node_positions(q)
    xi = np.linspace(0.0, 1.0, per_element + 1)
    n = cable_shape_functions(model.mesh.weights, model.mesh.scales, xi)[0]
    if model.family.has_triads:  # r, r_x of both nodes
        nodes = q.reshape(model.n_nodes, model.dpn)[:, : 2 * model.dim]
        e = np.concatenate([nodes[:-1], nodes[1:]], axis=1).reshape(model.n_el, 4, model.dim)
    else:
        e = model.gather(q).reshape(model.n_el, 4, model.dim)
    pts = np.einsum("eqk,ekd->eqd", n, e)
    return np.concatenate([pts[:, :-1].reshape(-1, model.dim), pts[-1:, -1]], axis=0)


def plot_modes(
    model: Model | System, modal: Any, path: str | Path, y: NDArray | None = None
) -> Path:
    """Mode shapes over the configuration they linearize about, one panel per mode."""
    growth = getattr(modal, "growth_rates", None)
    titles = []
    for i, f in enumerate(modal.frequencies_hz):
        title = f"mode {i + 1}: {f:.4f} Hz"
        if growth is not None and growth[i] > 0:
            title += f", growth {growth[i]:.3g} 1/s"
        titles.append(title)
    return plot_shapes(model, modal.modes, titles, path, y)


def plot_campbell(res: Any, path: str | Path) -> Path:
    """The Campbell diagram: each line one mode followed across the spin rates by its shape and
    labelled by its dominant motion (:func:`rancf.solvers.campbell.campbell`; crossing lines
    keep their colours), with the lines ``f = k Ω / 2π`` (k = 1, 2) of the once- and
    twice-per-revolution excitations."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    rates = np.asarray(res.spin_rates, dtype=float)
    freqs = np.asarray(res.frequencies_hz, dtype=float)
    labels = list(getattr(res, "labels", ())) or [f"mode {i + 1}" for i in range(freqs.shape[1])]
    for i in range(freqs.shape[1]):
        ax.plot(rates, freqs[:, i], "o-", ms=3, color=f"C{i % 10}", label=labels[i])
    top = float(rates.max(initial=0.0))
    for k in (1, 2):
        ax.plot([0.0, top], [0.0, k * top / (2 * np.pi)], "k--", lw=0.7, alpha=0.5)
    ax.set_xlabel("spin rate Ω [rad/s]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_ylim(0.0, 1.05 * float(freqs.max(initial=1.0)))
    ax.set_title("Campbell diagram (dashed: 1 and 2 per revolution)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    return save_figure(fig, path)


def plot_buckling(
    model: Model | System, res: Any, path: str | Path, y: NDArray | None = None
) -> Path:
    """Buckling mode shapes over the configuration they linearize about, titled by their
    critical load factor."""
    titles = [f"mode {i + 1}: λ = {lam:.6g}" for i, lam in enumerate(res.load_factors)]
    return plot_shapes(model, res.modes, titles, path, y)


def plot_shapes(
    model: Model | System,
    shapes: NDArray,
    titles: list[str],
    path: str | Path,
    y: NDArray | None = None,
) -> Path:
    """Shapes ``(k, n)`` (full coordinates) scaled over the configuration ``y``, one panel
    each: every flexible body's centreline, every rigid body's or point mass's position."""
    from rancf.system import as_system

    system = as_system(model)
    plt = pyplot()
    path = Path(path)
    base = system.q_from_y(system.y0 if y is None else y)
    flex = [(b, system.body_slice(k)) for k, b in system.bodies.items() if isinstance(b, Model)]
    other = [system.body_slice(k) for k, b in system.bodies.items() if not isinstance(b, Model)]
    dim = system.dim

    def points(q: NDArray) -> list[NDArray]:
        out = [centerline(b, q[sl]) for b, sl in flex]
        return out + [np.atleast_2d(q[sl][:dim]) for sl in other]

    ref = points(base)
    size = float(np.ptp(np.concatenate(ref), axis=0).max()) or 1.0
    n = len(titles)
    cols = min(3, n)
    rows = int(np.ceil(n / cols))
    fig = plt.figure(figsize=(4.5 * cols, 3.8 * rows), constrained_layout=True)
    for i in range(n):
        ax = fig.add_subplot(rows, cols, i + 1, projection="3d" if dim == 3 else None)
        shape = shapes[i]
        moved = [b.node_positions(shape[sl]) for b, sl in flex]
        moved += [np.atleast_2d(shape[sl][:dim]) for sl in other]
        amp = 0.15 * size / max(np.abs(np.concatenate(moved)).max(), 1e-300)
        for k, (r0, r1) in enumerate(zip(ref, points(base + amp * shape), strict=True)):
            style: dict[str, Any] = {"lw": 1} if len(r0) > 1 else {"marker": "o", "ls": ""}
            if k < len(flex) and flex[k][0].family.surface:  # a shell: its nodes, not a line
                style = {"marker": ".", "ls": "", "ms": 3}
            ax.plot(*r0.T, color="0.6", label="configuration" if k == 0 else None, **style)
            ax.plot(
                *r1.T,
                color="C3",
                label="mode (scaled)" if k == 0 else None,
                **({"lw": 2} if len(r1) > 1 and "marker" not in style else style),
            )
        ax.set_title(titles[i])
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        if dim == 3:
            ax.set_zlabel("z [m]")
        else:
            ax.set_aspect("equal", adjustable="datalim")
        if i == 0:
            ax.legend(fontsize=7)
    return save_figure(fig, path, 100)


def positions_at(model: Model, q: NDArray, sbar: NDArray) -> NDArray[np.float64]:
    """Centreline points at material points given by normalized reference arc length ``sbar``.

    Cable elements: each element's reference arc length ``s_e(ξ)`` is tabulated on a fine grid
    and inverted by interpolation (plotting accuracy, about 1e-8); beams: linear along chords.
    Shape ``(n_s, dim)`` (``q`` one configuration) or ``(n_t, n_s, dim)`` (``q`` a history).
    """
    q = np.asarray(q, dtype=float)
    sbar = np.asarray(sbar, dtype=float)
    hist = q.reshape(-1, model.n)
    if not model.family.gradient:
        pos0 = model.node_positions(model.q0)
        seg = np.linalg.norm(np.diff(pos0, axis=0), axis=1)
        s_nodes = np.concatenate([[0.0], np.cumsum(seg)]) / seg.sum()
        idx = np.clip(np.searchsorted(s_nodes, sbar, side="right") - 1, 0, model.n_el - 1)
        w = (sbar - s_nodes[idx]) / (s_nodes[idx + 1] - s_nodes[idx])
        pos = model.node_positions(hist)
        out = (1.0 - w)[None, :, None] * pos[:, idx] + w[None, :, None] * pos[:, idx + 1]
        return out[0] if q.ndim == 1 else out
    xi = np.linspace(0.0, 1.0, 401)
    _, n1, _ = cable_shape_functions(model.mesh.weights, model.mesh.scales, xi)
    ref = model.gather(model.q0).reshape(model.n_el, 4, model.dim)
    speed = np.linalg.norm(np.einsum("eqk,ekd->eqd", n1, ref), axis=2)
    cum = np.concatenate(
        [
            np.zeros((model.n_el, 1)),
            np.cumsum(0.5 * (speed[:, 1:] + speed[:, :-1]) * np.diff(xi), axis=1),
        ],
        axis=1,
    )
    starts = np.concatenate([[0.0], np.cumsum(cum[:, -1])])
    total = starts[-1]
    s_abs = sbar * total
    el = np.clip(np.searchsorted(starts, s_abs, side="right") - 1, 0, model.n_el - 1)
    xis = np.array([np.interp(s - starts[e], cum[e], xi) for s, e in zip(s_abs, el, strict=True)])
    out = np.empty((hist.shape[0], sbar.size, model.dim))
    for e in np.unique(el):
        sel = el == e
        n = cable_shape_functions(
            model.mesh.weights[e : e + 1], model.mesh.scales[e : e + 1], xis[sel]
        )[0][0]
        nodal = hist[:, model.element_dofs[e]].reshape(hist.shape[0], 4, model.dim)
        out[:, sel] = np.einsum("sk,tkd->tsd", n, nodal)
    return out[0] if q.ndim == 1 else out
