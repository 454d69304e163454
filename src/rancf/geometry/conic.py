"""Conic arcs in standard quadratic rational form, built from intuitive parameters.

A conic arc is ``r(u) = [(1-u)^2 P0 + 2u(1-u) ω P1 + u^2 P2] / [(1-u)^2 + 2u(1-u) ω + u^2]``,
``u ∈ [0, 1]`` (conic-section paper, eq. 13 / 23; math note sec. 1), with ``P0``, ``P2`` the end
points, ``P1`` the intersection of the end tangents and ``ω > 0`` the single interior weight.

The cubic forms with mapping factor ``K`` (paper sec. 2.2 and 4.2, eq. 15; math note sec. 2) are
produced by :meth:`Conic.cubic`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import (
    AngleError,
    ChordError,
    InputError,
    InteriorPointError,
    MappingFactorError,
    WeightError,
)
from rancf.geometry.bezier import RationalBezier, blossom
from rancf.geometry.quadrature import integrate

__all__ = [
    "Conic",
    "conic_arc",
    "conic_arc_through",
    "circular_arc",
    "tangent_intersection",
    "barycentric",
    "weight_from_point",
    "mapping_rho",
    "check_mapping_factor",
]

ConicKind = Literal["ellipse", "parabola", "hyperbola"]


def _cross2(a: NDArray, b: NDArray) -> NDArray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def tangent_intersection(chord: float, theta0: float, theta1: float) -> NDArray[np.float64]:
    """``P1``, the meeting point of the end tangents in the local frame (math note sec. 1).

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
    s = _cross2(b - a, c - a)
    l0 = _cross2(b - p, c - p) / s
    l1 = _cross2(c - p, a - p) / s
    l2 = _cross2(a - p, b - p) / s
    return np.stack([l0, l1, l2], axis=-1)


def weight_from_point(lam: ArrayLike) -> float:
    """Interior weight ``ω = λ1 / (2 sqrt(λ0 λ2))`` of the standard form (paper eq. 12)."""
    l0, l1, l2 = np.asarray(lam, dtype=float)
    return float(l1 / (2.0 * np.sqrt(l0 * l2)))


def check_mapping_factor(k: float, name: str = "k") -> float:
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
    """Möbius factor ``ρ = (K / (1 - K))^(1/3)`` of the mapping factor (math note sec. 2)."""
    k = check_mapping_factor(k)
    return float(np.cbrt(k / (1.0 - k)))


