"""The local basis of the C² spline space of a mesh (:mod:`rancf.mesh.continuity`).

Scalar problem: nodal values ``(u_k, u'_k)`` of a chain of cable elements (one coordinate; the
same for all), the linear C² condition (C2) of :mod:`rancf.mesh.continuity` at every inner node
that is not a C¹ node.  Each basis function is the solution (Hermite functions of a C¹ node:
value or slope one there) or the one-dimensional null space (inner B-splines ``N_2 … N_m`` of a
segment of ``m`` elements between C¹ nodes) of its conditions on its support: the conditions at
the nodes inside, zero value and slope at the ends of the support, and zero second derivative
from inside where the clamped knot vector gives the function a simple knot there (Piegl &
Tiller, *The NURBS Book*, sec. 2.2: a knot of multiplicity ``μ`` leaves ``C^{3-μ}``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.elements.cable import cable_shape_functions
from rancf.mesh.mesh import CableMesh

__all__ = ["G2_RTOL", "element_ends", "conditions", "scalar_basis"]

#: Curvature jump (relative) above which a node of the reference stays a C¹ node.
G2_RTOL = 1e-8


def element_ends(mesh: CableMesh) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Scalar shape functions' second derivatives at both ends ``(n_el, 4)`` each, and the
    reference first and second derivatives at both ends ``(n_el, 2, dim)`` each."""
    s = cable_shape_functions(mesh.weights, mesh.scales, np.array([0.0, 1.0]))
    e = mesh.element_nodal()
    d1 = np.einsum("eqk,ekd->eqd", s[1], e)
    d2 = np.einsum("eqk,ekd->eqd", s[2], e)
    return s[2][:, 0], s[2][:, 1], d1, d2


def conditions(mesh: CableMesh) -> tuple[NDArray, NDArray]:
    """(C2) at every inner node ``k = 1 … n_el - 1`` as coefficients over
    ``(u, u')`` of nodes ``k - 1, k, k + 1`` ``(n_el - 1, 6)``, and whether the reference is G²
    there (else the node stays a C¹ node)."""
    sdd0, sdd1, d1, d2 = element_ends(mesh)
    n_el = mesh.n_elements
    rows = np.zeros((max(n_el - 1, 0), 6))
    smooth = np.ones(max(n_el - 1, 0), dtype=bool)
    arc = mesh.arc_lengths()
    for k in range(1, n_el):
        lft, rgt = k - 1, k
        alpha = mesh.scales[rgt] / mesh.scales[lft]
        t = d1[lft, 1]
        diff = d2[rgt, 0] - alpha**2 * d2[lft, 1]
        beta = float(diff @ t / (t @ t))
        scale = np.linalg.norm(d2[rgt, 0]) + alpha**2 * np.linalg.norm(d2[lft, 1])
        scale += float(t @ t) / arc[lft]
        smooth[k - 1] = np.linalg.norm(diff - beta * t) <= G2_RTOL * scale
        c = rows[k - 1]
        c[2:6] += sdd0[rgt]
        c[0:4] -= alpha**2 * sdd1[lft]
        c[3] -= beta * mesh.scales[lft]  # r_L'(1) = l_L u'_k
    return rows, smooth


