"""The checks of a scenario that need several of its tables: one body or ``[[bodies]]``, the
dimension shared by all bodies and vectors, places against the bodies, names, and which keys
apply to which bodies (rod-only keys, moments, twist sensors, fixed joints).

Each check raises :func:`~rancf.scenario.base.fail` with the full key (``supports[1].position``,
``joints[0].between[1]``).  Node indices are checked against the mesh later, when the model is
built (:mod:`rancf.scenario.build`).
"""

from __future__ import annotations

from typing import Any

from pydantic_core import PydanticCustomError

from rancf.bodies.families import family, framed
from rancf.scenario.base import fail, shorten, show, under
from rancf.scenario.bodies import FlexibleBody, RigidBody
from rancf.scenario.places import ResolvedPlace, resolve_place
from rancf.scenario.section import check_flexible
from rancf.scenario.shell_checks import check_shell_uses
from rancf.scenario.surface import is_surface
from rancf.scenario.time_functions import time_size
from rancf.scenario.view import ScenarioView

__all__ = ["check_scenario"]

_FLEX_TABLES = ("geometry", "mesh", "section", "material")


def _size(key: str, v: Any, dim: int) -> None:
    if v is not None and len(v) != dim:
        raise fail(key, f"must be a list of {dim} numbers, got {show(v)}")


class _Context:
    """The scenario's bodies by name (None: one body) and its dimension."""

    def __init__(self, sc: ScenarioView) -> None:
        self.sc = sc
        self.bodies: dict[str, Any] | None = None
        if sc.bodies:
            self.bodies = {}
            for i, b in enumerate(sc.bodies):
                if b.name == "ground" or b.name in self.bodies:
                    raise fail(
                        f"bodies[{i}].name", f'{show(b.name)} is used twice or reserved ("ground")'
                    )
                self.bodies[b.name] = b
        self.dim = self._dim()
        self.shell = self.bodies is None and is_surface(sc.geometry)

    def _dim(self) -> int:
        sc = self.sc
        if self.bodies is None:
            for k in _FLEX_TABLES:
                if sc[k] is None:
                    raise fail(k, "required table is missing")
            try:
                check_flexible(sc.geometry, sc.mesh, sc.section, sc.material, sc["form"])
            except PydanticCustomError as exc:
                raise under("", exc) from None
            return int(sc.geometry.dim)
        for k in (*_FLEX_TABLES, "hydro", "form"):
            if sc[k] is not None:
                raise fail(
                    k,
                    f"does not apply with [[bodies]]: give it in each flexible body ([bodies.{k}])",
                )
        dims = [b.dim for b in sc.bodies]
        for i, d in enumerate(dims):
            if d != dims[0]:
                what = "geometry" if isinstance(sc.bodies[i], FlexibleBody) else "position"
                raise fail(
                    f"bodies[{i}].{what}",
                    f"is {d}D but bodies[0] is {dims[0]}D: all bodies are planar or all spatial",
                )
        return dims[0]

    def place(self, key: str, v: Any, ground: bool = False) -> ResolvedPlace:
        return resolve_place(key, v, self.bodies, ground, self.shell)

    def element(self, p: ResolvedPlace) -> str | None:
        """The element kind at a node place; ``"rigid"``, ``"mass"``; None for the ground."""
        if p.where == "ground":
            return None
        b = self.sc if self.bodies is None else self.bodies[str(p.body)]
        if self.bodies is None or isinstance(b, FlexibleBody):
            return "shell" if is_surface(b.geometry) else b.mesh.element
        return "rigid" if isinstance(b, RigidBody) else "mass"


def _rod_only(key: str, el: str | None) -> None:
    if not framed(el):
        raise fail(key, f'applies to rod elements only (mesh.element = "rod"), not {el!r}')


def _supports(c: _Context) -> list[ResolvedPlace]:
    places = []
    for i, s in enumerate(c.sc.supports):
        key = f"supports[{i}]"
        p = c.place(f"{key}.at", s.at)
        places.append(p)
        el = c.element(p)
        if el == "mass" and s.kind != "pin":
            raise fail(f"{key}.kind", f"a point mass has no orientation: use a pin, not {s.kind!r}")
        if s.fix_twist:
            _rod_only(f"{key}.fix_twist", el)
        for k in ("position", "direction", "axis"):
            _size(f"{key}.{k}", s[k], c.dim)
        if s.motion is not None and time_size(s.motion) != c.dim:
            raise fail(
                f"{key}.motion",
                f"must be a displacement of {c.dim} components, got {time_size(s.motion)}",
            )
    return places


