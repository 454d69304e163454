"""Systems of bodies: places, joints, springs, loads, the fluid they are in and their assembly."""

from rancf.system.connections import Joint, Load, Spring
from rancf.system.contact import Obstacle
from rancf.system.contact_outputs import ContactState, contact_history, contact_outputs
from rancf.system.fluid import DistributedLoad, Fluid, Hydro, Waves
from rancf.system.places import GROUND, Place
from rancf.system.system import System, as_system
from rancf.system.winches import Winch

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
