"""Cable meshes: chains of (R)ANCF elements with shared nodal vectors.

A :class:`CableMesh` is a chain: element ``e`` joins nodes ``e`` and ``e + 1``; each node carries
one nodal vector ``[r, r_x]``.  Global coordinates are ordered node by node,
``q = [r_0, r_x0, r_1, r_x1, ...]`` (``2 dim`` per node), so element ``e`` owns the contiguous
slice ``q[2 dim e : 2 dim e + 4 dim]`` and assembled matrices are banded.

Shared nodes (math note sec. 6): adjacent rational elements have parallel end derivatives but
different magnitudes; choosing each element's gradient scale by the walk
``l_e = g0_e / m_e``, ``m_{e+1} = g1_e / l_e`` (``g0``, ``g1`` the end-derivative magnitudes) makes
every shared nodal vector consistent, so the assembled reference curve is exactly the geometry.
The scales are finally multiplied by a common factor so that ``Σ l_e`` equals the arc length.

The magnitudes ``m_e`` grow by ``g1_e / g0_e`` per element: with Kopt they stay uniform, with one
fixed K far from Kopt they grow geometrically (e.g. a factor 2.6e10 over 16 elements with K = 0.1
on the paper's example 2), which ruins the conditioning; a warning is logged above 1e6.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import cable_shape_functions, nodal_from_bezier
from rancf.elements.mapping import gradient_ratio, kopt
from rancf.errors import ElementCountError, InputError
from rancf.geometry.bezier import RationalBezier
from rancf.geometry.conic import Conic, check_mapping_factor
from rancf.geometry.nurbs import NurbsCurve
from rancf.geometry.quadrature import integrate

__all__ = [
    "CableMesh",
    "check_element_count",
    "mesh_from_curves",
    "mesh_conic",
    "mesh_line",
    "mesh_nurbs",
    "to_ancf",
    "conic_breakpoints",
]

Spacing = Literal["arc", "parameter"]

logger = logging.getLogger(__name__)

#: Above this ratio of largest to smallest nodal gradient a mesh is reported as ill-conditioned.
GRADIENT_SPAN_WARNING = 1e6


def check_element_count(n: object, name: str = "elements") -> int:
    """Validate a number of elements (an integer >= 1)."""
    try:
        ok = int(n) == n and int(n) >= 1  # type: ignore[call-overload]
    except (TypeError, ValueError):
        ok = False
    if not ok or isinstance(n, bool):
        raise ElementCountError(name, n, "an integer number of elements >= 1")
    return int(n)  # type: ignore[call-overload]


@dataclass(frozen=True)
class CableMesh:
    """A chain of cable elements with shared nodes.

    Attributes
    ----------
    nodes : ndarray, shape (n_el + 1, 2, dim)
        Reference nodal vectors ``[r, r_x]``.
    weights : ndarray, shape (n_el, 4)
        Rational weights (all ones for ANCF).
    scales : ndarray, shape (n_el,)
        Gradient scales ``l_e``.
    kind : {"rancf", "ancf"}
    k : ndarray, shape (n_el,)
        Mapping factor per element (NaN where not a conic element).
    parameters : ndarray, shape (n_el + 1,)
        Parameter of the source geometry at each node.
    """

    nodes: NDArray[np.float64]
    weights: NDArray[np.float64]
    scales: NDArray[np.float64]
    kind: Literal["rancf", "ancf"] = "rancf"
    k: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    parameters: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))

    def __post_init__(self) -> None:
        n_el = self.weights.shape[0]
        if self.nodes.shape[0] != n_el + 1 or self.scales.shape != (n_el,):
            raise InputError("mesh", (self.nodes.shape, self.weights.shape), "n_el + 1 nodes")
        if self.k.size == 0:
            object.__setattr__(self, "k", np.full(n_el, np.nan))
        if self.parameters.size == 0:
            object.__setattr__(self, "parameters", np.linspace(0.0, 1.0, n_el + 1))
        for name in ("nodes", "weights", "scales", "k", "parameters"):
            arr = np.array(getattr(self, name), dtype=float)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    @property
    def n_elements(self) -> int:
        """Number of elements."""
        return self.weights.shape[0]

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return self.nodes.shape[0]

    @property
    def dim(self) -> int:
        """Space dimension (2 or 3)."""
        return self.nodes.shape[2]

    @property
    def n_dofs(self) -> int:
        """Number of nodal coordinates ``2 dim n_nodes``."""
        return self.nodes.size

    @property
    def q0(self) -> NDArray[np.float64]:
        """Reference configuration as a flat vector ``(n_dofs,)``."""
        return self.nodes.reshape(-1).copy()

    def element_nodal(self, q: ArrayLike | None = None) -> NDArray[np.float64]:
        """Element nodal coordinates ``(n_el, 4, dim)`` of ``q`` (default: the reference)."""
        nodes = self.nodes if q is None else np.asarray(q, dtype=float).reshape(self.nodes.shape)
        return np.concatenate([nodes[:-1], nodes[1:]], axis=1)

    def element_curves(self, q: ArrayLike | None = None) -> list[RationalBezier]:
        """Rational cubic Bézier form of each element in configuration ``q``."""
        from rancf.elements.cable import bezier_from_nodal

        e = self.element_nodal(q)
        return [
            bezier_from_nodal(e[j], self.weights[j], self.scales[j]) for j in range(self.n_elements)
        ]

    def gradient_ratios(self) -> NDArray[np.float64]:
        """Gradient ratio of each element's reference curve."""
        return np.array([gradient_ratio(c) for c in self.element_curves()])

    def evaluate(self, xi: ArrayLike, q: ArrayLike | None = None, order: int = 0) -> NDArray:
        """Points (or ξ-derivatives) at ``xi`` in every element, ``(n_el, n_xi, dim)``."""
        n = cable_shape_functions(self.weights, self.scales, xi)[order]
        return np.einsum("eqk,ekd->eqd", n, self.element_nodal(q))

    def arc_lengths(self) -> NDArray[np.float64]:
        """Reference arc length of each element (adaptive quadrature)."""
        out = np.empty(self.n_elements)
        for j in range(self.n_elements):
            w, s = self.weights[j : j + 1], self.scales[j : j + 1]
            nod = self.element_nodal()[j]

            def speed(x: NDArray, w=w, s=s, nod=nod) -> NDArray:
                return np.linalg.norm(cable_shape_functions(w, s, x)[1][0] @ nod, axis=1)

            out[j] = integrate(speed, 0.0, 1.0, rtol=1e-13)
        return out


