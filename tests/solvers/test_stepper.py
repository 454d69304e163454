"""The stepper's contract: a step is accepted (the state moves to t + h) or rejected (the state
stays), with its error estimate and the step to try next; a block of fixed steps in the
compiled core moves the state as the same steps one by one."""

from __future__ import annotations

import numpy as np

import rancf
from rancf.solvers.generalized_alpha import GeneralizedAlpha
from rancf.solvers.stepper import Stepper
from rancf.system import as_system


def _stepper(adaptive: bool, rtol: float = 1e-5, max_newton: int = 12) -> Stepper:
    model = rancf.Model(
        rancf.mesh_line([0.0, 0.0], [1.0, 0.0], 4),
        "rancf",
        rancf.Section.circular(0.01),
        rancf.Material(density=7800.0, youngs_modulus=2.0e9),
        supports=[rancf.Support(0, "pin")],
        gravity=[0.0, -9.81],
    )
    system = as_system(model)
    o = rancf.DynamicOptions(t_end=1.0, step=1e-3, adaptive=adaptive, rtol=rtol)
    integ = GeneralizedAlpha(system, o.rho_inf, o.newton_tol, max_newton, o.newton, o.rtol)
    y, v, lam = system.y0.copy(), system.v0.copy(), np.zeros(system.m)
    a = integ.initial_acceleration(y, v, 0.0, lam)
    return Stepper(integ, o, (0.0, y, v, a, a.copy(), lam), o.step, 1e-6, 0.1, None)


def test_an_accepted_step_moves_the_state():
    st = _stepper(adaptive=False)
    y0 = st.y.copy()
    step = st.step(1e-3)
    assert step.accepted and not step.rejected and step.failure is None
    assert st.t == 1e-3 and not np.array_equal(st.y, y0)
    assert step.error > 0.0 and step.h_next == 1e-3  # fixed: the step again


def test_a_rejected_step_leaves_the_state_and_suggests_a_smaller_one():
    st = _stepper(adaptive=True, rtol=1e-12)
    y0 = st.y.copy()
    step = st.step(0.05)
    assert step.rejected and not step.accepted and step.error > 1.0
    assert st.t == 0.0 and np.array_equal(st.y, y0)
    assert 0.2 * 0.05 <= step.h_next < 0.05


def test_a_block_of_fixed_steps_is_the_steps_one_by_one():
    one, block = _stepper(adaptive=False), _stepper(adaptive=False)
    for _ in range(10):
        assert one.step(1e-3).accepted
    b = block.block(10, 10, 0, 0, lambda i: 0.01 * (i + 1), False, 10.0)
    assert b.converged and b.done == 10 and b.stored == 1 and not b.left
    np.testing.assert_allclose(block.y, one.y, rtol=0, atol=1e-12)
