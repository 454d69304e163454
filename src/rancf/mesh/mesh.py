"""Cable meshes: chains of (R)ANCF elements with shared nodal vectors.

A :class:`CableMesh` is a chain: element ``e`` joins nodes ``e`` and ``e + 1``; each node carries
one nodal vector ``[r, r_x]``.  Global coordinates are ordered node by node,
``q = [r_0, r_x0, r_1, r_x1, ...]`` (``2 dim`` per node), so element ``e`` owns the contiguous
slice ``q[2 dim e : 2 dim e + 4 dim]`` and assembled matrices are banded.

Shared nodes (docs/derivations/cable.md sec. 6): adjacent rational elements have parallel end
derivatives but
different magnitudes; choosing each element's gradient scale by the walk
``l_e = g0_e / m_e``, ``m_{e+1} = g1_e / l_e`` (``g0``, ``g1`` the end-derivative magnitudes) makes
every shared nodal vector consistent, so the assembled reference curve is exactly the geometry.
The scales are finally multiplied by a common factor so that ``Σ l_e`` equals the arc length.

The magnitudes ``m_e`` grow by ``g1_e / g0_e`` per element: with Kopt they stay uniform, with one
fixed K far from Kopt they grow geometrically (e.g. a factor 2.6e10 over 16 elements with K = 0.1
on the paper's example 2), which ruins the conditioning; a warning is logged above 1e6.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import cable_shape_functions
from rancf.elements.mapping import gradient_ratio
from rancf.errors import ElementCountError, InputError
from rancf.geometry.bezier import RationalBezier
from rancf.geometry.quadrature import integrate_many
from rancf.geometry.tangents import GAP_RTOL, KINK_TOL, is_closed, touching_ends_note
from rancf.mesh.conic_chain import refined_extreme

__all__ = [
    "CableMesh",
    "check_element_count",
    "mesh_from_curves",
    "mesh_from_arrays",
]

Spacing = Literal["arc", "parameter"]


#: Above this ratio of largest to smallest nodal gradient a mesh is reported as ill-conditioned.
GRADIENT_SPAN_WARNING = 1e6


def check_element_count(n: object, name: str = "elements") -> int:
    """Validate a number of elements (an integer >= 1)."""
    if isinstance(n, numbers.Real) and not isinstance(n, bool):
        f = float(n)
        if f.is_integer() and f >= 1:  # not NaN or inf
            return int(f)
    raise ElementCountError(name, n, "an integer number of elements >= 1")


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
    closed : bool
        A closed curve (a ring): the last node is the first one.  It is stored twice (node
        ``n_el`` repeats node 0's position, and its gradient is node 0's times
        :attr:`seam_ratio`), so the chain stays a band; a model ties the two by linear
        constraint rows (:mod:`rancf.bodies.closure`).
    notes : tuple of str
        Remarks on the geometry for the user (e.g. ends that touch at a kink: an open curve).
    """

    nodes: NDArray[np.float64]
    weights: NDArray[np.float64]
    scales: NDArray[np.float64]
    kind: Literal["rancf", "ancf"] = "rancf"
    k: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    parameters: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    closed: bool = False
    notes: tuple[str, ...] = ()

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
        """Number of stored nodes (a closed mesh stores its first node again at the end)."""
        return self.nodes.shape[0]

    @property
    def n_distinct_nodes(self) -> int:
        """Number of distinct nodes: ``n_nodes``, or ``n_el`` for a closed mesh."""
        return self.nodes.shape[0] - int(self.closed)

    @property
    def seam_ratio(self) -> float:
        """Closed meshes: ``|r_x|`` of the last stored node over that of the first (the gradient
        scales of a consistent chain need not return to their start value); 1 if open."""
        if not self.closed:
            return 1.0
        return float(np.linalg.norm(self.nodes[-1, 1]) / np.linalg.norm(self.nodes[0, 1]))

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

    def gradient_ratios(self, exact: bool = True) -> NDArray[np.float64]:
        """Gradient ratio ``max |r_ξ| / min |r_ξ|`` of each element's reference curve (eq. 29).

        ``exact``: every extremum located by root finding
        (:func:`rancf.elements.mapping.gradient_ratio`, about 1 ms an element); otherwise all
        elements at once from 33 samples each, the extremes of ``log |r_ξ|`` refined by
        parabolas as in :func:`rancf.mesh.conic_chain.kopt_many`: a million elements in
        seconds, relative error below 1e-10 for the short elements of a fine mesh (measured
        against the exact ratios at 1001 elements of four conics) but up to ~1e-6 for one
        element spanning a whole arc.
        """
        if exact:
            return np.array([gradient_ratio(c) for c in self.element_curves()])
        pts, w, out = self.control_points(), self.weights, np.empty(self.n_elements)
        xi = np.linspace(0.0, 1.0, 33)
        for i in range(0, self.n_elements, 16384):
            part = slice(i, i + 16384)
            m = w[part].shape[0]
            log_s = np.log(cubic_speed(pts[part], w[part], np.broadcast_to(xi, (m, xi.size))))
            out[part] = np.exp(refined_extreme(log_s, 1.0) - refined_extreme(log_s, -1.0))
        return out

    def evaluate(self, xi: ArrayLike, q: ArrayLike | None = None, order: int = 0) -> NDArray:
        """Points (or ξ-derivatives) at ``xi`` in every element, ``(n_el, n_xi, dim)``."""
        n = cable_shape_functions(self.weights, self.scales, xi)[order]
        return np.einsum("eqk,ekd->eqd", n, self.element_nodal(q))

    def control_points(self) -> NDArray[np.float64]:
        """Rational Bézier control points of every element ``(n_el, 4, dim)`` (reference)."""
        e = self.element_nodal()
        w, sc = self.weights, self.scales
        a = (sc * w[:, 0] / (3.0 * w[:, 1]))[:, None]
        b = (sc * w[:, 3] / (3.0 * w[:, 2]))[:, None]
        return np.stack([e[:, 0], e[:, 0] + a * e[:, 1], e[:, 2] - b * e[:, 3], e[:, 2]], axis=1)

    def arc_lengths(self) -> NDArray[np.float64]:
        """Reference arc length of each element (adaptive quadrature, all elements at once)."""
        return _arc_lengths(self.control_points(), self.weights)


