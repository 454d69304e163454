"""CAD files in and out: round trips at 1e-12, files written by other tools, chains and kinks."""

import json

import numpy as np
import pytest

from rancf.cad import read_curves, write_curve
from rancf.cli import main
from rancf.elements.cad import bspline_to_ancf, chain_to_nurbs, nurbs_to_rancf
from rancf.errors import ScenarioError
from rancf.geometry.nurbs import NurbsCurve
from rancf.scenario import load_scenario
from tests.scenario.test_scenario import BASE

FIG5 = np.array([0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 5, 5, 5, 5], float)


def test_fig5_knot_vector_round_trip():
    rng = np.random.default_rng(3)
    pts = rng.normal(size=(10, 2))
    back = chain_to_nurbs(bspline_to_ancf(NurbsCurve.bspline(3, FIG5, pts)))
    assert np.array_equal(back.knots, FIG5)
    assert np.abs(back.points - pts).max() < 1e-14
    w = rng.uniform(0.3, 3.0, 10)
    back = chain_to_nurbs(nurbs_to_rancf(NurbsCurve(3, FIG5, pts, w)))
    assert np.array_equal(back.knots, FIG5)
    assert np.abs(back.weights / back.weights[0] - w / w[0]).max() < 1e-13


def test_knot_removal_keeps_a_real_kink():
    pts = np.array([[0, 0], [1, 0], [2, 0], [2, 0], [2, 1], [2, 2], [2, 3]], float)
    knots = [0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2]
    back = chain_to_nurbs(bspline_to_ancf(NurbsCurve.bspline(3, knots, pts)))
    assert np.array_equal(back.knots, knots)


@pytest.mark.parametrize("suffix", ["json", "dxf", "step", "stp", "igs", "iges"])
@pytest.mark.parametrize("dim", [2, 3])
def test_written_files_read_back_to_1e12(tmp_path, suffix, dim):
    rng = np.random.default_rng(dim)
    curve = NurbsCurve(3, FIG5, rng.normal(size=(10, dim)), rng.uniform(0.2, 5.0, 10))
    path = write_curve(tmp_path / f"c.{suffix}", curve, "route")
    (back,) = read_curves(path)
    u = np.linspace(0, 5, 501)
    x = back.curve(u)
    assert np.abs(x[:, :dim] - curve(u)).max() <= 1e-12 * np.abs(curve(u)).max()
    assert np.all(x[:, dim:] == 0)
    assert np.array_equal(back.curve.knots, FIG5)
    # DXF entities have no names: a SPLINE is named by its handle
    assert back.name == "route" if suffix != "dxf" else back.name.startswith("#")


@pytest.mark.parametrize("suffix", ["step", "igs"])
def test_long_curve_names_round_trip(tmp_path, suffix):
    # IGES: the whole name as a Name property (406-15), its first 8 characters as the label
    name = "hose route A, segment 2"
    curve = NurbsCurve(2, [0, 0, 0, 1, 1, 1], [[0, 0], [1, 1], [2, 0]], [1, 0.7, 1])
    (back,) = read_curves(write_curve(tmp_path / f"c.{suffix}", curve, name))
    assert back.name == name


def test_iges_entity_label_names_a_curve(tmp_path):
    # an IGES file written by OpenCASCADE directly, with only the 8-character entity label
    import io

    from OCP.GeomToIGES import GeomToIGES_GeomCurve
    from OCP.IGESControl import IGESControl_Writer
    from OCP.IGESData import IGESData_IGESWriter
    from OCP.IGESSelect import IGESSelect_WorkLibrary
    from OCP.TCollection import TCollection_HAsciiString

    from rancf.cad.occ import _to_geom

    curve = NurbsCurve(2, [0, 0, 0, 1, 1, 1], [[0, 0, 0], [1, 1, 0], [2, 0, 0]], [1, 0.7, 1])
    w = IGESControl_Writer("M", 0)
    conv = GeomToIGES_GeomCurve()
    conv.SetModel(w.Model())
    ent = conv.TransferCurve(_to_geom(curve), 0.0, 1.0)
    ent.SetLabel(TCollection_HAsciiString("HOSE1"))
    w.AddEntity(ent)
    w.ComputeModel()
    iw = IGESData_IGESWriter(w.Model())
    iw.SendModel(IGESSelect_WorkLibrary.DefineProtocol_s())
    buf = io.BytesIO()
    assert iw.Print(buf)
    (tmp_path / "label.igs").write_bytes(buf.getvalue())
    (back,) = read_curves(tmp_path / "label.igs")
    assert back.name == "HOSE1"


