"""Rods in the solvers: modes of a clamped arc, torsional modes, planar equivalence with the
planar cable (statics and dynamics), and a pendulum whose tangents turn by more than 180°."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Model
from rancf.bodies.properties import Material, PointLoad, Section, Support
from rancf.geometry.conic import conic_arc, conic_arc_through
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.modal import natural_modes
from rancf.solvers.static import solve_static

SEC = Section.circular(0.03)
CABLE = Material(6000.0, 2.0e7)
ROD = Material(6000.0, 2.0e7, poisson_ratio=0.3)
SAG = 0.5 * (1 - np.cos(np.pi / 6))  # circle through (0, 0), (0.5, 0), tangent angles 30°


def clamped_arc(n: int, element: str) -> Model:
    """The clamped circular arc of Example 6.3's shape (chord 0.5 m, angles 30°/30°)."""
    if element == "rod":
        arc = conic_arc_through([0, 0, 0], [0.5, 0, 0], [30, 30], [0.25, SAG, 0])
        return Model(mesh_conic(arc, n), "rod", SEC, ROD, [Support(0, "clamp")])
    return Model(
        mesh_conic(conic_arc(0.5, [30, 30], [0.25, SAG]), n),
        "rancf",
        SEC,
        CABLE,
        [Support(0, "clamp")],
    )


def split_modes(model: Model, res) -> tuple[np.ndarray, np.ndarray]:
    """In-plane and out-of-plane frequencies of a rod arc in the x–y plane (modes decouple)."""
    shapes = res.modes.reshape(len(res.frequencies_hz), model.n_nodes, 7)
    out = np.sum(shapes[:, :, [2, 5, 6]] ** 2, axis=(1, 2)) / np.sum(shapes**2, axis=(1, 2))
    assert np.all((out < 1e-8) | (out > 1 - 1e-8))  # every mode is one or the other
    return res.frequencies_hz[out < 0.5], res.frequencies_hz[out > 0.5]


def test_clamped_arc_modes_rod_against_planar_cable(capsys):
    table = []
    for n in (4, 8, 16, 32):
        rod = clamped_arc(n, "rod")
        res = natural_modes(rod)
        assert res.n_rigid == 0
        assert res.frequencies_hz.min() > 1.0  # no spurious zero (or near-zero) modes
        inplane, outplane = split_modes(rod, res)
        cable = natural_modes(clamped_arc(n, "rancf")).frequencies_hz
        k = min(8, cable.size)
        assert inplane[:k] == pytest.approx(cable[:k], rel=1e-8)
        table.append(outplane[:4])
    table = np.array(table)
    with capsys.disabled():
        print("\nout-of-plane frequencies [Hz] of the clamped arc, rod, 4/8/16/32 elements:")
        for n, row in zip((4, 8, 16, 32), table, strict=True):
            print(f"  {n:3d}  " + "  ".join(f"{f:9.5f}" for f in row))
    steps = np.abs(np.diff(table, axis=0)) / table[1:]
    assert np.all(steps[1:] < steps[:-1])  # refinement converges
    assert steps[-1].max() < 2e-3
    assert np.all(np.diff(table, axis=0) < 0)  # from above, as a conforming discretization


def test_straight_rod_reports_torsional_modes():
    """Clamped-free torsion bar: f = (2k - 1) / (4 L) sqrt(G J / (ρ I_p)) (J = I_p: circle)."""
    length = 0.5
    m = Model(mesh_line([0, 0, 0], [0, length, 0], 16), "rod", SEC, ROD, [Support(0, "clamp")])
    res = natural_modes(m)
    shapes = res.modes.reshape(len(res.frequencies_hz), m.n_nodes, 7)
    twist = np.sum(shapes[:, :, 6] ** 2, axis=1) / np.sum(shapes**2, axis=(1, 2)) > 0.99
    f_t = res.frequencies_hz[twist][:2]
    exact = np.array([1, 3]) / (4 * length) * np.sqrt(ROD.shear / ROD.density)
    assert f_t == pytest.approx(exact, rel=5e-3)


def test_planar_rod_equals_planar_cable_statics_and_dynamics():
    arc2 = conic_arc(0.5, [30, 40], [0.315, 0.077])
    arc3 = conic_arc_through([0, 0, 0], [0.5, 0, 0], [30, 40], [0.315, 0.077, 0])
    cable = Model(
        mesh_conic(arc2, 4),
        "rancf",
        SEC,
        CABLE,
        [Support(0, "clamp")],
        gravity=[0, -9.81],
        point_loads=[PointLoad(-1, (0.3, -0.2))],
    )
    rod = Model(
        mesh_conic(arc3, 4),
        "rod",
        SEC,
        ROD,
        [Support(0, "clamp")],
        gravity=[0, -9.81, 0],
        point_loads=[PointLoad(-1, (0.3, -0.2, 0))],
    )
    xs_c = cable.node_positions(solve_static(cable, load_steps=4).q)
    xs_r = rod.node_positions(solve_static(rod, load_steps=4).q)
    assert np.abs(xs_c - xs_c[0]).max() > 1e-3  # a real deflection
    assert xs_r[:, :2] == pytest.approx(xs_c, abs=1e-10)
    assert np.abs(xs_r[:, 2]).max() == 0.0
    # dynamics: a pinned pendulum swinging in its plane
    opts = DynamicOptions(t_end=0.1, step=1e-3, output_step=1e-2)
    cable = Model(mesh_conic(arc2, 4), "rancf", SEC, CABLE, [Support(0)], gravity=[0, -9.81])
    rod = Model(mesh_conic(arc3, 4), "rod", SEC, ROD, [Support(0)], gravity=[0, -9.81, 0])
    rc, rr = integrate(cable, opts), integrate(rod, opts)
    pc, pr = cable.node_positions(rc.q), rod.node_positions(rr.q)
    assert np.abs(pc[-1] - pc[0]).max() > 1e-2
    assert pr[..., :2] == pytest.approx(pc, abs=1e-9)
    assert rr.n_newton == rc.n_newton


def test_rod_pendulum_turns_its_tangents_through_several_revolutions():
    """A pinned straight rod spun about a tilted axis loops over the top under gravity: the
    nodal triads are re-referenced after every step, so tangents may turn without limit."""
    n, length = 6, 0.5
    mesh = mesh_line([0, 0, 0], [length, 0, 0], n)
    omega = np.array([0.0, 3.0, 10.0])  # rad/s, mostly about z (gravity along -y), tilted
    v0 = {i: np.cross(omega, mesh.nodes[i, 0]) for i in range(1, n + 1)}
    m = Model(
        mesh,
        "rod",
        Section.circular(0.01),
        Material(1000.0, 1e8, poisson_ratio=0.3),
        [Support(0)],
        gravity=[0, -9.81, 0],
        initial_velocities=v0,
    )
    r = integrate(m, DynamicOptions(t_end=1.5, step=1e-3, rho_inf=0.9, output_step=1e-2))
    assert r.status.value == "completed", r.message
    tip = r.q.reshape(len(r.t), m.n_nodes, 7)[:, -1]
    turn = np.unwrap(np.arctan2(tip[:, 4], tip[:, 3]))
    assert np.degrees(np.ptp(turn)) > 540  # one and a half turns
    assert np.abs(tip[:, 2]).max() > 0.1  # truly spatial
    e = r.total_energy
    assert np.abs(e - e[0]).max() < 2e-3 * e[0]
