"""Sensors at a fixed point in space (``at_point``): the material point nearest to it.

A belt's span or a line running through a guide moves through the place one wants to watch,
so a sensor fixed to the material (``at`` a node) travels away.  An ``at_point`` sensor reads,
at every output row, the material point of the flexible bodies' centrelines nearest to the fixed
point ``p`` (of one body when the sensor names ``body``):

1. the centreline of every element is sampled at :data:`COARSE` + 1 values of ``ξ`` and the
   nearest sample picked;
2. ``ξ`` is refined by Newton's method on ``d(ξ) = (r(ξ) - p) · r'(ξ) = 0`` (the foot of the
   perpendicular), ``d' = |r'|² + (r - p) · r''``, kept inside the element; at an element's end
   the search moves on to its neighbour.

The values there:

* ``position``: ``r(ξ)`` (the nearest point of the centreline);
* ``axial_force``: the section value ``N`` interpolated linearly in ``ξ`` between the sample
  stations around ``ξ`` (:class:`rancf.bodies.section_outputs.SectionSampler`);
* ``twist`` (rods): the nodal twist angles interpolated linearly in ``ξ``.

Cable and rod elements only (a beam's centreline is its chord).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.elements.cable import cable_shape_functions
from rancf.errors import InputError

__all__ = ["NearestPoint", "nearest_point", "COARSE"]

#: Samples per element of the coarse search.
COARSE = 16
#: Newton iterations of the refinement (converged to round-off well before).
NEWTON = 12


class NearestPoint:
    """The centreline of one flexible body, searched for the point nearest to ``p``."""

    def __init__(self, model: Model) -> None:
        if model.element == "beam":
            raise InputError("sensors.at_point", "a beam body", "cable or rod elements")
        self.model = model
        self.xi = np.linspace(0.0, 1.0, COARSE + 1)

    def _element(self, q: NDArray) -> NDArray[np.float64]:
        m = self.model
        nodes = q.reshape(m.n_nodes, m.dpn)[:, : 2 * m.dim]
        return m.mesh.element_nodal(nodes)  # (n_el, 4, dim)

    def find(self, q: NDArray, p: NDArray) -> tuple[int, float, NDArray, float]:
        """``(element, ξ, r(ξ), distance)`` of the point nearest to ``p`` in the body's full
        coordinates ``q`` (module docstring)."""
        m = self.model
        e_nodal = self._element(q)
        n0 = cable_shape_functions(m.mesh.weights, m.mesh.scales, self.xi)[0]
        pts = np.einsum("eqk,ekd->eqd", n0, e_nodal)
        dist = np.linalg.norm(pts - p, axis=-1)
        e, k = np.unravel_index(int(np.argmin(dist)), dist.shape)
        e, xi = int(e), float(self.xi[k])
        for _ in range(NEWTON):
            w, sc = m.mesh.weights[e : e + 1], m.mesh.scales[e : e + 1]
            f0, f1, f2 = (f[0, 0] for f in cable_shape_functions(w, sc, np.array([xi])))
            r, r1, r2 = f0 @ e_nodal[e], f1 @ e_nodal[e], f2 @ e_nodal[e]
            d = (r - p) @ r1
            dd = r1 @ r1 + (r - p) @ r2
            step = -d / dd if dd > 0 else -np.sign(d) * 0.25
            new = xi + step
            if new < 0.0 and e > 0:  # on to the neighbour
                e, xi = e - 1, 1.0
                continue
            if new > 1.0 and e < m.n_el - 1:
                e, xi = e + 1, 0.0
                continue
            new = min(max(new, 0.0), 1.0)
            if abs(new - xi) < 1e-14:
                xi = new
                break
            xi = new
        w, sc = m.mesh.weights[e : e + 1], m.mesh.scales[e : e + 1]
        r = cable_shape_functions(w, sc, np.array([xi]))[0][0, 0] @ e_nodal[e]
        return e, xi, r, float(np.linalg.norm(r - p))


def nearest_point(
    finders: dict[str, NearestPoint], offsets: dict[str, slice], q: NDArray, p: NDArray
) -> tuple[str, int, float, NDArray]:
    """``(body, element, ξ, r)`` nearest to ``p`` over the bodies of ``finders`` in the
    system's full coordinates ``q`` (a row)."""
    best: tuple[float, str, int, float, NDArray] | None = None
    for name, f in finders.items():
        e, xi, r, d = f.find(q[offsets[name]], p)
        if best is None or d < best[0]:
            best = (d, name, e, xi, r)
    assert best is not None
    return best[1], best[2], best[3], best[4]


def at_point_reader(out: Any, sen: Any) -> Any:
    """The reader of an ``at_point`` sensor (:class:`rancf.system.sensors.SensorReader`)."""
    s = out.system
    p = np.asarray(sen.point, dtype=float)
    key = f"sensors.{sen.name}"
    if p.size != s.dim:
        raise InputError(f"{key}.at_point", list(p), f"{s.dim} numbers [m]")
    flex = {name: b for name, b in out.flex}
    if getattr(sen, "body", None) is not None:
        if sen.body not in flex:
            raise InputError(f"{key}.body", sen.body, f"a flexible body: {', '.join(flex)}")
        flex = {sen.body: flex[sen.body]}
    if sen.kind == "twist":
        flex = {k: b for k, b in flex.items() if b.element == "rod"}
        if not flex:
            raise InputError(f"{key}.kind", "twist", 'a rod body (mesh.element = "rod")')
    finders = {k: NearestPoint(b) for k, b in flex.items()}
    offsets = {k: s.body_slice(k) for k in flex}

    def read(blk: Any) -> NDArray:
        rows = []
        for i, q in enumerate(blk[1]):
            name, e, xi, r = nearest_point(finders, offsets, q, p)
            if sen.kind == "position":
                rows.append(r)
            elif sen.kind == "axial_force":
                sampler = out.samplers[name]
                along = out.body_along(blk[3]["s"][i : i + 1], name)[0, :, 1]
                u = xi * sampler.per_element
                k = min(int(np.floor(u)), sampler.per_element - 1)
                j = e * sampler.per_element + k
                rows.append([(1 - (u - k)) * along[j] + (u - k) * along[j + 1]])
            else:  # twist: the nodal angles, linear in ξ
                b = flex[name]
                phi = q[offsets[name]].reshape(b.n_nodes, b.dpn)[:, 6]
                rows.append([(1 - xi) * phi[e] + xi * phi[e + 1]])
        return np.array(rows, dtype=float).reshape(len(blk[0]), -1)

    return read
