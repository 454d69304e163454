"""Modes and statics of systems: natural modes on the null space of the
constraints (sparse), zero-frequency modes (rigid-body motions, mechanisms) recognised, and
``rancf static`` / ``rancf modes`` on scenarios of several bodies."""

from __future__ import annotations

import json
from importlib import resources

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.cli import main
from rancf.mesh.factories import mesh_line
from rancf.scenario import Scenario
from rancf.solvers.modal import natural_modes
from rancf.solvers.static import solve_static
from rancf.system import Joint, Spring, System


def _cable(a, b, n, supports=(), element="ancf"):
    mat = Material(7850, 2e11, poisson_ratio=0.3)
    return Model(mesh_line(a, b, n), element, Section.circular(0.01), mat, list(supports))


def test_two_cables_fixed_together_vibrate_as_one():
    """A clamped cable of 16 elements, and two of 8 joined by a fixed joint (position and
    tangent direction; a straight cable at rest: the gradient's length is not excited in
    bending): the first five frequencies agree to 1e-8 (the dense QZ path)."""
    one = natural_modes(_cable([0, 0], [1, 0], 16, [Support(0, "clamp")]), count=5)
    two = System(
        {"a": _cable([0, 0], [0.5, 0], 8, [Support(0, "clamp")]), "b": _cable([0.5, 0], [1, 0], 8)},
        joints=[Joint("fixed", ("a:end", "b:start"))],
    )
    res = natural_modes(two, count=5)
    assert res.n_rigid == 0
    assert np.allclose(res.frequencies_hz, one.frequencies_hz, rtol=1e-8)
    assert res.modes.shape == (5, two.n)


def test_sparse_path_on_a_large_system():
    """Two cables of 200 elements joined by a fixed joint (1 606 unknowns: shift-invert
    Arnoldi on the sparse bordered matrices) against the one-body dense solver on one cable of
    400 elements: within 2e-5 (measured 1.3e-6 on the first mode, 1e-8 above: the round-off
    of this ill-conditioned fine mesh, the same size in the dense solver; 7.7e-6 on the first
    mode with OpenBLAS's Sandybridge kernels)."""
    one = natural_modes(_cable([0, 0], [1, 0], 400, [Support(0, "clamp")]), count=6)
    two = System(
        {
            "a": _cable([0, 0], [0.5, 0], 200, [Support(0, "clamp")]),
            "b": _cable([0.5, 0], [1, 0], 200),
        },
        joints=[Joint("fixed", ("a:end", "b:start"))],
    )
    res = natural_modes(two, count=6)
    assert res.n_rigid == 0
    assert np.allclose(res.frequencies_hz, one.frequencies_hz, rtol=2e-5)


@pytest.mark.parametrize(("dim", "rigid"), [(2, 3), (3, 6)])
def test_free_bodies_have_their_rigid_body_modes(dim, rigid):
    """A free cable (2D) or rod (3D) pinned to a free point mass: 3 or 6 rigid-body modes
    removed, the rest as for the body with the mass."""
    end = [1.0, 0.0] if dim == 2 else [1.0, 0.0, 0.0]
    body = _cable([0.0] * dim, end, 8, element="ancf" if dim == 2 else "rod")
    s = System(
        {"c": body, "m": PointMass(dim, 0.1, tuple(end))}, joints=[Joint("pin", ("c:end", "m"))]
    )
    res = natural_modes(s, count=4)
    assert res.n_rigid == rigid
    assert np.all(res.frequencies_hz > 1.0)


