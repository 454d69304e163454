"""Scenario tables of the model's parts: ``[section]``, ``[material]``, ``[[supports]]`` and
``[[loads.point]]``, with the keys of rod elements.

Rules (each violation names its key, see :func:`rancf.model.scenario.parse_scenario`):

* ``[section]``: ``radius``; or ``area`` + ``inertia``; or (rods) ``area`` + ``inertia_y`` +
  ``inertia_z`` + ``orientation`` (the first principal axis ``m1`` at the first node, bending
  stiffness ``E inertia_y`` about it); optional ``torsion_constant`` (rods; default the polar
  moment ``I_y + I_z``, exact for a circle).
* ``[material]``: rods need exactly one of ``shear_modulus`` and ``poisson_ratio``
  (``G = E / (2 (1 + ν))``); cables and beams refuse both (they have no torsion, so a value
  there would be silently meaningless).
* ``[[supports]]``: ``fix_twist = true`` (rods) also holds the twist of a pin; a clamp holds it
  anyway.
* ``[[loads.point]]``: ``force``, ``moment = [mx, my, mz]`` (rods) or both.
* ``[section] rotary_inertia``: ``"torsion"`` (default) or ``"full"`` (rods).
* ``[initial_motion]``: ``velocity``, ``angular_velocity`` (3 numbers in 3D, one in 2D) and
  ``about`` (default the origin), at least one of the first two: a rigid-body velocity field
  (:mod:`rancf.model.motion`).

Keys that only rods have are refused, naming the key, for other elements.
"""

from __future__ import annotations

import math
import sys
from typing import Any

from rancf.model.scenario_checks import _REQ, _choice, _err, _number, _place, _table, _vector

__all__ = [
    "parse_section",
    "parse_material",
    "parse_supports",
    "parse_point_loads",
    "parse_initial_motion",
]

SECTION_KEYS = ("radius", "area", "inertia", "inertia_y", "inertia_z", "orientation")
SECTION_KEYS += ("torsion_constant", "rotary_inertia")
_ROD_SECTION = ("inertia_y", "inertia_z", "orientation", "torsion_constant", "rotary_inertia")


def _rod_only(path: str, key: str, element: str) -> None:
    if element != "rod":
        raise _err(
            path, key, f'applies to rod elements only (mesh.element = "rod"), not {element!r}'
        )


def parse_section(path: str, raw: Any, element: str) -> dict[str, Any]:
    """The ``[section]`` table: one of the three ways to give a section (module docstring)."""
    s = _table(path, "section", raw, dict.fromkeys(SECTION_KEYS))
    for k in _ROD_SECTION:
        if s[k] is not None:
            _rod_only(path, f"section.{k}", element)
    for k in ("radius", "area", "inertia", "inertia_y", "inertia_z", "torsion_constant"):
        if s[k] is not None:
            s[k] = _number(path, f"section.{k}", s[k], positive=True)
    if s["rotary_inertia"] is not None:
        s["rotary_inertia"] = _choice(
            path, "section.rotary_inertia", s["rotary_inertia"], ("torsion", "full")
        )
    principal = [k for k in ("inertia_y", "inertia_z", "orientation") if s[k] is not None]
    if s["radius"] is not None:
        _check_radius(path, s["radius"])
        extra = [k for k in ("area", "inertia", *principal) if s[k] is not None]
        if extra:
            raise _err(
                path, "section", f"give either radius, or area and inertia, not both ({extra[0]})"
            )
    elif principal:
        if s["inertia"] is not None:
            raise _err(
                path, "section.inertia", "give inertia (equal bending stiffnesses) or "
                "inertia_y + inertia_z + orientation, not both",
            )  # fmt: skip
        for k in ("area", "inertia_y", "inertia_z", "orientation"):
            if s[k] is None:
                raise _err(
                    path, f"section.{k}", "required with principal inertias "
                    "(area + inertia_y + inertia_z + orientation)",
                )  # fmt: skip
        s["orientation"] = _vector(path, "section.orientation", s["orientation"], (3,))
        if not any(x != 0.0 for x in s["orientation"]):
            raise _err(path, "section.orientation", "must be a nonzero vector, got [0, 0, 0]")
    elif s["area"] is None or s["inertia"] is None:
        raise _err(path, "section", "requires radius, or both area and inertia")
    return s


def _check_radius(path: str, r: float) -> None:
    """A radius whose area ``π r²`` and second moment ``π r⁴ / 4`` are normal positive numbers
    (``1e100`` overflows, ``1e-100`` underflows to zero)."""
    try:
        area, inertia = math.pi * r**2, math.pi * r**4 / 4.0
    except OverflowError:
        area = inertia = math.inf
    if not (math.isfinite(inertia) and inertia >= sys.float_info.min and area > 0):
        raise _err(
            path,
            "section.radius",
            f"must give a finite, nonzero area π r² and second moment π r⁴/4, got {r:g} "
            f"(second moment {inertia:g})",
        )