def _end_derivatives(curve: RationalBezier) -> tuple[NDArray, NDArray]:
    w, q = curve.weights, curve.points
    return 3.0 * w[1] / w[0] * (q[1] - q[0]), 3.0 * w[2] / w[3] * (q[3] - q[2])


def mesh_from_curves(
    curves: list[RationalBezier],
    k: ArrayLike | None = None,
    parameters: ArrayLike | None = None,
    kind: Literal["rancf", "ancf"] = "rancf",
    total_length: float | None = None,
) -> CableMesh:
    """Chain of rational cubic curves → mesh with consistent shared nodes (math note sec. 6).

    Raises
    ------
    InputError
        If adjacent curves do not meet, or their tangents at the joint are not parallel
        (a kink cannot be represented by one shared nodal gradient).
    """
    if not curves:
        raise ElementCountError("elements", 0, "at least one element")
    n_el = len(curves)
    ends = [_end_derivatives(c) for c in curves]
    g0 = np.array([np.linalg.norm(d0) for d0, _ in ends])
    g1 = np.array([np.linalg.norm(d1) for _, d1 in ends])
    size = max(float(np.abs(np.concatenate([c.points for c in curves])).max()), 1e-300)
    for j in range(n_el - 1):
        gap = np.linalg.norm(curves[j].points[-1] - curves[j + 1].points[0])
        t_a = ends[j][1] / g1[j]
        t_b = ends[j + 1][0] / g0[j + 1]
        if gap > 1e-10 * size or np.linalg.norm(t_a - t_b) > 1e-8:
            raise InputError(
                "geometry",
                f"joint {j + 1}: gap {gap:.3g}, tangent jump {np.linalg.norm(t_a - t_b):.3g}",
                "a tangent-continuous chain of curves (shared end points, parallel end tangents)",
            )
    scales = np.empty(n_el)
    m = 1.0
    for j in range(n_el):
        scales[j] = g0[j] / m
        m = g1[j] / scales[j]
    if total_length is None:
        total_length = 0.0
        for c in curves:
            total_length += integrate(
                lambda x, c=c: np.linalg.norm(c.derivatives(x, 1)[1], axis=1), 0.0, 1.0, rtol=1e-13
            )
    scales *= total_length / scales.sum()
    nodes = np.empty((n_el + 1, 2, curves[0].dim))
    for j, c in enumerate(curves):
        e = nodal_from_bezier(c, float(scales[j]))
        nodes[j] = e[:2]
        if j == n_el - 1:
            nodes[j + 1] = e[2:]
    weights = np.array([c.weights for c in curves])
    span = float(
        np.max(np.linalg.norm(nodes[:, 1], axis=1)) / np.min(np.linalg.norm(nodes[:, 1], axis=1))
    )
    if span > GRADIENT_SPAN_WARNING:
        logger.warning(
            "nodal gradient magnitudes span a factor %.3g over %d elements: with one fixed K far "
            "from Kopt the consistent shared nodes grow geometrically along the chain and the "
            "model is badly conditioned; use k='opt' or fewer elements",
            span,
            n_el,
        )
    kk = np.full(n_el, np.nan) if k is None else np.asarray(k, dtype=float)
    par = np.linspace(0.0, 1.0, n_el + 1) if parameters is None else np.asarray(parameters, float)
    return CableMesh(nodes, weights, scales, kind, kk, par)


