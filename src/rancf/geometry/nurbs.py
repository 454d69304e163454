"""B-spline and NURBS curves: validation, evaluation, knot insertion and Bézier extraction.

Shape conventions: ``knots`` ``(n_ctrl + degree + 1,)``, control points ``(n_ctrl, dim)``,
weights ``(n_ctrl,)``.  The curve is defined on ``[knots[degree], knots[n_ctrl]]``; knot vectors
need not be clamped (Sanborn & Shabana 2009, sec. 6: the first and last knot are never used).

Knot insertion (Boehm; Piegl & Tiller, *The NURBS Book*, A5.1) is expressed as a matrix acting on
control points, so that Bézier extraction is a checkable linear map ``C`` with
``bezier_points = C @ control_points``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError, KnotVectorError, WeightError
from rancf.geometry.bezier import RationalBezier, to_homogeneous

__all__ = ["check_knots", "insertion_matrix", "extraction", "NurbsCurve", "basis_functions"]


def check_knots(knots: ArrayLike, degree: int, n_ctrl: int) -> NDArray[np.float64]:
    """Validate a knot vector and return it as a float array.

    Raises
    ------
    KnotVectorError
        If it decreases anywhere, has the wrong length, an interior knot of multiplicity above
        ``degree``, or an empty curve domain.
    """
    try:
        u = np.asarray(knots, dtype=float).ravel()
    except (TypeError, ValueError):
        raise KnotVectorError("knots", knots, "a sequence of numbers") from None
    if not np.all(np.isfinite(u)):
        raise KnotVectorError("knots", u, "finite numbers")
    if u.size != n_ctrl + degree + 1:
        raise KnotVectorError(
            "knots",
            u,
            f"{n_ctrl + degree + 1} knots for {n_ctrl} control points of degree {degree}",
        )
    d = np.diff(u)
    if np.any(d < 0.0):
        i = int(np.argmax(d < 0.0))
        raise KnotVectorError(
            "knots",
            u,
            f"a non-decreasing sequence (knot {i + 1} = {u[i + 1]:g} < knot {i} = {u[i]:g})",
        )
    a, b = u[degree], u[n_ctrl]
    if not b > a:
        raise KnotVectorError("knots", u, f"a non-empty domain [knots[{degree}], knots[{n_ctrl}]]")
    interior = u[(u > a) & (u < b)]
    if interior.size:
        vals, counts = np.unique(interior, return_counts=True)
        if counts.max() > degree:
            raise KnotVectorError(
                "knots",
                u,
                f"interior knots of multiplicity at most {degree} (knot {vals[counts.argmax()]:g} "
                f"repeats {counts.max()} times)",
            )
    return u


def _insert_once(knots: NDArray, ctrl: NDArray, degree: int, u: float) -> tuple[NDArray, NDArray]:
    """Insert knot ``u`` once (Boehm); ``ctrl`` rows are control points (any width)."""
    p = degree
    k = int(np.searchsorted(knots, u, side="right") - 1)  # knots[k] <= u < knots[k+1]
    s = int(np.sum(knots == u))
    n = ctrl.shape[0]
    new = np.empty((n + 1, ctrl.shape[1]))
    new[: k - p + 1] = ctrl[: k - p + 1]
    for i in range(k - p + 1, k - s + 1):
        alpha = (u - knots[i]) / (knots[i + p] - knots[i])
        new[i] = alpha * ctrl[i] + (1.0 - alpha) * ctrl[i - 1]
    new[k - s + 1 :] = ctrl[k - s :]
    return np.insert(knots, k + 1, u), new


def insertion_matrix(
    knots: ArrayLike, degree: int, n_ctrl: int, values: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Knot insertion as a matrix: ``(new_knots, A)`` with ``new_ctrl = A @ ctrl``."""
    u = check_knots(knots, degree, n_ctrl)
    a = np.eye(n_ctrl)
    for v in np.atleast_1d(np.asarray(values, dtype=float)):
        u, a = _insert_once(u, a, degree, float(v))
    return u, a


def extraction(
    knots: ArrayLike, degree: int, n_ctrl: int
) -> tuple[NDArray[np.float64], list[NDArray[np.float64]]]:
    """Bézier extraction of every non-zero knot span of the curve domain.

    Every distinct knot in ``[a, b]`` (``a = knots[degree]``, ``b = knots[n_ctrl]``) is raised to
    multiplicity ``degree``; then each span's ``degree + 1`` control points are its Bézier points.

    Returns
    -------
    breakpoints : ndarray, shape (n_spans + 1,)
        Distinct knot values bounding the non-zero spans.
    operators : list of ndarray, each (degree + 1, n_ctrl)
        ``C_e`` with ``bezier_points_e = C_e @ control_points`` (apply to homogeneous points for
        NURBS).
    """
    u = check_knots(knots, degree, n_ctrl)
    p = degree
    a, b = u[p], u[n_ctrl]
    breaks = np.unique(u[(u >= a) & (u <= b)])
    to_insert = []
    for v in breaks:
        if v == a or v == b:
            # only the inner side matters: raise to multiplicity p counting knots within [a, b]
            s = int(np.sum(u == v))
            need = p - s
        else:
            need = p - int(np.sum(u == v))
        to_insert += [v] * max(need, 0)
    new_knots, mat = insertion_matrix(u, p, n_ctrl, to_insert)
    ops = []
    for j in range(breaks.size - 1):
        lo = breaks[j]
        k = int(np.searchsorted(new_knots, lo, side="right") - 1)  # last index with knot == lo
        ops.append(mat[k - p : k + 1])
    return breaks, ops


