"""The elastic catenary with rancf's Green–Lagrange law, Irvine's closed form, the hanging chain.

Independent of rancf (numpy/scipy).  A cable without bending stiffness: the strain energy per unit
reference length ``EA eps^2 / 2`` with ``eps = (lambda^2 - 1)/2`` gives the tension
``T = EA eps lambda`` (eq. (2) of :mod:`tests.references.elastica` without bending), solved for the
stretch by :func:`tests.references.elastica.stretch`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import jn_zeros

from tests.references.elastica import stretch


@dataclass(frozen=True)
class Catenary:
    """An elastic catenary between supports at the same height, span ``x = 0 .. span``.

    ``horizontal``: the horizontal force H (constant); ``vertical``: each support's vertical
    reaction (half the weight); ``end_tension``: the tension at the supports; ``mid_sag``: the
    depth of the midpoint (positive down); ``s, x, y, tension`` sampled along the reference arc.
    """

    horizontal: float
    vertical: float
    end_tension: float
    mid_sag: float
    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    tension: np.ndarray


def elastic_catenary(
    span: float,
    length: float,
    ea: float,
    weight: float,
    *,
    law: Literal["green_lagrange", "engineering"] = "green_lagrange",
    points: int = 201,
) -> Catenary:
    """A cable without bending stiffness of reference ``length`` under its ``weight`` [N/m of
    reference length], pinned at ``(0, 0)`` and ``(span, 0)``.

    The internal force is ``n = (H, w s0 - V)`` with ``V = w L / 2`` (symmetry), the tension
    ``T = |n|``, and ``r' = lambda n / T`` with ``T = EA eps lambda``, ``eps = (lambda^2 - 1)/2``
    (``"green_lagrange"``, rancf's law, eq. (2) without bending) or ``T = EA (lambda - 1)``
    (``"engineering"``, Irvine's).  ``x(L; H) = span`` is solved for ``H`` (Brent) with the
    integrals by adaptive quadrature.
    """
    v = 0.5 * weight * length

    def lam(t: float) -> float:
        return stretch(t, 0.0, ea, 1.0, "simple") if law == "green_lagrange" else 1.0 + t / ea

    def dx(s: float, h: float) -> float:
        t = np.hypot(h, weight * s - v)
        return lam(t) * h / t

    def dy(s: float, h: float) -> float:
        ny = weight * s - v
        t = np.hypot(h, ny)
        return lam(t) * ny / t

    def integral(f: Callable[[float, float], float], a: float, b: float, h: float) -> float:
        return quad(f, a, b, args=(h,), epsabs=1e-13 * length, epsrel=1e-12, limit=200)[0]

    def x_end(h: float) -> float:
        return 2.0 * integral(dx, 0.0, 0.5 * length, h)

    hi = v
    while x_end(hi) < span:
        hi *= 2.0
    h = brentq(lambda h: x_end(h) - span, 1e-9 * v, hi, xtol=1e-13 * hi, rtol=1e-15)
    s = np.linspace(0.0, length, points)
    xs = np.zeros(points)
    ys = np.zeros(points)
    for i in range(1, points):
        xs[i] = xs[i - 1] + integral(dx, s[i - 1], s[i], h)
        ys[i] = ys[i - 1] + integral(dy, s[i - 1], s[i], h)
    sag = -integral(dy, 0.0, 0.5 * length, h)
    return Catenary(
        horizontal=float(h),
        vertical=float(v),
        end_tension=float(np.hypot(h, v)),
        mid_sag=float(sag),
        s=s,
        x=xs,
        y=ys,
        tension=np.hypot(h, weight * s - v),
    )


def irvine_catenary(span: float, length: float, ea: float, weight: float) -> dict[str, float]:
    """Irvine's closed-form elastic catenary (engineering strain ``T = EA (lambda - 1)``).

    With ``V = wL/2``: ``span = H L / EA + (2H/w) asinh(V/H)`` (solved for H) and
    ``sag = (sqrt(H^2 + V^2) - H)/w + w L^2 / (8 EA)`` (Irvine, *Cable Structures*, 1981, 2.1).
    """
    v = 0.5 * weight * length

    def f(h: float) -> float:
        return h * length / ea + 2.0 * h / weight * np.arcsinh(v / h) - span

    hi = v
    while f(hi) < 0.0:
        hi *= 2.0
    h = brentq(f, 1e-9 * v, hi, xtol=1e-13 * hi, rtol=1e-15)
    sag = (np.hypot(h, v) - h) / weight + weight * length**2 / (8.0 * ea)
    return {
        "horizontal": float(h),
        "vertical": float(v),
        "end_tension": float(np.hypot(h, v)),
        "mid_sag": float(sag),
    }


def chain_frequencies(length: float, g: float = 9.81, count: int = 3) -> np.ndarray:
    """Natural frequencies [Hz] of a heavy chain hanging from a pin (Bernoulli, 1732):
    ``f_n = (j_{0,n} / 2) sqrt(g/L) / (2 pi)``, ``j_{0,n}`` the zeros of the Bessel J0."""
    return jn_zeros(0, count) / 2.0 * np.sqrt(g / length) / (2.0 * np.pi)


#: Code_Aster SSNL114 (Irvine's elastic catenary): span and reference length [m], A [m^2], E [Pa],
#: rho [kg/m^3], g [m/s^2].
SSNL114 = {"span": 325.0, "length": 325.0, "area": 2.2783e-4, "youngs": 5.7e10, "density": 2844.23}


def ssnl114(law: Literal["green_lagrange", "engineering"] = "green_lagrange") -> Catenary:
    """Code_Aster SSNL114 (:data:`SSNL114`, g = 9.81 m/s^2) by :func:`elastic_catenary`."""
    c = SSNL114
    return elastic_catenary(
        c["span"],
        c["length"],
        c["youngs"] * c["area"],
        c["density"] * c["area"] * 9.81,
        law=law,
    )
