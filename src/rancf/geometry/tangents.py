"""Tangent continuity: the angle between two tangents, and when a curve counts as closed.

Every test of a kink (a joint of two curves, an interior knot of full multiplicity) and of a
closed curve uses these tolerances and :func:`vector_angle`, which is accurate near zero.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from rancf.geometry.conic_params import pad3

__all__ = ["GAP_RTOL", "KINK_TOL", "vector_angle", "is_closed", "touching_ends_note"]

#: Largest gap between two ends that meet, relative to the size of the curve(s).
GAP_RTOL = 1e-10
#: Largest angle [rad] between two tangents that count as the same direction.
KINK_TOL = 1e-8


def vector_angle(a: ArrayLike, b: ArrayLike) -> float:
    """Angle [rad] in ``[0, π]`` between two planar or spatial vectors.

    ``atan2(|a × b|, a · b)``: accurate for every angle, unlike ``arccos`` of the normalized
    dot product, which turns one unit of round-off below 1 into about 1.5e-8 rad.
    """
    a3, b3 = pad3(a), pad3(b)
    return float(np.arctan2(np.linalg.norm(np.cross(a3, b3)), np.dot(a3, b3)))


def is_closed(
    start: ArrayLike, start_tangent: ArrayLike, end: ArrayLike, end_tangent: ArrayLike, size: float
) -> bool:
    """Whether a curve is closed: its end is its start (within ``GAP_RTOL * size``) and it
    arrives there in the direction it left (within ``KINK_TOL``).

    Ends that merely touch at an angle (a kink) make an open curve.
    """
    gap = float(np.linalg.norm(np.asarray(end, float) - np.asarray(start, float)))
    return gap <= GAP_RTOL * size and vector_angle(end_tangent, start_tangent) <= KINK_TOL


def touching_ends_note(
    start: ArrayLike, start_tangent: ArrayLike, end: ArrayLike, end_tangent: ArrayLike, size: float
) -> tuple[str, ...]:
    """The remark for a curve whose ends meet at an angle (a kink): it stays an open curve, since
    one shared node cannot carry two tangents; empty if the ends do not meet."""
    if float(np.linalg.norm(np.asarray(end) - np.asarray(start))) > GAP_RTOL * size:
        return ()
    where = ", ".join(f"{x:.6g}" for x in np.asarray(start))
    angle = np.degrees(vector_angle(end_tangent, start_tangent))
    return (
        f"geometry: the curve's ends meet at ({where}) at an angle of {angle:.4g} deg: it is "
        "meshed as an open curve, its ends not joined (a closed curve needs the same tangent "
        "at both ends)",
    )
