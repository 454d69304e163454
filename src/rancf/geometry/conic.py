"""Conic arcs in standard quadratic rational form, built from intuitive parameters.

A conic arc is ``r(u) = [(1-u)^2 P0 + 2u(1-u) ω P1 + u^2 P2] / [(1-u)^2 + 2u(1-u) ω + u^2]``,
``u ∈ [0, 1]`` (conic-section paper, eq. 13 / 23; docs/derivations/cable.md sec. 1), with ``P0``,
``P2`` the end
points, ``P1`` the intersection of the end tangents and ``ω > 0`` the single interior weight.

The cubic forms with mapping factor ``K`` (paper sec. 2.2 and 4.2, eq. 15;
docs/derivations/cable.md sec. 2) are
produced by :meth:`Conic.cubic`. This module holds the constructors from intuitive parameters;
the class is defined in :mod:`rancf.geometry.conic_curve` (and importable from here), the
tangent intersection, weight and mapping-factor helpers in :mod:`rancf.geometry.conic_params`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from rancf.errors import AngleError, ChordError, InputError, InteriorPointError
from rancf.geometry.conic_curve import Conic
from rancf.geometry.conic_params import barycentric, tangent_intersection, weight_from_point

__all__ = [
    "Conic",
    "conic_arc",
    "conic_arc_through",
    "circular_arc",
    "LENGTH_RANGE",
    "ANGLE_MARGIN",
]

#: Chord lengths a conic arc may have [m]: far beyond any cable, and far inside the range where
#: areas and squared lengths (``L²``, ``L⁴``) of the construction stay normal floating-point
#: numbers, so an out-of-range value is refused by name instead of ending in a NaN.
LENGTH_RANGE = (1e-9, 1e9)
#: Closest an end-tangent angle may come to 0° or 90° [deg] (the tangent triangle's apex then
#: lies 1.7e-8 to 5.7e7 chords from the chord: still a well-conditioned construction).
ANGLE_MARGIN = 1e-6


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
        if not (ANGLE_MARGIN <= val <= 90.0 - ANGLE_MARGIN):
            raise AngleError(
                f"angles ({name})",
                float(val),
                f"tangent-to-chord angles must lie in (0, 90) degrees, at least {ANGLE_MARGIN:g}° "
                "from either end",
            )
    return float(a[0]), float(a[1])


def _check_chord(chord: float) -> float:
    try:
        c = float(chord)
    except (TypeError, ValueError):
        raise ChordError("chord", chord, "a positive number (metres)") from None
    if not (np.isfinite(c) and c > 0.0):
        raise ChordError("chord", chord, "the chord length must be finite and > 0")
    lo, hi = LENGTH_RANGE
    if not lo <= c <= hi:
        raise ChordError("chord", chord, f"the chord length must lie in [{lo:g}, {hi:g}] m")
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
    with np.errstate(all="ignore"):  # a point far outside: refused below, without warnings
        lam = barycentric(pu, p0, p1, p2)
    if not np.all(np.isfinite(lam)) or np.any(lam <= 1e-12):
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
    """Conic arc in global 2D or 3D coordinates (docs/derivations/cable.md sec. 1, rigid placement).

    The start, end and interior point fix the plane and the side of the chord the arc lies on;
    the local frame has ``x`` along the chord and ``y`` towards the interior point.  In 2D this
    frame may be mirrored (an isometry), so arcs on either side of the chord are allowed.

    Parameters
    ----------
    start, end : array_like, shape ``(dim,)``
        End points, ``dim`` 2 or 3.
    angles_deg : (float, float)
        Tangent-to-chord angles at start and end, degrees in ``(0, 90)``.
    point : array_like, shape ``(dim,)``
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
    scale = float(np.max(np.abs(chord_vec)))  # no overflow or underflow in the squares
    length = float(np.linalg.norm(chord_vec / scale)) * scale if scale > 0 else 0.0
    if not length > 0.0:
        raise ChordError("chord", length, "start and end must be distinct points (chord > 0)")
    _check_chord(length)
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
