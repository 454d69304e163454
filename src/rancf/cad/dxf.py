"""DXF ``SPLINE`` entities through ezdxf (control points, knots, weights; fit-point-only splines
are not read).  Curves are named by their entity handle; planar curves get ``z = 0``."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rancf.atomic import atomic_path
from rancf.cad.curve import CadCurve, file_curve
from rancf.errors import InputError, shorten
from rancf.geometry.nurbs import NurbsCurve

__all__ = ["read_dxf", "write_dxf"]


def read_dxf(path: Path) -> list[CadCurve]:
    """Every ``SPLINE`` of the model space with control points, in file order."""
    import ezdxf

    try:
        doc = ezdxf.readfile(str(path))
    except (OSError, ezdxf.DXFError) as exc:
        why = shorten(" ".join(str(exc).split()))
        raise InputError("file", str(path), f"a readable DXF file ({why})") from None
    out = []
    for e in doc.modelspace().query("SPLINE"):
        pts = np.array([tuple(p) for p in e.control_points], dtype=float)
        if pts.shape[0] == 0:
            continue
        w = np.asarray(list(e.weights), dtype=float)
        if w.size == 0:
            w = np.ones(pts.shape[0])
        knots = np.asarray(list(e.knots), dtype=float)
        curve = file_curve(path, len(out), int(e.dxf.degree), knots, pts, w)
        out.append(CadCurve(len(out), f"#{e.dxf.handle}", curve))
    return out


def write_dxf(path: Path, curve: NurbsCurve) -> None:
    """Write one (rational) ``SPLINE`` to a new DXF R2000 file (atomically)."""
    import ezdxf

    pts = curve.points
    if curve.dim == 2:
        pts = np.column_stack([pts, np.zeros(pts.shape[0])])
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    if np.all(curve.weights == 1.0):
        msp.add_open_spline(pts.tolist(), curve.degree, curve.knots.tolist())
    else:
        msp.add_rational_spline(
            pts.tolist(), curve.weights.tolist(), curve.degree, curve.knots.tolist()
        )
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
