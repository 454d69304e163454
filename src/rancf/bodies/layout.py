"""What every consumer of a flexible body reads first: its node layout (a protocol that
:class:`rancf.bodies.flexible.Model` satisfies)."""

from __future__ import annotations

from typing import Protocol

from rancf.bodies.families import ElementFamily

__all__ = ["BodyLayout"]


class BodyLayout(Protocol):
    """The node layout of a flexible body: dimension, coordinates per node, elements, nodes and
    the element kind, and its family (:mod:`rancf.bodies.families`: what differs between the
    kinds is asked of it, not of the kind's name)."""

    # read-only: implementations may narrow a member's type
    @property
    def dim(self) -> int: ...

    @property
    def dpn(self) -> int: ...

    @property
    def n_el(self) -> int: ...

    @property
    def n_nodes(self) -> int: ...

    @property
    def element(self) -> str: ...

    @property
    def family(self) -> ElementFamily: ...
