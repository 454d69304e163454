"""Pairs in contact, :class:`~rancf.system.part.Part`\\ s: a flexible body and an obstacle
(:class:`ContactPair`), two flexible bodies (:class:`BodyPair`; the same twice: self-contact).

Their records are the contact law's coefficients per pair as the core's contact
(``src/cpp/contact/contact.hpp``, ``src/cpp/contact/body_contact.hpp``) takes them; the law and
its defaults are in :mod:`rancf.system.contact`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from rancf.kernels.contact_records import BodyPairRecord, ContactPairRecord
from rancf.system.part import NoOutputs
from rancf.system.parts.obstacle import (
    ONSET_FACTOR,
    SLIP_VELOCITY,
    STIFFNESS_FACTOR,
    Obstacle,
    _geometry,
)
from rancf.system.seabed import seabed_stiffness

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["ContactPair", "BodyPair"]


@dataclass(frozen=True)
class ContactPair(NoOutputs):
    """The flexible body ``body`` on the obstacle ``obstacle`` (called ``obstacle_name`` in the
    system, its ``index``-th)."""

    body: str
    obstacle: Obstacle
    obstacle_name: str
    index: int = 0

    @property
    def name(self) -> str:
        """``BODY/OBSTACLE``."""
        return f"{self.body}/{self.obstacle_name}"

    def record(self, system: Any, rows: RecordRows | None = None) -> ContactPairRecord:
        """Its law: the obstacle's coefficients; the stiffness by default a seabed's
        (:func:`rancf.system.seabed.seabed_stiffness`) or ``STIFFNESS_FACTOR E``, the onset
        ``ONSET_FACTOR`` of the body's radius, the normal damping per area times the contact
        width ``D`` (:mod:`rancf.system.contact`)."""
        ob = self.obstacle
        k = ob.stiffness
        if k is None:
            k = seabed_stiffness(system, self.body, ob, _geometry(ob, system.dim)[1])
        if k is None:
            k = STIFFNESS_FACTOR * system.bodies[self.body].material.youngs_modulus
        rt = system.bodies[self.body].section.radius
        onset = ONSET_FACTOR * rt if ob.onset is None else ob.onset
        cn = ob.damping_normal * 2.0 * rt  # per area to per length: the contact width D
        flex = system.flex.index(system.bodies[self.body])
        return ContactPairRecord(
            flex, self.index, k, onset, ob.damping, ob.friction, ob.slip_velocity, cn
        )


@dataclass(frozen=True)
class BodyPair:
    """The flexible bodies ``a`` and ``b`` in contact (the same: self-contact), with the Coulomb
    coefficient ``friction``."""

    a: str
    b: str
    friction: float = 0.0
    #: No sensor kinds of its own (its forces: its bodies' contact outputs).
    sensor_kinds: ClassVar[Mapping[str, Any]] = {}

    @property
    def name(self) -> str:
        """``A/B``."""
        return f"{self.a}/{self.b}"

    def record(self, system: Any, rows: RecordRows | None = None) -> BodyPairRecord:
        """Its law: the stiffness ``STIFFNESS_FACTOR E / 2`` of the softer (two sections in
        series), the onset ``ONSET_FACTOR`` of the thinner radius, regularized by
        ``SLIP_VELOCITY``."""
        ma, mb = system.bodies[self.a], system.bodies[self.b]
        k = 0.5 * STIFFNESS_FACTOR * min(ma.material.youngs_modulus, mb.material.youngs_modulus)
        onset = ONSET_FACTOR * min(ma.section.radius, mb.section.radius)
        a, b = system.flex.index(ma), system.flex.index(mb)
        return BodyPairRecord(a, b, k, onset, self.friction, SLIP_VELOCITY)

    def sensors(self, system: Any) -> Sequence[str]:
        """Its contact columns: the total contact force ``A_B_contact_force`` [N] (the sum of
        the pressures' magnitudes) and the largest penetration ``A_B_penetration`` [m]."""
        return (f"{self.a}_{self.b}_contact_force", f"{self.a}_{self.b}_penetration")

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """Its contact columns at the coordinates ``y`` (``src/cpp/contact/body_contact.hpp``)."""
        k = next(k for k, p in enumerate(system.contact_parts) if p is self) - len(
            system.contact_pairs
        )
        out = np.empty(3 * len(system.body_contacts))
        system.contact.body_outputs(np.ascontiguousarray(y, dtype=float), out)
        values = (float(out[3 * k + 2]), max(0.0, -float(out[3 * k])))
        return dict(zip(self.sensors(system), values, strict=True))
