"""The scenario format as a JSON Schema (draft 2020-12), for editors that check TOML files.

``rancf schema`` prints :func:`scenario_schema`.  The schema describes the same tables and keys as
:func:`rancf.model.scenario.parse_scenario` (a test checks that the two agree); the parser stays
the authority for checks a schema cannot express (e.g. ``step <= t_end``, node indices against
the mesh).
"""

from __future__ import annotations

from typing import Any

from rancf.model.analysis import MAX_LOAD_STEPS, MAX_NEWTON
from rancf.model.scenario_sensors import SENSOR_KINDS
from rancf.model.scenario_tables import ELEMENTS, GEOMETRY_KEYS, K_RANGE, MAX_ELEMENTS

__all__ = ["scenario_schema"]

_NUM = {"type": "number"}
_POS = {"type": "number", "exclusiveMinimum": 0}
_PLACE = {
    "description": '"start", "end" or a node index (negative counts from the end)',
    "oneOf": [{"enum": ["start", "end"]}, {"type": "integer"}],
}


def _vec(sizes: tuple[int, ...] = (2, 3)) -> dict[str, Any]:
    return {"type": "array", "items": _NUM, "minItems": min(sizes), "maxItems": max(sizes)}


def _table(props: dict[str, Any], required: tuple[str, ...] = (), **extra: Any) -> dict[str, Any]:
    out: dict[str, Any] = {"type": "object", "properties": props, "additionalProperties": False}
    if required:
        out["required"] = list(required)
    return {**out, **extra}


_GEOMETRY_PROPS: dict[str, Any] = {
    "start": {**_vec(), "description": "start point; 2 coordinates: planar, 3: spatial"},
    "end": _vec(),
    "angles_deg": {**_vec((2,)), "description": "tangent-to-chord angles in (0, 90) degrees"},
    "point": {**_vec(), "description": "an interior point of the arc, global coordinates"},
    "degree": {"type": "integer", "minimum": 2, "maximum": 3},
    "knots": {"type": "array", "items": _NUM},
    "control_points": {"type": "array", "items": _vec(), "minItems": 3},
    "weights": {"type": "array", "items": _POS},
    "file": {"type": "string", "description": "CAD file (STEP, IGES, DXF, geomdl JSON)"},
    "curve": {
        "description": "curve index or name in the file, or a list of them forming a chain",
        "oneOf": [
            {"type": "integer", "minimum": 0},
            {"type": "string"},
            {"type": "array", "items": {"type": ["integer", "string"]}, "minItems": 1},
        ],
    },
}
_REQUIRED = {"conic": GEOMETRY_KEYS["conic"], "line": ("start", "end")}
_REQUIRED["nurbs"] = ("degree", "knots", "control_points")
_REQUIRED["cad"] = ("file",)


def _geometry() -> dict[str, Any]:
    kinds = []
    for kind, keys in GEOMETRY_KEYS.items():
        props = {"kind": {"const": kind}, **{k: _GEOMETRY_PROPS[k] for k in keys}}
        kinds.append(_table(props, ("kind", *_REQUIRED[kind])))
    return {"oneOf": kinds, "description": "the cable's reference geometry"}


