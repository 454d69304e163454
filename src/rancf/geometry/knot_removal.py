"""Knot removal for NURBS curves (Piegl & Tiller, *The NURBS Book*, 2nd ed., sec. 5.4, A5.8).

Removal works on homogeneous control points ``(w P, w)``: knot ``u`` of multiplicity ``s`` can be
removed once when the curve is ``C^{p-s+1}`` there, which A5.8 detects by solving for the new
control points from both sides and comparing them.  :func:`remove_knots` removes every interior
knot as often as the curve allows and keeps a removal only if the new curve also matches the old
one at sample points of every span to ``rtol`` (relative to the size of the control polygon), so
the result represents the same curve to round-off with the lowest interior multiplicities.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.geometry.bezier import to_homogeneous
from rancf.geometry.nurbs import NurbsCurve

__all__ = ["remove_knot_once", "remove_knots"]


def remove_knot_once(
    knots: NDArray, hpts: NDArray, degree: int, r: int, tol: float
) -> tuple[NDArray, NDArray] | None:
    """Remove the knot ``knots[r]`` once (A5.8 with one removal), or None if not within ``tol``.

    Parameters
    ----------
    knots : ndarray, shape (n_ctrl + degree + 1,)
    hpts : ndarray, shape (n_ctrl, dim + 1)
        Homogeneous control points.
    degree : int
    r : int
        Index of the *last* occurrence of the knot value in ``knots``.
    tol : float
        Largest allowed distance between the two solutions for the new control points.

    Returns
    -------
    (new_knots, new_hpts) or None
    """
    p = degree
    u = knots[r]
    s = int(np.sum(knots == u))
    first, last = r - p, r - s
    off = first - 1
    temp = np.empty((last - off + 2, hpts.shape[1]))
    temp[0] = hpts[off]
    temp[last + 1 - off] = hpts[last + 1]
    i, j, ii, jj = first, last, 1, last - off
    while j - i > 0:
        alfi = (u - knots[i]) / (knots[i + p + 1] - knots[i])
        alfj = (u - knots[j]) / (knots[j + p + 1] - knots[j])
        temp[ii] = (hpts[i] - (1.0 - alfi) * temp[ii - 1]) / alfi
        temp[jj] = (hpts[j] - alfj * temp[jj + 1]) / (1.0 - alfj)
        i, ii, j, jj = i + 1, ii + 1, j - 1, jj - 1
    if j - i < 0:
        err = np.linalg.norm(temp[ii - 1] - temp[jj + 1])
    else:
        alfi = (u - knots[i]) / (knots[i + p + 1] - knots[i])
        err = np.linalg.norm(hpts[i] - (alfi * temp[ii + 1] + (1.0 - alfi) * temp[ii - 1]))
    if not err <= tol:
        return None
    new = np.array(hpts)
    i, j = first, last
    while j - i > 0:
        new[i] = temp[i - off]
        new[j] = temp[j - off]
        i, j = i + 1, j - 1
    fout = (2 * r - s - p) // 2
    return np.delete(knots, r), np.delete(new, fout, axis=0)


def _samples(curve: NurbsCurve) -> NDArray[np.float64]:
    a, b = curve.domain
    br = np.unique(curve.knots[(curve.knots >= a) & (curve.knots <= b)])
    t = np.linspace(0.0, 1.0, 9)
    return np.unique(
        np.concatenate([lo + t * (hi - lo) for lo, hi in zip(br[:-1], br[1:], strict=True)])
    )


def remove_knots(curve: NurbsCurve, rtol: float = 1e-12) -> NurbsCurve:
    """The same curve with every removable interior knot removed (as often as possible).

    A removal is attempted with tolerance ``1e-10 * size`` (``size`` the largest homogeneous
    control-point coordinate) and kept only if the curve moves by at most ``rtol * size`` at
    9 points per span of the original curve.
    """
    h = to_homogeneous(curve.points, curve.weights)
    size = float(np.abs(h).max())
    knots = np.array(curve.knots)
    u_check = _samples(curve)
    ref = curve(u_check)
    a, b = curve.domain
    p = curve.degree
    for value in np.unique(knots[(knots > a) & (knots < b)]):
        while True:
            r = int(np.flatnonzero(knots == value)[-1])
            out = remove_knot_once(knots, h, p, r, 1e-10 * size)
            if out is None:
                break
            trial = NurbsCurve(p, out[0], out[1][:, :-1] / out[1][:, -1:], out[1][:, -1])
            if not np.abs(trial(u_check) - ref).max() <= rtol * max(np.abs(ref).max(), 1e-300):
                break
            knots, h = out
            if not np.any(knots == value):
                break
    return NurbsCurve(p, knots, h[:, :-1] / h[:, -1:], h[:, -1])
