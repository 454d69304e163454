"""Form-finding (``[form]``): the unstretched length of a line that meets a sag, a horizontal
tension or an end tension in statics, used by every analysis.

The reference is the elastic catenary of a level span (Irvine, *Cable Structures*, 1981, §2.2),
solved here on its own: with the horizontal tension ``H``, the unstretched length ``L``, the
weight ``w`` per unstretched length, the half span and the sag at midspan are
``l / 2 = H L / (2 EA) + (H / w) asinh(w L / (2 H))`` and
``d = (H / w) (sqrt(1 + (w L / (2 H))²) - 1) + w L² / (8 EA)``.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import fsolve

import rancf
from rancf.bodies.length import unstretched_length
from rancf.errors import ScenarioError
from rancf.runs.modes import run_modes
from rancf.runs.static import run_static
from rancf.scenario.scenario import parse_scenario

SPAN, SAG, MASS, EA, G = 200.0, 5.0, 1.628, 3.23e7, 9.81
W = MASS * G
AREA = 1.0e-4


def level_catenary(sag: float) -> tuple[float, float]:
    """``(H, L)`` of the elastic catenary of the level span with ``sag`` at midspan."""

    def eqs(u: np.ndarray) -> list[float]:
        h, length = u[0] * 1e4, u[1] * 100.0
        a = W * length / (2.0 * h)
        return [
            h * length / (2.0 * EA) + (h / W) * math.asinh(a) - SPAN / 2.0,
            (h / W) * (math.sqrt(1.0 + a * a) - 1.0) + W * length**2 / (8.0 * EA) - sag,
        ]

    h0 = W * SPAN**2 / (8.0 * sag)
    sol = fsolve(eqs, [h0 / 1e4, SPAN / 100.0], xtol=1e-14)
    assert max(abs(r) for r in eqs(sol)) < 1e-9
    return sol[0] * 1e4, sol[1] * 100.0


H_CAT, L_CAT = level_catenary(SAG)


def _span(form: dict, bodies: bool = False, **more) -> dict:
    body = {
        "geometry": {"kind": "line", "start": [0.0, 0.0], "end": [SPAN, 0.0]},
        "mesh": {"elements": 40},
        "section": {"area": AREA, "inertia": 1.0e-12},
        "material": {"density": MASS / AREA, "youngs_modulus": EA / AREA},
        "form": form,
    }
    at = ("line:start", "line:end") if bodies else ("start", "end")
    raw = {
        "supports": [{"at": at[0], "kind": "pin"}, {"at": at[1], "kind": "pin"}],
        "loads": {"gravity": [0.0, -G]},
        "sensors": [
            {"name": "mid", "kind": "position", "at": "line:20" if bodies else 20},
            {"name": "pull", "kind": "tension", "at": at[1]},
        ],
        **more,
    }
    if bodies:
        return {"bodies": [{"name": "line", **body}], **raw}
    return {**body, **raw}


def _horizontal(run) -> float:
    forces = [r.force for r in run.outputs.static_reactions(run.result.y, run.result.lam)]
    return float(abs(forces[-1][0]))


@pytest.mark.parametrize("bodies", [False, True], ids=["one-body", "bodies"])
def test_sag_meets_its_target_and_the_catenary(bodies):
    """``sag = 5``: the static sag (the midspan node, the lowest point of a level span) 5 m
    within 2 mm, the horizontal reaction within 0.1 % of the elastic catenary's."""
    sc = parse_scenario(_span({"sag": SAG}, bodies))
    run = run_static(sc)
    assert -run.sensors["mid_y"] == pytest.approx(SAG, abs=2e-3)
    assert _horizontal(run) == pytest.approx(H_CAT, rel=1e-3)
    length = run.form["unstretched_length"]  # one body with a [form]: its length
    assert length == pytest.approx(L_CAT, rel=1e-5)  # measured: 200.233815 against 200.233742
    assert run.form_lines and f"{length:.9g}" in run.form_lines[0]


@pytest.mark.parametrize("key", ["horizontal_tension", "end_tension"])
def test_tension_targets_give_the_catenary_sag(key):
    """The catenary's ``H`` (or its end tension ``sqrt(H² + (w L / 2)²)``) as the target: the
    sag within 0.2 % of 5 m, the target met."""
    target = H_CAT if key == "horizontal_tension" else math.hypot(H_CAT, W * L_CAT / 2.0)
    run = run_static(parse_scenario(_span({key: target})))
    assert -run.sensors["mid_y"] == pytest.approx(SAG, rel=2e-3)
    got = _horizontal(run) if key == "horizontal_tension" else run.sensors["pull"]
    assert got == pytest.approx(target, rel=1e-6)


