"""The sensor table of the outputs guide lists every sensor kind the scenario schema accepts."""

import re

from rancf.scenario.sensors import SENSOR_KINDS
from tests.pages import DOCS, section


def test_every_sensor_kind_has_a_row():
    text = section(DOCS / "guide" / "outputs.md", "Sensors")
    rows = re.findall(r'^\| `"(\w+)"` \|', text, flags=re.M)
    assert sorted(rows) == sorted(SENSOR_KINDS)
