"""Clamp paths: a support's motion as absolute positions (a path file with a header row), and a
clamp whose direction turns (``rotation``): the end stays on the path, its tangent (a rod's
whole frame, twist included) turns with the rotation, and the constraint rows of the turning
frame have the Jacobian of their central differences."""

from __future__ import annotations

import contextlib
import io

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.time_function import TimeFunction
from rancf.cli import main
from rancf.errors import ScenarioError
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.factories import mesh_line
from rancf.post.system_run import load_run
from rancf.scenario import load_scenario
from rancf.system import Joint, System

T_TURN = 1.0  # [s] the gripper's move and turn
AXIS = np.array([0.3, 0.2, 1.0]) / np.linalg.norm([0.3, 0.2, 1.0])  # the 3D turn's axis


def _smooth(t: np.ndarray) -> np.ndarray:
    """The cubic ``3 s² − 2 s³`` of ``s = t / T_TURN`` (held at 1 after the turn)."""
    s = np.clip(np.asarray(t, dtype=float) / T_TURN, 0.0, 1.0)
    return 3 * s**2 - 2 * s**3


def _path(t: np.ndarray, dim: int) -> np.ndarray:
    """The gripper's absolute positions: from the cable's end (0.6, 0[, 0]) along a cubic."""
    h = _smooth(t)
    cols = [0.6 - 0.25 * h, 0.15 * h] if dim == 2 else [0.6 - 0.25 * h, 0.1 * h, 0.15 * h]
    return np.stack(cols, axis=-1)


def _turn(t: np.ndarray, dim: int) -> np.ndarray:
    """90 degrees about z (2D), or about AXIS (3D, a rotation vector), along the same cubic."""
    a = 0.5 * np.pi * _smooth(t)
    return a[:, None] if dim == 2 else a[:, None] * AXIS


def _csv(path, header: str, rows: np.ndarray) -> None:
    lines = [header] + [",".join(f"{x:.15g}" for x in r) for r in rows]
    path.write_text("\n".join(lines) + "\n")


def _harness(tmp_path, dim: int, element: str = "rancf", extra: str = "") -> str:
    """A 0.6 m harness cable clamped at the origin; its gripper end follows path.csv (absolute
    positions, a header row) and turns by turn.csv."""
    t = np.linspace(0.0, T_TURN, 11)
    axes = "xyz"[:dim]
    _csv(tmp_path / "path.csv", "t," + ",".join(axes), np.c_[t, _path(t, dim)])
    names = "angle" if dim == 2 else "rx,ry,rz"
    _csv(tmp_path / "turn.csv", f"t,{names}", np.c_[t, _turn(t, dim)])
    zero = ", 0.0" * (dim - 1)
    return f"""
[geometry]
kind = "line"
start = [0.0{zero}]
end = [0.6{zero}]
[mesh]
elements = 6
element = "{element}"
[section]
radius = 0.004
[material]
density = 1500.0
youngs_modulus = 1.0e8
{"shear_modulus = 4.0e7" if element == "rod" else ""}
[[supports]]
at = "start"
kind = "clamp"
[[supports]]
at = "end"
kind = "clamp"
motion = {{ table = "path.csv", absolute = true, interpolation = "cubic" }}
rotation = {{ table = "turn.csv", interpolation = "cubic" }}
[loads]
gravity = [0.0, {"-9.81" if dim == 2 else "0.0, -9.81"}]
[damping]
mass_proportional = 2.0
[solver]
t_end = 1.3
step = 2.0e-3
output_step = 0.05
initial_state = "static"
{extra}"""


def _simulate(tmp_path, text: str, out: str = "run"):
    (tmp_path / "s.toml").write_text(text)
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        assert main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / out)]) == 0
    return load_run(tmp_path / out)


def _end_frames(run) -> tuple[np.ndarray, np.ndarray]:
    """The end node's position and unit tangent at every output."""
    body = run.body()
    q = body.q.reshape(len(body.t), body.n_nodes, -1)
    dim = body.dim
    g = q[:, -1, dim : 2 * dim]
    return q[:, -1, :dim], g / np.linalg.norm(g, axis=1, keepdims=True)


