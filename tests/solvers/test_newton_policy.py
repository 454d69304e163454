"""The Newton policy of a time step (docs/derivations/newton.md): gradient increments measured
as displacements, a step that fails or (chord) contracts slowly from the predictor taken again
from y0 — the same answers as a tightly converged full Newton, no step cut where the predictor
fails."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.geometry.conic import conic_arc
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.solvers.increment_scale import body_scale, increment_scale
from rancf.system import System
from rancf.system.system import as_system
from tests.system.test_winch import hoist, payout

SECTION, MATERIAL = Section.circular(0.02), Material(6000.0, 2.0e8)


def pendulum(n: int, element: str = "ancf", **kw) -> Model:
    """The straight pendulum of the benchmarks (L = 1.2 m, E = 2e8 Pa), released horizontal."""
    return Model(
        mesh_line([0, 0], [1.2, 0], n),
        element,
        SECTION,
        MATERIAL,
        [Support(0, "pin")],
        gravity=[0, -9.81],
        **kw,
    )


def test_gradients_are_scaled_by_their_elements_length():
    s = body_scale(pendulum(4)).reshape(5, 4)  # 0.3 m elements, unit tangents
    np.testing.assert_allclose(s[:, :2], 1.0, rtol=0, atol=0)
    np.testing.assert_allclose(s[:, 2:], 0.3, rtol=1e-14)
    beam = body_scale(pendulum(4, "beam")).reshape(5, 3)  # (x, y, angle)
    np.testing.assert_allclose(beam, np.c_[np.ones((5, 2)), np.full(5, 0.3)], rtol=1e-14)
    rod = Model(
        mesh_line([0, 0, 0], [1.2, 0, 0], 4),
        "rod",
        SECTION,
        Material(6000.0, 2.0e8, poisson_ratio=0.3),
    )
    np.testing.assert_allclose(
        body_scale(rod).reshape(5, 7), np.tile([1, 1, 1, 0.3, 0.3, 0.3, 1], (5, 1)), rtol=1e-14
    )  # the twist keeps 1
    # a conic arc: the shorter chord of each node's elements over its gradient's length
    arc = Model(
        mesh_conic(conic_arc(0.5, (30.0, 40.0), (0.315, 0.077)), 6),
        "rancf",
        SECTION,
        MATERIAL,
        [Support(0, "pin")],
    )
    q = arc.q0.reshape(7, 4)
    chords = np.linalg.norm(np.diff(q[:, :2], axis=0), axis=1)
    near = np.minimum(np.r_[chords[0], chords], np.r_[chords, chords[-1]])
    expect = near / np.linalg.norm(q[:, 2:], axis=1)
    np.testing.assert_allclose(
        body_scale(arc).reshape(7, 4)[:, 2:], np.c_[expect, expect], rtol=1e-14
    )
    # elements longer than 1 m keep the plain test (never stricter than before)
    assert np.all(
        body_scale(Model(mesh_line([0, 0], [30.0, 0], 3), "ancf", SECTION, MATERIAL)) == 1.0
    )


def test_where_the_scale_is_one():
    c2 = pendulum(6, "ancf", continuity="C2")  # control points, not nodal coordinates
    assert body_scale(c2) is None
    wound = hoist(payout, horizon=1.0, n_el=4)  # a winch changes the wire's element lengths
    assert np.all(increment_scale(wound) == 1.0)
    two = System({"a": pendulum(2), "b": pendulum(3)})
    s = increment_scale(two)
    assert s.shape == (two.n,) and sorted(set(np.round(s, 12))) == [0.4, 0.6, 1.0]


@pytest.mark.parametrize("newton", ["chord", "full"])
def test_a_fine_mesh_takes_its_first_step_whole(newton):
    """512 elements: Newton from the predictor y0 + h a0 h/2 diverges at t = 0 (the consistent
    acceleration is kinked at the pin); from y0 the step converges and is not cut to h/4."""
    r = integrate(pendulum(512), DynamicOptions(t_end=0.002, step=1e-3, newton=newton))
    assert r.status.name == "COMPLETED"
    assert r.n_rejected == 0 and len(r.t) == 3


def test_chord_is_tightly_converged_full_newton_within_the_tolerance():
    """128 elements over the first 0.05 s, where the chord iteration contracts slowly and the
    gradients at the pin decided the old test: every node within the tolerance (1.2e-10 m)
    of full Newton at 1.2e-13, and fewer iterations than the plain test's 4.2 a step."""
    m = pendulum(128)
    opts = {"t_end": 0.05, "step": 1e-3}
    ref = integrate(m, DynamicOptions(**opts, newton="full", newton_tol=1e-13, max_newton=30))
    res = integrate(m, DynamicOptions(**opts))
    assert ref.n_rejected == 0 and res.n_rejected == 0
    pos = [m.node_positions(x.q) for x in (ref, res)]
    err = np.abs(pos[1] - pos[0]).max()
    assert err < 1.2e-10, err
    assert res.n_newton / 50 < 3.8, res.n_newton  # measured 3.64 (the balance at t_{n+1})


