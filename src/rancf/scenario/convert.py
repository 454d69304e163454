"""A one-body scenario written as a system of one flexible body (one ``[[bodies]]`` table).

A file without ``[[bodies]]`` builds the system of one flexible body named ``body``
(:mod:`rancf.scenario.system_build`); :func:`as_bodies` writes the same model in the
``[[bodies]]`` form (the form self-contact and further bodies need): its ``geometry``, ``mesh``,
``section``, ``material`` and ``hydro`` become the body's tables, and every place ``P`` of a
support, point load, initial velocity, joint, spring or sensor becomes ``"NAME:P"``
(``"ground"`` stays).  Both
files run to the same numbers; the supports' reaction columns are named ``NAME:P_fx ...`` as in
any system.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rancf.errors import ScenarioError

if TYPE_CHECKING:
    from rancf.scenario.scenario import Scenario

__all__ = ["as_bodies"]

#: The tables of a one-body file that describe its flexible body.
BODY_TABLES = ("geometry", "mesh", "section", "material", "hydro", "form")


def as_bodies(sc: Scenario, name: str = "body") -> Scenario:
    """The one-body scenario ``sc`` as a scenario with one ``[[bodies]]`` table, the flexible
    body ``name`` (module docstring); errors name the scenario and the key."""
    from rancf.scenario.scenario import Scenario

    if sc.bodies:
        raise ScenarioError(sc.path, "bodies", "is given: the scenario is already a system")
    d: dict[str, Any] = sc.to_dict()
    body: dict[str, Any] = {"name": name}
    for key in BODY_TABLES:
        if key in d:
            body[key] = d.pop(key)
    d["bodies"] = [body]

    def place(v: Any) -> Any:
        if isinstance(v, list | tuple):  # a shell's point [u, v]: "NAME:u,v"
            return f"{name}:{','.join(repr(float(x)) for x in v)}"
        return v if v == "ground" else f"{name}:{v}"

    for key in ("supports", "initial_velocity"):
        for row in d.get(key, []):
            row["at"] = place(row["at"])
    for row in d.get("loads", {}).get("point", []):
        row["at"] = place(row["at"])
    for key in ("joints", "springs"):
        for row in d.get(key, []):
            row["between"] = [place(p) for p in row["between"]]
    for row in d.get("sensors", []):
        if "at" in row:
            row["at"] = place(row["at"])
        if "between" in row:
            row["between"] = [place(p) for p in row["between"]]
    return Scenario.from_dict(d, sc.path)