def test_planar_gripper_follows_its_path_and_turns_90_degrees(tmp_path):
    run = _simulate(tmp_path, _harness(tmp_path, 2))
    t = run.body().t
    x, tangent = _end_frames(run)
    assert np.abs(x - _path(t, 2)).max() < 1e-6  # on the path at every output
    angle = np.degrees(np.arctan2(tangent[:, 1], tangent[:, 0]))
    after = t >= T_TURN
    assert after.sum() >= 3 and np.all(np.abs(angle[after] - 90.0) < 5.0)
    assert np.abs(angle - 90.0 * _smooth(t)).max() < 1e-6  # and all along the turn
    head = (tmp_path / "run" / "reactions.csv").read_text().splitlines()[0]
    assert head.split(",")[4:] == ["end_fx", "end_fy", "end_mz"]  # a support's columns


def test_spatial_rod_end_frame_follows_the_rotation_vector(tmp_path):
    run = _simulate(tmp_path, _harness(tmp_path, 3, "rod"))
    body = run.body()
    x, tangent = _end_frames(run)
    assert np.abs(x - _path(body.t, 3)).max() < 1e-6
    m1 = np.asarray(body.directors)[:, -1]  # the end's first director: the twist
    rot = Rotation.from_rotvec(_turn(body.t, 3)).as_matrix()
    assert np.abs(np.einsum("kij,j->ki", rot, tangent[0]) - tangent).max() < 1e-8
    assert np.abs(np.einsum("kij,j->ki", rot, m1[0]) - m1).max() < 1e-8
    assert np.abs(m1[-1] - m1[0]).max() > 0.3  # it did turn


def test_spatial_cable_tangent_follows_the_rotation_vector(tmp_path):
    run = _simulate(tmp_path, _harness(tmp_path, 3, "rancf"))
    x, tangent = _end_frames(run)
    rot = Rotation.from_rotvec(_turn(run.body().t, 3)).as_matrix()
    assert np.abs(np.einsum("kij,j->ki", rot, tangent[0]) - tangent).max() < 1e-8


def test_a_turning_clamp_that_does_not_turn_is_a_clamp(tmp_path):
    """Its reactions (from the joint's multipliers) are the held clamp's (from the held rows),
    and a reaction sensor at it reads them."""
    plain = _harness(tmp_path, 2).replace(
        'rotation = { table = "turn.csv", interpolation = "cubic" }\n', ""
    )
    plain = plain.replace(", absolute = true", "").replace("path.csv", "still.csv")
    _csv(tmp_path / "still.csv", "t,x,y", np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]))
    plain = plain.replace("t_end = 1.3", "t_end = 0.1")
    sensor = '\n[[sensors]]\nname = "grip"\nkind = "reaction"\nat = "end"\n'
    ref = _simulate(tmp_path, plain + sensor)
    turning = plain.replace('kind = "clamp"\nmotion', 'kind = "clamp"\nrotation = 0.0\nmotion')
    assert turning != plain
    got = _simulate(tmp_path, turning + sensor, "turning")
    assert np.abs(got.sensors - ref.sensors).max() < 1e-6 * np.abs(ref.sensors).max()
    assert np.abs(ref.sensors[:, -1]).max() > 1e-3  # a clamp moment


@pytest.mark.parametrize("turning", [False, True], ids=["held", "turning"])
def test_gripper_in_a_system_file(tmp_path, turning):
    """The same keys in a [[bodies]] file: a held support on an absolute path (its coordinates
    prescribed: exact), and the turning clamp (its reaction under the support's name)."""
    text = _harness(tmp_path, 2).replace(
        "[geometry]", '[[bodies]]\nname = "cable"\n[bodies.geometry]'
    )
    for k in ("mesh", "section", "material"):
        text = text.replace(f"[{k}]", f"[bodies.{k}]")
    text = text.replace('at = "start"', 'at = "cable:start"').replace(
        'at = "end"', 'at = "cable:end"'
    )
    if not turning:
        text = text.replace('rotation = { table = "turn.csv", interpolation = "cubic" }\n', "")
    run = _simulate(tmp_path, text)
    t = run.body().t
    x, tangent = _end_frames(run)
    assert np.abs(x - _path(t, 2)).max() < (1e-6 if turning else 1e-12)
    angle = np.degrees(np.arctan2(tangent[:, 1], tangent[:, 0]))
    assert np.abs(angle - (90.0 * _smooth(t) if turning else 0.0)).max() < 1e-6
    head = (tmp_path / "run" / "reactions.csv").read_text().splitlines()[0].split(",")
    assert head[4:] == ["cable:end_fx", "cable:end_fy", "cable:end_mz"]