def parse_material(path: str, raw: Any, element: str) -> dict[str, Any]:
    """The ``[material]`` table; ``shear_modulus`` xor ``poisson_ratio`` for rods only."""
    mat = _table(
        path, "material", raw, {"density": _REQ, "youngs_modulus": _REQ,
                                "shear_modulus": None, "poisson_ratio": None},
    )  # fmt: skip
    for k in ("density", "youngs_modulus"):
        mat[k] = _number(path, f"material.{k}", mat[k], positive=True)
    for k in ("shear_modulus", "poisson_ratio"):
        if mat[k] is not None:
            _rod_only(path, f"material.{k}", element)
    if mat["shear_modulus"] is not None:
        if mat["poisson_ratio"] is not None:
            raise _err(
                path, "material.poisson_ratio", "give shear_modulus or poisson_ratio, not both"
            )
        mat["shear_modulus"] = _number(
            path, "material.shear_modulus", mat["shear_modulus"], positive=True
        )
    elif mat["poisson_ratio"] is not None:
        nu = _number(path, "material.poisson_ratio", mat["poisson_ratio"])
        if not -1.0 < nu < 0.5:
            raise _err(path, "material.poisson_ratio", f"must be in (-1, 0.5), got {nu!r}")
        mat["poisson_ratio"] = nu
    elif element == "rod":
        raise _err(
            path, "material.shear_modulus", "required for rod elements: give shear_modulus or "
            "poisson_ratio (the torsional stiffness is G J)",
        )  # fmt: skip
    return mat


def parse_supports(path: str, raw: Any, element: str, dim: int) -> list[dict[str, Any]]:
    """The ``[[supports]]`` array: ``at``, ``kind`` (``pin``, ``clamp``, ``roller``), ``axis``
    (roller), ``position`` and ``direction`` (clamp) of the installed support, and (rods)
    ``fix_twist``; ``label`` keeps ``at`` as written (reaction columns)."""
    if not isinstance(raw, list):
        raise _err(path, "supports", "must be an array of tables [[supports]]")
    out = []
    for i, sp in enumerate(raw):
        key = f"supports[{i}]"
        t = _table(
            path, key, sp, {"at": _REQ, "kind": "pin", "fix_twist": False, "position": None,
                            "direction": None, "axis": None},
        )  # fmt: skip
        t["label"] = t["at"]
        t["at"] = _place(path, f"{key}.at", t["at"])
        t["kind"] = _choice(path, f"{key}.kind", t["kind"], ("pin", "clamp", "roller"))
        if not isinstance(t["fix_twist"], bool):
            raise _err(path, f"{key}.fix_twist", f"must be true or false, got {t['fix_twist']!r}")
        if t["fix_twist"]:
            _rod_only(path, f"{key}.fix_twist", element)
        for k in ("position", "direction", "axis"):
            if t[k] is not None:
                t[k] = _vector(path, f"{key}.{k}", t[k], (dim,))
        if t["kind"] == "roller" and t["axis"] is None:
            raise _err(path, f"{key}.axis", "required for a roller (the direction it moves along)")
        if t["kind"] != "roller" and t["axis"] is not None:
            raise _err(path, f"{key}.axis", f'applies to kind = "roller" only, not {t["kind"]!r}')
        if t["kind"] != "clamp" and t["direction"] is not None:
            raise _err(
                path, f"{key}.direction", f'applies to kind = "clamp" only, not {t["kind"]!r}'
            )
        for k in ("direction", "axis"):
            if t[k] is not None and not any(x != 0.0 for x in t[k]):
                raise _err(path, f"{key}.{k}", "must be a nonzero vector")
        out.append(t)
    return out


def parse_point_loads(path: str, raw: Any, dim: int, element: str) -> list[dict[str, Any]]:
    """The ``[[loads.point]]`` array: ``at``, ``force`` and/or (rods) ``moment``, and
    ``frequency_hz``."""
    if not isinstance(raw, list):
        raise _err(path, "loads.point", "must be an array of tables [[loads.point]]")
    pts = []
    for i, pl in enumerate(raw):
        key = f"loads.point[{i}]"
        t = _table(path, key, pl, {"at": _REQ, "force": None, "moment": None, "frequency_hz": None})
        t["at"] = _place(path, f"{key}.at", t["at"])
        if t["force"] is None and t["moment"] is None:
            raise _err(path, f"{key}.force", "required key is missing (give force, moment or both)")
        if t["force"] is not None:
            t["force"] = _vector(path, f"{key}.force", t["force"], (dim,))
        if t["moment"] is not None:
            _rod_only(path, f"{key}.moment", element)
            t["moment"] = _vector(path, f"{key}.moment", t["moment"], (3,))
        if t["frequency_hz"] is not None:
            t["frequency_hz"] = _number(
                path, f"{key}.frequency_hz", t["frequency_hz"], positive=True
            )
        pts.append(t)
    return pts


def parse_initial_motion(path: str, raw: Any, dim: int) -> dict[str, Any] | None:
    """The ``[initial_motion]`` table (None when absent): ``v = velocity + ω × (x − about)``."""
    if raw is None:
        return None
    t = _table(
        path, "initial_motion", raw, {"velocity": None, "angular_velocity": None, "about": None}
    )
    if t["velocity"] is None and t["angular_velocity"] is None:
        raise _err(path, "initial_motion", "needs velocity and/or angular_velocity")
    for k in ("velocity", "about"):
        if t[k] is not None:
            t[k] = _vector(path, f"initial_motion.{k}", t[k], (dim,))
    w = t["angular_velocity"]
    if w is not None:
        key = "initial_motion.angular_velocity"
        if dim == 2:
            if isinstance(w, list):
                raise _err(path, key, f"must be a number in 2D (the rate about z), got {w!r}")
            t["angular_velocity"] = [_number(path, key, w)]
        else:
            t["angular_velocity"] = _vector(path, key, w, (3,))
    return t
