"""The residual of a static state as the outputs read it (the supports' reactions in its held
rows): the nonlinear balance, or after a linear analysis its linearization about the reference
(:mod:`rancf.solvers.linear_static`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.kernels.call_records import ResidualOptions, ResidualPoint

__all__ = ["static_residual"]


def static_residual(s: Any, y: NDArray, lam: NDArray, res: NDArray, at: ResidualOptions) -> None:
    """The static residual of ``s`` at ``(y, lam)`` into ``res`` (its held rows: the supports'
    reactions).  After a linear analysis (:mod:`rancf.solvers.linear_static`, which leaves its
    reference ``z₀`` and the norms' scale ``c`` as ``s.linear_reference``) the linear one,
    ``r(z₀) + ∂r/∂z(z₀) (z - z₀)``, by the central difference
    ``(r(z₀ + h Δz) - r(z₀ - h Δz)) / 2h`` with ``max |c h Δz| = 1e-6`` (the residual is not
    polynomial: the rational curvature; truncation ``O(1e-12)``, round-off ``O(ε / 1e-6)``
    relative): the reactions of the linear solve, not of the nonlinear balance at its state."""
    ref = getattr(s, "linear_reference", None)
    if ref is None:
        s.core.residual(ResidualPoint(y, lam, res), at)
        return
    z0, scale = ref
    dz = np.r_[y, lam] - z0
    n, big = s.n, float(np.max(np.abs(dz * scale), initial=0.0))
    h = min(1.0, 1e-6 / big) if big > 0.0 else 1.0
    rp, rm = np.empty_like(res), np.empty_like(res)
    for z, r in ((z0, res), (z0 + h * dz, rp), (z0 - h * dz, rm)):
        s.core.residual(ResidualPoint(np.ascontiguousarray(z[:n]), z[n:].copy(), r), at)
    res += (rp - rm) / (2.0 * h)
