"""The outputs of a run are the forces its dynamics uses: at every output of every shipped
system example the reported joint reactions, contact forces (and their moments), point loads,
gravity and damping on each rigid body and point mass sum to its mass times its stored
acceleration, and their moments about its centre of mass to its moment of inertia times its
angular acceleration (planar examples), within 1e-6 of the largest force of the run.

Signs: a joint's columns are the force (and moment about its place) it exerts on its first
place; its second place gets the opposite (the places coincide).  An obstacle's columns are the
force it exerts on the flexible bodies and its moment about the obstacle's point; the body that
carries it gets the opposite.  Damping is mass-proportional: ``-c m v`` and ``-c J ω``."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

from rancf.bodies.rigid import PointMass, RigidBody
from rancf.cli import main
from rancf.post.results import load_results
from rancf.scenario import Scenario
from rancf.studies.common import example_path

#: Every shipped example with rigid bodies or point masses.
SYSTEMS = ["belt-drive", "capstan", "slider-crank", "spin-up-beam", "tether-payload"]


def _cross(a: np.ndarray, f: np.ndarray) -> float:
    return float(a[0] * f[1] - a[1] * f[0])


def _run(tmp_path, name: str, outputs: int = 12) -> tuple:
    """The example cut to ``outputs`` output steps, run by ``rancf simulate``: (system,
    results)."""
    raw = tomllib.loads(example_path(name).read_text())
    sv = raw.setdefault("solver", {})
    out_dt = sv.get("output_step", sv.get("step"))
    sv["t_end"] = min(sv.get("t_end", 1.0), outputs * out_dt)
    sc = Scenario.from_dict(raw)
    sc.save(tmp_path / f"{name}.toml")
    run = tmp_path / "run"
    assert main(["simulate", str(tmp_path / f"{name}.toml"), "--out", str(run), "--quiet"]) == 0
    return sc.build_system(), load_results(run / "results.npz")


def _balances(s, z) -> tuple[list[tuple[str, np.ndarray, np.ndarray]], float]:
    """Per rigid body or point mass: (name, force residual (n_t, 2), moment residual (n_t,));
    and the largest force of the run."""
    t, q, v, a = z["t"], z["q"], z["v"], z["a"]
    cols = z["metadata"]["reaction_columns"]
    r = z["reactions"]

    def col(key: str) -> np.ndarray:
        return r[:, cols.index(key)] if key in cols else np.zeros(t.size)

    bodies = {n: b for n, b in s.bodies.items() if isinstance(b, RigidBody | PointMass)}
    force = {n: np.zeros((t.size, 2)) for n in bodies}
    moment = {n: np.zeros(t.size) for n in bodies}
    largest = 0.0

    def centre(name: str, i: int) -> np.ndarray:
        o = s.offsets[name]
        return q[i, o : o + 2]

    def add(name: str, i: int, f: np.ndarray, m: float, at: np.ndarray) -> None:
        nonlocal largest
        force[name][i] += f
        moment[name][i] += m + _cross(at - centre(name, i), f)
        largest = max(largest, float(np.abs(f).max()))

    for k, j in enumerate(s.joints):
        label = j.name or f"joint{k}"
        f = np.column_stack([col(f"{label}_fx"), col(f"{label}_fy")])
        m = col(f"{label}_mz")
        for side, sign in ((0, 1.0), (1, -1.0)):
            p = s.resolve(j.between[side])
            if p.body not in bodies:
                continue
            for i in range(t.size):
                at = s.place_state(p, s.y_from_q(q[i]), float(t[i]))[0][:2]
                add(p.body, i, sign * f[i], sign * m[i], at)
    for ob in s.obstacles:
        if ob.body is None:
            continue
        name = ob.name
        f = np.column_stack(
            [
                col(f"{name}_normal_x") + col(f"{name}_friction_x"),
                col(f"{name}_normal_y") + col(f"{name}_friction_y"),
            ]
        )
        m = col(f"{name}_mz")
        local = np.asarray(ob.center if ob.kind != "plane" else ob.point, float)
        o = s.offsets[ob.body]
        for i in range(t.size):
            c, sn = np.cos(q[i, o + 2]), np.sin(q[i, o + 2])
            at = centre(ob.body, i) + np.array([[c, -sn], [sn, c]]) @ local
            add(ob.body, i, -f[i], -m[i], at)
    for ld in s.loads:
        p = s.resolve(ld.at)
        if p.body not in bodies:
            continue
        for i in range(t.size):
            factor = 1.0 if ld.time is None else float(ld.time.value(float(t[i])))
            f = factor * np.asarray(ld.force if ld.force is not None else (0.0, 0.0), float)
            m = factor * float(np.atleast_1d(ld.torque)[-1]) if ld.torque is not None else 0.0
            at = s.place_state(p, s.y_from_q(q[i]), float(t[i]))[0][:2]
            add(p.body, i, f, m, at)
    out = []
    for name, b in bodies.items():
        o = s.offsets[name]
        mass = b.mass
        for i in range(t.size):
            add(name, i, mass * s.gravity[:2], 0.0, centre(name, i))
            add(name, i, -s.damping * mass * v[i, o : o + 2], 0.0, centre(name, i))
        fr = force[name] - mass * a[:, o : o + 2]
        mr = moment[name].copy()
        if isinstance(b, RigidBody):
            inertia = float(b.inertia_vector()[0])
            mr -= inertia * (a[:, o + 2] + s.damping * v[:, o + 2])
        out.append((name, fr, mr))
    return out, largest


@pytest.mark.parametrize("name", SYSTEMS)
def test_forces_balance_momentum_change(tmp_path, name):
    """Measured (largest force residual / largest force; moments over the largest force times
    the system's size): belt-drive 5.6e-16 and 4e-18, capstan 0, slider-crank 1.2e-16 and
    4.9e-17, spin-up-beam 0 and 6.7e-17, tether-payload 0 (round-off)."""
    s, z = _run(tmp_path, name)
    assert s.dim == 2  # the shipped systems are planar: moments are numbers
    balances, largest = _balances(s, z)
    assert largest > 0.0 and balances
    for body, fr, mr in balances:
        assert np.abs(fr).max() <= 1e-6 * largest, (body, np.abs(fr).max(), largest)
        assert np.abs(mr).max() <= 1e-6 * largest * s.size, (body, np.abs(mr).max(), largest)


def test_the_balance_sees_a_missing_force(tmp_path):
    """The check can fail: leaving out the belt drive's contact (its forces on the pulleys)
    breaks the pulleys' balance by far more than the tolerance."""
    s, z = _run(tmp_path, "belt-drive", 6)
    cols = z["metadata"]["reaction_columns"]
    keep = [not c.startswith("pulley_") for c in cols]
    z["reactions"] = z["reactions"] * np.array(keep, dtype=float)
    balances, largest = _balances(s, z)
    worst = max(float(np.abs(fr).max()) for _, fr, _ in balances)
    assert worst > 1e-3 * largest
