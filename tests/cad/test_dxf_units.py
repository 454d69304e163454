"""DXF units ($INSUNITS) are converted to metres with a note, and splines given by fit points
only are read as the cubic B-spline through them, with a note."""

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from rancf.cad import read_curves, write_curve
from rancf.cli import main
from rancf.geometry.nurbs import NurbsCurve
from rancf.post.checks import section_warnings
from rancf.scenario import load_scenario
from tests.cad.test_cad_files import _scenario

S = np.sqrt(0.5)
ARC = ([(0.5, 0, 0), (0.5, 0.5, 0), (0, 0.5, 0)], [1, S, 1], 2, [0, 0, 0, 1, 1, 1])


def _quarter_circle(path, scale, units):
    import ezdxf

    doc = ezdxf.new("R2000", units=units)
    pts, w, deg, knots = ARC
    doc.modelspace().add_rational_spline([tuple(scale * np.array(p)) for p in pts], w, deg, knots)
    doc.saveas(path)
    return path


def test_millimetres_are_converted_to_metres_with_a_note(tmp_path, capsys):
    mm = _quarter_circle(tmp_path / "arc_mm.dxf", 1000.0, 4)  # drawn in millimetres
    m = _quarter_circle(tmp_path / "arc_m.dxf", 1.0, 6)
    (a,), (b,) = read_curves(mm), read_curves(m)
    assert np.abs(a.curve.points - b.curve.points).max() < 1e-15  # 500 mm -> 0.5 m
    assert a.notes == (
        "arc_mm.dxf: $INSUNITS = 4 (millimeters): lengths converted to metres (× 0.001)",
    )
    assert b.notes == ()
    model = load_scenario(_scenario(tmp_path, "arc_mm.dxf", "0")).build_model()
    assert model.mesh.arc_lengths().sum() == pytest.approx(0.25 * np.pi, rel=1e-12)
    assert section_warnings(model) == list(a.notes)  # the run's one warning line
    assert main(["cad", "list", str(mm)]) == 0
    err = capsys.readouterr().err
    assert err == f"rancf: note: {a.notes[0]}\n"


def test_inches_and_files_rancf_writes(tmp_path):
    inch = _quarter_circle(tmp_path / "arc_in.dxf", 1.0 / 0.0254, 1)
    # 19.685... inches as the DXF text stores them (ezdxf writes 16 significant digits)
    assert np.abs(read_curves(inch)[0].curve.points[:, :2].max() - 0.5) < 1e-11
    c = NurbsCurve(2, ARC[3], np.array(ARC[0])[:, :2], ARC[1])
    back = read_curves(write_curve(tmp_path / "w.dxf", c))[0]  # written in metres, says so
    assert back.notes == () and np.abs(back.curve.points[:, :2] - c.points).max() == 0.0


def test_fit_point_spline_is_the_cubic_through_its_points(tmp_path):
    import ezdxf

    fit = [(0.0, 0.0, 0.0), (0.2, 0.1, 0.0), (0.45, 0.05, 0.0), (0.7, 0.2, 0.0), (1.0, 0.1, 0.0)]
    doc = ezdxf.new("R2000", units=5)  # centimetres
    doc.modelspace().add_spline(fit)  # fit points only, as CAD programs store a drawn spline
    doc.saveas(tmp_path / "fit.dxf")
    (c,) = read_curves(tmp_path / "fit.dxf")
    assert c.curve.degree == 3 and len(c.notes) == 2
    assert c.notes[1].startswith("fit.dxf: spline #") and "5 fit points only" in c.notes[1]
    lo, hi = c.curve.domain
    for p in 0.01 * np.array(fit[1:-1]):  # every inner fit point (in metres) lies on the curve
        u = np.linspace(lo, hi, 2001)
        k = int(np.argmin(np.linalg.norm(c.curve(u) - p, axis=1)))
        res = minimize_scalar(
            lambda x, p=p: np.linalg.norm(c.curve(np.array([x]))[0] - p),
            bounds=(u[max(k - 1, 0)], u[min(k + 1, 2000)]),
            method="bounded",
            options={"xatol": 1e-14},
        )
        assert res.fun < 1e-10
    ends = c.curve(np.array([lo, hi]))
    assert np.abs(ends - 0.01 * np.array([fit[0], fit[-1]])).max() < 1e-15