def conic_breakpoints(conic: Conic, n: int, spacing: Spacing = "arc") -> NDArray[np.float64]:
    """Quadratic parameters ``u_0 = 0 < ... < u_n = 1`` of the element ends.

    ``"arc"``: equal arc length (default); ``"parameter"``: equal steps of ``u``.
    """
    n = check_element_count(n)
    if spacing == "parameter":
        return np.linspace(0.0, 1.0, n + 1)
    if spacing != "arc":
        raise InputError("spacing", spacing, 'one of "arc", "parameter"')
    total = conic.arc_length()
    u = conic.parameters_at_arc_lengths(total * np.arange(1, n) / n)
    return np.concatenate([[0.0], u, [1.0]])


def mesh_conic(
    conic: Conic, n: int, k: float | str | None = None, spacing: Spacing = "arc"
) -> CableMesh:
    """Exact subdivision of a conic arc into ``n`` RANCF conic-section elements.

    Parameters
    ----------
    conic : Conic
    n : int
        Number of elements (>= 1).
    k : float, "opt" or None
        One mapping factor for every element, or Kopt of each sub-arc (``"opt"``/None).
    spacing : {"arc", "parameter"}
    """
    n = check_element_count(n)
    u = conic_breakpoints(conic, n, spacing)
    subs = [conic.sub_arc(u[j], u[j + 1]) for j in range(n)]
    if k is None or (isinstance(k, str) and k == "opt"):
        ks = np.array([kopt(s) for s in subs])
    else:
        ks = np.full(n, check_mapping_factor(k))  # type: ignore[arg-type]
    curves = [s.cubic(kk) for s, kk in zip(subs, ks, strict=True)]
    return mesh_from_curves(curves, ks, u, "rancf", total_length=conic.arc_length())


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
    pts = a + t[:, None] * (b - a)
    curves = [
        RationalBezier(
            np.array([pts[j] + f * (pts[j + 1] - pts[j]) for f in (0, 1 / 3, 2 / 3, 1)]), np.ones(4)
        )
        for j in range(n)
    ]
    return mesh_from_curves(curves, None, t, "ancf", total_length=length)


def mesh_nurbs(curve: NurbsCurve, n_per_span: int = 1) -> CableMesh:
    """A tangent-continuous NURBS curve (degree 2 or 3) as RANCF elements, ``n_per_span`` per span.

    Spans are subdivided at equal parameter steps (exact, by blossoming).
    """
    n_per_span = check_element_count(n_per_span, "elements per span")
    if curve.degree not in (2, 3):
        raise InputError("degree", curve.degree, "a NURBS curve of degree 2 or 3")
    breaks, segs = curve.bezier_segments()
    curves, params = [], [breaks[0]]
    for j, seg in enumerate(segs):
        cub = seg
        while cub.degree < 3:
            cub = cub.elevated()
        t = np.linspace(0.0, 1.0, n_per_span + 1)
        for i in range(n_per_span):
            piece = cub.restricted(t[i], t[i + 1])
            curves.append(RationalBezier(piece.points, piece.weights / piece.weights[0]))
            params.append(breaks[j] + t[i + 1] * (breaks[j + 1] - breaks[j]))
    return mesh_from_curves(curves, None, np.array(params), "rancf")


def to_ancf(mesh: CableMesh) -> CableMesh:
    """Classical ANCF cable mesh at the same nodes: unit tangents, ``l_e`` = element arc length.

    Node positions and tangent directions are exact; inside an element the Hermite cubic only
    approximates a curved geometry (the reference is then that cubic, stress-free).
    """
    lengths = mesh.arc_lengths()
    nodes = np.array(mesh.nodes)
    t = nodes[:, 1]
    nodes[:, 1] = t / np.linalg.norm(t, axis=1, keepdims=True)
    return CableMesh(
        nodes,
        np.ones((mesh.n_elements, 4)),
        lengths,
        "ancf",
        np.full(mesh.n_elements, np.nan),
        mesh.parameters,
    )
