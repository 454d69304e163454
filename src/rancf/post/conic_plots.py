"""Figures of a conic-section element (conic-section paper, Figs. 6–10, 12 and 13)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rancf.elements.cable import cable_shape_functions
from rancf.elements.mapping import gradient_ratio
from rancf.geometry.conic_curve import Conic
from rancf.post.plots import save_figure

__all__ = ["plot_conic", "draw_gradient_curves", "draw_parameter_points", "k_study_figure"]


def k_study_figure(  # noqa: ANN201
    conic: Conic,
    ks,  # noqa: ANN001
    k_opt: float,
    titles: tuple[str, str],
    plane: tuple[str, str] = ("x", "y"),
):
    """Gradient curves and parameter distributions side by side (paper Figs. 12–13, 25).

    ``plane`` names the model's axes that the conic's local x and y lie along (``("X", "Z")``
    for an arc in a vertical plane of a spatial model).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), constrained_layout=True)
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(ks)))
    draw_gradient_curves(axes[0], conic, ks, k_opt, colors)
    draw_parameter_points(axes[1], conic, ks, colors, plane)
    axes[0].set_title(titles[0])
    axes[1].set_title(titles[1])
    return fig


def draw_parameter_points(  # noqa: ANN001
    ax, conic: Conic, ks, colors, plane: tuple[str, str] = ("x", "y")
) -> None:
    """Points at ξ = 0, 0.1, ..., 1 for several K (paper Fig. 13), curves offset for legibility.

    ``plane``: the names of the axes the conic's local x and y lie along.
    """
    pts = conic(np.linspace(0.0, 1.0, 400))
    ax.plot(pts[:, 0], pts[:, 1], "-", color="0.7", lw=1)
    xi_pts = np.linspace(0.0, 1.0, 11)
    for i, (kk, col) in enumerate(zip(ks, colors, strict=True)):
        p = conic.cubic(kk)(xi_pts)
        off = (i - len(ks) / 2) * 0.02 * conic.chord
        ax.plot(
            p[:, 0],
            p[:, 1] + off,
            "o",
            color=col,
            ms=4,
            label=f"K = {kk:.4g} (offset {off:+.3f} m)",
        )
    ax.set_aspect("equal")
    ax.set_xlabel(f"{plane[0]} [m]")
    ax.set_ylabel(f"{plane[1]} [m] (curves offset for legibility)")
    ax.set_title("points at ξ = 0, 0.1, ..., 1")
    ax.legend(fontsize=7)


def draw_gradient_curves(ax, conic: Conic, ks, k_opt: float, colors) -> None:  # noqa: ANN001
    """``|r_ξ|`` against ξ for several K, Kopt marked (paper Figs. 10, 12)."""
    xi = np.linspace(0.0, 1.0, 400)
    for kk, col in zip(ks, colors, strict=True):
        c = conic.cubic(kk)
        sp = np.linalg.norm(c.derivatives(xi, 1)[1], axis=1)
        lab = f"K = {kk:.4g}, ratio {gradient_ratio(c):.3f}"
        if abs(kk - k_opt) < 5e-5:
            lab += " (Kopt)"
        ax.plot(xi, sp, color=col, label=lab)
    ax.set_xlabel("ξ [-]")
    ax.set_ylabel("|r_ξ| [m]")
    ax.set_title("gradient magnitude along the element")
    ax.legend(fontsize=7)


def _k_set(k_opt: float, k_used: float) -> list[float]:
    ks = sorted({0.2, round(k_opt, 4), 0.6, round(k_used, 4)})
    return ks


