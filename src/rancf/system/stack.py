"""The bodies of a system and their stacked coordinates ``y``: the flexible bodies (their model
coordinates, held supports included), then the rigid bodies and point masses
(:mod:`rancf.bodies.rigid`); places resolved against the bodies, and a place's record for the
compiled core (:class:`rancf.kernels.records.PlaceRecord`)."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.errors import InputError
from rancf.kernels.records import PlaceRecord, vec3
from rancf.system.places import Place

__all__ = ["BodyStack", "Body"]

Body = Model | RigidBody | PointMass


class BodyStack:
    """Named bodies and their coordinates stacked in ``y`` (module docstring).

    Attributes
    ----------
    dim : int
        2 or 3, every body's.
    bodies : dict name -> Model | RigidBody | PointMass
        Flexible bodies first.
    names, flex, rigid : lists
        The names in stacking order; the flexible bodies; the rigid bodies and point masses.
    offsets : dict name -> int
        A body's first coordinate in ``y``.
    n : int
        Coordinates.
    y0, v0 : ``(n,)``
        The reference (installed) coordinates and the initial velocities.
    single : str or None
        The name of the only body (then places need no body name), or None.
    """

    def __init__(self, bodies: Mapping[str, Body]) -> None:
        if not bodies:
            raise InputError("bodies", {}, "at least one body")
        for name in bodies:
            if not isinstance(name, str) or not name or name == "ground" or ":" in name:
                raise InputError("bodies.name", name, 'a name without ":", not "ground"')
        flex = [(k, b) for k, b in bodies.items() if isinstance(b, Model)]
        rigid = [(k, b) for k, b in bodies.items() if isinstance(b, RigidBody | PointMass)]
        both: list[tuple[str, Body]] = [*flex, *rigid]
        if len(flex) + len(rigid) != len(bodies):
            raise InputError("bodies", list(bodies), "Model, RigidBody or PointMass objects")
        dims = {b.dim for _, b in both}
        if len(dims) != 1:
            raise InputError("bodies", sorted(dims), "bodies of one dimension (all 2D or all 3D)")
        self.dim = dims.pop()
        self.bodies = dict(both)
        self.names = [k for k, _ in both]
        self.flex = [b for _, b in flex]
        self.rigid = [b for _, b in rigid]
        self.offsets: dict[str, int] = {}
        n = 0
        for name, b in both:
            self.offsets[name] = n
            n += b.n if isinstance(b, Model) else b.size
        self.n = n
        y0, v0 = np.zeros(n), np.zeros(n)
        for name, b in both:
            o = self.offsets[name]
            if isinstance(b, Model):
                y0[o : o + b.n], v0[o : o + b.n] = b.y0, b.v0
            else:
                yy, vv = b.initial()
                y0[o : o + b.size], v0[o : o + b.size] = yy, vv
        self.y0, self.v0 = y0, v0
        self.single = self.names[0] if len(self.names) == 1 else None

    # ---------------------------------------------------------------- places
    def resolve(self, spec: Place | str | int) -> Place:
        """A place with its body checked (node indices normalized, points checked)."""
        p = Place.parse(spec, self.single)
        if p.body is None:
            return p
        if p.body not in self.bodies:
            raise InputError("place", str(p), f"a body: {', '.join(self.names)} or ground")
        b = self.bodies[p.body]
        if isinstance(b, Model):
            at = {"start": 0, "end": -1}.get(p.at, p.at) if isinstance(p.at, str) else p.at
            if not isinstance(at, int):
                raise InputError("place", str(p), f'a node of {p.body}: "start", "end" or an index')
            return Place(p.body, b.check_node(at, f"place {p}"))
        if isinstance(b, PointMass) and p.at is not None:
            raise InputError("place", str(p), f"the point mass itself: {p.body!r}")
        if isinstance(b, RigidBody):
            b.point(p.at if isinstance(p.at, str) or p.at is None else str(p.at))
        return p

    def reference_position(self, p: Place) -> NDArray[np.float64]:
        """A place's position in the reference configuration (3 components)."""
        b = self.bodies[p.body_name()]
        if isinstance(b, Model):
            return np.r_[b.node_positions(b.q0)[p.node()], np.zeros(3 - self.dim)]
        yy, _ = b.initial()
        x = np.r_[yy[: self.dim], np.zeros(3 - self.dim)]
        if isinstance(b, RigidBody) and p.at is not None:
            r = b.rotation()
            s = b.point(p.point_name())[: self.dim]
            x[: self.dim] += r @ s
        return x

    def place_record(self, p: Place) -> PlaceRecord:
        """The core's record of the resolved place ``p`` on a body (:meth:`resolve`)."""
        b = self.bodies[p.body_name()]
        if isinstance(b, Model):
            node = p.node()
            beam = b.family.beam_kernel(b.kernel)
            angle0 = float(beam.psi0[node]) if beam is not None else 0.0
            return PlaceRecord(b.family.place_kind, self.flex.index(b), node, angle0=angle0)
        if isinstance(b, PointMass):
            return PlaceRecord("mass", self.rigid.index(b))
        kind = "rigid2d" if self.dim == 2 else "rigid3d"
        return PlaceRecord(kind, self.rigid.index(b), point=vec3(b.point(p.point_name())))

    # ---------------------------------------------------------------- coordinates
    def body_slice(self, name: str) -> slice:
        """The coordinates of one body in ``y``."""
        o = self.offsets[name]
        b = self.bodies[name]
        return slice(o, o + (b.n if isinstance(b, Model) else b.size))

    @property
    def fixed(self) -> NDArray[np.bool_]:
        """Held coordinates (flexible bodies' supports)."""
        out = np.zeros(self.n, dtype=bool)
        for name, b in zip(self.names, self.flex, strict=False):
            out[self.body_slice(name)] = b.fixed
        out[list(getattr(self, "held_coordinates", ()))] = True  # held drums (system.drums)
        return out

    def reset_triads(self) -> None:
        """Rods: every flexible body's nodal triads back to their reference."""
        for b in self.flex:
            b.reset_triads()

    def _each_flex(self) -> list[tuple[Model, slice]]:
        return [(b, self.body_slice(name)) for name, b in zip(self.names, self.flex, strict=False)]

    def q_from_y(self, y: ArrayLike) -> NDArray[np.float64]:
        """Full coordinates (a flexible body's nodal coordinates, clamp rotations undone; rigid
        bodies' as they are), ``(..., n)``."""
        q = np.array(y, dtype=float)
        for b, sl in self._each_flex():
            if b.reduction is not None or b.rotations:  # else q = y on the body's columns
                q[..., sl] = b.q_from_y(q[..., sl])
        return q

    def y_from_q(self, q: ArrayLike) -> NDArray[np.float64]:
        """Inverse of :meth:`q_from_y`."""
        y = np.array(q, dtype=float)
        for b, sl in self._each_flex():
            if b.reduction is not None or b.rotations:  # else y = q on the body's columns
                y[..., sl] = b.y_from_q(y[..., sl])
        return y

    def nodal_directors(self, y: NDArray) -> NDArray[np.float64] | None:
        """Rods' nodal directors ``(n_rod_nodes, 3)`` of every rod body (None without rods)."""
        parts = [b.nodal_directors(y[sl]) for b, sl in self._each_flex() if b.family.has_triads]
        rods = [d for d in parts if d is not None]  # a rod has directors
        return np.concatenate(rods) if rods else None

    def rereference(self, y: NDArray, v: NDArray, a: NDArray, w: NDArray | None = None) -> None:
        """Rods: carry the nodal triads to ``y`` (their spin rates in ``v``, ``a`` kept; the
        algorithmic accelerations ``w`` carried as ``a``)."""
        for b, sl in self._each_flex():
            if b.family.has_triads:
                vv, aa = v[sl].copy(), a[sl].copy()
                ww = None if w is None else w[sl].copy()
                b.core.rereference(y[sl], vv, aa, ww)
                v[sl], a[sl] = vv, aa
                if w is not None:
                    w[sl] = ww

    @property
    def size(self) -> float:
        """Characteristic length: the largest extent of the reference (Newton tolerances)."""
        pts = [b.node_positions(b.q0) for b in self.flex]
        pts += [
            np.atleast_2d(self.y0[self.body_slice(k)][: self.dim])
            for k, b in self.bodies.items()
            if not isinstance(b, Model)
        ]
        allp = np.concatenate(pts)
        return float(np.ptp(allp, axis=0).max()) or 1.0
