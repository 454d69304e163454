"""Systems of bodies: places, joints, springs, loads, the fluid they are in and their assembly.

The contact, fluid and winch names are loaded on first use: a system without them (and a run of
it) does not import their modules.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from rancf.system.connections import Joint, Load, Spring
from rancf.system.places import GROUND, Place
from rancf.system.system import System, as_system

if TYPE_CHECKING:
    from rancf.system.contact import Obstacle
    from rancf.system.contact_states import ContactState, contact_history, contact_outputs
    from rancf.system.fluid import DistributedLoad, Fluid, Hydro, Waves
    from rancf.system.winches import Winch

#: Name loaded on first use -> module that defines it.
_LAZY = {
    "Obstacle": "rancf.system.contact",
    "ContactState": "rancf.system.contact_states",
    "contact_outputs": "rancf.system.contact_states",
    "contact_history": "rancf.system.contact_states",
    "Fluid": "rancf.system.fluid",
    "Waves": "rancf.system.fluid",
    "Hydro": "rancf.system.fluid",
    "DistributedLoad": "rancf.system.fluid",
    "Winch": "rancf.system.winches",
}

__all__ = [
    "System",
    "Joint",
    "Spring",
    "Load",
    "Place",
    "GROUND",
    "Obstacle",
    "ContactState",
    "contact_outputs",
    "contact_history",
    "as_system",
    "Fluid",
    "Waves",
    "Hydro",
    "DistributedLoad",
    "Winch",
]


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rancf.system' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
