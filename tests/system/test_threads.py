"""The element loop shared between threads (``src/cpp/bodies/threads.hpp``): a run on two
threads gives the same numbers bit for bit as on one (each thread computes its elements, the
calling thread adds them in element order; a large band's two halves, linalg/band.hpp), for
a planar pinned cable, a clamped one (the rotated gradient blocks), a spatial conic chain and
a mooring line (its fluid loads' loop too); ``rancf simulate`` chooses one thread for a small
model and takes ``--threads``."""

from __future__ import annotations

import re

import numpy as np
import pytest

from rancf.cli.sim import element_threads
from rancf.kernels import _core
from rancf.scenario import load_scenario
from rancf.solvers.dynamic import integrate
from rancf.studies.common import example_path


def _run(text: str, tmp_path, threads: int):
    path = tmp_path / f"s{threads}.toml"
    path.write_text(text)
    sc = load_scenario(path)
    system = sc.build_system()
    before = _core.assembly_threads()
    _core.set_assembly_threads(threads)
    try:
        return system, integrate(system, sc.dynamic_options())
    finally:
        _core.set_assembly_threads(before)


def _case(name: str, elements: int, clamp: bool = False) -> str:
    text = example_path(name).read_text()
    text = re.sub(r"(?m)^elements = \d+", f"elements = {elements}", text)
    text = re.sub(r"(?m)^t_end = .*$", "t_end = 0.01", text)
    text = re.sub(r"(?m)^step = .*$", "step = 0.001", text)
    text = re.sub(r"(?m)^output_step = .*$", "", text)
    return text.replace('kind = "pin"', 'kind = "clamp"', 1) if clamp else text


@pytest.mark.parametrize(
    ("name", "clamp", "elements"),
    [
        ("planar-pendulum", False, 64),
        ("planar-pendulum", True, 64),
        ("spatial-pendulum", False, 64),
        ("mooring-line", False, 64),
        ("planar-pendulum", False, 128),  # the band solver's two halves on two threads too
        ("mooring-line", False, 128),
    ],
)
def test_two_threads_give_the_numbers_of_one(tmp_path, name, clamp, elements):
    text = _case(name, max(elements, _core.min_parallel_elements()), clamp)
    system, one = _run(text, tmp_path, 1)
    assert max(b.n_el for b in system.flex) >= _core.min_parallel_elements()
    split = any(b.n >= _core.band_split_from(b.ku) for b in system.flex)
    assert split == (elements >= 128)
    _, two = _run(text, tmp_path, 2)
    assert one.t.size > 5 and np.abs(one.q[-1] - one.q[0]).max() > 0  # it moved
    for key in ("q", "v"):
        assert np.array_equal(getattr(one, key), getattr(two, key)), key


def test_a_run_chooses_its_threads(tmp_path, monkeypatch):
    """One thread for a small model; for a large one the idle cores (here 4 cores at load
    average 1.2: 3), less one where the output worker derives every step's row beside the
    loop; ``--threads`` as given."""
    small = load_scenario(example_path("planar-pendulum")).build_system()
    assert max(b.n_el for b in small.flex) < _core.min_parallel_elements()
    assert element_threads(small, None) == 1
    assert element_threads(small, 3) == 3
    path = tmp_path / "large.toml"
    path.write_text(_case("planar-pendulum", _core.min_parallel_elements()))
    large = load_scenario(path).build_system()
    monkeypatch.setattr("rancf.sweep.threads.default_threads", lambda: 4)
    monkeypatch.setattr("os.getloadavg", lambda: (1.2, 1.0, 1.0))
    assert element_threads(large, None) == 3
    assert element_threads(large, None, rows_beside=True) == 2
    assert element_threads(large, 1) == 1
    monkeypatch.setattr("os.getloadavg", lambda: (9.0, 9.0, 9.0))
    assert element_threads(large, None, rows_beside=True) == 1