def test_spring_pendulum_about_its_equilibrium():
    """A point mass hanging from a spring on a fixed rigid anchor: the static solution (the
    tangent is singular at zero load: the swing has no stiffness before the spring pulls; the
    stabilized first step gets past it) stretches the spring by m g / k; about it the modes are
    the pendulum's √(g / L) and the spring's √(k / m) (the load stiffness of the constraints
    and spring included), to 1e-9."""
    g, k, m = 9.81, 100.0, 1.0
    s = System(
        {"mass": PointMass(2, m, (0.0, -1.0)), "anchor": RigidBody(2, 1.0, 1.0, (0.0, 0.0))},
        joints=[Joint("fixed", ("anchor", "ground"))],
        springs=[Spring(("mass", "anchor"), k)],
        gravity=[0.0, -g],
    )
    st = solve_static(s)
    length = 1.0 + m * g / k
    assert st.y[1] == pytest.approx(-length, rel=1e-12)
    res = natural_modes(s, st.y, 2, st.lam)
    want = np.sqrt([g / length, k / m]) / (2 * np.pi)
    assert np.allclose(res.frequencies_hz, want, rtol=1e-9)
    assert res.n_rigid == 0
    about_reference = natural_modes(s, count=1)  # no tension: the swing is a mechanism
    assert about_reference.n_rigid == 1


def _l_frame() -> Scenario:
    mat = {"density": 7850.0, "youngs_modulus": 2.0e11, "poisson_ratio": 0.3}
    rod = {"mesh": {"elements": 4, "element": "rod"}, "section": {"radius": 0.01}, "material": mat}

    def leg(name: str, a: list, b: list) -> dict:
        return {"name": name, "geometry": {"kind": "line", "start": a, "end": b}, **rod}

    return Scenario(
        bodies=[leg("a", [0, 0, 0], [1, 0, 0]), leg("b", [1, 0, 0], [1, 1, 0])],
        joints=[{"name": "corner", "kind": "fixed", "between": ["a:end", "b:start"]}],
        supports=[{"at": "a:start", "kind": "clamp"}],
        loads={"point": [{"at": "b:end", "force": [0.0, 0.0, -10.0]}]},
        sensors=[
            {"name": "corner_force", "kind": "reaction", "joint": "corner"},
            {"name": "root", "kind": "reaction", "at": "a:start"},
        ],
    )


def test_static_and_modes_commands_on_a_system(tmp_path, capsys):
    """``rancf static --json`` on the L-frame: the root's reaction balances the tip load, the
    corner joint carries it; ``--out`` writes the load path as a system run; ``rancf modes
    --json`` on the shipped slider-crank (its driven crank is not a mechanism) and the tether
    (its swing about the reference is)."""
    f = tmp_path / "frame.toml"
    _l_frame().save(f)
    assert main(["static", str(f), "--json", "--out", str(tmp_path / "st")]) == 0
    doc = json.loads(capsys.readouterr().out)
    reactions = {r["at"]: r for r in doc["reactions"]}  # the documented list, sensors or not
    assert list(reactions) == ["a:start", "corner"]
    assert reactions["a:start"]["force"][2] == pytest.approx(10.0, rel=1e-9)
    assert reactions["corner"]["force"][2] == pytest.approx(-10.0, rel=1e-9)  # on a:end
    assert doc["sensors"]["corner_force_z"] == pytest.approx(-10.0, rel=1e-9)  # on a:end
    assert doc["sensors"]["root_z"] == pytest.approx(10.0, rel=1e-9)
    assert (tmp_path / "st" / "bodies" / "b" / "results.npz").is_file()
    summary = json.loads((tmp_path / "st" / "summary.json").read_text())
    assert summary["analysis"] == "static" and summary["status"] == "completed"
    examples = resources.files("rancf.examples")
    with resources.as_file(examples / "slider-crank.toml") as p:
        assert main(["modes", str(p), "--json", "--count", "3"]) == 0
    crank = json.loads(capsys.readouterr().out)
    assert crank["rigid_body_modes_removed"] == 0 and crank["constraints"] == 8
    assert 100.0 < crank["frequencies_hz"][0] < 200.0  # the rod pinned at both ends
    with resources.as_file(examples / "slider-crank.toml") as p:  # unloaded: the same state
        assert main(["modes", str(p), "--json", "--count", "3", "--about", "static"]) == 0
    static = json.loads(capsys.readouterr().out)  # (the solve's multipliers of 1e-27 once
    assert np.allclose(static["frequencies_hz"], crank["frequencies_hz"], rtol=1e-9)  # broke it)
    with resources.as_file(examples / "tether-payload.toml") as p:
        assert main(["modes", str(p), "--json", "--count", "2"]) == 0
    assert json.loads(capsys.readouterr().out)["rigid_body_modes_removed"] == 1
