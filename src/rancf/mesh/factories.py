"""Meshes made from a geometry: a conic arc subdivided exactly into RANCF elements, a straight
line of ANCF elements, and the classical ANCF mesh at the nodes of another mesh."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError
from rancf.geometry.conic_curve import Conic
from rancf.geometry.conic_params import check_mapping_factor
from rancf.mesh.conic_chain import arc_breakpoints, cubic_forms, kopt_many, sub_arcs
from rancf.mesh.mesh import CableMesh, Spacing, check_element_count, mesh_from_arrays

__all__ = ["mesh_conic", "mesh_line", "to_ancf", "conic_breakpoints"]


def conic_breakpoints(conic: Conic, n: int, spacing: Spacing = "arc") -> NDArray[np.float64]:
    """Quadratic parameters ``u_0 = 0 < ... < u_n = 1`` of the element ends.

    ``"arc"``: equal arc length (default); ``"parameter"``: equal steps of ``u``.
    """
    n = check_element_count(n)
    if spacing == "parameter":
        return np.linspace(0.0, 1.0, n + 1)
    if spacing != "arc":
        raise InputError("spacing", spacing, 'one of "arc", "parameter"')
    return arc_breakpoints(conic, n)


def mesh_conic(
    conic: Conic, n: int, k: float | str | None = None, spacing: Spacing = "arc"
) -> CableMesh:
    """Exact subdivision of a conic arc into ``n`` RANCF conic-section elements (O(n)).

    Parameters
    ----------
    conic : Conic
    n : int
        Number of elements (>= 1).
    k : float, "opt" or None
        One mapping factor for every element, or Kopt of each sub-arc (``"opt"``/None;
        :func:`rancf.mesh.conic_chain.kopt_many`).
    spacing : {"arc", "parameter"}
    """
    n = check_element_count(n)
    u = conic_breakpoints(conic, n, spacing)
    pts, om = sub_arcs(conic, u)
    if k is None or (isinstance(k, str) and k == "opt"):
        ks = kopt_many(pts, om)
    else:
        ks = np.full(n, check_mapping_factor(k))
    cp, w = cubic_forms(pts, om, ks)
    return mesh_from_arrays(cp, w, ks, u, "rancf", total_length=conic.arc_length())


def mesh_line(start: ArrayLike, end: ArrayLike, n: int) -> CableMesh:
    """A straight segment as ``n`` equal cable elements (all weights 1: classical ANCF)."""
    n = check_element_count(n)
    a = np.asarray(start, dtype=float).ravel()
    b = np.asarray(end, dtype=float).ravel()
    if a.size not in (2, 3) or b.size != a.size:
        raise InputError("start/end", (a.tolist(), b.tolist()), "two points of dimension 2 or 3")
    length = float(np.linalg.norm(b - a))
    if not length > 0.0:
        raise InputError("end", b.tolist(), "a point different from start (length > 0)")
    t = np.linspace(0.0, 1.0, n + 1)
    f = t[:-1, None] + np.array([0.0, 1.0, 2.0, 3.0])[None, :] / (3.0 * n)
    f[:, -1] = t[1:]
    pts = a + f[..., None] * (b - a)
    return mesh_from_arrays(pts, np.ones((n, 4)), None, t, "ancf", total_length=length)


def to_ancf(mesh: CableMesh) -> CableMesh:
    """Classical ANCF cable mesh at the same nodes: unit tangents, ``l_e`` = element arc length.

    Node positions and tangent directions are exact; inside an element the Hermite cubic only
    approximates a curved geometry (the reference is then that cubic, stress-free).
    """
    lengths = mesh.arc_lengths()
    nodes = np.array(mesh.nodes)
    t = nodes[:, 1]
    nodes[:, 1] = t / np.linalg.norm(t, axis=1, keepdims=True)
    if mesh.closed:
        nodes[-1] = nodes[0]
    return CableMesh(
        nodes,
        np.ones((mesh.n_elements, 4)),
        lengths,
        "ancf",
        np.full(mesh.n_elements, np.nan),
        mesh.parameters,
        mesh.closed,
        mesh.notes,
    )
