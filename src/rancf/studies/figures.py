"""Figures the paper's studies share: error against elements, AB(t) for several meshes."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from rancf.studies.common import NOT_REACHED, n_elements

__all__ = ["kind_style", "plot_ab", "plot_errors"]


_MARKERS = ("o", "s", "^", "D", "v", "P", "X")
_DASHES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1)), (0, (3, 1)), "-")


def kind_style(i: int, kind: str) -> dict[str, Any]:
    """Line style of element kind number ``i`` in an error-against-elements plot.

    Kinds often lie on top of each other (Kopt and ANCF converge alike for a soft cable): Kopt is
    drawn as a wide band under everything else, each other kind as a thin line with its own
    colour ``C{i}``, marker and dash pattern, so every curve stays visible where they coincide.
    """
    if kind == "Kopt":
        return dict(color=f"C{i}", marker="o", ms=9, lw=4.5, ls="-", alpha=0.55, zorder=2)
    return dict(
        color=f"C{i}",
        marker=_MARKERS[i % len(_MARKERS)],
        ms=4.5,
        lw=1.3,
        ls=_DASHES[i % len(_DASHES)],
        zorder=3,
    )


def plot_ab(
    plt: Any,
    runs: Mapping[int, Mapping[str, Any]],
    ref: Mapping[str, Any],
    show: Sequence[int],
    title: str,
) -> Any:
    """AB(t) for several numbers of elements and the reference (paper Figs. 15–17, 21, 24, 26)."""
    fig, ax = plt.subplots(figsize=(7, 4.2), constrained_layout=True)
    for n in show:
        if n in runs:
            ax.plot(runs[n]["t"], runs[n]["ab"], label=n_elements(n))
    ax.plot(ref["t"], ref["ab"], "k--", lw=1, label=f"reference ({n_elements(ref['n_el'])})")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("distance AB [m]")
    ax.set_title(title)
    ax.legend(fontsize=8)
    return fig


def plot_errors(
    plt: Any, runs: Mapping[str, Mapping[int, Mapping[str, Any]]], tol: float, title: str
) -> Any:
    """Tip error against the number of elements, one curve per element kind (:func:`kind_style`)."""
    from matplotlib.ticker import MaxNLocator

    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    for i, (kind, by_n) in enumerate(runs.items()):  # colour C{i} per kind, as callers assume
        n_list = [n for n in sorted(by_n) if np.isfinite(by_n[n]["err"])]
        ax.semilogy(n_list, [by_n[n]["err"] for n in n_list], label=kind, **kind_style(i, kind))
        failed = [n for n in sorted(by_n) if not np.isfinite(by_n[n]["err"])]
        if failed:
            ax.plot([], [], " ", color=f"C{i}", label=f"{kind}: {NOT_REACHED} for n = {failed}")
    ax.axhline(tol, color="k", ls="--", lw=1, label=f"tolerance {tol:g} m")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("number of elements")
    ax.set_ylabel("max_t |tip - tip_ref| [m]")
    ax.set_title(title)
    ax.legend(fontsize=8)
    return fig
