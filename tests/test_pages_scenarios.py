"""Every complete scenario shown on the README's and the documentation's pages runs: its first
20 steps through ``rancf.simulate`` (the path of ``rancf simulate``) complete (the systems
page's example once failed at t = 0 on a spring to ground, and its roller fought the crank)."""

from __future__ import annotations

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
    d = SCENARIOS[name]
    solver = d.setdefault("solver", {})
    step = float(solver.get("step", 1e-3))
    solver.update(t_end=20 * step, adaptive=False)
    solver.pop("output_step", None)
    result, names, values = rancf.simulate(parse_scenario(d, name))
    assert result.status.value == "completed", (name, result.message)
    assert result.n_steps == 20 and values.shape[1] == len(names)
