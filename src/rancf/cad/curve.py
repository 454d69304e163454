"""One curve of a CAD file: the record every reader returns, and the check of a stored curve."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from rancf.errors import InputError
from rancf.geometry.nurbs import NurbsCurve

__all__ = ["CadCurve", "file_curve"]


@dataclass(frozen=True)
class CadCurve:
    """One curve of a CAD file.

    Attributes
    ----------
    index : int
        Position in the file (0-based, file order).
    name : str
        Its name in the file ("" when the format or the file gives none).
    curve : NurbsCurve
        Control points in metres (3 coordinates for DXF, STEP and IGES).
    notes : tuple of str
        One-line remarks on how it was read (e.g. a DXF's lengths converted to metres).
    """

    index: int
    name: str
    curve: NurbsCurve
    notes: tuple[str, ...] = ()


def file_curve(
    path: Path, index: int, degree: int, knots: ArrayLike, points: ArrayLike, weights: ArrayLike
) -> NurbsCurve:
    """The NURBS curve ``index`` of the file ``path``; a curve the file stores wrongly (knots,
    weights) raises the error of :class:`NurbsCurve` with the file and the curve named."""
    try:
        arrays = (np.asarray(x, dtype=float) for x in (knots, points, weights))
        return NurbsCurve(degree, *arrays)
    except InputError as exc:  # every InputError subclass takes (parameter, value, allowed)
        where = f"{path}: curve {index}: {exc.parameter}"
        raise type(exc)(where, exc.value, exc.allowed) from None
