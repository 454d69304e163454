"""A system: flexible bodies, rigid bodies and point masses, joints, springs and loads, assembled
into the compiled core's :class:`rancf.kernels._core.System` (``src/cpp/system.hpp``).

Coordinates ``y`` stack the bodies in the order flexible bodies (their model coordinates, held
supports included), then rigid bodies and point masses (:mod:`rancf.bodies.rigid`).  A joint's
orientation data (reference relative rotations, axes in the bodies' frames) are measured in the
reference configuration, so every joint holds there exactly.  ``"ground"`` in a joint or spring
is the other place's reference position; a joint to the ground with ``motion`` moves that point
by the time function (a moving support of a rigid body).  Supports of flexible bodies are the
models' own (held coordinates); a support's ``motion`` makes its held position follow the time
function.  Gravity acts on rigid bodies and point masses through ``gravity``; a flexible body's
gravity is its model's.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.closure import closure_matrix, closure_rows
from rancf.bodies.flexible import Model
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.kernels import _core
from rancf.system.connections import JOINT_KINDS, Joint, Load, Spring
from rancf.system.contact import CONTACT_POINTS, Obstacle
from rancf.system.core_data import attach_contact, build_core
from rancf.system.joint_data import joint_data
from rancf.system.places import Place

__all__ = ["System", "Body"]

Body = Model | RigidBody | PointMass
_NODE_KIND = {"rancf": 1, "ancf": 1, "rod": 2, "beam": 3}


@dataclass
class _Rows:
    """Growing arrays of the core's constructor."""

    places: list[tuple] = field(default_factory=list)
    joints: list[dict] = field(default_factory=list)
    tfs: list[TimeFunction] = field(default_factory=list)

    def tf(self, f: TimeFunction | None) -> int:
        if f is None:
            return -1
        self.tfs.append(f)
        return len(self.tfs) - 1