def _loads(c: _Context) -> None:
    ld = c.sc.loads
    _size("loads.gravity", ld.gravity, c.dim)
    for i, pl in enumerate(ld.point):
        key = f"loads.point[{i}]"
        el = c.element(c.place(f"{key}.at", pl.at))
        _size(f"{key}.force", pl.force, c.dim)
        m = pl.moment
        if m is None:
            continue
        if el == "rigid":
            if c.dim == 2 and isinstance(m, list):
                raise fail(
                    f"{key}.moment", f"must be a number in 2D (the torque about z), got {show(m)}"
                )
            if c.dim == 3 and not isinstance(m, list):
                raise fail(f"{key}.moment", f"must be a list of 3 numbers, got {show(m)}")
        else:
            _rod_only(f"{key}.moment", el)
            if not isinstance(m, list):
                raise fail(f"{key}.moment", f"must be a list of 3 numbers, got {show(m)}")


def _motion(c: _Context) -> None:
    sc = c.sc
    for i, iv in enumerate(sc.initial_velocity):
        p = c.place(f"initial_velocity[{i}].at", iv.at)
        if p.where != "node":
            raise fail(
                f"initial_velocity[{i}].at",
                "must be a node of a flexible body (rigid bodies and point masses take velocity)",
            )
        _size(f"initial_velocity[{i}].value", iv.value, c.dim)
    per_body = [i for i, b in enumerate(sc.bodies) if getattr(b, "initial_motion", None)]
    if sc.initial_motion is not None:
        try:
            sc.initial_motion.check_dim(c.dim)
        except PydanticCustomError as exc:
            raise under("initial_motion", exc) from None
        if sc.initial_velocity:
            raise fail("initial_motion", "give [initial_motion] or [[initial_velocity]], not both")
        if per_body:
            raise fail(
                "initial_motion",
                f"give [initial_motion] for the whole system or "
                f"bodies[{per_body[0]}].initial_motion, not both",
            )
        rigid = [i for i, b in enumerate(sc.bodies) if not isinstance(b, FlexibleBody)]
        if rigid:
            raise fail(
                "initial_motion",
                f"moves the flexible bodies: give bodies[{rigid[0]}] (a rigid body or point "
                "mass) its velocity in its own table, and each flexible body its "
                "[bodies.initial_motion]",
            )


def _sliding(c: _Context, key: str, j: Any) -> None:
    """A sliding joint: a flexible body of cable or rod elements, and a place (the ground at
    ``position``)."""
    a, b = j.between
    body = c.bodies.get(str(a)) if c.bodies is not None else (c.sc if a == "body" else None)
    if body is None or (c.bodies is not None and not isinstance(body, FlexibleBody)):
        names = [
            k
            for k, v in (c.bodies or {"body": None}).items()
            if c.bodies is None or isinstance(v, FlexibleBody)
        ]
        known = shorten(", ".join(names)) or "none"
        raise fail(
            f"{key}.between[0]",
            f"names the flexible body that slides through the "
            f"place (one of {known}), got {show(a)}",
        )
    if not family(body.mesh.element).gradient:
        raise fail(f"{key}.between[0]", "a body of cable or rod elements slides (not beams)")
    p = c.place(f"{key}.between[1]", b, ground=True)
    if p.where == "ground" and j.position is None:
        raise fail(
            f"{key}.position", "required for a sliding joint to the ground: where the guide is"
        )
    if p.where != "ground" and j.position is not None:
        raise fail(
            f"{key}.position",
            "only for a sliding joint to the ground (a place on a body is where it is)",
        )
    _size(f"{key}.position", j.position, c.dim)


