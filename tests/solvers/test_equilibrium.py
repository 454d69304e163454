"""Equilibrium analysis: slender cables from a tension-free start, installation,
reactions, dynamics from an equilibrium, modes about loaded states.

The references are independent solutions in ``tests/references`` (elastic catenary with rancf's
Green–Lagrange law, shooting solution of the clamped elastica, Bernoulli's hanging chain)."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.reactions import support_reactions
from rancf.geometry.conic import conic_arc_through
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.modal import natural_modes
from rancf.solvers.sag_start import SAG_START
from rancf.solvers.static import solve_equilibrium, solve_static
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system import as_system
from tests.references.catenary import SSNL114, chain_frequencies, elastic_catenary, ssnl114
from tests.references.elastica import HOSE, installed_hose


def _reactions(m: Model, y: np.ndarray):
    return support_reactions(m, y, SystemEquilibrium(as_system(m)).full_residual(y, 1.0))


def ssnl114_model(n: int = 40) -> Model:
    c = SSNL114
    area = c["area"]
    sec = Section(area, area**2 / (4.0 * np.pi))  # a solid round wire
    return Model(
        mesh_line([0.0, 0.0], [c["span"], 0.0], n),
        "rancf",
        sec,
        Material(c["density"], c["youngs"]),
        [Support(0), Support(-1)],
        gravity=[0.0, -9.81],
    )


def test_ssnl114_elastic_catenary_from_the_straight_tension_free_start():
    """Code_Aster SSNL114: the straight stress-free 325 m cable sags 6.349 m by stretching
    alone.  Newton's first step from the straight line (bending stiffness only) overshoots by
    six orders of magnitude; the line search cuts it back.  Measured: 6 load steps, 34 Newton
    iterations; sag and H agree with the Green–Lagrange catenary to 1e-7."""
    m = ssnl114_model(40)
    res = solve_static(m)
    ref = ssnl114()
    sag = -m.node_positions(res.q)[20, 1]
    assert sag == pytest.approx(6.349, rel=1e-3)
    assert sag == pytest.approx(ref.mid_sag, rel=1e-5)
    r = _reactions(m, res.y)
    assert -r[0].force[0] == pytest.approx(13213.0, rel=2e-3)
    assert -r[0].force[0] == pytest.approx(ref.horizontal, rel=1e-5)
    assert np.hypot(*r[0].force) == pytest.approx(ref.end_tension, rel=1e-5)
    assert res.n_newton < 500


def test_slack_steel_cable_from_a_curved_reference():
    """80 m span, circular stress-free reference 82 m long, A = 1e-4 m², E = 2e11 Pa: the sag of
    the elastic catenary of the same length (negligible bending stiffness) in a few dozen
    iterations (measured 25; a load path without a sagged start took 164,342)."""
    th = 21.999218277040956  # the tangent angle of a circular arc 82 m long over 80 m
    arc = conic_arc_through([0.0, 0.0], [80.0, 0.0], [th, th], [40.0, -7.774929182949902])
    m = Model(
        mesh_conic(arc, 32),
        "rancf",
        Section(1e-4, 1e-13),
        Material(7850.0, 2e11),
        [Support(0), Support(-1)],
        gravity=[0.0, -9.81],
    )
    res = solve_static(m)
    ref = elastic_catenary(80.0, 82.0, 2e11 * 1e-4, 7850.0 * 1e-4 * 9.81)
    assert -m.node_positions(res.q)[16, 1] == pytest.approx(ref.mid_sag, rel=1e-6)
    assert res.n_newton < 500


def test_arc_length_follows_the_same_path():
    res = solve_static(ssnl114_model(20), method="arc_length")
    assert res.load_factors[-1] == 1.0
    load = solve_static(ssnl114_model(20))
    assert np.allclose(res.q, load.q, rtol=0, atol=1e-8 * 325)


def shallow_arch(n: int = 16) -> Model:
    """A shallow steel wire arch 10 m wide rising 0.48 m, pinned at both ends, under its weight:
    at 0.657 of it the arch snaps through to hang below its supports."""
    arc = conic_arc_through([0.0, 0.0], [10.0, 0.0], [11.0, 11.0], [5.0, 0.4811])
    return Model(
        mesh_conic(arc, n),
        "rancf",
        Section(1e-4, 8e-10),
        Material(7850.0, 2e11),
        [Support(0), Support(-1)],
        gravity=[0.0, -9.81],
    )


def test_arc_length_passes_a_snap_through_that_load_control_cannot():
    """Load control stops at the arch's limit point (relaxation under the full load then lets
    it snap through); arc length traces the path past it (the load factor turns back) to the
    same hanging state, which the default solve finds from the sagged start."""
    relaxed = solve_equilibrium(
        SystemEquilibrium(as_system(shallow_arch())), 10, 1e-10, 30, None, "load", 0.0
    )
    assert relaxed.method == "relaxation+newton" and relaxed.relaxation_steps > 0
    assert relaxed.load_factors[-2] == pytest.approx(0.657, abs=2e-3)  # where load control stops
    assert relaxed.load_factors[-1] == 1.0
    path = []
    m = shallow_arch()
    res = solve_static(m, method="arc_length", on_step=lambda lam, y: path.append(lam))
    lam = np.array(path)
    assert lam[-1] == 1.0
    limit = int(np.argmax(np.diff(lam) < 0.0))  # the path turns back after its limit point
    assert limit > 0 and lam[limit] == pytest.approx(0.657, abs=2e-3)  # measured 0.6566
    mid = m.node_positions(res.q)[8]
    assert mid[1] < 0.0  # snapped through: the arch hangs
    r = SystemEquilibrium(as_system(m)).residual(res.y, 1.0)
    assert np.abs(r).max() <= 1e-6 * np.abs(m.external_force(0.0, res.y, True)).max()
    assert res.method == "arc_length"
    assert np.abs(relaxed.q - res.q).max() <= 1e-8 * 10.0  # the same hanging state (10 m span)
    sagged = solve_static(shallow_arch())
    assert sagged.method == SAG_START
    assert np.abs(sagged.q - res.q).max() <= 1e-8 * 10.0


def hose(n: int = 32, angle: float = 0.0) -> Model:
    """The installed hose, the whole problem turned by ``angle`` (radians)."""
    h = HOSE
    c, s = np.cos(angle), np.sin(angle)
    rot = np.array([[c, -s], [s, c]])
    end = rot @ [h["length"], 0.0]
    pos, d = rot @ [h["span"], 0.0], rot @ [1.0, 0.0]
    return Model(
        mesh_line([0.0, 0.0], end, n),
        "rancf",
        Section.circular(h["radius"]),
        Material(h["density"], h["youngs"]),
        [Support(0, "clamp"), Support(-1, "clamp", position=tuple(pos), direction=tuple(d))],
        gravity=rot @ [0.0, -h["g"]],
    )


def test_installed_hose_matches_the_elastica():
    """Sag and reactions of the hose installed 0.8 m apart against the shooting solution
    (measured at 32 elements: sag 3e-8, force 3e-5, moment 2e-5 relative)."""
    ref = installed_hose()
    m = hose(32)
    res = solve_static(m)
    assert res.load_factors[-1] == 2.0  # loads on (1), then the end moved in (2)
    assert -m.node_positions(res.q)[16, 1] == pytest.approx(ref.mid_sag, rel=1e-6)
    r = _reactions(m, res.y)
    assert np.allclose(r[0].force, ref.start_force, rtol=2e-4)
    assert r[0].moment[0] == pytest.approx(ref.start_moment, rel=2e-4)
    assert np.allclose(r[1].force, ref.end_force, rtol=2e-4)
    assert r[1].moment[0] == pytest.approx(ref.end_moment, rel=2e-4)


def test_reactions_are_objective():
    """The whole installation turned by 0.7 rad: the reactions turn with it."""
    base, turned = hose(8), hose(8, 0.7)
    r0 = _reactions(base, solve_static(base).y)
    r1 = _reactions(turned, solve_static(turned).y)
    c, s = np.cos(0.7), np.sin(0.7)
    rot = np.array([[c, -s], [s, c]])
    for a, b in zip(r0, r1, strict=True):
        assert np.allclose(rot @ a.force, b.force, rtol=0, atol=1e-9)
        assert b.moment == pytest.approx(a.moment, abs=1e-9)


def test_installation_load_vector_is_the_path_derivative():
    """``-∂r/∂p`` while the supports move (stage 2: central differences of the residual) against
    the exact tangent's ``-K[:, held] Δ``."""
    m = hose(8)
    prob = SystemEquilibrium(as_system(m))
    y = solve_static(m).y
    prob.stage = 1
    p = 1.6
    prob.place_supports(y, p)
    _, ok = prob.tangent(y, p)
    q = prob.load_vector(y, ok)
    _, ab = m.internal_force_and_tangent(y)
    d = np.zeros(m.n)
    d[m.fixed] = prob.delta
    exact = -(m.dense(ab) @ d)
    exact[m.fixed] = 0.0
    assert np.abs(q).max() > 0.0
    assert np.allclose(q, exact, rtol=0, atol=1e-6 * np.abs(exact).max())


