"""A system in a frame turning at a steady rate: the frame's rotation on the coordinates, the
centrifugal loads and the steady state (docs/derivations/rotating.md).

The frame turns at ``Ω`` [rad/s] about the unit axis ``n`` through the point ``c``.  On every
3-vector block of a flexible body's full coordinates (nodal positions, relative to ``c``, and
gradients) and on a point mass's position the frame's rotation acts as ``ŵ = Ω [n]ₓ``
(rotating.md, eq. (1)); in model coordinates ``y`` (clamp rotations, C² reduction) it is
``W = Y Ŵ T`` with ``q = T y`` and ``y = Y q`` (eq. (2)).  With the centreline's mass ``M``
(constant), the kinetic energy seen from the turning frame is

    T = ½ (ẏ + W (y - c̄))ᵀ M (ẏ + W (y - c̄))                                 (eq. (3))

and Lagrange's equations give, besides the inertial-frame terms,

* the centrifugal force ``f_c(y) = Wᵀ M W (y - c̄)``                          (eq. (4)),
  whose stiffness ``-Wᵀ M W`` is the spin softening;
* the gyroscopic (Coriolis) force ``-(M W - Wᵀ M) ẏ``                         (eq. (5)).

The steady state is the static equilibrium in the turning frame with ``f_c`` among the loads:
:class:`RotatingEquilibrium` is :class:`~rancf.solvers.system_equilibrium.SystemEquilibrium`
with the centrifugal force growing with the load factor ``p`` (as ``p Ω²``) and its stiffness
in the tangent (factored as a sparse matrix, SuperLU).  A rod's rotary inertia of its sections
takes no part in the frame terms (their share is of order ``(radius / length)²``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import PointMass
from rancf.errors import InputError, RancfError
from rancf.options import MAX_SPIN_RATE, SPIN_RATES
from rancf.solvers.linearized import system_jacobian
from rancf.solvers.system_equilibrium import STABILIZER, SystemEquilibrium
from rancf.system import System

__all__ = ["Spin", "FrameTerms", "frame_terms", "RotatingEquilibrium"]


@dataclass(frozen=True)
class Spin:
    """A steady rotation: ``rate`` [rad/s] about the unit ``axis`` through ``center``."""

    axis: tuple[float, float, float]
    center: tuple[float, float, float]
    rate: float

    @classmethod
    def of(cls, axis: ArrayLike, center: ArrayLike, rate: float) -> Spin:
        """Checked: ``axis`` a non-zero 3-vector (normalized), ``center`` 3 finite numbers."""
        a = np.asarray(axis, dtype=float).ravel()
        c = np.asarray(center, dtype=float).ravel()
        if a.size != 3 or not np.all(np.isfinite(a)) or np.linalg.norm(a) == 0:
            raise InputError("modes.spin_axis", list(a), "a non-zero vector of 3 numbers")
        if c.size != 3 or not np.all(np.isfinite(c)):
            raise InputError("modes.spin_center", list(c), "3 finite numbers [m]")
        if not abs(rate) <= MAX_SPIN_RATE:  # NaN too
            raise InputError("modes.spin_rates", rate, f"rates {SPIN_RATES} in size")
        a = a / np.linalg.norm(a)
        return cls(tuple(a), tuple(c), float(rate))


@dataclass(frozen=True)
class FrameTerms:
    """The frame's rotation on a system's model coordinates, at unit rate (module docstring).

    Attributes
    ----------
    w : scipy.sparse.csr_matrix
        ``(n, n)`` ``W / Ω`` (eq. (2)).
    center : ndarray
        ``(n,)`` ``c̄``: ``c`` on every position block, 0 elsewhere (model coordinates).
    mass : scipy.sparse.csr_matrix
        ``(n, n)`` the centreline's (translational) mass ``M``; zero rows for coordinates the
        frame does not turn.
    """

    w: sp.csr_matrix
    center: NDArray[np.float64]
    mass: sp.csr_matrix

    def centrifugal_force(self, y: NDArray, rate: float) -> NDArray[np.float64]:
        """``f_c = Ω² Wᵀ M W (y - c̄)`` (eq. (4))."""
        return rate**2 * (self.w.T @ (self.mass @ (self.w @ (np.asarray(y) - self.center))))

    def centrifugal_stiffness(self, rate: float) -> sp.csr_matrix:
        """``∂(-f_c)/∂y = -Ω² Wᵀ M W`` (eq. (4)), the spin softening."""
        return (-(rate**2) * (self.w.T @ self.mass @ self.w)).tocsr()

    def gyroscopic(self, rate: float) -> sp.csr_matrix:
        """``D = Ω (M W - Wᵀ M)``, skew-symmetric: the force ``-D ẏ`` (eq. (5))."""
        mw = self.mass @ self.w
        return (rate * (mw - self.w.T @ self.mass)).tocsr()


def _skew(n: NDArray) -> NDArray[np.float64]:
    return np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])


def _body_mass(b: Model) -> NDArray[np.float64]:
    """A flexible body's constant (centreline) mass, dense in its model coordinates."""
    eye = np.eye(b.n)
    return np.column_stack([b.mass_times(eye[:, j]) for j in range(b.n)])