def _scenario_error(tmp_path, text: str) -> str:
    (tmp_path / "s.toml").write_text(text)
    with pytest.raises(ScenarioError) as exc:
        load_scenario(tmp_path / "s.toml").build_system()
    return str(exc.value)


def test_a_path_that_starts_away_from_the_support_is_refused_in_one_line(tmp_path):
    text = _harness(tmp_path, 2).replace('initial_state = "static"', "")
    rows = np.loadtxt(tmp_path / "path.csv", delimiter=",", skiprows=1)
    rows[:, 1] += 0.01  # 1 cm to the right
    _csv(tmp_path / "path.csv", "t,x,y", rows)
    msg = _scenario_error(tmp_path, text)
    assert "supports[1].motion" in msg and "0.01 m away" in msg and "build_up" in msg
    assert "\n" not in msg
    built_up = text.replace("absolute = true,", "absolute = true, build_up = 0.2,")
    (tmp_path / "s.toml").write_text(built_up)
    load_scenario(tmp_path / "s.toml").build_system()  # the support moves onto the path


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (('kind = "clamp"\nmotion', 'kind = "pin"\nmotion'), 'applies to kind = "clamp" only'),
        (("rotation = { table", "direction = [1.0, 0.0]\nrotation = { table"), "not both"),
    ],
)
def test_rotation_on_other_supports_is_refused_in_one_line(tmp_path, change, words):
    text = _harness(tmp_path, 2).replace(*change)
    (tmp_path / "s.toml").write_text(text)
    with pytest.raises(ScenarioError) as exc:
        load_scenario(tmp_path / "s.toml")
    assert "supports[1].rotation" in str(exc.value) and words in str(exc.value)
    assert "\n" not in str(exc.value)


def test_a_rotation_of_the_wrong_size_is_refused(tmp_path):
    text = _harness(tmp_path, 3, "rod").replace("turn.csv", "angle.csv")
    _csv(tmp_path / "angle.csv", "t,a", np.array([[0.0, 0.0], [1.0, 0.5]]))
    msg = _scenario_error(tmp_path, text)
    assert "supports[1].rotation" in msg and "rotation vector of 3" in msg


def test_absolute_belongs_to_support_motions(tmp_path):
    text = _harness(tmp_path, 2).replace(
        'rotation = { table = "turn.csv",', 'rotation = { absolute = true, table = "turn.csv",'
    )
    (tmp_path / "s.toml").write_text(text)
    with pytest.raises(ScenarioError) as exc:
        load_scenario(tmp_path / "s.toml")
    assert "absolute" in str(exc.value)


def _check_multiplier_terms(s: System, y: np.ndarray, t: float, rng) -> None:
    """The balance's tangent in y with multipliers (Gᵀλ and its derivative, the turned frame's
    vectors in it) against central differences of the static residual, on the free rows."""
    z, lam = np.zeros(s.n), rng.standard_normal(s.m)
    dense = np.empty((s.n + s.m) ** 2)
    assert s.core.dense_jacobian(
        StatePoint(y, z, z, lam), TangentOptions(t, 1.0, dynamic=False), dense
    )
    free = np.flatnonzero(~s.fixed)
    jac = dense.reshape(s.n + s.m, -1)[np.ix_(free, free)]
    fd = np.empty_like(jac)
    r = np.empty(s.n + s.m)
    for c, j in enumerate(free):
        h = 1e-6 * (1 + abs(y[j]))
        out = []
        for sign in (1.0, -1.0):
            yy = y.copy()
            yy[j] += sign * h
            assert s.core.residual(ResidualPoint(yy, lam, r), ResidualOptions(t, dynamic=False))
            out.append(r[free].copy())
        fd[:, c] = (out[0] - out[1]) / (2 * h)
    assert np.abs(jac - fd).max() <= 2e-6 * max(1.0, np.abs(fd).max())


