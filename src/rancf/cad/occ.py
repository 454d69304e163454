"""STEP and IGES curves through OpenCASCADE (cadquery-ocp, the optional extra ``rancf[cad]``).

Reading: every edge of the file's shapes, in file order, becomes a NURBS curve —
``Geom_BSplineCurve`` as stored (cut to the edge's parameter range by exact knot insertion when
the edge uses only part of it, or when the curve is periodic: a closed curve opens at its seam
into a clamped one, the seam pole stored at both ends); lines, circles, ellipses and other
conics are converted exactly by ``GeomConvert`` (rational quadratic B-splines); degree-1
curves are raised to degree 2.  Lengths are converted to metres (``xstep.cascade.unit = M``).

Writing: one ``Geom_BSplineCurve`` edge, length unit metre, reals printed with ``%.17G`` instead
of OpenCASCADE's default 12 digits (``StepData_StepWriter``/``IGESData_IGESWriter`` float
writer), so that reading the file back gives the same doubles.
"""

from __future__ import annotations

import io
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Literal

import numpy as np

from rancf.atomic import atomic_write
from rancf.cad.curve import CadCurve, file_curve
from rancf.errors import InputError
from rancf.extras import require
from rancf.geometry.nurbs import NurbsCurve

__all__ = ["read_occ", "write_occ"]

Kind = Literal["step", "iges"]


def _ocp() -> Any:
    ocp = require("OCP", "cad", "STEP and IGES files")
    from OCP.Message import Message, Message_Gravity

    printers = Message.DefaultMessenger_s().Printers()  # silence OpenCASCADE's console banners
    for k in range(1, printers.Length() + 1):
        printers.Value(k).SetTraceLevel(Message_Gravity.Message_Fail)
    return ocp


def _arrays() -> tuple[Any, Any, Any]:
    try:  # OCP >= 7.8 with NCollection templates bound as OCP.collections
        from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int

        return Array1_gp_Pnt, Array1_double, Array1_int
    except ImportError:  # pragma: no cover - older OCP
        from OCP.TColgp import TColgp_Array1OfPnt
        from OCP.TColStd import TColStd_Array1OfInteger, TColStd_Array1OfReal

        return TColgp_Array1OfPnt, TColStd_Array1OfReal, TColStd_Array1OfInteger


def _to_geom(curve: NurbsCurve) -> Any:
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt

    arr_pnt, arr_real, arr_int = _arrays()
    pts = (
        curve.points if curve.dim == 3 else np.column_stack([curve.points, np.zeros(curve.n_ctrl)])
    )
    poles = arr_pnt(1, curve.n_ctrl)
    weights = arr_real(1, curve.n_ctrl)
    for i, (p, w) in enumerate(zip(pts, curve.weights, strict=True)):
        poles.SetValue(i + 1, gp_Pnt(float(p[0]), float(p[1]), float(p[2])))
        weights.SetValue(i + 1, float(w))
    values, mult = np.unique(curve.knots, return_counts=True)
    knots, mults = arr_real(1, values.size), arr_int(1, values.size)
    for i, (v, m) in enumerate(zip(values, mult, strict=True)):
        knots.SetValue(i + 1, float(v))
        mults.SetValue(i + 1, int(m))
    return Geom_BSplineCurve(poles, weights, knots, mults, curve.degree, False, False)


def _from_geom(b: Any, path: Path, index: int) -> NurbsCurve:
    n = b.NbPoles()
    pts = np.array([[b.Pole(i).X(), b.Pole(i).Y(), b.Pole(i).Z()] for i in range(1, n + 1)])
    w = np.array([b.Weight(i) for i in range(1, n + 1)])
    kn = [b.Knot(i) for i in range(1, b.NbKnots() + 1)]
    mu = [b.Multiplicity(i) for i in range(1, b.NbKnots() + 1)]
    return file_curve(path, index, int(b.Degree()), np.repeat(kn, mu), pts, w)


