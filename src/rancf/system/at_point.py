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
#: Rows searched at once.
CHUNK = 64


class NearestPoint:
    """The centreline of one flexible body, searched for the point nearest to ``p``."""

    def __init__(self, model: Model) -> None:
        if not model.family.gradient:
            raise InputError("sensors.at_point", "a beam body", "cable or rod elements")
        self.model = model
        self.xi = np.linspace(0.0, 1.0, COARSE + 1)
        self._n0 = cable_shape_functions(model.mesh.weights, model.mesh.scales, self.xi)[0]

    def _basis(self, e: NDArray, xi: NDArray) -> list[NDArray]:
        """``[N, N_ξ, N_ξξ]`` ``(k, 4)`` of element ``e[i]`` at ``xi[i]`` for every row ``i``."""
        m, i = self.model, np.arange(e.size)
        return [f[i, i] for f in cable_shape_functions(m.mesh.weights[e], m.mesh.scales[e], xi)]

    def find(self, qs: NDArray, p: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """For every row of the body's full coordinates ``qs`` ``(k, n)``: the element, ``ξ``,
        the point ``r(ξ)`` ``(k, dim)`` nearest to ``p`` and its distance (module docstring);
        rows :data:`CHUNK` at a time."""
        m = self.model
        qs = np.atleast_2d(np.asarray(qs, dtype=float))
        nodes = qs.reshape(len(qs), m.n_nodes, m.dpn)[:, :, : 2 * m.dim]
        nodes = nodes.reshape(len(qs), m.n_nodes, 2, m.dim)
        en = np.concatenate([nodes[:, :-1], nodes[:, 1:]], axis=2)  # (k, n_el, 4, dim)
        parts = [self._find(en[c : c + CHUNK], p) for c in range(0, len(qs), CHUNK)]
        element, xi, point, distance = (np.concatenate(x) for x in zip(*parts, strict=True))
        return element, xi, point, distance

    def _find(self, en: NDArray, p: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        m, k = self.model, en.shape[0]
        rows = np.arange(k)
        pts = np.einsum("eqm,kemd->keqd", self._n0, en)
        flat = np.argmin(np.linalg.norm(pts - p, axis=-1).reshape(k, -1), axis=1)
        e, j = np.divmod(flat, self.xi.size)
        xi = self.xi[j].astype(float)
        for _ in range(NEWTON):
            f0, f1, f2 = self._basis(e, xi)
            nodal = en[rows, e]  # (k, 4, dim)
            r, r1, r2 = (np.einsum("km,kmd->kd", f, nodal) for f in (f0, f1, f2))
            d = np.sum((r - p) * r1, axis=1)
            dd = np.sum(r1 * r1, axis=1) + np.sum((r - p) * r2, axis=1)
            new = xi + np.where(dd > 0, -d / np.where(dd > 0, dd, 1.0), -np.sign(d) * 0.25)
            back, ahead = (new < 0.0) & (e > 0), (new > 1.0) & (e < m.n_el - 1)
            new = np.clip(new, 0.0, 1.0)
            new[back], new[ahead] = 1.0, 0.0  # on to the neighbour
            e = e - back + ahead
            moved = np.abs(new - xi).max(initial=0.0)
            xi = new
            if moved < 1e-14 and not (back.any() or ahead.any()):
                break
        f0 = self._basis(e, xi)[0]
        r = np.einsum("km,kmd->kd", f0, en[rows, e])
        return e, xi, r, np.linalg.norm(r - p, axis=1)


def nearest_point(
    finders: dict[str, NearestPoint], offsets: dict[str, slice], qs: NDArray, p: NDArray
) -> tuple[list[str], NDArray, NDArray, NDArray]:
    """For every row of the system's full coordinates ``qs`` ``(k, n)``: the body, element,
    ``ξ`` and point ``r`` nearest to ``p`` over the bodies of ``finders``."""
    found = {name: f.find(qs[:, offsets[name]], p) for name, f in finders.items()}
    names = list(found)
    dist = np.array([found[n][3] for n in names])  # (n_bodies, k)
    best = np.argmin(dist, axis=0)
    k = np.arange(qs.shape[0])
    e = np.array([found[n][0] for n in names])[best, k]
    xi = np.array([found[n][1] for n in names])[best, k]
    r = np.array([found[n][2] for n in names])[best, k]
    return [names[b] for b in best], e, xi, r


def at_point_reader(out_: Any, sen: Any) -> Any:
    """The reader of an ``at_point`` sensor (:class:`rancf.system.sensors.SensorReader`)."""
    s = out_.system
    p = np.asarray(sen.point, dtype=float)
    key = f"sensors.{sen.name}"
    if p.size != s.dim:
        raise InputError(f"{key}.at_point", list(p), f"{s.dim} numbers [m]")
    flex = {name: b for name, b in out_.flex}
    if getattr(sen, "body", None) is not None:
        if sen.body not in flex:
            raise InputError(f"{key}.body", sen.body, f"a flexible body: {', '.join(flex)}")
        flex = {sen.body: flex[sen.body]}
    if sen.kind == "twist":
        flex = {k: b for k, b in flex.items() if b.family.has_triads}
        if not flex:
            raise InputError(f"{key}.kind", "twist", 'a rod body (mesh.element = "rod")')
    finders = {k: NearestPoint(b) for k, b in flex.items()}
    offsets = {k: s.body_slice(k) for k in flex}

    def read(blk: Any) -> NDArray:
        qs = np.asarray(blk[1], dtype=float)
        bodies, e, xi, r = nearest_point(finders, offsets, qs, p)
        if sen.kind == "position":
            return r
        out = np.empty(len(qs))
        for i, name in enumerate(bodies):
            if sen.kind in ("axial_force", "tension"):  # a line's tension is its axial force
                sampler = out_.samplers[name]
                along = out_.body_along(blk[3]["s"][i : i + 1], name)[0, :, 1]
                u = xi[i] * sampler.per_element
                k = min(int(np.floor(u)), sampler.per_element - 1)
                j = e[i] * sampler.per_element + k
                out[i] = (1 - (u - k)) * along[j] + (u - k) * along[j + 1]
            else:  # twist: the nodal angles, linear in ξ
                b = flex[name]
                phi = qs[i, offsets[name]].reshape(b.n_nodes, b.dpn)[:, 6]
                out[i] = (1 - xi[i]) * phi[e[i]] + xi[i] * phi[e[i] + 1]
        return out[:, None]

    return read
