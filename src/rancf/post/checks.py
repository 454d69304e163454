"""Warnings for likely unit mistakes: the run goes on, the warning is one line on standard error
and an entry of ``summary.json``'s ``"warnings"`` list.

* The largest axial strain over the stored states passes :data:`STRAIN_LIMIT` (10 %): e.g. a
  Young's modulus of 50 Pa meant as 50 MPa stretches a 1 m hose to several metres.
* The section's radius (``sqrt(A / π)`` for a section given by its area) exceeds
  :data:`RADIUS_LIMIT` (a tenth) of the body's reference length: e.g. 10 m meant as 10 mm.

The axial strain is the elements' own Green–Lagrange measure
(:func:`rancf.elements.cable.axial_strain`), of a cable or rod centreline at every node and
element middle, and of a beam's chords (about 1 µs per stored state of a 128-element model).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from rancf.elements.cable import axial_strain, cable_shape_functions
from rancf.model.system import Model

__all__ = [
    "STRAIN_LIMIT",
    "RADIUS_LIMIT",
    "section_warnings",
    "strain_warning",
    "StrainCheck",
    "run_warnings",
    "at_time",
    "at_load_factor",
]

#: Largest axial strain (magnitude) that passes without a warning.
STRAIN_LIMIT = 0.10
#: Largest section radius, as a fraction of the body's reference length, without a warning.
RADIUS_LIMIT = 0.1


def section_warnings(model: Model) -> list[str]:
    """A warning if the section's radius exceeds a tenth of the body's reference length."""
    r = model.section.radius
    length = float(np.sum(model.mesh.scales))  # Σ l_e: the reference arc length
    if r <= RADIUS_LIMIT * length:
        return []
    return [
        f"the section's radius {r:.4g} m is more than a tenth of the body's length "
        f"{length:.4g} m: check the units of section.radius or section.area (metres)"
    ]


def strain_warning(strain: float, when: str) -> str | None:
    """The warning for a largest axial strain ``strain`` reached ``when`` (None below 10 %)."""
    if not strain > STRAIN_LIMIT:  # NaN (a diverged state) says nothing about units
        return None
    return (
        f"the largest axial strain is {100.0 * strain:.4g} % ({when}), more than "
        f"{100.0 * STRAIN_LIMIT:g} %: check the units of material.youngs_modulus (Pa), the "
        "section (m) and the loads (N)"
    )


class StrainCheck:
    """The largest axial strain of a model's states, block by block (memory stays bounded).

    Attributes
    ----------
    largest : float
        Largest ``|ε|`` seen so far (0 before any state).
    at : float
        The time (or load factor) of that state.
    """

    def __init__(self, model: Model) -> None:
        self.model = model
        self.largest = 0.0
        self.at = 0.0
        if model.element == "beam":
            x0 = model.q0.reshape(model.n_nodes, 3)[:, :2]
            self._ref = x0[1:] - x0[:-1]
        else:  # r_ξ at an element's ends is l r_x exactly; in its middle from N_ξ(1/2)
            n1 = cable_shape_functions(model.mesh.weights, model.mesh.scales, [0.5])[1]
            self._n1 = n1[:, 0, None, :]  # (n_el, 1, 4)
            self._ref = self._tangents(model.q0[None])[0]

    def _tangents(self, q: NDArray) -> NDArray:
        """Tangents ``(k, n_nodes + n_el, dim)`` of states ``q (k, n)``: the nodal gradients,
        then ``r_ξ(1/2)`` of every element (each a multiple of ``dr/ds`` that the reference
        shares, so the strain of :func:`axial_strain` is exact there)."""
        m = self.model
        nodes = q.reshape(q.shape[0], m.n_nodes, m.dpn)[..., : 2 * m.dim]
        e = np.concatenate([nodes[:, :-1], nodes[:, 1:]], axis=2)
        e = e.reshape(q.shape[0], m.n_el, 4, m.dim)
        mid = (self._n1 @ e)[:, :, 0]  # (n_el, 1, 4) @ (k, n_el, 4, dim), batched
        return np.concatenate([nodes[..., m.dim :], mid], axis=1)

    def add(self, t: NDArray, q: NDArray) -> None:
        """Take states ``q (k, n)`` at times ``t (k,)`` into account."""
        q = np.asarray(q, dtype=float)
        if q.size == 0:
            return
        q = np.atleast_2d(q)
        t = np.atleast_1d(np.asarray(t, dtype=float))
        m = self.model
        rows = max(1, (1 << 21) // max(1, 4 * m.n * m.dim))
        for i in range(0, q.shape[0], rows):
            part = q[i : i + rows]
            if m.element == "beam":
                x = part.reshape(part.shape[0], m.n_nodes, 3)[..., :2]
                eps = axial_strain(x[:, 1:] - x[:, :-1], self._ref)
            else:
                eps = axial_strain(self._tangents(part), self._ref)
            per_state = np.abs(eps).max(axis=1)
            j = int(np.argmax(per_state))
            if per_state[j] > self.largest:
                self.largest, self.at = float(per_state[j]), float(t[i + j])

    def warning(self, when: Callable[[float], str]) -> str | None:
        """:func:`strain_warning` of the largest strain; ``when(at)`` describes its state."""
        return strain_warning(self.largest, when(self.at))


def at_time(t: float) -> str:
    """``at t = 0.5 s``."""
    return f"at t = {t:g} s"


def at_load_factor(lam: float) -> str:
    """``at load factor λ = 1``."""
    return f"at load factor λ = {lam:g}"


def run_warnings(model: Model, t: NDArray, q: NDArray, static: bool = False) -> list[str]:
    """Every warning of a run: the section's radius, and the largest axial strain of the
    states ``q (n_t, n)`` at times (or load factors, ``static``) ``t``."""
    check = StrainCheck(model)
    check.add(t, q)
    strain = check.warning(at_load_factor if static else at_time)
    return section_warnings(model) + ([strain] if strain else [])
