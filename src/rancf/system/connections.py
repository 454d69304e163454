"""Joints, springs and loads of a system: Parts (:mod:`rancf.system.part`), one module a kind in
:mod:`rancf.system.parts` (:mod:`~rancf.system.parts.joint`, :mod:`~rancf.system.parts.spring`,
:mod:`~rancf.system.parts.load`), gathered here.

The joint kinds are described in :mod:`rancf.system.parts.joint` (docs/derivations/systems.md
section 3).
"""

from __future__ import annotations

from rancf.system.parts.joint import JOINT_KINDS, Joint
from rancf.system.parts.load import Load
from rancf.system.parts.spring import Spring

__all__ = ["Joint", "Spring", "Load", "JOINT_KINDS"]
