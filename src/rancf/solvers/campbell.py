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

from collections.abc import Iterable, Sequence
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

__all__ = [
    "CampbellResult",
    "RotatingModes",
    "rotating_modes",
    "campbell",
    "track",
    "mac",
    "motion_shares",
    "motion_label",
    "MAX_FREE",
]

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
    """Frequencies against spin rate: ``frequencies_hz[i, j]`` is line ``j`` of the diagram at
    ``spin_rates[i]``. A line follows one mode across the rates by its shape (:func:`track`),
    so lines that cross keep their identity; ``labels[j]`` names its dominant motion
    (:func:`motion_label`: ``"flap 1"``, ``"lag 1"``, ...). Lines are ordered by their
    frequency at the first rate."""

    spin_rates: NDArray[np.float64]
    frequencies_hz: NDArray[np.float64]
    growth_rates: NDArray[np.float64]
    labels: tuple[str, ...] = ()


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
        raise RancfError(
            f"modes.spin_rates: the rotating eigenproblem is dense, for at most "
            f"{MAX_FREE} free coordinates; this system has {n_free} (use fewer "
            "elements)"
        )
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
        raise RancfError(
            f"only {order.size} modes found about the spin rate {spin.rate:g} rad/s, {count} asked"
        )
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
    through ``center`` (:func:`rotating_modes`), each line of the diagram tracked across the
    rates by its mode shape and labelled by its dominant motion."""
    spin_axis = Spin.of(axis, center, 0.0).axis
    runs = []
    for rate in rates:
        runs.append(
            rotating_modes(system, Spin.of(axis, center, rate), count, loads, load_steps, method)
        )
    system.reset_triads()
    freqs = np.array([r.frequencies_hz for r in runs])
    growth = np.array([r.growth_rates for r in runs])
    order = track([r.modes for r in runs])  # order[i, j]: rate i's mode on line j
    rows = np.arange(len(runs))[:, None]
    freqs, growth = freqs[rows, order], growth[rows, order]
    shares = np.array(
        [
            [motion_shares(system, r.y, r.modes[k], spin_axis) for k in o]
            for r, o in zip(runs, order, strict=True)
        ]
    )
    lines = np.lexsort((freqs[-1], freqs[0]))  # by the first rate's frequency (ties: the last)
    labels = _number(motion_label(shares[:, j]) for j in lines)
    return CampbellResult(
        np.asarray(rates, dtype=float), freqs[:, lines], growth[:, lines], tuple(labels)
    )


def mac(a: NDArray, b: NDArray) -> NDArray[np.float64]:
    """Modal assurance criteria ``|aᵢᴴ bⱼ|² / (|aᵢ|² |bⱼ|²)`` of shapes ``a (k, n)``, ``b (m, n)``:
    1 for the same shape (any complex factor), 0 for orthogonal ones."""
    num = np.abs(np.conj(a) @ b.T) ** 2
    den = np.outer(np.sum(np.abs(a) ** 2, axis=1), np.sum(np.abs(b) ** 2, axis=1))
    return num / np.maximum(den, np.finfo(float).tiny)


def track(shapes: Sequence[NDArray]) -> NDArray[np.intp]:
    """Lines through the modes ``shapes[i] (count, n)`` of consecutive spin rates: ``order[i, j]``
    is the mode of rate ``i`` on line ``j``. Neighbouring rates are matched by the assignment
    that maximizes the summed :func:`mac` (:func:`scipy.optimize.linear_sum_assignment`),
    walking from the last rate down: at rest flap and lag pairs of a symmetric section share a
    frequency and their computed shapes are any mix of the two, while spinning splits them."""
    from scipy.optimize import linear_sum_assignment

    n_rates, count = len(shapes), shapes[0].shape[0]
    order = np.empty((n_rates, count), dtype=np.intp)
    order[-1] = np.arange(count)
    for i in range(n_rates - 2, -1, -1):
        ahead = shapes[i + 1][order[i + 1]]  # line j's shape at rate i + 1
        rows, cols = linear_sum_assignment(-mac(ahead, shapes[i]))
        order[i, rows] = cols
    return order


def motion_shares(system: System, y: NDArray, shape: NDArray, axis: Sequence[float]) -> NDArray:
    """How a mode ``shape`` (full coordinates) about the steady state ``y`` moves its flexible
    bodies' nodes: the shares ``[flap, lag, axial, torsion]`` (summing to 1) of the nodes'
    squared motion along the spin ``axis`` (flap, out of the plane of rotation), in that plane
    across the body (lag), along its tangent (axial), and of a rod's twist times the section's
    radius of gyration (torsion)."""
    from rancf.bodies.flexible import Model

    a = np.asarray(axis, dtype=float)
    q = system.q_from_y(y)
    out = np.zeros(4)
    for name, b in system.bodies.items():
        if not isinstance(b, Model):
            continue
        sl = system.body_slice(name)
        pos = b.node_positions(q[sl])
        t = np.gradient(pos, axis=0) if len(pos) > 1 else np.tile(np.eye(3)[0], (1, 1))
        t = t - np.outer(t @ a, a)  # the tangent in the plane of rotation
        t /= np.maximum(np.linalg.norm(t, axis=1, keepdims=True), np.finfo(float).tiny)
        d = b.node_positions(shape[sl].real) + 1j * b.node_positions(shape[sl].imag)
        ax, fl = np.einsum("nd,nd->n", d, t), d @ a
        out[0] += np.sum(np.abs(fl) ** 2)
        out[2] += np.sum(np.abs(ax) ** 2)
        out[1] += np.sum(np.abs(d) ** 2) - np.sum(np.abs(fl) ** 2) - np.sum(np.abs(ax) ** 2)
        if b.family.has_triads:
            twist = shape[sl].reshape(b.n_nodes, b.dpn)[:, -1]
            out[3] += np.sum(np.abs(twist) ** 2) * b.section.radius**2 / 2
    total = out.sum()
    return out / total if total > 0 else out


MOTIONS = ("flap", "lag", "axial", "torsion")


def motion_label(shares: NDArray) -> str:
    """The dominant motion of a line of the diagram from its :func:`motion_shares` at every
    rate ``(n_rates, 4)``: the motion with the largest share where one dominates most."""
    best = np.unravel_index(int(np.argmax(shares)), shares.shape)
    return MOTIONS[int(best[1])]


def _number(labels: Iterable[str]) -> list[str]:
    """``flap 1``, ``lag 1``, ``flap 2``: each motion's lines counted in order."""
    seen: dict[str, int] = {}
    out = []
    for name in labels:
        seen[name] = seen.get(name, 0) + 1
        out.append(f"{name} {seen[name]}")
    return out
