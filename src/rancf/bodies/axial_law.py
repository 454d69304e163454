"""A nonlinear axial law: the tension ``T(e)`` [N] of the engineering strain ``e = λ − 1`` of a
cable or rod, given as a table of rows ``(e_i, T_i)`` through ``(0, 0)``, both increasing.

It replaces ``EA e`` in the axial energy of the element kernels: the energy per reference length
is ``w(e) = ∫₀ᵉ T`` (``src/cpp/elements/tension_law.hpp``).  The table is interpolated by the
monotone piecewise cubic Hermite curve of Fritsch and Carlson (weighted harmonic mean slopes
inside, the end intervals' secants at the ends): C¹, so Newton's tangent ``dT/de`` is
continuous, and ``dT/de > 0`` for an increasing table, so the tangent stays positive definite.
Beyond the last row it goes on linearly with its last slope; in compression (``e < 0``) with its
slope at 0: a rope carries no compression, but the solver needs a positive stiffness there.
Derivation and choices: docs/derivations/axial-law.md.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError
from rancf.kernels import _core

__all__ = ["AxialLaw", "KEY", "pchip_coefficients"]

#: The key of the table (relative to the body).
KEY = "material.axial_law.table"


def pchip_coefficients(x: NDArray[np.float64], y: NDArray[np.float64]) -> NDArray[np.float64]:
    """The cubic coefficients ``(k, 4)`` of the monotone Hermite interpolant of increasing
    ``y(x)`` (docs/derivations/axial-law.md eqs. 4-6): on piece ``i``, ``c0 + c1 s + c2 s² +
    c3 s³`` with ``s = x − x_i``.

    Slopes: the weighted harmonic mean of the neighbouring secants ``δ`` inside (eq. 5),
    ``d = (w1 + w2) / (w1 / δ_{i−1} + w2 / δ_i)`` with ``w1 = 2 h_i + h_{i−1}`` and
    ``w2 = h_i + 2 h_{i−1}``; the end pieces' secants at the ends.  Every slope lies in
    ``(0, 3 min δ]``, Fritsch and Carlson's monotone region.
    """
    h = np.diff(x)
    delta = np.diff(y) / h
    d = np.empty_like(y)
    d[0], d[-1] = delta[0], delta[-1]
    w1, w2 = 2.0 * h[1:] + h[:-1], h[1:] + 2.0 * h[:-1]
    d[1:-1] = (w1 + w2) / (w1 / delta[:-1] + w2 / delta[1:])
    c2 = (3.0 * delta - 2.0 * d[:-1] - d[1:]) / h
    c3 = (d[:-1] + d[1:] - 2.0 * delta) / h**2
    return np.column_stack([y[:-1], d[:-1], c2, c3])


def _checked(rows: Any) -> NDArray[np.float64]:
    """The table as an array ``(k + 1, 2)``, or :class:`InputError` naming what is wrong."""
    allowed = "rows [strain, tension] through [0, 0], both strictly increasing"
    try:
        a = np.array(rows, dtype=float)
    except (TypeError, ValueError):
        raise InputError(KEY, rows, allowed) from None
    if a.ndim != 2 or a.shape[1] != 2 or a.shape[0] < 2 or not np.all(np.isfinite(a)):
        raise InputError(KEY, rows, f"2 or more finite {allowed}")
    if a[0, 0] != 0.0 or a[0, 1] != 0.0:
        raise InputError(KEY, a[0].tolist(), f"a first row [0, 0]: {allowed}")
    for j, what in ((0, "strain"), (1, "tension")):
        bad = np.flatnonzero(np.diff(a[:, j]) <= 0.0)
        if bad.size:
            i = int(bad[0]) + 1
            raise InputError(
                f"{KEY}[{i}]",
                a[i].tolist(),
                f"a {what} above the row before's ({a[i - 1, j]:g}): {allowed}",
            )
    return a


@dataclass(frozen=True)
class AxialLaw:
    """The tension-strain table of a cable or rod (module docstring).

    Parameters
    ----------
    rows : array_like, shape (k + 1, 2)
        ``[engineering strain, tension in N]`` rows, the first ``[0, 0]``, both columns
        strictly increasing.
    """

    rows: tuple[tuple[float, float], ...]
    core: Any = field(init=False, repr=False, compare=False)

    def __init__(self, rows: ArrayLike) -> None:
        a = _checked(rows)
        object.__setattr__(self, "rows", tuple((float(e), float(t)) for e, t in a))
        coef = np.ascontiguousarray(pchip_coefficients(a[:, 0], a[:, 1]))
        law = _core.AxialLaw(breaks=np.ascontiguousarray(a[:, 0]), coef=coef.ravel())
        object.__setattr__(self, "core", law)

    @property
    def strain(self) -> NDArray[np.float64]:
        """The table's strains."""
        return np.array([r[0] for r in self.rows])

    @property
    def max_strain(self) -> float:
        """The largest strain of the table (beyond it: linear with the last slope)."""
        return self.rows[-1][0]

    def evaluate(self, e: ArrayLike) -> tuple[NDArray, NDArray, NDArray]:
        """``(T, dT/de, ∫₀ᵉ T)`` at the strains ``e`` (the core's evaluation, any shape)."""
        x = np.asarray(e, dtype=float)
        t, dt, w = (np.empty(x.size) for _ in range(3))
        _core.tension_law(self.core, np.ascontiguousarray(x.ravel()), t, dt, w)
        return t.reshape(x.shape), dt.reshape(x.shape), w.reshape(x.shape)

    def tension(self, e: ArrayLike) -> NDArray[np.float64]:
        """The tension ``T(e)`` [N]."""
        return self.evaluate(e)[0]

    def tangent(self, e: ArrayLike) -> NDArray[np.float64]:
        """The tangent axial stiffness ``dT/de`` [N] (the ``EA`` of small motions about ``e``)."""
        return self.evaluate(e)[1]

    @property
    def ea0(self) -> float:
        """The slope at zero strain [N]: the ``EA`` of small strains (catenary start shapes,
        scales of round-off)."""
        return float(self.tangent(0.0))

    def leaves_table(self, max_strain: float) -> str:
        """A warning's line when a run's largest strain ``max_strain`` is beyond the table
        (else empty)."""
        if not max_strain > self.max_strain:
            return ""
        return (
            f"the strain reaches {max_strain:.4g}, beyond the axial_law table's last row "
            f"({self.max_strain:.4g}): the tension there is extrapolated linearly with the "
            f"last slope ({float(self.tangent(self.max_strain)):.4g} N)"
        )
