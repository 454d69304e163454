import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, PointLoad, Section, Support
from rancf.mesh.factories import mesh_line
from rancf.solvers.dynamic import DynamicOptions, DynamicStatus, integrate


def pendulum(element="rancf", n=4, e_mod=0.7e6):
    """The flexible pendulum of the ANCF literature (L = 1.2 m), released horizontal."""
    return Model(
        mesh_line([0, 0], [1.2, 0], n),
        element,
        Section(0.0018, 1.215e-8),
        Material(5540.0, e_mod),
        [Support(0, "pin")],
        gravity=[0, -9.81],
    )


def test_energy_is_conserved_without_dissipation():
    r = integrate(pendulum(), DynamicOptions(t_end=1.0, step=1e-3, rho_inf=1.0))
    assert r.status is DynamicStatus.COMPLETED
    e = r.total_energy
    assert np.abs(e - e[0]).max() < 1e-3 * r.kinetic.max()


def test_numerical_dissipation_decreases_energy():
    m = Model(
        mesh_line([0, 0], [0.5, 0], 6),
        "rancf",
        Section.circular(0.03),
        Material(6000, 2e7),
        [Support(0, "clamp")],
        initial_velocities={-1: [0.0, 0.01]},
    )
    opts = dict(t_end=2.0, step=5e-3)
    e1 = integrate(m, DynamicOptions(rho_inf=1.0, **opts)).total_energy
    e5 = integrate(m, DynamicOptions(rho_inf=0.5, **opts)).total_energy
    assert np.abs(e1 / e1[0] - 1).max() < 1e-3
    # the physical energy at the step points is not the algorithm's Lyapunov function, so it
    # may rise by O((ωh)²) within a step; window by window it decreases strictly
    windows = e5[::40]
    assert np.all(np.diff(windows) < 0)
    assert e5[-1] < 0.6 * e5[0]
    assert np.diff(e5).max() < 5e-4 * e5[0]


def test_second_order_convergence():
    m = pendulum(n=3)
    ref = integrate(m, DynamicOptions(t_end=0.2, step=1e-3 / 32, rho_inf=0.8)).q[-1]
    errs = []
    for h in (4e-3, 2e-3, 1e-3):
        q = integrate(m, DynamicOptions(t_end=0.2, step=h, rho_inf=0.8)).q[-1]
        errs.append(np.abs(q - ref).max())
    rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all((rates > 1.8) & (rates < 2.3))


def test_element_types_agree_as_the_mesh_is_refined():
    diffs = []
    for n in (4, 16):
        tips = []
        for el in ("rancf", "ancf", "beam"):
            r = integrate(pendulum(el, n, 1e8), DynamicOptions(t_end=0.3, step=2e-3))
            tips.append(r.q[-1].reshape(n + 1, -1)[-1, :2])
        tips = np.array(tips)
        diffs.append(np.abs(tips - tips[0]).max())
    assert diffs[1] < 0.5 * diffs[0]
    assert diffs[1] < 1e-3


def test_adaptive_steps_track_fixed_steps():
    m = pendulum(n=3)
    fixed = integrate(m, DynamicOptions(t_end=0.3, step=2.5e-4, output_step=0.05))
    adapt = integrate(
        m, DynamicOptions(t_end=0.3, step=1e-3, adaptive=True, rtol=1e-6, output_step=0.05)
    )
    assert adapt.status is DynamicStatus.COMPLETED
    assert np.allclose(adapt.t, fixed.t)
    assert np.abs(adapt.q - fixed.q).max() < 5e-4
    assert adapt.min_step_taken < adapt.max_step_taken


def test_failed_newton_keeps_what_was_computed():
    r = integrate(pendulum(), DynamicOptions(t_end=1.0, step=1e-2, max_newton=2, min_step=2e-3))
    assert r.status is DynamicStatus.FAILED
    assert "did not converge at t =" in r.message
    assert 0.0 < r.t_reached < 1.0
    assert r.q.shape[0] == r.t.size == r.kinetic.size
    assert f"{r.t_reached:.6g}" in r.message


def test_harmonic_load_and_mass_proportional_damping():
    sec, mat = Section.circular(0.03), Material(6000, 2e7)
    base = dict(supports=[Support(0, "clamp")])
    mesh = mesh_line([0, 0], [0.5, 0], 6)
    # damping: free decay of the first mode at rate c / 2
    c = 0.5
    m = Model(mesh, "rancf", sec, mat, damping=c, initial_velocities={-1: [0, 0.01]}, **base)
    r = integrate(m, DynamicOptions(t_end=4.0, step=2e-3, rho_inf=1.0))
    tip = m.node_positions(r.q)[:, -1, 1]
    peaks = [np.abs(tip[(r.t >= a) & (r.t < a + 1.0)]).max() for a in (0.0, 3.0)]
    assert peaks[1] / peaks[0] == pytest.approx(np.exp(-c / 2 * 3.0), rel=0.05)
    # a harmonic load at low frequency follows the static response F/k
    f0, freq = 1e-3, 0.05
    m = Model(
        mesh, "rancf", sec, mat, point_loads=[PointLoad(-1, (0, f0), freq)], damping=2.0, **base
    )
    r = integrate(m, DynamicOptions(t_end=5.0, step=1e-2, rho_inf=0.8))
    tip = m.node_positions(r.q)[:, -1, 1]
    k = 3 * mat.youngs_modulus * sec.inertia / 0.5**3
    expected = f0 / k * np.sin(2 * np.pi * freq * r.t)
    assert np.abs(tip - expected)[r.t > 2].max() < 0.05 * f0 / k


def test_a_run_does_not_depend_on_the_load(monkeypatch):
    """The compiled loop's step times are the last output's time plus the steps since it, so
    where a call ends (on the wall clock: after 0.1 s, or after every step) does not move the
    answer: the spin-up beam (a time-dependent drive) gives the same numbers bit for bit, with
    and without a stop flag polled between calls."""
    import dataclasses
    from importlib import resources

    import rancf.solvers.dynamic as dyn
    from rancf.scenario import load_scenario

    sc = load_scenario(str(resources.files("rancf.examples") / "spin-up-beam.toml"))
    opts = dataclasses.replace(sc.dynamic_options(), t_end=2.0)
    ref = dyn.integrate(sc.build_system(), opts)
    monkeypatch.setattr(dyn, "CALL_SECONDS", 0.0)
    assert np.array_equal(dyn.integrate(sc.build_system(), opts).q, ref.q)
    polled = dyn.integrate(sc.build_system(), opts, should_stop=lambda: False)
    assert np.array_equal(polled.q, ref.q)
    # calls sized to the wall clock (CALL_TARGET_SECONDS): the least of 1 % of the outputs, or
    # grown to the memory bound, give the same numbers
    sizes = []
    run_steps = dyn.GeneralizedAlpha.run_steps

    def counted(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN202
        sizes.append(args[6] // args[7])  # n_steps // per_out: the outputs asked of the call
        return run_steps(self, *args, **kwargs)

    monkeypatch.setattr(dyn.GeneralizedAlpha, "run_steps", counted)
    for target in (1e-12, 10.0):
        monkeypatch.setattr(dyn, "CALL_SECONDS", 10.0)
        monkeypatch.setattr(dyn, "CALL_TARGET_SECONDS", target)
        sizes.clear()
        assert np.array_equal(dyn.integrate(sc.build_system(), opts).q, ref.q), target
        assert (max(sizes) <= 2) if target < 1 else (max(sizes) >= 16), sizes
