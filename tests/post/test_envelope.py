"""``bodies/NAME/envelope.csv``: the extremes of the section values over a run, with their
times, written with the run's files; ``rancf plot`` draws them."""

from __future__ import annotations

import json
import tomllib

import numpy as np
import pytest

from rancf.cli import main
from rancf.post.envelope import Envelope, read_envelope
from rancf.scenario import Scenario
from rancf.studies.common import example_path


def test_a_cantilever_s_clamp_moment_envelope_is_the_static_p_l(tmp_path):
    """The shipped cantilever (L = 0.5 m, tip load P = 1 mN) solved statically along its load
    path (``rancf static --out``): the envelope of the bending moment at the clamp (s = 0)
    reaches P L at the full load (load factor 1) within 1e-6 relative.  Why this is exact: a
    tip-loaded cantilever's moment is linear in s, so cubic elements hold the small-deflection
    solution exactly, and the tip's deflection (PL³/3EI = 3.3e-6 m) shortens the lever arm by a
    share of order 1e-11; measured: 2.6e-11 relative."""
    run = tmp_path / "run"
    assert main(["static", str(example_path("cantilever")), "--out", str(run)]) == 0
    env = read_envelope(str(run / "bodies" / "body" / "envelope.csv"))
    assert env["s"][0] == 0.0 and env["s"][-1] == pytest.approx(0.5, rel=1e-12)
    p_l = 1e-3 * 0.5
    low, high = env["bending_moment_min"][0], env["bending_moment_max"][0]
    extreme, t_ext = (
        (low, env["bending_moment_min_t"][0])
        if abs(low) > abs(high)
        else (high, env["bending_moment_max_t"][0])
    )
    assert abs(extreme) == pytest.approx(p_l, rel=1e-6)
    assert t_ext == 1.0
    # the other end of the band is the unloaded reference (0 at load factor 0)
    other = high if extreme is low else low
    assert abs(other) <= 1e-12 * p_l


def test_the_envelope_is_the_extremes_of_the_stored_section_values(tmp_path):
    """A short dynamic run of the cantilever: every column of the envelope equals the minimum
    and maximum over the rows of ``along`` in ``bodies/body/results.npz`` (to the 12 digits
    of the CSV file: 1e-11 relative), and each time is that of the first row reaching it
    (``rancf plot`` draws ``envelope_body.png``: the docs' example, tests/test_readme_post)."""
    raw = tomllib.loads(example_path("cantilever").read_text())
    raw["solver"] = {"t_end": 0.05, "step": 1e-3}
    sc = Scenario.from_dict(raw)
    sc.save(tmp_path / "c.toml")
    run = tmp_path / "run"
    assert main(["simulate", str(tmp_path / "c.toml"), "--out", str(run), "--quiet"]) == 0
    env = read_envelope(str(run / "bodies" / "body" / "envelope.csv"))
    z = np.load(run / "bodies" / "body" / "results.npz")
    t, along = z["t"], z["along"]
    names = json.loads(str(z["metadata"]))["section_names"]

    def same(a: np.ndarray, b: np.ndarray) -> bool:
        return np.allclose(a, b, rtol=1e-11, atol=1e-300)

    assert same(env["s"], z["along_s"])
    for j, name in enumerate(names):
        col = along[:, :, j]
        assert same(env[f"{name}_min"], col.min(axis=0))
        assert same(env[f"{name}_max"], col.max(axis=0))
        assert same(env[f"{name}_min_t"], t[np.argmin(col, axis=0)])
        assert same(env[f"{name}_max_t"], t[np.argmax(col, axis=0)])
    assert np.ptp(env["bending_moment_max_t"]) > 0  # the extremes are not all at one time


def test_envelope_chunks_keep_the_first_time_of_an_extreme():
    """Rows fed in two chunks give the extremes of all rows, a tie keeping the earlier time."""
    env = Envelope(np.array([0.0, 1.0]), ["a"])
    env.update(np.array([0.0, 1.0]), np.array([[[1.0], [5.0]], [[3.0], [-2.0]]]))
    env.update(np.array([2.0]), np.array([[[3.0], [7.0]]]))
    assert env.low[:, 0].tolist() == [1.0, -2.0] and env.t_low[:, 0].tolist() == [0.0, 1.0]
    assert env.high[:, 0].tolist() == [3.0, 7.0] and env.t_high[:, 0].tolist() == [1.0, 2.0]