def test_geomdl_reads_our_json(tmp_path):
    from geomdl import exchange

    curve = NurbsCurve(3, FIG5, np.random.default_rng(1).normal(size=(10, 3)), np.ones(10))
    write_curve(tmp_path / "c.json", curve)
    (g,) = exchange.import_json(str(tmp_path / "c.json"))
    assert g.degree == 3
    u = np.linspace(0, 1, 11)  # geomdl normalizes the knot vector to [0, 1]
    pts = np.array([g.evaluate_single(float(x)) for x in u])
    assert np.abs(pts - curve(5 * u)).max() < 1e-12


def _other_tool_files(d):
    """Files written with ezdxf and OpenCASCADE directly (not through rancf)."""
    import ezdxf
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.GC import GC_MakeArcOfCircle
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pnt
    from OCP.IGESControl import IGESControl_Writer
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    s = np.sqrt(0.5)
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    # quarter circle r = 0.5 from (0.5, 0) to (0, 0.5), then a straight continuation to
    # (-0.3, 0.5) drawn backwards, then a spline with a kink at (0.3, 0.5)
    msp.add_rational_spline(
        [(0.5, 0, 0), (0.5, 0.5, 0), (0, 0.5, 0)], [1, s, 1], 2, [0, 0, 0, 1, 1, 1]
    )
    msp.add_open_spline(
        [(-0.3, 0.5, 0), (-0.2, 0.5, 0), (-0.1, 0.5, 0), (0, 0.5, 0)], 3, [0] * 4 + [1] * 4
    )
    kinked = [
        (0, 0.5, 0),
        (0.1, 0.5, 0),
        (0.2, 0.5, 0),
        (0.3, 0.5, 0),
        (0.3, 0.6, 0),
        (0.3, 0.7, 0),
    ]
    msp.add_open_spline(kinked + [(0.3, 0.8, 0)], 3, [0] * 4 + [1] * 3 + [2] * 4)
    doc.saveas(d / "route.dxf")
    circ = gp_Circ(gp_Ax2(gp_Pnt(0, 0, 0.2), gp_Dir(0, 0, 1)), 500.0)  # millimetres, at z = 0.2 mm
    edge = BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(circ, 0.0, np.pi / 3, True).Value()).Edge()
    w = STEPControl_Writer()
    w.Transfer(edge, STEPControl_AsIs)
    w.Write(str(d / "arc_mm.step"))
    iw = IGESControl_Writer("MM", 0)
    iw.AddShape(edge)
    iw.ComputeModel()
    iw.Write(str(d / "arc_mm.igs"))


CONIC = "start = [0.0, 0.0]\nend = [0.5, 0.0]\nangles_deg = [30.0, 40.0]\npoint = [0.315, 0.077]"
SCEN = BASE.replace('kind = "conic"\n' + CONIC, 'kind = "cad"\nfile = "FILE"\ncurve = CURVE')


def _scenario(d, file, curve, gravity="[0.0, -9.81]"):
    f = d / "cad.toml"
    text = SCEN.replace("FILE", file).replace("CURVE", curve)
    f.write_text(text.replace("gravity = [0.0, -9.81]", f"gravity = {gravity}"))
    return f


@pytest.fixture(scope="module")
def cad_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("cad")
    _other_tool_files(d)
    return d


@pytest.mark.parametrize("file", ["arc_mm.step", "arc_mm.igs"])
def test_other_tool_circle_meshes_exactly(cad_dir, file):
    model = load_scenario(_scenario(cad_dir, file, "0", "[0.0, 0.0, -9.81]")).build_model()
    mesh = model.mesh
    assert mesh.dim == 3 and mesh.n_elements == 3  # z = 0.2 mm: spatial
    pts = mesh.evaluate(np.linspace(0, 1, 41)).reshape(-1, 3)
    assert np.abs(np.linalg.norm(pts[:, :2], axis=1) - 0.5).max() < 1e-12 * 0.5
    assert np.abs(pts[:, 2] - 2e-4).max() < 1e-15
    assert mesh.arc_lengths().sum() == pytest.approx(0.5 * np.pi / 3, rel=1e-12)


def test_dxf_chain_is_one_exact_planar_mesh(cad_dir):
    model = load_scenario(_scenario(cad_dir, "route.dxf", "[0, 1]")).build_model()
    mesh = model.mesh
    assert mesh.dim == 2 and mesh.n_elements == 6
    assert np.allclose(mesh.nodes[[0, 3, 6], 0], [[0.5, 0], [0, 0.5], [-0.3, 0.5]], atol=1e-15)
    arc = mesh.evaluate(np.linspace(0, 1, 21))[:3].reshape(-1, 2)
    assert np.abs(np.linalg.norm(arc, axis=1) - 0.5).max() < 1e-15
    assert mesh.arc_lengths().sum() == pytest.approx(0.25 * np.pi + 0.3, rel=1e-12)


