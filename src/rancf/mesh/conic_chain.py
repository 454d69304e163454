"""A conic arc cut into many sub-arcs, vectorized over the sub-arcs (meshing is O(n)).

Shape conventions: ``n`` sub-arcs; quadratic standard forms as control points ``(n, 3, dim)``
with interior weights ``(n,)``; cubic forms as control points ``(n, 4, dim)`` and weights
``(n, 4)``.  Formulas: sub-arcs by blossoming (docs/derivations/cable.md sec. 6), cubic forms with
mapping factor
K (docs/derivations/cable.md sec. 2, as :meth:`rancf.geometry.conic.Conic.cubic`), equal-arc-length
breakpoints by
safeguarded Newton on the arc length, Kopt per sub-arc as the minimizer of the sampled gradient
ratio (paper sec. 4.3).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.elements.mapping import K_RANGE
from rancf.errors import ConvergenceError
from rancf.geometry.conic_curve import Conic
from rancf.geometry.quadrature import integrate_many

__all__ = [
    "quadratic_speed",
    "arc_breakpoints",
    "sub_arcs",
    "cubic_forms",
    "kopt_many",
    "refined_extreme",
]

#: Samples of ``u`` for the vectorized Kopt (extrema refined by parabolas): 129 per sub-arc for
#: up to 16 000 sub-arcs, then fewer (at least 17) so that ~2e6 samples are kept; many sub-arcs
#: are short, so ``|r_u|`` varies little along each and the parabolas stay exact to ~1e-8.
_KOPT_SAMPLE_BUDGET = 1 << 21


def quadratic_speed(points: NDArray, omega: NDArray, u: NDArray) -> NDArray[np.float64]:
    """``|r_u|`` of standard quadratic forms ``(points (n, 3, dim), omega (n,))`` at ``u (n, m)``.

    ``r = A / D`` with ``A = (1-u)² P0 + 2u(1-u) ω P1 + u² P2``, ``D = (1-u)² + 2u(1-u) ω + u²``.
    """
    b0, b1, b2 = (1.0 - u) ** 2, 2.0 * u * (1.0 - u), u * u
    d0, d1, d2 = -2.0 * (1.0 - u), 2.0 - 4.0 * u, 2.0 * u
    om = omega[:, None]
    p0, p1, p2 = (points[:, None, i, :] for i in range(3))
    a = b0[..., None] * p0 + (b1 * om)[..., None] * p1 + b2[..., None] * p2
    da = d0[..., None] * p0 + (d1 * om)[..., None] * p1 + d2[..., None] * p2
    dd = b0 + b1 * om + b2
    ddd = d0 + d1 * om + d2
    num = da * dd[..., None] - a * ddd[..., None]
    return np.linalg.norm(num, axis=-1) / dd**2


def arc_breakpoints(conic: Conic, n: int) -> NDArray[np.float64]:
    """Quadratic parameters ``0 = u_0 < ... < u_n = 1`` at equal arc-length steps.

    An arc-length table on 64 equal parameter steps gives the first guess; Newton steps on
    ``s(u) - s_i`` (integrating only the increments) with bisection safeguards refine all
    breakpoints at once to round-off.
    """
    p0, p1, p2, om = conic.p0, conic.p1, conic.p2, conic.omega
    c0, c1, c2 = p1 - p0, p2 - p0, p2 - p1

    def speed(_: NDArray | None, x: NDArray) -> NDArray:
        # r_u = 2 [ω (1-u)² (P1-P0) + u² ω (P2-P1) + u (1-u) (P2-P0)] / D², D as above
        y = 1.0 - x
        a, b, c = om * y * y, om * x * x, x * y
        sq = sum((a * c0[i] + b * c2[i] + c * c1[i]) ** 2 for i in range(c0.size))
        d = y * y + 2.0 * c * om + x * x
        return 2.0 * np.sqrt(sq) / (d * d)

    grid = np.linspace(0.0, 1.0, 65)
    table = np.concatenate([[0.0], np.cumsum(integrate_many(speed, grid[:-1], grid[1:], points=8))])
    total = table[-1]
    if n == 1:
        return np.array([0.0, 1.0])
    s = total * np.arange(1, n) / n
    u = np.interp(s, table, grid)
    k = np.clip(np.searchsorted(grid, u) - 1, 0, grid.size - 2)
    done = table[k] + integrate_many(speed, grid[k], u, points=8)  # s(u) for the first guess
    lo, hi = np.zeros_like(u), np.ones_like(u)
    for _ in range(60):
        f = done - s
        lo = np.where(f <= 0.0, u, lo)
        hi = np.where(f >= 0.0, u, hi)
        if np.all(np.abs(f) <= 4.0 * np.finfo(float).eps * total):
            return np.concatenate([[0.0], u, [1.0]])
        sp = speed(None, u[:, None])[:, 0]
        new = u - f / sp
        new = np.where((new > lo) & (new < hi), new, 0.5 * (lo + hi))
        new = np.where(np.abs(f) <= 4.0 * np.finfo(float).eps * total, u, new)
        done = done + _signed_integral(speed, u, new)
        u = new
    raise ConvergenceError("equal arc-length breakpoints did not converge")


def _signed_integral(speed, a: NDArray, b: NDArray) -> NDArray:  # noqa: ANN001
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    moved = hi > lo
    out = np.zeros_like(a)
    if np.any(moved):
        out[moved] = integrate_many(speed, lo[moved], hi[moved], points=8)
    return np.where(b >= a, out, -out)


def sub_arcs(conic: Conic, u: NDArray) -> tuple[NDArray, NDArray]:
    """Standard forms of the parts ``[u_j, u_{j+1}]``: control points ``(n, 3, dim)``, ``ω (n,)``.

    Homogeneous control points ``b(ua,ua), b(ua,ub), b(ub,ub)`` by blossoming, then
    ``ω' = ω_mid / sqrt(ω_a ω_b)`` (as :meth:`Conic.sub_arc`).
    """
    h = conic.bezier.homogeneous  # (3, dim + 1)
    ua, ub = u[:-1], u[1:]

    def blossom(x: NDArray, y: NDArray) -> NDArray:
        c = np.stack([(1 - x) * (1 - y), (1 - x) * y + x * (1 - y), x * y], axis=1)
        return c @ h

    ha, hm, hb = blossom(ua, ua), blossom(ua, ub), blossom(ub, ub)
    pts = np.stack([ha[:, :-1] / ha[:, -1:], hm[:, :-1] / hm[:, -1:], hb[:, :-1] / hb[:, -1:]], 1)
    return pts, hm[:, -1] / np.sqrt(ha[:, -1] * hb[:, -1])


def cubic_forms(points: NDArray, omega: NDArray, k: NDArray) -> tuple[NDArray, NDArray]:
    """Cubic rational forms with mapping factors ``k (n,)``: control points and weights."""
    om = omega
    rho = np.cbrt(k / (1.0 - k))
    a1 = (1.0 - k) + 2.0 * om * k
    a2 = 2.0 * om * (1.0 - k) + k
    p0, p1, p2 = points[:, 0], points[:, 1], points[:, 2]
    q1 = ((1.0 - k)[:, None] * p0 + (2.0 * om * k)[:, None] * p1) / a1[:, None]
    q2 = ((2.0 * om * (1.0 - k))[:, None] * p1 + k[:, None] * p2) / a2[:, None]
    one = np.ones_like(k)
    w = np.stack([one, a1 * rho / (3.0 * k), a2 * rho**2 / (3.0 * k), one], axis=1)
    return np.stack([p0, q1, q2, p2], axis=1), w


def _log_ratio(log_s: NDArray, u: NDArray, t: NDArray) -> NDArray:
    """``log(max g / min g)`` with ``g(u) = s(u) (ρ (1-u) + u)²``, ``ρ = e^t``, per row."""
    lg = log_s + 2.0 * np.log(np.exp(t)[:, None] * (1.0 - u) + u)
    return refined_extreme(lg, 1.0) - refined_extreme(lg, -1.0)


def refined_extreme(y: NDArray, sign: float) -> NDArray:
    """Max (``sign = 1``) or min of sampled rows, refined by a parabola at interior extrema."""
    i = np.argmax(sign * y, axis=1)
    rows = np.arange(y.shape[0])
    best = y[rows, i]
    inner = (i > 0) & (i < y.shape[1] - 1)
    j = np.clip(i, 1, y.shape[1] - 2)
    ym, y0, yp = y[rows, j - 1], y[rows, j], y[rows, j + 1]
    curv = ym - 2.0 * y0 + yp
    with np.errstate(divide="ignore", invalid="ignore"):
        peak = y0 - (ym - yp) ** 2 / (8.0 * curv)
    ok = inner & (sign * curv < 0.0) & np.isfinite(peak)
    return np.where(ok, np.where(sign * peak > sign * best, peak, best), best)


def kopt_many(points: NDArray, omega: NDArray) -> NDArray[np.float64]:
    """Kopt of many conic arcs ``(points (n, 3, dim), omega (n,))`` at once.

    On the quadratic parameter ``u`` the cubic form with mapping factor K has
    ``|r_ξ| ∝ |r_u(u)| (ρ (1-u) + u)²``, ``ρ = (K/(1-K))^(1/3)``; the ratio of its extremes is
    minimized over ``log ρ`` by a 13-point scan and a golden-section search, with the extremes
    taken on 17 to 129 samples refined by parabolas.  The result agrees with the exact
    :func:`rancf.elements.mapping.kopt` to about 1e-6.
    """
    n = points.shape[0]
    u = np.linspace(0.0, 1.0, 1 + 16 * int(np.clip(_KOPT_SAMPLE_BUDGET // (16 * n), 1, 8)))
    log_s = np.log(quadratic_speed(points, omega, np.broadcast_to(u, (n, u.size))))
    t_lo, t_hi = (np.log(np.cbrt(k / (1.0 - k))) for k in K_RANGE)
    scan = np.linspace(t_lo, t_hi, 13)
    vals = np.stack([_log_ratio(log_s, u, np.full(n, t)) for t in scan], axis=1)
    best = np.argmin(vals, axis=1)
    a = scan[np.maximum(best - 1, 0)]
    b = scan[np.minimum(best + 1, scan.size - 1)]
    g = 0.5 * (np.sqrt(5.0) - 1.0)
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = _log_ratio(log_s, u, c), _log_ratio(log_s, u, d)
    for _ in range(30):  # bracket 0.5 -> 5e-7 in log(rho)
        left = fc < fd
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        c_new = np.where(left, b - g * (b - a), d)
        d_new = np.where(left, c, a + g * (b - a))
        f_new = _log_ratio(log_s, u, np.where(left, c_new, d_new))
        fc, fd = np.where(left, f_new, fd), np.where(left, fc, f_new)
        c, d = c_new, d_new
    rho3 = np.exp(3.0 * 0.5 * (a + b))
    return rho3 / (1.0 + rho3)
