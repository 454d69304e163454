"""docs/guide/contact.md: its TOML example is a valid scenario with an obstacle and a
``contact_force`` sensor (its console blocks run in tests/test_readme.py, with every page's)."""

from __future__ import annotations

import tomllib

from rancf.scenario import parse_scenario
from tests.pages import DOCS, blocks, text


def test_contact_page_scenario_is_valid():
    (toml,) = blocks(text(DOCS / "guide" / "contact.md"), "toml")
    sc = parse_scenario(tomllib.loads(toml), "contact.md")
    assert [o.kind for o in sc.obstacles] == ["plane"]
    assert [s.kind for s in sc.sensors] == ["contact_force"]
    assert sc.build_system().obstacle_names == ["ground"]
