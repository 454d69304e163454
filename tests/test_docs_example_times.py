"""The performance guide states the run time of every shipped example."""

import re

from rancf.studies.catalog import EXAMPLES, SCENARIO_ANALYSES
from tests.pages import DOCS, section


def test_every_shipped_example_has_a_run_time():
    text = section(DOCS / "guide" / "performance.md", "Run times of the shipped examples")
    rows = dict(re.findall(r"^\| `([\w-]+)` \| ([\d.]+ s) \|$", text, flags=re.M))
    assert sorted(rows) == sorted([*EXAMPLES, *SCENARIO_ANALYSES])
    assert "AMD EPYC" in text  # the machine is named