def test_dynamics_from_the_equilibrium_stays_at_rest():
    m = hose(16)
    y = solve_static(m, at_time=0.0).y
    res = integrate(m, DynamicOptions(t_end=0.2, step=1e-3), initial=y)
    assert np.abs(res.q - m.q_from_y(y)).max() <= 1e-9


def test_hanging_chain_keeps_its_pendulum_mode():
    """A 1 m chain pinned at the top: Bernoulli's frequencies 0.5994, 1.3758, 2.1569 Hz.  The
    pendulum mode is a rigid rotation about the pin, but gravity's tension resists it: it is a
    real mode (the former modes removed it as rigid)."""
    area = np.pi * 1e-6
    m = Model(
        mesh_line([0.0, 0.0], [0.0, -1.0], 48),
        "rancf",
        Section(area, 1e-20),
        Material(7850.0, 2e11),
        [Support(0)],
        gravity=[0.0, -9.81],
    )
    res = natural_modes(m, solve_static(m).y, count=3)
    assert res.n_rigid == 0
    assert np.allclose(res.frequencies_hz, chain_frequencies(1.0), rtol=3e-3)
    assert np.allclose(res.frequencies_hz, [0.5994, 1.3758, 2.1569], rtol=3e-3)


def test_a_free_body_under_dead_tension_keeps_only_its_translations_rigid():
    """A free straight cable stretched by dead end forces ±N: translations are still free
    (2 rigid modes removed), but turning it is resisted like a compass needle — the rotation is
    a real mode with ω² = 12 N / (m L) (rigid-body estimate: the lowest flexural mode is ten
    times higher)."""
    from rancf.bodies.flexible import PointLoad

    length, stretch = 1.0, 1.0 + 1e-6
    sec, mat = Section.circular(0.01), Material(1000.0, 1e11)
    ea = mat.youngs_modulus * sec.area
    force = ea * 0.5 * (stretch**2 - 1.0) * stretch  # N = EA ε λ
    m = Model(
        mesh_line([0.0, 0.0], [length, 0.0], 8),
        "rancf",
        sec,
        mat,
        [],
        point_loads=[PointLoad(0, (-force, 0.0)), PointLoad(-1, (force, 0.0))],
    )
    q = m.q0.reshape(-1, 4).copy()
    q[:, 0] *= stretch  # uniformly stretched: an exact equilibrium
    q[:, 2] *= stretch
    y = m.y_from_q(q.ravel())
    assert np.abs(SystemEquilibrium(as_system(m)).residual(y, 1.0)).max() <= 1e-6 * force
    res = natural_modes(m, y, count=2)
    assert res.n_rigid == 2
    omega = np.sqrt(12.0 * force / (m.total_mass * length * stretch))
    assert 2 * np.pi * res.frequencies_hz[0] == pytest.approx(omega, rel=1e-2)


