"""``load_results`` reads a run from its ``results.npz`` or from the run folder that holds it."""

import numpy as np
import pytest

from rancf import load_results
from rancf.cli import main
from rancf.errors import InputError
from tests.scenario.test_scenario import BASE


def test_a_run_folder_reads_as_its_results_file(tmp_path):
    (tmp_path / "pend.toml").write_text(BASE.replace("t_end = 0.02", "t_end = 0.003"))
    run = tmp_path / "run"
    assert main(["simulate", str(tmp_path / "pend.toml"), "--out", str(run), "--quiet"]) == 0
    a, b = load_results(run), load_results(run / "results.npz")
    assert a.keys() == b.keys() and a["metadata"] == b["metadata"]
    np.testing.assert_array_equal(a["q"], b["q"])
    assert a["t"][-1] == pytest.approx(0.003)


def test_a_folder_without_results_names_what_is_allowed(tmp_path):
    with pytest.raises(InputError, match=r"path.*a results.npz file or a run folder"):
        load_results(tmp_path)