class System:
    """Bodies, joints, springs and loads (module docstring).

    Parameters
    ----------
    bodies : mapping name -> Model | RigidBody | PointMass
    joints, springs, loads : sequences of :class:`Joint`, :class:`Spring`, :class:`Load`
    gravity : ``(dim,)``, optional
        On rigid bodies and point masses.
    damping : float
        Mass-proportional damping ``c`` of every body [1/s] (flexible bodies: their model's is
        ignored).
    obstacles : sequence of :class:`rancf.system.Obstacle`
        Contact (:mod:`rancf.system.contact`).
    contacts : sequence of (flexible body, obstacle) names, optional
        The pairs in contact; default every flexible body with every obstacle.
    contact_points : int
        Gauss points per element at which contact is evaluated.
    body_contacts : sequence of (flexible body, flexible body) names
        Contact between flexible bodies; a body twice: self-contact.
    body_friction : float
        Coulomb coefficient of the contact between flexible bodies.
    observe : sequence of places
        Places on bodies whose position and frame outputs read (:meth:`place_state`).
    horizon : float, optional
        The end of the runs [s]: time functions given as Python callables are sampled on
        ``[0, horizon]`` (a cubic table of 2001 points, :meth:`TimeFunction.sampled`) for the
        compiled loop; required when there are such functions.
    """

    def __init__(
        self,
        bodies: Mapping[str, Body],
        joints: Sequence[Joint] = (),
        springs: Sequence[Spring] = (),
        loads: Sequence[Load] = (),
        gravity: ArrayLike | None = None,
        damping: float = 0.0,
        observe: Sequence[Place | str] = (),
        horizon: float | None = None,
        obstacles: Sequence[Obstacle] = (),
        contacts: Sequence[tuple[str, str]] | None = None,
        contact_points: int = CONTACT_POINTS,
        body_contacts: Sequence[tuple[str, str]] = (),
        body_friction: float = 0.0,
    ) -> None:
        if not bodies:
            raise InputError("bodies", {}, "at least one body")
        for name in bodies:
            if not isinstance(name, str) or not name or name == "ground" or ":" in name:
                raise InputError("bodies.name", name, 'a name without ":", not "ground"')
        flex = [(k, b) for k, b in bodies.items() if isinstance(b, Model)]
        rigid = [(k, b) for k, b in bodies.items() if isinstance(b, RigidBody | PointMass)]
        if len(flex) + len(rigid) != len(bodies):
            raise InputError("bodies", list(bodies), "Model, RigidBody or PointMass objects")
        dims = {b.dim for _, b in flex + rigid}
        if len(dims) != 1:
            raise InputError("bodies", sorted(dims), "bodies of one dimension (all 2D or all 3D)")
        self.dim = dims.pop()
        self.bodies = dict(flex + rigid)
        self.names = [k for k, _ in flex + rigid]
        self.flex = [b for _, b in flex]
        self.rigid = [b for _, b in rigid]
        self.gravity = (
            np.zeros(3) if gravity is None else np.r_[np.asarray(gravity, float), 0.0][:3]
        )
        if gravity is not None and np.asarray(gravity).size != self.dim:
            raise InputError("loads.gravity", list(np.asarray(gravity)), f"{self.dim} components")
        self._check_gravity(flex)
        if not (np.isfinite(damping) and damping >= 0):
            raise InputError("damping.mass_proportional", damping, "a finite number >= 0")
        self.damping = float(damping)
        self.horizon = horizon
        self.offsets: dict[str, int] = {}
        n = 0
        for name, b in flex + rigid:
            self.offsets[name] = n
            n += b.n if isinstance(b, Model) else b.size
        self.n = n
        y0, v0 = np.zeros(n), np.zeros(n)
        for name, b in flex + rigid:
            o = self.offsets[name]
            if isinstance(b, Model):
                y0[o : o + b.n], v0[o : o + b.n] = b.y0, b.v0
            else:
                yy, vv = b.initial()
                y0[o : o + b.size], v0[o : o + b.size] = yy, vv
        self.y0, self.v0 = y0, v0
        self.joints, self.springs, self.loads = tuple(joints), tuple(springs), tuple(loads)
        self.single = self.names[0] if len(self.names) == 1 else None
        self._linear = self._closures()
        rows = _Rows()
        self._place_index: dict[Place, int] = {}
        self._prescribed = self._motions(rows)
        self._spring_rows = [self._spring(s, rows) for s in springs]
        self._load_rows = [self._load(ld, rows) for ld in self._all_loads()]
        for spec in observe:
            p = self.resolve(spec)
            if p.body is None:
                raise InputError("place", "ground", "a place on a body")
            self._index(p, rows)
        pre = [self._place(j, rows) for j in joints]  # places first: their reference frames
        self.core = self._build(rows, [])
        self.joint_data = [self._joint(j, ab, rows) for j, ab in zip(joints, pre, strict=True)]
        self.core = self._build(rows, self.joint_data)
        self.m = int(self.core.m)
        self.joint_rows = list(self.core.joint_rows)
        self.obstacles = tuple(obstacles)  # contact: attached to the core
        self.body_contacts, self.contact_points = [(a, b) for a, b in body_contacts], contact_points
        self.contact, self.obstacle_names, self.contact_pairs = attach_contact(
            self, self.obstacles, contacts, contact_points, body_contacts, body_friction
        )
        self._check_reference()

    def _check_gravity(self, flex: list[tuple[str, Model]]) -> None:
        """A flexible body's weight comes from its model's ``gravity``, a rigid body's from the
        system's: a model with no gravity of its own in a system with gravity gets one warning
        line (its weight is left out); an explicit model gravity is taken as meant."""
        if not self.gravity.any():
            return
        for name, b in flex:
            if b.gravity is None:
                warnings.warn(f"rancf: body {name!r} has no gravity of its own, so its weight "
                              f"is left out of the system's gravity "
                              f"{self.gravity[: self.dim].tolist()}: give its Model the same "
                              "gravity (or gravity=[0, ...] to mean it)", stacklevel=3)  # fmt: skip

    def _check_reference(self) -> None:
        """Every joint holds in the reference configuration at t = 0 (positions to 1e-9 of the
        system's size; an orientation holds by construction): else one line naming the joint
        and how far apart its places are."""
        g = np.empty(self.m)
        self.core.constraints(self.y0, 0.0, g)
        for k, j in enumerate(self.joints):
            rows = g[self.joint_rows[k] : self.joint_rows[k] + (2 if self.dim == 2 else 3)]
            if j.kind == "slider":
                rows = g[self.joint_rows[k] : self.joint_rows[k] + self.dim - 1]
            gap = float(np.linalg.norm(rows))
            if not gap <= 1e-9 * self.size:
                name = j.name or f"joints[{k}]"
                raise InputError(
                    f"{name}.between", [str(x) for x in j.between],
                    f"places that coincide in the reference configuration (they are "
                    f"{gap:.4g} m apart; move the bodies, or the points, so they meet)",
                )  # fmt: skip

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

    def _index(self, p: Place, rows: _Rows, ground_point: NDArray | None = None,
               motion: int = -1) -> int:  # fmt: skip
        key = p if p.body is not None else Place(None, (tuple(ground_point), motion))  # type: ignore[arg-type]
        if key in self._place_index:
            return self._place_index[key]
        point, kind, body, node, angle0 = np.zeros(3), 0, -1, 0, 0.0
        if p.body is None:
            point[: self.dim] = ground_point[: self.dim]  # type: ignore[index]
        else:
            b = self.bodies[p.body]
            if isinstance(b, Model):
                kind, body, node = _NODE_KIND[b.element], self.flex.index(b), int(p.at)  # type: ignore[arg-type]
                if b.element == "beam":
                    angle0 = float(b.kernel.psi0[node])
            elif isinstance(b, PointMass):
                kind, body = 6, self.rigid.index(b)
            else:
                kind, body = (4 if self.dim == 2 else 5), self.rigid.index(b)
                point = b.point(p.at)  # type: ignore[arg-type]
        rows.places.append((kind, body, node, point, motion if p.body is None else -1, angle0))
        self._place_index[key] = len(rows.places) - 1
        return len(rows.places) - 1

    def place_state(
        self, spec: Place | str, y: NDArray, t: float = 0.0
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Position ``(3,)`` and frame rows ``(k, 3)`` (a cable node: its unit tangent; a rod
        node or rigid body: its frame; a point mass: none) of a joint's, spring's, load's or
        observed place at ``y``, ``t``."""
        key = self.resolve(spec)
        if key not in self._place_index:
            raise InputError("place", str(key), "a place of a joint, spring, load or sensor")
        x, f = self.core.place(self._place_index[key], np.asarray(y, dtype=float), float(t))
        return np.asarray(x), np.asarray(f).reshape(-1, 3)

    def reference_position(self, p: Place) -> NDArray[np.float64]:
        """A place's position in the reference configuration (3 components)."""
        b = self.bodies[p.body]  # type: ignore[index]
        if isinstance(b, Model):
            return np.r_[b.node_positions(b.q0)[int(p.at)], np.zeros(3 - self.dim)]  # type: ignore[arg-type]
        yy, _ = b.initial()
        x = np.r_[yy[: self.dim], np.zeros(3 - self.dim)]
        if isinstance(b, RigidBody) and p.at is not None:
            r = b.rotation()
            s = b.point(p.at)[: self.dim]  # type: ignore[arg-type]
            x[: self.dim] += r @ s
        return x

    def _pair(self, between: Sequence, rows: _Rows, motion: int = -1) -> tuple[int, int]:
        if len(between) != 2:
            raise InputError("between", list(between), "two places")
        a, b = (self.resolve(x) for x in between)
        if a.body is None and b.body is None:
            raise InputError("between", [str(a), str(b)], "at least one place on a body")
        if a.body is None:  # the body's place first
            a, b = b, a
        gp = self.reference_position(a)
        return self._index(a, rows), self._index(b, rows, gp, motion)

    # ---------------------------------------------------------------- parts
    def _motions(self, rows: _Rows) -> list[tuple[int, int, int, float]]:
        """Held positions of flexible bodies that follow their support's motion."""
        out = []
        for name, b in zip(self.names, self.flex, strict=False):
            for sup in b.supports:
                if sup.motion is None:
                    continue
                if sup.kind == "roller":
                    raise InputError(
                        "supports.motion", "roller", "a pin or clamp (moving supports)"
                    )
                if sup.motion.size != self.dim:
                    raise InputError("supports.motion", sup.motion.size, f"{self.dim} components")
                k = rows.tf(sup.motion)
                base = self.offsets[name] + b._node_base(b.check_node(sup.node, "supports.at"))
                for i in range(self.dim):
                    out.append(
                        (base + i, k, i, float(b.y_installed[base - self.offsets[name] + i]))
                    )
        return out

    def _closures(self) -> tuple[NDArray, NDArray, NDArray]:
        """The seams of closed flexible bodies as linear rows ``(row, column, coefficient)``
        (:func:`rancf.bodies.closure.closure_rows`), in system coordinates."""
        parts, m = [], 0
        for name, b in zip(self.names, self.flex, strict=False):
            r, c, v = closure_rows(b)
            parts.append((r + m, c + self.offsets[name], v))
            m += closure_matrix(b).shape[0]
        if not parts:
            return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0)
        return tuple(np.concatenate(x) for x in zip(*parts, strict=True))  # type: ignore[return-value]

    def _spring(self, s: Spring, rows: _Rows) -> tuple[int, int, float, float, float]:
        a, b = self._pair(s.between, rows)
        for key, v in (("springs.stiffness", s.stiffness), ("springs.damping", s.damping)):
            if not (np.isfinite(v) and v >= 0):
                raise InputError(key, v, "a finite number >= 0")
        pa, pb = (self.resolve(x) for x in s.between)
        xa = self.reference_position(pa) if pa.body is not None else None
        xb = self.reference_position(pb) if pb.body is not None else None
        ref = 0.0 if xa is None or xb is None else float(np.linalg.norm(xa - xb))
        length = ref if s.length is None else float(s.length)
        if length != 0.0 and ref <= 1e-12 * self.size:  # no direction where the places meet
            raise InputError(f"springs.{s.name or '/'.join(map(str, s.between))}.length",
                             length, "0 where its places meet at the reference (ground sits at "
                             "the other place's reference): the linear spring-damper "
                             "k (x_a - x_b) + c (v_a - v_b)")  # fmt: skip
        return a, b, float(s.stiffness), float(s.damping), length

    def _all_loads(self) -> list[Load]:
        """The loads, and flexible bodies' point forces (and rods' moments) times a time
        function."""
        out = list(self.loads)
        for name, b in zip(self.names, self.flex, strict=False):
            for p in b.point_loads:
                if p.time is None:
                    continue
                out.append(
                    Load(
                        Place(name, b.check_node(p.node, "loads.point.at")),
                        p.force,
                        p.moment,
                        p.time,
                    )
                )
        return out

    def _load(self, ld: Load, rows: _Rows) -> tuple[int, NDArray, NDArray, int]:
        p = self.resolve(ld.at)
        if p.body is None:
            raise InputError("loads.point.at", "ground", "a place on a body")
        f = np.zeros(3) if ld.force is None else np.asarray(ld.force, dtype=float)
        t = np.zeros(3) if ld.torque is None else np.asarray(ld.torque, dtype=float)
        if ld.force is not None and f.size != self.dim:
            raise InputError("loads.point.force", list(f), f"{self.dim} components")
        b = self.bodies[p.body]
        rod = isinstance(b, Model) and b.element == "rod"
        if ld.torque is not None and not (isinstance(b, RigidBody) or rod):
            raise InputError("loads.point.moment", list(t), "a rigid body or a rod's node")
        tt = np.r_[np.zeros(2), t] if t.size == 1 else np.r_[t, np.zeros(3 - t.size)]
        if ld.time is not None and ld.time.size != 1:
            raise InputError("loads.point.time", ld.time.size, "a scalar time function (a factor)")
        return self._index(p, rows), np.r_[f, np.zeros(3 - f.size)], tt, rows.tf(ld.time)

    def _place(self, j: Joint, rows: _Rows) -> tuple[int, int]:
        if j.kind not in JOINT_KINDS:
            raise InputError("joints.kind", j.kind, f"one of {', '.join(JOINT_KINDS)}")
        return self._pair(j.between, rows, rows.tf(j.motion))

    def _frames(self, index: int) -> tuple[NDArray, NDArray]:
        x, f = self.core.place(index, self.y0, 0.0)
        return np.asarray(x), np.asarray(f).reshape(-1, 3)

    def _joint(self, j: Joint, ab: tuple[int, int], rows: _Rows) -> dict:
        a, b = ab
        angle = rows.tf(j.angle) if j.angle is not None else -1
        return joint_data(j, a, b, self._frames(a)[1], self._frames(b)[1], self.dim, angle)

    def _build(self, rows: _Rows, joints: list[dict]) -> _core.System:
        return build_core(self, rows, joints, [self._compiled(f) for f in rows.tfs])

    def _compiled(self, f: TimeFunction) -> TimeFunction:
        """A time function the compiled core evaluates (a callable sampled on the horizon)."""
        if f.kind != "callable":
            return f
        if self.horizon is None or not self.horizon > 0:
            raise InputError("horizon", self.horizon, "the run's end time t_end [s] > 0 (a Python "
                             "time function is sampled on [0, t_end])")  # fmt: skip
        return f.sampled(float(self.horizon))

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
        return out

    def energies(self, y: NDArray, v: NDArray) -> tuple[float, float, float]:
        """Kinetic, strain (with springs) and gravitational energy (zero at the reference)."""
        return self.core.energies(np.asarray(y, float), np.asarray(v, float))

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
            q[..., sl] = b.q_from_y(q[..., sl])
        return q

    def y_from_q(self, q: ArrayLike) -> NDArray[np.float64]:
        """Inverse of :meth:`q_from_y`."""
        y = np.array(q, dtype=float)
        for b, sl in self._each_flex():
            y[..., sl] = b.y_from_q(y[..., sl])
        return y

    def nodal_directors(self, y: NDArray) -> NDArray[np.float64] | None:
        """Rods' nodal directors ``(n_rod_nodes, 3)`` of every rod body (None without rods)."""
        parts = [b.nodal_directors(y[sl]) for b, sl in self._each_flex() if b.element == "rod"]
        return np.concatenate(parts) if parts else None

    def rereference(self, y: NDArray, v: NDArray, a: NDArray) -> None:
        """Rods: carry the nodal triads to ``y`` (their spin rates in ``v``, ``a`` kept)."""
        for b, sl in self._each_flex():
            if b.element == "rod":
                vv, aa = v[sl].copy(), a[sl].copy()
                b.core.rereference(y[sl], vv, aa)
                v[sl], a[sl] = vv, aa

    @property
    def size(self) -> float:
        """Characteristic length: the largest extent of the reference (Newton tolerances)."""
        pts = [b.node_positions(b.q0) for b in self.flex]
        pts += [np.atleast_2d(self.y0[self.body_slice(k)][: self.dim]) for k, b in
                self.bodies.items() if not isinstance(b, Model)]  # fmt: skip
        allp = np.concatenate(pts)
        return float(np.ptp(allp, axis=0).max()) or 1.0
