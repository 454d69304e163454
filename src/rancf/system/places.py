"""Places: where joints, springs, supports and loads attach (``"BODY:end"``, ``"crank:tip"``).

Spelling: ``"BODY:start"``, ``"BODY:end"``, ``"BODY:N"`` (node index, negative from the
end) on a flexible body; ``"BODY"`` (a rigid body's centre of mass or a point mass);
``"BODY:POINT"`` (a named point of a rigid body); ``"ground"``.  In a one-body system
``"start"``, ``"end"`` and node indices keep working.
"""

from __future__ import annotations

from dataclasses import dataclass

from rancf.errors import InputError

__all__ = ["Place", "GROUND"]


@dataclass(frozen=True)
class Place:
    """A place: ``body`` (None: the ground) and ``at`` (a node index, ``"start"``/``"end"``, a
    point name, or None: the body itself)."""

    body: str | None
    at: int | str | None = None

    @classmethod
    def parse(cls, spec: Place | str | int, single: str | None = None) -> Place:
        """A place from its spelling; ``single``: the name of the only body (then "start",
        "end" and node indices need no body name)."""
        if isinstance(spec, Place):
            return spec
        if isinstance(spec, bool):
            raise InputError("place", spec, 'a place like "BODY:end", "BODY:POINT" or "ground"')
        if isinstance(spec, int):
            if single is None:
                raise InputError("place", spec, 'a place with its body, e.g. "cable:3"')
            return cls(single, spec)
        if not isinstance(spec, str) or not spec:
            raise InputError("place", spec, 'a place like "BODY:end", "BODY:POINT" or "ground"')
        if spec == "ground":
            return cls(None)
        if spec in ("start", "end") and single is not None:
            return cls(single, spec)
        body, sep, at = spec.partition(":")
        if not sep:
            return cls(body)
        try:
            return cls(body, int(at))
        except ValueError:
            return cls(body, at)

    def body_name(self) -> str:
        """The body of a place on a body (the ground has none)."""
        if self.body is None:
            raise InputError("place", "ground", "a place on a body")
        return self.body

    def node(self) -> int:
        """The node index of a resolved place on a flexible body."""
        if not isinstance(self.at, int):
            raise InputError("place", str(self), "a node of a flexible body")
        return self.at

    def point_name(self) -> str | None:
        """The point (None: the centre of mass) of a place on a rigid body."""
        if isinstance(self.at, int):
            raise InputError("place", str(self), "a point of a rigid body")
        return self.at

    def __str__(self) -> str:
        if self.body is None:
            return "ground"
        return self.body if self.at is None else f"{self.body}:{self.at}"


GROUND = Place(None)
