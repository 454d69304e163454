"""Places: where supports, loads, joints, springs and sensors attach.

In a file with ``[[bodies]]``:

* ``"BODY:start"``, ``"BODY:end"``, ``"BODY:N"``: a node of a flexible body (``N`` counts from
  0, negative from the end; checked against the mesh when the model is built);
* ``"BODY"``: a rigid body's centre of mass, or a point mass;
* ``"BODY:POINT"``: a named point of a rigid body (its ``points`` table);
* ``"ground"``: the fixed frame (joints and springs).

In a file without ``[[bodies]]`` (one flexible body) a place is ``"start"``, ``"end"`` or a node
index, as always (and ``"ground"`` for joints and springs).

A shell (a surface ``[geometry]``) has edges ``"u0"``, ``"u1"``, ``"v0"``, ``"v1"`` and surface
points ``[u, v]`` (``"NAME:u0"``, ``"NAME:u,v"`` with ``[[bodies]]``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rancf.errors import InputError
from rancf.scenario.base import fail, shorten, show
from rancf.scenario.bodies import FlexibleBody, PointMass, RigidBody
from rancf.scenario.surface import is_surface
from rancf.system.places import GROUND, Place

__all__ = ["ResolvedPlace", "resolve_place", "ONE_BODY"]

#: The name of the one flexible body of a file without ``[[bodies]]``: parsing gives the file the
#: bodies form, that body's places resolve to it.
ONE_BODY = "body"


@dataclass(frozen=True)
class ResolvedPlace:
    """A place resolved against the scenario's bodies.

    Attributes
    ----------
    text : int or str
        The place as written.
    where : str
        ``"node"`` (of a flexible body), ``"center"`` (a rigid body's centre of mass or a point
        mass), ``"point"`` (a named point of a rigid body) or ``"ground"``.
    body : str or None
        The body's name (:data:`ONE_BODY` in a file without ``[[bodies]]``; None: the ground).
    node : int or None
        The node index (``"start"``: 0, ``"end"``: -1) of a ``"node"`` place.
    point : str or None
        The point's name of a ``"point"`` place.
    edge : str or None
        A shell's edge (``"u0"``, ``"u1"``, ``"v0"``, ``"v1"``) of an ``"edge"`` place.
    uv : tuple of float or None
        A shell's surface point ``(u, v)`` of a ``"surface"`` place.
    """

    text: Any
    where: str
    body: str | None = None
    node: int | None = None
    point: str | None = None
    edge: str | None = None
    uv: tuple[float, float] | None = None

    def system_place(self) -> Place:
        """The :class:`rancf.system.places.Place` of the system builder."""
        if self.where in ("edge", "surface"):
            raise InputError("at", self.text, "a place of a line or rigid body (not a shell's)")
        if self.where == "ground" or self.body is None:
            return GROUND
        return Place(self.body, self.node if self.where == "node" else self.point)


def _node(text: str) -> int | None:
    if text == "start":
        return 0
    if text == "end":
        return -1
    try:
        return int(text)
    except ValueError:
        return None


_SHELL_PLACE = (
    'a place of a shell is an edge ("u0", "u1", "v0", "v1") or a surface point [u, v] '
    "with 0 <= u, v <= 1"
)


def _uv(v: Any) -> tuple[float, float] | None:
    """``[u, v]`` (a list, or the text ``"u,v"``) as two numbers in [0, 1], else None."""
    if isinstance(v, str):
        try:
            v = [float(x) for x in v.split(",")]
        except ValueError:
            return None
    if not isinstance(v, list | tuple) or len(v) != 2:
        return None
    if not all(isinstance(x, int | float) and not isinstance(x, bool) for x in v):
        return None
    if not all(0.0 <= float(x) <= 1.0 for x in v):
        return None
    return float(v[0]), float(v[1])


def shell_place(key: str, v: Any, body: str, sub: Any) -> ResolvedPlace:
    """The place ``sub`` of the shell ``body`` (``v`` as written): an edge or a point."""
    if sub in ("u0", "u1", "v0", "v1"):
        return ResolvedPlace(v, "edge", body, edge=str(sub))
    uv = _uv(sub)
    if uv is None:
        raise fail(key, f"{_SHELL_PLACE}, got {show(v)}")
    return ResolvedPlace(v, "surface", body, uv=uv)


def resolve_place(
    key: str, v: Any, bodies: dict[str, Any] | None, ground: bool = False, shell: bool = False
) -> ResolvedPlace:
    """The :class:`ResolvedPlace` of ``v`` (of the key ``key``, relative to the table validated).

    Parameters
    ----------
    bodies : dict or None
        The bodies by name; None for a file without ``[[bodies]]``.
    ground : bool
        Whether ``"ground"`` is allowed (joints and springs).
    shell : bool
        The one body of a file without ``[[bodies]]`` is a shell: its places are edges and
        surface points (:func:`shell_place`); with ``[[bodies]]`` a shell's are ``"NAME:u0"``
        and ``"NAME:u,v"``.
    """
    if v == "ground":
        if not ground:
            raise fail(key, 'cannot be "ground" here (the ground does not move)')
        return ResolvedPlace(v, "ground")
    if bodies is None and shell:
        return shell_place(key, v, ONE_BODY, v)
    if isinstance(v, list):
        raise fail(key, f"a surface point [u, v] is a place of a shell, got {show(v)}")
    if bodies is None:
        if isinstance(v, int):
            return ResolvedPlace(v, "node", ONE_BODY, node=v)
        if v in ("start", "end"):
            return ResolvedPlace(v, "node", ONE_BODY, node=0 if v == "start" else -1)
        raise fail(key, f'must be "start", "end" or a node index, got {show(v)}')
    names = ", ".join(bodies)
    if isinstance(v, int):
        raise fail(
            key,
            f'must be "BODY:start", "BODY:end", "BODY:N", "BODY" or "BODY:POINT" '
            f"with [[bodies]] (bodies: {shorten(names)}), got {show(v)}",
        )
    name, _, sub = v.partition(":")
    body = bodies.get(name)
    if body is None:
        raise fail(key, f"names no body: {show(name)} (bodies: {shorten(names)})")
    if isinstance(body, FlexibleBody) and is_surface(body.geometry):
        return shell_place(key, v, name, sub)
    if isinstance(body, FlexibleBody):
        node = _node(sub)
        if node is None:
            raise fail(
                key,
                f'a place of the flexible body {show(name)} is "{name}:start", '
                f'"{name}:end" or "{name}:N" (a node index), got {show(v)}',
            )
        return ResolvedPlace(v, "node", name, node=node)
    if not sub:
        return ResolvedPlace(v, "center", name)
    if isinstance(body, PointMass):
        raise fail(key, f'the point mass {show(name)} is the place "{name}" itself, got {show(v)}')
    assert isinstance(body, RigidBody)
    if sub not in body.points:
        known = ", ".join(body.points) or "none"
        raise fail(
            key, f"the rigid body {show(name)} has no point {show(sub)} (its points: {known})"
        )
    return ResolvedPlace(v, "point", name, point=sub)
