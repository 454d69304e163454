"""The kinds of a joint and of a support: one class each in a registry, which the scenario's
schema, the Part and the core's record all read."""

from __future__ import annotations

import typing

import numpy as np
import pytest

from rancf.bodies import support_kinds
from rancf.bodies.properties import Support
from rancf.bodies.rigid import PointMass
from rancf.errors import InputError
from rancf.scenario.joints import JointTable
from rancf.solvers.static import solve_static
from rancf.system import Joint, Spring, System
from rancf.system.parts import joint_kinds


def test_the_schemas_kinds_are_the_registries():
    assert typing.get_args(JointTable.model_fields["kind"].annotation) == tuple(joint_kinds.KINDS)
    kinds = typing.get_args(typing.get_type_hints(Support)["kind"])
    assert kinds == tuple(support_kinds.KINDS)


def test_an_unknown_kind_is_one_line_naming_it():
    with pytest.raises(InputError) as info:
        joint_kinds.joint_kind("hinge")
    assert str(info.value).splitlines()[0].startswith("joints.kind")
    assert "hinge" in str(info.value) and "pin, revolute, fixed, slider, sliding" in str(info.value)
    with pytest.raises(InputError) as info:
        support_kinds.support_kind("hinge")
    assert '"pin", "clamp", "roller"' in str(info.value)


@pytest.mark.parametrize(
    ("kind", "dim", "driven", "moment"),
    [
        ("pin", 2, False, False),
        ("pin", 2, True, True),
        ("revolute", 2, False, False),
        ("revolute", 3, False, True),
        ("fixed", 2, False, True),
        ("slider", 3, False, False),
        ("sliding", 2, False, False),
    ],
)
def test_which_kinds_transmit_a_moment(kind, dim, driven, moment):
    assert joint_kinds.KINDS[kind].transmits_moment(dim, driven) is moment


class _Tether(joint_kinds.JointKind):
    """A pin that also reports how far its first place is from the origin (a kind added in one
    class)."""

    name = "tether"

    def columns(self, label: str) -> list[str]:
        return [f"{label}_r"]

    def values(self, system, k, y, lam) -> list[float]:
        x, _ = system.place_state(system.joints[k].between[0], y)
        return [float(np.linalg.norm(x))]

    def planar(self, info, axis, fa, fb) -> None:
        info["kind"] = "pin"  # the core's rows: a pin's


def test_a_kind_added_to_the_registry_is_one_class(monkeypatch):
    """A mass on a spring hung from the new kind hangs as from a pin; its column follows its
    class."""
    monkeypatch.setitem(joint_kinds.KINDS, "tether", _Tether())
    bodies = {"top": PointMass(2, 1.0, (0.1, 0.0)), "bob": PointMass(2, 2.0, (0.1, -1.0))}
    systems = [
        System(
            bodies,
            joints=[Joint(k, ("top", "ground"), name="j")],
            springs=[Spring(("top", "bob"), 100.0)],
            gravity=(0.0, -9.81),
        )
        for k in ("pin", "tether")
    ]
    pin, tether = (solve_static(s) for s in systems)
    np.testing.assert_allclose(tether.y, pin.y, rtol=0, atol=1e-12)
    s = systems[1]
    assert s.joints[0].sensors(s) == ["j_fx", "j_fy", "j_r"]
    values = s.joints[0].reactions(s, tether.y, tether.lam)
    assert values["j_fy"] == pytest.approx(3.0 * 9.81, rel=1e-9)
    assert values["j_r"] == pytest.approx(0.1, rel=1e-12)


def test_past_the_scenario_no_code_compares_a_joint_or_support_kinds_name():
    """The system, solvers, outputs and drivers ask the kind (its registry entry); the
    scenario's tables check their keys before a system exists, and shells have kinds of
    their own."""
    import re
    from pathlib import Path

    src = Path(joint_kinds.__file__).resolve().parents[2]
    names = "|".join([*joint_kinds.KINDS, *support_kinds.KINDS])
    compare = re.compile(rf"kind\s*(==|!=|in|not in)\s*\(?\s*[\"']({names})[\"']")
    found = [
        f"{f.relative_to(src)}:{i}"
        for folder in ("system", "solvers", "post", "runs", "sweep", "studies", "bodies")
        for f in sorted((src / folder).rglob("*.py"))
        if not f.name.startswith("shell")
        for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1)
        if compare.search(line)
    ]
    assert not found
