"""One schema past parsing: a file without ``[[bodies]]`` is, once parsed, the system of one
flexible body named ``body``, and the code that builds, runs and reads scenarios sees every file
in that one form (the bodies with their key prefixes)."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np

from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.scenario import as_bodies, parse_scenario
from rancf.scenario.places import ONE_BODY
from tests.scenario.test_scenario import BASE

SRC = Path(__file__).resolve().parents[2] / "src" / "rancf"

#: The modules of parsing itself: they read the file as written.
PARSING = {"checks.py", "data.py", "places.py", "convert.py", "scenario.py", "schema.py"}

#: Reading a file's form: its ``[[bodies]]`` or a one-body file's own tables.
FORM = re.compile(
    r"\bsc\.(bodies|geometry|mesh|section|material|hydro)\b"
    r'|\bsc\["(bodies|geometry|mesh|section|material|hydro)"\]'
    r'|data\["(geometry|mesh|section|material|hydro)"\]'
)


def _one_body():
    return parse_scenario(tomllib.loads(BASE))


def test_a_one_body_file_parses_to_one_flexible_body():
    sc = _one_body()
    ((key, body),) = sc.body_tables
    assert key == "" and body.name == ONE_BODY and body.kind == "flexible"
    assert body.mesh is sc.mesh and body.geometry is sc.geometry
    (data,) = sc.data["bodies"]
    assert data["name"] == ONE_BODY and data["mesh"]["elements"] == 3 and data["key"] == ""
    p = sc.place("end")
    assert (p.where, p.body, p.node) == ("node", ONE_BODY, -1)


def test_both_forms_build_the_same_system():
    sc = _one_body()
    other = as_bodies(sc)
    assert [k for k, _ in other.body_tables] == ["bodies[0]."]
    a, b = sc.build_system(), other.build_system()
    assert a.names == b.names == [ONE_BODY]
    y = a.y0 + 1e-3 * np.sin(np.arange(a.n))
    ra, rb = np.empty(a.n + a.m), np.empty(b.n + b.m)
    lam = np.zeros(a.m)
    static = ResidualOptions(0.0, amplitude=True, dynamic=False)
    a.core.residual(ResidualPoint(y, lam, ra), static)
    b.core.residual(ResidualPoint(y, lam, rb), static)
    np.testing.assert_array_equal(ra, rb)


def test_no_code_past_parsing_reads_the_file_form():
    found = [
        f"{f.relative_to(SRC)}:{i}: {line.strip()}"
        for f in sorted(SRC.rglob("*.py"))
        if not (f.parent.name == "scenario" and f.name in PARSING)
        for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1)
        if FORM.search(line)
    ]
    assert not found, "\n".join(found)


def test_the_form_scan_finds_a_branch():
    assert FORM.search("    if not sc.bodies:") and FORM.search('mesh = sc.data["mesh"]')
    assert not FORM.search('for b in sc.data["bodies"]:')


def test_the_system_rigid_motion_moves_a_body_in_either_form():
    """``[initial_motion]`` of a file is the whole system's: its flexible body starts with that
    rigid motion whether the file is written with ``[[bodies]]`` or without."""
    d = tomllib.loads(BASE)
    d["initial_motion"] = {"velocity": [0.0, 1.0]}
    d.pop("supports")
    sc = parse_scenario(d)
    a, b = sc.build_system(), as_bodies(sc).build_system()
    assert np.abs(a.v0).max() == 1.0
    np.testing.assert_array_equal(a.v0, b.v0)
