"""DXF ``SPLINE`` entities through ezdxf.  Curves are named by their entity handle; planar
curves get ``z = 0``.

* Units: the header's ``$INSUNITS`` (the drawing's length unit, e.g. 4 = millimetres) scales
  the control points to metres (``ezdxf.units.conversion_factor``), and every curve read so
  carries a one-line note saying so (:attr:`~rancf.cad.curve.CadCurve.notes`).  A file without
  units (``$INSUNITS`` = 0 or absent) is read as metres.
* A spline given by fit points only (no control points) is the cubic B-spline that interpolates
  them as CAD programs construct it (ezdxf's ``Spline.construction_tool``: global interpolation
  with chord-length parameters and the file's end tangents, if it gives both); its note says
  the control points were constructed.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from rancf.atomic import atomic_path
from rancf.cad.curve import CadCurve, file_curve
from rancf.errors import InputError, shorten
from rancf.geometry.nurbs import NurbsCurve

__all__ = ["read_dxf", "write_dxf", "dxf_unit_scale"]


def dxf_unit_scale(doc: Any, path: Path) -> tuple[float, str]:
    """Metres per drawing unit of ``doc`` (``$INSUNITS``) and the note saying so ("" for
    metres or no units)."""
    from ezdxf import units

    code = doc.header.get("$INSUNITS", 0)
    if not code or code == units.M:
        return 1.0, ""
    try:
        scale = float(units.conversion_factor(units.InsertUnits(code), units.InsertUnits.Meters))
        name = units.unit_name(code).lower()
    except (KeyError, ValueError, TypeError):
        allowed = "a length unit of the DXF standard (0 = none, 1 = inches, 4 = millimetres, ...)"
        raise InputError(f"{path}: $INSUNITS", code, allowed) from None
    return scale, (
        f"{path.name}: $INSUNITS = {code} ({name}): lengths converted to metres (× {scale:g})"
    )


def _spline(e: Any) -> tuple[int, Any, Any, Any, bool]:
    """Degree, knots, control points and weights of a SPLINE, and whether they were built from
    fit points (module docstring)."""
    if e.control_point_count():
        w = np.asarray(list(e.weights), dtype=float)
        pts = np.array([tuple(p) for p in e.control_points], dtype=float)
        return int(e.dxf.degree), np.asarray(list(e.knots), dtype=float), pts, w, False
    bs = e.construction_tool()  # fit points only: the CAD programs' cubic interpolation
    pts = np.array([tuple(p) for p in bs.control_points], dtype=float)
    w = np.asarray(bs.weights(), dtype=float)
    return int(bs.degree), np.asarray(bs.knots(), dtype=float), pts, w, True


def read_dxf(path: Path) -> list[CadCurve]:
    """Every ``SPLINE`` of the model space with control points or fit points, in file order,
    in metres (module docstring)."""
    import ezdxf
    from ezdxf.entities import Spline

    try:
        doc = ezdxf.readfile(str(path))
    except (OSError, ezdxf.DXFError) as exc:
        why = shorten(" ".join(str(exc).split()))
        raise InputError("file", str(path), f"a readable DXF file ({why})") from None
    scale, unit_note = dxf_unit_scale(doc, path)
    out: list[CadCurve] = []
    for e in doc.modelspace().query("SPLINE"):
        assert isinstance(e, Spline)  # the query's entities
        if not e.control_point_count() and e.fit_point_count() < 2:
            continue
        degree, knots, pts, w, fitted = _spline(e)
        if w.size == 0:
            w = np.ones(pts.shape[0])
        curve = file_curve(path, len(out), degree, knots, scale * pts, w)
        notes: tuple[str, ...] = (unit_note,) if unit_note else ()
        if fitted:
            notes += (
                f"{path.name}: spline #{e.dxf.handle} is given by {e.fit_point_count()} "
                "fit points only: its control points are those of the cubic B-spline "
                "through them, as CAD programs construct it",
            )
        out.append(CadCurve(len(out), f"#{e.dxf.handle}", curve, notes))
    return out


def write_dxf(path: Path, curve: NurbsCurve) -> None:
    """Write one (rational) ``SPLINE`` to a new DXF R2000 file in metres (``$INSUNITS`` = 6),
    atomically."""
    import ezdxf
    from ezdxf import units

    pts = curve.points
    if curve.dim == 2:
        pts = np.column_stack([pts, np.zeros(pts.shape[0])])
    doc = ezdxf.new("R2000", units=units.M)
    msp = doc.modelspace()
    if np.all(curve.weights == 1.0):
        msp.add_open_spline(pts.tolist(), curve.degree, curve.knots.tolist())
    else:
        msp.add_rational_spline(
            pts.tolist(), curve.weights.tolist(), curve.degree, curve.knots.tolist()
        )
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
