"""The :class:`Conic` class: a conic arc in standard quadratic rational form.

Properties (dimension, chord, kind, end angles, circularity), evaluation with tangent, curvature
and speed, arc length and its inverse, the implicit form, sub-arcs, rigid placement and the cubic
form with mapping factor ``K``. The form itself and the constructors from intuitive parameters are
in :mod:`rancf.geometry.conic`; the scalar ingredients in :mod:`rancf.geometry.conic_params`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import ChordError, InputError, InteriorPointError, WeightError
from rancf.geometry.bezier import RationalBezier, blossom
from rancf.geometry.conic_params import (
    barycentric,
    check_mapping_factor,
    cross2,
    mapping_rho,
    pad3,
)
from rancf.geometry.quadrature import integrate
from rancf.geometry.tangents import vector_angle

__all__ = ["Conic", "ConicKind"]

ConicKind = Literal["ellipse", "parabola", "hyperbola"]


@dataclass(frozen=True)
class Conic:
    """A conic arc in standard quadratic rational form (end weights 1).

    Attributes
    ----------
    p0, p1, p2 : ndarray, shape ``(dim,)``
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
        area = np.linalg.norm(np.cross(pad3(pts[1] - pts[0]), pad3(pts[2] - pts[0])))
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
        a0 = vector_angle(self.p1 - self.p0, c)
        a1 = vector_angle(self.p2 - self.p1, c)
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
            return cross2(d1, d2) / speed3
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
        e1 = pad3(self.p2 - self.p0)
        e1 /= np.linalg.norm(e1)
        v = pad3(self.p1 - self.p0)
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
        """The part ``u ∈ [ua, ub]`` as a conic in standard form (docs/derivations/cable.md sec. 6).

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
        """Standard cubic rational Bézier form with mapping factor ``K`` (docs/derivations/cable.md
        sec. 2).

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
