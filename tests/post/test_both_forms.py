"""Every shipped example through ``simulate``, ``plot``, ``export`` (``--vtk``, and ``--nurbs``
where the elements have an exact curve) and ``animate``; a one-body example also in its
one-``[[bodies]]`` form (:func:`rancf.scenario.as_bodies`), whose run folder must hold the same
numbers (1e-9 of each array's scale): a run of a one-body file is a system of one body, read by
one reader."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

from rancf.cli import main
from rancf.post.results import load_results
from rancf.scenario import Scenario, as_bodies
from rancf.studies.common import EXAMPLES, SCENARIO_ANALYSES, example_path

#: Every shipped scenario file.
SHIPPED = sorted(set(EXAMPLES) | set(SCENARIO_ANALYSES))

#: Arrays of a run's and of its body's results.npz compared between the two forms.
RUN_KEYS = ("t", "q", "v", "a", "lam", "kinetic", "strain", "gravity", "sensors", "reactions")
BODY_KEYS = (
    "t",
    "q",
    "v",
    "a",
    "reactions",
    "along",
    "along_s",
    "weights",
    "scales",
    "reference",
    "directors",
)


def _short(name: str) -> Scenario:
    """The shipped example cut to three output steps."""
    raw = tomllib.loads(example_path(name).read_text())
    sv = raw.setdefault("solver", {})
    out_dt = sv.get("output_step", sv.get("step", 1e-3))
    sv["t_end"] = min(sv.get("t_end", 1.0), 3 * out_dt)
    return Scenario.from_dict(raw, str(example_path(name)))


def _all_commands(sc: Scenario, folder, capsys) -> None:
    folder.mkdir()
    sc.save(folder / "s.toml")
    run = folder / "run"
    assert main(["simulate", str(folder / "s.toml"), "--out", str(run), "--quiet"]) == 0
    assert main(["plot", str(run), "--configurations", "2"]) == 0
    meta = load_results(run / "results.npz")["metadata"]
    curves = all(b.get("element") != "beam" for b in meta["bodies"] if b["kind"] == "flexible")
    nurbs = ["--nurbs", str(folder / "shape.json")] if len(_flexible(meta)) == 1 and curves else []
    assert main(["export", str(run), "--vtk", str(folder / "vtk"), *nurbs]) == 0
    shell = any(b["kind"] == "shell" for b in meta["bodies"])  # drawn from its VTK surfaces
    code = main(["animate", str(run), "--out", str(folder / "a.gif"), "--every", "3"])
    assert code == (2 if shell else 0)
    capsys.readouterr()
    if not shell:
        assert (run / "plots" / "configurations.png").stat().st_size > 0
        assert (folder / "a.gif").stat().st_size > 0
    for name in _flexible(meta):
        assert (folder / "vtk" / name / f"{name}.pvd").is_file()


def _flexible(meta: dict) -> list[str]:
    return [b["name"] for b in meta["bodies"] if b["kind"] == "flexible"]


def _same(a, b, what: str) -> None:
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert a.shape == b.shape, what
    scale = max(float(np.abs(a).max(initial=0.0)), 1e-300)
    assert np.abs(a - b).max(initial=0.0) <= 1e-9 * scale, what


@pytest.mark.parametrize("name", SHIPPED)
def test_every_example_through_every_post_command_in_both_forms(tmp_path, capsys, name):
    sc = _short(name)
    _all_commands(sc, tmp_path / "file", capsys)
    if sc.bodies:  # a system: it has one form
        return
    _all_commands(as_bodies(sc), tmp_path / "bodies", capsys)
    one, two = (tmp_path / f / "run" for f in ("file", "bodies"))
    za, zb = load_results(one / "results.npz"), load_results(two / "results.npz")
    for key in RUN_KEYS:
        _same(za[key], zb[key], key)
    ma, mb = za["metadata"], zb["metadata"]
    assert ma["bodies"] == mb["bodies"] and ma["sensor_columns"] == mb["sensor_columns"]
    assert len(ma["reaction_columns"]) == len(mb["reaction_columns"])
    if not (one / "bodies" / "body" / "results.npz").is_file():  # a shell: its surfaces
        return
    ba = load_results(one / "bodies" / "body" / "results.npz")
    bb = load_results(two / "bodies" / "body" / "results.npz")
    assert sorted(ba) == sorted(bb)
    for key in BODY_KEYS:
        if key in ba:
            _same(ba[key], bb[key], f"body {key}")
    for f in ("sensors.csv", "energy.csv"):
        assert (one / f).read_text() == (two / f).read_text()
    if (tmp_path / "file" / "shape.json").is_file():
        from rancf.cad import read_curves

        (a,), (b,) = (read_curves(tmp_path / f / "shape.json") for f in ("file", "bodies"))
        _same(a.curve.points, b.curve.points, "NURBS control points")
        _same(a.curve.weights, b.curve.weights, "NURBS weights")
