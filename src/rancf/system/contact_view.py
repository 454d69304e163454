"""What contact reads of a system (:class:`ContactSystem`): the contact modules
(:mod:`rancf.system.contact`, :mod:`rancf.system.contact_states`) are used by the system, so
they see it through this protocol rather than importing it."""

from __future__ import annotations

from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["ContactSystem"]


class ContactSystem(Protocol):
    """What contact reads of a system (:class:`rancf.system.system.System`): it is built by the
    system, so it sees the system through this protocol rather than importing it."""

    dim: int
    bodies: dict[str, Any]
    rigid: list[Any]
    obstacles: tuple[Any, ...]
    obstacle_names: list[str]
    contact: Any

    def y_from_q(self, q: Any) -> NDArray[np.float64]: ...
