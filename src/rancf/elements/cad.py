"""CAD integration (Sanborn & Shabana 2009): Bézier, B-spline and NURBS ↔ (R)ANCF cable chains.

* ANCF cable ↔ cubic Bézier: their eq. 9 (:func:`rancf.elements.cable.ancf_to_bezier_matrix`).
* Cubic B-spline → chain of ANCF cable elements, one per non-zero knot span (their eq. 27),
  preserving shape and parameterization: on span ``[u_j, u_{j+1}]`` the element parameter is
  ``ξ = (u - u_j) / (u_{j+1} - u_j)`` and the gradient scale ``l_j = c (u_{j+1} - u_j)``, so the
  nodal gradient ``r_x = r_u / c`` is the same from both sides of a C¹ break point.
* NURBS of degree 2 or 3 → chain of RANCF elements (Bézier extraction in homogeneous
  coordinates, degree elevation of quadratic spans).
* A chain of ANCF/RANCF elements → one cubic NURBS: first with interior knots of multiplicity 3,
  which represents any chain exactly (adjacent segments' weights are rescaled to share the joint's
  homogeneous control point), then with every knot removed that the curve's smoothness allows
  (Piegl & Tiller A5.8), so a chain that came from a smooth curve gets its knot vector back.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import (
    bezier_from_nodal,
    bezier_to_ancf_matrix,
    cable_shape_functions,
    nodal_from_bezier,
)
from rancf.errors import InputError, WeightError
from rancf.geometry.bezier import RationalBezier, to_homogeneous
from rancf.geometry.knot_removal import remove_knots
from rancf.geometry.nurbs import NurbsCurve, extraction

__all__ = [
    "ElementChain",
    "bspline_to_ancf_matrix",
    "bspline_to_ancf",
    "nurbs_to_rancf",
    "chain_to_nurbs",
    "curves_to_chain",
]


@dataclass(frozen=True)
class ElementChain:
    """A chain of cable elements, each with its own nodal coordinates (not yet shared).

    Attributes
    ----------
    nodal : ndarray, shape (n_el, 4, dim)
        ``[rA, rA_x, rB, rB_x]`` per element.
    weights : ndarray, shape (n_el, 4)
        All ones for ANCF elements.
    scales : ndarray, shape (n_el,)
        Gradient scales ``l``.
    breakpoints : ndarray, shape (n_el + 1,)
        Curve parameter at the element ends; element ``j`` covers ``[b_j, b_{j+1}]``.
    """

    nodal: NDArray[np.float64]
    weights: NDArray[np.float64]
    scales: NDArray[np.float64]
    breakpoints: NDArray[np.float64]

    @property
    def n_elements(self) -> int:
        """Number of elements."""
        return self.nodal.shape[0]

    @property
    def dim(self) -> int:
        """Space dimension."""
        return self.nodal.shape[2]

    def element_curve(self, j: int) -> RationalBezier:
        """Rational cubic Bézier form of element ``j``."""
        return bezier_from_nodal(self.nodal[j], self.weights[j], float(self.scales[j]))

    def locate(self, u: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """Element index and ``ξ`` for curve parameters ``u``."""
        u = np.atleast_1d(np.asarray(u, dtype=float))
        b = self.breakpoints
        j = np.clip(np.searchsorted(b, u, side="right") - 1, 0, self.n_elements - 1)
        return j, (u - b[j]) / (b[j + 1] - b[j])

    def __call__(self, u: ArrayLike) -> NDArray[np.float64]:
        """Points of the chain at curve parameters ``u`` using the element shape functions."""
        j, xi = self.locate(u)
        out = np.empty((j.size, self.dim))
        for e in np.unique(j):
            sel = j == e
            n = cable_shape_functions(self.weights[e : e + 1], self.scales[e : e + 1], xi[sel])[0]
            out[sel] = n[0] @ self.nodal[e]
        return out


def bspline_to_ancf_matrix(
    knots: ArrayLike, n_ctrl: int, length_scale: float = 1.0
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Linear map from cubic B-spline control points to ANCF nodal coordinates (S&S eq. 27).

    Returns
    -------
    matrix : ndarray, shape (4 n_el, n_ctrl)
        Rows ``4 j + (0, 1, 2, 3)`` give ``rA, rA_x, rB, rB_x`` of element ``j`` (per coordinate).
    scales : ndarray, shape (n_el,)
        ``l_j = c (u_{j+1} - u_j)``.
    breakpoints : ndarray, shape (n_el + 1,)
    """
    c = _check_scale(length_scale)
    breaks, ops = extraction(knots, 3, n_ctrl)
    scales = c * np.diff(breaks)
    blocks = [bezier_to_ancf_matrix(s) @ op for s, op in zip(scales, ops, strict=True)]
    return np.vstack(blocks), scales, breaks


