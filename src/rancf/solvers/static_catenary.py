"""The inextensible catenary of a line between two points, lying on a seabed where it would dip
below it: the shapes of the sagged start (:mod:`rancf.solvers.sag_start`, whose docstring states
them) and their touchdown points.

* Free: ``z = z_v + a (cosh((x - x_v)/a) - 1)`` through both ends with the line's length.
* On a horizontal floor below the ends: two catenaries from the ends down to touchdown points,
  tangent to the floor there, the line straight on the floor between them (one horizontal
  tension ``H = w a``: no friction).
* On a sloped floor ``z = floor + x tan β`` with one end on it: straight on it from that end
  to the touchdown, where the catenary to the other end leaves it tangent to it
  (``sinh u_t = tan β``; MoorPy's frictionless sloped seabed, ``moorpy.Catenary.catenary`` with
  ``alpha``).
* Free with a weight per length that changes from element to element (a line crossing the free
  surface, its buoyancy only under water): :func:`weighted_catenary`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["catenary_shape", "free_bend_radii", "touchdowns", "weighted_catenary"]


def _bisect(f: Any, lo: float, hi: float, n: int = 200) -> float:
    """A root of ``f`` in ``[lo, hi]`` (``f(lo) > 0 >= f(hi)``) by bisection in ``log``."""
    for _ in range(n):
        mid = math.sqrt(lo * hi)
        if f(mid) > 0.0:
            lo = mid
        else:
            hi = mid
        if hi / lo - 1.0 < 1e-14:
            break
    return math.sqrt(lo * hi)


def _free(span: float, rise: float, length: float) -> tuple[float, float]:
    """``(a, x_v)`` of the catenary ``z = z_v + a (cosh((x - x_v)/a) - 1)`` of ``length``
    from ``(0, 0)`` to ``(span, rise)``: ``sqrt(L² - rise²) = 2 a sinh(span / (2 a))``,
    ``x_v = span/2 - a atanh(rise / L)``."""
    c = math.sqrt(length**2 - rise**2)

    def f(a: float) -> float:  # positive while a is too small (too long a curve)
        u = span / (2.0 * a)
        return 2.0 * a * math.sinh(u) - c if u < 700.0 else math.inf

    a = _bisect(f, span * 1e-6, span * 1e6)
    return a, span / 2.0 - a * math.atanh(rise / length)


def _grounded(span: float, h1: float, h2: float, length: float) -> float | None:
    """``a`` of the line touching down on a plane ``h1``, ``h2`` below its ends (module
    docstring), or None where the free catenary does not reach the plane or the line is longer
    than ``h1 + h2 + span`` (no touchdown shape: it would pile up)."""
    if length >= h1 + h2 + span:
        return None

    def parts(a: float) -> tuple[float, float]:  # suspended lengths, horizontal extents
        s = [math.sqrt(h * h + 2.0 * a * h) for h in (h1, h2)]
        return sum(s), sum(a * math.asinh(si / a) for si in s)

    a_hi = _bisect(lambda a: span - parts(a)[1], span * 1e-9, span * 1e9)  # no grounded length
    if parts(a_hi)[0] >= length:
        return None  # the hanging line does not reach the plane
    return _bisect(lambda a: parts(a)[0] + span - parts(a)[1] - length, span * 1e-9, a_hi)


def _sloped(dx: float, dz: float, length: float, slope: float) -> tuple[float, float] | None:
    """``(l_b, a)`` of a line of ``length`` lying from ``(0, 0)`` along the floor ``z = x tan β``
    (``slope = tan β``) for the grounded length ``l_b``, then hanging as the catenary tangent to
    the floor at the touchdown ``l_b (cos β, sin β)`` (``sinh u_t = tan β``) up to ``(dx, dz)``
    above the floor (module docstring); None where the line is too short to touch it or too long
    to hang (it would pile up).  Given ``l_b``, ``a`` solves ``a (cosh(u_t + Δx / a) - cosh
    u_t) = Δz`` (the catenary from the touchdown to the end); ``l_b`` makes the lengths add up:
    ``l_b + a (sinh(u_t + Δx / a) - sinh u_t) = length``."""
    c, sn = 1.0 / math.hypot(1.0, slope), slope / math.hypot(1.0, slope)
    ut = math.asinh(slope)

    def hang(lb: float) -> tuple[float, float] | None:  # (a, hanging length) from l_b
        ex, ez = dx - lb * c, dz - lb * sn
        if ex <= 0.0 or ez <= ex * slope:
            return None
        size = math.hypot(ex, ez)

        def f(a: float) -> float:  # positive while a is too small (the curve too deep)
            u = ut + ex / a
            return a * (math.cosh(u) - math.cosh(ut)) - ez if u < 700.0 else math.inf

        a = _bisect(f, size * 1e-9, size * 1e9)
        return a, a * (math.sinh(ut + ex / a) - math.sinh(ut))

    def gap(lb: float) -> float:  # positive while l_b is too long
        h = hang(lb)
        return math.inf if h is None else lb + h[1] - length

    lo = 0.0
    if not gap(lo) < 0.0:
        return None  # the line is too short to lie on the floor
    top = min(dx / c, length)  # the touchdown short of the end's foot: l_b < top
    hi = next((t for t in (top * (1.0 - 0.5**k) for k in range(1, 50)) if gap(t) > 0.0), None)
    if hi is None or not math.isfinite(gap(hi)):
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if gap(mid) < 0.0 else (lo, mid)
        if hi - lo < 1e-13 * length:
            break
    lb = 0.5 * (lo + hi)
    h = hang(lb)
    return None if h is None else (lb, h[0])


def _sloped_shape(
    span: float, rise: float, length: float, s: NDArray, floor: float, slope: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """:func:`catenary_shape` on the sloped floor ``z = floor + x slope`` with one end on it
    (within 1e-6 of the length), or None (no end on it, or no grounded shape)."""
    tol = 1e-6 * length
    h1, h2 = -floor, rise - floor - span * slope
    if abs(h1) <= tol and h2 > tol:  # the start on the floor
        found = _sloped(span, rise - floor, length, slope)
        mirror = False
    elif abs(h2) <= tol and h1 > tol:  # the end on it: solved from the end, mirrored
        found = _sloped(span, h1 - span * slope, length, -slope)
        mirror = True
    else:
        return None
    if found is None:
        return None
    lb, a = found
    sig = length - s if mirror else s  # arc length from the grounded end
    k = -slope if mirror else slope
    c, sn = 1.0 / math.hypot(1.0, k), k / math.hypot(1.0, k)
    ut = math.asinh(k)
    on = sig <= lb
    u = np.where(on, ut, np.arcsinh(math.sinh(ut) + np.maximum(sig - lb, 0.0) / a))
    x = np.where(on, sig * c, lb * c + a * (u - ut))
    z = np.where(on, sig * sn, lb * sn + a * (np.cosh(u) - math.cosh(ut)))
    tan = np.c_[1.0 / np.cosh(u), np.tanh(u)]
    if mirror:  # from the end back: x measured from the end, the tangent reversed
        return np.c_[span - x, z + floor + span * slope], np.c_[tan[:, 0], -tan[:, 1]]
    return np.c_[x, z + floor], tan


def free_bend_radii(span: float, rise: float, length: float, s: NDArray) -> NDArray[np.float64]:
    """The smallest bend radius ``a cosh²(u)`` (``u = (x - x_v) / a``, :func:`_free`) over each
    stretch ``[s_i, s_(i+1)]`` of the arc lengths ``s`` along the inextensible catenary of
    ``length`` hanging free from ``(0, 0)`` to ``(span, rise)``: ``a`` at the vertex where the
    stretch holds it (``n - 1`` values)."""
    a, xv = _free(span, rise, length)
    u = np.arcsinh(math.sinh(-xv / a) + np.clip(np.asarray(s, dtype=float), 0.0, length) / a)
    lo, hi = u[:-1], u[1:]
    nearest = np.where((lo <= 0.0) & (hi >= 0.0), 0.0, np.minimum(np.abs(lo), np.abs(hi)))
    return np.asarray(a * np.cosh(nearest) ** 2, dtype=float)


def catenary_shape(
    span: float,
    rise: float,
    length: float,
    s: NDArray,
    floor: float | None = None,
    slope: float = 0.0,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Points ``(x, z)`` and unit tangents of the inextensible catenary of ``length`` from
    ``(0, 0)`` to ``(span, rise)`` (``span > 0``, ``length`` above the chord) at the arc lengths
    ``s`` from its start, lying on the line ``z = floor + x slope`` where it would dip below it
    (module docstring); ``(n, 2)`` each."""
    s = np.clip(np.asarray(s, dtype=float), 0.0, length)
    a = None
    if floor is not None and slope != 0.0:
        shape = _sloped_shape(span, rise, length, s, floor, slope)
        if shape is not None:
            return shape
        floor = None  # both ends above a sloped floor: hanging free
    if floor is not None:
        h1, h2 = max(-floor, 0.0), max(rise - floor, 0.0)
        a = _grounded(span, h1, h2, length)
    if a is None or floor is None:
        a, xv = _free(span, rise, length)
        u1 = -xv / a
        u = np.arcsinh(math.sinh(u1) + s / a)
        x = xv + a * u
        z = a * (np.cosh(u) - math.cosh(u1))
        return np.c_[x, z], np.c_[1.0 / np.cosh(u), np.tanh(u)]
    s1, s2 = (math.sqrt(h * h + 2.0 * a * h) for h in (h1, h2))
    x1, x2 = (a * math.asinh(si / a) for si in (s1, s2))
    u = np.zeros_like(s)  # on the plane: u = 0, the tangent horizontal
    first, last = s < s1, s > length - s2
    u[first] = -np.arcsinh((s1 - s[first]) / a)
    u[last] = np.arcsinh((s[last] - (length - s2)) / a)
    x = np.where(first, x1 + a * u, np.where(last, span - x2 + a * u, x1 + s - s1))
    z = floor + a * (np.cosh(u) - 1.0)
    return np.c_[x, z], np.c_[1.0 / np.cosh(u), np.tanh(u)]


