"""Modes about a steady rotation: the frame terms against finite differences of the kinetic
energy seen from the turning frame, and a spinning cantilever against the exact rotating-beam
frequencies (a power series of the rotating Euler-Bernoulli equation, itself checked against
Wright et al. 1982)."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest
import scipy.optimize
from scipy.spatial.transform import Rotation

from rancf.bodies.flexible import Model
from rancf.bodies.properties import Material, Section, Support
from rancf.mesh.factories import mesh_line
from rancf.solvers.campbell import campbell, rotating_modes
from rancf.solvers.modal import natural_modes
from rancf.solvers.rotating import Spin, frame_terms
from rancf.system import as_system

L, R, E, RHO = 1.0, 0.01, 2.0e9, 7800.0
AXIS, CENTER = np.array([0.0, 0.0, 1.0]), np.zeros(3)


def blade(n: int = 12, clamp: bool = True) -> Model:
    """The uniform rod of the rotating-beam benchmark along x, clamped at the spin axis."""
    return Model(
        mesh_line([0, 0, 0], [L, 0, 0], n),
        "rod",
        Section.circular(R),
        Material(RHO, E, poisson_ratio=0.3),
        [Support(0, "clamp")] if clamp else [],
    )


def _end_values(tau2: float, mu2: float, terms: int = 100) -> np.ndarray:
    """``[[w''(1), w'''(1)]]`` of the two power-series solutions ``w = Σ a_k ξ^k`` of
    ``w'''' = (τ²/2) ((1 - ξ²) w')' + μ² w`` with ``w(0) = w'(0) = 0`` (``a2 = 1`` or ``a3 = 1``):
    ``(k+1)(k+2)(k+3)(k+4) a_{k+4} = (τ²/2) [(k+1)(k+2) a_{k+2} - k(k+1) a_k] + μ² a_k``."""
    out = np.empty((2, 2))
    k = np.arange(terms, dtype=float)
    for col, start in enumerate((2, 3)):
        a = np.zeros(terms + 4)
        a[start] = 1.0
        for j in range(terms):
            rhs = 0.5 * tau2 * ((j + 1) * (j + 2) * a[j + 2] - j * (j + 1) * a[j]) + mu2 * a[j]
            a[j + 4] = rhs / ((j + 1) * (j + 2) * (j + 3) * (j + 4))
        a = a[:terms]
        out[0, col] = np.sum(k * (k - 1) * a)  # w''(1)
        out[1, col] = np.sum(k * (k - 1) * (k - 2) * a)  # w'''(1)
    return out


def exact_flap(t: float) -> float:
    """The first nondimensional flap frequency ``μ = ω √(ρA L⁴ / EI)`` of a cantilever turning
    at ``T = Ω √(ρA L⁴ / EI)`` about its clamped end (no hub): the first root of the free end's
    determinant ``w''(1) = w'''(1) = 0``."""

    def det(mu: float) -> float:
        return float(np.linalg.det(_end_values(t * t, mu * mu)))

    grid = np.linspace(1.0, 4.0 + 1.2 * t, 60)
    vals = [det(m) for m in grid]
    i = next(i for i in range(len(grid) - 1) if np.sign(vals[i]) != np.sign(vals[i + 1]))
    return float(scipy.optimize.brentq(det, grid[i], grid[i + 1], xtol=1e-13))


def test_the_power_series_gives_wright_s_tabulated_frequencies():
    """Wright, Smith, Thresher & Wang (1982), J. Appl. Mech. 49, 197-202, table of the first
    flap mode of a uniform cantilever without hub: μ at T = 0, 1, 2, 4, 8, 12 is 3.5160,
    3.6817, 4.1373, 5.5850, 9.2568, 13.1702 (4 decimals); the series agrees to 1e-4."""
    table = {0: 3.5160, 1: 3.6817, 2: 4.1373, 4: 5.5850, 8: 9.2568, 12: 13.1702}
    for t, mu in table.items():
        assert exact_flap(float(t)) == pytest.approx(mu, abs=1.2e-4)


def _rotate(model: Model, y: np.ndarray, angle: float) -> np.ndarray:
    """``y`` turned rigidly by ``angle`` about the spin axis through the centre (positions about
    the centre, gradients as directions; a rod's twist angle kept)."""
    rot = Rotation.from_rotvec(angle * AXIS).as_matrix()
    q = model.q_from_y(y).reshape(model.n_nodes, model.dpn).copy()
    q[:, :3] = (q[:, :3] - CENTER) @ rot.T + CENTER
    q[:, 3:6] = q[:, 3:6] @ rot.T
    return model.y_from_q(q.ravel())


def test_frame_terms_are_the_derivatives_of_the_kinetic_energy_seen_from_the_turning_frame():
    """``T(y, ẏ) = ½ vᵀ M v`` with ``v`` the inertial velocity of ``y + ẏ t`` carried by the
    frame turning at ``Ω``, by central differences in time (h = 1e-5).  T is quadratic in
    ``(y, ẏ)``, so its derivatives are polarization differences (unit steps): the centrifugal
    force ``∂T/∂y`` at ``ẏ = 0``, the centrifugal stiffness ``∂²T/∂y²`` and the gyroscopic
    matrix ``∂²T/∂ẏ∂y - (∂²T/∂ẏ∂y)ᵀ`` agree with :class:`FrameTerms` to 1e-8 of their largest
    entry, about a deformed state of a clamped rod (clamp rotations in ``y``)."""
    model = blade(2)
    system = as_system(model)
    rate, h = 3.0, 1e-5
    frame = frame_terms(system, AXIS, CENTER)
    mass = frame.mass.toarray()
    rng = np.random.default_rng(4)
    y = model.y0 + 0.05 * rng.standard_normal(model.n) * ~model.fixed

    def energy(yy: np.ndarray, vv: np.ndarray) -> float:
        ahead = _rotate(model, yy + vv * h, rate * h)
        back = _rotate(model, yy - vv * h, -rate * h)
        v = (ahead - back) / (2 * h)
        return 0.5 * v @ mass @ v

    n, zero = model.n, np.zeros(model.n)
    eye = np.eye(n)
    base = energy(y, zero)
    grad = np.array([(energy(y + eye[i], zero) - energy(y - eye[i], zero)) / 2 for i in range(n)])
    fc = frame.centrifugal_force(y, rate)
    assert np.abs(grad - fc).max() <= 1e-8 * np.abs(fc).max()
    e_y = np.array([energy(y + eye[i], zero) for i in range(n)])
    hyy = np.array(
        [
            [energy(y + eye[i] + eye[j], zero) - e_y[i] - e_y[j] + base for j in range(n)]
            for i in range(n)
        ]
    )
    kc = frame.centrifugal_stiffness(rate).toarray()
    assert np.abs(-hyy - kc).max() <= 1e-8 * np.abs(kc).max()
    e_v = np.array([energy(y, eye[i]) for i in range(n)])
    hvy = np.array(
        [[energy(y + eye[j], eye[i]) - e_v[i] - e_y[j] + base for j in range(n)] for i in range(n)]
    )
    gyro = frame.gyroscopic(rate).toarray()
    assert np.abs(gyro).max() > 0
    assert np.abs((hvy - hvy.T) - gyro).max() <= 1e-8 * np.abs(gyro).max()


def test_without_spin_the_frequencies_are_the_natural_ones():
    """At Ω = 0 the companion eigenproblem gives ``natural_modes``'s frequencies (1e-9)."""
    system = as_system(blade(6))
    spun = rotating_modes(system, Spin.of(AXIS, CENTER, 0.0), 6)
    still = natural_modes(system, None, 6)
    assert spun.frequencies_hz == pytest.approx(still.frequencies_hz, rel=1e-9)


def _split(system, modes) -> tuple[list[int], list[int]]:
    """Indices of the flap (z) and lead-lag (y) bending modes among ``modes``, by the larger
    of the nodes' y and z displacement; axial and torsion modes are neither."""
    flap, lag = [], []
    for i, phi in enumerate(modes.modes):
        q = np.abs(system.q_from_y(phi.real) + 1j * system.q_from_y(phi.imag))
        nodes = q.reshape(-1, 7)
        size = np.linalg.norm(nodes[:, :3], axis=0)
        if size[2] > 10 * max(size[0], size[1]):
            flap.append(i)
        elif size[1] > 10 * max(size[0], size[2]):
            lag.append(i)
    return flap, lag


def test_a_spinning_cantilever_has_the_rotating_beam_frequencies():
    """The uniform rod (1 m, r = 0.01 m, E = 2e9 Pa, ρ = 7800 kg/m³, 8 rod elements) clamped
    at the spin axis: the first flap frequency within 0.5 % of the exact rotating
    Euler-Bernoulli value at 0, 10, 20 and 30 rad/s (measured: 2e-6, -1.3e-4, -1.9e-4,
    -2.2e-4), and the first lead-lag frequency with ``ω_lag² = ω_flap² - Ω²`` (exact flap)
    within 0.5 % (measured: 2e-6, -5.5e-4, -2.0e-3, -4.0e-3)."""
    system = as_system(blade(8))
    sqrt_ratio = np.sqrt(RHO * np.pi * R**2 * L**4 / (E * np.pi * R**4 / 4))
    for rate in (0.0, 10.0, 20.0, 30.0):
        out = rotating_modes(system, Spin.of(AXIS, CENTER, rate), 4)
        flap, lag = _split(system, out)
        w_flap = 2 * np.pi * out.frequencies_hz[flap[0]]
        w_lag = 2 * np.pi * out.frequencies_hz[lag[0]]
        exact = exact_flap(rate * sqrt_ratio) / sqrt_ratio
        assert w_flap == pytest.approx(exact, rel=5e-3), (rate, w_flap, exact)
        lag_exact = np.sqrt(exact**2 - rate**2)
        assert w_lag == pytest.approx(lag_exact, rel=5e-3), (rate, w_lag, lag_exact)
        assert np.all(out.growth_rates == 0)


def test_the_lead_lag_softening_is_exact_and_coriolis_lowers_it(monkeypatch):
    """Without the gyroscopic matrix the model's own ``ω_lag² = ω_flap² - Ω²`` holds to 1e-9
    at 30 rad/s (the spin softening acts across the axis only); with it the lead-lag
    frequency is lower (measured -0.43 %): the Coriolis coupling of lead-lag with the axial
    stretching of the extensible rod, which the inextensible reference leaves out."""
    import scipy.sparse as sp

    import rancf.solvers.rotating as rotating

    system, rate = as_system(blade(8)), 30.0
    full = rotating_modes(system, Spin.of(AXIS, CENTER, rate), 4)
    monkeypatch.setattr(
        rotating.FrameTerms, "gyroscopic", lambda self, r: sp.csr_matrix(self.mass.shape)
    )
    bare = rotating_modes(system, Spin.of(AXIS, CENTER, rate), 4)
    flap, lag = _split(system, bare)
    w_flap, w_lag = (2 * np.pi * bare.frequencies_hz[i[0]] for i in (flap, lag))
    assert w_lag == pytest.approx(np.sqrt(w_flap**2 - rate**2), rel=1e-9)
    lag_full = 2 * np.pi * full.frequencies_hz[_split(system, full)[1][0]]
    assert -6e-3 < lag_full / w_lag - 1 < -2e-3


def test_the_campbell_diagram_rises_with_the_spin():
    """Frequencies against the spin rate: the first flap frequency rises (centrifugal
    stiffening) and the table has one row per rate."""
    out = campbell(as_system(blade(6)), AXIS, CENTER, [0.0, 15.0], 3)
    assert out.frequencies_hz.shape == (2, 3)
    assert out.frequencies_hz[1, 1] > 1.5 * out.frequencies_hz[0, 1]


def test_modes_json_has_the_campbell_object(tmp_path, capsys):
    """``rancf modes --json`` of a file with ``[modes] spin_rates`` adds ``"campbell":
    {"spin_rates", "frequencies_hz"}``, the same numbers as :func:`campbell` (1e-12); a zero
    spin axis is refused naming the key (``--plot``: the docs' example, tests/test_readme_post)."""
    import json

    from rancf.cli import main
    from rancf.errors import ScenarioError
    from rancf.scenario import Scenario
    from tests.pages import DOCS, blocks, section

    text = blocks(section(DOCS / "guide" / "statics.md", "Modes about a steady rotation"), "toml")[
        0
    ].replace("elements = 8", "elements = 4")
    (tmp_path / "b.toml").write_text(text)
    assert main(["modes", str(tmp_path / "b.toml"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    cam = out["campbell"]
    assert cam["spin_rates"] == [0.0, 10.0, 20.0, 30.0]
    ref = campbell(as_system(blade(4)), AXIS, CENTER, cam["spin_rates"], 4)
    assert np.allclose(cam["frequencies_hz"], ref.frequencies_hz, rtol=1e-12, atol=0)
    with pytest.raises(ScenarioError, match="spin_axis"):
        Scenario.from_dict(tomllib.loads(text.replace("[0.0, 0.0, 1.0]", "[0.0, 0.0, 0.0]")))


def test_a_point_mass_on_an_isotropic_spring_whirls_at_omega0_plus_minus_the_spin():
    """A point mass (2 kg) on a zero-length spring (8 N/m, ω0 = 2 rad/s) to its reference on
    the spin axis: seen from the frame turning at Ω its frequencies are |ω0 - Ω|, ω0 (along
    the axis) and ω0 + Ω (1e-12), the point-mass path of the frame terms; held on a slider
    across the axis, ``√(ω0² - Ω²)`` through the constraints' null space, and past Ω = ω0 a
    divergence growing at ``√(Ω² - ω0²)`` with frequency 0."""
    from rancf.bodies.rigid import PointMass
    from rancf.system import Joint, Spring, System

    def system(joints=()):
        return System(
            {"m": PointMass(3, 2.0, (1.0, 0.0, 0.0))},
            joints=joints,
            springs=[Spring(("m", "ground"), 8.0, length=0.0)],
        )

    free = system()
    for rate in (0.5, 3.0):
        out = rotating_modes(free, Spin.of([0, 0, 2.0], [1.0, 0, 0], rate), 3)
        expected = np.sort([abs(2.0 - rate), 2.0, 2.0 + rate])
        assert np.allclose(2 * np.pi * out.frequencies_hz, expected, rtol=1e-12, atol=0)
    slider = system([Joint("slider", ("m", "ground"), axis=(1.0, 0.0, 0.0))])
    for rate in (1.5, 2.5):
        out = rotating_modes(slider, Spin.of([0, 0, 1.0], [1.0, 0, 0], rate), 1)
        if rate < 2.0:
            assert 2 * np.pi * out.frequencies_hz[0] == pytest.approx(
                np.sqrt(4 - rate**2), rel=1e-12
            )
            assert out.growth_rates[0] == 0
        else:
            assert out.frequencies_hz[0] == 0
            assert out.growth_rates[0] == pytest.approx(np.sqrt(rate**2 - 4), rel=1e-12)


def test_the_steady_state_tangent_is_the_derivative_of_its_residual():
    """The factored tangent of :class:`RotatingEquilibrium` (the core's tangent plus
    ``-p Ω² Wᵀ M W``) solves the central differences (h = 1e-6) of the residual along a random
    direction back to that direction (1e-6), about the spinning blade's steady state."""
    from rancf.solvers.rotating import RotatingEquilibrium
    from rancf.solvers.static import solve_equilibrium

    system = as_system(blade(4))
    system.reset_triads()
    problem = RotatingEquilibrium(system, Spin.of(AXIS, CENTER, 20.0))
    z = solve_equilibrium(problem, 4).y.copy()
    z = np.r_[z, np.zeros(system.m)]
    rng = np.random.default_rng(1)
    dz = rng.standard_normal(z.size) * problem.free * 1e-2
    h = 1e-6
    fd = (problem.residual(z + h * dz, 1.0) - problem.residual(z - h * dz, 1.0)) / (2 * h)
    _, ok = problem.tangent(z, 1.0)
    back = problem.solve(ok, fd)
    assert back is not None
    assert np.abs(back - dz).max() <= 1e-6 * np.abs(dz).max()


def test_a_spin_of_a_planar_system_is_refused_in_one_line():
    """A planar system has no spin axis to turn about: one line naming ``modes.spin_rates``."""
    from rancf.errors import RancfError

    planar = as_system(
        Model(
            mesh_line([0, 0], [1, 0], 2),
            "ancf",
            Section.circular(R),
            Material(RHO, E),
            [Support(0, "clamp")],
        )
    )
    with pytest.raises(RancfError, match=r"modes\.spin_rates: .* this one is planar"):
        frame_terms(planar, AXIS, CENTER)


def _flat_blade(n: int = 6) -> Model:
    """The benchmark rod with a flat section: stiff in the plane of rotation (lag) at four times
    the bending stiffness across it (flap), so that at rest lag 1 is twice flap 1's frequency."""
    from rancf.mesh.factories import mesh_line

    i_flap = np.pi * R**4 / 4
    sec = Section(
        area=np.pi * R**2, inertia=4 * i_flap, inertia_z=i_flap, orientation=(0.0, 0.0, 1.0)
    )
    return Model(
        mesh_line([0, 0, 0], [L, 0, 0], n),
        "rod",
        sec,
        Material(RHO, E, poisson_ratio=0.3),
        [Support(0, "clamp")],
    )


def test_campbell_lines_follow_their_mode_shapes_through_a_crossing():
    """Spinning stiffens flap 1 past lag 1 (between 15 and 20 rad/s): the line labelled
    ``flap 1`` starts below ``lag 1`` and ends above it, rising all the way, where rows sorted on
    their own would swap the two; neighbouring shapes on a line agree (MAC > 0.9)."""
    from rancf.solvers.campbell import mac

    rates = [0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0]
    system = as_system(_flat_blade())
    out = campbell(system, AXIS, CENTER, rates, 2)
    assert out.labels == ("flap 1", "lag 1")
    flap, lag = out.frequencies_hz[:, 0], out.frequencies_hz[:, 1]
    assert np.all(np.diff(flap) > 0) and flap[0] < lag[0] and flap[-1] > 1.4 * lag[-1]
    assert not np.array_equal(out.frequencies_hz, np.sort(out.frequencies_hz, axis=1))
    shapes = [rotating_modes(system, Spin.of(AXIS, CENTER, r), 2).modes for r in (15.0, 20.0)]
    m = mac(shapes[0], shapes[1])
    assert m[0, 1] > 0.9 and m[1, 0] > 0.9  # the two swapped places in frequency order


def test_mac_is_one_for_the_same_shape_and_zero_for_orthogonal_ones():
    from rancf.solvers.campbell import mac

    a = np.array([[1.0, 2.0, 0.0], [0.0, 0.0, 1.0]])
    got = mac(a, (2.0 - 3.0j) * a)
    assert np.allclose(got, np.eye(2), rtol=0, atol=1e-15)