def test_kink_and_gap_are_reported_by_location(cad_dir):
    with pytest.raises(ScenarioError, match=r"kink of 90 deg at \(0\.3, 0\.5\) \(curve 2"):
        load_scenario(_scenario(cad_dir, "route.dxf", "[2]"))
    with pytest.raises(ScenarioError, match=r"kink of 180 deg at \(0, 0\.5\).*curve 0.*curve 2"):
        load_scenario(_scenario(cad_dir, "route.dxf", "[0, 2]"))
    with pytest.raises(ScenarioError, match=r"geometry.curve.*index in 0..2"):
        load_scenario(_scenario(cad_dir, "route.dxf", "7"))
    with pytest.raises(ScenarioError, match=r"geometry.file.*existing"):
        load_scenario(_scenario(cad_dir, "missing.dxf", "0"))


def test_cad_list(cad_dir, capsys):
    assert main(["cad", "list", str(cad_dir / "route.dxf")]) == 0
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 4 and "(0.5, 0, 0) -> (0, 0.5, 0)" in out[1]


def test_missing_ocp_message(monkeypatch, tmp_path, capsys):
    import sys

    monkeypatch.setitem(sys.modules, "OCP", None)
    (tmp_path / "x.step").write_text("ISO-10303-21;")
    assert main(["cad", "list", str(tmp_path / "x.step")]) == 2
    err = capsys.readouterr().err
    assert err == (
        "rancf: error: STEP and IGES files need the optional package 'OCP': "
        "pip install 'rancf[cad]'\n"
    )


def test_periodic_step_curve_opens_exactly(tmp_path):
    """A periodic B-spline of another tool (seam knot of multiplicity 1: the seam is no pole)
    is read as the clamped curve OpenCASCADE's own reader gives, on the same parameters."""
    pytest.importorskip("OCP")
    from OCP.BRep import BRep_Tool
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    from rancf.cad.occ import _arrays

    arr_pnt, arr_real, arr_int = _arrays()
    n = 7
    ang = 2 * np.pi * np.arange(n) / n
    pts = np.column_stack([0.3 * np.cos(ang), 0.2 * np.sin(ang), 0.01 * np.sin(3 * ang)])
    poles, weights = arr_pnt(1, n), arr_real(1, n)
    knots, mults = arr_real(1, n + 1), arr_int(1, n + 1)
    for i in range(n):
        poles.SetValue(i + 1, gp_Pnt(*(float(x) for x in pts[i])))
        weights.SetValue(i + 1, 1.0 + 0.3 * np.sin(ang[i]))
    for i, k in enumerate([0.0, 0.2, 0.6, 0.9, 1.2, 1.4, 1.7, 2.0]):
        knots.SetValue(i + 1, k)
        mults.SetValue(i + 1, 1)
    periodic = Geom_BSplineCurve(poles, weights, knots, mults, 3, True, False)
    w = STEPControl_Writer()  # OpenCASCADE's defaults: millimetres, 12 digits
    w.Transfer(BRepBuilderAPI_MakeEdge(periodic).Edge(), STEPControl_AsIs)
    w.Write(str(tmp_path / "loop.step"))
    r = STEPControl_Reader()  # what OpenCASCADE reads: a periodic curve (in millimetres)
    r.ReadFile(str(tmp_path / "loop.step"))
    r.TransferRoots()
    edge = (getattr(TopoDS, "Edge_s", None) or TopoDS.Edge)(
        TopExp_Explorer(r.Shape(1), TopAbs_EDGE).Current()
    )
    ref = BRep_Tool.Curve_s(edge, 0.0, 0.0)
    assert ref.IsPeriodic() and ref.NbPoles() == n
    (c,) = read_curves(tmp_path / "loop.step")  # was: 8 knots for 7 control points
    curve = c.curve
    assert curve.domain == (ref.FirstParameter(), ref.LastParameter())
    assert np.array_equal(curve.points[0], curve.points[-1])
    u = np.linspace(*curve.domain, 41)
    want = np.array([[ref.Value(x).X(), ref.Value(x).Y(), ref.Value(x).Z()] for x in u]) / 1e3
    assert np.abs(curve(u) - want).max() <= 1e-12 * 0.3


def test_invalid_curve_error_names_the_file(tmp_path, capsys):
    bad = tmp_path / "bad.json"
    curve = {
        "type": "spline",
        "degree": 2,
        "knotvector": [0, 0, 0, 1, 1],  # one knot short for 3 control points of degree 2
        "control_points": {"points": [[0, 0], [1, 1], [2, 0]]},
    }
    bad.write_text(json.dumps({"shape": {"type": "curve", "data": [curve]}}))
    assert main(["cad", "list", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    head = f"rancf: error: {bad}: curve 0: knots = [0., 0., 0., 1., 1.] is not allowed"
    assert err.startswith(head)
    assert err.endswith("6 knots for 3 control points of degree 2\n")
