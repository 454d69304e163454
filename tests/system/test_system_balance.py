"""Balance laws and joints of rods through scenarios built in Python: a free rod
under a force and moment pulse (momentum = impulse, a straight centre-of-mass path), and an
L-shaped frame of two rods joined by a fixed joint (linear frame solution; objectivity of the
joint and the rods under a rigid rotation of the whole system)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from rancf.cli import main
from rancf.post.results import load_results
from rancf.scenario import Scenario
from rancf.scenario.system_build import build_system
from rancf.solvers.static import solve_static

ROD = {
    "mesh": {"elements": 8, "element": "rod"},
    "section": {"radius": 0.01},
    "material": {"density": 7850.0, "youngs_modulus": 2.0e11, "poisson_ratio": 0.3},
}


def test_free_rod_pulse_momentum_and_center_of_mass(tmp_path):
    """A free rod (no supports), a force of 1 N across it and a moment of 0.1 N m, both times a
    triangular pulse table of 0.02 s (impulse 0.01 N s): after the pulse the momentum sensor
    is constant to 1e-9 relative and equals the impulse to the time-discretization error, its
    components across the force stay zero to round-off (that of the internal forces, ε EA, over
    the 0.1 s run: 1.4e-9 N s), and the centre of mass moves on a straight line at impulse /
    mass.  Measured: variation 1e-12 relative, transverse 2.6e-11 N s (Newton tolerances 1e-10
    and 1e-14 give the same: it is round-off)."""
    sc = Scenario(
        geometry={"kind": "line", "start": [0.0, 0.0, 0.0], "end": [1.0, 0.0, 0.0]},
        **ROD,
        loads={
            "point": [
                {
                    "at": "end",
                    "force": [0.0, 1.0, 0.0],
                    "moment": [0.0, 0.0, 0.1],
                    "time": {"table": [[0.0, 0.0], [0.01, 1.0], [0.02, 0.0]]},
                }
            ]
        },
        solver={"t_end": 0.1, "step": 1e-4, "output_step": 1e-3, "rho_inf": 1.0},
        sensors=[{"name": "p", "kind": "momentum"}, {"name": "c", "kind": "center_of_mass"}],
    )
    path = tmp_path / "free.toml"
    sc.save(path)
    assert main(["simulate", str(path), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    data = load_results(tmp_path / "run" / "results.npz")  # full precision (CSV: 12 digits)
    names = data["metadata"]["sensor_columns"]
    d = {"t": data["t"], **{n: data["sensors"][:, k] for k, n in enumerate(names)}}
    after = d["t"] >= 0.02 - 1e-12
    py = d["p_y"][after]
    assert np.ptp(py) <= 1e-9 * abs(py[-1])
    assert py[-1] == pytest.approx(0.01, rel=1e-6)
    # across the force: zero up to the round-off of the internal forces, ε EA (their
    # translation invariance holds to it), over the run's duration
    ea = 2.0e11 * np.pi * 0.01**2
    assert np.abs(np.column_stack([d["p_x"], d["p_z"]])).max() <= 0.1 * np.finfo(float).eps * ea
    mass = 7850.0 * np.pi * 0.01**2
    c = np.column_stack([d["c_x"], d["c_y"], d["c_z"]])[after]
    t = d["t"][after]
    speed = (c[-1] - c[0]) / (t[-1] - t[0])
    assert speed[1] == pytest.approx(0.01 / mass, rel=1e-6)
    assert np.abs(speed[[0, 2]]).max() <= 1e-10
    line = c[0] + np.outer(t - t[0], speed)  # straight, at constant speed
    assert np.abs(c - line).max() <= 1e-9 * np.abs(c[-1] - c[0]).max()


def _frame(load: float, rot: np.ndarray) -> Scenario:
    def leg(name: str, a: list[float], b: list[float]) -> dict:
        return {
            "name": name,
            "geometry": {"kind": "line", "start": list(rot @ a), "end": list(rot @ b)},
            **ROD,
        }

    return Scenario(
        bodies=[leg("a", [0, 0, 0], [1, 0, 0]), leg("b", [1, 0, 0], [1, 1, 0])],
        joints=[{"name": "corner", "kind": "fixed", "between": ["a:end", "b:start"]}],
        supports=[{"at": "a:start", "kind": "clamp"}],
        loads={"point": [{"at": "b:end", "force": list(rot @ [0.0, 0.0, load])}]},
    )


def _solved(sc: Scenario) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The tip, the corner joint's force on leg a and the clamp's force."""
    from rancf.post.results import system_outputs

    s = build_system(sc)
    res = solve_static(s, sc.solver["load_steps"])
    b = s.bodies["b"]
    tip = b.node_positions(res.q[s.body_slice("b")])[-1]
    out = system_outputs(s)
    row = out.rows(np.ones(1), res.q[None], lam=res.lam[None], static=True)["r"][0]
    corner = row[out.joint_columns("corner")][:3]
    return tip, corner, row[:3]


