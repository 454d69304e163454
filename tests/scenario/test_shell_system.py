"""Shell bodies in the core's System: the static driver (load steps, arc length, run folder),
modes and simulate on shell scenarios, checked against the obstacle course's references and
against the shell kernel solved on its own (supports as Lagrange multipliers)."""

from __future__ import annotations

import copy
import json
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spl

from rancf.bodies.shell_supports import constraint_rows
from rancf.errors import ScenarioError
from rancf.runs.modes import run_modes
from rancf.runs.static import run_static
from rancf.scenario import Scenario
from rancf.scenario.shell_build import shell_body, shell_load

DATA = Path(__file__).parent / "data"
ROOF = DATA / "scordelis_lo.toml"
PINCHED = DATA / "pinched_cylinder.toml"
PLATE = DATA / "plate_simply_supported.toml"
#: The middle of the roof's free edge moves down 0.3006 (linear; MacNeal & Harder 1985).
ROOF_REFERENCE = 0.3006
#: The pinched cylinder's displacement under the load (linear; MacNeal & Harder 1985).
PINCHED_REFERENCE = 1.8248e-5
#: pi sqrt(D / (rho t)) / a^2 of the simply supported steel plate (1 m, 10 mm).
PLATE_F1 = 47.986


def _raw(path: Path) -> dict:
    return tomllib.loads(path.read_text())


def _scenario(raw: dict, path: Path) -> Scenario:
    return Scenario.from_dict(copy.deepcopy(raw), str(path))


def _displacement(sc: Scenario, at: tuple[float, float]) -> np.ndarray:
    run = run_static(sc)
    b = run.system.flex[0]
    y = run.result.y[run.system.body_slice(b.body.name)]
    return b.positions(y, at) - b.positions(b.y0, at)


def _kernel_newton(sc: Scenario, steps: int = 10) -> np.ndarray:
    """The static state of a one-shell scenario solved with the kernel alone: Newton on
    ``f(q) + Cᵀ λ = p f_ext``, ``C (q - q0) = 0`` in ``steps`` equal load steps."""
    body = shell_body(sc, 0)
    from rancf.kernels.shell import ShellKernel

    k = ShellKernel.from_mesh(
        body.mesh, body.thickness, body.youngs_modulus, body.poisson_ratio, body.density
    )
    f, (c, _) = shell_load(sc, body), constraint_rows(body)
    q, lam = body.q0.copy(), np.zeros(c.shape[0])
    for p in np.linspace(1.0 / steps, 1.0, steps):
        for _ in range(30):
            r = np.concatenate([k.forces(q) + c.T @ lam - p * f, c @ (q - body.q0)])
            if np.abs(r).max() < 1e-10 * np.abs(f).max():
                break
            a = sp.bmat([[k.tangent(q), c.T], [c, None]], format="csc")
            d = spl.spsolve(a, -r)
            q, lam = q + d[: body.n_dofs], lam + d[body.n_dofs :]
    return q


def test_the_roof_in_the_linear_limit_meets_the_reference():
    """The static driver is geometrically nonlinear; under 1e-4 of the roof's load it is
    linear, and the middle of the free edge moves 1e-4 of the reference."""
    raw = _raw(ROOF)
    scale = 1e-4
    raw["loads"]["distributed"][0]["force"] = [0.0, 0.0, -90.0 * scale]
    w = -_displacement(_scenario(raw, ROOF), (1.0, 1.0))[2] / scale
    assert abs(w - ROOF_REFERENCE) < 0.015 * ROOF_REFERENCE, w


def test_the_roof_under_its_full_load_is_the_kernels_nonlinear_state():
    """Under the full load the roof's deflection (0.2529 at 4 x 4, geometrically nonlinear) is
    the state the shell kernel reaches on its own with the supports as multipliers (2 x 2
    here: the same equations, fewer of them)."""
    raw = _raw(ROOF)
    raw["mesh"]["elements"] = [2, 2]
    sc = _scenario(raw, ROOF)
    run = run_static(sc)
    b = run.system.flex[0]
    q = b.to_body(b.q_from_y(run.result.y[run.system.body_slice(b.body.name)]))
    ref = _kernel_newton(sc, 4)
    assert np.abs(q - ref).max() < 1e-7 * np.abs(ref - b.body.q0).max()
    w = -(b.body.position((1.0, 1.0), q) - b.body.position((1.0, 1.0)))[2]
    assert 0.23 < w < 0.27, w  # stiffer than the linear 0.3006: the membrane carries more
    assert run.sensors["free_mid_z"] == pytest.approx(b.body.position((1.0, 1.0), q)[2])


