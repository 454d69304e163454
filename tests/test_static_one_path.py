"""One static path: ``solve_static`` of a one-body model is the equilibrium of its one-body
:class:`~rancf.system.System` (``SystemEquilibrium``, the only static problem), ``rancf static``
builds every scenario's System, and its output does not depend on which sensors exist.

The one-body answers are compared with those of the former one-body path (its own problem class
on the band tangent of the model), computed before it was removed:
``tests/references/static_before_one_path.json`` (rancf main at commit 6d0b943, one
``solve_static`` per case with the same arguments as here; the reactions from the held rows of
its residual).  The physics of these cases is checked against independent references elsewhere
(the installed hose against a shooting solution of the elastica in ``test_equilibrium``; the
rods' moments against finite differences in ``test_modes_moments``)."""

from __future__ import annotations

import importlib.util
import inspect
import json
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.scenario import load_scenario
from rancf.solvers.static import solve_static
from rancf.system.outputs import SystemOutputs
from tests.solvers.test_modes_moments import cantilever

BEFORE = json.loads(
    (Path(__file__).parent / "references" / "static_before_one_path.json").read_text()
)["cases"]
EXAMPLES = ["arc-vibration", "cantilever", "installed-hose", "ring", "robot-cable"]
RODS = {
    "rod-moment-straight": ("straight", (3.0, -2.0, 20.0)),
    "rod-moment-curved": ("curved", (0.5, 0.3, 2.0)),
}


def _flat(reactions) -> np.ndarray:
    return np.array([[*r.force, *([] if r.moment is None else r.moment)] for r in reactions])


def _compare(name: str, q: np.ndarray, reactions, twist: slice | None = None) -> None:
    """q and reactions to 1e-9 relative; a rod's nodal twists (``twist``: every 7th from the
    7th) to 1e-6 rad: they are measured from triads re-referenced along the solver's path,
    which moves with the round-off of the linear algebra (LAPACK builds differ by 2e-7 on the
    curved rod), while the rod's shape and reactions stay put."""
    ref = BEFORE[name]
    q0 = np.array(ref["q"])
    keep = np.ones(q.size, bool)
    if twist is not None:
        keep[twist] = False
        assert np.abs(q - q0)[twist].max() <= 1e-6
    assert np.abs(q - q0)[keep].max() <= 1e-9 * np.abs(q0).max()
    r0 = np.array(ref["reactions"])
    if r0.size:
        assert np.abs(_flat(reactions) - r0).max() <= 1e-9 * np.abs(r0).max()
    else:
        assert not reactions


@pytest.mark.parametrize("name", EXAMPLES)
def test_shipped_one_body_examples_keep_their_equilibrium(name):
    """Through the scenario's System (as ``rancf static``) and through its Model (the Python
    one-body front): the same equilibrium and reactions as before, to 1e-9 relative (the
    installed hose with its installation stage, the ring with its seam)."""
    with resources.as_file(resources.files("rancf.examples") / f"{name}.toml") as p:
        sc = load_scenario(p)
    opts = {"load_steps": sc.solver["load_steps"], "method": sc.solver["static_method"]}
    system = sc.build_system()
    res = solve_static(system, **opts)
    assert res.method == "load"
    _compare(name, res.q, SystemOutputs(system).static_reactions(res.y, res.lam))
    (model,) = system.flex
    res_m = solve_static(model, **opts)
    assert np.array_equal(res_m.q, res.q)


@pytest.mark.parametrize("name", list(RODS))
def test_rods_with_point_moments_keep_their_equilibrium(name):
    """A clamped rod with a tip moment (the moment's load stiffness is not symmetric)."""
    geo, moment = RODS[name]
    m = cantilever(moment, geo=geo)
    res = solve_static(m, 10)
    from rancf.system import as_system

    _compare(
        name, res.q, SystemOutputs(as_system(m)).static_reactions(res.y, res.lam), slice(6, None, 7)
    )


def test_the_second_static_path_stays_removed():
    """One problem class, no conversion of a system back into a model, and one code path for
    ``rancf static`` (no branch on the kind of scenario)."""
    import rancf.cli.equilibrium as cli_eq
    import rancf.solvers.static as static

    assert importlib.util.find_spec("rancf.solvers.equilibrium") is None
    assert not hasattr(static, "_one_model") and not hasattr(static, "EquilibriumProblem")
    assert importlib.util.find_spec("rancf.cli.system") is None  # the systems' own commands
    source = inspect.getsource(cli_eq._cmd_static)
    for branch in ("needs_system", "is_system", "build_model", "single"):
        assert branch not in source, branch
    assert "isinstance(model" not in inspect.getsource(static)


def _without_reaction_sensors(text: str) -> str:
    blocks = text.split("[[sensors]]")
    return "[[sensors]]".join(b for b in blocks if 'kind = "reaction"' not in b)


@pytest.mark.parametrize("name", ["robot-cable", "slider-crank"])
def test_static_json_does_not_depend_on_the_sensors(tmp_path, capsys, name):
    """``rancf static --json`` with and without ``reaction`` sensors: the same keys, the
    reactions the same documented list (one object per support and joint: at, force, moment)
    with the same numbers."""
    assert main(["example", "copy", name, str(tmp_path)]) == 0
    capsys.readouterr()
    with_sensors = tmp_path / f"{name}.toml"
    text = with_sensors.read_text()
    bare = tmp_path / "bare.toml"
    bare.write_text(_without_reaction_sensors(text))
    docs = []
    for f in (with_sensors, bare):
        assert main(["static", str(f), "--json"]) == 0
        docs.append(json.loads(capsys.readouterr().out))
    a, b = docs
    assert set(a) == set(b)
    assert isinstance(a["reactions"], list) and a["reactions"]
    assert [r["at"] for r in a["reactions"]] == [r["at"] for r in b["reactions"]]
    for ra, rb in zip(a["reactions"], b["reactions"], strict=True):
        assert set(ra) <= {"at", "force", "moment"} and set(ra) == set(rb)
        assert ra["force"] == rb["force"] and ra.get("moment") == rb.get("moment")
    assert a["positions"] == b["positions"]
