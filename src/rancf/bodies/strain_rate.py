"""Kelvin-Voigt strain-rate damping of a flexible body (:class:`rancf.StrainRateDamping`): its
force and Jacobians from the compiled core (docs/derivations/strain-rate-damping.md)."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["damping_force"]


def damping_force(
    model: Any, y: ArrayLike, v: ArrayLike, ck: float | None = None, cv: float = 0.0
) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The damping force ``f_d(y, v)`` of a model's strain rates (eq. 3).

    Parameters
    ----------
    model : rancf.bodies.flexible.Model
    y, v : array_like, shape ``(n,)``
        Model coordinates and velocities.
    ck, cv : float, optional
        With ``ck``, also the Jacobian ``ck ∂f_d/∂y + cv ∂f_d/∂v`` (eqs. 5, 4).

    Returns
    -------
    ndarray or (ndarray, ndarray)
        ``f_d`` ``(n,)``; with ``ck``, ``(f_d, ab)``, ``ab`` the Jacobian in band storage
        ``(2 ku + 1, n)`` (:meth:`~rancf.mesh.coordinates.Coordinates.dense` unpacks it).
    """
    yy, vv = np.asarray(y, dtype=float), np.asarray(v, dtype=float)
    f = np.empty(model.n)
    if ck is None:
        model.core.damping_force(yy, vv, f)
        return f
    ab = np.empty((2 * model.ku + 1, model.n))
    model.core.damping_force(yy, vv, f, ab, ck=ck, cv=cv)
    return f, ab