def _solve(
    lo: int,
    hi: int,
    given: dict[int, tuple[float, float]],
    cond: list[tuple[int, NDArray]],
    slope: NDArray,
) -> NDArray:
    """Nodal ``(u, u')`` of nodes ``lo … hi`` ``(hi - lo + 1, 2)``: nodes in ``given`` take their
    values, the others are unknowns in the null space (or, when a given value is not zero, the
    solution) of ``cond`` (each a first node and coefficients over ``(u, u')`` of consecutive
    nodes).  Unknowns ``(u, slope_k u')`` and rows of unit length keep the small systems well
    conditioned."""
    nn = hi - lo + 1
    free = [k for k in range(lo, hi + 1) if k not in given]
    col = {k: i for i, k in enumerate(free)}
    a = np.zeros((len(cond), 2 * len(free)))
    b = np.zeros(len(cond))
    for r, (first, c) in enumerate(cond):
        for j in range(c.size // 2):
            k = first + j
            if k in col:
                a[r, 2 * col[k]] += c[2 * j]
                a[r, 2 * col[k] + 1] += c[2 * j + 1] / slope[k]
            elif k in given:
                b[r] -= c[2 * j] * given[k][0] + c[2 * j + 1] * given[k][1]
    norm = np.linalg.norm(a, axis=1)
    norm[norm == 0.0] = 1.0
    a, b = a / norm[:, None], b / norm
    out = np.zeros((nn, 2))
    for k, v in given.items():
        out[k - lo] = v
    if not free:
        return out
    if any(v != (0.0, 0.0) for v in given.values()):  # a Hermite function: unique solution
        x = np.linalg.lstsq(a, b, rcond=None)[0]
    else:
        x = np.linalg.svd(a)[2][-1] if a.shape[0] else np.ones(a.shape[1])
    for k, i in col.items():
        out[k - lo] = x[2 * i], x[2 * i + 1] / slope[k]
    return out


def scalar_basis(
    mesh: CableMesh, c1_nodes: set[int]
) -> tuple[list[tuple[str, int, int, NDArray]], list[int]]:
    """The scalar functions in their order along the chain: ``(kind, node, lo, U)`` with kind
    ``"value"``/``"slope"`` (Hermite functions of C¹ node ``node``) or ``"inner"`` (centred on
    inner node ``node``), nodal values ``U (hi - lo + 1, 2)`` from node ``lo``; and the C¹ nodes
    in order."""
    n_el = mesh.n_elements
    rows, _ = conditions(mesh)
    sdd1 = element_ends(mesh)[1]
    sdd0 = element_ends(mesh)[0]
    c2 = {k: rows[k - 1] for k in range(1, n_el) if k not in c1_nodes}
    l_el = np.asarray(mesh.scales, dtype=float)
    slope = np.concatenate([l_el[:1], 0.5 * (l_el[:-1] + l_el[1:]), l_el[-1:]])
    ends = sorted(c1_nodes)

    def cond_at(k: int) -> list[tuple[int, NDArray]]:
        return [(k - 1, c2[k])] if k in c2 else []

    def zero_second_from_left(k: int) -> tuple[int, NDArray]:  # element k-1 at its end
        return (k - 1, sdd1[k - 1])

    def zero_second_from_right(k: int) -> tuple[int, NDArray]:  # element k at its start
        return (k, sdd0[k])

    funcs: list[tuple[str, int, int, NDArray]] = []
    for si, a in enumerate(ends):
        # Hermite functions of C¹ node a: parts on the segments left and right of it
        for kind, val in (("value", (1.0, 0.0)), ("slope", (0.0, 1.0))):
            lo = hi = a
            parts: list[tuple[int, NDArray]] = []
            if si > 0:  # the segment on the left, [p, a]: elements max(p, a - 2) ... a - 1
                lo = max(ends[si - 1], a - 2)
                cond = [c for k in range(lo + 1, a) for c in cond_at(k)]
                if a - lo == 2:
                    cond.append(zero_second_from_right(lo))
                parts.append((lo, _solve(lo, a, {a: val, lo: (0.0, 0.0)}, cond, slope)))
            if si + 1 < len(ends):  # the segment on the right, [a, b]
                hi = min(ends[si + 1], a + 2)
                cond = [c for k in range(a + 1, hi) for c in cond_at(k)]
                if hi - a == 2:
                    cond.append(zero_second_from_left(hi))
                parts.append((a, _solve(a, hi, {a: val, hi: (0.0, 0.0)}, cond, slope)))
            u = np.zeros((hi - lo + 1, 2))
            for start, part in parts:
                u[start - lo : start - lo + part.shape[0]] = part
            funcs.append((kind, a, lo, u))
        if si + 1 == len(ends):
            break
        b = ends[si + 1]
        m = b - a
        for j in range(2, m + 1):  # inner B-splines N_2 … N_m of the clamped knot vector
            s0, s1 = max(0, j - 3), min(j, m - 1)  # support: elements a + s0 … a + s1
            lo, hi = a + s0, a + s1 + 1
            cond = [c for k in range(lo + 1, hi) for c in cond_at(k)]
            if lo > a or j == 3:  # vanishes to second order at its first knot
                cond.append(zero_second_from_right(lo))
            if hi < b or j == m - 1:
                cond.append(zero_second_from_left(hi))
            u = _solve(lo, hi, {lo: (0.0, 0.0), hi: (0.0, 0.0)}, cond, slope)
            funcs.append(("inner", a + j - 1, lo, u))
    return funcs, ends
