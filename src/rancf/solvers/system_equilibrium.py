"""The static equilibrium problem of a system along its load path, as
:func:`rancf.solvers.static.solve_static` sees it (the one problem of the static solvers: a
one-body :class:`~rancf.bodies.flexible.Model` is solved as the system of that one body).

The path parameter ``p`` runs through one or two stages:

1. ``p ∈ [0, 1]``: the loads act with ``p`` times their amplitude, the supports at their
   reference values;
2. with installed supports (``position``/``direction`` away from the reference,
   :attr:`Model.y_installed <rancf.bodies.flexible.Model.y_installed>`), ``p ∈ [1, 2]``: the
   loads at full amplitude, the supports moved ``p - 1`` of the way to their installed values.

With ``λ(p) = p``, ``μ = 0`` in the first stage and ``λ = 1``, ``μ(p) = p - 1`` in the second
(each linear in ``p`` also past its stage's end, as an arc-length step may go), the held
coordinates are ``y[held] = y0[held] + μ Δ`` with ``Δ = y_installed[held] - y0[held]``.
Loading first, then installing, keeps the path clear of bifurcations: a straight hose whose ends
are pushed together while it is still straight meets a perfect bifurcation (it may buckle up,
down or into an S), while the same hose already sagging under gravity just sags further.

The unknowns are ``z = (y, μ)``: the coordinates of all bodies and the joints' multipliers.  The
residual is the compiled core's balance and constraints at zero velocity and acceleration,

    r(z, p) = [ f_int(y) - λ f_ext(y) + f_springs(y) + G(y)ᵀ μ ;  g(y) ],

and its Jacobian the bordered block-band matrix of the time integrator without inertia
(:class:`rancf.kernels._core.SystemIntegrator`: ``factor_static``, ``solve_factored``).  The
multipliers take no part in norms and tolerances (scale 0); the reactions of the joints are
``-Gᵀ μ``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.kernels.call_records import (
    ResidualOptions,
    ResidualPoint,
    StatePoint,
    StaticOptions,
    StaticPoint,
    TangentOptions,
    evaluator,
)
from rancf.system import System
from rancf.system.sliding import start_multipliers
from rancf.system.winches import unloaded_at

__all__ = ["SystemEquilibrium", "STABILIZER", "INSTALL_RTOL", "path_stages"]

#: Installed values closer to the reference than this (relative to the size) are the reference:
#: round-off, not an installation.
INSTALL_RTOL = 1e-12

#: The mass-proportional term of a singular tangent, relative to the stiffness-to-mass scale.
STABILIZER = 1e-6


def path_stages(delta: NDArray[np.float64], size: float) -> list[tuple[float, float]]:
    """The stages of the load path ``(p_start, p_end)``: the loads (``[0, 1]``), then the
    installation (``[1, 2]``) when a held coordinate moves by more than round-off (``delta``:
    installed minus reference values of the held coordinates; ``size`` the model's length)."""
    moves = delta.size and np.abs(delta).max() > INSTALL_RTOL * max(size, 1.0)
    return [(0.0, 1.0)] + ([(1.0, 2.0)] if moves else [])


class SystemEquilibrium:
    """Residual, tangent and linear solves of ``r(z, p) = 0`` for a system (module docstring).

    Parameters
    ----------
    system : System
    at_time : float, optional
        Loads as they act at this time; default their amplitudes.
    """

    def __init__(self, system: System, at_time: float | None = None) -> None:
        self.system = system
        s = system
        self._t = 0.0 if at_time is None else float(at_time)
        self._amp = at_time is None
        self.n, self.m = s.n, s.m
        self._held = s.fixed  # the held coordinates of y
        self._zero = np.zeros(s.n)  # zero velocities and accelerations (never written)
        fixed = np.zeros(s.n + s.m, dtype=bool)
        fixed[: s.n] = self._held
        self.fixed, self.free = fixed, ~fixed
        installed = s.y0.copy()
        for name, b in zip(s.names, s.flex, strict=False):
            installed[s.body_slice(name)] = b.y_installed
        self._y0 = unloaded_at(s, self._t)  # y0, winches' bodies at their length at t
        self.delta = (installed - s.y0)[s.fixed]
        self.size = s.size
        self.stages = path_stages(self.delta, self.size)
        self.stage = 0
        scale = np.zeros(s.n + s.m)  # the multipliers: not in norms
        scale[: s.n] = 1.0
        for name in s.names:
            sl = s.body_slice(name)
            body = s.bodies[name]
            pos = np.zeros(sl.stop - sl.start, dtype=bool)
            if isinstance(body, Model):
                pos = body.position_mask()
            else:
                pos[: s.dim] = True
            scale[sl][pos] = 1.0 / self.size
        self.scale = scale
        self._integ = evaluator(s.core)

    @property
    def conservative(self) -> bool:
        """False: the system's tangent is in general not symmetric (constraints, moments)."""
        return False

    def start(self) -> NDArray[np.float64]:
        """The reference configuration with zero multipliers (and the sliding joints' material
        coordinates in their slots)."""
        return np.r_[self._y0, start_multipliers(self.system)]

    def load_factor(self, p: float) -> float:
        return p if self.stage == 0 else 1.0

    def support_factor(self, p: float) -> float:
        return 0.0 if self.stage == 0 else p - 1.0

    def place_supports(self, z: NDArray, p: float) -> None:
        """Held coordinates at their values at ``p`` (in place)."""
        y = z[: self.n]
        y[self._held] = self._y0[self._held] + self.support_factor(p) * self.delta

    def full_residual(self, z: NDArray, p: float) -> NDArray[np.float64]:
        """Balance (held rows kept: the reactions) and constraints at ``(z, p)``."""
        r = np.empty(self.n + self.m)
        ok = self.system.core.residual(
            ResidualPoint(z[: self.n], z[self.n :], r),
            ResidualOptions(self._t, self.load_factor(p), self._amp, dynamic=False),
        )
        return r if ok else np.full_like(r, np.nan)

    def residual(self, z: NDArray, p: float) -> NDArray[np.float64]:
        r = self.full_residual(z, p)
        r[self.fixed] = 0.0
        return r

    def tangent(self, z: NDArray, p: float) -> tuple[NDArray, bool]:
        """Residual (held rows zero) and the factored Jacobian (a flag: it is usable).

        A tangent that is singular (a hanging pendulum or spring before its tension builds up:
        its swing has no stiffness at zero load) is factored again with ``s M`` added, ``s``
        :data:`STABILIZER` times the largest stiffness-to-mass ratio of the diagonals: a
        quasi-Newton step, the residual (and so the equilibrium found) unchanged."""
        return self._factored(z, p, True)

    def exact_tangent(self, z: NDArray, p: float) -> tuple[NDArray, bool]:
        """:meth:`tangent` without the stabilizer: a singular tangent is unusable (a linear
        analysis, whose one step is its answer: :mod:`rancf.solvers.linear_static`)."""
        return self._factored(z, p, False)

    def _factored(self, z: NDArray, p: float, stabilize: bool) -> tuple[NDArray, bool]:
        """:meth:`tangent` (``stabilize``) or :meth:`exact_tangent`."""
        r = np.empty(self.n + self.m)
        point = StaticPoint(np.ascontiguousarray(z[: self.n]), np.ascontiguousarray(z[self.n :]), r)
        options = StaticOptions(self.load_factor(p), self._amp, self._t)
        ok = self._integ.factor_static(point, options)
        if not ok and stabilize and np.all(np.isfinite(r)):
            stab = STABILIZER * self._stiffness_scale(z)
            ok = self._integ.factor_static(point, replace(options, stab=stab))
        r[self.fixed] = 0.0
        return r, bool(ok)

    def damped_tangent(self, z: NDArray, p: float, rate: float) -> tuple[NDArray, bool]:
        """Residual (held rows zero) and the Jacobian with ``rate M`` added, factored: the step
        ``(M/Δτ + K) Δz = -r`` of pseudo-transient continuation, ``rate = 1/Δτ``
        (:mod:`rancf.solvers.relaxation`)."""
        r = np.empty(self.n + self.m)
        ok = self._integ.factor_static(
            StaticPoint(np.ascontiguousarray(z[: self.n]), np.ascontiguousarray(z[self.n :]), r),
            StaticOptions(self.load_factor(p), self._amp, self._t, stab=float(rate)),
        )
        r[self.fixed] = 0.0
        return r, bool(ok)

    def stiffness_scale(self, z: NDArray) -> float:
        """The largest ratio of the diagonals of the tangent and the mass on the free
        coordinates at ``z`` [1/s²] (the square of the highest frequency's order)."""
        return self._stiffness_scale(z)

    def _stiffness_scale(self, z: NDArray) -> float:
        """The largest ratio of the diagonals of the tangent and the mass (free coordinates)."""
        k, m = self._diagonal(z, 1.0, 0.0), self._diagonal(z, 0.0, 1.0)
        return float(np.max(k[m > 0] / m[m > 0])) if np.any(m > 0) else 1.0

    def _diagonal(self, z: NDArray, ck: float, ca: float) -> NDArray[np.float64]:
        """``|diag(ck K + ca M)|`` on the free coordinates at ``z`` (loads at their full value)."""
        y, lam, zero = z[: self.n], z[self.n :], np.zeros(self.n)
        _, _, rows, cols, vals = self.system.core.sparse_jacobian(
            StatePoint(np.ascontiguousarray(y), zero, zero, np.ascontiguousarray(lam)),
            TangentOptions(self._t, ck, 0.0, ca, ca != 0.0),
        )
        d = np.zeros(self.n)
        rows, cols, vals = np.asarray(rows), np.asarray(cols), np.asarray(vals)
        on = (rows == cols) & (rows < self.n)
        np.add.at(d, rows[on], vals[on])
        return np.abs(d[~self.system.fixed])

    def mechanism(self, z: NDArray) -> bool:
        """Whether the structure at ``z`` (the reference, no load) is a mechanism the loads move:
        the stiffness the loads meet there, the Rayleigh quotient ``ρ = xᵀK₀x / xᵀx = fᵀx / xᵀx``
        of the linear response ``K₀ x = f`` (``K₀`` the tangent at load factor 0 with the
        joints' constraints, ``f`` the load vector), is below round-off of the stiffest
        coordinate: ``ρ <= ε max|diag K₀|``, ``ε`` the machine precision, both in the scaled
        coordinates of the norms (:attr:`scale`: positions over the model's size), so that the
        test does not depend on the units (in metres a 10 µm cantilever's gradients outweighed
        its positions in ``xᵀx`` and it was taken for a mechanism).  A pendulum pinned at one
        end and drawn horizontal meets ``ρ ≈ 1e-20 max|diag K₀|`` (its swing has no stiffness
        there: ``K₀`` is singular and ``x`` round-off's); a tension-free straight cable, whose
        transverse stiffness is its bending stiffness alone, ``6e-13`` (at 1 m).  A tangent
        that cannot be factored is a mechanism too; loads that do no work (``f = 0``) are not
        moved by one."""
        _, ok = self.tangent(z, 0.0)
        if not ok:
            return True
        f = self.load_vector(z, ok)
        x = self.solve(ok, f)
        if x is None:
            return True
        fy, xy, sc = f[: self.n], x[: self.n], self.scale[: self.n]
        xx = float(np.sum((xy * sc) ** 2))
        if xx == 0.0:
            return False
        diag = self._diagonal(z, 1.0, 0.0) / sc[~self.system.fixed] ** 2
        kmax = float(np.max(diag, initial=0.0))
        return bool(float(fy @ xy) / xx <= np.finfo(float).eps * kmax)

    def solve(self, ok: bool, rhs: NDArray) -> NDArray[np.float64] | None:
        """The last factored Jacobian's solution of ``rhs`` (None if it was singular)."""
        if not ok:
            return None
        out = np.array(rhs, dtype=float)
        x = out[: self.n]
        x[self._held] = 0.0
        self._integ.solve_factored(x, out[self.n :])
        return out if np.isfinite(out).all() else None

    def load_vector(self, z: NDArray, ok: bool) -> NDArray[np.float64]:
        """``-∂r/∂p`` in the current stage: ``r(p=0) - r(p=1)`` (the residual is linear in the
        load factor) while loading, central differences while the supports move."""
        if self.stage == 0:
            q = self.full_residual(z, 0.0) - self.full_residual(z, 1.0)
        else:
            h, p = 1e-6, self._p_of(z)
            zp, zm = z.copy(), z.copy()
            self.place_supports(zp, p + h)
            self.place_supports(zm, p - h)
            q = -(self.full_residual(zp, p + h) - self.full_residual(zm, p - h)) / (2 * h)
        q[self.fixed] = 0.0
        return q

    def _p_of(self, z: NDArray) -> float:
        """The path parameter of the held coordinates in ``z`` (installation stage)."""
        if not np.any(self.delta):
            return 1.0
        held = z[: self.n][self._held] - self._y0[self._held]
        k = int(np.argmax(np.abs(self.delta)))
        return 1.0 + held[k] / self.delta[k]

    def norm(self, dz: NDArray) -> float:
        return float(np.linalg.norm(dz * self.scale))

    def accept(self, z: NDArray) -> None:
        """A converged state: rods carry their nodal triads to it."""
        y = z[: self.n]
        zero = np.zeros(self.n)
        self.system.rereference(y, zero.copy(), zero.copy())
