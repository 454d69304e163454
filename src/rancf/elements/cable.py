"""Shape functions of the RANCF cable element and its classical ANCF special case.

The cable element interpolates ``r(ξ) = S(ξ) e`` with nodal coordinates
``e = [rA, rA_x, rB, rB_x]`` (each a ``dim``-vector) and ``S = [N0 I, N1 I, N2 I, N3 I]``.
For the rational element (conic-section paper eqs. 17–22; docs/derivations/cable.md sec. 3)

    N0 = R0 + R1,  N1 = (l w0 / (3 w1)) R1,  N2 = R2 + R3,  N3 = -(l w3 / (3 w2)) R2

with ``R_i = w_i B_i / Σ_j w_j B_j`` the rational cubic Bernstein basis and ``l`` a gradient
scale.  With all weights 1 these are the Hermite shape functions of the classical ANCF cable
(Sanborn & Shabana 2009, eq. 8).

Shape conventions: ``weights`` ``(n_el, 4)``, ``scales`` ``(n_el,)``, parameters ``xi``
``(n_qp,)``; scalar shape functions are returned as ``(n_el, n_qp, 4)``.  Nodal coordinates of
one element are stored as ``(4, dim)`` (rows ``rA, rA_x, rB, rB_x``) or flattened to
``(4 dim,)`` in that order.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError, WeightError
from rancf.geometry.bezier import RationalBezier, bernstein

__all__ = [
    "axial_strain",
    "rational_basis",
    "cable_shape_functions",
    "ancf_shape_functions",
    "control_to_nodal_matrix",
    "nodal_to_control_matrix",
    "nodal_from_bezier",
    "bezier_from_nodal",
    "ancf_to_bezier_matrix",
    "bezier_to_ancf_matrix",
]


def axial_strain(d1: ArrayLike, d10: ArrayLike) -> NDArray[np.float64]:
    """Green–Lagrange axial strain ``ε = (|r'|² − |r0'|²) / (2 |r0'|²)`` of tangents ``d1``
    against the reference tangents ``d10`` (coordinates on the last axis; broadcast).

    The strain measure of every element (cable and rod centrelines; a beam's chords), as the
    compiled kernels use it (docs/derivations/cable.md sec. 3).
    """
    d1, d10 = np.asarray(d1, dtype=float), np.asarray(d10, dtype=float)
    g, g0 = np.sum(d1 * d1, axis=-1), np.sum(d10 * d10, axis=-1)
    return (g - g0) / (2.0 * g0)


def _as_weights(weights: ArrayLike) -> NDArray[np.float64]:
    w = np.atleast_2d(np.asarray(weights, dtype=float))
    if w.shape[-1] != 4:
        raise InputError("weights", w.shape, "four weights per cubic element")
    if not np.all(np.isfinite(w)) or np.any(w <= 0.0):
        raise WeightError("weights", w, "every weight must be finite and > 0")
    return w


def rational_basis(weights: ArrayLike, xi: ArrayLike) -> list[NDArray[np.float64]]:
    """Rational cubic basis ``R_i`` and its first two derivatives (docs/derivations/cable.md sec.
    3).

    ``R = w B / D``, ``R' = (w B' - R D') / D``, ``R'' = (w B'' - 2 R' D' - R D'') / D``,
    ``D = Σ w_j B_j``.

    Parameters
    ----------
    weights : array_like, shape (n_el, 4)
    xi : array_like, shape (n_qp,)

    Returns
    -------
    list of 3 ndarrays, each (n_el, n_qp, 4)
    """
    w = _as_weights(weights)[:, None, :]
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    b0, b1, b2 = (bernstein(3, xi, k)[None, :, :] for k in range(3))
    d0 = np.sum(w * b0, axis=-1, keepdims=True)
    d1 = np.sum(w * b1, axis=-1, keepdims=True)
    d2 = np.sum(w * b2, axis=-1, keepdims=True)
    r0 = w * b0 / d0
    r1 = (w * b1 - r0 * d1) / d0
    r2 = (w * b2 - 2.0 * r1 * d1 - r0 * d2) / d0
    return [r0, r1, r2]


def cable_shape_functions(
    weights: ArrayLike, scales: ArrayLike, xi: ArrayLike
) -> list[NDArray[np.float64]]:
    """Scalar RANCF cable shape functions ``N_k`` and their ξ-derivatives.

    Parameters
    ----------
    weights : array_like, shape (n_el, 4)
    scales : array_like, shape (n_el,)
        Gradient scales ``l`` (the element "length").
    xi : array_like, shape (n_qp,)

    Returns
    -------
    list of 3 ndarrays, each (n_el, n_qp, 4)
        ``[N, N_ξ, N_ξξ]``; ``r^(j)(ξ) = Σ_k N^(j)_k e_k``.
    """
    w = _as_weights(weights)
    scale = np.atleast_1d(np.asarray(scales, dtype=float))
    c1 = (scale * w[:, 0] / (3.0 * w[:, 1]))[:, None]
    c3 = -(scale * w[:, 3] / (3.0 * w[:, 2]))[:, None]
    out = []
    for r in rational_basis(w, xi):
        n = np.empty_like(r)
        n[..., 0] = r[..., 0] + r[..., 1]
        n[..., 1] = c1 * r[..., 1]
        n[..., 2] = r[..., 2] + r[..., 3]
        n[..., 3] = c3 * r[..., 2]
        out.append(n)
    return out


def ancf_shape_functions(scale: float, xi: ArrayLike) -> NDArray[np.float64]:
    """Classical ANCF cable (Hermite) shape functions (Sanborn & Shabana 2009, eq. 8).

    ``[1 - 3ξ² + 2ξ³, l(ξ - 2ξ² + ξ³), 3ξ² - 2ξ³, l(-ξ² + ξ³)]``, shape ``(n_qp, 4)``.
    """
    x = np.atleast_1d(np.asarray(xi, dtype=float))
    return np.stack(
        [
            1 - 3 * x**2 + 2 * x**3,
            scale * (x - 2 * x**2 + x**3),
            3 * x**2 - 2 * x**3,
            scale * (x**3 - x**2),
        ],
        axis=-1,
    )


def control_to_nodal_matrix(weights: ArrayLike, scale: float) -> NDArray[np.float64]:
    """4×4 matrix ``T`` with ``e = T Q`` (rows ``rA, rA_x, rB, rB_x``; docs/derivations/cable.md
    sec. 3).

    ``rA = Q0``, ``rA_x = 3 (w1/w0)(Q1 - Q0)/l``, ``rB = Q3``, ``rB_x = 3 (w2/w3)(Q3 - Q2)/l``.
    Acts on each coordinate; use ``np.kron(T, I_dim)`` for flattened nodal vectors.
    """
    w = _as_weights(weights)[0]
    a = 3.0 * w[1] / (w[0] * scale)
    b = 3.0 * w[2] / (w[3] * scale)
    return np.array([[1.0, 0, 0, 0], [-a, a, 0, 0], [0, 0, 0, 1.0], [0, 0, -b, b]])


def nodal_to_control_matrix(weights: ArrayLike, scale: float) -> NDArray[np.float64]:
    """Inverse of :func:`control_to_nodal_matrix`.

    ``Q1 = rA + l w0 rA_x / (3 w1)``, ``Q2 = rB - l w3 rB_x / (3 w2)``.
    """
    w = _as_weights(weights)[0]
    a = scale * w[0] / (3.0 * w[1])
    b = scale * w[3] / (3.0 * w[2])
    return np.array([[1.0, 0, 0, 0], [1.0, a, 0, 0], [0, 0, 1.0, -b], [0, 0, 1.0, 0]])


def ancf_to_bezier_matrix(scale: float) -> NDArray[np.float64]:
    """Sanborn & Shabana (2009) eq. 9 inverted: cubic Bézier points from ANCF nodal coordinates."""
    return nodal_to_control_matrix(np.ones(4), scale)


def bezier_to_ancf_matrix(scale: float) -> NDArray[np.float64]:
    """Sanborn & Shabana (2009) eq. 9: ANCF nodal coordinates from cubic Bézier points."""
    return control_to_nodal_matrix(np.ones(4), scale)


def nodal_from_bezier(curve: RationalBezier, scale: float) -> NDArray[np.float64]:
    """Nodal coordinates ``(4, dim)`` of the element whose curve is the rational cubic ``curve``."""
    if curve.degree != 3:
        raise InputError("curve.degree", curve.degree, "a cubic (degree 3) rational Bézier curve")
    return control_to_nodal_matrix(curve.weights, scale) @ curve.points


def bezier_from_nodal(nodal: ArrayLike, weights: ArrayLike, scale: float) -> RationalBezier:
    """Rational cubic Bézier curve of an element with nodal coordinates ``(4, dim)``."""
    e = np.asarray(nodal, dtype=float)
    return RationalBezier(nodal_to_control_matrix(weights, scale) @ e, np.asarray(weights, float))
