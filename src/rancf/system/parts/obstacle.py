"""Obstacles of a system's contact, a :class:`~rancf.system.part.Part`.

An obstacle (a plane, a cylinder or a sphere; carried by a rigid body or fixed) with its contact
law's coefficients; the law itself and its defaults are in :mod:`rancf.system.contact`.  Its
record is what the core's contact (``src/cpp/contact/contact.hpp``) takes of it: its kind, the
rigid body that carries it and its point, direction and radius.  The pairs of bodies and
obstacles in contact are Parts of :mod:`rancf.system.parts.contact_pair`.  Its sensor kinds:
``contact_force`` (the normal and friction forces on it, from its columns) and, a fixed plane,
``touchdown`` (where a line leaves it, :mod:`rancf.system.touchdown`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.rigid import RigidBody
from rancf.errors import InputError
from rancf.kernels.contact_records import OBSTACLE_KINDS, ObstacleRecord
from rancf.kernels.records import vec3
from rancf.system.readers import Reader, SensorBuilder, SensorHost

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = [
    "Obstacle",
    "OBSTACLE_KINDS",
    "STIFFNESS_FACTOR",
    "ONSET_FACTOR",
    "SLIP_VELOCITY",
]

#: Default penalty stiffness per Young's modulus (:mod:`rancf.system.contact`).
STIFFNESS_FACTOR = 0.1
#: Default onset width per tube radius (:mod:`rancf.system.contact`).
ONSET_FACTOR = 1e-3
#: Default regularization velocity ε of the friction [m/s].
SLIP_VELOCITY = 1e-3


def contact_force_reader(host: SensorHost, sen: Any) -> Reader:
    """A ``contact_force`` sensor: the normal plus the friction force on the obstacle
    ``sen.obstacle`` (its columns among the reactions)."""
    names = host.system.obstacle_names
    if sen.obstacle not in names:
        raise InputError(
            f"sensors.{sen.name}.obstacle",
            sen.obstacle,
            f"an obstacle: {', '.join(names) or 'none'}",
        )
    c, d = host.out.contact_columns(sen.obstacle).start, host.system.dim
    return lambda blk: blk[3]["r"][:, c : c + d] + blk[3]["r"][:, c + d : c + 2 * d]


def touchdown_reader(host: SensorHost, sen: Any) -> Reader:
    """A ``touchdown`` sensor: where the line leaves the fixed plane ``sen.obstacle``
    (:func:`rancf.system.touchdown.touchdown_point`)."""
    from rancf.system.touchdown import touchdown_point

    s = host.system
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
    flex = [n for n, b in host.out.flex if b.family.gradient]
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


@dataclass(frozen=True)
class Obstacle:
    """An obstacle (:mod:`rancf.system.contact`).

    Parameters
    ----------
    kind : {"plane", "cylinder", "sphere"}
    point, normal : (dim,)
        Plane: a point of it and its outward normal (need not be unit).
    center, radius :
        Cylinder (a circle in 2D) and sphere.
    axis : (3,)
        Cylinder in 3D.
    body : str, optional
        The rigid body that carries it (geometry then in its frame).
    friction : float
        Coulomb coefficient μ.
    stiffness : float, optional
        Penalty ``k`` [N/m²]; default: on a seabed (a fixed plane in a fluid facing up against
        the body's gravity) the body's wet weight over 1 % of its diameter
        (:func:`rancf.system.seabed.seabed_stiffness`), else a tenth of its Young's modulus.
    onset : float, optional
        Width ``d`` [m] of the pressure's smooth onset; default 1e-3 of each body's radius.
    damping : float
        Hunt–Crossley factor ``χ`` [s/m]: the pressure is ``k <-g> (1 + χ <-ġ>)`` while the
        point approaches the obstacle (``ġ < 0``), so impacts lose energy and nothing pulls.
    damping_normal : float
        Linear normal damping ``c`` per unit contact area [Pa s/m] while in contact, as
        MoorDyn's seabed ``cBot``: the force per length ``p - c D ġ`` (``D`` the tube's
        diameter, the contact width), never pulling.
    slip_velocity : float
        Regularization ``ε`` of the friction [m/s] (:mod:`rancf.system.contact`).
    name : str
    """

    kind: Literal["plane", "cylinder", "sphere"]
    point: Sequence[float] | None = None
    normal: Sequence[float] | None = None
    center: Sequence[float] | None = None
    radius: float | None = None
    axis: Sequence[float] | None = None
    body: str | None = None
    friction: float = 0.0
    stiffness: float | None = None
    onset: float | None = None
    damping: float = 0.0
    damping_normal: float = 0.0
    slip_velocity: float = SLIP_VELOCITY
    name: str = ""
    #: Its sensor kinds (module docstring).
    sensor_kinds: ClassVar[Mapping[str, SensorBuilder]] = {
        "contact_force": contact_force_reader,
        "touchdown": touchdown_reader,
    }

    def record(self, system: Any, rows: RecordRows | None = None, name: str = "") -> ObstacleRecord:
        """Its record (module docstring), its fields checked; ``name``: its name in the system
        (errors name it), default its own."""
        name = name or self.name or self.kind
        p, d, rad = _geometry(self, system.dim)
        body = -1
        if self.body is not None:
            b = system.bodies.get(self.body)
            if not isinstance(b, RigidBody):
                raise InputError(f"obstacles.{name}.body", self.body, "the name of a rigid body")
            body = system.rigid.index(b)
        for key, v in (
            ("friction", self.friction),
            ("damping", self.damping),
            ("damping_normal", self.damping_normal),
        ):
            _number(f"obstacles.{name}.{key}", v, 0.0, False)
        _number(f"obstacles.{name}.slip_velocity", self.slip_velocity, 0.0, True)
        for key, given in (("stiffness", self.stiffness), ("onset", self.onset)):
            if given is not None:
                _number(f"obstacles.{name}.{key}", given, 0.0, True)
        return ObstacleRecord(self.kind, body, vec3(p), vec3(d), float(rad))

    def sensors(self, system: Any) -> Sequence[str]:
        """Its contact columns: the force it exerts on the bodies, normal ``NAME_normal_x, _y[,
        _z]`` and friction ``NAME_friction_x ...`` [N], their moment about its point
        ``NAME_mz`` (3D ``NAME_mx, _my, _mz``) [N m], the contact length ``NAME_length`` and the
        largest penetration ``NAME_penetration`` [m] (``NAME``: its name in the system)."""
        name, dim = _system_name(system, self), system.dim
        cols = [f"{name}_{part}_{a}" for part in ("normal", "friction") for a in "xyz"[:dim]]
        cols += [f"{name}_m{a}" for a in ("z" if dim == 2 else "xyz")]
        return [*cols, f"{name}_length", f"{name}_penetration"]

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """Its contact columns at the coordinates ``y`` without velocities (no friction)
        (:func:`rancf.system.contact_states.contact_outputs`)."""
        from rancf.system.contact_states import contact_outputs

        c = contact_outputs(system, y)[_system_name(system, self)]
        values = [*c.normal, *c.friction, *np.atleast_1d(c.moment), c.length, c.penetration]
        return dict(zip(self.sensors(system), map(float, values), strict=True))


def _system_name(system: Any, ob: Obstacle) -> str:
    """The name of the obstacle ``ob`` in ``system`` (its own, or ``obstacleK``)."""
    k = next(k for k, o in enumerate(system.obstacles) if o is ob)
    return str(system.obstacle_names[k])


def _vec(key: str, v: Sequence[float] | None, dim: int, unit: bool = False) -> NDArray:
    a = np.asarray([] if v is None else v, dtype=float)
    if a.shape != (dim,) or not np.all(np.isfinite(a)) or (unit and not np.linalg.norm(a) > 0):
        what = "a nonzero vector" if unit else "a point"
        raise InputError(key, None if v is None else list(v), f"{what} of {dim} finite numbers")
    a = np.r_[a, np.zeros(3 - dim)]
    return a / np.linalg.norm(a) if unit else a


def _number(key: str, v: float | None, lo: float, strict: bool) -> float:
    ok = v is not None and np.isfinite(v) and (v > lo if strict else v >= lo)
    if not ok:
        raise InputError(key, v, f"a finite number {'>' if strict else '>='} {lo:g}")
    return float(v)  # type: ignore[arg-type]


def _geometry(ob: Obstacle, dim: int) -> tuple[NDArray, NDArray, float]:
    """(point, direction, radius) of an obstacle, 3 components each."""
    key = f"obstacles.{ob.name or ob.kind}"
    if ob.kind not in OBSTACLE_KINDS:
        raise InputError("obstacles.kind", ob.kind, f"one of {', '.join(OBSTACLE_KINDS)}")
    if ob.kind == "plane":
        return _vec(f"{key}.point", ob.point, dim), _vec(f"{key}.normal", ob.normal, dim, True), 0.0
    if ob.kind == "sphere" and dim == 2:
        raise InputError(f"{key}.kind", "sphere", 'a 3D system (in 2D a circle is "cylinder")')
    center = _vec(f"{key}.center", ob.center, dim)
    radius = _number(f"{key}.radius", ob.radius, 0.0, True)
    if ob.kind == "sphere":
        return center, np.array([0.0, 0.0, 1.0]), radius
    if dim == 2:
        if ob.axis is not None:
            raise InputError(f"{key}.axis", list(ob.axis), "none in 2D (a circle in the plane)")
        return center, np.array([0.0, 0.0, 1.0]), radius
    return center, _vec(f"{key}.axis", ob.axis, 3, True), radius