def cubic_speed(points: NDArray, weights: NDArray, xi: NDArray) -> NDArray[np.float64]:
    """``|r_ξ|`` of rational cubics ``(points (n, 4, dim), weights (n, 4))`` at ``xi (n, m)``.

    Points are taken relative to each curve's start, so short curves far from the origin keep
    full relative precision.
    """
    points = points - points[:, :1]
    b = np.stack([(1 - xi) ** 3, 3 * xi * (1 - xi) ** 2, 3 * xi**2 * (1 - xi), xi**3], axis=-1)
    db = np.stack(
        [-3 * (1 - xi) ** 2, 3 * (1 - xi) * (1 - 3 * xi), 3 * xi * (2 - 3 * xi), 3 * xi**2], axis=-1
    )
    hw = weights[:, None, :]
    d = np.sum(b * hw, axis=-1)
    dd = np.sum(db * hw, axis=-1)
    a = np.einsum("nmk,nkd->nmd", b * hw, points)
    da = np.einsum("nmk,nkd->nmd", db * hw, points)
    return np.linalg.norm(da * d[..., None] - a * dd[..., None], axis=-1) / d**2


def _arc_lengths(points: NDArray, weights: NDArray) -> NDArray[np.float64]:
    n = points.shape[0]
    return integrate_many(
        lambda i, x: cubic_speed(points[i], weights[i], x), np.zeros(n), np.ones(n), rtol=1e-13
    )


def mesh_from_curves(
    curves: list[RationalBezier],
    k: ArrayLike | None = None,
    parameters: ArrayLike | None = None,
    kind: Literal["rancf", "ancf"] = "rancf",
    total_length: float | None = None,
) -> CableMesh:
    """Chain of rational cubic curves → mesh with consistent shared nodes
    (docs/derivations/cable.md sec. 6).

    See :func:`mesh_from_arrays` (this takes a list of :class:`RationalBezier` cubics).
    """
    if not curves:
        raise ElementCountError("elements", 0, "at least one element")
    for c in curves:
        if c.degree != 3:
            raise InputError("curve.degree", c.degree, "cubic (degree 3) rational Bézier curves")
    points = np.array([c.points for c in curves])
    weights = np.array([c.weights for c in curves])
    return mesh_from_arrays(points, weights, k, parameters, kind, total_length)