def _tip(sc: Scenario) -> np.ndarray:
    return _solved(sc)[0]


def test_l_frame_linear_solution_and_objectivity():
    """Small tip force P out of the frame's plane: δ = 2PL³/(3EI) + PL³/(GJ) (both legs bent,
    the first twisted) within 0.5 %; at a large load the tip's displacement in the frame's
    axes does not change when the whole system is rotated rigidly.  Measured: 1e-4 relative
    (linear), 1e-12 m (rotated)."""
    r, e, nu = 0.01, 2.0e11, 0.3
    ei = e * np.pi * r**4 / 4
    gj = e / (2 * (1 + nu)) * np.pi * r**4 / 2
    p = 1e-3
    tip = _tip(_frame(p, np.eye(3)))
    assert tip[2] == pytest.approx(2 * p / (3 * ei) + p / gj, rel=5e-3)
    big = 50.0
    rot = Rotation.from_rotvec([0.3, -0.5, 0.8]).as_matrix()
    plain, corner, clamp = _solved(_frame(big, np.eye(3)))
    turned, corner_r, clamp_r = _solved(_frame(big, rot))
    assert abs(plain[2]) > 0.05  # a large deflection
    assert np.abs(rot.T @ turned - plain).max() <= 1e-9
    # the reactions turn with it: the clamp's force balances the load, the corner carries it
    assert np.allclose(clamp, [0.0, 0.0, -big], atol=1e-9 * big)  # the force on the body
    assert np.allclose(rot.T @ clamp_r, clamp, atol=1e-9 * big)
    assert np.allclose(rot.T @ corner_r, corner, atol=1e-9 * big)
    assert np.linalg.norm(corner) == pytest.approx(big, rel=1e-9)


def test_a_python_callable_moves_a_support():
    """The Python API takes any callable as a TIME_FUNCTION: sampled on [0, t_end] as a cubic
    table for the compiled loop, the pinned end follows 0.01 sin(3t) to 1e-9 m (the table's
    interpolation error, 2001 points)."""
    import rancf

    sc = Scenario(
        geometry={"kind": "line", "start": [0.0, 0.0], "end": [1.0, 0.0]},
        mesh={"elements": 4},
        section={"radius": 0.002},
        material={"density": 7800.0, "youngs_modulus": 2.0e11},
        supports=[
            {"at": "start", "kind": "clamp"},
            {"at": "end", "kind": "pin", "motion": lambda t: [0.01 * np.sin(3 * t), 0.0]},
        ],
        solver={"t_end": 0.5, "step": 1e-3, "output_step": 0.01},
        sensors=[{"name": "tip", "kind": "position", "at": "end"}],
    )
    res, names, vals = rancf.simulate(sc)
    assert names == ["tip_x", "tip_y"]
    assert np.abs(vals[:, 0] - (1.0 + 0.01 * np.sin(3 * res.t))).max() <= 1e-9
