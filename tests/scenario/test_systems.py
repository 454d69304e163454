"""The system keys: bodies, places, joints, springs, time functions, new sensors.

Valid files parse into the typed models (what a builder reads); every bad one stops with one
line naming the file and the key; until the system solver takes them, the one-body commands
refuse systems, prescribed motion and time functions of loads with one line (exit 2).
"""

from __future__ import annotations

import copy
import json
import tomllib

import numpy as np
import pytest

from rancf.cli import main
from rancf.errors import ScenarioError
from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.scenario import FlexibleBody, PointMass, RigidBody, parse_scenario
from tests.scenario.systems import SLIDER_CRANK, TETHER_3D
from tests.scenario.test_scenario import BASE


def _sc(text: str, **changes):
    d = tomllib.loads(text)
    for path, value in changes.items():
        _set(d, path, value)
    return parse_scenario(d, "s.toml")


def _set(d: dict, path: str, value) -> None:
    """``a__0__b`` sets ``d["a"][0]["b"]`` (``None`` deletes)."""
    *head, last = [int(p) if p.isdigit() else p for p in path.split("__")]
    for p in head:
        d = d[p]
    if value is None:
        del d[last]
    elif isinstance(d, list) and last == len(d):
        d.append(value)
    else:
        d[last] = value


def test_slider_crank_models():
    sc = _sc(SLIDER_CRANK)
    assert sc.dim == 2 and len(sc.bodies) == 3
    crank, rod, slider = sc.bodies
    assert isinstance(crank, RigidBody) and isinstance(rod, FlexibleBody)
    assert isinstance(slider, PointMass) and rod.kind == "flexible"
    assert crank.points == {"pivot": [-0.075, 0.0], "tip": [0.075, 0.0]}
    motor = sc.joints[0]
    assert motor.between == ["crank:pivot", "ground"]
    f = sc.data["joints"][0]["angle"]
    assert f.kind == "spin_up" and f.duration == 0.05 and f.values == (150.0,)
    assert f.rate(1.0) == 150.0
    assert [s.columns(2) for s in sc.sensors] == [
        ["x_x", "x_y"],
        ["guide_force_x", "guide_force_y"],
        ["theta"],
        ["N"],
        ["p_x", "p_y"],
    ]
    assert sc.sensors[1].joint == "guide" and sc.sensors[3].places == ("rod:4",)
    assert sc.data["bodies"][1]["geometry"]["kind"] == "line"
    # places as the system builder takes them
    ends = [[str(sc.place(p).system_place()) for p in j.between] for j in sc.joints]
    assert ends == [
        ["crank:pivot", "ground"],
        ["crank:tip", "rod:0"],
        ["rod:-1", "slider"],
        ["slider", "ground"],
    ]
    assert set(sc.bodies_by_name) == {"crank", "rod", "slider"}
    with pytest.raises(ScenarioError, match=r"^s\.toml: \[place\] names no body: 'wheel'"):
        sc.place("wheel:1")


def test_spatial_system_models():
    sc = _sc(TETHER_3D)
    assert sc.dim == 3
    place = sc.support_place(0)
    assert (place.where, place.body, place.node) == ("node", "cable", 0)
    motion = sc.data["supports"][0]["motion"]
    assert motion.vector and motion.size == 3 and motion.interpolation == "cubic"
    assert motion.value(2.5).tolist() == [0.1, 0.1, 0.0]
    load = sc.data["loads"]["point"][0]["time"]
    assert load.value(0.25) == pytest.approx(0.5, rel=1e-15)
    assert sc.bodies[0].initial_motion.angular_velocity == [0.0, 0.1, 0.0]
    assert sc.springs[0].damping == 0.5 and sc.springs[0].length is None


