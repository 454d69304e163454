"""A validated scenario's bodies in one form, its tables as plain dictionaries, its sensors.

One schema past parsing: :func:`body_tables` gives every scenario's bodies as ``[[bodies]]``
tables with the prefix of their keys; a file without ``[[bodies]]`` is the flexible body
:data:`~rancf.scenario.places.ONE_BODY` made of its ``geometry``, ``mesh``, ``section``,
``material``, ``hydro`` and ``initial_motion`` (keys without a prefix), whose places resolve to
it (:func:`~rancf.scenario.places.resolve_place`).  Code past parsing reads these and never
asks which form the file was written in.

:func:`scenario_data` gives :attr:`rancf.scenario.scenario.Scenario.data`: every table with its
defaults filled in, TIME_FUNCTIONs as :class:`~rancf.bodies.time_function.TimeFunction`, the
places as written (``label``) and, in a one-body file, ``"start"``/``"end"`` as node numbers;
``bodies`` holds every body (of :func:`body_tables`, each with its ``key`` prefix), and a
one-body file's own tables stay at the top too, as written.
"""

from __future__ import annotations

from typing import Any

from rancf.scenario.base import fail, show
from rancf.scenario.bodies import FlexibleBody
from rancf.scenario.geometry import GEOMETRY_KEYS, CadGeometry
from rancf.scenario.motions import motion_function
from rancf.scenario.places import ONE_BODY
from rancf.scenario.sensors import Sensor, SensorTable
from rancf.scenario.surface import is_surface
from rancf.scenario.time_functions import time_function

__all__ = ["body_tables", "scenario_data", "columns_once", "sensor_record"]


def body_tables(sc: Any) -> tuple[tuple[str, Any], ...]:
    """Every body of a validated scenario as ``(key prefix, [[bodies]] table)`` (module
    docstring): ``("bodies[i].", table)``, or a one-body file's ``("", flexible body)``."""
    if sc.bodies:
        return tuple((f"bodies[{i}].", b) for i, b in enumerate(sc.bodies))
    tables = ("geometry", "mesh", "section", "material", "hydro", "initial_motion", "form")
    one = FlexibleBody.model_construct(name=ONE_BODY, **{k: sc[k] for k in tables})
    return (("", one),)


def _geometry_data(g: Any) -> dict[str, Any]:
    out: dict[str, Any] = dict.fromkeys(k for keys in GEOMETRY_KEYS.values() for k in keys)
    out.update(g.plain())
    if isinstance(g, CadGeometry):
        out["file"], out["curves"], out["labels"] = g.resolved_file, g.curves, g.labels
        out["curve"] = 0 if g.curve is None else g.curve
    return out


def _tf(v: Any) -> Any:
    return None if v is None else time_function(v)


def _node_or_text(v: Any, one_body: bool) -> Any:
    if one_body and v in ("start", "end"):
        return 0 if v == "start" else -1
    return v


def scenario_data(sc: Any) -> dict[str, Any]:
    """The tables of a validated scenario as plain dictionaries (:attr:`Scenario.data`)."""
    one = not sc.bodies
    d: dict[str, Any] = {}
    if one:
        d["geometry"] = _geometry_data(sc.geometry)
        for k in ("mesh", "section", "material"):
            d[k] = sc[k].plain()
    d["bodies"] = []
    for key, b in body_tables(sc):
        bd = {**b.plain(), "key": key}
        if isinstance(b, FlexibleBody):
            bd["geometry"] = _geometry_data(b.geometry)
            # its own, else the whole system's rigid motion (one form: a one-body file's too)
            im = b.initial_motion if b.initial_motion is not None else sc.initial_motion
            bd["initial_motion"] = None if im is None else im.as_dict()
        d["bodies"].append(bd)
    notes: list[str] = []

    def motion(v: Any, key: str) -> Any:
        f, note = motion_function(v, key)
        notes.extend([note] if note else [])
        return f

    d["joints"] = [
        {**j.plain(frozenset({"angle"})), "angle": motion(j.angle, f"joints[{i}].angle")}
        for i, j in enumerate(sc.joints)
    ]
    d["springs"] = [s.plain() for s in sc.springs]
    d["obstacles"] = [o.plain() for o in sc.obstacles]
    d["winches"] = [
        {
            **w.plain(frozenset({"length", "speed", "torque"})),
            **{k: _tf(w[k]) for k in ("length", "speed", "torque")},
        }
        for w in sc.winches
    ]
    d["supports"] = [
        {
            **s.plain(frozenset({"motion"})),
            "at": _node_or_text(s.at, one),
            "label": s.at,
            "motion": motion(s.motion, f"supports[{i}].motion"),
        }
        for i, s in enumerate(sc.supports)
    ]
    d["loads"] = {
        "gravity": sc.loads.gravity,
        "point": [
            {**p.plain(frozenset({"time"})), "at": _node_or_text(p.at, one), "time": _tf(p.time)}
            for p in sc.loads.point
        ],
        "distributed": [
            {**p.plain(frozenset({"time"})), "time": _tf(p.time)} for p in sc.loads.distributed
        ],
        "edge": [{**p.plain(frozenset({"time"})), "time": _tf(p.time)} for p in sc.loads.edge],
    }
    d["damping"] = sc.damping.plain()
    d["initial_velocity"] = [
        {"at": _node_or_text(iv.at, one), "value": iv.value} for iv in sc.initial_velocity
    ]
    d["initial_motion"] = None if sc.initial_motion is None else sc.initial_motion.as_dict()
    d["solver"] = sc.solver.plain()
    d["modes"] = sc.modes.plain()
    d["notes"] = notes
    return d


def columns_once(sensors: tuple[Sensor, ...], dim: int) -> None:
    """Refuse two sensors that give a column of the same name (a position ``tip`` gives
    ``tip_x``, as a sensor named ``tip_x`` does): readers would take one for the other."""
    owner: dict[str, int] = {}
    for i, s in enumerate(sensors):
        for col in s.columns(dim):
            if col in owner:
                j = owner[col]
                raise fail(
                    f"sensors[{i}].name",
                    f"{show(s.name)} gives the column {col!r}, as "
                    f"sensors[{j}] ({show(sensors[j].name)}, kind {sensors[j].kind!r}) "
                    "does: each column of sensors.csv needs its own name",
                )
            owner[col] = i


def sensor_record(s: SensorTable, bodies: dict[str, Any] | None, geometry: Any = None) -> Sensor:
    """The sensor record of a ``[[sensors]]`` table (a one-body file: its nodes by number; a
    shell's, of a surface ``geometry``: its places as written)."""
    if bodies is not None or is_surface(geometry):
        return s.record()
    return s.record(tuple(int(_node_or_text(p, True)) for p in s.places()))
