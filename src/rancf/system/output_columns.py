"""The names of a system's reaction columns (:mod:`rancf.system.outputs`, "Column names").

A support's ``LABEL_fx ...`` (the label is its place as the caller wrote it, else ``BODY:AT``),
a joint's ``NAME_fx ...`` and moment where it transmits one (``NAME_s`` for a sliding joint),
every obstacle's normal, friction, moment, length and penetration, and every pair of flexible
bodies in contact.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

__all__ = ["support_labels", "joint_column_names", "contact_column_names", "joint_has_moment"]


def joint_has_moment(system: Any, k: int) -> bool:
    """Whether joint ``k`` transmits a moment (``fixed``, a 3D ``revolute``, a driven joint)."""
    j = system.joints[k]
    return j.kind == "fixed" or j.angle is not None or (j.kind == "revolute" and system.dim == 3)


def _node_name(body: Any, node: int) -> str:
    """A node as a scenario spells it: ``start``, ``end`` or ``nodeK``."""
    k = node % body.n_nodes
    return "start" if k == 0 else "end" if k == body.n_nodes - 1 else f"node{k}"


def support_labels(
    flex: Sequence[tuple[str, Any]], labels: Mapping[str, Sequence[int | str]] | None
) -> dict[str, list[int | str]]:
    """Every flexible body's support labels: as the user wrote them, else ``BODY:AT`` (unique
    in every system)."""
    given = dict(labels or {})
    out: dict[str, list[int | str]] = {}
    for name, b in flex:
        default: list[int | str] = [f"{name}:{_node_name(b, sup.node)}" for sup in b.supports]
        out[name] = list(given[name]) if given.get(name) is not None else default
    return out


def joint_column_names(system: Any) -> list[list[str]]:
    """Every joint's reaction columns: force, moment where it transmits one, a sliding joint's
    arc length ``NAME_s`` (:mod:`rancf.system.sliding`)."""
    out: list[list[str]] = []
    axes = "xyz"[: system.dim]
    for k, j in enumerate(system.joints):
        lab = j.name or f"joint{k}"
        cols = [f"{lab}_f{a}" for a in axes]
        if joint_has_moment(system, k):
            cols += [f"{lab}_mz"] if system.dim == 2 else [f"{lab}_m{a}" for a in "xyz"]
        if j.kind == "sliding":
            cols.append(f"{lab}_s")
        out.append(cols)
    return out


def contact_column_names(system: Any) -> list[str]:
    """Every obstacle's contact columns, then every pair of flexible bodies in contact."""
    out: list[str] = []
    axes = "xyz"[: system.dim]
    moments = ["z"] if system.dim == 2 else ["x", "y", "z"]
    for ob in system.obstacle_names:
        cols = [f"{ob}_{part}_{a}" for part in ("normal", "friction") for a in axes]
        cols += [f"{ob}_m{a}" for a in moments]
        out += [*cols, f"{ob}_length", f"{ob}_penetration"]
    for first, second in system.body_contacts:
        pair = f"{first}_{second}"
        out += [f"{pair}_contact_force", f"{pair}_penetration"]
    return out