def test_arc_length_follows_the_roof_to_the_same_state():
    raw = _raw(ROOF)
    raw["mesh"]["elements"] = [2, 2]
    load = run_static(_scenario(raw, ROOF))
    raw["solver"] = {"static_method": "arc_length"}
    arc = run_static(_scenario(raw, ROOF))
    assert arc.result.method == "arc_length" and arc.result.load_factors[-1] == 1.0
    assert abs(arc.sensors["free_mid_z"] - load.sensors["free_mid_z"]) < 1e-7


def test_the_pinched_cylinder_at_16_by_16_is_within_two_percent():
    w = -_displacement(Scenario.from_toml(PINCHED), (1.0, 1.0))[2]
    assert abs(w - PINCHED_REFERENCE) < 0.02 * PINCHED_REFERENCE, w


def test_supports_in_a_turned_basis_hold_as_the_kernels_rows_do():
    """A roller whose axis is no coordinate axis turns its nodes' vectors into a basis of their
    own (y_k = B q_k), and a mesh with fewer elements along v numbers its nodes along v first:
    the System's linear solution equals the kernel's with the support rows as multipliers, and
    the rows hold."""
    raw = _raw(PLATE)
    raw["mesh"]["elements"] = [3, 2]
    raw["supports"] = [
        {"at": "u0", "kind": "pin"},
        {"at": "v0", "kind": "roller", "axis": [1.0, 1.0, 0.0]},
    ]
    raw["loads"] = {"point": [{"at": [1.0, 1.0], "force": [10.0, -20.0, -30.0]}]}
    sc = _scenario(raw, PLATE)
    system = sc.build_system()
    b = system.flex[0]
    assert b.rotations  # the roller's vectors turned
    # the shorter direction first: nodes nv + 2 apart in an element (u first: 71, nu + 2)
    assert b.ku == 12 * (2 + 3) - 1
    _, ab = b.internal_force_and_tangent(b.y0)
    free = ~b.fixed
    du = np.zeros(b.n)
    du[free] = np.linalg.solve(b.dense(ab)[np.ix_(free, free)], b.f_gravity[free])
    u = b.to_body(b.q_from_y(b.y0 + du) - b.q0)
    body = b.body
    from rancf.kernels.shell import ShellKernel

    k = ShellKernel.from_mesh(
        body.mesh, body.thickness, body.youngs_modulus, body.poisson_ratio, body.density
    )
    c, _ = constraint_rows(body)
    a = sp.bmat([[k.tangent(body.q0), c.T], [c, None]], format="csc")
    ref = spl.spsolve(a, np.concatenate([shell_load(sc, body), np.zeros(c.shape[0])]))
    ref = ref[: body.n_dofs]
    assert np.abs(u - ref).max() < 1e-9 * np.abs(ref).max()
    assert np.abs(c @ u).max() < 1e-12 * np.abs(u).max()
    raw["loads"]["point"][0]["force"] = [0.01, -0.02, -0.03]  # 1e-3 of it: linear to 1e-6
    run = run_static(_scenario(raw, PLATE))  # the sensor at [0.5, 0.5] through the numbering
    moved = body.position((0.5, 0.5), body.q0 + 1e-3 * ref) - body.position((0.5, 0.5))
    got = np.array([run.sensors[f"centre_{c}"] for c in "xyz"]) - body.position((0.5, 0.5))
    assert np.abs(got - moved).max() < 1e-5 * np.abs(moved).max()


def test_the_simply_supported_plate_first_frequency():
    run = run_modes(Scenario.from_toml(PLATE), 1)
    f1 = float(run.result.frequencies_hz[0])
    assert abs(f1 - PLATE_F1) < 0.01 * PLATE_F1, f1
    about = run_modes(Scenario.from_toml(PLATE), 1, "static")  # unloaded: the same plate
    assert about.about == "static"
    assert float(about.result.frequencies_hz[0]) == pytest.approx(f1, rel=1e-9)


