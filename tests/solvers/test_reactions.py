"""Reactions and section quantities: balance laws, the pendulum's pin force over
time, moment and tension lines along the body."""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support
from rancf.bodies.reactions import support_reactions
from rancf.bodies.section_outputs import SectionSampler
from rancf.mesh.factories import mesh_line
from rancf.post.results import system_outputs
from rancf.scenario import load_scenario
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.form import find_form
from rancf.solvers.static import solve_static
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system import as_system
from rancf.system.outputs import SystemOutputs


def _one_body_static(f) -> bool:
    """A one-body line example without time functions (its static equilibrium is the one-body
    solver's; a shell's supports report no reactions yet)."""
    if not f.name.endswith(".toml"):
        return False
    text = f.read_text()
    shell = "thickness =" in text
    return not shell and "[[bodies]]" not in text and "motion" not in text and "[fluid]" not in text


EXAMPLES = sorted(
    f.name for f in resources.files("rancf.examples").iterdir() if _one_body_static(f)
)


def _moment_about(points: np.ndarray, forces: np.ndarray) -> np.ndarray:
    if points.shape[1] == 2:
        return points[:, 0] * forces[:, 1] - points[:, 1] * forces[:, 0]
    return np.cross(points, forces)


@pytest.mark.parametrize("name", EXAMPLES)
def test_shipped_examples_reactions_balance_the_loads(name):
    """Every shipped example with a static equilibrium: the reactions balance the applied loads
    and the weight, forces and moments, to 1e-9 relative to the loads and reactions, above the
    round-off floor of the internal forces (EA times machine epsilon: a 1 mN load on a cable
    with EA = 5.7e4 N cannot balance to better than about 1e-11 N).  The pendulums are
    mechanisms (a pin and gravity): relaxation brings them to their hanging state.  The
    reactions are those ``rancf static`` reports (:meth:`SystemOutputs.static_reactions`)."""
    with resources.as_file(resources.files("rancf.examples") / name) as path:
        sc = load_scenario(path)
    find_form(sc)  # a [form]'s length first
    m = sc.build_model()
    res = solve_static(m, sc.solver["load_steps"])
    if "pendulum" in name or "exact-geometry" in name:
        assert res.method == "relaxation+newton"
    reac = SystemOutputs(as_system(m)).static_reactions(res.y, res.lam)
    q = res.q.reshape(m.n_nodes, m.dpn)
    fq = m.q_from_y(m.external_force(0.0, res.y, True)).reshape(m.n_nodes, m.dpn)
    loads = fq[:, : m.dim]  # nodal forces, weight included (the gradient rows carry moments)
    total = loads.sum(axis=0) + sum(r.force for r in reac)
    floor = 100 * np.finfo(float).eps * m.props.ea
    scale = np.abs(loads).sum() + sum(np.abs(r.force).sum() for r in reac)
    assert np.abs(total).max() <= 1e-9 * scale + floor
    # moments about the origin: nodal forces, the gradient rows' couples r_x x Q, reactions
    pos = q[:, : m.dim]
    grad, qg = q[:, m.dim : 2 * m.dim], fq[:, m.dim : 2 * m.dim]
    moment = _moment_about(pos, loads).sum(axis=0) + _moment_about(grad, qg).sum(axis=0)
    for r, sup in zip(reac, m.supports, strict=True):
        at = pos[sup.node % m.n_nodes]
        moment = moment + _moment_about(at[None], r.force[None])[0]
        if r.moment is not None:
            moment = moment + (r.moment[0] if m.dim == 2 else r.moment)
    assert np.abs(moment).max() <= (1e-9 * scale + floor) * np.ptp(pos, axis=0).max()