def test_an_installed_place_equal_to_the_reference_up_to_round_off_is_no_installation():
    """A support given its reference point through a computation (off by round-off) needs no
    installation stage; a real installation (1 µm) still has one."""
    mesh = mesh_line(np.zeros(2), np.array([0.1 + 0.2, 0.0]), 4)  # end x = 0.30000000000000004
    mat, sec = Material(7850.0, 2e11), Section.circular(0.01)
    for shift, stages in ((0.0, 1), (1e-16, 1), (1e-6, 2)):
        end = (0.3 + shift, 0.0)
        model = Model(
            mesh,
            "rancf",
            sec,
            mat,
            gravity=(0.0, -9.81),
            supports=[Support(0, "pin"), Support(-1, "pin", position=end)],
        )
        assert len(SystemEquilibrium(as_system(model)).stages) == stages, shift
        res = solve_static(model)
        assert np.abs(model.node_positions(res.q)[-1] - end).max() <= 1e-15 + 1e-12 * 0.3


def test_a_pinned_arc_under_gravity_comes_to_rest_hanging_and_without_its_pin_says_why():
    """The elliptic arc of paper example 6.1 pinned at its start is a pendulum: neither method
    can leave its reference (no stiffness against the swing there), relaxation takes it to the
    hanging state, where it balances its weight (the pin's reaction is the weight to 1e-9 and the
    centre of mass is straight below the pin).  Without the pin there is no equilibrium: one
    line that says so."""
    from rancf.errors import ConvergenceError

    arc = conic_arc_through([0.0, 0.0], [0.5, 0.0], [30.0, 40.0], [0.315, 0.077])

    def pendulum(supports):
        return Model(
            mesh_conic(arc, 4),
            "rancf",
            Section.circular(0.02),
            Material(6000.0, 2e6),
            supports,
            gravity=[0.0, -9.81],
        )

    weight = pendulum([]).total_mass * 9.81
    for method in ("load", "arc_length"):
        m = pendulum([Support(0, "pin")])
        res = solve_static(m, 4, method=method)
        assert res.method == "relaxation+newton" and res.load_factors[-1] == 1.0
        (pin,) = _reactions(m, res.y)
        assert np.abs(pin.force - [0.0, weight]).max() <= 1e-9 * weight
        # centre of mass: ∫ρA x ds = t_xᵀ M q with t_x the rigid translation along x
        t_x = np.zeros(m.n)
        t_x[0 :: m.dpn] = 1.0
        centre = t_x @ m.dense(m.mass_band) @ res.y / m.total_mass
        assert abs(centre) <= 1e-9 * 0.5
        with pytest.raises(ConvergenceError) as info:
            solve_static(pendulum([]), 4, method=method)
        text = str(info.value)
        assert "\n" not in text and "no equilibrium" in text and "add a support" in text
