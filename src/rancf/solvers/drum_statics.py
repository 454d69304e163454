"""Statics of a system with driven drums (:mod:`rancf.system.drums`).

Two stages: the system's equilibrium with every drum's length held at its start (the path
methods of :mod:`rancf.solvers.static`, which start a hanging line from its unloaded, slack
reference), then Newton with the lengths free, to where each drum's line pulls the torque back
(``r T = τ``, docs/derivations/variable-length.md §3.4).  The second stage solves with the
whole sparse Jacobian (:meth:`rancf.kernels._core.System.sparse_jacobian`, the bordered
matrix's entries, by :func:`scipy.sparse.linalg.spsolve`): a body whose own block is singular in
statics (a point mass held by a joint) needs no stabilizing mass there, which would stiffen
the drum's direction, whose stiffness is only the line's weight per length.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.kernels.call_records import (
    ResidualOptions,
    ResidualPoint,
    StatePoint,
    TangentOptions,
)
from rancf.system import System

__all__ = ["free_drums"]


def free_drums(
    system: System,
    y: NDArray,
    lam: NDArray,
    t: float | None,
    scale: NDArray,
    tol: float,
    max_iter: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64], bool, int]:
    """Newton from ``(y, λ)`` (an equilibrium with the drums held) with the drums' lengths
    free, at the loads of time ``t`` (None: their amplitudes); converged when the largest
    increment times ``scale`` (per unknown of ``(y, λ)``) is at most ``tol``.  Returns
    ``(y, λ, converged, iterations)``."""
    import scipy.sparse as sp  # only here: simulate and static of other systems never load it
    from scipy.sparse.linalg import spsolve

    n, m = system.n, system.m
    held = system.fixed
    zero = np.zeros(n)
    tt, amp = (0.0, True) if t is None else (float(t), False)
    z = np.r_[y, lam].astype(float)
    for it in range(1, max_iter + 1):
        r = np.empty(n + m)
        ok = system.core.residual(
            ResidualPoint(z[:n], z[n:], r), ResidualOptions(tt, 1.0, amp, dynamic=False)
        )
        ok2, size, rows, cols, vals = system.core.sparse_jacobian(
            StatePoint(np.ascontiguousarray(z[:n]), zero, zero, np.ascontiguousarray(z[n:])),
            TangentOptions(tt, 1.0, 0.0, 0.0, False, 1.0, amp),
        )
        if not (ok and ok2):
            return z[:n], z[n:], False, it
        keep = np.ones(size, dtype=bool)
        keep[:n] = ~held
        rows, cols, vals = np.asarray(rows), np.asarray(cols), np.asarray(vals)
        on = keep[rows] & keep[cols]  # held rows and columns: the identity
        a = sp.coo_matrix((vals[on], (rows[on], cols[on])), shape=(size, size)).tocsc()
        a = a + sp.diags((~keep).astype(float))
        rhs = np.zeros(size)
        rhs[: n + m] = -r
        rhs[~keep] = 0.0
        dz = np.asarray(spsolve(a, rhs))[: n + m]
        if not np.all(np.isfinite(dz)):
            return z[:n], z[n:], False, it
        z += dz
        if float(np.max(np.abs(dz * scale))) <= tol:
            return z[:n], z[n:], True, it
    return z[:n], z[n:], False, max_iter
