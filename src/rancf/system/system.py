"""A system: flexible bodies, rigid bodies and point masses, joints, springs and loads, assembled
into the compiled core's :class:`rancf.kernels._core.System` (``src/cpp/system/system.hpp``).

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
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.closure import closure_terms
from rancf.bodies.flexible import Model
from rancf.errors import InputError
from rancf.kernels.records import PlaceRecord, SystemModel, vec3
from rancf.system.connections import Joint, Load, Spring
from rancf.system.core_data import PlaceFrames, body_parts, build_core
from rancf.system.part import Part
from rancf.system.parts.flexible import FlexibleBody
from rancf.system.places import Place
from rancf.system.record_rows import RecordRows
from rancf.system.sliding import (
    sliding_records,
    sliding_starts,
    start_multipliers,
)
from rancf.system.stack import Body, BodyStack

if TYPE_CHECKING:  # imported where a system has them: a run without them loads none
    from rancf.system.contact import Obstacle
    from rancf.system.fluid import Fluid, Hydro
    from rancf.system.parts.distributed import DistributedLoad
    from rancf.system.parts.winch import Winch

__all__ = ["System", "Body", "as_system"]

#: Gauss points per element at which contact is evaluated (default; :mod:`rancf.system.contact`).
CONTACT_POINTS = 8


class System(BodyStack):
    """Bodies, joints, springs and loads (module docstring); the bodies' coordinates and places
    as in :class:`rancf.system.stack.BodyStack`.

    Parameters
    ----------
    bodies : mapping name -> Model | RigidBody | PointMass
    joints, springs, loads : sequences of :class:`Joint`, :class:`Spring` (or any spring
        :class:`~rancf.system.part.Part`, e.g. a :class:`~rancf.system.parts.spring.SpringLaw`),
        :class:`Load`
    gravity : ``(dim,)``, optional
        On rigid bodies and point masses.
    damping : float
        Mass-proportional damping ``c`` of every body [1/s] (flexible bodies: their model's is
        ignored).
    stiffness_damping : float
        Stiffness-proportional damping ``β`` of the flexible bodies [s]: the force ``β K_T(y) v``
        (Rayleigh: ``C = c M + β K_T``, modal damping ratios ``c / 2ω + β ω / 2``).
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
    winches : sequence of :class:`rancf.system.winches.Winch`
        Cables paid out or reeled in at an end (:mod:`rancf.system.winches`).
    observe : sequence of places
        Places on bodies whose position and frame outputs read (:meth:`place_state`).
    fluid : :class:`rancf.system.fluid.Fluid`, optional
        The fluid the bodies are in; ``hydro`` maps flexible bodies to their coefficients
        (:class:`~rancf.system.fluid.Hydro`; bodies without them feel no fluid).
    distributed : sequence of :class:`~rancf.system.parts.distributed.DistributedLoad`
        Forces per length on flexible bodies.
    horizon : float, optional
        The end of the runs [s]: time functions given as Python callables are sampled on
        ``[0, horizon]`` (a cubic table of 2001 points, :meth:`TimeFunction.sampled`) for the
        compiled loop; required when there are such functions.

    Attributes
    ----------
    model : :class:`rancf.kernels.records.SystemModel`
        The one record the core was built from, once: the bodies' and every part's records
        (places, joints, springs, loads, time functions, prescribed motions, linear rows, the
        fluid, contact, winches, sliding bodies; :mod:`rancf.kernels.records`).
    """

    drums: dict[str, int]  #: each driven drum's coordinate (rancf.system.winches.add_drums)

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
        fluid: Fluid | None = None,
        hydro: Mapping[str, Hydro] | None = None,
        distributed: Sequence[DistributedLoad] = (),
        winches: Sequence[Winch] = (),
        stiffness_damping: float = 0.0,
    ) -> None:
        super().__init__(bodies)
        self.gravity = (
            np.zeros(3) if gravity is None else np.r_[np.asarray(gravity, float), 0.0][:3]
        )
        if gravity is not None and np.asarray(gravity).size != self.dim:
            raise InputError("loads.gravity", list(np.asarray(gravity)), f"{self.dim} components")
        self._check_gravity()
        if not (np.isfinite(damping) and damping >= 0):
            raise InputError("damping.mass_proportional", damping, "a finite number >= 0")
        self.damping = float(damping)
        if not (np.isfinite(stiffness_damping) and stiffness_damping >= 0):
            raise InputError(
                "damping.stiffness_proportional", stiffness_damping, "a finite number >= 0"
            )
        self.stiffness_damping = float(stiffness_damping)
        self.horizon = horizon
        #: One line each on an impulsive start (a scenario's, :attr:`Scenario.warnings`).
        self.start_warnings: tuple[str, ...] = ()
        self.joints, self.springs, self.loads = tuple(joints), tuple(springs), tuple(loads)
        #: The bodies as Parts, in the order of ``y`` (flexible bodies, then rigid bodies and
        #: point masses), and the flexible bodies' supports.
        self.body_parts = body_parts(self.names, self.bodies)
        flexible = [p for p in self.body_parts if isinstance(p, FlexibleBody)]
        self.supports = [sup for p in flexible for sup in p.supports()]
        #: The point loads: the system's, then the flexible bodies' with a time function.
        self.point_loads = [*self.loads, *(ld for p in flexible for ld in p.loads())]
        rows = RecordRows(horizon)
        self._place_index: dict[Place, int] = {}
        records: dict[str, Any] = {  # each Part's record (system.part)
            "prescribed": [r for sup in self.supports for r in sup.record(self, rows)],
            "springs": [s.record(self, rows) for s in springs],
            "loads": [ld.record(self, rows) for ld in self.point_loads],
            "linear": closure_terms(self.names, self.flex, self.offsets),
        }
        self.fluid, self.hydro = fluid, dict(hydro or {})
        self.fluid_part: Part | None = None
        if fluid is not None or self.hydro or distributed:  # else nothing of the fluid loaded
            from rancf.system.parts.fluid import FluidPart

            self.fluid_part = FluidPart(fluid, self.hydro, tuple(distributed))
            in_fluid = self.fluid_part.record(self, rows)
            if in_fluid is not None:
                records["fluid"], records["lines"] = in_fluid
        for spec in observe:
            p = self.resolve(spec)
            if p.body is None:
                raise InputError("place", "ground", "a place on a body")
            self.place_index(p, rows)
        self._frames: list[tuple[NDArray, NDArray]] = []
        self._place_frames: PlaceFrames | None = None  # the bodies alone (reference_frames)
        records["joints"] = [j.record(self, rows) for j in joints]
        self.winches = tuple(winches)
        self.winch_lengths: dict[str, Any] = {}
        if self.winches:
            from rancf.system.winches import winch_functions

            self.winch_lengths = winch_functions(self, self.winches)
        records["winches"] = [w.record(self, rows) for w in self.winches]
        self.obstacles = tuple(obstacles)
        self.body_contacts, self.contact_points = [(a, b) for a, b in body_contacts], contact_points
        self.contact_parts: list[Part] = []  # the pairs in contact (body-obstacle, body-body)
        self.obstacle_names: list[str] = []
        self.contact_pairs: list[tuple[str, str]] = []
        if self.obstacles or contacts or body_contacts:
            from rancf.system.contact import build_contact

            built = build_contact(
                self, self.obstacles, contacts, contact_points, body_contacts, body_friction
            )
            records["contact"], self.obstacle_names = built.record, built.obstacle_names
            self.contact_parts = [*built.pairs, *built.body_pairs]
            self.contact_pairs = [(p.body, p.obstacle_name) for p in built.pairs]
        records["sliding"] = sliding_records(self, self.joints)
        # the one record the core is built from (the class docstring's ``model``)
        self.model = self._model(**rows.fields(**records))
        self.core = build_core(self.model)  # once, every part
        self.contact: Any = self.core.contact  # the core's Contact (from model.contact), or None
        self.m = int(self.core.m)
        self.joint_rows = list(self.core.joint_rows)
        self.drums = {}
        if self.winches:
            from rancf.system.winches import add_drums

            add_drums(self, self.winches)
        sliding_starts(self)
        self._check_reference()

    @property
    def parts(self) -> list[Part]:
        """Every Part of the system, in the order of their records and output columns: the
        bodies, supports, springs, point loads, the fluid, joints, winches, obstacles and the
        pairs in contact."""
        return self.labelled_parts()

    def labelled_parts(
        self, labels: Mapping[str, Sequence[int | str] | None] | None = None
    ) -> list[Part]:
        """:attr:`parts`, the supports' columns labelled by ``labels`` (per flexible body, the
        supports' places as the user wrote them; default ``BODY:AT``)."""
        supports = self.supports
        if labels:
            flexible = [p for p in self.body_parts if isinstance(p, FlexibleBody)]
            supports = [sup for p in flexible for sup in p.supports(labels.get(p.name))]
        fluid = [] if self.fluid_part is None else [self.fluid_part]
        return [
            *self.body_parts,
            *supports,
            *self.springs,
            *self.point_loads,
            *fluid,
            *self.joints,
            *self.winches,
            *self.obstacles,
            *self.contact_parts,
        ]

    def _check_gravity(self) -> None:
        """A flexible body's weight comes from its model's ``gravity``, a rigid body's from the
        system's: a model with no gravity of its own in a system with gravity gets one warning
        line (its weight is left out); an explicit model gravity is taken as meant."""
        if not self.gravity.any():
            return
        for name, b in zip(self.names, self.flex, strict=False):
            if b.gravity is None:
                warnings.warn(
                    f"rancf: body {name!r} has no gravity of its own, so its weight "
                    f"is left out of the system's gravity "
                    f"{self.gravity[: self.dim].tolist()}: give its Model the same "
                    "gravity (or gravity=[0, ...] to mean it)",
                    stacklevel=3,
                )

    def _check_reference(self) -> None:
        """Every joint holds in the reference configuration at t = 0 (positions to 1e-9 of the
        system's size; an orientation holds by construction): else one line naming the joint
        and how far apart its places are."""
        g = np.empty(self.m)
        self.core.constraints(self.y0, 0.0, g, start_multipliers(self))
        for k, j in enumerate(self.joints):
            gap = j.reference_gap(g[self.joint_rows[k] :], self.dim)
            if not gap <= 1e-9 * self.size:
                name = j.name or f"joints[{k}]"
                raise InputError(
                    f"{name}.between",
                    [str(x) for x in j.between],
                    f"places that coincide in the reference configuration (they are "
                    f"{gap:.4g} m apart; move the bodies, or the points, so they meet)",
                )

    # ---------------------------------------------------------------- places
    def place_index(
        self,
        p: Place,
        rows: RecordRows,
        ground_point: NDArray | None = None,
        motion: int = -1,
        rotation: int = -1,
    ) -> int:
        """The index of the record of the place ``p`` (resolved); the ground: at
        ``ground_point``, moved by the time function ``motion``, its frame turned by
        ``rotation``."""
        if p.body is None:
            assert ground_point is not None  # the callers give the ground's point
            point = np.zeros(3)
            point[: self.dim] = ground_point[: self.dim]
            ground = PlaceRecord("ground", point=vec3(point), motion=motion, rotation=rotation)
            return rows.place(ground, lambda: ground)
        self._place_index[p] = rows.place(p, lambda: self.place_record(p))
        return self._place_index[p]

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

    def place_pair(
        self, between: Sequence, rows: RecordRows, motion: int = -1, rotation: int = -1
    ) -> tuple[int, int]:
        if len(between) != 2:
            raise InputError("between", list(between), "two places")
        a, b = (self.resolve(x) for x in between)
        if a.body is None and b.body is None:
            raise InputError("between", [str(a), str(b)], "at least one place on a body")
        if a.body is None:  # the body's place first
            a, b = b, a
        gp = self.reference_position(a)
        return self.place_index(a, rows), self.place_index(b, rows, gp, motion, rotation)

    # ---------------------------------------------------------------- parts
    def reference_frames(self, rows: RecordRows) -> list[tuple[NDArray, NDArray]]:
        """``(position, frame rows)`` of every place registered in ``rows`` so far, in the
        reference configuration (:class:`rancf.system.core_data.PlaceFrames`; the places added
        since the last call only): what joints measure their orientation data in."""
        done = len(self._frames)
        if done < len(rows.places):  # the new places only
            if self._place_frames is None:
                self._place_frames = PlaceFrames(self._model())
            self._frames += self._place_frames(rows.places[done:], rows.tfs)
        return self._frames

    def _model(self, **records: Any) -> SystemModel:
        """The model record of the bodies (their Parts' records) with the parts' ``records``
        (fields of :class:`~rancf.kernels.records.SystemModel` by name)."""
        return SystemModel(
            dim=self.dim,
            models=tuple(p.record(self) for p in self.body_parts if isinstance(p, FlexibleBody)),
            rigid=tuple(p.record(self) for p in self.body_parts if not isinstance(p, FlexibleBody)),
            y_ref=np.ascontiguousarray(self.y0, dtype=float),
            gravity=vec3(self.gravity),
            damping=self.damping,
            stiffness_damping=self.stiffness_damping,
            **records,
        )

    # ---------------------------------------------------------------- coordinates
    @property
    def has_contact(self) -> bool:
        """Whether the system has contact (obstacles or flexible bodies touching each other)."""
        return self.contact is not None

    def energies(self, y: NDArray, v: NDArray, t: float = 0.0) -> tuple[float, float, float]:
        """Kinetic, strain (with springs) and gravitational energy (zero at the reference) at
        time ``t`` (winches: their lengths at ``t``)."""
        return self.core.energies(np.asarray(y, float), np.asarray(v, float), float(t))


def as_system(model: Model | System) -> System:
    """The system every analysis solves: a flexible body (:class:`~rancf.bodies.flexible.Model`)
    becomes the system of that one body, named ``"body"`` as in a scenario file without
    ``[[bodies]]``, with its damping; a system is itself.  The one front of the one-body API."""
    if isinstance(model, System):
        return model
    return System({"body": model}, damping=model.damping)
