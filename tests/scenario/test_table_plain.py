"""A table's plain values (:meth:`rancf.scenario.base.Table.plain`, what a scenario's data are
made of) are what pydantic's ``model_dump`` gives, for every table of the shipped examples."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from rancf.scenario import load_scenario
from rancf.scenario.base import Table
from rancf.studies.common import example_path

FILES = sorted(example_path("planar-pendulum").parent.glob("*.toml"))


def _same(a: Any, b: Any) -> bool:
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, np.ndarray):
        return bool(np.array_equal(a, b))
    return bool(a == b)


def _tables(x: Any) -> list[Table]:
    if isinstance(x, Table):
        return [x, *(t for v in x.__dict__.values() for t in _tables(v))]
    if isinstance(x, (list, tuple)):
        return [t for v in x for t in _tables(v)]
    return []


@pytest.mark.parametrize("path", FILES, ids=[f.stem for f in FILES])
def test_plain_values_are_the_dump(path):
    tables = _tables(load_scenario(path))
    assert len(tables) > 5
    for t in tables:
        assert _same(t.plain(), t.model_dump()), type(t).__name__
    sc = tables[0]
    assert sc.plain(frozenset({"solver"})).keys() == sc.model_dump(exclude={"solver"}).keys()
