"""Bernstein polynomials and rational Bézier curves in homogeneous coordinates.

Shape conventions: parameter arrays ``t`` have shape ``(n_t,)``; control points ``P`` have shape
``(n + 1, dim)`` for a curve of degree ``n``; weights ``w`` have shape ``(n + 1,)``; evaluated
points have shape ``(n_t, dim)``.

Every geometric operation (degree elevation, subdivision, restriction to a sub-interval) is
expressed as a matrix acting on homogeneous control points ``(w_i P_i, w_i)``, so that each one is
a checkable linear map (the Splipy convention).
"""

from __future__ import annotations

from dataclasses import dataclass
from math import comb

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError, WeightError

__all__ = [
    "bernstein",
    "RationalBezier",
    "degree_elevation_matrix",
    "restriction_matrix",
    "blossom",
    "to_homogeneous",
    "from_homogeneous",
]


def bernstein(degree: int, t: ArrayLike, derivative: int = 0) -> NDArray[np.float64]:
    """Bernstein polynomials ``B_i^n(t)`` or their derivatives.

    ``B_i^n(t) = C(n, i) t^i (1 - t)^(n - i)``; the ``k``-th derivative follows from
    ``d/dt B_i^n = n (B_{i-1}^{n-1} - B_i^{n-1})`` (Sanborn & Shabana 2009, eq. 15).

    Parameters
    ----------
    degree : int
        Polynomial degree ``n >= 0``.
    t : array_like, shape (n_t,)
        Parameter values.
    derivative : int
        Order of the derivative, ``0 <= derivative``.

    Returns
    -------
    ndarray, shape (n_t, degree + 1)
    """
    t = np.atleast_1d(np.asarray(t, dtype=float))
    if derivative > degree:
        return np.zeros((t.size, degree + 1))
    m = degree - derivative
    i = np.arange(m + 1)
    c = np.array([comb(m, k) for k in range(m + 1)], dtype=float)
    base = c * t[:, None] ** i * (1.0 - t[:, None]) ** (m - i)
    # apply the forward-difference operator `derivative` times
    out = base
    for level in range(derivative):
        k = m + level + 1  # degree after this step
        padded = np.zeros((t.size, out.shape[1] + 1))
        padded[:, 1:] += out
        padded[:, :-1] -= out
        out = k * padded
    return out


def to_homogeneous(points: ArrayLike, weights: ArrayLike) -> NDArray[np.float64]:
    """Homogeneous control points ``(w_i P_i, w_i)``, shape ``(n + 1, dim + 1)``."""
    p = np.asarray(points, dtype=float)
    w = np.asarray(weights, dtype=float)
    return np.hstack([p * w[:, None], w[:, None]])


