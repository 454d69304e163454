"""Adaptive Gauss–Legendre quadrature for smooth integrands, one or many at a time.

Each interval is integrated with a ``points``-point Gauss–Legendre rule and with the same rule
on its two halves; an interval is accepted when the two agree to its share of the tolerance,
otherwise its halves are examined in the next round (local bisection, so a sharp peak of
``|r'|`` — e.g. a NURBS with widely varying weights — refines only where it is).  All open
intervals of a round are evaluated in one vectorized call.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from rancf.errors import ConvergenceError

__all__ = ["gauss_legendre", "integrate", "integrate_many"]

#: Rounds of bisection before giving up (an interval is then 2**-60 of the domain).
_MAX_ROUNDS = 60
#: Open intervals at which the bisection gives up (bounds time and memory).
_MAX_INTERVALS = 1 << 21


@lru_cache(maxsize=64)
def _gl(n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    x, w = np.polynomial.legendre.leggauss(n)
    x.setflags(write=False)
    w.setflags(write=False)
    return x, w


def gauss_legendre(n: int, a: float = 0.0, b: float = 1.0) -> tuple[NDArray, NDArray]:
    """Gauss–Legendre points and weights on ``[a, b]`` (exact for degree ``2n - 1``)."""
    x, w = _gl(n)
    half = 0.5 * (b - a)
    return a + half * (x + 1.0), half * w


def integrate_many(
    f: Callable[[NDArray[np.int64], NDArray[np.float64]], NDArray[np.float64]],
    a: NDArray[np.float64],
    b: NDArray[np.float64],
    rtol: float = 1e-14,
    points: int = 20,
) -> NDArray[np.float64]:
    """Integrals of ``m`` smooth functions ``f_i`` over ``[a_i, b_i]``.

    Parameters
    ----------
    f : callable
        ``f(owner, x)`` with ``owner`` of shape ``(k,)`` (which integrand) and ``x`` of shape
        ``(k, q)`` returns the values ``(k, q)``.
    a, b : ndarray, shape (m,)
    rtol : float
        Relative tolerance of each integral (round-off of the rule is the floor).

    Raises
    ------
    ConvergenceError
        If some interval is still not resolved after 60 bisections.
    """
    a = np.atleast_1d(np.asarray(a, dtype=float))
    b = np.atleast_1d(np.asarray(b, dtype=float))
    x, w = _gl(points)
    owner = np.arange(a.size)
    lo, hi = a.copy(), b.copy()
    total = np.zeros(a.size)
    width = np.where(b != a, np.abs(b - a), 1.0)
    estimate: NDArray[np.float64] | None = None
    for _ in range(_MAX_ROUNDS):
        if owner.size == 0:
            return total
        mid = 0.5 * (lo + hi)
        edges = np.stack([lo, mid, hi], axis=1)  # (k, 3)
        half = 0.25 * (hi - lo)
        centres = np.concatenate([0.5 * (edges[:, :2] + edges[:, 1:]), mid[:, None]], axis=1)
        halves = np.concatenate([half[:, None] * np.ones((1, 2)), 2.0 * half[:, None]], axis=1)
        xs = centres[:, :, None] + halves[:, :, None] * x[None, None, :]  # (k, 3, q)
        vals = f(owner, xs.reshape(owner.size, -1)).reshape(xs.shape)
        if not np.all(np.isfinite(vals)):
            raise ConvergenceError("adaptive quadrature: the integrand is not finite")
        parts = np.einsum("kpq,q->kp", vals, w) * halves
        fine = parts[:, 0] + parts[:, 1]
        coarse = parts[:, 2]
        if estimate is None:
            estimate = np.abs(fine).copy()
        scale = np.maximum(estimate[owner], np.einsum("kpq,q->k", np.abs(vals[:, :2]), w) * half)
        share = (hi - lo) / width[owner]
        floor = 64.0 * np.finfo(float).eps * scale
        ok = np.abs(fine - coarse) <= np.maximum(rtol * scale * share, floor)
        np.add.at(total, owner[ok], fine[ok])
        keep = ~ok
        owner = np.repeat(owner[keep], 2)
        lo = np.stack([lo[keep], mid[keep]], axis=1).ravel()
        hi = np.stack([mid[keep], hi[keep]], axis=1).ravel()
        if owner.size > _MAX_INTERVALS:
            break
    if owner.size == 0:
        return total
    raise ConvergenceError(
        f"adaptive quadrature did not reach rtol={rtol:g} on {np.unique(owner).size} "
        f"integral(s) after {_MAX_ROUNDS} bisections or {_MAX_INTERVALS} intervals"
    )


def integrate(
    f: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    a: float,
    b: float,
    rtol: float = 1e-14,
    points: int = 20,
) -> float:
    """Integral of a vectorized smooth function over ``[a, b]`` (see :func:`integrate_many`).

    Raises
    ------
    ConvergenceError
        If the adaptive bisection does not resolve the integrand.
    """
    return float(
        integrate_many(
            lambda _, xs: f(xs.ravel()).reshape(xs.shape),
            np.array([a]),
            np.array([b]),
            rtol,
            points,
        )[0]
    )
