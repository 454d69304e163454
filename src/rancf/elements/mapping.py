"""The mapping factor K: standard RANCF conic-section elements, gradient ratio and Kopt.

Conic-section paper sec. 4 (eqs. 27–29); math note sec. 2 and 4.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rancf.elements.cable import nodal_from_bezier
from rancf.geometry.bezier import RationalBezier
from rancf.geometry.conic import Conic, check_mapping_factor

__all__ = ["gradient_extrema", "gradient_ratio", "kopt", "ConicElement", "conic_element"]

_SAMPLES = 513


def gradient_extrema(curve: RationalBezier) -> tuple[float, float]:
    """``(min_ξ |r'(ξ)|, max_ξ |r'(ξ)|)`` over ``ξ ∈ [0, 1]``, located to round-off.

    A dense sample brackets each extremum; a bounded Brent search on the neighbouring sample
    interval refines it (``xatol`` 1e-13), so the ratio is exact to far better than 1e-4.
    """
    from scipy.optimize import minimize_scalar  # lazy: a 0.4 s import, not needed for lines

    xi = np.linspace(0.0, 1.0, _SAMPLES)

    def speed(x: NDArray | float) -> NDArray:
        return np.linalg.norm(curve.derivatives(np.atleast_1d(x), 1)[1], axis=1)

    s = speed(xi)
    result = []
    for sign in (1.0, -1.0):  # minimum, then maximum
        i = int(np.argmin(sign * s))
        best = sign * s[i]
        lo, hi = xi[max(i - 1, 0)], xi[min(i + 1, xi.size - 1)]
        if 0 < i < xi.size - 1:
            res = minimize_scalar(
                lambda x, sg=sign: sg * float(speed(x)[0]),
                bounds=(lo, hi),
                method="bounded",
                options={"xatol": 1e-13},
            )
            best = min(best, float(res.fun))
        result.append(sign * best)
    return result[0], result[1]


def gradient_ratio(curve: RationalBezier) -> float:
    """Gradient ratio ``max_ξ |r_ξ| / min_ξ |r_ξ|`` (paper eq. 29); 1 means arc-length mapping."""
    lo, hi = gradient_extrema(curve)
    return hi / lo


def kopt(conic: Conic, xatol: float = 1e-10) -> float:
    """Optimal mapping factor: the K in (0, 1) that minimizes the gradient ratio (paper sec. 4.3).

    The ratio is unimodal in K, so a bounded Brent search converges in a few dozen evaluations.
    """
    from scipy.optimize import minimize_scalar  # lazy: a 0.4 s import, not needed for lines

    res = minimize_scalar(
        lambda k: gradient_ratio(conic.cubic(k)),
        bounds=(1e-4, 1.0 - 1e-4),
        method="bounded",
        options={"xatol": xatol},
    )
    return float(res.x)


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