def test_pendulum_pin_force_is_the_rate_of_momentum():
    """The planar pendulum example released from its reference: at every stored time the pin
    reaction plus the weight equals dP/dt of the body, P = Σ M v over the x and y rows.  The
    difference is the time-discretization error: relative 2.4e-3 at h = 2 ms, 2.2e-4 at
    0.5 ms (measured; second order, irregular as the soft cable's axial vibrations are resolved
    differently by each step)."""
    with resources.as_file(resources.files("rancf.examples") / "planar-pendulum.toml") as p:
        sc = load_scenario(p)
    errors = []
    for h in (2e-3, 5e-4):
        m = sc.build_model()
        res = integrate(m, DynamicOptions(t_end=0.4, step=h, rho_inf=0.9, output_step=h))
        reac = system_outputs(m).rows(res.t, res.q, res.v)["r"]
        ones = np.zeros((m.dim, m.n))
        for i in range(m.dim):
            ones[i].reshape(m.n_nodes, m.dpn)[:, i] = 1.0
        mom = np.array([[o @ m.mass_times(m.y_from_q(v)) for o in ones] for v in res.v])
        rate = np.gradient(mom, res.t, axis=0, edge_order=2)
        weight = m.total_mass * np.asarray(m.gravity)
        err = np.abs(reac[:, : m.dim] + weight - rate)[2:-2].max()
        errors.append(err / np.abs(reac[:, : m.dim]).max())
    assert errors[1] < 5e-4
    assert errors[0] / errors[1] > 4.0  # faster than first order


def cantilever(n: int = 8, force: float = -1e-3) -> Model:
    return Model(
        mesh_line([0.0, 0.0], [0.5, 0.0], n),
        "rancf",
        Section.circular(0.03),
        Material(6000.0, 2e7),
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, (0.0, force))],
    )


def test_cantilever_moment_line_and_clamp_moment():
    """A small tip load P: M(s) = P (L - s) along the cantilever, the clamp's reaction moment
    and the section moment at the clamp are the same, the tension is (nearly) zero."""
    m = cantilever(8)
    res = solve_static(m)
    sampler = SectionSampler(m)
    vals = sampler.values(res.y)
    moment, tension = vals[:, 3], vals[:, 1]
    expect = -1e-3 * (0.5 - sampler.s)  # the load bends it down: clockwise moment
    assert np.allclose(moment, expect, rtol=0, atol=2e-3 * 5e-4)
    assert np.abs(tension).max() < 1e-3 * 1e-3
    r = support_reactions(m, res.y, SystemEquilibrium(as_system(m)).full_residual(res.y, 1.0))[0]
    assert r.moment[0] == pytest.approx(-moment[0], rel=1e-3)


def test_ssnl114_tension_along_the_cable():
    """The catenary's axial force at the supports is the end tension (the reactions' size) and
    its horizontal part is the same everywhere."""
    from tests.solvers.test_equilibrium import ssnl114_model

    m = ssnl114_model(40)
    res = solve_static(m)
    sampler = SectionSampler(m)
    vals = sampler.values(res.y)
    r = support_reactions(m, res.y, SystemEquilibrium(as_system(m)).full_residual(res.y, 1.0))
    assert vals[0, 1] == pytest.approx(np.hypot(*r[0].force), rel=2e-4)
    assert vals[-1, 1] == pytest.approx(np.hypot(*r[1].force), rel=2e-4)
    tang = np.gradient(sampler.positions(res.y), sampler.s, axis=0)
    horiz = vals[:, 1] * tang[:, 0] / np.linalg.norm(tang, axis=1)
    assert np.ptp(horiz[1:-1]) <= 2e-4 * horiz.mean()


def test_rod_moments_against_the_reactions():
    """A rod cantilever under a tip moment about its axis and a transverse force: the twisting
    moment is the applied torque along the whole rod, and the clamp's reaction moment balances
    the tip's loads."""
    sec = Section.circular(0.01)
    mat = Material(7850.0, 2e11, poisson_ratio=0.3)
    m = Model(
        mesh_line([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 8),
        "rod",
        sec,
        mat,
        [Support(0, "clamp")],
        point_loads=[PointLoad(-1, (0.0, 0.0, -1.0), moment=(2.0, 0.0, 0.0))],
    )
    res = solve_static(m)
    vals = SectionSampler(m).values(res.y)
    assert np.allclose(vals[:, 5], 2.0, rtol=2e-3)  # twisting moment = the torque
    r = support_reactions(m, res.y, SystemEquilibrium(as_system(m)).full_residual(res.y, 1.0))[0]
    tip = m.node_positions(res.q)[-1]
    expect = -(np.array([2.0, 0.0, 0.0]) + np.cross(tip, [0.0, 0.0, -1.0]))
    assert np.allclose(r.moment, expect, rtol=0, atol=1e-8)
    assert np.allclose(r.force, [0.0, 0.0, 1.0], rtol=0, atol=1e-7)