def touchdowns(
    span: float, rise: float, length: float, floor: float, slope: float
) -> tuple[float, list[float]] | None:
    """The bend radius ``T / w`` where the shape of :func:`catenary_shape` on the floor
    ``z = floor + x slope`` meets it (``a`` on a horizontal floor; ``a cosh u_t = a sqrt(1 +
    tan² β)`` on a sloped one) and the arc lengths of its touchdown points (where a hanging part
    meets it), or None (the line hangs free)."""
    if slope != 0.0:
        return _sloped_touchdown(span, rise, length, floor, slope)
    h1, h2 = max(-floor, 0.0), max(rise - floor, 0.0)
    a = _grounded(span, h1, h2, length)
    if a is None:
        return None
    s1, s2 = (math.sqrt(h * h + 2.0 * a * h) for h in (h1, h2))
    return a, [s for s, h in ((s1, h1), (length - s2, h2)) if h > 0.0]


def _sloped_touchdown(
    span: float, rise: float, length: float, floor: float, slope: float
) -> tuple[float, list[float]] | None:
    """:func:`touchdowns` on a sloped floor: ``T / w = a cosh u_t = a sqrt(1 + tan² β)``
    at the touchdown of :func:`_sloped` (one end on the floor), or None."""
    tol = 1e-6 * length
    h1, h2 = -floor, rise - floor - span * slope
    if abs(h1) <= tol and h2 > tol:
        found = _sloped(span, rise - floor, length, slope)
        at = None if found is None else found[0]
    elif abs(h2) <= tol and h1 > tol:
        found = _sloped(span, h1 - span * slope, length, -slope)
        at = None if found is None else length - found[0]
    else:
        return None
    if found is None or at is None:
        return None
    return found[1] * math.hypot(1.0, slope), [at]