@contextmanager
def _statics() -> Iterator[Callable[[str, str | int], None]]:
    """Set OpenCASCADE's process-wide translator parameters for one read or write and restore
    the previous values afterwards (other OpenCASCADE users in the process are unaffected)."""
    from OCP.Interface import Interface_Static

    saved: list[tuple[str, str | int]] = []

    def put(key: str, value: str | int) -> None:
        if isinstance(value, int):
            saved.append((key, Interface_Static.IVal_s(key)))
            ok = Interface_Static.SetIVal_s(key, value)
        else:
            saved.append((key, Interface_Static.CVal_s(key)))
            ok = Interface_Static.SetCVal_s(key, value)
        if not ok:  # pragma: no cover - OCP API change
            raise RuntimeError(f"OpenCASCADE did not accept {key} = {value}")

    try:
        yield put
    finally:
        for key, value in reversed(saved):
            if isinstance(value, int):
                Interface_Static.SetIVal_s(key, value)
            else:
                Interface_Static.SetCVal_s(key, value)


def write_occ(path: Path, curve: NurbsCurve, kind: Kind, name: str = "") -> None:
    """Write ``curve`` as one edge of a new STEP (AP214) or IGES file, lengths in metres."""
    _ocp()
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge

    with _statics() as put:
        edge = BRepBuilderAPI_MakeEdge(_to_geom(curve)).Edge()
        buf = io.BytesIO()
        if kind == "step":
            from OCP.StepAP214 import StepAP214
            from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer
            from OCP.StepData import StepData_StepWriter
            from OCP.TCollection import TCollection_HAsciiString

            w = STEPControl_Writer()  # registers the static parameters set next
            put("xstep.cascade.unit", "M")
            put("write.step.unit", "M")
            w.Transfer(edge, STEPControl_AsIs)
            model = w.Model()
            if name:
                for i in range(1, model.NbEntities() + 1):
                    ent = model.Value(i)
                    if ent.DynamicType().Name() == "StepGeom_TrimmedCurve":
                        ent.SetName(TCollection_HAsciiString(name))
            sw = StepData_StepWriter(model)
            sw.FloatWriter().SetFormat("%.17G", True)
            sw.SendModel(StepAP214.Protocol_s())
            ok = sw.Print(buf)
        else:
            from OCP.GeomToIGES import GeomToIGES_GeomCurve
            from OCP.IGESControl import IGESControl_Writer
            from OCP.IGESData import IGESData_IGESWriter
            from OCP.IGESSelect import IGESSelect_WorkLibrary

            w = IGESControl_Writer("M", 0)
            put("xstep.cascade.unit", "M")
            gs = w.Model().GlobalSection()
            gs.SetCascadeUnit(1000.0)  # our lengths are metres (1000 mm); no rescaling on output
            w.Model().SetGlobalSection(gs)
            # the curve itself as entity 126: no shape processing, which splits curves at C1 knots
            geom = _to_geom(curve)
            conv = GeomToIGES_GeomCurve()
            conv.SetModel(w.Model())
            conv.SetUnit(1.0)  # file unit = model unit (metre)
            ent = conv.TransferCurve(geom, geom.FirstParameter(), geom.LastParameter())
            if name:
                _name_iges_entity(ent, name)
            w.AddEntity(ent)
            w.ComputeModel()
            iw = IGESData_IGESWriter(w.Model())
            iw.FloatWriter().SetFormat("%.17G", True)
            iw.SendModel(IGESSelect_WorkLibrary.DefineProtocol_s())
            ok = iw.Print(buf)
    if not ok:
        raise InputError("--nurbs", str(path), f"a {kind.upper()} file OpenCASCADE can write")
    data = buf.getvalue()
    atomic_write(path, data)