def basis_functions(knots: ArrayLike, degree: int, n_ctrl: int, u: ArrayLike) -> NDArray:
    """All B-spline basis functions at ``u`` (Cox–de Boor), shape ``(n_u, n_ctrl)``.

    At the right end of the domain the left limit is taken.
    """
    kn = np.asarray(knots, dtype=float)
    x = np.atleast_1d(np.asarray(u, dtype=float))
    p = degree
    a, b = kn[p], kn[n_ctrl]
    span = np.searchsorted(kn, x, side="right") - 1
    span = np.clip(span, p, n_ctrl - 1)
    # left limit at b
    span = np.where(x >= b, np.searchsorted(kn, b, side="left") - 1, span)
    out = np.zeros((x.size, n_ctrl))
    for m, (xx, k) in enumerate(zip(x, span, strict=True)):
        n = np.zeros(p + 1)
        left = np.zeros(p + 1)
        right = np.zeros(p + 1)
        n[0] = 1.0
        for j in range(1, p + 1):
            left[j] = xx - kn[k + 1 - j]
            right[j] = kn[k + j] - xx
            saved = 0.0
            for r in range(j):
                tmp = n[r] / (right[r + 1] + left[j - r])
                n[r] = saved + right[r + 1] * tmp
                saved = left[j - r] * tmp
            n[j] = saved
        out[m, k - p : k + 1] = n
    del a
    return out


@dataclass(frozen=True)
class NurbsCurve:
    """A NURBS curve ``r(u) = Σ N_i(u) w_i P_i / Σ N_i(u) w_i`` (Sanborn & Shabana eq. 28).

    Attributes
    ----------
    degree : int
    knots : ndarray, shape (n_ctrl + degree + 1,)
    points : ndarray, shape (n_ctrl, dim)
    weights : ndarray, shape (n_ctrl,)
        All ones for a (non-rational) B-spline.
    """

    degree: int
    knots: NDArray[np.float64]
    points: NDArray[np.float64]
    weights: NDArray[np.float64]

    def __post_init__(self) -> None:
        if int(self.degree) != self.degree or self.degree < 1:
            raise InputError("degree", self.degree, "a positive integer")
        p = np.array(self.points, dtype=float)
        if p.ndim != 2 or p.shape[0] < self.degree + 1:
            raise InputError(
                "points", p.shape, f"at least {self.degree + 1} control points of shape (n, dim)"
            )
        w = np.array(self.weights, dtype=float).ravel()
        if w.size != p.shape[0]:
            raise WeightError("weights", w, f"{p.shape[0]} weights, one per control point")
        if not np.all(np.isfinite(w)) or np.any(w <= 0.0):
            raise WeightError("weights", w, "every weight must be finite and > 0")
        u = check_knots(self.knots, self.degree, p.shape[0])
        for name, arr in (("knots", u), ("points", p), ("weights", w)):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "degree", int(self.degree))

    @classmethod
    def bspline(cls, degree: int, knots: ArrayLike, points: ArrayLike) -> NurbsCurve:
        """A non-rational B-spline (all weights 1)."""
        p = np.asarray(points, dtype=float)
        return cls(degree, np.asarray(knots, dtype=float), p, np.ones(p.shape[0]))

    @property
    def n_ctrl(self) -> int:
        """Number of control points."""
        return self.points.shape[0]

    @property
    def dim(self) -> int:
        """Space dimension."""
        return self.points.shape[1]

    @property
    def domain(self) -> tuple[float, float]:
        """``(knots[degree], knots[n_ctrl])``."""
        return float(self.knots[self.degree]), float(self.knots[self.n_ctrl])

    def __call__(self, u: ArrayLike) -> NDArray[np.float64]:
        """Points at parameters ``u`` (shape ``(n_u, dim)``)."""
        n = basis_functions(self.knots, self.degree, self.n_ctrl, u)
        h = n @ to_homogeneous(self.points, self.weights)
        return h[:, :-1] / h[:, -1:]

    def bezier_segments(self) -> tuple[NDArray[np.float64], list[RationalBezier]]:
        """``(breakpoints, segments)``: one rational Bézier curve per non-zero knot span.

        Segment ``j`` at ``t ∈ [0, 1]`` is the curve at ``u = u_j + t (u_{j+1} - u_j)``.
        """
        breaks, ops = extraction(self.knots, self.degree, self.n_ctrl)
        h = to_homogeneous(self.points, self.weights)
        return breaks, [RationalBezier.from_homogeneous(c @ h) for c in ops]
