"""Fluid loads on lines (docs/derivations/fluid.md): every force's tangent against central
differences of the assembled residual (positions, velocities, accelerations; cables and rods,
2D and 3D; current profile, waves and an irregular sea), a rigid motion in still water without
drag gives no fluid force, and the added mass sits in the Jacobian's mass part."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.time_function import TimeFunction
from rancf.kernels.call_records import ResidualOptions, ResidualPoint, StatePoint, TangentOptions
from rancf.mesh.factories import mesh_line
from rancf.system import System
from rancf.system.fluid import DistributedLoad, Fluid, Hydro, JonswapWaves, Waves

SEC, MAT = Section.circular(0.02), Material(3000.0, 1e7)
ROD = Material(3000.0, 1e7, poisson_ratio=0.3)
HYDRO = Hydro(
    diameter=0.05, drag_normal=1.2, drag_axial=0.4, added_mass_normal=1.0, added_mass_axial=0.3
)


def _system(
    case: str, fluid: Fluid | None, hydro: Hydro | None = HYDRO, loads=(), weight=True
) -> System:
    if case == "2d":
        g = [0.0, -9.81 * weight]
        m = Model(
            mesh_line([0, -1], [2, -1.5], 3), "rancf", SEC, MAT, [Support(0, "pin")], gravity=g
        )
    else:
        g = [0.0, 0.0, -9.81 * weight]
        kind, mat = ("rod", ROD) if case.startswith("rod") else ("rancf", MAT)
        sup = Support(0, "clamp" if case.endswith("clamp") else "pin")
        m = Model(mesh_line([0, 0, -1], [2, 0.5, -1.6], 3), kind, SEC, mat, [sup], gravity=g)
    return System(
        {"line": m},
        gravity=g,
        fluid=fluid,
        hydro={"line": hydro} if hydro else {},
        distributed=loads,
        horizon=10.0,
    )


def _fluids(dim: int) -> dict[str, Fluid]:
    cur = (0.4, 0.3, -0.1)[:dim]
    prof = (
        (-3.0, *(0.1, 0.2, 0.0)[:dim]),
        (-1.2, *(0.5, -0.1, 0.05)[:dim]),
        (0.0, *(0.8, 0.0, 0.0)[:dim]),
    )
    return {
        "current": Fluid(1025.0, surface=-1.3, current=cur),
        "profile": Fluid(1025.0, current_profile=prof),
        "waves": Fluid(1025.0, surface=0.0, current=cur, waves=Waves(1.5, 4.0, 30.0, depth=6.0)),
        "sea": Fluid(
            1025.0,
            surface=0.0,
            current=cur,
            waves=JonswapWaves(1.5, 4.0, depth=6.0, components=6, seed=2, direction_deg=30.0),
        ),
    }


def _residual(s: System, y, v, a, t, dynamic=True) -> np.ndarray:
    r = np.empty(s.n + s.m)
    assert s.core.residual(
        ResidualPoint(y, np.zeros(s.m), r, v, a), ResidualOptions(t, dynamic=dynamic)
    )
    return r[: s.n]


def _state(s: System, rng) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    y = s.y0 + 0.05 * rng.standard_normal(s.n)
    v = 0.5 * rng.standard_normal(s.n)
    a = 2.0 * rng.standard_normal(s.n)
    for x in (y, v, a):
        x[s.fixed] = (s.y0 if x is y else 0.0 * s.y0)[s.fixed]
    return y, v, a


def _fluid_jacobian(s: System, bare: System, y, v, a, t, coef) -> np.ndarray:
    """The fluid's part of the Jacobian (the system's less that of the same bodies without)."""
    out = []
    for x in (s, bare):
        dense = np.empty((x.n + x.m) ** 2)
        assert x.core.dense_jacobian(
            StatePoint(y, v, a, np.zeros(x.m)), TangentOptions(t, *coef), dense
        )
        out.append(dense.reshape(x.n + x.m, -1)[: x.n, : x.n])
    return out[0] - out[1]


@pytest.mark.parametrize("case", ["2d", "cable", "rod", "rod-clamp"])
@pytest.mark.parametrize("which", ["current", "profile", "waves", "sea"])
def test_fluid_tangent_against_differences(case, which, rng):
    """ck d/dy, cv d/dv and ca d/da of the fluid's and distributed loads' part of the residual
    against central differences (error below 1e-6 of the largest entry)."""
    dim = 2 if case == "2d" else 3
    tf = TimeFunction.harmonic(0.5, 1.0)
    s = _system(case, _fluids(dim)[which], loads=[DistributedLoad((3.0, -2.0, 1.0)[:dim], time=tf)])
    bare = _system(case, None, None)
    y, v, a = _state(s, rng)
    t = 0.7
    free = np.flatnonzero(~s.fixed)

    def res(*state):
        return _residual(s, *state, t) - _residual(bare, *state, t)

    for k, coef in enumerate([(1, 0, 0), (0, 1, 0), (0, 0, 1)]):
        jac = _fluid_jacobian(s, bare, y, v, a, t, coef)
        fd = np.zeros((s.n, s.n))
        for j in free:
            h = 1e-6 * (1 + abs([y, v, a][k][j]))
            plus, minus = [y.copy(), v.copy(), a.copy()], [y.copy(), v.copy(), a.copy()]
            plus[k][j] += h
            minus[k][j] -= h
            fd[:, j] = (res(*plus) - res(*minus)) / (2 * h)
        sub = np.ix_(free, free)
        scale = np.abs(fd[sub]).max()
        assert scale > 0.1  # the fluid's part is there
        assert np.abs(jac[sub] - fd[sub]).max() <= 1e-6 * scale, (which, k)


def test_fluid_statics_tangent(rng):
    """Statics (no velocity, no inertia, no waves): the tangent of buoyancy and current drag
    times the load factor."""
    s = _system("cable", _fluids(3)["profile"])
    y = s.y0 + 0.05 * rng.standard_normal(s.n)
    y[s.fixed] = s.y0[s.fixed]
    z = np.zeros(s.n)
    free = np.flatnonzero(~s.fixed)
    ok, size, rows, cols, vals = s.core.sparse_jacobian(
        StatePoint(y, z, z, np.zeros(s.m)),
        TangentOptions(0.0, 1.0, 0.0, 0.0, dynamic=False, load_factor=0.6),
    )
    assert ok
    jac = np.zeros((size, size))
    np.add.at(jac, (rows, cols), vals)
    fd = np.zeros((s.n, s.n))

    def res(x):
        r = np.empty(s.n + s.m)
        s.core.residual(
            ResidualPoint(x, np.zeros(s.m), r), ResidualOptions(0.0, 0.6, dynamic=False)
        )
        return r[: s.n]

    for j in free:
        h = 1e-6 * (1 + abs(y[j]))
        e = np.eye(s.n)[j] * h
        fd[:, j] = (res(y + e) - res(y - e)) / (2 * h)
    sub = np.ix_(free, free)
    assert np.abs(jac[: s.n, : s.n][sub] - fd[sub]).max() <= 1e-6 * np.abs(fd[sub]).max()


@pytest.mark.parametrize("case", ["2d", "cable", "rod"])
def test_rigid_motion_gives_no_fluid_force(case, rng):
    """Still water, no drag, no gravity: a line moved rigidly (rotated and shifted) at a uniform
    velocity feels no fluid force; with drag, a current moving with the line gives none either;
    a uniform acceleration gives the added-mass force of the whole line."""
    dim = 2 if case == "2d" else 3
    s0 = _system(case, Fluid(1025.0), Hydro(0.05, 0.0, 0.0, 1.0, 0.5), weight=False)
    ang = 0.7
    rot = np.eye(3)
    rot[:2, :2] = [[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]]
    rot = rot[:dim, :dim]
    m = s0.flex[0]
    q0 = m.q_from_y(s0.y0).reshape(m.n_nodes, m.dpn)
    q = q0.copy()
    q[:, :dim] = q0[:, :dim] @ rot.T + 0.3
    q[:, dim : 2 * dim] = q0[:, dim : 2 * dim] @ rot.T
    y = m.y_from_q(q.ravel())
    vel = np.array([0.4, -0.2, 0.3])[:dim]
    qv = np.zeros_like(q)
    qv[:, :dim] = vel
    v = m.y_from_q(qv.ravel())
    z = np.zeros(s0.n)
    f = np.asarray(s0.core.fluid_forces(y, v, z, 0.3))
    assert np.abs(f).max() == 0.0
    # drag, with a current equal to the line's velocity
    s1 = _system(
        case, Fluid(1025.0, current=tuple(vel)), Hydro(0.05, 1.2, 0.5, 1.0, 0.5), weight=False
    )
    f = np.asarray(s1.core.fluid_forces(y, v, z, 0.3))
    assert np.abs(f).max() <= 1e-12
    # a uniform acceleration along the line: the axial added mass rho A Cat L acc
    t_dir = rot @ np.r_[(np.array([2, 0.5, -0.6]) if dim == 3 else np.array([2, -0.5]))]
    length = np.linalg.norm(t_dir)
    acc = 2.0 * t_dir / length
    qa = np.zeros_like(q)
    qa[:, :dim] = acc
    f = np.asarray(s0.core.fluid_forces(y, v, m.y_from_q(qa.ravel()), 0.3))[:dim]
    want = -1025.0 * np.pi * 0.05**2 / 4 * 0.5 * length * acc
    assert np.allclose(f, want, rtol=1e-12, atol=1e-12)


def test_wave_kinematics_against_airy_theory():
    """A short line across the waves at depth: its fluid force is the Morison force of linear
    (Airy) wave kinematics written out here (wave number from the dispersion relation by
    bisection), plus buoyancy; 1e-9 relative."""
    from scipy.optimize import brentq

    rho, g, h, height, period, beta = 1025.0, 9.81, 30.0, 3.0, 7.0, 25.0
    d, cd, length = 0.05, 1.1, 1e-3
    z0, x0, t = -4.0, 3.0, 1.3
    b = np.radians(beta)
    e_b = np.array([np.cos(b), np.sin(b), 0.0])
    along = np.array([-np.sin(b), np.cos(b), 0.0])  # horizontal, across the waves
    mid = np.array([x0, 0.0, z0])
    m = Model(
        mesh_line(mid - along * length / 2, mid + along * length / 2, 1),
        "rancf",
        SEC,
        MAT,
        [],
        gravity=[0.0, 0.0, -g],
    )
    fl = Fluid(rho, surface=0.0, waves=Waves(height, period, beta, depth=h))
    s = System(
        {"line": m}, gravity=[0.0, 0.0, -g], fluid=fl, hydro={"line": Hydro(d, cd, 0.0, 0.0, 0.0)}
    )
    z = np.zeros(s.n)
    f = np.asarray(s.core.fluid_forces(s.y0, z, z, t))
    om = 2 * np.pi / period
    k = brentq(lambda k: g * k * np.tanh(k * h) - om**2, 1e-6, 10.0, xtol=1e-15)
    th = k * (mid @ e_b) - om * t
    amp = height / 2 * om / np.sinh(k * h)
    u = amp * np.cosh(k * (z0 + h)) * np.cos(th) * e_b
    u[2] = amp * np.sinh(k * (z0 + h)) * np.sin(th)
    du = amp * om * np.cosh(k * (z0 + h)) * np.sin(th) * e_b
    du[2] = -amp * om * np.sinh(k * (z0 + h)) * np.cos(th)
    area = np.pi * d**2 / 4
    want = length * (
        0.5 * rho * d * cd * np.linalg.norm(u) * u
        + rho * area * du
        + rho * area * g * np.array([0.0, 0.0, 1.0])
    )
    assert np.allclose(f, want, rtol=1e-9, atol=1e-12 * np.abs(want).max())
