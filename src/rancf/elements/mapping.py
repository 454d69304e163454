"""The mapping factor K: standard RANCF conic-section elements, gradient ratio and Kopt.

Conic-section paper sec. 4 (eqs. 27–29); docs/derivations/cable.md sec. 2 and 4.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import comb

import numpy as np
from numpy.polynomial import polynomial as P
from numpy.typing import NDArray

from rancf.elements.cable import nodal_from_bezier
from rancf.geometry.bezier import RationalBezier
from rancf.geometry.conic_curve import Conic
from rancf.geometry.conic_params import check_mapping_factor

__all__ = ["gradient_extrema", "gradient_ratio", "kopt", "ConicElement", "conic_element"]

#: Mapping factors searched by :func:`kopt` (the cubic form degenerates at 0 and 1).
K_RANGE = (1e-4, 1.0 - 1e-4)


def _power_basis(curve: RationalBezier) -> tuple[NDArray, NDArray]:
    """Homogeneous numerator ``A(ξ)`` (``(dim, n+1)``) and denominator ``D(ξ)`` in powers of ξ."""
    n = curve.degree
    basis = np.zeros((n + 1, n + 1))  # row i: Bernstein B_i^n in the power basis
    for i in range(n + 1):
        basis[i] = P.polymul(P.polypow([0.0, 1.0], i), P.polypow([1.0, -1.0], n - i))[
            : n + 1
        ] * comb(n, i)
    h = curve.homogeneous
    coef = basis.T @ h  # (n + 1, dim + 1)
    return coef[:, :-1].T, coef[:, -1]


def speed_critical_points(curve: RationalBezier) -> NDArray[np.float64]:
    """Every ``ξ ∈ [0, 1]`` where ``|r'(ξ)|`` can have a local extremum, ends included.

    With ``r = A / D``, ``|r'|² = |N|² / D⁴`` where ``N = A' D - A D'``; its derivative vanishes
    at the real roots of the polynomial ``(|N|²)' D - 4 |N|² D'`` (degree ≤ 10 for a cubic),
    found as companion-matrix eigenvalues.  Roots with a small imaginary part are kept too
    (their real parts are extra candidates; evaluating there never over-states an extremum).
    """
    a, d = _power_basis(curve)
    dd = P.polyder(d)
    num = [P.polysub(P.polymul(P.polyder(ai), d), P.polymul(ai, dd)) for ai in a]
    n2 = np.zeros(1)
    for c in num:
        n2 = P.polyadd(n2, P.polymul(c, c))
    crit = P.polysub(P.polymul(P.polyder(n2), d), 4.0 * P.polymul(n2, dd))
    crit = np.trim_zeros(np.asarray(crit, dtype=float), "b")
    cand = [0.0, 1.0]
    if crit.size > 1 and np.any(crit[1:] != 0.0):
        roots = P.polyroots(crit / np.abs(crit).max())
        real = roots[np.abs(roots.imag) <= 1e-6 * np.maximum(1.0, np.abs(roots))].real
        cand += [float(r) for r in real if 0.0 < r < 1.0]
    return np.unique(np.array(cand))


def gradient_extrema(curve: RationalBezier) -> tuple[float, float]:
    """``(min_ξ |r'(ξ)|, max_ξ |r'(ξ)|)`` over ``ξ ∈ [0, 1]``.

    Every local extremum is a root of ``r'·r''``.  The approximate roots of
    :func:`speed_critical_points` and 257 even samples (with the roots' neighbours) form a grid;
    each sign change of ``r'·r''`` on it is solved by Brent's method (``xtol`` 1e-15), and the
    speed is compared at those roots and at both ends — so no narrow peak is missed however
    extreme the conic.
    """
    from scipy.optimize import brentq  # lazy: scipy.optimize takes 0.4 s to import

    approx = speed_critical_points(curve)
    grid = np.unique(
        np.clip(
            np.concatenate([np.linspace(0.0, 1.0, 257), approx, approx - 1e-4, approx + 1e-4]),
            0.0,
            1.0,
        )
    )

    def slope(x: NDArray | float) -> NDArray:
        _, d1, d2 = curve.derivatives(np.atleast_1d(x), 2)
        return np.einsum("ij,ij->i", d1, d2)

    f = slope(grid)
    xs = [0.0, 1.0]

    def scalar(t: float) -> float:
        return float(slope(t)[0])

    for i in np.flatnonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0):
        a, b = grid[i], grid[i + 1]
        if scalar(a) * scalar(b) < 0.0:
            xs.append(brentq(scalar, a, b, xtol=1e-15))
        else:  # |r'·r''| at round-off level at an end of the bracket
            xs += [a, b]
    xs += [float(x) for x in grid[1:-1][f[1:-1] == 0.0]]
    s = np.linalg.norm(curve.derivatives(np.array(xs), 1)[1], axis=1)
    return float(s.min()), float(s.max())


def gradient_ratio(curve: RationalBezier) -> float:
    """Gradient ratio ``max_ξ |r_ξ| / min_ξ |r_ξ|`` (paper eq. 29); 1 means arc-length mapping."""
    lo, hi = gradient_extrema(curve)
    return hi / lo


def kopt(conic: Conic, xatol: float = 1e-10) -> float:
    """Optimal mapping factor: the K in (0, 1) that minimizes the gradient ratio (paper sec. 4.3).

    A scan of 41 factors, evenly spaced in ``log(K / (1 - K))`` over :data:`K_RANGE`, brackets
    the best one (the ratio need not be unimodal for extreme conics), and a bounded Brent
    search refines it inside that bracket.
    """
    from scipy.optimize import minimize_scalar  # lazy, as above

    lo, hi = (np.log(k / (1.0 - k)) for k in K_RANGE)
    z = np.linspace(lo, hi, 41)
    ks = 1.0 / (1.0 + np.exp(-z))
    ratios = np.array([gradient_ratio(conic.cubic(k)) for k in ks])
    i = int(np.argmin(ratios))
    lo, hi = ks[max(i - 1, 0)], ks[min(i + 1, ks.size - 1)]
    res = minimize_scalar(
        lambda k: gradient_ratio(conic.cubic(k)),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": xatol},
    )
    return float(res.x) if res.fun <= ratios[i] else float(ks[i])


@dataclass(frozen=True)
class ConicElement:
    """One standard RANCF conic-section element (paper sec. 3.2, eqs. 24–26).

    Attributes
    ----------
    k : float
        Mapping factor K.
    curve : RationalBezier
        The cubic rational form (end weights 1).
    scale : float
        Gradient scale ``l``.
    nodal : ndarray, shape (4, dim)
        ``[rA, rA_x, rB, rB_x]``.
    gradient_ratio : float
        ``max |r_ξ| / min |r_ξ|``.
    """

    k: float
    curve: RationalBezier
    scale: float
    nodal: NDArray[np.float64]
    gradient_ratio: float

    @property
    def weights(self) -> NDArray[np.float64]:
        """The four weights ``(1, w1, w2, 1)``."""
        return self.curve.weights


def conic_element(conic: Conic, k: float | None = None, scale: float | None = None) -> ConicElement:
    """The single-element definition of a conic arc with mapping factor K.

    Parameters
    ----------
    conic : Conic
    k : float, optional
        Mapping factor in (0, 1); default Kopt.
    scale : float, optional
        Gradient scale ``l``; default the arc length, as in the paper.
    """
    kk = kopt(conic) if k is None else check_mapping_factor(k)
    curve = conic.cubic(kk)
    length = conic.arc_length() if scale is None else float(scale)
    return ConicElement(kk, curve, length, nodal_from_bezier(curve, length), gradient_ratio(curve))
