"""Quantities derived from stored states: support reactions and section values along the body.

A run stores its states ``(t, q, v, a)`` (and, for rods, the nodal directors ``m1``, which the
coordinates alone do not fix).  :class:`DerivedOutputs` turns rows of them into the reactions of
every support (:mod:`rancf.model.reactions`, residual of the held rows) and the section
quantities at the sample points (:mod:`rancf.model.sections`).  Dynamic rows use the residual of
the equations of motion ``M a + c M v + f_int(y) - f_ext(t, y)``; static rows (the load path,
``t`` = the load factor ``λ``) ``f_int(y) - λ f_ext(y)``.

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

    @property
    def n_points(self) -> int:
        """Section sample points."""
        return self.sampler.n_points

    def rows(
        self,
        t: NDArray,
        q: NDArray,
        v: NDArray | None = None,
        a: NDArray | None = None,
        directors: NDArray | None = None,
        static: bool = False,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Reactions ``(k, n_reaction_columns)`` and section values ``(k, n_points, n_names)``
        of ``k`` rows (``q, v, a (k, n_q)``, rods' ``directors (k, n_nodes, 3)`` or flat)."""
        m = self.model
        t = np.atleast_1d(np.asarray(t, dtype=float))
        k = t.size
        q = np.asarray(q, dtype=float).reshape(k, -1)
        reactions = np.empty((k, len(self.reaction_names)))
        along = np.empty((k, self.n_points, len(self.section_names)))
        with self._triads() as set_row:
            for i in range(k):
                y = m.y_from_q(q[i])
                if m.element == "rod" and directors is not None:
                    set_row(q[i], np.asarray(directors[i]).reshape(-1, 3))
                    y.reshape(m.n_nodes, m.dpn)[:, 6] = 0.0
                if static:
                    res = m.internal_force(y) - t[i] * m.external_force(0.0, y, True)
                else:
                    res = m.internal_force(y) - m.external_force(float(t[i]), y)
                    if a is not None:
                        res += m.mass_times(m.y_from_q(np.asarray(a[i], dtype=float)))
                    if v is not None and m.damping:
                        res += m.damping * m.mass_times(m.y_from_q(np.asarray(v[i], dtype=float)))
                reactions[i] = reaction_row(support_reactions(m, y, res, self.labels))
                along[i] = self.sampler.values(y)
        return reactions, along

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
