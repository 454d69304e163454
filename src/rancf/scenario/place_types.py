"""The types of places as a scenario writes them: one place, and a pair of places."""

from __future__ import annotations

from typing import Annotated, Any

import numpy as np
from pydantic import BeforeValidator, Field

from rancf.scenario.base import fail, show


def _place(v: Any) -> Any:
    if isinstance(v, np.integer):
        v = int(v)
    if isinstance(v, list | tuple) and len(v) == 2:
        if all(isinstance(x, int | float) and not isinstance(x, bool) for x in v):
            return [float(x) for x in v]
    if isinstance(v, bool) or not isinstance(v, int | str) or v == "":
        raise fail(
            "",
            f'must be a place ("start", "end", a node index, "BODY:..."; a shell\'s edge "u0" '
            f"or point [u, v]), got {show(v)}",
        )
    return v


#: A place as written: ``"start"``, ``"end"``, a node index, ``"ground"`` or ``"BODY[:WHERE]"``
#: (checked against the scenario's bodies by :mod:`rancf.scenario.places`); a shell's edge
#: ``"u0"`` or surface point ``[u, v]``.
PlaceValue = Annotated[
    int | str | list[float],
    BeforeValidator(_place),
    Field(
        description='"start", "end" or a node index (negative from the end) in a one-body file; '
        '"BODY:start", "BODY:end", "BODY:N", "BODY" (a rigid body\'s centre of mass or a point '
        'mass), "BODY:POINT" (a named point of a rigid body) or "ground" with [[bodies]]; a '
        'shell: an edge "u0", "u1", "v0", "v1" or a surface point [u, v] in [0, 1]^2 ("BODY:u0", '
        '"BODY:u,v" with [[bodies]])'
    ),
]


def _pair(v: Any) -> Any:
    if isinstance(v, tuple):
        v = list(v)
    if not isinstance(v, list) or len(v) != 2:
        raise fail("", f"must be two places [A, B], got {show(v)}")
    return v


#: Two places ``[A, B]``.
PlacePair = Annotated[list[PlaceValue], Field(min_length=2, max_length=2), BeforeValidator(_pair)]
