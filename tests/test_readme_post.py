"""Runs the console examples of the sections on looking at a run, CAD export, sweeps, rods and
the exact-geometry study, in order and in one folder (a later section reads what an earlier one
wrote), and compares their output with the page's (text exactly, numbers within
:data:`tests.numbers.RTOL`). The sections are found by their headings in the pages of
:data:`tests.pages.PAGES`; every other console block is run by ``tests/test_readme.py``."""

import os
import shlex

import numpy as np
import pytest

from rancf.cli import main
from tests.numbers import assert_lines_match
from tests.pages import DOCS, blocks, section, transcript
from tests.scenario.test_scenario import BASE

#: (page, heading) of the sections run here, in the order they run.
SECTIONS = (
    (DOCS / "guide" / "outputs.md", "Looking at a run"),
    (DOCS / "guide" / "outputs.md", "CAD export"),
    (DOCS / "guide" / "sweeps.md", "Parameter sweeps on Dask"),
    (DOCS / "guide" / "rods.md", "Rods with torsion"),
    (DOCS / "guide" / "rods.md", "Rod dynamics"),
    (DOCS / "guide" / "studies.md", "Where exact geometry pays"),
    (DOCS / "guide" / "statics.md", "Modes about a steady rotation"),
)


def test_page_console_examples(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "short.toml").write_text(BASE)
    (tmp_path / "sweep.toml").write_text(blocks(section(*SECTIONS[2]), "toml")[0])
    (tmp_path / "rod.toml").write_text(blocks(section(*SECTIONS[3]), "toml")[0])
    dynamics = section(*SECTIONS[4])
    (tmp_path / "top.toml").write_text(blocks(dynamics, "toml")[0])
    (tmp_path / "blade.toml").write_text(blocks(section(*SECTIONS[6]), "toml")[0])
    n = 0
    for where in SECTIONS:
        for block in blocks(section(*where), "console"):
            for cmd, expected in transcript(block):
                argv = shlex.split(cmd)
                assert argv[0] == "rancf", cmd
                capsys.readouterr()
                assert main(argv[1:]) == 0, cmd
                got = capsys.readouterr().out.rstrip("\n").splitlines()
                assert_lines_match(got, expected, what=cmd)
                n += 1
    assert n >= 8
    assert len(list((tmp_path / "run" / "vtk" / "body").glob("*.vtu"))) == 5
    assert os.path.getsize(tmp_path / "run.gif") > 0
    # the heavy top's sensors as the page shows them (numbers across machines: 1e-6)
    shown = blocks(dynamics, "text")[0].splitlines()
    run = (tmp_path / "top" / "sensors.csv").read_text().splitlines()
    assert run[0] == shown[0] and len(run) == len(shown)
    got, want = (np.array([r.split(",") for r in rows[1:]], dtype=float) for rows in (run, shown))
    assert np.allclose(got, want, rtol=1e-6, atol=1e-6)


@pytest.mark.parametrize("where", SECTIONS, ids=[t for _, t in SECTIONS])
def test_sections_exist(where):
    assert blocks(section(*where), "console")