def test_static_of_a_system_file(tmp_path, capsys):
    """``rancf static`` takes a system file: the slider-crank without loads rests in its
    reference (zero reactions)."""
    f = tmp_path / "s.toml"
    f.write_text(SLIDER_CRANK)
    assert main(["static", str(f), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["load_factors"][-1] == 1.0
    assert doc["method"] == "load" and doc["reactions"]  # one object per joint
    values = [v for r in doc["reactions"] for v in [*r["force"], *r.get("moment", [])]]
    assert max(map(abs, values)) <= 1e-9
    assert doc["positions"]["slider"] == pytest.approx([0.45, 0.0], abs=1e-12)


ONE_BODY_EXTRAS = [
    {"supports": [{"at": "start", "motion": {"ramp": 1.0, "value": [0.0, 0.1]}}]},
    {"loads": {"point": [{"at": "end", "force": [0.0, 1.0], "time": 2.0}]}},
    {"sensors": [{"name": "cm", "kind": "center_of_mass"}]},
]


@pytest.mark.parametrize("tables", ONE_BODY_EXTRAS)
def test_one_body_files_build_their_model_whatever_they_hold(tables):
    """Moving supports, time loads and system sensors are a flexible body's (or the run's):
    ``build_model`` gives the model, whose system equals the scenario's (the same coordinates
    and the same residual)."""
    d = tomllib.loads(BASE)
    d.update(tables)
    sc = parse_scenario(d, "s.toml")
    model, system = sc.build_model(), sc.build_system()
    from rancf.system import as_system

    one = as_system(model)
    assert one.n == system.n and one.m == system.m
    r1, r2 = (np.empty(s.n + s.m) for s in (one, system))
    for s, r in ((one, r1), (system, r2)):
        z = np.zeros(s.n)
        s.core.residual(ResidualPoint(s.y0, np.zeros(s.m), r, z, z), ResidualOptions(0.1))
    assert np.array_equal(r1, r2)


def test_a_system_file_has_no_one_model():
    """A file with joints is a system of parts: ``build_model`` refuses it in one line that
    points to ``build_system``."""
    d = tomllib.loads(BASE)
    d["joints"] = [{"name": "j", "kind": "pin", "between": ["end", "ground"]}]
    sc = parse_scenario(d, "s.toml")
    with pytest.raises(ScenarioError) as info:
        sc.build_model()
    text = str(info.value)
    assert text.startswith("s.toml: [joints] makes this scenario a system") and "\n" not in text
    assert "build_system()" in text


RIGID = {"name": "r", "kind": "rigid", "mass": 1.0, "inertia": 0.1, "position": [0.0, 0.0]}
BAD = [
    ("body-name-ground", {"bodies__2__name": "ground"}, "bodies[2].name", "reserved"),
    ("body-name-twice", {"bodies__2__name": "rod"}, "bodies[2].name", "twice"),
    ("body-name-colon", {"bodies__0__name": "a:b"}, "bodies[0].name", "simple name"),
    ("body-kind", {"bodies__2__kind": "spring"}, "bodies[2].kind", "'flexible', 'rigid'"),
    ("body-unknown-key", {"bodies__2__inertia": 1.0}, "bodies[2].inertia", "unknown key"),
    ("rigid-no-mass", {"bodies__0__mass": None}, "bodies[0].mass", "missing"),
    ("rigid-mass-0", {"bodies__0__mass": 0.0}, "bodies[0].mass", "> 0"),
    (
        "rigid-inertia-3-in-2d",
        {"bodies__0__inertia": [1.0, 1.0, 1.0]},
        "bodies[0].inertia",
        "number in 2D",
    ),
    (
        "rigid-orientation-in-2d",
        {"bodies__0__orientation": [[1.0, 0, 0]] * 3},
        "bodies[0].orientation",
        "orientation_deg",
    ),
    (
        "rigid-point-3d",
        {"bodies__0__points": {"tip": [0.1, 0.0, 0.0]}},
        "bodies[0].points.tip",
        "2 numbers",
    ),
    (
        "rigid-rate-vector",
        {"bodies__0__angular_velocity": [0.0, 0.0, 1.0]},
        "bodies[0].angular_velocity",
        "number in 2D",
    ),
    (
        "mass-velocity-3d",
        {"bodies__2__velocity": [0.0, 0.0, 1.0]},
        "bodies[2].velocity",
        "2 numbers",
    ),
    ("mixed-dims", {"bodies__2__position": [0.45, 0.0, 0.0]}, "bodies[2].position", "all bodies"),
    (
        "flex-angles",
        {"bodies__1__geometry__kind": "conic"},
        "bodies[1].geometry.angles_deg",
        "missing",
    ),
    ("flex-rod-2d", {"bodies__1__mesh__element": "rod"}, "bodies[1].mesh.element", "spatial"),
    ("flex-elements-0", {"bodies__1__mesh__elements": 0}, "bodies[1].mesh.elements", ">= 1"),
    (
        "flex-shear",
        {"bodies__1__material__shear_modulus": 1e9},
        "bodies[1].material.shear_modulus",
        "rod elements only",
    ),
    (
        "top-level-geometry",
        {"geometry": {"kind": "line", "start": [0, 0], "end": [1, 0]}},
        "geometry",
        "[bodies.geometry]",
    ),
    ("no-bodies-no-geometry", {"bodies": []}, "geometry", "required table is missing"),
    (
        "place-no-body",
        {"joints__1__between": ["crank:tip", "rood:start"]},
        "joints[1].between[1]",
        "'rood'",
    ),
    (
        "place-no-point",
        {"joints__1__between": ["crank:tipp", "rod:start"]},
        "joints[1].between[0]",
        "no point 'tipp'",
    ),
    (
        "place-flexible-alone",
        {"joints__1__between": ["crank:tip", "rod"]},
        "joints[1].between[1]",
        '"rod:start"',
    ),
    (
        "place-flexible-middle",
        {"joints__1__between": ["crank:tip", "rod:middle"]},
        "joints[1].between[1]",
        "node index",
    ),
    (
        "place-mass-point",
        {"joints__2__between": ["rod:end", "slider:x"]},
        "joints[2].between[1]",
        "point mass",
    ),
    (
        "place-int-with-bodies",
        {"joints__2__between": [-1, "slider"]},
        "joints[2].between[0]",
        "BODY:start",
    ),
    ("place-one-body-words", {"sensors__0__at": "end"}, "sensors[0].at", "no body: 'end'"),
    (
        "joint-ground-twice",
        {"joints__3__between": ["ground", "ground"]},
        "joints[3].between",
        "different places",
    ),
    (
        "joint-same-place",
        {"joints__1__between": ["rod:end", "rod:end"]},
        "joints[1].between",
        "different places",
    ),
    ("joint-one-place", {"joints__1__between": ["rod:end"]}, "joints[1].between", "two places"),
    ("joint-kind", {"joints__1__kind": "weld"}, "joints[1].kind", "one of"),
    ("joint-name-twice", {"joints__1__name": "motor"}, "joints[1].name", "twice"),
    (
        "revolute-in-2d",
        {"joints__1__kind": "revolute", "joints__1__axis": [0.0, 1.0]},
        "joints[1].kind",
        "spatial",
    ),
    ("slider-no-axis", {"joints__3__axis": None}, "joints[3].axis", "required"),
    ("slider-axis-zero", {"joints__3__axis": [0.0, 0.0]}, "joints[3].axis", "nonzero"),
    ("slider-axis-3d", {"joints__3__axis": [1.0, 0.0, 0.0]}, "joints[3].axis", "2 numbers"),
    ("pin-axis", {"joints__1__axis": [1.0, 0.0]}, "joints[1].axis", "revolute and slider"),
    ("fixed-angle", {"joints__0__kind": "fixed"}, "joints[0].angle", "pin and revolute"),
    ("fixed-to-mass", {"joints__2__kind": "fixed"}, "joints[2].kind", "point mass"),
    ("angle-without-rigid", {"joints__2__angle": 1.0}, "joints[2].angle", "rigid body"),
    ("angle-vector", {"joints__0__angle": [1.0, 2.0]}, "joints[0].angle", "scalar"),
    ("angle-kind", {"joints__0__angle": {"spin": 1.0}}, "joints[0].angle", "spin_up"),
    (
        "angle-two-kinds",
        {"joints__0__angle": {"ramp": 1.0, "harmonic": 2.0}},
        "joints[0].angle",
        "ramp, harmonic",
    ),
    (
        "spin-up-negative",
        {"joints__0__angle": {"spin_up": -1.0, "rate": 1.0}},
        "joints[0].angle.spin_up",
        "> 0",
    ),
    (
        "spin-up-unknown",
        {"joints__0__angle": {"spin_up": 1.0, "omega": 1.0}},
        "joints[0].angle.omega",
        "unknown key",
    ),
    (
        "table-times",
        {"joints__0__angle": {"table": [[0.0, 0.0], [1.0, 1.0], [0.5, 2.0]]}},
        "joints[0].angle.table[2][0]",
        "increase",
    ),
    (
        "table-rows",
        {"joints__0__angle": {"table": [[0.0, 0.0], [1.0, 1.0, 2.0]]}},
        "joints[0].angle.table[1]",
        "first row",
    ),
    (
        "table-one-row",
        {"joints__0__angle": {"table": [[0.0, 0.0]]}},
        "joints[0].angle.table",
        "at least 2",
    ),
    (
        "table-nan",
        {"joints__0__angle": {"table": [[0.0, 0.0], [1.0, float("nan")]]}},
        "joints[0].angle.table[1][1]",
        "finite",
    ),
    (
        "table-interpolation",
        {"joints__0__angle": {"table": [[0.0, 0.0], [1.0, 1.0]], "interpolation": "spline"}},
        "joints[0].angle.interpolation",
        "'linear' or 'cubic'",
    ),
    (
        "harmonic-phase-string",
        {"joints__0__angle": {"harmonic": 1.0, "phase_deg": "90"}},
        "joints[0].angle.phase_deg",
        "number",
    ),
    (
        "spring-nothing",
        {"springs": [{"between": ["crank", "slider"], "stiffness": 0.0}]},
        "springs[0].stiffness",
        "does nothing",
    ),
    (
        "spring-stiffness-missing",
        {"springs": [{"between": ["crank", "slider"]}]},
        "springs[0].stiffness",
        "missing",
    ),
    (
        "spring-length-0",
        {"springs": [{"between": ["crank", "slider"], "stiffness": 1.0, "length": 0.0}]},
        "springs[0].length",
        "> 0",
    ),
    ("support-ground", {"supports": [{"at": "ground"}]}, "supports[0].at", "ground"),
    (
        "support-motion-scalar",
        {"supports": [{"at": "rod:end", "motion": 0.1}]},
        "supports[0].motion",
        "vector",
    ),
    (
        "support-motion-3d",
        {"supports": [{"at": "rod:end", "motion": [0.1, 0.0, 0.0]}]},
        "supports[0].motion",
        "2 components",
    ),
    (
        "support-motion-spin-up",
        {"supports": [{"at": "rod:end", "motion": {"spin_up": 1.0, "rate": 1.0}}]},
        "supports[0].motion",
        "vector",
    ),
    (
        "support-motion-and-position",
        {"supports": [{"at": "rod:end", "motion": [0.1, 0.0], "position": [0.5, 0.0]}]},
        "supports[0].motion",
        "not both",
    ),
    (
        "support-clamp-mass",
        {"supports": [{"at": "slider", "kind": "clamp"}]},
        "supports[0].kind",
        "point mass",
    ),
    (
        "load-time-and-frequency",
        {
            "loads": {
                "point": [{"at": "slider", "force": [1.0, 0.0], "time": 1.0, "frequency_hz": 2.0}]
            }
        },
        "loads.point[0].time",
        "not both",
    ),
    (
        "load-time-vector",
        {
            "loads": {
                "point": [
                    {
                        "at": "slider",
                        "force": [1.0, 0.0],
                        "time": {"ramp": 1.0, "value": [1.0, 2.0]},
                    }
                ]
            }
        },
        "loads.point[0].time",
        "scalar",
    ),
    (
        "load-moment-on-cable",
        {"loads": {"point": [{"at": "rod:end", "moment": [0.0, 0.0, 1.0]}]}},
        "loads.point[0].moment",
        "rod elements only",
    ),
    (
        "load-moment-2d-rigid",
        {"loads": {"point": [{"at": "crank", "moment": [0.0, 0.0, 1.0]}]}},
        "loads.point[0].moment",
        "number in 2D",
    ),
    (
        "velocity-on-rigid",
        {"initial_velocity": [{"at": "crank", "value": [0.0, 1.0]}]},
        "initial_velocity[0].at",
        "node of a flexible body",
    ),
    (
        "motion-top-and-body",
        {
            "initial_motion": {"angular_velocity": 1.0},
            "bodies__1__initial_motion": {"angular_velocity": 1.0},
        },
        "initial_motion",
        "not both",
    ),
    (
        "body-motion-vector-2d",
        {"bodies__1__initial_motion": {"angular_velocity": [0, 0, 1.0]}},
        "bodies[1].initial_motion.angular_velocity",
        "number in 2D",
    ),
    ("sensor-joint-unknown", {"sensors__1__joint": "guid"}, "sensors[1].joint", "no joint"),
    ("sensor-reaction-both", {"sensors__1__at": "slider"}, "sensors[1].joint", "one of them"),
    (
        "sensor-reaction-not-support",
        {"sensors__1__joint": None, "sensors__1__at": "slider"},
        "sensors[1].at",
        "support",
    ),
    ("sensor-angle-flexible", {"sensors__2__body": "rod"}, "sensors[2].body", "rigid body"),
    ("sensor-angle-no-body", {"sensors__2__body": None}, "sensors[2].body", "needs body"),
    ("sensor-angle-at", {"sensors__2__at": "crank"}, "sensors[2].at", "not for a angle"),
    ("sensor-axial-on-mass", {"sensors__3__at": "slider"}, "sensors[3].at", "flexible body"),
    ("sensor-body-unknown", {"sensors__4__body": "wheel"}, "sensors[4].body", "no body"),
    (
        "sensor-joint-on-position",
        {"sensors__0__joint": "guide"},
        "sensors[0].joint",
        "reaction sensors only",
    ),
    ("sensor-twist-on-cable", {"sensors__0__kind": "twist"}, "sensors[0].kind", "rod elements"),
]


@pytest.mark.parametrize(
    ("changes", "key", "needle"), [c[1:] for c in BAD], ids=[c[0] for c in BAD]
)
def test_bad_system_files_name_the_key(changes, key, needle):
    with pytest.raises(ScenarioError) as info:
        _sc(SLIDER_CRANK, **changes)
    msg = str(info.value)
    assert msg.startswith(f"s.toml: [{key}] "), msg
    assert needle in msg and "\n" not in msg, msg


BAD_3D = [
    (
        "inertia-triangle",
        {"bodies__2__inertia": [0.1, 0.1, 0.5]},
        "bodies[2].inertia",
        "Ixx <= Iyy + Izz",
    ),
    ("inertia-number-3d", {"bodies__2__inertia": 0.1}, "bodies[2].inertia", "[Ixx, Iyy, Izz]"),
    (
        "orientation-not-rotation",
        {"bodies__2__orientation": [[1, 0, 0], [0, 1, 0], [0, 0, -1]]},
        "bodies[2].orientation",
        "rotation matrix",
    ),
    (
        "orientation-rows",
        {"bodies__2__orientation": [[1, 0, 0], [0, 1, 0]]},
        "bodies[2].orientation",
        "3 rows",
    ),
    (
        "orientation-deg-3d",
        {"bodies__2__orientation_deg": 30.0},
        "bodies[2].orientation_deg",
        "is 2D",
    ),
    (
        "pin-angle-3d",
        {"joints": [{"name": "m", "kind": "pin", "between": ["box", "ground"], "angle": 1.0}]},
        "joints[0].angle",
        "spherical",
    ),
    ("revolute-no-axis", {"joints__1__axis": None}, "joints[1].axis", "required"),
    (
        "motion-table-width",
        {"supports__0__motion": {"table": [[0.0, 0.0, 0.0], [1.0, 0.1, 0.0]]}},
        "supports[0].motion",
        "3 components",
    ),
    ("rigid-moment-number", {"loads__point__0__moment": 0.1}, "loads.point[0].moment", "3 numbers"),
    (
        "rod-twist-at-mass",
        {"sensors": [{"name": "tw", "kind": "twist", "at": "payload"}]},
        "sensors[0].kind",
        "rod elements",
    ),
    (
        "support-twice-at-a-mass",
        {"supports__1": {"at": "payload", "kind": "pin"}, "supports__2": {"at": "payload"}},
        "supports[2].at",
        "'payload' is held by supports[1] already: one support per place",
    ),
]


@pytest.mark.parametrize(
    ("changes", "key", "needle"), [c[1:] for c in BAD_3D], ids=[c[0] for c in BAD_3D]
)
def test_bad_spatial_system_files_name_the_key(changes, key, needle):
    with pytest.raises(ScenarioError) as info:
        _sc(TETHER_3D, **changes)
    msg = str(info.value)
    assert msg.startswith(f"s.toml: [{key}] "), msg
    assert needle in msg, msg


def test_bad_system_file_through_the_cli(tmp_path, capsys):
    """A wrong place stops every command with one line, exit 2, nothing written."""
    import tomli_w

    d = tomllib.loads(SLIDER_CRANK)
    d["joints"][1]["between"] = ["crank:tip", "rood:start"]
    f = tmp_path / "s.toml"
    f.write_text(tomli_w.dumps(copy.deepcopy(d)))
    assert main(["simulate", str(f), "--out", str(tmp_path / "run")]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.strip().splitlines() == [
        f"rancf: error: {f}: [joints[1].between[1]] names no body: 'rood' "
        "(bodies: crank, rod, slider)"
    ]
    assert not (tmp_path / "run").exists()


@pytest.mark.parametrize(
    ("changes", "key", "needle"),
    [
        (
            {"joints__2": {"name": "anchor", "kind": "pin", "between": ["ground", "cable:0"]}},
            "joints[2].between[1]",
            "'cable:0' is held by supports[0] already: a joint to the ground there holds it again",
        ),
        (
            {
                "supports__1": {"at": "payload", "kind": "pin"},
                "joints__2": {"name": "anchor", "kind": "pin", "between": ["payload", "ground"]},
            },
            "joints[2].between[0]",
            "'payload' is held by supports[1] already: a joint to the ground there holds it again",
        ),
        (
            {"joints__2": {"name": "again", "kind": "pin", "between": ["payload", "cable:-1"]}},
            "joints[2].between",
            "'payload' and 'cable:-1' are joined by joints[0] already: a second joint between",
        ),
    ],
    ids=["node", "point-mass", "joint-pair"],
)
def test_a_joint_to_the_ground_at_a_supported_place_is_refused_naming_both_keys(
    changes, key, needle
):
    """Its rows repeat the support's (or a second joint between the same two places repeats
    the first's): the solves failed without naming a key."""
    with pytest.raises(ScenarioError) as info:
        _sc(TETHER_3D, **changes).build_system()
    msg = str(info.value)
    assert msg.startswith(f"s.toml: [{key}] "), msg
    assert needle in msg and "redundant constraint" in msg, msg


def test_a_joint_to_the_ground_at_another_node_is_kept():
    joint = {"name": "anchor", "kind": "pin", "between": ["ground", "cable:end"]}
    system = _sc(TETHER_3D, joints__2=joint).build_system()
    assert "anchor" in [j.name for j in system.joints]
