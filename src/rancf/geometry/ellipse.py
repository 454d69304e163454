"""A full ellipse (a circle when the semi-axes are equal): points, arc length and its inverse,
and the conic sub-arcs between parameter values.

The ellipse ``r(t) = c + a cos t e1 + b sin t e2`` (``e1``, ``e2`` orthonormal; planar or
spatial) is the affine image of the unit circle, so its arc between ``t_a`` and ``t_b``
(``t_b - t_a < π``) is the image of a circular arc of half angle ``h = (t_b - t_a) / 2``: a conic
in standard form with end points ``r(t_a)``, ``r(t_b)``, tangent intersection
``c + (a cos m e1 + b sin m e2) / cos h`` (``m`` the mid parameter) and weight ``ω = cos h``
(affine maps keep rational forms; ``docs/derivations/cable.md`` sec. 1).  Every sub-arc is exact.

Arc length: ``ds = sqrt(a² sin² t + b² cos² t) dt``.  With ``A = max(a, b)`` and
``m = 1 - min(a, b)² / A²`` it is ``A sqrt(1 - m cos² t)`` if ``a ≥ b`` and ``A sqrt(1 - m sin² t)``
otherwise, so ``s(t) = A [E(t + π/2 | m) - E(π/2 | m)]`` or ``A E(t | m)`` (Legendre's incomplete
integral of the second kind, :func:`scipy.special.ellipeinc`) and the perimeter is ``4 A E(m)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError

__all__ = ["Ellipse", "ellipse_axes"]


def ellipse_axes(
    dim: int, rotation_deg: float = 0.0, axes: ArrayLike | None = None
) -> tuple[NDArray, NDArray]:
    """Orthonormal axis directions ``(e1, e2)``: planar from ``rotation_deg``, spatial from
    ``axes`` (two perpendicular non-zero vectors; default x and y).

    Raises
    ------
    InputError
        Naming ``axes`` if they are not two perpendicular non-zero vectors of 3 numbers.
    """
    if dim == 2:
        th = np.radians(float(rotation_deg))
        return np.array([np.cos(th), np.sin(th)]), np.array([-np.sin(th), np.cos(th)])
    if axes is None:
        return np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    v = np.asarray(axes, dtype=float)
    if v.shape != (2, 3) or not np.all(np.isfinite(v)):
        raise InputError("axes", np.asarray(axes).tolist(), "two vectors of 3 numbers")
    n1, n2 = np.linalg.norm(v, axis=1)
    if not (n1 > 0.0 and n2 > 0.0):
        raise InputError("axes", v.tolist(), "two non-zero vectors")
    e1, e2 = v[0] / n1, v[1] / n2
    if abs(float(e1 @ e2)) > 1e-9:
        raise InputError(
            "axes",
            v.tolist(),
            f"two perpendicular vectors (the angle between them is "
            f"{np.degrees(np.arccos(np.clip(e1 @ e2, -1, 1))):.6g} deg)",
        )
    e2 = e2 - (e1 @ e2) * e1  # exactly perpendicular
    return e1, e2 / np.linalg.norm(e2)


@dataclass(frozen=True)
class Ellipse:
    """A full ellipse ``r(t) = center + a cos t e1 + b sin t e2``, ``t ∈ [t0, t0 + 2π]``.

    Attributes
    ----------
    center : ndarray, shape (dim,)
    a, b : float
        Semi-axes along ``e1`` and ``e2`` (> 0).
    e1, e2 : ndarray, shape (dim,)
        Orthonormal axis directions.
    """

    center: NDArray[np.float64]
    a: float
    b: float
    e1: NDArray[np.float64]
    e2: NDArray[np.float64]

    def __post_init__(self) -> None:
        c = np.array(self.center, dtype=float).ravel()
        if c.size not in (2, 3):
            raise InputError("center", c.tolist(), "2 or 3 numbers")
        for name, v in (("semi_axes", self.a), ("semi_axes", self.b)):
            if not (np.isfinite(v) and v > 0.0):
                raise InputError(name, [self.a, self.b], "two lengths > 0")
        for name in ("e1", "e2"):
            e = np.array(getattr(self, name), dtype=float).ravel()
            if e.size != c.size:
                raise InputError(name, e.tolist(), f"{c.size} numbers")
            object.__setattr__(self, name, e)
        object.__setattr__(self, "center", c)
        object.__setattr__(self, "a", float(self.a))
        object.__setattr__(self, "b", float(self.b))

    @property
    def dim(self) -> int:
        """2 (planar) or 3 (spatial)."""
        return self.center.size

    def __call__(self, t: ArrayLike) -> NDArray[np.float64]:
        """Points ``(n_t, dim)`` at parameters ``t``."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return (
            self.center
            + self.a * np.cos(t)[:, None] * self.e1
            + self.b * np.sin(t)[:, None] * self.e2
        )

    def implicit_residual(self, points: ArrayLike) -> NDArray[np.float64]:
        """``(x/a)² + (y/b)² - 1`` of points in the ellipse's axes (and the distance from its
        plane, for spatial points, relative to ``max(a, b)``)."""
        d = np.atleast_2d(np.asarray(points, dtype=float)) - self.center
        x, y = d @ self.e1 / self.a, d @ self.e2 / self.b
        res = x * x + y * y - 1.0
        if self.dim == 3:
            off = d - np.outer(d @ self.e1, self.e1) - np.outer(d @ self.e2, self.e2)
            res = res + np.linalg.norm(off, axis=1) / max(self.a, self.b)
        return res

    def _elliptic(self) -> tuple[float, float, bool]:
        big, small = max(self.a, self.b), min(self.a, self.b)
        return big, 1.0 - (small / big) ** 2, self.a >= self.b

    def perimeter(self) -> float:
        """``4 max(a, b) E(m)`` (module docstring)."""
        import scipy.special  # here, not at import: 0.1 s of every command's start-up

        big, m, _ = self._elliptic()
        return float(4.0 * big * scipy.special.ellipe(m))

    def arc_length(self, t: ArrayLike) -> NDArray[np.float64]:
        """Arc length from ``t = 0`` to ``t`` (signed, any real ``t``)."""
        import scipy.special

        big, m, wide = self._elliptic()
        t = np.asarray(t, dtype=float)
        if wide:
            half = np.pi / 2
            return big * (scipy.special.ellipeinc(t + half, m) - scipy.special.ellipeinc(half, m))
        return big * scipy.special.ellipeinc(t, m)

    def speed(self, t: ArrayLike) -> NDArray[np.float64]:
        """``|dr/dt|``."""
        t = np.asarray(t, dtype=float)
        return np.sqrt((self.a * np.sin(t)) ** 2 + (self.b * np.cos(t)) ** 2)

    def parameters_at_arc_lengths(self, t0: float, s: ArrayLike) -> NDArray[np.float64]:
        """Parameters ``t`` with ``arc_length(t) - arc_length(t0) = s`` (Newton, to round-off)."""
        s = np.asarray(s, dtype=float)
        target = self.arc_length(t0) + s
        t = t0 + 2.0 * np.pi * s / self.perimeter()
        for _ in range(60):
            step = (self.arc_length(t) - target) / self.speed(t)
            t = t - step
            if np.all(np.abs(step) <= 1e-15 * (1.0 + np.abs(t))):
                break
        return t

    def sub_arcs(self, t: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Standard conic forms of the arcs ``[t_j, t_{j+1}]`` (each shorter than half a turn):
        control points ``(n, 3, dim)`` and weights ``ω (n,)`` (module docstring)."""
        t = np.asarray(t, dtype=float)
        ta, tb = t[:-1], t[1:]
        h = 0.5 * (tb - ta)
        if np.any(h <= 0.0) or np.any(h >= 0.5 * np.pi * (1.0 - 1e-9)):
            raise InputError(
                "elements", t.size - 1, "arcs of less than half a turn each (at least 3 elements)"
            )
        mid = 0.5 * (ta + tb)
        p1 = (
            self.center
            + (self.a * np.cos(mid) / np.cos(h))[:, None] * self.e1
            + (self.b * np.sin(mid) / np.cos(h))[:, None] * self.e2
        )
        pts = np.stack([self(ta), p1, self(tb)], axis=1)
        return pts, np.cos(h)