def test_the_length_found_is_used_by_modes():
    """``rancf modes`` about the static state: the body has the length found, the same as
    statics'."""
    sc = parse_scenario(_span({"sag": SAG}))
    modes = run_modes(sc, 3, "static")
    length = unstretched_length(modes.system.bodies["body"])
    assert length == pytest.approx(run_static(sc).form["unstretched_length"], rel=1e-12)
    assert modes.result.frequencies_hz[0] > 0.0


@pytest.mark.parametrize(
    "form, more, match",
    [
        ({"end_tension": 1000.0}, {}, r"\[form\.end_tension\] needs at least 2.*N.*got 1000"),
        ({"sag": 1.0, "end_tension": 1e4}, {}, r"\[form\] needs exactly one of sag"),
        ({}, {}, r"\[form\] needs exactly one"),
        ({"sag": 1.0}, {"loads": {"gravity": [0.0, 0.0]}}, r"\[form\.sag\].*gravity"),
        ({"sag": -1.0}, {}, r"\[form\.sag\]"),
    ],
    ids=["tension-too-low", "two-targets", "none", "no-gravity", "negative"],
)
def test_infeasible_or_bad_targets_are_one_line(form, more, match):
    with pytest.raises(ScenarioError, match=match) as e:
        run_static(parse_scenario(_span(form, **more)))
    assert "\n" not in str(e.value)


def test_a_chain_on_the_seabed_by_its_fairlead_tension():
    """The 100 m chain of tests/scenario/test_line_length.py in seawater on its seabed, given
    by MoorPy's fairlead tension instead of its length: the length found is MoorPy's 100 m
    within 0.01 % (measured: 100.0005 m), the tension met."""
    from tests.scenario.test_line_length import D_VOL, T_MOORPY, _system

    raw = _system(-30.0 - D_VOL / 2).to_dict()
    del raw["bodies"][0]["geometry"]["length"]
    raw["bodies"][0]["form"] = {"end_tension": T_MOORPY}
    run = run_static(parse_scenario(raw))
    assert run.form["unstretched_length"] == pytest.approx(100.0, rel=1e-4)
    assert run.sensors["fairlead"] == pytest.approx(T_MOORPY, rel=1e-6)


def test_form_where_it_does_not_apply():
    raw = _span({"sag": 1.0})
    raw["geometry"]["length"] = 201.0
    with pytest.raises(ScenarioError, match=r"\[form\].*not both"):
        parse_scenario(raw)
    raw = _span({"sag": 1.0})
    raw["geometry"]["end"] = [0.0, -SPAN]  # a vertical chord: no sag below it
    with pytest.raises(ScenarioError, match=r"\[form\.sag\].*apart horizontally"):
        run_static(parse_scenario(raw))
    raw = _span({"sag": 1.0})
    raw["mesh"]["element"] = "beam"
    with pytest.raises(ScenarioError, match=r"\[form\] applies to cable and rod"):
        parse_scenario(raw)


def test_unfound_form_is_refused_when_built_alone():
    sc = parse_scenario(_span({"sag": SAG}))
    with pytest.raises(ScenarioError, match=r"\[form\].*find_form"):
        sc.build_system()


def test_cli_prints_and_writes_the_length(tmp_path):
    """``rancf static --json`` and ``summary.json`` hold ``unstretched_length``."""
    from rancf.scenario.toml_text import dumps

    (tmp_path / "span.toml").write_text(dumps(_span({"sag": SAG})))
    src = str(Path(rancf.__file__).resolve().parents[1])
    env = {**os.environ, "PYTHONPATH": src}
    cmd = [sys.executable, "-m", "rancf", "static", "span.toml"]
    p = subprocess.run(
        [*cmd, "--json"], cwd=tmp_path, capture_output=True, text=True, env=env, check=True
    )
    length = json.loads(p.stdout)["unstretched_length"]
    assert length == pytest.approx(L_CAT, rel=1e-5)
    p = subprocess.run(
        [*cmd, "--out", "run"], cwd=tmp_path, capture_output=True, text=True, env=env, check=True
    )
    assert f"unstretched length {length:.9g} m (form: sag = 5 m)" in p.stdout
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["unstretched_length"] == length


def test_a_sag_met_only_in_compression_is_refused():
    """A section so stiff that its weight alone bends it less than the sag (a radius of 3 m on
    the 200 m span, as 3 mm would read in metres: EI = 2e13 N m²) meets the sag only as a beam
    longer than its span, pushed in: that is refused naming the key, not printed as a power
    line with a negative tension; the 1.1 cm conductor's own section is in tension."""
    raw = _span({"sag": SAG})
    raw["section"] = {"radius": 3.0}
    with pytest.raises(ScenarioError, match=r"\[form\.sag\] needs a line in tension.*compress"):
        run_static(parse_scenario(raw))
    raw["section"] = {"radius": 0.0113}
    run = run_static(parse_scenario(raw))
    assert run.sensors["pull"] > 0.0
