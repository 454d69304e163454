"""The names of a system's reaction columns (:mod:`rancf.system.outputs`, "Column names"), as
its Parts name them (:meth:`rancf.system.part.Part.sensors`, in the order of
:attr:`rancf.system.system.System.parts`): every support's ``LABEL_fx ...`` (the label is its
place as the caller wrote it, else ``BODY:AT``), every joint's ``NAME_fx ...`` and moment
where it transmits one (``NAME_s`` for a sliding joint), every obstacle's normal, friction,
moment, length and penetration, and every pair of flexible bodies in contact.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from rancf.system.parts.flexible import FlexibleBody

__all__ = ["support_labels", "part_columns"]


def support_labels(
    system: Any, labels: Mapping[str, Sequence[int | str] | None] | None
) -> dict[str, list[str]]:
    """Every flexible body's support labels: as the user wrote them, else ``BODY:AT`` (unique
    in every system; :meth:`rancf.system.parts.support.Support.label`)."""
    given = dict(labels or {})
    return {
        p.name: [sup.label(system) for sup in p.supports(given.get(p.name))]
        for p in system.body_parts
        if isinstance(p, FlexibleBody)
    }


def part_columns(
    system: Any, labels: Mapping[str, Sequence[int | str]]
) -> list[tuple[Any, list[str]]]:
    """Every part of ``system`` with output columns and its columns, in order; ``labels``: the
    supports' (:func:`support_labels`)."""
    out = []
    for part in system.labelled_parts(labels):
        cols = list(part.sensors(system))
        if cols:
            out.append((part, cols))
    return out