def _name_iges_entity(ent: Any, name: str) -> None:
    """Give an IGES entity ``name``: as its 8-character entity label and, whole, as a Name
    property (entity 406, form 15), which IGES readers show as the entity's name."""
    from OCP.IGESBasic import IGESBasic_Name
    from OCP.TCollection import TCollection_HAsciiString

    ent.SetLabel(TCollection_HAsciiString(name[:8]))
    prop = IGESBasic_Name()
    prop.Init(1, TCollection_HAsciiString(name))
    ent.AddProperty(prop)


def _entity_name(ent: Any) -> str:
    """The name of the file entity an edge came from: a STEP item's name; an IGES entity's
    Name property (406-15) or else its entity label; "" when it has none."""
    if ent is None:
        return ""
    try:
        if hasattr(ent, "HasName"):  # IGES
            if ent.HasName():
                return str(ent.NameValue().ToCString()).strip()
            return str(ent.ShortLabel().ToCString()).strip() if ent.HasShortLabel() else ""
        if hasattr(ent, "Name"):  # STEP representation items
            return str(ent.Name().ToCString()).strip()
    except AttributeError:  # an entity without a name string
        return ""
    return ""


def _edge_curve(edge: Any) -> Any:
    from OCP.BRep import BRep_Tool
    from OCP.Geom import Geom_BSplineCurve, Geom_TrimmedCurve
    from OCP.GeomConvert import GeomConvert
    from OCP.TopAbs import TopAbs_REVERSED
    from OCP.TopoDS import TopoDS

    edge = (getattr(TopoDS, "Edge_s", None) or TopoDS.Edge)(edge)  # Edge_s before OCP 8
    crv = BRep_Tool.Curve_s(edge, 0.0, 0.0)
    f, last = BRep_Tool.Range_s(edge)
    if isinstance(crv, Geom_TrimmedCurve):
        crv = crv.BasisCurve()
    if isinstance(crv, Geom_BSplineCurve):
        b = Geom_BSplineCurve(crv)  # copy
        tol = 1e-12 * max(1.0, abs(b.LastParameter() - b.FirstParameter()))
        # A periodic curve (STEP readers make one of every closed B-spline, our own exported
        # rings included) stores its seam pole once and its knots cyclically: ``Segment`` opens
        # it by exact knot insertion into the clamped curve of the edge's range.
        if b.IsPeriodic() or f > b.FirstParameter() + tol or last < b.LastParameter() - tol:
            b.Segment(f, last)
    else:
        b = GeomConvert.CurveToBSplineCurve_s(Geom_TrimmedCurve(crv, f, last))
    if b.Degree() < 2:
        b.IncreaseDegree(2)
    if edge.Orientation() == TopAbs_REVERSED:
        b.Reverse()
    return b


def read_occ(path: Path, kind: Kind) -> list[CadCurve]:
    """Every edge curve of a STEP or IGES file as a NURBS curve (metres), in file order."""
    _ocp()
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer

    with _statics() as put:
        if kind == "step":
            from OCP.STEPControl import STEPControl_Reader

            reader = STEPControl_Reader()
        else:
            from OCP.IGESControl import IGESControl_Reader

            reader = IGESControl_Reader()
            # keep B-splines whole (the default splits them at knots of low continuity)
            put("read.iges.bspline.continuity", 0)
        put("xstep.cascade.unit", "M")
        if reader.ReadFile(str(path)) != IFSelect_RetDone:
            raise InputError("file", str(path), f"a readable {kind.upper()} file")
        reader.TransferRoots()
        transfer = reader.WS().TransferReader()
        out: list[CadCurve] = []
        for s in range(1, reader.NbShapes() + 1):
            ex = TopExp_Explorer(reader.Shape(s), TopAbs_EDGE)
            while ex.More():
                edge = ex.Current()
                name = _entity_name(transfer.EntityFromShapeResult(edge, 1))
                out.append(CadCurve(len(out), name, _from_geom(_edge_curve(edge), path, len(out))))
                ex.Next()
    return out
