"""``[mesh]``: how a flexible body's geometry is divided into elements.

A line body (cable, beam, rod) has ``elements`` = a number (per knot span of a NURBS or CAD
curve); a shell (a surface ``[geometry]``: :mod:`rancf.scenario.surface`) has ``elements = [nu,
nv]``, the elements along ``u`` and ``v`` (per knot span of a NURBS surface).  Which of the two a
body needs is checked with its geometry (:func:`rancf.scenario.section.check_flexible`).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BeforeValidator, Field

from rancf.elements.mapping import K_RANGE  # the factors a scenario may fix
from rancf.scenario.base import (
    MAX_ELEMENTS,
    JsonSchema,
    QuadraturePoints,
    Table,
    fail,
    show,
    to_number,
)

__all__ = ["MeshTable", "ElementCounts"]


def _count(v: Any, key: str = "") -> int:
    """A number of elements: a whole number in ``[1, MAX_ELEMENTS]``."""
    if isinstance(v, np.integer):
        v = int(v)
    if isinstance(v, bool) or not isinstance(v, int):
        raise fail(key, f"must be an integer (a shell: [nu, nv] of them), got {show(v)}")
    if v < 1:
        raise fail(key, f"must be >= 1, got {show(v)}")
    if v > MAX_ELEMENTS:
        raise fail(key, f"must be at most {MAX_ELEMENTS}, got {show(v)}")
    return v


def _counts(v: Any) -> Any:
    """A number of elements (a line body) or ``[nu, nv]`` (a shell)."""
    if isinstance(v, np.ndarray):
        v = v.tolist()
    if isinstance(v, list | tuple):
        if len(v) != 2:
            raise fail("", f"must be [nu, nv] (a shell) or one integer (a line), got {show(v)}")
        return [_count(x, f"[{i}]") for i, x in enumerate(v)]
    return _count(v)


_COUNT = {"type": "integer", "minimum": 1, "maximum": MAX_ELEMENTS}
#: ``elements``: a number, or ``[nu, nv]``.
ElementCounts = Annotated[
    int | list[int],
    BeforeValidator(_counts),
    JsonSchema(
        {"oneOf": [_COUNT, {"type": "array", "items": _COUNT, "minItems": 2, "maxItems": 2}]}
    ),
]


def _k(v: Any) -> Any:
    lo, hi = K_RANGE
    bad = f'must be "opt" or a number in [{lo:g}, {hi:g}], got {show(v)}'
    if v == "opt" and isinstance(v, str):
        return v
    try:
        k = to_number(v)
    except Exception:  # noqa: BLE001 - any non-number is the same mistake
        raise fail("", bad) from None
    if not lo <= k <= hi:
        raise fail("", bad)
    return k


class MeshTable(Table):
    """``[mesh]``: how the geometry is divided into elements."""

    elements: ElementCounts = Field(
        description="number of elements (NURBS and CAD curves: per knot span); a shell: [nu, "
        "nv] along u and v (NURBS surfaces: per knot span)"
    )
    element: Literal["rancf", "ancf", "beam", "rod"] = Field(
        "rancf",
        description='"rancf" (rational, exact conics) | "ancf" (polynomial cable) | "beam" '
        '(planar co-rotational Euler-Bernoulli, 2D only) | "rod" (spatial rod with torsion, '
        "3D only)",
    )
    k: Annotated[
        Literal["opt"] | float,
        BeforeValidator(_k),
        JsonSchema(
            {
                "oneOf": [
                    {"const": "opt"},
                    {"type": "number", "minimum": K_RANGE[0], "maximum": K_RANGE[1]},
                ]
            }
        ),
    ] = Field("opt", description='mapping factor: "opt" (Kopt per element) or a number')
    spacing: Literal["arc", "parameter"] = Field(
        "arc", description='"arc" (equal arc length) | "parameter" (equal parameter steps)'
    )
    continuity: Literal["C1", "C2"] = Field(
        "C1",
        description='"C1" (shared nodes: the nodal coordinates are the unknowns) | "C2" (the '
        "control points of the cubic (rational) B-spline through the mesh are the unknowns: "
        "curvature continuous, fewer unknowns; cables and rods)",
    )
    stress_free: Literal["auto", "reference", "straight"] = Field(
        "auto",
        description='"auto" ("straight" for a spatial cable drawn curved whose rest curvature\'s '
        "moment EI max k0 is below 1e-3 of its weight's moment w L^2/8, a chain or a rope, with "
        'a note; else "reference") | "reference" (the start shape is unloaded) | "straight" '
        "(unloaded straight, same arc length: a rope laid over a pulley carries its bending "
        "energy; cables and rods)",
    )
    quadrature_points: QuadraturePoints | None = Field(
        None,
        description="Gauss points per element (default: 6 for polynomial (ANCF) elements, 10 "
        "for rational ones)",
    )

    @property
    def count(self) -> int:
        """The number of elements of a line body (its ``elements`` is one number)."""
        e = self.elements
        return e if isinstance(e, int) else int(e[0])

    @property
    def pair(self) -> tuple[int, int]:
        """``(nu, nv)`` of a shell (its ``elements`` is ``[nu, nv]``)."""
        e = self.elements
        return (e, e) if isinstance(e, int) else (int(e[0]), int(e[1]))
