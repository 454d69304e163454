"""Modes about a steady rotation and the Campbell diagram (docs/derivations/rotating.md).

For each spin rate ``Ω`` the steady state ``y*`` in the turning frame is the static equilibrium
with the centrifugal loads (:class:`rancf.solvers.rotating.RotatingEquilibrium`, the one static
solver).  Small motions about it obey (rotating.md, eq. (6))

    M ẍ + D ẋ + (K + K_c) x + Gᵀ μ = 0,        G x = 0,

with the tangent ``K`` at ``(y*, λ*)`` (its stress stiffening is the centrifugal stiffening), the
spin softening ``K_c = -Ω² Wᵀ M_c W`` and the gyroscopic ``D = Ω (M_c W - Wᵀ M_c)``
(:class:`rancf.solvers.rotating.FrameTerms`).  On an orthonormal basis ``N`` of ``ker G`` the
quadratic eigenproblem ``(s² M + s D + K) φ = 0`` is solved in its first companion form

    [0  I; -K  -D] [φ; sφ] = s [I  0; 0  M] [φ; sφ]                                   (eq. (7))

by QZ (:func:`scipy.linalg.eig`, dense: up to :data:`MAX_FREE` free coordinates).  A pair
``s = g ± iω`` is one mode at ``ω / 2π`` Hz growing at ``g`` [1/s] (0 for a stable one); a real
pair ``±a`` (divergence) has frequency 0 and growth ``a``; eigenvalues with ``|s|²`` below
:data:`rancf.solvers.modal.ZERO_RTOL` of the median stiffness-to-mass ratio (the rigid-body
motions of an unsupported system) are dropped.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError, RancfError
from rancf.solvers.linearized import linearize
from rancf.solvers.modal import ZERO_RTOL
from rancf.solvers.rotating import RotatingEquilibrium, Spin
from rancf.solvers.static import StaticMethod, solve_equilibrium
from rancf.system import System

__all__ = ["CampbellResult", "RotatingModes", "rotating_modes", "campbell", "MAX_FREE"]

#: The largest number of free coordinates of the dense companion eigenproblem.
MAX_FREE = 1500


@dataclass(frozen=True)
class RotatingModes:
    """The modes about one steady rotation.

    Attributes
    ----------
    frequencies_hz : ndarray
        ``(count,)`` ascending, ``|Im s| / 2π``.
    growth_rates : ndarray
        ``(count,)`` ``Re s`` [1/s] where it is above round-off, else 0.
    modes : ndarray
        ``(count, n)`` complex shapes in the system's model coordinates (held ones 0).
    y : ndarray
        ``(n,)`` the steady state in the turning frame.
    """

    frequencies_hz: NDArray[np.float64]
    growth_rates: NDArray[np.float64]
    modes: NDArray[np.complex128]
    y: NDArray[np.float64]


@dataclass(frozen=True)
class CampbellResult:
    """Frequencies against spin rate: ``frequencies_hz[i]`` at ``spin_rates[i]`` (ascending,
    each row sorted on its own: no mode tracking)."""

    spin_rates: NDArray[np.float64]
    frequencies_hz: NDArray[np.float64]
    growth_rates: NDArray[np.float64]


def _companion(k: NDArray, d: NDArray, m: NDArray) -> tuple[NDArray, NDArray]:
    """Eigenvalues and ``φ`` parts of the eigenvectors of eq. (7)."""
    n = k.shape[0]
    eye, zero = np.eye(n), np.zeros((n, n))
    a = np.block([[zero, eye], [-k, -d]])
    b = np.block([[eye, zero], [zero, m]])
    s, v = scipy.linalg.eig(a, b)
    ok = np.isfinite(s)
    return s[ok], v[:n, ok]


def rotating_modes(
    system: System,
    spin: Spin,
    count: int,
    loads: bool = False,
    load_steps: int = 10,
    method: StaticMethod = "load",
) -> RotatingModes:
    """The lowest ``count`` modes about the steady rotation ``spin`` (module docstring).

    ``loads``: the system's own loads act in the steady state too (else the centrifugal ones
    alone).  The system's rod triads are left at the steady state.

    Raises
    ------
    InputError
        ``count`` out of range.
    RancfError
        More than :data:`MAX_FREE` free coordinates, or fewer than ``count`` modes found.
    """
    system.reset_triads()
    problem = RotatingEquilibrium(system, spin, loads)
    res = solve_equilibrium(problem, load_steps, method=method)
    y, lam = res.y, res.lam
    lin = linearize(system, y, lam, 1.0 if loads else 0.0)
    n_free = lin.k.shape[0]
    if n_free > MAX_FREE:
        raise RancfError(f"modes.spin_rates: the rotating eigenproblem is dense, for at most "
                         f"{MAX_FREE} free coordinates; this system has {n_free} (use fewer "
                         "elements)")  # fmt: skip
    if isinstance(count, bool) or not 1 <= count <= n_free:
        raise InputError("count", count, f"an integer in [1, {n_free}]")
    idx = np.flatnonzero(lin.free)
    frame = problem.frame
    kc = frame.centrifugal_stiffness(spin.rate)[idx][:, idx]
    dg = frame.gyroscopic(spin.rate)[idx][:, idx]
    k, d, m = (lin.k + kc).toarray(), dg.toarray(), lin.mass.toarray()
    basis = None
    if lin.g.shape[0]:
        basis = scipy.linalg.null_space(lin.g.toarray())
        k, d, m = (basis.T @ x @ basis for x in (k, d, m))
    s, phi = _companion(k, d, m)
    dk, dm = np.abs(np.diag(k)), np.abs(np.diag(m))
    both = (dk > 0) & (dm > 0)
    scale = float(np.median(dk[both] / dm[both])) if np.any(both) else 1.0
    zero = np.abs(s) ** 2 <= ZERO_RTOL * scale
    keep = ~zero & ((s.imag > 0) | ((np.abs(s.imag) <= 1e-9 * np.abs(s)) & (s.real > 0)))
    s, phi = s[keep], phi[:, keep]
    order = np.argsort(np.abs(s.imag), kind="stable")[:count]
    if order.size < count:
        raise RancfError(f"only {order.size} modes found about the spin rate {spin.rate:g} "
                         f"rad/s, {count} asked")  # fmt: skip
    s, phi = s[order], phi[:, order]
    if basis is not None:
        phi = basis @ phi
    full = np.zeros((count, system.n), dtype=complex)
    full[:, idx] = phi.T
    growth = np.where(np.abs(s.real) > 1e-7 * np.abs(s), s.real, 0.0)
    return RotatingModes(np.abs(s.imag) / (2 * np.pi), growth, full, y)


def campbell(
    system: System,
    axis: ArrayLike,
    center: ArrayLike,
    rates: Sequence[float],
    count: int,
    loads: bool = False,
    load_steps: int = 10,
    method: StaticMethod = "load",
) -> CampbellResult:
    """The lowest ``count`` frequencies at each spin rate of ``rates`` [rad/s] about ``axis``
    through ``center`` (:func:`rotating_modes`)."""
    freqs, growth = [], []
    for rate in rates:
        out = rotating_modes(system, Spin.of(axis, center, rate), count, loads, load_steps,
                             method)  # fmt: skip
        freqs.append(out.frequencies_hz)
        growth.append(out.growth_rates)
    system.reset_triads()
    return CampbellResult(np.asarray(rates, dtype=float), np.array(freqs), np.array(growth))
