"""Ingredients of conic arcs in standard form: the tangent intersection, barycentric coordinates,
the interior weight, and the mapping factor ``K`` with its parameter maps.

The standard quadratic rational form and its cubic forms are described in
:mod:`rancf.geometry.conic` (paper eq. 6, 12 and 15; docs/derivations/cable.md sec. 1 and 2). These
functions
serve the :class:`~rancf.geometry.conic_curve.Conic` class, the arc constructors in
:mod:`rancf.geometry.conic`, the element mapping and the meshes.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import MappingFactorError

__all__ = [
    "cross2",
    "pad3",
    "tangent_intersection",
    "barycentric",
    "weight_from_point",
    "check_mapping_factor",
    "mapping_rho",
    "quadratic_parameter",
    "cubic_parameter",
]


def pad3(a: ArrayLike) -> NDArray:
    """Planar vectors ``(..., 2)`` as spatial ones ``(..., 3)`` with ``z = 0``; spatial ones are
    returned as they are (as float arrays)."""
    v = np.asarray(a, dtype=float)
    return v if v.shape[-1] == 3 else np.concatenate([v, np.zeros(v.shape[:-1] + (1,))], axis=-1)


def cross2(a: NDArray, b: NDArray) -> NDArray:
    """Planar cross product ``a_x b_y - a_y b_x`` over the last axis.

    Parameters
    ----------
    a, b : ndarray, shape (..., 2)
        Planar vectors (broadcast against each other).

    Returns
    -------
    ndarray, shape (...)
        Twice the signed area of the triangle spanned by ``a`` and ``b``.
    """
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def tangent_intersection(chord: float, theta0: float, theta1: float) -> NDArray[np.float64]:
    """``P1``, the meeting point of the end tangents in the local frame (docs/derivations/cable.md
    sec. 1).

    ``P1 = (L tanθ1 / (tanθ0 + tanθ1), L tanθ0 tanθ1 / (tanθ0 + tanθ1))`` with angles in
    radians.
    """
    t0, t1 = np.tan(theta0), np.tan(theta1)
    return np.array([chord * t1 / (t0 + t1), chord * t0 * t1 / (t0 + t1)])


def barycentric(point: ArrayLike, p0: ArrayLike, p1: ArrayLike, p2: ArrayLike) -> NDArray:
    """Barycentric coordinates of planar points from signed areas (paper eq. 6).

    Returns
    -------
    ndarray, shape (..., 3)
        ``(λ0, λ1, λ2)`` with ``λ0 + λ1 + λ2 = 1``.
    """
    p = np.asarray(point, dtype=float)
    a, b, c = (np.asarray(x, dtype=float) for x in (p0, p1, p2))
    s = cross2(b - a, c - a)
    l0 = cross2(b - p, c - p) / s
    l1 = cross2(c - p, a - p) / s
    l2 = cross2(a - p, b - p) / s
    return np.stack([l0, l1, l2], axis=-1)


def weight_from_point(lam: ArrayLike) -> float:
    """Interior weight ``ω = λ1 / (2 sqrt(λ0 λ2))`` of the standard form (paper eq. 12)."""
    l0, l1, l2 = np.asarray(lam, dtype=float)
    return float(l1 / (2.0 * np.sqrt(l0 * l2)))


def check_mapping_factor(k: float | str, name: str = "k") -> float:
    """Validate a mapping factor ``K ∈ (0, 1)`` and return it as a float."""
    try:
        kf = float(k)
    except (TypeError, ValueError):
        raise MappingFactorError(
            name, k, "the mapping factor K must be a number in (0, 1)"
        ) from None
    if not (0.0 < kf < 1.0):
        raise MappingFactorError(
            name, k, "the mapping factor K must lie in the open interval (0, 1)"
        )
    return kf


def mapping_rho(k: float) -> float:
    """Möbius factor ``ρ = (K / (1 - K))^(1/3)`` of the mapping factor (docs/derivations/cable.md
    sec. 2)."""
    k = check_mapping_factor(k)
    return float(np.cbrt(k / (1.0 - k)))


def quadratic_parameter(xi: ArrayLike, k: float) -> NDArray[np.float64]:
    """``u(ξ) = ρ ξ / (1 - ξ + ρ ξ)`` for mapping factor ``K`` (docs/derivations/cable.md sec.
    2)."""
    rho = mapping_rho(k)
    xi = np.asarray(xi, dtype=float)
    return rho * xi / (1.0 - xi + rho * xi)


def cubic_parameter(u: ArrayLike, k: float) -> NDArray[np.float64]:
    """Inverse of :func:`quadratic_parameter`: ``ξ(u) = u / (ρ (1 - u) + u)``."""
    rho = mapping_rho(k)
    u = np.asarray(u, dtype=float)
    return u / (rho * (1.0 - u) + u)
