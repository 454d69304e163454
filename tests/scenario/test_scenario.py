import copy
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.errors import ScenarioError
from rancf.scenario import load_scenario, parse_scenario

BASE = """
[geometry]
kind = "conic"
start = [0.0, 0.0]
end = [0.5, 0.0]
angles_deg = [30.0, 40.0]
point = [0.315, 0.077]

[mesh]
elements = 3
element = "rancf"
k = "opt"

[section]
radius = 0.02

[material]
density = 6000.0
youngs_modulus = 2.0e6

[[supports]]
at = "start"
kind = "pin"

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.02
step = 1.0e-3

[[sensors]]
name = "AB"
kind = "distance"
between = ["start", "end"]

[[sensors]]
name = "tip"
kind = "position"
at = "end"
"""


def base():
    return tomllib.loads(BASE)


def test_base_scenario_builds():
    sc = parse_scenario(base(), "base.toml")
    model = sc.build_model()
    assert model.n_el == 3 and model.dim == 2
    assert [s.columns(2) for s in sc.sensors] == [["AB"], ["tip_x", "tip_y"]]


def _mutate(fn):
    d = base()
    fn(d)
    return d


BAD = [
    (lambda d: d["mesh"].update(elemnts=3), "mesh.elemnts", "unknown key"),
    (lambda d: d.update(solvr={}), "solvr", "unknown table"),
    (lambda d: d["material"].pop("density"), "material.density", "missing"),
    (lambda d: d.pop("section"), "section", "missing"),
    (lambda d: d["mesh"].update(elements="five"), "mesh.elements", "integer"),
    (lambda d: d["material"].update(density=-1.0), "material.density", "> 0"),
    (lambda d: d["material"].update(youngs_modulus=0.0), "material.youngs_modulus", "> 0"),
    (lambda d: d["section"].update(radius=0.0), "section.radius", "> 0"),
    (lambda d: d["solver"].update(step=-1e-3), "solver.step", "> 0"),
    (lambda d: d["solver"].update(t_end=True), "solver.t_end", "number"),
    (lambda d: d["supports"][0].update(at=7), "supports[0].at", "does not exist"),
    (lambda d: d["supports"][0].update(kind="weld"), "supports[0].kind", "one of"),
    (lambda d: d["geometry"].update(angles_deg=[30.0, 95.0]), "geometry.angles_deg[1]", "(0, 90)"),
    (lambda d: d["geometry"].update(point=[0.3, 0.5]), "geometry.point", "triangle"),
    (lambda d: d["mesh"].update(k=1.5), "mesh.k", "[0.0001, 0.9999]"),
    (lambda d: d["loads"].update(gravity=[0.0, -9.81, 0.0]), "loads.gravity", "2"),
    (lambda d: d["sensors"][1].update(at="middle"), "sensors[1].at", "start"),
    (lambda d: d["geometry"].update(kind="spline"), "geometry.kind", "one of"),
    # a second support at a node held already (node 0 is "start"): each would report the whole
    # reaction, and the later position would silently win
    (
        lambda d: d["supports"].append({"at": 0, "kind": "pin", "position": [0.0, 0.1]}),
        "supports[1].at",
        "node 0 is held by supports[0] already: one support per node",
    ),
]


@pytest.mark.parametrize(("mutate", "key", "needle"), BAD)
def test_bad_scenarios_name_the_key_and_file(mutate, key, needle):
    with pytest.raises(ScenarioError) as info:
        parse_scenario(_mutate(mutate), "bad.toml").build_model()
    msg = str(info.value)
    assert msg.startswith("bad.toml: [")
    assert key in msg and needle in msg


def _toml(d):
    """Tiny TOML writer for the test's dictionaries."""
    lines = []

    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return repr(v)

    for k, v in d.items():
        if isinstance(v, dict):
            lines.append(f"[{k}]")
            sub = {
                kk: vv
                for kk, vv in v.items()
                if not isinstance(vv, list) or not vv or not isinstance(vv[0], dict)
            }
            lines += [f"{kk} = {val(vv)}" for kk, vv in sub.items()]
            for kk, vv in v.items():
                if kk not in sub:
                    for item in vv:
                        lines.append(f"[[{k}.{kk}]]")
                        lines += [f"{a} = {val(b)}" for a, b in item.items()]
        elif isinstance(v, list):
            for item in v:
                lines.append(f"[[{k}]]")
                lines += [f"{a} = {val(b)}" for a, b in item.items()]
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize(("mutate", "key", "needle"), BAD[:4] + BAD[10:11])
def test_cli_bad_scenario_exit_2_without_output(tmp_path, capsys, mutate, key, needle):
    f = tmp_path / "bad.toml"
    f.write_text(_toml(_mutate(mutate)))
    out = tmp_path / "out"
    for argv in (
        ["simulate", str(f), "--out", str(out)],
        ["static", str(f), "--json"],
        ["modes", str(f), "--json"],
    ):
        assert main(argv) == 2
        o, e = capsys.readouterr()
        assert o == "" and len(e.strip().splitlines()) == 1
        assert str(f) in e and key in e
    assert not out.exists()


def test_missing_file_and_invalid_toml(tmp_path, capsys, monkeypatch):
    assert main(["static", str(tmp_path / "nope.toml")]) == 2
    err = capsys.readouterr().err
    assert "cannot be read" in err and "rancf example copy" not in err
    monkeypatch.chdir(tmp_path)  # an example's name for a file: where to get the file
    assert main(["simulate", "tether-payload", "--out", "run"]) == 2
    err = capsys.readouterr().err
    assert err.strip().endswith(
        "(a shipped scenario: `rancf example copy tether-payload .` writes tether-payload.toml)"
    )
    bad = tmp_path / "x.toml"
    bad.write_text("[geometry\nkind=")
    assert main(["static", str(bad)]) == 2
    assert "not valid TOML" in capsys.readouterr().err


def test_round_trip_writer_matches():
    d = base()
    assert tomllib.loads(_toml(d)) == d
    assert copy.deepcopy(d) == base()


def test_load_from_file(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text(BASE)
    sc = load_scenario(f)
    assert sc.path == str(f)
    assert Path(sc.path).exists()
    assert np.allclose(sc.build_model().node_positions(sc.build_model().q0)[-1], [0.5, 0.0])


NURBS = """
[geometry]
kind = "nurbs"
degree = 2
knots = KNOTS
control_points = [[0.0, 0.0], [0.25, 0.2], [0.5, 0.0]]
weights = WEIGHTS

[mesh]
elements = 2

[section]
radius = 0.02

[material]
density = 6000.0
youngs_modulus = 2.0e6

[[supports]]
at = "start"
kind = "clamp"
"""


@pytest.mark.parametrize(
    ("knots", "weights", "needle"),
    [
        ("[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]", "[1.0, 0.8, 1.0]", None),
        ("[0.0, 0.0, 1.0, 0.5, 1.0, 1.0]", "[1.0, 0.8, 1.0]", "non-decreasing"),
        ("[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]", "[1.0, -0.8, 1.0]", "weights"),
        ("[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]", "[1.0, 0.0, 1.0]", "weights"),
    ],
)
def test_nurbs_geometry_bad_knots_and_weights_through_the_cli(
    tmp_path, capsys, knots, weights, needle
):
    f = tmp_path / "n.toml"
    f.write_text(NURBS.replace("KNOTS", knots).replace("WEIGHTS", weights))
    code = main(["modes", str(f), "--json", "--count", "1"])
    out, err = capsys.readouterr()
    if needle is None:
        assert code == 0 and json.loads(out)["frequencies_hz"][0] > 0
        return
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and needle in err and str(f) in err
