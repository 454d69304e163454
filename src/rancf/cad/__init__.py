"""CAD files in and out: B-spline/NURBS curves of STEP, IGES, DXF and geomdl JSON files.

* ``.json`` — geomdl's exchange format (``{"shape": {"type": "curve", "data": [...]}}``);
* ``.dxf`` — ``SPLINE`` entities, through ezdxf;
* ``.step``/``.stp`` and ``.igs``/``.iges`` — through cadquery-ocp (OpenCASCADE), the optional
  extra ``pip install 'rancf[cad]'``.  Lengths are in metres (files in other units are converted
  on reading; files are written in metres), and reals are written with 17 significant digits so
  that a round trip reproduces the curve to round-off.

Every reader returns :class:`CadCurve` records in file order; every writer writes one curve
atomically, with the umask's permissions (:mod:`rancf.atomic`).
"""

from __future__ import annotations

from pathlib import Path

from rancf.cad.curve import CadCurve, file_curve
from rancf.errors import InputError
from rancf.geometry.nurbs import NurbsCurve

__all__ = [
    "CadCurve",
    "file_curve",
    "read_curves",
    "write_curve",
    "READ_SUFFIXES",
    "WRITE_SUFFIXES",
]

READ_SUFFIXES = (".json", ".dxf", ".step", ".stp", ".igs", ".iges")
WRITE_SUFFIXES = READ_SUFFIXES


def _suffix(path: Path, allowed: tuple[str, ...], what: str) -> str:
    s = path.suffix.lower()
    if s not in allowed:
        raise InputError(what, str(path), f"a file ending in {', '.join(allowed)}")
    return s


def read_curves(path: str | Path) -> list[CadCurve]:
    """All B-spline/NURBS curves of a CAD file, in file order.

    Raises
    ------
    InputError
        Unknown suffix, unreadable file, or no curve in it.
    MissingExtraError
        STEP/IGES without cadquery-ocp installed.
    """
    p = Path(path)
    s = _suffix(p, READ_SUFFIXES, "file")
    if not p.is_file():
        raise InputError("file", str(p), "an existing, readable CAD file")
    if s == ".json":
        from rancf.cad.geomdl_json import read_json

        curves = read_json(p)
    elif s == ".dxf":
        from rancf.cad.dxf import read_dxf

        curves = read_dxf(p)
    else:
        from rancf.cad.occ import read_occ

        curves = read_occ(p, "step" if s in (".step", ".stp") else "iges")
    if not curves:
        raise InputError("file", str(p), "a CAD file holding at least one B-spline/NURBS curve")
    return curves


def write_curve(path: str | Path, curve: NurbsCurve, name: str = "") -> Path:
    """Write ``curve`` as the only curve of a new CAD file (format from the suffix)."""
    p = Path(path)
    s = _suffix(p, WRITE_SUFFIXES, "--nurbs")
    if not p.parent.is_dir():
        raise InputError("--nurbs", str(p), "a file in an existing directory")
    if s == ".json":
        from rancf.cad.geomdl_json import write_json

        write_json(p, curve, name)
    elif s == ".dxf":
        from rancf.cad.dxf import write_dxf

        write_dxf(p, curve)
    else:
        from rancf.cad.occ import write_occ

        write_occ(p, curve, "step" if s in (".step", ".stp") else "iges", name)
    return p