def _joints(c: _Context) -> None:
    names: set[str] = set()
    for i, j in enumerate(c.sc.joints):
        key = f"joints[{i}]"
        if j.name in names:
            raise fail(f"{key}.name", f"{show(j.name)} is used twice")
        names.add(j.name)
        if j.kind == "sliding":
            _sliding(c, key, j)
            continue
        ps = [c.place(f"{key}.between[{k}]", v, ground=True) for k, v in enumerate(j.between)]
        if all(p.where == "ground" for p in ps):
            raise fail(f"{key}.between", "joins the ground to itself")
        els = [c.element(p) for p in ps]
        _size(f"{key}.axis", j.axis, c.dim)
        if j.kind == "revolute" and c.dim == 2:
            raise fail(
                f"{key}.kind", 'revolute joints are spatial: in 2D a "pin" is a revolute joint'
            )
        if j.kind == "fixed" and "mass" in els:
            raise fail(
                f"{key}.kind",
                "a point mass has no orientation: a fixed joint needs "
                "bodies with orientation (use a pin)",
            )
        if j.angle is not None:
            if j.kind == "pin" and c.dim == 3:
                raise fail(f"{key}.angle", "a pin is spherical in 3D: drive a revolute joint")
            if "rigid" not in els:
                raise fail(f"{key}.angle", "a driven joint needs a rigid body on one side")
    for i, s in enumerate(c.sc.springs):
        ps = [
            c.place(f"springs[{i}].between[{k}]", v, ground=True) for k, v in enumerate(s.between)
        ]
        if all(p.where == "ground" for p in ps):
            raise fail(f"springs[{i}].between", "joins the ground to itself")


def _sensors(c: _Context, supports: list[ResolvedPlace]) -> None:
    names: set[str] = set()
    joints = {j.name for j in c.sc.joints}
    winches = [w.name for w in c.sc.winches]
    for i, s in enumerate(c.sc.sensor_tables):
        key = f"sensors[{i}]"
        if s.name in names or s.name == "t":
            raise fail(f"{key}.name", f"{show(s.name)} is used twice or reserved")
        if s.winch is not None and s.winch not in winches:
            raise fail(
                f"{key}.winch",
                f"names no winch: {show(s.winch)} (winches: {', '.join(winches) or 'none'})",
            )
        names.add(s.name)
        _size(f"{key}.about", s.about, c.dim)
        places = []
        if s.between is not None:
            places = [c.place(f"{key}.between[{k}]", v) for k, v in enumerate(s.between)]
        elif s.at is not None:
            places = [c.place(f"{key}.at", s.at)]
        _size(f"{key}.at_point", s.at_point, c.dim)
        els = [c.element(p) for p in places]
        if s.kind == "twist" and places and not framed(els[0]):
            raise fail(
                f"{key}.kind",
                f"'twist' needs rod elements (mesh.element = \"rod\"), not {els[0]!r}",
            )
        if s.kind in ("axial_force", "tension") and places and places[0].where != "node":
            raise fail(f"{key}.at", f"a {s.kind} sensor measures at a node of a flexible body")
        if s.kind == "reaction":
            if s.joint is not None and s.joint not in joints:
                raise fail(
                    f"{key}.joint",
                    f"names no joint: {show(s.joint)} (joints: "
                    f"{', '.join(sorted(joints)) or 'none'})",
                )
            if s.at is not None and places[0] not in supports:
                raise fail(f"{key}.at", f"must be the place of a support, got {show(s.at)}")
        if s.body is not None:
            b = None if c.bodies is None else c.bodies.get(s.body)
            if b is None:
                known = (
                    "none: a file without [[bodies]]" if c.bodies is None else ", ".join(c.bodies)
                )
                raise fail(f"{key}.body", f"names no body: {show(s.body)} (bodies: {known})")
            if s.kind == "angle" and not isinstance(b, RigidBody):
                raise fail(f"{key}.body", f"an angle is of a rigid body, {show(s.body)} is not one")
        elif s.kind == "angle":
            raise fail(f"{key}.body", "an angle sensor needs body = NAME (a rigid body)")