def scenario_schema() -> dict[str, Any]:
    """JSON Schema of a scenario file (the TOML document as JSON)."""
    lo, hi = K_RANGE
    mesh = _table(
        {
            "elements": {"type": "integer", "minimum": 1, "maximum": MAX_ELEMENTS},
            "element": {
                "enum": list(ELEMENTS),
                "default": "rancf",
                "description": '"rod": spatial rod with torsion (3D geometry only)',
            },
            "k": {
                "oneOf": [{"const": "opt"}, {"type": "number", "minimum": lo, "maximum": hi}],
                "default": "opt",
            },
            "spacing": {"enum": ["arc", "parameter"], "default": "arc"},
            "quadrature_points": {
                "type": "integer",
                "minimum": 2,
                "maximum": 64,
                "description": "default: 6 for polynomial (ANCF) elements, 10 for rational ones",
            },
        },
        ("elements",),
    )
    section = _table(
        {
            "radius": _POS,
            "area": _POS,
            "inertia": _POS,
            "inertia_y": {**_POS, "description": "rods: about the first principal axis"},
            "inertia_z": {**_POS, "description": "rods: about the second principal axis"},
            "orientation": {
                **_vec((3,)),
                "description": "rods: the first principal axis at the first node",
            },
            "torsion_constant": {**_POS, "description": "rods; default inertia_y + inertia_z"},
            "rotary_inertia": {
                "enum": ["torsion", "full"],
                "default": "torsion",
                "description": 'rods: "full" adds rho I of both bending directions',
            },
        },
        oneOf=[
            {"required": ["radius"]},
            {"required": ["area", "inertia"]},
            {"required": ["area", "inertia_y", "inertia_z", "orientation"]},
        ],
    )
    point_load = _table(
        {
            "at": _PLACE,
            "force": _vec(),
            "moment": {**_vec((3,)), "description": "rods: a point moment [N m]"},
            "frequency_hz": _POS,
        },
        ("at",),
        anyOf=[{"required": ["force"]}, {"required": ["moment"]}],
    )
    solver = _table(
        {
            "t_end": {**_POS, "default": 1.0},
            "step": {**_POS, "default": 1e-3, "description": "(initial) time step, <= t_end"},
            "rho_inf": {"type": "number", "minimum": 0, "maximum": 1, "default": 0.9},
            "load_steps": {
                "type": "integer",
                "minimum": 1,
                "maximum": MAX_LOAD_STEPS,
                "default": 10,
            },
            "adaptive": {"type": "boolean", "default": False},
            "rtol": {**_POS, "default": 1e-5},
            "output_step": {**_POS, "description": "default: step; <= t_end"},
            "min_step": {**_POS, "description": "default: step / 1024; <= step"},
            "newton_tol": {**_POS, "default": 1e-10},
            "max_newton": {
                "type": "integer",
                "minimum": 1,
                "maximum": MAX_NEWTON,
                "default": 12,
            },
            "newton": {"enum": ["full", "modified"], "default": "full"},
            "static_method": {
                "enum": ["load", "arc_length"],
                "default": "load",
                "description": "statics: adaptive load increments or arc length (limit points)",
            },
            "initial_state": {
                "enum": ["reference", "static"],
                "default": "reference",
                "description": "simulate: start from the reference or the static equilibrium",
            },
        }
    )
    sensor = _table(
        {
            "name": {"type": "string", "pattern": "^[A-Za-z_][A-Za-z0-9_]*$"},
            "kind": {
                "enum": list(SENSOR_KINDS),
                "description": '"twist" (rods): the nodal twist angle [rad]; '
                '"angular_momentum" (about `about`) and "energy": of the whole model',
            },
            "between": {"type": "array", "items": _PLACE, "minItems": 2, "maxItems": 2},
            "at": _PLACE,
            "about": {**_vec(), "description": "angular_momentum: the point (default origin)"},
        },
        ("name", "kind"),
    )
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "rancf scenario",
        "description": "A model and its analysis (TOML). See the rancf README.",
        **_table(
            {
                "geometry": _geometry(),
                "mesh": mesh,
                "section": section,
                "material": _table(
                    {
                        "density": _POS,
                        "youngs_modulus": _POS,
                        "shear_modulus": {**_POS, "description": "rods (or poisson_ratio)"},
                        "poisson_ratio": {
                            "type": "number",
                            "exclusiveMinimum": -1,
                            "exclusiveMaximum": 0.5,
                            "description": "rods (or shear_modulus): G = E / (2 (1 + ν))",
                        },
                    },
                    ("density", "youngs_modulus"),
                ),
                "supports": {
                    "type": "array",
                    "items": _table(
                        {
                            "at": _PLACE,
                            "kind": {"enum": ["pin", "clamp", "roller"], "default": "pin"},
                            "fix_twist": {
                                "type": "boolean",
                                "default": False,
                                "description": "rods: also hold the twist (a clamp holds it)",
                            },
                            "position": {
                                **_vec(),
                                "description": "installed position (default: the reference)",
                            },
                            "direction": {
                                **_vec(),
                                "description": "clamp: installed tangent (default: reference)",
                            },
                            "axis": {**_vec(), "description": "roller: the line it moves along"},
                        },
                        ("at",),
                    ),
                },
                "loads": _table(
                    {"gravity": _vec(), "point": {"type": "array", "items": point_load}}
                ),
                "damping": _table({"mass_proportional": {"type": "number", "minimum": 0}}),
                "initial_velocity": {
                    "type": "array",
                    "items": _table({"at": _PLACE, "value": _vec()}, ("at", "value")),
                },
                "initial_motion": _table(
                    {
                        "velocity": _vec(),
                        "angular_velocity": {
                            "oneOf": [{"type": "number"}, _vec((3,))],
                            "description": "3 components in 3D, the rate about z in 2D [rad/s]",
                        },
                        "about": {**_vec(), "description": "default: the origin"},
                    },
                    description="a rigid-body velocity v0 + w x (x - about) on every coordinate",
                ),
                "solver": solver,
                "modes": _table(
                    {
                        "count": {"type": "integer", "minimum": 1, "default": 6},
                        "about": {"enum": ["reference", "static"], "default": "reference"},
                    }
                ),
                "sensors": {"type": "array", "items": sensor},
            },
            ("geometry", "mesh", "section", "material"),
        ),
    }
