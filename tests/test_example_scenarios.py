"""`rancf example run` runs every shipped scenario `rancf example list` shows:
the paper studies, and the other scenarios with the analyses they are meant for."""

from __future__ import annotations

import json
import subprocess
import sys
from importlib import resources

import pytest

from rancf.cli import main
from rancf.studies.common import EXAMPLES, SCENARIO_ANALYSES, example_path


def test_every_shipped_scenario_can_be_run():
    shipped = {
        f.name.removesuffix(".toml")
        for f in resources.files("rancf.examples").iterdir()
        if f.name.endswith(".toml")
    }
    assert shipped == set(EXAMPLES) | set(SCENARIO_ANALYSES)
    assert not set(EXAMPLES) & set(SCENARIO_ANALYSES)
    for analyses in SCENARIO_ANALYSES.values():
        assert analyses and set(analyses) <= {"simulate", "static", "modes", "buckling"}


def test_example_list_says_what_run_does(capsys):
    assert main(["example", "list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    (cantilever,) = [x for x in lines if x.startswith("cantilever ")]
    assert cantilever.endswith("(cantilever.toml; run: static, modes)")


def test_example_run_of_the_cantilever_writes_a_small_report(tmp_path):
    out = tmp_path / "cant"
    p = subprocess.run(
        [sys.executable, "-m", "rancf", "example", "run", "cantilever", "--out", str(out)],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0, p.stderr  # was: "a paper study, one of ..."
    assert p.stdout == f"report written to {out / 'report.html'}\n"
    # the scenario, the static load path as a run directory, the modes, their figures
    assert (out / "cantilever.toml").read_text() == example_path("cantilever").read_text()
    static = json.loads((out / "static" / "summary.json").read_text())
    assert static["status"] == "completed" and static["analysis"] == "static"
    modes = json.loads((out / "modes.json").read_text())
    assert len(modes["frequencies_hz"]) == 6
    assert modes["frequencies_hz"][0] == pytest.approx(1.9385, rel=1e-3)  # docs: 1.938485 Hz
    html = (out / "report.html").read_text()
    assert "the shipped scenario cantilever" in html and "Paper says" not in html
    # load path: sensors, envelope, configurations; modes
    assert html.count("data:image/png;base64,") == 4
    assert "Static equilibrium: 4 load steps" in html and "Natural frequencies" in html
    report = json.loads((out / "report.json").read_text())
    assert report["complete"] and list(report["studies"]) == ["cantilever"]
    assert (out / "static" / "plots" / "configurations.png").stat().st_size > 0


@pytest.mark.parametrize("name", sorted(SCENARIO_ANALYSES))
def test_example_run_of_every_shipped_scenario(tmp_path, name):
    """Each shipped scenario runs with the analyses it is listed for (the robot cable's moving
    support was refused here once, while ``rancf simulate`` ran it) and writes its report."""
    out = tmp_path / name
    assert main(["example", "run", name, "--out", str(out)]) == 0
    report = json.loads((out / "report.json").read_text())
    assert report["complete"] and list(report["studies"]) == [name]
    for analysis in SCENARIO_ANALYSES[name]:
        folder = {"simulate": "run", "static": "static"}.get(analysis)
        if folder:
            summary = json.loads((out / folder / "summary.json").read_text())
            assert summary["status"] == "completed", (analysis, summary["status"])
        else:
            assert (out / f"{analysis}.json").is_file()
