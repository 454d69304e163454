"""Sensors of a system, evaluated from stored rows and their derived values.

Kinds (column names ``NAME`` for one number, ``NAME_x``, ``NAME_y`` (, ``NAME_z``) for vectors):

* ``position`` (``at``) and ``distance`` (``between``) of places; ``twist`` (``at``, a rod node:
  its twist coordinate ``φ`` [rad]);
* ``angular_momentum`` about ``about`` (default the origin; 2D: the ``z`` component) and
  ``energy`` (kinetic + strain + gravitational [J]) of the whole system;
* ``reaction``: the force of the joint ``joint`` or of the support at ``at`` (a ``sliding``
  joint: also the arc length ``NAME_s`` at its place) and, where it
  carries one (a clamp, a rod's support, a ``fixed`` or driven joint, a 3D ``revolute``), its
  moment ``NAME_mz`` (planar) or ``NAME_mx, NAME_my, NAME_mz``: the columns of
  ``reactions.csv`` (:mod:`rancf.system.outputs`);
* ``axial_force`` (or ``tension``) at a node of a flexible body (the section value ``N``,
  :mod:`rancf.bodies.section_outputs`; of cables and rods from the nodal forces,
  :mod:`rancf.bodies.nodal_forces`);
* ``touchdown``: where a line leaves a plane obstacle (:mod:`rancf.system.touchdown`);
* ``fluid_force`` on a flexible body (``body``) or on all of them: buoyancy, drag and the
  waves' Froude–Krylov force (:mod:`rancf.system.fluid`; the added mass left out);
* ``wave_elevation`` with ``at_point``: the free surface's height above that point's horizontal
  position (:func:`surface_elevation`);
* ``angle`` of a rigid body: its angle [rad] in 2D (continuous, as integrated), its rotation
  vector in 3D;
* ``center_of_mass`` [m] and ``momentum`` (linear, [kg m/s]) of the body ``body`` or, without
  it, of the whole system;
* ``position``, ``twist``, ``axial_force`` and ``tension`` with ``at_point``: at the material
  point nearest to a fixed point in space (:mod:`rancf.system.at_point`).

Mass, centre of mass and momentum of a flexible body: a rigid translation ``e_i`` moves every
node's position by ``e_i`` and no gradient, and the shape functions' position parts sum to one,
so with the mass matrix ``M`` and ``w_i = M T_i`` (``T_i``: the coordinates of that
translation) ``m = T_iᵀ M T_i``, ``∫ ρA r_i ds = w_i · y`` and ``p_i = w_i · v`` (beams: their
consistent translational mass, the same identity).  Rigid bodies and point masses contribute
``m x`` and ``m ẋ``; angular momentum adds ``R J ω`` (3D, ``ω = 2 G(p) ṗ`` in the body frame).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.motion import angular_momentum
from rancf.bodies.rigid import PointMass, RigidBody, body_angular_velocity
from rancf.bodies.shell_model import shell_reader
from rancf.errors import InputError
from rancf.system.at_point import at_point_reader
from rancf.system.parts.support import Support
from rancf.system.places import Place
from rancf.system.readers import Block, NamedReader, Reader

__all__ = ["SensorReader"]


class OutputsView(Protocol):
    """What the sensors read of a run's derived outputs
    (:class:`rancf.system.outputs.SystemOutputs`, which holds the sensors)."""

    system: Any
    flex: list[tuple[str, Model]]
    samplers: dict[str, Any]
    part_columns: list[tuple[Any, list[str]]]

    def joint_columns(self, name: str) -> slice: ...

    def contact_columns(self, name: str) -> slice: ...

    def body_along(self, along: NDArray, name: str) -> NDArray[np.float64]: ...


class SensorReader:
    """The sensors' columns of blocks of rows (module docstring)."""

    def __init__(self, outputs: OutputsView, sensors: Sequence[Any]) -> None:
        self.out = outputs
        self.system = outputs.system
        self.names: list[str] = []
        self._readers: list[Reader] = []
        self._mass: dict[str, tuple[float, NDArray]] = {}
        self._kinds: list[str] = []
        for sen in sensors:
            reader = self._reader(sen)
            columns = reader.columns if isinstance(reader, NamedReader) else []
            self.names += columns or sen.columns(self.system.dim)
            self._readers.append(reader)
            self._kinds.append(sen.kind)

    def values(
        self,
        t: NDArray,
        q: NDArray,
        v: NDArray | None,
        derived: dict[str, NDArray],
        energy: NDArray | None,
    ) -> NDArray[np.float64]:
        """Columns ``(k, n_columns)`` of rows ``q``, ``v`` with their ``derived`` values."""
        vv = np.zeros_like(q) if v is None else np.asarray(v, dtype=float).reshape(q.shape)
        if energy is None and any(s == "energy" for s in self._kinds):
            sy = self.system
            energy = np.array(
                [
                    sy.energies(sy.y_from_q(a), sy.y_from_q(b), tt)
                    for a, b, tt in zip(q, vv, t, strict=True)
                ]
            )
        block = (t, q, vv, derived, energy if energy is not None else np.zeros((len(t), 3)))
        cols = [np.asarray(r(block), dtype=float).reshape(len(t), -1) for r in self._readers]
        return np.concatenate(cols, axis=1) if cols else np.empty((len(t), 0))

    # ------------------------------------------------------------------ places
    def _place(self, sen: Any, spec: Any) -> Place:
        try:
            p = self.system.resolve(spec)
        except InputError as exc:
            raise InputError(f"sensors.{sen.name}", spec, exc.allowed) from None
        if p.body is None:
            raise InputError(f"sensors.{sen.name}", "ground", "a place on a body")
        return p

    def _position(self, sen: Any, spec: Any) -> Reader:
        s = self.system
        p = self._place(sen, spec)
        body = p.body_name()
        b = s.bodies[body]
        if isinstance(b, Model):
            base = s.offsets[body] + p.node() * b.dpn
            return lambda blk: blk[1][:, base : base + s.dim]
        if isinstance(b, PointMass) or p.at is None:
            o = s.offsets[body]
            return lambda blk: blk[1][:, o : o + s.dim]
        s.place_state(p, s.y0)  # raises unless the place is observed

        def read(blk: Block) -> NDArray:
            return np.array(
                [
                    s.place_state(p, s.y_from_q(row), tt)[0][: s.dim]
                    for tt, row in zip(blk[0], blk[1], strict=True)
                ]
            )

        return read

    # ------------------------------------------------------------------ kinds
    def _reader(self, sen: Any) -> Reader:
        kind = sen.kind
        places = tuple(getattr(sen, "places", ()) or getattr(sen, "nodes", ()))
        reader: Reader
        if kind == "wave_elevation":
            from rancf.system.fluid import surface_elevation

            pt = sen.point
            reader = lambda blk: surface_elevation(self.system, pt, blk[0])  # noqa: E731
        elif getattr(sen, "point", None) is not None:
            reader = at_point_reader(self.out, sen)
        elif kind == "position":  # a shell's point [u, v] by its shape-function row
            reader = shell_reader(self.system, places[0]) or self._position(sen, places[0])
        elif kind == "distance":
            a, b = (self._position(sen, x) for x in places[:2])
            reader = lambda blk: np.linalg.norm(b(blk) - a(blk), axis=1)  # noqa: E731
        elif kind == "twist":
            reader = self._twist(sen, places[0])
        elif kind == "energy":
            reader = lambda blk: blk[4].sum(axis=1)  # noqa: E731
        elif kind == "angular_momentum":
            reader = self._angular_momentum(sen)
        elif kind == "reaction":
            reader = self._reaction(sen, places)
        elif kind in ("axial_force", "tension"):  # a line's tension is its axial force
            reader = self._axial_force(sen, places[0])
        elif kind == "angle":
            reader = self._angle(sen)
        elif kind in ("center_of_mass", "momentum"):
            reader = self._mass_moment(sen, kind == "momentum")
        elif kind == "contact_force":
            reader = self._contact_force(sen)
        elif kind == "fluid_force":
            reader = self._fluid_force(sen)
        elif kind == "touchdown":
            reader = self._touchdown(sen)
        elif kind == "winch":
            from rancf.system.winches import winch_reader

            reader = winch_reader(self.out, sen)
        else:
            raise InputError(f"sensors.{sen.name}.kind", kind, "a sensor kind")
        return reader

    def _twist(self, sen: Any, spec: Any) -> Reader:
        p = self._place(sen, spec)
        body = p.body_name()
        b = self.system.bodies[body]
        if not (isinstance(b, Model) and b.family.has_triads):
            raise InputError(f"sensors.{sen.name}.at", str(p), "a node of a rod")
        i = self.system.offsets[body] + p.node() * b.dpn + 6
        return lambda blk: blk[1][:, i]

    def _reaction(self, sen: Any, places: tuple) -> Reader:
        """The reaction columns of the joint or support (its Part's columns in
        ``reactions.csv``, :meth:`~rancf.system.part.Part.sensors`), renamed for the sensor:
        ``LABEL_fx`` as ``NAME_x``, ``LABEL_mz`` as ``NAME_mz``, ``LABEL_s`` as ``NAME_s``."""
        out, sy = self.out, self.system
        if getattr(sen, "joint", None) is not None:
            try:
                cols = out.joint_columns(sen.joint)
            except KeyError:
                names = [j.name for j in sy.joints if j.name]
                allowed = f"a joint: {', '.join(names) or 'none named'}"
                raise InputError(f"sensors.{sen.name}.joint", sen.joint, allowed) from None
            joint = next(j for j in sy.joints if j.label(sy) == sen.joint)
            return _columns_reader(sen.name, joint.label(sy), joint.sensors(sy), cols)
        p = self._place(sen, places[0])
        start = 0
        for part, names in out.part_columns:
            if isinstance(part, Support) and part.body == p.body:
                if sy.bodies[p.body].check_node(part.node, "supports.at") == p.at:
                    cols = slice(start, start + len(names))
                    return _columns_reader(sen.name, part.label(sy), names, cols)
            start += len(names)
        turning = [j for j in sy.joints if getattr(j, "rotation", None) is not None]
        for j in turning:  # a turning clamp: a joint with a support's columns (its name)
            if sy.resolve(j.between[0]) == p:
                cols = out.joint_columns(j.name)
                return _columns_reader(sen.name, j.label(sy), j.sensors(sy), cols)
        raise InputError(f"sensors.{sen.name}.at", str(p), "the place of a support")

    def _contact_force(self, sen: Any) -> Reader:
        names = self.system.obstacle_names
        if sen.obstacle not in names:
            raise InputError(
                f"sensors.{sen.name}.obstacle",
                sen.obstacle,
                f"an obstacle: {', '.join(names) or 'none'}",
            )
        c, d = self.out.contact_columns(sen.obstacle).start, self.system.dim
        return lambda blk: blk[3]["r"][:, c : c + d] + blk[3]["r"][:, c + d : c + 2 * d]

    def _fluid_force(self, sen: Any) -> Reader:
        """Buoyancy, drag and the waves' Froude-Krylov force on one flexible body or on all of
        them (docs/derivations/fluid.md section 3; the added mass needs accelerations: left
        out)."""
        s, d = self.system, self.system.dim
        flex = [n for n, _ in self.out.flex]
        body = getattr(sen, "body", None)
        if body is not None and body not in flex:
            raise InputError(
                f"sensors.{sen.name}.body", body, f"a flexible body: {', '.join(flex)}"
            )
        pick = [flex.index(body)] if body is not None else list(range(len(flex)))

        def read(blk: Block) -> NDArray:
            out = np.zeros((len(blk[0]), d))
            for k, (tt, q, v) in enumerate(zip(blk[0], blk[1], blk[2], strict=True)):
                y, w = s.y_from_q(q), s.y_from_q(v)
                f = np.asarray(s.core.fluid_forces(y, w, np.zeros_like(y), float(tt)))
                out[k] = f.reshape(-1, 3)[pick, :d].sum(axis=0)
            return out

        return read

    def _touchdown(self, sen: Any) -> Reader:
        """Where the line leaves a plane obstacle
        (:func:`rancf.system.touchdown.touchdown_point`)."""
        from rancf.system.touchdown import touchdown_point

        s = self.system
        names = list(s.obstacle_names)
        ob = s.obstacles[names.index(sen.obstacle)] if sen.obstacle in names else None
        if ob is None or ob.kind != "plane" or ob.body is not None:
            planes = [
                n
                for n, o in zip(names, s.obstacles, strict=False)
                if o.kind == "plane" and o.body is None
            ]
            raise InputError(
                f"sensors.{sen.name}.obstacle",
                sen.obstacle,
                f"a fixed plane: {', '.join(planes) or 'none'}",
            )
        flex = [n for n, b in self.out.flex if b.family.gradient]
        body = getattr(sen, "body", None) or (flex[0] if len(flex) == 1 else None)
        if body not in flex:
            raise InputError(
                f"sensors.{sen.name}.body",
                body,
                f"a line (cable or rod elements): {', '.join(flex)}",
            )
        m, sl = s.bodies[body], s.body_slice(body)
        point, normal = np.asarray(ob.point, float), np.asarray(ob.normal, float)
        return lambda blk: np.array([touchdown_point(m, q[sl], point, normal) for q in blk[1]])

    def _axial_force(self, sen: Any, spec: Any) -> Reader:
        p = self._place(sen, spec)
        name = p.body_name()
        b = self.system.bodies[name]
        if not isinstance(b, Model):
            raise InputError(f"sensors.{sen.name}.at", str(p), "a node of a flexible body")
        sp = self.out.samplers[name]
        point = min(p.node() * sp.per_element, sp.n_points - 1)
        return lambda blk: self.out.body_along(blk[3]["s"], name)[:, point, 1]

    def _angle(self, sen: Any) -> Reader:
        s = self.system
        b = s.bodies.get(sen.body)
        if not isinstance(b, RigidBody):
            rigid = [n for n, x in s.bodies.items() if isinstance(x, RigidBody)]
            raise InputError(
                f"sensors.{sen.name}.body", sen.body, f"a rigid body: {', '.join(rigid) or 'none'}"
            )
        o = s.offsets[sen.body]
        if s.dim == 2:
            return lambda blk: blk[1][:, o + 2]
        from scipy.spatial.transform import Rotation

        return lambda blk: Rotation.from_quat(blk[1][:, o + 3 : o + 7][:, [1, 2, 3, 0]]).as_rotvec()

    def _translation(self, name: str) -> tuple[float, NDArray]:
        """Mass and ``w_i = M T_i`` ``(dim, n_body)`` of a flexible body (module docstring)."""
        if name not in self._mass:
            b = self.system.bodies[name]
            assert isinstance(b, Model)
            d = self.system.dim
            w = np.empty((d, b.n))
            for i in range(d):
                ti = np.zeros((b.n_nodes, b.dpn))
                ti[:, i] = 1.0
                w[i] = b.mass_times(ti.ravel())
                if i == 0:
                    mass = float(w[0] @ ti.ravel())
            self._mass[name] = (mass, w)
        return self._mass[name]

    def _mass_moment(self, sen: Any, momentum: bool) -> Reader:
        s = self.system
        names = s.names if sen.body is None else [sen.body]
        if sen.body is not None and sen.body not in s.bodies:
            raise InputError(f"sensors.{sen.name}.body", sen.body, f"a body: {', '.join(s.names)}")

        def read(blk: Block) -> NDArray:
            total, acc = 0.0, np.zeros((len(blk[0]), s.dim))
            for name in names:
                b, sl = s.bodies[name], s.body_slice(name)
                x = blk[2][:, sl] if momentum else blk[1][:, sl]
                if isinstance(b, Model):
                    m, w = self._translation(name)
                    acc += s.y_from_q(blk[2] if momentum else blk[1])[:, sl] @ w.T
                else:
                    m = b.mass
                    acc += m * x[:, : s.dim]
                total += m
            return acc if momentum else acc / total

        return read

    def _angular_momentum(self, sen: Any) -> Reader:
        s = self.system
        about = getattr(sen, "about", None)
        c = np.zeros(3) if about is None else np.r_[np.asarray(about, float), 0.0][:3]

        def read(blk: Block) -> NDArray:
            k = len(blk[0])
            total = np.zeros((k, 3 if s.dim == 3 else 1))
            for name in s.names:
                b, sl = s.bodies[name], s.body_slice(name)
                q, v = blk[1][:, sl], blk[2][:, sl]
                if isinstance(b, Model):
                    total += angular_momentum(b, q, v, c[: s.dim])
                    continue
                r, p = q[:, : s.dim] - c[: s.dim], b.mass * v[:, : s.dim]
                if s.dim == 2:
                    total[:, 0] += r[:, 0] * p[:, 1] - r[:, 1] * p[:, 0]
                    if isinstance(b, RigidBody):
                        total[:, 0] += b.inertia_vector()[0] * v[:, 2]
                    continue
                total += np.cross(r, p)
                if isinstance(b, RigidBody):
                    from scipy.spatial.transform import Rotation

                    rot = Rotation.from_quat(q[:, 3:7][:, [1, 2, 3, 0]]).as_matrix()
                    for i in range(k):
                        w = body_angular_velocity(q[i, 3:7], v[i, 3:7])
                        total[i] += rot[i] @ (b.inertia_vector() * w)
            return total

        return read


def _columns_reader(name: str, label: str, columns: Sequence[str], cols: slice) -> Reader:
    """A reader of the reaction columns ``cols``, named ``columns`` (``LABEL_SUFFIX``) by their
    part: as the sensor ``name``'s ``NAME_SUFFIX``, a force's ``fx`` as ``x``."""
    suffixes = [c[len(label) + 1 :] for c in columns]
    names = [f"{name}_{x[1:] if x[:1] == 'f' and len(x) == 2 else x}" for x in suffixes]

    def read(blk: Block) -> NDArray:
        return blk[3]["r"][:, cols]

    return NamedReader(read, names)