def frame_terms(system: System, axis: ArrayLike, center: ArrayLike) -> FrameTerms:
    """:class:`FrameTerms` of ``system`` turning about ``axis`` through ``center`` (eqs. (1),
    (2)).

    Raises
    ------
    RancfError
        A planar system or one with rigid bodies (their orientation coordinates are not
        turned by a linear map).
    """
    if system.dim != 3:
        raise RancfError(
            "modes.spin_rates: a spin needs a spatial (3D) scenario (its axis and "
            "the motion out of the plane); this one is planar"
        )
    n_hat = np.asarray(axis, dtype=float)
    n_hat = n_hat / np.linalg.norm(n_hat)
    c = np.asarray(center, dtype=float)
    skew = _skew(n_hat)
    blocks_w, blocks_m, centers = [], [], []
    for name in system.names:
        b = system.bodies[name]
        if isinstance(b, Model):
            nq, dpn = b.n_nodes * b.dpn, b.dpn
            wq = np.zeros((nq, nq))
            cq = np.zeros(nq)
            for k in range(b.n_nodes):
                o = k * dpn
                wq[o : o + 3, o : o + 3] = skew  # position
                wq[o + 3 : o + 6, o + 3 : o + 6] = skew  # gradient
                cq[o : o + 3] = c
            t = b.q_from_y(np.eye(b.n)).T  # (nq, n): q = T y
            yq = b.y_from_q(np.eye(nq)).T  # (n, nq): y = Y q
            blocks_w.append(yq @ wq @ t)
            blocks_m.append(_body_mass(b))
            centers.append(b.y_from_q(cq))
        elif isinstance(b, PointMass):
            blocks_w.append(skew)
            blocks_m.append(b.mass * np.eye(3))
            centers.append(c.copy())
        else:
            raise RancfError(
                f"modes.spin_rates: a spin needs a system of flexible bodies and "
                f"point masses; {name!r} is a rigid body"
            )
    w = sp.block_diag(blocks_w, format="csr")
    mass = sp.block_diag(blocks_m, format="csr")
    return FrameTerms(w, np.concatenate(centers), mass)


class RotatingEquilibrium(SystemEquilibrium):
    """The steady state in the turning frame (module docstring): the static problem with the
    centrifugal force ``p Ω² Wᵀ M W (y - c̄)`` among the loads.

    Parameters
    ----------
    system : System
    spin : Spin
    loads : bool
        The system's own loads act too (growing with ``p`` like the centrifugal ones); False:
        the centrifugal loads alone.
    """

    def __init__(self, system: System, spin: Spin, loads: bool = True) -> None:
        super().__init__(system)
        self.spin, self.loads = spin, loads
        self.frame = frame_terms(system, spin.axis, spin.center)
        self._lu: spla.SuperLU | None = None

    def load_factor(self, p: float) -> float:
        return super().load_factor(p) if self.loads else 0.0

    def spin_factor(self, p: float) -> float:
        """The share of the centrifugal force at ``p``: ``p`` while loading, then 1."""
        return p if self.stage == 0 else 1.0

    def full_residual(self, z: NDArray, p: float) -> NDArray[np.float64]:
        r = super().full_residual(z, p)
        fc = self.frame.centrifugal_force(z[: self.n], self.spin.rate)
        r[: self.n] -= self.spin_factor(p) * fc
        return r

    def _factor(self, z: NDArray, p: float, stab: float) -> bool:
        """Factor ``∂r/∂z`` (plus ``stab M``) with the held coordinates' rows and columns
        replaced by the identity."""
        s, n = self.system, self.n
        y, lam = np.ascontiguousarray(z[:n]), np.ascontiguousarray(z[n:])
        args = (self.load_factor(p), self._amp, self._t)
        j = system_jacobian(s, y, lam, 1.0, 0.0, *args)
        extra = self.spin_factor(p) * self.frame.centrifugal_stiffness(self.spin.rate)
        if stab:
            extra = extra + stab * system_jacobian(s, y, lam, 0.0, 1.0, *args)[:n, :n]
        j = j + sp.block_diag([extra, sp.csr_matrix((self.m, self.m))])
        keep = sp.diags(self.free.astype(float))
        j = keep @ j @ keep + sp.diags(self.fixed.astype(float))
        try:
            self._lu = spla.splu(j.tocsc())
        except RuntimeError:
            self._lu = None
            return False
        return True

    def tangent(self, z: NDArray, p: float) -> tuple[NDArray, bool]:
        r = self.residual(z, p)
        if not np.all(np.isfinite(r)):
            return r, False
        ok = self._factor(z, p, 0.0) or self._factor(z, p, STABILIZER * self._stiffness_scale(z))
        return r, ok

    def damped_tangent(self, z: NDArray, p: float, rate: float) -> tuple[NDArray, bool]:
        r = self.residual(z, p)
        return r, bool(np.all(np.isfinite(r))) and self._factor(z, p, float(rate))

    def solve(self, ok: bool, rhs: NDArray) -> NDArray[np.float64] | None:
        if not ok or self._lu is None:
            return None
        x = np.array(rhs, dtype=float)
        x[self.fixed] = 0.0
        out = self._lu.solve(x)
        return out if np.isfinite(out).all() else None