def _stiff_steps(k: int) -> tuple[list[int], list[int]]:
    """The count of steps since one started again from y0 (the integrator's memory) after each
    of ``k`` steps of 192 stiff elements (E = 2e11), and the iterations of each step."""
    from rancf.solvers.generalized_alpha import GeneralizedAlpha

    model = Model(
        mesh_line([0, 0], [1.2, 0], 192),
        "ancf",
        SECTION,
        Material(6000.0, 2e11),
        [Support(0, "pin")],
        gravity=[0, -9.81],
    )
    s = as_system(model)
    integ = GeneralizedAlpha(s, 0.9, 1.2e-10, 25, "chord")
    y, v, lam = s.y0.copy(), s.v0.copy(), np.zeros(s.m)
    integ.prescribe(0.0, y, v)
    a = integ.initial_acceleration(y, v, 0.0, lam)
    w = a.copy()
    counts, iters = [], []
    for i in range(k):
        done, ok, it, *_ = integ.run_steps(y, v, a, w, i * 1e-3, 1e-3, 1, 1, 0)
        assert done == 1 and ok == 1
        counts.append(int(integ.memory()[0]))
        iters.append(it)
    return counts, iters


def test_steps_after_one_that_started_again_start_from_y0():
    """After a step that had to start again from y0, the next 7 start there at once (the count
    goes 1 .. 8); the 8th after it tries the predictor, and where that fails the count starts
    over at 1 (docs/derivations/newton.md)."""
    counts, iters = _stiff_steps(24)
    assert counts[:8] == list(range(1, 9))
    starts = [i for i, c in enumerate(counts) if c == 1]
    assert len(starts) >= 2
    for i in starts:  # 8 in a row from each start, unless the next start comes first
        run = counts[i : i + 8]
        assert run == list(range(1, len(run) + 1))
    for i, c in enumerate(counts[1:], 1):  # the count only grows by one, or ends, or restarts
        assert c in (counts[i - 1] + 1, 0, 1)
    assert max(iters) <= 8


def test_the_count_is_restored_and_checked():
    """The integrator's memory carries the count; a count out of range is refused, a memory
    without it (rancf 0.2) is taken as none."""
    from rancf.solvers.generalized_alpha import GeneralizedAlpha

    s = as_system(pendulum(8))
    integ = GeneralizedAlpha(s, 0.9, 1.2e-10, 25, "chord")
    np.testing.assert_array_equal(integ.memory(), [0.0])
    integ.restore(np.array([5.0]), 3)
    np.testing.assert_array_equal(integ.memory(), [5.0])
    integ.restore(np.empty(0), 3)
    np.testing.assert_array_equal(integ.memory(), [0.0])
    for bad in ([9.0], [-1.0], [2.5], [1.0, 2.0]):
        with pytest.raises(ValueError, match="does not fit"):
            integ.restore(np.array(bad), 3)


def test_a_rope_falling_on_rough_ground_needs_no_step_cuts():
    """A soft 40-element rope released upright on the ground (friction 0.3, eps = 1 mm/s)
    folds over: regularized friction saturates, and full Newton jumps back and forth about the
    root in some steps; damping an increment that turns back (from the fourth iteration)
    converges them. Over 0.4 s at h = 1 ms: at most 3 cut steps (24 without the damping) and at
    most 5.5 iterations a step (8.0 without)."""
    from rancf.system import Obstacle

    rope = Model(
        mesh_line([0.0, 0.005], [0.02, 2.0], 40),
        "rancf",
        Section.circular(0.005),
        Material(1100.0, 1.0e6),
        [],
        gravity=[0, -9.81],
    )
    ground = Obstacle(
        "plane", point=(0, 0), normal=(0, 1), friction=0.3, damping=1.0, name="ground"
    )
    s = System({"rope": rope}, obstacles=[ground], gravity=[0, -9.81])
    res = integrate(
        s, DynamicOptions(t_end=0.4, step=1e-3, rho_inf=0.5, max_newton=25, output_step=0.01)
    )
    assert res.status.value == "completed", res.message
    assert res.n_rejected <= 3
    assert res.n_newton <= 5.5 * res.n_steps
