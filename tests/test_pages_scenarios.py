"""Every complete scenario shown on the README's and the documentation's pages runs: its first
20 steps through ``rancf.simulate`` (the path of ``rancf simulate``) complete (the systems
page's example once failed at t = 0 on a spring to ground, and its roller fought the crank)."""

from __future__ import annotations

import copy
import tomllib

import pytest

import rancf
from rancf.scenario import parse_scenario
from tests import pages


def _complete() -> dict[str, dict]:
    out = {}
    for page in pages.PAGES:
        for i, block in enumerate(pages.blocks(pages.text(page), "toml")):
            d = tomllib.loads(block)
            if {"geometry", "mesh"} <= set(d) or "bodies" in d:
                out[f"{pages.name(page)}[{i}]"] = d
    return out


SCENARIOS = _complete()


def test_the_pages_show_complete_scenarios():
    assert len(SCENARIOS) >= 4


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_a_page_scenario_runs(name):
    d = copy.deepcopy(SCENARIOS[name])
    solver = d.setdefault("solver", {})
    step = float(solver.get("step", 1e-3))
    solver.update(t_end=20 * step, adaptive=False)
    solver.pop("output_step", None)
    result, names, values = rancf.simulate(parse_scenario(d, name))
    assert result.status.value == "completed", (name, result.message)
    assert result.n_steps == 20 and values.shape[1] == len(names)


def test_a_failed_run_is_said_in_one_warning_line():
    """``rancf.simulate`` of a run that cannot converge returns what it computed (status
    ``failed``) and says so in one warning line (it was silent)."""
    d = copy.deepcopy(SCENARIOS[next(iter(SCENARIOS))])
    d["solver"].update(t_end=0.01, step=1e-3, max_newton=1, newton_tol=1e-300)
    with pytest.warns(UserWarning, match=r"^rancf: the run failed at t = 0 s: ") as seen:
        result, names, values = rancf.simulate(parse_scenario(d, "x"))
    assert len(seen) == 1 and result.status.value == "failed" and values.shape[0] >= 1
