"""geomdl's JSON exchange format (NURBS-Python ``exchange.export_json``/``import_json``).

``{"shape": {"type": "curve", "count": n, "data": [{"degree": p, "knotvector": [...],
"control_points": {"points": [[x, y(, z)], ...], "weights": [...]}, "name": "..."}]}}`` with
Cartesian (not weighted) control points; Python's ``repr`` of floats makes the round trip exact.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from rancf.atomic import atomic_write
from rancf.cad.curve import CadCurve, file_curve
from rancf.errors import InputError, shorten
from rancf.geometry.nurbs import NurbsCurve

__all__ = ["read_json", "write_json", "curve_dict"]


def curve_dict(curve: NurbsCurve, name: str = "") -> dict[str, Any]:
    """The geomdl dictionary of one curve."""
    rational = bool(np.any(curve.weights != curve.weights[0]))
    d: dict[str, Any] = {
        "type": "spline",
        "rational": rational,
        "dimension": curve.dim,
        "degree": curve.degree,
        "knotvector": curve.knots.tolist(),
        "control_points": {"points": curve.points.tolist(), "weights": curve.weights.tolist()},
    }
    if name:
        d["name"] = name
    return d


def write_json(path: Path, curve: NurbsCurve, name: str = "") -> None:
    """Write one curve in geomdl's JSON exchange format."""
    doc = {"shape": {"type": "curve", "count": 1, "data": [curve_dict(curve, name)]}}
    text = json.dumps(doc, indent=2, allow_nan=False) + "\n"  # a curve is finite
    atomic_write(path, text)


def read_json(path: Path) -> list[CadCurve]:
    """Read every curve of a geomdl JSON file."""
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
        shape = doc["shape"]
        if shape.get("type") != "curve":
            raise InputError("file", str(path), 'a geomdl JSON file of shape type "curve"')
        out = []
        for i, d in enumerate(shape["data"]):
            pts = np.asarray(d["control_points"]["points"], dtype=float)
            w = d["control_points"].get("weights")
            w = np.ones(len(pts)) if w is None else np.asarray(w, dtype=float)
            deg = d["degree"][0] if isinstance(d["degree"], list) else d["degree"]
            kv = d["knotvector"]
            kv = kv[0] if kv and isinstance(kv[0], list) else kv
            curve = file_curve(path, i, int(deg), kv, pts, w)
            out.append(CadCurve(i, str(d.get("name", "")), curve))
        return out
    except InputError:
        raise
    except RecursionError:
        raise InputError(
            "file", str(path), "a geomdl JSON curve file (nested too deeply)"
        ) from None
    except (OSError, ValueError, KeyError, TypeError, IndexError) as exc:
        why = shorten(f"{type(exc).__name__}: {' '.join(str(exc).split())}")
        raise InputError("file", str(path), f"a geomdl JSON curve file ({why})") from None