@dataclass(frozen=True)
class Conic:
    """A conic arc in standard quadratic rational form (end weights 1).

    Attributes
    ----------
    p0, p1, p2 : ndarray, shape (dim,)
        Start point, tangent intersection, end point; ``dim`` is 2 or 3.
    omega : float
        Interior weight ``ω > 0``: ``ω < 1`` ellipse, ``ω = 1`` parabola, ``ω > 1`` hyperbola.
    """

    p0: NDArray[np.float64]
    p1: NDArray[np.float64]
    p2: NDArray[np.float64]
    omega: float

    def __post_init__(self) -> None:
        pts = [np.array(p, dtype=float).ravel() for p in (self.p0, self.p1, self.p2)]
        dim = pts[0].size
        if dim not in (2, 3) or any(p.size != dim for p in pts):
            raise InputError(
                "points", [p.tolist() for p in pts], "three points of dimension 2 or 3"
            )
        om = float(self.omega)
        if not np.isfinite(om) or om <= 0.0:
            raise WeightError("omega", om, "the conic weight must be finite and > 0")
        chord = np.linalg.norm(pts[2] - pts[0])
        if not chord > 0.0:
            raise ChordError("chord", float(chord), "start and end points must differ")
        area = np.linalg.norm(np.cross(_pad3(pts[1] - pts[0]), _pad3(pts[2] - pts[0])))
        if not area > 1e-14 * chord**2:
            raise InteriorPointError(
                "p1", pts[1].tolist(), "the tangent intersection must not lie on the chord"
            )
        for name, p in zip(("p0", "p1", "p2"), pts, strict=True):
            p.setflags(write=False)
            object.__setattr__(self, name, p)
        object.__setattr__(self, "omega", om)

    # ----------------------------------------------------------------- basic properties
    @property
    def dim(self) -> int:
        """Dimension of the space (2 or 3)."""
        return self.p0.size

    @property
    def chord(self) -> float:
        """Chord length ``|P2 - P0|``."""
        return float(np.linalg.norm(self.p2 - self.p0))

    @property
    def bezier(self) -> RationalBezier:
        """The quadratic rational Bézier form with weights ``(1, ω, 1)``."""
        return RationalBezier(
            np.array([self.p0, self.p1, self.p2]), np.array([1.0, self.omega, 1.0])
        )

    @property
    def kind(self) -> ConicKind:
        """``"ellipse"`` (ω < 1), ``"parabola"`` (ω = 1) or ``"hyperbola"`` (ω > 1)."""
        if abs(self.omega - 1.0) <= 1e-12:
            return "parabola"
        return "ellipse" if self.omega < 1.0 else "hyperbola"

    @property
    def end_angles(self) -> tuple[float, float]:
        """Angles (radians) between the end tangents and the chord, ``(θ0, θ1)``."""
        c = self.p2 - self.p0
        a0 = _angle(self.p1 - self.p0, c)
        a1 = _angle(self.p2 - self.p1, c)
        return a0, a1

    def circularity(self) -> float:
        """Relative deviation from a circular arc, ``max(|θ0 - θ1|, |ω - cos θ|)``.

        A conic arc is circular exactly when ``θ0 = θ1 = θ`` and ``ω = cos θ``.
        """
        t0, t1 = self.end_angles
        return float(max(abs(t0 - t1), abs(self.omega - np.cos(0.5 * (t0 + t1)))))

    def is_circular(self, tol: float = 1e-9) -> bool:
        """Whether the arc is a circular arc to within ``tol`` (see :meth:`circularity`)."""
        return self.circularity() <= tol

    def radius(self) -> float:
        """Radius of a circular arc, ``L / (2 sin θ)``; NaN if the arc is not circular."""
        if not self.is_circular():
            return float("nan")
        t0, t1 = self.end_angles
        return self.chord / (2.0 * np.sin(0.5 * (t0 + t1)))

    # ----------------------------------------------------------------- evaluation
    def derivatives(self, u: ArrayLike, order: int = 2) -> list[NDArray[np.float64]]:
        """``[r, r_u, r_uu]`` at parameters ``u``, each of shape ``(n_u, dim)``."""
        return self.bezier.derivatives(u, order)

    def __call__(self, u: ArrayLike) -> NDArray[np.float64]:
        """Points ``r(u)``, shape ``(n_u, dim)``."""
        return self.bezier(u)

    def tangent(self, u: ArrayLike) -> NDArray[np.float64]:
        """Unit tangent ``r_u / |r_u|``, shape ``(n_u, dim)``."""
        d1 = self.derivatives(u, 1)[1]
        return d1 / np.linalg.norm(d1, axis=1, keepdims=True)

    def curvature(self, u: ArrayLike) -> NDArray[np.float64]:
        """Curvature ``κ = (r_u × r_uu) / |r_u|^3``.

        Signed (positive when the arc turns counter-clockwise) for planar arcs, the magnitude
        ``|r_u × r_uu| / |r_u|^3`` for spatial arcs.  Shape ``(n_u,)``.
        """
        _, d1, d2 = self.derivatives(u, 2)
        speed3 = np.linalg.norm(d1, axis=1) ** 3
        if self.dim == 2:
            return _cross2(d1, d2) / speed3
        return np.linalg.norm(np.cross(d1, d2), axis=1) / speed3

    def speed(self, u: ArrayLike) -> NDArray[np.float64]:
        """``|r_u(u)|``, shape ``(n_u,)``."""
        return np.linalg.norm(self.derivatives(u, 1)[1], axis=1)

    def arc_length(self, a: float = 0.0, b: float = 1.0, rtol: float = 1e-14) -> float:
        """Arc length between parameters ``a`` and ``b`` by adaptive Gauss–Legendre (1e-13 rel.)."""
        if a == b:
            return 0.0
        return integrate(self.speed, a, b, rtol=rtol)

    def parameters_at_arc_lengths(self, s: ArrayLike) -> NDArray[np.float64]:
        """Parameters ``u`` with arc length ``s`` from the start (safeguarded Newton).

        ``s`` must be increasing and within ``[0, arc_length]``.  Each solve starts from the
        previous one and integrates only the increment, so the cost is linear in ``len(s)``.
        """
        s = np.atleast_1d(np.asarray(s, dtype=float))
        total = self.arc_length()
        out = np.empty_like(s)
        u_prev, s_prev = 0.0, 0.0
        for i, target in enumerate(s):
            if target <= 0.0:
                out[i] = 0.0
                continue
            if target >= total:
                out[i] = 1.0
                continue
            lo, hi = u_prev, 1.0
            u = u_prev + (target - s_prev) / total
            u = min(max(u, lo), hi)
            for _ in range(100):
                f = s_prev + self.arc_length(u_prev, u) - target
                if f > 0:
                    hi = u
                else:
                    lo = u
                step = f / float(self.speed(u)[0])
                u_new = u - step
                if not (lo < u_new < hi):
                    u_new = 0.5 * (lo + hi)
                if abs(u_new - u) <= 1e-15 * max(1.0, abs(u)):
                    u = u_new
                    break
                u = u_new
            out[i] = u
            s_prev = s_prev + self.arc_length(u_prev, u)
            u_prev = u
        return out

    # ----------------------------------------------------------------- implicit form
    def plane_frame(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Orthonormal ``(e1, e2)`` spanning the plane of the arc, ``e1`` along the chord."""
        e1 = _pad3(self.p2 - self.p0)
        e1 /= np.linalg.norm(e1)
        v = _pad3(self.p1 - self.p0)
        e2 = v - np.dot(v, e1) * e1
        e2 /= np.linalg.norm(e2)
        return e1[: self.dim], e2[: self.dim]

    def implicit_residual(self, points: ArrayLike) -> NDArray[np.float64]:
        """Distance-like residual of points from the conic (zero on the curve).

        In barycentric coordinates of ``P0 P1 P2`` the conic is ``λ1² = 4 ω² λ0 λ2``.  The
        residual is ``(λ1² - 4 ω² λ0 λ2)`` scaled by the chord, plus, in 3D, the distance from
        the plane.  Shape ``(n_points,)``.
        """
        pts = np.atleast_2d(np.asarray(points, dtype=float))
        e1, e2 = self.plane_frame()
        rel = pts - self.p0

        def loc(x: NDArray) -> NDArray:
            return np.stack([x @ e1, x @ e2], axis=-1)

        lam = barycentric(loc(rel), np.zeros(2), loc(self.p1 - self.p0), loc(self.p2 - self.p0))
        res = (lam[:, 1] ** 2 - 4.0 * self.omega**2 * lam[:, 0] * lam[:, 2]) * self.chord
        if self.dim == 3:
            normal = np.cross(e1, e2)
            res = np.abs(res) + np.abs(rel @ normal)
        return res

    # ----------------------------------------------------------------- derived arcs
    def sub_arc(self, ua: float, ub: float) -> Conic:
        """The part ``u ∈ [ua, ub]`` as a conic in standard form (math note sec. 6).

        Homogeneous control points ``b(ua,ua), b(ua,ub), b(ub,ub)`` by blossoming, then
        ``ω' = ω_mid / sqrt(ω_a ω_b)``.
        """
        if not (0.0 <= ua < ub <= 1.0):
            raise InputError("(ua, ub)", (ua, ub), "sub-arc parameters with 0 <= ua < ub <= 1")
        h = self.bezier.homogeneous
        ha = blossom(h, [ua, ua])
        hm = blossom(h, [ua, ub])
        hb = blossom(h, [ub, ub])
        wa, wm, wb = ha[-1], hm[-1], hb[-1]
        return Conic(ha[:-1] / wa, hm[:-1] / wm, hb[:-1] / wb, wm / np.sqrt(wa * wb))

    def sub_arc_map(self, ua: float, ub: float) -> tuple[float, float, float]:
        """``(ua, ub, σ)`` of the map from the sub-arc parameter ``v`` to ``u``.

        ``u = ua + (ub - ua) t`` with ``t = σ v / (1 - v + σ v)`` and ``σ = sqrt(ω_a / ω_b)``,
        where ``ω_a``, ``ω_b`` are the homogeneous weights of the blossom end points.
        """
        h = self.bezier.homogeneous
        wa = blossom(h, [ua, ua])[-1]
        wb = blossom(h, [ub, ub])[-1]
        return ua, ub, float(np.sqrt(wa / wb))

    def transformed(self, rotation: ArrayLike, translation: ArrayLike) -> Conic:
        """Image under the isometry ``x ↦ R x + c`` (``R`` of shape ``(dim_out, dim)``)."""
        rot = np.asarray(rotation, dtype=float)
        c = np.asarray(translation, dtype=float)
        return Conic(rot @ self.p0 + c, rot @ self.p1 + c, rot @ self.p2 + c, self.omega)

    def cubic(self, k: float) -> RationalBezier:
        """Standard cubic rational Bézier form with mapping factor ``K`` (math note sec. 2).

        ``Q1 = ((1-K) P0 + 2ωK P1) / ((1-K) + 2ωK)``,
        ``Q2 = (2ω(1-K) P1 + K P2) / (2ω(1-K) + K)``, ``ρ = (K / (1-K))^(1/3)``,
        ``w = (1, ((1-K) + 2ωK) ρ / (3K), (2ω(1-K) + K) ρ² / (3K), 1)``.
        The cubic at ``ξ`` is the conic at ``u = ρ ξ / (1 - ξ + ρ ξ)``, for every ``K``.
        """
        k = check_mapping_factor(k)
        om = self.omega
        rho = mapping_rho(k)
        a1 = (1.0 - k) + 2.0 * om * k
        a2 = 2.0 * om * (1.0 - k) + k
        q1 = ((1.0 - k) * self.p0 + 2.0 * om * k * self.p1) / a1
        q2 = (2.0 * om * (1.0 - k) * self.p1 + k * self.p2) / a2
        w = np.array([1.0, a1 * rho / (3.0 * k), a2 * rho**2 / (3.0 * k), 1.0])
        return RationalBezier(np.array([self.p0, q1, q2, self.p2]), w)


def quadratic_parameter(xi: ArrayLike, k: float) -> NDArray[np.float64]:
    """``u(ξ) = ρ ξ / (1 - ξ + ρ ξ)`` for mapping factor ``K`` (math note sec. 2)."""
    rho = mapping_rho(k)
    xi = np.asarray(xi, dtype=float)
    return rho * xi / (1.0 - xi + rho * xi)


def cubic_parameter(u: ArrayLike, k: float) -> NDArray[np.float64]:
    """Inverse of :func:`quadratic_parameter`: ``ξ(u) = u / (ρ (1 - u) + u)``."""
    rho = mapping_rho(k)
    u = np.asarray(u, dtype=float)
    return u / (rho * (1.0 - u) + u)


__all__ += ["quadratic_parameter", "cubic_parameter"]


def _pad3(v: NDArray) -> NDArray:
    v = np.asarray(v, dtype=float)
    return v if v.size == 3 else np.array([v[0], v[1], 0.0])


def _angle(a: NDArray, b: NDArray) -> float:
    a3, b3 = _pad3(a), _pad3(b)
    return float(np.arctan2(np.linalg.norm(np.cross(a3, b3)), np.dot(a3, b3)))


def _check_angles(angles_deg: ArrayLike) -> tuple[float, float]:
    try:
        a = np.asarray(angles_deg, dtype=float).ravel()
    except (TypeError, ValueError):
        raise AngleError("angles", angles_deg, "two numbers (degrees) in (0, 90)") from None
    if a.size != 2:
        raise AngleError("angles", angles_deg, "exactly two angles (degrees), theta0 and theta1")
    for name, val in zip(("theta0", "theta1"), a, strict=True):
        if not (0.0 < val < 90.0):
            raise AngleError(
                f"angles ({name})",
                float(val),
                "tangent-to-chord angles must lie in (0, 90) degrees",
            )
    return float(a[0]), float(a[1])


def _check_chord(chord: float) -> float:
    try:
        c = float(chord)
    except (TypeError, ValueError):
        raise ChordError("chord", chord, "a positive number (metres)") from None
    if not (np.isfinite(c) and c > 0.0):
        raise ChordError("chord", chord, "the chord length must be finite and > 0")
    return c


def conic_arc(chord: float, angles_deg: ArrayLike, point: ArrayLike) -> Conic:
    """Conic arc in the paper's local frame from its intuitive parameters (paper sec. 3.2).

    ``P0 = (0, 0)``, ``P2 = (L, 0)``, end tangents at ``θ0``, ``θ1`` to the chord on the ``+y``
    side, and one interior point ``Pu = (X, Y)`` strictly inside triangle ``P0 P1 P2``.

    Parameters
    ----------
    chord : float
        Chord length ``L > 0``.
    angles_deg : (float, float)
        ``(θ0, θ1)`` in degrees, each in ``(0, 90)``.
    point : (float, float)
        Interior point ``(X, Y)`` of the arc in the local frame.

    Raises
    ------
    ChordError, AngleError, InteriorPointError
    """
    length = _check_chord(chord)
    t0, t1 = _check_angles(angles_deg)
    pu = np.asarray(point, dtype=float).ravel()
    if pu.size != 2 or not np.all(np.isfinite(pu)):
        raise InteriorPointError("point", point, "two finite coordinates (X, Y) in the local frame")
    p0 = np.zeros(2)
    p2 = np.array([length, 0.0])
    p1 = tangent_intersection(length, np.radians(t0), np.radians(t1))
    lam = barycentric(pu, p0, p1, p2)
    if np.any(lam <= 1e-12):
        raise InteriorPointError(
            "point",
            pu,
            "the interior point must lie strictly inside the tangent triangle "
            f"(0, 0), ({p1[0]:.6g}, {p1[1]:.6g}), ({length:.6g}, 0)",
        )
    return Conic(p0, p1, p2, weight_from_point(lam))


def circular_arc(chord: float, angle_deg: float) -> Conic:
    """Exact circular arc of chord ``L``, end tangents at ``θ`` to the chord (ω = cos θ)."""
    length = _check_chord(chord)
    t, _ = _check_angles([angle_deg, angle_deg])
    th = np.radians(t)
    return Conic(
        np.zeros(2), tangent_intersection(length, th, th), np.array([length, 0.0]), np.cos(th)
    )


def conic_arc_through(
    start: ArrayLike, end: ArrayLike, angles_deg: ArrayLike, point: ArrayLike
) -> Conic:
    """Conic arc in global 2D or 3D coordinates (math note sec. 1, rigid placement).

    The start, end and interior point fix the plane and the side of the chord the arc lies on;
    the local frame has ``x`` along the chord and ``y`` towards the interior point.  In 2D this
    frame may be mirrored (an isometry), so arcs on either side of the chord are allowed.

    Parameters
    ----------
    start, end : array_like, shape (dim,)
        End points, ``dim`` 2 or 3.
    angles_deg : (float, float)
        Tangent-to-chord angles at start and end, degrees in ``(0, 90)``.
    point : array_like, shape (dim,)
        Any interior point of the arc.
    """
    a = np.asarray(start, dtype=float).ravel()
    b = np.asarray(end, dtype=float).ravel()
    p = np.asarray(point, dtype=float).ravel()
    if a.size not in (2, 3) or b.size != a.size or p.size != a.size:
        raise InputError(
            "start/end/point",
            (a.tolist(), b.tolist(), p.tolist()),
            "three points of equal dimension 2 or 3",
        )
    chord_vec = b - a
    length = float(np.linalg.norm(chord_vec))
    if not length > 0.0:
        raise ChordError("chord", length, "start and end must be distinct points (chord > 0)")
    e1 = chord_vec / length
    rel = p - a
    x = float(rel @ e1)
    perp = rel - x * e1
    y = float(np.linalg.norm(perp))
    if not y > 1e-12 * length:
        raise InteriorPointError("point", p, "the interior point must not lie on the chord line")
    e2 = perp / y
    local = conic_arc(length, angles_deg, [x, y])
    rot = np.stack([e1, e2], axis=1)  # (dim, 2): local (x, y) -> global
    return local.transformed(rot, a)
