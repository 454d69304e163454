"""The part classes of a system, and the sensor kinds they offer.

Every kind of :class:`~rancf.system.part.Part` is listed once in :data:`PARTS`; a run's sensors
find their kinds among their parts' classes, and a kind of a part the system lacks among these
(:func:`sensor_kinds`; its builder then names what is missing), so a new part brings its
sensors with it: its class in this list, its kinds in its own module.  It loads every part's
module: the sensors import it only for a kind the system's parts do not offer.
"""

from __future__ import annotations

from rancf.system.part import Part
from rancf.system.parts.contact_pair import BodyPair, ContactPair
from rancf.system.parts.distributed import DistributedLoad
from rancf.system.parts.flexible import FlexibleBody
from rancf.system.parts.fluid import FluidPart
from rancf.system.parts.joint import Joint
from rancf.system.parts.load import Load
from rancf.system.parts.obstacle import Obstacle
from rancf.system.parts.point_mass import PointMassPart
from rancf.system.parts.rigid import RigidBodyPart
from rancf.system.parts.spring import Spring
from rancf.system.parts.support import Support
from rancf.system.parts.winch import Winch
from rancf.system.readers import SensorBuilder

__all__ = ["PARTS", "sensor_kinds"]

#: The part classes, in the order of a system's parts.
PARTS: tuple[type[Part], ...] = (
    FlexibleBody,
    RigidBodyPart,
    PointMassPart,
    Support,
    Joint,
    Spring,
    Load,
    DistributedLoad,
    FluidPart,
    Winch,
    Obstacle,
    ContactPair,
    BodyPair,
)


def sensor_kinds() -> dict[str, SensorBuilder]:
    """Every sensor kind the part classes offer, by name (a kind two classes offer is one
    builder: a joint's and a support's ``reaction``)."""
    kinds: dict[str, SensorBuilder] = {}
    for part in PARTS:
        for name, build in part.sensor_kinds.items():
            if kinds.setdefault(name, build) is not build:
                raise ValueError(f"sensor kind {name!r} offered by two builders")
    return kinds