def from_homogeneous(hpoints: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Inverse of :func:`to_homogeneous`: ``(points, weights)``."""
    h = np.asarray(hpoints, dtype=float)
    w = h[:, -1]
    return h[:, :-1] / w[:, None], w.copy()


def degree_elevation_matrix(degree: int) -> NDArray[np.float64]:
    """Matrix ``E`` of shape ``(degree + 2, degree + 1)`` with ``Q = E P`` the elevated points.

    ``Q_i = (i / (n + 1)) P_{i-1} + (1 - i / (n + 1)) P_i`` (Piegl & Tiller, eq. 5.36), applied to
    homogeneous points for rational curves.
    """
    n = degree
    e = np.zeros((n + 2, n + 1))
    for i in range(n + 2):
        a = i / (n + 1)
        if i >= 1:
            e[i, i - 1] = a
        if i <= n:
            e[i, i] = 1.0 - a
    return e


def blossom(hpoints: ArrayLike, args: ArrayLike) -> NDArray[np.float64]:
    """Blossom (polar form) of a Bézier curve at ``args = (t_1, ..., t_n)``.

    De Casteljau's algorithm with a different parameter at each level; for rational curves pass
    homogeneous points.  ``blossom(P, (t, ..., t))`` is the point at ``t``.
    """
    pts = np.array(hpoints, dtype=float)
    args = np.asarray(args, dtype=float)
    n = pts.shape[0] - 1
    if args.size != n:
        raise ValueError(f"blossom of degree {n} needs {n} arguments, got {args.size}")
    for level, t in enumerate(args):
        pts = (1.0 - t) * pts[: n - level] + t * pts[1 : n - level + 1]
    return pts[0]


def restriction_matrix(degree: int, a: float, b: float) -> NDArray[np.float64]:
    """Matrix ``A`` with ``A P`` the control points of the same curve on ``[a, b]``.

    Row ``i`` holds the blossom ``b(a^(n - i), b^i)`` expressed in the original control points,
    so the sub-curve reparameterized to ``[0, 1]`` is exactly the original restricted to
    ``[a, b]`` (subdivision by blossoming).  Apply to homogeneous points for rational curves.
    """
    n = degree
    eye = np.eye(n + 1)
    rows = [blossom(eye, [a] * (n - i) + [b] * i) for i in range(n + 1)]
    return np.array(rows)


@dataclass(frozen=True)
class RationalBezier:
    """A rational Bézier curve ``r(t) = Σ w_i B_i(t) P_i / Σ w_i B_i(t)``, ``t ∈ [0, 1]``.

    Attributes
    ----------
    points : ndarray, shape (n + 1, dim)
        Control points.
    weights : ndarray, shape (n + 1,)
        Strictly positive weights.
    """

    points: NDArray[np.float64]
    weights: NDArray[np.float64]

    def __post_init__(self) -> None:
        p = np.array(self.points, dtype=float)
        w = np.array(self.weights, dtype=float)
        if p.ndim != 2 or w.ndim != 1 or p.shape[0] != w.shape[0]:
            raise InputError(
                "points/weights",
                (p.shape, w.shape),
                "points of shape (n + 1, dim) and weights of shape (n + 1,)",
            )
        if not np.all(np.isfinite(w)) or np.any(w <= 0.0):
            raise WeightError("weights", w, "every weight must be finite and > 0")
        p.setflags(write=False)
        w.setflags(write=False)
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "weights", w)

    @property
    def degree(self) -> int:
        """Polynomial degree ``n``."""
        return self.points.shape[0] - 1

    @property
    def dim(self) -> int:
        """Dimension of the space the curve lies in."""
        return self.points.shape[1]

    @property
    def homogeneous(self) -> NDArray[np.float64]:
        """Homogeneous control points, shape ``(n + 1, dim + 1)``."""
        return to_homogeneous(self.points, self.weights)

    @classmethod
    def from_homogeneous(cls, hpoints: ArrayLike) -> RationalBezier:
        """Build from homogeneous control points ``(w P, w)``."""
        p, w = from_homogeneous(hpoints)
        return cls(p, w)

    def derivatives(self, t: ArrayLike, order: int = 2) -> list[NDArray[np.float64]]:
        """Point and parametric derivatives up to ``order`` (at most 2).

        With ``A = Σ w_i B_i P_i`` and ``D = Σ w_i B_i``: ``r = A / D``,
        ``r' = (A' - r D') / D``, ``r'' = (A'' - 2 r' D' - r D'') / D``.

        Returns
        -------
        list of ndarray, each of shape (n_t, dim)
            ``[r, r', r'']`` truncated to ``order + 1`` entries.
        """
        t = np.atleast_1d(np.asarray(t, dtype=float))
        h = self.homogeneous
        out: list[NDArray[np.float64]] = []
        hs = [bernstein(self.degree, t, k) @ h for k in range(order + 1)]
        d = [x[:, -1:] for x in hs]
        a = [x[:, :-1] for x in hs]
        r = a[0] / d[0]
        out.append(r)
        if order >= 1:
            r1 = (a[1] - r * d[1]) / d[0]
            out.append(r1)
        if order >= 2:
            r2 = (a[2] - 2.0 * r1 * d[1] - r * d[2]) / d[0]
            out.append(r2)
        return out

    def __call__(self, t: ArrayLike) -> NDArray[np.float64]:
        """Points on the curve, shape ``(n_t, dim)``."""
        return self.derivatives(t, order=0)[0]

    def elevated(self) -> RationalBezier:
        """The same curve as a rational Bézier curve of one degree higher."""
        return RationalBezier.from_homogeneous(
            degree_elevation_matrix(self.degree) @ self.homogeneous
        )

    def restricted(self, a: float, b: float) -> RationalBezier:
        """The part of the curve for ``t ∈ [a, b]``, reparameterized to ``[0, 1]``."""
        return RationalBezier.from_homogeneous(
            restriction_matrix(self.degree, a, b) @ self.homogeneous
        )

    def split(self, t: float) -> tuple[RationalBezier, RationalBezier]:
        """De Casteljau subdivision at ``t``: the parts on ``[0, t]`` and ``[t, 1]``."""
        return self.restricted(0.0, t), self.restricted(t, 1.0)

    def reparameterized(self, rho: float) -> RationalBezier:
        """Möbius reparameterization ``t = ρ s / (1 - s + ρ s)``.

        Substituting the map multiplies ``w_i`` by ``ρ^i`` and leaves the control points and the
        curve unchanged (Farin, *NURBS*, sec. 5.3).  The returned curve at ``s`` equals this
        curve at ``t(s)``.
        """
        if not rho > 0.0:
            raise InputError("rho", rho, "the Möbius factor must be > 0")
        return RationalBezier(self.points, self.weights * rho ** np.arange(self.degree + 1))

    def standardized(self) -> RationalBezier:
        """Equivalent curve with end weights 1 (Möbius map plus a common scale)."""
        n = self.degree
        rho = (self.weights[0] / self.weights[-1]) ** (1.0 / n)
        w = self.weights * rho ** np.arange(n + 1)
        return RationalBezier(self.points, w / w[0])

    def transformed(self, rotation: ArrayLike, translation: ArrayLike) -> RationalBezier:
        """Image under ``x ↦ R x + c``; weights are invariant under affine maps."""
        rot = np.asarray(rotation, dtype=float)
        c = np.asarray(translation, dtype=float)
        return RationalBezier(self.points @ rot.T + c, self.weights)
