"""Our own CAD export read back as ``kind = "cad"``: reference and deformed shapes of runs with
1 to 32 elements, in every format, mesh again without a false kink."""

from __future__ import annotations

import contextlib
import io

import numpy as np
import pytest

from rancf.cli import main
from rancf.geometry.tangents import vector_angle
from rancf.post.centerline import centerline_nodes
from rancf.post.system_run import load_run
from rancf.scenario import load_scenario
from tests.scenario.test_scenario import BASE

#: Every element count 1..32 is exported as JSON (the cheapest format); the other formats are
#: written for the counts that failed before (8, 16: a false kink of 8.5e-7 deg from arccos of a
#: dot product one unit of round-off below 1) and the ends of the range.
ALL_COUNTS = range(1, 33)
OTHER_FORMATS = {"dxf": (1, 8, 16, 32), "step": (8, 16), "igs": (8, 16)}


def _quiet(argv: list[str]) -> None:
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(argv) == 0, argv


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """A 0.02 s pendulum run (the short scenario of the docs) for every element count."""
    root = tmp_path_factory.mktemp("reimport")
    out = {}
    for n in ALL_COUNTS:
        d = root / f"n{n}"
        d.mkdir()
        (d / "s.toml").write_text(BASE.replace("elements = 3", f"elements = {n}"))
        _quiet(["simulate", str(d / "s.toml"), "--out", str(d / "run"), "--quiet"])
        out[n] = d
    return out


def _round_trip(d, suffix: str, time: str | None) -> None:
    """``rancf export --nurbs`` of the run, then the file as the geometry of a new scenario."""
    name = f"shape_{time or 'last'}.{suffix}"
    _quiet(
        ["export", str(d / "run"), "--nurbs", str(d / name), *(["--time", time] if time else [])]
    )
    sc = d / f"cad_{name}.toml"
    rest = BASE.split("[mesh]", 1)[1]
    sc.write_text(f'[geometry]\nkind = "cad"\nfile = "{name}"\n\n[mesh]{rest}')
    mesh = load_scenario(sc).build_model().mesh  # refused before as a kink of 8.5e-7 deg
    run = load_run(d / "run").body()
    ends = centerline_nodes(run, run.q[run.time_index(None if time is None else 0.0)])[[0, -1]]
    # the re-imported curve starts and ends where the exported shape does (and has its slopes)
    assert np.abs(mesh.nodes[[0, -1], 0] - ends[:, 0]).max() <= 1e-12
    for k in (0, -1):
        assert vector_angle(mesh.nodes[k, 1], ends[k, 1]) <= 1e-12


@pytest.mark.parametrize("time", ["0", None], ids=["reference", "deformed"])
def test_every_element_count_reimports_as_json(runs, time):
    for n in ALL_COUNTS:
        _round_trip(runs[n], "json", time)


@pytest.mark.parametrize("time", ["0", None], ids=["reference", "deformed"])
@pytest.mark.parametrize("suffix", sorted(OTHER_FORMATS))
def test_other_formats_reimport(runs, suffix, time):
    if suffix in ("step", "igs"):
        pytest.importorskip("OCP")
    for n in OTHER_FORMATS[suffix]:
        _round_trip(runs[n], suffix, time)


def test_vector_angle_is_accurate_near_zero():
    # arccos(cos θ) loses everything below ~1.5e-8 rad; atan2(|a x b|, a.b) keeps θ to round-off
    for theta in (0.0, 1e-15, 1e-12, 1e-9, 1e-6, 0.3, np.pi / 2, 3.0, np.pi):
        a = np.array([2.0, 0.0])
        b = 3.0 * np.array([np.cos(theta), np.sin(theta)])
        assert vector_angle(a, b) == pytest.approx(theta, rel=1e-12, abs=1e-300)
    assert vector_angle([1.0, 0.0, 0.0], [1.0, 1e-10, 0.0]) == pytest.approx(1e-10, rel=1e-12)
    # one unit of round-off in a tangent's direction is no kink
    t = np.array([0.6, 0.8])
    assert vector_angle(t, np.nextafter(t, 1.0)) < 1e-15


#: A free ring (the shipped example ``ring``, 8 elements, a short run): a closed curve, whose
#: first control point is its last.  STEP readers make a periodic B-spline of it (seam pole
#: stored once, knots cyclic), which was read back as 148 knots for 144 control points.
RING = """
[geometry]
kind = "ellipse"
center = [0.0, 0.0]
semi_axes = [1.0, 1.0]

[mesh]
elements = 8
element = "rancf"

[section]
radius = 0.01

[material]
density = 7850.0
youngs_modulus = 2.0e11

[[initial_velocity]]
at = 0
value = [5.0, 0.0]

[[initial_velocity]]
at = 4
value = [-5.0, 0.0]

[solver]
t_end = 0.004
step = 5.0e-4
"""


@pytest.fixture(scope="module")
def ring(tmp_path_factory):
    d = tmp_path_factory.mktemp("ring")
    (d / "ring.toml").write_text(RING)
    _quiet(["simulate", str(d / "ring.toml"), "--out", str(d / "run"), "--quiet"])
    return d


def _close(a, b, scale: float) -> bool:
    return bool(np.abs(np.asarray(a) - np.asarray(b)).max() <= 1e-12 * scale)


@pytest.mark.parametrize("time", ["0", None], ids=["reference", "deformed"])
@pytest.mark.parametrize("suffix", ["json", "dxf", "step", "igs"])
def test_closed_ring_round_trips(ring, suffix, time):
    """A ring's shape written in every format reads back as the exported curve (control points,
    weights, knots to 1e-12) and meshes again as a closed ring on the run's nodes."""
    from rancf.cad import read_curves
    from rancf.cli.post import run_to_nurbs

    if suffix in ("step", "igs"):
        pytest.importorskip("OCP")
    name = f"ring_{time or 'last'}.{suffix}"
    cmd = ["export", str(ring / "run"), "--nurbs", str(ring / name)]
    _quiet(cmd + (["--time", time] if time else []))
    run = load_run(ring / "run").body()
    i = run.time_index(None if time is None else 0.0)
    exported = run_to_nurbs(run, i)
    (back,) = read_curves(ring / name)
    got = back.curve
    assert np.array_equal(got.points[0], got.points[-1])  # closed, seam pole at both ends
    assert got.degree == exported.degree and got.n_ctrl == exported.n_ctrl
    scale = np.abs(exported.points).max()
    assert _close(got.points[:, :2], exported.points, scale)
    if got.dim == 3:
        assert np.abs(got.points[:, 2]).max() <= 1e-12 * scale
    assert _close(got.weights, exported.weights, 1.0)
    assert _close(got.knots, exported.knots, exported.knots[-1])
    # the file as the geometry of a new scenario: one element per knot span, a closed mesh on
    # the run's nodes (positions and slopes)
    sc = ring / f"cad_{name}.toml"
    rest = RING.split("[mesh]", 1)[1].replace("elements = 8", "elements = 1")
    sc.write_text(f'[geometry]\nkind = "cad"\nfile = "{name}"\n\n[mesh]{rest}')
    mesh = load_scenario(sc).build_model().mesh
    nodes = centerline_nodes(run, run.q[i])
    assert mesh.closed and mesh.n_elements == 8
    assert _close(mesh.nodes[:, 0, :2], nodes[:, 0], scale)
    for k in range(nodes.shape[0]):
        assert vector_angle(mesh.nodes[k, 1, :2], nodes[k, 1]) <= 1e-12
