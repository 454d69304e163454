"""The warning about fixed steps that do not fit the output interval: ``rancf simulate`` says so
on standard error and in ``summary.json``, and the steps it warns about are really shortened,
all to one size that divides the interval (:meth:`rancf.options.DynamicOptions.fitted`)."""

from __future__ import annotations

import json

import pytest

from rancf.cli import main
from rancf.options import DynamicOptions
from rancf.post.checks import step_warnings
from tests.test_cli_warnings import HOSE

#: The hose of the unit-mistake warnings with a stiff material, 0.03 s long, and an interval.
PENDULUM = (
    HOSE.replace("youngs_modulus = 50.0", "youngs_modulus = 1.0e8").replace(
        "t_end = 0.1", "t_end = 0.03"
    )
    + "output_step = {out}\n"
)


@pytest.mark.parametrize(
    ("out", "warned"),
    [
        (None, False),
        (1e-3, False),
        (2e-3, False),
        (3e-3, False),
        (5e-4, False),
        (1.5e-3, True),
        (2.5e-3, True),
        (1.0000001e-3, True),
    ],
)
def test_only_a_fractional_number_of_steps_above_one_warns(out, warned):
    w = step_warnings(DynamicOptions(t_end=1.0, step=1e-3, output_step=out))
    assert bool(w) == warned
    if warned:
        assert w[0].startswith(f"solver.output_step = {out:g} s is not a whole number of steps")


def test_adaptive_steps_are_not_warned_about():
    assert (
        step_warnings(DynamicOptions(t_end=1.0, step=1e-3, output_step=1.5e-3, adaptive=True)) == []
    )


@pytest.mark.parametrize(("out", "steps"), [(2e-3, 30), (1.5e-3, 40)])
def test_simulate_warns_once_and_the_steps_are_cut(tmp_path, capsys, out, steps):
    f = tmp_path / "p.toml"
    f.write_text(PENDULUM.format(out=out))
    assert main(["simulate", str(f), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    err = capsys.readouterr().err
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["steps"] == steps  # 1.5 ms: steps of 1 and 0.5 ms, 20 outputs, 40 steps
    warned = [w for w in summary["warnings"] if w.startswith("solver.output_step")]
    assert len(warned) == (out == 1.5e-3)
    assert err.count("rancf: warning: solver.output_step") == len(warned)
    if warned:
        assert "output_step = 0.002 s keeps the step" in warned[0]
        assert "steps of 0.00075 s, 2 an output interval" in warned[0]
    h = 7.5e-4 if warned else 1e-3  # 1.5 ms: two steps of 0.75 ms an interval
    assert summary["min_step_s"] == pytest.approx(h, rel=1e-15)
    assert summary["max_step_s"] == pytest.approx(h, rel=1e-15)


@pytest.mark.parametrize(
    ("step", "out", "n", "h"),
    [
        (1e-3, 1.5e-3, 2, 7.5e-4),
        (0.02, 0.05, 3, 0.05 / 3),
        (1e-3, 2.5e-3, 3, 2.5e-3 / 3),
        (1e-3, 2e-3, None, 1e-3),
        (1e-3, 5e-4, None, 1e-3),
        (1e-3, None, None, 1e-3),
    ],
)
def test_fitted_steps_divide_the_interval(step, out, n, h):
    """The steps taken: ``output_step / ceil(output_step / step)`` where the interval is not a
    whole number of steps (as many steps as cutting each interval's last one, all of one size),
    else ``step``; a ``min_step`` above the fitted step comes down to it."""
    o = DynamicOptions(t_end=1.0, step=step, output_step=out, min_step=step)
    assert o.steps_per_output == n
    f = o.fitted()
    assert f.step == h and f.min_step == min(step, h)
    if n is not None:
        assert n * f.step == pytest.approx(out, rel=1e-15) and f.step < step
    adaptive = DynamicOptions(t_end=1.0, step=step, output_step=out, adaptive=True)
    assert adaptive.fitted().step == step