def plot_conic(
    conic: Conic, k_opt: float, k_used: float, path: str | Path, n_elements: int = 1
) -> Path:
    """Write a 2×3 panel PNG describing the conic and its K-family of element definitions.

    Panels: (a) the arc with the control polygons of the cubic forms (Fig. 7); (b) points at equal
    steps of ξ for several K (Fig. 13, parameter distribution); (c) ``|r_ξ|`` against ξ for several
    K including Kopt (Figs. 10, 12); (d) interior weights against K (Fig. 8); (e) gradient ratio
    against K with Kopt marked (eq. 29); (f) shape functions for several K (Fig. 9).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = Path(path)
    ks = _k_set(k_opt, k_used)
    colors = plt.cm.viridis(np.linspace(0.0, 0.9, len(ks)))
    fig, axes = plt.subplots(2, 3, figsize=(15, 8.5), constrained_layout=True)
    u = np.linspace(0.0, 1.0, 400)
    pts = conic(u)
    xi = np.linspace(0.0, 1.0, 400)

    ax = axes[0, 0]
    ax.plot(pts[:, 0], pts[:, 1], "k-", lw=2, label=f"{conic.kind} arc, ω = {conic.omega:.5f}")
    tri = np.array([conic.p0, conic.p1, conic.p2])
    ax.plot(tri[:, 0], tri[:, 1], "k:", lw=1, label="tangent triangle P0 P1 P2")
    for kk, col in zip(ks, colors, strict=True):
        q = conic.cubic(kk).points
        ax.plot(
            q[:, 0], q[:, 1], "o--", color=col, ms=4, lw=1, label=f"control polygon K = {kk:.4g}"
        )
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("(a) arc and cubic control polygons")
    ax.legend(fontsize=7)

    draw_parameter_points(axes[0, 1], conic, ks, colors)
    draw_gradient_curves(axes[0, 2], conic, ks, k_opt, colors)

    kgrid = np.linspace(0.03, 0.97, 95)
    w = np.array([conic.cubic(kk).weights for kk in kgrid])
    ax = axes[1, 0]
    ax.plot(kgrid, w[:, 1], label="w1")
    ax.plot(kgrid, w[:, 2], label="w2")
    ax.axvline(k_opt, color="k", ls=":", label=f"Kopt = {k_opt:.4f}")
    ax.set_yscale("log")
    ax.set_xlabel("K [-]")
    ax.set_ylabel("interior weight [-]")
    ax.set_title("(d) interior weights against K")
    ax.legend(fontsize=7)

    ratios = np.array([gradient_ratio(conic.cubic(kk)) for kk in kgrid])
    ax = axes[1, 1]
    ax.plot(kgrid, ratios, "b-")
    ax.plot([k_opt], [gradient_ratio(conic.cubic(k_opt))], "r*", ms=12, label=f"Kopt = {k_opt:.4f}")
    if abs(k_used - k_opt) > 5e-5:
        ax.plot(
            [k_used], [gradient_ratio(conic.cubic(k_used))], "ks", label=f"K used = {k_used:.4g}"
        )
    ax.set_yscale("log")
    ax.set_xlabel("K [-]")
    ax.set_ylabel("gradient ratio max|r_ξ| / min|r_ξ| [-]")
    ax.set_title("(e) gradient ratio against K")
    ax.legend(fontsize=7)

    ax = axes[1, 2]
    length = conic.arc_length()
    for kk, col in zip(ks, colors, strict=True):
        n = cable_shape_functions(conic.cubic(kk).weights[None, :], [length], xi)[0][0]
        for j, ls in enumerate(["-", "--", "-.", ":"]):
            ax.plot(
                xi,
                n[:, j],
                ls,
                color=col,
                lw=1,
                label=f"S{j + 1}, K = {kk:.4g}" if j == 0 else None,
            )
    ax.set_xlabel("ξ [-]")
    ax.set_ylabel("shape function [-] (S2, S4 in m)")
    ax.set_title("(f) shape functions S1 (—) S2 (--) S3 (-.) S4 (:)")
    ax.legend(fontsize=7)

    fig.suptitle(
        f"Conic arc: chord {conic.chord:.4g} m, {conic.kind}, arc length {length:.5f} m, "
        f"Kopt = {k_opt:.4f}, {n_elements} element(s)"
    )
    return save_figure(fig, path, 110)