def mesh_from_arrays(
    points: NDArray,
    weights: NDArray,
    k: ArrayLike | None = None,
    parameters: ArrayLike | None = None,
    kind: Literal["rancf", "ancf"] = "rancf",
    total_length: float | None = None,
) -> CableMesh:
    """Chain of rational cubics ``(points (n_el, 4, dim), weights (n_el, 4))`` → mesh.

    Vectorized over the elements (O(n_el)).  The gradient-scale walk
    ``l_e = g0_e / m_e``, ``m_{e+1} = g1_e / l_e`` is a cumulative product.

    Raises
    ------
    InputError
        If adjacent curves do not meet, their tangents at a joint are not parallel (a kink
        cannot be represented by one shared nodal gradient), or a curve is degenerate (a
        vanishing derivative somewhere, e.g. from coincident control points).
    """
    points = np.asarray(points, dtype=float)
    weights = np.asarray(weights, dtype=float)
    n_el = points.shape[0]
    if n_el == 0:
        raise ElementCountError("elements", 0, "at least one element")
    size = max(
        float(np.abs(points).max()),
        float(np.ptp(points.reshape(-1, points.shape[-1]), axis=0).max()),
        1e-300,
    )
    xi = np.broadcast_to(np.linspace(0.0, 1.0, 9), (n_el, 9))
    speed = cubic_speed(points, weights, xi)
    chord = np.linalg.norm(points[:, 3] - points[:, 0], axis=1)
    bad = ~np.all(np.isfinite(speed), axis=1) | (
        speed.min(axis=1) <= 1e-9 * np.maximum(chord, 1e-12 * size)
    )
    if np.any(bad):
        j = int(np.argmax(bad))
        raise InputError(
            "geometry",
            f"element {j}: |dr/dxi| = {float(np.nanmin(speed[j])):.3g} somewhere",
            "a regular curve (no vanishing derivative: distinct, non-coincident control points)",
        )
    d0 = 3.0 * (weights[:, 1] / weights[:, 0])[:, None] * (points[:, 1] - points[:, 0])
    d1 = 3.0 * (weights[:, 2] / weights[:, 3])[:, None] * (points[:, 3] - points[:, 2])
    g0, g1 = np.linalg.norm(d0, axis=1), np.linalg.norm(d1, axis=1)
    gap = np.linalg.norm(points[:-1, 3] - points[1:, 0], axis=1)
    jump = np.linalg.norm(d1[:-1] / g1[:-1, None] - d0[1:] / g0[1:, None], axis=1)
    bad = (gap > GAP_RTOL * size) | (jump > KINK_TOL)  # |u1 - u0| = 2 sin(angle / 2)
    if np.any(bad):
        j = int(np.argmax(bad))
        raise InputError(
            "geometry",
            f"joint {j + 1}: gap {gap[j]:.3g}, tangent jump {jump[j]:.3g}",
            "a tangent-continuous chain of curves (shared end points, parallel end tangents)",
        )
    closed = is_closed(points[0, 0], d0[0], points[-1, 3], d1[-1], size)
    notes = () if closed else touching_ends_note(points[0, 0], d0[0], points[-1, 3], d1[-1], size)
    log_m = np.concatenate([[0.0], np.cumsum(np.log(g1[:-1]) - np.log(g0[:-1]))])
    scales = g0 * np.exp(-log_m)
    if total_length is None:
        total_length = float(_arc_lengths(points, weights).sum())
    scales *= total_length / scales.sum()
    a = 3.0 * weights[:, 1] / (weights[:, 0] * scales)
    b = 3.0 * weights[:, 2] / (weights[:, 3] * scales)
    nodes = np.empty((n_el + 1, 2, points.shape[2]))
    nodes[:-1, 0] = points[:, 0]
    nodes[:-1, 1] = a[:, None] * (points[:, 1] - points[:, 0])
    nodes[-1, 0] = points[-1, 3]
    nodes[-1, 1] = b[-1] * (points[-1, 3] - points[-1, 2])
    if closed:  # the last node is the first: exactly its position, its gradient direction
        ratio = np.linalg.norm(nodes[-1, 1]) / np.linalg.norm(nodes[0, 1])
        nodes[-1, 0], nodes[-1, 1] = nodes[0, 0], ratio * nodes[0, 1]
    mags = np.linalg.norm(nodes[:, 1], axis=1)
    span = float(mags.max() / mags.min())
    kk = np.full(n_el, np.nan) if k is None else np.asarray(k, dtype=float)
    if span > GRADIENT_SPAN_WARNING:
        fixed = bool(np.all(np.isfinite(kk))) and np.ptp(kk) == 0.0
        import logging  # only for this warning (logging is a start-up cost of every run)

        logging.getLogger(__name__).warning(
            "nodal gradient magnitudes span a factor %.3g over %d elements: the consistent "
            "shared nodes grow along the chain and the model is badly conditioned; %s",
            span,
            n_el,
            "use k='opt' or fewer elements" if fixed else "use fewer elements",
        )
    par = np.linspace(0.0, 1.0, n_el + 1) if parameters is None else np.asarray(parameters, float)
    return CableMesh(nodes, weights, scales, kind, kk, par, closed, notes)