def _systems() -> list[System]:
    """A 2D cable, a 3D cable and a 3D rod, each clamped at its start and held at its end by a
    frame turning by a ramp (the rows of a turning clamp)."""
    out = []
    for dim, element, rot in (
        (2, "rancf", 0.7),
        (3, "rancf", [0.3, -0.2, 0.6]),
        (3, "rod", [0.3, -0.2, 0.6]),
    ):
        mat = Material(1000.0, 1e7, poisson_ratio=0.3)
        end = [1.0, 0.2] if dim == 2 else [1.0, 0.2, -0.1]
        model = Model(
            mesh_line([0.0] * dim, end, 3),
            element,
            Section.circular(0.01),
            mat,
            [Support(0, "clamp")],
        )
        turn = TimeFunction.ramp(1.0, rot)
        joint = Joint("fixed", ("c:end", "ground"), name="grip", rotation=turn)
        out.append(System({"c": model}, [joint]))
    return out


@pytest.mark.parametrize("k", [0, 1, 2])
def test_turning_frame_rows_against_differences(k, rng):
    """At t = 0.6 (turned by 0.6 of the ramp), at a perturbed state: the Jacobian of the
    constraint rows against central differences; and the rows vanish where the end is turned
    by the frame's rotation (the constraint follows the rotated reference tangent)."""
    s = _systems()[k]
    t = 0.6
    y = s.y0 + 1e-2 * rng.standard_normal(s.n)
    y[s.fixed] = s.y0[s.fixed]
    z = np.zeros(s.n)
    dense = np.empty((s.n + s.m) ** 2)
    assert s.core.dense_jacobian(StatePoint(y, z, z, np.zeros(s.m)), TangentOptions(t, 1.0), dense)
    rows = dense.reshape(s.n + s.m, -1)[s.n :, : s.n]
    fd = np.empty((s.m, s.n))
    for j in range(s.n):
        h = 1e-6 * (1 + abs(y[j]))
        gp, gm = np.empty(s.m), np.empty(s.m)
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        s.core.constraints(yp, t, gp)
        s.core.constraints(ym, t, gm)
        fd[:, j] = (gp - gm) / (2 * h)
    assert np.abs(fd).max() > 0.1
    assert np.allclose(rows, fd, rtol=0, atol=1e-7 * np.abs(fd).max())
    _check_multiplier_terms(s, y, t, rng)
    if k == 2:
        return  # a rod's frame: its twist too (test_spatial_rod_end_frame_follows_...)
    turned = s.y0.copy()  # the end's gradient turned by the frame's rotation at t
    rot = np.atleast_1d(TimeFunction.ramp(1.0, [0.7] if k == 0 else [0.3, -0.2, 0.6])(t))
    dim = s.dim
    r = Rotation.from_rotvec([0.0, 0.0, rot[0]] if dim == 2 else rot).as_matrix()[:dim, :dim]
    body = s.bodies["c"]
    q = body.q_from_y(s.y0)
    base = (body.n_nodes - 1) * body.dpn
    q[base + dim : base + 2 * dim] = r @ q[base + dim : base + 2 * dim]
    turned[:] = body.y_from_q(q)
    g = np.empty(s.m)
    s.core.constraints(turned, t, g)
    assert np.abs(g).max() < 1e-12
    s.core.constraints(s.y0, t, g)  # the unturned end breaks them
    assert np.abs(g).max() > 0.1


def test_a_static_start_installs_the_gripper_at_the_path_and_angle_of_t0(tmp_path):
    """A path 1 cm off the cable's end and a turn that starts at 0.3 rad, from the static
    equilibrium: the statics puts the gripper there, on the path and at the angle from the
    first stored state on."""
    text = _harness(tmp_path, 2).replace("t_end = 1.3", "t_end = 0.5")
    rows = np.loadtxt(tmp_path / "path.csv", delimiter=",", skiprows=1)
    rows[:, 1] += 0.01
    _csv(tmp_path / "path.csv", "t,x,y", rows)
    turn = np.loadtxt(tmp_path / "turn.csv", delimiter=",", skiprows=1)
    turn[:, 1] += 0.3
    _csv(tmp_path / "turn.csv", "t,angle", turn)
    run = _simulate(tmp_path, text)
    t = run.body().t
    x, tangent = _end_frames(run)
    assert np.abs(x - _path(t, 2) - [0.01, 0.0]).max() < 1e-6
    angle = np.arctan2(tangent[:, 1], tangent[:, 0])
    assert np.abs(angle - 0.3 - 0.5 * np.pi * _smooth(t)).max() < 1e-8
