"""Supports of flexible bodies in a system, a :class:`~rancf.system.part.Part`.

A flexible body's supports are its model's own (held coordinates, :mod:`rancf.bodies.properties`
``Support``).  In a system, a support with a ``motion`` makes its held position follow the time
function: the core's prescribed records, one per held position coordinate, each the
coordinate's installed value plus that component of the motion (``src/cpp/system/system.hpp``).
A support without a motion needs no record.  Its reaction is the held rows of the balance
residual (:mod:`rancf.bodies.reactions`), the outputs read every support's at once; a ``reaction``
sensor reads a support's or a joint's columns (:func:`reaction_reader`).  A clamp
whose direction turns (a scenario's ``rotation``) is no held support: it is a fixed
:class:`~rancf.system.parts.joint.Joint` to a turning ground frame
(``docs/derivations/clamp-paths.md``).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.reactions import has_moment, support_label, support_reactions
from rancf.bodies.support_kinds import support_kind
from rancf.errors import InputError
from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.kernels.records import PrescribedRecord
from rancf.system.readers import (
    Block,
    NamedReader,
    Reader,
    SensorBuilder,
    SensorHost,
    sensor_places,
)

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["Support", "reaction_reader", "supports_of"]


def _columns_reader(name: str, label: str, columns: Sequence[str], cols: slice) -> Reader:
    """A reader of the reaction columns ``cols``, named ``columns`` (``LABEL_SUFFIX``) by their
    part: as the sensor ``name``'s ``NAME_SUFFIX``, a force's ``fx`` as ``x``."""
    suffixes = [c[len(label) + 1 :] for c in columns]
    names = [f"{name}_{x[1:] if x[:1] == 'f' and len(x) == 2 else x}" for x in suffixes]

    def read(blk: Block) -> NDArray:
        return blk[3]["r"][:, cols]

    return NamedReader(read, names)


def reaction_reader(host: SensorHost, sen: Any) -> Reader:
    """A ``reaction`` sensor: the reaction columns of the joint ``sen.joint`` or of the support
    at its place (its Part's columns in ``reactions.csv``,
    :meth:`~rancf.system.part.Part.sensors`), renamed for the sensor: ``LABEL_fx`` as
    ``NAME_x``, ``LABEL_mz`` as ``NAME_mz``, ``LABEL_s`` as ``NAME_s``."""
    out, sy = host.out, host.system
    if getattr(sen, "joint", None) is not None:
        try:
            cols = out.joint_columns(sen.joint)
        except KeyError:
            names = [j.name for j in sy.joints if j.name]
            allowed = f"a joint: {', '.join(names) or 'none named'}"
            raise InputError(f"sensors.{sen.name}.joint", sen.joint, allowed) from None
        joint = next(j for j in sy.joints if j.label(sy) == sen.joint)
        return _columns_reader(sen.name, joint.label(sy), joint.sensors(sy), cols)
    p = host.place(sen, sensor_places(sen)[0])
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


@dataclass(frozen=True)
class Support:
    """The support number ``index`` of the flexible body ``body``, at its node ``node`` (module
    docstring)."""

    body: str
    index: int
    node: int
    #: Its place as the user wrote it (its output columns' label); None: ``BODY:AT``.
    label_as: int | str | None = None
    #: Its sensor kinds: its ``reaction`` (:func:`reaction_reader`).
    sensor_kinds: ClassVar[Mapping[str, SensorBuilder]] = {"reaction": reaction_reader}

    @property
    def name(self) -> str:
        """``BODY:NODE``: its body and node."""
        return f"{self.body}:{self.node}"

    def held(self, system: Any) -> Any:
        """The model's support (:class:`rancf.bodies.properties.Support`)."""
        return system.bodies[self.body].supports[self.index]

    def record(self, system: Any, rows: RecordRows) -> tuple[PrescribedRecord, ...]:
        """The core's prescribed records of a moving support (its motion registered in
        ``rows``); none for a support that stays."""
        b, sup = system.bodies[self.body], self.held(system)
        if sup.motion is None:
            return ()
        if not support_kind(sup.kind).moves:
            raise InputError("supports.motion", sup.kind, "a pin or clamp (moving supports)")
        if sup.motion.size != system.dim:
            raise InputError("supports.motion", sup.motion.size, f"{system.dim} components")
        k = rows.tf(sup.motion)
        base = b.node_base(b.check_node(sup.node, "supports.at"))
        start = system.offsets[self.body] + base
        return tuple(
            PrescribedRecord(start + i, k, i, float(b.y_installed[base + i]))
            for i in range(system.dim)
        )

    def label(self, system: Any) -> str:
        """Its columns' label: its place as the user wrote it, else ``BODY:AT`` (``AT``:
        ``start``, ``end`` or ``nodeK``)."""
        if self.label_as is not None:
            return support_label(self.label_as)
        b = system.bodies[self.body]
        k = self.node % b.n_nodes
        at = "start" if k == 0 else "end" if k == b.n_nodes - 1 else f"node{k}"
        return f"{self.body}:{at}"

    def sensors(self, system: Any) -> Sequence[str]:
        """Its reaction columns: the force it exerts on its body ``LABEL_fx, _fy[, _fz]``, then
        its moment where it carries one (a clamp, a rod's support): ``LABEL_mz`` (planar) or
        ``LABEL_mx, _my, _mz``."""
        lab, dim = self.label(system), system.dim
        cols = [f"{lab}_f{a}" for a in "xyz"[:dim]]
        if has_moment(system.bodies[self.body], self.held(system).kind):
            cols += [f"{lab}_mz"] if dim == 2 else [f"{lab}_m{a}" for a in "xyz"]
        return cols

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """Its reaction at the static state ``(y, λ)``, the loads at the factor ``t``: the held
        rows of the static residual (module docstring)."""
        res = np.empty(system.n + system.m)
        y = np.ascontiguousarray(y, dtype=float)
        lam = np.ascontiguousarray(lam, dtype=float)
        static = ResidualOptions(0.0, min(float(t), 1.0), amplitude=True, dynamic=False)
        system.core.residual(ResidualPoint(y, lam, res), static)
        b, sl = system.bodies[self.body], system.body_slice(self.body)
        r = support_reactions(b, y[sl], res[sl])[self.index]
        values = [*r.force, *(() if r.moment is None else r.moment)]
        return dict(zip(self.sensors(system), map(float, values), strict=True))


def supports_of(system: Any) -> list[Support]:
    """The supports of the system's flexible bodies, body by body in file order."""
    return list(system.supports)
