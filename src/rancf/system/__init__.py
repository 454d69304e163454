"""Systems of bodies: places, joints, springs, loads and their assembly (issue 18)."""

from rancf.system.parts import Joint, Load, Spring
from rancf.system.places import GROUND, Place
from rancf.system.system import System

__all__ = ["System", "Joint", "Spring", "Load", "Place", "GROUND"]