def _obstacles(c: _Context) -> set[str]:
    names: set[str] = set()
    for i, o in enumerate(c.sc.obstacles):
        key = f"obstacles[{i}]"
        if o.name in names:
            raise fail(f"{key}.name", f"{show(o.name)} is used twice")
        names.add(o.name)
        for k in ("point", "normal", "center"):
            _size(f"{key}.{k}", o[k], c.dim)
        if o.kind == "sphere" and c.dim == 2:
            raise fail(f"{key}.kind", 'a sphere is spatial: in 2D a circle is kind = "cylinder"')
        if o.kind == "cylinder" and c.dim == 3 and o.axis is None:
            raise fail(f"{key}.axis", "required for a cylinder in 3D")
        if o.kind == "cylinder" and c.dim == 2 and o.axis is not None:
            raise fail(f"{key}.axis", "does not apply in 2D (the cylinder is a circle)")
        if o.body is not None:
            b = None if c.bodies is None else c.bodies.get(o.body)
            if not isinstance(b, RigidBody):
                raise fail(f"{key}.body", f"must name a rigid body, got {show(o.body)}")
    flex = (
        ["body"]
        if c.bodies is None
        else [n for n, b in c.bodies.items() if isinstance(b, FlexibleBody)]
    )
    for i, pair in enumerate(c.sc.contacts or []):
        if len(pair) != 2 or pair[0] not in flex or pair[1] not in names:
            raise fail(
                f"contacts[{i}]",
                f"must be [FLEXIBLE_BODY, OBSTACLE] (bodies: "
                f"{', '.join(flex)}; obstacles: {', '.join(sorted(names)) or 'none'}), "
                f"got {show(pair)}",
            )
    _once("contacts", [tuple(p) for p in c.sc.contacts or []])
    for i, pair in enumerate(c.sc.body_contacts):
        if len(pair) != 2 or not all(x in flex for x in pair):
            raise fail(
                f"body_contacts[{i}]",
                f"must be [FLEXIBLE_BODY, FLEXIBLE_BODY] (bodies: "
                f"{', '.join(flex)}), got {show(pair)}",
            )
    _once("body_contacts", [tuple(sorted(p)) for p in c.sc.body_contacts])
    for i, s in enumerate(c.sc.sensor_tables):
        if s.obstacle is not None and s.obstacle not in names:
            raise fail(
                f"sensors[{i}].obstacle",
                f"names no obstacle: {show(s.obstacle)} "
                f"(obstacles: {', '.join(sorted(names)) or 'none'})",
            )
    return names


def _once(key: str, pairs: list[tuple[str, ...]]) -> None:
    """Refuse a contact pair listed twice (its contact would count twice); ``pairs`` as
    compared (a pair of bodies in either order is the same)."""
    seen: dict[tuple[str, ...], int] = {}
    for i, pair in enumerate(pairs):
        if pair in seen:
            raise fail(
                f"{key}[{i}]",
                f"lists the pair {show(list(pair))} again ({key}"
                f"[{seen[pair]}] has it; its contact would count twice): give each pair "
                "once",
            )
        seen[pair] = i


def _winches(c: _Context) -> None:
    """Winch names once, one winch per body, scalar laws."""
    names: dict[str, int] = {}
    bodies: dict[str, int] = {}
    for i, w in enumerate(c.sc.winches):
        key = f"winches[{i}]"
        if w.name in names:
            raise fail(
                f"{key}.name",
                f"{show(w.name)} is used twice (winches[{names[w.name]}] "
                "has it): each winch needs its own name",
            )
        names[w.name] = i
        body = w.at.rpartition(":")[0] if c.bodies is not None else ""
        if body in bodies:
            which = f"body {show(body)}" if body else "the body"
            raise fail(
                f"{key}.at",
                f"{show(w.at)}: {which} already has a winch "
                f"(winches[{bodies[body]}]): one winch per body",
            )
        bodies[body] = i


def check_scenario(sc: ScenarioView) -> tuple[int, dict[str, Any] | None, list[ResolvedPlace]]:
    """Check ``sc`` as a whole; return its dimension, its bodies by name (None: one body) and
    the resolved places of its supports."""
    c = _Context(sc)
    supports = _supports(c)
    _loads(c)
    _motion(c)
    _joints(c)
    _sensors(c, supports)
    _obstacles(c)
    _winches(c)
    check_shell_uses(c)
    return c.dim, c.bodies, supports