def _weighted_ends(
    h: float, v0: float, ell: NDArray, w: NDArray
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Node increments ``dx``, ``dz`` and the vertical forces ``V`` at the nodes of the
    inextensible line with horizontal tension ``h``, ``V = v0`` at its start and the weight
    ``w_i`` per length on its piece ``i`` of length ``ell_i`` (:func:`weighted_catenary`)."""
    v = v0 + np.r_[0.0, np.cumsum(w * ell)]
    t = np.hypot(h, v)
    va, vb, ta, tb = v[:-1], v[1:], t[:-1], t[1:]
    dz = (va + vb) * ell / (ta + tb)  # (tb - ta) / w without the division
    light = np.abs(w * ell) <= 1e-9 * (h + np.abs(va))
    wl = np.where(light, 1.0, w)
    dx = np.where(light, h * ell / ta, h / wl * (np.arcsinh(vb / h) - np.arcsinh(va / h)))
    return dx, dz, v


def weighted_catenary(
    span: float, rise: float, s: NDArray, w: NDArray, guess: tuple[float, float] | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64], tuple[float, float]] | None:
    """Points ``(x, z)`` and unit tangents at the arc lengths ``s`` (the nodes, ``n + 1``) of
    the inextensible line hanging free from ``(0, 0)`` to ``(span, rise)`` whose piece ``i``
    (from ``s_i`` to ``s_i+1``) weighs ``w_i`` per length (along ``-z``; any sign), and its
    ``(H, V0)``, or None where Newton's method finds none.

    The tension ``(H, V(s))`` has ``V(s) = V0 + ∫ w`` (``H`` constant); on a piece with
    ``V`` from ``V_a`` to ``V_b`` the catenary of ``a = H / w_i`` moves it by
    ``dx = a (asinh(V_b / H) − asinh(V_a / H))``, ``dz = (T_b − T_a) / w_i``
    (``T = sqrt(H² + V²)``; straight where ``w_i`` vanishes).  ``H`` (as ``log H``) and
    ``V0`` solve ``Σ dx = span``, ``Σ dz = rise`` by Newton's method from ``guess = (H, V0)``
    (default: the uniform catenary of the mean weight ``w̄``, ``H = |w̄| a``) with
    central-difference derivatives.
    """
    ell = np.diff(np.asarray(s, dtype=float))
    w = np.asarray(w, dtype=float)
    length, scale = float(ell.sum()), float(np.sum(np.abs(w) * ell))
    if not scale > 0.0:
        return None
    if guess is None:
        mean = float(np.sum(w * ell)) / length
        sign = 1.0 if mean >= 0.0 else -1.0
        a, xv = _free(span, sign * rise, length)
        h0 = a * max(abs(mean), scale / length * 1e-3)
        guess = (h0, sign * h0 * math.sinh(-xv / a))

    def gap(p: NDArray) -> NDArray[np.float64]:
        dx, dz, _ = _weighted_ends(math.exp(p[0]), p[1] * scale, ell, w)
        return np.array([dx.sum() - span, dz.sum() - rise]) / float(ell.sum())

    p = np.array([math.log(guess[0]), guess[1] / scale])
    for _ in range(60):
        r = gap(p)
        if np.max(np.abs(r)) < 1e-13:
            break
        jac = np.column_stack([(gap(p + d) - gap(p - d)) / 2e-7 for d in np.eye(2) * 1e-7])
        step = np.linalg.solve(jac, -r)
        p = p + step * min(1.0, 1.0 / max(np.max(np.abs(step)), 1e-300))
    else:
        return None
    h, v0 = math.exp(p[0]), p[1] * scale
    dx, dz, v = _weighted_ends(h, v0, ell, w)
    pts = np.c_[np.r_[0.0, np.cumsum(dx)], np.r_[0.0, np.cumsum(dz)]]
    return pts, np.c_[np.full(v.shape, h), v] / np.hypot(h, v)[:, None], (h, v0)
