"""NURBS curves as exact RANCF meshes: every knot span (a rational Bézier segment) split into
equal parameter steps by blossoming, the pieces joined with consistent shared nodes
(:func:`rancf.mesh.mesh.mesh_from_curves`, docs/derivations/cable.md sec. 6)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.geometry.bezier import RationalBezier
from rancf.geometry.nurbs import NurbsCurve
from rancf.mesh.mesh import CableMesh, check_element_count, mesh_from_curves

__all__ = ["mesh_nurbs", "mesh_segments"]


def mesh_nurbs(curve: NurbsCurve, n_per_span: int = 1) -> CableMesh:
    """A tangent-continuous NURBS curve (degree 2 or 3) as RANCF elements, ``n_per_span`` per span.

    Spans are subdivided at equal parameter steps (exact, by blossoming).
    """
    if curve.degree not in (2, 3):
        raise InputError("degree", curve.degree, "a NURBS curve of degree 2 or 3")
    breaks, segs = curve.bezier_segments()
    return mesh_segments(segs, breaks, n_per_span)


def mesh_segments(
    segments: list[RationalBezier], breaks: NDArray, n_per_span: int = 1
) -> CableMesh:
    """Rational Bézier segments of degree <= 3 (curve parameter ``breaks[j]..breaks[j + 1]``)
    as RANCF elements, each segment split at ``n_per_span`` equal parameter steps (exact)."""
    n_per_span = check_element_count(n_per_span, "elements per span")
    curves, params = [], [breaks[0]]
    t = np.linspace(0.0, 1.0, n_per_span + 1)
    for j, seg in enumerate(segments):
        cub = seg
        while cub.degree < 3:
            cub = cub.elevated()
        for i in range(n_per_span):
            piece = cub.restricted(t[i], t[i + 1])
            curves.append(RationalBezier(piece.points, piece.weights / piece.weights[0]))
            params.append(breaks[j] + t[i + 1] * (breaks[j + 1] - breaks[j]))
    return mesh_from_curves(curves, None, np.array(params), "rancf")
