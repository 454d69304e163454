"""Quantities derived from stored states: accelerations, support reactions and section values.

A run stores its states ``(t, q, v)`` (and, for rods, the nodal directors ``m1``, which the
coordinates alone do not fix).  :class:`DerivedOutputs` turns rows of them into

* the accelerations consistent with the state, ``a = M(y)⁻¹ (f_ext(t, y) - f_int(y) - c M v -
  g(y, v))`` on the free coordinates (zero on the held ones; ``M(y)`` and the gyroscopic
  ``g`` include a rod's rotary inertia);
* the reactions of every support (:mod:`rancf.model.reactions`): the held rows of the residual
  ``F_in(y, v, a) + f_int(y) - f_ext(t, y)`` with the inertial force
  ``F_in = M(y) a + g(y, v) + c M v``;
* the section quantities at the sample points (:mod:`rancf.model.sections`).

Static rows (the load path, ``t`` the path parameter ``p`` with the loads at ``min(p, 1)``) have
``a = v = 0`` and the residual ``f_int(y) - λ f_ext(y)``.

Why not the integrator's own acceleration: in generalized-α ``a_{n+1}`` approximates the
acceleration at ``t_{n+1} + (α_m - α_f) h`` (Arnold & Brüls 2007), a first-order shift for
``ρ∞ < 1``; the consistent acceleration of the stored ``(y, v)`` has only their error, so the
reactions converge at second order.

Rods: each row is evaluated with the nodal triads of that row (tangent from ``q``, director
``m1`` stored, twist ``φ = 0`` relative to it); the model's own triads are restored afterwards.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator, Sequence

import numpy as np
from numpy.typing import NDArray

from rancf.model.reactions import reaction_columns, reaction_row, support_reactions
from rancf.model.sections import SectionSampler, section_names
from rancf.model.system import Model

__all__ = ["DerivedOutputs"]


class DerivedOutputs:
    """Reactions and section values of rows of stored states.

    Parameters
    ----------
    model : Model
    labels : sequence, optional
        The supports' ``at`` as the user wrote it (reaction column names).
    per_element : int
        Section sample points per element.
    """

    def __init__(
        self, model: Model, labels: Sequence[int | str] | None = None, per_element: int = 4
    ) -> None:
        self.model = model
        self.labels = None if labels is None else list(labels)
        self.sampler = SectionSampler(model, per_element)
        self.reaction_names = reaction_columns(model, self.labels)
        self.section_names = section_names(model)
        self._mass_factor: NDArray | None = None
        #: The largest |axial strain| of the rows seen so far, and the ``t`` of its row.
        self.largest_strain: tuple[float, float] = (0.0, 0.0)

    @property
    def n_points(self) -> int:
        """Section sample points."""
        return self.sampler.n_points

    def inertial_force(self, y: NDArray, v: NDArray, a: NDArray) -> NDArray[np.float64]:
        """``F_in(y, v, a) = M(y) a + g(y, v) + c M v`` (model coordinates)."""
        m = self.model
        f = m.mass_times(a) + m.damping * m.mass_times(v)
        if m.element == "rod":  # the rotary inertia: M_r(y) a + g(y, v) + c M_r(y) v
            fr, ab = np.empty(m.n), np.empty_like(m.mass_band)
            m.core.inertia(y, v, a, m.damping, 0.0, 0.0, 0.0, fr, ab)
            f += fr
        return f

    def acceleration(self, t: float, y: NDArray, v: NDArray) -> NDArray[np.float64]:
        """``M(y)⁻¹ (f_ext(t, y) - f_int(y) - F_in(y, v, 0))`` on the free coordinates (model
        coordinates); for cables and beams the Cholesky factor of the constant mass matrix is
        computed once."""
        import scipy.linalg

        m = self.model
        rhs = m.external_force(float(t), y) - m.internal_force(y)
        rhs -= self.inertial_force(y, v, np.zeros(m.n))
        rhs[m.fixed] = 0.0
        if m.element == "rod":
            from rancf.kernels import _core

            a = rhs.copy()
            if not _core.band_solve(m.mass_matrix(y), a, m.fixed.astype(np.uint8)):
                return np.full(m.n, np.nan)
            return a
        if self._mass_factor is None:
            ab = m.mass_band[: m.ku + 1].copy()  # upper band storage of the symmetric M
            held = np.flatnonzero(m.fixed)
            for k in range(m.ku + 1):  # held rows and columns replaced by the identity
                off = m.ku - k
                ab[k, held] = 0.0
                cols = held + off
                ab[k, cols[cols < m.n]] = 0.0
            ab[m.ku, held] = 1.0
            self._mass_factor = scipy.linalg.cholesky_banded(ab)
        return scipy.linalg.cho_solve_banded((self._mass_factor, False), rhs)

    def rows(
        self,
        t: NDArray,
        q: NDArray,
        v: NDArray | None = None,
        directors: NDArray | None = None,
        static: bool = False,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Accelerations ``(k, n_q)`` (full coordinates), reactions ``(k, n_reaction_columns)``
        and section values ``(k, n_points, n_names)`` of ``k`` rows (``q, v (k, n_q)``, rods'
        ``directors (k, n_nodes, 3)`` or flat)."""
        m = self.model
        t = np.atleast_1d(np.asarray(t, dtype=float))
        k = t.size
        q = np.asarray(q, dtype=float).reshape(k, -1)
        acc = np.zeros((k, m.n))
        reactions = np.empty((k, len(self.reaction_names)))
        along = np.empty((k, self.n_points, len(self.section_names)))
        with self._triads() as set_row:
            for i in range(k):
                y = m.y_from_q(q[i])
                if m.element == "rod" and directors is not None:
                    set_row(q[i], np.asarray(directors[i]).reshape(-1, 3))
                    y.reshape(m.n_nodes, m.dpn)[:, 6] = 0.0
                if static:
                    lam = min(float(t[i]), 1.0)
                    res = m.internal_force(y) - lam * m.external_force(0.0, y, True)
                else:
                    vy = np.zeros(m.n) if v is None else m.y_from_q(np.asarray(v[i], dtype=float))
                    a = self.acceleration(float(t[i]), y, vy)
                    acc[i] = m.q_from_y(a)
                    res = m.internal_force(y) - m.external_force(float(t[i]), y)
                    res += self.inertial_force(y, vy, a)
                reactions[i] = reaction_row(support_reactions(m, y, res, self.labels))
                along[i] = self.sampler.values(y)
                strain = float(np.max(np.abs(along[i, :, 0])))
                if strain > self.largest_strain[0]:  # NaN (a diverged state) is never larger
                    self.largest_strain = (strain, float(t[i]))
        return acc, reactions, along

    @contextlib.contextmanager
    def _triads(self) -> Iterator:
        """Rods: a setter of the triads of a row; the model's triads are restored at the end."""
        m = self.model
        if m.element != "rod":
            yield lambda q, m1: None
            return
        kern = m.kernel
        saved = kern.tref.copy(), kern.m1ref.copy()

        def set_row(q: NDArray, m1: NDArray) -> None:
            g = q.reshape(m.n_nodes, m.dpn)[:, 3:6]
            kern.tref[...] = (g / np.linalg.norm(g, axis=1, keepdims=True)).reshape(kern.tref.shape)
            kern.m1ref[...] = m1.reshape(kern.m1ref.shape)

        try:
            yield set_row
        finally:
            kern.tref[...] = saved[0]
            kern.m1ref[...] = saved[1]