def test_a_plate_under_a_sudden_load_keeps_its_energy(tmp_path, monkeypatch):
    """Generalized-alpha without numerical damping (rho_inf = 1) on the shell: kinetic plus
    strain energy plus the loads' potential stays zero."""
    from rancf.cli import main

    raw = _raw(PLATE)
    raw["loads"] = {"distributed": [{"force": [0.0, 0.0, -1000.0]}]}
    raw["solver"] = {"t_end": 0.01, "step": 0.0005, "rho_inf": 1.0}
    monkeypatch.chdir(tmp_path)
    (tmp_path / "plate.toml").write_text(_scenario(raw, PLATE).to_toml())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert main(["simulate", "plate.toml", "--out", "run"]) == 0
    e = np.loadtxt(tmp_path / "run" / "energy.csv", delimiter=",", skiprows=1)
    assert e[:, 2].max() > 0.05  # it moves: strain energy [J]
    assert np.abs(e[:, 4]).max() < 1e-5 * e[:, 2].max()
    assert (tmp_path / "run" / "bodies" / "body" / "body.pvd").exists()


def test_the_static_command_writes_the_roofs_run_folder(tmp_path, monkeypatch, capsys):
    from rancf.cli import main

    monkeypatch.chdir(tmp_path)
    (tmp_path / "roof.toml").write_text(ROOF.read_text())
    assert main(["static", "roof.toml", "--out", "run"]) == 0
    out = capsys.readouterr().out
    assert "free_mid_z" in out
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["status"] == "completed" and summary["element"] == "shell"
    sensors = np.loadtxt(tmp_path / "run" / "sensors.csv", delimiter=",", skiprows=1)
    head = (tmp_path / "run" / "sensors.csv").read_text().splitlines()[0]
    assert head == "t,free_mid_x,free_mid_y,free_mid_z"
    assert sensors[0, 3] == pytest.approx(25.0 * np.sin(np.radians(130.0)), abs=1e-9)
    assert sensors[-1, 0] == 1.0 and sensors[-1, 3] < sensors[0, 3] - 0.2
    pvd = tmp_path / "run" / "bodies" / "body" / "body.pvd"
    assert pvd.exists() and len(list(pvd.parent.glob("body_*.vtu"))) == len(sensors)
    assert main(["view", "run"]) == 2  # the surfaces are for ParaView: said in one line
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'body' is a shell" in err[0] and "body.pvd" in err[0], err


def test_a_shell_in_contact_is_refused_in_one_line():
    raw = _raw(ROOF)
    raw["obstacles"] = [{"name": "floor", "kind": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}]
    with pytest.raises(ScenarioError, match=r"\[obstacles\] not with a shell"):
        _scenario(raw, ROOF).build_system()


def test_a_shell_starts_at_rest():
    raw = _raw(ROOF)
    raw["initial_motion"] = {"velocity": [0.0, 0.0, 1.0]}
    with pytest.raises(ScenarioError, match=r"\[initial_motion\] not for a shell yet"):
        _scenario(raw, ROOF)


def test_a_time_function_on_a_shells_load_is_refused_in_one_line():
    raw = _raw(ROOF)
    raw["loads"]["distributed"][0]["time"] = {"ramp": 1.0}
    with pytest.raises(ScenarioError, match=r"\[loads\.distributed\[0\]\.time\] not for a load"):
        _scenario(raw, ROOF)


def test_a_closed_cylinder_is_refused_in_one_line_not_split_at_its_seam():
    """A 360 deg cylinder's seam ties nodes across the mesh, which the System does not hold:
    refused naming the geometry, where it would otherwise be solved as a slit tube."""
    raw = _raw(ROOF)
    raw["geometry"]["angles_deg"] = [0.0, 360.0]
    raw["supports"] = [{"at": "v0", "kind": "clamp"}]
    with pytest.raises(ScenarioError, match=r"\[geometry\] an open surface.*closed in u"):
        _scenario(raw, ROOF).build_system()