def bspline_to_ancf(curve: NurbsCurve, length_scale: float = 1.0) -> ElementChain:
    """Every non-zero knot span of a cubic B-spline as one ANCF cable element (S&S sec. 6)."""
    if curve.degree != 3:
        raise InputError("degree", curve.degree, "a cubic B-spline (degree 3); use nurbs_to_rancf")
    if not np.all(curve.weights == curve.weights[0]):
        raise WeightError(
            "weights", curve.weights, "equal weights for a B-spline; use nurbs_to_rancf for NURBS"
        )
    mat, scales, breaks = bspline_to_ancf_matrix(curve.knots, curve.n_ctrl, length_scale)
    nodal = (mat @ curve.points).reshape(-1, 4, curve.dim)
    return ElementChain(nodal, np.ones((nodal.shape[0], 4)), scales, breaks)


def curves_to_chain(
    curves: list[RationalBezier], breakpoints: ArrayLike, length_scale: float = 1.0
) -> ElementChain:
    """Rational cubic (or quadratic, elevated) Bézier segments as RANCF elements.

    Each segment's weights are scaled so that ``w0 = 1`` (a common factor leaves the curve and
    its parameterization unchanged); ``l_j = c (b_{j+1} - b_j)``.
    """
    c = _check_scale(length_scale)
    b = np.asarray(breakpoints, dtype=float)
    scales = c * np.diff(b)
    nodal, weights = [], []
    for seg, s in zip(curves, scales, strict=True):
        cub = seg
        while cub.degree < 3:
            cub = cub.elevated()
        if cub.degree != 3:
            raise InputError("degree", seg.degree, "segments of degree 2 or 3")
        cub = RationalBezier(cub.points, cub.weights / cub.weights[0])
        nodal.append(nodal_from_bezier(cub, float(s)))
        weights.append(cub.weights)
    return ElementChain(np.array(nodal), np.array(weights), scales, b)


def nurbs_to_rancf(curve: NurbsCurve, length_scale: float = 1.0) -> ElementChain:
    """A NURBS curve of degree 2 or 3 as a chain of RANCF cable elements, one per span."""
    if curve.degree not in (2, 3):
        raise InputError("degree", curve.degree, "a NURBS curve of degree 2 or 3")
    breaks, segments = curve.bezier_segments()
    return curves_to_chain(segments, breaks, length_scale)


def chain_to_nurbs(chain: ElementChain) -> NurbsCurve:
    """One cubic NURBS curve that represents a chain of (R)ANCF elements exactly, with the lowest
    interior knot multiplicities that do.

    First knots ``[b0]*4 + [b1]*3 + ... + [bn]*4``: every interior break point has multiplicity
    3, so each span is exactly one element's rational cubic (element ``j + 1``'s weights scaled
    so its first homogeneous control point equals element ``j``'s last); then
    :func:`~rancf.geometry.knot_removal.remove_knots` lowers each multiplicity as far as the
    curve stays the same to 1e-12 (the Sanborn & Shabana Fig. 5 knot vector comes back as
    itself from its ANCF chain).

    Raises
    ------
    InputError
        If adjacent elements do not meet (the chain is not C⁰).
    """
    hpts: list[NDArray] = []
    factor = 1.0
    for j in range(chain.n_elements):
        seg = chain.element_curve(j)
        h = to_homogeneous(seg.points, seg.weights)
        if j > 0:
            prev = hpts[-1]
            gap = np.linalg.norm(h[0, :-1] / h[0, -1] - prev[:-1] / prev[-1])
            size = max(np.abs(chain.nodal[:, [0, 2]]).max(), 1e-300)
            if gap > 1e-9 * size:
                raise InputError(
                    "chain",
                    f"gap {gap:.3g} at element {j}",
                    "adjacent elements must share end points",
                )
            factor = prev[-1] / h[0, -1]
            h = h * factor
            hpts.extend(h[1:])
        else:
            hpts.extend(h)
    b = chain.breakpoints
    knots = np.concatenate([[b[0]] * 4, np.repeat(b[1:-1], 3), [b[-1]] * 4])
    h = np.array(hpts)
    return remove_knots(NurbsCurve(3, knots, h[:, :-1] / h[:, -1:], h[:, -1]))


def _check_scale(c: float) -> float:
    cf = float(c)
    if not (np.isfinite(cf) and cf > 0.0):
        raise InputError("length_scale", c, "a finite number > 0")
    return cf
