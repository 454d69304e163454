"""The shell bodies of a scenario: the :class:`~rancf.bodies.shell.ShellBody` of a body whose
``[geometry]`` is a surface, with the supports at its places, its load vector and its sensors.

The load vector is the sum of the point loads at its surface points, the edge loads on its
edges, the distributed loads (per reference area) on it and gravity ``ρ t g`` per area, at their
full value: the System scales it along a static load path and holds it constant in a
simulation (a ``time`` on a shell's load is refused: :mod:`rancf.scenario.shell_checks`).
:func:`shell_model` makes the body the System's flexible body
(:class:`~rancf.bodies.shell_model.ShellModel`); :func:`refuse_shells` refuses, in one line,
what the System does not do for shells yet.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray
from pydantic_core import PydanticCustomError

from rancf.bodies.shell import ShellBody, ShellSupport
from rancf.bodies.shell_loads import distributed_load, edge_load, point_load
from rancf.bodies.shell_model import ShellModel
from rancf.errors import InputError, ScenarioError
from rancf.scenario.shell_checks import shell_mesh
from rancf.scenario.surface import is_surface

__all__ = [
    "shell_body",
    "shell_load",
    "shell_model",
    "refuse_shells",
    "shell_sensors",
    "shell_sensor_values",
    "shell_indices",
]


def shell_indices(sc: Any) -> list[int]:
    """The indices in ``sc.body_tables`` of the shell bodies."""
    return [
        i
        for i, (_, b) in enumerate(sc.body_tables)
        if b.kind == "flexible" and is_surface(b.geometry)
    ]


def _on(sc: Any, name: str, at: Any) -> Any:
    """The resolved place ``at`` if it is on the shell ``name``, else None."""
    p = sc.place(at)
    return p if p.body == name and p.where in ("edge", "surface") else None


def shell_body(sc: Any, i: int) -> ShellBody:
    """The shell body ``i`` of ``sc.body_tables`` with the supports at its places."""
    key, b = sc.body_tables[i]
    try:
        mesh = shell_mesh(b.geometry, b.mesh)
    except PydanticCustomError as exc:
        ctx = exc.context or {}
        raise ScenarioError(sc.path, f"{key}{ctx.get('key', '')}", str(exc)) from None
    supports = []
    for s in sc.supports:
        p = _on(sc, b.name, s.at)
        if p is not None:
            at = p.edge if p.where == "edge" else p.uv
            normal = None if s.normal is None else tuple(s.normal)
            axis = None if s.axis is None else tuple(s.axis)
            supports.append(ShellSupport(s.kind, at, normal, axis))
    return ShellBody(
        mesh,
        float(b.section.thickness),
        float(b.material.youngs_modulus),
        float(b.material.poisson_ratio),
        float(b.material.density),
        b.name,
        supports,
    )


def shell_load(sc: Any, body: ShellBody) -> NDArray[np.float64]:
    """The body's load vector (module docstring)."""
    q = np.zeros(body.n_dofs)
    for pl in sc.loads.point:
        p = _on(sc, body.name, pl.at)
        if p is not None and pl.force is not None:
            q += point_load(body, p.uv, pl.force)
    for el in sc.loads.edge:
        p = _on(sc, body.name, el.at)
        if p is not None:
            q += edge_load(body, str(p.edge), el.force, el.moment)
    per_area = np.zeros(3)
    for dl in sc.loads.distributed:
        if dl.body in (None, body.name):
            per_area += dl.force
    if sc.loads.gravity is not None:
        per_area += body.density * body.thickness * np.asarray(sc.loads.gravity, dtype=float)
    if np.any(per_area != 0.0):
        q += distributed_load(body, per_area)
    return q


def shell_sensors(sc: Any, body: ShellBody) -> list[tuple[str, tuple[float, float]]]:
    """The ``position`` sensors on the body: ``(name, (u, v))``."""
    out = []
    for s in sc.sensor_tables:
        if s.kind == "position" and s.at is not None:
            p = _on(sc, body.name, s.at)
            if p is not None and p.uv is not None:
                out.append((s.name, p.uv))
    return out


def shell_sensor_values(sc: Any, body: ShellBody, q: NDArray) -> dict[str, float]:
    """The columns ``NAME_x``, ``NAME_y``, ``NAME_z`` of the body's ``position`` sensors in the
    configuration ``q``."""
    out = {}
    for name, uv in shell_sensors(sc, body):
        for c, x in zip("xyz", body.position(uv, q), strict=True):
            out[f"{name}_{c}"] = float(x)
    return out


def shell_model(sc: Any, i: int) -> ShellModel:
    """The shell body ``i`` of ``sc.body_tables`` as a flexible body of the scenario's System
    (:class:`~rancf.bodies.shell_model.ShellModel`): its supports, its load vector
    (:func:`shell_load`) and the scenario's mass-proportional damping."""
    _, b = sc.body_tables[i]
    body = shell_body(sc, i)
    keys = [f"supports[{k}]" for k, s in enumerate(sc.supports) if _on(sc, b.name, s.at)]
    try:
        return ShellModel(
            body,
            shell_load(sc, body),
            sc.loads.gravity,
            sc.damping.mass_proportional,
            support_keys=keys,
        )
    except InputError as exc:
        raise ScenarioError(sc.path, exc.parameter, f"{exc.allowed} (got {exc.value!r})") from None


#: The tables a scenario with a shell may not have yet: the System holds a shell's elements,
#: supports, loads and mass, not its contact, fluid loads or winches.
NOT_WITH_SHELLS = ("obstacles", "body_contacts", "fluid", "hydro", "winches")


def refuse_shells(sc: Any, what: str | None = None) -> None:
    """Refuse, in one line naming the key, what a scenario with a shell body asks that the
    System does not do for shells yet: a table of :data:`NOT_WITH_SHELLS`, or the analysis
    ``what`` (e.g. ``"buckling"``, named by its command).  Nothing without a shell."""
    i = next(iter(shell_indices(sc)), None)
    if i is None:
        return
    key, b = sc.body_tables[i]
    if what is not None:
        raise ScenarioError(
            sc.path,
            f"{key}geometry",
            f"{b.geometry.kind!r} makes the body a shell, and `rancf {what}` does not run "
            "shells yet (static, modes and simulate do: docs/derivations/shell.md sec. 8)",
        )
    for k in NOT_WITH_SHELLS:
        if sc[k]:
            raise ScenarioError(
                sc.path,
                k,
                f"not with a shell (body {b.name!r}) yet: the System holds a shell's elements, "
                "supports, loads and mass (docs/derivations/shell.md sec. 8)",
            )
