"""A full ellipse as a closed mesh of exact RANCF conic-section elements.

The nodes lie at the parameters ``t_j`` of :class:`~rancf.geometry.ellipse.Ellipse`, from
``t_0 = start`` once around (equal arc length, or equal parameter steps); each element is the
exact conic sub-arc ``[t_j, t_{j+1}]`` (:meth:`Ellipse.sub_arcs`) in cubic form with its own
Kopt (or one given K), joined with consistent shared nodes
(:func:`rancf.mesh.mesh.mesh_from_arrays`), which sees the ends meet with the same tangent and
makes the mesh closed.
"""

from __future__ import annotations

import numpy as np

from rancf.errors import InputError
from rancf.geometry.conic_params import check_mapping_factor
from rancf.geometry.ellipse import Ellipse
from rancf.mesh.conic_chain import cubic_forms, kopt_many
from rancf.mesh.mesh import CableMesh, Spacing, check_element_count, mesh_from_arrays

__all__ = ["mesh_ellipse", "ellipse_breakpoints"]


def ellipse_breakpoints(
    ellipse: Ellipse, n: int, spacing: Spacing = "arc", start_deg: float = 0.0
) -> np.ndarray:
    """Parameters ``t_0 < ... < t_n = t_0 + 2π`` of the nodes (``t_0 = start_deg`` in radians).

    ``"arc"``: equal arc length (Newton on the elliptic integral); ``"parameter"``: equal ``t``.
    """
    n = check_element_count(n)
    if n < 3:
        raise InputError(
            "elements",
            n,
            "at least 3 elements for a closed ellipse (each element "
            "is a conic arc of less than half a turn)",
        )
    t0 = np.radians(float(start_deg))
    if spacing == "parameter":
        t = t0 + np.linspace(0.0, 2.0 * np.pi, n + 1)
    elif spacing == "arc":
        s = ellipse.perimeter() * np.arange(1, n) / n
        t = np.concatenate([[t0], ellipse.parameters_at_arc_lengths(t0, s), [t0 + 2.0 * np.pi]])
    else:
        raise InputError("spacing", spacing, 'one of "arc", "parameter"')
    return t


def mesh_ellipse(
    ellipse: Ellipse,
    n: int,
    k: float | str | None = None,
    spacing: Spacing = "arc",
    start_deg: float = 0.0,
) -> CableMesh:
    """The closed mesh of ``n`` (>= 3) conic-section elements of a full ellipse.

    Parameters
    ----------
    ellipse : Ellipse
    n : int
    k : float, "opt" or None
        One mapping factor for every element, or Kopt of each sub-arc (``"opt"``/None).
    spacing : {"arc", "parameter"}
    start_deg : float
        Parameter of the first node (the seam) [deg].

    Returns
    -------
    CableMesh
        ``closed`` is True; ``parameters`` are the nodes' ``t`` [rad].
    """
    t = ellipse_breakpoints(ellipse, n, spacing, start_deg)
    pts, om = ellipse.sub_arcs(t)
    if k is None or (isinstance(k, str) and k == "opt"):
        ks = kopt_many(pts, om)
    else:
        ks = np.full(t.size - 1, check_mapping_factor(k))
    pts[-1, 2] = pts[0, 0]  # the same point to the last bit
    cp, w = cubic_forms(pts, om, ks)
    mesh = mesh_from_arrays(cp, w, ks, t, "rancf", total_length=ellipse.perimeter())
    if not mesh.closed:  # pragma: no cover - the sub-arcs meet with equal tangents
        raise InputError("geometry", "an ellipse", "a closed mesh")
    return mesh
