"""The static equilibrium problem of a model along its load path, as the solvers see it.

The path parameter ``p`` runs through one or two stages:

1. ``p ∈ [0, 1]``: the loads act with ``p`` times their amplitude, the supports at their
   reference values;
2. with installed supports (``position``/``direction`` away from the reference,
   :attr:`Model.y_installed <rancf.bodies.flexible.Model.y_installed>`), ``p ∈ [1, 2]``: the
   loads at full amplitude, the supports moved ``p - 1`` of the way to their installed values.

With ``λ(p) = p``, ``μ = 0`` in the first stage and ``λ = 1``, ``μ(p) = p - 1`` in the second
(each linear in ``p`` also past its stage's end, as an arc-length step may go)::

    y[held] = y0[held] + μ Δ,        Δ = y_installed[held] - y0[held]
    r(y, p) = f_int(y) - λ f_ext(y) = 0    on the free coordinates

Loading first, then installing, keeps the path clear of bifurcations: a straight hose whose ends
are pushed together while it is still straight meets a perfect bifurcation (it may buckle up,
down or into an S), while the same hose already sagging under gravity just sags further.  The
held rows of ``f_int - λ f_ext`` are the reactions.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.kernels import _core

__all__ = ["EquilibriumProblem"]


#: Installed values closer to the reference than this (relative to the size) are the reference:
#: round-off, not an installation.
INSTALL_RTOL = 1e-12


def path_stages(delta: NDArray[np.float64], size: float) -> list[tuple[float, float]]:
    """The stages of the load path ``(p_start, p_end)``: the loads (``[0, 1]``), then the
    installation (``[1, 2]``) when a held coordinate moves by more than round-off (``delta``:
    installed minus reference values of the held coordinates; ``size`` the model's length)."""
    moves = delta.size and np.abs(delta).max() > INSTALL_RTOL * max(size, 1.0)
    return [(0.0, 1.0)] + ([(1.0, 2.0)] if moves else [])


class EquilibriumProblem:
    """Residual, tangent and linear solves of ``r(y, λ) = 0`` (module docstring).

    Parameters
    ----------
    model : Model
    at_time : float, optional
        Loads as they act at this time (a harmonic load ``F0 sin(2π f t)`` with its value
        then: the static state a dynamic run starts from); default their amplitudes.
    """

    def __init__(self, model: Model, at_time: float | None = None) -> None:
        self.model = model
        self._t = 0.0 if at_time is None else float(at_time)
        self._amp = at_time is None
        self.fixed = model.fixed
        self.free = ~model.fixed
        self._fixed_u8 = model.fixed.astype(np.uint8)
        self.delta = (model.y_installed - model.y0)[model.fixed]
        #: Characteristic length: the largest extent of the reference (positions are scaled by
        #: it in norms and tolerances).
        self.size = float(np.ptp(model.node_positions(model.q0), axis=0).max()) or 1.0
        #: The stages of the path, ``(p_start, p_end)``.
        self.stages = path_stages(self.delta, self.size)
        #: The stage the path is in (:meth:`load_factor`, :meth:`support_factor`).
        self.stage = 0
        scale = np.ones(model.n)
        scale[model.position_mask()] = 1.0 / self.size
        self.scale = scale  # per coordinate: 1/size on positions, 1 elsewhere

    @property
    def conservative(self) -> bool:
        """True without point moments (their load stiffness is not symmetric)."""
        return not any(p.moment is not None for p in self.model.point_loads)

    def start(self) -> NDArray[np.float64]:
        """The reference configuration (λ = 0)."""
        return self.model.y0.copy()

    def load_factor(self, p: float) -> float:
        """``λ(p)`` in the current stage: the factor on the loads."""
        return p if self.stage == 0 else 1.0

    def support_factor(self, p: float) -> float:
        """``μ(p)`` in the current stage: how far the supports are installed."""
        return 0.0 if self.stage == 0 else p - 1.0

    def place_supports(self, y: NDArray, p: float) -> None:
        """Held entries of ``y`` at their values at ``p`` (in place)."""
        y[self.fixed] = self.model.y0[self.fixed] + self.support_factor(p) * self.delta

    def full_residual(self, y: NDArray, p: float) -> NDArray[np.float64]:
        """``f_int(y) - λ f_ext(y)`` on every coordinate (the held rows are the reactions)."""
        lam = self.load_factor(p)
        return self.model.internal_force(y) - lam * self.model.external_force(self._t, y, self._amp)

    def residual(self, y: NDArray, p: float) -> NDArray[np.float64]:
        """``r(y, p)``, zero on the held rows."""
        r = self.full_residual(y, p)
        r[self.fixed] = 0.0
        return r

    def tangent(self, y: NDArray, p: float) -> tuple[NDArray, NDArray]:
        """Residual (held rows zero) and ``∂r/∂y`` in band storage, at ``(y, p)``."""
        m = self.model
        lam = self.load_factor(p)
        f, ab = m.internal_force_and_tangent(y)
        r = f - lam * m.external_force(self._t, y, self._amp)
        if not self.conservative:
            ab = ab - lam * m.load_stiffness(self._t, y, self._amp)
        r[self.fixed] = 0.0
        return r, ab

    def load_vector(self, y: NDArray, ab: NDArray) -> NDArray[np.float64]:
        """``-∂r/∂p`` on the free rows at ``y`` in the current stage: ``f_ext`` (loading), or
        ``-K[:, held] Δ`` (installing: the held entries move; ``ab`` the tangent at ``y``)."""
        m = self.model
        if self.stage == 0:
            q = m.external_force(self._t, y, self._amp)
        else:
            d = np.zeros(m.n)
            d[self.fixed] = self.delta
            q = -_core_band_matvec(ab, d, m.ku)
        q[self.fixed] = 0.0
        return q

    def solve(self, ab: NDArray, rhs: NDArray) -> NDArray[np.float64] | None:
        """``K x = rhs`` on the free coordinates (``x`` zero on the held ones); None if the
        tangent is singular."""
        x = np.array(rhs, dtype=float)
        ok = _core.band_solve(ab, x, self._fixed_u8)
        return x if ok and np.all(np.isfinite(x)) else None

    def norm(self, dy: NDArray) -> float:
        """Scaled norm of an increment: positions relative to :attr:`size`."""
        return float(np.linalg.norm(dy * self.scale))

    def accept(self, y: NDArray) -> None:
        """A converged state: rods carry their nodal triads to it."""
        self.model.core.rereference(y)


def _core_band_matvec(ab: NDArray, x: NDArray, ku: int) -> NDArray[np.float64]:
    """``A x`` for band storage ``ab[ku + i - j, j] = A[i, j]``."""
    n = x.size
    out = np.zeros(n)
    for k in range(2 * ku + 1):
        off = ku - k  # column - row
        i0, i1 = max(0, -off), min(n, n - off)
        out[i0:i1] += ab[k, i0 + off : i1 + off] * x[i0 + off : i1 + off]
    return out
